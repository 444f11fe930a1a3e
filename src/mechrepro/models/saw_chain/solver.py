"""The saw_chain solver: the kinematic difference method, Eqs. (1)-(22), over one period (a
drive link, then a tie strap, seated on a tooth) with K steps per stage; the outputs a
scene names contribute beside it on the same grid."""
from __future__ import annotations

import numpy as np

from mechrepro.units import var

from .chain import Chain, chain_from_run
from .difference import check_roundoff, difference_arrays, roundoff_load, truncation_load
from .effects import EFFECTS, Context, period_vars
from .kinematics import stage_positions

__all__ = ["EFFECTS", "SOLVERS", "Chain", "chain_from_run", "constant_speed", "context",
           "difference_method", "stage_switch_index", "variables"]

#: the difference method's outputs and the reference's contribution each is compared with
COMPARED = {"tight_side_velocity": "tight_side_velocity_exact",
            "dynamic_load_x": "dynamic_load_x_exact"}


def difference_method(chain: Chain, beyond_roundoff_limit: bool = False, loads: bool = True) -> dict:
    """Tight-side velocity, acceleration and loads by backward differences: Eqs. (11)-(13) in
    stage 1 (from V^0 = R omega, a^0 = 0), Eqs. (17)-(19) in stage 2 (from O2's values at t1),
    loads Eqs. (14)-(16), (20)-(22), and the error budget.  K beyond the round-off limit is
    refused unless allowed; ``loads=False`` computes the velocity alone, refused only beyond
    its own (higher) limit."""
    if not loads:
        return velocity_only(chain, beyond_roundoff_limit)
    budget = error_budget(chain, beyond_roundoff_limit)
    return {**period_vars("", "difference method (Eqs. 11-22)", *difference_arrays(chain)), **budget}


def velocity_only(chain: Chain, beyond_roundoff_limit: bool = False) -> dict:
    """The tight-side velocity alone, Eqs. (12), (18), refused only beyond its own limit."""
    budget = velocity_budget(chain, beyond_roundoff_limit)
    parts = []
    for L, _, phi in chain.stages():
        x = stage_positions(phi, chain.R, L, chain.Tx)["trail_x"]
        parts.append(np.diff(x) * (1.0 / ((phi[1] - phi[0]) / chain.omega)))  # as Eq. (12) in the full method
    vx = np.concatenate([[chain.R * chain.omega], *parts])
    return {**period_vars("", "difference method (Eqs. 12, 18)", vx), **budget}


def velocity_budget(chain: Chain, beyond_roundoff_limit: bool) -> dict:
    """Whether this K is beyond the velocity's round-off limit (refused unless allowed)."""
    dominated = check_roundoff(chain.K, chain.velocity_roundoff_limit(), beyond_roundoff_limit,
                               what="velocities")
    return {"roundoff_dominated": var((), int(dominated), "1",
                                      "1 if K is beyond the velocity's round-off limit")}


def constant_speed(chain: Chain, loads: bool = True, beyond_roundoff_limit: bool = False) -> dict:
    """The rival without the polygon effect (``options.polygon: false``): the pitch-line speed
    :attr:`.Chain.chain_speed` everywhere, zero acceleration and load (round-off left out, so
    the rival does not depend on the CPU); K is refused as in the method."""
    n, how = 2 * chain.K + 1, "constant speed (rival)"
    v = np.full(n, chain.chain_speed)
    if not loads:
        return {**period_vars("", how, v), **velocity_budget(chain, beyond_roundoff_limit)}
    zero = np.zeros(n)
    return {**period_vars("", how, v, zero, zero.copy(), zero.copy()),
            **error_budget(chain, beyond_roundoff_limit)}


def error_budget(chain: Chain, beyond_roundoff_limit: bool) -> dict:
    """Round-off bound and truncation estimate of one load sample, the round-off limit of K and
    whether this K is beyond it (:mod:`.difference`); refused unless allowed."""
    limit = chain.roundoff_limit()
    dominated = check_roundoff(chain.K, limit, beyond_roundoff_limit)
    K = chain.K
    truncation = max(truncation_load(T / K, J)
                     for T, J in zip(chain.stage_times(), chain.load_jerk_max()))
    roundoff = roundoff_load(min(chain.stage_times()) / K, chain.Tx + chain.R, chain.roundoff_mass())
    return {
        "roundoff_load_bound": var((), roundoff, "N",
                                   "bound of round-off in a load sample (second backward difference)"),
        "truncation_load_estimate": var((), truncation, "N",
                                        "leading truncation error of a load sample, dt max|dF/dt|"),
        "roundoff_limit_K": var((), limit, "1",
                                "K beyond which round-off exceeds truncation (refused unless allowed)"),
        "roundoff_dominated": var((), int(dominated), "1",
                                  "1 if K is beyond the round-off limit (allowed for the study)"),
    }


