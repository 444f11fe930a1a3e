"""The compiled kernels of :mod:`.ivp_kernel` (imported lazily: it imports numba).

Module-level functions so that numba's on-disk cache (``cache=True``) finds them again in
the next process (closures over other compiled functions are never found in the cache)."""
from __future__ import annotations

import math

import numba
import numpy as np

from .ivp_kernel import (AM, CLR, CMAX, DAMP, DMAX, FX, FY, GRAV, KC, L0, L1, L2, L3, M2, M3,
                         M11, M22, MU, NEXP, OMEGA, PLOAD, RBUSH, RPIN, VEPS)

jit = numba.njit(cache=True, error_model="numpy")


@jit
def contact(t, th3, ph2, w3, w2, p):
    """ClearanceJoint._contact, same operations in the same order."""
    c3, s3, c2, s2 = math.cos(th3), math.sin(th3), math.cos(ph2), math.sin(ph2)
    th1 = p[OMEGA] * t
    c1, s1 = math.cos(th1), math.sin(th1)
    ex = p[L1] * c1 - (p[L0] + p[L3] * c3 + p[L2] * c2)
    ey = p[L1] * s1 - (p[L3] * s3 + p[L2] * s2)
    edx = -p[L1] * p[OMEGA] * s1 - (-p[L3] * w3 * s3 - p[L2] * w2 * s2)
    edy = p[L1] * p[OMEGA] * c1 - (p[L3] * w3 * c3 + p[L2] * w2 * c2)
    e = math.hypot(ex, ey)
    delta = e - p[CLR]
    if delta <= 0.0:
        return 0.0, 0.0, 0.0, 0.0, c3, s3, c2, s2, ex, ey, edx, edy, e, delta
    nx, ny = ex / e, ey / e
    tx, ty = -ny, nx
    vN = edx * nx + edy * ny
    vT = edx * tx + edy * ty + p[OMEGA] * p[RPIN] - w2 * p[RBUSH]
    FN = p[KC] * delta ** p[NEXP]
    if p[DAMP] != 0.0:
        x = delta / p[DMAX]
        K2 = p[CMAX] if x >= 1.0 else p[CMAX] * x * x * (3.0 - 2.0 * x)
        FN += K2 * vN
    if FN < 0.0:
        FN = 0.0
    FT = 0.0
    if p[MU] != 0.0:
        FT = p[MU] * FN * vT / math.sqrt(vT * vT + p[VEPS] * p[VEPS])
    return (FN * nx + FT * tx, FN * ny + FT * ty, FN, FT, c3, s3, c2, s2, ex, ey, edx,
            edy, e, delta)

@jit
def rhs(t, y, p, out):
    """ClearanceJoint.rhs into ``out``."""
    th3, ph2, w3, w2 = y[0], y[1], y[2], y[3]
    fx, fy, FN, FT, c3, s3, c2, s2, ex, ey, edx, edy, e, delta = contact(t, th3, ph2, w3,
                                                                         w2, p)
    exx, eyy = p[L0] + 0.5 * p[L3] * c3, 0.5 * p[L3] * s3
    dx, dy = p[FX] - exx, p[FY] - eyy
    dn = math.hypot(dx, dy)
    Px, Py = p[PLOAD] * dx / dn, p[PLOAD] * dy / dn
    Q3 = (0.5 * p[L3] * (-s3 * Px + c3 * Py)
          - p[GRAV] * (0.5 * p[M3] * p[L3] + p[M2] * p[L3]) * c3)
    Q2 = -p[GRAV] * p[M2] * 0.5 * p[L2] * c2
    Q3 += p[L3] * (-s3 * fx + c3 * fy)
    Q2 += p[L2] * (-s2 * fx + c2 * fy) + p[RBUSH] * FT
    cd = c3 * c2 + s3 * s2
    sd = s3 * c2 - c3 * s2
    b3 = Q3 - p[AM] * sd * w2 * w2
    b2 = Q2 + p[AM] * sd * w3 * w3
    m12 = p[AM] * cd
    det = p[M11] * p[M22] - m12 * m12
    out[0] = w3
    out[1] = w2
    out[2] = (p[M22] * b3 - m12 * b2) / det
    out[3] = (p[M11] * b2 - m12 * b3) / det

