"""The one cost-of-accuracy path: error against a trusted reference vs wall time.

A paper declares its studies in config (``accuracy:``; see ``config/schema/paper.schema.json``)::

    accuracy:
      - name: K                    # one curve family of the table
        study: cost_of_accuracy    # a study (its runs along ``run``) or a scene's run
        knob: K                    # the coordinate of the knob along the study
        finer: larger              # which direction is finer
        reference: exact           # exact solution, extrapolated (Richardson), or finest point
        time: wall_time            # the time per point [s], a variable of the study
        quantities:
          load: {error: relative, variable: load_error}   # errors each run stored

A quantity whose errors each run stores names that variable; any other has a function in
``models/<paper>/accuracy.py``::

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

COLUMNS = ["accuracy", "knob", "knob_value", "quantity", "line", "error", "error_kind",
           "error_unit", "reference", "reference_error", "reference_proven", "observed_order",
           "time_s", "time_of"]


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


def _step(knob, finer: str):
    """A step size along the knob: smaller is finer."""
    k = np.asarray(knob, float)
    return 1.0 / k if finer == "larger" else k


def curve_order(h, err) -> float:
    """Observed order of one curve: the slope over its truncation branch (coarse points up to
    the smallest error; points past it are the round-off floor).  NaN with < 2 points."""
    h, err = np.asarray(h, float), np.asarray(err, float)
    ok = np.isfinite(err) & (err > 0)
    h, err = h[ok], err[ok]
    if len(h) < 2:
        return float("nan")
    o = np.argsort(h)[::-1]                     # coarse -> fine
    h, err = h[o], err[o]
    stop = int(np.argmin(err)) + 1
    if stop < 2:
        return float("nan")
    return observed_order(h[:stop], err[:stop])


ROUNDOFF = 1e-13   # relative: a few hundred ulp of double precision, the floor of a converged curve


def at_roundoff(h, err) -> bool:
    """Whether the two finest points of a curve lie at round-off (relative errors)."""
    h, err = np.asarray(h, float), np.asarray(err, float)
    ok = np.isfinite(err)
    finest = err[ok][np.argsort(h[ok])][:2]
    return len(finest) == 2 and bool(np.all(finest <= ROUNDOFF))


def reference_error(reference: str, h, err, h_ref: float | None, given: float | None = None):
    """(error estimate of the curve's reference, proven) in the units of ``err``.

    ``exact``: 0.  ``extrapolated``: the estimate the quantity gives (``given``), else how far
    the finest point departs from the power law of the two before it (a reference off by d
    moves the finest error by ~d).  ``finest``: Richardson from the last two refinements,
    e_ref = e_(n-1) / ((h_(n-1)/h_ref)^p - 1), p the curve's observed order (an error against
    the finest point is measured from it, so its own error is what the curve left out).
    Proven when the estimate is finite and below the smallest error on the curve."""
    h, err = np.asarray(h, float), np.asarray(err, float)
    ok = np.isfinite(err) & (err > 0)
    h, err = h[ok], err[ok]
    smallest = float(err.min()) if len(err) else float("nan")
    if reference == "exact":
        return 0.0, True
    est = float("nan")
    if given is not None:
        est = float(given)
    elif reference == "extrapolated" and len(h) >= 3:
        o = np.argsort(h)[::-1]
        (h0, h1, h2), (e0, e1, e2) = h[o][-3:], err[o][-3:]
        if e0 > e1 > 0:
            p = np.log(e0 / e1) / np.log(h0 / h1)
            est = abs(e2 - e1 * (h2 / h1) ** p)
    elif reference == "finest" and len(h) >= 2 and h_ref is not None:
        p = curve_order(h, err)
        o = np.argsort(h)
        if len(h) >= 3:
            # errors measured from the finest run are C (h^p - h_ref^p): their successive
            # differences give p without that bias
            (ha, hb, hc), (ea, eb, ec) = h[o][2::-1], err[o][2::-1]
            if ea > eb > ec and ha / hb > 1 and hb / hc > 1:
                pd = np.log((ea - eb) / (eb - ec)) / np.log(hb / hc)
                if np.isfinite(pd) and abs(np.log(ha / hb) - np.log(hb / hc)) < 1e-6:
                    p = min(p, pd)
        if len(h) >= 2:
            # and the last refinement must itself converge at that order (a stall in the
            # round-off floor gives a small last-pair order, hence a large reference error)
            (hb, hc), (eb, ec) = h[o][1::-1], err[o][1::-1]
            p = min(p, np.log(eb / ec) / np.log(hb / hc)) if hb > hc else p
        h1, e1 = h[o][0], err[o][0]              # the finest point on the curve
        r = h1 / h_ref
        if np.isfinite(p) and p > 0 and r > 1:
            est = e1 / (r ** p - 1.0)
    proven = bool(np.isfinite(est) and est < smallest)
    return est, proven


def _lines(ds, entry, n: int):
    """Labels of the curve's lines (one per method): ``entry['line_by']`` or a ``method``
    variable along the knob when the study has one; else one line."""
    by = entry.get("line_by", "method" if "method" in getattr(ds, "variables", {}) else None)
    if by is None:
        return np.full(n, "", dtype=object)
    v = np.asarray(ds[by].values)
    return np.broadcast_to(v, (n,)).astype(str).astype(object) if v.size in (1, n) else \
        np.full(n, "", dtype=object)


def rows(entries: list[dict], dataset: Callable[[str], object],
         quantities: AccuracyQuantities | None) -> list[dict]:
    """The long-form cost-of-accuracy table of one paper (``dataset(name)`` opens a study
    or a run).  Sorted from coarse to fine; the reference point of ``finest`` is left out,
    and so is a point whose error is NaN (a quantity that does not apply to it).  Each row
    carries its line (method), the curve's observed order and its reference's error
    estimate and whether that is proven smaller than every error on the curve."""
    out = []
    for entry in entries:
        ds = dataset(entry["study"])
        knob = np.asarray(ds[entry["knob"]].values)
        time_var = entry.get("time", "wall_time")
        t = np.broadcast_to(np.asarray(ds[time_var].values, float), knob.shape)
        order = np.argsort(knob.astype(float))
        if entry["finer"] == "smaller":
            order = order[::-1]
        h = _step(knob, entry["finer"])
        lines = _lines(ds, entry, len(knob))
        fi = finest_index(knob, entry["finer"])
        for qname, qspec in entry["quantities"].items():
            reference = qspec.get("reference", entry["reference"])
            err = np.asarray(ds[qspec["variable"]].values if "variable" in qspec else
                             quantities(qname, ds, entry), float)
            if err.shape != knob.shape:
                raise ValueError(f"accuracy {entry['name']}.{qname}: "
                                 f"{err.shape} errors for {knob.shape} knob values")
            def on_line(line):
                on = (lines == line) & np.isfinite(err)
                if reference == "finest":
                    on[fi] = False
                return on

            # the reference's error comes from the line it belongs to (the finest point's
            # method) and holds for every line of the entry
            ref_line = on_line(lines[fi])
            ref_err, _ = reference_error(
                reference, h[ref_line], err[ref_line],
                float(h[fi]) if reference == "finest" else None, qspec.get("reference_error"))
            floor = ROUNDOFF if qspec["error"] == "relative" else 0.0
            if not np.isfinite(ref_err) and floor and at_roundoff(h[ref_line], err[ref_line]):
                # the curve reaches its reference within round-off: that bounds its error
                ref_err = floor
            for line in dict.fromkeys(lines):
                on = on_line(line)
                sel = np.flatnonzero(on)
                e = err[sel][err[sel] > floor]
                proven = bool(reference == "exact" or (np.isfinite(ref_err) and len(e)
                                                       and ref_err < e.min()))
                p = curve_order(h[sel], err[sel])
                for i in order:
                    if not on[i]:
                        continue   # another line, the reference itself, or not applicable
                    out.append({
                        "accuracy": entry["name"], "knob": entry["knob"],
                        "knob_value": knob[i].item(), "quantity": qname, "line": line,
                        "error": float(err[i]), "error_kind": qspec["error"],
                        "error_unit": "1" if qspec["error"] == "relative" else qspec.get("unit", "1"),
                        "reference": reference, "reference_error": ref_err,
                        "reference_proven": proven, "observed_order": p,
                        "time_s": float(t[i]), "time_of": entry.get("time_of", "one solve"),
                    })
    return out


def _true(v) -> bool:
    return v is True or str(v).lower() == "true"


def plot(table: list[dict], accuracy: str | None = None, ax=None, annotate: bool = True):
    """Error vs time, one labelled line per (quantity, method) of one entry (the first when
    not given).  A line whose reference is not proven more accurate than its points is drawn
    dashed with hollow markers and says so in its label."""
    import matplotlib.pyplot as plt

    accuracy = accuracy or table[0]["accuracy"]
    sel = [r for r in table if r["accuracy"] == accuracy]
    if ax is None:
        _, ax = plt.subplots(figsize=(6, 4.2))
    curves = list(dict.fromkeys((r["quantity"], r.get("line", "")) for r in sel))
    for j, (q, line) in enumerate(curves):
        pts = [r for r in sel if r["quantity"] == q and r.get("line", "") == line]
        proven = _true(pts[0].get("reference_proven", True))
        p = float(pts[0].get("observed_order", "nan") or "nan")
        label = f"{q}{' ' + line if line else ''} ({pts[0]['error_kind']}"
        label += f", order {p:.2g})" if np.isfinite(p) else ")"
        if not proven:
            label += " [reference unproven]"
        ax.loglog([float(r["time_s"]) for r in pts], [float(r["error"]) for r in pts],
                  "o-" if proven else "o--", mfc=None if proven else "none", label=label)
        if annotate and j == 0:
            for r in pts:
                ax.annotate(f"{r['knob']}={r['knob_value']}", (float(r["time_s"]), float(r["error"])),
                            fontsize=7, textcoords="offset points", xytext=(4, 4))
    ax.set_xlabel(f"wall time [s] ({sel[0]['time_of']})")
    ax.set_ylabel(f"error vs {sel[0]['reference']}")
    ax.set_title(f"cost of accuracy: {accuracy}")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    return ax


TARGET_COLUMNS = ["run", "quantity", "reduce", "knob", "extrapolated", "value", "requested",
                  "estimated_error",
                  "verified_error", "observed_order", "knob_value", "time_s", "time_all_solves_s",
                  "default_knob_value", "default_error", "default_estimated_error", "default_time_s",
                  "unit"]


def target_rows(cfg, root) -> list[dict]:
    """``tables/accuracy_targets.csv``: per scene run with a ``target:``, what was asked
    (absolute), estimated (Richardson), verified (against ``exact``), the knob value chosen
    and its solve time, next to the scene's fixed default knob value's error and time."""
    import xarray as xr

    from pathlib import Path

    out = []
    for name, run in cfg.runs.items():
        t = run.get("target")
        path = Path(root) / "runs" / f"{name}.nc"
        if not t or not path.exists():
            continue
        with xr.open_dataset(path) as ds:
            g = lambda k: float(ds[f"target_{k}"].values) if f"target_{k}" in ds else float("nan")  # noqa: E731
            out.append({"run": name, "quantity": t["quantity"], "reduce": t.get("reduce", "max"),
                        "knob": t["knob"], "extrapolated": bool(t.get("extrapolate")),
                        "value": g("value"), "requested": g("requested"),
                        "estimated_error": g("estimated_error"),
                        "verified_error": g("verified_error"),
                        "observed_order": g("observed_order"), "knob_value": g("knob_value"),
                        "time_s": g("seconds_chosen"), "time_all_solves_s": g("seconds_all_solves"),
                        "default_knob_value": g("default_value"),
                        "default_error": g("default_error"),
                        "default_estimated_error": g("default_estimated_error"),
                        "default_time_s": g("default_seconds"),
                        "unit": t.get("unit", "1")})
    return out
