"""Compose the disk_tension effects named by a scene into one xarray Dataset.

Effects (declaration order = evaluation order):

``exact_reference``      Bessel-function frequencies of the unrolled annular plate
``stress_calibration``   effective alpha of the thermal analogy from Table 1 (N_d = 4)
``roll_tension``         Eq. (4) temperature and the plane-stress residual stress
``slots``                radial expansion slots (2-D model only)
``axisym``               discretisation 1: cos(N_d theta) harmonics, radial Hermite elements
``plate2d``              discretisation 2: Argyris plate FE on a mesh (scikit-fem)
``eigen``                Eq. (5): frequencies after rolling by eigen-analysis
``eq9``                  Eq. (9): first-order estimate from the unrolled modes
``critical_load``        load factor at which the residual stress buckles the disk
``modal_matrices``       Eqs. (16)-(17) at the first r_c of the scene
``stiffness_sensitivity`` Fig. 7: 1 % stiffer 10 mm annulus at r_a (axisym)
"""
from __future__ import annotations

import numpy as np
import xarray as xr

from mechrepro.timing import time_call
from mechrepro.effects import EffectRegistry

from . import calibration, exact, thermal
from .axisym import AxisymDisk
from .modal import delta_f_exact, delta_f_linearised, frequency

EFFECTS = EffectRegistry("disk_tension")
MODEL_EFFECTS = ("axisym", "plate2d")
NEEDS_STRESS = ("eigen", "eq9", "critical_load", "modal_matrices")


class Context:
    """Parameters in SI, the calibrated thickness, and the variables produced so far."""

    def __init__(self, run: dict):
        p, self.run = run["parameters"], run
        self.effects = list(run["effects"])
        self.resolution = run.get("resolution", {})
        self.b = 0.5 * p["outer_diameter"]
        self.r_f = p["clamp_radius"]
        self.r_c = np.atleast_1d(np.asarray(p["rolling_radius"], float))
        self.n_d = np.atleast_1d(np.asarray(p["nodal_diameters"], int))
        self.E, self.nu, self.rho = p["youngs_modulus"], p["poisson_ratio"], p["density"]
        self.alpha = p["thermal_expansion"]
        self.A, self.s = p["temperature_amplitude"], p["gaussian_width"]
        self.bc = p["inplane_bc"]
        self.p = p
        self._check()
        self.h = calibration.thickness(f_target=p["calibration_frequency"],
                                       n_d=int(p["calibration_nodal_diameter"]),
                                       r_f=p["calibration_clamp_radius"], b=self.b,
                                       E=self.E, nu=self.nu, rho=self.rho)
        self.vars: dict = {}
        self.coords: dict = {
            "n_d": ("n_d", self.n_d, {"long_name": "number of nodal diameters N_d", "units": "1"}),
            "r_c": ("r_c", self.r_c, {"long_name": "centre radius of rolling r_c, Eq. (4)",
                                      "units": "m"}),
        }
        self.models: dict = {}
        self.slots = None
        self.put("thickness", (), self.h, "m", "disk thickness h (calibrated on the unrolled "
                 "N_d = 4 frequency, Sec. 4.3)")
        self.put("clamp_radius", (), self.r_f, "m", "clamping radius r_f")

    def _check(self):
        if not 0 < self.r_f < self.b:
            raise ValueError(f"clamp_radius r_f = {self.r_f} m must lie in (0, b = {self.b} m)")
        if np.any(self.n_d < 0):
            raise ValueError(f"nodal_diameters must be >= 0, got {self.n_d.tolist()}")
        if self.bc not in thermal.INPLANE_BCS:
            raise ValueError(f"inplane_bc = {self.bc!r}: allowed {thermal.INPLANE_BCS}")
        chosen = [e for e in self.effects if e in MODEL_EFFECTS]
        if any(e in self.effects for e in NEEDS_STRESS + ("stiffness_sensitivity",)) and not chosen:
            raise ValueError(f"effects {self.effects}: name a discretisation ({MODEL_EFFECTS})")
        for e in NEEDS_STRESS:
            if e in self.effects and "roll_tension" not in self.effects:
                raise ValueError(f"effect {e!r} needs 'roll_tension' (the residual stress)")
        if "slots" in self.effects and "plate2d" not in self.effects:
            raise ValueError("effect 'slots' needs 'plate2d': the axisymmetric model cannot "
                             "carry slots")
        if "slots" in self.effects and "axisym" in self.effects:
            raise ValueError("effects 'slots' and 'axisym' exclude each other: a slotted "
                             "blade is not axisymmetric")
        if "stiffness_sensitivity" in self.effects and "axisym" not in self.effects:
            raise ValueError("effect 'stiffness_sensitivity' is computed with 'axisym'")

    def put(self, name, dims, data, units, long_name):
        self.vars[name] = (dims, np.asarray(data), {"units": units, "long_name": long_name})

    def stress(self, r_c, inplane_bc=None):
        kw = dict(amplitude=self.A, r_c=float(r_c), s=self.s, r_f=self.r_f, b=self.b, E=self.E,
                  nu=self.nu, alpha=self.alpha, inplane_bc=inplane_bc or self.bc)
        return (lambda r: thermal.thermal_stress(r, **kw)[0],
                lambda r: thermal.thermal_stress(r, **kw)[1])

    def temperature(self, r_c):
        return lambda r: thermal.temperature(r, self.A, float(r_c), self.s)

    def timed(self, fn, *args):
        """(result, fastest wall time [s]) of ``fn(*args)``: fast phases are repeated for at
        least ``options.timing_min_s`` (default 0.05 s) so a timing is not one noisy sample;
        the result is that of the first call."""
        opts = self.run.get("options") or {}
        return time_call(fn, *args, min_time=float(opts.get("timing_min_s", 0.05)))

    def dataset(self) -> xr.Dataset:
        return xr.Dataset(self.vars, coords=self.coords)


