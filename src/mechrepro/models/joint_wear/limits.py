"""joint_wear's load-time declarations and cost (read by :mod:`mechrepro.limits` before any job).

``PRODUCED_BY``: the dataset parts built from the wear result (:mod:`.dataset`
``calibration_part``, ``prediction_part``, keyed on ``res["wear"]``) exist only when a
scene names ``archard_wear`` (:func:`.solver.with_wear`); a reported quantity reading them
from a scene without it is refused at load, not in validation.

:func:`cost`: a run is a count of joint periods (what each solver of :mod:`.solver`
simulates, counted from the run record) times the cost of one period at the run's
resolution.  The coefficients are CPU seconds and bytes of ``compute(run)`` in one warm
process, measured on a loaded 2-core machine (upper readings): a quasi-static period per
sample, the compiled Radau per step (steps per period ~ rtol^-0.3), scipy's integrators
per step and per output sample, local wear per sample and reachable bushing cell.
:data:`SPREAD` is the band a run's measured compute wall time keeps around its estimate,
from an idle machine to a loaded one.
"""
from __future__ import annotations

import math

PRODUCED_BY = {v: "archard_wear" for v in (
    "k_calibrated", "K_table", "K_table_mean", "K_archard_mean", "wear_factor_calibration",
    "wear_calibration_replay", "k_mean", "wear_predicted", "wear_factor_prediction",
    "wear_report", "report_is_node")}

#: a run's measured compute wall time over :func:`solve_seconds`, idle machine to this
#: load (module docstring): what the estimate promises, and what tests/test_inputs.py checks
SPREAD = (0.1, 300.0)

#: a warm solver process [MB]; a solve job's start [s]: interpreter, imports and the
#: cached kernels
BASE_MB = 260.0
JOB_START_S = 2.0

_QS_S, _QS_PER_SAMPLE_S, _QS_B = 3.0e-3, 3.5e-6, 340.0
_RADAU_STEP_S, _RADAU_B = 3.1e-6, 100.0
# scipy's integrators: (seconds per step, steps per settled period at rtol 1e-6)
_SCIPY = {"LSODA": (45e-6, 38_000), "BDF": (5e-4, 14_000), "RK45": (2.1e-4, 1.5e7)}
_SCIPY_SAMPLE_S, _SCIPY_B = 50e-6, 400.0
_LOCAL_CELL_S, _LOCAL_B, _GROOVE_CELL_S = 0.13e-6, 50.0, 0.65e-6
_LOCAL_PATCH = math.radians(15.0)   # the widest contact patch of the scenes (assumed F)
#: steps from the concentric start (impact, rattling) over a settled period's at the same rtol
_CONCENTRIC = {"Radau": 300.0, "scipy": 2.2}


def _qs(n: int) -> float:
    """One quasi-static period [s] (module docstring)."""
    return _QS_S + _QS_PER_SAMPLE_S * n


def _dynamic(res: dict, start: str) -> float:
    """One run of the dynamic joint (``periods`` periods, ``n_out`` samples each) [s],
    with its settled start (a 4-pass quasi-static period of 720 samples)."""
    method, rtol = res.get("method", "Radau"), float(res.get("rtol", 1e-5))
    periods, samples = int(res.get("periods", 1)), int(res.get("periods", 1)) * int(res["n_out"])
    concentric = start == "concentric"
    if method == "Radau":
        steps = 400.0 * (1e-5 / rtol) ** 0.3 if rtol <= 1e-5 else 400.0 * (rtol / 1e-5) ** 1.36
        steps *= periods * (_CONCENTRIC["Radau"] if concentric else 1.0)
        seconds = _RADAU_STEP_S * steps + 1e-6 * samples
    else:
        per_step, steps = _SCIPY[method]
        steps *= (1e-6 / rtol) ** 0.3 * periods * (_CONCENTRIC["scipy"] if concentric else 1.0)
        if res.get("max_steps"):
            steps = min(steps, int(res["max_steps"]))
        seconds = per_step * steps + _SCIPY_SAMPLE_S * samples
    return seconds + (0.0 if concentric else 2 * _qs(720))


def _dynamic_mb(res: dict) -> float:
    samples = int(res.get("periods", 1)) * int(res.get("n_out", 720))
    per = _RADAU_B if res.get("method", "Radau") == "Radau" else _SCIPY_B
    return per * samples / 1e6


def _wear_periods(run: dict, interval_h: float, sides: int, update: bool) -> int:
    """Periods the interval method solves: per side the calibration (one per measured
    interval) and the prediction (one per interval, or one for a frozen bushing)."""
    p = run["parameters"]
    n_cal = len(p["measured_wear_B1"])
    t0 = float(p["measurement_interval"]) * n_cal / 3600.0
    n_int = math.ceil((float(p["prediction_end"]) / 3600.0 - t0) / interval_h - 1e-9)
    return sides * (n_cal + (max(n_int, 1) if update else 1))


