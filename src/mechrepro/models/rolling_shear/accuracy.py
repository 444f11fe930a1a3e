"""The error functions of rolling_shear's cost-of-accuracy quantities, one error per run."""
from __future__ import annotations

import numpy as np

from mechrepro.accuracy import AccuracyQuantities, against_finest, finest_index

from .motion_laws import LAW_GRID, pose_error

ACCURACY = AccuracyQuantities("rolling_shear")


def _relative(values, reference):
    values, reference = np.asarray(values, float), np.asarray(reference, float)
    return np.abs(values - reference) / np.abs(reference)


@ACCURACY.register("newton_motion_laws")
def newton_motion_laws(ds, entry):
    """max over the cut and the six angles of |theta_Newton - theta_closed form| (rad)."""
    err = [pose_error(ds[f"newton_theta{k}"].values, ds[f"exact_theta{k}"].values)
           for k in range(1, 7)]
    return np.max(np.stack(err), axis=(0, 2))


@ACCURACY.register("newton_objective_h")
def newton_objective_h(ds, entry):
    """|H_Newton - H_ref| / H_ref, H_ref the closed form's (reference ``exact``) or the
    finest run's (reference ``finest``)."""
    H = ds["newton_synthetic_horizontal_displacement"].values
    if entry["reference"] == "finest":
        return against_finest(H, ds[entry["knob"]].values, entry["finer"], "relative")
    return _relative(H, ds["exact_synthetic_horizontal_displacement"].values)


@ACCURACY.register("interpolated_motion_laws")
def interpolated_motion_laws(ds, entry):
    """max |theta1, theta2 of a run's spline - the finest run's| at the finest run's cut points
    (rad): every run stores its spline on the nested LAW_GRID."""
    n = np.asarray(ds[entry["knob"]].values, int)
    f = finest_index(n, entry["finer"])
    step = (LAW_GRID - 1) // (n[f] - 1) if (LAW_GRID - 1) % (n[f] - 1) == 0 else 1
    laws = np.stack([ds[f"newton_law_theta{k}"].values[:, ::step] for k in (1, 2)])
    err = np.abs(laws - laws[:, f:f + 1]).max(axis=(0, 2))
    err[f] = np.nan
    return err
