"""The one timer: what a run costs, split into the solver core and each effect or output.

The runner (:func:`mechrepro.solve.run_solver`) makes a :class:`Timer` current while a run
is computed; :meth:`EffectRegistry.evaluate <mechrepro.effects.EffectRegistry.evaluate>`
times each effect's contribution under ``effect:<name>`` and each output under
``output:<name>``, a model names its own phases
with :func:`phase` (whose handle also gives the block's seconds, for a cost-of-accuracy
study that reports them), and everything not inside either is the solver core.  The
split is stored in the run's netCDF (:func:`timing_variables`) and summed per paper into
the report's effect-cost table (:mod:`mechrepro.costs`).

Work too short to time in one call is timed by :func:`time_call` (fastest of repeated
calls) or :func:`mean_time` (mean of repeated calls); nothing else reads the clock.
"""
from __future__ import annotations

import time
from collections import defaultdict
from contextlib import contextmanager
from contextvars import ContextVar

EFFECT, OUTPUT = "effect:", "output:"


class Timer:
    """Seconds spent per named phase (nested phases are counted in each enclosing one) and
    how often each was entered: its evaluations, a cost no machine changes."""

    def __init__(self):
        self.phases: dict[str, float] = defaultdict(float)
        self.calls: dict[str, int] = defaultdict(int)

    @contextmanager
    def phase(self, name: str):
        with _measured() as block:
            yield block
        self.phases[name] += block.seconds
        self.calls[name] += 1

    def effects(self) -> dict[str, float]:
        """Seconds per effect and output the run named (by name)."""
        return {_named(k): v for k, v in self.phases.items() if _named(k) != k}


def _named(phase: str) -> str:
    """An effect's or output's name from its phase; any other phase unchanged."""
    return phase.removeprefix(EFFECT).removeprefix(OUTPUT)


_current: ContextVar[Timer | None] = ContextVar("mechrepro_timer", default=None)


class _Block:
    seconds: float = float("nan")


@contextmanager
def _measured():
    block = _Block()
    t0 = time.perf_counter()
    try:
        yield block
    finally:
        block.seconds = time.perf_counter() - t0


@contextmanager
def phase(name: str):
    """``with phase(name) as block: ...`` then ``block.seconds``: the block timed under
    ``name`` in the current run's timer (outside a run: only measured)."""
    timer = _current.get()
    with (timer.phase(name) if timer is not None else _measured()) as block:
        yield block


def time_call(fn, *args, min_time: float = 0.05, max_repeat: int = 50, **kwargs):
    """Call ``fn`` until ``min_time`` has elapsed; return (result, fastest call [s]).

    Fast solves are repeated and the fastest call is kept (as ``timeit`` advises): the
    other calls measure the machine's other load, not the solver.
    """
    result, best, _ = timed_run(fn, *args, min_time=min_time, max_repeat=max_repeat, **kwargs)
    return result, best


def mean_time(fn, *args, min_time: float = 0.02, windows: int = 20, **kwargs) -> float:
    """Mean wall time of ``fn`` (s) over calls repeated until ``min_time`` has elapsed,
    after one call that warms the caches: for work too short to time in one call, whose
    cost is compared as a mean (rolling_shear's time per Eq. (9) solve).  The time is
    split into ``windows`` equal windows and the fastest window's mean kept, as
    :func:`time_call` keeps the fastest call: a preemption by another process inflates
    one window, not the result (one mean over all calls moves with the machine's load)."""
    fn(*args, **kwargs)
    best = float("inf")
    for _ in range(max(1, windows)):
        n, t0 = 0, time.perf_counter()
        while n == 0 or time.perf_counter() - t0 < min_time / max(1, windows):
            fn(*args, **kwargs)
            n += 1
        best = min(best, (time.perf_counter() - t0) / n)
    return best


def timed_run(fn, *args, min_time: float = 0.05, max_repeat: int = 50, **kwargs):
    """As :func:`time_call`, each call under a fresh current :class:`Timer`; returns the
    fastest call's result, time and phases (so that times a model measures inside the call
    come from a warm call too; the calls are deterministic, their results equal).
    Times compared by difference are taken in alternation (:func:`mechrepro.solve.alternated`)."""
    best, best_timer, result, n = float("inf"), None, None, 0
    t_start = time.perf_counter()
    while n < 1 or (time.perf_counter() - t_start < min_time and n < max_repeat):
        timer = Timer()
        token = _current.set(timer)
        try:
            t0 = time.perf_counter()
            out = fn(*args, **kwargs)
            dt = time.perf_counter() - t0
        finally:
            _current.reset(token)
        if dt < best:   # the result, its phases and any time it measured inside: one call
            best, best_timer, result = dt, timer, out
        n += 1
    return result, best, best_timer


def timing_variables(seconds: float, timer: Timer | None, effects: list[str]) -> dict:
    """The run's time split as dataset variables: ``wall_time`` (the solve), ``core_time``
    (everything but the effects' contributions), ``effect_time`` and ``effect_calls`` over
    ``timed_effect``, and ``phase_time`` and ``phase_calls`` of the model's named phases over
    ``timed_phase``."""
    per = timer.effects() if timer is not None else {}
    calls = {_named(k): v for k, v in (timer.calls if timer else {}).items()}
    eff = [float(per.get(e, 0.0)) for e in effects]
    out = {
        "wall_time": ((), seconds, {"units": "s", "long_name": "wall time of one solve"}),
        "core_time": ((), max(seconds - sum(eff), 0.0),
                      {"units": "s", "long_name": "wall time of the solver core (no effect or output)"}),
    }
    if effects:
        out["effect_time"] = (("timed_effect",), eff,
                              {"units": "s", "long_name": "wall time of each effect or output"})
        out["effect_calls"] = (("timed_effect",), [int(calls.get(e, 0)) for e in effects],
                               {"units": "1", "long_name": "evaluations of each effect or output"})
    named = sorted(k for k in (timer.phases if timer else {}) if _named(k) == k)
    if named:
        out["timed_phase"] = (("timed_phase",), named, {"long_name": "phase a model names"})
        out["phase_time"] = (("timed_phase",), [timer.phases[k] for k in named],
                             {"units": "s", "long_name": "wall time spent in each named phase"})
        out["phase_calls"] = (("timed_phase",), [int(timer.calls[k]) for k in named],
                              {"units": "1", "long_name": "times each named phase was entered"})
    return out
