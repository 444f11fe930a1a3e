"""The chain_drive figures, each drawn from the results it declares (config ``figures``:
``figNN(R)`` returns the Figure), and what they and the notebook's tables show, computed
from the datasets: runs of a sweep with their base scene, the unstable speeds, the
simulated peaks per resonance order, the Fig. 3 panel order, the convergence of the peaks.
"""
from __future__ import annotations

import numpy as np

from mechrepro import accuracy
from mechrepro.io import run_attrs
from mechrepro.plotting import log_ticks, plt
from mechrepro.units import from_si

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


def by_modes(R, scene: str, study: str) -> dict:
    """{transverse modes: run dataset} of a Fig. 10 scene and its mode study."""
    return {int(resolution(d, "n_transverse")): d
            for d in [R.run(scene)] + R.study_runs(study)}


def drawn_modes(R, scene: str) -> int:
    return int(resolution(R.run(scene), "n_transverse"))


def mode_ratios(R, coupled: str, uncoupled: str) -> dict:
    """coupled / uncoupled steady amplitude at the probe per mode count."""
    c, u = by_modes(R, coupled, coupled + "_modes"), by_modes(R, uncoupled, uncoupled + "_modes")
    return {n: float(c[n].steady_amplitude) / float(u[n].steady_amplitude)
            for n in sorted(set(c) & set(u))}


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


def resonance_speeds(R) -> tuple[list, list]:
    """Table resonance_speeds (Fig. 5): per centre distance, order and curve (without /
    with length change), the short- and long-span resonance speeds and the simulated peaks
    (prominence >= 0.05 mm, stable speeds) in the order's window (:func:`.claims.order_window`)."""
    cds, plain = with_base(R, "fig05_plain_cd", "fig05_plain", "centre_distance")
    rows = []
    for cd, dp, dl in zip(cds, plain, with_base(R, "fig05_length_cd", "fig05_length", "centre_distance")[1]):
        for k in dp.order.values:
            for label, ds in (("plain", dp), ("length", dl)):
                short = float(ds.resonance_speed_short.sel(order=k))
                long = float(ds.resonance_speed_long.sel(order=k))
                lo, hi = C.order_window(long, short)
                found = C.peak_speeds(ds.speed.values, ds.amplitude.values, lo, hi,
                                      stable=~ds.unstable.values.astype(bool))
                rows.append([cd, int(k), label, short, long, " ".join(f"{x:.1f}" for x in found)])
    return RESONANCE_COLUMNS, rows


TIMING_COLUMNS = ["sweep", "speeds", "grid_points", "time_steps", "wall_time_s"]


