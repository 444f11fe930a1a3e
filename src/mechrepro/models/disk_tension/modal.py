"""Eigen-analysis (Eqs. 5-6), the first-order estimate (Eq. 9), the modal matrices
(Eqs. 16-17), buckling and frequency conversions, shared by both discretisations."""
from __future__ import annotations

import math

import numpy as np

from mechrepro.errors import Refusal

TWO_PI = 2.0 * np.pi


class BucklingError(Refusal, ArithmeticError):
    """A requested frequency does not exist because the stressed plate has buckled."""


#: sizes (unknowns) of the banded problems solved by inverse iteration (see ``eigen``)
BANDED_MIN, BANDED_MAX = 64, 128


def eigen(K, M, count=1, bandwidth=None):
    """Lowest ``count`` eigenpairs of (K - omega^2 M) phi = 0, Eq. (5)/(6).

    Returns (omega^2, Phi) with mass-normalised columns (Phi^T M Phi = I).  omega^2 may be
    negative when K includes compressive K^(sigma): the caller decides (see ``frequency``).

    ``bandwidth``: half-bandwidth of K and M when they are banded (the radial Hermite
    elements: 3).  The fundamental (``count = 1``) of a banded pencil with K positive
    definite and at most ``BANDED_MAX`` unknowns is found by inverse iteration with K's
    banded Cholesky factor (:func:`lowest_banded`, O(n) per step instead of the dense
    driver's O(n^3)); a buckled K (not positive definite) or an iteration that does not
    converge falls back to the dense driver, as does every larger problem.
    """
    count = min(int(count), len(K))
    phi = None
    if bandwidth is not None and count == 1 and BANDED_MIN <= len(K) <= BANDED_MAX:
        x = lowest_banded(K, M, bandwidth)
        phi = None if x is None else x[:, None]
    if phi is None:
        import scipy.linalg as sla  # here: validate_disk_tension imports this module, never solves

        lam, phi = sla.eigh(K, M, subset_by_index=[0, count - 1])
    # LAPACK's subset driver (gvx) loses digits on the small eigenvalues of fine meshes
    # (1e-5 at 256 Hermite elements); its vectors are good, and the Rayleigh quotient of a
    # good vector is accurate to the square of the vector error
    KP, MP = K @ phi, M @ phi
    m = np.einsum("ij,ij->j", phi, MP)
    lam = np.einsum("ij,ij->j", phi, KP) / m
    return lam, phi / np.sqrt(m)


def lowest_banded(K, M, bandwidth, tol=1e-13, maxiter=200):
    """Eigenvector of the lowest eigenvalue of (K, M) by inverse iteration, K symmetric
    positive definite with half-bandwidth ``bandwidth``; None if K is not positive definite
    or the iteration has not converged (|change| < ``tol`` of the largest entry) within
    ``maxiter`` steps.  Start vector: all ones (deterministic).  Each step costs one banded
    triangular solve pair and one product with M; the error falls by omega_1^2 / omega_2^2
    per step (1/10 or less for the clamped disk)."""
    from scipy.linalg.lapack import dpbtrf, dpbtrs

    n, u = len(K), int(bandwidth)
    ab = np.zeros((u + 1, n))
    for k in range(u + 1):
        ab[u - k, k:] = K.diagonal(k)
    c, info = dpbtrf(ab, overwrite_ab=1)
    if info != 0:
        return None
    # the step's angle says for free when the change test cannot pass yet: |change| <
    # tol max|y| (unit x, y) needs sin^2(x, y) <= |y - x|^2 < n tol^2, far below SCREEN,
    # and SCREEN is far above the round-off of q - s^2 (~1e-16 q); the test itself (an
    # exact comparison, same steps, same vector) runs only in the last few steps
    screen = n * tol * tol < 1e-3 * SCREEN
    amax, amin = np.maximum.reduce, np.minimum.reduce
    x = np.ones(n) / np.sqrt(n)
    for _ in range(maxiter):
        y, info = dpbtrs(c, M @ x, overwrite_b=1)
        s, q = y @ x, y.dot(y)
        # np.linalg.norm's own arithmetic (sqrt of y.dot(y)) without its ~10 us of checks:
        # the loop runs ~17 times per call, 7000 calls in the identifiability scan
        y /= math.copysign(math.sqrt(q), s)
        if not (screen and q - s * s > SCREEN * q):
            d = y - x
            if amax(np.abs(d, out=d)) < tol * max(amax(y), -amin(y)):
                return y
        x = y
    return None


#: sin^2 of a step's angle above which inverse iteration's change test is not evaluated
SCREEN = 1e-12


