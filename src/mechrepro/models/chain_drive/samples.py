"""Compiled per-sample loops of the excitation's elementwise formulas (numba, cached on disk).

The sprocket kinematics and the step-averaged impact are evaluated at every sample of a
(time, speed) block; as numpy expressions each formula is ~10-30 passes over the block, the
compiled loop one pass per sample (the cosine of theta_1 is then most of the cost; profiled,
these formulas were about half of a Fig. 5 march sweep's time).  The loops call the formulas themselves
(:func:`.four_bar._phases`, :func:`.four_bar._kinematics`, :func:`.loads._whole_pulses`,
written elementwise so that numpy and numba read the same source), with the same bits.

The loops run wherever numba is installed (:func:`mechrepro.compiled.available`), whatever
the block's size: the processes that evaluate the effects are solve jobs, which load numba
for the march anyway (:mod:`.fd_kernel`), and the choice then depends on the installation
alone, never on what ran before.
"""
from __future__ import annotations

from functools import cache

import numpy as np

from mechrepro.compiled import available

from . import four_bar, loads


@cache
def _loops():
    from numba.extending import register_jitable

    from mechrepro.compiled import jit

    for f in (four_bar._travel, four_bar._phases, four_bar._kinematics, loads._whole_pulses):
        register_jitable(f)     # callable from the loops below, and still plain Python

    @jit
    def phases(t, w, tooth, r1, s_off, p_c, th1, c1, s2, ph1, near):
        for i in range(th1.shape[0]):
            for j in range(th1.shape[1]):
                th1[i, j], c1[i, j], s2[i, j], ph1[i, j], near[i, j] = four_bar._phases(
                    w[j] * t[i, j], tooth, r1, s_off, p_c)

    @jit
    def kinematics(w, c1, s2, c20, r1, r2, s1, c2, sn2, w2, a2):
        for i in range(c1.shape[0]):
            for j in range(c1.shape[1]):
                s1[i, j], c2[i, j], sn2[i, j], w2[i, j], a2[i, j] = four_bar._kinematics(
                    w[j], c1[i, j], s2[i, j], c20, r1, r2)

    @jit
    def whole_pulses(t, tau, J, step, t_i, out, near):
        for i in range(out.shape[0]):
            for j in range(out.shape[1]):
                out[i, j], near[i, j] = loads._whole_pulses(t[i, j], tau[j], J[j], step[i, j],
                                                            t_i)

    return phases, kinematics, whole_pulses


def block(t, omega1) -> tuple | None:
    """(T, S) when t (T, 1 | S) and omega1 (1, S) form a block the loops take and they are
    compiled here; None otherwise (the caller evaluates the formula on the arrays)."""
    t, omega1 = np.asarray(t), np.asarray(omega1)
    if (t.ndim == 2 and omega1.ndim == 2 and omega1.shape[0] == 1
            and t.shape[1] in (1, omega1.shape[1]) and available()):
        return t.shape[0], omega1.shape[1]
    return None


def phases(t, omega1, shape, tooth, r1, s_off, p_c):
    """:func:`.four_bar._phases` at phi = omega1 t on a :func:`block`."""
    out = [np.empty(shape) for _ in range(4)] + [np.empty(shape, np.bool_)]
    _loops()[0](np.broadcast_to(np.asarray(t, float), shape),
                np.ascontiguousarray(omega1[0], float), tooth, r1, s_off, p_c, *out)
    return out


def kinematics(omega1, c1, s2, c20, r1, r2):
    """:func:`.four_bar._kinematics` on a :func:`block` (c1, s2 of :func:`phases`)."""
    out = [np.empty(c1.shape) for _ in range(5)]
    _loops()[1](np.ascontiguousarray(omega1[0], float), c1, s2, c20, r1, r2, *out)
    return out


def whole_pulses(t, tau, J, step, t_i, shape):
    """:func:`.loads._whole_pulses` on a :func:`block` (tau, J per speed (1, S); step a
    number or (T, S))."""
    out, near = np.empty(shape), np.empty(shape, np.bool_)
    _loops()[2](np.broadcast_to(np.asarray(t, float), shape),
                np.ascontiguousarray(np.broadcast_to(tau, (1, shape[1]))[0], float),
                np.ascontiguousarray(np.broadcast_to(J, (1, shape[1]))[0], float),
                np.broadcast_to(np.asarray(step, float), shape), float(t_i), out, near)
    return out, near


def warm() -> None:
    """Load the loops (numba's disk cache, or a compile) by one call each on a tiny block of
    the production types (times shared by the speeds, a fixed step): a solver process pays
    this once, before any timed solve."""
    if not available():
        return
    t, w = np.linspace(0.0, 1e-3, 3)[:, None], np.array([[50.0, 60.0]])
    four_bar.rigid_kinematics(t, w, n1=19, n2=38, p_c=0.0127, f_p=0.3)
    loads.impact_load(t, w, 19, 0.0127, loads.impact_constants(0.02, 2e8, 0.1), step=1e-4)
