"""saw_chain: Richardson extrapolation of the load maximum across K, against an independent
60-digit reference of the exact peak (not the solver's own exact_reference effect)."""
import math
from dataclasses import replace
from decimal import Decimal, localcontext

import numpy as np
import pytest

from mechrepro.models.saw_chain.analysis import equivalent_K
from mechrepro.models.saw_chain.richardson import _levels, from_levels, to_accuracy
from mechrepro.models.saw_chain.chain import chain_from_run
from mechrepro.models.saw_chain.difference import load_x
from mechrepro.solve import solve

from test_saw_chain import run

DIGITS = 60


def extrapolate_extreme(chain, K: int, fn=np.max):
    """``fn`` of the load x over one period, extrapolated from K/4, K/2, K (richardson's
    levels and estimate)."""
    Ks = _levels(K)
    return from_levels(chain, Ks, [float(fn(load_x(replace(chain, K=k)))) for k in Ks])


def _series(x, first, step):
    """sum of first * prod(step(i)) terms until the sum stops changing (sin, cos)."""
    term, total, i = first, first, 0
    while True:
        i += 1
        term = step(term, i)
        if total + term == total:
            return total
        total += term


def _sin(x):
    return _series(x, x, lambda t, i: -t * x * x / ((2 * i) * (2 * i + 1)))


def _cos(x):
    return _series(x, Decimal(1), lambda t, i: -t * x * x / ((2 * i - 1) * (2 * i)))


def _pi():
    """pi by Machin's formula, arctan(1/n) summed as a series."""
    def atan_inv(n):
        n = Decimal(n)
        return _series(1 / n, 1 / n, lambda t, i: -t * (2 * i - 1) / ((2 * i + 1) * n * n))
    return 4 * (4 * atan_inv(5) - atan_inv(239))


def _asin(y):
    x = Decimal(math.asin(float(y)))
    for _ in range(8):                      # Newton: quadratic from 16 digits to > 60
        x -= (_sin(x) - y) / _cos(x)
    return x


def exact_peak_60_digits():
    """The exact peak of the total tight-side load, F(t2-) = m_L a_A2x + (M m_L + N m_C) a_O3x
    at the end of stage 2 (where the exact load peaks), from the closed-form positions of
    Eqs. (1), (6), (9)-(10) in 60-digit decimal arithmetic, their second derivatives by a
    central difference of step 1e-20 rad (truncation ~1e-40, round-off ~1e-20 relative).
    Independent of the solver: no float, no hand-differentiated formula
    (:func:`.kinematics.stage_derivatives`), no sampling."""
    with localcontext() as ctx:
        ctx.prec = DIGITS + 10
        D = Decimal
        p1, p2, z = D("8.91e-3"), D("7.56e-3"), 8
        pi = _pi()
        w = D(6550) * 2 * pi / 60
        m_L, m_C, M, N = D("1.906e-3"), D("1.296e-3"), 32, 32
        R = (p1 * p1 + p2 * p2 + 2 * p1 * p2 * _cos(pi / z)).sqrt() / (2 * _sin(pi / z))
        Tx, span = p1 + 2 * p2, 2 * _asin(p1 / (2 * R))      # Eq. (6): stage 2 lasts span / w

        def trail_mid(phi):                                  # Eqs. (9)-(10), O2 leading
            xl, yl = Tx + R * _sin(phi), R * (1 - _cos(phi))
            xt = xl - (p1 * p1 - yl * yl).sqrt()
            return xt, (xl + xt) / 2

        h = D("1e-20")
        (t0, m0), (t1, m1), (t2, m2) = (trail_mid(span + k * h) for k in (-1, 0, 1))
        a_trail, a_mid = ((a - 2 * b + c) / (h * h) * w * w for a, b, c in ((t0, t1, t2), (m0, m1, m2)))
        return +(m_L * a_mid + (M * m_L + N * m_C) * a_trail)


@pytest.fixture(scope="module")
def chain_exact():
    """The paper's chain and its exact peak load (60-digit reference, as a float)."""
    return chain_from_run(run(K=1)), float(exact_peak_60_digits())


def test_the_exact_reference_output_matches_the_60_digit_peak(chain_exact):
    """The solver's exact_reference (hand-differentiated, float) peaks at the last sample t2,
    at the 60-digit value to round-off (measured 1.3e-15 relative)."""
    _, exact = chain_exact
    F = solve(run(K=4000, outputs=["exact_reference"]))["dynamic_load_x_exact"].values
    assert int(np.argmax(F)) == F.size - 1
    assert F[-1] == pytest.approx(exact, rel=1e-13)
    assert exact == pytest.approx(217.8503506565, abs=1e-9)


