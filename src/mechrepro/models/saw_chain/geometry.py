"""Sprocket and chain geometry (Sec. 2.3, 3.1).  The tie strap pitch is ``p1``, the drive
link's ``p2``: Eqs. (3), (7), (9), (14), (20) and Sec. 4 agree on it, and the sentence
under Eq. (1) has the two names swapped."""
from __future__ import annotations

import numpy as np

from mechrepro.errors import Refusal


class MeshingError(Refusal):
    """The chain cannot mesh with the sprocket for the given p1, p2, z."""


def pitch_radius(p1, p2, z):
    """Pitch radius, Eq. (1): R = sqrt(p1^2 + p2^2 + 2 p1 p2 cos(pi/z)) / (2 sin(pi/z)) [m]."""
    check_meshing(p1, p2, z)
    return radius(p1, p2, z)


def radius(p1, p2, z):
    """Eq. (1) unchecked, on arrays of designs (broadcast)."""
    return np.sqrt(p1**2 + p2**2 + 2 * p1 * p2 * np.cos(np.pi / z)) / (2 * np.sin(np.pi / z))


def check_meshing(p1, p2, z):
    """Raise :class:`MeshingError` unless p1, p2 > 0 and z is an integer >= 3 (Eq. 1 closes the
    tooth angle exactly for any such chain)."""
    if not (np.isfinite(p1) and np.isfinite(p2) and p1 > 0 and p2 > 0):
        raise MeshingError(f"pitches must be positive and finite, got p1={p1}, p2={p2}")
    if int(z) != z or z < 3:
        raise MeshingError(f"number of teeth must be an integer >= 3, got z={z}")


def stage_angles(p1, p2, R):
    """Sprocket rotation at the end of stages 1 and 2, Eqs. (5)-(6): 2 asin(p2 / 2R), then
    + 2 asin(p1 / 2R) = 2 pi / z."""
    phi1 = 2 * np.arcsin(p2 / (2 * R))
    return phi1, phi1 + 2 * np.arcsin(p1 / (2 * R))


def initial_points(p1, p2):
    """Initial x of T, O2, O3, A1, A2 on the tight side (y = 0), Eqs. (2)-(4) [m]."""
    return {"T": p1 + 2 * p2, "O2": p1 + p2, "O3": p2,
            "A1": p1 + 1.5 * p2, "A2": 0.5 * p1 + p2}
