"""Turn the paper's worded claims into well-posed computed quantities.

All functions take plain arrays (speed in rpm, amplitude in m) and return numbers or
booleans.  The thresholds are physical and fixed a priori, once, here -- never relative to
a sweep's own maximum (which an instability capped at ``u_cap`` would set):

* ``PEAK_PROMINENCE`` = 0.05 mm: a peak must rise this far above the higher of its two
  flanking minima.  It is 1/8 of the chordal end-motion amplitude r (1 - cos(pi/n)) =
  0.41 mm of a 24-tooth No. 40 sprocket, the quasi-static response level of every sweep;
  ripples below it are invisible on the paper's amplitude scale.
* ``ORDER_WINDOW`` = 3 %: an order's peaks are searched in [0.97 x long-span speed,
  1.03 x short-span speed] -- the region where the paper's "two peaks per order" are.
* ``AMPLIFIED`` = 2: "amplified" = the peak within 5 % of the first resonance is at least
  twice the quasi-static amplitude at the lowest speed.
"""
from __future__ import annotations

import numpy as np

PEAK_PROMINENCE = 0.05e-3  # m
ORDER_WINDOW = 0.03
AMPLIFIED = 2.0
NEAR_PEAK = 0.06           # a predicted resonance "has" a peak within 6 % of it


def find_peaks(x, prominence: float):
    """``scipy.signal.find_peaks(x, prominence=prominence)[0]`` for a 1-D float array, by
    scipy's own algorithm (``_local_maxima_1d``, then ``_peak_prominences`` with no window):
    a local maximum (a flat top counts once, at its middle, rounded down) whose height above
    the higher of the lowest points between it and a higher sample (or the end) on each side
    is at least ``prominence``.  Written out because importing ``scipy.signal`` imports
    ``scipy.stats`` too (~0.6-1 s, twice per reproduction: validation and notebook), for
    one function on arrays of a few hundred speeds; ``tests/test_chain_drive_claims.py``
    checks it against scipy's."""
    x = np.ascontiguousarray(x, dtype=float)
    n = x.size
    out = []
    i = 1
    while i < n - 1:
        if x[i - 1] < x[i]:
            ahead = i + 1
            while ahead < n - 1 and x[ahead] == x[i]:
                ahead += 1
            if x[ahead] < x[i]:
                peak = (i + ahead - 1) // 2
                top = x[peak]
                j, left_min = peak, top
                while j >= 0 and x[j] <= top:
                    left_min = min(left_min, x[j])
                    j -= 1
                j, right_min = peak, top
                while j < n and x[j] <= top:
                    right_min = min(right_min, x[j])
                    j += 1
                if top - max(left_min, right_min) >= prominence:
                    out.append(peak)
                i = ahead
        i += 1
    return np.array(out, dtype=np.intp)


def peaks(speed, amp, prominence: float = PEAK_PROMINENCE, stable=None):
    """Indices of local maxima of amp(speed) rising >= ``prominence`` [m] above their flanks.

    ``stable``: optional mask; unstable (capped) speeds are excluded from the search (an
    instability is reported as such, not as a resonance peak)."""
    a = np.nan_to_num(np.asarray(amp, float), nan=0.0)
    ok = np.ones(a.size, int) if stable is None else np.asarray(stable, bool).astype(int)
    # split at unstable speeds: a peak never straddles an instability band
    edges = np.flatnonzero(np.diff(np.concatenate([[0], ok, [0]])))
    out = [start + find_peaks(a[start:stop], prominence)
           for start, stop in zip(edges[::2], edges[1::2]) if stop - start >= 3]
    return np.concatenate(out).astype(int) if out else np.array([], int)


def order_window(long_speed: float, short_speed: float, width: float = ORDER_WINDOW):
    lo, hi = sorted((long_speed, short_speed))
    return lo * (1 - width), hi * (1 + width)


def peak_speeds(speed, amp, lo: float, hi: float, stable=None) -> list[float]:
    speed = np.asarray(speed, float)
    idx = peaks(speed, amp, stable=stable)
    return [float(s) for s in speed[idx] if lo <= s <= hi]


def nearest_peak(speed, amp, target: float, window: float = NEAR_PEAK, stable=None):
    """Speed of the peak closest to target within a +-window band, or nan.  Not the grid
    point (it jumps by a step when the speed grid is refined) but the resonance of the
    one-mode response through the peak sample and its two neighbours: for a damped single
    mode 1/A^2 is exactly a quadratic in omega^2, so its vertex is the peak whatever the grid.
    ``stable``: as in :func:`peaks` (a peak and its neighbours are stable speeds)."""
    speed, amp = np.asarray(speed, float), np.asarray(amp, float)
    idx = peaks(speed, amp, stable=stable)
    idx = idx[np.abs(speed[idx] / target - 1) <= window] if np.isfinite(target) else idx[:0]
    if idx.size == 0:
        return float("nan")
    i = int(idx[np.argmin(np.abs(speed[idx] - target))])
    x, y = speed[i - 1:i + 2], amp[i - 1:i + 2]
    return float(np.sqrt(parabola_vertex(x * x, -1.0 / (y * y))))


