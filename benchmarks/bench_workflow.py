"""Whole-workflow timings, an old revision and this tree measured side by side in one run.

    python benchmarks/bench_workflow.py [--before REV] [--profiles ci default] [--cores 2] [--warm]

For each version (``REV`` checked out with ``git archive``, and the working tree without
its ``__pycache__``, like a fresh clone; then its package bytecode compiled where that
version's Makefile does it before a run) in a fresh temporary copy, per profile: the pipeline from clean (numba compiling its kernels on
the way), then a no-op run, then a dry run (the no-op *decision*), then `make reproduce`'s
no-op (``mechrepro.reproduce``, which starts nothing when no file changed), and with ``--warm`` once
more from clean results with the compiled kernels cached.  Then, per paper (from the last
run), the solver jobs' wall time (Snakemake's
benchmark files) against the solves' own time (``wall_time`` of each run), i.e. how much
is start-up and writing; the summed wall time per job kind (solve, gather, validate,
notebook, other); and Snakemake's own import time, the floor of a no-op decision.
With ``--interleave N``, each profile is then run N more times from clean in each tree
with the compiled kernels cached, the trees alternating (before, after, before, ...), and
as many no-op decisions, alternating too: a shared or throttled VM drifts in speed within
the hour (a pure-Python loop here took 1.7 s at one time and 2.5 s at another), which a
before-then-after pair would read as a difference of the trees.  The median of each
tree and the median of the per-round ratios are printed.
Timings are printed, never asserted.
"""
from __future__ import annotations

import argparse
import csv
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
ITEMS = ("Snakefile", "workflow", "config", "notebooks", "src", "results/reference")


def checkout(rev: str | None, dst: Path) -> Path:
    dst.mkdir(parents=True)
    if rev is None:
        for item in ITEMS:
            src = ROOT / item
            # without __pycache__: a fresh clone has no compiled (numba) kernels on disk either
            if src.is_dir():
                shutil.copytree(src, dst / item, ignore=shutil.ignore_patterns("__pycache__"))
            else:
                shutil.copy2(src, dst / item)
    else:
        tar = subprocess.run(["git", "archive", rev, *ITEMS], cwd=ROOT, capture_output=True,
                             check=True).stdout
        subprocess.run(["tar", "x"], cwd=dst, input=tar, check=True)
    # the package's bytecode, where that version's `make reproduce` compiles it first
    makefile = ((ROOT / "Makefile").read_text() if rev is None else subprocess.run(
        ["git", "show", f"{rev}:Makefile"], cwd=ROOT, capture_output=True, text=True).stdout)
    if "compileall" in makefile:
        subprocess.run([sys.executable, "-m", "compileall", "-q", "src"], cwd=dst, check=True,
                       stdout=subprocess.DEVNULL)
    return dst


def snakemake(work: Path, *args: str) -> float:
    t0 = time.perf_counter()
    proc = subprocess.run([sys.executable, "-m", "snakemake", *args], cwd=work,
                          capture_output=True, text=True)
    dt = time.perf_counter() - t0
    if proc.returncode != 0:
        raise SystemExit(f"{work}: snakemake {' '.join(args)} failed\n{proc.stderr[-3000:]}")
    return dt


def per_paper(results: Path) -> dict[str, tuple[float, float, int]]:
    """{paper: (solver job seconds, solve seconds, jobs)} from benchmark files and runs."""
    import netCDF4

    out = {}
    for paper_dir in sorted(p for p in results.iterdir() if (p / "runs").is_dir()):
        job = 0.0
        tsvs = sorted((paper_dir / "benchmarks").glob("solve*.tsv"))
        for tsv in tsvs:
            with open(tsv, newline="") as f:
                job += float(next(csv.DictReader(f, delimiter="\t"))["s"])
        solve = 0.0
        for nc in (paper_dir / "runs").glob("*.nc"):
            with netCDF4.Dataset(nc) as ds:
                solve += float(ds["wall_time"][...]) if "wall_time" in ds.variables else float(
                    ds.getncattr("wall_time_s"))
        out[paper_dir.name] = (job, solve, len(tsvs))
    return out


KINDS = ("solve", "gather", "validate", "notebook")


def per_kind(results: Path) -> dict[str, tuple[float, int]]:
    """{job kind: (summed wall seconds, jobs)} over every benchmark file of a results tree:
    solver jobs, gather, validation, notebooks and the cross-paper jobs (``other``)."""
    out: dict[str, tuple[float, int]] = {}
    for tsv in results.rglob("benchmarks/*.tsv"):
        kind = next((k for k in KINDS if tsv.stem.split("__")[0] == k), "other")
        with open(tsv, newline="") as f:
            s = float(next(csv.DictReader(f, delimiter="\t"))["s"])
        t, n = out.get(kind, (0.0, 0))
        out[kind] = (t + s, n + 1)
    return out


def import_seconds(module: str) -> float:
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-c", f"import {module}"], check=True)
    return time.perf_counter() - t0


def make_noop(work: Path, cores: int, cfg: list[str]) -> float:
    """`make reproduce` with nothing changed (mechrepro.reproduce: once to record the state,
    then timed); NaN in a tree without it (Snakemake and the plan ran every time)."""
    if not (work / "src" / "mechrepro" / "reproduce.py").exists():
        return float("nan")
    cmd = [sys.executable, "-m", "mechrepro.reproduce", cfg[-1].split("=", 1)[1], "--",
           "--cores", str(cores), *cfg]
    env = {**os.environ, "PYTHONPATH": str(work / "src")}
    subprocess.run(cmd, cwd=work, capture_output=True, check=True, env=env)
    t0 = time.perf_counter()
    subprocess.run(cmd, cwd=work, capture_output=True, check=True, env=env)
    return time.perf_counter() - t0


