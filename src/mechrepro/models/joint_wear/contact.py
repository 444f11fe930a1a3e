"""Contact kinematics and clearance forces of joint B (Eqs. 5-15, 18-20).

Conventions: i = pin (on the crank), j = bushing (on the coupler).  e = r_i - r_j
(Eq. 5), n = e/|e| points from the bushing centre to the pin centre, t = n turned by
+90 deg (Eq. 10).  The force the pin exerts on the bushing is f = F_N n + F_T t; the
bushing's moment about its centre is R_j F_T.
"""
from __future__ import annotations

import numpy as np


def damping_K2(delta, d_max, C_max):
    """Eq. (14): step damping K''(delta) rising smoothly from 0 to C_max at d_max."""
    x = np.clip(np.asarray(delta, float) / d_max, 0.0, 1.0)
    return C_max * x * x * (3.0 - 2.0 * x)


def normal_force(delta, delta_dot, K, n_exp, d_max, C_max, damping=True):
    """Eq. (11): F_N = K' delta^n + K'' delta_dot, zero out of contact, never adhesive.

    A damping term that would pull the bodies together on separation is clipped at zero:
    the contact cannot transmit tension.
    """
    delta = np.asarray(delta, float)
    dp = np.maximum(delta, 0.0)
    F = K * dp ** n_exp
    if damping:
        F = F + damping_K2(dp, d_max, C_max) * delta_dot
    return np.where(delta > 0.0, np.maximum(F, 0.0), 0.0)


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


def contact_area(delta, R_pin, R_bush, width):
    """Eq. (20): A_a = |AB| w [m2]."""
    return contact_chord(delta, R_pin, R_bush) * width
