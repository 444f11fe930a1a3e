"""Every netCDF result passes the IOOS compliance-checker's CF-1.8 check without errors
and without an exception in any check, and, where it is installed, the NCAS CF checker
(`cfchecks`, package cfchecker, which needs the UDUNITS-2 C library) without errors.

The checker takes seconds per file, and the runs of one scene (a study's points, the
verdict variants) share one layout, so each distinct layout (variable names, types,
dimensions) is checked once; the attributes all come from the one writer
(`mechrepro.io.write_dataset`).
"""
import copy
import functools
from contextlib import contextmanager

import pytest

pytestmark = pytest.mark.slow

# Whole-dataset lookups the checker recomputes for every variable it looks at (O(n^2) in the
# variables: 22 s for a 181-variable rolling_shear file). Each is a pure function of the
# open, unchanged dataset, so one answer per dataset is the same answer.
PURE_LOOKUPS = ("get_auxiliary_coordinate_variables", "get_coordinate_variables",
                "get_axis_variables", "get_time_variables", "get_time_variable",
                "get_climatology_variable", "get_geophysical_variables", "is_geophysical",
                "get_axis_map", "get_z_variable", "get_z_variables", "get_latitude_variables",
                "get_longitude_variables", "get_cell_boundary_variables", "get_bounds_variables",
                "get_forecast_metadata_variables", "get_platform_variables",
                "get_instrument_variables", "get_grid_mapping_variables")
# The checker's own per-dataset caches of the same kind never hit (compliance-checker 6.1:
# looked up by the dataset, stored by its str(), whose every call formats the whole
# dataset): one answer per dataset too.
CHECKER_LOOKUPS = ("_find_coord_vars", "_find_aux_coord_vars", "_find_ancillary_vars",
                   "_find_boundary_vars", "_find_clim_vars", "_find_geophysical_vars",
                   "_find_metadata_vars")


PACKAGED_TABLE = []    # the packaged standard-name table, parsed once (read only)


@contextmanager
def memoised_lookups():
    """The lookups above memoised, and the packaged standard-name table parsed once (the
    suite builds every checker class again for each file, and each parsed it): the 111
    layouts of the ci profile give the same 2437 results (name, value, weight, messages
    compared) in 6.3 s instead of 44 s with the util lookups alone memoised (and ~10x that
    with none)."""
    from compliance_checker.cf import cf_base, util

    checker = cf_base.CFBaseCheck
    original = {n: getattr(util, n) for n in (*PURE_LOOKUPS, "StandardNameTable")}
    methods = {n: getattr(checker, n) for n in CHECKER_LOOKUPS}
    cache = {}

    def memo(fn, method=False):
        @functools.wraps(fn)
        def wrapped(*args, **kwargs):
            self, (nc, *rest) = (args[0], args[1:]) if method else (None, args)
            key = (fn.__name__, id(nc), tuple(rest))
            if key not in cache:
                cache[key] = (nc, fn(*args))       # keeps nc alive: its id is not reused
            return copy.copy(cache[key][1])        # a caller may extend a returned list
        return wrapped

    def table(cached_location=None):
        if cached_location:
            return original["StandardNameTable"](cached_location)
        if not PACKAGED_TABLE:
            PACKAGED_TABLE.append(original["StandardNameTable"]())
        return PACKAGED_TABLE[0]

    try:
        for n in PURE_LOOKUPS:
            setattr(util, n, memo(original[n]))
        for n, fn in methods.items():
            setattr(checker, n, memo(fn, method=True))
        util.StandardNameTable = table
        yield cache
    finally:
        for n, fn in original.items():
            setattr(util, n, fn)
        for n, fn in methods.items():
            setattr(checker, n, fn)


def layout(path):
    import netCDF4

    with netCDF4.Dataset(path) as nc:
        return tuple(sorted((n, str(v.dtype), v.dimensions) for n, v in nc.variables.items()))


def cf_errors(paths):
    from compliance_checker.runner import CheckSuite

    suite = CheckSuite()
    suite.load_all_available_checkers()
    errors = []
    for path in paths:
        with memoised_lookups():
            results, crashed = suite.run_all(suite.load_dataset(str(path)), ["cf:1.8"],
                                             skip_checks=[])["cf:1.8"]
        # a check that raised is a check that did not pass (the checker cannot read the file)
        errors += [f"{path.name}: {name}: checker exception {exc[0]!r}"
                   for name, exc in crashed.items()]
        for r in results:
            score = r.value if isinstance(r.value, tuple) else (int(bool(r.value)), 1)
            if r.weight == 3 and score[0] < score[1]:  # HIGH priority = an error
                errors.append(f"{path.name}: {r.name}: {'; '.join(r.msgs)}")
    return errors


def layouts(work):
    """One result file per distinct layout."""
    seen, paths = set(), []
    for path in sorted((work / "results").rglob("*.nc")):
        if path.name.startswith(".") or "reference" in path.parts:
            continue
        key = layout(path)
        if key not in seen:
            seen.add(key)
            paths.append(path)
    assert paths
    return paths


def test_every_netcdf_layout_is_cf_compliant(workflow):
    errors = cf_errors(layouts(workflow[0]))
    assert not errors, "\n".join(errors)


def cfchecks_errors(paths, tmp):
    """The NCAS CF checker on each file: its error count, and any exception as an error.
    Offline: the CF standard-name table is compliance-checker's copy; the area-type and
    region tables are one-entry stand-ins (no result uses area_type or region names)."""
    import re
    import subprocess
    import sys
    from pathlib import Path

    import compliance_checker

    exe = Path(sys.executable).with_name("cfchecks")
    names = Path(compliance_checker.__file__).parent / "data" / "cf-standard-name-table.xml"
    tables = {}
    for flag, root in (("-a", "area_type_table"), ("-r", "standardized_region_list")):
        tables[flag] = tmp / f"{root}.xml"
        tables[flag].write_text(f'<?xml version="1.0"?>\n<{root}><version_number>0'
                                f'</version_number><date>none</date><entry id="x"/></{root}>\n')
    errors = []
    for path in paths:
        proc = subprocess.run([str(exe), "-s", str(names), "-a", str(tables["-a"]),
                               "-r", str(tables["-r"]), str(path)],
                              capture_output=True, text=True, timeout=300)
        out = proc.stdout + proc.stderr
        m = re.search(r"ERRORS detected: (\d+)", out)
        if "Traceback" in out or not m:
            errors.append(f"{path.name}: cfchecks did not finish: {out[-600:]}")
        elif int(m.group(1)):
            errors.append(f"{path.name}: " + "; ".join(l for l in out.splitlines()
                                                      if l.startswith("ERROR")))
    return errors


def test_every_netcdf_layout_passes_the_ncas_cf_checker(workflow, tmp_path):
    pytest.importorskip("cfchecker")
    try:
        import cfunits  # noqa: F401  (needs libudunits2 on the library path)
    except (ImportError, OSError) as exc:
        pytest.skip(f"cfchecker installed without UDUNITS-2: {exc}")
    errors = cfchecks_errors(layouts(workflow[0]), tmp_path)
    assert not errors, "\n".join(errors)
