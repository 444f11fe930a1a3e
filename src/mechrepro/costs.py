"""What a paper's runs cost: per effect, per solver core, and per job against its solves.

``effect_cost`` sums the time split and the evaluation counts every run stores
(:mod:`mechrepro.timing`) into one row per (solver, effect or named phase) -- the report's
effect-cost table; ``job_time`` sets each solver
job's wall time (Snakemake's benchmark file) against the solve time of its runs, so the
overhead of starting a job shows, and against the declared cost model's estimate.  Both tables are written by ``validate_<paper>``.
"""
from __future__ import annotations

import csv
import functools
import json
from pathlib import Path

import numpy as np

EFFECT_COST_COLUMNS = ["solver", "effect", "runs", "calls", "time_s", "share"]
JOB_TIME_COLUMNS = ["job", "runs", "solve_s", "job_s", "estimate_s"]
MARGINAL_COLUMNS = ["scene", "solver", "effect", "direct_s", "marginal_s", "marginal_median_s",
                    "marginal_min_s", "marginal_max_s", "below_noise", "with_s", "without_s"]
VERIFICATION_COLUMNS = ["variant", "kind", "runs", "solve_s", "share", "rows", "decides",
                        "decided_rows"]


def run_times(path: str | Path) -> dict:
    """wall/core/effect times of one run file, read without loading its other variables."""
    return _run_times(str(path))


@functools.lru_cache(maxsize=None)
def _run_times(path: str) -> dict:
    # both cost tables read every run: open each file once per process
    import netCDF4

    with netCDF4.Dataset(path) as nc:
        out = {"solver": getattr(nc, "solver", "") or "(undeclared)",
               "wall": float(nc["wall_time"][...]),
               "core": float(nc["core_time"][...]) if "core_time" in nc.variables else np.nan,
               "effects": {}, "calls": {}, "phases": {},
               "outputs": set(json.loads(getattr(nc, "outputs", "[]"))),
               "rounds": (np.asarray(nc["timing_rounds"][...], float)
                          if "timing_rounds" in nc.variables else np.array([]))}
        if "effect_time" in nc.variables:
            names = [str(x) for x in nc["timed_effect"][...]]
            out["effects"] = dict(zip(names, np.asarray(nc["effect_time"][...], float)))
            if "effect_calls" in nc.variables:
                out["calls"] = dict(zip(names, np.asarray(nc["effect_calls"][...], int)))
        if "phase_time" in nc.variables:
            out["phases"] = {str(k): (float(t), int(c)) for k, t, c in zip(
                nc["timed_phase"][...], nc["phase_time"][...], nc["phase_calls"][...])}
    return out


def effect_cost(run_files) -> list[dict]:
    """One row per (solver, effect) and per (solver, ``(output) <name>``), a ``(solver
    core)`` row per solver and a ``(phase) <name>`` row per phase a model names (inside the
    core, an effect or an output, so phases are not added to the rest): the summed time over
    the runs that used it, how often it was evaluated, and its share of those runs' wall
    time."""
    acc: dict[tuple[str, str], list[tuple]] = {}
    for f in run_files:
        t = run_times(f)
        acc.setdefault((t["solver"], "(solver core)"), []).append((t["core"], t["wall"], 1))
        for e, sec in t["effects"].items():
            row = f"(output) {e}" if e in t["outputs"] else e
            acc.setdefault((t["solver"], row), []).append((sec, t["wall"], t["calls"].get(e, np.nan)))
        for name, (sec, calls) in t["phases"].items():
            acc.setdefault((t["solver"], f"(phase) {name}"), []).append((sec, t["wall"], calls))
    rows = []
    for (solver, effect), v in sorted(acc.items()):
        sec, wall, calls = np.array(v, float).T
        rows.append({"solver": solver, "effect": effect, "runs": len(v),
                     "calls": int(calls.sum()) if np.isfinite(calls).all() else np.nan,
                     "time_s": float(np.nansum(sec)),
                     "share": float(np.nansum(sec) / wall.sum()) if wall.sum() > 0 else np.nan})
    return rows


def benchmark_seconds(tsv: str | Path) -> float:
    """Wall seconds of one job from Snakemake's benchmark file (NaN if there is none)."""
    try:
        with open(tsv, newline="") as f:
            return float(next(csv.DictReader(f, delimiter="\t"))["s"])
    except (OSError, StopIteration, KeyError, ValueError):
        return float("nan")


