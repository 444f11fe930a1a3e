"""What-if experiments: a parameter variant run beside the baseline, what it changed, and
results restored from an archive.

    mechrepro exp run NAME --set chain_drive.static_tension=800 [--set ...] [--cores N]
    mechrepro exp show
    mechrepro diff A B [--out DIR]        # two result directories or archives
    mechrepro restore ARCHIVE [--into DIR]

An experiment lives in ``experiments/NAME/``: a working directory whose ``Snakefile``,
``workflow/``, ``src/`` and ``notebooks/`` are links to the project's, whose ``config/`` is
the project's with the overrides applied (validated exactly as the configs are, before any
job), and whose ``results/`` starts with copies of every baseline result the change does
not touch: a run whose resolved record is unchanged, and every file of a paper whose config
is unchanged.  Snakemake then runs only what is missing or out of date, into the
experiment's own directory.

The baseline is never written because none of its results is shared: they are copied with
their checksum records, never hard-linked (only the committed reference, which no job
writes, is a link).  Snakemake writes in place into files it did not
create (it rewrites a job's benchmark file, puts a failed job's ``update()`` outputs back by
copying a backup over them, touches outputs after their job), so through a link an
experiment's job would write the baseline.  For the same reason an experiment runs the
profile its baseline was made with (the resolution its run files record) or is refused:
reused results of another profile would pass for this one's.
"""
from __future__ import annotations

import argparse
import csv
import datetime as _dt
import html
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tarfile
import tempfile
import time
from pathlib import Path

import yaml

from .config import ConfigError, load_paper, workflow_config

LINKED = ("Snakefile", "workflow", "src", "notebooks", "profiles")


# --- experiments -------------------------------------------------------------------------

def parse_sets(sets: list[str]) -> dict[str, dict[str, object]]:
    """``["chain_drive.static_tension=800"]`` -> {"chain_drive": {"static_tension": 800}}.
    A key with more dots is a path into the paper file (``saw_chain.scenes.fig07_fig08.
    resolution.K=2000``); a single name is a parameter's value, in the paper's own unit."""
    out: dict[str, dict[str, object]] = {}
    for item in sets:
        key, sep, value = item.partition("=")
        paper, dot, path = key.partition(".")
        if not sep or not dot or not path:
            raise ConfigError(f"--set {item!r}: expected PAPER.PARAMETER=VALUE "
                              "(e.g. chain_drive.static_tension=800)")
        value = yaml.safe_load(value)
        if isinstance(value, str) and re.fullmatch(r"[-+]?\d+[eE][-+]?\d+", value):
            value = float(value)    # YAML 1.1 reads 1e-14 as text
        out.setdefault(paper, {})[path] = value
    return out


def apply_sets(raw: dict, sets: dict[str, object], where: str) -> dict:
    """The paper config with the overrides applied (the loader validates the result)."""
    for path, value in sets.items():
        keys = path.split(".")
        if len(keys) == 1:
            if keys[0] not in raw["parameters"]:
                raise ConfigError(f"{where}: --set {path}: not a parameter; parameters: "
                                  f"{', '.join(raw['parameters'])}")
            raw["parameters"][keys[0]]["value"] = value
            continue
        node = raw
        for k in keys[:-1]:
            if not isinstance(node, dict) or k not in node:
                raise ConfigError(f"{where}: --set {path}: no key {k!r}")
            node = node[k]
        node[keys[-1]] = value
    return raw


def _copy_tree(src: Path, dst: Path) -> int:
    """Copy every result under ``src`` into ``dst`` (temporary files of killed jobs left out)."""
    return sum(_copy(f, dst / f.relative_to(src)) for f in sorted(src.rglob("*"))
               if f.is_file() and not f.name.startswith("."))


def _copy(f: Path, target: Path) -> int:
    """Copy a result and its checksum record, time stamps kept: to heal and Snakemake the
    copy is the result its job wrote."""
    from .io import sum_path

    target.parent.mkdir(parents=True, exist_ok=True)
    for src, dst in ((f, target), (sum_path(f), sum_path(target))):
        if src.is_file():
            shutil.copy2(src, dst)
    return 1


