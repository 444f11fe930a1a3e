"""Before a run: find what Snakemake cannot see, and remove it so that it is rebuilt.

Snakemake decides by file existence and modification time.  It cannot see

- a temporary ``.*.part.*`` file left by a killed job (harmless, but it stays forever);
- a result file that cannot be read any more (a truncated ``.nc``): its time stamp is new,
  so it would be trusted;
- a result written by something other than its job (garbage pasted into a table): its
  time stamp is later than the end of the job that made it, as Snakemake recorded it;
- a result whose bytes changed while its time stamp did not (a bit flip, a copy over it
  with ``cp -p``): the manifest of the last archived run still has its checksum.

``python -m mechrepro.heal RESULTS`` removes each of these and names it; the run that
follows rebuilds exactly them and what depends on them.  Files newer than the manifest
are results of a later run and are kept.
"""
from __future__ import annotations

import base64
import json
import os
import sys
from pathlib import Path

from .provenance import file_sha256


def stale_parts(results: Path) -> list[Path]:
    return sorted(p for p in results.rglob(".*.part*") if p.is_file())


def unreadable_netcdf(results: Path) -> list[Path]:
    import netCDF4

    bad = []
    for p in sorted(results.rglob("*.nc")):
        if p.name.startswith(".") or "reference" in p.parts:
            continue
        try:
            netCDF4.Dataset(p).close()
        except OSError:
            bad.append(p)
    return bad


def changed_since_manifest(results: Path) -> list[Path]:
    man_path = results / "archive" / "manifest.json"
    if not man_path.exists():
        return []
    try:
        man = json.loads(man_path.read_text())
        files = man["files"]
    except (ValueError, KeyError):
        return [man_path]  # an unreadable manifest is rebuilt by the archive rule
    stamp = man_path.stat().st_mtime
    out = []
    for rel, sha in files.items():
        f = results / rel
        if f.is_file() and f.stat().st_mtime <= stamp and file_sha256(f) != sha:
            out.append(f)
    return out


def _job_record(path: Path, metadata: Path) -> dict | None:
    """Snakemake's record of the job that wrote ``path`` (its persistence layout)."""
    b64 = base64.urlsafe_b64encode(str(path).encode()).decode()
    try:
        max_len = os.pathconf(metadata, "PC_NAME_MAX") or 255
    except OSError:
        max_len = 255
    chunks = [b64[i:i + max_len - 1] for i in range(0, len(b64), max_len - 1)]
    rec = metadata.joinpath(*(["@" + c for c in chunks[:-1]] + [chunks[-1]]))
    try:
        return json.loads(rec.read_text())
    except (OSError, ValueError):
        return None


def modified_after_job(results: Path, workdir: Path) -> list[Path]:
    metadata = workdir / ".snakemake" / "metadata"
    if not metadata.is_dir():
        return []
    out = []
    for sub in sorted(results.iterdir()):
        if sub.name in ("reference", "logs") or not sub.is_dir():
            continue
        for f in sorted(sub.rglob("*")):
            if not f.is_file() or "logs" in f.parts or "benchmarks" in f.parts:
                continue
            rec = _job_record(f, metadata)
            # 2 s: file systems with coarse time stamps
            if rec and rec.get("endtime") and f.stat().st_mtime > rec["endtime"] + 2.0:
                out.append(f)
    return out


def heal(results: str | Path, workdir: str | Path = ".") -> list[str]:
    results = Path(results)
    if not results.is_dir():
        return []
    lines = []
    for why, files in (("temporary file of an interrupted job", stale_parts(results)),
                       ("unreadable netCDF (truncated or corrupted)", unreadable_netcdf(results)),
                       ("changed after the job that wrote it", modified_after_job(results, Path(workdir))),
                       ("checksum differs from the last manifest", changed_since_manifest(results))):
        for f in files:
            if f.exists():
                f.unlink()
                lines.append(f"removed {f}: {why}")
    return lines


if __name__ == "__main__":
    for line in heal(sys.argv[1]):
        print(f"[heal] {line}", flush=True)