@EFFECTS.register("exact_reference")
def _exact(ctx: Context):
    f = [exact.natural_frequencies(n, a=ctx.r_f, b=ctx.b, h=ctx.h, E=ctx.E, nu=ctx.nu,
                                   rho=ctx.rho)[0] for n in ctx.n_d]
    ctx.exact = np.array(f)
    ctx.put("f_exact", ("n_d",), ctx.exact, "Hz",
            "exact unrolled frequency (Bessel solution, clamped-free annular plate)")


@EFFECTS.register("stress_calibration")
def _calibrate(ctx: Context):
    p = ctx.p
    handbook = ctx.alpha
    ctx.alpha, d_hb, df_hb = calibration.alpha_effective(
        target=p["calibration_delta_omega2"], n_d=int(p["calibration_nodal_diameter"]),
        r_c=p["calibration_rolling_radius"], r_f=p["calibration_clamp_radius"], b=ctx.b,
        h=ctx.h, E=ctx.E, nu=ctx.nu, rho=ctx.rho, alpha=handbook,
        amplitude=p["calibration_temperature_amplitude"], s=p["calibration_gaussian_width"],
        inplane_bc=ctx.bc)
    ctx.put("alpha_effective", (), ctx.alpha, "1/K",
            "thermal-analogy expansion coefficient calibrated on Table 1 (N_d = 4)")
    ctx.put("stress_scale", (), ctx.alpha / handbook, "1",
            "calibrated / handbook expansion coefficient")
    ctx.put("handbook_delta_omega2_eq9", (), d_hb, "rad2/s2",
            "Eq. (9) Delta omega^2 of the calibration case with the handbook alpha")
    ctx.put("handbook_delta_f_eigen", (), df_hb, "Hz",
            "eigen-analysis Delta f of the calibration case with the handbook alpha")


@EFFECTS.register("roll_tension")
def _roll_tension(ctx: Context):
    """Eq. (4) temperature and its plane-stress field for the scene's ``inplane_bc`` only
    (the other condition is another scene, or a range variant of the run)."""
    r = np.linspace(0.0, ctx.b, 256)
    ctx.coords["r"] = ("r", r, {"long_name": "radius", "units": "m"})
    T = np.stack([thermal.temperature(r, ctx.A, rc, ctx.s) for rc in ctx.r_c])
    ctx.put("temperature", ("r_c", "r"), T, "K", "thermal-analogy temperature T(r), Eq. (4)")
    sr = np.full((len(ctx.r_c), len(r)), np.nan)
    st = sr.copy()
    ok = r >= (ctx.r_f if ctx.bc == "clamped" else r[1])
    for j, rc in enumerate(ctx.r_c):
        a, b_ = ctx.stress(rc)
        sr[j, ok], st[j, ok] = a(r[ok]), b_(r[ok])
    ctx.put("sigma_r", ("r_c", "r"), sr, "Pa",
            f"radial residual stress (thermal analogy, plane stress, {ctx.bc})")
    ctx.put("sigma_theta", ("r_c", "r"), st, "Pa",
            f"circumferential residual stress (thermal analogy, plane stress, {ctx.bc})")
    ctx.put("alpha_used", (), ctx.alpha, "1/K", "expansion coefficient used for the stress")
    ctx.put("amplitude_used", (), ctx.A, "K", "temperature amplitude A of Eq. (4) used for the stress")