def _made_with(results: Path, config: Path, paper: str) -> tuple[set[str], str] | None:
    """The profiles of ``config`` whose resolution of a run is the one its baseline file
    records, judged on the first run whose resolution differs between the profiles and
    whose file is there, with the evidence (None: no such file tells the profiles apart)."""
    import netCDF4

    cfgs = {"default": load_paper(config)}
    cfgs.update({p: load_paper(config, p) for p in cfgs["default"].raw.get("profiles", {})})
    for run in sorted(set.intersection(*(set(c.runs) for c in cfgs.values()))):
        res = {p: json.dumps(c.runs[run]["resolution"], sort_keys=True) for p, c in cfgs.items()}
        f = results / paper / "runs" / f"{run}.nc"
        if len(set(res.values())) == 1 or not f.is_file():
            continue
        try:
            with netCDF4.Dataset(f) as ds:
                got = ds.getncattr("resolution") if "resolution" in ds.ncattrs() else ""
        except OSError:
            continue     # unreadable: heal removes it, another run tells
        return {p for p, r in res.items() if r == got}, f"{f} records resolution {got}"
    return None


def _profile(name: str, profile: str | None, top: dict, results: Path, base: Path) -> str:
    """The experiment's profile: the baseline's (or ``profile``, refused unless it is)."""
    made = {p: m for p in top["papers"]
            if (m := _made_with(results, base / "config" / "papers" / f"{p}.yaml", p))}
    if profile is None:
        common = set.intersection(*(m[0] for m in made.values())) if made else set()
        profile = top["profile"] if not common or top["profile"] in common else min(common)
    for paper, (profiles, why) in made.items():
        if profile not in profiles:
            fix = (f"run it with --profile {min(profiles)}" if profiles else
                   "the baseline is older than its config: run it again first")
            raise ConfigError(
                f"experiment {name!r}: profile {profile!r}, but the baseline's {paper} results "
                f"were made with profile {' or '.join(map(repr, sorted(profiles))) or 'none'} "
                f"({why}); an experiment reuses the baseline's results, so the profiles must "
                f"match: {fix}")
    return profile


def prepare(name: str, sets: list[str], base: Path = Path("."), profile: str | None = None
            ) -> tuple[Path, dict]:
    """Make ``experiments/NAME``: links to the code, overridden configs (validated), copies
    of the reused results.  ``profile`` defaults to the baseline's."""
    base = base.resolve()
    top = workflow_config(base / "config" / "config.yaml")
    overrides = parse_sets(sets)
    unknown = sorted(set(overrides) - set(top["papers"]))
    if unknown:
        raise ConfigError(f"--set: no paper {unknown}; papers: {', '.join(top['papers'])}")
    results = base / top["results"]
    profile = _profile(name, profile, top, results, base)
    exp = base / "experiments" / name
    if exp.exists():
        raise ConfigError(f"experiment {name!r} exists ({exp}); remove it or choose another name")
    (base / "experiments").mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{name}.", dir=base / "experiments"))
    try:
        (tmp / "config" / "papers").mkdir(parents=True)
        for item in LINKED:
            (tmp / item).symlink_to(os.path.relpath(base / item, exp))
        (tmp / "config" / "schema").symlink_to(os.path.relpath(base / "config" / "schema",
                                                               exp / "config"))
        for extra in ("reference.yaml", "costs.csv"):
            shutil.copy2(base / "config" / extra, tmp / "config" / extra)
        (tmp / "config" / "config.yaml").write_text(
            f"# config/config.yaml of the project for experiment {name}\n"
            + yaml.safe_dump({**top, "profile": profile, "results": "results"}, sort_keys=False))
        (tmp / "results").mkdir()
        (tmp / "results" / "reference").symlink_to(os.path.relpath(
            base / "results" / "reference", exp / "results"))
        reused = 0
        for paper in top["papers"]:
            src = base / "config" / "papers" / f"{paper}.yaml"
            dst = tmp / "config" / "papers" / f"{paper}.yaml"
            if paper in overrides:
                raw = yaml.safe_load(src.read_text())
                apply_sets(raw, overrides[paper], str(src))
                dst.write_text(f"# {src.name} with the overrides of experiment {name}\n"
                               + yaml.safe_dump(raw, sort_keys=False, allow_unicode=True))
            else:
                shutil.copy2(src, dst)
            st = src.stat()
            os.utime(dst, ns=(st.st_atime_ns, st.st_mtime_ns))   # an edit, not a new file
            new = load_paper(dst, profile)            # refused here, before any job
            if paper not in overrides:
                if (results / paper).is_dir():
                    reused += _copy_tree(results / paper, tmp / "results" / paper)
                continue
            old = load_paper(src, profile)
            same = [r for r, rec in new.runs.items() if old.runs.get(r) == rec]
            for r in same:
                f = results / paper / "runs" / f"{r}.nc"
                if f.is_file():
                    reused += _copy(f, tmp / "results" / paper / "runs" / f.name)
            for s, members in new.studies.items():
                f = results / paper / "studies" / f"{s}.nc"
                if set(members) <= set(same) and old.studies.get(s) == members and f.is_file():
                    reused += _copy(f, tmp / "results" / paper / "studies" / f.name)
        record = {"name": name, "sets": sets, "profile": profile, "baseline": str(results),
                  "created": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
                  "reused_files": reused, "status": "prepared"}
        (tmp / "experiment.json").write_text(json.dumps(record, indent=2) + "\n")
        os.replace(tmp, exp)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    return exp, record


