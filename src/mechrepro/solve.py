"""Run one solver job: run records from the config in, provenance-stamped netCDF out (the
Snakemake edge)."""
from __future__ import annotations

import importlib
import os
import sys
import time
from pathlib import Path

import numpy as np

from .errors import Refusal
from .timing import timed_run, timing_variables


class UnknownSolver(Refusal):
    """A run names a solver its paper's ``SOLVERS`` does not hold."""


def model(paper: str):
    """The model package of a paper.  One contract for every paper: ``SOLVERS``, a table
    {solver name: ``solver(run, ctx) -> result``} (the physics, called by :func:`compute`:
    what is timed) with an optional ``context(run)`` that builds ``ctx`` (without one a
    solver gets None and reads the run), and ``variables(result, run) -> {name: var(...)}``
    (what the run's file holds, labelled with :func:`mechrepro.units.var`; the framework
    packs it, :func:`pack`); optionally ``warm(runs)`` (load the compiled kernels those runs
    use; called once per solver process, before the first timed run)."""
    return importlib.import_module(f"mechrepro.models.{paper}")


def compute(run: dict):
    """The physics of one run, untimed: ``SOLVERS[run["solver"]](run, context(run))`` of its
    paper (:func:`model`); a solver the paper does not hold is refused."""
    m = model(run["paper"])
    if run.get("solver") not in m.SOLVERS:
        raise UnknownSolver(f"{run['paper']}: solver {run.get('solver')!r}: allowed "
                            f"{', '.join(m.SOLVERS)}")
    context = getattr(m, "context", None)
    return m.SOLVERS[run["solver"]](run, context and context(run))


def model_modules(paper: str) -> list[str]:
    """The modules of ``models/<paper>/`` a solve imports (paths relative to the mechrepro
    package): those the package reaches from its
    ``__init__`` by relative imports (at any depth, in functions too) and by its lazy
    exports (a string naming a sibling module).  What only validation and notebook read
    (validation.py, figures.py, accuracy.py, ...) is left out, so editing it reruns no solve.
    The imports are found as text, not parsed (every Snakemake start asks, for each solve
    job), each at the start of its line: a match in a string or comment can only add a
    module (tests/test_framework.py checks that none a model loads is missed)."""
    import ast
    import re

    pkg = Path(__file__).parent / "models" / paper
    seen, todo = set(), ["__init__"] + [n.value for n in ast.walk(ast.parse(
        (pkg / "__init__.py").read_text())) if isinstance(n, ast.Constant)
        and isinstance(n.value, str) and n.value.isidentifier()]
    while todo:
        name = todo.pop()
        if name in seen or not (pkg / f"{name}.py").exists():
            continue
        seen.add(name)
        for module, names in re.findall(r"^[ \t]*from \.(?!\.)(\w*)[\w.]* import (\([^)]*\)|.*)",
                                        (pkg / f"{name}.py").read_text(), re.M):
            todo += [module] if module else re.findall(r"\w+", names)
    return sorted(f"models/{paper}/{m}.py" for m in seen)


def paper_part(paper: str, module: str, name: str, required: bool = True):
    """``name`` (``Q``, ``ACCURACY``) from ``models/<paper>/<module>.py``, or from the
    package itself where a small paper keeps everything in its ``__init__``."""
    try:
        return getattr(importlib.import_module(f"mechrepro.models.{paper}.{module}"), name)
    except ModuleNotFoundError as exc:
        if exc.name != f"mechrepro.models.{paper}.{module}":
            raise
    found = getattr(model(paper), name, None)
    if found is None and required:
        raise ImportError(f"mechrepro.models.{paper}: no {module}.py and no {name} in the package")
    return found


def pack(variables: dict, run: dict):
    """The run's Dataset from the variables its paper names: a variable named like its only
    dimension is that dimension's coordinate, a string is a global attribute; the run's
    solver is one too."""
    import xarray as xr

    def dims(v):
        return (v[0],) if isinstance(v[0], str) else tuple(v[0])

    attrs = {k: v for k, v in variables.items() if isinstance(v, str)}
    if run.get("solver"):
        attrs["solver"] = run["solver"]
    coords = {k: v for k, v in variables.items() if k not in attrs and dims(v) == (k,)}
    data = {k: v for k, v in variables.items() if k not in attrs and k not in coords}
    return xr.Dataset(data, coords, attrs)


def solve(run: dict):
    """One run's Dataset, untimed (tests, benchmarks, notebooks): :func:`compute`, packed.
    The pipeline's jobs time the same call (:func:`run_solver`)."""
    return pack(model(run["paper"]).variables(compute(run), run), run)


