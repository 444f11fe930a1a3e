"""The one scene loader: paper config -> validated, fully resolved runs.

A paper config (``config/papers/<paper>.yaml``) holds the paper's parameters (each with
unit, the values it may take (``allowed:``) and source, or ``assumed: true`` and ``why``),
named **scenes** (effects +
resolution + parameter overrides) and **studies** (sweeps over a scene).  Loading:

1. the file is validated against ``config/schema/paper.schema.yaml`` (its shape);
2. the profile overlay (``profiles: {ci: ...}``) is merged in;
3. every scene and every study point is expanded into a **run** record and validated
   against the run schema generated from the config (:func:`run_schema`: each parameter's
   ``allowed:``, each knob's, the options, what each solver and effect needs), so a bad
   value is reported with file, key, value and allowed range before anything runs;
4. parameters are converted to SI (:mod:`mechrepro.units`);
5. the **variant runs** that re-check the verdicts are added (``<run>@coarser``,
   ``<run>@coarsest``, ``<run>@<param>-lo|hi``; see docs/VALIDATION.md): for every verdict
   row of the ``reported:`` block, each scene or study it ``reads`` is re-run one and two
   levels coarser (``refine:``; the baseline is the finest level, as in a grid convergence
   index study) and at both ends of the ``range`` of every assumed constant the row
   ``depends_on``.

A run record is plain JSON (str, int, float, list, dict) so that Snakemake's params
trigger can see every change.
"""
from __future__ import annotations

import copy
import dataclasses
import functools
import itertools
import json
import math
from dataclasses import dataclass, field
from pathlib import Path

import yaml

from .effects import declared
from .errors import Refusal
from .limits import solve_key
from .units import UNITS, to_si

SCHEMA_DIR_NAME = "schema"
#: the workflow's own profiles: one a paper does not overlay runs at the paper's defaults
WORKFLOW_PROFILES = ("ci",)

#: the fields of a run record that name it; everything else is what its solve computes
RUN_IDENTITY = ("run", "scene", "study", "sweep", "sweep_units", "variant")


class ConfigError(Refusal):
    """A config file is malformed or a value is out of range; the message names it."""


@dataclass
class PaperConfig:
    paper: str
    path: str
    profile: str
    source: str
    raw: dict
    runs: dict[str, dict] = field(default_factory=dict)
    studies: dict[str, list[str]] = field(default_factory=dict)
    # variant name -> names (scenes and studies) re-run under it
    variants: dict[str, list[str]] = field(default_factory=dict)
    # variant name -> {"kind", "label", "parameters" (paper units: what it sets)}
    variant_info: dict[str, dict] = field(default_factory=dict)
    # variant name -> {scene or study: why it cannot run} (a coarser level beyond a
    # solver's limits: the rows reading it get a two-level error estimate)
    variant_skipped: dict[str, dict[str, str]] = field(default_factory=dict)
    # the figures/tables this config was cut down to and the reported rows it evaluates
    # (:meth:`for_artefacts`); () = all
    artefacts: tuple[str, ...] = ()
    rows: tuple[str, ...] = ()

    @property
    def reported(self) -> dict[str, dict]:
        """What the paper reports (docs/VALIDATION.md), with ``kind`` filled in."""
        return {q: {"kind": "compare", **spec} for q, spec in self.raw.get("reported", {}).items()}

    @property
    def base_runs(self) -> list[str]:
        return [r for r in self.runs if "@" not in r]

    @property
    def base_studies(self) -> list[str]:
        return [s for s in self.studies if "@" not in s]

    @property
    def figures(self) -> list[str]:
        return list(self.raw.get("figures", {}))

    def figure(self, name: str) -> dict:
        """The declaration of figure ``name``: {caption, draw (``module.function``, by default
        ``figures.<name>``), reads}."""
        return {"draw": f"figures.{name}", **self.raw.get("figures", {})[name]}

    def table(self, name: str) -> dict:
        """The declaration of notebook table ``name``: {caption, make (``module.function``
        returning (header, rows), by default ``figures.<name>``), reads}."""
        return {"make": f"figures.{name}", **self.raw.get("tables", {})[name]}

    def caption(self, figure: str) -> str:
        return self.figure(figure)["caption"]

    @property
    def tables(self) -> list[str]:
        """Every table of the paper: the validation table, the notebook's (``tables:``), then
        the framework's others."""
        return list(dict.fromkeys(["validation", *self.raw.get("tables", {}),
                                   *self.framework_tables]))

    @property
    def notebook_tables(self) -> list[str]:
        """Tables the notebook writes (the others are the framework's: validation,
        cost_of_accuracy when the paper declares ``accuracy:``, effect_cost, job_time)."""
        return [t for t in self.tables if t not in self.framework_tables]

    @property
    def framework_tables(self) -> list[str]:
        return ["validation", "verdict_evidence", "discrimination", "verification_cost",
                "effect_cost", "job_time"] + (
            ["cost_of_accuracy"] if self.raw.get("accuracy") else []) + (
            ["effect_marginal_cost"] if self.raw.get("marginal_cost") else []) + (
            ["accuracy_targets"] if any(r.get("target") for r in self.runs.values()) else [])

    @property
    def ablations(self) -> dict[str, tuple[str, str]]:
        """``<scene>@without-<effect>`` -> (scene, effect): the runs that measure what each
        effect of a ``marginal_cost:`` scene costs the solve (:func:`mechrepro.costs.marginal`)."""
        return {r: (run["scene"], run["variant"][len("without-"):])
                for r, run in self.runs.items() if run.get("variant", "").startswith("without-")}

    def cached(self, cache_dir, key, files, build):
        """``build()`` kept in ``cache_dir`` by ``key`` and the content of ``files`` and of
        this config's schemas (:func:`_cached`)."""
        return _cached(cache_dir, key, files, _schema_dir(Path(self.path)), build)

    def assumed(self) -> dict[str, dict]:
        """Parameters the paper does not give, with value, unit and justification."""
        return {k: v for k, v in self.raw["parameters"].items() if v.get("assumed")}

    def same_solve(self) -> dict[str, str]:
        """{run: the earlier run it repeats}: runs equal in everything but their names (a
        scene that is also a point of a study, a rival that sets a value a study
        sweeps), which the solve job solves once and writes under each name with the one
        measured time (:func:`mechrepro.solve.main`).  Runs timed against each other
        (``marginal_cost:``) or solved to an accuracy target are never merged.  Worked out
        once per loaded config (every planning step asks; outside the dataclass fields, so
        a config cut down by :func:`dataclasses.replace` works its own out)."""
        if "_same" in self.__dict__:
            return self.__dict__["_same"]
        first: dict[str, str] = {}
        out = self.__dict__["_same"] = {}
        for name, run in self.runs.items():
            if run.get("target") or run.get("timing_repeat"):
                continue
            key = json.dumps([{k: v for k, v in run.items() if k not in RUN_IDENTITY},
                              solve_key(self.paper, run)], sort_keys=True, default=repr)
            if key in first:
                out[name] = first[key]
            else:
                first[key] = name
        return out

    def solve_jobs(self) -> dict[str, list[str]]:
        """{job name: runs it solves}, granularity by cost as the config declares it:
        a study under ``fan_out:`` gets one job per run (its points cost seconds each);
        a scene or study under ``alone:`` one job with its verdict variants; every other
        run of the paper shares one ``batch`` job (one interpreter start and import).  A
        run that repeats another (:meth:`same_solve`) goes to that run's job, which solves
        it once."""
        fan, alone = set(self.raw.get("fan_out", [])), set(self.raw.get("alone", []))
        same = self.same_solve()
        job_of: dict[str, str] = {}
        jobs: dict[str, list[str]] = {}
        for run, rec in self.runs.items():
            group = rec["study"] or rec["scene"]
            if run in same:
                key = job_of[same[run]]
            elif group in fan:
                key = run
            elif group in alone:
                key = ("study_" if rec["study"] else "scene_") + group
            else:
                key = "batch"
            job_of[run] = key
            jobs.setdefault(key.replace("@", "__").replace("-", "_"), []).append(run)
        return jobs

    def studies_solved_with(self, runs) -> list[str]:
        """The studies (and study variants) whose runs are all among ``runs``: a solver job
        stacks those itself; the others are gathered by the ``gather`` rule."""
        runs = set(runs)
        return [s for s, members in self.studies.items() if set(members) <= runs]

    def for_artefacts(self, artefacts, together=()) -> "PaperConfig":
        """This paper cut down to the verdict rows of some figures or tables and the runs
        those rows read: their baselines and the variants that re-check exactly these rows
        (``mechrepro.cli artefact``; ``pytest -k chain_drive-fig05``).  ``together``:
        groups of rows one extraction function computes at once (its reads are read
        whichever of its rows is asked for), each kept whole.  The rows come out as in the
        whole paper: the same runs, the same variants."""
        reported = self.reported
        rows = {q for q, s in reported.items() if s["artefact"] in artefacts}
        if not rows:
            have = sorted({s["artefact"] for s in reported.values()})
            raise ConfigError(f"{self.path}: artefacts {sorted(artefacts)}: none has a reported "
                              f"row in this paper; allowed: {', '.join(have)}")
        rows |= {q for group in together if rows & set(group) for q in group}
        wanted = {(name, variant) for q in rows for name in reported[q]["reads"]
                  for variant in [None, *_variant_names(reported[q], self.raw)]}
        runs = {r: rec for r, rec in self.runs.items()
                if (rec["study"] or rec["scene"], rec.get("variant")) in wanted}
        return dataclasses.replace(
            self, runs=runs, artefacts=tuple(sorted(artefacts)),
            rows=tuple(q for q in reported if q in rows),
            studies={s: m for s, m in self.studies.items() if set(m) <= set(runs)},
            variants={v: kept for v, names in self.variants.items()
                      if (kept := [n for n in names if (n, v) in wanted])})