def _record(exp: Path, record: dict, **changes) -> None:
    from .io import write_text

    record.update(changes)
    write_text(exp / "experiment.json", json.dumps(record, indent=2) + "\n", record=False)


def run(name: str, sets: list[str], base: Path = Path("."), cores: int = 2,
        profile: str | None = None) -> dict:
    """Prepare the experiment and run the workflow in it.  Its record says "running" (with
    this process's id) while Snakemake runs, then "done" or "failed" (also when interrupted),
    and what ran."""
    exp, record = prepare(name, sets, base, profile)
    _record(exp, record, status="running", pid=os.getpid())
    t0, log = time.perf_counter(), None
    try:
        # up to the report, never the archive: an experiment's numbers differ from the
        # committed reference by design, so its reference check reports the drift
        proc = subprocess.run([sys.executable, "-m", "snakemake", "--cores", str(cores),
                               "--omit-from", "archive", "results/report/index.html"],
                              cwd=exp, capture_output=True, text=True)
        log = proc.stdout + proc.stderr
        (exp / "snakemake.log").write_text(log)
    finally:
        record.pop("pid")
        ok = log is not None and proc.returncode == 0
        _record(exp, record, status="done" if ok else "failed",
                seconds=round(time.perf_counter() - t0, 1), jobs=_jobs_run(log or ""))
    if record["status"] != "done":
        sys.stderr.write(log[-3000:])
    return record


def _jobs_run(log: str) -> dict[str, int]:
    """{rule: jobs} of a Snakemake run, from its 'Job stats' table."""
    jobs, on = {}, False
    for line in log.splitlines():
        if line.startswith("job ") and "count" in line:
            on = True
            continue
        if on:
            parts = line.split()
            if len(parts) == 2 and parts[1].isdigit():
                if parts[0] != "total":
                    jobs[parts[0]] = int(parts[1])
            elif not set(line.strip()) <= {"-", " "}:
                break
    return jobs


def show(base: Path = Path(".")) -> list[dict]:
    """Every experiment's record, with each paper's claim counts when it is done (the
    results of one not done are partly the baseline's copies).  One still "running" whose
    process is gone was killed: failed."""
    out = []
    for f in sorted((base / "experiments").glob("*/experiment.json")):
        rec = json.loads(f.read_text())
        if rec.get("status") == "running" and not _alive(rec.get("pid")):
            rec["status"] = "failed"
        rec["claims"] = _claims(f.parent / "results") if rec.get("status") == "done" else {}
        out.append(rec)
    return out


def _alive(pid) -> bool:
    try:
        os.kill(int(pid), 0)
    except (TypeError, ValueError, ProcessLookupError):
        return False
    except PermissionError:
        pass
    return True


# --- diffs -------------------------------------------------------------------------------

def _claims(results: Path) -> dict[str, dict]:
    return {c.parent.name: json.loads(c.read_text()) for c in sorted(results.glob("*/claim.json"))}


def _table(path: Path, key: str = "quantity") -> dict[str, dict]:
    if not path.is_file():
        return {}
    with open(path, newline="") as f:
        return {r[key]: r for r in csv.DictReader(f)}


def _float(x: str) -> float:
    try:
        return float(x)
    except (TypeError, ValueError):
        return math.nan


