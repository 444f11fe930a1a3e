"""Work-precision of maintained ODE libraries against joint_wear's own integrators on the
dynamic period (scene ``period_dynamic``: settled start, one period, n_out = 720).

Compared, on exactly the same problem (the project's compiled right-hand side and analytic
contact Jacobian of ``clearance.py``, the initial state of ``dynamics.initial_state``, the
atol of ``dynamics.simulate``: rtol * 1e-2 on angles, 10x that on rates), all in one process:

  own Radau, own BDF      radau.py / bdf.py (numba, one call per period)
  scipy LSODA             the pipeline's ``LSODA`` (scipy stepping, compiled RHS/Jacobian)
  numbalsoda LSODA/DOP853 a numba ``cfunc`` RHS wrapping ``clearance.rhs_into`` (numbalsoda
                          takes a scalar atol: the state is scaled by (1, 1, 10, 10) so that
                          the scalar atol gives the project's per-component atol exactly);
                          LSODA forms its Jacobian by differences (numbalsoda has no hook)
  sksundae CVODE BDF      SUNDIALS CVODE, dense linear solver, analytic Jacobian; its
                          callbacks are Python calling the compiled kernels

Reference: own Radau at rtol 1e-12 (the accuracy study's reference), its own error shown
against rtol 1e-13.  Errors: the joint force history F_N on the 720-point output grid
(max |F_N - F_N_ref| / max F_N_ref), the mean force (Eq. 22) and the wear per period
(wear factor G, Eq. 29), relative.  Time: the fastest of ``--repeats`` calls, methods
interleaved.  "xRadau": the time over that of the cheapest own Radau run at least as
accurate (in F_N history, in wear per period; "-": no Radau run is); without interpolation
between Radau's decades this favours the candidates.

    PYTHONPATH=src /tmp/odevenv/bin/python benchmarks/bench_ode_libraries.py [--repeats 3]

A library that is not importable is skipped with a message.  Changes no product code.

Install (Python 3.11, numpy 2.4.6 / numba 0.68.1 / scipy 1.17.1 of requirements.lock kept):
scikit-sundae 1.2.0 is a manylinux wheel; numbalsoda 0.3.4 has no cp311 wheel (the last
wheels, 0.3.1, stop at cp310): it builds from source and needs a Fortran compiler (gfortran).

Measured (2026-12-06, 2 shared cores): no candidate beats own Radau at equal error in the
wear per period, and only numbalsoda LSODA draws level (~1.0-1.4x) in the F_N history, at
errors 1e-5..1e-6; at the pipeline's point (Radau 1e-5: ~1.7 ms, F_N 8e-4, wear 5e-6) the
candidates are 3-20x (numbalsoda LSODA) and 8-140x (CVODE: Python callbacks) slower.
DOP853 cannot finish the stiff period (200 000 steps reach t = 0.145 s of 6.25 s).
Below rtol ~1e-5 every BDF-type method (own BDF, LSODA, CVODE) has O(0.1-1) errors in
wear, and below ~1e-4 Radau too: the steps skip over the contact's ringing.
"""
from __future__ import annotations

import argparse
import contextlib
import os
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
# DOP853's warnings go through gfortran's buffered unit 6: unbuffered, quiet_c_stdout drops them
os.environ.setdefault("GFORTRAN_UNBUFFERED_PRECONNECTED", "y")

import numpy as np  # noqa: E402

from mechrepro.config import load_paper  # noqa: E402
from mechrepro.models.joint_wear import clearance, dynamics, wear  # noqa: E402
from mechrepro.models.joint_wear.bdf import bdf  # noqa: E402
from mechrepro.models.joint_wear.radau import radau  # noqa: E402
from mechrepro.models.joint_wear.solver import setup  # noqa: E402

W = np.array([1.0, 1.0, 10.0, 10.0])     # dynamics.simulate's atol weights


