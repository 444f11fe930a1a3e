"""The effects and outputs of disk_tension: pure functions ``fn(ctx) -> {key: value}`` declared
in ``config/papers/disk_tension.yaml``, the effects evaluated in three stages by :mod:`.solver`,
the outputs (references, analyses) after the last."""
from __future__ import annotations

from dataclasses import dataclass
from functools import partial
from typing import Callable

import numpy as np

from mechrepro.effects import EffectRegistry
from mechrepro.errors import Refusal
from mechrepro.levels import extrapolate
from mechrepro.timing import phase
from mechrepro.units import var

from . import calibration, design, exact, identifiability as idf, rotation, thermal
from .axisym import AxisymDisk
from .modal import delta_f_exact, delta_f_linearised, frequency

EFFECTS = EffectRegistry("disk_tension")

#: element counts of the rolled reference: Richardson (h^4) of two runs still in the h^4 range
#: (beyond 128 elements round-off exceeds the h^4 error)
REFERENCE_ELEMENTS = (64, 128)
#: radii at which the closed-form temperature and stress are stored
N_RADII = 256

#: seconds of a fresh solve of each memoised effect or output, per (name, input), once per process
_COLD: dict = {}


def _cold(effect, key, solve_afresh, plus=0.0):
    """What ``effect`` costs with nothing memoised: a fresh solve, once per input."""
    if (effect, key) not in _COLD:
        with phase("disk_tension.cold") as sw:
            solve_afresh()
        _COLD[effect, key] = sw.seconds
    return var((), _COLD[effect, key] + plus, "s", f"wall time of {effect}, nothing memoised")


@dataclass(frozen=True)
class ThermalLoad:
    """Eq. (4) temperature of one centre radius of rolling and its plane-stress field."""

    r_c: float
    temperature: Callable      # T(r) [K]
    sigma: tuple               # (sigma_r(r), sigma_theta(r)) [Pa], closed form
    alpha: float               # expansion coefficient of the thermal analogy [1/K]
    inplane_bc: str


def thermal_load(ctx, r_c) -> ThermalLoad:
    """Eq. (4) at ``r_c`` with the context's amplitude, width, alpha and in-plane condition."""
    rc = float(r_c)
    return ThermalLoad(r_c=rc, alpha=ctx.alpha, inplane_bc=ctx.bc,
                       temperature=lambda r: thermal.temperature(r, ctx.A, rc, ctx.s),
                       sigma=thermal.field(amplitude=ctx.A, r_c=rc, s=ctx.s, r_f=ctx.r_f, b=ctx.b,
                                           E=ctx.E, nu=ctx.nu, alpha=ctx.alpha, inplane_bc=ctx.bc,
                                           stress_model=ctx.stress_model,
                                           profile_rc=ctx.p["calibration_rolling_radius"]))


# --- stage 1: what the load and the mesh need ---------------------------------------------
@EFFECTS.register("stress_calibration")
def stress_calibration(ctx) -> dict:
    """The thermal-analogy alpha that meets Table 1's N_d = 4 entry (Eq. 9 is linear in it)."""
    p = ctx.p
    case = dict(n_d=int(p["calibration_nodal_diameter"]), r_c=p["calibration_rolling_radius"],
                r_f=p["calibration_clamp_radius"], b=ctx.b, h=ctx.h, E=ctx.E, nu=ctx.nu,
                rho=ctx.rho, alpha=ctx.alpha, amplitude=p["calibration_temperature_amplitude"],
                s=ctx.s, inplane_bc=ctx.bc)
    if ctx.stress_model != "thermal_analogy":   # a rival is re-calibrated on its own stress
        case["stress_model"] = ctx.stress_model
    target = p["calibration_delta_omega2"]
    alpha, d_hb, df_hb = calibration.alpha_effective(target=target, **case)
    return {
        "stress_calibration_time_cold": _cold(
            "stress_calibration", (target, *sorted(case.items())),
            lambda: calibration.alpha_effective(target=target, memo=False, **case)),
        "thermal_expansion": alpha,
        "alpha_effective": var((), alpha, "1/K", "thermal-analogy alpha calibrated on Table 1"),
        "stress_scale": var((), alpha / ctx.alpha, "1", "calibrated / handbook alpha"),
        "handbook_delta_omega2_eq9": var((), d_hb, "rad2/s2", "Eq. (9) of Table 1's N_d = 4 entry, "
                                         "handbook alpha"),
        "handbook_delta_f_eigen": var((), df_hb, "Hz", "eigen Delta f there, handbook alpha"),
    }


