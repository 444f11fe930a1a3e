"""disk_tension beyond the paper: the centrifugal stress of the spinning disk and the
travelling-wave critical speed, against closed forms (Lamb & Southwell's membrane limit,
Southwell's first-order relation)."""
import numpy as np
import pytest

from mechrepro.models.disk_tension import calibration, rotation
from mechrepro.models.disk_tension.axisym import AxisymDisk
from mechrepro.models.disk_tension.modal import eigen

E, NU, RHO, B = 206e9, 0.3, 7850.0, 0.1275
H = calibration.thickness(f_target=434.5, n_d=4, r_f=0.025, b=B, E=E, nu=NU, rho=RHO)


def centrifugal(r_f, bc, omega=1.0):
    kw = dict(omega=omega, rho=RHO, nu=NU, r_f=r_f, b=B, inplane_bc=bc)
    return (lambda r: rotation.centrifugal_stress(r, **kw)[0],
            lambda r: rotation.centrifugal_stress(r, **kw)[1])


@pytest.mark.parametrize("bc", ["clamped", "free_disk"])
def test_centrifugal_stress_is_in_equilibrium_and_free_at_the_rim(bc):
    omega = 600.0
    r = np.linspace(0.025, B, 20001)
    sr, st = rotation.centrifugal_stress(r, omega=omega, rho=RHO, nu=NU, r_f=0.025, b=B,
                                         inplane_bc=bc)
    resid = np.gradient(sr, r) + (sr - st) / r + RHO * omega**2 * r
    assert np.max(np.abs(resid[2:-2])) < 1e-6 * RHO * omega**2 * B
    assert abs(sr[-1]) < 1e-9 * np.max(np.abs(st))
    if bc == "clamped":   # u_r(r_f) = r (sigma_theta - nu sigma_r) / E = 0
        assert st[0] - NU * sr[0] == pytest.approx(0.0, abs=1e-9 * np.max(np.abs(st)))


def test_membrane_limit_is_lamb_and_southwell():
    """A spinning membrane disk (bending stiffness -> 0) has omega_r^2 = lambda Omega^2 with
    lambda = n ((1 - nu) n + 3 + nu) / 4 for the mode without nodal circles (Lamb &
    Southwell 1921; w = r^n); n = 1 gives the stationary tilt, lambda = 1."""
    d = AxisymDisk(r_f=5e-4, b=B, h=H, E=E * 1e-9, nu=NU, rho=RHO, n_d=[1, 2, 3, 4],
                   n_elements=128)
    Kc = d.stress_stiffness(centrifugal(5e-4, "free_disk"))
    lam = np.array([eigen(d.K[n] + Kc[n], d.M[n])[0][0] for n in (1, 2, 3, 4)])
    closed = np.array([n * ((1 - NU) * n + 3 + NU) / 4 for n in (1, 2, 3, 4)])
    np.testing.assert_allclose(lam, closed, rtol=2e-3)


def test_critical_speed_stops_the_backward_wave_and_obeys_southwell():
    d = AxisymDisk(r_f=0.025, b=B, h=H, E=E, nu=NU, rho=RHO, n_d=range(5), n_elements=64)
    d.unrolled()
    Kc = d.stress_stiffness(centrifugal(0.025, "clamped"))
    assert np.isinf(rotation.critical_speed(d.K[0], d.M[0], Kc[0], 0))
    for n in (2, 3, 4):
        oc = rotation.critical_speed(d.K[n], d.M[n], Kc[n], n)
        # at Omega_c the rotating-frame frequency is n Omega_c: backward wave at rest
        w2 = eigen(d.K[n] + oc**2 * Kc[n], d.M[n])[0][0]
        assert np.sqrt(w2) == pytest.approx(n * oc, rel=1e-9)
        lam, o_sw = rotation.southwell(d.omega2[n], d.phi[n], d.M[n], Kc[n], n)
        assert 0 < lam < n * n
        assert o_sw * (1 - 5e-3) < oc <= o_sw * (1 + 1e-12)   # Rayleigh: at most first order
