"""Never lose a good result, never certify an unchecked one (issue 31).

Heal decides by content, under the run lock: a copy without time stamps schedules nothing
and deletes nothing, a second run started while one writes is refused before it touches
anything, an interrupted run keeps what it finished, a result changed behind the
workflow's back is removed and rebuilt.  The pipeline tests run saw_chain's ci profile
(about 10 s) in a copy of the workflow.
"""
import os
import shutil
import signal
import subprocess
import sys
import time

import pytest

from conftest import copy_workflow
from mechrepro import heal as healmod
from mechrepro.io import read_sum, sum_path, write_text
from mechrepro.provenance import file_sha256

PAPER = "saw_chain"
SM = [sys.executable, "-m", "snakemake", "--cores", "2", "--config", "profile=ci",
      f"papers=[{PAPER}]"]


def sm(work, *args, check=True):
    proc = subprocess.run([*SM, *args], cwd=work, capture_output=True, text=True, timeout=900)
    if check and proc.returncode != 0:
        raise AssertionError(proc.stdout[-3000:] + proc.stderr[-3000:])
    return proc


def hashes(root):
    """sha256 of every result file (records included), by path relative to ``root``."""
    return {str(p.relative_to(root)): file_sha256(p) for p in sorted(root.rglob("*"))
            if p.is_file() and "logs" not in p.parts and "benchmarks" not in p.parts
            and "reference" not in p.parts}


# --- heal on its own (no pipeline) -------------------------------------------------------

def test_heal_keeps_what_its_writer_wrote_and_restores_its_time_stamp(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    res = tmp_path / "results"
    f = res / "p" / "tables" / "t.csv"
    write_text(f, "a,b\n1,2\n")
    rec = read_sum(f)
    assert rec["sha256"] == file_sha256(f) and rec["mtime_ns"] == f.stat().st_mtime_ns
    os.utime(f, (time.time() + 100, time.time() + 100))   # as cp -r / a touch leaves it
    assert healmod.heal(res) == []
    healmod.release(res)
    assert f.exists() and f.stat().st_mtime_ns == rec["mtime_ns"]


def test_heal_removes_changed_content_even_with_the_old_time_stamp(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    res = tmp_path / "results"
    f = res / "p" / "tables" / "t.csv"
    write_text(f, "a,b\n1,2\n")
    st = f.stat()
    f.write_text("a,b\n1,7\n")            # same size, one byte flipped
    os.utime(f, ns=(st.st_atime_ns, st.st_mtime_ns))
    part = f.parent / ".t.x.part.csv"
    part.write_text("half")
    lines = healmod.heal(res)
    healmod.release(res)
    assert any("content differs" in l and "t.csv" in l for l in lines), lines
    assert any("interrupted job" in l for l in lines)
    assert not f.exists() and not sum_path(f).exists() and not part.exists()


def test_heal_is_refused_while_another_process_holds_the_run_lock(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    res = tmp_path / "results"
    f = res / "p" / "runs" / "r.nc"
    write_text(f, "not netCDF, but what its writer wrote")
    holder = subprocess.Popen(
        [sys.executable, "-c", "import sys, time; sys.path.insert(0, sys.argv[1]);"
         "from mechrepro import heal; heal.acquire('results'); print('held', flush=True);"
         "time.sleep(60)", str(healmod.Path(healmod.__file__).parents[1])],
        cwd=tmp_path, stdout=subprocess.PIPE, text=True)
    try:
        assert holder.stdout.readline().strip() == "held"
        (f.parent / ".r.x.part.nc").write_text("a job of the other run is writing this")
        with pytest.raises(healmod.RunInProgress, match=f"process {holder.pid}"):
            healmod.heal(res)
        assert (f.parent / ".r.x.part.nc").exists()   # nothing touched
    finally:
        holder.kill()
        holder.wait()
    assert healmod.heal(res)   # the kernel dropped the lock with the process
    healmod.release(res)


def test_heal_cli_has_help_and_a_dry_run(tmp_path):
    env = {**os.environ, "PYTHONPATH": str(healmod.Path(healmod.__file__).parents[1])}
    out = subprocess.run([sys.executable, "-m", "mechrepro.heal", "--help"], cwd=tmp_path,
                         capture_output=True, text=True, env=env)
    assert out.returncode == 0 and "--dry-run" in out.stdout


# --- the pipeline (saw_chain, ci profile) -------------------------------------------------

@pytest.fixture(scope="module")
def run(tmp_path_factory):
    work = copy_workflow(tmp_path_factory.mktemp("rel"))
    sm(work)
    return work


pipeline = pytest.mark.slow


@pipeline
def test_a_copy_without_time_stamps_schedules_nothing_and_deletes_nothing(run, tmp_path):
    copy = tmp_path / "copy"
    shutil.copytree(run, copy, copy_function=shutil.copy)   # cp -r: new time stamps
    before = hashes(copy / "results")
    proc = sm(copy)
    assert "Nothing to be done" in proc.stdout + proc.stderr, proc.stderr[-3000:]
    assert "[heal] removed" not in proc.stderr
    assert hashes(copy / "results") == before


@pipeline
def test_a_second_run_is_refused_while_the_first_writes(run, tmp_path):
    work = tmp_path / "w"
    shutil.copytree(run, work, symlinks=True)
    first = subprocess.Popen([*SM, "--forcerun", f"solve_{PAPER}__batch"], cwd=work,
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                             start_new_session=True)
    runs = work / "results" / PAPER / "runs"
    deadline = time.time() + 120
    while time.time() < deadline and not list(runs.glob(".*.part*")) and first.poll() is None:
        time.sleep(0.02)
    second = sm(work, check=False)
    assert second.returncode != 0
    assert "another run is writing results" in second.stderr, second.stderr[-2000:]
    assert first.wait(timeout=600) == 0
    assert "Nothing to be done" in sm(work, "-n").stdout


@pipeline
def test_an_interrupted_run_keeps_what_it_finished(run, tmp_path):
    """Ctrl-C after the solve job ended: its runs are kept (same bytes, not rerun)."""
    work = tmp_path / "w"
    shutil.copytree(run, work, symlinks=True)
    runs = work / "results" / PAPER / "runs"
    proc = subprocess.Popen([*SM, "--forceall"], cwd=work, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True, start_new_session=True)
    # wait for the validation job: the solve job has finished by then
    log = work / "results" / PAPER / "logs" / "validate.log"
    stamp = log.stat().st_mtime if log.exists() else 0
    deadline = time.time() + 300
    while time.time() < deadline and proc.poll() is None and not (
            log.exists() and log.stat().st_mtime > stamp):
        time.sleep(0.02)
    solved = {p.name: file_sha256(p) for p in runs.glob("*.nc")}
    os.killpg(proc.pid, signal.SIGINT)
    proc.wait(timeout=120)
    out = sm(work, "--rerun-incomplete")
    assert f"solve_{PAPER}__batch" not in out.stdout + out.stderr
    assert "[heal] removed" not in out.stderr
    assert {p.name: file_sha256(p) for p in runs.glob("*.nc")} == solved
    assert "Nothing to be done" in sm(work, "-n").stdout
