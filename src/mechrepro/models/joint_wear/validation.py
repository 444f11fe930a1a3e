"""Reproduced values of joint_wear; what the paper reports is in config/papers/joint_wear.yaml.

Each function reads the runs its quantities declare (``reads:``) and returns numbers; the
framework builds the rows, the verdicts and their robustness checks.
"""
from __future__ import annotations

import math

import numpy as np

from mechrepro.io import run_attrs
from mechrepro.levels import level_error
from mechrepro.validation import Quantities, Reproduced

from . import accuracy, wear
from .geometry import from_parameters

Q = Quantities("joint_wear")
SIDES = ("b1", "b2")


def _param_si(ds, name):
    return run_attrs(ds)["parameters"]["values_si"][name]


def _periods_predicted(ds) -> float:
    """Crank periods from the start to the end of a run's prediction."""
    return (float(ds["hour"][-1]) - float(ds["hour"][0])) * 3600.0 / float(ds["period"])


# ---- Tables 3-4 ---------------------------------------------------------------------------
@Q.register(*[f"k_{s}_p{i}" for s in SIDES for i in range(1, 6)], "k_mean_b1", "k_mean_b2")
def coefficients(R):
    ds = R.run("wear_prediction")
    out = {}
    for s in SIDES:
        K = ds["K_table"].sel(side=s.upper()).values
        for i, v in enumerate(K, start=1):
            q = f"k_{s}_p{i}"
            out[q] = Reproduced(float(v), f"paper/ours = {R.paper_value(q) / v:.4g}")
        km = float(ds["K_table_mean"].sel(side=s.upper()))
        out[f"k_mean_{s}"] = Reproduced(km, f"paper/ours = {R.paper_value(f'k_mean_{s}') / km:.4g}; "
                                             f"k = K/21 = {km / 21:.4g} m2/N")
    return out


@Q.register("k_mean_b1_in_assumption_range", "k_mean_b2_in_assumption_range",
            "k_mean_b1_scan_min", "k_mean_b1_scan_max", "k_mean_b2_scan_min", "k_mean_b2_scan_max")
def coefficient_scan(R):
    ds = R.run("coefficient_scan")
    out = {}
    for s in SIDES:
        K = ds["scan_K_table_mean"].sel(side=s.upper()).values
        lo, hi = float(np.nanmin(K)), float(np.nanmax(K))
        paper = R.cfg.reported[f"k_mean_{s}"]["value"]
        n = int(np.isfinite(K).sum())
        note = (f"over {n} of {K.size} load points x gravity planes ({K.size - n} refused: "
                "continuous contact lost): "
                f"K in [{lo:.3g}, {hi:.3g}] 1/Pa, a factor {hi / lo:.3g}; paper {paper:.5g}")
        out[f"k_mean_{s}_in_assumption_range"] = Reproduced(bool(lo <= paper <= hi), note)
        out[f"k_mean_{s}_scan_min"] = lo
        out[f"k_mean_{s}_scan_max"] = hi
    return out


@Q.register("k_archard_mean_b1", "k_archard_paper_b1", "implied_wear_range_b1")
def unit_chain(R):
    ds = R.run("wear_prediction")
    H = float(_param_si(ds, "hardness_bushing"))
    K_paper = R.cfg.reported["k_mean_b1"]["value"]
    k_paper = float(wear.k_from_table(K_paper, H))
    M = wear.periods_per_interval(float(_param_si(ds, "measurement_interval")) / 3600.0, float(ds["period"]))
    dh = float(np.mean(_param_si(ds, "measured_increment_B1"))) / M
    L = wear.implied_wear_range(k_paper, dh, float(ds["F_N_mean"]), float(ds["sliding_distance"]),
                                float(_param_si(ds, "width")))
    L_ours = float(ds["L_arc"])
    return {"k_archard_mean_b1": float(ds["K_archard_mean"].sel(side="B1")),
            "k_archard_paper_b1": float(wear.archard_dimensionless(k_paper, H)),
            "implied_wear_range_b1": Reproduced(L * 1e3, f"ours: L_arc = {L_ours * 1e3:.3g} mm "
                                                f"({math.degrees(float(ds['contact_arc_angle'])):.3g} deg)")}


