"""The low/medium-speed span: contributions -> excitation -> FD sweep (Sec. 2.3.2).

One call solves a whole operating-speed sweep as one array computation (``vectorised``),
or speed by speed (``loop``, kept for the benchmark and the equivalence test).
"""
from __future__ import annotations

import math

import numpy as np

from . import fd, geometry
from .effects import EFFECTS, SpanContext, consume
from .errors import PitchScaleInstability, UnknownChoice

# the contributions the finite-difference march consumes (effects.py lists every key)
FD_KEYS = ("tension_coefficient", "tension", "tension_short", "tension_long", "long",
           "u_left", "u_right", "kappa")


def span_geometry(prm: dict, length_change: bool = True) -> dict:
    """Common tangent, fractional pitch (Eq. 2-6) and the two span lengths (both L_ct
    without ``length_change``: the centre distance as an average span length)."""
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


def as_run(effects) -> dict:
    """A run record (``effects``, and ``contributes`` when it comes from the config), or a
    plain list of effect names (tests, benchmarks) made into one."""
    return effects if isinstance(effects, dict) else {"effects": list(effects)}


def dynamic_tension(c, shape) -> np.ndarray:
    """P_t (Eqs. 2-36/2-37): the sum of the ``tension`` contributions, plus the elastic
    four-bar load of the span length in force (``long``; the short span when the length
    does not change)."""
    Pt = c.total("tension", zero=np.zeros(shape))
    if "tension_short" in c:
        long = c.get("long")
        Pt = Pt + (c.get("tension_short") if long is None
                   else np.where(long, c.get("tension_long"), c.get("tension_short")))
    return Pt


# Effects whose tension is a pulse shorter than a wave's transit over one pitch (the impact:
# t_i = 28 us against p / c_w ~ 0.5 ms): a comb of tension impulses, which pumps mode k with
# a Mathieu parameter growing like k (docs/chain_drive.md, hard case).
IMPULSIVE_TENSION = frozenset({"impact"})


def pitch_scale_inputs(probe, span_geo: dict) -> list[str]:
    """The inputs of a run (its contributions to the probe) that kick pitch-scale waves: the
    impulsive impact in the tension, and the instantaneous length switch (a span whose two
    lengths differ, f_p != 0)."""
    out = []
    impulsive = sorted(set(probe.sources("tension")) & IMPULSIVE_TENSION) if "tension" in probe \
        else []
    if impulsive:
        out.append(f"the impulsive tension of {', '.join(impulsive)} (a pulse shorter than a "
                   "wave's transit over one pitch)")
    if "long" in probe and span_geo["L_short"] != span_geo["L_long"]:
        out.append(f"the instantaneous span-length switch (f_p = {span_geo['f_p']:.3g})")
    return out


def refuse_undamped_pitch_scale(res: dict, probe, span_geo: dict) -> None:
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
    kicks = pitch_scale_inputs(probe, span_geo)
    if kicks:
        raise PitchScaleInstability(
            "central differencing with " + " and ".join(kicks) + ": without numerical damping "
            "the waves of ~2 grid intervals (shorter than a pitch, outside the string model) "
            "that this input kicks grow at most speeds and on every grid (at 3-8 points per "
            "pitch, 22-44 of 45 speeds around the order-4 resonance); use the paper's mixed "
            "differencing (differencing: mixed, Eq. 2-38), whose numerical damping bounds them")


# the contributions the dynamic tension P_t is formed from (:func:`dynamic_tension`)
TENSION_KEYS = ("tension", "tension_short", "tension_long", "long")


def _tension_effects(run: dict, probe) -> tuple[list | None, list]:
    """The named effects the dynamic tension depends on, and the others, from the keys each
    contributed to the probe (``long`` counts only with ``tension_short``: it then picks the
    elastic load).  (None, []) when the split is not known: evaluate everything at once."""
    keys = set(TENSION_KEYS) if "tension_short" in probe else {"tension"}
    by_effect: dict = {}
    for key in probe.keys():
        for e in probe.sources(key):
            by_effect.setdefault(e, set()).add(key)
    named = list(run["effects"])
    dyn = [e for e in named if by_effect.get(e, set()) & keys]
    rest = [e for e in named if e not in dyn and e in by_effect]
    if any(e not in by_effect for e in named):
        return None, []      # an effect contributed nothing to the probe: keep one pass
    return dyn, rest


class _Merged:
    """Two :class:`~mechrepro.effects.Contributions` of disjoint effects read as one."""

    def __init__(self, first, second):
        self.parts = (first, second)

    def __contains__(self, key):
        return any(key in p for p in self.parts)

    def get(self, key, default=None):
        for p in self.parts:
            if key in p:
                return p.get(key)
        return default


