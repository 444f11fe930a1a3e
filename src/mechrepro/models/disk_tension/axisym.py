"""Axisymmetric harmonic model: w(r, theta) = W(r) cos(N_d theta), radial Hermite elements.

For one harmonic N_d the Kirchhoff plate energies reduce to radial integrals (the common
factor int cos^2 cancels in every eigenvalue and Rayleigh quotient):

  stiffness    D [W''^2 + k_t^2 + 2 nu W'' k_t + 2 (1-nu) N_d^2 (W'/r - W/r^2)^2] r,
               k_t = W'/r - N_d^2 W/r^2                                   -> [K]
  mass         rho h W^2 r                                                -> [M]
  stress       h [sigma_r W'^2 + sigma_theta N_d^2 W^2 / r^2] r           -> [K^(sigma)], Eq. (3)

Only the w rows of Eq. (3)'s shell stress block enter (a flat plate's in-plane stress couples
bending only through grad(w)^T sigma grad(w)).  Cubic Hermite elements carry W and ell W'
(ell the mean element length: one unit keeps [K], [M] well conditioned); clamped at r_f.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.polynomial.legendre import leggauss

from .modal import align_signs, critical_load_factor, eigen, eq9_delta_omega2, once

#: Gauss-Legendre points and weights on [-1, 1]: 6, exact for the polynomial parts (the
#: Gaussian stress needs a few more points than they do)
XG, WG = leggauss(6)
BANDWIDTH = 3  # half-bandwidth of [K], [M]: element DOFs W, ell W' of two neighbouring nodes


@dataclass(frozen=True)
class RadialMesh:
    nodes: np.ndarray  # radii [m], increasing, nodes[0] = r_f (clamped), nodes[-1] = b

    @property
    def ell(self) -> float:
        """Scale of the slope DOF (mean element length) [m]."""
        return float(self.nodes[-1] - self.nodes[0]) / self.n_elements

    @property
    def n_elements(self) -> int:
        return len(self.nodes) - 1



def radial_mesh(r_f, b, n_elements, breakpoints=()):
    """Uniform mesh of ``n_elements`` (>= 1) on [r_f, b] (0 < r_f < b: the config refuses the
    rest at load); extra ``breakpoints`` become nodes."""
    nodes = np.linspace(r_f, b, int(n_elements) + 1)
    ell = (b - r_f) / n_elements
    for x in breakpoints:
        if not r_f < x < b:
            continue
        # move the nearest interior node onto the breakpoint instead of adding a sliver
        # element (slivers wreck the conditioning of [K])
        i = int(np.argmin(np.abs(nodes - x)))
        if abs(nodes[i] - x) < 0.5 * ell and 0 < i < len(nodes) - 1:
            nodes[i] = x
        else:
            nodes = np.sort(np.append(nodes, x))
    return RadialMesh(nodes)


def quadrature(mesh: RadialMesh):
    """Quadrature radii r[e, q], weights w[e, q] (incl. Jacobian) and Hermite basis."""
    xi = 0.5 * (XG + 1.0)
    L = np.diff(mesh.nodes)[:, None]
    r = mesh.nodes[:-1, None] + L * xi[None, :]
    w = 0.5 * WG[None, :] * L
    x = xi[None, :] * np.ones_like(L)
    g = L / mesh.ell  # slope DOFs are ell W'
    N = np.stack([1 - 3 * x**2 + 2 * x**3, g * (x - 2 * x**2 + x**3),
                  3 * x**2 - 2 * x**3, g * (-x**2 + x**3)], axis=-1)
    dN = np.stack([(-6 * x + 6 * x**2) / L, g * (1 - 4 * x + 3 * x**2) / L,
                   (6 * x - 6 * x**2) / L, g * (-2 * x + 3 * x**2) / L], axis=-1)
    d2N = np.stack([(-6 + 12 * x) / L**2, g * (-4 + 6 * x) / L**2,
                    (6 - 12 * x) / L**2, g * (-2 + 6 * x) / L**2], axis=-1)
    return r, w, N, dN, d2N


def _assemble(mesh: RadialMesh, ke):
    """Scatter element matrices ke[e, 4, 4] into the clamped global matrix (dense)."""
    ne = mesh.n_elements
    n_full = 2 * (ne + 1)
    dofs = 2 * np.arange(ne)[:, None] + np.arange(4)[None, :]
    K = np.zeros((n_full, n_full))
    np.add.at(K, (dofs[:, :, None], dofs[:, None, :]), ke)
    return K[2:, 2:]


def mass_matrix(mesh, *, rho_h, quad=None):
    """[M] (Eq. 1 operator, clamped at r_f): the same for every harmonic N_d."""
    r, w, N = (quad if quad is not None else quadrature(mesh))[:3]
    return _assemble(mesh, np.einsum("eq,eqi,eqj->eij", rho_h * w * r, N, N))


def bending_matrix(mesh, n_d, *, D, nu, quad=None, d_scale=None):
    """[K] of harmonic ``n_d`` (Eq. 1); ``d_scale(r)`` multiplies D."""
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
    return _assemble(mesh, ke)


def stress_stiffness(mesh, n_d, sr, st, h, quad=None):
    """Eq. (3) for the harmonic: [K^(sigma)] from sigma_r, sigma_theta [Pa] at the
    quadrature points (``sr``, ``st``: arrays shaped like the quadrature radii)."""
    r, w, N, dN, _ = quad if quad is not None else quadrature(mesh)
    n2 = float(n_d) ** 2
    ke = (np.einsum("eq,eqi,eqj->eij", h * sr * w * r, dN, dN)
          + np.einsum("eq,eqi,eqj->eij", h * st * n2 * w / r, N, N))
    return _assemble(mesh, ke)


class AxisymDisk:
    """The clamped disk discretised per harmonic (one dense block per N_d)."""

    def __init__(self, *, r_f, b, h, E, nu, rho, n_d, n_elements):
        self.mesh = radial_mesh(r_f, b, n_elements)
        self.quad = quadrature(self.mesh)
        self.h, self.n_d = h, np.asarray(n_d, int)
        D = E * h**3 / (12 * (1 - nu**2))
        # [M] has no N_d in it: one matrix, shared (read only) by every harmonic
        M = mass_matrix(self.mesh, rho_h=rho * h, quad=self.quad)
        self.K, self.M = {}, {}
        # results per K^(sigma) object (the analyses share the r_c of one run: Tables 1-2 and
        # the critical load re-read the eigen effect's solves instead of repeating them)
        self._memo = {}
        for n in self.n_d:
            self.K[n] = bending_matrix(self.mesh, n, D=D, nu=nu, quad=self.quad)
            self.M[n] = M

    def unrolled(self):
        """omega^2 and mass-normalised mode of the fundamental of each N_d, Eq. (6)."""
        self.omega2, self.phi = {}, {}
        for n in self.n_d:
            lam, phi = eigen(self.K[n], self.M[n], 1, BANDWIDTH)
            self.omega2[n], self.phi[n] = lam[0], phi[:, 0]
        return np.array([self.omega2[n] for n in self.n_d])

    @staticmethod
    def uniform_stress(sigma0):
        """sigma_r = sigma_theta = ``sigma0`` [Pa] everywhere (the exact stressed reference)."""
        return (lambda r: np.full_like(r, sigma0, dtype=float),
                lambda r: np.full_like(r, sigma0, dtype=float))

    def stress_stiffness(self, sigma):
        """[K^(sigma)] of every harmonic, Eq. (3); ``sigma`` = (sigma_r(r), sigma_theta(r)),
        callables of r [m] returning Pa, evaluated once for all harmonics."""
        r = self.quad[0]
        sr, st = sigma[0](r), sigma[1](r)
        return {n: stress_stiffness(self.mesh, n, sr, st, self.h, quad=self.quad)
                for n in self.n_d}

    def rolled(self, Ks):
        """Eq. (5) per harmonic: omega~^2 and mode of the fundamental."""
        return once(self._memo, "rolled", Ks, self._rolled)

    def _rolled(self, Ks):
        out, modes = [], {}
        for n in self.n_d:
            lam, phi = eigen(self.K[n] + Ks[n], self.M[n], 1, BANDWIDTH)
            out.append(lam[0])
            modes[n] = phi[:, 0]
        return np.array(out), modes

    def eq9(self, Ks):
        return np.array([eq9_delta_omega2(self.phi[n], Ks[n], self.M[n])[0] for n in self.n_d])

    def critical_load(self, Ks):
        return once(self._memo, "critical_load", Ks, lambda Ks: np.array(
            [critical_load_factor(self.K[n], Ks[n]) for n in self.n_d]))

    def modal_matrices(self, Ks):
        """Eqs. (16)-(17) over N_d: harmonics are orthogonal, so off-diagonals are exactly 0
        (the paper's small off-diagonal entries come from its non-axisymmetric mesh)."""
        col = {n: self.phi[n][:, None] for n in self.n_d}
        k_hat = np.diag([(col[n].T @ Ks[n] @ col[n])[0, 0] for n in self.n_d])
        return k_hat, np.diag(self.m_hat_diag(Ks))

    def m_hat_diag(self, Ks, scale=1.0):
        """Diagonal of Eq. (17) with K^(sigma) scaled by ``scale`` (mode change vs stress)."""
        _, modes = self.rolled(Ks if scale == 1.0 else {n: scale * Ks[n] for n in self.n_d})
        return np.array([align_signs(modes[n][:, None], self.M[n], self.phi[n][:, None])[:, 0]
                         @ self.M[n] @ self.phi[n] for n in self.n_d])

    def sensitivity(self, *, r_a, width, increase, E, nu, rho):
        """Fig. 7: Delta f [Hz] of each N_d for D raised by ``increase`` in |r - r_a| <= width/2."""
        D = E * self.h**3 / (12 * (1 - nu**2))
        r_f, b = self.mesh.nodes[0], self.mesh.nodes[-1]
        out = np.full((len(r_a), len(self.n_d)), np.nan)
        for i, ra in enumerate(r_a):
            lo, hi = ra - width / 2, ra + width / 2
            mesh = radial_mesh(r_f, b, self.mesh.n_elements, breakpoints=(lo, hi))
            quad = quadrature(mesh)
            scale = lambda r: 1.0 + increase * ((r >= lo) & (r <= hi))  # noqa: E731
            M = mass_matrix(mesh, rho_h=rho * self.h, quad=quad)
            for j, n in enumerate(self.n_d):
                K0 = bending_matrix(mesh, n, D=D, nu=nu, quad=quad)
                K1 = bending_matrix(mesh, n, D=D, nu=nu, quad=quad, d_scale=scale)
                w0 = eigen(K0, M, 1, BANDWIDTH)[0][0]
                w1 = eigen(K1, M, 1, BANDWIDTH)[0][0]
                out[i, j] = (np.sqrt(w1) - np.sqrt(w0)) / (2 * np.pi)
        return out
