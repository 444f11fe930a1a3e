"""Turn the paper's worded claims into computed quantities (used by the notebook and tests).

All functions take plain arrays (speed in rpm, amplitude in m) and return numbers or
booleans; thresholds are stated here once, a priori, not tuned to the outcome.
"""
from __future__ import annotations

import numpy as np
from scipy.signal import find_peaks

PEAK_PROMINENCE = 0.05     # a peak rises by >= 5 % of the sweep's largest amplitude
MATCH_TOL = 0.015          # a peak "is at" a predicted speed within 1.5 % of it
AMPLIFIED = 2.0            # "amplified": peak >= 2 x the quasi-static amplitude


def peaks(speed, amp, prominence: float = PEAK_PROMINENCE):
    """Indices of local maxima of amp(speed) with relative prominence."""
    a = np.nan_to_num(np.asarray(amp, float), nan=0.0)
    if a.size < 3 or np.max(a) <= 0:
        return np.array([], int)
    idx, _ = find_peaks(a, prominence=prominence * np.max(a))
    return idx


def peak_near(speed, amp, target: float, tol: float = MATCH_TOL):
    """Speed of the highest peak within tol (relative) of target, or nan."""
    speed = np.asarray(speed, float)
    idx = peaks(speed, amp)
    if not np.isfinite(target):
        return float("nan")
    near = idx[np.abs(speed[idx] / target - 1) <= tol]
    if near.size == 0:
        return float("nan")
    return float(speed[near[np.argmax(np.asarray(amp)[near])]])


def nearest_peak(speed, amp, target: float, window: float = 0.06):
    """Speed of the peak closest to target within a +-window band, or nan."""
    speed = np.asarray(speed, float)
    idx = peaks(speed, amp)
    idx = idx[np.abs(speed[idx] / target - 1) <= window] if np.isfinite(target) else idx[:0]
    if idx.size == 0:
        return float("nan")
    return float(speed[idx[np.argmin(np.abs(speed[idx] - target))]])


def count_peaks(speed, amp, lo: float, hi: float) -> int:
    speed = np.asarray(speed, float)
    idx = peaks(speed, amp)
    return int(np.sum((speed[idx] >= lo) & (speed[idx] <= hi)))


def amplification(speed, amp, target: float, window: float = 0.05) -> float:
    """Largest amplitude within +-window of target over the amplitude at the lowest speed."""
    speed, amp = np.asarray(speed, float), np.asarray(amp, float)
    band = np.abs(speed / target - 1) <= window
    if not band.any():
        return float("nan")
    return float(np.nanmax(amp[band]) / amp[0])


def off_resonance_mask(speed, resonances, width: float = 0.04):
    """True where the speed is more than width (relative) from every predicted resonance."""
    speed = np.asarray(speed, float)
    r = np.asarray([x for x in np.ravel(resonances) if np.isfinite(x)])
    if r.size == 0:
        return np.ones(speed.shape, bool)
    return np.all(np.abs(speed[:, None] / r[None, :] - 1) > width, axis=1)


def resonance_peak_level(speed, amp, resonances, window: float = 0.02) -> float:
    """Mean over predicted resonances (inside the speed range) of the max amplitude near each."""
    speed, amp = np.asarray(speed, float), np.asarray(amp, float)
    vals = []
    for r in np.ravel(resonances):
        if np.isfinite(r) and speed[0] <= r <= speed[-1]:
            band = np.abs(speed / r - 1) <= window
            if band.any():
                vals.append(np.nanmax(amp[band]))
    return float(np.mean(vals)) if vals else float("nan")


def monotone_increasing(values) -> bool:
    v = np.asarray(values, float)
    return bool(np.all(np.isfinite(v)) and np.all(np.diff(v) > 0))
