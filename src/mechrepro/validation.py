"""The one validation builder: what the paper reports (config) against what we reproduce.

What a paper reports is data: the ``reported:`` block of ``config/papers/<paper>.yaml``
(value typed once, unit, source, tolerance and why, evidence class, what it reads and
which assumed constants it depends on).  ``models/<paper>/validation.py`` only registers
functions that extract the reproduced values (:class:`Quantities`).  :func:`build` then

1. evaluates every quantity on the baseline runs;
2. re-evaluates every verdict row on its variant runs (next finer resolution, both ends
   of the range of each assumed constant it depends on), and makes a verdict that flips
   ``inconclusive``, saying what flips it;
3. returns the rows; :func:`write_table` writes ``validation.csv`` and :func:`claim`
   the replication claim, which counts only ``independent`` rows.

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

from .io import write_json, write_text
from .registry import Registry

COLUMNS = ["quantity", "source", "paper_value", "reproduced_value", "unit", "rel_error",
           "tolerance", "status", "evidence", "note", "artefact", "criterion"]
EVIDENCE = ("independent", "calibration", "determined", "construction", "target")
STATUSES = ("pass", "fail", "inconclusive", "info")
OPS = {">": operator.gt, ">=": operator.ge, "<": operator.lt, "<=": operator.le}


class ValidationError(RuntimeError):
    """A quantity cannot be extracted as declared (the message names it)."""


@dataclass
class Reproduced:
    """A reproduced value with a note computed from the runs (e.g. the exact value).

    ``flips`` names re-checks the extraction did itself that change the verdict (a joint
    corner of several assumed constants, which the one-at-a-time variants do not reach);
    a pass or fail with flips is ``inconclusive``.
    """
    value: float | bool
    note: str = ""
    flips: list[str] = field(default_factory=list)


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
            self._open[path] = xr.open_dataset(path, engine="netcdf4")
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
        if self.variant and self.variant.rsplit("-", 1)[0] == name:
            value = spec["range"][0 if self.variant.endswith("-lo") else 1]
        return to_si(value, spec["unit"])[0]


@dataclass
class Row:
    quantity: str
    spec: dict
    value: float
    note: str = ""
    status: str = "info"
    flips: list[str] = field(default_factory=list)

    @property
    def kind(self) -> str:
        return self.spec["kind"]

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
            notes.insert(0, "INCONCLUSIVE: " + "; ".join(self.flips))
        if self.spec.get("evidence_why"):
            notes.append(f"[{self.spec['evidence']}] {self.spec['evidence_why']}")
        return [self.quantity, self.spec["source"], _fmt(self.paper_value), _fmt(self.value),
                self.unit, _fmt(self.rel_error), _fmt(tol), self.status, self.spec["evidence"],
                " ".join(notes), self.spec["artefact"], self.criterion]


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
        return "pass" if bool(value) else "fail"
    x = float(value)
    if math.isnan(x):
        return "fail"
    if kind == "bound":
        return "pass" if OPS[spec["op"]](x, float(spec["value"])) else "fail"
    return "pass" if abs(rel_error(spec["value"], x)) <= float(spec["tolerance"]) else "fail"


def _describe_variant(cfg, variant: str) -> str:
    if variant == "finer":
        return f"at the next finer resolution (refine {cfg.raw.get('refine', {})})"
    p, end = variant.rsplit("-", 1)
    spec = cfg.raw["parameters"][p]
    v = spec["range"][0 if end == "lo" else 1]
    unit = f" {spec['unit']}" if isinstance(v, (int, float)) and spec["unit"] != "1" else ""
    return f"at {p} = {v}{unit} (range {end})"


def build(cfg, quantities: Quantities, results_dir: str | Path,
          files: ResultFiles | None = None) -> list[Row]:
    """Evaluate every reported quantity and its robust verdict (see module docstring).
    ``files``: the job's open result files (default: opened here, closed on return)."""
    if files is None:
        with ResultFiles() as files:
            return build(cfg, quantities, results_dir, files)
    from .config import _variant_names

    reported = cfg.reported
    missing = sorted(set(reported) - set(quantities.names))
    extra = sorted(set(quantities.names) - set(reported))
    if missing or extra:
        raise ValidationError(f"{cfg.paper}: reported quantities without an extraction function: "
                              f"{missing}; functions for quantities not reported: {extra}")
    base = quantities.evaluate(list(reported), ValidationInputs(cfg, results_dir, files=files))
    rows = []
    for q, spec in reported.items():
        r = base[q]
        value = float(r.value) if not isinstance(r.value, bool) else float(r.value)
        row = Row(q, spec, value, r.note, verdict(spec, r.value))
        if row.status in ("pass", "fail"):
            row.flips += list(r.flips)
        rows.append(row)
    by_variant: dict[str, list[str]] = {}
    for q, spec in reported.items():
        for v in _variant_names(spec):
            by_variant.setdefault(v, []).append(q)
    index = {row.quantity: row for row in rows}
    for variant, qs in by_variant.items():
        got = quantities.evaluate(qs, ValidationInputs(cfg, results_dir, variant, files))
        for q in qs:
            row, s = index[q], verdict(reported[q], got[q].value)
            if s != row.status:
                row.flips.append(f"{s} {_describe_variant(cfg, variant)}: "
                                 f"{_fmt_short(got[q].value)}")
    for row in rows:
        if row.flips:
            row.status = "inconclusive"
    return rows


def _fmt(x) -> str:
    if isinstance(x, str):
        return x
    x = float(x)
    return "" if math.isnan(x) else repr(x)


def _fmt_short(x) -> str:
    return str(bool(x)).lower() if isinstance(x, bool) else f"{float(x):.6g}"


