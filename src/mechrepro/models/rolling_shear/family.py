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
from .context import Context
from .geometry import cut_points, with_intent
from .design import Unreachable
from .loops import NonAssembly

GRID_KEYS = ("blade_offset", "R", "width", "y_joint", "eq8_reading", "carrier_constants")


def member_geometry(base, member: dict):
    """The uncalibrated linkage of one grid member."""
    return replace(with_intent(base, **{k: float(member[k]) for k in GRID_KEYS[:4]}),
                   eq8=member["eq8_reading"], carrier=member["carrier_constants"])


def calibrated_member(ctx: Context, member: dict, levers: dict) -> tuple[float, ...]:
    """(tilt, H of the lever set, buildable, rod gap mm, joint height mm, min and max crank-rod
    angle deg, blade rise mm, open transmission angle deg, buildable with the lever set) of one
    member; NaN where it cannot reach the target (H NaN: the levers do not assemble)."""
    from . import stroke
    from .constraints import broken, margins, settings

    try:
        gc, info = calibrate_tilt(member_geometry(ctx.g_uncalibrated, member),
                                  ctx.calibration_target, ctx.n, ctx.tol_floor,
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
    out = {"family_member_tilt": var("member", rows[:, 0], "rad",
                                     "calibrated guide-rod tilt (NaN: the member cannot reach the target)"),
           "family_member_H_levers": var("member", rows[:, 1], "mm",
                                         "synthetic horizontal displacement of the scene's levers"),
           "family_member_reduction": var("member", 100.0 * (rows[:, 1] / target - 1.0), "%",
                                          "reduction of the scene's levers against the calibrated original"),
           "family_member_assembles": var("member", np.where(cal, np.isfinite(rows[:, 1]), np.nan), "1",
                                          "1: the scene's levers assemble on the design branch inside the "
                                          "paper's ranges over the stroke (NaN: not calibrated)"),
           "family_member_buildable": var("member", rows[:, 2], "1",
                                          "1: the calibrated member meets the constraints of constraints.py "
                                          "at the run's settings and guide_rod_plane reading (NaN: not "
                                          "calibrated)"),
           "family_member_rod_gap": var("member", rows[:, 3], "mm",
                                        "how far the guide rod ED (E, D over the stroke) stays beside the "
                                        "plate (negative: over its span), constraints.margins"),
           "family_member_joint_height": var("member", rows[:, 4], "mm",
                                             "lowest y of the rod joints C, I over the stroke"),
           "family_member_mu_min": var("member", rows[:, 5], "deg",
                                       "smallest crank-rod angle of both dyads over the stroke"),
           "family_member_mu_max": var("member", rows[:, 6], "deg",
                                       "largest crank-rod angle of both dyads over the stroke"),
           "family_member_rise": var("member", rows[:, 7], "mm", "blade end's rise over the plate"),
           "family_member_open_mu": var("member", rows[:, 8], "deg",
                                        "worst transmission angle at the open position (NaN: not reached)"),
           "family_member_levers_buildable": var("member", rows[:, 9], "1",
                                                 "1: the machine with the scene's levers meets the constraints "
                                                 "too (NaN: not calibrated, or the levers do not assemble)")}
    for k in GRID_KEYS:
        vals = [m[k] for m in members]
        if isinstance(vals[0], str):
            out[f"family_member_{k}"] = var("member", np.array(vals, dtype=object).astype(str), "1", k)
        else:
            out[f"family_member_{k}"] = var("member", np.asarray(vals, float), "mm", k)
    return out
