"""Scene solver for the low/medium-speed span: effects -> excitation -> FD sweep (Sec. 2.3.2).

One call solves a whole operating-speed sweep as one array computation (``vectorised``),
or speed by speed (``loop``, kept for the benchmark and the equivalence test).
"""
from __future__ import annotations

import math

import numpy as np

from . import fd, geometry
from .effects import EFFECTS, SpanContext


def span_geometry(prm: dict, length_change: bool) -> dict:
    """Common tangent, fractional pitch (Eq. 2-6) and the two span lengths."""
    p = prm["pitch"]
    n1, n2 = int(prm["n1"]), int(prm["n2"])
    C = prm["centre_distance"] * p
    r1, r2 = geometry.pitch_radius(p, n1), geometry.pitch_radius(p, n2)
    L_ct = math.sqrt(C**2 - (r2 - r1) ** 2)
    f_p = geometry.fractional_pitch(L_ct, p)
    L0, L1 = geometry.span_lengths(L_ct, p)
    if not length_change:
        L0 = L1 = L_ct      # the centre distance as an average span length (Fig. 5, solid)
    return {"L_ct": L_ct, "f_p": f_p, "L_short": L0, "L_long": L1}


def make_grid(span: dict, p_c: float, points_per_pitch: int) -> fd.Grid:
    if span["L_short"] == span["L_long"]:
        n = max(int(round(span["L_long"] / p_c * points_per_pitch)), 4)
        return fd.Grid(span["L_long"], n, n)
    n_short = int(round(span["L_short"] / p_c)) * points_per_pitch
    return fd.Grid(span["L_long"], n_short + points_per_pitch, n_short)


def speed_axis(prm: dict, n_speeds: int) -> np.ndarray:
    return np.linspace(prm["speed_min"], prm["speed_max"], int(n_speeds))


def assemble(effects: list[str], prm: dict, omega1, res: dict, registry=EFFECTS) -> dict:
    """Evaluate the selected effects on the time grid; return the march inputs."""
    selected = registry.select(effects)
    if "longitudinal_coupling" in selected:
        raise ValueError("longitudinal_coupling is the high-speed Galerkin model; "
                         "the finite-difference span solver does not take it")
    m, T_s, c_d = prm["mass_per_length"], prm["static_tension"], prm["transverse_damping"]
    span = span_geometry(prm, "length_change" in selected)
    grid = make_grid(span, prm["pitch"], int(res["points_per_pitch"]))
    omega1 = np.atleast_1d(np.asarray(omega1, float))
    c = geometry.chain_speed(omega1, int(prm["n1"]), prm["pitch"])
    # static part first: it fixes the characteristic speeds and hence the time step
    probe = SpanContext(prm, omega1, np.zeros(1), 1.0, span)
    P = np.full(omega1.shape, T_s, float)
    if "speed_tensioning" in selected:
        P = P + selected["speed_tensioning"](probe)["static_tension"]
    sigma = c_d / (2 * m)
    tau_max = float(np.max(geometry.tooth_period(omega1, int(prm["n1"]))))
    settle = float(res["decay_times"]) / sigma if sigma > 0 else 0.0
    window = float(res["window_periods"]) * tau_max
    # a first dt from the static tension, refined below with the dynamic tension bound
    dt = fd.stable_time_step(grid.dx, c, P, m, float(res["cfl"]))
    for _ in range(4):
        n_steps = int(math.ceil((settle + window) / dt))
        t = np.arange(n_steps + 1) * dt
        ctx = SpanContext(prm, omega1, t, dt, span)
        parts = {name: fn(ctx) for name, fn in selected.items() if name != "speed_tensioning"}
        Pt = np.zeros((n_steps + 1, omega1.size))
        for part in parts.values():
            if "tension" in part:
                Pt += part["tension"]
        long = parts["length_change"]["long"] if "length_change" in parts else None
        if "polygonal_elastic" in parts:
            tb = parts["polygonal_elastic"]["tension_by_length"]
            Pt += tb["short"] if long is None else np.where(long, tb["long"], tb["short"])
        P_max = P + np.max(Pt, axis=0)
        P_min = P + np.min(Pt, axis=0)
        if fd.stable_time_step(grid.dx, c, P_max, m, float(res["cfl"])) >= dt * (1 - 1e-12):
            break
        # re-evaluate on a finer grid, with a margin so that one more pass normally suffices
        dt = fd.stable_time_step(grid.dx, c, P + 1.1 * np.max(np.abs(Pt), axis=0), m,
                                 float(res["cfl"]))
    else:
        raise fd.StabilityError("no stable time step found for the dynamic tension")
    exc = fd.Excitation(tension=Pt, long=long)
    if "end_excitation" in parts:
        exc.u_left, exc.u_right = parts["end_excitation"]["u_left"], parts["end_excitation"]["u_right"]
    if "sag" in parts:
        exc.load = parts["sag"]["kappa"][None, :] * Pt
    return {"grid": grid, "span": span, "c": c, "P": P, "P_min": P_min, "dt": dt,
            "n_steps": n_steps, "measure_from": int(round(settle / dt)), "exc": exc,
            "s_star": geometry.s_star(c, T_s, m), "omega1": omega1, "m": m, "c_d": c_d}


def sweep(effects, prm, omega1, res, mode: str = "vectorised", probes=(), record_every=0,
          registry=EFFECTS) -> dict:
    """Maximum steady amplitude vs operating speed (Figs. 5-9)."""
    a = assemble(effects, prm, omega1, res, registry)
    kw = dict(m=a["m"], c_d=a["c_d"], grid=a["grid"], dt=a["dt"], n_steps=a["n_steps"],
              measure_from=a["measure_from"], u_cap=float(res.get("u_cap", 0.05)))
    if mode == "vectorised":
        r = fd.march(c=a["c"], P=a["P"], exc=a["exc"], s_star=a["s_star"], probes=probes,
                     record_every=record_every, **kw)
        out = {"amplitude": r.amplitude, "growth": r.growth, "unstable": r.unstable,
               "probes": r.probes, "t_rec": r.t_rec}
    elif mode == "loop":
        amp, gr, un = [], [], []
        for i in range(a["omega1"].size):
            sl = slice(i, i + 1)
            e = a["exc"]
            exc = fd.Excitation(**{k: (None if getattr(e, k) is None else getattr(e, k)[:, sl])
                                   for k in ("tension", "u_left", "u_right", "long", "load")})
            r = fd.march(c=a["c"][sl], P=a["P"][sl], exc=exc, s_star=a["s_star"][sl], **kw)
            amp.append(r.amplitude[0]); gr.append(r.growth[0]); un.append(r.unstable[0])
        out = {"amplitude": np.array(amp), "growth": np.array(gr), "unstable": np.array(un),
               "probes": None, "t_rec": None}
    else:
        raise ValueError(f"sweep mode {mode!r}: allowed vectorised, loop")
    slack = a["P_min"] <= 0
    out["unstable"] = out["unstable"] | slack
    out.update({k: a[k] for k in ("grid", "span", "c", "P", "P_min", "dt", "n_steps", "s_star")})
    out["slack"] = slack
    return out
