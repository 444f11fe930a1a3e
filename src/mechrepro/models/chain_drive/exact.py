"""Independent checks of the FD scheme, not from the paper.

* exact free vibration of the axially moving string (Wickert & Mote 1990):
  u(x, t) = sin(k pi x/L) cos(omega_k (t + c x/(c_w^2 - c^2))) with
  omega_k = k pi (c_w^2 - c^2)/(c_w L) solves Eq. (2-37) without damping and excitation;
* a manufactured solution with damping, time-varying tension, moving ends and a source,
  for the observed order of convergence.
"""
from __future__ import annotations

import numpy as np

from mechrepro.timing import phase
from mechrepro.units import var

from . import fd, geometry


def moving_string_mode(x, t, k, c, cw, L):
    wk = k * np.pi * (cw**2 - c**2) / (cw * L)
    return np.sin(k * np.pi * x / L) * np.cos(wk * (t + c * x / (cw**2 - c**2)))


def zero_crossing_frequency(t, y) -> float:
    """Angular frequency from the first and last zero crossings (linear interpolation)."""
    s = np.signbit(y)
    idx = np.nonzero(s[1:] != s[:-1])[0]
    if len(idx) < 3:
        return float("nan")
    tz = t[idx] - y[idx] * (t[idx + 1] - t[idx]) / (y[idx + 1] - y[idx])
    return float(np.pi * (len(tz) - 1) / (tz[-1] - tz[0]))


def free_vibration(n: int, *, L, m, T, c, k=1, cfl=0.9, periods=4.0, s_star=None):
    """March the exact mode k for ``periods`` periods; return (max error, omega_fd, omega_exact, dt, wall)."""
    cw = np.sqrt(T / m)
    grid = fd.Grid(L, n, n)
    x = grid.x
    c_arr = np.array([c], float)
    dt = fd.stable_time_step(grid.dx, c_arr, T, m, cfl)
    wk = float(geometry.moving_string_frequencies(k, c, T, m, L))
    n_steps = int(np.ceil(periods * 2 * np.pi / wk / dt))
    u0 = moving_string_mode(x, 0.0, k, c, cw, L)[None]
    u1 = moving_string_mode(x, dt, k, c, cw, L)[None]
    probe = int(round(0.37 * n))
    with phase("chain_drive.free_vibration") as sw:
        r = fd.march(c=c_arr, P=np.array([T]), m=m, c_d=0.0, grid=grid, dt=dt, n_steps=n_steps,
                     exc=fd.Excitation(), s_star=s_star, u0=u0, u1=u1, probes=[probe],
                     record_every=1, u_cap=1e3)
    wall = sw.seconds
    t_end = n_steps * dt
    err = np.max(np.abs(r.final[0] - moving_string_mode(x, t_end, k, c, cw, L)))
    w_fd = zero_crossing_frequency(r.t_rec, r.probes[:, 0, 0])
    return float(err), w_fd, wk, dt, wall


def free_vibration_check(prm: dict, res: dict) -> dict:
    """Convergence table over ``res["points"]`` (a list) for central and mixed differencing."""
    L = prm["centre_distance"] * prm["pitch"]
    m, T = prm["mass_per_length"], prm["static_tension"]
    cw = np.sqrt(T / m)
    c = float(res["speed_ratio"]) * cw
    pts = np.atleast_1d(res["points"]).astype(int)
    col = _by_scheme(pts, lambda n, s: free_vibration(
        n, L=L, m=m, T=T, c=c, k=int(res.get("mode", 1)), cfl=float(res["cfl"]),
        periods=float(res.get("periods", 4)), s_star=s))
    return {
        "error_max": var(DIMS, col(0), "m",
                         "max |u_FD - u_exact| after the march (unit mode amplitude)"),
        "omega_fd": var(DIMS, col(1), "rad/s", "frequency from zero crossings of the FD response"),
        "omega_exact": var((), float(col(2)[0, 0]), "rad/s",
                           "Wickert-Mote frequency k pi (c_w^2-c^2)/(c_w L)"),
        # one time per grid for each differencing (the cost-of-accuracy curves)
        "march_wall_time_central": var("points", col(4)[0], "s", "wall time of the central march"),
        "march_wall_time_mixed": var("points", col(4)[1], "s", "wall time of the mixed march"),
        **_differencing_coords(pts)}


