import os
import shutil
import sys
from pathlib import Path

import pytest
import yaml

ROOT = Path(__file__).resolve().parent.parent
# one BLAS thread per test process (read when numpy loads, so before any worker imports it):
# xdist runs a worker per core and more, and OpenBLAS threads would spin on cores the other
# workers use
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")


def pytest_configure(config):
    """xdist hands out groups largest first (`--loadscope-reorder`, its default), which
    ranks by test count and puts one-test groups that take minutes last; the order of
    :func:`pytest_collection_modifyitems` is the schedule."""
    if hasattr(config.option, "loadscopereorder"):
        config.option.loadscopereorder = False


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(config, items):
    """Under xdist (`make test`: `-n 3 --dist loadgroup` on 2 cores) a worker takes whole groups: every
    test that reads the session's ci pipeline run goes to one group, so the pipeline runs
    once; every other test stays with its module, whose module-scoped fixtures (a SLURM
    cluster, a solved disk) are then set up once.  First among the hooks: xdist's own
    (which turns the marks into the groups) must see them (run after it, each worker would
    run the whole ci pipeline)."""
    groups = {}
    for item in items:
        group = "ci_pipeline" if "workflow" in getattr(item, "fixturenames", ()) else \
            item.nodeid.split("::")[0]
        item.add_marker(pytest.mark.xdist_group(group))
        if group == "ci_pipeline":     # it reads a pipeline run: `-m "not slow"` leaves it out
            item.add_marker(pytest.mark.slow)
        groups[item.nodeid] = group
    # the groups that take minutes go first (a worker takes groups in this order): the
    # session's ci run on one worker, SLURM on the other (mostly the executor waiting
    # between status checks, while the ci run's two-core jobs get both cores), then the
    # faults and the reliability tests; the many short groups last, where they even out
    # the workers' ends
    first = ("ci_pipeline", "tests/test_slurm.py", "tests/test_faults.py",
             "tests/test_reliability.py")
    items.sort(key=lambda i: first.index(groups[i.nodeid]) if groups[i.nodeid] in first
               else len(first))


_NICE = []


@pytest.hookimpl(tryfirst=True)
def pytest_runtest_setup(item):
    """Under xdist the session's ci pipeline is the longest chain of work (its run, then the
    tests that read it) and the suite is CPU-bound: a worker whose first test is not of that
    group yields the CPU to it (nice 10, inherited by all it starts, before any fixture), so
    the pipeline runs nearly as fast as alone while this worker fills the cores it leaves idle."""
    if not _NICE and os.environ.get("PYTEST_XDIST_WORKER"):
        _NICE.append(item.get_closest_marker("xdist_group").args[0] != "ci_pipeline")
        if _NICE[0]:
            os.nice(10)


@pytest.fixture(autouse=True)
def _in_the_repository(monkeypatch):
    """Every test starts in the repository (paths such as config/papers/... are relative to
    it), whatever directory an earlier test or the caller left."""
    monkeypatch.chdir(ROOT)


@pytest.fixture
def config_copy(tmp_path):
    """A writable copy of config/ (schemas + paper files) for mutation tests."""
    dst = tmp_path / "config"
    shutil.copytree(ROOT / "config", dst)
    return dst


@pytest.fixture
def edit_config(config_copy):
    """Apply ``fn`` to the parsed copy of a paper's config; return the edited file's path."""
    def edit(paper, fn):
        from mechrepro.inputs import read_yaml

        path = config_copy / "papers" / f"{paper}.yaml"
        raw = read_yaml(path)
        fn(raw)
        path.write_text(yaml.safe_dump(raw))
        return path
    return edit


