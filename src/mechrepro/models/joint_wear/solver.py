"""The solvers of joint_wear: a scene's ``solver`` decides the joint model and method, its
effects (effects.py) the terms; both are declared in ``config/papers/joint_wear.yaml``.

Solvers
-------
``clearance_implicit``  dynamic clearance joint (Eqs. 5-15), stiff implicit integrator
                        (``resolution.method``: Radau, BDF, LSODA); wear on that model
``clearance_explicit``  the same equations with an explicit integrator stopped by a step
                        budget: its cost per period, extrapolated; no wear
``continuous_contact``  quasi-static continuous contact (Sec. 3.2), the paper's model;
                        wear on that model
``period_by_period``    Fig. 6: the wear simulated one period at a time (timed sample)
``coefficient_scan``    the calibration (Eqs. 32-34) over load points F and gravity
                        planes the paper leaves open (contact loss refused)
``load_point_fit``      F estimated from Tables 3-4 jointly, with its uncertainty, its
                        contact arc and wear side, and the 86-h wear it predicts
``constant_sensitivity`` friction, contact exponent, d_max, C_max reading at their range ends
``local_wear``          local Archard wear per bushing angle vs the uniform depth (Fig. 14)

Each builds a :class:`~.effects.Context`, evaluates the named effects in three stages
(mechanism terms, wear set-up, wear) and reads their contributions by key.
"""
from __future__ import annotations

import functools
import math
from dataclasses import replace

import numpy as np

from mechrepro.errors import Refusal
from mechrepro.timing import stopwatch

from . import dataset, dynamics, kinematics, quasistatic, wear
from .effects import EFFECTS, Context
from .geometry import FourBar, from_parameters

#: the contributions each stage reads (the effects that contribute them are evaluated there)
MECHANISM = ("gravity", "friction_coefficient", "damping_ceiling")
WEAR_SETUP = ("sides", "worn_bushing")
WEAR = ("wear",)
NO_FACTOR = dict.fromkeys(("S", "F_N_mean", "AB_mean", "A_mean", "arc", "arc_q90", "L_arc",
                           "L_wear", "G", "min_penetration", "F_N_min", "F_N_max"), math.nan)


class ContactLost(Refusal):
    """The joint force vanishes over the period: the continuous-contact model (Sec. 3.2)
    does not apply there."""


# --- the mechanism ---------------------------------------------------------------------------
def setup(run: dict) -> tuple[FourBar, Context]:
    """The mechanism of a run with the terms its effects contribute, and the context."""
    p = run["parameters"]
    s = {**run.get("resolution", {}), **run.get("options", {})}
    bare = from_parameters(p)
    c = EFFECTS.evaluate(run, Context(p, s, bare), keys=MECHANISM)
    fb = replace(bare, g=c.total("gravity"), mu=c.total("friction_coefficient"),
                 C_max=c.total("damping_ceiling"))
    return fb, Context(p, s, fb)


# --- joint models over one period ------------------------------------------------------------
def quasi_static_period(fb: FourBar, s: dict) -> dict:
    """Quasi-static continuous contact over one period (n_steps uniform samples)."""
    return quasistatic.one_period(fb, int(s["n_steps"]))


def dynamic_period(fb: FourBar, s: dict) -> dict:
    """Dynamic clearance joint; the last of ``periods`` periods, as one period.  An
    integration stopped by its step budget returns what it reached, flagged."""
    periods, n_out, T = int(s.get("periods", 1)), int(s["n_out"]), fb.period
    r = dynamics.simulate(fb, periods * T, periods * n_out + 1, method=s["method"],
                          rtol=float(s["rtol"]), damping=fb.C_max > 0.0,
                          start=s.get("start", "equilibrium"), max_steps=s.get("max_steps"))
    if r["status"] == -1:
        raise RuntimeError(f"joint_wear: {s['method']} failed at t = {r['t_reached']:.4g} s: "
                           f"{r['message']}")
    completed = r["status"] == 0
    sl = slice(-(n_out + 1), -1) if completed else slice(None)
    out = {k: np.asarray(v)[sl] for k, v in r.items()
           if isinstance(v, np.ndarray) and v.ndim == 1 and v.size == r["t"].size}
    out["t"] = out["t"] - (periods - 1) * T
    out.update(nfev=r["nfev"], steps=r["steps"], full=r, completed=completed,
               t_reached=r["t_reached"], integration_wall=r["wall"], message=r["message"])
    return out


