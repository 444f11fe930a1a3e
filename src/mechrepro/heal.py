"""Before a run: find what Snakemake cannot see, and remove it so that it is rebuilt.

Snakemake decides by file existence and modification time.  It cannot see

- a temporary ``.*.part.*`` file left by a killed job (harmless, but it stays forever);
- a result file that cannot be read any more (a truncated ``.nc``): its time stamp is new,
  so it would be trusted;
- a result whose bytes changed while its time stamp did not (a bit flip, a copy over it
  with ``cp -p``): the manifest of the last archived run still has its checksum.

``python -m mechrepro.heal RESULTS`` removes each of these and names it; the run that
follows rebuilds exactly them and what depends on them.  Files newer than the manifest
are results of a later run and are kept.
"""
from __future__ import annotations

import json
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


def heal(results: str | Path) -> list[str]:
    results = Path(results)
    if not results.is_dir():
        return []
    lines = []
    for why, files in (("temporary file of an interrupted job", stale_parts(results)),
                       ("unreadable netCDF (truncated or corrupted)", unreadable_netcdf(results)),
                       ("checksum differs from the last manifest", changed_since_manifest(results))):
        for f in files:
            if f.exists():
                f.unlink()
                lines.append(f"removed {f}: {why}")
    return lines


if __name__ == "__main__":
    for line in heal(sys.argv[1]):
        print(f"[heal] {line}", flush=True)
