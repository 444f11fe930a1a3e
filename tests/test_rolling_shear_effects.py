"""rolling_shear's effect protocol: each solver runs with every effect and output its scene
does not name replaced by one that raises; each, switched on, changes the output of a scene
built to show it."""
import numpy as np
import pytest

from mechrepro.effects import declared

from mechrepro.models.rolling_shear import EFFECTS, SOLVERS

from mechrepro.solve import solve

from test_rolling_shear_helpers import config, run

PAPER_H = 1.4341  # mm, the calibration target (Sec. 4)


def small(scene, named, **options):
    """A small run of ``scene`` naming ``named`` (effects and outputs, each in its list)."""
    raw = config("ci").raw
    assert set(named) <= set(declared(raw)), named
    r = run(scene, "ci")
    r["effects"] = [e for e in named if e in raw["effects"]]
    r["outputs"] = [o for o in named if o in raw["outputs"]]
    r["contributes"] = {e: declared(raw)[e]["contributes"] for e in named}
    r["resolution"]["calibration_points"] = 17
    r["resolution"]["n_points"] = 5
    r["options"] = {**r.get("options", {}), **options}
    return r


@pytest.fixture
def raising():
    """Solve a run with every effect and output it does not name replaced by one that raises."""
    def boom(ctx):
        raise AssertionError("evaluated an effect or output the scene did not name")

    def solve_raising(r):
        with pytest.MonkeyPatch.context() as mp:
            for name in EFFECTS.names:
                if name not in r["effects"] + r["outputs"]:
                    mp.setitem(EFFECTS._fn, name, boom)
            return solve(r)
    return solve_raising


SMALL_SCENES = {
    "continuation": lambda: small("original", []),
    "method_comparison": lambda: small("solver_comparison", [], methods=["cold_root"]),
    "lever_optimisation": lambda: {**(r := small("optimisation", [], optimisers=["selpso"])),
                                   "resolution": {**r["resolution"], "n_points": 3,
                                                  "opt_swarm": 4, "opt_iter": 2}},
    "family_scan": lambda: small("family", [], grid={
        "blade_offset": [1200], "R": [35000], "width": [3200], "y_joint": [250],
        "eq8_reading": ["rotation"], "carrier_constants": ["frozen"]}),
    "design_front": lambda: {**(r := small("design", [])),
                             "resolution": {**r["resolution"], "front_l6_points": 3,
                                            "front_samples": 4, "front_rounds": 1}},
}


def test_every_solver_has_a_small_scene():
    assert set(SMALL_SCENES) == set(SOLVERS) == set(config("ci").raw["solvers"])


@pytest.mark.parametrize("solver", sorted(SMALL_SCENES))
def test_solver_never_evaluates_an_effect_or_output_the_scene_does_not_name(raising, solver):
    r = SMALL_SCENES[solver]()
    assert r["solver"] == solver
    ds = raising(r)
    assert "geometry_tilt" in ds
    for e in EFFECTS.names:
        assert not set(declared(config("ci").raw)[e]["contributes"]) & set(ds.data_vars), e


def test_constant_rate_drive_lets_the_lowest_point_leave_the_overlap_line(raising):
    off = raising(small("original", []))
    on = raising(small("original", ["constant_rate_drive"]))
    assert "crd_y_k" not in off
    # the reverse-solved drive keeps y_k = -s; the constant-rate drive does not (Fig. 9)
    assert float(on["newton_overlap_max_deviation"]) < 1e-6
    assert float(on["crd_overlap_max_deviation"]) > 1.0
    np.testing.assert_array_equal(on["newton_theta1"], off["newton_theta1"])


def test_tilt_scan_brackets_the_calibrated_tilt(raising):
    off = raising(small("original", []))
    on = raising(small("original", ["tilt_scan"]))
    assert "family_h" not in off
    H, tilt = on["family_h"].values, on["family_tilt"].values
    ok = np.isfinite(H)
    assert np.nanmin(H) < PAPER_H < np.nanmax(H)
    assert tilt[ok].min() < float(on["geometry_tilt"]) < tilt[ok].max()


def test_initial_values_give_the_fig12_histories(raising):
    inits = [[4.2, 4.3, 2.6, 2.5], [0.0, 0.0, 0.0, 0.0]]
    off = raising(small("solver_comparison", [], methods=["cold_root"], initial_values=inits))
    on = raising(small("solver_comparison", ["initial_values"], methods=["cold_root"],
                       initial_values=inits))
    assert "iv_fitness_history" not in off
    assert on["iv_fitness_history"].shape[0] == 2 and bool(on["iv_converged"].all())
    np.testing.assert_array_equal(on["cold_root_theta"], off["cold_root_theta"])


def test_lever_scan_shows_that_only_l6_moves_the_objective(raising):
    def scene(outputs):
        r = small("optimisation", outputs, optimisers=["selpso"])
        r["resolution"].update(n_points=3, opt_swarm=4, opt_iter=2, scan_points=3)
        return r

    off, on = raising(scene([])), raising(scene(["lever_scan"]))
    assert "scan_spread" not in off
    spread = dict(zip(on["lever"].values.tolist(), on["scan_spread"].values))
    assert spread["l6"] > 0.01 and max(spread[k] for k in ("l1", "l3", "l5", "l10")) < 1e-9
    np.testing.assert_array_equal(on["opt_selpso_levers"], off["opt_selpso_levers"])
