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


def test_the_claim_sentence_names_artefacts_by_their_rows_majority_with_counts():
    """A figure agrees when most of its independent rows pass, disagrees when most fail,
    else is not settled (chain_drive's Fig. 5, 12 passes and 4 fails, said "disagrees");
    info rows and other evidence classes do not vote."""
    def rows(artefact, *statuses, evidence="independent"):
        return [{"artefact": artefact, "status": s, "evidence": evidence} for s in statuses]

    r = [*rows("fig05", *["pass"] * 12, *["fail"] * 4, "info"), *rows("table2", "fail"),
         *rows("fig09", "pass", "fail"), *rows("fig10", "pass", "inconclusive", "not_converged"),
         *rows("fig07", "fail", "fail", evidence="calibration")]
    s = claim_sentence({"independent": {"pass": 14, "fail": 6, "inconclusive": 1,
                                        "not_converged": 1},
                        "not_discriminating": ["tight_side_velocity_fluctuation"]}, r)
    assert s == ("14 of 22 independent checks pass; agrees on Fig. 5 (12 of 16 rows pass); "
                 "disagrees on Table 2 (1 of 1 row fails); not settled on Fig. 9 (1 pass, "
                 "1 fail), Fig. 10 (1 pass, 1 inconclusive, 1 not converged); "
                 "1 pass reproduced, not discriminating (no rival fails them; not counted).")
    assert [artefact_title(a) for a in ("fig07", "fig6a", "table12", "text", "cost_of_accuracy")] == [
        "Fig. 7", "Fig. 6a", "Table 12", "Statements in the text", "cost of accuracy"]


def _page(results: Path) -> Path:
    """A report page from the template (no paper), as write_report places it."""
    from mechrepro.report import render

    page = results / "report" / "index.html"
    page.parent.mkdir(parents=True)
    b = banner(results / "report" / "reference_check.txt", "ci")
    page.write_text(render({"banner": b, "papers": [], "cost": None, "time": None,
                            "mark": "../last_run_failed.js"}))
    return page


def _shown(page: Path, mark: Path) -> str:
    """What the page's failure-mark script puts on its first screen with ``mark`` loaded
    (node, on a few lines of stand-in DOM)."""
    node = shutil.which("node")
    if node is None:
        pytest.skip("needs node to run the page's script")
    script = re.search(r"<script>(.*?)</script>", page.read_text(), re.S).group(1)
    written = re.search(r'data-written="([0-9.]+)"', page.read_text()).group(1)
    js = f"""
const mk = tag => ({{tag, children: [], dataset: {{}}, textContent: "",
                     append(...c) {{ this.children.push(...c); }}}});
const slot = mk("div"); slot.dataset.written = "{written}";
globalThis.document = {{getElementById: id => id === "failed-run" ? slot : null,
                        createElement: mk, head: mk("head")}};
{script}
if (document.head.children[0].src !== "../last_run_failed.js") throw new Error("mark path");
{mark.read_text() if mark.exists() else ""}
const text = n => typeof n === "string" ? n : n.textContent + n.children.map(text).join("");
console.log(text(slot));"""
    return subprocess.run([node, "-e", js], capture_output=True, text=True, check=True).stdout


def test_a_failure_mark_describes_the_failed_run_and_is_never_archived(tmp_path):
    """A failed `make` leaves a mark beside the results, never in a page the archive
    certifies: the page shows it on its first screen (whether that run wrote the page or
    left an earlier one), the next completed run removes it, and no archive takes it in."""
    import os
    import time

    from mechrepro.archive import linked_extras
    from mechrepro.plan import main

    results = tmp_path / "results"
    page = _page(results)
    before = page.read_bytes()
    log = tmp_path / "run.snakemake.log"
    log.write_text("rule validate_saw_chain:\nError in rule validate_saw_chain:\n")
    mark = results / "last_run_failed.js"
    assert _shown(page, mark) == "\n"                        # no mark, no banner

    written = float(re.search(r'data-written="([0-9.]+)"', page.read_text()).group(1))
    # a run that started before the page was written (a drift: it wrote the report, then
    # its archive was refused) and one that started after it (the page is an earlier run's)
    for since, says in ((written - 5, "that run wrote this report"),
                        (written + 5, "this report is from an earlier run")):
        os.utime(log, (since + 1, since + 1))
        assert main([str(results), str(log), "--since", str(since), "--status", "1"]) == 0
        shown = _shown(page, mark)
        assert shown.startswith("The last run failed (exit status 1; failed: "
                                "validate_saw_chain; "), shown
        assert says in shown, shown
        assert page.read_bytes() == before                    # the page itself is untouched
        assert linked_extras(results, {"report/index.html": "sha"}) == []   # never archived

    # a refused config (no job planned) is a failed run too; a completed run removes the mark
    assert main([str(results), str(log), "--since", str(time.time() + 60), "--status", "1"]) == 0
    assert "before any job" in _shown(page, mark)
    assert main([str(results), str(log), "--status", "0"]) == 0
    assert not mark.exists() and _shown(page, mark) == "\n"
