"""The invented geometry: the constants the paper omits (l2, l4, l8, l11, alpha, beta1, beta2,
d, x_mid), derived from design intents argued in docs/rolling_shear.md; nothing here looks
at the paper's 1.4341 or -34.96 %.

Intents at mid-cut (beta = 0, lowest point at (x_mid, -s)): identical drive sides (l2 = l1,
l4 = l3, C and I l9 apart at height y_joint); the guide rod at theta6_mid (calibrated on
1.4341, calibrate.py); I left of D; both dyads bent at ``elbow_angle``; the blade centre
``blade_offset`` from I along the cut."""
from __future__ import annotations

import math

from mechrepro.errors import Refusal


class Unreachable(Refusal):
    """Design intents no linkage of these lever lengths can meet."""


INTENTS = ("l1", "l3", "l5", "l6", "l9", "l10", "s", "h", "R", "y_joint", "theta6_mid",
           "elbow_angle", "blade_offset")


def design(*, l1, l3, l5, l6, l9, l10, s, h, R, y_joint, theta6_mid, elbow_angle,
           blade_offset=None) -> dict:
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
            "beta2": beta2, "d": d, "x_mid": x_mid}
