"""The discrete-link span (issue 59): the chain as it is at the pitch scale.

The rollers of the span are particles of mass m_r = m p with transverse freedom y_i, a
pitch apart; the links carry the axial tension P + P_t (the same effects as the string's,
:mod:`.effects`) and the transverse damping acts per roller (c_d p on its velocity).  The
end rollers sit on the sprockets and follow the polygon, Eqs. (2-24), (2-25).  Per tooth
period one roller is released from the driven sprocket (x = 0; the span gains a pitch) and
one is seated on the driving sprocket (x = L; it loses one), at the phases of the four-bar
(:func:`.four_bar.tooth_phases`): that *is* the periodic length change and the polygonal
action, and it needs no convective operator: the rollers move with the chain (Lagrangian),
so the moving string's Coriolis and centripetal terms come from the relabelling.

Assumed choices (declared, not tuned): rigid axial motion (the rollers a pitch apart,
links inextensible along the span); the impact of Eq. (2-4) a tension pulse in every link
(as in the string model) for its share ``impact_share`` and in the engaging link (to the
driving end) alone for the rest: with rigid links the pulse reaches every link at once,
while the axial wave of an elastic chain crosses the span in ~5 contact times, so the
truth lies between (the parameter's range, 0 to 1); a seated roller's transverse state is
dropped (the sprocket takes it over: a perfectly inelastic seating); a released roller
starts with the driven end's position and velocity; without the ``long`` state (no
length_change effect) the roller set is fixed, released and seated at once.

Equation of roller i (i = 1..N, y_0 and y_(N+1) the end rollers):
    m_r y_i'' = (P + P_t)/p (y_(i+1) - 2 y_i + y_(i-1)) - c_d p y_i',
the engaging link's tension (1 - impact_share) D_imp higher and the others' lower by it.
Between events it is linear with time-periodic coefficients; one tooth period with its
events is an affine map x -> M x + b of the free rollers' state (positions, velocities),
so the periodic steady state is one linear solve and its stability the eigenvalues of M
(Floquet multipliers), the relabelling included.
"""
from __future__ import annotations

import math

import numpy as np

from . import geometry, span
from .effects import EFFECTS, SpanContext, declared_keys


def beaded_frequencies(n: int, tension: float, mass: float, spacing: float) -> np.ndarray:
    """Exact natural frequencies [rad/s] of n beads of ``mass`` at ``spacing`` under
    ``tension`` between fixed ends: omega_k = 2 sqrt(T / (m a)) sin(k pi / (2 (n + 1)))."""
    k = np.arange(1, n + 1)
    return 2.0 * np.sqrt(tension / (mass * spacing)) * np.sin(k * np.pi / (2 * (n + 1)))


def _accel(y, v, left, right, k_over_m, damp, last, load, a):
    """Roller accelerations into ``a`` (N, K): (P/(m_r p)) (second difference with the end
    rollers) - damp v, plus ``last`` (an extra tension / (m_r p) in the link to the driving
    end) on the last roller and the sag load per mass ``load`` on every roller.  The end
    rollers and the load act on the forced (last) column alone: the other columns are the
    map's unit states."""
    n, f = y.shape[0], y.shape[1] - 1
    for i in range(n):              # row by row: the loop over the columns runs along memory
        for k in range(f + 1):
            lo, hi = (left, right) if k == f else (0.0, 0.0)
            below = y[i - 1, k] if i > 0 else lo
            above = y[i + 1, k] if i < n - 1 else hi
            a[i, k] = (below - 2.0 * y[i, k] + above) * k_over_m - damp * v[i, k]
    for k in range(f + 1):
        a[n - 1, k] += last * ((right if k == f else 0.0) - y[n - 1, k])
    for i in range(n):
        a[i, f] += load


def _stage(y, v, vs, a, c, ys, vo):
    """ys = y + c vs, vo = v + c a (one RK4 stage's state)."""
    n, k_cols = y.shape
    for i in range(n):
        for k in range(k_cols):
            ys[i, k] = y[i, k] + c * vs[i, k]
            vo[i, k] = v[i, k] + c * a[i, k]


