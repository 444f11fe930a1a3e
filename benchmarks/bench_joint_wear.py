"""joint_wear benchmark: wall time of one period (stiff implicit, explicit, quasi-static)
and of the whole 86-hour prediction.  Not a test: it prints numbers against the targets.

    PYTHONPATH=src .venv/bin/python benchmarks/bench_joint_wear.py [--explicit-steps 20000]
    PYTHONPATH=src .venv/bin/python benchmarks/bench_joint_wear.py --floor [--profile ci] [--measure]
    PYTHONPATH=src .venv/bin/python benchmarks/bench_joint_wear.py --runs [RUN ...] [--profile ci] [--against REF]

The second prints only the solve floor of the profile's runs from operation counts
(:func:`floor`), with ``--measure`` beside their measured solve (benchmarks/_floor.py);
the default run prints it last.

Timings are the best of a few repeats; other jobs sharing the 2 cores make them
pessimistic.  The explicit integrator cannot finish a period on the stiff contact in any
reasonable time, so it runs for a step budget (deterministic, unlike a wall-clock budget)
and its time per period is extrapolated from the simulated time it reached.
"""
from __future__ import annotations

import argparse
import importlib
import math
import os
import time
from pathlib import Path

# must precede the first numpy import: OpenBLAS reads it when it loads
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import _floor  # noqa: E402

from mechrepro.config import load_paper
from mechrepro.models.joint_wear import setup
from mechrepro.solve import solve
from mechrepro.models.joint_wear import dynamics, quasistatic

ROOT = Path(__file__).resolve().parent.parent


def best_of(fn, repeats):
    best, out = float("inf"), None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def _reference(ref: str):
    """The model package as it is at git ``ref``, imported as a package of its own beside
    the working tree's (its submodules: ``importlib.import_module(name + ".quasistatic")``)."""
    import importlib.util
    import io
    import subprocess
    import sys
    import tarfile
    import tempfile

    tar = subprocess.run(["git", "archive", ref, "src/mechrepro/models/joint_wear"], cwd=ROOT,
                         capture_output=True, check=True).stdout
    tmp = Path(tempfile.mkdtemp())
    tarfile.open(fileobj=io.BytesIO(tar)).extractall(tmp, filter="data")
    # the revision's package under its own name, beside this tree's (no sys.path edit)
    pkg = tmp / "src" / "mechrepro" / "models" / "joint_wear"
    name = f"joint_wear_{ref.replace('-', '_').replace('/', '_')}"
    spec = importlib.util.spec_from_file_location(name, pkg / "__init__.py",
                                                  submodule_search_locations=[str(pkg)])
    sys.modules[name] = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(sys.modules[name])
    return sys.modules[name]


def side_by_side(cfg, repeats, against="main"):
    """The compiled Radau, BDF and RK45 (radau.py, bdf.py, rk45.py) against scipy's with
    the same compiled physics (clearance.py), in one process; LSODA runs in scipy only."""
    fb, _ = setup(cfg.runs["period_dynamic"])
    T = fb.period
    print("side by side (scipy -> compiled, best of repeats; the first compiled call is excluded)")
    for method, rtol, start, steps in (("Radau", 1e-5, "equilibrium", None),
                                       ("Radau", 1e-7, "equilibrium", None),
                                       ("BDF", 1e-6, "equilibrium", None),
                                       ("LSODA", 1e-7, "concentric", None),
                                       ("RK45", 1e-5, "equilibrium", 5000)):
        n = 2501 if start == "concentric" else 721
        run = lambda kernel: dynamics.simulate(fb, T, n, method=method, rtol=rtol,  # noqa: E731
                                               start=start, max_steps=steps, kernel=kernel)
        run("auto")
        t_old, r_old = best_of(lambda: run("scipy"), 1)
        if method not in dynamics.COMPILED:
            print(f"  {method:5s} rtol {rtol:.0e} {start:11s}: scipy {t_old:8.3f} s "
                  f"({r_old['steps']} steps)")
            continue
        t_new, r_new = best_of(lambda: run("auto"), repeats)
        print(f"  {method:5s} rtol {rtol:.0e} {start:11s}: scipy {t_old:8.3f} s -> compiled "
              f"{t_new:8.4f} s  ({t_old / t_new:6.1f}x; steps {r_old['steps']} / {r_new['steps']})")
    old = importlib.import_module(_reference(against).__name__ + ".quasistatic")
    for n in (360, 720):
        old.one_period(fb, n)
        quasistatic.one_period(fb, n)
        t_old, _ = best_of(lambda: old.one_period(fb, n), 20 * repeats)
        t_new, _ = best_of(lambda: quasistatic.one_period(fb, n), 20 * repeats)
        print(f"  quasi-static period, {n} samples: {against} {t_old * 1e3:6.2f} ms -> "
              f"{t_new * 1e3:6.2f} ms ({t_old / t_new:4.1f}x)")


