"""One test per declared figure (config ``figures``), on the session's ci results: the
notebook drew it through its declaration (PaperResults.figure: the declared function, opening
only the declared runs and studies) and the lint found nothing in it (no two texts overlap, no
legend over data, every labelled series visible, axes with units: recorded in the PNG by
mechrepro.plotting.savefig; drawing it again here would repeat that work for the same
pixels)."""
import importlib

import pytest

from conftest import ROOT
from mechrepro.inputs import read_yaml

FIGURES = [(paper, fig) for paper in read_yaml(ROOT / "config" / "config.yaml")["papers"]
           for fig in read_yaml(ROOT / "config" / "papers" / f"{paper}.yaml")["figures"]]


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
