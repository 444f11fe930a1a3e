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

from mechrepro import accuracy
from mechrepro.models.rolling_shear import validation as V
from mechrepro.models.rolling_shear.blade import linkage_at
from mechrepro.plotting import log_ticks, plt
from mechrepro.results import PaperResults

R = PaperResults(paper, results_dir, config_file, profile)
orig, popt, opt = R.run("original"), R.run("paper_optimised"), R.run("optimisation")
comp, iv = R.run("solver_comparison"), R.run("selpso_initial_values")
paper_value = {r["quantity"]: r["paper_value"] for r in R.validation()}
s = float(orig["geometry_s"])  # overlap (mm): the lowest point is held on y = -s
huch = orig["huch"].values

# %% [markdown]
# ## The assembled linkage (start, middle and end of the cut)

# %%
fig, ax = plt.subplots(figsize=(9, 4.2))
for i, c in ((0, "tab:blue"), (len(huch) // 2, "tab:green"), (len(huch) - 1, "tab:red")):
    L = linkage_at(orig, i)
    for a, b in L["links"]:
        ax.plot([np.real(a), np.real(b)], [np.imag(a), np.imag(b)], "-o", color=c, ms=3, lw=1.2)
    ax.plot(*L["blade"], color=c, lw=2, label=f"huch = {huch[i]:.0f} mm")
ax.axhline(0, color="k", lw=0.8)
ax.axhline(-s, color="k", lw=0.6, ls=":")
# the plate (Table I: up to 50 mm thick) over the rolled length: the guide rod ED must stay
# beside it (constraints.py)
x_lo = float(orig["geometry_x_mid"]) - 0.5 * float(orig["geometry_width"])
ax.fill_between([x_lo, x_lo + float(orig["geometry_width"])], 0, 50, color="0.6", alpha=0.5,
                label="plate (50 mm, rolled length)")
ax.set(aspect="equal", xlabel="x [mm]", ylabel="y [mm]",
       title=f"Assembled linkage (calibrated tilt {float(orig['geometry_tilt']):.4f} rad), E at the origin")
ax.legend(fontsize=7)
R.save_figure(fig, "linkage")

# %% [markdown]
# ## The admissible family and Table II's result as a distribution
# Left: H of the original levers against the guide-rod tilt at the configured other intents
# (the calibration picks the tilt where H = 1.4341). Middle: the reduction the paper's
# Table II levers give over the family grid (scene `family`, each member calibrated on
# 1.4341): grey every calibrated member, colour those that can be built (constraints.py:
# guide rod beside the plate, rod joints over it, transmission, opening), hollow those
# that only the out-of-plane reading of the guide rod (`guide_rod_plane`) can build. Right: the same
# over the framework's members of family `machine` (joint corners and seeded samples;
# members refused as unbuildable or uncalibrated have no value). Both re-check the Table II
# verdicts: a member of either that can be built and passes makes them inconclusive (the
# grid's under either reading of the guide rod). The paper's -34.96 % is marked with its
# 5 % tolerance band.

# %%
fam = R.run("family")
paper_red = float(paper_value["horizontal_displacement_reduction"])
fig, ax = plt.subplots(1, 3, figsize=(15, 3.8))
ax[0].plot(orig["family_tilt"], orig["family_h"], "o-", ms=3)
ax[0].axhline(float(paper_value["synthetic_horizontal_displacement_original"]), color="k", ls=":",
              label="paper, 1.4341 mm")
ax[0].axvline(float(orig["geometry_tilt"]), color="tab:red", lw=0.8, label="calibrated tilt")
ax[0].set(xlabel="guide-rod tilt theta6_mid - pi [rad]", ylabel="H, original levers [mm]",
          yscale="log", title="family: H against the tilt")
ax[0].legend(fontsize=7)
red = fam["family_member_reduction"].values
built = fam["family_member_buildable"].values == 1.0
P = R.cfg.raw["parameters"]   # the configured constraints (mm, deg)
cons = dict(clearance=float(P["clearance"]["value"]), mu_min=float(P["transmission_min"]["value"]),
            plate_top=float(P["plate_thickness_max"]["value"]), opening=float(P["opening"]["value"]))
oop = V.buildable_members(fam, **cons)["out_of_plane"] & ~built   # only out of plane
car = fam["family_member_carrier_constants"].values.astype(str)
eq8 = fam["family_member_eq8_reading"].values.astype(str)
bins = np.arange(-60, 50, 2.5)
for k, (c, e) in enumerate([(c, e) for c in ("frozen", "rederived") for e in ("rotation", "literal")]):
    sel = (car == c) & (eq8 == e) & np.isfinite(red)
    x = np.full(sel.sum(), k) + np.linspace(-0.25, 0.25, sel.sum())
    nb = ~built[sel] & ~oop[sel]
    ax[1].plot(x[nb], red[sel][nb], "o", ms=2.5, color="0.75")
    ax[1].plot(x[oop[sel]], red[sel][oop[sel]], "o", ms=3.5, mfc="none", color=f"C{k}")
    ax[1].plot(x[built[sel]], red[sel][built[sel]], "o", ms=3.5, color=f"C{k}")
ax[1].plot([], [], "o", color="0.75", ms=3,
           label=f"calibrated, not buildable ({int((np.isfinite(red) & ~built & ~oop).sum())})")
ax[1].plot([], [], "o", color="C0", ms=3, label=f"buildable ({int((built & np.isfinite(red)).sum())})")
ax[1].plot([], [], "o", color="C0", mfc="none", ms=3,
           label=f"buildable only with the guide rod out of plane ({int((oop & np.isfinite(red)).sum())})")
ax[1].axhline(paper_red, color="k", ls=":", label="paper, -34.96 % (band: 5 %)")
ax[1].axhspan(paper_red * 1.05, paper_red * 0.95, color="k", alpha=0.12, lw=0)
ax[1].set_xticks(range(4), ["frozen\nrotation", "frozen\nliteral", "re-derived\nrotation", "re-derived\nliteral"])
ax[1].set(ylabel="reduction by Table II's levers [%]",
          title=f"family grid ({fam.sizes['member']} members, each calibrated): joint re-check")
ax[1].legend(fontsize=6.5, loc="upper center", bbox_to_anchor=(0.5, -0.22))
ev = [r for r in R.table("verdict_evidence")
      if r["quantity"] == "horizontal_displacement_reduction" and r["kind"] == "family"]
vals = np.array([float(r["value"]) if r["value"] not in ("", "nan") else np.nan for r in ev])
ok = np.isfinite(vals)
ax[2].hist(vals[ok], bins=bins, color="C0", label=f"{int(ok.sum())} of {len(vals)} members buildable and calibrated")
ax[2].axvline(paper_red, color="k", ls=":")
ax[2].axvspan(paper_red * 1.05, paper_red * 0.95, color="k", alpha=0.12, lw=0)
ax[2].set(xlabel="reduction by Table II's levers [%]", ylabel="members [1]",
          title="framework family 'machine': one member at a time")
ax[2].legend(fontsize=7)
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
    ax[1].semilogy(ds["huch"], ds[f"{pre}_overlap_deviation"] + 1e-16, "o-", ms=3, label=lab)
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
ax[2].legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.18))
fig.tight_layout()
R.save_figure(fig, "fig09")


