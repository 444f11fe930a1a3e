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
# # chain_drive — vibration of roller chain drives (Choi & Johnson)
#
# A roller-chain span modelled as an axially moving string: polygonal action (rigid and
# elastic four-bar), roller impact, external load, end-point motion and periodic length
# change enter through the tension and the boundary conditions.  Finite differences
# (Eqs. 2-36..2-38) at low/medium speed, Galerkin + RK4 (Eqs. 2-39..2-41) at high speed.
# The paper gives few numbers: its claims are about where peaks and instabilities
# appear; each is a computed check in the validation table (built by the framework).  Constants the paper does not give are
# `assumed: true` in `config/papers/chain_drive.yaml` (see docs/chain_drive.md).

# %% tags=["parameters"]
paper = "chain_drive"
results_dir = "results"
config_file = "config/papers/chain_drive.yaml"
profile = "default"

# %%
import numpy as np
import xarray as xr

from mechrepro.accuracy import cost_of_accuracy, plot
from mechrepro.models.chain_drive import claims as C
from mechrepro.plotting import plt
from mechrepro.results import PaperResults
from mechrepro.validation import read_table

R = PaperResults(paper, results_dir, config_file, profile)
# rows are built by the framework (rule validate_chain_drive); the notebook only shows them
table = {r["quantity"]: r for r in read_table(R.table_path("validation"))}


def mark_unstable(ax, ds, scale=1e3, label="unstable (growing or capped)"):
    """Every figure marks the speeds whose response grows (never drawn as a peak)."""
    un = np.asarray(ds.unstable.values, bool)
    if un.any():
        ax.plot(ds.speed.values[un], ds.amplitude.values[un] * scale, "rx", ms=4, label=label)


def study_with_base(study, base, key, base_value):
    """A study's runs plus its base scene (the scene itself is one point of the sweep)."""
    st = R.study(study)
    runs = [R.run(base)] + [st.isel(run=i) for i in range(st.sizes["run"])]
    values = [base_value] + list(np.asarray(st[key].values, float))
    order = np.argsort(values)
    return [values[i] for i in order], [runs[i] for i in order]


prm = {k: v["value"] for k, v in R.cfg.raw["parameters"].items()}

# %% [markdown]
# ## Fig. 1 — impact load (Eqs. 2-2..2-4, Appendix I)
# The pressure angle of Eq. (2-3) is garbled in the text; we take the ANSI transition
# angle eta = 35 deg + 60 deg / n1 (docs/chain_drive.md).

# %%
d1 = R.run("fig01_impact")
fig, ax = plt.subplots(1, 2, figsize=(10, 3.6))
ax[0].plot(d1.t_wide * 1e3, d1.impact_load_wide)
ax[0].set(xlabel="t [ms]", ylabel="D_imp [N] (step-averaged)", title="Fig. 1b: three tooth periods")
ax[1].plot(d1.t_near * 1e6, d1.impact_load_near)
ax[1].axvline(float(d1.contact_time) * 1e6, color="k", ls=":", label="pi/omega_d")
ax[1].set(xlabel="t after impact [us]", ylabel="D_imp [N]", title="Fig. 1c: near the impact")
ax[1].legend()
R.save_figure(fig, "fig01")

# %% [markdown]
# ## Fig. 3 — rigid four-bar: driven speed and polygonal load at 300 rpm

# %%
d3 = R.run("fig03")
fig, ax = plt.subplots(2, 3, figsize=(12, 5.5), sharex=True)
t_ms = d3.t * 1e3
for j, n2 in enumerate(d3.n2.values[np.argsort(d3.panel.values)]):
    ax[0, j].plot(t_ms, d3.omega2.sel(n2=n2))
    ax[0, j].set(title=f"Fig. 3{'abc'[j]}: (n1, n2) = ({prm['n1']}, {n2})", ylabel="omega_2 [rpm]")
    ax[1, j].plot(t_ms, d3.polygonal_load.sel(n2=n2))
    ax[1, j].set(xlabel="t [ms]", ylabel="D_pol [N]")
