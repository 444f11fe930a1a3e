"""joint_wear's figures, each drawn from the results it declares (config ``figures``), and
what they draw, taken from the datasets (SI in, SI out; angles a dataset stores in degrees
stay so).  The draw functions only convert to the paper's units and draw.
"""
from __future__ import annotations

import numpy as np

from mechrepro.accuracy import plot as accuracy_plot
from mechrepro.io import run_attrs
from mechrepro.plotting import plt
from mechrepro.units import from_si

from . import accuracy, wear

def measured_wear(ds, side: str):
    """Tables 3-4: the measured cumulative wear h^P of ``side`` at the ends of the
    calibration intervals, with the new bushing at 0 h: (hours [h], wear [m])."""
    h = run_attrs(ds)["parameters"]["values_si"][f"measured_wear_{side}"]
    return np.r_[0.0, ds["cal_hour"].values], np.r_[0.0, np.asarray(h, float)]


def table3(R) -> tuple[list, list]:
    """Table 3: the equivalent wear coefficients of side B1 (:func:`coefficient_table`)."""
    return coefficient_table(R, "B1")


def table4(R) -> tuple[list, list]:
    """Table 4: the equivalent wear coefficients of side B2 (:func:`coefficient_table`)."""
    return coefficient_table(R, "B2")


def coefficient_table(R, side: str) -> tuple[list, list]:
    """Table 3 (B1) or 4 (B2): point, hour, paper K, our K [1/Pa], paper / ours."""
    ds, s = R.run("wear_prediction"), side.lower()
    K, hours = ds["K_table"].sel(side=side).values, ds["cal_hour"].values
    rows = [[f"P{i}", float(hours[i - 1]), R.value(f"k_{s}_p{i}", "paper_value"), float(K[i - 1])]
            for i in range(1, K.size + 1)]
    rows.append(["mean", "", R.value(f"k_mean_{s}", "paper_value"), float(ds["K_table_mean"].sel(side=side))])
    header = ["point", "hour", "paper_K_per_Pa", "ours_K_per_Pa", "paper_over_ours"]
    return header, [r + [r[2] / r[3]] for r in rows]


def relative_to(base, other, side: str = "B1"):
    """Figs. 16, 18, 19: ``other``'s prediction relative to ``base``'s [1], at the
    measurement times that are nodes of ``other``'s interval schedule."""
    ok = other["report_is_node"].values > 0.5
    hrs = other["report_hour"].values[ok]
    w = other["wear_report"].sel(side=side).values[ok]
    return hrs, w / base["wear_report"].sel(side=side).values[ok] - 1.0


def interval_runs(R) -> dict:
    """{interval length [h]: run}, sorted, of the runs of the interval study (Figs. 17-19)."""
    out = {float(run_attrs(d)["resolution"]["interval_h"]): d for d in R.study_runs("intervals")}
    return dict(sorted(out.items()))


def load_point_posterior(R) -> tuple[list, list]:
    """The load-point distribution's statements (scene load_point_posterior): per
    quantity its posterior 2.5 / 50 / 97.5 % (mass-weighted, wear on the upper part) and its
    range over the credible set (the 95 % likelihood region)."""
    from .validation import weighted_quantiles
    ds = R.run("load_point_posterior")
    w = ds["post_point_weight"].values
    cred = ds["post_point_credible"].values == 1
    H = float(run_attrs(ds)["parameters"]["values_si"]["hardness_bushing"])
    cols = {(name, unit): ds[f"post_point_{v}"].values for name, unit, v in (
        ("gravity", "m/s2", "gravity"), ("distance_F_E", "m", "distance"),
        ("friction_coefficient", "1", "friction"), ("direction_F_E", "deg", "direction"),
        ("contact_margin_quasistatic", "1", "qs_margin"), ("contact_arc", "deg", "arc"),
        ("wear_factor_new_bushing", "N/m", "wear_factor"))}
    for s in ("B1", "B2"):
        K = ds["post_point_K_table"].sel(side=s).values
        cols[(f"k_archard_{s.lower()}", "1")] = wear.archard_dimensionless(wear.k_from_table(K, H), H)
    for s in ("B1", "B2"):
        cols[(f"wear_86h_{s.lower()}", "mm")] = ds["post_point_wear_86h"].sel(side=s).values * 1e3
    out = []
    for (name, unit), x in cols.items():
        q = weighted_quantiles(x, w) if np.any(w > 0) else np.full(3, np.nan)
        xc = x[cred & np.isfinite(x)]
        out.append({"quantity": name, "unit": unit, "q025": q[0], "median": q[1], "q975": q[2],
                    "credible_min": xc.min() if xc.size else np.nan,
                    "credible_max": xc.max() if xc.size else np.nan})
    return list(out[0]), [list(r.values()) for r in out]


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