def _run_parameters(results: Path, paper: str) -> dict[str, dict]:
    """{scene run: parameters} of a paper's base scene runs (no variants, no study points)."""
    import netCDF4

    out = {}
    for f in sorted((results / paper / "runs").glob("*.nc")):
        if "@" in f.stem or f.stem[-4:-3] == "-" and f.stem[-3:].isdigit():
            continue
        with netCDF4.Dataset(f) as ds:
            p = json.loads(ds.getncattr("parameters")) if "parameters" in ds.ncattrs() else {}
        # {"values_si": {...}, ...}: one level flattened, so that each parameter is a key
        out[f.stem] = {(f"{k}.{j}" if k != "values_si" else j): w
                       for k, v in p.items() for j, w in (v.items() if isinstance(v, dict) else [("", v)])}
    return out


def _is_timing(var) -> bool:
    """A measured wall time (the framework's ``wall_time``/``core_time``/``effect_time``
    and the models' ``*_time_*``): seconds whose name says time."""
    return var.attrs.get("units") == "s" and "time" in var.name and var.name not in var.dims


def _data_differs(a: Path, b: Path) -> bool:
    """Whether two run files hold different data (attributes such as times ignored)."""
    import filecmp

    import numpy as np

    from .io import open_dataset

    # an experiment copies the runs it reuses: the same bytes need no reading as data
    if a.exists() and b.exists() and (os.path.samefile(a, b) or filecmp.cmp(a, b, shallow=False)):
        return False
    with open_dataset(a) as x, open_dataset(b) as y:
        for v in set(x.data_vars) | set(y.data_vars):
            if _is_timing(x.get(v, y.get(v))):
                continue   # timings differ on every run
            if v not in x or v not in y:
                return True
            p, q = x[v].values, y[v].values
            if p.shape != q.shape or not (np.allclose(p, q, rtol=1e-12, atol=0.0, equal_nan=True)
                                          if p.dtype.kind in "fc" else np.array_equal(p, q)):
                return True
    return False


def _extract(archive: Path, into: Path) -> None:
    """Extract ``archive`` into ``into`` after checking every member: one with an absolute
    path, one climbing out (``..``) or one tarfile's data filter refuses (a link out, a
    device) is named and nothing is extracted (the filter alone strips a leading ``/`` and
    extracts the members before a bad one)."""
    try:
        with tarfile.open(archive) as tar:
            members = tar.getmembers()
            for m in members:
                name = Path(m.name)
                why = ("has an absolute path" if name.is_absolute() else
                       "climbs out of the destination" if ".." in name.parts else None)
                if why is None:
                    try:
                        tarfile.data_filter(m, str(into))
                    except tarfile.FilterError as exc:
                        why = f"is refused by tarfile's data filter ({type(exc).__name__})"
                if why:
                    raise ValueError(f"{archive}: member {m.name!r} {why}; nothing was extracted")
            tar.extractall(into, members=members, filter="data")
    except tarfile.TarError as exc:
        raise ValueError(f"{archive}: not a readable archive ({exc})") from None


def _unpack(path: Path, into: Path) -> Path:
    """A results directory, or an archive extracted (members checked) into ``into``."""
    if path.is_dir():
        return path
    _extract(path, into)
    return into


def diff(a: Path, b: Path, reference: Path = Path("results/reference"),
         profile: str = "default", out: Path | None = None) -> dict:
    """What differs between two result sets (directories or archives): parameters, validation
    rows that moved beyond their reference tolerance or changed verdict, claims, figures
    whose data changed, and the time each took.  With ``out``, the page (:func:`write_diff`)
    is written there while an archive side is still extracted."""
    with tempfile.TemporaryDirectory() as tmp:
        da, db = _unpack(Path(a), Path(tmp) / "a"), _unpack(Path(b), Path(tmp) / "b")
        d = {**_diff(da, db, reference, profile), "a": str(a), "b": str(b)}
        if out is not None:
            write_diff(d, Path(out), da, db)
    return d


