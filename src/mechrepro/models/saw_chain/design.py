"""Design maps from the exact solution: peak load, speed fluctuation and the textbook's error
over many chains at once (the guidelines the paper's conclusion promises).  The exact
derivatives of Eqs. (7)-(10) loaded by Eqs. (14)-(16), (20)-(22) on ``n`` angles per stage,
extrema refined by a parabola; no difference method, no K."""
from __future__ import annotations

import numpy as np

from .geometry import radius, stage_angles
from .kinematics import stage_derivatives
from .loads import dynamic_load, tight_side_mass


def _refined(y, kind):
    """min or max along the last axis, refined by a parabola through an interior extremum's
    neighbours."""
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
    """Exact per-design extrema of one period (arrays broadcast; SI): ``peak_load``, ``min_load``,
    ``speed_max`` = R omega, ``speed_min``, ``speed_fluctuation``, ``textbook_peak`` (Eq. 23 with
    the assumed theta = -pi/z on the whole tight side) and ``textbook_error``."""
    p1, p2, z, omega, m_L, m_C, M, N = np.broadcast_arrays(
        *(np.asarray(a, float) for a in (p1, p2, z, omega, m_L, m_C, M, N)))
    R = radius(p1, p2, z)
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
    """The scaling laws at the design ``base``: local exponents d ln q / d ln x of the closed form
    (or a limit), each with the sentence it supports."""
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


def chord_angle(p, R):
    """Angle a link of pitch p subtends on the pitch circle, 2 asin(p / 2R) (Eqs. 5-6) [rad]."""
    return 2.0 * np.arcsin(p / (2.0 * R))


def rule_speed_fluctuation(p1, p2, z):
    """Relative speed fluctuation ~ 2 alpha^2 / 27, alpha the longer link's chord angle (leading
    order).  With lambda = L / R the trailing hinge moves at
    v / (R omega) = 1 - phi^2 / 2 + phi^3 / (2 lambda) + O(phi^4), lowest at phi = 2 lambda / 3."""
    R = radius(*(np.asarray(a, float) for a in (p1, p2, z)))
    return 2.0 * chord_angle(np.maximum(p1, p2), R) ** 2 / 27.0


def _stage_end_load(p, m_link, m_tight, R, omega):
    """F_dx at the end of the stage in which a link of pitch p and mass m_link seats."""
    a = chord_angle(p, R)
    return omega**2 * R * ((m_tight + 0.5 * m_link) * np.tan(0.5 * a) - 0.5 * m_link * np.sin(a))


def rule_peak_load(p1, p2, z, omega, m_L, m_C, M, N):
    """Peak load, exact: the larger stage end of
    F = omega^2 R [(M m_L + N m_C + m/2) tan(alpha/2) - m sin(alpha) / 2] (Eqs. 14-16, 20-22
    at t1-, t2-): at the stage end a_trail = R omega^2 tan(alpha/2), a_lead,x = -R omega^2 sin(alpha)."""
    args = [np.asarray(a, float) for a in (p1, p2, z, omega, m_L, m_C, M, N)]
    p1, p2, z, omega, m_L, m_C, M, N = np.broadcast_arrays(*args)
    R, m_tight = radius(p1, p2, z), tight_side_mass(M, N, m_L, m_C)
    return np.maximum(_stage_end_load(p1, m_L, m_tight, R, omega),
                      _stage_end_load(p2, m_C, m_tight, R, omega))


def rule_peak_load_simple(p1, p2, M, N, m_L, m_C, omega):
    """Peak load ~ (M m_L + N m_C) omega^2 p_long / 2: :func:`rule_peak_load` to leading order in
    alpha, independent of z."""
    return tight_side_mass(M, N, m_L, m_C) * np.asarray(omega, float) ** 2 * np.maximum(p1, p2) / 2.0


#: the rules checked against the exact solution over teeth and pitch ratios (rule_errors)
RULES = {"speed_fluctuation_2alpha2_27": "speed_fluctuation",
         "peak_load_stage_end": "peak_load",
         "peak_load_m_omega2_p_2": "peak_load"}