# --- the figures -----------------------------------------------------------------------------

def _mm(x):
    """Lengths drawn in mm."""
    return from_si(np.asarray(x), "mm")


def _deg(x):
    """Angles drawn in deg."""
    return from_si(np.asarray(x), "deg")


def fig13(R):
    """Fig. 13: the contact points of the pin on the bushing.  Left: over time, the first
    period from the paper's concentric start (free flight, impact, rattling) against the
    settled dynamic and the quasi-static period; middle: their distribution over the bushing;
    right: the quasi-static contact arc at the load points Tables 3-4 imply (credible set of
    scene load_point_posterior) against the assumed F's few degrees."""
    cp, per_dyn, per_qs, post = (R.run(n) for n in ("fig13_contact_points", "period_dynamic",
                                                    "period_quasistatic", "load_point_posterior"))
    on = cp["penetration_full"].values > 0                # the pin touches the bushing

    def psi(x):      # the contact angle on the bushing [deg] in [0, 360), 0 = direction C -> B
        return _deg(np.mod(np.asarray(x, float), 2 * np.pi))
    psi_c, psi_dyn = psi(cp["contact_angle_full"].values[on]), psi(per_dyn["contact_angle"].values)
    fig, ax = plt.subplots(1, 3, figsize=(15, 4), layout="constrained")
    ax[0].plot(cp["t_full"].values[on], psi_c, ".", ms=1.5, label="dynamic, concentric start (1st period)")
    ax[0].plot(per_dyn["t"], psi_dyn, "-", label="dynamic, settled period")
    ax[0].plot(per_qs["t"], psi(per_qs["contact_angle"].values), "--", label="quasi-static continuous contact")
    ax[0].set(xlabel="t [s]", ylabel="contact angle ψ on the bushing [deg]\n(coupler frame, 0 = direction C→B)", title="Fig. 13")
    ax[0].legend(fontsize=7)
    bins = np.linspace(np.floor(psi_c.min()) - 1, np.ceil(psi_c.max()) + 1, 80)
    ax[1].hist(psi_c, bins=bins, density=True, alpha=0.6, label="1st period (impact, rattling, sliding)")
    ax[1].hist(psi_dyn, bins=bins, density=True, alpha=0.6, label="settled period")
    ax[1].set(xlabel="contact angle ψ [deg]", ylabel="share of time in contact [1/deg]", title="distribution of contact points")
    ax[1].legend(fontsize=7)
    # the contact arcs of the credible load points (their ends, the first in [0, 360)) and of
    # the quasi-static period at the assumed F (from its smallest unwrapped contact angle)
    cr = np.flatnonzero(post["post_point_credible"].values == 1)
    ends, n = post["post_point_arc_ends"].values[cr], cr.size
    ax[2].barh(np.arange(n), ends[:, 1] - ends[:, 0], left=np.mod(ends[:, 0], 360.0), height=0.6,
               color="tab:green", label="load points Tables 3–4 imply (credible set)")
    ax[2].barh([n], [from_si(float(per_qs["contact_arc_angle"]), "deg")], height=0.6, color="tab:gray",
               left=[float(np.degrees(np.min(np.unwrap(per_qs["contact_angle"].values)))) % 360.0], label="assumed F")
    labels = [f"g {g:.2g}, {a:.0f}°" for g, a in zip(post["post_point_gravity"].values[cr],
                                                      post["post_point_direction"].values[cr])]
    ax[2].set_yticks(np.arange(n + 1), labels + ["assumed F"], fontsize=6)
    ax[2].set(xlabel="contact angle ψ on the bushing [deg] (coupler frame)", title="contact arc at the table-implied F (quasi-static)")
    ax[2].legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=2)
    return fig


