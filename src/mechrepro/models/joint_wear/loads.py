"""Mass matrix of the coupler-follower chain (its velocity terms and applied forces are
written in clearance.rhs_into and qs_numba.setup).

Minimal coordinates q = (theta3, phi2): the follower hangs from the ideal joint D, the
coupler from the ideal joint C; the driven crank carries the pin.  With joint B ideal the
mechanism has no degree of freedom; the clearance of B frees exactly these two -- the
"two extra DOF" of the clearance joint.  This is Eq. (3) projected on the null space of the
ideal constraints A, C, D and the driver (a minimal-coordinate formulation): no constraint
drift, hence no Baumgarte stabilisation needed.  Centres of mass at the link mid-points
(E is the follower's centre, Sec. 4.1).
"""
from __future__ import annotations

from .geometry import FourBar


def mass_terms(fb: FourBar):
    """Constant parts (M11, M22, a) with M12 = a cos(theta3 - phi2)."""
    M11 = fb.I3 + fb.m3 * (fb.l3 / 2) ** 2 + fb.m2 * fb.l3 ** 2
    M22 = fb.I2 + fb.m2 * (fb.l2 / 2) ** 2
    a = fb.m2 * fb.l3 * fb.l2 / 2
    return M11, M22, a

