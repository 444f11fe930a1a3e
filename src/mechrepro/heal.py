"""Before a run: find by content what Snakemake cannot see, rebuild it, and never touch work.

Snakemake decides by file existence and modification time.  It cannot see

- a temporary ``.*.part*`` file left by a killed job (harmless, but it stays forever);
- a result whose bytes are no longer what its job wrote (a truncated ``.nc``, garbage
  pasted into a table, a bit flip, a ``cp -p`` over it): its time stamp looks fine;
- a project copied without its time stamps (``cp -r``, an unpacked zip): every result
  looks newer or older than its inputs in an arbitrary order.

Every result is written by :func:`mechrepro.io.atomic_path`, which records beside it
(``.<name>.sum``) the sha256, size and time stamp it wrote.  Heal compares each result
with that record: the same content with another time stamp gets its recorded time stamp
back (a copy schedules nothing); other content is removed, named, and rebuilt by the run.
A result without a readable record (restored from an archive, written by an older version,
or its record garbled) is checked against the sha256 of every archive manifest that lists
it (the full run's and each one-paper run's) and, when it matches, gets the record of what
made it from that manifest; a netCDF file is also opened.  Time stamps alone never remove
anything.  Whether a result is current is then decided by what made it
(:mod:`mechrepro.staleness`, :func:`steer_workflow`), never by time stamps.

Heal runs inside the workflow (``workflow/rules/common.smk``) before Snakemake builds its
jobs, so ``make reproduce`` and a plain ``snakemake`` are healed alike, and only while this
process holds the run lock of its results directory (an ``fcntl`` lock the kernel drops
when the process ends, even on ``kill -9``): a second run started while one is writing is
refused before it can remove anything.  ``python -m mechrepro.heal RESULTS`` heals by hand
under the same lock (``--dry-run`` lists what it would do).
"""
from __future__ import annotations

import fcntl
import hashlib
import json
import os
import sys
from pathlib import Path

from .io import SUM_SUFFIX, read_sum, sum_path, write_text
from .provenance import file_sha256
from .staleness import ARCHIVE_FILES, _manifests, archive_record, steer, write_table

LOCK_DIR = Path(".snakemake") / "mechrepro"
SKIP_DIRS = {"reference", "logs", "benchmarks"}
# Snakemake invocations that parse the workflow but run no job: never heal there.
NOT_A_RUN = {"-n", "--dry-run", "--dryrun", "--unlock", "--lint", "-t", "--touch", "-l",
             "--list", "--list-rules", "--list-target-rules", "-S", "--summary", "-D",
             "--detailed-summary", "--cleanup-metadata", "--cm", "--lc", "--li", "--lp",
             "--lt", "--lu", "--list-changes", "--list-untracked", "--dag", "--rulegraph",
             "--filegraph", "--d3dag", "--containerize", "--archive", "--cleanup-shadow",
             "--delete-all-output", "--delete-temp-output", "--report", "--export-cwl",
             "--print-compilation", "--help", "-h", "--version", "-v"}


class RunInProgress(RuntimeError):
    pass


_held: dict[str, int] = {}   # results dir -> fd of the lock this process holds


def lock_file(results: str | Path, workdir: str | Path = ".") -> Path:
    key = hashlib.sha256(str(Path(workdir, results).resolve()).encode()).hexdigest()[:16]
    return Path(workdir) / LOCK_DIR / f"run-{Path(results).name}-{key}.lock"


def acquire(results: str | Path, workdir: str | Path = ".") -> None:
    """Take the run lock of ``results`` for the rest of this process (idempotent).

    Raises :class:`RunInProgress` naming the holder's pid when another process has it."""
    path = lock_file(results, workdir)
    if str(path) in _held:
        return
    path.parent.mkdir(parents=True, exist_ok=True)
    fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o666)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        holder = os.pread(fd, 64, 0).decode(errors="replace").strip() or "?"
        os.close(fd)
        raise RunInProgress(
            f"another run is writing {results} (process {holder}, lock {path}); wait for it "
            f"to end (nothing was changed). Dry runs (-n) work meanwhile.") from None
    os.ftruncate(fd, 0)
    os.pwrite(fd, f"{os.getpid()}\n".encode(), 0)
    _held[str(path)] = fd