@EFFECTS.register("slots")
def slots(ctx) -> dict:
    """Radial expansion slots cut from the rim (the 2-D mesh leaves them out)."""
    from .plate2d import Slots  # scikit-fem is imported only by scenes that use it

    s = Slots(int(ctx.p["slot_count"]), ctx.p["slot_depth"], ctx.p["slot_width"])
    return {"slots": s, "slot_count": var((), s.count, "1", "number of radial expansion slots")}


# --- stage 2: the load --------------------------------------------------------------------
@EFFECTS.register("roll_tension")
def roll_tension(ctx) -> dict:
    """Eq. (4) temperature of every r_c and its plane-stress field (the run's inplane_bc)."""
    loads = [thermal_load(ctx, rc) for rc in ctx.r_c]
    r = np.linspace(0.0, ctx.b, N_RADII)
    sr, st = np.full((2, len(loads), len(r)), np.nan)
    ok = r >= (ctx.r_f if ctx.bc == "clamped" else r[1])
    for j, ld in enumerate(loads):
        sr[j, ok], st[j, ok] = ld.sigma[0](r[ok]), ld.sigma[1](r[ok])
    bc = {"inplane_bc": ctx.bc}
    return {
        "thermal_load": loads,
        "r": var("r", r, "m", "radius"),
        "temperature": var(("r_c", "r"), [ld.temperature(r) for ld in loads], "K", "T(r), Eq. (4)"),
        "sigma_r": var(("r_c", "r"), sr, "Pa", f"radial residual stress ({ctx.bc})", **bc),
        "sigma_theta": var(("r_c", "r"), st, "Pa", f"hoop residual stress ({ctx.bc})", **bc),
        "amplitude_used": var((), ctx.A, "K", "amplitude A of Eq. (4) used for the stress"),
        "width_used": var((), ctx.s, "m", "Gaussian width s of Eq. (4) used for the stress"),
    }


@EFFECTS.register("cutting_heat")
def cutting_heat(ctx) -> dict:
    """The rim heated in the cut: Eq. (4)'s form at r_c = b, compressing the rim."""
    p = ctx.p
    kw = dict(amplitude=p["rim_temperature_rise"], r_c=ctx.b, s=p["rim_heat_width"],
              r_f=ctx.r_f, b=ctx.b, E=ctx.E, nu=ctx.nu, alpha=p["thermal_expansion"],
              inplane_bc=p["centrifugal_bc"])
    r = np.linspace(ctx.r_f, ctx.b, N_RADII)
    st = thermal.thermal_stress(r, **kw)[1]
    return {
        "cutting_heat_stress": ThermalLoad(
            r_c=ctx.b, alpha=kw["alpha"], inplane_bc=kw["inplane_bc"], sigma=thermal.field(**kw),
            temperature=lambda x: thermal.temperature(x, kw["amplitude"], ctx.b, kw["s"])),
        "r_heat": var("r_heat", r, "m", "radius of the cutting-heat stress"),
        "heat_temperature": var("r_heat", thermal.temperature(r, kw["amplitude"], ctx.b, kw["s"]),
                                "K", "temperature rise of the blade in the cut"),
        "heat_sigma_theta": var("r_heat", st, "Pa", "hoop stress of the cutting heat"),
    }


