# Solver jobs, and gather, which stacks the runs of a fanned-out study into one dataset.
#
# Job granularity follows cost, as each paper's config declares it (PaperConfig.solve_jobs):
# every cheap run of a paper (scenes, study points, their verdict variants) is solved in one
# `batch` job, paying the interpreter start and the imports once, and that job stacks its
# studies itself; a scene or study under `alone:` gets a job of its own; a study under
# `fan_out:` one job per run, so they spread over cores and cluster nodes.  The run records
# are the job's params: a changed record reruns exactly the job that solves it.

for _paper in PAPERS:
    for _job, _runs in solve_jobs(_paper).items():

        rule:
            name:
                f"solve_{_paper}__{_job}"
            # not the paper's config file: the run records below are (as params), so an
            # edit of one scene reruns exactly the jobs whose records it changes
            input:
                code=model_code(_paper),
            # update(): Snakemake does not remove the last results before the job and
            # restores them if it fails, so a failing job (a solver's refusal, a crash)
            # never loses its siblings' good results; they are rerun when their
            # records change, as before
            output:
                runs=[update(f"{RESULTS}/{_paper}/runs/{r}.nc") for r in _runs],
                studies=[update(f"{RESULTS}/{_paper}/studies/{s}.nc")
                         for s in CFG[_paper].studies_solved_with(_runs)],
            params:
                python=RUN["python"],
                paper=_paper,
                profile=PROFILE,
                base=RUN["base"],
                results=lambda wc, output: str(Path(output.runs[0]).parents[2]),
                runs=" ".join(_runs),
                # the resolved run records: Snakemake's params trigger reruns this job
                # when one of them changes, and only then
                records=records_of(_paper, _runs),
            log:
                f"{RESULTS}/{_paper}/logs/solve/{_job}.log",
            benchmark:
                f"{RESULTS}/{_paper}/benchmarks/solve__{_job}.tsv"
            # the rule's declared memory and time (mechrepro.limits), or the job's estimate
            # when a run above them was allowed on purpose (--config over_budget=true)
            resources:
                **job_resources(CFG[_paper], _job, OVER_BUDGET),
            # a paper estimated to solve in seconds (limits.quick_paper) first of all (the
            # first figures appear early), then the longest estimated solve, then the
            # validations, the summary and reference check (validation tables only), the
            # notebooks, and the report and archive last: limits.priorities; results do
            # not depend on the order
            priority: PRIORITY[_paper, _job]
            shell:
                "{params.python} -m mechrepro.solve {params.paper} {params.base}/config "
                "{params.profile} {params.results} {params.runs} > {log} 2>&1"


rule gather:
    input:
        runs=lambda wc: expand(f"{RESULTS}/{wc.paper}/runs/{{run}}.nc",
                               run=CFG[wc.paper].studies[wc.study]),
        code=code("io.py", "cli.py"),
    output:
        f"{RESULTS}/{{paper}}/studies/{{study}}.nc",
    wildcard_constraints:
        study=fanned_out_studies(),
    params:
        python=RUN["python"],
    log:
        f"{RESULTS}/{{paper}}/logs/gather/{{study}}.log",
    benchmark:
        f"{RESULTS}/{{paper}}/benchmarks/gather__{{study}}.tsv"
    shell:
        "{params.python} -m mechrepro.cli gather {output} {input.runs} > {log} 2>&1"
