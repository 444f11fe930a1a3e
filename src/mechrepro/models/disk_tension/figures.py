"""disk_tension's figures, each drawn from the results it declares (config ``figures``), and
what they draw, taken from the runs in SI."""
from __future__ import annotations

import textwrap
from functools import partial

import matplotlib.ticker as mticker
import numpy as np

from mechrepro import accuracy
from mechrepro.plotting import plt
from mechrepro.units import from_si

from . import design, identifiability as idf
from .design import RPM, by_clamp, eigen_and_eq9_times, lowest_critical_speed as lowest, rc_grid

ND = [0, 1, 2, 3, 4]


def mm(x):
    return from_si(np.asarray(x, float), "mm")


def matrix_table(R, scene: str, matrix: str) -> tuple[list, list]:
    """A modal matrix of run ``scene`` (Tables 1-2): header and rows ``[N_d, entries...]``."""
    da = R.run(scene)[matrix]
    return ["N_d"] + [str(n) for n in ND], [[int(n)] + [float(v) for v in da.sel(row=n).values]
                                            for n in da["row"].values]


#: Tables 1 ([K^(sigma)]) and 2 ([m^], Eq. 17), by the axisymmetric and the 2-D plate model
table1 = partial(matrix_table, scene="table12", matrix="k_sigma_hat")
table2 = partial(matrix_table, scene="table12", matrix="m_hat")
table1_plate2d = partial(matrix_table, scene="table12_plate2d", matrix="k_sigma_hat")
table2_plate2d = partial(matrix_table, scene="table12_plate2d", matrix="m_hat")


def effect_cold_warm(R, scenes=("table12", "table12_plate2d", "stressed_axisym",
                                "stressed_plate2d")) -> tuple[list, list]:
    """Table [scene, effect, warm s, cold s] of the memoised effects."""
    return ["scene", "effect", "warm_s", "cold_s"], [
        [scene, str(e), float(ds["effect_time"].values[i]), float(ds[f"{e}_time_cold"])]
        for scene, ds in ((s, R.run(s)) for s in scenes)
        for i, e in enumerate(ds["timed_effect"].values) if f"{e}_time_cold" in ds]


def fig03(R):
    """Fig. 3: the finite-element models of the disk: the 2-D Argyris mesh of the flexible
    annulus (the core r < r_f is clamped, meshed only for the free-disk plane-stress problem)
    and the radial cubic Hermite elements of the axisymmetric model."""
    t12, t12_2d = R.run("table12"), R.run("table12_plate2d")
    fig, axes = plt.subplots(1, 2, figsize=(11, 5.2), gridspec_kw={"width_ratios": [1.2, 1]})
    ax = axes[0]
    ax.triplot(mm(t12_2d["mesh_x"]), mm(t12_2d["mesh_y"]),
               t12_2d["mesh_cells"].values, lw=0.3, color="k")
    ax.add_patch(plt.Circle((0, 0), mm(t12_2d["clamp_radius"]), color="0.7", label="clamped r ≤ r_f"))
    ax.set(aspect="equal", xlabel="x [mm]", ylabel="y [mm]",
           title=f"Fig. 3: 2-D mesh ({t12_2d.sizes['mesh_cell']} triangles, "
                 f"{int(t12_2d['n_dofs'])} Argyris DOFs)")
    ax.legend(fontsize=8, loc="upper right")
    ax = axes[1]
    nodes = mm(t12["mesh_r"])
    ax.plot(nodes, np.zeros_like(nodes), "|", ms=12, color="k")
    ax.axvspan(0, nodes[0], color="0.8", label="clamped")
    ax.set(xlabel="r [mm]", yticks=[], xlim=(0, nodes[-1] * 1.02),
           title=f"axisymmetric model: {len(nodes) - 1} cubic Hermite elements × cos(N_d θ)")
    ax.legend(fontsize=8)
    return fig


