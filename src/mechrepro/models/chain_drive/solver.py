"""``solve(run) -> xarray.Dataset`` for every kind of chain_drive scene.

The scene's ``options.kind`` picks what is computed; its ``effects`` pick the physics:
``impact_load`` (Fig. 1), ``rigid_load`` (Fig. 3), ``elastic_load`` (Fig. 4), ``sweep``
(Figs. 5-9: maximum steady amplitude vs operating speed, one vectorised FD computation),
``time_history`` (one speed, response at probe points; uniform or non-uniform step),
``galerkin`` (Fig. 10), ``exact_free`` and ``manufactured`` (independent checks of the FD
scheme).  Speeds in the datasets are in rpm; everything else SI.
"""
from __future__ import annotations

import math
import time

import numpy as np
import xarray as xr

from . import exact, fd, four_bar, galerkin, geometry, loads, span
from .effects import EFFECTS

RPM = 30.0 / math.pi   # rad/s -> rpm


def _v(data, dims, units, long_name):
    return (dims, np.asarray(data), {"units": units, "long_name": long_name})


def _speed_coord(omega1):
    return {"speed": ("speed", np.asarray(omega1) * RPM,
                      {"units": "rpm", "long_name": "driving sprocket speed omega_1"})}


def _scalar(x, units, long_name):
    return ((), np.asarray(x, float), {"units": units, "long_name": long_name})


def resonance_table(prm, effects, span_geo, orders) -> dict:
    """Speeds where the tooth frequency meets the k-th moving-string frequency (Wickert-Mote)."""
    kw = dict(n1=int(prm["n1"]), p_c=prm["pitch"], T_s=prm["static_tension"],
              m=prm["mass_per_length"], lam=prm["lambda_support"],
              speed_tensioning="speed_tensioning" in effects)
    out = {}
    for name in ("L_short", "L_long", "L_ct"):
        out[name] = np.array([geometry.resonance_speed(k, span_geo[name], **kw) for k in orders])
    return out


# ---------------------------------------------------------------------------- kinds

def _impact_load(run, prm, res):
    EFFECTS.select(run["effects"])
    w1 = prm["speed"]
    n1, p = int(prm["n1"]), prm["pitch"]
    k = loads.impact_constants(prm["impact_mass_links"] * p * prm["mass_per_length"],
                               prm["contact_stiffness"], prm["contact_damping_ratio"])
    tau = 2 * np.pi / (n1 * w1)
    n = int(res["samples"])
    t_near = np.linspace(0, 1.5 * k["t_i"], n)
    t_wide = np.linspace(0, 3 * tau, n)
    V, eta = loads.relative_velocity(w1, p), loads.pressure_angle(n1)
    near = loads.impact_pulse(t_near, V, eta, k)
    wide = loads.impact_load(t_wide, w1, n1, p, k, step=t_wide[1] - t_wide[0])
    from scipy.integrate import quad
    J_quad = quad(lambda s: float(loads.impact_pulse(s, V, eta, k)), 0, k["t_i"], limit=200)[0]
    J_exact = float(loads.impact_pulse_integral(np.inf, V, eta, k))
    return xr.Dataset({
        "impact_load_near": _v(near, ("t_near",), "N", "impact load D_imp near the impact, Eq. (2-4)"),
        "impact_load_wide": _v(wide, ("t_wide",), "N", "impact load over three tooth periods (step-averaged)"),
        "contact_time": _scalar(k["t_i"], "s", "contact duration pi/omega_d (Appendix I)"),
        "tooth_period": _scalar(tau, "s", "tooth period 2 pi/(n1 omega1)"),
        "impact_peak": _scalar(near.max(), "N", "peak impact load"),
        "impulse_quadrature": _scalar(J_quad, "N*s", "impulse of one impact by quadrature of Eq. (2-4)"),
        "impulse_closed_form": _scalar(J_exact, "N*s", "impulse of one impact in closed form"),
        "pressure_angle": _scalar(np.rad2deg(eta), "deg", "angle eta, Eq. (2-3) from ANSI tooth form"),
    }, coords={"t_near": ("t_near", t_near, {"units": "s", "long_name": "time after impact"}),
               "t_wide": ("t_wide", t_wide, {"units": "s", "long_name": "time"})})