@jit
def jac(t, y, p, J):
    """ClearanceJoint.jac into ``J`` (exact contact terms, M(q) frozen), written out."""
    th3, ph2, w3, w2 = y[0], y[1], y[2], y[3]
    for i in range(4):
        for j in range(4):
            J[i, j] = 0.0
    J[0, 2] = 1.0
    J[1, 3] = 1.0
    fx, fy, FN, FT, c3, s3, c2, s2, ex, ey, edx, edy, e, delta = contact(t, th3, ph2, w3,
                                                                         w2, p)
    if delta <= 0.0 or FN <= 0.0:
        return
    nx, ny = ex / e, ey / e
    tx, ty = -ny, nx
    vN = edx * nx + edy * ny
    vTe = edx * tx + edy * ty
    vT = vTe + p[OMEGA] * p[RPIN] - w2 * p[RBUSH]
    a = p[NEXP] * p[KC] * delta ** (p[NEXP] - 1.0)
    gx, gy = a * nx, a * ny                 # dFN/de
    hx, hy = 0.0, 0.0                       # dFN/d(edot)
    if p[DAMP] != 0.0:
        x = delta / p[DMAX]
        if x < 1.0:
            K2 = p[CMAX] * x * x * (3.0 - 2.0 * x)
            dK2 = p[CMAX] * (6.0 * x - 6.0 * x * x) / p[DMAX]
        else:
            K2, dK2 = p[CMAX], 0.0
        gx = gx + dK2 * vN * nx + K2 * vTe / e * tx
        gy = gy + dK2 * vN * ny + K2 * vTe / e * ty
        hx, hy = K2 * nx, K2 * ny
    v2 = p[VEPS] * p[VEPS]
    s = vT / math.sqrt(vT * vT + v2)
    ds = v2 / (vT * vT + v2) ** 1.5
    mu = p[MU]
    dvx, dvy = -vN / e * tx, -vN / e * ty   # dvT/de
    ax = mu * (s * gx + FN * ds * dvx)      # dFT/de
    ay = mu * (s * gy + FN * ds * dvy)
    bx = mu * (s * hx + FN * ds * tx)       # dFT/d(edot)
    by = mu * (s * hy + FN * ds * ty)
    dFT_dw2 = mu * FN * ds * (-p[RBUSH])
    # f = FN n + FT t: df/de (A), df/d(edot) (B)
    fe = FN / e
    te = FT / e
    A00 = nx * gx + fe * tx * tx + tx * ax - te * nx * tx
    A01 = nx * gy + fe * tx * ty + tx * ay - te * nx * ty
    A10 = ny * gx + fe * ty * tx + ty * ax - te * ny * tx
    A11 = ny * gy + fe * ty * ty + ty * ay - te * ny * ty
    B00 = nx * hx + tx * bx
    B01 = nx * hy + tx * by
    B10 = ny * hx + ty * bx
    B11 = ny * hy + ty * by
    l3, l2 = p[L3], p[L2]
    Jb00, Jb01, Jb10, Jb11 = -l3 * s3, -l2 * s2, l3 * c3, l2 * c2
    D00, D01, D10, D11 = l3 * w3 * c3, l2 * w2 * c2, l3 * w3 * s3, l2 * w2 * s2
    # X = A (-Jb) + B D
    X00 = -(A00 * Jb00 + A01 * Jb10) + (B00 * D00 + B01 * D10)
    X01 = -(A00 * Jb01 + A01 * Jb11) + (B00 * D01 + B01 * D11)
    X10 = -(A10 * Jb00 + A11 * Jb10) + (B10 * D00 + B11 * D10)
    X11 = -(A10 * Jb01 + A11 * Jb11) + (B10 * D01 + B11 * D11)
    q00 = Jb00 * X00 + Jb10 * X10
    q01 = Jb00 * X01 + Jb10 * X11
    q10 = Jb01 * X00 + Jb11 * X10
    q11 = Jb01 * X01 + Jb11 * X11
    rb = p[RBUSH]
    q10 += rb * (-(ax * Jb00 + ay * Jb10) + (bx * D00 + by * D10))
    q11 += rb * (-(ax * Jb01 + ay * Jb11) + (bx * D01 + by * D11))
    # Y = B (-Jb); dQ_dw = Jb^T Y
    Y00 = -(B00 * Jb00 + B01 * Jb10)
    Y01 = -(B00 * Jb01 + B01 * Jb11)
    Y10 = -(B10 * Jb00 + B11 * Jb10)
    Y11 = -(B10 * Jb01 + B11 * Jb11)
    r00 = Jb00 * Y00 + Jb10 * Y10
    r01 = Jb00 * Y01 + Jb10 * Y11
    r10 = Jb01 * Y00 + Jb11 * Y10
    r11 = Jb01 * Y01 + Jb11 * Y11
    r10 += rb * (-(bx * Jb00 + by * Jb10))
    r11 += rb * (-(bx * Jb01 + by * Jb11))
    r01 += Jb00 * tx * dFT_dw2 + Jb10 * ty * dFT_dw2
    r11 += Jb01 * tx * dFT_dw2 + Jb11 * ty * dFT_dw2
    r11 += rb * dFT_dw2
    m12 = p[AM] * (c3 * c2 + s3 * s2)
    det = p[M11] * p[M22] - m12 * m12
    i00, i01, i11 = p[M22] / det, -m12 / det, p[M11] / det
    J[2, 0] = i00 * q00 + i01 * q10
    J[2, 1] = i00 * q01 + i01 * q11
    J[3, 0] = i01 * q00 + i11 * q10
    J[3, 1] = i01 * q01 + i11 * q11
    J[2, 2] = i00 * r00 + i01 * r10
    J[2, 3] = i00 * r01 + i01 * r11
    J[3, 2] = i01 * r00 + i11 * r10
    J[3, 3] = i01 * r01 + i11 * r11

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
    rhs(t0 + h0, y1, p, f1)
    nfev[0] += 1
    d2 = rms(f1 - f0, scale) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / (order + 1))
    return min(100 * h0, h1, interval_length)

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
    nfev = np.zeros(1, dtype=np.int64)
    Yout = np.empty((t_eval.size, n))
    Yout[0] = y0
    kk = 1
    y = y0.copy()
    t = t0
    f = np.empty(n)
    rhs(t, y, p, f)
    nfev[0] += 1
    h_abs_s = initial_step(t, y, t_bound, f, 3, rtol, atol, p, nfev)
    h_abs_old_s = -1.0
    error_norm_old_s = -1.0
    newton_tol = max(10 * EPS / rtol, min(0.03, rtol ** 0.5))
    J = np.empty((n, n))
    jac(t, y, p, J)
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
                        rhs(t + h * C[i], yi, p, fr)
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
                    jac(t, y, p, J)
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
                rhs(t, yi, p, fr)
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
        rhs(t_new, y_new, p, f_new)
        nfev[0] += 1
        if recompute_jac:
            jac(t_new, y_new, p, J)
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

