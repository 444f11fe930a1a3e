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


def resonance_peak(speed, amplitude) -> tuple[float, float]:
    """The resonance peak of a sweep (Figs. 5-9): its amplitude and speed at the one-mode
    vertex through the largest sample and its neighbours (:func:`.claims.one_mode_peak`;
    the speed axis may be adaptive).  Returns (amplitude, speed)."""
    sp, a = C.one_mode_peak(speed, amplitude)
    return a, sp


def _peaks(ds) -> np.ndarray:
    """(amplitude, speed) of the resonance peak of every run of a sweep study."""
    return np.array([resonance_peak(ds.speed.values, ds.amplitude.isel(run=i).values)
                     for i in range(ds.sizes["run"])])


def _finest(ds, entry, values, error):
    return against_finest(values, ds[entry["knob"]].values, entry["finer"], error)


@ACCURACY.register("peak_amplitude")
def peak_amplitude(ds, entry):
    return _finest(ds, entry, _peaks(ds)[:, 0], entry["quantities"]["peak_amplitude"]["error"])


@ACCURACY.register("peak_speed")
def peak_speed(ds, entry):
    return _finest(ds, entry, _peaks(ds)[:, 1], entry["quantities"]["peak_speed"]["error"])


@ACCURACY.register("steady_amplitude")
def steady_amplitude(ds, entry):
    """Galerkin steady amplitude at the probe (last quarter of whole tooth periods)."""
    return _finest(ds, entry, ds.steady_amplitude.values,
                   entry["quantities"]["steady_amplitude"]["error"])


def _exact(ds, differencing):
    """max |u_FD - u_exact| after the march over the unit amplitude of the exact mode."""
    return ds.error_max.sel(differencing=differencing).values / 1.0


@ACCURACY.register("exact_mode_central")
def exact_mode_central(ds, entry):
    return _exact(ds, "central")


@ACCURACY.register("exact_mode_mixed")
def exact_mode_mixed(ds, entry):
    return _exact(ds, "mixed")


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


@ACCURACY.register("peak_amplitude_vs_central")
def peak_amplitude_vs_central(ds, entry):
    return _against_central(ds, 0)


@ACCURACY.register("peak_speed_vs_central")
def peak_speed_vs_central(ds, entry):
    return _against_central(ds, 1)
