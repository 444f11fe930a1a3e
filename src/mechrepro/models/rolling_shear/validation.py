"""Validation rows and tables of rolling_shear: the paper's numbers against our runs.

Tolerances, fixed before looking at the results:
- numbers that depend on the (missing) geometry: 5 % -- they can only agree by accident;
- a constant overlap: |y_k + s| <= 1e-6 mm (Eq. 7 is solved to 1e-9 mm);
- solver agreement with the closed form: 1e-9 rad.
"""
from __future__ import annotations

import math

import numpy as np
import xarray as xr

from mechrepro.validation import check, compare, info

from .geometry import OPTIMISED_LEVERS

TOL_GEOMETRY = 0.05
TOL_OVERLAP_MM = 1e-6
TOL_ANGLE = 1e-9
SPEEDUP_TARGET = 300.0
PAPER_H_ORIGINAL, PAPER_H_OPTIMISED, PAPER_REDUCTION = 1.4341, 0.9327, -34.96
PAPER_SOLVE_TIME = 0.321982
GEOMETRY_NOTE = ("The paper gives only l1, l3, l5, l6, l10 (Table II) and the process data; "
                 "l2, l4, l8, l9, l11, alpha, beta1, beta2, d, h, R and the cut are invented "
                 "(docs/rolling_shear.md), so the value depends on that invention.")


def paper_levers(cfg_raw: dict) -> dict:
    """The paper's optimised levers, as configured in the paper_optimised scene (mm)."""
    return {k: float(v) for k, v in cfg_raw["scenes"]["paper_optimised"]["parameters"].items()}


def _reduction(after: float, before: float) -> float:
    return 100.0 * (after - before) / before


