"""Compiled Radau IIA (order 5) for the clearance joint: scipy's algorithm, one numba call
per period.

Why it stays: the dynamic period is a 4-state system integrated in hundreds to ~1e5 steps,
where scipy's ``Radau`` spends its time in per-step Python, not arithmetic (the work-precision
benchmark ``benchmarks/bench_joint_wear.py``).  BDF and RK45 have compiled copies too
(:mod:`.bdf`, :mod:`.rk45`, sharing this module's start, norm, LU and dense-output
sampling); LSODA runs in scipy.

The code is scipy 1.17's ``Radau`` (``scipy/integrate/_ivp/radau.py``, ``common.py``): the
initial step, the simplified Newton iteration on the transformed collocation system, its
convergence and Jacobian-reuse rules, the error estimate, the step-size controller and the
dense output, with the sampling at ``t_eval`` of :func:`.dynamics.simulate`.  Only the
summation order of a few 3- and 4-term dot products and the 4x4 LU (partial pivoting
written out, as LAPACK's ``getrf`` pivots) differ, so it takes scipy's steps to round-off
(``tests/test_joint_wear_kernel.py``).  It calls the physics of :mod:`.clearance`; nothing
of the model is restated here.

Adapted from SciPy, which is distributed under this licence:

Copyright (c) 2001-2002 Enthought, Inc. 2003, SciPy Developers.
All rights reserved.

Redistribution and use in source and binary forms, with or without
modification, are permitted provided that the following conditions
are met:

1. Redistributions of source code must retain the above copyright
   notice, this list of conditions and the following disclaimer.

2. Redistributions in binary form must reproduce the above
   copyright notice, this list of conditions and the following
   disclaimer in the documentation and/or other materials provided
   with the distribution.

3. Neither the name of the copyright holder nor the names of its
   contributors may be used to endorse or promote products derived
   from this software without specific prior written permission.

THIS SOFTWARE IS PROVIDED BY THE COPYRIGHT HOLDERS AND CONTRIBUTORS
"AS IS" AND ANY EXPRESS OR IMPLIED WARRANTIES, INCLUDING, BUT NOT
LIMITED TO, THE IMPLIED WARRANTIES OF MERCHANTABILITY AND FITNESS FOR
A PARTICULAR PURPOSE ARE DISCLAIMED. IN NO EVENT SHALL THE COPYRIGHT
OWNER OR CONTRIBUTORS BE LIABLE FOR ANY DIRECT, INDIRECT, INCIDENTAL,
SPECIAL, EXEMPLARY, OR CONSEQUENTIAL DAMAGES (INCLUDING, BUT NOT
LIMITED TO, PROCUREMENT OF SUBSTITUTE GOODS OR SERVICES; LOSS OF USE,
DATA, OR PROFITS; OR BUSINESS INTERRUPTION) HOWEVER CAUSED AND ON ANY
THEORY OF LIABILITY, WHETHER IN CONTRACT, STRICT LIABILITY, OR TORT
(INCLUDING NEGLIGENCE OR OTHERWISE) ARISING IN ANY WAY OUT OF THE USE
OF THIS SOFTWARE, EVEN IF ADVISED OF THE POSSIBILITY OF SUCH DAMAGE.
"""
from __future__ import annotations

import math

import numpy as np

from .clearance import jac_into, jit, rhs_into


@jit
def rms(x, scale):
    s = 0.0
    for i in range(x.size):
        v = x[i] / scale[i]
        s += v * v
    return math.sqrt(s) / math.sqrt(x.size)

@jit
def initial_step(t0, y0, t_bound, f0, order, rtol, atol, p, nfev):
    """scipy.integrate._ivp.common.select_initial_step (max_step = inf, direction +1)."""
    n = y0.size
    interval_length = abs(t_bound - t0)
    scale = atol + np.abs(y0) * rtol
    d0 = rms(y0, scale)
    d1 = rms(f0, scale)
    if d0 < 1e-5 or d1 < 1e-5:
        h0 = 1e-6
    else:
        h0 = 0.01 * d0 / d1
    h0 = min(h0, interval_length)
    y1 = y0 + h0 * f0
    f1 = np.empty(n)
    rhs_into(t0 + h0, y1, p, f1)
    nfev[0] += 1
    d2 = rms(f1 - f0, scale) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / (order + 1))
    return min(100 * h0, h1, interval_length)

