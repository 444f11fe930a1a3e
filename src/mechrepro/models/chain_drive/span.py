"""The low/medium-speed span: contributions -> excitation -> FD sweep (Sec. 2.3.2).

One call solves a whole operating-speed sweep as one array computation.
"""
from __future__ import annotations

import math

import numpy as np

from . import fd, geometry
from .geometry import span_geometry
from .effects import EFFECTS, SpanContext, declared_keys, refuse_unhonoured
from .errors import PitchScaleInstability

# the contributions the finite-difference march consumes (effects.py lists every key)
FD_KEYS = ("tension_coefficient", "tension_pulse", "tension", "tension_external",
           "tension_short", "tension_long", "long", "u_left", "u_right", "kappa")
# the additive parts of the dynamic tension P_t, in the order they are summed
# (:func:`dynamic_tension`)
PT_KEYS = ("tension_pulse", "tension", "tension_external")
# what the axial tension P is formed from (:func:`.geometry.axial_tension`): evaluated first
STEADY_KEYS = ("tension_coefficient",)


def make_grid(span: dict, p_c: float, points_per_pitch: int) -> fd.Grid:
    if span["L_short"] == span["L_long"]:
        n = max(int(round(span["L_long"] / p_c * points_per_pitch)), 4)
        return fd.Grid(span["L_long"], n, n)
    n_short = int(round(span["L_short"] / p_c)) * points_per_pitch
    return fd.Grid(span["L_long"], n_short + points_per_pitch, n_short)


def speed_axis(prm: dict, n_speeds: int) -> np.ndarray:
    return np.linspace(prm["speed_min"], prm["speed_max"], int(n_speeds))


def dynamic_tension(c, shape) -> np.ndarray:
    """P_t (Eqs. 2-36/2-37): the sum of the contributions to :data:`PT_KEYS` (in that
    order, the order in which the effects are declared), plus the elastic four-bar load of
    the span length in force (``long``; the short span when the length does not change)."""
    Pt = np.zeros(shape)
    for key in PT_KEYS:
        c.total(key, out=Pt)
    if "tension_short" in c:
        long = c.get("long")
        Pt += (c.get("tension_short") if long is None
               else np.where(long, c.get("tension_long"), c.get("tension_short")))
    return Pt


def pitch_scale_inputs(run: dict, span_geo: dict) -> list[str]:
    """The inputs of a run (by what its effects declare) that kick pitch-scale waves: a
    tension pulse shorter than a wave's transit over one pitch (``tension_pulse``: the
    impact, t_i = 28 us against p / c_w ~ 0.5 ms, a comb of tension impulses that pumps
    mode k with a Mathieu parameter growing like k; docs/chain_drive.md, hard case), and
    the instantaneous length switch (a span whose two lengths differ, f_p != 0)."""
    out = []
    impulsive = sorted(e for e in run["effects"] if "tension_pulse" in run["contributes"][e])
    if impulsive:
        out.append(f"the impulsive tension of {', '.join(impulsive)} (a pulse shorter than a "
                   "wave's transit over one pitch)")
    if "long" in declared_keys(run) and span_geo["L_short"] != span_geo["L_long"]:
        out.append(f"the instantaneous span-length switch (f_p = {span_geo['f_p']:.3g})")
    return out


