"""saw_chain's figures, each drawn from the results it declares (config ``figures``)."""
from __future__ import annotations

import numpy as np

from mechrepro import accuracy
from mechrepro.io import run_attrs
from mechrepro.plotting import plt
from mechrepro.units import from_si

from . import design
from . import identification as idf
from .analysis import error_budget_relative, load_range_against_K, paper_band, stage_one_end


def _preferred(idn) -> tuple[int, str]:
    """Index and name of the explanation the paper's six numbers select (the least χ² at the
    declared model error, the first of the run's model errors)."""
    best = int(idn["fit_chi2"].values[0].argmin())
    return best, idf.EXPLANATIONS[best][0]


def fig07(R):
    """Fig. 7: the tight-side velocity over one tooth period (difference method, exact
    derivative, textbook Eq. 23) against the paper's band and the measured mean (left), and
    every band side by side (right): the paper's, the measured one, the preferred
    explanation's (run ``identification``) and Eq. (1)'s, which the paper's lies 2 % above."""
    run, idn = R.run("fig07_fig08"), R.run("identification")
    K = run_attrs(run)["resolution"]["K"]
    t_ms, t1_ms = from_si(run["t"], "ms"), from_si(stage_one_end(run), "ms")
    best, best_name = _preferred(idn)
    pred = idn["fit_prediction"].values[0, best]
    lo, hi = paper_band(R.row("measured_velocity_mean"))
    v = run["tight_side_velocity"].values
    paper_lo, paper_hi = (R.value(q, "paper_value") for q in ("tight_side_velocity_min", "tight_side_velocity_max"))
    bands = {   # label: (low, high, colour)
        "measured": (lo, hi, "tab:green"),
        "paper's\nband": (paper_lo, paper_hi, "tab:red"),
        "preferred\nexplanation": (pred[0], pred[1], "tab:purple"),
        "Eq. (1)\n(model)": (float(v.min()), float(v.max()), "tab:blue"),
    }
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(10.5, 4.8), width_ratios=[2.2, 1.2])
    ax.axhspan(paper_lo, paper_hi, color="tab:red", alpha=0.12, lw=0, zorder=0,
               label=f"paper's predicted band {paper_lo}–{paper_hi} m/s")
    ax.axhspan(lo, hi, facecolor="none", edgecolor="tab:green", hatch="///", lw=0, zorder=0,
               label=f"measured {R.value('measured_velocity_mean', 'paper_value')} ± {(hi - lo) / 2:.1f} m/s")
    ax.plot(t_ms, run["tight_side_velocity"], "-", lw=2.2, label=f"difference method (K={K})")
    ax.plot(t_ms, run["tight_side_velocity_exact"], ":", color="k", lw=1.2, label="exact derivative")
    ax.plot(t_ms, run["tight_side_velocity_textbook"], "--", color="tab:orange", label="textbook, Eq. (23)")
    ax.axvline(t1_ms, color="gray", lw=0.6, ls="--")
    ax.annotate(f"t1 = {t1_ms:.3f} ms:\ndrive link seated", (t1_ms, 0.04), xycoords=("data", "axes fraction"),
                xytext=(4, 0), textcoords="offset points", fontsize=7, color="gray")
    ax.set(xlabel="t [ms]", ylabel="tight-side velocity [m/s]", title="Fig. 7")
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=3)
    for i, (label, (b_lo, b_hi, c)) in enumerate(bands.items()):
        bx.plot([i, i], [b_lo, b_hi], "-", color=c, lw=6, solid_capstyle="butt", alpha=0.8)
        for y, va in ((b_lo, "top"), (b_hi, "bottom")):
            bx.annotate(f"{y:.3f}", (i, y), xytext=(0, -3 if va == "top" else 3),
                        textcoords="offset points", ha="center", va=va, fontsize=7, color=c)
    bx.set_xticks(range(len(bands)), list(bands), fontsize=7)
    bx.set(xlim=(-0.6, len(bands) - 0.4), ylabel="band [m/s]", title=f"the bands, min to max (model at K={K})",
           ylim=(min(b[0] for b in bands.values()) - 0.06, max(b[1] for b in bands.values()) + 0.06))
    bx.grid(True, axis="y", alpha=0.3)
    print(f"preferred explanation '{best_name}': band {pred[0]:.4f} to {pred[1]:.4f} m/s against the "
          f"paper's {paper_lo} to {paper_hi} (rounds to {pred[0]:.2f} and {pred[1]:.2f}); Eq. (1): "
          f"{v.min():.4f} to {v.max():.4f} m/s, {paper_lo / v.min() - 1:.2%} and "
          f"{paper_hi / v.max() - 1:.2%} below the paper's ends")
    return fig


