"""Code version, package versions and config hashes recorded with every result."""
from __future__ import annotations

import functools
import hashlib
import json
import subprocess
from importlib import metadata
from pathlib import Path

SRC_ROOT = Path(__file__).resolve().parent
TRACKED_PACKAGES = ("numpy", "scipy", "xarray", "netCDF4", "matplotlib", "snakemake",
                    "papermill", "scikit-fem", "jsonschema", "PyYAML")


@functools.cache
def package_versions() -> dict[str, str]:
    out = {}
    for name in TRACKED_PACKAGES:
        try:
            out[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            out[name] = "not installed"
    import platform
    out["python"] = platform.python_version()
    return out


@functools.cache
def source_hash() -> str:
    """sha256 over the package's own source files: the code version without git."""
    h = hashlib.sha256()
    for f in sorted(SRC_ROOT.rglob("*.py")):
        h.update(str(f.relative_to(SRC_ROOT)).encode())
        h.update(f.read_bytes())
    return h.hexdigest()[:16]


@functools.cache
def code_version() -> str:
    """git describe (with -dirty) when available, always followed by the source hash."""
    try:
        desc = subprocess.run(["git", "describe", "--always", "--dirty"], cwd=SRC_ROOT,
                              capture_output=True, text=True, timeout=5).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        desc = ""
    return f"{desc or 'nogit'}+src.{source_hash()}"


def json_hash(obj) -> str:
    return hashlib.sha256(json.dumps(obj, sort_keys=True).encode()).hexdigest()


def file_sha256(path: Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()
