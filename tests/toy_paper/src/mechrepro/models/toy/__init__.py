"""toy: free vibration of a damped oscillator, marched by central differences (Eq. 1).

    m x'' + c x' + k x = 0,  x(0) = 1,  x'(0) = 0                                    (1)
    c = 2 zeta sqrt(k m)                                                              (2)
    x(t) = exp(-zeta w t) (cos(w_d t) + zeta w / w_d sin(w_d t)),  w_d = w sqrt(1 - zeta^2)  (3)

A paper this small keeps its effects (damping: physics, Eq. 2; the exact response: a
reference, Eq. 3) and its reproduced value in this one module.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechrepro.effects import EffectRegistry
from mechrepro.units import var
from mechrepro.validation import Quantities, Reproduced

EFFECTS = EffectRegistry("toy")
Q = Quantities("toy")


@dataclass(frozen=True)
class Context:
    t: np.ndarray
    mass: float
    stiffness: float
    damping_ratio: float


@EFFECTS.register("damping")
def damping(ctx: Context) -> dict:
    return {"damping_coefficient": 2 * ctx.damping_ratio * np.sqrt(ctx.stiffness * ctx.mass)}


@EFFECTS.register("exact_reference")
def exact_reference(ctx: Context) -> dict:
    w = np.sqrt(ctx.stiffness / ctx.mass)
    z = ctx.damping_ratio
    wd = w * np.sqrt(1 - z**2)
    x = np.exp(-z * w * ctx.t) * (np.cos(wd * ctx.t) + z * w / wd * np.sin(wd * ctx.t))
    return {"displacement_exact": var("t", x, "m", "displacement, exact Eq. (3)")}


def context(run: dict) -> Context:
    """The run's oscillator and its time grid, ``steps_per_period`` steps per undamped period."""
    p = run["parameters"]
    # options.springs = parallel: the rival reading of the textbook's spring as its two equal
    # halves side by side instead of in series, four times as stiff (rivals.stiffer_spring)
    parallel = run.get("options", {}).get("springs") == "parallel"
    m, k = p["mass"], p["stiffness"] * (4.0 if parallel else 1.0)
    n = run["resolution"]["steps_per_period"]
    dt = 2 * np.pi / np.sqrt(k / m) / n
    return Context(t=dt * np.arange(5 * n + 1), mass=m, stiffness=k,
                   damping_ratio=p["damping_ratio"])


def central_difference(run: dict, ctx: Context) -> dict:
    """Eq. (1) marched by central differences from x(0) = 1, v(0) = 0."""
    c = EFFECTS.evaluate(run, ctx)
    damping = float(c.total("damping_coefficient")) if "damping_coefficient" in c else 0.0
    t, m, k = ctx.t, ctx.mass, ctx.stiffness
    dt = t[1]                                               # the grid's step, exactly
    x = np.empty_like(t)
    x[0] = 1.0
    x[1] = 1.0 - 0.5 * dt**2 * k / m                        # Taylor start, v(0) = 0
    a, b = m / dt**2 + damping / (2 * dt), m / dt**2 - damping / (2 * dt)
    for i in range(1, t.size - 1):
        x[i + 1] = ((2 * m / dt**2 - k) * x[i] - b * x[i - 1]) / a
    beside = {key: c.get(key) for key in c.keys() if key != "damping_coefficient"}
    return {"t": t, "x": x, "beside": beside}


SOLVERS = {"central_difference": central_difference}


def variables(result: dict, run: dict) -> dict:
    return {"t": var("t", result["t"], "s", "time"),
            "displacement": var("t", result["x"], "m", "displacement x, Eq. (1)"),
            **result["beside"]}


@Q.register("natural_frequency")
def natural_frequency(R):
    """The frequency from the mean spacing of the upward zero crossings, linearly
    interpolated (their own error is far below a step, so none is added)."""
    ds = R.run("response")
    t, x = ds["t"].values, ds["displacement"].values
    i = np.flatnonzero((x[:-1] < 0) & (x[1:] >= 0))
    up = t[i] - x[i] * (t[i + 1] - t[i]) / (x[i + 1] - x[i])
    return Reproduced(float(1.0 / np.mean(np.diff(up))), f"{up.size} upward zero crossings")


def fig01(R):
    """Fig. 1: the free response, central differences against the exact Eq. (3)."""
    from mechrepro.plotting import plt

    ds = R.run("response")
    fig, ax = plt.subplots()
    ax.plot(ds["t"], ds["displacement"], label="central differences")
    ax.plot(ds["t"], ds["displacement_exact"], "--", label="exact, Eq. (3)")
    ax.set(xlabel="t [s]", ylabel="x [m]")
    ax.legend()
    return fig