def fig04(R):
    """Fig. 4: the thermal-analogy temperature of Eq. (4) (r_c = 65 mm, A = 50 degC, s = 5 mm),
    with the rolled width 4 s (Sec. 3.2)."""
    t12 = R.run("table12")
    fig, ax = plt.subplots(figsize=(6, 3.4))
    r = mm(t12["r"])
    ax.plot(r, from_si(t12["temperature"].isel(r_c=0), "degC"), "-")
    ax.axvspan(0, mm(t12["clamp_radius"]), color="0.85", label="clamped r ≤ r_f")
    rc65, s = float(t12["r_c"][0]), float(t12["width_used"])
    ax.axvspan(mm(rc65 - 2 * s), mm(rc65 + 2 * s), color="tab:orange", alpha=0.15,
               label="rolling width 4s")
    ax.set(xlabel="r [mm]", ylabel="T [°C]", title="Fig. 4: thermal-analogy temperature, Eq. (4)",
           xlim=(0, r.max()))
    ax.legend(fontsize=8)
    return fig


def fig05(R):
    """Fig. 5: the residual stress after rolling, sigma_r and sigma_theta along the radius (the
    load is axisymmetric, where the paper draws a contour on 1/12 of the disk): closed form for
    both in-plane conditions and the 2-D model's plane-stress P2 field (radial bin means)."""
    t12, t12_cl, t12_2d = R.run("table12"), R.run("table12_clamped"), R.run("table12_plate2d")
    r = mm(t12["r"])
    fig, ax = plt.subplots(figsize=(6.5, 4))
    for ds, ls in ((t12, "-"), (t12_cl, "--")):
        bc = ds["sigma_theta"].attrs["inplane_bc"]
        ax.plot(r, from_si(ds["sigma_theta"].isel(r_c=0), "MPa"), ls, color="C3", label=f"σ_θ, {bc}")
        ax.plot(r, from_si(ds["sigma_r"].isel(r_c=0), "MPa"), ls, color="C0", label=f"σ_r, {bc}")
    rb = mm(t12_2d["r_bin"])
    for var, color, sym in (("sigma_theta", "C3", "σ_θ"), ("sigma_r", "C0", "σ_r")):
        ax.plot(rb, from_si(t12_2d[f"{var}_binned"], "MPa"), ".", color=color, ms=3,
                label=f"{sym}, 2-D FE ({t12_2d['sigma_theta'].attrs['inplane_bc']})")
    ax.axhline(0, color="k", lw=0.6)
    ax.set(xlabel="r [mm]", ylabel="residual stress [MPa]", xlim=(0, r.max()),
           title="Fig. 5: thermal-analogy residual stress (r_c = 65 mm, α calibrated per condition)")
    ax.legend(fontsize=7, ncol=3, loc="upper center", bbox_to_anchor=(0.5, -0.16))
    return fig


def fig06(R):
    """Fig. 6a-c: the natural frequencies after rolling against r_c by the eigen-analysis
    (Eq. 5), r_f = 25, 55, 75 mm; unrolled at r_c = 0 (open markers); r_f = 25 mm also under
    the clamped in-plane condition (dotted) and with the paper's 434.5 / 502.1 Hz (Sec. 4.3)."""
    grid, clamped = rc_grid(R), R.run("rc_grid_clamped")
    f_u, f_r = R.value("f_unrolled_nd4_rf25"), R.value("f_rolled_nd4_rc65_rf25", "paper_value")
    fig, axes = plt.subplots(1, 3, figsize=(13, 4.2), sharey=False)
    for ax, (rf, ds), letter in zip(axes, sorted(grid.items()), "abc"):
        rc = mm(ds["r_c"])
        for n in ND:
            ax.plot(rc, ds["f_rolled"].sel(n_d=n), "o-", ms=3, color=f"C{n}", label=f"N_d={n}")
            ax.plot([0], [float(ds["f_unrolled"].sel(n_d=n))], "o", mfc="none", color=f"C{n}")
        if rf == 25:
            for n in ND:
                ax.plot(rc, clamped["f_rolled"].sel(n_d=n), ":", lw=1, color=f"C{n}",
                        label="clamped" if n == 0 else None)
            ax.plot([0, mm(0.065)], [f_u, f_r], "*", color="k", ms=9, label="paper (Sec. 4.3)")
        ax.axvspan(0, rf, color="0.9")
        ax.set(xlabel="r_c [mm]", ylabel="natural frequency [Hz]",
               title=f"Fig. 6{letter}: r_f = {rf} mm")
    fig.legend(*axes[0].get_legend_handles_labels(), loc="lower center", ncol=6, fontsize=8,
               bbox_to_anchor=(0.5, -0.1))
    return fig