# %% [markdown]
# ## Figs. 10–11 — midpoint trajectory against trajectory 1 (Eq. 8)
# Reading of Eq. (8) set by the config's `eq8_reading` ("rotation": equal blade rotation,
# anchored at the first cut point; "literal": θ = huch/R, anchored mid-cut); the validation
# table re-checks every verdict under the other reading.

# %%
def midpoint_figure(ds, pre, title, extra=None):
    fig, ax = plt.subplots(1, 2, figsize=(10, 4.4))
    # both trajectories span millimetres in x over a metres-long cut: x is drawn from the
    # midpoint's first position, padded so that neither curve sits on the frame
    x0 = float(ds[f"{pre}_x_h"].values[0])
    xh, xt = ds[f"{pre}_x_h"].values - x0, ds[f"{pre}_x_traj1"].values - x0
    ax[0].plot(xh, ds[f"{pre}_y_h"], "o-", ms=3, lw=0.8, label="midpoint, Eq. (5)")
    ax[0].plot(xt, ds[f"{pre}_y_traj1"], "s--", ms=3, mfc="none", lw=0.8, label="trajectory 1, Eq. (8)")
    lo, hi = min(xh.min(), xt.min()), max(xh.max(), xt.max())
    ax[0].set_xlim(lo - 0.15 * (hi - lo), hi + 0.15 * (hi - lo))
    ax[0].set(xlabel="x - x of the midpoint at the first cut point [mm]", ylabel="y [mm]",
              title=f"{title} (cut of {float(ds['huch'].values[-1]):.0f} mm)")
    ax[1].plot(ds["huch"], ds[f"{pre}_horizontal_displacement"], "o-", ms=3,
               label=f"H = {float(ds[f'{pre}_synthetic_horizontal_displacement']):.3f} mm")
    if extra is not None:
        d2, p2, lab = extra
        ax[1].plot(d2["huch"], d2[f"{p2}_horizontal_displacement"], "s--", ms=3,
                   label=f"{lab}: H = {float(d2[f'{p2}_synthetic_horizontal_displacement']):.3f} mm")
    ax[1].axhline(0, color="k", lw=0.6)
    ax[1].set(xlabel="rolled length huch [mm]", ylabel="x_h - x_traj1 [mm]", title="horizontal displacement")
    for a in ax:
        a.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2)
    fig.tight_layout()
    return fig