def assemble(effects, prm: dict, omega1, res: dict, registry=EFFECTS,
             period: float | None = None) -> dict:
    """Evaluate the named effects on the time grid of a sweep; return the march inputs.

    ``effects``: the run (or a list of effect names).  First every named effect is probed
    on one time sample: the steady contributions fix the axial tension P (the tension
    coefficient: hence the characteristic speeds and the time step) and whether the span
    length changes (a ``long`` state: the grid then covers both span lengths; otherwise
    the span is the common tangent L_ct).  Then the effects are evaluated on the time grid,
    refined until the step is stable for the dynamic tension too.

    ``period`` (s): march exactly one excitation period instead of settling + window (the
    shooting of :mod:`.shooting`): the step is the stable step shortened so that a whole
    number (>= 3) of steps spans the period, and no settling time is added.
    """
    run = as_run(effects)
    m, T_s, c_d = prm["mass_per_length"], prm["static_tension"], prm["transverse_damping"]
    omega1 = np.atleast_1d(np.asarray(omega1, float))
    full = span_geometry(prm, True)
    cache: dict = {}
    probe = consume(registry.evaluate(run, SpanContext(prm, omega1, np.zeros(1), 1.0, full,
                                                       cache=cache)), FD_KEYS, "finite-difference")
    span = full if "long" in probe else span_geometry(prm, False)
    refuse_undamped_pitch_scale(res, probe, span)
    grid = make_grid(span, prm["pitch"], int(res["points_per_pitch"]))
    c = geometry.chain_speed(omega1, int(prm["n1"]), prm["pitch"])
    k_c = probe.total("tension_coefficient")
    P = geometry.axial_tension(T_s, k_c, c)
    sigma = c_d / (2 * m)
    tau_max = float(np.max(geometry.tooth_period(omega1, int(prm["n1"]))))
    settle = float(res.get("decay_times", 0.0)) / sigma if sigma > 0 else 0.0
    window = float(res.get("window_periods", 0.0)) * tau_max
    # the refinement passes evaluate only the effects the dynamic tension depends on (by
    # their declared contributions); the others (end motion, sag) once, on the final grid
    dyn, rest = _tension_effects(run, probe)
    # a first dt from the static tension, refined below with the dynamic tension bound
    dt = fd.stable_time_step(grid.dx, c, P, m, float(res["cfl"]))
    for _ in range(4):
        if period is not None:
            n_steps = max(int(math.ceil(period / dt * (1 - 1e-12))), 3)
            dt = period / n_steps
        else:
            n_steps = int(math.ceil((settle + window) / dt))
        t = np.arange(n_steps + 1) * dt
        ctx = SpanContext(prm, omega1, t, dt, span, cache=cache)
        contrib = registry.evaluate(run if dyn is None else dict(run, effects=dyn), ctx)
        Pt = dynamic_tension(contrib, (n_steps + 1, omega1.size))
        P_max = P + np.max(Pt, axis=0)
        P_min = P + np.min(Pt, axis=0)
        if fd.stable_time_step(grid.dx, c, P_max, m, float(res["cfl"])) >= dt * (1 - 1e-12):
            break
        # re-evaluate on a finer grid, with a margin so that one more pass normally suffices
        dt = fd.stable_time_step(grid.dx, c, P + 1.1 * np.max(np.abs(Pt), axis=0), m,
                                 float(res["cfl"]))
    else:
        raise fd.StabilityError("no stable time step found for the dynamic tension")
    if rest:
        # the same context: the sprocket kinematics computed for the tension is reused
        more = registry.evaluate(dict(run, effects=rest), ctx)
        contrib = _Merged(contrib, more)
    kappa = contrib.get("kappa")
    exc = fd.Excitation(tension=Pt, long=contrib.get("long"), u_left=contrib.get("u_left"),
                        u_right=contrib.get("u_right"),
                        load=None if kappa is None else kappa[None, :] * Pt)
    return {"grid": grid, "span": span, "c": c, "P": P, "P_min": P_min, "dt": dt,
            "n_steps": n_steps, "exc": exc,
            "measure_from": 0 if period is not None else int(round(settle / dt)),
            # first-difference weight of Eq. (2-38); 0 = central differencing (second order)
            "s_star": (np.zeros_like(c) if res.get("differencing") == "central"
                       else geometry.s_star(c, T_s, m)),
            "omega1": omega1, "m": m, "c_d": c_d,
            "tension_coefficient": k_c}


def sweep(effects, prm, omega1, res, mode: str = "vectorised", probes=(), record_every=0,
          registry=EFFECTS) -> dict:
    """Maximum steady amplitude vs operating speed (Figs. 5-9)."""
    a = assemble(effects, prm, omega1, res, registry)
    kw = dict(m=a["m"], c_d=a["c_d"], grid=a["grid"], dt=a["dt"], n_steps=a["n_steps"],
              measure_from=a["measure_from"], u_cap=float(res.get("u_cap", 0.05)),
              differencing=res.get("differencing"))
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
        raise UnknownChoice(f"sweep mode {mode!r}: allowed vectorised, loop")
    slack = a["P_min"] <= 0
    out["unstable"] = out["unstable"] | slack
    out.update({k: a[k] for k in ("grid", "span", "c", "P", "P_min", "dt", "n_steps", "s_star",
                                  "tension_coefficient")})
    out["slack"] = slack
    return out
