"""disk_tension: the effect protocol -- an effect or output not named is never evaluated (for
each solver), every one changes the output of a scene built to show it, and what the effects
and outputs return is what the config declares (its keys), each array with a unit."""
import copy
import re
from pathlib import Path

import numpy as np
import pytest

from mechrepro.config import load_paper
from mechrepro.effects import declared
from mechrepro.models.disk_tension import EFFECTS
from mechrepro.solve import solve
from mechrepro.inputs import read_yaml
from mechrepro.units import UNITS

ROOT = Path(__file__).resolve().parent.parent
CFG = ROOT / "config" / "papers" / "disk_tension.yaml"
RAW = read_yaml(CFG)
DECLARED = declared(RAW)   # effects and outputs, one namespace
SMALL = {"axisym": {"n_elements": 8}, "plate2d": {"n_rings": 3, "n_sectors": 24}}


@pytest.fixture(scope="module")
def cfg():
    return load_paper(CFG, "ci")


def small_run(cfg, scene, named=None, solver=None, **parameters):
    """A fast run of ``scene``: coarse mesh, one r_c, no repeated timings; ``named`` (effects
    and outputs) replaces the scene's own."""
    run = copy.deepcopy(cfg.runs[scene])
    run["solver"] = solver or run["solver"]
    if named is not None:
        run["effects"] = [e for e in named if e not in RAW["outputs"]]
        run["outputs"] = [e for e in named if e in RAW["outputs"]]
    run["contributes"] = {e: DECLARED[e]["contributes"] for e in run["effects"] + run["outputs"]}
    run["resolution"] = dict(SMALL[run["solver"]])
    run["options"] = {"timing_min_s": 0.0}
    run["parameters"].update({"rolling_radius": [0.065], **parameters})
    return run


@pytest.mark.parametrize("solver, scene", [("axisym", "table12"), ("plate2d", "slotted_rc_sweep")])
def test_an_effect_the_scene_does_not_name_is_never_evaluated(cfg, monkeypatch, solver, scene):
    run = small_run(cfg, scene)
    assert run["solver"] == solver

    def boom(ctx):
        raise AssertionError("an effect or output the scene does not name was evaluated")

    for name in EFFECTS.names:
        if name not in run["effects"] + run["outputs"]:
            monkeypatch.setitem(EFFECTS._fn, name, boom)
    ds = solve(run)
    assert "f_rolled" in ds


def _changed(a, b, var):
    return var in b and (var not in a or not np.allclose(a[var].values, b[var].values,
                                                         equal_nan=True))


# effect or output -> (solver, the scene's others, a variable switching it on must change)
SHOWS = {
    "stress_calibration": ("axisym", ["roll_tension"], "sigma_theta"),
    "slots": ("plate2d", [], "f_unrolled"),
    "roll_tension": ("axisym", [], "sigma_theta"),
    "exact_reference": ("axisym", [], "error_unrolled"),
    "rolled_reference": ("axisym", ["roll_tension"], "f_rolled_reference"),
    "stressed_reference": ("axisym", [], "error_stressed"),
    "identifiability": ("axisym", [], "prof_width"),
    "critical_speed": ("axisym", ["roll_tension"], "critical_speed"),
    "design_map": ("axisym", ["roll_tension"], "design_best_speed"),
    "cutting_heat": ("axisym", ["roll_tension", "design_map"], "heat_sigma_theta"),
    "eigen": ("axisym", ["roll_tension"], "f_rolled"),
    "eq9": ("axisym", ["roll_tension"], "delta_f_eq9_exact"),
    "critical_load": ("axisym", ["roll_tension"], "critical_load_factor"),
    "modal_matrices": ("axisym", ["roll_tension"], "k_sigma_hat"),
    "stiffness_sensitivity": ("axisym", [], "sensitivity_delta_f"),
}


def test_every_declared_effect_has_a_scene_that_shows_it():
    assert set(SHOWS) == set(DECLARED) == set(EFFECTS.names)


@pytest.mark.parametrize("effect", list(SHOWS))
def test_switching_an_effect_on_changes_the_output(cfg, effect):
    solver, others, var = SHOWS[effect]
    scene = "slotted_rc_sweep" if solver == "plate2d" else "table12"
    off = solve(small_run(cfg, scene, others))
    on = solve(small_run(cfg, scene, others + [effect]))
    assert _changed(off, on, var), f"{effect} did not change {var}"
    assert np.isfinite(on[var].values.astype(float)).any()


def test_the_plate2d_stress_is_the_one_roll_tension_contributes(cfg):
    """The solver core reads the load by key: the 2-D plane-stress FE field follows the
    calibrated alpha (stress_calibration) through roll_tension's contribution."""
    a = solve(small_run(cfg, "table12_plate2d", ["roll_tension", "eigen"]))
    b = solve(small_run(cfg, "table12_plate2d", ["stress_calibration", "roll_tension", "eigen"]))
    scale = float(b["stress_scale"])
    np.testing.assert_allclose(b["sigma_theta_binned"], scale * a["sigma_theta_binned"],
                               rtol=1e-8, atol=1e-6)


@pytest.mark.parametrize("solver, scene", [("axisym", "table12"), ("axisym", "fig07_sensitivity"),
                                           ("plate2d", "slotted_rc_sweep")])
def test_contributions_are_the_declared_keys_with_units(cfg, monkeypatch, solver, scene):
    seen = {}
    for name, fn in list(EFFECTS._fn.items()):
        def wrapped(ctx, _fn=fn, _name=name):
            seen[_name] = out = _fn(ctx)
            return out
        monkeypatch.setitem(EFFECTS._fn, name, wrapped)
    named = [e for e, d in DECLARED.items() if solver in d["honoured_by"]
             and not (e in ("exact_reference", "rolled_reference", "stressed_reference")
                      and solver == "plate2d")]
    if scene == "fig07_sensitivity":
        named = ["stiffness_sensitivity"]
    solve(small_run(cfg, scene, named))
    assert set(seen) == set(named)
    for name, out in seen.items():
        assert set(out) <= set(DECLARED[name]["contributes"])
        for key, value in out.items():
            if isinstance(value, tuple):
                unit = value[2]["units"]
                assert unit in UNITS or re.fullmatch(r"[A-Za-z0-9*/^() .-]+", unit), (name, key)
