"""chain_drive high-speed model: Galerkin frequencies, RK4 against solve_ivp."""
import math

import numpy as np
import pytest

from mechrepro.models.chain_drive import galerkin, geometry

from mechrepro.models.chain_drive.errors import DivergenceError

M, EA, L = 0.61, 2e6, 0.254


def rk4(f, t0, y0, dt, n_steps, y_cap=1e3):
    """Classical RK4 with a fixed step on a right-hand side f(t, y): the reference the
    tabulated, compiled RK4 of the scenes is checked against.  Stages at the step ends take
    one-sided limits (the kinks of the end motion sit on step boundaries)."""
    y = np.array(y0, float)
    out_t, out_y = [t0], [y.copy()]
    eps = 1e-9 * dt
    for i in range(n_steps):
        t = t0 + i * dt
        k1 = f(t + eps, y)
        k2 = f(t + dt / 2, y + dt / 2 * k1)
        k3 = f(t + dt / 2, y + dt / 2 * k2)
        k4 = f(t + dt - eps, y + dt * k3)
        y = y + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        if not np.all(np.isfinite(y)) or np.max(np.abs(y)) > y_cap:
            raise DivergenceError(f"RK4 diverged at t = {t + dt:.4g} s")
        out_t.append(t0 + (i + 1) * dt)
        out_y.append(y.copy())
    return np.array(out_t), np.array(out_y)


def library(f, t0, y0, t_end, t_eval, rtol=1e-6, atol=1e-12, max_step=np.inf):
    """solve_ivp (DOP853) on the same right-hand side."""
    from scipy.integrate import solve_ivp

    sol = solve_ivp(f, (t0, t_end), y0, method="DOP853", t_eval=t_eval, rtol=rtol, atol=atol,
                    max_step=max_step)
    assert sol.success, sol.message
    return sol.t, sol.y.T, sol.nfev


def rhs(model, ends, tension):
    """f(t, y) of the model with scalar end motion ends(t) -> (g, h, g', h') and P_t(t)."""
    return lambda t, y: model.rhs_values(y, *ends(t), tension(t))


def transverse(model, y, t, ends, xi):
    """u2 at x = xi: the modal part plus the end-motion line."""
    e = np.array([ends(tt)[:2] for tt in np.atleast_1d(t)])
    return model.u2_at(y, xi) + (1 - xi / model.L) * e[:, 0] + xi / model.L * e[:, 1]


def forcing(run, prm, omega1, geo, step=None):
    """The forcing t -> (g, h, g', h', P_t) as a scalar function of t."""
    def at(t):
        F = galerkin.forcing_arrays(run, prm, omega1, geo, t, step)
        return tuple(float(F[k]) for k in ("g", "h", "gd", "hd", "Pt"))
    return at


def _linear_frequencies(model):
    nt, nl = model.n_t, model.n_l
    n = nt + nl
    Minv = np.zeros((n, n)); Minv[:nt, :nt] = model.Mt_inv; Minv[nt:, nt:] = model.Ml_inv
    K = np.zeros((n, n)); K[:nt, :nt] = model.Kt; K[nt:, nt:] = model.Kl
    G = np.zeros((n, n)); G[:nt, :nt] = model.Gt; G[nt:, nt:] = model.Gl
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ K, -Minv @ G]])
    lam = np.linalg.eigvals(A)
    return np.sort(np.abs(lam.imag[lam.imag > 1e-6]))


def test_galerkin_transverse_frequencies_converge_to_wickert_mote():
    P = 400.0
    cw = math.sqrt(P / M)
    c = 0.4 * cw
    exact = geometry.moving_string_frequencies(np.arange(1, 4), c, P, M, L)
    errs = []
    for nt in (4, 16):
        model = galerkin.GalerkinModel(L=L, m=M, EA=EA, P=P, c=c, c_d=0.0, n_t=nt, n_l=1,
                                       coupling=False)
        w = _linear_frequencies(model)
        errs.append(np.max(np.abs(w[:3] / exact - 1)))
    assert errs[1] < 0.01 and errs[1] < errs[0]


def test_longitudinal_frequency_of_the_galerkin_rod():
    c = 20.0
    model = galerkin.GalerkinModel(L=L, m=M, EA=EA, P=400.0, c=c, c_d=0.0, n_t=1, n_l=6,
                                   coupling=False)
    w = _linear_frequencies(model)
    wl = geometry.longitudinal_frequency(1, EA, M, c, L)
    assert np.min(np.abs(w / wl - 1)) < 0.01


def test_rk4_agrees_with_solve_ivp_on_the_coupled_model():
    model = galerkin.GalerkinModel(L=L, m=M, EA=EA, P=600.0, c=10.0, c_d=12.2, n_t=4, n_l=2)
    w = 2 * math.pi * 80

    def ends(t):
        return (1e-3 * math.sin(w * t), 0.0, 1e-3 * w * math.cos(w * t), 0.0)

    def tension(t):
        return 50.0 * math.sin(2 * w * t)

    f = rhs(model, ends, tension)
    y0 = np.zeros(2 * (model.n_t + model.n_l))
    dt = 0.5 * model.max_stable_step()
    n = int(0.01 / dt)
    t, y = rk4(f, 0.0, y0, dt, n)
    t2, y2, _ = library(f, 0.0, y0, t[-1], t, rtol=1e-9)
    u1 = transverse(model, y, t, ends, L / 3)
    u2 = transverse(model, y2, t2, ends, L / 3)
    assert np.max(np.abs(u1 - u2)) / np.max(np.abs(u2)) < 1e-3