def _format_error(err: "jsonschema.ValidationError", where: str) -> str:
    loc = ".".join(str(p) for p in err.absolute_path) or "<top>"
    v, inst = err.validator, err.instance
    allowed = {
        "minimum": lambda s: f"must be >= {s}",
        "exclusiveMinimum": lambda s: f"must be > {s}",
        "maximum": lambda s: f"must be <= {s}",
        "exclusiveMaximum": lambda s: f"must be < {s}",
        "enum": lambda s: f"allowed: {', '.join(map(str, s))}",
        "type": lambda s: f"must be of type {s}",
    }
    if v in allowed:
        return f"{where}: {loc} = {inst!r}: {allowed[v](err.validator_value)}"
    if v == "required":
        return f"{where}: {loc}: missing key ({err.message})"
    if v == "additionalProperties":
        known = ", ".join(sorted(err.schema.get("properties", {}))) or "none"
        hint = " (a resolution knob is declared under refine:)" if loc == "resolution" else ""
        return f"{where}: {loc}: unknown key ({err.message}); allowed: {known}{hint}"
    return f"{where}: {loc}: {err.message}"


_VALIDATORS: dict[str, tuple] = {}


def _validate(instance, schema, where: str) -> None:
    """Every run of every scene and variant is checked: jsonschema-rs decides (compiled,
    fast), and only an instance it refuses is checked again by jsonschema, whose errors
    say where and what is allowed (:func:`_format_error`)."""
    key = json.dumps(schema, sort_keys=True)   # a run schema is generated per load
    pair = _VALIDATORS.get(key)
    if pair is None:  # compiled once per schema; imported here: a job that reads the
        import jsonschema_rs  # cached config never validates

        pair = _VALIDATORS[key] = (jsonschema_rs.validator_for(schema), schema)
    if pair[0].is_valid(instance):
        return
    import jsonschema

    validator = jsonschema.validators.validator_for(schema)(schema)
    errors = sorted(validator.iter_errors(instance), key=lambda e: list(map(str, e.absolute_path)))
    if errors:
        raise ConfigError("invalid config:\n  " + "\n  ".join(_format_error(e, where) for e in errors))


def _deep_merge(base: dict, over: dict) -> dict:
    out = copy.deepcopy(base)
    for k, v in over.items():
        if isinstance(v, dict) and isinstance(out.get(k), dict):
            out[k] = _deep_merge(out[k], v)
        else:
            out[k] = copy.deepcopy(v)
    return out


def _schema_dir(path: Path) -> Path:
    # config/papers/<paper>.yaml -> config/schema/
    return path.resolve().parent.parent / SCHEMA_DIR_NAME


@functools.lru_cache(maxsize=None)
def load_schema(name: str, schema_dir: Path) -> dict:
    """A schema file, parsed once per process (treat it as read-only)."""
    return yaml.safe_load((schema_dir / name).read_text())


#: options every run may carry, whatever its paper (read by :mod:`mechrepro.solve`)
FRAMEWORK_OPTIONS = {"timing_min_s": {
    "type": "number", "minimum": 0,
    "description": "repeat a fast solve for at least this long and keep its fastest call "
                   "(default 0.02 s: mechrepro.solve)"}}


