"""rolling_shear: 2-DOF hydraulic rolling-shear linkage, selPSO, lever optimisation.

Li & Wei, "Research of Rolling Shear Motion Laws Based On Improved PSO".
A scene names its solver (``continuation``, ``method_comparison``, ``lever_optimisation``,
``family_scan``; see solver.py) and its effects (effects.py); only those are evaluated.

The names below are imported on first use (module ``__getattr__``), so that a reader of
results (the notebook: ``validation``, ``drawing``) does not import the solvers and scipy.
"""
from __future__ import annotations

import importlib

#: public name -> submodule that defines it
_LAZY = {"EFFECTS": "effects", "SOLVERS": "solver", "compute": "solver", "solve": "solver",
         "to_dataset": "solver"}

__all__ = list(_LAZY)


def __getattr__(name: str):
    if name in _LAZY:
        value = getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(__all__))
