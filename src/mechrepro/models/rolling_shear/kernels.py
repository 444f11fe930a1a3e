"""Compiled loops of rolling_shear (numba, cached on disk): the selPSO iterations on
Eqs. (7) and (9) and the warm-started Newton continuation of the blade pose (Eq. 7).

Both loops are sequential (a swarm iteration needs the previous one's gbest, a cut point
the previous points' poses), so numpy can only vectorise inside one iteration, over 10-60
particles or 2 unknowns: the interpreter's overhead per iteration (~40 numpy calls) is what
the Python loops spend their time on.  The kernels do the same floating-point operations
in the same order as :func:`.selpso.selpso` with the fitnesses of :mod:`.pose` and
:mod:`.loops`, and as :func:`.newton.pose` (no fast-math, no contraction into FMA; numpy's
and numba's sin/cos are the C library's), so they give the same bits -- tested against the
Python paths in ``tests/test_rolling_shear_kernels.py``.  The swarm draws its random numbers
from the run's own :class:`numpy.random.Generator` (numba shares its bit generator's state),
one ``random()`` after the other in the order of ``rng.random((2, N, n))``, so the stream and
every later draw from it are unchanged.

Import is lazy (numba costs ~0.3 s to import and ~0.1 s to load the cached kernels, once
per process); without numba (``available()`` false) the Python paths run, with the same
results.  Which path runs depends on nothing but whether numba is installed (and
``MECHREPRO_RS_KERNEL=numpy``, for tests and benchmarks): never on what ran before.
"""
from __future__ import annotations

import numpy as np

from mechrepro import compiled

#: fitness kinds of the compiled swarm
LOOPS, POSE = 0, 1
#: status codes of the compiled Newton (see :func:`.newton._newton2`)
CONVERGED, NON_FINITE, SINGULAR, NO_CONVERGENCE = 0, 1, 2, 3

_K = None


def available() -> bool:
    """numba importable and not switched off (``MECHREPRO_RS_KERNEL=numpy`` or
    ``MECHREPRO_KERNEL=numpy``): :func:`mechrepro.compiled.available`."""
    return compiled.available("MECHREPRO_RS_KERNEL")


def kernel(name: str):
    """One compiled kernel (built, or loaded from numba's disk cache, on first use)."""
    global _K
    if _K is None:
        from . import _kernels_nb

        _K = _kernels_nb
    return getattr(_K, name)


def warm() -> None:
    """Load every kernel (numba's disk cache, or a compile) by calling it once on tiny
    inputs of the production types, so that this one-time cost of a process (~0.2-0.5 s)
    is paid at import, not inside the first timed solve (it would inflate e.g. the first
    selPSO run's time per solve).  Nothing is computed that a run uses."""
    if not available():
        return
    z2 = np.zeros((2, 2))
    gen = np.random.default_rng(0)
    kernel("selpso_iterate")(LOOPS, np.zeros(13), z2.copy(), z2.copy(), z2.copy(), np.ones(2),
                             np.zeros(2), 1.0, gen, 1, 0.9, 0.4, 2.0, 2.0, 0.0, 1.0, True,
                             True, np.empty(2))
    kernel("fitness")(POSE, np.zeros(8), z2, np.empty(2))
    kernel("pose_stroke")(np.ones(8), np.zeros(2), 0.0, 0.0, 1.0, 1, 1.0, 1e-12, z2.copy())
    kernel("pose_newton")(np.ones(8), 0.0, 0.0, 0.0, 1.0, 1, 1.0, 1e-12)
    kernel("loops_newton")(np.ones(11), 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1, 1e-12)
    kernel("loops_stroke")(np.ones(11), np.zeros((2, 6)), 1.0, 1, 1e-12)
    kernel("assembles_clearly")(np.ones(13), z2, 1e-9)
    betas = np.zeros(2)
    betas.setflags(write=False)   # the scan grid of pose.exact_pose is read-only
    kernel("guide_scan")(np.ones(7), betas, 0.0, np.empty(2), np.empty(2), np.empty(2))


def loops_constants(g, theta5: float, theta6: float) -> np.ndarray:
    """The constants of the Eq. (9) fitness, computed exactly as :func:`.loops.residuals`
    computes them."""
    import math

    c6, s6 = g.l6 * math.cos(theta6), g.l6 * math.sin(theta6)
    cx, cy = g.l8 * math.cos(theta5 + g.alpha), g.l8 * math.sin(theta5 + g.alpha)
    ix, iy = g.l5 * math.cos(theta5), g.l5 * math.sin(theta5)
    return np.array([g.l1, g.l2, g.l3, g.l4, cx, cy, c6, s6, ix, iy, g.l9, g.l10, g.l11])


def pose_constants(g, x_target: float = 0.0) -> np.ndarray:
    """The constants of Eq. (7) (fitness and Newton)."""
    return np.array([g.l6, g.d, g.beta1, g.beta2, g.h, g.R, g.s, x_target])


def assembly_constants(g) -> np.ndarray:
    """The constants of :func:`._kernels_nb.assembles_clearly`."""
    return np.array([g.l1, g.l2, g.l3, g.l4, g.l5, g.l6, g.l8, g.l9, g.l10, g.l11, g.alpha,
                     float(g.elbow1), float(g.elbow2)])


def guide_constants(g) -> np.ndarray:
    """The constants of :func:`._kernels_nb.guide_scan`."""
    return np.array([g.R, g.h, g.d, g.beta1, g.beta2, g.s, g.l6])


def newton_loops_constants(g) -> np.ndarray:
    """The constants of :func:`._kernels_nb.loops_newton`."""
    return np.array([g.l1, g.l2, g.l3, g.l4, g.l5, g.l6, g.l8, g.l9, g.l10, g.l11, g.alpha])
