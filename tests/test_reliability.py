"""Never lose a good result, never certify an unchecked one (issue 31).

Heal decides by content, under the run lock: a copy without time stamps schedules nothing
and deletes nothing, a second run started while one writes is refused before it touches
anything, an interrupted run keeps what it finished, a result changed behind the
workflow's back is removed and rebuilt.  The pipeline tests break a copy of the toy paper's
ci pipeline (conftest.toy_pipeline, the smallest whole one); the bad-input tests refuse
edits of saw_chain's config (see BAD_PAPER) in a copy of saw_chain's part of the session's
five-paper ci run.
"""
import os
import shutil
import signal
import subprocess
import sys
import time

import pytest

import snakemake_fork
from conftest import toy_pipeline
from mechrepro import heal as healmod
from mechrepro.io import read_sum, sum_path, write_text
from mechrepro.provenance import file_sha256

PAPER = "toy"
# the bad-input tests edit saw_chain's config (the edits of test_inputs.BAD and those below
# name its text and reach its own checks: a chain pitch's plausible range, K's round-off
# limit, its solve job's memory estimate), so they refuse a run of saw_chain's pipeline
BAD_PAPER = "saw_chain"
SM = [sys.executable, "-m", "snakemake", "--cores", "2", "--config", "profile=ci",
      f"papers=[{PAPER}]"]
# the disk-full test's tmpfs: the results' size plus this (kB): room for the new tables and
# figures and what update() keeps aside, not for a second archive (the toy's: 120 kB)
ROOM_K = 300


def sm(work, *args, check=True, paper=PAPER):
    proc = snakemake_fork.run([*SM[3:-1], f"papers=[{paper}]", *args], work, timeout=900)
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
        [sys.executable, "-c", "import time; from mechrepro import heal;"
         "heal.acquire('results'); print('held', flush=True); time.sleep(60)"],
        cwd=tmp_path, stdout=subprocess.PIPE, text=True,
        env={**os.environ, "PYTHONPATH": str(healmod.Path(healmod.__file__).parents[1])})
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


# --- the pipeline (the toy paper, ci profile) --------------------------------------------

@pytest.fixture(scope="module")
def run(tmp_path_factory):
    return toy_pipeline(tmp_path_factory, tmp_path_factory.mktemp("rel"))[0]


@pytest.fixture(scope="module")
def bad_run(workflow):
    """The session's ci pipeline, whose saw_chain config the bad-input tests edit (BAD_PAPER)."""
    return workflow[0]


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
    # the first run holds the run lock from its heal to its end, its pid written in it (a
    # result's .part file lives milliseconds in the toy's run: polled for, it was missed)
    lock = healmod.lock_file("results", work)
    deadline = time.time() + 120
    while time.time() < deadline and first.poll() is None and \
            (not lock.is_file() or lock.read_text().strip() != str(first.pid)):
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
    # stderr to a file, not a pipe: nothing reads a pipe while the test waits, and a child
    # that fills one blocks in its write (the Popen.wait deadlock the Python docs warn of)
    err = tmp_path / "snakemake.stderr"
    with open(err, "w") as sink:
        proc = subprocess.Popen([*SM, "--forceall"], cwd=work, stdout=subprocess.DEVNULL,
                                stderr=sink, start_new_session=True)
    # wait for the validation job: the solve job has finished by then
    log = work / "results" / PAPER / "logs" / "validate.log"
    stamp = log.stat().st_mtime if log.exists() else 0

    def validating():
        try:
            return log.stat().st_mtime > stamp
        except FileNotFoundError:    # Snakemake removes the last log as the job starts
            return False

    deadline = time.time() + 300
    while time.time() < deadline and proc.poll() is None and not validating():
        time.sleep(0.02)
    solved = {p.name: file_sha256(p) for p in runs.glob("*.nc")}
    os.killpg(proc.pid, signal.SIGINT)
    try:
        proc.wait(timeout=120)
    except subprocess.TimeoutExpired:
        # seen once (a fresh-clone CI run, both cores loaded): name what was still running
        tree = subprocess.run(["ps", "-o", "pid,ppid,stat,etime,args", "-s", str(proc.pid)],
                              capture_output=True, text=True).stdout
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()
        pytest.fail(f"Snakemake still running 120 s after Ctrl-C; its session:\n{tree}\n"
                    f"its stderr (end):\n{err.read_text()[-4000:]}")
    out = sm(work, "--rerun-incomplete")
    assert f"solve_{PAPER}__batch" not in out.stdout + out.stderr
    assert "[heal] removed" not in out.stderr
    assert {p.name: file_sha256(p) for p in runs.glob("*.nc")} == solved
    assert "Nothing to be done" in sm(work, "-n").stdout


