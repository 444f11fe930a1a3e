"""saw_chain: error budget of the difference method, its round-off limit, and hard cases."""
import math
from dataclasses import replace

import numpy as np
import pytest

from mechrepro.solve import solve
from mechrepro.models.saw_chain.analysis import (equivalent_K, error_model_optimum, load_extreme_at,
                                                 observed_order, pitch_radius_readings,
                                                 textbook_constants_for_range, velocity_band)
from mechrepro.models.saw_chain.difference import RoundoffError
from mechrepro.models.saw_chain.effects import Context, exact_reference
from mechrepro.models.saw_chain.kinematics import stage_derivatives, stage_jerks
from mechrepro.models.saw_chain.solver import chain_from_run, stage_switch_index
from mechrepro.models.saw_chain.loads import textbook_velocity_load

from test_saw_chain import P, difference_method_loop, run

WITH_EXACT = ["exact_reference"]


def allowed(K, **over):
    r = run(K=K, outputs=WITH_EXACT, **over)
    r["options"] = {"beyond_roundoff_limit": True, "timing_min_s": 0.0}
    return r


def test_exact_jerk_matches_finite_differences_of_exact_acceleration():
    R, L, w = 0.0211, 0.00756, 686.0
    phi, h = np.linspace(0.01, 0.35, 7), 1e-6
    d = lambda ph: stage_derivatives(ph, R, L, w)  # noqa: E731
    j = stage_jerks(phi, R, L, w)
    for a, jk in (("trail_ax", "trail_jx"), ("mid_ax", "mid_jx"), ("mid_ay", "mid_jy")):
        fd = (d(phi + h)[a] - d(phi - h)[a]) / (2 * h) * w
        np.testing.assert_allclose(j[jk], fd, rtol=1e-6)


def test_leading_error_is_minus_dt_times_the_load_jerk():
    """a^i = a(t_i) - dt a'(t_i) + O(dt^2): the method is first order, with a known constant."""
    chain = chain_from_run(run(K=1))
    errs = []
    for K in (250, 1000):  # round-off stays far below the O(dt^2) remainder
        ds = solve(run(K=K, outputs=WITH_EXACT))
        F, Fe = ds["dynamic_load_x"].values, ds["dynamic_load_x_exact"].values
        dt = chain.stage_times()[1] / K
        # stage 2 interior samples, away from the switch: compare with -dt dF/dt
        i = np.arange(K + 3, 2 * K + 1)
        L, m_link, _ = chain.stages()[1]
        phi = (ds["t"].values[i] - ds["t"].values[K]) * chain.omega
        j = stage_jerks(phi, chain.R, L, chain.omega)
        dFdt = m_link * j["mid_jx"] + chain.m_tight * j["trail_jx"]
        errs.append(np.max(np.abs((F[i] - Fe[i]) + dt * dFdt)) / np.max(np.abs(dt * dFdt)))
    # the remainder is O(dt^2): relative to the leading term it falls like 1/K
    assert errs[0] < 1e-2 and errs[1] < errs[0] / 3


def test_stage_switch_sample_does_not_converge_and_is_reported_apart():
    vals = []
    for K in (100, 1000, 10000):
        ds = solve(run(K=K, outputs=WITH_EXACT))
        s = stage_switch_index(K)
        F, Fe = ds["dynamic_load_x"].values, ds["dynamic_load_x_exact"].values
        assert float(ds["dynamic_load_x_switch"]) == F[s]
        # it straddles the jump at t1: between the one-sided exact values, far from both
        assert Fe[s] + 50 < F[s] < Fe[K] - 50
        assert float(ds["dynamic_load_x_error_switch"]) > 0.3
        # excluded from the pointwise error, which converges
        assert float(ds["dynamic_load_x_error_pointwise"]) < 5.0 / K
        vals.append(F[s])
    assert max(vals) - min(vals) < 0.03 * abs(vals[-1])


def test_refusal_threshold_sits_at_the_measured_optimum():
    """The solver's a-priori limit agrees with where the measured pointwise error is smallest."""
    limit = chain_from_run(run(K=1)).roundoff_limit()
    Ks = np.unique(np.geomspace(limit / 4, limit * 4, 9).astype(int))
    err = np.array([float(solve(allowed(int(K)))["dynamic_load_x_error_pointwise"]) for K in Ks])
    best = Ks[np.argmin(err)]
    assert limit / 2 <= best <= 2 * limit
    at_limit = float(solve(allowed(limit))["dynamic_load_x_error_pointwise"])
    assert at_limit <= 1.5 * err.min()
    # the fitted optimum of the study's error model agrees too
    K_opt, e_opt, *_ = error_model_optimum(Ks, err)
    assert limit / 2 <= K_opt <= 2 * limit and e_opt <= 1.5 * err.min()


