"""The tensioning design map (issue 61): the lowest critical speed over N_d >= 2 against the
rolling radius and amplitude under a buckling margin."""
import copy

import numpy as np
import pytest

from mechrepro.config import load_paper
from mechrepro.models.disk_tension import design, rotation
from mechrepro.models.disk_tension.axisym import AxisymDisk
from mechrepro.solve import _solve_once

CFG = "config/papers/disk_tension.yaml"
E, NU, RHO, B, H = 206e9, 0.3, 7850.0, 0.1275, 1.31e-3


@pytest.fixture(scope="module")
def cfg():
    return load_paper(CFG, "default")


def design_run(cfg, rolling_radius=(45, 65, 85, 105), n_elements=16, scene="design_map",
               **parameters):
    run = copy.deepcopy(cfg.runs[scene])
    run["resolution"] = {"n_elements": n_elements}
    run["options"] = {"timing_min_s": 0.0}
    run["parameters"].update(rolling_radius=[x * 1e-3 for x in rolling_radius], design_steps=7,
                             **parameters)
    return run


@pytest.fixture(scope="module")
def mapped(cfg):
    return _solve_once(design_run(cfg))


def test_the_batched_critical_speed_is_the_generalised_eigenproblem_s():
    """design.speeds (one symmetric eigen-decomposition per load factor) against
    rotation.critical_speed (scipy's generalised solver): 1e-9 relative; NaN once the
    stressed K is no longer positive definite, inf for N_d = 0."""
    d = AxisymDisk(r_f=0.025, b=B, h=H, E=E, nu=NU, rho=RHO, n_d=range(5), n_elements=16)
    kw = dict(omega=1.0, rho=RHO, nu=NU, r_f=0.025, b=B)
    Kc = d.stress_stiffness((lambda r: rotation.centrifugal_stress(r, **kw)[0],
                             lambda r: rotation.centrifugal_stress(r, **kw)[1]))
    Kr = d.stress_stiffness((lambda r: -2e6 * np.exp(-((r - 0.06) / 0.01) ** 2),
                             lambda r: 3e6 * (r / B) ** 2 - 1e6))
    factors = [0.0, 0.5, 3.0, 40.0]
    for n, pen in zip(range(5), design.pencils(d.K, Kr, d.M, Kc, range(5))):
        got, w2 = design.speeds(pen, factors)
        want = [rotation.critical_speed(d.K[n] + a * Kr[n], d.M[n], Kc[n], n) for a in factors]
        np.testing.assert_array_equal(np.isnan(got), np.isnan(want))
        np.testing.assert_array_equal(np.isinf(got), np.isinf(want))
        ok = np.isfinite(want)
        np.testing.assert_allclose(got[ok], np.asarray(want)[ok], rtol=1e-9)
        np.testing.assert_array_equal(np.isnan(got), w2 <= 0)
    assert np.isnan(design.speeds(design.pencils(d.K, Kr, d.M, Kc, [0])[0], [40.0])[0]).all()


def test_at_zero_intensity_the_map_is_the_untensioned_critical_speed(mapped):
    cs = mapped["design_critical_speed"].values[:, 0, :]
    untensioned = mapped["critical_speed_untensioned"].values
    np.testing.assert_allclose(cs, np.broadcast_to(untensioned, cs.shape), rtol=1e-9)
    low = design.lowest_map(mapped)[:, 0]
    np.testing.assert_allclose(low, np.min(untensioned[2:]), rtol=1e-9)


def test_the_buckling_margin_is_respected(mapped):
    """Every optimum rolls at most A_cr / m; where the margin binds it rolls exactly that; the
    disk at the optimum stands (every at-rest frequency real), and the map is buckled only
    beyond A_cr."""
    a_cr = mapped["design_buckling_amplitude"].values
    m = mapped["design_margin"].values
    a = mapped["design_best_amplitude"].values
    binds = mapped["design_best_binds"].values
    assert np.all(a <= a_cr[None, :] / m[:, None] * (1 + 1e-12))
    at = binds == design.BINDS.index("buckling margin")
    assert at.any()
    np.testing.assert_allclose(a[at], np.broadcast_to(a_cr[None, :] / m[:, None], a.shape)[at],
                               rtol=1e-12)
    assert np.all(mapped["design_best_frequency_ratio"].values > 0)
    amp = mapped["design_amplitude"].values
    gone = np.isnan(design.lowest_map(mapped))
    np.testing.assert_array_equal(gone, amp >= a_cr[:, None])