def coefficient_scan(R):
    """The mean K of Tables 3-4 (Eqs. 32-34) calibrated with F 0.5 m from E's mid-stroke
    position in 12 directions, for three gravity planes, against the paper's; and the
    contact-point arc L_arc of Eq. (29) there, against the wear range the paper's K needs
    and the bushing circumference (the absolute coefficient hinges on what the paper leaves
    open)."""
    scan, per_qs = R.run("coefficient_scan"), R.run("period_quasistatic")
    fig, ax = plt.subplots(1, 2, figsize=(11, 4))
    dirs = scan["scan_direction"].values
    for i, g in enumerate(scan["scan_gravity"].values):
        for side, mk in (("B1", "o-"), ("B2", "s--")):
            ax[0].semilogy(dirs, scan["scan_K_table_mean"].sel(side=side).values[i], mk, ms=3,
                           label=f"{side}, g = {g:g} m/s²")
        ax[1].semilogy(dirs, _mm(scan["scan_L_arc"].values[i]), "o-", ms=3, label=f"g = {g:g} m/s²")
    for side, col in (("B1", "k"), ("B2", "gray")):
        ax[0].axhline(R.value(f"k_mean_{side.lower()}", "paper_value"), color=col, lw=1, ls=":", label=f"paper mean {side}")
    ax[0].set(xlabel="direction of F from E [deg]", ylabel="mean K [1/Pa] (table units)", title="calibrated coefficient")
    ax[0].legend(fontsize=6, ncol=3, loc="upper center", bbox_to_anchor=(0.5, -0.16))
    ax[1].axhline(R.value("implied_wear_range_b1"), color="k", ls=":", label="wear range the paper's K needs")
    ax[1].axhline(_mm(2 * np.pi * float(per_qs["bushing_radius"])), color="r", lw=0.8, label="bushing circumference")
    ax[1].set(xlabel="direction of F from E [deg]", ylabel="contact-point arc L_arc [mm]", title="wear range of Eq. (29)")
    ax[1].legend(fontsize=6, ncol=2, loc="upper center", bbox_to_anchor=(0.5, -0.16))
    return fig


