"""chain_drive's solvers follow the framework's contract (``SOLVERS[run["solver"]](run, ctx)``
returns labelled variables; only that call is timed) and its deliberate errors are
mechrepro.errors.Refusal subclasses."""
import subprocess
import sys

import numpy as np
import pytest

from mechrepro.config import load_paper
from mechrepro.errors import Refusal
from mechrepro.models import chain_drive
from mechrepro.models.chain_drive import errors, fd, shooting
from mechrepro.solve import UnknownSolver, compute, pack, solve


def declared(effects) -> dict:
    """A run record for a list of effect names (or a run whose effects were swapped), with
    what each declares it contributes (the config's ``effects:``), as a config run has."""
    spec = load_paper("config/papers/chain_drive.yaml").raw["effects"]
    run = effects if isinstance(effects, dict) else {"effects": list(effects)}
    return {**run, "contributes": {e: spec.get(e, {}).get("contributes", [])
                                   for e in run["effects"]}}


def test_compute_then_variables_is_the_frameworks_solve():
    run = load_paper("config/papers/chain_drive.yaml").runs["accuracy_peak"]
    result = compute(run)
    # labelled variables (mechrepro.units.var), no Dataset: the framework packs them
    assert all(isinstance(v, str) or (isinstance(v, tuple) and len(v) == 3)
               for v in result.values())
    a, b = pack(chain_drive.variables(result, run), run), solve(run)
    assert np.array_equal(a.amplitude.values, b.amplitude.values)
    assert set(a.data_vars) == set(b.data_vars)


def test_the_solvers_import_no_xarray():
    code = ("import sys; from mechrepro.models.chain_drive import exact, galerkin, solver; "
            "print('xarray' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_deliberate_errors_are_refusals():
    for name in dir(errors):
        obj = getattr(errors, name)
        if isinstance(obj, type) and obj.__module__ == errors.__name__:
            assert issubclass(obj, Refusal)
    assert fd.StabilityError is errors.StabilityError
    assert shooting.PeriodicityError is errors.PeriodicityError
    with pytest.raises(UnknownSolver):
        compute({"paper": "chain_drive", "solver": "nope", "parameters": {}, "resolution": {}})
    with pytest.raises(errors.StabilityError):
        fd.stable_time_step(1e-3, [0.0], [-1.0], 1.0)
