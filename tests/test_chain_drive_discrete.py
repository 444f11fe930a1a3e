"""chain_drive: the discrete-link span (models/chain_drive/discrete.py) against exact
solutions: the beaded string's modes, the string limit at O(N^-2), energy conservation of
the roller set, the release / seating schedule against the four-bar's tooth phases, and
Floquet multipliers that a refined step does not move."""
import copy
import math
from pathlib import Path

import numpy as np
import pytest

from mechrepro.config import load_paper
from mechrepro.models.chain_drive import discrete as D
from mechrepro.models.chain_drive import four_bar, geometry

CONFIG = Path(__file__).resolve().parents[1] / "config" / "papers" / "chain_drive.yaml"


def stiffness(n: int, tension: float, spacing: float) -> np.ndarray:
    """Transverse stiffness matrix of n rollers between fixed ends: T/a tridiag(-1, 2, -1)."""
    return tension / spacing * (2 * np.eye(n) - np.eye(n, k=1) - np.eye(n, k=-1))


def modal_frequencies(n: int, tension: float, mass: float, spacing: float) -> np.ndarray:
    """Natural frequencies [rad/s] of the roller set without motion (eigenvalues of K / m)."""
    return np.sqrt(np.linalg.eigvalsh(stiffness(n, tension, spacing)) / mass)


def energy(y, v, y_left, y_right, tension: float, mass: float, spacing: float):
    """Kinetic + elastic transverse energy of the rollers (ends included in the links)."""
    y = np.asarray(y, float)
    row = y.shape[1:]
    full = np.concatenate([np.broadcast_to(y_left, row)[None], y,
                           np.broadcast_to(y_right, row)[None]])
    return 0.5 * mass * np.sum(v * v, axis=0) + 0.5 * tension / spacing * np.sum(
        np.diff(full, axis=0) ** 2, axis=0)


def test_modes_without_motion_are_the_beaded_strings():
    """N masses m at spacing a under tension T between fixed ends:
    omega_k = 2 sqrt(T / (m a)) sin(k pi / (2 (N + 1)))."""
    for n, T, m, a in ((1, 400.0, 7.7e-3, 12.7e-3), (19, 400.0, 7.7e-3, 12.7e-3),
                       (40, 123.0, 1e-2, 5e-3)):
        got = modal_frequencies(n, T, m, a)
        assert np.allclose(got, D.beaded_frequencies(n, T, m, a), rtol=1e-12, atol=0)


def test_modes_approach_the_strings_at_second_order():
    """At fixed span L and mass rho L the first five frequencies tend to k pi sqrt(T/rho)/L
    with an error ~ (k pi/(N+1))^2 / 24: observed order 2."""
    L, rho, T = 20 * 12.7e-3, 0.61, 400.0
    exact = np.arange(1, 6) * np.pi / L * math.sqrt(T / rho)
    errs = []
    for n in (15, 31, 63, 127):
        a = L / (n + 1)
        errs.append(np.abs(modal_frequencies(n, T, rho * a, a)[:5] / exact - 1))
    order = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    assert np.all(np.abs(order[-1] - 2.0) < 0.02), order
    assert np.all(np.diff(np.array(errs), axis=0) < 0)


def test_energy_of_a_fixed_roller_set_is_conserved_to_the_integrators_order():
    """No release, no seating, no damping, fixed ends, constant tension: RK4 loses energy
    at its own order (>= 4 in the step), and little of it."""
    n, T, m, a = 12, 400.0, 0.61 * 12.7e-3, 12.7e-3
    rng = np.random.default_rng(0)
    y0, v0 = rng.normal(size=(n, 1)) * 1e-3, rng.normal(size=(n, 1)) * 1e-2
    w_max = D.beaded_frequencies(n, T, m, a)[-1]
    t_end = 20 * 2 * np.pi / D.beaded_frequencies(n, T, m, a)[0]
    drift = []
    for steps in (8000, 16000):
        t = np.linspace(0.0, t_end, steps + 1)
        assert w_max * (t[1] - t[0]) < 2.0        # inside RK4's stability interval
        zeros = np.zeros(2 * steps + 1)
        y, v, _ = D.rk4(y0, v0, t, zeros, zeros, np.full(steps, T / (m * a)), 0.0)
        e0, e1 = (energy(yy, vv, 0.0, 0.0, T, m, a)[0] for yy, vv in ((y0, v0), (y, v)))
        drift.append(abs(e1 / e0 - 1))
    assert drift[0] < 1e-3
    assert math.log2(drift[0] / drift[1]) > 3.9, drift