@jit
def start(p, t0, y0, t_bound, t_eval, order, rtol, atol):
    """What an integrator does first: the samples with the first one filled, the state and
    its derivative, the evaluation counter and scipy's initial step for ``order``."""
    nfev = np.zeros(1, dtype=np.int64)
    Yout = np.empty((t_eval.size, y0.size))
    Yout[0] = y0
    y = y0.copy()
    f = np.empty(y0.size)
    rhs_into(t0, y, p, f)
    nfev[0] += 1
    return Yout, y, f, nfev, initial_step(t0, y, t_bound, f, order, rtol, atol, p, nfev)


@jit
def lu_factor(A, piv):
    """In-place LU with partial pivoting (LAPACK getrf's choice: max |re| + |im|)."""
    n = A.shape[0]
    for k in range(n):
        m, best = k, -1.0
        for i in range(k, n):
            v = abs(A[i, k].real) + abs(A[i, k].imag)
            if v > best:
                m, best = i, v
        piv[k] = m
        if m != k:
            for j in range(n):
                A[k, j], A[m, j] = A[m, j], A[k, j]
        if A[k, k] != 0:
            inv = 1.0 / A[k, k]
            for i in range(k + 1, n):
                A[i, k] = A[i, k] * inv
        for i in range(k + 1, n):
            lik = A[i, k]
            if lik != 0:
                for j in range(k + 1, n):
                    A[i, j] -= lik * A[k, j]

@jit
def lu_solve(LU, piv, b):
    """Solve in place (getrs: row swaps, unit-lower then upper substitution)."""
    n = LU.shape[0]
    for k in range(n):
        m = piv[k]
        if m != k:
            b[k], b[m] = b[m], b[k]
    for i in range(n):
        s = b[i]
        for j in range(i):
            s -= LU[i, j] * b[j]
        b[i] = s
    for i in range(n - 1, -1, -1):
        s = b[i]
        for j in range(i + 1, n):
            s -= LU[i, j] * b[j]
        b[i] = s / LU[i, i]

S6 = 6 ** 0.5
C = np.array([(4 - S6) / 10, (4 + S6) / 10, 1])
E = np.array([-13 - 7 * S6, -13 + 7 * S6, -1]) / 3
MU_REAL = 3 + 3 ** (2 / 3) - 3 ** (1 / 3)
MU_COMPLEX = (3 + 0.5 * (3 ** (1 / 3) - 3 ** (2 / 3))
              - 0.5j * (3 ** (5 / 6) + 3 ** (7 / 6)))
T = np.array([
    [0.09443876248897524, -0.14125529502095421, 0.03002919410514742],
    [0.25021312296533332, 0.20412935229379994, -0.38294211275726192],
    [1, 1, 0]])
TI = np.array([
    [4.17871859155190428, 0.32768282076106237, 0.52337644549944951],
    [-4.17871859155190428, -0.32768282076106237, 0.47662355450055044],
    [0.50287263494578682, -2.57192694985560522, 0.59603920482822492]])
TI_REAL = TI[0].copy()
TI_COMPLEX = TI[1] + 1j * TI[2]
P = np.array([
    [13 / 3 + 7 * S6 / 3, -23 / 3 - 22 * S6 / 3, 10 / 3 + 5 * S6],
    [13 / 3 - 7 * S6 / 3, -23 / 3 + 22 * S6 / 3, 10 / 3 - 5 * S6],
    [1 / 3, -8 / 3, 10 / 3]])
EPS = float(np.finfo(float).eps)
NEWTON_MAXITER = 6

@jit
def predict_factor(h_abs, h_abs_old, error_norm, error_norm_old):
    """radau.predict_factor; a negative *_old stands for None."""
    if error_norm_old < 0 or h_abs_old < 0 or error_norm == 0:
        multiplier = 1.0
    else:
        multiplier = h_abs / h_abs_old * (error_norm_old / error_norm) ** 0.25
    if error_norm == 0:
        return np.inf
    return min(1.0, multiplier) * error_norm ** -0.25

@jit
def sample(t_eval, k, t_new, t_old, h, y_old, Q, order, scale_h, Yout):
    """Dense output of the step (t_old, t_new] at the samples it holds; the next k."""
    j = np.searchsorted(t_eval, t_new, side="right")
    n = y_old.size
    while k < j:
        x = (t_eval[k] - t_old) / h
        for r in range(n):
            acc = 0.0
            pw = 1.0
            for o in range(order + 1):
                pw = pw * x
                acc += Q[r, o] * pw
            Yout[k, r] = scale_h * acc + y_old[r]
        k += 1
    return k