def run_schema(raw: dict) -> dict:
    """The JSON schema of a run record, generated from the paper config where each thing is
    declared once: each parameter's ``allowed:``, each resolution knob's ``description:``
    and ``allowed:`` under ``refine:``, the options under ``options:`` (and
    :data:`FRAMEWORK_OPTIONS`), the resolution keys a solver needs
    (``solvers.<s>.resolution``) and those an effect or output needs
    (``effects.<e>.resolution``, ``.options``; ``outputs.<o>...``); shared fragments under
    ``defs:`` (``{"$ref": "#/$defs/<name>"}``)."""
    knobs = {k: {**v.get("allowed", {}), "description": v["description"]}
             for k, v in raw.get("refine", {}).items()}
    needs = [({"solver": {"const": s}}, {"resolution": {"required": spec["resolution"]}})
             for s, spec in raw["solvers"].items() if spec.get("resolution")]
    for kind, e, spec in ((k, e, v) for k in ("effects", "outputs") for e, v in raw[k].items()):
        then = {k: {"required": spec[k]} for k in ("resolution", "options") if spec.get(k)}
        if then:
            needs.append(({kind: {"contains": {"const": e}}}, then))
    schema = {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "title": f"{raw['paper']} run (values in config units)",
        "type": "object", "required": ["solver", "effects", "resolution", "parameters"],
        "additionalProperties": False,
        "$defs": raw.get("defs", {}),
        "properties": {
            "solver": {"enum": list(raw["solvers"])},
            **{k: {"type": "array", "uniqueItems": True, "items": {"enum": list(raw[k])}}
               for k in ("effects", "outputs")},
            "resolution": {"type": "object", "additionalProperties": False, "properties": knobs},
            "options": {"type": "object", "additionalProperties": False,
                        "properties": {**FRAMEWORK_OPTIONS, **raw.get("options", {})}},
            "parameters": {"type": "object", "additionalProperties": False,
                           "required": list(raw["parameters"]),
                           "properties": {k: p["allowed"] for k, p in raw["parameters"].items()}},
        },
    }
    if needs:
        schema["allOf"] = [{"if": {"properties": cond}, "then": {"properties": then}}
                           for cond, then in needs]
    return schema


# Where jobs keep validated configs (relative to the workflow directory they run in).
CACHE_DIR = ".snakemake/mechrepro"


def _cached(cache_dir, key, files, schema_dir: Path, build):
    """``build()``, kept in ``cache_dir`` keyed by ``key`` and the content of ``files``, of
    every schema and of the loader's own code: every job of a run loads the same configs.
    Unreadable or unwritable caches only cost the validation again."""
    import hashlib
    import os
    import pickle
    import tempfile

    h = hashlib.sha256(repr(key).encode())
    try:
        for f in [*files, *sorted(schema_dir.glob("*.yaml")), Path(__file__),
                  Path(__file__).with_name("units.py"), Path(__file__).with_name("inputs.py")]:
            h.update(f.name.encode() + b"\0" + f.read_bytes())
    except OSError:
        return build()   # an unreadable config: the loader says which and why
    cached = Path(cache_dir) / f"config-{h.hexdigest()[:32]}.pickle"
    try:
        return pickle.loads(cached.read_bytes())
    except (OSError, EOFError, pickle.UnpicklingError, AttributeError):
        pass
    out = build()
    try:
        cached.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=cached.parent, suffix=".part")
        with os.fdopen(fd, "wb") as f:
            f.write(pickle.dumps(out))
        os.replace(tmp, cached)   # atomic: a concurrent job reads old or new, whole
        for old in sorted(cached.parent.glob("config-*.pickle"),
                          key=lambda f: f.stat().st_mtime)[:-64]:
            old.unlink(missing_ok=True)   # papers x profiles x a few edits are enough
    except OSError:
        pass
    return out


def load_paper(path: str | Path, profile: str = "default",
               cache_dir: str | Path | None = None) -> PaperConfig:
    """Load, validate and expand one paper config (the only way configs are read); with
    ``cache_dir`` (:data:`CACHE_DIR` in jobs), the result of an unchanged config is reused."""
    path = Path(path)
    if cache_dir is not None:
        return _cached(cache_dir, ("paper", str(path), profile), [path], _schema_dir(path),
                       lambda: load_paper(path, profile))
    where = str(path)
    try:
        # strict (mechrepro.inputs): UTF-8, no duplicate keys, no NaN, plausible units
        from .inputs import read_yaml; raw = read_yaml(path)  # noqa: E702
    except (OSError, yaml.YAMLError) as exc:
        raise ConfigError(f"{where}: cannot read: {exc}") from exc
    sdir = _schema_dir(path)
    _validate(raw, load_schema("paper.schema.yaml", sdir), where)
    for name, p in raw["parameters"].items():
        if p["unit"] not in UNITS:
            raise ConfigError(f"{where}: parameters.{name}.unit = {p['unit']!r}: "
                              f"allowed: {', '.join(UNITS)}")
    profiles = raw.get("profiles", {})
    if profile not in ("default", *WORKFLOW_PROFILES, *profiles):
        raise ConfigError(f"{where}: profile {profile!r} not defined (have: default, "
                          f"{', '.join(dict.fromkeys([*WORKFLOW_PROFILES, *profiles]))})")
    if profile in profiles:
        _check_overlay_names(raw, profiles[profile], f"{where}: profiles.{profile}")
        raw = _deep_merge(raw, profiles[profile])
        # an overlay can break what the file alone satisfied: check the merged result too
        _validate({k: v for k, v in raw.items() if k != "profiles"},
                  load_schema("paper.schema.yaml", sdir), f"{where} (profile {profile})")
    raw.setdefault("effects", {})
    raw.setdefault("outputs", {})
    _check_effects(raw, where)
    _check_artefacts(raw, where)
    paper = raw.setdefault("paper", path.stem)
    raw.setdefault("seed", 0)
    if paper != path.stem:
        raise ConfigError(f"{where}: paper = {paper!r}: must be the file's name, {path.stem!r} "
                          "(a paper is discovered from config/papers/<paper>.yaml)")
    schema = run_schema(raw)
    cfg = PaperConfig(paper=paper, path=where, profile=profile,
                      source=raw.get("source", ""), raw=raw)
    for scene in raw["scenes"]:
        cfg.runs[scene] = _make_run(raw, scene, None, 0, {}, schema, where)
    for study, spec in raw.get("studies", {}).items():
        if spec["scene"] not in raw["scenes"]:
            raise ConfigError(f"{where}: studies.{study}.scene = {spec['scene']!r}: "
                              f"allowed: {', '.join(raw['scenes'])}")
        names = []
        for i, point in enumerate(_sweep_points(spec, where, study)):
            run = f"{study}-{i:03d}"
            cfg.runs[run] = _make_run(raw, spec["scene"], study, i, point, schema, where)
            names.append(run)
        cfg.studies[study] = names
    _check_reported(raw, where)
    for key in ("fan_out", "alone"):   # job granularity names scenes or studies
        for name in raw.get(key, []):
            if name not in raw["scenes"] and name not in raw.get("studies", {}):
                raise ConfigError(f"{where}: {key}: {name!r} is neither a scene nor a study")
    _add_variants(cfg, raw, schema, where)
    _add_ablations(cfg, raw, where)
    _check_makers(cfg, where)
    for name, run in cfg.runs.items():
        _cross_check(raw.get("cross_checks", {}), run, f"{where} (run {name})")
    return cfg


