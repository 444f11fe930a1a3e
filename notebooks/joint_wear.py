# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # joint_wear — revolute-joint wear of a four-bar with one clearance joint (Lai et al., 2018)
#
# Four-bar of Table 1 (crank 9.6 r/min), joint B with clearance (Table 2), load P at E
# towards a fixed point F.  Models: the dynamic clearance joint (Lankarani–Nikravesh contact,
# Eqs. 11–14, regularised Coulomb friction Eq. 15, stiff implicit integration) and the
# quasi-static continuous-contact joint (the paper's low-speed assumption); Archard wear
# (Eqs. 16–31), the equivalent wear coefficient calibrated on the first 10 h (Eqs. 32–34,
# Tables 3–4) and the interval method (Sec. 3.3) predicting 10 → 86 h.
#
# **Unit reading.** We read the equivalent wear coefficient as Archard's dimensional
# coefficient k = K/H in m²/N = 1/Pa (the unit Tables 3–4 print), with every other quantity
# of Eq. (32) in SI (F_N in N, S, w, L_arc in m).  Dimensionless Archard K = k·H with
# H = 21 HB = 2.06e8 Pa.  Young's moduli of Table 2 (printed "N/mm²") are read as Pa,
# d_max = 0.01 of Eq. (14) as mm, C_max = 0.01·K' numerically in N·s/m.
#
# **Measured data.** The paper's text gives the measured wear only for 2–10 h (Tables 3–4);
# the measured points after 10 h exist only in the lost Figs. 15–18.  Everything after 10 h
# here is therefore a prediction that cannot be scored against measurement.

# %% tags=["parameters"]
paper = "joint_wear"
results_dir = "results"
config_file = "config/papers/joint_wear.yaml"
profile = "default"

# %%
import numpy as np

from mechrepro.accuracy import cost_of_accuracy, plot
from mechrepro.io import run_attrs
from mechrepro.plotting import plt
from mechrepro.results import PaperResults
from mechrepro.validation import check, compare, info

R = PaperResults(paper, results_dir, config_file, profile)
raw = R.cfg.raw["parameters"]
fig13 = R.run("fig13_contact_points")
per_dyn, per_qs = R.run("period_dynamic"), R.run("period_quasistatic")
wp, wnu, wsp, wdyn = (R.run(n) for n in ("wear_prediction", "wear_no_update", "wear_swept_patch", "wear_dynamic"))
interval_runs = {float(run_attrs(d)["resolution"]["interval_h"]): d
                 for d in (R.run(n) for n in R.cfg.studies["intervals"])}
st_dyn, st_exp, st_qs = R.study("accuracy_dynamic"), R.study("accuracy_explicit"), R.study("accuracy_quasistatic")
h_meas = {s: np.array(raw[f"measured_wear_{s}"]["value"]) for s in ("B1", "B2")}   # mm
paper_k = {"B1": np.array([7.2992, 8.5114, 9.0665, 7.0839, 7.0981]) * 1e-11,     # Table 3
           "B2": np.array([5.0716, 5.8303, 6.2404, 4.8549, 4.8705]) * 1e-11}     # Table 4
paper_kmean = {"B1": 7.8118e-11, "B2": 5.3735e-11}
period = 60.0 / raw["crank_speed"]["value"]
M = 2 * 3600 / period
print(f"period {period:.4g} s, periods per 2 h M = {M:.6g}")

# %% [markdown]
# ## Fig. 13 — contact points on the bushing over a period
# From the paper's start (pin concentric), the first period contains the free flight, the
# impact and the rattling of the pin (a lightly damped "pendulum" mode of the clearance,
# ~1e3 rad/s, damped only by friction); the steady period (dynamic from the equilibrium
# contact state, and quasi-static) sweeps a narrow arc: in this planar model only the link
# weights and inertia turn the joint force relative to the coupler.

