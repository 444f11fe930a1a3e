"""Blade pose at a cut point: theta5, theta6 from Eq. (7) with the lowest point on y = -s.

Two unknowns, two equations (Sec. 3.2):  x_k(theta5, theta6) = x_k*,  y_k(theta5, theta6) = -s.
:func:`exact_pose` is the trusted reference: for a blade angle beta the pose with the
lowest point at (x_k*, -s) is fixed, and the guide rod closes only if |ED| = l6 -- one
scalar equation in beta, bracketed and solved by Brent's method.
"""
from __future__ import annotations

import functools
import math

import numpy as np
from scipy.optimize import brentq

from . import closure, kernels
from .blade import lowest_point
from .geometry import Geometry
from .loops import NonAssembly

UNKNOWNS = ("theta5", "theta6")


def residuals(g: Geometry, th, x_target: float):
    """Eq. (7) residuals for one or many (theta5, theta6) candidates (..., 2)."""
    th = np.asarray(th, float)
    xk, yk = lowest_point(g, th[..., 0], th[..., 1])
    return np.stack([xk - x_target, yk + g.s], axis=-1)


def _guide_joint(g: Geometry, k):
    """beta, x_target -> carrier joint D (complex) when the blade has angle beta and touches
    (x_target, -s): :func:`.closure.guide_point` of ``k`` (:func:`.kernels.chosen`, chosen
    once: Brent calls it ~20 times per root)."""
    joint, c = k.guide_joint, g.constants
    return lambda beta, x_target: complex(*joint(c, float(beta), float(x_target)))


def _guide_distance_scan(g: Geometry, betas: np.ndarray, x_target: float, k) -> tuple:
    """(|ED(beta)| - l6, x of D) on the scan grid (:func:`.closure.guide_scan` compiled where
    numba is installed, :func:`.closure.guide_point` on the whole grid in numpy otherwise);
    the few values of |ED| - l6 within 1e-6 mm of zero (where a round-off difference could
    flip a sign) are recomputed by the scalar :func:`_guide_joint`, so the brackets are
    exactly those of a scalar scan."""
    if k is closure:
        dx, dy, f = np.empty_like(betas), np.empty_like(betas), np.empty_like(betas)
        closure.guide_scan(g.constants, betas, float(x_target), dx, dy, f)
    else:
        dx, dy = closure.python.guide_point(g, betas, x_target)
        f = np.hypot(dx, dy) - g.l6
    joint = _guide_joint(g, k)
    for i in np.nonzero(np.abs(f) < 1e-6)[0]:
        f[i] = abs(joint(betas[i], x_target)) - g.l6
    return f, dx


@functools.lru_cache(maxsize=8)
def _scan_grid(beta_window: float, n_scan: int) -> np.ndarray:
    betas = np.linspace(-beta_window, beta_window, n_scan)
    betas.setflags(write=False)
    return betas


def exact_pose(g: Geometry, x_target: float, beta_window: float = 0.3, n_scan: int = 601):
    """Reference (theta5, theta6) with theta6 in [pi, 2 pi] and theta5 in [0, pi].

    The guide rod has two assembly modes inside the paper's range; the design mode
    (``g.guide_mode``, the sign of cos theta6) is kept.  Scans |ED(beta)| - l6 over |beta| <= beta_window, keeps the roots whose pose is inside
    the paper's ranges, and returns the one with the smallest |beta| (the cutting stroke
    turns the blade by a few degrees).  Raises NonAssembly when no root qualifies.
    """
    betas = _scan_grid(float(beta_window), int(n_scan))
    k = kernels.chosen()
    f, dx = _guide_distance_scan(g, betas, x_target, k)
    # a root between two grid points where D lies clearly on the other side of E (the
    # other assembly mode of the guide rod) cannot qualify: x of D is within
    # (|R - h| + d) (d beta)^2 / 8 of the chord between the grid points, so it keeps its sign
    other = g.guide_mode * dx < -(abs(g.R - g.h) + g.d) * (betas[1] - betas[0]) ** 2
    roots = []
    joint = _guide_joint(g, k)
    for i in np.nonzero(np.sign(f[:-1]) * np.sign(f[1:]) <= 0)[0]:
        if other[i] and other[i + 1]:
            continue
        b = brentq(lambda x: abs(joint(x, x_target)) - g.l6, betas[i], betas[i + 1],
                   xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=200)
        D = joint(b, x_target)
        t5, t6 = b + g.beta2, math.atan2(D.imag, D.real) % (2 * math.pi)
        if (0.0 <= t5 <= math.pi and math.pi <= t6 <= 2 * math.pi
                and g.guide_mode * math.cos(t6) > 0):
            roots.append((abs(b), t5, t6))
    if not roots:
        raise NonAssembly(f"guide rod l6 = {g.l6:.6g} mm cannot reach the carrier with the "
                          f"lowest point at x_k = {x_target:.6g} mm (no root of |ED| = l6 for "
                          f"|beta| <= {beta_window})", x_k=x_target)
    _, t5, t6 = min(roots)
    return np.array([t5, t6])
