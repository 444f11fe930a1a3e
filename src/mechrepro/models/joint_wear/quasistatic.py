"""Continuous-contact joint B, quasi-static (the paper's low-speed assumption, Sec. 3.2).

The pin slides on the bushing with the penetration that carries the joint force, the
bushing's centre at r_j = r_i - (c + delta) n (Eqs. 5-8 read backwards).  The joint-B force
follows from the minimal-coordinate equations of motion (loads.py) solved for it; Eqs. (11),
(15) give F_N, the penetration and the contact direction.  No stiff dynamics is integrated.

Clearance kinematics.  The bushing centre is offset from the pin by (c + delta) along n,
which turns the links by ~c / l.  That offset is what the dynamic clearance joint settles
on: without it the quasi-static state is off the dynamic one by enough to ring the
clearance's lightly damped rocking mode when a dynamic run starts there, and a worn joint's
enlarged clearance would not reach the force history.  The positions are a fixed point:
ideal kinematics -> force -> n -> bushing centre -> link angles (rates by spectral
differentiation of the periodic angles) -> force ...; the correction shrinks by ~c/l per
pass, so ``passes`` = 2 leaves ~1e-10 in the wear per period.
"""
from __future__ import annotations

import functools
import math
from typing import NamedTuple

import numpy as np

from . import contact, kinematics, loads, qs_numba
from .geometry import FourBar


def one_period(fb: FourBar, n_steps: int, passes: int = 2, t0: float = 0.0,
               settled: bool = False, offset=None) -> dict:
    """Contact history over one crank period on a uniform periodic grid of n_steps from t0.

    passes = 0 is the ideal-kinematics approximation (the bushing centre on the pin's).
    settled=True converges the link angles to round-off (4 passes, full friction fixed
    point in each): the start of a dynamic run needs the bushing position to ~1e-10 m,
    since a tangential offset d rings the rocking mode with an amplitude d / c.
    offset(state, phi2) -> (x, y): the pin centre's offset from the bushing centre (global
    frame) for a worn groove (groove.py); default the circle's (c + delta) n.
    """
    return periods([fb], n_steps, passes, t0, settled, offset)[0]


def periods(fbs, n_steps: int, passes: int = 2, t0: float = 0.0, settled: bool = False,
            offset=None) -> list:
    """:func:`one_period` of mechanisms that differ in the bushing alone (R_j and K', as
    FourBar.with_bushing_radius makes them), solved together: every stage runs over all
    their samples at once (rows), each row's arithmetic that of its own one_period.
    ``offset``: one mechanism only."""
    fb, rows = fbs[0], len(fbs)
    bush = tuple(np.array(x, float) for x in zip(*((f.R_bush, f.K_contact, f.clearance) for f in fbs)))
    if settled:
        passes = max(passes, 4)
    ideal = _ideal_cached if n_steps <= CACHED_GRID else _ideal
    t, th1, th3, ph2, w3, w2, a3, a2, px, py = (np.repeat(x[None], rows, 0) for x in ideal(
        fb.l0, fb.l1, fb.l2, fb.l3, fb.omega, int(n_steps), float(t0)))
    # intermediate passes only steer the link angles: a rougher friction fixed point will do
    rough = 4 if settled else 2
    out = _contact_state(fb, bush, t, th1, th3, ph2, w3, w2, a3, a2, rough if passes else 4,
                         same_motion=True)
    for i in range(passes):
        if offset is None:
            ecc = bush[2][:, None] + out["delta"]
            ox, oy = ecc * out["nx"], ecc * out["ny"]
        else:
            ox, oy = offset({k: v[0] for k, v in out.items()}, ph2[0])
        th3, ph2 = kinematics.positions_from_point(fb, px - ox, py - oy)
        d1, d2 = periodic_derivatives(np.stack([th3, ph2], axis=1), fb.period)
        w3, w2, a3, a2 = d1[:, 0], d1[:, 1], d2[:, 0], d2[:, 1]
        out = _contact_state(fb, bush, t, th1, th3, ph2, w3, w2, a3, a2,
                             4 if i == passes - 1 else rough)
    # the contact angle of the last pass only (the passes before steer by n alone)
    out.update(psi=qs_numba.contact_angle(out.pop("ang_n").ravel(), ph2.ravel()).reshape(ph2.shape),
               w3=w3, w2=w2)
    return [{k: v[r] for k, v in out.items()} for r in range(rows)]


def _ideal(l0, l1, l2, l3, omega, n_steps, t0):
    """The grid, the ideal four-bar's motion on it (kinematics.py) and the pin's path: the
    same for every bushing radius, load point and gravity plane, so computed once per
    link geometry."""
    fb = _Links(l0, l1, l2, l3, omega)
    t = t0 + np.arange(n_steps) * (fb.period / n_steps)
    th1 = fb.omega * t
    th3, ph2 = kinematics.positions(fb, th1)
    w3, w2 = kinematics.velocities(fb, th1, th3, ph2)
    a3, a2 = kinematics.accelerations(fb, th1, th3, ph2, w3, w2)
    return t, th1, th3, ph2, w3, w2, a3, a2, fb.l1 * np.cos(th1), fb.l1 * np.sin(th1)