R.save_figure(fig, "fig03")

# %% [markdown]
# ## Fig. 4 — elastic four-bar (Eqs. 2-11..2-23)
# A X = F (Eq. 2-20) is obtained by projecting Eq. (2-19) on the nine harmonics numerically
# (Appendix II has duplicated/garbled entries), then solved by least squares (Eq. 2-21).

# %%
d4 = R.run("fig04_elastic")
fig, ax = plt.subplots(1, 2, figsize=(11, 4))
for i, w in enumerate(d4.case.values):
    ax[0].plot(d4.phase, d4.load_shape[i], label=f"{'abcde'[i]}: {w:.0f} rpm")
ax[0].set(xlabel="t / tooth period", ylabel="D_pol [N]", title="Fig. 4a-e: load shapes")
ax[0].legend(fontsize=7)
ax[1].semilogy(d4.curve_speed, d4.peak_to_peak_short, label="k1 = AE/L_0 (short)")
ax[1].semilogy(d4.curve_speed, d4.peak_to_peak_long, label="k2 = AE/(L_0 + p) (long)")
for v in (float(d4.omega_c1), float(d4.omega_c2)):
    ax[1].axvline(v, color="k", ls=":")
ax[1].set(xlabel="omega_1 [rpm]", ylabel="peak-to-peak D_pol [N]", title="resonances omega_c1, omega_c2")
ax[1].legend(fontsize=8)
R.save_figure(fig, "fig04")

# %% [markdown]
# ## Fig. 5 — maximum amplitude vs speed: centre distance and periodic length change
# Each curve is one vectorised FD computation over all speeds (1.5 rpm grid; 2 rpm in ci).
# Dotted lines: speeds where the tooth frequency meets the Wickert–Mote frequencies of the
# short (green) / long (red) span.  19.7 pitches is the start of the paper's range.

# %%
cds_p, plain = study_with_base("fig05_plain_cd", "fig05_plain", "centre_distance", prm["centre_distance"])
cds_l, withl = study_with_base("fig05_length_cd", "fig05_length", "centre_distance", prm["centre_distance"])
fig, ax = plt.subplots(len(cds_p), 1, figsize=(9, 2.6 * len(cds_p)), sharex=True)
for i, cd in enumerate(cds_p):
    a = ax[i]
    a.semilogy(plain[i].speed, plain[i].amplitude * 1e3, "-", label="without length change")
    a.semilogy(withl[i].speed, withl[i].amplitude * 1e3, "--", label="with length change")
    mark_unstable(a, plain[i])
    mark_unstable(a, withl[i], label=None)
    for v in withl[i].resonance_speed_short.values:
        a.axvline(v, color="tab:green", ls=":", lw=0.7)
    for v in withl[i].resonance_speed_long.values:
        a.axvline(v, color="tab:red", ls=":", lw=0.7)
    a.set(ylabel="max |u| [mm]", title=f"Fig. 5: centre distance {cd} pitches")
a.set_xlabel("omega_1 [rpm]")
ax[0].legend(fontsize=7)
R.save_figure(fig, "fig05")

table_rows = []
for i, cd in enumerate(cds_p):
    for k in plain[i].order.values:
        for lab, ds, lo_var, hi_var in (("plain", plain[i], "resonance_speed_long", "resonance_speed_short"),
                                        ("length", withl[i], "resonance_speed_long", "resonance_speed_short")):
            lo, hi = C.order_window(float(ds[lo_var].sel(order=k)), float(ds[hi_var].sel(order=k)))
            found = C.peak_speeds(ds.speed.values, ds.amplitude.values, lo, hi,
                                  stable=~ds.unstable.values.astype(bool))
            table_rows.append([cd, int(k), lab, float(ds.resonance_speed_short.sel(order=k)),
                               float(ds.resonance_speed_long.sel(order=k)),
                               " ".join(f"{x:.1f}" for x in found)])
