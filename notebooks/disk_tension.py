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
# # disk_tension — a circular saw disk tensioned by rolling (Kuratani & Yano)
#
# Re-derives Figs. 4–8 and Tables 1–2 from Eqs. (3)–(17): the roll-tensioning is a Gaussian
# temperature load (Eq. 4), its plane-stress field stiffens the clamped Kirchhoff disk
# (Eq. 3), the frequencies after rolling come from the eigenproblem (Eq. 5) and from the
# first-order estimate (Eq. 9).  Two discretisations — cos(N_d θ) harmonics with radial
# Hermite elements (`axisym`) and a 2-D Argyris plate mesh (`plate2d`, scikit-fem) — are
# checked against the exact Bessel solution of the clamped/free annular plate.
#
# **Constants the paper does not give.** Thickness h: calibrated so that the exact unrolled
# N_d = 4 frequency at r_f = 25 mm is 434.5 Hz. Steel E, ν, ρ: handbook. The thermal
# analogy's α·A: the temperature is fictitious, so α is calibrated on Table 1's N_d = 4
# diagonal (2.40e6 rad²/s²); the handbook α = 12e-6/K is kept as a comparison scene.
# **In-plane condition of the residual stress:** `free_disk` (the blade's stress before it is
# clamped), chosen on the α-independent ratios of Table 1 (N_d = 0–3 over N_d = 4: within
# 2.7 % vs −9.7 % for `clamped`); `clamped` (u_r(r_f) = 0) is drawn beside it and is the
# other end of the declared range, so every verdict is re-checked under it.

# %% tags=["parameters"]
paper = "disk_tension"
results_dir = "results"
config_file = "config/papers/disk_tension.yaml"
profile = "default"

# %%
import numpy as np

from mechrepro.accuracy import cost_of_accuracy, plot
from mechrepro.io import run_attrs
from mechrepro.models.disk_tension.convergence import reference_pair, richardson
from mechrepro.plotting import plt
from mechrepro.validation import read_table
from mechrepro.results import PaperResults

R = PaperResults(paper, results_dir, config_file, profile)
MM, ND = 1e3, [0, 1, 2, 3, 4]
COLORS = {n: f"C{n}" for n in ND}


def study_runs(name, key):
    """{swept value: run dataset} of a study."""
    return {R.cfg.runs[r]["sweep"][key]: R.run(r) for r in R.cfg.studies[name]}


t12, t12_2d, t12_cl = R.run("table12"), R.run("table12_plate2d"), R.run("table12_clamped")
stress = t12
grid = {25: R.run("rc_grid"), **study_runs("fig06", "clamp_radius")}
clamped, fig07 = R.run("rc_grid_clamped"), R.run("fig07_sensitivity")
plain2d, slotted = R.run("plate2d_rc_sweep"), R.run("slotted_rc_sweep")
buck = sorted([(50.0, R.run("buckling"))] + list(study_runs("buckling_sweep", "temperature_amplitude").items()))
print(f"thickness h = {float(t12['thickness']) * 1e3:.4f} mm, alpha_eff = "
      f"{float(t12['alpha_effective']) * 1e6:.3f}e-6/K (x{float(t12['stress_scale']):.4f})")

# %% [markdown]
# ## Fig. 3 — the FE models of the disk
# Left: the 2-D Argyris mesh of this profile's `table12_plate2d` run (the flexible annulus
# r_f ≤ r ≤ b; the core r < r_f is clamped, and meshed only for the free-disk plane-stress
# problem). Right: the radial Hermite elements of the axisymmetric model (`table12`).

