"""The one owner of optional compiled kernels (numba).

Every model asks :func:`available` whether its compiled path may run, and compiles with
:func:`jit`: the choice depends on the installation (and on an explicit switch a test or
benchmark sets before the process first asks, ``MECHREPRO_KERNEL=numpy``), never on what
ran before, and the compiled and the Python path execute the same source.
"""
from __future__ import annotations

import hashlib
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


@cache
def available(switch: str | None = None) -> bool:
    """numba is installed and neither :data:`SWITCH` nor the model's own ``switch``
    variable says ``numpy``.  Read once per process and switch (a model asks per solve,
    tens of thousands of times a run, and each read of the environment costs microseconds):
    a switch set before the process first asks is honoured; a test that switches in-process
    calls ``available.cache_clear()``."""
    for name in (SWITCH, switch):
        if name and os.environ.get(name, "auto") == "numpy":
            return False
    return _numba()


def _cache_root() -> Path:
    """Where compiled kernels are kept: ``NUMBA_CACHE_DIR`` if set, else the user's cache
    (``$XDG_CACHE_HOME``, ``~/.cache``), so that every copy of the project shares them."""
    root = os.environ.get("NUMBA_CACHE_DIR") or os.environ.get("XDG_CACHE_HOME") \
        or Path.home() / ".cache"
    return Path(root) / "mechrepro" / "numba"


@cache
def _cache_dir(package: Path) -> str:
    """numba's disk cache for the kernels of one model package, keyed by the source of every
    file in it: numba keys a cached kernel on its own file alone, so a kernel that calls
    another file's (joint_wear's Radau calls clearance.py's right-hand side) would keep
    running the old code after that file changed.  Not keyed by where the package lies:
    numba's own locators hash the absolute path, so each copy of the project (the test
    suite's pipelines, an experiment, a moved checkout) would compile every kernel again."""
    digest = hashlib.sha256(b"".join(p.read_bytes() for p in sorted(package.glob("*.py"))))
    return str(_cache_root() / f"{package.name}-{digest.hexdigest()[:16]}")


@cache
def _locator():
    """numba's locator of a kernel compiled by :func:`jit` (set on the function as
    ``_mechrepro_jit``): the cache directory is :func:`_cache_dir` of its package."""
    from numba.core.caching import CacheImpl, UserProvidedCacheLocator

    class PackageLocator(UserProvidedCacheLocator):
        def __init__(self, py_func, py_file):
            self._py_file = py_file
            self._lineno = py_func.__code__.co_firstlineno
            self._cache_path = _cache_dir(Path(py_file).resolve().parent)

        @classmethod
        def from_function(cls, py_func, py_file):
            if not getattr(py_func, "_mechrepro_jit", False) or not os.path.exists(py_file):
                return None
            self = cls(py_func, py_file)
            try:
                self.ensure_cache_path()
            except OSError:       # not writable: numba's own locators take over
                return None
            return self

    CacheImpl._locator_classes.insert(0, PackageLocator)
    return PackageLocator


def jit(fn=None, **options):
    """``numba.njit(cache=True, error_model="numpy", **options)`` where compiled kernels are
    :func:`available`, the function itself otherwise (the same source runs as Python)."""
    def wrap(f):
        if not available():
            return f
        import numba

        _locator()
        f._mechrepro_jit = True    # the cache locator is chosen when the kernel is decorated
        return numba.njit(cache=True, error_model="numpy", **options)(f)
    return wrap(fn) if fn is not None else wrap
