"""One test per figure or table of each paper (`pytest -k fig08`, `pytest -k saw_chain`).

Each test reads the rows of one artefact from the ci pipeline's validation table (the
session's run of the workflow; when only these tests are selected, a run of the selected
artefacts' runs and rows alone) and holds them to the committed reference: the same
verdict, and the value within the tolerance measured across platform variants.  What
the paper reports, with its tolerance and the reason for it, is in the paper's config
(`reported:`); the rows' evidence classes say what each pass or fail is evidence of.
"""
import math

import pytest

from conftest import ROOT
from mechrepro.validation import read_table
from mechrepro.inputs import read_yaml

PAPERS = read_yaml((ROOT / "config" / "config.yaml"))["papers"]


def artefacts():
    for paper in PAPERS:
        raw = read_yaml((ROOT / "config" / "papers" / f"{paper}.yaml"))
        for art in sorted({spec["artefact"] for spec in raw.get("reported", {}).values()}):
            yield pytest.param(paper, art, id=f"{paper}-{art}", marks=pytest.mark.slow)


@pytest.mark.parametrize("paper, artefact", list(artefacts()))
def test_artefact_matches_reference(workflow, paper, artefact):
    work, _ = workflow
    tables = work / "results" / paper / "tables"
    # the whole paper's table, or, when only per-artefact tests were selected, the table of
    # the selected artefacts' rows (conftest.workflow)
    table = tables / "validation.csv"
    if not table.exists():
        (table,) = tables.glob("validation-*.csv")
    rows = [r for r in read_table(table) if r["artefact"] == artefact]
    assert rows, f"no validation rows for {paper} {artefact}"
    ref = {r["quantity"]: r for r in read_table(ROOT / "results" / "reference" / "ci" / f"{paper}.csv")}
    for r in rows:
        q = r["quantity"]
        assert q in ref, f"{q}: not in the reference (make reference)"
        if ref[q]["basis"] == "timing":
            continue
        assert r["status"] == ref[q]["status"], (q, r["status"], ref[q]["status"], r["note"])
        if ref[q]["basis"] == "value" and r["reproduced_value"]:
            now, then = float(r["reproduced_value"]), float(ref[q]["reproduced_value"])
            if not (math.isnan(now) and math.isnan(then)):
                assert abs(now - then) <= float(ref[q]["tolerance"]), (q, now, then, ref[q]["tolerance"])


def test_one_artefact_alone_gives_the_rows_of_the_whole_run(workflow, tmp_path):
    """The workflow cut down to one figure (`--config artefacts=[...]`, what `pytest -k
    saw_chain-fig07` runs) solves only that figure's runs and writes its rows exactly as
    the whole paper's run does, and refuses an artefact no paper has."""
    from conftest import copy_workflow, snakemake

    work, _ = workflow
    alone = copy_workflow(tmp_path)
    snakemake(alone, "papers=[saw_chain]", "artefacts=[saw_chain-fig07]")
    tables = alone / "results" / "saw_chain" / "tables"
    assert [f.name for f in tables.glob("*.csv")] == ["validation-fig07.csv"]
    assert not (alone / "results" / "saw_chain" / "notebook.ipynb").exists()
    whole, cut = ([r for r in read_table(t) if r["artefact"] == "fig07"]
                  for t in (work / "results" / "saw_chain" / "tables" / "validation.csv",
                            tables / "validation-fig07.csv"))
    assert cut and cut == whole
    out = snakemake(alone, "papers=[saw_chain]", "artefacts=[fig99]", "-n", check=False)
    assert "artefacts: ['fig99']: no reported row" in out and "allowed:" in out
