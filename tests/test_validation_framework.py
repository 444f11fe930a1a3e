"""The validation builder, the config's reported block and the platform-derived reference."""
import math

import numpy as np
import pytest
import xarray as xr
import yaml

from mechrepro import io as mio
from mechrepro import reference as ref
from mechrepro.config import ConfigError, load_paper
from mechrepro.validation import (Quantities, Reproduced, Row, ValidationError, build, claim,
                                  discrimination, grade_rivals, read_table, sledgehammers,
                                  write_table)


def reported_config(raw):
    """saw_chain's config with a small reported block of every kind."""
    p = raw["parameters"]
    for name, spec in p.items():
        if spec.get("assumed"):
            for k in ("range", "range_why", "calibrated_on", "numerical"):
                spec.pop(k, None)
            spec["numerical"] = True
    p["textbook_mass"].pop("numerical")
    p["textbook_mass"].update(range=[1.296, 102.464], range_why="one link .. whole side")
    raw["refine"]["K"]["factor"] = 2
    raw["reported"] = {
        "load_max": dict(artefact="fig08", source="Fig. 8", evidence="independent",
                         value=100.0, unit="N", tolerance=0.01, why="1 %", reads=["fig07_fig08"]),
        "mass_claim": dict(artefact="fig08", source="Sec. 4", evidence="independent",
                           kind="check", reads=["fig07_fig08"], depends_on=["textbook_mass"]),
        "order": dict(artefact="text", source="ours", evidence="construction",
                      evidence_why="arithmetic", kind="bound", op=">", value=0.5, unit="1",
                      why="first order", reads=["cost_of_accuracy"]),
        "exact": dict(artefact="fig08", source="ours", evidence="independent", kind="info",
                      unit="N", reads=["fig07_fig08"]),
    }
    for prof in raw.get("profiles", {}).values():
        prof.pop("drift_tolerance", None)


def write_runs(cfg, results, load):
    """A dataset per run whose `load` depends on K and textbook_mass as ``load(run)``."""
    for name, run in cfg.runs.items():
        ds = xr.Dataset({"load": ((), load(run), {"units": "N", "long_name": "load"})})
        mio.write_dataset(ds, results / cfg.paper / "runs" / f"{name}.nc", run)
    for study, runs in cfg.studies.items():
        st = mio.gather_study([results / cfg.paper / "runs" / f"{r}.nc" for r in runs])
        mio.write_dataset(st, results / cfg.paper / "studies" / f"{study}.nc")


def quantities(reads_extra=False):
    Q = Quantities("saw_chain")

    @Q.register("load_max", "exact")
    def _(R):
        v = float(R.run("fig07_fig08")["load"])
        if reads_extra:
            R.run("speed_12000")
        return {"load_max": v, "exact": Reproduced(v, note="exact is v")}

    @Q.register("mass_claim")
    def _(R):
        return R.parameter("textbook_mass") > 0.01

    @Q.register("order")
    def _(R):
        return float(R.study("cost_of_accuracy")["load"].size)

    return Q


@pytest.fixture
def paper(edit_config, tmp_path):
    path = edit_config("saw_chain", reported_config)
    return load_paper(path, "ci"), tmp_path / "results"


def test_variant_runs_are_made_for_what_verdicts_read(paper):
    cfg, _ = paper
    K = cfg.runs["fig07_fig08"]["resolution"]["K"]
    assert cfg.runs["fig07_fig08@coarser"]["resolution"]["K"] == K // 2
    assert cfg.runs["fig07_fig08@coarsest"]["resolution"]["K"] == K // 4
    # a counted row's reads also run one level finer (the error bar from both sides)
    assert cfg.runs["fig07_fig08@finer"]["resolution"]["K"] == 2 * K
    assert cfg.runs["fig07_fig08@textbook_mass-lo"]["parameters"]["textbook_mass"] == pytest.approx(1.296e-3)
    assert "cost_of_accuracy@coarser" in cfg.studies
    # its coarsest level (K = 1) is outside the run schema: skipped with the reason, and the
    # row gets the two-level estimate
    assert "K = 1: must be >= 2" in cfg.variant_skipped["coarsest"]["cost_of_accuracy"]
    # info rows are not re-checked, and the check row does not read the study
    assert "cost_of_accuracy@textbook_mass-lo" not in cfg.studies
    assert "speed_12000@coarser" not in cfg.runs


