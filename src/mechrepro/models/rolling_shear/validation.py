"""Reproduced values of rolling_shear's reported quantities, and the tables the notebook
writes besides validation.csv (config ``tables``, ``make: validation.<id>``); only extraction
(the framework builds rows and verdicts)."""
from __future__ import annotations

import math

import numpy as np

from mechrepro.validation import Quantities, Reproduced, verdict

from .geometry import GRID_KEYS, OPTIMISED_LEVERS
from .motion_laws import pose_error

Q = Quantities("rolling_shear")


def _reduction(after: float, before: float) -> float:
    return 100.0 * (after - before) / before


def _geometry_note(ds) -> str:
    return (f"tilt {float(ds['geometry_tilt']):.4f} rad calibrated on the original levers, "
            f"x_mid {float(ds['geometry_x_mid']):.0f} mm")


@Q.register("synthetic_horizontal_displacement_original", "calibrated_tilt",
            "family_h_min", "family_h_max", "overlap_max_deviation",
            "overlap_max_deviation_constant_rate_drive", "newton_vs_closed_form_max_angle_error")
def original(R):
    ds = R.run("original")
    H, tilt = ds["family_h"].values, ds["family_tilt"].values
    ok = np.isfinite(H)
    err = max(float(np.max(pose_error(ds[f"newton_theta{k}"].values, ds[f"exact_theta{k}"].values)))
              for k in range(1, 7))
    return {
        "synthetic_horizontal_displacement_original": Reproduced(
            float(ds["calibrated_H_original"]),
            note=f"{_geometry_note(ds)}; Eq. (8) read as '{R.parameter('eq8_reading')}'; at the "
                 f"run's {ds.sizes['cut']} cut points "
                 f"{float(ds['newton_synthetic_horizontal_displacement']):.4g} mm"),
        "calibrated_tilt": Reproduced(float(ds["geometry_tilt"]),
                                      note="theta6_mid - pi; smaller tilts leave theta6 in [pi, 2 pi] "
                                           f"below {tilt[ok].min():.2f} rad"),
        "family_h_min": Reproduced(float(np.nanmin(H)),
                                   note=f"original levers over the assembling tilts {tilt[ok].min():.2f}-"
                                        f"{tilt[ok].max():.2f} rad at the configured other intents"),
        "family_h_max": float(np.nanmax(H)),
        "overlap_max_deviation": float(ds["newton_overlap_max_deviation"]),
        "overlap_max_deviation_constant_rate_drive": Reproduced(
            float(ds["crd_overlap_max_deviation"]),
            note="the original levers driven at a constant rate between the same end positions: "
                 "the lowest point leaves y = -s"),
        "newton_vs_closed_form_max_angle_error": err,
    }




def admissible_members(R, fam) -> dict[str, np.ndarray]:
    """The family-grid members that calibrate and can be built, per reading of ``guide_rod_plane``,
    at the most permissive ends of the constraints' ranges (a member some plausible machine
    builds is plausible); planar members also keep the blade offset in its range."""
    P = R.cfg.raw["parameters"]
    return buildable_members(fam, **constraint_ends(R),
                             plate_top=float(R.parameter("plate_thickness_max")) * 1e3,
                             opening=float(R.parameter("opening")) * 1e3,
                             blade_range=P["blade_offset"]["range"])


def constraint_ends(R, end=min) -> dict:
    """The constraints' range ends, clearance (mm) and transmission floor (deg): ``min`` the most
    permissive, ``max`` the strict."""
    P = R.cfg.raw["parameters"]
    return {"clearance": float(end(P["clearance"]["range"])), "mu_min": float(end(P["transmission_min"]["range"]))}


def configured_constraints(R) -> dict:
    """The buildability constraints at their configured values (mm, deg): the keywords of
    :func:`buildable_members` (and the margins of :func:`design_front`)."""
    P = R.cfg.raw["parameters"]
    return dict(clearance=float(P["clearance"]["value"]), mu_min=float(P["transmission_min"]["value"]),
                plate_top=float(P["plate_thickness_max"]["value"]), opening=float(P["opening"]["value"]))


