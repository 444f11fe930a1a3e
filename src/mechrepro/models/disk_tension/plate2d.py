"""2-D plate model (scikit-fem): quintic Argyris bending triangles and a plane-stress P2
residual stress on the same mesh, so slotted blades are handled like the plain disk.  Modes
are labelled by MAC against the unrolled sin/cos pair subspaces; Eq. (9) of a pair is the
mean eigenvalue of its 2x2 block of Phi^T K^(sigma) Phi (degenerate first-order perturbation).
"""
from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from skfem import Basis, BilinearForm, ElementTriArgyris, ElementTriP2, ElementVector, LinearForm, MeshTri, asm
from skfem.element.discrete_field import DiscreteField
from skfem.helpers import dd, ddot, div, grad, sym_grad, trace

from mechrepro.errors import Refusal

from .modal import align_pair, once

INTORDER = 8  # mass of quintics needs 10 for exactness; 8 changes f by < 1e-6 and is faster


class Argyris(ElementTriArgyris):
    """scikit-fem's Argyris triangle with its 21 global basis functions built in one batched
    product with the inverse Vandermonde matrix (scikit-fem re-evaluates the monomials per
    function), cached for the other 20 calls; equal to round-off."""

    _gcache = None

    def gbasis(self, mapping, X, i, tind=None):
        c = self._gcache
        if c is None or c[0] is not mapping or c[1] is not X or c[2] is not tind:
            self._gcache = c = (mapping, X, tind, self._gbasis_all(mapping, X, tind))
        return c[3][i]

    def _gbasis_all(self, mapping, X, tind):
        if tind is None:
            tind = np.arange(mapping.mesh.t.shape[1])
        if self.V is None:
            self._pbasis_init(self.maxdeg, self.dim, self.derivatives, self.tensorial_basis)
            self.V = np.linalg.inv(self._eval_dofs(mapping.mesh))
        V = self.V[tind]                                     # (element, monomial, function)
        x = mapping.F(X, tind=tind)
        N = len(self._pbasis[()])
        shape = x[0].shape                                   # (element, point)
        U = []
        for k in range(self.derivatives + 1):
            Uk = np.empty((N,) + (self.dim,) * k + shape)
            for diff in itertools.product(*((list(range(self.dim)),) * k)):
                P = np.stack([np.broadcast_to(self._pbasis[diff][m](*x), shape)
                              for m in range(N)], axis=-1)   # (element, point, monomial)
                Uk[(slice(None),) + diff] = np.matmul(P, V).transpose(2, 0, 1)
            U.append(Uk)
        return [(DiscreteField(value=U[0][i], grad=U[1][i], hess=U[2][i]),) for i in range(N)]


def symmetric_lu(A):
    """Sparse LU in SuperLU's symmetric mode (less fill); a small pivot raises."""
    return spla.splu(sp.csc_matrix(A), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                     options=dict(SymmetricMode=True))


@dataclass(frozen=True)
class Slots:
    """Radial expansion slots cut from the outer edge (constant angular width)."""
    count: int
    depth: float  # [m] from the outer edge inward
    width: float  # [m] at the outer edge


