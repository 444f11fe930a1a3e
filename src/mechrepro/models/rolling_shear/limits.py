"""rolling_shear's declared cost (read by :mod:`mechrepro.limits` before any job).

Measured in fresh processes (peak memory: the child's own VmHWM; 2 shared cores, native,
a fault-test run beside them, so the times are upper readings), scene -> resolution ->
peak MB, solve s:

- continuation ``original``: n_points 17, 513, 4097, 32769, 131073 -> 293, 277, 280, 301,
  381 MB and 5.9, 4.4, 5.4, 20.9, 157 s;
- method_comparison ``accuracy_selpso`` (selpso + pso_standard, 20 seeds, 10 x 25):
  n_points 3, 4097, 32769 -> 299, 282, 297 MB and 2.2, 65, 513 s; at 60 x 1000,
  n_points 3 -> 279 MB, 1.6 s; ``solver_comparison`` (six methods) n_points 33, 257 ->
  281, 281 MB and 6.1, 7.2 s;
- family_scan ``family`` (432 members) n_points 17, 65 -> 269, 269 MB and 4.1, 6.3 s;
- lever_optimisation ``optimisation`` (selpso + de) n_points 9, 33, 129 at 10 x 15 or
  20 x 30, and 33 at 40 x 60 -> 272 MB each and 1.8, 2.2, 2.2, 3.0 s.

Memory is the interpreter with numpy, scipy and numba (~280 MB) plus ~0.8 kB per cut
point (the stroke's arrays), whatever the methods, seeds or swarm (the methods solve one
after the other and keep per point only scalars).  Time is linear in the cut points times
what each point costs.  A fresh process first spends ~4-6 s loading the numba kernels and
calibrating; a solve job pays that once for all its runs (the ci batch: 158 runs, 9.3 s of
solving), so it is :data:`JOB_START_S`, not part of a run's estimate.  Each fit plus
:data:`JOB_START_S` lies above every measurement above (memory 10-20 %, time up to a
factor 2, more for swarms that stop early: their bound is the full iteration count).

Within the run schema (n_points <= 4097) a run stays near 335 MB: what the model refuses
there is time (a selPSO budget of 200 x 1000 at 4097 points and 20 seeds: 172 min for the
ci batch, against the solve rule's 30 min); it would refuse a stroke of 3e6 points
(2880 MB) should the schema ever allow one.
"""
from __future__ import annotations

import math

#: what a fresh solve process spends before its first run (numba kernels, calibration)
JOB_START_S = 6.0

#: methods of method_comparison that run a swarm at every cut point (the rest are root
#: finders: cold random starts or warm-started, ~5 ms per point each)
_SWARMS = {"selpso", "pso_standard"}


def _members(grid: dict) -> int:
    return math.prod(len(v) if isinstance(v, list) else 1 for v in grid.values()) if grid else 1


def cost(run: dict) -> dict:
    """Expected peak memory (MB) and solve time (s) of one run in a warm solve process
    (module docstring; a job adds :data:`JOB_START_S` once)."""
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
        seconds = 0.2 + _members(opt.get("grid", {})) * (0.01 + 1.5e-4 * n)
    elif solver == "design_front":
        # a stroke per l6, then every round's samples at once: ~2 us per sample and cut point
        points = int(res.get("front_l6_points", 41))
        samples = points * int(res.get("front_samples", 400)) * (int(res.get("front_rounds", 6)) + 1)
        seconds = 0.2 + points * 2e-3 * n + 2e-6 * samples * n
    else:   # a solver added later: no fit yet, the continuation's
        seconds = 0.2 + 1.2e-3 * n
    return {"mem_mb": mem, "seconds": seconds}
