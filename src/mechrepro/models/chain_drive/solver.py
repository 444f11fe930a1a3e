"""The solvers of chain_drive (``SOLVERS``, each ``solver(run, ctx)`` returning labelled
variables; the paper has no run-wide context, so ``ctx`` is None).

The solvers and the effects each honours are declared in ``config/papers/chain_drive.yaml``
(a scene naming an effect its solver does not honour is refused when the config is
loaded).  Every solver builds a :class:`.effects.SpanContext` per case, asks ``EFFECTS`` for the
contributions by key (``evaluate``, or ``stages`` where some fix the grid of others) and
reads them by key; none reads an effect's name.

``impact_load`` (Fig. 1), ``rigid_four_bar`` (Fig. 3), ``elastic_four_bar`` (Fig. 4),
``speed_sweep`` (Figs. 5-9: maximum steady amplitude vs operating speed, one vectorised FD
computation, shooting, or the discrete-link span of :mod:`.discrete`), ``galerkin`` (Fig. 10, :func:`.galerkin.solve_scene`), ``impact_timestep`` (Sec. 3.1), ``exact_free`` and
``manufactured`` (independent checks of the FD scheme).  Speeds in the datasets are in
rpm; everything else SI.
"""
from __future__ import annotations

import numpy as np
from scipy.integrate import quad

from mechrepro.timing import phase
from mechrepro.units import var

from . import claims, discrete, exact, four_bar, galerkin, geometry, loads, shooting, span, timestep
from .effects import EFFECTS, SpanContext, declared_keys, refuse_unhonoured
from .geometry import RPM


def _contributions(run, ctx, keys, solver):
    """Every named effect on ``ctx`` (a figure's own time grid), after refusing those that
    declare a key the solver does not consume."""
    refuse_unhonoured(run, keys, solver)
    return EFFECTS.evaluate(run, ctx)


def sweep_geometry(prm, tension_coefficient, geo, res, omega1, wc, slack) -> dict:
    """What every speed sweep writes beside its amplitudes: the speeds where the tooth
    frequency meets the k-th moving-string frequency (Wickert-Mote) of the short, long and
    mean span (orders 1 .. ``res["orders"]``), with P = T_s + k c^2 (k: the tension
    coefficient), the span lengths, the drive's elastic four-bar resonance (nan outside a
    speed_window_elastic) and the slack speeds."""
    orders = np.arange(1, int(res.get("orders", 8)) + 1)
    kw = dict(n1=int(prm["n1"]), p_c=prm["pitch"], T_s=prm["static_tension"],
              m=prm["mass_per_length"], tension_coefficient=tension_coefficient)
    out = {f"resonance_speed_{name}": var(
        "order", np.array([geometry.resonance_speed(k, geo[L], **kw) for k in orders]) * RPM,
        "rpm", f"tooth frequency = k-th moving-string frequency, {what}")
        for name, L, what in (("short", "L_short", "short span"), ("long", "L_long", "long span"),
                              ("mean", "L_ct", "span L_ct"))}
    return {**out,
            "L_short": var((), geo["L_short"], "m", "short span length L_0"),
            "L_long": var((), geo["L_long"], "m", "long span length"),
            "fractional_pitch": var((), geo["f_p"], "1", "fractional pitch f_p, Eq. (2-6)"),
            "elastic_resonance_speed": var((), np.nan if wc is None else wc * RPM, "rpm",
                                           "omega_c of the drive's elastic four-bar (k = AE/L_ct)"),
            "speed": var("speed", omega1 * RPM, "rpm", "driving sprocket speed omega_1"),
            "order": var("order", orders, "1", "resonance order k"),
            "slack": var("speed", slack.astype("i1"), "1", "1 where P + P_t <= 0 somewhere")}


# ---------------------------------------------------------------------------- Figs. 1, 3, 4

