"""Bad config input is refused when the config is loaded (before any job), naming the file,
the key, the value and what is allowed (mechrepro.inputs, mechrepro.config)."""
import math
from pathlib import Path

import pytest
import yaml

from mechrepro.config import ConfigError, load_paper
from mechrepro.inputs import read_yaml

SCENES_LINE = (Path(__file__).resolve().parents[1] / "config/papers/saw_chain.yaml"
               ).read_text().splitlines().index("scenes:") + 1
PITCH = "tie_strap_pitch:        {value: 8.91,  unit: mm,"

# (class, text edit of saw_chain.yaml, what the message must name)
BAD = [
    ("NaN in a parameter without a cross-check",
     lambda t: t.replace("{value: 32,    unit: \"1\", source: \"Sec. 4 (M)\"",
                         "{value: .nan,  unit: \"1\", source: \"Sec. 4 (M)\""),
     ["parameters.tie_straps_tight_side.value", "nan", "finite"]),
    ("infinity in a scene override",
     lambda t: t.replace("parameters: {sprocket_speed: 12000}", "parameters: {sprocket_speed: .inf}"),
     ["scenes.speed_12000.parameters.sprocket_speed", "inf", "finite"]),
    ("duplicate top-level key (a second scenes: block)",
     lambda t: t + "\nscenes:\n  x: {solver: difference_method, effects: []}\n",
     ["'scenes' given twice", f"line {SCENES_LINE}", "each key once"]),
    ("duplicate nested key",
     lambda t: t.replace(PITCH, "tie_strap_pitch:        {value: 8.91, value: 9.0, unit: mm,"),
     ["'value' given twice", "each key once"]),
    ("non-UTF-8 byte",
     lambda t: t.replace("Sec. 4 (p1)", "Sec. 4 (p1) \udce9"),
     ["line 8", "not UTF-8", "b'\\xe9'"]),
    ("a unit of another scale (8.91 m chain pitch)",
     lambda t: t.replace(PITCH, "tie_strap_pitch:        {value: 8.91,  unit: m,"),
     ["parameters.tie_strap_pitch.value = 8.91", "chain pitch between 3 mm and 200 mm"]),
    ("a link mass in kg where g is meant (scene-independent parameter)",
     lambda t: t.replace("{value: 1.906, unit: g,", "{value: 1.906, unit: kg,"),
     ["parameters.tie_strap_mass.value = 1.906", "1.906 kg", "a chain link", "0.1 to 50 g"]),
    ("a speed in a scene override 1000 times the machine's",
     lambda t: t.replace("parameters: {sprocket_speed: 12000}",
                         "parameters: {sprocket_speed: 12000000}"),
     ["scenes.speed_12000.parameters.sprocket_speed = 12000000", "chain-saw sprocket",
      "2000 to 16000 rpm"]),
    ("a negative pitch (schema)",
     lambda t: t.replace("value: 8.91,", "value: -8.91,"),
     ["parameters.tie_strap_pitch = -8.91", "must be > 0"]),
]


@pytest.mark.parametrize("name, edit, expect", BAD, ids=[b[0] for b in BAD])
def test_bad_input_is_refused_at_load_with_file_key_value_and_what_is_allowed(
        config_copy, name, edit, expect):
    path = config_copy / "papers" / "saw_chain.yaml"
    text = edit(path.read_text())
    path.write_bytes(text.encode("utf-8", "surrogateescape"))
    with pytest.raises(ConfigError) as err:
        load_paper(path, "ci")
    msg = str(err.value)
    assert str(path) in msg, msg
    for part in expect:
        assert part in msg, (part, msg)


def test_the_committed_configs_read_as_before(config_copy):
    """The strict reader gives the same data as the plain safe loader on valid files."""
    for path in sorted((config_copy / "papers").glob("*.yaml")):
        assert read_yaml(path) == yaml.safe_load(path.read_text()), path


def _ranged():
    from conftest import ROOT

    return [(f.stem, n) for f in sorted((ROOT / "config" / "papers").glob("*.yaml"))
            for n, p in sorted(read_yaml(f)["parameters"].items()) if "plausible" in p]


