"""An accuracy asked for instead of a resolution (src/mechrepro/target.py)."""
import math
from pathlib import Path

import numpy as np
import pytest

from mechrepro.config import load_paper
from mechrepro.solve import run_solver
from mechrepro.levels import order_and_error


def test_order_and_error_of_a_first_and_a_second_order_sequence():
    for p in (1.0, 2.0):
        q = [5.0 + 3.0 * h ** p for h in (0.4, 0.2, 0.1)]
        order, err = order_and_error(q, 2.0)
        assert order == pytest.approx(p) and err == pytest.approx(q[2] - 5.0)
    assert math.isinf(order_and_error([1.0, 2.0, 4.0], 2.0)[1])   # diverging: no estimate


def test_saw_chain_load_max_target_is_met_at_near_the_cheapest_k():
    run = load_paper(Path(__file__).resolve().parents[1] / "config/papers/saw_chain.yaml").runs["load_max_target"]
    ds = run_solver(run)
    requested = float(ds["target_requested"])
    k = float(ds["target_knob_value"])
    # verified against the exact derivative: achieved <= requested
    assert float(ds["target_verified_error"]) <= requested
    # the cheapest K on a fine sample that meets it (the difference method's cost is linear in K)
    errors = {}
    for kk in np.unique(np.geomspace(100, 20000, 60).astype(int)):
        d = run_solver({**run, "target": None, "resolution": {**run["resolution"], "K": int(kk)}})
        errors[int(kk)] = abs(float(d["dynamic_load_x"].max()) - float(d["dynamic_load_x_exact"].max()))
    cheapest = min(kk for kk, e in errors.items() if e <= requested)
    assert k <= 2 * cheapest


def test_extrapolation_meets_a_tight_request_at_a_far_coarser_level():
    """A first-order method q(k) = Q + C/k + D/k^2 (the difference method's shape): asked for
    1e-6, the plain value needs k ~ C / 1e-6, the extrapolated one a few hundred, and its
    error estimate (two successive extrapolations) bounds its true error."""
    import xarray as xr

    from mechrepro.target import solve

    Q, C, D = 10.0, 3.0, 40.0

    def once(run):
        k = run["resolution"]["K"]
        return xr.Dataset({"q": ((), Q + C / k + D / k ** 2)}), float(k)   # cost ~ k

    base = {"run": "t", "resolution": {"K": 8},
            "target": {"quantity": "q", "reduce": "max", "rtol": 1e-6, "knob": "K", "factor": 2}}
    _, plain = solve(base, once)
    _, rich = solve({**base, "target": {**base["target"], "extrapolate": True}}, once)
    assert abs(plain["value"] - Q) <= 1e-6 * Q and abs(rich["value"] - Q) <= 1e-6 * Q
    assert abs(rich["value"] - Q) <= rich["estimated_error"]
    assert rich["knob_value"] * 10 < plain["knob_value"]
    assert rich["seconds_chosen"] * 10 < plain["seconds_chosen"]


@pytest.mark.parametrize("p, a, b, rtol", [
    (1, 3.0, 40.0, 1e-5),     # the difference method's shape, same-signed terms
    (1, 3.0, -40.0, 1e-5),    # terms of opposite sign: the extrapolations converge late
    (1, -3.0, 5.0, 1e-4),     # ... and cross zero on the way
    (2, 3.0, -40.0, 1e-6),    # a second-order method
])
def test_extrapolated_target_is_met_near_the_cheapest_extrapolation_of_an_exact_sequence(
        p, a, b, rtol):
    """q(h) = q* + a h^p + b h^(p+1), h = 1/K, cost ~ K: the delivered extrapolation is within
    the request and within its own estimate, and its finest level K costs at most twice the
    cheapest sampled extrapolation (K/4, K/2, K) from which on every one meets the request.
    Trusting the extrapolations' observed order above p + 1 (5.3 for p = 1, b = -40: not yet
    asymptotic) gives an estimate 8x too small and an error 8x the request."""
    import xarray as xr

    from mechrepro.target import solve

    Q = 10.0

    def f(k):
        return Q + a / k ** p + b / k ** (p + 1)

    def once(run):
        k = run["resolution"]["K"]
        return xr.Dataset({"q": ((), f(k))}), float(k)

    _, rec = solve({"run": "t", "resolution": {"K": 8},
                    "target": {"quantity": "q", "reduce": "max", "rtol": rtol, "knob": "K",
                               "factor": 2, "extrapolate": True}}, once)
    achieved = abs(rec["value"] - Q)
    assert achieved <= rec["estimated_error"] <= rec["requested"]

    def extrapolated_error(k):
        q = [f(k / 4), f(k / 2), f(k)]
        d1, d2 = abs(q[0] - q[1]), abs(q[1] - q[2])
        if not 0 < d2 < d1:
            return math.inf
        s = math.log(d1 / d2) / math.log(2)
        return abs(q[2] + (q[2] - q[1]) / (2 ** s - 1) - Q)

    sample = np.arange(32, 16385, 4)
    ok = [extrapolated_error(k) <= rec["requested"] for k in sample]
    assert ok[-1]
    cheapest = sample[len(ok) - ok[::-1].index(False)] if False in ok else sample[0]
    assert rec["knob_value"] <= 2 * cheapest, (rec["knob_value"], cheapest)