def runs_side_by_side(profile: str, names, against="main"):
    """The solve time of the profile's runs ``names`` (every run without) with the model at
    git ``against`` and with the working tree's, in one process, run by run in turn (both
    under the same load), their kernels loaded first."""
    import mechrepro.models.joint_wear as new
    cfg = load_paper(ROOT / "config/papers/joint_wear.yaml", profile)
    old = _reference(against)
    runs = {r: cfg.runs[r] for r in names or cfg.runs}
    old.warm(list(runs.values()))
    new.warm(list(runs.values()))
    total = [0.0, 0.0]
    print(f"runs of profile {profile} side by side ({against} -> working tree)")
    for name, run in runs.items():
        t = []
        for model in (old, new):
            t0 = time.perf_counter()
            model.compute(run)
            t.append(time.perf_counter() - t0)
        total = [a + b for a, b in zip(total, t)]
        print(f"  {name:44s} {t[0]:8.2f} s -> {t[1]:8.2f} s ({t[0] / t[1]:4.2f}x)", flush=True)
    print(f"  {'all':44s} {total[0]:8.2f} s -> {total[1]:8.2f} s ({total[0] / total[1]:4.2f}x)")


_T, _S = _floor.TRANSCENDENTAL, _floor.SQRT

#: flops of one quasi-static period of n samples (:func:`.quasistatic.one_period`, two
#: position passes, the friction fixed point 2, 2 and 4 times), per sample:
#: 3 contact states x (setup: 6 sin/cos, a hypot, 2 divisions, ~45 mul/add; direction:
#: sin, cos) + 8 friction iterations x (force: hypot, sqrt, atan2, atan, pow, 2 divisions,
#: ~15; friction: sqrt, division, ~10) + 2 position passes x (positions from the bushing
#: centre: ~3 transcendentals, a sqrt, ~24) + the contact angle, plus the FFTs: per
#: friction iteration one real FFT pair of the contact angle (5 log2 n), per pass two
#: angles' first and second derivatives (15 log2 n)
QS_PER_SAMPLE = (3 * (45 + 6 * _T + 3 * _S + 2 * _T) + 8 * ((15 + 3 * _T + 4 * _S + _T)
                 + (10 + 2 * _S)) + 2 * (24 + 3 * _T + _S) + (5 + _T))
QS_PER_SAMPLE_LOG2N = 8 * 5 + 2 * 15


def qs_flops(n: int) -> float:
    """Flops of one quasi-static period of ``n`` samples (:data:`QS_PER_SAMPLE`)."""
    return n * (QS_PER_SAMPLE + QS_PER_SAMPLE_LOG2N * math.log2(n))


