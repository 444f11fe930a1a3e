"""The effects of a chain_drive scene: one pure function ``fn(ctx) -> {key: value}`` each.

Declared once in ``config/papers/chain_drive.yaml`` (``effects:``: what each contributes,
its units, which solvers honour it; a run record carries it as ``contributes``).  Every
solver builds a :class:`SpanContext` and asks the framework's registry for contributions
by key (``EFFECTS.evaluate(run, ctx, keys=...)``, or ``EFFECTS.stages(run, ctx)`` stage by
stage), selecting the effects by the keys they declare (:func:`declared_keys`), never by
name; it reads the contributions by key:

=====================  ===========  =====================================================
key                    shape        meaning
=====================  ===========  =====================================================
tension_coefficient    scalar       k in P = T_s + k c^2 (:func:`.geometry.axial_tension`)
tension                (T, S)       dynamic tension P_t, summed over the effects
tension_pulse          (T, S)       a part of P_t that is a pulse shorter than a wave's
                                    transit over one pitch (it kicks pitch-scale waves)
tension_external       (T, S)       a part of P_t periodic in the external load's period
                                    2 pi/(r omega1) (Eq. 2-5), not in the tooth period
tension_short/_long    (T, S)       P_t of the elastic four-bar on the short / long span
long                   (T, S) bool  span-length state (True = long span)
u_left, u_right        (T, S)       end displacements (x = 0 driven, x = L driving)
v_left, v_right        (T, S)       their time derivatives (only when ``ctx.end_velocity``)
kappa                  (S,)         sag factor of the kappa P_t term
coupling_stiffness     scalar       EA of the longitudinal-transverse coupling
=====================  ===========  =====================================================

An effect that is not named is never looked up or evaluated; the shared sprocket
kinematics is computed lazily, only when a named effect asks for it.
"""
from __future__ import annotations

from functools import cached_property

import numpy as np

from mechrepro.effects import EffectRegistry

from . import four_bar, geometry, loads
from .errors import EffectNotHonoured, NoEquilibrium

EFFECTS = EffectRegistry("chain_drive")
G = 9.80665   # standard gravity [m/s^2]


BLOCK = 1 << 16      # samples per block of :meth:`SpanContext.blocked`


