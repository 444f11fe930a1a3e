"""Which path runs the loops of :mod:`.closure`: compiled (numba, cached on disk) or Python.

selPSO iterations and Newton continuations are sequential, so numpy can only vectorise over
a few particles or unknowns; compiled, the same source runs with the same bits and the same
random stream (numba shares the Generator's bit generator).  The path depends only on
whether numba is installed (and ``MECHREPRO_RS_KERNEL=numpy``).  Newton on the 2x2 blocks of
Eqs. (7) and (9) in plain floats, converged on the paper's G."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import closure
from .geometry import Geometry, constants


def chosen():
    """:mod:`.closure` (compiled) where :func:`available`, :data:`.closure.python` otherwise."""
    return closure if closure.available() else closure.python


def kernel(name: str):
    """A function of :func:`chosen`."""
    return getattr(chosen(), name)


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


def newton_pose(g: Geometry, x0, x_target: float, tol: float, max_iter: int = 30) -> NewtonResult:
    """Eq. (7) by Newton (:func:`.closure.newton2`): theta5, theta6 with the lowest point at
    (x_target, -s); a near-singular step (a toggle) is reported, never hidden."""
    return _result(*kernel("pose_newton")(
        g.constants, float(x0[0]), float(x0[1]), float(x_target), float(tol), int(max_iter),
        SINGULAR_RTOL), max_iter)


def newton_loops(g: Geometry, x0, theta5: float, theta6: float, tol: float,
          max_iter: int = 30) -> NewtonResult:
    """Eq. (9) by Newton: theta1..theta4 as two independent 2x2 blocks."""
    t1, t2, t3, t4 = x0
    d1, d2 = kernel("loops_newton")(
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


def warm(runs=None) -> None:
    """Load every kernel (numba's disk cache or a compile) on tiny inputs of the production types,
    so that this one-time cost is paid before the first timed solve."""
    if not closure.available():
        return
    from .selpso import iterate

    c = constants(closure.Linkage(*[1.0] * len(closure.Linkage._fields)))
    q = (0.0,) * 6
    z2 = np.zeros((2, 2))
    gen = np.random.default_rng(0)
    iterate(closure.LOOPS, c, q, z2.copy(), z2.copy(), z2.copy(), np.ones(2), np.zeros(2), 1.0,
            gen, 1, 0.9, 0.4, 2.0, 2.0, 0.0, 1.0, True, True, np.empty(2))
    closure.pose_stroke(c, np.zeros(2), 0.0, 0.0, 1.0, 1, 1e-12, -1.0, z2.copy())
    closure.pose_newton(c, 0.0, 0.0, 0.0, 1.0, 1, 1e-12)
    closure.loops_newton(c, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1, 1e-12)
    closure.loops_stroke(c, np.zeros((2, 6)), 1.0, 1, 1e-12)
    closure.assembles_clearly(c, z2, 1e-9)
    betas = np.zeros(2)
    betas.setflags(write=False)   # the scan grid of blade.exact_pose is read-only
    closure.guide_pose(c, betas, np.zeros(2), np.zeros(2), 0.0, -1.0, 0.0, 1e-15, 1e-15, 1)
