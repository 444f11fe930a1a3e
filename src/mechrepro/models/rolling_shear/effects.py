"""rolling_shear's effect (config ``effects:``), the Fig. 9 contrast's drive law, and outputs
(``outputs:``) costing extra solves; each a pure function of the :class:`~.run_context.Context`."""
from __future__ import annotations

import math

import numpy as np

from mechrepro.effects import EffectRegistry
from mechrepro.units import var

from . import optimise

EFFECTS = EffectRegistry("rolling_shear")


@EFFECTS.register("constant_rate_drive")
def constant_rate_drive(ctx) -> dict:
    """Fig. 9 contrast: both levers at a constant rate between the stroke's end positions;
    Eq. (9) forward, then Eq. (7)."""
    from .blade import constant_rate_drive as drive

    r = drive(ctx.g, ctx.stroke.theta)
    w = "both levers at a constant rate between the stroke's end positions"
    return {
        "crd_x_k": var("cut", r["x_k"], "mm", f"lowest point x_k, {w}"),
        "crd_y_k": var("cut", r["y_k"], "mm", f"lowest point y_k, {w}"),
        "crd_overlap_max_deviation": var((), np.max(np.abs(r["y_k"] + ctx.g.s)), "mm",
                                         f"max |y_k + s|, {w}"),
    }


@EFFECTS.register("tilt_scan")
def tilt_scan(ctx) -> dict:
    """H of the original levers over the guide-rod tilt; a calibrating run's scanned tilts are
    reused, the rest scanned here."""
    from .calibrate import TILTS, H_of_tilt

    cal = ctx.calibration
    H = np.full(len(TILTS), np.nan) if cal is None else np.array(cal["H_scan"], float)
    n_scan = 33 if cal is None else int(cal["n_scan"])
    for j in range(0 if cal is None else int(cal["n_scanned"]), len(TILTS)):
        H[j] = H_of_tilt(ctx.g_original, float(TILTS[j]), n_scan, ctx.tol_floor)
    return {"family_tilt": var("tilt", TILTS, "rad", "guide-rod tilt theta6_mid - pi"),
            "family_h": var("tilt", H, "mm",
                            "synthetic horizontal displacement, original levers, 33 cut points "
                            "(NaN: leaves the paper's ranges)")}


@EFFECTS.register("initial_values")
def initial_values(ctx) -> dict:
    """Fig. 12: selPSO fitness G of Eq. (9) against the iterations at mid-cut from each of
    ``options.initial_values``."""
    from .blade import exact_pose
    from .loops import in_ranges, on_design_branch
    from .selpso import selpso
    from .stroke import loops_fitness

    inits = np.asarray(ctx.options["initial_values"], float)
    i_mid = ctx.n // 2
    t5, t6 = exact_pose(ctx.g, float(ctx.x_k[i_mid]))
    rng = ctx.rng(4)
    st = ctx.settings.pso_loops
    hist = np.full((len(inits), st.max_iter + 1), np.nan)
    rows = []   # per initial value: iterations, converged, design branch, in ranges
    for k, x0 in enumerate(inits):
        r = selpso(loops_fitness(ctx.g, t5, t6), x0, st, rng, period=2 * math.pi)
        hist[k, :r.history.size] = r.history
        th = np.array([*r.x, t5, t6])
        rows.append((r.iterations, r.converged, on_design_branch(ctx.g, th), in_ranges(th)))
    iters, conv, design, inr = zip(*rows)
    return {
        "iv_initial_value": var(("initial_value", "unknown"), inits, "rad",
                                "initial values theta1..theta4 of selPSO"),
        "iv_fitness_history": var(("initial_value", "iteration"), hist, "mm",
                                  "best fitness G of Eq. (9) after each iteration"),
        "iv_iterations": var("initial_value", np.asarray(iters, float), "1",
                             "iterations to G < tol"),
        "iv_converged": var("initial_value", np.asarray(conv, np.int8), "1", "G < tol reached"),
        "iv_design_branch": var("initial_value", np.asarray(design, np.int8), "1",
                                "solution on the design branch"),
        "iv_in_ranges": var("initial_value", np.asarray(inr, np.int8), "1",
                            "solution inside the paper's ranges (on the design branch or its mirror mode)"),
        "iv_cut_point_x_k": var((), ctx.x_k[i_mid], "mm", "cut point of Fig. 12 solves"),
    }


@EFFECTS.register("lever_scan")
def lever_scan(ctx) -> dict:
    """One-at-a-time scans of H over each lever's bounds (Table II): which levers H determines."""
    k = int(ctx.res.get("scan_points", 21))
    f = optimise.penalised(ctx.g, ctx.x_k, ctx.settings.tol_pose)
    base = np.array(ctx.g.levers())
    frac = np.linspace(-1, 1, k) * float(ctx.p["lever_bound_fraction"])
    H = np.full((len(base), k), np.nan)
    for j in range(len(base)):
        for m, fr in enumerate(frac):
            x = base.copy()
            x[j] *= 1 + fr
            v = f(x)
            H[j, m] = v if v < optimise.PENALTY else np.nan
    return {
        "scan_fraction": var("scan", frac, "1", "relative change of the scanned lever"),
        "scan_objective": var(("lever", "scan"), H, "mm",
                              "synthetic horizontal displacement, one lever varied (NaN: no assembly)"),
        "scan_spread": var("lever", np.nanmax(H, axis=1) - np.nanmin(H, axis=1), "mm",
                           "max - min of the objective over the scan"),
    }
