"""The tensioning design map: where to roll (r_c) and how hard (A of Eq. 4) for the highest
critical speed under a buckling margin, A <= A_cr / m.  The rolled stress is linear in A, so
one [K^(sigma)] per r_c gives every a = A / A_0; per harmonic n, omega~^2 (Eq. 5) and
Omega_c = 1 / sqrt(mu_max) of (n^2 M - K^(c)) phi = mu (K + a K^(sigma)) phi come from one
symmetric eigen-decomposition per (r_c, a, n) in the basis M = L L^T.  Also the groupings of
runs by flange radius that the figures, the rows and the notebook read.
"""
from __future__ import annotations

import numpy as np

from mechrepro.errors import Refusal
from mechrepro.units import from_si

#: what binds at an optimum (stored as this code)
BINDS = ("untensioned", "buckling margin", "interior", "scan cap")


def pencils(K, Kr, M, Kc, n_d):
    """Per harmonic n: (n, K, K^(sigma), n^2 M - K^(c)) in the basis M = L L^T."""
    out = []
    for n in n_d:
        Li = np.linalg.inv(np.linalg.cholesky(M[n]))
        out.append((int(n), Li @ K[n] @ Li.T, Li @ Kr[n] @ Li.T,
                    n * n * np.eye(len(Li)) - Li @ Kc[n] @ Li.T))
    return out


def speeds(pencil, factors):
    """(Omega_c, lowest omega~^2 at rest) of one ``pencil`` per load factor (NaN: buckled)."""
    n, Kw, Krw, Bw = pencil
    a = np.atleast_1d(np.asarray(factors, float))
    d, V = np.linalg.eigh(Kw[None] + a[:, None, None] * Krw[None])
    ok = d[:, 0] > 0
    if n == 0:
        return np.where(ok, np.inf, np.nan), d[:, 0]
    s = 1.0 / np.sqrt(np.where(d > 0, d, 1.0))
    C = np.swapaxes(V, 1, 2) @ Bw @ V * s[:, :, None] * s[:, None, :]
    mu = np.linalg.eigvalsh(C)[:, -1]
    omega_c = np.where(mu > 0, 1.0 / np.sqrt(np.where(mu > 0, mu, 1.0)), np.inf)
    return np.where(ok, omega_c, np.nan), d[:, 0]


def lowest(pencils_, factors, n_min=2):
    """(lowest Omega_c over N_d >= ``n_min``, its N_d, Omega_c and omega~^2 per N_d)."""
    n_d = np.array([p[0] for p in pencils_])
    cs, w2 = zip(*(speeds(p, factors) for p in pencils_))
    cs, w2 = np.stack(cs, -1), np.stack(w2, -1)
    low = lowest_over(cs, n_d, n_min)
    sel = n_d >= n_min
    k = np.argmin(np.where(np.isnan(cs[..., sel]), np.inf, cs[..., sel]), axis=-1)
    return low, np.where(np.isnan(low), -1, n_d[sel][k]), cs, w2


def lowest_over(cs, n_d, n_min=0):
    """min over N_d >= ``n_min`` of cs[..., N_d]; NaN where any harmonic has buckled."""
    sel = np.asarray(n_d) >= n_min
    low = np.min(np.where(np.isnan(cs[..., sel]), np.inf, cs[..., sel]), axis=-1)
    return np.where(np.isnan(cs).any(axis=-1), np.nan, low)


def optimum(fn, grid, vals, *, capped, xatol=1e-4):
    """(a*, value, binds) maximising ``fn`` (load factor -> lowest Omega_c) over the ``grid``
    where it is ``vals``, refined between the best point's neighbours (binds: :data:`BINDS`)."""
    from scipy.optimize import minimize_scalar

    vals = np.where(np.isnan(vals), -np.inf, vals)
    k = int(np.argmax(vals))
    if k == len(grid) - 1:
        return float(grid[k]), float(vals[k]), BINDS.index("scan cap" if capped else "buckling margin")
    if k == 0:
        return 0.0, float(vals[0]), BINDS.index("untensioned")
    res = minimize_scalar(lambda a: -fn(a), bounds=(grid[k - 1], grid[k + 1]), method="bounded",
                          options={"xatol": xatol * grid[-1]})
    if -res.fun > vals[k]:
        return float(res.x), -float(res.fun), BINDS.index("interior")
    return float(grid[k]), float(vals[k]), BINDS.index("interior")