def finished_dynamic_period(fb: FourBar, s: dict) -> dict:
    """A dynamic period that must finish (wear needs a whole period)."""
    hist = dynamic_period(fb, s)
    if not hist["completed"]:
        raise RuntimeError(f"joint_wear: {hist['message']}: no period to compute wear from")
    return hist


CONTACT_LOSS_FRACTION = 1e-2


def continuous_contact_period(fb: FourBar, s: dict) -> dict:
    """A quasi-static period for the wear model: refused where contact is lost.

    The continuous-contact model (Sec. 3.2) cannot represent a joint force that vanishes:
    there the pin flies across the clearance (the dynamic model shows it).  Below 1 % of
    its peak the force is taken as vanishing -- a refusal, never a verdict."""
    hist = quasi_static_period(fb, s)
    F = np.asarray(hist["F_N"])
    if not F.min() > CONTACT_LOSS_FRACTION * F.max():
        i = int(np.argmin(F))
        raise ContactLost(
            f"joint_wear: continuous contact lost: the joint-B force falls to {F[i]:.3g} N "
            f"(peak {F.max():.3g} N) at t = {hist['t'][i]:.3g} s; the continuous-contact wear "
            "model (Sec. 3.2) does not apply -- use the clearance_implicit solver")
    return hist


# --- what every period solver shares ------------------------------------------------------------
def one_period(fb: FourBar, s: dict, joint) -> dict:
    """One period of ``joint``, its wall time and its wear factor (Eqs. 18-24, 29)."""
    with stopwatch() as sw:
        hist = joint(fb, s)
    out = {"fb": fb, "hist": hist, "period_wall": sw.seconds}
    if hist.get("completed", True):
        out["factor"] = wear.period_wear_factor(hist, fb, fb.period,
                                                s.get("wear_range", "contact_point"))
    else:   # the time the unfinished integrator would need per period (a timing only)
        out["period_wall"] = hist["integration_wall"] * fb.period / max(hist["t_reached"], 1e-12)
        out["factor"] = dict(NO_FACTOR)
    return out


def with_wear(run: dict, fb: FourBar, ctx: Context, res: dict, joint) -> dict:
    """Stages two and three: the wear set-up, then the wear effects on ``joint``."""
    ctx = replace(ctx, one_period=lambda fb_w: joint(fb_w, ctx.s))
    c = EFFECTS.evaluate(run, ctx, keys=WEAR_SETUP)
    ctx = replace(ctx, sides=c.get("sides", ["B1"]), worn_bushing=c.get("worn_bushing"))
    c = EFFECTS.evaluate(run, ctx, keys=WEAR)
    if "wear" in c:
        res["wear"] = c.get("wear")
    return res


# --- the solvers -----------------------------------------------------------------------------
def clearance_implicit(run: dict) -> dict:
    fb, ctx = setup(run)
    res = one_period(fb, ctx.s, dynamic_period)
    return with_wear(run, fb, ctx, res, finished_dynamic_period)


def clearance_explicit(run: dict) -> dict:
    fb, ctx = setup(run)
    return one_period(fb, ctx.s, dynamic_period)


def continuous_contact(run: dict) -> dict:
    fb, ctx = setup(run)
    res = one_period(fb, ctx.s, quasi_static_period)
    return with_wear(run, fb, ctx, res, continuous_contact_period)


