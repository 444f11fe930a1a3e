"""rolling_shear: 2-DOF hydraulic rolling-shear linkage, selPSO, lever optimisation.

Li & Wei, "Research of Rolling Shear Motion Laws Based On Improved PSO".
Effects (a scene names the ones it needs; the others are never evaluated):
``newton`` (warm-started continuation, the default solver), ``exact`` (closed-form
reference), ``selpso`` (the paper's solver), ``cold_root`` / ``least_squares`` (scipy from
random starts), ``initial_values`` (Fig. 12), ``lever_selpso`` / ``lever_de`` (lever
optimisation), ``lever_scan`` (which levers the objective determines).
"""
from .solver import EFFECTS, compute, solve, to_dataset

__all__ = ["EFFECTS", "compute", "solve", "to_dataset"]
