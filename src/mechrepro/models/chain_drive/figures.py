"""What the chain_drive figures and tables show, computed from the datasets (the notebook
only draws): runs of a sweep with their base scene, the unstable speeds, the simulated
peaks per resonance order, the Fig. 3 panel order, the frequency error of the FD mode.
"""
from __future__ import annotations

import numpy as np

from mechrepro.io import run_attrs

from . import claims as C


def parameter(ds, name: str) -> float:
    """The SI value of a parameter in the run that wrote ``ds`` (its provenance)."""
    return run_attrs(ds)["parameters"]["values_si"][name]


def resolution(ds, name: str):
    """A resolution knob of the run that wrote ``ds`` (its provenance)."""
    return run_attrs(ds)["resolution"][name]


def with_base(R, study: str, scene: str, key: str):
    """A study's runs plus its base scene (the scene itself is one point of the sweep),
    sorted by the swept value; returns (values, datasets).  The swept parameters of this
    paper (centre distance in pitches, I2, T_s, omega_ex / omega_1) are SI in the config."""
    st, base = R.study(study), R.run(scene)
    values = [parameter(base, key)] + [float(v) for v in st[key].values]
    runs = [base] + R.study_runs(study)
    order = np.argsort(values)
    return [values[i] for i in order], [runs[i] for i in order]


def steady(ds) -> np.ndarray:
    """A sweep's steady amplitude [m], nan where the speed is unstable: an unstable periodic
    orbit has no steady amplitude (:func:`.claims.steady`)."""
    return C.steady(ds.amplitude.values, ~np.asarray(ds.unstable.values, bool))


def stability_classes(ds) -> dict[str, np.ndarray]:
    """Fig. 9: the speeds of a sweep by what the string model says there, as masks over
    ``ds.speed``: ``stable`` (a steady amplitude), ``growth`` (a Floquet multiplier > 1 in
    a mode the string represents), ``outside`` (growth in a mode shorter than its validity
    limit, the assumed parameter ``valid_wavelength``) and ``slack`` (P + P_t <= 0: no string at all).  Every
    speed is in exactly one class."""
    un = np.asarray(ds.unstable.values, bool)
    slack = np.asarray(ds.slack.values, bool) if "slack" in ds else np.zeros_like(un)
    # growth in a mode shorter than the string holds (``outside_validity``; none in a
    # march's dataset): drawn apart from the growth the model can claim
    outside = (np.asarray(ds.outside_validity.values, bool) if "outside_validity" in ds
               else np.zeros_like(un)) & un & ~slack
    return {"stable": ~un, "growth": un & ~slack & ~outside, "outside": outside, "slack": slack}


def order_window(ds, k: int) -> tuple[float, float]:
    """:func:`.claims.order_window` of a sweep's order k (the short- and long-span resonance
    speeds it tabulates)."""
    return C.order_window(float(ds.resonance_speed_long.sel(order=k)),
                          float(ds.resonance_speed_short.sel(order=k)))


def resonances_in_window(ds) -> np.ndarray:
    """Short- and long-span resonance speeds [rpm] of a sweep that lie inside its speed range."""
    v = np.concatenate([ds.resonance_speed_short.values, ds.resonance_speed_long.values])
    return v[(v >= float(ds.speed[0])) & (v <= float(ds.speed[-1]))]


RESONANCE_COLUMNS = ["centre_distance_pitches", "order", "curve", "short_span_rpm",
                     "long_span_rpm", "simulated_peaks_rpm"]


def resonance_rows(centre_distances, plain, length) -> list[list]:
    """Table resonance_speeds (Fig. 5): per centre distance, order and curve (without /
    with length change), the short- and long-span resonance speeds and the simulated peaks
    (prominence >= 0.05 mm, stable speeds) in the order's window (:func:`.claims.order_window`)."""
    rows = []
    for cd, dp, dl in zip(centre_distances, plain, length):
        for k in dp.order.values:
            for label, ds in (("plain", dp), ("length", dl)):
                short = float(ds.resonance_speed_short.sel(order=k))
                long = float(ds.resonance_speed_long.sel(order=k))
                lo, hi = C.order_window(long, short)
                found = C.peak_speeds(ds.speed.values, ds.amplitude.values, lo, hi,
                                      stable=~ds.unstable.values.astype(bool))
                rows.append([cd, int(k), label, short, long, " ".join(f"{x:.1f}" for x in found)])
    return rows