@EFFECTS.register("slots")
def _slots(ctx: Context):
    from .plate2d import Slots  # scikit-fem is imported only by scenes that use it

    p = ctx.p
    ctx.slots = Slots(int(p["slot_count"]), p["slot_depth"], p["slot_width"])
    ctx.put("slot_count", (), ctx.slots.count, "1", "number of radial expansion slots")


def _model_common(ctx: Context, model, name):
    w2, t_unrolled = ctx.timed(model.unrolled)
    ctx.models[name] = model
    f = frequency(w2)
    ctx.put(f"{name}_f_unrolled", ("n_d",), f, "Hz", f"{name}: unrolled frequency, Eq. (6)")
    ctx.put(f"{name}_time_unrolled", (), t_unrolled + model.build_time, "s",
            f"{name}: wall time of assembly + unrolled eigen-analysis")
    if hasattr(ctx, "exact"):
        err = f / ctx.exact - 1.0
        ctx.put(f"{name}_error_unrolled", ("n_d",), err, "1",
                f"{name}: relative error of the unrolled frequency vs exact")
        ctx.put(f"{name}_error_unrolled_max", (), np.max(np.abs(err)), "1",
                f"{name}: max |relative error| of unrolled frequencies vs exact")


@EFFECTS.register("axisym")
def _axisym(ctx: Context):
    n_el = int(ctx.resolution.get("n_elements", 64))
    model, t_build = ctx.timed(lambda: AxisymDisk(r_f=ctx.r_f, b=ctx.b, h=ctx.h, E=ctx.E,
                                                  nu=ctx.nu, rho=ctx.rho, n_d=ctx.n_d,
                                                  n_elements=n_el))
    model.build_time = t_build
    _model_common(ctx, model, "axisym")


@EFFECTS.register("plate2d")
def _plate2d(ctx: Context):
    from .plate2d import PlateDisk  # scikit-fem is imported only by scenes that use it

    model, t_build = ctx.timed(lambda: PlateDisk(
        r_f=ctx.r_f, b=ctx.b, h=ctx.h, E=ctx.E, nu=ctx.nu, rho=ctx.rho, n_d=ctx.n_d,
        n_rings=int(ctx.resolution.get("n_rings", 12)),
        n_sectors=int(ctx.resolution.get("n_sectors", 64)), slots=ctx.slots,
        seed=int(ctx.run.get("seed", 0))))
    model.build_time = t_build
    ctx.put("plate2d_n_dofs", (), model.basis.N, "1", "plate2d: number of Argyris DOFs")
    # Fig. 3: the mesh itself (annulus r_f..b; the core r < r_f is clamped)
    ctx.coords["mesh_node"] = ("mesh_node", np.arange(model.mesh.p.shape[1]),
                               {"long_name": "node of the 2-D mesh", "units": "1"})
    ctx.coords["mesh_cell"] = ("mesh_cell", np.arange(model.mesh.t.shape[1]),
                               {"long_name": "triangle of the 2-D mesh", "units": "1"})
    ctx.coords["vertex"] = ("vertex", [0, 1, 2], {"long_name": "triangle vertex", "units": "1"})
    ctx.put("plate2d_mesh_x", ("mesh_node",), model.mesh.p[0], "m", "plate2d: node x")
    ctx.put("plate2d_mesh_y", ("mesh_node",), model.mesh.p[1], "m", "plate2d: node y")
    ctx.put("plate2d_mesh_cells", ("mesh_cell", "vertex"), model.mesh.t.T.astype(np.int32), "1",
            "plate2d: node indices of each triangle")
    _model_common(ctx, model, "plate2d")


def _stress_matrices(ctx, name, model):
    """K^(sigma) of every r_c (cached: eigen and eq9 share them, timed separately)."""
    cache = getattr(ctx, "_ks", {})
    ctx._ks = cache
    if name not in cache:
        if name == "plate2d":
            sig, dt = ctx.timed(lambda: [model.residual_stress(ctx.temperature(rc), ctx.alpha,
                                                               ctx.bc) for rc in ctx.r_c])
            cache[name], dt_k = ctx.timed(lambda: [model.stress_stiffness(s) for s in sig])
            dt += dt_k
            _plate2d_stress_profile(ctx, model, sig[0])
        else:
            cache[name], dt = ctx.timed(lambda: [model.stress_stiffness(ctx.stress(rc))
                                                 for rc in ctx.r_c])
        ctx.put(f"{name}_time_stress", (), dt, "s",
                f"{name}: wall time of the thermal stress and K^(sigma) for all r_c")
    return cache[name]


