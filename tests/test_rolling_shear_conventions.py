"""rolling_shear: the conventions chosen where the printed equations contradict each other."""
import math
from dataclasses import replace

import numpy as np
import pytest

from mechrepro.models.rolling_shear import blade, loops
from mechrepro.models.rolling_shear.motion_laws import (horizontal_displacement, trajectory1,
                                                       trajectory1_for)

from test_rolling_shear_helpers import geometry, stroke_exact


def M12(g) -> np.ndarray:
    """Eq. (4): frame x1Oy1 (blade) -> x2Dy2 (carrier), as printed (rotation -beta2)."""
    c, s = np.cos(g.beta2), np.sin(g.beta2)
    return np.array([[c, s, g.d * np.cos(g.beta1)],
                     [-s, c, g.d * np.sin(g.beta1)],
                     [0.0, 0.0, 1.0]])


def M20(g, theta5: float, theta6: float) -> np.ndarray:
    """Eq. (4): frame x2Dy2 -> xEy, rotation **+theta5** (the corrected sign, see blade.py)."""
    c, s = np.cos(theta5), np.sin(theta5)
    return np.array([[c, -s, g.l6 * np.cos(theta6)],
                     [s, c, g.l6 * np.sin(theta6)],
                     [0.0, 0.0, 1.0]])


def M20_printed(g, theta5, theta6):
    """Eq. (4) exactly as printed (rotation -theta5), against which the convention is tested."""
    c, s = np.cos(theta5), np.sin(theta5)
    return np.array([[c, s, g.l6 * np.cos(theta6)],
                     [-s, c, g.l6 * np.sin(theta6)],
                     [0.0, 0.0, 1.0]])


@pytest.fixture(scope="module")
def g():
    return geometry()


POSES = [(2.60, 3.35), (2.6438, 3.29), (2.69, 3.17), (2.2, 4.0)]


@pytest.mark.parametrize("t5,t6", POSES)
def test_transform_chain_matches_written_out_form(g, t5, t6):
    for p1 in [(0.0, -g.h), (123.0, 45.0), (-700.0, 10.0)]:
        x, y, _ = M20(g, t5, t6) @ M12(g) @ np.array([*p1, 1.0])
        xw, yw = blade.to_fixed(g, t5, t6, *p1)
        assert abs(x - xw) < 1e-9 and abs(y - yw) < 1e-9


@pytest.mark.parametrize("t5,t6", POSES)
def test_M20_rotation_sense_agrees_with_loop_equations(g, t5, t6):
    # frame x2Dy2 has x2 along DI: the point (l5, 0) of frame 2 must be I = D + l5 e^{i t5}
    D = g.l6 * np.exp(1j * t6)
    I = D + g.l5 * np.exp(1j * t5)
    x, y, _ = M20(g, t5, t6) @ np.array([g.l5, 0.0, 1.0])
    assert abs(complex(x, y) - I) < 1e-9
    xp, yp, _ = M20_printed(g, t5, t6) @ np.array([g.l5, 0.0, 1.0])
    assert abs(complex(xp, yp) - I) > 1.0  # the printed sign contradicts Eq. (9)


@pytest.mark.parametrize("t5,t6", POSES)
def test_blade_turns_by_theta5_minus_beta2(g, t5, t6):
    M = M20(g, t5, t6) @ M12(g)
    assert math.isclose(math.atan2(M[1, 0], M[0, 0]), math.remainder(t5 - g.beta2, 2 * math.pi),
                        abs_tol=1e-12)
    Mp = M20_printed(g, t5, t6) @ M12(g)
    assert not math.isclose(math.atan2(Mp[1, 0], Mp[0, 0]),
                            math.remainder(t5 - g.beta2, 2 * math.pi), abs_tol=1e-3)


@pytest.mark.parametrize("t5,t6", POSES[:3])
def test_lowest_point_is_the_lowest_point_of_the_arc(g, t5, t6):
    xa, ya = blade.arc_points(g, t5, t6, half_angle=0.2, n=400001)
    xk, yk = blade.lowest_point(g, t5, t6)
    i = int(np.argmin(ya))
    assert abs(ya[i] - yk) < 1e-6
    assert abs(xa[i] - xk) < g.R * 0.4 / 400000 + 1e-9   # one grid step of the arc
    # the printed sign of Eq. (6) lies 2 R (1 - cos beta) above the true lowest point
    xh, yh = blade.midpoint(g, t5, t6)
    b = t5 - g.beta2
    if abs(b) > 0.01:
        assert (yh + g.R * (1 - math.cos(b))) - ya.min() > 1.0


