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
  :data:`NAMED`) or for its machine class (its ``plausible:`` range): the unit of another
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


def _plausibility(name: str, value, unit: str, declared: dict | None = None) -> str | None:
    """Why ``value`` (in ``unit``) is implausible for parameter ``name`` (with its machine
    class's range ``declared``, the parameter's ``plausible:``), or None."""
    if unit not in UNITS or isinstance(value, bool):
        return None
    values = value if isinstance(value, list) else [value]
    for v in values:
        if not isinstance(v, (int, float)) or isinstance(v, bool):
            continue
        si, si_unit = to_si(v, unit)
        rules = []
        if isinstance(declared, dict) and UNITS.get(declared.get("unit"), (0, None))[1] == si_unit \
                and si != 0:
            lo, hi, u = declared["min"], declared["max"], declared["unit"]
            rules.append((to_si(lo, u)[0], to_si(hi, u)[0],
                          f"{declared['why']}: {lo:g} to {hi:g} {u} in magnitude"))
        rules += [NAMED[k] for k in NAMED if k[0] in name.lower() and k[1] == si_unit]
        rules += [PLAUSIBLE[si_unit]] if si_unit in PLAUSIBLE else []
        for lo, hi, why in rules:
            if not lo <= abs(si) <= hi:
                return (f"{v!r} {unit} = {si:.4g} {si_unit} is not plausible: allowed is "
                        f"{why} (a unit of another scale?)")
    return None


def check_parameters(raw: dict) -> list[str]:
    """Implausible parameter values of a paper config: the declared ones, and scene, study
    and profile overrides (in the parameter's declared unit)."""
    params = raw.get("parameters") if isinstance(raw, dict) else None
    if not isinstance(params, dict):
        return []
    units = {n: p.get("unit") for n, p in params.items() if isinstance(p, dict)}
    out = []

    def check(where, name, value, unit):
        declared = params[name].get("plausible") if isinstance(params.get(name), dict) else None
        msg = _plausibility(name, value, unit, declared) if unit else None
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
    implausible = check_parameters(raw)
    if implausible:
        raise InputError("; ".join(implausible))
    return raw
