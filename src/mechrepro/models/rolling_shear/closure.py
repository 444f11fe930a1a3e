"""Eqs. (4)-(9) of the linkage, their Newton solves and the loops over a stroke, written once.

Each function is compiled by :func:`mechrepro.compiled.jit` where numba is installed;
:data:`python` holds the same source un-jitted (the numpy paths).  A kernel takes the
linkage as the array :func:`.geometry.constants` and names it by :func:`record`.  No
fast-math and the C library's sin/cos, so both paths give the same bits.

:func:`guide_brent` is adapted from SciPy's ``brentq`` (scipy/optimize/Zeros/brentq.c),
Copyright (c) 2001-2002 Enthought, Inc. 2003, SciPy Developers, under the BSD 3-clause
licence whose full text :mod:`mechrepro.models.joint_wear.radau` carries."""
from __future__ import annotations

import math
import types
from typing import NamedTuple

import numpy as np

from mechrepro import compiled
from mechrepro.compiled import jit

from .geometry import LINKAGE_KEYS


def available() -> bool:
    """Whether the compiled path runs (numba importable, ``MECHREPRO_RS_KERNEL`` not ``numpy``)."""
    return compiled.available("MECHREPRO_RS_KERNEL")


#: fitness kinds of :func:`fitness` and blocks of :func:`newton2`
LOOPS, POSE, ABCD, GHID = 0, 1, 2, 3
#: status codes of :func:`newton2` (see :func:`.newton.reason`), :func:`guide_brent` and
#: :func:`pose_stroke`
CONVERGED, NON_FINITE, SINGULAR, NO_CONVERGENCE, NO_BRACKET, OFF_BRANCH = 0, 1, 2, 3, 4, 5


#: the constants of :class:`.geometry.Geometry` the equations read (mm, rad), by name; the
#: elbows (+1/-1) as floats
Linkage = NamedTuple("Linkage", [(k, float) for k in LINKAGE_KEYS])


@jit
def record(c):
    """The :class:`Linkage` of an array of :func:`constants` (the order of its fields)."""
    return Linkage(c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], c[8], c[9], c[10], c[11],
                   c[12], c[13], c[14], c[15], c[16], c[17], c[18], c[19], c[20])


# -- Eqs. (4)-(7): the blade ------------------------------------------------------------------

@jit
def to_fixed(p, theta5, theta6, x1, y1):
    """Eq. (4), M20 M12 (x1, y1) written out: a point of the blade frame in the fixed frame."""
    b = theta5 - p.beta2
    cb, sb = np.cos(b), np.sin(b)
    ox = p.l6 * np.cos(theta6) + p.d * np.cos(theta5 + p.beta1)
    oy = p.l6 * np.sin(theta6) + p.d * np.sin(theta5 + p.beta1)
    return ox + cb * x1 - sb * y1, oy + sb * x1 + cb * y1


@jit
def lowest_point(p, theta5, theta6):
    """Eq. (7) with the corrected sign of Eq. (6): (x_k, y_k) from the midpoint (Eq. 5)."""
    xh, yh = to_fixed(p, theta5, theta6, 0.0, -p.h)
    b = theta5 - p.beta2
    return xh - p.R * np.sin(b), yh - p.R * (1.0 - np.cos(b))


@jit
def guide_point(p, beta, x_target):
    """Carrier joint D (x, y) when the blade has angle beta and its lowest point is at
    (x_target, -s): Eqs. (4)-(7) solved backwards from the lowest point."""
    sb, cb = np.sin(beta), np.cos(beta)
    mx, my = x_target + p.R * sb, -p.s + p.R * (1.0 - cb)
    ox, oy = mx + p.h * -sb, my + p.h * cb
    t = beta + p.beta2 + p.beta1
    return ox - p.d * np.cos(t), oy - p.d * np.sin(t)


@jit
def guide_distance(p, beta, x_target):
    """|ED| - l6 at blade angle beta: zero where the guide rod closes (``abs(complex)``: the C
    library's hypot on both paths, unlike ``math.hypot``)."""
    dx, dy = guide_point(p, beta, x_target)
    return abs(complex(dx, dy)) - p.l6


