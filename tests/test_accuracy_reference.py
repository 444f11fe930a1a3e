"""Cost of accuracy: a curve's reference must be shown more accurate than every point on it.

A reference is proven only when the levels approach it monotonically with shrinking
differences between successive levels (an observed order gives its error), or reach a noise
floor measured at the finest levels and stay there; the finest levels inside that floor's
band are drawn, not compared."""
import math

import numpy as np
import pytest

from mechrepro import accuracy
from mechrepro.accuracy import assess, noise_floor


class DS(dict):
    @property
    def variables(self):
        return self


class Var:
    def __init__(self, v):
        self.values = np.asarray(v)


def table(q, knob, reference="finest", method=None, exact=0.0, error="absolute"):
    ds = DS(n=Var(knob), wall_time=Var(np.asarray(knob, float)), q=Var(q))
    if method is not None:
        ds["method"] = Var(method)
    Q = accuracy.AccuracyQuantities("toy")

    @Q.register("q")
    def _(d, entry):
        if reference == "exact":
            return np.abs(np.asarray(d["q"].values) - exact)
        return accuracy.against_finest(d["q"].values, d["n"].values, "larger", error)

    entry = {"name": "toy", "study": "s", "knob": "n", "finer": "larger", "reference": reference,
             "quantities": {"q": {"error": error}}}
    return accuracy.rows([entry], lambda name: ds, Q)


def finest(q, n):
    """(h, errors against the finest level, h of the finest level) of values q at knob n."""
    q, h = np.asarray(q, float), 1.0 / np.asarray(n, float)
    return h[:-1], np.abs(q[:-1] - q[-1]), h[-1]


def test_finest_reference_of_a_second_order_curve_is_proven():
    n = np.array([4, 8, 16, 32, 64])
    rows = table(1.0 + 1.0 / n ** 2, n)
    assert all(r["reference_proven"] for r in rows)
    # errors measured from the finest run bias the slope up a little (2.13 here)
    assert abs(rows[0]["observed_order"] - 2) < 0.15
    # its estimate is the finest point's true error (1/64^2) within 10 %
    assert abs(rows[0]["reference_error"] * 64 ** 2 - 1) < 0.1
    assert "Richardson at observed order 2" in rows[0]["reference_why"]


def test_finest_reference_in_the_round_off_floor_is_flagged_not_silent():
    n = np.array([4, 8, 16, 32, 64])
    floor = np.array([0, 0, 0, 3e-3, -3e-3])       # the last two runs are noise, not refinement
    rows = table(1.0 + 1.0 / n ** 2 + floor, n)
    assert not any(r["reference_proven"] for r in rows)
    assert rows[0]["reference_why"].startswith("NOT CONVERGED")


def test_exact_reference_is_proven_and_methods_are_separate_labelled_lines():
    n = np.array([4, 8, 16, 4, 8])
    method = ["A", "A", "A", "B", "B"]
    rows = table(1.0 + np.array([1, 0.5, 0.25, 4, 1]) / n, n, "exact", method, exact=1.0)
    assert {r["line"] for r in rows} == {"A", "B"}
    orders = {r["line"]: r["observed_order"] for r in rows}
    assert abs(orders["A"] - 2) < 1e-9 and abs(orders["B"] - 3) < 1e-9
    assert all(r["reference_proven"] and r["reference_error"] == 0 for r in rows)


# ---------------------------------------------------------------- monotone or not


