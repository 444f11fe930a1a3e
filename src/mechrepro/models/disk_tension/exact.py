"""Exact natural frequencies of the annular Kirchhoff plate (Bessel solution), unstressed
or under a uniform isotropic in-plane stress sigma_0 (membrane force N = sigma_0 h).

Clamped at r = a (W = W' = 0), free at r = b (M_r = 0, V_r - N W' = 0: the natural condition
of Eq. 3's stress-stiffness energy).  D lap^2 w - N lap w - rho h omega^2 w = 0 factors as
(lap - k1^2)(lap + k2^2) w = 0, k1^2, -k2^2 = (N/D +- sqrt((N/D)^2 + 4 rho h omega^2 / D)) / 2,
so W = C1 J_n(k2 r) + C2 Y_n(k2 r) + C3 I_n(k1 r) + C4 K_n(k1 r); in units of b = 1 the four
boundary conditions give a 4x4 determinant in lambda = (rho h omega^2 b^4 / D)^(1/4) and
T = N b^2 / D whose roots are the frequency parameters (a buckled fundamental has none).
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np
from scipy.optimize import brentq
from scipy.special import ive, jv, jvp, kve, yv, yvp

from mechrepro.errors import Refusal


def wavenumbers(lam, tension=0.0):
    """(k1 b, k2 b) of the I/K and J/Y columns at ``lam`` under T = N b^2 / D."""
    lam = np.asarray(lam, float)
    if tension == 0.0:
        return lam, lam
    omega2, t = lam**4, float(tension)
    disc = np.sqrt(t * t + 4.0 * omega2)
    return np.sqrt(0.5 * (t + disc)), np.sqrt(0.5 * (disc - t))


def boundary_matrix(lam, n, ratio, nu, tension=0.0):
    """Boundary matrices [..., 4, 4] (rows W(a), W'(a), M_r(b), V_r(b) - N W'(b); columns
    J, Y, I, K) for an array of frequency parameters ``lam``, in units of b = 1, under the
    stress parameter ``tension`` = N b^2 / D."""
    k1, k2 = wavenumbers(lam, tension)

    def bessel(kind, x, scale):
        if kind == "J":
            return jv(n, x), jvp(n, x), -1.0
        if kind == "Y":
            return yv(n, x), yvp(n, x), -1.0
        if kind == "I":
            return ive(n, x) * scale, (ive(n - 1, x) - n / x * ive(n, x)) * scale, 1.0
        return kve(n, x) * scale, (-kve(n - 1, x) - n / x * kve(n, x)) * scale, 1.0

    cols = []
    for kind in ("J", "Y", "I", "K"):
        k = k2 if kind in "JY" else k1
        xa, xb = k * ratio, k
        shrink = np.exp(xa - xb)  # the positive column scalings e^{-k} (I) and e^{k a/b} (K)
        sa, sb = {"J": (1, 1), "Y": (1, 1), "I": (shrink, 1.0), "K": (1.0, shrink)}[kind]
        Za, dZa, _ = bessel(kind, xa, sa)
        Zb, dZb, sgn = bessel(kind, xb, sb)
        # at r = b = 1 with W = Z(k r): W' = k Z', and lap W = sgn k^2 W
        W, dW = Zb, k * dZb
        moment = sgn * k**2 * W - (1 - nu) * (dW - n * n * W)                    # M_r / D
        shear = sgn * k**2 * dW - (1 - nu) * n * n * (dW - W) - tension * dW    # (V_r - N W') / D
        cols.append(np.stack([Za, k * dZa, moment, shear], axis=-1))
    return np.stack(cols, axis=-1)


def frequency_determinant(lam, n, ratio, nu, tension=0.0):
    """det of the boundary matrix at frequency parameter(s) lam."""
    return np.linalg.det(boundary_matrix(lam, n, ratio, nu, tension))


#: the root scan of frequency_parameters: up to lambda = LAM_MAX by STEP, CHUNK at a time
LAM_MAX, STEP, CHUNK = 60.0, 0.02, 8.0


def frequency_parameters(n, ratio, nu, count=1, tension=0.0, memo=True):
    """The first ``count`` roots lambda for harmonic ``n`` under ``tension`` = N b^2 / D,
    memoised (``memo``): the determinant is entire, so every sign change on the scan grid
    brackets one."""
    if not (0.0 < ratio < 1.0):
        raise Refusal(f"a/b = {ratio} must be in (0, 1) for the annular plate")
    roots = _roots if memo else _roots.__wrapped__
    return np.array(roots(int(n), float(ratio), float(nu), int(count), float(tension)))


@lru_cache(maxsize=1024)
def _roots(n, ratio, nu, count, tension):
    f = lambda x: float(frequency_determinant(x, n, ratio, nu, tension))  # noqa: E731
    roots, lo = [], STEP
    while len(roots) < count and lo < LAM_MAX:
        lams = np.arange(lo, min(lo + CHUNK, LAM_MAX) + STEP / 2, STEP)
        det = frequency_determinant(lams, n, ratio, nu, tension)
        idx = np.nonzero(np.sign(det[:-1]) * np.sign(det[1:]) < 0)[0]
        roots += [brentq(f, lams[i], lams[i + 1], xtol=1e-15, rtol=1e-15) for i in idx]
        lo = lams[-1]
    if len(roots) < count:
        raise RuntimeError(f"found only {len(roots)} roots below lambda = {LAM_MAX}")
    return tuple(roots[:count])


def natural_frequencies(n_d, *, a, b, h, E, nu, rho, count=1, sigma=0.0, memo=True):
    """Exact frequencies [Hz] of harmonic n_d under a uniform stress ``sigma`` [Pa]."""
    D = E * h**3 / (12 * (1 - nu**2))
    t = float(sigma) * h * b * b / D
    lam = frequency_parameters(int(n_d), a / b, nu, count=count, tension=t, memo=memo)
    omega = (lam / b) ** 2 * np.sqrt(D / (rho * h))
    return omega / (2 * np.pi)
