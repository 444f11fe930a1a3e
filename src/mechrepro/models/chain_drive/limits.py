"""chain_drive's declared cost (read by :mod:`mechrepro.limits` before any job, which also
solves the longest jobs' papers last and refuses a job above its rule's budget).

The work of a run follows from its resolution and parameters without solving anything
(:func:`size`): the FD grid (points per pitch x span length), the step (cfl x the von Neumann
limit dx/sqrt(c_w^2 - c^2) at the static tension P = T_s + k c^2; the dynamic tension
shortens it further, by a factor the fit absorbs), the speeds and

- a march (Figs. 5, 8, accuracy studies): S speeds x (n + 1) points x the steps of settling
  + window; its memory is the (time, speed) excitation arrays the effects fill;
- shooting (Figs. 6, 7, 9): per speed one march of 2n + 1 lanes over one tooth period
  (N steps) plus the monodromy's bounds / eigenvalues (~ (2n)^3), at about
  :data:`SHOOTING_REFINE` x the initial speeds (the adaptive bisection of edges and peaks);
- the discrete span (Fig. 7): speeds x RK4 steps per tooth period;
- Galerkin (Fig. 10): RK4 steps x (modes)^2; the exact / manufactured checks and the
  time-step study: their grids.

The fit (:data:`FIT`, measured on 2 shared, loaded cores: upper readings) reads a
run's work, not its name, so a resolution edited in the config moves its estimate; a job
above the solve rule's 2000 MB / 30 min is refused before any job, with the estimate.
``benchmarks/bench_chain_drive.py --floor`` counts the same work in flops (the floor).
"""
from __future__ import annotations

import math

import numpy as np

from . import four_bar, geometry
from .effects import declared_keys

def stability_only(run: dict) -> bool:
    """Whether nothing but "is any speed unstable" is read from this run, so that its
    adaptive sweep stops at the first unstable speed and bisects no amplitude peak
    (:func:`adaptive_sweep` ``until_unstable``, ``prominence=None``): without an unstable
    speed it still bisects every growth-rate bump (ii), where a tongue narrower than the
    grid first shows; edges (i) need an unstable speed, which ends it.

    ``options.variants: stability`` declares it for a scene whose verdict rows read only
    that (Figs. 7 and 9): its rival and range-end variants are stability-only; its
    base run and @coarser/@coarsest levels are not (the figure draws their amplitudes and
    edges, and its convergence note compares their peaks)."""
    return (run.get("options", {}).get("variants") == "stability"
            and run.get("variant") not in (None, "coarser", "coarsest"))


#: what the solve reads of a run's identity beyond its record (:meth:`mechrepro.config.
#: PaperConfig.same_solve`): whether its sweep is stability-only, which follows from its variant
solve_key = stability_only


#: what a fresh solve process spends before its first run (imports, numba kernels)
JOB_START_S = 3.0

#: evaluated speeds / initial speeds of an adaptive shooting sweep (edges, growth-rate bumps
#: and peaks bisected): measured 1.2-2.9 over the 24 shooting runs of the default batch
#: (mean 1.7), 3.2-3.6 for fig09b and its former @finer level (many unstable bands); a rival with a
#: flat growth rate can reach ~4.6 (fig07_ts-001 overdamped)
SHOOTING_REFINE = 3.5

#: flops per grid-point update of the FD step (rhs 6 mul + 7 add, forward elimination 2,
#: back substitution 3, the speed's coefficients)
FLOPS_PER_UPDATE = 19

# Fitted to the default profile's jobs (CPU seconds: each run's solve time x its job's
# CPU / wall, 2 shared cores under load, so upper readings; idle is ~1.5-2x faster): each
# job's estimate lies 1.1-2.7x above its measured CPU (batch 279 s, fig09b 99-140 s,
# fig07_ts 184 s, fig05_plain_cd 56 s, fig05_length_cd 93 s); single runs scatter 0.3-3x
# around the fit (the load came and went).  Anchors: fig05_plain (751 speeds
# x 81 points x 5290 steps) 3.05 s CPU and fig05_plain at the former @finer level (1126 x 121 x 12866) 15.3 s
# (~7 ns per update, ~0.18 us per (step, speed) sample of the effects); peak memory 344 and
# 686 MB in fresh processes (34 bytes per sample above ~215 MB); shooting fig07_tension
# (85 points, ~81 steps per period) 26 ms per speed for the ~42 Mflop of
# :func:`shooting_flops`.
FIT = {
    "march_update_s": 1e-8,       # per grid-point update of a march
    "march_effect_s": 2.6e-7,       # per (time step, speed) sample of the effects
    "march_mem_mb": 4e-5,         # per (time step, speed) sample: the excitation arrays
    "shoot_flop_s": 5.5e-10,      # per flop of :func:`shooting_flops`
    "shoot_speed_s": 1.5e-3,        # per speed: effects on one period, Python, packaging
    "galerkin_s": 2.5e-4,           # per n_t x duration / rk4_cfl x (modes)^2
    "library_s": 2.0,             # the solve_ivp comparison of a Galerkin run
    "timestep_s": 0.12,            # per tooth period x refine of the time-step study
    "grid_s": 2.5e-6,               # per points^2 (x periods) of an exact / manufactured check
    "elastic_speed_s": 0.002,      # per speed of the elastic four-bar curve
    "base_mb": 300.0,             # the interpreter with numpy, scipy, xarray, numba
    "run_s": 0.05,                # any run
    "discrete_step_s": 8e-5,      # per (speed, RK4 step) of the discrete span, compiled (2x measured)
}


