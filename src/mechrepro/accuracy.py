"""The one cost-of-accuracy path: error against a trusted reference vs wall time.

A paper declares its studies in config (``accuracy:``; see ``config/schema/paper.schema.yaml``)::

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
        return ...                 # or (errors, the reference's own error estimate)

A quantity taken against the finest point uses :func:`against_finest`.  The framework
(rule ``validate_<paper>``) turns every entry into the rows of one long-form table,
``tables/cost_of_accuracy.csv``: one row per (entry, knob value, quantity), columns
:data:`COLUMNS`.  :func:`plot` draws it the same way for every paper.
"""
from __future__ import annotations

import textwrap
from collections.abc import Callable
from typing import NamedTuple

import numpy as np

from .levels import richardson_error
from .registry import Registry

COLUMNS = ["accuracy", "knob", "knob_value", "quantity", "line", "error", "error_kind",
           "error_unit", "reference", "reference_error", "reference_proven", "observed_order",
           "time_s", "time_of", "reference_why"]


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


MARGIN = 10.0   # a level within 10x the noise floor may owe a tenth of its error to noise
# a reference error proven below a curve's smallest error must be below it by more than the
# round-off of the estimate: an estimate that equals that error in exact arithmetic (order 1
# halved once more: e/(2 - 1) = e) came out 1 ulp below it on one CPU and 1 ulp above on another
PROOF_RTOL = 1e-9


def _below(est: float, err) -> bool:
    """Whether ``est`` is below every error in ``err`` by more than round-off."""
    return bool(len(err)) and bool(est < (1.0 - PROOF_RTOL) * float(np.min(err)))


def _coarse_to_fine(h, err):
    h, err = np.asarray(h, float), np.asarray(err, float)
    ok = np.isfinite(err) & np.isfinite(h)
    o = np.argsort(h[ok])[::-1]
    return h[ok][o], err[ok][o]


def noise_floor(h, err) -> tuple[float, float]:
    """(noise floor, step where it starts) measured at a curve's finest levels (``err``:
    errors against its reference): from the first level that comes no closer to the
    reference than the level before it, the largest error up to the finest level.  Those
    levels differ by noise (round-off, an integrator's error control), not by truncation,
    if every coarser level stands well above it (:func:`assess`).  (0, NaN) when every
    refinement comes closer."""
    h, e = _coarse_to_fine(h, err)
    stall = np.flatnonzero(np.diff(e) >= 0)
    if not len(stall):
        return 0.0, float("nan")
    return float(e[stall[0] + 1:].max()), float(h[stall[0] + 1])


def _difference_order(h, e) -> float:
    """The order p of three levels' errors against the finest run, e_i = C (h_i^p - h_ref^p),
    from their successive differences, which do not hold the reference:
    (e_0 - e_1) / (e_1 - e_2) = (h_0^p - h_1^p) / (h_1^p - h_2^p), any step ratios.  The
    right side grows from ln(h_0/h_1) / ln(h_1/h_2) at p -> 0: shrinking differences per
    e-fold of the step are what give a root.  NaN without one in (0, 20)."""
    from scipy.optimize import brentq

    D = (e[0] - e[1]) / (e[1] - e[2])
    x = np.log(np.asarray(h, float) / h[2])          # h_i^p / h_2^p = exp(p x_i)
    g = lambda p: (np.exp(p * x[0]) - np.exp(p * x[1])) / (np.exp(p * x[1]) - 1.0) - D  # noqa: E731
    lo, hi = 1e-6, 20.0
    if not (np.isfinite(D) and g(lo) < 0 < g(hi)):
        return float("nan")
    return float(brentq(g, lo, hi, xtol=1e-10))


class Reference(NamedTuple):
    """A curve's reference: its error estimate (units of the curve's errors), whether that is
    proven below every error on the curve above the noise band, the noise floor and why."""
    error: float
    proven: bool
    floor: float
    why: str