DIMS = ("differencing", "points")


def _by_scheme(pts, solve):
    """``solve(n, s_star)`` on every grid of ``pts``, central (s* = 0) then mixed (None: Eq.
    2-38); returns column i of the results as a (differencing, points) array."""
    rows = {k: [solve(int(n), s) for n in pts] for k, s in (("central", 0.0), ("mixed", None))}
    return lambda i: np.array([[r[i] for r in rows[k]] for k in ("central", "mixed")])


def _differencing_coords(pts) -> dict:
    return {"points": var("points", pts, "1", "grid intervals over the span"),
            "differencing": var("differencing", ["central", "mixed"], "1",
                                "first-derivative differencing")}


def manufactured(n: int, *, L=0.25, m=0.6, T=400.0, c=5.0, c_d=10.0, cfl=0.9, t_end=0.02,
                 s_star=None, kappa=0.0):
    """Observed-order check: u_m = X(x) Tm(t) with moving ends, P_t(t) and damping."""
    grid = fd.Grid(L, n, n)
    x = grid.x
    w, w2 = 2 * np.pi * 60.0, 2 * np.pi * 35.0
    X = 1 + 0.5 * np.sin(2 * np.pi * x / L + 0.3)
    Xx = 0.5 * (2 * np.pi / L) * np.cos(2 * np.pi * x / L + 0.3)
    Xxx = -0.5 * (2 * np.pi / L) ** 2 * np.sin(2 * np.pi * x / L + 0.3)
    Tm = lambda t: 1e-3 * np.sin(w * t + 0.4)                # noqa: E731
    Tt = lambda t: 1e-3 * w * np.cos(w * t + 0.4)            # noqa: E731
    Ttt = lambda t: -1e-3 * w**2 * np.sin(w * t + 0.4)       # noqa: E731
    Pt = lambda t: 0.2 * T * np.sin(w2 * t)                  # noqa: E731
    c_arr = np.array([c])
    dt = fd.stable_time_step(grid.dx, c_arr, T * 1.2, m, cfl)
    n_steps = int(np.ceil(t_end / dt))
    dt = t_end / n_steps
    t = np.arange(n_steps + 1) * dt

    def residual(tj):
        return (m * X * Ttt(tj) + 2 * m * c * Xx * Tt(tj) + m * c**2 * Xxx * Tm(tj)
                + c_d * (X * Tt(tj) + c * Xx * Tm(tj)) - (T + Pt(tj)) * Xxx * Tm(tj)
                - kappa * Pt(tj))

    exc = fd.Excitation(tension=Pt(t)[:, None], u_left=(X[0] * Tm(t))[:, None],
                        u_right=(X[-1] * Tm(t))[:, None],
                        load=(kappa * Pt(t))[:, None] if kappa else None,
                        source=lambda j: residual(t[j])[None, 1:-1])
    with phase("chain_drive.manufactured") as sw:
        r = fd.march(c=c_arr, P=np.array([T]), m=m, c_d=c_d, grid=grid, dt=dt, n_steps=n_steps,
                     exc=exc, s_star=s_star, u0=(X * Tm(0.0))[None], u1=(X * Tm(dt))[None],
                     u_cap=1.0)
    wall = sw.seconds
    err = np.max(np.abs(r.final[0] - X * Tm(t[-1]))) / 1e-3
    return float(err), dt, grid.dx, wall


def manufactured_check(prm: dict, res: dict) -> dict:
    """Convergence table over ``res["points"]`` for central and mixed differencing."""
    pts = np.atleast_1d(res["points"]).astype(int)
    col = _by_scheme(pts, lambda n, s: manufactured(n, cfl=float(res["cfl"]), s_star=s, kappa=0.01))
    return {
        "error_max": var(DIMS, col(0), "1", "max relative error against the manufactured solution"),
        **_differencing_coords(pts)}
