"""The numbers in README.md come from the run (mechrepro.docs), never typed: its blocks
match what the configs and the committed default references say."""
import csv

from conftest import ROOT
from mechrepro import docs

README = (ROOT / "README.md").read_text()


def test_every_block_of_the_readme_has_a_generator():
    assert set(docs.BLOCK_NAME.findall(README)) == set(docs.README_BLOCKS)


def test_the_assumed_constants_are_the_configs():
    assert docs.block(README, "assumed_constants") == docs.assumed_constants(
        ROOT / "results", ROOT / "config")


def test_the_claim_counts_are_the_committed_default_references():
    rows = [line.split("|") for line in docs.block(README, "claims").splitlines()[2:]]
    assert [c[1].strip().strip("`") for c in rows] == docs._papers(ROOT / "config")
    for cells in rows:
        paper = cells[1].strip().strip("`")
        with open(ROOT / "results/reference/default" / f"{paper}.csv", newline="") as fh:
            ref = list(csv.DictReader(fh))
        counted = [r["status"] for r in ref if r.get("evidence") == "independent"]
        readme = dict(zip(docs.VERDICTS, (int(c) for c in cells[4:8])))
        assert readme == {s: counted.count(s) for s in docs.VERDICTS}, (
            f"{paper}: README {readme}; regenerate it from a default run: "
            "python -m mechrepro.docs README.md results")


def test_every_paper_page_lists_its_knobs_as_declared():
    """docs/<paper>.md's knob table is its paper's refine: block (config only, no run)."""
    for paper in docs._papers(ROOT / "config"):
        page = (ROOT / "docs" / f"{paper}.md").read_text()
        assert docs.block(page, "knobs") == docs.knobs(ROOT / "results" / paper, ROOT / "config"), (
            f"docs/{paper}.md: regenerate its knobs: python -m mechrepro.docs docs/{paper}.md results")
