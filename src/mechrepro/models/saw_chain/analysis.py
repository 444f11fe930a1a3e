"""Measurements on the saw_chain model: order, round-off optimum, the paper's K, readings of R.

Pure functions over a :class:`~.solver.Chain` or a cost-of-accuracy study; the
validation extractors and the notebook call them, nothing here is a verdict.
"""
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
    """Observed order p of err ~ K^-p from the two finest truncation-dominated runs.

    A run is truncation-dominated when the solver's own round-off bound is below
    ``1/margin`` of its truncation estimate (the window follows from each run's error
    budget, not from a chosen K range); the finest pair of them is the closest to the
    asymptotic range.  Returns (order, local orders of all consecutive pairs used, K pair).
    """
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
    """The fitted error model err(K) = a/K + b K^2 and its minimum; ``reason`` says why
    K* is NaN ("" when it is not)."""
    K_opt: float
    err_opt: float
    a: float
    b: float
    reason: str


#: columns whose scaled singular values are closer than this are one column (rank-deficient)
RANK_RTOL = 1e-8


def error_model_optimum(K, err) -> Optimum:
    """Fit err(K) = a/K + b K^2 (truncation + round-off) and return its minimum.

    The fit minimises the relative residuals, a linear least-squares problem in a, b
    with columns 1/(K err) and K^2/err.  Those differ by ~K^3 (1e-1 against 1e14 on a
    study over six decades), so each column is scaled to unit norm before solving:
    unscaled, ``lstsq`` cuts the small singular value as noise and drops the truncation
    column (a z = 3 chain with 5:1 pitches then gave K* = 5.9e-6).  The optimum
    K* = (a / 2b)^(1/3) does not depend on where the sweep samples.  NaN, with the
    reason, when the scaled columns are rank-deficient (fewer than two distinct K,
    collinear columns) or a branch is missing (a <= 0: no truncation; b <= 0: no
    round-off, e.g. a study that stops below the limit).
    """
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
    """Maximum (or ``fn``) of the difference-method load x over one period at K steps per stage."""
    return float(fn(load_x(replace(chain, K=int(K)))))


def load_max_at(chain: Chain, K: int) -> float:
    return load_extreme_at(chain, K, np.max)


def equivalent_K(chain: Chain, target: float):
    """Smallest K whose difference-method load maximum reaches ``target`` (bisection).

    The maximum sits at the last sample t2 and lags the exact value by dt max|dF/dt|, so
    it rises monotonically with K (checked on the bracket); the root is found on the
    solver itself, not interpolated between study points.  Returns (K, max at K - 1,
    max at K); K is None if ``target`` is not reached below the round-off limit.
    """
    lo, hi = 2, chain.roundoff_limit()
    f_lo, f_hi = load_max_at(chain, lo), load_max_at(chain, hi)
    if not (f_lo < target <= f_hi):
        return None, f_lo, f_hi
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if load_max_at(chain, mid) >= target:
            hi = mid
        else:
            lo = mid
    return hi, load_max_at(chain, hi - 1), load_max_at(chain, hi)


def pitch_radius_readings(p1, p2, z):
    """Common readings of a sprocket's pitch radius for the alternating p1/p2 chain [m].

    - ``eq1``: Eq. (1), the circle through the hinge centres (the model's R);
    - ``pair_chord``: the roller-chain formula R = p / (2 sin(pi/z)) with the pair
      p = p1 + p2 taken as one straight chord per tooth;
    - ``mean_pitch``: R = p / (2 sin(pi/2z)) with the mean pitch p = (p1 + p2)/2 on 2z links;
    - ``pitch_line``: the circle whose circumference is the chain length per revolution,
      z (p1 + p2) / (2 pi) (the mean chain speed over omega);
    - ``tie_strap``, ``drive_link``: one pitch alone on 2z links.
    """
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
    """Exact min and max of the tight-side velocity of Eqs. (5)-(10) for a given R [m/s].

    Stage angles follow Eqs. (5)-(6) with this R.  The maximum R omega is reached at the
    stage ends; the minimum is located by a bounded scalar minimisation in each stage,
    so it does not depend on a sampling grid.
    """
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
    """theta [rad] and mass [kg] for which Eq. (23) spans [F_low, F_high] over one tooth.

    Both ends negative means sin(omega t + theta) > 0 over omega t in [0, 2 pi/z]; with
    theta + 2 pi/z < pi/2 the load runs monotonically from -A sin(theta) (= F_high) to
    -A sin(theta + 2 pi/z) (= F_low), A = m R omega^2.  Two numbers fix the two constants:
    cot(theta) = (r - cos a) / sin a with r = F_low / F_high, a = 2 pi / z.
    """
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
    """The minimum of a load sampled over one period (2K + 1 samples, K per stage), read at
    the vertex of the parabola through the lowest sample and its two neighbours; and the
    lowest sample's index.

    An interior minimum lies between samples: the lowest sample misses it by
    F''(t*) delta^2 / 2, delta the distance to the nearest sample, and delta / dt jumps
    erratically with K (the fraction of t* / dt: 0.13, 0.26, 0.48 of a step at K = 250,
    500, 1000 on the paper's chain), so that error follows no power law and the levels'
    Richardson estimate under-estimated it 1.9x at K = 1000 (issue 63).  The vertex removes
    the grid phase to O(dt^3 F'''/F''), leaving the method's own error, smooth in K (second
    order at an interior extremum, where F' = 0).  At an end of the period, next to the
    stage switch (its own non-converging sample) or where the neighbours do not curve
    upward (a flat load: the constant-speed rival), the lowest sample itself is returned.
    """
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
    """The difference method's load extremes along the K study, and the exact ones.

    The exact extremes (analytic derivatives of Eqs. 7-10) do not depend on K up to the
    sampling of the period; those of the study's first run are the reference.
    Returns {"K": K, "max": (method, exact), "min": (method, exact)}.
    """
    return {"K": study["K"].values,
            "max": (study["dynamic_load_x_max"].values, float(study["dynamic_load_x_exact_max"][0])),
            "min": (study["dynamic_load_x_min"].values, float(study["dynamic_load_x_exact_min"][0]))}


def error_budget_relative(study) -> dict:
    """The solver's a-priori error budget along the K study, relative to the exact peak load.

    ``truncation``: dt max|dF/dt| (the leading term of Eqs. 13, 19), falling like 1/K;
    ``roundoff``: 4 eps x m / dt^2 of the second backward difference, growing like K^2
    (see :mod:`.difference`).  Returns {"K", "truncation", "roundoff"}.
    """
    peak = float(study["dynamic_load_x_exact_max"][0])
    return {"K": study["K"].values,
            "truncation": study["truncation_load_estimate"].values / peak,
            "roundoff": study["roundoff_load_bound"].values / peak}


def paper_band(row: dict) -> tuple[float, float]:
    """The band a validation row accepts around the paper's value: value (1 -+ tolerance),
    in the row's unit (e.g. the measured 14.6 +- 0.1 m/s of Fig. 7)."""
    value, tol = float(row["paper_value"]), float(row["tolerance"])
    return value - abs(value) * tol, value + abs(value) * tol
