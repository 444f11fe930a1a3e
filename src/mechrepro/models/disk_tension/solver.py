"""The two solvers of disk_tension, one discretisation of the clamped disk each: ``axisym``
(:mod:`.axisym`) and ``plate2d`` (:mod:`.plate2d`).  Both run the effects (:mod:`.effects`) in
three stages read by key -- what the load and mesh need, the load (Eq. 4), then after the
core ([K], [M] of Eq. 1, Eq. 6, [K^(sigma)] of Eq. 3) the rest and the outputs (the analyses).
"""
from __future__ import annotations

import numpy as np

from mechrepro.errors import Refusal
from mechrepro.timing import phase
from mechrepro.units import var

from . import calibration
from .axisym import AxisymDisk
from .effects import EFFECTS
from .modal import frequency

#: contributions the solver consumes (never written to the dataset), by stage
BEFORE_LOAD = {"thermal_expansion", "slots"}
LOAD = {"thermal_load", "cutting_heat_stress"}


class Disk:
    """The context of one run: SI parameters, thickness, what the stages have made."""

    def __init__(self, run: dict):
        p, self.run, self.p = run["parameters"], run, run["parameters"]
        self.solver, self.resolution = run["solver"], run.get("resolution", {})
        self.b = 0.5 * p["outer_diameter"]
        self.r_f = p["clamp_radius"]
        self.r_c = np.atleast_1d(np.asarray(p["rolling_radius"], float))
        self.n_d = np.atleast_1d(np.asarray(p["nodal_diameters"], int))
        self.E, self.nu, self.rho = p["youngs_modulus"], p["poisson_ratio"], p["density"]
        self.A, self.s = p["temperature_amplitude"], p["gaussian_width"]
        self.alpha, self.bc = p["thermal_expansion"], p["inplane_bc"]
        #: the residual-stress model: the paper's, or a rival's (config rivals:)
        self.stress_model = run.get("options", {}).get("residual_stress", "thermal_analogy")
        # what the config cannot refuse (the schema, cross_checks and the effect protocol
        # refuse the rest at load)
        if self.stress_model != "thermal_analogy" and self.solver != "axisym":
            raise Refusal(f"options.residual_stress = {self.stress_model!r}: the rivals' stress "
                          "is closed-form, on the axisym harmonics only (the 2-D model solves "
                          "the paper's plane-stress field by FE)")
        self.h = calibration.thickness(f_target=p["calibration_frequency"],
                                       n_d=int(p["calibration_nodal_diameter"]),
                                       r_f=p["calibration_clamp_radius"], b=self.b,
                                       E=self.E, nu=self.nu, rho=self.rho)
        #: what the stages make; ``heat``: the rim's cutting-heat stress (effect cutting_heat)
        self.slots = self.loads = self.model = self.k_sigma = self.heat = self.k_heat = None
        self.vars = {
            "n_d": var("n_d", self.n_d, "1", "number of nodal diameters N_d"),
            "r_c": var("r_c", self.r_c, "m", "centre radius of rolling r_c, Eq. (4)"),
            "thickness": var((), self.h, "m", "disk thickness h (calibrated on the unrolled "
                             "N_d = 4 frequency, Sec. 4.3)"),
            "clamp_radius": var((), self.r_f, "m", "clamping radius r_f"),
        }

    @property
    def omega_unrolled(self):
        """Unrolled omega of each N_d [rad/s] (the pair mean on the 2-D mesh)."""
        w2 = self.model.omega2
        return np.sqrt(np.array([np.mean(w2[n]) for n in self.n_d]))

    def put(self, name, *variable):
        self.vars[name] = var(*variable)

    def keep(self, contributions):
        """Write the contributions to the dataset, all but those the solver consumes."""
        self.vars.update({k: contributions.get(k) for k in contributions.keys()
                          if k not in BEFORE_LOAD | LOAD})


