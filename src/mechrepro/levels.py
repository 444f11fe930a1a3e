"""The one estimator of a value's error and observed order from resolution levels, used by
the verdicts (:mod:`mechrepro.validation`), the accuracy targets (:mod:`mechrepro.target`) and
the cost-of-accuracy curves (:mod:`mechrepro.accuracy`).

Three levels q0, q1, q2, each refined by r (every knob together), differ by d1 = q0 - q1 and
d2 = q1 - q2; for a method of order p they contract by |d1| / |d2| = r^p.  Richardson's
extrapolation removes the leading term, R = q2 + (q2 - q1) / (r^p - 1), and the finest
level's error is its distance to R, |d2| / (r^p - 1) (Roache's grid convergence index
without a safety factor).  Levels that do not contract (|d1| / |d2| <= 1.05) give no
estimate: they do not converge.
"""
from __future__ import annotations

import math

# differences between levels below this share of the tolerance band cannot move a verdict
NEGLIGIBLE = 1e-3
# |d1| / |d2| at or below this: the levels do not contract
CONTRACTION_MIN = 1.05


def extrapolate(coarse, fine, ratio: float, order: float):
    """Richardson's extrapolation of two levels of a method of order p refined by r:
    R = q_fine + (q_fine - q_coarse) / (r^p - 1) (arrays elementwise)."""
    return fine + (fine - coarse) / (ratio ** order - 1.0)


def richardson_error(coarse, fine, ratio: float, order: float):
    """Richardson's error estimate of the finer of two levels of order p:
    |q_fine - q_coarse| / (r^p - 1)."""
    return abs(fine - coarse) / (ratio ** order - 1.0)


def order_and_error(q, ratio: float) -> tuple[float, float]:
    """(observed order, Richardson error of the finest) of three levels q0, q1, q2 (coarse
    to fine): (inf, 0) when the two finest agree exactly, (nan, inf) when the levels do not
    contract."""
    d1, d2 = abs(q[0] - q[1]), abs(q[1] - q[2])
    if d2 == 0.0:
        return math.inf, 0.0
    if d1 / d2 <= CONTRACTION_MIN:
        return math.nan, math.inf   # not in the asymptotic range: no estimate
    p = math.log(d1 / d2) / math.log(ratio)
    return p, richardson_error(q[1], q[2], ratio, p)


def level_error(coarsest: float, coarse: float, base: float, ratio: float, width: float,
                own: float = 0.0) -> tuple[float, float, bool, str]:
    """Error estimate of ``base``, the finest level, from the two levels below it (every
    knob coarsened by ``ratio`` per level): (error, observed order, converged, how).

    d1 = coarsest - coarse and d2 = coarse - base contract by q = |d1| / |d2| = ratio^p
    for a method of order p; the baseline's error is then |d2| / (q - 1), its distance to
    the Richardson extrapolate (Roache's grid convergence index without a safety factor).
    Differences below round-off, a thousandth of ``width`` (the tolerance band) or the
    coarsest level's own resolution (``own``, the extraction's error at the base level, e.g.
    half a grid step, times ``ratio``^2) are negligible: a value read off a grid jitters
    within its step; levels that do not contract (q <= 1.05) do not converge; contracting
    levels that oscillate (d1 and d2 of opposite sign) have no extrapolate, their spread
    max(|d1|, |d2|) is the error.  ``coarsest`` NaN: two levels only, no order is measured:
    the error is Richardson's at first order, |d2| / (ratio - 1), and at least |d2|."""
    d2 = abs(coarse - base)
    if math.isnan(coarsest):
        # no order measured: first order, the lowest of any scheme here, and never below |d2|
        e = d2 * max(1.0, 1.0 / (ratio - 1.0)) if math.isfinite(ratio) and ratio > 1 else d2
        return e, math.nan, True, (f"2 levels: |coarser - base| = {d2:.3g}, taken as first "
                                   f"order at ratio {ratio:.3g}")
    d1 = abs(coarsest - coarse)
    floor = max(1e-9 * abs(base), NEGLIGIBLE * width if math.isfinite(width) else 0.0,
                own * max(ratio, 1.0) ** 2 if math.isfinite(ratio) else own)
    if max(d1, d2) <= floor:
        return max(d1, d2), math.nan, True, ("levels agree to within round-off, 1e-3 of the "
                                             "band or the quantity's own sampling step")
    if d2 == 0.0:
        return 0.0, math.inf, True, "coarser and base agree exactly"
    q = d1 / d2
    order, error = order_and_error((coarsest, coarse, base), ratio)
    if not math.isfinite(error):
        return math.inf, math.nan, False, (f"does not converge: coarsest {coarsest:.6g}, "
                                           f"coarser {coarse:.6g}, base {base:.6g} "
                                           f"(|d1|/|d2| = {q:.3g})")
    if min(d1, d2) > floor and (coarsest - coarse) * (coarse - base) < 0:
        # oscillating levels have no Richardson extrapolate: the spread is the error
        return max(d1, d2), math.nan, True, (f"levels oscillate: coarsest {coarsest:.6g}, "
                                             f"coarser {coarse:.6g}, base {base:.6g}")
    return error, order, True, f"3 levels, |d1|/|d2| = {q:.3g}"
