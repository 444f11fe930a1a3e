"""Archard wear of the bushing per motion period and the interval method (Eqs. 16-34).

Unit reading (one consistent SI reading of the paper's mixed units): the *equivalent
wear coefficient* k = K/H of Eqs. (25)-(32) is Archard's dimensional coefficient in
m^2/N = m^3/(N m) = 1/Pa -- the unit the paper prints in Tables 3-4 ("10^-11 Pa^-1").
The dimensionless Archard K is k * H with H = 21 HB = 21 * 9.80665e6 Pa (Table 2).

Per period (Eq. 29):  dh_j = k * F_N_mean * S / (w * L_wear)  =  k * G,
G [N/m] is the *wear factor* of one period; it is all the calibration and the
prediction need from a mechanism simulation.

Wear range.  Eq. (29) divides by L_arc^j, the length of the arc the contact point
covers.  When the load direction barely moves relative to the bushing that arc shrinks
to zero and Eq. (29) diverges, although the worn region is never narrower than the
contact patch |AB| itself.  The default ``contact_point`` is the paper's literal
L_arc (it reproduces the paper's own calibration factors, see the notebook);
``swept_patch`` uses L_wear = L_arc + mean |AB| (the union of the contact patches over
the period), which stays finite when the arc collapses.

Bushing growth (Sec. 4.4 steps 1, 4): the measured h^P of Eq. (33) is a change of
*diameter* across the worn side, so the enlarged bushing circle has diameter D0 + h,
i.e. R_j = R_j0 + h / 2.
"""
from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from . import contact
from .geometry import FourBar


def contact_arc(psi, in_contact=None):
    """Angular range [rad] the contact point covers on the bushing (Fig. 4, Arc^j).

    psi is the contact angle in the bushing's frame; it is centred on its circular
    mean before the range is taken, so a range straddling +-pi is measured correctly.
    """
    psi = np.asarray(psi, float)
    if in_contact is not None:
        psi = psi[np.asarray(in_contact, bool)]
    if psi.size == 0:
        return 0.0
    centre = np.angle(np.mean(np.exp(1j * psi)))
    rel = np.angle(np.exp(1j * (psi - centre)))
    return float(rel.max() - rel.min())


def period_wear_factor(hist: dict, fb: FourBar, period: float,
                       wear_range: str = "contact_point") -> dict:
    """Eqs. (18)-(24), (29) over one period sampled uniformly (periodic rectangle rule).

    hist: t, F_N, delta, v_T, psi on a uniform grid covering one period.
    """
    F_N, delta, v_T = (np.asarray(hist[k], float) for k in ("F_N", "delta", "v_T"))
    in_contact = delta > 0.0
    S = float(np.mean(np.abs(v_T) * in_contact) * period)                     # Eq. (21)
    F_mean = float(np.mean(F_N))                                              # Eq. (22)
    AB = contact.contact_chord(np.where(in_contact, delta, 0.0), fb.R_pin, fb.R_bush)
    AB = np.where(in_contact, AB, 0.0)
    AB_mean = float(np.mean(AB))                                              # Eq. (23)
    A_mean = AB_mean * fb.width                                               # Eq. (24)
    arc = contact_arc(hist["psi"], in_contact)
    L_arc = fb.R_bush * arc
    if wear_range == "swept_patch":
        L_wear = L_arc + AB_mean
    elif wear_range == "contact_point":
        L_wear = L_arc
    else:
        raise ValueError(f"joint_wear: wear_range {wear_range!r}: allowed swept_patch, contact_point")
    G = F_mean * S / (fb.width * L_wear) if L_wear > 0 else math.inf          # Eq. (29) / k
    return {"S": S, "F_N_mean": F_mean, "AB_mean": AB_mean, "A_mean": A_mean,
            "arc": arc, "L_arc": L_arc, "L_wear": L_wear, "G": G,
            "min_penetration": float(delta.min()), "F_N_min": float(F_N.min()),
            "F_N_max": float(F_N.max())}


def local_wear_depth(k: float, F_mean: float, S: float, A_mean: float) -> float:
    """Eq. (25): dh* = (K/H) F_N S / A_a -- the depth if all wear sat at one point G."""
    return k * F_mean * S / A_mean


def distributed_wear_depth(dh_star: float, AB_mean: float, L_wear: float) -> float:
    """Eq. (28): the volume of Eq. (26) spread over the wear range: dh* AB / L."""
    return dh_star * AB_mean / L_wear


def bushing_radius(R0: float, h: float) -> float:
    """Worn bushing circle: diameter D0 + h (Sec. 4.4 step 1), so R = R0 + h / 2."""
    return R0 + 0.5 * h


def periods_per_interval(hours: float, period: float) -> float:
    """M of Eq. (34): 2 h at 6.25 s per period = 1152 periods."""
    return hours * 3600.0 / period


def calibrate(h_measured, interval_h: float, period: float, R0: float,
              wear_factor: Callable[[float], float]):
    """Eqs. (32)-(34): k_p = (dh^P / M) / G(R at the start of interval p).

    h_measured: cumulative measured wear h^P after each interval (Tables 3-4).
    Returns (k_p per interval, mean k, the wear factors G_p used).
    """
    h = np.concatenate([[0.0], np.asarray(h_measured, float)])
    dh = np.diff(h)                                                             # Eq. (33)
    M = periods_per_interval(interval_h, period)
    G = np.array([wear_factor(bushing_radius(R0, hp)) for hp in h[:-1]])
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
            update: bool = True):
    """Sec. 3.3 / 4.4: one simulated period per interval, scaled by its periods.

    update=False freezes the bushing at its starting size (no wear_update effect).
    Returns (node times [h], cumulative wear at the nodes [m], G per simulation).
    """
    nodes = interval_nodes(t_start_h, t_end_h, interval_h)
    h = np.empty(nodes.size)
    h[0] = h_start
    Gs = []
    G_fixed = None
    for i in range(nodes.size - 1):
        if update or G_fixed is None:
            G_fixed = wear_factor(bushing_radius(R0, h[i]))
        Gs.append(G_fixed)
        M = periods_per_interval(nodes[i + 1] - nodes[i], period)
        h[i + 1] = h[i] + k * G_fixed * M
    return nodes, h, np.array(Gs)


def period_by_period(h_start: float, n_periods: int, k: float, R0: float,
                     wear_factor: Callable[[float], float]):
    """Fig. 6: the reference the interval method replaces -- one simulation per period."""
    h = h_start
    for _ in range(n_periods):
        h += k * wear_factor(bushing_radius(R0, h))
    return h
