"""The kinematic difference method, Eqs. (11)-(13) and (17)-(19), and its error budget:

    V^i = (U^i - U^(i-1)) / dt,   a^i = (V^i - V^(i-1)) / dt,   i = 1..K

Truncation a^i = a(t_i) - dt a'(t_i) + O(dt^2) falls like 1/K; round-off of the second
difference grows like K^2.  Beyond :func:`roundoff_limit`, where they meet, the error grows
again, so :func:`check_roundoff` refuses such K."""
from __future__ import annotations

import math

import numpy as np

from mechrepro.errors import Refusal

from .kinematics import stage_positions
from .loads import dynamic_load

EPS = np.finfo(float).eps


class RoundoffError(Refusal):
    """K beyond the round-off limit: the second backward difference is dominated by round-off."""


def backward_differences(x, dt, v0, a0):
    """Velocity and acceleration of positions ``x`` (K+1 steps) by Eqs. (12)-(13), from ``v0``,
    ``a0`` at index 0 (into preallocated arrays: the hot path)."""
    v = np.empty_like(x)
    a = np.empty_like(x)
    v[0], a[0] = v0, a0
    np.subtract(x[1:], x[:-1], out=v[1:])
    v[1:] *= 1.0 / dt
    np.subtract(v[1:], v[:-1], out=a[1:])
    a[1:] *= 1.0 / dt
    return v, a


def truncation_load(dt, load_jerk_max):
    """Leading truncation error of a load sample, dt max|dF/dt| [N]."""
    return dt * load_jerk_max


def roundoff_load(dt, x_max, mass):
    """Round-off bound of a load sample [N]: errors ~eps x_max with weights summing to 4, divided
    by dt^2, times the mass they multiply."""
    return 4.0 * EPS * x_max * mass / dt**2


def roundoff_limit(stage_times, load_jerk_max, x_max, mass):
    """Largest K with round-off bound below truncation:
    K^3 = max_s(T_s J_s) min_s(T_s)^2 / (4 eps x m)."""
    trunc = max(T * J for T, J in zip(stage_times, load_jerk_max))
    return int(math.floor((trunc * min(stage_times) ** 2 / (4.0 * EPS * x_max * mass)) ** (1.0 / 3.0)))


def velocity_roundoff_limit(stage_times, accel_max, x_max):
    """The same for the velocity (first difference, round-off ~K):
    K^2 = max_s(T_s A_s) min_s(T_s) / (4 eps x)."""
    trunc = max(T * A for T, A in zip(stage_times, accel_max))
    return int(math.floor(math.sqrt(trunc * min(stage_times) / (4.0 * EPS * x_max))))


def check_roundoff(K, limit, allow=False, what="loads"):
    """Raise :class:`RoundoffError` for K beyond the limit unless ``allow`` (the cost-of-accuracy
    study crosses it on purpose)."""
    if K > limit and not allow:
        raise RoundoffError(
            f"K = {K}: beyond K = {limit} the round-off of the "
            f"{'second' if what == 'loads' else 'first'} backward difference "
            f"exceeds its truncation error, so the {what} get less accurate, not more; "
            f"allowed: K <= {limit}")
    return K > limit


def difference_arrays(chain):
    """Velocity, acceleration and loads x, y of :func:`difference_method` as plain arrays (no
    round-off check: the hot path of K sequences)."""
    R, w, K = chain.R, chain.omega, chain.K
    n = 2 * K + 1
    vx, ax, Fx, Fy = np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    v_trail, a_trail, v_mid, a_mid = R * w, 0.0, R * w, 0.0
    for stage, (L, m_link, phi) in enumerate(chain.stages()):
        pos = stage_positions(phi, R, L, chain.Tx)
        dt = (phi[1] - phi[0]) / w
        vt, at = backward_differences(pos["trail_x"], dt, v_trail, a_trail)
        _, amx = backward_differences(pos["mid_x"], dt, v_mid, a_mid)
        _, amy = backward_differences(pos["mid_y"], dt, 0.0, 0.0)
        Fsx, Fsy = dynamic_load(m_link, amx, amy, chain.m_tight, at)
        # stage 2's index 0 repeats t1 (already stored by stage 1)
        dst = slice(0, K + 1) if stage == 0 else slice(K + 1, n)
        src = slice(0, K + 1) if stage == 0 else slice(1, K + 1)
        vx[dst], ax[dst], Fx[dst], Fy[dst] = vt[src], at[src], Fsx[src], Fsy[src]
        v_trail = v_mid = vt[-1]
        a_trail = a_mid = at[-1]
    return vx, ax, Fx, Fy


def load_x(chain) -> np.ndarray:
    """The difference method's load F_dx over one period [N] (K checked against the limit)."""
    check_roundoff(chain.K, chain.roundoff_limit())
    return difference_arrays(chain)[2]
