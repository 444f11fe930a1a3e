"""A paper's solve floor beside its cost model and its measured solve (issue #35).

Each paper's benchmark sizes every run of a profile from its run record (no solve), counts
the flops of the algorithm its solver uses and passes them here as rows
``(run, solver kind, flops, cost-model seconds)``.  The floor of a run is

    t_floor = flops / RATE,    RATE = 10 GFlop/s (one core, SIMD, operands in cache),

the rate bench_chain_drive.py's floor uses: a lower bound that no implementation on one
core of this machine beats, not a prediction.  With ``--measure`` the runs are solved in one
warm process as a solve job does (``compute(run)`` after the model's ``warm()``, BLAS on
one thread, in config order, so caches shared between runs count as in a job), each
timed by the process's CPU time, and the ratio measured / floor is printed per kind, in
total and for the longest run of each kind.  Timings are printed, never asserted.
"""
from __future__ import annotations

import os
import time
from collections import defaultdict

#: flops per second of one core (SIMD, in cache): the floor's rate, as chain_drive's
RATE = 1e10
#: what a transcendental (sin, cos, atan2, exp, pow) and a sqrt or a division count as in
#: the floors: a vectorised libm call costs ~10-20 multiply-adds, vsqrtpd / vdivpd ~4
TRANSCENDENTAL, SQRT = 20, 4


def measure(paper: str, runs: dict) -> dict:
    """CPU seconds of ``compute(run)`` per run, in one warm process (module docstring)."""
    if os.environ.get("OPENBLAS_NUM_THREADS") != "1":
        raise SystemExit("--measure needs OPENBLAS_NUM_THREADS=1 set before numpy loads "
                         "(the benchmark sets it unless the caller set another value)")
    from mechrepro.solve import compute, model

    m = model(paper)
    if hasattr(m, "warm"):
        m.warm()
    out = {}
    for name, run in runs.items():
        c0 = time.process_time()
        compute(run)
        out[name] = time.process_time() - c0
    return out


def arguments(ap) -> None:
    """The floor's options of a paper's benchmark (argparse parser ``ap``)."""
    ap.add_argument("--profile", default="default")
    ap.add_argument("--floor", action="store_true",
                    help="print only the solve floor from operation counts")
    ap.add_argument("--measure", action="store_true",
                    help="with the floor, the measured solve of the same runs")


def report(paper: str, profile: str, rows: list, estimate_note: str,
           runs: dict | None = None) -> None:
    """Print the floor per solver kind and in total, the cost model's estimate and, given
    the profile's ``runs``, their measured CPU time (:func:`measure`) and its ratio to the
    floor."""
    measured = measure(paper, runs) if runs else None
    kinds = defaultdict(lambda: [0, 0.0, 0.0, 0.0])
    for name, kind, flops, est in rows:
        k = kinds[kind]
        k[0] += 1
        k[1] += flops
        k[2] += est
        k[3] += measured[name] if measured else 0.0
    print(f"== solve floor of {paper} ({profile}) from operation counts at "
          f"{RATE / 1e9:g} GFlop/s; cost-model estimate: {estimate_note}")
    head = f"  {'solver':42s} {'runs':>5s} {'flops':>9s} {'floor s':>9s} {'estimate s':>10s}"
    if measured:
        head += f" {'measured s':>10s} {'measured/floor':>14s}"
    print(head)
    total = [sum(k[i] for k in kinds.values()) for i in range(4)]
    for kind, (n, fl, est, got) in sorted(kinds.items()) + [("total", total)]:
        line = f"  {kind:42s} {n:5d} {fl:9.3g} {fl / RATE:9.4f} {est:10.2f}"
        if measured:
            line += f" {got:10.3f} {_ratio(got, fl):>14s}"
        print(line)
    if measured:
        small = [r for r in rows if r[2] / RATE < 1e-3]
        print(f"  runs whose floor is below 1 ms: {len(small)}, measured "
              f"{sum(measured[r[0]] for r in small):.3f} s")
        longest = {}
        for row in sorted(rows, key=lambda r: -measured[r[0]]):
            longest.setdefault(row[1], row)
        print("  the longest run of each kind (CPU s, floor s, ratio):")
        for name, kind, flops, est in sorted(longest.values(), key=lambda r: -measured[r[0]]):
            print(f"    {kind:42s} {name:38s} {measured[name]:8.3f} {flops / RATE:9.5f} "
                  f"{_ratio(measured[name], flops):>9s}")


def _ratio(seconds: float, flops: float) -> str:
    """measured / floor, or "-" for work a benchmark does not count (0 flops)."""
    if not flops:
        return "-"
    r = seconds / (flops / RATE)
    return f"{r:.1f}x" if r < 10 else f"{r:.0f}x"
