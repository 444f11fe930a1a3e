"""Exact natural frequencies of the unstressed annular Kirchhoff plate (Bessel solution).

Clamped at r = a (W = W' = 0), free at r = b (M_r = 0, V_r = 0).  With
W = C1 J_n(kr) + C2 Y_n(kr) + C3 I_n(kr) + C4 K_n(kr) and k^4 = rho h omega^2 / D, the
four boundary conditions give a 4x4 determinant in lambda = k b whose roots are the
frequency parameters.  Columns of I_n and K_n are scaled by positive factors
(exp(-lambda), exp(lambda a/b)) so that the determinant stays O(1) without moving a root.
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np
from scipy.optimize import brentq
from scipy.special import ive, jv, jvp, kve, yv, yvp


def boundary_matrix(lam, n, ratio, nu):
    """Boundary matrices [..., 4, 4] (rows W(a), W'(a), M_r(b), V_r(b); columns J, Y, I, K)
    for an array of frequency parameters ``lam``, in units of b = 1."""
    lam = np.asarray(lam, float)
    xa, xb = lam * ratio, lam
    shrink = np.exp(xa - xb)  # the positive column scalings e^{-lam} (I) and e^{lam a/b} (K)

    def bessel(kind, x, scale):
        if kind == "J":
            return jv(n, x), jvp(n, x), -1.0
        if kind == "Y":
            return yv(n, x), yvp(n, x), -1.0
        if kind == "I":
            return ive(n, x) * scale, (ive(n - 1, x) - n / x * ive(n, x)) * scale, 1.0
        return kve(n, x) * scale, (-kve(n - 1, x) - n / x * kve(n, x)) * scale, 1.0

    cols = []
    for kind, sa, sb in (("J", 1, 1), ("Y", 1, 1), ("I", shrink, 1.0), ("K", 1.0, shrink)):
        Za, dZa, _ = bessel(kind, xa, sa)
        Zb, dZb, sgn = bessel(kind, xb, sb)
        # at r = b = 1 with W = Z(lam r): W' = lam Z', and lap W = sgn lam^2 W
        W, dW = Zb, lam * dZb
        moment = sgn * lam**2 * W - (1 - nu) * (dW - n * n * W)          # M_r / D
        shear = sgn * lam**2 * dW - (1 - nu) * n * n * (dW - W)          # V_r / D
        cols.append(np.stack([Za, lam * dZa, moment, shear], axis=-1))
    return np.stack(cols, axis=-1)


def frequency_determinant(lam, n, ratio, nu):
    """det of the boundary matrix at frequency parameter(s) lam = k b."""
    return np.linalg.det(boundary_matrix(lam, n, ratio, nu))


def frequency_parameters(n, ratio, nu, count=1, lam_max=60.0, step=0.02, chunk=8.0):
    """The first ``count`` roots lambda = k b of the determinant for harmonic ``n``.

    The determinant is an entire function of lambda (no poles), so every sign change on the
    scan grid brackets a root; the scan stops at the first chunk that completes ``count``.
    A pure function of its arguments, so memoised: every run of a batch needs the same few
    (n, a/b, nu) -- the thickness calibration, the exact and the rolled references -- and
    the cached roots are the very numbers a fresh solve gives.
    """
    if not (0.0 < ratio < 1.0):
        raise ValueError(f"a/b = {ratio} must be in (0, 1) for the annular plate")
    return np.array(_roots(int(n), float(ratio), float(nu), int(count), float(lam_max),
                           float(step), float(chunk)))


@lru_cache(maxsize=1024)
def _roots(n, ratio, nu, count, lam_max, step, chunk):
    f = lambda x: float(frequency_determinant(x, n, ratio, nu))  # noqa: E731
    roots, lo = [], step
    while len(roots) < count and lo < lam_max:
        lams = np.arange(lo, min(lo + chunk, lam_max) + step / 2, step)
        det = frequency_determinant(lams, n, ratio, nu)
        idx = np.nonzero(np.sign(det[:-1]) * np.sign(det[1:]) < 0)[0]
        roots += [brentq(f, lams[i], lams[i + 1], xtol=1e-15, rtol=1e-15) for i in idx]
        lo = lams[-1]
    if len(roots) < count:
        raise RuntimeError(f"found only {len(roots)} roots below lambda = {lam_max}")
    return tuple(roots[:count])


def natural_frequencies(n_d, *, a, b, h, E, nu, rho, count=1):
    """Exact natural frequencies [Hz] of harmonic n_d (0 nodal circles first)."""
    D = E * h**3 / (12 * (1 - nu**2))
    lam = frequency_parameters(int(n_d), a / b, nu, count=count)
    omega = (lam / b) ** 2 * np.sqrt(D / (rho * h))
    return omega / (2 * np.pi)
