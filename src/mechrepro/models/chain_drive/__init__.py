"""chain_drive: transverse vibration of a roller-chain span as an axially moving string.

Choi & Johnson, "Vibration of roller chain drives at low, medium and high operating
speeds" (University of Michigan).  The solvers and effects are declared in
config/papers/chain_drive.yaml (which solver honours which effect); finite differences
(Eqs. 2-36..2-38) at low/medium speed, Galerkin + RK4 (Eqs. 2-39..2-41) at high speed.
"""
# imported on first use (mechrepro.lazy): the notebook, which reads datasets, does not
# import the solvers and scipy
from mechrepro.lazy import lazy_exports  # noqa: E402

#: public name -> submodule that defines it
_LAZY = {'EFFECTS': 'effects', 'solve': 'solver'}

__all__ = list(_LAZY)
__getattr__, __dir__ = lazy_exports(__name__, _LAZY)
