"""disk_tension: vibration of a circular saw disk tensioned by rolling (FEM).

Kuratani & Yano: thermal-analogy residual stress (Eq. 4), stress stiffening (Eq. 3),
eigen-analysis (Eq. 5), the first-order estimate (Eq. 9) and the modal matrices
(Eqs. 16-17), on two discretisations checked against the exact Bessel solution.  The names
below are imported on first use, so that a reader of results does not import the solvers.
"""
from __future__ import annotations

from mechrepro.lazy import lazy_exports

#: public name -> submodule that defines it
_LAZY = {"EFFECTS": "effects", "SOLVERS": "solver", "context": "solver", "variables": "solver"}

__all__ = list(_LAZY)
__getattr__, __dir__ = lazy_exports(__name__, _LAZY)