# --- stage 3: analyses of the discretised disk ---------------------------------------------
def _stiffened(ctx):
    """[K^(sigma)] of every r_c (the analyses that read it need the residual stress)."""
    if ctx.loads is None:
        raise Refusal("this analysis needs the residual stress: name 'roll_tension'")
    return ctx.k_sigma


def _disk_key(ctx, *more) -> tuple:
    """What a reference of the plain disk depends on (the key of its cold cost and memo)."""
    return (float(ctx.r_f), float(ctx.b), float(ctx.h), float(ctx.E), float(ctx.nu),
            float(ctx.rho), tuple(int(n) for n in ctx.n_d), *more)


def _exact_frequencies(ctx, sigma=0.0, memo=True):
    """Exact Bessel frequencies [Hz] of every N_d of the plain annulus under ``sigma`` [Pa]."""
    return [exact.natural_frequencies(n, a=ctx.r_f, b=ctx.b, h=ctx.h, E=ctx.E, nu=ctx.nu,
                                      rho=ctx.rho, sigma=sigma, memo=memo)[0] for n in ctx.n_d]


@EFFECTS.register("exact_reference")
def exact_reference(ctx) -> dict:
    """Exact Bessel frequencies of the unrolled clamped-free annulus (plain disk)."""
    return {"f_exact": var("n_d", _exact_frequencies(ctx), "Hz", "exact unrolled frequency"),
            "exact_reference_time_cold": _cold("exact_reference", _disk_key(ctx),
                                               lambda: _exact_frequencies(ctx, memo=False))}


#: rolled references solved in this process, by every parameter they depend on (the 2-D
#: Table 1-2 scene and its cost study share one)
_ROLLED_REFERENCES: dict = {}


@EFFECTS.register("rolled_reference")
def rolled_reference(ctx) -> dict:
    """Rolled frequencies by Richardson (h^4) of 64 and 128 axisym elements, and its error."""
    key = _disk_key(ctx, float(ctx.A), float(ctx.s), ctx.bc,
                    tuple((ld.r_c, float(ld.alpha), ld.inplane_bc) for ld in ctx.loads))
    if key not in _ROLLED_REFERENCES:
        _ROLLED_REFERENCES[key] = _solve_rolled_reference(ctx)
    f_ref, err = _ROLLED_REFERENCES[key]
    n0, n1 = REFERENCE_ELEMENTS
    return {
        "f_rolled_reference": var(("r_c", "n_d"), f_ref.copy(), "Hz", "rolled frequency: "
                                  f"Richardson (h^4) of {n0} and {n1} axisym elements"),
        "reference_error_unrolled": var((), err, "1", "its max |relative error| on the unrolled "
                                        "frequencies"),
        "rolled_reference_time_cold": _cold("rolled_reference", key,
                                            lambda: _solve_rolled_reference(ctx)),
    }


def _solve_rolled_reference(ctx):
    """(Richardson rolled frequencies [r_c, n_d], its max error on the unrolled ones)."""
    runs = []
    for n_el in REFERENCE_ELEMENTS:
        disk = AxisymDisk(r_f=ctx.r_f, b=ctx.b, h=ctx.h, E=ctx.E, nu=ctx.nu, rho=ctx.rho,
                          n_d=ctx.n_d, n_elements=n_el)
        f_u = frequency(disk.unrolled())
        f_r = frequency(np.stack([disk.rolled(disk.stress_stiffness(ld.sigma))[0]
                                  for ld in ctx.loads]))
        runs.append((f_u, f_r))
    (u0, r0), (u1, r1) = runs
    richardson = lambda f0, f1: extrapolate(f0, f1, 2.0, 4.0)  # noqa: E731  (h^4, n and 2n)
    return richardson(r0, r1), np.max(np.abs(richardson(u0, u1) / _exact_frequencies(ctx) - 1))


