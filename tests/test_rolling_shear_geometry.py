"""rolling_shear: the invented geometry is what design.py derives, and it assembles."""
import math

import numpy as np
import pytest

from mechrepro.models.rolling_shear import blade, loops, optimise, stroke
from mechrepro.models.rolling_shear.loops import in_ranges, on_design_branch
from mechrepro.models.rolling_shear.design import design
from mechrepro.models.rolling_shear.geometry import cut_points, with_intent

from test_rolling_shear_helpers import config, geometry, run, stroke_exact


@pytest.fixture(scope="module")
def g():
    return geometry()


def test_geometry_is_derived_from_the_intents_at_run_time():
    P = config().raw["parameters"]
    v = {k: P[k]["value"] for k in P}
    d = design(l1=v["l1"], l3=v["l3"], l5=v["l5"], l6=v["l6"], l9=v["l9"], l10=v["l10"],
               s=v["s"], h=v["h"], R=v["R"], y_joint=v["y_joint"], theta6_mid=v["theta6_mid"],
               elbow_angle=math.radians(v["elbow_angle"]), blade_offset=v["blade_offset"])
    g = geometry()
    for k in ("l2", "l4", "l8", "l11", "d", "x_mid", "alpha", "beta1", "beta2"):
        assert abs(d[k] - getattr(g, k)) < 1e-9, k
    # an intent changed at run time changes every constant that follows from it
    g2 = with_intent(g, blade_offset=v["blade_offset"] + 100.0)
    assert abs(g2.x_mid - g.x_mid - 100.0) < 1e-9 and g2.d != g.d


def test_every_assumed_constant_declares_range_calibration_or_numerical():
    P = config().raw["parameters"]
    invented = ["l9", "h", "R", "width", "y_joint", "theta6_mid", "elbow_angle", "blade_offset",
                "eq8_reading", "carrier_constants", "elbow1", "elbow2", "guide_mode"]
    for k in invented:
        assert P[k].get("assumed") is True and len(P[k]["why"]) > 20, k
        assert ("range" in P[k]) + ("calibrated_on" in P[k]) + bool(P[k].get("numerical")) == 1, k
    assert P["theta6_mid"]["calibrated_on"] == "synthetic_horizontal_displacement_original"
    for k in ("pose_tol", "pso_swarm", "pso_max_iter", "pso_c1", "pso_w_start", "initial_value"):
        assert P[k]["numerical"] is True, k
    for k in ("l1", "l3", "l5", "l6", "l10", "s"):
        assert "Table" in P[k]["source"], k


def test_calibration_hits_the_paper_number_and_is_monotone(g):
    from mechrepro.models.rolling_shear.calibrate import TILTS, calibrate_tilt

    gc, info = calibrate_tilt(g, 1.4341, 9, 1e-9)
    xk = cut_points(gc, 9)[1]
    assert abs(optimise.objective(gc, xk, 1e-9) - 1.4341) < 1e-9
    ok = np.isfinite(info["H_scan"])
    H = info["H_scan"][ok & (TILTS <= 0.5)]
    assert np.all(np.diff(H) > 0)                   # H rises with the tilt: one root
    assert np.nanmax(info["H_scan"]) > 5 * 1.4341   # (it levels off past 0.5 rad, far above)
    assert TILTS[np.isfinite(info["H_scan"])].min() > 0   # theta6 = pi itself leaves the range


def test_mid_cut_pose_is_the_design_pose(g):
    t5, t6 = blade.exact_pose(g, g.x_mid)
    assert abs(t5 - g.beta2) < 1e-6                              # beta = 0 at mid-cut
    assert abs(t6 - config().raw["parameters"]["theta6_mid"]["value"]) < 1e-6


@pytest.mark.parametrize("n", [5, 33])
def test_linkage_assembles_over_the_whole_stroke_and_closes_every_loop(g, n):
    sol = stroke_exact(g, n)
    for th in sol.theta:
        assert np.all(np.abs(loops.residuals(g, th[:4], th[4], th[5])) < 1e-9)  # mm
        assert in_ranges(th) and on_design_branch(g, th)
    xk, yk = blade.lowest_point(g, sol.theta[:, 4], sol.theta[:, 5])
    assert np.max(np.abs(yk + g.s)) < 1e-9
    assert np.allclose(xk, cut_points(g, n)[1], atol=1e-9)
    # far from toggle and fold everywhere
    assert loops.dyad_margins(g, sol.theta[:, 4], sol.theta[:, 5]).min() > 300.0