_MATH = {k: getattr(math, k) for k in ("pi", "sqrt", "sin", "cos", "tan", "asin", "acos",
                                       "atan", "atan2", "hypot", "radians", "degrees", "exp",
                                       "log", "floor", "ceil")}
_MATH.update(abs=abs, min=min, max=max)


def _cross_check(checks: dict, run: dict, where: str) -> None:
    """Evaluate the paper's physical cross-checks on one run's SI parameters."""
    env = {**_MATH, **run["parameters"]}
    for name, spec in checks.items():
        try:
            ok = eval(spec["require"], {"__builtins__": {}}, env)  # noqa: S307 (config, not input)
        except Exception as exc:
            raise ConfigError(f"{where}: cross_checks.{name}: cannot evaluate "
                              f"{spec['require']!r}: {exc}") from None
        if not ok:
            used = {k: v for k, v in run["parameters"].items() if k in spec["require"]}
            raise ConfigError(f"{where}: physical cross-check {name!r} fails: "
                              f"{spec['require']} with {used} (SI): {spec['why']}")


VERDICT_KINDS = ("compare", "bound", "check")
# The resolution levels that give a verdict its error bar, by how many levels each lies
# below the baseline: its error is extrapolated from the two coarser ones (Richardson;
# Roache's grid convergence index) and, for a counted row, checked one level finer: a value
# that drifts when refined is seen, and a verdict the finer level changes is not decided.
LEVELS = {"finer": -1, "coarser": 1, "coarsest": 2}
# the level a rival's, a range end's and a family member's run are made at
# (docs/VALIDATION.md): a rival must make a check fail that passes there without it,
# and a range end or a family member moves the value by what it moves the value at that
# level (validation._row); one level below shows either as well as the baseline would, at
# a fraction of its cost
VARIANT_LEVEL = "coarser"


def _check_effects(raw: dict, where: str) -> None:
    """The effect protocol (:mod:`mechrepro.effects`), checked before any job is planned:
    every scene names a declared solver and only effects and outputs that solver honours,
    with what they require and without what they exclude.  Never silently ignored."""
    solvers, decl = raw["solvers"], declared(raw)
    if both := sorted(set(raw["effects"]) & set(raw["outputs"])):
        raise ConfigError(f"{where}: {both} declared both as effects and as outputs")
    for kind, name, spec in ((k, n, v) for k in ("effects", "outputs") for n, v in raw[k].items()):
        at = f"{where}: {kind}.{name}"
        for s in spec["honoured_by"]:
            if s not in solvers:
                raise ConfigError(f"{at}.honoured_by: solver {s!r} is not declared; solvers: "
                                  f"{', '.join(solvers) or '(none)'}")
        for key, e in ((k, e) for k in ("requires", "excludes") for e in spec.get(k, [])):
            if e not in decl:
                raise ConfigError(f"{at}.{key}: {e!r} is not a declared effect or output; "
                                  f"declared: {', '.join(decl)}")
        for k, unit in spec.get("units", {}).items():
            if k not in spec["contributes"]:
                raise ConfigError(f"{at}.units.{k}: not one of its contributions "
                                  f"{spec['contributes']}")
            if unit not in UNITS and not _udunits_like(unit):
                raise ConfigError(f"{at}.units.{k} = {unit!r}: not a unit")
    for scene, spec in raw["scenes"].items():
        _check_scene_effects(raw, spec["solver"], spec.get("effects", []),
                             f"{where}: scenes.{scene}", spec.get("outputs", []))


def _check_scene_effects(raw: dict, solver: str, effects: list[str], at: str,
                         outputs: list[str] = ()) -> None:
    """One scene's (or rival's) solver, effects and outputs against the declarations."""
    solvers, decl = raw["solvers"], declared(raw)
    if solver not in solvers:
        raise ConfigError(f"{at}.solver = {solver!r}: not declared; solvers: "
                          f"{', '.join(solvers) or '(none)'}")
    for k, e in [("effect", e) for e in effects] + [("output", e) for e in outputs]:
        if e not in raw[k + "s"]:
            raise ConfigError(f"{at}.{k}s: {e!r} is not a declared {k}; {k}s: "
                              f"{', '.join(raw[k + 's']) or '(none)'}")
    kind = {**dict.fromkeys(effects, "effect"), **dict.fromkeys(outputs, "output")}
    for e, k in kind.items():   # first what the solver cannot do at all, then combinations
        if solver not in decl[e]["honoured_by"]:
            raise ConfigError(f"{at}: {k} {e!r} is not honoured by solver {solver!r} "
                              f"(honoured by: {', '.join(decl[e]['honoured_by'])}); "
                              "remove it or choose one of those solvers")
    for e, k in kind.items():
        missing = [r for r in decl[e].get("requires", []) if r not in kind]
        if missing:
            raise ConfigError(f"{at}: {k} {e!r} requires {missing}")
        clash = [x for x in decl[e].get("excludes", []) if x in kind]
        if clash:
            raise ConfigError(f"{at}: {k} {e!r} excludes {clash}")


def _udunits_like(unit: str) -> bool:
    """Units of contributions not in the config table: products/powers of known symbols."""
    import re

    return bool(re.fullmatch(r"[A-Za-z0-9*/^() .-]+", unit))


def _check_rival(raw: dict, name: str, spec: dict, where: str) -> None:
    """A rival is a model the paper's text or physics rules out, never an edit of
    a number the paper gives, and never a change that stays inside what the config itself
    calls plausible (that is a range end, checked as such).  Refused here: a parameter with a
    paper ``source``; an assumed value inside its ``range``; an effect switched off whose
    strength is an assumed constant whose range reaches zero."""
    params = raw["parameters"]
    at = f"{where}: rivals.{name}"
    for p, v in spec.get("parameters", {}).items():
        d = params[p]
        if d.get("source") and not d.get("assumed"):
            raise ConfigError(f"{at}.parameters.{p} = {v!r}: the paper gives {p} "
                              f"({d['source']}); a rival is a model the paper rules out, never "
                              "an edit of its numbers (a solver option or an effect switched "
                              "off, with the paper's values kept)")
        lo_hi = d.get("range")
        if lo_hi and all(isinstance(x, (int, float)) for x in [*lo_hi, v]) \
                and min(lo_hi) <= v <= max(lo_hi):
            raise ConfigError(f"{at}.parameters.{p} = {v!r}: inside {p}'s plausible range "
                              f"{lo_hi}: a range end, not a rival (verdicts are re-checked "
                              "there already)")
    for e in spec.get("effects_off", []):
        for key in raw.get("effects", {}).get(e, {}).get("contributes", []):
            lo_hi = params.get(key, {}).get("range")
            if params.get(key, {}).get("assumed") and lo_hi and \
                    all(isinstance(x, (int, float)) for x in lo_hi) and min(lo_hi) <= 0:
                raise ConfigError(f"{at}.effects_off: {e!r}: its strength {key} is assumed with "
                                  f"a plausible range {lo_hi} that reaches zero: switching it "
                                  "off is a range end, not a rival")