def fig07(R):
    """Fig. 7: the frequency change of each N_d for a 1 % stiffer 10 mm annulus at r_a
    (r_f = 25 mm, Sec. 4.2): where stiffening helps which mode."""
    ds = R.run("fig07_sensitivity")
    fig, ax = plt.subplots(figsize=(6, 4))
    for n in ND:
        ax.plot(mm(ds["r_a"]), ds["sensitivity_delta_f"].sel(n_d=n), "o-", ms=3,
                color=f"C{n}", label=f"N_d={n}")
    ax.set(xlabel="r_a [mm]", ylabel="Δf for +1 % stiffness [Hz]",
           title="Fig. 7: sensitivity of natural frequency to stiffness (r_f = 25 mm)")
    ax.legend(fontsize=7)
    return fig


def fig08(R):
    """Fig. 8a-c: Delta f against r_c by Eq. (9), linearised conversion Delta omega^2 / (2
    omega) (solid: reproduces the paper's 70.0 Hz from Table 1) and exact conversion (dashed),
    against the eigen-analysis (dots); at r_f = 25 mm the paper's 70.0 Hz (Eq. 9) and 67.6 Hz
    (eigen), 2.4 Hz apart, on the curves and in a zoom."""
    grid, x65 = rc_grid(R), mm(0.065)     # the paper's Delta f at r_c = 65 mm (Sec. 4.3)
    d_eq9, d_eig = (R.value(f"delta_f_{k}_nd4_rc65_rf25", "paper_value") for k in ("eq9", "eigen"))
    fig, axes = plt.subplots(1, 3, figsize=(13, 4.2))
    for ax, (rf, ds), letter in zip(axes, sorted(grid.items()), "abc"):
        rc, eig = mm(ds["r_c"]), ds["f_rolled"] - ds["f_unrolled"]
        for n in ND:
            ax.plot(rc, ds["delta_f_eq9_linearised"].sel(n_d=n), "-", color=f"C{n}",
                    label=f"N_d={n}" + (", Eq. (9) linearised" if n == 0 else ""))
            ax.plot(rc, ds["delta_f_eq9_exact"].sel(n_d=n), "--", lw=0.8, color=f"C{n}",
                    label="Eq. (9), exact conversion" if n == 0 else None)
            ax.plot(rc, eig.sel(n_d=n), ".", color=f"C{n}",
                    label="eigen-analysis" if n == 0 else None)
        if rf == 25:
            zoom = ax.inset_axes([0.06, 0.04, 0.36, 0.27])
            for a, ms in ((ax, 1.0), (zoom, 0.8)):
                a.plot([x65], [d_eq9], "*", mfc="none", mec="k", ms=12 * ms, mew=1.1,
                       label="paper Eq. (9)" if a is ax else None)
                a.plot([x65], [d_eig], "P", mfc="none", mec="k", ms=7 * ms, mew=1.1,
                       label="paper eigen" if a is ax else None)
            for n in (3, 4):
                zoom.plot(rc, ds["delta_f_eq9_linearised"].sel(n_d=n), "-", color=f"C{n}")
                zoom.plot(rc, eig.sel(n_d=n), ".", color=f"C{n}")
            zoom.set(xlim=(x65 - 4, x65 + 4), ylim=(d_eig - 4, d_eq9 + 2))
            zoom.tick_params(labelsize=6)
            ax.text(0.44, 0.05, f"zoom at {x65:.0f} mm, paper:\n{d_eq9:.1f} Hz (★), {d_eig:.1f} Hz (+)",
                    fontsize=7, transform=ax.transAxes)
        ax.axhline(0, color="k", lw=0.6)
        ax.set(xlabel="r_c [mm]", ylabel="Δf [Hz]", title=f"Fig. 8{letter}: r_f = {rf} mm")
    fig.legend(*axes[0].get_legend_handles_labels(), loc="lower center", ncol=5, fontsize=8,
               bbox_to_anchor=(0.5, -0.16))
    return fig


