"""joint_wear effect protocol: every solver runs with only the effects its scene names (the
others raise), every effect changes the output of a scene built to show it, and the
combinations that make no sense are refused when the config is loaded."""
from __future__ import annotations

import numpy as np
import pytest
import yaml

from mechrepro.config import ConfigError, load_paper
from mechrepro.models.joint_wear import EFFECTS, SOLVERS, dynamics
from mechrepro.solve import solve

from conftest import ROOT
from mechrepro.inputs import read_yaml

CFG = load_paper(ROOT / "config/papers/joint_wear.yaml")

# a small scene of every solver: (scene, resolution, options)
SMALL = {
    "clearance_implicit": ("period_dynamic", {"n_out": 64}, {}),
    "clearance_explicit": ("period_explicit", {"max_steps": 100, "n_out": 64}, {}),
    "continuous_contact": ("wear_prediction", {"n_steps": 64, "interval_h": 16}, {}),
    "period_by_period": ("timing_period_by_period", {"n_steps": 32}, {"period_by_period_sample": 3}),
    "coefficient_scan": ("coefficient_scan", {"n_steps": 32},
                         {"scan_load_direction_deg": [0, 180], "scan_gravity": [9.8]}),
    "load_point_fit": ("load_point_fit", {"n_steps": 64, "interval_h": 38},
                       {"fit_load_direction_deg": [120, 130, 140], "fit_gravity": [9.8],
                        "fit_secant_steps": 0}),
    "constant_sensitivity": ("constant_sensitivity", {"n_steps": 64, "interval_h": 38},
                             {"sensitivity": {"friction_coefficient": [0.05, 0.5]}}),
    "local_wear": ("local_wear", {"n_steps": 64, "interval_h": 38, "n_theta": 64}, {}),
    "load_point_posterior": ("load_point_posterior",
                             {"n_steps": 64, "n_out": 64, "periods": 1, "n_gravity": 1, "edge_bisections": 1},
                             {"fit_load_direction_deg": [120, 130, 140], "fit_secant_steps": 0,
                              "posterior_distance": [0.65], "posterior_friction": [0.15811]}),
}


def small(solver: str, effects=None) -> dict:
    scene, res, opt = SMALL[solver]
    run = dict(CFG.runs[scene])
    assert run["solver"] == solver
    run["resolution"] = dict(run["resolution"], **res)
    run["options"] = dict(run["options"], **opt)
    if effects is not None:
        run["effects"] = list(effects)
    return run


def test_every_solver_has_a_small_scene():
    assert set(SMALL) == set(SOLVERS) == set(read_yaml(
        (ROOT / "config/papers/joint_wear.yaml"))["solvers"])


@pytest.mark.parametrize("solver", list(SMALL))
def test_effects_not_named_are_never_evaluated(solver, monkeypatch):
    run = small(solver)

    def boom(*a, **k):
        raise AssertionError("evaluated an effect the scene did not name")
    for name in EFFECTS.names:
        if name not in run["effects"]:
            monkeypatch.setitem(EFFECTS._fn, name, boom)
    if solver not in ("clearance_implicit", "clearance_explicit", "constant_sensitivity",
                      "load_point_posterior"):
        monkeypatch.setattr(dynamics, "simulate", boom)   # no stiff dynamics either
    ds = solve(run)
    assert ds.attrs["solver"] == solver


def _without(solver, effect):
    run = small(solver)
    return solve(run), solve(small(solver, [e for e in run["effects"] if e != effect]))


def test_gravity_turns_the_contact_point():
    on, off = _without("continuous_contact", "gravity")
    # without the link weights the coupler is a two-force member: the arc collapses
    assert float(off["contact_arc_angle"]) < 0.1 * float(on["contact_arc_angle"])


def test_friction_adds_a_friction_force():
    on, off = _without("continuous_contact", "friction")
    assert float(np.abs(off["F_T"]).max()) == 0.0
    assert float(np.abs(on["F_T"]).max()) > 0.05 * float(on["F_N_mean"])


def test_contact_damping_changes_the_dynamic_contact_force():
    on, off = _without("clearance_implicit", "contact_damping")
    d = np.abs(on["F_N"].values - off["F_N"].values).max()
    assert d > 0.0 and float(on["min_penetration"]) > 0.0 and float(off["min_penetration"]) > 0.0


def test_archard_wear_predicts_the_wear():
    run = small("continuous_contact")
    on = solve(run)
    off = solve(small("continuous_contact", ["friction", "gravity"]))
    assert "wear_predicted" in on and "wear_predicted" not in off
    assert float(on["wear_at_end_B1"]) > float(on["wear_calibration_replay"].sel(side="B1")[-1])


def test_unbalanced_load_adds_side_b2():
    on, off = _without("continuous_contact", "unbalanced_load")
    assert list(on["side"].values) == ["B1", "B2"] and list(off["side"].values) == ["B1"]
    assert float(on["wear_at_end_B1"]) > float(on["wear_at_end_B2"])


def test_wear_update_grows_the_bushing_between_intervals():
    on, off = _without("continuous_contact", "wear_update")
    G_on = on["wear_factor_prediction"].sel(side="B1").values[:-1]
    G_off = off["wear_factor_prediction"].sel(side="B1").values[:-1]
    assert np.all(G_off == G_off[0]) and not np.all(G_on == G_on[0])
    assert float(on["wear_at_end_B1"]) != float(off["wear_at_end_B1"])


@pytest.mark.parametrize("scene, effects, message", [
    ("period_quasistatic", ["friction", "gravity", "contact_damping"],
     "'contact_damping' is not honoured by solver 'continuous_contact'"),
    ("period_explicit", ["friction", "gravity", "archard_wear"],
     "'archard_wear' is not honoured by solver 'clearance_explicit'"),
    ("coefficient_scan", ["friction", "gravity", "contact_damping"], "'contact_damping' is not honoured by solver 'coefficient_scan'"),
    ("period_quasistatic", ["friction", "gravity", "wear_update"], "'wear_update' requires"),
    ("period_quasistatic", ["friction", "gravity", "unbalanced_load"], "'unbalanced_load' requires"),
])
def test_meaningless_combinations_are_refused_at_load(config_copy, scene, effects, message):
    path = config_copy / "papers" / "joint_wear.yaml"
    raw = read_yaml(path)
    raw["scenes"][scene]["effects"] = effects
    path.write_text(yaml.safe_dump(raw))
    with pytest.raises(ConfigError, match=message):
        load_paper(path)
