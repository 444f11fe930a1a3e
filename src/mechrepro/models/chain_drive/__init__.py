"""chain_drive: transverse vibration of a roller-chain span as an axially moving string.

Choi & Johnson, "Vibration of roller chain drives at low, medium and high operating
speeds" (University of Michigan).  The solvers and effects are declared in
config/papers/chain_drive.yaml (which solver honours which effect); finite differences
(Eqs. 2-36..2-38) at low/medium speed, Galerkin + RK4 (Eqs. 2-39..2-41) at high speed.

The names below are imported on first use (:func:`mechrepro.lazy.lazy_exports`), so that a reader of
results (the notebook imports ``figures``; validate_chain_drive ``claims`` and ``fd``) does
not import the solvers.
"""
from __future__ import annotations

from mechrepro.lazy import lazy_exports

#: public name -> submodule that defines it
_LAZY = {"EFFECTS": "effects", "SOLVERS": "solver", "variables": "solver",
         "warm": "solver"}

__all__ = list(_LAZY)
__getattr__, __dir__ = lazy_exports(__name__, _LAZY)
