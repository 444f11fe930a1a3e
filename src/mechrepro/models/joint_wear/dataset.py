"""The variables of one joint_wear run: one function per part of a solver's result.

Each part returns ``(coords, variables)`` labelled with :func:`mechrepro.units.var`; a part
whose result is absent (no wear, no scan ...) contributes nothing.
"""
from __future__ import annotations

import math

import numpy as np

from mechrepro.units import var

from . import wear



def _scalars(items: dict) -> dict:
    """{name: (value, unit, long_name)} -> scalar variables."""
    return {k: var((), float(v), u, ln) for k, (v, u, ln) in items.items()}


def _series(dims, get, spec: dict) -> dict:
    """{name: (key, unit, long_name)} -> variables over ``dims`` with the values get(key)."""
    return {k: var(dims, get(key), u, ln) for k, (key, u, ln) in spec.items()}


def _column(rows: list):
    """get(key) of _series over a list of dicts: one float column."""
    return lambda key: np.array([r[key] for r in rows], float)


def _sides(sides=("B1", "B2")) -> dict:
    return {"side": var("side", np.array(sides, dtype=object), "1", "side of the bushing (Fig. 10)")}


def period_part(res: dict, run: dict):
    """The contact history of the simulated period and its wear factor (Eqs. 18-29)."""
    h, f = res["hist"], res["factor"]
    coords = {"t": var("t", np.asarray(h["t"]), "s", "time within the crank period")}
    v = _series("t", h.__getitem__, {
        "F_N": ("F_N", "N", "normal contact force at joint B, Eq. (11)"),
        "F_T": ("F_T", "N", "friction force at joint B, Eq. (15)"),
        "penetration": ("delta", "m", "penetration depth delta, Eq. (8)"),
        "sliding_velocity": ("v_T", "m/s", "tangential relative velocity v_T, Eq. (10)"),
        "contact_angle": ("psi", "rad", "contact point on the bushing, angle in the coupler frame from C->B"),
        "phi2": ("phi2", "rad", "coupler angle C->B"),
    })
    v.update(_scalars({
        "F_N_mean": (f["F_N_mean"], "N", "mean normal contact force over the period, Eq. (22)"),
        "F_N_min": (f["F_N_min"], "N", "minimum normal contact force over the period"),
        "min_penetration": (f["min_penetration"], "m", "minimum penetration over the period"),
        "sliding_distance": (f["S"], "m", "sliding distance over the period, Eq. (21)"),
        "contact_arc_angle": (f["arc"], "rad", "angular range of the contact point on the bushing (Fig. 13)"),
        "contact_arc_q90": (f["arc_q90"], "rad", "central range of the contact angle holding 90 % of the contact time (well-posed under rattling)"),
        "L_arc": (f["L_arc"], "m", "length of the contact-point arc on the bushing, Arc^j"),
        "L_wear": (f["L_wear"], "m", "length of the wear range used in Eq. (29)"),
        "wear_factor": (f["G"], "N/m", "wear depth per period per unit k, F_N S / (w L), Eq. (29)"),
        "period_wall_time": (res["period_wall"], "s", "wall time of one simulated period (extrapolated from t_reached if unfinished)"),
    }))
    return coords, v


def mechanism_part(res: dict, run: dict):
    fb = res["fb"]
    return {}, _scalars({
        "bushing_radius": (fb.R_bush, "m", "bushing radius R_j (new bushing)"),
        "period": (fb.period, "s", "crank period"),
    })


def integrator_part(res: dict, run: dict):
    """Cost of the dynamic integration and the whole simulated history (dynamic joint)."""
    h = res["hist"]
    full = h["full"]
    coords = {"t_full": var("t_full", full["t"], "s", "time since start of the simulation")}
    v = _series("t_full", full.__getitem__, {
        "penetration_full": ("delta", "m", "penetration depth over the whole simulation"),
        "contact_angle_full": ("psi", "rad", "contact angle over the whole simulation"),
    })
    v.update(_scalars({
        "nfev": (h["nfev"], "1", "right-hand-side evaluations of the integrator"),
        "steps": (h["steps"], "1", "integrator steps taken"),
        "completed": (h["completed"], "1", "1 if the integrator finished the period within its step budget"),
        "t_reached": (h["t_reached"], "s", "time the integrator reached"),
    }))
    return coords, v