def assess(reference: str, h, err, h_ref: float | None = None, given: float | None = None,
           floor: float = 0.0, floor_why: str = "declared") -> Reference:
    """The error of a curve's reference and whether it is proven (``h``: step, smaller is
    finer; ``err``: errors against the reference; ``floor``: a noise floor known beforehand,
    ``floor_why`` where it comes from).

    The noise floor F is the larger of ``floor`` and the one the curve measures
    (:func:`noise_floor`).  The levels above the noise band (error > MARGIN F) must
    approach the reference monotonically, and the differences between successive levels
    (the last one against the next level: the band's first, or the reference when that is
    the finest run) must shrink, per e-fold of the step, so that uneven knob ratios
    (2, 3, 4, 6 ...) do not read as growth.  A curve whose errors stop decreasing at a
    level not within a tenth of every coarser one is not monotone: the largest error from
    there (its measured F) leaves no level above the band.  The estimate, never below F:

    ``exact``: 0.  ``extrapolated``: the estimate the quantity gives (``given``; the
    reference was made from another sequence, whose proof is the quantity's: this curve
    need not be monotone, only above that estimate), else how far the finest level departs
    from the power law of the two before it (a reference off by d moves the finest error by
    ~d).  ``finest``: Richardson from the last refinements,
    e_ref = e_(n-1) / ((h_(n-1)/h_ref)^p - 1), p the observed order (an error against the
    finest run is measured from it, so its own error is what the curve left out); F when
    the band holds two levels or more, however many stand above it (the sequence reached
    its floor and stayed there: those levels agree with the reference to F).  Proven when the estimate is finite and below every
    error above the band; levels inside the band are drawn, not compared."""
    if reference == "exact":
        return Reference(0.0, True, 0.0, "exact solution")
    h, err = _coarse_to_fine(h, err)
    if given is not None:     # made from another sequence: its proof is the quantity's
        est, e = max(float(given), float(floor)), err[err > MARGIN * floor]
        if np.any(np.diff(e) >= 0):   # a curve that does not approach it proves nothing
            k = int(np.flatnonzero(np.diff(e) >= 0)[0])
            return Reference(est, False, float(floor),
                             f"error {float(given):.2g} given by the quantity; NOT PROVEN: "
                             f"not monotone (error {e[k]:.2g} then {e[k + 1]:.2g})")
        return Reference(est, _below(est, e), float(floor),
                         f"error {float(given):.2g} given by the quantity")
    measured, h_stall = noise_floor(h, err)
    F = max(measured, float(floor))
    above = err > MARGIN * F
    ha, ea = h[above], err[above]          # a coarse prefix, strictly decreasing
    band = int((~above).sum())
    where = ("no noise floor" if F == 0 else
             f"noise floor {F:.2g} ({floor_why})" if floor >= measured else
             f"noise floor {F:.2g} (measured: the largest error from step {h_stall:.3g} on)")
    if not len(ea):
        return Reference(float("nan"), False, F, (
            f"NOT CONVERGED: not monotone: the level at step {h_stall:.3g} comes no closer to "
            f"the reference than the one before it, and no level stands above {MARGIN:g} x "
            f"the largest error from there ({F:.2g})" if F == measured else
            f"NOT CONVERGED: no level above {MARGIN:g} x the {where}"))
    seq_h, seq_e = list(ha), list(ea)
    if band:
        seq_h.append(h[len(ha)]), seq_e.append(err[len(ha)])
    elif reference == "finest" and h_ref is not None:
        seq_h.append(h_ref), seq_e.append(0.0)
    d = -np.diff(seq_e) / np.log(np.asarray(seq_h[:-1]) / np.asarray(seq_h[1:]))
    grow = np.flatnonzero(np.diff(d) >= 0)
    if len(grow):
        k = int(grow[0])
        return Reference(float("nan"), False, F,
                         f"NOT CONVERGED: the differences between successive levels do not "
                         f"shrink ({d[k]:.2g} then {d[k + 1]:.2g} per e-fold of the step, "
                         f"levels at step {seq_h[k]:.3g}, {seq_h[k + 1]:.3g}, {seq_h[k + 2]:.3g})")
    est, p = float("nan"), float("nan")
    if reference == "extrapolated" and len(ha) >= 3:
        (h0, h1, h2), (e0, e1, e2) = ha[-3:], ea[-3:]
        p = np.log(e0 / e1) / np.log(h0 / h1)
        est = abs(e2 - e1 * (h2 / h1) ** p)
    elif reference == "finest" and band >= 2:
        # two finer levels or more agree with the reference to the floor: a Richardson
        # estimate from the levels above them (which assumes the prefix's order holds down
        # to the reference) would contradict them
        return Reference(F, _below(F, ea), F,
                         f"reached its {where} after {len(ea)} level(s) and stayed there "
                         f"over {band} finer levels")
    elif reference == "finest" and h_ref is not None and len(ha) >= 2:
        p = curve_order(ha, ea)
        if len(ha) >= 3:
            p = min(p, _difference_order(ha[-3:], ea[-3:]))
        # and the last refinement must itself converge at that order (a stall gives a
        # small last-pair order, hence a large reference error)
        p = min(p, np.log(ea[-2] / ea[-1]) / np.log(ha[-2] / ha[-1]))
        r = ha[-1] / h_ref
        if np.isfinite(p) and p > 0 and r > 1:
            est = richardson_error(ea[-1], 0.0, r, p)   # an error against the finest: its d2
    if not np.isfinite(est):
        return Reference(float("nan"), False, F,
                         f"NOT CONVERGED: {len(ea)} level(s) above the band of the {where}: "
                         f"no observed order")
    est = float(max(est, F))
    return Reference(est, _below(est, ea), F,
                     f"Richardson at observed order {p:.2g} from {len(ea)} levels; {where}")


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
            got = ds[qspec["variable"]].values if "variable" in qspec else \
                quantities(qname, ds, entry)
            given = qspec.get("reference_error")
            if isinstance(got, tuple):   # (errors, the reference's own error estimate)
                got, given = got
            err = np.asarray(got, float)
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
            # a relative error resolves no less than one ulp of the reference
            ulp = np.finfo(float).eps if qspec["error"] == "relative" else 0.0
            ref = assess(reference, h[ref_line], err[ref_line],
                         float(h[fi]) if reference == "finest" else None,
                         given, ulp, "one ulp of the reference")
            for line in dict.fromkeys(lines):
                on = on_line(line)
                sel = np.flatnonzero(on)
                e = err[sel][err[sel] > MARGIN * ref.floor]   # the band is drawn, not compared
                proven = bool(reference == "exact" or (ref.proven and len(e)
                                                       and ref.error < e.min()))
                why = ref.why if proven or not ref.proven else (
                    f"NOT CONVERGED: the reference's error {ref.error:.2g} is not below "
                    f"this line's errors")
                p = curve_order(h[sel], err[sel]) if entry.get("order", True) else np.nan
                for i in order:
                    if not on[i]:
                        continue   # another line, the reference itself, or not applicable
                    out.append({
                        "accuracy": entry["name"], "knob": entry["knob"],
                        "knob_value": knob[i].item(), "quantity": qname, "line": line,
                        "error": float(err[i]), "error_kind": qspec["error"],
                        "error_unit": "1" if qspec["error"] == "relative" else qspec.get("unit", "1"),
                        "reference": reference, "reference_error": ref.error,
                        "reference_proven": proven, "reference_why": why, "observed_order": p,
                        "time_s": float(t[i]), "time_of": entry.get("time_of", "one solve"),
                    })
    return out