def eq9_vs_eigen(R):
    """Eq. (9) against the eigen-analysis over the whole grid of Figs. 6/8: the relative
    frequency error, and the wall time of each (the same K^(sigma): eigen-solves against
    quadratic forms), the paper's 'less computational effort' (Conclusion 1)."""
    grid, plain2d = rc_grid(R), R.run("plate2d_rc_sweep")
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    ax = axes[0]
    for (rf, ds), sym in zip(sorted(grid.items()), ["o-", "s--", "^:"]):
        for n in ND:
            ax.semilogy(mm(ds["r_c"]), ds["eq9_rel_error"].sel(n_d=n), sym, ms=3,
                        color=f"C{n}", label=f"N_d={n}" if rf == 25 else None)
    ax.set(xlabel="r_c [mm]", ylabel="|f(Eq. 9) / f(eigen) − 1| [1]",
           title="Eq. (9) error (o r_f=25, s 55, ^ 75 mm)")
    ax.legend(fontsize=7)
    times = [eigen_and_eq9_times(*grid.values()), eigen_and_eq9_times(plain2d)]
    ax = axes[1]
    labels = [f"axisym\n({len(grid)} r_f × {grid[25].sizes['r_c']} r_c × {len(ND)} N_d)",
              f"plate2d\n({plain2d.sizes['r_c']} r_c, r_f=25)"]
    x = np.arange(2)
    ax.bar(x - 0.2, [t[0] for t in times], 0.4, label="eigen-analysis, Eq. (5)")
    ax.bar(x + 0.2, [t[1] for t in times], 0.4, label="first order, Eq. (9)")
    ax.set_yscale("log")
    ax.set_xticks(x, labels)
    ax.set(ylabel="wall time [s]", title="cost: Eq. (9) vs eigen-analysis")
    ax.legend(fontsize=7)
    return fig


def slotted_blade(R):
    """Beyond the paper: a sawblade with radial expansion slots on the 2-D model against the
    plain disk, frequencies after rolling against r_c (N_d = 2-4); the slots split the pairs
    (drawn as a band), the optimal r_c per mode moves."""
    plain2d, slotted = R.run("plate2d_rc_sweep"), R.run("slotted_rc_sweep")
    fig, ax = plt.subplots(figsize=(7, 4.2))
    for n in (2, 3, 4):
        ax.plot(mm(plain2d["r_c"]), plain2d["f_rolled"].sel(n_d=n), "o-", ms=3, color=f"C{n}",
                label=f"plain, N_d={n}")
        p = slotted["f_rolled_pair"].sel(n_d=n)
        ax.fill_between(mm(slotted["r_c"]), p.isel(member=0), p.isel(member=1), color=f"C{n}",
                        alpha=0.3)
        ax.plot(mm(slotted["r_c"]), p.mean("member"), "s--", ms=3, color=f"C{n}",
                label=f"slotted, N_d={n}")
        for ds, mk in ((plain2d, "o"), (slotted, "s")):
            ax.plot([0], [float(ds["f_unrolled"].sel(n_d=n))], mk, mfc="none", color=f"C{n}")
    ax.set(xlabel="r_c [mm]", ylabel="natural frequency [Hz]",
           title=f"slotted sawblade ({int(slotted['slot_count'])} slots) vs plain disk, r_f = 25 mm")
    ax.legend(fontsize=7, ncol=2)
    return fig