def calibration_part(res: dict, run: dict):
    """Tables 3-4: the coefficients calibrated per interval (Eqs. 32-34) and their replay."""
    w, p = res["wear"], run["parameters"]
    H = float(p["hardness_bushing"])
    k, k_mean, G = np.array(w["k"]), np.array(w["k_mean"]), np.array(w["G_cal"])
    M_cal = wear.periods_per_interval(float(p["measurement_interval"]) / 3600.0, res["fb"].period)
    sc = ("side", "cal_hour")
    coords = {**_sides(w["sides"]), "cal_hour": var("cal_hour", w["cal_hours"], "h", "end of calibration interval P1..P5")}
    v = {
        "k_calibrated": var(sc, k, "m2/N", "dimensional wear coefficient k = K/H per interval, Eqs. (32)-(34)"),
        "K_table": var(sc, wear.table_from_k(k, H), "1/Pa", "equivalent wear coefficient K = k H_number as Tables 3-4 print it"),
        "K_table_mean": var("side", wear.table_from_k(k_mean, H), "1/Pa", "mean equivalent wear coefficient K as Tables 3-4 print it"),
        "K_archard_mean": var("side", wear.archard_dimensionless(k_mean, H), "1", "mean dimensionless Archard coefficient K_A = k H, H = 21 HB in Pa"),
        "wear_factor_calibration": var(sc, G, "N/m", "wear factor of the simulated period per calibration interval"),
        "wear_calibration_replay": var(sc, np.cumsum(k_mean[:, None] * G * M_cal, axis=1), "m", "the measured intervals replayed with the mean coefficient (in-sample, Eqs. 32-34)"),
        "k_mean": var("side", k_mean, "m2/N", "mean dimensional wear coefficient k = K/H"),
    }
    return coords, v


def prediction_part(res: dict, run: dict):
    """Fig. 15: the interval prediction, also at the paper's measurement times."""
    w = res["wear"]
    nodes = w["nodes"][0]
    # the paper's measurement times (every measurement interval from the start of the
    # prediction): nodes of every interval length that divides the schedule, so studies
    # over the interval can be compared there without re-gridding
    step_h = float(run["parameters"]["measurement_interval"]) / 3600.0
    rep = np.arange(nodes[0], nodes[-1] + 1e-9, step_h)
    rep[-1] = nodes[-1]
    coords = {"hour": var("hour", nodes, "h", "operating time at the interval nodes"),
              "report_hour": var("report_hour", rep, "h", "the paper's measurement times from the start of the prediction")}
    v = {
        "wear_predicted": var(("side", "hour"), np.array(w["h"]), "m", "predicted cumulative wear depth of the bushing (Fig. 15)"),
        "wear_factor_prediction": var(("side", "hour"), np.array([np.append(g, np.nan) for g in w["G_pred"]]), "N/m", "wear factor of the period simulated at the start of each interval"),
        "wear_report": var(("side", "report_hour"), np.array([np.interp(rep, nodes, h) for h in w["h"]]), "m",
                           "predicted cumulative wear at the measurement times (linear between interval nodes)"),
        "report_is_node": var("report_hour", np.isclose(rep[:, None], nodes[None, :], atol=1e-9).any(axis=1).astype(float), "1",
                              "1 where the measurement time is a node of this run's interval schedule"),
    }
    # the interval method assumes the wear per period barely changes within an interval
    # (Sec. 3.3); its largest change between successive simulations measures that
    changes = [np.max(np.abs(np.diff(g) / g[:-1])) if len(g) > 1 else 0.0 for g in w["G_pred"]]
    scal = {f"wear_at_end_{side}": (h[-1], "m", f"predicted wear of side {side} at the end of the prediction")
            for side, h in zip(w["sides"], w["h"])}
    scal.update({f"wear_at_end_limit_{side}": (h, "m", f"the interval method's limit (interval -> 0, wear.interval_limit) of side {side} at the end of the prediction")
                 for side, h in zip(w["sides"], w.get("limit", []))})
    scal.update({
        "n_simulations_prediction": (sum(len(g) for g in w["G_pred"]), "1", "one-period simulations of the prediction (all sides)"),
        "n_simulations_per_side": (len(w["G_pred"][0]), "1", "one-period simulations of the prediction per side"),
        "wall_time_wear": (w["wall_time_prediction"], "s", "wall time of calibration + prediction, all sides"),
        "interval_factor_change_max": (max(changes), "1", "largest relative change of the wear per period between successive interval simulations"),
    })
    v.update(_scalars(scal))
    return coords, v


