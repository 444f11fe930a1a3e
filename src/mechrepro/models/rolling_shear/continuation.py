"""Solver ``continuation`` (Sec. 3.3 steps 1-2, Figs. 9-11, 13, 14): the stroke by
warm-started Newton (Eq. 7 then Eq. 9 at every cut point), against the closed form.  Solver
``method_comparison`` (Sec. 4, Fig. 12): the same, then every cut point by each method of
``options.methods``; each method has its own random stream, so adding one changes no other's
numbers."""
from __future__ import annotations

import numpy as np

from mechrepro.timing import time_call
from mechrepro.units import var

from . import stroke
from .run_context import Context
from .motion_laws import driving_laws_on_grid, pose_error, stroke_outputs


def newton_stroke(ctx: Context) -> tuple[stroke.StrokeSolution, dict]:
    """The warm-started Newton stroke and its outputs; raises NonAssembly.  Timed as the fastest
    of repeated strokes (one is too short to time alone)."""
    sol = stroke.solve_newton(ctx.g, ctx.x_k, ctx.settings)  # also warms the caches
    _, wall = time_call(stroke.solve_newton, ctx.g, ctx.x_k, ctx.settings, min_time=0.02)
    out = stroke_outputs(ctx.g, sol.theta, "newton", "warm-started Newton")
    out.update(driving_laws_on_grid(ctx.huch, sol.theta, ctx.g.width, "newton",
                                    "warm-started Newton"))
    out.update({
        "newton_fitness_loops": var("cut", sol.fitness_loops, "mm", "G of Eq. (9), Newton"),
        "newton_stroke_time": var((), wall, "s", "Newton wall time of the whole stroke"),
        "newton_time_per_loops_solve": var(
            (), stroke.time_newton_loops(ctx.g, sol.theta, ctx.settings), "s",
            "Newton wall time per Eq. (9) solve (continuation, poses given)"),
        "newton_success_rate": var((), sol.converged.mean(), "1", "Newton converged fraction"),
        "newton_right_branch_rate": var((), sol.right.mean(), "1",
                                        "Newton fraction on the design branch"),
        "newton_in_ranges_rate": var((), sol.in_ranges.mean(), "1",
                                     "Newton fraction inside the paper's ranges"),
    })
    return sol, out


def solve_continuation(run: dict, ctx: Context) -> dict:
    """Newton and closed-form (the reference) strokes; the named effects and outputs read
    ``ctx.stroke``.  A stroke that does not assemble raises NonAssembly (a scene lever set's
    is refused by :func:`.solver.refusing`)."""
    ctx.stroke, data = newton_stroke(ctx)
    data["levers_assemble"] = var((), 1.0, "1", "1: the lever set assembles over the stroke")
    ctx.reference = stroke.exact_theta(ctx.g, ctx.x_k)
    return data | stroke_outputs(ctx.g, ctx.reference, "exact", "closed-form reference")


#: the comparison methods and the salt of their random stream
METHOD_STREAMS = {"selpso": 1, "cold_root": 2, "least_squares": 3, "warm_root": 7,
                  "warm_least_squares": 8, "pso_standard": 9}


def compare(ctx: Context, method: str) -> dict:
    """One method at every cut point, recorded (never raising)."""
    sol = stroke.solve_compare(ctx.g, ctx.x_k, method, ctx.settings,
                               ctx.rng(METHOD_STREAMS[method]))
    err = pose_error(sol.theta, ctx.reference)
    w = method
    out = {
        f"{w}_theta": var(("cut", "angle"), sol.theta, "rad", f"theta1..theta6, {w}"),
        f"{w}_fitness_loops": var("cut", sol.fitness_loops, "mm", f"G of Eq. (9), {w}"),
        f"{w}_converged": var("cut", sol.converged.astype(np.int8), "1",
                              f"both systems below tolerance, {w}"),
        f"{w}_in_ranges": var("cut", sol.in_ranges.astype(np.int8), "1",
                              f"angles inside the paper's ranges, {w}"),
        f"{w}_design_branch": var("cut", sol.design_branch.astype(np.int8), "1",
                                  f"on the design assembly branch, {w}"),
        f"{w}_error": var(("cut", "angle"), err, "rad", f"|theta - exact|, {w}"),
        f"{w}_success_rate": var((), sol.converged.mean(), "1", f"converged fraction, {w}"),
        f"{w}_in_ranges_rate": var((), sol.in_ranges.mean(), "1",
                                   f"fraction inside the paper's ranges, {w}"),
        f"{w}_right_branch_rate": var((), sol.right.mean(), "1",
                                      f"converged and on the design branch, {w}"),
        f"{w}_time_per_solve": var((), sol.time_loops, "s", f"wall time per Eq. (9) solve, {w}"),
        f"{w}_time_per_pose_solve": var((), sol.time_pose, "s",
                                        f"wall time per Eq. (7) solve, {w}"),
    }
    if method == "selpso":
        st = ctx.settings.pso_loops
        out["swarm_x_iter"] = var((), st.swarm * st.max_iter, "1",
                                  "selPSO budget: particles x iterations on each system")
    if method in ("selpso", "pso_standard") and int(ctx.options.get("seeds", 0)) > 0:
        out.update(_over_seeds(ctx, method, sol))
    return out


def _over_seeds(ctx: Context, method: str, sol: stroke.StrokeSolution) -> dict:
    """A stochastic method over ``options.seeds`` strokes: pose-error quantiles, the probability
    of a whole stroke on the design branch, the branch rate per seed and the mean stroke time
    (seed 0: the run's stream; seed k: the stream (run seed, salt, k))."""
    sols = [sol] + [stroke.solve_compare(ctx.g, ctx.x_k, method, ctx.settings,
                                         np.random.default_rng([ctx.seed, METHOD_STREAMS[method], k]))
                    for k in range(1, int(ctx.options["seeds"]))]
    errs = np.array([float(np.max(pose_error(s.theta, ctx.reference))) for s in sols])
    ok, rates = [bool(s.right.all()) for s in sols], [float(s.right.mean()) for s in sols]
    times = [ctx.n * (s.time_pose + s.time_loops) for s in sols]
    w = method
    return {
        f"{w}_pose_error_seeds": var("seed", errs, "rad",
                                     f"max |theta - closed form| over the cut, per seed, {w}"),
        f"{w}_pose_error_q50": var((), np.quantile(errs, 0.5), "rad",
                                   f"median over seeds of the stroke's max pose error, {w}"),
        f"{w}_pose_error_q90": var((), np.quantile(errs, 0.9), "rad",
                                   f"90 % quantile over seeds of the stroke's max pose error, {w}"),
        f"{w}_stroke_failure_probability": var(
            (), 1.0 - float(np.mean(ok)), "1",
            f"fraction of seeds whose stroke leaves the design branch or does not converge, {w}"),
        f"{w}_branch_rate_seeds": var("seed", np.asarray(rates), "1",
                                      f"fraction of the cut points converged on the design branch, per seed, {w}"),
        f"{w}_stroke_time_seeds": var((), float(np.mean(times)), "s",
                                      f"mean wall time of the whole stroke over seeds, {w}"),
    }


def solve_method_comparison(run: dict, ctx: Context) -> dict:
    """The continuation (with its reference), then every listed method."""
    data = solve_continuation(run, ctx)
    for method in ctx.options.get("methods", []):
        data.update(compare(ctx, method))
    return data