@EFFECTS.register("stressed_reference")
def stressed_reference(ctx) -> dict:
    """Eqs. 3, 5 under each uniform ``reference_stress`` against the exact Bessel solution."""
    s0 = np.atleast_1d(np.asarray(ctx.p["reference_stress"], float))
    model = ctx.model
    with phase("disk_tension.stressed_reference_fe") as sw:
        w2 = np.stack([model.rolled(model.stress_stiffness(model.uniform_stress(s)))[0]
                       for s in s0])
    if np.any(~(w2 > 0)):
        bad = s0[np.any(~(w2 > 0), axis=1)]
        raise Refusal(f"reference_stress {bad.tolist()} Pa buckles the disk: the exact "
                         "reference needs a stable disk (choose a smaller compression)")
    with phase("disk_tension.stressed_reference_exact"):
        f_ex = np.array([_exact_frequencies(ctx, s) for s in s0])
    f, dims = frequency(w2), ("reference_stress", "n_d")
    return {
        "reference_stress": var("reference_stress", s0, "Pa", "uniform in-plane stress"),
        "f_stressed": var(dims, f, "Hz", "frequency under the uniform stress, Eqs. 3, 5"),
        "f_stressed_exact": var(dims, f_ex, "Hz", "exact frequency under the uniform stress"),
        "error_stressed": var(dims, f / f_ex - 1.0, "1", "relative error of f_stressed"),
        "time_stressed": var((), sw.seconds, "s", "wall time of K^(sigma) and Eq. (5) there"),
        "stressed_reference_time_cold": _cold(
            "stressed_reference", _disk_key(ctx, tuple(s0)),
            lambda: [_exact_frequencies(ctx, s, memo=False) for s in s0], plus=sw.seconds),
    }


@EFFECTS.register("eigen")
def eigen(ctx) -> dict:
    """Eq. (5) for every r_c (NaN and a flag if buckled); on the 2-D mesh both pair members."""
    model, ks = ctx.model, _stiffened(ctx)
    pairs_of = getattr(model, "degenerate_pairs", False)
    w2 = np.full((len(ks), len(ctx.n_d)), np.nan)
    pairs = np.full((len(ks), len(ctx.n_d), 2), np.nan)
    with phase("disk_tension.eigen") as sw:
        for i, k in enumerate(ks):
            w2[i] = model.rolled(k)[0]
            for j, n in enumerate(ctx.n_d if pairs_of else ()):
                pairs[i, j, :] = model.rolled_pairs[n]   # one value (N_d = 0) fills both
    out = {
        "omega2_rolled": var(("r_c", "n_d"), w2, "rad2/s2", "omega~^2 after rolling, Eq. (5)"),
        "f_rolled": var(("r_c", "n_d"), frequency(w2), "Hz", "rolled frequency, Eq. (5) (NaN: "
                        "buckled)"),
        "buckled": var(("r_c", "n_d"), (w2 < 0).astype(np.int8), "1", "1 where omega~^2 < 0"),
        "time_eigen": var((), sw.seconds, "s", "wall time of Eq. (5) over the r_c grid"),
    }
    if pairs_of:
        out["member"] = var("member", [0, 1], "1", "member of a sin/cos pair (ascending)")
        out["f_rolled_pair"] = var(("r_c", "n_d", "member"), frequency(pairs), "Hz",
                                   "rolled frequency of each pair member (split by slots)")
    return out