# --- the core of each solver -----------------------------------------------------------------
def _axisym(ctx: Disk):
    n_el = int(ctx.resolution.get("n_elements", 64))
    model = AxisymDisk(r_f=ctx.r_f, b=ctx.b, h=ctx.h, E=ctx.E, nu=ctx.nu, rho=ctx.rho,
                       n_d=ctx.n_d, n_elements=n_el)
    ctx.put("radial_node", "radial_node", np.arange(n_el + 1), "1", "node of the radial mesh")
    ctx.put("mesh_r", "radial_node", model.mesh.nodes, "m", "radius of the Hermite elements' nodes")
    return model


def _plate2d(ctx: Disk):
    from .plate2d import PlateDisk  # scikit-fem is imported only by scenes that use it

    model = PlateDisk(r_f=ctx.r_f, b=ctx.b, h=ctx.h, E=ctx.E, nu=ctx.nu, rho=ctx.rho,
                      n_d=ctx.n_d, n_rings=int(ctx.resolution.get("n_rings", 12)),
                      n_sectors=int(ctx.resolution.get("n_sectors", 64)), slots=ctx.slots,
                      seed=int(ctx.run.get("seed", 0)))
    ctx.put("n_dofs", (), model.basis.N, "1", "plate2d: number of Argyris DOFs")
    # Fig. 3: the mesh itself (annulus r_f..b; the core r < r_f is clamped)
    ctx.put("mesh_node", "mesh_node", np.arange(model.mesh.p.shape[1]), "1", "node of the 2-D mesh")
    ctx.put("mesh_cell", "mesh_cell", np.arange(model.mesh.t.shape[1]), "1", "triangle of the mesh")
    ctx.put("vertex", "vertex", [0, 1, 2], "1", "triangle vertex")
    ctx.put("mesh_x", "mesh_node", model.mesh.p[0], "m", "plate2d: node x")
    ctx.put("mesh_y", "mesh_node", model.mesh.p[1], "m", "plate2d: node y")
    ctx.put("mesh_cells", ("mesh_cell", "vertex"), model.mesh.t.T.astype(np.int32), "1",
            "node indices of each triangle")
    return model


def _stress_stiffness(ctx: Disk):
    """[K^(sigma)] of every r_c, Eq. (3): from the closed-form stress on the harmonics, from
    the 2-D plane-stress FE solution of the same temperature on the mesh (whose first r_c's
    field, averaged on radial bins, Fig. 5 draws)."""
    model = ctx.model
    with phase("disk_tension.stress") as sw:
        if ctx.solver == "plate2d":
            sig = [model.residual_stress(ld.temperature, ld.alpha, ld.inplane_bc)
                   for ld in ctx.loads]
            ks = [model.stress_stiffness(s) for s in sig]
        else:
            ks = [model.stress_stiffness(ld.sigma) for ld in ctx.loads]
    if ctx.solver == "plate2d":
        from scipy.stats import binned_statistic

        r, sr, st = model.polar_stress(sig[0])
        means, edges, _ = binned_statistic(r, [sr, st], "mean", bins=80)   # NaN: an empty bin
        ctx.put("r_bin", "r_bin", 0.5 * (edges[1:] + edges[:-1]), "m", "radius (bin centre)")
        for nm, mean in zip(("sigma_r", "sigma_theta"), means):
            ctx.put(f"{nm}_binned", "r_bin", mean, "Pa", f"FE {nm} averaged on radial bins (first r_c)")
    ctx.put("time_stress", (), sw.seconds, "s", "wall time of thermal stress + K^(sigma), all r_c")
    return ks


def _discretise(ctx: Disk, mesh):
    """The solver core: [K], [M] (``mesh(ctx)``), the unrolled eigen-analysis (Eq. 6) and
    [K^(sigma)]."""
    with phase("disk_tension.unrolled") as sw:
        ctx.model = model = mesh(ctx)
        w2 = model.unrolled()
    ctx.put("f_unrolled", "n_d", frequency(w2), "Hz", f"{ctx.solver}: unrolled frequency, Eq. (6)")
    ctx.put("time_unrolled", (), sw.seconds, "s", "wall time of assembly + unrolled eigen-analysis")
    if ctx.loads is not None:
        ctx.k_sigma = _stress_stiffness(ctx)
    if ctx.heat is not None:
        ctx.k_heat = model.stress_stiffness(ctx.heat.sigma)


