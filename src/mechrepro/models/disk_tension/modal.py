"""Eigen-analysis (Eqs. 5-6), the first-order estimate (Eq. 9), the modal matrices
(Eqs. 16-17), buckling and frequency conversions, shared by both discretisations."""
from __future__ import annotations

import math

import numpy as np

TWO_PI = 2.0 * np.pi

#: sizes (unknowns) of the banded problems solved by inverse iteration (see ``eigen``)
BANDED_MIN, BANDED_MAX = 64, 128
def eigen(K, M, count=1, bandwidth=None):
    """Lowest ``count`` eigenpairs of (K - omega^2 M) phi = 0, Eq. (5)/(6): (omega^2, Phi),
    Phi mass-normalised (omega^2 < 0: buckled).  A banded fundamental of ``BANDED_MIN`` to
    ``BANDED_MAX`` unknowns by inverse iteration (O(n) a step), all else by the dense driver."""
    count = min(int(count), len(K))
    phi = None
    if bandwidth is not None and count == 1 and BANDED_MIN <= len(K) <= BANDED_MAX:
        x = lowest_banded(K, M, bandwidth)
        phi = None if x is None else x[:, None]
    if phi is None:
        import scipy.linalg as sla  # here: validate_disk_tension imports this module, never solves

        lam, phi = sla.eigh(K, M, subset_by_index=[0, count - 1])
    # LAPACK's subset driver loses digits on the small eigenvalues of fine meshes; the
    # Rayleigh quotient of its (good) vectors is accurate to the square of the vector error
    KP, MP = K @ phi, M @ phi
    m = np.einsum("ij,ij->j", phi, MP)
    lam = np.einsum("ij,ij->j", phi, KP) / m
    return lam, phi / np.sqrt(m)


def lowest_banded(K, M, bandwidth, tol=1e-13, maxiter=200):
    """Lowest eigenvector of (K, M) by banded inverse iteration; None: buckled or no convergence."""
    from scipy.linalg.lapack import dpbtrf, dpbtrs

    u = int(bandwidth)
    ab = np.zeros((u + 1, len(K)))
    for k in range(u + 1):
        ab[u - k, k:] = K.diagonal(k)
    c, info = dpbtrf(ab, overwrite_ab=1)
    if info != 0:
        return None
    x = np.ones(len(K)) / np.sqrt(len(K))
    for _ in range(maxiter):
        y = dpbtrs(c, M @ x, overwrite_b=1)[0]
        y /= math.copysign(math.sqrt(y.dot(y)), y @ x)
        if np.abs(y - x).max() < tol * np.abs(y).max():
            return y
        x = y
    return None


def once(memo: dict, what, Ks, fn):
    """``fn(Ks)`` once per (analysis ``what``, K^(sigma) object), kept in ``memo`` with the
    object (so that its id cannot be reused while the model lives)."""
    hit = memo.get((what, id(Ks)))
    if hit is None or hit[0] is not Ks:
        hit = memo[what, id(Ks)] = (Ks, fn(Ks))
    return hit[1]


def positive_definite(K) -> bool:
    """Whether the (stressed) stiffness K is positive definite: the disk has not buckled."""
    try:
        np.linalg.cholesky(K)
    except np.linalg.LinAlgError:
        return False
    return True


def frequency(omega2):
    """f = sqrt(omega^2) / 2 pi [Hz]; a negative omega^2 (buckled) gives NaN (the caller
    stores a buckled flag)."""
    omega2 = np.asarray(omega2, float)
    return np.sqrt(np.where(omega2 < 0, np.nan, omega2)) / TWO_PI


def eq9_delta_omega2(phi, K_sigma, M):
    """Eq. (9): Delta omega^2 = phi^T K^(sigma) phi / phi^T M phi (unrolled mode phi)."""
    phi = np.atleast_2d(np.asarray(phi).T).T
    num = np.einsum("ik,ij,jk->k", phi, K_sigma, phi)
    den = np.einsum("ik,ij,jk->k", phi, M, phi)
    return num / den


def delta_f_linearised(omega, delta_omega2):
    """Delta f = Delta omega^2 / (2 omega) / 2 pi: first-order conversion [Hz]."""
    return np.asarray(delta_omega2) / (2.0 * np.asarray(omega)) / TWO_PI


def delta_f_exact(omega, delta_omega2):
    """Delta f = (sqrt(omega^2 + Delta omega^2) - omega) / 2 pi [Hz]; NaN if buckled."""
    omega = np.asarray(omega, float)
    return frequency(omega**2 + np.asarray(delta_omega2, float)) - omega / TWO_PI


def critical_load_factor(K, K_sigma):
    """Smallest lambda > 0 with det(K + lambda K^(sigma)) = 0 (inf if none): a compressive
    mode of K_sigma phi = mu K phi has mu < 0 and buckles at lambda = -1/mu."""
    import scipy.linalg as sla  # here: validate_disk_tension imports this module, never solves

    mu = sla.eigh(K_sigma, K, eigvals_only=True)
    neg = mu[mu < 0]
    return float(-1.0 / neg.min()) if neg.size else float("inf")


def align_signs(Phi_rolled, M, Phi):
    """Flip rolled modes so that diag(Phi~^T M Phi) >= 0 (eigenvector sign is arbitrary)."""
    s = np.sign(np.einsum("ij,ij->j", Phi_rolled, M @ Phi))
    s[s == 0] = 1.0
    return Phi_rolled * s


def align_pair(Q, M, P):
    """Canonical basis of a rolled mode pair ``Q`` for Eq. (17), whose rotation an
    eigensolver leaves arbitrary: the Procrustes rotation R = U V^T (U S V^T = Q^T M P) onto
    the unrolled pair ``P`` makes (Q R)^T M P = V S V^T independent of it."""
    C = Q.T @ (M @ P)
    U, _, Vt = np.linalg.svd(C)
    return Q @ (U @ Vt)


def harmonic_coupling_symmetry(nonzero_pairs, n_max, orders=range(2, 65)):
    """Smallest symmetry order N of a mesh whose Eq. (16) couples ``nonzero_pairs`` (i < j <=
    n_max): on a C_N mesh cos(i theta), cos(j theta) couple iff i = +-j (mod N); None: none."""
    want = {tuple(sorted(p)) for p in nonzero_pairs}
    for N in orders:
        got = {(i, j) for i in range(n_max + 1) for j in range(i + 1, n_max + 1)
               if (i - j) % N == 0 or (i + j) % N == 0}
        if got == want:
            return N
    return None


def degenerate_harmonics(N, n_d):
    """N_d that stay degenerate pairs on a C_N mesh (N_d mod N not 0 or N/2)."""
    return [int(n) for n in n_d if (n % N) != 0 and (2 * n) % N != 0]