def _plate2d_stress_profile(ctx, model, sigma):
    """FE stress of the first r_c on radial bins, and (plain disk) its error vs Eq. (4)'s
    closed-form plane-stress field."""
    r, sr, st = model.polar_stress(sigma)
    edges = np.linspace(r.min(), r.max(), 81)
    k = np.clip(np.digitize(r, edges) - 1, 0, len(edges) - 2)
    cnt = np.bincount(k, minlength=len(edges) - 1)
    mid = 0.5 * (edges[1:] + edges[:-1])
    ctx.coords["r_bin"] = ("r_bin", mid, {"long_name": "radius (bin centre)", "units": "m"})
    for nm, v in (("sigma_r", sr), ("sigma_theta", st)):
        mean = np.bincount(k, weights=v, minlength=len(mid)) / np.maximum(cnt, 1)
        ctx.put(f"plate2d_{nm}_binned", ("r_bin",), np.where(cnt > 0, mean, np.nan), "Pa",
                f"plate2d: FE {nm} averaged over radial bins (first r_c)")
    if ctx.slots is None:
        a_r, a_t = ctx.stress(ctx.r_c[0])
        rr = np.clip(r, ctx.r_f, ctx.b)
        scale = np.max(np.abs(a_t(rr)))
        dev = np.concatenate([sr - a_r(rr), st - a_t(rr)]) / scale
        ctx.put("plate2d_stress_rel_error_max", (), np.max(np.abs(dev)), "1",
                "plate2d: max |FE - closed-form stress| / max |sigma_theta| (first r_c)")
        ctx.put("plate2d_stress_rel_error_rms", (), np.sqrt(np.mean(dev**2)), "1",
                "plate2d: rms (FE - closed-form stress) / max |sigma_theta| (first r_c)")


@EFFECTS.register("eigen")
def _eigen(ctx: Context):
    for name, model in ctx.models.items():
        Ks = _stress_matrices(ctx, name, model)

        def solve_all():
            w2 = np.full((len(ctx.r_c), len(ctx.n_d)), np.nan)
            pairs = np.full((len(ctx.r_c), len(ctx.n_d), 2), np.nan)
            for i, k in enumerate(Ks):
                w2[i] = model.rolled(k)[0]
                if name == "plate2d":
                    for j, n in enumerate(ctx.n_d):
                        v = model.rolled_pairs[n]
                        pairs[i, j, :] = v if len(v) == 2 else v[0]
            return w2, pairs
        (w2, pairs), dt = ctx.timed(solve_all)
        if name == "plate2d":
            ctx.coords["member"] = ("member", [0, 1], {"long_name": "member of a sin/cos pair "
                                                       "(ascending frequency)", "units": "1"})
            ctx.put("plate2d_f_rolled_pair", ("r_c", "n_d", "member"), frequency(pairs), "Hz",
                    "plate2d: rolled frequency of each pair member (split by slots)")
        ctx.put(f"{name}_omega2_rolled", ("r_c", "n_d"), w2, "rad2/s2",
                f"{name}: omega~^2 after rolling, Eq. (5)")
        ctx.put(f"{name}_f_rolled", ("r_c", "n_d"), frequency(w2), "Hz",
                f"{name}: frequency after rolling by eigen-analysis, Eq. (5) (NaN if buckled)")
        ctx.put(f"{name}_buckled", ("r_c", "n_d"), (w2 < 0).astype(np.int8), "1",
                f"{name}: 1 where omega~^2 < 0 (the residual stress buckles the disk)")
        ctx.put(f"{name}_time_eigen", (), dt, "s",
                f"{name}: wall time of the eigen-analyses over the r_c grid")


