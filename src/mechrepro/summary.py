"""The cross-paper summary: cost-of-accuracy curves side by side, and one table.

Each paper's ``results/<paper>/tables/cost_of_accuracy.csv`` is the long-form table of
:mod:`mechrepro.accuracy`; its first entry's first quantity is the paper's headline curve.
The table adds what each paper's config says about the resolution its default profile
uses and why (``default_resolution:``).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from .config import CACHE_DIR, load_paper
from .validation import read_table, write_csv


def headline(results: Path, paper: str) -> list[dict]:
    """The rows of the paper's headline curve (first entry, first quantity, first line)."""
    table = read_table(results / paper / "tables" / "cost_of_accuracy.csv")
    key = ("accuracy", "quantity", "line")
    return [r for r in table if all(r.get(k, "") == table[0].get(k, "") for k in key)]


COLUMNS = ["paper", "knob", "reference", "error_quantity", "knob_range", "best_error",
           "wall_time_range_s", "default_resolution", "why"]


def _raw(config_dir: Path, paper: str) -> dict:
    return load_paper(config_dir / "papers" / f"{paper}.yaml", cache_dir=CACHE_DIR).raw


def with_accuracy(config_dir: Path, papers: list[str]) -> list[str]:
    """The papers that declare a cost-of-accuracy study (``accuracy:``; it is optional)."""
    return [p for p in papers if _raw(config_dir, p).get("accuracy")]


def rows(results: Path, config_dir: Path, papers: list[str], profile: str) -> list[dict]:
    out = []
    for paper in with_accuracy(config_dir, papers):
        h = headline(results, paper)
        err = np.array([float(r["error"]) for r in h])
        t = np.array([float(r["time_s"]) for r in h])
        default = _raw(config_dir, paper).get("default_resolution", {})
        out.append({
            "paper": paper, "knob": h[0]["knob"], "reference": h[0]["reference"],
            "error_quantity": f"{h[0]['quantity']} ({h[0]['error_kind']})",
            "knob_range": f"{h[0]['knob_value']}..{h[-1]['knob_value']}",
            "best_error": float(np.nanmin(err)),
            "wall_time_range_s": f"{t.min():.3g}..{t.max():.3g}",
            "default_resolution": default.get("value", ""), "why": default.get("why", ""),
        })
    return out


def write_summary(png: str, csv: str, results: str, config_dir: str, papers: list[str],
                  profile: str) -> None:
    from .plotting import plt, savefig

    results, config_dir = Path(results), Path(config_dir)
    write_csv(csv, COLUMNS, rows(results, config_dir, papers, profile))
    fig, ax = plt.subplots(figsize=(7.5, 5))
    for paper in with_accuracy(config_dir, papers):
        h = headline(results, paper)
        ax.loglog([float(r["time_s"]) for r in h], [float(r["error"]) for r in h], "o-",
                  label=f"{paper}: {h[0]['quantity']}{' ' + h[0]['line'] if h[0].get('line') else ''}"
                        f" vs {h[0]['reference']} "
                        f"[{h[0].get('error_unit') or '1'}] (knob {h[0]['knob']})")
    ax.set_xlabel("wall time per solve [s]")
    # the headline quantities differ in kind: each curve's unit is in its label
    ax.set_ylabel("error of the headline quantity [its unit, in the legend]")
    ax.set_title("cost of accuracy, all papers")
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14))   # clear of the data
    savefig(fig, png)
