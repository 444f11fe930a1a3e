"""Reference numbers that hold on any machine: tolerances measured across platform variants.

``make reference`` (:func:`measure` then :func:`derive`) runs a profile once per platform
variant of ``config/reference.yaml`` (other BLAS kernels, numpy SIMD limited to the
baseline, another BLAS thread count) and writes ``results/reference/<profile>/<paper>.csv``:

    quantity, reproduced_value, status, basis, spread, tolerance, variants, evidence, inputs

``spread`` is the largest difference from the native value over the variants, and
``tolerance = max(safety * spread, floor * |value|)``.  ``inputs`` is a digest of what the
row's value is computed from (:func:`row_inputs`): when a regeneration finds the committed
row made from the same inputs, its value is one more observation (variant ``previous``,
most often another machine's) and its spread is kept, so that the tolerance covers the
machines the reference was ever made on.  ``basis`` says what is compared:
``value`` (value within tolerance and same verdict), ``verdict`` (only the status: a
round-off-level residual, declared ``drift: verdict`` with a reason) or ``timing``
(nothing: wall-clock quantities never enter the check).  A verdict that differs between
the variants is refused: such a quantity is not well defined and must be fixed at its
source.

:func:`check` compares a results tree with the reference (the ``reference_check`` rule).
"""
from __future__ import annotations

import csv
import hashlib
import io
import math
import os
import subprocess
import sys
import time
from pathlib import Path

import yaml

from .config import load_paper, workflow_config
from .io import write_text
from .provenance import SRC_ROOT, json_hash, package_versions
from .validation import read_table

HEADER = ["quantity", "reproduced_value", "status", "basis", "spread", "tolerance", "variants",
          "evidence", "inputs"]
# what every reference file has (older ones lack the evidence class)
REQUIRED = HEADER[:7]


class DriftError(RuntimeError):
    pass


class ResultFileError(ValueError):
    """A result or reference file cannot be read as expected (names file, row, value)."""


def settings(config_dir: str | Path) -> dict:
    return yaml.safe_load((Path(config_dir) / "reference.yaml").read_text())


def variant_env(spec: dict) -> dict:
    return {**os.environ, **{k: str(v) for k, v in spec.get("env", {}).items()}}


def measure(profile: str, papers: list[str], workdir: str | Path, config_dir: str | Path,
            cores: int = 2, variants: list[str] | None = None) -> dict[str, Path]:
    """Run the pipeline of ``profile`` once per platform variant into ``workdir/<variant>``."""
    conf = settings(config_dir)
    names = variants or list(conf["variants"])
    out = {}
    for i, name in enumerate(names, 1):
        spec = conf["variants"][name]
        res = Path(workdir) / name
        targets = [f"{res}/{p}/tables/validation.csv" for p in papers]
        cmd = [sys.executable, "-m", "snakemake", "--cores", str(cores), "--config",
               f"profile={profile}", f"results={res}", f"papers=[{','.join(papers)}]",
               "--nolock", *targets]
        t0 = time.perf_counter()
        print(f"[reference {i}/{len(names)}] {name}: {spec or 'native kernels'}", flush=True)
        proc = subprocess.run(cmd, env=variant_env(spec), capture_output=True, text=True)
        if proc.returncode != 0:
            raise RuntimeError(f"variant {name} failed:\n{proc.stderr[-3000:]}")
        print(f"[reference {i}/{len(names)}] {name}: done in {time.perf_counter() - t0:.0f} s",
              flush=True)
        out[name] = res
    return out


def _float(text: str, where: str) -> float:
    if text == "":
        return math.nan
    try:
        return float(text)
    except ValueError:
        raise ResultFileError(f"{where}: {text!r} is not a number") from None


