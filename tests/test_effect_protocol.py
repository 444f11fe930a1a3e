"""The effect protocol of the framework: declarations checked at config load, contributions
evaluated only for named effects and outputs (outputs after every effect), each timed, the
time split stored with the run."""
from __future__ import annotations

import copy
from pathlib import Path

import numpy as np
import pytest
import yaml

from mechrepro import effects as fx
from mechrepro import timing
from mechrepro.config import ConfigError, discover_papers, load_all, load_paper
from mechrepro.inputs import read_yaml

CONFIG = Path(__file__).resolve().parents[1] / "config"
PAPERS = discover_papers(CONFIG)


def _raw(paper):
    return {"paper": paper, **read_yaml((CONFIG / "papers" / f"{paper}.yaml"))}


def _load(tmp_path, raw):
    d = tmp_path / "config"
    (d / "papers").mkdir(parents=True)
    for f in (CONFIG / "schema").glob("*.yaml"):
        (d / "schema").mkdir(exist_ok=True)
        (d / "schema" / f.name).write_text(f.read_text())
    path = d / "papers" / f"{raw['paper']}.yaml"
    path.write_text(yaml.safe_dump(raw, sort_keys=False))
    return load_paper(path)


@pytest.mark.parametrize("paper", PAPERS)
def test_every_scene_declares_a_solver_that_honours_its_effects(paper):
    raw = _raw(paper)
    assert raw.get("solvers") and fx.declared(raw), f"{paper}: declare solvers: and effects: or outputs:"
    for name, scene in raw["scenes"].items():
        assert scene.get("solver") in raw["solvers"], f"{paper}: scene {name} names no solver"
    cfg = load_all(CONFIG, [paper])[paper]
    for run in cfg.runs.values():
        assert run["solver"] in raw["solvers"]
        assert set(run["contributes"]) == set(run["effects"]) | set(run["outputs"])


@pytest.mark.parametrize("paper", PAPERS)
def test_every_declared_effect_is_implemented_and_vice_versa(paper):
    import importlib

    registry = importlib.import_module(f"mechrepro.models.{paper}").EFFECTS
    assert set(registry.names) == set(fx.declared(_raw(paper)))


@pytest.mark.parametrize("paper", PAPERS)
def test_an_effect_the_solver_does_not_honour_is_refused_at_load(paper, tmp_path):
    raw = _raw(paper)
    for (scene_name, scene), kind in ((s, k) for s in raw["scenes"].items()
                                      for k in ("effects", "outputs")):
        solver = scene["solver"]
        foreign = [e for e, d in raw.get(kind, {}).items()
                   if solver not in d["honoured_by"] and e not in scene.get(kind, [])]
        if foreign:
            break
    else:
        pytest.skip(f"{paper}: every solver honours every effect and output")
    bad = copy.deepcopy(raw)
    bad["scenes"][scene_name][kind] = list(scene.get(kind, [])) + [foreign[0]]
    bad.pop("profiles", None)
    with pytest.raises(ConfigError, match=rf"{foreign[0]}.*not honoured by solver {solver!r}"):
        _load(tmp_path, bad)


def test_undeclared_solver_requires_and_excludes_are_refused(tmp_path):
    raw = _raw("chain_drive")
    raw.pop("profiles", None)
    scene = next(iter(raw["scenes"]))
    bad = copy.deepcopy(raw)
    bad["scenes"][scene]["solver"] = "warp_drive"
    with pytest.raises(ConfigError, match="solver = 'warp_drive': not declared"):
        _load(tmp_path / "a", bad)
    bad = copy.deepcopy(raw)
    bad["scenes"][scene]["effects"] = ["no_such_effect"]
    with pytest.raises(ConfigError, match="'no_such_effect' is not a declared effect"):
        _load(tmp_path / "b", bad)
    bad = copy.deepcopy(raw)
    e = bad["scenes"][scene]["effects"][0]
    bad["effects"][e]["requires"] = [x for x in bad["effects"] if x != e][:1]
    with pytest.raises(ConfigError, match=f"effect '{e}' requires"):
        _load(tmp_path / "c", bad)


def test_evaluate_calls_only_named_effects_times_each_and_checks_declared_keys():
    reg = fx.EffectRegistry("demo")
    calls = []

    @reg.register("a")
    def a(ctx):
        calls.append("a")
        return {"tension": np.ones(3)}

    @reg.register("b")
    def b(ctx):
        raise AssertionError("an effect that is not named must never run")

    @reg.register("c")
    def c(ctx):
        return {"tension": 2 * np.ones(3), "kappa": 0.5}

    run = {"effects": ["c", "a"], "contributes": {"a": ["tension"], "c": ["tension", "kappa"]}}
    timer = timing.Timer()
    token = timing._current.set(timer)
    try:
        out = reg.evaluate(run, ctx=None)
    finally:
        timing._current.reset(token)
    assert out.total("tension").tolist() == [3.0, 3.0, 3.0]
    assert out.sources("tension") == ["a", "c"] and out.get("kappa") == 0.5
    assert "u_left" not in out and out.total("u_left") == 0.0
    with pytest.raises(fx.ContributionError):
        out.get("tension")
    assert set(timer.effects()) == {"a", "c"} and calls == ["a"]
    with pytest.raises(fx.ContributionError, match="its declaration contributes"):
        reg.evaluate({"effects": ["a"], "contributes": {"a": ["kappa"]}}, ctx=None)
    with pytest.raises(fx.UnknownEffect):
        reg.evaluate({"effects": ["z"]}, ctx=None)


def test_outputs_come_after_every_effect_and_are_timed_apart():
    reg, calls = fx.EffectRegistry("demo"), []
    for name in ("ref", "load", "drag"):     # registered with an output first
        reg.register(name)(lambda ctx, name=name: calls.append(name) or {name: 1.0})
    run = {"effects": ["load", "drag"], "outputs": ["ref"],
           "contributes": {"ref": ["ref"], "load": ["load"], "drag": ["drag"]}}
    timer = timing.Timer()
    token = timing._current.set(timer)
    try:
        stage = reg.stages(run, ctx=None)
        assert stage({"load"}).keys() == ["load"] and calls == ["load"]
        assert stage().keys() == ["drag", "ref"] and stage().keys() == []
    finally:
        timing._current.reset(token)
    assert calls == ["load", "drag", "ref"]
    assert set(timer.phases) == {"effect:load", "effect:drag", "output:ref"}
    assert set(timer.effects()) == {"load", "drag", "ref"}
    with pytest.raises(fx.ContributionError, match="demo: output 'ref' returned"):
        reg.stages({"effects": [], "outputs": ["ref"], "contributes": {"ref": ["x"]}}, None)()


def test_timed_run_keeps_the_phases_of_the_fastest_call():
    def work():
        with timing.phase("effect:x"):
            sum(range(20000))
        return 1

    result, seconds, timer = timing.timed_run(work, min_time=0.02)
    assert result == 1 and 0 < timer.effects()["x"] <= seconds
    v = timing.timing_variables(seconds, timer, ["x", "y"])
    assert v["effect_time"][1][1] == 0.0 and v["core_time"][1] >= 0
