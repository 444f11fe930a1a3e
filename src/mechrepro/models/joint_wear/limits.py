"""joint_wear's load-time declarations and cost form (read by :mod:`mechrepro.limits` before any job).

``PRODUCED_BY``: the dataset parts built from the wear result (:mod:`.dataset`
``calibration_part``, ``prediction_part``, keyed on ``res["wear"]``) exist only when a
scene names ``archard_wear`` (:func:`.solver.with_wear`); a reported quantity reading them
from a scene without it is refused at load, not in validation.

:func:`work`: a run is a count of joint periods (what each solver of :mod:`.solver`
simulates, counted from the run record) times the work of one period at the run's
resolution: a quasi-static period and its samples, the compiled Radau's or scipy's
integrator steps (steps per settled period ~ rtol^-0.3, many more from a concentric
start, where impacts and rattling set the step) and output samples, local wear's reachable
bushing cells and the groove's explicit steps.  The seconds per unit are data
(config/costs.csv); memory stays typed (no run records it).
"""
from __future__ import annotations

import math

PRODUCED_BY = {v: "archard_wear" for v in (
    "k_calibrated", "K_table", "K_table_mean", "K_archard_mean", "wear_factor_calibration",
    "wear_calibration_replay", "k_mean", "wear_predicted", "wear_factor_prediction",
    "wear_report", "report_is_node")}

#: a warm solver process [MB], and bytes per sample of a quasi-static period, a dynamic
#: run's output (the compiled Radau's, scipy's) and a local-wear bushing cell
BASE_MB, _QS_B, _RADAU_B, _SCIPY_B, _LOCAL_B = 260.0, 340.0, 100.0, 400.0, 50.0
#: integrator steps per settled period at rtol 1e-5 (Radau) or 1e-6 (scipy's)
_STEPS = {"Radau": 400.0, "LSODA": 38_000, "BDF": 14_000, "RK45": 1.5e7}
_LOCAL_PATCH = math.radians(15.0)   # the widest contact patch of the scenes (assumed F)
#: steps from the concentric start (impact, rattling) over a settled period's at the same rtol
_CONCENTRIC = {"Radau": 300.0, "scipy": 2.2}


def _add(out: dict, terms: dict, times: float = 1.0) -> dict:
    for k, v in terms.items():
        out[k] = out.get(k, 0.0) + times * v
    return out


def _qs(n: int) -> dict:
    """One quasi-static period of ``n`` samples."""
    return {"qs_periods": 1.0, "qs_samples": float(n)}


def _dynamic(res: dict, start: str) -> dict:
    """One run of the dynamic joint (``periods`` periods, ``n_out`` samples each), with its
    settled start (a 4-pass quasi-static period of 720 samples)."""
    method, rtol = res.get("method", "Radau"), float(res.get("rtol", 1e-5))
    periods = int(res.get("periods", 1))
    concentric = start == "concentric"
    if method == "Radau":
        steps = _STEPS["Radau"] * ((1e-5 / rtol) ** 0.3 if rtol <= 1e-5 else (rtol / 1e-5) ** 1.36)
        steps *= periods * (_CONCENTRIC["Radau"] if concentric else 1.0)
    else:
        steps = _STEPS[method] * (1e-6 / rtol) ** 0.3 * periods * (_CONCENTRIC["scipy"] if concentric else 1.0)
        steps = min(steps, int(res["max_steps"])) if res.get("max_steps") else steps
    out = {f"{method}_steps": steps, "dynamic_samples": float(periods * int(res["n_out"]))}
    return out if concentric else _add(out, _qs(720), 2)


def _dynamic_mb(res: dict) -> float:
    per = _RADAU_B if res.get("method", "Radau") == "Radau" else _SCIPY_B
    return per * int(res.get("periods", 1)) * int(res.get("n_out", 720)) / 1e6


def _wear_periods(run: dict, interval_h: float, sides: int, update: bool) -> int:
    """Periods the interval method solves: per side the calibration (one per measured
    interval) and the prediction (one per interval, or one for a frozen bushing)."""
    p = run["parameters"]
    n_cal = len(p["measured_wear_B1"])
    t0 = float(p["measurement_interval"]) * n_cal / 3600.0
    n_int = math.ceil((float(p["prediction_end"]) / 3600.0 - t0) / interval_h - 1e-9)
    return sides * (n_cal + (max(n_int, 1) if update else 1))


