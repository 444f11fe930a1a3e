"""Compiled RK4 of the Galerkin model (numba, cached on disk): :func:`.galerkin.rk4_tabulated`
with :meth:`.galerkin.GalerkinModel.rhs_values` inlined.

The state is tiny (2 (n_t + n_l) <= ~30 numbers, n_q ~ 40 quadrature points), so the numpy
loop spends its time in the overhead of ~30 small array calls per right-hand side (~50 us);
compiled, one right-hand side is ~1000 floating-point operations (~1 us).  The arithmetic
is the one of ``rhs_values`` term by term (the linear matrices of the model, the same
quadrature for the coupling terms); only the summation order of the small matrix-vector
products differs, so both loops agree to round-off.  Compiled without ``fastmath``: no
contraction into FMA, no reassociation, no libm call, so the result does not depend on
the CPU the kernel is compiled for (``NUMBA_CPU_NAME``).

Compiled by :func:`mechrepro.compiled.jit` (numpy's error model: a division by zero gives
inf, which the y_cap check refuses; the disk cache keyed on the package's sources), lazily
(numba costs ~0.3 s to import and the cached kernel ~0.2 s to load): the choice is made by the size of the integration alone (:func:`worth_it`), never by what ran
before in the process.
"""
from __future__ import annotations

import numpy as np

from mechrepro.compiled import available, jit
from .errors import DivergenceError

# "auto" uses the compiled loop from this many RK4 steps on: the numpy loop costs ~0.2 ms per
# step, loading numba and the cached kernel ~0.5 s per process
MIN_STEPS = 3000
_KERNEL = None


def worth_it(n_steps: int) -> bool:
    """Whether ``kernel="auto"`` should run the compiled loop for this many RK4 steps."""
    return n_steps >= MIN_STEPS


def _build():
    # a module global, not a closure variable of rk4: numba keys its disk cache on the
    # closure's objects, so a helper defined here as a local was compiled again in every
    # process (~2 s)
    global matvec, project_add

    @jit(inline="always")
    def matvec(At, x, acc, n_in, n):
        """acc = A x from A's transpose At (n_in, n): each acc[r] sums A[r, j] x[j] over
        j = 0, 1, ... from 0.0, the order of a dot product per row, with r innermost:
        independent lanes that vectorise without reordering any sum (bit-identical)."""
        for r in range(n):
            acc[r] = 0.0
        for j in range(n_in):
            xj = x[j]
            for r in range(n):
                acc[r] += At[j, r] * xj

    @jit(inline="always")
    def project_add(Wt, f, out, acc, nq, n):
        """out += Wt^T f over the quadrature points: one independent sum per mode (the
        mode innermost), added to ``out`` after the sum, as the numpy path orders it."""
        for r in range(n):
            acc[r] = 0.0
        for q in range(nq):
            for r in range(n):
                acc[r] += Wt[q, r] * f[q]
        for r in range(n):
            out[r] += acc[r]

    @jit
    def rk4(y0, dt, n_steps, F, record_every, y_cap, nt, nl, B, SWt, Sx, Sxx, CWt, Cx, Cxx,
            a0, a1, GtT, KtT, GlT, KlT, MtiT, MliT, Cend0, CendL, Sx0, SxL, L, m, c, c_d, EA,
            coupling, out_y):
        """F: (5, n_steps, 4) = g, h, g', h', P_t at the four stage times of every step;
        the model's matrices are passed transposed (``GtT`` = Gt^T, ...: :func:`matvec`)."""
        n = y0.size
        nq = Sx.shape[1]
        y = y0.copy()
        K = np.empty((4, n))               # the stages k1..k4
        ys = np.empty(n)                   # the state a stage is evaluated at
        ft = np.empty(nt); fl = np.empty(nl); acc = np.empty(max(nt, nl))
        m1 = np.empty(max(nt, nl)); m2 = np.empty(max(nt, nl))
        fq = np.empty(nq); fc = np.empty(nq)
        u2x = np.empty(nq); u2xx = np.empty(nq); u1x = np.empty(nq); u1xx = np.empty(nq)
        for j in range(n):
            out_y[0, j] = y[j]
        irec = 1
        h2 = dt / 2
        h6 = dt / 6
        for i in range(n_steps):
            for st in range(4):
                # the state of this stage: y, y + dt/2 k1, y + dt/2 k2, y + dt k3
                if st == 0:
                    for j in range(n):
                        ys[j] = y[j]
                else:
                    hs = dt if st == 3 else h2
                    for j in range(n):
                        ys[j] = y[j] + hs * K[st - 1, j]
                g = F[0, i, st]
                h = F[1, i, st]
                gd = F[2, i, st]
                hd = F[3, i, st]
                Pt = F[4, i, st]
                out = K[st]
                # ---- GalerkinModel.rhs_values(ys, g, h, gd, hd, Pt) ----
                # dphi = z - B (g', h'); dpsi
                for r in range(nt):
                    out[r] = ys[nt + nl + r] - (B[r, 0] * gd + B[r, 1] * hd)
                for r in range(nl):
                    out[nt + r] = ys[2 * nt + nl + r]
                ub_x = (h - g) / L
                ub_xt = (hd - gd) / L
                matvec(GtT, out, m1, nt, nt)
                matvec(KtT, ys, m2, nt, nt)
                for r in range(nt):
                    ft[r] = -m1[r] - m2[r]
                matvec(GlT, out[nt:], m1, nl, nl)
                matvec(KlT, ys[nt:], m2, nl, nl)
                for r in range(nl):
                    fl[r] = -m1[r] - m2[r]
                # end-motion loads without its acceleration (gyroscopic and damping) and the
                # coupling terms at the quadrature points (the points innermost: independent
                # lanes, vectorised without reordering any sum)
                gyr = 2 * m * c * ub_xt
                cub = c * ub_x
                for q in range(nq):
                    fq[q] = -(gyr + c_d * ((a0[q] * gd + a1[q] * hd) + cub))
                if coupling:
                    for q in range(nq):
                        u2x[q] = 0.0
                        u2xx[q] = 0.0
                        u1x[q] = 0.0
                        u1xx[q] = 0.0
                    for j in range(nt):
                        yj = ys[j]
                        for q in range(nq):
                            u2x[q] += yj * Sx[j, q]
                            u2xx[q] += yj * Sxx[j, q]
                    for j in range(nl):
                        yj = ys[nt + j]
                        for q in range(nq):
                            u1x[q] += yj * Cx[j, q]
                            u1xx[q] += yj * Cxx[j, q]
                    for q in range(nq):
                        ax = u2x[q] + ub_x
                        bx = u2xx[q]
                        fq[q] += EA * (u1xx[q] * ax + u1x[q] * bx + 1.5 * ax * ax * bx)
                        fc[q] = EA * ax * bx
                    project_add(CWt, fc, fl, acc, nq, nl)
                # the projections: one independent sum per mode (the mode innermost)
                project_add(SWt, fq, ft, acc, nq, nt)
                ex0 = 0.0
                exL = 0.0
                if coupling:
                    s0 = 0.0
                    sL = 0.0
                    for j in range(nt):
                        s0 += ys[j] * Sx0[j]
                        sL += ys[j] * SxL[j]
                    ex0 = 0.5 * EA * (s0 + ub_x) ** 2
                    exL = 0.5 * EA * (sL + ub_x) ** 2
                # boundary terms of Eq. (2-40)
                for r in range(nl):
                    fl[r] += (ex0 - Pt) * Cend0[r] + (-exL + Pt) * CendL[r]
                matvec(MtiT, ft, m1, nt, nt)
                for r in range(nt):
                    out[nt + nl + r] = m1[r]
                matvec(MliT, fl, m2, nl, nl)
                for r in range(nl):
                    out[2 * nt + nl + r] = m2[r]
            bad = False
            for j in range(n):
                y[j] = y[j] + h6 * (K[0, j] + 2 * K[1, j] + 2 * K[2, j] + K[3, j])
                if not (abs(y[j]) <= y_cap):      # also catches NaN
                    bad = True
            if bad:
                return i + 1
            if (i + 1) % record_every == 0:
                for j in range(n):
                    out_y[irec, j] = y[j]
                irec += 1
        return 0

    return rk4


