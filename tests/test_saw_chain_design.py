"""saw_chain design maps: the vectorised closed form, and each design rule checked against it."""
import math

import numpy as np
import pytest

from mechrepro.solve import solve
from mechrepro.models.saw_chain.analysis import velocity_band
from mechrepro.models.saw_chain.design import design_quantities, design_rules
from mechrepro.models.saw_chain.geometry import pitch_radius

from test_saw_chain import P, run

BASE = dict(p1=P["tie_strap_pitch"], p2=P["drive_link_pitch"], z=8, omega=P["sprocket_speed"],
            m_L=P["tie_strap_mass"], m_C=P["drive_link_mass"], M=32, N=32)
OTHERS = [dict(z=3, p1=20e-3, p2=4e-3), dict(z=3, p1=4e-3, p2=20e-3), dict(z=40), dict(p2=8.91e-3),
          dict(M=2, N=2)]


def q(**over):
    return {k: float(v) for k, v in design_quantities(**{**BASE, **over}).items()}


@pytest.mark.parametrize("over", [{}] + OTHERS)
def test_design_quantities_equal_the_exact_reference_of_the_solver(over):
    """The design map's closed form against the solver's exact effect on a fine grid (and the
    bounded minimisation of velocity_band for the speed minimum)."""
    names = dict(p1="tie_strap_pitch", p2="drive_link_pitch", z="teeth", M="tie_straps_tight_side",
                 N="drive_links_tight_side")
    r = run(K=20000, outputs=["exact_reference"], **{names[k]: v for k, v in over.items()})
    r["options"] = {"beyond_roundoff_limit": True}   # only the exact output is read
    ds = solve(r)
    d = q(**over)
    F = ds["dynamic_load_x_exact"].values
    assert d["peak_load"] == pytest.approx(F.max(), rel=1e-12)    # an end sample
    assert d["min_load"] == pytest.approx(F.min(), rel=1e-5, abs=1e-5 * F.max())
    b = {**BASE, **over}
    lo, hi = velocity_band(b["p1"], b["p2"], b["omega"], pitch_radius(b["p1"], b["p2"], b["z"]))
    assert d["speed_max"] == pytest.approx(hi, rel=1e-14)
    assert d["speed_min"] == pytest.approx(lo, rel=5e-6)   # 2.7e-6 at z = 3, 5:1 (n = 65)


def test_vectorised_equals_one_design_at_a_time():
    zs = np.arange(3, 20)
    many = design_quantities(**{**BASE, "z": zs, "M": zs * 2})
    for i, z in enumerate(zs):
        one = q(z=int(z), M=int(2 * z))
        for k in one:
            assert many[k][i] == pytest.approx(one[k], rel=1e-13)


@pytest.mark.parametrize("over", [{}] + OTHERS)
def test_rule_peak_load_scales_with_speed_squared(over):
    assert q(omega=2 * BASE["omega"], **over)["peak_load"] == pytest.approx(
        4 * q(**over)["peak_load"], rel=1e-12)


def test_rule_peak_load_nearly_independent_of_z_at_fixed_speed_and_z_minus_2_at_fixed_chain_speed():
    rules = design_rules(BASE)
    assert abs(rules["design_peak_load_teeth_exponent_fixed_speed"][0]) < 0.05
    assert abs(design_rules({**BASE, "z": 40})["design_peak_load_teeth_exponent_fixed_speed"][0]) < 0.002
    # the closed form over a decade: z = 8 -> 60 changes the peak by < 3 % at fixed omega ...
    assert q(z=60)["peak_load"] / q()["peak_load"] == pytest.approx(1, abs=0.03)
    # ... and by (8/60)^2 within 3 % at the same chain speed
    assert q(z=60, omega=BASE["omega"] * 8 / 60)["peak_load"] / q()["peak_load"] == pytest.approx(
        (8 / 60) ** 2, rel=0.03)
    assert rules["design_peak_load_teeth_exponent_fixed_chain_speed"][0] == pytest.approx(-2, abs=0.05)


def test_rule_speed_fluctuation_falls_like_z_squared():
    assert design_rules(BASE)["design_fluctuation_teeth_exponent"][0] == pytest.approx(-2, abs=0.01)
    c = [q(z=z, p2=BASE["p1"])["speed_fluctuation"] * z**2 for z in (50, 100, 200)]
    assert c == pytest.approx([2 * math.pi**2 / 27] * 3, rel=2e-3)
    # independent of speed and of the masses (kinematics)
    assert q(omega=3 * BASE["omega"], M=2, N=5)["speed_fluctuation"] == pytest.approx(
        q()["speed_fluctuation"], rel=1e-9)


def test_rule_peak_load_is_affine_in_the_tight_side_links():
    F = [q(M=m, N=m)["peak_load"] for m in (10, 20, 30, 40)]
    assert np.allclose(np.diff(F, 2), 0, atol=1e-9 * F[-1])
    assert design_rules(BASE)["design_peak_load_mass_exponent"][0] == pytest.approx(1, abs=0.02)


