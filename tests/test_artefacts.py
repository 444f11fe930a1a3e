"""One test per figure or table of each paper (`pytest -k fig08`, `pytest -k saw_chain`).

Each test reads the rows of one artefact from the ci pipeline's validation table (the
session's run of the workflow) and holds them to the committed reference: the same
verdict, and the value within the tolerance measured across platform variants.  What
the paper reports, with its tolerance and the reason for it, is in the paper's config
(`reported:`); the rows' evidence classes say what each pass or fail is evidence of.
"""
import math

import pytest
import yaml

from conftest import ROOT
from mechrepro.validation import read_table

PAPERS = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())["papers"]


def artefacts():
    for paper in PAPERS:
        raw = yaml.safe_load((ROOT / "config" / "papers" / f"{paper}.yaml").read_text())
        for art in sorted({spec["artefact"] for spec in raw.get("reported", {}).values()}):
            yield pytest.param(paper, art, id=f"{paper}-{art}", marks=pytest.mark.slow)


@pytest.mark.parametrize("paper, artefact", list(artefacts()))
def test_artefact_matches_reference(workflow, paper, artefact):
    work, _ = workflow
    rows = [r for r in read_table(work / "results" / paper / "tables" / "validation.csv")
            if r["artefact"] == artefact]
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
