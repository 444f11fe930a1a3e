"""Results decide their own staleness (mechrepro.staleness): a restored, metadata-less,
copied or touched project reruns exactly the jobs whose results were made by something
else than today's run records, code and packages, never by time stamps, and the archive
certifies only current results.

Each test breaks a copy of the toy paper's ci pipeline (conftest.toy_pipeline: the smallest
whole pipeline; staleness does not depend on the paper) as a user would, then runs Snakemake
as `make ci-reproduce` does.
"""
import json
import os
import shutil

import pytest
import yaml

import conftest
from mechrepro.archive import verify
from mechrepro.io import open_dataset, read_sum, run_attrs

pytestmark = pytest.mark.slow

PAPER, TAG = "toy", "-toy"
SOLVE = f"rule solve_{PAPER}__batch:"
# the edit: one parameter of one scene, set in its config to SCALE times its value
SCENE, PARAM, SCALE = "response", "stiffness", 12500 / 12000
SOURCE = f"src/mechrepro/models/{PAPER}/__init__.py"    # a module its solve job imports
DRIFT = "natural_frequency: reference"      # the reference check's line for the edited row
OLD_TIME = 946_684_800 * 10**9     # 2000-01-01: an edit that keeps an old time stamp


def snakemake(work, *args, check=True):
    return conftest.snakemake(work, *args, check=check,
                              base=[*conftest.SNAKEMAKE, f"papers=[{PAPER}]"])


@pytest.fixture(scope="module")
def wf(tmp_path_factory):
    return conftest.toy_pipeline(tmp_path_factory, tmp_path_factory.mktemp("st"))


@pytest.fixture
def copy(wf, tmp_path):
    work, _ = wf
    shutil.copytree(work, tmp_path / "w", symlinks=True)
    return tmp_path / "w"


def set_param(work, keep_time=False):
    """PARAM of scene SCENE, set in its config to SCALE times the paper's value."""
    path = work / "config" / "papers" / f"{PAPER}.yaml"
    st = path.stat()
    raw = yaml.safe_load(path.read_text())
    value = raw["parameters"][PARAM]["value"] * SCALE
    raw["scenes"][SCENE].setdefault("parameters", {})[PARAM] = value
    path.write_text(yaml.safe_dump(raw, sort_keys=False))
    if keep_time:
        os.utime(path, ns=(st.st_atime_ns, st.st_mtime_ns))


def recorded(work):
    ds = open_dataset(work / "results" / PAPER / "runs" / f"{SCENE}.nc")
    return run_attrs(ds)["parameters"]


def rerun_after_the_edit(work, before):
    """The edited scene is solved again: its result records the new value, the reference
    check sees the new numbers drift and the archive refuses them (the last one is kept)."""
    log = snakemake(work, check=False)
    assert SOLVE in log, log[-3000:]
    assert recorded(work)["values_si"][PARAM] == pytest.approx(before * SCALE, rel=1e-12)
    assert DRIFT in log and "not archiving" in log
    return log


def current(work):
    """Nothing left to do, and the archive's records match today's config and code."""
    assert "Nothing to be done" in snakemake(work, "-n")
    assert verify(work / "results", work / "results" / f"archive{TAG}" / "manifest.json") == []


def test_every_result_records_what_made_it(wf):
    work, _ = wf
    results = work / "results" / PAPER
    for f in [*results.glob("runs/*.nc"), *results.glob("tables/*.csv"),
              *results.glob("figures/*.png"), results / "notebook.ipynb"]:
        made_by = read_sum(f)["made_by"]
        assert {"code", "packages", "inputs"} <= set(made_by), f
    attrs = run_attrs(open_dataset(results / "runs" / f"{SCENE}.nc"))
    assert json.loads(attrs["made_by"])["record"] == read_sum(
        results / "runs" / f"{SCENE}.nc")["made_by"]["record"]