def rows(orig: xr.Dataset, popt: xr.Dataset, opt: xr.Dataset, comp: xr.Dataset,
         iv: xr.Dataset, cfg_raw: dict) -> list:
    H0 = float(orig["newton_synthetic_horizontal_displacement"])
    H1 = float(opt["opt_selpso_objective"])
    Hde = float(opt["opt_de_objective"])
    Hp = float(popt["newton_synthetic_horizontal_displacement"])
    t_pso = float(comp["selpso_time_per_solve"])
    t_newton = float(comp["newton_time_per_solve"])
    spread = dict(zip(opt["lever"].values.tolist(), opt["scan_spread"].values))
    pl = paper_levers(cfg_raw)
    ours = dict(zip(OPTIMISED_LEVERS, opt["opt_selpso_levers"].values))
    n_iv = int(iv["iv_converged"].size)
    exact_err = max(float(np.max(np.abs(orig[f"newton_{k}"].values - orig[f"exact_{k}"].values)))
                    for k in ("theta1", "theta2", "theta3", "theta4", "theta5", "theta6"))
    sel_ok = comp["selpso_design_branch"].values.astype(bool) & comp["selpso_converged"].values.astype(bool)
    sel_err = float(np.max(comp["selpso_error"].values[sel_ok])) if sel_ok.any() else math.nan
    out = [
        compare("overlap_max_deviation", "Fig. 9, Sec. 4 (overlap becomes a constant, s = 5 mm)",
                0.0, float(orig["newton_overlap_max_deviation"]), "mm", TOL_OVERLAP_MM,
                "max |y_k + s| of the dynamic lowest point over the cut, original levers; "
                "constant by construction once Eq. (7) is solved with y_k = -s"),
        compare("overlap_max_deviation_optimised", "Fig. 9 (optimised trajectory of the lowest points)",
                0.0, float(opt["opt_selpso_overlap_max_deviation"]), "mm", TOL_OVERLAP_MM,
                "same, levers optimised by selPSO"),
        info("overlap_max_deviation_constant_rate_drive", "Fig. 9 context, Sec. 1 (uneven overlap)",
             float(orig["crd_overlap_max_deviation"]), "mm",
             note="the original levers driven at a constant rate between the same start and end "
                  "positions: the lowest point leaves y = -s (rises above the lower blade mid-cut)"),
        check("reverse_solved_drive_makes_overlap_constant", "Abstract, Fig. 9 (overlap becomes a constant)",
              float(orig["crd_overlap_max_deviation"]) > 1e3 * max(
                  float(orig["newton_overlap_max_deviation"]), 1e-9),
              "the overlap is constant under the reverse-solved motion laws and not under a "
              "constant-rate drive of the same levers"),
        compare("synthetic_horizontal_displacement_original", "Sec. 4, text after Fig. 11 (1.4341 before optimisation)",
                PAPER_H_ORIGINAL, H0, "mm", TOL_GEOMETRY,
                f"mean |midpoint - trajectory 1| over the cut, original levers. {GEOMETRY_NOTE} "
                "Our invented guide rod tilts by up to 0.2 rad, so the blade slips ~1 % of the "
                "rolled length."),
        compare("synthetic_horizontal_displacement_optimised", "Sec. 4, text after Fig. 11 (0.9327 after optimisation)",
                PAPER_H_OPTIMISED, H1, "mm", TOL_GEOMETRY,
                f"selPSO-optimised levers in our geometry. {GEOMETRY_NOTE}"),
        compare("horizontal_displacement_reduction", "Abstract, Sec. 4, Sec. 5 (-34.96 %)",
                PAPER_REDUCTION, _reduction(H1, H0), "%", TOL_GEOMETRY,
                "reduction by our optimisation; in our formulation the objective depends on l6 "
                "only and falls monotonically with l6, so the optimum sits on the +30 % bound "
                "and the reduction is set by that (assumed) bound, not by the paper"),
        info("horizontal_displacement_reduction_best_anchor", "Abstract (-34.96 %), our convention check",
             _reduction(float(opt["opt_selpso_synthetic_horizontal_displacement_best_anchor"]),
                        float(orig["newton_synthetic_horizontal_displacement_best_anchor"])), "%",
             PAPER_REDUCTION,
             "the same optimisation measured with trajectory 1 shifted horizontally to its best "
             f"fit instead of anchored at the first cut point (original "
             f"{float(orig['newton_synthetic_horizontal_displacement_best_anchor']):.4g} mm, optimised "
             f"{float(opt['opt_selpso_synthetic_horizontal_displacement_best_anchor']):.4g} mm): how much "
             "the number depends on the correspondence the paper leaves open"),
        compare("paper_levers_reduction", "Table II (optimised levers) evaluated in our geometry",
                PAPER_REDUCTION, _reduction(Hp, H0), "%", TOL_GEOMETRY,
                f"the paper's optimised levers give H = {Hp:.4g} mm against {H0:.4g} mm for the "
                "original ones in our geometry: the paper shortens l6, which in our geometry "
                "tilts the guide rod further and increases the slip"),
        check("paper_levers_assemble", "Table II (optimised levers)",
              bool(float(popt["newton_right_branch_rate"]) == 1.0),
              "the paper's optimised levers assemble over the whole stroke of our geometry on "
              "the design branch"),
        check("optimisation_reduces_displacement", "Abstract (synthetic horizontal translation reduced)",
              H1 < H0, f"selPSO {H1:.4g} mm, DE {Hde:.4g} mm, original {H0:.4g} mm"),
        compare("optimised_l6", "Table II (L6 optimised 809.3 mm)", pl["l6"], ours["l6"], "mm",
                TOL_GEOMETRY, "l6 is the only lever the objective determines in our formulation; "
                "ours runs to the upper bound"),
    ]
    for k in ("l1", "l3", "l5", "l10"):
        out.append(info(f"optimised_{k}", f"Table II ({k} optimised {pl[k]:g} mm)", ours[k], "mm",
                        pl[k], f"not determined: the objective does not depend on {k} "
                        f"(one-lever scan spread {spread[k]:.3g} mm); any value that assembles is optimal"))
    out += [
        info("objective_spread_l6", "Sec. 3.3 step 3 (levers optimised)", spread["l6"], "mm",
             note="range of the objective over the +-30 % scan of l6 alone"),
        check("selpso_converges_from_each_initial_value", "Fig. 12, Sec. 4 (G < 1e-11 from different initial values)",
              bool(iv["iv_converged"].values.all()),
              f"{int(iv['iv_converged'].sum())}/{n_iv} initial values reach G < 1e-11 mm on Eq. (9) "
              f"(max {int(iv['iv_iterations'].max())} iterations); "
              f"{int(iv['iv_design_branch'].sum())}/{n_iv} land on the design assembly branch"),
        info("selpso_design_branch_rate_initial_values", "Fig. 12", float(iv["iv_design_branch"].mean()),
             "1", note="the paper's ranges cannot tell the two assembly modes of AB-BC apart (l1 = l3)"),
        info("selpso_mean_solve_time", "Sec. 4, text after Fig. 12 (0.321982 s, MATLAB)", t_pso, "s", PAPER_SOLVE_TIME,
             "mean wall time of one selPSO solve of Eq. (9) (Python/NumPy, vectorised swarm, "
             "shared 2-core machine): not comparable across language and hardware"),
        info("newton_mean_solve_time", "ours", t_newton, "s", note="warm-started Newton, per system solve"),
        info("default_solver_speedup", "ours (issue target >= 300)", t_pso / t_newton, "1",
             note="selPSO time per solve / warm Newton time per solve"),
        check("default_solver_speedup_ge_300", "ours (issue target)", t_pso / t_newton >= SPEEDUP_TARGET,
              f"ratio {t_pso / t_newton:.0f}"),
        check("newton_all_right_branch", "ours", float(comp["newton_right_branch_rate"]) == 1.0,
              "warm-started Newton: every cut point converged on the design branch"),
        check("selpso_success_rate_all", "Sec. 5 (selPSO overcomes the sensitivity to the initial value)",
              float(comp["selpso_success_rate"]) == 1.0,
              f"selPSO converged at {float(comp['selpso_success_rate']):.0%} of the cut points, "
              f"{float(comp['selpso_right_branch_rate']):.0%} on the design branch; cold scipy root "
              f"{float(comp['cold_root_success_rate']):.0%} / {float(comp['cold_root_right_branch_rate']):.0%}, "
              f"least_squares {float(comp['least_squares_success_rate']):.0%} / "
              f"{float(comp['least_squares_right_branch_rate']):.0%}"),
        compare("newton_vs_closed_form_max_angle_error", "ours", 0.0, exact_err, "rad", TOL_ANGLE,
                "warm Newton against circle intersections + Brent, all six angles"),
        compare("selpso_vs_closed_form_max_angle_error", "ours", 0.0, sel_err, "rad", TOL_ANGLE,
                "selPSO solutions on the design branch against the closed form"),
        info("theta1_range", "Fig. 13 (motion law of theta1)",
             float(np.ptp(orig["newton_theta1"].values)), "rad", note="range of theta1 over the cut, original levers"),
        info("theta2_range", "Fig. 14 (motion law of theta2)",
             float(np.ptp(orig["newton_theta2"].values)), "rad", note="range of theta2 over the cut, original levers"),
    ]
    return out


