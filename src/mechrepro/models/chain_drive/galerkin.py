"""High-speed model: Galerkin discretisation of the coupled transverse/longitudinal span,
Eqs. (2-39) to (2-41), integrated by classical RK4 (the paper) or scipy's solve_ivp.

    u1 = sum_j psi_j(t) cos(j pi x/L)                          (free-free rod modes)
    u2 = sum_j phi_j(t) sin(j pi x/L) + (L-x)/L g(t) + x/L h(t) (string modes + end motion)

The projections of (2-40) (with its boundary terms) on cos(k pi x/L) and of (2-41) on
sin(k pi x/L) are evaluated by Gauss-Legendre quadrature; the linear parts are assembled
once as matrices, the cubic/quadratic coupling terms at every right-hand-side call.

The end motions of Eqs. (2-24)/(2-25) have velocity jumps at every tooth (the chordal
kinks), so their acceleration is impulsive.  The state therefore carries the modal
"momentum" z = phi' + beta(t), beta = projection of the end-motion velocity on the sine
modes: only g, h, g', h' enter, never g'', h''.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from mechrepro.timing import phase
from mechrepro.units import var

from . import four_bar, galerkin_kernel, geometry, loads
from .effects import EFFECTS, SpanContext, refuse_unhonoured
from .geometry import RPM, span_geometry
from .span import dynamic_tension
from .errors import DivergenceError, KernelUnavailable, RecordError, UnknownChoice


class GalerkinModel:
    def __init__(self, *, L, m, EA, P, c, c_d, n_t: int, n_l: int, n_quad: int | None = None,
                 coupling: bool = True):
        self.L, self.m, self.EA, self.P, self.c, self.c_d = L, m, EA, P, c, c_d
        self.n_t, self.n_l, self.coupling = n_t, n_l, coupling
        nq = n_quad or 4 * max(n_t, n_l) + 16
        xg, wg = np.polynomial.legendre.leggauss(nq)
        self.x = 0.5 * L * (xg + 1)
        self.w = 0.5 * L * wg
        kt = np.arange(1, n_t + 1)[:, None] * np.pi / L
        kl = np.arange(1, n_l + 1)[:, None] * np.pi / L
        x = self.x[None, :]
        self.S, self.Sx, self.Sxx = np.sin(kt * x), kt * np.cos(kt * x), -kt**2 * np.sin(kt * x)
        self.C, self.Cx, self.Cxx = np.cos(kl * x), -kl * np.sin(kl * x), -kl**2 * np.cos(kl * x)
        self.Cend0 = np.ones(n_l)
        self.CendL = np.cos(kl[:, 0] * L)
        W = self.w[None, :]
        # transverse: m(phi'' + 2c phi'_x + c^2 phi_xx) - P phi_xx + c_d(phi' + c phi_x), projected on S
        self.Mt = m * (self.S * W) @ self.S.T
        self.Gt = (self.S * W) @ (2 * m * c * self.Sx.T + c_d * self.S.T)
        self.Kt = (self.S * W) @ ((m * c**2 - P) * self.Sxx.T + c_d * c * self.Sx.T)
        # longitudinal: m(psi'' + 2c psi'_x + c^2 psi_xx) - EA psi_xx projected on C
        self.Ml = m * (self.C * W) @ self.C.T
        self.Gl = (self.C * W) @ (2 * m * c * self.Cx.T)
        self.Kl = (self.C * W) @ ((m * c**2 - EA) * self.Cxx.T)
        self.Mt_inv = np.linalg.inv(self.Mt)
        self.Ml_inv = np.linalg.inv(self.Ml)
        self.lin = (L - self.x) / L, self.x / L
        # beta = B @ (g', h'): sine-mode projection of the end-motion velocity field
        self.B = np.linalg.solve((self.S * W) @ self.S.T,
                                 (self.S * W) @ np.stack(self.lin, axis=1))
        # the quadrature-weighted modes and the mode slopes at the ends, formed once (the
        # right-hand side is called ~10^5 times per run)
        self.SW, self.CW = self.S * self.w, self.C * self.w
        k = np.arange(1, n_t + 1)
        self._Sx0 = k * np.pi / L
        self._SxL = k * np.pi / L * np.cos(k * np.pi)

    def rhs_values(self, y, g, h, gd, hd, Pt):
        """The right-hand side for given end motion (g, h, g', h') and dynamic tension P_t."""
        nt, nl = self.n_t, self.n_l
        phi, psi = y[:nt], y[nt:nt + nl]
        z, dpsi = y[nt + nl:2 * nt + nl], y[2 * nt + nl:]
        dphi = z - self.B @ np.array([gd, hd])
        a0, a1 = self.lin
        L, m, c, c_d = self.L, self.m, self.c, self.c_d
        ub_t = a0 * gd + a1 * hd
        ub_x, ub_xt = (h - g) / L, (hd - gd) / L
        u2x = phi @ self.Sx + ub_x
        u2xx = phi @ self.Sxx
        # end-motion loads without its acceleration (absorbed in z): gyroscopic and damping
        f_b = -(2 * m * c * ub_xt + c_d * (ub_t + c * ub_x))
        ft = -(self.Gt @ dphi) - (self.Kt @ phi) + self.SW @ f_b
        fl = -(self.Gl @ dpsi) - (self.Kl @ psi)
        ex0 = exL = 0.0
        if self.coupling:
            u1x, u1xx = psi @ self.Cx, psi @ self.Cxx
            EA = self.EA
            ft += self.SW @ (EA * (u1xx * u2x + u1x * u2xx + 1.5 * u2x**2 * u2xx))
            fl += self.CW @ (EA * u2x * u2xx)
            ex0 = 0.5 * EA * (phi @ self._Sx0 + ub_x) ** 2
            exL = 0.5 * EA * (phi @ self._SxL + ub_x) ** 2
        # boundary terms of Eq. (2-40): {EA(u1,x + u2,x^2/2) - P_t} at x = 0, its negative
        # at x = L (u1,x = 0 at the ends of cosine modes)
        fl += (ex0 - Pt) * self.Cend0 + (-exL + Pt) * self.CendL
        return np.concatenate([dphi, dpsi, self.Mt_inv @ ft, self.Ml_inv @ fl])

    def u2_at(self, y, xi, g=0.0, h=0.0):
        """Transverse displacement at x = xi of state(s) y, plus the end motion's line
        (L - xi)/L g + xi/L h where the end displacements g, h are given."""
        k = np.arange(1, self.n_t + 1) * np.pi / self.L
        return np.asarray(y)[..., :self.n_t] @ np.sin(k * xi) + (1 - xi / self.L) * g + xi / self.L * h

    def max_stable_step(self) -> float:
        """RK4 stability bound from the highest linearised eigenvalue (|lambda| dt <= 2.78)."""
        nt, nl = self.n_t, self.n_l
        n = nt + nl
        Minv = np.zeros((n, n)); Minv[:nt, :nt] = self.Mt_inv; Minv[nt:, nt:] = self.Ml_inv
        K = np.zeros((n, n)); K[:nt, :nt] = self.Kt; K[nt:, nt:] = self.Kl
        G = np.zeros((n, n)); G[:nt, :nt] = self.Gt; G[nt:, nt:] = self.Gl
        A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ K, -Minv @ G]])
        lam = np.max(np.abs(np.linalg.eigvals(A)))
        return 2.78 / lam


def rk4_tabulated(model, y0, dt, n_steps, F, record_every=1, y_cap=1e3, kernel="auto"):
    """RK4 of :meth:`GalerkinModel.rhs_values` with the forcing tabulated at the stage times.

    F: dict of arrays (n_steps, 4) for g, h, gd, hd, Pt at t + (eps, dt/2, dt/2, dt - eps) --
    the same one-sided stage times as :func:`rk4`, evaluated in one vectorised call instead
    of four scalar calls per step.
    kernel: ``"auto"`` runs the loop compiled (:mod:`.galerkin_kernel`, numba) when numba is
    installed and the integration has at least ``galerkin_kernel.MIN_STEPS`` steps (its
    size alone decides); ``"numpy"`` forces the loop below; ``"compiled"`` requires the
    compiled one.  Both give the same result to round-off.
    """
    if kernel not in ("auto", "numpy", "compiled"):
        raise UnknownChoice(f"kernel {kernel!r}: allowed auto, numpy, compiled")
    if kernel != "numpy":
        fast = ((kernel == "compiled" or galerkin_kernel.worth_it(n_steps))
                and galerkin_kernel.available())
        if kernel == "compiled" and not fast:
            raise KernelUnavailable("compiled Galerkin kernel unavailable here (needs numba)")
        if fast:
            return galerkin_kernel.rk4_tabulated(model, y0, dt, n_steps, F,
                                                 record_every=record_every, y_cap=y_cap)
    y = np.array(y0, float)
    out_t, out_y = [0.0], [y.copy()]
    G, H, GD, HD, P = (F[k] for k in ("g", "h", "gd", "hd", "Pt"))
    rv = model.rhs_values
    for i in range(n_steps):
        k1 = rv(y, G[i, 0], H[i, 0], GD[i, 0], HD[i, 0], P[i, 0])
        k2 = rv(y + dt / 2 * k1, G[i, 1], H[i, 1], GD[i, 1], HD[i, 1], P[i, 1])
        k3 = rv(y + dt / 2 * k2, G[i, 2], H[i, 2], GD[i, 2], HD[i, 2], P[i, 2])
        k4 = rv(y + dt * k3, G[i, 3], H[i, 3], GD[i, 3], HD[i, 3], P[i, 3])
        y = y + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        if not np.all(np.isfinite(y)) or np.max(np.abs(y)) > y_cap:
            raise DivergenceError(f"RK4 diverged at t = {(i + 1) * dt:.4g} s")
        if (i + 1) % record_every == 0:
            out_t.append((i + 1) * dt)
            out_y.append(y.copy())
    return np.array(out_t), np.array(out_y)


def stage_times(dt, n_steps):
    eps = 1e-9 * dt
    base = np.arange(n_steps)[:, None] * dt
    return base + np.array([eps, dt / 2, dt / 2, dt - eps])[None, :]


# the contributions the Galerkin model consumes (no span-length state, no sag term: the
# config refuses length_change and sag for this solver): the steady ones, evaluated once
# (they fix the speed, P and the model), and the forcing
STEADY_KEYS = ("tension_coefficient", "coupling_stiffness")
FORCING_KEYS = ("tension_pulse", "tension", "tension_external", "tension_short", "tension_long", "u_left",
                "u_right", "v_left", "v_right")


def forcing_arrays(run: dict, prm: dict, omega1: float, geo: dict, t, step=None,
                   registry=None) -> dict:
    """g, h, g', h' (Eqs. 2-24/25 and their time derivatives) and P_t at the times ``t``
    (any shape), from the contributions of the named effects (zero where none)."""
    t = np.asarray(t, float)
    c = (registry or EFFECTS).evaluate(run, SpanContext(prm, [omega1], np.ravel(t), step, geo,
                                                        end_velocity=True), keys=FORCING_KEYS)
    out = {"Pt": dynamic_tension(c, (t.size, 1)).reshape(t.shape)}
    for name, key in (("g", "u_left"), ("h", "u_right"), ("gd", "v_left"), ("hd", "v_right")):
        v = c.get(key)
        out[name] = np.zeros(t.shape) if v is None else np.reshape(v, t.shape)
    return out


def forcing_breakpoints(prm: dict, omega1: float, geo: dict, window, t_end: float) -> np.ndarray:
    """Edges [0, ..., t_end] of the intervals on which every contribution is smooth.

    The forcing of the model is smooth (analytic) between: the engagements at the driving
    sprocket, t = k tau (kinks of the end motions, jumps of D_pol); the wraps of the driven
    sprocket (Eq. 2-8; chain travel s + s_off = j p_c, once per tooth period, at the same
    instant for an integral fractional pitch); and, for the impact pulse averaged over
    ``window`` (its onset and its end at the contact time t_i are jumps), the four edges
    k tau -/+ window/2 and k tau + t_i -/+ window/2.  Edges of effects that are not named
    only cost an extra interval.  Edges closer than 1e-9 tau are merged.
    """
    n1, p = int(prm["n1"]), prm["pitch"]
    tau = float(geometry.tooth_period(omega1, n1))
    offsets = [0.0, four_bar.driven_wrap_time(omega1, n1, int(prm["n2"]), p, geo["f_p"])]
    if window:
        t_i = loads.impact_of(prm)["t_i"]
        h = 0.5 * window
        offsets += [-h, h, t_i - h, t_i + h]
    k = np.arange(-1, math.ceil(t_end / tau) + 2)[:, None] * tau
    edges = np.sort((k + np.array(offsets)[None, :]).ravel())
    edges = np.r_[0.0, edges[(edges > 0) & (edges < t_end)], t_end]
    keep = np.r_[True, np.diff(edges) > 1e-9 * tau]
    edges = edges[keep]
    edges[-1] = t_end
    return edges


def _chebyshev(edges, n_nodes: int) -> dict:
    """The Chebyshev nodes (and the midpoints between them) of every interval of ``edges``
    (:class:`PiecewiseForcing`)."""
    a, b = edges[:-1], edges[1:]
    eps = 1e-9 * (b - a)
    lo, hi = a + eps, b - eps
    k = np.arange(n_nodes + 1)
    x = np.cos(np.pi * k / n_nodes)[::-1]                      # -1 .. 1
    mid = np.cos(np.pi * (k[:-1] + 0.5) / n_nodes)[::-1]

    def at(u):
        return 0.5 * (lo + hi)[:, None] + 0.5 * (hi - lo)[:, None] * u[None, :]

    return {"a": a, "lo": lo, "hi": hi,
            "w": (-1.0) ** k * np.where((k == 0) | (k == n_nodes), 0.5, 1.0),
            "nodes": at(x), "mids": at(mid)}                    # (n_int, n_nodes + 1), (.., n)


def piecewise_times(edges, n_nodes: int = 16) -> np.ndarray:
    """The times at which :class:`PiecewiseForcing` reads the forcing: nodes, then midpoints."""
    c = _chebyshev(np.asarray(edges, float), n_nodes)
    return np.concatenate([c["nodes"].ravel(), c["mids"].ravel()])


class PiecewiseForcing:
    """A cheap scalar forcing t -> (g, h, g', h', P_t) for an adaptive integrator that is
    restarted at every edge of :func:`forcing_breakpoints`.

    On each smooth interval [a, b] the contributions are evaluated once (one vectorised
    call for all intervals) at ``n_nodes`` Chebyshev points of [a + eps, b - eps]
    (eps = 1e-9 (b - a): one-sided limits at the edges, as :func:`rk4` takes them) and
    interpolated barycentrically (exponentially convergent for an analytic function).
    The interpolant is checked against the contributions at the midpoints between the
    nodes; a larger deviation than ``check_rtol`` x the largest value of a component (an
    edge missing from the list) is refused.
    """

    def __init__(self, run, prm, omega1, geo, step, edges, n_nodes: int = 16,
                 check_rtol: float = 1e-12, registry=None, F=None):
        """``F``: the forcing (:func:`forcing_arrays`) at :func:`piecewise_times` of
        ``edges``, when the caller evaluated it together with its own (else evaluated here)."""
        self.edges = np.asarray(edges, float)
        c = _chebyshev(self.edges, n_nodes)
        a, self.lo, self.hi, self.w, self.nodes, mids = (c[k] for k in ("a", "lo", "hi", "w",
                                                                        "nodes", "mids"))
        if F is None:
            F = forcing_arrays(run, prm, omega1, geo, piecewise_times(self.edges, n_nodes), step,
                               registry)
        keys = ("g", "h", "gd", "hd", "Pt")
        V = np.stack([F[key] for key in keys], axis=-1)           # (n_t, 5)
        nn = self.nodes.size
        self.values = V[:nn].reshape(self.nodes.shape + (5,))
        # the check at the midpoints
        Vm = V[nn:].reshape(a.size, n_nodes, 5)
        q = self.w / (mids[:, :, None] - self.nodes[:, None, :])
        got = np.einsum("imk,ikc->imc", q, self.values) / q.sum(axis=-1)[..., None]
        scale = np.maximum(np.max(np.abs(V), axis=0), 1e-300)
        self.error = float(np.max(np.abs(got - Vm) / scale))
        if self.error > check_rtol:
            raise RecordError(f"piecewise forcing: interpolation error {self.error:.2e} > "
                             f"{check_rtol:.0e}: a non-smooth point is missing from the edges")

    def _interp(self, i, t):
        d = t - self.nodes[i]
        if not d.all():                  # at a node
            return self.values[i, np.argmin(np.abs(d))]
        q = self.w / d
        return (q @ self.values[i]) / q.sum()

    def on(self, i: int):
        """The forcing on interval ``i`` (clamped into it: its one-sided edge values)."""
        lo, hi = self.lo[i], self.hi[i]

        def at(t):
            return self._interp(i, min(max(t, lo), hi))
        return at


def library_piecewise(rhs, forcing_on, edges, y0, t_eval, rtol=1e-9, atol=1e-14,
                      method="DOP853"):
    """solve_ivp restarted at every edge of the piecewise smooth forcing: the adaptive
    controller never steps across a kink or jump (which would cost it many rejected steps
    and its accuracy), and no interval is stepped over.  ``rhs(y, g, h, gd, hd, Pt)``;
    ``forcing_on(i)`` -> the forcing t -> (g, h, gd, hd, Pt) on interval i.  Returns the
    states at ``t_eval`` (within [edges[0], edges[-1]]) and the number of rhs calls."""
    y = np.array(y0, float)
    t_eval = np.asarray(t_eval, float)
    out = np.empty((t_eval.size, y.size))
    nfev = 0
    for i, (a, b) in enumerate(zip(edges[:-1], edges[1:])):
        f = forcing_on(i)
        sel = (t_eval >= a) & (t_eval < b)
        sol = solve_ivp(lambda t, yy: rhs(yy, *f(t)), (a, b), y, method=method,
                        t_eval=np.r_[t_eval[sel], b], rtol=rtol, atol=atol)
        if not sol.success:
            raise RuntimeError(f"solve_ivp failed on [{a:.6g}, {b:.6g}] s: {sol.message}")
        nfev += sol.nfev
        out[sel] = sol.y[:, :-1].T
        y = sol.y[:, -1]
    out[t_eval >= edges[-1]] = y
    return out, nfev


# ---------------------------------------------------------------------------- the Fig. 10 scene

def _resonant_speed(run, prm, tension_coefficient, L) -> float:
    """omega1 from options.resonance: tooth frequency = ``detuning`` x the j-th longitudinal or
    the k-th transverse frequency of the span (derived, never typed in); else ``speed``."""
    opts = run.get("options", {})
    spec = opts.get("resonance")
    if not spec:
        return prm["speed"]
    what, order = spec
    d = float(opts.get("detuning", 1.0))
    n1, p, m = int(prm["n1"]), prm["pitch"], prm["mass_per_length"]
    if what == "transverse":
        return geometry.resonance_speed(int(order), L, n1=n1, p_c=p, T_s=prm["static_tension"], m=m,
                                        tension_coefficient=tension_coefficient, harmonic=1.0 / d)

    def f(w):
        return n1 * w - d * geometry.longitudinal_frequency(int(order), prm["axial_stiffness"], m,
                                                            float(geometry.chain_speed(w, n1, p)), L)
    return float(brentq(f, 1e-3, 1e5))


def envelope_statistics(u, steps_per_tooth: int) -> dict:
    """Well-posed statistics of a probe record sampled at every RK4 step.

    The record is cut into quarters of whole tooth periods (the forcing period), so each
    quarter holds the same phases of the forcing; the statistic is the maximum of |u| over
    every step of a quarter (never over a decimated record, whose maximum depends on the
    sampling).  ``steady_amplitude`` = max over the last quarter; ``steady_ratio`` = last
    quarter / third quarter (1 for a steady envelope).
    """
    u = np.abs(np.asarray(u, float))
    n_periods = (u.size - 1) // steps_per_tooth
    q = n_periods // 4
    if q < 1:
        raise RecordError(f"record of {n_periods} tooth periods: too short for quarter statistics")
    edges = [(u.size - 1) - (4 - i) * q * steps_per_tooth for i in range(5)]
    blocks = [np.max(u[edges[i] + 1: edges[i + 1] + 1]) for i in range(4)]
    return {"steady_amplitude": blocks[3], "steady_ratio": blocks[3] / blocks[2],
            "quarter_periods": q}


def _galerkin_setup(run, prm, res) -> dict:
    """The Galerkin model of the span L_ct at the speed of ``options.resonance`` (the steady
    contributions -- tension coefficient, coupling -- fix the speed and P) and its RK4 step."""
    n1, m = int(prm["n1"]), prm["mass_per_length"]
    geo = span_geometry(prm, False)
    L = geo["L_ct"]
    refuse_unhonoured(run, STEADY_KEYS + FORCING_KEYS, "galerkin")
    steady = EFFECTS.evaluate(run, SpanContext(prm, [prm["speed"]], np.zeros(0), None, geo),
                              keys=STEADY_KEYS)
    k_c = steady.total("tension_coefficient")
    w1 = _resonant_speed(run, prm, k_c, L)
    c = float(geometry.chain_speed(w1, n1, prm["pitch"]))
    P = float(geometry.axial_tension(prm["static_tension"], k_c, c))
    model = GalerkinModel(L=L, m=m, EA=prm["axial_stiffness"], P=P, c=c,
                                   c_d=prm["transverse_damping"], n_t=int(res["n_transverse"]),
                                   n_l=int(res["n_longitudinal"]),
                                   coupling="coupling_stiffness" in steady)
    dt_limit = model.max_stable_step()
    # a whole number of steps per tooth period: the end-motion kinks and the impacts then sit
    # on step boundaries (RK4 is only first order across a kink inside a step)
    tau = 2 * np.pi / (n1 * w1)
    per_tooth = math.ceil(tau / (float(res["rk4_cfl"]) * dt_limit))
    return {"model": model, "prm": prm, "geo": geo, "L": L, "w1": w1, "c": c, "P": P,
            "per_tooth": per_tooth, "dt": tau / per_tooth,
            "n_steps": per_tooth * max(int(math.ceil(float(res["duration"]) / tau)), 4),
            # impact pulses shorter than the step enter with their exact impulse, spread over
            # a fixed fraction of the tooth period (the forcing must not change with the step)
            "window": tau / 16, "xi": float(prm["probe_fraction"]) * L}   # xi from the driven end


def _library_window(res, g, t_all) -> tuple[int, np.ndarray]:
    """The library check's steps (whole tooth periods of the record at most: a slower
    speed, e.g. at a lower EA, has fewer of them in the same duration) and the edges of its
    smooth intervals (:func:`forcing_breakpoints`)."""
    n_lib = g["per_tooth"] * max(min(int(round(float(res["library_periods"]))),
                                     (len(t_all) - 1) // g["per_tooth"]), 1)
    return n_lib, forcing_breakpoints(g["prm"], g["w1"], g["geo"], g["window"], t_all[n_lib])


def _library_check(run, prm, res, g, u_all, t_all, Fe, F_lib) -> dict:
    """solve_ivp (DOP853) over the first tooth periods: with a tolerance far below the RK4
    error (rtol 1e-9) the difference is RK4's own error, not the adaptive controller's.

    The integration is restarted at every kink or jump of the forcing
    (:func:`forcing_breakpoints`), with the forcing interpolated on each smooth interval
    (:class:`PiecewiseForcing`, checked to 1e-12; ``F_lib``, its forcing, evaluated with
    RK4's): ~3x fewer right-hand-side calls than one integration across the kinks at the
    same rtol, and ~400x closer to the solution at rtol 1e-12 (5e-11 instead of 2e-8
    relative, benchmarks/bench_chain_drive.py)."""
    model, xi = g["model"], g["xi"]
    n_lib, edges = _library_window(res, g, t_all)
    with phase("chain_drive.library_check"):
        pf = PiecewiseForcing(run, prm, g["w1"], g["geo"], g["window"], edges, F=F_lib)
        y_lib, nfev = library_piecewise(model.rhs_values, pf.on, edges,
                                        np.zeros(2 * (model.n_t + model.n_l)), t_all[:n_lib + 1],
                                        rtol=float(res.get("library_rtol", 1e-9)), atol=1e-14)
    u_lib = model.u2_at(y_lib, xi, Fe["g"][:n_lib + 1], Fe["h"][:n_lib + 1])
    scale = np.max(np.abs(u_all[:n_lib + 1]))
    return {
        "rk4_vs_library": var((), np.max(np.abs(u_all[:n_lib + 1] - u_lib)) / scale, "1",
                              "max |u_RK4 - u_library| / max |u| over the library window"),
        "library_nfev": var((), nfev, "1", "right-hand-side calls of solve_ivp"),
        "rk4_nfev": var((), 4 * g["n_steps"], "1", "right-hand-side calls of RK4")}


def solve_scene(run, ctx=None):
    """Fig. 10: the coupled Galerkin model (Eqs. 2-39..2-41) at the speed of
    ``options.resonance``, RK4 with a whole number of steps per tooth period; optionally
    compared with solve_ivp over the first tooth periods (``options.compare_library``)."""
    prm, res = run["parameters"], run["resolution"]
    opts = run.get("options", {})
    g = _galerkin_setup(run, prm, res)
    model, dt, n_steps, xi, L, c, w1 = (g[k] for k in ("model", "dt", "n_steps", "xi", "L", "c", "w1"))
    n1, m = int(prm["n1"]), prm["mass_per_length"]
    stages = stage_times(dt, n_steps)
    t_rec = np.arange(n_steps + 1) * dt
    # the forcing at the RK4 stages, (for the end-motion line) at the recorded steps and at
    # the library check's nodes: the effects evaluated once, in one call
    times = [stages.ravel(), t_rec + 1e-9 * dt]
    if opts.get("compare_library", False):
        times.append(piecewise_times(_library_window(res, g, t_rec)[1]))
    cut = np.cumsum([t.size for t in times])
    with phase("chain_drive.solve_scene") as sw_rk:
        F = forcing_arrays(run, prm, w1, g["geo"], np.concatenate(times), step=g["window"])
        Fs = {k: v[:cut[0]].reshape(stages.shape) for k, v in F.items()}
        Fe = {k: v[cut[0]:cut[1]] for k, v in F.items()}
        t_all, y_all = rk4_tabulated(model, np.zeros(2 * (model.n_t + model.n_l)), dt,
                                              n_steps, Fs, record_every=1)
    u_all = model.u2_at(y_all, xi, Fe["g"], Fe["h"])
    stats = envelope_statistics(u_all, g["per_tooth"])
    rec = max(n_steps // int(res["samples"]), 1)
    data = {
        "u_probe_rk4": var("t", u_all[::rec], "m", "transverse displacement at the probe, RK4 "
                           f"(every {rec}th step, for the figure)"),
        "rk4_wall_time": var((), sw_rk.seconds, "s", "wall time of the forcing and RK4"),
        "speed": var((), w1 * RPM, "rpm", "driving sprocket speed"),
        "detuning": var((), float(opts.get("detuning", 1.0)), "1",
                        "tooth frequency / the resonance frequency named in options"),
        "transverse_order_at_speed": var(
            (), n1 * w1 / float(geometry.moving_string_frequencies(1, c, g["P"], m, L)), "1",
            "tooth frequency / first transverse frequency of the moving span"),
        "steady_amplitude": var((), stats["steady_amplitude"], "m",
                                "max |u| at the probe over every step of the last quarter "
                                "(whole tooth periods)"),
        "steady_ratio": var((), stats["steady_ratio"], "1",
                            "max |u| last quarter / third quarter (whole tooth periods)"),
        "t": var("t", t_all[::rec], "s", "time")}
    if opts.get("compare_library", False):
        data.update(_library_check(run, prm, res, g, u_all, t_all, Fe,
                                   {k: v[cut[1]:] for k, v in F.items()}))
    return data
