"""rolling_shear speed: the full cutting stroke by selPSO and by warm-started Newton.

Run: `.venv/bin/python benchmarks/bench_rolling_shear.py [n_points]`.
Target (issue 6): the pipeline's default solver (warm-started Newton) >= 300x faster per
solve than selPSO, with 100 % of the solves on the design branch.  Printed, never
asserted: timings depend on the machine and on what else runs on it.
"""
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "src"))

from mechrepro.config import load_paper  # noqa: E402
from mechrepro.models.rolling_shear import stroke  # noqa: E402
from mechrepro.models.rolling_shear.geometry import cut_points  # noqa: E402
from mechrepro.models.rolling_shear.solver import Context  # noqa: E402


def main(n_points: int = 33) -> None:
    run = load_paper(ROOT / "config/papers/rolling_shear.yaml").runs["solver_comparison"]
    run = dict(run, resolution={**run["resolution"], "n_points": n_points})
    ctx = Context(run)
    xk = cut_points(ctx.g, n_points)[1]
    ref = stroke.solve_exact(ctx.g, xk)

    t0 = time.perf_counter()
    pso = stroke.solve_compare(ctx.g, xk, "selpso", ctx.settings, ctx.rng(1))
    t_pso = time.perf_counter() - t0

    reps, t0 = 0, time.perf_counter()
    while time.perf_counter() - t0 < 1.0 or reps < 5:
        newton = stroke.solve_newton(ctx.g, xk, ctx.settings)
        reps += 1
    t_newton = (time.perf_counter() - t0) / reps

    solves = 2 * n_points  # Eq. (7) and Eq. (9) at every cut point
    err = np.max(np.abs(np.angle(np.exp(1j * (newton.theta - ref.theta)))))
    print(f"rolling_shear stroke, {n_points} cut points ({solves} nonlinear solves per stroke)")
    print(f"  selPSO : {t_pso:8.3f} s/stroke  {t_pso / solves * 1e3:9.3f} ms/solve  "
          f"success {pso.converged.mean():6.1%}  in ranges {pso.in_ranges.mean():6.1%}  "
          f"design branch {pso.right.mean():6.1%}")
    print(f"  Newton : {t_newton:8.5f} s/stroke  {t_newton / solves * 1e3:9.4f} ms/solve  "
          f"success {newton.converged.mean():6.1%}  design branch {newton.right.mean():6.1%}  "
          f"(max |theta - closed form| = {err:.1e} rad, {reps} repeats)")
    ratio = t_pso / t_newton
    print(f"  ratio selPSO / Newton per solve: {ratio:.0f}x "
          f"({'meets' if ratio >= 300 and newton.right.all() else 'MISSES'} the >= 300x, "
          f"100 % right-branch target)")


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:2]))