def _march(y, v, times, left, right, k_over_m, damp, last, load):
    """Classical RK4 of :func:`_accel` over ``times`` (n + 1 nodes): ``left``/``right`` the
    end rollers' positions at the 2 n + 1 half-step nodes, ``k_over_m`` (P + P_t)/(m_r p),
    ``last`` and ``load`` per step (n,).  y, v: (N, K), the last column forced.  Returns the
    final y, v and max |y| of the forced column over the period: at the nodes and, where a
    roller's velocity changes sign within a step, at its turning point (y_j + v_j theta h / 2,
    theta = v_j / (v_j - v_(j+1)): the maximum to O(h^3), not the nodes' O(h^2), whose
    jitter with the node placement would read as a change between levels)."""
    n_rollers, k_cols = y.shape
    y, v = y.copy(), v.copy()
    y2, v2, y3, v3 = np.empty_like(y), np.empty_like(y), np.empty_like(y), np.empty_like(y)
    y4, v4, a1, a2 = np.empty_like(y), np.empty_like(y), np.empty_like(y), np.empty_like(y)
    a3, a4 = np.empty_like(y), np.empty_like(y)
    amp = 0.0
    for i in range(n_rollers):
        amp = max(amp, abs(y[i, k_cols - 1]))
    for j in range(len(times) - 1):
        h = times[j + 1] - times[j]
        kom, ex, ld = k_over_m[j], last[j], load[j]
        _accel(y, v, left[2 * j], right[2 * j], kom, damp, ex, ld, a1)
        _stage(y, v, v, a1, 0.5 * h, y2, v2)
        _accel(y2, v2, left[2 * j + 1], right[2 * j + 1], kom, damp, ex, ld, a2)
        _stage(y, v, v2, a2, 0.5 * h, y3, v3)
        _accel(y3, v3, left[2 * j + 1], right[2 * j + 1], kom, damp, ex, ld, a3)
        _stage(y, v, v3, a3, h, y4, v4)
        _accel(y4, v4, left[2 * j + 2], right[2 * j + 2], kom, damp, ex, ld, a4)
        f = k_cols - 1
        for i in range(n_rollers):
            y0, v0 = y[i, f], v[i, f]
            for k in range(k_cols):
                y[i, k] = y[i, k] + h / 6.0 * (v[i, k] + 2.0 * v2[i, k] + 2.0 * v3[i, k]
                                               + v4[i, k])
                v[i, k] = v[i, k] + h / 6.0 * (a1[i, k] + 2.0 * a2[i, k] + 2.0 * a3[i, k]
                                               + a4[i, k])
            amp = max(amp, abs(y[i, f]))
            if v0 * v[i, f] < 0.0:
                amp = max(amp, abs(y0 + 0.5 * v0 * (v0 / (v0 - v[i, f])) * h))
    return y, v, amp


_KERNEL = None


def rk4(y, v, times, left, right, k_over_m, damp, last=None, load=None):
    """Classical RK4 of the rollers over ``times`` (:func:`_march`, compiled by
    :func:`mechrepro.compiled.jit` where numba is installed, the same source as Python
    otherwise: a sweep solves hundreds of periodic orbits, each ~1e7 flops in ~1e4 small
    loops).  ``last``/``load``: None for none.  Returns the final (y, v) and max |y| of the
    forced (last) column over the nodes."""
    global _KERNEL
    if _KERNEL is None:
        from mechrepro.compiled import jit

        global _accel, _stage
        _accel, _stage = jit(inline="always")(_accel), jit(inline="always")(_stage)
        _KERNEL = jit(_march)
    zeros = np.zeros(len(times) - 1)
    f64 = lambda x: np.ascontiguousarray(x, dtype=np.float64)  # noqa: E731
    return _KERNEL(f64(y), f64(v), f64(times), f64(left), f64(right), f64(k_over_m),
                   float(damp), zeros if last is None else f64(last),
                   zeros if load is None else f64(load))


def events(prm: dict, omega1: float) -> tuple[float, float, int]:
    """(tau, t_r, n_short): the tooth period, the release time in [0, tau) of the roller
    leaving the driven sprocket (:func:`.four_bar.driven_wrap_time`) and the free rollers of
    the short span."""
    from . import four_bar

    p, n1 = prm["pitch"], int(prm["n1"])
    geo = geometry.span_geometry(prm, True)
    t_r = four_bar.driven_wrap_time(omega1, n1, int(prm["n2"]), p, geo["f_p"])
    return float(geometry.tooth_period(omega1, n1)), t_r, int(round(geo["L_short"] / p)) - 1