def load_point_fit(R):
    """The load point estimated from Tables 3-4: the misfit mean ln(K_p ours / K_p paper)
    over F's direction, its zeros marked by where the wear sits (Sec. 4.2); and the local
    Archard groove of side B1 at 86 h at the assumed and an estimated F against the paper's
    uniform depth (Eq. 29, Fig. 14), with the 8 measuring points of Eq. (33)."""
    fit = R.run("load_point_fit")
    fig, ax = plt.subplots(1, 2, figsize=(11, 4))
    for i, g in enumerate(fit["fit_gravity"].values):
        ax[0].plot(fit["fit_direction"], fit["fit_misfit"].values[i], "o-", ms=3, label=f"g = {g:g} m/s²")
    for j in range(fit.sizes["fit_solution"]):
        r = fit.isel(fit_solution=j)
        ax[0].plot(float(r["fit_sol_direction"]), 0.0, "^" if float(r["fit_sol_upper_share"]) > 0.5 else "v",
                   color="k", ms=7)
    ax[0].axhline(0, color="k", lw=0.6)
    ax[0].set(xlabel="direction of F from E [deg]", ylabel="mean ln(K_p ours / K_p paper) [1]",
              title="load point from Tables 3-4 (▲ wear on the upper part)")
    ax[0].legend(fontsize=7)
    for name, ls in (("local_wear", "-"), ("local_wear_estimated", "--")):
        lw, label = R.run(name), name.replace("_", " ")
        c = centred_profile(lw)
        line, = ax[1].plot(_deg(c["rel"]), _mm(c["profile"]), ls, label=f"{label} (centre {_deg(c['centre']):.0f}°)")
        ax[1].axhline(_mm(float(lw["uniform_depth"][-1])), ls=ls, color="gray", lw=0.8)
        ax[1].plot(_deg(c["points"]), _mm(c["at_points"]), "o", color=line.get_color(), mfc="none", ms=5,
                   label=f"{label}: the 8 measuring points (Eq. 33)")
    ax[1].set_ylim(top=1.8 * ax[1].get_ylim()[1])                 # the legend above the profiles
    ax[1].set(xlabel="bushing angle θ from the worn region's centre [deg] (coupler frame)", ylabel="wear depth at 86 h [mm]",
              title="groove profile vs uniform depth (grey)")
    ax[1].legend(fontsize=7, loc="upper left")
    return fig


def groove(R):
    """The worn groove in the contact: side B1 at 86 h at the load point estimated from
    Tables 3-4, the worn profile in the contact gap against the mean-circle feedback and the
    paper's uniform depth (Eq. 29); and local / uniform - 1 at 86 h over the placement of the
    8 measuring points of Eq. (33)."""
    lw = R.run("local_wear_estimated")
    c, u = centred_profile(lw), float(lw["uniform_depth"][-1])
    fig, ax = plt.subplots(1, 2, figsize=(11, 4))
    for var_, ls, lab in (("local_profile_end", "-", "groove in the contact"),
                          ("circle_profile_end", "--", "mean-circle feedback")):
        ax[0].plot(_deg(c["rel"]), _mm(lw[var_].values[c["order"]]), ls, label=lab)
    ax[0].axhline(_mm(u), color="gray", lw=0.8, label="uniform depth (Eq. 29)")
    ax[0].plot(_deg(c["points"]), _mm(c["at_points"]), "o", mfc="none", color="k", ms=5, label="measuring points (Eq. 33)")
    ax[0].set(xlabel="bushing angle from the worn region's centre [deg]", ylabel="wear depth at 86 h [mm]",
              title="side B1, estimated F")
    ax[0].legend(fontsize=7, loc="upper left")
    x = np.arange(lw.sizes["placement"])
    ax[1].plot(x, 100 * (lw["placement_mean_depth"].values / u - 1), "o", label="groove in the contact")
    ax[1].plot([0], [100 * (float(lw["circle_mean_depth"][-1]) / u - 1)], "s", mfc="none",
               label="mean-circle feedback (baseline points)")
    ax[1].axhline(0, color="k", lw=0.6)
    ax[1].set_xticks(x, [f"shift {a:+g}\nspan ×{b:g}" for a, b in
                         zip(lw["placement_shift"].values, lw["placement_scale"].values)], fontsize=7)
    ax[1].set(ylabel="local / uniform − 1 at 86 h [%]", title="placement of the 8 points on the contact arc")
    ax[1].legend(fontsize=7)
    return fig


