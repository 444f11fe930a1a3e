"""rolling_shear (issues 58, 62): what the verdicts rest on -- no rival that edits a paper
value, the initial swarm's spread as an assumed constant whose range ends flip the branch
verdict, calibration_points refined with the levels, buildability that sees the guide rod's
moving joint D, and the planar reading of the guide rod declared with its alternative."""
import copy
import math

import numpy as np
import pytest

from mechrepro.models.rolling_shear import stroke
from mechrepro.models.rolling_shear.blade import carrier_points
from mechrepro.models.rolling_shear.constraints import margins, settings, violations
from mechrepro.models.rolling_shear.run_context import Context
from mechrepro.models.rolling_shear.geometry import cut_points
from mechrepro.models.rolling_shear.validation import admissible_members, paper_levers
from mechrepro.solve import compute, solve
from mechrepro.validation import level_error

from test_rolling_shear_helpers import Results, config, grid, run

TABLE2 = {"l1": 926.7, "l3": 689.3, "l5": 984.6, "l6": 809.3, "l10": 1704.3}


# --- 1. no rival edits a paper value; paper_levers_assemble is not credited by one ----------

def test_no_rival_changes_a_value_the_paper_gives():
    """The framework's rule (issue 58): a rival never edits a number with a paper source --
    neither a sourced parameter nor one of Table II's levers (the old short_rods set l3 to
    300 mm)."""
    raw = config().raw
    sourced = {k for k, v in raw["parameters"].items() if "source" in v}
    paper_levers_ = set(TABLE2.values()) | {raw["parameters"][k]["value"] for k in TABLE2}
    for name, spec in raw.get("rivals", {}).items():
        assert not set(spec.get("parameters", {})) & sourced, name
        for k, v in spec.get("options", {}).get("levers", {}).items():
            assert v in paper_levers_, (name, k, v)
    assert "rivals" not in raw["reported"]["paper_levers_assemble"]


def test_paper_levers_assemble_is_unsettled_where_a_buildable_member_breaks_it():
    """Re-checked over the family grid: a member that can be built in which Table II's
    levers leave the paper's ranges flips the check (the grid of the pipeline has one:
    blade offset -600 mm, R 70 m, width 2350 mm, y_joint 100 mm, re-derived carrier
    constants); a member nobody can build does not."""
    r = run("paper_optimised")
    ds = solve(r)
    ok = paper_levers(Results(r, paper_optimised=ds))["paper_levers_assemble"]
    assert ok.value is True and ok.flips == []
    bad = grid(assembles=[1.0, 0.0], H_levers=[1.6, np.nan], reduction=[11.6, np.nan],
               rod_gap=[500.0, 500.0])
    got = paper_levers(Results(r, paper_optimised=ds, family=bad))
    assert got["paper_levers_assemble"].value is True
    assert len(got["paper_levers_assemble"].flips) == 1
    assert "fail in family-grid member" in got["paper_levers_assemble"].flips[0]
    # the same member with its guide rod over the plate counts only under the out-of-plane
    # reading, and one whose rod joints dip into the plate under neither
    for col, val, n in (("rod_gap", -100.0, 1), ("joint_height", 10.0, 0)):
        g = grid(assembles=[1.0, 0.0], H_levers=[1.6, np.nan], reduction=[11.6, np.nan],
                 **{col: [grid()[f"family_member_{col}"].values[0], val]})
        flips = paper_levers(Results(r, paper_optimised=ds, family=g))["paper_levers_assemble"].flips
        assert len(flips) == n and all("out_of_plane" in f for f in flips)


# --- 2. the initial swarm's spread: assumed, its range ends flip the branch verdict ------------