@EFFECTS.register("eq9")
def _eq9(ctx: Context):
    for name, model in ctx.models.items():
        Ks = _stress_matrices(ctx, name, model)
        d, dt = ctx.timed(lambda: np.stack([model.eq9(k) for k in Ks]))
        w = np.sqrt(np.array([model.omega2[n].mean() if np.ndim(model.omega2[n]) else
                              model.omega2[n] for n in ctx.n_d]))
        ctx.put(f"{name}_delta_omega2_eq9", ("r_c", "n_d"), d, "rad2/s2",
                f"{name}: Delta omega^2 by Eq. (9)")
        ctx.put(f"{name}_delta_f_eq9_linearised", ("r_c", "n_d"), delta_f_linearised(w, d), "Hz",
                f"{name}: Delta f = Delta omega^2 / (2 omega) / 2 pi (first order)")
        ctx.put(f"{name}_delta_f_eq9_exact", ("r_c", "n_d"), delta_f_exact(w, d), "Hz",
                f"{name}: Delta f = (sqrt(omega^2 + Delta omega^2) - omega) / 2 pi")
        ctx.put(f"{name}_time_eq9", (), dt, "s",
                f"{name}: wall time of Eq. (9) over the r_c grid (K^(sigma) excluded)")
        if f"{name}_omega2_rolled" in ctx.vars:
            w2 = ctx.vars[f"{name}_omega2_rolled"][1]
            f_eig = frequency(w2)
            f_eq9 = frequency(w[None, :] ** 2 + d)
            err = np.abs(f_eq9 - f_eig) / f_eig
            ctx.put(f"{name}_eq9_rel_error_max", (), np.nanmax(err), "1",
                    f"{name}: max |f by Eq. (9) - f by eigen-analysis| / f over the grid")


@EFFECTS.register("critical_load")
def _critical(ctx: Context):
    for name, model in ctx.models.items():
        Ks = _stress_matrices(ctx, name, model)
        if name == "axisym":
            lam = np.stack([model.critical_load(k) for k in Ks])
            ctx.put("axisym_critical_load_factor", ("r_c", "n_d"), lam, "1",
                    "axisym: load factor on the residual stress at which N_d buckles (inf: never)")
        else:
            lam = np.array([model.critical_load(k) for k in Ks])
            ctx.put("plate2d_critical_load_factor", ("r_c",), lam, "1",
                    "plate2d: smallest load factor on the residual stress that buckles the disk")


@EFFECTS.register("modal_matrices")
def _modal(ctx: Context):
    ctx.coords["row"] = ("row", ctx.n_d, {"long_name": "N_d of the row mode", "units": "1"})
    ctx.coords["col"] = ("col", ctx.n_d, {"long_name": "N_d of the column mode", "units": "1"})
    for name, model in ctx.models.items():
        Ks = _stress_matrices(ctx, name, model)[0]
        out = model.modal_matrices(Ks)
        ctx.put(f"{name}_k_sigma_hat", ("row", "col"), out[0], "rad2/s2",
                f"{name}: Eq. (16) Phi^T K^(sigma) Phi (mass-normalised modes), first r_c")
        ctx.put(f"{name}_m_hat", ("row", "col"), out[1], "1",
                f"{name}: Eq. (17) Phi~^T M Phi, first r_c (rolled pairs rotated onto the "
                "unrolled cos/sin basis)")
        if name == "axisym":
            lam = float(np.min(model.critical_load(Ks)))
            ctx.put("axisym_buckling_load_factor", (), lam, "1",
                    "axisym: smallest load factor on the residual stress that buckles any N_d "
                    "(first r_c)")
            ctx.put("axisym_m_hat_diag_at_buckling", ("n_d",),
                    model.m_hat_diag(Ks, scale=(1 - 1e-6) * lam), "1",
                    "axisym: diagonal of Eq. (17) with the residual stress scaled to just below "
                    "the buckling load: the largest mode change a stable disk can show")


@EFFECTS.register("stiffness_sensitivity")
def _sensitivity(ctx: Context):
    p = ctx.p
    r_a = np.atleast_1d(np.asarray(p["annulus_radii"], float))
    w = p["annulus_width"]
    if np.any(r_a - w / 2 < ctx.r_f - 1e-12) or np.any(r_a + w / 2 > ctx.b + 1e-12):
        raise ValueError(f"annulus radii {r_a} +/- {w / 2} must stay inside [r_f, b]")
    d = ctx.models["axisym"].sensitivity(r_a=r_a, width=w, increase=p["stiffness_increase"],
                                         E=ctx.E, nu=ctx.nu, rho=ctx.rho)
    ctx.coords["r_a"] = ("r_a", r_a, {"long_name": "centre radius of the stiffened annulus",
                                      "units": "m"})
    ctx.put("sensitivity_delta_f", ("r_a", "n_d"), d, "Hz",
            "frequency change for a 1 % stiffer 10 mm annulus at r_a (Fig. 7)")


def compute(run: dict) -> Context:
    selected = EFFECTS.select(run["effects"])
    ctx = Context(run)
    for fn in selected.values():
        fn(ctx)
    return ctx


def solve(run: dict) -> xr.Dataset:
    """Entry point of the pipeline: one run record in, one Dataset out."""
    return compute(run).dataset()
