"""joint_wear: the honest coefficient scan -- contact loss refused by the project's own
continuous-contact check, contact arcs that wrap across +-pi measured without the parabola
refinement running over the cut."""
import math

import numpy as np
import pytest

from mechrepro.config import load_paper
from mechrepro.models.joint_wear import solver, wear
from mechrepro.solve import compute

from conftest import ROOT

CFG = load_paper(ROOT / "config/papers/joint_wear.yaml")


def test_arc_across_the_cut_equals_the_arc_away_from_it():
    t = np.arange(720) / 720
    path = 0.6 * np.sin(2 * np.pi * t) + 0.1 * np.cos(4 * np.pi * t)
    ref = wear.contact_arc(path)
    for centre in (math.pi, -math.pi + 0.05, math.pi - 0.3):      # straddles +-pi
        psi = np.angle(np.exp(1j * (path + centre)))
        assert wear.contact_arc(psi) == pytest.approx(ref, rel=1e-12)
    # an extreme sitting exactly on the cut (the former refinement read a 2 pi jump there)
    shift = math.pi - path.max()
    psi = np.angle(np.exp(1j * (path + shift)))
    assert wear.contact_arc(psi) == pytest.approx(ref, rel=1e-12)


def test_arc_of_a_path_running_round_the_bushing_is_the_full_circle():
    t = np.arange(360) / 360
    psi = np.angle(np.exp(1j * (2 * np.pi * t + 0.3 * np.sin(2 * np.pi * t))))
    assert wear.contact_arc(psi) == pytest.approx(2 * math.pi)
    wide = np.angle(np.exp(1j * 3.0 * np.sin(2 * np.pi * t)))   # 6 rad, no winding
    assert wear.contact_arc(wide) <= 2 * math.pi


def _scan(directions, gravity):
    run = dict(CFG.runs["coefficient_scan"])
    run["resolution"] = dict(run["resolution"], n_steps=360)
    run["options"] = dict(run["options"], scan_load_direction_deg=directions,
                          scan_gravity=gravity)
    return compute(run)["scan"]


def test_scan_refuses_the_load_points_where_contact_is_lost():
    """g = 0, F at 90 / 120 / 300 deg: the joint force falls to ~0.1 N (of ~60 N) and the
    contact point runs round the bushing; the continuous-contact check refuses them (the
    former filter caught an error the period never raised and kept them, with arcs of
    405-450 deg from a refinement across the cut, setting the scan's top at 9.6e-10)."""
    sc = _scan([0, 90, 120, 300], [0.0])
    k, F_min = sc["k"][:, 0], sc["F_N_min"][0]
    assert np.all(np.isfinite(k[:, 0])) and np.all(np.isnan(k[:, 1:]))
    assert np.all(F_min[1:] < 0.2)
    assert np.all(sc["L_arc"][0] <= 2 * math.pi * 0.0101)     # never beyond a circumference
    # the check the scan uses is the one the wear scenes use
    fb, ctx = solver.setup(CFG.runs["coefficient_scan"])
    from dataclasses import replace
    E = sc["E_mid"]
    fb0 = replace(fb, g=0.0, F=(E[0], E[1] + 0.5))
    with pytest.raises(ValueError, match="continuous contact lost"):
        solver.continuous_contact_period(fb0, {"n_steps": 360})


def test_fit_and_sensitivity_options_are_the_configs_own_numbers():
    """The paper's K_p the fit aims at are the reported rows; the sensitivity ends are the
    declared ranges (SI)."""
    for scene in ("load_point_fit", "load_point_posterior"):
        fit = CFG.runs[scene]["options"]["fit_K_paper"]
        for m, s in enumerate(("b1", "b2")):
            assert fit[m] == [CFG.reported[f"k_{s}_p{i}"]["value"] for i in range(1, 6)]
    raw = CFG.raw["parameters"]
    si = {"friction_coefficient": 1.0, "contact_exponent": 1.0, "d_max": 1e-3, "C_max_ratio": 1.0}
    for name, ends in CFG.runs["constant_sensitivity"]["options"]["sensitivity"].items():
        assert ends == pytest.approx([v * si[name] for v in raw[name]["range"]], rel=1e-12)


def test_inverse_radius_formula_is_the_interval_method_with_g_over_r():
    """The comparison without mechanics: with G = R0/R and a frozen radius it is linear in
    time; the calibration reproduces the mean measured rate; growth lowers the 86-h wear."""
    h = np.array([0.0229, 0.0496, 0.0779, 0.1000, 0.1221]) * 1e-3
    dh = np.array([0.0229, 0.0267, 0.0283, 0.0221, 0.0221]) * 1e-3
    R0 = 0.01
    n, w = wear.inverse_radius_prediction(h, dh, 2.0, 86.0, 2.0, 6.25, R0)
    assert n[0] == 10.0 and n[-1] == 86.0 and w[0] == h[-1]
    linear = h[-1] + dh.mean() / 2.0 * 76.0
    assert w[-1] < linear                                      # the rate falls as R grows
    assert w[-1] == pytest.approx(linear, rel=0.05)
