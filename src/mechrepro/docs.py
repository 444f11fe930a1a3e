"""Numbers in the documents come from a run, never typed: marked blocks filled from results.

A document marks each generated block ::

    <!-- run:NAME -->
    ...replaced...
    <!-- /run:NAME -->

and this fills them: ``README.md`` from the framework's blocks below (the claim of every
paper from ``results/<paper>/claim.json``, the assumed constants from the paper configs),
``docs/<paper>.md`` from the blocks every paper page may use (:data:`PAPER_BLOCKS`: counts,
verdicts, info rows, ``<!-- run:notes q1 q2 -->`` for the notes of named rows, ...) and
the paper's own ``models/<paper>/docs.py`` (``BLOCKS``), each a function of
``results/<paper>``::

    .venv/bin/python -m mechrepro.docs README.md results
    .venv/bin/python -m mechrepro.docs docs/disk_tension.md results

Run it on the default profile's results (``make reproduce``) after the last change; tests
check the filled blocks against the committed default references.
"""
from __future__ import annotations

import importlib
import json
import re
import sys
from collections.abc import Callable
from pathlib import Path

# the rows of a result table, as dicts (what the papers' docs blocks read)
from .validation import read_table as table_rows

# <!-- run:NAME --> or <!-- run:NAME ARG ARG --> (a block given arguments: notes q1 q2)
BLOCK = re.compile(r"<!-- run:(\w+)((?: [\w.]+)*) -->.*?<!-- /run:\1 -->", flags=re.S)
BLOCK_NAME = re.compile(r"<!-- run:(\w+)[ \w.]* -->")
VERDICTS = ("pass", "fail", "inconclusive", "not_converged")


def number(x, digits: int = 4) -> str:
    """A number as the docs print it: '' stays '', NaN is a dash, infinity ∞, an integer has
    no point."""
    if x in ("", None):
        return ""
    try:
        v = float(x)
    except ValueError:
        return str(x)
    if v != v:
        return "—"
    if abs(v) == float("inf"):     # an error bar of levels that do not contract
        return "∞" if v > 0 else "-∞"
    if v == int(v) and abs(v) < 1e6:
        return f"{int(v)}"
    return f"{v:.{digits}g}"


def regenerate(text: str, blocks: dict[str, Callable[[Path], str]], root: Path) -> str:
    """``text`` with every ``<!-- run:NAME ARGS -->`` block filled by
    ``blocks[NAME](root, *ARGS)``."""
    unknown = sorted(set(BLOCK_NAME.findall(text)) - set(blocks))
    if unknown:
        raise KeyError(f"no generator for the block(s) {unknown}; have {sorted(blocks)}")

    def fill(m):
        name, args = m.group(1), m.group(2)
        return (f"<!-- run:{name}{args} -->\n{blocks[name](root, *args.split())}\n"
                f"<!-- /run:{name} -->")
    return BLOCK.sub(fill, text)


def block(text: str, name: str) -> str:
    """The current content of block ``name`` of ``text``."""
    m = re.search(rf"<!-- run:{name}[ \w.]* -->\n(.*?)\n<!-- /run:{name} -->", text, flags=re.S)
    if not m:
        raise KeyError(f"block {name} missing")
    return m.group(1)


def _papers(config_dir: Path) -> list[str]:
    from .config import workflow_config

    return workflow_config(config_dir / "config.yaml")["papers"]


def claims(results: Path, config_dir: Path = Path("config")) -> str:
    """One row per paper: its claim, the counts of its independent verdicts and its passes
    that no rival fails (reproduced, not counted)."""
    from .config import load_paper

    out = ["| id | paper | claim | pass | fail | inconclusive | not converged | reproduced, not "
           "discriminating | details |", "|---|---|---|---|---|---|---|---|---|"]
    for paper in _papers(config_dir):
        c = json.loads((results / paper / "claim.json").read_text())
        title = load_paper(config_dir / "papers" / f"{paper}.yaml").raw.get("title", "")
        n = c["independent"]
        out.append(f"| `{paper}` | {title} | {c['claim']} | "
                   + " | ".join(str(n.get(s, 0)) for s in VERDICTS)
                   + f" | {len(c.get('not_discriminating', []))} | `docs/{paper}.md` |")
    return "\n".join(out)


