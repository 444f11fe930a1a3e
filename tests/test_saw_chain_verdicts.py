"""saw_chain (issue 63): what a verdict and the accuracy target compare with, and how the
load minimum's error bar is made."""
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from mechrepro.config import load_paper
from mechrepro.solve import run_solver

ROOT = Path(__file__).resolve().parents[1]
CONFIG = ROOT / "config" / "papers" / "saw_chain.yaml"


@pytest.mark.parametrize("profile", ["ci", "default"])
def test_the_accuracy_target_is_compared_with_the_paper_scenes_setting(profile):
    """The target's "fixed default" was its own first level, K = 30 (29.8 N off): a straw
    man.  It is the paper scene's K (fig07_fig08: 1000, ci 300), 0.93 N off at 1000, which
    the target beats in accuracy (0.08 N) at a quarter of the K."""
    cfg = load_paper(CONFIG, profile)
    run = cfg.runs["load_max_target"]
    K_paper = cfg.runs["fig07_fig08"]["resolution"]["K"]
    assert run["target"]["default"] == K_paper
    ds = run_solver({**run, "options": {**run.get("options", {}), "timing_min_s": 0.0}})
    assert int(ds["target_default_value"]) == K_paper
    exact = float(ds["dynamic_load_x_exact"].max())
    plain = run_solver({**run, "target": None, "resolution": {"K": K_paper},
                        "options": {**run.get("options", {}), "timing_min_s": 0.0}})
    default_error = abs(float(plain["dynamic_load_x"].max()) - exact)
    assert float(ds["target_default_error"]) == pytest.approx(default_error, rel=1e-12)
    assert default_error > float(ds["target_requested"]) > float(ds["target_verified_error"])
    # the estimate of the default's error bounds it (triangle through the delivered value)
    assert float(ds["target_default_estimated_error"]) >= default_error
    if profile == "default":
        assert default_error == pytest.approx(0.93, abs=0.01)


PAPERS = ["saw_chain", "rolling_shear", "joint_wear", "disk_tension", "chain_drive"]


def test_the_report_shows_the_accuracy_target_table_of_every_paper_that_has_one(tmp_path):
    """Issue 63: ``tables/accuracy_targets.csv`` was in no report.  Every paper with a scene
    that asks for an accuracy (``target:``) shows it, with the fixed setting compared with."""
    import json

    from mechrepro.accuracy import TARGET_COLUMNS
    from mechrepro.report import paper_view
    from mechrepro.validation import COLUMNS

    results = tmp_path / "results"
    for paper in PAPERS:
        cfg = load_paper(ROOT / "config" / "papers" / f"{paper}.yaml", "ci")
        targets = [r for r, run in cfg.runs.items() if run.get("target")]
        assert targets, paper                     # every paper has one today
        tables = results / paper / "tables"
        tables.mkdir(parents=True)
        (tables / "validation.csv").write_text(",".join(COLUMNS) + "\n")
        (results / paper / "claim.json").write_text(json.dumps(
            {"claim": "partial", "independent": {"pass": 0, "fail": 0}}))
        (tables / "accuracy_targets.csv").write_text(
            ",".join(TARGET_COLUMNS) + "\n" + "\n".join(
                ",".join(targets[0] if c == "run" else "1.5" for c in TARGET_COLUMNS)
                for _ in targets) + "\n")
        view = paper_view(paper, results, ROOT / "config", "ci", tmp_path / "report")
        shown = [t for t in view["tables"] if t["title"].startswith("Accuracy asked for")]
        assert len(shown) == 1, (paper, [t["title"] for t in view["tables"]])
        assert shown[0]["rows"][0][0] == targets[0]
        assert "default_knob_value" in " ".join(shown[0]["head"])


class _Runs:
    """What an extraction function reads (``R.run``, ``R.paper_value``), from solves at K."""

    def __init__(self, cfg, K):
        self.cfg, self.K = cfg, K

    def run(self, name):
        from mechrepro.io import provenance_attrs
        from mechrepro.solve import solve

        run = {**self.cfg.runs[name], "resolution": {"K": self.K}}
        return solve(run).assign_attrs(provenance_attrs(run))

    def paper_value(self, q):
        return float(self.cfg.reported[q]["value"])


