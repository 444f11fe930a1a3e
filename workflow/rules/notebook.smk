# Per paper: `validate_<paper>` builds the validation table and the replication claim from
# the `reported:` block (baseline and variant runs); the papermill notebook draws every
# figure and writes the paper's other tables.  Outputs differ per paper (its declared
# figures/tables), so the rules are made per paper.

for _paper in PAPERS:
    _J = job(f"validate_{_paper}",
             runs_of(_paper, variants=True) + studies_of(_paper, variants=True),
             [f"{RESULTS}/{_paper}/tables/{t}.csv" for t in CFG[_paper].framework_tables]
             + [f"{RESULTS}/{_paper}/claim.json"],
             # the cost table made job_time.csv's estimates (mechrepro.limits.COSTS)
             config=[paper_config(_paper), BASE / "config/costs.csv"],
             code=code(*VALIDATE_CORE, f"models/{_paper}"))

    rule:
        name:
            _J.rule
        input:
            runs=runs_of(_paper, variants=True),
            studies=studies_of(_paper, variants=True),
        # update(): a failing job gets its last good outputs back from Snakemake instead
        # of losing them (as the solve jobs); it reruns until what made them is current
        output:
            table=update(f"{RESULTS}/{_paper}/tables/validation.csv"),
            claim=update(f"{RESULTS}/{_paper}/claim.json"),
            # the framework's cost tables (mechrepro.accuracy, mechrepro.costs)
            costs=[update(f"{RESULTS}/{_paper}/tables/{t}.csv")
                   for t in CFG[_paper].framework_tables if t != "validation"],
        params:
            paper=_paper,
            python=RUN["python"],
            results=lambda wc, output: str(Path(output.table).parents[2]),
            profile=RUN["profile"],
            config=paper_config(_paper),
            made_by=_J.env,
        log:
            f"{RESULTS}/{_paper}/logs/validate.log",
        benchmark:
            f"{RESULTS}/{_paper}/benchmarks/validate.tsv"
        # after every solve, except a quick paper's (limits.priorities)
        priority: PRIORITY[_paper, "validate"]
        shell:
            "{params.made_by} MECHREPRO_INPUTS='{input}' MECHREPRO_RESULTS={params.results} "
            "{params.python} -m mechrepro.cli validate {params.paper} "
            "{params.results} {params.config} {params.profile} > {log} 2>&1"


for _paper in PAPERS:
    _J = job(f"notebook_{_paper}",
             runs_of(_paper) + studies_of(_paper)
             + [f"{RESULTS}/{_paper}/tables/{t}.csv" for t in CFG[_paper].framework_tables],
             [f"{RESULTS}/{_paper}/notebook.ipynb"] + figures_of(_paper)
             + tables_of(_paper, notebook_only=True),
             source=[BASE / f"notebooks/{_paper}.py"], config=[paper_config(_paper)],
             code=code(*NOTEBOOK_CORE, f"models/{_paper}"))

    rule:
        name:
            _J.rule
        input:
            _J.inputs,
        output:
            notebook=update(f"{RESULTS}/{_paper}/notebook.ipynb"),
            figures=[update(f) for f in figures_of(_paper)],
            tables=[update(f) for f in tables_of(_paper, notebook_only=True)],
        params:
            paper=_paper,
            python=RUN["python"],
            results=lambda wc, output: str(Path(output.notebook).parents[1]),
            profile=RUN["profile"],
            source=str(BASE / f"notebooks/{_paper}.py"),
            config=paper_config(_paper),
            made_by=_J.env,
        log:
            f"{RESULTS}/{_paper}/logs/notebook.log",
        benchmark:
            f"{RESULTS}/{_paper}/benchmarks/notebook.tsv"
        priority: PRIORITY[_paper, "notebook"]
        shell:
            "{params.made_by} MECHREPRO_INPUTS='{input}' MECHREPRO_RESULTS={params.results} "
            "{params.python} -m mechrepro.notebook {params.paper} {params.source} "
            "{output.notebook} {params.results} {params.config} {params.profile} > {log} 2>&1"
