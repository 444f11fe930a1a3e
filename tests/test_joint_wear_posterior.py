"""joint_wear (#60 item 1): the load point as a distribution -- the rounding noise of the
printed increments, the exact integral over F's direction, the likelihood region, the two
readings of the calibration's bushing, and a synthetic paper whose load point the fit must
recover within its credible set."""
import copy
import math

import numpy as np
import pytest

from mechrepro.config import load_paper
from mechrepro.models.joint_wear import solver
from mechrepro.solve import compute

from conftest import ROOT

CFG = load_paper(ROOT / "config/papers/joint_wear.yaml")


def test_rounding_noise_is_half_a_printed_digit_uniform():
    sig = solver.rounding_sigma([0.0229, 0.01956, 0.1])
    assert sig == pytest.approx([1e-4 / math.sqrt(12) / 0.0229, 1e-5 / math.sqrt(12) / 0.01956,
                                 0.1 / math.sqrt(12) / 0.1], rel=1e-12)


def test_laplace_weight_is_the_gaussian_integral_over_the_direction():
    """Linear ratios r_i + s delta: the closed form equals the quadrature to 1e-9."""
    rng = np.random.default_rng(CFG.raw["seed"])
    r, sig, slope = rng.normal(0, 2e-3, 10), rng.uniform(1e-3, 2e-3, 10), -0.15
    chi2, width, logw, shift = solver.laplace_log_weight(r, sig, slope)
    d = np.linspace(-0.2, 0.2, 400_001)
    f = np.exp(-0.5 * np.sum(((r[:, None] + slope * d) / sig[:, None]) ** 2, axis=0))
    assert logw == pytest.approx(math.log(np.trapezoid(f, d)), abs=1e-9)
    assert chi2 == pytest.approx(-2 * np.log(f.max()), rel=1e-6)
    assert shift == pytest.approx(d[np.argmax(f)], abs=1e-6)


def test_likelihood_region_is_a_chi2_quantile_above_the_best():
    c = np.array([10.0, 19.0, 19.6, np.nan, 30.0])
    assert list(solver.likelihood_region(c, 0.95)) == [True, True, False, False, False]


def test_gravity_nodes_cover_the_range_and_carry_its_mass():
    g, w = solver.gravity_nodes(0.0, 9.8, 8)
    assert w.sum() == pytest.approx(1.0) and np.all(np.diff(g) > 0) and 0 < g[0] < 0.02


def test_the_prior_nodes_are_the_declared_ranges_cell_midpoints():
    o = CFG.runs["load_point_posterior"]["options"]
    lo, hi = CFG.raw["parameters"]["load_point_distance"]["range"]
    n = len(o["posterior_distance"])
    assert o["posterior_distance"] == pytest.approx(lo + (hi - lo) * (np.arange(n) + 0.5) / n, rel=1e-4)
    lo, hi = CFG.raw["parameters"]["friction_coefficient"]["range"]
    n = len(o["posterior_friction"])
    assert o["posterior_friction"] == pytest.approx(lo * (hi / lo) ** ((np.arange(n) + 0.5) / n), rel=1e-4)


def test_the_new_bushing_reading_misses_the_tables_pattern():
    """Every interval on the new bushing: the ten log-ratios are the printed increments over
    the printed K_p, whatever the load point; their chi2 about a common level is ~61, far
    outside the likelihood region of the growing bushing's best (~13)."""
    p = CFG.runs["load_point_posterior"]["parameters"]
    K = solver._K_paper(CFG.runs["load_point_posterior"]["options"], p)
    dh = np.array([p[f"measured_increment_{s}"] for s in solver.SIDES])
    chi2 = solver.laplace_log_weight(np.log(dh / K), solver.rounding_sigma(dh * 1e3), 1.0)[0]
    assert 55 < chi2 < 70