def kernel():
    """The compiled RK4 (built, or loaded from numba's disk cache, on first use)."""
    global _KERNEL
    if _KERNEL is None:
        _KERNEL = _build()
    return _KERNEL


def warm() -> None:
    """Load the compiled RK4 (numba's disk cache, or a compile) by one zero-step call of the
    production argument types: paid once per solver process, before any timed solve."""
    if not available():
        return
    a1, a2 = np.zeros(1), np.zeros((1, 1))
    kernel()(np.zeros(4), 1.0, 0, np.zeros((5, 0, 4)), 1, 1e3, 1, 1, a2, a2, a2, a2, a2, a2, a2,
             a1, a1, a2, a2, a2, a2, a2, a2, a1, a1, a1, a1, 1.0, 1.0, 1.0, 0.0, 1.0, False,
             np.zeros((1, 4)))


def rk4_tabulated(model, y0, dt, n_steps, F, record_every=1, y_cap=1e3):
    """Compiled :func:`.galerkin.rk4_tabulated`: same arguments, same result to round-off."""
    nt, nl = model.n_t, model.n_l

    def c2(a):
        return np.ascontiguousarray(a, dtype=float)

    n_rec = n_steps // record_every + 1
    out_y = np.empty((n_rec, 2 * (nt + nl)))
    Fs = np.ascontiguousarray(np.stack([np.asarray(F[k], float).reshape(n_steps, 4)
                                        for k in ("g", "h", "gd", "hd", "Pt")]))
    bad = kernel()(c2(y0), float(dt), int(n_steps), Fs, int(record_every), float(y_cap), nt, nl,
                   c2(model.B), c2(model.SW.T), c2(model.Sx), c2(model.Sxx),
                   c2(model.CW.T), c2(model.Cx), c2(model.Cxx), c2(model.lin[0]),
                   c2(model.lin[1]), c2(model.Gt.T), c2(model.Kt.T), c2(model.Gl.T),
                   c2(model.Kl.T), c2(model.Mt_inv.T), c2(model.Ml_inv.T), c2(model.Cend0), c2(model.CendL),
                   c2(model._Sx0), c2(model._SxL), float(model.L), float(model.m),
                   float(model.c), float(model.c_d), float(model.EA), bool(model.coupling), out_y)
    if bad:
        raise DivergenceError(f"RK4 diverged at t = {bad * dt:.4g} s")
    t = np.arange(n_rec) * record_every * dt
    return t, out_y