def release(results: str | Path, workdir: str | Path = ".") -> None:
    fd = _held.pop(str(lock_file(results, workdir)), None)
    if fd is not None:
        os.close(fd)   # closing drops the flock


def snakemake_locked(results: str | Path, workdir: str | Path = ".") -> Path | None:
    """A Snakemake lock file that names a file under ``results`` (a run in progress, or the
    lock a killed master left: its orphaned jobs may still be writing), or None."""
    prefix = os.path.normpath(str(results)) + os.sep
    for lock in sorted(Path(workdir, ".snakemake", "locks").glob("*.lock")):
        try:
            lines = lock.read_text().splitlines()
        except OSError:
            continue
        if any(os.path.normpath(line.strip()).startswith(prefix) for line in lines):
            return lock
    return None


def _results_files(results: Path):
    for sub in sorted(results.iterdir()):
        if sub.name in SKIP_DIRS:
            continue
        if sub.is_file():
            yield sub
            continue
        for root, dirs, files in os.walk(sub):
            dirs[:] = sorted(d for d in dirs if d not in SKIP_DIRS)
            for name in sorted(files):
                yield Path(root, name)




def _readable_netcdf(path: Path) -> bool:
    import netCDF4

    try:
        netCDF4.Dataset(path).close()
        return True
    except OSError:
        return False


def inspect(results: str | Path, workdir: str | Path = "."):
    """What heal would do: ([(file to remove, why)], [file whose time stamp to restore],
    [record whose file is gone], [file restored to its previous version], [(file without
    a record, the record its manifest gives it)])."""
    results = Path(results)
    remove, restore, orphans, reverted, adopt = [], [], [], [], []
    if not results.is_dir():
        return remove, restore, orphans, reverted, adopt
    manifest = None
    for f in _results_files(results):
        name = f.name
        if name.startswith("."):
            if ".part" in name:
                remove.append((f, "temporary file of an interrupted job"))
            elif name.endswith(SUM_SUFFIX) and not (f.parent / name[1:-len(SUM_SUFFIX)]).exists():
                orphans.append(f)   # Snakemake removed the file before rerunning its job
            continue
        rec = read_sum(f)
        st = f.stat()
        if rec is not None:
            if st.st_size != rec["size"] or file_sha256(f) != rec["sha256"]:
                prev = rec.get("previous")
                if prev and st.st_size == prev["size"] and file_sha256(f) == prev["sha256"]:
                    # the last good version, put back by Snakemake after its job failed
                    reverted.append(f)
                else:
                    remove.append((f, "content differs from what its job wrote (checksum)"))
            elif st.st_mtime_ns != rec["mtime_ns"]:
                restore.append(f)
            continue
        # no record: a result of an older version of the writer
        if manifest is None:
            manifest = _manifests(results)
        rel = str(f.relative_to(results))
        if f.parent.name.startswith("archive") and f.name in ARCHIVE_FILES:
            made_by = archive_record(f)
            if made_by is not None:
                adopt.append((f, {"sha256": file_sha256(f), "size": st.st_size,
                                  "mtime_ns": st.st_mtime_ns, "made_by": made_by}))
            continue
        sha = file_sha256(f) if rel in manifest else None
        if rel in manifest and sha not in manifest[rel]:
            remove.append((f, "checksum differs from the last manifest"))
        elif name.endswith(".nc") and not _readable_netcdf(f):
            remove.append((f, "unreadable netCDF (truncated or corrupted)"))
        elif sha is not None:
            # a restored archive: the record of what made it comes from the manifest (an
            # archive without one leaves the file unrecorded: its job reruns)
            rec = {"sha256": sha, "size": st.st_size, "mtime_ns": st.st_mtime_ns}
            if manifest[rel][sha] is not None:
                rec["made_by"] = manifest[rel][sha]
            adopt.append((f, rec))
    return remove, restore, orphans, reverted, adopt


