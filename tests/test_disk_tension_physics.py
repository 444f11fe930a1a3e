"""disk_tension: exact solution, thermal stress, axisymmetric model, Eq. (9), hard cases."""
import numpy as np
import pytest

from mechrepro.models.disk_tension import calibration, exact, modal, thermal
from mechrepro.models.disk_tension.axisym import AxisymDisk, radial_mesh

E, NU, RHO, B = 206e9, 0.3, 7850.0, 0.1275
H = calibration.thickness(f_target=434.5, n_d=4, r_f=0.025, b=B, E=E, nu=NU, rho=RHO)
ALPHA = 12e-6


def stress(r_c, r_f=0.025, A=50.0, bc="clamped", alpha=ALPHA):
    kw = dict(amplitude=A, r_c=r_c, s=0.005, r_f=r_f, b=B, E=E, nu=NU, alpha=alpha, inplane_bc=bc)
    return (lambda r: thermal.thermal_stress(r, **kw)[0], lambda r: thermal.thermal_stress(r, **kw)[1])


def disk(r_f=0.025, n_elements=64, n_d=range(5)):
    d = AxisymDisk(r_f=r_f, b=B, h=H, E=E, nu=NU, rho=RHO, n_d=list(n_d), n_elements=n_elements)
    d.unrolled()
    return d


# -- exact Bessel solution --------------------------------------------------------------
def test_thickness_calibration_hits_434_5_hz_exactly():
    f = exact.natural_frequencies(4, a=0.025, b=B, h=H, E=E, nu=NU, rho=RHO)[0]
    assert f == pytest.approx(434.5, rel=1e-12)
    assert 1.0e-3 < H < 2.0e-3  # a plausible saw-blade gauge


def test_exact_roots_are_roots_and_ordered():
    lam = exact.frequency_parameters(2, 0.3, NU, count=3)
    assert np.all(np.diff(lam) > 0)
    scale = np.abs(exact.frequency_determinant(lam * 1.01, 2, 0.3, NU))
    assert np.all(np.abs(exact.frequency_determinant(lam, 2, 0.3, NU)) < 1e-9 * scale)


@pytest.mark.parametrize("r_f", [0.025, 0.055, 0.075])
def test_axisym_matches_exact_bessel_frequencies(r_f):
    d = disk(r_f=r_f, n_elements=64)
    f = np.sqrt([d.omega2[n] for n in range(5)]) / (2 * np.pi)
    fe = np.array([exact.natural_frequencies(n, a=r_f, b=B, h=H, E=E, nu=NU, rho=RHO)[0]
                   for n in range(5)])
    np.testing.assert_allclose(f, fe, rtol=2e-6)


def test_axisym_converges_at_fourth_order():
    fe = exact.natural_frequencies(3, a=0.025, b=B, h=H, E=E, nu=NU, rho=RHO)[0]
    ne = np.array([16, 32, 64])  # asymptotic range (4..16 is pre-asymptotic)
    err = [np.sqrt(disk(n_elements=n, n_d=[3]).omega2[3]) / (2 * np.pi) / fe - 1 for n in ne]
    assert np.all(np.array(err) > 0)  # conforming Rayleigh-Ritz: from above
    order = np.polyfit(np.log(1.0 / ne), np.log(err), 1)[0]
    assert 3.5 < order < 5.0


# -- exact stressed reference (uniform in-plane stress) ----------------------------------
def test_stressed_exact_solution_reduces_to_the_unstressed_one_and_moves_with_the_stress():
    f0 = [exact.natural_frequencies(n, a=0.025, b=B, h=H, E=E, nu=NU, rho=RHO)[0] for n in range(5)]
    tiny = [exact.natural_frequencies(n, a=0.025, b=B, h=H, E=E, nu=NU, rho=RHO, sigma=1.0)[0]
            for n in range(5)]
    np.testing.assert_allclose(tiny, f0, rtol=1e-6)
    up = [exact.natural_frequencies(n, a=0.025, b=B, h=H, E=E, nu=NU, rho=RHO, sigma=10e6)[0]
          for n in range(5)]
    down = [exact.natural_frequencies(n, a=0.025, b=B, h=H, E=E, nu=NU, rho=RHO, sigma=-3e6)[0]
            for n in range(5)]
    assert np.all(np.array(up) > f0) and np.all(np.array(down) < f0)
    # the memoised and the fresh solve are the same numbers
    assert exact.natural_frequencies(3, a=0.025, b=B, h=H, E=E, nu=NU, rho=RHO, sigma=10e6,
                                     memo=False)[0] == up[3]