def K(run):
    return run["resolution"]["K"]


def test_a_verdict_whose_error_bar_straddles_the_tolerance_is_inconclusive(paper):
    cfg, results = paper
    # converges at first order to 100.5 N; at K = 300 it is 100.5 + 150 / 300 = 101.0 N and the
    # Richardson error estimate 0.5 N reaches past the 1 N band
    write_runs(cfg, results, lambda run: 100.5 + 150.0 / K(run))
    rows = {r.quantity: r for r in build(cfg, quantities(), results)}
    assert rows["load_max"].status == "inconclusive"
    assert rows["load_max"].error == pytest.approx(0.5)
    assert rows["load_max"].order == pytest.approx(1.0)
    assert "straddles the tolerance" in rows["load_max"].cells()[9]
    assert rows["exact"].status == "info" and "exact is v" in rows["exact"].cells()[9]
    # the mass claim (textbook_mass > 10 g) fails at the low end of its range
    assert rows["mass_claim"].status == "inconclusive"
    assert "textbook_mass = 1.296 g" in " ".join(rows["mass_claim"].flips)
    assert rows["order"].status == "pass"


def test_levels_that_do_not_contract_are_not_converged(paper):
    cfg, results = paper
    # 100.5 at K / 4 and K / 2, 100.2 at K: the finer difference is the larger
    write_runs(cfg, results, lambda run: 100.5 if "@coarse" in run["run"] else 100.2)
    rows = {r.quantity: r for r in build(cfg, quantities(), results)}
    assert rows["load_max"].status == "not_converged"
    assert "does not converge" in rows["load_max"].cells()[9]
    assert claim(cfg, list(rows.values()))["independent"]["not_converged"] == 1


def test_a_value_that_drifts_one_level_finer_is_not_converged(paper, edit_config):
    """Levels on both sides: coarser levels that agree prove nothing if the value moves when
    refined once more; a row without the finer level says its error bar is one-sided."""
    cfg, results = paper
    write_runs(cfg, results, lambda run: 102.0 if run.get("variant") == "finer" else 100.5)
    row = {r.quantity: r for r in build(cfg, quantities(), results)}["load_max"]
    assert row.status == "not_converged" and "refined once more" in row.flips[0]
    # contracting on both sides at first order: the finer level's distance and error count
    write_runs(cfg, results, lambda run: 100.2 + 60.0 / K(run))    # base K = 300: 100.4
    row = {r.quantity: r for r in build(cfg, quantities(), results)}["load_max"]
    assert row.status == "pass" and row.error == pytest.approx(0.2)
    assert "one level finer" in row.note
    cfg = load_paper(edit_config("saw_chain", lambda raw: (reported_config(raw), raw["reported"][
        "load_max"].update(finer=False, finer_why="it would cost 4x the baseline"))), "ci")
    # the baseline as the middle level: the coarser run's value, the error from both sides
    write_runs(cfg, results, lambda run: 100.2 + 60.0 / K(run))    # K 75 / 150 / 300
    row = {r.quantity: r for r in build(cfg, quantities(), results)}["load_max"]
    assert row.value == pytest.approx(100.6) and row.error == pytest.approx(0.4)
    assert "The baseline is the middle level" in row.note and "4x" in row.note


def test_a_quantity_that_does_not_exist_is_reported_not_scored(paper):
    """An extractor that finds no such quantity (an unstable orbit has no steady amplitude)
    returns NaN with its reason: the row says so and is not decided, never a fail."""
    cfg, results = paper
    Q = Quantities("saw_chain")
    Q.register("load_max", "exact")(lambda R: {"load_max": Reproduced(
        math.nan, note="the orbit is unstable: no steady amplitude"), "exact": 1.0})
    Q.register("mass_claim")(lambda R: True)
    Q.register("order")(lambda R: 1.0)
    write_runs(cfg, results, lambda run: 100.0)
    row = {r.quantity: r for r in build(cfg, Q, results)}["load_max"]
    assert row.status == "inconclusive"
    assert row.flips == ["no value: the orbit is unstable: no steady amplitude"]


