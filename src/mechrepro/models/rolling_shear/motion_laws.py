"""What one solved stroke gives (Figs. 9-11, 13, 14) as dataset variables (mm, rad)."""
from __future__ import annotations

import numpy as np

from mechrepro.units import var

from .blade import lowest_point, midpoint
from .geometry import Geometry
from .loops import dyad_margins
from .trajectory import horizontal_displacement, trajectory1_for

ANGLE_NAMES = ("theta1", "theta2", "theta3", "theta4", "theta5", "theta6")
#: cut points of the nested grid on which the motion laws are interpolated (2^12 + 1):
#: the nodes of every run with 2^k + 1 cut points (k <= 12) are points of it
LAW_GRID = 4097


def angle_vars(prefix: str, theta: np.ndarray, what: str) -> dict:
    return {f"{prefix}_{n}": var("cut", theta[:, j], "rad", f"{n}, {what}")
            for j, n in enumerate(ANGLE_NAMES)}


def stroke_outputs(g: Geometry, theta: np.ndarray, prefix: str, what: str) -> dict:
    """Motion laws, lowest points (Eq. 7), midpoints (Eq. 5), trajectory 1 (Eq. 8), H and the
    dyad margins of one stroke."""
    t5, t6 = theta[:, 4], theta[:, 5]
    xk, yk = lowest_point(g, t5, t6)
    xh, yh = midpoint(g, t5, t6)
    beta = t5 - g.beta2
    x1, y1 = trajectory1_for(g, beta, xk)
    dx = horizontal_displacement(g, beta, xk)
    out = angle_vars(prefix, theta, what)
    out.update({
        f"{prefix}_x_k": var("cut", xk, "mm", f"dynamic lowest point x_k, Eq. (7), {what}"),
        f"{prefix}_y_k": var("cut", yk, "mm", f"dynamic lowest point y_k, Eq. (7), {what}"),
        f"{prefix}_overlap_deviation": var("cut", np.abs(yk + g.s), "mm",
                                           f"|y_k + s|, distance from the overlap line, {what}"),
        f"{prefix}_x_h": var("cut", xh, "mm", f"blade midpoint x_h, Eq. (5), {what}"),
        f"{prefix}_y_h": var("cut", yh, "mm", f"blade midpoint y_h, Eq. (5), {what}"),
        f"{prefix}_x_traj1": var("cut", x1, "mm", f"trajectory 1 x, Eq. (8), {what}"),
        f"{prefix}_y_traj1": var("cut", y1, "mm", f"trajectory 1 y, Eq. (8), {what}"),
        f"{prefix}_beta": var("cut", beta, "rad", f"blade angle beta = theta5 - beta2, {what}"),
        f"{prefix}_horizontal_displacement": var("cut", dx, "mm",
                                                 f"midpoint minus trajectory 1 (slip), {what}"),
        f"{prefix}_dyad_margin": var(("cut", "loop"), dyad_margins(g, t5, t6), "mm",
                                     f"distance of each dyad from toggle/fold, {what}"),
        f"{prefix}_synthetic_horizontal_displacement":
            var((), np.mean(np.abs(dx)), "mm", f"synthetic horizontal displacement, {what}"),
        f"{prefix}_synthetic_horizontal_displacement_best_anchor":
            var((), np.mean(np.abs(dx - np.median(dx))), "mm",
                f"synthetic horizontal displacement with trajectory 1 shifted to its best "
                f"horizontal position (median), {what}"),
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