TIMING_COLUMNS = ["sweep", "speeds", "grid_points", "time_steps", "wall_time_s"]


def timing_rows(named_sweeps: dict) -> list[list]:
    """Table timings: speeds, grid points, time steps and wall time of each named sweep."""
    return [[name, int(ds.speed.size), int(ds.n_points), int(ds.n_steps), float(ds.wall_time)]
            for name, ds in named_sweeps.items()]


#: peak amplitudes that move less than this between grid levels, contracting at least at
#: first order (the lower of the two schemes' formal orders), are called converged
CONVERGED_SPREAD = 0.05


#: peak amplitudes whose levels agree to this (relative) agree: differences at this level
#: (the one-mode vertex, the speed sampling, round-off) need no contraction to be small
AGREE_SPREAD = 1e-3


def levels_converged(spread: float, order: float) -> bool:
    """Whether a sweep's peak levels (:func:`peak_level_spread`) show convergence: observed
    order >= 1 and a spread below :data:`CONVERGED_SPREAD` (26 % at order 0.43 is not), or
    levels that agree to :data:`AGREE_SPREAD` whether they contract or not."""
    return bool(spread < AGREE_SPREAD or (np.isfinite(order) and order >= 1.0
                                          and spread < CONVERGED_SPREAD))


def peak_level_spread(R, name: str, n_peaks: int = 5, window: float = 3.0):
    """How far the steady amplitude of the ``n_peaks`` largest stable peaks of run ``name``
    moves between its @coarsest, @coarser and base levels (the framework runs all three for
    every verdict's reads): (max relative spread, observed order or nan, peak speeds).  The
    amplitude at a level is the one-mode vertex (:func:`.claims.one_mode_peak`) of its
    stable values within +-``window`` rpm of the base peak; peaks within ``window`` of an
    unstable speed (a stable orbit at a stability edge grows without bound there) or of a
    larger peak (a shoulder the window's vertex does not measure) are left out.  An observed
    order needs a contracting sequence (|d1| > 1.05 |d2|); a spread with none is an
    amplitude that does not converge under refinement, and the figure says so."""
    try:
        ds = [R.run(f"{name}{s}") for s in ("@coarsest", "@coarser", "")]
    except FileNotFoundError:
        return float("nan"), float("nan"), []
    base = ds[2]
    un = np.asarray(base.unstable.values, bool)
    A = np.where(un, 0.0, base.amplitude.values)
    idx = C.peaks(base.speed.values, A)
    # a stable orbit next to an unstable band has no limit (its multiplier nears 1)
    near = [np.any(un & (np.abs(base.speed.values - base.speed.values[i]) <= window)) for i in idx]
    idx = idx[~np.array(near, bool)] if len(idx) else idx
    # a peak the window shares with a larger one (a shoulder) is not what the window's
    # vertex measures at every level
    sp = base.speed.values
    idx = np.array([i for i in idx if A[i] >= np.max(A[np.abs(sp - sp[i]) <= window])], int)
    idx = idx[np.argsort(A[idx])[::-1][:n_peaks]]
    spread, orders = 0.0, []
    for i in idx:
        s0 = float(base.speed.values[i])
        vals = []
        for d in ds:
            m = np.abs(d.speed.values - s0) <= window
            a = np.where(np.asarray(d.unstable.values, bool)[m], np.nan, d.amplitude.values[m])
            # the one-mode vertex, not the largest sample: the levels sample speeds apart
            vals.append(C.one_mode_peak(d.speed.values[m], a)[1] if np.isfinite(a).any()
                        else np.nan)
        c2, c, b = vals
        spread = max(spread, np.nanmax(np.abs(np.array([c2, c]) - b)) / b)
        d1, d2 = abs(c2 - c), abs(c - b)
        orders.append(np.log(d1 / d2) / np.log(1.5) if d2 > 0 and d1 > 1.05 * d2 else np.nan)
    order = float(np.nanmin(orders)) if np.isfinite(orders).all() and orders else float("nan")
    return float(spread), order, [float(base.speed.values[i]) for i in idx]