def test_the_toy_pipeline_is_whole_and_its_additions_stay_in_the_copy(wf):
    """conftest.toy_pipeline: its ci run passed the reference check and was archived, with
    the study it adds (TOY_ADDED) solved; tests/toy_paper itself has neither the study nor
    the ci overlay (test_adding_a_paper counts its keys)."""
    work, _ = wf
    check = (work / "results" / f"report{TAG}" / "reference_check.txt").read_text()
    assert check.splitlines()[0].endswith(": OK") and f"{PAPER}: 1 quantities" in check, check
    assert verify(work / "results", work / "results" / f"archive{TAG}" / "manifest.json") == []
    assert (work / "results" / PAPER / "studies" / "steps.nc").exists()
    copied = yaml.safe_load((work / "config" / "papers" / f"{PAPER}.yaml").read_text())
    assert {"studies", "profiles"} <= set(copied)
    own = yaml.safe_load((conftest.TOY / "config" / "papers" / f"{PAPER}.yaml").read_text())
    assert not {"studies", "profiles"} & set(own)


def test_restore_then_edit_reruns_the_solve(wf, tmp_path):
    """The archive restored into a fresh checkout schedules nothing but its own archive; an
    edit of one scene then reruns its solve job, whose new numbers the reference check sees."""
    from mechrepro.experiment import restore

    work, _ = wf
    (tmp_path / "fresh").mkdir()
    fresh = conftest.toy_workflow(tmp_path / "fresh",
                                  work / "results" / "reference" / "ci" / f"{PAPER}.csv")
    restore(work / "results" / f"archive{TAG}" / "mechrepro-results.tar.gz", fresh)
    from test_pipeline import scheduled

    # restore puts the archive under archive/, where this one-paper run's is archive-toy/
    assert scheduled(snakemake(fresh, "-n")) <= {"archive", "all"}
    set_param(fresh)
    log = rerun_after_the_edit(fresh, recorded(work)["values_si"][PARAM])
    assert "changed since it was made: its run records" in log


def test_no_metadata_then_edit_with_an_old_time_stamp(copy):
    """`rm -rf .snakemake`, then the config edited with its old time stamp kept (as `cp -p`
    from a backup leaves it): the solve reruns, from what the result records."""
    shutil.rmtree(copy / ".snakemake")
    before = recorded(copy)["values_si"][PARAM]
    set_param(copy, keep_time=True)
    rerun_after_the_edit(copy, before)


def test_a_source_edit_with_an_old_time_stamp_reruns_its_jobs(copy):
    src = copy / SOURCE
    src.write_text(src.read_text() + "\n# an edit restored from a backup with cp -p\n")
    os.utime(src, ns=(OLD_TIME, OLD_TIME))
    log = snakemake(copy)
    assert SOLVE in log and "the code it imports" in log, log[-3000:]
    current(copy)


def test_time_stamps_never_decide(copy):
    """Without metadata, every source, config and benchmark file touched: nothing reruns
    (their contents did not change); then an edit with benchmarks touched reruns the solve."""
    shutil.rmtree(copy / ".snakemake")
    for top in ("src", "config", "notebooks", "workflow", "results"):
        for p in (copy / top).rglob("*"):
            if p.is_file() and (top != "results" or "benchmarks" in p.parts):
                os.utime(p)
    assert "Nothing to be done" in snakemake(copy, "-n")
    before = recorded(copy)["values_si"][PARAM]
    set_param(copy, keep_time=True)
    for p in (copy / "results").rglob("benchmarks/*"):
        os.utime(p)
    rerun_after_the_edit(copy, before)


def test_the_archive_refuses_a_result_that_is_not_current(copy):
    """A result whose record says another package set made it is named, not archived."""
    from mechrepro.archive import ArchiveRefused, certify

    results = copy / "results"
    f = results / PAPER / "runs" / f"{SCENE}.nc"
    side = f.parent / f".{f.name}.sum"
    rec = json.loads(side.read_text())
    rec["made_by"]["packages"] = "0" * 64
    side.write_text(json.dumps(rec))
    with pytest.raises(ArchiveRefused, match=f"{SCENE}.nc: changed since it was made: .*the "
                                             "package set"):
        certify(results, [str(f)], results / f".jobs{TAG}.json")


def test_the_snakemake_step_steered_is_there():
    """heal.steer_workflow wraps Workflow._prepare_dag and sets the DAG's
    rules_allowed_for_needrun (Snakemake 9): an upgrade that renames either fails here,
    not silently in a run."""
    import inspect

    import snakemake.api  # noqa: F401  (Snakemake's modules import each other in this order)
    from snakemake.dag import DAG
    from snakemake.workflow import Workflow

    assert "rules_allowed_for_needrun" in inspect.signature(DAG.__init__).parameters
    src = inspect.getsource(Workflow._prepare_dag)
    assert "self._dag = DAG(" in src and "forcerun" in src