def _identification(R):
    """Run ``identification`` and the sprocket speed it was run at in r/min (the printed 6550)."""
    idn = R.run("identification")
    return idn, float(from_si(float(idn["sprocket_speed"]), "rpm"))


def identification_table(R) -> tuple[list, list]:
    """Table ``identification``: each explanation at each model error
    (:func:`.identification.table`)."""
    return idf.COLUMNS, idf.table(*_identification(R))


def identification_readings(R) -> tuple[list, list]:
    """Table ``identification_readings``: the readings under the joint explanation
    (:func:`.identification.reading_table`)."""
    return idf.READING_COLUMNS, idf.reading_table(*_identification(R))


def design_rules(R) -> tuple[list, list]:
    """Table ``design_rules``: each closed-form rule's largest error (:func:`.design.rule_table`)."""
    return design.RULE_COLUMNS, design.rule_table(R.run("design_maps"))


def identification(R):
    """What the paper's six numbers select (run ``identification``, ``identification.py``):
    χ² over the sprocket speed run for each pitch-radius reading (stretch profiled; 68 % and
    95 % levels), each explanation's χ² at the three model errors, and the pulls of the six
    numbers as printed and under the preferred explanation."""
    idn, rpm = _identification(R)
    best, best_name = _preferred(idn)
    names = [e[0] for e in idf.EXPLANATIONS]
    readings = [r.split(" ", 1)[1] for r in idn["reading"].attrs["long_name"].split(": ", 1)[1].split(", ")]
    errors = idn["model_error"].values
    fig, ax = plt.subplots(1, 3, figsize=(15, 5), width_ratios=[1.2, 1.1, 1],
                           gridspec_kw={"wspace": 0.45})
    s_rpm = idn["speed_factor"].values * rpm
    c0 = idn["joint_chi2"].values[0].min()
    for k, r in enumerate(readings):
        # eq1 and mean_pitch differ by 0.01 % in R: drawn wide and dashed so both show
        ax[0].plot(s_rpm, idn["joint_prof_speed"].values[0, k] - c0, lw=3.5 if r == "eq1" else 1.5,
                   ls="--" if r == "mean_pitch" else "-", alpha=0.6 if r == "eq1" else 1.0,
                   label=f"{r} (min Δχ² {idn['joint_chi2'].values[0, k] - c0:.1f})")
    for lev, ls in (("68", ":"), ("95", "--")):
        ax[0].axhline(idf.DCHI2[lev], color="gray", lw=0.8, ls=ls)
        ax[0].annotate(f"{lev} %", (1.0, idf.DCHI2[lev]), xycoords=("axes fraction", "data"),
                       xytext=(3, 0), textcoords="offset points", va="center", fontsize=7, color="gray")
    ax[0].set_yscale("symlog", linthresh=10)
    ax[0].set(xlabel="sprocket speed run [r/min]", ylabel=f"Δχ² [1] (model error {errors[0]:.1%}; linear below 10)",
              ylim=(0, 3e3), xlim=(6380, 6830))
    ax[0].legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2,
                 title="pitch-radius reading (stretch profiled)", title_fontsize=7)
    y = np.arange(len(names))
    for i, (me, mk) in enumerate(zip(errors, "os^")):
        ax[1].semilogx(idn["fit_chi2"].values[i], y, mk, ls="none", label=f"model error {me:.1%}")
    ax[1].set_yticks(y, names, fontsize=7)
    ax[1].set(xlabel="χ² of the best fit (6 numbers) [1]")
    ax[1].grid(True, axis="x", which="both", alpha=0.3)
    ax[1].legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=3)
    printed = names.index("as printed")
    x = np.arange(len(idf.DATA))
    ax[2].bar(x - 0.2, idn["fit_pull"].values[0, printed], 0.4, label="as printed")
    ax[2].bar(x + 0.2, idn["fit_pull"].values[0, best], 0.4, label=f"preferred: {best_name}")
    ax[2].axhline(0, color="k", lw=0.6)
    ax[2].set_xticks(x, ["band\nmin", "band\nmax", "meas.\nmean", "meas.\nfluct.", "load\nmin",
                         "load\nmax"], fontsize=7)
    ax[2].annotate("K fitted:\n≈ 0", (x[-1], 0), xytext=(0, 6), textcoords="offset points", ha="center",
                   fontsize=7)
    ax[2].set(ylabel="(prediction − paper) / σ [1]")
    ax[2].legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=1)
    return fig


