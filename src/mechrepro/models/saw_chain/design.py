"""Design maps from the exact solution: peak load, speed fluctuation and the textbook's error
over many chains at once (the guidelines the paper's conclusion promises and does not show).

Every quantity is a closed-form function of the design (p1, p2, z, omega, m_L, m_C, M, N):
the exact derivatives of Eqs. (7)-(10) (:func:`.kinematics.stage_derivatives`), loaded by
Eqs. (14)-(16), (20)-(22), evaluated on a fixed grid of ``n`` angles per stage for all designs
at once (arrays broadcast against each other), with the extrema refined by a parabola
through the three samples around each (measured against n = 4097 at the default n = 65: <= 1.5e-6 relative for z = 3..60 at the paper's pitches, 2.7e-6 for z = 3 with 5:1 pitches; the peak is exact, an end sample).
No difference method, no K: a design costs a few microseconds.
"""
from __future__ import annotations

import numpy as np

from .geometry import stage_angles
from .kinematics import stage_derivatives
from .loads import dynamic_load, tight_side_mass


def _refined(y, kind):
    """min or max along the last axis, refined by a parabola through the neighbours of the
    sampled extremum when it is interior (an end sample is the extremum itself)."""
    i = (np.argmin if kind == "min" else np.argmax)(y, axis=-1)
    n = y.shape[-1]
    j = np.clip(i, 1, n - 2)
    take = lambda k: np.take_along_axis(y, k[..., None], axis=-1)[..., 0]  # noqa: E731
    ym, y0, yp = take(j - 1), take(j), take(j + 1)
    curv = ym - 2 * y0 + yp
    with np.errstate(divide="ignore", invalid="ignore"):
        vertex = y0 - 0.125 * (yp - ym) ** 2 / curv
    interior = (i > 0) & (i < n - 1) & (curv != 0)
    return np.where(interior, vertex, take(i))


def design_quantities(p1, p2, z, omega, m_L, m_C, M, N, n=65) -> dict:
    """Exact per-design extrema of one period (arrays broadcast; SI units).

    Returns ``peak_load`` and ``min_load`` [N] (F_dx of the exact derivatives),
    ``speed_max`` = R omega and ``speed_min`` [m/s], ``speed_fluctuation`` =
    (R omega - v_min) / (R omega), ``textbook_peak`` = (M m_L + N m_C) R omega^2 sin(pi/z) [N]
    (Eq. 23 with theta = -pi/z on the whole tight side, the pipeline's assumed constants)
    and ``textbook_error`` = textbook_peak / peak_load - 1.
    """
    p1, p2, z, omega, m_L, m_C, M, N = np.broadcast_arrays(
        *(np.asarray(a, float) for a in (p1, p2, z, omega, m_L, m_C, M, N)))
    R = _radius(p1, p2, z)
    phi1, phi2 = stage_angles(p1, p2, R)
    m_tight = tight_side_mass(M, N, m_L, m_C)
    u = np.linspace(0.0, 1.0, n)
    Fmax, Fmin, vmin = [], [], []
    for L, m_link, span in ((p2, m_C, phi1), (p1, m_L, phi2 - phi1)):
        phi = span[..., None] * u
        d = stage_derivatives(phi, R[..., None], L[..., None], omega[..., None])
        F, _ = dynamic_load(m_link[..., None], d["mid_ax"], d["mid_ay"], m_tight[..., None], d["trail_ax"])
        Fmax.append(_refined(F, "max")), Fmin.append(_refined(F, "min"))
        vmin.append(_refined(d["trail_vx"], "min"))
    peak = np.maximum(*Fmax)
    v_top = R * omega
    v_low = np.minimum(*vmin)
    textbook = m_tight * R * omega**2 * np.sin(np.pi / z)
    return {"peak_load": peak, "min_load": np.minimum(*Fmin), "speed_max": v_top,
            "speed_min": v_low, "speed_fluctuation": (v_top - v_low) / v_top,
            "textbook_peak": textbook, "textbook_error": textbook / peak - 1.0}


def _radius(p1, p2, z):
    """Eq. (1) on arrays (:func:`.geometry.pitch_radius` checks one design at a time)."""
    return np.sqrt(p1**2 + p2**2 + 2 * p1 * p2 * np.cos(np.pi / z)) / (2 * np.sin(np.pi / z))


def log_slope(f, x, x0, rel=1e-3):
    """d ln f / d ln x at x0 by a central difference in ln x (f: x -> array of the quantity)."""
    lo, hi = f(x0 * (1 - rel)), f(x0 * (1 + rel))
    return (np.log(hi) - np.log(lo)) / (np.log1p(rel) - np.log1p(-rel))


