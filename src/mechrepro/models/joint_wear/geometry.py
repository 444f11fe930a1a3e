"""The four-bar of Table 1 and the clearance joint B of Table 2, as one immutable record.

All values SI.  Built once per run from the run record's ``parameters`` (already SI).
Link angles are measured anticlockwise from the ground line A -> D (the global x axis,
Point A = origin, Sec. 4.1).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

from mechrepro.errors import Refusal


@dataclass(frozen=True)
class FourBar:
    l1: float          # crank AB [m]
    l2: float          # coupler BC [m]
    l3: float          # follower CD [m]
    l0: float          # ground AD [m]
    m2: float          # coupler mass [kg]
    m3: float          # follower mass [kg]
    I2: float          # coupler inertia about its centre, pin axis [kg m2]
    I3: float          # follower inertia about its centre, pin axis [kg m2]
    omega: float       # crank speed [rad/s]
    P: float           # load magnitude at E [N]
    F: tuple           # fixed point the load points to [m]
    g: float           # gravity [m/s2], acting in -y; 0 when the gravity effect is off
    R_pin: float       # pin radius R_i [m]
    R_bush: float      # bushing radius R_j [m]
    width: float       # pin-bushing width w [m]
    K_contact: float   # K' of Eq. (12) [N/m^n]
    n_exp: float       # exponent n of Eq. (11)
    d_max: float       # d_max of Eq. (14) [m]
    C_max: float       # C_max of Eq. (14) [N s/m]
    mu: float          # friction coefficient of Eq. (15); 0 when friction is off
    v_eps: float       # velocity scale of the regularised Coulomb law [m/s]

    @property
    def clearance(self) -> float:
        """c = R_j - R_i (Sec. 2.2.1; the paper's 'R_i - R_j' is a sign slip)."""
        return self.R_bush - self.R_pin

    @property
    def period(self) -> float:
        return 2.0 * math.pi / self.omega

    def with_bushing_radius(self, R_bush: float) -> "FourBar":
        """The worn joint: a larger bushing circle, K' of Eq. (12) re-evaluated."""
        K = stiffness_K(self.R_pin, R_bush, self._h_sum)
        # C_max stays the same fraction of K' (Sec. 2.2.2)
        return replace(self, R_bush=R_bush, K_contact=K, C_max=self.C_max * K / self.K_contact)

    _h_sum: float = 0.0  # h_i + h_j of Eq. (13) [1/Pa], kept for re-evaluating K'


def material_h(E: float, nu: float) -> float:
    """Eq. (13): h_k = (1 - nu_k^2) / (pi E_k)  [1/Pa]."""
    return (1.0 - nu * nu) / (math.pi * E)


def stiffness_K(R_pin: float, R_bush: float, h_sum: float) -> float:
    """Eq. (12): K' = 4 / (3 pi (h_i + h_j)) * (R_i R_j / (R_j - R_i))^(1/2)  [N/m^1.5]."""
    c = R_bush - R_pin
    if not c > 0.0:
        raise Refusal(f"joint_wear: clearance R_bush - R_pin = {c!r} m must be > 0")
    return 4.0 / (3.0 * math.pi * h_sum) * math.sqrt(R_pin * R_bush / c)


def from_parameters(p: dict) -> FourBar:
    """The bare mechanism from SI run parameters: no gravity, no friction, no damping.

    The effects ``gravity``, ``friction`` and ``contact_damping`` switch those terms on
    (solver.py); a term that is off is zero and costs nothing.
    """
    c = p["radial_clearance"]
    if not c > 0.0:
        raise Refusal(f"joint_wear: radial_clearance = {c!r} m: the clearance must be > 0 "
                         "(a pin as large as the bushing is an ideal joint, not a clearance joint)")
    R_bush = p["pin_radius"] + c
    h_sum = material_h(p["E_pin"], p["nu_pin"]) + material_h(p["E_bushing"], p["nu_bushing"])
    K = stiffness_K(p["pin_radius"], R_bush, h_sum)
    return FourBar(
        l1=p["crank_length"], l2=p["coupler_length"], l3=p["follower_length"],
        l0=p["ground_length"], m2=p["coupler_mass"], m3=p["follower_mass"],
        I2=p["coupler_inertia"], I3=p["follower_inertia"], omega=p["crank_speed"],
        P=p["load"], F=(p["load_point_x"], p["load_point_y"]), g=0.0,
        R_pin=p["pin_radius"], R_bush=R_bush, width=p["width"],
        K_contact=K, n_exp=p["contact_exponent"], d_max=p["d_max"],
        C_max=p["C_max_ratio"] * K, mu=0.0, v_eps=p["friction_v_eps"], _h_sum=h_sum)
