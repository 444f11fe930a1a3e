# Config loading and validation (before any rule runs), and the file lists rules share.
import hashlib
import json
import os
import re
import sys
from pathlib import Path

# Paths relative to the working directory, so that a moved or copied project (results
# included) schedules nothing: Snakemake compares the set of input paths of every job.
BASE = Path(os.path.relpath(workflow.basedir))
SRC = BASE / "src"
sys.path.insert(0, str(SRC.resolve()))  # this workflow's own package, not whatever is installed

from mechrepro.config import CACHE_DIR, ConfigError, load_all  # noqa: E402

# config/config.yaml through the papers' strict reader and its schema, --config merged over
# it (the Snakefile has no `configfile:`: Snakemake's reader let a duplicate key through)
try:
    from mechrepro.config import workflow_config  # noqa: E402

    config.update(workflow_config(BASE / "config/config.yaml", dict(config)))
except ConfigError as exc:
    sys.stderr.write(f"\n{exc}\n\n")
    raise SystemExit(1)
PROFILE = config["profile"]
RESULTS = config["results"]
PAPERS = config["papers"]
# The cross-paper report and archive of a run of some papers go beside the full ones
# (`report-saw_chain/`), so `--config papers=[saw_chain]` never replaces the five-paper
# report or its archive.
_ALL = workflow_config(BASE / "config/config.yaml")["papers"]
_TAG = "" if sorted(PAPERS) == sorted(_ALL) else "-" + "+".join(PAPERS)
REPORT = f"{RESULTS}/report{_TAG}"
ARCHIVE = f"{RESULTS}/archive{_TAG}"
# A read-only project (a read-only mount, `chmod -R a-w`) stops here with one line naming
# the directory, before the config cache, the heal or Snakemake's own lock directory try to
# write (a traceback otherwise, even for a run with nothing to do).
from mechrepro.heal import refuse_read_only  # noqa: E402

refuse_read_only(workflow, RESULTS)
try:
    # validated once per content of the configs, schemas and loader (a no-op start is fast)
    CFG = load_all(BASE / "config", PAPERS, PROFILE, cache_dir=CACHE_DIR)
except ConfigError as exc:
    sys.stderr.write(f"\n{exc}\n\n")
    raise SystemExit(1)

# Each solver's own limits and declared cost (models/<paper>/limits.py), before any job:
# a run its solver would refuse, or a job expected above the solve rule's memory or time,
# stops the run here with the estimate (`--config over_budget=true` runs it on purpose).
from mechrepro.limits import LimitError, check_all, job_resources, priorities  # noqa: E402

OVER_BUDGET = str(config.get("over_budget", False)).lower() == "true"   # --config gives text
try:
    check_all(CFG, OVER_BUDGET, cache_dir=CACHE_DIR)
except LimitError as exc:
    sys.stderr.write(f"\n{exc}\n\n")
    raise SystemExit(1)

# the order in which free cores take jobs (limits.priorities)
PRIORITY = priorities(CFG)

# Every job runs `python -m mechrepro.<module>` with this workflow's src/ first on the path.
# relative when the interpreter lives in the project (.venv), so a moved project keeps its
# commands; absolute when it lives elsewhere, which does not move with the project
# One name per interpreter: `make` starts `.venv/bin/python -m snakemake`, the script
# `.venv/bin/snakemake` runs `.venv/bin/python3`; the command is a param of every job, so
# two spellings of one venv's interpreter would rerun every job when switching between them.
_exe = (Path(sys.prefix) / "bin" / "python" if sys.prefix != sys.base_prefix
        and (Path(sys.prefix) / "bin" / "python").exists() else Path(sys.executable)).absolute()
PY = (os.path.relpath(_exe) if _exe.is_relative_to(Path(workflow.basedir).absolute())
      else str(_exe))
RUN = {"python": f"PYTHONPATH={SRC} {PY}", "profile": PROFILE, "base": str(BASE)}


def code(*relpaths):
    """Source files a job imports (Snakemake does not track imported modules): their
    bytes are part of what made its results (mechrepro.staleness), never their times."""
    out = []
    for rel in (*CORE, *relpaths):
        p = SRC / "mechrepro" / rel
        out += sorted(str(f) for f in p.rglob("*.py")) if p.is_dir() else [str(p)]
    # a model's load-time limits (models/<paper>/limits.py) are read by the workflow
    # before any job, by no job: changing them reruns nothing
    return sorted({f for f in out
                   if not (Path(f).name == "limits.py" and "models" in Path(f).parts)})


