"""Compose the joint_wear effects a scene names into one xarray Dataset.

Effects
-------
joint model (exactly one):
  ``clearance_contact``   dynamic clearance joint, stiff contact, implicit integrator
  ``continuous_contact``  quasi-static continuous contact (the paper's low-speed model)
force terms: ``friction`` (Eq. 15), ``contact_damping`` (Eq. 14), ``gravity``
wear: ``archard_wear`` (calibration Eqs. 32-34 + interval prediction, Sec. 3.3/4.4),
  ``unbalanced_load`` (sides B1 and B2 each with their own coefficient, Sec. 4.3),
  ``wear_update`` (the bushing grows between intervals, Sec. 4.4 step 4)
"""
from __future__ import annotations

import math
import time
from dataclasses import replace

import numpy as np
import xarray as xr

from mechrepro.effects import EffectRegistry

from . import dynamics, quasistatic, wear
from .geometry import FourBar, from_parameters

EFFECTS = EffectRegistry("joint_wear")
JOINT_MODELS = ("clearance_contact", "continuous_contact")


# --- force-term effects: they switch a term of the mechanism on -------------------------
@EFFECTS.register("gravity")
def gravity(fb: FourBar, p: dict, s: dict) -> FourBar:
    """Link weights in -y (plane of motion vertical, assumed)."""
    return replace(fb, g=p["gravity"])


@EFFECTS.register("friction")
def friction(fb: FourBar, p: dict, s: dict) -> FourBar:
    """Regularised Coulomb friction of Eq. (15)."""
    return replace(fb, mu=p["friction_coefficient"])


@EFFECTS.register("contact_damping")
def contact_damping(fb: FourBar, p: dict, s: dict) -> FourBar:
    """Hysteresis damping K'' of Eq. (14) in the dynamic contact law."""
    s["damping"] = True
    return fb


# --- joint models: one period of contact history ----------------------------------------
@EFFECTS.register("continuous_contact")
def continuous_contact(fb: FourBar, s: dict) -> dict:
    """Quasi-static continuous contact over one period (n_steps uniform samples)."""
    return quasistatic.one_period(fb, int(s["n_steps"]))


@EFFECTS.register("clearance_contact")
def clearance_contact(fb: FourBar, s: dict) -> dict:
    """Dynamic clearance joint; the last of ``periods`` periods is returned as one period."""
    periods = int(s.get("periods", 1))
    n_out = int(s["n_out"])
    T = fb.period
    r = dynamics.simulate(fb, periods * T, periods * n_out + 1, method=s["method"],
                          rtol=float(s["rtol"]), damping=s.get("damping", False),
                          start=s.get("start", "equilibrium"), max_wall_s=s.get("max_wall_s"))
    if r["status"] == -1:
        raise RuntimeError(f"joint_wear: {s['method']} failed at t = {r['t_reached']:.4g} s: "
                           f"{r['message']}")
    completed = r["status"] == 0
    # a finished run: its last period on the uniform periodic grid; an unfinished one
    # (wall-time budget spent): what it reached, flagged
    sl = slice(-(n_out + 1), -1) if completed else slice(None)
    out = {k: np.asarray(v)[sl] for k, v in r.items()
           if isinstance(v, np.ndarray) and v.ndim == 1 and v.size == r["t"].size}
    out["t"] = out["t"] - (periods - 1) * T
    out.update(nfev=r["nfev"], full=r, completed=completed, t_reached=r["t_reached"],
               integration_wall=r["wall"], message=r["message"])
    return out


# --- wear effects --------------------------------------------------------------------------
@EFFECTS.register("archard_wear")
def archard_wear(fb: FourBar, s: dict, p: dict, one_period, sides, update: bool) -> dict:
    """Calibrate k on the first 10 h of each side, then predict to t_end (Sec. 4.3-4.4)."""
    R0 = fb.R_bush
    wear_range = s.get("wear_range", "contact_point")

    def factor(R_bush):
        fb_w = fb.with_bushing_radius(R_bush)
        return wear.period_wear_factor(one_period(fb_w), fb_w, fb.period, wear_range)["G"]

    cal_h = float(p["measurement_interval"]) / 3600.0
    out = {"sides": [], "k": [], "k_mean": [], "G_cal": [], "nodes": [], "h": [], "G_pred": []}
    t0 = time.perf_counter()
    for side in sides:
        h_meas = np.asarray(p[f"measured_wear_{side}"], float)
        k, k_mean, G = wear.calibrate(h_meas, cal_h, fb.period, R0, factor)
        t_start = cal_h * h_meas.size
        nodes, h, Gp = wear.predict(h_meas[-1], t_start, float(p["prediction_end"]) / 3600.0,
                                    float(s["interval_h"]), k_mean, fb.period, R0, factor,
                                    update=update)
        for key, val in (("sides", side), ("k", k), ("k_mean", k_mean), ("G_cal", G),
                         ("nodes", nodes), ("h", h), ("G_pred", Gp)):
            out[key].append(val)
    out["wall_time_prediction"] = time.perf_counter() - t0
    out["cal_hours"] = cal_h * (1 + np.arange(len(out["k"][0])))
    return out


