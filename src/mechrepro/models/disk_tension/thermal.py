"""Thermal analogy of roll-tensioning: the Gaussian temperature of Eq. (4) and its closed-form
plane-stress field (Timoshenko & Goodier, Sec. 143), the residual stress after rolling.  At
the clamp (``inplane_bc``): ``clamped``, u_r(r_f) = 0 (the paper's FE model taken literally),
or ``free_disk``, the solid disk (a blade rolled before it is mounted); sigma_r(b) = 0.
"""
from __future__ import annotations

import numpy as np
from scipy.special import erf

from mechrepro.errors import Refusal


def temperature(r, amplitude, r_c, s):
    """Eq. (4): T(r) = A exp(-(r - r_c)^2 / 2 s^2)  [K]."""
    r = np.asarray(r, float)
    return amplitude * np.exp(-((r - r_c) ** 2) / (2.0 * s * s))


def _antiderivative(r, amplitude, r_c, s):
    """G(r) with dG/dr = T(r) r (closed form of the Gaussian moment)."""
    t = np.asarray(r, float) - r_c
    return amplitude * (-s * s * np.exp(-t * t / (2 * s * s))
                        + r_c * s * np.sqrt(np.pi / 2) * erf(t / (s * np.sqrt(2))))


def thermal_stress(r, *, amplitude, r_c, s, r_f, b, E, nu, alpha, inplane_bc="clamped"):
    """Plane-stress thermal stresses (sigma_r, sigma_theta) [Pa] at radii ``r >= r_f``.

    u = (1+nu) alpha Q/r + C1 r + C2/r with Q(r) = int_{r0}^r T rho d rho, and
    sigma_r = -alpha E Q/r^2 + E/(1-nu^2) ((1+nu) C1 - (1-nu) C2/r^2),
    sigma_theta = alpha E Q/r^2 - alpha E T + E/(1-nu^2) ((1+nu) C1 + (1-nu) C2/r^2).
    ``inplane_bc`` (clamped or free_disk), 0 <= r_f < b and s > 0 are the config's to refuse.
    """
    r = np.asarray(r, float)
    r0 = 0.0 if inplane_bc == "free_disk" else r_f
    if np.any(r < r0 - 1e-12) or np.any(r <= 0):
        raise Refusal("thermal_stress is evaluated only on the flexible region r >= r_f > 0")
    G0 = _antiderivative(r0, amplitude, r_c, s)
    Q = _antiderivative(r, amplitude, r_c, s) - G0
    Qb = _antiderivative(b, amplitude, r_c, s) - G0
    T = temperature(r, amplitude, r_c, s)
    if inplane_bc == "free_disk":
        c1, c2 = (1 - nu) * alpha * Qb / b**2, 0.0
    else:
        a = r_f
        c1 = alpha * Qb / b**2 * (1 - nu**2) / ((1 + nu) + (1 - nu) * a**2 / b**2)
        c2 = -c1 * a * a
    k = E / (1 - nu**2)
    sig_r = -alpha * E * Q / r**2 + k * ((1 + nu) * c1 - (1 - nu) * c2 / r**2)
    sig_t = alpha * E * Q / r**2 - alpha * E * T + k * ((1 + nu) * c1 + (1 - nu) * c2 / r**2)
    return sig_r, sig_t



#: the residual-stress model (``options.residual_stress``): the paper's, or a rival's
STRESS_MODELS = ("thermal_analogy", "hoop_only", "fixed_profile")


def residual_stress(r, *, stress_model="thermal_analogy", profile_rc=None, **kw):
    """(sigma_r, sigma_theta) [Pa] at ``r`` of the paper's field (``thermal_analogy``), or of
    a rival: ``hoop_only`` (sigma_r = 0), ``fixed_profile`` (the profile of ``profile_rc``
    wherever one rolls, scaled to the rim hoop stress of the run's r_c)."""
    if stress_model not in STRESS_MODELS:
        raise Refusal(f"options.residual_stress = {stress_model!r}: allowed {STRESS_MODELS}")
    if stress_model == "fixed_profile":
        if profile_rc is None:
            raise Refusal("stress model fixed_profile needs profile_rc (the profile's r_c)")
        ref = {**kw, "r_c": profile_rc}
        rim = np.array([kw["b"]])
        scale = thermal_stress(rim, **kw)[1][0] / thermal_stress(rim, **ref)[1][0]
        sig_r, sig_t = thermal_stress(r, **ref)
        return scale * sig_r, scale * sig_t
    sig_r, sig_t = thermal_stress(r, **kw)
    if stress_model == "hoop_only":
        return np.zeros_like(sig_r), sig_t
    return sig_r, sig_t


def field(**kw):
    """(sigma_r(r), sigma_theta(r)) of :func:`residual_stress` as callables of r [m]."""
    return (lambda r: residual_stress(r, **kw)[0], lambda r: residual_stress(r, **kw)[1])
