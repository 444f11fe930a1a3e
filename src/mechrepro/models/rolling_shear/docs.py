"""The generated blocks of docs/rolling_shear.md, from ``results/rolling_shear``
(``python -m mechrepro.docs docs/rolling_shear.md results`` on the default results)."""
from __future__ import annotations

from pathlib import Path

# one formatter for every paper page
from mechrepro.docs import number as _g, table_rows as _rows


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


BLOCKS = {"design_front": design_front, "solvers": solvers, "branch": branch}
