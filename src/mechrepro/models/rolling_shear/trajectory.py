"""Trajectory 1 (Eq. 8) and the synthetic horizontal displacement (Sec. 3.3, Sec. 4).

Eq. (8): theta = huch / r,  x = -huch + r sin(theta) + x0,  y = r (1 - cos(theta)) + y0
is the midpoint of an arc of radius r = R rolling without slip to the left on y = y0.

Corresponding points: the paper compares "the difference between (5) and (8)" at the
calculated points without saying how points correspond.  We compare at equal blade
rotation: trajectory 1 is the pure rolling that starts from the actual pose at the
first cut point, huch = R (beta - beta_0), x0 = x_k,0 + R beta_0, y0 = -s.  Then the
vertical difference is zero (the lowest point is held on y = -s) and the horizontal
difference is the slip of the blade on the plate accumulated since the start of the cut:

    dx_i = x_h,i - x_1,i = (x_k,i - x_k,0) + R (beta_i - beta_0).

The synthetic horizontal displacement is its mean absolute value over the cut points
("mean value of all horizontal displacement relating to calculated points", Abstract).
"""
from __future__ import annotations

import numpy as np


def trajectory1(huch, r: float, x0: float, y0: float):
    """Eq. (8): the pure-rolling midpoint trajectory."""
    huch = np.asarray(huch, float)
    th = huch / r
    return -huch + r * np.sin(th) + x0, r * (1.0 - np.cos(th)) + y0


def trajectory1_for(beta, x_k, R: float, s: float):
    """Trajectory 1 through the first cut point, sampled at the actual blade angles.

    theta of Eq. (8) is the blade angle beta, so huch = R beta is counted from the
    (virtual) pose beta = 0 of the pure rolling that passes through the first cut point.
    """
    beta, x_k = np.asarray(beta, float), np.asarray(x_k, float)
    return trajectory1(R * beta, R, x_k[0] + R * beta[0], -s)


def horizontal_displacement(beta, x_k, R: float):
    """Slip of the midpoint relative to trajectory 1, per cut point (mm)."""
    beta, x_k = np.asarray(beta, float), np.asarray(x_k, float)
    return (x_k - x_k[0]) + R * (beta - beta[0])


def synthetic_horizontal_displacement(beta, x_k, R: float) -> float:
    """Mean |horizontal displacement| over the cut points (the paper's objective)."""
    return float(np.mean(np.abs(horizontal_displacement(beta, x_k, R))))