@pytest.mark.parametrize("sigma0", [10e6, -3e6])
def test_axisym_matches_the_stressed_exact_solution_at_fourth_order(sigma0):
    """The stress-stiffening path (Eq. 3 on the harmonics, Eq. 5) against the Bessel solution
    of the annulus under uniform in-plane stress: h^4 until round-off."""
    fe = np.array([exact.natural_frequencies(n, a=0.025, b=B, h=H, E=E, nu=NU, rho=RHO,
                                             sigma=sigma0)[0] for n in range(5)])
    err = []
    for ne in (16, 32, 64):  # asymptotic range
        d = disk(n_elements=ne)
        f = np.sqrt(d.rolled(d.stress_stiffness(d.uniform_stress(sigma0)))[0]) / (2 * np.pi)
        assert np.all(f > fe)  # conforming Rayleigh-Ritz: from above
        err.append(np.max(np.abs(f / fe - 1)))
    order = np.log2(np.array(err[:-1]) / np.array(err[1:]))
    assert np.all((3.5 < order) & (order < 5.0)), order
    d = disk(n_elements=128)
    f = np.sqrt(d.rolled(d.stress_stiffness(d.uniform_stress(sigma0)))[0]) / (2 * np.pi)
    assert np.max(np.abs(f / fe - 1)) < 2e-7


def test_exact_rejects_bad_ratio():
    with pytest.raises(ValueError, match="a/b"):
        exact.frequency_parameters(0, 1.2, NU)


# -- thermal analogy --------------------------------------------------------------------
@pytest.mark.parametrize("bc", ["clamped", "free_disk"])
def test_thermal_stress_is_in_equilibrium_and_traction_free_at_rim(bc):
    r = np.linspace(0.03, B, 4001)
    sr, st = thermal.thermal_stress(r, amplitude=50, r_c=0.065, s=0.005, r_f=0.025, b=B, E=E,
                                    nu=NU, alpha=ALPHA, inplane_bc=bc)
    resid = np.gradient(sr, r) + (sr - st) / r
    assert np.max(np.abs(resid[5:-5])) * 0.005 < 1e-4 * np.max(np.abs(st))
    assert abs(sr[-1]) < 1e-6 * np.max(np.abs(st))


def test_clamped_inplane_condition_gives_zero_hoop_strain_at_clamp():
    r_f = 0.025
    sr, st = thermal.thermal_stress(np.array([r_f]), amplitude=50, r_c=0.03, s=0.005, r_f=r_f,
                                    b=B, E=E, nu=NU, alpha=ALPHA)
    T = thermal.temperature(r_f, 50, 0.03, 0.005)
    assert (st[0] - NU * sr[0]) / E + ALPHA * T == pytest.approx(0.0, abs=1e-12)


def test_free_disk_hoop_force_balances():
    # a half disk carries no net hoop force: int_0^b sigma_theta dr = 0
    r = np.linspace(1e-6, B, 200001)
    _, st = thermal.thermal_stress(r, amplitude=50, r_c=0.065, s=0.005, r_f=1e-6, b=B, E=E,
                                   nu=NU, alpha=ALPHA, inplane_bc="free_disk")
    assert abs(np.trapezoid(st, r)) < 1e-5 * np.max(np.abs(st)) * B


def test_thermal_stress_bad_input():
    # a bad inplane_bc, r_f or s is refused at load (test_disk_tension_solver.py); the
    # clamped annulus's stress is not evaluated inside the clamp
    with pytest.raises(ValueError, match="r >= r_f"):
        thermal.thermal_stress([0.01], amplitude=1, r_c=0.05, s=0.005, r_f=0.025, b=B, E=E,
                               nu=NU, alpha=ALPHA)


# -- Eq. (9), Eqs. (16)-(17) ------------------------------------------------------------
def test_eq9_is_an_upper_bound_and_exact_to_first_order():
    d = disk()
    Ks = d.stress_stiffness(stress(0.065))
    d9 = d.eq9(Ks)
    w2, _ = d.rolled(Ks)
    w0 = np.array([d.omega2[n] for n in range(5)])
    assert np.all(w2 <= w0 + d9 + 1e-9 * w0)  # Rayleigh quotient of the unrolled mode
    # Eq. (9) is the first-order term: the rest shrinks linearly with the load factor
    # (below ~1e-3 the eigensolver's round-off on omega^2 dominates the difference)
    dev = []
    for eps in (0.1, 0.01):
        w2s, _ = d.rolled({n: eps * k for n, k in Ks.items()})
        dev.append(np.abs((w2s - w0) / (eps * d9) - 1))
    assert np.all(dev[0] < 2e-2) and np.all(dev[1] < 2e-3)
    assert np.all(dev[1] < 0.2 * dev[0])


