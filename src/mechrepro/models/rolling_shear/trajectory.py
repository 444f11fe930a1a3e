"""Trajectory 1 (Eq. 8) and the synthetic horizontal displacement (Sec. 3.3, Sec. 4).

Eq. (8): theta = huch / r, x = -huch + r sin(theta) + x0, y = r (1 - cos(theta)) + y0.
The paper does not say which points of Eqs. (5) and (8) correspond (``Geometry.eq8``):
``rotation`` compares at equal blade rotation from the first cut point,
dx_i = (x_k,i - x_k,0) + R (beta_i - beta_0); ``literal`` at theta = huch / R from the middle
cut point m, dx_i = R (sin beta_i - sin theta_i).  H is the mean |dx_i| (Abstract)."""
from __future__ import annotations

import numpy as np

from mechrepro.errors import Refusal

READINGS = ("rotation", "literal")


def trajectory1(huch, r: float, x0: float, y0: float):
    """Eq. (8): the pure-rolling midpoint trajectory."""
    huch = np.asarray(huch, float)
    th = huch / r
    return -huch + r * np.sin(th) + x0, r * (1.0 - np.cos(th)) + y0


def _literal_theta(g, beta, x_k):
    m = len(x_k) // 2
    return beta[m] + (x_k[m] - x_k) / g.R


def trajectory1_for(g, beta, x_k):
    """Trajectory 1 sampled at the cut points, in the reading ``g.eq8``."""
    beta, x_k = np.asarray(beta, float), np.asarray(x_k, float)
    if g.eq8 == "literal":
        th = _literal_theta(g, beta, x_k)
        return x_k + g.R * np.sin(th), -g.s + g.R * (1.0 - np.cos(th))
    return trajectory1(g.R * beta, g.R, x_k[0] + g.R * beta[0], -g.s)


def horizontal_displacement(g, beta, x_k):
    """Midpoint minus trajectory 1, horizontally, per cut point (mm), reading ``g.eq8``."""
    beta, x_k = np.asarray(beta, float), np.asarray(x_k, float)
    if g.eq8 == "literal":
        return g.R * (np.sin(beta) - np.sin(_literal_theta(g, beta, x_k)))
    if g.eq8 != "rotation":
        raise Refusal(f"eq8 reading {g.eq8!r}: allowed {READINGS}")
    return (x_k - x_k[0]) + g.R * (beta - beta[0])


def synthetic_horizontal_displacement(g, beta, x_k) -> float:
    """Mean |horizontal displacement| over the cut points (the paper's objective)."""
    return float(np.mean(np.abs(horizontal_displacement(g, beta, x_k))))
