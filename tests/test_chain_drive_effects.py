"""chain_drive's effect protocol: every solver evaluates exactly the effects its scene names,
every effect changes what a scene built to show it computes, and an effect a solver cannot
honour is refused when the config is loaded."""
from __future__ import annotations

import copy
from functools import lru_cache
from pathlib import Path

import numpy as np
import pytest
import yaml

from mechrepro.config import ConfigError, load_paper
from mechrepro.models.chain_drive import EFFECTS
from mechrepro.solve import solve
from mechrepro.models.chain_drive.solver import SOLVERS
from mechrepro.inputs import read_yaml

CFG = Path(__file__).resolve().parents[1] / "config" / "papers" / "chain_drive.yaml"
FD_SMALL = {"points_per_pitch": 2, "n_speeds": 2, "decay_times": 0.3, "window_periods": 1,
            "orders": 2}
# two speeds around the first resonance of the 20-pitch span (~125 rpm), where the interior
# of the span moves more than its ends
FD_SHOW = dict(FD_SMALL, decay_times=1, window_periods=2)
NEAR_FIRST = {"speed_min": 12.5, "speed_max": 13.5}   # rad/s
# equal sprockets at a whole number of pitches turn at equal speeds: no polygonal load
FRACTIONAL = dict(NEAR_FIRST, centre_distance=20.25)
GALERKIN_SMALL = {"n_transverse": 2, "n_longitudinal": 1, "duration": 0.002, "samples": 20,
                  "library_periods": 1}

# one small scene per solver: (scene, resolution overrides, parameter overrides)
SMALL = {
    "impact_load": ("fig01_impact", {"samples": 50}, {}),
    "rigid_four_bar": ("fig03", {"samples": 50}, {}),
    "elastic_four_bar": ("fig04_elastic", {"samples": 20, "n_speeds": 5}, {}),
    "speed_sweep": ("fig08_external", FD_SMALL, NEAR_FIRST),
    "galerkin": ("rk4_check_coupled", GALERKIN_SMALL, {}),
    "impact_timestep": ("impact_timestep", {"points_per_pitch": 2, "tooth_periods": 0.5,
                                            "refine": 2}, {}),
    "exact_free": ("exact_free", {"points": [10, 20], "periods": 1}, {}),
    "manufactured": ("manufactured", {"points": [10, 20]}, {}),
}


@lru_cache(maxsize=1)
def _cfg():
    return load_paper(CFG, "ci")


def _declared():
    return read_yaml(CFG)["effects"]


def _run(scene, resolution, effects=None, parameters=None):
    run = copy.deepcopy(_cfg().runs[scene])
    run["resolution"].update(resolution)
    run["parameters"].update(parameters or {})
    if effects is not None:
        run["effects"] = list(effects)
    run["contributes"] = {e: _declared()[e]["contributes"] for e in run["effects"]}
    return run


def test_every_solver_has_a_small_scene():
    assert set(SMALL) == set(read_yaml(CFG)["solvers"]) == set(SOLVERS)
    for solver, (scene, _, _) in SMALL.items():
        assert _cfg().runs[scene]["solver"] == solver


@pytest.mark.parametrize("solver", sorted(SMALL))
def test_an_effect_the_scene_does_not_name_is_never_evaluated(solver, monkeypatch):
    scene, res, prm = SMALL[solver]
    run = _run(scene, res, parameters=prm)
    called = []

    def named(name, fn):
        def wrapped(ctx):
            called.append(name)
            return fn(ctx)
        return wrapped

    def boom(name):
        def fn(ctx):
            raise AssertionError(f"{solver}: effect {name} evaluated although not named")
        return fn

    swapped = {name: named(name, fn) if name in run["effects"] else boom(name)
               for name, fn in EFFECTS._fn.items()}
    monkeypatch.setattr(EFFECTS, "_fn", swapped)
    solve(run)
    assert set(called) == set(run["effects"])


