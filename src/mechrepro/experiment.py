"""What-if experiments: a parameter variant run beside the baseline, what it changed, and
results restored from an archive.

    mechrepro exp run NAME --set chain_drive.static_tension=800 [--set ...] [--cores N]
    mechrepro exp show
    mechrepro diff A B [--out DIR]        # two result directories or archives
    mechrepro restore ARCHIVE [--into DIR]

An experiment lives in ``experiments/NAME/``: a working directory whose ``Snakefile``,
``workflow/``, ``src/`` and ``notebooks/`` are links to the project's, whose ``config/`` is
the project's with the overrides applied (validated exactly as the configs are, before any
job), and whose ``results/`` starts with hard links to every baseline result the change does
not touch: a run whose resolved record is unchanged, and every file of a paper whose config
is unchanged.  Snakemake then runs only what is missing or out of date, into the
experiment's own directory; the baseline is never written.
"""
from __future__ import annotations

import argparse
import csv
import datetime as _dt
import json
import math
import os
import shutil
import subprocess
import sys
import tarfile
import tempfile
import time
from pathlib import Path

import yaml

from .config import ConfigError, load_paper

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
        out.setdefault(paper, {})[path] = yaml.safe_load(value)
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


def _link_tree(src: Path, dst: Path) -> int:
    """Hard-link every file under ``src`` into ``dst`` (a copy across file systems)."""
    n = 0
    for f in src.rglob("*"):
        if f.is_file() and not f.name.startswith("."):
            n += _link(f, dst / f.relative_to(src))
    return n


def _link(f: Path, target: Path) -> int:
    target.parent.mkdir(parents=True, exist_ok=True)
    if target.exists():
        return 0
    try:
        os.link(f, target)
    except OSError:
        shutil.copy2(f, target)
    return 1


def prepare(name: str, sets: list[str], base: Path = Path("."), profile: str | None = None
            ) -> tuple[Path, dict]:
    """Make ``experiments/NAME``: links, overridden configs (validated), reused results."""
    base = base.resolve()
    top = yaml.safe_load((base / "config" / "config.yaml").read_text())
    profile = profile or top["profile"]
    overrides = parse_sets(sets)
    unknown = sorted(set(overrides) - set(top["papers"]))
    if unknown:
        raise ConfigError(f"--set: no paper {unknown}; papers: {', '.join(top['papers'])}")
    exp = base / "experiments" / name
    if exp.exists():
        raise ConfigError(f"experiment {name!r} exists ({exp}); remove it or choose another name")
    tmp = Path(tempfile.mkdtemp(prefix=f".{name}.", dir=base / "experiments"
                                if (base / "experiments").is_dir() else _mk(base / "experiments")))
    try:
        (tmp / "config" / "papers").mkdir(parents=True)
        for item in LINKED:
            (tmp / item).symlink_to(os.path.relpath(base / item, exp))
        (tmp / "config" / "schema").symlink_to(os.path.relpath(base / "config" / "schema",
                                                               exp / "config"))
        for extra in ("reference.yaml",):
            shutil.copy2(base / "config" / extra, tmp / "config" / extra)
        shutil.copy2(base / "config" / "config.yaml", tmp / "config" / "config.yaml")
        with open(tmp / "config" / "config.yaml", "a") as f:
            f.write(f"\n# experiment {name}\nprofile: {profile}\nresults: results\n")
        (tmp / "results").mkdir()
        (tmp / "results" / "reference").symlink_to(os.path.relpath(
            base / "results" / "reference", exp / "results"))
        results = base / top["results"]
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
                    reused += _link_tree(results / paper, tmp / "results" / paper)
                continue
            old = load_paper(src, profile)
            same = [r for r, rec in new.runs.items() if old.runs.get(r) == rec]
            for r in same:
                f = results / paper / "runs" / f"{r}.nc"
                if f.is_file():
                    reused += _link(f, tmp / "results" / paper / "runs" / f.name)
            for s, members in new.studies.items():
                f = results / paper / "studies" / f"{s}.nc"
                if set(members) <= set(same) and old.studies.get(s) == members and f.is_file():
                    reused += _link(f, tmp / "results" / paper / "studies" / f.name)
        record = {"name": name, "sets": sets, "profile": profile, "baseline": str(results),
                  "created": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
                  "reused_files": reused, "status": "prepared"}
        (tmp / "experiment.json").write_text(json.dumps(record, indent=2) + "\n")
        os.replace(tmp, exp)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    return exp, record


