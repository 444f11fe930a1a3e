"""saw_chain: polygon effect of an oil-saw chain by the kinematic difference method (Shi,
Peng, Zhao, Zhang, 2012).  Names are imported on first use, so a reader of results does not
import the solver."""
from __future__ import annotations

from mechrepro.lazy import lazy_exports

#: public name -> submodule that defines it
_LAZY = {"EFFECTS": "effects", "SOLVERS": "solver", "context": "solver", "variables": "solver"}

__all__ = list(_LAZY)
__getattr__, __dir__ = lazy_exports(__name__, _LAZY)