@Q.register("k_mean_ratio_b1_b2", "k_pattern_b1", "k_pattern_b2",
            "wear_factor_trend_b1", "wear_factor_trend_b2")
def ratios(R):
    ds = R.run("wear_prediction")
    out = {"k_mean_ratio_b1_b2": float(ds["K_table_mean"].sel(side="B1") / ds["K_table_mean"].sel(side="B2"))}
    for s in SIDES:
        paper = np.array([R.cfg.reported[f"k_{s}_p{i}"]["value"] for i in range(1, 6)])
        ours = ds["K_table"].sel(side=s.upper()).values
        dev = (ours / ours.mean()) / (paper / paper.mean()) - 1.0
        out[f"k_pattern_{s}"] = Reproduced(float(np.max(np.abs(dev))),
                                           "per point: " + ", ".join(f"{d:+.2e}" for d in dev))
        dh = np.asarray(_param_si(ds, f"measured_increment_{s.upper()}"))
        G = ds["wear_factor_calibration"].sel(side=s.upper()).values
        paper_trend = (dh[-1] / paper[-1]) / (dh[0] / paper[0])
        out[f"wear_factor_trend_{s}"] = Reproduced(float(G[-1] / G[0]),
                                                   f"the table implies {paper_trend:.4f}")
    return out


# ---- Fig. 13 ------------------------------------------------------------------------------
@Q.register("contact_arc_steady_deg")
def arc_steady(R):
    ds = R.run("period_quasistatic")
    return Reproduced(math.degrees(float(ds["contact_arc_angle"])),
                      f"{float(ds['L_arc']) * 1e3:.3g} mm of the bushing; mean force "
                      f"{float(ds['F_N_mean']):.4g} N")


@Q.register("contact_arc_concentric_q90_deg")
def arc_concentric(R):
    ds = R.run("fig13_contact_points")
    psi, on = ds["contact_angle"].values, (ds["penetration"].values > 0).astype(float)
    # the same trajectory read at 1/4, 1/2 and all of its output samples: the statistic's
    # sampling error by the levels' estimator (the integrator's steps do not change)
    q = [math.degrees(wear.contact_arc_quantile(psi[::m], on[::m], 0.9)) for m in (4, 2, 1)]
    err = level_error(*q, 2.0, math.inf)[0]
    return Reproduced(math.degrees(float(ds["contact_arc_q90"])),
                      f"max-min over the output samples {math.degrees(float(ds['contact_arc_angle'])):.3g} deg "
                      f"(set by the impact, not well defined); sampling: {psi.size // 4}, {psi.size // 2}, "
                      f"{psi.size} samples give {q[0]:.4f}, {q[1]:.4f}, {q[2]:.4f} deg, error estimate "
                      f"{err:.2g} deg ({err / q[2] * 100:.2g} %)", error=err)


# ---- Sec. 3.2 -----------------------------------------------------------------------------
@Q.register("continuous_contact_dynamic", "min_penetration_dynamic")
def continuous_contact(R):
    ds = R.run("period_dynamic")
    d = float(ds["min_penetration"])
    return {"continuous_contact_dynamic": Reproduced(d > 0, f"min penetration {d:.3e} m"),
            "min_penetration_dynamic": d}


def weighted_quantiles(x, w, qs=(0.025, 0.5, 0.975)) -> np.ndarray:
    """Quantiles of a discrete distribution (values x, masses w; NaN and massless values
    left out): the smallest x whose cumulative mass reaches each q."""
    x, w = np.asarray(x, float), np.asarray(w, float)
    ok = np.isfinite(x) & (w > 0)
    return np.quantile(x[ok], qs, weights=w[ok], method="inverted_cdf")


@Q.register("continuous_contact_margin_fitted_f", "fitted_load_point_misfit",
            "load_point_posterior_g_credible_min", "load_point_posterior_arc_deg_median",
            "load_point_posterior_k_archard_b1_median", "load_point_posterior_wear_86h_b1_median",
            "load_point_posterior_wear_86h_b2_median")
