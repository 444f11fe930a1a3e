"""What the joint_wear notebook draws, taken from the datasets (SI in, SI out).

The notebook only converts to the paper's units (``mechrepro.units.from_si``) and draws.
"""
from __future__ import annotations

import numpy as np

from mechrepro.io import run_attrs

from . import accuracy

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
