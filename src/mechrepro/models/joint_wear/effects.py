"""The effects of joint_wear: pure functions of the solver's context, declared in
``config/papers/joint_wear.yaml`` (``effects:``) and read by the solvers by key.

Three kinds, evaluated in this order by the solvers (solver.py):

mechanism terms (the bare mechanism of ``geometry.from_parameters`` has none of them)
  ``gravity``          ``gravity``          in-plane gravity g [m/s2]
  ``friction``         ``friction_coefficient``  mu of Eq. (15)
  ``contact_damping``  ``damping_ceiling``  C_max of Eq. (14) [N s/m] (dynamic joint only)
wear set-up
  ``unbalanced_load``  ``sides``            the bushing sides calibrated and predicted
  ``wear_update``      ``worn_bushing``     the bushing circle R(R0, h) between intervals
wear
  ``archard_wear``     ``wear``             calibration (Eqs. 32-34) + interval prediction

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
    """What the effects read: the run's SI parameters and settings, the bare mechanism,
    and (for the wear effects) the solver's joint model over one period."""
    p: dict
    s: dict
    fb: FourBar
    one_period: Callable[[FourBar], dict] | None = None
    sides: list = field(default_factory=lambda: ["B1"])
    worn_bushing: Callable[[float, float], float] | None = None
    #: G(R_bush) in place of the joint model's wear factor (a rival without mechanics:
    #: solver.closed_form_factor); None: one period of ``one_period`` per radius
    wear_factor: Callable[[float], float] | None = None


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
    fb, p, s = ctx.fb, ctx.p, ctx.s
    R0 = fb.R_bush
    wear_range = s.get("wear_range", "contact_point")

    def factor(R_bush):
        if ctx.wear_factor is not None:
            return ctx.wear_factor(R_bush)
        fb_w = fb.with_bushing_radius(R_bush)
        return wear.period_wear_factor(ctx.one_period(fb_w), fb_w, fb.period, wear_range,
                                       statistics=False)["G"]

    cal_h = float(p["measurement_interval"]) / 3600.0
    out = {"sides": [], "k": [], "k_mean": [], "G_cal": [], "nodes": [], "h": [], "G_pred": []}
    with phase("joint_wear.archard_wear") as sw:
        for side in ctx.sides:
            h_meas = np.asarray(p[f"measured_wear_{side}"], float)
            k, k_mean, G = wear.calibrate(h_meas, cal_h, fb.period, R0, factor,
                                          dh_measured=p[f"measured_increment_{side}"],
                                          feedback=float(p["calibration_wear_feedback"]))
            t_start = cal_h * h_meas.size
            nodes, h, Gp = wear.predict(h_meas[-1], t_start, float(p["prediction_end"]) / 3600.0,
                                        float(s["interval_h"]), k_mean, fb.period, R0, factor,
                                        worn_bushing=ctx.worn_bushing)
            for key, val in (("sides", side), ("k", k), ("k_mean", k_mean), ("G_cal", G),
                             ("nodes", nodes), ("h", h), ("G_pred", Gp)):
                out[key].append(val)

    out["wall_time_prediction"] = sw.seconds
    if s.get("interval_limit") and ctx.worn_bushing is not None:     # not timed: a reference
        out["limit"] = [wear.interval_limit(h[0], n[0], n[-1], km, fb.period, R0, factor,
                                            ctx.worn_bushing)
                        for h, n, km in zip(out["h"], out["nodes"], out["k_mean"])]
    out["cal_hours"] = cal_h * (1 + np.arange(len(out["k"][0])))
    return {"wear": out}
