"""Solver ``design_front``: levers l1, l3, l5, l6, l10 chosen for H (Eqs. 5, 8; Sec. 3.3 step
3, smaller is better) and the worst transmission angle min(mu, 180 deg - mu) of Eq. (9)'s
dyads over the stroke (larger is better), among buildable lever sets (:mod:`.constraints`).

With frozen carrier constants Eq. (7) fixes the blade pose from the guide rod alone, so the
strokes are solved once per l6 of a grid; at each, lever sets of the other four are sampled
in the box and refined about the best buildable one with a halving spread (a (1, lambda)
evolution strategy).  The front is the non-dominated set of the buildable designs."""
from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from mechrepro.errors import Refusal
from mechrepro.units import var

from . import closure, optimise
from .constraints import dyad_transmission, open_pose
from .constraints import settings as constraint_settings
from .run_context import Context
from .design import Unreachable
from .geometry import OPTIMISED_LEVERS, cut_points
from .loops import RANGES, NonAssembly, dyads
from .motion_laws import synthetic_horizontal_displacement

#: the four levers sampled at each l6 (OPTIMISED_LEVERS without l6)
OTHERS = ("l1", "l3", "l5", "l10")


def dyad_metrics(g, poses: np.ndarray, levers: np.ndarray, open_q=None) -> dict:
    """Eq. (9)'s two dyads for many lever sets ``levers`` (m, 4: l1, l3, l5, l10) at one stroke
    ``poses`` (n, 2), vectorised: (m,) arrays ``assembles``, ``mu_worst``, ``mu_min``, ``mu_max``
    (deg), ``joint_height`` (mm) and ``open_mu`` (deg, at the open pose ``open_q``)."""
    loops = dyads(g, poses[None, :, 0], poses[None, :, 1], [levers[:, k, None] for k in range(4)])
    ok = np.ones(levers.shape[0], bool)
    mu_lo, mu_hi = np.full(levers.shape[0], np.inf), np.full(levers.shape[0], -np.inf)
    for (P, Q, rp, rq, e), (ri, rj) in zip(loops, ((0, 2), (1, 3))):
        P, Q = np.broadcast_arrays(P, Q)
        with np.errstate(invalid="ignore"):
            x, y, _ = closure.python.dyad_joint(P.real, P.imag, Q.real, Q.imag, rp, rq, e)
        B = x + 1j * y
        crank = np.mod(np.angle(B - P), 2 * math.pi)
        rod = np.mod(np.angle(B - Q), 2 * math.pi)
        with np.errstate(invalid="ignore"):
            ok &= np.all((crank >= RANGES[ri][0]) & (crank <= RANGES[ri][1])
                         & (rod >= RANGES[rj][0]) & (rod <= RANGES[rj][1]), axis=1)
            mu = np.degrees(np.abs(np.angle((P - B) / (Q - B))))
            mu_lo = np.minimum(mu_lo, mu.min(axis=1))
            mu_hi = np.maximum(mu_hi, mu.max(axis=1))
    worst = np.minimum(mu_lo, 180.0 - mu_hi)
    height = np.minimum(loops[0][1].imag.min(), loops[1][1].imag.min(axis=1))
    out = {"assembles": ok & np.isfinite(worst), "mu_worst": np.where(ok, worst, np.nan),
           "mu_min": mu_lo, "mu_max": mu_hi, "joint_height": height}
    out["open_mu"] = (np.full(levers.shape[0], np.nan) if open_q is None
                      else dyad_transmission(g, open_q[0], open_q[1], levers))
    return out


def stroke_of(g, n: int, tol: float, opening: float | None):
    """(poses, H, rod gap, open pose) of the member with guide rod ``g.l6``, or None off the
    guide rod's design branch (open pose None: not reached, or ``opening`` None)."""
    x_k = cut_points(g, n)[1]
    try:
        poses = optimise.stroke_poses(g, x_k, tol)
    except (NonAssembly, Unreachable):
        return None
    H = synthetic_horizontal_displacement(g, poses[:, 0] - g.beta2, x_k)
    lo, hi = g.x_mid - 0.5 * g.width, g.x_mid + 0.5 * g.width
    xs = np.concatenate([[0.0], g.l6 * np.cos(poses[:, 1])])   # E, then D over the stroke
    return (poses, float(H), float(max(lo - xs.max(), xs.min() - hi)),
            None if opening is None else open_pose(g, opening))


def buildable(m: dict, rod_gap, *, clearance: float, plate_top: float, mu_min: float,
              rise: float, opening: float, guide_rod_plane: str) -> np.ndarray:
    """Constraints 1-4 of :mod:`.constraints` on :func:`dyad_metrics` ``m`` (mu_min in deg)."""
    rod_ok = rod_gap >= clearance if guide_rod_plane == "planar" else True
    with np.errstate(invalid="ignore"):
        return (m["assembles"] & rod_ok & (m["joint_height"] >= plate_top)
                & (m["mu_worst"] >= mu_min) & (rise <= opening) & (m["open_mu"] >= mu_min))


