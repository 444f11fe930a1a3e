"""The one validation builder: what the paper reports (config) against what we reproduce.

What a paper reports is data: the ``reported:`` block of ``config/papers/<paper>.yaml``
(value typed once, unit, source, tolerance and why, evidence class, what it reads and
which assumed constants it depends on).  ``models/<paper>/validation.py`` only registers
functions that extract the reproduced values (:class:`Quantities`).  :func:`build` then

1. evaluates every quantity on the baseline runs;
2. re-evaluates every verdict row on its variant runs: one and two levels coarser (every
   knob together) give the baseline value's error estimate and observed order, or show
   that it does not converge (``not_converged``); other seeds add their spread; both ends of an
   assumed constant's range, or the corners and seeded members of a declared family, must
   not flip the verdict (else ``inconclusive``, saying what flips it); a counted row is
   re-run under every rival model of its paper (the discrimination matrix);
3. decides each verdict with its error bar: ``pass`` when |value - paper| + error is within
   the tolerance, ``fail`` when |value - paper| - error is beyond it, else ``inconclusive``;
   a counted (``independent``) pass that no rival fails (other than a sledgehammer, which
   fails most rows) is graded ``not_discriminating``: reproduced, not counted;
4. returns the rows; :func:`write_table` writes ``validation.csv``, :func:`write_evidence`
   every re-check (``verdict_evidence.csv``), :func:`discrimination` the rows x rivals
   matrix and :func:`claim` the replication claim, which
   counts only ``independent`` rows.

See docs/VALIDATION.md for the contract.
"""
from __future__ import annotations

import csv
import io
import math
import operator
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

from .errors import Refusal
from .io import ENGINE, write_json, write_text
from .levels import NEGLIGIBLE, level_error  # noqa: F401  (the one estimator; tests import it here)
from .registry import Registry

COLUMNS = ["quantity", "source", "paper_value", "reproduced_value", "unit", "rel_error",
           "tolerance", "status", "evidence", "note", "artefact", "criterion",
           "error_estimate", "observed_order", "rivals"]
EVIDENCE_COLUMNS = ["quantity", "variant", "kind", "value", "status", "label"]
# not_discriminating: a counted pass no rival fails (reproduced, not evidence for the model)
EVIDENCE = ("independent", "not_discriminating", "calibration", "determined", "construction",
            "target")
NOT_RUN = "not run (the row names the rivals it runs under)"
DISCRIMINATION_COLUMNS = ["quantity", "artefact", "status", "evidence", "rival", "removes",
                          "value", "rival_status", "outcome", "sledgehammer", "credits"]
STATUSES = ("pass", "fail", "inconclusive", "not_converged", "info")
OPS = {">": operator.gt, ">=": operator.ge, "<": operator.lt, "<=": operator.le}


class ValidationError(Refusal):
    """A quantity cannot be extracted as declared (the message names it)."""


@dataclass
class Reproduced:
    """A reproduced value with a note computed from the runs (e.g. the exact value).

    ``flips`` names re-checks the extraction did itself that change the verdict (a joint
    corner of several assumed constants, which the one-at-a-time variants do not reach);
    a pass or fail with flips is ``inconclusive``.  ``error``: an error the extraction
    knows of its own (e.g. half the step of the grid a peak was read from), added to the
    error estimate from the resolution levels and seeds.  ``not_converged``: why the
    extraction's own refinement study (runs it reads at several resolutions) shows that the
    value does not converge; the row is then ``not_converged`` whatever its levels say.
    """
    value: float | bool
    note: str = ""
    flips: list[str] = field(default_factory=list)
    error: float = 0.0
    not_converged: str = ""


class Quantities(Registry):
    """The registry of a paper's extraction functions, one per reported quantity."""

    kind = "quantity"

    def evaluate(self, wanted, R: "ValidationInputs") -> dict[str, Reproduced]:
        """Call each function needed for ``wanted`` once; values wrapped as Reproduced."""
        out: dict[str, Reproduced] = {}
        for fn in dict.fromkeys(self._fn[q] for q in wanted):
            names = self._names[fn]
            R.allowed = R.reads_of(names)
            try:
                got = fn(R)
            except ValidationError:
                raise
            except Exception as exc:  # name the quantity, keep the cause
                raise ValidationError(f"{self.paper}: extracting {', '.join(names)} "
                                      f"({R.describe()}) failed: {exc!r}") from exc
            if len(names) == 1 and not isinstance(got, dict):
                got = {names[0]: got}
            if set(got) != set(names):
                raise ValidationError(f"{self.paper}: {fn.__name__} returned {sorted(got)}, "
                                      f"registered {sorted(names)}")
            for n, v in got.items():
                out[n] = v if isinstance(v, Reproduced) else Reproduced(v)
        return out


