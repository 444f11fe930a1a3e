"""Mass matrix, velocity terms and applied generalised forces of the coupler-follower chain.

Minimal coordinates q = (theta3, phi2): the follower hangs from the ideal joint D, the
coupler from the ideal joint C; the driven crank carries the pin.  With joint B ideal the
mechanism has no degree of freedom; the clearance of B frees exactly these two -- the
"two extra DOF" of the clearance joint.  This is Eq. (3) projected on the null space of the
ideal constraints A, C, D and the driver (a minimal-coordinate formulation): no constraint
drift, hence no Baumgarte stabilisation needed.  Centres of mass at the link mid-points
(E is the follower's centre, Sec. 4.1).
"""
from __future__ import annotations


import numpy as np

from .geometry import FourBar


def mass_terms(fb: FourBar):
    """Constant parts (M11, M22, a) with M12 = a cos(theta3 - phi2)."""
    M11 = fb.I3 + fb.m3 * (fb.l3 / 2) ** 2 + fb.m2 * fb.l3 ** 2
    M22 = fb.I2 + fb.m2 * (fb.l2 / 2) ** 2
    a = fb.m2 * fb.l3 * fb.l2 / 2
    return M11, M22, a


def applied_forces(fb: FourBar, theta3, phi2):
    """Generalised forces of the load P at E (towards F) and of gravity (-y).  Vectorised."""
    c3, s3 = np.cos(theta3), np.sin(theta3)
    ex, ey = fb.l0 + fb.l3 / 2 * c3, fb.l3 / 2 * s3
    dx, dy = fb.F[0] - ex, fb.F[1] - ey
    dn = np.hypot(dx, dy)
    Px, Py = fb.P * dx / dn, fb.P * dy / dn
    Q3 = fb.l3 / 2 * (-s3 * Px + c3 * Py) - fb.g * (fb.m3 * fb.l3 / 2 + fb.m2 * fb.l3) * c3
    Q2 = -fb.g * fb.m2 * fb.l2 / 2 * np.cos(phi2)
    return Q3, Q2
