"""The scene loader refuses bad input with file, key, value and what is allowed."""
import math

import pytest
import yaml

from mechrepro.config import ConfigError, load_paper
from mechrepro.inputs import read_yaml


def test_scenes_and_studies_expand_to_si_runs(config_copy):
    cfg = load_paper(config_copy / "papers" / "saw_chain.yaml")
    run = cfg.runs["speed_12000"]
    assert run["parameters"]["tie_strap_pitch"] == pytest.approx(8.91e-3)
    assert run["parameters"]["sprocket_speed"] == pytest.approx(12000 * 2 * math.pi / 60)
    assert run["units"]["sprocket_speed"] == "rad/s"
    names = cfg.studies["cost_of_accuracy"]
    assert [cfg.runs[n]["resolution"]["K"] for n in names] == \
        cfg.raw["studies"]["cost_of_accuracy"]["sweep"]["K"]
    assert all(cfg.runs[n]["sweep"]["K"] == cfg.runs[n]["resolution"]["K"] for n in names)


def test_ci_profile_overlays_resolution(config_copy):
    default = load_paper(config_copy / "papers" / "saw_chain.yaml")
    ci = load_paper(config_copy / "papers" / "saw_chain.yaml", "ci")
    assert ci.runs["fig07_fig08"]["resolution"]["K"] < default.runs["fig07_fig08"]["resolution"]["K"]
    assert ci.runs["fig07_fig08"]["parameters"] == default.runs["fig07_fig08"]["parameters"]


def test_a_cached_load_is_the_load_and_follows_every_edit(edit_config, config_copy, tmp_path):
    path = config_copy / "papers" / "saw_chain.yaml"
    cache = tmp_path / "cache"
    fresh = load_paper(path, "ci")
    assert load_paper(path, "ci", cache).runs == fresh.runs
    assert load_paper(path, "ci", cache).runs == fresh.runs   # read back from the cache
    assert len(list(cache.glob("config-*.pickle"))) == 1
    edit_config("saw_chain", lambda r: r["parameters"]["tie_strap_pitch"].update(value=9.0))
    assert load_paper(path, "ci", cache).runs["speed_12000"]["parameters"]["tie_strap_pitch"] \
        == pytest.approx(9.0e-3)
    edit_config("saw_chain", lambda r: r["parameters"]["tie_strap_pitch"].update(value=-8.91))
    with pytest.raises(ConfigError, match="tie_strap_pitch"):
        load_paper(path, "ci", cache)   # a bad edit is refused, never served from the cache
    with pytest.raises(ConfigError, match="cannot read"):
        load_paper(config_copy / "papers" / "nope.yaml", "ci", cache)


def test_negative_pitch_names_file_key_value_and_range(edit_config):
    path = edit_config("saw_chain", lambda r: r["parameters"]["tie_strap_pitch"].update(value=-8.91))
    with pytest.raises(ConfigError) as e:
        load_paper(path)
    msg = str(e.value)
    assert str(path) in msg and "parameters.tie_strap_pitch" in msg
    assert "-8.91" in msg and "must be > 0" in msg


def test_unknown_effect_lists_allowed(edit_config):
    path = edit_config("saw_chain", lambda r: r["scenes"]["fig07_fig08"]["outputs"].append("warp_drive"))
    with pytest.raises(ConfigError) as e:
        load_paper(path)
    msg = str(e.value)
    declared = ", ".join(sorted(yaml.safe_load(path.read_text())["outputs"]))
    assert "fig07_fig08" in msg and "'warp_drive'" in msg and f"outputs: {declared}" in msg


def test_a_parameter_no_one_declared_is_named(edit_config):
    # a scene that sets a parameter the paper does not declare (declared once: parameters:)
    path = edit_config("saw_chain", lambda r: r["scenes"]["speed_12000"]["parameters"].update(
        teeths=8))
    with pytest.raises(ConfigError, match=r"speed_12000.*parameters: unknown key.*teeths.*allowed: .*teeth"):
        load_paper(path)


def test_bad_scene_override_and_resolution(edit_config):
    path = edit_config("saw_chain", lambda r: r["scenes"]["speed_12000"]["parameters"].update(teeth=2))
    with pytest.raises(ConfigError, match=r"speed_12000.*parameters.teeth = 2: must be >= 3"):
        load_paper(path)
    path = edit_config("saw_chain", lambda r: r["scenes"]["speed_12000"]["parameters"].update(teeth=8)
                  or r["scenes"]["fig07_fig08"]["resolution"].update(K=1))
    with pytest.raises(ConfigError, match=r"resolution.K = 1: must be >= 2"):
        load_paper(path)


