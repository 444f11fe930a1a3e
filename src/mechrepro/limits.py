"""Each solver's own limits and its declared cost, checked when the workflow loads the
configs: a run the solver would refuse, or one expected to exceed its job's memory or
time, is refused before any job, with the file, the run, the key, the value, what is
allowed and (for costs) the estimate.

A model declares them in ``mechrepro/models/<paper>/limits.py``:

- ``check(run) -> list[str]``: the solver's refusals, as ``"<key> = <value>: <why>;
  allowed: <what>"`` (the same conditions the solver raises on, evaluated on the run
  record alone, cheaply);
- ``work(run) -> {term: amount}``: the cost FORM of one run, the work it does counted
  from its record (grid points x steps, periods, particles x iterations, ...), and
  ``mem_mb(run)``, its expected peak memory [MB] (typed: no run records its memory, so
  there is nothing to fit).  The seconds per unit of each term, and what a solve process
  spends once, are data: :data:`COSTS`, written by ``python -m mechrepro.costs``;
- ``PRODUCED_BY = {variable: effect}``: solver outputs that exist only when a scene names
  that effect (beside the effects' declared contributions), and ``NEEDS_EFFECTS =
  {solver: why}``: solvers whose run without effects gives nothing a reported quantity
  reads, both for :func:`missing_effects`;
- ``solve_key(run)``: what the solve reads of a run's name fields (``variant``, ...)
  beyond its physics and resolution, so that runs equal in all else are not taken for
  one solve (:meth:`mechrepro.config.PaperConfig.same_solve`; chain_drive's stability-only
  sweeps).

A solve job solves its runs one after the other in one process: its memory is the largest
run's, its time its start plus the sum (:func:`job_costs`).  A job expected above the solve rule's
declared memory (:data:`SOLVE_MEM_MB`) or time (:data:`SOLVE_RUNTIME_MIN`) is refused
unless the run is started with ``--config over_budget=true`` on purpose; then the job
asks its executor for the estimate (a cluster gets the true request).
"""
from __future__ import annotations

import csv
import functools
import importlib
import math
from collections import Counter
from pathlib import Path

#: what the solve rule declares (workflow/rules/solve.smk reads these)
SOLVE_MEM_MB = 2000
SOLVE_RUNTIME_MIN = 30


#: the measured cost coefficients, in config/ because the workflow reads it with the
#: configs, at load, before any job (:mod:`mechrepro.costs` writes it from a default run)
COSTS = Path(__file__).resolve().parents[2] / "config" / "costs.csv"

#: the refinements a run solved to an accuracy target (:mod:`mechrepro.target`) is costed at
TARGET_LEVELS = 4


class LimitError(ValueError):
    pass


def coefficients() -> dict[tuple[str, str], dict[str, float]]:
    """{(paper, solver): {term: seconds per unit}} of the table (solver ``(job)``, term
    ``start``: what a paper's solve process spends beyond its runs' compute), read once."""
    return _read(COSTS)


@functools.lru_cache(maxsize=None)
def _read(path: Path) -> dict[tuple[str, str], dict[str, float]]:
    out: dict[tuple[str, str], dict[str, float]] = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            out.setdefault((row["paper"], row["solver"]), {})[row["term"]] = float(row["coefficient"])
    return out


def _fit(paper: str, solver: str, terms=("start",)) -> dict[str, float]:
    fit = coefficients().get((paper, solver), {})
    lack = [t for t in terms if t not in fit]
    if lack:
        raise LimitError(f"{COSTS}: no cost coefficients for paper {paper}, solver {solver}"
                         + (f", work term(s) {', '.join(lack)}" if fit else "") + "; allowed: the "
                         "table `python -m mechrepro.costs results` writes after a default run "
                         "that solved it with this code (make costs)")
    return fit


def work(paper: str, run: dict) -> dict[str, float] | None:
    """The work terms of one run (its model's ``work``; a run solved to an accuracy target:
    summed over :data:`TARGET_LEVELS` refinements of its knob), None if undeclared."""
    mod = _model(paper)
    if not hasattr(mod, "work") or not run.get("target"):
        return mod.work(run) if hasattr(mod, "work") else None
    out, res, knob, r = Counter(), run["resolution"], run["target"]["knob"], float(run["target"]["factor"])
    for k in range(TARGET_LEVELS):     # the target's refinements (ratio > 1: finer is larger)
        v = [x * r ** k for x in res[knob]] if isinstance(res[knob], list) else res[knob] * r ** k
        out.update(mod.work({**run, "resolution": {**res, knob: v}}))
    return dict(out)