def load_point_posterior(R):
    ds = R.run("load_point_posterior")
    w = ds["post_point_weight"].values
    cred = ds["post_point_credible"].values == 1
    fb = float(_param_si(ds, "calibration_wear_feedback"))
    col = {k: ds[f"post_point_{k}"].values for k in ("gravity", "distance", "friction", "direction",
                                                     "qs_margin", "arc", "chi2")}
    n, nc = int(np.isfinite(col["direction"]).sum()), int(cred.sum())
    margin = float(ds["post_margin_min"])
    if nc:
        wv = {k: float(ds[f"post_worst_{k}"]) for k in ("gravity", "friction", "distance", "direction", "qs_margin")}
        worst = (f"smallest at the credible set's edge g {wv['gravity']:.3g} m/s2, mu {wv['friction']:.3g}, "
                 f"F {wv['distance']:.3g} m at {wv['direction']:.2f} deg: quasi-static "
                 f"{wv['qs_margin']:.4g}, dynamic {float(ds['post_worst_dyn_margin']):.4g}; "
                 f"chi2 of the new-bushing reading {float(ds['post_chi2_new_bushing']):.1f} "
                 f"({'inside' if int(ds['post_new_bushing_credible']) else 'outside'} the region)")
        q_m = weighted_quantiles(col["qs_margin"], w)
        g_cred = np.unique(col["gravity"][cred])
        note = (f"{n} load points reproduce the mean of Tables 3-4 over the prior grid "
                f"(calibration_wear_feedback {fb:g}); {nc} form the {float(ds['post_credible_level']):.0%} "
                f"credible set (wear on the upper part), gravity nodes {', '.join(f'{g:.3g}' for g in g_cred)} "
                f"m/s2; quasi-static margin 2.5/50/97.5 % {q_m[0]:.3g} / {q_m[1]:.3g} / {q_m[2]:.3g}; {worst}")
    else:
        note = "no load point reproduces Tables 3-4 with the wear on the upper part"
    misfit = float(np.nanmax(np.abs(ds["post_point_misfit"].values))) if n else math.nan
    out = {"continuous_contact_margin_fitted_f": Reproduced(margin, note),
           "fitted_load_point_misfit": Reproduced(misfit, f"largest |mean ln(K ours / K paper)| over the {n} fitted F")}
    H = float(_param_si(ds, "hardness_bushing"))
    K = ds["post_point_K_table"].sel(side="B1").values
    h86 = {s: ds["post_point_wear_86h"].sel(side=s).values * 1e3 for s in ("B1", "B2")}
    kA = wear.archard_dimensionless(wear.k_from_table(K, H), H)
    for key, x, fmt in (("arc_deg_median", col["arc"], ".1f"), ("k_archard_b1_median", kA, ".4g"),
                        ("wear_86h_b1_median", h86["B1"], ".4f"), ("wear_86h_b2_median", h86["B2"], ".4f")):
        q = weighted_quantiles(x, w) if nc else np.full(3, math.nan)
        out[f"load_point_posterior_{key}"] = Reproduced(
            float(q[1]), f"posterior 2.5 / 50 / 97.5 %: {q[0]:{fmt}} / {q[1]:{fmt}} / {q[2]:{fmt}}")
    out["load_point_posterior_g_credible_min"] = Reproduced(
        float(col["gravity"][cred].min()) if nc else math.nan,
        f"prior nodes {', '.join(f'{g:.3g}' for g in ds['post_gravity'].values)} m/s2")
    return out


@Q.register("quasistatic_vs_dynamic_wear_per_period")
def qs_vs_dynamic(R):
    ref = R.run("period_dynamic_converged")
    qs = R.run("period_quasistatic")
    e = abs(float(qs["wear_factor"]) / float(ref["wear_factor"]) - 1.0)
    eF = abs(float(qs["F_N_mean"]) / float(ref["F_N_mean"]) - 1.0)
    rtol = float(run_attrs(ref)["resolution"]["rtol"])
    return Reproduced(e, f"against Radau rtol {rtol:g}; mean force {eF:.1e}")