class ResultFiles:
    """The result files of one validate job, each opened once and read lazily.

    A job reads ~20-60 files, most for a few of their variables, and the variants re-read
    the baseline runs they do not re-run; loading every variable of every file (what
    :func:`mechrepro.io.open_dataset` does for a reader that keeps the data) was most of
    the job's reading time.  Values are decoded by xarray exactly as ``open_dataset``
    decodes them, only when first used.  Use as a context manager: it closes the files.
    """

    def __init__(self):
        self._open: dict[Path, object] = {}
        self._derived: dict = {}

    def __call__(self, path: str | Path):
        import xarray as xr

        path = Path(path)
        if path not in self._open:
            self._open[path] = xr.open_dataset(path, engine=ENGINE)
        return self._open[path]

    def derived(self, key, make):
        """``make()`` once per job and ``key`` (e.g. a study split into its points, which
        several quantities and their variants read; key it by the ids of the datasets it
        is made of: they stay open, so their ids are unique, until :meth:`close`)."""
        if key not in self._derived:
            self._derived[key] = make()
        return self._derived[key]

    def close(self) -> None:
        for ds in self._open.values():
            ds.close()
        self._open.clear()
        self._derived.clear()

    def __enter__(self) -> "ResultFiles":
        return self

    def __exit__(self, *exc) -> None:
        self.close()


class ValidationInputs:
    """What an extraction function may read: the runs of one variant, as declared."""

    def __init__(self, cfg, results_dir: str | Path, variant: str | None = None,
                 files: ResultFiles | None = None):
        self.cfg = cfg
        self.root = Path(results_dir) / cfg.paper
        self.variant = variant
        self.allowed: set[str] = set()
        self._files = ResultFiles() if files is None else files

    def reads_of(self, names) -> set[str]:
        return {r for n in names for r in self.cfg.reported[n]["reads"]}

    def describe(self) -> str:
        return "baseline" if self.variant is None else f"variant {self.variant}"

    def _name(self, name: str, kind: str) -> str:
        if name not in self.allowed:
            raise ValidationError(f"{self.cfg.paper}: reads {kind} {name!r}, which its quantities "
                                  f"do not declare (reads: {sorted(self.allowed)})")
        table = self.cfg.runs if kind == "run" else self.cfg.studies
        v = f"{name}@{self.variant}"
        # a run that this variant does not re-run is the baseline run (the variant only
        # re-runs what the rows needing it read)
        return v if self.variant and v in table else name

    def _open(self, path: Path):
        return self._files(path)

    def run(self, name: str):
        return self._open(self.root / "runs" / f"{self._name(name, 'run')}.nc")

    def study(self, name: str):
        return self._open(self.root / "studies" / f"{self._name(name, 'study')}.nc")

    def study_runs(self, name: str) -> list:
        """The run datasets of a study, in sweep order: what a study file cannot stack
        (variables whose length differs between its runs, e.g. adaptively sampled speeds)."""
        return [self._open(self.root / "runs" / f"{r}.nc")
                for r in self.cfg.studies[self._name(name, "study")]]

    def derived(self, key, make):
        """See :meth:`ResultFiles.derived` (read the datasets it needs through :meth:`run`
        and :meth:`study` first, so that the declared reads are checked every time)."""
        return self._files.derived(key, make)

    def reported(self, quantity: str) -> dict:
        return self.cfg.reported[quantity]

    def paper_value(self, quantity: str) -> float:
        return float(self.cfg.reported[quantity]["value"])

    def parameter(self, name: str):
        """SI value of a paper parameter in this variant (as a scene without overrides sees it)."""
        from .units import to_si

        spec = self.cfg.raw["parameters"][name]
        value = spec["value"]
        if self.variant:
            value = self.cfg.variant_info[self.variant]["parameters"].get(name, value)
        return to_si(value, spec["unit"])[0]


