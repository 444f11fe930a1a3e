"""Which assembly branch a solution is on: the paper's ranges (Sec. 3.1) do not separate the
guide rod's two modes nor the mirror modes of the dyad l1 = l3, so the *design branch* adds
the assembly modes of :class:`Geometry`, which the machine cannot leave without a toggle."""
from __future__ import annotations

import math

import numpy as np

from .geometry import Geometry
from .loops import elbow_signs

TWO_PI = 2.0 * math.pi
#: the paper's ranges, order theta1..theta6 (lower, upper)
RANGES = ((math.pi, TWO_PI), (math.pi, TWO_PI), (0.0, math.pi), (0.0, math.pi),
          (0.0, math.pi), (math.pi, TWO_PI))


def wrap(theta):
    return np.mod(np.asarray(theta, float), TWO_PI)


def in_ranges(theta6, which=range(6)) -> bool:
    """theta (6,) (theta1..theta6) inside the paper's ranges, angles taken mod 2 pi."""
    t = wrap(theta6)
    return all(RANGES[i][0] <= t[i] <= RANGES[i][1] for i in which)


def on_design_branch(g: Geometry, theta6) -> bool:
    """Paper's ranges and the design assembly modes of guide rod and both dyads."""
    t = wrap(theta6)
    if not in_ranges(t):
        return False
    if g.guide_mode * math.cos(t[5]) <= 0:
        return False
    e1, e2 = elbow_signs(g, t[:4], t[4], t[5])
    return e1 == g.elbow1 and e2 == g.elbow2
