"""The invented geometry: every constant the paper omits, derived from stated design intents.

The paper gives l1, l3, l5, l6, l10 (and l7, read as l9) in Table II and the process data
of Table I; l2, l4, l8, l11, alpha, beta1, beta2, d, h, R, the rolled length and the
position of the cut are missing.  :func:`design` derives them from a handful of design
intents, each argued in docs/rolling_shear.md and marked ``assumed`` in the config; the
config holds the rounded outputs and a test checks that they match this derivation.
Nothing here looks at the paper's 1.4341 or -34.96 %.

Design intents, all at mid-cut (blade turned by beta = 0, lowest point at (x_mid, -s)):
1. the two drive sides are identical: l2 = l1, l4 = l3, and the rod joints C, I on the
   carrier are spaced by l9 at the same height y_joint, so A - C = G - I;
2. the guide rod l6 hangs at theta6_mid (slightly below the horizontal through E, so that
   theta6 stays in the paper's range [pi, 2 pi] over the whole stroke);
3. I lies on the carrier side of D towards the blade (left of D);
4. both dyads are bent at the elbow angle ``elbow_angle`` (far from toggle and fold);
5. the blade centre lies ``blade_offset`` to the side of I along the cut (negative: towards
   C; -l9/2 is midway between C and I).

The intents form the *admissible family* (docs/rolling_shear.md): every member satisfies
Table I, Table II and the paper's angle ranges over the whole stroke.  One intent, the
guide-rod tilt theta6_mid, is calibrated on the paper's 1.4341 (``calibrate.py``).
"""
from __future__ import annotations

import math

from mechrepro.errors import Refusal


class Unreachable(Refusal):
    """Design intents no linkage of these lever lengths can meet."""


INTENTS = ("l1", "l3", "l5", "l6", "l9", "l10", "s", "h", "R", "y_joint", "theta6_mid",
           "elbow_angle", "blade_offset")


def design(*, l1, l3, l5, l6, l9, l10, s, h, R, y_joint, theta6_mid, elbow_angle,
           blade_offset=None, elbow1=1, elbow2=1) -> dict:
    """Derived constants (mm, rad) from the design intents above."""
    l2, l4 = l1, l3
    D = l6 * complex(math.cos(theta6_mid), math.sin(theta6_mid))
    dy = y_joint - D.imag
    if abs(dy) >= l5:
        raise Unreachable(f"y_joint = {y_joint} unreachable from D with l5 = {l5}")
    I = complex(D.real - math.sqrt(l5 * l5 - dy * dy), y_joint)
    C = I - l9
    x_mid = I.real + (-0.5 * l9 if blade_offset is None else blade_offset)
    beta2 = math.atan2((I - D).imag, (I - D).real)
    l8 = abs(C - D)
    alpha = math.atan2((C - D).imag, (C - D).real) - beta2
    # dyad GH-HI bent at elbow_angle: |G - I| by the law of cosines
    L = math.sqrt(l2 * l2 + l4 * l4 - 2 * l2 * l4 * math.cos(elbow_angle))
    dx = -l10 - I.real
    if abs(dx) >= L:
        raise Unreachable("crank pivot G too far sideways for the chosen elbow angle")
    l11 = y_joint + math.sqrt(L * L - dx * dx)
    O = complex(x_mid, -s + h)
    d = abs(O - D)
    beta1 = math.atan2((O - D).imag, (O - D).real) - beta2
    return {"l2": l2, "l4": l4, "l8": l8, "l11": l11, "alpha": alpha, "beta1": beta1,
            "beta2": beta2, "d": d, "x_mid": x_mid, "elbow1": elbow1, "elbow2": elbow2}
