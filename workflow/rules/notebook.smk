# One papermill job per paper: the notebook writes every figure and table of the paper.
# Outputs differ per paper (its declared figures/tables), so one rule is made per paper.

NOTEBOOK_CORE = ["__init__.py", "config.py", "units.py", "io.py", "results.py",
                 "validation.py", "accuracy.py", "plotting.py", "notebook.py"]

for _paper in PAPERS:

    rule:
        name:
            f"notebook_{_paper}"
        input:
            runs=runs_of(_paper),
            studies=studies_of(_paper),
            source=str(BASE / f"notebooks/{_paper}.py"),
            config=str(BASE / f"config/papers/{_paper}.yaml"),
            code=code(*NOTEBOOK_CORE, f"models/{_paper}"),
        output:
            notebook=f"{RESULTS}/{_paper}/notebook.ipynb",
            figures=figures_of(_paper),
            tables=tables_of(_paper),
            # every paper's cost of accuracy, for the cross-paper summary
            cost_of_accuracy=f"{RESULTS}/{_paper}/tables/cost_of_accuracy.nc",
            claim=f"{RESULTS}/{_paper}/claim.json",
        params:
            paper=_paper,
        log:
            f"{RESULTS}/{_paper}/logs/notebook.log",
        benchmark:
            f"{RESULTS}/{_paper}/benchmarks/notebook.tsv"
        shell:
            "PYTHONPATH={SRC} {PY} -m mechrepro.notebook {params.paper} {input.source} "
            "{output.notebook} {RESULTS} {input.config} {PROFILE} > {log} 2>&1"
