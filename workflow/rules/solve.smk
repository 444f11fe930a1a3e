# One solver job per run; gather stacks a study's runs into one dataset.


rule solve:
    input:
        params=f"{RESULTS}/{{paper}}/params/{{run}}.json",
        code=lambda wc: model_code(wc.paper),
    output:
        f"{RESULTS}/{{paper}}/runs/{{run}}.nc",
    params:
        python=RUN["python"],
    log:
        f"{RESULTS}/{{paper}}/logs/solve/{{run}}.log",
    benchmark:
        f"{RESULTS}/{{paper}}/benchmarks/{{run}}.tsv"
    resources:
        mem_mb=2000,
        runtime=30,
    shell:
        "{params.python} -m mechrepro.solve {input.params} {output} > {log} 2>&1"


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
