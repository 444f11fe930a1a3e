"""Sprocket and chain geometry of the saw chain (Shi et al. 2012, Sec. 2.3 and 3.1).

Naming follows Sec. 4 and the equations, not the sentence under Eq. (1): the tie strap
pitch is ``p1`` and the drive-link pitch is ``p2``.  Eq. (3) puts O2 at p1 + p2 and O3 at
p2, so O1O2 (the drive link, Eq. 7) has length p2 and O2O3 (the tie strap, Eq. 9) has
length p1; Eq. (14) loads A1 with the drive-link mass m_C and Eq. (20) loads A2 with the
tie-strap mass m_L.  The sentence "p1 and p2 are the pitches of the drive links and tie
straps" therefore has the two names swapped.
"""
from __future__ import annotations

import numpy as np

from mechrepro.errors import Refusal


class MeshingError(Refusal):
    """The chain cannot mesh with the sprocket for the given p1, p2, z."""


def pitch_radius(p1, p2, z):
    """Pitch radius R of the sprocket, Eq. (1) [m].

    R = sqrt(p1^2 + p2^2 + 2 p1 p2 cos(pi/z)) / (2 sin(pi/z)): the circle through the hinge
    centres of an alternating polygon of chords p1, p2 with z pairs per revolution.
    """
    check_meshing(p1, p2, z)
    return np.sqrt(p1**2 + p2**2 + 2 * p1 * p2 * np.cos(np.pi / z)) / (2 * np.sin(np.pi / z))


def check_meshing(p1, p2, z):
    """Raise :class:`MeshingError` unless p1, p2 > 0 and z is an integer >= 3.

    These are the only conditions: Eq. (1) is the circumradius of a triangle with sides
    p1, p2 and the angle pi - pi/z between them, so for any positive pitches and z >= 3
    the two chord angles 2 asin(p/2R) close the tooth angle 2 pi/z exactly
    (checked in the tests down to z = 3 with very unequal pitches).
    """
    if not (np.isfinite(p1) and np.isfinite(p2) and p1 > 0 and p2 > 0):
        raise MeshingError(f"pitches must be positive and finite, got p1={p1}, p2={p2}")
    if int(z) != z or z < 3:
        raise MeshingError(f"number of teeth must be an integer >= 3, got z={z}")


def stage_angles(p1, p2, R):
    """Sprocket rotation at the end of stage 1 and 2, Eqs. (5)-(6) [rad].

    omega*t1 = 2 asin(p2 / 2R)  (drive link O1O2 seated),
    omega*t2 = omega*t1 + 2 asin(p1 / 2R)  (tie strap O2O3 seated) = 2 pi / z.
    """
    phi1 = 2 * np.arcsin(p2 / (2 * R))
    return phi1, phi1 + 2 * np.arcsin(p1 / (2 * R))


def initial_points(p1, p2):
    """Initial x of T, O2, O3, A1, A2 on the tight side (y = 0), Eqs. (2)-(4) [m]."""
    return {"T": p1 + 2 * p2, "O2": p1 + p2, "O3": p2,
            "A1": p1 + 1.5 * p2, "A2": 0.5 * p1 + p2}
