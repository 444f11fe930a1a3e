"""The report a reader sees: trust on the first screen, every paper's artefacts with their rows.

The layout checks render the page in headless Chromium (Debian's `chromium`; skipped where it
is not installed) at 1280 px and read what the page measured of itself after load
(`data-*` on <body>, set by the template's script): elements wider than the viewport, images
that did not load, internal links without a target, where the trust banner ends.
"""
import re
import shutil
import subprocess
import tarfile
from pathlib import Path

import pytest

from mechrepro.report import artefact_title, banner, claim_sentence

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")


def measured(page: Path, tmp_path: Path) -> dict[str, int]:
    """The page's own measurements at 1280 x 900 px in headless Chromium."""
    import tempfile

    profile = tempfile.mkdtemp(dir=tmp_path)   # one per start: Chromium locks its profile
    dom = subprocess.run(
        [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         f"--user-data-dir={profile}", "--window-size=1280,900", "--virtual-time-budget=20000",
         "--dump-dom", page.resolve().as_uri()],
        capture_output=True, text=True, timeout=180).stdout
    body = re.search(r"<body([^>]*)>", dom)
    assert body, f"Chromium rendered nothing of {page}"
    body = body.group(1)
    return {k: int(v) for k, v in re.findall(r'data-([a-z-]+)="(\d+)"', body)}


def check_layout(page: Path, tmp_path: Path) -> None:
    m = measured(page, tmp_path)
    assert m["overflow"] == 0, "elements wider than the 1280 px viewport"
    assert m["broken-images"] == 0
    assert m["broken-links"] == 0
    assert m["banner-bottom"] <= 900, "the trust banner does not fit the first screen"


@pytest.mark.slow
@pytest.mark.skipif(CHROMIUM is None, reason="needs Debian's chromium")
def test_report_and_archived_report_render_at_1280px(workflow, tmp_path):
    work, _ = workflow
    res = work / "results"
    check_layout(res / "report" / "index.html", tmp_path)
    with tarfile.open(res / "archive" / "mechrepro-results.tar.gz") as tar:
        tar.extractall(tmp_path / "x", filter="data")
    pages = list((tmp_path / "x").rglob("report/index.html"))
    assert len(pages) == 1
    check_layout(pages[0], tmp_path)


@pytest.mark.parametrize("text, ok, shown", [
    ("reference check, profile ci: OK\nsaw_chain: 26 quantities within tolerance\n", True,
     "Reference check passed"),
    ("reference check, profile ci: DRIFT\nsaw_chain: DRIFT against x.csv\n"
     "  dynamic_load_max: 1 outside 2 +- 0.1\n", False, "dynamic_load_max: 1 outside"),
    ("reference check, profile ci: OK\nsaw_chain: (not checked: no reference file)\n", False,
     "not checked"),
    (None, False, "the reference check did not run"),
])
def test_the_banner_says_whether_to_trust_the_run(tmp_path, text, ok, shown):
    f = tmp_path / "reference_check.txt"
    if text is not None:
        f.write_text(text)
    b = banner(f, "ci")
    assert b["ok"] is ok
    assert shown in " ".join([b["headline"], b["detail"], *b["lines"]])


def test_the_claim_sentence_names_artefacts_not_row_ids():
    s = claim_sentence({"independent": {"pass": 2, "fail": 1, "inconclusive": 0},
                        "agree": ["fig07"], "disagree": ["table2"], "inconclusive": [],
                        "not_counted_passes": ["tight_side_velocity_fluctuation"]})
    assert s == ("2 of 3 independent checks pass; agrees on Fig. 7; disagrees on Table 2; "
                 "1 pass not counted (no falsifier that fails).")
    assert [artefact_title(a) for a in ("fig07", "fig6a", "table12", "text", "cost_of_accuracy")] == [
        "Fig. 7", "Fig. 6a", "Table 12", "Statements in the text", "cost of accuracy"]


def test_a_failed_run_marks_the_report_it_leaves_behind(tmp_path):
    from mechrepro.report import mark_stale

    page = tmp_path / "index.html"
    page.write_text('<!doctype html>\n<body>\n<header class="banner ok" id="banner">OK</header>\n</body>')
    mark_stale(page, "exit status 1; failed: solve_saw_chain__batch")
    mark_stale(page, "exit status 1; failed: validate_joint_wear")     # once, the newest
    text = page.read_text()
    assert text.count('id="stale"') == 1 and "validate_joint_wear" in text
    assert text.index('id="stale"') < text.index('id="banner"')
