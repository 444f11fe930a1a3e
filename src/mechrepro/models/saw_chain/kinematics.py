"""Closed-form positions of the key points and their exact time derivatives (the reference).
In each stage the leading hinge runs on the pitch circle, the trailing one on y = 0
(Eqs. 7, 9); with phi = omega tau, Tx = p1 + 2 p2 and link length L:

    lead  = (Tx + R sin phi, R (1 - cos phi))
    trail = (lead_x - sqrt(L^2 - lead_y^2), 0)
    mid   = (lead + trail) / 2                                  (Eqs. 8, 10)

Stage 1: lead O1, trail O2, L = p2 (drive link); stage 2: lead O2, trail O3, L = p1."""
from __future__ import annotations

import numpy as np


def _sin_versine(phi):
    """sin(phi) and 1 - cos(phi) = 2 h^2 (h = sin(phi/2)) for 0 <= phi < pi: no cancellation at
    small phi, and valid for stages beyond pi/2 (few teeth, unequal pitches)."""
    h = np.sin(0.5 * phi)
    h2 = h * h
    return 2.0 * h * np.sqrt(1.0 - h2), 2.0 * h2


def stage_positions(phi, R, L, Tx):
    """x, y of lead, trail and midpoint for rotation angles ``phi`` (array) [m]."""
    s, vers = _sin_versine(phi)
    xl = Tx + R * s
    yl = R * vers
    xt = xl - np.sqrt(L**2 - yl**2)
    return {"lead_x": xl, "lead_y": yl, "trail_x": xt,
            "mid_x": 0.5 * (xl + xt), "mid_y": 0.5 * yl}


def stage_derivatives(phi, R, L, omega):
    """Exact velocities and accelerations of trail and midpoint: with s = sqrt(L^2 - y^2),
    s' = -y y'/s, s'' = -(y'^2 + y y'' + s'^2)/s."""
    yl = R * (1.0 - np.cos(phi))
    xl_d, yl_d = R * omega * np.cos(phi), R * omega * np.sin(phi)
    xl_dd, yl_dd = -R * omega**2 * np.sin(phi), R * omega**2 * np.cos(phi)
    s = np.sqrt(L**2 - yl**2)
    s_d = -yl * yl_d / s
    s_dd = -(yl_d**2 + yl * yl_dd + s_d**2) / s
    xt_d, xt_dd = xl_d - s_d, xl_dd - s_dd
    return {"trail_vx": xt_d, "trail_ax": xt_dd,
            "mid_vx": 0.5 * (xl_d + xt_d), "mid_vy": 0.5 * yl_d,
            "mid_ax": 0.5 * (xl_dd + xt_dd), "mid_ay": 0.5 * yl_dd}


def stage_jerks(phi, R, L, omega):
    """Exact jerks of trail x and midpoint x, y: s''' = -(3 y' y'' + y y''' + 3 s' s'') / s; the
    leading truncation term of Eqs. (13), (19)."""
    c, sn = np.cos(phi), np.sin(phi)
    y = R * (1.0 - c)
    y1, y2, y3 = R * omega * sn, R * omega**2 * c, -R * omega**3 * sn
    s = np.sqrt(L**2 - y**2)
    s1 = -y * y1 / s
    s2 = -(y1**2 + y * y2 + s1**2) / s
    s3 = -(3 * y1 * y2 + y * y3 + 3 * s1 * s2) / s
    xl3 = -R * omega**3 * c
    xt3 = xl3 - s3
    return {"trail_jx": xt3, "mid_jx": 0.5 * (xl3 + xt3), "mid_jy": 0.5 * y3}
