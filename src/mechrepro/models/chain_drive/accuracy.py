"""The error functions of chain_drive's cost-of-accuracy quantities (config ``accuracy:``).

Each takes the study (or run) dataset of its entry and returns one error per knob value;
the framework (:mod:`mechrepro.accuracy`) writes the long-form table.
"""
from __future__ import annotations

import math

import numpy as np

from mechrepro.accuracy import AccuracyQuantities, against_finest

from . import claims as C

ACCURACY = AccuracyQuantities("chain_drive")


def _peaks(ds) -> np.ndarray:
    """(amplitude, speed) of the resonance peak of every run of a sweep study (Figs. 5-9):
    the one-mode vertex through the largest sample and its neighbours
    (:func:`.claims.one_mode_peak`; the speed axis may be adaptive)."""
    return np.array([C.one_mode_peak(ds.speed.values, ds.amplitude.isel(run=i).values)[::-1]
                     for i in range(ds.sizes["run"])])


# against the finest run: the resonance peak of a sweep, and the Galerkin steady amplitude at
# the probe (last quarter of whole tooth periods)
for _q, _get in (("peak_amplitude", lambda ds: _peaks(ds)[:, 0]), ("peak_speed", lambda ds: _peaks(ds)[:, 1]),
                 ("steady_amplitude", lambda ds: ds.steady_amplitude.values)):
    ACCURACY.register(_q)(lambda ds, entry, q=_q, get=_get: against_finest(
        get(ds), ds[entry["knob"]].values, entry["finer"], entry["quantities"][q]["error"]))


# max |u_FD - u_exact| after the march over the unit amplitude of the exact mode
for _d in ("central", "mixed"):
    ACCURACY.register(f"exact_mode_{_d}")(
        lambda ds, entry, d=_d: ds.error_max.sel(differencing=d).values / 1.0)


def _against_central(ds, j: int):
    """(|peak / reference - 1| per run, the reference's own relative error): the reference
    is the central (cfl 0.98) run of the most points per pitch, its error from it and the
    two runs below it at ratio 1.5 (:func:`mechrepro.levels.level_error`, the one
    estimator: inf where they do not contract); those three get NaN (not on the curve)."""
    from mechrepro.levels import level_error

    vals = _peaks(ds)[:, j]
    fine = np.argsort(ds.points_per_pitch.values)[-3:]
    c2, c1, b = vals[fine]
    e_ref = level_error(c2, c1, b, 1.5, math.inf)[0] / abs(b)
    err = np.abs(vals / b - 1.0)
    err[fine] = np.nan
    return err, e_ref


for _j, _q in enumerate(("peak_amplitude_vs_central", "peak_speed_vs_central")):
    ACCURACY.register(_q)(lambda ds, entry, j=_j: _against_central(ds, j))