# --- the problem -------------------------------------------------------------------------
def problem(scene="period_dynamic"):
    run = load_paper("config/papers/joint_wear.yaml").runs[scene]
    fb, ctx = setup(run)
    s = ctx.s
    assert int(s.get("periods", 1)) == 1
    p = clearance.params(fb, fb.C_max > 0.0)
    y0 = dynamics.initial_state(fb, s.get("start", "equilibrium"))
    t_eval = np.linspace(0.0, fb.period, int(s["n_out"]) + 1)
    return fb, s, p, y0, t_eval


def quantities(fb, s, p, t_eval, Y):
    """What the paper takes from a period: F_N history, mean force, wear factor G."""
    h = dynamics.contact_history(p, t_eval, np.ascontiguousarray(Y))
    h = {k: np.asarray(v)[:-1] for k, v in h.items()}          # as solver.dynamic_period
    f = wear.period_wear_factor(h, fb, fb.period, s.get("wear_range", "contact_point"))
    return {"F_N": h["F_N"], "F_mean": f["F_N_mean"], "G": f["G"]}


def errors(q, ref):
    return (float(np.max(np.abs(q["F_N"] - ref["F_N"])) / np.max(ref["F_N"])),
            abs(q["F_mean"] / ref["F_mean"] - 1.0), abs(q["G"] / ref["G"] - 1.0))


@contextlib.contextmanager
def quiet_c_stdout():
    """DOP853 prints a line per stiffness detection: drop fd 1 (and C's buffer)."""
    import ctypes
    import sys

    libc = ctypes.CDLL(None)
    sys.stdout.flush()
    saved, null = os.dup(1), os.open(os.devnull, os.O_WRONLY)
    os.dup2(null, 1)
    try:
        yield
    finally:
        libc.fflush(None)
        os.dup2(saved, 1)
        os.close(saved)
        os.close(null)


# --- the methods: each (p, y0, t_eval, rtol) -> (Y (4, n), RHS calls or None), or raises ---
def own(kernel):
    def f(p, y0, t, rtol):
        Y, m, nfev, steps, status, _ = kernel(p, 0.0, y0, float(t[-1]), t, rtol, W * rtol * 1e-2, 0)
        if status != 0 or m != t.size:
            raise RuntimeError(f"status {status}")
        return Y.T, nfev
    return f


def scipy_lsoda(p, y0, t, rtol):
    out = dynamics._scipy(p, "LSODA", y0, t, rtol, W * rtol * 1e-2, None)
    if out["status"] != 0:
        raise RuntimeError(out["message"])
    return out["y"], out["nfev"]


def numbalsoda_methods():
    try:
        import numbalsoda
    except ImportError as e:
        print(f"numbalsoda: skipped, not importable ({e})")
        return {}
    import numba
    from numba import types

    rhs_into, record = clearance.rhs_into, clearance.record
    sig = types.void(types.double, types.CPointer(types.double), types.CPointer(types.double),
                     types.CPointer(types.double))

    @numba.cfunc(sig)
    def rhs_scaled(t, z_, dz_, a_):         # z = y / W: a scalar atol is the project's atol
        z = numba.carray(z_, (4,))
        dz = numba.carray(dz_, (4,))
        a = numba.carray(a_, (24,))
        y = np.empty(4)
        for i in range(4):
            y[i] = z[i] * W[i]
        rhs_into(t, y, record(a), dz)
        for i in range(4):
            dz[i] /= W[i]

    ptr = rhs_scaled.address

    def make(driver, mxstep):
        def f(p, y0, t, rtol):
            with quiet_c_stdout():
                Z, ok = driver(ptr, y0 / W, t, data=clearance.flat(p), rtol=rtol,
                               atol=rtol * 1e-2, mxstep=mxstep)
            if not ok:
                raise RuntimeError("not successful (mxstep or step size)")
            return (Z * W).T, None
        return f
    return {"numbalsoda LSODA": make(numbalsoda.lsoda, 100_000),
            "numbalsoda DOP853": make(numbalsoda.dop853, 200_000)}


