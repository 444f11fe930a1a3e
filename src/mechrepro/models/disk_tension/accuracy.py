"""Cost-of-accuracy quantities of disk_tension (config ``accuracy:``): the errors along a
study's runs, against exact (Bessel) solutions wherever one exists; the rolled Gaussian
stress has none, so the 2-D model's rolled errors are taken against the axisym Richardson
reference of output ``rolled_reference``.
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
    return ds["error_unrolled_max"].values


@ACCURACY.register("unrolled_nd4_vs_exact")
def unrolled_nd4_vs_exact(ds, entry):
    """|f / f_exact - 1| of N_d = 4, the mode the thickness is calibrated on."""
    return np.abs(ds["error_unrolled"].sel(n_d=4).values)


@ACCURACY.register("stressed_max_vs_exact")
def stressed_max_vs_exact(ds, entry):
    """max over (reference stress, N_d) of |f / f_exact - 1| (Eqs. 3, 5)."""
    return _max_over(ds["error_stressed"], ds)


@ACCURACY.register("rolled_max_vs_richardson")
def rolled_max_vs_richardson(ds, entry):
    """max over (r_c, N_d) of |f~ / f~_ref - 1| (Eq. 5 against the converged reference)."""
    return _max_over(ds["f_rolled"] / ds["f_rolled_reference"] - 1.0, ds)
