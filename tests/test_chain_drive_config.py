"""chain_drive config: every constant sourced or assumed, schema refuses bad runs, datasets CF."""
import copy

import pytest

from mechrepro.config import ConfigError, load_paper
from mechrepro.io import check_cf
from mechrepro.models.chain_drive import EFFECTS
from mechrepro.solve import solve
from mechrepro.inputs import read_yaml

CFG = "config/papers/chain_drive.yaml"


@pytest.fixture(scope="module")
def root():
    from pathlib import Path
    return Path(__file__).resolve().parent.parent


def test_config_loads_in_both_profiles(root):
    d = load_paper(root / CFG)
    c = load_paper(root / CFG, "ci")
    scenes = set(d.raw["scenes"])
    assert scenes == set(c.raw["scenes"])           # ci coarsens, it does not drop scenes
    assert len(c.runs) < len(d.runs)                # fewer study points in ci
    for cfg in (d, c):
        for run in cfg.runs.values():
            assert set(run["effects"]) <= set(EFFECTS.names)


def test_every_parameter_has_a_source_or_a_reason(root):
    raw = read_yaml((root / CFG))
    for name, p in raw["parameters"].items():
        assert p.get("source") or (p.get("assumed") and p.get("why")), name


@pytest.mark.parametrize("mutate, msg", [
    (lambda r: r["scenes"]["fig05_plain"].__setitem__("effects", ["polygon"]), "not a declared effect"),
    (lambda r: r["scenes"]["fig05_plain"]["resolution"].__setitem__("cfl", 1.5), "must be <= 1"),
    (lambda r: r["parameters"]["lambda_support"].__setitem__("value", 2.0), "must be <= 1"),
    (lambda r: r["scenes"]["fig05_plain"]["resolution"].__setitem__("grid", 3), "unknown key"),
])
def test_schema_refuses_bad_runs(edit_config, mutate, msg):
    path = edit_config("chain_drive", mutate)
    with pytest.raises(ConfigError, match=msg):
        load_paper(path)


@pytest.mark.parametrize("scene", ["fig01_impact", "fig03", "fig04_elastic"])
def test_small_scenes_give_cf_datasets(root, scene):
    run = copy.deepcopy(load_paper(root / CFG, "ci").runs[scene])
    ds = solve(run)
    check_cf(ds)


def test_rows_allowed_to_differ_between_profiles_read_a_coarser_ci_grid():
    """A row may keep a ci verdict that differs from the default's only because the ci
    profile resolves less (reported.<q>.profile_differs_why): its reads' speed grids and
    spatial grids (Galerkin: transverse modes) are coarser in ci, so the default's verdict
    is the one that stands."""
    from mechrepro.config import load_paper

    default, ci = (load_paper("config/papers/chain_drive.yaml", p) for p in ("default", "ci"))
    rows = [q for q, s in default.reported.items() if s.get("profile_differs_why")]
    for q in rows:
        for name in default.reported[q]["reads"]:
            for run in set(default.studies.get(name, [name])) & set(ci.runs):
                d, c = default.runs[run]["resolution"], ci.runs[run]["resolution"]
                if "n_transverse" in d:      # a Galerkin run: fewer modes in ci
                    assert c["n_transverse"] < d["n_transverse"], (q, run)
                    continue
                # no knob finer in ci, one at least coarser
                knobs = ("n_speeds", "points_per_pitch")
                assert all(c[k] <= d[k] for k in knobs) and any(c[k] < d[k] for k in knobs), (q, run)
