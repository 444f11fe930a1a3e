"""disk_tension's rivals (config rivals:): solver options with every paper number kept,
what physics each removes, and that each fails the rows it is named by and not the rest."""
import copy
from pathlib import Path

import numpy as np
import pytest

from mechrepro.config import load_paper
from mechrepro.errors import Refusal
from mechrepro.inputs import read_yaml
from mechrepro.models.disk_tension import thermal
from mechrepro.solve import solve

ROOT = Path(__file__).resolve().parent.parent
RAW = read_yaml(ROOT / "config" / "papers" / "disk_tension.yaml")
KW = dict(amplitude=50.0, s=0.005, r_f=0.025, b=0.1275, E=206e9, nu=0.3, alpha=12e-6,
          inplane_bc="free_disk")
R = np.linspace(0.026, 0.1275, 400)


@pytest.fixture(scope="module")
def cfg():
    return load_paper(ROOT / "config" / "papers" / "disk_tension.yaml", "ci")


def test_every_rival_is_a_solver_option_with_the_papers_numbers_kept():
    fal = RAW["rivals"]
    assert set(fal) == {"hoop_only", "fixed_profile"}
    for name, spec in fal.items():
        assert set(spec) == {"why", "removes", "options"}, name
        assert spec["options"] == {"residual_stress": name}


def test_every_counted_row_runs_under_every_rival(cfg):
    from mechrepro.config import _variant_names
    for q, s in cfg.reported.items():
        if s["evidence"] == "independent" and s.get("kind", "compare") != "info":
            assert {"rival-hoop_only", "rival-fixed_profile"} <= set(_variant_names(s, cfg.raw)), q


def test_hoop_only_drops_the_radial_stress_and_breaks_radial_equilibrium():
    sr, st = thermal.residual_stress(R, stress_model="hoop_only", r_c=0.065, **KW)
    pr, pt = thermal.thermal_stress(R, r_c=0.065, **KW)
    assert np.all(sr == 0) and np.array_equal(st, pt)
    # the paper's field: d(r sigma_r)/dr = sigma_theta; the rival's: 0 = sigma_theta, violated
    lhs = np.gradient(R * pr, R)
    assert np.max(np.abs(lhs - pt)[5:-5]) < 1e-3 * np.max(np.abs(pt))
    assert np.max(np.abs(st)) > 1e6


def test_fixed_profile_is_the_papers_field_at_its_own_rc_and_does_not_move_with_rc():
    same = thermal.residual_stress(R, stress_model="fixed_profile", profile_rc=0.065,
                                   r_c=0.065, **KW)
    paper = thermal.thermal_stress(R, r_c=0.065, **KW)
    for a, b in zip(same, paper):
        np.testing.assert_allclose(a, b, rtol=1e-12, atol=1e-6)
    sr, st = thermal.residual_stress(R, stress_model="fixed_profile", profile_rc=0.065,
                                     r_c=0.095, **KW)
    far = thermal.thermal_stress(R, r_c=0.095, **KW)
    assert np.argmin(st) == np.argmin(paper[1]) != np.argmin(far[1])   # the band stays at 65
    assert st[-1] == pytest.approx(far[1][-1], rel=1e-12)               # the rim level moves
    with pytest.raises(Refusal):
        thermal.residual_stress(R, stress_model="fixed_profile", r_c=0.065, **KW)


def test_an_unknown_stress_model_and_a_rival_on_the_2d_mesh_are_refused(cfg):
    with pytest.raises(Refusal):
        thermal.residual_stress(R, stress_model="membrane", r_c=0.065, **KW)
    run = copy.deepcopy(cfg.runs["table12_plate2d"])
    run["options"] = {"residual_stress": "hoop_only"}
    with pytest.raises(Refusal, match="axisym"):
        solve(run)


def _table1_ratios(run, model):
    run = copy.deepcopy(run)
    run["options"] = {**run.get("options", {}), "residual_stress": model}
    ds = solve(run)
    k = np.diag(ds["k_sigma_hat"].values)
    return k, float(ds["alpha_effective"])


def test_hoop_only_is_recalibrated_and_fails_table1_which_the_paper_passes(cfg):
    run = cfg.runs["table12@rival-hoop_only"]
    paper = np.asarray(RAW["parameters"]["fit_table1_diagonal"]["value"], float)
    k0, a0 = _table1_ratios(run, "thermal_analogy")
    k1, a1 = _table1_ratios(run, "hoop_only")
    assert k1[4] == pytest.approx(paper[4], rel=1e-6) and a1 != a0   # re-calibrated
    assert np.all(np.abs(k0[:4] / paper[:4] - 1) < 0.03)
    assert np.all(np.abs(k1[:4] / paper[:4] - 1) > 0.03)
    assert k1[0] == 0.0 and k1[1] > 0   # no radial stress: N_d = 0 unmoved, N_d = 1 stiffened


def test_fixed_profile_leaves_table1_and_flattens_the_location_of_the_maximum(cfg):
    run = cfg.runs["table12@rival-hoop_only"]
    k0, a0 = _table1_ratios(run, "thermal_analogy")
    k1, a1 = _table1_ratios(run, "fixed_profile")
    np.testing.assert_allclose(k1, k0, rtol=1e-12)
    assert a1 == a0
    grid = copy.deepcopy(cfg.runs["rc_grid@rival-fixed_profile"])
    base = copy.deepcopy(grid)
    base["options"] = {}
    f_p = solve(base)["f_rolled"].sel(n_d=4).values
    f_r = solve(grid)["f_rolled"].sel(n_d=4).values
    rc = np.asarray(RAW["scenes"]["rc_grid"]["parameters"]["rolling_radius"])
    assert 55 <= rc[np.nanargmax(f_p)] <= 75 < rc[np.nanargmax(f_r)]
