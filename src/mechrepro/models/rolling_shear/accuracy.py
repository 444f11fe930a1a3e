"""The error functions of rolling_shear's cost-of-accuracy quantities (config ``accuracy:``).

Each returns one error per run of the study, along its ``run`` dimension (mm, rad inside).
"""
from __future__ import annotations

import numpy as np

from mechrepro.accuracy import AccuracyQuantities, against_finest, finest_index

from .motion_laws import LAW_GRID, pose_error

ACCURACY = AccuracyQuantities("rolling_shear")


def _relative(values, reference):
    values, reference = np.asarray(values, float), np.asarray(reference, float)
    return np.abs(values - reference) / np.abs(reference)


@ACCURACY.register("selpso_motion_laws")
def selpso_motion_laws(ds, entry):
    """max |theta1..theta6 - closed form| over the cut (rad), stored by each run."""
    return ds["selpso_pose_error"].values


@ACCURACY.register("selpso_motion_laws_q50")
def selpso_motion_laws_q50(ds, entry):
    """Median over ``options.seeds`` strokes of the max pose error (rad)."""
    return ds["selpso_pose_error_q50"].values


@ACCURACY.register("selpso_motion_laws_q90")
def selpso_motion_laws_q90(ds, entry):
    """90 % quantile over ``options.seeds`` strokes of the max pose error (rad)."""
    return ds["selpso_pose_error_q90"].values


@ACCURACY.register("selpso_failure_probability")
def selpso_failure_probability(ds, entry):
    """1 - the probability over seeds that a whole stroke lands on the design branch."""
    return ds["selpso_stroke_failure_probability"].values


@ACCURACY.register("pso_standard_motion_laws_q50")
def pso_standard_motion_laws_q50(ds, entry):
    """The same median for the standard constricted PSO (w 0.7298, c 1.49618)."""
    return ds["pso_standard_pose_error_q50"].values


@ACCURACY.register("pso_standard_motion_laws_q90")
def pso_standard_motion_laws_q90(ds, entry):
    return ds["pso_standard_pose_error_q90"].values


@ACCURACY.register("pso_standard_failure_probability")
def pso_standard_failure_probability(ds, entry):
    return ds["pso_standard_stroke_failure_probability"].values


@ACCURACY.register("selpso_objective_h")
def selpso_objective_h(ds, entry):
    """|H from the selPSO poses - H of the closed form| / H of the closed form."""
    return _relative(ds["selpso_synthetic_horizontal_displacement"].values,
                     ds["exact_synthetic_horizontal_displacement_ref"].values)


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
    """max |theta1, theta2 of a run interpolated by cubic spline - the finest run's| at the
    finest run's own cut points (rad).

    Every run stores its spline on the nested grid of LAW_GRID points
    (:func:`.motion_laws.driving_laws_on_grid`); the finest run's cut points are every
    (LAW_GRID - 1) / (n_finest - 1)-th point of it, where its spline is its solution."""
    n = np.asarray(ds[entry["knob"]].values, int)
    f = finest_index(n, entry["finer"])
    step = (LAW_GRID - 1) // (n[f] - 1) if (LAW_GRID - 1) % (n[f] - 1) == 0 else 1
    laws = np.stack([ds[f"newton_law_theta{k}"].values[:, ::step] for k in (1, 2)])
    err = np.abs(laws - laws[:, f:f + 1]).max(axis=(0, 2))
    err[f] = np.nan
    return err
