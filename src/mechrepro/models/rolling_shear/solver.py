"""rolling_shear's solvers (continuation, method_comparison, lever_optimisation, family_scan,
design_front), each followed by the scene's named effects and outputs; the run's variables."""
from __future__ import annotations

import math

import numpy as np

from mechrepro.units import var

from .run_context import Context, Refused
from .design import Unreachable
from .loops import NonAssembly
from .continuation import solve_continuation, solve_method_comparison
from .effects import EFFECTS
from .family import solve_family_scan
from .geometry import GEOMETRY_KEYS, OPTIMISED_LEVERS
from .motion_laws import ANGLE_NAMES
from .front import solve_design_front
from .lever_optimisation import solve_lever_optimisation

def geometry_outputs(ctx: Context) -> dict:
    """The constants of the run's geometry (after calibration and the scene's lever set)
    and its calibration (mm, rad)."""
    g = ctx.g
    out = {f"geometry_{k}": var((), getattr(g, k), "rad" if k in ("alpha", "beta1", "beta2") else "mm",
                                f"constant {k} of the run's geometry")
           for k in GEOMETRY_KEYS}
    out["geometry_tilt"] = var((), dict(ctx.g_original.intents)["theta6_mid"] - math.pi, "rad",
                               "guide-rod tilt at mid-cut, theta6_mid - pi (calibrated if the run calibrates)")
    if ctx.calibration is not None:
        n = ctx.calibration["n"]
        out["calibrated_H_original"] = var(
            (), ctx.calibration["H_original"], "mm",
            f"synthetic horizontal displacement of the original levers after calibration, {n} cut points")
        if "H_levers" in ctx.calibration:
            out["calibrated_H_levers"] = var(
                (), ctx.calibration["H_levers"], "mm",
                f"synthetic horizontal displacement of the scene's levers, {n} cut points")
    return out


def variables(result: dict, run: dict) -> dict:
    """The run's variables: the solver's outputs and their coordinates (a refused lever set's:
    :func:`refusal_variables`)."""
    if "refused" in result:
        return refusal_variables(result["refused"])
    ctx: Context = result["ctx"]
    data = result["data"]
    coords = {
        "cut": var("cut", np.arange(ctx.n), "1", "cut point index"),
        "huch": var("cut", ctx.huch, "mm", "rolled length from the start of the cut"),
        "x_k_target": var("cut", ctx.x_k, "mm", "prescribed x of the lowest point on y = -s"),
        "angle": var("angle", list(ANGLE_NAMES), "1", "unknown angle"),
        "lever": var("lever", list(OPTIMISED_LEVERS), "1", "optimised lever"),
    }
    used = {d for dims, *_ in data.values() for d in dims}
    out = {k: v for k, v in coords.items() if v[0][0] in used or k in ("cut", "huch", "x_k_target")}
    out |= {d: var(d, np.arange(np.shape(v[1])[v[0].index(d)]), "1", f"{d} index")
            for v in data.values() for d in v[0] if d not in out}
    return out | data | {"length_unit": "mm"}


def refusing(run: dict, fn, *args):
    """``fn(*args)``, or the :class:`Refused` it raises: a lever set refused by name, or one of
    the scene's that does not assemble, is a result (:func:`refusal_variables`), not a crash."""
    try:
        return fn(*args)
    except Refused as exc:
        return exc
    except (NonAssembly, Unreachable) as exc:
        if "levers" not in run.get("options", {}):
            raise
        return Refused("assembly", f"lever set {dict(run['options']['levers'])}: {exc}")


def context(run: dict) -> Context | Refused:
    """The run's :class:`Context`, or why its lever set is refused."""
    return refusing(run, Context, run)


def with_effects(solver):
    """``solver(run, ctx)`` followed by the effects and outputs the scene names (they read what
    it leaves in the context) and the geometry's constants; a refused lever set gives
    ``{"refused": ...}``."""
    def solve(run: dict, ctx: Context | Refused) -> dict:
        data = ctx if isinstance(ctx, Refused) else refusing(run, solver, run, ctx)
        if isinstance(data, Refused):
            return {"refused": data}
        c = EFFECTS.evaluate(run, ctx)
        return {"ctx": ctx, "data": data | {key: c.get(key) for key in c.keys()}
                | geometry_outputs(ctx)}
    return solve


SOLVERS = {name: with_effects(solver) for name, solver in (
    ("continuation", solve_continuation), ("method_comparison", solve_method_comparison),
    ("lever_optimisation", solve_lever_optimisation), ("family_scan", solve_family_scan),
    ("design_front", solve_design_front))}


def refusal_variables(exc: Refused) -> dict:
    """The variables of a refused lever set: what was refused and why, no stroke."""
    return {
        "levers_assemble": var((), 0.0 if exc.kind == "assembly" else np.nan, "1",
                               "1: the lever set assembles over the stroke; 0: refused; NaN: "
                               "the member was refused before (not calibrated, not buildable)"),
        "length_unit": "mm", "refusal_kind": exc.kind, "refusal": exc.message}


__all__ = ["EFFECTS", "SOLVERS", "context", "variables"]
