"""Richardson extrapolation of the difference method's load extrema across K.

The backward second difference is first order with a smooth error expansion,
a^i = a(t_i) - dt a'(t_i) + dt^2 c(t_i) + ..., so a load sampled at a fixed time (the
peak sits at the last sample t2 at every K) obeys q(K) = q + A/K + B/K^2 + ...  Two levels
K/2, K cancel A: E(K) = 2 q(K) - q(K/2), error B'/K^2 (second order).  A third level K/4
gives the error estimate of E(K): |E(K) - E(K/2)| / (2^2 - 1), the Richardson estimate of
a second-order sequence, plus the round-off E(K) carries: 2 b(K) + b(K/2) = 2.25 b(K), b the
solver's round-off bound of one load sample (:func:`.difference.roundoff_load`), since the
extrapolation takes twice the finer value.  Round-off grows like K^2 while the truncation of
E falls like 1/K^2, so E is most accurate near K ~ (limit)^(1/2)...(limit) / 10: on the paper's
chain 1.1e-6 at K = 4096, against 1.4e-4 for the plain method at the limit K = 39434.  An extremum whose location moves with K (the minimum) has no such
expansion; :func:`extrapolate_extreme` reports its estimate anyway, and it is the caller's
to check it against the exact value where one exists (``tests/test_saw_chain_richardson.py``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from mechrepro.errors import Refusal
from mechrepro.levels import extrapolate, richardson_error

from .chain import Chain
from .difference import roundoff_load
from .difference import load_x

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
        """Steps per stage summed over the levels solved (the cost in units of one step)."""
        return int(sum(self.K))


def _levels(K: int) -> tuple:
    if K % RATIO**2 or K < 4 * RATIO**2:
        raise Refusal(f"K={K}: the finest level must be a multiple of {RATIO**2} and >= {4 * RATIO**2}")
    return (K // RATIO**2, K // RATIO, K)


def extrapolate_extreme(chain: Chain, K: int, fn=np.max) -> Extrapolated:
    """``fn`` of the load x over one period, extrapolated from K/4, K/2, K (see module)."""
    Ks = _levels(K)
    q = [float(fn(load_x(replace(chain, K=k)))) for k in Ks]
    return from_levels(chain, Ks, q)


def from_levels(chain: Chain, Ks, q) -> Extrapolated:
    """The extrapolation and its estimate from three plain values at K/4, K/2, K: Richardson
    (:mod:`mechrepro.target`) at the method's known order, plus the round-off it carries."""
    r = RATIO
    E_coarse = extrapolate(q[0], q[1], r, ORDER)
    E_fine = extrapolate(q[1], q[2], r, ORDER)
    b = roundoff_load(min(chain.stage_times()) / Ks[-1], chain.Tx + chain.R, chain.roundoff_mass())
    return Extrapolated(E_fine, richardson_error(E_coarse, E_fine, r, ORDER + 1)
                        + (r + r**-2) / (r - 1) * b,
                        tuple(int(k) for k in Ks), tuple(q))


def to_accuracy(chain: Chain, rtol: float, fn=np.max, K0: int = 16) -> Extrapolated:
    """The cheapest finest K = K0 2^n whose extrapolated extremum has estimate <= rtol |value|.

    Each doubling reuses the two finer levels of the previous one, so reaching K costs
    the solves at K0/4, K0/2, ..., K once each (< 2K steps in all).  The extrapolation and
    its estimate are the framework's (:mod:`mechrepro.target`); what is saw_chain's is the
    method's known order, the round-off bound and the stop where round-off overtakes
    truncation, which the framework's measured-order target has no way to know.
    """
    Ks = list(_levels(K0))
    q = [float(fn(load_x(replace(chain, K=k)))) for k in Ks]
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
        q.append(float(fn(load_x(replace(chain, K=Ks[-1])))))
