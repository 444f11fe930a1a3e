"""rolling_shear speed benchmarks (printed, never asserted: timings depend on the machine).

`.venv/bin/python benchmarks/bench_rolling_shear.py [n_points]` -- like for like (issue 6):
Eq. (9) solves only, time per design-branch solution.  Target: the pipeline's default
solver (warm-started Newton) >= 300x faster per solve than selPSO at equal branch success.
A selPSO solve that lands on the other assembly mode must be repeated, so the selPSO time is
divided by its design-branch rate; both the paper's settings (w 0.9 -> 0.4, c = 2) and the
standard constriction constants (w = 0.7298, c = 1.49618) are timed, with and without
natural selection.

`.venv/bin/python benchmarks/bench_rolling_shear.py paths [revision] [rounds]` -- issue 32:
every compiled path (Newton on Eqs. 7 and 9, the two warm continuations, the swarm on both
fitnesses, the lever objective with its assembly check, the closed-form pose with its scan,
the Newton stroke) on fixed work, the code at ``revision`` (default: where this branch left
``main``) and this worktree side by side: one process per variant and round, the variants
alternating, each path the fastest of 5 repetitions in a process and of ``rounds`` rounds.

`.venv/bin/python benchmarks/bench_rolling_shear.py speed [profile] [revision] [repeats]` --
issue 18: every run of the profile (``compute(run)``, the solve without dataset and netCDF)
timed side by side, in one script run, for the code at ``revision`` (default: where this branch left ``main``,
extracted by ``git archive``), this worktree's code with the compiled loops
(``closure.py``) and without them (``MECHREPRO_RS_KERNEL=numpy``).  Each variant runs in its
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


def _checkout(revision: str, tmp: str) -> tuple[str, Path]:
    """(revision, its src/ extracted into tmp); default: where this branch left main."""
    revision = revision or subprocess.run(
        ["git", "-C", str(ROOT), "merge-base", "HEAD", "main"], capture_output=True, text=True,
        check=True).stdout.strip()[:10]
    old = Path(tmp) / "old"
    old.mkdir()
    archive = subprocess.run(["git", "-C", str(ROOT), "archive", revision, "src"],
                             capture_output=True, check=True).stdout
    subprocess.run(["tar", "-x", "-C", str(old)], input=archive, check=True)
    return revision, old


# the compiled paths on fixed work, each the fastest of 5 repetitions; prints {path: s} as JSON
PATHS = r"""
import json, math, sys, time
sys.path.insert(0, sys.argv[1])
import numpy as np
from mechrepro.config import load_paper
from mechrepro.models.rolling_shear import kernels, newton, optimise, pose, stroke
from mechrepro.models.rolling_shear.geometry import cut_points, from_parameters
from mechrepro.models.rolling_shear.selpso import SelPSOSettings, selpso
assert kernels.available()
kernels.warm()
g = from_parameters(load_paper(sys.argv[2]).runs["original"]["parameters"])
x_k = cut_points(g, 33)[1]
th = stroke.solve_exact(g, x_k).theta
t5, t6 = th[16, 4], th[16, 5]
st = SelPSOSettings(swarm=40, max_iter=300, v_max=1.0)
paths = {
    "newton.pose x33": lambda: [newton.pose(g, (th[i, 4] + 1e-3, th[i, 5] - 1e-3),
                                            float(x_k[i]), 1e-9) for i in range(33)],
    "newton.loops x33": lambda: [newton.loops(g, th[i, :4] + 1e-3, th[i, 4], th[i, 5], 1e-11)
                                 for i in range(33)],
    "stroke_poses": lambda: optimise.stroke_poses(g, x_k, 1e-9),
    "loops stroke x20": lambda: [stroke._newton_loops_stroke(g, th, stroke.SolverSettings())
                                 for _ in range(20)],
    "selpso Eq. 9 x3": lambda: [selpso(stroke.loops_fitness(g, t5, t6), th[16, :4] + 0.1, st,
                                       np.random.default_rng(s), period=2 * math.pi)
                                for s in range(3)],
    "selpso Eq. 7 x3": lambda: [selpso(stroke.pose_fitness(g, float(x_k[3])),
                                       np.array([t5 + 0.1, t6 - 0.1]), SelPSOSettings(
                                           swarm=40, max_iter=300, v_max=1.0, tol=1e-9),
                                       np.random.default_rng(s), period=2 * math.pi)
                                for s in range(3)],
    "objective x3": lambda: [optimise.objective(g, x_k, 1e-9) for _ in range(3)],
    "exact_pose x9": lambda: [pose.exact_pose(g, float(x_k[i])) for i in range(0, 33, 4)],
    "solve_newton": lambda: stroke.solve_newton(g, x_k, stroke.SolverSettings(
        initial_value=tuple(np.round(th[0], 1)))),
}
out = {}
for name, fn in paths.items():
    fn()
    best = math.inf
    for _ in range(5):
        t = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t)
    out[name] = best
print(json.dumps(out))
"""


def paths(revision: str = "", rounds: int = 5) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        revision, old = _checkout(revision, tmp)
        variants = {revision: old / "src", "this tree": ROOT / "src"}
        best = {}
        for _ in range(rounds):
            for name, src in variants.items():
                out = subprocess.run([sys.executable, "-c", PATHS, str(src), str(CONFIG)],
                                     capture_output=True, text=True, check=True)
                t = json.loads(out.stdout.strip().splitlines()[-1])
                best[name] = {r: min(v, best.get(name, {}).get(r, np.inf)) for r, v in t.items()}
    print(f"rolling_shear compiled paths: ms, fastest of 5 x {rounds} rounds (interleaved)")
    print(f"{'path':20s}{revision:>12s}{'this tree':>12s}{'ratio':>8s}")
    for r, a in best[revision].items():
        b = best["this tree"][r]
        print(f"{r:20s}{a * 1e3:12.3f}{b * 1e3:12.3f}{b / a:8.3f}")


def speed(profile: str = "ci", revision: str = "", repeats: int = 2) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        revision, old = _checkout(revision, tmp)
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
    if sys.argv[1:2] == ["paths"]:
        paths(*(sys.argv[2:3]), *(int(a) for a in sys.argv[3:4]))
    elif sys.argv[1:2] == ["speed"]:
        speed(*(sys.argv[2:4]), *(int(a) for a in sys.argv[4:5]))
    else:
        like_for_like(*(int(a) for a in sys.argv[1:2]))
