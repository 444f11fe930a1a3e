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
from mechrepro.results import PaperResults

R = PaperResults(paper, results_dir, config_file, profile)

# %% [markdown]
# ## Fig. 1 — the free response, central differences against the exact Eq. (3)

# %%
R.figure("fig01")
