"""Archard wear of the bushing per motion period and the interval method (Eqs. 16-34).

Unit chain.  Eq. (32) reads dh_j = K / (H w) * F_N S / L_arc with K printed in Pa^-1
(Tables 3-4) and H as "21 HB" (Table 2): dh_j is a length only if H enters as the bare
hardness number 21, so k = K / 21 [m^2/N] and Archard's K_A = k H = K * 9.80665e6 (the
readings this rules out, and why: docs/joint_wear.md, "Unit chain").

Per period (Eq. 29):  dh_j = k * F_N_mean * S / (w * L_wear)  =  k * G,
G [N/m] is the *wear factor* of one period; it is all the calibration and the
prediction need from a mechanism simulation.

Wear range.  Eq. (29) divides by L_arc^j, the length of the arc the contact point
covers.  When the load direction barely moves relative to the bushing that arc shrinks
to zero and Eq. (29) diverges, although the worn region is never narrower than the
contact patch |AB| itself.  The default ``contact_point`` is the paper's literal
L_arc; ``swept_patch`` uses L_wear = L_arc + mean |AB| (the union of the contact
patches over the period), which stays finite when the arc collapses.

Bushing growth (Sec. 4.4 steps 1, 4): the measured h^P of Eq. (33) is a change of
*diameter* across the worn side, so the enlarged bushing circle has diameter D0 + h,
i.e. R_j = R_j0 + h / 2.
"""
from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from mechrepro.errors import Refusal
from mechrepro.units import from_si

from . import contact
from .geometry import FourBar


def contact_arc(psi, in_contact=None):
    """Angular range [rad] the contact point covers on the bushing (Fig. 4, Arc^j), psi the
    contact angle (bushing frame) over one period on a uniform periodic grid.

    A continuous contact: the range of the path unwrapped along time (contact_arc_bounds,
    extremes refined by a parabola: O(dt^3) in the sampling), 2 pi where it winds round
    the bushing.  With gaps (free flight, not smooth) the raw sample range about the
    circular mean.
    """
    psi = np.asarray(psi, float)
    full = in_contact is None or bool(np.all(in_contact))
    if not full:
        psi = psi[np.asarray(in_contact, bool)]
    if psi.size == 0:
        return 0.0
    if not full or psi.size < 3:
        centre = np.angle(np.mean(np.exp(1j * psi)))
        rel = np.angle(np.exp(1j * (psi - centre)))
        return float(rel.max() - rel.min())
    bounds = contact_arc_bounds(psi)
    if bounds is None:                     # winds once round the bushing per period
        return 2.0 * math.pi
    return float(min(bounds[1] - bounds[0], 2.0 * math.pi))


def contact_arc_bounds(psi):
    """(lo, hi) [rad]: the ends of the arc a continuous contact path covers (contact_arc),
    on the path unwrapped from psi[0] (hi - lo may exceed pi; the ends are angles modulo
    2 pi), each refined by the vertex of the parabola through it; None when the path winds
    round the bushing (the arc is the whole circle and has no ends)."""
    psi = np.asarray(psi, float)
    if psi.size < 3:
        return float(psi.min()), float(psi.max())
    step = np.angle(np.exp(1j * np.diff(np.append(psi, psi[0]))))   # wrapped, periodic
    if abs(step.sum()) > math.pi:
        return None
    path = psi[0] + np.concatenate([[0.0], np.cumsum(step[:-1])])
    return _vertex(path, int(np.argmin(path))), _vertex(path, int(np.argmax(path)))


def _vertex(y, i):
    """Extreme value of the parabola through y[i-1], y[i], y[i+1] (periodic indices; the
    neighbours taken as y[i] plus their wrapped differences, so a path continued across
    the period's end is not broken by a multiple of 2 pi)."""
    y0 = y[i]
    ym = y0 + math.remainder(y[i - 1] - y0, 2.0 * math.pi)
    yp = y0 + math.remainder(y[(i + 1) % y.size] - y0, 2.0 * math.pi)
    curv = yp - 2.0 * y0 + ym
    if curv == 0.0:
        return float(y0)
    return float(y0 - (yp - ym) ** 2 / (8.0 * curv))


