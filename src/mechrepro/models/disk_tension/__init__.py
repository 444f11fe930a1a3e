"""disk_tension: vibration of a circular saw disk tensioned by rolling (FEM).

Kuratani & Yano, "Vibration analysis of a circular disk tensioned by rolling using finite
element method".  Thermal-analogy residual stress (Eq. 4), stress stiffening (Eq. 3),
eigen-analysis (Eq. 5), the first-order estimate (Eq. 9) and the modal matrices
(Eqs. 16-17), on two discretisations (axisymmetric harmonics, 2-D Argyris plate) checked
against the exact Bessel solution.
"""
from .effects import EFFECTS
from .solver import compute, solve, to_dataset

__all__ = ["EFFECTS", "compute", "solve", "to_dataset"]
