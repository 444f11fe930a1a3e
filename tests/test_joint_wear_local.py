"""joint_wear: local Archard wear (a depth per bushing angle) against the paper's uniform
depth over the wear range (Eq. 29, Fig. 14), in the limit where they must agree."""
import math

import numpy as np
import pytest

from mechrepro.config import load_paper
from mechrepro.models.joint_wear import setup, wear

from conftest import ROOT

CFG = load_paper(ROOT / "config/papers/joint_wear.yaml")
FB = setup(CFG.runs["wear_interval"])[0]


def sweep(arc, n=4000, delta=1e-9, F=60.0, v=0.01):
    """The contact point sweeping the arc at a uniform rate (a triangle wave in time: every
    angle of the arc gets the same contact time), constant force, sliding speed and a small
    penetration (a patch much narrower than the arc)."""
    t = np.arange(n) / n
    psi = arc * (np.abs(2.0 * t - 1.0) - 0.5)
    return {"F_N": np.full(n, F), "delta": np.full(n, delta), "v_T": np.full(n, v), "psi": psi}


def test_local_equals_uniform_for_a_uniform_sweep_with_a_small_patch():
    h = sweep(math.radians(60.0))
    theta = np.linspace(-math.pi, math.pi, 7200, endpoint=False)
    local = wear.local_wear_per_period(h, FB, FB.period, theta)
    G = wear.period_wear_factor(h, FB, FB.period)["G"]
    pts = wear.wear_range_points(h["psi"])
    at = np.interp(pts, theta, local, period=2 * math.pi)
    assert np.all(np.abs(at / G - 1.0) < 2e-2)                  # every Eq.-35 point
    AB = wear.period_wear_factor(h, FB, FB.period)["AB_mean"]
    assert AB / (FB.R_bush * math.radians(60.0)) < 0.05        # the limit: patch << arc


def test_local_wear_conserves_the_archard_volume():
    """w R * integral of dh dtheta = k F_N S (Eq. 26), whatever the distribution."""
    fb = FB
    from mechrepro.models.joint_wear import quasistatic
    h = quasistatic.one_period(fb, 360)
    theta = np.linspace(-math.pi, math.pi, 3600, endpoint=False)
    local = wear.local_wear_per_period(h, fb, fb.period, theta)
    vol = fb.width * fb.R_bush * local.sum() * (2 * math.pi / theta.size)
    f = wear.period_wear_factor(h, fb, fb.period)
    assert vol == pytest.approx(f["F_N_mean"] * f["S"], rel=2e-2)


def test_local_prediction_reproduces_the_uniform_one_in_the_limit():
    """The whole interval method (calibration on the Eq.-35 points, profile fed back) gives
    the uniform model's 86-h wear when every period is a uniform sweep with a small patch."""
    h_meas = np.asarray(CFG.runs["wear_interval"]["parameters"]["measured_wear_B1"])
    dh = np.asarray(CFG.runs["wear_interval"]["parameters"]["measured_increment_B1"])
    arc = math.radians(60.0)

    def one(fb_w):
        return sweep(arc, n=2000)
    theta = np.linspace(-math.pi, math.pi, 3600, endpoint=False)
    pts = wear.wear_range_points(one(FB)["psi"])
    nodes, mean, peak, k, prof = wear.local_predict(
        dh, 2.0, 86.0, 2.0, FB.period, wear.mean_circle_increment(FB, FB.period, one, theta, pts),
        theta, pts)

    def G(R):
        fb_w = FB.with_bushing_radius(R)
        return wear.period_wear_factor(one(fb_w), fb_w, FB.period)["G"]
    _, k_u, _ = wear.calibrate(h_meas, 2.0, FB.period, FB.R_bush, G, dh_measured=dh)
    _, h_u, _ = wear.predict(h_meas[-1], 10.0, 86.0, 2.0, k_u, FB.period, FB.R_bush, G)
    assert mean[0] == pytest.approx(h_meas[-1], rel=1e-9)       # calibrated on Table 3
    assert mean[-1] == pytest.approx(h_u[-1], rel=2e-2)
    assert peak[-1] / mean[-1] < 1.05                            # flat: the uniform profile


def test_measuring_points_lie_on_the_arc_centred_on_its_midpoint():
    """Eq. (33)'s 8 points "uniformly distributed within the main wear range": at the middle
    of 8 equal parts of the contact arc, so every point lies on the arc, also where the
    contact point dwells near one end of it (there the time-weighted mean angle, the former
    centre, lies a quarter of the arc off the midpoint and 2 points fell off the arc)."""
    t = np.arange(720) / 720
    arc, mid = math.radians(60.0), 3.0          # the arc straddles the +-pi cut
    psi = np.angle(np.exp(1j * (mid + arc * (np.sin(np.pi * t) ** 8 - 0.5))))
    pts = wear.wear_range_points(psi)
    off = np.angle(np.exp(1j * (pts - mid)))
    assert np.all(np.abs(off) < 0.5 * arc)
    assert off == pytest.approx(arc * ((np.arange(8) + 0.5) / 8 - 0.5), abs=1e-4)
    # the contact path of the wear scenes (assumed F): all 8 on the arc
    from mechrepro.models.joint_wear import quasistatic
    h = quasistatic.one_period(FB, 360)
    lo, hi = wear.contact_arc_bounds(h["psi"])
    rel = np.angle(np.exp(1j * (wear.wear_range_points(h["psi"]) - lo)))
    assert np.all((rel > 0) & (rel < hi - lo))
