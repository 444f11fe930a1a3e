"""Result archive with manifest, and the drift check against the committed reference.

The reference (``results/reference/<profile>/<paper>.csv``: quantity, reproduced_value,
drift_rtol) holds the validation numbers of a profile.  CI recomputes the ``ci`` profile
and fails when a number drifts beyond its tolerance, printing a readable diff.  Refresh
it deliberately with ``make reference`` (see README).
"""
from __future__ import annotations

import csv
import io
import math
import tarfile
from pathlib import Path

from .config import load_paper
from .io import atomic_path, write_json, write_text
from .provenance import code_version, file_sha256, json_hash, package_versions
from .validation import read_table

DEFAULT_DRIFT_RTOL = 1e-6


class DriftError(RuntimeError):
    pass


def _files(results: Path, papers: list[str]) -> list[Path]:
    out = [results / "report" / "index.html"]
    for paper in papers:
        root = results / paper
        for sub in ("runs", "studies", "figures", "tables"):
            out += sorted((root / sub).glob("*")) if (root / sub).is_dir() else []
        out += [root / "notebook.ipynb", root / "claim.json"]
    return [f for f in out if f.is_file() and not f.name.startswith(".")]


def write_archive(archive: str, manifest: str, results: str, config_dir: str,
                  papers: list[str], profile: str) -> None:
    results, config_dir = Path(results), Path(config_dir)
    files = _files(results, papers)
    configs = {p: load_paper(config_dir / "papers" / f"{p}.yaml", profile).raw for p in papers}
    man = {
        "profile": profile,
        "code_version": code_version(),
        "package_versions": package_versions(),
        "config_hash": json_hash(configs),
        "files": {str(f.relative_to(results)): file_sha256(f) for f in files},
    }
    with atomic_path(archive) as tmp:
        with tarfile.open(tmp, "w:gz") as tar:
            for f in files:
                tar.add(f, arcname=str(f.relative_to(results)))
            data = (str(man) + "\n").encode()
            info = tarfile.TarInfo("manifest.txt")
            info.size = len(data)
            tar.addfile(info, io.BytesIO(data))
    write_json(manifest, man)


def reference_rows(results: Path, paper: str, drift: dict) -> list[list]:
    rows = read_table(results / paper / "tables" / "validation.csv")
    return [[r["quantity"], r["reproduced_value"], drift.get(r["quantity"], DEFAULT_DRIFT_RTOL)]
            for r in rows]


def compare(current: list[dict], reference: list[dict]) -> list[str]:
    """Readable differences between a validation table and its reference."""
    cur = {r["quantity"]: r for r in current}
    ref = {r["quantity"]: r for r in reference}
    problems = []
    for q in sorted(set(ref) - set(cur)):
        problems.append(f"  {q}: in reference, missing now")
    for q in sorted(set(cur) - set(ref)):
        problems.append(f"  {q}: new quantity, not in reference")
    for q in sorted(set(cur) & set(ref)):
        a, b = cur[q]["reproduced_value"], ref[q]["reproduced_value"]
        tol = float(ref[q]["drift_rtol"])
        xa = float(a) if a else math.nan
        xb = float(b) if b else math.nan
        if math.isnan(xa) and math.isnan(xb):
            continue
        scale = max(abs(xb), 1e-300)
        drift = abs(xa - xb) / scale if not (math.isnan(xa) or math.isnan(xb)) else math.inf
        if drift > tol:
            problems.append(f"  {q}: reference {xb!r}, now {xa!r}, drift {drift:.3g} > {tol:g}")
    return problems


def check_reference(out: str, results: str, reference_dir: str, papers: list[str],
                    profile: str) -> None:
    results, ref_root = Path(results), Path(reference_dir) / profile
    lines, failed = [f"reference check, profile {profile}"], False
    for paper in papers:
        ref_file = ref_root / f"{paper}.csv"
        if not ref_file.exists():
            lines.append(f"{paper}: no reference at {ref_file} (not checked)")
            continue
        with open(ref_file, newline="") as f:
            ref = list(csv.DictReader(f))
        problems = compare(read_table(results / paper / "tables" / "validation.csv"), ref)
        if problems:
            failed = True
            lines.append(f"{paper}: DRIFT against {ref_file}")
            lines += problems
        else:
            lines.append(f"{paper}: {len(ref)} quantities within tolerance of {ref_file}")
    text = "\n".join(lines) + "\n"
    print(text)
    if failed:
        raise DriftError(text + "If the change is deliberate, refresh with `make reference`.")
    write_text(out, text)


def refresh_reference(results: str, reference_dir: str, config_dir: str, papers: list[str],
                      profile: str) -> None:
    """Deliberately overwrite the reference of ``profile`` with the current tables."""
    for paper in papers:
        cfg = load_paper(Path(config_dir) / "papers" / f"{paper}.yaml", profile)
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(["quantity", "reproduced_value", "drift_rtol"])
        w.writerows(reference_rows(Path(results), paper, cfg.raw.get("drift_tolerance", {})))
        write_text(Path(reference_dir) / profile / f"{paper}.csv", buf.getvalue())
        print(f"reference refreshed: {Path(reference_dir) / profile / f'{paper}.csv'}")


if __name__ == "__main__":
    import sys

    results, reference_dir, config_dir, profile, *papers = sys.argv[1:]
    refresh_reference(results, reference_dir, config_dir, papers, profile)