def period_by_period(run: dict) -> dict:
    """Fig. 6: a sample of consecutive periods, each simulated and its wear added before
    the next (the bushing grows every period); only its time is a result."""
    fb, ctx = setup(run)
    res = one_period(fb, ctx.s, quasi_static_period)
    n = int(ctx.s["period_by_period_sample"])
    k = 1e-13   # any coefficient: only the time per period is measured here

    def g_of(R_bush):
        fb_w = fb.with_bushing_radius(R_bush)
        return wear.period_wear_factor(quasi_static_period(fb_w, ctx.s), fb_w, fb.period,
                                       ctx.s.get("wear_range", "contact_point"),
                                       statistics=False)["G"]
    with stopwatch() as sw:
        wear.period_by_period(float(ctx.p["measured_wear_B1"][-1]), n, k, fb.R_bush, g_of)
    res["pbp"] = (n, sw.seconds)
    return res


SIDES = ("B1", "B2")


def load_point(fb: FourBar, E, distance: float, direction_deg: float, g: float) -> FourBar:
    """The mechanism with F at ``distance`` [m] from E's mid-stroke position ``E`` in the
    direction ``direction_deg`` (from +x, anticlockwise) and gravity ``g`` [m/s2]."""
    a = math.radians(direction_deg)
    return replace(fb, g=g, F=(E[0] + distance * math.cos(a), E[1] + distance * math.sin(a)))


def load_point_grid(run: dict, prefix: str):
    """The set-up of a solver over load points: the mechanism, its context, E's mid-stroke
    position and the options ``<prefix>_load_distance``, ``<prefix>_load_direction_deg``,
    ``<prefix>_gravity``."""
    fb, ctx = setup(run)
    s = ctx.s
    return (fb, ctx, kinematics.load_point_mid_stroke(fb), float(s[f"{prefix}_load_distance"]),
            np.asarray(s[f"{prefix}_load_direction_deg"], float),
            np.asarray(s[f"{prefix}_gravity"], float))


def wear_factor_of(fb_v: FourBar, s: dict):
    """G(R_bush): the wear factor of one continuous-contact period of ``fb_v`` with the
    bushing at radius R_bush (what calibration and prediction step through).  A radius
    met again (both sides start calibrating at the new bushing) is not solved again."""
    @functools.cache
    def factor(R_bush):
        fb_w = fb_v.with_bushing_radius(R_bush)
        return wear.period_wear_factor(continuous_contact_period(fb_w, s), fb_w,
                                       fb_v.period, statistics=False)["G"]
    return factor


def coefficient_scan(run: dict) -> dict:
    """The mean calibrated coefficient of both sides over load points F and gravity planes.

    F is placed at ``scan_load_distance`` [m] from E's mid-stroke position in each of the
    directions ``scan_load_direction_deg`` (from +x, anticlockwise); the gravity values
    ``scan_gravity`` [m/s2] stand for planes of motion from horizontal (0) to vertical.
    Only the calibration is run (5 periods per point): it is what fixes the coefficient.
    """
    fb, ctx, E, d, dirs, gs = load_point_grid(run, "scan")
    s, p = ctx.s, ctx.p
    k = np.full((len(SIDES), gs.size, dirs.size), np.nan)
    L = np.full((gs.size, dirs.size), np.nan)
    F_min = np.full((gs.size, dirs.size), np.nan)
    for i, g in enumerate(gs):
        for j, a in enumerate(dirs):
            fb_v = load_point(fb, E, d, a, g)
            f0 = wear.period_wear_factor(quasi_static_period(fb_v, s), fb_v, fb.period)
            L[i, j], F_min[i, j] = f0["L_arc"], f0["F_N_min"]
            try:
                k[:, i, j] = [float(np.mean(K)) for K in _calibrated(fb_v, s, p)]
            except ContactLost:     # the paper's premise fails there -- refused (k stays NaN)
                pass
    return {"fb": fb, "scan": {"k": k, "L_arc": L, "F_N_min": F_min, "directions": dirs,
                               "gravity": gs, "E_mid": E, "distance": d, "sides": list(SIDES)}}


