"""chain_drive: the compiled FD time loop (fd_kernel) and the second-order default scheme.

The compiled loop must be the numpy loop of fd.march to round-off (same stencils, same
span-length switching, block maxima, capping and probe records); the default for the
sweeps without impact is central differencing (s* = 0) at cfl 0.98: observed order 2
against the exact moving-string mode, and stable just inside the von Neumann limit.
"""
import math

import numpy as np
import pytest

from mechrepro.accuracy import observed_order
from mechrepro.models.chain_drive import exact, fd, fd_kernel, span
from mechrepro.models.chain_drive.effects import EFFECTS
from test_chain_drive_contract import declared

needs_numba = pytest.mark.skipif(not fd_kernel.available(), reason="numba not installed")

M, T, L = 0.61, 400.0, 0.254
CW = math.sqrt(T / M)
PRM = dict(pitch=0.0127, mass_per_length=0.61, n1=24, n2=24, centre_distance=20.25,
           static_tension=400.0, lambda_support=0.9, transverse_damping=12.2,
           axial_stiffness=2e6, driven_inertia=0.002, impact_mass_links=2,
           contact_stiffness=2e8, contact_damping_ratio=0.1, external_load_ratio=0.2,
           external_frequency_ratio=2.0, speed=300 * math.pi / 30,
           speed_min=100 * math.pi / 30, speed_max=600 * math.pi / 30, probe_fraction=1 / 3)


def _both(**kw):
    return fd.march(kernel="numpy", **kw), fd.march(kernel="compiled", **kw)


def _same(a, b, rtol=1e-9):
    scale = np.max(np.abs(a.block_max))
    assert np.array_equal(a.unstable, b.unstable)
    np.testing.assert_allclose(b.block_max, a.block_max, rtol=0, atol=rtol * scale)
    np.testing.assert_allclose(b.final, a.final, rtol=0, atol=rtol * scale)
    np.testing.assert_allclose(b.amplitude, a.amplitude, rtol=rtol)


@needs_numba
@pytest.mark.parametrize("differencing", ["central", "mixed"])
def test_compiled_loop_equals_numpy_loop_with_length_change_and_sag(differencing):
    """11 speeds (not a multiple of the lanes), length change switching the span, impact,
    polygonal action, end motion and the sag load: every output equal to round-off."""
    effects = ["speed_tensioning", "impact", "polygonal_rigid", "end_excitation",
               "length_change", "sag"]
    res = dict(points_per_pitch=2, cfl=0.98, decay_times=0.3, window_periods=1)
    om = np.linspace(PRM["speed_min"], PRM["speed_max"], 11)
    a = span.assemble(declared(effects), PRM, om, res, EFFECTS)
    assert a["grid"].n_short != a["grid"].n_long and a["exc"].load is not None
    assert a["exc"].long.any() and (~a["exc"].long).any()
    kw = dict(c=a["c"], P=a["P"], m=a["m"], c_d=a["c_d"], grid=a["grid"], dt=a["dt"],
              n_steps=a["n_steps"], exc=a["exc"], s_star=a["s_star"],
              measure_from=a["measure_from"], u_cap=0.05, probes=[3, 17], record_every=5,
              differencing=differencing)
    ref, got = _both(**kw)
    _same(ref, got)
    assert got.probes.shape == ref.probes.shape
    np.testing.assert_allclose(got.probes, ref.probes, rtol=0, atol=1e-9 * np.max(np.abs(ref.probes)))
    np.testing.assert_allclose(got.t_rec, ref.t_rec, rtol=1e-12)