# %%
deg = np.degrees
wrap = lambda a: np.mod(deg(a), 360.0)   # noqa: E731  contact angle in [0, 360) deg
fig, ax = plt.subplots(1, 2, figsize=(10, 4))
tf, pf, df = fig13["t_full"].values, fig13["contact_angle_full"].values, fig13["penetration_full"].values
c = df > 0
ax[0].plot(tf[c], wrap(pf[c]), ".", ms=1.5, label="dynamic, concentric start (1st period)")
ax[0].plot(per_dyn["t"], wrap(per_dyn["contact_angle"].values), "-", label="dynamic, steady period")
ax[0].plot(per_qs["t"], wrap(per_qs["contact_angle"].values), "--", label="quasi-static continuous contact")
ax[0].set(xlabel="t [s]", ylabel="contact angle ψ on the bushing [deg]\n(coupler frame, 0 = direction C→B)", title="Fig. 13")
ax[0].legend(fontsize=7)
bins = np.linspace(np.floor(wrap(pf[c]).min()) - 1, np.ceil(wrap(pf[c]).max()) + 1, 80)
ax[1].hist(wrap(pf[c]), bins=bins, density=True, alpha=0.6, label="1st period (impact, rattling, sliding)")
ax[1].hist(wrap(per_dyn["contact_angle"].values), bins=bins, density=True, alpha=0.6, label="steady period")
ax[1].set(xlabel="contact angle ψ [deg]", ylabel="share of time in contact [1/deg]", title="distribution of contact points")
ax[1].legend(fontsize=7)
R.save_figure(fig, "fig13")
arc_steady = float(deg(per_dyn["contact_arc_angle"])); arc_first = float(deg(fig13["contact_arc_angle"]))
print(f"contact arc: steady {arc_steady:.2f} deg, first period incl. impact {arc_first:.1f} deg")

# %% [markdown]
# ## Tables 3 and 4 — equivalent wear coefficients (calibration, Eqs. 32–34)
# Our k_p = (Δh^P / M) / G_p with G_p = F̄_N S / (w L_arc) of the period simulated with the
# bushing enlarged to the measured state at the start of interval p.  The last columns give
# the paper's value divided by ours and by ours × M.

# %%
tables = {}
for side, name in (("B1", "table3"), ("B2", "table4")):
    k = wp["k_calibrated"].sel(side=side).values
    h = h_meas[side]
    dh = np.diff(np.r_[0.0, h])
    rows = [[f"P{i+1}", 2 * (i + 1), h[i], dh[i], paper_k[side][i], k[i], k[i] * M,
             paper_k[side][i] / k[i], paper_k[side][i] / (k[i] * M)] for i in range(h.size)]
    rows.append(["mean", "", "", "", paper_kmean[side], float(wp["k_mean"].sel(side=side)),
                 float(wp["k_mean"].sel(side=side)) * M,
                 paper_kmean[side] / float(wp["k_mean"].sel(side=side)),
                 paper_kmean[side] / (float(wp["k_mean"].sel(side=side)) * M)])
    R.write_table(name, ["point", "hour", "h_mm", "dh_mm", "paper_K_per_Pa", "ours_k_per_Pa",
                         "ours_k_times_M_per_Pa", "paper_over_ours", "paper_over_ours_times_M"], rows)
    tables[side] = rows
    for r in rows:
        print(side, r[0], f"paper {r[4]:.4e}  ours {r[5]:.4e} 1/Pa  paper/ours {r[7]:.4g}  paper/(ours*M) {r[8]:.4f}")

# %% [markdown]
# ## Figs. 15 and 16 — prediction 10 → 86 h, B1 and B2
# Fig. 16 of the paper is the error against measurements after 10 h, which the text does not
# give.  We show instead (left) the in-sample residual of the calibration — each measured
# interval replayed with the mean coefficient — and (right) how far the model variants and a
# straight-line extrapolation of the measured 10-h rate lie from our prediction: a
# model-to-model spread, not a prediction error.

# %%
hours_m = 2.0 * np.arange(1, 6)
fig, ax = plt.subplots(figsize=(7, 4.5))
for side, col in (("B1", "tab:blue"), ("B2", "tab:orange")):
    ax.plot(wp["hour"], wp["wear_predicted"].sel(side=side) * 1e3, "o-", ms=3, color=col, label=f"{side} predicted (continuous contact, 2 h)")
    ax.plot(wnu["hour"], wnu["wear_predicted"].sel(side=side) * 1e3, ":", color=col, label=f"{side} without wear_update")
    ax.plot(wsp["hour"], wsp["wear_predicted"].sel(side=side) * 1e3, "-.", color=col, lw=0.8, label=f"{side} wear range L_arc+|AB|")
    ax.plot(np.r_[0, hours_m], np.r_[0, h_meas[side]], "s", color=col, mfc="none", label=f"{side} measured (Tables 3-4)")
