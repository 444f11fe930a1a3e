"""One refusal type.

Every error mechrepro raises on purpose is a :class:`Refusal`: an input, a result or a state
is outside what the code can answer, and the message names the file, key or quantity, the
value and what is allowed.  Domain errors (a config value out of range, a time step beyond
its stability limit, a K beyond the round-off limit, a mechanism that cannot assemble) are
subclasses, so a caller catches exactly the refusal it can handle and never a bare
``ValueError`` from a bug.
"""
from __future__ import annotations


class Refusal(ValueError):
    """mechrepro refuses: the message says what, the value, and what is allowed."""