# %%
fig, axes = plt.subplots(1, 2, figsize=(11, 5.2), gridspec_kw={"width_ratios": [1.2, 1]})
ax = axes[0]
x, y = t12_2d["plate2d_mesh_x"].values * MM, t12_2d["plate2d_mesh_y"].values * MM
ax.triplot(x, y, t12_2d["plate2d_mesh_cells"].values, lw=0.3, color="k")
ax.add_patch(plt.Circle((0, 0), float(t12_2d["clamp_radius"]) * MM, color="0.7", label="clamped r ≤ r_f"))
ax.set(aspect="equal", xlabel="x [mm]", ylabel="y [mm]",
       title=f"Fig. 3: 2-D mesh ({t12_2d.sizes['mesh_cell']} triangles, "
             f"{int(t12_2d['plate2d_n_dofs'])} Argyris DOFs)")
ax.legend(fontsize=8, loc="upper right")
ax = axes[1]
n_el = run_attrs(t12)["resolution"]["n_elements"]
nodes = np.linspace(float(t12["clamp_radius"]), 0.5 * R.cfg.raw["parameters"]["outer_diameter"]["value"] / MM, n_el + 1) * MM
ax.plot(nodes, np.zeros_like(nodes), "|", ms=12, color="k")
ax.axvspan(0, nodes[0], color="0.8", label="clamped")
ax.set(xlabel="r [mm]", yticks=[], xlim=(0, nodes[-1] * 1.02),
       title=f"axisymmetric model: {n_el} cubic Hermite elements × cos(N_d θ)")
ax.legend(fontsize=8)
R.save_figure(fig, "fig03")

# %% [markdown]
# ## Fig. 4 — temperature distribution (r_c = 65 mm, A = 50 °C, s = 5 mm)

# %%
fig, ax = plt.subplots(figsize=(6, 3.4))
r = stress["r"].values * MM
ax.plot(r, stress["temperature"].isel(r_c=0), "-")
ax.axvspan(0, float(stress["clamp_radius"]) * MM, color="0.85", label="clamped r ≤ r_f")
ax.axvspan(65 - 10, 65 + 10, color="tab:orange", alpha=0.15, label="rolling width 4s")
ax.set(xlabel="r [mm]", ylabel="T [°C]", title="Fig. 4: thermal-analogy temperature, Eq. (4)",
       xlim=(0, r.max()))
ax.legend(fontsize=8)
R.save_figure(fig, "fig04")

# %% [markdown]
# ## Fig. 5 — residual stress distribution
# The paper draws a contour on 1/12 of the disk; for an axisymmetric load the field is
# radial, so we plot σ_r and σ_θ along the radius: closed form for both in-plane clamps,
# and the plane-stress P2 finite-element field of the 2-D model (radial bin means).

# %%
fig, ax = plt.subplots(figsize=(6.5, 4))
for name, ds, ls in (("table12", t12, "-"), ("table12_clamped", t12_cl, "--")):
    bc = R.cfg.runs[name]["parameters"]["inplane_bc"]
    ax.plot(r, ds["sigma_theta"].isel(r_c=0) / 1e6, ls, color="C3", label=f"σ_θ, {bc}")
    ax.plot(r, ds["sigma_r"].isel(r_c=0) / 1e6, ls, color="C0", label=f"σ_r, {bc}")
rb = t12_2d["r_bin"].values * MM
ax.plot(rb, t12_2d["plate2d_sigma_theta_binned"] / 1e6, ".", color="C3", ms=3, label="σ_θ, 2-D FE (free_disk)")
ax.plot(rb, t12_2d["plate2d_sigma_r_binned"] / 1e6, ".", color="C0", ms=3, label="σ_r, 2-D FE (free_disk)")
ax.axhline(0, color="k", lw=0.6)
ax.set(xlabel="r [mm]", ylabel="residual stress [MPa]", xlim=(0, r.max()),
       title="Fig. 5: thermal-analogy residual stress (r_c = 65 mm, α calibrated per condition)")
ax.legend(fontsize=7, ncol=2)
R.save_figure(fig, "fig05")

# %% [markdown]
# ## Fig. 6 — natural frequencies after rolling vs r_c (eigen-analysis, Eq. 5)
# Unrolled frequencies at r_c = 0 (open markers); the paper's 434.5 / 502.1 Hz (N_d = 4,
# r_f = 25 mm) as stars.

