"""The one name -> function registry behind a paper's effects (:mod:`.effects`), its
cost-of-accuracy quantities (:mod:`.accuracy`) and its reported quantities
(:mod:`.validation`): register once, refuse a name registered twice."""
from __future__ import annotations

from collections.abc import Callable


class Registry:
    kind = "entry"

    def __init__(self, paper: str):
        self.paper = paper
        self._fn: dict[str, Callable] = {}
        self._names: dict[Callable, tuple[str, ...]] = {}

    def register(self, *names: str) -> Callable[[Callable], Callable]:
        """Decorator: ``fn`` provides ``names`` (one, or several it returns together)."""
        def deco(fn: Callable) -> Callable:
            for n in names:
                if n in self._fn:
                    raise ValueError(f"{self.paper}: {self.kind} {n!r} registered twice")
                self._fn[n] = fn
            self._names[fn] = names
            return fn
        return deco

    @property
    def names(self) -> list[str]:
        return list(self._fn)

    @property
    def groups(self) -> list[tuple[str, ...]]:
        """The names each function provides together."""
        return list(self._names.values())

    def __contains__(self, name: str) -> bool:
        return name in self._fn