ax.plot(wdyn["hour"], wdyn["wear_predicted"].sel(side="B1") * 1e3, "x--", color="k",
        label=f"B1 dynamic clearance joint, {run_attrs(wdyn)['resolution']['interval_h']:g} h")
ax.axvline(10, color="gray", lw=0.6)
ax.set(xlabel="operating time [h]", ylabel="cumulative wear depth [mm]", title="Fig. 15")
ax.legend(fontsize=6.5)
R.save_figure(fig, "fig15")

fig, ax = plt.subplots(1, 2, figsize=(10, 4))
for side in ("B1", "B2"):
    G = wp["wear_factor_calibration"].sel(side=side).values
    replay = np.cumsum(float(wp["k_mean"].sel(side=side)) * G * M) * 1e3
    ax[0].plot(hours_m, (replay - h_meas[side]) / h_meas[side] * 100, "o-", label=side)
ax[0].axhline(0, color="k", lw=0.6)
ax[0].set(xlabel="t [h]", ylabel="(model - measured) / measured [%]", title="Fig. 16 (in-sample, 2-10 h)")
ax[0].legend(fontsize=7)
base = wp["wear_predicted"].sel(side="B1").values
hh = wp["hour"].values
lin = h_meas["B1"][-1] * 1e-3 * hh / 10.0
for lab, y in (("without wear_update", wnu["wear_predicted"].sel(side="B1").values),
               ("wear range L_arc+|AB|", wsp["wear_predicted"].sel(side="B1").values),
               (f"dynamic joint ({run_attrs(wdyn)['resolution']['interval_h']:g} h)", np.interp(hh, wdyn["hour"].values, wdyn["wear_predicted"].sel(side="B1").values)),
               ("linear extrapolation of measured rate", lin)):
    ax[1].plot(hh, (y - base) / base * 100, label=lab)
ax[1].set(xlabel="t [h]", ylabel="relative to our B1 prediction [%]", title="Fig. 16 substitute: model spread")
ax[1].legend(fontsize=7)
R.save_figure(fig, "fig16")

# %% [markdown]
# ## Figs. 17–19 — interval length
# Fig. 18 of the paper compares with measurements after 10 h (not in the text); ours compares
# with the finest interval of the study (the reference of the interval method).

# %%
ivals = sorted(interval_runs)
ref_iv = ivals[0]
ref = interval_runs[ref_iv]
def at(run, hours):
    return np.interp(hours, run["hour"].values, run["wear_predicted"].sel(side="B1").values)
fig, ax = plt.subplots(figsize=(7, 4.5))
for iv in ivals:
    d = interval_runs[iv]
    ax.plot(d["hour"], d["wear_predicted"].sel(side="B1") * 1e3, "o-" if iv >= 2 else "-", ms=4, lw=1,
            label=f"{iv:g} h ({int(d['n_simulations_per_side'])} simulations)")
ax.plot(np.r_[0, hours_m], np.r_[0, h_meas["B1"]], "ks", mfc="none", label="measured B1")
ax.set(xlabel="t [h]", ylabel="cumulative wear B1 [mm]", title="Fig. 17")
ax.legend(fontsize=7)
R.save_figure(fig, "fig17")

fig, ax = plt.subplots(figsize=(6.5, 4))
rel_ref = {}
for iv in ivals[1:]:
    d = interval_runs[iv]
    hrs = d["hour"].values
    e = (d["wear_predicted"].sel(side="B1").values - at(ref, hrs)) / at(ref, hrs) * 100
    rel_ref[iv] = np.max(np.abs(e))
    ax.plot(hrs, e, "o-", ms=3, label=f"{iv:g} h vs {ref_iv:g} h")