# %%
fig, axes = plt.subplots(1, 3, figsize=(13, 4.2), sharey=False)
for ax, (rf, ds) in zip(axes, sorted(grid.items())):
    rc = ds["r_c"].values * MM
    for n in ND:
        ax.plot(rc, ds["axisym_f_rolled"].sel(n_d=n), "o-", ms=3, color=COLORS[n], label=f"N_d={n}")
        ax.plot([0], [float(ds["axisym_f_unrolled"].sel(n_d=n))], "o", mfc="none", color=COLORS[n])
    if rf == 25:
        for n in ND:
            ax.plot(rc, clamped["axisym_f_rolled"].sel(n_d=n), ":", lw=1, color=COLORS[n],
                    label="clamped" if n == 0 else None)
        ax.plot([0, 65], [R.cfg.raw["parameters"]["calibration_frequency"]["value"],
                          R.cfg.reported["f_rolled_nd4_rc65_rf25"]["value"]], "*", color="k", ms=9,
                label="paper (Sec. 4.3)")
    ax.axvspan(0, rf, color="0.9")
    ax.set(xlabel="r_c [mm]", ylabel="natural frequency [Hz]", title=f"Fig. 6{'abc'[[25, 55, 75].index(rf)]}: r_f = {rf} mm")
fig.legend(*axes[0].get_legend_handles_labels(), loc="lower center", ncol=6, fontsize=8,
           bbox_to_anchor=(0.5, -0.1))
R.save_figure(fig, "fig06")

# %% [markdown]
# ## Fig. 7 — sensitivity to a 1 % stiffer 10 mm annulus at r_a (r_f = 25 mm)

# %%
fig, ax = plt.subplots(figsize=(6, 4))
ra = fig07["r_a"].values * MM
for n in ND:
    ax.plot(ra, fig07["sensitivity_delta_f"].sel(n_d=n), "o-", ms=3, color=COLORS[n], label=f"N_d={n}")
ax.set(xlabel="r_a [mm]", ylabel="Δf for +1 % stiffness [Hz]",
       title="Fig. 7: sensitivity of natural frequency to stiffness (r_f = 25 mm)")
ax.legend(fontsize=7)
R.save_figure(fig, "fig07")

# %% [markdown]
# ## Fig. 8 — Δf by Eq. (9) vs r_c
# Solid: Δω²/(2ω)/2π, the linearised conversion that reproduces the paper's 70.0 Hz from
# Table 1; dashed: exact conversion √(ω²+Δω²) − ω; dots: eigen-analysis.

# %%
fig, axes = plt.subplots(1, 3, figsize=(13, 4.2))
for ax, (rf, ds) in zip(axes, sorted(grid.items())):
    rc = ds["r_c"].values * MM
    for n in ND:
        ax.plot(rc, ds["axisym_delta_f_eq9_linearised"].sel(n_d=n), "-", color=COLORS[n], label=f"N_d={n}")
        ax.plot(rc, ds["axisym_delta_f_eq9_exact"].sel(n_d=n), "--", lw=0.8, color=COLORS[n])
        ax.plot(rc, ds["axisym_f_rolled"].sel(n_d=n) - ds["axisym_f_unrolled"].sel(n_d=n), ".",
                color=COLORS[n])
    if rf == 25:
        ax.plot([65], [R.cfg.reported["delta_f_eq9_nd4_rc65_rf25"]["value"]], "*", color="k", ms=10,
                label="paper Eq. (9)")
        ax.plot([65], [R.cfg.reported["delta_f_eigen_nd4_rc65_rf25"]["value"]], "P", color="k", ms=7,
                label="paper eigen")
    ax.axhline(0, color="k", lw=0.6)
    ax.set(xlabel="r_c [mm]", ylabel="Δf [Hz]", title=f"Fig. 8{'abc'[[25, 55, 75].index(rf)]}: r_f = {rf} mm")