def timings(R) -> tuple[list, list]:
    """Table timings: speeds, grid points, time steps and wall time of each sweep of Fig. 5,
    per centre distance: the string without and with length change, the discrete-link span."""
    rows = []
    for label, run in (("plain", "plain"), ("length_string", "length_string"), ("length_discrete", "length")):
        for cd, ds in zip(*with_base(R, f"fig05_{run}_cd", f"fig05_{run}", "centre_distance")):
            rows.append([f"fig05_{label}_cd{cd:g}", int(ds.speed.size), int(ds.n_points), int(ds.n_steps),
                         float(ds.wall_time)])
    return TIMING_COLUMNS, rows


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
    amplitude that does not converge under refinement, and the figure says so.  (nan, nan,
    []) where the profile runs no such level (ci runs no @coarsest of some sweeps)."""
    levels = [f"{name}{s}" for s in ("@coarsest", "@coarser", "")]
    if any(n not in R.cfg.runs for n in levels):     # a profile that runs no such level
        return float("nan"), float("nan"), []
    ds = [R.run(n) for n in levels]
    sp, un = ds[2].speed.values, np.asarray(ds[2].unstable.values, bool)
    A = np.where(un, 0.0, ds[2].amplitude.values)
    # left out: a stable orbit next to an unstable band (no limit: its multiplier nears 1)
    # and a peak the window shares with a larger one (a shoulder: not what the window's
    # vertex measures at every level)
    idx = np.array([i for i in C.peaks(sp, A) if not np.any(un & (np.abs(sp - sp[i]) <= window))
                    and A[i] >= np.max(A[np.abs(sp - sp[i]) <= window])], int)
    idx = idx[np.argsort(A[idx])[::-1][:n_peaks]]
    spread, orders = 0.0, []
    for i in idx:
        # the one-mode vertex, not the largest sample: the levels sample speeds apart
        c2, c, b = (_vertex(d, np.abs(d.speed.values - sp[i]) <= window)[1] for d in ds)
        spread = max(spread, np.nanmax(np.abs(np.array([c2, c]) - b)) / b)
        d1, d2 = abs(c2 - c), abs(c - b)
        orders.append(np.log(d1 / d2) / np.log(1.5) if d2 > 0 and d1 > 1.05 * d2 else np.nan)
    order = float(np.nanmin(orders)) if np.isfinite(orders).all() and orders else float("nan")
    return float(spread), order, [float(sp[i]) for i in idx]


LEVEL_RUNS = ("@coarsest", "@coarser", "", "@finer")
DISCRETE_PEAK_COLUMNS = ["run", "order", "quantity", "unit", "coarsest", "coarser", "base",
                         "finer", "error", "observed_order_below", "observed_order_above", "how"]


def order_peak(ds, k: int) -> tuple[float, float]:
    """(speed [rpm], amplitude [m]) of the largest stable peak of order k (within
    :func:`.claims.order_window` of its short- and long-span resonance speeds), at the
    one-mode vertex through its neighbours (:func:`.claims.one_mode_peak`)."""
    lo, hi = order_window(ds, k)
    return _vertex(ds, (ds.speed.values >= lo) & (ds.speed.values <= hi))


def _vertex(ds, m) -> tuple[float, float]:
    """(speed, amplitude) of the one-mode vertex (:func:`.claims.one_mode_peak`) of the
    stable speeds of ``ds`` in the mask ``m``; nan where none is stable."""
    a = steady(ds)[m]
    return C.one_mode_peak(ds.speed.values[m], a) if np.isfinite(a).any() else (np.nan, np.nan)


def stable_orders(ds, n: int = 2) -> list[int]:
    """The first ``n`` resonance orders whose window (:func:`.claims.order_window`) lies in
    the sweep and holds no unstable speed: a peak next to a stability edge has no
    converging amplitude."""
    sp, un = ds.speed.values, np.asarray(ds.unstable.values, bool)
    windows = {int(k): order_window(ds, k) for k in ds.order.values}
    return [k for k, (lo, hi) in windows.items()
            if lo >= sp[0] and hi <= sp[-1] and not np.any(un & (sp >= lo) & (sp <= hi))][:n]


#: the band the levels' differences are compared with (:func:`mechrepro.levels.level_error`
#: calls a thousandth of it negligible): 2 % of the value, the tolerance of the paper's
#: resonance-speed rows, the tightest it sets on a peak
PEAK_BAND = 0.02


def level_runs(R, name: str) -> list:
    """The four levels of a discrete sweep, coarsest to finest: the framework's variants of
    run ``name`` (@coarsest, @coarser, base, @finer), or, where the framework runs none (a
    scene no verdict reads), the runs of the study ``<name>_levels`` spelling them out, by
    steps per tooth period around the base scene ``name``."""
    if f"{name}@coarsest" in R.cfg.runs:
        return [R.run(f"{name}{s}") for s in LEVEL_RUNS]
    runs = sorted(R.study_runs(f"{name}_levels"), key=lambda d: resolution(d, "steps_per_period"))
    return runs[:2] + [R.run(name)] + runs[2:]


def discrete_peaks(R) -> tuple[list, list]:
    """Table discrete_peaks: :func:`discrete_peak_rows` of the discrete-link sweeps of Figs. 5-8."""
    return DISCRETE_PEAK_COLUMNS, [
        r for name in ("fig05_length", "fig06_inertia", "fig06_i2-000", "fig07_tension", "fig07_ts-000",
                       "fig08_discrete") for r in discrete_peak_rows(name, level_runs(R, name))]


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


# ----------------------------------------------------------------------------- drawing
def _mm(x):
    return from_si(np.asarray(x), "mm")


def _ms(x):
    return from_si(np.asarray(x), "ms")


def convergence_note(R, name: str) -> str:
    """What refinement says about a sweep's steady amplitudes (:func:`peak_level_spread`:
    its largest peaks at @coarsest / @coarser / base): the figures never show an
    unconverged amplitude silently (issue 26).  Converged only where the levels contract at
    least at the schemes' first order with a small spread (:func:`levels_converged`)."""
    spread, order, _ = peak_level_spread(R, name)
    if not np.isfinite(spread):
        return ""
    if levels_converged(spread, order):
        if not np.isfinite(order) or order < 1.0:
            return f"peaks agree to {100 * spread:.2g} % between grid levels"
        return f"peaks converge (observed order {order:.2g}, {100 * spread:.2g} % between levels)"
    got = f", observed order {order:.2g}" if np.isfinite(order) else ", levels do not contract"
    return f"amplitudes NOT converged: peaks move {100 * spread:.2g} % between grid levels{got}"