def buildable_members(fam, *, clearance, mu_min, plate_top, opening, blade_range=(-np.inf, np.inf)):
    """{reading of ``guide_rod_plane``: mask of the family-grid members that calibrate and can be
    built at these settings (mm, deg)}, from the margins the family scan stores."""
    v = {k: fam[f"family_member_{k}"].values for k in
         ("tilt", "rod_gap", "joint_height", "mu_min", "mu_max", "rise", "blade_offset", "open_mu")}
    with np.errstate(invalid="ignore"):
        other = (np.isfinite(v["tilt"]) & (v["joint_height"] >= plate_top)
                 & (v["mu_min"] >= mu_min) & (v["mu_max"] <= 180.0 - mu_min) & (v["rise"] <= opening)
                 & (v["open_mu"] >= mu_min))
        lo, hi = blade_range
        planar = other & (v["rod_gap"] >= clearance) & (v["blade_offset"] >= lo) & (v["blade_offset"] <= hi)
    return {"planar": planar, "out_of_plane": other}


def _member(fam, i, keys=GRID_KEYS) -> str:
    return ", ".join(f"{k} {fam[f'family_member_{k}'].values[i]}" for k in keys)


def grid_flips(R, quantity: str, base_status: str, values: np.ndarray, fam, what: str) -> tuple[list, str]:
    """Re-check a Table II verdict over the admissible members under both readings: members whose
    own verdict (``values`` per member, NaN: none) differs from ``base_status`` flip it.
    Returns (flips, note)."""
    spec = R.reported(quantity)
    adm = admissible_members(R, fam)
    flips, counts = [], []
    configured = str(R.cfg.raw["parameters"]["guide_rod_plane"]["value"])
    seen = np.zeros(values.shape, bool)
    for reading in (configured, *(r for r in adm if r != configured)):
        sel = adm[reading]
        ok = sel & np.isfinite(values)
        status = np.array([verdict(spec, float(x)) if np.isfinite(x) else "" for x in values])
        flipped = [i for i in np.flatnonzero(ok & (status != base_status) & ~seen)]
        seen |= sel
        counts.append(f"{int(sel.sum())} under the {reading} reading"
                      + (f" ({len(flipped)} flip it)" if flipped else ""))
        only = "" if reading == configured else f"buildable only with guide_rod_plane = {reading}: "
        for i in flipped[:2]:
            flips.append(f"{status[i]} in family-grid member {_member(fam, i)} ({only}{what} "
                         f"{values[i]:.4g} at {fam.sizes['cut']} cut points)")
        if len(flipped) > 2:
            flips.append(f"and {len(flipped) - 2} more grid members under the {reading} reading")
    note = ("Re-checked over the family grid's members that calibrate and can be built at "
            "clearance {clearance:g} mm and a {mu_min:g} deg transmission floor: ".format(**constraint_ends(R))
            + "; ".join(counts) + ".")
    return flips, note


@Q.register("synthetic_horizontal_displacement_optimised", "horizontal_displacement_reduction",
            "paper_levers_assemble", "theta1_range_paper_levers", "theta2_range_paper_levers")
