"""Dynamic clearance joint B: stiff Lankarani-Nikravesh contact integrated implicitly.

The right-hand side and its analytic contact Jacobian are :mod:`.clearance` (written once,
compiled with numba where installed).  The integrators are scipy's algorithms: Radau (the
default), BDF and RK45 in compiled copies (:mod:`.radau`, :mod:`.bdf`, :mod:`.rk45`: the
same steps to round-off, without scipy's per-step Python), the others scipy's own.
"""
from __future__ import annotations

import math

import numpy as np

from mechrepro.errors import Refusal

from . import clearance
from .geometry import FourBar


def initial_state(fb: FourBar, start: str = "concentric", t0: float = 0.0):
    """Initial state at t0.

    ``concentric``: the pin centred in the bushing, ideal-mechanism velocities (Sec. 4.1):
    the first impact excites the clearance's lightly damped rocking mode (~1e3 rad/s).
    ``equilibrium`` (the settled start): positions and rates of the quasi-static
    continuous-contact solution with clearance kinematics (quasistatic.py), the state the
    dynamic joint settles on: a steady period is integrated from its first step.
    """
    from . import kinematics, quasistatic

    if start == "equilibrium":
        qs = quasistatic.one_period(fb, 720, t0=t0, settled=True)
        return np.array([qs["theta3"][0], qs["phi2"][0], qs["w3"][0], qs["w2"][0]])
    if start != "concentric":
        raise Refusal(f"joint_wear: initial state {start!r}: allowed concentric, equilibrium")
    th1 = fb.omega * t0
    th3, ph2 = kinematics.positions(fb, th1)
    w3, w2 = kinematics.velocities(fb, th1, th3, ph2)
    return np.array([float(th3), float(ph2), float(w3), float(w2)])


METHODS = ("Radau", "BDF", "LSODA", "RK45")
IMPLICIT = ("Radau", "BDF", "LSODA")
#: the methods with a compiled copy of scipy's algorithm (the others step scipy's)
COMPILED = ("Radau", "BDF", "RK45")
TOO_SMALL_STEP = "Required step size is less than spacing between numbers."


def simulate(fb: FourBar, t_end: float, n_out: int, method: str = "Radau",
             rtol: float = 1e-5, damping: bool = True, start: str = "concentric",
             max_steps: int | None = None,
             t_start: float = 0.0, kernel: str = "auto") -> dict:
    """Integrate the clearance joint over [t_start, t_end], sample n_out uniform points.

    atol on angles is rtol / 100 [rad] (on rates 10x that): the clearance is
    ~3e-4 of the link lengths, so an angle tolerance of rtol alone would let the
    penetration (~1 um) drown in the error.  A step budget ``max_steps`` (never a wall-clock
    one: where the integration stops must not depend on the machine's load) can stop an
    integrator that cannot finish and still report how far it got.
    status: 0 finished, -1 integrator failure, -2 step budget spent.
    ``kernel``: ``"auto"`` runs the methods of :data:`COMPILED` compiled where numba is
    installed; ``"scipy"`` steps scipy's solver (the two agree to round-off).
    """
    if method not in METHODS:
        raise Refusal(f"joint_wear: method {method!r}: allowed {', '.join(METHODS)}")
    if kernel not in ("auto", "scipy"):
        raise Refusal(f"joint_wear: kernel {kernel!r}: allowed auto, scipy")
    p = clearance.params(fb, damping)
    y0 = initial_state(fb, start, t_start)
    atol = np.array([1.0, 1.0, 10.0, 10.0]) * rtol * 1e-2
    t_eval = np.linspace(t_start, t_end, n_out)
    if method in COMPILED and kernel == "auto" and clearance.available():
        out = _compiled(method, p, y0, t_eval, rtol, atol, max_steps)
    else:
        out = _scipy(p, method, y0, t_eval, rtol, atol, max_steps)
    out.update(contact_history(p, out["t"], out["y"]))
    return out


