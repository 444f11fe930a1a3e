"""The whole workflow on the ci profile, in a copy: outputs, reference, incremental reruns.

Slow (it runs Snakemake and every paper's notebook) but part of `make test`: this is the
check CI relies on to compare the fast profile against results/reference/ci.
"""
import json
import re
import subprocess
from html.parser import HTMLParser

import pytest

from conftest import ROOT, SNAKEMAKE, snakemake
from mechrepro.provenance import file_sha256
from mechrepro.validation import read_table
from mechrepro.inputs import read_yaml

pytestmark = pytest.mark.slow


def scheduled(dry_run_output: str) -> set[str]:
    """{'rule' or 'rule[wildcards]'} of every job in a dry run."""
    jobs, current = set(), None
    for line in dry_run_output.splitlines():
        m = re.match(r"^(?:local)?rule (\w+):", line)
        if m:
            if current:
                jobs.add(current)
            current = m.group(1)
        elif current and line.strip().startswith("wildcards:"):
            current += "[" + line.split(":", 1)[1].strip() + "]"
    if current:
        jobs.add(current)
    return jobs


class Images(HTMLParser):
    def __init__(self):
        super().__init__()
        self.src = []

    def handle_starttag(self, tag, attrs):
        if tag == "img":
            self.src.append(dict(attrs)["src"])


def test_pipeline_writes_every_output_and_matches_reference(workflow):
    work, log = workflow
    papers = read_yaml((work / "config" / "config.yaml"))["papers"]
    res = work / "results"
    for paper in papers:
        cfg = read_yaml((work / "config" / "papers" / f"{paper}.yaml"))
        for fig in cfg["figures"]:
            assert (res / paper / "figures" / f"{fig}.png").stat().st_size > 1000
        for table in cfg.get("tables", ["validation"]):
            assert (res / paper / "tables" / f"{table}.csv").exists()
        assert (res / paper / "notebook.ipynb").exists()
        assert list((res / paper / "benchmarks").glob("*.tsv"))
        assert not list(res.rglob("*.part*")), "temporary files left behind"
    # the drift check ran against the committed reference of every paper
    check = (res / "report" / "reference_check.txt").read_text()
    assert check.splitlines()[0] == "reference check, profile ci: OK", check
    for paper in papers:
        assert re.search(rf"^{paper}: \d+ quantities within tolerance", check, re.M), check
    # manifest: checksums of every archived file
    man = json.loads((res / "archive" / "manifest.json").read_text())
    assert man["profile"] == "ci" and man["config_hash"] and man["package_versions"]["numpy"]
    for rel, sha in man["files"].items():
        assert file_sha256(res / rel) == sha
    # the report links every figure of every paper, and the files exist
    page = (res / "report" / "index.html").read_text()
    imgs = Images()
    imgs.feed(page)
    n_figures = sum(len(read_yaml((work / "config" / "papers" / f"{p}.yaml")
                                       )["figures"]) for p in papers)
    assert len(imgs.src) == n_figures + 1  # + the cross-paper cost-of-accuracy figure
    assert "cost_of_accuracy_all.png" in imgs.src
    summary = (res / "report" / "summary.csv").read_text().splitlines()
    assert [line.split(",")[0] for line in summary[1:]] == papers
    for src in imgs.src:
        assert (res / "report" / src).resolve().exists(), src
    assert page.count('class="pass"') + page.count('class="fail"') > 0


def test_the_summary_figure_passes_the_lint(workflow):
    """The cross-paper summary figure, drawn by the framework, with the lint's record in its
    PNG as every paper figure has (tests/test_figures.py)."""
    from mechrepro.plotting import lint_record

    work, _ = workflow
    assert lint_record(work / "results" / "report" / "cost_of_accuracy_all.png") == []


def test_no_change_schedules_nothing(workflow):
    work, _ = workflow
    out = snakemake(work, "-n")
    assert "Nothing to be done" in out, out[-3000:]


def test_one_parameter_reruns_exactly_its_runs_notebook_and_report(workflow):
    """Changing the speed of one scene reruns the solver job its runs (baseline and verdict
    variants) are batched in, the paper's validation and notebook, and the cross-paper
    steps; nothing of the other papers, and no gather (the batch stacks its studies)."""
    from mechrepro.config import load_paper

    work, _ = workflow
    path = work / "config" / "papers" / "saw_chain.yaml"
    original = path.read_text()
    before = load_paper(path, "ci").runs
    try:
        path.write_text(original.replace("parameters: {sprocket_speed: 12000}",
                                         "parameters: {sprocket_speed: 11000}"))
        after = load_paper(path, "ci").runs
        jobs = scheduled(snakemake(work, "-n"))
    finally:
        path.write_text(original)
    changed = sorted(r for r in after if after[r] != before.get(r))
    assert changed and all(r.startswith("speed_12000") for r in changed), changed
    assert jobs == {"solve_saw_chain__batch", "validate_saw_chain",
                    "notebook_saw_chain", "summary", "reference_check", "report", "archive",
                    "all"}, jobs
    assert "Nothing to be done" in snakemake(work, "-n")


def test_bad_config_stops_before_any_job(workflow, tmp_path):
    work, _ = workflow
    path = work / "config" / "papers" / "saw_chain.yaml"
    original = path.read_text()
    try:
        path.write_text(original.replace("value: 8.91,", "value: -8.91,"))
        proc = subprocess.run([*SNAKEMAKE, "-n"], cwd=work, capture_output=True, text=True)
    finally:
        path.write_text(original)
    assert proc.returncode != 0
    assert "parameters.tie_strap_pitch = -8.91: must be > 0" in proc.stderr + proc.stdout


def test_another_platform_gives_the_same_verdicts(workflow):
    """The session's ci run is made under the platform variant ``ci_variant`` of
    config/reference.yaml (other BLAS kernels, numpy SIMD at its baseline, numba for a
    generic CPU; :func:`conftest.workflow`) on whatever CPU runs the tests, while the
    committed reference was measured natively on another machine: every verdict must be
    the reference's."""
    work, _ = workflow
    for paper in read_yaml((work / "config" / "config.yaml"))["papers"]:
        ref = {r["quantity"]: r["status"] for r in
               read_table(ROOT / "results" / "reference" / "ci" / f"{paper}.csv")}
        other = {r["quantity"]: r["status"] for r in
                 read_table(work / "results" / paper / "tables" / "validation.csv")}
        assert ref == other, {q: (ref[q], other.get(q)) for q in ref if ref[q] != other.get(q)}