def paper_levers(R):
    ds = R.run("paper_optimised")
    fam = R.run("family")
    how = (f"Table II's optimised levers, carrier constants {R.parameter('carrier_constants')}, "
           f"Eq. (8) '{R.parameter('eq8_reading')}'")
    if "refusal" in ds.attrs:
        # a refused run is graded from its refusal: a member that cannot be calibrated on
        # 1.4341 has no H (NaN); a lever set that does not assemble fails the check
        why = f"refused ({ds.attrs['refusal_kind']}): {ds.attrs['refusal']}"
        assembles = float(ds["levers_assemble"])
        H0 = Hp = math.nan
        ok = bool(assembles == 1.0) if math.isfinite(assembles) else math.nan
        notes = {q: f"{how}; {why}" for q in ("synthetic_horizontal_displacement_optimised",
                                                "horizontal_displacement_reduction")}
        notes["paper_levers_assemble"] = why
        thetas = (math.nan, math.nan)
    else:
        H0, Hp = float(ds["calibrated_H_original"]), float(ds["calibrated_H_levers"])
        how = f"{how}, {_geometry_note(ds)}"
        ok = bool(float(ds["levers_assemble"]) == 1.0 and float(ds["newton_right_branch_rate"]) == 1.0)
        notes = {"synthetic_horizontal_displacement_optimised": how,
                 "horizontal_displacement_reduction": f"{Hp:.4g} mm against {H0:.4g} mm; {how}",
                 "paper_levers_assemble": "every cut point on the design branch inside the paper's "
                                          "ranges (a lever set that does not assemble is refused "
                                          "by name and fails this check)"}
        thetas = (float(np.ptp(ds["newton_theta1"].values)), float(np.ptp(ds["newton_theta2"].values)))
    # each row: its value, and the family scan's variable that holds it per member
    rows = {"synthetic_horizontal_displacement_optimised": (Hp, "H_levers", "H"),
            "horizontal_displacement_reduction": (_reduction(Hp, H0), "reduction", "reduction"),
            "paper_levers_assemble": (ok, "assembles", "assembles")}
    out = {}
    for q, (value, member, what) in rows.items():
        base = verdict(R.reported(q), value) if not (isinstance(value, float) and math.isnan(value)) else ""
        flips, note = (grid_flips(R, q, base, fam[f"family_member_{member}"].values, fam, what)
                       if base in ("pass", "fail") else ([], ""))
        out[q] = Reproduced(value, note=" ".join(x for x in (notes[q], note) if x), flips=flips)
    out["theta1_range_paper_levers"], out["theta2_range_paper_levers"] = thetas
    return out


def _optimum(opt):
    """Of a lever optimisation run: H of the original levers and of selPSO's optimum, the
    optimum's levers and the one-lever scans' spreads."""
    return (float(opt["opt_original_objective"]), float(opt["opt_selpso_objective"]),
            dict(zip(OPTIMISED_LEVERS, opt["opt_selpso_levers"].values)),
            dict(zip(opt["lever"].values.tolist(), opt["scan_spread"].values)))


@Q.register("our_optimisation_reduction", "our_optimised_h", "optimised_l1", "optimised_l3",
            "optimised_l5", "optimised_l6", "optimised_l10")
def our_optimisation(R):
    opt = R.run("optimisation")
    H0, H1, levers, spread = _optimum(opt)
    frac = float(R.parameter("lever_bound_fraction"))
    out = {
        "our_optimisation_reduction": Reproduced(
            _reduction(H1, H0), note=f"selPSO {H1:.4g} mm (DE {float(opt['opt_de_objective']):.4g} mm) "
                                     f"against {H0:.4g} mm; bounds +-{frac:.0%}"),
        "our_optimised_h": H1,
    }
    for k in OPTIMISED_LEVERS:
        out[f"optimised_{k}"] = Reproduced(float(levers[k]),
                                           note=f"one-lever scan spread of the objective {spread[k]:.3g} mm")
    return out


@Q.register("table2_reduction_family_frozen_min", "table2_reduction_family_frozen_max",
            "table2_reduction_family_rederived_min", "table2_reduction_family_rederived_max")
