"""joint_wear's load-time declarations and cost (read by :mod:`mechrepro.limits` before any job).

``PRODUCED_BY``: the dataset parts built from the wear result (:mod:`.dataset`
``calibration_part``, ``prediction_part``, keyed on ``res["wear"]``) exist only when a
scene names ``archard_wear`` (:func:`.solver.with_wear`); a reported quantity reading them
from a scene without it is refused at load, not in validation.

:func:`cost`: a run is a count of joint periods (what each solver of :mod:`.solver`
simulates, counted from the run record) times the cost of one period at the run's
resolution.  Measured on the 2-core VM shared with other agents (load 8-14), CPU seconds
of ``compute(run)`` in one warm process, every run of the ci and default profiles
(``/proc`` peak memory of fresh processes for the memory terms):

- quasi-static period, ``n_steps`` samples: 3.5-4.7 ms at 360-720 (coefficient_scan,
  load_point_fit, the wear runs), 0.27, 0.94, 3.6 s at 65 536, 262 144, 1e6 samples and
  +340 B per sample (555 MB peak at 1e6);
- compiled Radau, settled start: 398, 740, 1329, 2872, 9720, 17 504, 29 466, 50 915 steps
  per period at rtol 1e-5 ... 1e-12 (~ rtol^-0.3), 9197 at 1e-4 (Newton failures in the
  contact), ~3.1 us per step; the concentric start (impact, rattling) at 1e-7: 1.2 s;
- scipy's integrators (per step, steps per period): LSODA 45 us, 38 204 settled at 1e-6 and
  161 857 from the concentric start at 1e-7; BDF 0.5 ms, 13 855 at 1e-6; RK45 0.21 ms,
  ~1.5e7 steps for a period of the stiff contact (20 000 reach 8.2 ms of 6.25 s), so a run
  without a step budget is refused by time; their dense output ~50 us and ~400 B per
  output sample (LSODA at 2e5 samples: 17.7 s, 300 MB), the compiled Radau's ~100 B;
- local wear (``n_theta`` bushing angles): ~0.13 us and ~50 B per sample and bushing cell
  its contact patch can reach (the patch, <= ~15 deg, and 2 cells either side: 35 of 720;
  n_theta 8192 at 360 samples: 16 ms, 5.4 MB; before issue #35 every cell: 12.7 s, 340 MB);
- a warm solver process (interpreter, numpy, scipy, numba, xarray) peaks at 220-260 MB.

The times are upper readings: the default runs took 75.6 s of CPU here, 19.1 s of wall
time on the idle machine (README).  Measured over estimated (:func:`solve_seconds`), every
run of both profiles (105 ci, 125 default): CPU 0.81-9.3, median 0.94 (ci) and 0.98
(default); the sums 42.7 s against 41.7 s (ci), 75.6 s against 74.6 s (default).  Above
3 (before issue 58): the dynamic joint at the load points estimated from Tables 3-4 and
their variants (2.5-9x the assumed point's Radau steps), and 50-52 for the former
no-gravity rival there, whose contact rattled (110 000 steps where the assumed point
takes 740 per period) -- nothing in a run record announces that; load_point_posterior solves
the dynamic joint only where the quasi-static margin keeps the contact rule.  Wall time over the estimate at that load
(wall ~2-3x CPU): 0.9-19, those two 105-265; on the idle machine ~4x less.
:data:`SPREAD` is the band a run's measured compute wall time keeps around its estimate,
from an idle machine to this load.
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

#: a warm solver process [MB]; a solve job's start [s]: interpreter, imports (1.2 s CPU)
#: and the cached kernels (0.7 s) -- a fresh clone's first jobs compile them, ~23 s of CPU
#: here (Radau 17 s), once
BASE_MB = 260.0
JOB_START_S = 2.0

_QS_S, _QS_PER_SAMPLE_S, _QS_B = 3.0e-3, 3.5e-6, 340.0
_RADAU_STEP_S, _RADAU_B = 3.1e-6, 100.0
# scipy's integrators: (seconds per step, steps per settled period at rtol 1e-6)
_SCIPY = {"LSODA": (45e-6, 38_000), "BDF": (5e-4, 14_000), "RK45": (2.1e-4, 1.5e7),
          "RK23": (2.1e-4, 1.5e7), "DOP853": (2.1e-4, 1.5e7)}
_SCIPY_SAMPLE_S, _SCIPY_B = 50e-6, 400.0
_LOCAL_CELL_S, _LOCAL_B, _GROOVE_CELL_S = 0.13e-6, 50.0, 0.65e-6
_LOCAL_PATCH = math.radians(15.0)   # the widest contact patch of the scenes (assumed F)
#: steps from the concentric start (impact, rattling) over a settled period's at the same
#: rtol: compiled Radau at 1e-7 (1.2 s: ~390 000 steps against 1329), LSODA (161 857
#: against ~76 000)
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
        # each zero of the misfit (measured: 4 per gravity plane): secant steps, the
        # estimate, its period and the 86-h wear of both sides at it and +- its uncertainty
        per_zero = ((int(opt.get("fit_secant_steps", 3)) + 1) * 2 * n_cal + 1
                    + 3 * _wear_periods(run, interval, 2, True))
        return _qs(n) * (grid + 4 * planes * per_zero), qs_mb
    if solver == "load_point_posterior":
        nodes = (len(opt.get("posterior_distance", [])) * len(opt.get("posterior_friction", []))
                 * int(res.get("n_gravity", 1)))
        grid = len(opt.get("fit_load_direction_deg", [])) * 2 * n_cal
        # each node: ~4 zeros, each with its secant steps (Brent's where they stall, ~20 more
        # misfits near contact loss), a quasi-static period, and, where credible, the 86-h
        # wear; the dynamic joint once, at the credible point of the smallest margin
        # (measured: 9 000-62 000 Radau steps for four periods at rtol 1e-7 near the rule)
        per_zero = ((int(opt.get("fit_secant_steps", 3)) + 2) * 2 * n_cal + 2
                    + _wear_periods(run, interval, 2, True)) * _qs(n)
        dyn = 10.0 * _dynamic(res, opt.get("start", "equilibrium"))
        return nodes * (_qs(n) * grid / (2 * n_cal) + 4 * per_zero) + dyn, max(qs_mb, _dynamic_mb(res))
    if solver == "local_wear":
        periods = 1 + _wear_periods(run, interval, 1, True)
        n_theta = int(res.get("n_theta", 720))
        cells = n * min(n_theta, n_theta * _LOCAL_PATCH / (2 * math.pi) + 5)
        # the groove: ~8 000 explicit steps at groove_step 4 (2 100 at the assumed F, 11 400
        # at the estimated one), each ~0.65 us per sample and angle (measured, 24 x 180)
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