def test_hard_case_K_at_the_refusal_edge():
    limit = chain_from_run(run(K=1)).roundoff_limit()
    ds = solve(run(K=limit, outputs=WITH_EXACT))
    assert int(ds["roundoff_dominated"]) == 0
    assert float(ds["dynamic_load_x_error_pointwise"]) < 1e-3
    with pytest.raises(RoundoffError, match=rf"K = {limit + 1}: .*allowed: K <= {limit}"):
        solve(run(K=limit + 1, outputs=[]))
    # the exact reference has no such limit
    chain = chain_from_run(run(K=10 * limit))
    exact = exact_reference(Context(chain, chain.time()))["dynamic_load_x_exact"][1]
    assert np.all(np.isfinite(exact))


def test_hard_case_roundoff_floor_is_bounded_and_flagged():
    """Far beyond the limit (allowed for the study): finite, flagged, within the error budget."""
    ds = solve(allowed(1_000_000))
    assert int(ds["roundoff_dominated"]) == 1
    F, Fe = ds["dynamic_load_x"].values, ds["dynamic_load_x_exact"].values
    assert np.all(np.isfinite(F))
    keep = np.arange(F.size) != stage_switch_index(1_000_000)
    budget = float(ds["truncation_load_estimate"]) + float(ds["roundoff_load_bound"])
    assert np.max(np.abs(F - Fe)[keep]) <= budget
    # and round-off, not truncation, is what the error is made of
    assert float(ds["roundoff_load_bound"]) > 10 * float(ds["truncation_load_estimate"])
    assert float(ds["dynamic_load_x_error_pointwise"]) > 10 * float(
        solve(allowed(chain_from_run(run(K=1)).roundoff_limit()))["dynamic_load_x_error_pointwise"])


@pytest.mark.parametrize("p1,p2", [(20e-3, 4e-3), (4e-3, 20e-3)])
def test_hard_case_three_teeth_very_unequal_stages(p1, p2):
    """z = 3 with pitches 5:1: one stage is several times longer than the other."""
    over = dict(teeth=3, tie_strap_pitch=p1, drive_link_pitch=p2)
    chain = chain_from_run(run(K=1, **over))
    T1, T2 = chain.stage_times()
    assert max(T1, T2) / min(T1, T2) > 3
    assert (T1 + T2) * chain.omega == pytest.approx(2 * math.pi / 3, rel=1e-14)
    errs = []
    for K in (300, 3000):
        ds = solve(run(K=K, outputs=WITH_EXACT, **over))
        v = ds["tight_side_velocity_exact"].values
        assert v.max() == pytest.approx(chain.R * chain.omega, rel=1e-12)
        assert np.all(np.isfinite(ds["dynamic_load_x"].values))
        errs.append(float(ds["dynamic_load_x_error_pointwise"]))
    assert math.log(errs[0] / errs[1]) / math.log(10) == pytest.approx(1.0, abs=0.05)
    v_loop, F_loop = difference_method_loop(p1, p2, 3, chain.omega, chain.m_L, chain.m_C,
                                            chain.M, chain.N, 300)
    ds = solve(run(K=300, outputs=WITH_EXACT, **over))
    np.testing.assert_allclose(ds["dynamic_load_x"].values, F_loop, rtol=0,
                               atol=float(ds["roundoff_load_bound"]))
    # the limit still guards the short stage
    assert chain.roundoff_limit() > 1000


def test_equivalent_K_is_a_root_of_the_solver():
    chain = chain_from_run(run(K=1))
    K, below, at = equivalent_K(chain, 209.4)
    assert below < 209.4 <= at
    assert load_extreme_at(chain, K - 1) == below and load_extreme_at(chain, K) == at
    # monotonic around the root, so the smallest such K is unique
    m = [load_extreme_at(chain, k) for k in range(K - 20, K + 20)]
    assert np.all(np.diff(m) > 0)
    assert equivalent_K(chain, 1e6)[0] is None


