"""Dynamic loads in the span tension: impact and external load (Sec. 2.1.1); the speed
tensioning of Eq. (2-1) is :func:`.geometry.axial_tension`.

Pure functions of time (vectorised over any array shape), SI units.
"""
from __future__ import annotations

import numpy as np

from . import samples
from .samples import whole_pulse_formulas


def pressure_angle(n1: int) -> float:
    """Eq. (2-3), decided from the ANSI tooth form: eta = 35 deg + 60 deg / n1 [rad].

    The printed formula (``35 + 24Q/n1 + epsilon``) is garbled.  The paper says the
    contact point stays close to the transition between seating and working curve; in the
    ANSI (ASME B29.1) tooth form that transition lies on the line at angle
    A = 35 deg + 60 deg / N.  We take eta = A (epsilon << 1 dropped).  See docs/chain_drive.md.
    """
    return np.deg2rad(35.0 + 60.0 / n1)


def impact_constants(m_i: float, k_i: float, zeta_i: float) -> dict:
    """Appendix I: omega_n = sqrt(k_i/m_i), zeta, omega_d = omega_n sqrt(1 - zeta^2), c_i."""
    wn = np.sqrt(k_i / m_i)
    c_i = 2.0 * zeta_i * np.sqrt(m_i * k_i)
    return {"omega_n": wn, "zeta": zeta_i, "omega_d": wn * np.sqrt(1 - zeta_i**2),
            "c_i": c_i, "k_i": k_i, "m_i": m_i, "t_i": np.pi / (wn * np.sqrt(1 - zeta_i**2))}


def impact_of(prm: dict) -> dict:
    """:func:`impact_constants` of a run's parameters: the impacting mass of
    ``impact_mass_links`` links (Sec. 2.1.1), its contact stiffness and damping ratio."""
    return impact_constants(prm["impact_mass_links"] * prm["pitch"] * prm["mass_per_length"],
                            prm["contact_stiffness"], prm["contact_damping_ratio"])


def relative_velocity(omega1, p_c: float):
    """Eq. (2-2): V_rel = omega1 p_c."""
    return np.asarray(omega1, float) * p_c


def impact_pulse(t_local, V_rel, eta: float, k: dict):
    """Eq. (2-4a/b), Appendix I: the impact load at time ``t_local`` after the impact.

    D_imp = V_rel sin(2 eta)/(2 omega_d) e^{-zeta omega_n t} {(k_i - c_i zeta omega_n) sin omega_d t
    + c_i omega_d cos omega_d t} for 0 < t < pi/omega_d, zero afterwards in the tooth period.
    """
    t = np.asarray(t_local, float)
    wd, wn, z, ki, ci = k["omega_d"], k["omega_n"], k["zeta"], k["k_i"], k["c_i"]
    on = (t > 0) & (t < np.pi / wd)
    val = (V_rel * np.sin(2 * eta) / (2 * wd) * np.exp(-z * wn * t)
           * ((ki - ci * z * wn) * np.sin(wd * t) + ci * wd * np.cos(wd * t)))
    return np.where(on, val, 0.0)


def impact_pulse_integral(t_local, V_rel, eta: float, k: dict):
    """Exact time integral of Eq. (2-4) from the impact instant to ``t_local``.

    Since D_imp = (c_i x0' + k_i x0) cos(eta) for the free contact oscillator
    m_i x0'' + c_i x0' + k_i x0 = 0, its integral is cos(eta) (c_i x0 + k_i X0) where
    X0 = int x0 dt = -(m_i x0' + c_i x0)/k_i + m_i x0'(0)/k_i.  Used to apply a pulse
    shorter than the time step with its exact impulse (hard case).
    """
    t = np.clip(np.asarray(t_local, float), 0.0, np.pi / k["omega_d"])
    wd, wn, z, ki, ci, mi = k["omega_d"], k["omega_n"], k["zeta"], k["k_i"], k["c_i"], k["m_i"]
    v0 = V_rel * np.sin(eta)
    e = np.exp(-z * wn * t)
    x0 = v0 / wd * e * np.sin(wd * t)
    xd = v0 * e * (np.cos(wd * t) - z * wn / wd * np.sin(wd * t))
    X0 = (mi * v0 - mi * xd - ci * x0) / ki
    return np.cos(eta) * (ci * x0 + ki * X0)


def impact_load(t, omega1, n1: int, p_c: float, k: dict, step: float | None = None):
    """D_imp(t) repeated every tooth period, impacts at t = 0, tau, 2 tau, ... .

    With ``step`` the load is averaged over [t - step/2, t + step/2] exactly (impulse
    preserved), so a contact pulse much shorter than the time step is neither missed
    nor aliased.  Broadcasts t against omega1.
    """
    t = np.asarray(t, float)
    omega1 = np.asarray(omega1, float)
    tau = 2 * np.pi / (n1 * omega1)
    V = relative_velocity(omega1, p_c)
    eta = pressure_angle(n1)
    if step is None:
        return impact_pulse(np.mod(t, tau), V, eta, k)
    # the cumulative impulse is I(t) = floor(t/tau) J + Ipulse(t mod tau).  Only the
    # samples whose window reaches into a contact see a partial pulse; every other window
    # holds whole impulses only, I(b) - I(a) = (floor(b/tau) - floor(a/tau)) J exactly, and
    # the pulse (exp, sin, cos) is evaluated on those few samples (~(t_i + step)/tau) alone
    J = impact_pulse_integral(np.inf * np.ones_like(V), V, eta, k)
    t_i = np.pi / k["omega_d"]
    shape = samples.block(t, omega1)
    if shape:
        out, near = samples.whole_pulses(t, tau, J, step, t_i, shape)
    else:
        out, near = whole_pulse_formulas(t, tau, J, step, t_i)
        out = np.array(out, float)                      # writable, also from 0-d inputs
    if np.any(near):
        shape = near.shape
        tau_n, J_n, V_n = (np.broadcast_to(x, shape)[near] for x in (tau, J, V))

        def cum_near(s):
            return (np.floor(s / tau_n) * J_n
                    + impact_pulse_integral(np.mod(s, tau_n), V_n, eta, k))

        t_n, step_n = np.broadcast_to(t, shape)[near], np.broadcast_to(step, shape)[near]
        out[near] = cum_near(t_n + step_n / 2) - cum_near(t_n - step_n / 2)
    return out / step


def external_load(t, T_ex: float, omega_ex):
    """Eq. (2-5): D_ext = T_ex cos(omega_ex t)."""
    return T_ex * np.cos(np.asarray(omega_ex, float) * np.asarray(t, float))
