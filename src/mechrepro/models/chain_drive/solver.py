"""``solve(run) -> xarray.Dataset``: the scene's ``solver`` computes, its effects are the physics.

The solvers and the effects each honours are declared in ``config/papers/chain_drive.yaml``
(a scene naming an effect its solver does not honour is refused when the config is
loaded).  Every solver builds a :class:`.effects.SpanContext`, calls ``EFFECTS.evaluate``
and reads the contributions by key; none reads an effect's name.

``impact_load`` (Fig. 1), ``rigid_four_bar`` (Fig. 3), ``elastic_four_bar`` (Fig. 4),
``speed_sweep`` (Figs. 5-9: maximum steady amplitude vs operating speed, one vectorised FD
computation), ``galerkin`` (Fig. 10), ``impact_timestep`` (Sec. 3.1), ``exact_free`` and
``manufactured`` (independent checks of the FD scheme).  Speeds in the datasets are in
rpm; everything else SI.
"""
from __future__ import annotations

import math

import numpy as np
import xarray as xr
from scipy.integrate import quad
from scipy.optimize import brentq

from mechrepro.timing import stopwatch
from mechrepro.units import var

from . import exact, four_bar, galerkin, geometry, loads, span, timestep
from .effects import EFFECTS, SpanContext, consume

RPM = 30.0 / math.pi   # rad/s -> rpm


def _coord(name, values, units, long_name):
    return {name: var(name, values, units, long_name)}


def _contributions(run, ctx, keys, solver):
    return consume(EFFECTS.evaluate(run, ctx), keys, solver)


def resonance_table(prm, tension_coefficient, span_geo, orders) -> dict:
    """Speeds where the tooth frequency meets the k-th moving-string frequency (Wickert-Mote)
    of the short, long and mean span, with P = T_s + k c^2 (k: the tension coefficient)."""
    kw = dict(n1=int(prm["n1"]), p_c=prm["pitch"], T_s=prm["static_tension"],
              m=prm["mass_per_length"], tension_coefficient=tension_coefficient)
    return {name: np.array([geometry.resonance_speed(k, span_geo[name], **kw) for k in orders])
            for name in ("L_short", "L_long", "L_ct")}


# ---------------------------------------------------------------------------- Figs. 1, 3, 4

def impact_load(run, prm, res):
    """Fig. 1: the tension contributed at 300 rpm near one impact (point values) and over
    three tooth periods (step-averaged), with the impact model's closed-form checks."""
    w1, n1, p = prm["speed"], int(prm["n1"]), prm["pitch"]
    k = loads.impact_constants(prm["impact_mass_links"] * p * prm["mass_per_length"],
                               prm["contact_stiffness"], prm["contact_damping_ratio"])
    tau = float(geometry.tooth_period(w1, n1))
    n = int(res["samples"])
    t_near, t_wide = np.linspace(0, 1.5 * k["t_i"], n), np.linspace(0, 3 * tau, n)
    geo = span.span_geometry(prm, False)
    near, wide = (_contributions(run, SpanContext(prm, [w1], t, step, geo), ("tension",),
                                 "impact_load").total("tension", np.zeros((n, 1)))[:, 0]
                  for t, step in ((t_near, None), (t_wide, t_wide[1] - t_wide[0])))
    V, eta = loads.relative_velocity(w1, p), loads.pressure_angle(n1)
    J_quad = quad(lambda s: float(loads.impact_pulse(s, V, eta, k)), 0, k["t_i"], limit=200)[0]
    J_exact = float(loads.impact_pulse_integral(np.inf, V, eta, k))
    return xr.Dataset({
        "impact_load_near": var("t_near", near, "N", "impact load D_imp near the impact, Eq. (2-4)"),
        "impact_load_wide": var("t_wide", wide, "N", "impact load over three tooth periods (step-averaged)"),
        "contact_time": var((), k["t_i"], "s", "contact duration pi/omega_d (Appendix I)"),
        "tooth_period": var((), tau, "s", "tooth period 2 pi/(n1 omega1)"),
        "impact_peak": var((), near.max(), "N", "peak impact load"),
        "impulse_quadrature": var((), J_quad, "N*s", "impulse of one impact by quadrature of Eq. (2-4)"),
        "impulse_closed_form": var((), J_exact, "N*s", "impulse of one impact in closed form"),
        "pressure_angle": var((), np.rad2deg(eta), "deg", "angle eta, Eq. (2-3) from ANSI tooth form"),
    }, coords={**_coord("t_near", t_near, "s", "time after impact"),
               **_coord("t_wide", t_wide, "s", "time")})