def family(R):
    """Table II's reduction over the buildable family-grid members per carrier reading; the notes
    count the members and give the range over every calibrated one."""
    ds = R.run("family")
    red = ds["family_member_reduction"].values
    carrier = ds["family_member_carrier_constants"].values.astype(str)
    built = ds["family_member_buildable"].values == 1.0
    out = {}
    for c in ("frozen", "rederived"):
        cal = (carrier == c) & np.isfinite(red)
        sel = cal & built
        lo, hi = int(np.argmin(np.where(sel, red, np.inf))), int(np.argmax(np.where(sel, red, -np.inf)))
        member = lambda i: _member(ds, i, GRID_KEYS[:5])  # noqa: E731
        lev = ds["family_member_levers_buildable"].values == 1.0
        note = (f"{int(sel.sum())} buildable of {int(cal.sum())} grid members that reach 1.4341 "
                f"(of {int((carrier == c).sum())}; {ds.sizes['cut']} cut points), in "
                f"{int((sel & lev).sum())} of them the machine with Table II's levers can be built too; "
                f"over every calibrated member {np.nanmin(red[cal]):.1f} .. {np.nanmax(red[cal]):.1f} %")
        if not sel.any():
            out[f"table2_reduction_family_{c}_min"] = Reproduced(math.nan, note=note)
            out[f"table2_reduction_family_{c}_max"] = Reproduced(math.nan, note=note)
            continue
        out[f"table2_reduction_family_{c}_min"] = Reproduced(float(red[lo]), note=f"{note}; at {member(lo)}")
        out[f"table2_reduction_family_{c}_max"] = Reproduced(float(red[hi]), note=f"at {member(hi)}")
    return out


@Q.register("optimisation_shortens_l6")
def l6_direction(R):
    """Does our optimisation shorten l6, as Table II's does, under both carrier readings (a
    direction that differs between them is a flip)?"""
    l6_0 = float(R.parameter("l6")) * 1e3
    got = {scene: float(_optimum(R.run(scene))[2]["l6"])
           for scene in ("optimisation", "optimisation_rederived")}
    l6 = got["optimisation"]
    flips = [] if (got["optimisation_rederived"] < l6_0) == (l6 < l6_0) else [
        f"{'pass' if got['optimisation_rederived'] < l6_0 else 'fail'} with re-derived carrier "
        f"constants: l6 = {got['optimisation_rederived']:.1f} mm"]
    return Reproduced(l6 < l6_0, flips=flips,
                      note=f"ours {l6:.1f} mm against {l6_0:.0f} mm, carrier constants "
                           f"{R.parameter('carrier_constants')}; re-derived: "
                           f"{got['optimisation_rederived']:.1f} mm")


@Q.register("our_optimisation_reduction_rederived", "optimised_l5_rederived",
            "optimised_l6_rederived")
def our_optimisation_rederived(R):
    H0, H1, levers, spread = _optimum(R.run("optimisation_rederived"))
    return {
        "our_optimisation_reduction_rederived": Reproduced(
            _reduction(H1, H0), note=f"selPSO {H1:.4g} mm against {H0:.4g} mm; one-lever scan spreads "
                                     + ", ".join(f"{k} {spread[k]:.3g}" for k in OPTIMISED_LEVERS) + " mm"),
        "optimised_l5_rederived": float(levers["l5"]),
        "optimised_l6_rederived": float(levers["l6"]),
    }


@Q.register("selpso_converges_from_each_initial_value", "selpso_design_branch_rate_initial_values",
            "selpso_success_in_paper_ranges", "selpso_branch_success_rate")
def selpso_rows(R):
    """The selPSO rows, from the selPSO-only scene."""
    c = R.run("selpso_initial_values")
    n_iv = int(c["iv_converged"].size)
    r_sel = float(c["selpso_right_branch_rate"])
    conv_in = (c["selpso_converged"].values.astype(bool) & c["selpso_in_ranges"].values.astype(bool))
    return {
        "selpso_converges_from_each_initial_value": Reproduced(
            bool(c["iv_converged"].values.all()),
            note=f"{int(c['iv_converged'].sum())}/{n_iv} reach G < 1e-11 mm (max "
                 f"{int(c['iv_iterations'].max())} iterations); {int(c['iv_design_branch'].sum())}/{n_iv} "
                 f"on the design branch, {int(c['iv_in_ranges'].sum())}/{n_iv} inside the paper's ranges"),
        "selpso_design_branch_rate_initial_values": float(c["iv_design_branch"].mean()),
        "selpso_success_in_paper_ranges": Reproduced(
            float(conv_in.mean()), note=f"{conv_in.mean():.0%} of the cut points converged inside "
                                        "the paper's ranges (a solve on the mirror mode counts)"),
        "selpso_branch_success_rate": Reproduced(
            r_sel, note=f"warm Newton {float(c['newton_right_branch_rate']):.0%}; the other methods "
                        "in solver_comparison.csv"),
    }