ax.set(xlabel="t [h]", ylabel="relative difference [%]", title=f"Fig. 18 substitute: vs finest interval {ref_iv:g} h")
ax.legend(fontsize=7)
R.save_figure(fig, "fig18")

fig, ax = plt.subplots(figsize=(6.5, 4))
rel2 = {}
two = interval_runs[2.0]
for iv in [v for v in ivals if v > 2]:
    d = interval_runs[iv]
    hrs = d["hour"].values
    e = (d["wear_predicted"].sel(side="B1").values - at(two, hrs)) / at(two, hrs) * 100
    rel2[iv] = np.max(np.abs(e))
    ax.plot(hrs, e, "o-", ms=3, label=f"{iv:g} h vs 2 h")
ax.set(xlabel="t [h]", ylabel="relative difference [%]", title="Fig. 19")
ax.legend(fontsize=7)
R.save_figure(fig, "fig19")
print("max |rel diff| vs 2 h [%]:", rel2, " vs finest [%]:", rel_ref)

# %% [markdown]
# ## Cost of accuracy
# (a) dynamic clearance joint: Radau/BDF over rtol, error of the wear per period (∝ wear
# factor G) and of the mean contact force against the finest Radau run; the explicit RK45
# point did not finish within its wall-time budget — its time per period is extrapolated from
# how far it got.  (b) quasi-static continuous contact over samples per period, against the
# same dynamic reference (what the model saves and what it loses).  (c) wear at 86 h against
# the interval length, against the finest interval.

# %%
def sel_method(st, m):
    idx = [i for i, v in enumerate(st["method"].values) if v == m]
    return st.isel(run=idx)
radau = sel_method(st_dyn, "Radau")
iref = int(np.argmin(radau["rtol"].values))
G_ref, F_ref = float(radau["wear_factor"][iref]), float(radau["F_N_mean"][iref])
coa_sets = {}
for m in sorted(set(st_dyn["method"].values)):
    s = sel_method(st_dyn, m)
    keep = np.array([not (m == "Radau" and i == iref) for i in range(s.sizes["run"])])
    s = s.isel(run=np.where(keep)[0])
    coa_sets[m] = cost_of_accuracy(paper, "rtol", s["rtol"].values, s["period_wall_time"].values,
                                   {f"wear_per_period_{m}": np.abs(s["wear_factor"].values / G_ref - 1),
                                    f"mean_force_{m}": np.abs(s["F_N_mean"].values / F_ref - 1)},
                                   reference=f"Radau rtol={radau['rtol'].values[iref]:g}",
                                   description=f"dynamic clearance joint, {m}")
qs = cost_of_accuracy(paper, "n_steps", st_qs["n_steps"].values, st_qs["period_wall_time"].values,
                      {"wear_per_period_quasistatic": np.abs(st_qs["wear_factor"].values / G_ref - 1),
                       "mean_force_quasistatic": np.abs(st_qs["F_N_mean"].values / F_ref - 1)},
                      reference=f"Radau rtol={radau['rtol'].values[iref]:g}", description="quasi-static continuous contact")
iv_arr = np.array(ivals[1:])
w86 = np.array([float(interval_runs[v]["wear_at_end_B1"]) for v in iv_arr])
w86_ref = float(interval_runs[ref_iv]["wear_at_end_B1"])
iv_wall = np.array([float(run_attrs(interval_runs[v])["wall_time_s"]) for v in iv_arr])
coa_iv = cost_of_accuracy(paper, "interval_h", iv_arr, iv_wall, {"wear_86h": np.abs(w86 / w86_ref - 1)},
                          reference=f"interval {ref_iv:g} h", knob_units="h",
                          description="wear of B1 at 86 h vs interval length")
main = coa_sets["Radau"]
R.write_dataset(main, "cost_of_accuracy")
R.write_dataset(qs, "cost_of_accuracy_quasistatic")
R.write_dataset(coa_iv, "cost_of_accuracy_interval")
for m, d in coa_sets.items():
    if m != "Radau":
        R.write_dataset(d, f"cost_of_accuracy_{m.lower()}")
rows_coa = []
for m, d in list(coa_sets.items()) + [("quasistatic", qs)]:
    for i in range(d.sizes["resolution"]):
        errs = [float(d[v][i]) for v in d.data_vars if v.startswith("error_")]
        rows_coa.append([m, float(d["resolution"][i]), float(d["wall_time"][i]), errs[0], errs[1]])