def contact_margin(R):
    """The load point as a distribution (Secs. 3.2, 4.2): the points Tables 3-4 allow over
    F's direction x distance coloured by their chi2 above the best, the continuous-contact
    margin min F_N / max F_N of every point against g (the counted row is the credible set's
    smallest), and that smallest margin at every re-check of the row (verdict evidence)."""
    post = R.run("load_point_posterior")
    rows = [r for r in R.table("verdict_evidence") if r["quantity"] == "continuous_contact_margin_fitted_f"]
    pt = {k: post[f"post_point_{k}"].values for k in ("direction", "distance", "gravity", "chi2", "credible",
                                                       "upper_share", "qs_margin")}
    up, cred = pt["upper_share"] > 0.5, pt["credible"] == 1      # wear on the upper part; credible
    # chi2 above the best upper-part point, clipped to the colour scale
    dchi2 = np.clip(pt["chi2"] - np.nanmin(np.where(up, pt["chi2"], np.nan)), 0, 50)
    fig, ax = plt.subplots(1, 3, figsize=(16, 4.6), gridspec_kw={"width_ratios": [1.2, 1.2, 1]},
                           layout="constrained")
    norm = plt.Normalize(0, 50)
    cmap = plt.get_cmap("viridis_r")
    for a, (x, y) in zip(ax[:2], ((pt["direction"], pt["distance"]), (pt["gravity"], pt["qs_margin"]))):
        a.plot(x[~up], y[~up], "x", color="0.6", ms=4, label="wear below the centre (excluded)")
        out = up & ~cred
        a.scatter(x[out], y[out], facecolors="none", edgecolors=cmap(norm(dchi2[out])), marker="o", s=28,
                  label="outside the 95 % region (open)")
        sc = a.scatter(x[cred], y[cred], c=dchi2[cred], cmap=cmap, norm=norm, marker="o", s=28,
                       edgecolors="k", linewidths=0.5, label="credible (95 % region)")
    wg, wm = float(post["post_worst_gravity"]), float(post["post_worst_qs_margin"])
    ax[1].plot(wg, wm, "*", color="tab:red", ms=12, label=f"credible set's edge, smallest margin ({wm:.3g})")
    fig.colorbar(sc, ax=ax[1], label="Δχ² from the best point [1]\n(likelihood ratio exp(−Δχ²/2))")
    ax[0].set(xlabel="direction of F from E's mid-stroke position [deg]", ylabel="distance of F from E [m]",
              title="load points the tables allow (all g, μ)")
    ax[0].legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2)
    ax[1].axhline(0.01, color="r", lw=1, ls="--", label="1 % rule")
    ax[1].set_yscale("log")
    ax[1].set(xlabel="gravity component in the plane of motion [m/s²]", ylabel="contact margin min F_N / max F_N [1]",
              title="contact margin of every load point")
    ax[1].legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2)
    vals = [float(r["value"]) for r in rows]
    cols = ["tab:green" if r["status"] == "pass" else "tab:red" if r["status"] == "fail" else "gray" for r in rows]
    ax[2].barh(np.arange(len(rows)), 100 * np.asarray(vals), color=cols)
    ax[2].axvline(1.0, color="r", lw=1, ls="--", label="1 % rule")
    ax[2].set_yticks(np.arange(len(rows)), [r["variant"] for r in rows], fontsize=7)
    ax[2].invert_yaxis()
    status = R.row("continuous_contact_margin_fitted_f")["status"]
    ax[2].set(xlabel="smallest margin over the credible set [%]", xlim=(0, 1.3 * 100 * max(vals + [0.01])),
              title=f"every re-check (green pass, red fail): {status}")
    ax[2].legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16))
    return fig


