"""rolling_shear's declared cost (read by :mod:`mechrepro.limits` before any job).

Memory: the interpreter with numpy, scipy and numba plus the stroke's arrays per cut point;
time: linear in the cut points times what each point costs.  The coefficients are fits that
lie above measurements in fresh processes on 2 shared cores."""
from __future__ import annotations

import math

#: what a fresh solve process spends before its first run (numba kernels, calibration)
JOB_START_S = 6.0

#: methods of method_comparison that run a swarm at every cut point (the rest are root
#: finders: cold random starts or warm-started, ~5 ms per point each)
_SWARMS = {"selpso", "pso_standard"}


def cost(run: dict) -> dict:
    """Expected peak memory (MB) and solve time (s) of one run in a warm solve process (a job
    adds :data:`JOB_START_S` once)."""
    res, opt, p = run["resolution"], run.get("options", {}), run["parameters"]
    n = int(res["n_points"])
    mem = 330 + 8.5e-4 * n
    solver = run["solver"]
    if solver == "continuation":
        seconds = 0.2 + 1.2e-3 * n
    elif solver == "method_comparison":
        methods = opt.get("methods", [])
        swarm = int(res.get("pso_swarm", p.get("pso_swarm", 60)))
        iters = int(res.get("pso_iter", p.get("pso_max_iter", 1000)))
        # a swarm: 0.4 ms per point and seed, 0.25 us per particle and iteration
        per_point = (sum(m in _SWARMS for m in methods) * (4e-4 + swarm * iters * 2.5e-7)
                     + sum(m not in _SWARMS for m in methods) * 5e-3)
        seconds = 0.2 + 1.2e-3 * n + n * int(opt.get("seeds", 1)) * per_point
    elif solver == "lever_optimisation":
        evals = (len(opt.get("optimisers", ["selpso"])) * int(res.get("opt_swarm", 20))
                 * int(res.get("opt_iter", 30)) + 5 * int(res.get("scan_points", 11)))
        seconds = 0.2 + 1e-5 * evals * n
    elif solver == "family_scan":
        members = math.prod(len(v) if isinstance(v, list) else 1 for v in opt.get("grid", {}).values())
        seconds = 0.2 + members * (0.01 + 1.5e-4 * n)
    elif solver == "design_front":
        # a stroke per l6, then every round's samples at once: ~2 us per sample and cut point
        points = int(res.get("front_l6_points", 41))
        samples = points * int(res.get("front_samples", 400)) * (int(res.get("front_rounds", 6)) + 1)
        seconds = 0.2 + points * 2e-3 * n + 2e-6 * samples * n
    else:   # a solver added later: no fit yet, the continuation's
        seconds = 0.2 + 1.2e-3 * n
    return {"mem_mb": mem, "seconds": seconds}
