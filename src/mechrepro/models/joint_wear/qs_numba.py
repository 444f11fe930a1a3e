"""The element-wise stages of the quasi-static contact state (quasistatic.py), written once.

Each stage is one loop over the samples of a period (a few hundred; a row of them per
bushing where quasistatic.periods solves several together), rather than ~25 numpy
operations each paying numpy's call overhead: compiled with numba where installed (cached
on disk), the same source run as Python otherwise (slow, but the same arithmetic).  The
spectral derivative between the stages stays numpy's FFT.
"""
from __future__ import annotations

import math

import numpy as np

from mechrepro.compiled import jit


@jit
def setup(th3, ph2, w3, w2, a3, a2, M11, M22, am, l0, l2, l3, m2, m3, P, Fx, Fy, g):
    """b3, b2 (the equations of motion without the joint force) and J^T of the joint (2-D:
    a row per link motion)."""
    b3 = np.empty(th3.shape)
    b2 = np.empty(th3.shape)
    j11 = np.empty(th3.shape)
    j12 = np.empty(th3.shape)
    j21 = np.empty(th3.shape)
    j22 = np.empty(th3.shape)
    det = np.empty(th3.shape)
    for r in range(th3.shape[0]):
        for i in range(th3.shape[1]):
            c3, s3 = math.cos(th3[r, i]), math.sin(th3[r, i])
            c2, s2 = math.cos(ph2[r, i]), math.sin(ph2[r, i])
            cd = math.cos(th3[r, i] - ph2[r, i])
            sd = math.sin(th3[r, i] - ph2[r, i])
            rhs3 = M11 * a3[r, i] + am * cd * a2[r, i] + am * sd * w2[r, i] ** 2
            rhs2 = am * cd * a3[r, i] + M22 * a2[r, i] - am * sd * w3[r, i] ** 2
            # the load P at E towards F and the link weights (as clearance.rhs_into)
            ex, ey = l0 + l3 / 2 * c3, l3 / 2 * s3
            dx, dy = Fx - ex, Fy - ey
            dn = math.hypot(dx, dy)
            Px, Py = P * dx / dn, P * dy / dn
            Q3 = l3 / 2 * (-s3 * Px + c3 * Py) - g * (m3 * l3 / 2 + m2 * l3) * c3
            Q2 = -g * m2 * l2 / 2 * c2
            b3[r, i] = rhs3 - Q3
            b2[r, i] = rhs2 - Q2
            j11[r, i], j12[r, i] = -l3 * s3, l3 * c3
            j21[r, i], j22[r, i] = -l2 * s2, l2 * c2
            det[r, i] = j11[r, i] * j22[r, i] - j12[r, i] * j21[r, i]
    return b3, b2, j11, j12, j21, j22, det


@jit
def force(b3, b2, j11, j12, j21, j22, det, tau, sgn, mu, K, n_exp):
    """The joint force for a friction moment tau: F_N, the contact direction, delta (2-D:
    a row per bushing, K' of each row in ``K``)."""
    rows, n = b3.shape
    F_N = np.empty((rows, n))
    ang_n = np.empty((rows, n))
    delta = np.empty((rows, n))
    inv_n = 1.0 / n_exp
    for r in range(rows):
        for i in range(n):
            c2 = b2[r, i] - tau[r, i]
            fx = (b3[r, i] * j22[r, i] - j12[r, i] * c2) / det[r, i]
            fy = (j11[r, i] * c2 - j21[r, i] * b3[r, i]) / det[r, i]
            mus = mu * sgn[r, i]
            F_N[r, i] = math.hypot(fx, fy) / math.sqrt(1.0 + mus ** 2)
            ang_n[r, i] = math.atan2(fy, fx) - math.atan(mus)
            delta[r, i] = (max(F_N[r, i], 0.0) / K[r]) ** inv_n
    return F_N, ang_n, delta


