"""Which unstated choices of the authors' program the paper's six numbers select (Sec. 4: the
band 14.57-14.77 m/s, the measured 14.6 and 0.2 m/s, the loads -74.5 and 209.4 N).

Explanations: the pitch-radius ``reading`` (:func:`.analysis.pitch_radius_readings`), the
sprocket ``speed`` factor s actually run, the test chain's ``stretch`` e; K of 209.4 N is
profiled.  Predictions are closed form in s and e (velocities scale with s, loads with s^2,
the measured chain's velocities with 1 + e).  Noise: each number's printed rounding
(variance h^2/3), a declared relative model error, and the printed inputs' rounding
propagated (J diag(h^2/3) J^T).  chi^2 = r^T C^-1 r, s and e profiled; intervals where the
profile stays within 1 (68 %) and 3.84 (95 %).  Reported, not adopted."""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from .analysis import pitch_radius_readings, velocity_band
from .chain import Design
from .geometry import stage_angles
from .kinematics import stage_derivatives, stage_positions

#: the six paper numbers, in the order of every array here
DATA = ("band_min", "band_max", "measured_mean", "measured_fluctuation", "load_min", "load_max")
#: explanations: (name, readings allowed, speed free, stretch free)
EXPLANATIONS = (("as printed", ("eq1",), False, False),
                ("speed", ("eq1",), True, False),
                ("stretch", ("eq1",), False, True),
                ("speed + stretch", ("eq1",), True, True),
                ("reading", None, False, False),
                ("reading + stretch", None, False, True),
                ("reading + speed", None, True, False),
                ("reading + speed + stretch", None, True, True))
#: Delta chi^2 of a 68 % and a 95 % interval of one parameter
DCHI2 = {"68": 1.0, "95": 3.841}


def _stage_loads_exact(d: Design, R, n=2001):
    """Exact F_dx over one period with pitch radius R (Eqs. 7-10, 14-16, 20-22) [N]."""
    phi1, phi2 = stage_angles(d.p1, d.p2, R)
    m_tight = d.M * d.m_L + d.N * d.m_C
    F = []
    for L, m, span in ((d.p2, d.m_C, phi1), (d.p1, d.m_L, phi2 - phi1)):
        phi = np.linspace(0.0, span, n)
        g = stage_derivatives(phi, R, L, d.omega)
        F.append(m * g["mid_ax"] + m_tight * g["trail_ax"])
    return np.concatenate(F)


def last_sample_load(d: Design, R, K):
    """The difference method's load at the last sample t2 for every K (three positions per K: a
    second backward difference in stage 2); the method's maximum on the paper's chain."""
    K = np.asarray(K, float)
    phi1, phi2 = stage_angles(d.p1, d.p2, R)
    span = phi2 - phi1
    dt = span / (K * d.omega)
    pos = [stage_positions(span * (1.0 - j / K), R, d.p1, d.p1 + 2 * d.p2) for j in (0, 1, 2)]
    second = {k: (pos[0][k] - 2.0 * pos[1][k] + pos[2][k]) / dt**2 for k in ("trail_x", "mid_x")}
    return d.m_L * second["mid_x"] + (d.M * d.m_L + d.N * d.m_C) * second["trail_x"]


def unit_predictions(d: Design, reading: str, K) -> dict:
    """Per-reading constants at s = 1, e = 0: band ends, the real chain's mean and
    fluctuation, the exact load minimum and the load maximum at each K of ``K``."""
    R = pitch_radius_readings(d.p1, d.p2, d.z)[reading]
    R1 = pitch_radius_readings(d.p1, d.p2, d.z)["eq1"]
    lo, hi = velocity_band(d.p1, d.p2, d.omega, R)
    lo1, hi1 = velocity_band(d.p1, d.p2, d.omega, R1)
    return {"band_min": lo, "band_max": hi,
            "measured_mean": d.z * (d.p1 + d.p2) * d.omega / (2 * math.pi),
            "measured_fluctuation": hi1 - lo1,
            "load_min": float(_stage_loads_exact(d, R).min()),
            "load_max_K": last_sample_load(d, R, K)}