def _calibrated(fb_v: FourBar, s: dict, p: dict, sides=SIDES, factor=None) -> np.ndarray:
    """K_p [m2/N] of Eqs. (32)-(34) for each side (rows) and interval (columns) with the
    mechanism fb_v on the quasi-static joint (``factor``: its wear_factor_of, if made
    already); ContactLost where continuous contact is lost."""
    cal_h = float(p["measurement_interval"]) / 3600.0
    factor = factor or wear_factor_of(fb_v, s)
    return np.array([wear.calibrate(p[f"measured_wear_{side}"], cal_h, fb_v.period,
                                    fb_v.R_bush, factor,
                                    dh_measured=p[f"measured_increment_{side}"])[0]
                     for side in sides])


def _predicted_86h(fb_v: FourBar, s: dict, p: dict, k_mean, factor=None) -> list:
    """The 86-h wear [m] of each side from its calibrated k on fb_v (Sec. 4.4, 2-h steps)."""
    out = []
    cal_h = float(p["measurement_interval"]) / 3600.0
    factor = factor or wear_factor_of(fb_v, s)
    for side, k in zip(SIDES, k_mean):
        h = np.asarray(p[f"measured_wear_{side}"], float)
        out.append(wear.predict(h[-1], cal_h * h.size, float(p["prediction_end"]) / 3600.0,
                                float(s.get("interval_h", 2.0)), float(k), fb_v.period,
                                fb_v.R_bush, factor)[1][-1])
    return out


def contact_side(hist: dict) -> dict:
    """Where on the bushing the wear sits, in the lab frame: the contact point is at the
    bushing centre + R n (n = e / |e|, Eq. 5), so its direction is n.  The wear-weighted
    (F_N |v_T|, Archard's integrand) circular mean of n, and the share of the wear above
    the bushing centre (n_y > 0): "the upper part of the bushing" of Sec. 4.2."""
    w = np.asarray(hist["F_N"]) * np.abs(np.asarray(hist["v_T"]))
    nx, ny = np.asarray(hist["nx"]), np.asarray(hist["ny"])
    mean = math.degrees(math.atan2(float(np.sum(w * ny)), float(np.sum(w * nx))))
    return {"wear_direction_deg": mean, "upper_share": float(np.sum(w * (ny > 0)) / np.sum(w))}