@pytest.mark.parametrize("paper, name", _ranged(), ids=[f"{p}.{n}" for p, n in _ranged()])
def test_a_unit_slip_of_every_ranged_parameter_is_refused(paper, name):
    """Every parameter with a machine-class range (``plausible:``) passes as committed, and
    is refused when its value is typed in the
    unit 1000 times larger or smaller (an angle: in degrees where rad is declared, or the
    reverse; an angular speed whose range is narrower than 60 / (2 pi): also its rad/s
    number typed for r/min and its r/min number with unit rad/s), naming the key, the
    value and the range."""
    from conftest import ROOT
    from mechrepro.inputs import check_parameters

    raw = yaml.safe_load((ROOT / "config" / "papers" / f"{paper}.yaml").read_text())
    assert check_parameters(raw) == []
    p = raw["parameters"][name]
    lo, hi, unit = (p["plausible"][k] for k in ("min", "max", "unit"))
    scale = lambda v, f: [x * f for x in v] if isinstance(v, list) else v * f  # noqa: E731
    if unit == "deg":   # the declared unit's number typed in the other angle unit
        slips = [(scale(p["value"], 180 / 3.141592653589793), "rad")] if p["unit"] == "rad" \
            else [(p["value"], "rad")]
    else:
        slips = [(scale(p["value"], 1e3), p["unit"]), (scale(p["value"], 1e-3), p["unit"])]
    if unit in ("rpm", "r/min") and hi / lo < 60 / (2 * 3.141592653589793):
        slips += [(scale(p["value"], 2 * 3.141592653589793 / 60), p["unit"]),
                  (p["value"], "rad/s")]
    for value, u in slips:
        raw["parameters"][name] = {**p, "value": value, "unit": u}
        msg = "; ".join(check_parameters(raw))
        assert f"parameters.{name}.value" in msg and "not plausible" in msg, (value, u, msg)
        assert f"{lo:g} to {hi:g} {unit}" in msg or "within one turn" in msg or \
            "chain pitch" in msg, msg


@pytest.mark.parametrize("typed, shown", [
    ("{value: 1.005, unit: r/min", "1.005 r/min"),    # the rad/s number typed for r/min
    ("{value: 9.6, unit: rad/s", "9.6 rad/s"),         # the r/min number given as rad/s
])
def test_an_angular_speed_in_the_wrong_unit_is_refused_at_load(config_copy, typed, shown):
    """joint_wear's crank speed typed in rad/s where r/min is meant ran into the job and
    failed there (ContactLost), the unit never named: refused at load, naming it."""
    path = config_copy / "papers" / "joint_wear.yaml"
    text = path.read_text()
    assert "{value: 9.6, unit: r/min" in text
    path.write_text(text.replace("{value: 9.6, unit: r/min", typed))
    with pytest.raises(ConfigError) as err:
        load_paper(path, "ci")
    msg = str(err.value)
    for part in (str(path), "parameters.crank_speed.value", shown, "not plausible",
                 "3 to 28 r/min"):
        assert part in msg, (part, msg)


def test_merge_keys_may_override(tmp_path):
    p = tmp_path / "x.yaml"
    p.write_text("a: &a {x: 1, y: 2}\nb:\n  <<: *a\n  y: 3\n")
    assert read_yaml(p) == {"a": {"x": 1, "y": 2}, "b": {"x": 1, "y": 3}}


# --- each solver's own limits, effects it needs, its declared cost (mechrepro.limits) ----

PAPERS = ["saw_chain", "rolling_shear", "joint_wear", "disk_tension", "chain_drive"]


@pytest.mark.parametrize("profile", ["default", "ci"])
def test_the_committed_configs_pass_every_limit(profile):
    """No false refusal: every committed config is within its solvers' limits, names the
    effects its quantities read and fits the solve rule's memory and time."""
    from mechrepro import limits
    from mechrepro.config import load_all

    from conftest import ROOT

    cfgs = load_all(ROOT / "config", PAPERS, profile)
    limits.check_all(cfgs)
    for cfg in cfgs.values():
        assert limits.missing_effects(cfg) == [] and limits.refusals(cfg) == []


def _limit_problems(edit_config, paper, fn, profile="ci", over_budget=False):
    from mechrepro import limits

    path = edit_config(paper, fn)
    cfg = load_paper(path, profile)
    with pytest.raises(limits.LimitError) as err:
        limits.check_all({paper: cfg}, over_budget)
    return str(err.value), path


