"""Eq. (3) in Cartesian coordinates with Lagrange multipliers, for the ideal mechanism.

An independent check of the minimal-coordinate equations (loads.py, quasistatic.py):
bodies 1 crank, 2 coupler, 3 follower, q_i = (x_i, y_i, phi_i) of the centre of mass
(link mid-points); revolute joints A, B, C, D and the driver phi1 = omega t give nine
constraints for nine coordinates.  Solving

    [ M    Phi_q^T ] [ q'' ]   [ g     ]
    [ Phi_q   0    ] [ lam ] = [ gamma ]          (Eqs. 3-4)

per instant returns the joint reactions; lam_B is the force the pin exerts on the bushing
when joint B is ideal.  Vectorised over time (stacked 18x18 solves).  Used by the tests.
"""
from __future__ import annotations

import numpy as np

from . import kinematics
from .geometry import FourBar


def _rot(phi):
    c, s = np.cos(phi), np.sin(phi)
    return c, s


def joint_B_reaction(fb: FourBar, t, crank_mass: float, crank_inertia: float):
    """Force on the bushing at an ideal joint B (N x 2) and q'' (N x 9) from Eq. (3)."""
    t = np.asarray(t, float)
    n = t.size
    th1 = fb.omega * t
    th3, ph2 = kinematics.positions(fb, th1)
    w3, w2 = kinematics.velocities(fb, th1, th3, ph2)
    w1 = np.full(n, fb.omega)
    phi = [th1, ph2, th3]
    om = [w1, w2, w3]
    L = [fb.l1, fb.l2, fb.l3]
    m = [crank_mass, fb.m2, fb.m3]
    inertia = [crank_inertia, fb.I2, fb.I3]
    # local points: crank A (-l1/2), B (+l1/2); coupler C (-l2/2), B (+l2/2);
    # follower D (-l3/2), C (+l3/2)
    # joints as (body_i, s_i, body_j, s_j); body -1 = ground
    joints = [(0, -L[0] / 2, -1, None),          # A at the origin
              (0, +L[0] / 2, 1, +L[1] / 2),      # B: crank end = coupler end
              (1, -L[1] / 2, 2, +L[2] / 2),      # C
              (2, -L[2] / 2, -1, None)]          # D at (l0, 0)
    A = np.zeros((n, 18, 18))
    b = np.zeros((n, 18))
    for i in range(3):
        A[:, 3 * i, 3 * i] = A[:, 3 * i + 1, 3 * i + 1] = m[i]
        A[:, 3 * i + 2, 3 * i + 2] = inertia[i]
        b[:, 3 * i + 1] = -m[i] * fb.g
    # load P at E (the follower's centre of mass) towards F
    ex, ey = fb.l0 + fb.l3 / 2 * np.cos(th3), fb.l3 / 2 * np.sin(th3)
    dx, dy = fb.F[0] - ex, fb.F[1] - ey
    dn = np.hypot(dx, dy)
    b[:, 6] += fb.P * dx / dn
    b[:, 7] += fb.P * dy / dn
    row = 9
    for (bi, si, bj, sj) in joints:
        for body, s, sign in ((bi, si, 1.0), (bj, sj, -1.0)):
            if body < 0:
                continue
            c, sn = _rot(phi[body])
            # Phi = sum sign * (r + A s); d/dphi (A s) = (-s sin, s cos)
            A[:, row, 3 * body] = sign
            A[:, row + 1, 3 * body + 1] = sign
            A[:, row, 3 * body + 2] = sign * (-s * sn)
            A[:, row + 1, 3 * body + 2] = sign * (s * c)
            # gamma = -(Phi_q q')_q q' = sign * A s phi'^2
            b[:, row] += sign * s * c * om[body] ** 2
            b[:, row + 1] += sign * s * sn * om[body] ** 2
        row += 2
    A[:, row, 2] = 1.0                      # driver phi1 - omega t = 0, gamma = 0
    # symmetric: Phi_q^T in the upper right block
    A[:, :9, 9:] = np.transpose(A[:, 9:, :9], (0, 2, 1))
    x = np.linalg.solve(A, b[..., None])[..., 0]
    lam = x[:, 9:]
    # M q'' + Phi_q^T lam = g: the constraint force on body j is -Phi_qj^T lam;
    # joint B's Phi has -I for the coupler's r, so the force on the bushing is +lam_B
    return lam[:, 2:4], x[:, :9]
