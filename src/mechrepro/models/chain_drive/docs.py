"""The blocks of docs/chain_drive.md (numbers from a run, not typed), made from
``results/chain_drive`` (discrete_peaks.csv, cost_of_accuracy.csv; the counts and the verdict
table are the framework's blocks) and filled by :mod:`mechrepro.docs`::

    .venv/bin/python -m mechrepro.docs docs/chain_drive.md results

Run it on the default profile's results after the last change; tests/test_docs.py checks
the page's blocks against the committed default reference.
"""
from __future__ import annotations

from pathlib import Path

from mechrepro.docs import number as _g
from mechrepro.docs import markdown, table_rows as _rows


def discrete_peaks(root: Path) -> str:
    """Table discrete_peaks: per run and order, the peak speed and amplitude of the
    discrete-link span at @coarsest / @coarser / base / @finer, the baseline's error from
    both sides and the observed orders."""
    out = ["| run | order | quantity | coarsest / coarser / base / finer | ± error | "
           "observed order below / above |", "|---|---|---|---|---|---|"]
    for r in _rows(root / "tables" / "discrete_peaks.csv"):
        lv = " / ".join(_g(r[k], 6) for k in ("coarsest", "coarser", "base", "finer"))
        out.append(f"| {r['run']} | {r['order']} | {r['quantity']} [{r['unit']}] | {lv} | "
                   f"{_g(r['error'], 2)} | {_g(r['observed_order_below'], 2)} / "
                   f"{_g(r['observed_order_above'], 2)} |")
    return "\n".join(out)


def string_vs_discrete(root: Path) -> str:
    """The cost-of-accuracy entries that measure the string against the discrete span:
    per scheme (line) and points per pitch, the error and the string's own time."""
    return markdown(["entry", "quantity", "scheme", "points per pitch", "error", "string time [s]"],
                    [[r["accuracy"], r["quantity"], r["line"] or "—", r["knob_value"],
                      f"{float(r['error']):.3g}", f"{float(r['time_s']):.2g}"]
                     for r in _rows(root / "tables" / "cost_of_accuracy.csv")
                     if r["accuracy"].startswith("string_vs_discrete")])


BLOCKS = {"discrete_peaks": discrete_peaks, "string_vs_discrete": string_vs_discrete}