# The framework modules every job imports (it writes through io.py, which records what
# made each file: staleness.py), and those of each kind of job.
CORE = ["__init__.py", "errors.py", "io.py", "provenance.py", "staleness.py"]
SOLVER_CORE = CORE + ["solve.py", "timing.py", "effects.py", "registry.py", "lazy.py",
                      "units.py", "config.py"]
VALIDATE_CORE = CORE + ["cli.py", "config.py", "units.py", "validation.py", "accuracy.py",
                        "costs.py", "registry.py", "lazy.py"]
NOTEBOOK_CORE = CORE + ["config.py", "units.py", "results.py", "validation.py", "accuracy.py",
                        "plotting.py", "notebook.py", "kernel.py", "registry.py", "lazy.py"]


def model_code(paper):
    """What a solver job imports: the framework core and the modules of its model the solve
    reaches (mechrepro.solve.model_modules), not those only validation and notebook read."""
    from mechrepro.solve import model_modules

    return code(*SOLVER_CORE, *model_modules(paper))


def fanned_out_studies():
    """Studies that `gather` stacks: those no solver job holds whole (a regex for its
    wildcard, so that it and the batch jobs never both claim a study file)."""
    return "|".join(s for p in PAPERS for s in CFG[p].studies
                    if not any(s in CFG[p].studies_solved_with(r)
                               for r in CFG[p].solve_jobs().values())) or "^$"


def records_of(paper, runs):
    """The digest of a job's run records.  A digest, not the records: Snakemake stores a
    job's params in the metadata of each of its outputs, and a batch job's records there
    are hundreds of kB per output, parsed again by every no-op run."""
    return hashlib.sha256(json.dumps({r: CFG[paper].runs[r] for r in runs},
                                     sort_keys=True).encode()).hexdigest()


# Every job, declared once: its result inputs, its outputs and the files whose bytes made
# them besides (mechrepro.staleness).  Rules take their inputs, outputs and the `made_by`
# param from it, and start their command with what made it, the inputs it reads and the
# results directory (MECHREPRO_MADE_BY, MECHREPRO_INPUTS, MECHREPRO_RESULTS); before any
# job, the records of what made each result are compared with these (end of the Snakefile).
from mechrepro.staleness import Job  # noqa: E402

JOBS = []


def job(rule, inputs, outputs, record=None, **sources):
    JOBS.append(Job(rule, [str(f) for f in inputs], [str(f) for f in outputs],
                    {k: [str(f) for f in v] for k, v in sources.items()}, record))
    return JOBS[-1]


# the job table of this start, which the archive job checks every archived file against
JOB_TABLE = f"{RESULTS}/.jobs{_TAG}.json"


def paper_config(paper):
    return str(BASE / f"config/papers/{paper}.yaml")


def runs_of(paper, variants=False):
    """Run files of a paper; with ``variants``, also the verdict re-check runs (``run@variant``)."""
    names = list(CFG[paper].runs) if variants else CFG[paper].base_runs
    return expand(f"{RESULTS}/{paper}/runs/{{run}}.nc", run=names)


def studies_of(paper, variants=False):
    names = list(CFG[paper].studies) if variants else CFG[paper].base_studies
    return expand(f"{RESULTS}/{paper}/studies/{{study}}.nc", study=names)



def figures_of(paper):
    return expand(f"{RESULTS}/{paper}/figures/{{f}}.png", f=CFG[paper].figures)


def tables_of(paper, notebook_only=False):
    names = CFG[paper].notebook_tables if notebook_only else CFG[paper].tables
    return expand(f"{RESULTS}/{paper}/tables/{{t}}.csv", t=names)


def report_assets():
    return [f"{REPORT}/index.html", f"{REPORT}/cost_of_accuracy_all.png",
            f"{REPORT}/summary.csv", f"{REPORT}/reference_check.txt"]


def archived_outputs():
    """What the archive holds: the declared results of every paper and the report, and
    nothing else (no glob: a renamed scene's leftovers are never certified)."""
    out = report_assets()
    for p in PAPERS:
        out += runs_of(p, variants=True) + studies_of(p, variants=True) + figures_of(p)
        out += tables_of(p) + [f"{RESULTS}/{p}/notebook.ipynb", f"{RESULTS}/{p}/claim.json"]
    return out


def every_output():
    """Every declared output (the target of the workflow), so that a deleted one is restored."""
    return archived_outputs() + [f"{ARCHIVE}/manifest.json",
                                 f"{ARCHIVE}/mechrepro-results.tar.gz"]