def pareto_mask(H: np.ndarray, mu: np.ndarray) -> np.ndarray:
    """Non-dominated designs minimising H and maximising mu (NaN never on the front)."""
    ok = np.isfinite(H) & np.isfinite(mu)
    idx = np.flatnonzero(ok)
    order = idx[np.lexsort((-mu[idx], H[idx]))]
    out = np.zeros(H.shape, bool)
    best = -np.inf
    for i in order:
        if mu[i] > best:
            out[i], best = True, mu[i]
    return out


def search(g, n: int, tol: float, box: np.ndarray, constraints: dict, *, l6_points: int,
           samples: int, rounds: int, rng: np.random.Generator) -> dict:
    """The search of the module docstring.  Returns, per l6 of the grid whose stroke exists, H, the
    rod gap and the buildable design of the largest worst transmission angle (NaN levers where
    none is), the design keeping the other levers (``kept_*``), and every design evaluated
    (``sample_*``) for the figure."""
    if g.carrier != "frozen":
        raise Refusal("design_front shares one stroke per l6 among the other levers, which "
                      "holds with frozen carrier constants only (carrier_constants = frozen)")
    j6 = OPTIMISED_LEVERS.index("l6")
    jo = [OPTIMISED_LEVERS.index(k) for k in OTHERS]
    lo, hi = box[jo, 0], box[jo, 1]
    x0 = np.array([getattr(g, k) for k in OTHERS])
    rise = g.width ** 2 / (2.0 * g.R)
    env, cloud = [], []

    def at(l6):
        """The envelope entry at guide rod l6 (None: no stroke); its samples go into ``cloud``."""
        g6 = g.with_levers(l6=float(l6))
        s = stroke_of(g6, n, tol, constraints["opening"])
        if s is None:
            return None
        poses, H, gap, q_open = s
        m0 = dyad_metrics(g6, poses, x0[None, :], q_open)
        kept = (float(m0["mu_worst"][0]), float(m0["joint_height"][0]),
                bool(buildable(m0, gap, rise=rise, **constraints)[0]))
        best, best_mu, height, spread = None, math.nan, math.nan, 0.25 * (hi - lo)
        for _ in range(rounds + 1):
            if best is None:
                X = lo + (hi - lo) * rng.random((samples, 4))
            else:
                X = np.clip(best + spread * rng.standard_normal((samples, 4)), lo, hi)
                spread = 0.5 * spread
            m = dyad_metrics(g6, poses, X, q_open)
            ok = buildable(m, gap, rise=rise, **constraints)
            cloud.append((np.full(samples, H), m["mu_worst"], ok))
            if ok.any():
                i = int(np.argmax(np.where(ok, m["mu_worst"], -np.inf)))
                if best is None or m["mu_worst"][i] > best_mu:
                    best, best_mu, height = X[i], float(m["mu_worst"][i]), float(m["joint_height"][i])
        levers = np.full(5, math.nan)
        levers[j6] = l6
        if best is not None:
            levers[jo] = best
        return (levers, H, gap, best_mu, height, *kept)

    for l6 in np.linspace(box[j6, 0], box[j6, 1], l6_points):
        e = at(l6)
        if e is not None:
            env.append(e)
    # the guide rod's joint D reaches the clearance between two grid lengths: that length, where
    # H is lowest among the buildable ones (H falls with l6), is solved for and searched too
    if constraints["guide_rod_plane"] == "planar":
        gaps = np.array([e[2] for e in env])
        cross = np.flatnonzero((gaps[:-1] >= constraints["clearance"]) & (gaps[1:] < constraints["clearance"]))
        for k in cross:
            a_, b_ = env[k][0][j6], env[k + 1][0][j6]

            def gap_minus(l6):
                s = stroke_of(g.with_levers(l6=float(l6)), n, tol, None)
                return (s[2] if s is not None else -np.inf) - constraints["clearance"]
            l6_star = brentq(gap_minus, a_, b_, xtol=1e-6)
            # just inside the constraint, so that round-off cannot put the design outside it
            e = at(l6_star - 1e-5)
            if e is not None:
                env.insert(k + 1, e)
    out = {k: np.array([e[i] for e in env]) for i, k in enumerate(
        ("levers", "H", "rod_gap", "mu_worst", "joint_height", "kept_mu_worst", "kept_joint_height",
         "kept_buildable"))}
    return out | {k: np.concatenate([c[i] for c in cloud])
                  for i, k in enumerate(("sample_H", "sample_mu_worst", "sample_buildable"))}


def evaluate(g, levers: dict, n: int, tol: float, constraints: dict) -> dict:
    """H, worst transmission angle, buildability and margins of one lever set (a paper design)."""
    gl = g.with_levers(**levers)
    s = stroke_of(gl, n, tol, constraints["opening"])
    if s is None:
        return {"H": math.nan, "mu_worst": math.nan, "buildable": False, "rod_gap": math.nan,
                "joint_height": math.nan}
    poses, H, gap, q_open = s
    X = np.array([[levers.get(k, getattr(g, k)) for k in OTHERS]], float)
    m = dyad_metrics(gl, poses, X, q_open)
    ok = buildable(m, gap, rise=g.width ** 2 / (2.0 * g.R), **constraints)
    return {"H": H, "mu_worst": float(m["mu_worst"][0]), "buildable": bool(ok[0]), "rod_gap": gap,
            "joint_height": float(m["joint_height"][0])}