def fig08(R):
    """Fig. 8: the total tight-side dynamic load over one period, difference method, exact
    derivative and textbook Eq. (23), with the paper's ranges (Sec. 4)."""
    run = R.run("fig07_fig08")
    t_ms, t1_ms = from_si(run["t"], "ms"), from_si(stage_one_end(run), "ms")
    fig, ax = plt.subplots(figsize=(6.5, 4))
    ax.plot(t_ms, run["dynamic_load_x"], "-", label=f"difference method (K={run_attrs(run)['resolution']['K']})")
    ax.plot(t_ms, run["dynamic_load_x_exact"], ":", color="k", label="exact derivative")
    ax.plot(t_ms, run["dynamic_load_x_textbook"], "--", label="textbook, Eq. (23)")
    for q, c in (("dynamic_load_min", "tab:blue"), ("dynamic_load_max", "tab:blue"),
                 ("textbook_load_min", "tab:orange"), ("textbook_load_max", "tab:orange")):
        ax.axhline(R.value(q, "paper_value"), color=c, lw=0.7, ls="-.")
    ax.plot([], [], color="gray", ls="-.", lw=0.7, label="paper's ranges (Sec. 4)")
    ax.axvline(t1_ms, color="gray", lw=0.5)
    ax.set(xlabel="t [ms]", ylabel="dynamic load F_dx [N]", title="Fig. 8")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return fig


def k_dependence(R):
    """The load's maximum and minimum against K (study ``cost_of_accuracy``): the maximum
    converges from below at first order and reaches the paper's 209.4 N at
    ``paper_equivalent_k``; the minimum converges from above to the exact value, never to the
    paper's; beyond the round-off limit (grey) noise moves both."""
    rng = load_range_against_K(R.study("cost_of_accuracy"))
    fig, ax = plt.subplots(1, 2, figsize=(9, 3.6))
    for a, end, paper_q in ((ax[0], "max", "dynamic_load_max"), (ax[1], "min", "dynamic_load_min")):
        method, exact = rng[end]
        a.semilogx(rng["K"], method, "o-", label="difference method")
        a.axhline(exact, color="k", ls=":", label="exact")
        a.axhline(R.value(paper_q, "paper_value"), color="tab:red", ls="-.", label="paper")
        a.axvspan(R.value("roundoff_limit_k"), rng["K"].max(), color="gray", alpha=0.15, lw=0)
        a.set(xlabel="K (steps per stage) [1]", ylabel=f"{end} F_dx [N]")
    ax[0].axvline(R.value("paper_equivalent_k"), color="tab:red", lw=0.6)
    ax[0].legend(fontsize=7)
    fig.suptitle("saw_chain: load range vs K")
    return fig