def _steady_mm(ds):
    """The steady amplitude [mm], nan at unstable speeds (an unstable orbit has none)."""
    return _mm(steady(ds))


def _mark_unstable(ax, ds, label="unstable: no steady amplitude", color="r"):
    """Every sweep marks the speeds whose periodic orbit is unstable (or whose span goes
    slack) as ticks along the top of the axis, never as amplitudes; call after the curves
    (the ticks sit at the axis's upper limit, which they do not move)."""
    sp = ds.speed.values[np.asarray(ds.unstable.values, bool)]
    if sp.size:
        top = ax.get_ylim()[1]
        ax.plot(sp, np.full(sp.size, top), "|", color=color, ms=8, label=label)
        ax.set_ylim(top=top)


#: near a stability edge a stable orbit's amplitude grows without bound (multiplier -> 1):
#: the amplitude axes of Figs. 5-7 stop at 50 mm
CAP = _mm(0.05)


def _cap_axis(ax, *dss):
    """Cut ``ax`` at :data:`CAP` where the sweeps' steady amplitudes reach beyond it (call
    before :func:`_mark_unstable`); returns the title's note on how far they reach."""
    top = float(np.nanmax([np.nanmax(_steady_mm(d)) for d in dss]))
    if not top > CAP:
        return ""
    ax.set_ylim(top=CAP)
    return f"axis cut at {CAP:g} mm; stable orbits at stability edges reach {top:.2g} mm"


def _shared_legend(axes):
    """Every panel's labelled marks once (handles by label)."""
    return {lb: h for x in axes for h, lb in zip(*x.get_legend_handles_labels())}


def fig01(R):
    """Fig. 1: the impact load D_imp of a roller on the span (Eqs. 2-2..2-4, Appendix I),
    step-averaged over three tooth periods (1b) and point values near one impact (1c), with
    the contact time pi/omega_d."""
    d1 = R.run("fig01_impact")
    fig, ax = plt.subplots(1, 2, figsize=(10, 3.6))
    ax[0].plot(_ms(d1.t_wide), d1.impact_load_wide)
    ax[0].set(xlabel="t [ms]", ylabel="D_imp [N] (step-averaged)", title="Fig. 1b: three tooth periods")
    ax[1].plot(_ms(d1.t_near), d1.impact_load_near)
    ax[1].axvline(_ms(float(d1.contact_time)), color="k", ls=":", label="pi/omega_d")
    ax[1].set(xlabel="t after impact [ms]", ylabel="D_imp [N]", title="Fig. 1c: near the impact")
    ax[1].legend()
    return fig


