"""Measurements on the saw_chain model: order, round-off optimum, the paper's K, readings of R;
pure functions, no verdicts."""
from __future__ import annotations

import math
from dataclasses import replace
from typing import NamedTuple

import numpy as np

from mechrepro.errors import Refusal

from .geometry import stage_angles
from .kinematics import stage_derivatives
from .chain import Chain
from .difference import load_x


def observed_order(K, err, truncation, roundoff, margin=100.0):
    """Observed order p of err ~ K^-p from the two finest truncation-dominated runs (round-off
    bound below 1/``margin`` of the truncation estimate).  Returns (order, local orders, K pair)."""
    K, err = np.asarray(K, float), np.asarray(err, float)
    use = (np.asarray(roundoff) * margin < np.asarray(truncation)) & (err > 0)
    k, e = K[use], err[use]
    order = np.argsort(k)
    k, e = k[order], e[order]
    if k.size < 2:
        return math.nan, [], ()
    local = list(-np.diff(np.log(e)) / np.diff(np.log(k)))
    return float(local[-1]), [float(x) for x in local], (int(k[-2]), int(k[-1]))


class Optimum(NamedTuple):
    """The fitted err(K) = a/K + b K^2 and its minimum; ``reason`` says why K* is NaN."""
    K_opt: float
    err_opt: float
    a: float
    b: float
    reason: str


#: columns whose scaled singular values are closer than this are one column (rank-deficient)
RANK_RTOL = 1e-8


def error_model_optimum(K, err) -> Optimum:
    """Fit err(K) = a/K + b K^2 by relative least squares and return its minimum
    K* = (a / 2b)^(1/3).  The columns differ by ~K^3, so each is scaled to unit norm (unscaled,
    ``lstsq`` drops the truncation column).  NaN with the reason when rank-deficient or a
    branch is missing (a <= 0 or b <= 0)."""
    K, err = np.asarray(K, float), np.asarray(err, float)
    use = np.isfinite(err) & (err > 0) & (K > 0)
    K, err = K[use], err[use]
    nan = math.nan
    if np.unique(K).size < 2:
        return Optimum(nan, nan, nan, nan, f"rank-deficient: {np.unique(K).size} distinct K")
    A = np.column_stack([1.0 / (K * err), K**2 / err])
    scale = np.linalg.norm(A, axis=0)
    s = np.linalg.svd(A / scale, compute_uv=False)
    if s[-1] <= RANK_RTOL * s[0]:
        return Optimum(nan, nan, nan, nan,
                       f"rank-deficient: scaled singular values {s[0]:.3g}, {s[-1]:.3g}")
    coef, *_ = np.linalg.lstsq(A / scale, np.ones_like(K), rcond=None)
    a, b = (float(c) for c in coef / scale)
    if not a > 0:
        return Optimum(nan, nan, a, b, f"no truncation branch (a = {a:.3g})")
    if not b > 0:
        return Optimum(nan, nan, a, b, f"no round-off branch (b = {b:.3g})")
    K_opt = (a / (2.0 * b)) ** (1.0 / 3.0)
    return Optimum(float(K_opt), float(a / K_opt + b * K_opt**2), a, b, "")


def load_extreme_at(chain: Chain, K: int, fn=np.max) -> float:
    """``fn`` of the difference-method load x over one period at K steps per stage."""
    return float(fn(load_x(replace(chain, K=int(K)))))


def equivalent_K(chain: Chain, target: float):
    """Smallest K whose load maximum reaches ``target``, by bisection on the solver (the maximum
    rises monotonically with K).  Returns (K, max at K - 1, max at K); K None if not reached
    below the round-off limit."""
    lo, hi = 2, chain.roundoff_limit()
    f_lo, f_hi = load_extreme_at(chain, lo), load_extreme_at(chain, hi)
    if not (f_lo < target <= f_hi):
        return None, f_lo, f_hi
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if load_extreme_at(chain, mid) >= target:
            hi = mid
        else:
            lo = mid
    return hi, load_extreme_at(chain, hi - 1), load_extreme_at(chain, hi)


