"""The toy's effects: damping (physics, Eq. 2) and the exact response (a reference, Eq. 3)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechrepro.effects import EffectRegistry
from mechrepro.units import var

EFFECTS = EffectRegistry("toy")


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
