"""The numbers in README.md and docs/<paper>.md come from the run (mechrepro.docs), never
typed: their blocks match what the configs and the committed default references say."""
import csv
import importlib
import re
from pathlib import Path

import pytest

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
        readme["not_discriminating"] = int(cells[8])
        counted_nd = sum(r.get("evidence") == "not_discriminating" for r in ref)
        assert readme == {**{s: counted.count(s) for s in docs.VERDICTS},
                          "not_discriminating": counted_nd}, (
            f"{paper}: README {readme}; regenerate it from a default run: "
            "python -m mechrepro.docs README.md results")


def test_every_paper_page_lists_its_knobs_as_declared():
    """docs/<paper>.md's knob table is its paper's refine: block (config only, no run)."""
    for paper in docs._papers(ROOT / "config"):
        page = (ROOT / "docs" / f"{paper}.md").read_text()
        assert docs.block(page, "knobs") == docs.knobs(ROOT / "results" / paper, ROOT / "config"), (
            f"docs/{paper}.md: regenerate its knobs: python -m mechrepro.docs docs/{paper}.md results")


PAPERS = docs._papers(ROOT / "config")


def _page(paper):
    return (ROOT / "docs" / f"{paper}.md").read_text()


def _reference(paper):
    with open(ROOT / "results/reference/default" / f"{paper}.csv", newline="") as fh:
        return {r["quantity"]: r for r in csv.DictReader(fh)}


@pytest.mark.parametrize("paper", PAPERS)
def test_every_block_a_paper_page_marks_has_a_generator(paper):
    try:
        own = set(importlib.import_module(f"mechrepro.models.{paper}.docs").BLOCKS)
    except ModuleNotFoundError:
        own = set()
    names = set(docs.BLOCK_NAME.findall(_page(paper)))
    assert own <= names <= own | set(docs.PAPER_BLOCKS)


@pytest.mark.parametrize("paper", PAPERS)
def test_a_paper_pages_verdicts_and_counts_are_the_committed_default_reference(paper):
    """Its verdict table holds every row of the evidence classes it names (all but info
    rows when it names none), each with the reference's verdict and value; its counts are
    the reference's independent ones."""
    page, ref = _page(paper), _reference(paper)
    hint = f"regenerate: python -m mechrepro.docs docs/{paper}.md results (default run)"
    if "<!-- run:verdicts" in page:
        evidence = re.search(r"<!-- run:verdicts([ \w]*) -->", page).group(1).split()
        lines = docs.block(page, "verdicts").splitlines()
        head = [c.strip() for c in lines[0].split("|")]
        rows = [dict(zip(head, (c.strip() for c in line.split("|")))) for line in lines[2:]]
        got = {r["row"].strip("`"): r for r in rows}
        assert set(got) == {q for q, r in ref.items() if r["status"] != "info"
                            and (not evidence or r["evidence"] in evidence)}, hint
        for q, r in got.items():
            assert r["verdict"] == ref[q]["status"], (q, hint)
            if ref[q]["basis"] == "timing":     # a measured time: the reference compares none
                continue
            if ref[q]["reproduced_value"] in ("", "nan"):     # no value: its verdict only
                continue
            assert float(r["ours"].split()[0]) == pytest.approx(
                float(ref[q]["reproduced_value"]), rel=1e-5, abs=1e-12), (q, hint)
    if "<!-- run:counts" in page:
        counted = [r["status"] for r in ref.values() if r["evidence"] == "independent"]
        text = docs.block(page, "counts")
        for s in ("pass", "fail", "inconclusive"):
            assert re.search(rf"\b{counted.count(s)} {s}\b", text), (s, text, hint)


def _output_table() -> list[list[str]]:
    """The path patterns of README's "What comes out", one list per row: a name without a
    directory lies in the directory of the full path before it in the same cell."""
    section = README.split("## What comes out", 1)[1].split("\n## ", 1)[0]
    rows = []
    for line in section.splitlines():
        if not line.startswith("| `"):
            continue
        pats, here = [], ""
        for item in re.findall(r"`([^`]+)`", line.split(" | ", 1)[0]):
            if item.startswith("results/"):
                here = item if item.endswith("/") else item.rsplit("/", 1)[0] + "/"
                pats.append(item)
            else:
                pats.append(here + item)
        rows.append(pats)
    return rows


def _regex(pattern: str, papers: list[str]) -> re.Pattern:
    parts = re.split(r"(<paper>|<[a-z]+>|\*)", pattern)
    rx = "".join("(" + "|".join(papers) + ")" if p == "<paper>" else "[^/@]+" if p.startswith("<")
                 else "[^/]*" if p == "*" else re.escape(p) for p in parts)
    return re.compile(rx + (".+" if pattern.endswith("/") else ""))


def test_the_readme_output_table_is_what_a_run_writes(tmp_path):
    """Every path pattern of README's "What comes out" names a file the workflow declares
    (a dry run of a fresh ci copy: outputs, logs, benchmarks) or one `make reproduce` writes
    after Snakemake (mechrepro.plan); and every such file is in the table."""
    from conftest import copy_workflow, snakemake
    from mechrepro.plan import main as plan

    work = copy_workflow(tmp_path)
    out = snakemake(work, "-n")
    files = {f.replace(" (update)", "").strip()
             for kind, line in re.findall(r"^\s+(output|log|benchmark): (.*)$", out, re.M)
             for f in line.split(", ")}
    log = tmp_path / "plan" / "run.snakemake.log"
    log.parent.mkdir()
    log.write_text("rule report:\nError in rule report:\n")
    assert plan([str(work / "results"), str(log), "--status", "1"]) == 0
    files |= {str(f.relative_to(work)) for f in (work / "results").iterdir() if f.is_file()}
    files = {f for f in files if not Path(f).name.startswith(".")}  # records, bookkeeping
    assert "results/report/summary.csv" in files and "results/rerun_plan.html" in files
    papers = docs._papers(ROOT / "config")
    table = {p: _regex(p, papers) for row in _output_table() for p in row}
    assert len(table) > 10
    unmatched = [p for p, rx in table.items() if not any(rx.fullmatch(f) for f in files)]
    assert not unmatched, f"README names paths no run writes: {unmatched}"
    untold = sorted(f for f in files if not any(rx.fullmatch(f) for rx in table.values()))
    assert not untold, f"README's output table misses: {untold[:20]}"