def fig15(R):
    """Fig. 15: the cumulative wear of B1 and B2 predicted from 10 h to 86 h (quasi-static
    joint, 2-h intervals) against the measured points of Tables 3-4, beside the model
    variants (no wear update, swept-patch wear range, the worn bushing fed back into the
    stiff dynamic joint) and the 86-h band of the load points estimated from Tables 3-4."""
    wp, wdyn, fit = R.run("wear_prediction"), R.run("wear_dynamic"), R.run("load_point_fit")
    lines = ((wp, "o-", {"ms": 3}, "predicted (quasi-static, 2 h)"), (R.run("wear_no_update"), ":", {}, "without wear_update"),
             (R.run("wear_swept_patch"), "-.", {"lw": 0.8}, "wear range L_arc+|AB|"))
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for side, col in (("B1", "tab:blue"), ("B2", "tab:orange")):
        for d, fmt, kw, lab in lines:
            ax.plot(d["hour"], _mm(d["wear_predicted"].sel(side=side)), fmt, color=col, label=f"{side} {lab}", **kw)
        hours, h = measured_wear(wp, side)
        ax.plot(hours, _mm(h), "s", color=col, mfc="none", label=f"{side} measured (Tables 3-4)")
    ax.plot(wdyn["hour"], _mm(wdyn["wear_predicted"].sel(side="B1")), "x--", color="k",
            label=f"B1 stiff dynamic joint with wear feedback, {run_attrs(wdyn)['resolution']['interval_h']:g} h")
    for side, col in (("B1", "tab:blue"), ("B2", "tab:orange")):   # band of the estimated load points
        w = fit["fit_sol_wear_86h"].sel(side=side).values[fit["fit_sol_upper_share"].values > 0.5]
        w86 = _mm(np.array((w.min(), w.max())))     # wear on the upper part: smallest, largest
        ax.errorbar([86.0], [0.5 * (w86.max() + w86.min())], yerr=[[0.5 * (w86.max() - w86.min())]],
                    color=col, capsize=4, lw=2, label=f"{side} 86 h, load points estimated from Tables 3-4")
    ax.axvline(float(wp["hour"][0]), color="gray", lw=0.6)
    ax.set(xlabel="operating time [h]", ylabel="cumulative wear depth [mm]", title="Fig. 15")
    ax.legend(fontsize=6.5, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return fig


def fig16(R):
    """Fig. 16 (the paper's error against measurements after 10 h, not in its text): left the
    in-sample calibration replay with the mean coefficient against Tables 3-4; right how far
    the model variants and a straight-line extrapolation of the measured rate lie from our
    B1 prediction (a model-to-model spread, not a prediction error)."""
    wp, wdyn = R.run("wear_prediction"), R.run("wear_dynamic")
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    for side in ("B1", "B2"):
        _, h = measured_wear(wp, side)
        ax[0].plot(wp["cal_hour"], 100 * (wp["wear_calibration_replay"].sel(side=side).values / h[1:] - 1.0),
                   "o-", label=side)
    ax[0].axhline(0, color="k", lw=0.6)
    ax[0].set(xlabel="t [h]", ylabel="(replay with mean K - measured) / measured [%]", title="Fig. 16 (in-sample, 2-10 h)")
    ax[0].legend(fontsize=7)
    for lab, d in (("without wear_update", R.run("wear_no_update")), ("wear range L_arc+|AB|", R.run("wear_swept_patch")),
                   (f"stiff dynamic joint ({run_attrs(wdyn)['resolution']['interval_h']:g} h)", wdyn)):
        hrs, rel = relative_to(wp, d)
        ax[1].plot(hrs, 100 * rel, "o-", ms=3, label=lab)
    hh, base = wp["report_hour"].values, wp["wear_report"].sel(side="B1").values   # the first 10 h's rate
    ax[1].plot(hh, 100 * (base[0] * hh / hh[0] / base - 1.0), label="linear extrapolation of measured rate")
    ax[1].set(xlabel="t [h]", ylabel="relative to our B1 prediction [%]", title="Fig. 16 substitute: model spread")
    ax[1].legend(fontsize=7)
    return fig


def fig17(R):
    """Fig. 17: the cumulative wear of B1 predicted with every interval length of the
    interval study (Sec. 3.3), against the measured points of Table 3."""
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for iv, d in interval_runs(R).items():
        ax.plot(d["hour"], _mm(d["wear_predicted"].sel(side="B1")), "o-" if iv >= 2 else "-", ms=4, lw=1,
                label=f"{iv:g} h ({int(d['n_simulations_per_side'])} simulations)")
    hours, h = measured_wear(R.run("wear_prediction"), "B1")
    ax.plot(hours, _mm(h), "ks", mfc="none", label="measured B1")
    ax.set(xlabel="t [h]", ylabel="cumulative wear B1 [mm]", title="Fig. 17")
    ax.legend(fontsize=7)
    return fig


def _vs_interval(R, base, title: str):
    """Figs. 18-19: the B1 prediction of every interval length longer than ``base`` (None:
    the finest) relative to that of ``base`` [%], at the measurement times both reach."""
    runs = interval_runs(R)
    base = min(runs) if base is None else base
    fig, ax = plt.subplots(figsize=(6.5, 4))
    for iv in (v for v in runs if v > base):
        hrs, rel = relative_to(runs[base], runs[iv])
        ax.plot(hrs, 100 * rel, "o-", ms=3, label=f"{iv:g} h vs {base:g} h")
    ax.set(xlabel="t [h]", ylabel="relative difference [%]", title=title)
    ax.legend(fontsize=7)
    return fig


def fig18(R):
    """Fig. 18 substitute (the paper compares with measurements after 10 h, not in its
    text): every interval length's B1 prediction relative to the finest interval's."""
    return _vs_interval(R, None, "Fig. 18 substitute: vs the finest interval")


def fig19(R):
    """Fig. 19: the 4, 8 and 16 h interval predictions of B1 relative to the 2 h one."""
    return _vs_interval(R, 2.0, "Fig. 19")


def cost_of_accuracy(R):
    """Cost of accuracy (the framework's table cost_of_accuracy): (a) the stiff integrators
    of the dynamic joint over rtol, with the explicit RK45 run's extrapolated time per
    period; (b) the quasi-static joint over its samples per period; (c) the wear at 86 h
    over the interval length against the interval method's exact limit; (d) the quasi-static
    wear per period against the dynamic reference and against its finest sampling."""
    coa = R.table("cost_of_accuracy")
    fig, ax = plt.subplots(1, 4, figsize=(20, 4.3), sharey=False)
    for a, entry, title in zip(ax, ("dynamic", "quasistatic", "interval"), (
            "one period, dynamic joint: implicit (and explicit RK45)", "one period, quasi-static joint",
            "wear at 86 h vs interval length")):
        accuracy_plot(coa, entry, a)
        a.set_title(title)
    ex = R.study("accuracy_explicit")      # step budget, time reached, extrapolated time per period
    for i in range(ex.sizes["run"]):
        rtol, steps, t, w = (float(ex[k][i]) for k in ("rtol", "steps", "t_reached", "period_wall_time"))
        ax[0].axvline(w, color="r", ls=":", lw=1)
        ax[0].annotate(f"RK45 rtol={rtol:g}: step budget {steps:.0f}\nreached {t:.3g} s, "
                       f"extrapolated {w:.3g} s/period", (w, 0.97), xycoords=("data", "axes fraction"),
                       fontsize=6, color="r", rotation=90, ha="right", va="top")
        ax[0].set_xlim(right=max(ax[0].get_xlim()[1], 10 ** np.ceil(np.log10(w))))   # in view
    # the quasi-static wear per period against the finest Radau run (model + sampling) and
    # against its own finest sampling
    st_qs, st_dyn = R.study("accuracy_quasistatic"), R.study("accuracy_dynamic")
    ref = st_dyn.isel(run=accuracy.finest_radau(st_dyn))
    G, n = st_qs["wear_factor"].values, st_qs["n_steps"].values
    ax[3].loglog(n, np.abs(G / float(ref["wear_factor"]) - 1.0) + 1e-16, "o-",
                 label=f"quasi-static vs Radau rtol={float(ref['rtol']):g}")
    ax[3].loglog(n, np.abs(G / G[np.argmax(n)] - 1.0) + 1e-16, "s--", label="quasi-static vs its finest")
    ax[3].set(xlabel="samples per period [1]", ylabel="relative error of wear per period [1]",
              title="quasi-static vs dynamic joint")
    ax[3].legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.2))
    ax[3].grid(True, which="both", alpha=0.3)
    return fig
