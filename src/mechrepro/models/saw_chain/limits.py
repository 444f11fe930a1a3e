"""saw_chain's load-time limits and cost (read by :mod:`mechrepro.limits` before any job).

The refusals are the solver's own (:func:`.geometry.check_meshing`,
:func:`.difference.check_roundoff`), evaluated on the run record: a K beyond the
round-off limit is refused when the config is loaded, not inside the solve job.
"""
from __future__ import annotations

from .chain import chain_from_run


def check(run: dict) -> list[str]:
    """The solver's refusals of one run record, as :func:`.solver.difference_method` raises
    them: K beyond the loads' round-off limit, or, for a velocity-only run
    (``options.loads: false``, the first difference alone), beyond the velocity's own limit
    (~100x the loads'), unless ``options.beyond_roundoff_limit``."""
    try:
        chain = chain_from_run(run)   # check_meshing: positive pitches, integer z >= 3
    except ValueError as exc:
        return [f"parameters: {exc}; allowed: positive finite pitches and teeth >= 3"]
    opts = run.get("options", {})
    loads = opts.get("loads", True)
    K = chain.K
    limit = chain.roundoff_limit() if loads else chain.velocity_roundoff_limit()
    if K > limit and not opts.get("beyond_roundoff_limit", False):
        what = ("second backward difference exceeds its truncation error, so the loads"
                if loads else "first backward difference exceeds its truncation error, so "
                "the velocities (options.loads: false)")
        return [f"resolution.K = {K}: beyond K = {limit} (this run's round-off limit) the "
                f"round-off of the {what} get less accurate, not more (the solver refuses "
                f"it); allowed: K <= {limit}, or options.beyond_roundoff_limit: true on purpose"]
    return []


#: what a solve process spends before its first run: the model's imports (scipy, xarray),
#: which the first run's compute pays (fig07_fig08: 0.62 s of CPU, 2.5-3.8 s of wall time
#: at load 8-14 on 2 cores, where the same run takes 0.002 s once imported)
JOB_START_S = 0.7


def cost(run: dict) -> dict:
    """Peak memory and time of one run, linear in K (2K+1 samples of ~16 float64 arrays
    plus the netCDF write).  Measured (2 cores, native): scene ``accuracy`` K = 1e3, 1e5,
    1e6, 3e6 -> peak RSS 107, 117, 350, 869 MB and 0.23, 0.26, 0.99, 3.1 s; ``fig07_fig08``
    K = 3e6 -> 875 MB, 4.0 s; ``cost_of_accuracy-010`` K = 3e5 in a fresh process (the
    test) -> 212 MB.  The fit lies 25-40 % above every measurement.  Every run of the ci
    and default profiles in one warm process (load 8-14 on 2 cores, wall ~5x CPU): CPU
    0.2-35 % of the estimate (first run aside: JOB_START_S; the 0.3 s floor is writing; most
    runs take 1-2 ms), wall 0.2-215 %, the top end K = 1e7 (3.9 s against 1.8 s)."""
    K = int(run["resolution"]["K"])
    return {"mem_mb": 200 + 3.0e-4 * K, "seconds": 0.3 + 1.5e-6 * K}


#: the difference method alone is read by no reported quantity: each compares it with
#: the exact reference or the textbook method (effects), or reads their contributions
NEEDS_EFFECTS = {"difference_method": "every reported quantity reads it beside the exact "
                                      "reference or the textbook method"}