@needs_numba
def test_compiled_loop_caps_growing_rows_like_the_numpy_loop():
    """A Mathieu tongue (pumping at 2 omega_1, large amplitude): the growing rows are frozen
    and reported unstable by both loops, the others agree to round-off."""
    grid = fd.Grid(L, 20, 20)
    ff = np.array([1.5, 2.0, 2.6])
    w1 = math.pi * CW / L
    dt = fd.stable_time_step(grid.dx, np.zeros(3), T * 1.3, M, 0.98)
    n_steps = int(60 * 2 * math.pi / w1 / dt)
    t = np.arange(n_steps + 1) * dt
    Pt = 0.3 * T * np.cos(ff[None, :] * w1 * t[:, None])
    u0 = 1e-4 * np.repeat(np.sin(np.pi * grid.x / L)[None], 3, 0)
    kw = dict(c=np.zeros(3), P=np.full(3, T), m=M, c_d=0.5, grid=grid, dt=dt,
              n_steps=n_steps, exc=fd.Excitation(tension=Pt), u0=u0, u_cap=1e-3,
              measure_from=n_steps // 3, differencing="central")
    ref, got = _both(**kw)
    assert ref.unstable.tolist() == [False, True, False]
    assert np.isinf(ref.growth[1]) and np.isinf(got.growth[1])
    _same(ref, got)


@needs_numba
def test_auto_kernel_falls_back_to_numpy_without_numba(monkeypatch):
    grid = fd.Grid(L, 16, 16)
    u0 = 1e-4 * np.sin(np.pi * grid.x / L)[None]
    kw = dict(c=np.array([3.0]), P=np.array([T]), m=M, c_d=1.0, grid=grid,
              dt=fd.stable_time_step(grid.dx, 3.0, T, M, 0.98), n_steps=400,
              exc=fd.Excitation(), u0=u0, differencing="central")
    compiled = fd.march(kernel="compiled", **kw)
    monkeypatch.setattr(fd_kernel, "MIN_UPDATES", 0)
    monkeypatch.setattr(fd_kernel, "available", lambda: False)
    fallback = fd.march(**kw)
    with pytest.raises(ValueError, match="compiled kernel unavailable"):
        fd.march(kernel="compiled", **kw)
    _same(fallback, compiled)


def test_unknown_differencing_or_kernel_is_refused():
    kw = dict(c=np.array([1.0]), P=np.array([T]), m=M, c_d=0.0, grid=fd.Grid(L, 8, 8),
              dt=1e-5, n_steps=4, exc=fd.Excitation())
    with pytest.raises(ValueError, match="differencing"):
        fd.march(differencing="upwind", **kw)
    with pytest.raises(ValueError, match="kernel"):
        fd.march(kernel="fortran", **kw)


@pytest.mark.parametrize("kernel", ["numpy", "compiled"])
@pytest.mark.parametrize("cfl", [0.9, 0.98])
def test_central_default_is_second_order_against_the_exact_mode(cfl, kernel, monkeypatch):
    """Wickert-Mote mode 1 at c = 0.5 c_w, marched by either loop (no source term):
    observed order 2 at the default's cfl 0.98 as at 0.9."""
    if kernel == "compiled":
        if not fd_kernel.available():
            pytest.skip("numba not installed")
        monkeypatch.setattr(fd_kernel, "MIN_UPDATES", 0)
    else:
        monkeypatch.setattr(fd_kernel, "worth_it", lambda updates: False)
    errs, hs = [], []
    for n in (20, 40, 80):
        e, w_fd, w_ex, _, _ = exact.free_vibration(n, L=L, m=M, T=T, c=0.5 * CW, cfl=cfl,
                                                   s_star=0.0)
        errs.append(e)
        hs.append(1 / n)
    assert 1.9 < observed_order(hs, errs) < 2.1
    assert abs(w_fd / w_ex - 1) < 1e-3


@pytest.mark.parametrize("kernel", ["numpy", pytest.param("compiled", marks=needs_numba)])
@pytest.mark.parametrize("a", [0.0, 0.2, 0.5])
def test_central_at_the_default_cfl_stays_bounded_with_dynamic_tension(a, kernel):
    """cfl 0.98 of the limit set by the largest tension of the record (as span.assemble
    sets it): a pumped, lightly damped span off its tongues stays bounded for 20000 steps;
    the same span 3 % past the limit of its largest tension grows."""
    grid = fd.Grid(L, 40, 40)
    c = np.array([a * CW])
    eps = 0.3
    w1 = math.pi * (CW**2 - c[0] ** 2) / (CW * L)
    rng = np.random.default_rng(1)
    u0 = 1e-6 * rng.standard_normal((1, 41))

    def run(factor):
        dt = factor * fd.stable_time_step(grid.dx, c, T * (1 + eps), M, cfl=1.0)
        n_steps = 20000
        t = np.arange(n_steps + 1) * dt
        Pt = eps * T * np.cos(1.3 * w1 * t)[:, None]
        return fd.march(c=c, P=np.array([T]), m=M, c_d=0.2, grid=grid, dt=dt,
                        n_steps=n_steps, exc=fd.Excitation(tension=Pt), u0=u0, u_cap=1e-2,
                        measure_from=n_steps // 2, differencing="central", kernel=kernel)

    inside = run(0.98)
    assert not inside.unstable[0] and np.max(np.abs(inside.final)) < 1e-4
    assert run(1.03).unstable[0]


WARM_THEN_SOLVE = """
import math, numpy as np
from mechrepro.models.chain_drive import fd, fd_kernel, galerkin, galerkin_kernel, solver
L, M, T = 0.254, 0.61, 400.0
solver.warm()
grid = fd.Grid(L, 16, 16)
fd.march(c=np.array([3.0]), P=np.array([T]), m=M, c_d=1.0, grid=grid,
         dt=fd.stable_time_step(grid.dx, 3.0, T, M, 0.98), n_steps=400, exc=fd.Excitation(),
         u0=1e-4 * np.sin(np.pi * grid.x / L)[None], differencing="central", kernel="compiled")
model = galerkin.GalerkinModel(L=L, m=M, EA=2e6, P=T, c=10.0, c_d=1.0, n_t=4, n_l=2)
F = {k: np.zeros((50, 4)) for k in ("g", "h", "gd", "hd", "Pt")}
galerkin.rk4_tabulated(model, np.zeros(12), 1e-6, 50, F, kernel="compiled")
print(len(fd_kernel.kernel().signatures), len(galerkin_kernel.kernel().signatures))
"""


@needs_numba
def test_warm_loads_the_signatures_the_solvers_call():
    """solver.warm() (the runner calls it before the first timed run) calls both kernels
    with the production argument types: in a fresh process, a compiled march and a compiled
    RK4 after it leave one signature each, so nothing is loaded or compiled inside a timed
    solve."""
    import os
    import subprocess
    import sys

    from conftest import ROOT

    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    out = subprocess.run([sys.executable, "-c", WARM_THEN_SOLVE], env=env, capture_output=True,
                         text=True, check=True).stdout
    assert out.split() == ["1", "1"]


@needs_numba
@pytest.mark.parametrize("n1, n2, f_p", [(24, 24, 0.0), (19, 38, 0.3), (15, 40, 0.5)])
def test_compiled_sample_loops_equal_the_formulas_on_arrays(monkeypatch, n1, n2, f_p):
    """The excitation's per-sample loops (samples.py) run the elementwise formulas of
    four_bar and loads: on a (time, speed) block with samples exactly at engagements and
    wraps (the round-off branch), on shared and on per-speed times, every output equals
    the numpy evaluation of the same formulas (to a cosine's last bit: numpy's may be a
    SIMD one)."""
    from mechrepro.models.chain_drive import four_bar, loads, samples

    p_c = PRM["pitch"]
    k = loads.impact_constants(2 * p_c * M, 2e8, 0.1)
    om = np.linspace(20.0, 400.0, 37)[None, :]
    tau = 2 * np.pi / (n1 * om)
    shared = np.concatenate([np.arange(60)[:, None] * tau[:, :1] / 7,
                             np.random.default_rng(1).uniform(0, 0.05, (40, 1))])
    own = np.arange(50)[:, None] * tau / 9

    def evaluate():
        out = []
        for t, step in ((shared, 2.3e-5), (own, np.broadcast_to(tau / 9, own.shape))):
            kin = four_bar.rigid_kinematics(t, om, n1=n1, n2=n2, p_c=p_c, f_p=f_p)
            out += [kin[q] for q in ("theta1", "cos_theta1", "sin_theta1", "cos_theta2",
                                     "sin_theta2", "omega2", "alpha2", "phase1", "phase2")]
            out.append(loads.impact_load(t, om, n1, p_c, k, step=step))
        return out

    compiled = evaluate()
    assert samples.block(shared, om) and samples.block(own, om)
    monkeypatch.setattr(samples, "block", lambda t, omega1: None)
    for got, ref in zip(compiled, evaluate()):
        np.testing.assert_allclose(got, ref, rtol=0, atol=4e-16 * max(np.max(np.abs(ref)), 1))
