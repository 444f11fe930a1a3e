"""The compiled Radau, BDF and RK45 of joint_wear (radau.py, bdf.py, rk45.py) against
scipy's, and the compiled physics (clearance.py) against the same source run as Python.

radau.py is scipy's Radau algorithm: over the first steps (a few: the step-size controller
amplifies round-off quickly on the stiff contact) it takes the same steps with the same
number of right-hand-side evaluations and reaches the same time to round-off; over a whole
period the stiff trajectory differs by round-off amplified by the step-size controller,
i.e. well inside the integrator tolerance."""
from __future__ import annotations

import numpy as np
import pytest

from mechrepro.config import load_paper
from mechrepro.models.joint_wear import clearance, dynamics, setup

pytestmark = pytest.mark.skipif(not clearance.available(), reason="numba not installed")


@pytest.fixture(scope="module")
def fb():
    cfg = load_paper("config/papers/joint_wear.yaml", "ci")
    return setup(cfg.runs["period_dynamic"])[0]


def test_compiled_physics_is_the_python_source(fb):
    """One source, two executions: numba's and Python's evaluate the same right-hand side
    and Jacobian (to round-off: libm against Python's math)."""
    p = clearance.params(fb, True)
    y0 = dynamics.initial_state(fb, "equilibrium")
    rng = np.random.default_rng(1)
    for t in np.linspace(0.0, fb.period, 13):
        y = y0 + rng.normal(size=4) * np.array([1e-6, 1e-6, 1e-4, 1e-4])
        f, fp = clearance.rhs(t, y, p), clearance.rhs.py_func(t, y, p)
        np.testing.assert_allclose(f, fp, rtol=1e-12, atol=1e-12 * np.abs(fp).max())
        J = clearance.jac(t, y, p)
        Jp = np.empty((4, 4))
        clearance.jac_into.py_func(t, y, p, Jp)
        np.testing.assert_allclose(J, Jp, rtol=0, atol=1e-12 * np.abs(Jp).max())


def test_compiled_radau_steps_are_scipys(fb):
    a = dynamics.simulate(fb, fb.period, 721, method="Radau", rtol=1e-5, start="equilibrium",
                          max_steps=5, kernel="scipy")
    b = dynamics.simulate(fb, fb.period, 721, method="Radau", rtol=1e-5, start="equilibrium",
                          max_steps=5, kernel="auto")
    assert a["status"] == b["status"] == -2
    assert a["steps"] == b["steps"] and a["nfev"] == b["nfev"]
    assert b["t_reached"] == pytest.approx(a["t_reached"], rel=1e-8)
    assert a["t"].size == b["t"].size
    np.testing.assert_allclose(b["y"], a["y"], rtol=1e-8, atol=1e-12)


def test_compiled_rk45_steps_are_scipys(fb):
    """rk45.py is scipy's RK45: on the stiff contact's step budget (the cost-of-accuracy
    study's explicit run) it takes the same steps with the same evaluations, and reaches
    the same time to round-off amplified by the step-size controller."""
    for budget, rel in ((200, 1e-14), (5000, 1e-8)):
        a, b = (dynamics.simulate(fb, fb.period, 721, method="RK45", rtol=1e-5,
                                  start="equilibrium", max_steps=budget, kernel=k)
                for k in ("scipy", "auto"))
        assert a["status"] == b["status"] == -2
        assert a["steps"] == b["steps"] == budget and a["nfev"] == b["nfev"]
        assert b["t_reached"] == pytest.approx(a["t_reached"], rel=rel)
    # the dense output sampled where the budget reaches past a sample
    a, b = (dynamics.simulate(fb, 2e-3, 41, method="RK45", rtol=1e-5, start="equilibrium",
                              max_steps=5000, kernel=k) for k in ("scipy", "auto"))
    assert a["t"].size == b["t"].size > 10
    np.testing.assert_allclose(b["y"], a["y"], rtol=1e-7, atol=1e-12)


def test_compiled_bdf_steps_are_scipys_and_its_period_within_tolerance(fb):
    """bdf.py is scipy's BDF: over its first steps it takes scipy's steps with the same
    evaluations (the order and step controller amplify round-off to ~1e-8 in the time
    reached after 40 steps); over the whole period the mean contact force agrees within
    the integrator tolerance."""
    a, b = (dynamics.simulate(fb, fb.period, 721, method="BDF", rtol=1e-6,
                              start="equilibrium", max_steps=40, kernel=k)
            for k in ("scipy", "auto"))
    assert a["status"] == b["status"] == -2
    assert a["steps"] == b["steps"] == 40 and a["nfev"] == b["nfev"]
    assert b["t_reached"] == pytest.approx(a["t_reached"], rel=1e-7)
    a, b = (dynamics.simulate(fb, fb.period, 721, method="BDF", rtol=1e-6,
                              start="equilibrium", kernel=k) for k in ("scipy", "auto"))
    assert a["status"] == b["status"] == 0
    assert abs(b["steps"] - a["steps"]) < 0.05 * a["steps"]
    assert np.mean(b["F_N"]) == pytest.approx(np.mean(a["F_N"]), rel=1e-5)


def test_compiled_radau_period_within_tolerance(fb):
    a = dynamics.simulate(fb, fb.period, 721, method="Radau", rtol=1e-6, start="equilibrium",
                          kernel="scipy")
    b = dynamics.simulate(fb, fb.period, 721, method="Radau", rtol=1e-6, start="equilibrium")
    assert a["status"] == b["status"] == 0
    assert abs(b["steps"] - a["steps"]) < 0.35 * a["steps"]
    assert np.mean(b["F_N"]) == pytest.approx(np.mean(a["F_N"]), rel=1e-6)
    assert np.min(b["delta"]) == pytest.approx(np.min(a["delta"]), rel=1e-4)


def test_compiled_impact_path_is_scipys(fb):
    """The concentric start of Fig. 13 (free flight, impact, rattling) over its first 0.2 s:
    the compiled Radau takes scipy's steps, meets the bushing at the same sample, with the
    same impact force peak and the same 90 % contact range."""
    from mechrepro.models.joint_wear import wear
    out = []
    for kernel in ("scipy", "auto"):
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


def test_without_numba_the_same_source_runs_as_python(fb):
    """numba hidden: the physics (clearance.py, qs_numba.py) runs as Python and Radau is
    scipy's; the settled period agrees with the compiled one within the tolerance."""
    import subprocess
    import sys

    code = ("import sys; sys.modules['numba'] = None\n"
            "import numpy as np\n"
            "from mechrepro.config import load_paper\n"
            "from mechrepro.models.joint_wear import clearance, dynamics, setup\n"
            "assert not clearance.available()\n"
            "fb = setup(load_paper('config/papers/joint_wear.yaml', 'ci').runs['period_dynamic'])[0]\n"
            "r = dynamics.simulate(fb, fb.period, 721, rtol=1e-6, start='equilibrium')\n"
            "print(r['status'], np.mean(r['F_N']), np.min(r['delta']))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.split()
    b = dynamics.simulate(fb, fb.period, 721, rtol=1e-6, start="equilibrium")
    assert int(out[0]) == b["status"] == 0
    assert float(out[1]) == pytest.approx(np.mean(b["F_N"]), rel=1e-6)
    assert float(out[2]) == pytest.approx(np.min(b["delta"]), rel=1e-4)