def predict(u: dict, s, e, load_max_paper: float):
    """The six predictions for speed factors ``s`` and stretches ``e`` (broadcast), and the
    profiled K of the load maximum.  Returns (array [..., 6], K array)."""
    s, e = np.broadcast_arrays(np.asarray(s, float), np.asarray(e, float))
    FK = u["load_max_K"]                         # increasing in K: the lag dt max|dF/dt| falls
    target = load_max_paper / s**2
    j = np.clip(np.searchsorted(FK, target), 1, FK.size - 1)
    nearer = np.where(np.abs(FK[j - 1] - target) <= np.abs(FK[j] - target), j - 1, j)
    out = np.stack([s * u["band_min"], s * u["band_max"], s * (1 + e) * u["measured_mean"],
                    s * (1 + e) * u["measured_fluctuation"], s**2 * u["load_min"],
                    s**2 * FK[nearer]], axis=-1)
    return out, nearer + 2


def input_jacobian(d: Design, reading: str, h_rel=1e-4) -> np.ndarray:
    """d prediction / d input for the printed inputs p1, p2, m_L, m_C (6 x 4), at s = 1,
    e = 0; the load maximum's by its exact value (its K lag scales alike)."""
    names = ("p1", "p2", "m_L", "m_C")
    K = np.array([1000])

    def vec(dd):
        u = unit_predictions(dd, reading, K)
        return np.array([u[k] for k in DATA[:-1]] + [float(_stage_loads_exact(dd, pitch_radius_readings(
            dd.p1, dd.p2, dd.z)[reading]).max())])
    J = np.empty((len(DATA), len(names)))
    for i, n in enumerate(names):
        x = getattr(d, n)
        hi = vec(Design(**{**d.__dict__, n: x * (1 + h_rel)}))
        lo = vec(Design(**{**d.__dict__, n: x * (1 - h_rel)}))
        J[:, i] = (hi - lo) / (2 * h_rel * x)
    return J


def covariance(paper, printed_half, model_error, J, inputs_half) -> np.ndarray:
    """Covariance of the residuals: the outputs' rounding, the model error, the inputs'
    rounding propagated (see module)."""
    paper, printed_half = np.asarray(paper, float), np.asarray(printed_half, float)
    C = np.diag(printed_half**2 / 3.0 + (model_error * paper) ** 2)
    return C + J @ np.diag(np.asarray(inputs_half, float) ** 2 / 3.0) @ J.T


def chi2(pred, paper, Cinv):
    r = pred - np.asarray(paper, float)
    return np.einsum("...i,ij,...j->...", r, Cinv, r)


@dataclass(frozen=True)
class Fit:
    """One explanation's best fit and profiles (``speed``, ``stretch``: grids; ``prof_*``:
    chi^2 profiles over them, NaN where the explanation fixes the parameter)."""
    explanation: str
    reading: str
    chi2: float
    free: int
    speed: float
    stretch: float
    K: int
    pred: np.ndarray
    pull: np.ndarray
    prof_speed: np.ndarray
    prof_stretch: np.ndarray


def interval(grid, prof, level: str):
    """Ends of {x: prof(x) <= min + DCHI2[level]} (grid values; an end at the grid's end is
    open: the scan, not the data, bounds it)."""
    if not np.isfinite(prof).any():
        return math.nan, math.nan
    ok = np.flatnonzero(prof <= np.nanmin(prof) + DCHI2[level])
    return float(grid[ok[0]]), float(grid[ok[-1]])


