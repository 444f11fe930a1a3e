"""rolling_shear's entry point: the scene's solver, its effects, one xarray Dataset (mm, rad).

    solver               what it computes                                    effects it honours
    continuation         Newton stroke + closed form (continuation.py)       constant_rate_drive, tilt_scan
    method_comparison    the same + options.methods at every cut point        constant_rate_drive, tilt_scan,
                         (comparison.py)                                      initial_values
    lever_optimisation   levers by options.optimisers (lever_optimisation.py) lever_scan
    family_scan          the admissible family on a grid (family.py)          (none)
"""
from __future__ import annotations

from .comparison import solve_method_comparison
from .context import Context
from .continuation import solve_continuation
from .dataset import geometry_outputs, to_dataset
from .effects import EFFECTS
from .family import solve_family_scan
from .lever_optimisation import solve_lever_optimisation

SOLVERS = {"continuation": solve_continuation, "method_comparison": solve_method_comparison,
           "lever_optimisation": solve_lever_optimisation, "family_scan": solve_family_scan}


def compute(run: dict) -> dict:
    """The physics of one run: its solver, which evaluates only the effects it names."""
    ctx = Context(run)
    data = SOLVERS[run["solver"]](run, ctx)
    data.update(geometry_outputs(ctx))
    return {"ctx": ctx, "data": data}


def solve(run: dict):
    return to_dataset(compute(run), run)


__all__ = ["EFFECTS", "SOLVERS", "compute", "solve", "to_dataset"]