def _solve_seconds(run: dict) -> tuple[float, float]:
    """(seconds of one ``compute(run)``, extra MB above the process)."""
    res, opt, eff = run["resolution"], run.get("options", {}), run["effects"]
    n, solver = int(res.get("n_steps", 720)), run["solver"]
    interval = float(res.get("interval_h", 2.0))
    wear = "archard_wear" in eff
    worn = _wear_periods(run, interval, 2 if "unbalanced_load" in eff else 1,
                         "wear_update" in eff) if wear else 0
    qs_mb = _QS_B * n / 1e6
    if solver in ("clearance_implicit", "clearance_explicit"):
        one = _dynamic(res, opt.get("start", "equilibrium"))
        return one * (1 + worn), _dynamic_mb(res)
    if solver == "continuous_contact":
        return _qs(n) * (1 + worn), qs_mb
    if solver == "period_by_period":
        return _qs(n) * (1 + int(opt.get("period_by_period_sample", 300))), qs_mb
    n_cal = len(run["parameters"]["measured_wear_B1"])
    if solver == "coefficient_scan":
        points = len(opt.get("scan_load_direction_deg", [])) * len(opt.get("scan_gravity", []))
        return _qs(n) * points * (1 + 2 * n_cal), qs_mb
    if solver == "load_point_fit":
        planes = len(opt.get("fit_gravity", []))
        grid = len(opt.get("fit_load_direction_deg", [])) * planes * 2 * n_cal
        # each zero of the misfit (~4 per gravity plane): secant steps, the estimate, its
        # period and the 86-h wear of both sides at it and +- its uncertainty
        per_zero = ((int(opt.get("fit_secant_steps", 3)) + 1) * 2 * n_cal + 1
                    + 3 * _wear_periods(run, interval, 2, True))
        return _qs(n) * (grid + 4 * planes * per_zero), qs_mb
    if solver == "load_point_posterior":
        nodes = (len(opt.get("posterior_distance", [])) * len(opt.get("posterior_friction", []))
                 * int(res.get("n_gravity", 1)))
        grid = len(opt.get("fit_load_direction_deg", [])) * 2 * n_cal
        # each node: ~4 zeros, each with its secant steps (Brent's where they stall), a
        # quasi-static period and, where credible, the 86-h wear; the dynamic joint once, at
        # the credible point of the smallest margin (~10x a settled run's steps near the rule)
        per_zero = ((int(opt.get("fit_secant_steps", 3)) + 2) * 2 * n_cal + 2
                    + _wear_periods(run, interval, 2, True)) * _qs(n)
        dyn = 10.0 * _dynamic(res, opt.get("start", "equilibrium"))
        return nodes * (_qs(n) * grid / (2 * n_cal) + 4 * per_zero) + dyn, max(qs_mb, _dynamic_mb(res))
    if solver == "local_wear":
        periods = 1 + _wear_periods(run, interval, 1, True)
        n_theta = int(res.get("n_theta", 720))
        cells = n * min(n_theta, n_theta * _LOCAL_PATCH / (2 * math.pi) + 5)
        # the groove: ~8 000 explicit steps at groove_step 4, each per sample and angle
        steps = 8000.0 * 4.0 / float(res.get("groove_step", 4.0))
        groove = steps * _GROOVE_CELL_S * int(res.get("groove_samples", 24)) * n_theta
        return (periods * (4 * _qs(n) + _LOCAL_CELL_S * cells) + groove,
                max(qs_mb, _LOCAL_B * cells / 1e6))
    if solver == "constant_sensitivity":
        rows = 1 + 2 * len(opt.get("sensitivity", {}))
        dyn = _dynamic({"method": "Radau", "rtol": res.get("rtol", 1e-6), "n_out": n},
                       "equilibrium")
        return rows * (_qs(n) * (1 + _wear_periods(run, interval, 1, True)) + dyn), qs_mb
    return _qs(n), qs_mb     # a solver added later: no fit yet, one quasi-static period


def cost(run: dict) -> dict:
    """Expected peak memory (MB) and time (s) of one run in a warm solve process (module
    docstring; a job adds :data:`JOB_START_S` once): its compute, repeated for the
    rounds of a ``marginal_cost:`` scene's alternated timing, at least the 20 ms a fast
    solve is repeated for, plus packing and writing (~0.05 s)."""
    seconds, extra_mb = _solve_seconds(run)
    if run.get("target"):   # mechrepro.target refines its knob level by level: ~8 doublings
        knob, res = run["target"]["knob"], run["resolution"]
        levels = [_solve_seconds({**run, "resolution": {**res, knob: res[knob] * 2 ** k}})
                  for k in range(8)]
        seconds, extra_mb = sum(s for s, _ in levels), levels[-1][1]
    rounds = int(run.get("timing_repeat", 1))
    return {"mem_mb": BASE_MB + extra_mb, "seconds": rounds * max(seconds, 0.02) + 0.05}


def solve_seconds(run: dict) -> float:
    """The expected time of one ``compute(run)`` [s] (what a run's ``wall_time`` measures)."""
    return _solve_seconds(run)[0]
