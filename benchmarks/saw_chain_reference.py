"""What the saw_chain benchmark times against the pipeline: the whole difference method as a
per-step Python loop (the paper's MATLAB style), the one tests/test_saw_chain.py checks the
solver against (loaded from there by path: no copy, no sys.path edit), and the Richardson
extrapolation of one extremum from K/4, K/2, K (as in tests/test_saw_chain_richardson.py)."""
from __future__ import annotations

import importlib.util
from dataclasses import replace
from pathlib import Path

import numpy as np

from mechrepro.models.saw_chain.difference import load_x
from mechrepro.models.saw_chain.richardson import _levels, from_levels

_spec = importlib.util.spec_from_file_location(
    "saw_chain_test_reference", Path(__file__).resolve().parent.parent / "tests" / "test_saw_chain.py")
_tests = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_tests)
difference_method_loop = _tests.difference_method_loop


def extrapolate_extreme(chain, K: int, fn=np.max):
    """``fn`` of the load x over one period, extrapolated from K/4, K/2, K."""
    Ks = _levels(K)
    return from_levels(chain, Ks, [float(fn(load_x(replace(chain, K=k)))) for k in Ks])
