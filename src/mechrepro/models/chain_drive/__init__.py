"""chain_drive: transverse vibration of a roller-chain span as an axially moving string.

Choi & Johnson, "Vibration of roller chain drives at low, medium and high operating
speeds" (University of Michigan).  Effects: speed_tensioning, impact, polygonal_rigid,
polygonal_elastic, external_load, end_excitation, length_change, sag,
longitudinal_coupling.  Finite differences (Eqs. 2-36..2-38) at low/medium speed,
Galerkin + RK4 (Eqs. 2-39..2-41) at high speed.
"""
from .effects import EFFECTS
from .solver import solve

__all__ = ["EFFECTS", "solve"]
