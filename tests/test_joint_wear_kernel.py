"""The compiled integrators of joint_wear (ivp_kernel / ivp_numba) against scipy's.

They are the same algorithms: over the first steps (a few: the step-size controller
amplifies round-off quickly on the stiff contact) they take the same steps with the same
number of right-hand-side evaluations and reach the same time to round-off; over a whole
period the stiff trajectory differs by round-off amplified by the step-size controller,
i.e. well inside the integrator tolerance."""
from __future__ import annotations

import numpy as np
import pytest

from mechrepro.config import load_paper
from mechrepro.models.joint_wear import dynamics, ivp_kernel, setup

pytestmark = pytest.mark.skipif(not ivp_kernel.available(), reason="numba not installed")


@pytest.fixture(scope="module")
def fb():
    cfg = load_paper("config/papers/joint_wear.yaml", "ci")
    return setup(cfg.runs["period_dynamic"])[0]


def test_rhs_and_jacobian_equal_the_python_ones(fb):
    k = ivp_kernel.kernels()
    p = ivp_kernel.params(fb, True)
    sys_ = dynamics.ClearanceJoint(fb, damping=True)
    y0 = dynamics.initial_state(fb, "equilibrium")
    rng = np.random.default_rng(1)
    for t in np.linspace(0.0, fb.period, 13):
        y = y0 + rng.normal(size=4) * np.array([1e-6, 1e-6, 1e-4, 1e-4])
        f = np.empty(4)
        k["rhs"](t, y, p, f)
        np.testing.assert_array_equal(f, np.asarray(sys_.rhs(t, y)))
        J = np.empty((4, 4))
        k["jac"](t, y, p, J)
        Jp = sys_.jac(t, y)
        np.testing.assert_allclose(J, Jp, rtol=0, atol=1e-13 * np.abs(Jp).max())


@pytest.mark.parametrize("method,rtol,steps", [("Radau", 1e-5, 5), ("BDF", 1e-6, 40),
                                               ("RK45", 1e-5, 1000)])
def test_compiled_steps_are_scipys(fb, method, rtol, steps):
    a = dynamics.simulate(fb, fb.period, 721, method=method, rtol=rtol, start="equilibrium",
                          max_steps=steps, kernel="scipy")
    b = dynamics.simulate(fb, fb.period, 721, method=method, rtol=rtol, start="equilibrium",
                          max_steps=steps, kernel="numba")
    assert a["status"] == b["status"] == -2
    assert a["steps"] == b["steps"] and a["nfev"] == b["nfev"]
    assert b["t_reached"] == pytest.approx(a["t_reached"], rel=1e-8)
    assert a["t"].size == b["t"].size
    np.testing.assert_allclose(b["y"], a["y"], rtol=1e-8, atol=1e-12)


def test_compiled_radau_period_within_tolerance(fb):
    a = dynamics.simulate(fb, fb.period, 721, method="Radau", rtol=1e-6, start="equilibrium",
                          kernel="scipy")
    b = dynamics.simulate(fb, fb.period, 721, method="Radau", rtol=1e-6, start="equilibrium",
                          kernel="numba")
    assert a["status"] == b["status"] == 0
    assert abs(b["steps"] - a["steps"]) < 0.1 * a["steps"]
    assert np.mean(b["F_N"]) == pytest.approx(np.mean(a["F_N"]), rel=1e-6)
    assert np.min(b["delta"]) == pytest.approx(np.min(a["delta"]), rel=1e-4)


def test_lsoda_with_compiled_callbacks_starts_as_scipys(fb):
    a = dynamics.simulate(fb, fb.period, 721, method="LSODA", rtol=1e-6, start="equilibrium",
                          max_steps=200, kernel="scipy")
    b = dynamics.simulate(fb, fb.period, 721, method="LSODA", rtol=1e-6, start="equilibrium",
                          max_steps=200, kernel="auto")
    assert a["steps"] == b["steps"]
    assert b["t_reached"] == pytest.approx(a["t_reached"], rel=1e-6)


def test_compiled_bdf_whole_period_agrees_with_scipys(fb):
    """BDF over a whole settled period (the default profile's BDF point of the accuracy
    study): both finish, in the same number of steps to 2 %, with the same mean force to
    1e-3 -- BDF rings the clearance's rocking mode (~1e-2 in the wear per period, see the
    docs), which follows round-off, so the two agree only to the ringing's level -- and both
    within 1e-3 of Radau's mean force."""
    a = dynamics.simulate(fb, fb.period, 721, method="BDF", rtol=1e-5, start="equilibrium",
                          kernel="scipy")
    b = dynamics.simulate(fb, fb.period, 721, method="BDF", rtol=1e-5, start="equilibrium",
                          kernel="numba")
    r = dynamics.simulate(fb, fb.period, 721, method="Radau", rtol=1e-7, start="equilibrium")
    assert a["status"] == b["status"] == r["status"] == 0
    assert abs(b["steps"] - a["steps"]) < 0.02 * a["steps"]
    assert np.mean(b["F_N"]) == pytest.approx(np.mean(a["F_N"]), rel=1e-3)
    for x in (a, b):
        assert np.mean(x["F_N"]) == pytest.approx(np.mean(r["F_N"]), rel=1e-3)
        assert np.min(x["delta"]) > 0                       # contact kept over the period


def test_compiled_impact_path_is_scipys(fb):
    """The concentric start of Fig. 13 (free flight, impact, rattling) over its first 0.2 s:
    the compiled Radau takes scipy's steps, meets the bushing at the same sample, with the
    same impact force peak and the same 90 % contact range."""
    from mechrepro.models.joint_wear import wear
    out = []
    for kernel in ("scipy", "numba"):
        r = dynamics.simulate(fb, 0.2, 2001, method="Radau", rtol=1e-6, start="concentric",
                              kernel=kernel)
        on = r["delta"] > 0
        out.append((r["status"], r["steps"], int(np.argmax(on)), r["F_N"].max(),
                    wear.contact_arc_quantile(r["psi"], on.astype(float))))
    (sa, na, ia, Fa, qa), (sb, nb, ib, Fb, qb) = out
    assert sa == sb == 0 and ia == ib > 0
    assert abs(nb - na) <= 0.01 * na
    assert Fb == pytest.approx(Fa, rel=1e-4)
    assert qb == pytest.approx(qa, rel=1e-4)
