"""Dynamic loads of the tight side due to the polygon effect, and the textbook model."""
from __future__ import annotations

import numpy as np


def tight_side_mass(M, N, m_L, m_C):
    """Mass translating with the trailing hinge: M tie straps and N drive links [kg]."""
    return M * m_L + N * m_C


def dynamic_load(m_link, a_mid_x, a_mid_y, m_tight, a_trail_x):
    """Tight-side dynamic load, Eqs. (14)-(16), (20)-(22): F_dx = m_link a_mid_x +
    (M m_L + N m_C) a_trail_x, F_dy = m_link a_mid_y [N]."""
    return m_link * a_mid_x + m_tight * a_trail_x, m_link * a_mid_y


def textbook_velocity_load(t, R, omega, theta, mass):
    """Eq. (23): V = R omega cos(omega t + theta), a = -R omega^2 sin(omega t + theta), F = m a."""
    phase = omega * np.asarray(t) + theta
    v = R * omega * np.cos(phase)
    a = -R * omega**2 * np.sin(phase)
    return v, a, mass * a
