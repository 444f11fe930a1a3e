"""Every rerun explained: the jobs of the last run (job, wildcards, reason) as a page.

`make reproduce` (:mod:`mechrepro.reproduce`) calls :func:`main` after Snakemake: it reads the
run's own log (the newest ``.snakemake/log/*.snakemake.log``, where Snakemake writes each
job's reason as it starts it; so the workflow is parsed once, not a second time for a dry
run) and writes ``<results>/rerun_plan.txt`` (the log) and ``<results>/rerun_plan.html``
(one row per job with its reason: params changed, code changed, input changed, missing
output ...).  The plan is not an input of any rule, so saving it never triggers a rerun by
itself.

A run that failed leaves a failure mark, ``<results>/last_run_failed.js`` (:func:`mark_failed`):
what failed, when, and when that run started.  Every report page of the results directory
loads it and says on its first screen that the last run failed, and whether that run wrote
the page or left an earlier one.  The next run that completes removes it.  The mark is no
declared output and no page names it in a ``src``/``href`` attribute, so no archive holds it:
a failure never outlives the fix, nor is it certified with the results.
"""
from __future__ import annotations

import html
import re
import sys
from collections import Counter
from pathlib import Path

KINDS = (("Params have changed", "params changed"), ("Code has changed", "code changed"),
         ("Updated input files", "input changed"), ("Missing output files", "missing output"),
         ("Input files updated by another job", "upstream job reruns"),
         ("Set of input files has changed", "input set changed"),
         ("stale: ", "stale"), ("Forced execution", "forced"),
         ("Rules with a run or shell", "always"))


def parse(dry_run: str) -> list[dict]:
    """Jobs of a ``snakemake -n`` output: rule, wildcards, reason (full and classified)."""
    jobs, job = [], None
    for line in dry_run.splitlines():
        m = re.match(r"^(?:local)?rule (\w+):", line)
        if m:
            job = {"rule": m.group(1), "wildcards": "", "reason": ""}
            jobs.append(job)
            continue
        if job is None:
            continue
        s = line.strip()
        if s.startswith("wildcards:"):
            job["wildcards"] = s.split(":", 1)[1].strip()
        elif s.startswith("reason:"):
            job["reason"] = s.split(":", 1)[1].strip()
    # the workflow's own reason for a job it forced (mechrepro.staleness): what changed
    stale = dict(re.findall(r"^\[stale\] (\w+): (.*)$", dry_run, re.M))
    for job in jobs:
        if "Forced execution" in job["reason"] and job["rule"] in stale:
            job["reason"] = job["reason"].replace("Forced execution",
                                                  f"stale: {stale[job['rule']]}")
        job["kind"] = "; ".join(k for key, k in KINDS if key in job["reason"]) or "other"
    return jobs


def cap_reason(line: str, names: int = 3) -> str:
    """A ``reason:`` line of Snakemake's console output with each of its file lists cut to
    the count and the first ``names`` ("Input files updated by another job: 226 (a.nc,
    b.nc, c.nc, ...)"): a validation job's reason named every run, 45,140 characters on
    one line.  The whole reasons stay in Snakemake's log and ``rerun_plan.txt``."""
    m = re.match(r"(\s*reason: )(.*?)(\s*)$", line, re.S)
    if m is None:
        return line
    clauses = []
    for clause in m.group(2).split("; "):
        label, sep, items = clause.partition(": ")
        files = items.split(", ")
        if sep and len(files) > names:
            clause = f"{label}: {len(files)} ({', '.join(files[:names])}, …)"
        clauses.append(clause)
    return m.group(1) + "; ".join(clauses) + m.group(3)


def to_html(jobs: list[dict], status: int = 0) -> str:
    counts = Counter(j["rule"] for j in jobs)
    rows = "".join(
        f"<tr><td>{html.escape(j['rule'])}</td><td>{html.escape(j['wildcards'])}</td>"
        f"<td>{html.escape(j['kind'])}</td><td class='r'>{html.escape(j['reason'][:400])}</td></tr>"
        for j in jobs if j["rule"] != "all")
    summary = ", ".join(f"{r}: {n}" for r, n in sorted(counts.items()) if r != "all")
    failed = (f"<p><b>The run failed (exit status {status})</b>: these jobs were planned; "
              "the failed ones and their logs are named in the console output.</p>"
              if status else "")
    return (HEAD + failed
            + f"<p><b>{len(jobs) - counts.get('all', 0)} jobs</b> {html.escape(summary)}</p>"
            + ("<table><tr><th>rule</th><th>wildcards</th><th>why</th><th>snakemake's reason</th></tr>"
               f"{rows}</table>" if rows else "<p>Nothing to be done: every result is up to date.</p>"))


