"""Compiled BDF (variable order 1-5 NDF, quasi-constant step) for the clearance joint:
scipy's algorithm, one numba call per run, with the outputs of :func:`.radau.radau`.

Why it is compiled: BDF is one of the stiff integrators the cost-of-accuracy study compares
beside the compiled Radau; stepped by scipy its time per period would measure scipy's
per-step Python, not the method.

The code is scipy 1.17's ``BDF`` (``scipy/integrate/_ivp/bdf.py``, the initial step of
``common.py``): the predictor from the modified divided differences D, the simplified Newton
iteration with its convergence rate test, the Jacobian-reuse and step-halving rules, the
error estimate, the order and step-size selection and the dense output, sampled at
``t_eval``.  Only the summation order of the small dot products and the 4x4 LU (partial
pivoting written out, :func:`.radau.lu_factor`) differ, so it takes scipy's steps to
round-off (``tests/test_joint_wear_kernel.py``).  Adapted from SciPy under the BSD licence
whose full text :mod:`.radau` carries.
"""
from __future__ import annotations

import numpy as np

from .clearance import jac_into, jit, rhs_into
from .radau import EPS, lu_factor, lu_solve, rms, start

BDF_MAX_ORDER = 5
BDF_NEWTON_MAXITER = 4
_kappa = np.array([0, -0.1850, -1 / 9, -0.0823, -0.0415, 0])
BDF_GAMMA = np.hstack((0, np.cumsum(1 / np.arange(1, BDF_MAX_ORDER + 1))))
BDF_ALPHA = (1 - _kappa) * BDF_GAMMA
BDF_ERROR_CONST = _kappa * BDF_GAMMA + 1 / np.arange(1, BDF_MAX_ORDER + 2)


@jit
def compute_R(order, factor):
    M = np.zeros((order + 1, order + 1))
    for i in range(1, order + 1):
        for j in range(1, order + 1):
            M[i, j] = (i - 1 - factor * j) / i
    for j in range(order + 1):
        M[0, j] = 1.0
    for i in range(1, order + 1):
        for j in range(order + 1):
            M[i, j] = M[i - 1, j] * M[i, j]
    return M


@jit
def change_D(D, order, factor):
    R = compute_R(order, factor)
    U = compute_R(order, 1.0)
    m = order + 1
    RU = np.zeros((m, m))
    for i in range(m):
        for j in range(m):
            acc = 0.0
            for q in range(m):
                acc += R[i, q] * U[q, j]
            RU[i, j] = acc
    n = D.shape[1]
    Dn = np.zeros((m, n))
    for i in range(m):
        for r in range(n):
            acc = 0.0
            for q in range(m):
                acc += RU[q, i] * D[q, r]
            Dn[i, r] = acc
    for i in range(m):
        for r in range(n):
            D[i, r] = Dn[i, r]


