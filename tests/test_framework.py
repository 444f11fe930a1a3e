"""Shared framework: effects, atomic netCDF writer, gather, cost of accuracy."""
import math

import numpy as np
import pytest
import xarray as xr

from conftest import ROOT
from mechrepro import io as mio
from mechrepro import accuracy
from mechrepro.accuracy import observed_order
from mechrepro.timing import time_call
from mechrepro.effects import EffectRegistry, UnknownEffect

RUN = {"paper": "saw_chain", "scene": "s", "run": "s", "study": None, "sweep": {},
       "effects": ["a"], "resolution": {"K": 3}, "parameters": {"x": 1.0},
       "units": {"x": "m"}, "options": {}, "seed": 0}


def small_dataset(value=1.0):
    return xr.Dataset({"y": ("t", np.arange(3.0) * value, {"units": "m", "long_name": "y"})},
                      {"t": ("t", np.arange(3.0), {"units": "s", "long_name": "time"})})


def test_registry_selects_only_named_effects_in_declaration_order():
    reg = EffectRegistry("demo")
    calls = []
    for name in ("first", "second", "third"):
        reg.register(name)(lambda name=name: calls.append(name))
    sel = reg.select(["third", "first"])
    assert list(sel) == ["first", "third"]
    for fn in sel.values():
        fn()
    assert calls == ["first", "third"]
    with pytest.raises(UnknownEffect, match="allowed"):
        reg.select(["fourth"])
    with pytest.raises(ValueError, match="twice"):
        reg.register("first")(lambda: None)


def test_writer_adds_provenance_and_refuses_missing_units(tmp_path):
    path = mio.write_dataset(small_dataset(), tmp_path / "r.nc", RUN)
    ds = mio.open_dataset(path)
    attrs = mio.run_attrs(ds)
    assert attrs["paper"] == "saw_chain" and attrs["resolution"] == {"K": 3}
    assert "numpy" in attrs["package_versions"] and attrs["code_version"]
    assert attrs["parameters"]["values_si"] == {"x": 1.0}
    bad = small_dataset()
    del bad["y"].attrs["units"]
    with pytest.raises(ValueError, match="y:units"):
        mio.write_dataset(bad, tmp_path / "bad.nc", RUN)
    assert not (tmp_path / "bad.nc").exists()


def test_interrupted_write_leaves_no_file(tmp_path, monkeypatch):
    target = tmp_path / "runs" / "r.nc"
    mio.write_dataset(small_dataset(1.0), target, RUN)
    before = target.read_bytes()

    def crash(self, path, **kw):
        with open(path, "wb") as f:
            f.write(b"CDF half")
        raise KeyboardInterrupt("killed mid-write")

    monkeypatch.setattr(xr.Dataset, "to_netcdf", crash)
    with pytest.raises(KeyboardInterrupt):
        mio.write_dataset(small_dataset(2.0), target, RUN)
    assert target.read_bytes() == before  # old complete file untouched
    # no partial file left (beside the result: its recorded checksum, mechrepro.io.sum_path)
    assert sorted(p.name for p in target.parent.iterdir()) == [".r.nc.sum", "r.nc"]
    with pytest.raises(KeyboardInterrupt):
        mio.write_dataset(small_dataset(2.0), tmp_path / "runs" / "new.nc", RUN)
    assert not (tmp_path / "runs" / "new.nc").exists()


def test_gather_stacks_scalars_and_equal_shapes(tmp_path):
    paths = []
    for i, K in enumerate((3, 5)):
        ds = small_dataset(K)
        ds["s"] = ((), float(K), {"units": "1", "long_name": "scalar"})
        if K == 5:  # a variable whose length differs between runs cannot be stacked
            ds["z"] = ("u", np.ones(K), {"units": "1", "long_name": "z"})
        run = dict(RUN, run=f"st-{i:03d}", study="st", sweep={"K": K})
        paths.append(mio.write_dataset(ds, tmp_path / f"{i}.nc", run))
    g = mio.gather_study(paths)
    assert list(g["run"].values) == ["st-000", "st-001"]
    assert list(g["K"].values) == [3, 5]
    assert g["s"].values.tolist() == [3.0, 5.0] and g["y"].shape == (2, 3)
    assert "z" not in g
    mio.check_cf(g)