def fig03(R):
    """Fig. 3: the rigid four-bar at 300 rpm: driven sprocket speed (Eq. 2-7) and polygonal
    load D_pol (Eq. 2-10) over two tooth periods, one panel per driven tooth number."""
    d3 = R.run("fig03")
    fig, ax = plt.subplots(2, 3, figsize=(12, 5.5), sharex=True)
    for j, n2 in enumerate(d3.n2.values[np.argsort(d3.panel.values)]):   # panels a, b, c
        ax[0, j].plot(_ms(d3.t), d3.omega2.sel(n2=n2))
        ax[0, j].set(title=f"Fig. 3{'abc'[j]}: (n1, n2) = ({parameter(d3, 'n1'):g}, {n2})",
                     ylabel="omega_2 [rpm]")
        ax[1, j].plot(_ms(d3.t), d3.polygonal_load.sel(n2=n2))
        ax[1, j].set(xlabel="t [ms]", ylabel="D_pol [N]")
    return fig


def fig04(R):
    """Fig. 4: the elastic four-bar (Eqs. 2-11..2-23): polygonal load shapes at five speeds
    (4a-e) and the peak-to-peak load of the short and long span against speed with the
    resonances omega_c1, omega_c2; +-T_s marks the scale (the undamped four-bar's load
    reaches many times the static tension near its resonances)."""
    d4 = R.run("fig04_elastic")
    fig, ax = plt.subplots(1, 2, figsize=(11, 4))
    for i, w in enumerate(d4.case.values):
        ax[0].plot(d4.phase, d4.load_shape[i], label=f"{'abcde'[i]}: {w:.0f} rpm")
    ts4 = parameter(d4, "static_tension")
    pk4 = float(max(d4.peak_to_peak_short.max(), d4.peak_to_peak_long.max()))
    for sgn in (1, -1):
        ax[0].axhline(sgn * ts4, color="0.4", ls="--", lw=0.8,
                      label=f"+-T_s = {ts4:g} N" if sgn > 0 else None)
    amp4 = float(np.max(np.abs(d4.load_shape)))
    ax[0].set(xlabel="t / tooth period [1]", ylabel="D_pol [N]",
              title=f"Fig. 4a-e: load shapes\nup to +-{amp4 / 1e3:.3g} kN = {amp4 / ts4:.0f} x T_s")
    ax[0].legend(fontsize=7)
    ax[1].semilogy(d4.curve_speed, d4.peak_to_peak_short, label="k1 = AE/L_0 (short)")
    ax[1].semilogy(d4.curve_speed, d4.peak_to_peak_long, label="k2 = AE/(L_0 + p) (long)")
    ax[1].axhline(ts4, color="0.4", ls="--", lw=0.8, label=f"static tension T_s = {ts4:g} N")
    for v in (float(d4.omega_c1), float(d4.omega_c2)):
        ax[1].axvline(v, color="k", ls=":")
    ax[1].set(xlabel="omega_1 [rpm]", ylabel="peak-to-peak D_pol [N]",
              title=f"resonances omega_c1, omega_c2 (dotted): peak-to-peak up to {pk4 / 1e3:.3g} kN\n"
                    "(undamped: grows as the speed grid approaches them)")
    ax[1].legend(fontsize=8)
    for a in ax:
        a.title.set_fontsize(10)
    fig.tight_layout()
    return fig