@dataclass
class Row:
    quantity: str
    spec: dict
    value: float
    note: str = ""
    status: str = "info"
    flips: list[str] = field(default_factory=list)
    error: float = math.nan          # error estimate of value (levels + seeds + own)
    order: float = math.nan          # observed order across the levels
    evidence: str = ""               # as graded (a pass no rival fails: not_discriminating)
    rivals: dict = field(default_factory=dict)   # rival -> (status, value, outcome, level)
    checks: list[tuple] = field(default_factory=list)   # (variant, kind, value, status, label)

    def __post_init__(self):
        self.evidence = self.evidence or self.spec["evidence"]

    def add_note(self, text: str) -> None:
        self.note = " ".join(x for x in (self.note, text) if x)

    @property
    def kind(self) -> str:
        return self.spec["kind"]

    @property
    def verdict(self) -> str:
        """The verdict of the value alone (no error bar, no re-check)."""
        return verdict(self.spec, self.value)

    @property
    def paper_value(self) -> float:
        if self.kind == "check":
            return 1.0
        return float(self.spec.get("value", math.nan))

    @property
    def reproduced_value(self) -> float:
        return self.value

    @property
    def unit(self) -> str:
        return self.spec.get("unit", "bool" if self.kind == "check" else "1")

    @property
    def rel_error(self) -> float:
        return rel_error(self.paper_value, self.value)

    @property
    def criterion(self) -> str:
        k = self.kind
        if k == "compare":
            return f"|rel_error| <= {self.spec['tolerance']:g}"
        if k == "bound":
            return f"reproduced {self.spec['op']} {self.spec['value']:g} {self.spec.get('unit', '')}".strip()
        if k == "check":
            return "claim holds"
        return ""

    def cells(self) -> list:
        tol = self.spec.get("tolerance", math.nan) if self.kind == "compare" else math.nan
        notes = [n for n in (self.spec.get("note", ""), self.note) if n]
        if self.flips:
            notes.insert(0, self.status.upper().replace("_", " ") + ": " + "; ".join(self.flips))
        if self.spec.get("evidence_why"):
            notes.append(f"[{self.spec['evidence']}] {self.spec['evidence_why']}")
        return [self.quantity, self.spec["source"], _fmt(self.paper_value), _fmt(self.value),
                self.unit, _fmt(self.rel_error), _fmt(tol), self.status, self.evidence,
                " ".join(notes), self.spec["artefact"], self.criterion,
                _fmt(self.error), _fmt(self.order), self.rivals_text]

    @property
    def rivals_text(self) -> str:
        return "; ".join(f"{r}: {o} ({_fmt_short(v)}{f' at the {at} level' if at else ''})"
                         for r, (_, v, o, at) in self.rivals.items() if o != NOT_RUN)


def rel_error(paper: float, reproduced: float) -> float:
    p, r = float(paper), float(reproduced)
    if math.isnan(p) or math.isnan(r):
        return math.nan
    return abs(r - p) if p == 0.0 else (r - p) / abs(p)


def verdict(spec: dict, value) -> str:
    """pass / fail of one value against one reported spec (info rows: info)."""
    kind = spec["kind"]
    if kind == "info":
        return "info"
    if kind == "check":
        if isinstance(value, float) and math.isnan(value):
            return "no_value"   # bool(nan) is True: a check that was not evaluated is no pass
        return "pass" if bool(value) else "fail"
    x = float(value)
    if math.isnan(x):
        return "no_value"   # the quantity does not exist there (its note says why)
    if kind == "bound":
        return "pass" if OPS[spec["op"]](x, float(spec["value"])) else "fail"
    return "pass" if abs(rel_error(spec["value"], x)) <= float(spec["tolerance"]) else "fail"


def band(spec: dict, value: float) -> float:
    """The width a difference must stay below to leave a verdict alone: the tolerance
    band of a compare row, the distance to the threshold of a bound row."""
    if spec["kind"] == "compare":
        p = float(spec["value"])
        return float(spec["tolerance"]) * (abs(p) if p != 0.0 else 1.0)
    if spec["kind"] == "bound":
        return abs(float(value) - float(spec["value"]))
    return math.nan


def verdict_with_error(spec: dict, value: float, error: float) -> tuple[str, str]:
    """pass / fail / inconclusive of a compare or bound row whose value is known to
    +- ``error`` (and why, when inconclusive)."""
    if isinstance(error, float) and math.isnan(error):
        return "inconclusive", "no error estimate: a resolution level gave no value"
    if not error:
        return verdict(spec, value), ""
    if spec["kind"] == "compare":
        d, w = abs(float(value) - float(spec["value"])), band(spec, value)
        if d + error <= w:
            return "pass", ""
        if d - error > w:
            return "fail", ""
        return "inconclusive", (f"the error bar straddles the tolerance: |value - paper| = "
                                f"{d:.4g} +- {error:.3g} against {w:.4g}")
    lo, hi = verdict(spec, value - error), verdict(spec, value + error)
    if lo == hi:
        return lo, ""
    return "inconclusive", (f"the error bar straddles the threshold: {float(value):.6g} +- "
                            f"{error:.3g} {spec['op']} {float(spec['value']):g}")


def _level_ratio(cfg, spec: dict) -> float:
    """The refinement factor of one level (the largest over the refined knobs of the
    row's reads; >1)."""
    from .config import refine_spec

    refine = refine_spec(cfg.raw)
    keys = {k for r in spec["reads"]
            for run in (cfg.studies.get(r) or [r]) for k in cfg.runs[run]["resolution"]}
    ratios = [max(f, 1 / f) for k in keys if "factor" in refine.get(k, {})
              for f in [refine[k]["factor"]]]
    return max(ratios, default=math.nan)


def _distribution(values: list[float]) -> str:
    v = sorted(x for x in values if not math.isnan(x))
    if not v:
        return ""
    return f"min {v[0]:.6g}, median {v[len(v) // 2]:.6g}, max {v[-1]:.6g}"