def test_a_verdict_without_a_level_below_its_baseline_is_inconclusive(edit_config, tmp_path):
    """A baseline at the grid's minimum has no coarser level to estimate its error from:
    the row says so and is not decided (never a verdict without an error bar)."""
    def edit(raw):
        reported_config(raw)
        raw["profiles"]["ci"]["scenes"]["fig07_fig08"] = {"resolution": {"K": 2}}
    cfg = load_paper(edit_config("saw_chain", edit), "ci")
    assert "fig07_fig08" in cfg.variant_skipped["coarser"]
    results = tmp_path / "results"
    write_runs(cfg, results, lambda run: 100.5)
    row = {r.quantity: r for r in build(cfg, quantities(), results)}["load_max"]
    assert row.status == "inconclusive"
    assert "no resolution level below the baseline" in row.flips[0]
    assert "K = 1: must be >= 2" in row.flips[0]


def test_level_error_is_richardson_with_the_observed_order():
    from mechrepro.validation import level_error

    for p in (1, 2, 4):
        exact = 3.0
        v = [exact + 0.7 * h ** p for h in (0.4, 0.2, 0.1)]
        e, order, ok, _ = level_error(*v, ratio=2.0, width=1.0)
        assert ok and order == pytest.approx(p) and e == pytest.approx(v[2] - exact)
    assert level_error(1.0, 1.0, 1.0 + 1e-13, 2.0, 1.0)[2]          # round-off: negligible
    assert not level_error(1.0, 1.1, 1.3, 2.0, 1e-3)[2]               # diverging
    # chain_drive Fig. 8b: the change of the peaks under the load at 2 / 3 / 4 points per pitch
    e, order, ok, how = level_error(-0.02, -0.09, -0.06, 1.5, 1.0)   # oscillating
    assert ok and e == pytest.approx(0.07) and math.isnan(order) and "oscillate" in how
    assert not level_error(1.0, 1.1, 0.9, 1.5, 1e-3)[2]               # oscillating, growing
    e, order, ok, how = level_error(math.nan, 1.0, 1.1, 2.0, 1.0)     # two levels
    assert ok and e == pytest.approx(0.1) and math.isnan(order)
    # two levels 1.5x apart, first order assumed: twice their difference
    assert level_error(math.nan, 1.0, 1.1, 1.5, 1.0)[0] == pytest.approx(0.2)
    assert level_error(math.nan, 1.0, 1.1, 10.0, 1.0)[0] == pytest.approx(0.1)   # >= |d2|


RIVAL = {"options": {"polygon": False}}   # a model change, the paper's numbers kept


def heavier(run):
    """The synthetic loads of the rival's model: 100x those of the paper's."""
    return 100.0 if run.get("options", {}).get("polygon") is False else 1.0


def with_rival(raw, changes):
    reported_config(raw)
    raw["rivals"] = {"heavy": {"why": "a model whose loads are 100x larger",
                               "removes": "the light chain", **changes}}


