"""One test per declared figure (config ``figures``): drawn by its declared function from
the runs and studies it declares, out of the session's ci results, and linted (no two texts
overlap, no legend over data, every labelled series visible, axes with units)."""
import pytest

from conftest import ROOT
from mechrepro.inputs import read_yaml

FIGURES = [(paper, fig) for paper in read_yaml(ROOT / "config" / "config.yaml")["papers"]
           for fig in read_yaml(ROOT / "config" / "papers" / f"{paper}.yaml")["figures"]]


@pytest.mark.parametrize("paper,figure", FIGURES, ids=[f"{p}-{f}" for p, f in FIGURES])
def test_figure_draws_from_what_it_declares_and_passes_the_lint(workflow, paper, figure):
    from mechrepro.plotting import lint, plt
    from mechrepro.results import PaperResults

    work, _ = workflow
    R = PaperResults(paper, work / "results", work / "config" / "papers" / f"{paper}.yaml", "ci")
    fig = R.draw(figure)
    try:
        assert lint(fig) == []
    finally:
        plt.close(fig)