fig.legend(*axes[0].get_legend_handles_labels(), loc="lower center", ncol=7, fontsize=8,
           bbox_to_anchor=(0.5, -0.1))
R.save_figure(fig, "fig08")

# %% [markdown]
# ## Eq. (9) against the eigen-analysis over the whole grid — error and time
# The paper's claim is "less computational effort"; both use the same K^(σ), so the time
# compared is eigen-analysis vs the quadratic forms of Eq. (9).

# %%
fig, axes = plt.subplots(1, 2, figsize=(11, 4))
ax = axes[0]
for rf, ds in sorted(grid.items()):
    w2 = (2 * np.pi * ds["axisym_f_unrolled"]) ** 2 + ds["axisym_delta_omega2_eq9"]
    f9 = np.sqrt(w2.where(w2 > 0)) / (2 * np.pi)
    err = np.abs(f9 / ds["axisym_f_rolled"] - 1)
    for n in ND:
        ax.semilogy(ds["r_c"] * MM, err.sel(n_d=n), ["o-", "s--", "^:"][[25, 55, 75].index(rf)],
                    ms=3, color=COLORS[n], label=f"N_d={n}" if rf == 25 else None)
ax.set(xlabel="r_c [mm]", ylabel="|f(Eq. 9) / f(eigen) − 1|",
       title="Eq. (9) error (o r_f=25, s 55, ^ 75 mm)")
ax.legend(fontsize=7)
t_eig = {m: sum(float(g[f"{m}_time_eigen"]) for g in grid.values()) for m in ["axisym"]}
t_eq9 = {m: sum(float(g[f"{m}_time_eq9"]) for g in grid.values()) for m in ["axisym"]}
t_eig["plate2d"], t_eq9["plate2d"] = float(plain2d["plate2d_time_eigen"]), float(plain2d["plate2d_time_eq9"])
ax = axes[1]
labels = ["axisym\n(27 r_c×r_f × 5 N_d)", f"plate2d\n({plain2d.sizes['r_c']} r_c, r_f=25)"]
x = np.arange(2)
ax.bar(x - 0.2, [t_eig["axisym"], t_eig["plate2d"]], 0.4, label="eigen-analysis, Eq. (5)")
ax.bar(x + 0.2, [t_eq9["axisym"], t_eq9["plate2d"]], 0.4, label="first order, Eq. (9)")
ax.set_yscale("log")
ax.set_xticks(x, labels)
ax.set(ylabel="wall time [s]", title="cost: Eq. (9) vs eigen-analysis")
ax.legend(fontsize=7)
R.save_figure(fig, "eq9_vs_eigen")
for m in t_eig:
    print(f"{m}: eigen {t_eig[m]:.4g} s, Eq. (9) {t_eq9[m]:.4g} s, ratio {t_eig[m] / t_eq9[m]:.0f}x")

# %% [markdown]
# ## Beyond the paper: a sawblade with radial expansion slots (2-D model)
# Six slots cut the hoop-stress path at the rim; the slotted N_d = 3 pair splits (6 slots
# couple cos 3θ and sin 3θ differently). Pair members are drawn as a band.

# %%
fig, ax = plt.subplots(figsize=(7, 4.2))
for n in (2, 3, 4):
    rc = plain2d["r_c"].values * MM
    ax.plot(rc, plain2d["plate2d_f_rolled"].sel(n_d=n), "o-", ms=3, color=COLORS[n], label=f"plain, N_d={n}")
    p = slotted["plate2d_f_rolled_pair"].sel(n_d=n)
    ax.fill_between(slotted["r_c"].values * MM, p.isel(member=0), p.isel(member=1), color=COLORS[n], alpha=0.3)
    ax.plot(slotted["r_c"].values * MM, p.mean("member"), "s--", ms=3, color=COLORS[n], label=f"slotted, N_d={n}")
    ax.plot([0], [float(plain2d["plate2d_f_unrolled"].sel(n_d=n))], "o", mfc="none", color=COLORS[n])
    ax.plot([0], [float(slotted["plate2d_f_unrolled"].sel(n_d=n))], "s", mfc="none", color=COLORS[n])
