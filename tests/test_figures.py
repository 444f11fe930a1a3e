"""One test per declared figure (config ``figures``), on the session's ci results: the
notebook drew it through its declaration (PaperResults.figure: the declared function, opening
only the declared runs and studies) and the lint found nothing in it (no two texts overlap, no
legend over data, every labelled series visible, axes with units: recorded in the PNG by
mechrepro.plotting.savefig; drawing it again here would repeat that work for the same
pixels).  One test per declared table (config ``tables``): the notebook wrote it, with the
header its declared function gives from the declared runs and studies."""
import csv
import importlib

import pytest

from conftest import ROOT
from mechrepro.inputs import read_yaml

PAPERS = {paper: read_yaml(ROOT / "config" / "papers" / f"{paper}.yaml")
          for paper in read_yaml(ROOT / "config" / "config.yaml")["papers"]}
FIGURES = [(paper, fig) for paper, raw in PAPERS.items() for fig in raw["figures"]]
TABLES = [(paper, table) for paper, raw in PAPERS.items() for table in raw.get("tables", {})]


@pytest.mark.parametrize("paper,figure", FIGURES, ids=[f"{p}-{f}" for p, f in FIGURES])
def test_figure_is_drawn_from_what_it_declares_and_passes_the_lint(workflow, paper, figure):
    from mechrepro.config import load_paper
    from mechrepro.plotting import lint_record

    work, _ = workflow
    cfg = load_paper(work / "config" / "papers" / f"{paper}.yaml", "ci")
    spec = cfg.figure(figure)
    module, _, function = spec["draw"].rpartition(".")
    package = f"mechrepro.models.{paper}"
    assert callable(getattr(importlib.import_module(f"{package}.{module}" if module else package),
                            function))
    res = work / "results" / paper
    for name in spec["reads"]:
        assert (res / "runs" / f"{name}.nc").exists() or (res / "studies" / f"{name}.nc").exists(), name
    assert lint_record(res / "figures" / f"{figure}.png") == []


@pytest.mark.parametrize("paper,table", TABLES, ids=[f"{p}-{t}" for p, t in TABLES])
def test_table_is_made_from_what_it_declares(workflow, paper, table, monkeypatch):
    from mechrepro.results import PaperResults

    work, _ = workflow
    monkeypatch.chdir(work)     # the config cache of PaperResults, beside the workflow's
    R = PaperResults(paper, "results", f"config/papers/{paper}.yaml", "ci")
    res = work / "results" / paper
    for name in R.cfg.table(table)["reads"]:
        assert (res / "runs" / f"{name}.nc").exists() or (res / "studies" / f"{name}.nc").exists(), name
    header, _ = R.make(table)   # the declared function, opening only the declared reads
    with open(res / "tables" / f"{table}.csv", newline="") as f:
        assert next(csv.reader(f)) == [str(h) for h in header]
