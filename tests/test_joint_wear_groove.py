"""joint_wear: the worn groove in the contact (groove.py) -- the conforming contact against
the elastic-foundation closed form, and a uniform groove against the paper's circle."""
import math

import numpy as np
import pytest

from mechrepro.config import load_paper
from mechrepro.models.joint_wear import groove, quasistatic, setup, wear

from conftest import ROOT

CFG = load_paper(ROOT / "config/papers/joint_wear.yaml")
FB = setup(CFG.runs["wear_interval"])[0]
THETA = np.linspace(-math.pi, math.pi, 720, endpoint=False)


def contact_half_angle(u_row, theta):
    """Half the angle over which u > 0 (one contact zone), the zero crossings interpolated
    linearly between grid nodes: the contact angle of the foundation solution."""
    on = np.flatnonzero(u_row > 0.0)
    if on.size == 0:
        return 0.0
    n, dth = u_row.size, groove.TWO_PI / u_row.size
    lo, hi = on[0], on[-1]
    f_lo = u_row[lo] / (u_row[lo] - u_row[(lo - 1) % n])
    f_hi = u_row[hi] / (u_row[hi] - u_row[(hi + 1) % n])
    return 0.5 * ((hi - lo) + f_lo + f_hi) * dth


@pytest.mark.parametrize("worn", [0.0, 0.5e-3])
@pytest.mark.parametrize("F_N", [5.0, 100.0])
def test_static_load_matches_the_foundation_closed_form(worn, F_N):
    """A static load on a round bushing (new, and worn 0.5 mm all round): the solved
    pressure's peak and contact half-angle are (G4)'s closed form within 1 %, the pin sits
    on the load's line at the Eq.-(11) penetration."""
    psi = 0.7
    e, k_f, p, delta = groove.solve_offset(np.array([F_N]), np.array([psi]), THETA,
                                           np.full(THETA.size, worn), FB)
    R = FB.R_bush + worn
    _, phi0, p_max = groove.foundation_circle(F_N, delta[0], R, FB.R_pin, FB.width)
    u = e[0, 0] * np.cos(THETA) + e[0, 1] * np.sin(THETA) - FB.clearance - worn
    assert contact_half_angle(u, THETA) == pytest.approx(phi0, rel=1e-2)
    assert p.max() == pytest.approx(p_max, rel=1e-2)
    assert math.hypot(*e[0]) - (R - FB.R_pin) == pytest.approx(delta[0], rel=1e-2)
    assert math.atan2(e[0, 1], e[0, 0]) == pytest.approx(psi, abs=1e-3)


@pytest.mark.parametrize("worn", [0.0, 0.5e-3])
def test_a_uniform_groove_is_the_papers_circle(worn):
    """Depth the same at every angle: the groove's period (offset, pressure, sliding speed of
    G6) gives the circle model's force, contact angle and wear factor (Eq. 29) to 1e-6."""
    fb = FB.with_bushing_radius(FB.R_bush + worn)
    g = groove.period(fb, 360, THETA, np.zeros(THETA.size))
    c = quasistatic.one_period(fb, 360)
    assert np.max(np.abs(g["F_N"] / c["F_N"] - 1.0)) < 1e-6
    assert np.max(np.abs(np.angle(np.exp(1j * (g["psi"] - c["psi"]))))) < 1e-6
    G_g = wear.period_wear_factor(g, fb, fb.period)["G"]
    G_c = wear.period_wear_factor(c, fb, fb.period)["G"]
    assert G_g / G_c - 1.0 == pytest.approx(0.0, abs=1e-6)


def test_a_groove_the_pin_wore_spreads_the_load():
    """A load that swings over a 40 deg arc: the interval method (G5 integrated in k x
    periods) calibrates on the points (their mean reaches the measured 10-h depth at the
    calibrated k), and the groove it wears spreads the pressure: the contact half-angle at
    the end exceeds the new bushing's."""
    n = 24
    psi = math.radians(20.0) * np.sin(2 * math.pi * np.arange(n) / n)
    hist = {"F_N": np.full(n, 60.0), "psi": psi, "v_T": np.full(n, 0.0104)}
    dh = np.asarray(CFG.runs["wear_interval"]["parameters"]["measured_increment_B1"])
    pts = [wear.wear_range_points(psi), wear.wear_range_points(psi, scale=0.5)]
    r = groove.interval_method(lambda prof: (hist, FB, 0.0), THETA, pts, dh, 10.0, 20.0, 4.0,
                               n, 2.0)
    for k, t in enumerate(r["tau_cal"]):
        assert np.interp(t, r["tau"], r["mean"][k]) == pytest.approx(dh.sum(), rel=1e-9)
    assert r["refreshes"] == dh.size + 3          # the 5 measured intervals, 10, 14, 18 h
    e0, _, _, _ = groove.solve_offset(hist["F_N"][:1], psi[:1], THETA, np.zeros(THETA.size), FB)
    e1, _, p1, _ = groove.solve_offset(hist["F_N"][:1], psi[:1], THETA, r["profile"], FB)
    u0 = e0[0, 0] * np.cos(THETA) + e0[0, 1] * np.sin(THETA) - FB.clearance
    u1 = e1[0, 0] * np.cos(THETA) + e1[0, 1] * np.sin(THETA) - FB.clearance - r["profile"]
    assert contact_half_angle(u1, THETA) > 2.0 * contact_half_angle(u0, THETA)
