"""Forward kinematics (Eq. 9): the blade under prescribed driving angles theta1, theta2, e.g.
both levers at a constant rate instead of the reverse-solved motion laws."""
from __future__ import annotations

import math

import numpy as np

from .blade import lowest_point
from .geometry import Geometry
from .loops import NonAssembly, on_design_branch, residuals


def _jacobian(g: Geometry, t3, t4, t5, t6) -> np.ndarray:
    """d b / d(theta3, theta4, theta5, theta6) of Eq. (9)."""
    return np.array([
        [g.l3 * math.sin(t3), 0.0, g.l8 * math.sin(t5 + g.alpha), g.l6 * math.sin(t6)],
        [-g.l3 * math.cos(t3), 0.0, -g.l8 * math.cos(t5 + g.alpha), -g.l6 * math.cos(t6)],
        [0.0, g.l4 * math.sin(t4), g.l5 * math.sin(t5), g.l6 * math.sin(t6)],
        [0.0, -g.l4 * math.cos(t4), -g.l5 * math.cos(t5), -g.l6 * math.cos(t6)],
    ])


def drive(g: Geometry, theta1, theta2, start, tol: float = 1e-11, max_iter: int = 30):
    """theta1..theta6 along prescribed driving angles, warm-started from ``start`` (6,); raises
    NonAssembly at the step that fails or leaves the design branch."""
    x = np.asarray(start, float)[2:].copy()          # theta3..theta6
    out = np.empty((len(theta1), 6))
    prev = None
    for i, (t1, t2) in enumerate(zip(theta1, theta2)):
        guess = x if prev is None else 2 * x - prev
        y = guess.copy()
        for _ in range(max_iter):
            f = residuals(g, np.array([t1, t2, y[0], y[1]]), y[2], y[3])
            if np.abs(f).sum() < tol:
                break
            y = y - np.linalg.solve(_jacobian(g, *y), f)
        th = np.array([t1, t2, *y])
        if np.abs(residuals(g, th[:4], th[4], th[5])).sum() >= tol or not on_design_branch(g, th):
            raise NonAssembly(f"drive step {i}: no assembly on the design branch for "
                              f"theta1 = {t1:.6g}, theta2 = {t2:.6g} rad", i)
        prev, x = x, y
        out[i] = th
    return out


def constant_rate_drive(g: Geometry, theta_stroke: np.ndarray) -> dict:
    """Both levers turned at a constant rate between the start and end of a solved stroke."""
    tau = np.linspace(0.0, 1.0, theta_stroke.shape[0])
    t1 = theta_stroke[0, 0] + tau * (theta_stroke[-1, 0] - theta_stroke[0, 0])
    t2 = theta_stroke[0, 1] + tau * (theta_stroke[-1, 1] - theta_stroke[0, 1])
    th = drive(g, t1, t2, theta_stroke[0])
    xk, yk = lowest_point(g, th[:, 4], th[:, 5])
    return {"theta": th, "x_k": xk, "y_k": yk}
