"""disk_tension's load-time limits (read by :mod:`mechrepro.limits` before any job): the
stiffened annuli of Fig. 7 inside the flexible region, which the effect
:func:`.effects.stiffness_sensitivity` would otherwise refuse inside the job."""
from __future__ import annotations

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


def cost(run: dict) -> dict:
    """Peak memory [MB] and time [s] of one run: quadratic in the radial elements, linear in
    the cells of the 2-D mesh (fits above the benchmark's measurements)."""
    res = run["resolution"]
    if "n_elements" in res:
        n = int(res["n_elements"])
        return {"mem_mb": 160 + 7.5e-4 * n * n, "seconds": 2.5 + 1.2e-4 * n * n}
    cells = int(res.get("n_rings", 1)) * int(res.get("n_sectors", 8))
    return {"mem_mb": 160 + 0.2 * cells, "seconds": 1.0 + 5e-3 * cells}
