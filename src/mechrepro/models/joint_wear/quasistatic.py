"""Continuous-contact joint B, quasi-static (the paper's low-speed assumption, Sec. 3.2).

At 9.6 r/min the pin never leaves the bushing (checked: the dynamic clearance model's
minimum penetration over a period stays > 0).  The joint then moves with the ideal
kinematics; the joint-B force follows from the minimal-coordinate equations of motion
(loads.py) solved for the contact force, Eqs. (11), (15) give F_N, the penetration and the
contact arc.  No stiff dynamics is integrated: one period costs a few vectorised array
operations.
"""
from __future__ import annotations

import numpy as np

from . import contact, kinematics, loads
from .geometry import FourBar


def one_period(fb: FourBar, n_steps: int) -> dict:
    """Contact history over one crank period on a uniform periodic grid of n_steps."""
    t = np.arange(n_steps) * (fb.period / n_steps)
    th1 = fb.omega * t
    th3, ph2 = kinematics.positions(fb, th1)
    w3, w2 = kinematics.velocities(fb, th1, th3, ph2)
    a3, a2 = kinematics.accelerations(fb, th1, th3, ph2, w3, w2)
    M11, M22, am = loads.mass_terms(fb)
    cd = np.cos(th3 - ph2)
    sd = np.sin(th3 - ph2)
    # M q'' + c(q, q') = Q_applied + J^T f + [0, R_j F_T]
    rhs3 = M11 * a3 + am * cd * a2 + am * sd * w2 ** 2
    rhs2 = am * cd * a3 + M22 * a2 - am * sd * w3 ** 2
    Q3, Q2 = loads.applied_forces(fb, th3, ph2)
    b3, b2 = rhs3 - Q3, rhs2 - Q2
    # J^T = [[l3 u3'], [l2 u2']], u' = (-sin, cos)
    j11, j12 = -fb.l3 * np.sin(th3), fb.l3 * np.cos(th3)
    j21, j22 = -fb.l2 * np.sin(ph2), fb.l2 * np.cos(ph2)
    det = j11 * j22 - j12 * j21
    tau = np.zeros_like(t)
    v_T = fb.omega * fb.R_pin - w2 * fb.R_bush
    for _ in range(6):  # friction moment R_j F_T is ~1e-3 of the load terms: fixed point
        c2 = b2 - tau
        fx = (b3 * j22 - j12 * c2) / det
        fy = (j11 * c2 - j21 * b3) / det
        sgn = contact.friction_sign(v_T, fb.v_eps)
        mus = fb.mu * sgn
        F_N = np.hypot(fx, fy) / np.sqrt(1.0 + mus ** 2)
        # f = F_N (n + mu s t): n is f turned back by the friction angle
        beta = np.arctan(mus)
        ang_f = np.arctan2(fy, fx)
        ang_n = ang_f - beta
        nx, ny = np.cos(ang_n), np.sin(ang_n)
        delta = contact.static_penetration(F_N, fb.K_contact, fb.n_exp)
        # e = (c + delta) n moves with the contact direction: its tangential rate enters v_T
        ang_u = np.unwrap(ang_n)
        dang = _periodic_derivative(ang_u, fb.period, fb.omega)
        v_T = (fb.clearance + delta) * dang + fb.omega * fb.R_pin - w2 * fb.R_bush
        F_T = contact.friction_force(F_N, v_T, fb.mu, fb.v_eps)
        tau = fb.R_bush * F_T
    psi = np.angle(np.exp(1j * (ang_n - ph2)))  # contact point on the bushing, coupler frame
    return {"t": t, "theta1": th1, "theta3": th3, "phi2": ph2, "F_N": F_N, "F_T": F_T,
            "delta": delta, "v_T": v_T, "psi": psi, "nx": nx, "ny": ny}


def _periodic_derivative(ang_unwrapped, period, omega):
    """d/dt of an angle sampled uniformly over one period (central differences, wrapped).

    The angle may gain 2 pi k over the period; that secular part is removed first.
    """
    n = ang_unwrapped.size
    dt = period / n
    drift = ang_unwrapped[-1] + (ang_unwrapped[1] - ang_unwrapped[0]) - ang_unwrapped[0]
    k = np.round(drift / (2 * np.pi))
    lin = 2 * np.pi * k * np.arange(n) / n
    per = ang_unwrapped - lin
    d = (np.roll(per, -1) - np.roll(per, 1)) / (2 * dt)
    return d + 2 * np.pi * k / period