def buckling(R):
    """Hard case: rolling near the rim (r_c = 105 mm) lowers omega~^2 of N_d >= 2 linearly in
    the amplitude A (Eq. 3) through zero at each mode's critical amplitude (dotted), where the
    solver reports a buckled flag, never sqrt(negative)."""
    runs = [R.run("buckling"), *R.study_runs("buckling_sweep")]
    amps = np.array([float(ds["amplitude_used"]) for ds in runs])
    order = np.argsort(amps)
    w2 = np.array([ds["omega2_rolled"].isel(r_c=0).values for ds in runs])[order]
    a_cr = from_si(amps[0] * runs[0]["critical_load_factor"].isel(r_c=0).values, "degC")
    amps = from_si(amps[order], "degC")
    fig, ax = plt.subplots(figsize=(6.5, 4))
    for j, n in enumerate(ND):
        ax.plot(amps, w2[:, j], "o-", color=f"C{n}", label=f"N_d={n}")
        if np.isfinite(a_cr[j]) and a_cr[j] < 2 * amps.max():
            ax.axvline(a_cr[j], color=f"C{n}", ls=":", lw=0.8)
    ax.axhline(0, color="k", lw=0.8)
    ax.set(xlabel="temperature amplitude A [°C]", ylabel="ω̃² [rad²/s²]",
           title="buckling: ω̃² through zero at the critical amplitude (dotted)")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return fig


def cost_of_accuracy(R):
    """Cost of accuracy of both FE models against exact solutions (the framework's table
    ``cost_of_accuracy``): top, the disk under a uniform in-plane stress against its Bessel
    solution; bottom, the unrolled disk against its Bessel solution, and the 2-D model's
    rolled frequencies against the axisym Richardson reference (dotted: that reference's own
    accuracy on the unrolled frequencies, and the 2-D model's goal)."""
    coa = R.table("cost_of_accuracy")
    fig, axes = plt.subplots(2, 2, figsize=(12, 9.2), constrained_layout=True)
    for ax, entry in zip(axes.ravel(), ("axisym_stressed", "plate2d_stressed", "axisym", "plate2d")):
        accuracy.plot(coa, entry, ax)
        ax.set_xlabel(textwrap.fill(ax.get_xlabel(), 60))   # the long "what is timed" labels
        ax.margins(x=0.12)                                  # room for the last point's label
        ax.xaxis.set_minor_formatter(mticker.NullFormatter())   # minor labels collide on short spans
    ref_err = float(R.run("table12_plate2d")["reference_error_unrolled"])
    axes[1, 1].axhline(ref_err, color="k", ls=":", lw=0.8)
    axes[1, 1].annotate("accuracy of the rolled reference", (axes[1, 1].get_xlim()[0], ref_err),
                        fontsize=7, xytext=(4, 3), textcoords="offset points")
    axes[1, 1].axhline(R.value("plate2d_unrolled_vs_exact", "paper_value"), color="k", ls=":", lw=0.8)
    axes[1, 1].legend(fontsize=8, loc="lower right", bbox_to_anchor=(1.0, 0.12))   # clear of the curves
    return fig


