"""chain_drive high-speed model: Galerkin frequencies, RK4 against solve_ivp."""
import math

import numpy as np
import pytest

from mechrepro.models.chain_drive import galerkin, geometry

M, EA, L = 0.61, 2e6, 0.254


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

    f = lambda t, y: model.rhs(t, y, ends, tension)  # noqa: E731
    y0 = np.zeros(2 * (model.n_t + model.n_l))
    dt = 0.5 * model.max_stable_step()
    n = int(0.01 / dt)
    t, y = galerkin.rk4(f, 0.0, y0, dt, n)
    t2, y2, _ = galerkin.library(f, 0.0, y0, t[-1], t, rtol=1e-9)
    u1 = model.transverse(y, t, ends, L / 3)
    u2 = model.transverse(y2, t2, ends, L / 3)
    assert np.max(np.abs(u1 - u2)) / np.max(np.abs(u2)) < 1e-3


def test_rk4_past_its_limit_fails_loudly():
    model = galerkin.GalerkinModel(L=L, m=M, EA=EA, P=600.0, c=10.0, c_d=0.0, n_t=4, n_l=2)
    f = lambda t, y: model.rhs(t, y, lambda t: (0.0, 0.0, 0.0, 0.0), lambda t: 0.0)  # noqa: E731
    y0 = np.zeros(12)
    y0[6] = 1e-3          # a little modal momentum
    with pytest.raises(FloatingPointError, match="RK4 diverged"):
        galerkin.rk4(f, 0.0, y0, 3.0 * model.max_stable_step(), 20000)
