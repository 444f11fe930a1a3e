"""saw_chain: polygon effect of an oil-saw chain by the kinematic difference method.

Shi, Peng, Zhao, Zhang, J. Mech. Sci. Technol. (KSME & Springer) 2012.
Effects: ``difference_method`` (Eqs. 1-22), ``textbook`` (Eq. 23), ``exact_reference``
(analytic derivatives of the closed-form positions of Eqs. 7-10).
"""
from .solver import EFFECTS, compute, solve, to_dataset

__all__ = ["EFFECTS", "compute", "solve", "to_dataset"]