def rule_errors(base: dict, teeth, ratios, n=257) -> dict:
    """Relative error of each rule against the exact solution over teeth x pitch ratios at the
    base's p1 + p2, masses and links."""
    s = base["p1"] + base["p2"]
    z = np.asarray(teeth, float)[:, None]
    r = np.asarray(ratios, float)[None, :]
    d = {**base, "z": z, "p1": s * r / (1 + r), "p2": s / (1 + r)}
    exact = design_quantities(**d, n=n)
    rules = {"speed_fluctuation_2alpha2_27": rule_speed_fluctuation(d["p1"], d["p2"], z),
             "peak_load_stage_end": rule_peak_load(**d),
             "peak_load_m_omega2_p_2": rule_peak_load_simple(d["p1"], d["p2"], d["M"], d["N"],
                                                              d["m_L"], d["m_C"], d["omega"])}
    return {k: v / exact[RULES[k]] - 1.0 for k, v in rules.items()}


#: the quantities each design map shows (rows of figure design_maps)
MAP_QUANTITIES = ("peak_load", "speed_fluctuation", "textbook_error")
#: the pitch ratios of the map over teeth, the teeth of the map over pitch ratios
Z_RATIOS, RATIO_TEETH = (1.0, None, 2.0, 5.0), (4, 8, 16)   # None: the base design's ratio


def design_maps(base: dict, teeth, ratios, speeds, links, rule_teeth, rule_ratios) -> dict:
    """The maps of figure design_maps (over teeth, also at the base's chain speed; over p1/p2 at
    fixed p1 + p2; over speed; over links M = N; at the base) and the rules' errors."""
    s = base["p1"] + base["p2"]
    r0 = base["p1"] / base["p2"]
    zr = np.array([r0 if r is None else r for r in Z_RATIOS])[:, None]
    z = np.asarray(teeth, float)[None, :]
    by_z = {**base, "z": z, "p1": s * zr / (1 + zr), "p2": s / (1 + zr)}
    ra = np.asarray(ratios, float)[None, :]
    rz = np.asarray(RATIO_TEETH, float)[:, None]
    out = {"z_ratio": zr[:, 0], "ratio_teeth": rz[:, 0]}
    maps = {"z": design_quantities(**by_z),
            "ratio": design_quantities(**{**base, "z": rz, "p1": s * ra / (1 + ra), "p2": s / (1 + ra)}),
            "speed": design_quantities(**{**base, "omega": np.asarray(speeds, float)}),
            "links": design_quantities(**{**base, "M": np.asarray(links), "N": np.asarray(links)}),
            "paper": design_quantities(**base)}
    for m, d in maps.items():
        for q in MAP_QUANTITIES:
            out[f"{m}_{q}"] = d[q]
    out["z_peak_load_fixed_chain_speed"] = design_quantities(
        **{**by_z, "omega": base["omega"] * base["z"] / z})["peak_load"]
    errors = rule_errors(base, rule_teeth, rule_ratios)
    out["rule_error"] = np.stack([errors[k] for k in RULES])
    return out


#: each rule's formula, as the table prints it
RULE_FORMULAS = {
    "speed_fluctuation_2alpha2_27": "(R omega - v_min)/(R omega) ~ 2 alpha_long^2 / 27, alpha = 2 asin(p / 2R)",
    "peak_load_stage_end": "F_peak = omega^2 R [(M m_L + N m_C + m/2) tan(alpha/2) - m sin(alpha)/2], longer link's stage end",
    "peak_load_m_omega2_p_2": "F_peak ~ (M m_L + N m_C) omega^2 p_long / 2",
}
RULE_COLUMNS = ["rule", "formula", "max_abs_error", "worst_teeth", "worst_ratio", "teeth", "ratios"]


def rule_table(ds) -> list[list]:
    """Rows of ``design_rules.csv``: each rule's largest error over the checked teeth and ratios."""
    teeth, ratios = ds["rule_teeth"].values, ds["rule_ratio"].values
    rows = []
    for k, rule in enumerate(RULES):
        e = np.abs(ds["rule_error"].values[k])
        i, j = np.unravel_index(int(np.argmax(e)), e.shape)
        rows.append([rule, RULE_FORMULAS[rule], float(e.max()), int(teeth[i]), float(ratios[j]),
                     f"{int(teeth[0])}-{int(teeth[-1])}", f"{ratios[0]:g}-{ratios[-1]:g}"])
    return rows