def load_point_fit(run: dict) -> dict:
    """The load point F estimated from Tables 3-4 jointly (Sec. 4.3-4.4 read backwards).

    With Eq. (32) read as k = K/21, the printed K_p of both tables fix the wear factor G of
    the paper's own simulation; G depends on F (and the gravity plane), which the paper
    does not give.  For each gravity value in ``fit_gravity`` F runs over the directions
    ``fit_load_direction_deg`` at ``fit_load_distance`` from E's mid-stroke position; the
    misfit m = mean over both sides and the five intervals of ln(K_p ours / K_p paper) is
    interpolated linearly in direction between grid points and its zeros are the
    estimates.  Each zero carries the uncertainty of the tables (the scatter of the ten
    log-ratios, i.e. the rounding of the printed increments, standard error of the mean)
    turned into direction through the local slope dm/dtheta.  At every estimate: the
    contact arc, where the wear sits (contact_side), and the 86-h wear of both sides, also
    at the estimate +- its uncertainty -- the band on Fig. 15.  Contact loss is refused.
    """
    fb, ctx, E, d, dirs, gs = load_point_grid(run, "fit")
    s, p = ctx.s, ctx.p
    H = float(p["hardness_bushing"])
    K_paper = np.asarray(s["fit_K_paper"], float) / wear.hardness_number(H)   # m2/N, 2 x 5

    def mech(g, a):
        return load_point(fb, E, d, a, g)
    m = np.full((gs.size, dirs.size), np.nan)
    for i, g in enumerate(gs):
        for j, a in enumerate(dirs):
            try:
                m[i, j] = float(np.mean(np.log(_calibrated(mech(g, a), s, p) / K_paper)))
            except ContactLost:         # refused
                pass
    sols = []
    for i, g in enumerate(gs):
        for j in range(dirs.size):
            j2 = (j + 1) % dirs.size
            a0, a1 = dirs[j], dirs[j2] + (360.0 if j2 == 0 else 0.0)
            m0, m1 = m[i, j], m[i, j2]
            if not (np.isfinite(m0) and np.isfinite(m1)) or m0 * m1 > 0 or m0 == m1:
                continue
            a = a0 + (a1 - a0) * m0 / (m0 - m1)
            for _ in range(int(s.get("fit_secant_steps", 3))):   # refine the zero: secant
                ma = float(np.mean(np.log(_calibrated(mech(g, a), s, p) / K_paper)))
                if ma * m0 > 0:
                    a0, m0 = a, ma
                else:
                    a1, m1 = a, ma
                a = a0 + (a1 - a0) * m0 / (m0 - m1)
            fb_a = mech(g, a)
            factor_a = wear_factor_of(fb_a, s)
            K = _calibrated(fb_a, s, p, factor=factor_a)
            r = np.log(K / K_paper).ravel()
            se = float(np.std(r, ddof=1) / math.sqrt(r.size))
            slope = (m1 - m0) / (a1 - a0)                    # per degree
            sig = abs(se / slope)
            hist = continuous_contact_period(fb_a, s)
            f = wear.period_wear_factor(hist, fb_a, fb.period)
            band = []
            for da in (-sig, 0.0, sig):
                if da == 0.0:     # the estimate itself: calibrated above
                    band.append(_predicted_86h(fb_a, s, p, np.mean(K, axis=1), factor_a))
                    continue
                fb_b = mech(g, a + da)
                factor_b = wear_factor_of(fb_b, s)
                band.append(_predicted_86h(fb_b, s, p, np.mean(_calibrated(
                    fb_b, s, p, factor=factor_b), axis=1), factor_b))
            sols.append({"gravity": float(g), "direction": float(a % 360.0), "sigma_deg": sig,
                         "misfit": float(np.mean(r)),
                         "misfit_se": se, "F": fb_a.F, "arc_deg": math.degrees(f["arc"]),
                         "F_N_mean": f["F_N_mean"], "F_N_min": f["F_N_min"],
                         **contact_side(hist), "wear_86h": np.array(band)})    # 3 x 2 sides
    return {"fb": fb, "fit": {"misfit": m, "directions": dirs, "gravity": gs, "distance": d,
                              "solutions": sols}}


def constant_sensitivity(run: dict) -> dict:
    """The assumed constants the scan does not vary, each at both ends of its declared
    range (option ``sensitivity``: {parameter: [lo, hi]} in SI), one at a time at the
    assumed load point: the calibrated mean coefficient of side B1, the 86-h wear of B1,
    the contact arc (quasi-static joint), and the wear per period of the settled dynamic
    joint (Radau, ``rtol``) against the quasi-static one -- d_max and C_max enter only
    there (the quasi-static joint has no penetration rate, Eq. 14)."""
    base_fb, ctx = setup(run)
    s = ctx.s
    rows = [("(assumed)", math.nan)]
    for name, ends in s["sensitivity"].items():
        rows += [(name, float(v)) for v in ends]
    out = []
    for name, v in rows:
        p = dict(ctx.p) if name == "(assumed)" else {**ctx.p, name: v}
        fb, c2 = setup({**run, "parameters": p})
        K = _calibrated(fb, s, p, sides=("B1",))[0]
        h86 = _predicted_86h(fb, s, p, [float(np.mean(K))])[0]
        qs = wear.period_wear_factor(continuous_contact_period(fb, s), fb, fb.period)
        with stopwatch() as sw:
            dyn = finished_dynamic_period(fb, {**s, "n_out": int(s["n_steps"]), "periods": 1,
                                               "method": "Radau", "start": "equilibrium"})
        g_dyn = wear.period_wear_factor(dyn, fb, fb.period)["G"]
        out.append({"parameter": name, "value": v, "K_mean": float(np.mean(K)),
                    "wear_86h": h86, "arc_deg": math.degrees(qs["arc"]),
                    "qs_vs_dynamic": qs["G"] / g_dyn - 1.0, "dynamic_steps": dyn["steps"],
                    "dynamic_wall": sw.seconds})
    return {"fb": base_fb, "sens": out}