def contact_arc_quantile(psi, weights=None, q=0.9):
    """Central range [rad] holding the share q of the contact time, weights the time per
    sample (0 out of contact): where the contact point dwells, well-posed under impact and
    rattling, where the max - min of ``contact_arc`` is set by a few samples of the impact.
    """
    psi = np.asarray(psi, float)
    w = np.ones_like(psi) if weights is None else np.asarray(weights, float)
    keep = w > 0
    psi, w = psi[keep], w[keep]
    if psi.size == 0:
        return 0.0
    centre = np.angle(np.sum(w * np.exp(1j * psi)))
    rel = np.angle(np.exp(1j * (psi - centre)))
    order = np.argsort(rel)
    cw = np.cumsum(w[order]) / np.sum(w)
    lo = np.interp(0.5 * (1.0 - q), cw, rel[order])
    hi = np.interp(0.5 * (1.0 + q), cw, rel[order])
    return float(hi - lo)


def period_wear_factor(hist: dict, fb: FourBar, period: float,
                       wear_range: str = "contact_point", statistics: bool = True) -> dict:
    """Eqs. (18)-(24), (29) over one period sampled uniformly (periodic rectangle rule).

    hist: t, F_N, delta, v_T, psi on a uniform grid covering one period.
    statistics=False leaves out what G does not need (the contact patch of Eqs. 23-24
    unless the wear range adds it, the 90 % contact range: NaN), for calibration and
    prediction, which read G alone.
    """
    F_N, delta, v_T = (np.asarray(hist[k], float) for k in ("F_N", "delta", "v_T"))
    in_contact = delta > 0.0
    S = float(np.mean(np.abs(v_T) * in_contact) * period)                     # Eq. (21)
    F_mean = float(np.mean(F_N))                                              # Eq. (22)
    AB_mean = A_mean = arc_q90 = math.nan
    if statistics or wear_range == "swept_patch":
        AB = contact.contact_chord(np.where(in_contact, delta, 0.0), fb.R_pin, fb.R_bush)
        AB = np.where(in_contact, AB, 0.0)
        AB_mean = float(np.mean(AB))                                          # Eq. (23)
        A_mean = AB_mean * fb.width                                           # Eq. (24)
    arc = contact_arc(hist["psi"], in_contact)
    if statistics:
        arc_q90 = contact_arc_quantile(hist["psi"], in_contact.astype(float), 0.9)
    L_arc = fb.R_bush * arc
    if wear_range == "swept_patch":
        L_wear = L_arc + AB_mean
    elif wear_range == "contact_point":
        L_wear = L_arc
    else:
        raise Refusal(f"joint_wear: wear_range {wear_range!r}: allowed swept_patch, contact_point")
    G = F_mean * S / (fb.width * L_wear) if L_wear > 0 else math.inf          # Eq. (29) / k
    return {"S": S, "F_N_mean": F_mean, "AB_mean": AB_mean, "A_mean": A_mean,
            "arc": arc, "arc_q90": arc_q90, "L_arc": L_arc, "L_wear": L_wear, "G": G,
            "min_penetration": float(delta.min()), "F_N_min": float(F_N.min()),
            "F_N_max": float(F_N.max())}


def hardness_number(H):
    """The bare number Eq. (32) divides by: H [Pa] in Brinell units, 21 for 21 HB."""
    return from_si(H, "HB")


def k_from_table(K_table, H):
    """Eq. (32) with the printed units: k = K / H_number [m^2/N]; H [Pa] (SI run value)."""
    return np.asarray(K_table, float) / hardness_number(H)


def table_from_k(k, H):
    """k [m^2/N] -> the coefficient K as Tables 3-4 print it [Pa^-1]: K = k H_number."""
    return np.asarray(k, float) * hardness_number(H)


def archard_dimensionless(k, H):
    """Archard's dimensionless coefficient K_A = k H, H [Pa]."""
    return np.asarray(k, float) * H


def implied_wear_range(k, dh_per_period, F_mean, S, width):
    """The wear range L_arc [m] that Eq. (29) needs to turn k into dh_per_period."""
    return k * F_mean * S / (width * dh_per_period)


def bushing_radius(R0: float, h: float) -> float:
    """Worn bushing circle: diameter D0 + h (Sec. 4.4 step 1), so R = R0 + h / 2."""
    return R0 + 0.5 * h


def periods_per_interval(hours: float, period: float) -> float:
    """M of Eq. (34): 2 h at 6.25 s per period = 1152 periods."""
    return hours * 3600.0 / period


