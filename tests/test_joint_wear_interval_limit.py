"""joint_wear (#60 item 4): the interval method's exact limit, its cost-of-accuracy reference:
against a closed-form wear law the limit is exact to 1e-10 and the method's error is of order 1."""
import math

import numpy as np
import pytest

from mechrepro.models.joint_wear import wear

R0, T, K, H0 = 0.01, 6.25, 1e-13, 1.2e-4


def G(R):
    return 4e5 * R0 / R        # a wear factor falling with the radius, as the four-bar's does


def exact(t0, t1):
    """dh/dt = k G(R0 + h/2) 3600/T: R0 h + h^2/4 grows linearly in time."""
    a = K * 4e5 * R0 * 3600.0 / T
    c = R0 * H0 + H0 * H0 / 4 + a * (t1 - t0)
    return -2 * R0 + math.sqrt(4 * R0 * R0 + 4 * c)


def test_the_limit_is_the_closed_form():
    h = wear.interval_limit(H0, 10.0, 86.0, K, T, R0, G)
    assert h == pytest.approx(exact(10.0, 86.0), rel=1e-10)


def test_the_interval_method_converges_to_it_at_order_one():
    ref = wear.interval_limit(H0, 10.0, 86.0, K, T, R0, G)
    errs = [abs(wear.predict(H0, 10.0, 86.0, iv, K, T, R0, G)[1][-1] / ref - 1) for iv in (1.0, 2.0, 4.0)]
    orders = np.log2(np.array(errs[1:]) / np.array(errs[:-1]))
    assert orders == pytest.approx([1.0, 1.0], abs=0.02)
