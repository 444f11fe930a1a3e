"""The result archive: only checked results, everything the report links, a JSON manifest.

The archive is built after the reference check and refuses to certify results that
drifted from the reference.  ``manifest.json`` (beside the tarball and inside it) lists
the sha256 of every archived file with the provenance of the run; :func:`verify`
re-hashes a results tree against it and names every mismatch.
"""
from __future__ import annotations

import io
import json
import tarfile
from pathlib import Path

from .config import CACHE_DIR, load_paper
from .io import atomic_path, write_json
from .provenance import code_version, file_sha256, json_hash, package_versions


class ArchiveRefused(RuntimeError):
    pass


REPORT_ASSETS = ("index.html", "cost_of_accuracy_all.png", "summary.csv", "reference_check.txt")


def _files(results: Path, papers: list[str]) -> list[Path]:
    out = [results / "report" / name for name in REPORT_ASSETS]
    for paper in papers:
        root = results / paper
        for sub in ("runs", "studies", "figures", "tables"):
            out += sorted((root / sub).glob("*")) if (root / sub).is_dir() else []
        out += [root / "notebook.ipynb", root / "claim.json"]
    return [f for f in out if f.is_file() and not f.name.startswith(".")]


def manifest(results: Path, config_dir: Path, papers: list[str], profile: str) -> dict:
    configs = {p: load_paper(config_dir / "papers" / f"{p}.yaml", profile, CACHE_DIR).raw for p in papers}
    return {
        "profile": profile,
        "papers": papers,
        "code_version": code_version(),
        "package_versions": package_versions(),
        "config_hash": json_hash(configs),
        "files": {str(f.relative_to(results)): file_sha256(f) for f in _files(results, papers)},
    }


def write_archive(archive: str, manifest_path: str, results: str, config_dir: str,
                  papers: list[str], profile: str) -> None:
    results, config_dir = Path(results), Path(config_dir)
    check = results / "report" / "reference_check.txt"
    status = check.read_text().splitlines()[0] if check.exists() else "missing"
    if not status.endswith(": OK"):
        raise ArchiveRefused(f"not archiving: the reference check did not pass ({check}):\n"
                             + (check.read_text() if check.exists() else "no check file"))
    man = manifest(results, config_dir, papers, profile)
    data = (json.dumps(man, indent=2, sort_keys=True) + "\n").encode()
    with atomic_path(archive) as tmp:
        # zlib's default level: tarfile's 9 took 2.7x as long for 0.1 % less (netCDF
        # results barely compress)
        with tarfile.open(tmp, "w:gz", compresslevel=6) as tar:
            for rel in man["files"]:
                tar.add(results / rel, arcname=rel)
            info = tarfile.TarInfo("manifest.json")
            info.size, info.mode = len(data), 0o644
            tar.addfile(info, io.BytesIO(data))
    write_json(manifest_path, man)


def verify(results: str, manifest_path: str) -> list[str]:
    """Re-hash every file of the manifest; return the mismatches (empty: all verified)."""
    results = Path(results)
    man = json.loads(Path(manifest_path).read_text())
    problems = []
    for rel, sha in man["files"].items():
        f = results / rel
        if not f.is_file():
            problems.append(f"{rel}: missing")
        elif file_sha256(f) != sha:
            problems.append(f"{rel}: sha256 differs from the manifest")
    return problems