def heal(results: str | Path, workdir: str | Path = ".", dry_run: bool = False) -> list[str]:
    """Remove what is not what its job wrote, restore the time stamps of what is.

    Takes the run lock of ``results`` first (kept by this process: a workflow that heals
    keeps it until it ends); raises :class:`RunInProgress` if another process has it."""
    results = Path(results)
    if not dry_run:
        acquire(results, workdir)
        lock = snakemake_locked(results, workdir)
        if lock is not None:
            return [f"not healed: Snakemake's lock {lock} names files of {results} (a run "
                    f"killed with its jobs still writing?); when no job is left, "
                    f"`snakemake --unlock` and run again"]
    remove, restore, orphans, reverted, adopt = inspect(results, workdir)
    verb = "would remove" if dry_run else "removed"
    lines = []
    for f, why in remove:
        if not dry_run:
            f.unlink(missing_ok=True)
            sum_path(f).unlink(missing_ok=True)
        lines.append(f"{verb} {f}: {why}")
    for f in orphans:
        if not dry_run:
            f.unlink(missing_ok=True)
    for f in reverted:
        if not dry_run:
            # the record (what made it) and the time stamp follow the file back to its
            # writing: the run then compares that record with today's (staleness), so the
            # failed job runs again while what made the file is not what would make it now
            rec = read_sum(f)["previous"]
            sum_path(f).write_text(json.dumps(rec, sort_keys=True) + "\n")
            os.utime(f, ns=(rec["mtime_ns"], rec["mtime_ns"]))
        lines.append(f"{'would keep' if dry_run else 'kept'} {f}: the last good version, "
                     f"restored after its job failed")
    for f in restore:
        if not dry_run:
            rec = read_sum(f)
            os.utime(f, ns=(rec["mtime_ns"], rec["mtime_ns"]))
    for f, rec in adopt:
        if not dry_run:
            write_text(sum_path(f), json.dumps(rec, sort_keys=True) + "\n", record=False)
    if adopt:
        lines.append(f"{'would record' if dry_run else 'recorded'} what made {len(adopt)} "
                     f"results from their archive's manifest (e.g. {adopt[0][0]})")
    if restore and dry_run:
        # not said in a run: Snakemake touches every output after its job, so this is
        # every result after every run; after a copy (cp -r) it is what schedules nothing
        lines.append(f"would restore the time stamps of {len(restore)} results whose "
                     f"content is what their jobs wrote (e.g. {restore[0]})")
    return lines


def read_only(results: str | Path, workdir: str | Path = ".", run: bool = True) -> str | None:
    """The first directory a Snakemake invocation needs to write but cannot, as one line
    saying what to do, or None.  Snakemake writes its locks under ``.snakemake/`` in every
    invocation (a dry run too); a run writes every directory under ``results`` (heal, job
    outputs by atomic rename, the report).  Asked of the kernel (``os.access``): a
    read-only mount refuses even root, ``chmod a-w`` refuses everyone else."""
    meta = Path(workdir, ".snakemake")
    dirs = [meta if meta.is_dir() else Path(workdir)]
    results = Path(workdir, results)
    if run and results.is_dir():
        dirs.append(results)
        dirs += [Path(root, d) for root, subs, _ in os.walk(results) for d in sorted(subs)
                 if d not in SKIP_DIRS]
    elif run:   # created by the run: where it will be created
        dirs.append(next(p for p in results.parents if p.is_dir()))
    for d in dirs:
        if not os.access(d, os.W_OK):
            what = "its locks (.snakemake/)" if d in (meta, Path(workdir)) \
                and not (run and d == dirs[-1] and not results.is_dir()) \
                else f"its results ({os.path.relpath(results, workdir)}/)"
            return (f"cannot run: {os.path.relpath(d, workdir)} is read-only, and Snakemake "
                    f"writes {what} there; nothing was changed. Make it writable (chmod -R "
                    f"u+w {os.path.relpath(d, workdir)}) or work in a writable copy (cp -a)")
    return None


