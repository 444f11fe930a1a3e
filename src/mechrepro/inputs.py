"""Reading a paper config: what YAML and the JSON schema let through, refused here.

:func:`read_yaml` is the one reader of ``config/papers/<paper>.yaml`` and of
``config/config.yaml`` (called by :func:`mechrepro.config.load_paper` and
:func:`mechrepro.config.workflow_config` before the schema).  It refuses, naming the file,
the key, the value and what is allowed:

- bytes that are not UTF-8 (line, column and text of the line of the first bad byte);
- a key given twice in one mapping, at any level (YAML keeps the last silently: a second
  ``scenes:`` block would replace the first);
- NaN or infinity anywhere (``.nan``, ``.inf``): JSON-schema comparisons with NaN are
  false, so ``minimum: 0`` lets NaN through to the solver;
- a parameter whose value, in SI, is implausible for its dimension (:data:`PLAUSIBLE`,
  :data:`NAMED`) or for its machine class (:data:`RANGES`, per paper): the unit of another
  scale typed for the paper's (8.91 m for a chain pitch of 8.91 mm, 908 m for a shear's
  908 mm link, 206 MPa for a steel's 206 GPa), in the declared value and in every scene,
  study, sweep and profile override.

Each refusal is an :class:`InputError`, a ``yaml.YAMLError``, so the loader reports it as
it reports a syntax error: ``<file>: cannot read: <what>``.
"""
from __future__ import annotations

import math
from pathlib import Path

import yaml

from .units import UNITS, to_si


class InputError(yaml.YAMLError):
    pass


_Base = getattr(yaml, "CSafeLoader", yaml.SafeLoader)


class StrictLoader(_Base):
    """libyaml's safe loader where available, refusing duplicate keys at any level."""


def _mapping(loader, node, deep=False):
    seen = {}
    for key_node, _ in node.value:
        if key_node.tag == "tag:yaml.org,2002:merge":
            continue   # `<<: *anchor`: merged keys may be overridden, as YAML intends
        key = loader.construct_object(key_node, deep=True)
        try:
            hash(key)
        except TypeError:
            continue   # the base constructor names unhashable keys
        if key in seen:
            raise InputError(
                f"key {key!r} given twice in one mapping (line {seen[key] + 1} and line "
                f"{key_node.start_mark.line + 1}); YAML would keep only the last: allowed "
                f"is each key once")
        seen[key] = key_node.start_mark.line
    return loader.construct_mapping(node, deep=deep)


StrictLoader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, _mapping)


def _non_finite(obj, where=""):
    """Yield the dotted path and value of every NaN or infinity in ``obj``."""
    if isinstance(obj, float) and not math.isfinite(obj):
        yield where, obj
    elif isinstance(obj, dict):
        for k, v in obj.items():
            yield from _non_finite(v, f"{where}.{k}" if where else str(k))
    elif isinstance(obj, list):
        for i, v in enumerate(obj):
            yield from _non_finite(v, f"{where}[{i}]")


# SI unit -> (lowest, highest) plausible magnitude of a parameter of machine dynamics:
# desk- to plant-size machines.  Wide on purpose: they catch a unit of another scale
# (a factor 1e3 or more), never a design choice.  No lower bound on lengths and masses:
# tolerances (1e-11 mm) and regularisations are lengths too.
PLAUSIBLE = {
    "m": (0.0, 1e3, "a length up to 1 km"),
    "kg": (0.0, 1e6, "a mass up to 1000 t"),
    "rad/s": (0.0, 1e5, "an angular speed up to 1e5 rad/s (~1e6 r/min)"),
    "m/s": (0.0, 1e3, "a speed up to 1 km/s"),
    "Pa": (0.0, 1e13, "a stress or modulus up to 10 TPa"),
    "kg/m3": (1.0, 3e4, "a density between 1 kg/m3 and 30 000 kg/m3 (osmium: 22 600)"),
}
# name fragment, SI unit -> (lowest, highest, why): named parameters a unit slip can put
# within PLAUSIBLE yet far from any real machine
NAMED = {
    ("pitch", "m"): (3e-3, 0.2, "a chain pitch between 3 mm and 200 mm (ISO 606 / ANSI "
                                "roller chains 6.35-114.3 mm, saw chains 6.35-10.26 mm)"),
}