def analyse(d: Design, paper, printed_half, inputs_half, model_error, speeds, stretches, K):
    """Every explanation of :data:`EXPLANATIONS` fitted, and every reading under the joint
    explanation.  Returns (list of explanation Fits, dict reading -> joint Fit)."""
    paper = np.asarray(paper, float)
    readings = tuple(pitch_radius_readings(d.p1, d.p2, d.z))
    units = {r: unit_predictions(d, r, K) for r in readings}
    Cinv = {r: np.linalg.inv(covariance(paper, printed_half, model_error,
                                        input_jacobian(d, r), inputs_half)) for r in readings}
    i1, i0 = int(np.argmin(np.abs(speeds - 1.0))), int(np.argmin(np.abs(stretches)))

    def fit(name, r, speed_free, stretch_free):
        s = speeds if speed_free else speeds[i1:i1 + 1]
        e = stretches if stretch_free else stretches[i0:i0 + 1]
        pred, Ks = predict(units[r], s[:, None], e[None, :], paper[-1])
        c = chi2(pred, paper, Cinv[r])
        a, b = np.unravel_index(int(np.argmin(c)), c.shape)
        nan_s, nan_e = np.full(speeds.size, np.nan), np.full(stretches.size, np.nan)
        p_s = c.min(axis=1) if speed_free else nan_s
        p_e = c.min(axis=0) if stretch_free else nan_e
        pull = (pred[a, b] - paper) / np.sqrt(np.diag(np.linalg.inv(Cinv[r])))
        return Fit(name, r, float(c[a, b]), int(speed_free) + int(stretch_free), float(s[a]),
                   float(e[b]), int(Ks[a, b]), pred[a, b], pull, p_s, p_e)

    joint = {r: fit("reading + speed + stretch", r, True, True) for r in readings}
    fits = []
    for name, allowed, sf, ef in EXPLANATIONS:
        best = min((replace(joint[r], explanation=name) if sf and ef else fit(name, r, sf, ef)
                    for r in (allowed or readings)), key=lambda f: f.chi2)
        fits.append(best)
    return fits, joint


def weights(chi2s) -> np.ndarray:
    """Relative likelihoods exp(-(chi^2 - min)/2), normalised to sum 1."""
    c = np.asarray(chi2s, float)
    w = np.exp(-(c - c.min()) / 2.0)
    return w / w.sum()


#: half a unit of the last printed digit of each paper number (14.57, 14.77, 14.6, 0.2 m/s;
#: -74.5, 209.4 N), in :data:`DATA` order [m/s, N]
PRINTED = (0.005, 0.005, 0.05, 0.05, 0.05, 0.05)


#: half a unit of the last printed digit of p1 = 8.91 mm, p2 = 7.56 mm, m_L = 1.906 g,
#: m_C = 1.296 g (Sec. 4) [m, m, kg, kg]
INPUTS_HALF = (0.005e-3, 0.005e-3, 0.0005e-3, 0.0005e-3)


def as_variables(results, errors, speeds, stretches) -> dict:
    """The fits of :func:`analyse` at each model error as dataset variables."""
    from mechrepro.units import var

    readings = list(results[0][1])
    # the declared error first, then its range's ends: an index, not a coordinate (CF
    # coordinates are monotonic)
    me, ex, rd, dm = "model_error_case", "explanation", "reading", "datum"
    fits = [[f for f in r[0]] for r in results]
    joint = [[r[1][k] for k in readings] for r in results]
    g = lambda rows, a: np.array([[getattr(f, a) for f in row] for row in rows])  # noqa: E731
    return {
        "model_error": var(me, np.asarray(errors, float), "1",
                           "relative model error: the declared value, then its range's ends"),
        "explanation": var(ex, np.arange(len(EXPLANATIONS)), "1", "explanation: " + ", ".join(
            f"{i} {e[0]}" for i, e in enumerate(EXPLANATIONS))),
        "reading": var(rd, np.arange(len(readings)), "1", "pitch-radius reading: " + ", ".join(
            f"{i} {k}" for i, k in enumerate(readings))),
        "datum": var(dm, np.arange(len(DATA)), "1", "paper number: " + ", ".join(
            f"{i} {k}" for i, k in enumerate(DATA))),
        "speed_factor": var("speed_factor", speeds, "1", "sprocket speed run / 6550 r/min (scan)"),
        "stretch": var("stretch", stretches, "1", "elongation of the tested chain (scan)"),
        "fit_reading": var((me, ex), np.array([[readings.index(f.reading) for f in r] for r in fits]),
                           "1", "best pitch-radius reading of each explanation"),
        "fit_chi2": var((me, ex), g(fits, "chi2"), "1", "chi^2 of each explanation's best fit"),
        "fit_free": var(ex, np.array([f.free for f in fits[0]]), "1",
                        "continuous parameters each explanation fits (speed, stretch)"),
        "fit_speed": var((me, ex), g(fits, "speed"), "1", "best-fit speed factor"),
        "fit_stretch": var((me, ex), g(fits, "stretch"), "1", "best-fit stretch"),
        "fit_k": var((me, ex), g(fits, "K"), "1", "profiled K of the paper's 209.4 N"),
        "fit_prediction": var((me, ex, dm), g(fits, "pred"), "1", "predicted paper numbers [m/s, N]"),
        "fit_pull": var((me, ex, dm), g(fits, "pull"), "1", "residual / its standard deviation"),
        "fit_prof_speed": var((me, ex, "speed_factor"), g(fits, "prof_speed"), "1",
                              "chi^2 profile over the speed factor (NaN: fixed)"),
        "fit_prof_stretch": var((me, ex, "stretch"), g(fits, "prof_stretch"), "1",
                                "chi^2 profile over the stretch (NaN: fixed)"),
        "joint_chi2": var((me, rd), g(joint, "chi2"), "1",
                          "chi^2 of the joint explanation (speed + stretch) per reading"),
        "joint_speed": var((me, rd), g(joint, "speed"), "1", "joint best speed factor per reading"),
        "joint_stretch": var((me, rd), g(joint, "stretch"), "1", "joint best stretch per reading"),
        "joint_prof_speed": var((me, rd, "speed_factor"), g(joint, "prof_speed"), "1",
                                "joint chi^2 profile over the speed factor per reading"),
    }


