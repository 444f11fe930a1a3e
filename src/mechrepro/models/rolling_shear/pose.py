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

from . import kernels
from .blade import lowest_point
from .geometry import Geometry
from .loops import NonAssembly

UNKNOWNS = ("theta5", "theta6")


def residuals(g: Geometry, th, x_target: float):
    """Eq. (7) residuals for one or many (theta5, theta6) candidates (..., 2)."""
    th = np.asarray(th, float)
    xk, yk = lowest_point(g, th[..., 0], th[..., 1])
    return np.stack([xk - x_target, yk + g.s], axis=-1)


def _guide_point(g: Geometry, beta: float, x_target: float) -> complex:
    """Carrier joint D when the blade has angle beta and touches (x_target, -s)."""
    K = complex(x_target, -g.s)
    M = K + complex(g.R * math.sin(beta), g.R * (1.0 - math.cos(beta)))
    O = M + g.h * complex(-math.sin(beta), math.cos(beta))
    theta5 = beta + g.beta2
    return O - g.d * complex(math.cos(theta5 + g.beta1), math.sin(theta5 + g.beta1))


def _guide_point_array(g: Geometry, beta: np.ndarray, x_target: float) -> tuple:
    """:func:`_guide_point` for an array of blade angles, as (real, imag) arrays.

    The same operations in the same order, componentwise (so the same bits where numpy's
    sin/cos are the C library's; the scan only brackets the roots, see
    :func:`_guide_distance_scan`)."""
    sb, cb = np.sin(beta), np.cos(beta)
    mx, my = x_target + g.R * sb, -g.s + g.R * (1.0 - cb)
    ox, oy = mx + g.h * -sb, my + g.h * cb
    t = beta + g.beta2 + g.beta1
    return ox - g.d * np.cos(t), oy - g.d * np.sin(t)


def _guide_distance_scan(g: Geometry, betas: np.ndarray, x_target: float) -> tuple:
    """(|ED(beta)| - l6, x of D) on the scan grid, vectorised (compiled where numba is
    installed); the few values of |ED| - l6 within 1e-6 mm of zero (where a round-off
    difference could flip a sign) are recomputed by the scalar :func:`_guide_point`, so the
    brackets are exactly those of a scalar scan."""
    if kernels.available():
        dx, dy, f = np.empty_like(betas), np.empty_like(betas), np.empty_like(betas)
        kernels.kernel("guide_scan")(kernels.guide_constants(g), betas, float(x_target),
                                     dx, dy, f)
    else:
        dx, dy = _guide_point_array(g, betas, x_target)
        f = np.hypot(dx, dy) - g.l6
    for i in np.nonzero(np.abs(f) < 1e-6)[0]:
        f[i] = abs(_guide_point(g, float(betas[i]), x_target)) - g.l6
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
    f, dx = _guide_distance_scan(g, betas, x_target)
    # a root between two grid points where D lies clearly on the other side of E (the
    # other assembly mode of the guide rod) cannot qualify: x of D is within
    # (|R - h| + d) (d beta)^2 / 8 of the chord between the grid points, so it keeps its sign
    other = g.guide_mode * dx < -(abs(g.R - g.h) + g.d) * (betas[1] - betas[0]) ** 2
    roots = []
    for i in np.nonzero(np.sign(f[:-1]) * np.sign(f[1:]) <= 0)[0]:
        if other[i] and other[i + 1]:
            continue
        b = brentq(lambda x: abs(_guide_point(g, x, x_target)) - g.l6, betas[i], betas[i + 1],
                   xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=200)
        D = _guide_point(g, b, x_target)
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