def rigid_four_bar(run, prm, res):
    """Fig. 3: driven speed and the contributed tension (D_pol) over two tooth periods at
    ``speed``, one case per driven tooth number in ``options.cases`` (default: n2), and the
    peak load at 0.5, 1 and 2 x ``speed``."""
    n1 = int(prm["n1"])
    panels = [int(x) for x in run.get("options", {}).get("cases", [prm["n2"]])]
    cases = sorted(panels)   # a CF dimension coordinate is monotonic; the panel is kept beside
    w1, samples = prm["speed"], int(res["samples"])
    t = np.linspace(0, 2 * float(geometry.tooth_period(w1, n1)), samples)
    speeds = w1 * np.array([0.5, 1.0, 2.0])
    t_check = np.stack([np.linspace(0, 2 * float(geometry.tooth_period(w, n1)), samples)
                        for w in speeds], axis=1)
    keys = ("tension", "u_left", "u_right")
    out = {"omega2": [], "polygonal_load": [], "u_left": [], "peak_load_by_speed": [],
           "fractional_pitch": []}
    for n2 in cases:
        p2 = {**prm, "n2": n2}
        geo = span.span_geometry(p2, True)
        ctx = SpanContext(p2, [w1], t, None, geo)
        c = _contributions(run, ctx, keys, "rigid_four_bar")
        out["omega2"].append(ctx.kinematics["omega2"][:, 0] * RPM)
        out["polygonal_load"].append(c.total("tension", np.zeros((samples, 1)))[:, 0])
        if "u_left" in c:
            out["u_left"].append(c.get("u_left")[:, 0])
        check = _contributions(run, SpanContext(p2, speeds, t_check, None, geo), keys,
                               "rigid_four_bar").total("tension", np.zeros(t_check.shape))
        out["peak_load_by_speed"].append(np.max(np.abs(check), axis=0))
        out["fractional_pitch"].append(geo["f_p"])
    data = {
        "omega2": var(("n2", "t"), out["omega2"], "rpm", "driven sprocket speed omega_2, Eq. (2-7)"),
        "polygonal_load": var(("n2", "t"), out["polygonal_load"], "N", "dynamic load D_pol, Eq. (2-10)"),
        "peak_load_by_speed": var(("n2", "check_speed"), out["peak_load_by_speed"], "N",
                                  "max |D_pol| at the check speeds"),
        "fractional_pitch": var("n2", out["fractional_pitch"], "1", "fractional pitch f_p, Eq. (2-6)"),
        "panel": var("n2", np.array([panels.index(n) for n in cases], dtype=np.int32), "1",
                     "panel of Fig. 3 (0 = a, 1 = b, 2 = c) in the order of options.cases"),
    }
    if out["u_left"]:
        data["u_left"] = var(("n2", "t"), out["u_left"], "m",
                             "driven-end transverse displacement u_0, Eq. (2-25)")
    return xr.Dataset(data, coords={**_coord("t", t, "s", "time"),
                                    **_coord("n2", cases, "1", "driven sprocket tooth number"),
                                    **_coord("check_speed", speeds * RPM, "rpm", "check speed")})


