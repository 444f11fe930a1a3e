"""saw_chain: polygon effect of an oil-saw chain by the kinematic difference method.

Shi, Peng, Zhao, Zhang, J. Mech. Sci. Technol. (KSME & Springer) 2012.
Solver ``difference_method`` (Eqs. 1-22); effects ``exact_reference`` (analytic derivatives
of the closed-form positions of Eqs. 7-10) and ``textbook`` (Eq. 23), computed beside it.

The names below are imported on first use (:func:`mechrepro.lazy.lazy_exports`), so that a reader of
results (the notebook imports ``analysis``) does not import the solver.
"""
from __future__ import annotations

from mechrepro.lazy import lazy_exports

#: public name -> submodule that defines it
_LAZY = {"EFFECTS": "effects", "compute": "solver", "variables": "solver"}

__all__ = list(_LAZY)
__getattr__, __dir__ = lazy_exports(__name__, _LAZY)
