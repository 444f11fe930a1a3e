"""Lever optimisation (Sec. 3.3 step 3): l1, l3, l5, l6, l10 against H, by selPSO and by
scipy's differential evolution.

A lever set's objective: the poses of the stroke (Eq. 7), H (Eqs. 5, 8), and both dyads of
Eq. (9) on the design branch in the paper's ranges at every cut point, else the flat
``PENALTY``.  With frozen carrier constants H depends on l6 only (with re-derived ones on
l5, l6): the other levers enter only through assembly."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import differential_evolution

from . import closure, kernels
from .blade import exact_pose
from .geometry import OPTIMISED_LEVERS, Geometry, cut_points
from .design import Unreachable
from .loops import RANGES, NonAssembly, dyads
from .selpso import SelPSOSettings, selpso
from .motion_laws import synthetic_horizontal_displacement

PENALTY = 1.0e4  # mm, far above any feasible objective
#: how clearly (rad; relative, on the squared dyad height) the compiled assembly check must
#: pass for the numpy check to be skipped: far above round-off, so both decide alike
ASSEMBLY_MARGIN = 1.0e-9


def stroke_poses(g: Geometry, x_k, tol: float, max_iter: int = 30) -> np.ndarray:
    """theta5, theta6 at every cut point: exact first point, warm Newton afterwards
    (:func:`.closure.pose_stroke`); raises NonAssembly off the guide rod's design branch."""
    out = np.empty((len(x_k), 2))
    guess = exact_pose(g, float(x_k[0]))
    x = np.ascontiguousarray(x_k, float)
    i, status, G, det = kernels.kernel("pose_stroke")(
        g.constants, x, float(guess[0]), float(guess[1]), float(tol), int(max_iter),
        kernels.SINGULAR_RTOL, float(g.guide_mode), out)
    if status == closure.OFF_BRANCH:
        raise NonAssembly(f"cut point {i} (x_k = {float(x_k[i]):.6g} mm): blade pose leaves "
                          f"the guide rod's design branch (theta5 = {out[i, 0]:.4g}, "
                          f"theta6 = {out[i, 1]:.4g} rad)", int(i), float(x_k[i]))
    if i >= 0:
        raise NonAssembly(f"cut point {i} (x_k = {float(x[i]):.6g} mm): blade pose (Eq. 7) "
                          f"did not converge: {kernels.reason(status, det, max_iter)}",
                          int(i), float(x[i]))
    return out


def dyad_angles(g: Geometry, theta5, theta6) -> np.ndarray:
    """Closed-form theta1..theta4 for arrays of poses (n, 4); NaN where a loop cannot close."""
    out = []
    for P, Q, rp, rq, e in dyads(g, theta5, theta6):
        with np.errstate(invalid="ignore"):
            x, y, _ = closure.python.dyad_joint(P.real, P.imag, Q.real, Q.imag, rp, rq, e)
        out += [np.arctan2(y - P.imag, x - P.real), np.arctan2(y - Q.imag, x - Q.real)]
    return np.mod(np.stack([out[0], out[2], out[1], out[3]], axis=1), 2 * math.pi)


def check_assembly(g: Geometry, x_k, poses) -> np.ndarray:
    """theta1..theta4 of the stroke; raises NonAssembly naming the first bad cut point."""
    th = dyad_angles(g, poses[:, 0], poses[:, 1])
    ok = np.isfinite(th).all(axis=1)
    for j in range(4):
        lo, hi = RANGES[j]
        ok &= (th[:, j] >= lo) & (th[:, j] <= hi)
    if not ok.all():
        i = int(np.argmin(ok))
        why = ("dyad cannot close (toggle/fold passed)" if not np.isfinite(th[i]).all()
               else f"angles {np.round(th[i], 4).tolist()} leave the paper's ranges")
        loop = "ABCD (l1, l3)" if not np.isfinite(th[i, [0, 2]]).all() or not (
            RANGES[0][0] <= th[i, 0] <= RANGES[0][1] and RANGES[2][0] <= th[i, 2] <= RANGES[2][1]
        ) else "GHID (l2, l4)"
        raise NonAssembly(f"cut point {i} (x_k = {float(x_k[i]):.6g} mm): loop {loop}: {why}",
                          i, float(x_k[i]))
    return th


def objective(g: Geometry, x_k, tol: float) -> float:
    """H of a lever set (mm) at the cut points of ``g`` (they move with re-derived carrier
    constants); raises NonAssembly."""
    x_k = cut_points(g, len(x_k))[1]
    poses = stroke_poses(g, x_k, tol)
    if not (closure.available() and kernels.kernel("assembles_clearly")(
            g.constants, poses, ASSEMBLY_MARGIN)):
        check_assembly(g, x_k, poses)  # decides wherever the compiled check is not clear
    return synthetic_horizontal_displacement(g, poses[:, 0] - g.beta2, x_k)


def penalised(g: Geometry, x_k, tol: float, names=OPTIMISED_LEVERS):
    def f(levers) -> float:
        try:
            return objective(g.with_levers(**dict(zip(names, map(float, levers)))), x_k, tol)
        except (NonAssembly, Unreachable):
            return PENALTY
    return f


@dataclass
class OptimisationResult:
    method: str
    levers: np.ndarray
    objective: float
    evaluations: int
    history: np.ndarray      # best objective after each iteration/generation


def optimise_selpso(g, x_k, bounds, settings: SelPSOSettings, rng, tol) -> OptimisationResult:
    f = penalised(g, x_k, tol)
    lo, hi = np.asarray(bounds, float).T
    r = selpso(lambda X: np.array([f(x) for x in X]), 0.5 * (lo + hi), settings, rng, lo, hi)
    return OptimisationResult("selpso", r.x, r.fitness, r.evaluations, r.history)


def optimise_de(g, x_k, bounds, budget: int, population: int, seed: int,
                tol) -> OptimisationResult:
    """scipy differential_evolution with the same bounds and at most the same budget (population
    ~ the swarm, no polishing, which would spend evaluations outside the budget)."""
    f = penalised(g, x_k, tol)
    n = len(bounds)
    popsize = max(1, int(round(population / n)))
    maxiter = max(1, budget // (popsize * n) - 1)
    hist, count = [], [0]

    def fc(x):
        count[0] += 1
        return f(x)

    def callback(intermediate_result):
        hist.append(float(intermediate_result.fun))

    r = differential_evolution(fc, bounds, popsize=popsize, maxiter=maxiter, tol=0.0, atol=0.0,
                               seed=seed, polish=False, init="latinhypercube",
                               updating="immediate", callback=callback)
    return OptimisationResult("differential_evolution", np.asarray(r.x), float(r.fun), count[0],
                              np.asarray(hist))
