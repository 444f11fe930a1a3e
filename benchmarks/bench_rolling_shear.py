"""rolling_shear speed, like for like: Eq. (9) solves only, time per design-branch solution.

Run: `.venv/bin/python benchmarks/bench_rolling_shear.py [n_points]`.
Target (issue 6): the pipeline's default solver (warm-started Newton) >= 300x faster per
solve than selPSO at equal branch success.  A selPSO solve that lands on the other
assembly mode must be repeated, so the selPSO time is divided by its design-branch rate;
both the paper's settings (w 0.9 -> 0.4, c = 2) and the standard constriction constants
(w = 0.7298, c = 1.49618) are timed, with and without natural selection.  Printed, never
asserted: timings depend on the machine and on what else runs on it.
"""
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "src"))

from mechrepro.config import load_paper  # noqa: E402
from mechrepro.models.rolling_shear import stroke  # noqa: E402
from mechrepro.models.rolling_shear.context import Context  # noqa: E402


def main(n_points: int = 33) -> None:
    run = load_paper(ROOT / "config/papers/rolling_shear.yaml").runs["solver_comparison"]
    run = dict(run, resolution={**run["resolution"], "n_points": n_points})
    ctx = Context(run)
    ref = stroke.solve_exact(ctx.g, ctx.x_k)
    t_newton = stroke.time_newton_loops(ctx.g, ref.theta, ctx.settings, min_time=1.0)
    print(f"rolling_shear, {n_points} cut points, Eq. (9) only; warm Newton "
          f"{t_newton * 1e6:.1f} us per solve, 100 % design branch")
    s = ctx.settings
    variants = {
        "selPSO (paper's w, c)": s,
        "selPSO (constriction)": replace(s, pso_loops=s.pso_std_loops, pso_pose=s.pso_std_pose),
        "PSO without selection (paper's w, c)": replace(
            s, pso_loops=replace(s.pso_loops, selection=False),
            pso_pose=replace(s.pso_pose, selection=False)),
    }
    for name, st in variants.items():
        sol = stroke.solve_compare(ctx.g, ctx.x_k, "selpso", st, ctx.rng(1))
        rate = sol.right.mean()
        per = sol.time_loops / rate if rate > 0 else np.inf
        print(f"  {name:38s} {sol.time_loops * 1e3:8.2f} ms/solve  design branch {rate:6.1%}  "
              f"median iterations {np.median(sol.iterations_loops):6.0f}  "
              f"per design-branch solve {per * 1e3:8.2f} ms = {per / t_newton:7.0f}x Newton")


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:2]))