def build(cfg, quantities: Quantities, results_dir: str | Path,
          files: ResultFiles | None = None) -> list[Row]:
    """Evaluate every reported quantity and its verdict with error bar (module docstring).
    ``files``: the job's open result files (default: opened here, closed on return)."""
    if files is None:
        with ResultFiles() as files:
            return build(cfg, quantities, results_dir, files)
    from .config import _variant_names

    reported = cfg.reported
    missing = sorted(set(reported) - set(quantities.names))
    extra = sorted(set(quantities.names) - set(reported))
    if cfg.rows:   # a config cut down to some artefacts (PaperConfig.for_artefacts)
        reported = {q: reported[q] for q in cfg.rows}
    if missing or extra:
        raise ValidationError(f"{cfg.paper}: reported quantities without an extraction function: "
                              f"{missing}; functions for quantities not reported: {extra}")
    base = quantities.evaluate(list(reported), ValidationInputs(cfg, results_dir, files=files))
    by_variant: dict[str, list[str]] = {}
    for q, spec in reported.items():
        for v in _variant_names(spec, cfg.raw):
            by_variant.setdefault(v, []).append(q)
    skipped = {v: [q for q in qs if set(reported[q]["reads"]) & set(cfg.variant_skipped.get(v, {}))]
               for v, qs in by_variant.items()}
    got: dict[str, dict[str, Reproduced]] = {
        variant: quantities.evaluate([q for q in qs if q not in skipped[variant]],
                                     ValidationInputs(cfg, results_dir, variant, files))
        for variant, qs in by_variant.items()}
    rows = [_row(cfg, q, spec, base[q], {v: got[v][q] for v in _variant_names(spec, cfg.raw)
                                         if q in got[v]})
            for q, spec in reported.items()]
    grade_rivals(rows)
    return rows


