"""The solvers of joint_wear (``SOLVERS``; each described under ``solvers:`` in
``config/papers/joint_wear.yaml``): a scene's solver decides the joint model and method,
its effects (effects.py) the terms.  Each is called as ``solver(run, ctx)`` with the run's
:class:`~.effects.Context` (:func:`context`: the mechanism with the terms of the first of the
three stages of effects, mechanism terms, wear set-up, wear), evaluates the later stages and
reads their contributions by key.
"""
from __future__ import annotations

import functools
import math
import operator
from dataclasses import fields, replace

import numpy as np
from scipy import optimize, stats

from mechrepro.errors import Refusal
from mechrepro.timing import EFFECT, phase

from . import dataset, dynamics, groove, kinematics, quasistatic, wear
from .effects import EFFECTS, Context
from .geometry import FourBar, from_parameters

#: the contributions each stage reads (the effects that contribute them are evaluated there)
MECHANISM = ("gravity", "friction_coefficient", "damping_ceiling")
WEAR_SETUP = ("sides", "worn_bushing")
WEAR = ("wear",)
NO_FACTOR = dict.fromkeys(("S", "F_N_mean", "arc", "arc_q90", "L_arc", "L_wear", "G",
                           "min_penetration", "F_N_min"), math.nan)


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


#: what a quasi-static period reads of a mechanism: all but the damping of Eq. (14)
_QS_KEY = operator.attrgetter(*(f.name for f in fields(FourBar) if f.name not in ("C_max", "d_max")))


def kept_periods(s: dict, size: int = 512):
    """quasi_static_period for one run's ``s``, keeping its last ``size`` periods: the fit's
    brackets and zeros and the calibration revisit load points and bushing radii, and a
    mechanism met again (by the values a quasi-static period reads, _QS_KEY) is not solved
    again.  Its ``many(fbs, s)`` solves the bushings of one mechanism not kept yet together
    (quasistatic.periods).  Made per run, so that no run's time depends on what ran before
    it in the process; the kept arrays are read-only (shared)."""
    kept: dict = {}

    def many(fbs, _s: dict) -> list:
        keys = [_QS_KEY(fb) for fb in fbs]
        new = {k: fb for k, fb in zip(keys, fbs) if k not in kept}
        for k, hist in zip(new, quasistatic.periods(list(new.values()), int(s["n_steps"]))
                           if new else ()):
            for v in hist.values():
                v.flags.writeable = False
            kept[k] = hist
        out = []
        for k in keys:
            kept[k] = kept.pop(k)           # the most recently used last
            out.append(dict(kept[k]))
        while len(kept) > size:
            del kept[next(iter(kept))]
        return out

    def joint(fb: FourBar, s_: dict) -> dict:
        return many([fb], s_)[0]
    joint.many = many
    return joint


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
    """A dynamic period that must finish (wear and a contact margin need a whole period)."""
    hist = dynamic_period(fb, s)
    if not hist["completed"]:
        raise RuntimeError(f"joint_wear: {hist['message']}: no whole period")
    return hist


#: the project's contact rule: a joint force below this share of its peak is taken as vanishing
CONTACT_LOSS_FRACTION = 1e-2


def continuous_contact_period(fb: FourBar, s: dict) -> dict:
    """A quasi-static period for the wear model, refused (ContactLost) where its joint force
    falls below CONTACT_LOSS_FRACTION of its peak: the continuous-contact model (Sec. 3.2)
    cannot represent a vanishing force -- the pin flies across the clearance there."""
    return refuse_contact_loss(quasi_static_period(fb, s))


def margin(hist: dict) -> float:
    """The contact margin min F_N / max F_N of a period."""
    return float(np.min(hist["F_N"]) / np.max(hist["F_N"]))


def refuse_contact_loss(hist: dict) -> dict:
    """``hist`` if its joint force keeps above CONTACT_LOSS_FRACTION of its peak."""
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
    with phase("joint_wear.one_period") as sw:
        hist = joint(fb, s)
    out = {"fb": fb, "hist": hist, "period_wall": sw.seconds}
    if hist.get("completed", True):
        out["factor"] = wear.period_wear_factor(hist, fb, fb.period,
                                                s.get("wear_range", "contact_point"))
    else:   # the time the unfinished integrator would need per period (a timing only)
        out["period_wall"] = hist["integration_wall"] * fb.period / max(hist["t_reached"], 1e-12)
        out["factor"] = dict(NO_FACTOR)
    return out


def period_factor(fb_v: FourBar, s: dict, joint):
    """G(R_bush): the wear factor (Eq. 29) of one period of ``joint`` with the bushing of
    ``fb_v`` at radius R_bush -- what calibration and prediction step through."""
    def factor(R_bush):
        fb_w = fb_v.with_bushing_radius(R_bush)
        return _factor_G(joint(fb_w, s), fb_w, fb_v, s)
    return factor


def _factor_G(hist: dict, fb_w: FourBar, fb_v: FourBar, s: dict) -> float:
    """G (Eq. 29) of the period ``hist`` of fb_v's mechanism with the bushing of ``fb_w``."""
    return wear.period_wear_factor(hist, fb_w, fb_v.period, s.get("wear_range", "contact_point"),
                                   statistics=False)["G"]


