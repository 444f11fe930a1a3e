"""Loop-closure equations (9), their Jacobian and exact dyads (mm, rad):

    b1 = l1 cos t1 - l3 cos t3 - l8 cos(t5 + alpha) - l6 cos t6 - l10 - l9
    b2 = l1 sin t1 - l3 sin t3 - l8 sin(t5 + alpha) - l6 sin t6 + l11
    b3 = l2 cos t2 - l4 cos t4 - l5 cos t5 - l6 cos t6 - l10
    b4 = l2 sin t2 - l4 sin t4 - l5 sin t5 - l6 sin t6 + l11

Each loop is a dyad with a closed-form solution (:func:`dyad`), the reference; the paper's
angle ranges and the design assembly branch."""
from __future__ import annotations

import math

import numpy as np

from mechrepro.errors import Refusal

from .geometry import Geometry


class NonAssembly(Refusal):
    """The linkage does not assemble at a cut point; the message names it and why."""

    def __init__(self, message: str, cut_point: int | None = None, x_k: float | None = None):
        super().__init__(message)
        self.cut_point = cut_point
        self.x_k = x_k


def pivots(g: Geometry) -> tuple[complex, complex]:
    """Fixed crank pivots A (lever AB) and G (lever GH), read off Eq. (9)."""
    return complex(-g.l10 - g.l9, g.l11), complex(-g.l10, g.l11)


def dyads(g: Geometry, theta5, theta6, levers=None) -> tuple:
    """Eq. (9)'s two dyads at poses theta5, theta6 (arrays broadcast), with lever lengths
    ``levers`` = (l1, l3, l5, l10) of their own if given (arrays): (crank pivot, carrier joint,
    crank, rod, elbow) of loop ABCD, then of GHID; points as complex x + iy (mm)."""
    l1, l3, l5, l10 = (g.l1, g.l3, g.l5, g.l10) if levers is None else levers
    t5 = np.asarray(theta5, float)
    D = g.l6 * np.exp(1j * np.asarray(theta6, float))
    C, I = D + g.l8 * np.exp(1j * (t5 + g.alpha)), D + l5 * np.exp(1j * t5)
    return ((-l10 - g.l9 + 1j * g.l11, C, l1, l3, g.elbow1),
            (-l10 + 1j * g.l11, I, g.l2, g.l4, g.elbow2))


def columns(th) -> tuple:
    """The unknowns of one candidate (n,) as scalars, or of many (..., n) as arrays (scalar
    arithmetic is much cheaper for scipy's one-candidate calls; same bits)."""
    th = np.asarray(th, float)
    return tuple(th) if th.ndim == 1 else tuple(th[..., k] for k in range(th.shape[-1]))


def stacked(values):
    """The inverse of :func:`columns`: (n,) from scalars, (..., n) from arrays."""
    return np.stack(values, axis=-1) if np.ndim(values[0]) else np.array(values)


def residuals(g: Geometry, th, theta5, theta6):
    """Eq. (9) for one or many candidate vectors ``th`` (..., 4); returns (..., 4)
    (:func:`.closure.loop_residuals`)."""
    from .closure import python

    return stacked(python.loop_residuals(g, python.loop_knowns(g, theta5, theta6), *columns(th)))


def jacobian(g: Geometry, th) -> np.ndarray:
    """d b / d(theta1..theta4) of Eq. (9): block diagonal, the two loops'
    :func:`.closure.dyad_block` Jacobians."""
    from .closure import python

    t1, t2, t3, t4 = th
    J = np.zeros((4, 4))
    J[0, 0], J[0, 2], J[1, 0], J[1, 2] = python.dyad_block(g.l1, g.l3, 0.0, 0.0, t1, t3)[2:]
    J[2, 1], J[2, 3], J[3, 1], J[3, 3] = python.dyad_block(g.l2, g.l4, 0.0, 0.0, t2, t4)[2:]
    return J