def _model(paper: str):
    try:
        return importlib.import_module(f"mechrepro.models.{paper}.limits")
    except ModuleNotFoundError as exc:
        if exc.name != f"mechrepro.models.{paper}.limits":
            raise
        return None


def refusals(cfg) -> list[str]:
    """The solver's own refusals of every run of a paper config (empty: none)."""
    mod = _model(cfg.paper)
    if mod is None or not hasattr(mod, "check"):
        return []
    seen: dict[tuple, list[str]] = {}   # a scene's variants repeat its refusal: once
    for name, run in cfg.runs.items():
        for msg in mod.check(run):
            seen.setdefault((run["scene"], run["solver"], msg), []).append(name)
    out = []
    for (scene, solver, msg), names in seen.items():
        more = f" and {len(names) - 3} more" if len(names) > 3 else ""
        out.append(f"{cfg.path}: scene {scene} (solver {solver}; run "
                   f"{', '.join(names[:3])}{more}): {msg}")
    return out


def run_cost(paper: str, run: dict) -> dict | None:
    """{"mem_mb", "seconds", "compute_s"} of one run: ``compute_s`` the expected time of its
    ``compute(run)`` (what its ``wall_time_s`` measures), its work terms times the table's
    coefficients for its solver; ``seconds`` its time in its job, that repeated for the
    rounds of an alternated timing (``timing_repeat``) and to the least time a fast solve
    is repeated for (``options.timing_min_s``, :func:`mechrepro.solve._min_time`)."""
    w = work(paper, run)
    if w is None:
        return None
    fit = _fit(paper, run["solver"], w)
    sec = sum(fit[k] * v for k, v in w.items())
    return {"mem_mb": _model(paper).mem_mb(run), "compute_s": sec, "seconds": int(
        run.get("timing_repeat", 1)) * max(sec, float(run.get("options", {}).get("timing_min_s", 0.02)))}


def solve_key(paper: str, run: dict):
    """What a model's solve reads of a run beyond its record's physics and resolution (its
    ``models/<paper>/limits.py`` ``solve_key(run)``, e.g. chain_drive's stability-only
    sweeps, decided by the variant); None for a model that reads nothing more."""
    mod = _model(paper)
    return mod.solve_key(run) if mod is not None and hasattr(mod, "solve_key") else None


def job_costs(cfg) -> dict[str, dict]:
    """{solve job: {"mem_mb", "seconds", "largest", "longest"}} for the jobs whose runs all
    declare a cost (memory: the largest run; time: the paper's job start plus the sum, runs
    being solved one after the other, a run that repeats another's solve not counted)."""
    out, same = {}, cfg.same_solve()
    for job, runs in cfg.solve_jobs().items():
        costs = {r: run_cost(cfg.paper, cfg.runs[r]) for r in runs if r not in same}
        if not costs or any(c is None for c in costs.values()):
            continue
        largest = max(costs, key=lambda r: costs[r]["mem_mb"])
        out[job] = {"mem_mb": costs[largest]["mem_mb"], "largest": largest,
                    "longest": max(costs, key=lambda r: costs[r]["seconds"]),
                    "seconds": _fit(cfg.paper, "(job)")["start"] + sum(c["seconds"] for c in costs.values())}
    return out


def over_budget(cfg, mem_mb: float = SOLVE_MEM_MB,
                runtime_min: float = SOLVE_RUNTIME_MIN) -> list[str]:
    """Solve jobs expected above the rule's memory or time, each with its estimate."""
    out = []
    for job, c in job_costs(cfg).items():
        big = cfg.runs[c["largest"]]
        if c["mem_mb"] > mem_mb:
            out.append(f"{cfg.path}: job solve_{cfg.paper}__{job}: run {c['largest']} "
                       f"(resolution {big['resolution']}) is expected to take "
                       f"{c['mem_mb']:.0f} MB, above the solve rule's {mem_mb:.0f} MB; allowed: "
                       f"a resolution within {mem_mb:.0f} MB, or `--config over_budget=true` on "
                       f"purpose (the job then asks for {math.ceil(c['mem_mb'])} MB)")
        if c["seconds"] > 60 * runtime_min:
            slow = cfg.runs[c["longest"]]
            secs = run_cost(cfg.paper, slow)["seconds"]
            out.append(f"{cfg.path}: job solve_{cfg.paper}__{job}: its runs are expected to "
                       f"take {c['seconds'] / 60:.0f} min (the longest, run {c['longest']} "
                       f"(resolution {slow['resolution']}): {secs / 60:.0f} min), above the "
                       f"solve rule's {runtime_min:.0f} min; allowed: fewer or coarser runs, or "
                       f"`--config over_budget=true` on purpose")
    return out


