"""Dynamic clearance joint B: stiff Lankarani-Nikravesh contact integrated implicitly.

State y = (theta3, phi2, dtheta3/dt, dphi2/dt) -- the two extra DOF of the clearance
joint in minimal coordinates (see loads.py).  The right-hand side is written with scalar
``math`` calls: for a 4-state system the numpy call overhead would dominate, and the
integrator (scipy ``solve_ivp``, Radau by default) calls it a few thousand times per
period.  The Jacobian of the contact force (Eqs. 11, 14, 15 through Eqs. 5-10) is
analytic; the slow, non-stiff parts (mass-matrix variation, velocity terms) are left out
of it, which only affects Newton convergence, never the solution.

Effects: friction off -> mu = 0; contact_damping off -> the K'' term is never evaluated.
"""
from __future__ import annotations

import math

import numpy as np

from mechrepro.errors import Refusal

from . import loads
from .geometry import FourBar


class ClearanceJoint:
    """Right-hand side and Jacobian of one configuration, closures over plain floats."""

    def __init__(self, fb: FourBar, damping: bool = True):
        self.fb = fb
        self.damping = damping
        self.M11, self.M22, self.am = loads.mass_terms(fb)
        self.nfev = 0

    # --- contact -----------------------------------------------------------------
    def _contact(self, t, th3, ph2, w3, w2):
        """Force on the bushing (fx, fy), friction F_T and the geometry, Eqs. (5)-(15)."""
        fb = self.fb
        c3, s3, c2, s2 = math.cos(th3), math.sin(th3), math.cos(ph2), math.sin(ph2)
        th1 = fb.omega * t
        c1, s1 = math.cos(th1), math.sin(th1)
        # Eq. (5): e = r_i - r_j, and its rate
        ex = fb.l1 * c1 - (fb.l0 + fb.l3 * c3 + fb.l2 * c2)
        ey = fb.l1 * s1 - (fb.l3 * s3 + fb.l2 * s2)
        edx = -fb.l1 * fb.omega * s1 - (-fb.l3 * w3 * s3 - fb.l2 * w2 * s2)
        edy = fb.l1 * fb.omega * c1 - (fb.l3 * w3 * c3 + fb.l2 * w2 * c2)
        e = math.hypot(ex, ey)                               # Eq. (6)
        delta = e - fb.clearance                             # Eq. (8)
        geo = (c3, s3, c2, s2, ex, ey, edx, edy, e, delta)
        if delta <= 0.0:
            return 0.0, 0.0, 0.0, 0.0, geo
        nx, ny = ex / e, ey / e                              # Eq. (7)
        tx, ty = -ny, nx
        vN = edx * nx + edy * ny                             # Eq. (9)
        vT = edx * tx + edy * ty + fb.omega * fb.R_pin - w2 * fb.R_bush   # Eq. (10)
        FN = fb.K_contact * delta ** fb.n_exp                # Eq. (11), elastic part
        if self.damping:
            x = delta / fb.d_max
            K2 = fb.C_max if x >= 1.0 else fb.C_max * x * x * (3.0 - 2.0 * x)   # Eq. (14)
            FN += K2 * vN
        if FN < 0.0:
            FN = 0.0
        FT = 0.0
        if fb.mu:
            FT = fb.mu * FN * vT / math.sqrt(vT * vT + fb.v_eps * fb.v_eps)   # Eq. (15)
        return FN * nx + FT * tx, FN * ny + FT * ty, FN, FT, geo

    def rhs(self, t, y):
        self.nfev += 1
        fb = self.fb
        th3, ph2, w3, w2 = y
        fx, fy, FN, FT, (c3, s3, c2, s2, *_rest) = self._contact(t, th3, ph2, w3, w2)
        # applied loads (load P at E towards F, gravity) -- scalar copy of loads.applied_forces
        exx, eyy = fb.l0 + 0.5 * fb.l3 * c3, 0.5 * fb.l3 * s3
        dx, dy = fb.F[0] - exx, fb.F[1] - eyy
        dn = math.hypot(dx, dy)
        Px, Py = fb.P * dx / dn, fb.P * dy / dn
        Q3 = 0.5 * fb.l3 * (-s3 * Px + c3 * Py) - fb.g * (0.5 * fb.m3 * fb.l3 + fb.m2 * fb.l3) * c3
        Q2 = -fb.g * fb.m2 * 0.5 * fb.l2 * c2
        # contact: J^T f + moment R_j F_T on the coupler
        Q3 += fb.l3 * (-s3 * fx + c3 * fy)
        Q2 += fb.l2 * (-s2 * fx + c2 * fy) + fb.R_bush * FT
        cd = c3 * c2 + s3 * s2
        sd = s3 * c2 - c3 * s2
        b3 = Q3 - self.am * sd * w2 * w2
        b2 = Q2 + self.am * sd * w3 * w3
        m12 = self.am * cd
        det = self.M11 * self.M22 - m12 * m12
        return [w3, w2, (self.M22 * b3 - m12 * b2) / det, (self.M11 * b2 - m12 * b3) / det]

    def jac(self, t, y):
        """d rhs / d y: exact contact terms (stiffness, damping, friction); M(q) frozen."""
        fb = self.fb
        th3, ph2, w3, w2 = y
        J = np.zeros((4, 4))
        J[0, 2] = J[1, 3] = 1.0
        _, _, FN, FT, (c3, s3, c2, s2, ex, ey, edx, edy, e, delta) = self._contact(t, th3, ph2, w3, w2)
        if delta <= 0.0 or FN <= 0.0:
            return J
        n = np.array([ex / e, ey / e])
        tt = np.array([-n[1], n[0]])
        ed = np.array([edx, edy])
        vN, vTe = ed @ n, ed @ tt
        vT = vTe + fb.omega * fb.R_pin - w2 * fb.R_bush
        # dF_N / de and dF_N / d(edot)
        dFN_de = fb.n_exp * fb.K_contact * delta ** (fb.n_exp - 1.0) * n
        dFN_ded = np.zeros(2)
        if self.damping:
            x = delta / fb.d_max
            if x < 1.0:
                K2 = fb.C_max * x * x * (3.0 - 2.0 * x)
                dK2 = fb.C_max * (6.0 * x - 6.0 * x * x) / fb.d_max
            else:
                K2, dK2 = fb.C_max, 0.0
            dFN_de = dFN_de + dK2 * vN * n + K2 * vTe / e * tt
            dFN_ded = K2 * n
        s = vT / math.sqrt(vT * vT + fb.v_eps ** 2)
        ds = fb.v_eps ** 2 / (vT * vT + fb.v_eps ** 2) ** 1.5
        dvT_de = -vN / e * tt
        dFT_de = fb.mu * (s * dFN_de + FN * ds * dvT_de)
        dFT_ded = fb.mu * (s * dFN_ded + FN * ds * tt)
        dFT_dw2 = fb.mu * FN * ds * (-fb.R_bush)
        # f = F_N n + F_T t
        df_de = (np.outer(n, dFN_de) + FN / e * np.outer(tt, tt)
                 + np.outer(tt, dFT_de) - FT / e * np.outer(n, tt))
        df_ded = np.outer(n, dFN_ded) + np.outer(tt, dFT_ded)
        Jb = np.array([[-fb.l3 * s3, -fb.l2 * s2], [fb.l3 * c3, fb.l2 * c2]])  # d r_j / d q
        # e = r_i - r_j(q), edot = rdot_i - Jb qdot
        # edot = rdot_i - Jb(q) qdot also depends on q: d edot / dq = [l3 w3 u3, l2 w2 u2]
        dedq = np.array([[fb.l3 * w3 * c3, fb.l2 * w2 * c2], [fb.l3 * w3 * s3, fb.l2 * w2 * s2]])
        dQ_dq = Jb.T @ (df_de @ (-Jb) + df_ded @ dedq)
        dQ_dq[1] += fb.R_bush * (dFT_de @ (-Jb) + dFT_ded @ dedq)
        dQ_dw = Jb.T @ df_ded @ (-Jb)
        dQ_dw[1] += fb.R_bush * (dFT_ded @ (-Jb))
        dQ_dw[:, 1] += Jb.T @ (tt * dFT_dw2)
        dQ_dw[1, 1] += fb.R_bush * dFT_dw2
        m12 = self.am * (c3 * c2 + s3 * s2)
        Minv = np.linalg.inv(np.array([[self.M11, m12], [m12, self.M22]]))
        J[2:, :2] = Minv @ dQ_dq
        J[2:, 2:] = Minv @ dQ_dw
        return J