def _diff(a: Path, b: Path, reference: Path, profile: str) -> dict:
    ca, cb = _claims(a), _claims(b)
    papers = sorted(set(ca) | set(cb))
    out = {"a": str(a), "b": str(b), "papers": {}}
    for paper in papers:
        pa, pb = _run_parameters(a, paper), _run_parameters(b, paper)
        params = {}
        for run in sorted(set(pa) & set(pb)):
            for k in sorted(set(pa[run]) | set(pb[run])):
                if pa[run].get(k) != pb[run].get(k) and k not in params:
                    params[k] = [pa[run].get(k), pb[run].get(k)]
        ta = _table(a / paper / "tables" / "validation.csv")
        tb = _table(b / paper / "tables" / "validation.csv")
        ref = _table(reference / profile / f"{paper}.csv")
        tol = {q: _float(r.get("tolerance")) for q, r in ref.items()}
        rows = []
        for q in sorted(set(ta) | set(tb)):
            if ref.get(q, {}).get("basis") == "timing":
                continue   # wall-clock quantities differ on every run
            ra, rb = ta.get(q, {}), tb.get(q, {})
            va, vb = _float(ra.get("reproduced_value")), _float(rb.get("reproduced_value"))
            t = tol.get(q, math.nan)
            t = t if math.isfinite(t) else 1e-9 * max(abs(va), abs(vb), 1e-300)
            moved = not (va == vb or (math.isnan(va) and math.isnan(vb))) and not abs(va - vb) <= t
            if moved or ra.get("status") != rb.get("status") or ra.get("evidence") != rb.get("evidence"):
                rows.append({"quantity": q, "a": ra.get("reproduced_value", ""),
                             "b": rb.get("reproduced_value", ""), "unit": rb.get("unit") or ra.get("unit", ""),
                             "status_a": ra.get("status", ""), "status_b": rb.get("status", ""),
                             "evidence_a": ra.get("evidence", ""), "evidence_b": rb.get("evidence", "")})
        runs_a = {f.name for f in (a / paper / "runs").glob("*.nc")}
        runs_b = {f.name for f in (b / paper / "runs").glob("*.nc")}
        changed = sorted((runs_a ^ runs_b) | {n for n in runs_a & runs_b
                                              if _data_differs(a / paper / "runs" / n, b / paper / "runs" / n)})
        figures = sorted(f.name for f in (b / paper / "figures").glob("*.png")) if changed else []
        claim = {side: {k: (c.get(paper) or {}).get(k) for k in ("claim", "independent")}
                 for side, c in (("a", ca), ("b", cb))}
        claim = claim if claim["a"] != claim["b"] else {}
        d = {"parameters": params, "rows": rows, "claim": claim, "runs_changed": changed,
             "figures_changed": figures, "time": {"a": _time(a, paper), "b": _time(b, paper)}}
        if params or rows or claim or changed:
            out["papers"][paper] = d
    return out


def _time(results: Path, paper: str) -> float:
    t = _table(results / paper / "tables" / "job_time.csv", key="job")
    return round(sum(_float(r.get("job_s")) for r in t.values() if math.isfinite(_float(r.get("job_s")))), 2)


def _fmt(v) -> str:
    """A value as a reader wants it: numbers to 10 digits, structures as JSON, none as -."""
    if v is None:
        return "-"
    if isinstance(v, float):
        return f"{v:.10g}"
    return v if isinstance(v, str) else json.dumps(v, sort_keys=True)


def _claim(c: dict) -> str:
    """``partial (pass 2, fail 5)``: a claim and its independent rows' verdicts."""
    counts = ", ".join(f"{k} {v}" for k, v in (c.get("independent") or {}).items())
    return f"{c.get('claim') or 'none'} ({counts or 'no independent rows'})"


def markdown(d: dict) -> str:
    if not d["papers"]:
        return f"No differences between {d['a']} and {d['b']}.\n"
    lines = [f"# Diff: {d['a']} -> {d['b']}", ""]
    for paper, p in d["papers"].items():
        lines += [f"## {paper}", ""]
        for k, (x, y) in p["parameters"].items():
            lines.append(f"- parameter `{k}`: {_fmt(x)} -> {_fmt(y)} (SI)")
        if p["claim"]:
            lines.append(f"- claim: {_claim(p['claim']['a'])} -> {_claim(p['claim']['b'])}")
        if p["rows"]:
            lines += ["", "| quantity | A | B | unit | verdict A | verdict B |", "|---|---|---|---|---|---|"]
            lines += [f"| {r['quantity']} | {r['a']} | {r['b']} | {r['unit']} | {r['status_a']} "
                      f"({r['evidence_a']}) | {r['status_b']} ({r['evidence_b']}) |" for r in p["rows"]]
        lines += ["", f"- runs whose data changed: {len(p['runs_changed'])}; figures redrawn from "
                      f"them: {', '.join(p['figures_changed']) or 'none'}",
                  f"- solver job time: A {p['time']['a']} s, B {p['time']['b']} s", ""]
    return "\n".join(lines) + "\n"