def test_pure_rolling_keeps_lowest_point_on_the_line_and_follows_trajectory1(g):
    # pose the blade by pure rolling (ignoring the guide rod): contact x = x0 - R beta
    beta = np.linspace(-0.05, 0.05, 41)
    x0 = -2000.0
    xh = x0 - g.R * beta + g.R * np.sin(beta)
    yh = -g.s + g.R * (1 - np.cos(beta))
    xk = xh - g.R * np.sin(beta)
    yk = yh - g.R * (1 - np.cos(beta))            # corrected Eq. (6)
    assert np.max(np.abs(yk + g.s)) < 1e-9
    yk_printed = yh + g.R * (1 - np.cos(beta))
    assert np.max(np.abs(yk_printed + g.s)) > 50.0
    xt, yt = trajectory1(g.R * beta, g.R, x0, -g.s)
    assert np.max(np.abs(xt - xh)) < 1e-8 and np.max(np.abs(yt - yh)) < 1e-8
    for reading in ("rotation", "literal"):        # no slip under either reading of Eq. (8)
        gr = replace(g, eq8=reading)
        assert np.max(np.abs(horizontal_displacement(gr, beta, xk))) < 1e-8


@pytest.mark.parametrize("reading,anchor", [("rotation", 0), ("literal", 4)])
def test_trajectory1_anchored_where_the_reading_says(g, reading, anchor):
    gr = replace(g, eq8=reading)
    sol = stroke_exact(gr, 9)
    beta = sol.theta[:, 4] - gr.beta2
    xk, yk = blade.lowest_point(gr, sol.theta[:, 4], sol.theta[:, 5])
    xh, yh = blade.midpoint(gr, sol.theta[:, 4], sol.theta[:, 5])
    xt, yt = trajectory1_for(gr, beta, xk)
    assert abs(xt[anchor] - xh[anchor]) < 1e-8
    assert np.allclose(xh - xt, horizontal_displacement(gr, beta, xk), atol=1e-8)
    if reading == "rotation":                      # equal rotation: no vertical difference
        assert np.max(np.abs(yt - yh)) < 1e-8
    else:                                          # equal rolled length, Eq. (8) as printed
        th = beta[anchor] + (xk[anchor] - xk) / gr.R   # theta = huch / R from the anchor pose
        x0 = xh[anchor] + gr.R * th[anchor] - gr.R * np.sin(th[anchor])
        x8, y8 = trajectory1(gr.R * th, gr.R, x0, -gr.s)
        assert np.allclose(xt, x8, atol=1e-6) and np.allclose(yt, y8, atol=1e-6)


@pytest.mark.parametrize("t5,t6", POSES)
def test_pose_jacobian_matches_finite_differences(g, t5, t6):
    J = blade.lowest_point_jacobian(g, t5, t6)
    e = 1e-7
    for j, (d5, d6) in enumerate(((e, 0), (0, e))):
        fp = np.array(blade.lowest_point(g, t5 + d5, t6 + d6))
        fm = np.array(blade.lowest_point(g, t5 - d5, t6 - d6))
        assert np.allclose((fp - fm) / (2 * e), J[:, j], rtol=1e-6, atol=1e-4)


def test_loop_jacobian_matches_finite_differences(g):
    th = np.array([4.25, 4.3, 2.6, 2.5])
    J = loops.jacobian(g, th)
    for j in range(4):
        d = np.zeros(4)
        d[j] = 1e-7
        fd = (loops.residuals(g, th + d, 2.64, 3.29) - loops.residuals(g, th - d, 2.64, 3.29)) / 2e-7
        assert np.allclose(fd, J[:, j], atol=1e-4)


def test_exact_pose_satisfies_eq7(g):
    for xk in (g.x_mid + 0.5 * g.width, g.x_mid, g.x_mid - 0.5 * g.width):   # the cut's ends
        t = blade.exact_pose(g, xk)
        assert np.abs(blade.pose_residuals(g, t, xk)).sum() < 1e-9