def wear_factor_of(fb_v: FourBar, s: dict, joint=None):
    """period_factor of ``joint`` (default continuous_contact_period, which refuses contact
    loss; quasi_static_period where a margin is measured, not assumed), a radius met again
    not solved again; ``factor.many(radii)`` gives several (a calibration's), solved
    together where the joint can (``joint.many``: kept_periods)."""
    joint = joint or continuous_contact_period
    G: dict = {}

    def many(radii):
        new = [fb_v.with_bushing_radius(R) for R in dict.fromkeys(radii) if R not in G]
        hists = joint.many(new, s) if hasattr(joint, "many") else (joint(f, s) for f in new)
        for fb_w, hist in zip(new, hists):
            G[fb_w.R_bush] = _factor_G(hist, fb_w, fb_v, s)
        return [G[R] for R in radii]

    def factor(R_bush):
        return many([R_bush])[0]
    factor.many = many
    return factor


def with_wear(run: dict, fb: FourBar, ctx: Context, res: dict, joint) -> dict:
    """Stages two and three: the wear set-up, then the wear effect's law applied to each
    side with the wear factor of ``joint`` (or the closed form of option
    ``closed_form_growth``, a rival), timed as that effect's contribution."""
    g = ctx.s.get("closed_form_growth")
    factor = (period_factor(fb, ctx.s, joint) if g is None
              else wear.closed_form_factor(fb.R_bush, float(g)))
    c = EFFECTS.evaluate(run, ctx, keys=WEAR_SETUP)
    sides, worn = c.get("sides", ["B1"]), c.get("worn_bushing")
    c = EFFECTS.evaluate(run, ctx, keys=WEAR)
    if "wear" not in c:
        return res
    with phase(EFFECT + c.sources("wear")[0]) as sw:
        rows = [c.get("wear")(side, fb.period, fb.R_bush, factor, worn) for side in sides]
    w = {k: [r[k] for r in rows] for k in rows[0]}
    w["wall_time_prediction"] = sw.seconds
    if ctx.s.get("interval_limit") and worn is not None:     # not timed: a reference
        w["limit"] = [wear.interval_limit(h[0], n[0], n[-1], km, fb.period, fb.R_bush, factor,
                                          worn) for h, n, km in zip(w["h"], w["nodes"], w["k_mean"])]
    w["cal_hours"] = wear.calibration_hours(ctx.p) * (1 + np.arange(len(w["k"][0])))
    res["wear"] = w
    return res


# --- the solvers -----------------------------------------------------------------------------
def clearance_implicit(run: dict, ctx: Context) -> dict:
    return with_wear(run, ctx.fb, ctx, one_period(ctx.fb, ctx.s, dynamic_period),
                     finished_dynamic_period)


def clearance_explicit(run: dict, ctx: Context) -> dict:
    return one_period(ctx.fb, ctx.s, dynamic_period)


def continuous_contact(run: dict, ctx: Context) -> dict:
    return with_wear(run, ctx.fb, ctx, one_period(ctx.fb, ctx.s, quasi_static_period),
                     continuous_contact_period)


def period_by_period(run: dict, ctx: Context) -> dict:
    """Fig. 6: a sample of consecutive periods, each simulated and its wear added before
    the next (the bushing grows every period); only its time is a result."""
    fb = ctx.fb
    res = one_period(fb, ctx.s, quasi_static_period)
    n = int(ctx.s["period_by_period_sample"])
    g_of = period_factor(fb, ctx.s, quasi_static_period)
    with phase("joint_wear.period_by_period") as sw:     # any k: only the time is measured
        wear.period_by_period(float(ctx.p["measured_wear_B1"][-1]), n, 1e-13, fb.R_bush, g_of)
    res["pbp"] = (n, sw.seconds)
    return res


SIDES = ("B1", "B2")


def load_point(fb: FourBar, E, distance: float, direction_deg: float, g: float) -> FourBar:
    """The mechanism with F at ``distance`` [m] from E's mid-stroke position ``E`` in the
    direction ``direction_deg`` (from +x, anticlockwise) and gravity ``g`` [m/s2]."""
    a = math.radians(direction_deg)
    return replace(fb, g=g, F=(E[0] + distance * math.cos(a), E[1] + distance * math.sin(a)))


def gravity_planes(run: dict, planes) -> np.ndarray:
    """The gravity values [m/s2] a solver that weighs the plane of motion runs over: the
    scene's, or g = 0 alone where the scene does not name the gravity effect (no link
    weights)."""
    return np.asarray(planes if "gravity" in run["effects"] else [0.0], float)


def coefficient_scan(run: dict, ctx: Context) -> dict:
    """The mean calibrated coefficient of both sides over load points F and gravity planes.

    F is placed at ``scan_load_distance`` [m] from E's mid-stroke position in each of the
    directions ``scan_load_direction_deg`` (from +x, anticlockwise); the gravity values
    ``scan_gravity`` [m/s2] stand for planes of motion from horizontal (0) to vertical.
    Only the calibration is run (5 periods per point): it is what fixes the coefficient.
    """
    fb = ctx.fb
    s, p = ctx.s, ctx.p
    E, d = kinematics.load_point_mid_stroke(fb), float(s["scan_load_distance"])
    dirs = np.asarray(s["scan_load_direction_deg"], float)
    gs = gravity_planes(run, s["scan_gravity"])
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
    factor = factor or wear_factor_of(fb_v, s)
    return np.array([wear.calibrate_side(p, side, fb_v.period, fb_v.R_bush, factor)[0]
                     for side in sides])


