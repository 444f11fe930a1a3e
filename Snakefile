# mechrepro: config -> solver runs (netCDF) -> validation, notebooks -> report -> archive.
# Run `make reproduce` (full, into results/) or `make ci-reproduce` (fast profile, as
# `snakemake --cores 2 --config profile=ci results=results-ci`).
configfile: "config/config.yaml"


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
