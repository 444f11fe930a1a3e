"""Blade pose: transforms M12, M20 (Eq. 4), midpoint (Eq. 5), dynamic lowest point (Eqs. 6-7),
and the pose at a cut point, theta5, theta6 from Eq. (7) with the lowest point on y = -s, whose
reference :func:`exact_pose` solves |ED| = l6 for the blade angle by Brent's method.

Where the printed equations contradict each other (mm, rad, y up): M20 rotates by
**+theta5** (Eq. 9 measures theta5 counter-clockwise and beta = theta5 - beta2 holds only
then); Eq. (6) is y_k = y_h **-** R(1 - cos beta), the only sign under which y_k stays
constant under the rolling of Eq. (8).  Forward kinematics (Eq. 9): the blade under
prescribed driving angles theta1, theta2, e.g. both levers at a constant rate.  The assembled
linkage of a solved run, for drawing (Figs. 2-5)."""
from __future__ import annotations

import functools
import math

import numpy as np

from .geometry import GEOMETRY_KEYS, Geometry
from .loops import NonAssembly, columns, on_design_branch, pivots, residuals, stacked


def to_fixed(g: Geometry, theta5, theta6, x1, y1):
    """Eq. (4), M20 M12 (x1, y1), for arrays of poses (:func:`.closure.to_fixed`; M20 rotates by
    **+theta5**, the corrected sign, see module doc)."""
    from .closure import python

    return python.to_fixed(g, np.asarray(theta5, float), np.asarray(theta6, float), x1, y1)


def midpoint(g: Geometry, theta5, theta6):
    """Eq. (5): midpoint (0, -h) of the cutting edge in the fixed frame."""
    return to_fixed(g, theta5, theta6, 0.0, -g.h)


def lowest_point(g: Geometry, theta5, theta6):
    """Eq. (7) with the corrected sign of Eq. (6) (:func:`.closure.lowest_point`)."""
    from .closure import python

    return python.lowest_point(g, np.asarray(theta5, float), np.asarray(theta6, float))


def pose_residuals(g: Geometry, th, x_target: float):
    """Eq. (7) residuals for one or many (theta5, theta6) candidates (..., 2)
    (:func:`.closure.lowest_point`)."""
    from .closure import python

    xk, yk = python.lowest_point(g, *columns(th))
    return stacked([xk - x_target, yk + g.s])


#: Brent's relative tolerance (scipy's least)
RTOL = 4 * np.finfo(float).eps


@functools.lru_cache(maxsize=8)
def _scan_grid(beta_window: float, n_scan: int) -> tuple[np.ndarray, float]:
    """The scan grid of :func:`exact_pose` (read-only) and its step squared."""
    betas = np.linspace(-beta_window, beta_window, n_scan)
    betas.setflags(write=False)
    return betas, (betas[1] - betas[0]) ** 2


def exact_pose(g: Geometry, x_target: float, beta_window: float = 0.3, n_scan: int = 601):
    """Reference (theta5, theta6) on the design mode of the guide rod: the root of |ED(beta)| - l6
    over |beta| <= beta_window in the paper's ranges with the smallest |beta|; raises
    NonAssembly when none qualifies."""
    from . import closure, kernels

    betas, step2 = _scan_grid(float(beta_window), int(n_scan))
    # a root between two grid points where D lies clearly on the other side of E (the
    # other assembly mode of the guide rod) cannot qualify: x of D is within
    # (|R - h| + d) (d beta)^2 / 8 of the chord between the grid points, so it keeps its sign
    margin = (abs(g.R - g.h) + g.d) * step2
    found, t5, t6, status = kernels.kernel("guide_pose")(
        g.constants, betas, np.empty_like(betas), np.empty_like(betas), float(x_target),
        float(g.guide_mode), float(margin), 1e-15, RTOL, 200)
    if status == closure.NO_CONVERGENCE:
        raise RuntimeError(f"Brent's method did not converge in 200 iterations (x_k = {x_target})")
    if status != closure.CONVERGED:
        raise ValueError(f"|ED| - l6 is NaN or keeps its sign in a bracket (x_k = {x_target})")
    if not found:
        raise NonAssembly(f"guide rod l6 = {g.l6:.6g} mm cannot reach the carrier with the "
                          f"lowest point at x_k = {x_target:.6g} mm (no root of |ED| = l6 for "
                          f"|beta| <= {beta_window})", x_k=x_target)
    return np.array([t5, t6])


def lowest_point_jacobian(g: Geometry, theta5: float, theta6: float) -> np.ndarray:
    """d(x_k, y_k)/d(theta5, theta6) of Eq. (7), analytic."""
    b = theta5 - g.beta2
    # d/dtheta5 of O + Rot(b)(0,-h) + (-R sin b, -R(1 - cos b))
    dx5 = -g.d * np.sin(theta5 + g.beta1) + g.h * np.cos(b) - g.R * np.cos(b)
    dy5 = g.d * np.cos(theta5 + g.beta1) + g.h * np.sin(b) - g.R * np.sin(b)
    dx6 = -g.l6 * np.sin(theta6)
    dy6 = g.l6 * np.cos(theta6)
    return np.array([[dx5, dx6], [dy5, dy6]])


def arc_points(g: Geometry, theta5: float, theta6: float, half_angle: float, n: int = 2001):
    """Points of the cutting-edge arc (centre R above the midpoint), for tests and plots."""
    phi = np.linspace(-half_angle, half_angle, n)
    x1 = g.R * np.sin(phi)
    y1 = -g.h + g.R * (1.0 - np.cos(phi))
    return to_fixed(g, theta5, theta6, x1, y1)


def carrier_points(g: Geometry, theta5, theta6) -> dict:
    """Joints of the blade carrier in the fixed frame: D, I, C, O (complex numbers)."""
    theta5, theta6 = np.asarray(theta5, float), np.asarray(theta6, float)
    D = g.l6 * np.exp(1j * theta6)
    return {"D": D, "I": D + g.l5 * np.exp(1j * theta5),
            "C": D + g.l8 * np.exp(1j * (theta5 + g.alpha)),
            "O": D + g.d * np.exp(1j * (theta5 + g.beta1))}


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


def geometry_of(ds) -> Geometry:
    """The run's own geometry (calibrated, with the scene's levers) from its dataset."""
    return Geometry(**{k: float(ds[f"geometry_{k}"]) for k in GEOMETRY_KEYS})


def linkage_at(ds, i: int, prefix: str = "exact", blade_half_width: float = 1900.0) -> dict:
    """The linkage at cut point ``i`` (motion laws ``<prefix>_theta1..6``): ``links``, (start, end)
    joint pairs as complex x + iy, and ``blade``, the cutting-edge arc over +- ``blade_half_width``."""
    g = geometry_of(ds)
    t = [float(ds[f"{prefix}_theta{k}"][i]) for k in range(1, 7)]
    P = carrier_points(g, t[4], t[5])
    A, G = pivots(g)
    B = A + g.l1 * np.exp(1j * t[0])
    H = G + g.l2 * np.exp(1j * t[1])
    links = [(0j, P["D"]), (A, B), (B, P["C"]), (G, H), (H, P["I"]), (P["D"], P["I"]),
             (P["D"], P["C"]), (P["D"], P["O"])]
    return {"links": links, "blade": arc_points(g, t[4], t[5], blade_half_width / g.R, 200)}