def shooting_flops(points: int, steps_per_period):
    """Flops of one shooting speed (:func:`.shooting.periodic_solution`) with ``points``
    grid points: the monodromy march of 2n + 1 lanes over one period, the LU solve of the
    periodic state (2/3 (2n)^3) and one Hessenberg reduction (10/3 (2n)^3, the least the
    multipliers' bounds or eigenvalues need).  Broadcasts over ``steps_per_period``."""
    n = points
    return ((2 * n + 1) * n * np.asarray(steps_per_period, float) * FLOPS_PER_UPDATE
            + 4.0 * (2 * n) ** 3)


def _speeds(run: dict, prm: dict) -> np.ndarray:
    """The initial speed axis [rad/s] (:func:`.solver.speed_sweep`)."""
    res, opt = run["resolution"], run.get("options", {})
    lo, hi = prm["speed_min"], prm["speed_max"]
    window = opt.get("speed_window_elastic")
    if window:
        lo, hi = four_bar.elastic_speed_window(prm, window)
    n = int(res["n_speeds"])
    extra = 2 * max(3, n // 3) if opt.get("dense_near_elastic") else 0
    return np.linspace(lo, hi, n + extra)


def size(run: dict) -> dict:
    """Speeds, grid points and steps of a speed sweep (no effect evaluated)."""
    prm, res, keys = run["parameters"], run["resolution"], declared_keys(run)
    w = _speeds(run, prm)
    L0, L1 = (geometry.span_geometry(prm, "long" in keys)[k] for k in ("L_short", "L_long"))
    ppp, p, m = int(res["points_per_pitch"]), prm["pitch"], prm["mass_per_length"]
    n = (int(round(L0 / p)) * ppp + ppp) if L0 != L1 else max(int(round(L1 / p * ppp)), 4)
    c = geometry.chain_speed(w, int(prm["n1"]), p)
    k = prm["lambda_support"] * m if "tension_coefficient" in keys else 0.0
    P = prm["static_tension"] + k * c * c
    dt = float(res["cfl"]) * (L1 / n) / np.sqrt(np.maximum(P / m - c * c, 1e-12))
    tau = geometry.tooth_period(w, int(prm["n1"]))
    out = {"speeds": w.size, "points": n + 1}
    if res.get("method", "march") == "shooting":
        # the elastic four-bar's dynamic tension can shorten the step well below the static
        # limit (fig09b: 18.8 steps per period measured against 8.5 from P = T_s + k c^2;
        # fig09a 26 against 28): an upper reading takes the larger
        out["steps_per_period"] = np.ceil(tau / dt) * (2.2 if "tension_short" in keys else 1)
    else:
        settle = float(res.get("decay_times", 0.0)) * 2 * m / prm["transverse_damping"]
        out["steps"] = math.ceil((settle + float(res.get("window_periods", 0.0)) * tau.max())
                                 / dt.min())
    return out


def cost(run: dict) -> dict:
    """Expected peak memory (MB) and solve time (s) of one run in a warm solve process
    (module docstring; a job adds :data:`JOB_START_S` once)."""
    f, res, solver = FIT, run["resolution"], run["solver"]
    mem, seconds = f["base_mb"], f["run_s"]
    if solver == "speed_sweep" and res.get("method") == "discrete":
        # per speed two tooth-period marches of 2N + 2 lanes of ~20 rollers (numpy RK4)
        seconds += f["discrete_step_s"] * _speeds(run, run["parameters"]).size \
            * int(res["steps_per_period"]) * (SHOOTING_REFINE if "edge_tol" in res else 1)
    elif solver == "speed_sweep":
        z = size(run)
        S, n1 = z["speeds"], z["points"]
        if "steps" in z:
            seconds += z["steps"] * S * (f["march_update_s"] * n1 + f["march_effect_s"])
            mem += f["march_mem_mb"] * z["steps"] * S
        else:
            per = (f["shoot_flop_s"] * shooting_flops(n1, z["steps_per_period"])
                   + f["shoot_speed_s"])
            seconds += SHOOTING_REFINE * float(per.sum())
    elif solver == "galerkin":
        # RK4 steps ~ n_t x duration / rk4_cfl (the highest mode sets the step), each
        # ~ (modes)^2; the solve_ivp comparison adds its own seconds
        nt = int(res["n_transverse"])
        modes = nt + int(res["n_longitudinal"])
        seconds += f["galerkin_s"] * nt * float(res["duration"]) / float(res["rk4_cfl"]) \
            * modes * modes
        if run.get("options", {}).get("compare_library"):
            seconds += f["library_s"]
    elif solver == "impact_timestep":
        # uniform and non-uniform marches refined to dt_min = t_i / refine
        seconds += f["timestep_s"] * float(res["tooth_periods"]) * float(res["refine"]) \
            * (int(res["points_per_pitch"]) / 4) ** 2
    elif solver in ("exact_free", "manufactured"):
        # one march per grid and scheme: points x steps ~ points^2 (x periods)
        seconds += f["grid_s"] * sum(int(n) ** 2 for n in res["points"]) \
            * float(res.get("periods", 4))
    elif solver == "elastic_four_bar":
        seconds += f["elastic_speed_s"] * int(res.get("n_speeds", 1))
    return {"mem_mb": mem, "seconds": seconds}
