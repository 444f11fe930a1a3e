"""Effect registry: a solver assembles only the effects its scene names.

Each paper keeps one :class:`EffectRegistry`.  Effect implementations register under the
name used in scenes; ``registry.select(run["effects"])`` returns only those callables, in
the registry's declaration order, and raises on names the paper does not know.  An effect
that is not selected is never looked up, let alone called -- tests check this by
replacing unselected entries with functions that raise.
"""
from __future__ import annotations

from collections.abc import Callable, Iterable


class UnknownEffect(KeyError):
    pass


class EffectRegistry:
    def __init__(self, paper: str):
        self.paper = paper
        self._effects: dict[str, Callable] = {}

    def register(self, name: str) -> Callable[[Callable], Callable]:
        def deco(fn: Callable) -> Callable:
            if name in self._effects:
                raise ValueError(f"{self.paper}: effect {name!r} registered twice")
            self._effects[name] = fn
            return fn
        return deco

    @property
    def names(self) -> list[str]:
        return list(self._effects)

    def select(self, effects: Iterable[str]) -> dict[str, Callable]:
        wanted = list(effects)
        unknown = [e for e in wanted if e not in self._effects]
        if unknown:
            raise UnknownEffect(f"{self.paper}: unknown effect(s) {unknown}; allowed: {self.names}")
        return {name: self._effects[name] for name in self._effects if name in wanted}

    def __contains__(self, name: str) -> bool:
        return name in self._effects