def _rigid_load(run, prm, res):
    """Fig. 3: one case per driven tooth number in ``options.cases`` (default: n2)."""
    EFFECTS.select(run["effects"])
    n1, p = int(prm["n1"]), prm["pitch"]
    panels = [int(x) for x in run.get("options", {}).get("cases", [prm["n2"]])]
    # a CF dimension coordinate is monotonic: cases sorted, the paper's panel kept beside
    cases = sorted(panels)
    w1 = prm["speed"]
    tau = 2 * np.pi / (n1 * w1)
    t = np.linspace(0, 2 * tau, int(res["samples"]))
    factors = np.array([0.5, 1.0, 2.0])
    speeds = w1 * factors
    om2, D, u0, peaks, fps = [], [], [], [], []
    for n2 in cases:
        geo = span.span_geometry({**prm, "n2": n2}, True)
        kin = four_bar.rigid_kinematics(t, w1, n1=n1, n2=n2, p_c=p, f_p=geo["f_p"])
        om2.append(kin["omega2"] * RPM)
        D.append(four_bar.polygonal_load_rigid(kin["alpha2"], prm["driven_inertia"], kin["r2"]))
        u0.append(four_bar.end_displacements(kin["theta1"], kin["theta2"], kin["r1"], kin["r2"], n2)[0])
        fps.append(geo["f_p"])
        pk = []
        for w in speeds:
            tt = np.linspace(0, 2 * 2 * np.pi / (n1 * w), int(res["samples"]))
            kk = four_bar.rigid_kinematics(tt, w, n1=n1, n2=n2, p_c=p, f_p=geo["f_p"])
            pk.append(np.max(np.abs(four_bar.polygonal_load_rigid(kk["alpha2"], prm["driven_inertia"],
                                                                  kk["r2"]))))
        peaks.append(pk)
    return xr.Dataset({
        "omega2": _v(om2, ("n2", "t"), "rpm", "driven sprocket speed omega_2, Eq. (2-7)"),
        "polygonal_load": _v(D, ("n2", "t"), "N", "dynamic load D_pol, Eq. (2-10)"),
        "u_left": _v(u0, ("n2", "t"), "m", "driven-end transverse displacement u_0, Eq. (2-25)"),
        "peak_load_by_speed": _v(peaks, ("n2", "check_speed"), "N", "max |D_pol| at the check speeds"),
        "fractional_pitch": _v(fps, ("n2",), "1", "fractional pitch f_p, Eq. (2-6)"),
        "panel": _v(np.array([panels.index(n) for n in cases], dtype=np.int32), ("n2",), "1",
                    "panel of Fig. 3 (0 = a, 1 = b, 2 = c) in the order of options.cases"),
    }, coords={"t": ("t", t, {"units": "s", "long_name": "time"}),
               "n2": ("n2", cases, {"units": "1", "long_name": "driven sprocket tooth number"}),
               "check_speed": ("check_speed", speeds * RPM, {"units": "rpm", "long_name": "check speed"})})


