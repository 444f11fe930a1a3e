"""rolling_shear speed benchmarks (printed, never asserted: timings depend on the machine).

`.venv/bin/python benchmarks/bench_rolling_shear.py [n_points]` -- like for like (issue 6):
Eq. (9) solves only, time per design-branch solution.  Target: the pipeline's default
solver (warm-started Newton) >= 300x faster per solve than selPSO at equal branch success.
A selPSO solve that lands on the other assembly mode must be repeated, so the selPSO time is
divided by its design-branch rate; both the paper's settings (w 0.9 -> 0.4, c = 2) and the
standard constriction constants (w = 0.7298, c = 1.49618) are timed, with and without
natural selection.

`.venv/bin/python benchmarks/bench_rolling_shear.py speed [profile] [revision] [repeats]` --
issue 18: every run of the profile (``compute(run)``, the solve without dataset and netCDF)
timed side by side, in one script run, for the code at ``revision`` (default: where this branch left ``main``,
extracted by ``git archive``), this worktree's code with the compiled loops
(``kernels.py``) and without them (``MECHREPRO_RS_KERNEL=numpy``).  Each variant runs in its
own process: one untimed pass (imports, numba's cache), then ``repeats`` passes, the fastest
per run kept; the variants alternate pass by pass, so that another process's load hits all
of them alike.  Prints per-run seconds and the ratios.
"""
import json
import os
import subprocess
import sys
import tempfile
from dataclasses import replace
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "src"))

from mechrepro.config import load_paper  # noqa: E402

CONFIG = ROOT / "config/papers/rolling_shear.yaml"

# one pass of every run of a profile, in a child process; prints {run: seconds} as JSON
CHILD = r"""
import json, sys, time
sys.path.insert(0, sys.argv[1])
from mechrepro.config import load_paper
from mechrepro.models.rolling_shear import solver
runs = load_paper(sys.argv[2], sys.argv[3]).runs
out = {}
for name, run in runs.items():
    t = time.perf_counter()
    solver.compute(run)
    out[name] = time.perf_counter() - t
print(json.dumps(out))
"""


def like_for_like(n_points: int = 33) -> None:
    from mechrepro.models.rolling_shear import stroke
    from mechrepro.models.rolling_shear.context import Context

    run = load_paper(CONFIG).runs["solver_comparison"]
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


def _pass(src: Path, profile: str, env: dict) -> dict:
    out = subprocess.run([sys.executable, "-c", CHILD, str(src), str(CONFIG), profile],
                         env={**os.environ, **env}, capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def speed(profile: str = "ci", revision: str = "", repeats: int = 2) -> None:
    revision = revision or subprocess.run(
        ["git", "-C", str(ROOT), "merge-base", "HEAD", "main"], capture_output=True, text=True,
        check=True).stdout.strip()[:10]          # default: where this branch left main
    with tempfile.TemporaryDirectory() as tmp:
        old = Path(tmp) / "old"
        old.mkdir()
        archive = subprocess.run(["git", "-C", str(ROOT), "archive", revision, "src"],
                                 capture_output=True, check=True).stdout
        subprocess.run(["tar", "-x", "-C", str(old)], input=archive, check=True)
        variants = {revision: (old / "src", {}),
                    "numpy loops": (ROOT / "src", {"MECHREPRO_RS_KERNEL": "numpy"}),
                    "compiled loops": (ROOT / "src", {"MECHREPRO_RS_KERNEL": "auto"})}
        best = {}
        for k in range(repeats + 1):                   # pass 0 warms caches, untimed
            for name, (src, env) in variants.items():
                t = _pass(src, profile, env)
                if k:
                    best[name] = {r: min(v, best.get(name, {}).get(r, np.inf)) for r, v in t.items()}
    runs = list(best[revision])
    names = list(variants)
    print(f"rolling_shear, profile {profile}: compute(run) seconds, fastest of {repeats} passes")
    print(f"{'run':42s}" + "".join(f"{n:>16s}" for n in names) + f"{'ratio':>9s}")
    for r in runs:
        row = [best[n][r] for n in names]
        print(f"{r:42s}" + "".join(f"{v:16.3f}" for v in row) + f"{row[0] / row[-1]:9.1f}")
    tot = [sum(best[n].values()) for n in names]
    print(f"{'total':42s}" + "".join(f"{v:16.3f}" for v in tot) + f"{tot[0] / tot[-1]:9.1f}")
    print(f"ratio {revision} / numpy loops {tot[0] / tot[1]:.1f}, "
          f"numpy loops / compiled loops {tot[1] / tot[2]:.1f}")


if __name__ == "__main__":
    if sys.argv[1:2] == ["speed"]:
        speed(*(sys.argv[2:4]), *(int(a) for a in sys.argv[4:5]))
    else:
        like_for_like(*(int(a) for a in sys.argv[1:2]))
