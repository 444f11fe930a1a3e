"""saw_chain speed: vectorised difference method vs a per-step Python loop, the study, and
the solve floor.

Run: `make benchmark` or `.venv/bin/python benchmarks/bench_saw_chain.py`.
Targets (issue 2): vectorised >= 50x the loop; the whole saw_chain study including its
cost-of-accuracy sweep <= 10 s.  Printed, never asserted: timings depend on the machine.

    .venv/bin/python benchmarks/bench_saw_chain.py --floor [--profile ci] [--measure]

prints only the solve floor of the profile's runs from operation counts (:func:`floor`),
with ``--measure`` beside their measured solve (benchmarks/_floor.py).
"""
import argparse
import os
from pathlib import Path

# must precede the first numpy import: OpenBLAS reads it when it loads
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

ROOT = Path(__file__).resolve().parent.parent

from mechrepro.timing import time_call
from mechrepro.config import load_paper
from mechrepro.models.saw_chain.solver import chain_from_run, difference_method
from mechrepro.timing import phase
from saw_chain_reference import difference_method_loop
from mechrepro.solve import run_solver

import _floor


def vectorised_vs_loop(K=10000):
    cfg = load_paper(ROOT / "config/papers/saw_chain.yaml")
    run = dict(cfg.runs["accuracy"], effects=[], resolution={"K": K})
    p = run["parameters"]
    # the solver core alone (what the run's core_time measures), without its reference
    _, t_vec = time_call(difference_method, chain_from_run(run), min_time=0.5)
    _, t_loop = time_call(difference_method_loop, p["tie_strap_pitch"], p["drive_link_pitch"],
                          int(p["teeth"]), p["sprocket_speed"], p["tie_strap_mass"],
                          p["drive_link_mass"], int(p["tie_straps_tight_side"]),
                          int(p["drive_links_tight_side"]), K, min_time=0.5)
    _, t_np = time_call(numpy_kernel_loop, run, min_time=0.5)
    return t_vec, t_loop, t_np


def numpy_kernel_loop(run):
    """The vectorised kernel called one step at a time (a per-step loop over numpy)."""
    import numpy as np

    from mechrepro.models.saw_chain.kinematics import stage_positions
    from mechrepro.models.saw_chain.solver import chain_from_run

    chain = chain_from_run(run)
    R, w = chain.R, chain.omega
    out = []
    for L, m_link, phi in chain.stages():
        dt = (phi[1] - phi[0]) / w
        prev = None
        for ph in phi:
            pos = stage_positions(np.float64(ph), R, L, chain.Tx)
            if prev is not None:
                out.append((pos["trail_x"] - prev["trail_x"]) / dt)
            prev = pos
    return out


def whole_study(profile="default"):
    cfg = load_paper(ROOT / "config/papers/saw_chain.yaml", profile)
    with phase("benchmark:1") as sw:
        for run in cfg.runs.values():
            run_solver(dict(run, options={**run["options"], "timing_min_s": 0.0}))
    return len(cfg.runs), sw.seconds


def richardson_vs_plain():
    """Peak-load error and time at equal finest K: plain vs Richardson (3 solves)."""
    import numpy as np

    from dataclasses import replace
    from mechrepro.models.saw_chain.design import design_quantities
    from saw_chain_reference import extrapolate_extreme
    from mechrepro.models.saw_chain.difference import load_x

    cfg = load_paper(ROOT / "config/papers/saw_chain.yaml")
    chain = chain_from_run(dict(cfg.runs["accuracy"], resolution={"K": 1}))
    exact = float(design_quantities(**chain.inputs())["peak_load"])
    rows = []
    for K in (128, 1024, 4096, 32768):
        plain, tp = time_call(lambda: float(load_x(replace(chain, K=K)).max()), min_time=0.2)
        ext, tr = time_call(extrapolate_extreme, chain, K, min_time=0.2)
        rows.append((K, abs(plain - exact) / exact, tp, abs(ext.value - exact) / exact, tr))
    zs = np.resize(np.arange(3, 61), 1000)
    _, td = time_call(design_quantities, **{**chain.inputs(), "z": zs}, min_time=0.2)
    return rows, td / zs.size


