"""The workflow on a real (local, single-node) SLURM cluster through the executor plugin.

Starts the cluster with scripts/slurm_local.sh (installs Debian's munge/slurm packages if
missing), runs a reduced study through `--profile profiles/slurm`, checks that the jobs
really were SLURM jobs, that the gathered study equals the local run's values, and that a
failing job is reported as failed.  Skipped, with the reason, only where the machine
cannot install packages (not root, or no apt-get).
"""
import os
import re
import shutil
import subprocess
import sys

import numpy as np
import pytest
import yaml

from conftest import ROOT, copy_workflow
from mechrepro.config import load_paper
from mechrepro.inputs import read_yaml
from mechrepro.io import open_dataset

pytestmark = pytest.mark.slow
SCRIPT = ROOT / "scripts" / "slurm_local.sh"
STUDY = "saw_chain/studies/cost_of_accuracy.nc"


def can_install() -> str | None:
    if os.geteuid() != 0:
        return "not root: cannot install or start SLURM daemons"
    if shutil.which("slurmctld") is None and shutil.which("apt-get") is None:
        return "no slurmctld and no apt-get to install it"
    return None


@pytest.fixture(scope="module")
def cluster():
    reason = can_install()
    if reason:
        pytest.skip(f"SLURM test skipped: {reason}")
    proc = subprocess.run(["bash", str(SCRIPT), "start"], capture_output=True, text=True,
                          timeout=600)
    assert proc.returncode == 0, proc.stderr
    print(proc.stderr.strip())
    yield
    subprocess.run(["bash", str(SCRIPT), "stop"], capture_output=True, text=True, timeout=120)


@pytest.fixture(scope="module")
def work(tmp_path_factory):
    return copy_workflow(tmp_path_factory.mktemp("slurm_wf"))


def snakemake(work, results, *args, timeout=900):
    cmd = ["timeout", "-k", "10", str(timeout), sys.executable, "-m", "snakemake", *args,
           "--config", "profile=ci", "papers=[saw_chain]", f"results={results}"]
    return subprocess.run(cmd, cwd=work, capture_output=True, text=True)


def slurm(work, target):
    # the first status check 1 s after submission, not the profile's 5 s: the executor adds
    # 10 s to its interval after every check that sees no job end, and it sleeps one more
    # interval after a failure before it exits, so a check that comes before this
    # one-node cluster's first job ends costs 10-25 s (the failing job's test: 47 s)
    return snakemake(work, "results-slurm", "--profile", str(ROOT / "profiles" / "slurm"),
                     "--default-resources", "slurm_partition=debug", "--slurm-no-account",
                     "--slurm-keep-successful-logs",
                     "--slurm-init-seconds-before-status-checks", "1", target)


def test_study_runs_as_slurm_jobs_and_equals_local(cluster, work):
    # fan the study out (one solver job per run, as a costly study would be), cut to three
    # runs: one of them repeats the scene `accuracy` (K 100) and is solved in the batch job,
    # so three SLURM jobs run; its eleven ci runs were twelve jobs on the node's two CPUs,
    # and the executor's polling (its interval grows 10 s per round that sees no job end)
    # made the test 64 s, nearly all of it waiting
    cfg = work / "config" / "papers" / "saw_chain.yaml"
    raw = read_yaml(cfg)
    raw["fan_out"] = ["cost_of_accuracy"]
    raw["profiles"]["ci"]["studies"]["cost_of_accuracy"]["sweep"]["K"] = [30, 100, 300]
    cfg.write_text(yaml.safe_dump(raw))
    local = snakemake(work, "results-local", "--cores", "2", f"results-local/{STUDY}")
    assert local.returncode == 0, local.stderr[-3000:]
    proc = slurm(work, f"results-slurm/{STUDY}")
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    # every solver job left a SLURM log named by its SLURM job id, and SLURM knows those ids
    logs = [p for d in (work / ".snakemake" / "slurm_logs").glob("rule_solve_saw_chain__cost_of_accuracy_*")
            for p in d.rglob("*.log")]
    ids = {p.stem for p in logs}
    # one job per run of the study, but a run repeating another (a scene's run) is solved
    # in that run's job (PaperConfig.same_solve)
    paper = load_paper(cfg, "ci")
    n_jobs = sum(r not in paper.same_solve() for r in paper.studies["cost_of_accuracy"])
    n_runs = len(open_dataset(work / "results-local" / STUDY)["run"])
    assert n_jobs == n_runs - 1 == 2     # cost_of_accuracy-001 (K 100) repeats the scene accuracy
    assert len(ids) == n_jobs and all(i.isdigit() for i in ids)
    known = subprocess.run(["squeue", "-t", "all", "-h", "-o", "%i %T"], capture_output=True,
                           text=True).stdout
    states = dict(line.split() for line in known.splitlines())
    assert all(states.get(i) == "COMPLETED" for i in ids), (ids, states)
    # the gathered study equals the local one (wall time is a measurement, not a result)
    a, b = open_dataset(work / "results-local" / STUDY), open_dataset(work / "results-slurm" / STUDY)
    assert set(a.data_vars) == set(b.data_vars)
    for name in a.data_vars:
        if not name.endswith("_time"):  # timings are measurements, not results
            assert np.array_equal(a[name].values, b[name].values), name
    assert list(a["K"].values) == list(b["K"].values)


def test_failing_slurm_job_is_reported_failed(cluster, work):
    # a solver crash injected into the copy's code (a bad config is refused at load now,
    # before any job is submitted: mechrepro.limits)
    solve = work / "src" / "mechrepro" / "solve.py"
    hook = '        write_dataset(ds, root / "runs" / f"{name}.nc", run)\n'
    assert hook in solve.read_text()
    solve.write_text(solve.read_text().replace(
        hook, '        raise RuntimeError("injected crash " + name)\n' + hook))
    proc = slurm(work, "results-slurm/saw_chain/runs/fig07_fig08.nc")
    assert proc.returncode != 0
    out = proc.stdout + proc.stderr
    m = re.search(r"SLURM-job '(\d+)' failed", out)
    assert m, out[-3000:]
    log = (work / "results-slurm" / "saw_chain" / "logs" / "solve" / "batch.log").read_text()
    assert "injected crash" in log
    assert not (work / "results-slurm" / "saw_chain" / "runs" / "fig07_fig08.nc").exists()
