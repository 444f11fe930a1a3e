"""The reproduction report: every figure and table of every paper, pass/fail at a glance."""
from __future__ import annotations

import csv
import datetime as _dt
import html
import json
import os
from collections import Counter
from pathlib import Path

from .config import CACHE_DIR, load_paper
from .io import write_text
from .provenance import code_version
from .validation import EVIDENCE, STATUSES, counts as evidence_counts

VERDICTS = ("pass", "fail", "inconclusive", "not_converged")

CSS = """
body{font-family:system-ui,sans-serif;margin:2em auto;max-width:1150px;color:#222;line-height:1.4}
h1{margin-bottom:0}h2{border-bottom:2px solid #ccc;padding-top:1em}
table{border-collapse:collapse;margin:.6em 0;font-size:13px}
td,th{border:1px solid #ccc;padding:3px 7px;text-align:left;vertical-align:top}
th{background:#f0f0f0}
tr.pass td.status{background:#c8efc8;font-weight:bold}
tr.fail td.status{background:#f6c3c3;font-weight:bold}
tr.info td.status{background:#e4e4f4}
tr.inconclusive td.status{background:#f6e3b0;font-weight:bold}
tr.not_converged td.status{background:#e8c8f0;font-weight:bold}
tr.nc td{color:#777}
.b-inconclusive{background:#f6e3b0}
.b-not_converged{background:#e8c8f0}
nav.toc{background:#f7f7f7;padding:.4em 1em;border:1px solid #ddd}
nav.toc a{margin-right:1em}
pre.check{background:#f4f4f4;padding:.6em;font-size:12px;white-space:pre-wrap}
pre.drift{background:#fbe0e0}
.badge{display:inline-block;padding:2px 8px;border-radius:8px;margin-right:6px;font-size:13px}
.b-pass{background:#c8efc8}.b-fail{background:#f6c3c3}.b-info{background:#e4e4f4}
.claim{background:#fff8e0;border-left:4px solid #e0b000;padding:.5em 1em}
figure{display:inline-block;margin:.5em;vertical-align:top}
figure img{max-width:520px;border:1px solid #ddd}
figcaption{font-size:12px;color:#555}
.note{color:#555;font-size:12px}
td.note{min-width:280px}
"""


CAPTIONS = {
    "effect_cost": "What each effect costs (effect_cost: summed over every run, verdict variants included; "
                   "share = of those runs' solve time)",
    "job_time": "Solver jobs: the solves' own time against the job's wall time (job_time)",
    "cost_of_accuracy": "Cost of accuracy (long form: error against the reference vs time)",
}


def _read_csv(path: Path) -> tuple[list[str], list[list[str]]]:
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def _fmt(cell: str) -> str:
    try:
        x = float(cell)
    except ValueError:
        return html.escape(cell)
    return html.escape(f"{x:.6g}")


def _evidence_table(rows: list[dict]) -> str:
    c = evidence_counts(rows)
    head = "".join(f"<th>{s}</th>" for s in STATUSES)
    body = "".join(f"<tr><td>{e}{' (counted)' if e == 'independent' else ''}</td>"
                   + "".join(f'<td class="b-{s}">{c.get(e, {}).get(s, 0)}</td>' for s in STATUSES)
                   + "</tr>" for e in EVIDENCE if e in c)
    return f"<table><tr><th>evidence</th>{head}</tr>{body}</table>"