def identifiability(R):
    """What Table 1 and Fig. 6a's 502.1 Hz pin down: the joint (s, c) regions of band width s
    and stress scale c = E alpha A / handbook (Delta chi^2 <= 2.30 and 6.18, Birge-scaled,
    minimised over the in-plane condition; hatched: clamped only) drawn as c s against s, the
    best fit, the chi^2 Hessian's soft axis, the single-alpha calibration and the scan bounds
    that cut a region; right, the profiles over s."""
    idn = R.run("identifiability")
    s_mm, c_grid = idn["scan_width"].values * 1e3, idn["scan_scale"].values
    levels = idn["fit_level"].values
    fig, axes = plt.subplots(1, 3, figsize=(15.5, 5.2))
    ss = np.geomspace(0.6, s_mm.max() * 1.4, 200)
    for j, (ax, name) in enumerate(zip(axes[:2], idf.SUBSETS)):
        lo, hi = idn["region_c_lo"].values[j], idn["region_c_hi"].values[j]
        best_s, best_c = float(idn["best_width"].values[j]) * 1e3, float(idn["best_scale"].values[j])
        for li, color in ((1, "#9ecae1"), (0, "#2171b5")):      # 95 % below 68 %
            for a, hatch in ((1, None), (0, "///")):
                ok = np.isfinite(lo[li, a])
                kw = dict(facecolor="none", edgecolor=color, hatch=hatch, lw=0) if hatch else \
                    dict(color=color)
                if ok.any():
                    ax.fill_between(s_mm, lo[li, a] * s_mm, hi[li, a] * s_mm, where=ok, **kw,
                                    label=f"Δχ² ≤ {levels[li]:.2f} ({list(idf.LEVELS)[li]} %)"
                                    + (", clamped only" if hatch else ""))
            # where the region reaches a scan's end: the s scan's ends, the c scan's ends
            c_lo, c_hi = np.fmin.reduce(lo[li]), np.fmax.reduce(hi[li])   # over the conditions
            for k in (0, -1):
                if np.isfinite(c_lo[k]):
                    ax.plot([s_mm[k]] * 2, [c_lo[k] * s_mm[k], c_hi[k] * s_mm[k]],
                            color="tab:red", lw=3, solid_capstyle="butt")
            for edge, cut in ((c_grid[0], c_lo <= c_grid[0]), (c_grid[-1], c_hi >= c_grid[-1])):
                if cut.any():
                    ax.plot(s_mm[cut], edge * s_mm[cut], color="tab:red", lw=3)
        ax.plot([], [], color="tab:red", lw=3, label="region cut by a scan bound")
        slope = float(idn["direction_slope"].values[j])
        half = float(idn["direction_halfwidth"].values[j][0]) * np.sqrt(levels[1] / levels[0])
        t = np.linspace(-half, half, 2) / np.hypot(1.0, slope)
        ax.plot(best_s * np.exp(t), best_s * best_c * np.exp((1 + slope) * t), "k-", lw=1.2,
                label="degenerate direction: the χ² Hessian's soft axis at the best fit")
        ax.axhline(best_s * best_c, color="0.5", lw=0.8, ls="--", zorder=0,
                   label="c·s constant through the best fit")
        ax.plot([best_s], [best_s * best_c], "o", color="k", ms=6, label="best fit")
        single = (float(idn["single_width"]) * 1e3, float(idn["single_scale"]))
        ax.plot([single[0]], [single[0] * single[1]], "x", color="tab:orange", ms=9, mew=2,
                label="single-α calibration")
        ax.axvspan(0.5, s_mm.min(), color="0.88", zorder=0)
        ax.axvspan(s_mm.max(), s_mm.max() * 1.5, color="0.88", zorder=0)
        ax.fill_between(ss, c_grid[-1] * ss, 100, color="0.88", zorder=0, lw=0)
        ax.fill_between(ss, 0, c_grid[0] * ss, color="0.88", zorder=0, lw=0)
        ax.set(xscale="log", xlim=(ss[0], ss[-1]), ylim=(5.8, 10.2),
               xlabel="Gaussian width s [mm]", ylabel="c·s [mm] (c = E·α·A / handbook)")
        ax.set_title(f"{name}: joint (s, c) regions; soft axis c ∝ $s^{{{slope:.2f}}}$", fontsize=10)
        ax.set_xticks([1, 2, 5, 10, 20])
        ax.xaxis.set_minor_formatter(mticker.NullFormatter())
        ax.xaxis.set_major_formatter(mticker.FuncFormatter(lambda v, _: f"{v:g}"))
    ax = axes[2]
    for j, name in enumerate(idf.SUBSETS):
        base = float(idn["chi2_min"].values[j])
        ax.plot(s_mm, idn["prof_width"].values[j] - base, label=name)
    for level, ls in zip(levels, (":", "--")):
        ax.axhline(level, color="k", ls=ls, lw=0.8, label=f"Δχ² = {level:.2f}")
    ax.set(xlabel="Gaussian width s [mm]", ylabel="profile Δχ² (Birge-scaled) [1]", ylim=(0, 14),
           xlim=(0, s_mm.max() * 1.02),
           title=f"profile over s (scan {s_mm.min():g}-{s_mm.max():g} mm: the axis)")
    ax.legend(fontsize=8, loc="upper center")
    axes[0].fill_between([], [], color="0.88", label="outside the scans (s 1-20 mm, c 0.25-8)")
    handles = {}
    for a in axes[:2]:
        handles.update(zip(*a.get_legend_handles_labels()[::-1]))
    fig.legend(handles.values(), handles.keys(), loc="lower center", ncol=3, fontsize=8,
               bbox_to_anchor=(0.36, 0.0))
    fig.subplots_adjust(bottom=0.25, wspace=0.28)
    return fig


