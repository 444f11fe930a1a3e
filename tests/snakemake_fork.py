"""`python -m snakemake ...` for the tests, forked from a process that has imported it.

The suite starts Snakemake over a hundred times (every fault, reliability and pipeline test
runs it, and a dry run after), and every start imported it again: ~1.3 s of CPU, half of a
no-op run of the one-paper workflow.  Here a multiprocessing fork server imports it once
per test process; each run is a child forked from that server, which is single-threaded
(forking a pytest-xdist worker, whose I/O thread may hold a lock, is not), and does then
what `python -m snakemake` does in a fresh interpreter: its own working directory, its
output in files of its own, the test process's environment as it is now, and the
workflow's package imported from the workflow's own src/ (the server never imports it).
Where a test gives an environment of its own (a platform variant, read by numpy and
OpenBLAS when they are imported), a fresh interpreter runs it, as before.
"""
from __future__ import annotations

import multiprocessing
import os
import subprocess
import sys
import tempfile

PRELOAD = ["snakemake.cli", "snakemake.api", "snakemake.workflow", "snakemake.dag",
           "snakemake.scheduling.job_scheduler", "snakemake_executor_plugin_slurm",
           "numpy", "yaml", "jsonschema_rs"]
_context = None


def _server():
    global _context
    if _context is None:
        _context = multiprocessing.get_context("forkserver")
        _context.set_forkserver_preload(PRELOAD)
    return _context


def _child(argv, cwd, environ, out, err):
    os.chdir(cwd)
    os.environ.clear()
    os.environ.update(environ)
    for fd, path in ((1, out), (2, err)):
        f = os.open(path, os.O_WRONLY | os.O_TRUNC)
        os.dup2(f, fd)
        os.close(f)
    # what `python -m snakemake` has as sys.argv and first path entry
    sys.argv = [os.path.join(os.path.dirname(sys.modules["snakemake.cli"].__file__),
                             "__main__.py"), *argv]
    sys.path[0:0] = [cwd]
    from snakemake.cli import main

    main(argv)


def run(argv, cwd, env=None, timeout=2400) -> subprocess.CompletedProcess:
    """``subprocess.run([sys.executable, "-m", "snakemake", *argv], cwd=cwd, env=env,
    capture_output=True, text=True, timeout=timeout)``, forked where ``env`` is None."""
    cmd = [sys.executable, "-m", "snakemake", *argv]
    if env is not None or sys.platform != "linux":
        return subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True,
                              timeout=timeout)
    with tempfile.TemporaryDirectory() as tmp:
        out, err = os.path.join(tmp, "stdout"), os.path.join(tmp, "stderr")
        for path in (out, err):
            open(path, "w").close()
        proc = _server().Process(target=_child, args=(list(argv), os.path.abspath(cwd),
                                                      dict(os.environ), out, err))
        proc.start()
        proc.join(timeout)
        if proc.exitcode is None:
            proc.kill()
            proc.join()
            raise subprocess.TimeoutExpired(cmd, timeout)
        with open(out) as o, open(err) as e:
            return subprocess.CompletedProcess(cmd, proc.exitcode, o.read(), e.read())
