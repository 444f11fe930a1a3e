"""What-if experiments, diffs and restore (src/mechrepro/experiment.py): on a copy of the
session's five-paper ci pipeline (``workflow``) as their baseline, and without a pipeline."""
import io
import json
import re
import shutil
import tarfile
import tempfile
import time
from pathlib import Path

import pytest

from conftest import copy_workflow, snakemake
from mechrepro import experiment
from mechrepro.config import ConfigError
from mechrepro.experiment import diff, main, parse_sets, prepare, restore, run, show, write_diff
from mechrepro.provenance import file_sha256

# valid, but refused in the solve job: a target of 1e-14 drives the difference method past
# its round-off limit (RoundoffError at K = 61440)
FAILING = "saw_chain.scenes.load_max_target.target.rtol=1.0e-14"


def _state(root):
    """{file: (sha256, modification time)} of every file under ``root``, records included."""
    return {str(f.relative_to(root)): (file_sha256(f), f.stat().st_mtime_ns)
            for f in sorted(root.rglob("*")) if f.is_file()}


@pytest.fixture(scope="module")
def saw(workflow, tmp_path_factory):
    """A project whose baseline ``results/`` is a copy of the session's ci pipeline run, and
    the baseline's state before any experiment."""
    work, _ = workflow
    base = tmp_path_factory.mktemp("exp") / "project"
    shutil.copytree(work, base, symlinks=True, ignore=shutil.ignore_patterns(".snakemake"))
    return base, _state(base / "results")


@pytest.fixture(scope="module")
def experiments(saw):
    """Experiments that fail in their solve job, run, and change nothing (every file of an
    untouched paper reused), with the time before."""
    base, _ = saw
    t0 = time.time_ns()
    return t0, {name: run(name, sets, base=base) for name, sets in
                (("broken", [FAILING]), ("faster", ["saw_chain.sprocket_speed=7000"]),
                 ("same", []))}


def test_the_diff_of_a_result_set_with_itself_is_empty(workflow):
    work, _ = workflow
    assert diff(work / "results", work / "results", work / "results" / "reference", "ci")["papers"] == {}


def test_an_override_reruns_its_paper_only_and_the_diff_shows_what_moved(saw, experiments):
    base, _ = saw
    rec = experiments[1]["faster"]
    assert rec["status"] == "done", (base / "experiments/faster/snakemake.log").read_text()[-3000:]
    # only saw_chain is solved, validated and drawn again; the other papers are reused
    solved = {j for j in rec["jobs"] if j.startswith(("solve_", "validate_", "notebook_"))}
    assert solved == {"solve_saw_chain__batch", "validate_saw_chain", "notebook_saw_chain"}
    d = diff(base / "results", base / "experiments/faster/results", base / "results/reference", "ci")
    assert set(d["papers"]) == {"saw_chain"}
    sc = d["papers"]["saw_chain"]
    assert sc["parameters"]["sprocket_speed"][1] == pytest.approx(7000 * 2 * 3.141592653589793 / 60)
    moved = {r["quantity"] for r in sc["rows"]}
    # loads scale with speed squared, velocities with speed; the K-study's order does not move
    assert {"dynamic_load_max", "dynamic_load_min", "tight_side_velocity_max"} <= moved
    assert "observed_order_load" not in moved
    assert "fig07.png" in sc["figures_changed"] and "fig08.png" in sc["figures_changed"]


def test_an_invalid_override_is_refused_before_any_job(workflow, tmp_path):
    work, _ = workflow
    for sets, message in ((["saw_chain.tie_strap_pitch=-8.91"], "tie_strap_pitch"),
                          (["saw_chain.no_such=1"], "not a parameter"),
                          (["nopaper.x=1"], "no paper"), (["saw_chain=1"], "PAPER.PARAMETER")):
        with pytest.raises(ConfigError, match=message):
            prepare("bad", sets, base=work, profile="ci")
        assert not (work / "experiments" / "bad").exists()
    assert parse_sets(["a.b.c=[1, 2]"]) == {"a": {"b.c": [1, 2]}}


def test_restore_into_a_fresh_checkout_schedules_nothing(workflow, tmp_path):
    work, _ = workflow
    (tmp_path / "fresh").mkdir()
    fresh = copy_workflow(tmp_path / "fresh")
    n = restore(work / "results/archive/mechrepro-results.tar.gz", fresh)
    assert n > 100
    out = snakemake(fresh, "-n")
    assert "Nothing to be done" in out, out[-2000:]
    with pytest.raises(ValueError, match="would overwrite"):
        restore(work / "results/archive/mechrepro-results.tar.gz", fresh)


def test_a_profile_other_than_the_baselines_is_refused_before_any_job(saw):
    base, before = saw
    with pytest.raises(ConfigError) as exc:
        run("other_profile", [], base=base, profile="default")
    assert "'default'" in str(exc.value) and "'ci'" in str(exc.value), exc.value
    assert "--profile ci" in str(exc.value), exc.value
    assert not (base / "experiments" / "other_profile").exists()
    assert _state(base / "results") == before