def impact_load(run, ctx=None):
    """Fig. 1: the tension contributed at 300 rpm near one impact (point values) and over
    three tooth periods (step-averaged), with the impact model's closed-form checks."""
    prm, res = run["parameters"], run["resolution"]
    w1, n1, p = prm["speed"], int(prm["n1"]), prm["pitch"]
    k = loads.impact_of(prm)
    tau = float(geometry.tooth_period(w1, n1))
    n = int(res["samples"])
    t_near, t_wide = np.linspace(0, 1.5 * k["t_i"], n), np.linspace(0, 3 * tau, n)
    geo = geometry.span_geometry(prm, False)
    near, wide = (span.dynamic_tension(_contributions(run, SpanContext(prm, [w1], t, step, geo),
                                                      ("tension_pulse",), "impact_load"),
                                       (n, 1))[:, 0]
                  for t, step in ((t_near, None), (t_wide, t_wide[1] - t_wide[0])))
    V, eta = loads.relative_velocity(w1, p), loads.pressure_angle(n1)
    J_quad = quad(lambda s: float(loads.impact_pulse(s, V, eta, k)), 0, k["t_i"], limit=200)[0]
    J_exact = float(loads.impact_pulse_integral(np.inf, V, eta, k))
    return {
        "impact_load_near": var("t_near", near, "N", "impact load D_imp near the impact, Eq. (2-4)"),
        "impact_load_wide": var("t_wide", wide, "N", "impact load over three tooth periods (step-averaged)"),
        "contact_time": var((), k["t_i"], "s", "contact duration pi/omega_d (Appendix I)"),
        "impact_peak": var((), near.max(), "N", "peak impact load"),
        "impulse_quadrature": var((), J_quad, "N*s", "impulse of one impact by quadrature of Eq. (2-4)"),
        "impulse_closed_form": var((), J_exact, "N*s", "impulse of one impact in closed form"),
        "pressure_angle": var((), np.rad2deg(eta), "deg", "angle eta, Eq. (2-3) from ANSI tooth form"),
        "t_near": var("t_near", t_near, "s", "time after impact"),
        "t_wide": var("t_wide", t_wide, "s", "time")}


def rigid_four_bar(run, ctx=None):
    """Fig. 3: driven speed and the contributed tension (D_pol) over two tooth periods at
    ``speed``, one case per driven tooth number in ``options.cases`` (default: n2), and the
    peak load at 0.5, 1 and 2 x ``speed``."""
    prm, res = run["parameters"], run["resolution"]
    n1 = int(prm["n1"])
    panels = [int(x) for x in run.get("options", {}).get("cases", [prm["n2"]])]
    cases = sorted(panels)   # a CF dimension coordinate is monotonic; the panel is kept beside
    w1, samples = prm["speed"], int(res["samples"])
    t = np.linspace(0, 2 * float(geometry.tooth_period(w1, n1)), samples)
    speeds = w1 * np.array([0.5, 1.0, 2.0])
    t_check = np.stack([np.linspace(0, 2 * float(geometry.tooth_period(w, n1)), samples)
                        for w in speeds], axis=1)
    keys = ("tension", "u_left", "u_right")
    out = {"omega2": [], "polygonal_load": [], "u_left": [], "peak_load_by_speed": []}
    for n2 in cases:
        p2 = {**prm, "n2": n2}
        geo = geometry.span_geometry(p2, True)
        ctx = SpanContext(p2, [w1], t, None, geo)
        c = _contributions(run, ctx, keys, "rigid_four_bar")
        out["omega2"].append(ctx.kinematics["omega2"][:, 0] * RPM)
        out["polygonal_load"].append(c.total("tension", np.zeros((samples, 1)))[:, 0])
        if "u_left" in c:
            out["u_left"].append(c.get("u_left")[:, 0])
        check = _contributions(run, SpanContext(p2, speeds, t_check, None, geo), keys,
                               "rigid_four_bar").total("tension", np.zeros(t_check.shape))
        out["peak_load_by_speed"].append(np.max(np.abs(check), axis=0))
    data = {
        "omega2": var(("n2", "t"), out["omega2"], "rpm", "driven sprocket speed omega_2, Eq. (2-7)"),
        "polygonal_load": var(("n2", "t"), out["polygonal_load"], "N", "dynamic load D_pol, Eq. (2-10)"),
        "peak_load_by_speed": var(("n2", "check_speed"), out["peak_load_by_speed"], "N",
                                  "max |D_pol| at the check speeds"),
        "panel": var("n2", np.array([panels.index(n) for n in cases], dtype=np.int32), "1",
                     "panel of Fig. 3 (0 = a, 1 = b, 2 = c) in the order of options.cases"),
    }
    if out["u_left"]:
        data["u_left"] = var(("n2", "t"), out["u_left"], "m",
                             "driven-end transverse displacement u_0, Eq. (2-25)")
    return {**data, "t": var("t", t, "s", "time"),
            "n2": var("n2", cases, "1", "driven sprocket tooth number"),
            "check_speed": var("check_speed", speeds * RPM, "rpm", "check speed")}