def moved_venv(proj: Path) -> Path:
    """A stand-in `.venv` of a project moved from /old/place: this interpreter, an editable
    install naming the old place, a stamp newer than the lock (the venv counts as built).
    Returns its site-packages."""
    venv = proj / ".venv"
    site = venv / "lib" / "python3.11" / "site-packages"
    site.mkdir(parents=True)
    cfg = ROOT / ".venv" / "pyvenv.cfg"
    (venv / "pyvenv.cfg").write_text(cfg.read_text() if cfg.exists() else "")
    (venv / "bin").mkdir()
    for name in ("python", "python3"):
        (venv / "bin" / name).symlink_to(sys.executable)
    (site / "__editable__.mechrepro-0.1.pth").write_text("/old/place/src\n")
    (venv / ".installed").touch()
    return site


def copy_workflow(dst: Path) -> Path:
    """What a run of the workflow needs, copied to ``dst`` (tests never touch the repo)."""
    for item in ("Snakefile", "workflow", "config", "notebooks", "src", "profiles"):
        src = ROOT / item
        (shutil.copytree if src.is_dir() else shutil.copy2)(src, dst / item)
    shutil.copytree(ROOT / "results" / "reference", dst / "results" / "reference")
    return dst


SNAKEMAKE = [sys.executable, "-m", "snakemake", "--cores", "2", "--config", "profile=ci"]


def snakemake(work, *args, check=True, env=None, base=SNAKEMAKE):
    """`python -m snakemake` (``base``, then ``args``) in ``work``: forked from a process
    that has imported Snakemake (:mod:`snakemake_fork`), or a fresh one given ``env``."""
    import snakemake_fork

    assert base[:3] == SNAKEMAKE[:3], base
    proc = snakemake_fork.run([*base[3:], *args], work, env=env, timeout=2400)
    if check and proc.returncode != 0:
        raise AssertionError(f"snakemake {' '.join(args)} failed:\n{proc.stdout[-4000:]}\n"
                             f"{proc.stderr[-4000:]}")
    return proc.stdout + proc.stderr


def check_artefacts(work: Path, artefacts) -> tuple[Path, str]:
    """What `python -m mechrepro.cli artefact` runs, in ``work`` (with a copy of config/):
    the rows of ``artefacts`` (``chain_drive-fig05``) in
    ``work/results/<paper>/tables/validation-<artefacts>.csv``."""
    import contextlib
    import io
    import os

    from mechrepro.inputs import read_yaml
    from mechrepro.validation import check_artefacts as check

    shutil.copytree(ROOT / "config", work / "config")
    here, log = os.getcwd(), io.StringIO()
    os.chdir(work)      # the config cache (.snakemake/mechrepro) goes to the copy
    try:
        with contextlib.redirect_stdout(log):
            check(artefacts, "results", "config", "ci", read_yaml("config/config.yaml")["papers"])
    finally:
        os.chdir(here)
    return work, log.getvalue()