def refuse_undamped_pitch_scale(res: dict, run: dict, span_geo: dict) -> None:
    """Refuse central differencing with an input that kicks pitch-scale waves
    (:class:`.errors.PitchScaleInstability`), before anything is marched.

    Measured (shooting, Floquet multipliers; T_s = 400 N, 20.25 pitches, 45 speeds over
    470-540 rpm around the order-4 resonance, length switch without impact, cfl 0.98):
    22 / 35 / 37 / 44 of 45 speeds unstable at 3 / 4 / 6 / 8 points per pitch, largest
    multiplier 1.28-1.44 per tooth period; the critical Floquet mode has a wavelength of
    ~2.2 grid intervals (0.56 pitch at 4, 0.28 at 8): it shortens with the grid, so no grid
    converges.  The mixed differencing of Eq. (2-38) is stable there at 4 and 8 points per
    pitch (multipliers 0.95-0.98, critical mode the span's first or second).  With the
    impact pulse, central is unstable at 67-88 of the 200 Fig. 5 speeds on every grid."""
    if res.get("differencing") != "central":
        return
    kicks = pitch_scale_inputs(run, span_geo)
    if kicks:
        raise PitchScaleInstability(
            "central differencing with " + " and ".join(kicks) + ": without numerical damping "
            "the waves of ~2 grid intervals (shorter than a pitch, outside the string model) "
            "that this input kicks grow at most speeds and on every grid (at 3-8 points per "
            "pitch, 22-44 of 45 speeds around the order-4 resonance); use the paper's mixed "
            "differencing (differencing: mixed, Eq. 2-38), whose numerical damping bounds them")


#: blocks of a march's measuring window whose maxima reveal growth (:func:`.fd.march`)
GROWTH_BLOCKS = 4


def excitation_tooth_periods(prm: dict, run) -> int:
    """q, the tooth periods of one excitation period: 1, except with an external load
    cos(r omega1 t) (an effect declaring ``tension_external``, Eq. 2-5), whose period
    2 pi/(r omega1) is n1/r tooth periods: the smallest q holding a whole number of load
    periods (r rational with a small denominator)."""
    from .errors import PeriodicityError

    n1 = int(prm["n1"])
    if ("tension_external" not in declared_keys(run)
            or prm.get("external_load_ratio", 0.0) == 0.0):
        return 1
    r = float(prm["external_frequency_ratio"])
    for q in range(1, 64 * n1 + 1):
        if abs(q * r / n1 - round(q * r / n1)) < 1e-9:
            return q
    raise PeriodicityError(f"external load ratio {r}: no common period with the teeth")


