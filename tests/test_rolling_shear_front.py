"""Design under buildability (scene ``design``, front.py): the front's designs can be built
and no buildable design sampled independently dominates them."""
import math

import numpy as np
import pytest

from mechrepro.models.rolling_shear import front
from mechrepro.models.rolling_shear.constraints import margins, settings
from mechrepro.models.rolling_shear.run_context import Context
from mechrepro.models.rolling_shear.geometry import OPTIMISED_LEVERS, cut_points
from mechrepro.models.rolling_shear.stroke import exact_theta

from test_rolling_shear_helpers import run

#: a design sampled independently may beat a front design by this much and still not
#: dominate it: the front is the best of a finite seeded search (deg, relative H)
MU_TOL, H_RTOL = 0.5, 1e-9


@pytest.fixture(scope="module")
def searched():
    r = run("design", "ci")
    ctx = Context(r)
    cs = settings(ctx.p)
    cons = dict(clearance=cs["clearance"], plate_top=cs["plate_top"], mu_min=math.degrees(cs["mu_min"]),
                opening=cs["opening"], guide_rod_plane=cs["guide_rod_plane"])
    box = front.lever_box(ctx)
    res = front.search(ctx.g_original, ctx.n, ctx.tol_floor, box, cons, l6_points=9, samples=200,
                       rounds=4, rng=np.random.default_rng(3))
    return ctx, cons, box, res


def test_pareto_mask_of_a_known_set():
    H = np.array([1.0, 2.0, 1.5, 3.0, np.nan, 1.0])
    mu = np.array([50.0, 80.0, 40.0, 80.0, 90.0, 60.0])
    assert front.pareto_mask(H, mu).tolist() == [False, True, False, False, False, True]


def test_a_front_design_is_buildable_by_the_constraints_module(searched):
    """Re-judged by constraints.margins on the closed-form stroke, independent of the
    vectorised dyads of front.py."""
    ctx, cons, _, res = searched
    on = np.flatnonzero(front.pareto_mask(res["H"], res["mu_worst"]))
    assert on.size
    for i in on:
        g = ctx.g_original.with_levers(**dict(zip(OPTIMISED_LEVERS, res["levers"][i])))
        m = margins(g, exact_theta(g, cut_points(g, ctx.n)[1]), opening=cons["opening"])
        assert m["rod_gap"] >= cons["clearance"]
        assert m["joint_height"] >= cons["plate_top"]
        worst = min(min(a, 180 - b) for a, b in m["mu"].values())
        assert worst >= cons["mu_min"] and m["open_mu"] >= cons["mu_min"]
        assert worst == pytest.approx(res["mu_worst"][i], abs=1e-9)


def test_no_independently_sampled_buildable_design_dominates_the_front(searched):
    ctx, cons, box, res = searched
    on = np.flatnonzero(front.pareto_mask(res["H"], res["mu_worst"]))
    rng = np.random.default_rng(12345)
    jo = [OPTIMISED_LEVERS.index(k) for k in front.OTHERS]
    rise = ctx.g_original.width ** 2 / (2 * ctx.g_original.R)
    l6s = rng.uniform(*box[OPTIMISED_LEVERS.index("l6")], 12)
    seen = 0
    for l6 in l6s:
        g6 = ctx.g_original.with_levers(l6=float(l6))
        s = front.stroke_of(g6, ctx.n, ctx.tol_floor, cons["opening"])
        if s is None:
            continue
        poses, H, gap, q_open = s
        X = box[jo, 0] + (box[jo, 1] - box[jo, 0]) * rng.random((3000, 4))
        m = front.dyad_metrics(g6, poses, X, q_open)
        ok = front.buildable(m, gap, rise=rise, **cons)
        seen += int(ok.sum())
        mu = m["mu_worst"][ok]
        for i in on:
            dominates = (H <= res["H"][i] * (1 + H_RTOL)) & (mu > res["mu_worst"][i] + MU_TOL)
            assert not dominates.any(), (l6, res["levers"][i])
    assert seen > 100   # the check saw buildable designs


def test_the_guide_rod_bounds_l6_not_the_box(searched):
    """Below, the guide rod leaves its design branch; above, the rod comes within the
    clearance of the plate: the buildable l6 stop inside the box at both ends."""
    _, cons, box, res = searched
    l6 = res["levers"][:, OPTIMISED_LEVERS.index("l6")]
    built = np.isfinite(res["mu_worst"])
    assert box[3, 0] < l6[built].min() and l6[built].max() < box[3, 1]
    assert (res["rod_gap"][~built & (l6 > l6[built].max())] < cons["clearance"]).all()


def test_the_dyad_metrics_match_the_closed_form_stroke():
    r = run("design", "ci")
    ctx = Context(r)
    g = ctx.g_original
    x_k = cut_points(g, ctx.n)[1]
    th = exact_theta(g, x_k)
    m = front.dyad_metrics(g, th[:, 4:], np.array([[g.l1, g.l3, g.l5, g.l10]]))
    ref = margins(g, th)
    assert m["assembles"][0]
    assert m["mu_min"][0] == pytest.approx(min(a for a, _ in ref["mu"].values()), abs=1e-9)
    assert m["mu_max"][0] == pytest.approx(max(b for _, b in ref["mu"].values()), abs=1e-9)
    assert m["joint_height"][0] == pytest.approx(ref["joint_height"], abs=1e-9)