def fig05(R):
    """Fig. 5: maximum steady transverse amplitude against speed, one panel per centre
    distance: the discrete-link span with length change (the verdicts) beside the paper's
    string model without and with periodic length change, with the speeds where the tooth
    frequency meets the Wickert-Mote frequencies of the short and the long span."""
    cds, plain = with_base(R, "fig05_plain_cd", "fig05_plain", "centre_distance")
    _, withl = with_base(R, "fig05_length_cd", "fig05_length", "centre_distance")
    _, withs = with_base(R, "fig05_length_string_cd", "fig05_length_string", "centre_distance")
    ppp5 = resolution(plain[0], "points_per_pitch")
    fig, ax = plt.subplots(len(cds), 1, figsize=(9, 2.6 * len(cds)), sharex=True)
    for a, cd, dp, dl, ds_ in zip(ax, cds, plain, withl, withs):
        a.semilogy(dp.speed, _steady_mm(dp), "-", color="0.55", lw=0.8,
                   label=f"string, {ppp5} points per pitch, without length change")
        a.semilogy(ds_.speed, _steady_mm(ds_), "--", color="0.55", lw=0.8,
                   label=f"string, {ppp5} points per pitch, with length change")
        a.semilogy(dl.speed, _steady_mm(dl), "-", color="tab:blue", lw=1.0,
                   label="discrete-link span, with length change (verdicts)")
        for k, v in enumerate(dl.resonance_speed_short.values):
            a.axvline(v, color="tab:green", ls=":", lw=0.7,
                      label="short span L_0: tooth = k-th string frequency" if k == 0 else None)
        for k, v in enumerate(dl.resonance_speed_long.values):
            a.axvline(v, color="tab:red", ls=":", lw=0.7,
                      label="long span L_0 + p: tooth = k-th string frequency" if k == 0 else None)
        cut5 = _cap_axis(a, dp, ds_, dl)
        a.set(ylabel="max |u| [mm]",
              title=f"Fig. 5: centre distance {cd:g} pitches" + (f" ({cut5})" if cut5 else ""))
        a.title.set_fontsize(9)
        _mark_unstable(a, dl, label="unstable (discrete span)")
        _mark_unstable(a, dp, label="unstable (string)", color="tab:orange")
        _mark_unstable(a, ds_, label=None, color="tab:orange")
    a.set_xlabel("omega_1 [rpm]")
    marks5 = _shared_legend(ax)
    ax[0].legend(marks5.values(), marks5.keys(), fontsize=7, loc="upper left",
                 bbox_to_anchor=(1.01, 1.0))
    fig.suptitle(f"discrete span (scene fig05_length): {convergence_note(R, 'fig05_length')}",
                 fontsize=9)
    fig.tight_layout()
    return fig


def fig06(R):
    """Fig. 6: maximum steady amplitude against speed around the 3rd and 4th resonance, one
    curve per moment of inertia I2 of the driven sprocket (discrete-link span, the
    verdicts), with the paper's string model at the scene's own I2."""
    i2s, d6 = with_base(R, "fig06_i2", "fig06_inertia", "driven_inertia")
    string6 = R.run("fig06_string")
    fig, ax = plt.subplots(figsize=(8, 3.8))
    lines6 = [ax.semilogy(d.speed, _steady_mm(d), label=f"discrete span, I2 = {v:g} kg m^2")[0]
              for v, d in zip(i2s, d6)]
    ax.semilogy(string6.speed, _steady_mm(string6), "--", color="0.45", lw=0.9,
                label=f"string, {resolution(string6, 'points_per_pitch')} points per pitch, "
                      f"I2 = {parameter(string6, 'driven_inertia'):g} kg m^2")
    cut6 = _cap_axis(ax, *d6, string6)
    for v, d, ln in zip(i2s, d6, lines6):
        _mark_unstable(ax, d, label=f"unstable, I2 = {v:g}: no steady amplitude"
                       if int(d.unstable.sum()) else None, color=ln.get_color())
    _mark_unstable(ax, string6, label="unstable (string)" if int(string6.unstable.sum()) else None,
                   color="0.45")
    for v in resonances_in_window(d6[0]):
        ax.axvline(v, color="k", ls=":", lw=0.7)
    ax.set(xlabel="omega_1 [rpm]", ylabel="max |u| [mm]",
           title="Fig. 6: effect of I2 (cd 20.25, length change)" + (f"; {cut6}" if cut6 else "")
                 + "\n"
                 f"discrete span: {convergence_note(R, 'fig06_inertia')}")
    ax.title.set_fontsize(9)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=2)
    fig.tight_layout()
    return fig


