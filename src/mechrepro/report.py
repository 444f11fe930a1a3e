"""The reproduction report: whether to trust the run on the first screen, then per paper each
figure and table beside what the paper states about it.

The page is a Jinja2 template (``templates/report.html.j2``) filled from structured data only:
the reference check, each paper's ``claim.json``, ``validation.csv`` and declared artefacts.
Images are linked relative to the page, so the report inside the archive is self-contained.
"""
from __future__ import annotations

import csv
import datetime as _dt
import json
import os
import platform
import re
from pathlib import Path

from .config import CACHE_DIR, load_paper
from .io import write_text
from .provenance import code_version
from .validation import artefact_verdicts, read_table

VERDICTS = ("pass", "fail", "inconclusive", "not_converged")
#: the failure mark of a run that did not complete, in the results directory
#: (written and removed by :func:`mechrepro.plan.mark_failed`, loaded by every report page)
MARK = "last_run_failed.js"

CSS = """
body{font-family:system-ui,sans-serif;margin:1em auto;max-width:1180px;padding:0 12px;color:#222;line-height:1.4}
h1{margin:.2em 0;font-size:1.5em}h2{border-bottom:2px solid #ccc;padding-top:.8em}
h3{margin:.8em 0 .3em}h3 a.anchor{color:inherit;text-decoration:none}
table{border-collapse:collapse;margin:.5em 0;font-size:13px}
td,th{border:1px solid #ccc;padding:3px 6px;text-align:left;vertical-align:top;overflow-wrap:anywhere}
td.mrow{min-width:12em;overflow-wrap:normal}table.matrix th{overflow-wrap:normal;font-size:12px}table.matrix td:last-child{min-width:16em}
th{background:#f0f0f0}
table.papers,table.rows{width:100%;table-layout:fixed}
table.papers th:nth-child(1){width:9em}table.papers th:nth-child(2){width:5em}table.papers th:nth-child(3){width:17em}
col.c-q{width:22%}col.c-v{width:13%}col.c-s{width:12%}col.c-w{width:40%}
.banner{border:2px solid;border-radius:6px;padding:.3em 1em .6em;margin-bottom:.6em}
.banner.ok{border-color:#3a9a3a;background:#f3fbf3}.banner.bad{border-color:#c33;background:#fdf0f0}
.trust{font-size:1.05em;margin:.3em 0}.meta{color:#555;font-size:12px;margin:.2em 0}
ul.drift{font-size:12px;margin:.2em 0}
.badge{display:inline-block;padding:1px 7px;border-radius:8px;margin:1px 4px 1px 0;font-size:12px;white-space:nowrap}
.b-pass{background:#c8efc8}.b-fail{background:#f6c3c3}.b-info{background:#e4e4f4}
.b-inconclusive{background:#f6e3b0}.b-not_converged{background:#e8c8f0}
tr.nc td{color:#777}
.claim{background:#fff8e0;border-left:4px solid #e0b000;padding:.4em 1em}
nav.toc{background:#f7f7f7;padding:.3em 1em;border:1px solid #ddd;position:sticky;top:0;z-index:1}
nav.toc a{margin-right:1em}
figure{margin:.4em 0}figure img{max-width:100%;height:auto;border:1px solid #ddd}
figcaption{font-size:12px;color:#555}
.note{color:#555;font-size:12px}.ours{color:#666;font-weight:normal;font-size:.85em}
details summary{cursor:pointer;color:#245}dl{font-size:12px;margin:.2em 0}dt{font-weight:bold}dd{margin:0 0 .3em 1em}
details.table{margin:.4em 0}.scroll{overflow-x:auto;max-width:100%}
@media print{nav.toc{display:none}details{display:block}details>*{display:block}
  .paper,.artefact{break-inside:avoid-page}body{max-width:none}}
"""

TABLE_TITLES = {
    "effect_cost": "What each effect and output costs (summed over every run, verdict variants included)",
    "effect_marginal_cost": "What each effect costs the solve: its own evaluation (direct) "
                            "beside the scene's time with it minus without it (marginal)",
    "job_time": "Solver jobs: the solves' own time against the job's wall time",
    "verification_cost": "What verification costs and what it decides: each re-check's runs, "
                         "their solve time and share, the verdict rows it re-checks and those "
                         "whose verdict it decides (a flip, the error bar, a failing rival)",
    "cost_of_accuracy": "Cost of accuracy: error against the reference vs time (long form)",
    "verdict_evidence": "Every re-check of every verdict (levels, seeds, range ends, family "
                        "members, rivals)",
    "discrimination": "Which physics each counted verdict tests: every counted row under every "
                      "rival model (fails: the row discriminates the paper's model from it; a "
                      "sledgehammer fails most rows and credits none by itself)",
    "accuracy_targets": "Accuracy asked for instead of a resolution (mechrepro.target): "
                        "requested, estimated and verified error at the chosen setting, beside "
                        "the fixed setting it is compared with (default_*)",
}


