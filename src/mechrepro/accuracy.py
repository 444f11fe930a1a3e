"""The one cost-of-accuracy path: error against a trusted reference vs wall time.

A paper declares its studies in config (``accuracy:``; see ``config/schema/paper.schema.json``)::

    accuracy:
      - name: K                    # one curve family of the table
        study: cost_of_accuracy    # a study (its runs along ``run``) or a scene's run
        knob: K                    # the coordinate of the knob along the study
        finer: larger              # which direction is finer
        reference: exact           # exact solution, extrapolated (Richardson), or finest point
        time: wall_time            # the time per point [s], a variable of the study
        quantities: {load: {error: relative}}

and registers one function per quantity in ``models/<paper>/accuracy.py``::

    ACCURACY = AccuracyQuantities("saw_chain")

    @ACCURACY.register("load")
    def load(ds, entry):           # -> errors along the knob's dimension
        return ...

A quantity taken against the finest point uses :func:`against_finest`.  The framework
(rule ``validate_<paper>``) turns every entry into the rows of one long-form table,
``tables/cost_of_accuracy.csv``: one row per (entry, knob value, quantity), columns
:data:`COLUMNS`.  :func:`plot` draws it the same way for every paper.
"""
from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .registry import Registry

COLUMNS = ["accuracy", "knob", "knob_value", "quantity", "error", "error_kind", "error_unit",
           "reference", "time_s", "time_of"]


class AccuracyQuantities(Registry):
    """The error functions of one paper's cost-of-accuracy quantities."""

    kind = "accuracy quantity"

    def __call__(self, name: str, ds, entry: dict):
        if name not in self._fn:
            raise KeyError(f"{self.paper}: accuracy quantity {name!r} has no function in "
                           f"models/{self.paper}/accuracy.py (have: {self.names})")
        return self._fn[name](ds, entry)


def finest_index(knob, finer: str) -> int:
    knob = np.asarray(knob, float)
    return int(np.argmax(knob) if finer == "larger" else np.argmin(knob))


def against_finest(values, knob, finer: str, error: str = "relative"):
    """Errors of ``values`` (first axis along the knob; further axes are norms' support)
    against the finest point: max |q_i - q_f| (over the other axes), divided by max |q_f|
    when ``error`` is relative.  The finest point itself gets NaN (it is the reference)."""
    q = np.asarray(values, float)
    f = finest_index(knob, finer)
    diff = np.abs(q - q[f]).reshape(len(q), -1).max(axis=1)
    if error == "relative":
        diff = diff / np.abs(q[f]).max()
    diff[f] = np.nan
    return diff


def observed_order(h, err) -> float:
    """Least-squares slope of log(err) vs log(h): the observed order of convergence."""
    h, err = np.asarray(h, float), np.asarray(err, float)
    ok = (err > 0) & np.isfinite(err)
    return float(np.polyfit(np.log(h[ok]), np.log(err[ok]), 1)[0])


def rows(entries: list[dict], dataset: Callable[[str], object],
         quantities: AccuracyQuantities) -> list[dict]:
    """The long-form cost-of-accuracy table of one paper (``dataset(name)`` opens a study
    or a run).  Sorted from coarse to fine; the reference point of ``finest`` is left out,
    and so is a point whose error is NaN (a quantity that does not apply to it)."""
    out = []
    for entry in entries:
        ds = dataset(entry["study"])
        knob = np.asarray(ds[entry["knob"]].values)
        time_var = entry.get("time", "wall_time")
        t = np.broadcast_to(np.asarray(ds[time_var].values, float), knob.shape)
        order = np.argsort(knob.astype(float))
        if entry["finer"] == "smaller":
            order = order[::-1]
        for qname, qspec in entry["quantities"].items():
            reference = qspec.get("reference", entry["reference"])
            err = np.asarray(quantities(qname, ds, entry), float)
            if err.shape != knob.shape:
                raise ValueError(f"{quantities.paper}: accuracy {entry['name']}.{qname}: "
                                 f"{err.shape} errors for {knob.shape} knob values")
            for i in order:
                if reference == "finest" and i == finest_index(knob, entry["finer"]):
                    continue
                if not np.isfinite(err[i]):
                    continue   # the quantity does not apply at this point (e.g. another method)
                out.append({
                    "accuracy": entry["name"], "knob": entry["knob"],
                    "knob_value": knob[i].item(), "quantity": qname,
                    "error": float(err[i]), "error_kind": qspec["error"],
                    "error_unit": "1" if qspec["error"] == "relative" else qspec.get("unit", "1"),
                    "reference": reference, "time_s": float(t[i]),
                    "time_of": entry.get("time_of", "one solve"),
                })
    return out


def plot(table: list[dict], accuracy: str | None = None, ax=None, annotate: bool = True):
    """Error vs time, one line per quantity of one entry (the first when not given)."""
    import matplotlib.pyplot as plt

    accuracy = accuracy or table[0]["accuracy"]
    sel = [r for r in table if r["accuracy"] == accuracy]
    if ax is None:
        _, ax = plt.subplots(figsize=(6, 4.2))
    quantities = list(dict.fromkeys(r["quantity"] for r in sel))
    for q in quantities:
        pts = [r for r in sel if r["quantity"] == q]
        ax.loglog([float(r["time_s"]) for r in pts], [float(r["error"]) for r in pts], "o-",
                  label=f"{q} ({pts[0]['error_kind']})")
        if annotate and q == quantities[0]:
            for r in pts:
                ax.annotate(f"{r['knob']}={r['knob_value']}", (float(r["time_s"]), float(r["error"])),
                            fontsize=7, textcoords="offset points", xytext=(4, 4))
    ax.set_xlabel(f"wall time [s] ({sel[0]['time_of']})")
    ax.set_ylabel(f"error vs {sel[0]['reference']}")
    ax.set_title(f"cost of accuracy: {accuracy}")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    return ax
