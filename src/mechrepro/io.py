"""The one netCDF writer (CF-style attributes, provenance, atomic) and the study gather.

Every result file is written to a temporary name in the target directory and renamed
into place only after it was closed successfully, so an interrupted job never leaves a
half-written ``.nc`` (or ``.csv``, ``.json``) that a later step would trust.
"""
from __future__ import annotations

import contextlib
import functools
import hashlib
import datetime as _dt
import json
import os
import tempfile
from pathlib import Path

from typing import TYPE_CHECKING

import numpy as np

from .provenance import code_version, file_sha256, package_versions

if TYPE_CHECKING:   # xarray (with pandas, slow to import) is imported where datasets are read:
    import xarray as xr   # the report, archive and reference jobs write files only


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


SUM_PREFIX, SUM_SUFFIX = ".", ".sum"


def sum_path(path: str | Path) -> Path:
    """The record of what ``path``'s writer wrote: ``.<name>.sum`` beside it (hidden, so
    no glob of results picks it up)."""
    path = Path(path)
    return path.parent / f"{SUM_PREFIX}{path.name}{SUM_SUFFIX}"


def read_sum(path: str | Path) -> dict | None:
    """``{"sha256", "size", "mtime_ns"}`` as the writer recorded them (and ``made_by``,
    what made it: :mod:`mechrepro.staleness`), or None."""
    try:
        rec = json.loads(sum_path(path).read_text())
        return rec if {"sha256", "size", "mtime_ns"} <= set(rec) else None
    except (OSError, ValueError, TypeError):
        return None


ENV_PARTS, ENV_INPUTS, ENV_RESULTS = "MECHREPRO_MADE_BY", "MECHREPRO_INPUTS", "MECHREPRO_RESULTS"


def _content(path: Path) -> str:
    """A result's sha256 as its writer recorded it (heal has checked it against the bytes
    before any job), else of its bytes; "missing" when there is no such file."""
    rec = read_sum(path)
    if rec is not None:
        return rec["sha256"]
    return file_sha256(path) if path.is_file() else "missing"


def digest_inputs(paths, results: str | Path) -> str:
    """sha256 over the contents of a job's result inputs, each named relative to the
    results directory (an experiment's copy of a result is the same input)."""
    h = hashlib.sha256()
    for p in sorted(os.path.relpath(p, results) for p in paths):
        h.update(f"{p}\0{_content(Path(results, p))}\n".encode())
    return h.hexdigest()


@functools.cache
def job_made_by() -> dict | None:
    """What made the files this process writes, when it runs as a job of the workflow
    (its parts and the digest of its inputs, read once: a job's inputs do not change
    while it runs); None outside a job."""
    parts = os.environ.get(ENV_PARTS)
    if not parts:
        return None
    inputs = os.environ.get(ENV_INPUTS, "").split()
    return {**json.loads(parts),
            "inputs": digest_inputs(inputs, os.environ.get(ENV_RESULTS, "."))}


def _write_sum(tmp: Path, path: Path) -> None:
    """Record the sha256, size and time stamp of ``tmp`` (about to become ``path``), so that
    `mechrepro.heal` decides by content whether ``path`` is still what its job wrote: a
    copy (``cp -r``) keeps the content and loses the time stamps, a paste or a bit flip
    keeps the time stamp and changes the content."""
    st = tmp.stat()
    rec = {"sha256": file_sha256(tmp), "size": st.st_size, "mtime_ns": st.st_mtime_ns}
    made_by = job_made_by()
    if made_by is not None:
        rec["made_by"] = made_by    # what made it (mechrepro.staleness)
    old = read_sum(path)
    if old is not None:
        # what was there before: a failed job's outputs are restored by Snakemake (the
        # rules' update() flag), and heal must recognise them as what their job wrote
        rec["previous"] = {k: old[k] for k in ("sha256", "size", "mtime_ns", "made_by")
                           if k in old}
    side = sum_path(path)
    fd, stmp = tempfile.mkstemp(prefix=side.name + ".", suffix=".part", dir=path.parent)
    with os.fdopen(fd, "w") as f:
        f.write(json.dumps(rec, sort_keys=True) + "\n")
    os.chmod(stmp, 0o666 & ~_umask())
    os.replace(stmp, side)


