"""docs/disk_tension.md prints what a run gave, not typed numbers (issue 29): its verdict
table is the committed default reference's, and the generator fills every marked block."""
import csv
import re
from pathlib import Path

import pytest

from mechrepro.models.disk_tension import docs

ROOT = Path(__file__).resolve().parent.parent
DOC = (ROOT / "docs" / "disk_tension.md").read_text()


def _block(name):
    m = re.search(rf"<!-- run:{name} -->\n(.*?)\n<!-- /run:{name} -->", DOC, flags=re.S)
    assert m, f"block {name} missing"
    return m.group(1)


def test_every_block_the_page_marks_has_a_generator():
    from mechrepro.docs import PAPER_BLOCKS

    names = set(re.findall(r"<!-- run:(\w+) -->", DOC))
    assert names == set(docs.BLOCKS) | set(PAPER_BLOCKS)


def test_the_verdict_table_is_the_committed_default_reference():
    with open(ROOT / "results" / "reference" / "default" / "disk_tension.csv", newline="") as fh:
        ref = {r["quantity"]: r for r in csv.DictReader(fh)}
    rows = [line.split("|") for line in _block("verdicts").splitlines()[2:]]
    assert rows
    for cells in rows:
        q = cells[1].strip().strip("`")
        value, status = float(cells[4]), cells[6].strip()
        assert status == ref[q]["status"], q
        assert value == pytest.approx(float(ref[q]["reproduced_value"]), rel=1e-5, abs=1e-12), q
