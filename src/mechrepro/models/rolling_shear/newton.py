"""Newton's method on the two small systems, in plain floats (no array overhead).

Both systems split into 2x2 blocks: Eq. (7) in (theta5, theta6) and Eq. (9) in
(theta1, theta3) + (theta2, theta4).  Each Newton step is solved by Cramer's rule; a
step is refused when the block's determinant is tiny relative to its scale (a toggle:
crank and rod collinear, sin(theta1 - theta3) = 0), which is reported, never hidden.
Convergence is on the paper's fitness G = sum |f_i| (mm).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from . import kernels
from .geometry import Geometry

SINGULAR_RTOL = 1e-12


@dataclass
class NewtonResult:
    x: tuple
    fitness: float
    iterations: int
    converged: bool
    reason: str = ""


def reason(status: int, det: float, max_iter: int) -> str:
    """Why a Newton solve failed, by status (1 non-finite, 2 singular, 3 no convergence;
    the codes of :mod:`.kernels`)."""
    return {1: "non-finite residual",
            2: f"singular Jacobian (det = {det:.3g}, toggle configuration)",
            3: f"no convergence in {max_iter} iterations"}[status]


def _newton2(f_and_j, x0, tol, max_iter, scale):
    a, b = x0
    G = math.inf
    for k in range(max_iter + 1):
        f1, f2, j11, j12, j21, j22 = f_and_j(a, b)
        G = abs(f1) + abs(f2)
        if G < tol:
            return NewtonResult((a, b), G, k, True)
        if not math.isfinite(G):
            return NewtonResult((a, b), G, k, False, reason(1, 0.0, max_iter))
        if k == max_iter:
            break
        det = j11 * j22 - j12 * j21
        if abs(det) <= SINGULAR_RTOL * scale:
            return NewtonResult((a, b), G, k, False, reason(2, det, max_iter))
        a -= (f1 * j22 - f2 * j12) / det
        b -= (j11 * f2 - j21 * f1) / det
    return NewtonResult((a, b), G, max_iter, False, reason(3, 0.0, max_iter))


def _result(a, b, G, k, status, det, max_iter) -> NewtonResult:
    return NewtonResult((a, b), G, k, status == 0, reason(status, det, max_iter) if status else "")


def pose(g: Geometry, x0, x_target: float, tol: float, max_iter: int = 30) -> NewtonResult:
    """Eq. (7): theta5, theta6 with the lowest point at (x_target, -s).  Compiled
    (:mod:`.kernels`) where numba is installed: the same operations, the same bits."""
    if kernels.available():
        return _result(*kernels.kernel("pose_newton")(
            kernels.pose_constants(g), float(x0[0]), float(x0[1]), float(x_target), float(tol),
            int(max_iter), abs(g.R - g.h) * g.l6, SINGULAR_RTOL), max_iter)
    R, h, d, l6, b1, b2, s = g.R, g.h, g.d, g.l6, g.beta1, g.beta2, g.s

    def fj(t5, t6):
        be = t5 - b2
        cb, sb = math.cos(be), math.sin(be)
        c51, s51 = math.cos(t5 + b1), math.sin(t5 + b1)
        c6, s6 = math.cos(t6), math.sin(t6)
        xk = l6 * c6 + d * c51 + h * sb - R * sb
        yk = l6 * s6 + d * s51 - h * cb - R * (1.0 - cb)
        return (xk - x_target, yk + s,
                -d * s51 + (h - R) * cb, -l6 * s6,
                d * c51 + (h - R) * sb, l6 * c6)

    return _newton2(fj, x0, tol, max_iter, scale=abs(R - h) * l6)


def loops(g: Geometry, x0, theta5: float, theta6: float, tol: float,
          max_iter: int = 30) -> NewtonResult:
    """Eq. (9): theta1..theta4 (two independent 2x2 blocks); compiled like :func:`pose`."""
    if kernels.available():
        t1, t2, t3, t4 = x0
        d1, d2 = kernels.kernel("loops_newton")(
            kernels.newton_loops_constants(g), float(t1), float(t2), float(t3), float(t4),
            float(theta5), float(theta6), float(tol), int(max_iter), SINGULAR_RTOL)
        r1, r2 = _result(*d1, max_iter), _result(*d2, max_iter)
        return _combine(r1, r2)
    c6, s6 = g.l6 * math.cos(theta6), g.l6 * math.sin(theta6)
    # carrier joints relative to the crank pivots A and G
    cx = g.l8 * math.cos(theta5 + g.alpha) + c6 + g.l10 + g.l9
    cy = g.l8 * math.sin(theta5 + g.alpha) + s6 - g.l11
    ix = g.l5 * math.cos(theta5) + c6 + g.l10
    iy = g.l5 * math.sin(theta5) + s6 - g.l11

    def block(la, lb, px, py):
        def fj(ta, tb):
            ca, sa, cb_, sb_ = math.cos(ta), math.sin(ta), math.cos(tb), math.sin(tb)
            return (la * ca - lb * cb_ - px, la * sa - lb * sb_ - py,
                    -la * sa, lb * sb_, la * ca, -lb * cb_)
        return fj

    t1, t2, t3, t4 = x0
    r1 = _newton2(block(g.l1, g.l3, cx, cy), (t1, t3), 0.5 * tol, max_iter, g.l1 * g.l3)
    r2 = _newton2(block(g.l2, g.l4, ix, iy), (t2, t4), 0.5 * tol, max_iter, g.l2 * g.l4)
    return _combine(r1, r2)


def _combine(r1: NewtonResult, r2: NewtonResult) -> NewtonResult:
    """The loops' result from the two dyads' (ABCD: theta1, theta3; GHID: theta2, theta4)."""
    x = (r1.x[0], r2.x[0], r1.x[1], r2.x[1])
    reason = "; ".join(f"loop {n}: {r.reason}" for n, r in (("ABCD", r1), ("GHID", r2))
                       if not r.converged)
    return NewtonResult(x, r1.fitness + r2.fitness, max(r1.iterations, r2.iterations),
                        r1.converged and r2.converged, reason)