@Q.register("selpso_mean_solve_time", "speedup_like_for_like", "newton_all_design_branch")
def solvers(R):
    c = R.run("solver_comparison")
    t_newton = float(c["newton_time_per_loops_solve"])
    t_std, r_std = float(c["pso_standard_time_per_solve"]), float(c["pso_standard_right_branch_rate"])
    t_sel, r_sel = float(c["selpso_time_per_solve"]), float(c["selpso_right_branch_rate"])
    # time per solve that lands on the design branch: a solve off it must be repeated
    best = min(t_std / r_std if r_std > 0 else math.inf, t_sel / r_sel if r_sel > 0 else math.inf)
    return {
        "selpso_mean_solve_time": Reproduced(
            t_sel, note="compiled swarm loop (numba; the NumPy loop where numba is missing), "
                        "shared machine"),
        "speedup_like_for_like": Reproduced(
            best / t_newton,
            note=f"Eq. (9) only, both the mean per solve over whole strokes: Newton "
                 f"{t_newton * 1e6:.2f} us per solve (100 % design branch); selPSO {t_sel * 1e3:.1f} ms "
                 f"at {r_sel:.0%}, standard constriction PSO {t_std * 1e3:.1f} ms at {r_std:.0%} on the "
                 "design branch; the faster per design-branch solve is used"),
        "newton_all_design_branch": bool(float(c["newton_right_branch_rate"]) == 1.0),
    }


def table2(R) -> tuple[list, list]:
    """Table II: the paper's levers (original, optimised) and ours, with H in our geometry."""
    orig, popt, opt = R.run("original"), R.run("paper_optimised"), R.run("optimisation")
    header = ["lever", "paper_original_mm", "paper_optimised_mm", "ours_selpso_mm", "ours_de_mm",
              "objective_spread_mm"]
    _, _, sel, spread = _optimum(opt)
    de = dict(zip(OPTIMISED_LEVERS, opt["opt_de_levers"].values))
    rows_ = [[k, round(float(orig[f"geometry_{k}"]), 9), round(float(popt[f"geometry_{k}"]), 9),
              float(sel[k]), float(de[k]), float(spread[k])] for k in OPTIMISED_LEVERS]
    rows_.append(["objective H at the run's cut points (geometry calibrated on 1.4341)",
                  float(orig["newton_synthetic_horizontal_displacement"]),
                  float(popt["newton_synthetic_horizontal_displacement"]),
                  float(opt["opt_selpso_objective"]), float(opt["opt_de_objective"]), math.nan])
    return header, rows_


def lever_scan(R) -> tuple[list, list]:
    """The one-lever scans of H about our optimum (run ``optimisation``) and their spread."""
    opt = R.run("optimisation")
    scan = opt["scan_objective"].values
    header = ["lever"] + [f"{f:+.3f}" for f in opt["scan_fraction"].values] + ["spread_mm"]
    return header, [[lv] + [float(v) for v in scan[j]] + [float(opt["scan_spread"][j])]
                    for j, lv in enumerate(opt["lever"].values.tolist())]


