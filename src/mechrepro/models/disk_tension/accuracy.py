"""Cost-of-accuracy quantities of disk_tension (config ``accuracy:``; one entry per solver).

Each function returns the errors along the study's runs.  The entry's ``name`` is the
solver whose variables are read (``axisym_*`` or ``plate2d_*``).  References: the exact
Bessel frequencies for the unrolled disk, and for the rolled disk the Richardson
extrapolation of the 64- and 128-element axisymmetric models that effect
``rolled_reference`` stores in every run (``f_rolled_reference``; converged to about 1e-9 on
the unrolled frequencies, where it can be checked against the exact solution).
"""
from __future__ import annotations

import numpy as np

from mechrepro.accuracy import AccuracyQuantities

ACCURACY = AccuracyQuantities("disk_tension")


def _max_over(err, ds):
    """max |err| over every dimension but ``run``."""
    a = np.abs(np.asarray(err, float))
    return a.reshape(ds.sizes["run"], -1).max(axis=1)


@ACCURACY.register("unrolled_max_vs_exact")
def unrolled_max_vs_exact(ds, entry):
    """max over N_d of |f / f_exact - 1| (Eq. 6 against the Bessel solution)."""
    return ds[f"{entry['name']}_error_unrolled_max"].values


@ACCURACY.register("unrolled_nd4_vs_exact")
def unrolled_nd4_vs_exact(ds, entry):
    """|f / f_exact - 1| of N_d = 4, the mode the thickness is calibrated on."""
    return np.abs(ds[f"{entry['name']}_error_unrolled"].sel(n_d=4).values)


@ACCURACY.register("rolled_max_vs_richardson")
def rolled_max_vs_richardson(ds, entry):
    """max over (r_c, N_d) of |f~ / f~_ref - 1| (Eq. 5 against the converged reference)."""
    name = entry["name"]
    return _max_over(ds[f"{name}_f_rolled"] / ds[f"{name}_f_rolled_reference"] - 1.0, ds)