def test_a_counted_pass_needs_a_rival_that_fails(edit_config, tmp_path):
    results = tmp_path / "results"
    # no rival: the robust pass is reproduced, not discriminating, and not counted
    cfg = load_paper(edit_config("saw_chain", lambda raw: (reported_config(raw),
                                                           raw.update(rivals={}))), "ci")
    write_runs(cfg, results, lambda run: 100.5)
    rows = {r.quantity: r for r in build(cfg, quantities(), results)}
    assert rows["load_max"].status == "pass" and rows["load_max"].evidence == "not_discriminating"
    assert "no rival of the paper is declared" in rows["load_max"].cells()[9]
    assert claim(cfg, list(rows.values()))["independent"]["pass"] == 0
    # a rival (a model change, a solver option: the loads stand for a model 100x heavier
    # here) under which the check fails: counted, and every counted row runs under it
    cfg = load_paper(edit_config("saw_chain", lambda raw: with_rival(raw, RIVAL)), "ci")
    assert cfg.runs["fig07_fig08@rival-heavy"]["options"] == {"polygon": False}
    write_runs(cfg, results, lambda run: 100.5 * heavier(run))
    rows = {r.quantity: r for r in build(cfg, quantities(), results)}
    assert rows["load_max"].status == "pass" and rows["load_max"].evidence == "independent"
    assert rows["load_max"].rivals["heavy"][2] == "fails"
    assert rows["load_max"].rivals_text.startswith("heavy: fails (10050")
    assert "heavy" in rows["mass_claim"].rivals and not rows["order"].rivals
    # a rival that does not fail: not discriminating, said so
    write_runs(cfg, results, lambda run: 100.5)
    rows = {r.quantity: r for r in build(cfg, quantities(), results)}
    assert rows["load_max"].evidence == "not_discriminating"
    assert "no rival fails it" in rows["load_max"].cells()[9]
    table = discrimination(cfg, list(rows.values()))
    assert ["load_max", "fig08", "pass", "not_discriminating", "heavy", "the light chain",
            "100.5", "pass", "passes", False, False] in table


def test_a_rival_runs_one_level_coarser_where_the_check_passes_too(edit_config, tmp_path):
    """The rival's run is the coarser level's resolution with the model change; it
    counts only where the check passes at that level without the change."""
    results = tmp_path / "results"
    cfg = load_paper(edit_config("saw_chain", lambda raw: with_rival(raw, RIVAL)), "ci")
    fal = cfg.runs["fig07_fig08@rival-heavy"]
    assert fal["resolution"] == cfg.runs["fig07_fig08@coarser"]["resolution"]
    assert fal["resolution"] != cfg.runs["fig07_fig08"]["resolution"]
    assert cfg.variant_info["rival-heavy"]["level_of"] == {"fig07_fig08": "coarser"}

    def load(run):      # the levels by variant; the rival runs heavy at the coarser one
        heavy = heavier(run)
        return {"coarsest": coarsest, "coarser": coarser}.get(run.get("variant"), base) * (
            coarser / base if run.get("variant") == "rival-heavy" else 1.0) * heavy
    coarsest, coarser, base = 100.0, 100.0, 100.0
    write_runs(cfg, results, load)
    rows = {r.quantity: r for r in build(cfg, quantities(), results)}
    assert rows["load_max"].status == "pass" and rows["load_max"].evidence == "independent"
    assert rows["load_max"].rivals_text.endswith("at the coarser level)")
    # contracting levels 104 / 101.2 / 100.2: a pass by its error bar (100.2 +- 0.56 within
    # 1 %), but the coarser level alone fails, so failing there under the change shows nothing
    coarsest, coarser, base = 104.0, 101.2, 100.2
    write_runs(cfg, results, load)
    row = {r.quantity: r for r in build(cfg, quantities(), results)}["load_max"]
    assert row.status == "pass" and row.evidence == "not_discriminating"
    assert row.rivals["heavy"][2] == "fail, but the check gives fail at that level without it"


def test_a_rival_that_fails_most_counted_passes_credits_none_by_itself():
    """A sledgehammer (fails more than half of the counted passes, at least two) credits no
    row alone; a row another rival fails stays counted."""
    def row(q, **rivals):
        r = Row(q, {"evidence": "independent", "kind": "check", "artefact": "fig01"}, 1.0,
                status="pass")
        r.rivals = {n: ("fail" if o == "fails" else "pass", 0.0, o, "coarser")
                    for n, o in rivals.items()}
        return r
    rows = [row("a", blunt="fails", sharp="fails"), row("b", blunt="fails", sharp="passes"),
            row("c", blunt="passes", sharp="passes")]
    assert sledgehammers(rows) == {"blunt": 2}
    grade_rivals(rows)
    assert [r.evidence for r in rows] == ["independent", "not_discriminating",
                                          "not_discriminating"]
    assert "only the sledgehammer blunt (failing 2 of 3 counted passes) fails it" in rows[1].note
    assert "no rival fails it" in rows[2].note
    # one pass, one rival failing it: no sledgehammer (a rule for many rows, not one)
    rows = [row("a", blunt="fails")]
    assert sledgehammers(rows) == {}


