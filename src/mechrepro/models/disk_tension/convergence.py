"""Converged reference for the cost-of-accuracy study of the axisymmetric model.

The Hermite discretisation converges as h^4 in frequency (tests/test_disk_tension_physics.py)
until round-off, which grows with the element count (the condition number of the
stiffness grows as n^4): 256 elements carry ~10x the round-off of 128.  The rolled
reference is therefore not the finest run but the Richardson extrapolation of two runs
that are still in the h^4 range, and its own accuracy is measured on the unrolled
frequencies, where the exact Bessel solution is known.
"""
from __future__ import annotations

import numpy as np

from mechrepro.errors import Refusal
from mechrepro.levels import extrapolate


def richardson(f_coarse, f_fine, ratio=2.0, order=4.0):
    """The h^4 Hermite elements' Richardson extrapolation of two runs whose element sizes
    differ by ``ratio`` (:func:`mechrepro.levels.extrapolate`)."""
    return extrapolate(np.asarray(f_coarse, float), np.asarray(f_fine, float), ratio, order)


def reference_pair(n_elements):
    """The two element counts of the reference: the largest pair (n, 2n) present with
    2n <= 128 (beyond 128 elements round-off exceeds the h^4 error)."""
    have = sorted(set(int(n) for n in n_elements))
    pairs = [(n, 2 * n) for n in have if 2 * n in have and 2 * n <= 128]
    if not pairs:
        raise Refusal(f"no (n, 2n) pair with 2n <= 128 among element counts {have}")
    return pairs[-1]