def _check_reported(raw: dict, where: str) -> None:
    """Cross-references of the reported block: reads, depends_on, calibrations, ranges."""
    names = set(raw["scenes"]) | set(raw.get("studies", {}))
    params = raw["parameters"]
    reported = raw["reported"]
    families, rivals = raw.get("families", {}), raw.get("rivals", {})
    in_family = family_of(raw)
    for f, fam in families.items():
        for p in fam["members"]:
            if p not in params or "range" not in params[p]:
                raise ConfigError(f"{where}: families.{f}.members: {p!r} is not an assumed "
                                  f"parameter with a range")
            if p in families:
                raise ConfigError(f"{where}: families.{f}: {p!r} is a family, not a parameter")
        if fam.get("corners", True) and len(fam["members"]) > 6:
            raise ConfigError(f"{where}: families.{f}: {len(fam['members'])} members have "
                              f"{2 ** len(fam['members'])} corners; at most 6 members with "
                              "corners: true (use corners: false and samples: N)")
        if f in params:
            raise ConfigError(f"{where}: families.{f}: a family cannot share a parameter's name")
    for f, spec in rivals.items():
        for p in spec.get("parameters", {}):
            if p not in params:
                raise ConfigError(f"{where}: rivals.{f}.parameters: {p!r} is not a parameter")
        _check_rival(raw, f, spec, where)
    for key, spec in refine_spec(raw).items():
        if spec.get("factor") == 1:
            raise ConfigError(f"{where}: refine.{key} = 1: a knob that is never refined; give "
                              "it a factor (>1 for counts, <1 for steps and tolerances) or "
                              "declare {fixed: why} if it is a choice, not an accuracy knob")
    for q, spec in reported.items():
        for r in spec["reads"]:
            if r not in names:
                raise ConfigError(f"{where}: reported.{q}.reads: {r!r} is neither a scene nor a "
                                  f"study; allowed: {', '.join(sorted(names))}")
        for study, pick in spec.get("members", {}).items():
            sweep = raw.get("studies", {}).get(study, {}).get("sweep")
            if study not in spec["reads"] or sweep is None:
                raise ConfigError(f"{where}: reported.{q}.members.{study}: not a study this row "
                                  f"reads (reads: {spec['reads']})")
            for k, vals in pick.items():
                if k not in sweep or any(v not in sweep[k] for v in vals):
                    raise ConfigError(f"{where}: reported.{q}.members.{study}.{k} = {vals}: "
                                      f"allowed: values of its sweep "
                                      f"({', '.join(f'{a}: {b}' for a, b in sweep.items())})")
        for r in spec.get("rivals", []):
            if r not in rivals:
                raise ConfigError(f"{where}: reported.{q}.rivals: {r!r} is not declared under "
                                  f"rivals: ({', '.join(rivals) or 'none'})")
        for p in spec.get("depends_on", []):
            if p in families:
                continue
            if p in in_family:
                raise ConfigError(f"{where}: reported.{q}.depends_on: {p!r} is a member of "
                                  f"family {in_family[p]!r}, which is checked jointly: depend "
                                  f"on the family")
            if p not in params or not params[p].get("assumed"):
                raise ConfigError(f"{where}: reported.{q}.depends_on: {p!r} is not an assumed "
                                  f"parameter")
            if "range" not in params[p]:
                raise ConfigError(f"{where}: reported.{q}.depends_on: {p!r} has no range "
                                  f"(parameters.{p}.range: [lo, hi] with range_why)")
    for p, spec in params.items():
        if not spec.get("assumed"):
            continue
        how = [k for k in ("range", "calibrated_on", "numerical") if k in spec]
        if len(how) != 1:
            raise ConfigError(f"{where}: parameters.{p}: an assumed constant declares exactly one "
                              f"of range (+ range_why), calibrated_on, numerical; got {how or 'none'}")
        if "range" in spec and "range_why" not in spec:
            raise ConfigError(f"{where}: parameters.{p}.range: missing range_why")
        if "calibrated_on" in spec:
            target = spec["calibrated_on"]
            if reported.get(target, {}).get("evidence") != "calibration":
                raise ConfigError(f"{where}: parameters.{p}.calibrated_on = {target!r}: must name "
                                  f"a reported quantity with evidence: calibration")
        if "range" in spec:
            lo, hi = spec["range"]
            v = spec["value"]
            if all(isinstance(x, (int, float)) for x in (lo, hi, v)) and not lo <= v <= hi:
                raise ConfigError(f"{where}: parameters.{p}: value {v} outside its range [{lo}, {hi}]")


def refine_spec(raw: dict) -> dict[str, dict]:
    """``refine:`` normalised: {key: {"factor": f} | {"fixed": why}} (with its ``why``)."""
    return {key: {k: v[k] for k in ("factor", "fixed", "why") if k in v}
            for key, v in raw.get("refine", {}).items()}


def family_of(raw: dict) -> dict[str, str]:
    """{member parameter: family} of the declared families."""
    return {m: f for f, spec in raw.get("families", {}).items() for m in spec["members"]}


def _variant_names(spec: dict, raw: dict | None = None) -> list[str]:
    """The variants that re-check one reported row (docs/VALIDATION.md): the resolution
    levels, other seeds, range ends (one constant) or members (a family), and for a counted
    (independent) row every rival of its paper (or those the row restricts itself to)."""
    if spec["kind"] not in VERDICT_KINDS:
        return []
    out = [v for v in LEVELS if v != "finer" or (spec.get("evidence") == "independent"
                                                 and spec.get("finer", True))] \
        if spec.get("levels", True) else []
    out += [f"seed{k}" for k in range(1, int(spec.get("seeds", 0)) + 1)]
    families = (raw or {}).get("families", {})
    for p in spec.get("depends_on", []):
        if p in families:
            out += _family_members(p, families[p])
        else:
            out += [f"{p}-lo", f"{p}-hi"]
    if spec.get("evidence") == "independent":
        out += [f"rival-{r}" for r in rivals_of(spec, raw)]
    return out


def rivals_of(spec: dict, raw: dict | None) -> list[str]:
    """The rivals a counted row is re-run under: every rival of its paper, or the subset its
    ``rivals:`` names (a rival that cannot touch what the row reads, or whose runs would cost
    a multiple of the paper's solve; the discrimination matrix shows the others as not run)."""
    declared = list((raw or {}).get("rivals", {}))
    return [r for r in declared if r in spec["rivals"]] if "rivals" in spec else declared


def _family_members(name: str, fam: dict) -> list[str]:
    n = len(fam["members"])
    corners = [f"{name}-c{i:02d}" for i in range(2 ** n)] if fam.get("corners", True) else []
    return corners + [f"{name}-s{i:02d}" for i in range(int(fam.get("samples", 0)))]