def table2(orig, popt, opt, cfg_raw) -> tuple[list, list]:
    """Table II: the paper's levers and ours, with the objective in our geometry."""
    pl = paper_levers(cfg_raw)
    p = cfg_raw["parameters"]
    header = ["lever", "paper_original_mm", "paper_optimised_mm", "ours_selpso_mm", "ours_de_mm",
              "determined_by_objective"]
    sel = dict(zip(OPTIMISED_LEVERS, opt["opt_selpso_levers"].values))
    de = dict(zip(OPTIMISED_LEVERS, opt["opt_de_levers"].values))
    spread = dict(zip(opt["lever"].values.tolist(), opt["scan_spread"].values))
    rows_ = [[k, float(p[k]["value"]), pl[k], float(sel[k]), float(de[k]),
              "yes" if spread[k] > 1e-9 else "no"] for k in OPTIMISED_LEVERS]
    rows_.append(["l7 (read as l9)", float(p["l9"]["value"]), float(p["l9"]["value"]),
                  float(p["l9"]["value"]), float(p["l9"]["value"]), "not varied"])
    rows_.append(["objective H (our geometry)", float(orig["newton_synthetic_horizontal_displacement"]),
                  float(popt["newton_synthetic_horizontal_displacement"]),
                  float(opt["opt_selpso_objective"]), float(opt["opt_de_objective"]), ""])
    rows_.append(["objective H (paper)", PAPER_H_ORIGINAL, PAPER_H_OPTIMISED, math.nan, math.nan, ""])
    return header, rows_


def solver_comparison(comp: xr.Dataset) -> tuple[list, list]:
    header = ["method", "success_rate", "in_paper_ranges_rate", "right_branch_rate",
              "median_fitness_loops_mm", "max_fitness_loops_mm", "time_per_solve_s",
              "time_per_pose_solve_s", "speed_vs_selpso"]
    t_ref = float(comp["selpso_time_per_solve"])
    out = []
    for m in ("newton", "selpso", "cold_root", "least_squares", "warm_root", "warm_least_squares"):
        if f"{m}_time_per_solve" not in comp:
            continue
        t = float(comp[f"{m}_time_per_solve"])
        fl = comp[f"{m}_fitness_loops"].values
        out.append([m, float(comp[f"{m}_success_rate"]), float(comp[f"{m}_in_ranges_rate"]),
                    float(comp[f"{m}_right_branch_rate"]), float(np.median(fl)), float(np.max(fl)),
                    t, float(comp.get(f"{m}_time_per_pose_solve", comp[f"{m}_time_per_solve"])),
                    t_ref / t])
    return header, out