def _range_ends(raw):
    raw["reported"]["load_max"]["depends_on"] = ["textbook_mass"]
    return "textbook_mass-"


def textbook_family(raw, samples: int):
    """textbook_mass and textbook_phase, Eq. (23)'s two unknowns, as one family."""
    ph = raw["parameters"]["textbook_phase"]
    ph.pop("numerical")
    ph.update(range=[-22.5, 22.5], range_why="one tooth")
    raw["families"] = {"textbook": {"members": ["textbook_mass", "textbook_phase"],
                                    "why": "Eq. (23)'s two unknowns", "samples": samples}}


def _family(raw):
    textbook_family(raw, 2)
    raw["reported"]["load_max"]["depends_on"] = ["textbook"]
    raw["reported"]["mass_claim"].pop("depends_on")     # a row without levels
    return "textbook-"


@pytest.mark.parametrize("variants", [_range_ends, _family], ids=["range_end", "family"])
def test_a_variant_of_an_assumed_constant_runs_one_level_coarser_and_moves_the_baseline(
        edit_config, tmp_path, variants):
    """A range end's or family member's run is the coarser level's resolution; the row
    judges the baseline moved by what the constants move the value at that level: the
    level's own error cancels (101.2 + 0.5 judged alone would fail the 1 % band, 100.2 +
    0.5 passes), a shift that takes the baseline out of the band flips the verdict.  (The
    baseline sits at the upper end of textbook_mass: that end is the baseline run, read as
    it is.)"""
    prefix = []

    def config(raw):
        reported_config(raw)
        prefix.append(variants(raw))
    cfg = load_paper(edit_config("saw_chain", config), "ci")
    names = [v for v in cfg.variants
             if v.startswith(prefix[0]) and f"fig07_fig08@{v}" in cfg.runs]
    assert names
    for v in names:
        assert cfg.runs[f"fig07_fig08@{v}"]["resolution"] == cfg.runs["fig07_fig08@coarser"]["resolution"]
        assert cfg.variant_info[v]["level_of"] == {"fig07_fig08": "coarser"}
    results = tmp_path / "results"

    def row(shift):
        write_runs(cfg, results, lambda run: {"coarsest": 104.0, "coarser": 101.2}.get(
            run.get("variant"), 100.2) + (101.2 - 100.2 + shift
                                          if run.get("variant", "").startswith(prefix[0]) else 0.0))
        return {r.quantity: r for r in build(cfg, quantities(), results)}["load_max"]
    r = row(0.5)
    assert r.status == "pass", r.flips
    moved = [c for c in r.checks if c[0] in names]
    assert moved and all(c[2] == pytest.approx(100.7) and c[3] == "pass" for c in moved)
    assert all("shift at the coarser level" in c[4] for c in moved)
    r = row(2.0)
    assert r.status == "inconclusive" and "fail" in " ".join(r.flips)