def drives_of(run, prm, omegas, steps_per_period) -> list:
    """Per speed, :func:`period_map`'s excitation on each of its grids (:func:`_grids`): the
    end rollers at the half-step nodes, P_t per step, its impact part D_imp (Eq. 2-4), the
    sag load kappa P_t / m (Eq. 2-36), from the scene's effects (:mod:`.effects`), evaluated
    once per set of speeds with grids of equal lengths (elementwise on their block)."""
    grids = [_grids(run, prm, w, steps_per_period)[-1] for w in omegas]
    groups, out, geo = {}, [[] for _ in omegas], geometry.span_geometry(prm, True)
    for i, g in enumerate(grids):
        groups.setdefault(tuple(len(t) for t, _ in g), []).append(i)
    for idx in groups.values():
        w = np.array([omegas[i] for i in idx], float)
        for k in range(len(grids[idx[0]])):
            t = np.stack([grids[i][k][0] for i in idx], 1)
            half = np.empty((2 * len(t) - 1, w.size))
            half[0::2], half[1::2] = t, 0.5 * (t[:-1] + t[1:])
            ends = EFFECTS.evaluate(run, SpanContext(prm, w, half, None, geo, end_velocity=True),
                                    keys=(keys := {"u_left", "u_right", "v_left", "v_right"}))
            ends = {key: ends.get(key) if key in ends else np.zeros(half.shape) for key in keys}
            tens = EFFECTS.evaluate(run, SpanContext(prm, w, half[1::2], np.array(
                [grids[i][k][1] for i in idx]), geo), keys=set(span.PT_KEYS) | {"kappa"})
            Pt = span.dynamic_tension(tens, (len(t) - 1, w.size))
            pulse = np.asarray(tens.total("tension_pulse", np.zeros(Pt.shape)))
            kappa = np.broadcast_to(np.asarray(tens.total("kappa", 0.0), float).ravel(), w.shape)
            for j, i in enumerate(idx):
                out[i].append(({key: x[:, j] for key, x in ends.items()}, Pt[:, j], pulse[:, j],
                               float(kappa[j]) * Pt[:, j] / prm["mass_per_length"]))
    return out


def tension_coefficient(run, prm) -> float:
    """k of P = T_s + k c^2 from the scene's effects (0 without speed tensioning)."""
    ctx = SpanContext(prm, 1.0, np.zeros(0), None, geometry.span_geometry(prm, True))
    return float(EFFECTS.evaluate(run, ctx, keys={"tension_coefficient"}).total("tension_coefficient"))


#: RK4's stability interval on the imaginary axis is |omega dt| <= 2 sqrt(2); a margin
#: for the dynamic tension's peaks
RK4_LIMIT = 2.5


def _refuse_unstable_step(P, m_r, p, n_free, dt, steps, tau) -> None:
    """Refuse a step beyond RK4's stability interval for the span's highest mode (at the
    static axial tension; the dynamic part is the margin of :data:`RK4_LIMIT`): the march
    would blow up (a multiplier of 15 at 50 rpm, 100 steps, 800 N), never silently."""
    from .errors import StabilityError

    w_max = float(beaded_frequencies(n_free, P, m_r, p)[-1])
    if w_max * dt > RK4_LIMIT:
        need = int(math.ceil(w_max * tau / RK4_LIMIT))
        raise StabilityError(f"discrete span: {steps} RK4 steps per tooth period give omega_max "
                             f"dt = {w_max * dt:.3g} > {RK4_LIMIT} (highest roller mode "
                             f"{w_max:.4g} rad/s at P = {P:.4g} N): at least {need} steps")


def _entering(ends, key: str, k_cols: int) -> np.ndarray:
    """The state row of a roller released from the driven sprocket: the driven end's
    position or velocity in the forced (last) column, 0 in the map's unit columns."""
    row = np.zeros((1, k_cols))
    row[0, -1] = ends[key][0]
    return row


def _refuse_unhonoured_keys(named: set) -> None:
    """Keys the discrete span cannot honour, refused before any march (never ignored)."""
    from .errors import UnknownChoice

    for key, why in (("tension_short", "the elastic four-bar load is not wired in"),
                     ("tension_external", "an external load's period is not one tooth period")):
        if key in named:
            raise UnknownChoice(f"discrete span: {why} ({key})")


#: RK4 steps within the impact's contact time per this many steps per tooth period: the
#: 28 us pulse (Eq. 2-4) is resolved by its own steps (>= 5 at the coarsest level in use)
#: instead of being averaged into one step of ~20 us, so that refining the step refines
#: the pulse with it
CONTACT_STEPS = 25


def _segments(tau, t_r, steps_per_period, t_i=0.0):
    """The time grids of the period's segments between its events: the contact [0, t_i]
    (impact on; ``steps_per_period`` / :data:`CONTACT_STEPS` steps), the release t_r and the
    seating tau; elsewhere ``steps_per_period`` per tooth period."""
    cuts = sorted({0.0, tau} | {t for t in (t_i, t_r) if 0.0 < t < tau})
    out = []
    for a, b in zip(cuts[:-1], cuts[1:]):
        n = (math.ceil(steps_per_period / CONTACT_STEPS) if b == t_i else
             math.ceil(steps_per_period * (b - a) / tau))
        out.append(np.linspace(a, b, max(int(n), 2) + 1))
    return out


