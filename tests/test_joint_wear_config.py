"""joint_wear config: both profiles load, every constant is sourced or assumed, SI units."""
import pytest

from mechrepro.config import load_paper
from mechrepro.io import check_cf
from mechrepro.models.joint_wear import EFFECTS
from mechrepro.solve import solve

from conftest import ROOT

PATH = ROOT / "config/papers/joint_wear.yaml"


@pytest.mark.parametrize("profile", ["default", "ci"])
def test_profiles_load_and_name_only_known_effects(profile):
    cfg = load_paper(PATH, profile)
    for run in cfg.runs.values():
        assert set(run["effects"]) <= set(EFFECTS.names)
    assert len(cfg.studies["intervals"]) >= 4
    assert {"fig13", "fig15", "fig16", "fig17", "fig18", "fig19", "cost_of_accuracy"} <= set(cfg.figures)


def test_parameters_sourced_or_assumed_and_converted_to_si():
    cfg = load_paper(PATH)
    for name, p in cfg.raw["parameters"].items():
        assert p.get("source") or (p.get("assumed") and p.get("why")), name
    assumed = cfg.assumed()
    assert {"load_point_x", "load_point_y", "gravity", "friction_coefficient", "d_max"} <= set(assumed)
    p = cfg.runs["period_quasistatic"]["parameters"]
    assert p["pin_radius"] == pytest.approx(9.9e-3)
    assert p["radial_clearance"] == pytest.approx(1e-4)
    assert p["crank_speed"] == pytest.approx(9.6 * 2 * 3.141592653589793 / 60)
    assert p["measured_wear_B1"][-1] == pytest.approx(0.1221e-3)
    assert p["prediction_end"] == pytest.approx(86 * 3600)
    assert p["hardness_bushing"] == pytest.approx(21 * 9.80665e6)


def test_a_run_dataset_is_cf_annotated_and_deterministic():
    cfg = load_paper(PATH, "ci")
    a, b = solve(cfg.runs["period_quasistatic"]), solve(cfg.runs["period_quasistatic"])
    check_cf(a)
    for v in a.data_vars:
        if v != "period_wall_time":
            assert (a[v].values == b[v].values).all(), v
