"""joint_wear unit chain: Eq. (32) with the printed units, checked by dimensional analysis,
and the consequences of each possible reading for the wear range the paper's numbers need."""
import math

import numpy as np
import pytest

from mechrepro.config import load_paper
from mechrepro.models.joint_wear import setup, quasistatic, wear

from conftest import ROOT

CFG = load_paper(ROOT / "config/papers/joint_wear.yaml")

# dimensions as exponents of (m, kg, s)
M_ = np.array([1, 0, 0])
N_ = np.array([1, 1, -2])          # kg m / s^2
PA = N_ - 2 * M_                   # N / m^2
ONE = np.zeros(3, int)


def dim_eq32(K, H):
    """[dh] of Eq. (32): K / (H A_a) * F_N * S * AB / L_arc."""
    A = 2 * M_
    return K - H - A + N_ + M_ + M_ - M_


def test_eq32_is_a_length_only_with_the_bare_hardness_number():
    # K in Pa^-1 as Tables 3-4 print it, H the bare number 21 of Table 2: a length
    assert np.array_equal(dim_eq32(-PA, ONE), M_)
    # H in Pa (21 HB = 2.06e8 Pa) with K in Pa^-1: not a length
    assert not np.array_equal(dim_eq32(-PA, PA), M_)
    # Archard's dimensionless K needs H in Pa: consistent, but then the printed unit is wrong
    assert np.array_equal(dim_eq32(ONE, PA), M_)
    # the wear factor G = F S / (w L) is N/m and k = K/H_number is m^2/N
    assert np.array_equal(N_ + M_ - M_ - M_, N_ - M_)
    assert np.array_equal((-PA - ONE) + (N_ - M_), M_)


def test_unit_chain_functions_and_the_hardness_number():
    H = CFG.runs["wear_prediction"]["parameters"]["hardness_bushing"]     # SI: Pa
    assert H == pytest.approx(21 * 9.80665e6)
    assert wear.hardness_number(H) == pytest.approx(21.0)
    K = 7.8118e-11
    k = wear.k_from_table(K, H)
    assert k == pytest.approx(K / 21)
    assert wear.table_from_k(k, H) == pytest.approx(K)
    # dimensionless Archard coefficient of the paper's mean: inside dry Al-on-steel 1e-4..1e-2
    KA = wear.archard_dimensionless(k, H)
    assert KA == pytest.approx(K * 9.80665e6)
    assert 1e-4 < KA < 1e-2


def test_only_the_bare_number_reading_gives_a_wear_range_inside_the_bushing():
    """Eq. (29) solved for L_arc with our mean force and sliding distance: the length of
    bushing that the paper's coefficient must wear to produce its measured increments."""
    run = CFG.runs["period_quasistatic"]
    fb = setup(run)[0]
    f = wear.period_wear_factor(quasistatic.one_period(fb, 360), fb, fb.period)
    p = run["parameters"]
    M = wear.periods_per_interval(2.0, fb.period)
    dh = np.mean(p["measured_increment_B1"]) / M
    K, H = 7.8118e-11, p["hardness_bushing"]
    circumference = 2 * math.pi * fb.R_bush
    L = {"K/21 (chosen)": wear.implied_wear_range(wear.k_from_table(K, H), dh, f["F_N_mean"], f["S"], fb.width),
         "K as k (H dropped)": wear.implied_wear_range(K, dh, f["F_N_mean"], f["S"], fb.width),
         "K dimensionless, H in Pa": wear.implied_wear_range(K / H, dh, f["F_N_mean"], f["S"], fb.width)}
    assert f["L_arc"] < L["K/21 (chosen)"] < circumference          # a physical wear range
    assert L["K as k (H dropped)"] > 10 * circumference              # eleven circumferences
    assert L["K dimensionless, H in Pa"] < 1e-6                      # nanometres
    assert L["K/21 (chosen)"] == pytest.approx(0.03, rel=0.3)


def test_calibration_uses_the_printed_increments():
    p = CFG.runs["wear_prediction"]["parameters"]
    h = np.asarray(p["measured_wear_B2"])
    dh = np.asarray(p["measured_increment_B2"])
    # Table 4 prints increments that differ from its cumulative column at P3 and P4
    assert not np.allclose(np.diff(np.r_[0, h]), dh, rtol=1e-3)
    G = lambda R: 1e5  # noqa: E731
    k, kmean, _ = wear.calibrate(h, 2.0, 6.25, 0.01, G, dh_measured=dh)
    assert np.allclose(k * 1e5 * 1152, dh)
    with pytest.raises(ValueError, match="increments"):
        wear.calibrate(h, 2.0, 6.25, 0.01, G, dh_measured=dh[:-1])