R.write_table("resonance_speeds", ["centre_distance_pitches", "order", "curve", "short_span_rpm",
                                   "long_span_rpm", "simulated_peaks_rpm"], table_rows)
timings = [[f"fig05_{lab}_cd{cd}", ds.speed.size, int(ds.n_points), int(ds.n_steps),
            float(ds.sweep_wall_time)]
           for lab, cds, dss in (("plain", cds_p, plain), ("length", cds_l, withl))
           for cd, ds in zip(cds, dss)]

# %% [markdown]
# ## Fig. 6 — moment of inertia of the driven sprocket, around the 3rd and 4th resonance

# %%
i2s, d6 = study_with_base("fig06_i2", "fig06_inertia", "driven_inertia", prm["driven_inertia"])
fig, ax = plt.subplots(figsize=(8, 3.6))
for v, d in zip(i2s, d6):
    ax.semilogy(d.speed, d.amplitude * 1e3, label=f"I2 = {v:g} kg m^2")
    mark_unstable(ax, d, label=f"unstable, I2 = {v:g}" if int(d.unstable.sum()) else None)
for v in np.concatenate([d6[0].resonance_speed_short.values, d6[0].resonance_speed_long.values]):
    if d6[0].speed[0] <= v <= d6[0].speed[-1]:
        ax.axvline(v, color="k", ls=":", lw=0.7)
ax.set(xlabel="omega_1 [rpm]", ylabel="max |u| [mm]", title="Fig. 6: effect of I2 (cd 20.25, length change)")
ax.legend(fontsize=8)
R.save_figure(fig, "fig06")

# %% [markdown]
# ## Fig. 7 — static tension (instabilities appear as T_s falls)

# %%
tss, d7 = study_with_base("fig07_ts", "fig07_tension", "static_tension", prm["static_tension"])
tss, d7 = tss[::-1], d7[::-1]        # the paper's order: high to low tension
fig, ax = plt.subplots(len(tss), 1, figsize=(8, 2.3 * len(tss)), sharex=True)
for a, v, d in zip(ax, tss, d7):
    a.semilogy(d.speed, d.amplitude * 1e3)
    mark_unstable(a, d)
    a.set(ylabel="max |u| [mm]", title=f"Fig. 7: T_s = {v:g} N ({int(d.unstable.sum())} unstable speeds)")
    a.legend(fontsize=7)
a.set_xlabel("omega_1 [rpm]")
R.save_figure(fig, "fig07")

# %% [markdown]
# ## Fig. 8 — external load T_ex = 0.2 T_s at 4, 2, 1 x omega_1

# %%
ws_, d8 = study_with_base("fig08_wex", "fig08_external", "external_frequency_ratio",
                          prm["external_frequency_ratio"])
ws_, d8 = ws_[::-1], d8[::-1]        # 4, 2, 1
base = R.run("fig08_none")
fig, ax = plt.subplots(len(d8) + 1, 1, figsize=(8, 2.3 * (len(d8) + 1)), sharex=True)
ax[0].semilogy(base.speed, base.amplitude * 1e3)
mark_unstable(ax[0], base)
ax[0].set(title="Fig. 8a: without external load", ylabel="max |u| [mm]")
for a, w, d in zip(ax[1:], ws_, d8):
    a.semilogy(base.speed, base.amplitude * 1e3, color="0.7", lw=0.8)
    a.semilogy(d.speed, d.amplitude * 1e3)
    mark_unstable(a, d)
    a.set(title=f"Fig. 8: T_ex = 0.2 T_s, omega_ex = {w:g} omega_1", ylabel="max |u| [mm]")
a.set_xlabel("omega_1 [rpm]")
R.save_figure(fig, "fig08")

# %% [markdown]
# ## Fig. 9 — medium speed with the elastic four-bar
# Each drive is swept over 0.25–1.25 x its own elastic four-bar resonance omega_c
# (dotted): the 15/40 drive resonates at ~6.6e3 rpm, far above the 24/24 drive.