def _html_table(head: list[str], rows: list[list]) -> str:
    def tr(tag, cells):
        return "<tr>" + "".join(f"<{tag}>{html.escape(_fmt(c))}</{tag}>" for c in cells) + "</tr>"
    return "<table>" + tr("th", head) + "".join(tr("td", r) for r in rows) + "</table>"


STYLE = ("body{font-family:system-ui,sans-serif;max-width:1180px;margin:1em auto;padding:0 12px}"
         "table{border-collapse:collapse;margin:.5em 0}th,td{border:1px solid #ccc;padding:2px 6px;"
         "text-align:left}.pair{display:grid;grid-template-columns:1fr 1fr;gap:8px}"
         ".pair img{width:100%}.note{color:#555}")


def write_diff(d: dict, out: Path, a: Path | None = None, b: Path | None = None) -> None:
    """``diff.json``, ``diff.md`` and ``diff.html``: per paper tables of the parameters,
    claims and validation rows that differ, and the changed figures of both sides at one
    width, copied from the result sets ``a`` and ``b`` (default: the diff's own) into
    ``out/figures/``, so that the page outlives an extracted archive."""
    from .io import write_json, write_text

    esc = html.escape
    out.mkdir(parents=True, exist_ok=True)
    write_json(out / "diff.json", d)
    write_text(out / "diff.md", markdown(d))
    parts = [f"<!doctype html><html><head><meta charset='utf-8'><title>diff</title><style>{STYLE}"
             f"</style></head><body><h1>Diff</h1><p>A: <code>{esc(d['a'])}</code><br>B: "
             f"<code>{esc(d['b'])}</code></p>" + ("" if d["papers"] else "<p>No differences.</p>")]
    for paper, p in d["papers"].items():
        parts.append(f"<h2>{esc(paper)}</h2>")
        if p["parameters"]:
            parts += ["<h3>Parameters that differ (SI)</h3>", _html_table(
                ["parameter", "A", "B"], [[k, x, y] for k, (x, y) in p["parameters"].items()])]
        if p["claim"]:
            parts += ["<h3>Claim</h3>", _html_table(["", "A", "B"], [[
                "claim (independent rows)", _claim(p["claim"]["a"]), _claim(p["claim"]["b"])]])]
        if p["rows"]:
            parts += ["<h3>Validation rows that moved beyond their tolerance or changed "
                      "verdict</h3>", _html_table(
                          ["quantity", "A", "B", "unit", "verdict A", "verdict B"],
                          [[r["quantity"], r["a"], r["b"], r["unit"],
                            f"{r['status_a']} ({r['evidence_a']})",
                            f"{r['status_b']} ({r['evidence_b']})"] for r in p["rows"]])]
        parts.append(f"<p>Runs whose data changed: {len(p['runs_changed'])}. Solver job time: "
                     f"A {_fmt(p['time']['a'])} s, B {_fmt(p['time']['b'])} s.</p>")
        if p["figures_changed"]:
            parts.append("<h3>Figures drawn from the changed runs</h3><p class='note'>Each side "
                         "as its notebook drew it, at the same width; each keeps its own axes: "
                         "compare the tick labels, not the positions.</p>")
        for fig in p["figures_changed"]:
            cells = []
            for side, root in (("A", a or d["a"]), ("B", b or d["b"])):
                src, rel = Path(root, paper, "figures", fig), Path("figures", side, paper, fig)
                if not src.is_file():
                    cells.append(f"<p>{side}: not drawn</p>")
                    continue
                (out / rel).parent.mkdir(parents=True, exist_ok=True)
                shutil.copy2(src, out / rel)
                cells.append(f"<figure><img src=\"{esc(rel.as_posix())}\" alt=\"{side} "
                             f"{esc(fig)}\"><figcaption>{side}</figcaption></figure>")
            parts.append(f"<h4>{esc(fig)}</h4><div class='pair'>{''.join(cells)}</div>")
    write_text(out / "diff.html", "".join(parts) + "</body></html>\n")


# --- restore -----------------------------------------------------------------------------