@pytest.mark.parametrize("p", [0.5, 1.0, 2.0, 4.0])
@pytest.mark.parametrize("n", [[2, 4, 8, 16, 32, 64], [2, 3, 4, 6, 8, 12, 16, 24]])
def test_a_monotone_convergent_sequence_gets_its_error_and_is_proven_where_it_holds(p, n):
    """q = 1 + h^p over even and uneven knob ratios: the differences shrink (per e-fold of
    the step, so the uneven ratios pass), and the estimate brackets the reference's true
    error h_ref^p within a factor 2 (the order is measured).  It is proven where that is
    below the finest level's error, i.e. where the last ratio r has r^p > 2: at orders 2
    and 4, not at 0.5 and 1, where the finest run is not more accurate than the level before
    it by as much as that level's error.  At order 1 and ratio 2 the estimate equals that
    error in exact arithmetic: a tie is no proof, whichever side of it round-off falls on
    (this CPU's libm put it 1 ulp below, and the test failed there only)."""
    h, err, h_ref = finest(1.0 + (1.0 / np.asarray(n, float)) ** p, n)
    ref = assess("finest", h, err, h_ref)
    assert ref.why.startswith("Richardson"), ref.why
    assert 0.5 < ref.error / h_ref ** p < 2.0, (ref.error, h_ref ** p)
    assert ref.proven == (p >= 2) == (ref.error < (1 - 1e-6) * err.min())


@pytest.mark.parametrize("q, why", [
    # oscillating about a level it never settles on
    ([1.0, 1.1, 0.95, 1.08, 0.97, 1.05], "not monotone"),
    # a plateau, then a jump (the first four levels agree, the fifth moves 1000x more)
    ([1.0 + 5.4e-6, 1.0 + 5.3e-6, 1.0 + 5.25e-6, 1.0 + 5.2e-6, 1.0 + 4.1e-6, 1.0 + 1.4e-8,
      1.0 + 2.9e-9, 1.0], "do not shrink"),
    # one level moves away, then convergence resumes
    ([1.1, 1.001, 1.01, 1.0001, 1.00001, 1.0], "not monotone"),
])
def test_a_non_monotone_sequence_is_not_proven_and_says_why(q, why):
    n = 2 ** np.arange(2, 2 + len(q))
    h, err, h_ref = finest(q, n)
    ref = assess("finest", h, err, h_ref)
    assert not ref.proven and math.isnan(ref.error)
    assert ref.why.startswith("NOT CONVERGED") and why in ref.why, ref.why
    rows = table(np.asarray(q), n)
    assert not any(r["reference_proven"] for r in rows)
    assert rows[0]["reference_why"] == ref.why


def test_monotone_errors_with_growing_differences_are_not_proven():
    """Every level comes closer to the reference, but the last moves more than the one
    before: not in the asymptotic range, whatever the last pair's order says."""
    h, err, h_ref = finest([1.1, 1.09, 1.08, 1.0005, 1.0], [4, 8, 16, 32, 64])
    ref = assess("finest", h, err, h_ref)
    assert not ref.proven and "do not shrink" in ref.why


def test_the_estimate_holds_on_an_exact_case_with_round_off():
    """Independent check: the central difference of sin at x = 1 (error h^2/6 cos(1)
    truncation, then ~eps/h round-off) against its finest level, with the exact cos(1)
    beside it.  The curve is proven above the floor it measures at its finest levels, the
    estimate bounds the reference's true error, and every level compared is truly less
    accurate than the reference."""
    x = 1.0
    h_all = 2.0 ** -np.arange(1, 31)
    q = (np.sin(x + h_all) - np.sin(x - h_all)) / (2 * h_all)
    h, err, h_ref = h_all[:-1], np.abs(q[:-1] - q[-1]), h_all[-1]
    ref = assess("finest", h, err, h_ref)
    floor, _ = noise_floor(h, err)
    assert floor > 0 and ref.floor == floor          # measured, no constant
    assert ref.proven, ref.why
    true_ref = abs(q[-1] - math.cos(x))
    assert true_ref <= ref.error                     # the estimate bounds the truth
    compared = err > accuracy.MARGIN * ref.floor
    true = np.abs(q[:-1] - math.cos(x))
    assert np.all(true[compared] > ref.error)
    # the compared levels are the truncation branch: second order, errors within 10 % of
    # their true values
    assert np.allclose(err[compared], true[compared], rtol=0.1)
    assert abs(accuracy.curve_order(h[compared], err[compared]) - 2) < 0.1


# ---------------------------------------------------------------- the noise floor (issue #25)