LIMITS = [
    ("saw_chain K beyond the round-off limit", "saw_chain",
     lambda raw: raw["profiles"]["ci"]["scenes"]["fig07_fig08"].update(resolution={"K": 50000}),
     ["scene fig07_fig08", "resolution.K = 50000", "K <= 39434",
      "options.beyond_roundoff_limit: true on purpose"]),
    ("disk_tension clamp_radius = 40 mm (Fig. 7's annuli from 30 mm)", "disk_tension",
     lambda raw: raw["parameters"]["clamp_radius"].update(value=40),
     ["scene fig07_sensitivity", "parameters.annulus_radii: 30 mm, 35 mm, 40 mm",
      "[r_f, b] = [40 mm, 127.5 mm]", "45 mm <= r_a <= 122.5 mm"]),
    ("an emptied output list a quantity reads (saw_chain speed_12000)", "saw_chain",
     lambda raw: raw["scenes"]["speed_12000"].update(outputs=[]),
     ["scenes.speed_12000.outputs = []", "'dynamic_load_x_textbook'", "output 'textbook'",
      "allowed: outputs including 'textbook'"]),
    ("an emptied output list of a solver that needs one (saw_chain accuracy)",
     "saw_chain", lambda raw: raw["scenes"]["accuracy"].update(outputs=[]),
     ["scenes.accuracy: no effects or outputs", "needs one", "allowed: at least one of"]),
    ("an effect a quantity reads dropped (joint_wear wear_prediction)", "joint_wear",
     lambda raw: raw["scenes"]["wear_prediction"].update(effects=["friction", "gravity"]),
     ["scenes.wear_prediction.effects = ['friction', 'gravity']", "effect 'archard_wear'"]),
    ("a resolution above the solve rule's memory", "saw_chain",
     lambda raw: raw["profiles"]["ci"]["scenes"].update(accuracy={"resolution": {"K": 9000000}}),
     ["job solve_saw_chain__batch", "run accuracy", "expected to take 2900 MB",
      "above the solve rule's 2000 MB", "--config over_budget=true"]),
    ("a rolling_shear selPSO budget above the solve rule's time", "rolling_shear",
     lambda raw: raw["profiles"]["ci"]["scenes"].update(accuracy_selpso={"resolution": {
         "n_points": 4097, "pso_swarm": 200, "pso_iter": 1000}}),
     ["job solve_rolling_shear__batch", "expected to take",
      "above the solve rule's 30 min", "--config over_budget=true"]),
    ("joint_wear dynamic samples above the solve rule's memory", "joint_wear",
     lambda raw: raw["profiles"]["ci"]["scenes"].update(
         period_dynamic={"resolution": {"n_out": 400000, "periods": 100}}),
     ["job solve_joint_wear__batch", "run period_dynamic", "'n_out': 400000",
      "'periods': 100", "expected to take 4260 MB", "above the solve rule's 2000 MB",
      "--config over_budget=true"]),
    ("joint_wear load-point fit samples above the solve rule's time", "joint_wear",
     lambda raw: raw["profiles"]["ci"]["scenes"].update(
         load_point_fit={"resolution": {"n_steps": 1000000}}),
     ["job solve_joint_wear__batch", "run load_point_fit", "'n_steps': 1000000",
      "min", "above the solve rule's 30 min", "--config over_budget=true"]),
    ("joint_wear explicit integrator without a step budget over many periods", "joint_wear",
     lambda raw: (raw["scenes"]["period_explicit"]["resolution"].pop("max_steps"),
                  raw["scenes"]["period_explicit"]["resolution"].update(periods=100, rtol=1.0e-6),
                  raw["profiles"]["ci"]["scenes"].pop("period_explicit")),
     ["run period_explicit", "'method': 'RK45'", "above the solve rule's 30 min"]),
    ("plate2d mesh above the solve rule's memory", "disk_tension",
     lambda raw: raw["profiles"]["ci"]["scenes"].update(
         table12_plate2d={"resolution": {"n_rings": 40, "n_sectors": 300}}),
     ["run table12_plate2d", "MB, above the solve rule's 2000 MB"]),
]


@pytest.mark.parametrize("name, paper, fn, expect", LIMITS, ids=[l[0] for l in LIMITS])
def test_a_solver_limit_is_refused_at_load_with_what_is_allowed(edit_config, name, paper,
                                                                fn, expect):
    msg, path = _limit_problems(edit_config, paper, fn)
    assert str(path) in msg, msg
    for part in expect:
        assert part in msg, (part, msg)


