"""The one validation-table writer.

``results/<paper>/tables/validation.csv`` has exactly the columns
``quantity,source,paper_value,reproduced_value,unit,rel_error,tolerance,status``.
Status is computed here, never typed in: ``pass`` when |rel_error| <= tolerance,
``fail`` otherwise, ``info`` when the paper gives no number (or for a calibration
target, which cannot validate anything).  A trend the paper states in words becomes a
:func:`check` row: paper_value 1 (the claim), reproduced_value 1 or 0.
Each row may carry a ``note`` (why it fails, which K it depends on ...); notes go to
``validation_notes.csv`` beside the table.
"""
from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass
from pathlib import Path

from .io import write_text

COLUMNS = ["quantity", "source", "paper_value", "reproduced_value", "unit",
           "rel_error", "tolerance", "status"]


@dataclass
class Row:
    quantity: str
    source: str
    paper_value: float
    reproduced_value: float
    unit: str
    tolerance: float = math.nan
    note: str = ""
    info: bool = False

    @property
    def rel_error(self) -> float:
        p, r = float(self.paper_value), float(self.reproduced_value)
        if math.isnan(p) or math.isnan(r):
            return math.nan
        if p == 0.0:
            return abs(r - p)
        return (r - p) / abs(p)

    @property
    def status(self) -> str:
        if self.info or math.isnan(self.tolerance) or math.isnan(float(self.paper_value)):
            return "info"
        err = self.rel_error
        return "pass" if (not math.isnan(err) and abs(err) <= self.tolerance) else "fail"


def compare(quantity, source, paper_value, reproduced_value, unit, tolerance, note="") -> Row:
    """A paper number against ours, with a relative tolerance."""
    return Row(quantity, source, float(paper_value), float(reproduced_value), unit,
               float(tolerance), note)


def check(quantity, source, holds: bool, note="") -> Row:
    """A claim the paper states in words, computed as true/false."""
    return Row(quantity, source, 1.0, 1.0 if bool(holds) else 0.0, "bool", 0.0, note)


def info(quantity, source, reproduced_value, unit, paper_value=math.nan, note="") -> Row:
    """A number reported for information (no paper number, or a calibration target)."""
    return Row(quantity, source, float(paper_value), float(reproduced_value), unit,
               math.nan, note, info=True)


def _fmt(x) -> str:
    if isinstance(x, str):
        return x
    x = float(x)
    return "" if math.isnan(x) else repr(x)


def table_text(rows: list[Row]) -> str:
    names = [r.quantity for r in rows]
    dup = {n for n in names if names.count(n) > 1}
    if dup:
        raise ValueError(f"duplicate validation quantities: {sorted(dup)}")
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(COLUMNS)
    for r in rows:
        w.writerow([r.quantity, r.source, _fmt(r.paper_value), _fmt(r.reproduced_value),
                    r.unit, _fmt(r.rel_error), _fmt(r.tolerance), r.status])
    return buf.getvalue()


def write_table(rows: list[Row], path: str | Path) -> Path:
    """Write validation.csv and validation_notes.csv (atomically)."""
    path = Path(path)
    write_text(path, table_text(rows))
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["quantity", "note"])
    for r in rows:
        w.writerow([r.quantity, r.note])
    write_text(path.with_name(path.stem + "_notes.csv"), buf.getvalue())
    return path


def read_table(path: str | Path) -> list[dict]:
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def write_csv(path: str | Path, header: list[str], rows: list[list]) -> Path:
    """Any other table of a paper (Table 1, Table II ...), same atomic writer."""
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(header)
    for r in rows:
        w.writerow([_fmt(x) if isinstance(x, float) else x for x in r])
    write_text(path, buf.getvalue())
    return Path(path)