def polar_mesh(r_f, b, n_rings, n_sectors, slots: Slots | None = None,
               equal_area: bool = True) -> MeshTri:
    """Structured ring x sector mesh of the annulus r_f..b, minus the slot cells (n_rings >= 1,
    n_sectors >= 8 and 0 < r_f < b are the config's refine limits and cross_checks)."""
    # geometric ring spacing keeps the cell aspect ratio uniform (cells near the clamp,
    # where the low-N_d curvature lives, are as fine tangentially as radially)
    r = r_f * (b / r_f) ** np.linspace(0.0, 1.0, n_rings + 1)
    th = np.linspace(0, 2 * np.pi, n_sectors, endpoint=False)
    if slots is not None and slots.count > 0:
        if not (0 < slots.depth < b - r_f):
            raise Refusal(f"slot depth {slots.depth} must lie in (0, b - r_f)")
        r0 = b - slots.depth
        # move the nearest ring onto the slot root instead of adding a thin ring
        r[np.argmin(np.abs(r[1:-1] - r0)) + 1] = r0 if n_rings > 1 else r[1]
        if n_rings == 1:
            r = np.array([r_f, r0, b])
        half = slots.width / (2 * b)
        centres = 2 * np.pi * (np.arange(slots.count) + 0.5) / slots.count
        edges = np.concatenate([centres - half, centres + half]) % (2 * np.pi)
        dth = 2 * np.pi / n_sectors
        gap = np.abs((th[:, None] - edges[None, :] + np.pi) % (2 * np.pi) - np.pi).min(axis=1)
        th = np.sort(np.concatenate([th[gap > 0.5 * dth], edges]))
    nr, nt = len(r), len(th)
    # equal-area polygons: the ring of n_sectors chords encloses the area of its circle,
    # which removes the leading O(dtheta^2) geometric error of an inscribed polygon
    dth = 2 * np.pi / n_sectors
    r = r * np.sqrt(dth / np.sin(dth)) if equal_area else r
    R, TH = np.meshgrid(r, th, indexing="ij")
    p = np.stack([(R * np.cos(TH)).ravel(), (R * np.sin(TH)).ravel()])
    i, j = np.meshgrid(np.arange(nr - 1), np.arange(nt), indexing="ij")
    i, j = i.ravel(), j.ravel()
    jn = (j + 1) % nt
    n00, n10, n11, n01 = i * nt + j, (i + 1) * nt + j, (i + 1) * nt + jn, i * nt + jn
    keep = np.ones(len(i), bool)
    if slots is not None and slots.count > 0:
        tc = (th[j] + ((th[jn] - th[j]) % (2 * np.pi)) / 2) % (2 * np.pi)
        rc = 0.5 * (r[i] + r[i + 1])
        dist = np.abs((tc[:, None] - centres[None, :] + np.pi) % (2 * np.pi) - np.pi).min(axis=1)
        keep = ~((dist < half) & (rc > b - slots.depth))
    t = np.concatenate([np.stack([n00[keep], n10[keep], n11[keep]]),
                        np.stack([n00[keep], n11[keep], n01[keep]])], axis=1)
    used = np.unique(t)
    remap = -np.ones(p.shape[1], int)
    remap[used] = np.arange(len(used))
    return MeshTri(p[:, used], remap[t])


def with_inner_disk(mesh: MeshTri) -> MeshTri:
    """The annulus mesh plus a mesh of the clamped core r < r_f (rings + centre fan), the
    annulus first with unchanged indices: a field solved on the whole disk (``free_disk``) is
    then evaluated at exactly the bending quadrature points."""
    rad = np.hypot(*mesh.p)
    r0 = rad.min()
    ring = np.nonzero(rad < r0 * (1 + 1e-9))[0]
    ring = ring[np.argsort(np.arctan2(mesh.p[1, ring], mesh.p[0, ring]))]
    th = np.arctan2(mesh.p[1, ring], mesh.p[0, ring])
    nt = len(ring)
    # ring spacing of the core close to the annulus's first ring width (cells of similar size)
    dr = np.sort(np.unique(np.round(rad, 12)))[1] - r0
    k = int(np.clip(np.ceil(r0 / dr), 2, 12))
    radii = r0 * np.arange(k - 1, 0, -1) / k
    base = mesh.p.shape[1]
    pts = [np.stack([rr * np.cos(th), rr * np.sin(th)]) for rr in radii]
    centre = base + nt * len(radii)
    p = np.hstack([mesh.p] + pts + [np.zeros((2, 1))])
    rings = [ring] + [base + i * nt + np.arange(nt) for i in range(len(radii))]
    tri = []
    j, jn = np.arange(nt), (np.arange(nt) + 1) % nt
    for outer, inner in zip(rings[:-1], rings[1:]):
        tri += [np.stack([outer[j], inner[j], inner[jn]]), np.stack([outer[j], inner[jn], outer[jn]])]
    tri.append(np.stack([rings[-1][j], np.full(nt, centre), rings[-1][jn]]))
    return MeshTri(p, np.hstack([mesh.t] + tri))


