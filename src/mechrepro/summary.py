"""The cross-paper summary: cost-of-accuracy curves side by side, and one table.

Each paper's notebook stores ``results/<paper>/tables/cost_of_accuracy.nc`` (written with
:func:`mechrepro.accuracy.cost_of_accuracy`); its first ``error_*`` variable is the
paper's headline error.  The table adds what each paper's config says about the
resolution its default profile uses and why (``default_resolution:``).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from .config import load_paper
from .io import open_dataset
from .validation import write_csv


def primary_error(ds) -> str:
    return [v for v in ds.data_vars if v.startswith("error_")][0]


def rows(results: Path, config_dir: Path, papers: list[str], profile: str) -> list[dict]:
    out = []
    for paper in papers:
        ds = open_dataset(results / paper / "tables" / "cost_of_accuracy.nc")
        err = primary_error(ds)
        default = load_paper(config_dir / "papers" / f"{paper}.yaml").raw.get("default_resolution", {})
        out.append({
            "paper": paper, "knob": ds.attrs["knob"], "reference": ds.attrs["reference"],
            "error_quantity": err.removeprefix("error_"),
            "knob_range": f"{ds['resolution'].values.min()}..{ds['resolution'].values.max()}",
            "best_error": float(np.nanmin(ds[err].values)),
            "wall_time_range_s": f"{ds['wall_time'].values.min():.3g}..{ds['wall_time'].values.max():.3g}",
            "default_resolution": default.get("value", ""), "why": default.get("why", ""),
        })
    return out


def write_summary(png: str, csv: str, results: str, config_dir: str, papers: list[str],
                  profile: str) -> None:
    from .plotting import plt, savefig

    results, config_dir = Path(results), Path(config_dir)
    table = rows(results, config_dir, papers, profile)
    write_csv(csv, list(table[0]), [list(r.values()) for r in table])
    fig, ax = plt.subplots(figsize=(7.5, 5))
    for paper in papers:
        ds = open_dataset(results / paper / "tables" / "cost_of_accuracy.nc")
        err = primary_error(ds)
        ax.loglog(ds["wall_time"].values, ds[err].values, "o-",
                  label=f"{paper}: {err.removeprefix('error_')} vs {ds.attrs['reference']} "
                        f"(knob {ds.attrs['knob']})")
    ax.set_xlabel("wall time per solve [s]")
    ax.set_ylabel("relative error")
    ax.set_title("cost of accuracy, all papers")
    ax.legend(fontsize=7)
    savefig(fig, png)