def _not_a_run(argv: list[str] | None) -> bool:
    """Whether the Snakemake command line (default: this process's) runs no job."""
    return any(a.split("=")[0] in NOT_A_RUN for a in (sys.argv[1:] if argv is None else argv))


def refuse_read_only(workflow, results: str, argv: list[str] | None = None) -> None:
    """Called while Snakemake parses the workflow, before anything is written: a read-only
    project stops here with one line (:func:`read_only`), not a traceback from Snakemake's
    lock directory or from the first job.  A dry run needs only ``.snakemake/``."""
    if workflow.exec_mode.name != "DEFAULT":
        return
    msg = read_only(results, run=not (workflow.output_settings.dryrun or _not_a_run(argv)))
    if msg:
        sys.stderr.write(f"\n{msg}\n\n")
        raise SystemExit(1)


def heal_workflow(workflow, results: str, argv: list[str] | None = None) -> None:
    """Called while Snakemake parses the workflow: heal the results before the jobs are
    decided, in the main process of a run only (not in a dry run, an ``--unlock``, a
    cluster job, ...).  A run in progress on the same results stops this one here."""
    if workflow.exec_mode.name != "DEFAULT" or workflow.output_settings.dryrun or _not_a_run(argv):
        return
    try:
        for line in heal(results):
            sys.stderr.write(f"[heal] {line}\n")
    except RunInProgress as exc:
        sys.stderr.write(f"\n{exc}\n\n")
        raise SystemExit(1)
    except OSError as exc:
        # read-only results or .snakemake: nothing can be healed, nor written by any job;
        # a no-op run must still say "Nothing to be done", not end in a traceback
        sys.stderr.write(f"[heal] not healed ({exc.strerror}: {exc.filename or results})\n")


def steer_workflow(workflow, jobs, results: str, table: str,
                   argv: list[str] | None = None) -> None:
    """Called while Snakemake parses the workflow, after every rule: when Snakemake builds
    its DAG, let it run exactly the jobs whose results are not what today's records, code,
    packages and inputs would make, and what depends on them
    (:func:`mechrepro.staleness.steer`), in a run or a dry run of the main process; a run
    also writes the job table the archive checks.

    Snakemake hands the workflow its DAG settings only after parsing, and decides which
    jobs need to run after it made the DAG: this wraps the step between the two
    (``Workflow._prepare_dag``, Snakemake 9; tests/test_staleness.py pins it) to force the
    stale jobs first and to restrict the DAG's jobs that may run to those rules after
    (every rule stays in the DAG, so a target made by another is still found)."""

    dry = workflow.output_settings.dryrun
    if workflow.exec_mode.name != "DEFAULT" or (not dry and _not_a_run(argv)):
        return
    prepare = workflow._prepare_dag

    def _prepare_dag(*args, **kwargs):
        from snakemake.logging import logger

        # through Snakemake's logger: on the console and in the run's log, which the rerun
        # plan reads (mechrepro.plan)
        allowed = steer(workflow, jobs, results, say=logger.info)
        if not dry:
            write_table(jobs, results, table)
        out = prepare(*args, **kwargs)
        if allowed is not None:
            workflow._dag.rules_allowed_for_needrun = allowed
        return out

    workflow._prepare_dag = _prepare_dag


def main(argv: list[str]) -> int:
    import argparse

    ap = argparse.ArgumentParser(
        prog="python -m mechrepro.heal",
        description="Remove results that are not what their job wrote (checked by content "
                    "against the checksum recorded beside each result, or the last manifest), "
                    "restore the time stamps of those that are; refused while a run writes "
                    "the same results. The workflow does this itself before every run.")
    ap.add_argument("results", help="results directory, e.g. results or results-ci")
    ap.add_argument("--dry-run", "-n", action="store_true", help="only say what would be done")
    args = ap.parse_args(argv)
    try:
        lines = heal(args.results, dry_run=args.dry_run)
    except RunInProgress as exc:
        sys.stderr.write(f"{exc}\n")
        return 1
    except OSError as exc:
        sys.stderr.write(f"heal: {exc.strerror}: {exc.filename}\n")
        return 1
    for line in lines:
        print(f"[heal] {line}", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