# ---- Sec. 4.4-4.5 -------------------------------------------------------------------------
@Q.register("wear_86h_b1", "wear_86h_b2", "wear_86h_b1_vs_linear_extrapolation",
            "prediction_error_within_70h", "wall_time_prediction_one_side", "periods_replaced",
            "period_ratio")
def prediction(R):
    ds = R.run("wear_prediction")
    h10 = float(_param_si(ds, "measured_wear_B1")[-1])
    t_end = float(ds["hour"][-1])
    real = _periods_predicted(ds)
    n_side = float(ds["n_simulations_per_side"])
    return {"wear_86h_b1": float(ds["wear_at_end_B1"]) * 1e3,
            "wear_86h_b2": float(ds["wear_at_end_B2"]) * 1e3,
            "wear_86h_b1_vs_linear_extrapolation": float(ds["wear_at_end_B1"]) / (h10 * t_end / float(ds["hour"][0])) - 1.0,
            "prediction_error_within_70h": math.nan,
            "wall_time_prediction_one_side": float(ds["wall_time_wear"]) / 2.0,
            "periods_replaced": real,
            "period_ratio": real / n_side}


@Q.register("wall_time_every_period_extrapolated", "wall_time_ratio")
def every_period(R):
    ds, tp = R.run("wear_prediction"), R.run("timing_period_by_period")
    real = _periods_predicted(ds)
    n, wall = float(tp["pbp_sample_periods"]), float(tp["pbp_sample_wall_time"])
    total = wall / n * real
    return {"wall_time_every_period_extrapolated": Reproduced(total, f"{n:.0f} consecutive periods timed"),
            "wall_time_ratio": total / (float(ds["wall_time_wear"]) / 2.0)}


@Q.register("wall_time_every_period_dynamic_h")
def every_period_dynamic(R):
    dyn, ds = R.run("period_dynamic"), R.run("wear_prediction")
    return float(dyn["period_wall_time"]) * _periods_predicted(ds) / 3600.0


@Q.register("wear_86h_dynamic_b1", "wear_86h_dynamic_vs_quasistatic_b1", "wall_time_dynamic_prediction")
def dynamic_feedback(R):
    dyn = R.run("wear_dynamic")
    iv = float(run_attrs(dyn)["resolution"]["interval_h"])
    qs = _intervals(R)[iv]                      # the quasi-static run on the same schedule
    hd = float(dyn["wear_at_end_B1"])
    hq = float(qs["wear_report"].sel(side="B1")[-1])
    n = int(dyn["n_simulations_per_side"])
    Gd = dyn["wear_factor_prediction"].sel(side="B1").values
    return {"wear_86h_dynamic_b1": Reproduced(hd * 1e3, f"{n} dynamic periods + 5 calibration, {iv:g}-h intervals"),
            "wear_86h_dynamic_vs_quasistatic_b1": Reproduced(
                abs(hd / hq - 1.0), f"{iv:g}-h schedule for both; dynamic wear factor over the "
                                    f"intervals {np.nanmin(Gd):.4g}..{np.nanmax(Gd):.4g} N/m"),
            "wall_time_dynamic_prediction": float(dyn["wall_time_wear"])}


@Q.register("explicit_steps_per_period")
def explicit_steps(R):
    st = R.study("accuracy_explicit")
    dyn = R.study("accuracy_dynamic")
    ref = dyn.isel(run=accuracy.finest_radau(dyn))
    steps = float(st["steps"][0]) * float(st["period"][0]) / float(st["t_reached"][0])
    return Reproduced(steps, f"RK45 reached t = {float(st['t_reached'][0]):.3g} s in {float(st['steps'][0]):.0f} steps; "
                             f"Radau rtol {float(ref['rtol']):g}: {float(ref['steps']):.0f} steps per period")