def job_resources(cfg, job: str, allow: bool) -> dict:
    """The resources the solve job asks for: the rule's, or its estimate when above them
    and ``allow`` (over_budget) was given."""
    c = job_costs(cfg).get(job) if allow else None
    mem, runtime = SOLVE_MEM_MB, SOLVE_RUNTIME_MIN
    if c:
        mem = max(mem, math.ceil(c["mem_mb"]))
        runtime = max(runtime, math.ceil(c["seconds"] / 60))
    return {"mem_mb": mem, "runtime": runtime}


#: a paper whose solve jobs together are estimated at most this long [s] is solved first
QUICK_PAPER_S = 15.0


def quick_paper(cfg) -> bool:
    """Every solve job of the paper declares a cost and together they are estimated at
    most :data:`QUICK_PAPER_S`: the workflow solves such a paper before the others (a
    scheduling order: its figures appear within seconds; no result depends on it)."""
    costs = job_costs(cfg)
    return (len(costs) == len(cfg.solve_jobs())
            and sum(c["seconds"] for c in costs.values()) <= QUICK_PAPER_S)


def priorities(cfgs: dict) -> dict[tuple[str, str], float]:
    """{(paper, job): scheduling priority}, the job a solve job's name or ``validate`` or
    ``notebook``: 3 for every job of a quick paper (:func:`quick_paper`: its figures appear
    within seconds); else 1 plus a solve's estimated time as a fraction of the longest
    estimate, in [1, 2) (longest processing time first), and 0.5 for a paper's validation
    and notebook, after every solve: the seconds-long validations and notebooks then fill
    both cores at the end, where with priority 2 (a paper drawn as soon as its runs
    existed) chain_drive's solves, then its notebook, ran last on one core with the other
    idle.  An order only: no result depends on it.

    ``("all", "summary")`` and ``("all", "reference_check")``: 0.75, above the notebooks.
    They read only the validation tables, so they slip in between the notebooks and the run
    ends on the report and the archive alone."""
    est = {(p, j): c["seconds"] for p, cfg in cfgs.items() for j, c in job_costs(cfg).items()}
    top = 1.0001 * max(est.values(), default=1.0)
    out = {}
    for p, cfg in cfgs.items():
        quick = quick_paper(cfg)
        for j in cfg.solve_jobs():
            out[p, j] = 3.0 if quick else 1.0 + est.get((p, j), 0.0) / top
        out[p, "validate"] = out[p, "notebook"] = 3.0 if quick else 0.5
    out["all", "summary"] = out["all", "reference_check"] = 0.75
    return out


def check_all(cfgs: dict, allow_over_budget: bool = False, cache_dir=None) -> None:
    """Raise :class:`LimitError` with every refusal of every loaded paper config (with
    ``cache_dir``, the static reading of the extraction functions is kept there, keyed by
    their source)."""
    problems = []
    for cfg in cfgs.values():
        problems += missing_effects(cfg, cache_dir) + refusals(cfg)
        job_costs(cfg)    # a solver or work term the cost table lacks: refused, over budget or not
        if not allow_over_budget:
            problems += over_budget(cfg)
    if problems:
        raise LimitError("\n".join(problems))


# --- effects a reported quantity reads ----------------------------------------------------