def sundae_methods():
    try:
        from sksundae.cvode import CVODE
    except ImportError as e:
        print(f"scikit-sundae: skipped, not importable ({e})")
        return {}
    from mechrepro.compiled import jit

    @jit
    def rhs(t, y, yp, a):
        clearance.rhs_into(t, y, clearance.record(a), yp)

    @jit
    def jac(t, y, J, a):
        clearance.jac_into(t, y, clearance.record(a), J)

    def f(p, y0, t, rtol):
        a = clearance.flat(p)
        solver = CVODE(lambda t_, y, yp: rhs(t_, y, yp, a), method="BDF", rtol=rtol,
                       atol=W * rtol * 1e-2, linsolver="dense", max_num_steps=100_000,
                       jacfn=lambda t_, y, yp, J: jac(t_, y, J, a))
        sol = solver.solve(t, y0)
        if not sol.success:
            raise RuntimeError(sol.message)
        return sol.y.T, sol.nfev
    return {"sksundae CVODE BDF": f}


# --- the benchmark -----------------------------------------------------------------------
def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--rtols", type=float, nargs="+", default=[10 ** (-k / 2) for k in range(8, 25)])
    args = ap.parse_args()
    fb, s, p, y0, t = problem()
    methods = {"own Radau": own(radau), "own BDF": own(bdf), "scipy LSODA": scipy_lsoda,
               **numbalsoda_methods(), **sundae_methods()}
    #: the slow baselines only where they take under ~1 s a call
    limits = {"scipy LSODA": 1e-7, "numbalsoda DOP853": 1e-5}

    for name, f in methods.items():                 # compile / load every kernel first
        try:
            f(p, y0, t[:3], 1e-6)
        except Exception:                            # noqa: BLE001
            pass
    ref = quantities(fb, s, p, t, own(radau)(p, y0, t, 1e-12)[0])
    ref13 = quantities(fb, s, p, t, own(radau)(p, y0, t, 1e-13)[0])
    print(f"period {fb.period:.4g} s, {t.size} output points")
    print("reference own Radau rtol 1e-12 vs 1e-13: F_N %.1e, mean force %.1e, wear %.1e"
          % errors(ref13, ref))

    rows = []
    for rtol in args.rtols:
        best = {}
        for _ in range(args.repeats):              # interleaved: same load for every method
            for name, f in methods.items():
                if rtol < limits.get(name, 0.0) or best.get(name) == "fail":
                    continue
                t0 = time.perf_counter()
                try:
                    Y, nfev = f(p, y0, t, rtol)
                except Exception as e:             # noqa: BLE001 (a failure is a result)
                    best[name] = "fail"
                    msg = f"{str(e)[:60]} after {(time.perf_counter() - t0) * 1e3:.0f} ms"
                    rows.append((name, rtol, None, msg, None))
                    continue
                dt = time.perf_counter() - t0
                if name not in best or dt < best[name][0]:
                    best[name] = (dt, Y, nfev)
        for name, b in best.items():
            if b != "fail":
                rows.append((name, rtol, b[0], errors(quantities(fb, s, p, t, b[1]), ref), b[2]))

    radau_runs = [(r[2], r[3]) for r in rows if r[0] == "own Radau" and r[2] is not None]

    def ratio(err, dt, k):
        """dt over the cheapest own Radau run at least as accurate in quantity k (no
        interpolation: Radau's decade steps make this favour the candidate)."""
        ok = [x for x, e in radau_runs if e[k] <= err[k]]
        return f"{dt / min(ok):.2f}" if ok else "-"

    print(f"\n{'method':20s} {'rtol':>7s} {'time ms':>9s} {'RHS calls':>9s} {'err F_N':>8s} "
          f"{'err mean':>8s} {'err wear':>8s} {'xRadau F_N':>10s} {'xRadau wear':>11s}")
    for name in methods:
        for n, rtol, dt, e, nfev in rows:
            if n != name:
                continue
            if dt is None:
                print(f"{name:20s} {rtol:7.1e}  FAILED: {e}")
            else:
                print(f"{name:20s} {rtol:7.1e} {dt * 1e3:9.2f} {nfev or '-':>9} {e[0]:8.1e} "
                      f"{e[1]:8.1e} {e[2]:8.1e} {ratio(e, dt, 0):>10s} {ratio(e, dt, 2):>11s}")

if __name__ == "__main__":
    main()
