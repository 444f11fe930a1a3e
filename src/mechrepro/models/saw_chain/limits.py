"""saw_chain's load-time limits and cost form (read by :mod:`mechrepro.limits` before any job):
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


def work(run: dict) -> dict:
    """The cost form: 2K + 1 samples of the difference method and its references, plus the
    outputs that solve design grids and fits of their own, once per run."""
    return {"run": 1.0, "K": float(run["resolution"]["K"]), **{e: 1.0 for e in run["outputs"]
                                                              if e in ("identification", "design_maps", "richardson_levels")}}


def mem_mb(run: dict) -> float:
    """Peak memory [MB]: the interpreter with its imports plus ~16 arrays of 2K + 1 samples."""
    return 200 + 3.0e-4 * int(run["resolution"]["K"])


#: the difference method alone is read by no reported quantity: each compares it with
#: the exact reference or the textbook method (outputs), or reads their contributions
NEEDS_EFFECTS = {"difference_method": "every reported quantity reads it beside the exact "
                                      "reference or the textbook method"}