def _extractor_reads(paper: str) -> dict[str, list[tuple[str, str, str, int]]]:
    """{quantity: [(kind, scene or study, variable, line)]}: what each extraction function
    of ``models/<paper>/validation.py`` visibly reads, by a static reading of its source:
    ``ds = R.run("scene")`` (or ``R.study``; literal or module constant), then
    ``ds["variable"]``, or a call passing ``ds`` with a literal variable name, or a module
    function called with ``ds`` (read the same way, transitively).  What it cannot see it
    leaves out (no refusal), so it never refuses a config whose validation works."""
    import ast

    path = Path(__file__).parent / "models" / paper / "validation.py"
    try:
        tree = ast.parse(path.read_text())
    except (OSError, SyntaxError):
        return {}
    consts = {t.id: n.value.value for n in tree.body if isinstance(n, ast.Assign)
              and isinstance(n.value, ast.Constant) and isinstance(n.value.value, str)
              for t in n.targets if isinstance(t, ast.Name)}
    funcs = {n.name: n for n in tree.body if isinstance(n, ast.FunctionDef)}

    def text(node):
        if isinstance(node, ast.Constant) and isinstance(node.value, str):
            return node.value
        return consts.get(node.id) if isinstance(node, ast.Name) else None

    def source(node, bound):
        if isinstance(node, ast.Name):
            return bound.get(node.id)
        if (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
                and node.func.attr in ("run", "study") and node.args
                and text(node.args[0]) is not None):
            return node.func.attr, text(node.args[0])
        return None

    def reads(fn, bound, depth=0):
        bound = dict(bound)
        for node in ast.walk(fn):   # names bound to an opened run or study
            if isinstance(node, ast.Assign) and len(node.targets) == 1:
                t, v = node.targets[0], node.value
                pairs = (zip(t.elts, v.elts) if isinstance(t, ast.Tuple)
                         and isinstance(v, ast.Tuple) else [(t, v)])
                for tt, vv in pairs:
                    if isinstance(tt, ast.Name) and source(vv, bound):
                        bound[tt.id] = source(vv, bound)
        out = []
        for node in ast.walk(fn):
            if isinstance(node, ast.Subscript) and source(node.value, bound) \
                    and text(node.slice) is not None:
                out.append((*source(node.value, bound), text(node.slice), node.lineno))
            elif isinstance(node, ast.Call):
                srcs = [(i, source(a, bound)) for i, a in enumerate(node.args)
                        if source(a, bound)]
                if len(srcs) != 1:
                    continue
                i, src = srcs[0]
                out += [(*src, text(a), node.lineno) for a in node.args
                        if text(a) is not None and a is not node.args[i]]
                callee = funcs.get(node.func.id) if isinstance(node.func, ast.Name) else None
                if callee is not None and depth < 4 and i < len(callee.args.args):
                    out += reads(callee, {callee.args.args[i].arg: src}, depth + 1)
        return out

    out = {}
    for fn in funcs.values():
        names = [text(a) for d in fn.decorator_list if isinstance(d, ast.Call)
                 and isinstance(d.func, ast.Attribute) and d.func.attr == "register"
                 for a in d.args]
        if names and None not in names:
            out.update(dict.fromkeys(names, reads(fn, {})))
    return out


def missing_effects(cfg, cache_dir=None) -> list[str]:
    """A scene whose effects and outputs lack one whose contribution a reported quantity
    reads from it (an emptied list would otherwise fail in validation, after the solve
    jobs)."""
    from .effects import declared

    effects = declared(cfg.raw)
    by_key = {k: e for e, spec in effects.items() for k in spec.get("contributes", [])}
    # a model may name solver outputs that exist only with an effect (not its declared
    # contributions): models/<paper>/limits.py PRODUCED_BY = {variable: effect}
    mod = _model(cfg.paper)
    by_key.update({k: e for k, e in getattr(mod, "PRODUCED_BY", {}).items() if e in effects})
    out, seen = [], set()
    if cache_dir is None:
        reads = _extractor_reads(cfg.paper)
    else:
        source = Path(__file__).parent / "models" / cfg.paper / "validation.py"
        reads = cfg.cached(cache_dir, ("extractor_reads", cfg.paper), [source, Path(__file__)],
                           lambda: _extractor_reads(cfg.paper))
    for q, found in reads.items():
        if q not in cfg.reported:
            continue
        for kind, name, key, line in found:
            members = [name] if kind == "run" else cfg.studies.get(name, [])
            if key not in by_key or not members or members[0] not in cfg.runs:
                continue
            run, need = cfg.runs[members[0]], by_key[key]
            kind_of = "outputs" if need in cfg.raw["outputs"] else "effects"
            if need in run[kind_of] or (run["scene"], need) in seen:
                continue
            seen.add((run["scene"], need))
            out.append(f"{cfg.path}: scenes.{run['scene']}.{kind_of} = {run[kind_of]}: "
                       f"reported quantity {q} reads {key!r} from {kind} {name} "
                       f"(models/{cfg.paper}/validation.py line {line}), which {kind_of[:-1]} "
                       f"{need!r} contributes; allowed: {kind_of} including {need!r} (honoured "
                       f"by {', '.join(effects[need]['honoured_by'])})")
    # a solver that computes nothing a reported quantity reads without effects:
    # models/<paper>/limits.py NEEDS_EFFECTS = {solver: why}
    needs = getattr(mod, "NEEDS_EFFECTS", {})
    read = {r for spec in cfg.reported.values() for r in spec.get("reads", [])}
    for scene, spec in cfg.raw["scenes"].items():
        studies = {s for s in cfg.studies if cfg.runs[cfg.studies[s][0]]["scene"] == scene}
        if (spec["solver"] in needs and not (spec.get("effects") or spec.get("outputs"))
                and (scene in read or studies & read)
                and not any(scene in o for o in out)):
            out.append(f"{cfg.path}: scenes.{scene}: no effects or outputs: solver "
                       f"{spec['solver']} needs one ({needs[spec['solver']]}); allowed: at least one of "
                       f"{', '.join(e for e, d in effects.items() if spec['solver'] in d['honoured_by'])}")
    return out
