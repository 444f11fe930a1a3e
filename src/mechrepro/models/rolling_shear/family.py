"""Solver ``family_scan``: every member of a grid of the design intents and readings
(docs/rolling_shear.md) calibrated on 1.4341 and given the scene's lever set (Table II), so
that a verdict flipped only by a combination of range ends shows."""
from __future__ import annotations

import itertools
import math
from dataclasses import replace

import numpy as np

from mechrepro.units import var

from . import optimise
from .calibrate import CalibrationError, calibrate_tilt
from .run_context import Context
from .geometry import GRID_KEYS, cut_points, with_intent
from .design import Unreachable
from .loops import NonAssembly

#: what :func:`calibrated_member` returns, in order: variable family_member_<name>, unit, long name
COLUMNS = (
    ("tilt", "rad", "calibrated guide-rod tilt (NaN: the member cannot reach the target)"),
    ("H_levers", "mm", "synthetic horizontal displacement of the scene's levers"),
    ("buildable", "1", "1: the calibrated member meets the constraints of constraints.py at the run's "
                       "settings and guide_rod_plane reading (NaN: not calibrated)"),
    ("rod_gap", "mm", "how far the guide rod ED (E, D over the stroke) stays beside the plate "
                      "(negative: over its span), constraints.margins"),
    ("joint_height", "mm", "lowest y of the rod joints C, I over the stroke"),
    ("mu_min", "deg", "smallest crank-rod angle of both dyads over the stroke"),
    ("mu_max", "deg", "largest crank-rod angle of both dyads over the stroke"),
    ("rise", "mm", "blade end's rise over the plate"),
    ("open_mu", "deg", "worst transmission angle at the open position (NaN: not reached)"),
    ("levers_buildable", "1", "1: the machine with the scene's levers meets the constraints too "
                              "(NaN: not calibrated, or the levers do not assemble)"))


def calibrated_member(ctx: Context, member: dict, levers: dict) -> tuple[float, ...]:
    """The values of :data:`COLUMNS` for one member; NaN where it cannot reach the target (H NaN:
    the levers do not assemble)."""
    from . import stroke
    from .constraints import broken, margins, settings

    try:
        g = replace(with_intent(ctx.g_uncalibrated, **{k: float(member[k]) for k in GRID_KEYS[:4]}),
                    eq8=member["eq8_reading"], carrier=member["carrier_constants"])
        gc, info = calibrate_tilt(g, ctx.calibration_target, ctx.n, ctx.tol_floor,
                                  whole_scan=False)  # only the tilt is kept
    except (CalibrationError, NonAssembly, Unreachable):
        return (math.nan,) * 10
    s = settings(ctx.p)
    m = margins(gc, stroke.exact_theta(gc, cut_points(gc, ctx.n)[1]), opening=s["opening"])
    ok = not broken(m, **dict(s, mu_min=math.degrees(s["mu_min"])))
    try:
        gp = gc.with_levers(**levers)
        H = optimise.objective(gp, cut_points(gp, ctx.n)[1], ctx.tol_floor)
        # the machine with the scene's levers, judged by the same constraints
        mp = margins(gp, stroke.exact_theta(gp, cut_points(gp, ctx.n)[1]), opening=s["opening"])
        ok_levers = float(not broken(mp, **dict(s, mu_min=math.degrees(s["mu_min"]))))
    except (NonAssembly, Unreachable):
        H = ok_levers = math.nan
    mu = np.array(list(m["mu"].values()))
    return (info["tilt"], H, float(ok), m["rod_gap"], m["joint_height"], float(mu[:, 0].min()),
            float(mu[:, 1].max()), m["rise"], m["open_mu"], ok_levers)


def solve_family_scan(run: dict, ctx: Context) -> dict:
    grid = ctx.options["grid"]
    levers = {k: float(v) for k, v in ctx.options["levers"].items()}
    members = [dict(zip(GRID_KEYS, combo))
               for combo in itertools.product(*(grid[k] for k in GRID_KEYS))]
    rows = np.asarray([calibrated_member(ctx, m, levers) for m in members])
    target = ctx.calibration_target
    cal = np.isfinite(rows[:, 0])
    out = {f"family_member_{k}": var("member", rows[:, i], u, d) for i, (k, u, d) in enumerate(COLUMNS)}
    out["family_member_reduction"] = var("member", 100.0 * (rows[:, 1] / target - 1.0), "%",
                                         "reduction of the scene's levers against the calibrated original")
    out["family_member_assembles"] = var("member", np.where(cal, np.isfinite(rows[:, 1]), np.nan), "1",
                                         "1: the scene's levers assemble on the design branch inside the "
                                         "paper's ranges over the stroke (NaN: not calibrated)")
    for k in GRID_KEYS:
        vals = [m[k] for m in members]
        if isinstance(vals[0], str):
            out[f"family_member_{k}"] = var("member", np.array(vals, dtype=object).astype(str), "1", k)
        else:
            out[f"family_member_{k}"] = var("member", np.asarray(vals, float), "mm", k)
    return out