def test_over_budget_on_purpose_runs_and_asks_for_the_estimate(edit_config):
    from mechrepro import limits

    path = edit_config("saw_chain", lambda raw: raw["profiles"]["ci"]["scenes"].update(
        accuracy={"resolution": {"K": 9000000}}))
    cfg = load_paper(path, "ci")
    limits.check_all({"saw_chain": cfg}, allow_over_budget=True)
    assert limits.job_resources(cfg, "batch", True)["mem_mb"] == 2900
    assert limits.job_resources(cfg, "batch", False)["mem_mb"] == limits.SOLVE_MEM_MB
    # a solver's own refusal is never overridden by over_budget
    msg, _ = _limit_problems(edit_config, "saw_chain", lambda raw: raw["profiles"]["ci"]["scenes"][
        "fig07_fig08"].update(resolution={"K": 50000}), over_budget=True)
    assert "round-off" in msg


def test_rolling_shear_over_budget_on_purpose_asks_for_the_estimate(edit_config):
    from mechrepro import limits

    path = edit_config("rolling_shear", lambda raw: raw["profiles"]["ci"]["scenes"].update(
        accuracy_selpso={"resolution": {"n_points": 4097, "pso_swarm": 200, "pso_iter": 1000}}))
    cfg = load_paper(path, "ci")
    limits.check_all({"rolling_shear": cfg}, allow_over_budget=True)
    res = limits.job_resources(cfg, "batch", True)
    est = limits.job_costs(cfg)["batch"]["seconds"]
    assert res["runtime"] == math.ceil(est / 60) > limits.SOLVE_RUNTIME_MIN, (res, est)
    assert res["mem_mb"] == limits.SOLVE_MEM_MB
    # memory: the schema's 4097 cut points keep a run near 335 MB; the model refuses a
    # stroke above the rule's memory (3e6 points: 2880 MB) should the schema allow it
    run = dict(cfg.runs["original"], resolution={"n_points": 3000000})
    assert limits.run_cost("rolling_shear", run)["mem_mb"] == pytest.approx(2880)


def test_joint_wear_plausible_runs_pass_and_over_budget_asks_for_the_estimate(edit_config):
    """A finer but plausible resolution passes (the wear prediction at 8192 samples per
    period: ~6 s); the absurd one above passes only on purpose, asking for its estimate."""
    from mechrepro import limits

    path = edit_config("joint_wear", lambda raw: raw["profiles"]["ci"]["scenes"].update(
        wear_prediction={"resolution": {"n_steps": 8192}}))
    cfg = load_paper(path, "ci")
    limits.check_all({"joint_wear": cfg})
    assert limits.run_cost("joint_wear", cfg.runs["wear_prediction"])["seconds"] < 60
    path = edit_config("joint_wear", lambda raw: raw["profiles"]["ci"]["scenes"].update(
        period_dynamic={"resolution": {"n_out": 400000, "periods": 100}}))
    cfg = load_paper(path, "ci")
    limits.check_all({"joint_wear": cfg}, allow_over_budget=True)
    assert limits.job_resources(cfg, "batch", True)["mem_mb"] == 4260


def _measured(paper, run, root):
    """(peak MB, solve CPU s) of one run solved in a fresh process (CPU, not wall, time:
    the cost models are fitted to it, and a loaded machine stretches only the wall)."""
    import json
    import os
    import subprocess
    import sys
    import tempfile

    # the peak of this process's own memory (VmHWM): ru_maxrss would also carry the RSS of
    # the (large, forked) pytest worker that started it, which Linux keeps across exec
    code = ("import sys, json, re, time;"
            "from mechrepro.solve import run_solver; run = json.loads(sys.argv[1]);"
            "t = time.process_time(); run_solver(run).to_netcdf(sys.argv[2]);"
            "t = time.process_time() - t;"
            "print(t, int(re.search(r'VmHWM:\\s+(\\d+)', open('/proc/self/status').read())"
            ".group(1)) / 1024)")
    with tempfile.TemporaryDirectory() as d:
        out = subprocess.run([sys.executable, "-c", code, json.dumps(run), f"{d}/x.nc"],
                             capture_output=True, text=True, check=True,
                             env={**os.environ, "PYTHONPATH": str(root / "src")})
    t, peak = map(float, out.stdout.split()[-2:])
    return peak, t


def test_rolling_shear_cost_is_above_a_measured_run():
    """rolling_shear's cost model against one measured solve: the stroke at 4097 cut points
    in a fresh process (the memory above the interpreter's is the per-point term's; the
    time within the paper's job start, config/costs.csv, of the estimate)."""
    from conftest import ROOT
    from mechrepro import limits

    cfg = load_paper(ROOT / "config" / "papers" / "rolling_shear.yaml", "ci")
    run = dict(cfg.runs["original"], resolution=dict(cfg.runs["original"]["resolution"],
                                                    n_points=4097, newton_tol=1e-11))
    peak, seconds = _measured("rolling_shear", run, ROOT)
    est = limits.run_cost("rolling_shear", run)
    assert peak < est["mem_mb"] < 2 * peak, (peak, est)
    assert seconds < est["seconds"] + limits.coefficients()["rolling_shear", "(job)"]["start"], (
        seconds, est)