HEAD = ("<!doctype html><meta charset='utf-8'><style>body{font:12px system-ui}"
        "td,th{border:1px solid #ccc;padding:2px 5px;vertical-align:top}"
        "table{border-collapse:collapse}.r{color:#555;font-size:11px}</style>")


def no_run_html(status: int) -> str:
    """The run stopped before Snakemake wrote a log (no job was planned)."""
    return (HEAD + f"<p><b>The last run stopped before any job was planned</b> (exit status "
            f"{status}): a refused config, another run in progress, or a locked directory; "
            "its console output says which. The results are those of the run before.</p>")


def latest_log(workdir: str | Path = ".") -> Path | None:
    logs = sorted(Path(workdir, ".snakemake", "log").glob("*.snakemake.log"))
    return logs[-1] if logs else None


def main(argv: list[str]) -> int:
    """``python -m mechrepro.plan RESULTS [SNAKEMAKE_LOG] [--since EPOCH] [--status N]``:
    with ``--since`` (the make's start), a log older than that is not this run's."""
    import argparse

    ap = argparse.ArgumentParser(prog="python -m mechrepro.plan", description=main.__doc__)
    ap.add_argument("results")
    ap.add_argument("log", nargs="?", help="default: the newest .snakemake/log/*.snakemake.log")
    ap.add_argument("--since", type=float, help="start time of the run (seconds since epoch)")
    ap.add_argument("--status", type=int, default=0, help="the run's exit status")
    args = ap.parse_args(argv)
    try:
        return save(args)
    except OSError as exc:
        # a read-only results directory: a failed run has said so itself (mechrepro.heal)
        if not args.status:
            sys.stderr.write(f"rerun plan: not saved ({exc.strerror}: {exc.filename})\n")
        return args.status or 1


def mark_failed(results: str | Path, status: int, why: str, since: float | None) -> None:
    """Leave the failure mark of the run that started at ``since`` (epoch seconds), or
    remove it when the run completed (``status`` 0).  The mark is a script calling the
    report's ``mechreproLastRun``: the page compares its own writing time with ``since``."""
    import datetime as dt
    import json

    from .io import write_text
    from .report import MARK

    path = Path(results) / MARK
    if not status:
        path.unlink(missing_ok=True)
        return
    when = dt.datetime.now().astimezone().isoformat(timespec="seconds")
    write_text(path, "mechreproLastRun(" + json.dumps(
        {"status": status, "why": why, "start": since, "when": when}) + ");\n", record=False)


def save(args) -> int:
    from .io import write_text

    results = Path(args.results)
    log = Path(args.log) if args.log else latest_log()
    if args.since is not None and (log is None or not log.exists()
                                   or log.stat().st_mtime < args.since - 1):
        write_text(results / "rerun_plan.html", no_run_html(args.status))
        mark_failed(results, args.status, f"exit status {args.status} before any job: see "
                    "the console", args.since)
        print(f"rerun plan: no job was planned -> {results}/rerun_plan.html")
        return 0
    if log is None or not log.exists():
        sys.stderr.write("rerun plan: no Snakemake log found\n")
        return 1
    out = log.read_text()
    jobs = parse(out)
    write_text(results / "rerun_plan.txt", out)
    write_text(results / "rerun_plan.html", to_html(jobs, args.status))
    failed = sorted({m for m in re.findall(r"Error in rule (\w+):", out)})
    mark_failed(results, args.status, f"exit status {args.status}"
                + (f"; failed: {', '.join(failed)}" if failed else ""), args.since)
    n = sum(j["rule"] != "all" for j in jobs)
    print(f"rerun plan: {n} jobs ran -> {results}/rerun_plan.html")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
