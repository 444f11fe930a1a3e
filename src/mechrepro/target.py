"""Ask for an accuracy instead of a resolution: the cheapest knob setting whose estimated error
meets a requested tolerance.

A scene may say::

    target: {quantity: dynamic_load_x, reduce: max, rtol: 1.0e-3, knob: K,
             exact: dynamic_load_x_exact}

The runner (:func:`solve`) solves the scene at its own knob value k0 and at k0 r, k0 r^2
(r: the knob's ``refine`` factor).  With q_i the reduced quantity, the three levels give the
observed order p = ln(|q0 - q1| / |q1 - q2|) / ln r and the error of the finest level,
e2 = |q1 - q2| / (r^p - 1) (Richardson).  A coarser level j is off by at most its distance to
the finest plus the finest's error, e_j = |q_j - q2| + e2 (the power law e2 (k2 / k_j)^p fitted
on the finest levels under-estimates it where the coarse levels are not yet asymptotic:
tests/test_target.py).  It returns the cheapest sampled level whose estimated error meets
``rtol |q|`` (or ``atol``), or else solves once more at the predicted setting
k* = k2 (e2 / tol)^(1/p) (when within one refinement of k2), whose estimated error is that
prediction.  The dataset records what was
requested, the estimated error, the error against ``exact`` where the scene computes one (the
verified error) and the time of every solve it took, beside the fixed setting it is compared
with: the scene's own knob value, or another scene's (``compare_with:``, e.g. the paper
scene's resolution; the config resolves it into ``default``).

With ``extrapolate: true`` the delivered value is Richardson's extrapolation of two levels,
R_i = q_i + (q_i - q_{i-1}) / (r^p_i - 1) with p_i measured on the three levels up to i.  The
extrapolations converge in turn, and their error is estimated as the plain values' is: from
three successive ones, e(R_i) = |R_i - R_{i-1}| / (r^p_R - 1), with p_R their observed order
(none unless |R_i - R_{i-1}| < |R_{i-1} - R_{i-2}|: the levels are refined until it is
observed) taken at most p_i + 1, the order of what removing h^p leaves; a coarser R_j is off
by at most |R_j - R_i| + e(R_i).  The cheapest R_j whose estimate meets the request is
delivered (five levels at least).
"""
from __future__ import annotations

import math
import time

import numpy as np

from .levels import extrapolate, order_and_error, richardson_error

SAFETY = 0.7       # the predicted setting aims at this fraction of the request (cost <= 0.7^(-1/p))
MAX_LEVELS = 24     # solves at most; a target not met by then is an error, not a guess

REDUCE = {"max": np.nanmax, "min": np.nanmin, "mean": np.nanmean,
          "absmax": lambda a: np.nanmax(np.abs(a))}


def reduce(ds, name: str, how: str, select: dict | None = None) -> float:
    """``how`` of variable ``name`` over all its points (after picking ``select``'s
    coordinate values along the dimensions the variable has)."""
    v = ds[name]
    pick = {k: x for k, x in (select or {}).items() if k in v.dims}
    return float(REDUCE[how](np.asarray(v.sel(pick).values if pick else v.values, float)))


def _with(run: dict, knob: str, value) -> dict:
    # a solver that takes a list of grids is given a list of one
    as_list = isinstance(run["resolution"][knob], list)
    return {**run, "resolution": {**run["resolution"], knob: [value] if as_list else value}}


