"""The saw_chain cost-of-accuracy quantities (config ``accuracy:``): errors against the exact
reference, read from the scalars each run of the study stores
(:func:`.solver.errors_against_exact`), all relative to the exact quantity's maximum."""
from __future__ import annotations

from mechrepro.accuracy import AccuracyQuantities

ACCURACY = AccuracyQuantities("saw_chain")


@ACCURACY.register("load_pointwise")
def load_pointwise(ds, entry):
    """max |F_dx - exact| / max |exact| over the period, stage-switch sample excluded."""
    return ds["dynamic_load_x_error_pointwise"].values


@ACCURACY.register("load_pointwise_rms")
def load_pointwise_rms(ds, entry):
    """RMS of |F_dx - exact| / max |exact| over the period, stage-switch sample excluded."""
    return ds["dynamic_load_x_error_pointwise_rms"].values


@ACCURACY.register("load_stage_switch")
def load_stage_switch(ds, entry):
    """|F_dx - exact| / max |exact| at the stage-switch sample t1 + dt (Eqs. 18-19)."""
    return ds["dynamic_load_x_error_switch"].values


@ACCURACY.register("velocity_pointwise")
def velocity_pointwise(ds, entry):
    """max |V - exact| / max |exact| over the period, stage-switch sample excluded."""
    return ds["tight_side_velocity_error_pointwise"].values