def test_the_declared_cost_is_above_a_measured_run():
    """saw_chain's cost model against one measured solve (peak memory of a child process)."""
    from conftest import ROOT
    from mechrepro import limits

    cfg = load_paper(ROOT / "config" / "papers" / "saw_chain.yaml", "ci")
    run = dict(cfg.runs["cost_of_accuracy-010"])   # K = 3e5
    peak, _ = _measured("saw_chain", run, ROOT)
    est = limits.run_cost("saw_chain", run)["mem_mb"]
    assert peak < est < 3 * peak, (peak, est)


def test_joint_wear_cost_is_above_a_measured_run():
    """joint_wear's cost model against one measured solve in a fresh process: the settled
    dynamic joint over 10 periods of 100 000 samples (its memory above a warm process's;
    its time below the estimate plus the paper's job start, config/costs.csv: the first
    run of a process carries the kernels' load, and the estimate is a high quantile)."""
    from conftest import ROOT
    from mechrepro import limits

    from mechrepro.models import joint_wear

    joint_wear.warm()   # the kernels in the disk cache: the child loads, not compiles, them
    cfg = load_paper(ROOT / "config" / "papers" / "joint_wear.yaml", "ci")
    run = dict(cfg.runs["period_dynamic"], resolution={
        **cfg.runs["period_dynamic"]["resolution"], "n_out": 100000, "periods": 10})
    peak, seconds = _measured("joint_wear", run, ROOT)
    est = limits.run_cost("joint_wear", run)
    assert peak < est["mem_mb"] < 2 * peak, (peak, est)
    start = limits.coefficients()["joint_wear", "(job)"]["start"]
    assert seconds < est["seconds"] + start, (seconds, est)


def test_the_cost_table_is_read_once_and_a_missing_solver_is_refused_at_load(tmp_path, monkeypatch):
    """The cost coefficients are data (config/costs.csv, written by ``python -m
    mechrepro.costs``): every solver of every paper has its row, and a table without a
    solver's is refused when the configs load, naming the file, the paper, the solver and
    the command that writes it."""
    from conftest import ROOT
    from mechrepro import costs, limits

    table = limits.coefficients()
    for p in ("saw_chain", "rolling_shear", "joint_wear", "disk_tension", "chain_drive"):
        cfg = load_paper(ROOT / "config" / "papers" / f"{p}.yaml", "ci")
        assert {(p, r["solver"]) for r in cfg.runs.values()} | {(p, "(job)")} <= set(table)
    cfg = load_paper(ROOT / "config" / "papers" / "saw_chain.yaml", "ci")
    cut = tmp_path / "costs.csv"
    cut.write_text("".join(ln for ln in limits.COSTS.read_text().splitlines(True)
                           if not ln.startswith("saw_chain,difference_method,")))
    monkeypatch.setattr(limits, "COSTS", cut)
    with pytest.raises(limits.LimitError) as err:
        limits.check_all({"saw_chain": cfg}, allow_over_budget=True)
    for part in (str(cut), "paper saw_chain", "solver difference_method", "python -m mechrepro.costs"):
        assert part in str(err.value), (part, str(err.value))
    # the fit: relative least squares, scaled so the estimate stays above QUANTILE of runs
    work = [{"run": 1.0, "K": k} for k in (10, 100, 1000, 10000)]
    c = costs.fit(work, [0.01 + 1e-5 * k for k in (10, 100, 1000, 10000)])
    assert c["run"] == pytest.approx(0.01, rel=1e-6) and c["K"] == pytest.approx(1e-5, rel=1e-6)


def test_a_refit_from_no_runs_loses_no_coefficient(tmp_path, monkeypatch, capsys):
    """`python -m mechrepro.costs` given a tree without runs (or none at all, or `--help`)
    stops with one line and leaves the table as it was."""
    from mechrepro import costs, limits

    before = limits.COSTS.read_bytes()
    table = tmp_path / "costs.csv"
    table.write_bytes(before)
    monkeypatch.setattr(limits, "COSTS", table)
    for argv in (["--help"], [str(tmp_path / "missing")], [str(tmp_path)]):
        with pytest.raises(SystemExit):
            costs.main(argv)
        assert table.read_bytes() == before, argv
