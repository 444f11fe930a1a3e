"""disk_tension: vibration of a circular saw disk tensioned by rolling (FEM).

Kuratani & Yano, "Vibration analysis of a circular disk tensioned by rolling using finite
element method".  Thermal-analogy residual stress (Eq. 4), stress stiffening (Eq. 3),
eigen-analysis (Eq. 5), the first-order estimate (Eq. 9) and the modal matrices
(Eqs. 16-17), on two discretisations (axisymmetric harmonics, 2-D Argyris plate) checked
against the exact Bessel solution.

The names below are imported on first use (:func:`mechrepro.lazy.lazy_exports`), so that a reader of
results (the notebook imports ``figures``; validate_disk_tension ``figures`` and ``modal``) does
not import the solvers and scipy.
"""
from __future__ import annotations

from mechrepro.lazy import lazy_exports

#: public name -> submodule that defines it
_LAZY = {"EFFECTS": "effects", "compute": "solver", "variables": "solver"}

__all__ = list(_LAZY)
__getattr__, __dir__ = lazy_exports(__name__, _LAZY)
