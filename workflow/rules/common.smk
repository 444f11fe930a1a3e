# Config loading and validation (before any rule runs), and the file lists rules share.
import sys
from pathlib import Path

from snakemake.utils import validate

BASE = Path(workflow.basedir)
SRC = BASE / "src"
sys.path.insert(0, str(SRC))  # this workflow's own package, not whatever is installed

from mechrepro.config import ConfigError, load_all  # noqa: E402

validate(config, str(BASE / "config/schema/config.schema.json"))
PROFILE = config["profile"]
RESULTS = config["results"]
PAPERS = config["papers"]
PY = sys.executable
try:
    CFG = load_all(BASE / "config", PAPERS, PROFILE)
except ConfigError as exc:
    sys.stderr.write(f"\n{exc}\n\n")
    raise SystemExit(1)


wildcard_constraints:
    paper="|".join(PAPERS),
    run="[a-z0-9_]+(-[0-9]{3})?(@[a-z0-9_]+(-lo|-hi)?)?",
    study="[a-z0-9_]+(@[a-z0-9_]+(-lo|-hi)?)?",


def code(*relpaths):
    """Source files a job depends on (Snakemake does not track imported modules)."""
    out = []
    for rel in relpaths:
        p = SRC / "mechrepro" / rel
        out += sorted(str(f) for f in p.rglob("*.py")) if p.is_dir() else [str(p)]
    return out


# The framework modules every solver job imports.
SOLVER_CORE = ["__init__.py", "solve.py", "io.py", "provenance.py", "accuracy.py", "effects.py"]


def model_code(paper):
    return code(*SOLVER_CORE, f"models/{paper}")


def runs_of(paper, variants=False):
    """Run files of a paper; with ``variants``, also the verdict re-check runs (``run@variant``)."""
    names = list(CFG[paper].runs) if variants else CFG[paper].base_runs
    return expand(f"{RESULTS}/{paper}/runs/{{run}}.nc", run=names)


def studies_of(paper, variants=False):
    names = list(CFG[paper].studies) if variants else CFG[paper].base_studies
    return expand(f"{RESULTS}/{paper}/studies/{{study}}.nc", study=names)


def migrated(paper):
    """Papers whose validation table the framework builds from their `reported:` block."""
    return "reported" in CFG[paper].raw


def figures_of(paper):
    return expand(f"{RESULTS}/{paper}/figures/{{f}}.png", f=CFG[paper].figures)


def tables_of(paper, notebook_only=False):
    names = CFG[paper].notebook_tables if notebook_only else CFG[paper].tables
    return expand(f"{RESULTS}/{paper}/tables/{{t}}.csv", t=names)