# --- the archive --------------------------------------------------------------------------

def archive_dir(work):
    return work / "results" / f"archive-{PAPER}"


@pipeline
def test_the_archive_holds_exactly_the_declared_outputs(run, tmp_path):
    import json
    import tarfile

    work = tmp_path / "w"
    shutil.copytree(run, work, symlinks=True)
    stray = work / "results" / PAPER / "runs" / "renamed_scene.nc"
    shutil.copy(next((work / "results" / PAPER / "runs").glob("*.nc")), stray)
    (work / "results" / PAPER / "tables" / "old_table.csv").write_text("a\n1\n")
    sm(work, "--forcerun", "archive")
    man = json.loads((archive_dir(work) / "manifest.json").read_text())
    with tarfile.open(archive_dir(work) / "mechrepro-results.tar.gz") as tar:
        names = set(tar.getnames())
    assert names == set(man["files"]) | set(man.get("extras", {})) | {"manifest.json"}
    assert not any("renamed_scene" in n or "old_table" in n or "/." in n for n in names)
    # every declared output of the paper is there, nothing else from its directory
    dry = sm(work, "--list-target-rules").stdout   # the workflow parses
    assert f"{PAPER}/claim.json" in names and f"{PAPER}/tables/validation.csv" in names, dry


@pipeline
@pytest.mark.parametrize("fault", ["missing reference", "drift"])
def test_a_failed_check_archives_nothing_and_keeps_the_last_good_archive(run, tmp_path, fault):
    work = tmp_path / "w"
    shutil.copytree(run, work, symlinks=True)
    keep = {n: file_sha256(archive_dir(work) / n)
            for n in ("manifest.json", "mechrepro-results.tar.gz")}
    if fault == "missing reference":
        (work / "results" / "reference" / "ci" / f"{PAPER}.csv").unlink()
    else:   # a reference value far from what the run gives
        ref = work / "results" / "reference" / "ci" / f"{PAPER}.csv"
        lines = ref.read_text().splitlines()
        i = next(i for i, l in enumerate(lines) if ",value," in l)
        cells = lines[i].split(",")
        cells[1] = repr(float(cells[1]) * 1.5 + 1.0)
        lines[i] = ",".join(cells)
        ref.write_text("\n".join(lines) + "\n")
    proc = sm(work, check=False)
    assert proc.returncode != 0
    check = (work / "results" / f"report-{PAPER}" / "reference_check.txt").read_text()
    assert "OK" not in check.splitlines()[0]
    assert ("not checked" if fault == "missing reference" else "DRIFT") in check
    assert "not archiving" in proc.stderr
    assert {n: file_sha256(archive_dir(work) / n) for n in keep} == keep
    # the manifest of the last good archive stays usable: it names exactly what the failed
    # run rewrote (the report of the failed check), so a later bit flip is still found
    from mechrepro.archive import verify

    assert {p.split(":")[0] for p in verify(work / "results", archive_dir(work) / "manifest.json")
            } <= {f"report-{PAPER}/index.html", f"report-{PAPER}/reference_check.txt"}