def paper_section(paper: str, results: Path, config_dir: Path, profile: str,
                  out_dir: Path) -> tuple[str, dict]:
    cfg = load_paper(config_dir / "papers" / f"{paper}.yaml", profile, CACHE_DIR)
    root = results / paper
    claim = json.loads((root / "claim.json").read_text())
    with open(root / "tables" / "validation.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    head = [h for h in rows[0]] if rows else []
    ind = Counter(r["status"] for r in rows if r.get("evidence") == "independent")
    parts = [f'<h2 id="{paper}">{html.escape(paper)} &mdash; {html.escape(cfg.raw.get("title", ""))}</h2>',
             f'<p class="note">{html.escape(cfg.source)}</p>',
             "<p>independent rows: " + "".join(
                 f'<span class="badge b-{s}">{s}: {ind.get(s, 0)}</span>'
                 for s in VERDICTS) + "</p>",
             f'<p class="claim"><b>Replication claim: {html.escape(claim["claim"])}.</b> '
             f'{html.escape(claim["text"])}</p>',
             "<h3>Rows by evidence class</h3>"
             "<p class='note'>Only <b>independent</b> rows (no constant was fitted to them) count "
             "in the claim; the others are shown, labelled, not counted.</p>", _evidence_table(rows)]
    flips = [r for r in rows if r["status"] in ("inconclusive", "not_converged")]
    if flips:
        parts.append("<h3>Inconclusive and not converged verdicts, and what decides them</h3><ul>"
                     + "".join(f"<li><b>{html.escape(r['quantity'])}</b> ({r['status']}): "
                               f"{html.escape(r.get('note', ''))}</li>" for r in flips) + "</ul>")
    falsified = [r for r in rows if r.get("falsifier")]
    if falsified:
        parts.append("<h3>Falsifiers: the model change under which each check must fail</h3>"
                     "<table><tr><th>quantity</th><th>status</th><th>falsifier: its verdict "
                     "(value)</th></tr>" + "".join(
                         f"<tr><td>{html.escape(r['quantity'])}</td><td>{r['status']}</td>"
                         f"<td>{html.escape(r['falsifier'])}</td></tr>" for r in falsified)
                     + "</table>")
    parts.append("<h3>Validation table</h3><table><tr>"
                 + "".join(f"<th>{html.escape(h)}</th>" for h in head) + "</tr>")
    for r in rows:
        counted = "" if r.get("evidence") == "independent" else " nc"
        cells = "".join(f'<td class="{h}">{_fmt(r[h])}</td>' for h in head)
        parts.append(f'<tr class="{r["status"]}{counted}">{cells}</tr>')
    parts.append("</table>")
    assumed = cfg.assumed()
    if assumed:
        parts.append("<h3>Assumed constants (not given by the paper)</h3><table>"
                     "<tr><th>parameter</th><th>value</th><th>unit</th><th>plausible range / "
                     "calibration</th><th>why</th></tr>")
        for k, v in assumed.items():
            rng = (f"{v['range']} ({v.get('range_why', '')})" if "range" in v else
                   f"calibrated on {v['calibrated_on']}" if "calibrated_on" in v else
                   "numerical setting" if v.get("numerical") else "")
            parts.append(f"<tr><td>{html.escape(k)}</td><td>{html.escape(str(v['value']))}</td>"
                         f"<td>{html.escape(v['unit'])}</td><td>{html.escape(rng)}</td>"
                         f"<td>{html.escape(v['why'])}</td></tr>")
        parts.append("</table>")
    parts.append("<h3>Figures</h3>")
    for fig in cfg.figures:
        rel = os.path.relpath(root / "figures" / f"{fig}.png", out_dir)
        parts.append(f'<figure><img src="{html.escape(rel)}" alt="{paper} {fig}">'
                     f"<figcaption>{html.escape(fig)}</figcaption></figure>")
    for table in cfg.tables:
        if table == "validation":
            continue
        h2, r2 = _read_csv(root / "tables" / f"{table}.csv")
        title = CAPTIONS.get(table, f"Table: {html.escape(table)}")
        parts.append(f"<h3>{title}</h3><table><tr>"
                     + "".join(f"<th>{html.escape(h)}</th>" for h in h2) + "</tr>"
                     + "".join("<tr>" + "".join(f"<td>{_fmt(c)}</td>" for c in row) + "</tr>"
                               for row in r2) + "</table>")
    return "\n".join(parts), {"independent": ind, "claim": claim}


def summary_section(out_dir: Path) -> str:
    """The cross-paper summary (cost of accuracy side by side) and the last rerun plan."""
    parts = []
    if (out_dir / "summary.csv").exists():
        head, rows = _read_csv(out_dir / "summary.csv")
        parts.append("<h2>Cost of accuracy, all papers</h2>"
                     '<figure><img src="cost_of_accuracy_all.png" alt="cost of accuracy, all papers">'
                     "<figcaption>error vs wall time per solve, each paper's headline quantity"
                     "</figcaption></figure><table><tr>"
                     + "".join(f"<th>{html.escape(h)}</th>" for h in head) + "</tr>"
                     + "".join("<tr>" + "".join(f"<td>{_fmt(c)}</td>" for c in r) + "</tr>"
                               for r in rows) + "</table>")
    if (out_dir.parent / "rerun_plan.html").exists():  # saved by `make reproduce`
        parts.append("<h2>Last rerun plan</h2><p class='note'>Why each job of the last "
                     "<code>make reproduce</code> ran (from Snakemake's log of that run, by "
                     "<code>python -m mechrepro.plan</code>).</p>"
                     '<iframe src="../rerun_plan.html" style="width:100%;height:320px;'
                     'border:1px solid #ccc"></iframe>')
    return "\n".join(parts)


def time_section(results: Path, papers: list[str]) -> str:
    """Per paper: the solves' own time against the solver jobs' wall time (start-up,
    imports, writing and repeated timing calls are the difference), and the paper's other
    jobs (validation, notebook)."""
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
        job = sum(float(x[head.index("job_s")]) for x in r)
        runs = sum(int(x[head.index("runs")]) for x in r)
        other = [benchmark_seconds(results / paper / "benchmarks" / f"{k}.tsv")
                 for k in ("validate", "notebook")]
        overhead = f"{(job - solve) / job:.0%}" if job > 0 else "n/a"
        rows.append(f"<tr><td>{paper}</td><td>{len(r)}</td><td>{runs}</td><td>{solve:.3g}</td>"
                    f"<td>{cell(job if job > 0 else float('nan'))}</td><td>{overhead}</td>"
                    + "".join(f"<td>{cell(x)}</td>" for x in other) + "</tr>")
    if not rows:
        return ""
    return ("<h2 id='time'>Where the time goes</h2><p class='note'>solve: the fastest call of "
            "each run's solve (<code>wall_time</code>), summed; job: the solver jobs' wall time "
            "from Snakemake's benchmark files; overhead: interpreter start, imports, repeated "
            "timing calls and writing. Each paper's <i>effect_cost</i> table splits the solves "
            "into the solver core and each effect. The validation job of a paper runs before "
            "this page is written; its notebook job too.</p><table><tr><th>paper</th>"
            "<th>solver jobs</th><th>runs</th><th>solve [s]</th><th>job [s]</th><th>overhead"
            "</th><th>validation job [s]</th><th>notebook job [s]</th></tr>"
            + "".join(rows) + "</table>")


def write_report(out: str, results: str, config_dir: str, papers: list[str], profile: str) -> None:
    out, results, config_dir = Path(out), Path(results), Path(config_dir)
    sections, summary = [], []
    for paper in papers:
        text, info = paper_section(paper, results, config_dir, profile, out.parent)
        sections.append(text)
        ind, claim = info["independent"], info["claim"]
        n_assumed = len(load_paper(config_dir / "papers" / f"{paper}.yaml", profile, CACHE_DIR).assumed())
        summary.append(f'<tr><td><a href="#{paper}">{paper}</a></td><td>{claim["claim"]}</td>'
                       + "".join(f'<td class="b-{s}">{ind.get(s, 0)}</td>'
                                 for s in VERDICTS)
                       + f'<td>{n_assumed}</td><td class="note">{html.escape(claim["text"])}</td></tr>')
    check_file = out.parent / "reference_check.txt"
    check = check_file.read_text() if check_file.exists() else "not run"
    drift = "" if check.splitlines()[0].endswith(": OK") else " drift"
    toc = "".join(f'<a href="#{p}">{p}</a>' for p in papers)
    now = _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")
    page = f"""<!doctype html><html><head><meta charset="utf-8">
<title>mechrepro reproduction report</title><style>{CSS}</style></head><body>
<h1>mechrepro reproduction report</h1>
<p class="note">profile <b>{html.escape(profile)}</b> &middot; code {html.escape(code_version())} &middot; {now}</p>
<nav class="toc"><a href="#summary">summary</a><a href="#reference">reference check</a>{toc}<a href="#cost">cost of accuracy</a><a href="#time">time</a></nav>
<h2 id="summary">Replication summary</h2>
<p class="note">Counts are of <b>independent</b> rows only (see each paper's rows by evidence class).</p>
<table><tr><th>paper</th><th>claim</th><th>pass</th><th>fail</th><th>inconclusive</th><th>not converged</th><th>assumed constants</th><th>what did not reproduce, and why</th></tr>
{''.join(summary)}</table>
<h2 id="reference">Reference check</h2>
<pre class="check{drift}">{html.escape(check)}</pre>
<div id="cost">{summary_section(out.parent)}</div>
{time_section(results, papers)}
{''.join(sections)}
<script>/* for `make screenshot`: the whole page's height once images are laid out */
window.addEventListener("load", () => document.body.dataset.height = document.documentElement.scrollHeight);</script>
</body></html>
"""
    write_text(out, page)