def table_text(rows: list[Row]) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(COLUMNS)
    for r in rows:
        w.writerow(r.cells())
    return buf.getvalue()


def write_table(rows: list[Row], path: str | Path) -> Path:
    write_text(path, table_text(rows))
    return Path(path)


def counts(rows) -> dict[str, dict[str, int]]:
    """{evidence: {status: n}} over rows (Row objects or validation.csv dicts)."""
    out: dict[str, Counter] = {e: Counter() for e in EVIDENCE}
    for r in rows:
        ev, st = (r.spec["evidence"], r.status) if isinstance(r, Row) else (r["evidence"], r["status"])
        out[ev][st] += 1
    return {e: {s: c[s] for s in STATUSES if c[s]} for e, c in out.items() if c}


def claim(cfg, rows: list[Row]) -> dict:
    """The replication claim: full / partial / none, from the independent rows only."""
    ind = [r for r in rows if r.spec["evidence"] == "independent" and r.status != "info"]
    by = {s: [r for r in ind if r.status == s] for s in ("pass", "fail", "inconclusive")}
    arts = {}
    for r in ind:
        arts.setdefault(r.spec["artefact"], set()).add(r.status)
    agree = sorted(a for a, s in arts.items() if s == {"pass"})
    disagree = sorted(a for a, s in arts.items() if "fail" in s)
    unsettled = sorted(a for a, s in arts.items() if "fail" not in s and "inconclusive" in s)
    # an artefact the paper reports but no independent verdict scores (only info rows)
    unscored = sorted({r.spec["artefact"] for r in rows} - set(arts))
    if ind and len(by["pass"]) == len(ind) and not unscored:
        kind = "full"
    elif by["pass"]:
        kind = "partial"
    else:
        kind = "none"
    n = {s: len(v) for s, v in by.items()}
    parts = [f"{n['pass']} of {len(ind)} independent checks pass, {n['fail']} fail, "
             f"{n['inconclusive']} inconclusive."]
    if agree:
        parts.append(f"Agree: {', '.join(agree)}.")
    if disagree:
        parts.append(f"Disagree: {', '.join(disagree)}.")
    if unsettled:
        parts.append(f"Not settled: {', '.join(unsettled)}.")
    if unscored:
        parts.append(f"Not scored by an independent verdict: {', '.join(unscored)}.")
    for r in by["fail"]:
        why = r.spec.get("note") or r.note
        parts.append(f"{r.quantity} fails{': ' + why if why else ''}")
    for r in by["inconclusive"]:
        parts.append(f"{r.quantity} is inconclusive ({'; '.join(r.flips)}).")
    if cfg.raw.get("claim_note"):
        parts.append(cfg.raw["claim_note"])
    return {"paper": cfg.paper, "claim": kind, "text": " ".join(parts),
            "independent": n, "counts": counts(rows),
            "agree": agree, "disagree": disagree, "inconclusive": unsettled,
            "unscored": unscored}


def validate(paper: str, results_dir: str, config_file: str, profile: str) -> list[Row]:
    """Build and write ``tables/validation.csv`` and ``claim.json`` of one paper."""
    import importlib

    from .config import CACHE_DIR, load_paper

    # as the solver jobs loaded it: from the cache keyed by the content of the config, the
    # schemas and the loader, validated once per content, not again here
    cfg = load_paper(config_file, profile, CACHE_DIR)
    module = importlib.import_module(f"mechrepro.models.{paper}.validation")
    root = Path(results_dir) / paper
    with ResultFiles() as files:   # one opening of each file for the tables below
        rows = build(cfg, module.Q, results_dir, files)
        write_table(rows, root / "tables" / "validation.csv")
        write_json(root / "claim.json", claim(cfg, rows))
        write_costs(cfg, results_dir, files)
    return rows


def write_costs(cfg, results_dir: str, files: ResultFiles | None = None) -> None:
    """The framework's other tables of a paper: the long-form cost of accuracy (from its
    ``accuracy:`` block), what each effect costs, and each solver job against its solves."""
    import importlib

    from . import accuracy, costs

    if files is None:
        with ResultFiles() as files:
            return write_costs(cfg, results_dir, files)
    root = Path(results_dir) / cfg.paper
    if cfg.raw.get("accuracy"):
        module = importlib.import_module(f"mechrepro.models.{cfg.paper}.accuracy")

        def dataset(name):
            kind = "studies" if name in cfg.studies else "runs"
            return files(root / kind / f"{name}.nc")

        table = accuracy.rows(cfg.raw["accuracy"], dataset, module.ACCURACY)
        write_csv(root / "tables" / "cost_of_accuracy.csv", accuracy.COLUMNS,
                  [[r[c] for c in accuracy.COLUMNS] for r in table])
    ec = costs.effect_cost([root / "runs" / f"{r}.nc" for r in cfg.runs])   # variants too
    write_csv(root / "tables" / "effect_cost.csv", costs.EFFECT_COST_COLUMNS,
              [[r[c] for c in costs.EFFECT_COST_COLUMNS] for r in ec])
    jt = costs.job_time(root, cfg.solve_jobs())
    write_csv(root / "tables" / "job_time.csv", costs.JOB_TIME_COLUMNS,
              [[r[c] for c in costs.JOB_TIME_COLUMNS] for r in jt])


def read_table(path: str | Path) -> list[dict]:
    """Rows of a validation.csv (or any result table) as dicts, with a readable error."""
    path = Path(path)
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return rows


def write_csv(path: str | Path, header: list[str], rows: list[list]) -> Path:
    """Any other table of a paper (Table 1, Table II ...), same atomic writer."""
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(header)
    for r in rows:
        w.writerow([_fmt(x) if isinstance(x, float) else x for x in r])
    write_text(path, buf.getvalue())
    return Path(path)