def fig07(R):
    """Fig. 7: maximum steady amplitude against speed, one panel per static tension T_s
    (high to low, the paper's order): instabilities appear as T_s falls.  Each panel counts
    the unstable speeds of the discrete-link span at every refinement level its verdict
    rows read; the paper's string model beside it at the scene's own T_s."""
    tss, d7 = with_base(R, "fig07_ts", "fig07_tension", "static_tension")
    # every level of every panel (the verdict rows read them all)
    levels7 = {lv: {parameter(x, "static_tension"): x for x in
                    [R.run("fig07_tension" + lv)] + R.study_runs("fig07_ts" + lv)}
               for lv in LEVEL_RUNS}
    string7 = R.run("fig07_string")
    fig, ax = plt.subplots(len(tss), 1, figsize=(8, 2.5 * len(tss)), sharex=True)
    for a, v, d in zip(ax, tss[::-1], d7[::-1]):          # the paper's order: high to low tension
        a.semilogy(d.speed, _steady_mm(d), label="discrete-link span (verdicts)")
        with_string = abs(v - parameter(string7, "static_tension")) < 1e-9
        if with_string:
            a.semilogy(string7.speed, _steady_mm(string7), "--", lw=0.9,
                       label=f"string, {resolution(string7, 'points_per_pitch')} points per pitch "
                             "(mixed, the paper's)")
        counts = " / ".join(str(int(levels7[lv][v].unstable.sum())) for lv in LEVEL_RUNS)
        steps = " / ".join(str(resolution(levels7[lv][v], "steps_per_period")) for lv in LEVEL_RUNS)
        a.set(ylabel="max |y| [mm]")
        _cap_axis(a, d, *([string7] if with_string else []))
        if with_string:
            _mark_unstable(a, string7, label="unstable (string)", color="tab:orange")
        _mark_unstable(a, d, label="unstable (discrete span)")
        a.set_title(f"Fig. 7: T_s = {v:g} N: unstable speeds {counts} at {steps} RK4 steps per "
                    "tooth period", fontsize=9)
    a.set_xlabel("omega_1 [rpm]")
    # one legend below the panels, clear of every curve
    marks7 = _shared_legend(ax)
    fig.legend(marks7.values(), marks7.keys(), fontsize=7, loc="lower center", ncol=2)
    fig.suptitle(f"discrete span (scene fig07_tension): {convergence_note(R, 'fig07_tension')}\n"
                 f"axes cut at {CAP:g} mm (stable orbits at stability edges)", fontsize=9)
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    return fig


def fig08(R):
    """Fig. 8: maximum steady amplitude against speed without external load (8a, the
    string model of the verdicts and the discrete-link span) and with T_ex = 0.2 T_s at
    omega_ex = 4, 2 and 1 x omega_1 (Eq. 2-5), the unloaded curve in grey behind each."""
    ws, d8 = with_base(R, "fig08_wex", "fig08_external", "external_frequency_ratio")
    base = R.run("fig08_none")
    disc8 = R.run("fig08_discrete")
    fig, ax = plt.subplots(len(d8) + 1, 1, figsize=(8, 2.3 * (len(d8) + 1)), sharex=True)
    ax[0].semilogy(base.speed, _steady_mm(base),
                   label=f"string, {resolution(base, 'points_per_pitch')} points per pitch (verdicts)")
    ax[0].semilogy(disc8.speed, _steady_mm(disc8), lw=0.9,
                   label="discrete-link span (no external load: table discrete_peaks)")
    _mark_unstable(ax[0], base, label="unstable (string)")
    _mark_unstable(ax[0], disc8, label="unstable (discrete span)", color="tab:orange")
    ax[0].set(title="; ".join(s for s in ("Fig. 8a: without external load",
                                         convergence_note(R, "fig08_none")) if s),
              ylabel="max |u| [mm]")
    ax[0].legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    for a, w, d in zip(ax[1:], ws[::-1], d8[::-1]):       # 4, 2, 1
        a.semilogy(base.speed, _steady_mm(base), color="0.7", lw=0.8)
        a.semilogy(d.speed, _steady_mm(d))
        _mark_unstable(a, d)
        a.set(title=f"Fig. 8: T_ex = 0.2 T_s, omega_ex = {w:g} omega_1", ylabel="max |u| [mm]")
    a.set_xlabel("omega_1 [rpm]")
    for a in ax:
        log_ticks(a.yaxis)
    return fig