def assumed_constants(results: Path, config_dir: Path = Path("config")) -> str:
    """Every constant a paper does not give, with its value, range or calibration, and why."""
    from .config import load_paper

    out = ["| paper | parameter | value | unit | plausible range / calibration | why |",
           "|---|---|---|---|---|---|"]
    for paper in _papers(config_dir):
        cfg = load_paper(config_dir / "papers" / f"{paper}.yaml")
        for name, p in cfg.assumed().items():
            why = " ".join(str(p["why"]).split()).replace("|", "/")
            how = (f"{p['range'][0]} … {p['range'][1]}" if "range" in p else
                   f"calibrated on `{p['calibrated_on']}`" if "calibrated_on" in p else
                   "numerical setting" if p.get("numerical") else "")
            out.append(f"| {paper} | `{name}` | {p['value']} | {p['unit']} | {how} | {why} |")
    return "\n".join(out)


def job_times(results: Path, config_dir: Path = Path("config")) -> str:
    """Where the time of the run went, per paper (the report's table, as markdown)."""
    from .report import time_view

    view = time_view(results, _papers(config_dir))
    if view is None:
        return "(no job times in this run)"
    return markdown(view["head"], view["rows"])


def knobs(results: Path, config_dir: Path = Path("config")) -> str:
    """Every resolution knob of a paper (``refine:``, its one declaration): what it is, what
    a scene may give it, how it refines for the verdicts' re-checks, and the values the
    default profile's scenes give it."""
    from .config import load_paper

    paper = results.name
    cfg = load_paper(config_dir / "papers" / f"{paper}.yaml")
    used: dict[str, set] = {}
    for run in cfg.runs.values():
        if "@" in run["run"]:     # a verdict variant (coarser levels, range ends)
            continue
        for k, v in run.get("resolution", {}).items():
            used.setdefault(k, set()).add(json.dumps(v))
    rows = []
    for key, spec in cfg.raw.get("refine", {}).items():
        a = spec["allowed"]
        rng = (", ".join(map(str, a["enum"])) if "enum" in a else
               " … ".join(str(a.get(lo, a.get("exclusive" + lo.capitalize(), "")))
                          for lo in ("minimum", "maximum")) if a.get("type") != "array" else "a list")
        how = (f"× {spec['factor']:g}" if "factor" in spec else "fixed: " + spec["fixed"])
        if spec.get("why"):
            how += f" ({spec['why']})"
        vals = [v.strip('"') for v in sorted(used.get(key, ()), key=lambda v: (len(v), v))]
        shown = ", ".join(vals[:6]) + (f" … ({len(vals)} values)" if len(vals) > 6 else "")
        rows.append([f"`{key}`", spec["description"], rng, how, shown or "not used"])
    return markdown(["knob", "what it is", "allowed", "per level (coarser: ÷)", "default profile"],
                    rows)