def calibrate(h_measured, interval_h: float, period: float, R0: float,
              wear_factor: Callable[[float], float], dh_measured=None, feedback: float = 1.0):
    """Eqs. (32)-(34): k_p = (dh^P / M) / G(R at the start of interval p).

    h_measured: cumulative measured wear h^P after each interval (Tables 3-4), which
    sets the bushing radius at the start of each interval (Sec. 4.4 step 1), times
    ``feedback`` (Sec. 4.3 does not say whether the calibration grew the bushing: 1, it did,
    as the prediction's step 1; 0, every interval on the new bushing);
    dh_measured: the increments dh^P the tables print (default: differences of h^P).
    ``wear_factor.many(radii)``, where it has one, gives the G of several radii at once.
    Returns (k_p per interval, mean k, the wear factors G_p used).
    """
    h = np.concatenate([[0.0], np.asarray(h_measured, float)])
    dh = np.diff(h) if dh_measured is None else np.asarray(dh_measured, float)    # Eq. (33)
    if dh.shape != h[1:].shape:
        raise Refusal(f"joint_wear: {dh.size} increments for {h.size - 1} cumulative values")
    M = periods_per_interval(interval_h, period)
    radii = [bushing_radius(R0, feedback * hp) for hp in h[:-1]]
    many = getattr(wear_factor, "many", None)
    G = np.array(many(radii) if many else [wear_factor(R) for R in radii])
    k = dh / M / G                                                              # Eq. (34)
    return k, float(np.mean(k)), G


def interval_nodes(t_start_h: float, t_end_h: float, interval_h: float) -> np.ndarray:
    """Simulation times of the interval method; the last interval is shortened to end at
    t_end (76 h in 16 h steps: 10, 26, 42, 58, 74, 86 -> 5 simulations, Sec. 4.5)."""
    n = int(math.ceil((t_end_h - t_start_h) / interval_h - 1e-9))
    nodes = t_start_h + interval_h * np.arange(n + 1)
    nodes[-1] = t_end_h
    return nodes


def predict(h_start: float, t_start_h: float, t_end_h: float, interval_h: float, k: float,
            period: float, R0: float, wear_factor: Callable[[float], float],
            worn_bushing: Callable[[float, float], float] | None = bushing_radius):
    """Sec. 3.3 / 4.4: one simulated period per interval, scaled by its periods.

    worn_bushing(R0, h): the bushing circle at the start of each interval (the
    wear_update effect: Sec. 4.4 step 4); None freezes the bushing at its starting size.
    Returns (node times [h], cumulative wear at the nodes [m], G per simulation).
    """
    nodes = interval_nodes(t_start_h, t_end_h, interval_h)
    h = np.empty(nodes.size)
    h[0] = h_start
    Gs = []
    G_fixed = None
    for i in range(nodes.size - 1):
        if worn_bushing is not None:
            G_fixed = wear_factor(worn_bushing(R0, h[i]))
        elif G_fixed is None:
            G_fixed = wear_factor(bushing_radius(R0, h[i]))
        Gs.append(G_fixed)
        M = periods_per_interval(nodes[i + 1] - nodes[i], period)
        h[i + 1] = h[i] + k * G_fixed * M
    return nodes, h, np.array(Gs)



def calibration_hours(p: dict) -> float:
    """The measurement interval of Tables 3-4 [h] (Eq. 33: every two hours)."""
    return float(p["measurement_interval"]) / 3600.0


def calibrate_side(p: dict, side: str, period: float, R0: float,
                   wear_factor: Callable[[float], float]):
    """:func:`calibrate` on the measurements of ``side`` (Tables 3-4) in the SI run
    parameters ``p``, with their calibration_wear_feedback."""
    return calibrate(p[f"measured_wear_{side}"], calibration_hours(p), period, R0, wear_factor,
                     dh_measured=p[f"measured_increment_{side}"],
                     feedback=float(p["calibration_wear_feedback"]))


def predict_side(p: dict, side: str, interval_h: float, k: float, period: float, R0: float,
                 wear_factor: Callable[[float], float],
                 worn_bushing: Callable[[float, float], float] | None = bushing_radius):
    """:func:`predict` of ``side`` from its last measurement to ``prediction_end``."""
    h = np.asarray(p[f"measured_wear_{side}"], float)
    return predict(h[-1], calibration_hours(p) * h.size, float(p["prediction_end"]) / 3600.0,
                   interval_h, k, period, R0, wear_factor, worn_bushing)

