"""The run's linkage as every solver, effect and output sees it (mm, rad): the geometry (tilt
calibrated on the original levers, Sec. 4, then the scene's levers), the cut points, the
pose solvers' settings and one random stream per consumer."""
from __future__ import annotations

import numpy as np

from mechrepro.errors import Refusal

from . import optimise, stroke
from .calibrate import CalibrationError
from .geometry import cut_points, from_parameters
from .selpso import SelPSOSettings


class Refused(Refusal):
    """A lever set the run refuses by name (``calibration``, ``assembly``, ``unbuildable``): a
    result with its reason, not a crash (``solver.refusal_variables``)."""

    def __init__(self, kind: str, message: str):
        super().__init__(f"{kind}: {message}")
        self.kind, self.message = kind, message


class Context:
    """Geometry, cut points, solver settings and random streams of one run."""

    def __init__(self, run: dict):
        p, res, opt = run["parameters"], run["resolution"], run.get("options", {})
        self.p, self.res, self.options = p, res, opt
        self.seed = int(run.get("seed", 0))
        self.n = int(res["n_points"])
        self.tol_floor = float(p["pose_tol"]) * 1e3  # m -> mm
        self.g_uncalibrated = self.g = from_parameters(p)
        target = run.get("calibration", {}).get("theta6_mid")
        self.calibration_target = float(target["value"]) * 1e3 if target is not None else None
        levers = opt.get("levers")
        try:
            self.calibration = self._calibrate() if target is not None else None
        except CalibrationError as exc:
            if levers is None:
                raise
            raise Refused("calibration", str(exc)) from None
        self.g_original = self.g
        if levers is not None and self.calibration is not None:
            self._check_buildable()
        if levers is not None:   # NonAssembly, Unreachable: refused by solver.refusing
            self.g = self.g.with_levers(**{k: float(v) for k, v in levers.items()})
            if self.calibration is not None:
                self.calibration["H_levers"] = optimise.objective(
                    self.g, cut_points(self.g, self.calibration["n"])[1], self.tol_floor)
        self.huch, self.x_k = cut_points(self.g, self.n)
        self.settings = self._settings()
        #: the solved stroke (a :class:`stroke.StrokeSolution`), once a solver has it
        self.stroke: stroke.StrokeSolution | None = None

    def _calibrate(self) -> dict:
        """Fit the tilt on the original levers in every run (range-end variants re-calibrate); the
        scan stops at its bracket, the output tilt_scan scans the rest at its own cost."""
        from .calibrate import calibrate_tilt

        n_cal = int(self.res["calibration_points"])
        self.g, cal = calibrate_tilt(self.g, self.calibration_target, n_cal, self.tol_floor,
                                     whole_scan=False)
        cal["n"] = n_cal
        cal["H_original"] = cal.pop("H")    # the levers calibrated on are the original ones
        return cal

    def _check_buildable(self) -> None:
        """Refuse a calibrated member nobody could build (constraints.py, under ``guide_rod_plane``)."""
        from .constraints import settings, violations

        n = self.calibration["n"]
        theta = stroke.exact_theta(self.g, cut_points(self.g, n)[1])
        broken = violations(self.g, theta, **settings(self.p))
        if broken:
            raise Refused("unbuildable", "; ".join(broken) + f" (tilt {self.calibration['tilt']:.4f} "
                          f"rad calibrated on 1.4341, {n} cut points)")

    def _settings(self) -> stroke.SolverSettings:
        p, res, opt = self.p, self.res, self.options
        newton_tol = float(res.get("newton_tol", p["loops_tol"] * 1e3))
        pso = dict(swarm=int(res.get("pso_swarm", p["pso_swarm"])),
                   max_iter=int(res.get("pso_iter", p["pso_max_iter"])),
                   w_start=p["pso_w_start"], w_end=p["pso_w_end"], c1=p["pso_c1"],
                   c2=p["pso_c2"], v_max=p["pso_v_max"], init_scale=p["pso_init_scale"])
        pso_tol = float(opt.get("pso_tol", p["loops_tol"] * 1e3))
        initial = tuple(float(v) for v in p["initial_value"])
        if self.calibration is not None:
            # the geometry is derived in-run: the rough initial value is its pose at the first
            # cut point rounded to 0.1 rad, as the configured one is for the default geometry
            first = stroke.exact_theta(self.g, self.x_k[:1])[0]
            initial = tuple(float(v) for v in np.round(first, 1))
        std = dict(pso, w_start=p["pso_std_w"], w_end=p["pso_std_w"], c1=p["pso_std_c"],
                   c2=p["pso_std_c"])
        return stroke.SolverSettings(
            tol_loops=newton_tol, tol_pose=max(newton_tol, self.tol_floor), initial_value=initial,
            pso_loops=SelPSOSettings(tol=pso_tol, **pso),
            pso_pose=SelPSOSettings(tol=max(pso_tol, self.tol_floor), **pso),
            pso_std_loops=SelPSOSettings(tol=pso_tol, **std),
            pso_std_pose=SelPSOSettings(tol=max(pso_tol, self.tol_floor), **std))

    def rng(self, salt: int) -> np.random.Generator:
        """One stream per consumer, so that adding one never shifts another's numbers."""
        return np.random.default_rng([self.seed, salt])
