"""Cost of accuracy: a curve's reference must be shown more accurate than every point on it."""
import numpy as np

from mechrepro import accuracy


class DS(dict):
    @property
    def variables(self):
        return self


class Var:
    def __init__(self, v):
        self.values = np.asarray(v)


def table(q, knob, reference="finest", method=None, exact=0.0):
    ds = DS(n=Var(knob), wall_time=Var(np.asarray(knob, float)), q=Var(q))
    if method is not None:
        ds["method"] = Var(method)
    Q = accuracy.AccuracyQuantities("toy")

    @Q.register("q")
    def _(d, entry):
        if reference == "exact":
            return np.abs(np.asarray(d["q"].values) - exact)
        return accuracy.against_finest(d["q"].values, d["n"].values, "larger", "absolute")

    entry = {"name": "toy", "study": "s", "knob": "n", "finer": "larger", "reference": reference,
             "quantities": {"q": {"error": "absolute"}}}
    return accuracy.rows([entry], lambda name: ds, Q)


def test_finest_reference_of_a_second_order_curve_is_proven():
    n = np.array([4, 8, 16, 32, 64])
    rows = table(1.0 + 1.0 / n ** 2, n)
    assert all(r["reference_proven"] for r in rows)
    # errors measured from the finest run bias the slope up a little (2.13 here)
    assert abs(rows[0]["observed_order"] - 2) < 0.15
    # its estimate is the finest point's true error (1/64^2) within 10 %
    assert abs(rows[0]["reference_error"] * 64 ** 2 - 1) < 0.1


def test_finest_reference_in_the_round_off_floor_is_flagged_not_silent():
    n = np.array([4, 8, 16, 32, 64])
    floor = np.array([0, 0, 0, 3e-3, -3e-3])       # the last two runs are noise, not refinement
    rows = table(1.0 + 1.0 / n ** 2 + floor, n)
    assert not any(r["reference_proven"] for r in rows)


def test_exact_reference_is_proven_and_methods_are_separate_labelled_lines():
    n = np.array([4, 8, 16, 4, 8])
    method = ["A", "A", "A", "B", "B"]
    rows = table(1.0 + np.array([1, 0.5, 0.25, 4, 1]) / n, n, "exact", method, exact=1.0)
    assert {r["line"] for r in rows} == {"A", "B"}
    orders = {r["line"]: r["observed_order"] for r in rows}
    assert abs(orders["A"] - 2) < 1e-9 and abs(orders["B"] - 3) < 1e-9
    assert all(r["reference_proven"] and r["reference_error"] == 0 for r in rows)


def test_a_curve_at_round_off_bounds_its_reference_by_round_off():
    """A quantity converged to the last bits from the second level on (errors 0 or ~1e-16
    against the finest run) has no Richardson estimate, but its reference is at least as
    good as round-off: the points above that floor are proven, the flat tail is not
    compared."""
    from mechrepro import accuracy

    knob = np.array([16, 32, 64, 128, 256])
    errors = np.array([2.1e-10, 0.0, 1.1e-16, 1.1e-16, 0.0])
    assert accuracy.at_roundoff(1.0 / knob, errors)
    assert not accuracy.at_roundoff(1.0 / knob, np.array([1e-3, 1e-4, 1e-5, 1e-6, 1e-7]))
