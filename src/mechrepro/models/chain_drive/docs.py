"""The blocks of docs/chain_drive.md (numbers from a run, not typed), made from
``results/chain_drive`` (claim.json, validation.csv, discrete_peaks.csv,
cost_of_accuracy.csv) and filled by :mod:`mechrepro.docs`::

    .venv/bin/python -m mechrepro.docs docs/chain_drive.md results

Run it on the default profile's results after the last change;
tests/test_chain_drive_docs.py checks the verdict table against the committed default
reference.
"""
from __future__ import annotations

import json
from pathlib import Path

from mechrepro.docs import number, table_rows

_rows = table_rows


def _g(x, digits: int = 4) -> str:
    """:func:`mechrepro.docs.number`, with an infinite error bar printed as such (levels that
    do not contract give none)."""
    try:
        if abs(float(x)) == float("inf"):
            return "∞"
    except (TypeError, ValueError):
        pass
    return number(x, digits)


def counts(root: Path) -> str:
    c = json.loads((root / "claim.json").read_text())
    ind = c["counts"]["independent"]
    nd = c["counts"].get("not_discriminating", {})
    return (f"Claim **{c['claim']}**. Independent: **{ind.get('pass', 0)} pass, "
            f"{ind.get('fail', 0)} fail, {ind.get('inconclusive', 0)} inconclusive, "
            f"{ind.get('not_converged', 0)} not converged**; reproduced, not discriminating: "
            f"{nd.get('pass', 0)} pass.")


def verdicts(root: Path) -> str:
    """Every counted or demoted verdict row (not info, construction or target), with its
    value, error bar, rivals and what the run says about it."""
    out = ["| row | figure | ours | ± error | verdict | evidence | rivals | note |",
           "|---|---|---|---|---|---|---|---|"]
    for r in _rows(root / "tables" / "validation.csv"):
        if r["evidence"] in ("independent", "not_discriminating") and r["status"] != "info":
            note = r["note"].replace("|", "/")
            note = note if len(note) <= 240 else note[:237] + "..."
            out.append(f"| `{r['quantity']}` | {r['artefact']} | {_g(r['reproduced_value'], 5)} | "
                       f"{_g(r['error_estimate'], 2)} | {r['status']} | {r['evidence']} | "
                       f"{r['rivals'] or '—'} | {note} |")
    return "\n".join(out)


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
    rows = [r for r in _rows(root / "tables" / "cost_of_accuracy.csv")
            if r["accuracy"].startswith("string_vs_discrete")]
    out = ["| entry | quantity | scheme | points per pitch | error | string time [s] |",
           "|---|---|---|---|---|---|"]
    for r in rows:
        out.append(f"| {r['accuracy']} | {r['quantity']} | {r['line'] or '—'} | "
                   f"{r['knob_value']} | {float(r['error']):.3g} | {float(r['time_s']):.2g} |")
    return "\n".join(out)


BLOCKS = {"counts": counts, "verdicts": verdicts, "discrete_peaks": discrete_peaks,
          "string_vs_discrete": string_vs_discrete}