def stage_switch_index(K):
    """Index of the first sample of stage 2, t1 + dt (Sec. 3.3 (2)).  Eqs. (18)-(19) start
    stage 2 from O2's stage-1 values, so this acceleration is a second difference across the
    jump at t1: it tends to a step-ratio-weighted mean of the one-sided values, not the exact
    load, and its error does not shrink with K."""
    return K + 1


def context(run: dict) -> Context:
    """What the solver and the outputs see: the run's chain, its time grid, its SI parameters
    and whether the polygon effect is on (``options.polygon: false``: the constant-speed
    rival, rivals.constant_speed)."""
    chain = chain_from_run(run)
    return Context(chain, chain.time(), run["parameters"], run.get("options", {}).get("polygon", True))


def one_period(run: dict, ctx: Context) -> dict:
    """The difference method (or its rival) and the outputs the scene names (timed apart, so
    ``core_time`` is the method's alone)."""
    opts, chain = run.get("options", {}), ctx.chain
    if ctx.polygon:
        method = difference_method(chain, opts.get("beyond_roundoff_limit", False),
                                   opts.get("loads", True))
    else:
        method = constant_speed(chain, opts.get("loads", True), opts.get("beyond_roundoff_limit", False))
    c = EFFECTS.evaluate(run, ctx)
    return {"chain": chain, "t": ctx.t, "data": method | {key: c.get(key) for key in c.keys()}}


SOLVERS = {"difference_method": one_period}


def ranges(ds: dict) -> dict:
    """Minimum and maximum of velocity and load x of each model present in ``ds`` (arrays)."""
    out = {}
    for suffix, label in (("", "difference method"), ("_exact", "exact"), ("_textbook", "textbook")):
        for q, unit in (("tight_side_velocity", "m/s"), ("dynamic_load_x", "N")):
            name = q + suffix
            if name in ds:
                out[f"{name}_min"] = var((), float(ds[name].min()), unit, f"minimum of {q}, {label}")
                out[f"{name}_max"] = var((), float(ds[name].max()), unit, f"maximum of {q}, {label}")
    return out


def errors_against_exact(ds: dict, K: int) -> dict:
    """Errors of the difference method against the exact reference, relative to max |exact|;
    pointwise errors exclude the stage-switch sample (reported on its own)."""
    switch = stage_switch_index(K)
    keep = np.arange(ds["t"].size) != switch
    out = {}
    for q, exact in COMPARED.items():
        if q not in ds:
            continue
        ref = ds[exact]
        # absolute where the exact is identically zero (the loads of the constant-speed rival)
        scale = np.max(np.abs(ref)) or 1.0
        err = np.abs(ds[q] - ref) / scale
        out[f"{q}_error_pointwise"] = var((), float(err[keep].max()), "1",
                                          f"max over samples (stage switch excluded) of |{q} - exact|, relative to max |exact|")
        out[f"{q}_error_pointwise_rms"] = var((), float(np.sqrt(np.mean(err[keep] ** 2))), "1",
                                              f"RMS over samples (stage switch excluded) of |{q} - exact|, relative to max |exact|")
        out[f"{q}_error_switch"] = var((), float(err[switch]), "1",
                                       f"|{q} - exact| at the stage-switch sample t1 + dt, relative to max |exact|")
    if "dynamic_load_x" not in ds:
        return out
    out["dynamic_load_x_switch"] = var((), float(ds["dynamic_load_x"][switch]), "N",
                                       "difference-method load at the stage-switch sample t1 + dt")
    out["dynamic_load_x_switch_exact"] = var((), float(ds["dynamic_load_x_exact"][switch]), "N",
                                             "exact load at the stage-switch sample t1 + dt")
    return out


def variables(result: dict, run: dict) -> dict:
    """A :func:`one_period` result as labelled variables with the scalars a study stacks."""
    chain, t = result["chain"], result["t"]
    out = {"t": var("t", t, "s", "time since O1 left the tangent point T"),
           "stage": var("t", np.where(np.arange(t.size) <= chain.K, 1, 2), "1",
                        "stage of the period (Sec. 3.1)"), **result["data"]}
    arrays = {k: np.asarray(v[1]) for k, v in out.items()}
    out |= ranges(arrays)
    if all(exact in arrays for exact in COMPARED.values()):
        out |= errors_against_exact(arrays, chain.K)
    if not run.get("options", {}).get("keep_history", True):
        # the scalars above are what a study stacks; the history itself is 16 bytes x
        # 2K + 1 samples per variable (45 MB per run at K = 1e6) that nothing reads
        out = {k: v for k, v in out.items() if v[0] != ("t",)}
    return out | {
        "pitch_radius": var((), chain.R, "m", "sprocket pitch radius, Eq. (1)"),
        "sprocket_speed": var((), chain.omega, "rad/s", "sprocket speed omega"),
        "period": var((), t[-1], "s", "period t2 of one tooth, Eq. (6)")}
