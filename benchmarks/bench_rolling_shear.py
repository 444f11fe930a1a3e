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

`.venv/bin/python benchmarks/bench_rolling_shear.py floor [--profile ci] [--measure]` (or
``--floor``) -- issue 35: the solve floor of every run of the profile from operation counts
(:func:`floor`), with ``--measure`` beside the measured solve (benchmarks/_floor.py).  The
default run (no argument, as ``make benchmark`` calls it) prints it last, for the default
profile.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
from dataclasses import replace
from pathlib import Path

# must precede the first numpy import: OpenBLAS reads it when it loads
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

import _floor  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent

from mechrepro.config import load_paper  # noqa: E402

CONFIG = ROOT / "config/papers/rolling_shear.yaml"

# one pass of every run of a profile, in a child process; prints {run: seconds} as JSON
CHILD = r"""
import json, sys, time
from mechrepro.config import load_paper
from mechrepro.solve import compute
runs = load_paper(sys.argv[1], sys.argv[2]).runs
out = {}
for name, run in runs.items():
    t = time.perf_counter()
    compute(run)
    out[name] = time.perf_counter() - t
print(json.dumps(out))
"""


def like_for_like(n_points: int = 33) -> None:
    from mechrepro.models.rolling_shear import stroke
    from mechrepro.models.rolling_shear.run_context import Context

    run = load_paper(CONFIG).runs["solver_comparison"]
    run = dict(run, resolution={**run["resolution"], "n_points": n_points})
    ctx = Context(run)
    ref = stroke.exact_theta(ctx.g, ctx.x_k)
    t_newton = stroke.time_newton_loops(ctx.g, ref, ctx.settings, min_time=1.0)
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
    out = subprocess.run([sys.executable, "-c", CHILD, str(CONFIG), profile],
                         env={**os.environ, **env, "PYTHONPATH": str(src)}, capture_output=True,
                         text=True, check=True)
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
import numpy as np
from mechrepro.config import load_paper
from mechrepro.models.rolling_shear import blade, closure, kernels, optimise, stroke
from mechrepro.models.rolling_shear.geometry import cut_points, from_parameters
from mechrepro.models.rolling_shear.selpso import SelPSOSettings, selpso
assert closure.available()
kernels.warm()
g = from_parameters(load_paper(sys.argv[1]).runs["original"]["parameters"])
x_k = cut_points(g, 33)[1]
th = stroke.exact_theta(g, x_k)
t5, t6 = th[16, 4], th[16, 5]
st = SelPSOSettings(swarm=40, max_iter=300, v_max=1.0)
paths = {
    "newton.pose x33": lambda: [kernels.newton_pose(g, (th[i, 4] + 1e-3, th[i, 5] - 1e-3),
                                            float(x_k[i]), 1e-9) for i in range(33)],
    "newton.loops x33": lambda: [kernels.newton_loops(g, th[i, :4] + 1e-3, th[i, 4], th[i, 5], 1e-11)
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
    "exact_pose x9": lambda: [blade.exact_pose(g, float(x_k[i])) for i in range(0, 33, 4)],
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
                out = subprocess.run([sys.executable, "-c", PATHS, str(CONFIG)],
                                     env={**os.environ, "PYTHONPATH": str(src)},
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


_T, _S = _floor.TRANSCENDENTAL, _floor.SQRT

#: flops of one evaluation of Eq. (7) in Newton form with its Jacobian and Cramer step
#: (:func:`.closure.pose_block`, :func:`.closure.newton2`): 6 sin/cos, ~22 mul/add, G 3,
#: det and the two updates 9 + 2 divisions
NEWTON_POSE_EVAL = 6 * _T + 34 + 2 * _S
#: one evaluation of a loop of Eq. (9) in Newton form (:func:`.closure.dyad_block`): 4 sin/cos,
#: 8 mul/add, G 3, Cramer 9 + 2 divisions; the knowns of a cut point (:func:`.closure.loop_knowns`)
NEWTON_DYAD_EVAL, LOOP_KNOWNS = 4 * _T + 20 + 2 * _S, 6 * _T + 6
#: evaluations per cut point and system of the warm-started Newton (its iterations + the
#: evaluation that finds G < tol): 2.2 iterations on Eq. (7) and on each loop of Eq. (9) at
#: newton_tol 1e-11, 1.1 at 0.1 (counted on the ci profile's continuation runs)
NEWTON_EVALS, NEWTON_EVALS_LOOSE = 3.2, 2.1
#: :func:`.blade.exact_pose`: the 601-point scan of |ED(beta)| - l6 (:func:`.closure.guide_scan`:
#: 4 sin/cos, ~18 mul/add and a hypot per point) and one Brent root of ~10 steps of the same
#: function (+ ~15 of Brent's own) and an atan2
EXACT_POSE = 601 * (4 * _T + 18 + _S) + 10 * (4 * _T + 33 + _S) + _T
#: the rest of a closed-form cut point (:func:`.stroke.exact_theta`): both dyads in closed
#: form (knowns 6 sin/cos; per dyad a hypot, a sqrt, 2 divisions, 2 atan2, ~15)
EXACT_REST = 6 * _T + 2 * (3 * _S + 2 * _S + 2 * _T + 15)
#: per cut point of the lever objective (:func:`.optimise.objective`) besides its Newton on
#: Eq. (7): the assembly check (:func:`.closure.assembles_clearly`: 6 sin/cos; per dyad a
#: hypot, a sqrt, 2 divisions, 2 atan2, 2 fmod, ~25) and H (Eq. 8: 2 sin, ~10)
OBJECTIVE_POINT = 6 * _T + 2 * (4 * _S + 2 * _T + 33) + 2 * _T + 10
#: the calibration of every run (:func:`.calibrate.calibrate_tilt`, whole_scan False): the
#: tilt scan stops after 4 tilts at min(33, calibration_points) cut points, Brent then takes
#: 9 objectives at calibration_points, and H of the original levers one more; a family
#: member (:func:`.family.calibrated_member`) takes 22 objectives at the run's cut points
#: on average (many scan every tilt and none calibrates) and 0.6 of the members a
#: closed-form stroke (all counted on the ci and default profiles' runs: 22.4 and 22.0,
#: 0.67 and 0.55)
CAL_SCAN, CAL_BRENT, MEMBER_OBJECTIVES, MEMBER_EXACT = 4, 10, 22, 0.6
#: the tilt scan effect: the 41 tilts less those the calibration scanned, at 33 cut points
TILT_SCAN = 41 - CAL_SCAN
#: the constant-rate drive (:func:`.blade.drive`) per cut point: ~3 Newton iterations on
#: Eq. (9) in 4 unknowns (residual 8 sin/cos, Jacobian 8, a 4 x 4 LU and solve ~60) and the
#: lowest point (8 sin/cos)
DRIVE_POINT = 3 * (16 * _T + 60 + 20) + 8 * _T + 10
#: a particle of a swarm per iteration (:func:`.selpso.iterate`): the fitness G of Eq. (9)
#: (8 sin/cos, ~23) or of Eq. (7) (8 sin/cos, ~20), per unknown the velocity and position
#: update with two uniform draws (~26), the natural selection's sort (~14)
PSO_LOOPS, PSO_POSE = 8 * _T + 23 + 4 * 26 + 14, 8 * _T + 20 + 2 * 26 + 14
#: iterations of a swarm that stops at its tolerance (pso_tol > 0; Eq. 7's swarm always
#: stops at pose_tol): ~300 on Eq. (9), ~130 on Eq. (7) at 60 particles (counted on the ci
#: profile's solver_comparison and coa_selpso runs); min(that, pso_iter)
PSO_LOOPS_ITERS, PSO_POSE_ITERS = 300, 130
#: scipy's root / least_squares per solve: ~14 evaluations (counted) of the residual and its
#: Jacobian (Eq. 9: ~300 + 300) and the solver's own small dense algebra (~200)
SCIPY_SOLVE = 14 * 800


def _objective(n: int) -> float:
    """Flops of :func:`.optimise.objective` at n cut points (the exact first pose, then the
    warm Newton on Eq. (7) and the assembly check per point)."""
    return EXACT_POSE + n * (NEWTON_EVALS * NEWTON_POSE_EVAL + OBJECTIVE_POINT)


def _newton_stroke(n: int, tol: float) -> float:
    e = NEWTON_EVALS if tol < 1e-3 else NEWTON_EVALS_LOOSE
    return n * (e * NEWTON_POSE_EVAL + LOOP_KNOWNS + 2 * e * NEWTON_DYAD_EVAL)


def _swarm_solves(res: dict, p: dict, pso_tol: float) -> float:
    """Flops of one swarm solve of Eq. (7) and one of Eq. (9) at a cut point."""
    swarm = int(res.get("pso_swarm", p["pso_swarm"]))
    iters = int(res.get("pso_iter", p["pso_max_iter"]))
    it_loops = iters if pso_tol == 0 else min(iters, PSO_LOOPS_ITERS)
    return swarm * ((it_loops + 1) * PSO_LOOPS + (min(iters, PSO_POSE_ITERS) + 1) * PSO_POSE)


def run_flops(run: dict) -> float:
    """Flops of one run of rolling_shear from its record (:func:`floor`)."""
    p, res, opt = run["parameters"], run["resolution"], run.get("options", {})
    n, n_cal = int(res["n_points"]), int(res["calibration_points"])
    tol = float(res.get("newton_tol", p["loops_tol"] * 1e3))
    effects = run.get("effects", [])
    solver = run["solver"]
    flops = (CAL_SCAN * _objective(min(33, n_cal)) + (CAL_BRENT + 1) * _objective(n_cal)
             + EXACT_POSE)                      # calibration, H original, the initial value
    if "levers" in opt and solver != "family_scan":   # buildable check, H of the levers
        flops += n_cal * (EXACT_POSE + EXACT_REST) + _objective(n_cal)
    if solver in ("continuation", "method_comparison"):
        flops += _newton_stroke(n, tol) + n * (EXACT_POSE + EXACT_REST)
        flops += ("tilt_scan" in effects) * TILT_SCAN * _objective(33)
        flops += ("constant_rate_drive" in effects) * n * DRIVE_POINT
    if solver == "method_comparison":
        methods = opt.get("methods", [])
        pso_tol = float(opt.get("pso_tol", p["loops_tol"] * 1e3))
        strokes = max(1, int(opt.get("seeds", 0)))
        swarms = sum(m in ("selpso", "pso_standard") for m in methods)
        flops += swarms * strokes * n * _swarm_solves(res, p, pso_tol)
        flops += (len(methods) - swarms) * n * 2 * SCIPY_SOLVE
        if "initial_values" in effects:
            swarm = int(res.get("pso_swarm", p["pso_swarm"]))
            iters = min(int(res.get("pso_iter", p["pso_max_iter"])), PSO_LOOPS_ITERS)
            flops += EXACT_POSE + len(opt["initial_values"]) * swarm * (iters + 1) * PSO_LOOPS
    elif solver == "lever_optimisation":
        swarm, iters = int(res["opt_swarm"]), int(res["opt_iter"])
        evals = (len(opt.get("optimisers", ["selpso"])) * swarm * (iters + 1) + 1
                 + ("lever_scan" in effects) * 5 * int(res.get("scan_points", 21)))
        flops += evals * _objective(n) + len(opt.get("optimisers", ["selpso"])) * (
            EXACT_POSE + _newton_stroke(n, tol))
    elif solver == "family_scan":
        members = math.prod(len(v) if isinstance(v, list) else 1 for v in opt["grid"].values())
        flops += members * (MEMBER_OBJECTIVES * _objective(min(33, n))
                            + MEMBER_EXACT * n * (EXACT_POSE + EXACT_REST))
    return flops


def floor(profile: str = "default", measure: bool = False) -> None:
    """rolling_shear's solve floor from operation counts: every run of the profile sized
    from its record (its solver, n_points, calibration_points, newton_tol, swarm, iterations,
    pso_tol, seeds, methods, optimisers, scan points, family grid members, effects), its
    flops counted as :func:`run_flops` does, at :data:`_floor.RATE`.  With T = 20 for a
    transcendental and S = 4 for a sqrt or division (:mod:`_floor`), n cut points, n_c
    calibration points:

    - a Newton evaluation of Eq. (7) 6T + 2S + 34 = 162, of a loop of Eq. (9)
      4T + 2S + 20 = 108, 3.2 evaluations per point and system (2.1 at a loose tolerance):
      a Newton stroke ~1.4k flops per cut point;
    - a closed-form pose (:func:`.blade.exact_pose`) ~63k: its 601-point scan of |ED| - l6
      (4T + S + 18 each) is 97 % of it; a closed-form cut point ~64k;
    - the lever objective (:func:`.optimise.objective`) 63k + ~840 n: the exact first pose
      and per point Newton on Eq. (7), the assembly check and H;
    - every run's calibration (4 objectives at min(33, n_c) + 10 at n_c = 129, counted):
      ~2.1 Mflop; with a lever set the buildable check adds n_c closed-form points (8 Mflop);
    - continuation: the Newton stroke, n closed-form points, the tilt scan (37 objectives at
      33 points) and the constant-rate drive (~1.1k per point) when named;
    - method_comparison: the continuation, then per swarm method, seed and cut point a swarm
      on Eq. (7) and one on Eq. (9), swarm x (iterations + 1) x (PSO_POSE 246 or PSO_LOOPS
      301; iterations: pso_iter when pso_tol = 0, else at most 130 on Eq. 7 and 300 on Eq. 9,
      counted); a scipy method 2 x ~11k per cut point; Fig. 12's 6 swarms on Eq. (9);
    - lever_optimisation: swarm x (iterations + 1) objectives per optimiser, 5 x scan points
      for the scan, the optimum's stroke;
    - family_scan: per grid member 22 objectives at n points and 0.6 closed-form strokes
      (counted averages: most members scan every tilt and do not calibrate).

    Left out: the strokes that ``newton_stroke`` and ``time_newton_loops`` repeat only to time
    them (``min_time``: wall-clock bound, not the algorithm; in the measured time), the
    geometry derivation of each lever set or tilt (:func:`.design.design`, ~100 flops), the
    objectives that raise (non-assembling tilts and lever sets: less than one objective
    each), the outputs (motion laws, errors against the closed form), the numpy and Python
    bookkeeping of the comparison methods and the random draws of the cold starts."""
    from mechrepro import limits

    cfg = load_paper(CONFIG, profile)
    rows = [(name, run["solver"], run_flops(run), limits.run_cost("rolling_shear", run)["seconds"])
            for name, run in cfg.runs.items()]
    _floor.report("rolling_shear", profile, rows, "limits.run_cost, per run",
                  cfg.runs if measure else None)


if __name__ == "__main__":
    if sys.argv[1:2] == ["paths"]:
        paths(*(sys.argv[2:3]), *(int(a) for a in sys.argv[3:4]))
    elif sys.argv[1:2] == ["speed"]:
        speed(*(sys.argv[2:4]), *(int(a) for a in sys.argv[4:5]))
    elif sys.argv[1:2] == ["floor"] or "--floor" in sys.argv:
        ap = argparse.ArgumentParser()
        _floor.arguments(ap)
        a = ap.parse_args([v for v in sys.argv[1:] if v != "floor"])
        floor(a.profile, a.measure)
    else:
        like_for_like(*(int(a) for a in sys.argv[1:2]))
        floor()