# ---- interval method (Figs. 17-19) --------------------------------------------------------
def _intervals(R) -> dict:
    """{interval [h]: run} of the interval study."""
    st = R.study("intervals")
    return {float(r["interval_h"]): r for r in (st.isel(run=i) for i in range(st.sizes["run"]))}


def interval_differences(runs: dict, base: float = 2.0) -> dict:
    """Largest |relative difference| [%] of each longer interval's prediction vs ``base``,
    at the longer run's own interval nodes (Fig. 19)."""
    ref = runs[base]["wear_report"].sel(side="B1").values
    nodes = {iv: runs[iv]["report_is_node"].values > 0.5 for iv in sorted(runs) if iv > base}
    return {iv: float(np.max(np.abs(runs[iv]["wear_report"].sel(side="B1").values[n] / ref[n] - 1.0)) * 100.0)
            for iv, n in nodes.items()}


def inverse_radius_runs(R) -> dict:
    """The G = R0/R comparison (wear.inverse_radius_prediction) on the interval study's
    schedules, side B1: {interval: (nodes, h)}."""
    par = R.cfg.runs["wear_interval"]["parameters"]            # SI, the study's scene
    fb = from_parameters(par)
    return {iv: wear.inverse_radius_prediction(
        np.asarray(par["measured_wear_B1"], float), np.asarray(par["measured_increment_B1"], float),
        wear.calibration_hours(par), float(par["prediction_end"]) / 3600.0, iv, fb.period, fb.R_bush)
            for iv in _intervals(R)}


def inverse_radius_differences(R, base: float = 2.0) -> dict:
    """interval_differences of the G = R0/R comparison: longer intervals vs ``base`` [%]."""
    ir = inverse_radius_runs(R)
    nb, hb = ir[base]
    return {iv: float(np.max(np.abs(h / np.interp(n, nb, hb) - 1.0)) * 100.0)
            for iv, (n, h) in sorted(ir.items()) if iv > base}


@Q.register("wear_86h_b1_inverse_radius", "wear_86h_b1_mechanics_vs_inverse_radius")
def without_mechanics(R):
    h_ir = inverse_radius_runs(R)[2.0][1][-1]
    h_m = float(_intervals(R)[2.0]["wear_report"].sel(side="B1")[-1])
    d = inverse_radius_differences(R)
    note = "G = R0/R, no four-bar; Fig. 19 from it: " + ", ".join(f"{k:g} h {v:.3g} %" for k, v in d.items())
    return {"wear_86h_b1_inverse_radius": Reproduced(h_ir * 1e3, note),
            "wear_86h_b1_mechanics_vs_inverse_radius": Reproduced(h_m / h_ir - 1.0,
                                                                   f"mechanics {h_m * 1e3:.5f} mm, formula {h_ir * 1e3:.5f} mm")}


@Q.register("interval_error_grows", "interval_error_small")
def interval_rows(R):
    d = interval_differences(_intervals(R))
    ivs = sorted(d)
    grows = all(d[a] < d[b] for a, b in zip(ivs, ivs[1:]))
    f = inverse_radius_differences(R)
    note = ("max |rel diff| vs 2 h: " + ", ".join(f"{k:g} h {v:.3g} %" for k, v in d.items())
            + "; decided by the measured wear and G ~ 1/R, not the four-bar: the formula without "
            "mechanics gives " + ", ".join(f"{k:g} h {v:.3g} %" for k, v in f.items()))
    return {"interval_error_grows": Reproduced(grows, note),
            "interval_error_small": Reproduced(max(d.values()), note)}


@Q.register("simulations_2h", "simulations_4h", "simulations_8h", "simulations_16h")
def simulation_counts(R):
    runs = _intervals(R)
    return {f"simulations_{iv:g}h": float(runs[float(iv)]["n_simulations_per_side"])
            for iv in (2, 4, 8, 16)}


# ---- the load point estimated from Tables 3-4 -----------------------------------------------
@Q.register("load_point_fit_solutions", "load_point_fit_upper_part", "load_point_fit_arc_deg",
            "load_point_fit_wear_86h_b1_lo", "load_point_fit_wear_86h_b1_hi",
            "load_point_fit_wear_86h_b2_lo", "load_point_fit_wear_86h_b2_hi",
            "load_point_assumed_upper_share", "b1_worse_than_b2")
