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
# # toy — free vibration of a damped oscillator

# %% tags=["parameters"]
paper = "toy"
results_dir = "results"
config_file = "config/papers/toy.yaml"
profile = "default"

# %%
from mechrepro.plotting import plt
from mechrepro.results import PaperResults

R = PaperResults(paper, results_dir, config_file, profile)
ds = R.run("response")

# %% [markdown]
# ## Fig. 1 — the free response, central differences against the exact Eq. (3)

# %%
fig, ax = plt.subplots()
ax.plot(ds["t"], ds["displacement"], label="central differences")
ax.plot(ds["t"], ds["displacement_exact"], "--", label="exact, Eq. (3)")
ax.set(xlabel="t [s]", ylabel="x [m]")
ax.legend()
R.save_figure(fig, "fig01")