#: the largest grid whose ideal motion is kept (80 B per sample): a finer one is a
#: convergence check, solved once, and would hold its memory for the rest of the process
CACHED_GRID = 8192
_ideal_cached = functools.lru_cache(maxsize=16)(_ideal)


class _Links(NamedTuple):
    """What the ideal kinematics of kinematics.py read from a :class:`FourBar`."""
    l0: float
    l1: float
    l2: float
    l3: float
    omega: float

    @property
    def period(self):
        return 2.0 * math.pi / self.omega


def _contact_state(fb, bush, t, th1, th3, ph2, w3, w2, a3, a2, iterations=4,
                   same_motion=False) -> dict:
    """Joint-B force, its normal/friction split and the penetration for given link motion
    (rows: the bushings ``bush`` = (R_j, K', c) of :func:`periods`; ``same_motion``: the
    same link motion in every row, whose equations of motion are then set up once).

    M q'' + c(q, q') = Q_applied + J^T f + [0, R_j F_T] solved for the joint force f; the
    friction moment R_j F_T is ~1e-3 of the load terms, so ``iterations`` passes (4 leave
    1e-9) settle it.  The element-wise stages are :mod:`.qs_numba` (compiled with numba
    where installed, the same source as Python otherwise); the spectral derivative of the
    contact direction between them is numpy's FFT."""
    R, K, c = bush
    rows = t.shape[0]
    M11, M22, am = loads.mass_terms(fb)
    m = 1 if same_motion else rows
    b = qs_numba.setup(*(np.ascontiguousarray(x[:m]) for x in (th3, ph2, w3, w2, a3, a2)),
                       M11, M22, am, fb.l0, fb.l2, fb.l3, fb.m2, fb.m3, fb.P, float(fb.F[0]),
                       float(fb.F[1]), fb.g)
    b3, b2, j11, j12, j21, j22, det = (x.repeat(rows, 0) for x in b) if m < rows else b
    tau = np.zeros_like(t)
    slide = fb.omega * fb.R_pin
    w2R = w2 * R[:, None]
    sgn = contact.friction_sign(slide - w2R, fb.v_eps)
    for _ in range(iterations):
        F_N, ang_n, delta = qs_numba.force(b3, b2, j11, j12, j21, j22, det, tau, sgn, fb.mu,
                                           K, fb.n_exp)
        dang = periodic_derivatives(ang_n[:, None], fb.period, second=False)[0][:, 0]
        v_T, sgn, F_T, tau = qs_numba.friction(F_N, delta, dang, slide, w2R, c,
                                               fb.v_eps, fb.mu, R)
    nx, ny = np.cos(ang_n), np.sin(ang_n)
    return {"t": t, "theta1": th1, "theta3": th3, "phi2": ph2, "F_N": F_N, "F_T": F_T,
            "delta": delta, "v_T": v_T, "ang_n": ang_n, "nx": nx, "ny": ny}


HARMONICS = 64


@functools.lru_cache(maxsize=64)
def _omegas(n, period):
    """i w and -w^2 (as complex, what numpy multiplies a complex spectrum by anyway) of the
    angular frequencies w of ``rfft`` over one period of n samples, stacked (read-only):
    the factors of the first and second derivative."""
    w = 2 * np.pi * np.fft.rfftfreq(n, period / n)
    factors = np.array([1j * w, -(w * w)])
    factors.flags.writeable = False
    return factors


def periodic_derivatives(angle, period, second=True, harmonics=HARMONICS):
    """First (and second) time derivative of angles sampled uniformly over one period
    (the last axis; a 3-D ``angle`` is a stack of independent calls, one per first index).

    Spectral differentiation of the periodic part; a secular 2 pi k per period (a link
    that turns fully) is removed first and its constant rate added back.  Only the first
    ``harmonics`` crank harmonics are kept: the mechanism's motion is smooth (its
    harmonics fall to round-off well before 64), while differentiating the round-off of
    the higher ones would feed noise into the position fixed point at frequencies above
    the clearance's rocking mode (~1e3 rad/s), where no quasi-static state exists and
    the fixed point diverges.
    """
    a = np.asarray(angle, float)
    n = a.shape[-1]
    group = a.shape[-2] if a.ndim == 3 else a.size // n
    per, k, turns, some = qs_numba.periodic_part(np.ascontiguousarray(a.reshape(-1, n)), group)
    f = np.fft.rfft(per.reshape(a.shape), axis=-1)
    factors = _omegas(n, period)
    f[..., min(harmonics + 1, (n - 1) // 2 + 1):] = 0.0   # incl. the Nyquist mode of an even n
    if second:      # both derivatives in one inverse transform
        d1, d2 = np.fft.irfft(factors.reshape((2,) + (1,) * (f.ndim - 1) + (-1,)) * f, n,
                              axis=-1)
    else:
        d1, d2 = np.fft.irfft(factors[0] * f, n, axis=-1), None
    if some:     # the rows of the calls where some row turns
        d1 = np.where(turns.reshape(a.shape[:-1] + (1,)),
                      d1 + 2 * np.pi * k.reshape(a.shape[:-1] + (1,)) / period, d1)
    return d1, d2