def _prm(scene="fig07_tension", **over):
    cfg = load_paper(CONFIG, "ci")
    run = copy.deepcopy(cfg.runs[scene])
    run["parameters"].update(over)
    return run, run["parameters"]


@pytest.mark.parametrize("cd", [20.25, 20.5, 19.7])
def test_release_and_seating_follow_the_four_bar(cd):
    """The driving sprocket seats a roller when its tooth phase wraps (t = 0, tau) and the
    driven one releases a roller when its phase wraps (t_r): the phases of four_bar."""
    run, prm = _prm(centre_distance=cd * 12.7e-3)
    w = 400.0 / geometry.RPM
    tau, t_r, n_s = D.events(prm, w)
    geo = geometry.span_geometry(prm, True)
    assert n_s == round(geo["L_short"] / prm["pitch"]) - 1
    t = np.linspace(0.0, tau, 200001)[1:-1]
    ph = four_bar.tooth_phases(t, w, n1=int(prm["n1"]), n2=int(prm["n2"]), p_c=prm["pitch"],
                               f_p=geo["f_p"])
    assert np.all(np.diff(ph["phase1"]) > 0)                 # no engagement inside (0, tau)
    wraps = np.flatnonzero(np.diff(ph["phase2"]) < -0.5)
    assert len(wraps) == 1
    assert abs(t[wraps[0]] - t_r) <= 2 * (t[1] - t[0])
    # the span is long from the release to the next seating (four_bar.long_span)
    long = four_bar.long_span(ph["phase1"], ph["phase2"])
    assert np.all(long[t > t_r + 1e-6 * tau]) and not np.any(long[t < t_r - 1e-6 * tau])


def test_floquet_multipliers_do_not_move_under_step_refinement():
    """The largest multiplier and the periodic amplitude at 200 and 400 steps per tooth
    period agree to within 1e-3 (RK4: the difference shrinks ~16x per halving)."""
    run, prm = _prm()
    run["effects"] = [e for e in run["effects"] if e != "impact"]
    w = 450.0 / geometry.RPM
    got = [D.periodic_orbit(run, prm, w, n) for n in (100, 200, 400)]
    rho = [g["rho"] for g in got]
    amp = [g["amplitude"] for g in got]
    assert all(g["residual"] < 1e-9 * max(amp) + 1e-15 for g in got)
    assert abs(rho[2] - rho[1]) < 1e-3 and abs(amp[2] / amp[1] - 1) < 1e-3, (rho, amp)
    assert abs(rho[2] - rho[1]) <= abs(rho[1] - rho[0]) + 1e-12


def test_a_step_beyond_rk4s_stability_is_refused():
    """At 50 rpm and 800 N, 100 steps per tooth period put the highest roller mode outside
    RK4's stability interval: refused with the steps needed, never a blown-up multiplier."""
    from mechrepro.models.chain_drive.errors import StabilityError

    run, prm = _prm(static_tension=800.0)
    w = 50.0 / geometry.RPM
    with pytest.raises(StabilityError, match="at least"):
        D.period_map(run, prm, w, 100)
    assert D.periodic_orbit(run, prm, w, 200)["rho"] < 1.0


def test_the_engaging_links_extra_tension_acts_on_the_last_roller_alone():
    """impact_share < 1: the link to the driving end carries (1 - share) D_imp more than the
    others; the accelerations are those of the stiffness with that link's tension raised."""
    n, T, extra, m, a = 7, 400.0, 150.0, 7.7e-3, 12.7e-3
    rng = np.random.default_rng(1)
    y, right = rng.normal(size=(n, 1)), 0.3
    K = stiffness(n, T, a)
    K[-1, -1] += extra / a
    want = -(K @ y) / m
    want[-1] += (T + extra) / (m * a) * right
    got = np.empty_like(y)
    D._accel(y, np.zeros_like(y), 0.0, right, T / (m * a), 0.0, extra / (m * a), 0.0, got)
    assert np.allclose(got, want, rtol=1e-12)