def _table(path: Path, required: list[str]) -> list[dict]:
    try:
        rows = read_table(path)
    except FileNotFoundError:
        raise ResultFileError(f"{path}: missing") from None
    except (csv.Error, UnicodeDecodeError) as exc:
        raise ResultFileError(f"{path}: not a readable CSV ({exc})") from None
    if rows and not set(required) <= set(rows[0]):
        raise ResultFileError(f"{path}: columns {list(rows[0])}, expected at least {required}")
    return rows


def _values(path: Path) -> dict[str, tuple[float, str, str]]:
    """quantity -> (value, status, evidence class) of a validation table."""
    rows = _table(path, ["quantity", "reproduced_value", "status"])
    out = {}
    for i, r in enumerate(rows, 2):
        where = f"{path}, line {i} ({r['quantity']}), reproduced_value"
        out[r["quantity"]] = (_float(r["reproduced_value"], where), r["status"],
                              r.get("evidence") or "")
    return out


def _basis(cfg) -> dict[str, str]:
    return {q: "timing" if spec.get("timing") else spec.get("drift", "value")
            for q, spec in cfg.reported.items()}


# modules that only present or book-keep results (a change there changes no value); any
# other module of the package, and the paper's own model, is code a row may be computed by
PRESENTATION = ("archive.py", "docs.py", "experiment.py", "heal.py", "kernel.py", "notebook.py",
                "plan.py", "plotting.py", "reference.py", "report.py", "results.py", "summary.py")


def code_digest(paper: str, src: Path = SRC_ROOT) -> str:
    """sha256 of the source a paper's values are computed by: the framework's modules but
    :data:`PRESENTATION`, and ``models/<paper>/``."""
    files = [f for f in src.glob("*.py") if f.name not in PRESENTATION]
    files += list((src / "models" / paper).rglob("*.py")) + [src / "models" / "__init__.py"]
    h = hashlib.sha256()
    for f in sorted(set(files)):
        if f.exists():
            h.update(str(f.relative_to(src)).encode())
            h.update(f.read_bytes())
    return h.hexdigest()


# config keys that reach a row only through the records of the runs it reads (scenes,
# studies, profiles), that are the other rows' (reported), or that only present results
NOT_INPUTS = ("reported", "scenes", "studies", "profiles", "figures", "tables", "claim_note",
              "title", "source")


def row_inputs(cfg, quantity: str, code: str) -> str:
    """A digest of what a row's value is computed from: the code (:func:`code_digest`), the
    tracked package versions, the paper's config but :data:`NOT_INPUTS`, the row's own
    entry and the records of every run it reads (its scenes and studies with their
    variants; a validation job may read no other).  The same digest means the same
    computation, whatever the machine."""
    reads = set(cfg.reported[quantity].get("reads", []))
    runs = {r: rec for r, rec in cfg.runs.items()
            if {r.split("@")[0], (rec.get("study") or "").split("@")[0], rec.get("scene")} & reads}
    packages = {k: v for k, v in package_versions().items() if k != "python"}
    return json_hash({"code": code, "packages": packages, "profile": cfg.profile,
                      "config": {k: v for k, v in cfg.raw.items() if k not in NOT_INPUTS},
                      "row": cfg.reported[quantity], "runs": runs})[:16]


def _committed(path: Path) -> dict[str, dict]:
    """The rows of a committed reference file, by quantity ({} when there is none)."""
    return {r["quantity"]: r for r in _table(path, REQUIRED)} if path.exists() else {}


