"""The one cost-of-accuracy helper: error against a trusted reference vs wall time.

Every solver run records its own wall time with :func:`time_call`.  A study over the
paper's **resolution** knob is then condensed by :func:`cost_of_accuracy` into one
dataset (dimension ``resolution``) holding, per quantity of interest, the error against
the reference (``exact`` solution or the ``finest`` run)
and the wall time; :func:`plot` draws it, the same way for all papers.
"""
from __future__ import annotations

import time

import numpy as np
import xarray as xr


def time_call(fn, *args, min_time: float = 0.05, max_repeat: int = 50, **kwargs):
    """Call ``fn`` until ``min_time`` has elapsed; return (first result, fastest call [s]).

    Fast solves are repeated and the fastest call is kept (as ``timeit`` advises): the
    other calls measure the machine's other load, not the solver.
    """
    t_start = time.perf_counter()
    result = fn(*args, **kwargs)
    best = time.perf_counter() - t_start
    n = 1
    while time.perf_counter() - t_start < min_time and n < max_repeat:
        t0 = time.perf_counter()
        fn(*args, **kwargs)
        best = min(best, time.perf_counter() - t0)
        n += 1
    return result, best


def observed_order(h, err) -> float:
    """Least-squares slope of log(err) vs log(h): the observed order of convergence."""
    h, err = np.asarray(h, float), np.asarray(err, float)
    ok = (err > 0) & np.isfinite(err)
    return float(np.polyfit(np.log(h[ok]), np.log(err[ok]), 1)[0])


def cost_of_accuracy(paper: str, knob: str, knob_values, wall_time_s, errors: dict,
                     reference: str, knob_units: str = "1", description: str = "") -> xr.Dataset:
    """Assemble the cost-of-accuracy dataset of one paper (dimension ``resolution``)."""
    order = np.argsort(np.asarray(knob_values, float))
    coords = {"resolution": ("resolution", np.asarray(knob_values)[order],
                             {"long_name": f"resolution knob {knob}", "units": knob_units})}
    data = {"wall_time": ("resolution", np.asarray(wall_time_s, float)[order],
                          {"long_name": "wall time of one solve", "units": "s"})}
    for name, err in errors.items():
        data[f"error_{name}"] = ("resolution", np.asarray(err, float)[order],
                                 {"long_name": f"relative error of {name} vs {reference}",
                                  "units": "1"})
    return xr.Dataset(data, coords, attrs={"paper": paper, "knob": knob,
                                           "reference": reference, "description": description})


def plot(ds: xr.Dataset, ax=None, annotate: bool = True):
    """Error vs wall time, one line per quantity, points labelled with the knob value."""
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(6, 4.2))
    t = ds["wall_time"].values
    for name in [v for v in ds.data_vars if v.startswith("error_")]:
        ax.loglog(t, ds[name].values, "o-", label=name.removeprefix("error_"))
    if annotate:
        first = [v for v in ds.data_vars if v.startswith("error_")][0]
        for x, y, k in zip(t, ds[first].values, ds["resolution"].values):
            ax.annotate(f"{ds.attrs['knob']}={k}", (x, y), fontsize=7,
                        textcoords="offset points", xytext=(4, 4))
    ax.set_xlabel("wall time per solve [s]")
    ax.set_ylabel(f"relative error vs {ds.attrs['reference']}")
    ax.set_title(f"{ds.attrs['paper']}: cost of accuracy ({ds.attrs['knob']})")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    return ax
