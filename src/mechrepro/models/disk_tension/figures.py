"""What the figures of disk_tension draw, taken from the runs in SI (the notebook only draws
and converts units)."""
from __future__ import annotations

import numpy as np

from mechrepro.units import from_si


def by_clamp(R, scene, study) -> list:
    """[(r_f [mm], dataset)] of ``scene`` and of the runs of its r_f ``study``."""
    return [(clamp_mm(ds), ds) for ds in [R.run(scene), *R.study_runs(study)]]


def rc_grid(R) -> dict:
    """{r_f [mm]: dataset} of Figs. 6 and 8: scene ``rc_grid`` and study ``fig06``."""
    return {int(round(rf)): ds for rf, ds in by_clamp(R, "rc_grid", "fig06")}


def paper_points(R) -> dict:
    """The paper's own numbers drawn on Figs. 6 and 8 (Sec. 4.3) and the 2-D model's accuracy
    goal, from the validation table."""
    rows = {r["quantity"]: r for r in R.validation()}
    paper = lambda q: float(rows[q]["paper_value"])  # noqa: E731
    return {"r_c": 0.065,
            "f_unrolled": float(rows["f_unrolled_nd4_rf25"]["reproduced_value"]),
            "f_rolled": paper("f_rolled_nd4_rc65_rf25"),
            "delta_f_eq9": paper("delta_f_eq9_nd4_rc65_rf25"),
            "delta_f_eigen": paper("delta_f_eigen_nd4_rc65_rf25"),
            "plate2d_goal": paper("plate2d_unrolled_vs_exact")}


def eigen_and_eq9_times(*runs) -> tuple[float, float]:
    """Wall time [s] of Eq. (5) and of Eq. (9) over ``runs`` (the same K^(sigma))."""
    return tuple(sum(float(ds[k]) for ds in runs) for k in ("time_eigen", "time_eq9"))


def buckling_series(R):
    """The hard case (r_c = 105 mm): amplitudes A [K] ascending, omega~^2 of each (A, N_d),
    and each N_d's critical amplitude A lambda_cr (omega~^2 is linear in A, Eq. 3)."""
    runs = [R.run("buckling"), *R.study_runs("buckling_sweep")]
    amps = np.array([float(ds["amplitude_used"]) for ds in runs])
    w2 = np.array([ds["omega2_rolled"].isel(r_c=0).values for ds in runs])
    order = np.argsort(amps)
    a_cr = amps[0] * runs[0]["critical_load_factor"].isel(r_c=0).values
    return amps[order], w2[order], a_cr


def matrix_rows(da) -> list[list]:
    """Rows ``[N_d, entries...]`` of a modal matrix (Tables 1-2)."""
    return [[int(n)] + [float(v) for v in da.sel(row=n).values] for n in da["row"].values]


def effect_cold_warm(R, scenes=("table12", "table12_plate2d", "stressed_axisym",
                                "stressed_plate2d")) -> list[list]:
    """Rows [scene, effect, warm s, cold s] of the memoised effects."""
    return [[scene, str(e), float(ds["effect_time"].values[i]), float(ds[f"{e}_time_cold"])]
            for scene, ds in ((s, R.run(s)) for s in scenes)
            for i, e in enumerate(ds["timed_effect"].values) if f"{e}_time_cold" in ds]


def clamp_mm(ds) -> float:
    """r_f [mm] of a run."""
    return float(from_si(float(ds["clamp_radius"]), "mm"))
