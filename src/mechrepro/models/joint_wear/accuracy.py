"""Cost-of-accuracy quantities of joint_wear (the ``accuracy:`` block of the config).

dynamic      the wear per period (proportional to the wear factor G of Eq. 29) and the mean
             joint force (Eq. 22) of each stiff integrator against the finest Radau run;
quasistatic  the same quantities over the samples per period against the finest sampling;
interval     the wear of side B1 at 86 h against the finest interval of the interval method.
"""
from __future__ import annotations

import numpy as np

from mechrepro.accuracy import AccuracyQuantities, against_finest, finest_index

ACCURACY = AccuracyQuantities("joint_wear")
REFERENCE_METHOD = "Radau"


def finest_radau(st) -> int:
    """Index of the dynamic reference: the Radau run at the smallest rtol of the study."""
    idx = [i for i, m in enumerate(st["method"].values) if m == REFERENCE_METHOD]
    return idx[int(np.argmin(st["rtol"].values[idx]))]


def against_dynamic_reference(st, variable: str, method: str) -> np.ndarray:
    """|q / q_ref - 1| of ``variable`` for the runs of ``method`` (NaN for the others and
    for the reference itself) against the finest Radau run."""
    i_ref = finest_radau(st)
    if i_ref != finest_index(st["rtol"].values, "smaller"):
        raise ValueError("joint_wear: the finest rtol of accuracy_dynamic must be a Radau run "
                         "(the reference of the dynamic accuracy entry)")
    q = st[variable].values.astype(float)
    err = np.abs(q / q[i_ref] - 1.0)
    err[st["method"].values != method] = np.nan
    err[i_ref] = np.nan
    return err


for _method in ("Radau", "BDF", "LSODA"):
    for _name, _var in (("wear_per_period", "wear_factor"), ("mean_force", "F_N_mean")):
        ACCURACY.register(f"{_name}_{_method.lower()}")(
            lambda ds, entry, v=_var, m=_method: against_dynamic_reference(ds, v, m))


@ACCURACY.register("wear_per_period")
def wear_per_period(ds, entry):
    return against_finest(ds["wear_factor"].values, ds[entry["knob"]].values, entry["finer"])


@ACCURACY.register("mean_force")
def mean_force(ds, entry):
    return against_finest(ds["F_N_mean"].values, ds[entry["knob"]].values, entry["finer"])


@ACCURACY.register("wear_86h")
def wear_86h(ds, entry):
    return against_finest(ds["wear_at_end_B1"].values, ds[entry["knob"]].values, entry["finer"])