ax.set(xlabel="r_c [mm]", ylabel="natural frequency [Hz]",
       title=f"slotted sawblade ({int(slotted['slot_count'])} slots) vs plain disk, r_f = 25 mm")
ax.legend(fontsize=7, ncol=2)
R.save_figure(fig, "slotted_blade")

# %% [markdown]
# ## Hard case: buckling under rolling near the rim (r_c = 105 mm)
# Compressive hoop stress lowers ω² of N_d ≥ 2 linearly in the amplitude A; past the
# critical amplitude ω² < 0 and the solver reports NaN + a `buckled` flag, never √(negative).

# %%
fig, ax = plt.subplots(figsize=(6.5, 4))
amps = np.array([a for a, _ in buck], float)
w2 = np.array([ds["axisym_omega2_rolled"].isel(r_c=0).values for _, ds in buck])
for j, n in enumerate(ND):
    ax.plot(amps, w2[:, j] / (2 * np.pi) ** 2 / 1e3, "o-", color=COLORS[n], label=f"N_d={n}")
    acr = amps[0] * float(buck[0][1]["axisym_critical_load_factor"].isel(r_c=0).sel(n_d=n))
    if np.isfinite(acr) and acr < 2 * amps.max():
        ax.axvline(acr, color=COLORS[n], ls=":", lw=0.8)
ax.axhline(0, color="k", lw=0.8)
ax.set(xlabel="temperature amplitude A [°C]", ylabel="ω̃²/(2π)² [kHz²]",
       title="buckling: ω̃² through zero at the critical amplitude (dotted)")
ax.legend(fontsize=7)
R.save_figure(fig, "buckling")

# %% [markdown]
# ## Tables 1 and 2 (r_c = 65 mm, r_f = 25 mm)

# %%
def matrix_rows(da):
    return [[int(n)] + [float(v) for v in da.sel(row=n).values] for n in da["row"].values]


hdr = ["N_d"] + [str(n) for n in ND]
R.write_table("table1", hdr, matrix_rows(t12["axisym_k_sigma_hat"]))
R.write_table("table2", hdr, matrix_rows(t12["axisym_m_hat"]))
R.write_table("table1_plate2d", hdr, matrix_rows(t12_2d["plate2d_k_sigma_hat"]))
R.write_table("table2_plate2d", hdr, matrix_rows(t12_2d["plate2d_m_hat"]))
np.set_printoptions(precision=4, linewidth=140)
print("Table 1 (axisym):\n", t12["axisym_k_sigma_hat"].values)
print("Table 1 (plate2d):\n", t12_2d["plate2d_k_sigma_hat"].values)
print("Table 2 (plate2d, pairs rotated onto the unrolled cos/sin basis):\n", t12_2d["plate2d_m_hat"].values)

# %% [markdown]
# ## Cost of accuracy
# Unrolled: error against the exact Bessel frequencies. Rolled: against a converged
# reference — the Richardson extrapolation (h⁴) of the 64- and 128-element axisym runs, not
# the finest run (256 elements carry ~10× the round-off of 128). The reference's own
# accuracy is measured on the unrolled frequencies, where the exact solution is known.
# Time = assembly + unrolled + stress + rolled eigen-analysis of one (r_c, r_f), each phase
# repeated for ≥ 0.05 s and the fastest call kept (the solver's own timers).