RPM = 60.0 / (2 * np.pi)
COLUMNS = ["r_f_mm", "rim_temperature_rise_degc", "buckling_margin", "stated", "r_c_opt_mm",
           "r_c_step_mm", "amplitude_opt_degc", "intensity_vs_paper", "binds", "lowest_mode_nd", "critical_speed_opt_rpm",
           "untensioned_rpm", "gain_vs_untensioned", "paper_rc65_a50_rpm", "gain_vs_paper",
           "best_at_rc65_rpm", "buckling_amplitude_at_opt_degc", "buckling_mode_at_opt_nd",
           "f_ratio_nd0", "f_ratio_nd1"]


def best(ds, q):
    """(index of the r_c of the best lowest critical speed at margin ``q``, that speed)."""
    v = np.asarray(ds["design_best_speed"].values[q], float)
    if np.isnan(v).all():
        return -1, float("nan")
    k = int(np.nanargmax(v))
    return k, float(v[k])


def table(runs, paper_rc=0.065, paper_amplitude=50.0) -> list[list]:
    """The design table of ``runs`` [(r_f [mm], design_map dataset)]: per flange radius and
    margin the optimum, what binds, its gains on the untensioned disk and on the paper's point."""
    rows = []
    for rf, ds in runs:
        rc = ds["r_c"].values
        stated = float(ds["design_stated_margin"])
        j65 = int(np.argmin(np.abs(rc - paper_rc)))
        if abs(rc[j65] - paper_rc) > 1e-9:
            raise Refusal(f"the design map's r_c grid has no {paper_rc * 1e3:g} mm")
        unt = float(lowest_map(ds)[0, 0])         # A = 0: the same at every r_c
        at65 = float(ds["design_paper_amplitude_speed"].values[j65])
        step = float(np.diff(rc).max() * 1e3) if len(rc) > 1 else float("nan")
        for q, m in enumerate(ds["design_margin"].values):
            k, v = best(ds, q)
            head = [rf, float(ds["design_rim_temperature_rise"]), float(m),
                    bool(abs(m - stated) < 1e-12)]
            if k < 0:       # every r_c buckled: no optimum, no number
                rows.append(head + [float("nan"), step, float("nan"), float("nan"), "buckled", -1]
                            + [float("nan")] * 6 + [-1, float("nan"), float("nan")])
                continue
            a = float(ds["design_best_amplitude"].values[q, k])
            fr = ds["design_best_frequency_ratio"].values[q, k]
            rows.append(head + [
                float(rc[k] * 1e3), step, a, a / paper_amplitude,
                BINDS[int(ds["design_best_binds"].values[q, k])],
                int(ds["design_best_mode"].values[q, k]),
                v * RPM, unt * RPM, v / unt - 1, at65 * RPM, v / at65 - 1,
                float(ds["design_best_speed"].values[q, j65]) * RPM,
                float(ds["design_buckling_amplitude"].values[k]),
                int(ds["design_buckling_mode"].values[k]), float(fr[0]), float(fr[1])])
    return rows


def map_table(R) -> tuple[list, list]:
    """Table ``design_map``: :func:`table` of every flange radius of the map, then of the blade
    in the cut (rim hotter)."""
    cut = R.run("design_map_in_cut")
    return COLUMNS, table(by_clamp(R, "design_map", "design_map_rf") + [(clamp_mm(cut), cut)])


def lowest_map(ds) -> np.ndarray:
    """The lowest critical speed over N_d >= 2 [rad/s], (r_c, design_step); NaN: buckled."""
    return lowest_over(np.asarray(ds["design_critical_speed"].values, float),
                       ds["n_d"].values, 2)


def lowest_critical_speed(ds) -> np.ndarray:
    """The lowest critical speed over N_d of each r_c [rad/s] of a critical-speed run; NaN:
    buckled."""
    return lowest_over(np.asarray(ds["critical_speed"].values, float), ds["n_d"].values)


def clamp_mm(ds) -> float:
    """r_f [mm] of a run."""
    return float(from_si(float(ds["clamp_radius"]), "mm"))


def by_clamp(R, scene, study) -> list:
    """[(r_f [mm], dataset)] of ``scene`` and of the runs of its r_f ``study``."""
    return [(clamp_mm(ds), ds) for ds in [R.run(scene), *R.study_runs(study)]]


def rc_grid(R) -> dict:
    """{r_f [mm]: dataset} of Figs. 6 and 8: scene ``rc_grid`` and study ``fig06``."""
    return {int(round(rf)): ds for rf, ds in by_clamp(R, "rc_grid", "fig06")}


def eigen_and_eq9_times(*runs) -> tuple[float, float]:
    """Wall time [s] of Eq. (5) and of Eq. (9) over ``runs`` (the same K^(sigma))."""
    return tuple(sum(float(ds[k]) for ds in runs) for k in ("time_eigen", "time_eq9"))