@pytest.mark.parametrize("check", [
    None,                                                        # no check was run
    "reference check, profile ci: DRIFT\nsaw_chain: DRIFT against ref\n",
    # OK on its first line, but a selected paper was not checked (no reference)
    "reference check, profile ci: OK\nsaw_chain: 3 quantities within tolerance of ref\n"
    "joint_wear: not checked: no reference at ref\n",
], ids=["no check", "drift", "a paper unchecked"])
def test_no_archive_exists_without_a_passed_check_of_every_paper(tmp_path, check):
    """The first archive of a tree is never written unless the check passed for every
    selected paper: no tar, no manifest (the pipeline tests cover the kept last good one)."""
    from mechrepro.archive import ArchiveRefused, write_archive

    (tmp_path / "saw_chain").mkdir()
    result = tmp_path / "saw_chain" / "claim.json"
    result.write_text("{}")
    if check is not None:
        (tmp_path / "check.txt").write_text(check)
    with pytest.raises(ArchiveRefused, match="not archiving"):
        write_archive(str(tmp_path / "a" / "x.tar.gz"), str(tmp_path / "a" / "manifest.json"),
                      str(tmp_path / "check.txt"), str(tmp_path), "config",
                      ["saw_chain", "joint_wear"], "ci", [str(result)])
    assert not (tmp_path / "a").exists() or not any((tmp_path / "a").iterdir())


def test_timing_verdicts_are_checked_and_profiles_must_agree(tmp_path):
    from mechrepro.reference import HEADER, compare, profiles_agree

    ref = [dict(zip(HEADER, ["speedup", "11231.7", "pass", "timing", "8920", "nan", "native",
                             "independent"]))]
    assert compare({"speedup": (16874.0, "pass", "independent")}, ref, "ref") == []  # value not compared
    assert "verdict pass in reference, now fail" in compare(
        {"speedup": (3.0, "fail", "independent")}, ref, "ref")[0]
    # a counted pass that is no longer counted (no rival fails it any more) is drift too
    assert "evidence independent in reference, now construction" in compare(
        {"speedup": (16874.0, "pass", "construction")}, ref, "ref")[0]
    for prof, status in (("ci", "pass"), ("default", "fail")):
        d = tmp_path / prof
        d.mkdir()
        (d / "p.csv").write_text(",".join(HEADER) + f"\nq,1.0,{status},value,0,1e-9,native\n")
    problems = profiles_agree(tmp_path, "p", None)
    assert len(problems) == 1 and "profile_differs_why" in problems[0]
    # the coarser ci profile may be undecided where the default decides, not the other way
    for ci, default in (("inconclusive", "pass"), ("not_converged", "fail"),
                           ("pass", "inconclusive")):
        for prof, status in (("ci", ci), ("default", default)):
            (tmp_path / prof / "p.csv").write_text(",".join(HEADER) + f"\nq,1.0,{status},value,0,1e-9,native\n")
        assert len(profiles_agree(tmp_path, "p", None)) == (ci == "pass"), (ci, default)


def test_cli_errors_are_readable(tmp_path):
    env = {**os.environ, "PYTHONPATH": str(healmod.Path(healmod.__file__).parents[1])}

    def cli(*args):
        return subprocess.run([sys.executable, "-m", "mechrepro.cli", *args], cwd=tmp_path,
                              capture_output=True, text=True, env=env)

    for args, rc, text in [((), 2, "usage"), (("--help",), 0, "gather"),
                           (("verify", "results"), 1, "no manifest"),
                           (("archive", "x"), 2, "needs at least"),
                           (("nonsense",), 2, "unknown command")]:
        out = cli(*args)
        assert out.returncode == rc and text in out.stdout + out.stderr, (args, out)
        assert "Traceback" not in out.stderr, out.stderr
    # the researcher's entry point (`mechrepro`, experiment.main), outside a project
    for args, rc, text in [((), 2, "usage"), (("--help",), 0, "project directory"),
                           (("exp", "run", "--help"), 0, "PAPER.KEY=VALUE"),
                           (("exp", "run", "t", "--set", "saw_chain.x=1"), 2,
                            "run mechrepro in the project directory"),
                           (("diff", "a", "b"), 2, "a: no such file"),
                           (("nonsense",), 2, "invalid choice")]:
        out = subprocess.run([sys.executable, "-m", "mechrepro.experiment", *args], cwd=tmp_path,
                             capture_output=True, text=True, env=env)
        assert out.returncode == rc and text in out.stdout + out.stderr, (args, out)
        assert "Traceback" not in out.stderr, out.stderr


# --- scene-precision reruns ---------------------------------------------------------------

