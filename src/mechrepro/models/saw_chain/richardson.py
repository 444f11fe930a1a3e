"""Richardson extrapolation of the difference method's load extrema across K.

The peak sits at the last sample at every K, so q(K) = q + A/K + B/K^2 + ...:
E(K) = 2 q(K) - q(K/2) is second order, and K/4 estimates its error as
|E(K) - E(K/2)| / 3 plus the round-off it carries (2.25 b(K), b the solver's bound).  An
extremum that moves with K (the minimum) has no such expansion; its estimate is the
caller's to check."""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from mechrepro.errors import Refusal
from mechrepro.levels import extrapolate, richardson_error

from .chain import Chain
from .analysis import load_extreme_at
from .difference import roundoff_load

RATIO = 2
ORDER = 1          # the backward second difference's, with a smooth expansion (see module)


@dataclass(frozen=True)
class Extrapolated:
    """An extrapolated extremum: ``value`` with its error ``estimate``, from the plain values
    ``plain`` at the levels ``K`` (coarse to fine; the finest is the cost-defining K)."""
    value: float
    estimate: float
    K: tuple
    plain: tuple

    @property
    def steps(self) -> int:
        """Steps per stage summed over the levels solved."""
        return int(sum(self.K))


def _levels(K: int) -> tuple:
    if K % RATIO**2 or K < 4 * RATIO**2:
        raise Refusal(f"K={K}: the finest level must be a multiple of {RATIO**2} and >= {4 * RATIO**2}")
    return (K // RATIO**2, K // RATIO, K)


def from_levels(chain: Chain, Ks, q) -> Extrapolated:
    """The extrapolation from plain values at K/4, K/2, K at the method's order, and its estimate
    plus the round-off."""
    r = RATIO
    E_coarse = extrapolate(q[0], q[1], r, ORDER)
    E_fine = extrapolate(q[1], q[2], r, ORDER)
    b = roundoff_load(min(chain.stage_times()) / Ks[-1], chain.Tx + chain.R, chain.roundoff_mass())
    return Extrapolated(E_fine, richardson_error(E_coarse, E_fine, r, ORDER + 1)
                        + (r + r**-2) / (r - 1) * b,
                        tuple(int(k) for k in Ks), tuple(q))


def to_accuracy(chain: Chain, rtol: float, fn=np.max, K0: int = 16) -> Extrapolated:
    """The cheapest finest K = K0 2^n whose extrapolated extremum has estimate <= rtol |value|
    (each doubling reuses the two finer levels); stops where round-off overtakes truncation."""
    Ks = list(_levels(K0))
    q = [load_extreme_at(chain, k, fn) for k in Ks]
    limit = chain.roundoff_limit()
    previous = math.inf
    while True:
        e = from_levels(chain, Ks[-3:], q[-3:])
        if e.estimate <= rtol * abs(e.value):
            return replace(e, K=tuple(Ks), plain=tuple(q))
        # past the optimum (round-off now grows faster than truncation falls) or the limit
        if e.estimate > previous or Ks[-1] * RATIO > limit:
            return replace(e, K=tuple(Ks), plain=tuple(q), estimate=math.inf)
        previous = e.estimate
        Ks.append(Ks[-1] * RATIO)
        q.append(load_extreme_at(chain, Ks[-1], fn))
