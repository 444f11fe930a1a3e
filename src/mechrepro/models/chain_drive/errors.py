"""chain_drive's deliberate refusals, each a :class:`mechrepro.errors.Refusal` (a ValueError):
a caller catches exactly the one it can handle, never a bare ValueError from a bug."""
from __future__ import annotations

from mechrepro.errors import Refusal


class StabilityError(Refusal):
    """A time step beyond the stability limit was requested, or the tension went slack."""


class PeriodicityError(Refusal):
    """The excitation is not periodic over the shooting period (shooting would be wrong)."""


class UnknownChoice(Refusal):
    """A named choice (solver, differencing, kernel, sweep mode) outside the allowed ones."""


class KernelUnavailable(Refusal):
    """The compiled loop was required but cannot run here (no numba, or its conditions)."""


class EffectNotHonoured(Refusal):
    """A solver was given a contribution it does not consume."""


class NoEquilibrium(Refusal):
    """No small-sag equilibrium: P_0 - m c^2 <= 0."""


class DivergenceError(Refusal, FloatingPointError):
    """An explicit integration left the finite numbers (step beyond its stability limit)."""


class RecordError(Refusal):
    """A record or a fitted input does not meet its stated accuracy or length."""


class PitchScaleInstability(Refusal):
    """Central differencing asked for with an input that kicks pitch-scale waves: the
    impulsive impact pulse in the tension, or the instantaneous span-length switch.  Without
    numerical damping those waves (about two grid intervals long, shorter than a pitch,
    where a roller chain has no modes) are pumped into a growth the string model cannot
    represent; the mixed differencing of Eq. (2-38) damps them."""
