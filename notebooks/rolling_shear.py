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
# # rolling_shear — hydraulic rolling-shear linkage, selPSO and lever optimisation (Li & Wei)
#
# Re-derives Figs. 9–14, Table II and the numbers of Sec. 4 from Eqs. (1)–(9).
#
# **Conventions** (the printed equations contradict each other; see docs/rolling_shear.md):
# y points up (the overlap line is y = −s below the lower blade), so Eq. (6) becomes
# y_k = y_h − R(1 − cos β) — only then is the lowest point really the lowest point of the
# arc and constant under the pure rolling of Eq. (8); M20 rotates by +θ5 (the loop
# equations measure θ5 counter-clockwise and the text says β = θ5 − β2), M12 is kept as
# printed (rotation −β2).
#
# **Geometry.** The paper gives five lever lengths and the process data. Everything else
# (l2, l4, l8, l9, l11, α, β1, β2, d, h, R, the cut) is derived from stated design
# intents (`design.py`), each with a plausible range in the config: the *admissible family*.
# One intent, the guide-rod tilt, is fitted in every run to the paper's 1.4341 (a
# calibration row); 0.9327, −34.96 % and Table II are then independent checks, re-checked at
# the range ends of the other intents and under both readings of Eq. (8) and of the lever
# optimisation (frozen or re-derived carrier constants).

# %% tags=["parameters"]
paper = "rolling_shear"
results_dir = "results"
config_file = "config/papers/rolling_shear.yaml"
profile = "default"

# %%
import numpy as np
from scipy.interpolate import CubicSpline

from mechrepro.accuracy import cost_of_accuracy, plot
from mechrepro.models.rolling_shear import validation as V
from mechrepro.models.rolling_shear.blade import arc_points, carrier_points
from mechrepro.models.rolling_shear.geometry import Geometry
from mechrepro.models.rolling_shear.loops import pivots
from mechrepro.plotting import plt
from mechrepro.results import PaperResults

R = PaperResults(paper, results_dir, config_file, profile)
orig, popt, opt = R.run("original"), R.run("paper_optimised"), R.run("optimisation")
comp = iv = R.run("solver_comparison")
s = R.cfg.raw["parameters"]["s"]["value"]
huch = orig["huch"].values

# %% [markdown]
# ## The assembled linkage (start, middle and end of the cut)

# %%
# the run's own (calibrated) geometry, as the solver derived it
g = Geometry(**{k: float(orig[f"geometry_{k}"]) for k in ("l2", "l4", "l8", "l11", "alpha", "beta1",
                                                          "beta2", "d", "x_mid")},
             **{k: R.cfg.raw["parameters"][k]["value"] for k in ("l1", "l3", "l5", "l6", "l9", "l10",
                                                                 "h", "R", "s", "width")})