R.save_figure(midpoint_figure(orig, "newton", "Fig. 10: original levers"), "fig10")
R.save_figure(midpoint_figure(popt, "newton", "Fig. 11: the paper's optimised levers (Table II)",
                              (opt, "opt_selpso", "our selPSO optimum")), "fig11")

# %% [markdown]
# ## Fig. 12 — selPSO fitness against iterations from different initial values (Eq. 9)

# %%
fig, ax = plt.subplots(figsize=(10, 4))
hist = iv["iv_fitness_history"].values
for k in range(hist.shape[0]):
    x0 = np.round(iv["iv_initial_value"].values[k], 2).tolist()
    branch = ("design branch" if iv["iv_design_branch"].values[k] else
              "mirror mode, in the paper's ranges" if iv["iv_in_ranges"].values[k] else
              "outside the paper's ranges")
    ax.semilogy(np.arange(hist.shape[1]), hist[k], ["-", "--", ":", "-."][k % 4], lw=1.4,
                label=f"x0 = {x0}: {branch}")
ax.axhline(1e-11, color="k", ls=":", lw=0.8, label="G = 1e-11")
ax.set(xlabel="iteration [1]", ylabel="fitness G [mm]",
       title=f"Fig. 12: selPSO on Eq. (9) at x_k = {float(iv['iv_cut_point_x_k']):.0f} mm")
ax.legend(fontsize=6, loc="upper left", bbox_to_anchor=(1.01, 1.0))
fig.tight_layout()
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
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    R.save_figure(fig, name)

# %% [markdown]
# ## Table II and the lever scans: which levers the objective determines

# %%
R.write_table("table2", *V.table2(orig, popt, opt))
R.write_table("lever_scan", *V.lever_scan(opt))

# %% [markdown]
# ## Design under buildability: H against the force transmission
# Scene `design` (front.py): lever sets of the configured member (original levers
# calibrated on 1.4341) sampled over a wide box and refined, each judged by its H and its
# worst transmission angle over the stroke; grey the designs that cannot be built (a loop
# does not close inside the paper's ranges, or a constraint of constraints.py breaks),
# blue those that can, the line the Pareto front; the paper's original and Table II designs
# and the design we recommend (buildable at the strict ends of the constraints' ranges).

# %%
des = R.run("design")
strict = V.constraint_ends(R, max)
fig, ax = plt.subplots(1, 2, figsize=(12, 4.2))
sb = des["sample_buildable"].values == 1.0
sH, smu = des["sample_H"].values, des["sample_mu_worst"].values
ax[0].plot(sH[~sb], smu[~sb], ".", ms=2, color="0.75", label="loops close, not buildable")
ax[0].plot(sH[sb], smu[sb], ".", ms=2, color="tab:blue", label="buildable")
on = des["envelope_on_front"].values == 1.0
ax[0].plot(des["envelope_H"].values[on], des["envelope_mu_worst"].values[on], "k-o", ms=7, mfc="none",
           mew=1.5, label=f"Pareto front ({int(on.sum())} design{'s' if on.sum() != 1 else ''})")
for k, (name, mk) in enumerate((("paper, original levers", "s"), ("paper, Table II levers", "D"))):
    ax[0].plot(des["paper_H"].values[k], des["paper_mu_worst"].values[k], mk, ms=8, mfc="none",
               mew=1.5, color=f"C{k + 1}", label=name)
rec = V.recommended(des, **strict)
if rec is not None:
    ax[0].plot(des["envelope_H"].values[rec["index"]], rec["mu_worst"], "*", ms=14,
               color="tab:red", label="recommended (buildable at the strict range ends)")
ax[0].axhline(cons["mu_min"], color="k", ls=":", lw=0.8, label=f"transmission floor {cons['mu_min']:.0f} deg")
ax[0].set(xlabel="synthetic horizontal displacement H [mm]",
          ylabel="worst transmission angle over the stroke [deg]", title="objectives of the lever sets")
fig.legend(*ax[0].get_legend_handles_labels(), fontsize=7, loc="lower left", ncol=4,
           bbox_to_anchor=(0.02, 0.0))
l6 = des["envelope_levers"].sel(lever="l6").values
ax[1].plot(l6, des["envelope_rod_gap"].values, "o-", ms=3, label="guide rod beside the plate [mm]")
ax[1].axhline(cons["clearance"], color="k", ls=":", lw=0.8, label=f"clearance {cons['clearance']:.0f} mm")
ax[1].axhspan(min(P["clearance"]["range"]), max(P["clearance"]["range"]), color="k", alpha=0.1, lw=0,
              label="clearance's range")