@BilinearForm
def _bending(u, v, w):
    # D [(1 - nu) dd(u):dd(v) + nu lap(u) lap(v)]
    return w.D * ((1 - w.nu) * ddot(dd(u), dd(v)) + w.nu * trace(dd(u)) * trace(dd(v)))


@BilinearForm
def _mass(u, v, w):
    return w.rho_h * u * v


@BilinearForm
def _geometric(u, v, w):
    # Eq. (3): h grad(u)^T sigma grad(v), sigma the in-plane residual stress; the in-plane
    # (u, v) rows of Eq. (3) are dropped: a flat plate's bending does not couple to them
    gu, gv = grad(u), grad(v)
    return w.h * (w.sxx * gu[0] * gv[0] + w.sxy * (gu[0] * gv[1] + gu[1] * gv[0])
                  + w.syy * gu[1] * gv[1])


@BilinearForm
def _membrane(u, v, w):
    eu, ev = sym_grad(u), sym_grad(v)
    return w.C * ((1 - w.nu) * ddot(eu, ev) + w.nu * trace(eu) * trace(ev))


@LinearForm
def _thermal_load(v, w):
    # plane-stress thermal stress E alpha T / (1 - nu) * I against eps(v)
    return w.EaT * div(v)


class PlateDisk:
    """Clamped (r <= r_f) disk or sawblade; fundamental of each N_d by MAC labelling."""

    #: N_d >= 1 are sin/cos pairs (both members after rolling: ``rolled_pairs``)
    degenerate_pairs = True

    def __init__(self, *, r_f, b, h, E, nu, rho, n_d, n_rings, n_sectors,
                 slots: Slots | None = None, extra_modes=4, seed=0):
        self.r_f, self.b, self.h, self.E, self.nu, self.rho = r_f, b, h, E, nu, rho
        self.n_d = np.asarray(n_d, int)
        self.mesh = polar_mesh(r_f, b, n_rings, n_sectors, slots)
        self.basis = Basis(self.mesh, Argyris(), intorder=INTORDER)
        D = E * h**3 / (12 * (1 - nu**2))
        self.K = asm(_bending, self.basis, D=D, nu=nu)
        self.M = asm(_mass, self.basis, rho_h=rho * h)
        rad = np.hypot(*self.mesh.p)
        r_in = rad.min()
        self._inner = self.mesh.facets_satisfying(lambda x: np.hypot(*x) < r_in * (1 + 1e-9))
        fixed = self.basis.get_dofs(self._inner).all(["u", "u_x", "u_y", "u_n"])
        self.free = np.setdiff1d(np.arange(self.basis.N), fixed)
        self.n_modes = int(2 * self.n_d.max() + 1 + extra_modes)
        outer = np.nonzero(rad > rad.max() * (1 - 1e-9))[0]
        self.ring_theta = np.arctan2(*self.mesh.p[::-1, outer])
        self.ring_dofs = self.basis.nodal_dofs[0, outer]
        self._inplane, self._memo = None, {}   # _memo: results per K^(sigma) (modal.once)
        # ARPACK's start vector, seeded: the rotation of each degenerate pair it returns
        # (the raw Eq. 17 entries) is then reproducible
        self._v0 = np.random.default_rng(seed).standard_normal(len(self.free))

    # -- helpers -----------------------------------------------------------------
    def _sub(self, A):
        return A[self.free][:, self.free]

    def _eigs(self, K, k, shift):
        A, M = self._sub(K), self._sub(self.M)
        lu = symmetric_lu(A - shift * M if shift else A)   # (A - shift M)^-1: ARPACK's shift-invert
        lam, vec = spla.eigsh(A, k=k, M=M, sigma=shift, which="LM", v0=self._v0,
                              OPinv=spla.LinearOperator(A.shape, matvec=lu.solve, dtype=float))
        order = np.argsort(lam)
        full = np.zeros((self.basis.N, k))
        full[self.free] = vec[:, order]
        return lam[order], full

    def harmonic_content(self, Phi):
        """(dominant N_d, cos/sin coefficients) of each mode on the outer edge."""
        nmax = int(self.n_d.max()) + 2
        th = self.ring_theta
        cols = [np.ones_like(th)]
        for n in range(1, nmax + 1):
            cols += [np.cos(n * th), np.sin(n * th)]
        A = np.stack(cols, axis=1)
        coef = np.linalg.lstsq(A, Phi[self.ring_dofs], rcond=None)[0]
        energy = np.vstack([coef[0] ** 2 * 2] + [coef[2 * n - 1] ** 2 + coef[2 * n] ** 2
                                                 for n in range(1, nmax + 1)])
        return energy.argmax(axis=0), coef

    # -- Eq. (6): unrolled modes ---------------------------------------------------
    def unrolled(self):
        """omega^2 of the fundamental of each N_d; pairs rotated to cos/sin members."""
        # the unstressed plate is positive definite: shift 0.  Repeated calls (timing) must
        # give the same modes, so no shift may depend on a previous call.
        lam, Phi = self._eigs(self.K, self.n_modes, 0.0)
        self._shift_scale = lam.max()
        nd, coef = self.harmonic_content(Phi)
        self.omega2, self.pair = {}, {}
        for n in self.n_d:
            idx = np.nonzero(nd == n)[0]
            need = 1 if n == 0 else 2
            if len(idx) < need:
                raise RuntimeError(f"plate2d: N_d = {n} not among the lowest {self.n_modes} "
                                   f"modes (labels {nd.tolist()}); increase extra_modes")
            idx = idx[:need]
            P = Phi[:, idx]
            if n > 0:
                # rotate the pair so that member 0 has no sin(n theta) content on the edge
                s = coef[2 * n, idx]
                a = np.array([s[1], -s[0]])
                c0 = P @ a
                c0 /= np.sqrt(c0 @ (self.M @ c0))
                c1 = P[:, 1] - (c0 @ (self.M @ P[:, 1])) * c0 if abs(s[0]) < abs(s[1]) else \
                    P[:, 0] - (c0 @ (self.M @ P[:, 0])) * c0
                c1 /= np.sqrt(c1 @ (self.M @ c1))
                P = np.stack([c0, c1], axis=1)
            self.pair[n] = P
            self.omega2[n] = lam[idx]
        return np.array([self.omega2[n].mean() for n in self.n_d])

    # -- thermal analogy: plane stress ---------------------------------------------
    def _inplane_problem(self, inplane_bc):
        """P2 plane-stress basis, free DOFs and factorised stiffness for ``inplane_bc``
        (clamped or free_disk, the config's enum)."""
        if inplane_bc == "clamped":
            ub = self.basis.with_element(ElementVector(ElementTriP2()))
            fixed = ub.get_dofs(self._inner).all()
        else:
            full = with_inner_disk(self.mesh)
            ub = Basis(full, ElementVector(ElementTriP2()), intorder=INTORDER)
            centre = int(np.argmin(np.hypot(*full.p)))
            ring = np.hypot(*full.p[:, :self.mesh.p.shape[1]])
            anchor = int(np.argmin(np.abs(full.p[1, :self.mesh.p.shape[1]])
                                   + (ring - ring.min())))
            fixed = np.array([ub.nodal_dofs[0, centre], ub.nodal_dofs[1, centre],
                              ub.nodal_dofs[1, anchor]])
        Kin = asm(_membrane, ub, C=self.E / (1 - self.nu**2), nu=self.nu).tocsr()
        free = np.setdiff1d(np.arange(ub.N), fixed)
        return ub, free, symmetric_lu(Kin[free][:, free])

    def residual_stress(self, temperature, alpha, inplane_bc="clamped"):
        """Plane-stress field of the Eq. (4) temperature: (sxx, sxy, syy) [Pa]."""
        if self._inplane is None or self._inplane[0] != inplane_bc:
            self._inplane = (inplane_bc,) + self._inplane_problem(inplane_bc)
        _, ub, free, lu = self._inplane
        x = np.asarray(ub.global_coordinates())
        T = temperature(np.hypot(x[0], x[1]))
        EaT = self.E * alpha * T / (1 - self.nu)
        f = asm(_thermal_load, ub, EaT=EaT)
        u = np.zeros(ub.N)
        u[free] = lu.solve(f[free])
        ne = self.mesh.t.shape[1]
        EaT = EaT[:ne]
        eps = sym_grad(ub.interpolate(u))[:, :, :ne]
        c = self.E / (1 - self.nu**2)
        tr = eps[0, 0] + eps[1, 1]
        sxx = c * ((1 - self.nu) * eps[0, 0] + self.nu * tr) - EaT
        syy = c * ((1 - self.nu) * eps[1, 1] + self.nu * tr) - EaT
        sxy = c * (1 - self.nu) * eps[0, 1]
        return sxx, sxy, syy

    def polar_stress(self, sigma):
        """(r, sigma_r, sigma_theta) at the bending quadrature points, flattened."""
        sxx, sxy, syy = sigma
        x = np.asarray(self.basis.global_coordinates())
        th = np.arctan2(x[1], x[0])
        c, s = np.cos(th), np.sin(th)
        sr = sxx * c * c + 2 * sxy * s * c + syy * s * s
        st = sxx * s * s - 2 * sxy * s * c + syy * c * c
        return np.hypot(x[0], x[1]).ravel(), sr.ravel(), st.ravel()

    def uniform_stress(self, sigma0):
        """(sxx, sxy, syy) of a uniform isotropic stress ``sigma0`` [Pa]."""
        shape = np.asarray(self.basis.global_coordinates()).shape[1:]
        s = np.full(shape, float(sigma0))
        return s, np.zeros(shape), s.copy()

    def stress_stiffness(self, sigma):
        """[K^(sigma)], Eq. (3), of the stress (sxx, sxy, syy) at the quadrature points."""
        sxx, sxy, syy = sigma
        return asm(_geometric, self.basis, h=self.h, sxx=sxx, sxy=sxy, syy=syy)

    # -- Eq. (5), Eq. (9), Eqs. (16)-(17) ------------------------------------------
    def rolled(self, Ks):
        """omega~^2 per N_d (the pair mean; both members in ``rolled_pairs``), labelled by
        subspace MAC against the unrolled modes; solved once per K^(sigma) object (kept with
        its result, so that its id cannot be reused while the model lives)."""
        out, self.rolled_modes, self.rolled_pairs = once(self._memo, "rolled", Ks, self._rolled)
        return out, self.rolled_modes

    def _rolled(self, Ks):
        # a compressive K^(sigma) may make K + K^(sigma) indefinite: shift below zero by a
        # tenth of the highest unrolled eigenvalue computed (fixed once by ``unrolled``)
        lam, Phi = self._eigs(self.K + Ks, self.n_modes, -0.1 * float(self._shift_scale))
        MPhi = self.M @ Phi
        out, modes, both = [], {}, {}
        taken = np.zeros(len(lam), bool)
        for n in self.n_d:
            mac = np.sum((self.pair[n].T @ MPhi) ** 2, axis=0)  # share in the unrolled subspace
            mac[taken] = -1
            idx = np.sort(np.argsort(mac)[::-1][:1 if n == 0 else 2])
            taken[idx] = True
            both[n], modes[n] = lam[idx], Phi[:, idx]
            out.append(lam[idx].mean())
        return np.array(out), modes, both

    def eq9(self, Ks):
        """Eq. (9) per N_d; for a pair, the mean of the eigenvalues of its 2x2 block
        Phi^T K^(sigma) Phi (degenerate first-order perturbation): half its trace."""
        return np.array([np.trace(self.pair[n].T @ (Ks @ self.pair[n])) / self.pair[n].shape[1]
                         for n in self.n_d])

    def modal_matrices(self, Ks):
        """Eqs. (16)-(17), each rolled pair rotated onto its unrolled cos/sin basis first."""
        Phi = np.stack([self.pair[n][:, 0] for n in self.n_d], axis=1)   # the cos members
        k_hat = Phi.T @ (Ks @ Phi)
        self.rolled(Ks)
        canon = []
        for n in self.n_d:
            P = self.pair[n][:, :1] if n == 0 else self.pair[n]
            canon.append(align_pair(self.rolled_modes[n], self.M, P)[:, 0])
        m_hat = np.stack(canon, axis=1).T @ (self.M @ Phi)
        return k_hat, m_hat
