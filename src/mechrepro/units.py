"""Units accepted in config files and their conversion to SI.

Configs keep the papers' own units (mm, r/min, g ...) so every value can be checked
against its source; solvers only ever see SI values.  ``to_si(value, unit)`` returns
``(value_si, si_unit)``; ``var(dims, data, units, long_name)`` labels a dataset variable.
"""
from __future__ import annotations

import math

# unit -> (factor to SI, SI unit).  Affine units (degC) are treated as differences.
UNITS: dict[str, tuple[float, str]] = {
    "1": (1.0, "1"),
    "m": (1.0, "m"), "mm": (1e-3, "m"), "cm": (1e-2, "m"), "um": (1e-6, "m"),
    "kg": (1.0, "kg"), "g": (1e-3, "kg"),
    "s": (1.0, "s"), "ms": (1e-3, "s"), "h": (3600.0, "s"),
    "N": (1.0, "N"), "kN": (1e3, "N"), "N/m": (1.0, "N/m"), "N*m": (1.0, "N*m"),
    "Pa": (1.0, "Pa"), "kPa": (1e3, "Pa"), "MPa": (1e6, "Pa"), "GPa": (1e9, "Pa"),
    "rad": (1.0, "rad"), "deg": (math.pi / 180.0, "rad"),
    "rad/s": (1.0, "rad/s"), "rpm": (2 * math.pi / 60.0, "rad/s"),
    "r/min": (2 * math.pi / 60.0, "rad/s"), "Hz": (1.0, "Hz"),
    "m/s": (1.0, "m/s"), "m/s2": (1.0, "m/s2"),
    "kg/m": (1.0, "kg/m"), "kg/m3": (1.0, "kg/m3"), "g/cm3": (1e3, "kg/m3"),
    "kg*m2": (1.0, "kg*m2"), "g*mm2": (1e-9, "kg*m2"),
    "degC": (1.0, "K"), "K": (1.0, "K"), "1/K": (1.0, "1/K"), "rad2/s2": (1.0, "rad2/s2"),
    "N*s/m": (1.0, "N*s/m"), "N*s/m2": (1.0, "N*s/m2"), "m3/(N*m)": (1.0, "m3/(N*m)"),
    "mm3/(N*m)": (1e-9, "m3/(N*m)"), "m2/N": (1.0, "m2/N"), "HB": (9.80665e6, "Pa"),
}


def to_si(value, unit: str):
    """Convert a scalar or a list of scalars from ``unit`` to SI."""
    factor, si = UNITS[unit]
    if isinstance(value, (list, tuple)):
        return [_scale(v, factor) for v in value], si
    return _scale(value, factor), si


def _scale(v, factor):
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        return v  # strings, booleans: unitless choices, passed through
    return v * factor if factor != 1.0 else v


def var(dims, data, units: str, long_name: str, **attrs):
    """A dataset variable with its unit: ``ds[name] = var(("speed",), x, "N", "peak load")``.

    ``dims`` is a dimension name, a tuple of them, or ``()`` for a scalar; ``units`` is the
    UDUNITS spelling (``"1"`` for dimensionless).  The one way the models label their output.
    """
    import numpy as np

    dims = (dims,) if isinstance(dims, str) else tuple(dims)
    return dims, np.asarray(data), {"units": units, "long_name": long_name, **attrs}


def from_si(value, unit: str):
    """SI value(s) expressed in ``unit`` (a figure axis in the paper's units)."""
    factor, _ = UNITS[unit]
    return value / factor if factor != 1.0 else value
