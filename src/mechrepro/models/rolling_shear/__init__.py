"""rolling_shear: 2-DOF hydraulic rolling-shear linkage, selPSO, lever optimisation.

Li & Wei, "Research of Rolling Shear Motion Laws Based On Improved PSO".
A scene names its solver (``continuation``, ``method_comparison``, ``lever_optimisation``,
``family_scan``; see solver.py) and its effects (effects.py); only those are evaluated.
"""
from .effects import EFFECTS
from .solver import SOLVERS, compute, solve, to_dataset

__all__ = ["EFFECTS", "SOLVERS", "compute", "solve", "to_dataset"]