def _row(cfg, q: str, spec: dict, r: Reproduced, variants: dict[str, Reproduced]) -> Row:
    """One row's verdict from its baseline value and its re-checks."""
    row = Row(q, spec, float(r.value), r.note, verdict(spec, r.value))
    if row.status == "info":
        return row
    info = cfg.variant_info
    numeric = spec["kind"] in ("compare", "bound") and math.isfinite(row.value)
    base_status = row.status
    if base_status == "no_value":
        row.status = "inconclusive"
        row.flips = [f"no value: {r.note or 'the quantity could not be evaluated'}"]
        return row
    for v, got in variants.items():
        s = verdict(spec, got.value)
        if info[v]["kind"] == "family" and math.isnan(float(got.value)):
            s = "excluded"   # a member the model refuses by name (not buildable, no root)
        row.checks.append((v, info[v]["kind"], float(got.value), s, info[v]["label"]))
    by_kind: dict[str, list[tuple]] = {}
    for c in row.checks:
        by_kind.setdefault(c[1], []).append(c)
    flips = list(r.flips)
    converged, how = True, ""
    error = float(r.error or 0.0)
    levels = {c[0]: c for c in by_kind.get("level", [])}
    if "coarser" in levels:
        if numeric:
            coarsest = levels["coarsest"][2] if "coarsest" in levels else math.nan
            if "coarsest" not in levels:
                row.add_note(f"No coarsest level ({_skipped_why(cfg, 'coarsest', spec)}).")
            ratio, width, own = _level_ratio(cfg, spec), band(spec, row.value), float(r.error or 0.0)
            e, row.order, converged, how = level_error(coarsest, levels["coarser"][2], row.value,
                                                       ratio, width, own)
            if "finer" in levels and converged:
                # both sides: the baseline is off by at least its distance to the finer
                # level, plus that level's own error from the three finest levels
                fine = levels["finer"][2]
                ef, order_f, converged, how_f = level_error(levels["coarser"][2], row.value,
                                                            fine, ratio, width, own)
                if not converged:
                    how = (f"refined once more, the levels do not contract: coarser "
                           f"{levels['coarser'][2]:.6g}, base {row.value:.6g}, finer {fine:.6g}")
                elif abs(row.value - fine) + ef > e:
                    e = abs(row.value - fine) + ef
                    how = (f"{how}; one level finer {fine:.6g}: |base - finer| + its error "
                           f"{ef:.3g}")
                    row.order = order_f
                if verdict(spec, fine) != base_status:
                    flips.append(f"{verdict(spec, fine)} one level finer: {_fmt_short(fine)}")
            elif spec.get("finer") is False and converged:
                # the baseline is the middle level: the value is the coarser run's, its error
                # its distance to the baseline plus the baseline's own (both sides)
                fine, row.value = row.value, levels["coarser"][2]
                e = abs(row.value - fine) + e
                how = f"{how}; the baseline {fine:.6g} is the level above this coarser value"
                row.add_note(f"The baseline is the middle level: the value is the coarser "
                             f"level's, the baseline run one level finer ({spec['finer_why']}).")
                if verdict(spec, fine) != verdict(spec, row.value):
                    flips.append(f"{verdict(spec, fine)} one level finer (the baseline run): "
                                 f"{_fmt_short(fine)}")
                base_status = row.status = verdict(spec, row.value)
            elif spec["evidence"] == "independent" and converged:
                why = _skipped_why(cfg, "finer", spec)
                row.add_note(f"Levels on one side only: no run one level finer ({why}).")
            error += e
        else:
            # a worded claim has no error bar: it must hold at every level
            flips += [f"{c[3]} {c[4]}: {_fmt_short(c[2])}" for c in levels.values()
                      if c[3] != base_status]
    elif spec.get("levels", True):
        flips.append("no error estimate: no resolution level below the baseline runs "
                     f"({_skipped_why(cfg, 'coarser', spec)})")
    seeds = by_kind.get("seed", [])
    if seeds and numeric:
        error += max(abs(c[2] - row.value) for c in seeds)
    moved = {c: _at_baseline(c, _level_of(info, c[0], spec), levels, row.value, spec, numeric)
             for c in by_kind.get("range", []) + by_kind.get("family", [])}
    row.checks = [moved.get(c, c) for c in row.checks]
    for c in seeds + [moved[c] for c in by_kind.get("range", [])]:
        if c[3] != base_status:
            flips.append(f"{c[3]} {c[4]}: {_fmt_short(c[2])}")
    fam = [moved[c] for c in by_kind.get("family", [])]
    if fam:
        names = sorted({c[0].rsplit("-", 1)[0] for c in fam})
        for name in names:
            members = [c for c in fam if c[0].rsplit("-", 1)[0] == name]
            excluded = [c for c in members if c[3] == "excluded"]
            members = [c for c in members if c[3] != "excluded"]
            flipped = [c for c in members if c[3] != base_status]
            dist = _distribution([c[2] for c in members]) if numeric else ""
            out = f", {len(excluded)} refused by the model" if excluded else ""
            row.add_note(f"Family {name} ({len(members)} members{out}): {dist}"
                         f"{'; ' if dist else ''}{len(flipped)} flip the verdict.")
            flips += [f"{c[3]} {c[4]}: {_fmt_short(c[2])}" for c in flipped[:3]]
            if len(flipped) > 3:
                flips.append(f"and {len(flipped) - 3} more members of {name}")
    row.error = error if numeric else math.nan
    if r.not_converged:
        converged, how = False, r.not_converged
    if not converged:
        row.status = "not_converged"
        row.flips = [how]
    elif flips:
        row.status, row.flips = "inconclusive", flips
    elif numeric:
        row.status, why = verdict_with_error(spec, row.value, error)
        if why:
            row.flips = [why]
    if how and numeric and converged and error:
        row.add_note(f"Error estimate {error:.3g} ({how}).")
    for c in by_kind.get("rival", []):
        at = _level_of(info, c[0], spec)
        ref = levels.get(at)[3] if at and at in levels else base_status if not at else None
        outcome = ("unchanged" if not set(spec["reads"]) & set(info[c[0]].get("changed", ()))
                   else
                   # the statement the paper makes has no value under the rival: failed
                   "fails (no such quantity under it)" if c[3] == "no_value" and ref == "pass"
                   else "no value" if c[3] == "no_value" else
                   "passes" if c[3] == "pass" else
                   f"{c[3]}, but the check gives {ref or 'no value'} at that level without it"
                   if ref != "pass" else "fails" if c[3] == "fail" else c[3])
        row.rivals[c[0][len("rival-"):]] = (c[3], c[2], outcome, at)
    if spec["evidence"] == "independent":   # the matrix is whole: a restricted row says so
        row.rivals = {n: row.rivals.get(n, ("", math.nan, NOT_RUN, None))
                      for n in cfg.raw.get("rivals", {})}
    return row


def _counted_passes(rows) -> list[Row]:
    return [r for r in rows if r.spec["evidence"] == "independent" and r.status == "pass"]


def _fails(cell: tuple) -> bool:
    return cell[2].startswith("fails")


def sledgehammers(rows: list[Row]) -> dict[str, int]:
    """{rival: counted passes it fails} of the rivals that fail more than half of their
    paper's counted passes (and at least two): a rival that fails nearly everything tests
    no physics in particular and credits no row by itself."""
    passes = _counted_passes(rows)
    fails = Counter(name for r in passes for name, c in r.rivals.items() if _fails(c))
    return {name: n for name, n in fails.items() if n >= 2 and 2 * n > len(passes)}


def grade_rivals(rows: list[Row]) -> None:
    """The discrimination matrix's verdict on the counted passes: one that no rival other
    than a sledgehammer (:func:`sledgehammers`) fails is ``not_discriminating``
    (reproduced, not counted as evidence for the paper's model)."""
    passes = _counted_passes(rows)
    sledge = sledgehammers(rows)
    for r in passes:
        credit = [n for n, c in r.rivals.items() if _fails(c) and n not in sledge]
        if credit:
            continue
        r.evidence = "not_discriminating"
        by = [n for n, c in r.rivals.items() if _fails(c)]
        why = (f"only the sledgehammer{'s' * (len(by) > 1)} {', '.join(by)} (failing "
               f"{', '.join(str(sledge[n]) for n in by)} of {len(passes)} counted passes) "
               f"fail{'s' * (len(by) == 1)} it" if by else
               "no rival of the paper is declared" if not r.rivals else "no rival fails it")
        r.add_note(f"[not discriminating] reproduced, not counted: {why}.")


