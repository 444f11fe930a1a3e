"""Buildability (issue 62): the guide rod's moving joint D counts, not only its pivot E; the
machine with Table II's levers is judged too; the guide rod's other assembly mode is
refused by name; the open degree of Table I can bind."""
import math

import numpy as np
import pytest

from mechrepro.models.rolling_shear import front, stroke
from mechrepro.models.rolling_shear.constraints import broken, margins, open_pose
from mechrepro.models.rolling_shear.run_context import Context
from mechrepro.models.rolling_shear.geometry import cut_points
from mechrepro.models.rolling_shear.loops import NonAssembly

from test_rolling_shear_helpers import run

TABLE2 = {"l1": 926.7, "l3": 689.3, "l5": 984.6, "l6": 809.3, "l10": 1704.3}


@pytest.fixture(scope="module")
def ctx():
    return Context(run("original", "ci"))


def _limits(c):
    p = c.p
    return dict(clearance=p["clearance"] * 1e3, plate_top=p["plate_thickness_max"] * 1e3,
                mu_min=p["transmission_min"], opening=p["opening"] * 1e3)


def _stroke(g, n=33):
    return stroke.exact_theta(g, cut_points(g, n)[1])


def test_the_rod_gap_is_the_joint_d_not_the_pivot_e(ctx):
    """E sits ~1.2 m beside the plate, D ~245 mm: the gap is D's, and a clearance between
    the two breaks the machine (a check of E alone passes it)."""
    g = ctx.g_original
    theta = _stroke(g)
    m = margins(g, theta)
    lo, hi = m["plate_x"]
    D = g.l6 * np.cos(theta[:, 5])
    assert m["rod_gap"] == pytest.approx(max(lo - D.max(), D.min() - hi), abs=1e-9)
    e_gap = max(lo, -hi)
    assert e_gap > m["rod_gap"] + 500.0
    clearance = 0.5 * (m["rod_gap"] + e_gap)
    assert any("guide rod ED" in v for v in broken(m, **dict(_limits(ctx), clearance=clearance)))


def test_a_longer_guide_rod_brings_d_to_the_plate(ctx):
    """In the design front, l6 is bounded above by D's gap: the rod gap falls with l6."""
    gaps = [front.stroke_of(ctx.g_original.with_levers(l6=l6), 17, ctx.tol_floor, 150.0)[2]
            for l6 in (900.0, 1000.0, 1100.0)]
    assert gaps[0] > gaps[1] > gaps[2]
    assert gaps[0] - gaps[2] == pytest.approx(200.0, rel=0.1)


def test_the_table2_machine_is_judged_by_the_same_constraints(ctx):
    g = ctx.g_original.with_levers(**TABLE2)
    m = margins(g, _stroke(g), opening=_limits(ctx)["opening"])
    assert broken(m, **_limits(ctx)) == []
    assert np.isfinite(m["open_mu"])
    # the front's vectorised verdict on the same machine agrees
    got = front.evaluate(ctx.g_original, TABLE2, 33, ctx.tol_floor,
                         dict(_limits(ctx), guide_rod_plane="planar"))
    assert got["buildable"]


def test_the_other_assembly_mode_of_the_guide_rod_is_refused_by_name():
    """guide_mode = +1 (D right of E) contradicts the design pose (theta6_mid = pi + tilt, D
    left of E): the calibration's stroke leaves the guide rod's design branch and says so;
    never a NaN or a silent stroke on the other mode."""
    r = run("original", "ci")
    r["parameters"]["guide_mode"] = 1
    with pytest.raises(NonAssembly, match="design branch"):
        Context(r)


def test_the_open_pose_lifts_the_lowest_point_to_the_open_degree(ctx):
    g = ctx.g_original
    from mechrepro.models.rolling_shear.blade import lowest_point

    q = open_pose(g, 150.0)
    x, y = lowest_point(g, q[0], q[1])
    assert float(x) == pytest.approx(g.x_mid, abs=1e-6)
    assert float(y) == pytest.approx(150.0, abs=1e-6)
    # the carrier is lifted by turning the guide rod up (theta6 falls towards pi and below)
    assert q[1] < _stroke(g)[len(_stroke(g)) // 2, 5]


def test_the_open_degree_can_bind(ctx):
    """With the transmission floor it holds at 150 mm, and a larger opening takes the
    dyads towards their toggles until it breaks: the constraint has teeth inside its own
    terms (it is no longer a rise that never reaches the opening)."""
    g = ctx.g_original
    theta = _stroke(g)
    lim = _limits(ctx)
    m150 = margins(g, theta, opening=150.0)
    assert not [v for v in broken(m150, **lim) if "open degree" in v]
    m600 = margins(g, theta, opening=600.0)
    assert m600["open_mu"] < m150["open_mu"]
    tight = dict(lim, mu_min=0.5 * (m150["open_mu"] + m600["open_mu"]))
    worst_cut = min(min(a, 180 - b) for a, b in m600["mu"].values())
    assert tight["mu_min"] < worst_cut   # the stroke itself meets that floor
    assert any("open degree" in v for v in broken(m600, **dict(tight, opening=600.0)))