def _scipy(p, method, y0, t_eval, rtol, atol, max_steps) -> dict:
    """Step scipy's solver by hand (its OdeSolver API, what ``solve_ivp`` does inside, so
    that a step budget can stop it), sampling each step's dense output at the samples the
    step holds."""
    from scipy import integrate

    from mechrepro.timing import phase

    a = clearance.flat(p)
    kw = {"jac": lambda t, y: clearance.jac(t, y, a)} if method in IMPLICIT else {}
    solver = getattr(integrate, method)(lambda t, y: clearance.rhs(t, y, a), t_eval[0], y0,
                                        t_eval[-1], rtol=rtol, atol=atol, **kw)
    T, Y = [t_eval[0]], [y0]
    k = 1
    steps = 0
    status, message = 0, "finished"
    te = t_eval.tolist() + [math.inf]
    with phase("joint_wear.scipy_integration") as sw:
        while solver.status == "running":
            msg = solver.step()
            steps += 1
            if solver.status == "failed":
                status, message = -1, str(msg)
                break
            if solver.t >= te[k]:    # the step holds samples (most hold none)
                j = np.searchsorted(t_eval, solver.t, side="right")
                sol = solver.dense_output()
                ts = t_eval[k:j]
                T.extend(ts)
                Y.extend(np.atleast_2d(sol(ts)).T)
                k = j
            if max_steps is not None and steps >= max_steps and solver.status == "running":
                status, message = -2, f"step budget {max_steps} spent at t = {solver.t:.4g} s"
                break
    return {"t": np.asarray(T), "y": np.asarray(Y).T, "status": status, "message": message,
            "nfev": int(solver.nfev), "steps": steps, "t_reached": float(solver.t),
            "wall": sw.seconds}


def _kernels() -> dict:
    """The compiled integrators of :data:`COMPILED` by name."""
    from .bdf import bdf
    from .radau import radau
    from .rk45 import rk45
    return {"Radau": radau, "BDF": bdf, "RK45": rk45}


def _compiled(method, p, y0, t_eval, rtol, atol, max_steps) -> dict:
    """:func:`_scipy` for a method of :data:`COMPILED`, its compiled copy (one call)."""
    from mechrepro.timing import phase

    with phase("joint_wear.compiled_integration") as sw:
        Yout, m, nfev, steps, status, t_reached = _kernels()[method](
            p, float(t_eval[0]), np.asarray(y0, float), float(t_eval[-1]), t_eval,
            float(rtol), np.asarray(atol, float), int(max_steps or 0))
    message = {0: "finished", -1: TOO_SMALL_STEP}.get(
        int(status), f"step budget {max_steps} spent at t = {t_reached:.4g} s")
    return {"t": t_eval[:m].copy(), "y": np.ascontiguousarray(Yout[:m].T),
            "status": int(status), "message": message, "nfev": int(nfev),
            "steps": int(steps), "t_reached": float(t_reached), "wall": sw.seconds}


def contact_history(p: clearance.Params, T, Y) -> dict:
    """Penetration, forces, sliding velocity and the contact angle on the bushing."""
    h = clearance.history(np.asarray(T, float), np.ascontiguousarray(Y, dtype=float), p)
    return {"F_N": h[0], "F_T": h[1], "delta": h[2], "v_T": h[3],
            "psi": np.angle(np.exp(1j * h[4])), "theta3": Y[0], "phi2": Y[1]}


_WARM: set = set()     # what warm() has loaded in this process: "physics" and methods


def warm(methods=COMPILED) -> None:
    """Load (or, on a fresh clone, compile) the compiled kernels once per process, with the
    argument types the solvers use, so that a period's measured time is not numba's
    one-time start: the physics, the quasi-static stages, the groove's balance, Radau
    (constant_sensitivity steps it whatever the scene names) and the other COMPILED
    integrators of ``methods`` (one no run steps is not compiled).  Changes no result."""
    if not clearance.available():
        return
    todo = [m for m in COMPILED if m in {"Radau", *methods} and m not in _WARM]
    if not todo and "physics" in _WARM:
        return
    from . import groove, qs_numba as q

    p = clearance.Params(*np.ones(len(clearance.Params._fields)))
    y, te, at = np.zeros(4), np.zeros(1), np.ones(4)
    for m in todo:
        _kernels()[m](p, 0.0, y, 0.0, te, 1e-5, at, 0)
        _WARM.add(m)
    if "physics" in _WARM:
        return
    clearance.history(te, np.zeros((4, 1)), p)
    clearance.rhs(0.0, y, clearance.flat(p))
    clearance.jac(0.0, y, clearance.flat(p))
    a, r, m = np.zeros(2), np.ones(1), np.zeros((1, 2))
    b = q.setup(m, m, m, m, m, m, 1.0, 1.0, 0.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 2.0, 0.0, 0.0)
    F_N, ang, delta = q.force(*b, m, m, 0.0, r, 1.5)
    q.friction(F_N, delta, m, 0.0, m, r, 1.0, 0.0, r)
    q.contact_angle(a, a)
    q.periodic_part(np.zeros((2, 2)), 2)
    groove._solve_offset_kernel(r, m, a, a, a, m, r, m, m, 1e-6, 0, 1.0)
    _WARM.add("physics")
