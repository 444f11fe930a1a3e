"""Fault injection on the ci pipeline: what is deleted, truncated, corrupted, garbled,
interrupted or moved is detected, named and rebuilt; bad input is refused before any job.

Each test breaks a ci pipeline copy (the toy paper's, see ONLY below), runs what
`make ci-reproduce` runs (Snakemake, whose workflow heals before any job) and checks
that exactly the broken results and what depends on them were rebuilt, and that the tree is whole again.
"""
import json
import os
import shutil
import subprocess
import sys

import pytest
import yaml

import conftest
from conftest import SNAKEMAKE
from mechrepro.archive import verify

pytestmark = pytest.mark.slow

# The faults break a one-paper pipeline of their own (the toy paper's, conftest.toy_pipeline,
# the smallest whole one: heal, the run lock, the checksums and the archive do not depend on
# the paper), which runs on the other xdist worker beside the session's five-paper ci
# pipeline instead of after it on the same one; its report and archive are report-<paper>/,
# archive-<paper>/ (never the five-paper ones).  MECHREPRO_FAULT_PAPERS=saw_chain breaks
# saw_chain's one-paper pipeline instead, "all" the session's five-paper run (on saw_chain).
ONLY = os.environ.get("MECHREPRO_FAULT_PAPERS", "toy")
ONLY = "" if ONLY == "all" else ONLY
TAG = "-" + "+".join(ONLY.split(",")) if ONLY else ""
REPORT, ARCHIVE = f"report{TAG}", f"archive{TAG}"
if ONLY:
    SNAKEMAKE = [*SNAKEMAKE, f"papers=[{ONLY}]"]

# what the faults break, per paper they run on: a run (the first its solve batch writes),
# a run of a study, a table of its own, a figure; and an edit of its profile input per fault
# of test_bad_profile_input_stops_before_any_job (the study's sweep of the default profile,
# the ci overlay's sweep, a misspelt scene in the ci overlay)
PAPER = "toy" if ONLY == "toy" else "saw_chain"
RUN, STUDY_RUN, STUDY, TABLE, FIGURE = {
    "toy": ("response", "steps-001", "steps", "verification_cost.csv", "fig01.png"),
    "saw_chain": ("fig07_fig08", "cost_of_accuracy-001", "cost_of_accuracy",
                  "cost_of_accuracy.csv", "fig07.png")}[PAPER]
SCENE_RUN = {"toy": "response", "saw_chain": "speed_12000"}[PAPER]   # a run of a scene
PROFILE_EDITS = {
    "toy": [
        (lambda raw: raw["studies"]["steps"]["sweep"].update(steps_per_period=["1e3"]),
         "must be of type"),
        (lambda raw: raw["profiles"]["ci"]["studies"]["steps"].update(
            sweep={"steps_per_period": []}), "should be non-empty"),
        (lambda raw: raw["profiles"]["ci"]["scenes"].update(respons={"resolution": {
            "steps_per_period": 3}}), "profiles.ci.scenes.respons: not one of the file's scenes")],
    "saw_chain": [
        (lambda raw: raw["studies"]["cost_of_accuracy"]["sweep"].update(K=["1e3"]),
         "must be of type"),
        (lambda raw: raw["profiles"]["ci"]["studies"]["cost_of_accuracy"].update(
            sweep={"K": []}), "should be non-empty"),
        (lambda raw: raw["profiles"]["ci"]["scenes"].update(fig07_fig8={"resolution": {"K": 3}}),
         "profiles.ci.scenes.fig07_fig8: not one of the file's scenes")]}[PAPER]


def snakemake(work, *args, check=True):
    return conftest.snakemake(work, *args, check=check, base=SNAKEMAKE)


if ONLY:
    @pytest.fixture(scope="module")
    def wf(tmp_path_factory):
        """A copy of the one-paper ci pipeline (MECHREPRO_FAULT_PAPERS)."""
        dst = tmp_path_factory.mktemp("faults")
        if ONLY == "toy":
            return conftest.toy_pipeline(tmp_path_factory, dst)
        return conftest.one_paper_pipeline(tmp_path_factory, ONLY, dst)
else:
    @pytest.fixture(scope="module")
    def wf(workflow):
        """The session's five-paper ci pipeline copy.  Named as a fixture argument, not
        fetched at run time, so that conftest puts these tests in the xdist group of the
        other tests of that run (a second worker would run the whole pipeline again)."""
        return workflow


def planned(work):
    from test_pipeline import scheduled

    return scheduled(snakemake(work, "-n"))


def restored(work):
    """Rerun (the workflow heals first: its log has the heal's lines), and check the whole
    tree against the fresh manifest."""
    log = snakemake(work)
    assert "Nothing to be done" in snakemake(work, "-n")
    assert verify(work / "results", work / "results" / ARCHIVE / "manifest.json") == []
    return log