def test_rk4_past_its_limit_fails_loudly():
    model = galerkin.GalerkinModel(L=L, m=M, EA=EA, P=600.0, c=10.0, c_d=0.0, n_t=4, n_l=2)
    f = rhs(model, lambda t: (0.0, 0.0, 0.0, 0.0), lambda t: 0.0)
    y0 = np.zeros(12)
    y0[6] = 1e-3          # a little modal momentum
    with pytest.raises(FloatingPointError, match="RK4 diverged"):
        rk4(f, 0.0, y0, 3.0 * model.max_stable_step(), 20000)


# ---------------------------------------------------------------------------- issue 18: speed

def _fig10_case(name="rk4_check_coupled"):
    from pathlib import Path

    from mechrepro.config import load_paper
    root = Path(__file__).resolve().parent.parent
    run = load_paper(root / "config/papers/chain_drive.yaml", "ci").runs[name]
    prm, res = run["parameters"], run["resolution"]
    return run, prm, res, galerkin._galerkin_setup(run, prm, res)


@pytest.mark.skipif(not galerkin.galerkin_kernel.available(), reason="numba not installed")
@pytest.mark.parametrize("name", ["rk4_check_coupled", "rk4_check_uncoupled"])
def test_compiled_rk4_equals_the_numpy_loop(name):
    """The compiled RK4 (galerkin_kernel) is the numpy loop of rk4_tabulated to round-off,
    coupled and linear, with a record every 3rd step."""
    run, prm, res, g = _fig10_case(name)
    model, dt, n = g["model"], g["dt"], 30 * g["per_tooth"]
    st = galerkin.stage_times(dt, n)
    F = galerkin.forcing_arrays(run, prm, g["w1"], g["geo"], st.ravel(), step=g["window"])
    F = {k: v.reshape(st.shape) for k, v in F.items()}
    y0 = np.zeros(2 * (model.n_t + model.n_l))
    ta, ya = galerkin.rk4_tabulated(model, y0, dt, n, F, record_every=3, kernel="numpy")
    tb, yb = galerkin.rk4_tabulated(model, y0, dt, n, F, record_every=3, kernel="compiled")
    np.testing.assert_array_equal(ta, tb)
    assert np.max(np.abs(ya - yb)) <= 1e-11 * np.max(np.abs(ya))


@pytest.mark.skipif(not galerkin.galerkin_kernel.available(), reason="numba not installed")
def test_compiled_rk4_past_its_limit_fails_loudly():
    model = galerkin.GalerkinModel(L=L, m=M, EA=EA, P=600.0, c=10.0, c_d=0.0, n_t=4, n_l=2)
    n = 20000
    F = {k: np.zeros((n, 4)) for k in ("g", "h", "gd", "hd", "Pt")}
    y0 = np.zeros(12)
    y0[6] = 1e-3
    with pytest.raises(FloatingPointError, match="RK4 diverged"):
        galerkin.rk4_tabulated(model, y0, 3.0 * model.max_stable_step(), n, F, kernel="compiled")


def test_piecewise_forcing_interpolates_the_contributions_and_refuses_a_missing_edge():
    run, prm, res, g = _fig10_case()
    t_end = 3 * g["per_tooth"] * g["dt"]
    edges = galerkin.forcing_breakpoints(prm, g["w1"], g["geo"], g["window"], t_end)
    pf = galerkin.PiecewiseForcing(run, prm, g["w1"], g["geo"], g["window"], edges)
    assert pf.error < 1e-12
    rng = np.random.default_rng(0)
    i = rng.integers(0, edges.size - 1, 50)
    t = edges[i] + rng.random(50) * (edges[i + 1] - edges[i])
    F = galerkin.forcing_arrays(run, prm, g["w1"], g["geo"], t, step=g["window"])
    got = np.array([pf.on(j)(tt) for j, tt in zip(i, t)])
    want = np.stack([F[k] for k in ("g", "h", "gd", "hd", "Pt")], axis=1)
    assert np.all(np.abs(got - want) <= 1e-11 * np.max(np.abs(want), axis=0))
    # without the impact edges the box-averaged pulse has kinks inside the intervals
    with pytest.raises(ValueError, match="non-smooth point"):
        galerkin.PiecewiseForcing(run, prm, g["w1"], g["geo"], g["window"],
                                  galerkin.forcing_breakpoints(prm, g["w1"], g["geo"], None,
                                                               t_end))


def test_segmented_library_is_closer_to_a_tight_solution_than_one_across_the_kinks():
    """solve_ivp restarted at the forcing's edges: fewer rhs calls and a smaller error (against
    the segmented solution at rtol 1e-12) than one integration across the kinks."""
    run, prm, res, g = _fig10_case("rk4_check_uncoupled")
    model = g["model"]
    t_ev = np.arange(2 * g["per_tooth"] + 1) * g["dt"]
    y0 = np.zeros(2 * (model.n_t + model.n_l))
    edges = galerkin.forcing_breakpoints(prm, g["w1"], g["geo"], g["window"], t_ev[-1])
    pf = galerkin.PiecewiseForcing(run, prm, g["w1"], g["geo"], g["window"], edges)
    ref, _ = galerkin.library_piecewise(model.rhs_values, pf.on, edges, y0, t_ev, rtol=1e-12)
    seg, n_seg = galerkin.library_piecewise(model.rhs_values, pf.on, edges, y0, t_ev, rtol=1e-9)
    at = forcing(run, prm, g["w1"], g["geo"], step=g["window"])
    _, one, n_one = library(lambda t, y: model.rhs_values(y, *at(t)), 0.0, y0,
                                     t_ev[-1], t_ev, rtol=1e-9, atol=1e-14, max_step=g["dt"])
    scale = np.max(np.abs(ref))
    assert n_seg < n_one
    assert np.max(np.abs(seg - ref)) < np.max(np.abs(one - ref))
    assert np.max(np.abs(seg - ref)) < 1e-9 * scale
