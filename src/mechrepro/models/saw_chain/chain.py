"""The chain of one run: geometry, masses and the time grid of one period (Eqs. 1-6)."""
from __future__ import annotations

from dataclasses import dataclass, fields, replace
from functools import lru_cache

import numpy as np

from .difference import roundoff_limit, velocity_roundoff_limit
from .geometry import check_meshing, initial_points, pitch_radius, stage_angles
from .kinematics import stage_derivatives, stage_jerks
from .loads import tight_side_mass


@dataclass(frozen=True)
class Design:
    """The printed inputs (SI): pitches, teeth, sprocket speed, link masses and counts."""
    p1: float
    p2: float
    z: int
    omega: float
    m_L: float
    m_C: float
    M: int
    N: int

    def inputs(self) -> dict:
        """The printed inputs by name, as :func:`.design.design_quantities` takes them."""
        return {f.name: getattr(self, f.name) for f in fields(Design)}


@dataclass(frozen=True)
class Chain(Design):
    """Geometry, masses and the time grid of one period (2K steps, Eqs. 5-6)."""
    K: int

    @property
    def R(self):
        return pitch_radius(self.p1, self.p2, self.z)

    @property
    def Tx(self):
        return initial_points(self.p1, self.p2)["T"]

    @property
    def phases(self):
        return stage_angles(self.p1, self.p2, self.R)

    @property
    def m_tight(self):
        return tight_side_mass(self.M, self.N, self.m_L, self.m_C)

    @property
    def chain_speed(self):
        """The pitch-line speed z (p1 + p2) omega / (2 pi) [m/s]: the time mean of the tight-side
        velocity of any model that conserves the chain length, and the constant-speed rival's."""
        return self.z * (self.p1 + self.p2) * self.omega / (2.0 * np.pi)

    def stages(self):
        """(lead-link length, link mass, local angles phi_i, i = 0..K) for each stage."""
        phi1, phi2 = self.phases
        return [(self.p2, self.m_C, np.linspace(0.0, phi1, self.K + 1)),
                (self.p1, self.m_L, np.linspace(0.0, phi2 - phi1, self.K + 1))]

    def stage_times(self):
        """Durations t1 and t2 - t1 of the two stages [s]."""
        phi1, phi2 = self.phases
        return phi1 / self.omega, (phi2 - phi1) / self.omega

    def load_jerk_max(self):
        """max |dF_dx/dt| of the exact load in each stage [N/s]."""
        return list(budget_constants(self.per_chain())[0])

    def roundoff_mass(self):
        """Mass multiplying second differences in one load sample (tight side + seating link)."""
        return self.m_tight + max(self.m_L, self.m_C)

    def roundoff_limit(self):
        """K beyond which round-off dominates the loads (see :mod:`.difference`)."""
        return budget_constants(self.per_chain())[1]

    def velocity_roundoff_limit(self):
        """K beyond which round-off dominates the velocity (first difference)."""
        return budget_constants(self.per_chain())[2]

    def per_chain(self) -> "Chain":
        """This chain with K = 1: the key of what does not depend on K."""
        return replace(self, K=1)

    def time(self):
        """Sample times: t = 0, then K steps of each stage [s]."""
        phi1, phi2 = self.phases
        return np.concatenate([np.linspace(0.0, phi1, self.K + 1),
                               np.linspace(phi1, phi2, self.K + 1)[1:]]) / self.omega


@lru_cache(maxsize=256)
def budget_constants(chain: Chain, n: int = 129):
    """(max |dF_dx/dt| per stage, the loads' round-off limit of K, the velocity's), from a fixed
    grid of ``n`` angles; cached per chain, because a K sequence solves one chain many times."""
    jerk, acc = [], []
    phi1, phi2 = chain.phases
    for L, m_link, span in ((chain.p2, chain.m_C, phi1), (chain.p1, chain.m_L, phi2 - phi1)):
        phi = np.linspace(0.0, span, n)
        j = stage_jerks(phi, chain.R, L, chain.omega)
        jerk.append(float(np.max(np.abs(m_link * j["mid_jx"] + chain.m_tight * j["trail_jx"]))))
        acc.append(float(np.max(np.abs(stage_derivatives(phi, chain.R, L, chain.omega)["trail_ax"]))))
    times, x_max = chain.stage_times(), chain.Tx + chain.R
    return (tuple(jerk), roundoff_limit(times, jerk, x_max, chain.roundoff_mass()),
            velocity_roundoff_limit(times, acc, x_max))


def chain_from_run(run: dict) -> Chain:
    """The run's chain; ``options.single_pitch``: the rival of one pitch (the tie strap's) for
    both links, as in a roller chain."""
    p = run["parameters"]
    p2 = p["tie_strap_pitch"] if run.get("options", {}).get("single_pitch") else \
        p["drive_link_pitch"]
    check_meshing(p["tie_strap_pitch"], p2, p["teeth"])  # before int()
    return Chain(p1=p["tie_strap_pitch"], p2=p2, z=int(p["teeth"]),
                 omega=p["sprocket_speed"], m_L=p["tie_strap_mass"],
                 m_C=p["drive_link_mass"], M=int(p["tie_straps_tight_side"]),
                 N=int(p["drive_links_tight_side"]), K=int(run["resolution"]["K"]))


def join_stages(stage1, stage2):
    """One period from two stages (stage 2's index 0 repeats t1 and is dropped)."""
    return np.concatenate([stage1, stage2[1:]])