def exact_load_minimum():
    """The exact minimum of the load, located on the closed form (Eqs. 7-10 differentiated,
    independent of any K grid): -73.66676 N, 0.3355 of the way through stage 2."""
    from scipy.optimize import minimize_scalar

    from mechrepro.models.saw_chain.kinematics import stage_derivatives
    from mechrepro.models.saw_chain.loads import dynamic_load
    from mechrepro.models.saw_chain.solver import chain_from_run

    ch = chain_from_run(load_paper(CONFIG, "ci").runs["fig07_fig08"])
    out = []
    for L, m, phi in ch.stages():
        def F(ph, L=L, m=m):
            d = stage_derivatives(np.float64(ph), ch.R, L, ch.omega)
            return float(dynamic_load(m, d["mid_ax"], d["mid_ay"], ch.m_tight, d["trail_ax"])[0])
        res = minimize_scalar(F, bounds=(0.0, float(phi[-1])), method="bounded",
                              options={"xatol": 1e-13})
        out.append(res.fun)
    return min(out)


@pytest.mark.parametrize("K", [300, 1000, 1200, 2000])
def test_the_load_minimum_error_bar_covers_its_true_error(K):
    """Issue 63: at K = 1000 the error bar of dynamic_load_min was 1.35e-4 N, its true error
    2.53e-4 N.  The minimum is interior, between samples: read as the lowest sample, it
    carries a grid-phase error F''(t*) delta^2 / 2 (delta the distance from the exact
    minimum to the nearest sample), and delta / dt = frac(0.3355 K) jumps from level to level
    (0.13, 0.26, 0.48 at K = 250, 500, 1000), so the levels' differences follow no power law
    and Richardson under-estimated.  Read at the vertex of the parabola through the lowest
    sample and its neighbours, the minimum is smooth in K (second order) and the framework's
    estimate from the three levels (K/4, K/2, K) covers the true error, within 10 %."""
    from mechrepro.models.saw_chain.validation import load_range
    from mechrepro.validation import NEGLIGIBLE, level_error

    cfg = load_paper(CONFIG, "ci")
    q = [load_range(_Runs(cfg, k))["dynamic_load_min"].value for k in (K // 4, K // 2, K)]
    width = abs(cfg.reported["dynamic_load_min"]["value"]) * cfg.reported["dynamic_load_min"]["tolerance"]
    est, order, converged, how = level_error(q[0], q[1], q[2], 2.0, width)
    true = abs(q[2] - exact_load_minimum())
    assert converged and est >= 0.9 * true, (K, q, est, true, how)
    # and does not hide it under a wide bar: at most 3x, or the levels' spread where they
    # agree within the framework's negligible floor (1e-3 of the band; K = 2000 here)
    assert est <= max(3 * true, NEGLIGIBLE * width), (K, est, true, how)


def test_text_about_the_paper_numbers_comes_from_the_run():
    """Issue 63's stale text: the implied textbook mass "matches none of the paper's masses"
    while 62.69 g is 2.8 % from M m_L (now the run names the nearest and its distance); the
    notebook said the pair-chord reading "reproduces both ends" (its maximum 14.760 rounds to
    14.76, not 14.77: now printed from the run) and that verdicts are re-checked "at 2K" (they
    are re-checked one and two levels coarser)."""
    from mechrepro.models.saw_chain.validation import textbook_range

    cfg = load_paper(CONFIG, "ci")
    assert "none of" not in cfg.reported["textbook_implied_mass"]["note"]
    r = textbook_range(_Runs(cfg, 300))["textbook_implied_mass"]
    assert r.value == pytest.approx(62.69, abs=0.01)
    assert "nearest of the paper's masses: M m_L = 60.99 g, +2.8%" in r.note, r.note
    # the notebook's text and its figures (drawn by models/saw_chain/figures.py)
    nb = ((ROOT / "notebooks" / "saw_chain.py").read_text()
          + (ROOT / "src" / "mechrepro" / "models" / "saw_chain" / "figures.py").read_text())
    for stale in ("reproduces both ends", "re-checked at 2K", "matches none"):
        assert stale not in nb, stale
    # Fig. 7 prints the preferred explanation's band beside the paper's from the run
    assert "rounds to" in nb and "preferred explanation" in nb
