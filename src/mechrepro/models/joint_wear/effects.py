"""The effects of joint_wear: pure functions of the solver's context, declared (with what
each contributes) under ``effects:`` in ``config/papers/joint_wear.yaml`` and read by the
solvers by key, in three stages: mechanism terms, wear set-up, wear (solver.py).

An effect that a scene does not name is never called; the solver then uses the term's
neutral value (0, no second side, a frozen bushing, no wear prediction).
"""
from __future__ import annotations

from dataclasses import dataclass

from mechrepro.effects import EffectRegistry

from . import wear
from .geometry import FourBar

EFFECTS = EffectRegistry("joint_wear")


@dataclass
class Context:
    """What the effects read: the run's SI parameters and settings and the mechanism."""
    p: dict
    s: dict
    fb: FourBar


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
    """Archard wear of the bushing (Eqs. 16-31): for one side, k calibrated on its first
    10 h (Eqs. 32-34), then the wear predicted to t_end by the interval method (Sec. 3.3,
    4.4), as a function of the wear factor G(R_bush) of the solver's joint model, which
    the solver applies to each side (solver.with_wear)."""
    p, interval_h = ctx.p, float(ctx.s["interval_h"])

    def side_wear(side: str, period: float, R0: float, factor, worn_bushing) -> dict:
        k, k_mean, G = wear.calibrate_side(p, side, period, R0, factor)
        nodes, h, Gp = wear.predict_side(p, side, interval_h, k_mean, period, R0, factor,
                                         worn_bushing)
        return {"sides": side, "k": k, "k_mean": k_mean, "G_cal": G, "nodes": nodes, "h": h,
                "G_pred": Gp}
    return {"wear": side_wear}