@jit
def guide_brent(p, x_target, xpre, xcur, xtol, rtol, max_iter):
    """Root of :func:`guide_distance` in [xpre, xcur]: ``scipy.optimize.brentq``'s C code step for
    step (the same root to the bit) without a call into Python per step.  Returns (root,
    status): ``NON_FINITE`` for a NaN, ``NO_BRACKET`` when f keeps its sign."""
    fpre = guide_distance(p, xpre, x_target)
    fcur = guide_distance(p, xcur, x_target)
    if math.isnan(fpre) or math.isnan(fcur):
        return xcur, NON_FINITE
    if fpre == 0:
        return xpre, CONVERGED
    if fcur == 0:
        return xcur, CONVERGED
    if (math.copysign(1.0, fpre) < 0) == (math.copysign(1.0, fcur) < 0):
        return 0.0, NO_BRACKET
    xblk = fblk = spre = scur = 0.0
    for _ in range(max_iter):
        if fpre != 0 and fcur != 0 and (math.copysign(1.0, fpre) < 0) != (
                math.copysign(1.0, fcur) < 0):
            xblk, fblk = xpre, fpre
            spre = scur = xcur - xpre
        if abs(fblk) < abs(fcur):
            xpre, xcur, xblk = xcur, xblk, xcur
            fpre, fcur, fblk = fcur, fblk, fcur
        delta = (xtol + rtol * abs(xcur)) / 2
        sbis = (xblk - xcur) / 2
        if fcur == 0 or abs(sbis) < delta:
            return xcur, CONVERGED
        if abs(spre) > delta and abs(fcur) < abs(fpre):
            if xpre == xblk:     # interpolate
                stry = -fcur * (xcur - xpre) / (fcur - fpre)
            else:                # extrapolate
                dpre = (fpre - fcur) / (xpre - xcur)
                dblk = (fblk - fcur) / (xblk - xcur)
                stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
            bound = abs(spre) if abs(spre) < 3 * abs(sbis) - delta else 3 * abs(sbis) - delta
            if 2 * abs(stry) < bound:
                spre, scur = scur, stry
            else:
                spre = scur = sbis
        else:
            spre = scur = sbis
        xpre, fpre = xcur, fcur
        xcur += scur if abs(scur) > delta else (delta if sbis > 0 else -delta)
        fcur = guide_distance(p, xcur, x_target)
        if math.isnan(fcur):
            return xcur, NON_FINITE
    return xcur, NO_CONVERGENCE


@jit
def _bracket_floor(betas, j):
    """The least |beta| a root in [betas[j], betas[j + 1]] can have."""
    if betas[j] <= 0.0 <= betas[j + 1]:
        return 0.0
    return min(abs(betas[j]), abs(betas[j + 1]))


@jit
def guide_pose(c, betas, f, dx, x_target, guide_mode, margin, xtol, rtol, max_iter):
    """The pose of :func:`.blade.exact_pose`: :func:`guide_brent` in every bracket of |ED| - l6
    (``f``) over ``betas`` not clearly (``margin``) in the guide rod's other mode, and of the roots
    in the paper's ranges the one with the smallest (|beta|, theta5, theta6).  Brackets are
    visited outwards from beta = 0 and only while they can hold a smaller |beta|; f and the x of
    D (``dx``) are filled in as reached.  Returns (found, theta5, theta6, status)."""
    p = record(c)
    two_pi = 2 * math.pi
    nb = betas.size - 1
    lo = 0                                       # the first bracket: the least floor
    for j in range(1, nb):
        if _bracket_floor(betas, j) < _bracket_floor(betas, lo):
            lo = j
    hi = lo
    for i in (lo, lo + 1):                       # points scanned: lo .. hi + 1
        dx[i], dy = guide_point(p, betas[i], x_target)
        f[i] = abs(complex(dx[i], dy)) - p.l6
    found, best, t5b, t6b = False, 0.0, 0.0, 0.0
    j = lo
    while True:
        f0, f1 = f[j], f[j + 1]
        if ((f0 <= 0.0 and f1 >= 0.0) or (f0 >= 0.0 and f1 <= 0.0)) and not (
                guide_mode * dx[j] < -margin and guide_mode * dx[j + 1] < -margin):
            b, status = guide_brent(p, x_target, betas[j], betas[j + 1], xtol, rtol, max_iter)
            if status != CONVERGED:
                return False, b, 0.0, status
            ex, ey = guide_point(p, b, x_target)
            t5, t6 = b + p.beta2, math.atan2(ey, ex) % two_pi
            if (0.0 <= t5 <= math.pi and math.pi <= t6 <= two_pi
                    and guide_mode * math.cos(t6) > 0):
                key = abs(b)
                if not found or key < best or (key == best and (
                        t5 < t5b or (t5 == t5b and t6 < t6b))):
                    found, best, t5b, t6b = True, key, t5, t6
        # the next bracket outwards: the one beside the scanned ones with the least floor
        left = _bracket_floor(betas, lo - 1) if lo > 0 else math.inf
        right = _bracket_floor(betas, hi + 1) if hi + 1 < nb else math.inf
        nxt = min(left, right)
        if nxt == math.inf or (found and nxt > best):
            return found, t5b, t6b, CONVERGED
        if left <= right:
            lo -= 1
            j, i = lo, lo
        else:
            hi += 1
            j, i = hi, hi + 1
        dx[i], dy = guide_point(p, betas[i], x_target)
        f[i] = abs(complex(dx[i], dy)) - p.l6


