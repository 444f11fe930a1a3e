"""What the joint_wear notebook draws, taken from the datasets (SI in, SI out; angles a
dataset stores in degrees stay so).

The notebook only converts to the paper's units (``mechrepro.units.from_si``) and draws.
"""
from __future__ import annotations

import numpy as np

from mechrepro.io import run_attrs
from mechrepro.units import from_si

from . import accuracy, wear

SIDES = ("B1", "B2")


def contact_angle(psi):
    """The contact point on the bushing (Fig. 13) as an angle in [0, 2 pi) [rad], coupler
    frame, 0 = direction C -> B."""
    return np.mod(np.asarray(psi, float), 2 * np.pi)


def contact_points_in_contact(ds):
    """(t, contact angle) of the whole dynamic simulation where the pin touches (delta > 0)."""
    c = ds["penetration_full"].values > 0
    return ds["t_full"].values[c], contact_angle(ds["contact_angle_full"].values[c])


def measured_wear(ds, side: str):
    """Tables 3-4: the measured cumulative wear h^P of ``side`` at the ends of the
    calibration intervals, with the new bushing at 0 h: (hours [h], wear [m])."""
    h = run_attrs(ds)["parameters"]["values_si"][f"measured_wear_{side}"]
    return np.r_[0.0, ds["cal_hour"].values], np.r_[0.0, np.asarray(h, float)]


def coefficient_table(ds, paper: dict, side: str) -> list[list]:
    """Rows of Table 3 (B1) or 4 (B2): point, hour, paper K, our K [1/Pa], paper / ours.

    ``paper``: {"p1".."p5", "mean": the paper's value}."""
    K = ds["K_table"].sel(side=side).values
    hours = ds["cal_hour"].values
    rows = [[f"P{i + 1}", float(hours[i]), paper[f"p{i + 1}"], float(K[i]),
             paper[f"p{i + 1}"] / float(K[i])] for i in range(K.size)]
    Km = float(ds["K_table_mean"].sel(side=side))
    rows.append(["mean", "", paper["mean"], Km, paper["mean"] / Km])
    return rows


def calibration_replay_error(ds, side: str):
    """Fig. 16 (in-sample): (replay with the mean coefficient - measured) / measured [1]."""
    _, h = measured_wear(ds, side)
    return ds["wear_calibration_replay"].sel(side=side).values / h[1:] - 1.0


def relative_to(base, other, side: str = "B1"):
    """Figs. 16, 18, 19: ``other``'s prediction relative to ``base``'s [1], at the
    measurement times that are nodes of ``other``'s interval schedule."""
    ok = other["report_is_node"].values > 0.5
    hrs = other["report_hour"].values[ok]
    w = other["wear_report"].sel(side=side).values[ok]
    return hrs, w / base["wear_report"].sel(side=side).values[ok] - 1.0


def linear_extrapolation(ds, side: str = "B1"):
    """The measured wear rate of the first 10 h continued, relative to the prediction
    (Fig. 16 substitute): (hours, relative difference [1])."""
    hh = ds["report_hour"].values
    base = ds["wear_report"].sel(side=side).values
    return hh, base[0] * hh / hh[0] / base - 1.0


def interval_runs(runs) -> dict:
    """{interval length [h]: run}, sorted, of the runs of the interval study (Figs. 17-19)."""
    out = {float(run_attrs(d)["resolution"]["interval_h"]): d for d in runs}
    return dict(sorted(out.items()))


def quasistatic_errors(st_qs, st_dyn) -> dict:
    """Relative error of the quasi-static wear per period over its samples per period,
    against the finest Radau run (model + sampling) and against its own finest sampling."""
    ref = st_dyn.isel(run=accuracy.finest_radau(st_dyn))
    G = st_qs["wear_factor"].values
    n = st_qs["n_steps"].values
    return {"n_steps": n, "reference": f"Radau rtol={float(ref['rtol']):g}",
            "vs_dynamic": np.abs(G / float(ref["wear_factor"]) - 1.0),
            "vs_finest": np.abs(G / G[np.argmax(n)] - 1.0)}


def explicit_points(st_exp) -> list[dict]:
    """The explicit RK45 runs: step budget, time reached and extrapolated time per period."""
    return [{"rtol": float(st_exp["rtol"][i]), "steps": float(st_exp["steps"][i]),
             "t_reached": float(st_exp["t_reached"][i]),
             "period_wall_time": float(st_exp["period_wall_time"][i])}
            for i in range(st_exp.sizes["run"])]


