"""Can the machine be built?  Constraints on a calibrated member of the family.

1. Under the ``planar`` reading of ``guide_rod_plane``, the guide rod ED (pivot E, joint D
   and the rod between) hangs below the pass line and must stay ``clearance`` beside the
   plate over the stroke; ``out_of_plane`` (the rod beside the plane of the cut) drops it.
2. The carrier's rod joints C, I pass over the thickest plate (``plate_top``).
3. Each dyad keeps its crank-rod angle in [mu_min, 180 deg - mu_min]: near a toggle the
   cylinder's force has no lever arm.
4. The machine opens (Table I, 150 mm): at the open position (Eq. 7 with y_k = +opening at
   x_mid) both dyads close with the floor of 3, and the blade end's rise width^2 / (2 R)
   stays inside the open degree.

:func:`margins` measures how far a member is from each, :func:`violations` what it breaks."""
from __future__ import annotations

import math

import numpy as np

from dataclasses import replace

from scipy.optimize import root

from .blade import carrier_points, exact_pose, pose_residuals
from .geometry import Geometry
from .loops import dyads, pivots

#: the readings of constraint 1 (config ``guide_rod_plane``)
PLANES = ("planar", "out_of_plane")


#: lift steps of the continuation from the mid-cut pose to the open position
OPEN_STEPS = 4


def open_pose(g: Geometry, opening: float) -> np.ndarray | None:
    """(theta5, theta6) of the open position (constraint 4), followed from the mid-cut pose in
    :data:`OPEN_STEPS` lifts by scipy's hybrid Powell method; None where a lift fails."""
    try:
        q = exact_pose(g, float(g.x_mid))
    except Exception:   # noqa: BLE001 -- no mid-cut pose: no open position either
        return None
    for y in np.linspace(-g.s, opening, OPEN_STEPS + 1)[1:]:
        gy = replace(g, s=-float(y))
        sol = root(lambda t: pose_residuals(gy, t, float(g.x_mid)), q, method="hybr",
                   options={"xtol": 1e-13})
        if not sol.success or np.abs(pose_residuals(gy, sol.x, float(g.x_mid))).max() > 1e-6:
            return None
        q = sol.x
    return q


def dyad_transmission(g: Geometry, theta5, theta6, levers=None) -> np.ndarray:
    """Worst min(mu, 180 - mu) (deg) of both dyads of Eq. (9), mu the crank-rod angle at the
    crank tip, at each pose, or at one pose for each lever set ``levers`` (m, 4: l1, l3, l5,
    l10); NaN where a dyad does not close."""
    from .closure import python

    worst = np.inf
    for piv, joint, rp, rq, e in dyads(g, np.atleast_1d(theta5), np.atleast_1d(theta6),
                                       None if levers is None else levers.T):
        with np.errstate(invalid="ignore"):
            x, y, _ = python.dyad_joint(piv.real, piv.imag, joint.real, joint.imag, rp, rq, e)
            tip = x + 1j * y
            mu = np.degrees(np.abs(np.angle((piv - tip) / (joint - tip))))
            worst = np.fmin(worst, np.minimum(mu, 180.0 - mu))
        worst[~np.isfinite(x)] = np.nan
    return worst