def solver_comparison(R) -> tuple[list, list]:
    """The position solvers of run ``solver_comparison`` on Eq. (9), side by side."""
    comp = R.run("solver_comparison")
    header = ["method", "success_rate", "in_paper_ranges_rate", "right_branch_rate",
              "median_fitness_loops_mm", "max_fitness_loops_mm", "time_per_loops_solve_s",
              "time_per_pose_solve_s"]
    out = []
    for m in ("newton", "selpso", "pso_standard", "cold_root", "least_squares", "warm_root",
              "warm_least_squares"):
        if f"{m}_success_rate" not in comp:
            continue
        t = float(comp["newton_time_per_loops_solve"] if m == "newton" else comp[f"{m}_time_per_solve"])
        fl = comp[f"{m}_fitness_loops"].values
        out.append([m, float(comp[f"{m}_success_rate"]), float(comp[f"{m}_in_ranges_rate"]),
                    float(comp[f"{m}_right_branch_rate"]), float(np.median(fl)), float(np.max(fl)),
                    t, float(comp.get(f"{m}_time_per_pose_solve", np.nan))])
    return header, out


def recommended(ds, *, clearance: float, mu_min: float) -> dict | None:
    """The recommended design of scene ``design``: the lowest H buildable at ``clearance`` and
    ``mu_min`` (deg; the strict range ends), preferring the design that changes only l6
    (``kept``) where it qualifies: its index over ``l6_grid``, "kept" or "envelope", levers,
    worst transmission angle and joint height; None if none qualifies."""
    gap, H = ds["envelope_rod_gap"].values, ds["envelope_H"].values
    with np.errstate(invalid="ignore"):
        ok = {w: (gap >= clearance) & (ds[f"{w}_mu_worst"].values >= mu_min) for w in ("kept", "envelope")}
        ok["kept"] &= ds["kept_buildable"].values == 1.0
    # the lowest H of each; "kept" first, so that it wins a tie
    best = [(int(np.flatnonzero(m)[np.argmin(H[m])]), w) for w, m in ok.items() if m.any()]
    if not best:
        return None
    i, which = min(best, key=lambda b: H[b[0]])
    lv = ds["envelope_levers"].values[i]
    if which == "kept":
        lv = ds["paper_levers"].values[0].copy()
        lv[OPTIMISED_LEVERS.index("l6")] = ds["envelope_levers"].sel(lever="l6").values[i]
    return {"index": i, "which": which, "levers": lv, "mu_worst": float(ds[f"{which}_mu_worst"][i]),
            "joint_height": float(ds[f"{which}_joint_height"][i])}


def design_front(R) -> tuple[list, list]:
    """The design-front table of run ``design``: the paper's designs, the front and the
    design recommended at the strict ends of the constraints' ranges, with levers, objectives
    and the buildability margins at the configured constraints."""
    ds, strict = R.run("design"), constraint_ends(R, max)
    clearance, mu_min, plate_top, opening = configured_constraints(R).values()
    header = ["design", *[f"{k}_mm" for k in OPTIMISED_LEVERS], "H_mm", "reduction_pct",
              "mu_worst_deg", "rod_gap_margin_mm", "joint_height_margin_mm",
              "transmission_margin_deg", "blade_rise_margin_mm", "box_margin", "buildable"]
    H0 = float(ds["paper_H"].values[0])
    rise = float(ds["geometry_width"]) ** 2 / (2.0 * float(ds["geometry_R"]))

    def row(name, levers, H, mu, gap, height, box, ok):
        return [name, *[round(float(v), 1) for v in levers], float(H), _reduction(float(H), H0),
                float(mu), float(gap) - clearance, float(height) - plate_top, float(mu) - mu_min,
                opening - rise, float(box), int(ok)]

    out = [row(f"paper_{d}", ds["paper_levers"].values[i], ds["paper_H"].values[i],
               ds["paper_mu_worst"].values[i], ds["paper_rod_gap"].values[i],
               ds["paper_joint_height"].values[i], math.nan, ds["paper_buildable"].values[i])
           for i, d in enumerate(ds["paper_design"].values.astype(str))]
    box = np.nanmin(ds["envelope_box_margin"].values, axis=1)
    for i in np.flatnonzero(ds["envelope_on_front"].values == 1.0):
        out.append(row("front", ds["envelope_levers"].values[i], ds["envelope_H"].values[i],
                       ds["envelope_mu_worst"].values[i], ds["envelope_rod_gap"].values[i],
                       ds["envelope_joint_height"].values[i], box[i], 1))
    d = recommended(ds, **strict)
    if d is not None:
        i = d["index"]
        lo, hi = ds["front_box"].values.T
        margin = float(np.min(np.minimum(d["levers"] - lo, hi - d["levers"]) / (hi - lo)))
        out.append(row(f"recommended ({'only l6 changed' if d['which'] == 'kept' else 'front envelope'})",
                       d["levers"], ds["envelope_H"].values[i], d["mu_worst"],
                       ds["envelope_rod_gap"].values[i], d["joint_height"], margin, 1))
    return header, out


