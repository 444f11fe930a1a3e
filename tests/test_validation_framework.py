"""The validation builder, the config's reported block and the platform-derived reference."""
import math

import numpy as np
import pytest
import xarray as xr
import yaml

from mechrepro import io as mio
from mechrepro import reference as ref
from mechrepro.config import ConfigError, load_paper
from mechrepro.validation import (Quantities, Reproduced, ValidationError, build, claim,
                                  read_table, write_table)


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
    raw["refine"] = {"K": 2}
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
    assert cfg.runs["fig07_fig08@finer"]["resolution"]["K"] == 2 * cfg.runs["fig07_fig08"]["resolution"]["K"]
    assert cfg.runs["fig07_fig08@textbook_mass-lo"]["parameters"]["textbook_mass"] == pytest.approx(1.296e-3)
    assert "cost_of_accuracy@finer" in cfg.studies
    # info rows are not re-checked, and the check row does not read the study
    assert "cost_of_accuracy@textbook_mass-lo" not in cfg.studies
    assert "speed_12000@finer" not in cfg.runs


def test_a_verdict_that_flips_at_finer_resolution_is_inconclusive(paper):
    cfg, results = paper
    # the load converges to 100.5 N: within 1 % at K, 2 % off at 2K -> flips
    write_runs(cfg, results, lambda run: 100.5 if "@finer" not in run["run"] else 102.0)
    rows = {r.quantity: r for r in build(cfg, quantities(), results)}
    assert rows["load_max"].status == "inconclusive"
    assert "fail at the next finer resolution" in rows["load_max"].cells()[9]
    assert rows["exact"].status == "info" and "exact is v" in rows["exact"].cells()[9]
    # the mass claim (textbook_mass > 10 g) fails at the low end of its range
    assert rows["mass_claim"].status == "inconclusive"
    assert "textbook_mass = 1.296 g" in " ".join(rows["mass_claim"].flips)
    assert rows["order"].status == "pass"


def test_robust_verdicts_and_claim_counts_only_independent_rows(paper, tmp_path):
    cfg, results = paper
    write_runs(cfg, results, lambda run: 100.5)
    Q = quantities()
    rows = build(cfg, Q, results)
    st = {r.quantity: r.status for r in rows}
    assert st["load_max"] == "pass"
    c = claim(cfg, rows)
    assert c["independent"] == {"pass": 1, "fail": 0, "inconclusive": 1}
    assert c["counts"]["construction"] == {"pass": 1}
    assert c["claim"] == "partial"
    out = write_table(rows, tmp_path / "validation.csv")
    table = read_table(out)
    assert {r["quantity"]: r["evidence"] for r in table} == {
        "load_max": "independent", "mass_claim": "independent", "order": "construction",
        "exact": "independent"}
    assert list(table[0])[:9] == ["quantity", "source", "paper_value", "reproduced_value", "unit",
                                  "rel_error", "tolerance", "status", "evidence"]


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
    (lambda raw: raw.pop("refine"), "refine: no factor for resolution key 'K'"),
    (lambda raw: raw["reported"]["order"].pop("evidence_why"), "evidence_why"),
    (lambda raw: raw["reported"]["load_max"].pop("why"), "why"),
    (lambda raw: raw["profiles"]["ci"]["scenes"].update(typo={"resolution": {"K": 3}}), "effects"),
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