def measure(label: str, work: Path, profile: str, cores: int, warm_too: bool) -> dict:
    cfg = ["--config", f"profile={profile}", f"results=results-{profile}"]
    full = snakemake(work, "--cores", str(cores), *cfg)
    noop = snakemake(work, "--cores", str(cores), *cfg)
    dry = snakemake(work, "-n", *cfg)
    made = make_noop(work, cores, cfg)
    print(f"  {label:>8s} {profile:8s} from clean {full:7.1f} s   no-op run {noop:5.2f} s   "
          f"no-op decision (-n) {dry:5.2f} s   no-op make reproduce {made:5.2f} s", flush=True)
    warm = float("nan")
    if warm_too:
        # results deleted, compiled kernels kept: every later reproduction on this clone
        shutil.rmtree(work / f"results-{profile}")
        shutil.rmtree(work / ".snakemake", ignore_errors=True)
        warm = snakemake(work, "--cores", str(cores), *cfg)
        print(f"  {label:>8s} {profile:8s} from clean with the compiled kernels cached "
              f"{warm:7.1f} s", flush=True)
    return {"full": full, "noop": noop, "dry": dry, "warm": warm,
            "papers": per_paper(work / f"results-{profile}"),
            "kinds": per_kind(work / f"results-{profile}")}


def interleave(versions: dict[str, Path], profile: str, cores: int, rounds: int) -> None:
    """Alternate the trees, ``rounds`` times: from clean with the kernels cached, then
    (on the results just made) a no-op decision; print each, the medians and the median
    of the per-round ratios before/after."""
    import statistics

    cfg = ["--config", f"profile={profile}", f"results=results-{profile}"]
    full = {label: [] for label in versions}
    dry = {label: [] for label in versions}
    for r in range(rounds):
        for label, work in versions.items():
            shutil.rmtree(work / f"results-{profile}", ignore_errors=True)
            shutil.rmtree(work / ".snakemake", ignore_errors=True)
            full[label].append(snakemake(work, "--cores", str(cores), *cfg))
            dry[label].append(snakemake(work, "-n", *cfg))
            print(f"  round {r + 1} {label.split()[0]:>8s} {profile:8s} from clean (kernels cached) "
                  f"{full[label][-1]:7.1f} s   no-op decision {dry[label][-1]:5.2f} s", flush=True)
    b, f = versions
    for name, t in (("from clean (kernels cached)", full), ("no-op decision", dry)):
        ratios = [x / y for x, y in zip(t[b], t[f])]
        print(f"  interleaved {profile} {name}: before median {statistics.median(t[b]):.2f} s, "
              f"after median {statistics.median(t[f]):.2f} s, median ratio before/after "
              f"{statistics.median(ratios):.2f}x over {rounds} rounds", flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--before", default="39b0397", help="revision to compare with")
    ap.add_argument("--profiles", nargs="+", default=["ci"])
    ap.add_argument("--cores", type=int, default=2)
    ap.add_argument("--warm", action="store_true",
                    help="also rerun the tree from clean results with its compiled kernels cached")
    ap.add_argument("--interleave", type=int, default=0, metavar="N",
                    help="then N alternating rounds per tree: from clean (kernels cached), no-op decision")
    a = ap.parse_args()
    tmp = Path(tempfile.mkdtemp(prefix="bench-workflow-"))
    versions = {f"before ({a.before})": checkout(a.before, tmp / "before"),
                "after (tree)": checkout(None, tmp / "after")}
    res = {}
    for profile in a.profiles:
        print(f"profile {profile}:", flush=True)
        for label, work in versions.items():
            res[(label, profile)] = measure(label.split()[0], work, profile, a.cores,
                                            a.warm and label.startswith("after"))
        b, f = (res[(lab, profile)] for lab in versions)
        print(f"  ratio before/after: from clean {b['full'] / f['full']:.2f}x, no-op decision "
              f"{b['dry'] / f['dry']:.2f}x")
        print(f"  {'paper':14s} {'jobs b/a':>9s} {'job s before':>13s} {'solve s before':>15s} "
              f"{'job s after':>12s} {'solve s after':>14s}")
        for paper in f["papers"]:
            jb, sb, nb = b["papers"].get(paper, (float("nan"),) * 2 + (0,))
            ja, sa, na = f["papers"][paper]
            print(f"  {paper:14s} {nb:4d}/{na:<4d} {jb:13.1f} {sb:15.1f} {ja:12.1f} {sa:14.1f}")
        print(f"  {'job kind':14s} {'jobs b/a':>9s} {'job s before':>13s} {'job s after':>12s}"
              "   (wall seconds summed over jobs; older trees have no benchmark for some kinds)")
        for kind in (*KINDS, "other"):
            tb, nb = b["kinds"].get(kind, (float("nan"), 0))
            ta, na = f["kinds"].get(kind, (float("nan"), 0))
            print(f"  {kind:14s} {nb:4d}/{na:<4d} {tb:13.1f} {ta:12.1f}")
        if a.interleave:
            interleave(versions, profile, a.cores, a.interleave)
    # the floor of any no-op decision: Snakemake's own import, measured beside it
    print(f"import snakemake.cli alone: {min(import_seconds('snakemake.cli') for _ in range(3)):.2f} s",
          flush=True)
    shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