def family_values(raw: dict, name: str, member: str) -> dict:
    """The parameter values (paper units) of one member variant of a family: a corner
    ``c<bits>`` (bit i set: member i at its range's upper end) or a seeded sample ``s<i>``
    (uniform inside the box; categorical or integer ranges take one of their ends)."""
    import zlib

    import numpy as np

    fam = raw["families"][name]
    params = raw["parameters"]
    out = {}
    if member.startswith("c"):
        bits = int(member[1:])
        for i, p in enumerate(fam["members"]):
            out[p] = params[p]["range"][(bits >> i) & 1]
        return out
    k = int(member[1:])
    rng = np.random.default_rng([int(raw.get("seed", 0)), zlib.crc32(name.encode()), k])
    for p in fam["members"]:
        lo, hi = params[p]["range"]
        u = float(rng.random())
        if all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in (lo, hi)):
            v = lo + u * (hi - lo)
            out[p] = int(round(v)) if all(isinstance(x, int) for x in (lo, hi, params[p]["value"])) else v
        else:
            out[p] = lo if u < 0.5 else hi
    return out


def _variant_overrides(raw: dict, variant: str) -> tuple[str, dict, str]:
    """(kind, parameter overrides in paper units, label) of a variant name."""
    if variant in LEVELS:
        return "level", {}, f"at the {variant} resolution"
    if variant.startswith("seed") and variant[4:].isdigit():
        return "seed", {}, f"at seed + {variant[4:]}"
    if variant.startswith("rival-"):
        f = variant[len("rival-"):]
        return "rival", dict(raw["rivals"][f].get("parameters", {})), \
            f"under rival {f} ({raw['rivals'][f]['removes']})"
    p, end = variant.rsplit("-", 1)
    if p in raw.get("families", {}):
        vals = family_values(raw, p, end)
        return "family", vals, f"at family {p} member {end} ({_short(vals)})"
    v = raw["parameters"][p]["range"][0 if end == "lo" else 1]
    return "range", {p: v}, f"at {p} = {v}{_unit(raw, p, v)} (range {end})"


def _unit(raw, p, v) -> str:
    u = raw["parameters"][p]["unit"]
    return f" {u}" if isinstance(v, (int, float)) and u != "1" else ""


def _short(vals: dict) -> str:
    return ", ".join(f"{k} = {v:.4g}" if isinstance(v, float) else f"{k} = {v}"
                     for k, v in vals.items())


def _add_variants(cfg: PaperConfig, raw: dict, run_schema: dict, where: str) -> None:
    """Add the variant runs (and studies) that the verdict rows need."""
    wanted: dict[str, dict[str, list[str]]] = {}  # variant -> name -> quantities needing it
    for q, spec in cfg.reported.items():
        for v in _variant_names(spec, raw):
            for name in spec["reads"]:
                wanted.setdefault(v, {}).setdefault(name, []).append(q)

    def members(name, quantities):
        """The runs of ``name`` these rows read: a study's declared ``members:`` (all
        of its points when a row declares none)."""
        if name in raw["scenes"]:
            return [name]
        picks = [cfg.reported[q].get("members", {}).get(name) for q in quantities]
        return [r for r in cfg.studies[name]
                if any(p is None or all(cfg.runs[r]["sweep"][k] in vals for k, vals in p.items())
                       for p in picks)]

    for variant, names in wanted.items():
        cfg.variants[variant] = sorted(names)
        kind, overrides, label = _variant_overrides(raw, variant)
        cfg.variant_info[variant] = {"kind": kind, "parameters": overrides, "label": label}
        for name, quantities in sorted(names.items()):
            why = f"variant {variant} of {name!r}, needed by {', '.join(quantities)}"
            # a rival, a range end or a family member runs at VARIANT_LEVEL where every
            # row reading it has levels (validation._row compares it with the check at that
            # same level)
            at = (VARIANT_LEVEL if kind in ("rival", "range", "family")
                  and all(cfg.reported[q].get("levels", True) for q in quantities) else None)
            # a variant identical to the baseline (a range end equal to the value) is not
            # re-run: the validation reads the baseline run for it
            try:
                base = members(name, quantities)
                runs = [_variant_run(raw, cfg.runs[run], variant, run_schema, where, why,
                                     at if kind == "rival" else None) for run in base]
                if at and kind in ("range", "family") and any(_differs(vr, cfg.runs[r])
                                                              for vr, r in zip(runs, base)):
                    runs = [_variant_run(raw, cfg.runs[run], variant, run_schema, where, why,
                                         at) for run in base]
            except ConfigError as exc:
                if variant not in LEVELS:
                    raise
                # a coarser level beyond what the run schema allows (a stability limit)
                cfg.variant_skipped.setdefault(variant, {})[name] = str(exc).split("\n")[-1].strip()
                continue
            if at and any(vr["resolution"] != cfg.runs[r]["resolution"]
                          for vr, r in zip(runs, base)):
                cfg.variant_info[variant].setdefault("level_of", {})[name] = at
            if name in raw["scenes"]:
                if _differs(runs[0], cfg.runs[name]):
                    cfg.runs[runs[0]["run"]] = runs[0]
                    cfg.variant_info[variant].setdefault("changed", []).append(name)
            else:
                if any(_differs(vr, cfg.runs[r]) for vr, r in zip(runs, base)):
                    cfg.runs.update({vr["run"]: vr for vr in runs})
                    cfg.studies[f"{name}@{variant}"] = [vr["run"] for vr in runs]
                    cfg.variant_info[variant].setdefault("changed", []).append(name)


def _add_ablations(cfg: PaperConfig, raw: dict, where: str) -> None:
    """One run per effect of each ``marginal_cost:`` scene, with that effect removed: the
    difference of the two solves' times is what the effect costs the solver (the work it
    causes inside the solve, not only its own evaluation). An effect another one (or an
    output) requires cannot be removed alone and gets no run; an output's cost is its own
    time (:mod:`mechrepro.effects`)."""
    for scene in raw.get("marginal_cost", []):
        if scene not in raw["scenes"]:
            raise ConfigError(f"{where}: marginal_cost: {scene!r} is not a scene; scenes: "
                              f"{', '.join(raw['scenes'])}")
        # the times are compared by difference: the solve job times the scene and these runs
        # in alternation, this many rounds, each keeping its fastest (mechrepro.solve.alternated)
        base = cfg.runs[scene] = {**cfg.runs[scene], "timing_repeat": 5}
        for e in base["effects"]:
            effects = [x for x in base["effects"] if x != e]
            try:
                _check_scene_effects(raw, base["solver"], effects, f"{where}: marginal_cost",
                                     base["outputs"])
            except ConfigError:
                continue
            cfg.runs[f"{scene}@without-{e}"] = {
                **base, "run": f"{scene}@without-{e}", "variant": f"without-{e}",
                "effects": effects, "contributes": _contributes(raw, effects, base["outputs"])}


