"""`make reproduce`: Snakemake, then the rerun plan; nothing at all when nothing changed.

A run with nothing to do still costs Snakemake seconds: its import, the DAG of ~800
files, and the heal's sha256 of every result.  After a run that succeeded, the state of
every file Snakemake reads is recorded (the workflow, configs, notebooks, sources, the
results directory and Snakemake's own metadata): size, modification and change time,
inode.  The next `make reproduce` with the same command compares that record and, when
no file differs, says so and stops, before any of it.

The change time (ctime) is what makes this safe: no program can set it back, so a result
rewritten with its time stamp kept (``cp -p`` over it, ``touch -r``, garbage pasted and
``os.utime``) differs from the record, and the run goes through Snakemake and the heal,
which finds it by content.  Only a change below the file system (a bit rotting on disk)
is not seen here: ``python -m snakemake --cores 2 --rerun-incomplete`` always heals by
content.

    python -m mechrepro.reproduce RESULTS -- SNAKEMAKE_ARGS ...
"""
from __future__ import annotations

import contextlib
import hashlib
import io
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

# What Snakemake reads to decide its jobs (besides the results directory); under
# .snakemake/, its logs and mechrepro's own lock, config cache and this record change
# without changing any decision.
READ = ("Snakefile", "workflow", "config", "notebooks", "src", "profiles", ".snakemake")
SKIP = {"__pycache__", ".ipynb_checkpoints", str(Path(".snakemake", "log")),
        str(Path(".snakemake", "mechrepro"))}


def _files(root: Path, rel: str):
    path = root / rel
    try:
        st = path.lstat()
    except FileNotFoundError:
        return
    if not path.is_dir():
        yield rel, st
        return
    with os.scandir(path) as it:
        for entry in sorted(it, key=lambda e: e.name):
            sub = os.path.join(rel, entry.name)
            if entry.name in SKIP or sub in SKIP:
                continue
            if entry.is_dir(follow_symlinks=False):
                yield from _files(root, sub)
            else:
                yield sub, entry.stat(follow_symlinks=False)


def state(results: str | Path, root: str | Path = ".") -> str:
    """A digest of (path, size, mtime, ctime, inode) of every file a run reads or writes."""
    root = Path(root)
    h = hashlib.sha256()
    for top in (*READ, os.path.normpath(results)):
        for rel, st in _files(root, top):
            h.update(f"{rel}\0{st.st_size}\0{st.st_mtime_ns}\0{st.st_ctime_ns}\0"
                     f"{st.st_ino}\n".encode())
    return h.hexdigest()


def record_path(results: str | Path, root: str | Path = ".") -> Path:
    key = hashlib.sha256(str(Path(root, results).resolve()).encode()).hexdigest()[:16]
    return Path(root, ".snakemake", "mechrepro", f"uptodate-{Path(results).name}-{key}.json")


def command_key(args: list[str], root: str | Path = ".") -> str:
    """The command and where it runs: another interpreter, project path or argument is
    another run."""
    return json.dumps([sys.executable, str(Path(root).resolve()), *args])


def unchanged(results: str | Path, args: list[str], root: str | Path = ".") -> str | None:
    """When the last successful run of this command left every file as it is now: its
    time (else None)."""
    try:
        rec = json.loads(record_path(results, root).read_text())
    except (OSError, ValueError):
        return None
    if not isinstance(rec, dict) or rec.get("command") != command_key(args, root):
        return None
    return rec.get("when") if rec.get("state") == state(results, root) else None


def remember(results: str | Path, args: list[str], root: str | Path = ".") -> None:
    from .io import write_json

    write_json(record_path(results, root), {
        "command": command_key(args, root), "state": state(results, root),
        "when": time.strftime("%Y-%m-%d %H:%M:%S", time.localtime())})


def snakemake(args: list[str]) -> int:
    """Snakemake's exit status.  Ctrl-C reaches Snakemake itself (same process group),
    which marks its jobs incomplete and releases its locks; this process waits for that
    instead of being interrupted first.  Its console output (stderr) passes through line by
    line with each ``reason:`` cut to counts and a few names (:func:`mechrepro.plan.cap_reason`)."""
    with subprocess.Popen([sys.executable, "-m", "snakemake", *args], stderr=subprocess.PIPE,
                          text=True, errors="replace", bufsize=1) as proc:
        old = {s: signal.signal(s, signal.SIG_IGN) for s in (signal.SIGINT, signal.SIGTERM)}
        try:
            from .plan import cap_reason   # while Snakemake starts

            for line in proc.stderr:
                sys.stderr.write(cap_reason(line))
                sys.stderr.flush()
            return proc.wait()
        finally:
            for s, h in old.items():
                signal.signal(s, h)


def main(argv: list[str]) -> int:
    if len(argv) < 2 or argv[1] != "--":
        sys.stderr.write(__doc__.rsplit("\n\n", 1)[-1])
        return 2
    results, args = argv[0], argv[2:]
    when = unchanged(results, args)
    if when:
        print(f"Nothing to be done: no file of the workflow, its configs, sources or "
              f"{results}/ changed since the last successful run ({when}). "
              f"`{Path(sys.executable).name} -m snakemake {' '.join(args)}` checks every "
              f"result by content.")
        return 0
    start = time.time()
    status = snakemake(args)
    from . import plan

    with contextlib.redirect_stdout(io.StringIO()):   # the plan names itself in the report
        plan.main([results, "--since", str(start), "--status", str(status)])
    if status == 0:
        remember(results, args)
    return status


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