@EFFECTS.register("eq9")
def eq9(ctx) -> dict:
    """Eq. (9): Delta omega^2 = phi^T K^(sigma) phi and its two conversions to Delta f."""
    model, ks = ctx.model, _stiffened(ctx)
    with phase("disk_tension.eq9") as sw:
        d = np.stack([model.eq9(k) for k in ks])
    w = ctx.omega_unrolled
    return {
        "delta_omega2_eq9": var(("r_c", "n_d"), d, "rad2/s2", "Delta omega^2 by Eq. (9)"),
        "delta_f_eq9_linearised": var(("r_c", "n_d"), delta_f_linearised(w, d), "Hz",
                                      "Delta f = Delta omega^2 / (2 omega) / 2 pi (first order)"),
        "delta_f_eq9_exact": var(("r_c", "n_d"), delta_f_exact(w, d), "Hz",
                                 "Delta f = (sqrt(omega^2 + Delta omega^2) - omega) / 2 pi"),
        "time_eq9": var((), sw.seconds, "s", "wall time of Eq. (9) over the r_c grid"),
    }


@EFFECTS.register("critical_load")
def critical_load(ctx) -> dict:
    """Load factor on the residual stress that buckles the disk (inf: never)."""
    lam = np.array([ctx.model.critical_load(k) for k in _stiffened(ctx)])
    return {"critical_load_factor": var(("r_c", "n_d"), lam, "1",
                                        "load factor that buckles (inf: never)")}


@EFFECTS.register("modal_matrices")
def modal_matrices(ctx) -> dict:
    """Eqs. (16)-(17) at the first r_c (Tables 1-2); on the harmonics also the largest mode
    change a stable disk can show (stress scaled to just below buckling)."""
    model, ks = ctx.model, _stiffened(ctx)[0]
    k_hat, m_hat = model.modal_matrices(ks)
    out = {
        "row": var("row", ctx.n_d, "1", "N_d of the row mode"),
        "col": var("col", ctx.n_d, "1", "N_d of the column mode"),
        "k_sigma_hat": var(("row", "col"), k_hat, "rad2/s2", "Eq. (16), first r_c"),
        "m_hat": var(("row", "col"), m_hat, "1", "Eq. (17), first r_c (pairs canonical)"),
    }
    if hasattr(model, "m_hat_diag"):
        lam = float(np.min(model.critical_load(ks)))
        out["buckling_load_factor"] = var((), lam, "1", "load factor that buckles any N_d")
        # a stress that buckles no harmonic (lam = inf: an all-tensile stress) has no "just
        # below buckling": NaN, not a solve at an infinite load
        out["m_hat_diag_at_buckling"] = var(
            "n_d", model.m_hat_diag(ks, scale=(1 - 1e-6) * lam) if np.isfinite(lam)
            else np.full(len(ctx.n_d), np.nan), "1",
            "diagonal of Eq. (17) with the residual stress scaled to just below the buckling "
            "load: the largest mode change a stable disk can show (NaN if none buckles)")
    return out


@EFFECTS.register("stiffness_sensitivity")
def stiffness_sensitivity(ctx) -> dict:
    """Fig. 7: Delta f of a 1 % stiffer 10 mm annulus at each r_a (re-solved per r_a; annuli
    outside [r_f, b] are refused at load, :mod:`.limits`)."""
    p = ctx.p
    r_a = np.atleast_1d(np.asarray(p["annulus_radii"], float))
    d = ctx.model.sensitivity(r_a=r_a, width=p["annulus_width"], E=ctx.E, nu=ctx.nu, rho=ctx.rho,
                              increase=p["stiffness_increase"])
    return {"r_a": var("r_a", r_a, "m", "centre radius of the stiffened annulus"),
            "sensitivity_delta_f": var(("r_a", "n_d"), d, "Hz", "Delta f of Fig. 7")}


#: the identifiability profiles' fine grids: steps per coarse step of the scan (c, s)
FINE_SCALE, FINE_WIDTH = 40, 5


def _scan(start, stop, step, fine):
    """(the scan start..stop by step, the same span ``fine`` times finer)."""
    return (np.arange(start, stop + step / 2, step),
            np.linspace(start, stop, int(round((stop - start) / (step / fine))) + 1))


def _legend(names) -> str:
    """'0 a, 1 b, ...': what each integer code stands for."""
    return ", ".join(f"{i} {k}" for i, k in enumerate(names))