def restore(archive: Path, into: Path = Path(".")) -> int:
    """Put an archive's results into a project checkout so that the pipeline schedules
    nothing: every member is checked against the archive's manifest first, then the files
    are moved into ``results/`` with one time stamp, newer than the checkout's sources."""
    from .provenance import file_sha256

    into = Path(into)
    with tempfile.TemporaryDirectory(dir=into) as tmp:
        tmp = Path(tmp)
        _extract(archive, tmp)
        man = json.loads((tmp / "manifest.json").read_text())
        bad = [rel for rel, sha in man["files"].items()
               if not (tmp / rel).is_file() or file_sha256(tmp / rel) != sha]
        if bad:
            raise ValueError(f"{archive}: {len(bad)} files differ from its manifest, e.g. {bad[:3]}")
        results = into / "results"
        clash = [rel for rel in man["files"] if (results / rel).exists()]
        if clash:
            raise ValueError(f"{results}: would overwrite {len(clash)} results, e.g. {clash[:3]}; "
                             "restore into a fresh checkout")
        now = time.time()
        for rel in man["files"]:
            dst = results / rel
            dst.parent.mkdir(parents=True, exist_ok=True)
            os.replace(tmp / rel, dst)
            os.utime(dst, (now, now))
        arch = results / "archive"
        arch.mkdir(parents=True, exist_ok=True)
        shutil.copy2(archive, arch / "mechrepro-results.tar.gz")
        os.replace(tmp / "manifest.json", arch / "manifest.json")
        for f in arch.iterdir():
            os.utime(f, (now + 1, now + 1))   # made after what it archives
    return len(man["files"])


# --- command line ------------------------------------------------------------------------

def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(
        prog="mechrepro", description=__doc__.split("\n\n")[0],
        epilog="Run it in the project directory (the one with config/ and Snakefile). The "
               "full reproduction is `make reproduce`; `python -m mechrepro.heal --help` and "
               "`python -m mechrepro.cli --help` list the workflow's own commands.")
    sub = ap.add_subparsers(dest="cmd", required=True)
    e = sub.add_parser("exp", help="what-if experiments").add_subparsers(dest="what", required=True)
    r = e.add_parser("run", help="run a parameter variant beside the baseline")
    r.add_argument("name", help="the experiment's name: its directory is experiments/NAME/")
    r.add_argument("--set", action="append", default=[], dest="sets", metavar="PAPER.KEY=VALUE",
                   help="a parameter override, e.g. chain_drive.static_tension=800 (repeatable)")
    r.add_argument("--cores", type=int, default=2, help="cores for Snakemake (default 2)")
    r.add_argument("--profile", help="config profile (default: the baseline's)")
    e.add_parser("show", help="list experiments")
    d = sub.add_parser("diff", help="what differs between two result sets")
    d.add_argument("a", type=Path)
    d.add_argument("b", type=Path)
    d.add_argument("--out", type=Path, help="write diff.json, diff.md, diff.html (with the "
                   "figures it shows) here")
    d.add_argument("--profile", default="default", help="whose reference tolerances to use")
    s = sub.add_parser("restore", help="put an archive's results into this checkout")
    s.add_argument("archive", type=Path)
    s.add_argument("--into", type=Path, default=Path("."))
    args = ap.parse_args(argv)
    try:
        if args.cmd == "exp" and args.what == "run":
            rec = run(args.name, args.sets, cores=args.cores, profile=args.profile)
            print(json.dumps(rec, indent=2))
            if rec["status"] == "done":
                exp = Path("experiments") / args.name
                print(markdown(diff(Path(rec["baseline"]), exp / "results",
                                    profile=rec["profile"], out=exp / "diff")))
            return 0 if rec["status"] == "done" else 1
        if args.cmd == "exp":
            for rec in show():
                claims = "; ".join(f"{p} {_claim(c)}" for p, c in rec["claims"].items())
                print(f"{rec['name']}: {rec['status']} {' '.join(rec['sets']) or '(no --set)'}"
                      + (f": {claims}" if claims else ""))
            return 0
        if args.cmd == "diff":
            print(markdown(diff(args.a, args.b, profile=args.profile, out=args.out)), end="")
            return 0
        n = restore(args.archive, args.into)
        print(f"restored {n} result files from {args.archive}")
        return 0
    except FileNotFoundError as exc:
        where = ("; run mechrepro in the project directory (the one with config/ and "
                 "Snakefile)" if "config" in str(exc.filename or "") else "")
        sys.stderr.write(f"mechrepro: {exc.filename}: no such file{where}\n")
        return 2
    except (ConfigError, ValueError, OSError) as exc:
        where = ("; run mechrepro in the project directory (the one with config/ and "
                 "Snakefile)" if not Path("config/config.yaml").is_file() else "")
        sys.stderr.write(f"mechrepro: {exc}{where}\n")
        return 2


if __name__ == "__main__":
    sys.exit(main())
