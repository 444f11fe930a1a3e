"""Compiled integrators of the clearance joint (numba, cached on disk).

The dynamic period is a 4-state system integrated a few hundred (Radau) to a few thousand
(RK45, step budget) steps; scipy's ``OdeSolver`` spends ~2 ms of Python per Radau step
(array wrappers, ``lu_factor``/``lu_solve`` on 4x4 matrices, the dense output objects)
against ~1 us of arithmetic.  This module is the *same algorithms* as scipy 1.17's
``Radau`` and ``RK45`` (``scipy/integrate/_ivp/radau.py``, ``rk.py``, ``common.py``: the
initial step, the simplified Newton iteration on the transformed collocation system, its
convergence and Jacobian-reuse rules, the error estimate and the step-size controller,
the dense output) with the right-hand side and the analytic Jacobian of
:class:`.dynamics.ClearanceJoint` inlined, and the sampling at ``t_eval`` of
:func:`.dynamics.simulate` -- one compiled call per period.  Only the summation order of a
few 3- and 4-term dot products and the 4x4 LU (partial pivoting written out, as LAPACK's
``getrf`` pivots) differ, so results agree with the scipy path to round-off
(``tests/test_joint_wear_kernel.py``).

Import is lazy (numba costs ~0.3 s to import, the cached kernels ~0.2 s to load);
:func:`available` says whether numba is installed.  Without it :func:`.dynamics.simulate`
steps scipy's solvers, with the same results to round-off.  The choice depends on
whether numba is installed only, never on what ran before in the process.
"""
from __future__ import annotations

import numpy as np

_K = None

# parameter vector layout (see :func:`params`)
(L1, L2, L3, L0, OMEGA, PLOAD, FX, FY, GRAV, M2, M3, RPIN, RBUSH, KC, NEXP, DMAX, CMAX, MU,
 VEPS, CLR, M11, M22, AM, DAMP) = range(24)


def available() -> bool:
    try:
        import numba  # noqa: F401
    except ImportError:
        return False
    return True


def params(fb, damping: bool) -> np.ndarray:
    from . import loads

    M11_, M22_, am = loads.mass_terms(fb)
    return np.array([fb.l1, fb.l2, fb.l3, fb.l0, fb.omega, fb.P, fb.F[0], fb.F[1], fb.g,
                     fb.m2, fb.m3, fb.R_pin, fb.R_bush, fb.K_contact, fb.n_exp, fb.d_max,
                     fb.C_max, fb.mu, fb.v_eps, fb.clearance, M11_, M22_, am,
                     1.0 if damping else 0.0], dtype=float)


def kernels():
    global _K
    if _K is None:
        from . import ivp_numba as m

        _K = {"rhs": m.rhs, "jac": m.jac, "radau": m.radau, "rk45": m.rk45,
              "history": m.history, "rhs_new": m.rhs_new, "jac_new": m.jac_new, "bdf": m.bdf}
    return _K


_WARM = False


def warm() -> None:
    """Load (or, on a fresh clone, compile) every compiled kernel once per process, with the
    argument types the solvers use, so that a period's measured time is the period's and
    not numba's one-time start (~1 s per process).  Changes no result."""
    global _WARM
    if _WARM or not available():
        return
    from . import qs_numba as q

    k = kernels()
    p = np.zeros(24)
    p[[L1, L2, L3, L0, OMEGA, M11, M22, KC, NEXP, DMAX, CLR]] = 1.0
    y = np.zeros(4)
    te = np.zeros(1)
    at = np.ones(4)
    for name in ("radau", "bdf", "rk45"):
        k[name](p, 0.0, y, 0.0, te, 1e-5, at, 0)
    k["history"](te, np.zeros((4, 1)), p)
    k["rhs_new"](0.0, y, p)
    k["jac_new"](0.0, y, p)
    a = np.zeros(2)
    b = q.setup(a, a, a, a, a, a, 1.0, 1.0, 0.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 2.0, 0.0, 0.0)
    F_N, ang, delta = q.force(*b, a, a, 0.0, 1.0, 1.5)
    q.friction(F_N, delta, a, 0.0, a, 1.0, 1.0, 0.0, 1.0)
    q.direction(ang, a)
    _WARM = True