COLUMNS = ["model_error", "explanation", "reading", "free", "chi2", "p_value", "rel_likelihood",
           "speed_rpm", "speed_lo_68", "speed_hi_68", "speed_lo_95", "speed_hi_95",
           "stretch_pct", "stretch_lo_68", "stretch_hi_68", "K_209_4",
           *(f"pull_{d}" for d in DATA)]


def table(ds, rpm: float) -> list[list]:
    """Rows of ``identification.csv``: each explanation at each model error with its reading,
    chi^2, p-value, relative likelihood, speed and stretch with intervals, and pulls."""
    from scipy.stats import chi2 as chi2_dist

    readings = ds["reading"].attrs["long_name"].split(": ", 1)[1].split(", ")
    names = [e[0] for e in EXPLANATIONS]
    s, e = ds["speed_factor"].values, ds["stretch"].values
    rows = []
    for i, me in enumerate(ds["model_error"].values):
        c = ds["fit_chi2"].values[i]
        rel = np.exp(-(c - c.min()) / 2.0)
        for j, name in enumerate(names):
            free = int(ds["fit_free"].values[j])
            s68 = interval(s, ds["fit_prof_speed"].values[i, j], "68")
            s95 = interval(s, ds["fit_prof_speed"].values[i, j], "95")
            e68 = interval(e, ds["fit_prof_stretch"].values[i, j], "68")
            rows.append([float(me), name, readings[int(ds["fit_reading"].values[i, j])].split(" ", 1)[1],
                         free, float(c[j]), float(chi2_dist.sf(c[j], len(DATA) - free)), float(rel[j]),
                         rpm * float(ds["fit_speed"].values[i, j]), *(rpm * x for x in s68),
                         *(rpm * x for x in s95), 100 * float(ds["fit_stretch"].values[i, j]),
                         *(100 * x for x in e68), int(ds["fit_k"].values[i, j]),
                         *(float(x) for x in ds["fit_pull"].values[i, j])])
    return rows


READING_COLUMNS = ["model_error", "reading", "chi2", "weight", "speed_rpm", "speed_lo_68",
                   "speed_hi_68", "stretch_pct"]


def reading_table(ds, rpm: float) -> list[list]:
    """Rows of ``identification_readings.csv``: the likelihood over the readings under the joint
    explanation, normalised per model error."""
    readings = ds["reading"].attrs["long_name"].split(": ", 1)[1].split(", ")
    s = ds["speed_factor"].values
    rows = []
    for i, me in enumerate(ds["model_error"].values):
        w = weights(ds["joint_chi2"].values[i])
        for k, r in enumerate(readings):
            lo, hi = interval(s, ds["joint_prof_speed"].values[i, k], "68")
            rows.append([float(me), r.split(" ", 1)[1], float(ds["joint_chi2"].values[i, k]),
                         float(w[k]), rpm * float(ds["joint_speed"].values[i, k]), rpm * lo,
                         rpm * hi, 100 * float(ds["joint_stretch"].values[i, k])])
    return rows