def elastic_four_bar(run, prm, res):
    """Fig. 4: the elastic four-bar load (contributions ``tension_short``/``tension_long``,
    switched by the span-length state ``long``) below, at, between, at and above its two
    resonances, and its peak-to-peak value over a speed window for k1 and k2."""
    n1, n2, p = int(prm["n1"]), int(prm["n2"]), prm["pitch"]
    geo = span.span_geometry(prm, True)
    r2 = geometry.pitch_radius(p, n2)
    wc_short, wc_long = (four_bar.elastic_resonance(prm["axial_stiffness"] / geo[L],
                                                    prm["driven_inertia"], r2, n1)
                         for L in ("L_short", "L_long"))
    # the paper's omega_c1 < omega_c2: the long (softer) span resonates first
    wc1, wc2 = min(wc_short, wc_long), max(wc_short, wc_long)
    window = run.get("options", {}).get("speed_window_elastic")
    lo, hi = elastic_speed_window(prm, window) if window else (prm["speed_min"], prm["speed_max"])
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
    return xr.Dataset({
        "load_shape": var(("case", "phase"), shapes.T, "N",
                          "elastic four-bar D_pol with the span-length switch, Eq. (2-22)"),
        "peak_to_peak_short": var("curve_speed", np.ptp(curve.get("tension_short"), axis=0), "N",
                                  "peak-to-peak D_pol, k1 = AE/L_0"),
        "peak_to_peak_long": var("curve_speed", np.ptp(curve.get("tension_long"), axis=0), "N",
                                 "peak-to-peak D_pol, k2 = AE/(L_0+p)"),
        "omega_c1": var((), wc1 * RPM, "rpm", "first resonance of the elastic four-bar (long span)"),
        "omega_c2": var((), wc2 * RPM, "rpm", "second resonance of the elastic four-bar (short span)"),
    }, coords={**_coord("case", cases * RPM, "rpm", "driving speed of Fig. 4 case"),
               **_coord("phase", s, "1", "time in tooth periods"),
               **_coord("curve_speed", curve_w * RPM, "rpm", "driving speed")})


def elastic_speed_window(prm, window) -> tuple[float, float]:
    """Speeds [lo, hi] x omega_c of the drive's own elastic four-bar resonance
    omega_c = r2 sqrt(k/I2)/n1 with k = AE/L_ct: a medium-speed window placed around the
    resonance of *this* drive, not a speed range copied from another drive."""
    geo = span.span_geometry(prm, False)
    wc = four_bar.elastic_resonance(prm["axial_stiffness"] / geo["L_ct"], prm["driven_inertia"],
                                    geometry.pitch_radius(prm["pitch"], int(prm["n2"])),
                                    int(prm["n1"]))
    return float(window[0] * wc), float(window[1] * wc)


# ---------------------------------------------------------------------------- Figs. 5-9

def speed_sweep(run, prm, res):
    """Figs. 5-9: maximum steady amplitude vs operating speed, one vectorised FD march
    (:func:`.span.sweep`), with the moving-string resonance speeds of the span."""
    window = run.get("options", {}).get("speed_window_elastic")
    wc = None
    if window:
        prm = dict(prm)
        prm["speed_min"], prm["speed_max"] = elastic_speed_window(prm, window)
        wc = prm["speed_max"] / window[1]
    omega1 = span.speed_axis(prm, int(res["n_speeds"]))
    out = span.sweep(run, prm, omega1, res)
    orders = np.arange(1, int(res.get("orders", 8)) + 1)
    geo = dict(out["span"])
    reso = resonance_table(prm, out["tension_coefficient"], geo, orders)
    g = out["grid"]
    return xr.Dataset({
        "amplitude": var("speed", out["amplitude"], "m", "maximum steady transverse amplitude"),
        "growth": var("speed", np.minimum(out["growth"], 1e300), "1",
                      "ratio of last to first block maximum in the measuring window"),
        "unstable": var("speed", out["unstable"].astype("i1"), "1",
                        "1 where the response grows (Mathieu instability) or the span goes slack"),
        "slack": var("speed", out["slack"].astype("i1"), "1", "1 where P + P_t <= 0 somewhere"),
        "s_star": var("speed", out["s_star"], "1", "mixed-differencing weight s*, Eq. (2-38)"),
        "resonance_speed_short": var("order", reso["L_short"] * RPM, "rpm",
                                     "tooth frequency = k-th moving-string frequency, short span"),
        "resonance_speed_long": var("order", reso["L_long"] * RPM, "rpm",
                                    "tooth frequency = k-th moving-string frequency, long span"),
        "resonance_speed_mean": var("order", reso["L_ct"] * RPM, "rpm",
                                    "tooth frequency = k-th moving-string frequency, span L_ct"),
        "time_step": var((), out["dt"], "s", "time step: cfl x the von Neumann limit dx/sqrt(c_w^2 - c^2)"),
        "n_steps": var((), out["n_steps"], "1", "number of time steps"),
        "n_points": var((), g.n_long + 1, "1", "grid points of the long span"),
        "L_short": var((), geo["L_short"], "m", "short span length L_0"),
        "L_long": var((), geo["L_long"], "m", "long span length"),
        "fractional_pitch": var((), geo["f_p"], "1", "fractional pitch f_p, Eq. (2-6)"),
        "elastic_resonance_speed": var((), np.nan if wc is None else wc * RPM, "rpm",
                                           "omega_c of the drive's elastic four-bar (k = AE/L_ct)"),
    }, coords={**_coord("speed", omega1 * RPM, "rpm", "driving sprocket speed omega_1"),
               **_coord("order", orders, "1", "resonance order k")})