def test_a_family_is_checked_at_its_joint_corners_and_samples(edit_config, tmp_path):
    def fam(raw):
        reported_config(raw)
        textbook_family(raw, 3)
        raw["reported"]["mass_claim"]["depends_on"] = ["textbook"]
    cfg = load_paper(edit_config("saw_chain", fam), "ci")
    members = sorted(v for v in cfg.variants if v.startswith("textbook-"))
    assert members == ["textbook-c00", "textbook-c01", "textbook-c02", "textbook-c03",
                       "textbook-s00", "textbook-s01", "textbook-s02"]
    c = {v: cfg.runs[f"fig07_fig08@{v}"]["parameters"] for v in members if f"fig07_fig08@{v}" in cfg.runs}
    assert c["textbook-c03"]["textbook_mass"] == pytest.approx(0.102464)
    assert c["textbook-c02"]["textbook_phase"] == pytest.approx(math.radians(22.5))
    assert c["textbook-c02"]["textbook_mass"] == pytest.approx(1.296e-3)
    assert "textbook-c01" not in c    # the baseline itself (both at the range ends it takes)
    # the same samples on every load (seeded from the config)
    again = load_paper(edit_config("saw_chain", fam), "ci")
    assert all(again.runs[f"fig07_fig08@{v}"]["parameters"] == cfg.runs[f"fig07_fig08@{v}"]["parameters"]
               for v in members if v.endswith(("s00", "s01", "s02")))
    results = tmp_path / "results"
    write_runs(cfg, results, lambda run: 100.5)
    rows = {r.quantity: r for r in build(cfg, quantities(), results)}
    # corners with the low mass (one drive link, 1.296 g) fail the > 10 g claim
    assert rows["mass_claim"].status == "inconclusive"
    assert "family textbook member c00" in " ".join(rows["mass_claim"].flips)
    with pytest.raises(ConfigError, match="member of family 'textbook'"):
        load_paper(edit_config("saw_chain", lambda raw: (
            fam(raw), raw["reported"]["mass_claim"].update(depends_on=["textbook_mass"]))), "ci")


def test_undeclared_reads_and_missing_functions_are_refused(paper):
    cfg, results = paper
    write_runs(cfg, results, lambda run: 100.0)
    with pytest.raises(ValidationError, match="speed_12000.*do not declare"):
        build(cfg, quantities(reads_extra=True), results)
    Q = Quantities("saw_chain")
    Q.register("load_max")(lambda R: 1.0)
    with pytest.raises(ValidationError, match="without an extraction function"):
        build(cfg, Q, results)


@pytest.mark.parametrize("edit, message", [
    (lambda raw: raw["reported"]["load_max"].update(reads=["nope"]), "neither a scene nor a study"),
    (lambda raw: raw["reported"]["mass_claim"].update(depends_on=["teeth"]), "not an assumed parameter"),
    (lambda raw: raw["parameters"]["textbook_mass"].pop("range"), "has no range"),
    (lambda raw: raw["parameters"]["textbook_mass"].update(range=[200, 300]), "outside its range"),
    (lambda raw: raw["parameters"]["textbook_phase"].update(calibrated_on="load_max", numerical=None)
     or raw["parameters"]["textbook_phase"].pop("numerical"), "evidence: calibration"),
    (lambda raw: raw.pop("refine"), r"resolution: unknown key .*'K' was unexpected.*allowed: none \(a resolution knob is declared under refine:\)"),
    (lambda raw: raw["refine"]["K"].update(factor=1), "refine.K = 1: a knob that is never refined"),
    (lambda raw: raw["reported"]["load_max"].update(rivals=["nope"]), "not declared under rivals"),
    (lambda raw: raw.update(rivals={"x": {"why": "y", "removes": "z", "parameters": {"nope": 1}}}),
     "not a parameter"),
    (lambda raw: raw.update(rivals={"x": {"why": "y"}}), "removes"),
    (lambda raw: raw["reported"]["order"].pop("evidence_why"), "evidence_why"),
    (lambda raw: raw["reported"]["load_max"].pop("why"), "why"),
    (lambda raw: raw["profiles"]["ci"]["scenes"].update(typo={"resolution": {"K": 3}}),
     "profiles.ci.scenes.typo: not one of the file's scenes"),
])
def test_reported_block_errors_name_the_key(edit_config, edit, message):
    path = edit_config("saw_chain", lambda raw: (reported_config(raw), edit(raw)))
    with pytest.raises(ConfigError, match=message):
        load_paper(path, "ci")


def _table(path, rows):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("quantity,reproduced_value,status\n"
                    + "".join(f"{q},{v},{s}\n" for q, v, s in rows))