def _mk(p: Path) -> Path:
    p.mkdir(parents=True, exist_ok=True)
    return p


def run(name: str, sets: list[str], base: Path = Path("."), cores: int = 2,
        profile: str | None = None) -> dict:
    """Prepare the experiment and run the workflow in it; its record says what ran."""
    exp, record = prepare(name, sets, base, profile)
    t0 = time.perf_counter()
    # up to the report: an experiment's numbers differ from the committed reference by
    # design, so its reference check reports the drift and nothing is archived
    proc = subprocess.run([sys.executable, "-m", "snakemake", "--cores", str(cores),
                           "results/report/index.html"], cwd=exp, capture_output=True, text=True)
    (exp / "snakemake.log").write_text(proc.stdout + proc.stderr)
    record.update(status="done" if proc.returncode == 0 else "failed",
                  seconds=round(time.perf_counter() - t0, 1),
                  jobs=_jobs_run(proc.stdout + proc.stderr))
    (exp / "experiment.json").write_text(json.dumps(record, indent=2) + "\n")
    if proc.returncode:
        sys.stderr.write((proc.stdout + proc.stderr)[-3000:])
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
    """Every experiment's record, with each paper's claim counts."""
    out = []
    for f in sorted((base / "experiments").glob("*/experiment.json")):
        rec = json.loads(f.read_text())
        rec["claims"] = _claims(f.parent / "results")
        out.append(rec)
    return out


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

    # an experiment hard-links the runs it reuses: the same bytes need no reading as data
    # (the diff of a ci result set with itself took 124 s of a loaded test suite)
    if a.exists() and b.exists() and (os.path.samefile(a, b) or filecmp.cmp(a, b, shallow=False)):
        return False
    with open_dataset(a) as x, open_dataset(b) as y:
        names = set(x.data_vars) | set(y.data_vars)
        for v in names:
            if _is_timing(x.get(v, y.get(v))):
                continue   # timings differ on every run
            if v not in x or v not in y:
                return True
            p, q = x[v].values, y[v].values
            if p.shape != q.shape:
                return True
            if p.dtype.kind in "fc":
                if not np.allclose(p, q, rtol=1e-12, atol=0.0, equal_nan=True):
                    return True
            elif not np.array_equal(p, q):
                return True
    return False


def _unpack(path: Path, into: Path) -> Path:
    """A results directory, or an archive extracted (members checked) into ``into``."""
    if path.is_dir():
        return path
    with tarfile.open(path) as tar:
        tar.extractall(into, filter="data")
    return into


def diff(a: Path, b: Path, reference: Path = Path("results/reference"),
         profile: str = "default") -> dict:
    """What differs between two result sets (directories or archives): parameters, validation
    rows that moved beyond their reference tolerance or changed verdict, claims, figures
    whose data changed, and the time each took."""
    with tempfile.TemporaryDirectory() as tmp:
        a, b = _unpack(Path(a), Path(tmp) / "a"), _unpack(Path(b), Path(tmp) / "b")
        return _diff(a, b, reference, profile)


def _diff(a: Path, b: Path, reference: Path, profile: str) -> dict:
    ca, cb = _claims(a), _claims(b)
    papers = sorted(set(ca) | set(cb))
    out = {"a": str(a), "b": str(b), "papers": {}}
    for paper in papers:
        d: dict = {}
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
        claim = {}
        if (ca.get(paper) or {}).get("independent") != (cb.get(paper) or {}).get("independent") or \
                (ca.get(paper) or {}).get("claim") != (cb.get(paper) or {}).get("claim"):
            claim = {"a": {k: (ca.get(paper) or {}).get(k) for k in ("claim", "independent")},
                     "b": {k: (cb.get(paper) or {}).get(k) for k in ("claim", "independent")}}
        d = {"parameters": params, "rows": rows, "claim": claim, "runs_changed": changed,
             "figures_changed": figures, "time": {"a": _time(a, paper), "b": _time(b, paper)}}
        if params or rows or claim or changed:
            out["papers"][paper] = d
    return out


def _time(results: Path, paper: str) -> float:
    t = _table(results / paper / "tables" / "job_time.csv", key="job")
    return round(sum(_float(r.get("job_s")) for r in t.values() if math.isfinite(_float(r.get("job_s")))), 2)