# ---------------------------------------------------------------------------- Fig. 10

def _resonant_speed(run, prm, tension_coefficient, L) -> float:
    """omega1 from options.resonance: tooth frequency = ``detuning`` x the j-th longitudinal or
    the k-th transverse frequency of the span (derived, never typed in); else ``speed``."""
    opts = run.get("options", {})
    spec = opts.get("resonance")
    if not spec:
        return prm["speed"]
    what, order = spec
    d = float(opts.get("detuning", 1.0))
    n1, p, m = int(prm["n1"]), prm["pitch"], prm["mass_per_length"]
    if what == "transverse":
        return geometry.resonance_speed(int(order), L, n1=n1, p_c=p, T_s=prm["static_tension"], m=m,
                                        tension_coefficient=tension_coefficient, harmonic=1.0 / d)

    def f(w):
        return n1 * w - d * geometry.longitudinal_frequency(int(order), prm["axial_stiffness"], m,
                                                            float(geometry.chain_speed(w, n1, p)), L)
    return float(brentq(f, 1e-3, 1e5))


def envelope_statistics(u, steps_per_tooth: int) -> dict:
    """Well-posed statistics of a probe record sampled at every RK4 step.

    The record is cut into quarters of whole tooth periods (the forcing period), so each
    quarter holds the same phases of the forcing; the statistic is the maximum of |u| over
    every step of a quarter (never over a decimated record, whose maximum depends on the
    sampling).  ``steady_amplitude`` = max over the last quarter; ``steady_ratio`` = last
    quarter / third quarter (1 for a steady envelope).
    """
    u = np.abs(np.asarray(u, float))
    n_periods = (u.size - 1) // steps_per_tooth
    q = n_periods // 4
    if q < 1:
        raise ValueError(f"record of {n_periods} tooth periods: too short for quarter statistics")
    edges = [(u.size - 1) - (4 - i) * q * steps_per_tooth for i in range(5)]
    blocks = [np.max(u[edges[i] + 1: edges[i + 1] + 1]) for i in range(4)]
    return {"steady_amplitude": blocks[3], "steady_ratio": blocks[3] / blocks[2],
            "quarter_periods": q}


def _galerkin_setup(run, prm, res) -> dict:
    """The Galerkin model of the span L_ct at the speed of ``options.resonance`` (the steady
    contributions -- tension coefficient, coupling -- fix the speed and P) and its RK4 step."""
    n1, m = int(prm["n1"]), prm["mass_per_length"]
    geo = span.span_geometry(prm, False)
    L = geo["L_ct"]
    steady = galerkin.contributions(run, prm, prm["speed"], geo, np.zeros(1), None)
    k_c = steady.total("tension_coefficient")
    w1 = _resonant_speed(run, prm, k_c, L)
    c = float(geometry.chain_speed(w1, n1, prm["pitch"]))
    P = float(geometry.axial_tension(prm["static_tension"], k_c, c))
    model = galerkin.GalerkinModel(L=L, m=m, EA=prm["axial_stiffness"], P=P, c=c,
                                   c_d=prm["transverse_damping"], n_t=int(res["n_transverse"]),
                                   n_l=int(res["n_longitudinal"]),
                                   coupling="coupling_stiffness" in steady)
    dt_limit = model.max_stable_step()
    # a whole number of steps per tooth period: the end-motion kinks and the impacts then sit
    # on step boundaries (RK4 is only first order across a kink inside a step)
    tau = 2 * np.pi / (n1 * w1)
    per_tooth = math.ceil(tau / (float(res["rk4_cfl"]) * dt_limit))
    return {"model": model, "geo": geo, "L": L, "w1": w1, "c": c, "P": P, "dt_limit": dt_limit,
            "per_tooth": per_tooth, "dt": tau / per_tooth,
            "n_steps": per_tooth * max(int(math.ceil(float(res["duration"]) / tau)), 4),
            # impact pulses shorter than the step enter with their exact impulse, spread over
            # a fixed fraction of the tooth period (the forcing must not change with the step)
            "window": tau / 16, "xi": float(prm["probe_fraction"]) * L}   # xi from the driven end