def _contact_time(run, prm) -> float:
    """The impact's contact time t_i = pi / omega_d (Appendix I); 0 without the impact."""
    from . import loads

    if "tension_pulse" not in declared_keys(run):
        return 0.0
    return float(loads.impact_of(prm)["t_i"])


def _grids(run, prm, omega1, steps_per_period):
    """tau, t_r (0 without the ``long`` state), n_short (:func:`events`) and the time grids
    with their steps: the segments between the events (:func:`_segments`), then the
    seating, where a roller enters when t_r = 0."""
    tau, t_r, n_s = events(prm, omega1)
    t_r = t_r if "long" in declared_keys(run) else 0.0
    return tau, t_r, n_s, [(g, g[1] - g[0]) for g in _segments(
        tau, t_r, steps_per_period, _contact_time(run, prm))] + (
        [(np.array([tau, tau + 1e-9 * tau]), 1e-9 * tau)] if t_r == 0 else [])


def period_map(run, prm: dict, omega1: float, steps_per_period: int, start=None, drives=None):
    """One tooth period of the discrete span from just after the seating at t = 0, events
    included: the affine map x -> M x + b of the free rollers' state x = (y, v).  Without
    the ``long`` state (no length_change effect) the roller set is fixed: the release
    coincides with the seating (t_r = 0).  With ``start`` (a state x) only that orbit is
    marched: M is None, b its state after the period and ``amplitude`` max |y| over the
    free rollers along it.  ``drives``: the excitation of each segment and of the seating
    (:func:`drives_of`, returned as ``drives``) of an earlier call at this speed, not
    evaluated again."""
    _refuse_unhonoured_keys(declared_keys(run))
    m, p = prm["mass_per_length"], prm["pitch"]
    m_r, damp = m * p, prm["transverse_damping"] * p / (m * p)
    tau, t_r, n_s, grids = _grids(run, prm, omega1, steps_per_period)
    share = float(prm.get("impact_share", 1.0))
    P = float(geometry.axial_tension(prm["static_tension"], tension_coefficient(run, prm), float(
        geometry.chain_speed(omega1, int(prm["n1"]), prm["pitch"]))))     # P = T_s + k c^2
    _refuse_unstable_step(P, m_r, p, n_s + 1, tau / steps_per_period, steps_per_period, tau)
    N0 = n_s
    if start is None:                            # unit columns + the forced column
        K = 2 * N0 + 1
        y, v = np.zeros((N0, K)), np.zeros((N0, K))
        y[np.arange(N0), np.arange(N0)] = 1.0
        v[np.arange(N0), N0 + np.arange(N0)] = 1.0
    else:
        K = 1
        y, v = np.asarray(start[:N0], float)[:, None], np.asarray(start[N0:], float)[:, None]
    amp, p_min = 0.0, math.inf
    drives = drives or drives_of(run, prm, [omega1], steps_per_period)[0]
    for (seg, _), (ends, Pt, pulse, load) in zip(grids[:len(grids) - (t_r == 0)], drives):
        local = (1.0 - share) * pulse            # the engaging link's alone
        if t_r > 0 and seg[0] == t_r:            # release: a roller enters at the driven end
            y = np.vstack([_entering(ends, "u_left", K), y])
            v = np.vstack([_entering(ends, "v_left", K), v])
        y, v, a = rk4(y, v, seg, ends["u_left"], ends["u_right"],
                      (P + Pt - local) / (m_r * p), damp, local / (m_r * p), load)
        amp = max(amp, a)
        p_min = min(p_min, float(np.min(P + Pt - np.maximum(local, 0.0))))
    # seating at tau: the last roller goes onto the driving sprocket (state dropped) ...
    y, v = y[:-1], v[:-1]
    if t_r == 0:                                 # ... and one leaves the driven sprocket
        ends = drives[-1][0]
        y = np.vstack([_entering(ends, "u_left", K), y])
        v = np.vstack([_entering(ends, "v_left", K), v])
    x = np.vstack([y, v])
    return {"M": x[:, :-1] if start is None else None, "b": x[:, -1], "tau": tau, "t_r": t_r,
            "n_short": n_s, "P": P, "P_min": p_min, "amplitude": amp, "drives": drives}


def floquet(M: np.ndarray) -> np.ndarray:
    """Floquet multipliers of the tooth-period map (eigenvalues of M), largest first."""
    mu = np.linalg.eigvals(M)
    return mu[np.argsort(-np.abs(mu))]