def discrimination(cfg, rows: list[Row]) -> list[list]:
    """Rows x rivals, long form (:data:`DISCRIMINATION_COLUMNS`): which physics each verdict
    tests."""
    rivals, sledge = cfg.raw.get("rivals", {}), sledgehammers(rows)
    return [[r.quantity, r.spec["artefact"], r.status, r.evidence, name, rivals[name]["removes"],
             _fmt_short(v), st, outcome, name in sledge,
             r.evidence == "independent" and outcome.startswith("fails") and name not in sledge]
            for r in rows for name, (st, v, outcome, _) in r.rivals.items()]


def _level_of(info: dict, variant: str, spec: dict) -> str | None:
    """The resolution level a variant of the row's reads ran at (config._add_variants),
    None at the baseline's."""
    return next(iter({info[variant].get("level_of", {}).get(n) for n in spec["reads"]}
                     - {None}), None)


def _at_baseline(c: tuple, at: str | None, levels: dict, base: float, spec: dict,
                 numeric: bool) -> tuple:
    """A range end's or family member's check (variant, kind, value, status, label) as the
    baseline ``base`` would give it.  Run at the level ``at`` (config.VARIANT_LEVEL), a
    numeric row's range end moves the baseline by what it moves the value at that level,
    v + (v_end - v_level), and is judged there: the shift is the constants' effect, the
    level's own error cancels in it.  A worded check is its own status at that level, which
    must be the baseline's (as the level's own must); a member the model refuses (no value)
    stays refused."""
    ref = levels.get(at) if at else None
    if (ref is None or not numeric or c[3] == "excluded"
            or not (math.isfinite(c[2]) and math.isfinite(ref[2]))):
        return c
    value = base + (c[2] - ref[2])
    return (c[0], c[1], value, verdict(spec, value),
            f"{c[4]}: the baseline moved by its shift at the {at} level "
            f"({_fmt_short(ref[2])} -> {_fmt_short(c[2])})")


def _skipped_why(cfg, variant: str, spec: dict) -> str:
    """Why a level was not run for a row's reads (the run schema's refusal per read)."""
    return "; ".join(f"{n}: {m}" for n, m in cfg.variant_skipped.get(variant, {}).items()
                     if n in spec["reads"])


def _fmt(x) -> str:
    if isinstance(x, str):
        return x
    x = float(x)
    return "" if math.isnan(x) else repr(x)


def _fmt_short(x) -> str:
    return str(bool(x)).lower() if isinstance(x, bool) else f"{float(x):.6g}"


def write_table(rows: list[Row], path: str | Path) -> Path:
    return write_csv(path, COLUMNS, [r.cells() for r in rows])


def counts(rows) -> dict[str, dict[str, int]]:
    """{evidence: {status: n}} over rows (Row objects or validation.csv dicts)."""
    out: dict[str, Counter] = {e: Counter() for e in EVIDENCE}
    for r in rows:
        ev, st = (r.evidence, r.status) if isinstance(r, Row) else (r["evidence"], r["status"])
        out[ev][st] += 1
    return {e: {s: c[s] for s in STATUSES if c[s]} for e, c in out.items() if c}


def artefact_verdicts(rows) -> dict[str, list[tuple[str, dict]]]:
    """Each figure or table scored by its independent rows (Row objects or validation.csv
    dicts), by their majority: ``agree`` when more than half pass, ``disagree`` when more
    than half fail, else ``not settled``; with its rows' counts by verdict.  One failing
    row among many passes does not make a figure disagree (the rows say which)."""
    by: dict[str, dict[str, int]] = {}
    for r in rows:
        art, ev, st = ((r.spec["artefact"], r.evidence, r.status) if isinstance(r, Row)
                       else (r["artefact"], r["evidence"], r["status"]))
        if ev == "independent" and st != "info":
            n = by.setdefault(art, {})
            n[st] = n.get(st, 0) + 1
    out: dict[str, list] = {"agree": [], "disagree": [], "not settled": []}
    for a, n in sorted(by.items()):
        total = sum(n.values())
        key = ("agree" if 2 * n.get("pass", 0) > total else
               "disagree" if 2 * n.get("fail", 0) > total else "not settled")
        out[key].append((a, n))
    return out


