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
from mechrepro.results import PaperResults

R = PaperResults(paper, results_dir, config_file, profile)

# %% [markdown]
# ## Fig. 1 — impact load (Eqs. 2-2..2-4, Appendix I)
# The pressure angle of Eq. (2-3) is garbled in the text; we take the ANSI transition
# angle eta = 35 deg + 60 deg / n1 (docs/chain_drive.md).

# %%
R.figure("fig01")


# %% [markdown]
# ## Fig. 3 — rigid four-bar: driven speed and polygonal load at 300 rpm

# %%
R.figure("fig03")


# %% [markdown]
# ## Fig. 4 — elastic four-bar (Eqs. 2-11..2-23)
# A X = F (Eq. 2-20) is obtained by projecting Eq. (2-19) on the nine harmonics numerically
# (Appendix II has duplicated/garbled entries), then solved by least squares (Eq. 2-21).
# **Scale**: at the resonances the load reaches tens of kN (the right panel's dashed line
# is the static tension T_s = 400 N): the four-bar has no damping, so only the truncated
# harmonic balance limits it, and a real span would go slack long before (the paper
# comments no magnitude; the ratio is the validation row elastic_load_peak_over_static_tension).

# %%
R.figure("fig04")


# %% [markdown]
# ## Fig. 5 — maximum amplitude vs speed: centre distance and periodic length change
# With length change (the verdicts): the discrete-link span, whose roller released at the
# driven and seated at the driving sprocket per tooth period *is* the length change.  The
# paper's string model at its resolution beside it: without (solid) and with (dashed)
# length change; a span of a non-integral number of links (the solid lines' L_ct) has no
# discrete counterpart.  Dotted lines: speeds where the tooth frequency meets the
# Wickert–Mote frequencies of the short (green) / long (red) span.  19.7 pitches is the
# start of the paper's range.

# %%
R.figure("fig05")
R.tabulate("resonance_speeds")
R.tabulate("timings")


# %% [markdown]
# ## Fig. 6 — moment of inertia of the driven sprocket, around the 3rd and 4th resonance
# The discrete-link span (the verdicts) per I2; the paper's string model at its resolution
# beside it at the scene's own I2.

# %%
R.figure("fig06")


# %% [markdown]
# ## Fig. 7 — static tension (instabilities appear as T_s falls)

# %%
R.tabulate("discrete_peaks")
R.figure("fig07")


# %% [markdown]
# ## Fig. 8 — external load T_ex = 0.2 T_s at 4, 2, 1 x omega_1

# %%
R.figure("fig08")


# %% [markdown]
# ## Fig. 9 — medium speed with the elastic four-bar
# Each drive is swept over 0.25–1.25 x its own elastic four-bar resonance omega_c
# (dotted): the 15/40 drive resonates at ~6.6e3 rpm, far above the 24/24 drive.

# %%
R.figure("fig09")


# %% [markdown]
# ## Fig. 10 — high speed: Galerkin (2-39..2-41), RK4; solve_ivp (DOP853, rtol 1e-9) check
# Fig. 10a is computed 5 % below the first longitudinal resonance: exactly at it the
# undamped longitudinal response grows without bound (no steady state to compare).

# %%
R.figure("fig10")


# %% [markdown]
# ## Beyond the paper — stability chart over speed and static tension (discrete-link span)
# The largest Floquet multiplier of the tooth-period map per (speed, T_s): the design
# message of Fig. 7 (how low a static tension a drive may run at) as a map; Fig. 7's
# tensions dotted.  Default profile (ci: one tension, a few speeds).

# %%
R.figure("chart_tension")


# %% [markdown]
# ## Independent checks: exact moving-string vibration (Wickert–Mote) and a manufactured solution

# %%
R.figure("exact_checks")


# %% [markdown]
# ## Cost of accuracy
# Written by the framework from the config's `accuracy:` block: peak amplitude and peak
# speed around the third resonance vs points per pitch (dx and dt refine together) and vs
# the CFL factor, against the finest run; the string's peak at 4 / 8 / 16 points per pitch
# against the discrete-link span's (its pitch-scale error, both schemes); Galerkin steady amplitude vs the number of
# transverse modes; the FD march of the exact moving-string mode vs grid points.

# %%
R.figure("cost_of_accuracy")


# %% [markdown]
# ## Validation table
# Built by the framework (`validate_chain_drive`) from the `reported:` block: evidence class
# per row, verdicts re-checked at the next finer resolution and at the range ends of the
# assumed constants they depend on (a flipping verdict is `inconclusive`).

# %%
for r in R.validation():
    print(f"{r['status']:12s} {r['evidence']:12s} {r['quantity']:52s} {r['note'][:120]}")
