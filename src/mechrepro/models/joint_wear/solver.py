"""Compose the joint_wear effects a scene names into one xarray Dataset.

Effects
-------
joint model (exactly one):
  ``clearance_contact``   dynamic clearance joint, stiff contact, implicit integrator
  ``continuous_contact``  quasi-static continuous contact (the paper's low-speed model)
force terms: ``friction`` (Eq. 15), ``contact_damping`` (Eq. 14), ``gravity``
wear: ``archard_wear`` (calibration Eqs. 32-34 + interval prediction, Sec. 3.3/4.4),
  ``unbalanced_load`` (sides B1 and B2 each with their own coefficient, Sec. 4.3),
  ``wear_update`` (the bushing grows between intervals, Sec. 4.4 step 4),
  ``assumption_scan`` (the calibrated coefficient over load directions and gravity
  planes the paper leaves open: how far the absolute coefficient is determined)
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
                          start=s.get("start", "equilibrium"), max_steps=s.get("max_steps"))
    if r["status"] == -1:
        raise RuntimeError(f"joint_wear: {s['method']} failed at t = {r['t_reached']:.4g} s: "
                           f"{r['message']}")
    completed = r["status"] == 0
    # a finished run: its last period on the uniform periodic grid; an unfinished one
    # (step budget spent): what it reached, flagged
    sl = slice(-(n_out + 1), -1) if completed else slice(None)
    out = {k: np.asarray(v)[sl] for k, v in r.items()
           if isinstance(v, np.ndarray) and v.ndim == 1 and v.size == r["t"].size}
    out["t"] = out["t"] - (periods - 1) * T
    out.update(nfev=r["nfev"], steps=r["steps"], full=r, completed=completed,
               t_reached=r["t_reached"], integration_wall=r["wall"], message=r["message"])
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
        k, k_mean, G = wear.calibrate(h_meas, cal_h, fb.period, R0, factor,
                                      dh_measured=p[f"measured_increment_{side}"])
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


@EFFECTS.register("assumption_scan")
def assumption_scan(fb: FourBar, s: dict, p: dict, one_period, sides) -> dict:
    """The mean calibrated coefficient per side over load points F and gravity planes.

    F is placed at ``scan_load_distance`` [m] from E's mid-stroke position in each of the
    directions ``scan_load_direction_deg`` (from +x, anticlockwise); the gravity values
    ``scan_gravity`` [m/s2] stand for planes of motion from horizontal (0) to vertical.
    Only the calibration is run (5 periods per point): it is what fixes the coefficient.
    """
    from . import kinematics

    th3, _ = kinematics.positions(fb, np.linspace(0.0, 2 * np.pi, 721))
    th_mid = 0.5 * (th3.min() + th3.max())
    E = (fb.l0 + 0.5 * fb.l3 * math.cos(th_mid), 0.5 * fb.l3 * math.sin(th_mid))
    d = float(s["scan_load_distance"])
    dirs = np.asarray(s["scan_load_direction_deg"], float)
    gs = np.asarray(s["scan_gravity"], float)
    cal_h = float(p["measurement_interval"]) / 3600.0
    k = np.full((len(sides), gs.size, dirs.size), np.nan)
    L = np.full((gs.size, dirs.size), np.nan)
    F_min = np.full((gs.size, dirs.size), np.nan)
    for i, g in enumerate(gs):
        for j, a in enumerate(dirs):
            F = (E[0] + d * math.cos(math.radians(a)), E[1] + d * math.sin(math.radians(a)))
            fb_v = replace(fb, g=g, F=F)
            try:
                f0 = wear.period_wear_factor(one_period(fb_v), fb_v, fb.period)
            except ValueError:      # contact lost: the paper's premise fails there
                continue
            L[i, j], F_min[i, j] = f0["L_arc"], f0["F_N_min"]

            def factor(R_bush, fb_v=fb_v):
                fb_w = fb_v.with_bushing_radius(R_bush)
                return wear.period_wear_factor(one_period(fb_w), fb_w, fb.period)["G"]
            for m, side in enumerate(sides):
                k[m, i, j] = wear.calibrate(p[f"measured_wear_{side}"], cal_h, fb.period,
                                            fb.R_bush, factor,
                                            dh_measured=p[f"measured_increment_{side}"])[1]
    return {"k": k, "L_arc": L, "F_N_min": F_min, "directions": dirs, "gravity": gs,
            "E_mid": E, "distance": d, "sides": list(sides)}


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
    wear_range = s.get("wear_range", "contact_point")

    def one_period(fb_w):
        hist = sel[joint](fb_w, s)
        if joint == "continuous_contact" and "archard_wear" in sel:
            _refuse_contact_loss(hist)
        return hist
    t0 = time.perf_counter()
    hist = one_period(fb)
    period_wall = time.perf_counter() - t0
    if not hist.get("completed", True):
        if "archard_wear" in sel:
            raise RuntimeError(f"joint_wear: {hist['message']}: no period to compute wear from")
        # the time the unfinished integrator would need per period (a timing, never a result)
        period_wall = hist["integration_wall"] * fb.period / max(hist["t_reached"], 1e-12)
    if hist.get("completed", True):
        factor = wear.period_wear_factor(hist, fb, fb.period, wear_range)
    else:
        factor = dict.fromkeys(("S", "F_N_mean", "AB_mean", "A_mean", "arc", "arc_q90",
                                "L_arc", "L_wear", "G", "min_penetration", "F_N_min",
                                "F_N_max"), math.nan)
    out = {"fb": fb, "hist": hist, "joint": joint, "period_wall": period_wall, "factor": factor}
    sides = sel["unbalanced_load"](p) if "unbalanced_load" in sel else ["B1"]
    if "archard_wear" in sel:
        update = sel["wear_update"]() if "wear_update" in sel else False
        out["wear"] = sel["archard_wear"](fb, s, p, one_period, sides, update)
    if "assumption_scan" in sel:
        out["scan"] = sel["assumption_scan"](fb, s, p, one_period, sides)
    n_pbp = int(s.get("period_by_period_sample", 0))
    if n_pbp:
        k = 1e-13   # any coefficient: only the time per period is measured here

        def g_of(R_bush):
            fb_w = fb.with_bushing_radius(R_bush)
            return wear.period_wear_factor(one_period(fb_w), fb_w, fb.period, wear_range)["G"]
        t0 = time.perf_counter()
        wear.period_by_period(float(p["measured_wear_B1"][-1]), n_pbp, k, fb.R_bush, g_of)
        out["pbp"] = (n_pbp, time.perf_counter() - t0)
    return out


CONTACT_LOSS_FRACTION = 1e-2


def _refuse_contact_loss(hist: dict) -> None:
    """The continuous-contact model (Sec. 3.2) cannot represent a joint force that
    vanishes: there the pin flies across the clearance (the dynamic model shows it).  Below
    1 % of its peak the force is taken as vanishing -- a refusal, never a verdict."""
    F = np.asarray(hist["F_N"])
    if not F.min() > CONTACT_LOSS_FRACTION * F.max():
        i = int(np.argmin(F))
        raise ValueError(
            f"joint_wear: continuous contact lost: the joint-B force falls to {F[i]:.3g} N "
            f"(peak {F.max():.3g} N) at t = {hist['t'][i]:.3g} s; the continuous-contact wear "
            "model (Sec. 3.2) does not apply -- use clearance_contact")


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
        "contact_arc_q90": (f["arc_q90"], "rad", "central range of the contact angle holding 90 % of the contact time (well-posed under rattling)"),
        "L_arc": (f["L_arc"], "m", "length of the contact-point arc on the bushing, Arc^j"),
        "L_wear": (f["L_wear"], "m", "length of the wear range used in Eq. (29)"),
        "wear_factor": (f["G"], "N/m", "wear depth per period per unit k, F_N S / (w L), Eq. (29)"),
        "period_wall_time": (res["period_wall"], "s", "wall time of one simulated period (extrapolated from t_reached if unfinished)"),
        "contact_stiffness": (fb.K_contact, "N/m^1.5", "K' of Eq. (12)"),
        "radial_clearance": (fb.clearance, "m", "radial clearance c"),
        "period": (fb.period, "s", "crank period"),
    }
    if "nfev" in h:
        scal["nfev"] = (float(h["nfev"]), "1", "right-hand-side evaluations of the integrator")
        scal["steps"] = (float(h["steps"]), "1", "integrator steps taken")
        scal["completed"] = (float(h["completed"]), "1", "1 if the integrator finished the period within its step budget")
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
        H = float(run["parameters"]["hardness_bushing"])
        v["k_calibrated"] = _var(("side", "cal_hour"), np.array(w["k"]), "m2/N", "dimensional wear coefficient k = K/H per interval, Eqs. (32)-(34)")
        v["K_table"] = _var(("side", "cal_hour"), wear.table_from_k(np.array(w["k"]), H), "1/Pa", "equivalent wear coefficient K = k H_number as Tables 3-4 print it")
        v["K_table_mean"] = _var("side", wear.table_from_k(np.array(w["k_mean"]), H), "1/Pa", "mean equivalent wear coefficient K as Tables 3-4 print it")
        v["K_archard_mean"] = _var("side", wear.archard_dimensionless(np.array(w["k_mean"]), H), "1", "mean dimensionless Archard coefficient K_A = k H, H = 21 HB in Pa")
        v["wear_factor_calibration"] = _var(("side", "cal_hour"), np.array(w["G_cal"]), "N/m", "wear factor of the simulated period per calibration interval")
        M_cal = wear.periods_per_interval(float(run["parameters"]["measurement_interval"]) / 3600.0, fb.period)
        replay = np.cumsum(np.array(w["k_mean"])[:, None] * np.array(w["G_cal"]) * M_cal, axis=1)
        v["wear_calibration_replay"] = _var(("side", "cal_hour"), replay, "m", "the measured intervals replayed with the mean coefficient (in-sample, Eqs. 32-34)")
        v["k_mean"] = _var("side", np.array(w["k_mean"]), "m2/N", "mean dimensional wear coefficient k = K/H")
        nodes = w["nodes"][0]
        coords["hour"] = _var("hour", nodes, "h", "operating time at the interval nodes")
        v["wear_predicted"] = _var(("side", "hour"), np.array(w["h"]), "m", "predicted cumulative wear depth of the bushing (Fig. 15)")
        v["wear_factor_prediction"] = _var(("side", "hour"), np.array([np.append(g, np.nan) for g in w["G_pred"]]), "N/m", "wear factor of the period simulated at the start of each interval")
        # the paper's measurement times (every measurement interval from the start of the
        # prediction): nodes of every interval length that divides the schedule, so studies
        # over the interval can be compared there without re-gridding
        step_h = float(run["parameters"]["measurement_interval"]) / 3600.0
        rep = np.arange(nodes[0], nodes[-1] + 1e-9, step_h)
        rep[-1] = nodes[-1]
        coords["report_hour"] = _var("report_hour", rep, "h", "the paper's measurement times from the start of the prediction")
        v["wear_report"] = _var(("side", "report_hour"), np.array([np.interp(rep, nodes, h) for h in w["h"]]), "m",
                                "predicted cumulative wear at the measurement times (linear between interval nodes)")
        v["report_is_node"] = _var("report_hour", np.isclose(rep[:, None], nodes[None, :], atol=1e-9).any(axis=1).astype(float), "1",
                                   "1 where the measurement time is a node of this run's interval schedule")
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
    if "scan" in res:
        sc = res["scan"]
        H = float(run["parameters"]["hardness_bushing"])
        coords.setdefault("side", _var("side", np.array(sc["sides"], dtype=object), "1", "side of the bushing (Fig. 10)"))
        coords["scan_gravity"] = _var("scan_gravity", sc["gravity"], "m/s2", "gravity component in the plane of motion")
        coords["scan_direction"] = _var("scan_direction", sc["directions"], "deg", "direction of the load point F from E's mid-stroke position")
        v["scan_K_table_mean"] = _var(("side", "scan_gravity", "scan_direction"), wear.table_from_k(sc["k"], H), "1/Pa", "mean equivalent wear coefficient (table units) calibrated with this load point and gravity")
        v["scan_L_arc"] = _var(("scan_gravity", "scan_direction"), sc["L_arc"], "m", "contact-point arc length on the bushing (new bushing)")
        v["scan_F_N_min"] = _var(("scan_gravity", "scan_direction"), sc["F_N_min"], "N", "minimum joint force over the period (new bushing)")
        scal["scan_load_distance"] = (sc["distance"], "m", "distance of F from E's mid-stroke position in the scan")
    ds = xr.Dataset(v, coords)
    for name, (val, unit, ln) in scal.items():
        ds[name] = ((), float(val), {"units": unit, "long_name": ln})
    ds.attrs["joint_model"] = res["joint"]
    return ds


def solve(run: dict) -> xr.Dataset:
    return to_dataset(compute(run), run)
