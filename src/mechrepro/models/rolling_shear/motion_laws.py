"""What one solved stroke gives (Figs. 9-11, 13, 14) as dataset variables (mm, rad).

Trajectory 1, Eq. (8): theta = huch / r, x = -huch + r sin(theta) + x0, y = r (1 - cos(theta)) + y0.
The paper does not say which points of Eqs. (5) and (8) correspond (``Geometry.eq8``):
``rotation`` compares at equal blade rotation from the first cut point,
dx_i = (x_k,i - x_k,0) + R (beta_i - beta_0); ``literal`` at theta = huch / R from the middle
cut point m, dx_i = R (sin beta_i - sin theta_i).  H is the mean |dx_i| (Abstract)."""
from __future__ import annotations

import numpy as np

from mechrepro.errors import Refusal
from mechrepro.units import var

from .blade import lowest_point, midpoint
from .geometry import Geometry

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


ANGLE_NAMES = ("theta1", "theta2", "theta3", "theta4", "theta5", "theta6")
#: cut points of the nested grid on which the motion laws are interpolated (2^12 + 1):
#: the nodes of every run with 2^k + 1 cut points (k <= 12) are points of it
LAW_GRID = 4097


def stroke_outputs(g: Geometry, theta: np.ndarray, prefix: str, what: str) -> dict:
    """Motion laws, lowest points (Eq. 7), midpoints (Eq. 5), trajectory 1 (Eq. 8) and H of one
    stroke."""
    t5, t6 = theta[:, 4], theta[:, 5]
    xk, yk = lowest_point(g, t5, t6)
    xh, yh = midpoint(g, t5, t6)
    beta = t5 - g.beta2
    x1, y1 = trajectory1_for(g, beta, xk)
    dx = horizontal_displacement(g, beta, xk)
    out = {f"{prefix}_{n}": var("cut", theta[:, j], "rad", f"{n}, {what}")
           for j, n in enumerate(ANGLE_NAMES)}
    out.update({
        f"{prefix}_x_k": var("cut", xk, "mm", f"dynamic lowest point x_k, Eq. (7), {what}"),
        f"{prefix}_y_k": var("cut", yk, "mm", f"dynamic lowest point y_k, Eq. (7), {what}"),
        f"{prefix}_overlap_deviation": var("cut", np.abs(yk + g.s), "mm",
                                           f"|y_k + s|, distance from the overlap line, {what}"),
        f"{prefix}_x_h": var("cut", xh, "mm", f"blade midpoint x_h, Eq. (5), {what}"),
        f"{prefix}_y_h": var("cut", yh, "mm", f"blade midpoint y_h, Eq. (5), {what}"),
        f"{prefix}_x_traj1": var("cut", x1, "mm", f"trajectory 1 x, Eq. (8), {what}"),
        f"{prefix}_y_traj1": var("cut", y1, "mm", f"trajectory 1 y, Eq. (8), {what}"),
        f"{prefix}_horizontal_displacement": var("cut", dx, "mm",
                                                 f"midpoint minus trajectory 1 (slip), {what}"),
        f"{prefix}_synthetic_horizontal_displacement":
            var((), np.mean(np.abs(dx)), "mm", f"synthetic horizontal displacement, {what}"),
        f"{prefix}_overlap_max_deviation":
            var((), np.max(np.abs(yk + g.s)), "mm", f"max |y_k + s| over the cut, {what}"),
    })
    return out


def driving_laws_on_grid(huch: np.ndarray, theta: np.ndarray, width: float,
                         prefix: str, what: str) -> dict:
    """theta1, theta2 (Figs. 13-14) by cubic spline on the nested LAW_GRID, so that runs with
    different cut points share one axis (:mod:`.accuracy`)."""
    from scipy.interpolate import CubicSpline

    grid = np.linspace(0.0, width, LAW_GRID)
    return {f"{prefix}_law_theta{k}": var(
        "law_point", CubicSpline(huch, theta[:, k - 1])(grid), "rad",
        f"theta{k} interpolated (cubic spline) on {LAW_GRID} cut points, {what}")
        for k in (1, 2)}


def pose_error(theta, ref) -> np.ndarray:
    """|theta - closed form| per cut point and angle (rad, wrapped to [0, pi]); a wrong assembly
    mode is an error of order 1 rad."""
    return np.abs(np.angle(np.exp(1j * (np.asarray(theta) - np.asarray(ref)))))
