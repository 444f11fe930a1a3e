"""Solver ``lever_optimisation`` (Sec. 3.3 step 3, Table II, Fig. 11): l1, l3, l5, l6, l10
against H within +- ``lever_bound_fraction``, by each of ``options.optimisers``."""
from __future__ import annotations

from dataclasses import replace

from mechrepro.units import var

from . import optimise, stroke
from .run_context import Context
from .geometry import OPTIMISED_LEVERS, cut_points
from .motion_laws import stroke_outputs
from .selpso import SelPSOSettings


def lever_bounds(ctx: Context) -> list[tuple[float, float]]:
    f = float(ctx.p["lever_bound_fraction"])
    return [((1 - f) * v, (1 + f) * v) for v in ctx.g.levers()]


def by_selpso(ctx: Context) -> optimise.OptimisationResult:
    st = SelPSOSettings(swarm=int(ctx.res["opt_swarm"]), max_iter=int(ctx.res["opt_iter"]),
                        w_start=ctx.p["pso_w_start"], w_end=ctx.p["pso_w_end"],
                        c1=ctx.p["pso_c1"], c2=ctx.p["pso_c2"], tol=0.0)
    return optimise.optimise_selpso(ctx.g, ctx.x_k, lever_bounds(ctx), st, ctx.rng(5),
                                    ctx.settings.tol_pose)


def by_differential_evolution(ctx: Context) -> optimise.OptimisationResult:
    swarm, iters = int(ctx.res["opt_swarm"]), int(ctx.res["opt_iter"])
    return optimise.optimise_de(ctx.g, ctx.x_k, lever_bounds(ctx), swarm * (iters + 1), swarm,
                                int(ctx.rng(6).integers(2**31)), ctx.settings.tol_pose)


#: optimiser -> (function, prefix of its outputs)
OPTIMISERS = {"selpso": (by_selpso, "opt_selpso"), "de": (by_differential_evolution, "opt_de")}


def optimised_outputs(ctx: Context, res: optimise.OptimisationResult, prefix: str) -> dict:
    """The optimum, its history and, if it assembles, the stroke of its levers."""
    out = {
        f"{prefix}_levers": var("lever", res.levers, "mm", f"optimised l1, l3, l5, l6, l10, {prefix}"),
        f"{prefix}_objective": var((), res.objective, "mm",
                                   f"optimised synthetic horizontal displacement, {prefix}"),
    }
    if res.objective < optimise.PENALTY:
        g = ctx.g.with_levers(**dict(zip(OPTIMISED_LEVERS, map(float, res.levers))))
        x_k = cut_points(g, ctx.n)[1]  # the cut moves with re-derived carrier constants
        # far lever sets move the cranks by more than the rough initial value absorbs: the
        # continuation starts from the closed-form pose at the first cut point
        first = tuple(stroke.exact_theta(g, x_k[:1])[0])
        sol = stroke.solve_newton(g, x_k, replace(ctx.settings, initial_value=first))
        out.update(stroke_outputs(g, sol.theta, prefix, f"levers optimised by {prefix}"))
    return out


def solve_lever_optimisation(run: dict, ctx: Context) -> dict:
    data = {"opt_original_objective": var(
        (), optimise.objective(ctx.g, ctx.x_k, ctx.settings.tol_pose), "mm",
        "synthetic horizontal displacement of the original levers, same cut points")}
    for name in ctx.options.get("optimisers", ["selpso"]):  # the paper's by default
        fn, prefix = OPTIMISERS[name]
        data.update(optimised_outputs(ctx, fn(ctx), prefix))
    return data
