"""Benchmark (not a test): the 200-speed sweep of the Fig. 5 study, vectorised vs per-speed loop.

    .venv/bin/python benchmarks/bench_chain_drive.py [--loop-speeds 12] [--profile default]

Prints, in one run, the wall time of the vectorised 200-speed sweep (scene fig05_length:
length change, impact, rigid polygonal action, end excitation; centre distance 20.25 pitches
so that the span length really changes) at the config's resolution,
and the time of the same computation speed by speed.  The loop runs on an evenly spread
subset of the speeds and is extrapolated linearly to all speeds (each speed costs the same
number of steps), which the output says; its amplitudes are checked against the
vectorised ones.  Timings on a shared machine are pessimistic.
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "src"))

from mechrepro.config import load_paper  # noqa: E402
from mechrepro.models.chain_drive import span  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--profile", default="default")
    ap.add_argument("--scene", default="fig05_length")
    ap.add_argument("--speeds", type=int, default=200)
    ap.add_argument("--centre-distance", type=float, default=20.25,
                    help="in pitches; non-integral so that the span length really changes")
    ap.add_argument("--loop-speeds", type=int, default=12,
                    help="speeds actually run in the per-speed loop (extrapolated to --speeds)")
    a = ap.parse_args()
    run = load_paper(ROOT / "config/papers/chain_drive.yaml", a.profile).runs[a.scene]
    prm, res, eff = dict(run["parameters"]), dict(run["resolution"]), run["effects"]
    prm["centre_distance"] = a.centre_distance
    om = span.speed_axis(prm, a.speeds)
    t0 = time.perf_counter()
    vec = span.sweep(eff, prm, om, res, mode="vectorised")
    t_vec = time.perf_counter() - t0
    sub = np.unique(np.linspace(0, a.speeds - 1, min(a.loop_speeds, a.speeds)).round().astype(int))
    # the loop reuses the step of the full sweep (set by the fastest speed) for equal work
    t0 = time.perf_counter()
    loop = span.sweep(eff, prm, om[sub], res, mode="loop")
    t_sub = time.perf_counter() - t0
    t_loop = t_sub * a.speeds / sub.size
    same_dt = abs(loop["dt"] / vec["dt"] - 1) < 1e-12
    err = (np.max(np.abs(loop["amplitude"] / vec["amplitude"][sub] - 1)) if same_dt else float("nan"))
    print(f"scene {a.scene} ({a.profile}), centre distance {a.centre_distance} pitches: "
          f"{a.speeds} speeds x {vec['grid'].n_long + 1} points x "
          f"{vec['n_steps']} steps = {a.speeds * (vec['grid'].n_long + 1) * vec['n_steps']:.3g} "
          f"grid-point updates")
    print(f"vectorised sweep      : {t_vec:8.2f} s  (target <= 10 s)")
    print(f"per-speed loop        : {t_loop:8.2f} s  (extrapolated from {sub.size} speeds run in "
          f"{t_sub:.2f} s)")
    print(f"loop / vectorised     : {t_loop / t_vec:8.1f} x")
    print(f"amplitude difference  : {err:.2e} (loop vs vectorised on the subset; nan if the subset's "
          f"time step differs)")


if __name__ == "__main__":
    main()