def test_unknown_unit_sweep_key_profile_and_source(edit_config):
    path = edit_config("saw_chain", lambda r: r["parameters"]["teeth"].update(unit="furlong"))
    with pytest.raises(ConfigError, match="parameters.teeth.unit = 'furlong'"):
        load_paper(path)
    path = edit_config("saw_chain", lambda r: r["parameters"]["teeth"].update(unit="1")
                  or r["studies"]["cost_of_accuracy"]["sweep"].update(Q=[1]))
    with pytest.raises(ConfigError, match="sweep.Q: not a resolution key"):
        load_paper(path)
    path = edit_config("saw_chain", lambda r: r["studies"]["cost_of_accuracy"]["sweep"].pop("Q"))
    with pytest.raises(ConfigError, match="profile 'huge' not defined"):
        load_paper(path, "huge")
    # an assumed constant must say why; a given one must say where from
    path = edit_config("saw_chain", lambda r: r["parameters"]["textbook_mass"].pop("why"))
    with pytest.raises(ConfigError, match="textbook_mass"):
        load_paper(path)


def test_every_configured_paper_loads_in_every_profile():
    from conftest import ROOT

    cfg = read_yaml((ROOT / "config" / "config.yaml"))
    for paper in cfg["papers"]:
        path = ROOT / "config" / "papers" / f"{paper}.yaml"
        for profile in ["default", *read_yaml(path).get("profiles", {})]:
            assert load_paper(path, profile).runs


@pytest.mark.parametrize("paper, edit, check", [
    ("disk_tension", lambda r: r["scenes"]["rc_grid"]["parameters"].update(rolling_radius=[65, 140]),
     "rolling_band_inside_disk"),
    ("disk_tension", lambda r: r["parameters"]["clamp_radius"].update(value=130),
     "clamp_inside_disk"),
    ("joint_wear", lambda r: r["parameters"]["pin_radius"].update(value=0.05),
     "clearance_smaller_than_pin"),
    ("joint_wear", lambda r: r["parameters"]["crank_length"].update(value=0.3), "crank_rocker"),
    # sprockets overlapping at the centre distance: before, 'math domain error' mid-run
    ("chain_drive", lambda r: r["parameters"]["centre_distance"].update(value=6.0),
     "sprockets_apart"),
    ("chain_drive", lambda r: r["parameters"]["n2"].update(value=120), "sprockets_apart"),
])
def test_impossible_geometry_is_refused_by_name_before_any_job(edit_config, paper, edit, check):
    path = edit_config(paper, edit)
    with pytest.raises(ConfigError, match=f"physical cross-check '{check}' fails"):
        load_paper(path)


def test_papers_are_discovered_from_their_files(config_copy):
    """A paper is its file: config.yaml only selects; an unknown id is refused by name with
    the ones there are; the id is the file's name, and a file whose optional `paper:` says
    otherwise is refused."""
    from mechrepro.config import discover_papers, load_all
    known = discover_papers(config_copy)
    assert "saw_chain" in known and known == sorted(known)
    with pytest.raises(ConfigError, match=r"'nope'.*allowed: .*saw_chain"):
        load_all(config_copy, ["nope"], every_profile=False)
    assert load_paper(config_copy / "papers" / "saw_chain.yaml").paper == "saw_chain"
    src = config_copy / "papers" / "saw_chain.yaml"
    (config_copy / "papers" / "saw.yaml").write_text("paper: saw_chain\n" + src.read_text())
    with pytest.raises(ConfigError, match="must be the file's name, 'saw'"):
        load_paper(config_copy / "papers" / "saw.yaml")


