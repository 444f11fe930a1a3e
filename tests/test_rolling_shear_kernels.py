"""rolling_shear: the compiled loops (closure.py through kernels.py, numba) give the numpy
paths' bits.

Each test runs the same computation with the kernels switched off (MECHREPRO_RS_KERNEL=numpy)
and on, and compares the results exactly -- and, for the swarm, the random stream after it.
"""
import math

import numpy as np
import pytest

from mechrepro import compiled
from mechrepro.models.rolling_shear import blade, closure, kernels, optimise, stroke
from mechrepro.models.rolling_shear.calibrate import calibrate_tilt
from mechrepro.models.rolling_shear.geometry import OPTIMISED_LEVERS, cut_points
from mechrepro.models.rolling_shear.loops import NonAssembly
from mechrepro.models.rolling_shear.selpso import SelPSOSettings, selpso

from test_rolling_shear_helpers import geometry

pytestmark = pytest.mark.skipif(not closure.available(), reason="numba not installed")


def both(monkeypatch, fn):
    """fn() with the kernels off, then on (the switch is read once per process: cleared)."""
    monkeypatch.setenv("MECHREPRO_RS_KERNEL", "numpy")
    compiled.available.cache_clear()
    assert not closure.available()
    off = fn()
    monkeypatch.delenv("MECHREPRO_RS_KERNEL")
    compiled.available.cache_clear()
    assert closure.available()
    return off, fn()


@pytest.mark.parametrize("settings", [
    SelPSOSettings(swarm=60, max_iter=1000, v_max=1.0),                  # the paper's, stops early
    SelPSOSettings(swarm=10, max_iter=25, v_max=1.0, tol=0.0),           # budget exhausted
    SelPSOSettings(swarm=11, max_iter=40, selection=False),              # odd swarm, no clamp
    SelPSOSettings(swarm=20, max_iter=60, w_start=0.7298, w_end=0.7298, c1=1.49618, c2=1.49618),
])
def test_selpso_compiled_equals_numpy_on_both_systems(monkeypatch, settings):
    g = geometry()
    t5, t6 = blade.exact_pose(g, g.x_mid)
    cases = [(stroke.loops_fitness(g, t5, t6), np.array([4.2, 4.3, 2.6, 2.5])),
             (stroke.loops_fitness(g, t5, t6), np.array([10.0, -10.0, 10.0, -10.0])),
             (stroke.pose_fitness(g, g.x_mid + 300.0), np.array([t5 + 0.1, t6 - 0.1]))]

    def run():
        out = []
        for seed, (fit, x0) in enumerate(cases):
            rng = np.random.default_rng([7, seed])
            r = selpso(fit, x0, settings, rng, period=2 * math.pi)
            out.append((r.x, r.fitness, r.iterations, r.evaluations, r.converged, r.history,
                        rng.random(3)))          # the stream goes on where it would have
        return out

    off, on = both(monkeypatch, run)
    for a, b in zip(off, on):
        for x, y in zip(a, b):
            assert np.array_equal(np.asarray(x), np.asarray(y)), (a, b)


def test_pose_stroke_exact_pose_and_objective_compiled_equal_numpy(monkeypatch):
    g = geometry()
    x_k = cut_points(g, 33)[1]

    def run():
        poses = optimise.stroke_poses(g, x_k, 1e-9)
        return (poses, blade.exact_pose(g, float(x_k[5])), optimise.objective(g, x_k, 1e-9))

    off, on = both(monkeypatch, run)
    for x, y in zip(off, on):
        assert np.array_equal(x, y)


def test_guide_brent_is_scipys_brentq():
    """closure.guide_brent, compiled and as Python, is scipy.optimize.brentq's C code step for
    step: the same root to the bit in brackets of every width, the scan grid's and wider
    (more steps, both interpolation and extrapolation), about roots of both assembly modes."""
    from scipy.optimize import brentq

    g = geometry()
    p, eps4 = closure.record(g.constants), 4 * np.finfo(float).eps
    rng = np.random.default_rng(5)
    n = 0
    for x in g.x_mid + rng.uniform(-1500.0, 1500.0, 40):
        f = lambda b: closure.python.guide_distance(p, b, float(x))
        betas = np.linspace(-0.3, 0.3, 13)
        for a, b in zip(betas[:-1], betas[1:]):
            if f(a) * f(b) > 0:
                continue
            for lo, hi in ((a, b), (a - rng.uniform(0, 0.1), b + rng.uniform(0, 0.1))):
                if f(lo) * f(hi) > 0:
                    continue
                ref = brentq(f, lo, hi, xtol=1e-15, rtol=eps4, maxiter=200)
                for k in (closure, closure.python):
                    root, status = k.guide_brent(p, float(x), lo, hi, 1e-15, eps4, 200)
                    assert status == closure.CONVERGED and root == ref, (x, lo, hi, root, ref)
                n += 1
    assert n > 30