# per paper: (scene, parameter, new value) -- None: the scene gets an override of the
# paper's first numeric parameter, 0.1 % off
SCENE_EDITS = {
    "saw_chain": ("speed_12000", "sprocket_speed", 11000),
    "rolling_shear": None,
    "joint_wear": None,
    "disk_tension": ("buckling", "rolling_radius", [100]),
    "chain_drive": ("fig09b", "driven_inertia", 0.0006),   # a job of its own
}


def _edit(raw, paper):
    spec = SCENE_EDITS[paper]
    if spec is None:
        name, p = next((k, v) for k, v in raw["parameters"].items()
                       if isinstance(v.get("value"), float) and not v.get("calibrated_on"))
        spec = (next(iter(raw["scenes"])), name, p["value"] * 1.001)
    scene, key, value = spec
    raw["scenes"][scene].setdefault("parameters", {})[key] = value
    return scene


@pytest.mark.parametrize("paper", list(SCENE_EDITS))
def test_one_parameter_in_one_scene_reruns_exactly_its_solve_jobs(paper, workflow):
    """In the session's ci run, edit one parameter of one scene and ask Snakemake (dry run,
    its reasons) what it would solve again: exactly the jobs holding a run whose record
    changed, none other (a job's results record the digest of its own run records).  The edit
    is undone after the dry run, which writes nothing (solving each paper again in a copy
    of its own cost 1,200 s of a loaded suite)."""
    import yaml

    from mechrepro.config import load_paper
    from test_pipeline import scheduled

    work, _ = workflow
    path = work / "config" / "papers" / f"{paper}.yaml"
    original = path.read_text()
    cfg = load_paper(path, "ci")
    targets = [f"results/{paper}/runs/{r}.nc" for r in cfg.runs] + \
              [f"results/{paper}/studies/{s}.nc" for s in cfg.studies]
    args = ["--cores", "2", "--config", "profile=ci", f"papers=[{paper}]"]
    try:
        raw = yaml.safe_load(original)
        scene = _edit(raw, paper)
        path.write_text(yaml.safe_dump(raw, sort_keys=False))
        after = load_paper(path, "ci")
        dry = snakemake_fork.run([*targets, "-n", *args], work)
    finally:
        path.write_text(original)
    changed = {r for r in after.runs if after.runs[r] != cfg.runs.get(r)}
    assert changed and all(after.runs[r]["scene"] == scene for r in changed), changed
    expected = {f"solve_{paper}__{job}" for job, runs in after.solve_jobs().items()
                if changed & set(runs)}
    jobs = scheduled(dry.stdout) - {"all"}
    assert jobs == expected, (jobs, expected, dry.stdout[-3000:])
    assert "changed since it was made: its run records" in dry.stdout + dry.stderr
    if paper == "chain_drive":
        assert jobs == {"solve_chain_drive__scene_fig09b"}


# --- bad input: refused before any job, nothing lost --------------------------------------

@pipeline
@pytest.mark.parametrize("edit, expect", [
    (lambda t: t.replace('{value: 32,    unit: "1", source: "Sec. 4 (M)"',
                         '{value: .nan,  unit: "1", source: "Sec. 4 (M)"'),
     "parameters.tie_straps_tight_side.value = nan"),
    (lambda t: t + "\nscenes:\n  x: {solver: difference_method, effects: []}\n",
     "'scenes' given twice"),
    (lambda t: t.replace("{value: 8.91,  unit: mm,", "{value: 8.91,  unit: m,"),
     "chain pitch between 3 mm and 200 mm"),
    (lambda t: t.replace("Sec. 4 (p1)", "Sec. 4 (p1) \udce9"), "not UTF-8"),
    (lambda t: t.replace("scenes: {fig07_fig08: {resolution: {K: 300}},",
                         "scenes: {fig07_fig08: {resolution: {K: 50000}},"),
     "resolution.K = 50000: beyond K = 39434"),
    (lambda t: t.replace("speed_12000: {solver: difference_method, outputs: [textbook],",
                         "speed_12000: {solver: difference_method, outputs: [],"),
     "scenes.speed_12000.outputs = []"),
    (lambda t: t.replace("scenes: {fig07_fig08: {resolution: {K: 300}},",
                         "scenes: {accuracy: {resolution: {K: 9000000}}, "
                         "fig07_fig08: {resolution: {K: 300}},"),
     "expected to take 2900 MB, above the solve rule's 2000 MB"),
], ids=["nan", "duplicate scenes", "8.91 m pitch", "latin-1 byte", "K beyond round-off",
        "emptied effects", "memory above the rule"])
