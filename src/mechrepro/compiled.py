"""The one owner of optional compiled kernels (numba).

Every model asks :func:`available` whether its compiled path may run, and compiles with
:func:`jit`: the choice depends on the installation (and on an explicit switch a test or
benchmark sets, ``MECHREPRO_KERNEL=numpy``), never on what ran before, and the compiled
and the Python path execute the same source.
"""
from __future__ import annotations

import os
from functools import cache

#: set to ``numpy`` to run every model's Python path (tests, benchmarks)
SWITCH = "MECHREPRO_KERNEL"


@cache
def _numba() -> bool:
    try:
        import numba  # noqa: F401
    except ImportError:
        return False
    return True


def available(switch: str | None = None) -> bool:
    """numba is installed and neither :data:`SWITCH` nor the model's own ``switch``
    variable says ``numpy``."""
    for name in (SWITCH, switch):
        if name and os.environ.get(name, "auto") == "numpy":
            return False
    return _numba()


def jit(fn=None, **options):
    """``numba.njit(cache=True, error_model="numpy", **options)`` where compiled kernels are
    :func:`available`, the function itself otherwise (the same source runs as Python)."""
    def wrap(f):
        if not available():
            return f
        import numba

        return numba.njit(cache=True, error_model="numpy", **options)(f)
    return wrap(fn) if fn is not None else wrap
