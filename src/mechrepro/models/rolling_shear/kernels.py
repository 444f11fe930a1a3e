"""Which path runs the loops of :mod:`.closure`: compiled (numba, cached on disk) or Python.

selPSO iterations and Newton continuations are sequential, so numpy can only vectorise over
a few particles or unknowns; compiled, the same source runs with the same bits and the same
random stream (numba shares the Generator's bit generator).  The path depends only on
whether numba is installed (and ``MECHREPRO_RS_KERNEL=numpy``)."""
from __future__ import annotations

import numpy as np

from . import closure
from .geometry import constants


def chosen():
    """:mod:`.closure` (compiled) where :func:`available`, :data:`.closure.python` otherwise."""
    return closure if closure.available() else closure.python


def kernel(name: str):
    """A function of :func:`chosen`."""
    return getattr(chosen(), name)


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
    betas.setflags(write=False)   # the scan grid of pose.exact_pose is read-only
    closure.guide_pose(c, betas, np.zeros(2), np.zeros(2), 0.0, -1.0, 0.0, 1e-15, 1e-15, 1)