def test_the_optimum_is_what_a_direct_critical_speed_run_gives_there(cfg, mapped):
    """Re-run the scene critical_speed at the optimum's r_c and amplitude: the lowest critical
    speed over N_d >= 2 is the design map's, to 1e-9 (the residual stress is linear in A)."""
    rows = design.table([(25.0, mapped)])
    for r in (dict(zip(design.COLUMNS, row)) for row in rows):
        run = copy.deepcopy(cfg.runs["critical_speed"])
        run["resolution"] = {"n_elements": 16}
        run["options"] = {"timing_min_s": 0.0}
        run["parameters"].update(rolling_radius=[r["r_c_opt_mm"] * 1e-3],
                                 temperature_amplitude=r["amplitude_opt_degc"],
                                 nodal_diameters=list(range(11)))
        ds = _solve_once(run)
        cs = ds["critical_speed"].values[0]
        assert not np.isnan(cs).any()
        assert np.min(cs[2:]) * design.RPM == pytest.approx(r["critical_speed_opt_rpm"], rel=1e-9)
        assert int(np.argmin(cs[2:])) + 2 == r["lowest_mode_nd"]


@pytest.mark.parametrize("r_f", [0.025, 0.075])
def test_the_highest_harmonic_of_the_map_never_decides(cfg, r_f):
    """N_d = 10, the map's last harmonic, is never the lowest critical speed of a standing
    disk nor the first to buckle (at r_f = 75 mm the lowest is N_d = 5 and rolling near the
    rim buckles N_d = 9 first): the map's harmonics are enough."""
    ds = _solve_once(design_run(cfg, rolling_radius=(45, 65, 85, 95, 105, 115), clamp_radius=r_f))
    cs = ds["design_critical_speed"].values
    standing = ~np.isnan(cs).any(axis=-1)
    assert np.all(np.argmin(cs[standing][:, 2:], axis=-1) + 2 < 10)
    assert np.all(ds["design_buckling_mode"].values < 10)


def test_a_map_with_no_standing_disk_has_no_optimum(cfg):
    """A design table row whose every r_c has buckled says 'buckled', never a number."""
    ds = _solve_once(design_run(cfg, rolling_radius=(65,)))
    gone = ds.copy()
    gone["design_best_speed"] = gone["design_best_speed"] * np.nan
    row = dict(zip(design.COLUMNS, design.table([(25.0, gone)])[1]))
    assert row["binds"] == "buckled" and np.isnan(row["critical_speed_opt_rpm"])


def test_the_cutting_heat_compresses_the_rim_and_lowers_the_critical_speed(cfg):
    """Effect cutting_heat (scene design_map_in_cut): a rim hotter than the eye gives hoop
    compression at the rim, and the untensioned blade in the cut has a lower critical speed
    than cold; at a zero rim temperature rise the in-cut map is the cold one to round-off."""
    cold = _solve_once(design_run(cfg))
    hot = _solve_once(design_run(cfg, scene="design_map_in_cut"))
    assert float(hot["heat_sigma_theta"].values[-1]) < 0 < float(hot["heat_temperature"].values[-1])
    assert design.lowest_map(hot)[0, 0] < design.lowest_map(cold)[0, 0]
    zero = _solve_once(design_run(cfg, scene="design_map_in_cut", rim_temperature_rise=0.0))
    np.testing.assert_allclose(design.lowest_map(zero), design.lowest_map(cold), rtol=1e-9)
    assert float(hot["design_rim_temperature_rise"]) > 0
    assert float(cold["design_rim_temperature_rise"]) == 0
