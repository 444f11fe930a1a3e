"""Polygonal action: the rigid four-bar (Eqs. 2-6 to 2-10), the end-point motions
(Eqs. 2-24, 2-25), the span-length state, and the elastic four-bar (Eqs. 2-11 to 2-23).

All functions broadcast over time and operating speed.  Angles in rad, SI units.
"""
from __future__ import annotations

import math

import numpy as np

from . import samples
from .geometry import pitch_radius, span_geometry
from .samples import kinematics_formulas, phase_formulas, tooth_constants


def driven_phase(n2: int, f_p: float) -> float:
    """alpha_f = 2 pi f_p / n2 (Eq. 2-7)."""
    return 2.0 * np.pi * f_p / n2


def chain_travel(t, omega1, n1: int, r1: float):
    """Chain length paid out by the driving sprocket since t = 0, and theta_1.

    theta_1 = omega1 t + pi/2 - pi/n1 within a tooth period (Eq. 2-7); each tooth period
    the chord r1 (cos theta_10 - cos theta_1) sweeps exactly one pitch.
    """
    t = np.asarray(t, float)
    phi = np.asarray(omega1, float) * t
    step = 2 * np.pi / n1
    k = np.floor(phi / step)
    th10 = np.pi / 2 - np.pi / n1
    th1 = th10 + (phi - k * step)
    p_c = 2 * r1 * np.sin(np.pi / n1)
    return k * p_c + r1 * (np.cos(th10) - np.cos(th1)), th1


def _driven_offset(n2, r2, f_p):
    """The driven sprocket's travel at t = 0, s_off in [0, p_c) (its phase f_p, Eq. 2-7)."""
    th20_start = np.pi / 2 - np.pi / n2
    return r2 * (np.cos(th20_start) - np.cos(th20_start + driven_phase(n2, f_p)))


def driven_wrap_time(omega1: float, n1: int, n2: int, p_c: float, f_p: float) -> float:
    """The time in [0, tau) at which a roller leaves the driven sprocket (its tooth phase
    wraps, Eq. 2-8; the driving sprocket seats one at t = 0, tau, ...): the chain travel
    since the last engagement r1 (cos theta_10 - cos theta_1) reaches p_c - s_off."""
    s_off = _driven_offset(n2, pitch_radius(p_c, n2), f_p)
    if s_off < 1e-12 * p_c or f_p == 0.0:
        return 0.0
    th10 = np.pi / 2 - np.pi / n1
    return (math.acos(math.cos(th10) - (p_c - s_off) / pitch_radius(p_c, n1)) - th10) / omega1


def tooth_phases(t, omega1, *, n1: int, n2: int, p_c: float, f_p: float) -> dict:
    """theta_1 and the driving/driven tooth phases (fraction of a pitch of chain travel since
    the last engagement / disengagement) -- the part of :func:`rigid_kinematics` the
    span-length state needs (one cosine per sample): :func:`.samples.phase_formulas` on the samples."""
    r1, r2 = pitch_radius(p_c, n1), pitch_radius(p_c, n2)
    omega1 = np.asarray(omega1, float)
    t = np.asarray(t, float)
    s_off = _driven_offset(n2, r2, f_p)
    tooth = tooth_constants(n1)
    shape = samples.block(t, omega1)
    if shape:
        th1, c1, s2, phase1, near = samples.phases(t, omega1, shape, tooth, r1, s_off, p_c)
    else:
        th1, c1, s2, phase1, near = phase_formulas(omega1 * t, tooth, r1, s_off, p_c)
    if np.any(near):
        # the side of the jump decided exactly as chain_travel + np.mod decide it
        s_full, _ = chain_travel(np.broadcast_to(t, near.shape)[near],
                                 np.broadcast_to(omega1, near.shape)[near], n1, r1)
        s2, phase1 = np.array(s2), np.array(phase1)     # writable, also from 0-d inputs
        s2[near] = np.mod(s_full + s_off, p_c)
        phase1[near] = np.mod(s_full, p_c) / p_c
    return {"theta1": th1, "cos_theta1": c1, "travel2": s2, "phase1": phase1,
            "phase2": s2 / p_c, "r1": r1, "r2": r2}