@Q.register("design_recommended_h", "design_recommended_reduction", "design_lowest_buildable_h",
            "design_table2_buildable", "design_original_mu_worst", "design_table2_mu_worst")
def design(R):
    ds = R.run("design")
    strict = constraint_ends(R, max)
    H0 = float(ds["paper_H"].values[0])
    H = ds["envelope_H"].values
    built = np.isfinite(ds["envelope_mu_worst"].values)
    d = recommended(ds, **strict)
    j = int(np.flatnonzero(built)[np.argmin(H[built])]) if built.any() else None
    clearance = float(R.parameter("clearance")) * 1e3

    def describe(levers, mu, k, height):
        lv = ", ".join(f"{n} {v:.0f}" for n, v in zip(OPTIMISED_LEVERS, levers))
        return (f"levers {lv} mm; worst transmission angle {mu:.1f} deg, guide rod "
                f"{float(ds['envelope_rod_gap'][k]):.0f} mm beside the plate, rod joints "
                f"{height:.0f} mm above the lower blade")
    grid = (f"{int(ds['front_evaluated'])} designs evaluated ({int(ds['front_buildable_count'])} buildable) "
            f"over {ds.sizes['l6_grid']} guide-rod lengths at {ds.sizes['cut']} cut points")
    if d is not None:
        rec_note = (f"the lowest H buildable at clearance {strict['clearance']:.0f} mm and a "
                    f"{strict['mu_min']:.0f} deg transmission floor (the strict range ends)"
                    + (", only l6 changed: " if d["which"] == "kept" else ": ")
                    + describe(d["levers"], d["mu_worst"], d["index"], d["joint_height"]) + f"; {grid}")
        Hr = float(H[d["index"]])
    else:
        rec_note, Hr = f"no design qualifies; {grid}", math.nan
    box = np.nanmin(ds["envelope_box_margin"].values, axis=1)
    table2 = bool(ds["paper_buildable"].values[1] == 1.0)
    return {
        "design_recommended_h": Reproduced(Hr, note=rec_note),
        "design_recommended_reduction": _reduction(Hr, H0),
        "design_lowest_buildable_h": Reproduced(
            float(H[j]) if j is not None else math.nan,
            note=(f"at the configured clearance {clearance:.0f} mm, the envelope's design of the largest "
                  f"worst transmission angle: {describe(ds['envelope_levers'].values[j], float(ds['envelope_mu_worst'][j]), j, float(ds['envelope_joint_height'][j]))}, "
                  f"levers at least {box[j]:.0%} of the sampling box's width inside it; a longer guide rod "
                  "takes D within the clearance of the plate" if j is not None else "none buildable")),
        "design_table2_buildable": Reproduced(
            table2, note=f"Table II's levers in the configured member: guide rod "
                         f"{float(ds['paper_rod_gap'].values[1]):.0f} mm beside the plate, rod joints "
                         f"{float(ds['paper_joint_height'].values[1]):.0f} mm up, worst transmission angle "
                         f"{float(ds['paper_mu_worst'].values[1]):.1f} deg"),
        "design_original_mu_worst": float(ds["paper_mu_worst"].values[0]),
        "design_table2_mu_worst": float(ds["paper_mu_worst"].values[1]),
    }