def test_an_artefact_alone_keeps_its_rows_and_exactly_the_runs_they_read():
    """`mechrepro.cli artefact ... fig07` / `pytest -k chain_drive-fig07`: the rows of one figure,
    every run they read with its verdict variants, the same records, and nothing else."""
    from mechrepro.config import _variant_names
    from mechrepro.validation import for_artefacts

    cfg = load_paper("config/papers/chain_drive.yaml", "ci")
    cut = for_artefacts(cfg, ["fig07"])
    assert cut.rows and {cfg.reported[q]["artefact"] for q in cut.rows} == {"fig07"}
    assert all(cut.runs[r] == cfg.runs[r] for r in cut.runs)
    reads = {(n, v) for q in cut.rows for n in cfg.reported[q]["reads"]
             for v in [None, *_variant_names(cfg.reported[q], cfg.raw)]}
    assert {(rec["study"] or rec["scene"], rec.get("variant")) for rec in cut.runs.values()} <= reads
    # fig07_ts's rows and the base scene's: no run of another figure, no ablation
    assert "fig07_ts-000" in cut.runs and "fig07_tension@coarser" in cut.runs
    assert not any(r.startswith(("fig05", "fig09", "fig10")) for r in cut.runs)
    assert set(cut.studies) <= set(cfg.studies) and "fig07_ts@coarser" in cut.studies
    with pytest.raises(ConfigError, match="allowed: .*fig05"):
        cfg.for_artefacts(["fig02"])


def test_a_row_re_checks_only_the_study_points_it_reads(edit_config):
    """`members:` names the points of a study a row reads: its variants re-run those
    points only (Fig. 7c/d's rival re-runs T_s = 200 and 100 N, not 800, which only the
    slack-tension rival re-runs); a point the sweep does not have is refused with the
    sweep's values."""
    cfg = load_paper("config/papers/chain_drive.yaml")
    ts = {cfg.runs[r]["sweep"]["static_tension"]: r for r in cfg.studies["fig07_ts"]}
    assert cfg.studies["fig07_ts@rival-overdamped"] == [f"{ts[200.0]}@rival-overdamped",
                                                        f"{ts[100.0]}@rival-overdamped"]
    assert cfg.studies["fig07_ts@rival-slack_tension"] == [f"{ts[800.0]}@rival-slack_tension"]
    assert len(cfg.studies["fig07_ts"]) == 3     # the baseline draws every point
    path = edit_config("chain_drive", lambda raw: raw["reported"]["instability_ts100"].__setitem__(
        "members", {"fig07_ts": {"static_tension": [150.0]}}))
    with pytest.raises(ConfigError, match=r"members.fig07_ts.static_tension = \[150.0\]: allowed"):
        load_paper(path)


def test_a_run_repeating_another_is_solved_once_in_its_job(tmp_path):
    """Runs equal in everything but their names (a scene that is also a study point) share
    one job and one solve, written under both names with the same values; a model that
    reads more of the run (chain_drive: stability-only sweeps, by variant) keeps apart what
    it would solve differently, and runs timed against each other are never merged."""
    import xarray as xr

    from conftest import ROOT
    from mechrepro import solve

    cfg = load_paper(ROOT / "config" / "papers" / "saw_chain.yaml", "ci")
    same = cfg.same_solve()
    assert same == {"cost_of_accuracy-003": "accuracy"}
    (job,) = [runs for runs in cfg.solve_jobs().values() if "accuracy" in runs]
    assert "cost_of_accuracy-003" in job
    assert not any(cfg.runs[r].get("timing_repeat") for r in same)   # fig07_fig08 is timed
    solve.main(["saw_chain", str(ROOT / "config"), "ci", str(tmp_path), "accuracy",
                "cost_of_accuracy-003"])
    a, b = (xr.load_dataset(tmp_path / "saw_chain" / "runs" / f"{r}.nc")
            for r in ("accuracy", "cost_of_accuracy-003"))
    assert b.attrs["run"] == "cost_of_accuracy-003" and a.attrs["run"] == "accuracy"
    for v in a.data_vars:
        assert a[v].equals(b[v]), v      # the timings too: one solve, one measured time
    cd = load_paper(ROOT / "config" / "papers" / "chain_drive.yaml", "ci")
    base = next(r for r in cd.runs.values() if r["solver"] == "speed_sweep"
                and r.get("options", {}).get("variants") == "stability" and not r.get("variant"))
    cd.runs = {"a": {**base, "run": "a", "variant": "coarser"},
               "b": {**base, "run": "b", "variant": "transverse_damping-lo"},
               "c": {**base, "run": "c", "variant": "rival-slack_tension"}}
    assert cd.same_solve() == {"c": "b"}   # b and c stop at the first unstable speed, a not


# --- config/config.yaml through the same strict reader (issue 57, item 4) -----------------

