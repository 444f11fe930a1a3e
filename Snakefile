# mechrepro: config -> solver runs (netCDF) -> validation, notebooks -> report -> archive.
# Run `make reproduce` (full, into results/) or `make ci-reproduce` (fast profile, as
# `snakemake --cores 2 --config profile=ci results=results-ci`).
# config/config.yaml is read by workflow/rules/common.smk (mechrepro.config.workflow_config:
# the strict reader of the paper configs), not by `configfile:`; --config overrides it.


include: "workflow/rules/common.smk"
wildcard_constraints:
    paper="|".join(PAPERS),
    # variants: @coarser, @coarsest, @seed1, @<param>-lo|hi, @<family>-c00|s00, @falsify-<name>
    run="[a-z0-9_]+(-[0-9]{3})?(@[A-Za-z0-9_]+(-[A-Za-z0-9_]+)?)?",
    study="[a-z0-9_]+(@[A-Za-z0-9_]+(-[A-Za-z0-9_]+)?)?",


include: "workflow/rules/solve.smk"
include: "workflow/rules/notebook.smk"
include: "workflow/rules/report.smk"


# Cheap bookkeeping runs on the submitting host even under a cluster executor.
localrules:
    all,
    gather,
    summary,
    report,
    archive,
    reference_check,


rule all:
    input:
        every_output(),


# Before the jobs are decided, in the main process of a run: take this results directory's
# run lock (a second run is refused here, before it can touch anything), heal by content
# (mechrepro.heal), then compare what made each result with what would make it today and
# let Snakemake run exactly the jobs that differ and what depends on them
# (mechrepro.staleness; a dry run is steered alike, so `-n` says what a run will do).
# `make reproduce` and a plain `snakemake` are alike.
from mechrepro.heal import heal_workflow, steer_workflow  # noqa: E402

heal_workflow(workflow, RESULTS)
steer_workflow(workflow, JOBS, RESULTS, JOB_TABLE)
