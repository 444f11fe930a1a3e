# Per paper: `validate_<paper>` builds the validation table and the replication claim from
# the `reported:` block (baseline and variant runs); the papermill notebook draws every
# figure and writes the paper's other tables.  Outputs differ per paper (its declared
# figures/tables), so the rules are made per paper.

VALIDATE_CORE = ["__init__.py", "cli.py", "config.py", "units.py", "io.py", "validation.py"]

for _paper in [p for p in PAPERS if migrated(p)]:

    rule:
        name:
            f"validate_{_paper}"
        input:
            runs=runs_of(_paper, variants=True),
            studies=studies_of(_paper, variants=True),
            config=str(BASE / f"config/papers/{_paper}.yaml"),
            code=code(*VALIDATE_CORE, f"models/{_paper}"),
        output:
            table=f"{RESULTS}/{_paper}/tables/validation.csv",
            claim=f"{RESULTS}/{_paper}/claim.json",
        params:
            paper=_paper,
        log:
            f"{RESULTS}/{_paper}/logs/validate.log",
        shell:
            "PYTHONPATH={SRC} {PY} -m mechrepro.cli validate {params.paper} {RESULTS} "
            "{input.config} {PROFILE} > {log} 2>&1"


NOTEBOOK_CORE = ["__init__.py", "config.py", "units.py", "io.py", "results.py",
                 "validation.py", "accuracy.py", "plotting.py", "notebook.py"]

for _paper in PAPERS:

    rule:
        name:
            f"notebook_{_paper}"
        input:
            runs=runs_of(_paper),
            studies=studies_of(_paper),
            validation=[f"{RESULTS}/{_paper}/tables/validation.csv"] if migrated(_paper) else [],
            source=str(BASE / f"notebooks/{_paper}.py"),
            config=str(BASE / f"config/papers/{_paper}.yaml"),
            code=code(*NOTEBOOK_CORE, f"models/{_paper}"),
        output:
            notebook=f"{RESULTS}/{_paper}/notebook.ipynb",
            figures=figures_of(_paper),
            tables=tables_of(_paper, notebook_only=True),
            # every paper's cost of accuracy, for the cross-paper summary
            cost_of_accuracy=f"{RESULTS}/{_paper}/tables/cost_of_accuracy.nc",
            claim=[] if migrated(_paper) else [f"{RESULTS}/{_paper}/claim.json"],
        params:
            paper=_paper,
        log:
            f"{RESULTS}/{_paper}/logs/notebook.log",
        benchmark:
            f"{RESULTS}/{_paper}/benchmarks/notebook.tsv"
        shell:
            "PYTHONPATH={SRC} {PY} -m mechrepro.notebook {params.paper} {input.source} "
            "{output.notebook} {RESULTS} {input.config} {PROFILE} > {log} 2>&1"