def interval_limit(h_start: float, t_start_h: float, t_end_h: float, k: float, period: float,
                   R0: float, wear_factor: Callable[[float], float],
                   worn_bushing: Callable[[float, float], float] = bushing_radius) -> float:
    """The interval method's limit as the interval shrinks to nothing (Sec. 3.3: its
    explicit steps h_(i+1) = h_i + k G(R(h_i)) M_i are Euler steps of this ODE):

        dh/dt = k G(R(h)) / T,   h(t_start) = h_start,

    integrated by DOP853 to rtol 1e-12 with G evaluated at every stage (one period each):
    the exact solution the interval study's cost of accuracy is measured against (the
    period-by-period sum of Fig. 6 differs from it by O(k G'(R) / 2)).  Returns h(t_end) [m]."""
    from scipy.integrate import solve_ivp
    rate = 3600.0 / period                      # periods per hour

    def f(_, h):
        return [k * wear_factor(worn_bushing(R0, float(h[0]))) * rate]
    r = solve_ivp(f, (t_start_h, t_end_h), [h_start], method="DOP853", rtol=1e-12, atol=1e-16)
    if not r.success:
        raise RuntimeError(f"joint_wear: the interval limit did not integrate: {r.message}")
    return float(r.y[0, -1])


def closed_form_factor(R0: float, p: float):
    """The wear factor of a rival without mechanics: G(R) = (R0 / R)^p, no four-bar, no
    contact (option ``closed_form_growth: p``).  p = 1 is the worn arc's length growing
    with the radius at a fixed arc, force and sliding; the calibration absorbs G's scale,
    so only its growth law enters the prediction."""
    return lambda R_bush: (R0 / R_bush) ** p


def period_by_period(h_start: float, n_periods: int, k: float, R0: float,
                     wear_factor: Callable[[float], float]):
    """Fig. 6: the reference the interval method replaces -- one simulation per period."""
    h = h_start
    for _ in range(n_periods):
        h += k * wear_factor(bushing_radius(R0, h))
    return h


def inverse_radius_prediction(h_measured, dh_measured, interval_h: float, t_end_h: float,
                              step_h: float, period: float, R0: float):
    """The comparison without mechanics: the wear factor taken as G(R) = R0 / R (the arc
    length L_arc = R * arc grows with the worn radius at a fixed arc, force and sliding
    distance: closed_form_factor with p = 1), calibrated on the same measured increments
    (Eqs. 32-34) and predicted by the same interval method (Sec. 4.4).  No four-bar, no
    contact: what it reproduces of Figs. 15-19 follows from the measured data and 1/R alone.
    Returns (node times [h], cumulative wear at the nodes [m])."""
    G = closed_form_factor(R0, 1.0)
    h = np.asarray(h_measured, float)
    _, k, _ = calibrate(h, interval_h, period, R0, G, dh_measured=dh_measured)
    nodes, hp, _ = predict(h[-1], interval_h * h.size, t_end_h, step_h, k, period, R0, G)
    return nodes, hp


# --- local Archard wear: depth per bushing angle (what Fig. 14's uniform depth replaces) --------
def local_wear_per_period(hist: dict, fb: FourBar, period: float, theta) -> np.ndarray:
    """Archard's law applied locally (Eq. 16 before the averaging of Eqs. 22-28), per unit k:
    the depth [m / (m2/N)] one period wears at each bushing angle theta (coupler frame),

        dh(theta) / k = sum_t F_N |v_T| dt / (w |AB|)  over the samples whose contact patch
                        (width |AB| of Eq. 19, centred on psi) covers theta,

    i.e. the pressure F_N / (w |AB|) uniform over the patch, times the sliding distance.  Its
    volume, w R sum dh dtheta, is k F_N S -- the volume Eq. (26) spreads uniformly over
    the wear range; only the distribution differs."""
    F_N, delta, v_T, psi = (np.asarray(hist[k], float) for k in ("F_N", "delta", "v_T", "psi"))
    on = delta > 0.0
    F_N, delta, v_T, psi = F_N[on], delta[on], v_T[on], psi[on]
    dt = period / on.size
    AB = contact.contact_chord(delta, fb.R_pin, fb.R_bush)
    rate = F_N * np.abs(v_T) * dt / (fb.width * AB)                      # per sample
    half = 0.5 * AB / fb.R_bush                                           # patch half-angle
    theta = np.asarray(theta, float)
    n = theta.size
    cell = 2.0 * math.pi / n                               # theta: a uniform grid of the circle
    # only the cells a patch can reach, its centre's and w either side: the others get
    # exact zeros, which change no sum (the sum is over samples in their order either way)
    w = int(math.ceil(half.max(initial=0.0) / cell)) + 2
    if 2 * w + 1 < n:
        near = np.rint((psi - theta[0]) / cell).astype(int)
        cells = (near[:, None] + np.arange(-w, w + 1)) % n
    else:
        cells = np.broadcast_to(np.arange(n), (psi.size, n))
    d = np.angle(np.exp(1j * (theta[cells] - psi[:, None])))
    # the share of each grid cell the patch covers (exact overlap, not a point test: the
    # depth then does not jump as the patch crosses grid points)
    h = half[:, None]
    cover = np.clip(np.minimum(d + 0.5 * cell, h) - np.maximum(d - 0.5 * cell, -h), 0.0, None)
    depth = np.zeros(n)
    np.add.at(depth, cells, rate[:, None] * cover / cell)
    return depth


