"""The effects of joint_wear: pure functions of the solver's context, declared (with what
each contributes) under ``effects:`` in ``config/papers/joint_wear.yaml`` and read by the
solvers by key, in three stages: mechanism terms, wear set-up, wear (solver.py).

An effect that a scene does not name is never called; the solver then uses the term's
neutral value (0, no second side, a frozen bushing, no wear prediction).
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from mechrepro.effects import EffectRegistry
from mechrepro.timing import phase

from . import wear
from .geometry import FourBar

EFFECTS = EffectRegistry("joint_wear")


@dataclass
class Context:
    """What the effects read: the run's SI parameters and settings, the mechanism, and (for
    the wear effects) G(R_bush), the wear factor of one period of the solver's joint model
    with the bushing at radius R_bush (solver.period_factor, or a rival's closed form)."""
    p: dict
    s: dict
    fb: FourBar
    wear_factor: Callable[[float], float] | None = None
    sides: list = field(default_factory=lambda: ["B1"])
    worn_bushing: Callable[[float, float], float] | None = None


# --- mechanism terms ----------------------------------------------------------------------
@EFFECTS.register("gravity")
def gravity(ctx: Context) -> dict:
    """Link weights in -y: the plane of motion taken vertical (assumed, see the config)."""
    return {"gravity": float(ctx.p["gravity"])}


@EFFECTS.register("friction")
def friction(ctx: Context) -> dict:
    """Regularised Coulomb friction of Eq. (15): the coefficient mu."""
    return {"friction_coefficient": float(ctx.p["friction_coefficient"])}


@EFFECTS.register("contact_damping")
def contact_damping(ctx: Context) -> dict:
    """Hysteresis damping K'' of Eq. (14): its ceiling C_max, a fraction of K' (Sec. 2.2.2)."""
    return {"damping_ceiling": float(ctx.p["C_max_ratio"]) * ctx.fb.K_contact}


# --- wear set-up ---------------------------------------------------------------------------
@EFFECTS.register("unbalanced_load")
def unbalanced_load(ctx: Context) -> dict:
    """The out-of-plane load wears the two sides B1 and B2 of the bushing differently
    (Fig. 8b, Sec. 4.3): each is calibrated on its own measurements (Tables 3 and 4)."""
    return {"sides": ["B1", "B2"]}


@EFFECTS.register("wear_update")
def wear_update(ctx: Context) -> dict:
    """The bushing circle grows with the predicted wear between intervals (Sec. 4.4,
    step 4): diameter D0 + h."""
    return {"worn_bushing": wear.bushing_radius}


# --- wear -----------------------------------------------------------------------------------
@EFFECTS.register("archard_wear")
def archard_wear(ctx: Context) -> dict:
    """Archard wear of the bushing (Eqs. 16-31): k calibrated on the first 10 h of each
    side (Eqs. 32-34), then predicted to t_end by the interval method (Sec. 3.3, 4.4),
    one period of the solver's joint model per interval."""
    fb, p, s, factor = ctx.fb, ctx.p, ctx.s, ctx.wear_factor
    out = {"sides": [], "k": [], "k_mean": [], "G_cal": [], "nodes": [], "h": [], "G_pred": []}
    with phase("joint_wear.archard_wear") as sw:
        for side in ctx.sides:
            k, k_mean, G = wear.calibrate_side(p, side, fb.period, fb.R_bush, factor)
            nodes, h, Gp = wear.predict_side(p, side, float(s["interval_h"]), k_mean, fb.period,
                                             fb.R_bush, factor, ctx.worn_bushing)
            for key, val in zip(out, (side, k, k_mean, G, nodes, h, Gp)):
                out[key].append(val)
    out["wall_time_prediction"] = sw.seconds
    if s.get("interval_limit") and ctx.worn_bushing is not None:     # not timed: a reference
        out["limit"] = [wear.interval_limit(h[0], n[0], n[-1], km, fb.period, fb.R_bush, factor,
                                            ctx.worn_bushing)
                        for h, n, km in zip(out["h"], out["nodes"], out["k_mean"])]
    out["cal_hours"] = wear.calibration_hours(p) * (1 + np.arange(len(out["k"][0])))
    return {"wear": out}