def assemble(run, prm: dict, omega1, res: dict, registry=EFFECTS,
             period: float | None = None) -> dict:
    """Stage the run's effects on the time grid of a sweep; return the march inputs.

    What the named effects declare they contribute (``run["contributes"]``, never their
    names) decides the stages: the steady contributions (the tension coefficient) fix the
    axial tension P, hence the first time step; a declared span-length state (``long``)
    makes the grid cover both span lengths.  Then the dynamic tension, refined until the
    step is stable for it too (each refinement stages it again on its finer grid), and
    the rest (end motion, sag) once, on the final grid.

    ``period`` (s): march exactly one excitation period instead of settling + window (the
    shooting of :mod:`.shooting`): a whole number (>= 3) of steps spans the period.
    """
    refuse_unhonoured(run, FD_KEYS, "finite-difference", registry)
    m, T_s, c_d = prm["mass_per_length"], prm["static_tension"], prm["transverse_damping"]
    omega1 = np.atleast_1d(np.asarray(omega1, float))
    named = declared_keys(run)
    span = span_geometry(prm, "long" in named)
    refuse_undamped_pitch_scale(res, run, span)
    grid = make_grid(span, prm["pitch"], int(res["points_per_pitch"]))
    c = geometry.chain_speed(omega1, int(prm["n1"]), prm["pitch"])
    # the stationary-string rival (option stationary_string): the transport speed leaves
    # the string's operator (no 2 c u_xt, no c^2 u_xx); the sprockets still turn, so the
    # excitation, its tooth frequency and the speed tensioning keep the chain speed
    c_op = np.zeros_like(c) if run.get("options", {}).get("stationary_string") else c
    cache: dict = {}
    k_c = registry.stages(run, SpanContext(prm, omega1, np.zeros(0), None, span, cache=cache))(
        STEADY_KEYS).total("tension_coefficient")
    P = geometry.axial_tension(T_s, k_c, c)
    sigma = c_d / (2 * m)
    tau_max = float(np.max(geometry.tooth_period(omega1, int(prm["n1"]))))
    settle = float(res.get("decay_times", 0.0)) / sigma if sigma > 0 else 0.0
    window = float(res.get("window_periods", 0.0)) * tau_max
    q = excitation_tooth_periods(prm, run)
    if q > 1:
        # an external load repeats every q tooth periods: each growth block must hold a
        # whole excitation period, or its slow modulation reads as growth
        window = max(window, GROWTH_BLOCKS * q * tau_max)
    # the span-length state is part of P_t only where it picks the elastic load
    tension = set(PT_KEYS) | (
        {"tension_short", "tension_long", "long"} if "tension_short" in named else set())
    # a first dt from the static tension, refined below with the dynamic tension bound
    dt = fd.stable_time_step(grid.dx, c_op, P, m, float(res["cfl"]))
    for _ in range(4):
        if period is not None:
            n_steps = max(int(math.ceil(period / dt * (1 - 1e-12))), 3)
            dt = period / n_steps
        else:
            n_steps = int(math.ceil((settle + window) / dt))
        # each pass stages the effects on its own time grid: the dynamic tension first
        # (it decides whether the step is stable), the rest once the step is final
        stages = registry.stages(run, SpanContext(prm, omega1, np.arange(n_steps + 1) * dt, dt,
                                                  span, cache=cache))
        contrib = stages(tension)
        Pt = dynamic_tension(contrib, (n_steps + 1, omega1.size))
        P_max = P + np.max(Pt, axis=0)
        P_min = P + np.min(Pt, axis=0)
        if fd.stable_time_step(grid.dx, c_op, P_max, m, float(res["cfl"])) >= dt * (1 - 1e-12):
            break
        # re-evaluate on a finer grid, with a margin so that one more pass normally suffices
        dt = fd.stable_time_step(grid.dx, c_op, P + 1.1 * np.max(np.abs(Pt), axis=0), m,
                                 float(res["cfl"]))
    else:
        raise fd.StabilityError("no stable time step found for the dynamic tension")
    rest = stages(set(FD_KEYS) - tension - set(STEADY_KEYS))
    long = contrib.get("long") if "long" in contrib else rest.get("long")
    kappa = rest.get("kappa")
    exc = fd.Excitation(tension=Pt, long=long, u_left=rest.get("u_left"),
                        u_right=rest.get("u_right"),
                        load=None if kappa is None else kappa[None, :] * Pt)
    return {"grid": grid, "span": span, "c": c_op, "P": P, "P_min": P_min, "dt": dt,
            "n_steps": n_steps, "exc": exc,
            "measure_from": 0 if period is not None else int(round(settle / dt)),
            # first-difference weight of Eq. (2-38); 0 = central differencing (second order)
            "s_star": (np.zeros_like(c) if res.get("differencing") == "central"
                       else geometry.s_star(c_op, T_s, m)),
            "omega1": omega1, "m": m, "c_d": c_d,
            "tension_coefficient": k_c}


def sweep(run, prm, omega1, res, probes=(), record_every=0, registry=EFFECTS) -> dict:
    """Maximum steady amplitude vs operating speed (Figs. 5-9): every speed in one march."""
    a = assemble(run, prm, omega1, res, registry)
    r = fd.march(c=a["c"], P=a["P"], exc=a["exc"], s_star=a["s_star"], m=a["m"], c_d=a["c_d"],
                 grid=a["grid"], dt=a["dt"], n_steps=a["n_steps"],
                 measure_from=a["measure_from"], u_cap=float(res.get("u_cap", 0.05)),
                 n_blocks=GROWTH_BLOCKS, differencing=res.get("differencing"), probes=probes,
                 record_every=record_every)
    slack = a["P_min"] <= 0
    return {"amplitude": r.amplitude, "growth": r.growth, "unstable": r.unstable | slack,
            "slack": slack, "probes": r.probes, "t_rec": r.t_rec,
            **{k: a[k] for k in ("grid", "span", "c", "P", "P_min", "dt", "n_steps", "s_star",
                                 "tension_coefficient")}}
