"""The kinematic difference method, Eqs. (11)-(13) and (17)-(19).

Each stage is divided into K steps; velocities are backward differences of the
displacements and accelerations backward differences of those velocities:

    V^i = (U^i - U^(i-1)) / dt,   a^i = (V^i - V^(i-1)) / dt,   i = 1..K

with V^0, a^0 given (stage 1: V^0 = (R omega, 0), a^0 = 0; stage 2: the values of O2 at
t1).  The second difference divides round-off in the positions (~eps*|x|) by dt^2, so
for large K the accelerations become noise; :func:`roundoff_acceleration` bounds that
noise and :func:`check_roundoff` refuses such a K instead of reporting noise as a load.
"""
from __future__ import annotations

import math

import numpy as np

EPS = np.finfo(float).eps


class RoundoffError(ValueError):
    """K so large that the second backward difference is dominated by round-off."""


def backward_differences(x, dt, v0, a0):
    """Velocity and acceleration of positions ``x`` (1-D, K+1 steps) by Eqs. (12)-(13).

    Vectorised over the steps; ``v0``, ``a0`` are the values at index 0.  Written into
    preallocated arrays because this is the solver's hot path.
    """
    v = np.empty_like(x)
    a = np.empty_like(x)
    v[0], a[0] = v0, a0
    np.subtract(x[1:], x[:-1], out=v[1:])
    v[1:] *= 1.0 / dt
    np.subtract(v[1:], v[:-1], out=a[1:])
    a[1:] *= 1.0 / dt
    return v, a


def roundoff_acceleration(x_max, dt):
    """Bound of the round-off in a second backward difference [m/s^2].

    Each position carries a relative error of a few eps (sin, sqrt); the second
    difference combines four such errors and divides by dt^2.
    """
    return 4.0 * EPS * x_max / dt**2


def max_steps(x_max, stage_time, accel_scale, tolerance):
    """Largest K whose round-off bound stays below ``tolerance * accel_scale``."""
    return int(math.floor(stage_time * math.sqrt(tolerance * accel_scale / (4.0 * EPS * x_max))))


def check_roundoff(K, x_max, stage_time, accel_scale, tolerance):
    """Raise :class:`RoundoffError` when K steps make the loads round-off noise."""
    dt = stage_time / K
    bound = roundoff_acceleration(x_max, dt)
    if bound > tolerance * accel_scale:
        raise RoundoffError(
            f"K={K}: round-off in the second backward difference reaches {bound:.3g} m/s^2, "
            f"more than {tolerance:g} of the acceleration scale {accel_scale:.3g} m/s^2; "
            f"the loads would be noise. Use K <= "
            f"{max_steps(x_max, stage_time, accel_scale, tolerance)} (or the exact_reference effect).")
    return bound
