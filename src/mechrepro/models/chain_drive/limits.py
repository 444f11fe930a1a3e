"""chain_drive's cost form (read by :mod:`mechrepro.limits` before any job, which also
solves the longest jobs' papers last and refuses a job above its rule's budget).

The work of a run follows from its resolution and parameters without solving anything
(:func:`size`): the FD grid (points per pitch x span length), the step (cfl x the von Neumann
limit dx/sqrt(c_w^2 - c^2) at the static tension P = T_s + k c^2), the speeds and

- a march (Figs. 5, 8, accuracy studies): speeds x (n + 1) points x the steps of settling
  + window, and per (step, speed) sample each effect's excitation; its memory is the
  (time, speed) excitation arrays the effects fill;
- shooting (Figs. 6, 7, 9): per initial speed one march of 2n + 1 lanes over one tooth
  period plus the monodromy's bounds / eigenvalues (:func:`shooting_flops`; the adaptive
  bisection of edges and peaks adds speeds in proportion, which the fit absorbs);
- the discrete span (Fig. 7): speeds x RK4 steps per tooth period;
- Galerkin (Fig. 10): RK4 steps x (modes)^2; the exact / manufactured checks and the
  time-step study: their grids.

The seconds per unit of each term are data (config/costs.csv), so a resolution edited in
the config moves its estimate; ``benchmarks/bench_chain_drive.py --floor`` counts the same
work in flops (the floor).  Memory stays typed (no run records it).
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


#: flops per grid-point update of the FD step (rhs 6 mul + 7 add, forward elimination 2,
#: back substitution 3, the speed's coefficients)
FLOPS_PER_UPDATE = 19

#: the interpreter with numpy, scipy, xarray, numba [MB]; a march's (step, speed) sample of
#: the excitation arrays [MB]
BASE_MB, SAMPLE_MB = 300.0, 4e-5


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


def work(run: dict) -> dict:
    """The work terms of one run (module docstring)."""
    res, solver, opt = run["resolution"], run["solver"], run.get("options", {})
    out = {"run": 1.0}
    if solver == "speed_sweep" and res.get("method") == "discrete":
        # per speed two tooth-period marches of 2N + 2 lanes of ~20 rollers (numpy RK4);
        # an adaptive sweep (edge_tol) bisects edges: its own term
        key = "adaptive_rk4_steps" if "edge_tol" in res else "rk4_steps"
        out[key] = _speeds(run, run["parameters"]).size * int(res["steps_per_period"])
    elif solver == "speed_sweep":
        z = size(run)
        if "steps" in z:
            samples = float(z["steps"] * z["speeds"])
            out |= {"updates": samples * z["points"], **{f"{e} samples": samples for e in run["effects"]}}
        else:
            # a stability-only sweep stops at its first unstable speed: terms of its own
            pre = "stability " if stability_only(run) else ""
            out |= {f"{pre}shooting_flops": float(shooting_flops(z["points"], z["steps_per_period"]).sum()),
                    f"{pre}shooting_speeds": float(z["speeds"])}
    elif solver == "galerkin":
        # RK4 steps ~ n_t x duration / rk4_cfl (the highest mode sets the step), each a
        # projection on the modes (~ modes, ~ modes^2 coupled); the solve_ivp comparison
        nt, nl = int(res["n_transverse"]), int(res["n_longitudinal"])
        steps = nt * float(res["duration"]) / float(res["rk4_cfl"])
        out |= {"steps": steps, "mode_steps": steps * (nt + nl), "library": float(bool(opt.get("compare_library"))),
                "coupled mode^2 steps": steps * (nt + nl) ** 2 * ("longitudinal_coupling" in run["effects"])}
    elif solver == "impact_timestep":
        # uniform and non-uniform marches refined to dt_min = t_i / refine
        out["periods"] = float(res["tooth_periods"]) * float(res["refine"]) * (int(res["points_per_pitch"]) / 4) ** 2
    elif solver in ("exact_free", "manufactured"):
        # one march per grid and scheme: points x steps ~ points^2 (x periods)
        out["grid"] = sum(int(n) ** 2 for n in res["points"]) * float(res.get("periods", 4))
    elif solver == "elastic_four_bar":
        out["speeds"] = float(res.get("n_speeds", 1))
    return out


def mem_mb(run: dict) -> float:
    """Peak memory [MB]: the process plus a march's excitation arrays."""
    if run["solver"] != "speed_sweep" or run["resolution"].get("method", "march") != "march":
        return BASE_MB
    return BASE_MB + SAMPLE_MB * (z := size(run))["steps"] * z["speeds"]