# paper -> {parameter: (lowest, highest, unit, why)}: the machine class of each paper's
# dimensional parameters, in the unit given.  Each range is narrower than a factor 1000
# where the class allows it (then every value inside it leaves it when typed in the unit
# one step of 1000 away: m for mm, kg for g, MPa for GPa), and wide enough never to refuse
# a design choice of that class.  Zero is never refused here (no unit makes a zero; the
# schema decides).  An angular speed's slip is a factor 60 / (2 pi) = 9.55 (the rad/s
# number typed for r/min, or the r/min number with unit rad/s): its range is narrower than
# that where the machine runs at one speed (saw_chain, joint_wear), so both slips leave
# it; chain_drive's own speeds span 50-800 r/min, and its range only catches larger slips.
# Parameters without a machine class (stiffnesses, damping, tolerances, fitted values) are
# left to the schema's `allowed`.
_ANGLE = (-360.0, 360.0, "deg", "an angle within one turn (a value in degrees given in "
                                "rad is ~57x too large)")
RANGES: dict[str, dict[str, tuple[float, float, str, str]]] = {
    "saw_chain": {
        "tie_strap_mass": (0.1, 50, "g", "a chain link (saw chain links 1-3 g; 50 g is a "
                                         "25 mm pitch roller chain link)"),
        "drive_link_mass": (0.1, 50, "g", "a chain link (saw chain links 1-3 g; 50 g is a "
                                          "25 mm pitch roller chain link)"),
        "textbook_mass": (0.5, 300, "g", "the textbook's moving mass, between one link "
                                         "(1.3 g) and the whole tight side (102 g) of a saw "
                                         "chain, with margin"),
        "sprocket_speed": (2000, 16000, "rpm", "a chain-saw sprocket (idle ~2800 r/min, "
                                               "cutting 9000-14000 r/min)"),
        "textbook_phase": _ANGLE,
    },
    "chain_drive": {
        "mass_per_length": (0.05, 40, "kg/m", "a roller chain (ISO 606: 0.15 kg/m at "
                                              "6.35 mm pitch to ~22 kg/m at 76 mm)"),
        "static_tension": (5, 2e5, "N", "a roller chain's static tension (breaking loads "
                                        "of ISO 606 chains are 4 kN to 1 MN)"),
        "speed": (1, 10000, "rpm", "a roller chain sprocket (ISO 10823: up to ~6000 r/min)"),
        "speed_min": (1, 10000, "rpm", "a roller chain sprocket (up to ~6000 r/min)"),
        "speed_max": (1, 10000, "rpm", "a roller chain sprocket (up to ~6000 r/min)"),
    },
    "disk_tension": {
        "outer_diameter": (50, 2000, "mm", "a circular saw blade (50 mm to ~2 m log saws)"),
        **{k: (2, 1000, "mm", "a radius on a circular saw blade of at most 2 m diameter")
           for k in ("clamp_radius", "rolling_radius", "calibration_clamp_radius",
                     "calibration_rolling_radius", "annulus_radii")},
        **{k: (0.05, 100, "mm", "a width of a heated or rolled band on a saw blade")
           for k in ("gaussian_width", "annulus_width",
                     "scan_gaussian_width")},
        "slot_depth": (0.1, 500, "mm", "a slot in a saw blade of at most 2 m diameter"),
        "slot_width": (0.1, 500, "mm", "a slot in a saw blade of at most 2 m diameter"),
        "youngs_modulus": (40, 700, "GPa", "a metal (magnesium 45 GPa, steel 190-215 GPa, "
                                           "tungsten carbide ~600 GPa)"),
        "density": (1000, 25000, "kg/m3", "a metal (magnesium 1740, steel 7850, tungsten "
                                          "19300 kg/m3)"),
        "thermal_expansion": (1e-6, 1e-4, "1/K", "a metal (tungsten 4.5e-6, steel 1.2e-5, "
                                                 "magnesium 2.6e-5 per K)"),
        "calibration_frequency": (1, 20000, "Hz", "a natural frequency of a saw blade "
                                                  "(tens of Hz to a few kHz)"),
        "fit_rolled_frequency": (1, 20000, "Hz", "a natural frequency of a saw blade "
                                                 "(tens of Hz to a few kHz)"),
    },
    "joint_wear": {
        **{k: (5, 5000, "mm", "a link of a planar four-bar linkage (5 mm to 5 m)")
           for k in ("crank_length", "coupler_length", "follower_length", "ground_length")},
        **{k: (0.01, 500, "kg", "a link of a planar four-bar linkage (10 g to 500 kg)")
           for k in ("coupler_mass", "follower_mass")},
        "load": (1, 50000, "N", "a load on a planar linkage of at most 500 kg links"),
        "crank_speed": (3, 28, "r/min", "the crank of a low-speed wear test of a linkage "
                                        "(the paper's rig 9.6 r/min; its continuous-contact "
                                        "model, Sec. 3.2, assumes low speed)"),
        "pin_radius": (0.01, 500, "mm", "a joint pin (watch pivots of ~0.05 mm to 0.5 m)"),
        "radial_clearance": (0.001, 5, "mm", "a radial clearance of a journal (1 um to 5 mm)"),
        "width": (1, 500, "mm", "a bushing width (1 mm to 0.5 m)"),
        **{k: (1, 700, "GPa", "a pin or bushing material (polymers ~1 GPa to tungsten "
                              "carbide ~600 GPa)") for k in ("E_pin", "E_bushing")},
        **{k: (1e-4, 10, "mm", "a measured wear depth of a journal (0.1 um to 10 mm)")
           for k in ("measured_wear_B1", "measured_wear_B2", "measured_increment_B1",
                     "measured_increment_B2")},
    },
    "rolling_shear": {
        **{k: (20, 20000, "mm", "a link of a plate shear (20 mm to 20 m)")
           for k in ("l1", "l3", "l5", "l6", "l9", "l10")},
        "s": (0.1, 200, "mm", "a blade overlap (0.1 to 200 mm)"),
        "width": (200, 10000, "mm", "a plate width of a plate shear (0.2 to 10 m)"),
        "opening": (10, 2000, "mm", "a blade opening of a plate shear (10 mm to 2 m)"),
        "R": (1000, 500000, "mm", "the arc radius of a rolling-cut blade (1 m to 500 m)"),
        "h": (10, 5000, "mm", "a height in a plate shear (10 mm to 5 m)"),
        "blade_offset": (10, 20000, "mm", "an offset of the blade in a plate shear (10 mm "
                                          "to 20 m either way)"),
        "clearance": (5, 2000, "mm", "a clearance in a plate shear (5 mm to 2 m)"),
        "plate_thickness_max": (1, 1000, "mm", "a plate thickness (1 mm to 1 m)"),
        "y_joint": (10, 5000, "mm", "a joint height in a plate shear (10 mm to 5 m)"),
        "transmission_min": _ANGLE,
        "elbow_angle": _ANGLE,
        "theta6_mid": _ANGLE,
    },
}