def dyad(P: complex, Q: complex, r_p: float, r_q: float, elbow: int):
    """Exact dyad: the joint X with |X - P| = r_p, |X - Q| = r_q on the ``elbow`` side (sign of
    (X - P) x (Q - X)).  Returns (angle of X - P, angle of X - Q, |Q - P|); raises
    :class:`NonAssembly` when the loop cannot close."""
    L = abs(Q - P)
    if not (abs(r_p - r_q) < L < r_p + r_q):
        raise NonAssembly(f"|PQ| = {L:.6g} mm outside ({abs(r_p - r_q):.6g}, {r_p + r_q:.6g}) mm")
    u = (Q - P) / L
    a = (r_p * r_p - r_q * r_q + L * L) / (2.0 * L)
    hgt = math.sqrt(max(r_p * r_p - a * a, 0.0))
    X = P + a * u - elbow * hgt * 1j * u  # cross((X-P),(Q-X)) = -sigma*hgt*L, sigma = -elbow
    return math.atan2((X - P).imag, (X - P).real), math.atan2((X - Q).imag, (X - Q).real), L


def elbow_signs(g: Geometry, th, theta5, theta6) -> tuple[int, int]:
    """Assembly mode of the two dyads of a solution (signs of the elbow cross products)."""
    t1, t2, t3, t4 = th
    u1, v1 = g.l1 * complex(math.cos(t1), math.sin(t1)), -g.l3 * complex(math.cos(t3), math.sin(t3))
    u2, v2 = g.l2 * complex(math.cos(t2), math.sin(t2)), -g.l4 * complex(math.cos(t4), math.sin(t4))
    c1 = u1.real * v1.imag - u1.imag * v1.real
    c2 = u2.real * v2.imag - u2.imag * v2.real
    return int(np.sign(c1)), int(np.sign(c2))


def exact_angles(g: Geometry, theta5: float, theta6: float) -> np.ndarray:
    """Closed-form theta1..theta4 on the design assembly mode (the trusted reference)."""
    A, G = pivots(g)
    D = g.l6 * complex(math.cos(theta6), math.sin(theta6))
    C = D + g.l8 * complex(math.cos(theta5 + g.alpha), math.sin(theta5 + g.alpha))
    I = D + g.l5 * complex(math.cos(theta5), math.sin(theta5))
    try:
        t1, t3p, _ = dyad(A, C, g.l1, g.l3, g.elbow1)
    except NonAssembly as exc:
        raise NonAssembly(f"loop ABCD (levers l1 = {g.l1:.6g}, l3 = {g.l3:.6g}): {exc}") from None
    try:
        t2, t4p, _ = dyad(G, I, g.l2, g.l4, g.elbow2)
    except NonAssembly as exc:
        raise NonAssembly(f"loop GHID (levers l2 = {g.l2:.6g}, l4 = {g.l4:.6g}): {exc}") from None
    # theta3, theta4 point from the carrier joint to the crank tip (Eq. 9: -l3 e^{i t3})
    return np.mod([t1, t2, t3p, t4p], 2.0 * math.pi)


def dyad_margins(g: Geometry, theta5, theta6) -> np.ndarray:
    """Distance (mm) of each dyad to its nearest toggle/fold for arrays of poses (negative: no
    assembly)."""
    m = [np.minimum(rp + rq - np.abs(Q - P), np.abs(Q - P) - abs(rp - rq))
         for P, Q, rp, rq, _ in dyads(g, theta5, theta6)]
    return np.stack(m, axis=-1)


TWO_PI = 2.0 * math.pi
#: the paper's ranges, order theta1..theta6 (lower, upper)
RANGES = ((math.pi, TWO_PI), (math.pi, TWO_PI), (0.0, math.pi), (0.0, math.pi),
          (0.0, math.pi), (math.pi, TWO_PI))


def wrap(theta):
    return np.mod(np.asarray(theta, float), TWO_PI)


def in_ranges(theta6, which=range(6)) -> bool:
    """theta (6,) (theta1..theta6) inside the paper's ranges, angles taken mod 2 pi."""
    t = wrap(theta6)
    return all(RANGES[i][0] <= t[i] <= RANGES[i][1] for i in which)


def on_design_branch(g: Geometry, theta6) -> bool:
    """The paper's ranges (Sec. 3.1) and the design assembly modes of the guide rod and both
    dyads: the ranges alone do not separate the guide rod's two modes nor the mirror modes of
    the dyad l1 = l3, and the machine cannot change mode without passing a toggle."""
    t = wrap(theta6)
    if not in_ranges(t):
        return False
    if g.guide_mode * math.cos(t[5]) <= 0:
        return False
    e1, e2 = elbow_signs(g, t[:4], t[4], t[5])
    return e1 == g.elbow1 and e2 == g.elbow2