def one_mode_peak(speed, amp) -> tuple[float, float]:
    """(speed, amplitude) of the peak of a sampled resonance curve: the vertex of 1/A^2 as a
    quadratic in omega^2 through the largest sample and its two neighbours (exact for one
    damped mode, whatever the spacing of the samples); the largest sample at an end."""
    speed, amp = np.asarray(speed, float), np.asarray(amp, float)
    i = int(np.nanargmax(amp))
    if not 0 < i < amp.size - 1:
        return float(speed[i]), float(amp[i])
    x, y = speed[i - 1:i + 2] ** 2, -1.0 / amp[i - 1:i + 2] ** 2
    xv = parabola_vertex(x, y)
    (x0, x1, x2), (y0, y1, y2) = x, y
    # the parabola through the three points, at its vertex (Lagrange form)
    yv = (y0 * (xv - x1) * (xv - x2) / ((x0 - x1) * (x0 - x2))
          + y1 * (xv - x0) * (xv - x2) / ((x1 - x0) * (x1 - x2))
          + y2 * (xv - x0) * (xv - x1) / ((x2 - x0) * (x2 - x1)))
    return float(np.sqrt(xv)), float(1.0 / np.sqrt(-yv)) if yv < 0 else float(amp[i])


def parabola_vertex(x, y) -> float:
    """Abscissa of the vertex of the parabola through three points (x may be non-uniform),
    clipped to [x0, x2]; the middle point when the three are collinear."""
    (x0, x1, x2), (y0, y1, y2) = np.asarray(x, float), np.asarray(y, float)
    d = (x0 - x1) * (x0 - x2) * (x1 - x2)
    a = (x2 * (y1 - y0) + x1 * (y0 - y2) + x0 * (y2 - y1)) / d
    b = (x2 * x2 * (y0 - y1) + x1 * x1 * (y2 - y0) + x0 * x0 * (y1 - y2)) / d
    if not np.isfinite(a) or a >= 0:
        return float(x1)
    return float(np.clip(-b / (2 * a), x0, x2))


def steady(amp, stable=None) -> np.ndarray:
    """The steady amplitude: nan at unstable speeds, where the periodic orbit is unstable and
    has no steady amplitude (its shooting "amplitude" is no response; a march's is a
    growing transient)."""
    amp = np.asarray(amp, float)
    return amp if stable is None else np.where(np.asarray(stable, bool), amp, np.nan)


def amplification(speed, amp, target: float, window: float = 0.05, stable=None) -> float:
    """Largest amplitude within +-window of target over the amplitude at the lowest stable
    speed; nan where a speed of the band is unstable (no steady amplitude there)."""
    speed, a = np.asarray(speed, float), steady(amp, stable)
    band = np.abs(speed / target - 1) <= window
    ok = np.isfinite(a)
    if not band.any() or not ok.any() or not ok[band].all():
        return float("nan")
    return float(np.max(a[band]) / a[np.argmax(ok)])


def _near(speed, at_speeds, width: float) -> np.ndarray:
    """True where the speed is within +-width (relative) of any finite one of ``at_speeds``."""
    r = np.asarray([x for x in np.ravel(at_speeds) if np.isfinite(x)], float)
    return np.any(np.abs(np.asarray(speed, float)[:, None] / r[None, :] - 1) <= width, axis=1)


def off_peak_mask(speed, peak_speeds_, width: float = 0.04):
    """True where the speed is more than width (relative) from every given peak speed."""
    return ~_near(speed, peak_speeds_, width)


def level_at(speed, amp, at_speeds, window: float = 0.01, stable=None) -> float:
    """Mean over the given speeds of the max amplitude within +-window of each; nan when a
    band holds an unstable speed (``stable`` mask): an unstable orbit has no steady
    amplitude, so the band's maximum does not exist."""
    speed, amp = np.asarray(speed, float), steady(amp, stable)
    vals = []
    for r in np.ravel(at_speeds):
        band = np.abs(speed / r - 1) <= window
        if band.any():
            vals.append(np.max(amp[band]))
    return float(np.mean(vals)) if vals else float("nan")


def unstable_in_bands(speed, stable, at_speeds, window: float) -> int:
    """How many speeds within +-window (relative) of any of ``at_speeds`` are unstable."""
    return int(np.sum(_near(speed, at_speeds, window) & ~np.asarray(stable, bool)))


def resonance_peak_level(speed, amp, resonances, window: float = 0.02, stable=None) -> float:
    """Mean over predicted resonances (inside the speed range) of the max amplitude near
    each; nan when a band holds an unstable speed (:func:`level_at`)."""
    speed = np.asarray(speed, float)
    inside = [r for r in np.ravel(resonances) if np.isfinite(r) and speed[0] <= r <= speed[-1]]
    return level_at(speed, amp, inside, window, stable)


def monotone_increasing(values) -> bool:
    v = np.asarray(values, float)
    return bool(np.all(np.isfinite(v)) and np.all(np.diff(v) > 0))