@pytest.mark.parametrize("K", [64, 256, 1024, 4096, 16384])
def test_extrapolated_peak_is_second_order_and_its_estimate_holds(chain_exact, K):
    """Measured: error 2.4e-3, 1.5e-4, 9.6e-6, 1.1e-6, 7.0e-6 (round-off from K ~ 4096 on);
    the plain maximum at the same K: 6.6e-2, 1.7e-2, 4.2e-3, 1.0e-3, 2.6e-4."""
    chain, exact = chain_exact
    e = extrapolate_extreme(chain, K)
    err = abs(e.value - exact)
    plain = abs(float(load_x(replace(chain, K=K)).max()) - exact)
    assert err <= 1.1 * e.estimate          # the estimate is the error, or bounds it
    if K <= 1024:                           # truncation-dominated: estimate within 10 %
        assert e.estimate <= 1.1 * err
        assert err < plain / 25


def _cheapest_doubling(chain, exact, rtol, K0=16):
    """By brute force, independently of :func:`to_accuracy`: the first finest level
    K = K0 2^n whose two-level extrapolation 2 q(K) - q(K/2) (first order, ratio 2) is
    truly within ``rtol`` of the 60-digit peak."""
    q = lambda K: float(load_x(replace(chain, K=K)).max())  # noqa: E731
    K = K0
    while abs(2 * q(K) - q(K // 2) - exact) > rtol * exact:
        K *= 2
        assert K <= chain.roundoff_limit(), (rtol, K)
    return K


@pytest.mark.parametrize("rtol, cheapest", [(1e-3, 128), (1e-5, 1024)])
def test_requested_accuracy_is_met_at_the_cheapest_doubling(chain_exact, rtol, cheapest):
    """to_accuracy stops at the first doubling whose estimate meets the request; that is the
    first doubling whose true error (against the 60-digit peak) does: measured 6.0e-4 at
    K = 128 (2.4e-3 at 64), 9.6e-6 at 1024 (3.8e-5 at 512), its estimate within 3 %."""
    chain, exact = chain_exact
    assert _cheapest_doubling(chain, exact, rtol) == cheapest
    e = to_accuracy(chain, rtol)
    assert e.K[-1] == cheapest and e.K[0] == 4       # doubling from K0 = 16's levels 4, 8, 16
    err = abs(e.value - exact)
    assert err <= rtol * exact                       # achieved <= requested
    assert e.estimate <= rtol * abs(e.value)         # and it knew it
    assert 0.9 * err <= e.estimate <= 1.1 * err      # truncation-dominated: estimate ~ error
    # the doubling before does not meet it, truly nor by its estimate
    coarser = extrapolate_extreme(chain, cheapest // 2)
    assert abs(coarser.value - exact) > rtol * exact
    assert coarser.estimate > rtol * abs(coarser.value)


def test_plain_method_needs_33x_the_K_for_1e3_and_cannot_reach_1e5(chain_exact):
    chain, exact = chain_exact
    K_plain, _, _ = equivalent_K(chain, exact * (1 - 1e-3))
    assert K_plain == 4273 and to_accuracy(chain, 1e-3).K[-1] == 128
    assert equivalent_K(chain, exact * (1 - 1e-5))[0] is None
    assert to_accuracy(chain, 1e-5).K[-1] == 1024


def test_richardson_run_is_what_the_figures_draw(chain_exact):
    """Effect richardson_levels (the notebook's figures read it, no solve of their own): its
    exact peak is the 60-digit one, its errors are the plain and extrapolated peaks' true
    errors, and its work counts 2K + 1 samples per solve."""
    chain, exact = chain_exact
    ds = solve(run(K=10, outputs=["richardson_levels"]))
    assert float(ds["richardson_exact_peak"]) == pytest.approx(exact, rel=1e-13)
    Ks = ds["richardson_k"].values
    i = int(np.flatnonzero(Ks == 128)[0])
    plain = abs(float(load_x(replace(chain, K=128)).max()) - exact) / exact
    assert float(ds["richardson_plain_error"][i]) == pytest.approx(plain, rel=1e-9)
    assert float(ds["richardson_error"][i]) == pytest.approx(
        abs(extrapolate_extreme(chain, 128).value - exact) / exact, rel=1e-6)
    assert float(ds["richardson_samples"][i]) == (2 * 32 + 1) + (2 * 64 + 1) + (2 * 128 + 1)
    assert np.isnan(ds["richardson_error"].values[:2]).all()      # K = 4, 8: no K/4 level