def periodic_orbit(run, prm: dict, omega1: float, steps_per_period: int, drives=None) -> dict:
    """Periodic steady state x* = (I - M)^-1 b of the tooth-period map, its largest
    Floquet multiplier and its amplitude (max |y| over the free rollers along one period
    marched from x*, which returns to x*: the residual).  ``drives``: :func:`drives_of`."""
    pm = period_map(run, prm, omega1, steps_per_period, drives=drives)
    M, b = pm["M"], pm["b"]
    x = np.linalg.solve(np.eye(M.shape[0]) - M, b)
    orbit = period_map(run, prm, omega1, steps_per_period, start=x, drives=pm["drives"])
    return {"x": x, "rho": float(np.max(np.abs(floquet(M)))), "amplitude": orbit["amplitude"],
            "tau": pm["tau"], "n_short": pm["n_short"], "slack": pm["P_min"] <= 0.0,
            "residual": float(np.max(np.abs(orbit["b"] - x)))}


def sweep(run, prm: dict, omega1, res: dict) -> dict:
    """Figs. 5-8 on the discrete span: per driving speed [rad/s] the periodic orbit's
    amplitude, the largest Floquet multiplier rho (unstable where rho > 1 or where a link
    goes slack, P + P_t <= 0) and the periodicity residual, at ``steps_per_period`` RK4
    steps per tooth period (the knob the levels refine).  With ``edge_tol``/``peak_tol``
    (rpm) the speeds are refined as the string's shooting sweeps are
    (:func:`.shooting.adaptive_sweep`: stability edges and growth-rate bumps), then every
    amplitude peak of prominence >= 0.05 mm (:func:`.claims.peaks`) that is no stable
    orbit at a stability edge (whose amplitude grows without bound as rho -> 1 and would
    set a relative prominence), so that a peak or an edge is located to those widths."""
    from . import claims
    from .errors import UnknownChoice
    from .limits import stability_only
    from .shooting import PeriodicSolution, adaptive_sweep

    if run.get("options", {}).get("stationary_string"):
        raise UnknownChoice("discrete span: the stationary_string option is the string's "
                            "(the rollers move with the chain)")
    n = int(res["steps_per_period"])

    def evaluate(ws):     # the excitation of 64 speeds at a time (drives_of)
        gs = [periodic_orbit(run, prm, w, n, d) for c in range(0, len(ws), 64)
              for w, d in zip(ws[c:c + 64], drives_of(run, prm, ws[c:c + 64], n))]
        return [PeriodicSolution(
            amplitude=g["amplitude"], rho=g["rho"], growth_rate=math.log(g["rho"]) / g["tau"],
            period=g["tau"], n_steps=n, residual=g["residual"], slack=g["slack"],
            multipliers=np.empty(0), rho_lower=g["rho"], rho_upper=g["rho"]) for g in gs]

    if "edge_tol" in res:
        sigma = prm["transverse_damping"] / (2 * prm["mass_per_length"])
        only = stability_only(run)
        peak_tol = float(res["peak_tol"]) / geometry.RPM
        omega1, sols, done = adaptive_sweep(
            evaluate, omega1, edge_tol=float(res["edge_tol"]) / geometry.RPM,
            peak_tol=peak_tol, rate_floor=-0.5 * sigma, prominence=None, until_unstable=only)
        pts = dict(zip(omega1.tolist(), sols))
        while not only:
            w = np.array(sorted(pts))
            un = np.array([pts[v].rho > 1.0 or pts[v].slack for v in w])
            idx = claims.peaks(w, [pts[v].amplitude for v in w], stable=~un)
            new = {0.5 * (w[j] + w[j + 1]) for i in idx if not (un[i - 1] or un[i + 1])
                   for j in (i - 1, i) if w[j + 1] - w[j] > peak_tol} - set(pts)
            if not new:
                break
            pts.update(zip(ws := sorted(new), evaluate(ws)))
        omega1 = np.array(sorted(pts))
        sols = [pts[v] for v in omega1]
    else:
        sols, done = evaluate([float(w) for w in omega1]), True
    rho = np.array([g.rho for g in sols])
    slack = np.array([g.slack for g in sols])
    return {"omega1": np.asarray(omega1, float), "amplitude": np.array([g.amplitude for g in sols]),
            "rho": rho, "slack": slack, "unstable": (rho > 1.0) | slack,
            "residual": np.array([g.residual for g in sols]), "sampling_converged": done,
            "n_rollers": events(prm, float(omega1[0]))[2]}