def load_point(R):
    fit = R.run("load_point_fit")
    n = fit.sizes["fit_solution"]
    up = fit["fit_sol_upper_share"].values > 0.5
    arcs = fit["fit_sol_arc"].values
    table = "; ".join(f"g {float(r['fit_sol_gravity']):g}: {float(r['fit_sol_direction']):.2f} "
                      f"+- {float(r['fit_sol_sigma']):.1e} deg, arc {float(r['fit_sol_arc']):.1f} deg, "
                      f"upper {float(r['fit_sol_upper_share']):.2f}, "
                      f"86 h B1 {float(r['fit_sol_wear_86h'].sel(side='B1', fit_band=0.0)) * 1e3:.4f} mm"
                      for r in (fit.isel(fit_solution=i) for i in range(n)))
    sel = fit.isel(fit_solution=np.flatnonzero(up)) if up.any() else fit
    w = {s: sel["fit_sol_wear_86h"].sel(side=s).values * 1e3 for s in ("B1", "B2")}
    qs = R.run("period_quasistatic")
    from .solver import contact_side
    ang = qs["contact_angle"].values + qs["phi2"].values       # psi = angle(n) - phi2
    cs = contact_side({"F_N": qs["F_N"].values, "v_T": qs["sliding_velocity"].values,
                       "nx": np.cos(ang), "ny": np.sin(ang)})
    wp = R.run("wear_prediction")
    ratio = float(wp["wear_at_end_B1"] / wp["wear_at_end_B2"])
    band = "over the estimates with the wear on the upper part, each +- its uncertainty"
    return {
        "load_point_fit_solutions": Reproduced(float(n), table),
        "load_point_fit_upper_part": Reproduced(float(up.sum()),
                                                f"of {n} estimates; the others put the wear below the bushing centre"),
        "load_point_fit_arc_deg": Reproduced(float(np.median(arcs[up] if up.any() else arcs)),
                                             f"median over the upper-part estimates; all: {arcs.min():.1f} .. {arcs.max():.1f} deg "
                                             f"(assumed F: {float(np.degrees(qs['contact_arc_angle'])):.2f} deg)"),
        "load_point_fit_wear_86h_b1_lo": Reproduced(float(w["B1"].min()), band),
        "load_point_fit_wear_86h_b1_hi": Reproduced(float(w["B1"].max()), band),
        "load_point_fit_wear_86h_b2_lo": Reproduced(float(w["B2"].min()), band),
        "load_point_fit_wear_86h_b2_hi": Reproduced(float(w["B2"].max()), band),
        "load_point_assumed_upper_share": Reproduced(cs["upper_share"],
                                                     f"wear-weighted mean contact direction {cs['wear_direction_deg']:.1f} deg from +x"),
        "b1_worse_than_b2": Reproduced(ratio, "86-h wear B1/B2: the planar model gives both sides one wear factor, so "
                                              "the ratio is the measured increments' (Tables 3-4); the model cannot decide it"),
    }


# ---- assumed constants at their range ends --------------------------------------------------
SENSITIVE = ("friction_coefficient", "contact_exponent", "d_max", "C_max_ratio")


@Q.register(*[f"sensitivity_{c.lower()}" for c in SENSITIVE])
def sensitivity(R):
    ds = R.run("constant_sensitivity")
    par = ds["sens_parameter"].values
    base = int(np.flatnonzero(par == "(assumed)")[0])

    def at(i, key):
        return float(ds[key].values[i])
    K0, h0 = at(base, "sens_K_table_mean"), at(base, "sens_wear_86h")
    out = {}
    for c in SENSITIVE:
        idx = np.flatnonzero(par == c)
        dK = max(abs(at(i, "sens_K_table_mean") / K0 - 1.0) for i in idx)
        parts = [f"{at(i, 'sens_value'):.4g}: K {at(i, 'sens_K_table_mean') / K0 - 1.0:+.2e}, "
                 f"86 h {at(i, 'sens_wear_86h') / h0 - 1.0:+.2e}, arc {at(i, 'sens_arc'):.3f} deg, "
                 f"qs-dyn {at(i, 'sens_qs_vs_dynamic'):+.1e}, {at(i, 'sens_dynamic_steps'):.0f} Radau steps"
                 for i in idx]
        out[f"sensitivity_{c.lower()}"] = Reproduced(dK, "largest |K/K_assumed - 1| at the range ends; " + "; ".join(parts))
    return out