def job_time(paper_root: str | Path, jobs: dict[str, list[str]],
             estimates: dict[str, float] | None = None) -> list[dict]:
    """Per solve job: its runs' own solve time, the job's wall time and what the paper's
    declared cost model expected of it (``estimates``, :func:`mechrepro.limits.job_costs`):
    every run measures the cost model it was admitted and scheduled by."""
    root = Path(paper_root)
    rows = []
    for job, runs in jobs.items():
        solve = sum(run_times(root / "runs" / f"{r}.nc")["wall"] for r in runs)
        rows.append({"job": job, "runs": len(runs), "solve_s": solve,
                     "job_s": benchmark_seconds(root / "benchmarks" / f"solve__{job}.tsv"),
                     "estimate_s": (estimates or {}).get(job, float("nan"))})
    return rows


def marginal(paper_root: str | Path, ablations: dict[str, tuple[str, str]]) -> list[dict]:
    """Per effect of an ablated scene: its direct cost (its own evaluation, timed inside the
    solve) beside its marginal cost, the scene's solve time with it minus without it, which
    also bills the work it causes in the solver (extra steps, a second solve per step); with
    the spread of that difference over the alternated rounds (median, min, max) and
    ``below_noise`` where the rounds disagree on its sign."""
    root = Path(paper_root)
    rows = []
    for run, (scene, effect) in ablations.items():
        full, without = (run_times(root / "runs" / f"{r}.nc") for r in (scene, run))
        n = min(len(full["rounds"]), len(without["rounds"]))
        d = full["rounds"][:n] - without["rounds"][:n] if n else np.array([np.nan])
        rows.append({"scene": scene, "solver": full["solver"], "effect": effect,
                     "direct_s": full["effects"].get(effect, np.nan),
                     "marginal_s": full["wall"] - without["wall"],
                     "marginal_median_s": float(np.median(d)), "marginal_min_s": float(d.min()),
                     "marginal_max_s": float(d.max()),
                     "below_noise": bool(n) and bool(d.min() <= 0.0 <= d.max()),
                     "with_s": full["wall"], "without_s": without["wall"]})
    return rows


def verification(paper_root: str | Path, cfg, rows) -> list[dict]:
    """What each verification variant costs and what it decides: its runs' solve time (and
    share of the paper's), the verdict rows it re-checks, and those whose verdict its outcome
    decides -- a level, seed, range end or family member that flips the baseline's verdict
    or sets the row's error bar, a rival that fails a counted row.  The baseline's own runs
    (what the figures draw) are the first line."""
    root = Path(paper_root)
    solve = {r: run_times(root / "runs" / f"{r}.nc")["wall"] for r in cfg.runs
             if (root / "runs" / f"{r}.nc").exists()}
    total = sum(solve.values()) or np.nan
    by_variant: dict[str, list[str]] = {}
    for r, rec in cfg.runs.items():
        by_variant.setdefault(rec.get("variant") or "", []).append(r)
    out = []
    for v, runs in sorted(by_variant.items(), key=lambda kv: (kv[0] != "", kv[0])):
        kind = "baseline" if not v else cfg.variant_info.get(v, {}).get("kind", "ablation")
        served = [r for r in rows if any(c[0] == v for c in r.checks)] if v else []
        decided = [r.quantity for r in served if _decides(r, v)]
        t = sum(solve.get(r, 0.0) for r in runs)
        out.append({"variant": v or "(baseline)", "kind": kind, "runs": len(runs), "solve_s": t,
                    "share": t / total, "rows": len(served), "decides": len(decided),
                    "decided_rows": " ".join(decided)})
    return out


def _decides(row, variant: str) -> bool:
    """Whether the check ``variant`` of a row decides its verdict (see :func:`verification`)."""
    if variant.startswith("rival-"):
        return row.rivals.get(variant[len("rival-"):], ("", 0, ""))[2].startswith("fails")
    c = next(c for c in row.checks if c[0] == variant)
    if c[1] == "level" and row.kind in ("compare", "bound"):
        return True   # the error bar is made of the levels: without them no verdict
    return c[3] not in ("excluded", row.verdict)


# --- the cost table (mechrepro.limits.COSTS) --------------------------------------------

#: the share of a solver's runs its fitted estimate stays above (:func:`fit`)
QUANTILE = 0.9
TABLE_COLUMNS = ["paper", "solver", "term", "coefficient", "runs", "quantile", "machine"]


def fit(work: list[dict[str, float]], seconds) -> dict[str, float]:
    """Seconds per unit of each work term: a least-squares fit of the relative error
    (each run weighs alike, whether it takes milliseconds or minutes) with no negative
    coefficient, then scaled up to the :data:`QUANTILE` of measured / estimated, so the
    estimate stays above that share of the runs (conservative: admission and cluster
    requests must not run short)."""
    from scipy.optimize import nnls

    terms = sorted({k for w in work for k in w})
    t = np.maximum(np.asarray(seconds, float), 1e-6)
    a = np.array([[w.get(k, 0.0) for k in terms] for w in work], float)
    scale = np.maximum(a.max(axis=0), 1e-300)       # columns of comparable size for nnls
    c = nnls(a / scale / t[:, None], np.ones(len(t)))[0] / scale
    est = a @ c
    c = c * np.quantile(t / np.where(est > 0, est, np.inf), QUANTILE, method="higher")
    return dict(zip(terms, c))