def posterior_table(ds) -> list[dict]:
    """The load-point distribution's statements (scene load_point_posterior): per
    quantity its posterior 2.5 / 50 / 97.5 % (mass-weighted, wear on the upper part) and its
    range over the credible set (the 95 % likelihood region)."""
    from .validation import weighted_quantiles
    w = ds["post_point_weight"].values
    cred = ds["post_point_credible"].values == 1
    H = float(run_attrs(ds)["parameters"]["values_si"]["hardness_bushing"])
    K = ds["post_point_K_table"]
    cols = {
        ("gravity", "m/s2"): ds["post_point_gravity"].values,
        ("distance_F_E", "m"): ds["post_point_distance"].values,
        ("friction_coefficient", "1"): ds["post_point_friction"].values,
        ("direction_F_E", "deg"): ds["post_point_direction"].values,
        ("contact_margin_quasistatic", "1"): ds["post_point_qs_margin"].values,
        ("contact_arc", "deg"): ds["post_point_arc"].values,
        ("wear_factor_new_bushing", "N/m"): ds["post_point_wear_factor"].values,
        ("k_archard_b1", "1"): wear.archard_dimensionless(wear.k_from_table(K.sel(side="B1").values, H), H),
        ("k_archard_b2", "1"): wear.archard_dimensionless(wear.k_from_table(K.sel(side="B2").values, H), H),
        ("wear_86h_b1", "mm"): ds["post_point_wear_86h"].sel(side="B1").values * 1e3,
        ("wear_86h_b2", "mm"): ds["post_point_wear_86h"].sel(side="B2").values * 1e3,
    }
    out = []
    for (name, unit), x in cols.items():
        q = weighted_quantiles(x, w) if np.any(w > 0) else np.full(3, np.nan)
        xc = x[cred & np.isfinite(x)]
        out.append({"quantity": name, "unit": unit, "q025": q[0], "median": q[1], "q975": q[2],
                    "credible_min": xc.min() if xc.size else np.nan,
                    "credible_max": xc.max() if xc.size else np.nan})
    return out


def centred_profile(lw) -> dict:
    """The groove profile of a local_wear run drawn unbroken about its worn region's centre:
    the angles from the centre, sorted [rad] (``rel``; ``order`` sorts any profile on the
    grid the same way), the profile on them, the centre [rad], and the Eq.-33 measuring
    points from the centre [rad] with the profile there."""
    th, prof = lw["theta"].values, lw["local_profile_end"].values
    centre = np.angle(np.sum(prof * np.exp(1j * th)))
    rel = np.angle(np.exp(1j * (th - centre)))
    o = np.argsort(rel)
    pts = np.angle(np.exp(1j * (lw["local_point_angle"].values - centre)))
    return {"rel": rel[o], "order": o, "profile": prof[o], "centre": centre, "points": pts,
            "at_points": np.interp(pts, rel[o], prof[o])}


def credible_arcs(post, qs) -> dict:
    """Fig. 13's contact arcs [deg]: of every credible load point of the load-point
    distribution (its ends, the first in [0, 360)) and of the quasi-static period ``qs`` at
    the assumed F (from its smallest unwrapped contact angle)."""
    cr = np.flatnonzero(post["post_point_credible"].values == 1)
    ends = post["post_point_arc_ends"].values[cr]
    return {"left": np.r_[np.mod(ends[:, 0], 360.0),
                          float(np.degrees(np.min(np.unwrap(qs["contact_angle"].values)))) % 360.0],
            "width": np.r_[ends[:, 1] - ends[:, 0], from_si(float(qs["contact_arc_angle"]), "deg")],
            "labels": [f"g {g:.2g}, {a:.0f}°" for g, a in zip(
                post["post_point_gravity"].values[cr], post["post_point_direction"].values[cr])] + ["assumed F"]}


def posterior_points(post) -> dict:
    """The points of the load-point distribution as drawn: their columns, whether their wear
    is on the upper part (``up``) and credible (``cred``), and their chi2 above the best
    upper-part point, clipped to [0, 50] (``dchi2``)."""
    pt = {k: post[f"post_point_{k}"].values for k in ("direction", "distance", "gravity", "chi2", "credible",
                                                       "upper_share", "qs_margin")}
    up = pt["upper_share"] > 0.5
    return {**pt, "up": up, "cred": pt["credible"] == 1,
            "dchi2": np.clip(pt["chi2"] - np.nanmin(np.where(up, pt["chi2"], np.nan)), 0, 50)}


def fit_band(fit, side: str):
    """Fig. 15's band at 86 h: the 86-h wear of ``side`` [m] at the load points estimated
    from Tables 3-4 with the wear on the upper part (their smallest and largest)."""
    w = fit["fit_sol_wear_86h"].sel(side=side).values[fit["fit_sol_upper_share"].values > 0.5]
    return w.min(), w.max()