def test_a_synthetic_paper_s_load_point_is_in_its_credible_set():
    """Tables made by our model at a known F (0.65 m, 136 deg, g on a node, mu 0.158), its
    increments' rounding drawn from a seeded RNG and K_p printed to five digits: the true
    direction lies within the credible set at the true node, within three of its standard
    deviations (~5e-4 deg) and 2e-3 deg, what the zero's own tolerance (FIT_TOLERANCE in the
    mean misfit, ~0.007 deg) leaves after the linear shift to the weighted best direction."""
    run = copy.deepcopy(CFG.runs["load_point_posterior"])
    run["resolution"].update(n_steps=180, n_gravity=4, edge_bisections=1, periods=1, n_out=180, interval_h=38)
    run["options"].update(posterior_distance=[0.65], posterior_friction=[0.15811])
    g_true = float(solver.gravity_nodes(0.0, 9.8, 4)[0][2])
    a_true, d_true, mu_true = 136.0, 0.65, 0.15811
    fb, ctx = solver.setup(run)
    s, p = ctx.s, dict(ctx.p)
    E = solver.kinematics.load_point_mid_stroke(fb)
    fb_t = solver.load_point(replace_mu(fb, mu_true), E, d_true, a_true, g_true)
    rng = np.random.default_rng(CFG.raw["seed"])
    dh = np.array([p[f"measured_increment_{x}"] for x in solver.SIDES])
    step = solver.rounding_sigma(dh * 1e3) * math.sqrt(12) * dh
    p_true = dict(p, **{f"measured_increment_{x}": list(dh[i] + rng.uniform(-0.5, 0.5, 5) * step[i])
                        for i, x in enumerate(solver.SIDES)})
    K_true = solver._calibrated(fb_t, s, p_true, factor=solver.wear_factor_of(fb_t, s, solver.quasi_static_period))
    K_print = [[float(f"{k * 21:.4e}") for k in row] for row in K_true]
    run["options"]["fit_K_paper"] = K_print
    post = compute(run)["posterior"]
    hits = [q for q in post["points"] if q["credible"] and q["gravity"] == pytest.approx(g_true)
            and abs(q["direction"] - a_true) < 3 * q["width"] + 2e-3]
    assert hits, [(round(q["gravity"], 3), round(q["direction"], 3), q["width"], q["chi2"], q["upper_share"], q["credible"]) for q in post["points"]]


def replace_mu(fb, mu):
    from dataclasses import replace
    return replace(fb, mu=mu)


def test_bushings_solved_together_are_each_ones_period_bit_for_bit():
    """The calibration's radii solved as rows of one batch (quasistatic.periods, through
    kept_periods.many) give every array of each one's own one_period exactly -- also where
    the contact direction wraps round (90 and 315 deg) -- and a kept period is the period."""
    from mechrepro.models.joint_wear import kinematics, quasistatic

    fb, ctx = solver.setup(CFG.runs["load_point_posterior"])
    E = kinematics.load_point_mid_stroke(fb)
    for a in (0.0, 90.0, 315.0):
        fb_a = solver.load_point(fb, E, 0.65, a, 9.8)
        fbs = [fb_a.with_bushing_radius(fb_a.R_bush + h) for h in (0.0, 2e-5, 1e-4, 4e-4)]
        kept = solver.kept_periods(ctx.s)
        for together in (quasistatic.periods(fbs, 360), kept.many(fbs, ctx.s),
                         [kept(f, ctx.s) for f in fbs]):
            for f, h in zip(fbs, together):
                alone = quasistatic.one_period(f, 360)
                assert set(h) == set(alone)
                for k in alone:
                    assert np.array_equal(h[k], alone[k]), (a, k)


def test_unwrap_and_the_stacked_derivatives_are_numpy_s_bit_for_bit():
    """qs_numba.unwrap is np.unwrap (steps of exactly +-pi, NaN and inf included), and a
    stack of calls of periodic_derivatives (3-D) gives each call's own result."""
    from mechrepro.models.joint_wear import qs_numba, quasistatic

    rng = np.random.default_rng(3)
    for _ in range(200):
        a = np.cumsum(rng.choice([math.pi, -math.pi, 2.0, -2.5, 0.1, np.nan, np.inf],
                                 (3, 40), p=[.2, .2, .2, .2, .16, .02, .02]), axis=1)
        u = a.copy()
        qs_numba.unwrap(u, 0, 3)
        with np.errstate(invalid="ignore"):
            assert np.array_equal(u, np.unwrap(a), equal_nan=True)
    t = np.linspace(0.0, 2 * math.pi, 64, endpoint=False)
    calls = np.array([[np.angle(np.exp(1j * (t + 0.3 * np.sin(2 * t)))), 0.2 * np.cos(t)],
                      [0.4 * np.sin(t), t + 0.1 * np.cos(3 * t)]])
    d1, d2 = quasistatic.periodic_derivatives(calls, 2.0)
    for c in range(2):
        e1, e2 = quasistatic.periodic_derivatives(calls[c], 2.0)
        assert np.array_equal(d1[c], e1) and np.array_equal(d2[c], e2)