def test_deleted_figure_run_and_summary_image_are_restored(wf):
    work, _ = wf
    res = work / "results"
    fig = res / PAPER / "figures" / FIGURE
    run = res / PAPER / "runs" / f"{SCENE_RUN}.nc"
    summary = res / REPORT / "cost_of_accuracy_all.png"
    for f in (fig, run, summary):
        f.unlink()
    jobs = planned(work)
    assert {f"notebook_{PAPER}", f"solve_{PAPER}__batch", "summary"} <= jobs
    assert not any(j.startswith("notebook_") and j != f"notebook_{PAPER}" for j in jobs), jobs
    restored(work)
    assert fig.stat().st_size > 1000 and run.exists() and summary.exists()


def test_truncated_netcdf_is_rebuilt_and_its_study_kept(wf):
    work, _ = wf
    run = work / "results" / PAPER / "runs" / f"{STUDY_RUN}.nc"
    study = work / "results" / PAPER / "studies" / f"{STUDY}.nc"
    st = run.stat()
    run.write_bytes(run.read_bytes()[:200])
    os.utime(run, ns=(st.st_atime_ns, st.st_mtime_ns))
    log = restored(work)
    assert "content differs from what its job wrote" in log and str(run.name) in log
    assert study.exists() and run.stat().st_size > 1000


def test_corruption_that_keeps_the_time_stamp_is_found_by_checksum(wf):
    work, _ = wf
    table = work / "results" / PAPER / "tables" / TABLE
    st = table.stat()
    data = bytearray(table.read_bytes())
    data[-5] = ord("7") if data[-5] != ord("7") else ord("8")
    table.write_bytes(bytes(data))
    os.utime(table, ns=(st.st_atime_ns, st.st_mtime_ns))
    assert verify(work / "results", work / "results" / ARCHIVE / "manifest.json") == [
        f"{PAPER}/tables/{TABLE}: sha256 differs from the manifest"]
    log = restored(work)
    assert "content differs from what its job wrote" in log


def test_make_reproduce_with_nothing_changed_starts_nothing_but_sees_a_kept_time_stamp(wf):
    """`make ci-reproduce`'s driver (mechrepro.reproduce): after a successful run, the next
    one with no file changed starts neither Snakemake nor the heal; a result rewritten
    with its time stamp kept has a new change time, so the run after it goes through the
    heal, which rebuilds it by content."""
    work, _ = wf
    env = {**os.environ, "PYTHONPATH": str(work / "src")}

    def reproduce():
        proc = subprocess.run([sys.executable, "-m", "mechrepro.reproduce", "results", "--",
                               *SNAKEMAKE[3:]], cwd=work, capture_output=True, text=True,
                              env=env, timeout=2400)
        assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
        return proc.stdout + proc.stderr

    assert "Building DAG" in reproduce()         # no record yet: Snakemake decides
    fast = reproduce()
    assert "changed since the last successful run" in fast and "Building DAG" not in fast
    table = work / "results" / PAPER / "tables" / "validation.csv"
    st = table.stat()
    table.write_text(_garbled(table))
    os.utime(table, ns=(st.st_atime_ns, st.st_mtime_ns))
    assert "validation.csv: content differs from what its job wrote" in reproduce()
    assert verify(work / "results", work / "results" / ARCHIVE / "manifest.json") == []
    assert "changed since the last successful run" in reproduce()


def _garbled(table):
    import csv
    import io

    rows = list(csv.reader(io.StringIO(table.read_text())))
    rows[1][rows[0].index("reproduced_value")] = "#garbage#"
    buf = io.StringIO()
    csv.writer(buf, lineterminator="\n").writerows(rows)
    return buf.getvalue()


def test_garbage_pasted_into_a_table_is_healed_by_plain_snakemake(wf):
    """Garbage pasted into a result (time stamp kept): the workflow's own heal finds it
    by content before any job, and the run rebuilds it."""
    work, _ = wf
    table = work / "results" / PAPER / "tables" / "validation.csv"
    st = table.stat()
    table.write_text(_garbled(table))
    os.utime(table, ns=(st.st_atime_ns, st.st_mtime_ns))
    log = snakemake(work)
    assert "validation.csv: content differs from what its job wrote" in log
    assert "Nothing to be done" in snakemake(work, "-n")
    assert "OK" in (work / "results" / REPORT / "reference_check.txt").read_text().splitlines()[0]
    assert verify(work / "results", work / "results" / ARCHIVE / "manifest.json") == []