def test_objective_decides_alike_over_the_lever_bounds(monkeypatch):
    """Random lever sets within +-30 %: the same H or the same refusal (and its message)."""
    g = geometry()
    x_k = cut_points(g, 9)[1]
    base = np.array(g.levers())
    levers = base * (1 + np.random.default_rng(3).uniform(-0.3, 0.3, (150, 5)))

    def run():
        out = []
        for lv in levers:
            try:
                gl = g.with_levers(**dict(zip(OPTIMISED_LEVERS, map(float, lv))))
                out.append(optimise.objective(gl, x_k, 1e-9))
            except (NonAssembly, ValueError) as exc:
                out.append(str(exc))
        return out

    off, on = both(monkeypatch, run)
    assert off == on
    assert sum(isinstance(v, str) for v in on) > 10        # refusals were exercised
    assert sum(isinstance(v, float) for v in on) > 10


def test_calibration_compiled_equals_numpy(monkeypatch):
    g = geometry()
    off, on = both(monkeypatch, lambda: calibrate_tilt(g, 1.4341, 9, 1e-9))
    assert off[0] == on[0]
    assert np.array_equal(off[1]["H_scan"], on[1]["H_scan"], equal_nan=True)


def test_partial_scan_gives_the_same_tilt():
    """The family's calibrations stop the tilt scan at the bracket they use: same tilt."""
    g = geometry()
    whole = calibrate_tilt(g, 1.4341, 9, 1e-9)
    first = calibrate_tilt(g, 1.4341, 9, 1e-9, whole_scan=False)
    assert whole[0] == first[0] and whole[1]["tilt"] == first[1]["tilt"]
    assert np.isnan(first[1]["H_scan"]).sum() > np.isnan(whole[1]["H_scan"]).sum()


def test_newton_continuation_compiled_equals_numpy(monkeypatch):
    """The warm Newton stroke (Eqs. 7 and 9 per cut point) and a refused start."""
    from dataclasses import replace

    g = geometry()
    x_k = cut_points(g, 33)[1]
    first = stroke.exact_theta(g, x_k[:1])[0]
    settings = stroke.SolverSettings(initial_value=tuple(np.round(first, 1)))

    def run():
        sol = stroke.solve_newton(g, x_k, settings)
        bad = kernels.newton_loops(g, (0.0, 0.0, 0.0, 0.0), 4.0, 3.3, 1e-11, 3)   # no convergence
        sing = kernels.newton_loops(replace(g, l3=g.l1), (1.0, 1.0, 1.0, 1.0), 2.0, 3.0, 1e-11)
        return (sol.theta, sol.fitness_pose, sol.fitness_loops, sol.iterations_loops,
                bad.x, bad.fitness, bad.iterations, bad.reason, sing.reason)

    off, on = both(monkeypatch, run)
    for x, y in zip(off, on):
        assert np.array_equal(np.asarray(x), np.asarray(y)), (x, y)


def test_one_source_for_both_paths():
    """Physics once (issue 32): every compiled function of closure.py runs, un-jitted, the very
    code object the numpy paths call, and the record's constants name Geometry's fields."""
    compiled = {n: f for n, f in vars(closure).items() if hasattr(f, "py_func")}
    assert {"lowest_point", "loop_residuals", "newton2", "pose_stroke", "guide_pose"} <= set(compiled)
    for name, f in compiled.items():
        plain = getattr(closure.python, name)
        assert not hasattr(plain, "py_func") and plain.__code__ is f.py_func.__code__
    g = geometry()
    assert closure.record(g.constants) == closure.Linkage(
        *(float(getattr(g, k)) for k in closure.Linkage._fields))