def test_bad_input_stops_a_real_run_before_any_job_and_loses_nothing(bad_run, tmp_path, edit,
                                                                     expect):
    _refused_and_nothing_lost(bad_run, tmp_path, edit, [expect])


def _bad_inputs():
    from test_inputs import BAD

    return BAD


@pipeline
@pytest.mark.parametrize("name, edit, expect", _bad_inputs(), ids=[b[0] for b in _bad_inputs()])
def test_every_bad_input_class_of_test_inputs_loses_nothing(bad_run, tmp_path, name, edit,
                                                            expect):
    _refused_and_nothing_lost(bad_run, tmp_path, edit, expect)


def _refused_and_nothing_lost(run, tmp_path, edit, expect):
    work = tmp_path / "w"
    # the refused paper's results and the run's own (report, archive), not the other
    # papers' (a run of BAD_PAPER alone never reaches them: copied, they would only cost time)
    others = {p.stem for p in (run / "config" / "papers").glob("*.yaml")} - {BAD_PAPER}
    shutil.copytree(run, work, symlinks=True, ignore=lambda d, names:
                    others & set(names) if d == str(run / "results") else ())
    before = hashes(work / "results")
    path = work / "config" / "papers" / f"{BAD_PAPER}.yaml"
    text = path.read_text()
    assert edit(text) != text, "the edit does not match the config: update the test"
    path.write_bytes(edit(text).encode("utf-8", "surrogateescape"))
    proc = sm(work, check=False, paper=BAD_PAPER)
    out = proc.stdout + proc.stderr
    assert proc.returncode != 0 and f"config/papers/{BAD_PAPER}.yaml" in out, out[-2000:]
    assert all(e in out for e in expect), (expect, out[-2000:])
    assert "rule " not in out and "Traceback" not in out, out[-2000:]
    assert hashes(work / "results") == before


@pipeline
def test_plain_snakemake_recovers_from_an_interrupted_run(run, tmp_path):
    """With the workflow profile (profiles/default), a plain `snakemake` reruns the jobs a
    kill left incomplete, as `make reproduce` does with --rerun-incomplete."""
    from conftest import ROOT

    work = tmp_path / "w"
    shutil.copytree(run, work, symlinks=True)
    shutil.copytree(ROOT / "profiles", work / "profiles", dirs_exist_ok=True)   # conftest copies it too
    proc = subprocess.Popen([*SM, "--forcerun", f"validate_{PAPER}"], cwd=work,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            start_new_session=True)
    marker = work / ".snakemake" / "incomplete"
    deadline = time.time() + 120
    while time.time() < deadline and proc.poll() is None and not (
            marker.is_dir() and any(marker.iterdir())):
        time.sleep(0.02)
    os.killpg(proc.pid, signal.SIGKILL)
    proc.wait()
    sm(work, "--unlock")
    sm(work)   # no --rerun-incomplete: the profile gives it
    assert "Nothing to be done" in sm(work, "-n").stdout


@pipeline
def test_the_archived_report_is_self_contained_with_a_saved_plan(run, tmp_path):
    import re
    import tarfile

    from mechrepro.plan import main as plan

    work = tmp_path / "w"
    shutil.copytree(run, work, symlinks=True)
    log = sorted((work / ".snakemake" / "log").glob("*.snakemake.log"))[-1]
    os.chdir(work)
    try:
        assert plan(["results", str(log)]) == 0      # what `make` does after a run
    finally:
        os.chdir(tmp_path)
    sm(work, "--forcerun", "report")
    page = (work / "results" / f"report-{PAPER}" / "index.html").read_text()
    out = tmp_path / "x"
    with tarfile.open(archive_dir(work) / "mechrepro-results.tar.gz") as tar:
        tar.extractall(out, filter="data")
    links = re.findall(r'(?:src|href)="([^"#:]+)"', page)
    broken = [l for l in links if not (out / f"report-{PAPER}" / l).resolve().exists()]
    assert links and not broken, broken


