"""The one owner of optional compiled kernels (numba).

Every model asks :func:`available` whether its compiled path may run, and compiles with
:func:`jit`: the choice depends on the installation (and on an explicit switch a test or
benchmark sets, ``MECHREPRO_KERNEL=numpy``), never on what ran before, and the compiled
and the Python path execute the same source.
"""
from __future__ import annotations

import hashlib
import inspect
import os
from functools import cache
from pathlib import Path

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


@cache
def _cache_dir(package: Path) -> str:
    """numba's disk cache for the kernels of one model package, keyed by the source of every
    file in it: numba keys a cached kernel on its own file alone, so a kernel that calls
    another file's (joint_wear's Radau calls clearance.py's right-hand side) would keep
    running the old code after that file changed."""
    digest = hashlib.sha256(b"".join(p.read_bytes() for p in sorted(package.glob("*.py"))))
    return str(package / "__pycache__" / "numba" / digest.hexdigest()[:16])


def jit(fn=None, **options):
    """``numba.njit(cache=True, error_model="numpy", **options)`` where compiled kernels are
    :func:`available`, the function itself otherwise (the same source runs as Python)."""
    def wrap(f):
        if not available():
            return f
        import numba

        before = numba.config.CACHE_DIR
        # the cache locator reads the directory when the kernel is decorated
        numba.config.CACHE_DIR = _cache_dir(Path(inspect.getfile(f)).resolve().parent)
        try:
            return numba.njit(cache=True, error_model="numpy", **options)(f)
        finally:
            numba.config.CACHE_DIR = before
    return wrap(fn) if fn is not None else wrap