def _plain(p, a, b, rtol, k0=8):
    import xarray as xr

    from mechrepro.target import solve

    def once(run):
        k = run["resolution"]["K"]
        return xr.Dataset({"q": ((), 10.0 + a / k ** p + b / k ** (p + 1))}), float(k)

    return solve({"run": "t", "resolution": {"K": k0},
                  "target": {"quantity": "q", "reduce": "max", "rtol": rtol, "knob": "K",
                             "factor": 2}}, once)[1]


@pytest.mark.parametrize("p, a, b, rtol", [(1, 3.0, 40.0, 1e-4), (2, 3.0, 40.0, 1e-6),
                                           (1, -3.0, 5.0, 1e-4), (1, 1.0, -2.0, 1e-3),
                                           (2, 1.0, -3.0, 1e-4)])
def test_plain_target_is_met_and_a_coarser_levels_estimate_bounds_its_error(p, a, b, rtol):
    """q(h) = q* + a h^p + b h^(p+1), h = 1/K, q* = 10.  A coarser sampled level's estimate
    (the scene's default, level 0) is its distance to the finest plus the finest's Richardson
    estimate, so it holds to within the finest's own estimate (1 %); scaling the finest's
    estimate back by the power law fitted on the finest levels gave 0.41 (p = 1) and 0.065
    (p = 2) for same-signed terms whose true errors are 1.0 and 0.125."""
    rec = _plain(p, a, b, rtol)
    assert rec["default_estimated_error"] >= 0.99 * abs(rec["values"][0] - 10.0)
    assert abs(rec["value"] - 10.0) <= rec["requested"]


@pytest.mark.xfail(strict=True, reason="known limit of the plain branch: the order observed on "
                   "three levels not yet asymptotic is trusted, and the setting it predicts is "
                   "delivered on that prediction, unmeasured")
@pytest.mark.parametrize("p, a, b, rtol", [
    (2, 3.0, -40.0, 1e-6),   # observed order 7.1 on K = 8, 16, 32: delivers K = 32 at 1.7e-3 (request 1e-5)
    (1, 3.0, -40.0, 1e-4),   # delivers the prediction K = 44 at 4.8e-2 (request 1e-3)
])
def test_plain_target_from_pre_asymptotic_levels(p, a, b, rtol):
    """Taking the predicted level only if its own Richardson estimate from the measured level
    meets the request fixes the second case, but on joint_wear's erratic wear factor it
    rejects K = 215 (true error 0.093 of 0.33) for 256 (0.25), above twice the cheapest
    sampled setting (124; tests/test_accuracy_targets.py): not done, left to a decision."""
    rec = _plain(p, a, b, rtol)
    assert abs(rec["value"] - 10.0) <= rec["requested"]


def test_a_one_off_cost_of_the_first_call_is_no_levels_time():
    """The first call of a process pays one-off costs (joint_wear: a numba compile, 43 s
    billed to a 16-step period): one untimed call before the levels; the values are the same."""
    import xarray as xr

    from mechrepro.target import solve

    calls = []

    def once(run):
        k = run["resolution"]["K"]
        calls.append(k)
        return xr.Dataset({"q": ((), 10.0 + 1.0 / k)}), (100.0 if len(calls) == 1 else 1.0)

    _, rec = solve({"run": "t", "resolution": {"K": 8},
                    "target": {"quantity": "q", "reduce": "max", "rtol": 1e-3, "knob": "K",
                               "factor": 2}}, once)
    assert calls[0] == 8 and rec["default_seconds"] == 1.0 and set(rec["seconds"]) == {1.0}