def test_garbage_written_by_a_job_is_named_and_not_archived(wf):
    """Garbage a job itself wrote (its checksum recorded, so heal keeps it): the reference
    check names file, line and value; the archive refuses and keeps the last good one."""
    from mechrepro.io import read_sum, sum_path, write_text
    from mechrepro.provenance import file_sha256

    work, _ = wf
    table = work / "results" / PAPER / "tables" / "validation.csv"
    archive = work / "results" / ARCHIVE
    keep = {f.name: file_sha256(f) for f in archive.iterdir() if not f.name.startswith(".")}
    made_by = read_sum(table)["made_by"]
    write_text(table, _garbled(table))
    # as its job writes it: with the record of what made it
    side = sum_path(table)
    side.write_text(json.dumps({**json.loads(side.read_text()), "made_by": made_by}))
    proc = subprocess.run([*SNAKEMAKE, "--keep-going"], cwd=work, capture_output=True, text=True)
    assert proc.returncode != 0
    check = (work / "results" / REPORT / "reference_check.txt").read_text()
    assert "DRIFT" in check.splitlines()[0] and "line 2" in check and "'#garbage#' is not a number" in check
    assert {f.name: file_sha256(f) for f in archive.iterdir() if not f.name.startswith(".")} == keep
    snakemake(work, "--forcerun", f"validate_{PAPER}")
    assert "OK" in (work / "results" / REPORT / "reference_check.txt").read_text().splitlines()[0]
    assert verify(work / "results", work / "results" / ARCHIVE / "manifest.json") == []


def test_an_interrupted_job_leaves_nothing_that_stays(wf):
    work, _ = wf
    stale = work / "results" / PAPER / "runs" / f".{SCENE_RUN}.abc.part.nc"
    stale.write_bytes(b"half")
    log = restored(work)
    assert "temporary file of an interrupted job" in log and not stale.exists()


def test_a_killed_run_recovers_as_the_readme_says(wf):
    """kill -9 in the middle of a solver job (as it writes RUN, its first run); then
    `snakemake --unlock` and a normal run."""
    import signal
    import time

    work, _ = wf
    run = work / "results" / PAPER / "runs" / f"{RUN}.nc"
    proc = subprocess.Popen([*SNAKEMAKE, "--forcerun", f"solve_{PAPER}__batch"],
                            cwd=work, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            start_new_session=True)
    deadline = time.time() + 120
    while time.time() < deadline and not list(run.parent.glob(f".{RUN}*.part*")) \
            and proc.poll() is None:
        time.sleep(0.05)
    os.killpg(proc.pid, signal.SIGKILL)
    proc.wait()
    snakemake(work, "--unlock")
    snakemake(work, "--rerun-incomplete")  # as `make reproduce` runs it: heal, then the jobs
    assert "Nothing to be done" in snakemake(work, "-n")
    assert verify(work / "results", work / "results" / ARCHIVE / "manifest.json") == []
    assert run.stat().st_size > 1000


def test_a_moved_project_with_its_results_schedules_nothing(wf, tmp_path):
    work, _ = wf
    moved = tmp_path / "moved"
    shutil.copytree(work, moved, symlinks=True)  # copytree keeps time stamps (copy2)
    assert "Nothing to be done" in snakemake(moved, "-n")


def test_results_honour_the_umask(wf):
    work, _ = wf
    for f in [work / "results" / PAPER / "runs" / f"{SCENE_RUN}.nc",
              work / "results" / REPORT / "index.html",
              work / "results" / ARCHIVE / "mechrepro-results.tar.gz"]:
        assert f.stat().st_mode & 0o044 == 0o044, f"{f} is not readable by others"
    import tarfile

    with tarfile.open(work / "results" / ARCHIVE / "mechrepro-results.tar.gz") as tar:
        members = tar.getmembers()
        names = {m.name for m in members}
        assert all(m.mode & 0o044 == 0o044 for m in members)
    # everything the archived report links is in the archive
    assert {f"{REPORT}/index.html", f"{REPORT}/cost_of_accuracy_all.png",
            f"{REPORT}/summary.csv", "manifest.json"} <= names


def test_the_extracted_archive_report_has_no_broken_link(wf, tmp_path):
    import re
    import tarfile

    work, _ = wf
    with tarfile.open(work / "results" / ARCHIVE / "mechrepro-results.tar.gz") as tar:
        tar.extractall(tmp_path, filter="data")
    page = (tmp_path / REPORT / "index.html").read_text()
    links = re.findall(r'(?:src|href)="([^"#]+)"', page)
    assert links
    broken = [l for l in links if not (tmp_path / REPORT / l).resolve().exists()]
    assert not broken, broken


def test_lint_is_clean_but_for_conda(wf):
    work, _ = wf
    proc = subprocess.run([*SNAKEMAKE, "--lint"], cwd=work, capture_output=True, text=True)
    lints = {line.strip() for line in (proc.stdout + proc.stderr).splitlines()
             if line.strip().startswith("* ")}
    assert lints <= {"* Specify a conda environment or container for each rule.:"}, lints