# %%
ax_names = ["table12"] + R.cfg.studies["cost_axisym"]
ax_runs = {run_attrs(R.run(r))["resolution"]["n_elements"]: R.run(r) for r in ax_names}
n0, n1 = reference_pair(ax_runs)
f_ref = richardson(ax_runs[n0]["axisym_f_rolled"].values, ax_runs[n1]["axisym_f_rolled"].values)
ref_unrolled = richardson(ax_runs[n0]["axisym_f_unrolled"].values, ax_runs[n1]["axisym_f_unrolled"].values)
ref_err = float(np.max(np.abs(ref_unrolled / ax_runs[n1]["f_exact"].values - 1)))
print(f"rolled reference: Richardson of {n0} and {n1} elements; on the unrolled frequencies it is "
      f"within {ref_err:.1e} of exact (the {n1}-element run: "
      f"{float(ax_runs[n1]['axisym_error_unrolled_max']):.1e})")


def coa(base, study, model, knob):
    """Error vs wall time over the base scene and its study runs."""
    names = [base] + R.cfg.studies[study]
    st = [R.run(r) for r in names]
    kv = [int(d["plate2d_n_dofs"]) if model == "plate2d" else R.cfg.runs[r]["resolution"]["n_elements"]
          for r, d in zip(names, st)]
    tw = np.array([float(d[f"{model}_time_unrolled"]) + float(d[f"{model}_time_stress"])
                   + float(d[f"{model}_time_eigen"]) for d in st])
    err_u = [float(d[f"{model}_error_unrolled_max"]) for d in st]
    err_r = [float(np.max(np.abs(d[f"{model}_f_rolled"].values / f_ref - 1))) for d in st]
    err_4 = [abs(float(d[f"{model}_error_unrolled"].sel(n_d=4))) for d in st]
    return cost_of_accuracy(paper, knob, kv, tw,
                            {"unrolled_max_vs_exact": err_u, "unrolled_nd4_vs_exact": err_4,
                             "rolled_max_vs_richardson": err_r},
                            reference=f"exact (unrolled) / Richardson {n0}+{n1} axisym (rolled)",
                            description=f"{model}: error vs wall time (fastest of repeated calls)")


c_ax = coa("table12", "cost_axisym", "axisym", "n_elements")
c_2d = coa("table12_plate2d", "cost_plate2d", "plate2d", "n_dofs")
c_ax.attrs["reference_error_unrolled"] = ref_err
R.write_dataset(c_ax, "cost_of_accuracy")
R.write_dataset(c_2d, "cost_of_accuracy_plate2d")
rows_coa = []
for name, c in (("axisym", c_ax), ("plate2d", c_2d)):
    for i in range(c.sizes["resolution"]):
        rows_coa.append([name, c.attrs["knob"], int(c["resolution"].values[i]), float(c["wall_time"][i]),
                         float(c["error_unrolled_max_vs_exact"][i]), float(c["error_unrolled_nd4_vs_exact"][i]),
                         float(c["error_rolled_max_vs_richardson"][i])])
R.write_table("cost_of_accuracy", ["model", "knob", "value", "wall_time_s", "error_unrolled_max_vs_exact",
                                   "error_unrolled_nd4_vs_exact", "error_rolled_max_vs_richardson"], rows_coa)
fig, axes = plt.subplots(1, 2, figsize=(12, 4.4))
plot(c_ax, axes[0])
plot(c_2d, axes[1])
axes[0].axhline(ref_err, color="k", ls=":", lw=0.8)
axes[0].annotate("accuracy of the rolled reference", (axes[0].get_xlim()[0], ref_err), fontsize=7,
                 xytext=(4, 3), textcoords="offset points")
axes[1].axhline(1e-3, color="k", ls=":", lw=0.8)
R.save_figure(fig, "cost_of_accuracy")
for row in rows_coa:
    print(row)

# %% [markdown]
# ## Validation table
# Built by the framework from the `reported:` block of the config (rule `validate_disk_tension`);
# only `independent` rows count in the replication claim.

# %%
table = read_table(R.table_path("validation"))
for r in table:
    print(f"{r['status']:12s} {r['evidence']:12s} {r['quantity']:42s} paper {r['paper_value']:>10s}  "
          f"ours {float(r['reproduced_value']):11.5g}  {r['note'][:70]}")
