"""chain_drive: the worded claims are well-posed measurements (fixed physical thresholds,
statistics independent of sampling and of a sweep's own maximum)."""
import math

import numpy as np
import pytest

from mechrepro.models.chain_drive import claims as C
from mechrepro.models.chain_drive.galerkin import envelope_statistics
from mechrepro.models.chain_drive.four_bar import elastic_speed_window


def _curve(extra_peak_height):
    sp = np.linspace(300, 500, 401)
    a = 0.5e-3 + 2e-3 * np.exp(-((sp - 400) / 3) ** 2) + extra_peak_height * np.exp(-((sp - 450) / 3) ** 2)
    return sp, a


def test_peak_threshold_is_physical_not_relative_to_the_sweep_maximum():
    sp, a = _curve(0.2e-3)
    assert len(C.peaks(sp, a)) == 2
    # a capped instability elsewhere (50 mm) must not hide the 0.2 mm peak
    a2 = a.copy()
    a2[10:13] = 0.05
    stable = np.ones(sp.size, bool)
    stable[10:13] = False
    assert len(C.peaks(sp, a2, stable=stable)) == 2
    # a ripple below 0.05 mm is not a peak, whatever the rest of the sweep
    sp, a = _curve(0.03e-3)
    assert len(C.peaks(sp, a)) == 1


def test_order_window_brackets_both_span_speeds():
    lo, hi = C.order_window(240.0, 250.0)
    assert lo == pytest.approx(240 * 0.97) and hi == pytest.approx(250 * 1.03)


def test_envelope_statistics_use_whole_tooth_periods_and_every_step():
    per_tooth = 13
    n_periods = 40
    t = np.arange(per_tooth * n_periods + 1) / per_tooth
    u = np.sin(2 * np.pi * t + 0.3)            # steady, forced at the tooth frequency
    s = envelope_statistics(u, per_tooth)
    assert s["steady_ratio"] == pytest.approx(1.0, abs=1e-12)
    decaying = np.exp(-t / 10) * u
    assert envelope_statistics(decaying, per_tooth)["steady_ratio"] < 0.9


def test_elastic_speed_window_follows_each_drive():
    prm = dict(pitch=0.0127, n1=24, n2=24, centre_distance=20.0, axial_stiffness=2e6,
               driven_inertia=0.002)
    lo, hi = elastic_speed_window(prm, [0.25, 1.25])
    prm2 = dict(prm, n1=15, n2=40, driven_inertia=0.0005)
    lo2, hi2 = elastic_speed_window(prm2, [0.25, 1.25])
    rpm = 30 / math.pi
    assert 1100 < hi / 1.25 * rpm < 1300          # 24/24: omega_c ~ 1.2e3 rpm
    assert 6000 < hi2 / 1.25 * rpm < 7200         # 15/40: omega_c ~ 6.6e3 rpm


def test_find_peaks_is_scipys():
    """claims.find_peaks (written out to spare the validation and the notebook the import of
    scipy.signal) finds what scipy.signal.find_peaks(x, prominence=p) finds: random walks,
    rounded to make flat tops and ties, edges, constant and tiny arrays."""
    from scipy.signal import find_peaks

    rng = np.random.default_rng(20261123)
    cases = [np.zeros(0), np.zeros(1), np.array([0.0, 1.0]), np.array([0.0, 1.0, 0.0]),
             np.ones(7), np.array([1.0, 2.0, 2.0, 2.0, 1.0]), np.array([2.0, 2.0, 1.0, 3.0, 3.0]),
             np.array([0.0, 1.0, 1.0, 2.0, 1.0, 1.0, 0.0])]
    for _ in range(400):
        walk = np.cumsum(rng.normal(size=rng.integers(3, 400)))
        cases.append(np.round(walk, int(rng.integers(0, 3))))
    for x in cases:
        for p in (0.0, 0.05, 0.5, 2.0):
            assert np.array_equal(C.find_peaks(x, p), find_peaks(x, prominence=p)[0]), (x, p)


def test_nearest_peak_is_the_one_mode_resonance_on_any_grid():
    """1/A^2 of one damped mode is a quadratic in omega^2: the 3-point estimate is its exact
    peak omega_n sqrt(1 - 2 zeta^2) on any speed grid (the grid point would jump by a step)."""
    wn, zeta = 300.0, 0.03
    peak = wn * np.sqrt(1 - 2 * zeta ** 2)
    for n in (41, 61, 97):
        w = np.linspace(200.0, 400.0, n)
        a = 1.0 / np.sqrt((wn ** 2 - w ** 2) ** 2 + (2 * zeta * wn * w) ** 2)
        assert abs(C.nearest_peak(w, a * 1e9, wn) / peak - 1) < 1e-9


def test_dense_near_elastic_adds_speeds_around_the_resonance():
    """Fig. 9a: n_speeds // 3 extra speeds within +-1 % of omega_c (the narrow Mathieu band
    at 1210.9-1211.9 rpm lies 0.3 % below omega_c = 1214.6 rpm, between two 8 rpm steps)."""
    from mechrepro.config import load_paper
    from mechrepro.models.chain_drive import solver

    run = load_paper("config/papers/chain_drive.yaml").runs["fig09a"]
    prm = dict(run["parameters"])
    prm["speed_min"], prm["speed_max"] = elastic_speed_window(prm, [0.25, 1.25])
    wc = prm["speed_max"] / 1.25
    base = np.linspace(prm["speed_min"], prm["speed_max"], 150)
    dense = solver.dense_near_elastic(run, prm, base, 0.01, 150)
    near = dense[np.abs(dense / wc - 1) <= 0.01]
    assert dense.size == 150 + 50 and np.all(np.diff(dense) > 0)
    assert np.max(np.diff(near)) < 0.9 / 1214.6 * wc   # finer than the 0.9 rpm band


def test_no_steady_amplitude_is_read_at_an_unstable_speed():
    """An unstable periodic orbit has no steady amplitude: a band that holds an unstable
    speed has no level (nan), whatever the orbit's "amplitude" there; the quasi-static
    reference of the amplification is the lowest stable speed."""
    sp = np.linspace(100.0, 200.0, 101)
    amp = np.full(sp.size, 1e-3)
    amp[50] = 25.0                       # an unstable orbit's huge "amplitude" at 150 rpm
    stable = np.ones(sp.size, bool)
    stable[50] = False
    assert math.isnan(C.level_at(sp, amp, [150.0], 0.01, stable))
    assert C.level_at(sp, amp, [120.0], 0.01, stable) == 1e-3
    assert C.unstable_in_bands(sp, stable, [150.0, 120.0], 0.01) == 1
    assert math.isnan(C.amplification(sp, amp, 150.0, 0.05, stable))
    stable[:] = True
    stable[0] = False
    amp[0], amp[50] = 9.0, 4e-3
    assert C.amplification(sp, amp, 150.0, 0.05, stable) == 4.0
