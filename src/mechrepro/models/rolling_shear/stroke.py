"""The cutting stroke: every cut point solved for theta5, theta6 (Eq. 7) then theta1..4 (Eq. 9).

Methods: ``newton`` (warm-started continuation; a point that does not converge or lands off
the design branch raises :class:`NonAssembly`), ``selpso`` and ``pso_standard`` (from the
initial value), ``cold_root``/``least_squares`` (scipy from random starts), ``warm_root``/
``warm_least_squares`` (scipy warm-started, no branch check); :func:`exact_theta` (closed form)
is the reference.  :func:`solve_compare` records the comparison methods and never raises."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares, root

from mechrepro.timing import mean_time, phase

from . import closure, kernels
from . import loops as loops_mod
from . import blade
from .geometry import Geometry
from .loops import NonAssembly, in_ranges, on_design_branch, wrap
from .selpso import KernelFitness, SelPSOSettings, selpso


@dataclass
class StrokeSolution:
    method: str
    x_k: np.ndarray
    theta: np.ndarray                      # (n, 6) theta1..theta6, wrapped to [0, 2 pi)
    fitness_pose: np.ndarray               # G of Eq. (7), mm
    fitness_loops: np.ndarray              # G of Eq. (9), mm
    converged: np.ndarray                  # both systems reached their tolerance
    in_ranges: np.ndarray
    design_branch: np.ndarray
    time_pose: float                       # mean wall time per solve of Eq. (7), s
    time_loops: float                      # mean wall time per solve of Eq. (9), s
    iterations_loops: np.ndarray

    @property
    def right(self) -> np.ndarray:
        return self.converged & self.design_branch


@dataclass(frozen=True)
class SolverSettings:
    tol_loops: float = 1e-11
    tol_pose: float = 1e-9
    max_iter: int = 30
    initial_value: tuple = (4.3, 4.3, 2.5, 2.5, 2.6, 3.3)
    pso_loops: SelPSOSettings = SelPSOSettings()
    pso_pose: SelPSOSettings = SelPSOSettings(tol=1e-9)
    #: selPSO with the standard constriction constants (like-for-like baseline)
    pso_std_loops: SelPSOSettings = SelPSOSettings()
    pso_std_pose: SelPSOSettings = SelPSOSettings(tol=1e-9)


def _point_error(g, i, xk, theta, res_pose, res_loops) -> str | None:
    """Why a Newton result at cut point i is refused, or None if it is accepted."""
    if not res_pose.converged:
        return (f"cut point {i} (x_k = {xk:.6g} mm): blade pose (Eq. 7) did not converge: "
                f"{res_pose.reason}")
    if not res_loops.converged:
        return _explain(g, i, xk, theta, res_loops.reason)
    if not on_design_branch(g, theta):
        return _explain(g, i, xk, theta, "Newton converged to another assembly mode "
                        "(the modes meet at a toggle)")
    return None


def _explain(g, i, xk, theta, why) -> str:
    m = loops_mod.dyad_margins(g, theta[4], theta[5])
    worst = "ABCD (l1, l3)" if m[0] < m[1] else "GHID (l2, l4)"
    state = ("the linkage does not assemble" if m.min() <= 0 else
             f"refused, {m.min():.4g} mm from a toggle of loop {worst}")
    return (f"cut point {i} (x_k = {xk:.6g} mm): {state}: {why}; dyad margins to "
            f"toggle/fold: ABCD {m[0]:.4g} mm, GHID {m[1]:.4g} mm (worst: loop {worst})")


def solve_newton(g: Geometry, x_k, settings: SolverSettings) -> StrokeSolution:
    """Warm-started Newton continuation along the stroke (the pipeline's default), point by
    point; its time is the caller's to measure (:func:`.continuation.newton_stroke`)."""
    n = len(x_k)
    theta = np.empty((n, 6))
    fp, fl, it = np.empty(n), np.empty(n), np.empty(n, int)
    guess = list(settings.initial_value)
    for i, xk in enumerate(x_k):
        xk = float(xk)
        # first-order predictor, then (near a toggle it can overshoot onto the other
        # assembly mode) the previous solution; a point neither accepts raises
        guesses = [guess] if i == 0 else [guess, list(theta[i - 1])]
        for trial in guesses:
            rp = kernels.newton_pose(g, (trial[4], trial[5]), xk, settings.tol_pose, settings.max_iter)
            t5, t6 = rp.x
            rl = kernels.newton_loops(g, trial[:4], t5, t6, settings.tol_loops, settings.max_iter)
            th = np.array([*rl.x, t5, t6])
            error = _point_error(g, i, xk, th, rp, rl)
            if error is None:
                break
        if error is not None:
            raise NonAssembly(error, i, xk)
        theta[i] = th
        fp[i], fl[i], it[i] = rp.fitness, rl.fitness, rl.iterations
        guess = list(2 * th - theta[i - 1]) if i > 0 else list(th)
    ok = np.ones(n, bool)
    return StrokeSolution("newton", np.asarray(x_k), wrap(theta), fp, fl, ok, ok.copy(), ok.copy(),
                          math.nan, math.nan, it)


def exact_theta(g: Geometry, x_k) -> np.ndarray:
    """theta1..theta6 (n x 6, mod 2 pi) of the closed form at every cut point (the reference)."""
    theta = np.empty((len(x_k), 6))
    for i, xk in enumerate(x_k):
        try:
            p = blade.exact_pose(g, float(xk))
            theta[i] = [*loops_mod.exact_angles(g, *p), *p]
        except NonAssembly as exc:
            raise NonAssembly(f"cut point {i} (x_k = {float(xk):.6g} mm): {exc}", i, float(xk)) from None
    return wrap(theta)


def _scipy_solve(kind, fun, jac, x0):
    """scipy's root (hybrid Powell) or least_squares (trf) from x0: (x, evaluations)."""
    r = (root(fun, x0, jac=jac, method="hybr", options={"xtol": 1e-14}) if kind.endswith("root")
         else least_squares(fun, x0, jac=jac, method="trf", xtol=1e-15, ftol=1e-15, gtol=1e-15))
    return r.x, int(r.nfev)


def pose_fitness(g: Geometry, xk: float) -> KernelFitness:
    """selPSO's fitness of Eq. (7): G = sum |residuals| (mm), numpy or compiled."""
    return KernelFitness(lambda X: np.abs(blade.pose_residuals(g, X, xk)).sum(-1),
                         closure.POSE, g.constants, (xk, 0.0, 0.0, 0.0, 0.0, 0.0))


def loops_fitness(g: Geometry, t5: float, t6: float) -> KernelFitness:
    """selPSO's fitness of Eq. (9): G = sum |residuals| (mm), numpy or compiled."""
    return KernelFitness(lambda X: np.abs(loops_mod.residuals(g, X, t5, t6)).sum(-1),
                         closure.LOOPS, g.constants, closure.python.loop_knowns(g, t5, t6))


def _solve_by(method, system, fitness, fun, jac, start, settings, rng):
    """Eq. (7) (``system`` "pose": theta5, theta6) or Eq. (9) ("loops": theta1..theta4) at one
    cut point by a comparison method: (x, iterations or evaluations)."""
    if method in ("selpso", "pso_standard"):
        st = getattr(settings, f"pso_{'' if method == 'selpso' else 'std_'}{system}")
        r = selpso(fitness(), start, st, rng, period=2 * math.pi)
        return r.x, r.iterations
    start = start if method.startswith("warm_") else rng.uniform(0, 2 * math.pi, len(start))
    return _scipy_solve(method, fun, jac, start)


def solve_compare(g: Geometry, x_k, method: str, settings: SolverSettings,
                  rng: np.random.Generator) -> StrokeSolution:
    """selPSO / scipy solves at every cut point, recorded, never raising (starts: see module)."""
    n = len(x_k)
    theta = np.empty((n, 6))
    fp, fl, it = np.empty(n), np.empty(n), np.zeros(n, int)
    conv, inr, des = np.zeros(n, bool), np.zeros(n, bool), np.zeros(n, bool)
    tp, tl = 0.0, 0.0
    init = np.asarray(settings.initial_value, float)
    warm = method.startswith("warm_")
    guess = init.copy()
    for i, xk in enumerate(x_k):
        xk = float(xk)
        with phase("rolling_shear.pose") as sw:
            t5, t6 = map(float, _solve_by(
                method, "pose", lambda: pose_fitness(g, xk), lambda x: blade.pose_residuals(g, x, xk),
                lambda x: blade.lowest_point_jacobian(g, *x), guess[4:], settings, rng)[0])
        tp += sw.seconds
        with phase("rolling_shear.loops") as sw:
            t14, it[i] = _solve_by(
                method, "loops", lambda: loops_fitness(g, t5, t6),
                lambda x: loops_mod.residuals(g, x, t5, t6), lambda x: loops_mod.jacobian(g, x),
                guess[:4], settings, rng)
        tl += sw.seconds
        th = np.array([*t14, t5, t6])
        if warm:
            guess = 2 * th - prev if i > 0 else th
            prev = th
        theta[i] = wrap(th)
        fp[i] = float(np.abs(blade.pose_residuals(g, th[4:], xk)).sum())
        fl[i] = float(np.abs(loops_mod.residuals(g, th[:4], t5, t6)).sum())
        conv[i] = fp[i] < settings.tol_pose and fl[i] < settings.tol_loops
        inr[i] = in_ranges(th)
        des[i] = on_design_branch(g, th)
    return StrokeSolution(method, np.asarray(x_k), theta, fp, fl, conv, inr, des,
                          tp / n, tl / n, it)


def time_newton_loops(g: Geometry, theta: np.ndarray, settings: SolverSettings,
                      min_time: float = 0.02) -> float:
    """Mean wall time per Eq. (9) solve of the warm-started continuation, poses given (s): the
    mean over whole strokes repeated for ``min_time``, timed as selPSO's is (like for like)."""
    return mean_time(_newton_loops_stroke, g, theta, settings, min_time=min_time) / len(theta)


def _newton_loops_stroke(g: Geometry, theta: np.ndarray, settings: SolverSettings) -> None:
    kernels.kernel("loops_stroke")(g.constants, np.ascontiguousarray(theta, float),
                                   float(settings.tol_loops), int(settings.max_iter),
                                   kernels.SINGULAR_RTOL)
