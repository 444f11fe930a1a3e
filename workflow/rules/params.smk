# Parameter generation: each scene, study point and verdict variant becomes one params file.
# The run record is passed as a plain JSON string, so Snakemake's params trigger reruns
# exactly the runs whose resolved parameters changed, and no other.  A shell rule (no
# Python start-up, no workflow re-parse) written through a temporary file.


rule run_params:
    output:
        f"{RESULTS}/{{paper}}/params/{{run}}.json",
    params:
        run=run_json,
    log:
        f"{RESULTS}/{{paper}}/logs/params/{{run}}.log",
    shell:
        "(printf '%s\\n' {params.run:q} > {output}.part && mv {output}.part {output}) > {log} 2>&1"