def wear_range_points(psi, n: int = 8, shift: float = 0.0, scale: float = 1.0) -> np.ndarray:
    """Eq. (33): n points "uniformly distributed within the main wear range", here the
    contact-point arc of the period (contact_arc_bounds), at the middle of n equal parts of
    it: centred on the arc's midpoint, so every point lies on the arc.  A path that winds
    round the bushing covers the whole circle: the points then divide the circle, starting
    from the circular mean.  shift (a share of the arc, + towards its upper end) and scale
    (of the span) place them otherwise: the placements the result's sensitivity is shown
    over (the paper's main wear range, angle phi of Fig. 11, is drawn in a lost figure)."""
    psi = np.asarray(psi, float)
    bounds = contact_arc_bounds(psi) if psi.size >= 3 else None
    if bounds is None:
        c, a = float(np.angle(np.mean(np.exp(1j * psi)))), 2.0 * math.pi
    else:
        c, a = 0.5 * (bounds[0] + bounds[1]), bounds[1] - bounds[0]
    return c + a * (shift + scale * ((np.arange(n) + 0.5) / n - 0.5))


def at_points(profile, theta, pts) -> float:
    """Eq. (33) on a profile: its mean over the measuring points (periodic interpolation)."""
    return float(np.mean(np.interp(np.angle(np.exp(1j * np.asarray(pts))), theta, profile,
                                   period=2.0 * math.pi)))


def mean_circle_increment(fb: FourBar, period: float, one_period: Callable[[FourBar], dict],
                          theta, pts) -> Callable:
    """The mean-circle feedback (before the groove): the joint of an interval is the bushing
    circle of radius R0 + h_c / 2, h_c the profile's mean over the Eq.-33 points (the
    paper's D0 + h convention, Sec. 4.4), and the pressure F_N / (w |AB|) is uniform over
    Eq. (19)'s patch (local_wear_per_period): the profile's shape never reaches the
    contact.  Returns profile -> the depth one period wears per unit k at theta."""
    def increment(prof):
        fb_w = fb.with_bushing_radius(bushing_radius(fb.R_bush, at_points(prof, theta, pts)))
        return local_wear_per_period(one_period(fb_w), fb_w, period, theta)
    return increment


def local_predict(dh_measured, interval_h: float, t_end_h: float, step_h: float,
                  period: float, increment: Callable, theta, pts):
    """The interval method with local wear: a depth profile h(theta) on the bushing, grown
    interval by interval by ``increment(profile)`` -- the depth one period of the joint with
    that profile wears per unit k (mean_circle_increment: through a circle only).
    Calibration (Eqs. 33-34): in each measured interval p, k_p makes the profile's mean over
    the Eq.-33 points ``pts`` grow by the printed increment dh^P; the profile after 10 h is
    the one those k_p wore.
    Prediction: k = mean k_p, the profile grown by M periods of local wear per interval.
    Returns (node hours, mean depth over the points [m], max depth [m], k, the profile at
    the end [m])."""
    prof = np.zeros(theta.size)
    M = periods_per_interval(interval_h, period)
    ks = []
    for dh in np.asarray(dh_measured, float):                          # calibration
        inc = increment(prof)
        ks.append(dh / (M * at_points(inc, theta, pts)))
        prof = prof + ks[-1] * M * inc
    k = float(np.mean(ks))
    nodes = interval_nodes(interval_h * len(ks), t_end_h, step_h)
    mean, peak = [at_points(prof, theta, pts)], [float(prof.max())]
    for i in range(nodes.size - 1):                                     # prediction
        prof = prof + k * periods_per_interval(nodes[i + 1] - nodes[i], period) * increment(prof)
        mean.append(at_points(prof, theta, pts))
        peak.append(float(prof.max()))
    return nodes, np.array(mean), np.array(peak), k, prof
