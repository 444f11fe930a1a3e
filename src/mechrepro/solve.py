"""Run one solver job: params JSON in, provenance-stamped netCDF out (the Snakemake edge)."""
from __future__ import annotations

import importlib
import json
import os
import sys
import time
from pathlib import Path

from .timing import timed_run, timing_variables
from .io import write_dataset


def model(paper: str):
    """The model package of a paper; it exposes ``solve(run) -> xarray.Dataset``."""
    return importlib.import_module(f"mechrepro.models.{paper}")


def run_solver(run: dict):
    """Solve one run and attach its measured time, split into solver core and effects.

    A model that separates its physics (``compute(run)``) from packaging
    (``to_dataset(result, run)``) is timed on the physics alone, so that the cost of
    accuracy is not blurred by xarray overhead; otherwise ``solve(run)`` is timed.
    Fast solves are repeated and the fastest call kept (:func:`mechrepro.timing.time_call`).
    """
    min_time = float(run.get("options", {}).get("timing_min_s", 0.05))
    m = model(run["paper"])
    if hasattr(m, "compute") and hasattr(m, "to_dataset"):
        result, seconds, timer = timed_run(m.compute, run, min_time=min_time)
        ds = m.to_dataset(result, run)
    else:
        ds, seconds, timer = timed_run(m.solve, run, min_time=min_time)
    # variables, not only attributes, so that gather stacks them along a study
    effects = list(run["effects"])
    ds = ds.assign(timing_variables(seconds, timer, effects))
    if effects:
        ds = ds.assign_coords(timed_effect=("timed_effect", effects,
                                            {"long_name": "effect named by the scene"}))
    ds.attrs["wall_time_s"] = seconds
    if run.get("solver"):
        ds.attrs["solver"] = run["solver"]
    return ds


def blas_threads() -> None:
    """Apply MECHREPRO_BLAS_THREADS (a platform variant of config/reference.yaml): Snakemake
    sets OPENBLAS_NUM_THREADS to the job's threads, which a variant cannot override."""
    n = os.environ.get("MECHREPRO_BLAS_THREADS")
    if n:
        from threadpoolctl import threadpool_limits

        threadpool_limits(int(n), user_api="blas")


def main(pairs: list[str]) -> None:
    """Solve ``params.json out.nc [params.json out.nc ...]`` in one process.

    Cheap runs share one job (one interpreter start, one import of the model) instead of
    paying both per run; each run is still timed and written on its own.
    """
    blas_threads()
    if len(pairs) % 2:
        raise SystemExit("usage: python -m mechrepro.solve PARAMS.json OUT.nc [...]")
    n = len(pairs) // 2
    for i in range(n):
        params_json, out_nc = pairs[2 * i], pairs[2 * i + 1]
        run = json.loads(Path(params_json).read_text())
        t0 = time.perf_counter()
        print(f"[{run['paper']} {i + 1}/{n}] {run['run']}: effects={run['effects']} "
              f"resolution={run['resolution']}", flush=True)
        ds = run_solver(run)
        write_dataset(ds, out_nc, run)
        print(f"[{run['paper']} {i + 1}/{n}] {run['run']}: solve {ds.attrs['wall_time_s']:.4g} s, "
              f"total {time.perf_counter() - t0:.3g} s -> {out_nc}", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