def margins(g: Geometry, theta: np.ndarray, opening: float | None = None) -> dict:
    """What constraints 1-4 measure on machine ``g`` over its stroke ``theta`` (n x 6, rad), mm and
    deg: ``rod_gap`` (negative: the rod reaches over the plate), ``rod_x``, ``joint_height``,
    ``mu`` {dyad: (min, max)}, ``rise`` and, with ``opening``, ``open_mu`` (NaN: not reached)."""
    t1, t2 = theta[:, 0], theta[:, 1]
    t5, t6 = theta[:, 4], theta[:, 5]
    P = carrier_points(g, t5, t6)
    lo, hi = g.x_mid - 0.5 * g.width, g.x_mid + 0.5 * g.width
    xs = np.concatenate([[0.0], P["D"].real])   # the rod ED: E at the origin, D over the stroke
    A, G = pivots(g)
    mu = {}
    for name, piv, crank, tc, joint in (("AB-BC", A, g.l1, t1, P["C"]),
                                        ("GH-HI", G, g.l2, t2, P["I"])):
        tip = piv + crank * np.exp(1j * tc)
        m = np.degrees(np.abs(np.angle((piv - tip) / (joint - tip))))   # angle at the crank tip
        mu[name] = (float(m.min()), float(m.max()))
    out = {"rod_gap": float(max(lo - xs.max(), xs.min() - hi)),
           "rod_x": (float(xs.min()), float(xs.max())), "plate_x": (float(lo), float(hi)),
           "joint_height": float(min(P["C"].imag.min(), P["I"].imag.min())),
           "mu": mu, "rise": float(g.width ** 2 / (2.0 * g.R))}
    if opening is not None:
        q = open_pose(g, opening)
        out["open_mu"] = math.nan if q is None else float(dyad_transmission(g, q[0], q[1])[0])
        out["opening"] = float(opening)
    return out


def broken(m: dict, *, clearance: float, plate_top: float, mu_min: float, opening: float,
           guide_rod_plane: str = "planar") -> list[str]:
    """The constraints margins ``m`` break at these settings (mm; ``mu_min`` in deg)."""
    if guide_rod_plane not in PLANES:
        raise ValueError(f"guide_rod_plane = {guide_rod_plane!r}: one of {PLANES}")
    out = []
    if guide_rod_plane == "planar" and m["rod_gap"] < clearance:
        (a, b), (lo, hi) = m["rod_x"], m["plate_x"]
        out.append(f"guide rod ED (x {a:.0f}..{b:.0f} mm, below the pass line) "
                   f"within {clearance:.0f} mm of the plate x in [{lo:.0f}, {hi:.0f}] mm "
                   f"({m['rod_gap']:.0f} mm beside it)")
    if m["joint_height"] < plate_top:
        out.append(f"rod joints C, I down to y = {m['joint_height']:.0f} mm, below the top of "
                   f"the thickest plate ({plate_top:.0f} mm)")
    for name, (a, b) in m["mu"].items():
        if a < mu_min or b > 180.0 - mu_min:
            out.append(f"dyad {name}: crank-rod angle {a:.0f}..{b:.0f} deg outside "
                       f"[{mu_min:.0f}, {180 - mu_min:.0f}] deg")
    if m["rise"] > opening:
        out.append(f"blade end rises {m['rise']:.0f} mm over the plate, more than the open "
                   f"degree {opening:.0f} mm")
    if "open_mu" in m and not m["open_mu"] >= mu_min:   # NaN: the open position is not reached
        out.append(f"open degree {m['opening']:.0f} mm not reached: " + (
            "no pose of the guide rod lifts the blade that high, or a dyad cannot close there"
            if not math.isfinite(m["open_mu"]) else
            f"a dyad's crank-rod angle comes within {m['open_mu']:.0f} deg of its toggle there "
            f"(floor {mu_min:.0f} deg)"))
    return out


def violations(g: Geometry, theta: np.ndarray, *, clearance: float, plate_top: float,
               mu_min: float, opening: float, guide_rod_plane: str = "planar") -> list[str]:
    """Constraints 1-4 broken by machine ``g`` over its stroke ``theta``; ``mu_min`` in rad."""
    return broken(margins(g, theta, opening=opening), clearance=clearance, plate_top=plate_top,
                  mu_min=math.degrees(mu_min), opening=opening, guide_rod_plane=guide_rod_plane)


def settings(p: dict) -> dict:
    """The constraint settings of a run's SI parameters, as :func:`violations` takes them."""
    return dict(clearance=float(p["clearance"]) * 1e3, plate_top=float(p["plate_thickness_max"]) * 1e3,
                mu_min=float(p["transmission_min"]), opening=float(p["opening"]) * 1e3,
                guide_rod_plane=str(p.get("guide_rod_plane", "planar")))
