"""An accuracy asked for (mechrepro.target), one small check per paper: the error achieved at the
chosen setting, against an exact or a Richardson-extrapolated reference, is within the request,
and the chosen setting costs at most twice the cheapest sampled setting that meets it.

Cost is compared through the knob (cost ~ knob^c, c the scheme's cost exponent: 1 for a march
or a 1-D mesh, 2 for the string's grid, whose CFL-bound time step shrinks with the grid), not
through wall time, so that the check gives the same answer on any machine."""
import math

import numpy as np
import pytest

from mechrepro.config import load_paper
from mechrepro.solve import _solve_once, run_solver
from mechrepro.target import reduce


def at(run, knob, k):
    v = [k] if isinstance(run["resolution"][knob], list) else k
    return {**run, "target": None, "resolution": {**run["resolution"], knob: v},
            "options": {**run.get("options", {}), "timing_min_s": 0.0}}


def quantity(run, k, name=None):
    t = run["target"]
    return reduce(_solve_once(at(run, t["knob"], k)), name or t["quantity"], t.get("reduce", "max"),
                  t.get("select"))


def richardson(run, k, name=None):
    """The reference from three levels k, 2k, 4k extrapolated with their observed order."""
    q = [quantity(run, kk, name) for kk in (k, 2 * k, 4 * k)]
    p = math.log(abs(q[0] - q[1]) / abs(q[1] - q[2])) / math.log(2)
    return q[2] + (q[2] - q[1]) / (2 ** p - 1)


CASES = {
    # paper: (scene, cost exponent, sampled knob values, reference)
    "saw_chain": ("load_max_target", 1, np.unique(np.geomspace(1000, 20000, 40).astype(int)),
                  "exact"),
    "chain_drive": ("exact_free_target", 2, np.arange(40, 161, 4), "exact"),
    "disk_tension": ("unrolled_frequency_target", 1, np.arange(8, 65, 2), "exact"),
    "joint_wear": ("wear_factor_target", 1, np.unique(np.geomspace(64, 1024, 30).astype(int)),
                   ("richardson", 2048)),
    "rolling_shear": ("stroke_h_target", 1, np.unique(np.geomspace(100, 1600, 25).astype(int)),
                      ("richardson_of", 2049, "exact_synthetic_horizontal_displacement")),
}


@pytest.mark.parametrize("paper", list(CASES))
def test_target_is_met_at_near_the_cheapest_setting(paper):
    scene, c, sample, ref = CASES[paper]
    run = load_paper(f"config/papers/{paper}.yaml").runs[scene]
    t = run["target"]
    ds = run_solver(run)
    requested, k = float(ds["target_requested"]), float(ds["target_knob_value"])
    if ref == "exact":
        exact = float(ds["target_verified_error"])   # |q(k) - exact|, the exact of the scene
        reference = reduce(ds, t["exact"], t.get("reduce", "max"), t.get("select"))
        errors = {int(kk): abs(quantity(run, int(kk)) - quantity(run, int(kk), t["exact"]))
                  for kk in sample}
        achieved = exact
    else:
        name = ref[2] if ref[0] == "richardson_of" else None
        reference = richardson(run, ref[1], name)
        achieved = abs(reduce(ds, t["quantity"], t.get("reduce", "max"), t.get("select"))
                       - reference)
        errors = {int(kk): abs(quantity(run, int(kk)) - reference) for kk in sample}
    assert achieved <= requested, (paper, achieved, requested, k, reference)
    meets = [kk for kk, e in errors.items() if e <= requested]
    assert meets, (paper, "no sampled setting meets the request", errors)
    cheapest = min(meets)
    assert k ** c <= 2 * cheapest ** c, (paper, k, cheapest)
    # the fixed default is recorded next to it; it misses the request (so this check can fail):
    # the scene's own first level, coarser than the chosen one, or the setting of the scene it
    # is compared with (compare_with: saw_chain's paper scene, K = 1000, finer than the
    # extrapolated target's K and still 4x off)
    k0 = int(ds["target_default_value"])
    default_error = (abs(quantity(run, k0) - quantity(run, k0, t["exact"])) if ref == "exact"
                     else abs(quantity(run, k0) - reference))
    assert default_error > requested
    assert k0 < k or t.get("compare_with")
    print(f"{paper}: requested {requested:.3g} estimated {float(ds['target_estimated_error']):.3g} "
          f"achieved {achieved:.3g} at {t['knob']}={k:g} (cheapest sampled {cheapest}) "
          f"time {float(ds['target_seconds_chosen']):.3g} s; default {t['knob']}={k0} error "
          f"{default_error:.3g} time {float(ds['target_default_seconds']):.3g} s")


def extrapolated(run, k, r):
    """What ``extrapolate: true`` delivers with k its finest level: Richardson's
    extrapolation of levels k/r^2, k/r, k (order measured on the three)."""
    q = [quantity(run, max(1, round(k / r ** j))) for j in (2, 1, 0)]
    p = math.log(abs(q[0] - q[1]) / abs(q[1] - q[2])) / math.log(r)
    return q[2] + (q[2] - q[1]) / (r ** p - 1)


def test_an_extrapolated_target_is_near_the_cheapest_extrapolation_that_meets_it():
    """The check above compares an extrapolated target with plain settings, which it beats by
    10x; here it is compared with its own method: the delivered value at each sampled finest
    level k is the extrapolation of k/r^2, k/r, k, whose cost is ~ k.  Measured 2026-11-29:
    from K = 168 on every sampled extrapolation meets 1e-3 (0.216); the target delivers
    K = 240 (error 0.077, estimated 0.078).  It failed (K = 480, 2.9x) while the estimate of
    R_i was |R_i - R_(i-1)|, the error of the coarser R_(i-1)."""
    run = load_paper("config/papers/saw_chain.yaml").runs["load_max_target"]
    t, r = run["target"], float(run["target"]["factor"])
    ds = run_solver(run)
    requested, k = float(ds["target_requested"]), float(ds["target_knob_value"])
    assert float(ds["target_verified_error"]) <= requested
    # finest levels that are multiples of r^2, so that every ratio is r
    sample = [int(r ** 2) * int(m) for m in np.unique(np.geomspace(15, 240, 17).astype(int))]
    ok = [abs(extrapolated(run, kk, r) - quantity(run, kk, t["exact"])) <= requested
          for kk in sample]
    # the cheapest from which on every sampled level meets it (not a lucky crossing of zero)
    assert ok[-1], (sample, ok)
    cheapest = sample[len(ok) - ok[::-1].index(False)] if False in ok else sample[0]
    assert k <= 2 * cheapest, (k, cheapest)