def pitch_radius_readings(p1, p2, z):
    """Readings of the pitch radius of the alternating p1/p2 chain [m]: ``eq1`` (Eq. 1, the
    model's), ``pair_chord`` (p1 + p2 as one chord per tooth), ``mean_pitch`` (the mean pitch on
    2z links), ``pitch_line`` (z (p1 + p2) / 2 pi), ``tie_strap``, ``drive_link`` (one pitch on
    2z links)."""
    s, s2 = math.sin(math.pi / z), math.sin(math.pi / (2 * z))
    return {
        "eq1": math.sqrt(p1**2 + p2**2 + 2 * p1 * p2 * math.cos(math.pi / z)) / (2 * s),
        "pair_chord": (p1 + p2) / (2 * s),
        "mean_pitch": 0.5 * (p1 + p2) / (2 * s2),
        "pitch_line": z * (p1 + p2) / (2 * math.pi),
        "tie_strap": p1 / (2 * s2),
        "drive_link": p2 / (2 * s2),
    }


def velocity_band(p1, p2, omega, R):
    """Exact min and max of the tight-side velocity of Eqs. (5)-(10) for a given R [m/s]: R omega
    at the stage ends, the minimum by bounded minimisation (no sampling grid)."""
    from scipy.optimize import minimize_scalar  # here: the notebook imports this module

    phi1, phi2 = stage_angles(p1, p2, R)
    lows = []
    for L, span in ((p2, phi1), (p1, phi2 - phi1)):
        vx = lambda ph, L=L: float(stage_derivatives(np.float64(ph), R, L, omega)["trail_vx"])  # noqa: E731
        res = minimize_scalar(vx, bounds=(0.0, float(span)), method="bounded",
                              options={"xatol": 1e-12 * float(span)})
        lows.append(min(res.fun, vx(0.0), vx(float(span))))
    return float(min(lows)), float(R * omega)


def textbook_constants_for_range(F_low, F_high, R, omega, z):
    """theta [rad] and mass [kg] for which Eq. (23) spans [F_low, F_high] < 0 over one tooth:
    cot(theta) = (r - cos a) / sin a, r = F_low / F_high, a = 2 pi / z."""
    a = 2 * math.pi / z
    if not (F_low < F_high < 0):
        raise Refusal(f"needs F_low < F_high < 0, got {F_low}, {F_high}")
    r = F_low / F_high
    theta = math.atan2(math.sin(a), r - math.cos(a))
    A = -F_high / math.sin(theta)
    if theta + a >= math.pi / 2:
        raise Refusal("the range is not monotonic over one tooth; no closed form")
    return theta, A / (R * omega**2)


def interior_minimum(F, K: int) -> tuple[float, int]:
    """Minimum of a load over one period (2K + 1 samples) at the vertex of the parabola through
    the lowest sample and its neighbours, and that sample's index.  The lowest sample alone
    carries a grid-phase error that jumps with K; the vertex leaves the method's own, smooth
    error.  At the period's ends, next to the stage switch or without upward curvature, the
    lowest sample itself."""
    F = np.asarray(F, float)
    i = int(np.argmin(F))
    if i < 1 or i >= F.size - 1 or i in (K, K + 1, K + 2):
        return float(F[i]), i
    y0, y1, y2 = F[i - 1], F[i], F[i + 1]       # within one stage: equal steps either side
    curvature = y0 - 2.0 * y1 + y2
    if not curvature > 0.0:
        return float(y1), i
    return float(y1 - (y2 - y0) ** 2 / (8.0 * curvature)), i


def time_mean(t, v):
    """Time mean of a sampled signal over its span (trapezoidal rule)."""
    t, v = np.asarray(t, float), np.asarray(v, float)
    return float(np.trapezoid(v, t) / (t[-1] - t[0]))


def stage_one_end(ds) -> float:
    """t1 of a run [s]: the end of stage 1, when the drive link O1O2 is seated (Eq. 5)."""
    t, stage = ds["t"].values, ds["stage"].values
    return float(t[stage == 1][-1])


def load_range_against_K(study) -> dict:
    """{"K", "max": (method, exact), "min": (method, exact)} of the load along the K study."""
    return {"K": study["K"].values,
            "max": (study["dynamic_load_x_max"].values, float(study["dynamic_load_x_exact_max"][0])),
            "min": (study["dynamic_load_x_min"].values, float(study["dynamic_load_x_exact_min"][0]))}


def error_budget_relative(study) -> dict:
    """The solver's truncation estimate and round-off bound along the K study, relative to the
    exact peak load."""
    peak = float(study["dynamic_load_x_exact_max"][0])
    return {"K": study["K"].values,
            "truncation": study["truncation_load_estimate"].values / peak,
            "roundoff": study["roundoff_load_bound"].values / peak}


def paper_band(row: dict) -> tuple[float, float]:
    """The band a row accepts: paper value (1 -+ tolerance), in the row's unit."""
    value, tol = float(row["paper_value"]), float(row["tolerance"])
    return value - abs(value) * tol, value + abs(value) * tol