def _compare(ctx: Disk):
    """Errors against the references, Eq. (9) against Eq. (5), the accuracy points' times."""
    get = lambda key: ctx.vars[key][1] if key in ctx.vars else None  # noqa: E731

    f_u, f_r, f_ex = get("f_unrolled"), get("f_rolled"), get("f_exact")
    if f_ex is not None:
        err = f_u / f_ex - 1.0
        ctx.put("error_unrolled", "n_d", err, "1", "relative error of the unrolled frequency")
        ctx.put("error_unrolled_max", (), np.max(np.abs(err)), "1", "its max |value| over N_d")
        _log_sums(ctx, "unrolled", f_u, f_ex, "the unrolled frequencies")
    if get("f_stressed_exact") is not None:
        _log_sums(ctx, "stressed", get("f_stressed"), get("f_stressed_exact"),
                  "the frequencies under every reference stress")
    if f_r is not None and get("f_rolled_reference") is not None:
        _log_sums(ctx, "rolled", f_r, get("f_rolled_reference"),
                  "the rolled frequencies of every r_c", reference="the rolled reference "
                  "(Richardson of 64 and 128 elements, error ~1e-8)")
    if f_r is not None and get("delta_omega2_eq9") is not None:
        f_eq9 = frequency(ctx.omega_unrolled[None, :] ** 2 + get("delta_omega2_eq9"))
        ctx.put("eq9_rel_error", ("r_c", "n_d"), np.abs(f_eq9 - f_r) / f_r, "1",
                "|f by Eq. (9) - f by eigen-analysis| / f")
    if get("time_eigen") is not None:
        t = sum(float(get(k)) for k in ("time_unrolled", "time_stress", "time_eigen"))
        ctx.put("time_solve", (), t, "s", "wall time of assembly + unrolled + K^(sigma) + rolled "
                "eigen-analysis over the r_c grid")
    if get("time_stressed") is not None:
        t = float(get("time_unrolled")) + float(get("time_stressed"))
        ctx.put("time_stressed_solve", (), t, "s", "wall time of assembly + unrolled + K^(sigma) "
                "and Eq. (5) under the reference stresses")


def _log_sums(ctx: Disk, what: str, f, f_exact, of: str, reference="exact Bessel solution"):
    """sum ln(f / 1 Hz) of model and reference: every mode converges from above."""
    ctx.put(f"ln_f_{what}_sum", (), float(np.sum(np.log(f))), "1", f"sum of ln(f / 1 Hz) over {of}")
    ctx.put(f"ln_f_{what}_exact_sum", (), float(np.sum(np.log(f_exact))), "1",
            f"sum of ln(f_exact / 1 Hz) over {of} ({reference})")


def staged(mesh):
    """A solver ``(run, ctx: Disk) -> Disk``: the run's effects evaluated stage by stage
    around the core on the discretisation ``mesh`` (:func:`_axisym`, :func:`_plate2d`), its
    outputs in the last stage."""
    def solve(run: dict, ctx: Disk) -> Disk:
        stage = EFFECTS.stages(run, ctx)
        before = stage(BEFORE_LOAD)
        ctx.alpha, ctx.slots = before.get("thermal_expansion", ctx.alpha), before.get("slots")
        load = stage(LOAD)
        ctx.loads, ctx.heat = load.get("thermal_load"), load.get("cutting_heat_stress")
        _discretise(ctx, mesh)
        for contributions in (before, load, stage()):
            ctx.keep(contributions)
        _compare(ctx)
        return ctx
    return solve


SOLVERS = {"axisym": staged(_axisym), "plate2d": staged(_plate2d)}
context = Disk


def variables(ctx: Disk, run: dict | None = None) -> dict:
    """The run's variables (those named like their only dimension are its coordinates)."""
    return dict(ctx.vars)