@pipeline
def test_a_failing_solve_job_keeps_its_last_good_results(run, tmp_path):
    """The solve job fails after writing its first run (a solver crash injected into the
    copy's code): every run and study of the batch is back as it was (update() outputs),
    heal keeps them, and fixing the cause reruns the job (the kept runs were made by other
    code than the fixed one)."""
    work = tmp_path / "w"
    shutil.copytree(run, work, symlinks=True)
    solved = {p.name: file_sha256(p) for d in ("runs", "studies")
              for p in (work / "results" / PAPER / d).glob("*.nc")}
    solve = work / "src" / "mechrepro" / "solve.py"
    original = solve.read_text()
    hook = '        write_dataset(ds, root / "runs" / f"{name}.nc", run)\n'
    assert hook in original
    solve.write_text(original.replace(hook, hook + '        raise RuntimeError("injected")\n'))
    proc = sm(work, check=False)
    assert proc.returncode != 0 and "Restored previous version" in proc.stderr
    assert "injected" in (work / "results" / PAPER / "logs" / "solve" / "batch.log").read_text()
    now = {p.name: file_sha256(p) for d in ("runs", "studies")
           for p in (work / "results" / PAPER / d).glob("*.nc")}
    assert now == solved
    assert "[heal] removed" not in sm(work, "-n").stderr
    before = set(healmod.inspect(work / "results")[0])
    assert not before, before
    # the cause fixed by another edit than the original: what made the kept results (the
    # original code) is not today's code, so the job reruns
    solve.write_text(original + "\n# fixed\n")
    out = sm(work)
    assert "[heal] removed" not in out.stderr and f"solve_{PAPER}__batch" in out.stdout + out.stderr
    assert "Nothing to be done" in sm(work, "-n").stdout


def test_a_profile_difference_passes_only_with_its_reason(tmp_path, edit_config, config_copy):
    from mechrepro.reference import HEADER, profiles_agree

    q = "tight_side_velocity_max"
    for prof, status in (("ci", "pass"), ("default", "fail")):
        (tmp_path / prof).mkdir()
        (tmp_path / prof / "saw_chain.csv").write_text(
            ",".join(HEADER) + f"\n{q},14.4,{status},value,0,1e-9,native\n")
    assert len(profiles_agree(tmp_path, "saw_chain", config_copy)) == 1
    edit_config("saw_chain", lambda raw: raw["reported"][q].update(
        profile_differs_why="the ci resolution cannot resolve the band (test)"))
    assert profiles_agree(tmp_path, "saw_chain", config_copy) == []


def test_heal_leaves_results_alone_while_snakemake_locks_name_them(tmp_path, monkeypatch):
    """A master killed with kill -9 leaves Snakemake's locks and maybe jobs still writing:
    heal touches nothing until `snakemake --unlock` (the README's recovery)."""
    monkeypatch.chdir(tmp_path)
    res = tmp_path / "results"
    part = res / "p" / "runs" / ".r.x.part.nc"
    part.parent.mkdir(parents=True)
    part.write_text("an orphaned job is writing this")
    locks = tmp_path / ".snakemake" / "locks"
    locks.mkdir(parents=True)
    (locks / "0.output.lock").write_text("results/p/runs/r.nc\n")
    lines = healmod.heal("results")
    healmod.release("results")
    assert part.exists() and "snakemake --unlock" in lines[0]
    (locks / "0.output.lock").write_text("results-ci/p/runs/r.nc\n")   # another results dir
    healmod.heal("results")
    healmod.release("results")
    assert not part.exists()


@pipeline
def test_make_and_plain_snakemake_name_the_interpreter_alike(run):
    """`make` runs `.venv/bin/python -m snakemake`, the script `.venv/bin/snakemake` runs
    `.venv/bin/python3`: either way the jobs' command is the same (it is a param: a second
    spelling reran every job)."""
    from pathlib import Path

    other = Path(sys.prefix) / "bin" / ("python3" if Path(sys.executable).name == "python"
                                        else "python")
    if not other.exists():
        pytest.skip(f"{other} does not exist")
    proc = subprocess.run([str(other), "-m", "snakemake", *SM[3:], "-n"], cwd=run,
                          capture_output=True, text=True, timeout=300)
    assert "Nothing to be done" in proc.stdout, proc.stdout[-3000:]