def test_an_experiment_that_runs_or_fails_never_writes_the_baseline(saw, experiments):
    base, before = saw
    t0, recs = experiments
    log = (base / "experiments/broken/snakemake.log").read_text()
    assert recs["broken"]["status"] == "failed" and "RoundoffError" in log, log[-3000:]
    assert recs["broken"]["jobs"].get("solve_saw_chain__batch") == 1
    for name in ("faster", "same"):
        assert recs[name]["status"] == "done", \
            (base / f"experiments/{name}/snakemake.log").read_text()[-3000:]
    assert recs["faster"]["profile"] == "ci"     # the baseline's
    assert _state(base / "results") == before    # content and time stamps
    # what the experiments' jobs wrote (benchmarks, logs, outputs, and the outputs Snakemake
    # put back after the failed job) is no baseline file
    for name in recs:
        res = base / "experiments" / name / "results"
        written = [f for f in res.rglob("*")
                   if f.is_file() and not f.is_relative_to(res / "reference")
                   and ({"benchmarks", "logs"} & set(f.relative_to(res).parts)
                        or f.stat().st_mtime_ns > t0)]
        parts = {p for f in written for p in f.relative_to(res).parts}
        # a failed job has no benchmark; an experiment that changes nothing solves nothing
        assert {"broken": {"logs", "runs"}, "faster": {"benchmarks", "logs", "runs"},
                "same": {"benchmarks", "logs"}}[name] <= parts, (name, written)
        assert [f for f in written if f.stat().st_nlink != 1] == [], name


def test_a_failed_or_interrupted_experiment_is_shown_as_failed(saw, experiments, monkeypatch,
                                                               capsys):
    base, _ = saw

    def ctrl_c(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(experiment.subprocess, "run", ctrl_c)   # Ctrl-C while Snakemake runs
    with pytest.raises(KeyboardInterrupt):
        run("interrupted", [], base=base)
    listed = {r["name"]: r for r in show(base)}
    for name in ("broken", "interrupted"):
        assert listed[name]["status"] == "failed" and listed[name]["claims"] == {}, listed[name]
    assert listed["faster"]["status"] == "done" and listed["faster"]["claims"]["saw_chain"]
    monkeypatch.chdir(base)
    assert main(["exp", "show"]) == 0
    out = capsys.readouterr().out
    assert re.search(r"^broken: failed", out, re.M), out
    assert re.search(r"^interrupted: failed", out, re.M), out


def test_a_diff_from_an_archive_keeps_the_figures_of_both_sides(saw, experiments, monkeypatch):
    base, _ = saw
    monkeypatch.chdir(base)
    archive = "results/archive/mechrepro-results.tar.gz"
    assert main(["diff", archive, "experiments/faster/results", "--out", "cmp"]) == 0
    page = (base / "cmp/diff.html").read_text()
    srcs = re.findall(r'<img src="([^"]+)"', page)
    assert srcs and [s for s in srcs if not (base / "cmp" / s).is_file()] == []
    assert len([s for s in srcs if "/A/" in s]) == len([s for s in srcs if "/B/" in s]) > 0, srcs
    assert "fig07.png" in " ".join(srcs)
    assert tempfile.gettempdir() not in page and "/tmp" not in page
    assert json.loads((base / "cmp/diff.json").read_text())["a"] == archive
    # tables, not text: the parameter that moved is a table row
    assert "<pre" not in page and re.search(r"<tr><td>sprocket_speed</td>", page)


# --- no pipeline ------------------------------------------------------------------------

def test_the_diff_page_is_tables_and_escapes_what_it_shows(tmp_path):
    (tmp_path / "A<1>/p/figures").mkdir(parents=True)
    (tmp_path / "A<1>/p/figures/f.png").write_bytes(b"png")
    claims = {"a": {"claim": "full", "independent": {"pass": 2}},
              "b": {"claim": "partial", "independent": {"pass": 1, "fail": 1}}}
    row = {"quantity": "<script>", "a": "1", "b": "2", "unit": "N", "status_a": "pass",
           "status_b": "fail", "evidence_a": "independent", "evidence_b": "independent"}
    d = {"a": str(tmp_path / "A<1>"), "b": str(tmp_path / "B"), "papers": {"p": {
        "parameters": {"x<y": [1.0, 2.0]}, "claim": claims, "rows": [row],
        "runs_changed": ["r.nc"], "figures_changed": ["f.png"], "time": {"a": 1.0, "b": 2.0}}}}
    write_diff(d, tmp_path / "out")
    page = (tmp_path / "out/diff.html").read_text()
    assert "<script>" not in page and "&lt;script&gt;" in page and "x&lt;y" in page
    assert "A&lt;1&gt;" in page and page.count("<table") == 3 and "{'" not in page
    assert "partial (pass 1, fail 1)" in page and "{'" not in (tmp_path / "out/diff.md").read_text()
    # the figure of side A is copied beside the page; side B drew none
    assert '<img src="figures/A/p/f.png"' in page and (tmp_path / "out/figures/A/p/f.png").is_file()
    assert "B: not drawn" in page


@pytest.mark.parametrize("member", ["../evil.txt", "/tmp/evil-absolute.txt"])
def test_restore_refuses_a_hostile_archive_naming_the_member(tmp_path, member, capsys):
    tar_path = tmp_path / "hostile.tar.gz"
    with tarfile.open(tar_path, "w:gz") as tar:
        for name, data in (("saw_chain/claim.json", b"{}"), (member, b"x"),
                           ("manifest.json", b'{"files": {}}')):
            info = tarfile.TarInfo(name)
            info.size = len(data)
            tar.addfile(info, io.BytesIO(data))
    into = tmp_path / "checkout"
    into.mkdir()
    assert main(["restore", str(tar_path), "--into", str(into)]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and member in err and "Traceback" not in err, err
    assert list(into.iterdir()) == [] and not (tmp_path / "evil.txt").exists()
    assert not Path("/tmp/evil-absolute.txt").exists()


def test_a_set_reads_an_exponent_without_a_dot_as_a_number():
    # YAML 1.1 (PyYAML) reads 1e-14 as text, which the schema then refuses as "not a number"
    assert parse_sets(["p.x=1e-14", "p.y=abc", "p.z=[1, 2]"]) == {"p": {"x": 1e-14, "y": "abc",
                                                                         "z": [1, 2]}}