# ---- local vs uniform wear ------------------------------------------------------------------
@Q.register("local_vs_uniform_86h_b1", "local_peak_to_mean_86h_b1",
            "local_vs_uniform_86h_b1_estimated_f", "local_peak_to_mean_86h_b1_estimated_f",
            "circle_vs_uniform_86h_b1", "circle_vs_uniform_86h_b1_estimated_f",
            "local_vs_uniform_placement_spread_estimated_f", "wall_time_local_over_uniform")
def local_vs_uniform(R):
    out = {}
    for scene, tag in (("local_wear", ""), ("local_wear_estimated", "_estimated_f")):
        ds = R.run(scene)
        m, pk, u = (float(ds[k][-1]) for k in ("local_mean_depth", "local_peak_depth", "uniform_depth"))
        c = float(ds["circle_mean_depth"][-1])
        info = (f"86 h: groove mean {m * 1e3:.4f} mm, peak {pk * 1e3:.3f} mm, uniform {u * 1e3:.4f} mm, "
                f"mean-circle feedback {c * 1e3:.4f} mm (peak/mean "
                f"{float(ds['circle_peak_depth'][-1]) / c:.2f}); contact arc "
                f"{math.degrees(float(ds['local_arc'])):.1f} deg, patch "
                f"{math.degrees(float(ds['local_AB_mean']) / (float(_param_si(ds, 'pin_radius')) + float(_param_si(ds, 'radial_clearance')))):.1f} deg; "
                f"k groove/uniform {float(ds['local_k']) / float(ds['local_k_uniform']):.3f}")
        out[f"local_vs_uniform_86h_b1{tag}"] = Reproduced(m / u - 1.0, info)
        out[f"local_peak_to_mean_86h_b1{tag}"] = Reproduced(pk / m, info)
        out[f"circle_vs_uniform_86h_b1{tag}"] = Reproduced(c / u - 1.0, info)
    r = ds["placement_mean_depth"].values / u - 1.0
    out["local_vs_uniform_placement_spread_estimated_f"] = Reproduced(
        float(r.max() - r.min()), "86 h, groove / uniform - 1 with the points "
        + ", ".join(f"shifted {a:+g} arc, span x{b:g}: {x:+.1%}" for a, b, x in
                    zip(ds["placement_shift"].values, ds["placement_scale"].values, r)))
    ds = R.run("local_wear")
    out["wall_time_local_over_uniform"] = Reproduced(
        float(ds["local_wall_time"]) / float(ds["local_uniform_wall_time"]),
        f"local {float(ds['local_wall_time']):.3g} s, uniform {float(ds['local_uniform_wall_time']):.3g} s")
    return out


# ---- effect costs in solver work --------------------------------------------------------------
@Q.register("effect_work_contact_damping", "effect_work_friction", "effect_work_gravity")
def effect_work(R):
    on = R.run("period_dynamic")
    out = {}
    for e in ("contact_damping", "friction", "gravity"):
        off = R.run(f"period_dynamic_no_{e}")
        out[f"effect_work_{e}"] = Reproduced(
            float(on["steps"]) / float(off["steps"]),
            f"Radau rtol 1e-5 steps {float(on['steps']):.0f} with / {float(off['steps']):.0f} without, "
            f"right-hand sides {float(on['nfev']):.0f} / {float(off['nfev']):.0f}; wall "
            f"{float(on['period_wall_time']) * 1e3:.3g} / {float(off['period_wall_time']) * 1e3:.3g} ms")
    return out