@EFFECTS.register("unbalanced_load")
def unbalanced_load(p: dict) -> list[str]:
    """The two sides of the bushing under the out-of-plane load (Fig. 8b, Sec. 4.3)."""
    return ["B1", "B2"]


@EFFECTS.register("wear_update")
def wear_update() -> bool:
    """The bushing circle grows with the cumulative wear between intervals."""
    return True


# --- composition ---------------------------------------------------------------------------
def setup(run: dict):
    """(FourBar, settings, selected effects) for a run; refuses inconsistent effect sets."""
    sel = EFFECTS.select(run["effects"])
    joint = [e for e in JOINT_MODELS if e in sel]
    if len(joint) != 1:
        raise ValueError(f"joint_wear: a scene needs exactly one of {JOINT_MODELS}, got {joint}")
    p = run["parameters"]
    s = dict(run.get("resolution", {}))
    s.update(run.get("options", {}))
    s.setdefault("damping", False)
    fb = from_parameters(p)
    for name in ("gravity", "friction", "contact_damping"):
        if name in sel:
            fb = sel[name](fb, p, s)
    return fb, s, sel, joint[0]


def compute(run: dict) -> dict:
    """The physics of one run (what the runner times)."""
    fb, s, sel, joint = setup(run)
    p = run["parameters"]
    one_period = lambda fb_w: sel[joint](fb_w, s)  # noqa: E731
    t0 = time.perf_counter()
    hist = one_period(fb)
    period_wall = time.perf_counter() - t0
    if not hist.get("completed", True):
        if "archard_wear" in sel:
            raise RuntimeError(f"joint_wear: {hist['message']}: no period to compute wear from")
        # extrapolate honestly: the wall time the unfinished integrator would need
        period_wall = hist["integration_wall"] * fb.period / max(hist["t_reached"], 1e-12)
    if hist.get("completed", True):
        factor = wear.period_wear_factor(hist, fb, fb.period, s.get("wear_range", "contact_point"))
    else:
        factor = dict.fromkeys(("S", "F_N_mean", "AB_mean", "A_mean", "arc", "L_arc", "L_wear",
                                "G", "min_penetration", "F_N_min", "F_N_max"), math.nan)
    out = {"fb": fb, "hist": hist, "joint": joint, "period_wall": period_wall, "factor": factor}
    if "archard_wear" in sel:
        sides = sel["unbalanced_load"](p) if "unbalanced_load" in sel else ["B1"]
        update = sel["wear_update"]() if "wear_update" in sel else False
        out["wear"] = sel["archard_wear"](fb, s, p, one_period, sides, update)
        n_pbp = int(s.get("period_by_period_sample", 0))
        if n_pbp:
            k = out["wear"]["k_mean"][0]

            def factor(R_bush):
                fb_w = fb.with_bushing_radius(R_bush)
                return wear.period_wear_factor(one_period(fb_w), fb_w, fb.period,
                                               s.get("wear_range", "contact_point"))["G"]
            t0 = time.perf_counter()
            wear.period_by_period(float(p["measured_wear_B1"][-1]), n_pbp, k, fb.R_bush, factor)
            out["pbp"] = (n_pbp, time.perf_counter() - t0)
    return out


def _var(dims, val, units, long_name):
    return (dims, val, {"units": units, "long_name": long_name})


