"""Axisymmetric harmonic model: w(r, theta) = W(r) cos(N_d theta), radial Hermite elements.

For one harmonic N_d the Kirchhoff plate energies reduce to radial integrals (the common
factor int cos^2 = pi or 2 pi cancels in every eigenvalue and Rayleigh quotient):

  stiffness    D [W''^2 + k_t^2 + 2 nu W'' k_t + 2 (1-nu) N_d^2 (W'/r - W/r^2)^2] r,
               k_t = W'/r - N_d^2 W/r^2                                   -> [K]
  mass         rho h W^2 r                                                -> [M]
  stress       h [sigma_r W'^2 + sigma_theta N_d^2 W^2 / r^2] r           -> [K^(sigma)], Eq. (3)

discretised by cubic Hermite elements (nodal W, W').  All elements are integrated at once
with Gauss quadrature (the Gaussian stress is sampled exactly at the quadrature points),
and the clamp r = r_f removes W, W' of the first node.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.polynomial.legendre import leggauss

N_GAUSS = 6  # exact for the polynomial parts; the Gaussian stress needs a few more points


@dataclass(frozen=True)
class RadialMesh:
    nodes: np.ndarray  # radii [m], increasing, nodes[0] = r_f (clamped), nodes[-1] = b

    @property
    def n_elements(self) -> int:
        return len(self.nodes) - 1

    @property
    def n_dofs(self) -> int:
        return 2 * len(self.nodes) - 2  # clamp removes W, W' at r_f


def radial_mesh(r_f, b, n_elements, breakpoints=()):
    """Uniform mesh of ``n_elements`` on [r_f, b]; extra ``breakpoints`` become nodes."""
    if n_elements < 1:
        raise ValueError(f"n_elements = {n_elements} must be >= 1")
    if not (0 < r_f < b):
        raise ValueError(f"need 0 < r_f < b, got r_f = {r_f}, b = {b}")
    nodes = np.linspace(r_f, b, int(n_elements) + 1)
    extra = [x for x in breakpoints if r_f < x < b]
    if extra:
        nodes = np.unique(np.concatenate([nodes, extra]))
        # merge slivers that would make the element matrices ill-conditioned
        keep = np.concatenate([[True], np.diff(nodes) > 1e-9 * (b - r_f)])
        nodes = nodes[keep]
    return RadialMesh(nodes)


def quadrature(mesh: RadialMesh, n_gauss=N_GAUSS):
    """Quadrature radii r[e, q], weights w[e, q] (incl. Jacobian) and Hermite basis."""
    xg, wg = leggauss(n_gauss)
    xi = 0.5 * (xg + 1.0)
    L = np.diff(mesh.nodes)[:, None]
    r = mesh.nodes[:-1, None] + L * xi[None, :]
    w = 0.5 * wg[None, :] * L
    one = np.ones_like(L)
    x = xi[None, :] * one
    N = np.stack([1 - 3 * x**2 + 2 * x**3, L * (x - 2 * x**2 + x**3),
                  3 * x**2 - 2 * x**3, L * (-x**2 + x**3)], axis=-1)
    dN = np.stack([(-6 * x + 6 * x**2) / L, 1 - 4 * x + 3 * x**2,
                   (6 * x - 6 * x**2) / L, -2 * x + 3 * x**2], axis=-1)
    d2N = np.stack([(-6 + 12 * x) / L**2, (-4 + 6 * x) / L,
                    (6 - 12 * x) / L**2, (-2 + 6 * x) / L], axis=-1)
    return r, w, N, dN, d2N


def _assemble(mesh: RadialMesh, ke):
    """Scatter element matrices ke[e, 4, 4] into the clamped global matrix (dense)."""
    ne = mesh.n_elements
    n_full = 2 * (ne + 1)
    dofs = 2 * np.arange(ne)[:, None] + np.arange(4)[None, :]
    K = np.zeros((n_full, n_full))
    np.add.at(K, (dofs[:, :, None], dofs[:, None, :]), ke)
    return K[2:, 2:]


def plate_matrices(mesh, n_d, *, D, nu, rho_h, quad=None, d_scale=None):
    """([K], [M]) of harmonic ``n_d`` (Eq. 1 operators, clamped at r_f)."""
    r, w, N, dN, d2N = quad if quad is not None else quadrature(mesh)
    n2 = float(n_d) ** 2
    rr = r[..., None]
    B1 = d2N
    B2 = dN / rr - n2 * N / rr**2
    B3 = np.sqrt(n2) * (dN / rr - N / rr**2)
    Dq = D * w * r
    if d_scale is not None:
        Dq = Dq * d_scale(r)
    ein = lambda A, B: np.einsum("eq,eqi,eqj->eij", Dq, A, B)  # noqa: E731
    ke = ein(B1, B1) + ein(B2, B2) + nu * (ein(B1, B2) + ein(B2, B1)) + 2 * (1 - nu) * ein(B3, B3)
    me = np.einsum("eq,eqi,eqj->eij", rho_h * w * r, N, N)
    return _assemble(mesh, ke), _assemble(mesh, me)


def stress_stiffness(mesh, n_d, sigma_r, sigma_t, h, quad=None):
    """Eq. (3) for the harmonic: [K^(sigma)] from sigma_r, sigma_theta at quadrature points.

    ``sigma_r``/``sigma_t`` are callables of r [m] returning Pa.
    """
    r, w, N, dN, _ = quad if quad is not None else quadrature(mesh)
    sr, st = sigma_r(r), sigma_t(r)
    n2 = float(n_d) ** 2
    ke = (np.einsum("eq,eqi,eqj->eij", h * sr * w * r, dN, dN)
          + np.einsum("eq,eqi,eqj->eij", h * st * n2 * w / r, N, N))
    return _assemble(mesh, ke)


def mode_values(mesh, phi, r):
    """Interpolate a clamped DOF vector ``phi`` (W, W' per node) to radii ``r``."""
    full = np.concatenate([[0.0, 0.0], phi])
    r = np.asarray(r, float)
    e = np.clip(np.searchsorted(mesh.nodes, r, side="right") - 1, 0, mesh.n_elements - 1)
    L = mesh.nodes[e + 1] - mesh.nodes[e]
    x = (r - mesh.nodes[e]) / L
    Nb = np.stack([1 - 3 * x**2 + 2 * x**3, L * (x - 2 * x**2 + x**3),
                   3 * x**2 - 2 * x**3, L * (-x**2 + x**3)], axis=-1)
    dofs = 2 * e[:, None] + np.arange(4)[None, :]
    return np.sum(Nb * full[dofs], axis=-1)