def test_eq9_is_linear_in_the_temperature_amplitude():
    d = disk(n_elements=32)
    a = d.eq9(d.stress_stiffness(stress(0.085, A=50)))
    b = d.eq9(d.stress_stiffness(stress(0.085, A=100)))
    np.testing.assert_allclose(b, 2 * a, rtol=1e-12)


def test_paper_70hz_is_the_linearised_conversion_of_table1():
    w = 2 * np.pi * 434.5
    assert modal.delta_f_linearised(w, 2.40e6) == pytest.approx(69.96, abs=0.01)
    assert modal.delta_f_exact(w, 2.40e6) == pytest.approx(65.08, abs=0.01)


def test_stress_calibration_meets_table1_and_modal_matrices_are_diagonal():
    a, _, _ = calibration.alpha_effective(target=2.40e6, n_d=4, r_c=0.065, r_f=0.025, b=B, h=H, E=E,
                                    nu=NU, rho=RHO, alpha=ALPHA, amplitude=50, s=0.005,
                                    inplane_bc="clamped")
    d = disk(n_elements=128)
    k_hat, m_hat = d.modal_matrices(d.stress_stiffness(stress(0.065, alpha=a)))
    assert k_hat[4, 4] == pytest.approx(2.40e6, rel=1e-6)
    assert np.all(k_hat - np.diag(np.diag(k_hat)) == 0)
    assert np.all((np.diag(m_hat) > 0.99) & (np.diag(m_hat) <= 1 + 1e-12))


# -- hard cases -------------------------------------------------------------------------
def test_buckling_is_reported_not_square_rooted():
    d = disk(n_elements=32)
    Ks = d.stress_stiffness(stress(0.105, A=50))
    lam = d.critical_load(Ks)
    n2 = list(d.n_d).index(2)
    assert 1.0 < lam[n2] < 3.0  # compressive hoop stress near the rim: N_d = 2 goes first
    w2, _ = d.rolled({n: 1.5 * lam[n2] * k for n, k in Ks.items()})
    assert w2[n2] < 0
    f = modal.frequency(w2)
    assert np.isnan(f[n2]) and np.array_equal(np.isnan(f), w2 < 0)
    # at the critical load factor the lowest eigenvalue of N_d = 2 crosses zero
    w2c, _ = d.rolled({n: lam[n2] * k for n, k in Ks.items()})
    assert abs(w2c[n2]) < 1e-8 * d.omega2[2]


def test_tensile_stress_never_buckles():
    d = disk(n_elements=16, n_d=[0])
    Ks = d.stress_stiffness((lambda r: 1e7 + 0 * r, lambda r: 1e7 + 0 * r))
    assert np.isinf(d.critical_load(Ks)[0])


def test_rolling_inside_the_clamp_changes_nothing_with_clamped_inplane_condition():
    d = disk(r_f=0.075, n_elements=32)
    d9 = d.eq9(d.stress_stiffness(stress(0.035, r_f=0.075)))
    w0 = np.array([d.omega2[n] for n in range(5)])
    assert np.max(np.abs(d9 / w0)) < 1e-12
    # ... but the free disk carries the rolling's hoop stress out to the flexible region
    d9f = d.eq9(d.stress_stiffness(stress(0.035, r_f=0.075, bc="free_disk")))
    assert np.max(np.abs(d9f / w0)) > 1e-3


def test_very_coarse_and_very_thin_axisymmetric_models_stay_finite():
    fe = exact.natural_frequencies(4, a=0.025, b=B, h=H, E=E, nu=NU, rho=RHO)[0]
    one = disk(n_elements=1, n_d=[4])
    assert 0 < np.sqrt(one.omega2[4]) / (2 * np.pi) / fe - 1 < 0.5   # n_elements < 1: at load
    thin = AxisymDisk(r_f=0.025, b=B, h=H / 20, E=E, nu=NU, rho=RHO, n_d=[4], n_elements=32)
    thin.unrolled()
    Ks = thin.stress_stiffness(stress(0.105))
    w2, _ = thin.rolled(Ks)
    lam = thin.critical_load(Ks)[0]
    assert (w2[0] < 0) == (lam < 1.0)  # a 20x thinner blade buckles under the same stress
    assert lam < 1.0


