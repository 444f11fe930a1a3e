"""docs/disk_tension.md prints what a run gave, not typed numbers (issue 29): its verdict
table is the committed default reference's, and the generator fills every marked block."""
import csv
from pathlib import Path

import pytest

from mechrepro.docs import block
from mechrepro.models.disk_tension import docs

ROOT = Path(__file__).resolve().parent.parent
DOC = (ROOT / "docs" / "disk_tension.md").read_text()



def test_every_block_the_page_marks_has_a_generator():
    from mechrepro.docs import BLOCK_NAME, PAPER_BLOCKS

    names = set(BLOCK_NAME.findall(DOC))
    assert set(docs.BLOCKS) <= names <= set(docs.BLOCKS) | set(PAPER_BLOCKS)


def test_the_verdict_table_is_the_committed_default_reference():
    with open(ROOT / "results" / "reference" / "default" / "disk_tension.csv", newline="") as fh:
        ref = {r["quantity"]: r for r in csv.DictReader(fh)}
    lines = block(DOC, "verdicts").splitlines()
    head = [c.strip() for c in lines[0].split("|")]
    rows = [dict(zip(head, (c.strip() for c in line.split("|")))) for line in lines[2:]]
    assert rows
    for r in rows:
        q = r["row"].strip("`")
        value, status = float(r["ours"].split()[0]), r["verdict"]
        assert status == ref[q]["status"], q
        assert value == pytest.approx(float(ref[q]["reproduced_value"]), rel=1e-5, abs=1e-12), q
