"""Every netCDF result passes the IOOS compliance-checker's CF-1.8 check without errors
and without an exception in any check.

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
# open, unchanged dataset, so one answer per dataset is the same answer: with them memoised
# the 107 layouts of the ci profile give the same findings 10x faster.
PURE_LOOKUPS = ("get_auxiliary_coordinate_variables", "get_coordinate_variables",
                "get_axis_variables", "get_time_variables", "get_time_variable",
                "get_climatology_variable", "get_geophysical_variables", "is_geophysical",
                "get_axis_map", "get_z_variable", "get_z_variables")


@contextmanager
def memoised_lookups():
    from compliance_checker.cf import util

    original = {n: getattr(util, n) for n in PURE_LOOKUPS}
    cache = {}

    def memo(fn):
        @functools.wraps(fn)
        def wrapped(nc, *args):
            key = (fn.__name__, id(nc), args)
            if key not in cache:
                cache[key] = (nc, fn(nc, *args))   # keeps nc alive: its id is not reused
            return copy.copy(cache[key][1])        # a caller may extend a returned list
        return wrapped

    try:
        for n, fn in original.items():
            setattr(util, n, memo(fn))
        yield cache
    finally:
        for n, fn in original.items():
            setattr(util, n, fn)


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


def test_every_netcdf_layout_is_cf_compliant(workflow):
    work, _ = workflow
    seen, paths = set(), []
    for path in sorted((work / "results").rglob("*.nc")):
        if path.name.startswith(".") or "reference" in path.parts:
            continue
        key = layout(path)
        if key not in seen:
            seen.add(key)
            paths.append(path)
    assert paths
    errors = cf_errors(paths)
    assert not errors, "\n".join(errors)