def _elastic_load(run, prm, res):
    EFFECTS.select(run["effects"])
    n1, n2, p = int(prm["n1"]), int(prm["n2"]), prm["pitch"]
    geo = span.span_geometry(prm, True)
    EA, I2 = prm["axial_stiffness"], prm["driven_inertia"]
    r2 = geometry.pitch_radius(p, n2)
    k1, k2 = EA / geo["L_short"], EA / geo["L_long"]
    wc_short, wc_long = (four_bar.elastic_resonance(k, I2, r2, n1) for k in (k1, k2))
    # the paper's omega_c1 < omega_c2: the long (softer) span resonates first
    wc1, wc2 = min(wc_short, wc_long), max(wc_short, wc_long)
    ks = {"short": k1, "long": k2}
    window = run.get("options", {}).get("speed_window_elastic")
    lo, hi = (elastic_speed_window(prm, window) if window else (prm["speed_min"], prm["speed_max"]))
    curve_w = np.linspace(lo, hi, int(res["n_speeds"]))
    peak = {}
    for name, k in ks.items():
        vals = []
        for w in curve_w:
            sol = four_bar.elastic_four_bar(w, k=k, I2=I2, n1=n1, n2=n2, p_c=p, f_p=geo["f_p"])
            tt = np.linspace(0, 2 * np.pi / (n1 * w), 64, endpoint=False)
            vals.append(np.ptp(four_bar.polygonal_load_elastic(tt, sol, w, k)))
        peak[name] = np.array(vals)
    # Fig. 4 a-e: below, at, between, at, above the two resonances
    cases = np.array([0.6 * wc1, wc1, 0.5 * (wc1 + wc2), wc2, 1.4 * wc2])
    s = np.linspace(0, 2, int(res["samples"]))   # time in tooth periods
    shapes = []
    for w in cases:
        tau = 2 * np.pi / (n1 * w)
        t = s * tau
        kin = four_bar.rigid_kinematics(t, w, n1=n1, n2=n2, p_c=p, f_p=geo["f_p"])
        lng = four_bar.long_span(kin["phase1"], kin["phase2"])
        D = {}
        for name, k in ks.items():
            sol = four_bar.elastic_four_bar(w, k=k, I2=I2, n1=n1, n2=n2, p_c=p, f_p=geo["f_p"])
            D[name] = four_bar.polygonal_load_elastic(t, sol, w, k)
        shapes.append(np.where(lng, D["long"], D["short"]) if geo["L_short"] != geo["L_long"] else D["short"])
    return xr.Dataset({
        "load_shape": _v(np.array(shapes), ("case", "phase"), "N",
                         "elastic four-bar D_pol with the span-length switch, Eq. (2-22)"),
        "peak_to_peak_short": _v(peak["short"], ("curve_speed",), "N", "peak-to-peak D_pol, k1 = AE/L_0"),
        "peak_to_peak_long": _v(peak["long"], ("curve_speed",), "N", "peak-to-peak D_pol, k2 = AE/(L_0+p)"),
        "omega_c1": _scalar(wc1 * RPM, "rpm", "first resonance of the elastic four-bar (long span)"),
        "omega_c2": _scalar(wc2 * RPM, "rpm", "second resonance of the elastic four-bar (short span)"),
    }, coords={"case": ("case", cases * RPM, {"units": "rpm", "long_name": "driving speed of Fig. 4 case"}),
               "phase": ("phase", s, {"units": "1", "long_name": "time in tooth periods"}),
               "curve_speed": ("curve_speed", curve_w * RPM, {"units": "rpm", "long_name": "driving speed"})})


def elastic_speed_window(prm, window) -> tuple[float, float]:
    """Speeds [lo, hi] x omega_c of the drive's own elastic four-bar resonance
    omega_c = r2 sqrt(k/I2)/n1 with k = AE/L_ct: a medium-speed window placed around the
    resonance of *this* drive, not a speed range copied from another drive."""
    geo = span.span_geometry(prm, False)
    wc = four_bar.elastic_resonance(prm["axial_stiffness"] / geo["L_ct"], prm["driven_inertia"],
                                    geometry.pitch_radius(prm["pitch"], int(prm["n2"])),
                                    int(prm["n1"]))
    return float(window[0] * wc), float(window[1] * wc)


