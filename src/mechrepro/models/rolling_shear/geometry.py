"""The rolling-shear linkage constants (Figs. 2-5, Table II) in one frozen record, mm and rad
(the paper's fitness G < 1e-11 is in mm); :func:`from_parameters` converts from SI once.

Frame (docs/rolling_shear.md): origin E = fixed pivot of the guide rod l6, y upwards, the
overlap line y = -s; crank pivots A = (-l10 - l9, l11), G = (-l10, l11) (Eq. 9);
D = E + l6 e^{i theta6}, I = D + l5 e^{i theta5}, C = D + l8 e^{i(theta5 + alpha)}, blade
origin O = D + d e^{i(theta5 + beta1)}, blade angle beta = theta5 - beta2."""
from __future__ import annotations

from dataclasses import dataclass, replace
from functools import cached_property, lru_cache

import numpy as np

from mechrepro.errors import Refusal

from .design import INTENTS, design

MM_PER_M = 1000.0

LEVERS = ("l1", "l2", "l3", "l4", "l5", "l6", "l8", "l9", "l10", "l11")
#: the design intents and readings of a family-grid member (solver family_scan)
GRID_KEYS = ("blade_offset", "R", "width", "y_joint", "eq8_reading", "carrier_constants")
#: the levers the paper optimises (Sec. 3.3, step 3; Table II)
OPTIMISED_LEVERS = ("l1", "l3", "l5", "l6", "l10")
#: constants of a run's geometry stored with it (enough to redraw the linkage; dataset.py)
GEOMETRY_KEYS = LEVERS + ("alpha", "beta1", "beta2", "d", "h", "R", "s", "width", "x_mid")
#: the constants the equations of :mod:`.closure` read, in the order of their array
#: (:func:`constants`, :class:`.closure.Linkage`); the elbows (+1/-1) as floats
LINKAGE_KEYS = GEOMETRY_KEYS + ("elbow1", "elbow2")


@dataclass(frozen=True)
class Geometry:
    """All constants of the linkage, mm and rad; ``elbow1``/``elbow2`` and ``guide_mode`` select
    the assembly modes the paper's ranges leave open."""
    l1: float
    l2: float
    l3: float
    l4: float
    l5: float
    l6: float
    l8: float
    l9: float
    l10: float
    l11: float
    alpha: float
    beta1: float
    beta2: float
    d: float
    h: float
    R: float
    s: float
    width: float
    x_mid: float
    elbow1: int = 1
    elbow2: int = 1
    guide_mode: int = -1
    #: reading of Eq. (8): "rotation" (equal blade rotation, anchored at the first cut
    #: point) or "literal" (theta = huch / R as printed, anchored mid-cut); trajectory.py
    eq8: str = "rotation"
    #: what a lever change does to the carrier constants: "frozen" (l8, alpha, beta1,
    #: beta2, d, l11, x_mid kept) or "rederived" (re-derived from the design intents)
    carrier: str = "frozen"
    #: the design intents (mm, rad) the constants were derived from, as (name, value) pairs
    intents: tuple = ()

    @cached_property
    def constants(self):
        """:func:`constants` of this geometry, computed once (a kernel's argument)."""
        return constants(self)

    def with_levers(self, **levers) -> "Geometry":
        if self.carrier == "rederived" and self.intents:
            return derive({**dict(self.intents), **levers}, self)
        return replace(self, **levers)

    def levers(self, names=OPTIMISED_LEVERS) -> tuple[float, ...]:
        return tuple(getattr(self, n) for n in names)


INTENT_LENGTHS = ("l1", "l3", "l5", "l6", "l9", "l10", "s", "h", "R", "y_joint", "blade_offset",
                  "width")


def derive(intents: dict, base: "Geometry | None" = None, **modes) -> Geometry:
    """Geometry derived from design intents (mm, rad) by :func:`design.design`."""
    kw = {k: getattr(base, k) for k in ("elbow1", "elbow2", "guide_mode", "eq8", "carrier")} \
        if base is not None else {}
    kw.update(modes)
    levers = {k: intents[k] for k in ("l1", "l3", "l5", "l6", "l9", "l10")}
    d = design(**{k: intents[k] for k in INTENTS})
    return Geometry(**levers, **d, h=intents["h"], R=intents["R"], s=intents["s"],
                    width=intents["width"], intents=tuple(sorted(intents.items())), **kw)


def from_parameters(p: dict) -> Geometry:
    """The geometry of a run's SI parameters, its carrier constants derived from the design
    intents at run time (so a range-end variant changes all that follows from it)."""
    intents = {k: float(p[k]) * MM_PER_M for k in INTENT_LENGTHS}
    intents.update(theta6_mid=float(p["theta6_mid"]), elbow_angle=float(p["elbow_angle"]))
    return derive(intents, elbow1=int(p.get("elbow1", 1)), elbow2=int(p.get("elbow2", 1)),
                  guide_mode=int(p.get("guide_mode", -1)), eq8=str(p.get("eq8_reading", "rotation")),
                  carrier=str(p.get("carrier_constants", "frozen")))


def with_intent(g: Geometry, **intents) -> Geometry:
    """The same family member with some intents changed (re-derived)."""
    return derive({**dict(g.intents), **intents}, g)


def cut_points(g: Geometry, n: int):
    """Stations of the lowest point on y = -s (Sec. 3.3, step 1): ``n`` equally spaced over the
    rolled ``width`` centred on ``x_mid``, right to left (Eq. 8).  Returns (huch, x_k)."""
    if n < 2:
        raise Refusal(f"need at least 2 cut points, got {n}")
    huch = _stations(g.width, n)
    return huch.copy(), g.x_mid + 0.5 * g.width - huch


@lru_cache(maxsize=64)
def _stations(width: float, n: int):
    """``n`` equally spaced stations over [0, width], read-only and cached."""
    huch = np.linspace(0.0, width, n)
    huch.setflags(write=False)
    return huch


def constants(g) -> np.ndarray:
    """The fields of :data:`LINKAGE_KEYS` as the read-only float array a kernel takes (numba types
    an array faster than a named tuple); use the cached :attr:`Geometry.constants`."""
    c = np.array([getattr(g, k) for k in LINKAGE_KEYS], float)
    c.setflags(write=False)
    return c
