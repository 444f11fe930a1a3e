"""Can the machine be built?  Constraints on a calibrated member of the family (issue 27).

The frame's origin E is the fixed pivot of the guide rod, at the height of the lower
blade's edge (the overlap line is y = -s, Eqs. 6-7); the plate (Table I: 6-50 mm thick)
lies on the lower blade over the rolled length x in [x_mid - width/2, x_mid + width/2].
A member whose equations close can still be a machine nobody can build:

1. **Nothing fixed or moving below the pass line inside the plate.**  The guide rod ED
   hangs below the horizontal through E (theta6 in [pi, 2 pi]), so E, D and the rod between
   them must lie beside the plate, ``clearance`` (bearings, housing, guards) clear of its
   edges, over the whole stroke; otherwise the rod sweeps through the plate or the lower
   blade.
2. **The carrier's rod joints pass over the plate.**  C and I ride on the blade holder:
   they must stay above the thickest plate (``plate_top`` = 50 mm) over the stroke.
3. **Transmission.**  Each dyad (crank AB - rod BC, crank GH - rod HI) keeps its angle
   between crank and rod inside [mu_min, 180 deg - mu_min] over the stroke: near 0 or 180 deg
   (the toggle) the cylinder's force has no lever arm on the carrier.
4. **Opening (Table I, 150 mm).**  The blade's far end over the plate rises
   width^2 / (2 R) above its lowest point; it must stay inside the open degree.

:func:`violations` returns what a member breaks (empty: buildable), with the margins.
"""
from __future__ import annotations

import math

import numpy as np

from .blade import carrier_points
from .geometry import Geometry
from .loops import pivots


def violations(g: Geometry, theta: np.ndarray, *, clearance: float, plate_top: float,
               mu_min: float, opening: float) -> list[str]:
    """Constraints 1-4 of the module docstring broken by machine ``g`` over its stroke
    ``theta`` (n x 6: theta1..theta6, rad); lengths in mm, ``mu_min`` in rad."""
    out = []
    t1, t2, t3, t4, t5, t6 = (theta[:, k] for k in range(6))
    P = carrier_points(g, t5, t6)
    lo, hi = g.x_mid - 0.5 * g.width, g.x_mid + 0.5 * g.width
    xs = np.concatenate([[0.0], P["D"].real])   # the rod ED: its ends bound it
    left, right = (lo - clearance) - xs.max(), xs.min() - (hi + clearance)
    if max(left, right) < 0.0:
        out.append(f"guide rod ED (x {xs.min():.0f}..{xs.max():.0f} mm, below the pass line) "
                   f"within {clearance:.0f} mm of the plate x in [{lo:.0f}, {hi:.0f}] mm")
    y_joint = min(P["C"].imag.min(), P["I"].imag.min())
    if y_joint < plate_top:
        out.append(f"rod joints C, I down to y = {y_joint:.0f} mm, below the top of the "
                   f"thickest plate ({plate_top:.0f} mm)")
    A, G = pivots(g)
    for name, piv, crank, tc, rod, joint in (("AB-BC", A, g.l1, t1, g.l3, P["C"]),
                                             ("GH-HI", G, g.l2, t2, g.l4, P["I"])):
        tip = piv + crank * np.exp(1j * tc)
        mu = np.abs(np.angle((piv - tip) / (joint - tip)))   # angle at the crank tip
        if mu.min() < mu_min or mu.max() > math.pi - mu_min:
            out.append(f"dyad {name}: crank-rod angle {math.degrees(mu.min()):.0f}.."
                       f"{math.degrees(mu.max()):.0f} deg outside [{math.degrees(mu_min):.0f}, "
                       f"{180 - math.degrees(mu_min):.0f}] deg")
    rise = g.width ** 2 / (2.0 * g.R)
    if rise > opening:
        out.append(f"blade end rises {rise:.0f} mm over the plate, more than the open degree "
                   f"{opening:.0f} mm")
    return out