def _predicted_86h(fb_v: FourBar, s: dict, p: dict, k_mean, factor=None) -> list:
    """The 86-h wear [m] of each side from its calibrated k on fb_v (Sec. 4.4, 2-h steps)."""
    factor = factor or wear_factor_of(fb_v, s)
    return [wear.predict_side(p, side, float(s.get("interval_h", 2.0)), float(k), fb_v.period,
                              fb_v.R_bush, factor)[1][-1] for side, k in zip(SIDES, k_mean)]


def contact_side(hist: dict) -> dict:
    """Where on the bushing the wear sits, in the lab frame: the contact point is at the
    bushing centre + R n (n = e / |e|, Eq. 5), so its direction is n.  The wear-weighted
    (F_N |v_T|, Archard's integrand) circular mean of n, and the share of the wear above
    the bushing centre (n_y > 0): "the upper part of the bushing" of Sec. 4.2."""
    w = np.asarray(hist["F_N"]) * np.abs(np.asarray(hist["v_T"]))
    nx, ny = np.asarray(hist["nx"]), np.asarray(hist["ny"])
    mean = math.degrees(math.atan2(float(np.sum(w * ny)), float(np.sum(w * nx))))
    return {"wear_direction_deg": mean, "upper_share": float(np.sum(w * (ny > 0)) / np.sum(w))}


#: the largest |misfit| a fitted load point may keep: a tenth of the tables' own scatter
#: (the standard error of the ten log-ratios, ~0.01); the config's calibration row
#: fitted_load_point_misfit states the same tolerance.  A sign change the secant steps do
#: not bring below it is a jump of the misfit, not a zero.
FIT_TOLERANCE = 1e-3


def tables_misfit(fb_v: FourBar, s: dict, p: dict, K_paper, factor=None) -> float:
    """m = mean over both sides and the five intervals of ln(K_p ours / K_p paper): zero
    where the load point of ``fb_v`` reproduces Tables 3-4 (Eq. 32 read as k = K/21)."""
    return float(np.mean(np.log(_calibrated(fb_v, s, p, factor=factor) / K_paper)))


