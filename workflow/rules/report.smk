# Report page, result archive with manifest, and the drift check against the reference.


rule summary:
    input:
        coa=expand(f"{RESULTS}/{{paper}}/tables/cost_of_accuracy.csv", paper=PAPERS),
        configs=[paper_config(p) for p in PAPERS],
        code=code("cli.py", "summary.py", "config.py", "plotting.py", "validation.py"),
    output:
        png=f"{RESULTS}/report/cost_of_accuracy_all.png",
        csv=f"{RESULTS}/report/summary.csv",
    params:
        papers=PAPERS,
        profile=PROFILE,
        python=RUN["python"],
        results=lambda wc, output: str(Path(output[0]).parents[1]),
        base=RUN["base"],
    log:
        f"{RESULTS}/logs/summary.log",
    benchmark:
        f"{RESULTS}/benchmarks/summary.tsv"
    shell:
        "{params.python} -m mechrepro.cli summary {output.png} {output.csv} {params.results} "
        "{params.base}/config {params.profile} {params.papers} > {log} 2>&1"


rule reference_check:
    input:
        tables=expand(f"{RESULTS}/{{paper}}/tables/validation.csv", paper=PAPERS),
        reference=[str(f) for p in PAPERS
                   for f in [BASE / "results/reference" / PROFILE / f"{p}.csv"] if f.exists()],
        code=code("cli.py", "reference.py", "validation.py"),
    output:
        f"{RESULTS}/report/reference_check.txt",
    params:
        papers=PAPERS,
        profile=PROFILE,
        python=RUN["python"],
        results=lambda wc, output: str(Path(output[0]).parents[1]),
        base=RUN["base"],
    log:
        f"{RESULTS}/logs/reference_check.log",
    benchmark:
        f"{RESULTS}/benchmarks/reference_check.tsv"
    shell:
        "{params.python} -m mechrepro.cli check-reference {output} {params.results} "
        "{params.base}/results/reference {params.profile} {params.papers} > {log} 2>&1"


rule report:
    input:
        summary=rules.summary.output,
        check=rules.reference_check.output,
        figures=[f for p in PAPERS for f in figures_of(p)],
        tables=[f for p in PAPERS for f in tables_of(p)],
        claims=expand(f"{RESULTS}/{{paper}}/claim.json", paper=PAPERS),
        configs=[paper_config(p) for p in PAPERS],
        code=code("cli.py", "report.py", "templates/report.html.j2", "config.py", "validation.py", "costs.py"),
    output:
        f"{RESULTS}/report/index.html",
    params:
        papers=PAPERS,
        profile=PROFILE,
        python=RUN["python"],
        results=lambda wc, output: str(Path(output[0]).parents[1]),
        base=RUN["base"],
    log:
        f"{RESULTS}/logs/report.log",
    benchmark:
        f"{RESULTS}/benchmarks/report.tsv"
    shell:
        "{params.python} -m mechrepro.cli report {output} {params.results} {params.base}/config "
        "{params.profile} {params.papers} > {log} 2>&1"


# Only results that passed the reference check are archived (the job fails otherwise).
rule archive:
    input:
        report=f"{RESULTS}/report/index.html",
        check=rules.reference_check.output,
        notebooks=expand(f"{RESULTS}/{{paper}}/notebook.ipynb", paper=PAPERS),
        runs=[f for p in PAPERS for f in runs_of(p, variants=True)],
        studies=[f for p in PAPERS for f in studies_of(p, variants=True)],
        configs=[paper_config(p) for p in PAPERS],
        code=code("cli.py", "archive.py", "config.py"),
    output:
        manifest=f"{RESULTS}/archive/manifest.json",
        archive=f"{RESULTS}/archive/mechrepro-results.tar.gz",
    params:
        papers=PAPERS,
        profile=PROFILE,
        python=RUN["python"],
        results=lambda wc, output: str(Path(output[0]).parents[1]),
        base=RUN["base"],
    log:
        f"{RESULTS}/logs/archive.log",
    benchmark:
        f"{RESULTS}/benchmarks/archive.tsv"
    shell:
        "{params.python} -m mechrepro.cli archive {output.archive} {output.manifest} "
        "{params.results} {params.base}/config {params.profile} {params.papers} > {log} 2>&1 "
        "|| {{ cat {log} >&2; exit 1; }}"