def run_solver(run: dict):
    """Solve one run and attach its measured time, split into solver core and effects.

    Only the physics (:func:`compute`) is timed, not its packaging (:func:`pack`), so
    that the cost of accuracy is not blurred by xarray overhead.
    Fast solves are repeated and the fastest call kept (:func:`mechrepro.timing.time_call`).
    A run with a ``target`` accuracy is solved at the cheapest setting that meets it
    (:mod:`mechrepro.target`), and says what it chose, estimated and verified.
    """
    if run.get("target"):
        from . import target

        ds, rec = target.solve(run, lambda r: (lambda d: (d, d.attrs["wall_time_s"]))(
            _solve_once(r)))
        return ds.assign({
            f"target_{k}": ((), float(rec[k]), {"units": "s" if "seconds" in k else "1" if k in (
                                                 "knob_value", "default_value", "observed_order") else
                                                 run["target"].get("unit", "1"),
                                                 "long_name": k.replace("_", " ")})
            for k in ("value", "requested", "estimated_error", "verified_error", "knob_value",
                      "seconds_all_solves", "seconds_chosen", "default_value", "default_error",
                      "default_seconds", "default_estimated_error", "observed_order")} | {
            "target_levels": (("target_level",), np.asarray(rec["levels"], float),
                              {"units": "1", "long_name": f"values of {rec['knob']} solved"}),
            "target_values": (("target_level",), np.asarray(rec["values"], float),
                              {"units": run["target"].get("unit", "1"),
                               "long_name": f"{run['target']['reduce']} of "
                                            f"{run['target']['quantity']} at each level"})})
    return _solve_once(run)


def _min_time(run: dict) -> float:
    # a fast solve is repeated for 20 ms and its fastest call kept: enough for a stable
    # minimum without timing sub-millisecond runs for long
    return float(run.get("options", {}).get("timing_min_s", 0.02))


def alternated(runs: dict[str, dict], rounds: int) -> dict[str, tuple]:
    """{run: (result, fastest time, its timer)} of runs whose times are compared by
    difference (a ``marginal_cost:`` scene and its ``@without-<effect>`` runs), timed in
    alternation, ``rounds`` rounds of one call each (a fast one repeated for its
    ``timing_min_s``), each keeping its fastest: a load that comes and goes during the job
    then touches all of them alike, where one after the other it would bill the difference
    of the machine's load to an effect."""
    best: dict[str, tuple] = {}
    times: dict[str, list[float]] = {name: [] for name in runs}
    for _ in range(rounds):
        for name, run in runs.items():
            out = timed_run(compute, run, min_time=_min_time(run))
            times[name].append(out[1])
            if name not in best or out[1] < best[name][1]:
                best[name] = out
    # every round's time too: the spread of the differences is the marginal cost's noise
    return {name: (*out, times[name]) for name, out in best.items()}


def _solve_once(run: dict, timed: tuple | None = None):
    """Solve (or take the ``timed`` (result, seconds, timer) of :func:`alternated`) and
    pack the Dataset with the run's times."""
    m = model(run["paper"])
    result, seconds, timer, *rounds = timed or timed_run(compute, run, min_time=_min_time(run))
    ds = pack(m.variables(result, run), run)
    if rounds:
        ds["timing_rounds"] = ("timing_round", np.asarray(rounds[0], float),
                               {"units": "s", "long_name": "solve time of each alternated round"})
    # variables, not only attributes, so that gather stacks them along a study
    named = [*run["effects"], *run.get("outputs", ())]
    ds = ds.assign(timing_variables(seconds, timer, named))
    if named:
        ds = ds.assign_coords(timed_effect=("timed_effect", named,
                                            {"long_name": "effect or output named by the scene"}))
    ds.attrs["wall_time_s"] = seconds
    return ds


def blas_threads() -> None:
    """Apply MECHREPRO_BLAS_THREADS (a platform variant of config/reference.yaml): Snakemake
    sets OPENBLAS_NUM_THREADS to the job's threads, which a variant cannot override."""
    n = os.environ.get("MECHREPRO_BLAS_THREADS")
    if n:
        from threadpoolctl import threadpool_limits

        threadpool_limits(int(n), user_api="blas")