def claim(cfg, rows: list[Row]) -> dict:
    """The replication claim: full / partial / none, from the independent rows only."""
    verdicts = ("pass", "fail", "inconclusive", "not_converged")
    ind = [r for r in rows if r.evidence == "independent" and r.status != "info"]
    by = {s: [r for r in ind if r.status == s] for s in verdicts}
    av = artefact_verdicts(ind)
    agree, disagree, unsettled = ([a for a, _ in av[k]] for k in ("agree", "disagree",
                                                                  "not settled"))
    # an artefact the paper reports but no independent verdict scores (only info rows)
    unscored = sorted({r.spec["artefact"] for r in rows} - {r.spec["artefact"] for r in ind})
    if ind and len(by["pass"]) == len(ind) and not unscored:
        kind = "full"
    elif by["pass"]:
        kind = "partial"
    else:
        kind = "none"
    n = {s: len(v) for s, v in by.items()}
    parts = [f"{n['pass']} of {len(ind)} independent checks pass, {n['fail']} fail, "
             f"{n['inconclusive']} inconclusive, {n['not_converged']} not converged."]
    # rows that name one finding (reported.<q>.finding) share one cause: counted once more
    groups: dict[str, list] = {}
    for r in ind:
        groups.setdefault(r.spec.get("finding", r.quantity), []).append(r)
    findings = {s: sum(1 for g in groups.values() if {r.status for r in g} == {s}) for s in verdicts}
    findings["inconclusive"] += sum(1 for g in groups.values() if len({r.status for r in g}) > 1)
    shared = {k: [r.quantity for r in g] for k, g in groups.items() if len(g) > 1}
    if shared:
        parts.append(f"As findings (rows of one cause counted once: "
                     f"{'; '.join(f'{k} = ' + ' + '.join(v) for k, v in shared.items())}): "
                     f"{findings['pass']} pass, {findings['fail']} fail, "
                     f"{findings['inconclusive']} inconclusive, {findings['not_converged']} not "
                     f"converged.")
    demoted = [r.quantity for r in rows if r.evidence == "not_discriminating"]
    sledge = sledgehammers(rows)
    if agree:
        parts.append(f"Agree (most rows pass): {', '.join(agree)}.")
    if disagree:
        parts.append(f"Disagree (most rows fail): {', '.join(disagree)}.")
    if unsettled:
        parts.append(f"Not settled: {', '.join(unsettled)}.")
    if unscored:
        parts.append(f"Not scored by an independent verdict: {', '.join(unscored)}.")
    if demoted:
        parts.append(f"Reproduced, not discriminating (no rival fails them; not counted): "
                     f"{', '.join(demoted)}.")
    for name, k in sledge.items():
        parts.append(f"Rival {name} ({cfg.raw['rivals'][name]['removes']}) fails {k} of the "
                     f"{len(by['pass']) + len(demoted)} counted passes: a sledgehammer, it "
                     "credits no row by itself.")
    for r in by["fail"]:
        why = r.spec.get("note") or r.note
        parts.append(f"{r.quantity} fails{': ' + why if why else ''}")
    for r in by["inconclusive"]:
        parts.append(f"{r.quantity} is inconclusive ({'; '.join(r.flips)}).")
    for r in by["not_converged"]:
        parts.append(f"{r.quantity} does not converge ({'; '.join(r.flips)}).")
    if cfg.raw.get("claim_note"):
        parts.append(cfg.raw["claim_note"])
    return {"paper": cfg.paper, "claim": kind, "text": " ".join(parts),
            "independent": n, "findings": findings, "counts": counts(rows),
            "agree": agree, "disagree": disagree, "inconclusive": unsettled,
            "unscored": unscored, "not_discriminating": demoted, "sledgehammers": sledge}


def write_evidence(rows: list[Row], path: str | Path) -> Path:
    """Every re-check of every verdict row, long form (:data:`EVIDENCE_COLUMNS`)."""
    return write_csv(path, EVIDENCE_COLUMNS,
                     [[r.quantity, v, kind, _fmt_short(value), status, label]
                      for r in rows for v, kind, value, status, label in r.checks])


def quantities_of(paper: str) -> Quantities:
    from .solve import paper_part

    return paper_part(paper, "validation", "Q")


def for_artefacts(cfg, artefacts):
    """``cfg`` cut down to the rows of ``artefacts`` (:meth:`PaperConfig.for_artefacts`),
    with every row computed together with one of them."""
    return cfg.for_artefacts(artefacts, quantities_of(cfg.paper).groups)


def artefact_table(results_dir, paper: str, artefacts) -> Path:
    """Where the validation rows of some artefacts only are written (beside the paper's
    whole table, never over it)."""
    return Path(results_dir) / paper / "tables" / f"validation-{'+'.join(sorted(artefacts))}.csv"


