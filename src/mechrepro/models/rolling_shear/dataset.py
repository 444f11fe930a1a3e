"""The run's dataset: the solver's outputs, the derived constants of its geometry and the
calibration, with coordinates (mm, rad)."""
from __future__ import annotations

import math

import numpy as np
import xarray as xr

from mechrepro.units import var

from .context import Context
from .geometry import GEOMETRY_KEYS, OPTIMISED_LEVERS
from .motion_laws import ANGLE_NAMES

__all__ = ["GEOMETRY_KEYS", "geometry_outputs", "to_dataset"]


def geometry_outputs(ctx: Context) -> dict:
    """The constants of the run's geometry (after calibration and the scene's lever set)
    and its calibration (mm, rad)."""
    g = ctx.g
    out = {f"geometry_{k}": var((), getattr(g, k), "rad" if k in ("alpha", "beta1", "beta2") else "mm",
                                f"constant {k} of the run's geometry")
           for k in GEOMETRY_KEYS}
    out["geometry_tilt"] = var((), dict(ctx.g_original.intents)["theta6_mid"] - math.pi, "rad",
                               "guide-rod tilt at mid-cut, theta6_mid - pi (calibrated if the run calibrates)")
    if ctx.calibration is not None:
        n = ctx.calibration["n"]
        out["calibrated_H_original"] = var(
            (), ctx.calibration["H_original"], "mm",
            f"synthetic horizontal displacement of the original levers after calibration, {n} cut points")
        if "H_levers" in ctx.calibration:
            out["calibrated_H_levers"] = var(
                (), ctx.calibration["H_levers"], "mm",
                f"synthetic horizontal displacement of the scene's levers, {n} cut points")
    return out


def to_dataset(result: dict, run: dict) -> xr.Dataset:
    ctx: Context = result["ctx"]
    data = result["data"]
    coords = {
        "cut": ("cut", np.arange(ctx.n), {"units": "1", "long_name": "cut point index"}),
        "huch": ("cut", ctx.huch, {"units": "mm", "long_name": "rolled length from the start of the cut"}),
        "x_k_target": ("cut", ctx.x_k, {"units": "mm", "long_name": "prescribed x of the lowest point on y = -s"}),
        "angle": ("angle", list(ANGLE_NAMES), {"units": "1", "long_name": "unknown angle"}),
        "lever": ("lever", list(OPTIMISED_LEVERS), {"units": "1", "long_name": "optimised lever"}),
        "loop": ("loop", ["ABCD", "GHID"], {"units": "1", "long_name": "dyad of Eq. (9)"}),
    }
    used = {d for dims, *_ in data.values() for d in dims}
    coords = {k: v for k, v in coords.items() if v[0] in used or k in ("cut", "huch", "x_k_target")}
    ds = xr.Dataset(dict(data), coords)
    for d in ds.dims:
        if d not in ds.coords:
            ds = ds.assign_coords({d: (d, np.arange(ds.sizes[d]),
                                       {"units": "1", "long_name": f"{d} index"})})
    ds.attrs["length_unit"] = "mm"
    ds["pose_tol_used"] = var((), ctx.settings.tol_pose, "mm", "tolerance on G of Eq. (7)")
    ds["loops_tol_used"] = var((), ctx.settings.tol_loops, "mm", "tolerance on G of Eq. (9)")
    ds["blade_radius"] = var((), ctx.g.R, "mm", "blade arc radius R")
    return ds
