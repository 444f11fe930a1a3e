# Solver jobs, and gather, which stacks a study's runs into one dataset.
#
# Job granularity follows cost: the runs of one scene or study (its points and its verdict
# variants) are solved in one job, paying the interpreter start and the imports once;
# a study a paper lists under `fan_out:` (each run costs seconds) gets one job per run,
# so they spread over cores and cluster nodes.  A changed run reruns its own job only.

for _paper in PAPERS:
    for _job, _runs in solve_jobs(_paper).items():

        rule:
            name:
                f"solve_{_paper}__{_job}"
            input:
                params=[f"{RESULTS}/{_paper}/params/{r}.json" for r in _runs],
                code=model_code(_paper),
            output:
                [f"{RESULTS}/{_paper}/runs/{r}.nc" for r in _runs],
            params:
                python=RUN["python"],
                pairs=lambda wc, input, output: " ".join(
                    f"{i} {o}" for i, o in zip(input.params, output)),
            log:
                f"{RESULTS}/{_paper}/logs/solve/{_job}.log",
            benchmark:
                f"{RESULTS}/{_paper}/benchmarks/solve__{_job}.tsv"
            resources:
                mem_mb=2000,
                runtime=30,
            shell:
                "{params.python} -m mechrepro.solve {params.pairs} > {log} 2>&1"


rule gather:
    input:
        runs=lambda wc: expand(f"{RESULTS}/{wc.paper}/runs/{{run}}.nc",
                               run=CFG[wc.paper].studies[wc.study]),
        code=code("io.py", "cli.py"),
    output:
        f"{RESULTS}/{{paper}}/studies/{{study}}.nc",
    params:
        python=RUN["python"],
    log:
        f"{RESULTS}/{{paper}}/logs/gather/{{study}}.log",
    shell:
        "{params.python} -m mechrepro.cli gather {output} {input.runs} > {log} 2>&1"