def test_rule_unequal_pitches_raise_fluctuation_and_peak_load():
    s = BASE["p1"] + BASE["p2"]
    at = lambda r: q(p1=s * r / (1 + r), p2=s / (1 + r))  # noqa: E731
    fl = [at(r)["speed_fluctuation"] for r in (1.0, 1.5, 2.0, 5.0)]
    pk = [at(r)["peak_load"] for r in (1.0, 1.5, 2.0, 5.0)]
    assert np.all(np.diff(fl) > 0) and np.all(np.diff(pk) > 0)
    # the fluctuation is kinematic and Eq. (1) symmetric: swapping p1, p2 keeps it
    assert at(0.5)["speed_fluctuation"] == pytest.approx(at(2.0)["speed_fluctuation"], rel=1e-6)
    assert design_rules(BASE)["design_peak_load_pitch_ratio_exponent"][0] > 0


def test_rule_textbook_error_is_the_textbook_outputs_own_peak():
    ds = solve(run(K=2000, outputs=["exact_reference", "textbook"]))
    tb = float(np.abs(ds["dynamic_load_x_textbook"].values).max())
    d = q()
    assert d["textbook_peak"] == pytest.approx(tb, rel=1e-6)
    assert d["textbook_error"] == pytest.approx(tb / float(ds["dynamic_load_x_exact"].max()) - 1, rel=1e-5)


# --- the design rules in closed form (design.rule_*), against the exact solution ----------
TEETH, RATIOS = np.arange(6, 41), np.linspace(1.0, 2.0, 101)


def test_rule_peak_load_is_the_exact_peak_over_teeth_and_pitch_ratios():
    """The stage-end closed form is exact (not an approximation): it equals the sampled exact
    peak over teeth 6-40 and pitch ratios 1-2, and either link being the longer (p1/p2 < 1)."""
    from mechrepro.models.saw_chain import design

    e = design.rule_errors(BASE, TEETH, RATIOS)["peak_load_stage_end"]
    assert np.abs(e).max() < 1e-12
    e_inv = design.rule_errors(BASE, TEETH, 1.0 / RATIOS)["peak_load_stage_end"]
    assert np.abs(e_inv).max() < 1e-12


@pytest.mark.parametrize("over", [{}] + OTHERS)
def test_rule_peak_load_matches_the_solvers_exact_reference(over):
    from mechrepro.models.saw_chain import design

    names = dict(p1="tie_strap_pitch", p2="drive_link_pitch", z="teeth", M="tie_straps_tight_side",
                 N="drive_links_tight_side")
    ds = solve(run(K=200, outputs=["exact_reference"], **{names[k]: v for k, v in over.items()}))
    assert float(design.rule_peak_load(**{**BASE, **over})) == pytest.approx(
        float(ds["dynamic_load_x_exact"].max()), rel=1e-12)


def test_rule_speed_fluctuation_is_leading_order_in_the_chord_angle():
    """2 alpha^2 / 27 is within 1.1 % over teeth 6-40 and ratios 1-2, its relative error falls
    like alpha^2 (halving alpha quarters it), and equal pitches give 2 pi^2 / 27 z^-2."""
    from mechrepro.models.saw_chain import design

    e = design.rule_errors(BASE, TEETH, RATIOS)["speed_fluctuation_2alpha2_27"]
    assert np.abs(e).max() < 0.011
    e40, e80 = (abs(float(design.rule_errors(BASE, [z], [1.0])["speed_fluctuation_2alpha2_27"][0, 0]))
                for z in (40, 80))
    assert e80 / e40 == pytest.approx(0.25, abs=0.01)
    z = 400.0
    assert float(design.rule_speed_fluctuation(0.01, 0.01, z)) * z**2 == pytest.approx(
        2 * math.pi**2 / 27, rel=1e-5)


def test_rule_peak_load_simple_from_mass_speed_and_pitch():
    """(M m_L + N m_C) omega^2 p_long / 2 within 5.5 % over teeth 6-40 and ratios 1-2, and
    exact to O(alpha) as z grows (for a tight side much heavier than the seating link)."""
    from mechrepro.models.saw_chain import design

    e = design.rule_errors(BASE, TEETH, RATIOS)["peak_load_m_omega2_p_2"]
    assert np.abs(e).max() < 0.055
    heavy = {**BASE, "M": 3200, "N": 3200}
    far = abs(float(design.rule_errors(heavy, [400], [1.0])["peak_load_m_omega2_p_2"][0, 0]))
    assert far < 1e-4


def test_design_maps_output_and_rule_table():
    from mechrepro.models.saw_chain import design

    ds = solve(run(K=10, outputs=["design_maps"]))
    rows = {r[0]: r for r in design.rule_table(ds)}
    assert rows["peak_load_stage_end"][2] < 1e-12
    assert 0.005 < rows["speed_fluctuation_2alpha2_27"][2] < 0.011
    assert rows["speed_fluctuation_2alpha2_27"][3] == 6      # worst at the fewest teeth
    # at a fixed chain speed the peak load falls like z^-2 (the map's dashed lines)
    z = ds["map_teeth"].values
    F = ds["z_peak_load_fixed_chain_speed"].values[1]
    slope = np.polyfit(np.log(z[z >= 20]), np.log(F[z >= 20]), 1)[0]
    assert slope == pytest.approx(-2.0, abs=0.05)