A, G = pivots(g)
fig, ax = plt.subplots(figsize=(9, 4.2))
for i, c in ((0, "tab:blue"), (len(huch) // 2, "tab:green"), (len(huch) - 1, "tab:red")):
    t = [float(orig[f"exact_theta{k}"][i]) for k in range(1, 7)]
    P = carrier_points(g, t[4], t[5])
    B = A + g.l1 * np.exp(1j * t[0])
    H = G + g.l2 * np.exp(1j * t[1])
    for a, b in ((0, P["D"]), (A, B), (B, P["C"]), (G, H), (H, P["I"]), (P["D"], P["I"]),
                 (P["D"], P["C"]), (P["D"], P["O"])):
        ax.plot([np.real(a), np.real(b)], [np.imag(a), np.imag(b)], "-o", color=c, ms=3, lw=1.2)
    xa, ya = arc_points(g, t[4], t[5], 1900 / g.R, 200)
    ax.plot(xa, ya, color=c, lw=2, label=f"huch = {huch[i]:.0f} mm")
ax.axhline(0, color="k", lw=0.8)
ax.axhline(-s, color="k", lw=0.6, ls=":")
ax.set(aspect="equal", xlabel="x [mm]", ylabel="y [mm]",
       title=f"Assembled linkage (calibrated tilt {float(orig['geometry_tilt']):.4f} rad), E at the origin")
ax.legend(fontsize=7)
R.save_figure(fig, "linkage")

# %% [markdown]
# ## The admissible family
# Left: H of the original levers against the guide-rod tilt at the configured other intents
# (the calibration picks the tilt where H = 1.4341). Right: the reduction the paper's
# Table II levers give in every grid member of the family, each calibrated on 1.4341.

# %%
fam = R.run("family")
fig, ax = plt.subplots(1, 2, figsize=(11, 3.8))
ax[0].plot(orig["family_tilt"], orig["family_h"], "o-", ms=3)
ax[0].axhline(R.cfg.reported["synthetic_horizontal_displacement_original"]["value"], color="k", ls=":",
              label="paper, 1.4341 mm")
ax[0].axvline(float(orig["geometry_tilt"]), color="tab:red", lw=0.8, label="calibrated tilt")
ax[0].set(xlabel="guide-rod tilt theta6_mid - pi [rad]", ylabel="H, original levers [mm]",
          yscale="log", title="family: H against the tilt")
ax[0].legend(fontsize=7)
red = fam["family_member_reduction"].values
car = fam["family_member_carrier_constants"].values.astype(str)
eq8 = fam["family_member_eq8_reading"].values.astype(str)
for k, (c, e) in enumerate([(c, e) for c in ("frozen", "rederived") for e in ("rotation", "literal")]):
    sel = (car == c) & (eq8 == e)
    ax[1].plot(np.full(sel.sum(), k) + np.linspace(-0.2, 0.2, sel.sum()), red[sel], "o", ms=3)
ax[1].axhline(R.cfg.reported["horizontal_displacement_reduction"]["value"], color="k", ls=":",
              label="paper, -34.96 %")
ax[1].set_xticks(range(4), ["frozen\nrotation", "frozen\nliteral", "re-derived\nrotation", "re-derived\nliteral"])
ax[1].set(ylabel="reduction by Table II's levers [%]", title="family grid, each member calibrated")
ax[1].legend(fontsize=7)
fig.tight_layout()
R.save_figure(fig, "family")

# %% [markdown]
# ## Fig. 9 — trajectory of the dynamic lowest points
# With Eq. (7) solved for θ5, θ6 at prescribed x_k on y = −s, the overlap is constant by
# construction; the figure shows how constant (round-off level).

# %%
fig, ax = plt.subplots(1, 3, figsize=(14, 3.8))
for ds, pre, lab in ((orig, "newton", "original levers"), (opt, "opt_selpso", "optimised (selPSO)"),
                     (popt, "newton", "paper's optimised levers")):
    ax[0].plot(ds[f"{pre}_x_k"], ds[f"{pre}_y_k"], "o-", ms=3, label=lab)
    ax[1].semilogy(ds["huch"], np.abs(ds[f"{pre}_y_k"] + s) + 1e-16, "o-", ms=3, label=lab)
ax[0].axhline(-s, color="k", ls=":", lw=0.8)
ax[0].set(xlabel="x_k [mm]", ylabel="y_k [mm]", ylim=(-s - 1, -s + 1),
          title="Fig. 9: lowest points, reverse-solved drive")
ax[1].set(xlabel="rolled length huch [mm]", ylabel="|y_k + s| [mm]", title="deviation from y = -s")
ax[0].legend(fontsize=7)
ax[2].plot(orig["crd_x_k"], orig["crd_y_k"], "o-", ms=3, color="tab:red",
           label="levers at constant rate (same end positions)")
ax[2].plot(orig["newton_x_k"], orig["newton_y_k"], "o-", ms=3, color="tab:blue",
           label="reverse-solved motion laws")
ax[2].axhline(0, color="k", lw=0.8)
ax[2].axhline(-s, color="k", ls=":", lw=0.8)
ax[2].set(xlabel="x_k [mm]", ylabel="y_k [mm]", title="contrast: original levers, other drive")
ax[2].legend(fontsize=7)
fig.tight_layout()
R.save_figure(fig, "fig09")


# %% [markdown]
# ## Figs. 10–11 — midpoint trajectory against trajectory 1 (Eq. 8)
# Reading of Eq. (8) set by the config's `eq8_reading` ("rotation": equal blade rotation,
# anchored at the first cut point; "literal": θ = huch/R, anchored mid-cut); the validation
# table re-checks every verdict under the other reading.

# %%
def midpoint_figure(ds, pre, title, extra=None):
    fig, ax = plt.subplots(1, 2, figsize=(10, 3.8))
    ax[0].plot(ds[f"{pre}_x_h"], ds[f"{pre}_y_h"], "o", ms=3, label="midpoint, Eq. (5)")
    ax[0].plot(ds[f"{pre}_x_traj1"], ds[f"{pre}_y_traj1"], "-", label="trajectory 1, Eq. (8)")
    ax[0].set(xlabel="x [mm]", ylabel="y [mm]", title=title)
    ax[1].plot(ds["huch"], ds[f"{pre}_horizontal_displacement"], "o-", ms=3,
               label=f"H = {float(ds[f'{pre}_synthetic_horizontal_displacement']):.3f} mm")
    if extra is not None:
        d2, p2, lab = extra
        ax[1].plot(d2["huch"], d2[f"{p2}_horizontal_displacement"], "s--", ms=3,
                   label=f"{lab}: H = {float(d2[f'{p2}_synthetic_horizontal_displacement']):.3f} mm")
    ax[1].axhline(0, color="k", lw=0.6)
    ax[1].set(xlabel="rolled length huch [mm]", ylabel="x_h - x_traj1 [mm]", title="horizontal displacement")
    for a in ax:
        a.legend(fontsize=7)
    return fig


R.save_figure(midpoint_figure(orig, "newton", "Fig. 10: original levers"), "fig10")
R.save_figure(midpoint_figure(popt, "newton", "Fig. 11: the paper's optimised levers (Table II)",
                              (opt, "opt_selpso", "our selPSO optimum")), "fig11")

# %% [markdown]
# ## Fig. 12 — selPSO fitness against iterations from different initial values (Eq. 9)

# %%
fig, ax = plt.subplots(figsize=(6.5, 4))
hist = iv["iv_fitness_history"].values
for k in range(hist.shape[0]):
    x0 = np.round(iv["iv_initial_value"].values[k], 2).tolist()
    branch = "design branch" if iv["iv_design_branch"].values[k] else "other assembly mode"
    ax.semilogy(np.arange(hist.shape[1]), hist[k], label=f"x0 = {x0} ({branch})")
ax.axhline(1e-11, color="k", ls=":", lw=0.8, label="G = 1e-11")
ax.set(xlabel="iteration", ylabel="fitness G [mm]",
       title=f"Fig. 12: selPSO on Eq. (9) at x_k = {float(iv['iv_cut_point_x_k']):.0f} mm")
ax.legend(fontsize=6)
R.save_figure(fig, "fig12")

# %% [markdown]
# ## Figs. 13–14 — motion laws of the driving links θ1, θ2

# %%
for k, name in ((1, "fig13"), (2, "fig14")):
    fig, ax = plt.subplots(figsize=(6.5, 4))
    ax.plot(popt["huch"], popt[f"newton_theta{k}"], "-", lw=2,
            label="paper's optimised levers (Table II), Newton")
    ax.plot(popt["huch"], popt[f"exact_theta{k}"], ":", color="k", label="paper's optimised levers, closed form")
    ax.plot(opt["huch"], opt[f"opt_selpso_theta{k}"], "--",
            label="our selPSO optimum (l1, l3, l10 undetermined)")
    ax.plot(orig["huch"], orig[f"newton_theta{k}"], "-.", label="original levers, Newton")
    th = comp["selpso_theta"].sel(angle=f"theta{k}").values
    ok = comp["selpso_design_branch"].values.astype(bool)
    ax.plot(comp["huch"].values[ok], th[ok], "o", ms=4, mfc="none", label="original, selPSO, design branch")
    if (~ok).any():
        ax.plot(comp["huch"].values[~ok], th[~ok], "x", ms=5, label="original, selPSO, other assembly mode")
    ax.set(xlabel="rolled length huch [mm]", ylabel=f"theta{k} [rad]",
           title=f"Fig. {12 + k}: motion law of theta{k}")
    ax.legend(fontsize=7)
    R.save_figure(fig, name)

# %% [markdown]
# ## Table II and the lever scans: which levers the objective determines

# %%
header, rows2 = V.table2(orig, popt, opt, R.cfg.raw)
R.write_table("table2", header, rows2)
for r in rows2:
    print(r)
scan = opt["scan_objective"].values
R.write_table("lever_scan", ["lever"] + [f"{f:+.3f}" for f in opt["scan_fraction"].values] + ["spread_mm"],
              [[lv] + [float(v) for v in scan[j]] + [float(opt["scan_spread"][j])]
               for j, lv in enumerate(opt["lever"].values.tolist())])

# %% [markdown]
# ## Solver comparison

# %%
header, rows3 = V.solver_comparison(comp)
R.write_table("solver_comparison", header, rows3)
for r in rows3:
    print(r)

# %% [markdown]
# ## Cost of accuracy
# Three knobs, one error measure: the max absolute error of the motion laws in rad (all six
# angles against the closed form — a point on the wrong assembly mode is an error of order
# 1 rad; for the cut-point knob, θ1, θ2 interpolated by cubic spline against the finest
# run), and the relative error of the objective H. Time: wall time of the whole stroke.

# %%
pts = R.study("coa_points")
names = R.cfg.runs_of("coa_points")
finest = R.run(names[int(np.argmax(pts["n_points"].values))])
H_ref = float(finest["newton_synthetic_horizontal_displacement"])
law_err = []
for name in names:
    ds = R.run(name)
    e = 0.0
    for k in (1, 2):
        ref = finest[f"newton_theta{k}"].values
        f = CubicSpline(ds["huch"].values, ds[f"newton_theta{k}"].values)
        e = max(e, float(np.max(np.abs(f(finest["huch"].values) - ref))))
    law_err.append(e)
coa_pts = cost_of_accuracy(paper, "n_points", pts["n_points"].values, pts["newton_stroke_time"].values,
                           {"motion_laws_rad": np.array(law_err),
                            "objective_H": np.abs(pts["newton_synthetic_horizontal_displacement"].values - H_ref) / H_ref},
                           reference="finest / closed form",
                           description="Newton stroke vs number of cut points; wall time of the whole stroke")

tol = R.study("coa_tolerance")
errs_t = np.max([np.max(np.abs(np.angle(np.exp(1j * (tol[f"newton_theta{k}"].values - tol[f"exact_theta{k}"].values)))),
                        axis=1) for k in range(1, 7)], axis=0)
H_exact = tol["exact_synthetic_horizontal_displacement"].values
coa_tol = cost_of_accuracy(paper, "newton_tol", tol["newton_tol"].values, tol["newton_stroke_time"].values,
                           {"motion_laws_rad": errs_t,
                            "objective_H": np.abs(tol["newton_synthetic_horizontal_displacement"].values - H_exact) / H_exact},
                           knob_units="mm", reference="closed form",
                           description="warm Newton vs tolerance; wall time of the whole stroke")

pso = R.study("coa_selpso")
budget = pso["pso_swarm"].values * pso["pso_iter"].values
H_ref_p = pso["exact_synthetic_horizontal_displacement_ref"].values
coa_pso = cost_of_accuracy(paper, "swarm_x_iter", budget, pso["selpso_stroke_time"].values,
                           {"motion_laws_rad": pso["selpso_pose_error"].values,
                            "objective_H": np.abs(pso["selpso_synthetic_horizontal_displacement"].values - H_ref_p) / H_ref_p},
                           reference="closed form",
                           description="selPSO vs swarm x iterations (no early stop); wall time of the whole stroke")

for d in (coa_pts, coa_tol, coa_pso):  # every knob is timed over the whole stroke
    d["wall_time"].attrs["long_name"] = "wall time of the whole stroke"
    # the motion-law error is absolute (rad), not relative as the shared builder labels it
    d["error_motion_laws_rad"].attrs.update(units="rad",
                                            long_name=f"max |theta - {d.attrs['reference']}|, motion laws")

# the paper's own resolution knob (particles x iterations of selPSO) is the headline
# cost_of_accuracy.nc that the cross-paper summary reads; the other two knobs beside it
R.write_dataset(coa_pso, "cost_of_accuracy")
R.write_dataset(coa_pts, "cost_of_accuracy_points")
R.write_dataset(coa_tol, "cost_of_accuracy_tolerance")
table = []
for d, knob in ((coa_pts, "n_points"), (coa_tol, "newton_tol"), (coa_pso, "swarm_x_iter")):
    for i in range(d.sizes["resolution"]):
        table.append([knob, float(d["resolution"][i]), float(d["wall_time"][i])] +
                     [f"{v.removeprefix('error_')}={float(d[v][i]):.3e}" for v in d.data_vars if v.startswith("error_")])
R.write_table("cost_of_accuracy", ["knob", "value", "stroke_wall_time_s", "errors"],
              [r[:3] + ["; ".join(r[3:])] for r in table])
fig, ax = plt.subplots(1, 3, figsize=(15, 4.2))
for a, d in zip(ax, (coa_pts, coa_tol, coa_pso)):
    with np.errstate(divide="ignore"):
        d = d.copy()
        for v in [v for v in d.data_vars if v.startswith("error_")]:
            d[v] = d[v].where(d[v] > 0, 1e-17)  # exact zeros drawn at the floor of the log axis
    plot(d, a)
    a.set_xlabel("wall time of the whole stroke [s]")
    a.set_ylabel("error: motion laws [rad], objective H [relative]")
    t = d["wall_time"].values
    if t.max() / t.min() > 10:  # minor labels only crowd an axis that spans decades
        a.xaxis.set_minor_formatter(plt.NullFormatter())
R.save_figure(fig, "cost_of_accuracy")

# %% [markdown]
# ## Validation table
# Built by the framework from the config's `reported:` block (rule `validate_rolling_shear`);
# shown here, never built here.

# %%
import pandas as pd  # noqa: E402

val = pd.read_csv(R.table_path("validation"))
print(val[["quantity", "paper_value", "reproduced_value", "status", "evidence"]].to_string())