def _sweep(run, prm, res, mode="vectorised"):
    window = run.get("options", {}).get("speed_window_elastic")
    wc = None
    if window:
        prm = dict(prm)
        prm["speed_min"], prm["speed_max"] = elastic_speed_window(prm, window)
        wc = prm["speed_max"] / window[1]
    omega1 = span.speed_axis(prm, int(res["n_speeds"]))
    t0 = time.perf_counter()
    out = span.sweep(run["effects"], prm, omega1, res, mode=mode)
    wall = time.perf_counter() - t0
    orders = np.arange(1, int(res.get("orders", 8)) + 1)
    geo = dict(out["span"])
    reso = resonance_table(prm, run["effects"], geo, orders)
    g = out["grid"]
    ds = xr.Dataset({
        "amplitude": _v(out["amplitude"], ("speed",), "m", "maximum steady transverse amplitude"),
        "growth": _v(np.minimum(out["growth"], 1e300), ("speed",), "1",
                     "ratio of last to first block maximum in the measuring window"),
        "unstable": _v(out["unstable"].astype("i1"), ("speed",), "1",
                       "1 where the response grows (Mathieu instability) or the span goes slack"),
        "slack": _v(out["slack"].astype("i1"), ("speed",), "1", "1 where P + P_t <= 0 somewhere"),
        "s_star": _v(out["s_star"], ("speed",), "1", "mixed-differencing weight s*, Eq. (2-38)"),
        "resonance_speed_short": _v(reso["L_short"] * RPM, ("order",), "rpm",
                                    "tooth frequency = k-th moving-string frequency, short span"),
        "resonance_speed_long": _v(reso["L_long"] * RPM, ("order",), "rpm",
                                   "tooth frequency = k-th moving-string frequency, long span"),
        "resonance_speed_mean": _v(reso["L_ct"] * RPM, ("order",), "rpm",
                                   "tooth frequency = k-th moving-string frequency, span L_ct"),
        "time_step": _scalar(out["dt"], "s", "time step: cfl x the von Neumann limit dx/sqrt(c_w^2 - c^2)"),
        "n_steps": _scalar(out["n_steps"], "1", "number of time steps"),
        "n_points": _scalar(g.n_long + 1, "1", "grid points of the long span"),
        "L_short": _scalar(geo["L_short"], "m", "short span length L_0"),
        "L_long": _scalar(geo["L_long"], "m", "long span length"),
        "fractional_pitch": _scalar(geo["f_p"], "1", "fractional pitch f_p, Eq. (2-6)"),
        "sweep_wall_time": _scalar(wall, "s", "wall time of the whole speed sweep"),
        "elastic_resonance_speed": _scalar(np.nan if wc is None else wc * RPM, "rpm",
                                           "omega_c of the drive's elastic four-bar (k = AE/L_ct)"),
    }, coords={**_speed_coord(omega1),
               "order": ("order", orders, {"units": "1", "long_name": "resonance order k"})})
    return ds


def _time_history(run, prm, res):
    """One speed, response at probes, uniform step or the non-uniform step of Sec. 3.1."""
    w = np.array([prm["speed"]])
    a = span.assemble(run["effects"], prm, w, res)
    g = a["grid"]
    probes = [int(round(f * g.n_short)) for f in (1 / 3, 0.5)]
    kw = dict(m=a["m"], c_d=a["c_d"], grid=g, n_steps=a["n_steps"], exc=a["exc"],
              measure_from=a["measure_from"], probes=probes, record_every=1, s_star=a["s_star"])
    t0 = time.perf_counter()
    r = fd.march(c=a["c"], P=a["P"], dt=a["dt"], **kw)
    wall = time.perf_counter() - t0
    return xr.Dataset({
        "u_probe": _v(r.probes[:, 0, :], ("t", "probe"), "m", "transverse displacement at probes"),
        "amplitude": _scalar(r.amplitude[0], "m", "maximum steady amplitude"),
        "time_step": _scalar(a["dt"], "s", "time step"),
        "march_wall_time": _scalar(wall, "s", "wall time of the time march"),
    }, coords={"t": ("t", r.t_rec, {"units": "s", "long_name": "time"}),
               "probe": ("probe", np.array(probes) * g.dx, {"units": "m",
                                                           "long_name": "probe position from driven sprocket"})})


def _resonant_speed(run, prm, selected, L) -> float:
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
                                        lam=prm["lambda_support"],
                                        speed_tensioning="speed_tensioning" in selected,
                                        harmonic=1.0 / d)
    from scipy.optimize import brentq

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


