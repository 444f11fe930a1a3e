"""Calibration of the guide-rod tilt theta6_mid - pi on the paper's 1.4341 (Sec. 4).

The blade slips by how far the line ED passes below the contact point, so H rises
monotonically with the tilt; a smaller tilt lets theta6 leave [pi, 2 pi] during the stroke."""
from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from mechrepro.errors import Refusal

from . import optimise
from .geometry import Geometry, cut_points, with_intent
from .design import Unreachable
from .loops import NonAssembly

#: tilts scanned for the bracket (rad): theta6_mid = pi + tilt
TILTS = np.round(np.arange(0.0, 0.8001, 0.02), 10)


class CalibrationError(Refusal):
    pass


def H_of_tilt(g: Geometry, tilt: float, n: int, tol: float) -> float:
    """H of the family member with this tilt; NaN where it does not assemble over the stroke."""
    try:
        gt = with_intent(g, theta6_mid=math.pi + tilt)
        return optimise.objective(gt, cut_points(gt, n)[1], tol)
    except (NonAssembly, Unreachable):
        return math.nan


def _scan(g: Geometry, target: float, n_scan: int, tol: float, whole: bool) -> np.ndarray:
    """H over ``TILTS`` at ``n_scan`` cut points; unless ``whole``, stopped at the first bracket of
    H - target between assembling tilts (the rest NaN)."""
    H = np.full(len(TILTS), np.nan)
    for j, t in enumerate(TILTS):
        H[j] = H_of_tilt(g, t, n_scan, tol)
        if (not whole and j > 0 and np.isfinite(H[j - 1]) and np.isfinite(H[j])
                and (H[j - 1] - target) * (H[j] - target) <= 0):
            break
    return H


def calibrate_tilt(g: Geometry, target: float, n: int, tol: float,
                   n_scan: int = 33, whole_scan: bool = True) -> tuple[Geometry, dict]:
    """The geometry whose tilt gives H = target (mm) at ``n`` cut points: the first bracket of the
    cheap scan, moved until it brackets the root at ``n`` points, refined by Brent; raises
    CalibrationError when no member reaches the target."""
    n_scan = min(n_scan, n)
    H = _scan(g, target, n_scan, tol, whole_scan)
    ok = np.isfinite(H)
    if not ok.any():
        # say why at the configured tilt (NonAssembly names the cut point and the loop)
        optimise.objective(g, cut_points(g, n)[1], tol)
        raise CalibrationError("no tilt in [0, 0.8] rad assembles over the whole stroke")
    f = H - target
    idx = [i for i in range(len(TILTS) - 1) if ok[i] and ok[i + 1] and f[i] * f[i + 1] <= 0]
    if not idx:
        raise CalibrationError(
            f"H = {target} mm is outside the family's reach: assembling tilts "
            f"{TILTS[ok].min():.2f}..{TILTS[ok].max():.2f} rad give H = "
            f"{np.nanmin(H):.4g}..{np.nanmax(H):.4g} mm (at {n_scan} cut points)")
    i = idx[0]

    # H at n points by tilt: brentq starts by evaluating the bracket the loop below has just
    # evaluated, and at n_scan = n the scan has evaluated that bracket already
    seen = {TILTS[i]: H[i], TILTS[i + 1]: H[i + 1]} if n_scan == n else {}

    def fn(t):
        if t not in seen:
            seen[t] = H_of_tilt(g, t, n, tol)
        return seen[t] - target

    lo, hi = TILTS[i], TILTS[i + 1]
    for _ in range(len(TILTS)):  # the root moves little between n_scan and n points
        flo, fhi = fn(lo), fn(hi)
        if not (math.isfinite(flo) and math.isfinite(fhi)):
            raise CalibrationError(f"bracket [{lo:.2f}, {hi:.2f}] rad leaves the family at {n} points")
        if flo * fhi <= 0:
            break
        step = hi - lo
        lo, hi = (lo - step, lo) if flo > 0 else (hi, hi + step)
    tilt = brentq(fn, lo, hi, xtol=1e-13, rtol=1e-13)
    gc = with_intent(g, theta6_mid=math.pi + tilt)
    return gc, {"tilt": tilt, "H": float(seen[tilt]), "H_scan": H, "n_scan": n_scan,
                "n_scanned": len(TILTS) if whole_scan else i + 2}