def markdown(header, rows) -> str:
    """A markdown table (cells with their line breaks and bars made safe)."""
    cell = lambda t: " ".join(str(t).split()).replace("|", "/")  # noqa: E731
    return "\n".join(["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
                     + ["| " + " | ".join(cell(c) for c in r) + " |" for r in rows])


def counts(root: Path) -> str:
    """The paper's claim and its verdict counts, independent first, then by evidence class."""
    c = json.loads((root / "claim.json").read_text())
    ind = c["independent"]
    return (f"Claim **{c['claim']}**. Independent: **{ind.get('pass', 0)} pass, "
            f"{ind.get('fail', 0)} fail, {ind.get('inconclusive', 0)} inconclusive, "
            f"{ind.get('not_converged', 0)} not converged** (counts by evidence class: "
            + "; ".join(f"{k} " + ", ".join(f"{n} {s}" for s, n in sorted(v.items()))
                        for k, v in sorted(c["counts"].items())) + ").")


def _validation(root: Path) -> list[dict]:
    return table_rows(root / "tables" / "validation.csv")


def verdicts(root: Path, *evidence: str) -> str:
    """Every row with a verdict (not info; ``<!-- run:verdicts independent ... -->``: of
    those evidence classes only): the paper's value, ours with its error bar, the verdict,
    its evidence class and the rivals it was checked against."""
    return markdown(["row", "source", "evidence", "paper", "ours", "± error", "verdict",
                     "rivals"],
                    [[f"`{r['quantity']}`", r["source"], r["evidence"], number(r["paper_value"]),
                      f"{number(r['reproduced_value'], 6)} {r['unit']}".strip(),
                      number(r["error_estimate"], 2), r["status"], r["rivals"] or "—"]
                     for r in _validation(root) if r["status"] != "info"
                     and (not evidence or r["evidence"] in evidence)])


def info(root: Path) -> str:
    """The info rows: what the run measures beside the verdicts."""
    return markdown(["row", "source", "value", "evidence"],
                    [[f"`{r['quantity']}`", r["source"],
                      f"{number(r['reproduced_value'], 5)} {r['unit']}".strip(), r["evidence"]]
                     for r in _validation(root) if r["status"] == "info"])


def not_discriminating(root: Path) -> str:
    """The independent passes no rival fails (reproduced, not counted)."""
    return "\n".join(f"* `{r['quantity']}`: {r['status']}, rivals {r['rivals'] or 'none'}"
                     for r in _validation(root) if r["evidence"] == "not_discriminating")


def notes(root: Path, *quantities: str) -> str:
    """``<!-- run:notes q1 q2 -->``: each row's value and note."""
    by = {r["quantity"]: r for r in _validation(root)}
    return "\n".join(f"* `{q}` = {number(by[q]['reproduced_value'], 6)} {by[q]['unit']}: "
                     f"{' '.join(by[q]['note'].split())}" for q in quantities if q in by)


def cost(root: Path) -> str:
    """The cost-of-accuracy curves: per entry and quantity, the knob's values, errors, times
    and the observed order."""
    rows = table_rows(root / "tables" / "cost_of_accuracy.csv")
    out = []
    for acc, q in dict.fromkeys((r["accuracy"], r["quantity"]) for r in rows):
        pts = [r for r in rows if r["accuracy"] == acc and r["quantity"] == q]
        out.append([acc, q, pts[0]["reference"], " / ".join(r["knob_value"] for r in pts),
                    " / ".join(f"{float(r['error']):.1e}" for r in pts),
                    " / ".join(f"{float(r['time_s']):.2g}" for r in pts),
                    number(pts[0]["observed_order"], 3)])
    return markdown(["entry", "quantity", "reference", "knob values", "errors", "times [s]",
                     "order"], out)


README_BLOCKS = {"claims": claims, "assumed_constants": assumed_constants, "job_times": job_times}
#: blocks every docs/<paper>.md may use, beside its own models/<paper>/docs.py BLOCKS
PAPER_BLOCKS = {"knobs": knobs, "counts": counts, "verdicts": verdicts, "info": info,
                "not_discriminating": not_discriminating, "notes": notes, "cost": cost}


def blocks_for(doc: Path) -> tuple[dict, str | None]:
    """The generators of a document, and the paper it belongs to (``docs/<paper>.md``)."""
    if doc.parent.name == "docs" and (doc.parents[1] / "config" / "papers" / doc.name
                                      ).with_suffix(".yaml").exists():
        paper = doc.stem
        try:
            own = importlib.import_module(f"mechrepro.models.{paper}.docs").BLOCKS
        except ModuleNotFoundError as exc:
            if exc.name != f"mechrepro.models.{paper}.docs":
                raise
            own = {}
        return {**PAPER_BLOCKS, **own}, paper
    return README_BLOCKS, None


def main(argv: list[str] | None = None) -> None:
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) != 2 or argv[0] in ("-h", "--help"):
        raise SystemExit("usage: python -m mechrepro.docs DOCUMENT RESULTS  "
                         "(README.md or docs/<paper>.md; RESULTS of the default profile)")
    doc, results = Path(argv[0]), Path(argv[1])
    blocks, paper = blocks_for(doc)
    root = results / paper if paper else results
    doc.write_text(regenerate(doc.read_text(), blocks, root))
    print(f"{doc}: {len(BLOCK.findall(doc.read_text()))} blocks filled from {root}")


if __name__ == "__main__":
    main()
