"""`make test` runs on every core (`-n 2 --dist loadgroup`); tests that share a module's or
the session's pipeline run must share a worker, or each worker pays for the run again.
pytest-xdist marks a grouped test by suffixing its node id with the group; a pytest that
drops the suffix (pytest 9.2 with pytest-xdist 3.8, pytest-dev/pytest-xdist#1386) makes
the grouping silently void -- two workers then each ran the whole ci pipeline."""


def test_a_test_under_loadgroup_carries_its_group(request):
    if not request.config.getoption("loadgroup", False):
        return   # not under `--dist loadgroup`: nothing is grouped
    assert request.node.nodeid.endswith("@tests/test_xdist_groups.py"), request.node.nodeid