def _z_slope(q, base, z, **over):
    """d ln q / d ln z by the neighbours z - 1, z + 1 (z is an integer); ``over`` may give
    a function of z for other design entries (e.g. omega at fixed chain speed)."""
    vals = []
    for zz in (z - 1, z + 1):
        extra = {k: f(zz) for k, f in over.items()}
        vals.append(float(design_quantities(**{**base, "z": zz, **extra})[q]))
    return (np.log(vals[1]) - np.log(vals[0])) / (np.log(z + 1) - np.log(z - 1))


def design_rules(base: dict) -> dict:
    """The scaling laws read off the design maps at the design ``base`` (keys of
    :func:`design_quantities`), each a number with the sentence it supports.

    Each is a local exponent d ln q / d ln x of the closed form (or a limit of it); the tests
    (``tests/test_saw_chain_design.py``) check each against the closed form at other designs.
    """
    z, w = int(base["z"]), float(base["omega"])
    q0 = {k: float(v) for k, v in design_quantities(**base).items()}
    s = base["p1"] + base["p2"]
    r0 = base["p1"] / base["p2"]
    at_ratio = lambda r: design_quantities(**{**base, "p1": s * r / (1 + r), "p2": s / (1 + r)})  # noqa: E731
    equal = design_quantities(**{**base, "z": 200, "p2": base["p1"]})
    return {
        "design_peak_load_speed_exponent": (
            float(log_slope(lambda x: design_quantities(**{**base, "omega": x})["peak_load"], None, w)),
            "peak load ~ omega^2: positions depend on omega t only"),
        "design_peak_load_teeth_exponent_fixed_speed": (
            _z_slope("peak_load", base, z),
            f"at a fixed sprocket speed the peak load hardly depends on z (z = 3: "
            f"{float(design_quantities(**{**base, 'z': 3})['peak_load']):.1f} N, z = {z}: {q0['peak_load']:.1f} N, "
            f"z = 60: {float(design_quantities(**{**base, 'z': 60})['peak_load']):.1f} N)"),
        "design_peak_load_teeth_exponent_fixed_chain_speed": (
            _z_slope("peak_load", base, z, omega=lambda zz: w * z / zz),
            "at a fixed chain speed z (p1 + p2) omega / 2 pi the peak load falls like z^-2: "
            "more teeth, slower sprocket"),
        "design_fluctuation_teeth_exponent": (
            _z_slope("speed_fluctuation", base, z),
            f"the relative speed fluctuation (R omega - v_min) / (R omega) falls like z^-2 "
            f"({q0['speed_fluctuation']:.4f} at z = {z})"),
        "design_fluctuation_equal_pitch_constant": (
            float(equal["speed_fluctuation"]) * 200**2,
            "z^2 x fluctuation for equal pitches at z = 200 (numerically 2 pi^2 / 27 = 0.731083)"),
        "design_peak_load_mass_exponent": (
            float(log_slope(lambda m: design_quantities(**{**base, "M": m * base["M"], "N": m * base["N"]})["peak_load"],
                            None, 1.0)),
            "peak load ~ tight-side mass: F = m_L a_mid(t2) + (M m_L + N m_C) a_trail(t2), affine in M, N"),
        "design_peak_load_pitch_ratio_exponent": (
            float(log_slope(lambda r: at_ratio(r)["peak_load"], None, r0)),
            f"at fixed p1 + p2, unequal pitches raise the peak load: p1/p2 = 1: "
            f"{float(at_ratio(1.0)['peak_load']):.1f} N, {r0:.3f}: {q0['peak_load']:.1f} N, 2: "
            f"{float(at_ratio(2.0)['peak_load']):.1f} N, 5: {float(at_ratio(5.0)['peak_load']):.1f} N; "
            f"fluctuation {float(at_ratio(1.0)['speed_fluctuation']):.4f}, {q0['speed_fluctuation']:.4f}, "
            f"{float(at_ratio(2.0)['speed_fluctuation']):.4f}, {float(at_ratio(5.0)['speed_fluctuation']):.4f}"),
        "design_textbook_error": (
            q0["textbook_error"],
            f"Eq. (23) with theta = -pi/z and the whole tight side over-predicts the peak by this "
            f"fraction; z = 3: {float(design_quantities(**{**base, 'z': 3})['textbook_error']):.3f}, "
            f"z = 60: {float(design_quantities(**{**base, 'z': 60})['textbook_error']):.3f}; p1/p2 = 5: "
            f"{float(at_ratio(5.0)['textbook_error']):.3f}"),
    }