def artefact_title(aid: str) -> str:
    """'fig07' -> 'Fig. 7', 'table2' -> 'Table 2', 'fig6a' -> 'Fig. 6a', others as words."""
    for prefix, word in (("fig", "Fig."), ("table", "Table")):
        rest = aid[len(prefix):]
        if aid.startswith(prefix) and rest[:1].isdigit():
            return f"{word} {rest.lstrip('0') or '0'}".replace("_", " ")
    return {"text": "Statements in the text"}.get(aid, aid.replace("_", " "))


def _read_csv(path: Path) -> tuple[list[str], list[list[str]]]:
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def _num(cell: str) -> str:
    try:
        x = float(cell)
    except ValueError:
        return cell
    return f"{x:.6g}"


_SENTENCE_END = re.compile(r"(?<!\bEq)(?<!\bEqs)(?<!\bFig)(?<!\bFigs)(?<!\bSec)(?<!\bRef)(?<!\be\.g)"
                           r"(?<!\bi\.e)(?<!\bvs)(?<!\bp)(?<!\bcf)\.\s+(?=[A-Z(\[])")


def _first_sentence(text: str, limit: int = 220) -> str:
    """The first sentence (abbreviations such as 'Eq.' and 'Fig.' do not end one)."""
    text = " ".join(text.split())
    m = _SENTENCE_END.search(text)
    out = text if m is None else text[:m.start() + 1]
    return out if len(out) <= limit else out[:limit - 1].rstrip() + "…"


def _row(r: dict, spec: dict) -> dict:
    """One validation.csv row as the report shows it."""
    error = r.get("error_estimate", "")
    ours = _num(r["reproduced_value"])
    if spec.get("kind") == "check":
        ours = {"1.0": "holds", "0.0": "does not hold"}.get(r["reproduced_value"], ours)
    if error and error not in ("0.0", "nan", "inf") and r["status"] != "info":
        ours += f" ± {float(error):.2g}"
    if r["unit"] not in ("1", "bool", ""):
        ours += f" {r['unit']}"
    paper = "claim holds" if spec.get("kind") == "check" else _num(r["paper_value"]) or "—"
    if paper not in ("—", "claim holds") and r["unit"] not in ("1", "bool", ""):
        paper += f" {r['unit']}"
    why = spec.get("why", "") if r["status"] == "pass" else ""
    why = _first_sentence(why or r.get("note", "") or spec.get("note", ""))
    details = [(k, v) for k, v in (
        ("criterion", r.get("criterion", "")), ("tolerance", r.get("tolerance", "")),
        ("observed order", _num(r.get("observed_order", ""))),
        ("rivals", r.get("rivals", "")), ("note", r.get("note", "")),
        ("tolerance why", spec.get("why", ""))) if v]
    return {"quantity": r["quantity"].replace("_", " "), "source": r["source"], "paper": paper,
            "ours": ours, "status": r["status"], "evidence": r["evidence"],
            "counted": r["evidence"] == "independent" and r["status"] != "info",
            "why": why, "details": details}


def claim_sentence(claim: dict, rows: list[dict]) -> str:
    """One plain sentence from claim.json's counts and the validation rows: the artefacts
    that agree, disagree and are not settled by their rows' majority, with the counts
    (artefact titles, no row ids)."""
    n = claim["independent"]
    total = sum(n.values())
    parts = [f"{n.get('pass', 0)} of {total} independent checks pass"]

    def counts(c: dict, key: str) -> str:
        rows_n = sum(c.values())
        if key != "not settled":
            word, k = ("pass", "passes") if key == "agree" else ("fail", "fails")
            m = c.get(word, 0)
            return f"{m} of {rows_n} row{'s' * (rows_n != 1)} {k if m == 1 else word}"
        return ", ".join(f"{c[s]} {s.replace('_', ' ')}" for s in VERDICTS if c.get(s))

    for key, arts in artefact_verdicts(rows).items():
        if arts:
            word = {"agree": "agrees on", "disagree": "disagrees on"}.get(key, "not settled on")
            parts.append(f"{word} " + ", ".join(f"{artefact_title(a)} ({counts(c, key)})"
                                               for a, c in arts))
    n_nc = len(claim.get("not_discriminating", []))
    if n_nc:
        parts.append(f"{n_nc} pass{'es' if n_nc != 1 else ''} reproduced, not discriminating "
                     "(no rival fails them; not counted)")
    return "; ".join(parts) + "."


