"""disk_tension's load-time limits and cost form (read by :mod:`mechrepro.limits` before any
job): the stiffened annuli of Fig. 7 inside the flexible region, which the effect
:func:`.effects.stiffness_sensitivity` would otherwise refuse inside the job, and the work
of a run (:func:`work`; the seconds per unit are data, config/costs.csv)."""
from __future__ import annotations

import math

import numpy as np


def _mm(x) -> str:
    return f"{x * 1e3:g} mm"


def check(run: dict) -> list[str]:
    p, out = run["parameters"], []
    b = p["outer_diameter"] / 2
    r_f = p["clamp_radius"]
    if "stiffness_sensitivity" in run["effects"] and 0 < r_f < b:
        r_a = np.atleast_1d(np.asarray(p["annulus_radii"], float))
        w = p["annulus_width"]
        bad = r_a[(r_a - w / 2 < r_f - 1e-12) | (r_a + w / 2 > b + 1e-12)]
        if bad.size:
            out.append(f"parameters.annulus_radii: {', '.join(_mm(r) for r in bad)} (+/- "
                       f"{_mm(w / 2)}) leave the flexible region [r_f, b] = [{_mm(r_f)}, "
                       f"{_mm(b)}] (effect stiffness_sensitivity refuses them); allowed: "
                       f"{_mm(r_f + w / 2)} <= r_a <= {_mm(b - w / 2)}")
    return out


def _size(run: dict) -> int:
    """Radial elements of the axisymmetric model, or cells of the 2-D mesh."""
    res = run["resolution"]
    if "n_elements" in res:
        return int(res["n_elements"])
    return int(res.get("n_rings", 1)) * int(res.get("n_sectors", 8))


def work(run: dict) -> dict:
    """The cost form: an assembly linear and an eigen-solve quadratic in the size
    (:func:`_size`), and each effect's and output's work linear in it and in the points of
    the swept parameters it solves again (rolling radii, nodal diameters; the design map's
    amplitude steps too)."""
    n, p = float(_size(run)), run["parameters"]
    grid = n * math.prod(len(v) for v in p.values() if isinstance(v, list))
    return {"run": 1.0, "size": n, "size^2": n * n,
            **{e: grid * (int(p["design_steps"]) if e == "design_map" else 1)
               for e in run["effects"] + run["outputs"]}}


def mem_mb(run: dict) -> float:
    """Peak memory [MB] (typed, no run records it): dense matrices quadratic in the radial
    elements, the 2-D mesh's linear in its cells."""
    return 160 + (7.5e-4 * _size(run) ** 2 if "n_elements" in run["resolution"] else 0.2 * _size(run))