@jit
def pose_block(p, x_target, t5, t6):
    """Eq. (7) in Newton form, x_k - x_target and y_k + s, with its Jacobian in (t5, t6)."""
    be = t5 - p.beta2
    cb, sb = math.cos(be), math.sin(be)
    c51, s51 = math.cos(t5 + p.beta1), math.sin(t5 + p.beta1)
    c6, s6 = math.cos(t6), math.sin(t6)
    xk = p.l6 * c6 + p.d * c51 + p.h * sb - p.R * sb
    yk = p.l6 * s6 + p.d * s51 - p.h * cb - p.R * (1.0 - cb)
    return (xk - x_target, yk + p.s,
            -p.d * s51 + (p.h - p.R) * cb, -p.l6 * s6,
            p.d * c51 + (p.h - p.R) * sb, p.l6 * c6)


# -- Eq. (9): the two loops ---------------------------------------------------------------------

@jit
def loop_knowns(p, theta5, theta6):
    """The terms of Eq. (9) that theta5, theta6 fix: l8 e^{i(t5 + alpha)}, l6 e^{i t6},
    l5 e^{i t5} as (cx, cy, c6, s6, ix, iy)."""
    c6, s6 = p.l6 * math.cos(theta6), p.l6 * math.sin(theta6)
    cx, cy = p.l8 * math.cos(theta5 + p.alpha), p.l8 * math.sin(theta5 + p.alpha)
    ix, iy = p.l5 * math.cos(theta5), p.l5 * math.sin(theta5)
    return cx, cy, c6, s6, ix, iy


@jit
def loop_residuals(p, k, t1, t2, t3, t4):
    """Eq. (9) as printed, b1..b4, with the knowns ``k`` of :func:`loop_knowns`."""
    cx, cy, c6, s6, ix, iy = k
    return (p.l1 * np.cos(t1) - p.l3 * np.cos(t3) - cx - c6 - p.l10 - p.l9,
            p.l1 * np.sin(t1) - p.l3 * np.sin(t3) - cy - s6 + p.l11,
            p.l2 * np.cos(t2) - p.l4 * np.cos(t4) - ix - c6 - p.l10,
            p.l2 * np.sin(t2) - p.l4 * np.sin(t4) - iy - s6 + p.l11)


@jit
def dyad_block(la, lb, px, py, ta, tb):
    """One loop of Eq. (9) in Newton form, la e^{i ta} - lb e^{i tb} - (px, py), with its
    Jacobian in (ta, tb)."""
    ca, sa, cb, sb = math.cos(ta), math.sin(ta), math.cos(tb), math.sin(tb)
    return (la * ca - lb * cb - px, la * sa - lb * sb - py,
            -la * sa, lb * sb, la * ca, -lb * cb)