@pipeline
def test_a_failing_notebook_job_keeps_its_last_good_figures(run, tmp_path):
    """update() outputs of validate_/notebook_: a notebook failing after it drew every
    figure gets the last good notebook, figures and tables back; fixed, it reruns."""
    work = tmp_path / "w"
    shutil.copytree(run, work, symlinks=True)
    res = work / "results" / PAPER
    drawn = {str(p.relative_to(res)): file_sha256(p) for p in
             [*res.glob("figures/*.png"), res / "notebook.ipynb"]}
    nb = work / "notebooks" / f"{PAPER}.py"
    original = nb.read_text()
    nb.write_text(original + '\n\nraise RuntimeError("injected notebook failure")\n')
    proc = sm(work, check=False)
    out = proc.stdout + proc.stderr
    assert proc.returncode != 0 and "injected notebook failure" in out   # the cause, on the console
    assert "Restored previous version" in out
    assert {k: file_sha256(res / k) for k in drawn} == drawn
    nb.write_text(original)
    sm(work)
    assert "Nothing to be done" in sm(work, "-n").stdout


def _read_only(work, target, cmd):
    """Run ``cmd`` in ``work`` with ``target`` read-only: a read-only bind mount in a mount
    namespace of its own when run as root (root ignores file modes), ``chmod -R a-w``
    otherwise (put back after)."""
    if os.geteuid() == 0:
        if not shutil.which("unshare"):
            pytest.skip("root without unshare: cannot make a directory read-only")
        # cd after the mount: a working directory entered before it stays writable
        script = ('mount --bind "$1" "$1" && mount -o remount,bind,ro "$1" && cd "$0" '
                  '&& shift && exec "$@"')
        probe = subprocess.run(["unshare", "-m", "sh", "-c", script, str(work), str(target),
                                "true"], capture_output=True)
        if probe.returncode != 0:
            pytest.skip(f"no read-only bind mount here: {probe.stderr.decode()[-200:]}")
        return subprocess.run(["unshare", "-m", "sh", "-c", script, str(work), str(target), *cmd],
                              cwd=work, capture_output=True, text=True, timeout=600)
    subprocess.run(["chmod", "-R", "a-w", str(target)], check=True)
    try:
        return subprocess.run(cmd, cwd=work, capture_output=True, text=True, timeout=600)
    finally:
        subprocess.run(["chmod", "-R", "u+w", str(target)], check=True)


@pipeline
@pytest.mark.parametrize("target", ["results", "project"])
def test_a_read_only_project_stops_with_one_line_even_on_a_no_op(run, tmp_path, target):
    """Read-only results (or the whole project, .snakemake/ included): a run, even one with
    nothing to do, and `make reproduce` stop before writing anything, with one line naming
    the directory and what to do; no traceback, nothing changed."""
    from conftest import ROOT

    work = tmp_path / "w"
    shutil.copytree(run, work, symlinks=True)
    for f in ("Makefile", "requirements.lock", "pyproject.toml"):
        shutil.copy2(ROOT / f, work / f)
    assert "Nothing to be done" in sm(work, "-n").stdout   # a no-op
    before = hashes(work / "results")
    ro = work / "results" if target == "results" else work
    venv = ROOT / ".venv"
    # -o: never remake the project's venv from this copy (a stamp older than
    # requirements.lock would reinstall it, its editable install pointing here)
    make = (["make", f"VENV={venv}", "-o", str(venv / ".installed"), "reproduce"]
            if (venv / ".installed").exists() else None)
    for cmd in [SM] + ([make] if make else []):
        proc = _read_only(work, ro, cmd)
        out = proc.stdout + proc.stderr
        assert proc.returncode != 0 and "Traceback" not in out, out[-3000:]
        lines = [l for l in proc.stderr.splitlines() if l.startswith("cannot run:")]
        name = "results" if target == "results" else ".snakemake"
        assert len(lines) == 1 and f"{name} is read-only" in lines[0], out[-3000:]
        assert "chmod -R u+w" in lines[0] and "nothing was changed" in lines[0]
    if target == "project":   # a dry run needs .snakemake/ too
        proc = _read_only(work, ro, [*SM, "-n"])
        assert proc.returncode != 0 and "Traceback" not in proc.stdout + proc.stderr
        assert "cannot run: .snakemake is read-only" in proc.stderr
    assert hashes(work / "results") == before


