"""rolling_shear's figures, each drawn from the results it declares (config ``figures``)."""
from __future__ import annotations

import numpy as np

from mechrepro import accuracy
from mechrepro.plotting import log_ticks, plt

from . import validation as V
from .blade import linkage_at


def linkage(R):
    """The assembled linkage of the original levers at the start, middle and end of the cut
    (scene ``original``, closed-form motion laws), the overlap line y = −s and the plate over
    the rolled length, beside which the guide rod ED must stay (constraints.py)."""
    orig = R.run("original")
    s, huch = float(orig["geometry_s"]), orig["huch"].values
    fig, ax = plt.subplots(figsize=(9, 4.2))
    for i, c in ((0, "tab:blue"), (len(huch) // 2, "tab:green"), (len(huch) - 1, "tab:red")):
        L = linkage_at(orig, i)
        for a, b in L["links"]:
            ax.plot([np.real(a), np.real(b)], [np.imag(a), np.imag(b)], "-o", color=c, ms=3, lw=1.2)
        ax.plot(*L["blade"], color=c, lw=2, label=f"huch = {huch[i]:.0f} mm")
    ax.axhline(0, color="k", lw=0.8)
    ax.axhline(-s, color="k", lw=0.6, ls=":")
    # the plate (Table I: up to 50 mm thick) over the rolled length
    x_lo = float(orig["geometry_x_mid"]) - 0.5 * float(orig["geometry_width"])
    ax.fill_between([x_lo, x_lo + float(orig["geometry_width"])], 0, 50, color="0.6", alpha=0.5,
                    label="plate (50 mm, rolled length)")
    ax.set(aspect="equal", xlabel="x [mm]", ylabel="y [mm]",
           title=f"Assembled linkage (calibrated tilt {float(orig['geometry_tilt']):.4f} rad), E at the origin")
    ax.legend(fontsize=7)
    return fig


def family(R):
    """The admissible geometry family and Table II's result as a distribution: H of the
    original levers against the guide-rod tilt (the calibration picks H = 1.4341), the
    reduction by Table II's levers over the family grid (scene ``family``; buildable, only
    buildable out of plane, not buildable) and over the framework's members of family
    ``machine`` (table ``verdict_evidence``), against the paper's −34.96 % and its band."""
    orig, fam = R.run("original"), R.run("family")
    paper_red = R.value("horizontal_displacement_reduction", "paper_value")
    fig, ax = plt.subplots(1, 3, figsize=(15, 3.8))
    ax[0].plot(orig["family_tilt"], orig["family_h"], "o-", ms=3)
    ax[0].axhline(R.value("synthetic_horizontal_displacement_original", "paper_value"), color="k", ls=":",
                  label="paper, 1.4341 mm")
    ax[0].axvline(float(orig["geometry_tilt"]), color="tab:red", lw=0.8, label="calibrated tilt")
    ax[0].set(xlabel="guide-rod tilt theta6_mid - pi [rad]", ylabel="H, original levers [mm]",
              yscale="log", title="family: H against the tilt")
    ax[0].legend(fontsize=7)
    red = fam["family_member_reduction"].values
    built = fam["family_member_buildable"].values == 1.0
    oop = V.buildable_members(fam, **V.configured_constraints(R))["out_of_plane"] & ~built   # only out of plane
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
    return fig


def fig09(R):
    """Fig. 9: the trajectory of the dynamic lowest points with Eq. (7) solved for θ5, θ6 at
    prescribed x_k on y = −s (original, our selPSO optimum, Table II): constant overlap by
    construction, its deviation at round-off level; beside it the original levers driven at
    a constant rate, which does not keep the overlap."""
    orig, popt, opt = R.run("original"), R.run("paper_optimised"), R.run("optimisation")
    s = float(orig["geometry_s"])  # overlap (mm): the lowest point is held on y = -s
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
    return fig


def _midpoint(ds, pre, title, extra=None):
    """The blade midpoint's trajectory (Eq. 5) against trajectory 1 (Eq. 8) and their
    horizontal distance H over the cut, motion laws ``<pre>_*`` of run ``ds``; ``extra``
    (run, prefix, label) adds a second H curve."""
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


def fig10(R):
    """Fig. 10: the midpoint trajectory against trajectory 1 (Eq. 8, in the configured
    ``eq8_reading``) and the horizontal displacement H over the cut, original levers."""
    return _midpoint(R.run("original"), "newton", "Fig. 10: original levers")


def fig11(R):
    """Fig. 11: as Fig. 10 for the paper's optimised levers (Table II), with our selPSO
    optimum's H beside them."""
    return _midpoint(R.run("paper_optimised"), "newton", "Fig. 11: the paper's optimised levers (Table II)",
                     (R.run("optimisation"), "opt_selpso", "our selPSO optimum"))


def fig12(R):
    """Fig. 12: selPSO's fitness G (Eq. 9) against iterations from different initial values
    at one cut point (scene ``selpso_initial_values``), each start labelled by the branch it
    ends on (design branch, mirror assembly mode, outside the paper's ranges)."""
    iv = R.run("selpso_initial_values")
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
    return fig


def _motion_law(R, k: int):
    """The motion law of driving link θk over the cut: Table II's levers (Newton and closed
    form), our selPSO optimum, the original levers by Newton and by selPSO (scene
    ``solver_comparison``: design branch or other assembly mode)."""
    orig, popt, opt = R.run("original"), R.run("paper_optimised"), R.run("optimisation")
    comp = R.run("solver_comparison")
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
    return fig


def fig13(R):
    """Fig. 13: the motion law of the driving link angle θ1 over the cut (:func:`_motion_law`)."""
    return _motion_law(R, 1)


def fig14(R):
    """Fig. 14: the motion law of the driving link angle θ2 over the cut (:func:`_motion_law`)."""
    return _motion_law(R, 2)


def design_front(R):
    """Design under buildability (scene ``design``, front.py): each sampled lever set's H
    against its worst transmission angle over the stroke, buildable or not, the Pareto front,
    the paper's original and Table II designs and the recommended design (buildable at the
    strict range ends); beside it what bounds l6 along the front: the guide rod's gap to
    the plate, with H."""
    des = R.run("design")
    strict, cons = V.constraint_ends(R, max), V.configured_constraints(R)
    P = R.cfg.raw["parameters"]
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
    return fig


def selpso_branch(R):
    """selPSO's branch benchmark (study ``branch_spread``): the fraction of the cut points
    that converge on the design branch against the initial swarm's spread σ (median, mean
    and 10-90 % band over seeds, the paper's early stop), and the time per Eq. (9) solve of
    selPSO and of warm Newton, timed alike."""
    bs = R.study("branch_spread")
    P = R.cfg.raw["parameters"]
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
    return fig


def cost_of_accuracy(R):
    """Cost of accuracy (the framework's table, config ``accuracy:``): for each knob (cut
    points, tolerance, selPSO budget) the error of the motion laws (rad) and of the objective
    H (relative) against the stroke's wall time, one panel per entry and error kind."""
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
    return fig