def rigid_kinematics(t, omega1, *, n1: int, n2: int, p_c: float, f_p: float,
                     phases: dict | None = None) -> dict:
    """Rigid four-bar, Eqs. (2-7) to (2-10) (without I2; see :func:`polygonal_load_rigid`).

    theta_2 follows from r2 cos theta_2 = r2 cos theta_20 - (chain travel mod p_c), the
    integrated form of Eq. (2-7) with the wrap of Eq. (2-8) at every driven tooth.
    Returns theta1, omega2 (Eq. 2-7), alpha2 (Eq. 2-9), the driving/driven tooth phases
    (fraction of a pitch since the last engagement / disengagement), and the sines and
    cosines of theta1, theta2 (theta2 itself, an arccos costing ~1/10 of this function,
    is read by no effect: arccos(cos_theta2), theta2 in (0, pi)).  ``phases``:
    :func:`tooth_phases` of the same arguments, when already computed.
    """
    ph = tooth_phases(t, omega1, n1=n1, n2=n2, p_c=p_c, f_p=f_p) if phases is None else phases
    r1, r2 = ph["r1"], ph["r2"]
    omega1 = np.asarray(omega1, float)
    c1, s2 = ph["cos_theta1"], ph["travel2"]
    c20 = np.cos(np.pi / 2 - np.pi / n2)
    if samples.block(t, omega1):
        s1, c2, sn2, w2, a2 = samples.kinematics(omega1, c1, s2, c20, r1, r2)
    else:
        s1, c2, sn2, w2, a2 = kinematics_formulas(omega1, c1, s2, c20, r1, r2)
    return {"theta1": ph["theta1"], "omega2": w2, "alpha2": a2, "r1": r1, "r2": r2,
            "phase1": ph["phase1"], "phase2": ph["phase2"],
            "cos_theta1": c1, "sin_theta1": s1, "cos_theta2": c2, "sin_theta2": sn2}


def polygonal_load_rigid(alpha2, I2: float, r2: float):
    """Eq. (2-10): D_pol = I2 alpha2 / r2."""
    return I2 * np.asarray(alpha2, float) / r2


def end_displacements(sin1, sin2, r1: float, r2: float, n2: int):
    """Eqs. (2-24), (2-25): u_n = r1 (1 - sin theta1) (driving end), u_0 = r2 (1 - sin theta2)
    (driven end), both shifted by -0.5 r2 (1 - cos(pi/n2)) as the paper states; from
    sin theta1/2 (:func:`rigid_kinematics`)."""
    shift = -0.5 * r2 * (1 - np.cos(np.pi / n2))
    return r2 * (1 - sin2) + shift, r1 * (1 - sin1) + shift


def end_velocities(cos1, cos2, omega1, omega2, r1: float, r2: float):
    """Time derivatives of Eqs. (2-25), (2-24): u_0' = -r2 cos(theta2) omega2 (driven end),
    u_n' = -r1 cos(theta1) omega1 (driving end); they jump at every tooth (chordal kinks).
    From cos theta1/2 (:func:`rigid_kinematics`)."""
    return -r2 * cos2 * omega2, -r1 * cos1 * omega1


def long_span(phase1, phase2):
    """Length state of Sec. 2.2: the span is long (L_0 + p_c) after a disengagement at the
    driven sprocket until the next engagement at the driving sprocket.

    A disengagement is more recent than the last engagement iff the driven phase is
    smaller than the driving phase (both measured in pitches of chain travel).
    """
    return np.asarray(phase2) < np.asarray(phase1)


# --------------------------------------------------------------------------- elastic four-bar

def fourier_coefficients(n1: int, n2: int, r1: float, r2: float, alpha: float) -> dict:
    """Eqs. (2-12), (2-14): a0, a1, a2 and N, b1, c1, b2, c2 (two harmonics kept)."""
    a0 = n1 * r1 / np.pi * np.sin(np.pi / n1)
    N = (n2 * r2 / np.pi * np.sin(np.pi / n2)) / a0
    return {
        "a0": a0, "a1": 2 * a0 / (1 - n1**2), "a2": 2 * a0 / (1 - 4 * n1**2), "N": N,
        "b1": 2 * N * a0 / (1 - n2**2) * np.cos(n2 * alpha),
        "c1": -2 * N * a0 / (1 - n2**2) * np.sin(n2 * alpha),
        "b2": 2 * N * a0 / (1 - 4 * n2**2) * np.cos(2 * n2 * alpha),
        "c2": -2 * N * a0 / (1 - 4 * n2**2) * np.sin(2 * n2 * alpha),
    }