def cost_of_accuracy(R):
    """Cost of accuracy: the difference method's pointwise errors against the exact
    derivative vs K (truncation slope −1 down to an optimum, then round-off ~K², with the
    solver's estimate and bound), vs wall time (the framework's table ``cost_of_accuracy``,
    drawn by ``accuracy.plot``) and vs the work counted as samples computed, plain and
    Richardson-extrapolated peak load (run ``richardson``)."""
    coa = R.table("cost_of_accuracy")
    budget = error_budget_relative(R.study("cost_of_accuracy"))
    rich = R.run("richardson")
    fig, ax = plt.subplots(1, 3, figsize=(16, 4.4), gridspec_kw={"wspace": 0.3})
    for q in dict.fromkeys(r["quantity"] for r in coa):
        rows = [r for r in coa if r["quantity"] == q]
        ax[0].loglog([int(r["knob_value"]) for r in rows], [float(r["error"]) for r in rows], "o-", label=q)
    ax[0].loglog(budget["K"], budget["truncation"], "--", color="gray", lw=0.8, label="truncation estimate")
    ax[0].loglog(budget["K"], budget["roundoff"], ":", color="gray", lw=0.8, label="round-off bound")
    ax[0].axvline(R.value("roundoff_limit_k"), color="gray", lw=0.6)
    ax[0].axvline(R.value("roundoff_optimum_k"), color="tab:green", lw=0.6, ls="--", label="fitted optimum")
    ax[0].set(xlabel="K (steps per stage) [1]", ylabel="relative error vs exact [1]", ylim=(1e-9, 2))
    ax[0].grid(True, which="both", alpha=0.3)
    ax[0].legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=2)
    accuracy.plot(coa, ax=ax[1])  # the headline entry (the first of accuracy:)
    ax[2].loglog(rich["richardson_plain_samples"], rich["richardson_plain_error"], "o-",
                 label="plain difference method (one solve)")
    ax[2].loglog(rich["richardson_samples"], rich["richardson_error"], "s-",
                 label="Richardson (K/4, K/2, K)")
    for r in (1e-3, 1e-5):
        ax[2].axhline(r, color="gray", ls=":", lw=0.8)
    ax[2].set(xlabel="work: samples computed (2K + 1 per solve, counted) [1]",
              ylabel="relative error of the peak load [1]", title="cost of accuracy: work")
    ax[2].grid(True, which="both", alpha=0.3)
    ax[2].legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.2))
    return fig


def richardson(R):
    """Richardson extrapolation of the peak load (run ``richardson``, ``richardson.py``):
    error against the exact peak vs the finest K, plain (first order) and extrapolated
    E(K) = 2 q(K) − q(K/2) (second order), with its K/4 estimate and the K each needs for
    1e-3 and 1e-5."""
    rich = R.run("richardson")
    fig, ax = plt.subplots(figsize=(6.5, 3.8))
    Ks = rich["richardson_k"].values
    ax.loglog(Ks, rich["richardson_plain_error"], "o-", label="plain difference method")
    ax.loglog(Ks, rich["richardson_error"], "s-", label="Richardson (K/4, K/2, K)")
    ax.loglog(Ks, rich["richardson_estimate"], "--", color="tab:orange", lw=0.8, label="its estimate")
    for r in (1e-3, 1e-5):
        ax.axhline(r, color="gray", ls=":", lw=0.8)
    ax.grid(True, which="both", alpha=0.3)
    ax.set(ylabel="relative error of the peak load [1]", xlabel="finest K (steps per stage) [1]")
    ax.axvline(R.value("roundoff_limit_k"), color="gray", lw=0.6)
    ax.legend(fontsize=7)
    ax.set_title(f"peak load to 1e-3: K = {R.value('plain_k_for_rtol_1e3'):.0f} plain, "
                 f"{R.value('richardson_k_for_rtol_1e3'):.0f} Richardson; to 1e-5: Richardson "
                 f"{R.value('richardson_k_for_rtol_1e5'):.0f}, plain not below the round-off limit", fontsize=8)
    return fig


