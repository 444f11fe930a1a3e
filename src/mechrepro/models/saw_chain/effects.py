"""The saw_chain outputs (config ``outputs:`` says why; no effects): references and analyses
beside the difference method on its time grid, each evaluated and timed only when named."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechrepro.effects import EffectRegistry
from mechrepro.units import var

from .chain import Chain, Design, join_stages
from .kinematics import stage_derivatives
from .loads import dynamic_load, textbook_velocity_load

EFFECTS = EffectRegistry("saw_chain")


@dataclass(frozen=True)
class Context:
    """What an output sees: the run's chain, its time grid, its SI parameters (the constants of
    Eq. (23) among them) and whether the polygon effect is on (off: the constant-speed rival)."""
    chain: Chain
    t: np.ndarray
    parameters: dict | None = None
    polygon: bool = True


def period_vars(suffix: str, how: str, v, a=None, Fx=None, Fy=None) -> dict:
    """The period's tight-side velocity, acceleration and loads (those given) as variables
    ``<quantity><suffix>`` on the time grid, described by ``how``."""
    spec = (("tight_side_velocity", v, "m/s", "tight-side velocity"),
            ("tight_side_acceleration", a, "m/s2", "tight-side acceleration"),
            ("dynamic_load_x", Fx, "N", "total tight-side dynamic load x"),
            ("dynamic_load_y", Fy, "N", "dynamic load y of the seating link"))
    return {q + suffix: var("t", x, u, f"{d}, {how}") for q, x, u, d in spec if x is not None}


@EFFECTS.register("exact_reference")
def exact_reference(ctx: Context) -> dict:
    """Velocity, acceleration and loads from the exact derivatives of Eqs. (7)-(10) (of the
    rival's positions, linear in time, when the polygon effect is off)."""
    chain = ctx.chain
    if not ctx.polygon:
        zero = np.zeros(ctx.t.size)
        return period_vars("_exact", "exact (constant speed)", np.full(ctx.t.size, chain.chain_speed),
                           zero, zero.copy(), zero.copy())
    vx, ax, Fx, Fy = [], [], [], []
    for L, m_link, phi in chain.stages():
        d = stage_derivatives(phi, chain.R, L, chain.omega)
        fx, fy = dynamic_load(m_link, d["mid_ax"], d["mid_ay"], chain.m_tight, d["trail_ax"])
        vx.append(d["trail_vx"]), ax.append(d["trail_ax"]), Fx.append(fx), Fy.append(fy)
    return period_vars("_exact", "exact derivative", *(join_stages(*x) for x in (vx, ax, Fx, Fy)))


@EFFECTS.register("textbook")
def textbook(ctx: Context) -> dict:
    """The textbook model, Eq. (23), with its phase theta and mass on the solver's grid."""
    chain, p = ctx.chain, ctx.parameters
    v, a, F = textbook_velocity_load(ctx.t, chain.R, chain.omega, p["textbook_phase"],
                                     p["textbook_mass"])
    return period_vars("_textbook", "textbook Eq. (23)", v, a, F)


@EFFECTS.register("identification")
def identification(ctx: Context) -> dict:
    """The paper's six numbers fitted by every explanation of :mod:`.identification`, at each
    declared model error."""
    from . import identification as idf

    p, ch = ctx.parameters, ctx.chain
    design = Design(**ch.inputs())
    paper = np.array([*p["identification_velocities"], *p["identification_loads"]], float)
    speeds, stretches = (np.linspace(a, b, int(round((b - a) / d)) + 1) for a, b, d in
                         (p["identification_scan_speed"], p["identification_scan_stretch"]))
    errors = list(p["identification_model_errors"])
    K = np.arange(2, ch.roundoff_limit() + 1)
    res = [idf.analyse(design, paper, idf.PRINTED, idf.INPUTS_HALF, me, speeds, stretches, K)
           for me in errors]
    return idf.as_variables(res, errors, speeds, stretches)


#: what the design maps span: teeth, pitch ratios p1/p2, sprocket speeds [r/min], links
#: M = N; the rules are checked over teeth 6-40 and pitch ratios 1-2
MAP_TEETH, MAP_RATIOS = np.arange(3, 61), np.geomspace(0.2, 5.0, 121)
MAP_SPEEDS_RPM, MAP_LINKS = np.linspace(1000, 14000, 131), np.arange(2, 101)
RULE_TEETH, RULE_RATIOS = np.arange(6, 41), np.linspace(1.0, 2.0, 101)


@EFFECTS.register("design_maps")
def design_maps(ctx: Context) -> dict:
    """Design maps from the exact closed form and the design rules' errors
    (:func:`.design.design_maps`) around the run's chain."""
    from . import design

    ch = ctx.chain
    base = ch.inputs()
    speeds = MAP_SPEEDS_RPM * np.pi / 30
    d = design.design_maps(base, MAP_TEETH, MAP_RATIOS, speeds, MAP_LINKS, RULE_TEETH, RULE_RATIOS)
    units = {"peak_load": "N", "speed_fluctuation": "1", "textbook_error": "1"}
    long = {"peak_load": "exact peak tight-side load", "speed_fluctuation":
            "relative speed fluctuation (R omega - v_min)/(R omega)", "textbook_error":
            "textbook (Eq. 23) peak / exact peak - 1"}
    dims = {"z": ("map_z_ratio", "map_teeth"), "ratio": ("map_ratio_teeth", "map_ratio"),
            "speed": "map_speed", "links": "map_links", "paper": ()}
    out = {"map_teeth": var("map_teeth", MAP_TEETH, "1", "teeth z"),
           "map_z_ratio": var("map_z_ratio", d["z_ratio"], "1", "pitch ratio p1/p2 of the map over z"),
           "map_ratio": var("map_ratio", MAP_RATIOS, "1", "pitch ratio p1/p2 (p1 + p2 fixed)"),
           "map_ratio_teeth": var("map_ratio_teeth", d["ratio_teeth"], "1", "teeth of the map over p1/p2"),
           "map_speed": var("map_speed", speeds, "rad/s", "sprocket speed"),
           "map_links": var("map_links", MAP_LINKS, "1", "tight-side tie straps M = drive links N"),
           "rule": var("rule", np.arange(len(design.RULES)), "1", "design rule: " + ", ".join(
               f"{i} {k}" for i, k in enumerate(design.RULES))),
           "rule_teeth": var("rule_teeth", RULE_TEETH, "1", "teeth z of the rules' check"),
           "rule_ratio": var("rule_ratio", RULE_RATIOS, "1", "pitch ratio p1/p2 of the rules' check"),
           "rule_error": var(("rule", "rule_teeth", "rule_ratio"), d["rule_error"], "1",
                             "rule / exact - 1 (p1 + p2, masses, links and speed of the run)"),
           "z_peak_load_fixed_chain_speed": var(dims["z"], d["z_peak_load_fixed_chain_speed"], "N",
                                                "exact peak load at the run's chain speed")}
    for m, dd in dims.items():
        for q in design.MAP_QUANTITIES:
            out[f"{m}_{q}"] = var(dd, d[f"{m}_{q}"], units[q], f"{long[q]} ({m} map)")
    return out


#: the levels of output richardson_levels: K = 4 ... 32768, doubling (below the round-off
#: limit 39 434 of the paper's chain)
RICHARDSON_K = 2 ** np.arange(2, 16)


@EFFECTS.register("richardson_levels")
def richardson_levels(ctx: Context) -> dict:
    """The plain peak load at each K of :data:`RICHARDSON_K`, its Richardson extrapolation from
    K/4, K/2, K, their errors against the exact peak and the samples each computes."""
    from .analysis import load_extreme_at
    from .design import rule_peak_load
    from .richardson import from_levels

    ch = ctx.chain
    exact = float(rule_peak_load(**ch.inputs()))
    Ks = RICHARDSON_K[RICHARDSON_K <= ch.roundoff_limit()]
    plain = np.array([load_extreme_at(ch, k) for k in Ks])
    nan = np.full(Ks.size, np.nan)
    value, estimate, samples = nan.copy(), nan.copy(), nan.copy()
    for i in range(2, Ks.size):
        e = from_levels(ch, Ks[i - 2:i + 1], plain[i - 2:i + 1])
        value[i], estimate[i] = e.value, e.estimate
        samples[i] = float(sum(2 * k + 1 for k in Ks[i - 2:i + 1]))
    k = "richardson_k"
    return {
        k: var(k, Ks, "1", "finest steps per stage K of the level"),
        "richardson_exact_peak": var((), exact, "N", "exact peak load (closed form at the stage end)"),
        "richardson_plain_error": var(k, np.abs(plain - exact) / exact, "1",
                                      "relative error of the plain difference-method peak at K"),
        "richardson_error": var(k, np.abs(value - exact) / exact, "1",
                                "relative error of the extrapolation from K/4, K/2, K"),
        "richardson_estimate": var(k, estimate / np.abs(value), "1",
                                   "its estimated relative error (levels + round-off bound)"),
        "richardson_plain_samples": var(k, 2.0 * Ks + 1, "1", "samples computed by one solve at K"),
        "richardson_samples": var(k, samples, "1",
                                  "samples computed by the three solves K/4, K/2, K"),
    }