def _machine() -> str:
    """The CPU model and core count of the machine that fits (the one that ran the results)."""
    import os
    import platform

    cpu = [ln.split(":", 1)[1].strip() for ln in open("/proc/cpuinfo") if ln.startswith("model name")] \
        if os.path.exists("/proc/cpuinfo") else []
    return f"{(cpu or [platform.processor() or platform.machine()])[0]} ({os.cpu_count()} cores)"


def measurements(results: str | Path, config_dir: str | Path = "config",
                 profile: str = "default") -> list[dict]:
    """The table's rows from a finished run's result tree: per paper and solver the fitted
    seconds per work term (:func:`fit`) from every run file whose record is today's (its
    ``wall_time_s``, or every solve of an accuracy target), and per paper the job start, the
    most any of its solve jobs spent beyond its runs' measured compute."""
    import netCDF4

    from .config import discover_papers, load_paper
    from .limits import work as work_of

    rows, machine = [], _machine()
    for paper in discover_papers(config_dir):
        cfg = load_paper(Path(config_dir) / "papers" / f"{paper}.yaml", profile)
        root, same, by_solver, spent = Path(results) / paper, cfg.same_solve(), {}, {}
        for name, run in cfg.runs.items():
            f = root / "runs" / f"{name}.nc"
            w = work_of(paper, run)
            if w is None or name in same or not f.exists():
                continue
            with netCDF4.Dataset(f) as nc:
                if nc.resolution != json.dumps(run["resolution"], sort_keys=True):
                    continue            # solved from another record: not this form's run
                sec = float(nc["target_seconds_all_solves"][...]
                            if "target_seconds_all_solves" in nc.variables else nc.wall_time_s)
            by_solver.setdefault(run["solver"], []).append((w, sec))
            least = float(run.get("options", {}).get("timing_min_s", 0.02))
            spent[name] = int(run.get("timing_repeat", 1)) * max(sec, least)
        for solver, pairs in sorted(by_solver.items()):
            for term, c in fit(*zip(*pairs)).items():
                rows.append({"paper": paper, "solver": solver, "term": term, "coefficient": f"{c:.4g}",
                             "runs": sum(w.get(term, 0) > 0 for w, _ in pairs),
                             "quantile": QUANTILE, "machine": machine})
        starts = [benchmark_seconds(root / "benchmarks" / f"solve__{job}.tsv")
                  - sum(spent.get(r, 0.0) for r in runs) for job, runs in cfg.solve_jobs().items()
                  if all(r in spent or r in same for r in runs)]
        if by_solver and starts:
            rows.append({"paper": paper, "solver": "(job)", "term": "start",
                         "coefficient": f"{max(0.0, np.nanmax(starts)):.4g}", "runs": len(starts),
                         "quantile": 1.0, "machine": machine})
    return rows


def main(argv=None) -> None:
    """``python -m mechrepro.costs RESULTS [PROFILE]``: write the cost table
    (:data:`mechrepro.limits.COSTS`) from a finished run of that profile (default: default).
    A solver the run did not measure keeps its row; a run that measured nothing writes
    nothing."""
    import argparse

    from .io import atomic_path
    from .limits import COSTS

    ap = argparse.ArgumentParser(prog="python -m mechrepro.costs", description=main.__doc__)
    ap.add_argument("results", help="a finished run's result tree, e.g. results")
    ap.add_argument("profile", nargs="?", default="default", help="its profile (default: default)")
    args = ap.parse_args(argv)
    rows = measurements(args.results, COSTS.parent, args.profile)
    if not rows:
        raise SystemExit(f"mechrepro.costs: {args.results}: no run of profile {args.profile} "
                         f"solved by today's records there; {COSTS} unchanged")
    fitted = {(r["paper"], r["solver"]) for r in rows}
    with open(COSTS, newline="") as f:
        kept = [r for r in csv.DictReader(f) if (r["paper"], r["solver"]) not in fitted]
    with atomic_path(COSTS, record=False) as tmp, open(tmp, "w", newline="") as f:
        w = csv.DictWriter(f, TABLE_COLUMNS, lineterminator="\n")
        w.writeheader()
        w.writerows(sorted(rows + kept, key=lambda r: (r["paper"], r["solver"], r["term"])))
    print(f"{COSTS}: {len(rows)} coefficients from {args.results}"
          + (f", {len(kept)} kept (solvers it did not measure)" if kept else ""))


if __name__ == "__main__":
    main()
