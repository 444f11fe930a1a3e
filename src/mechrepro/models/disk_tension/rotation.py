"""Rotation: the centrifugal stress of the spinning disk and the travelling-wave critical
speed that roll-tensioning exists to raise (Sec. 2: "the critical speed instability in
rotating disks occurs when the backward-traveling wave frequency is equal to zero").

Centrifugal stress (Timoshenko & Goodier Sec. 32), q = rho Omega^2: sigma_r = A + B / r^2 -
(3 + nu) / 8 q r^2, sigma_theta = A - B / r^2 - (1 + 3 nu) / 8 q r^2, with sigma_r(b) = 0 and
u_r(r_f) = 0 (``clamped``) or B = 0 (``free_disk``).  The backward wave of N_d = n stops at

    omega_r(Omega_c) = n Omega_c   <=>   det[K + K^(roll) - Omega_c^2 (n^2 M - K^(c))] = 0

(K^(c): Eq. 3 of the centrifugal stress at Omega = 1; Coriolis and in-plane inertia
neglected, as in Southwell's and Mote's thin-disk theory).  Southwell's first order,
Omega_c = omega / sqrt(n^2 - lambda) with lambda = phi^T K^(c) phi / phi^T M phi, bounds it
from above (Rayleigh).
"""
from __future__ import annotations

import numpy as np

from .modal import positive_definite


def centrifugal_stress(r, *, omega, rho, nu, r_f, b, inplane_bc="clamped"):
    """(sigma_r, sigma_theta) [Pa] of the disk spinning at ``omega`` [rad/s]."""
    r = np.asarray(r, float)
    q = rho * omega**2
    if inplane_bc == "free_disk":
        A, B = (3 + nu) / 8 * q * b * b, 0.0
    else:   # clamped (the config's enum refuses the rest), u(r_f) = 0: (1 - nu) A - (1 + nu) B / a^2 = (1 - nu^2) / 8 q a^2;  sigma_r(b) = 0
        a = r_f
        M = np.array([[1 - nu, -(1 + nu) / a**2], [1.0, 1.0 / b**2]])
        A, B = np.linalg.solve(M, [(1 - nu**2) / 8 * q * a * a, (3 + nu) / 8 * q * b * b])
    return (A + B / r**2 - (3 + nu) / 8 * q * r**2,
            A - B / r**2 - (1 + 3 * nu) / 8 * q * r**2)


def critical_speed(K, M, Kc, n):
    """Omega_c [rad/s] of harmonic ``n``, the smallest Omega with det[K - Omega^2 (n^2 M - Kc)]
    = 0; inf: never (n = 0); NaN: K not positive definite, buckled at rest, no critical speed."""
    import scipy.linalg as sla

    if not positive_definite(K):
        return float("nan")
    if n == 0:
        return float("inf")
    mu = sla.eigh(n * n * M - Kc, K, eigvals_only=True)   # (n^2 M - Kc) phi = mu K phi
    top = float(mu.max())
    return float(1.0 / np.sqrt(top)) if top > 0 else float("inf")


def southwell(omega2, phi, M, Kc, n):
    """(Southwell coefficient lambda, first-order Omega_c = omega / sqrt(n^2 - lambda))."""
    lam = float(phi @ Kc @ phi / (phi @ M @ phi))
    return lam, (float(np.sqrt(omega2 / (n * n - lam))) if n * n > lam else float("inf"))