def test_fig7_sensitivity_matches_first_order_energy_fraction():
    from mechrepro.models.disk_tension.axisym import bending_matrix, mass_matrix, quadrature

    d = disk(n_elements=32)
    r_a, w = np.array([0.04, 0.09]), 0.01
    df = d.sensitivity(r_a=r_a, width=w, increase=0.01, E=E, nu=NU, rho=RHO)
    D = E * H**3 / (12 * (1 - NU**2))
    for i, ra in enumerate(r_a):
        mesh = radial_mesh(0.025, B, 32, breakpoints=(ra - w / 2, ra + w / 2))
        q = quadrature(mesh)
        ind = lambda r: ((r >= ra - w / 2) & (r <= ra + w / 2)).astype(float)  # noqa: E731
        for j, n in enumerate(range(5)):
            K, M = bending_matrix(mesh, n, D=D, nu=NU, quad=q), mass_matrix(mesh, rho_h=RHO * H, quad=q)
            Ka = bending_matrix(mesh, n, D=D, nu=NU, quad=q, d_scale=ind)
            lam, phi = modal.eigen(K, M, 1)
            d_w2 = 0.01 * (phi[:, 0] @ Ka @ phi[:, 0])
            assert df[i, j] > 0  # a stiffer annulus never lowers a frequency
            assert df[i, j] == pytest.approx(modal.delta_f_linearised(np.sqrt(lam[0]), d_w2), rel=1e-2)


@pytest.mark.parametrize("amplitude", [0.0, 50.0, 400.0])
def test_banded_inverse_iteration_matches_dense_and_falls_back_when_buckled(amplitude):
    """The 32-64 element fundamentals come from banded inverse iteration (modal.eigen with a
    bandwidth): the same eigenpair as LAPACK's dense driver to round-off; a stress that
    buckles the harmonic (K + K^(sigma) indefinite) is handed to the dense driver."""
    disk = AxisymDisk(r_f=0.025, b=B, h=H, E=E, nu=NU, rho=RHO, n_d=range(5), n_elements=64)
    kw = dict(amplitude=amplitude, r_c=0.105, s=0.005, r_f=0.025, b=B, E=E, nu=NU,
              alpha=ALPHA, inplane_bc="free_disk")
    ks = disk.stress_stiffness((lambda r: thermal.thermal_stress(r, **kw)[0],
                                lambda r: thermal.thermal_stress(r, **kw)[1]))
    buckled = 0
    for n in range(5):
        A, M = disk.K[n] + ks[n], disk.M[n]
        assert len(A) == 128 and modal.BANDED_MIN <= len(A) <= modal.BANDED_MAX
        lam_b, phi_b = modal.eigen(A, M, 1, 3)
        lam_d, phi_d = modal.eigen(A, M, 1)
        if modal.lowest_banded(A, M, 3) is None:
            buckled += 1
            assert lam_d[0] < 0 and lam_b[0] == lam_d[0]
        np.testing.assert_allclose(lam_b, lam_d, rtol=1e-8)
        assert abs(abs(phi_b[:, 0] @ M @ phi_d[:, 0]) - 1) < 1e-12
    assert (buckled > 0) == (amplitude == 400.0)


def test_inverse_iteration_screen_returns_the_plain_iterate():
    """The change test of ``lowest_banded`` is skipped while the step's angle says it cannot
    pass: the vector returned is bit for bit the one the plain loop (test every step)
    returns, for the stressed and unstressed fundamentals of every harmonic."""
    from scipy.linalg.lapack import dpbtrf, dpbtrs

    def plain(K, M, u=3, tol=1e-13, maxiter=200):
        ab = np.zeros((u + 1, len(K)))
        for k in range(u + 1):
            ab[u - k, k:] = np.diagonal(K, k)
        c, info = dpbtrf(ab)
        if info != 0:
            return None
        x = np.ones(len(K)) / np.sqrt(len(K))
        for _ in range(maxiter):
            y, _ = dpbtrs(c, M @ x)
            y /= np.copysign(np.sqrt(y.dot(y)), y @ x)
            if np.abs(y - x).max() < tol * np.abs(y).max():
                return y
            x = y
        return None

    disk = AxisymDisk(r_f=0.025, b=B, h=H, E=E, nu=NU, rho=RHO, n_d=range(5), n_elements=64)
    for amplitude, r_c in ((0.0, 0.065), (50.0, 0.065), (150.0, 0.045), (400.0, 0.105)):
        kw = dict(amplitude=amplitude, r_c=r_c, s=0.005, r_f=0.025, b=B, E=E, nu=NU,
                  alpha=ALPHA, inplane_bc="free_disk")
        ks = disk.stress_stiffness((lambda r: thermal.thermal_stress(r, **kw)[0],
                                    lambda r: thermal.thermal_stress(r, **kw)[1]))
        for n in range(5):
            A = disk.K[n] + ks[n]
            a, b = plain(A, disk.M[n]), modal.lowest_banded(A, disk.M[n], 3)
            assert (a is None and b is None) or np.array_equal(a, b)