def validate(paper: str, results_dir: str, config_file: str, profile: str) -> list[Row]:
    """Build and write ``tables/validation.csv`` and ``claim.json`` of one paper."""
    from .config import CACHE_DIR, load_paper

    # as the solver jobs loaded it: from the cache keyed by the content of the config, the
    # schemas and the loader, validated once per content, not again here
    cfg = load_paper(config_file, profile, CACHE_DIR)
    root = Path(results_dir) / paper
    with ResultFiles() as files:   # one opening of each file for the tables below
        rows = build(cfg, quantities_of(paper), results_dir, files)
        write_table(rows, root / "tables" / "validation.csv")
        write_evidence(rows, root / "tables" / "verdict_evidence.csv")
        write_csv(root / "tables" / "discrimination.csv", DISCRIMINATION_COLUMNS,
                  discrimination(cfg, rows))
        write_json(root / "claim.json", claim(cfg, rows))
        write_costs(cfg, results_dir, files)
        from . import costs
        write_csv(root / "tables" / "verification_cost.csv", costs.VERIFICATION_COLUMNS,
                  costs.verification(root, cfg, rows))
    return rows


def check_artefacts(artefacts, results_dir: str | Path, config_dir: str | Path,
                    profile: str, papers, cores: int = 2) -> dict[str, list[Row]]:
    """{paper: rows} of some figures or tables (``fig05`` of every paper that reports one,
    or ``chain_drive-fig05``), without the workflow: each paper cut down to those rows and
    the runs they read (:func:`for_artefacts`), its solve jobs run in this process tree
    (:func:`mechrepro.solve.solve_jobs`), its rows built and written to
    :func:`artefact_table`.  An artefact no paper reports is refused first, with what is
    allowed.  ``pytest -k fig05`` runs this, not a pipeline."""
    from .config import CACHE_DIR, ConfigError, load_paper
    from .solve import solve_jobs

    cfgs = {p: load_paper(Path(config_dir) / "papers" / f"{p}.yaml", profile, CACHE_DIR)
            for p in papers}
    have = {(p, s["artefact"]) for p, cfg in cfgs.items() for s in cfg.reported.values()}
    pick = {a: {(p, x) for p, x in have if a in (x, f"{p}-{x}")} for a in artefacts}
    if not all(pick.values()):
        raise ConfigError(f"artefacts {[a for a, h in pick.items() if not h]}: no reported row "
                          f"of {list(cfgs)} has them; allowed: "
                          f"{sorted({x for _, x in have} | {f'{p}-{x}' for p, x in have})}")
    out = {}
    for paper in sorted({p for h in pick.values() for p, _ in h}):
        arts = sorted({x for h in pick.values() for p, x in h if p == paper})
        cut = for_artefacts(cfgs[paper], arts)
        solve_jobs(cut, config_dir, results_dir, cores)
        out[paper] = build(cut, quantities_of(paper), results_dir)
        write_table(out[paper], artefact_table(results_dir, paper, arts))
    return out


def write_costs(cfg, results_dir: str, files: ResultFiles | None = None) -> None:
    """The framework's other tables of a paper: the long-form cost of accuracy (from its
    ``accuracy:`` block), what each effect costs, and each solver job against its solves."""
    from . import accuracy, costs
    from .solve import paper_part

    if files is None:
        with ResultFiles() as files:
            return write_costs(cfg, results_dir, files)
    root = Path(results_dir) / cfg.paper
    if cfg.raw.get("accuracy"):
        # a paper whose every quantity names its stored variable has none
        quantities = paper_part(cfg.paper, "accuracy", "ACCURACY", required=False)

        def dataset(name):
            kind = "studies" if name in cfg.studies else "runs"
            return files(root / kind / f"{name}.nc")

        write_csv(root / "tables" / "cost_of_accuracy.csv", accuracy.COLUMNS,
                  accuracy.rows(cfg.raw["accuracy"], dataset, quantities))
    write_csv(root / "tables" / "effect_cost.csv", costs.EFFECT_COST_COLUMNS,
              costs.effect_cost([root / "runs" / f"{r}.nc" for r in cfg.runs]))   # variants too
    if cfg.ablations:
        write_csv(root / "tables" / "effect_marginal_cost.csv", costs.MARGINAL_COLUMNS,
                  costs.marginal(root, cfg.ablations))
    from .limits import job_costs

    write_csv(root / "tables" / "job_time.csv", costs.JOB_TIME_COLUMNS, costs.job_time(
        root, cfg.solve_jobs(), {j: c["seconds"] for j, c in job_costs(cfg).items()}))
    if targets := accuracy.target_rows(cfg, root):
        write_csv(root / "tables" / "accuracy_targets.csv", accuracy.TARGET_COLUMNS, targets)


def read_table(path: str | Path) -> list[dict]:
    """Rows of a validation.csv (or any result table) as dicts, with a readable error."""
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def write_csv(path: str | Path, header: list[str], rows: list[list] | list[dict]) -> Path:
    """Any other table of a paper (Table 1, Table II ...), same atomic writer; a row is a
    list of cells or a dict holding the header's keys."""
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(header)
    w.writerows([_fmt(x) if isinstance(x, float) else x
                 for x in ([r[c] for c in header] if isinstance(r, dict) else r)] for r in rows)
    write_text(path, buf.getvalue())
    return Path(path)