RA = np.array([
    [0, 0, 0, 0, 0],
    [1 / 5, 0, 0, 0, 0],
    [3 / 40, 9 / 40, 0, 0, 0],
    [44 / 45, -56 / 15, 32 / 9, 0, 0],
    [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0],
    [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656]])
RB = np.array([35 / 384, 0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84])
RC = np.array([0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1])
RE = np.array([-71 / 57600, 0, 71 / 16695, -71 / 1920, 17253 / 339200, -22 / 525, 1 / 40])
RP = np.array([
    [1, -8048581381 / 2820520608, 8663915743 / 2820520608,
     -12715105075 / 11282082432],
    [0, 0, 0, 0],
    [0, 131558114200 / 32700410799, -68118460800 / 10900136933,
     87487479700 / 32700410799],
    [0, -1754552775 / 470086768, 14199869525 / 1410260304,
     -10690763975 / 1880347072],
    [0, 127303824393 / 49829197408, -318862633887 / 49829197408,
     701980252875 / 199316789632],
    [0, -282668133 / 205662961, 2019193451 / 616988883, -1453857185 / 822651844],
    [0, 40617522 / 29380423, -110615467 / 29380423, 69997945 / 29380423]])

@jit
def rk45(p, t0, y0, t_bound, t_eval, rtol, atol, max_steps):
    """scipy RK45 (max_step inf), same outputs as :func:`radau`."""
    n = 4
    nfev = np.zeros(1, dtype=np.int64)
    Yout = np.empty((t_eval.size, n))
    Yout[0] = y0
    kk = 1
    y = y0.copy()
    t = t0
    f = np.empty(n)
    rhs(t, y, p, f)
    nfev[0] += 1
    h_abs = initial_step(t, y, t_bound, f, 4, rtol, atol, p, nfev)
    K = np.empty((7, n))
    yi = np.empty(n)
    y_new = np.empty(n)
    f_new = np.empty(n)
    scale = np.empty(n)
    err = np.empty(n)
    Qd = np.empty((n, 4))
    y_old = np.empty(n)
    steps = 0
    status = 0
    exponent = -1.0 / 5.0
    if t == t_bound:
        return Yout, kk, nfev[0], steps, status, t
    while True:
        min_step = 10 * abs(np.nextafter(t, np.inf) - t)
        if h_abs < min_step:
            h_abs = min_step
        step_accepted = False
        step_rejected = False
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
            # rk_step
            for r in range(n):
                K[0, r] = f[r]
            for s in range(1, 6):
                for r in range(n):
                    acc = 0.0
                    for q in range(s):
                        acc += K[q, r] * RA[s, q]
                    yi[r] = y[r] + acc * h
                rhs(t + RC[s] * h, yi, p, K[s])
                nfev[0] += 1
            for r in range(n):
                acc = 0.0
                for q in range(6):
                    acc += K[q, r] * RB[q]
                y_new[r] = y[r] + h * acc
            rhs(t + h, y_new, p, f_new)
            nfev[0] += 1
            for r in range(n):
                K[6, r] = f_new[r]
            for r in range(n):
                scale[r] = atol[r] + max(abs(y[r]), abs(y_new[r])) * rtol
                acc = 0.0
                for q in range(7):
                    acc += K[q, r] * RE[q]
                err[r] = acc * h
            error_norm = rms(err, scale)
            if error_norm < 1:
                if error_norm == 0:
                    factor = 10.0
                else:
                    factor = min(10.0, 0.9 * error_norm ** exponent)
                if step_rejected:
                    factor = min(1.0, factor)
                h_abs *= factor
                step_accepted = True
            else:
                h_abs *= max(0.2, 0.9 * error_norm ** exponent)
                step_rejected = True
        if failed:
            status = -1
            break
        for r in range(n):
            y_old[r] = y[r]
            for o in range(4):
                acc = 0.0
                for q in range(7):
                    acc += K[q, r] * RP[q, o]
                Qd[r, o] = acc
        t_old = t
        t = t_new
        for r in range(n):
            y[r] = y_new[r]
            f[r] = f_new[r]
        steps += 1
        kk = sample(t_eval, kk, t, t_old, t - t_old, y_old, Qd, 3, t - t_old, Yout)
        if t - t_bound >= 0:
            break
        if max_steps > 0 and steps >= max_steps:
            status = -2
            break
    return Yout, kk, nfev[0], steps, status, t