def initial_state(fb: FourBar, start: str = "concentric", t0: float = 0.0):
    """Initial state at t0.

    ``concentric``: the pin centred in the bushing, ideal-mechanism velocities (Sec. 4.1):
    the first impact excites the clearance's lightly damped "pendulum" mode (the pin
    rocking on the bushing, omega ~ sqrt(F_N / (c m)) ~ 1e3 rad/s) which friction barely
    damps once it saturates -- slow to integrate, and its amplitude is then set by the
    integrator's numerical damping.  ``equilibrium`` (the settled start): positions and
    rates of the quasi-static continuous-contact solution with clearance kinematics
    (quasistatic.py), the state the dynamic joint settles on; it leaves the rocking mode
    unexcited to ~1e-4 deg, so a steady period is integrated from its first step.
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


METHODS = {"Radau": "Radau", "BDF": "BDF", "LSODA": "LSODA", "RK45": "RK45",
           "DOP853": "DOP853", "RK23": "RK23"}
IMPLICIT = ("Radau", "BDF", "LSODA")


def simulate(fb: FourBar, t_end: float, n_out: int, method: str = "Radau",
             rtol: float = 1e-5, damping: bool = True, start: str = "concentric",
             atol_scale: float = 1e-2, max_steps: int | None = None,
             t_start: float = 0.0, kernel: str = "auto") -> dict:
    """Integrate the clearance joint over [t_start, t_end], sample n_out uniform points.

    atol on angles is rtol * atol_scale [rad] (on rates 10x that): the clearance is
    ~3e-4 of the link lengths, so an angle tolerance of rtol alone would let the
    penetration (~1 um) drown in the error.  The solver is stepped by hand (scipy's
    OdeSolver API, what solve_ivp does inside) so that a *step budget* ``max_steps`` can
    stop an integrator that cannot finish -- an explicit one on the stiff contact -- and
    still report how far it got.  A step budget, never a wall-clock one: where the
    integration stops must not depend on the machine's load.
    status: 0 finished, -1 integrator failure, -2 step budget spent.

    ``kernel``: ``"auto"`` runs Radau and RK45 in the compiled loop of
    :mod:`.ivp_kernel` (the same algorithms as scipy's, one call per period) when numba is
    installed, every other method -- and everything without numba -- by stepping scipy's
    solvers (``"scipy"``); the results agree to round-off.
    """
    from mechrepro.timing import stopwatch

    from . import ivp_kernel

    if method not in METHODS:
        raise Refusal(f"joint_wear: method {method!r}: allowed {', '.join(METHODS)}")
    if kernel not in ("auto", "scipy", "numba"):
        raise Refusal(f"joint_wear: kernel {kernel!r}: allowed auto, scipy, numba")
    sys_ = ClearanceJoint(fb, damping=damping)
    y0 = initial_state(fb, start, t_start)
    atol = np.array([1.0, 1.0, 10.0, 10.0]) * rtol * atol_scale
    compiled = method in COMPILED and (kernel == "numba" or (kernel == "auto"
                                                             and ivp_kernel.available()))
    if compiled:
        return _simulate_compiled(sys_, method, y0, t_start, t_end, n_out, rtol, atol, max_steps)
    if method == "LSODA" and kernel != "scipy" and ivp_kernel.available():
        return _simulate_lsoda(sys_, y0, t_start, t_end, n_out, rtol, atol, max_steps)
    from scipy import integrate

    kw = {"jac": sys_.jac} if method in IMPLICIT else {}
    solver = getattr(integrate, METHODS[method])(sys_.rhs, t_start, y0, t_end, rtol=rtol,
                                                 atol=atol, **kw)
    t_eval = np.linspace(t_start, t_end, n_out)
    T, Y = [t_start], [y0]
    k = 1
    steps = 0
    status, message = 0, "finished"
    with stopwatch() as sw:
        while solver.status == "running":
            msg = solver.step()
            steps += 1
            if solver.status == "failed":
                status, message = -1, str(msg)
                break
            # samples inside this step, from the step's dense output
            j = np.searchsorted(t_eval, solver.t, side="right")
            if j > k:
                sol = solver.dense_output()
                ts = t_eval[k:j]
                T.extend(ts)
                Y.extend(np.atleast_2d(sol(ts)).T)
                k = j
            if max_steps is not None and steps >= max_steps and solver.status == "running":
                status, message = -2, f"step budget {max_steps} spent at t = {solver.t:.4g} s"
                break
    wall = sw.seconds
    T, Y = np.asarray(T), np.asarray(Y).T
    out = {"t": T, "y": Y, "status": status, "message": message, "nfev": sys_.nfev,
           "steps": steps, "t_reached": float(solver.t), "wall": wall}
    out.update(contact_history(sys_, T, Y))
    return out


COMPILED = ("Radau", "BDF", "RK45")
TOO_SMALL_STEP = "Required step size is less than spacing between numbers."


def _simulate_compiled(sys_: ClearanceJoint, method, y0, t_start, t_end, n_out, rtol, atol,
                       max_steps) -> dict:
    """:func:`simulate` with the compiled Radau / RK45 of :mod:`.ivp_kernel`."""
    from mechrepro.timing import stopwatch

    from . import ivp_kernel

    k = ivp_kernel.kernels()
    p = ivp_kernel.params(sys_.fb, sys_.damping)
    t_eval = np.linspace(t_start, t_end, n_out)
    fn = {"Radau": k["radau"], "BDF": k["bdf"], "RK45": k["rk45"]}[method]
    with stopwatch() as sw:
        Yout, m, nfev, steps, status, t_reached = fn(p, float(t_start), np.asarray(y0, float),
                                                     float(t_end), t_eval, float(rtol),
                                                     np.asarray(atol, float),
                                                     int(max_steps or 0))
    wall = sw.seconds
    sys_.nfev += int(nfev)
    message = {0: "finished", -1: TOO_SMALL_STEP}.get(
        int(status), f"step budget {max_steps} spent at t = {t_reached:.4g} s")
    T, Y = t_eval[:m].copy(), np.ascontiguousarray(Yout[:m].T)
    out = {"t": T, "y": Y, "status": int(status), "message": message, "nfev": sys_.nfev,
           "steps": int(steps), "t_reached": float(t_reached), "wall": wall}
    out.update(contact_history(sys_, T, Y))
    return out


def _simulate_lsoda(sys_: ClearanceJoint, y0, t_start, t_end, n_out, rtol, atol,
                    max_steps) -> dict:
    """:func:`simulate` for LSODA with compiled callbacks: the Fortran integrator set up and
    stepped (one step per call, ``itask = 5``, ``tcrit = t_end``) exactly as scipy's
    ``LSODA`` solver does, its dense output (the Nordsieck history) evaluated here only in
    steps that hold samples -- without the ``OdeSolver`` wrappers around every step."""
    from scipy.integrate import ode

    from mechrepro.timing import stopwatch

    from . import ivp_kernel

    k = ivp_kernel.kernels()
    p = ivp_kernel.params(sys_.fb, sys_.damping)
    f, jac = k["rhs_new"], k["jac_new"]     # called by the Fortran code as f(t, y, p)
    n = 4
    solver = ode(f, jac)
    solver.set_integrator("lsoda", rtol=rtol, atol=atol, max_step=0, min_step=0.0,
                          first_step=0, lband=None, uband=None)
    solver.set_initial_value(np.asarray(y0, float), t_start)
    integ = solver._integrator
    integ.rwork[0] = t_end
    integ.call_args[4] = integ.rwork
    integ.call_args[2] = 5
    rwork, iwork = integ.rwork, integ.iwork
    t_eval = np.linspace(t_start, t_end, n_out)
    Yout = np.empty((n_out, n))
    Yout[0] = y0
    y, t = solver._y, float(t_start)
    kk, steps = 1, 0
    status, message = 0, "finished"
    with stopwatch() as sw:
        while t != t_end:
            y, t = integ.run(f, jac, y, t, t_end, (p,), (p,))
            steps += 1
            if not integ.success:
                status, message = -1, "Unexpected istate in LSODA."
                break
            j = int(np.searchsorted(t_eval, t, side="right"))
            if j > kk:      # LsodaDenseOutput of this step
                order = iwork[13]
                h = rwork[11]
                yh = np.reshape(rwork[20:20 + (order + 1) * n], (n, order + 1),
                                order="F").copy()
                if iwork[14] < order:
                    yh[:, -1] *= (h / rwork[10]) ** order
                x = ((t_eval[kk:j] - t) / h) ** np.arange(order + 1)[:, None]
                Yout[kk:j] = np.dot(yh, x).T
                kk = j
            if t >= t_end:
                break
            if max_steps is not None and steps >= max_steps:
                status, message = -2, f"step budget {max_steps} spent at t = {t:.4g} s"
                break
    wall = sw.seconds
    sys_.nfev += int(iwork[11])          # NFE: right-hand sides evaluated by LSODA
    T, Y = t_eval[:kk].copy(), np.ascontiguousarray(Yout[:kk].T)
    out = {"t": T, "y": Y, "status": status, "message": message, "nfev": sys_.nfev,
           "steps": steps, "t_reached": float(t), "wall": wall}
    out.update(contact_history(sys_, T, Y))
    return out


def contact_history(sys_: ClearanceJoint, T, Y) -> dict:
    """Penetration, forces, sliding velocity and the contact angle on the bushing."""
    from . import ivp_kernel

    if ivp_kernel.available():
        h = ivp_kernel.kernels()["history"](np.asarray(T, float), np.ascontiguousarray(Y),
                                            ivp_kernel.params(sys_.fb, sys_.damping))
        psi = np.angle(np.exp(1j * h[4]))
        return {"F_N": h[0], "F_T": h[1], "delta": h[2], "v_T": h[3], "psi": psi,
                "theta3": Y[0], "phi2": Y[1]}
    n = T.size
    FN, FT, dl, vT, psi = (np.zeros(n) for _ in range(5))
    fb = sys_.fb
    for k in range(n):
        th3, ph2, w3, w2 = Y[:, k]
        _, _, FN[k], FT[k], geo = sys_._contact(T[k], th3, ph2, w3, w2)
        ex, ey, edx, edy, e, delta = geo[4:]
        dl[k] = delta
        nx, ny = ex / e if e else 1.0, ey / e if e else 0.0
        vT[k] = edx * -ny + edy * nx + fb.omega * fb.R_pin - w2 * fb.R_bush
        psi[k] = math.atan2(ny, nx) - ph2
    psi = np.angle(np.exp(1j * psi))
    return {"F_N": FN, "F_T": FT, "delta": dl, "v_T": vT, "psi": psi,
            "theta3": Y[0], "phi2": Y[1]}
