"""The saved rerun plan names every job and classifies why it runs."""
from mechrepro.plan import parse, to_html

DRY_RUN = """Building DAG of jobs...
rule solve_saw_chain__batch:
    output: results/saw_chain/runs/speed_12000.nc
    reason: Params have changed since last execution: ...
rule gather:
    reason: Updated input files: results/saw_chain/runs/a-000.nc
    wildcards: paper=saw_chain, study=a
rule notebook_saw_chain:
    reason: Missing output files: results/saw_chain/notebook.ipynb
localrule all:
    reason: Input files updated by another job: results/report/index.html
"""


def test_parse_classifies_reasons():
    jobs = parse(DRY_RUN)
    assert [(j["rule"], j["kind"]) for j in jobs] == [
        ("solve_saw_chain__batch", "params changed"), ("gather", "input changed"),
        ("notebook_saw_chain", "missing output"), ("all", "upstream job reruns")]
    assert jobs[1]["wildcards"] == "paper=saw_chain, study=a"
    page = to_html(jobs)
    assert "3 jobs" in page and "params changed" in page


def test_empty_plan_says_nothing_to_do():
    assert "Nothing to be done" in to_html(parse("Building DAG of jobs...\nNothing to be done."))


def test_plan_is_read_from_the_run_log(tmp_path):
    from mechrepro.plan import main

    log = tmp_path / "run.snakemake.log"
    log.write_text(DRY_RUN)
    assert main([str(tmp_path / "results"), str(log)]) == 0
    assert "3 jobs" in (tmp_path / "results" / "rerun_plan.html").read_text()


def test_a_run_that_planned_nothing_does_not_show_an_old_plan(tmp_path):
    """A run stopped before Snakemake wrote its log (a refused config): the page says so,
    not "Nothing to be done" from the log of the run before."""
    import os

    from mechrepro.plan import main

    log = tmp_path / "old.snakemake.log"
    log.write_text("Building DAG of jobs...\nNothing to be done.")
    os.utime(log, (1000, 1000))
    assert main([str(tmp_path / "results"), str(log), "--since", "2000", "--status", "1"]) == 0
    page = (tmp_path / "results" / "rerun_plan.html").read_text()
    assert "stopped before any job was planned" in page and "Nothing to be done" not in page


def test_a_failed_run_says_it_failed(tmp_path):
    from mechrepro.plan import main

    log = tmp_path / "run.snakemake.log"
    log.write_text(DRY_RUN)
    assert main([str(tmp_path / "results"), str(log), "--status", "1"]) == 0
    assert "The run failed" in (tmp_path / "results" / "rerun_plan.html").read_text()


def test_a_reason_line_is_cut_to_counts_and_a_few_names():
    """Snakemake's reason for a validation job named every run it reads: 45,140 characters
    on one console line.  `make` shows each list's count and first names."""
    from mechrepro.plan import cap_reason

    runs = [f"results/disk_tension/runs/fig06-{i:03d}@unstated_model-c{i % 16:02d}.nc"
            for i in range(800)]
    line = ("    reason: Missing output files: results/disk_tension/tables/validation.csv; "
            f"Input files updated by another job: {', '.join(runs)}; Params have changed "
            "since last execution\n")
    assert len(line) > 45000
    short = cap_reason(line)
    assert len(short) < 400 and short.endswith("\n"), short
    assert short == ("    reason: Missing output files: results/disk_tension/tables/validation.csv; "
                     f"Input files updated by another job: 800 ({', '.join(runs[:3])}, …); "
                     "Params have changed since last execution\n")
    for other in ("    input: a, b, c, d, e\n", "rule all:\n", "    reason: Forced execution\n"):
        assert cap_reason(other) == other


def test_make_reproduce_shows_snakemakes_output_with_reasons_cut(tmp_path, monkeypatch, capfd):
    """mechrepro.reproduce passes Snakemake's console output through, line by line, with
    each reason cut (a stand-in Snakemake: the real one's reasons are in its log)."""
    from mechrepro import reproduce

    fake = tmp_path / "snakemake"      # a regular package: it shadows the installed one
    fake.mkdir()
    (fake / "__init__.py").write_text("")
    names = ", ".join(f"results/x/runs/r{i}.nc" for i in range(2000))
    (fake / "__main__.py").write_text(
        "import sys\n"
        "sys.stderr.write('rule validate_x:\\n')\n"
        f"sys.stderr.write('    reason: Updated input files: {names}\\n')\n"
        "sys.stderr.write('caf\\xe9 done\\n')\n"
        "sys.exit(3)\n")
    monkeypatch.setenv("PYTHONPATH", str(tmp_path))
    monkeypatch.chdir(tmp_path)        # no Snakefile here, whatever snakemake starts
    assert reproduce.snakemake(["--cores", "1"]) == 3
    err = capfd.readouterr().err
    assert err == ("rule validate_x:\n    reason: Updated input files: 2000 (results/x/runs/r0.nc, "
                   "results/x/runs/r1.nc, results/x/runs/r2.nc, …)\ncafé done\n"), err[:500]