def lever_box(ctx: Context) -> np.ndarray:
    """(5, 2) sampling box of OPTIMISED_LEVERS (mm): options.box_fraction times the original levers."""
    lo, hi = (float(v) for v in ctx.options["box_fraction"])
    return np.array([[lo * v, hi * v] for v in ctx.g_original.levers()])


def solve_design_front(run: dict, ctx: Context) -> dict:
    cs = constraint_settings(ctx.p)
    cons = dict(cs, mu_min=math.degrees(cs["mu_min"]))
    box = lever_box(ctx)
    res = search(ctx.g_original, ctx.n, ctx.tol_floor, box, cons,
                 l6_points=int(ctx.res["front_l6_points"]), samples=int(ctx.res["front_samples"]),
                 rounds=int(ctx.res["front_rounds"]), rng=ctx.rng(11))
    on_front = pareto_mask(res["H"], res["mu_worst"]).astype(float)
    L = res["levers"]
    box_margin = np.minimum(L - box[:, 0], box[:, 1] - L) / (box[:, 1] - box[:, 0])
    papers = {"original": {k: getattr(ctx.g_original, k) for k in OPTIMISED_LEVERS},
              "table2": {k: float(v) for k, v in ctx.options["table2_levers"].items()}}
    pe = {name: evaluate(ctx.g_original, lv, ctx.n, ctx.tol_floor, cons) for name, lv in papers.items()}
    # a thinned sample of every design evaluated, for the figure (its own stream)
    n_all = len(res["sample_H"])
    keep = np.sort(ctx.rng(12).choice(n_all, size=min(n_all, 4000), replace=False))

    def paper(key):
        return np.array([float(pe[k][key]) for k in papers])

    return {
        "envelope_levers": var(("l6_grid", "lever"), L, "mm",
                               "per l6: the buildable l1, l3, l5, l6, l10 of the largest worst "
                               "transmission angle found (NaN: none buildable)"),
        "envelope_H": var("l6_grid", res["H"], "mm", "synthetic horizontal displacement (depends on l6 only)"),
        "envelope_rod_gap": var("l6_grid", res["rod_gap"], "mm",
                                "guide rod ED beside the plate (constraint 1; depends on l6 only)"),
        "envelope_mu_worst": var("l6_grid", res["mu_worst"], "deg",
                                 "largest worst transmission angle over the stroke, min(mu, 180 - mu) "
                                 "of both dyads, among the buildable designs at this l6"),
        "envelope_joint_height": var("l6_grid", res["joint_height"], "mm",
                                     "lowest y of the rod joints C, I of that design (constraint 2)"),
        "envelope_box_margin": var(("l6_grid", "lever"), box_margin, "1",
                                   "distance of each lever to the sampling box, relative to the box width"),
        "envelope_on_front": var("l6_grid", on_front, "1",
                                 "1: on the Pareto front (H smallest, worst transmission angle largest)"),
        "kept_mu_worst": var("l6_grid", res["kept_mu_worst"], "deg",
                             "worst transmission angle with only l6 changed (the other levers the original's)"),
        "kept_joint_height": var("l6_grid", res["kept_joint_height"], "mm",
                                 "lowest rod joint with only l6 changed"),
        "kept_buildable": var("l6_grid", res["kept_buildable"].astype(float), "1",
                              "1: buildable with only l6 changed"),
        "front_box": var(("lever", "bound"), box, "mm", "sampling box of the levers"),
        "sample_H": var("sample", res["sample_H"][keep], "mm", "H of a thinned sample of the designs evaluated"),
        "sample_mu_worst": var("sample", res["sample_mu_worst"][keep], "deg",
                               "worst transmission angle of the same sample (NaN: a loop does not close)"),
        "sample_buildable": var("sample", res["sample_buildable"][keep].astype(float), "1", "1: buildable"),
        "front_evaluated": var((), float(n_all), "1", "designs evaluated"),
        "front_buildable_count": var((), float(res["sample_buildable"].sum()), "1",
                                     "buildable designs evaluated"),
        "paper_H": var("paper_design", paper("H"), "mm", "H of the paper's original and Table II designs"),
        "paper_mu_worst": var("paper_design", paper("mu_worst"), "deg",
                              "worst transmission angle of the paper's designs"),
        "paper_buildable": var("paper_design", paper("buildable"), "1",
                               "1: the paper's design is buildable in the run's member"),
        "paper_rod_gap": var("paper_design", paper("rod_gap"), "mm", "guide rod beside the plate"),
        "paper_joint_height": var("paper_design", paper("joint_height"), "mm", "lowest rod joint"),
        "paper_levers": var(("paper_design", "lever"),
                            np.array([[papers[k][n] for n in OPTIMISED_LEVERS] for k in papers]), "mm",
                            "the paper's levers (Table II)"),
        "paper_design": var("paper_design", list(papers), "1", "the paper's designs"),
    }