def test_reference_tolerance_is_derived_from_the_platform_spread(edit_config, tmp_path):
    path = edit_config("saw_chain", reported_config)
    config_dir = path.parent.parent
    res = {}
    for name, load in (("native", 100.0), ("other", 100.0 + 1e-5)):
        res[name] = tmp_path / name
        _table(res[name] / "saw_chain" / "tables" / "validation.csv",
               [("load_max", load, "pass"), ("exact", 3.0, "info")])
    ref.derive(res, tmp_path / "ref", config_dir, ["saw_chain"], "ci")
    rows = {r["quantity"]: r for r in read_table(tmp_path / "ref" / "ci" / "saw_chain.csv")}
    conf = ref.settings(config_dir)
    assert float(rows["load_max"]["spread"]) == pytest.approx(1e-5, rel=1e-6)
    assert float(rows["load_max"]["tolerance"]) == pytest.approx(conf["safety"] * 1e-5, rel=1e-6)
    assert float(rows["exact"]["tolerance"]) == pytest.approx(conf["floor"] * 3.0)
    # within tolerance: passes; beyond, or a changed verdict: drift, named
    _table(tmp_path / "now" / "saw_chain" / "tables" / "validation.csv",
           [("load_max", 100.0 + 5e-5, "pass"), ("exact", 3.0, "info")])
    ref.check(tmp_path / "now", tmp_path / "ref", ["saw_chain"], "ci")
    _table(tmp_path / "now" / "saw_chain" / "tables" / "validation.csv",
           [("load_max", 100.0 + 5e-4, "fail"), ("exact", 3.0, "info")])
    with pytest.raises(ref.DriftError, match="verdict pass in reference, now fail"):
        ref.check(tmp_path / "now", tmp_path / "ref", ["saw_chain"], "ci")
    _table(tmp_path / "now" / "saw_chain" / "tables" / "validation.csv",
           [("load_max", "#garbage#", "pass"), ("exact", 3.0, "info")])
    with pytest.raises(ref.DriftError, match=r"line 2 \(load_max\).*.#garbage#. is not a number"):
        ref.check(tmp_path / "now", tmp_path / "ref", ["saw_chain"], "ci")


def test_a_verdict_that_differs_between_platforms_is_refused(edit_config, tmp_path):
    path = edit_config("saw_chain", reported_config)
    res = {}
    for name, status in (("native", "pass"), ("other", "fail")):
        res[name] = tmp_path / name
        _table(res[name] / "saw_chain" / "tables" / "validation.csv", [("load_max", 1.0, status)])
    with pytest.raises(ref.DriftError, match="load_max: pass natively, fail under other"):
        ref.derive(res, tmp_path / "ref", path.parent.parent, ["saw_chain"], "ci")


def test_flips_found_by_the_extraction_make_a_verdict_inconclusive(paper):
    cfg, results = paper
    write_runs(cfg, results, lambda run: 100.5)
    Q = quantities()
    fn = Q._fn["load_max"]

    def with_corner(R):
        out = fn(R)
        out["load_max"] = Reproduced(out["load_max"], flips=["fail at the joint corner (a, b)"])
        return out
    Q._fn = {k: (with_corner if v is fn else v) for k, v in Q._fn.items()}
    Q._names[with_corner] = Q._names.pop(fn)
    rows = {r.quantity: r for r in build(cfg, Q, results)}
    assert rows["load_max"].status == "inconclusive"
    assert "joint corner" in rows["load_max"].cells()[9]


def test_a_check_without_a_value_is_no_pass_and_refused_members_are_left_out(paper):
    cfg, results = paper
    write_runs(cfg, results, lambda run: 100.5)
    Q = quantities()
    fn = Q._fn["mass_claim"]

    def nan_claim(R):
        return float("nan")
    Q._fn = {k: (nan_claim if v is fn else v) for k, v in Q._fn.items()}
    Q._names[nan_claim] = Q._names.pop(fn)
    rows = {r.quantity: r for r in build(cfg, Q, results)}
    assert rows["mass_claim"].status == "inconclusive"
    assert "could not be evaluated" in rows["mass_claim"].cells()[9]