def test_the_noise_floor_is_measured_at_the_finest_levels_not_assumed():
    """The joint_wear mean force against Radau rtol 1e-12 (ci profile, this machine): the
    finest two levels sit at 1.1e-12 and 1.5e-12, ten times a fixed 1e-13 round-off
    constant, and do not decrease.  The measured floor is the larger; the levels above 10x
    it converge monotonically and are proven; the reference's error is not below the floor."""
    rtol = 10.0 ** -np.arange(5, 12)
    err = np.array([1.02e-6, 2.95e-7, 5.87e-8, 2.16e-8, 1.23e-11, 1.13e-12, 1.48e-12])
    assert noise_floor(rtol, err) == (1.48e-12, 1e-11)
    ref = assess("finest", rtol, err, 1e-12)
    assert ref.proven and ref.floor == 1.48e-12 and ref.floor <= ref.error < 2.16e-8
    assert "measured" in ref.why
    # a floor declared larger than the measured one is used, and says where it comes from
    big = assess("finest", rtol, err, 1e-12, floor=1e-9, floor_why="an integrator's rtol")
    assert big.floor == 1e-9 and big.error >= 1e-9 and "an integrator's rtol" in big.why
    none = assess("finest", rtol, err, 1e-12, floor=1e-6, floor_why="an integrator's rtol")
    assert not none.proven and none.why == ("NOT CONVERGED: no level above 10 x the noise floor "
                                            "1e-06 (an integrator's rtol)")


def test_a_curve_that_reaches_its_floor_and_stays_there_is_proven_by_it():
    """A quantity converged to the last bits from the second level on (errors 0 or ~1e-16
    against the finest run) has no order, but the spread of its finest levels bounds its
    reference: the level above that band is proven, the flat tail is drawn, not compared."""
    knob = np.array([16, 32, 64, 128, 256])
    errors = np.array([2.1e-10, 0.0, 1.1e-16, 1.1e-16])
    ref = assess("finest", 1.0 / knob[:-1], errors, 1.0 / knob[-1])
    assert ref.proven and ref.error == ref.floor == 1.1e-16
    # a single level at the reference is no measured spread, and one level above it no order
    one = assess("finest", 1.0 / knob[:2], np.array([2.1e-10, 0.0]), 1.0 / knob[2])
    assert not one.proven and "no observed order" in one.why


def test_a_relative_error_resolves_no_less_than_one_ulp():
    """Errors 2e-10, 1e-16, 0: the pair 2e-10 -> 1e-16 is no order (10.4 here); the
    reference's error is one ulp, not the 1e-32 a Richardson step would claim."""
    n = np.array([16, 64, 256, 1024])
    q = 2.37 * (1 + np.array([2.13e-10, 1.14e-16, 0.0, 0.0]))
    rows = table(q, n, error="relative")
    assert all(r["reference_proven"] for r in rows)
    assert rows[0]["reference_error"] == np.finfo(float).eps
    assert "one ulp" in rows[0]["reference_why"]


def test_a_given_reference_error_is_compared_with_every_point():
    h = np.array([0.5, 0.25, 0.125])
    ref = assess("extrapolated", h, np.array([1e-4, 2e-5, 5e-6]), None, given=1e-8)
    assert ref.proven and ref.error == 1e-8
    assert not assess("extrapolated", h, np.array([1e-4, 2e-5, 5e-9]), None, given=1e-8).proven
    # a curve that does not approach its reference proves nothing, even where the reference
    # was made from another sequence (disk_tension's 2-D plate against the axisymmetric
    # Richardson reference, ci profile: 0.0176, 0.0186, 0.00065 at 816, 1376, 3792 DOFs)
    ref = assess("extrapolated", h, np.array([0.0176, 0.0186, 0.00065]), None, given=1e-8)
    assert not ref.proven and "not monotone" in ref.why


def test_an_unproven_curve_is_drawn_as_not_converged():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    n = 2 ** np.arange(2, 8)
    rows = table(np.array([1.0, 1.1, 0.95, 1.08, 0.97, 1.05]), n)
    ax = accuracy.plot(rows, "toy")
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert any("NOT CONVERGED" in t for t in labels)
    assert "not monotone" in ax.get_legend().get_title().get_text()   # why, above the lines
    assert ax.get_lines()[0].get_linestyle() == "--"
    plt.close(ax.figure)
