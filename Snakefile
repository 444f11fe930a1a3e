# mechrepro: config -> parameter files -> solver runs (netCDF) -> notebooks -> report -> archive.
# Run `make reproduce` (full) or `snakemake --cores 2 --config profile=ci` (fast profile).
configfile: "config/config.yaml"


include: "workflow/rules/common.smk"
include: "workflow/rules/params.smk"
include: "workflow/rules/solve.smk"
include: "workflow/rules/notebook.smk"
include: "workflow/rules/report.smk"


# Cheap bookkeeping runs on the submitting host even under a cluster executor.
localrules:
    all,
    run_params,
    gather,
    summary,
    report,
    archive,
    reference_check,


rule all:
    input:
        f"{RESULTS}/report/index.html",
        f"{RESULTS}/archive/manifest.json",
