"""saw_chain: geometry, exact kinematics, the difference method and its hard cases."""
import math

import numpy as np
import pytest

from mechrepro.solve import solve
from mechrepro.models.saw_chain.difference import RoundoffError
from mechrepro.models.saw_chain.geometry import MeshingError, pitch_radius, stage_angles
from mechrepro.models.saw_chain.kinematics import stage_derivatives, stage_positions

P = dict(tie_strap_pitch=8.91e-3, drive_link_pitch=7.56e-3, teeth=8,
         sprocket_speed=6550 * 2 * math.pi / 60, tie_strap_mass=1.906e-3,
         drive_link_mass=1.296e-3, tie_straps_tight_side=32, drive_links_tight_side=32,
         textbook_phase=-math.pi / 8, textbook_mass=0.102464)


def run(K=200, outputs=("exact_reference", "textbook"), **over):
    """A run of the difference_method solver naming ``outputs`` (what the config loader builds;
    saw_chain declares no effects)."""
    return {"paper": "saw_chain", "run": "t", "scene": "t", "solver": "difference_method",
            "effects": [], "outputs": list(outputs),
            "resolution": {"K": K}, "options": {}, "parameters": {**P, **over}}


def difference_method_loop(p1, p2, z, omega, m_L, m_C, M, N, K):
    """Tight-side velocity and total dynamic load x over one period, step by step: the whole
    difference method as a per-step Python loop (the paper's MATLAB style), the independent
    reference the vectorised solver is tested against."""
    R = math.sqrt(p1**2 + p2**2 + 2 * p1 * p2 * math.cos(math.pi / z)) / (2 * math.sin(math.pi / z))
    Tx = p1 + 2 * p2
    phi1 = 2 * math.asin(p2 / (2 * R))
    phi2 = phi1 + 2 * math.asin(p1 / (2 * R))
    m_tight = M * m_L + N * m_C
    velocity, load = [R * omega], [0.0]
    v_prev = vm_prev = R * omega
    for L, m_link, span in ((p2, m_C, phi1), (p1, m_L, phi2 - phi1)):
        dt = span / K / omega
        x_prev = xm_prev = None
        for i in range(K + 1):
            phi = span * i / K
            xl = Tx + R * math.sin(phi)
            yl = R * (1.0 - math.cos(phi))
            xt = xl - math.sqrt(L * L - yl * yl)
            xm = 0.5 * (xl + xt)
            if i > 0:
                v, vm = (xt - x_prev) / dt, (xm - xm_prev) / dt
                a, am = (v - v_prev) / dt, (vm - vm_prev) / dt
                velocity.append(v)
                load.append(m_link * am + m_tight * a)
                v_prev, vm_prev = v, vm
            x_prev, xm_prev = xt, xm
        vm_prev = v_prev  # A2 starts with O2's values at t1
    return velocity, load


def test_pitch_radius_closes_the_polygon_and_matches_regular_polygon():
    p1, p2, z = P["tie_strap_pitch"], P["drive_link_pitch"], 8
    R = pitch_radius(p1, p2, z)
    assert stage_angles(p1, p2, R)[1] == pytest.approx(2 * math.pi / z, rel=1e-14)
    # equal pitches: a regular 2z-gon, circumradius p / (2 sin(pi / 2z))
    assert pitch_radius(0.01, 0.01, 10) == pytest.approx(0.01 / (2 * math.sin(math.pi / 20)), rel=1e-14)


def test_exact_derivatives_match_finite_differences_of_positions():
    R, L, Tx, w = 0.0211, 0.00756, 0.024, 686.0
    phi = np.linspace(0.01, 0.35, 7)
    h = 1e-5
    pos = lambda ph: stage_positions(ph, R, L, Tx)  # noqa: E731
    d = stage_derivatives(phi, R, L, w)
    for key, dkey in (("trail_x", "trail_vx"), ("mid_x", "mid_vx"), ("mid_y", "mid_vy")):
        fd = (pos(phi + h)[key] - pos(phi - h)[key]) / (2 * h) * w
        np.testing.assert_allclose(d[dkey], fd, rtol=1e-7)
    # second difference: a larger step, since round-off grows like eps*x/h^2
    h2 = 2e-4
    fd2 = (pos(phi + h2)["trail_x"] - 2 * pos(phi)["trail_x"] + pos(phi - h2)["trail_x"]) / h2**2 * w**2
    np.testing.assert_allclose(d["trail_ax"], fd2, rtol=1e-5, atol=1e-2)


def test_tight_side_speed_bounds_and_mean_are_closed_form():
    ds = solve(run(K=2000, outputs=["exact_reference"]))
    v = ds["tight_side_velocity_exact"].values
    R_omega = float(ds["pitch_radius"]) * P["sprocket_speed"]
    assert v.max() == pytest.approx(R_omega, rel=1e-12)  # at both stage ends
    assert v[0] == pytest.approx(R_omega) and v[-1] == pytest.approx(R_omega)
    t = ds["t"].values
    mean = np.trapezoid(v, t) / t[-1]
    chain_speed = 8 * (P["tie_strap_pitch"] + P["drive_link_pitch"]) * 6550 / 60
    assert mean == pytest.approx(chain_speed, rel=1e-6)


def test_difference_method_converges_first_order_to_exact():
    errs, Ks = [], [100, 300, 1000, 3000]
    for K in Ks:
        ds = solve(run(K=K, outputs=["exact_reference"]))
        errs.append(float(ds["dynamic_load_x_error_pointwise"]))
    assert all(a > b for a, b in zip(errs, errs[1:]))
    slope = np.polyfit(np.log(1.0 / np.array(Ks)), np.log(errs), 1)[0]
    assert 0.8 < slope < 1.2


def test_vectorised_equals_per_step_loop():
    K = 500
    ds = solve(run(K=K, outputs=[]))
    v, F = difference_method_loop(P["tie_strap_pitch"], P["drive_link_pitch"], 8,
                                  P["sprocket_speed"], P["tie_strap_mass"], P["drive_link_mass"],
                                  32, 32, K)
    np.testing.assert_allclose(ds["tight_side_velocity"].values, v, rtol=1e-11)
    # loads are second differences: agreement to their round-off bound
    np.testing.assert_allclose(ds["dynamic_load_x"].values, F, rtol=0,
                               atol=float(ds["roundoff_load_bound"]))


def test_loads_scale_with_omega_squared_by_construction():
    """Positions depend on omega*t only: every load scales with omega^2 (not a hard case)."""
    slow = solve(run(K=1000))
    fast = solve(run(K=1000, sprocket_speed=12000 * 2 * math.pi / 60))
    ratio = (12000 / 6550) ** 2
    for q in ("dynamic_load_x_max", "dynamic_load_x_min", "dynamic_load_x_exact_max"):
        assert float(fast[q]) == pytest.approx(ratio * float(slow[q]), rel=1e-9)


@pytest.mark.parametrize("over", [{"teeth": 2}, {"tie_strap_pitch": 0.0},
                                  {"drive_link_pitch": -1e-3}, {"teeth": 7.5}])
def test_invalid_chain_is_a_clear_error(over):
    with pytest.raises(MeshingError, match="meshing|positive|integer"):
        solve(run(**over))


def test_same_run_same_numbers_bit_for_bit():
    a, b = solve(run(K=777)), solve(run(K=777))
    for name in a.data_vars:
        assert np.array_equal(a[name].values, b[name].values)