# %%
d9a, d9b = R.run("fig09a"), R.run("fig09b")
fig, ax = plt.subplots(2, 1, figsize=(8, 5.5))
for a, d, lab in ((ax[0], d9a, "(a) n1 = n2 = 24, I2 = 0.002"), (ax[1], d9b, "(b) n1 = 15, n2 = 40, I2 = 0.0005")):
    a.semilogy(d.speed, d.amplitude * 1e3)
    mark_unstable(a, d)
    a.axvline(float(d.elastic_resonance_speed), color="k", ls=":", lw=0.8, label="omega_c")
    a.set(title=f"Fig. 9{lab}", ylabel="max |u| [mm]", xlabel="omega_1 [rpm]")
    a.legend(fontsize=7)
fig.tight_layout()
R.save_figure(fig, "fig09")

# %% [markdown]
# ## Fig. 10 — high speed: Galerkin (2-39..2-41), RK4; solve_ivp (DOP853, rtol 1e-9) check
# Fig. 10a is computed 5 % below the first longitudinal resonance: exactly at it the
# undamped longitudinal response grows without bound (no steady state to compare).

# %%
dL, dLu = R.run("fig10_longitudinal"), R.run("fig10_uncoupled")
dT, dTu = R.run("fig10_transverse5"), R.run("fig10_transverse5_uncoupled")
fig, ax = plt.subplots(2, 1, figsize=(9, 6))
ax[0].plot(dL.t * 1e3, dL.u_probe_rk4 * 1e3, lw=0.6, label="coupled, RK4")
ax[0].plot(dLu.t * 1e3, dLu.u_probe_rk4 * 1e3, lw=0.6, alpha=0.7, label="uncoupled, RK4")
ax[0].set(title=f"Fig. 10a: near the first longitudinal resonance ({float(dL.speed):.0f} rpm, "
                f"{float(dL.detuning):g} x)", ylabel="u(L/3) [mm]")
ax[0].legend(fontsize=7)
ax[1].plot(dT.t * 1e3, dT.u_probe_rk4 * 1e3, lw=0.6, label="coupled")
ax[1].plot(dTu.t * 1e3, dTu.u_probe_rk4 * 1e3, lw=0.6, alpha=0.7, label="uncoupled")
ax[1].set(title=f"Fig. 10b: fifth transverse resonance ({float(dT.speed):.0f} rpm)",
          xlabel="t [ms]", ylabel="u(L/3) [mm]")
ax[1].legend(fontsize=7)
fig.tight_layout()
R.save_figure(fig, "fig10")

# %% [markdown]
# ## Independent checks: exact moving-string vibration (Wickert–Mote) and a manufactured solution

# %%
ef, mms = R.run("exact_free"), R.run("manufactured")
n_c = ef.points.values.astype(float)
fig, ax = plt.subplots(1, 2, figsize=(10, 3.8))
for dname, mk in (("central", "o-"), ("mixed", "s-")):
    ax[0].loglog(n_c, ef.error_max.sel(differencing=dname), mk, label=f"exact mode, {dname}")
    ax[0].loglog(mms.points, mms.error_max.sel(differencing=dname), mk.replace("-", "--"),
                 label=f"manufactured, {dname}")
    ax[1].loglog(n_c, np.abs(ef.omega_fd.sel(differencing=dname) / ef.omega_exact - 1), mk, label=dname)
ax[0].set(xlabel="grid intervals", ylabel="max error", title="convergence (exact mode at c = 0.5 c_w)")
ax[0].legend(fontsize=7)
ax[1].set(xlabel="grid intervals", ylabel="|omega_FD / omega_WM - 1|", title="first frequency vs Wickert-Mote")
ax[1].legend(fontsize=7)
R.save_figure(fig, "exact_checks")

# %% [markdown]
# ## Cost of accuracy
# Peak amplitude and peak speed around the third resonance vs points per pitch (dx and dt
# refine together at fixed CFL) and vs the time step (CFL factor at fixed grid), against
# the finest run; Galerkin steady amplitude vs the number of transverse modes; the exact
# moving-string mode vs grid points.

