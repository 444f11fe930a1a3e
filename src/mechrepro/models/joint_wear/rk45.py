"""Compiled RK45 (Dormand-Prince 5(4)) for the clearance joint: scipy's algorithm, one numba
call per run, with the outputs of :func:`.radau.radau`.

Why it is compiled: the explicit integrator is the stiff contact's cost reference (the
cost-of-accuracy study's RK45 run, stopped by a step budget); stepped by scipy its time per
period would measure scipy's per-step Python, not the method.

The code is scipy 1.17's ``RK45`` (``scipy/integrate/_ivp/rk.py``, the initial step of
``common.py``, max_step inf): the Butcher tableau, the error estimate, the step-size
controller (safety 0.9, factors 0.2-10, no growth after a rejection) and the quartic dense
output, sampled at ``t_eval`` as :func:`.radau.sample` does for Radau.  Only the summation
order of the stage sums differs, so it takes scipy's steps to round-off
(``tests/test_joint_wear_kernel.py``).  Adapted from SciPy under the BSD licence whose full
text :mod:`.radau` carries.
"""
from __future__ import annotations

import numpy as np

from .clearance import jit, rhs_into
from .radau import rms, sample, start

# scipy.integrate._ivp.rk.RK45: C, A, B, E, P
RC = np.array([0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1])
RA = np.array([
    [0, 0, 0, 0, 0],
    [1 / 5, 0, 0, 0, 0],
    [3 / 40, 9 / 40, 0, 0, 0],
    [44 / 45, -56 / 15, 32 / 9, 0, 0],
    [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0],
    [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656]])
RB = np.array([35 / 384, 0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84])
RE = np.array([-71 / 57600, 0, 71 / 16695, -71 / 1920, 17253 / 339200, -22 / 525, 1 / 40])
RP = np.array([
    [1, -8048581381 / 2820520608, 8663915743 / 2820520608, -12715105075 / 11282082432],
    [0, 0, 0, 0],
    [0, 131558114200 / 32700410799, -68118460800 / 10900136933, 87487479700 / 32700410799],
    [0, -1754552775 / 470086768, 14199869525 / 1410260304, -10690763975 / 1880347072],
    [0, 127303824393 / 49829197408, -318862633887 / 49829197408, 701980252875 / 199316789632],
    [0, -282668133 / 205662961, 2019193451 / 616988883, -1453857185 / 822651844],
    [0, 40617522 / 29380423, -110615467 / 29380423, 69997945 / 29380423]])


@jit
def rk45(p, t0, y0, t_bound, t_eval, rtol, atol, max_steps):
    """Integrate from ``t0`` to ``t_bound`` (``max_steps`` > 0: stop after that many steps);
    ``(Yout, samples filled, nfev, steps, status, t reached)`` as :func:`.radau.radau`."""
    n = y0.size
    Yout, y, f, nfev, h_abs = start(p, t0, y0, t_bound, t_eval, np.int64(4), rtol, atol)
    kk = np.int64(1)     # typed, not a Literal: one compiled sample() per integrator
    t = t0
    K = np.empty((7, n))
    yi = np.empty(n)
    y_new = np.empty(n)
    f_new = np.empty(n)
    scale = np.empty(n)
    err = np.empty(n)
    Q = np.empty((n, 4))
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
            t_new = min(t + h_abs, t_bound)
            h = t_new - t
            h_abs = abs(h)
            K[0] = f
            for s in range(1, 6):
                for r in range(n):
                    acc = 0.0
                    for q in range(s):
                        acc += K[q, r] * RA[s, q]
                    yi[r] = y[r] + acc * h
                rhs_into(t + RC[s] * h, yi, p, K[s])
                nfev[0] += 1
            for r in range(n):
                acc = 0.0
                for q in range(6):
                    acc += K[q, r] * RB[q]
                y_new[r] = y[r] + h * acc
            rhs_into(t + h, y_new, p, f_new)
            nfev[0] += 1
            K[6] = f_new
            for r in range(n):
                scale[r] = atol[r] + max(abs(y[r]), abs(y_new[r])) * rtol
                acc = 0.0
                for q in range(7):
                    acc += K[q, r] * RE[q]
                err[r] = acc * h
            error_norm = rms(err, scale)
            if error_norm < 1:
                factor = 10.0 if error_norm == 0 else min(10.0, 0.9 * error_norm ** exponent)
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
                Q[r, o] = acc
        t_old = t
        t = t_new
        y[:] = y_new
        f[:] = f_new
        steps += 1
        kk = sample(t_eval, kk, t, t_old, t - t_old, y_old, Q, 3, t - t_old, Yout)
        if t - t_bound >= 0:
            break
        if max_steps > 0 and steps >= max_steps:
            status = -2
            break
    return Yout, kk, nfev[0], steps, status, t
