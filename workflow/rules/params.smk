# Parameter generation: each scene and each study point becomes one params file.
# The run record is passed as a plain JSON string, so Snakemake's params trigger reruns
# exactly the runs whose resolved parameters changed, and no other.  A shell rule (no
# Python start-up, no workflow re-parse) written through a temporary file.
import json


def run_json(wc):
    return json.dumps(CFG[wc.paper].runs[wc.run], indent=2, sort_keys=True)


rule run_params:
    output:
        f"{RESULTS}/{{paper}}/params/{{run}}.json",
    params:
        run=run_json,
    shell:
        "printf '%s\\n' {params.run:q} > {output}.part && mv {output}.part {output}"
