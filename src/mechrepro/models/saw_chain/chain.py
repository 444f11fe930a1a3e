"""The chain of one run: geometry, masses and the time grid of one period (Eqs. 1-6).

Shared by the solver (:mod:`.solver`) and the effects (:mod:`.effects`) that are
evaluated beside it on the same grid.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .difference import roundoff_limit, velocity_roundoff_limit
from .geometry import check_meshing, initial_points, pitch_radius, stage_angles
from .kinematics import stage_derivatives, stage_jerks
from .loads import tight_side_mass


@dataclass(frozen=True)
class Chain:
    """Geometry, masses and the time grid of one period (2K steps, Eqs. 5-6)."""
    p1: float
    p2: float
    z: int
    omega: float
    m_L: float
    m_C: float
    M: int
    N: int
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

    def stages(self):
        """(lead-link length, link mass, local angles phi_i, i = 0..K) for each stage."""
        phi1, phi2 = self.phases
        return [(self.p2, self.m_C, np.linspace(0.0, phi1, self.K + 1)),
                (self.p1, self.m_L, np.linspace(0.0, phi2 - phi1, self.K + 1))]

    def stage_times(self):
        """Durations t1 and t2 - t1 of the two stages [s]."""
        phi1, phi2 = self.phases
        return phi1 / self.omega, (phi2 - phi1) / self.omega

    def load_jerk_max(self, n=129):
        """max |dF_dx/dt| of the exact load in each stage [N/s].

        The jerk is smooth within a stage, so a fixed grid of ``n`` angles (ends
        included) gives its maximum to ~1e-6, independently of K.
        """
        out = []
        for L, m_link, phi in self.stages():
            j = stage_jerks(np.linspace(0.0, phi[-1], n), self.R, L, self.omega)
            out.append(float(np.max(np.abs(m_link * j["mid_jx"] + self.m_tight * j["trail_jx"]))))
        return out

    def roundoff_mass(self):
        """Mass multiplying second differences in one load sample (tight side + seating link)."""
        return self.m_tight + max(self.m_L, self.m_C)

    def roundoff_limit(self):
        """K beyond which round-off dominates the loads (see :mod:`.difference`)."""
        return roundoff_limit(self.stage_times(), self.load_jerk_max(), self.Tx + self.R,
                              self.roundoff_mass())

    def velocity_roundoff_limit(self, n=129):
        """K beyond which round-off dominates the velocity (first difference; see
        :mod:`.difference`); max |a| of the trailing hinge on a fixed grid of ``n`` angles."""
        acc = [float(np.max(np.abs(stage_derivatives(np.linspace(0.0, phi[-1], n), self.R, L,
                                                     self.omega)["trail_ax"])))
               for L, _, phi in self.stages()]
        return velocity_roundoff_limit(self.stage_times(), acc, self.Tx + self.R)

    def time(self):
        """Sample times: t = 0, then K steps of each stage [s]."""
        phi1, phi2 = self.phases
        return np.concatenate([np.linspace(0.0, phi1, self.K + 1),
                               np.linspace(phi1, phi2, self.K + 1)[1:]]) / self.omega


def chain_from_run(run: dict) -> Chain:
    p = run["parameters"]
    check_meshing(p["tie_strap_pitch"], p["drive_link_pitch"], p["teeth"])  # before int()
    return Chain(p1=p["tie_strap_pitch"], p2=p["drive_link_pitch"], z=int(p["teeth"]),
                 omega=p["sprocket_speed"], m_L=p["tie_strap_mass"],
                 m_C=p["drive_link_mass"], M=int(p["tie_straps_tight_side"]),
                 N=int(p["drive_links_tight_side"]), K=int(run["resolution"]["K"]))


def join_stages(stage1, stage2):
    """One period from two stages sampled at i = 0..K: stage 2's index 0 repeats t1 and is
    dropped."""
    return np.concatenate([stage1, stage2[1:]])
