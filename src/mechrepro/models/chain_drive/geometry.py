"""Drive geometry and the analytic moving-string frequencies (SI units throughout).

Vocabulary follows Choi & Johnson: pitch ``p_c``, tooth numbers ``n1`` (driving) and
``n2`` (driven), chain (span) velocity ``c``, static tension ``T_s``, mass per unit
length ``m`` (the paper's m_1), span length ``L``.
"""
from __future__ import annotations

import math

import numpy as np

RPM = 30.0 / np.pi   # rad/s -> rpm


def pitch_radius(p_c: float, n: int) -> float:
    """Pitch-circle radius of an n-tooth sprocket: r = p_c / (2 sin(pi/n))."""
    return p_c / (2.0 * np.sin(np.pi / n))


def tooth_period(omega1, n1: int):
    """Tooth period tau = 2 pi / (n1 omega1) (Sec. 2.1.2b)."""
    return 2.0 * np.pi / (n1 * np.asarray(omega1, float))


def chain_speed(omega1, n1: int, p_c: float):
    """Mean chain (span) velocity c = n1 p_c omega1 / (2 pi): one pitch per tooth period."""
    return n1 * p_c * np.asarray(omega1, float) / (2.0 * np.pi)


def fractional_pitch(L_ct: float, p_c: float) -> float:
    """Eq. (2-6): f_p = (L_ct - i* p_c) / p_c with 0 <= f_p < 1."""
    q = L_ct / p_c
    f = q - np.floor(q + 1e-12)
    return float(0.0 if abs(f) < 1e-9 or abs(f - 1.0) < 1e-9 else f)


def span_lengths(L_ct: float, p_c: float) -> tuple[float, float]:
    """The two free-span lengths L_0 (short) and L_0 + p_c (long) of Sec. 2.1.2b.

    The free span always holds a whole number of pitches; its mean over a tooth period
    is the common-tangent length L_ct.  At an integral-pitch centre distance the two are
    equal (no length change).
    """
    f = fractional_pitch(L_ct, p_c)
    L0 = L_ct - f * p_c
    return (L0, L0) if f == 0.0 else (L0, L0 + p_c)


def span_geometry(prm: dict, length_change: bool = True) -> dict:
    """Common tangent, fractional pitch (Eq. 2-6) and the two span lengths (both L_ct
    without ``length_change``: the centre distance as an average span length)."""
    p = prm["pitch"]
    n1, n2 = int(prm["n1"]), int(prm["n2"])
    C = prm["centre_distance"] * p
    r1, r2 = pitch_radius(p, n1), pitch_radius(p, n2)
    L_ct = math.sqrt(C**2 - (r2 - r1) ** 2)
    f_p = fractional_pitch(L_ct, p)
    L0, L1 = span_lengths(L_ct, p)
    if not length_change:
        L0 = L1 = L_ct      # the centre distance as an average span length (Fig. 5, solid)
    return {"L_ct": L_ct, "f_p": f_p, "L_short": L0, "L_long": L1}


def axial_tension(T_s, tension_coefficient, c):
    """P = T_s + k c^2 (Eq. 2-36 with Eq. 2-1): k = lambda m with speed tensioning, else 0
    (the ``tension_coefficient`` contributed by the effects).  The one place P is formed."""
    return T_s + tension_coefficient * np.asarray(c, float) ** 2


def s_star(c, T_s, m):
    """Eq. (2-38): s* = c / sqrt(T_s / m), the mixed-differencing weight (clipped to [0, 1])."""
    return np.clip(np.asarray(c, float) / np.sqrt(T_s / m), 0.0, 1.0)


def moving_string_frequencies(k, c, P, m, L):
    """Exact natural frequencies of the axially moving string (Wickert & Mote 1990):

    omega_k = k pi (c_w^2 - c^2) / (c_w L),  c_w^2 = P/m.  Vectorised over k and c.
    """
    cw2 = np.asarray(P, float) / m
    cw = np.sqrt(cw2)
    return np.asarray(k, float) * np.pi * (cw2 - np.asarray(c, float) ** 2) / (cw * L)


def resonance_speed(k: int, L: float, *, n1: int, p_c: float, T_s: float, m: float,
                    tension_coefficient: float, harmonic: float = 1,
                    omega_max: float = 1e4) -> float:
    """Driving-sprocket speed omega1 [rad/s] at which the tooth frequency ``harmonic * n1 * omega1``
    meets the k-th moving-string natural frequency of a span of length L.

    Returns nan when no such speed exists below ``omega_max`` (beyond the critical speed).
    """
    from scipy.optimize import brentq   # here: limits.cost reads this module at config load

    def f(w1):
        c = chain_speed(w1, n1, p_c)
        P = axial_tension(T_s, tension_coefficient, c)
        return harmonic * n1 * w1 - moving_string_frequencies(k, c, P, m, L)

    lo = 1e-9
    if f(lo) >= 0:
        return float("nan")
    grid = np.geomspace(1e-3, omega_max, 400)
    vals = f(grid)        # f is vectorised (the bracket only needs the signs)
    idx = np.nonzero(np.diff(np.sign(vals)) > 0)[0]
    if len(idx) == 0:
        return float("nan")
    i = idx[0]
    return float(brentq(f, grid[i], grid[i + 1], xtol=1e-12))


def longitudinal_frequency(j: int, EA: float, m: float, c: float, L: float) -> float:
    """j-th longitudinal frequency of the span as a moving rod: j pi (a^2 - c^2)/(a L), a^2 = EA/m."""
    return float(moving_string_frequencies(j, c, EA, m, L))