def test_initial_spread_is_an_assumed_constant_the_selpso_verdicts_depend_on():
    raw = config().raw
    p = raw["parameters"]["pso_init_scale"]
    assert p["assumed"] is True and "source" not in p and len(p["why"]) > 50
    lo, hi = p["range"]
    assert lo < p["value"] <= hi == 1.0          # the standard normal itself is the upper end
    for q in ("selpso_branch_success_rate", "selpso_converges_from_each_initial_value"):
        assert "pso_init_scale" in raw["reported"][q]["depends_on"], q
    assert "selpso_initial_values@pso_init_scale-lo" in config().runs


@pytest.mark.parametrize("end,branch_rate_is_one", [("lo", True), ("hi", False)])
def test_branch_verdict_flips_across_the_spread_range(end, branch_rate_is_one):
    """seed 0, the default's 33 cut points: the literal standard normal (1 rad) lands ~30 %
    of the solves on the isosceles dyad's mirror mode, the range's lower end none."""
    r = run("solver_comparison")
    lo, hi = config().raw["parameters"]["pso_init_scale"]["range"]
    r["parameters"]["pso_init_scale"] = lo if end == "lo" else hi
    r["options"]["methods"] = ["selpso"]
    r["effects"], r["contributes"] = [], {}
    rate = float(compute(r)["data"]["selpso_right_branch_rate"][1])
    assert (rate == 1.0) is branch_rate_is_one, rate


# --- 3. calibration_points refined with the levels --------------------------------------------

def test_calibration_points_is_a_resolution_knob_refined_with_the_levels():
    cfg = config()
    assert "calibration_points" not in cfg.raw["parameters"]
    assert cfg.raw["refine"]["calibration_points"]["factor"] == 2
    for scene in cfg.raw["scenes"]:
        assert cfg.runs[scene]["resolution"]["calibration_points"] == 129, scene
    assert cfg.runs["paper_optimised@coarser"]["resolution"]["calibration_points"] == 64
    assert cfg.runs["paper_optimised@coarsest"]["resolution"]["calibration_points"] == 32


def test_table2_error_bar_from_calibration_points_is_real():
    """Before, the Table II rows' levels all evaluated H at 129 points: error 0.  Now their
    Richardson estimate from 129 / 64 / 32 points is of the size of the true error (against
    1025 points), first order."""
    H = {}
    for n in (32, 64, 129, 1025):
        r = run("paper_optimised")
        r["resolution"].update(calibration_points=n, n_points=9)
        H[n] = float(solve(r)["calibrated_H_levers"])
    e, order, converged, _ = level_error(H[32], H[64], H[129], 2.0, 0.05 * 0.9327)
    true = abs(H[129] - H[1025])
    assert converged and e > 0 and 0.5 < order < 1.5, (e, order)
    assert true / 3 < e < 3 * true and 1e-5 < true / H[1025] < 1e-3, (e, true)


# --- 4. buildability: the guide rod's moving joint D, the clearance range --------------------

def _configured():
    ctx = Context(run("paper_optimised"))
    g = ctx.g_original
    return ctx, g, stroke.exact_theta(g, cut_points(g, 129)[1])


def test_guide_rod_check_sees_the_moving_joint_D_not_only_the_pivot_E():
    """Fails if constraint 1 looks at E alone: the configured member's joint D passes far
    closer to the plate than its pivot E, so a clearance between the two gaps breaks it."""
    ctx, g, theta = _configured()
    D = carrier_points(g, theta[:, 4], theta[:, 5])["D"]
    hi = g.x_mid + 0.5 * g.width                       # the plate's right edge; E, D right of it
    gap_D, gap_E = float(D.real.min() - hi), float(0.0 - hi)
    assert 200.0 < gap_D < gap_E - 500.0
    lim = settings(ctx.p)
    assert violations(g, theta, **dict(lim, clearance=gap_D - 5.0)) == []
    broken = violations(g, theta, **dict(lim, clearance=gap_D + 5.0))
    assert len(broken) == 1 and "guide rod ED" in broken[0]
    assert abs(margins(g, theta)["rod_gap"] - gap_D) < 1e-9