def derive(results: dict[str, Path], reference_dir: str | Path, config_dir: str | Path,
           papers: list[str], profile: str, native: str = "native") -> None:
    """Write the reference of ``profile`` from the variant runs of :func:`measure`, with the
    committed value of a row made from the same inputs as one more observation."""
    conf = settings(config_dir)
    safety, floor = float(conf["safety"]), float(conf["floor"])
    refused = []
    for paper in papers:
        cfg = load_paper(Path(config_dir) / "papers" / f"{paper}.yaml", profile)
        basis = _basis(cfg)
        code = code_digest(paper)
        out = Path(reference_dir) / profile / f"{paper}.csv"
        committed = _committed(out)
        tables = {v: _values(res / paper / "tables" / "validation.csv") for v, res in results.items()}
        base = tables[native]
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(HEADER)
        for q, (value, status, evidence) in base.items():
            b = basis.get(q, "value")
            others = {v: t.get(q, (math.nan, "missing", ""))[:2] for v, t in tables.items()}
            inputs = row_inputs(cfg, q, code) if q in cfg.reported else ""
            prev, carried = committed.get(q), 0.0
            if inputs and prev and prev.get("inputs") == inputs:
                where = f"{out}, {q}"
                others["previous"] = (_float(prev["reproduced_value"], where), prev["status"])
                carried = _float(prev["spread"], where)
            if b != "timing" or status != "info":   # a timing verdict must not flip either
                flips = {v: s for v, (_, s) in others.items() if s != status}
                if flips:
                    refused.append(f"  {paper}.{q}: {status} natively, " + ", ".join(
                        f"{s} under {v} ({others[v][0]!r})" for v, s in flips.items()))
            spread = max([abs(x - value) for x, _ in others.values()
                          if not (math.isnan(x) and math.isnan(value))]
                         + ([] if math.isnan(carried) else [carried]), default=0.0)
            tol = (max(safety * spread, floor * abs(value))
                   if b == "value" and not math.isnan(value) else math.nan)
            w.writerow([q, repr(value), status, b, repr(spread), repr(tol),
                        " ".join(others), evidence, inputs])
        write_text(out, buf.getvalue(), record=False)
        print(f"reference written: {out}")
    if refused:
        raise DriftError("verdicts that differ between platform variants (fix each quantity "
                         "at its source; a verdict must not depend on the CPU):\n"
                         + "\n".join(refused))


def compare(current: dict[str, tuple[float, str, str]], ref_rows: list[dict], where: str
            ) -> list[str]:
    """Readable differences between a validation table and its reference."""
    ref = {r["quantity"]: r for r in ref_rows}
    problems = [f"  {q}: in reference, missing now" for q in sorted(set(ref) - set(current))]
    problems += [f"  {q}: new quantity, not in reference" for q in sorted(set(current) - set(ref))]
    for i, (q, r) in enumerate(ref.items(), 2):
        if q not in current:
            continue
        value, status, evidence = current[q]
        # a pass that became `not_discriminating` (no rival fails it any more) is a changed
        # verdict too: what the claim counts moved
        if r.get("evidence") and evidence and evidence != r["evidence"]:
            problems.append(f"  {q}: evidence {r['evidence']} in reference, now {evidence}")
        # a timing row's value is never compared (wall clock), its verdict always: the
        # criterion (e.g. a speed-up >= 100) must hold on any machine
        if status != r["status"]:
            problems.append(f"  {q}: verdict {r['status']} in reference, now {status}"
                            + (f" (timing row: value {value!r})" if r["basis"] == "timing" else ""))
        if r["basis"] != "value":
            continue
        x0 = _float(r["reproduced_value"], f"{where}, line {i} ({q}), reproduced_value")
        tol = _float(r["tolerance"], f"{where}, line {i} ({q}), tolerance")
        if math.isnan(x0) and math.isnan(value):
            continue
        drift = abs(value - x0) if not (math.isnan(x0) or math.isnan(value)) else math.inf
        if not drift <= tol:
            problems.append(f"  {q}: reference {x0!r}, now {value!r}, |drift| {drift:.3g} > "
                            f"tolerance {tol:.3g} (platform spread {r['spread']})")
    return problems


PROFILES = ("ci", "default")