for i in range(coa_iv.sizes["resolution"]):
    rows_coa.append(["interval_h", float(coa_iv["resolution"][i]), float(coa_iv["wall_time"][i]),
                     float(coa_iv["error_wear_86h"][i]), float("nan")])
explicit_rows = []
for i in range(st_exp.sizes["run"]):
    explicit_rows.append(["RK45", float(st_exp["rtol"][i]), float(st_exp["period_wall_time"][i]),
                          float("nan"), float("nan")])
R.write_table("cost_of_accuracy", ["model", "knob", "wall_time_s", "error_wear_or_wear86", "error_mean_force"],
              rows_coa + explicit_rows)

fig, ax = plt.subplots(1, 3, figsize=(15, 4.3))
for m, d in coa_sets.items():
    plot(d, ax[0], annotate=(m == "Radau"))
plot(qs, ax[0], annotate=False)
for i in range(st_exp.sizes["run"]):
    w = float(st_exp["period_wall_time"][i])
    ax[0].axvline(w, color="r", ls=":", lw=1)
    ax[0].annotate(f"RK45 rtol={float(st_exp['rtol'][i]):g}\nunfinished: reached {float(st_exp['t_reached'][i]):.3g} s,\n"
                   f"extrapolated {w:.3g} s/period", (w, 1e-6), fontsize=6, color="r", rotation=90, ha="right")
ax[0].set_title("one period: dynamic (implicit, explicit) vs quasi-static")
plot(coa_iv, ax[1])
ax[1].set_title("wear at 86 h vs interval length")
# what the quasi-static model loses: its converged difference from the dynamic reference
ax[2].semilogx(st_qs["n_steps"], np.abs(st_qs["wear_factor"] / G_ref - 1), "o-", label="quasi-static vs dynamic ref.")
fin = st_qs["wear_factor"].values[np.argmax(st_qs["n_steps"].values)]
ax[2].semilogx(st_qs["n_steps"], np.abs(st_qs["wear_factor"] / fin - 1) + 1e-16, "s--", label="quasi-static vs its finest")
ax[2].set_yscale("log"); ax[2].set(xlabel="samples per period", ylabel="relative error of wear per period")
ax[2].legend(fontsize=7); ax[2].grid(True, which="both", alpha=0.3)
R.save_figure(fig, "cost_of_accuracy")
qs_model_error = abs(float(per_qs["wear_factor"]) / G_ref - 1)
print(f"quasi-static model error of the wear per period vs dynamic reference: {qs_model_error:.2e}")

# %% [markdown]
# ## Efficiency (Sec. 4.5)

# %%
n_per_side = int(wp["n_simulations_per_side"])
real_periods = (raw["prediction_end"]["value"] - 10) * 3600 / period
pbp_n, pbp_wall = float(wp["pbp_sample_periods"]), float(wp["pbp_sample_wall_time"])
pbp_total = pbp_wall / pbp_n * real_periods                       # quasi-static, one side
wall_pred = float(wp["wall_time_wear"]) / 2                        # one side (B1 and B2 ran)
dyn_period = float(per_dyn["period_wall_time"])
print(f"simulations per side {n_per_side}, real periods {real_periods:.0f}, ratio {real_periods / n_per_side:.1f}")
print(f"interval method (one side, incl. calibration): {wall_pred:.3g} s; period by period (quasi-static): "
      f"{pbp_wall / pbp_n * 1e3:.3g} ms/period x {real_periods:.0f} = {pbp_total:.3g} s (extrapolated from {pbp_n:.0f} consecutive periods)")
print(f"dynamic clearance joint, one period {dyn_period:.3g} s -> every period: {dyn_period * real_periods / 3600:.3g} h")

# %% [markdown]
# ## Validation table

# %%
rows = []
src = {"B1": "Table 3 (p. 2934)", "B2": "Table 4 (p. 2934)"}
note_units = ("SI reading k = K/H [1/Pa] with F_N [N], S, w, L_arc [m], dh = dh^P/M (Eqs. 32-34); "
              "our per-interval coefficients differ from the paper's by one constant factor "
              "(see paper_k_over_ours_times_M), i.e. the paper's unit chain / model factor, not the data")
