"""docs/chain_drive.md prints what a run gave, not typed numbers: its blocks have generators
and its verdict table and counts are the committed default reference's."""
import csv
import re
from pathlib import Path

from mechrepro.docs import BLOCK_NAME, PAPER_BLOCKS, block
from mechrepro.models.chain_drive import docs

ROOT = Path(__file__).resolve().parent.parent
DOC = (ROOT / "docs" / "chain_drive.md").read_text()


def _reference():
    with open(ROOT / "results/reference/default/chain_drive.csv", newline="") as fh:
        return {r["quantity"]: r for r in csv.DictReader(fh)}


def test_every_block_has_a_generator():
    names = set(BLOCK_NAME.findall(DOC))
    assert set(docs.BLOCKS) <= names <= set(docs.BLOCKS) | set(PAPER_BLOCKS)


def test_the_verdict_table_is_the_committed_default_reference():
    ref = _reference()
    lines = block(DOC, "verdicts").splitlines()
    head = [c.strip() for c in lines[0].split("|")]
    rows = [dict(zip(head, (c.strip() for c in line.split("|")))) for line in lines[2:]]
    got = {r["row"].strip("`"): r["verdict"] for r in rows}
    assert got == {q: r["status"] for q, r in ref.items() if r["status"] != "info"
                   and r["evidence"] in ("independent", "not_discriminating")}, (
        "regenerate: python -m mechrepro.docs docs/chain_drive.md results (default run)")


def test_the_counts_are_the_committed_default_reference():
    ref = _reference()
    counted = [r for r in ref.values() if r["evidence"] == "independent"]
    text = block(DOC, "counts")
    for s in ("pass", "fail", "inconclusive"):
        k = sum(r["status"] == s for r in counted)
        assert re.search(rf"\b{k} {s}\b", text), (s, k, text)