def one_paper_pipeline(tmp_path_factory, papers: str, dst: Path,
                       prepare=copy_workflow) -> tuple[Path, str]:
    """A copy in ``dst`` of the ci pipeline of ``papers`` (`papers=[saw_chain]`) in the
    workflow copy ``prepare`` makes, run once per test session whichever xdist worker asks
    first: each fault, reliability and staleness test breaks a copy of one such run, and
    built twice it was run twice.  The copy keeps the time stamps (a moved project with its
    results schedules nothing: test_faults), so the copy is as the run left it."""
    import fcntl

    base = tmp_path_factory.getbasetemp()
    # the workers' base directories share one parent per session (pytest-N/popen-gwK);
    # without xdist the base itself is the session's
    shared = base.parent if os.environ.get("PYTEST_XDIST_WORKER") else base
    built = shared / f"pipeline-{papers.replace(',', '+')}"
    log = built.with_suffix(".log")           # written last: the run finished
    with open(built.with_suffix(".lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)      # the other workers wait for the one building
        if not log.exists():
            shutil.rmtree(built, ignore_errors=True)
            built.mkdir()
            prepare(built)
            log.write_text(snakemake(built, base=[*SNAKEMAKE, f"papers=[{papers}]"]))
    shutil.copytree(built, dst, symlinks=True, dirs_exist_ok=True)
    return dst, log.read_text()


TOY = ROOT / "tests" / "toy_paper"
# what the fault, reliability and staleness tests need that the toy paper lacks (toy_workflow)
TOY_ADDED = """
studies:
  steps: {scene: response, description: "steps per period swept (tests: a study to break)",
    sweep: {steps_per_period: [16, 32, 64, 128]}}
profiles:
  ci:
    scenes: {response: {resolution: {steps_per_period: 32}}}
    studies:
      steps: {sweep: {steps_per_period: [16, 32, 64]}}
"""


def toy_workflow(dst: Path, reference: Path | None = None) -> Path:
    """A workflow copy in ``dst`` with the toy paper (tests/toy_paper, one scene, one figure,
    one reported row) added as test_adding_a_paper adds it, the cheapest whole pipeline to
    break: the faults, reliability and staleness tests run it (`papers=[toy]`).  Added in
    the copy only (tests/toy_paper stays as small as its test requires), TOY_ADDED: a study
    (`steps`, a sweep of steps_per_period on scene `response`: a study and its runs to
    break) and a `profiles: ci:` overlay (its scene and study coarser: profile input to
    break); and the toy's ci reference, so that its reference check and archive run: copied
    from ``reference`` (a built copy's results/reference/ci/toy.csv, as a checkout that
    commits the paper has it), or made by `python -m mechrepro.reference ci` (native
    platform only, as docs/ADDING_A_PAPER.md makes one)."""
    import subprocess

    copy_workflow(dst)
    for src in sorted(p for p in TOY.rglob("*") if p.is_file() and "__pycache__" not in p.parts):
        (dst / src.relative_to(TOY)).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(src, dst / src.relative_to(TOY))
    cfg = dst / "config" / "papers" / "toy.yaml"
    cfg.write_text(cfg.read_text() + TOY_ADDED)
    ref = dst / "results" / "reference" / "ci" / "toy.csv"
    if reference is not None:
        shutil.copy2(reference, ref)
        return dst
    proc = subprocess.run([sys.executable, "-m", "mechrepro.reference", "ci", "ref-ci",
                           "--papers", "toy", "--variants", "native"], cwd=dst,
                          capture_output=True, text=True, timeout=900)
    assert proc.returncode == 0 and ref.exists(), proc.stdout[-3000:] + proc.stderr[-3000:]
    shutil.rmtree(dst / "ref-ci")
    return dst


def toy_pipeline(tmp_path_factory, dst: Path) -> tuple[Path, str]:
    """A copy in ``dst`` of the toy's ci pipeline (:func:`toy_workflow`), run once per
    session (:func:`one_paper_pipeline`)."""
    return one_paper_pipeline(tmp_path_factory, "toy", dst, prepare=toy_workflow)


@pytest.fixture(scope="session")
def workflow(request, tmp_path_factory):
    """The ci-profile pipeline, run once per test session in a copy of the workflow under
    the platform variant ``ci_variant`` of config/reference.yaml (other BLAS kernels, numpy
    SIMD at its baseline, numba for a generic CPU): the committed reference was measured
    natively on another machine, so its check here compares two platforms; or, when every
    selected test that reads it is a per-artefact test (`pytest -k chain_drive-fig05`), no
    pipeline: only the selected artefacts' runs, solved in this process tree, and their
    rows (:func:`check_artefacts`)."""
    work = tmp_path_factory.mktemp("wf")
    artefacts = set()
    for item in request.session.items:
        if "workflow" not in getattr(item, "fixturenames", ()):
            continue
        params = getattr(item, "callspec", None) and item.callspec.params
        if item.module.__name__ != "test_artefacts" or not params:
            from mechrepro.reference import settings, variant_env

            copy_workflow(work)
            conf = settings(work / "config")
            return work, snakemake(work, env=variant_env(conf["variants"][conf["ci_variant"]]))
        artefacts.add(f"{params['paper']}-{params['artefact']}")
    return check_artefacts(work, sorted(artefacts))