def critical_speed(R):
    """Beyond the paper (Sec. 2: what tensioning is for): the travelling-wave critical speed
    against r_c, rolled (A = 50 degC, alpha calibrated) and unrolled, per N_d at r_f = 25 mm
    (dotted: the other end of centrifugal_bc, free_disk), and the lowest over N_d per r_f, the
    design curve; a buckled rolled disk has none (a gap)."""
    cs, cs_free = R.run("critical_speed"), R.run("critical_speed_centrifugal_free")
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.2))
    rc_mm = cs["r_c"].values * 1e3
    for n in (2, 3, 4):
        axes[0].plot(rc_mm, cs["critical_speed"].sel(n_d=n).values * RPM, "o-",
                     color=f"C{n}", label=f"N_d={n}")
        axes[0].axhline(float(cs["critical_speed_untensioned"].sel(n_d=n)) * RPM,
                        color=f"C{n}", ls="--", lw=0.8)
        axes[0].plot(rc_mm, cs_free["critical_speed"].sel(n_d=n).values * RPM, ":",
                     color=f"C{n}", lw=1, label="dotted: free_disk" if n == 2 else None)
    axes[0].set(xlabel="rolling radius r_c [mm]", ylabel="critical speed [rpm]",
                title="r_f = 25 mm: rolled (solid; dotted: free_disk) vs unrolled (dashed)")
    axes[0].legend(fontsize=8)
    for i, (rf, ds) in enumerate(by_clamp(R, "critical_speed", "critical_speed_rf")):
        line, = axes[1].plot(rc_mm, lowest(ds) * RPM, "o-", label=f"r_f = {rf:.0f} mm")
        axes[1].axhline(float(ds["critical_speed_untensioned"].min()) * RPM,
                        color=line.get_color(), ls="--", lw=0.8)
        if i == 0:
            axes[1].plot(rc_mm, lowest(cs_free) * RPM, "o:", ms=3,
                         color=line.get_color(), label=f"r_f = {rf:.0f} mm, free_disk")
    axes[1].set(xlabel="rolling radius r_c [mm]", ylabel="lowest critical speed [rpm]",
                title="the design curve: lowest critical speed over N_d")
    # below every untensioned (dashed) line and left of the curves' drop at the rim
    axes[1].legend(fontsize=8, loc="lower center", bbox_to_anchor=(0.42, 0.0))
    return fig