def test_configured_member_is_buildable_at_both_ends_of_the_clearance_range():
    """The old member (blade offset -600 mm) had D 194 mm beside the plate: unbuildable at
    the declared 200 mm, and no run checked it.  Now the Table II rows depend on clearance."""
    cfg = config()
    lo, hi = cfg.raw["parameters"]["clearance"]["range"]
    ctx, g, theta = _configured()
    for c in (lo, hi):
        assert violations(g, theta, **dict(settings(ctx.p), clearance=float(c))) == [], c
    for q in ("synthetic_horizontal_displacement_optimised", "horizontal_displacement_reduction",
              "paper_levers_assemble"):
        assert "clearance" in cfg.reported[q]["depends_on"], q
    ds = solve(cfg.runs["paper_optimised@clearance-hi"])
    assert "refusal" not in ds.attrs


# --- 5. the planar reading of the guide rod, declared with its alternative --------------------

def test_guide_rod_plane_is_an_assumed_choice_with_both_readings():
    p = config().raw["parameters"]["guide_rod_plane"]
    assert p["assumed"] is True and p["value"] == "planar"
    assert p["range"] == ["planar", "out_of_plane"]
    ctx, g, theta = _configured()
    lim = dict(settings(ctx.p), clearance=5000.0)      # the rod can be nowhere near the plate
    assert any("guide rod ED" in v for v in violations(g, theta, **lim))
    assert violations(g, theta, **dict(lim, guide_rod_plane="out_of_plane")) == []


def test_table2_fails_are_unsettled_where_the_other_reading_builds_a_member_that_passes():
    """A member buildable only with the guide rod out of the cut's plane (its rod sweeps
    under the plate, blade centre right of I) that reproduces -34.96 % flips both Table II
    fails; the same member under the planar reading, or a planar one at +5 %, does not."""
    r = run("paper_optimised")
    ds = solve(r)
    H = 1.4341 * (1 - 0.356)
    oop = grid(H_levers=[1.6, H], rod_gap=[500.0, -300.0], blade_offset=[-650.0, 1800.0])
    got = paper_levers(Results(r, paper_optimised=ds, family=oop))
    for q in ("synthetic_horizontal_displacement_optimised", "horizontal_displacement_reduction"):
        assert got[q].value > 0 if q.endswith("reduction") else got[q].value > 1.5
        assert len(got[q].flips) == 1 and "out_of_plane" in got[q].flips[0], got[q].flips
        assert "blade_offset 1800.0" in got[q].flips[0]
        assert "planar reading" in got[q].note and "out_of_plane reading (1 flip it)" in got[q].note
    planar = grid(H_levers=[1.6, 1.4341 * 1.05], rod_gap=[500.0, 300.0])
    assert all(v.flips == [] for v in paper_levers(Results(r, paper_optimised=ds, family=planar)).values()
               if hasattr(v, "flips"))
    adm = admissible_members(Results(r, paper_optimised=ds), oop)
    assert adm["planar"].tolist() == [True, False] and adm["out_of_plane"].tolist() == [True, True]


def test_the_unclamped_swarm_is_a_range_end_not_a_rival():
    """Eq. (1) as printed has no velocity clamp: the unclamped swarm is pso_v_max's upper
    range end (the loader would refuse it as a rival), re-run for the Fig. 12 row, on the
    selPSO-only scene (its re-runs never solve the other five methods)."""
    cfg = config()
    raw = cfg.raw
    assert not raw["rivals"]
    spec = raw["reported"]["selpso_converges_from_each_initial_value"]
    assert "pso_v_max" in spec["depends_on"] and "rivals" not in spec
    assert max(raw["parameters"]["pso_v_max"]["range"]) == 100.0
    assert "selpso_initial_values@pso_v_max-hi" in cfg.runs
    for name, r in cfg.runs.items():
        if name.startswith("selpso_initial_values@"):
            assert r["options"]["methods"] == ["selpso"], name
    assert not any(n.startswith("solver_comparison@seed") for n in cfg.runs)