def test_velocity_band_of_eq1_radius_equals_the_solvers_exact_band():
    chain = chain_from_run(run(K=1))
    R = pitch_radius_readings(chain.p1, chain.p2, chain.z)["eq1"]
    assert R == pytest.approx(chain.R, rel=1e-15)
    lo, hi = velocity_band(chain.p1, chain.p2, chain.omega, R)
    v = solve(run(K=20000, outputs=["exact_reference"]))["tight_side_velocity_exact"].values
    assert lo == pytest.approx(v.min(), rel=1e-9) and hi == pytest.approx(v.max(), rel=1e-12)
    assert lo <= v.min()


def test_textbook_constants_round_trip():
    chain = chain_from_run(run(K=1))
    theta, m = textbook_constants_for_range(-463.2, -33.4, chain.R, chain.omega, chain.z)
    t = np.linspace(0, 2 * math.pi / chain.z / chain.omega, 2001)
    _, _, F = textbook_velocity_load(t, chain.R, chain.omega, theta, m)
    assert F.min() == pytest.approx(-463.2, rel=1e-9) and F.max() == pytest.approx(-33.4, rel=1e-9)


def test_observed_order_uses_only_truncation_dominated_runs():
    K = np.array([10, 100, 1000, 1e4, 1e5])
    err = 1.0 / K + 1e-12 * K**2
    trunc, roff = 1.0 / K, 1e-12 * K**2
    p, local, pair = observed_order(K, err, trunc, roff)
    assert pair == (100, 1000) and p == pytest.approx(1.0, abs=1e-3)


#: the six chains of issue 30: the paper's, z = 3 with 5:1 pitches both ways, z = 40,
#: equal pitches, and M = N = 2 (a light tight side)
SIX_CHAINS = {"paper": {}, "z3_tie_strap_5x": dict(teeth=3, tie_strap_pitch=20e-3, drive_link_pitch=4e-3),
              "z3_drive_link_5x": dict(teeth=3, tie_strap_pitch=4e-3, drive_link_pitch=20e-3),
              "z40": dict(teeth=40), "equal_pitches": dict(drive_link_pitch=8.91e-3),
              "M_N_2": dict(tie_straps_tight_side=2, drive_links_tight_side=2)}


@pytest.mark.parametrize("name", SIX_CHAINS)
def test_error_model_optimum_is_well_conditioned_on_six_chains(name):
    """Scaled columns: the fitted optimum sits at the measured one on every chain.

    Measured (15 K from limit/100 to 30 limit): K* / limit / best sampled K =
    3.97e4/39434/38264 (paper), 7.19e4/73833/71643 and 6.59e4/66065/64105 (z = 3, 5:1 both
    ways; the unscaled fit gave 5e-6), 1.34e4/9284/15959 (z = 40), 3.89e4/40347/39150 (equal),
    3.83e4/37319/36212 (M = N = 2)."""
    over = SIX_CHAINS[name]
    limit = chain_from_run(run(K=1, **over)).roundoff_limit()
    Ks = np.unique(np.geomspace(limit / 30, limit * 10, 9).astype(int))
    err = []
    for K in Ks:
        r = allowed(int(K), **over)
        r["options"]["keep_history"] = False
        err.append(float(solve(r)["dynamic_load_x_error_pointwise"]))
    err = np.array(err)
    opt = error_model_optimum(Ks, err)
    assert opt.reason == ""
    best = Ks[np.argmin(err)]
    assert best / 2 <= opt.K_opt <= 2 * best and limit / 2 <= opt.K_opt <= 2 * limit
    # the model adds both branches at K*, where the measured errors partly cancel
    assert opt.err_opt <= 2 * err.min()


def test_error_model_optimum_names_why_it_has_no_optimum():
    K = np.array([10.0, 100, 1000, 1e4])
    assert "rank-deficient" in error_model_optimum([100, 100], [1e-2, 1e-2]).reason
    assert math.isnan(error_model_optimum([100, 100], [1e-2, 1e-2]).K_opt)
    trunc_only = error_model_optimum(K, 1.0 / K)       # a study that stops below the limit
    assert math.isnan(trunc_only.K_opt) and "round-off" in trunc_only.reason
    roff_only = error_model_optimum(K, 1e-12 * K**2)
    assert math.isnan(roff_only.K_opt) and "truncation" in roff_only.reason
    # exact model data over 11 decades of column scale: recovered to round-off
    K = np.geomspace(3, 1e6, 12)
    opt = error_model_optimum(K, 0.5 / K + 3e-14 * K**2)
    assert opt.a == pytest.approx(0.5, rel=1e-9) and opt.b == pytest.approx(3e-14, rel=1e-9)


