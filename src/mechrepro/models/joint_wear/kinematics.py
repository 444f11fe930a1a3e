"""Kinematics of the ideal four-bar (all joints ideal): position, velocity, acceleration.

The crank is driven, theta1 = omega t from the horizontal (Sec. 4.1).  Loop closure
B = D + l3 u(theta3) + l2 u(phi2) is solved in closed form on the assembly branch with C
above the ground line (assumed; Fig. 8 is lost).  Vectorised over time: every function takes and returns numpy arrays.
``phi2`` is the direction C -> B of the coupler (the bushing sits at B), ``theta3`` the
direction D -> C of the follower.
"""
from __future__ import annotations

import math

import numpy as np

from .geometry import FourBar


def positions(fb: FourBar, theta1):
    """theta3, phi2 for crank angle theta1 (loop closure, upper assembly branch)."""
    theta1 = np.asarray(theta1, float)
    return positions_from_point(fb, fb.l1 * np.cos(theta1), fb.l1 * np.sin(theta1))


def positions_from_point(fb: FourBar, bx, by):
    """theta3, phi2 that put the coupler's end B at (bx, by) (two-link closure from D)."""
    dx, dy = fb.l0 - bx, -by                       # B -> D
    d2 = dx * dx + dy * dy
    d = np.sqrt(d2)
    # C lies on the circles |C-B| = l2 and |C-D| = l3; a = distance from B along B->D
    a = (fb.l2 ** 2 - fb.l3 ** 2 + d2) / (2.0 * d)
    h = np.sqrt(np.maximum(fb.l2 ** 2 - a * a, 0.0))
    ux, uy = dx / d, dy / d
    # left normal of B->D (anticlockwise): the branch with C above the ground line
    cx = bx + a * ux - h * uy
    cy = by + a * uy + h * ux
    theta3 = np.arctan2(cy, cx - fb.l0)
    phi2 = np.arctan2(by - cy, bx - cx)
    return theta3, phi2


def velocities(fb: FourBar, theta1, theta3, phi2):
    """Angular velocities (d theta3/dt, d phi2/dt) from the velocity closure."""
    w1 = fb.omega
    # C = D + l3 u3 = B - l2 u2  ->  l3 w3 u3' + l2 w2 u2' = l1 w1 u1'
    # written as a 2x2 linear system per instant
    s13, s23 = np.sin(theta1 - phi2), np.sin(theta3 - phi2)
    w3 = fb.l1 * w1 * s13 / (fb.l3 * s23)
    w2 = fb.l1 * w1 * np.sin(theta3 - theta1) / (fb.l2 * s23)
    return w3, w2


def accelerations(fb: FourBar, theta1, theta3, phi2, w3, w2):
    """Angular accelerations (alpha3, alpha2), crank at constant speed."""
    w1 = fb.omega
    # differentiate l3 w3 u3' + l2 w2 u2' = l1 w1 u1':
    # l3 a3 u3' + l2 a2 u2' = -l1 w1^2 u1 + l3 w3^2 u3 + l2 w2^2 u2
    rx = -fb.l1 * w1 ** 2 * np.cos(theta1) + fb.l3 * w3 ** 2 * np.cos(theta3) + fb.l2 * w2 ** 2 * np.cos(phi2)
    ry = -fb.l1 * w1 ** 2 * np.sin(theta1) + fb.l3 * w3 ** 2 * np.sin(theta3) + fb.l2 * w2 ** 2 * np.sin(phi2)
    a11, a21 = -fb.l3 * np.sin(theta3), fb.l3 * np.cos(theta3)
    a12, a22 = -fb.l2 * np.sin(phi2), fb.l2 * np.cos(phi2)
    det = a11 * a22 - a12 * a21
    a3 = (rx * a22 - a12 * ry) / det
    a2 = (a11 * ry - a21 * rx) / det
    return a3, a2


def load_point_mid_stroke(fb: FourBar, n: int = 721):
    """E (the follower's centre, where P acts, Sec. 4.1) at the middle of the follower's
    stroke: the centre of the load points F the coefficient scan places around it [m]."""
    th3, _ = positions(fb, np.linspace(0.0, 2 * np.pi, n))
    th_mid = 0.5 * (th3.min() + th3.max())
    return (fb.l0 + 0.5 * fb.l3 * math.cos(th_mid), 0.5 * fb.l3 * math.sin(th_mid))