def _library_check(run, prm, res, g, u_all, t_all, Fe) -> tuple[dict, dict]:
    """solve_ivp (DOP853) over the first tooth periods: with a tolerance far below the RK4
    error (rtol 1e-9) the difference is RK4's own error, not the adaptive controller's."""
    model, xi, L = g["model"], g["xi"], g["L"]
    at = galerkin.forcing(run, prm, g["w1"], g["geo"], step=g["window"])
    n_lib = g["per_tooth"] * max(int(round(float(res["library_periods"]))), 1)
    with stopwatch() as sw:
        t_lib, y_lib, nfev = galerkin.library(lambda t, y: model.rhs_values(y, *at(t)), 0.0,
                                              np.zeros(2 * (model.n_t + model.n_l)), t_all[n_lib],
                                              t_all[:n_lib + 1],
                                              rtol=float(res.get("library_rtol", 1e-9)),
                                              atol=1e-14, max_step=g["dt"])
    u_lib = (model.u2_at(y_lib, xi) + (1 - xi / L) * Fe["g"][:n_lib + 1]
             + xi / L * Fe["h"][:n_lib + 1])
    scale = np.max(np.abs(u_all[:n_lib + 1]))
    return {
        "u_probe_library": var("t_library", u_lib, "m",
                               "transverse displacement at the probe, solve_ivp DOP853 (first periods)"),
        "rk4_vs_library": var((), np.max(np.abs(u_all[:n_lib + 1] - u_lib)) / scale, "1",
                              "max |u_RK4 - u_library| / max |u| over the library window"),
        "library_wall_time": var((), sw.seconds, "s", "wall time of solve_ivp"),
        "library_nfev": var((), nfev, "1", "right-hand-side calls of solve_ivp"),
        "rk4_nfev": var((), 4 * g["n_steps"], "1", "right-hand-side calls of RK4"),
    }, _coord("t_library", t_lib, "s", "time")


