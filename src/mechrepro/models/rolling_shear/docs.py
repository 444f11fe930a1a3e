"""The generated blocks of docs/rolling_shear.md, from ``results/rolling_shear``
(``python -m mechrepro.docs docs/rolling_shear.md results`` on the default results)."""
from __future__ import annotations

from pathlib import Path

# one formatter for every paper page
from mechrepro.docs import markdown, number as _g, table_rows as _rows


def design_front(root: Path) -> str:
    rows = _rows(root / "tables" / "design_front.csv")
    head = list(rows[0])
    return markdown(head, [[_g(r[k], 4) for k in head] for r in rows])


def solvers(root: Path) -> str:
    rows = _rows(root / "tables" / "solver_comparison.csv")
    head = ["method", "success_rate", "right_branch_rate", "time_per_loops_solve_s"]
    return markdown(["method", "converged", "on the design branch", "time per Eq. (9) solve [s]"],
                    [[_g(r[k], 3) for k in head] for r in rows])


def branch(root: Path) -> str:
    """The branch benchmark: success against the initial spread, over seeds."""
    import numpy as np
    import xarray as xr

    with xr.open_dataset(root / "studies" / "branch_spread.nc") as ds:
        sig = ds["pso_init_scale"].values
        rates = ds["selpso_branch_rate_seeds"].values
        n_cut, n_seed = ds.sizes["cut"], rates.shape[1]
    head = ["σ [rad]", "median", "mean", f"min … max over {n_seed} seeds ({n_cut} cut points)"]
    return markdown(head, [[f"{s:g}", f"{np.median(r):.3f}", f"{r.mean():.3f}",
                            f"{r.min():.3f} … {r.max():.3f}"] for s, r in zip(sig, rates)])


BLOCKS = {"design_front": design_front, "solvers": solvers, "branch": branch}