def made_by(paper: str, spec: dict, key: str) -> tuple[str, str]:
    """Where a reader finds a declared figure's or table's code and data: its function
    (``spec[key]``) as ``models/<paper>/<module>.py: <function>``, and the runs it reads."""
    return (f"models/{paper}/" + (spec[key] if "." in spec[key] else "__init__." + spec[key])
            .replace(".", ".py: ", 1), ", ".join(spec["reads"]) or "its tables")


def paper_view(paper: str, results: Path, config_dir: Path, profile: str, out_dir: Path) -> dict:
    cfg = load_paper(config_dir / "papers" / f"{paper}.yaml", profile, CACHE_DIR)
    root = results / paper
    claim = json.loads((root / "claim.json").read_text())
    rows = read_table(root / "tables" / "validation.csv")
    reported = cfg.reported
    artefacts: dict[str, dict] = {}
    for fig in cfg.figures:
        artefacts[fig] = {"id": fig, "rows": [], "image": os.path.relpath(
            root / "figures" / f"{fig}.png", out_dir)}
    for r in rows:
        a = r["artefact"]
        artefacts.setdefault(a, {"id": a, "rows": [], "image": None})["rows"].append(
            _row(r, reported.get(r["quantity"], {})))
    for a in artefacts.values():
        a["title"] = artefact_title(a["id"])
        # ours: an artefact of no paper statement, or one whose every row cites us
        a["ours"] = not a["rows"] or all("ours" in r["source"] for r in a["rows"])
        a["caption"] = cfg.caption(a["id"]) if a["id"] in cfg.figures else a["title"]
        a["drawn"] = a["id"] in cfg.figures and made_by(paper, cfg.figure(a["id"]), "draw")
    tables = []
    for t in cfg.tables:
        if t in ("validation", "discrimination") or not (root / "tables" / f"{t}.csv").exists():
            continue
        head, body = _read_csv(root / "tables" / f"{t}.csv")
        spec = cfg.table(t) if t in cfg.notebook_tables else None
        tables.append({"title": TABLE_TITLES.get(t, f"{t}.csv"), "head": head,
                       "rows": [[_num(c) for c in row] for row in body],
                       "caption": spec and spec["caption"], "made": spec and made_by(paper, spec, "make")})
    assumed = [{"name": k, "value": f"{v['value']} {v['unit'] if v['unit'] != '1' else ''}".strip(),
                "range": (f"{v['range'][0]} … {v['range'][1]}: {v.get('range_why', '')}"
                          if "range" in v else f"calibrated on {v['calibrated_on']}"
                          if "calibrated_on" in v else "numerical setting"),
                "why": v["why"]} for k, v in cfg.assumed().items()]
    counts = [(s, n) for s in VERDICTS for n in [claim["independent"].get(s, 0)]
              if n or s in ("pass", "fail")]
    return {"id": paper, "title": cfg.raw.get("title", cfg.source), "source": cfg.source,
            "claim": claim["claim"], "counts": counts, "sentence": claim_sentence(claim, rows),
            "paper_note": cfg.raw.get("claim_note", ""), "artefacts": list(artefacts.values()),
            "tables": tables, "assumed": assumed,
            "matrix": matrix_view(root / "tables" / "discrimination.csv", cfg.raw.get("rivals", {})),
            "verification": verification_sentence(root / "tables" / "verification_cost.csv")}


def verification_sentence(path: Path) -> str:
    """What verification costs and what it decides, in one sentence (verification_cost.csv)."""
    if not path.exists():
        return ""
    rows = read_table(path)
    checks = [r for r in rows if r["kind"] not in ("baseline", "ablation")]
    base = sum(float(r["solve_s"]) for r in rows if r["kind"] == "baseline")
    spent = sum(float(r["solve_s"]) for r in checks)
    idle = [r for r in checks if r["decides"] == "0"]
    idle_s = sum(float(r["solve_s"]) for r in idle)
    return (f"Verification re-runs cost {spent:.3g} s of solve beside the baseline's {base:.3g} s; "
            f"{len(checks) - len(idle)} of {len(checks)} re-checks decide a verdict (a flip, "
            f"the error bar or a failing rival); the other {len(idle)} ({idle_s:.3g} s) decide "
            "none.")


#: a discrimination cell as the report shows it: (text, css class)
CELL = {"fails": ("fails", "b-pass"), "passes": ("passes", "b-fail"), "unchanged": ("—", ""),
        "no value": ("no value", "b-inconclusive")}