def elastic_four_bar(run, ctx=None):
    """Fig. 4: the elastic four-bar load (contributions ``tension_short``/``tension_long``,
    switched by the span-length state ``long``) below, at, between, at and above its two
    resonances, and its peak-to-peak value over a speed window for k1 and k2."""
    prm, res = run["parameters"], run["resolution"]
    n1 = int(prm["n1"])
    geo = geometry.span_geometry(prm, True)
    wc_short, wc_long = (four_bar.omega_c(prm, geo[L]) for L in ("L_short", "L_long"))
    # the paper's omega_c1 < omega_c2: the long (softer) span resonates first
    wc1, wc2 = min(wc_short, wc_long), max(wc_short, wc_long)
    window = run.get("options", {}).get("speed_window_elastic")
    lo, hi = four_bar.elastic_speed_window(prm, window) if window else (prm["speed_min"], prm["speed_max"])
    curve_w = np.linspace(lo, hi, int(res["n_speeds"]))
    keys = ("tension_short", "tension_long", "long")
    cache: dict = {}
    t_curve = np.stack([np.linspace(0, float(geometry.tooth_period(w, n1)), 64, endpoint=False)
                        for w in curve_w], axis=1)
    curve = _contributions(run, SpanContext(prm, curve_w, t_curve, None, geo, cache=cache), keys,
                           "elastic_four_bar")
    cases = np.array([0.6 * wc1, wc1, 0.5 * (wc1 + wc2), wc2, 1.4 * wc2])
    s = np.linspace(0, 2, int(res["samples"]))   # time in tooth periods
    t_cases = np.stack([s * float(geometry.tooth_period(w, n1)) for w in cases], axis=1)
    shapes = span.dynamic_tension(_contributions(run, SpanContext(prm, cases, t_cases, None, geo,
                                                                  cache=cache),
                                                 keys, "elastic_four_bar"), t_cases.shape)
    return {
        "load_shape": var(("case", "phase"), shapes.T, "N",
                          "elastic four-bar D_pol with the span-length switch, Eq. (2-22)"),
        "peak_to_peak_short": var("curve_speed", np.ptp(curve.get("tension_short"), axis=0), "N",
                                  "peak-to-peak D_pol, k1 = AE/L_0"),
        "peak_to_peak_long": var("curve_speed", np.ptp(curve.get("tension_long"), axis=0), "N",
                                 "peak-to-peak D_pol, k2 = AE/(L_0+p)"),
        "omega_c1": var((), wc1 * RPM, "rpm", "first resonance of the elastic four-bar (long span)"),
        "omega_c2": var((), wc2 * RPM, "rpm", "second resonance of the elastic four-bar (short span)"),
        "case": var("case", cases * RPM, "rpm", "driving speed of Fig. 4 case"),
        "phase": var("phase", s, "1", "time in tooth periods"),
        "curve_speed": var("curve_speed", curve_w * RPM, "rpm", "driving speed")}


# ---------------------------------------------------------------------------- Figs. 5-9