def markdown(d: dict) -> str:
    if not d["papers"]:
        return f"No differences between {d['a']} and {d['b']}.\n"
    lines = [f"# Diff: {d['a']} -> {d['b']}", ""]
    for paper, p in d["papers"].items():
        lines += [f"## {paper}", ""]
        for k, (x, y) in p["parameters"].items():
            lines.append(f"- parameter `{k}`: {x} -> {y} (SI)")
        if p["claim"]:
            lines.append(f"- claim: {p['claim']['a']} -> {p['claim']['b']}")
        if p["rows"]:
            lines += ["", "| quantity | A | B | unit | verdict A | verdict B |", "|---|---|---|---|---|---|"]
            lines += [f"| {r['quantity']} | {r['a']} | {r['b']} | {r['unit']} | {r['status_a']} "
                      f"({r['evidence_a']}) | {r['status_b']} ({r['evidence_b']}) |" for r in p["rows"]]
        lines += ["", f"- runs whose data changed: {len(p['runs_changed'])}; figures redrawn from "
                      f"them: {', '.join(p['figures_changed']) or 'none'}",
                  f"- solver job time: A {p['time']['a']} s, B {p['time']['b']} s", ""]
    return "\n".join(lines) + "\n"


def write_diff(d: dict, out: Path) -> None:
    """``diff.json``, ``diff.md`` and ``diff.html`` (changed figures side by side)."""
    import html

    from .io import write_json, write_text

    out.mkdir(parents=True, exist_ok=True)
    write_json(out / "diff.json", d)
    md = markdown(d)
    write_text(out / "diff.md", md)
    parts = [f"<!doctype html><html><head><meta charset='utf-8'><title>diff</title><style>"
             "body{font-family:system-ui,sans-serif;max-width:1180px;margin:1em auto;padding:0 12px}"
             "img{max-width:100%}.pair{display:grid;grid-template-columns:1fr 1fr;gap:8px}"
             "pre{white-space:pre-wrap}</style></head><body>", f"<pre>{html.escape(md)}</pre>"]
    for paper, p in d["papers"].items():
        for fig in p["figures_changed"]:
            fa = os.path.relpath(Path(d["a"]) / paper / "figures" / fig, out)
            fb = os.path.relpath(Path(d["b"]) / paper / "figures" / fig, out)
            parts.append(f"<h3>{paper} {html.escape(fig)}</h3><div class='pair'>"
                         f"<figure><img src='{html.escape(fa)}' alt='A {fig}'><figcaption>A</figcaption></figure>"
                         f"<figure><img src='{html.escape(fb)}' alt='B {fig}'><figcaption>B</figcaption></figure></div>")
    write_text(out / "diff.html", "".join(parts) + "</body></html>")


# --- restore -----------------------------------------------------------------------------

def restore(archive: Path, into: Path = Path(".")) -> int:
    """Put an archive's results into a project checkout so that the pipeline schedules
    nothing: every member is checked against the archive's manifest first, then the files
    are moved into ``results/`` with one time stamp, newer than the checkout's sources."""
    from .provenance import file_sha256

    into = Path(into)
    with tempfile.TemporaryDirectory(dir=into) as tmp:
        tmp = Path(tmp)
        with tarfile.open(archive) as tar:
            tar.extractall(tmp, filter="data")
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
    d.add_argument("--out", type=Path, help="write diff.json, diff.md, diff.html here")
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
                d = diff(Path(rec["baseline"]), Path("experiments") / args.name / "results",
                         profile=rec["profile"])
                write_diff(d, Path("experiments") / args.name / "diff")
                print(markdown(d))
            return 0 if rec["status"] == "done" else 1
        if args.cmd == "exp":
            for rec in show():
                counts = {p: c["independent"] for p, c in rec["claims"].items()}
                print(f"{rec['name']}: {rec['status']} {' '.join(rec['sets'])} {counts}")
            return 0
        if args.cmd == "diff":
            d = diff(args.a, args.b, profile=args.profile)
            if args.out:
                write_diff(d, args.out)
            print(markdown(d), end="")
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
        sys.stderr.write(f"mechrepro: {exc}\n")
        return 2


if __name__ == "__main__":
    sys.exit(main())