@jit
def fitness(kind, p, q, X, G):
    """selPSO's G = sum |residuals| per particle (rows of X) into G: Eq. (9) (``LOOPS``,
    q the knowns of :func:`loop_knowns`) or Eq. (7) (``POSE``, q[0] = x_target)."""
    for i in range(X.shape[0]):
        if kind == LOOPS:
            f1, f2, f3, f4 = loop_residuals(p, q, X[i, 0], X[i, 1], X[i, 2], X[i, 3])
            G[i] = abs(f1) + abs(f2) + abs(f3) + abs(f4)
        else:
            xk, yk = lowest_point(p, X[i, 0], X[i, 1])
            G[i] = abs(xk - q[0]) + abs(yk + p.s)


# -- Newton on the 2x2 blocks and the continuation along a stroke -------------------------------

@jit
def newton2(kind, p, q0, q1, a, b, tol, max_iter, scale, singular_rtol):
    """Newton on one 2x2 block (``POSE``: Eq. 7 at x_target = q0; ``ABCD``/``GHID``: the loop
    closing on (q0, q1)) by Cramer's rule, refused when |det| <= singular_rtol scale (a toggle).
    Returns (a, b, G, iterations, status, det)."""
    G = math.inf
    for k in range(max_iter + 1):
        if kind == POSE:
            f1, f2, j11, j12, j21, j22 = pose_block(p, q0, a, b)
        elif kind == ABCD:
            f1, f2, j11, j12, j21, j22 = dyad_block(p.l1, p.l3, q0, q1, a, b)
        else:
            f1, f2, j11, j12, j21, j22 = dyad_block(p.l2, p.l4, q0, q1, a, b)
        G = abs(f1) + abs(f2)
        if G < tol:
            return a, b, G, k, CONVERGED, 0.0
        if not math.isfinite(G):
            return a, b, G, k, NON_FINITE, 0.0
        if k == max_iter:
            break
        det = j11 * j22 - j12 * j21
        if abs(det) <= singular_rtol * scale:
            return a, b, G, k, SINGULAR, det
        a -= (f1 * j22 - f2 * j12) / det
        b -= (j11 * f2 - j21 * f1) / det
    return a, b, G, max_iter, NO_CONVERGENCE, 0.0


@jit
def pose_newton(c, t5, t6, x_target, tol, max_iter, singular_rtol):
    """Eq. (7): theta5, theta6 with the lowest point at (x_target, -s), by :func:`newton2`."""
    p = record(c)
    return newton2(POSE, p, x_target, 0.0, t5, t6, tol, max_iter, abs(p.R - p.h) * p.l6,
                   singular_rtol)


@jit
def loops_newton(c, t1, t2, t3, t4, theta5, theta6, tol, max_iter, singular_rtol):
    """Eq. (9): the two loops by :func:`newton2`, each to tol / 2, closing on its carrier joint
    relative to its crank pivot (A, G)."""
    p = record(c)
    cx, cy, c6, s6, ix, iy = loop_knowns(p, theta5, theta6)
    r1 = newton2(ABCD, p, cx + c6 + p.l10 + p.l9, cy + s6 - p.l11, t1, t3, 0.5 * tol,
                 max_iter, p.l1 * p.l3, singular_rtol)
    r2 = newton2(GHID, p, ix + c6 + p.l10, iy + s6 - p.l11, t2, t4, 0.5 * tol, max_iter,
                 p.l2 * p.l4, singular_rtol)
    return r1, r2


@jit
def pose_stroke(c, x_k, t5, t6, tol, max_iter, singular_rtol, guide_mode, out):
    """:func:`pose_newton` at every cut point, each from the linear extrapolation of the two
    previous, theta6 mod 2 pi, every pose checked on the guide rod's design branch.  Returns
    (first failing index or -1, status (``OFF_BRANCH``), G, det)."""
    for i in range(x_k.size):
        a, b, G, k, status, det = pose_newton(c, t5, t6, x_k[i], tol, max_iter, singular_rtol)
        if status != CONVERGED:
            return i, status, G, det
        out[i, 0], out[i, 1] = a, b
        if i > 0:
            t5, t6 = 2 * out[i, 0] - out[i - 1, 0], 2 * out[i, 1] - out[i - 1, 1]
        else:
            t5, t6 = a, b
    two_pi = 2 * math.pi
    for i in range(x_k.size):
        out[i, 1] = out[i, 1] % two_pi
    for i in range(x_k.size):
        t5, t6 = out[i, 0], out[i, 1]
        if not (t5 >= 0 and t5 <= math.pi and t6 >= math.pi and t6 <= two_pi
                and guide_mode * math.cos(t6) > 0):
            return i, OFF_BRANCH, 0.0, 0.0
    return -1, CONVERGED, 0.0, 0.0


