# Parameter generation: each scene and each study point becomes one params file.
# The run record is passed as a plain dict, so Snakemake's params trigger reruns exactly
# the runs whose resolved parameters changed, and no other.


rule run_params:
    output:
        f"{RESULTS}/{{paper}}/params/{{run}}.json",
    params:
        run=lambda wc: CFG[wc.paper].runs[wc.run],
    run:
        from mechrepro.io import write_json

        write_json(output[0], params.run)