def frequency(omega2, buckled="nan"):
    """f = sqrt(omega^2) / 2 pi [Hz]; a negative omega^2 (buckled) gives NaN or raises.

    Never a silent square root of a negative number: ``buckled="raise"`` raises
    :class:`BucklingError`, ``"nan"`` returns NaN (the caller stores a buckled flag).
    """
    omega2 = np.asarray(omega2, float)
    neg = omega2 < 0
    if np.any(neg) and buckled == "raise":
        raise BucklingError(f"omega^2 = {omega2[neg]} < 0: the stressed plate has buckled")
    out = np.sqrt(np.where(neg, np.nan, omega2)) / TWO_PI
    return out


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
    """Smallest lambda > 0 with det(K + lambda K^(sigma)) = 0 (inf if none).

    Solves K_sigma phi = mu K phi (K positive definite after clamping); a compressive mode
    has mu < 0 and buckles at lambda = -1/mu.
    """
    import scipy.linalg as sla  # here: validate_disk_tension imports this module, never solves

    mu = sla.eigh(K_sigma, K, eigvals_only=True)
    neg = mu[mu < 0]
    return float(-1.0 / neg.min()) if neg.size else float("inf")


def modal_stress_matrix(Phi, K_sigma):
    """Eq. (16): [K^hat(sigma)] = Phi^T K^(sigma) Phi."""
    return Phi.T @ K_sigma @ Phi


def modal_mass_cross(Phi_rolled, M, Phi):
    """Eq. (17): [m^hat] = Phi~^T M Phi (unit matrix when modes do not change)."""
    return Phi_rolled.T @ M @ Phi


def mac(Phi_a, Phi_b, M=None):
    """Modal assurance criterion |a^T M b|^2 / (a^T M a)(b^T M b) for all column pairs."""
    W = Phi_b if M is None else M @ Phi_b
    Wa = Phi_a if M is None else M @ Phi_a
    num = (Phi_a.T @ W) ** 2
    return num / np.outer(np.einsum("ij,ij->j", Phi_a, Wa), np.einsum("ij,ij->j", Phi_b, W))


def align_signs(Phi_rolled, M, Phi):
    """Flip rolled modes so that diag(Phi~^T M Phi) >= 0 (eigenvector sign is arbitrary)."""
    s = np.sign(np.einsum("ij,ij->j", Phi_rolled, M @ Phi))
    s[s == 0] = 1.0
    return Phi_rolled * s


def align_pair(Q, M, P):
    """Canonical basis of a rolled mode pair for Eq. (17): the rotation of ``Q`` closest to
    the unrolled pair ``P``.

    A degenerate sin/cos pair is returned by an eigensolver in an arbitrary rotation (it
    depends on the start vector, the BLAS kernels and the thread count), so a single member's
    entry of Eq. (17) is not well defined.  The orthogonal Procrustes rotation
    R = argmax trace((Q R)^T M P) = U V^T, with U S V^T = Q^T M P, aligns the pair with the
    cos/sin basis of the unstressed mode; the block (Q R)^T M P = V S V^T is then symmetric
    and independent of how ``Q`` was rotated or signed.  ``Q``, ``P``: (n_dof, k) with
    mass-normalised columns, k = 1 (N_d = 0) or 2.
    """
    C = Q.T @ (M @ P)
    U, _, Vt = np.linalg.svd(C)
    return Q @ (U @ Vt)


def harmonic_coupling_symmetry(nonzero_pairs, n_max, orders=range(2, 65)):
    """Smallest rotational symmetry order N of a mesh whose harmonic coupling pattern is
    ``nonzero_pairs`` (pairs (i, j), i < j <= n_max, of nonzero off-diagonals of Eq. (16)).

    On a mesh with C_N symmetry, cos(i theta) and cos(j theta) couple iff i = +-j (mod N)
    (selection rule of the cyclic group); returns None when no N <= max(orders) fits.
    """
    want = {tuple(sorted(p)) for p in nonzero_pairs}
    for N in orders:
        got = {(i, j) for i in range(n_max + 1) for j in range(i + 1, n_max + 1)
               if (i - j) % N == 0 or (i + j) % N == 0}
        if got == want:
            return N
    return None


def degenerate_harmonics(N, n_d):
    """Harmonics that stay degenerate sin/cos pairs on a C_N-symmetric mesh: N_d with
    N_d mod N not in {0, N/2} (the others split into two singlets)."""
    return [int(n) for n in n_d if (n % N) != 0 and (2 * n) % N != 0]