def _contributes(raw: dict, *named: list[str]) -> dict[str, list[str]]:
    decl = declared(raw)
    return {e: decl[e]["contributes"] for names in named for e in names}


def _differs(variant_run: dict, base: dict) -> bool:
    return any(variant_run[k] != base[k]
               for k in ("parameters", "resolution", "effects", "outputs", "solver", "options",
                         "seed"))


def _refined(raw, base: dict, variant: str, where: str, why: str) -> dict:
    """The run's resolution ``LEVELS[variant]`` levels coarser (every knob together, each
    divided by its factor that many times, integers rounded; finer: multiplied once)."""
    refine = refine_spec(raw)
    resolution = copy.deepcopy(base["resolution"])
    for key, value in resolution.items():
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            continue  # a choice (an integrator's name): the same at every level
        if key not in refine:
            raise ConfigError(f"{where}: refine: no factor for resolution key {key!r} "
                              f"(scene {base['scene']!r}; {why}); add refine.{key} "
                              "(a factor, or {fixed: why} if it is not an accuracy knob)")
        if "fixed" in refine[key]:
            continue
        coarse = value / refine[key]["factor"] ** LEVELS[variant]
        resolution[key] = max(1, int(round(coarse))) if isinstance(value, int) else float(coarse)
    return resolution


def _variant_run(raw, base: dict, variant: str, run_schema, where, why,
                 at: str | None = None) -> dict:
    """The run record of ``variant`` of run ``base``; a rival, a range end or a family
    member ``at`` a level runs at that level's resolution, or at the baseline's where the
    run schema refuses the level."""
    scene = raw["scenes"][base["scene"]]
    resolution = copy.deepcopy(base["resolution"])
    params = {k: v["value"] for k, v in raw["parameters"].items()}
    params.update(scene.get("parameters", {}))
    params.update({k: v for k, v in base["sweep"].items() if k in params})
    effects, solver = list(base["effects"]), base["solver"]
    options, seed = copy.deepcopy(base["options"]), base["seed"]
    kind, overrides, _ = _variant_overrides(raw, variant)
    if kind == "level":
        resolution = _refined(raw, base, variant, where, why)
    elif kind == "seed":
        seed = base["seed"] + int(variant[4:])
    elif kind == "rival":
        spec = raw["rivals"][variant[len("rival-"):]]
        params.update(overrides)   # a model change: it overrides the scene's own values
        effects = [e for e in effects if e not in spec.get("effects_off", [])]
        effects += [e for e in spec.get("effects_on", []) if e not in effects]
        solver = spec.get("solver", solver)
        options.update(spec.get("options", {}))
        _check_scene_effects(raw, solver, effects, f"{where}: {why}", base["outputs"])
    else:
        # a scene or sweep that sets the constant itself keeps its own value
        params.update({p: v for p, v in overrides.items()
                       if p not in scene.get("parameters", {}) and p not in base["sweep"]})
    record = {"solver": solver, "effects": effects, "outputs": base["outputs"],
              "resolution": resolution, "parameters": params, "options": options}
    if kind in ("rival", "range", "family") and at:
        try:
            coarse = _refined(raw, base, at, where, why)
            _validate({**record, "resolution": coarse}, run_schema, f"{where} ({why})")
            record["resolution"] = resolution = coarse
        except ConfigError:
            pass      # the level is beyond what the schema allows: the baseline's resolution
    _validate(record, run_schema, f"{where} ({why})")
    si, units = {}, {}
    for k, v in params.items():
        si[k], units[k] = to_si(v, raw["parameters"][k]["unit"])
    return {**base, "run": f"{base['run']}@{variant}", "variant": variant,
            "solver": solver, "effects": effects, "options": options, "seed": seed,
            "contributes": _contributes(raw, effects, base["outputs"]),
            "resolution": resolution, "parameters": si, "units": units}


def _sweep_points(spec: dict, where: str, study: str) -> list[dict]:
    sweep = spec["sweep"]
    keys = list(sweep)
    if spec.get("mode", "product") == "zip":
        lengths = {len(v) for v in sweep.values()}
        if len(lengths) != 1:
            raise ConfigError(f"{where}: studies.{study}.sweep: mode zip needs equal lengths, "
                              f"got {dict((k, len(v)) for k, v in sweep.items())}")
        combos = zip(*sweep.values())
    else:
        combos = itertools.product(*sweep.values())
    return [dict(zip(keys, c)) for c in combos]


def _make_run(raw, scene_name, study, index, point, run_schema, where) -> dict:
    scene = raw["scenes"][scene_name]
    params = {k: v["value"] for k, v in raw["parameters"].items()}
    params.update(scene.get("parameters", {}))
    resolution = dict(scene.get("resolution", {}))
    for key, value in point.items():
        if key in resolution:
            resolution[key] = value
        elif key in params:
            params[key] = value
        else:
            raise ConfigError(f"{where}: studies.{study}.sweep.{key}: not a resolution key of "
                              f"scene {scene_name!r} nor a parameter")
    record = {"solver": scene["solver"], "effects": list(scene.get("effects", [])),
              "outputs": list(scene.get("outputs", [])), "resolution": resolution,
              "parameters": params, "options": scene.get("options", {})}
    origin = f"{where} (run {scene_name if study is None else f'{study}[{index}]'})"
    _validate(record, run_schema, origin)
    si, units = {}, {}
    for k, v in params.items():
        si[k], units[k] = to_si(v, raw["parameters"][k]["unit"])
    return {
        "paper": raw["paper"],
        "run": scene_name if study is None else f"{study}-{index:03d}",
        "scene": scene_name,
        "study": study,
        "sweep": point,
        # the unit of each swept value as written in the config (resolution keys: "1")
        "sweep_units": {k: raw["parameters"][k]["unit"] if k in raw["parameters"] else "1"
                        for k in point},
        "solver": scene["solver"],
        "effects": record["effects"],
        "outputs": record["outputs"],
        # what each named effect and output declares it contributes (checked when evaluated)
        "contributes": _contributes(raw, record["effects"], record["outputs"]),
        "resolution": resolution,
        "options": record["options"],
        "parameters": si,
        "units": units,
        "seed": int(scene.get("seed", raw.get("seed", 0))),
        **_calibration(raw),
        **_target(raw, scene, resolution, origin),
    }