def _coded(dim, names, what):
    """Coordinate ``dim``: the integer codes of ``names``, named by :func:`_legend`."""
    return var(dim, np.arange(len(names)), "1", f"{what}: {_legend(names)}")


@EFFECTS.register("identifiability")
def identifiability(ctx) -> dict:
    """What the paper's numbers pin down: the joint fit of :mod:`.identifiability`."""
    p = ctx.p
    widths, fine_widths = _scan(*p["scan_gaussian_width"], FINE_WIDTH)
    scales, fine = _scan(*p["scan_stress_scale"], FINE_SCALE)
    r = idf.analyse(ctx.model, widths=widths, scales=scales, fine=fine, fine_widths=fine_widths,
                    single_width=ctx.s, table1_paper=np.asarray(p["fit_table1_diagonal"], float),
                    f_rolled_paper=float(p["fit_rolled_frequency"]),
                    r_c=p["calibration_rolling_radius"], alpha=ctx.alpha, E=ctx.E, nu=ctx.nu,
                    amplitude=p["calibration_temperature_amplitude"])
    sub, dat, lvl = "fit_data", "fit_datum", ("fit_data", "fit_level", "scan_condition",
                                                "scan_width")
    out = {
        "fit_data": _coded(sub, idf.SUBSETS, "data fitted"),
        "fit_datum": _coded(dat, idf.DATA, "paper number"),
        "fit_parameter": var("fit_parameter", [0, 1], "1", "0 gaussian width, 1 stress scale"),
        "scan_condition": _coded("scan_condition", idf.CONDITIONS, "in-plane condition"),
        "scan_width": var("scan_width", fine_widths, "m", "Gaussian width s (fine grid)"),
        "scan_scale": var("scan_scale", fine, "1", "stress scale c = E alpha A / handbook"),
        "fit_level": var("fit_level", list(idf.LEVELS.values()), "1",
                         "Delta chi^2 of the joint (s, c) regions: "
                         + ", ".join(f"{k} %" for k in idf.LEVELS)),
        "fit_axis": var("fit_axis", [0, 1], "1", "0 the soft (degenerate) axis, 1 the stiff"),
        "single_width": var((), ctx.s, "m", "Gaussian width of the single-alpha calibration"),
    }
    sw, sc, sa = (sub, "scan_width"), (sub, "scan_scale"), (sub, "fit_axis")
    for key, dims, unit, name in (
            ("prof_width", sw, "1", "profile chi^2 over s (Birge-scaled)"),
            ("prof_scale", sc, "1", "profile chi^2 over c (Birge-scaled)"),
            ("prof_condition", (sub, "scan_condition"), "1", "profile chi^2 over the condition"),
            ("prof_width_scale", sw, "1", "the valley floor along s: c minimising chi^2"),
            ("prof_scale_width", sc, "m", "the valley floor along c: s minimising chi^2"),
            ("birge", sub, "1", "Birge factor: chi^2 per degree of freedom of the best fit"),
            ("chi2_min", sub, "1", "Birge-scaled chi^2 of the best fit"),
            ("best_width", sub, "m", "best-fit Gaussian width s"),
            ("best_scale", sub, "1", "best-fit stress scale c"),
            ("best_condition", sub, "1", "best-fit in-plane condition"),
            ("best_table1_rel", (sub, "n_d"), "1", "Table 1 relative error at the best fit"),
            ("best_f_rolled", sub, "Hz", "f~(N_d = 4, r_c = 65 mm) at the best fit"),
            ("shares", (sub, "fit_parameter", dat), "1", "Fisher share of each paper number"),
            ("region_c_lo", lvl, "1", "lower c of the joint (s, c) region (NaN: none)"),
            ("region_c_hi", lvl, "1", "upper c of the joint (s, c) region (NaN: none)"),
            ("direction_slope", sub, "1", "d ln c / d ln s along the Hessian's soft axis"),
            ("direction_halfwidth", sa, "1", "68 % half-lengths along the soft, stiff axes"),
            ("single_chi2", sub, "1", "Birge-scaled chi^2 of the single-alpha calibration"),
            ("single_scale", (), "1", "stress scale of the single-alpha calibration"),
            ("single_table1_rel", "n_d", "1", "its Table 1 relative error"),
            ("single_f_rolled", (), "Hz", "its f~(N_d = 4, r_c = 65 mm)")):
        out[key] = var(dims, r[key], unit, name)
    return out


