"""One test per figure or table of each paper (`pytest -k fig08`, `pytest -k saw_chain`).

Each test reads the rows of one artefact from the ci pipeline's validation table (the
session's run of the workflow; when only these tests are selected, no pipeline: the
selected artefacts' runs and rows alone, `python -m mechrepro.cli artefact`) and holds them to the committed reference: the same
verdict, and the value within the tolerance measured across platform variants.  What
the paper reports, with its tolerance and the reason for it, is in the paper's config
(`reported:`); the rows' evidence classes say what each pass or fail is evidence of.
"""
import math
import os

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
    """`python -m mechrepro.cli artefact` (what `pytest -k saw_chain-fig07` runs, without
    the workflow) solves only the runs that figure's rows read and writes its rows exactly
    as the whole paper's run does, and refuses an artefact no paper has."""
    import shutil
    import subprocess
    import sys

    from mechrepro.config import load_paper
    from mechrepro.validation import for_artefacts

    work, _ = workflow
    shutil.copytree(ROOT / "config", tmp_path / "config")
    cli = [sys.executable, "-m", "mechrepro.cli", "artefact", "results", "config", "ci"]
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    out = subprocess.run([*cli, "saw_chain-fig07"], cwd=tmp_path, capture_output=True,
                         text=True, env=env)
    assert out.returncode == 0, out.stderr[-3000:]
    res = tmp_path / "results"
    assert [p.name for p in res.iterdir()] == ["saw_chain"]
    tables = res / "saw_chain" / "tables"
    assert [f.name for f in tables.glob("*.csv")] == ["validation-fig07.csv"]
    cut = for_artefacts(load_paper(tmp_path / "config" / "papers" / "saw_chain.yaml", "ci"),
                        ["fig07"])
    assert {f.stem for f in (res / "saw_chain" / "runs").glob("*.nc")} == set(cut.runs)
    whole, alone = ([r for r in read_table(t) if r["artefact"] == "fig07"]
                    for t in (work / "results" / "saw_chain" / "tables" / "validation.csv",
                              tables / "validation-fig07.csv"))
    assert alone and alone == whole
    out = subprocess.run([*cli, "fig99"], cwd=tmp_path, capture_output=True, text=True, env=env)
    assert out.returncode == 2
    assert "artefacts ['fig99']: no reported row" in out.stderr and "allowed:" in out.stderr