def period_by_period_part(res: dict, run: dict):
    n, wall = res["pbp"]
    return {}, _scalars({
        "pbp_sample_periods": (n, "1", "consecutive periods simulated one by one (Fig. 6) to time the reference"),
        "pbp_sample_wall_time": (wall, "s", "wall time of those periods"),
    })


def scan_part(res: dict, run: dict):
    """The calibrated coefficient over load points F and gravity planes."""
    sc = res["scan"]
    H = float(run["parameters"]["hardness_bushing"])
    gd = ("scan_gravity", "scan_direction")
    coords = {**_sides(sc["sides"]), "scan_gravity": var("scan_gravity", sc["gravity"], "m/s2", "gravity component in the plane of motion"),
              "scan_direction": var("scan_direction", sc["directions"], "deg", "direction of the load point F from E's mid-stroke position")}
    v = {
        "scan_K_table_mean": var(("side", *gd), wear.table_from_k(sc["k"], H), "1/Pa", "mean equivalent wear coefficient (table units) calibrated with this load point and gravity"),
        "scan_L_arc": var(gd, sc["L_arc"], "m", "contact-point arc length on the bushing (new bushing)"),
    }
    return coords, v


def fit_part(res: dict, run: dict):
    """The load point estimated from Tables 3-4: the misfit over F's direction and the
    estimates with what they predict."""
    f = res["fit"]
    sols = f["solutions"]
    gd = ("fit_gravity", "fit_direction")
    coords = {"fit_gravity": var("fit_gravity", f["gravity"], "m/s2", "gravity component in the plane of motion"),
              "fit_direction": var("fit_direction", f["directions"], "deg", "direction of F from E's mid-stroke position"),
              "fit_solution": var("fit_solution", np.arange(len(sols)), "1", "load point reproducing Tables 3-4"),
              "fit_band": var("fit_band", np.array([-1.0, 0.0, 1.0]), "1", "estimate - its uncertainty, the estimate, + its uncertainty"),
              **_sides()}
    v = {"fit_misfit": var(gd, f["misfit"], "1", "mean ln(K_p ours / K_p paper) over both sides and five intervals, every interval at the new bushing's wear factor (within 0.01 of the misfit; it places the zeros, the misfit refines them; NaN: contact lost)"),
         **_series("fit_solution", _column(sols), {
             "fit_sol_gravity": ("gravity", "m/s2", "gravity plane of the estimate"),
             "fit_sol_direction": ("direction", "deg", "estimated direction of F"),
             "fit_sol_sigma": ("sigma_deg", "deg", "its uncertainty from the tables (standard error of the ten log-ratios through the local slope)"),
             "fit_sol_arc": ("arc_deg", "deg", "contact arc on the bushing at the estimate (new bushing)"),
             "fit_sol_upper_share": ("upper_share", "1", "share of the wear above the bushing centre (Sec. 4.2: the upper part)")}),
         "fit_sol_wear_86h": var(("fit_solution", "fit_band", "side"),
                                 np.array([x["wear_86h"] for x in sols], float).reshape(len(sols), 3, 2),
                                 "m", "wear at 86 h predicted with the estimate (and +- its uncertainty)")}
    return coords, v


#: the columns of every point of the load-point distribution: name -> (key, unit, long_name)
_POST_POINT = {
    "post_point_distance": ("distance", "m", "F's distance from E"),
    "post_point_gravity": ("gravity", "m/s2", "gravity in the plane of motion"),
    "post_point_friction": ("friction", "1", "friction coefficient"),
    "post_point_direction": ("direction", "deg", "F's direction from E (a zero of the mean misfit)"),
    "post_point_misfit": ("misfit", "1", "mean misfit left at the zero"),
    "post_point_chi2": ("chi2", "1", "chi2 of the ten log-ratios about their best common level, rounding noise of the printed increments"),
    "post_point_credible": ("credible", "1", "1 inside the credible set"),
    "post_point_upper_share": ("upper_share", "1", "share of the wear above the bushing centre (Sec. 4.2)"),
    "post_point_qs_margin": ("qs_margin", "1", "quasi-static contact margin min F_N / max F_N"),
    "post_point_arc": ("arc_deg", "deg", "contact arc on the new bushing (Fig. 13's psi)"),
    "post_point_wear_factor": ("G", "N/m", "wear factor of the new bushing, Eq. (29)"),
}