def _centrifugal_stiffness(ctx):
    """K^(c) of every harmonic: Eq. (3) of the centrifugal stress at Omega = 1 rad/s."""
    kw = dict(omega=1.0, rho=ctx.rho, nu=ctx.nu, r_f=ctx.r_f, b=ctx.b,
              inplane_bc=ctx.p["centrifugal_bc"])
    return ctx.model.stress_stiffness((lambda r: rotation.centrifugal_stress(r, **kw)[0],
                                       lambda r: rotation.centrifugal_stress(r, **kw)[1]))


@EFFECTS.register("critical_speed")
def critical_speed(ctx) -> dict:
    """The travelling-wave critical speed per N_d (:mod:`.rotation`), untensioned (with
    Southwell's first-order form) and with the rolled stress of every r_c (NaN: buckled)."""
    model, bc = ctx.model, ctx.p["centrifugal_bc"]
    Kc = _centrifugal_stiffness(ctx)
    with phase("disk_tension.critical_speed") as sw:
        free = np.array([rotation.critical_speed(model.K[n], model.M[n], Kc[n], int(n))
                         for n in ctx.n_d])
        sw_pairs = [rotation.southwell(model.omega2[n], model.phi[n], model.M[n], Kc[n], int(n))
                    for n in ctx.n_d]
        ks = ctx.k_sigma if ctx.loads is not None else []
        rolled = np.array([[rotation.critical_speed(model.K[n] + k[n], model.M[n], Kc[n], int(n))
                            for n in ctx.n_d] for k in ks]).reshape(len(ks), len(ctx.n_d))
    out = {
        "critical_speed_untensioned": var("n_d", free, "rad/s", "critical speed, unrolled "
                                          "(inf: none)", centrifugal_bc=bc),
        "critical_speed_southwell": var("n_d", [p[1] for p in sw_pairs], "rad/s", "Southwell's "
                                        "omega / sqrt(N_d^2 - lambda)", centrifugal_bc=bc),
        "southwell_coefficient": var("n_d", [p[0] for p in sw_pairs], "1", "Southwell's lambda",
                                     centrifugal_bc=bc),
        "time_critical_speed": var((), sw.seconds, "s", "wall time of the critical speeds"),
    }
    if len(ks):
        out["critical_speed"] = var(("r_c", "n_d"), rolled, "rad/s", "critical speed, rolled "
                                    "(NaN: buckled; inf: none)", centrifugal_bc=bc)
    return out


