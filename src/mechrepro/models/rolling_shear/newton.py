"""Newton on the 2x2 blocks of Eq. (7) and Eq. (9) (:func:`.closure.newton2`), in plain floats;
a near-singular step (a toggle) is reported, never hidden.  Convergence on the paper's G."""
from __future__ import annotations

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
    """Why a Newton solve failed, by the status codes of :mod:`.closure`."""
    return {1: "non-finite residual",
            2: f"singular Jacobian (det = {det:.3g}, toggle configuration)",
            3: f"no convergence in {max_iter} iterations"}[status]


def _result(a, b, G, k, status, det, max_iter) -> NewtonResult:
    return NewtonResult((a, b), G, k, status == 0, reason(status, det, max_iter) if status else "")


def pose(g: Geometry, x0, x_target: float, tol: float, max_iter: int = 30) -> NewtonResult:
    """Eq. (7): theta5, theta6 with the lowest point at (x_target, -s)."""
    return _result(*kernels.kernel("pose_newton")(
        g.constants, float(x0[0]), float(x0[1]), float(x_target), float(tol), int(max_iter),
        SINGULAR_RTOL), max_iter)


def loops(g: Geometry, x0, theta5: float, theta6: float, tol: float,
          max_iter: int = 30) -> NewtonResult:
    """Eq. (9): theta1..theta4 as two independent 2x2 blocks."""
    t1, t2, t3, t4 = x0
    d1, d2 = kernels.kernel("loops_newton")(
        g.constants, float(t1), float(t2), float(t3), float(t4), float(theta5), float(theta6),
        float(tol), int(max_iter), SINGULAR_RTOL)
    return _combine(_result(*d1, max_iter), _result(*d2, max_iter))


def _combine(r1: NewtonResult, r2: NewtonResult) -> NewtonResult:
    """The loops' result from the two dyads' (ABCD: theta1, theta3; GHID: theta2, theta4)."""
    x = (r1.x[0], r2.x[0], r1.x[1], r2.x[1])
    reason = "; ".join(f"loop {n}: {r.reason}" for n, r in (("ABCD", r1), ("GHID", r2))
                       if not r.converged)
    return NewtonResult(x, r1.fitness + r2.fitness, max(r1.iterations, r2.iterations),
                        r1.converged and r2.converged, reason)
