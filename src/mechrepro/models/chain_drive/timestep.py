"""Sec. 3.1: the non-uniform time step refined near each impact, against uniform steps.

The paper samples the impact load at the time steps and shrinks the step near every
impact with an exponential function.  Here

    dt(t) = dt_min + (dt_max - dt_min) (1 - exp(-d(t) / delta)),

d(t) = time since the last impact or to the next one, delta = 3 t_i (t_i = contact time),
dt_min = t_i / refine, dt_max = the von Neumann limit step (x cfl).  It is compared with
uniform steps (point-sampled load) and with our uniform step whose impact load is
averaged exactly over each step (the pulse enters with its exact impulse).
"""
from __future__ import annotations

import numpy as np

from mechrepro.timing import phase

from . import fd, geometry, loads
from .effects import EFFECTS, SpanContext, refuse_unhonoured
from .geometry import span_geometry
from .span import FD_KEYS, STEADY_KEYS, dynamic_tension, make_grid


def nonuniform_times(t_end: float, tau: float, dt_max: float, dt_min: float, delta: float,
                     t_start: float = 0.0):
    """Time points with the exponential refinement around t = k tau."""
    ts = [t_start]
    t = t_start
    while t < t_end:
        ph = np.mod(t, tau)
        d = min(ph, tau - ph)
        t += dt_min + (dt_max - dt_min) * (1 - np.exp(-d / delta))
        ts.append(t)
    return np.array(ts)


# the contributions this march consumes (the FD march's, a uniform span: no length change):
# the steady one (the axial tension, once per comparison) and the forcing (once per time grid)
FORCING_KEYS = tuple(k for k in FD_KEYS if k not in STEADY_KEYS + ("long",))


def response(run: dict, prm: dict, t: np.ndarray, points_per_pitch: int, averaged: bool,
             tension_coefficient: float, registry=EFFECTS):
    """March one speed on the time points ``t`` with the named effects' forcing (pulses
    averaged over the local step, or point-sampled) and the axial tension of
    ``tension_coefficient``; returns u at mid-span and the wall time of the march."""
    n1, p, m = int(prm["n1"]), prm["pitch"], prm["mass_per_length"]
    w1 = np.array([prm["speed"]])
    geo = span_geometry(prm, False)
    grid = make_grid(geo, p, points_per_pitch)
    h = np.diff(t)
    # exact step average with the local step (centred window), or point values
    step = np.concatenate([[h[0]], 0.5 * (h[1:] + h[:-1]), [h[-1]]])[:, None] if averaged else None
    contrib = registry.evaluate(run, SpanContext(prm, w1, t, step, geo), keys=FORCING_KEYS)
    c = geometry.chain_speed(w1, n1, p)
    P = geometry.axial_tension(prm["static_tension"], tension_coefficient, c)
    tension = dynamic_tension(contrib, (t.size, 1))
    kappa = contrib.get("kappa")
    exc = fd.Excitation(tension=tension, u_left=contrib.get("u_left"),
                        u_right=contrib.get("u_right"),
                        load=None if kappa is None else kappa[None, :] * tension)
    fd.check_time_step(float(h.max()), grid.dx, c, P + tension.max(), m)
    mid = grid.n_long // 2
    uniform = len(np.unique(np.round(h / h[0], 12))) == 1
    with phase("chain_drive.response") as sw:
        r = fd.march(c=c, P=np.atleast_1d(P), m=m, c_d=prm["transverse_damping"], grid=grid,
                     dt=h[0] if uniform else None, dt_series=None if uniform else h,
                     n_steps=len(h), exc=exc, probes=[mid], record_every=1)
    return np.concatenate([[0.0, 0.0], r.probes[:, 0, 0]])[: len(t)], sw.seconds


def compare(run, prm: dict, res: dict, registry=EFFECTS) -> dict:
    """Errors (vs a fine uniform reference) and wall times of the time-step strategies.

    ``run``: the run (or a list of effect names)."""
    refuse_unhonoured(run, STEADY_KEYS + FORCING_KEYS, "impact_timestep", registry)
    n1, p, m = int(prm["n1"]), prm["pitch"], prm["mass_per_length"]
    w1 = prm["speed"]
    tau = 2 * np.pi / (n1 * w1)
    t_end = float(res.get("tooth_periods", 4)) * tau
    kimp = loads.impact_of(prm)
    geo = span_geometry(prm, False)
    ppp = int(res["points_per_pitch"])
    grid = make_grid(geo, p, ppp)
    # Eq. (2-36): P = T_s + k c^2 with the tension coefficient k of the named effects
    k_c = registry.evaluate(run, SpanContext(prm, [w1], np.zeros(0), None, geo),
                            keys=STEADY_KEYS).total("tension_coefficient")
    c = geometry.chain_speed(w1, n1, p)
    P = geometry.axial_tension(prm["static_tension"], k_c, c)
    # the point-sampled pulse peak raises the wave speed: bound it from Eq. (2-4)
    tt = np.linspace(0, kimp["t_i"], 2001)
    peak = float(np.max(loads.impact_pulse(tt, loads.relative_velocity(w1, p),
                                           loads.pressure_angle(n1), kimp)))
    dt_max = fd.stable_time_step(grid.dx, c, 1.01 * (P + peak), m, float(res["cfl"]))
    dt_min = kimp["t_i"] / float(res.get("refine", 10))

    # start half a tooth period before the first impact, so that no scheme loses it in
    # the starting levels of the three-level march
    t0 = -0.5 * tau

    def uniform(dt):
        n = int(np.ceil((t_end - t0) / dt))
        return t0 + np.arange(n + 1) * ((t_end - t0) / n)

    t_ref = uniform(dt_min / 2)
    u_ref, w_ref = response(run, prm, t_ref, ppp, averaged=True, tension_coefficient=k_c,
                            registry=registry)

    def err(t, u):
        return float(np.max(np.abs(np.interp(t_ref, t, u) - u_ref)) / np.max(np.abs(u_ref)))

    out = {"reference_wall": w_ref, "dt_max": dt_max, "dt_min": dt_min, "contact_time": kimp["t_i"]}
    for name, t, avg in (("uniform_sampled", uniform(dt_max), False),
                         ("uniform_averaged", uniform(dt_max), True),
                         ("nonuniform", nonuniform_times(t_end, tau, dt_max, dt_min,
                                                         3 * kimp["t_i"], t0), False)):
        u, w = response(run, prm, t, ppp, averaged=avg, tension_coefficient=k_c,
                        registry=registry)
        out[name] = {"error": err(t, u), "wall": w, "steps": len(t) - 1}
    # the uniform (point-sampled) step that matches the non-uniform accuracy
    target = out["nonuniform"]["error"]
    dt = dt_max
    while True:
        t = uniform(dt)
        u, w = response(run, prm, t, ppp, averaged=False, tension_coefficient=k_c,
                        registry=registry)
        e = err(t, u)
        if e <= target or dt <= dt_min / 2:
            out["uniform_equal_accuracy"] = {"error": e, "wall": w, "steps": len(t) - 1, "dt": dt}
            break
        dt /= 2
    return out
