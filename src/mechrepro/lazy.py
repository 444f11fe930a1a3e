"""Lazy public names of a model package (PEP 562): ``import mechrepro.models.<paper>`` stays
cheap (a notebook or a validation job that reads datasets never loads the solvers and
their scipy/numba imports); a name is imported from its submodule on first use."""
from __future__ import annotations

import importlib
import sys


def lazy_exports(package: str, names: dict[str, str]):
    """``__getattr__, __dir__ = lazy_exports(__name__, {public name: submodule})``."""
    module = sys.modules[package]

    def __getattr__(name: str):
        if name in names:
            value = getattr(importlib.import_module(f".{names[name]}", package), name)
            setattr(module, name, value)   # later lookups skip __getattr__
            return value
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    def __dir__():
        return sorted(set(vars(module)) | set(names))

    return __getattr__, __dir__