@jit
def friction(F_N, delta, dang, slide, w2R, clearance, v_eps, mu, R_bush):
    """Sliding velocity, friction sign and force, friction moment (2-D: a row per bushing,
    its clearance and R_j in ``clearance``, ``R_bush``)."""
    rows, n = F_N.shape
    v_T = np.empty((rows, n))
    sgn = np.empty((rows, n))
    F_T = np.empty((rows, n))
    tau = np.empty((rows, n))
    for r in range(rows):
        for i in range(n):
            v = (clearance[r] + delta[r, i]) * dang[r, i] + slide - w2R[r, i]
            v_T[r, i] = v
            s = v / math.sqrt(v * v + v_eps * v_eps)
            sgn[r, i] = s
            F_T[r, i] = mu * F_N[r, i] * s
            tau[r, i] = R_bush[r] * F_T[r, i]
    return v_T, sgn, F_T, tau


@jit
def contact_angle(ang_n, ph2):
    """The contact angle psi on the bushing (coupler frame), in (-pi, pi]."""
    n = ang_n.size
    psi = np.empty(n)
    for i in range(n):
        x = ang_n[i] - ph2[i]
        psi[i] = math.atan2(math.sin(x), math.cos(x))
    return psi


@jit
def periodic_part(a, group):
    """The periodic part of angles sampled uniformly over one period (the rows of ``a``,
    2-D) and the turns per period k taken from it, for each ``group`` of consecutive rows
    (one call of periodic_derivatives): where some step of the group reaches pi its rows
    are unwrapped (:func:`unwrap`; below pi it corrects none), then, where some row of it
    turns (|k| > 0.5 before rounding, half to even), a_i - 2 pi k i / n.  Returns (the
    part, k per row, whether the row's group turns, whether some group turns)."""
    rows, n = a.shape
    out = a.copy()
    k = np.zeros(rows)
    turns = np.zeros(rows, np.bool_)
    some = False
    for g in range(0, rows, group):
        e = g + group
        step, turn = steps(out, g, e)
        if not step < math.pi:
            unwrap(out, g, e)
            turn = steps(out, g, e)[1]
        if turn <= 0.5:
            continue
        some = True
        for r in range(g, e):
            k[r] = np.rint((out[r, -1] + (out[r, 1] - out[r, 0]) - out[r, 0]) / (2.0 * math.pi))
            c = 2.0 * math.pi * k[r]
            turns[r] = True
            for i in range(n):
                out[r, i] = out[r, i] - c * i / n
    return out, k, turns, some


@jit
def unwrap(a, r0, r1):
    """``np.unwrap`` of rows r0 to r1 of ``a`` (2-D, in place; period 2 pi, discontinuity
    pi), operation for operation: each step reduced to [-pi, pi) by numpy's floating
    remainder (the sign of the divisor), a step of exactly +pi kept at +pi, the corrections
    of the steps of pi and more summed left to right."""
    for r in range(r0, r1):
        prev = a[r, 0]
        c = 0.0
        for i in range(1, a.shape[1]):
            x = a[r, i]
            dd = x - prev
            prev = x
            red = (dd + math.pi) % (2.0 * math.pi) - math.pi    # Python's float % is numpy's
            if red == -math.pi and dd > 0.0:
                red = math.pi
            corr = 0.0 if abs(dd) < math.pi else red - dd
            c = corr if i == 1 else c + corr
            a[r, i] = x + c


@jit
def steps(a, r0, r1):
    """Over rows r0 to r1 of ``a`` (2-D): the largest |a[i] - a[i-1]| (np.unwrap corrects
    none below pi) and the largest |a[-1] + (a[1] - a[0]) - a[0]| / 2 pi (the turns per
    period that periodic_derivatives rounds: none up to 0.5); inf where a NaN is met."""
    step = 0.0
    turn = 0.0
    for r in range(r0, r1):
        for i in range(1, a.shape[1]):
            d = abs(a[r, i] - a[r, i - 1])
            if not d <= step:
                step = d if d == d else math.inf
        x = abs((a[r, -1] + (a[r, 1] - a[r, 0]) - a[r, 0]) / (2.0 * math.pi))
        if not x <= turn:
            turn = x if x == x else math.inf
    return step, turn