def solve(run: dict, solve_once) -> tuple[object, dict]:
    """``solve_once(run) -> (dataset, seconds)`` at the cheapest setting meeting the target;
    returns the chosen dataset and the record of the choice."""
    t = run["target"]
    knob, ratio = t["knob"], float(t["factor"])
    finer_is_larger = ratio > 1
    k0 = run["resolution"][knob]
    if isinstance(k0, list):
        if len(k0) != 1:
            raise ValueError(f"{run['run']}: target.knob {knob} = {k0}: give one value")
        k0 = k0[0]
    as_int = isinstance(k0, int)

    def level(k):
        return max(1, int(round(k))) if as_int else float(k)

    r = ratio if finer_is_larger else 1 / ratio              # > 1
    ks, solved, q, seconds = [], [], [], []

    def add(k):
        ds, s = solve_once(_with(run, knob, k))
        ks.append(k), solved.append(ds), seconds.append(s)
        q.append(reduce(ds, t["quantity"], t.get("reduce", "max"), t.get("select")))

    def step(k):                                            # smaller is finer
        return 1.0 / k if finer_is_larger else k

    # one untimed call first: a one-off cost of the process (a kernel compiled or loaded on
    # first use) is billed to no level
    solve_once(_with(run, knob, level(k0)))
    for i in range(3):
        add(level(k0 * ratio ** i))
    chosen = None
    p = math.nan
    value = None
    R = {}                     # level -> extrapolation with the order measured up to it
    while t.get("extrapolate") and len(ks) < MAX_LEVELS:
        tol = max(float(t.get("rtol", 0.0)) * abs(q[-1]), float(t.get("atol", 0.0)))
        i = measured = len(ks) - 1
        p, e_last = order_and_error(q[-3:], r)
        if p == math.inf:             # the levels agree exactly: nothing to extrapolate
            chosen, value, estimate = i, q[-1], 0.0
            break
        if math.isfinite(p) and p > 0:
            R[i] = extrapolate(q[i - 1], q[i], r, p)
        if all(j in R for j in (i - 2, i - 1, i)):
            # the extrapolations' own Richardson estimate, none unless their differences shrink
            p_R, _ = order_and_error([R[i - 2], R[i - 1], R[i]], r)
            if p_R > 0:
                # removing h^p leaves h^(p+1) or a higher power: an order observed above p + 1
                # is pre-asymptotic, no licence for a smaller estimate
                p_R = min(p_R, p + 1.0)
                e_R = richardson_error(R[i - 1], R[i], r, p_R)
                # a coarser extrapolation is off by its distance to R_i and R_i's error
                est = {j: abs(R[j] - R[i]) + e_R for j in R}
                meets = [j for j in sorted(R) if est[j] <= tol]
                if meets:
                    chosen, value, estimate = meets[0], R[meets[0]], est[meets[0]]
                    break
        add(level(ks[-1] * ratio))
    while chosen is None and len(ks) < MAX_LEVELS:
        tol = max(float(t.get("rtol", 0.0)) * abs(q[-1]), float(t.get("atol", 0.0)))
        p, e_last = order_and_error(q[-3:], r)
        measured = len(ks) - 1              # the level e_last is the error of
        if not (math.isfinite(e_last) and math.isfinite(p)) or p <= 0:
            add(level(ks[-1] * ratio))    # pre-asymptotic: refine and estimate again
            continue
        est = [abs(qj - q[measured]) + e_last for qj in q]     # triangle: see module
        meets = [i for i, e in enumerate(est) if e <= tol]
        if meets:
            chosen, estimate = meets[0], est[meets[0]]
            break
        # aim below the request: a Richardson estimate is itself ~10 % uncertain
        h_star = step(ks[-1]) * (SAFETY * tol / e_last) ** (1.0 / p)
        k_star = 1.0 / h_star if finer_is_larger else h_star
        if as_int:   # round towards finer
            k_star = math.ceil(k_star) if finer_is_larger else max(1, math.floor(k_star))
        k_star = level(k_star)
        if step(k_star) >= step(ks[-1]) / r:
            # within one refinement: the order measured here holds, solve at the prediction
            # (a prediction, not a measurement: from levels not yet asymptotic it can miss,
            # tests/test_target.py)
            add(k_star)
            chosen, estimate = len(ks) - 1, e_last * (step(k_star) / step(ks[measured])) ** p
            break
        # further than one refinement: the order may still change, refine and re-measure it
        add(level(ks[-1] * ratio))
    spent = sum(seconds)
    if chosen is None:
        raise RuntimeError(f"{run['run']}: target {t} cannot be met: the levels {ks} give "
                           f"{q}, which do not converge (no error estimate)")
    ds = solved[chosen]
    value = q[chosen] if value is None else value
    verified = exact = math.nan
    if t.get("exact"):
        exact = reduce(ds, t["exact"], t.get("reduce", "max"), t.get("select"))
        verified = abs(value - exact)
    # the fixed setting compared with: the scene's own knob value (level 0), or the one the
    # config names (``compare_with:`` a scene, e.g. the paper scene's resolution), solved once
    # more when it is not among the levels; its error estimate then runs through the
    # delivered value, |q_default - value| + estimate
    k_def = t.get("default", ks[0])
    k_def = k_def[0] if isinstance(k_def, list) else k_def   # a solver that takes a list of grids
    if k_def in ks:
        i = ks.index(k_def)
        q_def, s_def = q[i], seconds[i]
        est_def = abs(q_def - q[measured]) + e_last
    else:
        ds_def, s_def = solve_once(_with(run, knob, level(k_def)))
        q_def = reduce(ds_def, t["quantity"], t.get("reduce", "max"), t.get("select"))
        est_def = abs(q_def - value) + estimate
    record = {"knob": knob, "knob_value": ks[chosen], "levels": ks, "values": q, "value": value,
              "extrapolated": bool(t.get("extrapolate")),
              "observed_order": p, "requested": tol, "estimated_error": estimate,
              "verified_error": verified, "seconds_all_solves": spent,
              "seconds": seconds,
              # an extrapolated value costs the three levels it is made of (its estimate, the
              # finer levels, is in seconds_all_solves, as a plain value's is)
              "seconds_chosen": (sum(seconds[max(0, chosen - 2):chosen + 1])
                                 if t.get("extrapolate") else seconds[chosen]),
              # the fixed default: the scene's own knob value (level 0) or ``default``
              "default_value": k_def, "default_error": abs(q_def - exact),
              "default_seconds": s_def, "default_estimated_error": est_def}
    return ds, record


def timed(solve_fn):
    """``solve_fn(run) -> dataset`` as ``(dataset, seconds)``."""
    def once(run):
        t0 = time.perf_counter()
        ds = solve_fn(run)
        return ds, time.perf_counter() - t0
    return once