def test_cost_of_accuracy_long_table():
    h = np.array([0.1, 0.05, 0.025])
    assert observed_order(h, 3 * h**2) == pytest.approx(2.0)
    st = xr.Dataset({"wall_time": ("run", [3.0, 1.0, 2.0]), "q": ("run", [1.1, 1.3, 1.2])},
                    coords={"K": ("run", [30, 10, 20])})
    Q = accuracy.AccuracyQuantities("demo")
    Q.register("q_exact")(lambda ds, e: np.abs(ds["q"].values - 1.0))
    Q.register("q_finest")(lambda ds, e: accuracy.against_finest(ds["q"].values, ds["K"].values,
                                                                   e["finer"]))
    entries = [{"name": "k", "study": "st", "knob": "K", "finer": "larger", "reference": "exact",
                "quantities": {"q_exact": {"error": "absolute", "unit": "N"}}},
               {"name": "kf", "study": "st", "knob": "K", "finer": "larger",
                "reference": "finest", "quantities": {"q_finest": {"error": "relative"}}}]
    rows = accuracy.rows(entries, lambda name: st, Q)
    exact = [r for r in rows if r["accuracy"] == "k"]
    assert [r["knob_value"] for r in exact] == [10, 20, 30]
    assert [r["error"] for r in exact] == pytest.approx([0.3, 0.2, 0.1])
    assert exact[0]["time_s"] == 1.0 and exact[0]["error_unit"] == "N"
    fin = [r for r in rows if r["accuracy"] == "kf"]   # the finest point is the reference
    assert [r["knob_value"] for r in fin] == [10, 20]
    assert fin[0]["error"] == pytest.approx(0.2 / 1.1)
    assert set(rows[0]) == set(accuracy.COLUMNS)
    result, seconds = time_call(lambda: 42, min_time=0.01)
    assert result == 42 and 0 < seconds < 0.01


def test_the_writer_encodes_cf_types_without_touching_the_callers_dataset(tmp_path):
    ds = xr.Dataset(
        {"n": ("t", np.array([1, 2, 3], dtype=np.int64), {"units": "1", "long_name": "count"}),
         "big": ((), np.int64(2**40), {"units": "1", "long_name": "too big for int32"}),
         "a": ("t", np.arange(3.0), {"units": "deg", "long_name": "angle"})},
        coords={"t": ("t", np.arange(3.0), {"units": "s", "long_name": "time"})})
    before = ds.copy(deep=True)
    mio.write_dataset(ds, tmp_path / "x.nc", RUN)
    assert ds.identical(before)   # units and dtypes changed in the file only
    back = mio.open_dataset(tmp_path / "x.nc")
    assert back["n"].dtype == np.int32 and back["big"].dtype == np.float64
    assert float(back["big"]) == 2.0**40 and back["n"].values.tolist() == [1, 2, 3]
    assert back["a"].attrs["units"] == "degree" and "_FillValue" not in back["t"].encoding


def test_a_solve_job_s_code_holds_what_its_model_imports_and_not_its_figures():
    """A solve job's code (mechrepro.solve.model_modules, workflow/rules/common.smk) is what
    the model's entry reaches: every module importing the model and its solvers loads is in
    it, its figures.py and validation.py (read by the notebook and validation jobs) are not,
    so editing a figure reruns no solve."""
    import os
    import subprocess
    import sys

    from mechrepro.inputs import read_yaml
    from mechrepro.solve import model_modules

    for paper in read_yaml(ROOT / "config" / "config.yaml")["papers"]:
        names = {p.split("/")[-1][:-3] for p in model_modules(paper)}
        assert not names & {"figures", "validation"}, (paper, names)
        loaded = subprocess.run(
            [sys.executable, "-c", f"import sys, mechrepro.models.{paper} as m\n"
             "for k in m.__all__: getattr(m, k)\n"
             f"print(*[n.split('.')[-1] for n in sys.modules if n.startswith('{'mechrepro.models.' + paper + '.'}')])"],
            capture_output=True, text=True, check=True, cwd=ROOT,
            env={**os.environ, "PYTHONPATH": str(ROOT / "src")})
        assert set(loaded.stdout.split()) <= names, (paper, set(loaded.stdout.split()) - names)


def test_the_framework_calls_a_papers_solver_as_run_ctx_and_refuses_an_unknown_one(monkeypatch):
    """mechrepro.solve.compute looks the run's solver up in its paper's ``SOLVERS`` and calls
    it as ``solver(run, context(run))`` (None for a paper without ``context``); a name the
    table lacks is one refusal naming the paper, the solver and what is allowed.  Every
    paper's table holds exactly the solvers its config declares."""
    import sys
    import types

    from mechrepro.inputs import read_yaml
    from mechrepro.solve import UnknownSolver, compute, model

    demo = types.ModuleType("mechrepro.models.demo")
    demo.SOLVERS = {"echo": lambda run, ctx: (run, ctx)}
    monkeypatch.setitem(sys.modules, "mechrepro.models.demo", demo)
    run = {"paper": "demo", "solver": "echo"}
    assert compute(run) == (run, None)
    demo.context = lambda r: ("context of", r["solver"])
    assert compute(run) == (run, ("context of", "echo"))
    with pytest.raises(UnknownSolver, match="demo: solver 'nope': allowed echo"):
        compute({**run, "solver": "nope"})
    for paper in read_yaml(ROOT / "config" / "config.yaml")["papers"]:
        declared = read_yaml(ROOT / "config" / "papers" / f"{paper}.yaml")["solvers"]
        assert set(model(paper).SOLVERS) == set(declared), paper
