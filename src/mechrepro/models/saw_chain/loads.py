"""Dynamic loads of the tight side due to the polygon effect, and the textbook model."""
from __future__ import annotations

import numpy as np


def tight_side_mass(M, N, m_L, m_C):
    """Mass translating with the trailing hinge: M tie straps and N drive links [kg]."""
    return M * m_L + N * m_C


def dynamic_load(m_link, a_mid_x, a_mid_y, m_tight, a_trail_x):
    """Total tight-side dynamic load, Eqs. (14)-(16) (stage 1) and (20)-(22) (stage 2) [N].

    F_dx = m_link a_mid_x + (M m_L + N m_C) a_trail_x,   F_dy = m_link a_mid_y,
    where the link being seated (drive link in stage 1, tie strap in stage 2) is loaded
    at its midpoint and the rest of the tight side translates with the trailing hinge.
    """
    return m_link * a_mid_x + m_tight * a_trail_x, m_link * a_mid_y


def textbook_velocity_load(t, R, omega, theta, mass):
    """Textbook model of the polygon effect, Eq. (23).

    V = R omega cos(omega t + theta),  a = -R omega^2 sin(omega t + theta),  F = m a.
    """
    phase = omega * np.asarray(t) + theta
    v = R * omega * np.cos(phase)
    a = -R * omega**2 * np.sin(phase)
    return v, a, mass * a