LEVEL_RUNS = ("@coarsest", "@coarser", "", "@finer")
DISCRETE_PEAK_COLUMNS = ["run", "order", "quantity", "unit", "coarsest", "coarser", "base",
                         "finer", "error", "observed_order_below", "observed_order_above", "how"]


def order_peak(ds, k: int) -> tuple[float, float]:
    """(speed [rpm], amplitude [m]) of the largest stable peak of order k (within
    :func:`.claims.order_window` of its short- and long-span resonance speeds), at the
    one-mode vertex through its neighbours (:func:`.claims.one_mode_peak`)."""
    sp = ds.speed.values
    lo, hi = order_window(ds, k)
    m = (sp >= lo) & (sp <= hi)
    a = np.where(np.asarray(ds.unstable.values, bool), np.nan, ds.amplitude.values)[m]
    return C.one_mode_peak(sp[m], a) if np.isfinite(a).any() else (np.nan, np.nan)


def stable_orders(ds, n: int = 2) -> list[int]:
    """The first ``n`` resonance orders whose window (:func:`.claims.order_window`) lies in
    the sweep and holds no unstable speed: a peak next to a stability edge has no
    converging amplitude."""
    sp, un = ds.speed.values, np.asarray(ds.unstable.values, bool)
    out = []
    for k in ds.order.values:
        lo, hi = order_window(ds, k)
        if lo >= sp[0] and hi <= sp[-1] and not np.any(un & (sp >= lo) & (sp <= hi)):
            out.append(int(k))
    return out[:n]


#: the band the levels' differences are compared with (:func:`mechrepro.levels.level_error`
#: calls a thousandth of it negligible): 2 % of the value, the tolerance of the paper's
#: resonance-speed rows, the tightest it sets on a peak
PEAK_BAND = 0.02


def level_runs(R, name: str, study: str | None = None) -> list:
    """The four levels of a discrete sweep, coarsest to finest: the framework's variants of
    run ``name`` (@coarsest, @coarser, base, @finer), or, with ``study`` (a sweep spelling
    them out for a scene no verdict reads), its runs by steps per tooth period around the
    base scene ``name``."""
    if study is None:
        return [R.run(f"{name}{s}") for s in LEVEL_RUNS]
    runs = sorted(R.study_runs(study), key=lambda d: resolution(d, "steps_per_period"))
    return runs[:2] + [R.run(name)] + runs[2:]


def discrete_peak_rows(name: str, ds: list, n_orders: int = 2) -> list[list]:
    """Peak speed and amplitude of the first ``n_orders`` orders away from any instability
    (:func:`stable_orders`, on the baseline) of the discrete sweep ``name`` at its four
    levels ``ds`` (:func:`level_runs`), with the error of the baseline from both sides by
    the one estimator (:func:`mechrepro.levels.level_error`: coarsest / coarser / base and
    coarser / base / finer at the levels' ratio 1.5; the larger bound, plus |base - finer|)."""
    from mechrepro.levels import level_error

    tol = float(resolution(ds[2], "peak_tol"))
    rows = []
    for k in stable_orders(ds[2], n_orders):
        got = np.array([order_peak(d, k) for d in ds])          # (level, speed/amplitude)
        for j, (q, unit, scale) in enumerate((("peak_speed", "rpm", 1.0),
                                              ("peak_amplitude", "mm", 1e3))):
            c2, c1, b, f = got[:, j] * scale
            # a peak speed is located to half the base level's bisection width at best
            own = 0.5 * tol if q == "peak_speed" else 0.0
            e_lo, p_lo, _, how = level_error(c2, c1, b, 1.5, PEAK_BAND * abs(b), own)
            e_hi, p_hi, _, how_f = level_error(c1, b, f, 1.5, PEAK_BAND * abs(b), own / 1.5)
            rows.append([name, k, q, unit, c2, c1, b, f, max(e_lo, abs(b - f) + e_hi),
                         p_lo, p_hi, f"{how}; with finer: {how_f}"])
    return rows
