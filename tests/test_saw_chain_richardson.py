"""saw_chain: Richardson extrapolation of the load maximum across K, against the exact peak."""
import numpy as np
import pytest

from mechrepro.models.saw_chain.analysis import equivalent_K
from mechrepro.models.saw_chain.richardson import extrapolate_extreme, to_accuracy
from mechrepro.models.saw_chain.solver import chain_from_run, load_x
from mechrepro.solve import solve

from test_saw_chain import run


@pytest.fixture(scope="module")
def chain_exact():
    ds = solve(run(K=4000, effects=["exact_reference"]))
    return chain_from_run(run(K=1)), float(ds["dynamic_load_x_exact"].max())


@pytest.mark.parametrize("K", [64, 256, 1024, 4096, 16384])
def test_extrapolated_peak_is_second_order_and_its_estimate_holds(chain_exact, K):
    """Measured: error 2.4e-3, 1.5e-4, 9.6e-6, 1.1e-6, 7.0e-6 (round-off from K ~ 4096 on);
    the plain maximum at the same K: 6.6e-2, 1.7e-2, 4.2e-3, 1.0e-3, 2.6e-4."""
    chain, exact = chain_exact
    e = extrapolate_extreme(chain, K)
    err = abs(e.value - exact)
    plain = abs(float(load_x(chain.__class__(**{**chain.__dict__, "K": K})).max()) - exact)
    assert err <= 1.1 * e.estimate          # the estimate is the error, or bounds it
    if K <= 1024:                           # truncation-dominated: estimate within 10 %
        assert e.estimate <= 1.1 * err
        assert err < plain / 25


@pytest.mark.parametrize("rtol", [1e-3, 1e-5])
def test_requested_accuracy_is_met_at_the_cheapest_doubling(chain_exact, rtol):
    chain, exact = chain_exact
    e = to_accuracy(chain, rtol)
    assert abs(e.value - exact) <= 1.1 * rtol * exact     # achieved ~ requested (estimate within 10 %)
    assert e.estimate <= rtol * abs(e.value)
    # one doubling less does not meet it: the chosen K is the cheapest sampled one
    shorter = to_accuracy(chain, rtol, K0=16)
    assert shorter.K == e.K
    coarser = extrapolate_extreme(chain, e.K[-1] // 2)
    assert coarser.estimate > rtol * abs(coarser.value)


def test_plain_method_needs_33x_the_K_for_1e3_and_cannot_reach_1e5(chain_exact):
    chain, exact = chain_exact
    K_plain, _, _ = equivalent_K(chain, exact * (1 - 1e-3))
    assert K_plain == 4273 and to_accuracy(chain, 1e-3).K[-1] == 128
    assert equivalent_K(chain, exact * (1 - 1e-5))[0] is None
    assert to_accuracy(chain, 1e-5).K[-1] == 1024
