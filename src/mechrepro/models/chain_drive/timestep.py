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

import time

import numpy as np

from . import fd, four_bar, geometry, loads
from .span import make_grid, span_geometry


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


def response(prm: dict, effects, t: np.ndarray, points_per_pitch: int, averaged: bool):
    """March one speed on the time points ``t``; returns u at mid-span and wall time."""
    n1, n2, p, m = int(prm["n1"]), int(prm["n2"]), prm["pitch"], prm["mass_per_length"]
    w1 = np.array([prm["speed"]])
    c = geometry.chain_speed(w1, n1, p)
    P = prm["static_tension"] + (loads.speed_tensioning(prm["lambda_support"], m, c)
                                 if "speed_tensioning" in effects else 0.0)
    geo = span_geometry(prm, False)
    grid = make_grid(geo, p, points_per_pitch)
    h = np.diff(t)
    kimp = loads.impact_constants(prm["impact_mass_links"] * p * m, prm["contact_stiffness"],
                                  prm["contact_damping_ratio"])
    T = t[:, None]
    if averaged:
        # exact step average with the local step (centred window)
        hh = np.concatenate([[h[0]], 0.5 * (h[1:] + h[:-1]), [h[-1]]])[:, None]
        tension = loads.impact_load(T, w1[None, :], n1, p, kimp, step=hh)
    else:
        tension = loads.impact_load(T, w1[None, :], n1, p, kimp, step=None)
    exc = fd.Excitation(tension=tension)
    if "end_excitation" in effects:
        kin = four_bar.rigid_kinematics(T, w1[None, :], n1=n1, n2=n2, p_c=p, f_p=geo["f_p"])
        exc.u_left, exc.u_right = four_bar.end_displacements(kin["theta1"], kin["theta2"],
                                                             kin["r1"], kin["r2"], n2)
    if "sag" in effects:
        exc.load = m * 9.80665 / (prm["static_tension"] - m * c[None, :] ** 2) * tension
    fd.check_time_step(float(h.max()), grid.dx, c, P + tension.max(), m)
    mid = grid.n_long // 2
    t0 = time.perf_counter()
    r = fd.march(c=c, P=np.atleast_1d(P), m=m, c_d=prm["transverse_damping"], grid=grid,
                 dt=None if len(np.unique(np.round(h / h[0], 12))) > 1 else h[0],
                 dt_series=h if len(np.unique(np.round(h / h[0], 12))) > 1 else None,
                 n_steps=len(h), exc=exc, probes=[mid], record_every=1)
    wall = time.perf_counter() - t0
    return np.concatenate([[0.0, 0.0], r.probes[:, 0, 0]])[: len(t)], wall


def compare(prm: dict, effects, res: dict) -> dict:
    """Errors (vs a fine uniform reference) and wall times of the time-step strategies."""
    n1, p, m = int(prm["n1"]), prm["pitch"], prm["mass_per_length"]
    w1 = prm["speed"]
    tau = 2 * np.pi / (n1 * w1)
    t_end = float(res.get("tooth_periods", 4)) * tau
    c = geometry.chain_speed(w1, n1, p)
    kimp = loads.impact_constants(prm["impact_mass_links"] * p * m, prm["contact_stiffness"],
                                  prm["contact_damping_ratio"])
    geo = span_geometry(prm, False)
    ppp = int(res["points_per_pitch"])
    grid = make_grid(geo, p, ppp)
    P = prm["static_tension"] + loads.speed_tensioning(prm["lambda_support"], m, c)
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
    u_ref, w_ref = response(prm, effects, t_ref, ppp, averaged=True)

    def err(t, u):
        return float(np.max(np.abs(np.interp(t_ref, t, u) - u_ref)) / np.max(np.abs(u_ref)))

    out = {"reference_wall": w_ref, "dt_max": dt_max, "dt_min": dt_min, "contact_time": kimp["t_i"]}
    for name, t, avg in (("uniform_sampled", uniform(dt_max), False),
                         ("uniform_averaged", uniform(dt_max), True),
                         ("nonuniform", nonuniform_times(t_end, tau, dt_max, dt_min,
                                                         3 * kimp["t_i"], t0), False)):
        u, w = response(prm, effects, t, ppp, averaged=avg)
        out[name] = {"error": err(t, u), "wall": w, "steps": len(t) - 1}
    # the uniform (point-sampled) step that matches the non-uniform accuracy
    target = out["nonuniform"]["error"]
    dt = dt_max
    while True:
        t = uniform(dt)
        u, w = response(prm, effects, t, ppp, averaged=False)
        e = err(t, u)
        if e <= target or dt <= dt_min / 2:
            out["uniform_equal_accuracy"] = {"error": e, "wall": w, "steps": len(t) - 1, "dt": dt}
            break
        dt /= 2
    return out
