"""The saved rerun plan names every job and classifies why it runs."""
from mechrepro.plan import parse, to_html

DRY_RUN = """Building DAG of jobs...
rule run_params:
    output: results/saw_chain/params/speed_12000.json
    reason: Params have changed since last execution: ...
    wildcards: paper=saw_chain, run=speed_12000
rule solve:
    reason: Updated input files: src/mechrepro/models/saw_chain/solver.py
    wildcards: paper=saw_chain, run=fig07_fig08
rule notebook_saw_chain:
    reason: Missing output files: results/saw_chain/notebook.ipynb
localrule all:
    reason: Input files updated by another job: results/report/index.html
"""


def test_parse_classifies_reasons():
    jobs = parse(DRY_RUN)
    assert [(j["rule"], j["kind"]) for j in jobs] == [
        ("run_params", "params changed"), ("solve", "input changed"),
        ("notebook_saw_chain", "missing output"), ("all", "upstream job reruns")]
    assert jobs[1]["wildcards"] == "paper=saw_chain, run=fig07_fig08"
    page = to_html(jobs)
    assert "3 jobs" in page and "params changed" in page


def test_empty_plan_says_nothing_to_do():
    assert "Nothing to be done" in to_html(parse("Building DAG of jobs...\nNothing to be done."))
