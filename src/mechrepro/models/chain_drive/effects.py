"""The effects of a chain_drive scene, one registry entry each.

Every entry takes the scene context (:class:`SpanContext`) and returns its contribution:
``{"static_tension": (S,)}``, ``{"tension": (T, S)}``, ``{"u_left"/"u_right": (T, S)}``,
``{"long": (T, S)}``, or ``{"sag": True}``.  The solver calls only the entries of
``EFFECTS.select(run["effects"])``: an effect that is off is never looked up or evaluated,
and the shared sprocket kinematics is computed lazily, only when a selected effect asks.
"""
from __future__ import annotations

from functools import cached_property

import numpy as np

from mechrepro.effects import EffectRegistry

from . import four_bar, geometry, loads

EFFECTS = EffectRegistry("chain_drive")


class SpanContext:
    """Time grid x operating speeds, parameters (SI) and lazily computed kinematics."""

    def __init__(self, prm: dict, omega1, t, dt: float, span: dict):
        self.prm = prm
        self.omega1 = np.atleast_1d(np.asarray(omega1, float))          # (S,)
        self.t = np.asarray(t, float)                                   # (T,)
        self.dt = dt
        self.span = span                                                # L_short, L_long, f_p
        self.n1, self.n2 = int(prm["n1"]), int(prm["n2"])
        self.p_c = prm["pitch"]
        self.c = geometry.chain_speed(self.omega1, self.n1, self.p_c)

    @property
    def T(self):
        return self.t[:, None]

    @cached_property
    def kinematics(self) -> dict:
        return four_bar.rigid_kinematics(self.T, self.omega1[None, :], n1=self.n1, n2=self.n2,
                                         p_c=self.p_c, f_p=self.span["f_p"])


@EFFECTS.register("speed_tensioning")
def speed_tensioning(ctx: SpanContext) -> dict:
    """Eq. (2-1): P = T_s + lambda m c^2."""
    return {"static_tension": loads.speed_tensioning(ctx.prm["lambda_support"],
                                                     ctx.prm["mass_per_length"], ctx.c)}


@EFFECTS.register("impact")
def impact(ctx: SpanContext) -> dict:
    """Eqs. (2-2)-(2-4): impact load, averaged exactly over each time step."""
    k = loads.impact_constants(ctx.prm["impact_mass_links"] * ctx.p_c * ctx.prm["mass_per_length"],
                               ctx.prm["contact_stiffness"], ctx.prm["contact_damping_ratio"])
    return {"tension": loads.impact_load(ctx.T, ctx.omega1[None, :], ctx.n1, ctx.p_c, k,
                                         step=ctx.dt)}


@EFFECTS.register("polygonal_rigid")
def polygonal_rigid(ctx: SpanContext) -> dict:
    """Eqs. (2-6)-(2-10): D_pol = I2 alpha2 / r2 from the rigid four-bar."""
    kin = ctx.kinematics
    return {"tension": four_bar.polygonal_load_rigid(kin["alpha2"], ctx.prm["driven_inertia"],
                                                     kin["r2"])}


@EFFECTS.register("polygonal_elastic")
def polygonal_elastic(ctx: SpanContext) -> dict:
    """Eqs. (2-11)-(2-23): D_pol of the elastic four-bar with k = AE/L of the current span
    (k1 for the short, k2 for the long span when the length changes)."""
    EA, I2 = ctx.prm["axial_stiffness"], ctx.prm["driven_inertia"]
    out = {}
    for name, L in (("short", ctx.span["L_short"]), ("long", ctx.span["L_long"])):
        k = EA / L
        cols = []
        for w in ctx.omega1:
            sol = four_bar.elastic_four_bar(w, k=k, I2=I2, n1=ctx.n1, n2=ctx.n2, p_c=ctx.p_c,
                                            f_p=ctx.span["f_p"])
            cols.append(four_bar.polygonal_load_elastic(ctx.t, sol, w, k))
        out[name] = np.stack(cols, axis=1)
    return {"tension_by_length": out}


@EFFECTS.register("external_load")
def external_load(ctx: SpanContext) -> dict:
    """Eq. (2-5): T_ex cos(omega_ex t), T_ex and omega_ex relative to T_s and omega1."""
    T_ex = ctx.prm["external_load_ratio"] * ctx.prm["static_tension"]
    w_ex = ctx.prm["external_frequency_ratio"] * ctx.omega1[None, :]
    return {"tension": loads.external_load(ctx.T, T_ex, w_ex)}


@EFFECTS.register("end_excitation")
def end_excitation(ctx: SpanContext) -> dict:
    """Eqs. (2-24), (2-25): transverse motion of the span ends (with the stated shift)."""
    kin = ctx.kinematics
    u0, un = four_bar.end_displacements(kin["theta1"], kin["theta2"], kin["r1"], kin["r2"],
                                        ctx.n2)
    return {"u_left": u0, "u_right": un}


@EFFECTS.register("length_change")
def length_change(ctx: SpanContext) -> dict:
    """Sec. 2.2: the span shortens by one pitch at engagement, lengthens at disengagement."""
    kin = ctx.kinematics
    return {"long": four_bar.long_span(kin["phase1"], kin["phase2"])}


@EFFECTS.register("sag")
def sag(ctx: SpanContext) -> dict:
    """Eq. (2-36) instead of (2-37): the term kappa P_t, kappa = m g / (P_0 - m c^2) (Eq. 2-31)."""
    m = ctx.prm["mass_per_length"]
    P0 = ctx.prm["static_tension"]
    kappa = m * 9.80665 / (P0 - m * ctx.c**2)
    if np.any(kappa <= 0):
        raise ValueError("sag: P_0 - m c^2 <= 0, no small-sag equilibrium exists")
    return {"kappa": kappa}


@EFFECTS.register("longitudinal_coupling")
def longitudinal_coupling(ctx) -> dict:
    """Eqs. (2-39)-(2-41): marks the high-speed Galerkin model (see :mod:`.galerkin`)."""
    return {"galerkin": True}
