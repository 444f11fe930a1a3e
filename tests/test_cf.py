"""Every netCDF result passes the IOOS compliance-checker's CF-1.8 check without errors
and without an exception in any check.

The checker takes seconds per file, and the runs of one scene (a study's points, the
verdict variants) share one layout, so each distinct layout (variable names, types,
dimensions) is checked once; the attributes all come from the one writer
(`mechrepro.io.write_dataset`).
"""
import pytest

pytestmark = pytest.mark.slow


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