@EFFECTS.register("design_map")
def design_map(ctx) -> dict:
    """The tensioning design map (:mod:`.design`) at every ``buckling_margin``."""
    p, model = ctx.p, ctx.model
    Kc = _centrifugal_stiffness(ctx)
    if not ctx.A > 0:
        raise Refusal("design_map scales the rolled stress of the scene's amplitude: "
                      f"temperature_amplitude must be > 0, got {ctx.A}")
    margins = np.sort(np.atleast_1d(np.asarray(p["buckling_margin"], float)))
    stated = float(np.median(margins))
    cap = float(p["design_amplitude_cap"]) / ctx.A       # as a load factor on the scene's A
    steps, n_d, ks = int(p["design_steps"]), ctx.n_d, _stiffened(ctx)
    nr, nm, nn = len(ks), len(margins), len(n_d)
    cs, amp = np.full((nr, steps, nn), np.nan), np.zeros((nr, steps))
    lam_cr, mode_cr, paper = np.full(nr, np.inf), np.full(nr, -1), np.full(nr, np.nan)
    best = {k: np.full((nm, nr), np.nan) for k in ("a", "v", "binds", "mode")}
    best_f = np.full((nm, nr, nn), np.nan)
    w0 = np.array([model.omega2[n] for n in n_d])
    # in the cut (effect cutting_heat) the spinning blade carries the rim's heat stress; the
    # buckling margin is the cold blade's at rest
    K = model.K if ctx.k_heat is None else {n: model.K[n] + ctx.k_heat[n] for n in n_d}
    rim = 0.0 if ctx.heat is None else float(p["rim_temperature_rise"])
    with phase("disk_tension.design_map") as sw:
        for i, k in enumerate(ks):
            low = partial(design.lowest, design.pencils(K, k, model.M, Kc, n_d))
            lam = model.critical_load(k)
            lam_cr[i], mode_cr[i] = float(np.min(lam)), int(n_d[np.argmin(lam)])
            tops = np.minimum(lam_cr[i] / margins, cap)
            grid = np.linspace(0.0, tops.max(), steps)
            v, _, c, _ = low(np.r_[grid, tops, 1.0])
            cs[i], amp[i], paper[i] = c[:steps], grid * ctx.A, v[-1]
            for q, top in enumerate(tops):
                sel = grid < top
                x, val, bnd = design.optimum(lambda a: float(low([a])[0][0]),
                                             np.r_[grid[sel], top], np.r_[v[:steps][sel], v[steps + q]],
                                             capped=bool(top >= cap))
                _, md, _, w2x = low([x])
                best["a"][q, i], best["v"][q, i] = x * ctx.A, val
                best["binds"][q, i], best["mode"][q, i] = bnd, md[0]
                best_f[q, i] = np.sqrt(np.clip(w2x[0], 0, None) / w0)
    dims, bc = ("design_margin", "r_c"), {"centrifugal_bc": p["centrifugal_bc"]}
    return {
        "design_margin": var("design_margin", margins, "1", "buckling margin m (A <= A_cr / m)"),
        "design_step": var("design_step", np.arange(steps), "1", "step of the amplitude scan"),
        "design_stated_margin": var((), stated, "1", "the stated buckling margin (the map's)"),
        "design_amplitude": var(("r_c", "design_step"), amp, "K", "rolling amplitude A, Eq. (4)"),
        "design_critical_speed": var(("r_c", "design_step", "n_d"), cs, "rad/s", "critical "
                                     "speed (NaN: buckled; inf: none)", **bc),
        "design_buckling_amplitude": var("r_c", lam_cr * ctx.A, "K", "A_cr: buckles at rest"),
        "design_buckling_mode": var("r_c", mode_cr, "1", "N_d that buckles first"),
        "design_amplitude_cap": var((), cap * ctx.A, "K", "the amplitude scan's end"),
        "design_paper_amplitude_speed": var("r_c", paper, "rad/s", "lowest critical speed at "
                                            "the scene's A", **bc),
        "design_best_amplitude": var(dims, best["a"], "K", "the A maximising it"),
        "design_best_speed": var(dims, best["v"], "rad/s", "the lowest critical speed there", **bc),
        "design_best_binds": var(dims, best["binds"], "1",
                                 "what binds there: " + _legend(design.BINDS)),
        "design_best_mode": var(dims, best["mode"], "1", "N_d of the lowest critical speed there"),
        "design_best_frequency_ratio": var(dims + ("n_d",), best_f, "1", "rolled / unrolled "
                                           "frequency at rest there"),
        "design_rim_temperature_rise": var((), rim, "K", "rim temperature rise of the cut"),
        "time_design_map": var((), sw.seconds, "s", "wall time of the design map"),
    }