def test_make_venv_relocates_a_moved_project(tmp_path):
    """`make venv` in a moved project (its .venv built elsewhere, stamp up to date) rewrites
    the console scripts' shebangs and the editable install to where the project now is."""
    from conftest import ROOT, moved_venv

    if not shutil.which("make"):
        pytest.skip("no make")
    proj = tmp_path / "moved"
    (proj / "scripts").mkdir(parents=True)
    for f in ("Makefile", "requirements.lock", "pyproject.toml", "scripts/relocate_venv.py"):
        shutil.copy2(ROOT / f, proj / f)
    site, venv = moved_venv(proj), proj / ".venv"
    tool = venv / "bin" / "tool"
    tool.write_text("#!/old/place/.venv/bin/python3\nprint('ran')\n")
    tool.chmod(0o755)
    pth = site / "__editable__.mechrepro-0.1.pth"
    out = subprocess.run(["make", "venv"], cwd=proj, capture_output=True, text=True)
    assert out.returncode == 0, out.stdout + out.stderr
    assert tool.read_text().splitlines()[0] == f"#!{venv / 'bin' / 'python3'}"
    assert subprocess.run([str(tool)], capture_output=True, text=True).stdout == "ran\n"
    assert pth.read_text().strip() == str(proj / "src")
    again = subprocess.run(["make", "venv"], cwd=proj, capture_output=True, text=True)
    assert "already relocated" in again.stdout


@pipeline
def test_a_disk_full_while_archiving_is_archived_again_once_there_is_room(run, tmp_path):
    """The disk fills while the archive is written (a tmpfs of the results' size plus room
    for the new tables and figures, whose old versions update() keeps aside while their jobs
    run, but not for a second archive): Snakemake puts the last good archive back, but keeps the failed job's record,
    with the checksums of its new inputs, and would call that archive up to date.  The
    archive records what made it (its inputs' contents), which is not what would make it
    now, so the next run (the README's command, with room again) archives the new results
    and the manifest matches them."""
    if os.geteuid() != 0 or not shutil.which("unshare"):
        pytest.skip("needs root and unshare for a small tmpfs")
    work = tmp_path / "w"
    shutil.copytree(run, work, symlinks=True)
    saved = tmp_path / "saved"
    shutil.copytree(work / "results", saved, symlinks=True)
    used = sum(p.stat().st_size for p in saved.rglob("*") if p.is_file()) // 1024
    sm_cmd = " ".join(SM)
    script = f"""
cd {work}
mount -t tmpfs -o size={used + ROOM_K}k tmpfs results || exit 77
cp -a {saved}/. results/
{sm_cmd} --forcerun validate_{PAPER} > full.log 2>&1; echo "full=$?"
mount -o remount,size=200m results
{sm_cmd} > again.log 2>&1; echo "again=$?"
{sm_cmd} -n 2>&1 | grep -c "Nothing to be done"
PYTHONPATH={work / 'src'} {sys.executable} -c "from mechrepro.archive import verify; \
print('verify', verify('results', 'results/archive-{PAPER}/manifest.json'))"
"""
    out = subprocess.run(["unshare", "-m", "bash", "-c", script], capture_output=True,
                         text=True, timeout=900)
    if "full=" not in out.stdout:
        pytest.skip(f"no tmpfs here: {out.stderr[-300:]}")
    full = (work / "full.log").read_text()
    assert "full=1" in out.stdout and "No space left on device" in full, full[-2000:]
    assert "again=0" in out.stdout, (work / "again.log").read_text()[-3000:]
    assert f"[stale] archive: results/archive-{PAPER}/" in (work / "again.log").read_text()
    assert "verify []" in out.stdout, out.stdout