def test_velocity_only_run_is_not_refused_at_the_load_limit():
    """The refusal guards the quantities that suffer round-off: a velocity-only run beyond the
    loads' limit is accepted, equals the full method's velocity, and is refused only at its own."""
    chain = chain_from_run(run(K=1))
    limit, v_limit = chain.roundoff_limit(), chain.velocity_roundoff_limit()
    assert v_limit > 100 * limit
    K = 4 * limit
    r = run(K=K, outputs=WITH_EXACT)
    r["options"] = {"loads": False}
    ds = solve(r)
    assert "dynamic_load_x" not in ds and int(ds["roundoff_dominated"]) == 0
    full = solve(allowed(K))
    np.testing.assert_array_equal(ds["tight_side_velocity"].values, full["tight_side_velocity"].values)
    assert float(ds["tight_side_velocity_error_pointwise"]) < 1e-4
    with pytest.raises(RoundoffError, match="velocities"):
        solve(run(K=v_limit + 1, outputs=[], **{}) | {"options": {"loads": False}})


def test_stage_switch_sample_tends_to_the_step_weighted_value():
    """stage_switch_index's docstring: (F(t1+) + (dt1/dt2)(m_L + m_tight) a_O2(t1-)) / 2."""
    chain = chain_from_run(run(K=1))
    (L1, _, _), (L2, m2, _) = chain.stages()
    phi1, _ = chain.phases
    minus = stage_derivatives(np.float64(phi1), chain.R, L1, chain.omega)
    plus = stage_derivatives(np.float64(0.0), chain.R, L2, chain.omega)
    T1, T2 = chain.stage_times()
    F_plus = m2 * plus["mid_ax"] + chain.m_tight * plus["trail_ax"]
    limit = (F_plus + T1 / T2 * (m2 + chain.m_tight) * minus["trail_ax"]) / 2
    assert limit == pytest.approx(79.87, abs=0.01)
    ds = solve(run(K=30000, outputs=WITH_EXACT))
    assert float(ds["dynamic_load_x_switch"]) == pytest.approx(limit, rel=1e-3)


def _velocity_only_scene(K):
    """An edit of saw_chain's config: a scene of the velocity alone (``loads: false``) at K."""
    def edit(raw):
        raw["scenes"]["velocity_only"] = {
            "description": "the tight-side velocity alone (issue 63)", "solver": "difference_method",
            "outputs": ["exact_reference"], "resolution": {"K": K},
            "options": {"loads": False, "keep_history": False}}
    return edit


def test_velocity_only_run_beyond_the_load_limit_is_accepted_at_load(edit_config):
    """Issue 63: the loader refused a velocity-only scene at the loads' limit (K = 1e5 at
    39,434) although the solver, the run schema and docs/saw_chain.md accept it; the loader
    (config load + mechrepro.limits.check_all) now applies the velocity's own limit, and the
    run it built is solved as loaded."""
    from mechrepro import limits
    from mechrepro.config import load_paper

    chain = chain_from_run(run(K=1))
    limit, v_limit = chain.roundoff_limit(), chain.velocity_roundoff_limit()
    K = 100_000
    assert limit < K < v_limit
    cfg = load_paper(edit_config("saw_chain", _velocity_only_scene(K)), "ci")
    limits.check_all({"saw_chain": cfg})                 # not refused at load
    assert limits.refusals(cfg) == []
    ds = solve(cfg.runs["velocity_only"])                # and the solver takes it as loaded
    assert "dynamic_load_x_max" not in ds and int(ds["roundoff_dominated"]) == 0
    assert float(ds["tight_side_velocity_error_pointwise"]) < 1e-4
    # beyond the velocity's own limit it is refused at load, naming that limit
    cfg = load_paper(edit_config("saw_chain", _velocity_only_scene(v_limit + 1)), "ci")
    with pytest.raises(limits.LimitError) as err:
        limits.check_all({"saw_chain": cfg}, allow_over_budget=True)
    msg = str(err.value)
    assert "scene velocity_only" in msg and f"K <= {v_limit}" in msg and "velocit" in msg, msg
