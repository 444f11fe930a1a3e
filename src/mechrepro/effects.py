"""The effect protocol: a scene's solver, effects and outputs decide exactly what runs.

An **effect** is physics the solve includes; an **output** is what is computed from the
solved model beside it (a reference solution, an analysis, a comparison model), so that the
scene's physics never depends on it.  Both are declared once per paper in its config
(``config/papers/<paper>.yaml``), outputs under ``outputs:`` with the same fields::

    solvers:
      finite_difference: {description: "Eqs. (2-36)-(2-38), implicit march"}
    effects:
      impact:
        description: "Eqs. (2-2)-(2-4): impact load of a roller on a tooth"
        contributes: [tension]          # the keys its implementation returns
        units: {tension: N}
        honoured_by: [finite_difference, galerkin]
        requires: []                    # effects that must be named with it
        excludes: []                    # effects that must not

and checked when the config is loaded (:func:`mechrepro.config.load_paper`): a scene that
names an effect or output its solver does not honour is refused before any job is planned.

Implemented once per paper, effects and outputs alike: ``@EFFECTS.register("impact")`` on a
pure function ``fn(ctx) -> {key: value}`` of the solver's context.  A solver calls
:meth:`EffectRegistry.evaluate` with its run and context and reads the returned
:class:`Contributions` by *key* (``tension``, ``u_left``, ...), never by effect name: an
effect that is not named is never looked up, let alone called, and each one that is
named is timed (:mod:`mechrepro.timing`), so the report can say what it costs.  A solver
that needs some contributions before others asks for them by key, stage by stage
(:meth:`EffectRegistry.stages`); each effect is still evaluated once.  The outputs come
last, after every effect, each timed as ``output:<name>``; an output's cost is its own time,
never a difference of solves (``marginal_cost:`` removes effects only).
"""
from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import Any

from .errors import Refusal
from .registry import Registry
from .timing import EFFECT, OUTPUT, phase


def declared(raw: dict) -> dict[str, dict]:
    """Every effect and output of a paper config by name (one namespace)."""
    return {**raw.get("effects", {}), **raw.get("outputs", {})}


class UnknownEffect(Refusal, KeyError):
    """A scene names an effect no model registered."""


class ContributionError(Refusal):
    """An effect or output returned keys its declaration does not contribute."""


class Contributions:
    """What the named effects contributed, by key, in the registry's declaration order."""

    def __init__(self):
        self._by_key: dict[str, list[tuple[str, Any]]] = {}

    def add(self, effect: str, values: dict) -> None:
        for key, value in values.items():
            self._by_key.setdefault(key, []).append((effect, value))

    def __contains__(self, key: str) -> bool:
        return key in self._by_key

    def keys(self) -> list[str]:
        return list(self._by_key)

    def all(self, key: str) -> list:
        return [v for _, v in self._by_key.get(key, [])]

    def total(self, key: str, zero=0.0, out=None):
        """The sum of every contribution to ``key`` (``zero`` when none was named); with
        ``out`` (an array), added into it in place, in the same order (no temporary per
        term on a large grid)."""
        if out is not None:
            for v in self.all(key):
                out += v
            return out
        acc = zero
        for v in self.all(key):
            acc = acc + v
        return acc

    def get(self, key: str, default=None):
        """The single contribution to ``key``; two effects contributing it is an error."""
        vals = self._by_key.get(key, [])
        if len(vals) > 1:
            raise ContributionError(f"{key!r} contributed by {[e for e, _ in vals]}; "
                                    "expected one (use total() for additive terms)")
        return vals[0][1] if vals else default

    def sources(self, key: str) -> list[str]:
        """Which effects contributed ``key`` (for provenance and messages only)."""
        return [e for e, _ in self._by_key.get(key, [])]


class EffectRegistry(Registry):
    """The implementations of one paper's declared effects."""

    kind = "effect"

    def select(self, effects: Iterable[str]) -> dict[str, Callable]:
        """The implementations of ``effects`` in declaration order (unknown names raise)."""
        wanted = list(effects)
        unknown = [e for e in wanted if e not in self._fn]
        if unknown:
            raise UnknownEffect(f"{self.paper}: unknown effect(s) {unknown}; allowed: {self.names}")
        return {name: self._fn[name] for name in self._fn if name in wanted}

    def evaluate(self, run: dict, ctx, keys: Iterable[str] | None = None) -> Contributions:
        """Evaluate each effect the run names (or, with ``keys``, those of them whose
        declaration contributes any of these keys), timed, and return their contributions."""
        return Stages(self, run, ctx)(keys)

    def stages(self, run: dict, ctx) -> "Stages":
        """The run's effects, to be evaluated stage by stage (:class:`Stages`)."""
        return Stages(self, run, ctx)


class Stages:
    """A solver's named effects evaluated stage by stage, each exactly once: ``stage(keys)``
    evaluates those not yet evaluated whose declaration contributes any of ``keys`` (what
    the solver's next step reads), ``stage()`` all the rest and then the run's outputs.  A
    solver names keys, never effects.  The keys an effect or output returns must be the ones
    its declaration lists (``run["contributes"]``, from the config)."""

    def __init__(self, registry: EffectRegistry, run: dict, ctx):
        self.registry, self.run, self.ctx = registry, run, ctx
        self.pending, self.outputs = list(run["effects"]), list(run.get("outputs", ()))

    def __call__(self, keys: Iterable[str] | None = None) -> Contributions:
        declared = self.run.get("contributes", {})
        keys = None if keys is None else set(keys)
        names = [e for e in self.pending if keys is None or set(declared.get(e, ())) & keys]
        self.pending = [e for e in self.pending if e not in names]
        out = Contributions()
        timed = [(n, fn, EFFECT) for n, fn in self.registry.select(names).items()]
        if keys is None:
            timed += [(n, fn, OUTPUT) for n, fn in self.registry.select(self.outputs).items()]
            self.outputs = []
        for name, fn, kind in timed:
            with phase(kind + name):
                values = fn(self.ctx)
            if name in declared and set(values) - set(declared[name]):
                raise ContributionError(
                    f"{self.registry.paper}: {kind.rstrip(':')} {name!r} returned "
                    f"{sorted(values)}; its declaration contributes {declared[name]}")
            out.add(name, values)
        return out
