"""rolling_shear: 2-DOF hydraulic rolling-shear linkage, selPSO, lever optimisation.

Li & Wei, "Research of Rolling Shear Motion Laws Based On Improved PSO".
A scene names its solver (``continuation``, ``method_comparison``, ``lever_optimisation``,
``family_scan``; see solver.py) and its effects (effects.py); only those are evaluated.

The names below are imported on first use (:func:`mechrepro.lazy.lazy_exports`), so that a reader of
results (the notebook: ``validation``, ``drawing``) does not import the solvers and scipy.
"""
from __future__ import annotations

from mechrepro.lazy import lazy_exports

#: public name -> submodule that defines it
_LAZY = {"EFFECTS": "effects", "SOLVERS": "solver", "compute": "solver",
         "variables": "solver", "warm": "kernels"}

__all__ = list(_LAZY)
__getattr__, __dir__ = lazy_exports(__name__, _LAZY)