def test_newton_stroke_closes_every_loop_to_1e_9_mm(g):
    xk = cut_points(g, 33)[1]
    sol = stroke.solve_newton(g, xk, stroke.SolverSettings(initial_value=tuple(
        run()["parameters"]["initial_value"])))
    ex_theta = stroke.exact_theta(g, xk)
    for th in sol.theta:
        assert np.all(np.abs(loops.residuals(g, th[:4], th[4], th[5])) < 1e-9)
    assert np.max(np.abs(np.angle(np.exp(1j * (sol.theta - ex_theta))))) < 1e-10


def test_blade_stays_inside_the_opening_and_stroke_turns_a_few_degrees(g):
    sol = stroke_exact(g, 9)
    beta = sol.theta[:, 4] - g.beta2
    # pure rolling over the cut turns the blade by width / R (1.9 deg for 2350 mm, R 70 m)
    assert abs(np.ptp(beta) - g.width / g.R) < 0.05 * g.width / g.R
    # far end of the blade above the cut line, at the start of the cut (design rule for R)
    assert g.width ** 2 / (2 * g.R) <= config().raw["parameters"]["opening"]["value"]


def test_paper_optimised_levers_assemble_in_our_geometry(g):
    lev = {k: float(v) for k, v in config().raw["scenes"]["paper_optimised"]["options"]["levers"].items()}
    gp = g.with_levers(**lev)
    xk = cut_points(gp, 17)[1]
    H = optimise.objective(gp, xk, 1e-9)
    assert math.isfinite(H) and H > 0


@pytest.mark.parametrize("edit,expect", [
    (lambda c: c["scenes"]["original"].__setitem__("effects", ["constant_rate_drive", "magic"]),
     "'magic' is not a declared effect"),
    (lambda c: c["scenes"]["original"].__setitem__("outputs", ["tilt_scan", "magic"]),
     "'magic' is not a declared output"),
    (lambda c: c["scenes"]["original"].__setitem__("effects", ["tilt_scan"]),
     "'tilt_scan' is not a declared effect"),
    (lambda c: c["scenes"]["original"]["resolution"].__setitem__("n_points", 1), ">= 2"),
    (lambda c: c["parameters"]["l1"].__setitem__("value", -5), "l1"),
])
def test_schema_rejects_bad_runs(edit_config, edit, expect):
    from mechrepro.config import ConfigError, load_paper

    path = edit_config("rolling_shear", edit)
    with pytest.raises(ConfigError, match=expect):
        load_paper(path)


def test_forward_drive_with_reverse_solved_laws_reproduces_the_stroke(g):
    from mechrepro.models.rolling_shear.blade import constant_rate_drive, drive

    sol = stroke_exact(g, 17)
    th = drive(g, sol.theta[:, 0], sol.theta[:, 1], sol.theta[0])
    assert np.max(np.abs(np.angle(np.exp(1j * (th - sol.theta))))) < 1e-9
    xk, yk = blade.lowest_point(g, th[:, 4], th[:, 5])
    assert np.max(np.abs(yk + g.s)) < 1e-6
    # a constant-rate drive between the same end positions does not keep the overlap
    crd = constant_rate_drive(g, sol.theta)
    assert abs(crd["y_k"][0] + g.s) < 1e-6 and abs(crd["y_k"][-1] + g.s) < 1e-6
    assert np.max(np.abs(crd["y_k"] + g.s)) > 1.0


def test_every_run_recalibrates_for_its_own_intents():
    """A range-end variant of an intent re-fits the tilt: H of the original levers is the
    paper's number again (the calibration target comes from the reported block)."""
    from mechrepro.models.rolling_shear.run_context import Context

    base = run("original", "ci")
    assert base["calibration"]["theta6_mid"]["quantity"] == "synthetic_horizontal_displacement_original"
    tilts = []
    for width in (1.5, 2.35):     # m: the narrowest and the configured plate (3.2 m has no root)
        r = run("original", "ci")
        r["parameters"]["width"] = width
        r["resolution"]["calibration_points"] = 17
        ctx = Context(r)
        assert abs(ctx.calibration["H_original"] - 1.4341) < 1e-9
        tilts.append(ctx.calibration["tilt"])
    assert tilts[0] > tilts[1] + 0.005           # a shorter cut needs a steeper guide rod