def local_wear(run: dict) -> dict:
    """Side B1 with local Archard wear (wear.local_predict: a depth per bushing angle, the
    profile fed back interval by interval) against the paper's uniform depth (Eq. 29) on the
    same joint and schedule; quasi-static joint.  Option ``local_load_point``:
    [distance m, direction deg, gravity m/s2] of F from E's mid-stroke position (default:
    the assumed F and g)."""
    fb, ctx = setup(run)
    s, p = ctx.s, ctx.p
    lp = s.get("local_load_point")
    if lp:
        d, a, g = (float(x) for x in lp)
        fb = load_point(fb, kinematics.load_point_mid_stroke(fb), d, a, g)
    cal_h = float(p["measurement_interval"]) / 3600.0
    t_end, step = float(p["prediction_end"]) / 3600.0, float(s["interval_h"])
    h = np.asarray(p["measured_wear_B1"], float)
    dh = np.asarray(p["measured_increment_B1"], float)
    with stopwatch() as sw_l:
        nodes, mean, peak, k_l, prof, theta = wear.local_predict(
            h, dh, cal_h, t_end, step, fb, fb.period,
            lambda fb_w: continuous_contact_period(fb_w, s), n_theta=int(s["n_theta"]))

    factor = wear_factor_of(fb, s)
    with stopwatch() as sw_u:
        _, k_u, _ = wear.calibrate(h, cal_h, fb.period, fb.R_bush, factor, dh_measured=dh)
        _, h_u, _ = wear.predict(h[-1], cal_h * h.size, t_end, step, k_u, fb.period, fb.R_bush,
                                 factor)
    f0 = wear.period_wear_factor(continuous_contact_period(fb, s), fb, fb.period)
    return {"fb": fb, "local": {"hours": nodes, "mean": mean, "peak": peak, "uniform": h_u,
                                "k_local": k_l, "k_uniform": k_u, "profile": prof,
                                "theta": theta, "wall_local": sw_l.seconds,
                                "wall_uniform": sw_u.seconds, "arc": f0["arc"],
                                "AB_mean": f0["AB_mean"]}}


SOLVERS = {"clearance_implicit": clearance_implicit, "clearance_explicit": clearance_explicit,
           "continuous_contact": continuous_contact, "period_by_period": period_by_period,
           "coefficient_scan": coefficient_scan, "load_point_fit": load_point_fit,
           "constant_sensitivity": constant_sensitivity, "local_wear": local_wear}


def _methods(runs) -> set:
    return {r.get("resolution", {}).get("method") for r in runs}


def warm(runs=None) -> None:
    """Load the compiled kernels ``runs`` use (all without them) once per solver process;
    the runner calls this before the first timed run, so that no run's time carries numba's
    start."""
    dynamics.warm(dynamics.COMPILED if runs is None else _methods(runs))


def compute(run: dict) -> dict:
    """The physics of one run (what the runner times): the scene's solver.  The compiled
    kernels it uses are loaded first (once per process; the runner has, see warm), so that
    no measured period carries numba's start."""
    dynamics.warm(_methods([run]))
    return SOLVERS[run["solver"]](run)


variables = dataset.variables