@pytest.mark.parametrize("effect, option", [("external_load", None),
                                            (None, "stationary_string")])
def test_what_the_discrete_span_cannot_honour_is_refused_by_name(effect, option):
    from mechrepro.models.chain_drive.errors import UnknownChoice

    run, prm = _prm("fig08_external")
    run["resolution"] = {"method": "discrete", "steps_per_period": 200}
    run["effects"] = [e for e in run["effects"] if e in ("speed_tensioning", "polygonal_rigid",
                                                         "end_excitation", effect)]
    if option:
        run.setdefault("options", {})[option] = True
    with pytest.raises(UnknownChoice, match="discrete span"):
        D.sweep(run, prm, np.array([300.0 / geometry.RPM]), run["resolution"])


def test_the_sag_load_settles_into_the_beaded_strings_static_sag():
    """Eq. (2-36)'s kappa P_t on the rollers: a constant load per mass q on every roller of
    the forced column settles (damped, fixed ends) into the static deflection K y = m q, the
    beaded string's parabola y_i = q m i (N + 1 - i) a / (2 T); the map's unit columns feel
    no load."""
    n, T, m, a, q = 9, 400.0, 7.7e-3, 12.7e-3, 3.0
    steps, t_end = 20000, 2.0
    t = np.linspace(0.0, t_end, steps + 1)
    zeros = np.zeros(2 * steps + 1)
    y, _, _ = D.rk4(np.zeros((n, 2)), np.zeros((n, 2)), t, zeros, zeros,
                    np.full(steps, T / (m * a)), 40.0, load=np.full(steps, q))
    i = np.arange(1, n + 1)
    assert np.allclose(y[:, 1], q * m * i * (n + 1 - i) * a / (2 * T), rtol=1e-6)
    assert np.all(y[:, 0] == 0.0)


def test_the_impact_is_resolved_by_its_own_steps_so_the_orbit_converges_in_the_step():
    """With the impact on, the 28 us contact gets steps_per_period / CONTACT_STEPS steps of
    its own (an averaged pulse in one ~20 us step made the amplitude jump by 1-2 % between
    levels near a multiplier of 0.99): the Fig. 6 order-3 peak at 133-450 steps agrees to
    2e-4 and converges monotonically (successive differences shrink), the multiplier to
    1e-5."""
    run, prm = _prm("fig07_tension")
    tau, t_r, _ = D.events(prm, 371.674 / geometry.RPM)
    t_i = D._contact_time(run, prm)
    seg = D._segments(tau, t_r, 300, t_i)
    assert seg[0][-1] == t_i and len(seg[0]) - 1 == 12
    got = [D.periodic_orbit(run, prm, 371.674 / geometry.RPM, n) for n in (133, 200, 300, 450)]
    amp = np.array([g["amplitude"] for g in got])
    rho = np.array([g["rho"] for g in got])
    assert np.ptp(amp) < 2e-4 * amp[-1] and np.ptp(rho) < 1e-5, (amp, rho)
    d = np.diff(amp)
    assert np.all(d < 0) and np.all(np.abs(d[1:]) < np.abs(d[:-1])), amp


def test_peak_levels_that_agree_to_a_thousandth_are_converged_without_contracting():
    """A figure title says what the levels say: levels within 0.1 % agree (their differences
    are the vertex fit's and the sampling's, no order to measure); a larger spread needs a
    contracting sequence of at least first order."""
    from mechrepro.models.chain_drive import figures as F

    assert F.levels_converged(2.5e-4, math.nan)
    assert F.levels_converged(0.01, 1.5)
    assert not F.levels_converged(0.01, math.nan)
    assert not F.levels_converged(0.26, 0.43)
