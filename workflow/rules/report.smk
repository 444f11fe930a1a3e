# Report page, result archive with manifest, and the drift check against the reference.


rule summary:
    input:
        # `accuracy:` is optional: a paper without it has no curve here
        coa=[f"{RESULTS}/{p}/tables/cost_of_accuracy.csv" for p in PAPERS
             if CFG[p].raw.get("accuracy")],
        configs=[paper_config(p) for p in PAPERS],
        code=code("cli.py", "summary.py", "config.py", "plotting.py", "validation.py"),
    output:
        png=f"{REPORT}/cost_of_accuracy_all.png",
        csv=f"{REPORT}/summary.csv",
    params:
        papers=PAPERS,
        profile=PROFILE,
        python=RUN["python"],
        results=lambda wc, output: str(Path(output[0]).parents[1]),
        base=RUN["base"],
    log:
        f"{RESULTS}/logs/summary{_TAG}.log",
    benchmark:
        f"{RESULTS}/benchmarks/summary{_TAG}.tsv"
    priority: PRIORITY["all", "summary"]
    shell:
        "{params.python} -m mechrepro.cli summary {output.png} {output.csv} {params.results} "
        "{params.base}/config {params.profile} {params.papers} > {log} 2>&1"


rule reference_check:
    input:
        tables=expand(f"{RESULTS}/{{paper}}/tables/validation.csv", paper=PAPERS),
        # both profiles' references: their verdicts must agree (reference.profiles_agree);
        # a missing one fails the check (an unchecked paper is never archived)
        reference=[str(f) for p in PAPERS for prof in sorted({PROFILE, "ci", "default"})
                   for f in [BASE / "results/reference" / prof / f"{p}.csv"] if f.exists()],
        configs=[paper_config(p) for p in PAPERS],
        code=code("cli.py", "reference.py", "validation.py"),
    output:
        f"{REPORT}/reference_check.txt",
    params:
        papers=PAPERS,
        profile=PROFILE,
        python=RUN["python"],
        results=lambda wc, output: str(Path(output[0]).parents[1]),
        base=RUN["base"],
    log:
        f"{RESULTS}/logs/reference_check{_TAG}.log",
    benchmark:
        f"{RESULTS}/benchmarks/reference_check{_TAG}.tsv"
    priority: PRIORITY["all", "reference_check"]
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
        f"{REPORT}/index.html",
    params:
        papers=PAPERS,
        profile=PROFILE,
        python=RUN["python"],
        results=lambda wc, output: str(Path(output[0]).parents[1]),
        base=RUN["base"],
    log:
        f"{RESULTS}/logs/report{_TAG}.log",
    benchmark:
        f"{RESULTS}/benchmarks/report{_TAG}.tsv"
    shell:
        "{params.python} -m mechrepro.cli report {output} {params.results} {params.base}/config "
        "{params.profile} {params.papers} > {log} 2>&1"


# Only results that passed the reference check of every selected paper are archived.  The
# outputs are `update()`: Snakemake neither removes them before the job nor keeps a failed
# job's version; it restores the last good archive and manifest when the check refuses.
rule archive:
    input:
        check=rules.reference_check.output,
        files=archived_outputs(),
        configs=[paper_config(p) for p in PAPERS],
        code=code("cli.py", "archive.py", "config.py"),
    output:
        manifest=update(f"{ARCHIVE}/manifest.json"),
        archive=update(f"{ARCHIVE}/mechrepro-results.tar.gz"),
    params:
        papers=PAPERS,
        profile=PROFILE,
        python=RUN["python"],
        results=lambda wc, output: str(Path(output.manifest).parents[1]),
        base=RUN["base"],
    log:
        f"{RESULTS}/logs/archive{_TAG}.log",
    benchmark:
        f"{RESULTS}/benchmarks/archive{_TAG}.tsv"
    shell:
        "{params.python} -m mechrepro.cli archive {output.archive} {output.manifest} {input.check} "
        "{params.results} {params.base}/config {params.profile} {params.papers} "
        "--files {input.files} > {log} 2>&1 || {{ cat {log} >&2; exit 1; }}"