@jit
def loops_stroke(c, theta, tol, max_iter, singular_rtol):
    """:func:`loops_newton` at every pose theta[i, 4:6], warm-started like :func:`pose_stroke`;
    the summed fitness (so that no work is skipped)."""
    g1, g2, g3, g4 = theta[0, 0], theta[0, 1], theta[0, 2], theta[0, 3]
    p1 = p2 = p3 = p4 = 0.0
    total = 0.0
    for i in range(theta.shape[0]):
        r1, r2 = loops_newton(c, g1, g2, g3, g4, theta[i, 4], theta[i, 5], tol, max_iter,
                              singular_rtol)
        x1, x2, x3, x4 = r1[0], r2[0], r1[1], r2[1]
        if i > 0:
            g1, g2, g3, g4 = 2 * x1 - p1, 2 * x2 - p2, 2 * x3 - p3, 2 * x4 - p4
        else:
            g1, g2, g3, g4 = x1, x2, x3, x4
        p1, p2, p3, p4 = x1, x2, x3, x4
        total += r1[2] + r2[2]
    return total


@jit
def dyad_joint(px, py, qx, qy, rp, rq, e):
    """Joint X of a loop of Eq. (9): |X - P| = rp, |X - Q| = rq on side ``e`` (the sign of
    (X - P) x (Q - X)); returns (x, y, h2), h2 < 0 (x, y NaN) where the loop cannot close."""
    L = np.hypot(qx - px, qy - py)
    ux, uy = (qx - px) / L, (qy - py) / L
    a = (rp * rp - rq * rq + L * L) / (2.0 * L)
    h2 = rp * rp - a * a
    hgt = np.sqrt(h2)
    return px + a * ux + e * hgt * uy, py + a * uy - e * hgt * ux, h2


@jit
def assembles_clearly(c, poses, margin):
    """True when both loops of Eq. (9) close at every pose with theta1..4 inside the paper's ranges
    by more than ``margin``, so round-off cannot decide; False means "not clearly" and the
    caller runs :func:`.optimise.check_assembly`."""
    p = record(c)
    two_pi = 2.0 * math.pi
    for i in range(poses.shape[0]):
        t5, t6 = poses[i, 0], poses[i, 1]
        dx_, dy_ = p.l6 * math.cos(t6), p.l6 * math.sin(t6)
        for k in range(2):
            if k == 0:   # A -> C, levers l1, l3
                px, py = -p.l10 - p.l9, p.l11
                qx = dx_ + p.l8 * math.cos(t5 + p.alpha)
                qy = dy_ + p.l8 * math.sin(t5 + p.alpha)
                rp, rq, e = p.l1, p.l3, p.elbow1
            else:        # G -> I, levers l2, l4
                px, py = -p.l10, p.l11
                qx = dx_ + p.l5 * math.cos(t5)
                qy = dy_ + p.l5 * math.sin(t5)
                rp, rq, e = p.l2, p.l4, p.elbow2
            xx, xy, h2 = dyad_joint(px, py, qx, qy, rp, rq, e)
            if not h2 > margin * rp * rp:
                return False
            # theta1 / theta2 (crank, in [pi, 2 pi]) and theta3 / theta4 (rod, in [0, pi])
            crank = math.atan2(xy - py, xx - px) % two_pi
            rod = math.atan2(xy - qy, xx - qx) % two_pi
            if not (math.pi + margin < crank < two_pi - margin):
                return False
            if not (margin < rod < math.pi - margin):
                return False
    return True


def _uncompiled(namespace: dict) -> types.SimpleNamespace:
    """This module's functions un-jitted, calling each other un-jitted."""
    plain = dict(namespace)
    for name, f in namespace.items():
        src = getattr(f, "py_func", f)
        if isinstance(src, types.FunctionType) and src.__module__ == __name__:
            plain[name] = types.FunctionType(src.__code__, plain, src.__name__,
                                             src.__defaults__, src.__closure__)
    return types.SimpleNamespace(**plain)


#: every function above as Python (the numpy paths, and the Python path of each loop)
python = _uncompiled(globals())
