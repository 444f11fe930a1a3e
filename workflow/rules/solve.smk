# Solver jobs, and gather, which stacks the runs of a fanned-out study into one dataset.
#
# Job granularity follows cost, as each paper's config declares it (PaperConfig.solve_jobs):
# every cheap run of a paper (scenes, study points, their verdict variants) is solved in one
# `batch` job, paying the interpreter start and the imports once, and that job stacks its
# studies itself; a scene or study under `alone:` gets a job of its own; a study under
# `fan_out:` one job per run, so they spread over cores and cluster nodes.  The run records
# are the job's params: a changed record reruns exactly the job that solves it.

for _paper in PAPERS:
    for _job, _runs in CFG[_paper].solve_jobs().items():
        _J = job(f"solve_{_paper}__{_job}", [],
                 [f"{RESULTS}/{_paper}/runs/{r}.nc" for r in _runs]
                 + [f"{RESULTS}/{_paper}/studies/{s}.nc"
                    for s in CFG[_paper].studies_solved_with(_runs)],
                 record=records_of(_paper, _runs), code=model_code(_paper))

        rule:
            name:
                _J.rule
            # update(): Snakemake does not remove the last results before the job and
            # restores them if it fails, so a failing job (a solver's refusal, a crash)
            # never loses its siblings' good results; they are rerun when what made them
            # changes, as before
            output:
                [update(f) for f in _J.outputs],
            params:
                python=RUN["python"],
                paper=_paper,
                profile=PROFILE,
                base=RUN["base"],
                results=lambda wc, output: str(Path(output[0]).parents[2]),
                runs=" ".join(_runs),
                # what made its results: the run records, code and package set (digests);
                # a changed record reruns exactly the job that solves it
                made_by=_J.env,
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
                "{params.made_by} MECHREPRO_INPUTS='{input}' MECHREPRO_RESULTS={params.results} "
                "{params.python} -m mechrepro.solve {params.paper} {params.base}/config "
                "{params.profile} {params.results} {params.runs} > {log} 2>&1"


# one gather job per fanned-out study, made by the same code
_GATHER, _FANNED = Job("gather", [], [], {"code": code("cli.py")}), fanned_out_studies()
for _paper in PAPERS:
    for _study in filter(re.compile(_FANNED).fullmatch, CFG[_paper].studies):
        job("gather", [f"{RESULTS}/{_paper}/runs/{r}.nc" for r in CFG[_paper].studies[_study]],
            [f"{RESULTS}/{_paper}/studies/{_study}.nc"], **_GATHER.sources)


rule gather:
    input:
        runs=lambda wc: expand(f"{RESULTS}/{wc.paper}/runs/{{run}}.nc",
                               run=CFG[wc.paper].studies[wc.study]),
    output:
        f"{RESULTS}/{{paper}}/studies/{{study}}.nc",
    wildcard_constraints:
        study=_FANNED,
    params:
        python=RUN["python"],
        results=lambda wc, output: str(Path(output[0]).parents[2]),
        made_by=_GATHER.env,
    log:
        f"{RESULTS}/{{paper}}/logs/gather/{{study}}.log",
    benchmark:
        f"{RESULTS}/{{paper}}/benchmarks/gather__{{study}}.tsv"
    shell:
        "{params.made_by} MECHREPRO_INPUTS='{input}' MECHREPRO_RESULTS={params.results} "
        "{params.python} -m mechrepro.cli gather {output} {input.runs} > {log} 2>&1"
