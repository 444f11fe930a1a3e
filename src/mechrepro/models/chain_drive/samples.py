"""The excitation's elementwise formulas (the four-bar's phases and kinematics, Eqs. 2-7,
2-9; the impact counted in whole pulses) and their compiled per-sample loops (numba,
cached on disk).

The formulas are evaluated at every sample of a (time, speed) block; as numpy expressions
each is ~10-30 passes over the block, the compiled loop one pass per sample.  The loops
call the formulas themselves (:func:`phase_formulas`, :func:`kinematics_formulas`,
:func:`whole_pulse_formulas`, written elementwise so that numpy and numba read the same
source), with the same bits; :mod:`.four_bar` and :mod:`.loads` call them on arrays.

The loops run wherever numba is installed (:func:`mechrepro.compiled.available`), whatever
the block's size: the processes that evaluate the effects are solve jobs, which load numba
for the march anyway (:mod:`.fd_kernel`), and the choice then depends on the installation
alone, never on what ran before.
"""
from __future__ import annotations

from functools import cache

import numpy as np

from mechrepro.compiled import available


def tooth_constants(n1: int) -> tuple:
    """The constants of :func:`travel_in_tooth`: the tooth angle 2 pi/n1, theta_10 and its cosine
    (formed once, not per sample: the compiled loop would evaluate the cosine each time)."""
    th10 = np.pi / 2 - np.pi / n1
    return 2 * np.pi / n1, th10, np.cos(th10)


def travel_in_tooth(phi, tooth, r1):
    """theta_1 within the tooth period at phi = omega1 t (Eq. 2-7, as :func:`.four_bar.chain_travel`),
    cos theta_1 and the chain travel since the last engagement d1 = r1 (cos theta_10 -
    cos theta_1) in [0, p_c); ``tooth``: :func:`tooth_constants`."""
    step, th10, c10 = tooth
    th1 = th10 + (phi - np.floor(phi / step) * step)
    c1 = np.cos(th1)
    return th1, c1, r1 * (c10 - c1)


def phase_formulas(phi, tooth, r1, s_off, p_c):
    """theta_1, cos theta_1, the chain travel past the driven sprocket's last disengagement
    s2 in [0, p_c), the driving tooth phase, and whether the sample is within round-off of
    a wrap (there :func:`.four_bar.tooth_phases` decides s2 and the phase again, exactly).

    Elementwise on arrays, and the body of the compiled per-sample loop below:
    the one source of these formulas.  The wrap is written as arithmetic (w a + (1 - w) b
    with a bool w: exactly a or b, both finite), which both read alike."""
    th1, c1, d1 = travel_in_tooth(phi, tooth, r1)
    # (chain travel + s_off) mod p_c from the travel within the tooth period: the whole
    # pitches drop out (no large numbers, no mod) ...
    u = d1 + s_off
    past = u - p_c
    wrap = u >= p_c
    tol = 1e-9 * p_c
    # ... except at samples within round-off of a wrap (an engagement or a driven wrap at a
    # sample instant)
    near = (np.abs(past) < tol) | (d1 < tol) | (p_c - d1 < tol)
    return th1, c1, wrap * past + (1 - wrap) * u, d1 / p_c, near


def kinematics_formulas(omega1, c1, s2, c20, r1, r2):
    """sin theta_1, cos/sin theta_2, omega_2 and alpha_2 (Eqs. 2-7, 2-9) from cos theta_1
    and the driven travel s2 of :func:`phase_formulas` (elementwise, as it); c20 = cos theta_20 of
    the driven sprocket's start angle pi/2 - pi/n2."""
    s1 = np.sqrt(1.0 - c1 * c1)          # theta_1 in (0, pi)
    c2 = np.minimum(np.maximum(c20 - s2 / r2, -1.0), 1.0)
    sn2 = np.sqrt(1.0 - c2 * c2)         # theta_2 in (0, pi)
    r2sn2 = r2 * sn2
    w2 = omega1 * r1 * s1 / r2sn2
    a2 = (r1 * omega1**2 * c1 - r2 * w2**2 * c2) / r2sn2
    return s1, c2, sn2, w2, a2


def whole_pulse_formulas(t, tau, J, step, t_i):
    """The impulse over the window [t - step/2, t + step/2] counted in whole pulses J
    (impacts at t = 0, tau, 2 tau, ...), and whether an end of the window lies within a
    contact (t_i after an impact), where :func:`.loads.impact_load` integrates the pulse exactly.

    Elementwise on arrays, and the body of the compiled per-sample loop below:
    the one source of the formula."""
    a, b = t - step / 2, t + step / 2
    ka, kb = np.floor(a / tau), np.floor(b / tau)
    # the window ends' times since their last impact, against margins of round-off
    margin = 1e-9 * tau
    ra, rb = a - ka * tau, b - kb * tau
    lo, hi = t_i + margin, tau - margin
    return (kb - ka) * J, (ra < lo) | (rb < lo) | (ra > hi) | (rb > hi)


@cache
def _loops():
    from numba.extending import register_jitable

    from mechrepro.compiled import jit

    for f in (travel_in_tooth, phase_formulas, kinematics_formulas, whole_pulse_formulas):
        register_jitable(f)     # callable from the loops below, and still plain Python

    @jit
    def phases(t, w, tooth, r1, s_off, p_c, th1, c1, s2, ph1, near):
        for i in range(th1.shape[0]):
            for j in range(th1.shape[1]):
                th1[i, j], c1[i, j], s2[i, j], ph1[i, j], near[i, j] = phase_formulas(
                    w[j] * t[i, j], tooth, r1, s_off, p_c)

    @jit
    def kinematics(w, c1, s2, c20, r1, r2, s1, c2, sn2, w2, a2):
        for i in range(c1.shape[0]):
            for j in range(c1.shape[1]):
                s1[i, j], c2[i, j], sn2[i, j], w2[i, j], a2[i, j] = kinematics_formulas(
                    w[j], c1[i, j], s2[i, j], c20, r1, r2)

    @jit
    def whole_pulses(t, tau, J, step, t_i, out, near):
        for i in range(out.shape[0]):
            for j in range(out.shape[1]):
                out[i, j], near[i, j] = whole_pulse_formulas(t[i, j], tau[j], J[j], step[i, j],
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
    """:func:`phase_formulas` at phi = omega1 t on a :func:`block`."""
    out = [np.empty(shape) for _ in range(4)] + [np.empty(shape, np.bool_)]
    _loops()[0](np.broadcast_to(np.asarray(t, float), shape),
                np.ascontiguousarray(omega1[0], float), tooth, r1, s_off, p_c, *out)
    return out


def kinematics(omega1, c1, s2, c20, r1, r2):
    """:func:`kinematics_formulas` on a :func:`block` (c1, s2 of :func:`phases`)."""
    out = [np.empty(c1.shape) for _ in range(5)]
    _loops()[1](np.ascontiguousarray(omega1[0], float), c1, s2, c20, r1, r2, *out)
    return out


def whole_pulses(t, tau, J, step, t_i, shape):
    """:func:`whole_pulse_formulas` on a :func:`block` (tau, J per speed (1, S); step a
    number or (T, S))."""
    out, near = np.empty(shape), np.empty(shape, np.bool_)
    _loops()[2](np.broadcast_to(np.asarray(t, float), shape),
                np.ascontiguousarray(np.broadcast_to(tau, (1, shape[1]))[0], float),
                np.ascontiguousarray(np.broadcast_to(J, (1, shape[1]))[0], float),
                np.broadcast_to(np.asarray(step, float), shape), float(t_i), out, near)
    return out, near


#END
