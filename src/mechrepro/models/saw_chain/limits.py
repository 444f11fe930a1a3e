"""saw_chain's load-time limits and cost (read by :mod:`mechrepro.limits` before any job):
the solver's own refusals evaluated on the run record."""
from __future__ import annotations

from .chain import chain_from_run
from .difference import RoundoffError, check_roundoff


def check(run: dict) -> list[str]:
    """The solver's refusals of one run record: K beyond the loads' (or, ``options.loads: false``,
    the velocity's) round-off limit, unless ``options.beyond_roundoff_limit``."""
    try:
        chain = chain_from_run(run)   # check_meshing: positive pitches, integer z >= 3
    except ValueError as exc:
        return [f"parameters: {exc}; allowed: positive finite pitches and teeth >= 3"]
    opts = run.get("options", {})
    loads = opts.get("loads", True)
    limit = chain.roundoff_limit() if loads else chain.velocity_roundoff_limit()
    try:
        check_roundoff(chain.K, limit, opts.get("beyond_roundoff_limit", False),
                       "loads" if loads else "velocities (options.loads: false)")
    except RoundoffError as exc:
        return [f"resolution.{exc} (the solver refuses it), or "
                f"options.beyond_roundoff_limit: true on purpose"]
    return []


#: what a solve process spends before its first run: the model's imports (scipy, xarray),
#: which the first run's compute pays
JOB_START_S = 0.7


def cost(run: dict) -> dict:
    """Peak memory and time of one run, linear in K (2K+1 samples of ~16 arrays plus the write);
    the fit lies above measurements in fresh processes."""
    K = int(run["resolution"]["K"])
    return {"mem_mb": 200 + 3.0e-4 * K, "seconds": 0.3 + 1.5e-6 * K}


#: the difference method alone is read by no reported quantity: each compares it with
#: the exact reference or the textbook method (effects), or reads their contributions
NEEDS_EFFECTS = {"difference_method": "every reported quantity reads it beside the exact "
                                      "reference or the textbook method"}