def _impact_timestep(run, prm, res):
    """Non-uniform step of Sec. 3.1 vs uniform steps: error and wall time."""
    from . import timestep

    EFFECTS.select(run["effects"])
    out = timestep.compare(prm, run["effects"], res)
    names = ["uniform_sampled", "uniform_averaged", "nonuniform", "uniform_equal_accuracy"]
    return xr.Dataset({
        "error": _v([out[n]["error"] for n in names], ("strategy",), "1",
                    "max |u_mid - u_ref| / max |u_ref| against a fine uniform reference"),
        "march_wall_time": _v([out[n]["wall"] for n in names], ("strategy",), "s", "wall time of the march"),
        "steps": _v([out[n]["steps"] for n in names], ("strategy",), "1", "number of time steps"),
        "dt_max": _scalar(out["dt_max"], "s", "von Neumann limit step (x cfl)"),
        "dt_min": _scalar(out["dt_min"], "s", "smallest step of the non-uniform scheme"),
        "dt_equal_accuracy": _scalar(out["uniform_equal_accuracy"]["dt"], "s",
                                     "uniform step reaching the non-uniform accuracy"),
        "contact_time": _scalar(out["contact_time"], "s", "impact contact time pi/omega_d"),
    }, coords={"strategy": ("strategy", names, {"units": "1", "long_name": "time-step strategy"})})


