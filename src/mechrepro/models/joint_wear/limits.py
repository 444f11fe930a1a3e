"""joint_wear's load-time declarations and cost form (read by :mod:`mechrepro.limits` before any job).

``PRODUCED_BY``: the dataset parts built from the wear result (:mod:`.dataset`
``calibration_part``, ``prediction_part``, keyed on ``res["wear"]``) exist only when a
scene names ``archard_wear`` (:func:`.solver.with_wear`); a reported quantity reading them
from a scene without it is refused at load, not in validation.

:func:`work`: a run is a count of joint periods (what each solver of :mod:`.solver`
simulates, counted from the run record) times the work of one period at the run's
resolution: a quasi-static period's samples, a dynamic period's integrator steps per
integrator and start (:func:`_dynamic`) and its output samples, local wear's reachable
bushing cells and the groove's explicit steps.  The seconds per unit are data (config/costs.csv); memory
stays typed (no run records it).
"""
from __future__ import annotations

import math
from collections import Counter

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


def _qs(n: int, times: float = 1.0) -> Counter:
    """``times`` quasi-static periods of ``n`` samples (a period's setup costs as much as
    ~360 samples: the form stays linear in n and one run fixes it)."""
    return Counter({"qs_samples": times * (n + 360)})


def _dynamic(res: dict, start: str, times: float = 1.0) -> Counter:
    """``times`` runs of the dynamic joint: its integrator's steps (per settled period at
    rtol 1e-5 (Radau) or 1e-6 (the others), ~ rtol^-0.25, but ~ rtol^1.15 for the Radau
    above 1e-5, where the contact rattles; at most ``max_steps``; a concentric start,
    which impacts and rattles, a term of its own), its output samples and its settled
    start (a 4-pass quasi-static period of 720 samples)."""
    method, rtol = res.get("method", "Radau"), float(res.get("rtol", 1e-5))
    ref, periods = (1e-5 if method == "Radau" else 1e-6), times * int(res.get("periods", 1))
    rattles = method == "Radau" and rtol > ref
    steps = _STEPS[method] * periods * ((rtol / ref) ** 1.15 if rattles else (ref / rtol) ** 0.25)
    out = Counter({f"{method} {start} steps": min(steps, float(res.get("max_steps") or math.inf)),
                   "dynamic_samples": periods * int(res["n_out"])})
    return out if start == "concentric" else out + _qs(720, 2 * times)


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
    # a rival's closed-form growth replaces the interval method's periods
    worn = _wear_periods(run, interval, 2 if "unbalanced_load" in eff else 1, "wear_update" in eff) \
        if "archard_wear" in eff and "closed_form_growth" not in opt else 0
    qs_mb, n_cal = _QS_B * n / 1e6, len(run["parameters"]["measured_wear_B1"])
    if solver in ("clearance_implicit", "clearance_explicit"):
        return _dynamic(res, opt.get("start", "equilibrium"), 1 + worn), _dynamic_mb(res)
    if solver == "continuous_contact":   # the interval method's limit: its own term
        return _qs(n, 1 + worn) + Counter(interval_limit=float(bool(opt.get("interval_limit")))), qs_mb
    if solver == "period_by_period":
        return _qs(n, 1 + int(opt.get("period_by_period_sample", 300))), qs_mb
    if solver == "coefficient_scan":
        points = len(opt.get("scan_load_direction_deg", [])) * len(opt.get("scan_gravity", []))
        return _qs(n, points * (1 + 2 * n_cal)), qs_mb
    if solver == "load_point_fit":
        planes = len(opt.get("fit_gravity", []))
        grid = len(opt.get("fit_load_direction_deg", [])) * planes * 2 * n_cal
        # each zero of the misfit (~4 per gravity plane): secant steps, the estimate, its
        # period and the 86-h wear of both sides at it and +- its uncertainty
        per_zero = ((int(opt.get("fit_secant_steps", 3)) + 1) * 2 * n_cal + 1
                    + 3 * _wear_periods(run, interval, 2, True))
        return _qs(n, grid + 4 * planes * per_zero), qs_mb
    if solver == "load_point_posterior":
        nodes = (len(opt.get("posterior_distance", [])) * len(opt.get("posterior_friction", []))
                 * int(res.get("n_gravity", 1)))
        grid = len(opt.get("fit_load_direction_deg", []))
        # each node: ~4 zeros, each with its secant steps (Brent's where they stall), a
        # quasi-static period and, where credible, the 86-h wear; the dynamic joint once, at
        # the credible point of the smallest margin
        per_zero = ((int(opt.get("fit_secant_steps", 3)) + 2) * 2 * n_cal + 2
                    + _wear_periods(run, interval, 2, True))
        return (_qs(n, nodes * (grid + 4 * per_zero)) + _dynamic(res, opt.get("start", "equilibrium")),
                max(qs_mb, _dynamic_mb(res)))
    if solver == "local_wear":
        periods = 1 + _wear_periods(run, interval, 1, True)
        n_theta = int(res.get("n_theta", 720))
        cells = n * min(n_theta, n_theta * _LOCAL_PATCH / (2 * math.pi) + 5)
        # the groove: explicit steps ~ 1 / groove_step, each per sample, angle and placement
        groove = int(res.get("groove_samples", 24)) * n_theta / float(res.get("groove_step", 4.0)) \
            * len(opt.get("local_placements", [0]))
        return (_qs(n, 4 * periods) + Counter(local_cells=periods * cells, groove_cells=groove),
                max(qs_mb, _LOCAL_B * cells / 1e6))
    if solver == "constant_sensitivity":
        rows = 1 + 2 * len(opt.get("sensitivity", {}))
        dyn = _dynamic({"method": "Radau", "rtol": res.get("rtol", 1e-6), "n_out": n}, "equilibrium", rows)
        return _qs(n, rows * (1 + _wear_periods(run, interval, 1, True))) + dyn, qs_mb
    return _qs(n), qs_mb     # a solver added later: one quasi-static period


def work(run: dict) -> dict:
    """The work terms of one ``compute(run)`` (module docstring), with a term per run."""
    return {"run": 1.0, **_work(run)[0]}


def mem_mb(run: dict) -> float:
    """Peak memory [MB] of one run in a warm solve process."""
    return BASE_MB + _work(run)[1]
