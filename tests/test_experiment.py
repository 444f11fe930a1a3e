"""What-if experiments, diffs and restore (src/mechrepro/experiment.py) on the ci pipeline."""
import json
import shutil

import pytest

from conftest import copy_workflow, snakemake
from mechrepro.config import ConfigError
from mechrepro.experiment import diff, parse_sets, prepare, restore, run

pytestmark = pytest.mark.slow


def test_the_diff_of_a_result_set_with_itself_is_empty(workflow):
    work, _ = workflow
    assert diff(work / "results", work / "results", work / "results" / "reference", "ci")["papers"] == {}


def test_an_override_reruns_its_paper_only_and_the_diff_shows_what_moved(workflow, tmp_path):
    work, _ = workflow
    base = tmp_path / "project"
    shutil.copytree(work, base, symlinks=True, ignore=shutil.ignore_patterns(".snakemake"))
    rec = run("faster", ["saw_chain.sprocket_speed=7000"], base=base, profile="ci")
    assert rec["status"] == "done", (base / "experiments/faster/snakemake.log").read_text()[-3000:]
    # only saw_chain is solved, validated and drawn again; the other papers are reused
    solved = {j for j in rec["jobs"] if j.startswith(("solve_", "validate_", "notebook_"))}
    assert solved == {"solve_saw_chain__batch", "validate_saw_chain", "notebook_saw_chain"}
    d = diff(base / "results", base / "experiments/faster/results", base / "results/reference", "ci")
    assert set(d["papers"]) == {"saw_chain"}
    sc = d["papers"]["saw_chain"]
    assert sc["parameters"]["sprocket_speed"][1] == pytest.approx(7000 * 2 * 3.141592653589793 / 60)
    moved = {r["quantity"] for r in sc["rows"]}
    # loads scale with speed squared, velocities with speed; the K-study's order does not move
    assert {"dynamic_load_max", "dynamic_load_min", "tight_side_velocity_max"} <= moved
    assert "observed_order_load" not in moved
    assert "fig07.png" in sc["figures_changed"] and "fig08.png" in sc["figures_changed"]
    # the baseline is untouched
    assert json.loads((base / "results/saw_chain/claim.json").read_text()) == \
        json.loads((work / "results/saw_chain/claim.json").read_text())


def test_an_invalid_override_is_refused_before_any_job(workflow, tmp_path):
    work, _ = workflow
    for sets, message in ((["saw_chain.tie_strap_pitch=-8.91"], "tie_strap_pitch"),
                          (["saw_chain.no_such=1"], "not a parameter"),
                          (["nopaper.x=1"], "no paper"), (["saw_chain=1"], "PAPER.PARAMETER")):
        with pytest.raises(ConfigError, match=message):
            prepare("bad", sets, base=work, profile="ci")
        assert not (work / "experiments" / "bad").exists()
    assert parse_sets(["a.b.c=[1, 2]"]) == {"a": {"b.c": [1, 2]}}


def test_restore_into_a_fresh_checkout_schedules_nothing(workflow, tmp_path):
    work, _ = workflow
    (tmp_path / "fresh").mkdir()
    fresh = copy_workflow(tmp_path / "fresh")
    n = restore(work / "results/archive/mechrepro-results.tar.gz", fresh)
    assert n > 100
    out = snakemake(fresh, "-n")
    assert "Nothing to be done" in out, out[-2000:]
    with pytest.raises(ValueError, match="would overwrite"):
        restore(work / "results/archive/mechrepro-results.tar.gz", fresh)