for side in ("B1", "B2"):
    k = wp["k_calibrated"].sel(side=side).values
    for i in range(k.size):
        rows.append(compare(f"k_{side}_P{i+1}", f"{src[side]}, P{i+1}", paper_k[side][i], k[i], "1/Pa", 0.05, note_units))
    rows.append(compare(f"k_mean_{side}", f"{src[side]}, mean; Sec. 4.4 step 3", paper_kmean[side],
                        float(wp["k_mean"].sel(side=side)), "1/Pa", 0.05, note_units))
    kk = float(wp["k_mean"].sel(side=side))
    rows.append(info(f"k_mean_{side}_dimensionless_K", f"{src[side]} with H = 21 HB (Table 2)",
                     kk * raw["hardness_bushing"]["value"] * 9.80665e6, "1",
                     note="Archard K = k H in our reading; plausible range for dry Al on steel is 1e-4..1e-2"))
    rows.append(info(f"paper_k_over_ours_times_M_{side}", f"{src[side]}",
                     paper_kmean[side] / (kk * M), "1",
                     note="paper's mean / (our mean x M=1152): near 1 would mean the paper's coefficients are per 2-h "
                          "interval rather than per period; the residual depends on the assumed F, gravity and mu"))
    # the model factor's change with the enlarged bushing is implied by the table itself
    dh = np.diff(np.r_[0.0, h_meas[side]])
    paper_trend = (dh[-1] / paper_k[side][-1]) / (dh[0] / paper_k[side][0])
    G = wp["wear_factor_calibration"].sel(side=side).values
    rows.append(compare(f"calibration_factor_trend_{side}", f"{src[side]}: (dh5/K5)/(dh1/K1) = G(8 h)/G(0 h)",
                        paper_trend, G[-1] / G[0], "1", 0.005,
                        "how the simulated wear per period changes as the bushing grows 0 -> 8 h; "
                        "tolerance = rounding of the table's 3-4 digit entries"))
rows.append(compare("k_mean_ratio_B1_B2", "Tables 3-4, 7.8118/5.3735", paper_kmean["B1"] / paper_kmean["B2"],
                    float(wp["k_mean"].sel(side="B1") / wp["k_mean"].sel(side="B2")), "1", 0.005,
                    "unbalanced load: ratio of the two sides' coefficients"))
rows.append(info("wear_86h_B1", "Fig. 15 (curve lost; no number in the text)", float(wp["wear_at_end_B1"]) * 1e3, "mm",
                 note="prediction 10->86 h, 2-h intervals, continuous contact"))
rows.append(info("wear_86h_B2", "Fig. 15 (curve lost; no number in the text)", float(wp["wear_at_end_B2"]) * 1e3, "mm"))
rows.append(info("prediction_error_within_70h", "Fig. 16 / p. 2936: 'mainly under 5 % within 70 hours'", float("nan"), "%",
                 note="measured wear after 10 h is only in the lost figures: cannot be checked"))
rows.append(info("wear_86h_B1_vs_linear_extrapolation", "Tables 3 (rate of the first 10 h)",
                 float(wp["wear_at_end_B1"]) / (h_meas["B1"][-1] * 1e-3 * 8.6) - 1, "1",
                 note="our prediction relative to extending the measured 10-h mean rate"))
rows.append(check("continuous_contact_dynamic", "Sec. 3.2 / Conclusion 1: pin and bushing in continuous contact at low speed",
                  float(per_dyn["min_penetration"]) > 0,
                  f"min penetration over a steady dynamic period {float(per_dyn['min_penetration']):.3e} m"))
rows.append(check("continuous_contact_quasistatic", "Sec. 3.2: contact force never vanishes over the period",
                  float(per_qs["F_N_min"]) > 0, f"min F_N {float(per_qs['F_N_min']):.3g} N"))
rows.append(info("min_penetration_dynamic", "Sec. 3.2", float(per_dyn["min_penetration"]), "m"))
rows.append(check("quasistatic_matches_dynamic", "Sec. 3.2 low-speed assumption: wear per period within 1 % of the dynamic joint",
                  qs_model_error < 0.01, f"relative difference {qs_model_error:.2e}"))