def matrix_view(path: Path, rivals: dict) -> dict | None:
    """The discrimination matrix pivoted: one line per counted row, one column per rival,
    and the physics the row tests (what the rivals that credit it remove)."""
    if not path.exists() or not rivals:
        return None
    long = read_table(path)
    sledge = {r["rival"] for r in long if r["sledgehammer"] == "True"}
    rows: dict[str, dict] = {}
    for r in long:
        row = rows.setdefault(r["quantity"], {
            "quantity": r["quantity"].replace("_", " "), "artefact": artefact_title(r["artefact"]),
            "status": r["status"], "evidence": r["evidence"], "cells": {}, "tests": []})
        text, css = CELL.get(r["outcome"][:5] if r["outcome"].startswith("fails") else r["outcome"],
                             ("·" if r["outcome"].startswith("not run")
                                            else "not decisive", ""))
        row["cells"][r["rival"]] = (text, css, r["outcome"])
        if r["credits"] == "True":
            row["tests"].append(rivals[r["rival"]]["removes"])
    return {"rivals": [{"name": n, "removes": v["removes"], "sledgehammer": n in sledge}
                       for n, v in rivals.items()],
            "rows": [{**row, "cells": [row["cells"].get(n, ("·", "", "not run"))
                                       for n in rivals]} for row in rows.values()]}


def banner(check_file: Path, profile: str) -> dict:
    """Whether to trust the run: the reference check's first line decides (a drift, a paper
    without a reference, or no check at all is not OK)."""
    text = check_file.read_text() if check_file.exists() else ""
    lines = text.splitlines()
    ok = bool(lines) and lines[0].endswith(": OK") and "not checked" not in text
    if not lines:
        headline, detail = "Not checked:", "the reference check did not run."
    elif ok:
        headline, detail = "Reference check passed:", ("every value is within its measured "
                                                         "tolerance and every verdict is the same as in the committed reference.")
    else:
        headline, detail = "Do not trust these numbers yet:", "the reference check did not pass."
    bad = [ln.strip() for ln in lines[1:] if ln.startswith("  ") or "not checked" in ln
           or "DRIFT" in ln]
    return {"ok": ok, "headline": headline, "detail": detail, "lines": bad[:12],
            "profile": profile, "code": code_version(),
            "platform": f"{platform.machine()} {platform.system()}, Python {platform.python_version()}",
            "created": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
            # the page's writing time, against which a failure mark (mechrepro.plan) says
            # whether the failed run wrote this page or left an earlier one
            "written": f"{_dt.datetime.now().timestamp():.3f}"}


def time_view(results: Path, papers: list[str]) -> dict | None:
    """Per paper: the solves' own time against the solver jobs' wall time and what the
    paper's cost model expected of them, and the paper's other jobs (validation, notebook)."""
    from .costs import benchmark_seconds

    def cell(x: float) -> str:
        return "n/a" if x != x else f"{x:.3g}"

    rows = []
    for paper in papers:
        f = results / paper / "tables" / "job_time.csv"
        if not f.exists():
            continue
        head, r = _read_csv(f)
        solve = sum(float(x[head.index("solve_s")]) for x in r)
        # a job without its benchmark (regrouped between solve and validation) is unknown:
        # the paper's job total is then n/a, not a crash
        job = sum(float(x[head.index("job_s")] or "nan") for x in r)
        runs = sum(int(x[head.index("runs")]) for x in r)
        est = sum(float(x[head.index("estimate_s")] or "nan") for x in r) \
            if "estimate_s" in head else float("nan")
        other = [benchmark_seconds(results / paper / "benchmarks" / f"{k}.tsv")
                 for k in ("validate", "notebook")]
        rows.append([paper, str(len(r)), str(runs), f"{solve:.3g}",
                     cell(job if job > 0 else float("nan")),
                     f"{(job - solve) / job:.0%}" if job > 0 else "n/a", cell(est),
                     *map(cell, other)])
    if not rows:
        return None
    return {"head": ["paper", "solver jobs", "runs", "solve [s]", "job [s]", "overhead",
                     "cost model [s]", "validation job [s]", "notebook job [s]"], "rows": rows}


def render(context: dict) -> str:
    import jinja2

    env = jinja2.Environment(
        loader=jinja2.FileSystemLoader(Path(__file__).with_name("templates")),
        autoescape=True, undefined=jinja2.StrictUndefined, trim_blocks=True, lstrip_blocks=True)
    return env.get_template("report.html.j2").render(css=CSS, **context)


def write_report(out: str, results: str, config_dir: str, papers: list[str], profile: str) -> None:
    out, results, config_dir = Path(out), Path(results), Path(config_dir)
    cost = None
    if (out.parent / "summary.csv").exists():
        head, rows = _read_csv(out.parent / "summary.csv")
        cost = {"image": "cost_of_accuracy_all.png", "head": head,
                "rows": [[_num(c) for c in r] for r in rows]}
    write_text(out, render({
        "banner": banner(out.parent / "reference_check.txt", profile),
        "papers": [paper_view(p, results, config_dir, profile, out.parent) for p in papers],
        "cost": cost, "time": time_view(results, papers),
        "mark": Path(os.path.relpath(results / MARK, out.parent)).as_posix()}))