def fit_zeros(fb: FourBar, s: dict, p: dict, E, d: float, dirs, g: float, K_paper,
              joint=None, xtol: float = 1e-9) -> tuple[np.ndarray, list]:
    """The load points F at distance ``d`` from ``E`` (gravity ``g``) whose calibration
    reproduces Tables 3-4, the zeros over F's direction of the misfit (tables_misfit).

    The grid ``dirs`` places the sign changes with the new bushing's wear factor G(R0)
    taken for every interval (one period per direction instead of nine; within 0.01 of the
    misfit, G changing by < 1 % over 10 h); each is bracketed by the misfit itself (widened
    by a grid step where needed) and refined by ``fit_secant_steps`` secant steps, by
    Brent's method where they stall, to FIT_TOLERANCE.  ``joint``: the period model of the
    calibration (default continuous_contact_period: NaN misfit where contact is lost).
    Returns (the grid's misfit, one dict per zero: direction [deg], the misfit's slope over
    the last bracket [1/deg], the mechanism there, its wear factor function and K_p)."""
    def mech(a):
        return load_point(fb, E, d, a, g)

    @functools.cache
    def misfit(a, new_bushing=False):
        """The misfit at direction a [deg] (NaN where contact loss is refused); with
        ``new_bushing`` every interval at the new bushing's wear factor (the grid's)."""
        fb_v = mech(a)
        try:
            factor = wear_factor_of(fb_v, s, joint)
            if new_bushing:
                G0 = factor(fb_v.R_bush)
                factor = lambda R: G0      # noqa: E731
            return tables_misfit(fb_v, s, p, K_paper, factor)
        except ContactLost:
            return math.nan
    m = np.array([misfit(a, True) for a in dirs])
    n = dirs.size
    at = lambda j: float(dirs[j % n]) + 360.0 * (j // n)          # noqa: E731  unwrapped
    zeros = []
    for j in range(n):
        if not (np.isfinite(m[j]) and np.isfinite(m[(j + 1) % n])) or m[j] * m[(j + 1) % n] > 0 \
                or m[j] == m[(j + 1) % n]:
            continue
        for lo, hi in ((j, j + 1), (j - 1, j + 1), (j, j + 2)):
            a0, a1 = at(lo), at(hi)
            m0, m1 = misfit(a0 % 360.0), misfit(a1 % 360.0)
            if np.isfinite(m0) and np.isfinite(m1) and m0 * m1 <= 0 and m0 != m1:
                break
        else:
            continue
        a = a0 + (a1 - a0) * m0 / (m0 - m1)
        for _ in range(int(s.get("fit_secant_steps", 3))):   # refine the zero: secant
            ma = misfit(a % 360.0)
            if not np.isfinite(ma):
                break        # contact refused inside the bracket: no zero to refine there
            if ma * m0 > 0:
                a0, m0 = a, ma
            else:
                a1, m1 = a, ma
            a = a0 + (a1 - a0) * m0 / (m0 - m1)
        if np.isfinite(misfit(a % 360.0)) and not abs(misfit(a % 360.0)) <= FIT_TOLERANCE:
            # a steep zero (where the smallest joint force nears zero the contact arc, and
            # with it the misfit, changes by decades within a degree) that the secant steps
            # have not reached: Brent's method on the bracket they leave
            try:
                a = float(optimize.brentq(lambda x: misfit(x % 360.0), a0, a1, xtol=xtol,
                                          rtol=4 * np.finfo(float).eps, maxiter=200))
            except (ValueError, RuntimeError):
                continue     # no sign change left (a refused point inside): no zero
        if not abs(misfit(a % 360.0)) <= FIT_TOLERANCE:
            continue     # a jump of the misfit, no zero
        if any(abs(math.remainder(a - z["direction"], 360.0)) < 1e-6 for z in zeros):
            continue     # found from a neighbouring sign change already
        fb_a = mech(a % 360.0)
        factor_a = wear_factor_of(fb_a, s, joint)
        zeros.append({"direction": float(a % 360.0), "slope": (m1 - m0) / (a1 - a0),
                      "fb": fb_a, "factor": factor_a,
                      "K": _calibrated(fb_a, s, p, factor=factor_a)})
    return m, zeros


def _K_paper(s: dict, p: dict) -> np.ndarray:
    """Tables 3-4 as printed (option fit_K_paper, 1/Pa) as k = K/21 [m2/N], 2 x 5."""
    return np.asarray(s["fit_K_paper"], float) / wear.hardness_number(float(p["hardness_bushing"]))


def load_point_fit(run: dict, ctx: Context) -> dict:
    """The load point F estimated from Tables 3-4 jointly (Sec. 4.3-4.4 read backwards).

    With Eq. (32) read as k = K/21 the printed K_p fix the wear factor G of the paper's own
    simulation, and G depends on F (and the gravity plane), which the paper does not give.
    Per gravity value of ``fit_gravity``, the estimates are the zeros of the misfit over
    F's direction at ``load_point_distance`` from E's mid-stroke position (fit_zeros), each
    with the tables' uncertainty (standard error of the ten log-ratios) turned into
    direction through the local slope.  At every estimate: the contact arc, where the wear
    sits (contact_side) and the 86-h wear of both sides, also at +- its uncertainty (the
    band on Fig. 15).  Contact loss is refused.
    """
    fb = ctx.fb
    s, p = ctx.s, ctx.p
    E, d = kinematics.load_point_mid_stroke(fb), float(p["load_point_distance"])
    dirs = np.asarray(s["fit_load_direction_deg"], float)
    gs = gravity_planes(run, s["fit_gravity"])
    K_paper = _K_paper(s, p)
    m = np.full((gs.size, dirs.size), np.nan)
    sols = []
    for i, g in enumerate(gs):
        m[i], zeros = fit_zeros(fb, s, p, E, d, dirs, g, K_paper)
        for z in zeros:
            a, fb_a, factor_a, K = z["direction"], z["fb"], z["factor"], z["K"]
            r = np.log(K / K_paper).ravel()
            se = float(np.std(r, ddof=1) / math.sqrt(r.size))
            sig = abs(se / z["slope"])
            hist = continuous_contact_period(fb_a, s)
            f = wear.period_wear_factor(hist, fb_a, fb.period)
            band = []
            for da in (-sig, 0.0, sig):     # the estimate itself (da = 0): calibrated above
                fb_b = fb_a if da == 0.0 else load_point(fb, E, d, a + da, g)
                factor_b = factor_a if da == 0.0 else wear_factor_of(fb_b, s)
                K_b = K if da == 0.0 else _calibrated(fb_b, s, p, factor=factor_b)
                band.append(_predicted_86h(fb_b, s, p, np.mean(K_b, axis=1), factor_b))
            sols.append({"gravity": float(g), "direction": float(a % 360.0), "sigma_deg": sig,
                         "arc_deg": math.degrees(f["arc"]), **contact_side(hist),
                         "wear_86h": np.array(band)})    # 3 x 2 sides
    return {"fb": fb, "fit": {"misfit": m, "directions": dirs, "gravity": gs, "distance": d,
                              "solutions": sols}}


def contact_margins(fb_a: FourBar, s: dict) -> dict:
    """The contact margin min F_N / max F_N at the load point of ``fb_a``: of the
    quasi-static period, and where that keeps CONTACT_LOSS_FRACTION, of the dynamic
    clearance joint (the last of ``periods`` periods from the settled start; 0 where the
    pin leaves the bushing).  Below the fraction the quasi-static margin stands: the rule
    already calls that contact lost, whatever the dynamics adds."""
    row = {"qs_margin": margin(quasi_static_period(fb_a, s)), "dyn_margin": math.nan}
    if row["qs_margin"] >= CONTACT_LOSS_FRACTION:
        hist = finished_dynamic_period(fb_a, s)
        Fd = np.where(np.asarray(hist["delta"]) > 0.0, np.asarray(hist["F_N"]), 0.0)
        row["dyn_margin"] = float(Fd.min() / Fd.max())
    row["margin"] = float(np.nanmin([row["qs_margin"], row["dyn_margin"]]))
    return row


def printed_step(x: float) -> float:
    """The unit of the last digit a number is printed with (0.0229 -> 1e-4, 0.01956 -> 1e-5)."""
    for k in range(13):
        if abs(round(x, k) - x) <= 1e-9 * abs(x):
            return 10.0 ** -k
    return 10.0 ** -12


def rounding_sigma(dh_printed_mm) -> np.ndarray:
    """Relative standard deviation of a printed increment from its rounding: the true value
    is uniform within half a unit of the last printed digit either side, sd = step / sqrt(12),
    relative to the value.  It is the noise of ln(K_p ours / K_p paper): our K_p divides the
    printed increment, the paper's the one it measured (its K_p are printed to five digits,
    a rounding of 1e-5, negligible beside it)."""
    x = np.asarray(dh_printed_mm, float)
    return np.array([printed_step(v) for v in x.ravel()]).reshape(x.shape) / math.sqrt(12.0) / x


def laplace_log_weight(r, sigma, slope: float) -> tuple[float, float, float, float]:
    """The likelihood of the log-ratios r (Gaussian, sd ``sigma``) integrated over F's
    direction about a zero of their mean, where each moves by ``slope`` per degree:
    the integral of exp(-chi2(delta) / 2) over delta by the exact Gaussian integral of
    the linearised ratios (Laplace).  Returns (chi2 at the best direction, the direction's
    sd [deg], log of the integral [log deg] -- the posterior mass of the zero under a
    prior uniform in direction, up to a constant --, the best direction's offset from the
    zero [deg])."""
    r, w = np.ravel(r), 1.0 / np.ravel(sigma) ** 2
    A, B = float(np.sum(w)), float(np.sum(r * w))
    chi2 = float(np.sum(r * r * w)) - B * B / A
    width = 1.0 / (abs(slope) * math.sqrt(A))
    return chi2, width, -0.5 * chi2 + math.log(math.sqrt(2.0 * math.pi) * width), -B / (A * slope)


def likelihood_region(chi2, level: float, dof: int = 4) -> np.ndarray:
    """The points whose likelihood is within the ``level`` quantile of the chi2
    distribution with ``dof`` degrees of freedom of the best (a likelihood-ratio region:
    decided point by point, so a finer grid adds points to it but never moves one out,
    unlike a share of the mass, which a grid that misses a narrow ridge gets wrong); NaN
    chi2 are points the conditioning excluded."""
    c = np.asarray(chi2, float)
    if not np.isfinite(c).any():
        return np.zeros(c.shape, bool)
    return np.isfinite(c) & (c <= np.nanmin(c) + stats.chi2.ppf(level, dof))


def gravity_nodes(lo: float, hi: float, n: int) -> tuple[np.ndarray, np.ndarray]:
    """n cells of [lo, hi], edges at lo + (hi - lo) (i / n)^3 (denser towards lo, where the
    joint nears contact loss and the likelihood changes by decades within 0.1 m/s2): their
    midpoints and their shares of the range (the prior mass of each node, uniform in g)."""
    e = lo + (hi - lo) * (np.arange(n + 1) / n) ** 3
    return 0.5 * (e[1:] + e[:-1]), np.diff(e) / (hi - lo)


def _branch_point(fb: FourBar, s: dict, p: dict, E, d: float, a0: float, g: float, K_paper, sigma,
                  joint=quasi_static_period):
    """The zero of the misfit within 3 deg of direction ``a0`` at gravity ``g`` (one
    branch of the load points the tables allow), with its chi2 and quasi-static period
    (``joint``: quasi_static_period or the run's kept_periods); None where the branch has
    no zero there (contact refused or the branch ended)."""
    # xtol 1e-5 deg: the misfit moves by < 1e-4 of FIT_TOLERANCE there, and chi2, taken
    # about the ratios' common level, not at all
    _, zeros = fit_zeros(fb, s, p, E, d, np.array([a0 - 3.0, a0 + 3.0]), g, K_paper,
                         joint=joint, xtol=1e-5)
    zeros = [z for z in zeros if abs(math.remainder(z["direction"] - a0, 360.0)) <= 3.0]
    if not zeros:
        return None
    z = min(zeros, key=lambda z: abs(math.remainder(z["direction"] - a0, 360.0)))
    chi2 = laplace_log_weight(np.log(z["K"] / K_paper), sigma, z["slope"])[0]
    return {"gravity": g, "direction": z["direction"] % 360.0, "chi2": chi2,
            "qs": joint(z["fb"], s), "fb": z["fb"]}


def _inside(r, threshold: float) -> bool:
    """A branch point inside the likelihood region, with the wear on the upper part."""
    return r is not None and r["chi2"] <= threshold and contact_side(r["qs"])["upper_share"] > 0.5


def region_edge(fb: FourBar, s: dict, p: dict, E, d: float, branch: list, K_paper, sigma,
                threshold: float, bisections: int, bound: float, joint=quasi_static_period):
    """The lowest gravity on one branch of load points (``branch``: its points at the prior
    nodes, ascending g, each with its chi2 and margin) inside the likelihood region (chi2
    within ``threshold``, wear on the upper part), the branch's direction interpolated
    between its nodes.  The margin grows with g along a branch (the link weights carry it),
    so the credible set's smallest margin sits at such an edge, which the nodes alone place
    only to within their spacing (a narrow ridge of good fit can lie between two nodes).
    So, from the lowest node up, in every interval whose lower end's margin is below
    ``bound`` (the smallest credible margin so far) and whose better end is within 10x the
    threshold (chi2 is smooth in g), chi2's minimum is sought by ``bisections``
    golden-section steps; the first interval with a point inside (or a credible node) gives
    the edge, bisected ``bisections`` times below that point (``joint``: _branch_point's).
    Returns it, or None."""
    gb = np.array([q["gravity"] for q in branch])
    ab = np.unwrap(np.radians([q["direction"] for q in branch]))

    def at(g):
        return _branch_point(fb, s, p, E, d, math.degrees(float(np.interp(g, gb, ab))), g, K_paper,
                             sigma, joint)
    phi = 0.5 * (math.sqrt(5.0) - 1.0)
    for i, q in enumerate(branch):
        lo = float(gb[i - 1]) if i else float(s["posterior_gravity_range"][0])
        if q["credible"]:
            hi, best = float(gb[i]), None
        else:
            if not (i and branch[i - 1]["qs_margin"] < bound
                    and min(branch[i - 1]["chi2"], q["chi2"]) <= 10.0 * threshold):
                continue
            x1, x2 = gb[i] - phi * (gb[i] - lo), lo + phi * (gb[i] - lo)
            r1, r2 = at(x1), at(x2)
            a_, b_ = lo, float(gb[i])
            for _ in range(bisections):
                c1 = r1["chi2"] if r1 else math.inf
                c2 = r2["chi2"] if r2 else math.inf
                if c1 <= c2:
                    b_, x2, r2 = x2, x1, r1
                    x1 = b_ - phi * (b_ - a_)
                    r1 = at(x1)
                else:
                    a_, x1, r1 = x1, x2, r2
                    x2 = a_ + phi * (b_ - a_)
                    r2 = at(x2)
            inside = [r for r in (r1, r2) if _inside(r, threshold)]
            if not inside:
                continue
            best = min(inside, key=lambda r: r["gravity"])
            hi = best["gravity"]
        for _ in range(bisections):
            mid = 0.5 * (lo + hi)
            r = at(mid)
            if _inside(r, threshold):
                hi, best = mid, r
            else:
                lo = mid
        return best
    return None


def load_point_posterior(run: dict, ctx: Context) -> dict:
    """The load point F as a distribution the tables allow (Secs. 3.2, 4.2-4.3).

    Unknowns: F's direction and distance from E's mid-stroke position, the gravity
    component in the plane of motion and mu.  Prior: uniform over the nodes
    ``posterior_distance``, ``posterior_friction``, the ``n_gravity`` cells of
    ``posterior_gravity_range`` (gravity_nodes) and in direction.  Likelihood: the ten K_p
    of Tables 3-4 with the rounding of the printed increments as their noise
    (rounding_sigma), and the wear on the upper part of the bushing (Sec. 4.2 (2)) as an
    indicator.  The direction is integrated exactly about every zero of the mean misfit
    (fit_zeros, laplace_log_weight): the tables fix it too sharply for a grid.  At every
    point: contact margin, contact arc, wear coefficients, wear factor and posterior mass.
    The credible set is the likelihood region at ``posterior_credible`` (likelihood_region:
    prior-free, so the contested prior of g does not enter it); there the 86-h wear of both
    sides, and the dynamic margin (contact_margins) at its point of the smallest
    quasi-static margin, the result: the contact statement holds only with margin
    everywhere in the credible set."""
    fb = ctx.fb
    s, p = ctx.s, ctx.p
    E = kinematics.load_point_mid_stroke(fb)
    dirs = np.asarray(s["fit_load_direction_deg"], float)
    K_paper = _K_paper(s, p)
    ds_, mus = (np.asarray(s[f"posterior_{k}"], float) for k in ("distance", "friction"))
    gs, g_prior = gravity_nodes(*(float(x) for x in s["posterior_gravity_range"]), int(s["n_gravity"]))
    if "gravity" not in run["effects"]:
        gs, g_prior = np.zeros(1), np.ones(1)
    dh = np.array([p[f"measured_increment_{side}"] for side in SIDES])
    sigma = rounding_sigma(dh * 1e3)
    qs_of = kept_periods(s)
    pts = []
    for d in ds_:
        for j, g in enumerate(gs):
            for mu in mus:
                fb_n = replace(fb, mu=float(mu))
                _, zeros = fit_zeros(fb_n, s, p, E, float(d), dirs, float(g), K_paper,
                                     joint=qs_of)
                for z in zeros:
                    r = np.log(z["K"] / K_paper)
                    chi2, width, logw, shift = laplace_log_weight(r, sigma, z["slope"])
                    qs = qs_of(z["fb"], s)
                    f = wear.period_wear_factor(qs, z["fb"], fb.period)
                    pts.append({"distance": float(d), "gravity": float(g), "friction": float(mu),
                                "direction": (z["direction"] + shift) % 360.0, "misfit": float(np.mean(r)),
                                "chi2": chi2, "width": width, "log_lik": logw,
                                "log_prior": math.log(g_prior[j]),
                                "qs_margin": margin(qs),
                                "arc_deg": math.degrees(f["arc"]), "G": f["G"],
                                "arc_ends_deg": np.degrees(wear.contact_arc_bounds(qs["psi"]) or (math.nan, math.nan)),
                                "K_b1": float(np.mean(z["K"][0])), "K_b2": float(np.mean(z["K"][1])),
                                **contact_side(qs), "fb": z["fb"], "factor": z["factor"]})
    upper = np.array([q["upper_share"] > 0.5 for q in pts], bool)
    log_post = np.array([q["log_lik"] + q["log_prior"] for q in pts], float)
    log_post[~upper] = np.nan
    chi2 = np.array([q["chi2"] if u else math.nan for q, u in zip(pts, upper)], float)
    # the other reading of Sec. 4.3, every interval calibrated on the new bushing: the
    # wear factor is then one number per load point, the ten log-ratios differ only by the
    # printed increments over the paper's K_p, and their chi2 about a common level is the
    # same at every load point that fits the level -- no fit needed to weigh it
    chi2_new = laplace_log_weight(np.log(dh / K_paper), sigma, 1.0)[0]
    inside = likelihood_region(np.r_[chi2, chi2_new], float(s["posterior_credible"]))
    new_inside, inside = bool(inside[-1]), inside[:-1]
    if new_inside:      # the new-bushing reading is credible: so is every load point it fits
        inside = upper.copy()
    for q, c in zip(pts, inside):
        q["credible"] = bool(c)
        q["wear_86h"] = (_predicted_86h(q["fb"], s, p, [q["K_b1"], q["K_b2"]], q["factor"])
                         if c else [math.nan, math.nan])
    # the credible set's lower edge in g on every branch through a credible node
    # (region_edge), where its margin is smallest
    threshold = (np.nanmin(chi2) if np.isfinite(chi2).any() else math.nan) \
        + stats.chi2.ppf(float(s["posterior_credible"]), 4)
    branches = []
    for q in pts:
        if q["upper_share"] > 0.5 and not any(q in br for br in branches):
            branches.append(sorted((r for r in pts if r["distance"] == q["distance"]
                                    and r["friction"] == q["friction"] and r["upper_share"] > 0.5
                                    and abs(math.remainder(r["direction"] - q["direction"], 360.0)) < 15.0),
                                   key=lambda r: r["gravity"]))
    # branches through a credible node first: their edges set the bound below which a ridge
    # between nodes could lower the smallest credible margin
    branches.sort(key=lambda br: not any(r["credible"] for r in br))
    edges = []
    for br in [] if new_inside else branches:
        bound = min([q["qs_margin"] for q in pts if q["credible"]] + [e["qs_margin"] for e in edges],
                    default=math.inf)
        e = region_edge(replace(fb, mu=br[0]["friction"]), s, p, E, br[0]["distance"], br, K_paper,
                        sigma, threshold, int(s["edge_bisections"]), bound, qs_of)
        if e is not None:
            edges.append({"distance": br[0]["distance"], "friction": br[0]["friction"],
                          "gravity": e["gravity"], "direction": e["direction"], "chi2": e["chi2"],
                          "qs_margin": margin(e["qs"]), "fb": e["fb"]})
    worst = min([q for q in pts if q["credible"]] + edges, key=lambda q: q["qs_margin"], default=None)
    dyn = contact_margins(worst["fb"], s) if worst else {}
    for q in pts:
        del q["fb"], q["factor"]
    w = np.zeros(len(pts))
    if upper.any():
        lp = log_post[upper]
        w[upper] = np.exp(lp - lp.max()) / np.sum(np.exp(lp - lp.max()))
    return {"fb": fb, "posterior": {"gravity": gs, "points": pts,
                                    "weight": w, "worst": worst and {k: worst[k] for k in (
                                        "distance", "gravity", "friction", "direction", "qs_margin")},
                                    "worst_margins": dyn, "margin": dyn.get("margin", math.nan),
                                    "chi2_new_bushing": chi2_new, "new_bushing_credible": new_inside,
                                    "level": float(s["posterior_credible"])}}


def constant_sensitivity(run: dict, ctx: Context) -> dict:
    """The assumed constants the scan does not vary, each at both ends of its declared
    range (option ``sensitivity``: {parameter: [lo, hi]} in SI), one at a time at the
    assumed load point: B1's mean coefficient and 86-h wear, the contact arc, and the
    settled dynamic period's wear (Radau, ``rtol``) against the quasi-static one -- d_max
    and C_max enter only there (no penetration rate in the quasi-static joint, Eq. 14)."""
    base_fb = ctx.fb
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
        dyn = finished_dynamic_period(fb, {**s, "n_out": int(s["n_steps"]), "periods": 1,
                                           "method": "Radau", "start": "equilibrium"})
        g_dyn = wear.period_wear_factor(dyn, fb, fb.period)["G"]
        out.append({"parameter": name, "value": v, "K_mean": float(np.mean(K)),
                    "wear_86h": h86, "arc_deg": math.degrees(qs["arc"]),
                    "qs_vs_dynamic": qs["G"] / g_dyn - 1.0, "dynamic_steps": dyn["steps"]})
    return {"fb": base_fb, "sens": out}


def local_wear(run: dict, ctx: Context) -> dict:
    """Side B1 with local Archard wear, a depth per bushing angle that enters the contact
    gap (groove.py), against the paper's uniform depth (Eq. 29) on the same quasi-static
    joint and schedule, and beside it the mean-circle feedback (wear.mean_circle_increment)
    at the same points.  Options: ``local_load_point`` [distance m, direction deg] of F from
    E's mid-stroke position (default: the assumed F); ``local_placements`` [[shift, scale],
    ...] of the Eq.-33 points (wear.wear_range_points), the first the baseline."""
    fb = ctx.fb
    s, p = ctx.s, ctx.p
    lp = s.get("local_load_point")
    if lp:
        d, a = (float(x) for x in lp)
        fb = load_point(fb, kinematics.load_point_mid_stroke(fb), d, a, fb.g)
    cal_h = wear.calibration_hours(p)
    t_end, step = float(p["prediction_end"]) / 3600.0, float(s["interval_h"])
    dh = np.asarray(p["measured_increment_B1"], float)
    theta = np.linspace(-math.pi, math.pi, int(s["n_theta"]), endpoint=False)
    h0 = continuous_contact_period(fb, s)
    f0 = wear.period_wear_factor(h0, fb, fb.period)

    def groove_period(prof):
        d0 = float(prof.min())           # the unworn part: the circle the groove is cut in
        fb_w = fb.with_bushing_radius(fb.R_bush + d0)
        hist = groove.period(fb_w, int(s["n_steps"]), theta, prof - d0)
        return refuse_contact_loss(hist), fb_w, d0

    placements = s.get("local_placements", [[0.0, 1.0]])
    pts = [wear.wear_range_points(h0["psi"], 8, float(a), float(b)) for a, b in placements]
    t_cal = cal_h * dh.size
    with phase("joint_wear.local_interval_method") as sw_l:
        g = groove.interval_method(groove_period, theta, pts, dh, t_cal, t_end, step,
                                   int(s["groove_samples"]), float(s["groove_step"]))
    nodes = wear.interval_nodes(t_cal, t_end, step)
    at = g["tau_cal"][0] * nodes / t_cal
    ends = np.asarray(g["tau_cal"]) * t_end / t_cal
    circle = wear.local_predict(dh, cal_h, t_end, step, fb.period, wear.mean_circle_increment(
        fb, fb.period, lambda fb_w: continuous_contact_period(fb_w, s), theta, pts[0]),
        theta, pts[0])
    factor = wear_factor_of(fb, s)
    with phase("joint_wear.uniform_interval_method") as sw_u:
        _, k_u, _ = wear.calibrate_side(p, "B1", fb.period, fb.R_bush, factor)
        _, h_u, _ = wear.predict_side(p, "B1", step, k_u, fb.period, fb.R_bush, factor)
    M = wear.periods_per_interval(t_cal, fb.period)
    return {"fb": fb, "local": {"hours": nodes, "mean": np.interp(at, g["tau"], g["mean"][0]),
                                "peak": np.interp(at, g["tau"], g["peak"]), "uniform": h_u,
                                "points": pts[0], "k_local": g["tau_cal"][0] / M,
                                "k_uniform": k_u, "profile": g["profile"], "theta": theta,
                                "circle_mean": circle[1], "circle_peak": circle[2],
                                "circle_profile": circle[4],
                                "placements": np.asarray(placements, float),
                                "placement_mean": np.array([np.interp(t, g["tau"], m)
                                                            for t, m in zip(ends, g["mean"])]),
                                "placement_peak": np.interp(ends, g["tau"], g["peak"]),
                                "groove_steps": g["steps"], "groove_periods": g["refreshes"],
                                "wall_local": sw_l.seconds, "wall_uniform": sw_u.seconds,
                                "arc": f0["arc"], "AB_mean": f0["AB_mean"]}}


SOLVERS = {f.__name__: f for f in (
    clearance_implicit, clearance_explicit, continuous_contact, period_by_period, coefficient_scan,
    load_point_fit, constant_sensitivity, local_wear, load_point_posterior)}


def _methods(runs) -> set:
    return {r.get("resolution", {}).get("method") for r in runs}


def warm(runs=None) -> None:
    """Load the compiled kernels ``runs`` use (all without them) once per solver process;
    the runner calls this before the first timed run, so that no run's time carries numba's
    start."""
    dynamics.warm(dynamics.COMPILED if runs is None else _methods(runs))


def context(run: dict) -> Context:
    """The run's mechanism with the terms its effects contribute (:func:`setup`), its
    compiled kernels loaded first (once per process, see warm)."""
    dynamics.warm(_methods([run]))
    return setup(run)[1]


variables = dataset.variables

