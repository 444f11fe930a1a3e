"""Contact kinematics of joint B (Eqs. 5, 10, 15, 18-19).

Conventions: i = pin (on the crank), j = bushing (on the coupler).  e = r_i - r_j
(Eq. 5), n = e/|e| points from the bushing centre to the pin centre, t = n turned by
+90 deg (Eq. 10).  The force the pin exerts on the bushing is f = F_N n + F_T t; the
bushing's moment about its centre is R_j F_T.
"""
from __future__ import annotations

import numpy as np


def friction_sign(v_T, v_eps):
    """Regularised sign of Eq. (15): v/|v| -> v / sqrt(v^2 + v_eps^2) (smooth at v = 0)."""
    return v_T / np.sqrt(v_T * v_T + v_eps * v_eps)


def half_contact_angle(delta, R_pin, R_bush):
    """Eq. (18): theta = angle O_i O_j B, half the angle the contact arc AB subtends at O_j."""
    ecc = (R_bush - R_pin) + np.asarray(delta, float)       # |O_j O_i| = R_j + delta - R_i
    cos_t = (ecc ** 2 + R_bush ** 2 - R_pin ** 2) / (2.0 * ecc * R_bush)
    return np.arccos(np.clip(cos_t, -1.0, 1.0))


def contact_chord(delta, R_pin, R_bush):
    """Eq. (19): |AB| = sqrt(2 R_j^2 (1 - cos 2 theta)) = 2 R_j sin(theta) [m]."""
    th = half_contact_angle(delta, R_pin, R_bush)
    return np.sqrt(2.0 * R_bush ** 2 * (1.0 - np.cos(2.0 * th)))

