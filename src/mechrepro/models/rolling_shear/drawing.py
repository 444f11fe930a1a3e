"""The assembled linkage of a solved run, for drawing (Figs. 2-5): every joint (mm)."""
from __future__ import annotations

import numpy as np

from .blade import arc_points, carrier_points
from .geometry import GEOMETRY_KEYS, Geometry
from .loops import pivots


def geometry_of(ds) -> Geometry:
    """The run's own geometry (calibrated, with the scene's levers) from its dataset."""
    return Geometry(**{k: float(ds[f"geometry_{k}"]) for k in GEOMETRY_KEYS})


def linkage_at(ds, i: int, prefix: str = "exact", blade_half_width: float = 1900.0) -> dict:
    """The linkage at cut point ``i`` (motion laws ``<prefix>_theta1..6``): ``links``, (start, end)
    joint pairs as complex x + iy, and ``blade``, the cutting-edge arc over +- ``blade_half_width``."""
    g = geometry_of(ds)
    t = [float(ds[f"{prefix}_theta{k}"][i]) for k in range(1, 7)]
    P = carrier_points(g, t[4], t[5])
    A, G = pivots(g)
    B = A + g.l1 * np.exp(1j * t[0])
    H = G + g.l2 * np.exp(1j * t[1])
    links = [(0j, P["D"]), (A, B), (B, P["C"]), (G, H), (H, P["I"]), (P["D"], P["I"]),
             (P["D"], P["C"]), (P["D"], P["O"])]
    return {"links": links, "blade": arc_points(g, t[4], t[5], blade_half_width / g.R, 200)}