TOP = [
    ("a duplicate key", lambda t: t + b"profile: ci\n", ["key 'profile' given twice"]),
    ("a non-UTF-8 byte", lambda t: t.replace(b"results: results", b"results: r\xe9sults"),
     ["not UTF-8", "results: r"]),
    ("a schema error", lambda t: t.replace(b"profile: default", b"profile: CI"),
     ["profile: 'CI' does not match"]),
    ("an unknown key", lambda t: t + b"profil: ci\n", ["'profil' was unexpected"]),
]


@pytest.mark.parametrize("name, edit, expect", TOP, ids=[t[0] for t in TOP])
def test_the_workflow_config_is_read_strictly_naming_the_file_and_key(config_copy, name, edit,
                                                                        expect):
    from mechrepro.config import workflow_config

    path = config_copy / "config.yaml"
    path.write_bytes(edit(path.read_bytes()))
    with pytest.raises(ConfigError) as err:
        workflow_config(path)
    msg = str(err.value)
    assert str(path) in msg and all(part in msg for part in expect), msg


def test_the_workflow_config_takes_the_command_line_over_the_file(config_copy):
    from mechrepro.config import workflow_config

    path = config_copy / "config.yaml"
    cfg = workflow_config(path, {"profile": "ci", "papers": ["saw_chain"]})
    assert cfg["profile"] == "ci" and cfg["papers"] == ["saw_chain"] and cfg["results"] == "results"
    with pytest.raises(ConfigError, match=r"with --config profile: profile = 3: must be of type"):
        workflow_config(path, {"profile": 3})


def test_a_workflow_config_error_stops_snakemake_before_any_job(tmp_path):
    """The wiring: the Snakefile reads config/config.yaml through workflow_config, not
    Snakemake's `configfile:` (which kept the second `profile:` and ran)."""
    import shutil
    import subprocess
    import sys

    from conftest import ROOT

    for item in ("Snakefile", "workflow", "config", "src", "profiles"):
        (shutil.copytree if (ROOT / item).is_dir() else shutil.copy2)(ROOT / item, tmp_path / item)
    top = tmp_path / "config" / "config.yaml"
    top.write_text(top.read_text() + "profile: ci\n")
    proc = subprocess.run([sys.executable, "-m", "snakemake", "--cores", "1", "-n"],
                          cwd=tmp_path, capture_output=True, text=True, timeout=120)
    out = proc.stdout + proc.stderr
    assert proc.returncode == 1, out
    assert "config/config.yaml: cannot read: key 'profile' given twice" in out, out
    assert "rule " not in out and "Traceback" not in out, out


def test_a_misspelt_scene_in_a_profile_overlay_is_named_as_such(edit_config):
    path = edit_config("saw_chain", lambda raw: raw["profiles"]["ci"]["scenes"].update(
        fig07_fig8={"resolution": {"K": 3}}))
    with pytest.raises(ConfigError) as err:
        load_paper(path, "ci")
    msg = str(err.value)
    assert f"{path}: profiles.ci.scenes.fig07_fig8: not one of the file's scenes" in msg, msg
    assert "fig07_fig08" in msg and "missing key" not in msg, msg


# --- a rival: a model the paper rules out, never an edit of its numbers -----------------------

@pytest.mark.parametrize("paper, rival, message", [
    # the paper's drive-link pitch (Sec. 4): an edit of a number the paper gives
    ("saw_chain", {"why": "w", "parameters": {"drive_link_pitch": 8.0}},
     "parameters.drive_link_pitch = 8.0: the paper gives drive_link_pitch"),
    # an assumed tension inside its own plausible range: a range end
    ("chain_drive", {"why": "w", "parameters": {"static_tension": 300.0}},
     "inside static_tension's plausible range"),
    # gravity switched off, while its assumed strength's range reaches zero: a range end
    ("joint_wear", {"why": "w", "effects_off": ["gravity"]},
     "its strength gravity is assumed with a plausible range .* that reaches zero"),
])
def test_the_loader_refuses_a_rival_that_edits_a_paper_value_or_stays_in_range(
        edit_config, paper, rival, message):
    path = edit_config(paper, lambda r: r.setdefault("rivals", {}).update(
        x={"removes": "r", **rival}))
    with pytest.raises(ConfigError, match=f"rivals.x.*{message}"):
        load_paper(path)
