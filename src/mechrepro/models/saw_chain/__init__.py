"""saw_chain: polygon effect of an oil-saw chain by the kinematic difference method.

Shi, Peng, Zhao, Zhang, J. Mech. Sci. Technol. (KSME & Springer) 2012.
Solver ``difference_method`` (Eqs. 1-22); effects ``exact_reference`` (analytic derivatives
of the closed-form positions of Eqs. 7-10) and ``textbook`` (Eq. 23), computed beside it.
"""
from .effects import EFFECTS
from .solver import compute, solve, to_dataset

__all__ = ["EFFECTS", "compute", "solve", "to_dataset"]
