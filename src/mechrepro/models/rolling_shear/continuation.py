"""Solver ``continuation`` (Sec. 3.3 steps 1-2, Figs. 9-11, 13, 14): the stroke by
warm-started Newton (Eq. 7 then Eq. 9 at every cut point), against the closed form."""
from __future__ import annotations

from mechrepro.timing import time_call
from mechrepro.units import var

from . import stroke
from .context import Context, Refused
from .loops import NonAssembly
from .effects import EFFECTS
from .motion_laws import driving_laws_on_grid, stroke_outputs


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
        "newton_fitness_pose": var("cut", sol.fitness_pose, "mm", "G of Eq. (7), Newton"),
        "newton_iterations": var("cut", sol.iterations_loops.astype(float), "1",
                                 "Newton iterations on Eq. (9)"),
        "newton_time_per_solve": var((), wall / (2 * ctx.n), "s",
                                     "Newton wall time per system solve (fastest stroke / 2n)"),
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


def exact_stroke(ctx: Context) -> tuple[stroke.StrokeSolution, dict]:
    """The closed-form reference stroke and its outputs."""
    sol = stroke.solve_exact(ctx.g, ctx.x_k)
    out = stroke_outputs(ctx.g, sol.theta, "exact", "closed-form reference")
    out["exact_fitness_loops"] = var("cut", sol.fitness_loops, "mm", "G of Eq. (9), exact")
    out["exact_fitness_pose"] = var("cut", sol.fitness_pose, "mm", "G of Eq. (7), exact")
    return sol, out


def solve_continuation(run: dict, ctx: Context) -> dict:
    """Newton and closed-form strokes, then the named effects (they read ``ctx.stroke``); a scene
    lever set that does not assemble is refused by name."""
    try:
        ctx.stroke, data = newton_stroke(ctx)
    except NonAssembly as exc:
        if "levers" not in ctx.options:
            raise
        raise Refused("assembly", f"lever set {dict(ctx.options['levers'])}: {exc}") from None
    data["levers_assemble"] = var((), 1.0, "1", "1: the lever set assembles over the stroke")
    ctx.reference, exact = exact_stroke(ctx)
    data.update(exact)
    data.update(contributions(run, ctx))
    return data


def contributions(run: dict, ctx: Context) -> dict:
    """Every contribution of the named effects, by key."""
    c = EFFECTS.evaluate(run, ctx)
    return {key: c.get(key) for key in c.keys()}