def posterior_part(res: dict, run: dict):
    """The load point as a distribution (solver load_point_posterior): every point the
    tables allow (a zero of the misfit at a node), with
    its posterior weight, whether it is credible and what the mechanics give there.  A run
    without a point keeps one row of NaN (netCDF-3 has no empty dimension)."""
    f = res["posterior"]
    keys = [k for k, _, _ in _POST_POINT.values()] + ["K_b1", "K_b2"]
    pts = f["points"] or [dict.fromkeys(keys, math.nan) | {"wear_86h": [math.nan] * 2, "arc_ends_deg": [math.nan] * 2}]
    w = np.asarray(f["weight"], float) if f["points"] else np.array([math.nan])
    col = _column(pts)
    H = float(run["parameters"]["hardness_bushing"])
    dyn = f["worst_margins"] or {}
    worst = f["worst"] or {}
    if not f["points"]:
        f = {**f, "chi2_new_bushing": math.nan, "new_bushing_credible": False}
    coords = {"post_gravity": var("post_gravity", f["gravity"], "m/s2", "prior node: gravity component in the plane of motion"),
              "post_point": var("post_point", np.arange(len(pts)), "1", "load point reproducing the mean of Tables 3-4 at a prior node"),
              **_sides()}
    v = {**_series("post_point", col, _POST_POINT),
         "post_point_weight": var("post_point", w, "1", "posterior mass (0: the wear is not on the upper part of the bushing)"),
         "post_point_arc_ends": var(("post_point", "arc_end"), np.array([q["arc_ends_deg"] for q in pts], float).reshape(len(pts), 2), "deg",
                                    "ends of the contact-point arc on the new bushing (coupler frame, on the path unwrapped from its first sample)"),
         "post_point_K_table": var(("post_point", "side"), wear.table_from_k(np.c_[col("K_b1"), col("K_b2")], H), "1/Pa", "mean calibrated coefficient (table units)"),
         "post_point_wear_86h": var(("post_point", "side"), np.array([q["wear_86h"] for q in pts], float), "m", "86-h wear (NaN outside the credible set)"),
         **_scalars({"post_margin_min": (f["margin"], "1", "smallest contact margin over the credible set (dynamic at its worst quasi-static point; NaN: no credible point)"),
                     "post_worst_dyn_margin": (dyn.get("dyn_margin", math.nan), "1", "dynamic margin at the credible point of the smallest quasi-static margin"),
                     **{f"post_worst_{k}": (worst.get(k, math.nan), u, f"credible point of the smallest quasi-static margin (a node or a branch's lower edge in g): {ln}")
                        for k, u, ln in (("gravity", "m/s2", "gravity"), ("distance", "m", "F's distance from E"),
                                         ("friction", "1", "friction coefficient"), ("direction", "deg", "F's direction from E"),
                                         ("qs_margin", "1", "quasi-static margin"))},
                     "post_credible_level": (f["level"], "1", "level of the likelihood region (chi2 quantile, 4 degrees of freedom)"),
                     "post_chi2_new_bushing": (f["chi2_new_bushing"], "1", "chi2 of Tables 3-4 read with every calibration interval on the new bushing (the same at every load point)"),
                     "post_new_bushing_credible": (f["new_bushing_credible"], "1", "1 if that reading is inside the likelihood region")})}
    return coords, v