@jit
def history(T, Y, p):
    """contact_history's loop: F_N, F_T, delta, v_T, psi (unwrapped later)."""
    m = T.size
    out = np.empty((5, m))
    for k in range(m):
        th3, ph2, w3, w2 = Y[0, k], Y[1, k], Y[2, k], Y[3, k]
        fx, fy, FN, FT, c3, s3, c2, s2, ex, ey, edx, edy, e, delta = contact(
            T[k], th3, ph2, w3, w2, p)
        out[0, k] = FN
        out[1, k] = FT
        out[2, k] = delta
        if e:
            nx, ny = ex / e, ey / e
        else:
            nx, ny = 1.0, 0.0
        out[3, k] = edx * -ny + edy * nx + p[OMEGA] * p[RPIN] - w2 * p[RBUSH]
        out[4, k] = math.atan2(ny, nx) - ph2
    return out


@jit
def rhs_new(t, y, p):
    """rhs into a new array (the callback of scipy's LSODA/BDF)."""
    out = np.empty(4)
    rhs(t, y, p, out)
    return out


@jit
def jac_new(t, y, p):
    J = np.empty((4, 4))
    jac(t, y, p, J)
    return J


# ---- BDF (scipy/integrate/_ivp/bdf.py: variable order 1-5 NDF, quasi-constant step) ----
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
    """scipy BDF (analytic Jacobian, max_step inf), same outputs as :func:`radau`."""
    n = 4
    nfev = np.zeros(1, dtype=np.int64)
    Yout = np.empty((t_eval.size, n))
    Yout[0] = y0
    kk = 1
    t = t0
    f = np.empty(n)
    rhs(t, y0, p, f)
    nfev[0] += 1
    h_abs_s = initial_step(t, y0, t_bound, f, 1, rtol, atol, p, nfev)
    newton_tol = max(10 * EPS / rtol, min(0.03, rtol ** 0.5))
    J = np.empty((n, n))
    jac(t, y0, p, J)
    D = np.zeros((BDF_MAX_ORDER + 3, n))
    for r in range(n):
        D[0, r] = y0[r]
        D[1, r] = f[r] * h_abs_s
    order_s = 1
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
                    rhs(t_new, y_new, p, fr)
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
                    jac(t_new, y_predict, p, J)
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
            for r in range(n):
                Yout[kk, r] = D[0, r]
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