def profiles_agree(reference_dir: str | Path, paper: str, config_dir: str | Path | None
                   ) -> list[str]:
    """Verdicts of the committed references of the two profiles that differ, unless the
    paper's reported row says why (``profile_differs_why``): a verdict that depends on
    the resolution profile is not a verdict of the paper.  The ci profile may be undecided
    (inconclusive, not converged) where the default decides: its error bars are wider."""
    files = {p: Path(reference_dir) / p / f"{paper}.csv" for p in PROFILES}
    if not all(f.exists() for f in files.values()):
        return []
    status = {p: {r["quantity"]: r["status"] for r in _table(f, HEADER[:3])}
              for p, f in files.items()}
    a, b = (status[p] for p in PROFILES)
    # the coarser profile's wider error bars may leave undecided what the finer one decides;
    # any other difference (a decided ci verdict the default does not share) is a disagreement
    undecided = ("inconclusive", "not_converged")
    differ = sorted(q for q in set(a) & set(b)
                    if a[q] != b[q] and not (a[q] in undecided and b[q] in ("pass", "fail")))
    if not differ:
        return []
    reported = (load_paper(Path(config_dir) / "papers" / f"{paper}.yaml").reported
                if config_dir is not None else {})
    return [f"  {q}: verdict {a[q]} in {files['ci']}, {b[q]} in {files['default']} (the "
            f"profiles disagree; fix it, or say why in reported.{q}.profile_differs_why)"
            for q in differ if not (reported.get(q) or {}).get("profile_differs_why")]


def check(results: str, reference_dir: str, papers: list[str], profile: str,
          config_dir: str | Path | None = None) -> str:
    """Compare every paper's validation table with the reference; raise DriftError on drift
    or on a paper without a reference (it is not checked, so it must not be certified).
    ``config_dir`` (default: ``config/`` beside ``results/reference``) gives the reported
    rows' ``profile_differs_why``."""
    results, ref_root = Path(results), Path(reference_dir) / profile
    if config_dir is None:
        config_dir = Path(reference_dir).resolve().parents[1] / "config"
    lines, failed = [], False
    for paper in papers:
        ref_file = ref_root / f"{paper}.csv"
        if not ref_file.exists():
            failed = True
            lines.append(f"{paper}: not checked: no reference at {ref_file} (create it with "
                         f"`make reference REF_PROFILE={profile} REF_PAPERS={paper}`)")
            continue
        try:
            ref = _table(ref_file, REQUIRED)
            current = _values(results / paper / "tables" / "validation.csv")
            problems = compare(current, ref, str(ref_file))
            problems += profiles_agree(reference_dir, paper,
                                       config_dir if Path(config_dir).is_dir() else None)
        except ResultFileError as exc:  # one unreadable file does not hide the others
            problems = [f"  {exc}"]
        if problems:
            failed = True
            lines.append(f"{paper}: DRIFT against {ref_file}")
            lines += problems
        else:
            n = sum(r["basis"] != "timing" for r in ref)
            lines.append(f"{paper}: {n} quantities within tolerance of {ref_file} "
                         f"(same verdicts, timing rows' included; {len(ref) - n} timing "
                         f"values not compared)")
    text = "\n".join(lines) + "\n"
    if failed:
        raise DriftError(text + "If the change is deliberate, refresh with `make reference`.")
    return text


def main(argv: list[str]) -> int:
    """python -m mechrepro.reference PROFILE WORKDIR [--papers P ...] [--variants V ...]"""
    import argparse

    ap = argparse.ArgumentParser(prog="python -m mechrepro.reference", description=main.__doc__)
    ap.add_argument("profile")
    ap.add_argument("workdir")
    ap.add_argument("--papers", nargs="*", help="default: every paper of config/config.yaml")
    ap.add_argument("--variants", nargs="*", help="default: every variant of config/reference.yaml")
    ap.add_argument("--cores", type=int, default=2)
    args = ap.parse_args(argv)
    config_dir = Path("config")
    papers = args.papers or workflow_config(config_dir / "config.yaml")["papers"]
    results = measure(args.profile, papers, args.workdir, config_dir, cores=args.cores,
                      variants=args.variants or None)
    try:
        derive(results, "results/reference", config_dir, papers, args.profile)
    except DriftError as exc:
        sys.stderr.write(f"{exc}\n")
        return 1
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