def fig09(R):
    """Fig. 9: medium speed with the elastic four-bar, each drive swept over 0.25-1.25 x its
    own resonance omega_c: the steady amplitude where the periodic state is stable, and the
    speeds of Floquet growth, of growth in a mode shorter than the string model holds, and
    of a slack span (:func:`stability_classes`)."""
    fig, ax = plt.subplots(2, 1, figsize=(8, 5.5))
    for a, name, lab in ((ax[0], "fig09a", "(a) n1 = n2 = 24, I2 = 0.002"),
                         (ax[1], "fig09b", "(b) n1 = 15, n2 = 40, I2 = 0.0005")):
        d = R.run(name)
        sp = d.speed.values
        k = stability_classes(d)
        grow, out, sl = k["growth"], k["outside"], k["slack"]
        # steady amplitude only where the periodic state is stable (an unstable periodic
        # orbit, or a slack span outside the string model, has no steady amplitude to draw)
        a.semilogy(sp, np.where(k["stable"], _mm(d.amplitude), np.nan), lw=1,
                   label="stable: steady max |u|")
        ymin, ymax = a.get_ylim()
        if grow.any():
            a.plot(sp[grow], np.full(grow.sum(), ymax), "r|", ms=10,
                   label="growth: Floquet multiplier > 1" if "growth_rate" in d else "growth")
        # growth the string model cannot claim: its growing mode is shorter than a string of
        # links can carry (drawn apart from growth, like slack)
        if out.any():
            a.plot(sp[out], np.full(out.sum(), ymax), "v", mfc="none", color="0.35", ms=5,
                   label=f"growth in a mode shorter than {parameter(d, 'valid_wavelength'):g} "
                         "pitches: outside the string model")
        if sl.any():
            a.plot(sp[sl], np.full(sl.sum(), ymin), "|", color="0.5", ms=10,
                   label="slack (P + P_t <= 0): string model invalid")
        a.axvline(float(d.elastic_resonance_speed), color="k", ls=":", lw=0.8, label="omega_c")
        outside_note = f", {int(out.sum())} outside the string model" if out.any() else ""
        a.set(title=f"Fig. 9{lab}: {int(grow.sum())} growing{outside_note}, {int(sl.sum())} "
                    f"slack of {sp.size} speeds\n{convergence_note(R, name)}",
              ylabel="max |u| [mm]", xlabel="omega_1 [rpm]")
        a.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.tight_layout()
    return fig


def fig10(R):
    """Fig. 10: high speed, Galerkin (Eqs. 2-39..2-41) with RK4: the transverse response at
    L/3 with and without longitudinal coupling, 5 % below the first longitudinal resonance
    (10a: exactly at it the undamped longitudinal response has no steady state) and at the
    fifth transverse resonance (10b), with the coupled/uncoupled ratio over the mode study."""
    fig, ax = plt.subplots(2, 1, figsize=(9, 6))
    for a, (coupled, uncoupled, head) in zip(ax, (
            ("fig10_longitudinal", "fig10_uncoupled",
             "Fig. 10a: near the first longitudinal resonance ({:.0f} rpm, {:g} x)"),
            ("fig10_transverse5", "fig10_transverse5_uncoupled",
             "Fig. 10b: fifth transverse resonance ({:.0f} rpm)"))):
        dc, du = R.run(coupled), R.run(uncoupled)
        a.plot(_ms(dc.t), _mm(dc.u_probe_rk4), lw=0.6, label="coupled, RK4")
        a.plot(_ms(du.t), _mm(du.u_probe_rk4), lw=0.6, alpha=0.7, label="uncoupled, RK4")
        a.set(ylabel="u(L/3) [mm]")
        a.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
        # the drawn mode count, its RK4 cost and the coupled/uncoupled ratio over the mode study
        cost = float(dc.rk4_wall_time) + float(du.rk4_wall_time)
        ratios = ", ".join(f"{k}: {v:.3g}" for k, v in mode_ratios(R, coupled, uncoupled).items())
        a.set_title(head.format(float(dc.speed), float(dc.detuning))
                    + f"\n{drawn_modes(R, coupled)} transverse modes ({cost:.1f} s of RK4 for "
                    f"the pair); coupled/uncoupled by modes {ratios}", fontsize=8)
    ax[1].set(xlabel="t [ms]")
    fig.tight_layout()
    return fig