# %%
def peak_of(ds):
    a = ds.amplitude.values
    i = int(np.nanargmax(a))
    # parabolic interpolation of the peak over the speed grid
    if 0 < i < a.size - 1:
        y0, y1, y2 = a[i - 1], a[i], a[i + 1]
        den = y0 - 2 * y1 + y2
        off = 0.5 * (y0 - y2) / den if den != 0 else 0.0
    else:
        off = 0.0
    sp = ds.speed.values
    return float(np.max(a)), float(sp[i] + off * (sp[1] - sp[0]))


def coa_sweep(study, knob, units, desc):
    st = R.study(study)
    vals = st[knob].values.astype(float)
    runs = [st.isel(run=i) for i in range(st.sizes["run"])]
    pk = np.array([peak_of(r) for r in runs])
    finest = np.argmax(vals) if knob != "cfl" else np.argmin(vals)
    err_a = np.abs(pk[:, 0] / pk[finest, 0] - 1)
    err_s = np.abs(pk[:, 1] / pk[finest, 1] - 1)
    keep = np.arange(len(vals)) != finest
    return cost_of_accuracy(paper, knob, vals[keep], st.sweep_wall_time.values[keep],
                            {"peak_amplitude": err_a[keep], "peak_speed": err_s[keep]},
                            "finest", units, desc)


coa_ppp = coa_sweep("accuracy_ppp", "points_per_pitch", "1", "FD sweep around the 3rd resonance")
coa_cfl = coa_sweep("accuracy_cfl", "cfl", "1", "FD sweep, time step via the CFL factor")
st = R.study("accuracy_modes")
nm = st.n_transverse.values.astype(float)
amp = st.steady_amplitude.values
ref_i = int(np.argmax(nm))
keep = np.arange(nm.size) != ref_i
coa_modes = cost_of_accuracy(paper, "n_transverse", nm[keep], st.rk4_wall_time.values[keep],
                             {"steady_amplitude": np.abs(amp[keep] / amp[ref_i] - 1)}, "finest", "1",
                             "Galerkin at the fifth transverse resonance")
coa_grid = cost_of_accuracy(paper, "points", n_c, ef.march_wall_time.sel(differencing="central").values,
                            {"exact_mode_central": ef.error_max.sel(differencing="central").values,
                             "exact_mode_mixed": ef.error_max.sel(differencing="mixed").values},
                            "exact", "1", "exact moving-string mode (wall time of the central march)")
fig, ax = plt.subplots(2, 2, figsize=(11, 8))
for a, ds in zip(ax.ravel(), (coa_ppp, coa_cfl, coa_modes, coa_grid)):
    plot(ds, ax=a)
R.save_figure(fig, "cost_of_accuracy")
R.write_dataset(coa_ppp, "cost_of_accuracy")
R.write_dataset(coa_cfl, "cost_of_accuracy_cfl")
R.write_dataset(coa_modes, "cost_of_accuracy_modes")
R.write_dataset(coa_grid, "cost_of_accuracy_grid")
tab = []
for ds in (coa_ppp, coa_cfl, coa_modes, coa_grid):
    for i, k in enumerate(ds.resolution.values):
        for v in [v for v in ds.data_vars if v.startswith("error_")]:
            tab.append([ds.attrs["knob"], float(k), v.removeprefix("error_"), float(ds[v][i]),
                        float(ds.wall_time[i])])
R.write_table("cost_of_accuracy", ["knob", "value", "quantity", "relative_error", "wall_time_s"], tab)
R.write_table("timings", ["sweep", "speeds", "grid_points", "time_steps", "wall_time_s"], timings)

# %% [markdown]
# ## Validation table
# Built by the framework (`validate_chain_drive`) from the `reported:` block: evidence class
# per row, verdicts re-checked at the next finer resolution and at the range ends of the
# assumed constants they depend on (a flipping verdict is `inconclusive`).

# %%
for r in table.values():
    print(f"{r['status']:12s} {r['evidence']:12s} {r['quantity']:52s} {r['note'][:120]}")