@jit
def bdf(p, t0, y0, t_bound, t_eval, rtol, atol, max_steps):
    """scipy BDF (analytic Jacobian, max_step inf) from ``t0`` to ``t_bound``, sampled at
    ``t_eval``; ``(Yout, samples filled, nfev, steps, status, t reached)`` as :func:`.radau.radau`."""
    n = 4
    Yout, y0, f, nfev, h_abs_s = start(p, t0, y0, t_bound, t_eval, np.int64(1), rtol, atol)
    kk = np.int64(1)     # typed, not a Literal: one compiled sample() per integrator
    t = t0
    newton_tol = max(10 * EPS / rtol, min(0.03, rtol ** 0.5))
    J = np.empty((n, n))
    jac_into(t, y0, p, J)
    D = np.zeros((BDF_MAX_ORDER + 3, n))
    for r in range(n):
        D[0, r] = y0[r]
        D[1, r] = f[r] * h_abs_s
    order_s = np.int64(1)
    n_equal_steps = 0
    have_lu = False
    LU = np.empty((n, n))
    piv = np.empty(n, dtype=np.int64)
    y_predict = np.empty(n)
    scale = np.empty(n)
    psi = np.empty(n)
    y_new = np.empty(n)
    d = np.empty(n)
    dy = np.empty(n)
    fr = np.empty(n)
    err = np.empty(n)
    steps = 0
    status = 0
    if t == t_bound:
        return Yout, kk, nfev[0], steps, status, t
    while True:
        min_step = 10 * abs(np.nextafter(t, np.inf) - t)
        if h_abs_s < min_step:
            h_abs = min_step
            change_D(D, order_s, min_step / h_abs_s)
            n_equal_steps = 0
        else:
            h_abs = h_abs_s
        order = order_s
        current_jac = False
        step_accepted = False
        failed = False
        t_new = t
        n_iter = 0
        error_norm = 0.0
        safety = 0.0
        while not step_accepted:
            if h_abs < min_step:
                failed = True
                break
            h = h_abs
            t_new = t + h
            if t_new - t_bound > 0:
                t_new = t_bound
                change_D(D, order, abs(t_new - t) / h_abs)
                n_equal_steps = 0
                have_lu = False
            h = t_new - t
            h_abs = abs(h)
            for r in range(n):
                acc = 0.0
                for i in range(order + 1):
                    acc += D[i, r]
                y_predict[r] = acc
                scale[r] = atol[r] + rtol * abs(y_predict[r])
                acc = 0.0
                for i in range(1, order + 1):
                    acc += D[i, r] * BDF_GAMMA[i]
                psi[r] = acc / BDF_ALPHA[order]
            converged = False
            c = h / BDF_ALPHA[order]
            while not converged:
                if not have_lu:
                    for i in range(n):
                        for j in range(n):
                            LU[i, j] = (1.0 if i == j else 0.0) - c * J[i, j]
                    lu_factor(LU, piv)
                    have_lu = True
                # ---- solve_bdf_system ----
                for r in range(n):
                    y_new[r] = y_predict[r]
                    d[r] = 0.0
                dy_norm_old = -1.0
                converged = False
                k = 0
                while k < BDF_NEWTON_MAXITER:
                    rhs_into(t_new, y_new, p, fr)
                    nfev[0] += 1
                    finite = True
                    for r in range(n):
                        if not np.isfinite(fr[r]):
                            finite = False
                    if not finite:
                        break
                    for r in range(n):
                        dy[r] = c * fr[r] - psi[r] - d[r]
                    lu_solve(LU, piv, dy)
                    dy_norm = rms(dy, scale)
                    rate = -1.0
                    if dy_norm_old >= 0:
                        rate = dy_norm / dy_norm_old
                    if rate >= 0 and (rate >= 1 or rate ** (BDF_NEWTON_MAXITER - k)
                                      / (1 - rate) * dy_norm > newton_tol):
                        break
                    for r in range(n):
                        y_new[r] += dy[r]
                        d[r] += dy[r]
                    if dy_norm == 0 or (rate >= 0 and rate / (1 - rate) * dy_norm
                                        < newton_tol):
                        converged = True
                        break
                    dy_norm_old = dy_norm
                    k += 1
                n_iter = min(k, BDF_NEWTON_MAXITER - 1) + 1
                if not converged:
                    if current_jac:
                        break
                    jac_into(t_new, y_predict, p, J)
                    have_lu = False
                    current_jac = True
            if not converged:
                factor = 0.5
                h_abs *= factor
                change_D(D, order, factor)
                n_equal_steps = 0
                have_lu = False
                continue
            safety = 0.9 * (2 * BDF_NEWTON_MAXITER + 1) / (2 * BDF_NEWTON_MAXITER + n_iter)
            for r in range(n):
                scale[r] = atol[r] + rtol * abs(y_new[r])
                err[r] = BDF_ERROR_CONST[order] * d[r]
            error_norm = rms(err, scale)
            if error_norm > 1:
                factor = max(0.2, safety * error_norm ** (-1 / (order + 1)))
                h_abs *= factor
                change_D(D, order, factor)
                n_equal_steps = 0
            else:
                step_accepted = True
        if failed:
            status = -1
            break
        n_equal_steps += 1
        t = t_new
        h_abs_s = h_abs
        for r in range(n):
            D[order + 2, r] = d[r] - D[order + 1, r]
            D[order + 1, r] = d[r]
        for i in range(order, -1, -1):
            for r in range(n):
                D[i, r] += D[i + 1, r]
        if n_equal_steps >= order + 1:
            if order > 1:
                for r in range(n):
                    err[r] = BDF_ERROR_CONST[order - 1] * D[order, r]
                error_m_norm = rms(err, scale)
            else:
                error_m_norm = np.inf
            if order < BDF_MAX_ORDER:
                for r in range(n):
                    err[r] = BDF_ERROR_CONST[order + 1] * D[order + 2, r]
                error_p_norm = rms(err, scale)
            else:
                error_p_norm = np.inf
            f0 = error_m_norm ** (-1 / order) if error_m_norm != 0 else np.inf
            f1 = error_norm ** (-1 / (order + 1)) if error_norm != 0 else np.inf
            f2 = error_p_norm ** (-1 / (order + 2)) if error_p_norm != 0 else np.inf
            delta_order = -1
            fmax = f0
            if f1 > fmax:
                delta_order, fmax = 0, f1
            if f2 > fmax:
                delta_order, fmax = 1, f2
            order += delta_order
            order_s = order
            factor = min(10.0, safety * fmax)
            h_abs_s *= factor
            change_D(D, order, factor)
            n_equal_steps = 0
            have_lu = False
        steps += 1
        # BdfDenseOutput(t_old, t, h_abs, order, D[:order + 1])
        hd = h_abs_s
        j = np.searchsorted(t_eval, t, side="right")
        while kk < j:
            te = t_eval[kk]
            pw = 1.0
            acc = np.zeros(n)
            for i in range(order_s):
                pw = pw * ((te - (t - hd * i)) / (hd * (1 + i)))
                for r in range(n):
                    acc[r] += D[i + 1, r] * pw
            for r in range(n):
                Yout[kk, r] = acc[r] + D[0, r]
            kk += 1
        if t - t_bound >= 0:
            break
        if max_steps > 0 and steps >= max_steps:
            status = -2
            break
    return Yout, kk, nfev[0], steps, status, t