def design_maps(R):
    """Design maps from the exact closed form (run ``design_maps``: the guidelines the
    paper's conclusion promises): peak load, speed fluctuation and the textbook's error
    against teeth, pitch ratio, sprocket speed and tight-side links, the paper's chain
    starred; bottom row: each closed-form rule of ``design.py`` against the exact solution."""
    dm = R.run("design_maps")
    zs, ratios, links = dm["map_teeth"].values, dm["map_ratio"].values, dm["map_links"].values
    speeds_rpm = from_si(dm["map_speed"].values, "rpm")
    p = run_attrs(dm)["parameters"]["values_si"]
    paper_x = (p["teeth"], p["tie_strap_pitch"] / p["drive_link_pitch"], from_si(p["sprocket_speed"], "rpm"),
               p["tie_straps_tight_side"] + p["drive_links_tight_side"])
    fig, ax = plt.subplots(4, 4, figsize=(14, 11.5))
    rows = (("peak_load", "peak load F_dx [N]"), ("speed_fluctuation", "(Rω − v_min)/(Rω) [1]"),
            ("textbook_error", "textbook / exact peak − 1 [1]"))
    for i, (q, label) in enumerate(rows):
        for k, r in enumerate(dm["map_z_ratio"].values):
            line, = ax[i, 0].plot(zs, dm[f"z_{q}"].values[k], label=f"p1/p2 = {r:.3g}")
            if q == "peak_load":
                ax[i, 0].plot(zs, dm["z_peak_load_fixed_chain_speed"].values[k], "--", color=line.get_color())
        for k, z in enumerate(dm["map_ratio_teeth"].values):
            ax[i, 1].semilogx(ratios, dm[f"ratio_{q}"].values[k], label=f"z = {int(z)}")
        ax[i, 2].plot(speeds_rpm, dm[f"speed_{q}"].values)
        ax[i, 3].plot(2 * links, dm[f"links_{q}"].values)
        for a, x in zip(ax[i], paper_x):
            a.plot(x, float(dm[f"paper_{q}"]), "*", color="tab:red", ms=11, zorder=5)
        ax[i, 0].set_ylabel(label)
    ax[0, 0].plot([], [], "k-", label="fixed sprocket speed")
    ax[0, 0].plot([], [], "k--", label="fixed chain speed")
    ax[0, 0].set_yscale("log")
    ax[1, 0].set_yscale("log")
    for a in ax[1:3, 2:].ravel():   # independent of speed (and fluctuation of M, N): no offset noise
        a.ticklabel_format(axis="y", useOffset=False, style="plain")
        hi = a.get_lines()[0].get_ydata().max()
        a.set_ylim(0, 1.3 * max(hi, 1e-12))
    for a in ax[:3, 1]:
        a.set_xticks([0.2, 0.5, 1, 2, 5], ["0.2", "0.5", "1", "2", "5"])
        a.minorticks_off()
    ax[2, 2].set_xticks([2000, 6000, 10000, 14000])
    ax[0, 1].legend(fontsize=7)
    for a, xl in zip(ax[2], ("teeth z [1]", "p1 / p2 (p1 + p2 fixed) [1]", "sprocket speed [r/min]",
                             "tight-side links M + N (M = N) [1]")):
        a.set_xlabel(xl)
    rule_teeth, rule_ratios = dm["rule_teeth"].values, dm["rule_ratio"].values
    err = np.abs(dm["rule_error"].values)
    for k, rule in enumerate(design.RULES):
        ax[3, 0].semilogy(rule_teeth, np.maximum(err[k].max(axis=1), 1e-17), label=rule)
        ax[3, 1].semilogy(rule_ratios, np.maximum(err[k].max(axis=0), 1e-17), label=rule)
    ax[3, 0].set(xlabel="teeth z (worst pitch ratio 1-2) [1]", ylabel="|rule / exact − 1| [1]")
    ax[3, 1].set(xlabel="p1 / p2 (worst teeth 6-40) [1]")
    ax[3, 1].set_xscale("linear")
    for a in ax[3, 2:]:       # the legends of the first column, clear of the data
        a.axis("off")
    ax[3, 2].legend(*ax[0, 0].get_legend_handles_labels(), fontsize=8, loc="center",
                    title="maps over teeth z (first column)", title_fontsize=8)
    ax[3, 3].legend(*ax[3, 0].get_legend_handles_labels(), fontsize=8, loc="center",
                    title="closed-form rules (bottom row)", title_fontsize=8)
    fig.suptitle("saw_chain design maps from the exact solution; ★ the paper's chain")
    fig.subplots_adjust(hspace=0.35, wspace=0.3)
    return fig