def _target(raw: dict, scene: dict, resolution: dict, where: str) -> dict:
    """A scene's accuracy target, with the refinement step of its knob."""
    t = scene.get("target")
    if not t:
        return {}
    spec = {"factor": t["factor"]} if "factor" in t else refine_spec(raw).get(t["knob"], {})
    if t["knob"] not in resolution or "factor" not in spec:
        raise ConfigError(f"{where}: target.knob = {t['knob']!r}: must be a resolution key of the "
                          f"scene with a refine: factor (resolution: {sorted(resolution)})")
    default = {}
    if "compare_with" in t:   # the fixed setting compared with: another scene's knob value
        other = raw["scenes"].get(t["compare_with"], {}).get("resolution", {})
        if t["knob"] not in other:
            raise ConfigError(f"{where}: target.compare_with = {t['compare_with']!r}: must be a "
                              f"scene whose resolution sets {t['knob']!r}; allowed: "
                              f"{', '.join(n for n, s in raw['scenes'].items() if t['knob'] in s.get('resolution', {}))}")
        default = {"default": other[t["knob"]]}
    return {"target": {"reduce": "max", **t, "factor": spec["factor"], **default}}


def _calibration(raw: dict) -> dict:
    """The paper numbers that constants calibrated inside a run are fitted to (SI).

    A solver that re-calibrates a constant in every run (so that the assumed-range
    variants re-calibrate too) reads its target here instead of typing it again.
    """
    out = {}
    for p, spec in raw["parameters"].items():
        q = spec.get("calibrated_on")
        target = raw.get("reported", {}).get(q, {})
        if q and "value" in target and "unit" in target and target["unit"] in UNITS:
            value, unit = to_si(target["value"], target["unit"])
            out[p] = {"quantity": q, "value": value, "unit": unit}
    return {"calibration": out} if out else {}


def _check_artefacts(raw: dict, where: str) -> None:
    """A reported row's ``artefact`` is a declared figure or table, or ``text``."""
    allowed = [*raw.get("figures", {}), *raw.get("tables", {}), "text"]
    for q, spec in raw["reported"].items():
        if spec["artefact"] not in allowed:
            raise ConfigError(f"{where}: reported.{q}.artefact = {spec['artefact']!r}: allowed: "
                              f"a figure, a table or text ({', '.join(allowed)})")


#: what declares each kind of artefact's function: a figure's ``draw``, a table's ``make``
MAKER = {"figures": "draw", "tables": "make"}


def _check_makers(cfg: PaperConfig, where: str) -> None:
    """A figure draws and a table is made with a function of its paper's model package, from
    runs and studies of this profile."""
    models = Path(__file__).parent / "models" / cfg.paper
    for kind, key, name in ((k, key, n) for k, key in MAKER.items() for n in cfg.raw.get(k, {})):
        spec = getattr(cfg, kind[:-1])(name)
        if "." in spec[key] and not (models / f"{spec[key].split('.')[0]}.py").exists():
            raise ConfigError(f"{where}: {kind}.{name}.{key} = {spec[key]!r}: no module "
                              f"{spec[key].split('.')[0]}.py in src/mechrepro/models/"
                              f"{cfg.paper}; allowed: module.function of that package")
        for r in spec["reads"]:
            if r not in cfg.runs and r not in cfg.studies:
                raise ConfigError(f"{where}: {kind}.{name}.reads: {r!r} is neither a run nor a "
                                  f"study of profile {cfg.profile}; allowed: a scene, a study "
                                  f"or one of their runs (a name covers its @variants)")


def _check_overlay_names(raw: dict, overlay, at: str) -> None:
    """A profile overlay changes scenes, studies and parameters the file declares, never
    adds one: a misspelt name is refused as such (merged in, it became a new scene and the
    schema said only "missing key ('solver')")."""
    if not isinstance(overlay, dict):
        return   # the merged file's schema check names what is wrong
    for kind in ("scenes", "studies", "parameters"):
        names, known = overlay.get(kind), raw.get(kind) or {}
        for name in (names if isinstance(names, dict) else {}):
            if name not in known:
                raise ConfigError(f"{at}.{kind}.{name}: not one of the file's {kind} (a "
                                  f"misspelt name?); allowed: {', '.join(known) or 'none'}")


def discover_papers(config_dir: str | Path) -> list[str]:
    """Every paper there is: one ``config/papers/<paper>.yaml`` each (``config.yaml`` only
    selects among them)."""
    return sorted(f.stem for f in (Path(config_dir) / "papers").glob("*.yaml"))


def workflow_config(path: str | Path = "config/config.yaml", overrides=None) -> dict:
    """``config/config.yaml`` read as the paper configs are (:func:`mechrepro.inputs.read_yaml`:
    UTF-8, each key once, finite numbers) and checked against ``config.schema.yaml``, then
    with ``overrides`` (Snakemake's ``--config key=value``) merged over it and checked
    again: Snakemake's own reader kept a duplicate ``profile:`` silently and named neither
    file nor key for a bad byte or a schema error.  A :class:`ConfigError` names the file
    (and ``--config`` where an override is at fault) and the key."""
    from .inputs import read_yaml

    path = Path(path)
    try:
        raw = read_yaml(path)
    except (OSError, yaml.YAMLError) as exc:
        raise ConfigError(f"{path}: cannot read: {exc}") from exc
    schema = load_schema("config.schema.yaml", path.resolve().parent / SCHEMA_DIR_NAME)
    if not isinstance(raw, dict):
        raise ConfigError(f"{path}: must be a mapping of {', '.join(schema['properties'])}")
    # the file alone (its keys may come from --config instead), then what will run
    _validate(raw, {k: v for k, v in schema.items() if k != "required"}, str(path))
    merged = {**raw, **(overrides or {})}
    _validate(merged, schema, f"{path} with --config {', '.join(overrides)}" if overrides
              else str(path))
    return merged


def load_all(config_dir: str | Path, papers, profile: str = "default",
             every_profile: bool = True, cache_dir: str | Path | None = None
             ) -> dict[str, PaperConfig]:
    """The selected profile of every paper; ``every_profile`` also checks the others, so a
    bad value in a profile that is not running now is refused now, not mid-way later.
    With ``cache_dir``, kept as :func:`load_paper` keeps one paper (a no-op decision of
    the workflow skips the validation it already passed)."""
    config_dir = Path(config_dir)
    if cache_dir is not None:
        return _cached(cache_dir, ("all", str(config_dir), sorted(papers), profile, every_profile),
                       sorted((config_dir / "papers").glob("*.yaml")),
                       config_dir.resolve() / SCHEMA_DIR_NAME,
                       lambda: load_all(config_dir, papers, profile, every_profile))
    known = discover_papers(config_dir)
    missing = [p for p in papers if p not in known]
    if missing:
        raise ConfigError(f"papers: {', '.join(map(repr, missing))} has no "
                          f"{config_dir / 'papers'}/<paper>.yaml; allowed: {', '.join(known)}")
    out = {p: load_paper(config_dir / "papers" / f"{p}.yaml", profile) for p in papers}
    if every_profile:
        for p, cfg in out.items():
            for other in ["default", *cfg.raw.get("profiles", {})]:
                if other != profile:
                    load_paper(config_dir / "papers" / f"{p}.yaml", other)
    return out