@contextlib.contextmanager
def atomic_path(path: str | Path, record: bool = True):
    """Yield a temporary path next to ``path``; rename it to ``path`` on success only.

    The file gets the permissions a plain ``open`` would give it (0666 less the umask):
    ``mkstemp`` makes it 0600, which a shared results directory could not read.  With
    ``record`` (the default), its checksum is kept beside it (:func:`sum_path`), written
    before the rename: a kill between the two leaves a record that does not match, and the
    file is rebuilt, never trusted.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    # keep the real suffix last: writers (netCDF4, papermill) pick formats by extension
    fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=f".part{path.suffix}",
                               dir=path.parent)
    os.close(fd)
    try:
        yield Path(tmp)
        os.chmod(tmp, 0o666 & ~_umask())
        if record:
            _write_sum(Path(tmp), path)
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise


def write_text(path: str | Path, text: str, record: bool = True) -> None:
    with atomic_path(path, record) as tmp:
        tmp.write_text(text)


def write_json(path: str | Path, obj) -> None:
    write_text(path, json.dumps(obj, indent=2, sort_keys=True) + "\n")


def check_cf(ds: xr.Dataset) -> None:
    """Every variable and coordinate carries ``units`` and ``long_name`` (labels, i.e.
    strings, only a ``long_name``: CF gives text no unit)."""
    missing = [f"{n}:{a}" for n, v in ds.variables.items()
               for a in ("units", "long_name") if a not in v.attrs
               and not (a == "units" and v.dtype.kind in "USO")]
    if missing:
        raise ValueError(f"variables without CF attributes: {missing}")


def provenance_attrs(run: dict) -> dict:
    return {
        "paper": run["paper"],
        "scene": run["scene"],
        "run": run["run"],
        "study": run.get("study") or "",
        "variant": run.get("variant") or "",
        "sweep": json.dumps(run.get("sweep", {}), sort_keys=True),
        "sweep_units": json.dumps(run.get("sweep_units", {}), sort_keys=True),
        "effects": json.dumps(run["effects"]),
        "outputs": json.dumps(run.get("outputs", [])),
        "resolution": json.dumps(run["resolution"], sort_keys=True),
        "parameters": json.dumps({"values_si": run["parameters"], "units_si": run["units"],
                                  "options": run.get("options", {}), "seed": run.get("seed")},
                                 sort_keys=True),
        "code_version": code_version(),
        "package_versions": json.dumps(package_versions(), sort_keys=True),
        # what made it (mechrepro.staleness): kept inside the file, so a copy without its
        # record beside it still says so
        "made_by": json.dumps(job_made_by() or {}, sort_keys=True),
        "created": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
        "Conventions": "CF-1.8",
    }


# every result is written as netCDF-3 by scipy's writer (:func:`write_dataset`) and read back
# by the same library, faster than through netCDF4/HDF5 for files this small, the decoded
# datasets identical (xarray's ``identical``)
ENGINE = "scipy"

# config spellings that UDUNITS (and so the CF checker) does not know
CF_UNITS = {"deg": "degree", "r/min": "rpm", "HB": "kgf/mm2", "bool": "1"}


def _all_str(var) -> bool:
    v = var.values
    return v.dtype.kind in "US" or all(isinstance(x, str) for x in v.ravel())


def _cf_types(ds: xr.Dataset) -> dict:
    """The encoding of CF-1.8 data types (no 64-bit integers) and of no _FillValue on
    coordinates; units spelled as UDUNITS knows them.  Works on ``ds``'s Variables in place
    (``ds`` is the writer's own shallow copy): assigning DataArrays to a Dataset merges
    and aligns each time, which was a third of a run's write."""
    encoding = {}
    for name, var in ds.variables.items():
        enc = {}
        if var.dtype.kind in "iu" and var.dtype.itemsize == 8:
            v = var.values
            fits = v.size == 0 or (v.min() >= np.iinfo(np.int32).min and v.max() <= np.iinfo(np.int32).max)
            enc["dtype"] = np.dtype(np.int32 if fits else np.float64)
        if var.attrs.get("units") in CF_UNITS:
            var.attrs["units"] = CF_UNITS[var.attrs["units"]]
        if name in ds.coords or var.dtype.kind not in "fc":
            enc["_FillValue"] = None
        if var.dtype.kind in "USO" and _all_str(var):
            # text as char arrays: a string coordinate variable (run names, timed effects)
            # makes CF checkers fail (monotonicity of strings), and the NCAS checker refuses
            # variable-length strings anywhere (CF 2.2); xarray and netCDF4 read it back as
            # the same strings (its _Encoding attribute)
            enc["dtype"] = "S1"
        if enc:
            encoding[name] = enc
    return encoding


def write_dataset(ds: xr.Dataset, path: str | Path, run: dict | None = None,
                  extra_attrs: dict | None = None) -> Path:
    """Write ``ds`` atomically (CF-1.8 types); with ``run``, add the provenance attributes."""
    check_cf(ds)
    ds = ds.copy()
    encoding = _cf_types(ds)
    if run is not None:
        ds.attrs.update(provenance_attrs(run))
    if extra_attrs:
        ds.attrs.update(extra_attrs)
    ds.attrs.setdefault("Conventions", "CF-1.8")
    ds.attrs.setdefault("title", f"mechrepro {ds.attrs.get('paper', '')} "
                                 f"{ds.attrs.get('run') or ds.attrs.get('study') or Path(path).stem}")
    ds.attrs.setdefault("history", f"{ds.attrs.get('created', '')} written by mechrepro "
                                   f"{code_version()}")
    # netCDF-3 (64-bit offset) through scipy's writer: every result is small and its CF-1.8
    # types (:func:`_cf_types`) are netCDF-3's, and HDF5 costs per variable to create what a
    # file of scalars and short arrays does not need; every variable, type and attribute
    # is equal on read-back.
    with atomic_path(path) as tmp:
        ds.to_netcdf(tmp, engine="scipy", format="NETCDF3_64BIT", encoding=encoding)
    return Path(path)


def open_dataset(path: str | Path, indexes: bool = True) -> xr.Dataset:
    """Load a result fully into memory and close the file (one reader at a time).
    ``indexes=False``: without the (pandas) indexes of its dimension coordinates, for a
    reader that selects nothing by label (a third of an open's time)."""
    import xarray as xr

    with xr.open_dataset(path, engine=ENGINE, create_default_indexes=indexes) as ds:
        return ds.load()


def run_attrs(ds: xr.Dataset) -> dict:
    """Decode the JSON provenance attributes of a run dataset."""
    out = dict(ds.attrs)
    for k in ("effects", "outputs", "resolution", "parameters", "sweep", "package_versions"):
        if k in out and isinstance(out[k], str):
            out[k] = json.loads(out[k])
    return out


def gather_study(paths: list[str | Path]) -> xr.Dataset:
    """Stack the runs of one study along a ``run`` dimension.

    Swept keys become coordinates along ``run``.  Variables whose shape differs between
    runs (e.g. a time axis whose length is the resolution) cannot be stacked and are kept
    only as their scalar summaries: runs are expected to store the scalars a study needs.
    """
    import xarray as xr

    # no label is selected: concat checks the runs' coordinates equal itself (coord_equal
    # below); the stacked study is identical either way (every study of a default run)
    dsets = [open_dataset(p, indexes=False) for p in paths]
    attrs = [run_attrs(d) for d in dsets]
    names = [a["run"] for a in attrs]
    # plain Variables, not DataArrays: building a DataArray per variable and run was half
    # of a gather's time
    same_dim = {}   # dimension -> its coordinate is equal in every run that has one

    def coord_equal(dim: str) -> bool:
        if dim not in same_dim:
            ref = dsets[0][dim].values
            same_dim[dim] = all(np.array_equal(d.variables[dim].values, ref)
                                for d in dsets if dim in d.coords)
        return same_dim[dim]

    stackable = []
    for var in dsets[0].data_vars:
        shapes = {(d.variables[var].dims, d.variables[var].shape) if var in d.variables
                  else None for d in dsets}
        if len(shapes) == 1 and None not in shapes and all(
                map(coord_equal, dsets[0].variables[var].dims)):
            stackable.append(var)
    out = xr.concat([d[stackable] for d in dsets], dim="run", coords="minimal",
                    compat="override", combine_attrs="override")
    out = out.assign_coords(run=("run", names, {"long_name": "run name", "units": "1"}))
    units = json.loads(dsets[0].attrs.get("sweep_units", "{}"))
    for key in attrs[0]["sweep"]:
        vals = [a["sweep"][key] for a in attrs]
        unit = CF_UNITS.get(units.get(key, "1"), units.get(key, "1"))
        out = out.assign_coords({key: ("run", vals, {"long_name": f"swept {key} (in the "
                                                    f"config's unit)", "units": unit})})
    out.attrs = {"paper": attrs[0]["paper"], "study": attrs[0]["study"],
                 "scene": attrs[0]["scene"], "runs": json.dumps(names),
                 "code_version": code_version(),
                 "package_versions": json.dumps(package_versions(), sort_keys=True),
                 "created": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")}
    return out