def chart_tension(R):
    """Beyond the paper: the largest Floquet multiplier of the discrete-link span's tooth
    period map over speed and static tension, the design message of Fig. 7 (how low a
    static tension a drive may run at) as a map, with Fig. 7's tensions dotted."""
    tss, _ = with_base(R, "fig07_ts", "fig07_tension", "static_tension")
    tsc, dc = with_base(R, "chart_tension_ts", "chart_tension", "static_tension")
    sp_c = dc[0].speed.values
    rho_c = np.array([d.growth.values for d in dc])
    fig, ax = plt.subplots(figsize=(8, 4))
    mesh = ax.pcolormesh(sp_c, tsc, rho_c, shading="nearest", cmap="viridis",
                         vmin=float(np.nanmin(rho_c)), vmax=max(1.0, float(np.nanmax(rho_c))))
    if len(tsc) > 1 and np.nanmax(rho_c) > 1 > np.nanmin(rho_c):
        ax.contour(sp_c, tsc, rho_c, levels=[1.0], colors="r", linewidths=1.2)
    for v in tss:
        ax.axhline(v, color="w", ls=":", lw=0.8)
    fig.colorbar(mesh, ax=ax, label="largest Floquet multiplier [1]")
    un_c = int(np.sum(rho_c > 1))
    ax.set(xlabel="omega_1 [rpm]", ylabel="static tension T_s [N]",
           title=f"discrete span, {resolution(dc[0], 'steps_per_period')} RK4 steps per tooth "
                 f"period: {un_c} of {rho_c.size} (speed, T_s) unstable (red: multiplier 1)")
    ax.title.set_fontsize(9)
    fig.tight_layout()
    return fig


def exact_checks(R):
    """Verification of the FD scheme (ours): error against the exact free vibration of the
    moving string (Wickert & Mote 1990) and against a manufactured solution over the grid,
    both differencing schemes, and the first frequency against Wickert-Mote."""
    ef, mms = R.run("exact_free"), R.run("manufactured")
    fig, ax = plt.subplots(1, 2, figsize=(10, 3.8))
    for dname, mk in (("central", "o-"), ("mixed", "s-")):
        ax[0].loglog(ef.points, ef.error_max.sel(differencing=dname), mk,
                     label=f"exact mode, {dname}")
        ax[0].loglog(mms.points, mms.error_max.sel(differencing=dname), mk.replace("-", "--"),
                     label=f"manufactured, {dname}")
        ax[1].loglog(ef.points, np.abs(ef.omega_fd.sel(differencing=dname).values
                                       / float(ef.omega_exact) - 1), mk, label=dname)
    ax[0].set(xlabel="grid intervals [1]", ylabel="max error [m]",
              title="convergence (exact mode at c = 0.5 c_w)")
    ax[0].legend(fontsize=7)
    ax[1].set(xlabel="grid intervals [1]", ylabel="|omega_FD / omega_WM - 1| [1]",
              title="first frequency vs Wickert-Mote")
    ax[1].legend(fontsize=7)
    return fig


def cost_of_accuracy(R):
    """Cost of accuracy, one panel per entry of the config's ``accuracy:`` block (the
    framework's table, drawn by :func:`mechrepro.accuracy.plot`): error against the finest
    run vs wall time for points per pitch, CFL number, the string against the discrete-link
    span, transverse modes and the exact moving-string mode."""
    coa = R.table("cost_of_accuracy")
    entries = list(dict.fromkeys(r["accuracy"] for r in coa))
    rows_c = -(-len(entries) // 3)
    fig, ax = plt.subplots(rows_c, 3, figsize=(15, 4 * rows_c))
    for a, entry in zip(ax.ravel(), entries):
        accuracy.plot(coa, entry, ax=a)   # an unproven reference is drawn NOT CONVERGED, with why
        log_ticks(a.yaxis)                # a short log axis: no crowded minor labels
    for a in ax.ravel()[len(entries):]:
        a.set_axis_off()
    fig.tight_layout()
    return fig