# a value YAML reads as a string, in a profile that is not the one running; an empty sweep
# in the ci overlay; a misspelt scene in the overlay
@pytest.mark.parametrize("edit, message", PROFILE_EDITS,
                         ids=["string in another profile", "empty sweep", "misspelt scene"])
def test_bad_profile_input_stops_before_any_job(wf, edit, message):
    work, _ = wf
    path = work / "config" / "papers" / f"{PAPER}.yaml"
    original = path.read_text()
    raw = yaml.safe_load(original)
    edit(raw)
    try:
        path.write_text(yaml.safe_dump(raw))
        proc = subprocess.run([*SNAKEMAKE, "-n"], cwd=work, capture_output=True, text=True)
    finally:
        path.write_text(original)
    assert proc.returncode != 0
    assert message in proc.stderr + proc.stdout, (proc.stderr + proc.stdout)[-2000:]


# --- three faults of issue 31's second round (not in its table of 25) ----------------------

def _result_hashes(work):
    from mechrepro.provenance import file_sha256

    res = work / "results"
    return {str(p.relative_to(res)): file_sha256(p) for p in sorted(res.rglob("*"))
            if p.is_file() and not {"logs", "benchmarks", "reference"} & set(p.parts)
            and not p.name.startswith("rerun_plan")}


def test_a_deleted_snakemake_directory_loses_nothing(wf, tmp_path):
    """`rm -rf .snakemake` (Snakemake's metadata, incomplete markers, the config cache and
    the run locks, e.g. a copy that skipped hidden files): heal removes nothing, the solved
    runs keep their bytes (no solve job reruns); without Snakemake's input checksums, jobs
    whose inputs carry newer time stamps (here the config, edited and put back by the
    tests above) rerun, as Snakemake's time stamp rule says."""
    work, _ = wf
    copy = tmp_path / "w"
    shutil.copytree(work, copy, symlinks=True)
    shutil.rmtree(copy / ".snakemake")
    before = _result_hashes(copy)
    out = snakemake(copy)
    heal_lines = [line for line in out.splitlines() if "[heal]" in line]
    assert not any("removed" in line for line in heal_lines), heal_lines
    assert f"solve_{PAPER}__batch" not in out
    after = _result_hashes(copy)
    assert {k: v for k, v in after.items() if "/runs/" in k or "/studies/" in k} == \
        {k: v for k, v in before.items() if "/runs/" in k or "/studies/" in k}
    assert "Nothing to be done" in snakemake(copy, "-n")
    assert verify(copy / "results", copy / "results" / ARCHIVE / "manifest.json") == []


def test_a_clock_in_the_future_hides_no_later_edit(wf, tmp_path):
    """Every result stamped in 2099 (a clock set wrong while they were written, or `touch`
    on the tree): heal puts back the time stamps their jobs recorded, so a later edit of
    the notebook is still seen and its job reruns, and nothing else does."""
    work, _ = wf
    copy = tmp_path / "w"
    shutil.copytree(work, copy, symlinks=True)
    future = 4_070_908_800 * 10**9   # 2099-01-01
    for p in (copy / "results").rglob("*"):
        if p.is_file() and "reference" not in p.parts:
            os.utime(p, ns=(future, future))
    nb = copy / "notebooks" / f"{PAPER}.py"
    nb.write_text(nb.read_text() + "\n# an edit after the results were written\n")
    log = snakemake(copy)
    assert f"rule notebook_{PAPER}:" in log, log[-3000:]
    assert f"rule solve_{PAPER}__batch:" not in log and "[heal] removed" not in log
    assert "Nothing to be done" in snakemake(copy, "-n")


def test_garbled_checksum_records_delete_no_valid_result(wf, tmp_path):
    """Garbage in every checksum record of runs/ (`.<name>.sum`) and one run's bytes
    flipped: heal falls back to the last manifest, keeps every run that matches it and
    removes only the flipped one (its job, the paper's one solve batch, then rewrites every
    run: they carry their wall times, so not bit for bit)."""
    work, _ = wf
    copy = tmp_path / "w"
    shutil.copytree(work, copy, symlinks=True)
    runs = copy / "results" / PAPER / "runs"
    for rec in runs.glob(".*.sum"):
        rec.write_text("{not json")
    flipped = runs / f"{SCENE_RUN}.nc"
    data = bytearray(flipped.read_bytes())
    data[len(data) // 2] ^= 0xFF
    flipped.write_bytes(bytes(data))
    log = snakemake(copy)
    removed = [line for line in log.splitlines() if "[heal] removed" in line]
    assert len(removed) == 1 and f"{SCENE_RUN}.nc" in removed[0], removed
    assert "checksum differs from the last manifest" in removed[0]
    assert "Nothing to be done" in snakemake(copy, "-n")
    assert verify(copy / "results", copy / "results" / ARCHIVE / "manifest.json") == []
