# Report page, result archive with manifest, and the drift check against the reference.


_CONFIGS = [paper_config(p) for p in PAPERS]
# `accuracy:` is optional: a paper without it has no curve here
_S = job("summary", [f"{RESULTS}/{p}/tables/cost_of_accuracy.csv" for p in PAPERS
                     if CFG[p].raw.get("accuracy")],
         [f"{REPORT}/cost_of_accuracy_all.png", f"{REPORT}/summary.csv"], config=_CONFIGS,
         code=code("cli.py", "summary.py", "config.py", "plotting.py", "validation.py"))


rule summary:
    input:
        _S.inputs,
    output:
        png=f"{REPORT}/cost_of_accuracy_all.png",
        csv=f"{REPORT}/summary.csv",
    params:
        papers=PAPERS,
        profile=PROFILE,
        python=RUN["python"],
        results=lambda wc, output: str(Path(output[0]).parents[1]),
        base=RUN["base"],
        made_by=_S.env,
    log:
        f"{RESULTS}/logs/summary{_TAG}.log",
    benchmark:
        f"{RESULTS}/benchmarks/summary{_TAG}.tsv"
    priority: PRIORITY["all", "summary"]
    shell:
        "{params.made_by} MECHREPRO_INPUTS='{input}' MECHREPRO_RESULTS={params.results} "
        "{params.python} -m mechrepro.cli summary {output.png} {output.csv} {params.results} "
        "{params.base}/config {params.profile} {params.papers} > {log} 2>&1"


# both profiles' references: their verdicts must agree (reference.profiles_agree); a
# missing one fails the check (an unchecked paper is never archived)
_C = job("reference_check", [f"{RESULTS}/{p}/tables/validation.csv" for p in PAPERS],
         [f"{REPORT}/reference_check.txt"], config=_CONFIGS,
         reference=[f for p in PAPERS for prof in sorted({PROFILE, "ci", "default"})
                    for f in [BASE / "results/reference" / prof / f"{p}.csv"] if f.exists()],
         code=code("cli.py", "reference.py", "validation.py"))


rule reference_check:
    input:
        _C.inputs,
    output:
        f"{REPORT}/reference_check.txt",
    params:
        papers=PAPERS,
        profile=PROFILE,
        python=RUN["python"],
        results=lambda wc, output: str(Path(output[0]).parents[1]),
        base=RUN["base"],
        made_by=_C.env,
    log:
        f"{RESULTS}/logs/reference_check{_TAG}.log",
    benchmark:
        f"{RESULTS}/benchmarks/reference_check{_TAG}.tsv"
    priority: PRIORITY["all", "reference_check"]
    shell:
        "{params.made_by} MECHREPRO_INPUTS='{input}' MECHREPRO_RESULTS={params.results} "
        "{params.python} -m mechrepro.cli check-reference {output} {params.results} "
        "{params.base}/results/reference {params.profile} {params.papers} > {log} 2>&1"


_R = job("report", _S.outputs + _C.outputs + [f for p in PAPERS for f in figures_of(p)]
         + [f for p in PAPERS for f in tables_of(p)]
         + expand(f"{RESULTS}/{{paper}}/claim.json", paper=PAPERS),
         [f"{REPORT}/index.html"], config=_CONFIGS,
         code=code("cli.py", "report.py", "templates/report.html.j2", "config.py",
                   "validation.py", "costs.py"))


rule report:
    input:
        _R.inputs,
    output:
        f"{REPORT}/index.html",
    params:
        papers=PAPERS,
        profile=PROFILE,
        python=RUN["python"],
        results=lambda wc, output: str(Path(output[0]).parents[1]),
        base=RUN["base"],
        made_by=_R.env,
    log:
        f"{RESULTS}/logs/report{_TAG}.log",
    benchmark:
        f"{RESULTS}/benchmarks/report{_TAG}.tsv"
    shell:
        "{params.made_by} MECHREPRO_INPUTS='{input}' MECHREPRO_RESULTS={params.results} "
        "{params.python} -m mechrepro.cli report {output} {params.results} {params.base}/config "
        "{params.profile} {params.papers} > {log} 2>&1"


# Only results that passed the reference check of every selected paper are archived.  The
# outputs are `update()`: Snakemake neither removes them before the job nor keeps a failed
# job's version; it restores the last good archive and manifest when the check refuses.
_A = job("archive", _C.outputs + archived_outputs(),
         [f"{ARCHIVE}/manifest.json", f"{ARCHIVE}/mechrepro-results.tar.gz"],
         config=_CONFIGS, code=code("cli.py", "archive.py", "config.py"))


rule archive:
    input:
        check=rules.reference_check.output,
        files=archived_outputs(),
    output:
        manifest=update(f"{ARCHIVE}/manifest.json"),
        archive=update(f"{ARCHIVE}/mechrepro-results.tar.gz"),
    params:
        papers=PAPERS,
        profile=PROFILE,
        python=RUN["python"],
        results=lambda wc, output: str(Path(output.manifest).parents[1]),
        base=RUN["base"],
        made_by=_A.env,
        jobs=JOB_TABLE,
    log:
        f"{RESULTS}/logs/archive{_TAG}.log",
    benchmark:
        f"{RESULTS}/benchmarks/archive{_TAG}.tsv"
    shell:
        # the inputs are named once, by --files (the digest of their contents is taken
        # by the job: mechrepro.archive)
        "{params.made_by} MECHREPRO_RESULTS={params.results} {params.python} -m mechrepro.cli "
        "archive {output.archive} {output.manifest} {input.check} {params.results} "
        "{params.base}/config {params.profile} {params.papers} --jobs {params.jobs} "
        "--files {input.files} > {log} 2>&1 || {{ cat {log} >&2; exit 1; }}"