rows.append(info("contact_arc_steady_deg", "Fig. 13 (angle psi; figure lost)", arc_steady, "deg"))
rows.append(info("contact_arc_first_period_deg", "Fig. 13, period from the concentric start", arc_first, "deg"))
rows.append(compare("simulations_2h", "Sec. 4.5: 38 = (86-10)/2", 38, n_per_side, "1", 0.0))
for iv, n_paper in ((4.0, 19), (8.0, 10), (16.0, 5)):
    if iv in interval_runs:
        rows.append(compare(f"simulations_{iv:g}h", "Sec. 4.5: 19, 10, 5 simulations for 4, 8, 16 h", n_paper,
                            float(interval_runs[iv]["n_simulations_per_side"]), "1", 0.0))
rows.append(compare("periods_replaced", "Sec. 4.5: 43776 = (86-10) x 60 x 9.6", 43776, real_periods, "1", 1e-9))
rows.append(compare("period_ratio", "Sec. 4.5: 43776 / 38", 43776 / 38, real_periods / n_per_side, "1", 1e-9,
                    "target of the issue: >= 1000"))
rows.append(info("wall_time_prediction_one_side", "Sec. 4.5 (no time given)", wall_pred, "s",
                 note="calibration (5) + prediction (38) one-period quasi-static simulations, one side"))
rows.append(info("wall_time_every_period_extrapolated", "Sec. 4.5 / Fig. 6", pbp_total, "s",
                 note=f"period-by-period wear (Fig. 6), {pbp_n:.0f} consecutive periods timed, x {real_periods:.0f}/{pbp_n:.0f}"))
rows.append(info("wall_time_ratio", "Sec. 4.5 'highly effective and efficient'", pbp_total / wall_pred, "1"))
rows.append(info("wall_time_every_period_dynamic_h", "Sec. 4.5 / Fig. 6 with the dynamic joint", dyn_period * real_periods / 3600, "h"))
mono = all(rel2[a] < rel2[b] for a, b in zip(sorted(rel2), sorted(rel2)[1:]))
rows.append(check("interval_error_grows", "Fig. 19 / p. 2937: the longer the interval, the larger the relative error", mono,
                  "max |rel diff| vs 2 h: " + ", ".join(f"{k:g} h {v:.3g} %" for k, v in rel2.items())))
rows.append(check("interval_error_small", "Sec. 4.5: relative errors 'on the whole small' (we take < 5 %)",
                  max(rel2.values()) < 5.0, f"largest {max(rel2.values()):.3g} % (16 h vs 2 h)"))
for iv, v in rel_ref.items():
    rows.append(info(f"interval_{iv:g}h_vs_finest_max_rel", f"Fig. 18 substitute (vs {ref_iv:g} h)", v, "%"))
R.write_validation(rows)
for r in rows:
    print(f"{r.status:5s} {r.quantity:42s} paper {r.paper_value:11.5g} ours {r.reproduced_value:11.5g} {r.unit}")

# %%
n_fail = sum(r.status == "fail" for r in rows)
n_pass = sum(r.status == "pass" for r in rows)
R.write_claim("partial", (
    f"{n_pass} rows pass, {n_fail} fail. Reproduced: the calibration procedure of Tables 3-4 (the per-interval "
    "pattern, the B1/B2 ratio and the model factor's change with the growing bushing agree with the tables), the "
    "interval method and its efficiency (38 simulations per side for 43 776 periods; 19/10/5 for 4/8/16 h), "
    "the continuous contact at 9.6 r/min (dynamic stiff model and quasi-static agree within "
    f"{qs_model_error:.1e}), the Fig. 19 trend. Not reproduced: the absolute values of the equivalent wear "
    "coefficients - in the SI reading k = K/H our coefficients are ~1/1200 of the paper's (a constant factor "
    "close to M = 1152, i.e. the paper's unit chain or wear-range length, together with the assumed load point F); "
    "Figs. 15-18's measured points after 10 h are not in the text, so the 86-h prediction cannot be scored."))