def test_bench_saw_chain():
    t_vec, t_loop, t_np = vectorised_vs_loop()
    n, t_study = whole_study()
    print(f"\nsaw_chain K=10000 (20000 steps), fastest of repeated calls:")
    print(f"  vectorised difference method       {t_vec * 1e3:8.2f} ms")
    print(f"  per-step loop over the numpy kernel {t_np * 1e3:8.1f} ms  ratio {t_np / t_vec:5.0f}x (target >= 50x)")
    print(f"  per-step loop in scalar math        {t_loop * 1e3:8.1f} ms  ratio {t_loop / t_vec:5.0f}x "
          f"(hand-optimised Python floats)")
    rows, t_design = richardson_vs_plain()
    print("peak load at equal finest K: K, plain error, time | Richardson error, time (3 solves)")
    for K, ep, tp, er, tr in rows:
        print(f"  {K:6d}  {ep:.2e} {tp * 1e3:7.3f} ms | {er:.2e} {tr * 1e3:7.3f} ms")
    print(f"design maps: {t_design * 1e6:.1f} us per design (1000 designs per call)")
    print(f"saw_chain whole study (default profile, {n} runs, solve + packaging): "
          f"{t_study:.2f} s (target <= 10 s)")


#: flops per sample of one stage (benchmarks/_floor.py counts a sin or cos as
#: TRANSCENDENTAL, a sqrt or division as SQRT):
#: the difference method: positions (Eqs. 7-10: one sin of phi/2, two sqrt, 15 mul/add),
#: three backward differences (Eqs. 12-13, 17-19: 4 each) and the loads (Eqs. 14-16: 4)
FLOPS_METHOD = 31 + 2 * _floor.SQRT + _floor.TRANSCENDENTAL
#: ``options.loads: false``: the trailing hinge's x (one sin, two sqrt, 10) and Eq. (12)
FLOPS_VELOCITY = 12 + 2 * _floor.SQRT + _floor.TRANSCENDENTAL
#: effect exact_reference: the exact derivatives (a sin, a cos, a sqrt, two divisions,
#: ~30 mul/add) and the loads (4)
FLOPS_EXACT = 34 + 3 * _floor.SQRT + 2 * _floor.TRANSCENDENTAL
#: effect textbook, Eq. (23): a sin, a cos and 5 mul/add
FLOPS_TEXTBOOK = 5 + 2 * _floor.TRANSCENDENTAL


def floor(profile="default", measure=False):
    """saw_chain's solve floor from operation counts.  A run samples two stages of K steps
    each (K + 1 samples per stage, Sec. 3.3), and each sample costs

        FLOPS_METHOD (or FLOPS_VELOCITY for a velocity-only run)
        + FLOPS_EXACT if the scene names exact_reference + FLOPS_TEXTBOOK if textbook,

    so a run's flops are 2 (K + 1) x that sum, 59-190 flops per sample, at
    :data:`_floor.RATE`.  Flops bound it, not memory: a loop that fused the stages would
    write at most 8 arrays of 8 B per sample, ~6 ns per sample at ~10 GB/s against 6-19 ns
    of flops (numpy's temporaries are what makes today's solve memory-bound at large K).
    Nothing else is counted: the error budget and the effects'
    bookkeeping are O(1) per run.  A run with a ``target`` accuracy is sized at its
    configured K, as ``compute(run)`` solves it (the job's refinement repeats it at
    doubled K; the cost model's estimate includes that)."""
    from mechrepro import limits

    cfg = load_paper(ROOT / "config/papers/saw_chain.yaml", profile)
    rows = []
    for name, run in cfg.runs.items():
        K, eff = int(run["resolution"]["K"]), run["effects"]
        per = FLOPS_METHOD if run.get("options", {}).get("loads", True) else FLOPS_VELOCITY
        per += FLOPS_EXACT * ("exact_reference" in eff) + FLOPS_TEXTBOOK * ("textbook" in eff)
        kind = "+".join([run["solver"], *sorted(eff)])
        rows.append((name, kind, 2 * (K + 1) * per, limits.run_cost("saw_chain", run)["seconds"]))
    _floor.report("saw_chain", profile, rows, "limits.run_cost, per run (config/costs.csv)",
                  cfg.runs if measure else None)


def main():
    ap = argparse.ArgumentParser()
    _floor.arguments(ap)
    a = ap.parse_args()
    if not a.floor:
        test_bench_saw_chain()
    floor(a.profile, a.measure)


if __name__ == "__main__":
    main()