#: flops of one step of the compiled Radau IIA (3 stages, 4 states): ~3 simplified Newton
#: iterations x (3 right-hand sides of the clearance contact, ~110 mul/add + a sqrt, a pow
#: and an atan2 each; the real and the complex 4 x 4 back substitutions, 32 + 128; the
#: 3 x 3 stage transforms, ~150), the error estimate (a right-hand side and a solve), the
#: LU factors of both 4 x 4 matrices (2/3 n^3 real, 4x that complex) and step control
RADAU_STEP = (3 * (3 * (110 + _S + 2 * _T) + 32 + 128 + 150) + (110 + _S + 2 * _T + 32)
              + (43 + 172) + 50)
#: scipy's integrators, flops per step: LSODA, BDF ~1.5 Newton iterations of a right-hand
#: side and a 4 x 4 solve; the explicit pairs their stages' right-hand sides (RK45 6,
#: RK23 3, DOP853 12) and the combination
_RHS = 110 + _S + 2 * _T
SCIPY_STEP = {"LSODA": 1.5 * (_RHS + 32) + 50, "BDF": 1.5 * (_RHS + 32) + 50,
              "RK45": 6 * _RHS + 100, "RK23": 3 * _RHS + 50, "DOP853": 12 * _RHS + 300}
#: a dense-output sample of scipy's integrators (4 states x a degree-4 polynomial); per
#: (sample, bushing cell) of the local wear: the Archard increment, ~10
SAMPLE, LOCAL_CELL = 40, 10


def floor(profile="default", measure=False):
    """joint_wear's solve floor from operation counts.  A run is counted as its cost
    model counts it (:func:`.limits.work`: quasi-static periods of n samples per
    solver, dynamic periods of the Radau steps it estimates from rtol, scipy's steps,
    local-wear cells), each unit priced in flops instead of fitted seconds:

    - a quasi-static period of n samples, :func:`qs_flops`:
      n (QS_PER_SAMPLE + QS_PER_SAMPLE_LOG2N log2 n), ~2500 flops per sample at n = 720;
    - a compiled Radau step: RADAU_STEP (~2800 flops: Newton iterations on the 3-stage
      collocation system of 4 states, 4 x 4 real and complex LU);
    - a scipy step: SCIPY_STEP[method]; a dense-output sample SAMPLE; a local-wear
      (sample, cell) LOCAL_CELL;

    at :data:`_floor.RATE`.  The compiled Radau's own output samples are not counted.
    The Radau step counts are the cost model's estimates from rtol (a run whose contact
    rattles takes up to 50x more, which no run record announces)."""
    from mechrepro import limits as costs
    from mechrepro.models.joint_wear import limits

    cfg = load_paper(ROOT / "config/papers/joint_wear.yaml", profile)
    rows = []
    for name, run in cfg.runs.items():
        n = int(run["resolution"].get("n_steps", 720))
        price = {"qs_samples": qs_flops(n) / n, "Radau_steps": RADAU_STEP, "dynamic_samples": SAMPLE,
                 "local_cells": LOCAL_CELL, "groove_cells": LOCAL_CELL,
                 **{f"{k}_steps": v for k, v in SCIPY_STEP.items()}}
        flops = sum(price.get(k, 0.0) * v for k, v in limits.work(run).items())
        kind = run["solver"]
        if kind.startswith("clearance"):
            kind += " " + run["resolution"].get("method", "Radau")
        rows.append((name, kind, flops, costs.run_cost("joint_wear", run)["compute_s"]))
    _floor.report("joint_wear", profile, rows, "limits.run_cost compute_s, one compute per run",
                  cfg.runs if measure else None)


