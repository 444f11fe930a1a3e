"""rolling_shear's cost form (read by :mod:`mechrepro.limits` before any job): each solver's
work counted from the run record, in cut points of the stroke times what each point solves
(a position closure, a swarm of particles x iterations per seed, a root finder, an
optimiser's evaluations, a family member, a design-front sample).  The seconds per unit are
measured data (config/costs.csv).  Memory: the interpreter with numpy, scipy and numba plus
the stroke's arrays per cut point (typed: no run records its memory)."""
from __future__ import annotations

import math

#: methods of method_comparison that run a swarm at every cut point (the rest are root
#: finders: cold random starts or warm-started)
_SWARMS = {"selpso", "pso_standard"}


def mem_mb(run: dict) -> float:
    return 330 + 8.5e-4 * int(run["resolution"]["n_points"])


def work(run: dict) -> dict:
    """The work terms of one run (module docstring)."""
    res, opt, p = run["resolution"], run.get("options", {}), run["parameters"]
    n, solver = int(res["n_points"]), run["solver"]
    out = {"run": 1.0, "points": float(n),
           "calibration_points": float(res.get("calibration_points", 0))}
    if solver == "method_comparison":
        methods = opt.get("methods", [])
        swarm = int(res.get("pso_swarm", p.get("pso_swarm", 60)))
        iters = int(res.get("pso_iter", p.get("pso_max_iter", 1000)))
        seeded = n * int(opt.get("seeds", 1))
        swarms = sum(m in _SWARMS for m in methods)
        out |= {"swarm_points": seeded * swarms, "particle_iterations": seeded * swarms * swarm * iters,
                "root_points": seeded * (len(methods) - swarms)}
    elif solver == "lever_optimisation":
        out["evaluation_points"] = n * (len(opt.get("optimisers", ["selpso"])) * int(res.get("opt_swarm", 20))
                                        * int(res.get("opt_iter", 30)) + 5 * int(res.get("scan_points", 11)))
    elif solver == "family_scan":
        members = math.prod(len(v) if isinstance(v, list) else 1 for v in opt.get("grid", {}).values())
        out |= {"members": members, "member_points": members * n}
    elif solver == "design_front":
        # a stroke per l6, then every round's samples at once
        points = int(res.get("front_l6_points", 41))
        out |= {"l6_points": points * n, "sample_points": n * points * int(res.get("front_samples", 400))
                * (int(res.get("front_rounds", 6)) + 1)}
    return out