@jit
def radau(p, t0, y0, t_bound, t_eval, rtol, atol, max_steps):
    """scipy Radau (analytic Jacobian, max_step inf) from t0 to t_bound, sampled at
    t_eval (t_eval[0] = t0).  Returns (Y, n_samples, nfev, steps, status, t)."""
    n = 4
    # the order typed (int64, not a numba Literal): start and initial_step are compiled once
    # for the three integrators instead of once per order
    Yout, y, f, nfev, h_abs_s = start(p, t0, y0, t_bound, t_eval, np.int64(3), rtol, atol)
    kk = np.int64(1)     # typed, not a Literal: one compiled sample() per integrator
    t = t0
    h_abs_old_s = -1.0
    error_norm_old_s = -1.0
    newton_tol = max(10 * EPS / rtol, min(0.03, rtol ** 0.5))
    J = np.empty((n, n))
    jac_into(t, y, p, J)
    current_jac = True
    have_lu = False
    LUr = np.empty((n, n))
    LUc = np.empty((n, n), dtype=np.complex128)
    pivr = np.empty(n, dtype=np.int64)
    pivc = np.empty(n, dtype=np.int64)
    have_sol = False
    Qd = np.empty((n, 3))
    t_old_d, h_d = 0.0, 1.0
    y_old_d = y.copy()
    Z = np.zeros((3, n))
    Z0 = np.zeros((3, n))
    W = np.zeros((3, n))
    dW = np.zeros((3, n))
    F = np.empty((3, n))
    yi = np.empty(n)
    fr = np.empty(n)
    fc = np.empty(n, dtype=np.complex128)
    scale = np.empty(n)
    err = np.empty(n)
    ZE = np.empty(n)
    y_new = np.empty(n)
    f_new = np.empty(n)
    steps = 0
    status = 0
    rate = -1.0
    n_iter = 0
    error_norm = 0.0
    if t == t_bound:
        return Yout, kk, nfev[0], steps, status, t
    while True:
        # ---- Radau._step_impl ----
        min_step = 10 * abs(np.nextafter(t, np.inf) - t)
        if h_abs_s < min_step:
            h_abs = min_step
            h_abs_old = -1.0
            error_norm_old = -1.0
        else:
            h_abs = h_abs_s
            h_abs_old = h_abs_old_s
            error_norm_old = error_norm_old_s
        rejected = False
        step_accepted = False
        failed = False
        t_new = t
        while not step_accepted:
            if h_abs < min_step:
                failed = True
                break
            h = h_abs
            t_new = t + h
            if t_new - t_bound > 0:
                t_new = t_bound
            h = t_new - t
            h_abs = abs(h)
            if not have_sol:
                for i in range(3):
                    for r in range(n):
                        Z0[i, r] = 0.0
            else:
                for i in range(3):
                    x = (t + h * C[i] - t_old_d) / h_d
                    for r in range(n):
                        acc = 0.0
                        pw = 1.0
                        for o in range(3):
                            pw = pw * x
                            acc += Qd[r, o] * pw
                        Z0[i, r] = (acc + y_old_d[r]) - y[r]
            for r in range(n):
                scale[r] = atol[r] + abs(y[r]) * rtol
            converged = False
            while not converged:
                if not have_lu:
                    mr = MU_REAL / h
                    mc = MU_COMPLEX / h
                    for i in range(n):
                        for j in range(n):
                            d = 1.0 if i == j else 0.0
                            LUr[i, j] = mr * d - J[i, j]
                            LUc[i, j] = mc * d - J[i, j]
                    lu_factor(LUr, pivr)
                    lu_factor(LUc, pivc)
                    have_lu = True
                # ---- solve_collocation_system ----
                M_real = MU_REAL / h
                M_complex = MU_COMPLEX / h
                for i in range(3):
                    for r in range(n):
                        W[i, r] = TI[i, 0] * Z0[0, r] + TI[i, 1] * Z0[1, r] + TI[i, 2] * Z0[2, r]
                        Z[i, r] = Z0[i, r]
                dW_norm_old = -1.0
                converged = False
                rate = -1.0
                k = 0
                while k < NEWTON_MAXITER:
                    finite = True
                    for i in range(3):
                        for r in range(n):
                            yi[r] = y[r] + Z[i, r]
                        rhs_into(t + h * C[i], yi, p, fr)
                        nfev[0] += 1
                        for r in range(n):
                            F[i, r] = fr[r]
                            if not np.isfinite(fr[r]):
                                finite = False
                    if not finite:
                        break
                    for r in range(n):
                        fr[r] = (F[0, r] * TI_REAL[0] + F[1, r] * TI_REAL[1]
                                 + F[2, r] * TI_REAL[2]) - M_real * W[0, r]
                        fc[r] = ((F[0, r] * TI_COMPLEX[0] + F[1, r] * TI_COMPLEX[1]
                                  + F[2, r] * TI_COMPLEX[2])
                                 - M_complex * (W[1, r] + 1j * W[2, r]))
                    lu_solve(LUr, pivr, fr)
                    lu_solve(LUc, pivc, fc)
                    s2 = 0.0
                    for r in range(n):
                        dW[0, r] = fr[r]
                        dW[1, r] = fc[r].real
                        dW[2, r] = fc[r].imag
                    for i in range(3):
                        for r in range(n):
                            v = dW[i, r] / scale[r]
                            s2 += v * v
                    dW_norm = math.sqrt(s2) / math.sqrt(3.0 * n)
                    if dW_norm_old >= 0:
                        rate = dW_norm / dW_norm_old
                    if rate >= 0 and (rate >= 1 or rate ** (NEWTON_MAXITER - k)
                                      / (1 - rate) * dW_norm > newton_tol):
                        break
                    for i in range(3):
                        for r in range(n):
                            W[i, r] += dW[i, r]
                    for i in range(3):
                        for r in range(n):
                            Z[i, r] = T[i, 0] * W[0, r] + T[i, 1] * W[1, r] + T[i, 2] * W[2, r]
                    if dW_norm == 0 or (rate >= 0 and rate / (1 - rate) * dW_norm
                                        < newton_tol):
                        converged = True
                        break
                    dW_norm_old = dW_norm
                    k += 1
                n_iter = min(k, NEWTON_MAXITER - 1) + 1
                # ---- end solve_collocation_system ----
                if not converged:
                    if current_jac:
                        break
                    jac_into(t, y, p, J)
                    current_jac = True
                    have_lu = False
            if not converged:
                h_abs *= 0.5
                have_lu = False
                continue
            for r in range(n):
                y_new[r] = y[r] + Z[2, r]
                ZE[r] = (Z[0, r] * E[0] + Z[1, r] * E[1] + Z[2, r] * E[2]) / h
                err[r] = f[r] + ZE[r]
            lu_solve(LUr, pivr, err)
            for r in range(n):
                scale[r] = atol[r] + max(abs(y[r]), abs(y_new[r])) * rtol
            error_norm = rms(err, scale)
            safety = 0.9 * (2 * NEWTON_MAXITER + 1) / (2 * NEWTON_MAXITER + n_iter)
            if rejected and error_norm > 1:
                for r in range(n):
                    yi[r] = y[r] + err[r]
                rhs_into(t, yi, p, fr)
                nfev[0] += 1
                for r in range(n):
                    err[r] = fr[r] + ZE[r]
                lu_solve(LUr, pivr, err)
                error_norm = rms(err, scale)
            if error_norm > 1:
                factor = predict_factor(h_abs, h_abs_old, error_norm, error_norm_old)
                h_abs *= max(0.2, safety * factor)
                have_lu = False
                rejected = True
            else:
                step_accepted = True
        if failed:
            status = -1
            break
        recompute_jac = n_iter > 2 and rate > 1e-3
        factor = predict_factor(h_abs, h_abs_old, error_norm, error_norm_old)
        factor = min(10.0, safety * factor)
        if not recompute_jac and factor < 1.2:
            factor = 1.0
        else:
            have_lu = False
        rhs_into(t_new, y_new, p, f_new)
        nfev[0] += 1
        if recompute_jac:
            jac_into(t_new, y_new, p, J)
            current_jac = True
        else:
            current_jac = False
        h_abs_old_s = h_abs_s
        error_norm_old_s = error_norm
        h_abs_s = h_abs * factor
        # dense output of the step: Q = Z^T P
        for r in range(n):
            y_old_d[r] = y[r]
            for o in range(3):
                Qd[r, o] = Z[0, r] * P[0, o] + Z[1, r] * P[1, o] + Z[2, r] * P[2, o]
        t_old_d = t
        h_d = t_new - t
        have_sol = True
        t = t_new
        for r in range(n):
            y[r] = y_new[r]
            f[r] = f_new[r]
        steps += 1
        kk = sample(t_eval, kk, t, t_old_d, h_d, y_old_d, Qd, 2, 1.0, Yout)
        if t - t_bound >= 0:
            break
        if max_steps > 0 and steps >= max_steps:
            status = -2
            break
    return Yout, kk, nfev[0], steps, status, t
