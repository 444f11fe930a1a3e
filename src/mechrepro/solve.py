"""Run one solver job: params JSON in, provenance-stamped netCDF out (the Snakemake edge)."""
from __future__ import annotations

import importlib
import json
import sys
import time
from pathlib import Path

from .accuracy import time_call
from .io import write_dataset


def model(paper: str):
    """The model package of a paper; it exposes ``solve(run) -> xarray.Dataset``."""
    return importlib.import_module(f"mechrepro.models.{paper}")


def run_solver(run: dict):
    """Solve one run and attach its measured wall time (``wall_time_s`` attribute)."""
    min_time = float(run.get("options", {}).get("timing_min_s", 0.05))
    ds, seconds = time_call(model(run["paper"]).solve, run, min_time=min_time)
    ds.attrs["wall_time_s"] = seconds
    return ds


def main(params_json: str, out_nc: str) -> None:
    run = json.loads(Path(params_json).read_text())
    t0 = time.perf_counter()
    print(f"[{run['paper']}] {run['run']}: effects={run['effects']} "
          f"resolution={run['resolution']}", flush=True)
    ds = run_solver(run)
    write_dataset(ds, out_nc, run)
    print(f"[{run['paper']}] {run['run']}: solve {ds.attrs['wall_time_s']:.4g} s, "
          f"total {time.perf_counter() - t0:.3g} s -> {out_nc}", flush=True)


if __name__ == "__main__":
    main(*sys.argv[1:])