def _elastic_residual(X, omega1, k, I2, fc, pt):
    """Residual of Eq. (2-19) on one tooth period with Eqs. (2-13), (2-14), (2-16), (2-17).

    X = (l1, m1, l2, m2).  The residual is linear in X, so its harmonic projection
    gives the 9x4 system A X = F of Eq. (2-20).
    """
    l1, m1, l2, m2 = X
    a0, a1, a2, N = fc["a0"], fc["a1"], fc["a2"], fc["N"]
    b1, c1, b2, c2 = fc["b1"], fc["c1"], fc["b2"], fc["c2"]
    p = pt[1]
    ct, st, c2t, s2t = (np.cos(pt[0]), np.sin(pt[0]), np.cos(2 * pt[0]), np.sin(2 * pt[0]))
    # x1 + L - x2 without the secular terms (they cancel): Eqs. (2-13), (2-16)
    x1 = -omega1 * (a1 / p * st + a2 / (2 * p) * s2t)
    x2 = -omega1 / N * (l1 / p * st - m1 / p * ct + l2 / (2 * p) * s2t - m2 / (2 * p) * c2t) \
        - omega1 / (N * p) * (m1 + m2 / 2)
    stretch = x1 - x2
    r2s2 = N * a0 + b1 * ct + c1 * st + b2 * c2t + c2 * s2t            # Eq. (2-14)
    A_ = N * a0 + l1 * ct + m1 * st + l2 * c2t + m2 * s2t
    B_ = N * a0 - b1 * ct - c1 * st - b2 * c2t - c2 * s2t
    dA = p * (-l1 * st + m1 * ct - 2 * l2 * s2t + 2 * m2 * c2t)
    dB = p * (b1 * st - c1 * ct + 2 * b2 * s2t - 2 * c2 * c2t)
    th2dd = omega1 / (N**3 * a0**2) * (dA * B_ + A_ * dB)             # Eqs. (2-17), (2-18)
    return I2 * th2dd + k * stretch * r2s2                           # Eq. (2-19)


def elastic_four_bar(omega1: float, *, k: float, I2: float, n1: int, n2: int, p_c: float,
                     f_p: float, n_samples: int = 64) -> dict:
    """Elastic four-bar of Sec. 2.1.2b: solve A X = F (Eq. 2-20) by least squares (Eq. 2-21).

    A and F are the projections of Eq. (2-19) on the nine harmonics 1, cos ipt, sin ipt
    (i = 1..4), computed numerically (FFT of the residual over one tooth period) rather than
    transcribed from Appendix II, whose printed entries contain duplicates and typos.
    """
    r1, r2 = pitch_radius(p_c, n1), pitch_radius(p_c, n2)
    fc = fourier_coefficients(n1, n2, r1, r2, driven_phase(n2, f_p))
    p = n1 * omega1
    phase = 2 * np.pi * np.arange(n_samples) / n_samples
    pt = (phase, p)

    def harmonics(res):
        C = np.fft.rfft(res) / n_samples
        return np.concatenate([[C[0].real], np.ravel(np.column_stack(
            [2 * C[1:5].real, -2 * C[1:5].imag]))])

    F = -harmonics(_elastic_residual(np.zeros(4), omega1, k, I2, fc, pt))
    A = np.column_stack([harmonics(_elastic_residual(e, omega1, k, I2, fc, pt)) + F
                         for e in np.eye(4)])
    X, *_ = np.linalg.lstsq(A, F, rcond=None)
    return {"X": X, "A": A, "F": F, "coef": fc, "p": p, "r1": r1, "r2": r2}


def polygonal_load_elastic_speeds(sin_pt, cos_pt, sols, omega1, k: float):
    """Eq. (2-22), D_pol = k (x2 - x1 - L), for S speeds at once from sin(p t), cos(p t)
    shaped (T, S) (p = n1 omega1, shared by both span stiffnesses; the second harmonic by
    the double-angle formulas), ``sols`` the S solutions of :func:`elastic_four_bar`,
    ``omega1`` (S,)."""
    X = np.array([s["X"] for s in sols])                       # (S, 4)
    l1, m1, l2, m2 = X.T
    N = np.array([s["coef"]["N"] for s in sols])
    a1 = np.array([s["coef"]["a1"] for s in sols])
    a2 = np.array([s["coef"]["a2"] for s in sols])
    p = np.array([s["p"] for s in sols])
    s2 = 2 * sin_pt * cos_pt
    c2 = 1 - 2 * sin_pt * sin_pt
    return k * np.asarray(omega1, float) / (N * p) * ((N * a1 - l1) * sin_pt + m1 * cos_pt
                                                      + 0.5 * (N * a2 - l2) * s2
                                                      + 0.5 * m2 * c2 - m1 - 0.5 * m2)


def elastic_resonance(k: float, I2: float, r2: float, n1: int) -> float:
    """Driving speed omega1 at which the tooth frequency n1 omega1 meets the torsional
    frequency r2 sqrt(k/I2) of the driven sprocket on the span spring k = AE/L."""
    return r2 * np.sqrt(k / I2) / n1


def omega_c(prm, L: float) -> float:
    """The elastic four-bar resonance omega_c = r2 sqrt(k/I2)/n1 of a span L, k = AE/L."""
    return elastic_resonance(prm["axial_stiffness"] / L, prm["driven_inertia"],
                             pitch_radius(prm["pitch"], int(prm["n2"])), int(prm["n1"]))


def elastic_speed_window(prm, window) -> tuple[float, float]:
    """Speeds [lo, hi] x omega_c of the drive's own elastic four-bar resonance with
    k = AE/L_ct: a medium-speed window placed around the resonance of *this* drive, not a
    speed range copied from another drive."""
    wc = omega_c(prm, span_geometry(prm, False)["L_ct"])
    return float(window[0] * wc), float(window[1] * wc)