def galerkin_span(run, prm, res):
    """Fig. 10: the coupled Galerkin model (Eqs. 2-39..2-41) at the speed of
    ``options.resonance``, RK4 with a whole number of steps per tooth period; optionally
    compared with solve_ivp over the first tooth periods (``options.compare_library``)."""
    opts = run.get("options", {})
    g = _galerkin_setup(run, prm, res)
    model, dt, n_steps, xi, L, c, w1 = (g[k] for k in ("model", "dt", "n_steps", "xi", "L", "c", "w1"))
    n1, m = int(prm["n1"]), prm["mass_per_length"]
    stages = galerkin.stage_times(dt, n_steps)
    t_rec = np.arange(n_steps + 1) * dt
    with stopwatch() as sw_rk:
        # the forcing at the RK4 stages and (for the end-motion line) at the recorded steps
        F = galerkin.forcing_arrays(run, prm, w1, g["geo"],
                                    np.concatenate([stages.ravel(), t_rec + 1e-9 * dt]),
                                    step=g["window"])
        Fs = {k: v[:stages.size].reshape(stages.shape) for k, v in F.items()}
        Fe = {k: v[stages.size:] for k, v in F.items()}
        t_all, y_all = galerkin.rk4_tabulated(model, np.zeros(2 * (model.n_t + model.n_l)), dt,
                                              n_steps, Fs, record_every=1)
    u_all = model.u2_at(y_all, xi) + (1 - xi / L) * Fe["g"] + xi / L * Fe["h"]
    stats = envelope_statistics(u_all, g["per_tooth"])
    rec = max(n_steps // int(res["samples"]), 1)
    data = {
        "u_probe_rk4": var("t", u_all[::rec], "m", "transverse displacement at the probe, RK4 "
                           f"(every {rec}th step, for the figure)"),
        "rk4_time_step": var((), dt, "s", "RK4 step (a whole number per tooth period)"),
        "rk4_step_limit": var((), g["dt_limit"], "s", "RK4 linear stability limit"),
        "rk4_wall_time": var((), sw_rk.seconds, "s", "wall time of the forcing and RK4"),
        "chain_speed": var((), c, "m/s", "chain speed"),
        "longitudinal_frequency": var((), geometry.longitudinal_frequency(1, prm["axial_stiffness"],
                                                                          m, c, L), "rad/s",
                                      "first longitudinal frequency of the moving span"),
        "tooth_frequency": var((), n1 * w1, "rad/s", "tooth frequency n1 omega1"),
        "speed": var((), w1 * RPM, "rpm", "driving sprocket speed"),
        "detuning": var((), float(opts.get("detuning", 1.0)), "1",
                        "tooth frequency / the resonance frequency named in options"),
        "transverse_order_at_speed": var(
            (), n1 * w1 / float(geometry.moving_string_frequencies(1, c, g["P"], m, L)), "1",
            "tooth frequency / first transverse frequency of the moving span"),
        "steady_amplitude": var((), stats["steady_amplitude"], "m",
                                "max |u| at the probe over every step of the last quarter "
                                "(whole tooth periods)"),
        "steady_ratio": var((), stats["steady_ratio"], "1",
                            "max |u| last quarter / third quarter (whole tooth periods)"),
    }
    coords = _coord("t", t_all[::rec], "s", "time")
    if opts.get("compare_library", False):
        more, more_coords = _library_check(run, prm, res, g, u_all, t_all, Fe)
        data.update(more)
        coords.update(more_coords)
    return xr.Dataset(data, coords=coords)


# ---------------------------------------------------------------------------- Sec. 3.1, checks

def impact_timestep(run, prm, res):
    """Sec. 3.1: the non-uniform step refined near impacts vs uniform steps (error, wall time)."""
    out = timestep.compare(run, prm, res)
    names = ["uniform_sampled", "uniform_averaged", "nonuniform", "uniform_equal_accuracy"]
    return xr.Dataset({
        "error": var("strategy", [out[n]["error"] for n in names], "1",
                     "max |u_mid - u_ref| / max |u_ref| against a fine uniform reference"),
        "march_wall_time": var("strategy", [out[n]["wall"] for n in names], "s", "wall time of the march"),
        "steps": var("strategy", [out[n]["steps"] for n in names], "1", "number of time steps"),
        "dt_max": var((), out["dt_max"], "s", "von Neumann limit step (x cfl)"),
        "dt_min": var((), out["dt_min"], "s", "smallest step of the non-uniform scheme"),
        "dt_equal_accuracy": var((), out["uniform_equal_accuracy"]["dt"], "s",
                                     "uniform step reaching the non-uniform accuracy"),
        "contact_time": var((), out["contact_time"], "s", "impact contact time pi/omega_d"),
    }, coords=_coord("strategy", names, "1", "time-step strategy"))


SOLVERS = {"impact_load": impact_load, "rigid_four_bar": rigid_four_bar,
           "elastic_four_bar": elastic_four_bar, "speed_sweep": speed_sweep,
           "galerkin": galerkin_span, "impact_timestep": impact_timestep,
           "exact_free": lambda run, prm, res: exact.free_vibration_check(prm, res),
           "manufactured": lambda run, prm, res: exact.manufactured_check(prm, res)}


def solve(run: dict) -> xr.Dataset:
    solver = run.get("solver")
    if solver not in SOLVERS:
        raise ValueError(f"chain_drive: solver {solver!r}: allowed {sorted(SOLVERS)}")
    return SOLVERS[solver](run, run["parameters"], run["resolution"])