def main(argv: list[str]) -> None:
    """``python -m mechrepro.solve PAPER CONFIG_DIR PROFILE RESULTS RUN [RUN ...]``

    Solves the named runs of one paper in one process (one interpreter start, one import
    of the model) and writes ``RESULTS/PAPER/runs/<run>.nc`` for each, then stacks every
    study whose runs were all solved here into ``RESULTS/PAPER/studies/<study>.nc``.  The
    run records come from the validated config (the workflow passes them to Snakemake as
    params too, so a changed record reruns exactly its job).
    """
    if len(argv) < 5:
        raise SystemExit("usage: python -m mechrepro.solve PAPER CONFIG_DIR PROFILE RESULTS RUN [RUN ...]")
    paper, config_dir, profile, results, names = argv[0], argv[1], argv[2], Path(argv[3]), argv[4:]
    blas_threads()
    from .config import CACHE_DIR, load_paper
    from .io import gather_study, write_dataset

    cfg = load_paper(Path(config_dir) / "papers" / f"{paper}.yaml", profile, CACHE_DIR)
    unknown = [r for r in names if r not in cfg.runs]
    if unknown:
        raise SystemExit(f"{paper} ({profile}): no such run(s) {unknown}")
    root = results / paper
    # a model's compiled loops are loaded here, once, so that no run's measured time
    # carries the process's one-time load (numba's disk cache)
    warm = getattr(model(paper), "warm", None)
    if warm is not None:
        t0 = time.perf_counter()
        warm([cfg.runs[r] for r in names])
        print(f"[{paper}] compiled kernels loaded in {time.perf_counter() - t0:.3g} s", flush=True)
    # a marginal_cost: scene and its ablations, when this job solves them all, are timed
    # in alternation before the loop below packs and writes them
    groups: dict[str, list[str]] = {}
    for r, (scene, _) in cfg.ablations.items():
        groups.setdefault(scene, [scene]).append(r)
    timed = {}
    for scene, group in groups.items():
        if set(group) <= set(names) and not any(cfg.runs[r].get("target") for r in group):
            print(f"[{paper}] {scene}: {len(group)} runs timed in alternation "
                  f"({cfg.runs[scene]['timing_repeat']} rounds)", flush=True)
            timed.update(alternated({r: cfg.runs[r] for r in group},
                                    int(cfg.runs[scene]["timing_repeat"])))
    # a run that repeats another (PaperConfig.same_solve, which puts both in one job) is
    # packed from that run's solve under its own record, with the one measured time
    same, solved = cfg.same_solve(), {}
    n = len(names)
    for i, name in enumerate(names):
        run = cfg.runs[name]
        t0 = time.perf_counter()
        again = same.get(name) in solved
        print(f"[{paper} {i + 1}/{n}] {name}: solver={run.get('solver')} effects={run['effects']} "
              f"outputs={run.get('outputs', [])} resolution={run['resolution']}" + (f": the solve of {same[name]}" if again else ""),
              flush=True)
        if name in timed:
            ds = _solve_once(run, timed.pop(name))
        elif again:
            ds = _solve_once(run, solved[same[name]])
        elif name in same.values():
            solved[name] = timed_run(compute, run, min_time=_min_time(run))
            ds = _solve_once(run, solved[name])
        else:
            ds = run_solver(run)
        write_dataset(ds, root / "runs" / f"{name}.nc", run)
        print(f"[{paper} {i + 1}/{n}] {name}: solve {ds.attrs['wall_time_s']:.4g} s, "
              f"total {time.perf_counter() - t0:.3g} s", flush=True)
    done = set(names)
    for study, runs in cfg.studies.items():
        if set(runs) <= done:
            write_dataset(gather_study([root / "runs" / f"{r}.nc" for r in runs]),
                          root / "studies" / f"{study}.nc")
            print(f"[{paper}] study {study}: {len(runs)} runs stacked", flush=True)


def solve_jobs(cfg, config_dir: str | Path, results: str | Path, cores: int = 2) -> None:
    """Every run of ``cfg`` (a paper's config, perhaps cut down to some artefacts:
    :meth:`PaperConfig.for_artefacts`) solved without the workflow, by the jobs the workflow
    would run (:meth:`PaperConfig.solve_jobs`, each one :func:`main` call, longest estimated
    first) on ``cores`` processes forked from this one, then every study not stacked by its
    job gathered: ``mechrepro.cli artefact``, ``pytest -k fig05``."""
    import multiprocessing

    from .io import gather_study, write_dataset
    from .limits import job_costs

    jobs = cfg.solve_jobs()
    est = {j: c["seconds"] for j, c in job_costs(cfg).items()}
    argvs = [[cfg.paper, str(config_dir), cfg.profile, str(results), *jobs[j]]
             for j in sorted(jobs, key=lambda j: -est.get(j, 0.0))]
    warm = getattr(model(cfg.paper), "warm", None)
    if warm is not None:     # once, before the fork: every job inherits the loaded kernels
        warm(list(cfg.runs.values()))
    if cores > 1 and len(argvs) > 1:
        with multiprocessing.get_context("fork").Pool(min(cores, len(argvs))) as pool:
            list(pool.imap_unordered(main, argvs))
    else:
        for argv in argvs:
            main(argv)
    root = Path(results) / cfg.paper
    stacked = {s for runs in jobs.values() for s in cfg.studies_solved_with(runs)}
    for study, runs in cfg.studies.items():
        if study not in stacked:
            write_dataset(gather_study([root / "runs" / f"{r}.nc" for r in runs]),
                          root / "studies" / f"{study}.nc")


if __name__ == "__main__":
    main(sys.argv[1:])
