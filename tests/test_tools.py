"""What a user runs around the workflow: the Makefile's targets in a moved project and the
local SLURM cluster's script (no daemon started here: both run on stand-ins)."""
import os
import shutil
import subprocess
import sys

import pytest

from conftest import ROOT, moved_venv


def test_make_reproduce_finds_this_projects_package_in_a_moved_project(tmp_path):
    """A project moved with its `.venv`: the venv's editable install still names the old
    place, yet `make reproduce` (and `make ci-reproduce`) import this project's mechrepro
    (it failed with "No module named 'mechrepro'" before the Makefile gave PYTHONPATH=src).
    The stand-in venv has no Snakemake, so the run stops right after the import."""
    if not shutil.which("make"):
        pytest.skip("no make")
    proj = tmp_path / "moved"
    proj.mkdir()
    for f in ("Makefile", "requirements.lock", "pyproject.toml"):
        shutil.copy2(ROOT / f, proj / f)
    shutil.copytree(ROOT / "src", proj / "src", ignore=shutil.ignore_patterns("__pycache__"))
    moved_venv(proj)
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    for target in ("reproduce", "ci-reproduce"):
        out = subprocess.run(["make", target], cwd=proj, capture_output=True, text=True,
                             env=env, timeout=120)
        log = out.stdout + out.stderr
        assert "No module named 'mechrepro'" not in log, log
        assert "No module named snakemake" in log, log     # mechrepro.reproduce ran


SLURM = ROOT / "scripts" / "slurm_local.sh"
MARK = "# one node on loopback, written by scripts/slurm_local.sh"


def _slurm(state, conf, *args):
    env = {**os.environ, "MECHREPRO_SLURM_DIR": str(state), "MECHREPRO_SLURM_CONF": str(conf)}
    return subprocess.run(["bash", str(SLURM), *args], capture_output=True, text=True,
                          env=env, timeout=60)


def test_slurm_stop_refuses_a_state_directory_it_did_not_start(tmp_path):
    """`stop` with another MECHREPRO_SLURM_DIR than `start` had: it deleted slurm.conf and
    left the daemons running.  Now it refuses, names the directory that started them, and
    touches nothing; with that directory it stops them and removes its slurm.conf."""
    started, other, conf = tmp_path / "started", tmp_path / "other", tmp_path / "slurm.conf"
    started.mkdir()
    other.mkdir()
    conf.write_text(f"{MARK}\nStateSaveLocation={started}/state\n")
    daemon = subprocess.Popen(["sleep", "300"])      # stands in for slurmd (not ours to kill)
    try:
        (started / "slurmd.pid").write_text(f"{daemon.pid}\n")
        out = _slurm(other, conf, "stop")
        assert out.returncode != 0, out.stderr
        assert str(started) in out.stderr and "refus" in out.stderr, out.stderr
        assert conf.exists() and daemon.poll() is None and (started / "slurmd.pid").exists()
        # the one that started it: the pid is not a slurmd (a reused pid), so it is left
        # alone, and the conf is removed
        out = _slurm(started, conf, "stop")
        assert out.returncode == 0, out.stderr
        assert not conf.exists() and daemon.poll() is None, out.stderr
        assert "not slurmd" in out.stderr and not (started / "slurmd.pid").exists()
        # nothing started there (any more): refused, nothing touched
        conf.write_text("# somebody else's\n")
        out = _slurm(started, conf, "stop")
        assert out.returncode != 0 and conf.read_text() == "# somebody else's\n", out.stderr
    finally:
        daemon.kill()
        daemon.wait()