def _true(v) -> bool:
    return v is True or str(v).lower() == "true"


def _thinned(labels):
    """An artist that thins point labels where they are drawn: a label that would cover an
    earlier one is hidden (crowded points), decided on the final layout at every draw."""
    from matplotlib.artist import Artist   # here: validation jobs import this module

    class Thinned(Artist):
        def draw(self, renderer):
            kept = []
            for a in labels:
                a.set_visible(True)
                bb = a.get_window_extent(renderer)
                a.set_visible(not any(bb.overlaps(k) for k in kept))
                if a.get_visible():
                    kept.append(bb)

    out = Thinned()
    out.set_zorder(min((a.get_zorder() for a in labels), default=3) - 0.01)
    return out


def plot(table: list[dict], accuracy: str | None = None, ax=None, annotate: bool = True):
    """Error vs time, one labelled line per (quantity, method) of one entry (the first when
    not given).  A line whose reference is not proven more accurate than its points has not
    converged over the levels run: it is drawn dashed with hollow markers, its label says
    NOT CONVERGED and the panel says why."""
    import matplotlib.pyplot as plt

    accuracy = accuracy or table[0]["accuracy"]
    sel = [r for r in table if r["accuracy"] == accuracy]
    if ax is None:
        _, ax = plt.subplots(figsize=(6, 4.2))
    curves = list(dict.fromkeys((r["quantity"], r.get("line", "")) for r in sel))
    unproven, labels = {}, []
    for j, (q, line) in enumerate(curves):
        pts = [r for r in sel if r["quantity"] == q and r.get("line", "") == line]
        proven = _true(pts[0].get("reference_proven", True))
        p = float(pts[0].get("observed_order", "nan") or "nan")
        label = f"{q}{' ' + line if line else ''} ({pts[0]['error_kind']}"
        label += f", order {p:.2g})" if np.isfinite(p) else ")"
        if not proven:
            label += " [NOT CONVERGED]"
            unproven[q] = pts[0].get("reference_why") or "reference unproven"
        ax.loglog([float(r["time_s"]) for r in pts], [float(r["error"]) for r in pts],
                  "o-" if proven else "o--", mfc=None if proven else "none", label=label)
        if annotate and j == 0:
            last = max(range(len(pts)), key=lambda i: float(pts[i]["time_s"]))
            labels = [ax.annotate(f"{r['knob']}={r['knob_value']}",
                                  (float(r["time_s"]), float(r["error"])), fontsize=7,
                                  textcoords="offset points",
                                  # the rightmost label leftwards: inside the panel
                                  xytext=(-4, 4) if i == last else (4, 4),
                                  ha="right" if i == last else "left")
                      for i, r in enumerate(pts)]
    if annotate:
        ax.add_artist(_thinned(labels))
    ax.set_xlabel(f"wall time [s] ({sel[0]['time_of']})")
    ax.set_ylabel(f"error vs {sel[0]['reference']} [{sel[0].get('error_unit') or '1'}]")
    ax.set_title(f"cost of accuracy: {accuracy}")
    ax.grid(True, which="both", alpha=0.3)
    # the time axis labelled at whole decades only, at least two of them: matplotlib's minor
    # labels of a short log axis depend on the measured times and can collide
    times = np.array([float(r["time_s"]) for r in sel])
    times = times[times > 0]
    if times.size:
        from matplotlib.ticker import NullFormatter

        lo, hi = np.floor(np.log10(times.min())), np.ceil(np.log10(times.max()))
        ax.set_xlim(10 ** lo, 10 ** max(hi, lo + 1))
        ax.xaxis.set_minor_formatter(NullFormatter())
    # below the axes, clear of the data; why a line has not converged is its title, wrapped
    # to the panel (a long line would squeeze the figure's layout)
    leg = ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.2),
                    title="\n".join(textwrap.fill(f"{q}: {why}", 70)
                                    for q, why in unproven.items()) or None, title_fontsize=6)
    leg.get_title().set_color("crimson")
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
    from pathlib import Path

    from .io import open_dataset

    out = []
    for name, run in cfg.runs.items():
        t = run.get("target")
        path = Path(root) / "runs" / f"{name}.nc"
        if not t or not path.exists():
            continue
        with open_dataset(path) as ds:
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