ax[1].set(xlabel="guide rod l6 [mm]", ylabel="rod gap [mm]", title="what bounds l6: the rod's gap to the plate")
a2 = ax[1].twinx()
a2.plot(l6, des["envelope_H"].values, "s--", ms=3, color="tab:green", label="H [mm]")
a2.set_ylabel("H [mm]")
h1, l1_ = ax[1].get_legend_handles_labels()
h2, l2_ = a2.get_legend_handles_labels()
ax[1].legend(h1 + h2, l1_ + l2_, fontsize=7, loc="upper right")
fig.tight_layout(rect=(0, 0.1, 1, 1))
R.save_figure(fig, "design_front")
R.write_table("design_front", *V.design_front(des, strict=strict, **cons))

# %% [markdown]
# ## Solver comparison

# %%
R.write_table("solver_comparison", *V.solver_comparison(comp))

# %% [markdown]
# ## selPSO's branch benchmark: success against the initial spread
# Study `branch_spread`: selPSO with the paper's constants and early stop (G < 1e-11 mm) on
# Eq. (9) at every cut point, over seeds; left, the fraction of the cut points that converge
# on the design branch (median and the 10-90 % band over seeds) against the spread σ of the
# initial swarm about the rough initial value (`pso_init_scale`, assumed in [0.1, 1] rad);
# right, the time per Eq. (9) solve of selPSO and of warm Newton, both the mean over whole
# strokes with the poses given.

# %%
bs = R.study("branch_spread")
sig = bs["pso_init_scale"].values
rates = bs["selpso_branch_rate_seeds"].values          # run x seed
fig, ax = plt.subplots(1, 2, figsize=(11, 3.8))
ax[0].fill_between(sig, np.quantile(rates, 0.1, axis=1), np.quantile(rates, 0.9, axis=1),
                   color="tab:blue", alpha=0.25, lw=0, label="10-90 % over seeds")
ax[0].plot(sig, np.median(rates, axis=1), "o-", color="tab:blue", label="median over seeds")
ax[0].plot(sig, rates.mean(axis=1), "s--", ms=3, color="tab:orange", label="mean over seeds")
ax[0].axvspan(min(P["pso_init_scale"]["range"]), max(P["pso_init_scale"]["range"]), color="k",
              alpha=0.06, lw=0, label="pso_init_scale's range")
ax[0].set(xlabel="initial spread sigma [rad]", ylabel="cut points on the design branch [1]",
          ylim=(-0.02, 1.05), title=f"selPSO branch success ({rates.shape[1]} seeds, "
                                    f"{bs.sizes['cut']} cut points, early stop)")
ax[0].legend(fontsize=7, loc="lower left")
ax[1].semilogy(sig, bs["selpso_time_per_solve"].values, "o-", label="selPSO (seed 0)")
ax[1].semilogy(sig, bs["newton_time_per_loops_solve"].values, "s-", label="warm Newton")
ax[1].set(xlabel="initial spread sigma [rad]", ylabel="time per Eq. (9) solve [s]",
          title="time per solve, timed alike")
ax[1].legend(fontsize=7, loc="center right")
fig.tight_layout()
R.save_figure(fig, "selpso_branch")

# %% [markdown]
# ## Cost of accuracy
# Three knobs (config `accuracy:`, table built by the framework): the max absolute error of
# the motion laws in rad (all six angles against the closed form -- a point on the wrong
# assembly mode is an error of order 1 rad; for the cut-point knob, theta1, theta2
# interpolated by cubic spline against the finest run), and the relative error of the
# objective H. Time: wall time of the whole stroke.

# %%
coa = R.table("cost_of_accuracy")
# one panel per (entry, error kind): radians and relative errors never share an axis
panels = list(dict.fromkeys((r["accuracy"], r["error_kind"]) for r in coa))
ncol = 3
nrow = -(-len(panels) // ncol)
fig, ax = plt.subplots(nrow, ncol, figsize=(15, 4.6 * nrow), squeeze=False)
for a, (name, kind) in zip(ax.flat, panels):
    sel = [r for r in coa if r["error_kind"] == kind]
    accuracy.plot(sel, name, a)
    log_ticks(a.xaxis)
    log_ticks(a.yaxis)
    a.set_title(f"{name}: {kind} error", fontsize=9)
for a in ax.flat[len(panels):]:
    a.set_visible(False)
fig.tight_layout()
R.save_figure(fig, "cost_of_accuracy")

# %% [markdown]
# ## Validation table
# Built by the framework from the config's `reported:` block (rule `validate_rolling_shear`);
# shown here, never built here.

# %%
for r in R.validation():
    print(r["quantity"], r["paper_value"], r["reproduced_value"], r["status"], r["evidence"], sep=" | ")
