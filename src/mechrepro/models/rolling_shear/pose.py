"""Blade pose at a cut point: theta5, theta6 from Eq. (7) with the lowest point on y = -s.
:func:`exact_pose` is the reference: for a blade angle beta the pose is fixed and the guide
rod closes where |ED| = l6, one scalar equation bracketed on a grid and solved by Brent."""
from __future__ import annotations

import functools

import numpy as np

from . import closure, kernels
from .geometry import Geometry
from .loops import NonAssembly, columns, stacked


def residuals(g: Geometry, th, x_target: float):
    """Eq. (7) residuals for one or many (theta5, theta6) candidates (..., 2)
    (:func:`.closure.lowest_point`)."""
    xk, yk = closure.python.lowest_point(g, *columns(th))
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
