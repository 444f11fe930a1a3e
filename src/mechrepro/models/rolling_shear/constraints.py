"""Can the machine be built?  Constraints on a calibrated member of the family (issue 27).

The frame's origin E is the fixed pivot of the guide rod, at the height of the lower
blade's edge (the overlap line is y = -s, Eqs. 6-7); the plate (Table I: 6-50 mm thick)
lies on the lower blade over the rolled length x in [x_mid - width/2, x_mid + width/2].
A member whose equations close can still be a machine nobody can build:

1. **Nothing fixed or moving below the pass line inside the plate** (``guide_rod_plane``
   ``planar``, the reading of the paper's planar kinematic diagrams).  The guide rod ED
   hangs below the horizontal through E (theta6 in [pi, 2 pi]), so both of its ends -- the
   fixed pivot E *and the moving joint D* -- and the rod between them must lie beside the
   plate, ``clearance`` (bearings, housing, guards) clear of its edges, over the whole
   stroke; otherwise the rod sweeps through the plate or the lower blade.  The other
   reading, ``out_of_plane`` (the rod and its pivot beside the plane of the cut, along the
   rolling direction), drops this constraint: the paper's figures are lost and its text
   does not say (config ``guide_rod_plane``, an assumed choice with both readings).
2. **The carrier's rod joints pass over the plate.**  C and I ride on the blade holder:
   they must stay above the thickest plate (``plate_top`` = 50 mm) over the stroke.
3. **Transmission.**  Each dyad (crank AB - rod BC, crank GH - rod HI) keeps its angle
   between crank and rod inside [mu_min, 180 deg - mu_min] over the stroke: near 0 or 180 deg
   (the toggle) the cylinder's force has no lever arm on the carrier.
4. **Opening (Table I, open degree 150 mm).**  The machine must open: at the open position
   -- the blade lifted straight up at mid-cut until its lowest point is the open degree
   above the lower blade's edge (Eq. 7 with y_k = +opening at x_k = x_mid, reached from
   the mid-cut pose by continuation; the guide rod may turn above E there, the open
   position is not part of the cut and the paper's ranges are the cut's) -- both dyads of
   Eq. (9) must close on their assembly modes with the transmission floor of constraint 3:
   ``open_mu``, which binds for dyads that the lift takes towards a toggle.  And the
   blade's far end over the plate rises width^2 / (2 R) above its lowest point, which must
   stay inside the open degree (R's lower end, 35 m, is where the widest plate rises
   146 mm: R's range is this part).

:func:`margins` measures how far a member is from each constraint (what the family scan
stores, so that a verdict can ask for buildability at any clearance or transmission floor
of their ranges and under either reading), :func:`violations` what it breaks at the given
settings (empty: buildable), with the margins.
"""
from __future__ import annotations

import math

import numpy as np

from dataclasses import replace

from scipy.optimize import root

from .blade import carrier_points
from .geometry import Geometry
from .loops import pivots

#: the readings of constraint 1 (config ``guide_rod_plane``)
PLANES = ("planar", "out_of_plane")


#: lift steps of the continuation from the mid-cut pose to the open position
OPEN_STEPS = 4


def open_pose(g: Geometry, opening: float) -> np.ndarray | None:
    """(theta5, theta6) of the open position (constraint 4): Eq. (7) with the lowest point
    at (x_mid, +opening), followed from the mid-cut pose in :data:`OPEN_STEPS` lifts by
    scipy's hybrid Powell method; None where a lift does not converge (the guide rod cannot
    carry the blade that high)."""
    from . import pose

    try:
        q = pose.exact_pose(g, float(g.x_mid))
    except Exception:   # noqa: BLE001 -- no mid-cut pose: no open position either
        return None
    for y in np.linspace(-g.s, opening, OPEN_STEPS + 1)[1:]:
        gy = replace(g, s=-float(y))
        sol = root(lambda t: pose.residuals(gy, t, float(g.x_mid)), q, method="hybr",
                   options={"xtol": 1e-13})
        if not sol.success or np.abs(pose.residuals(gy, sol.x, float(g.x_mid))).max() > 1e-6:
            return None
        q = sol.x
    return q


def dyad_transmission(g: Geometry, theta5, theta6) -> np.ndarray:
    """Worst min(mu, 180 - mu) (deg) of both dyads of Eq. (9) at each pose, mu the angle
    between crank and rod at the crank tip; NaN where a dyad does not close."""
    from .closure import python

    A, G = pivots(g)
    P = carrier_points(g, np.atleast_1d(theta5), np.atleast_1d(theta6))
    worst = np.full(np.shape(P["D"]), np.inf)
    for piv, joint, rp, rq, e in ((A, P["C"], g.l1, g.l3, g.elbow1), (G, P["I"], g.l2, g.l4, g.elbow2)):
        with np.errstate(invalid="ignore"):
            x, y, _ = python.dyad_joint(piv.real, piv.imag, joint.real, joint.imag, rp, rq, e)
            tip = x + 1j * y
            mu = np.degrees(np.abs(np.angle((piv - tip) / (joint - tip))))
            worst = np.fmin(worst, np.minimum(mu, 180.0 - mu))
        worst[~np.isfinite(x)] = np.nan
    return worst


def margins(g: Geometry, theta: np.ndarray, opening: float | None = None) -> dict:
    """What constraints 1-4 measure on machine ``g`` over its stroke ``theta`` (n x 6:
    theta1..theta6, rad), mm and deg (``open_mu`` only with ``opening``, mm):

    ``rod_gap``: how far the guide rod ED (its pivot E, its joint D at every cut point and
    the rod between them) stays beside the plate, to the nearer edge (negative: the rod
    reaches over the plate's span); ``rod_x``: the x-interval the rod sweeps;
    ``joint_height``: the lowest y of the rod joints C, I; ``mu``: {dyad: (smallest,
    largest) crank-rod angle}; ``rise``: the blade end's rise over the plate; ``open_mu``:
    the worst transmission angle at the open position (NaN: no open position, or a dyad
    does not close there)."""
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
    """The constraints of the module docstring that margins ``m`` (:func:`margins`) break
    at these settings (mm; ``mu_min`` in deg)."""
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
    """Constraints 1-4 of the module docstring broken by machine ``g`` over its stroke
    ``theta`` (n x 6: theta1..theta6, rad); lengths in mm, ``mu_min`` in rad."""
    return broken(margins(g, theta, opening=opening), clearance=clearance, plate_top=plate_top,
                  mu_min=math.degrees(mu_min), opening=opening, guide_rod_plane=guide_rod_plane)


def settings(p: dict) -> dict:
    """The constraint settings of a run's SI parameters, as :func:`violations` takes them."""
    return dict(clearance=float(p["clearance"]) * 1e3, plate_top=float(p["plate_thickness_max"]) * 1e3,
                mu_min=float(p["transmission_min"]), opening=float(p["opening"]) * 1e3,
                guide_rod_plane=str(p.get("guide_rod_plane", "planar")))
