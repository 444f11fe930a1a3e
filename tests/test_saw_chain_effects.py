"""saw_chain effect protocol: the difference_method solver runs exactly the outputs a scene
names (saw_chain declares no effects), each one named changes what the scene outputs, and
each is timed apart from the core."""
import copy
from pathlib import Path

import numpy as np
import pytest

from mechrepro.config import load_paper
from mechrepro.effects import declared
from mechrepro.models.saw_chain import EFFECTS
from mechrepro.solve import solve
from mechrepro.solve import run_solver

CONFIG = Path(__file__).resolve().parents[1] / "config" / "papers" / "saw_chain.yaml"
CFG = load_paper(CONFIG, "ci")


def small(scene, K=50, outputs=None):
    """A config scene's run at small K (optionally naming other outputs), timed once, with
    its time history kept (the contributions are per-sample variables)."""
    run = copy.deepcopy(CFG.runs[scene])
    run["resolution"] = {"K": K}
    run["options"] = {**run.get("options", {}), "timing_min_s": 0.0, "keep_history": True}
    if outputs is not None:
        run["outputs"] = list(outputs)
        run["contributes"] = {e: declared(CFG.raw)[e]["contributes"]
                              for e in run["effects"] + run["outputs"]}
    return run


def _raising(name):
    def boom(ctx):
        raise AssertionError(f"{name!r} evaluated although the scene did not name it")
    return boom


@pytest.mark.parametrize("scene", list(CFG.raw["scenes"]))
def test_outputs_a_scene_does_not_name_are_never_evaluated(scene, monkeypatch):
    """Raising registry, for every scene of the one solver (difference_method)."""
    run = small(scene)
    assert run["solver"] == "difference_method"
    named = run["effects"] + run["outputs"]
    for name in EFFECTS.names:
        if name not in named:
            monkeypatch.setitem(EFFECTS._fn, name, _raising(name))
    ds = run_solver(run)
    for name, spec in declared(CFG.raw).items():
        for key in spec["contributes"]:
            assert (key in ds) == (name in named), (name, key)
    assert np.all(np.isfinite(ds["dynamic_load_x"].values))


def test_the_solver_alone_runs_without_any_output(monkeypatch):
    for name in EFFECTS.names:
        monkeypatch.setitem(EFFECTS._fn, name, _raising(name))
    ds = run_solver(small("accuracy", outputs=[]))
    assert "dynamic_load_x" in ds and "dynamic_load_x_error_pointwise" not in ds


def test_exact_reference_adds_the_reference_and_the_errors_against_it():
    off = solve(small("accuracy", K=200, outputs=[]))
    on = solve(small("accuracy", K=200, outputs=["exact_reference"]))
    assert set(on.data_vars) - set(off.data_vars) >= {
        "dynamic_load_x_exact", "dynamic_load_x_error_pointwise", "tight_side_velocity_error_pointwise"}
    # the difference method itself is untouched by its reference
    np.testing.assert_array_equal(on["dynamic_load_x"].values, off["dynamic_load_x"].values)
    err = float(on["dynamic_load_x_error_pointwise"])
    assert 0 < err < 5.0 / 200  # first order against a reference that differs from the method


def test_textbook_adds_eq23_which_differs_from_the_difference_method():
    off = solve(small("speed_12000", K=200, outputs=[]))
    on = solve(small("speed_12000", K=200, outputs=["textbook"]))
    assert "dynamic_load_x_textbook" not in off
    F, Ft = on["dynamic_load_x"].values, on["dynamic_load_x_textbook"].values
    assert np.abs(Ft).max() > 1.5 * np.abs(F).max()   # Sec. 4: the textbook overestimates
    assert float(on["dynamic_load_x_textbook_min"]) == pytest.approx(Ft.min())


def test_contributions_carry_the_declared_units():
    runs = {s: solve(small(s)) for s in ("fig07_fig08", "identification", "design_maps", "richardson")}
    assert declared(CFG.raw)   # every declared effect and output (saw_chain: outputs only)
    for name, spec in declared(CFG.raw).items():
        assert set(spec["units"]) == set(spec["contributes"])
        ds = runs[{"richardson_levels": "richardson"}.get(name, name) if name != "textbook"
                  and name != "exact_reference" else "fig07_fig08"]
        for key, unit in spec["units"].items():
            assert ds[key].attrs["units"] == unit, (name, key)


def test_each_output_is_timed_apart_from_the_solver_core():
    ds = run_solver(small("fig07_fig08", K=2000))
    times = dict(zip(ds["timed_effect"].values.tolist(), ds["effect_time"].values))
    assert set(times) == {"textbook", "exact_reference"} and all(t > 0 for t in times.values())
    assert 0 < float(ds["core_time"]) < float(ds["wall_time"])
    assert float(ds["core_time"]) + sum(times.values()) == pytest.approx(float(ds["wall_time"]))


@pytest.mark.parametrize("kind", ["effects", "outputs"])
def test_the_solver_named_as_an_effect_is_refused_at_load(edit_config, kind):
    """The old spelling (the method listed among the effects, or the outputs) stops before
    any job."""
    from mechrepro.config import ConfigError

    path = edit_config("saw_chain", lambda r: r["scenes"]["speed_12000"].setdefault(
        kind, []).append("difference_method"))
    with pytest.raises(ConfigError, match=f"'difference_method' is not a declared {kind[:-1]}"):
        load_paper(path)


def test_a_study_without_history_keeps_every_scalar_it_stacks():
    """``keep_history: false`` (the K study) drops the per-sample series and nothing else."""
    full = solve(small("accuracy", K=200))
    run = small("accuracy", K=200)
    run["options"]["keep_history"] = False
    lean = solve(run)
    assert "t" not in lean.dims
    assert set(lean.data_vars) == {v for v in full.data_vars if "t" not in full[v].dims}
    for v in lean.data_vars:
        np.testing.assert_array_equal(lean[v].values, full[v].values)