def _plausibility(name: str, value, unit: str, paper: str | None = None) -> str | None:
    """Why ``value`` (in ``unit``) is implausible for parameter ``name`` of ``paper``, or
    None."""
    if unit not in UNITS or isinstance(value, bool):
        return None
    values = value if isinstance(value, list) else [value]
    declared = RANGES.get(paper or "", {}).get(name)
    for v in values:
        if not isinstance(v, (int, float)) or isinstance(v, bool):
            continue
        si, si_unit = to_si(v, unit)
        rules = []
        if declared and UNITS.get(declared[2], (0, None))[1] == si_unit and si != 0:
            lo, hi, u, why = declared
            rules.append((to_si(lo, u)[0], to_si(hi, u)[0],
                          f"{why}: {lo:g} to {hi:g} {u} in magnitude"))
        rules += [NAMED[k] for k in NAMED if k[0] in name.lower() and k[1] == si_unit]
        rules += [PLAUSIBLE[si_unit]] if si_unit in PLAUSIBLE else []
        for lo, hi, why in rules:
            if not lo <= abs(si) <= hi:
                return (f"{v!r} {unit} = {si:.4g} {si_unit} is not plausible: allowed is "
                        f"{why} (a unit of another scale?)")
    return None


def check_parameters(raw: dict, paper: str | None = None) -> list[str]:
    """Implausible parameter values of ``paper`` (default: the file's ``paper:``): the
    declared ones, and scene, study and profile overrides (in the parameter's declared unit)."""
    params = raw.get("parameters") if isinstance(raw, dict) else None
    if not isinstance(params, dict):
        return []
    paper = raw.get("paper") if isinstance(raw.get("paper"), str) else paper
    units = {n: p.get("unit") for n, p in params.items() if isinstance(p, dict)}
    out = []

    def check(where, name, value, unit):
        msg = _plausibility(name, value, unit, paper) if unit else None
        if msg:
            out.append(f"{where} = {value!r}: {msg}")

    def overrides(tree, prefix):
        for kind in ("scenes", "studies"):
            for s, spec in (tree.get(kind) or {}).items():
                if not isinstance(spec, dict):
                    continue
                for n, v in (spec.get("parameters") or {}).items():
                    check(f"{prefix}{kind}.{s}.parameters.{n}", n, v, units.get(n))
                for n, v in ((spec.get("sweep") or {}) if kind == "studies" else {}).items():
                    check(f"{prefix}{kind}.{s}.sweep.{n}", n, v, units.get(n))

    for n, p in params.items():
        if isinstance(p, dict) and "value" in p:
            check(f"parameters.{n}.value", n, p["value"], p.get("unit"))
    overrides(raw, "")
    for prof, overlay in (raw.get("profiles") or {}).items():
        if isinstance(overlay, dict):
            for n, p in (overlay.get("parameters") or {}).items():
                if isinstance(p, dict) and "value" in p:
                    check(f"profiles.{prof}.parameters.{n}.value", n, p["value"],
                          p.get("unit", units.get(n)))
            overrides(overlay, f"profiles.{prof}.")
    return out


def read_yaml(path: str | Path):
    """Parse a config file strictly (see the module docstring); raise InputError."""
    path = Path(path)
    data = path.read_bytes()
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data[:exc.start].count(b"\n") + 1
        bol = data.rfind(b"\n", 0, exc.start) + 1
        eol = data.find(b"\n", exc.start)
        text = data[bol:eol if eol >= 0 else len(data)].decode("utf-8", "replace")
        raise InputError(f"byte {data[exc.start:exc.start + 1]!r} at line {line}, column "
                         f"{exc.start - bol + 1} ({text.strip()!r}) is not UTF-8: allowed is "
                         f"UTF-8 text (save the file as UTF-8)") from None
    raw = yaml.load(text, Loader=StrictLoader)
    bad = list(_non_finite(raw))
    if bad:
        raise InputError("; ".join(f"{w} = {v!r}: not a finite number, allowed are finite "
                                   f"numbers" for w, v in bad))
    implausible = check_parameters(raw, path.stem)
    if implausible:
        raise InputError("; ".join(implausible))
    return raw