class SpanContext:
    """What the effects see: parameters (SI), operating speeds ``omega1`` (S,), times ``t``
    ((T,) shared by every speed, or (T, S)), the averaging window ``step`` of pulses shorter
    than a time step (None: point values, Sec. 3.1), and the span geometry
    (:func:`.geometry.span_geometry`)."""

    def __init__(self, prm: dict, omega1, t, step, span: dict, end_velocity: bool = False,
                 cache: dict | None = None):
        self.prm = prm
        self.omega1 = np.atleast_1d(np.asarray(omega1, float))          # (S,)
        self.t = np.asarray(t, float)
        self.step = step
        self.span = span                                                # L_short, L_long, f_p
        self.end_velocity = end_velocity
        self.cache = {} if cache is None else cache     # elastic four-bar solutions, reused
        self.n1, self.n2 = int(prm["n1"]), int(prm["n2"])
        self.p_c = prm["pitch"]
        self.c = geometry.chain_speed(self.omega1, self.n1, self.p_c)
        self._last: dict = {}

    @property
    def T(self):
        """Times as a (T, 1) or (T, S) array (broadcasts against ``omega1[None, :]``)."""
        return self.t if self.t.ndim == 2 else self.t[:, None]

    def blocked(self, fn) -> dict:
        """``fn(rows) -> {key: (rows, S) array or scalar}`` evaluated block of time rows by
        block (~64k samples each, so that the temporaries of the elementwise formulas stay
        in cache instead of streaming (T, S) arrays through memory once per operation) and
        assembled (0-d/scalar outputs from the first block); the same numbers as one call
        on all rows."""
        n_rows, n_cols = self.T.shape[0], self.omega1.size
        rows = max(1, BLOCK // max(n_cols, 1))
        if n_rows <= 2 * rows:
            return fn(slice(0, n_rows))
        out: dict = {}
        for r0 in range(0, n_rows, rows):
            sl = slice(r0, min(r0 + rows, n_rows))
            for k, v in fn(sl).items():
                if np.ndim(v) == 2:
                    if k not in out:
                        out[k] = np.empty((n_rows, np.shape(v)[1]), np.asarray(v).dtype)
                    out[k][sl] = v
                elif k not in out:
                    out[k] = v
        return out

    def _last_block(self, name: str, rows: slice, fn) -> dict:
        """``fn()`` for the time rows ``rows``, kept until other rows are asked: the effects
        of a one-block grid (every shooting speed) share one evaluation; a many-block sweep
        keeps one block (a few MB), never its (T, S) grid."""
        hit = self._last.get(name)
        if hit is None or hit[0] != (rows.start, rows.stop):
            hit = self._last[name] = ((rows.start, rows.stop), fn())
        return hit[1]

    def phases_of(self, rows: slice) -> dict:
        """The tooth phases of the time rows ``rows`` (:func:`.four_bar.tooth_phases`)."""
        return self._last_block("phases", rows, lambda: four_bar.tooth_phases(
            self.T[rows], self.omega1[None, :], n1=self.n1, n2=self.n2, p_c=self.p_c,
            f_p=self.span["f_p"]))

    def kinematics_of(self, rows: slice) -> dict:
        """The rigid four-bar kinematics of the time rows ``rows`` (computed block by block,
        in cache; the effects keep only their contributions)."""
        return self._last_block("kinematics", rows, lambda: four_bar.rigid_kinematics(
            self.T[rows], self.omega1[None, :], n1=self.n1, n2=self.n2, p_c=self.p_c,
            f_p=self.span["f_p"], phases=self.phases_of(rows)))

    @cached_property
    def kinematics(self) -> dict:
        """The whole kinematics on the (T, S) grid (for the figures of Fig. 3)."""
        return self.blocked(self.kinematics_of)

    def elastic_solution(self, omega1: float, k: float) -> dict:
        """Eq. (2-21) at one speed and span stiffness (solved once per context family)."""
        key = (float(omega1), float(k), self.n1, self.n2, self.span["f_p"])
        if key not in self.cache:
            self.cache[key] = four_bar.elastic_four_bar(
                omega1, k=k, I2=self.prm["driven_inertia"], n1=self.n1, n2=self.n2,
                p_c=self.p_c, f_p=self.span["f_p"])
        return self.cache[key]


def declared_keys(run: dict) -> set:
    """Every key the named effects declare they contribute."""
    return {k for e in run["effects"] for k in run["contributes"][e]}


def refuse_unhonoured(run: dict, keys, solver: str, registry=None) -> None:
    """Refuse, by their declarations and before anything is evaluated, named effects of
    which the solver consumes no declared key (the config refuses such a scene at load
    already; this guards direct calls): an effect is honoured or refused, never ignored.
    (A key a solver does not ask for, like the end velocities outside Galerkin, is not
    returned.)"""
    (registry or EFFECTS).select(run["effects"])     # an unknown name is refused here
    by = [e for e in run["effects"] if not set(run["contributes"][e]) & set(keys)]
    if by:
        extra = sorted({k for e in by for k in run["contributes"][e]})
        raise EffectNotHonoured(f"chain_drive: the {solver} solver does not honour {sorted(by)} "
                                f"(contributions {extra})")


@EFFECTS.register("speed_tensioning")
def speed_tensioning(ctx: SpanContext) -> dict:
    """Eq. (2-1): D_c = lambda m c^2, i.e. P = T_s + k c^2 with k = lambda m."""
    return {"tension_coefficient": ctx.prm["lambda_support"] * ctx.prm["mass_per_length"]}


@EFFECTS.register("impact")
def impact(ctx: SpanContext) -> dict:
    """Eqs. (2-2)-(2-4): impact load, averaged exactly over ``ctx.step`` (point values
    without); a pulse of t_i = 28 us, shorter than a wave's transit over one pitch."""
    k, step = loads.impact_of(ctx.prm), ctx.step

    def rows(r):
        st = step[r] if np.ndim(step) == 2 else step
        return {"tension_pulse": loads.impact_load(ctx.T[r], ctx.omega1[None, :], ctx.n1,
                                                   ctx.p_c, k, step=st)}
    return ctx.blocked(rows)


@EFFECTS.register("polygonal_rigid")
def polygonal_rigid(ctx: SpanContext) -> dict:
    """Eqs. (2-6)-(2-10): D_pol = I2 alpha2 / r2 from the rigid four-bar."""
    def rows(r):
        kin = ctx.kinematics_of(r)
        return {"tension": four_bar.polygonal_load_rigid(kin["alpha2"],
                                                         ctx.prm["driven_inertia"], kin["r2"])}
    return ctx.blocked(rows)


@EFFECTS.register("polygonal_elastic")
def polygonal_elastic(ctx: SpanContext) -> dict:
    """Eqs. (2-11)-(2-23): D_pol of the elastic four-bar with k = AE/L of the short (k1) and
    the long (k2) span; the span-length state (``long``) picks one in time."""
    EA = ctx.prm["axial_stiffness"]
    spans = [("tension_short", EA / ctx.span["L_short"])]
    if ctx.span["L_long"] != ctx.span["L_short"]:
        spans.append(("tension_long", EA / ctx.span["L_long"]))
    sols = {key: [ctx.elastic_solution(w, k) for w in ctx.omega1] for key, k in spans}
    p = ctx.n1 * ctx.omega1                      # the tooth frequency of each speed

    def rows(r):
        # sin, cos of the tooth frequency x t: shared by both spans and both harmonics
        pt = ctx.T[r] * p[None, :]
        sin_pt, cos_pt = np.sin(pt), np.cos(pt)
        return {key: four_bar.polygonal_load_elastic_speeds(sin_pt, cos_pt, sols[key],
                                                            ctx.omega1, k)
                for key, k in spans}
    out = ctx.blocked(rows)
    if len(spans) == 1:
        out["tension_long"] = out["tension_short"]
    return out


@EFFECTS.register("external_load")
def external_load(ctx: SpanContext) -> dict:
    """Eq. (2-5): T_ex cos(omega_ex t), T_ex and omega_ex relative to T_s and omega1 (periodic
    in 2 pi/omega_ex, not in the tooth period: ``tension_external``)."""
    T_ex = ctx.prm["external_load_ratio"] * ctx.prm["static_tension"]
    w_ex = ctx.prm["external_frequency_ratio"] * ctx.omega1[None, :]
    return {"tension_external": loads.external_load(ctx.T, T_ex, w_ex)}


@EFFECTS.register("external_load_static")
def external_load_static(ctx: SpanContext) -> dict:
    """The rival of Eq. (2-5): the external load's amplitude T_ex as a constant tension (a
    static +T_ex / T_s pre-load) instead of T_ex cos(omega_ex t): periodic in every period,
    hence a part of P_t like the tooth-periodic loads (``tension``)."""
    T_ex = ctx.prm["external_load_ratio"] * ctx.prm["static_tension"]
    return {"tension": np.full((ctx.T.shape[0], ctx.omega1.size), T_ex)}


@EFFECTS.register("end_excitation")
def end_excitation(ctx: SpanContext) -> dict:
    """Eqs. (2-24), (2-25): transverse motion of the span ends (with the stated shift), and
    its velocity when the solver asks (the Galerkin end-motion line)."""
    def rows(r):
        k = ctx.kinematics_of(r)
        u0, un = four_bar.end_displacements(k["sin_theta1"], k["sin_theta2"], k["r1"], k["r2"],
                                            ctx.n2)
        out = {"u_left": u0, "u_right": un}
        if ctx.end_velocity:
            out["v_left"], out["v_right"] = four_bar.end_velocities(
                k["cos_theta1"], k["cos_theta2"], ctx.omega1[None, :], k["omega2"], k["r1"],
                k["r2"])
        return out
    return ctx.blocked(rows)


# Gauss-Legendre nodes of the engagement average (the window holds a kink of the polygon
# motion, so the quadrature converges like 1/K^2): 16 nodes are within 5e-4 relative of 64
# in the Fig. 9a amplitude (400 and 900 rpm, 4 points per pitch, measured)
ENGAGEMENT_NODES = np.polynomial.legendre.leggauss(16)


def engagement_time(prm: dict) -> float:
    """t_e = l_e p / sqrt(T_s/m): a wave's transit over ``engagement_spread`` (l_e) pitches
    of the static span, the shortest time scale the string model can represent."""
    return prm["engagement_spread"] * prm["pitch"] * np.sqrt(prm["mass_per_length"]
                                                             / prm["static_tension"])


@EFFECTS.register("end_excitation_distributed")
def end_excitation_distributed(ctx: SpanContext) -> dict:
    """Eqs. (2-24), (2-25) averaged over a centred window of the engagement time t_e
    (:func:`engagement_time`): the roller seats over a finite time instead of at the
    polygon's corner, so the end motion loses the kinks whose harmonics drive every span
    mode at once at a resonance (docs/chain_drive.md, amplitude convergence)."""
    half = 0.5 * engagement_time(ctx.prm)
    x, w = ENGAGEMENT_NODES
    # every node's shifted times in one context (the end motion is pointwise in time: one
    # evaluation instead of one per node, the same numbers), summed node by node in order
    n = ctx.t.shape[0]
    sub = SpanContext(ctx.prm, ctx.omega1, np.concatenate([ctx.t + half * xi for xi in x]),
                      ctx.step, ctx.span, ctx.end_velocity, cache=ctx.cache)
    out: dict = {}
    for k, v in end_excitation(sub).items():
        v = np.asarray(v)
        for i, wi in enumerate(w):
            out[k] = out.get(k, 0.0) + 0.5 * wi * v[i * n:(i + 1) * n]
    return out


@EFFECTS.register("length_change")
def length_change(ctx: SpanContext) -> dict:
    """Sec. 2.2: the span shortens by one pitch at engagement, lengthens at disengagement."""
    def rows(r):
        ph = ctx.phases_of(r)
        return {"long": four_bar.long_span(ph["phase1"], ph["phase2"])}
    return ctx.blocked(rows)


@EFFECTS.register("sag")
def sag(ctx: SpanContext) -> dict:
    """Eq. (2-36) instead of (2-37): the term kappa P_t, kappa = m g / (P_0 - m c^2) (Eq. 2-31)."""
    m = ctx.prm["mass_per_length"]
    kappa = m * G / (ctx.prm["static_tension"] - m * ctx.c**2)
    if np.any(kappa <= 0):
        raise NoEquilibrium("sag: P_0 - m c^2 <= 0, no small-sag equilibrium exists")
    return {"kappa": kappa}


@EFFECTS.register("longitudinal_coupling")
def longitudinal_coupling(ctx: SpanContext) -> dict:
    """Eqs. (2-39)-(2-41): the stretching terms EA (u1,x + u2,x^2 / 2) that couple the
    longitudinal and transverse motion."""
    return {"coupling_stiffness": ctx.prm["axial_stiffness"]}