def sensitivity_part(res: dict, run: dict):
    """The assumed constants at their range ends."""
    rows = res["sens"]
    c = ("sens_case",)
    coords = {"sens_case": var("sens_case", np.arange(len(rows)), "1", "constant at a range end (0: all assumed values)")}
    col = _column(rows)
    v = {"sens_parameter": var(c, np.array([r["parameter"] for r in rows], dtype=object), "1", "the constant moved"),
         "sens_K_table_mean": var(c, wear.table_from_k(col("K_mean"), float(run["parameters"]["hardness_bushing"])), "1/Pa", "mean coefficient of side B1 (table units)"),
         **_series(c, col, {"sens_value": ("value", "1", "its value (SI)"),
                            "sens_wear_86h": ("wear_86h", "m", "wear of B1 at 86 h"),
                            "sens_arc": ("arc_deg", "deg", "contact arc (quasi-static, new bushing)"),
                            "sens_qs_vs_dynamic": ("qs_vs_dynamic", "1", "quasi-static / settled dynamic wear per period - 1"),
                            "sens_dynamic_steps": ("dynamic_steps", "1", "Radau steps of the settled dynamic period")})}
    return coords, v


def local_part(res: dict, run: dict):
    """Local vs uniform wear of side B1."""
    lw = res["local"]
    coords = {"local_hour": var("local_hour", lw["hours"], "h", "node times of the prediction"),
              "theta": var("theta", lw["theta"], "rad", "bushing angle, coupler frame"),
              "local_point": var("local_point", np.arange(len(lw["points"])), "1", "measuring point of Eq. (33)"),
              "placement": var("placement", np.arange(len(lw["placements"])), "1", "placement of the Eq.-33 points (0: the baseline)")}
    h, pl = ("local_hour",), ("placement",)
    v = {"local_mean_depth": var(h, lw["mean"], "m", "groove model: mean depth over the 8 points of Eq. (33) in the wear range"),
         "local_peak_depth": var(h, lw["peak"], "m", "groove model: deepest point of the profile"),
         "circle_mean_depth": var(h, lw["circle_mean"], "m", "mean-circle feedback: mean depth over the 8 points"),
         "circle_peak_depth": var(h, lw["circle_peak"], "m", "mean-circle feedback: deepest point of the profile"),
         "circle_profile_end": var(("theta",), lw["circle_profile"], "m", "mean-circle feedback: wear profile at the end"),
         "placement_shift": var(pl, lw["placements"][:, 0], "1", "shift of the points' centre from the contact arc's midpoint, in arcs"),
         "placement_scale": var(pl, lw["placements"][:, 1], "1", "span of the points over the contact arc's"),
         "placement_mean_depth": var(pl, lw["placement_mean"], "m", "groove model, 86 h: mean depth over the points so placed (calibrated on them)"),
         "uniform_depth": var(h, lw["uniform"], "m", "uniform model (Eq. 29) on the same joint and schedule"),
         "local_profile_end": var(("theta",), lw["profile"], "m", "groove model: wear profile at the end"),
         "local_point_angle": var(("local_point",), np.angle(np.exp(1j * np.asarray(lw["points"]))), "rad",
                                  "bushing angle of the measuring points of Eq. (33): the middles of 8 equal parts of the contact arc (coupler frame)"),
         **_scalars({"local_k": (lw["k_local"], "m2/N", "calibrated k of the local model"),
                     "local_k_uniform": (lw["k_uniform"], "m2/N", "calibrated k of the uniform model"),
                     "local_wall_time": (lw["wall_local"], "s", "wall time, groove model (calibration + prediction), per placement"),
                     "local_uniform_wall_time": (lw["wall_uniform"], "s", "wall time, uniform model"),
                     "local_arc": (lw["arc"], "rad", "contact arc of the new bushing"),
                     "local_AB_mean": (lw["AB_mean"], "m", "mean contact chord of the new bushing")})}
    return coords, v


# (part, the key of the solver's result it needs)
PARTS = ((mechanism_part, "fb"), (period_part, "hist"), (calibration_part, "wear"),
         (prediction_part, "wear"), (period_by_period_part, "pbp"), (scan_part, "scan"),
         (fit_part, "fit"), (posterior_part, "posterior"), (sensitivity_part, "sens"),
         (local_part, "local"))


def variables(res: dict, run: dict) -> dict:
    """The run's variables from a solver's result (solver.py)."""
    out = {}
    parts = [p for p, key in PARTS if key in res]
    if "full" in res.get("hist", {}):
        parts.append(integrator_part)
    for part in parts:
        coords, v = part(res, run)
        out |= coords | v
    return out