def dense_near_elastic(run, prm, omega1, half_width: float, n_speeds: int) -> np.ndarray:
    """The speed axis with n_speeds // 3 extra speeds within +-half_width (relative) of each
    elastic four-bar resonance omega_c = r2 sqrt(k/I2)/n1 (k = AE/L of the short and long
    span) inside the sweep.  Why: the undamped elastic D_pol (Eqs. 2-11..2-23) peaks there,
    so the parametric (Mathieu) bands it pumps cluster there and are narrow, narrower than a
    uniform grid's step.  The dense count scales with n_speeds, so refining n_speeds refines
    it too."""
    geo = geometry.span_geometry(prm, "long" in declared_keys(run))
    extra = [omega1]
    for L in sorted({geo["L_short"], geo["L_long"]}):
        wc = four_bar.omega_c(prm, L)
        if omega1[0] <= wc <= omega1[-1]:
            extra.append(np.linspace(wc * (1 - half_width), wc * (1 + half_width),
                                     max(3, n_speeds // 3)))
    return np.unique(np.concatenate(extra))


def speed_sweep(run, ctx=None) -> dict:
    """Figs. 5-9: maximum steady amplitude vs operating speed, one vectorised FD march
    (:func:`.span.sweep`) or shooting per speed (:func:`.shooting.sweep`), with the
    moving-string resonance speeds of the span."""
    prm, res = run["parameters"], run["resolution"]
    window = run.get("options", {}).get("speed_window_elastic")
    wc = None
    if window:
        prm = dict(prm)
        prm["speed_min"], prm["speed_max"] = four_bar.elastic_speed_window(prm, window)
        wc = prm["speed_max"] / window[1]
    omega1 = span.speed_axis(prm, int(res["n_speeds"]))
    dense = run.get("options", {}).get("dense_near_elastic")
    if dense:
        omega1 = dense_near_elastic(run, prm, omega1, float(dense), int(res["n_speeds"]))
    if res.get("method") == "discrete":
        return discrete_sweep(run, prm, omega1, res, wc)
    shooting_ = res.get("method", "march") == "shooting"
    with phase("chain_drive.speed_sweep") as sw:
        if shooting_:
            out = shooting.sweep(run, prm, omega1, res)
            omega1 = out["omega1"]
        else:
            out = span.sweep(run, prm, omega1, res)
    data = {
        **sweep_geometry(prm, out["tension_coefficient"], out["span"], res, omega1, wc,
                         out["slack"]),
        "amplitude": var("speed", out["amplitude"], "m", "maximum steady transverse amplitude"),
        "growth": var("speed", np.minimum(out["growth"], 1e300), "1",
                      "spectral radius of the one-period monodromy matrix (Floquet multiplier); "
                      "nan where only bounded (rho_lower/rho_upper) or slack"
                      if shooting_ else
                      "ratio of last to first block maximum in the measuring window"),
        "unstable": var("speed", out["unstable"].astype("i1"), "1",
                        "1 where the response grows (Mathieu instability) or the span goes slack"),
        "n_steps": var((), out["n_steps"], "1", "number of time steps"),
        "n_points": var((), out["grid"].n_long + 1, "1", "grid points of the long span")}
    steps = run.get("options", {}).get("discrete_reference")
    if steps:
        ref = discrete.sweep(run, prm, omega1, {"steps_per_period": steps})["amplitude"]
        data["amplitude_discrete"] = var("speed", ref, "m", f"the discrete-link span's periodic "
                                         f"amplitude at the same speeds ({steps} RK4 steps per "
                                         "tooth period): the reference of the string's cost of "
                                         "accuracy")
        data["string_time"] = var((), sw.seconds, "s", "wall time of the string sweep alone")
        # the errors are the run's own: a shooting sweep's speed axis is its own per run
        (s_s, a_s), (s_d, a_d) = (claims.one_mode_peak(omega1 * RPM, a)
                                  for a in (out["amplitude"], ref))
        data["peak_amplitude_vs_discrete"] = var((), abs(a_s / a_d - 1.0), "1",
                                                 "|string peak amplitude / discrete span's - 1| "
                                                 "(one-mode vertex of each)")
        data["peak_speed_vs_discrete"] = var((), abs(s_s / s_d - 1.0), "1",
                                             "|string peak speed / discrete span's - 1|")
    if shooting_:
        data["sampling_converged"] = var((), int(out["sampling_converged"]), "1",
                                         "1 when the adaptive speed bisection finished (edges "
                                         "and peaks at edge_tol/peak_tol)")
        data["growth_rate"] = var("speed", out["growth_rate"], "1/s",
                                  "Floquet growth rate log(rho)/T of the span")
        data["rho_lower"] = var("speed", out["rho_lower"], "1",
                                "proven lower bound of rho (= rho where computed): |tr M^K|/n "
                                "<= rho^K; > 1 proves growth")
        data["rho_upper"] = var("speed", out["rho_upper"], "1",
                                "proven upper bound of rho (= rho where computed): rho^K <= "
                                "||M^K||_F; below exp(-sigma T/2) proves a stable speed")
        wl = out["mode_wavelength"] / prm["pitch"]
        limit = float(prm["valid_wavelength"])   # pitches (assumed: the config says why)
        data["critical_mode_wavelength"] = var(
            "speed", wl, "1", "wavelength of the growing Floquet mode in pitches (nan where "
            "the span does not grow)")
        data["outside_validity"] = var(
            "speed", (out["unstable"] & (wl < limit)).astype("i1"),
            "1", f"1 where the span grows in a Floquet mode shorter than "
            f"{limit:g} pitches: outside the string model's "
            "validity (a chain of rigid links has no such mode); still counted as growth")
    return data


def discrete_sweep(run, prm, omega1, res, wc=None) -> dict:
    """Figs. 5-8 on the discrete-link span (:func:`.discrete.sweep`): per speed the periodic
    orbit's amplitude and largest Floquet multiplier of the tooth-period map, with the
    moving-string resonance speeds of the span (the string's, for comparison)."""
    out = discrete.sweep(run, prm, omega1, res)
    geo = geometry.span_geometry(prm, "long" in declared_keys(run))
    steps = int(res["steps_per_period"])
    return {
        **sweep_geometry(prm, discrete.tension_coefficient(run, prm), geo, res, out["omega1"], wc,
                         out["slack"]),
        "amplitude": var("speed", out["amplitude"], "m",
                         "maximum transverse roller amplitude of the periodic orbit"),
        "growth": var("speed", out["rho"], "1", "largest Floquet multiplier of the tooth-period "
                      "map of the discrete span (rollers relabelled)"),
        "unstable": var("speed", out["unstable"].astype("i1"), "1",
                        "1 where a Floquet multiplier exceeds 1 or a link goes slack"),
        "sampling_converged": var((), int(out["sampling_converged"]), "1",
                                  "1 when the adaptive speed refinement finished"),
        "n_steps": var((), steps, "1", "RK4 steps per tooth period"),
        "n_points": var((), out["n_rollers"] + 2, "1", "rollers of the short span, ends included")}


# ---------------------------------------------------------------------------- Sec. 3.1, checks

def impact_timestep(run, ctx=None):
    """Sec. 3.1: the non-uniform step refined near impacts vs uniform steps (error, wall time)."""
    prm, res = run["parameters"], run["resolution"]
    out = timestep.compare(run, prm, res)
    names = ["uniform_sampled", "uniform_averaged", "nonuniform", "uniform_equal_accuracy"]
    return {
        "error": var("strategy", [out[n]["error"] for n in names], "1",
                     "max |u_mid - u_ref| / max |u_ref| against a fine uniform reference"),
        "march_wall_time": var("strategy", [out[n]["wall"] for n in names], "s", "wall time of the march"),
        "steps": var("strategy", [out[n]["steps"] for n in names], "1", "number of time steps"),
        "dt_max": var((), out["dt_max"], "s", "von Neumann limit step (x cfl)"),
        "dt_min": var((), out["dt_min"], "s", "smallest step of the non-uniform scheme"),
        "dt_equal_accuracy": var((), out["uniform_equal_accuracy"]["dt"], "s",
                                     "uniform step reaching the non-uniform accuracy"),
        "contact_time": var((), out["contact_time"], "s", "impact contact time pi/omega_d"),
        "strategy": var("strategy", names, "1", "time-step strategy")}


SOLVERS = {"impact_load": impact_load, "rigid_four_bar": rigid_four_bar,
           "elastic_four_bar": elastic_four_bar, "speed_sweep": speed_sweep,
           "galerkin": galerkin.solve_scene, "impact_timestep": impact_timestep,
           "exact_free": lambda run, ctx: exact.free_vibration_check(run["parameters"],
                                                                     run["resolution"]),
           "manufactured": lambda run, ctx: exact.manufactured_check(run["parameters"],
                                                                     run["resolution"])}


def warm(runs=None) -> None:
    """Load the compiled loops ``runs`` use (both without them) once per solver process
    (the runner calls this before the first timed solve), so that no run's time carries
    numba's start: the Galerkin RK4 for a galerkin run, the lane march and the excitation's
    per-sample loops for any other (a job of march sweeps does not compile the RK4 on a
    fresh machine)."""
    from . import fd_kernel, galerkin_kernel, samples

    solvers = None if runs is None else {r.get("solver") for r in runs}
    if solvers is None or solvers - {"galerkin"}:
        fd_kernel.warm()
        if samples.available():   # the excitation's per-sample loops, on a tiny block
            t, w = np.linspace(0.0, 1e-3, 3)[:, None], np.array([[50.0, 60.0]])
            four_bar.rigid_kinematics(t, w, n1=19, n2=38, p_c=0.0127, f_p=0.3)
            loads.impact_load(t, w, 19, 0.0127, loads.impact_constants(0.02, 2e8, 0.1), step=1e-4)
    if solvers is None or "galerkin" in solvers:
        galerkin_kernel.warm()


def variables(result: dict, run: dict | None = None) -> dict:
    """The run's variables: its solver already returns them."""
    return result
