"""Benchmark (not a test): the 200-speed sweep of the Fig. 5 study, vectorised vs per-speed loop.

    .venv/bin/python benchmarks/bench_chain_drive.py [--loop-speeds 12] [--profile default]

Prints, in one run, the wall time of the vectorised 200-speed sweep (scene fig05_length:
length change, impact, rigid polygonal action, end excitation; centre distance 20.25 pitches
so that the span length really changes) at the config's resolution,
and the time of the same computation speed by speed.  The loop runs on an evenly spread
subset of the speeds and is extrapolated linearly to all speeds (each speed costs the same
number of steps), which the output says; its amplitudes are checked against the
vectorised ones.  Timings on a shared machine are pessimistic.

    .venv/bin/python benchmarks/bench_chain_drive.py --schemes [--ppp 2 3 4 6 8 12] [--ref-ppp 16]

instead compares, side by side in one run, the paper's mixed differencing (Eq. 2-38) with
central differencing (s* = 0, second order) on the narrow sweep around the third resonance
(scene accuracy_peak): peak amplitude error against central at --ref-ppp, and wall time.
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
from mechrepro.models.chain_drive import fd, span  # noqa: E402


def _peak(a):
    """Peak of amp(speed) by parabolic interpolation through the three highest samples."""
    i = int(np.argmax(a))
    y0, y1, y2 = a[i - 1], a[i], a[i + 1]
    return y1 - 0.125 * (y0 - y2) ** 2 / (y0 - 2 * y1 + y2)


def schemes(profile: str, ppps, ref_ppp: int) -> None:
    run = load_paper(ROOT / "config/papers/chain_drive.yaml", profile).runs["accuracy_peak"]
    prm, res0, eff = dict(run["parameters"]), dict(run["resolution"]), run["effects"]
    om = span.speed_axis(prm, int(res0["n_speeds"]))

    def one(ppp, central):
        a = span.assemble(eff, prm, om, dict(res0, points_per_pitch=ppp))
        s = np.zeros_like(a["s_star"]) if central else a["s_star"]
        t0 = time.perf_counter()
        r = fd.march(c=a["c"], P=a["P"], exc=a["exc"], s_star=s, m=a["m"], c_d=a["c_d"],
                     grid=a["grid"], dt=a["dt"], n_steps=a["n_steps"],
                     measure_from=a["measure_from"], u_cap=0.05)
        return _peak(r.amplitude), time.perf_counter() - t0

    ref, _ = one(ref_ppp, True)
    print(f"reference: central differencing at {ref_ppp} points per pitch, peak {ref * 1e3:.4f} mm")
    print("points/pitch   central: error  time [s]    mixed (paper): error  time [s]")
    for ppp in ppps:
        (pc, tc), (pm, tm) = one(ppp, True), one(ppp, False)
        print(f"{ppp:12d}   {abs(pc / ref - 1):13.2%}  {tc:8.2f}    {abs(pm / ref - 1):19.2%}  {tm:8.2f}")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--profile", default="default")
    ap.add_argument("--scene", default="fig05_length")
    ap.add_argument("--speeds", type=int, default=200)
    ap.add_argument("--centre-distance", type=float, default=20.25,
                    help="in pitches; non-integral so that the span length really changes")
    ap.add_argument("--loop-speeds", type=int, default=12,
                    help="speeds actually run in the per-speed loop (extrapolated to --speeds)")
    ap.add_argument("--schemes", action="store_true",
                    help="compare central and mixed differencing (cost of accuracy) instead")
    ap.add_argument("--ppp", type=int, nargs="+", default=[2, 3, 4, 6, 8, 12])
    ap.add_argument("--ref-ppp", type=int, default=16)
    a = ap.parse_args()
    if a.schemes:
        schemes(a.profile, a.ppp, a.ref_ppp)
        return
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