def to_dataset(res: dict, run: dict) -> xr.Dataset:
    fb, h, f = res["fb"], res["hist"], res["factor"]
    t = np.asarray(h["t"])
    coords = {"t": _var("t", t, "s", "time within the crank period")}
    v = {
        "F_N": _var("t", h["F_N"], "N", "normal contact force at joint B, Eq. (11)"),
        "F_T": _var("t", h["F_T"], "N", "friction force at joint B, Eq. (15)"),
        "penetration": _var("t", h["delta"], "m", "penetration depth delta, Eq. (8)"),
        "sliding_velocity": _var("t", h["v_T"], "m/s", "tangential relative velocity v_T, Eq. (10)"),
        "contact_angle": _var("t", h["psi"], "rad", "contact point on the bushing, angle in the coupler frame from C->B"),
        "theta3": _var("t", h["theta3"], "rad", "follower angle"),
        "phi2": _var("t", h["phi2"], "rad", "coupler angle C->B"),
    }
    scal = {
        "F_N_mean": (f["F_N_mean"], "N", "mean normal contact force over the period, Eq. (22)"),
        "F_N_min": (f["F_N_min"], "N", "minimum normal contact force over the period"),
        "F_N_max": (f["F_N_max"], "N", "maximum normal contact force over the period"),
        "min_penetration": (f["min_penetration"], "m", "minimum penetration over the period"),
        "sliding_distance": (f["S"], "m", "sliding distance over the period, Eq. (21)"),
        "contact_chord_mean": (f["AB_mean"], "m", "mean contact arc chord |AB|, Eq. (23)"),
        "contact_area_mean": (f["A_mean"], "m2", "mean contact area, Eq. (24)"),
        "contact_arc_angle": (f["arc"], "rad", "angular range of the contact point on the bushing (Fig. 13)"),
        "L_arc": (f["L_arc"], "m", "length of the contact-point arc on the bushing, Arc^j"),
        "L_wear": (f["L_wear"], "m", "length of the wear range used in Eq. (29)"),
        "wear_factor": (f["G"], "N/m", "wear depth per period per unit k, F_N S / (w L), Eq. (29)"),
        "period_wall_time": (res["period_wall"], "s", "wall time of one simulated period (extrapolated from t_reached if unfinished)"),
        "contact_stiffness": (fb.K_contact, "N/m^1.5", "K' of Eq. (12)"),
        "radial_clearance": (fb.clearance, "m", "radial clearance c"),
    }
    if "nfev" in h:
        scal["nfev"] = (float(h["nfev"]), "1", "right-hand-side evaluations of the integrator")
        scal["completed"] = (float(h["completed"]), "1", "1 if the integrator finished the period within its wall-time budget")
        scal["t_reached"] = (float(h["t_reached"]), "s", "time the integrator reached")
    if res["joint"] == "clearance_contact":
        full = h["full"]
        v_full = {"t_full": _var("t_full", full["t"], "s", "time since start of the simulation")}
        coords.update(v_full)
        v["penetration_full"] = _var("t_full", full["delta"], "m", "penetration depth over the whole simulation")
        v["F_N_full"] = _var("t_full", full["F_N"], "N", "normal contact force over the whole simulation")
        v["contact_angle_full"] = _var("t_full", full["psi"], "rad", "contact angle over the whole simulation")
        v["sliding_velocity_full"] = _var("t_full", full["v_T"], "m/s", "sliding velocity over the whole simulation")
    if "wear" in res:
        w = res["wear"]
        sides = w["sides"]
        coords["side"] = _var("side", np.array(sides, dtype=object), "1", "side of the bushing (Fig. 10)")
        coords["cal_hour"] = _var("cal_hour", w["cal_hours"], "h", "end of calibration interval P1..P5")
        v["k_calibrated"] = _var(("side", "cal_hour"), np.array(w["k"]), "1/Pa", "equivalent wear coefficient k = K/H per interval, Eqs. (32)-(34)")
        v["wear_factor_calibration"] = _var(("side", "cal_hour"), np.array(w["G_cal"]), "N/m", "wear factor of the simulated period per calibration interval")
        v["k_mean"] = _var("side", np.array(w["k_mean"]), "1/Pa", "mean equivalent wear coefficient (Tables 3-4)")
        nodes = w["nodes"][0]
        coords["hour"] = _var("hour", nodes, "h", "operating time at the interval nodes")
        v["wear_predicted"] = _var(("side", "hour"), np.array(w["h"]), "m", "predicted cumulative wear depth of the bushing (Fig. 15)")
        v["wear_factor_prediction"] = _var(("side", "hour"), np.array([np.append(g, np.nan) for g in w["G_pred"]]), "N/m", "wear factor of the period simulated at the start of each interval")
        scal["wear_at_end_B1"] = (float(w["h"][0][-1]), "m", "predicted wear of side B1 at the end of the prediction")
        if len(sides) > 1:
            scal["wear_at_end_B2"] = (float(w["h"][1][-1]), "m", "predicted wear of side B2 at the end of the prediction")
        n_sim = sum(len(g) for g in w["G_pred"])
        scal["n_simulations_prediction"] = (float(n_sim), "1", "one-period simulations of the prediction (all sides)")
        scal["n_simulations_per_side"] = (float(len(w["G_pred"][0])), "1", "one-period simulations of the prediction per side")
        scal["wall_time_wear"] = (w["wall_time_prediction"], "s", "wall time of calibration + prediction, all sides")
        # the interval method assumes the wear per period barely changes within an interval
        # (Sec. 3.3); its largest change between successive simulations measures that
        changes = [np.max(np.abs(np.diff(g) / g[:-1])) if len(g) > 1 else 0.0 for g in w["G_pred"]]
        scal["interval_factor_change_max"] = (float(max(changes)), "1", "largest relative change of the wear per period between successive interval simulations")
        if "pbp" in res:
            n, wall = res["pbp"]
            scal["pbp_sample_periods"] = (float(n), "1", "consecutive periods simulated one by one (Fig. 6) to time the reference")
            scal["pbp_sample_wall_time"] = (wall, "s", "wall time of those periods")
    ds = xr.Dataset(v, coords)
    for name, (val, unit, ln) in scal.items():
        ds[name] = ((), float(val), {"units": unit, "long_name": ln})
    ds.attrs["joint_model"] = res["joint"]
    return ds


def solve(run: dict) -> xr.Dataset:
    return to_dataset(compute(run), run)