def main():
    ap = argparse.ArgumentParser()
    _floor.arguments(ap)
    ap.add_argument("--explicit-steps", type=int, default=20000)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--side-by-side-only", action="store_true")
    ap.add_argument("--against", default="main",
                    help="git commit whose quasi-static period the working tree's is timed against")
    ap.add_argument("--runs", nargs="*",
                    help="only the solve time of these runs of --profile (none named: all), "
                         "--against's model and the working tree's in turn")
    a = ap.parse_args()
    if a.floor:
        floor(a.profile, a.measure)
        return
    if a.runs is not None:
        runs_side_by_side(a.profile, a.runs, a.against)
        return
    cfg = load_paper(ROOT / "config/papers/joint_wear.yaml")
    side_by_side(cfg, a.repeats, a.against)
    if a.side_by_side_only:
        return
    fb, _ = setup(cfg.runs["period_dynamic"])
    T = fb.period
    print(f"joint_wear benchmark (period {T:.4g} s; 2 cores shared with other jobs: pessimistic)")

    t_stiff, r = best_of(lambda: dynamics.simulate(fb, T, 721, method="Radau", rtol=1e-5,
                                                   damping=True, start="equilibrium"), a.repeats)
    print(f"  stiff contact, Radau rtol 1e-5 + analytic Jacobian: {t_stiff:8.3f} s/period "
          f"({r['nfev']} RHS evals)   target <= 1 s: {'OK' if t_stiff <= 1 else 'MISSED'}")
    t_l, r = best_of(lambda: dynamics.simulate(fb, T, 721, method="Radau", rtol=1e-4,
                                               damping=True, start="equilibrium"), 1)
    print(f"  stiff contact, Radau rtol 1e-4 (error excites the pin's rocking mode): "
          f"{t_l:8.3f} s/period ({r['nfev']} RHS evals)")
    t_c, r = best_of(lambda: dynamics.simulate(fb, T, 721, method="LSODA", rtol=1e-5,
                                               damping=True, start="concentric"), 1)
    print(f"  stiff contact from the concentric start (impact + rattling), LSODA: {t_c:8.3f} s/period "
          f"({r['nfev']} RHS evals)")
    e = dynamics.simulate(fb, T, 721, method="RK45", rtol=1e-5, damping=True,
                          start="equilibrium", max_steps=a.explicit_steps)
    if e["status"] == 0:
        print(f"  explicit RK45: {e['wall']:8.3f} s/period (finished)")
    else:
        ext = e["wall"] * T / e["t_reached"]
        print(f"  explicit RK45 rtol 1e-5: {e['steps']} steps reached t = {e['t_reached']:.4g} s of {T:.4g} s in "
              f"{e['wall']:.1f} s -> extrapolated {ext:9.0f} s/period ({ext / t_stiff:.0f}x the stiff solver)")
    t_q, _ = best_of(lambda: quasistatic.one_period(fb, 720), 20)
    print(f"  quasi-static continuous contact (720 samples): {t_q * 1e3:8.3f} ms/period")

    run = cfg.runs["wear_prediction"]
    t_w, ds = best_of(lambda: solve(run), a.repeats)
    n = int(ds["n_simulations_prediction"])
    print(f"  whole 86-h prediction, B1 + B2 (2 x (5 calibration + 38 interval) periods): "
          f"{t_w:8.3f} s   target <= 10 s: {'OK' if t_w <= 10 else 'MISSED'}")
    real = (86 - 10) * 3600 / T
    print(f"  periods: {real:.0f} real vs {n // 2} simulated per side -> ratio {real / (n // 2):.0f}"
          f"   target >= 1000: {'OK' if real / (n // 2) >= 1000 else 'MISSED'}")
    print(f"  every period simulated (Fig. 6): quasi-static {t_q * real:8.1f} s, "
          f"stiff dynamic {t_stiff * real / 3600:8.2f} h (extrapolated from one period)")
    t_d, dd = best_of(lambda: solve(cfg.runs["wear_dynamic"]), 1)
    print(f"  whole 86-h prediction with the worn bushing fed back into the stiff dynamic joint, "
          f"B1 ({int(dd['n_simulations_per_side'])} + 5 periods): {t_d:8.1f} s; wear at 86 h "
          f"{float(dd['wear_at_end_B1']) * 1e3:.5f} mm vs quasi-static {float(ds['wear_at_end_B1']) * 1e3:.5f} mm")
    floor(a.profile, a.measure)


if __name__ == "__main__":
    main()