# effect -> (scene, base effects, the effect added; resolution, parameters, output compared)
SHOW = {
    "speed_tensioning": ("fig05_plain", ["end_excitation"], FD_SHOW, NEAR_FIRST, "amplitude"),
    "impact": ("fig05_plain", ["speed_tensioning", "end_excitation"], FD_SHOW, NEAR_FIRST,
               "amplitude"),
    "polygonal_rigid": ("fig05_plain", ["speed_tensioning", "end_excitation"], FD_SHOW, FRACTIONAL,
                        "amplitude"),
    "polygonal_elastic": ("fig05_plain", ["speed_tensioning", "end_excitation"], FD_SHOW,
                          NEAR_FIRST, "amplitude"),
    "external_load": ("fig05_plain", ["speed_tensioning", "end_excitation"], FD_SHOW,
                      dict(NEAR_FIRST, external_load_ratio=0.2), "amplitude"),
    # the static_external_load rival's effect: a constant pre-load moves the resonances
    "external_load_static": ("fig05_plain", ["speed_tensioning", "end_excitation"], FD_SHOW,
                             dict(NEAR_FIRST, external_load_ratio=0.2), "amplitude"),
    "end_excitation": ("fig05_plain", ["speed_tensioning", "polygonal_rigid"], FD_SHOW, FRACTIONAL,
                       "amplitude"),
    "end_excitation_distributed": ("fig05_plain", ["speed_tensioning", "polygonal_rigid"], FD_SHOW,
                                   FRACTIONAL, "amplitude"),
    "length_change": ("fig05_plain", ["speed_tensioning", "polygonal_rigid", "end_excitation"],
                      FD_SHOW, FRACTIONAL, "amplitude"),
    # without end motion the span stays straight: only the sag load kappa P_t moves it
    "sag": ("fig05_plain", ["speed_tensioning", "polygonal_rigid"], FD_SHOW, FRACTIONAL,
            "amplitude"),
    "longitudinal_coupling": ("fig10_transverse5_uncoupled",
                              ["speed_tensioning", "impact", "polygonal_rigid", "end_excitation"],
                              dict(GALERKIN_SMALL, duration=0.01), {}, "u_probe_rk4"),
}


def test_every_effect_has_a_scene_that_shows_it():
    assert set(SHOW) == set(EFFECTS.names)


@pytest.mark.parametrize("effect", sorted(SHOW))
def test_switching_an_effect_on_changes_the_output(effect):
    scene, base, res, prm, out = SHOW[effect]
    off = solve(_run(scene, res, base, prm))[out].values
    on = solve(_run(scene, res, base + [effect], prm))[out].values
    assert off.shape == on.shape and np.all(np.isfinite(on))
    assert not np.allclose(on, off, rtol=1e-6, atol=0), f"{effect} changes nothing"


def test_the_timestep_comparison_takes_speed_tensioning_only_when_named():
    """timestep.py once added lambda m c^2 to the step limit whether or not it was named."""
    scene, res, _ = SMALL["impact_timestep"]
    off = solve(_run(scene, res, ["impact", "sag"]))
    on = solve(_run(scene, res, ["impact", "sag", "speed_tensioning"]))
    assert float(on.dt_max) < float(off.dt_max)


def _bad(mutate, tmp_path):
    raw = read_yaml(CFG)
    mutate(raw)
    d = tmp_path / "config"
    (d / "papers").mkdir(parents=True)
    (d / "schema").mkdir()
    for f in (CFG.parents[1] / "schema").glob("*.yaml"):
        (d / "schema" / f.name).write_text(f.read_text())
    (d / "papers" / "chain_drive.yaml").write_text(yaml.safe_dump(raw, sort_keys=False))
    return d / "papers" / "chain_drive.yaml"


@pytest.mark.parametrize("effect", ["sag", "length_change"])
def test_the_galerkin_model_refuses_what_it_cannot_honour(effect, tmp_path):
    path = _bad(lambda r: r["scenes"]["fig10_longitudinal"]["effects"].append(effect), tmp_path)
    with pytest.raises(ConfigError, match=f"effect '{effect}' is not honoured by solver 'galerkin'"):
        load_paper(path)


def test_rigid_and_elastic_polygonal_action_exclude_each_other(tmp_path):
    path = _bad(lambda r: r["scenes"]["fig09a"]["effects"].append("polygonal_rigid"), tmp_path)
    with pytest.raises(ConfigError, match="excludes"):
        load_paper(path)


# what each solver reads before its time grid exists: evaluated once per solve
STEADY = {"speed_tensioning", "longitudinal_coupling"}


@pytest.mark.parametrize("solver", ["speed_sweep", "galerkin", "impact_timestep"])
def test_steady_effects_are_evaluated_once_and_selected_by_declared_keys(solver, monkeypatch):
    """No probe: the tension coefficient (and Galerkin's coupling) are evaluated once per
    solve, by the keys they declare; the FD sweep evaluates end motion, sag and the
    span-length state once, on its final grid, and the dynamic tension once per pass of the
    step refinement; Galerkin every effect once (the RK4 stages, the recorded steps and the
    library check's nodes in one call)."""
    scene, res, prm = SMALL[solver]
    run = _run(scene, res, parameters=prm)
    calls: dict = {}

    def counted(name, fn):
        def wrapped(ctx):
            calls[name] = calls.get(name, 0) + 1
            return fn(ctx)
        return wrapped

    monkeypatch.setattr(EFFECTS, "_fn", {n: counted(n, f) for n, f in EFFECTS._fn.items()})
    solve(run)
    assert set(calls) == set(run["effects"])
    for name in STEADY & set(run["effects"]):
        assert calls[name] == 1, (name, calls)
    if solver == "speed_sweep":
        forcing = {"end_excitation", "sag", "length_change"} & set(run["effects"])
        assert forcing and all(calls[e] == 1 for e in forcing), calls
    if solver == "galerkin":
        assert run["options"].get("compare_library") and set(calls.values()) == {1}, calls
