"""rolling_shear's entry point: the scene's solver (continuation, method_comparison,
lever_optimisation, family_scan, design_front), its effects and the run's variables."""
from __future__ import annotations

import numpy as np

from mechrepro.units import var

from .comparison import solve_method_comparison
from .context import Context, Refused
from .continuation import solve_continuation
from .dataset import geometry_outputs
from .dataset import variables as _variables
from .effects import EFFECTS
from .family import solve_family_scan
from .front import solve_design_front
from .lever_optimisation import solve_lever_optimisation

SOLVERS = {"continuation": solve_continuation, "method_comparison": solve_method_comparison,
           "lever_optimisation": solve_lever_optimisation, "family_scan": solve_family_scan,
           "design_front": solve_design_front}


def compute(run: dict) -> dict:
    """The run's solver; a lever set refused by name gives ``{"refused": ...}``."""
    try:
        ctx = Context(run)
        data = SOLVERS[run["solver"]](run, ctx)
    except Refused as exc:
        return {"refused": exc}
    data.update(geometry_outputs(ctx))
    return {"ctx": ctx, "data": data}


def refusal_variables(exc: Refused) -> dict:
    """The variables of a refused lever set: what was refused and why, no stroke."""
    return {
        "levers_assemble": var((), 0.0 if exc.kind == "assembly" else np.nan, "1",
                               "1: the lever set assembles over the stroke; 0: refused; NaN: "
                               "the member was refused before (not calibrated, not buildable)"),
        "calibrated": var((), float(exc.kind != "calibration"), "1",
                          "1: the family member reaches the paper's 1.4341 at some tilt"),
        "buildable": var((), 0.0 if exc.kind == "unbuildable" else np.nan, "1",
                         "0: the calibrated member breaks a constraint of constraints.py"),
        "length_unit": "mm", "refusal_kind": exc.kind, "refusal": exc.message}


def variables(result: dict, run: dict) -> dict:
    if "refused" in result:
        return refusal_variables(result["refused"])
    return _variables(result, run)


__all__ = ["EFFECTS", "SOLVERS", "compute", "variables"]