def _work(run: dict) -> tuple[dict, float]:
    """(work terms of one ``compute(run)``, extra MB above the process)."""
    res, opt, eff = run["resolution"], run.get("options", {}), run["effects"]
    n, solver = int(res.get("n_steps", 720)), run["solver"]
    interval = float(res.get("interval_h", 2.0))
    worn = _wear_periods(run, interval, 2 if "unbalanced_load" in eff else 1,
                         "wear_update" in eff) if "archard_wear" in eff else 0
    qs, qs_mb, n_cal = _qs(n), _QS_B * n / 1e6, len(run["parameters"]["measured_wear_B1"])
    if solver in ("clearance_implicit", "clearance_explicit"):
        return _add({}, _dynamic(res, opt.get("start", "equilibrium")), 1 + worn), _dynamic_mb(res)
    if solver == "continuous_contact":
        return _add({}, qs, 1 + worn), qs_mb
    if solver == "period_by_period":
        return _add({}, qs, 1 + int(opt.get("period_by_period_sample", 300))), qs_mb
    if solver == "coefficient_scan":
        points = len(opt.get("scan_load_direction_deg", [])) * len(opt.get("scan_gravity", []))
        return _add({}, qs, points * (1 + 2 * n_cal)), qs_mb
    if solver == "load_point_fit":
        planes = len(opt.get("fit_gravity", []))
        grid = len(opt.get("fit_load_direction_deg", [])) * planes * 2 * n_cal
        # each zero of the misfit (~4 per gravity plane): secant steps, the estimate, its
        # period and the 86-h wear of both sides at it and +- its uncertainty
        per_zero = ((int(opt.get("fit_secant_steps", 3)) + 1) * 2 * n_cal + 1
                    + 3 * _wear_periods(run, interval, 2, True))
        return _add({}, qs, grid + 4 * planes * per_zero), qs_mb
    if solver == "load_point_posterior":
        nodes = (len(opt.get("posterior_distance", [])) * len(opt.get("posterior_friction", []))
                 * int(res.get("n_gravity", 1)))
        grid = len(opt.get("fit_load_direction_deg", []))
        # each node: ~4 zeros, each with its secant steps (Brent's where they stall), a
        # quasi-static period and, where credible, the 86-h wear; the dynamic joint once, at
        # the credible point of the smallest margin (~10x a settled run's steps near the rule)
        per_zero = ((int(opt.get("fit_secant_steps", 3)) + 2) * 2 * n_cal + 2
                    + _wear_periods(run, interval, 2, True))
        out = _add({}, qs, nodes * (grid + 4 * per_zero))
        return (_add(out, _dynamic(res, opt.get("start", "equilibrium")), 10),
                max(qs_mb, _dynamic_mb(res)))
    if solver == "local_wear":
        periods = 1 + _wear_periods(run, interval, 1, True)
        n_theta = int(res.get("n_theta", 720))
        cells = n * min(n_theta, n_theta * _LOCAL_PATCH / (2 * math.pi) + 5)
        # the groove: ~8 000 explicit steps at groove_step 4, each per sample and angle
        groove = 8000.0 * 4.0 / float(res.get("groove_step", 4.0)) \
            * int(res.get("groove_samples", 24)) * n_theta
        return (_add({"local_cells": periods * cells, "groove_cells": groove}, qs, 4 * periods),
                max(qs_mb, _LOCAL_B * cells / 1e6))
    if solver == "constant_sensitivity":
        rows = 1 + 2 * len(opt.get("sensitivity", {}))
        dyn = _dynamic({"method": "Radau", "rtol": res.get("rtol", 1e-6), "n_out": n}, "equilibrium")
        return _add(_add({}, qs, rows * (1 + _wear_periods(run, interval, 1, True))), dyn, rows), qs_mb
    return qs, qs_mb     # a solver added later: one quasi-static period


def work(run: dict) -> dict:
    """The work terms of one ``compute(run)`` (module docstring), with a term per run."""
    return {"run": 1.0, **_work(run)[0]}


def mem_mb(run: dict) -> float:
    """Peak memory [MB] of one run in a warm solve process."""
    return BASE_MB + _work(run)[1]