def _galerkin(run, prm, res):
    selected = EFFECTS.select(run["effects"])
    opts = run.get("options", {})
    n1, p, m = int(prm["n1"]), prm["pitch"], prm["mass_per_length"]
    geo = span.span_geometry(prm, False)
    L = geo["L_ct"]
    w1 = _resonant_speed(run, prm, selected, L)
    c = float(geometry.chain_speed(w1, n1, p))
    P = prm["static_tension"] + (loads.speed_tensioning(prm["lambda_support"], m, c)
                                 if "speed_tensioning" in selected else 0.0)
    EA = prm["axial_stiffness"]
    model = galerkin.GalerkinModel(L=L, m=m, EA=EA, P=P, c=c, c_d=prm["transverse_damping"],
                                   n_t=int(res["n_transverse"]), n_l=int(res["n_longitudinal"]),
                                   coupling="longitudinal_coupling" in selected)
    kimp = loads.impact_constants(prm["impact_mass_links"] * p * m, prm["contact_stiffness"],
                                  prm["contact_damping_ratio"])
    dt_limit = model.max_stable_step()
    # a whole number of steps per tooth period: the end-motion kinks and the impacts then sit
    # on step boundaries (RK4 is only first order across a kink inside a step)
    tau = 2 * np.pi / (n1 * w1)
    per_tooth = math.ceil(tau / (float(res["rk4_cfl"]) * dt_limit))
    dt = tau / per_tooth
    # impact pulses shorter than the step enter with their exact impulse, spread over a
    # fixed fraction of the tooth period (not a number of steps: the forcing must not
    # change when the step is refined)
    window = tau / 16
    tension, ends = galerkin.forcing(selected, prm, w1, geo, kimp, step=window)
    f = lambda t, y: model.rhs(t, y, ends, tension)  # noqa: E731
    y0 = np.zeros(2 * (model.n_t + model.n_l))
    # a whole number of tooth periods
    n_steps = per_tooth * max(int(math.ceil(float(res["duration"]) / tau)), 4)
    t0 = time.perf_counter()
    F = galerkin.forcing_arrays(selected, prm, w1, geo, kimp, galerkin.stage_times(dt, n_steps),
                                step=window)
    t_all, y_all = galerkin.rk4_tabulated(model, y0, dt, n_steps, F, record_every=1)
    wall_rk = time.perf_counter() - t0
    xi = float(prm["probe_fraction"]) * L   # measured from the driven sprocket (x = 0)
    Fe = galerkin.forcing_arrays(selected, prm, w1, geo, kimp, t_all + 1e-9 * dt, step=window)
    u_all = model.u2_at(y_all, xi) + (1 - xi / L) * Fe["g"] + xi / L * Fe["h"]
    stats = envelope_statistics(u_all, per_tooth)
    rec = max(n_steps // int(res["samples"]), 1)
    t_rk, u_rk = t_all[::rec], u_all[::rec]
    data = {
        "u_probe_rk4": _v(u_rk, ("t",), "m", "transverse displacement at the probe, RK4 (every "
                          f"{rec}th step, for the figure)"),
        "rk4_time_step": _scalar(dt, "s", "RK4 step (a whole number per tooth period)"),
        "rk4_step_limit": _scalar(dt_limit, "s", "RK4 linear stability limit"),
        "rk4_wall_time": _scalar(wall_rk, "s", "wall time of RK4"),
        "chain_speed": _scalar(c, "m/s", "chain speed"),
        "longitudinal_frequency": _scalar(geometry.longitudinal_frequency(1, EA, m, c, L), "rad/s",
                                          "first longitudinal frequency of the moving span"),
        "tooth_frequency": _scalar(n1 * w1, "rad/s", "tooth frequency n1 omega1"),
        "speed": _scalar(w1 * RPM, "rpm", "driving sprocket speed"),
        "detuning": _scalar(float(opts.get("detuning", 1.0)), "1",
                            "tooth frequency / the resonance frequency named in options"),
        "transverse_order_at_speed": _scalar(
            n1 * w1 / float(geometry.moving_string_frequencies(1, c, P, m, L)), "1",
            "tooth frequency / first transverse frequency of the moving span"),
        "steady_amplitude": _scalar(stats["steady_amplitude"], "m",
                                    "max |u| at the probe over every step of the last quarter "
                                    "(whole tooth periods)"),
        "steady_ratio": _scalar(stats["steady_ratio"], "1",
                                "max |u| last quarter / third quarter (whole tooth periods)"),
    }
    if opts.get("compare_library", False):
        t0 = time.perf_counter()
        # the library covers the first tooth periods: with a tolerance far below the RK4
        # error (rtol 1e-9) the difference is RK4's own error, not the adaptive controller's
        # (rtol 1e-6 made it depend on step-size decisions, hence on the platform)
        n_lib = per_tooth * max(int(round(float(res["library_periods"]))), 1)
        t_lib, y_lib, nfev = galerkin.library(f, 0.0, y0, t_all[n_lib], t_all[:n_lib + 1],
                                              rtol=float(res.get("library_rtol", 1e-9)),
                                              atol=1e-14, max_step=dt)
        wall_lib = time.perf_counter() - t0
        u_lib = model.u2_at(y_lib, xi) + (1 - xi / L) * Fe["g"][:n_lib + 1] + xi / L * Fe["h"][:n_lib + 1]
        scale = np.max(np.abs(u_all[:n_lib + 1]))
        data.update({
            "u_probe_library": _v(u_lib, ("t_library",), "m",
                                  "transverse displacement at the probe, solve_ivp DOP853 (first periods)"),
            "rk4_vs_library": _scalar(np.max(np.abs(u_all[:n_lib + 1] - u_lib)) / scale, "1",
                                      "max |u_RK4 - u_library| / max |u| over the library window"),
            "library_wall_time": _scalar(wall_lib, "s", "wall time of solve_ivp"),
            "library_nfev": _scalar(nfev, "1", "right-hand-side calls of solve_ivp"),
            "rk4_nfev": _scalar(4 * n_steps, "1", "right-hand-side calls of RK4"),
        })
        coords_lib = {"t_library": ("t_library", t_lib, {"units": "s", "long_name": "time"})}
    else:
        coords_lib = {}
    return xr.Dataset(data, coords={"t": ("t", t_rk, {"units": "s", "long_name": "time"}),
                                    **coords_lib})


def _exact_free(run, prm, res):
    """FD against the exact moving-string free vibration (Wickert-Mote), see :mod:`.exact`."""
    return exact.free_vibration_check(prm, res)


def _manufactured(run, prm, res):
    return exact.manufactured_check(prm, res)


KINDS = {"impact_load": _impact_load, "rigid_load": _rigid_load, "elastic_load": _elastic_load,
         "sweep": _sweep, "time_history": _time_history, "impact_timestep": _impact_timestep, "galerkin": _galerkin,
         "exact_free": _exact_free, "manufactured": _manufactured}


def solve(run: dict) -> xr.Dataset:
    kind = run.get("options", {}).get("kind", "sweep")
    if kind not in KINDS:
        raise ValueError(f"chain_drive: options.kind {kind!r}: allowed {sorted(KINDS)}")
    prm, res = run["parameters"], run["resolution"]
    ds = KINDS[kind](run, prm, res)
    ds.attrs["kind"] = kind
    return ds
