"""rolling_shear: 2-DOF hydraulic rolling-shear linkage, selPSO, lever optimisation
(Li & Wei).  Names are imported on first use, so a reader of results does not import the
solvers."""
from __future__ import annotations

from mechrepro.lazy import lazy_exports

#: public name -> submodule that defines it
_LAZY = {"EFFECTS": "effects", "SOLVERS": "solver", "context": "solver",
         "variables": "solver", "warm": "kernels"}

__all__ = list(_LAZY)
__getattr__, __dir__ = lazy_exports(__name__, _LAZY)