def design_map(R):
    """Beyond the paper: the tensioning design map.  The lowest critical speed over N_d = 2-10
    against r_c and the amplitude A of Eq. (4), one panel per flange radius, up to the
    buckling-at-rest limit 1/m (white: the stated margin, dashed: its range's ends), with the
    optimum and the paper's r_c = 65 mm at A = 50 degC; the best lowest critical speed per r_c
    over the untensioned one (also in the cut, rim hotter); the N_d = 0, 1 frequency margins
    at rest that tensioning spends."""
    dm_runs, cut = by_clamp(R, "design_map", "design_map_rf"), R.run("design_map_in_cut")
    fig, axes = plt.subplots(2, 3, figsize=(15, 8.8), constrained_layout=True)
    ax, ax_f = axes[1, 1], axes[1, 2]
    for a, (rf, ds), c in zip(axes.flat, dm_runs, ("C0", "C1", "C2", "C3")):   # maps, then curves
        rc_mm, amp = ds["r_c"].values * 1e3, ds["design_amplitude"].values
        low = design.lowest_map(ds)
        unt = float(np.nanmin(low[:, 0]))
        pc = a.pcolormesh(np.broadcast_to(rc_mm[:, None], amp.shape), amp, low * RPM,
                          shading="gouraud", cmap="viridis")
        fig.colorbar(pc, ax=a, label="lowest critical speed [rpm]")
        a_cr = ds["design_buckling_amplitude"].values
        for m, ls in zip(ds["design_margin"].values, ("--", "-", "--")):
            a.plot(rc_mm, a_cr / m, ls, color="w", lw=1.4 if ls == "-" else 0.8)
        q = int(np.argmin(np.abs(ds["design_margin"].values - float(ds["design_stated_margin"]))))
        k, v = design.best(ds, q)
        a.plot(rc_mm[k], ds["design_best_amplitude"].values[q, k], "*", color="r", ms=13, mec="k")
        j65 = int(np.argmin(np.abs(rc_mm - 65)))
        a.plot(65, 50, "o", color="w", mec="k", ms=7)
        a.set(xlabel="rolling radius r_c [mm]", ylabel="rolling amplitude A [°C]",
              ylim=(0, np.nanmax(amp) * 1.02),
              title=f"r_f = {rf:.0f} mm: ★ {v * RPM:.0f}, ○ "
                    f"{float(ds['design_paper_amplitude_speed'][j65]) * RPM:.0f}, "
                    f"untensioned {unt * RPM:.0f} rpm")
        ax.plot(rc_mm, 100 * (ds["design_best_speed"].values[q] / unt - 1), "o-", ms=3,
                color=c, label=f"r_f {rf:.0f} mm, best A")
        ax.plot(rc_mm, 100 * (ds["design_paper_amplitude_speed"].values / unt - 1), ":",
                color=c, label=f"r_f {rf:.0f} mm, A = 50 °C")
        fr = ds["design_best_frequency_ratio"].values[q]
        ax_f.plot(rc_mm, fr[:, 0], "-", color=c, label=f"r_f {rf:.0f} mm, N_d = 0")
        ax_f.plot(rc_mm, fr[:, 1], ":", color=c, label=f"r_f {rf:.0f} mm, N_d = 1")
    unt25 = float(np.nanmin(design.lowest_map(dm_runs[0][1])[:, 0]))
    qc = int(np.argmin(np.abs(cut["design_margin"].values - float(cut["design_stated_margin"]))))
    ax.plot(cut["r_c"].values * 1e3, 100 * (cut["design_best_speed"].values[qc] / unt25 - 1),
            "k--", lw=1.2,
            label=f"r_f 25 mm in the cut, rim +{float(cut['design_rim_temperature_rise']):.0f} °C")
    ax.axhline(0, color="k", lw=0.8)
    ax.set(xlabel="rolling radius r_c [mm]", ylabel="lowest critical speed over untensioned [%]",
           title="the design curve (stated margin; a gap: buckled)", ylim=(-120, 60))
    ax.legend(fontsize=7, ncol=2, loc="lower left")    # below the curves
    ax_f.set(xlabel="rolling radius r_c [mm]", ylabel="f̃ / f at rest, best A [1]", ylim=(0, 1.7),
             title="N_d = 0, 1 frequency margins (stated margin)")
    ax_f.legend(fontsize=7, ncol=2, loc="upper left")
    return fig
