"""The generated blocks of docs/rolling_shear.md, from ``results/rolling_shear``
(``python -m mechrepro.docs docs/rolling_shear.md results`` on the default results)."""
from __future__ import annotations

import json
from pathlib import Path

# one formatter for every paper page
from mechrepro.docs import number as _g, table_rows as _rows


def _cell(text: str) -> str:
    return " ".join(str(text).split()).replace("|", "/")


def counts(root: Path) -> str:
    c = json.loads((root / "claim.json").read_text())
    ind = c["independent"]
    return (f"Claim **{c['claim']}**. Independent: **{ind['pass']} pass, {ind['fail']} fail, "
            f"{ind['inconclusive']} inconclusive, {ind['not_converged']} not converged**.")


def verdicts(root: Path) -> str:
    """Every row with a verdict (not info), with its error bar and what flips it."""
    out = ["| row | source | paper | ours | ± error | verdict | evidence |",
           "|---|---|---|---|---|---|---|"]
    for r in _rows(root / "tables" / "validation.csv"):
        if r["status"] != "info":
            out.append(f"| `{r['quantity']}` | {_cell(r['source'])} | {_g(r['paper_value'])} | "
                       f"{_g(r['reproduced_value'], 5)} {r['unit']} | {_g(r['error_estimate'], 2)} | "
                       f"{r['status']} | {r['evidence']} |")
    return "\n".join(out)


def info(root: Path) -> str:
    """The info rows: what the run measures beside the verdicts."""
    out = ["| row | source | value | evidence |", "|---|---|---|---|"]
    for r in _rows(root / "tables" / "validation.csv"):
        if r["status"] == "info":
            out.append(f"| `{r['quantity']}` | {_cell(r['source'])} | {_g(r['reproduced_value'], 5)} "
                       f"{r['unit']} | {r['evidence']} |")
    return "\n".join(out)


def notes(root: Path, quantities) -> str:
    rows = {r["quantity"]: r for r in _rows(root / "tables" / "validation.csv")}
    return "\n".join(f"- `{q}`: {_cell(rows[q]['note'])}" for q in quantities if q in rows)


def design_front(root: Path) -> str:
    rows = _rows(root / "tables" / "design_front.csv")
    head = list(rows[0])
    out = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for r in rows:
        out.append("| " + " | ".join(_g(r[k], 4) for k in head) + " |")
    return "\n".join(out)


def solvers(root: Path) -> str:
    rows = _rows(root / "tables" / "solver_comparison.csv")
    head = ["method", "success_rate", "right_branch_rate", "time_per_loops_solve_s"]
    out = ["| method | converged | on the design branch | time per Eq. (9) solve [s] |",
           "|---|---|---|---|"]
    for r in rows:
        out.append("| " + " | ".join(_g(r[k], 3) for k in head) + " |")
    return "\n".join(out)


def branch(root: Path) -> str:
    """The branch benchmark: success against the initial spread, over seeds."""
    import numpy as np
    import xarray as xr

    with xr.open_dataset(root / "studies" / "branch_spread.nc") as ds:
        sig = ds["pso_init_scale"].values
        rates = ds["selpso_branch_rate_seeds"].values
        n_cut, n_seed = ds.sizes["cut"], rates.shape[1]
    out = [f"| σ [rad] | median | mean | min … max over {n_seed} seeds ({n_cut} cut points) |",
           "|---|---|---|---|"]
    for s, r in zip(sig, rates):
        out.append(f"| {s:g} | {np.median(r):.3f} | {r.mean():.3f} | {r.min():.3f} … {r.max():.3f} |")
    return "\n".join(out)


BLOCKS = {
    "counts": counts,
    "verdicts": verdicts,
    "info": info,
    "design_front": design_front,
    "design_notes": lambda root: notes(root, ["design_recommended_h", "design_lowest_buildable_h",
                                              "design_table2_buildable"]),
    "solvers": solvers,
    "solver_notes": lambda root: notes(root, ["speedup_like_for_like", "selpso_branch_success_rate",
                                              "selpso_converges_from_each_initial_value"]),
    "table2_notes": lambda root: notes(root, ["horizontal_displacement_reduction",
                                              "paper_levers_assemble",
                                              "table2_reduction_family_frozen_min",
                                              "table2_reduction_family_rederived_min"]),
    "branch": branch,
}
