"""Cost-of-accuracy quantities of joint_wear (the ``accuracy:`` block of the config).

dynamic      the wear per period (proportional to the wear factor G of Eq. 29) and the mean
             joint force (Eq. 22) of every stiff integrator run against the finest Radau run;
quasistatic  the same quantities over the samples per period against the finest sampling;
interval     the wear of side B1 at 86 h against the interval method's limit (its exact solution).
"""
from __future__ import annotations

import numpy as np

from mechrepro.accuracy import AccuracyQuantities, against_finest, finest_index
from mechrepro.errors import Refusal

ACCURACY = AccuracyQuantities("joint_wear")
REFERENCE_METHOD = "Radau"


def finest_radau(st) -> int:
    """Index of the dynamic reference: the Radau run at the smallest rtol of the study."""
    idx = [i for i, m in enumerate(st["method"].values) if m == REFERENCE_METHOD]
    return idx[int(np.argmin(st["rtol"].values[idx]))]


def against_dynamic_reference(st, variable: str) -> np.ndarray:
    """|q / q_ref - 1| of ``variable`` for every run of the study (whatever its method)
    against the finest Radau run (NaN for the reference itself)."""
    i_ref = finest_radau(st)
    if i_ref != finest_index(st["rtol"].values, "smaller"):
        raise Refusal("joint_wear: the finest rtol of accuracy_dynamic must be a Radau run "
                         "(the reference of the dynamic accuracy entry)")
    q = st[variable].values.astype(float)
    err = np.abs(q / q[i_ref] - 1.0)
    err[i_ref] = np.nan
    return err


def _per_period(variable: str):
    """The error of ``variable`` over one period: in the dynamic study against the finest
    Radau run, in the quasi-static one against the finest sampling."""
    def error(ds, entry):
        if "method" in ds:
            return against_dynamic_reference(ds, variable)
        return against_finest(ds[variable].values, ds[entry["knob"]].values, entry["finer"])
    return error


#: the wear per period (proportional to the wear factor G of Eq. 29), the mean joint force (Eq. 22)
ACCURACY.register("wear_per_period")(_per_period("wear_factor"))
ACCURACY.register("mean_force")(_per_period("F_N_mean"))


@ACCURACY.register("wear_86h")
def wear_86h(ds, entry):
    """Wear of side B1 at 86 h against the interval method's limit (wear.interval_limit,
    the exact solution of its time stepping), or the finest interval where not stored."""
    if "wear_at_end_limit_B1" in ds:
        return np.abs(ds["wear_at_end_B1"].values / ds["wear_at_end_limit_B1"].values - 1.0)
    return against_finest(ds["wear_at_end_B1"].values, ds[entry["knob"]].values, entry["finer"])
