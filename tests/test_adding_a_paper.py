"""docs/ADDING_A_PAPER.md followed literally: a toy paper (tests/toy_paper/: one solver, two
effects, one figure, one reported number with its rival) added to a copy of the
workflow by its own new files only, then its references made and the pipeline run to the
report, as the document says."""
import json
import shutil
import subprocess
import sys

import pytest

from conftest import ROOT, copy_workflow

TOY = ROOT / "tests" / "toy_paper"



def test_a_new_paper_is_small():
    """What a one-figure paper costs its author: at most 4 files, 10 top-level keys in its
    YAML and 6 framework names imported by its code."""
    import ast

    import yaml

    files = [p for p in TOY.rglob("*") if p.is_file() and "__pycache__" not in p.parts]
    assert len(files) <= 4, [str(p.relative_to(TOY)) for p in files]
    raw = yaml.safe_load((TOY / "config" / "papers" / "toy.yaml").read_text())
    assert len(raw) <= 10, list(raw)
    names = {(node.module, a.name) for p in files if p.suffix == ".py"
             for node in ast.walk(ast.parse(p.read_text()))
             if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("mechrepro")
             for a in node.names}
    assert len(names) <= 6, sorted(names)


@pytest.mark.slow
def test_a_new_paper_needs_only_its_own_files(tmp_path):
    work = copy_workflow(tmp_path)
    for src in sorted(p for p in TOY.rglob("*") if p.is_file() and "__pycache__" not in p.parts):
        dst = work / src.relative_to(TOY)
        assert not dst.exists(), f"{dst.relative_to(work)}: the toy would edit a shared file"
        dst.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(src, dst)

    def run(*cmd):
        proc = subprocess.run([sys.executable, *cmd], cwd=work, capture_output=True, text=True,
                              timeout=900)
        assert proc.returncode == 0, f"{' '.join(cmd)}:\n{proc.stdout[-3000:]}\n{proc.stderr[-3000:]}"

    # "Then `make reference REF_PAPERS=<id>`" (both profiles: the report compares either)
    for profile in ("ci", "default"):
        run("-m", "mechrepro.reference", profile, f"ref-{profile}", "--papers", "toy",
            "--variants", "native")
    # "Try it"
    run("-m", "snakemake", "--cores", "2", "--config", "papers=[toy]", "profile=ci",
        "results=out")

    out = work / "out"
    assert (out / "toy" / "figures" / "fig01.png").stat().st_size > 0
    assert "natural_frequency" in (out / "report-toy" / "index.html").read_text()
    claim = json.loads((out / "toy" / "claim.json").read_text())
    assert claim["independent"]["pass"] == 1 and claim["claim"] == "full", claim
    evidence = (out / "toy" / "tables" / "verdict_evidence.csv").read_text()
    assert "rival-stiffer_spring" in evidence and ",fail" in evidence
