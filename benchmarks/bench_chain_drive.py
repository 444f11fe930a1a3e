"""Benchmark (not a test): chain_drive FD speed sweeps, today's default against the new one.

    .venv/bin/python benchmarks/bench_chain_drive.py [--ref-ppp 24] [--repeat 3]

Prints, measured side by side in one run:

1. Equal-accuracy ratio (issue #18).  Scene ``accuracy_peak`` of the profile (a narrow
   sweep over the third resonance, polygonal action and end motion, no impact; its speeds,
   settling and resolution as config/papers/chain_drive.yaml sets them, printed with the
   results): peak amplitude = the maximum of the sampled amplitude over the speeds (the
   definition of the cost-of-accuracy table), its relative error against central
   differencing at ``--ref-ppp`` points per pitch (cfl 0.9), and the time of
   - today's default: the paper's mixed differencing (Eq. 2-38), 4 points per pitch,
     cfl 0.9, the numpy time loop (``kernel="numpy"``);
   - the new default: the scene's configured resolution with the compiled loop (numba,
     cached on disk; its first call, which loads or compiles the cache, is timed
     separately).
   Times: the march (best of ``--repeat``), and the whole sweep (effects evaluated on the
   time grid + march), both for both.
2. The 200-speed Fig. 5 sweep with length change and impact (fig05_length, 20.25 pitches;
   these scenes keep the mixed scheme, see docs/chain_drive.md): numpy loop vs compiled
   loop on the same grid, their largest amplitude difference, and the operation count
   (grid points x steps x speeds x ~19 flops per point-update) against the time.

3. The solve floor of the profile's chain_drive runs from operation counts (:func:`floor`;
   also alone with ``--floor``, and with ``--measure`` beside the measured solve of the
   same runs, benchmarks/_floor.py).

Timings on a shared machine are pessimistic; the ratios are measured in one run.

    .venv/bin/python benchmarks/bench_chain_drive.py --shooting [--scene fig09a]

prints the issue-26 side by side instead: a figure's peak and stability map by shooting
with adaptive speeds against the uniform 450-speed march, their peak errors against a
finer shooting reference and the time ratio (measured, and extrapolated to equal accuracy).

    .venv/bin/python benchmarks/bench_chain_drive.py --schemes [--ppp 2 3 4 6 8 12]

instead prints the cost-of-accuracy table of both schemes on ``accuracy_peak`` (error and
compiled march time per points per pitch, at cfl 0.9 and at the new default's cfl).

    .venv/bin/python benchmarks/bench_chain_drive.py --discrete [--profile ci]

prints the discrete-link span's cost (models/chain_drive/discrete.py) beside the string
march's on ``accuracy_peak`` (no impact), each to rtol 1e-3 of its own converged peak.

    .venv/bin/python benchmarks/bench_chain_drive.py --speed [--profile ci] [--repeat 3]

prints the issue-#18 side-by-side comparisons instead:

3. Galerkin RK4 (Fig. 10): the numpy loop (``kernel="numpy"``, one ``rhs_values`` call per
   stage) against the compiled loop (:mod:`.galerkin_kernel`), same tabulated forcing;
   time, ratio and the largest state difference.
4. The library check (``rk4_check_*``): one ``solve_ivp`` across the kinks with the forcing
   evaluated through the effects at every scalar time (the former path) against the
   segmented integration with the piecewise (interpolated) forcing; right-hand-side calls,
   time, and each one's distance to the segmented solution at rtol 1e-12.
5. FD speed sweeps: the whole scene (effects + march) with the source of ``--base`` (a git
   revision, ``main`` by default; ``git archive``, run in a subprocess) against this
   checkout's source, the same scenes and profile, interleaved, best of ``--repeat``; the
   effects' share (their evaluation on the time grid, :func:`.span.assemble`) apart.
"""
from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

# must precede the first numpy import: OpenBLAS reads it when it loads
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

import _floor  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent

from mechrepro.config import load_paper  # noqa: E402
from mechrepro.models.chain_drive import fd, fd_kernel, span  # noqa: E402

from mechrepro.models.chain_drive.limits import FLOPS_PER_UPDATE  # noqa: E402


def _peak(a):
    """Peak amplitude as the cost-of-accuracy table defines it: max over the sampled speeds."""
    return float(np.max(a))


def _peak_interp(a):
    """For information: parabolic interpolation through the three highest samples."""
    i = int(np.argmax(a))
    if 0 < i < a.size - 1:
        y0, y1, y2 = a[i - 1], a[i], a[i + 1]
        den = y0 - 2 * y1 + y2
        if den != 0:
            return float(y1 - 0.125 * (y0 - y2) ** 2 / den)
    return float(a[i])


def _scene(profile: str, name: str):
    run = load_paper(ROOT / "config/papers/chain_drive.yaml", profile).runs[name]
    return dict(run["parameters"]), dict(run["resolution"]), run   # the run: its effects


def _march(a, differencing, kernel):
    return fd.march(c=a["c"], P=a["P"], exc=a["exc"], s_star=a["s_star"], m=a["m"],
                    c_d=a["c_d"], grid=a["grid"], dt=a["dt"], n_steps=a["n_steps"],
                    measure_from=a["measure_from"], u_cap=0.05, differencing=differencing,
                    kernel=kernel)


def _timed(fn, repeat):
    best, out = np.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return out, best


def _updates(a):
    return a["c"].size * (a["grid"].n_long + 1) * a["n_steps"]


def equal_accuracy(profile: str, ref_ppp: int, repeat: int) -> None:
    prm, res, eff = _scene(profile, "accuracy_peak")
    om = span.speed_axis(prm, int(res["n_speeds"]))
    new = {"differencing": res.get("differencing", "mixed"), "ppp": int(res["points_per_pitch"]),
           "cfl": float(res["cfl"]), "kernel": "compiled" if fd_kernel.available() else "numpy"}
    old = {"differencing": "mixed", "ppp": 4, "cfl": 0.9, "kernel": "numpy"}

    def assemble(ppp, cfl, differencing):
        # the differencing goes into the assembly: it sets s* (0 for central), and
        # fd.march(differencing="mixed") keeps the s* it is given (a central s* = 0 before:
        # the "today" row marched central differencing under a mixed label)
        return span.assemble(eff, prm, om, dict(res, points_per_pitch=ppp, cfl=cfl,
                                                 differencing=differencing))

    t0 = time.perf_counter()
    if fd_kernel.available():   # a tiny march: imports numba, loads (or compiles) the kernel
        fd.march(c=np.ones(1), P=np.full(1, 400.0), m=0.61, c_d=0.0, grid=fd.Grid(0.25, 8, 8),
                 dt=1e-5, n_steps=4, exc=fd.Excitation(), kernel="compiled")
    t_load = time.perf_counter() - t0
    ref_a = assemble(ref_ppp, 0.9, "central")
    ref = _peak(_march(ref_a, "central", "auto").amplitude)
    rows = {}
    for name, s in (("today", old), ("new", new)):
        a, t_asm = _timed(lambda: assemble(s["ppp"], s["cfl"], s["differencing"]), repeat)
        r, t_m = _timed(lambda: _march(a, s["differencing"], s["kernel"]), repeat)
        rows[name] = dict(s, peak=_peak(r.amplitude), interp=_peak_interp(r.amplitude),
                          march=t_m, sweep=t_m + t_asm, updates=_updates(a),
                          steps=a["n_steps"], points=a["grid"].n_long + 1)
    rpm = om * 30 / np.pi
    print(f"== equal accuracy: scene accuracy_peak ({profile}), {om.size} speeds over "
          f"{rpm[0]:.1f}-{rpm[-1]:.1f} rpm, {res.get('decay_times')} decay times; reference: "
          f"central at {ref_ppp} points per pitch, cfl 0.9: peak {ref * 1e3:.5f} mm")
    print(f"{'':10s} {'scheme':8s} {'ppp':>4s} {'cfl':>5s} {'loop':>8s} {'points':>6s} "
          f"{'steps':>6s} {'peak mm':>9s} {'error':>7s} {'(interp.)':>9s} {'march s':>8s} "
          f"{'sweep s':>8s}")
    for name, r in rows.items():
        print(f"{name:10s} {r['differencing']:8s} {r['ppp']:4d} {r['cfl']:5.2f} {r['kernel']:>8s} "
              f"{r['points']:6d} {r['steps']:6d} {r['peak'] * 1e3:9.5f} "
              f"{abs(r['peak'] / ref - 1):7.2%} {abs(r['interp'] / ref - 1):9.2%} "
              f"{r['march']:8.3f} {r['sweep']:8.3f}")
    o, n = rows["today"], rows["new"]
    print(f"ratio today / new: march {o['march'] / n['march']:.1f}x, whole sweep (incl. effects) "
          f"{o['sweep'] / n['sweep']:.1f}x; grid-point updates {o['updates'] / n['updates']:.2f}x "
          f"fewer; error {abs(o['peak'] / ref - 1):.2%} -> {abs(n['peak'] / ref - 1):.2%}")
    print(f"compiled loop: import numba and load the kernel from its disk cache (or compile "
          f"it, once per checkout) {t_load:.2f} s per process, not in the times above")


def fig05(profile: str, repeat: int) -> None:
    prm, res, eff = _scene(profile, "fig05_length")
    prm["centre_distance"] = 20.25
    om = span.speed_axis(prm, 200)
    a = span.assemble(eff, prm, om, res)
    diff = res.get("differencing", "mixed")
    rn, tn = _timed(lambda: _march(a, diff, "numpy"), 1)
    rc, tc = _timed(lambda: _march(a, diff, "auto"), repeat)
    ok = ~rn.unstable
    dmax = float(np.max(np.abs(rc.amplitude[ok] / rn.amplitude[ok] - 1))) if ok.any() else 0.0
    up = _updates(a)
    print(f"== 200-speed Fig. 5 sweep (fig05_length, {profile}, 20.25 pitches, {diff} "
          f"differencing, {res['points_per_pitch']} points per pitch, cfl {res['cfl']}): "
          f"{om.size} speeds x {a['grid'].n_long + 1} points x {a['n_steps']} steps = "
          f"{up:.3g} point-updates")
    print(f"numpy loop    : {tn:8.2f} s  ({tn / up * 1e9:5.1f} ns per point-update)")
    print(f"compiled loop : {tc:8.2f} s  ({tc / up * 1e9:5.1f} ns per point-update; "
          f"{FLOPS_PER_UPDATE * up / tc / 1e9:.2f} GFlop/s at ~{FLOPS_PER_UPDATE} flops each)")
    print(f"numpy / compiled: {tn / tc:.1f}x; largest amplitude difference {dmax:.1e} "
          f"(relative, stable speeds), unstable speeds equal: "
          f"{bool(np.array_equal(rn.unstable, rc.unstable))}")
    fl = FLOPS_PER_UPDATE * up
    print(f"operation-count floor: {fl:.3g} flops = {fl / _floor.RATE:.2f} s at "
          f"{_floor.RATE / 1e9:g} GFlop/s (one core, SIMD); compiled loop at "
          f"{tc / (fl / _floor.RATE):.1f}x the floor")


def schemes(profile: str, ppps, ref_ppp: int) -> None:
    prm, res0, eff = _scene(profile, "accuracy_peak")
    om = span.speed_axis(prm, int(res0["n_speeds"]))
    cfl_new = float(res0["cfl"])

    def one(ppp, differencing, cfl):
        a = span.assemble(eff, prm, om, dict(res0, points_per_pitch=ppp, cfl=cfl,
                                             differencing=differencing))
        r, t = _timed(lambda: _march(a, differencing, "auto"), 1)
        return _peak(r.amplitude), t

    ref, _ = one(ref_ppp, "central", 0.9)
    print(f"reference: central differencing at {ref_ppp} points per pitch, cfl 0.9, "
          f"peak {ref * 1e3:.5f} mm (max over the sampled speeds)")
    # each (scheme, cfl) once: at a scene cfl of 0.9 the two central columns were one
    # column printed twice
    schemes_ = list(dict.fromkeys((("central", 0.9), ("central", cfl_new), ("mixed", 0.9))))
    print("points/pitch" + "".join(f"  {d} cfl {c:g}: error time[s]" for d, c in schemes_))
    for ppp in ppps:
        cols = [one(ppp, d, c) for d, c in schemes_]
        print(f"{ppp:12d}  " + "  ".join(f"{abs(p / ref - 1):19.2%} {t:7.2f}" for p, t in cols))


# ---------------------------------------------------------------------------- issue #18

def _galerkin_inputs(profile, name):
    from mechrepro.models.chain_drive import galerkin as G
    run = load_paper(ROOT / "config/papers/chain_drive.yaml", profile).runs[name]
    prm, res = run["parameters"], run["resolution"]
    g = G._galerkin_setup(run, prm, res)
    return G, run, prm, res, g


def galerkin_rk4(profile: str, repeat: int) -> None:
    print(f"== Galerkin RK4 (Fig. 10, {profile}): numpy loop vs compiled loop, same forcing")
    for name in ("fig10_longitudinal", "fig10_uncoupled", "fig10_transverse5"):
        G, run, prm, res, g = _galerkin_inputs(profile, name)
        model, dt, n = g["model"], g["dt"], g["n_steps"]
        st = G.stage_times(dt, n)
        F, t_f = _timed(lambda: G.forcing_arrays(run, prm, g["w1"], g["geo"], st.ravel(),
                                                 step=g["window"]), 1)
        F = {k: v.reshape(st.shape) for k, v in F.items()}
        y0 = np.zeros(2 * (model.n_t + model.n_l))
        G.rk4_tabulated(model, y0, dt, 4, {k: v[:4] for k, v in F.items()}, kernel="compiled")
        (_, ya), t_np = _timed(lambda: G.rk4_tabulated(model, y0, dt, n, F, kernel="numpy"), 1)
        (_, yc), t_c = _timed(lambda: G.rk4_tabulated(model, y0, dt, n, F, kernel="compiled"),
                              repeat)
        d = float(np.max(np.abs(ya - yc)) / np.max(np.abs(ya)))
        print(f"{name:20s} n_t={model.n_t} n_l={model.n_l} {n} steps ({4 * n} rhs): numpy "
              f"{t_np:6.2f} s ({t_np / (4 * n) * 1e6:5.1f} us/rhs), compiled {t_c:6.3f} s "
              f"({t_c / (4 * n) * 1e6:5.2f} us/rhs), ratio {t_np / t_c:5.0f}x; forcing "
              f"(vectorised) {t_f:.3f} s; max |dy|/max|y| {d:.1e}")


def library_check(profile: str) -> None:
    print(f"== library check (rk4_check_*, {profile}): solve_ivp DOP853 rtol 1e-9 over 8 tooth "
          "periods")
    for name in ("rk4_check_coupled", "rk4_check_uncoupled"):
        G, run, prm, res, g = _galerkin_inputs(profile, name)
        model = g["model"]
        n_lib = g["per_tooth"] * int(round(float(res["library_periods"])))
        t_ev = np.arange(n_lib + 1) * g["dt"]
        y0 = np.zeros(2 * (model.n_t + model.n_l))
        edges = G.forcing_breakpoints(prm, g["w1"], g["geo"], g["window"], t_ev[-1])

        def new(rtol):
            pf = G.PiecewiseForcing(run, prm, g["w1"], g["geo"], g["window"], edges)
            return G.library_piecewise(model.rhs_values, pf.on, edges, y0, t_ev, rtol=rtol)

        def old():   # one solve_ivp across the kinks, the forcing evaluated per call
            from scipy.integrate import solve_ivp

            def at(t):
                F = G.forcing_arrays(run, prm, g["w1"], g["geo"], t, g["window"])
                return tuple(float(F[k]) for k in ("g", "h", "gd", "hd", "Pt"))
            sol = solve_ivp(lambda t, y: model.rhs_values(y, *at(t)), (0.0, t_ev[-1]), y0,
                            method="DOP853", t_eval=t_ev, rtol=1e-9, atol=1e-14,
                            max_step=g["dt"])
            return sol.y.T, sol.nfev

        (y_ref, _), _ = _timed(lambda: new(1e-12), 1)
        (y_old, n_old), t_old = _timed(old, 1)
        (y_new, n_new), t_new = _timed(lambda: new(1e-9), 1)
        xi = g["xi"]

        def err(y):
            return float(np.max(np.abs(model.u2_at(y - y_ref, xi)))
                         / np.max(np.abs(model.u2_at(y_ref, xi))))
        print(f"{name:20s} {edges.size - 1} smooth intervals; across the kinks: {n_old:6d} rhs "
              f"{t_old:6.2f} s, error {err(y_old):.1e}; segmented: {n_new:5d} rhs {t_new:5.2f} s, "
              f"error {err(y_new):.1e} (errors against segmented rtol 1e-12, probe, relative); "
              f"ratio {t_old / t_new:.0f}x")


_FD_SCRIPT = """
import sys, time, json
from mechrepro.config import load_paper
from mechrepro.solve import solve
runs = load_paper(sys.argv[1] + "/config/papers/chain_drive.yaml", sys.argv[2]).runs
import numpy as np
from mechrepro.models.chain_drive import fd
# numba import and kernel load (or compile, in a fresh copy of the source), not timed
fd.march(c=np.ones(1), P=np.full(1, 400.0), m=0.61, c_d=0.0, grid=fd.Grid(0.25, 8, 8), dt=1e-5,
         n_steps=4, exc=fd.Excitation(), kernel="compiled")
solve(runs["accuracy_peak"])
from mechrepro.models.chain_drive import span
asm = span.assemble
spent = []


def timed_assemble(*a, **k):
    t0 = time.perf_counter()
    r = asm(*a, **k)
    spent.append(time.perf_counter() - t0)
    return r


span.assemble = timed_assemble
out = {}
for name in sys.argv[3:]:
    spent.clear()
    t0 = time.perf_counter(); solve(runs[name])
    out[name] = (time.perf_counter() - t0, sum(spent))
print(json.dumps(out))
"""


def fd_sweeps(profile: str, repeat: int, base: str = "main") -> None:
    import json
    import subprocess
    import tempfile
    names = ["fig05_plain", "fig05_length", "fig07_tension", "fig08_external", "fig09a", "fig09b"]
    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run(f"git -C {ROOT} archive {base} src | tar -x -C {tmp}", shell=True,
                       check=True)
        times = {"main": [], "here": []}
        for _ in range(repeat):
            for label, src in (("main", f"{tmp}/src"), ("here", str(ROOT / "src"))):
                r = subprocess.run([sys.executable, "-c", _FD_SCRIPT, str(ROOT), profile, *names],
                                   env={"PYTHONPATH": src, "PATH": "/usr/bin:/bin"},
                                   capture_output=True, text=True, check=True)
                times[label].append(json.loads(r.stdout.strip().splitlines()[-1]))
    print(f"== FD speed sweeps ({profile}): whole scene (effects + march), {base} ('main' "
          f"below) vs this checkout, best of {repeat}")
    tot = {"main": np.zeros(2), "here": np.zeros(2)}
    for n in names:
        b = {k: np.min([t[n] for t in v], axis=0) for k, v in times.items()}
        tot = {k: tot[k] + b[k] for k in tot}
        print(f"{n:16s} main {b['main'][0]:6.2f} s (effects {b['main'][1]:5.2f} s)  here "
              f"{b['here'][0]:6.2f} s (effects {b['here'][1]:5.2f} s)  ratio "
              f"{b['main'][0] / b['here'][0]:4.1f}x (effects {b['main'][1] / b['here'][1]:4.1f}x)")
    print(f"{'total':16s} main {tot['main'][0]:6.2f} s (effects {tot['main'][1]:5.2f} s)  here "
          f"{tot['here'][0]:6.2f} s (effects {tot['here'][1]:5.2f} s)  ratio "
          f"{tot['main'][0] / tot['here'][0]:4.1f}x (effects {tot['main'][1] / tot['here'][1]:4.1f}x)")


def _top_peaks(sp, amp, un, k: int = 3):
    """The k largest stable local maxima (speeds [rpm], amplitudes [m]) of prominence
    >= 2 % of the largest (the adaptive sweep's own peak criterion)."""
    from scipy.signal import find_peaks

    A = np.where(un, 0.0, amp)
    idx, _ = find_peaks(np.r_[0.0, A, 0.0], prominence=0.02 * A.max())
    idx = idx - 1
    idx = idx[np.argsort(A[idx])[::-1][:k]]
    return sp[idx], A[idx]


def _bands(sp, un):
    """The unstable bands of a sampled stability map: (first, last) unstable speed of each
    run of consecutive unstable samples (it printed the edges' brackets before, which read
    as two one-point bands for Fig. 9a's one band)."""
    idx = np.flatnonzero(un)
    if not idx.size:
        return []
    cut = np.flatnonzero(np.diff(idx) > 1)
    return [(round(float(sp[a]), 1), round(float(sp[b]), 1))
            for a, b in zip(np.r_[idx[0], idx[cut + 1]], np.r_[idx[cut], idx[-1]])]


def shooting_vs_march(profile: str, scene: str = "fig09a", n_uniform: int = 450,
                      k_peaks: int = 3) -> None:
    """Issue 26: the peak and stability map of a figure by shooting/Floquet with adaptive
    speed sampling (the scene as configured) against today's uniform march (n_uniform
    speeds, settling 4 decay times, growth window 2 tooth periods), side by side in one
    run, at equal accuracy of the peaks' speeds and amplitudes.

    Reference: shooting with peak_tol / 8 (the same scheme's periodic steady state, peaks
    bisected 8x finer).  Error of a method = max over the reference's ``k_peaks`` largest
    peaks of |speed - reference| [rpm] and |amplitude / reference - 1| at its nearest peak.
    The march's speed error is set by its grid (~ spacing / 4 on average, spacing / 2 at
    worst): reaching the shooting's speed error needs ~ n_uniform x (march error / shooting
    error) speeds, and its time grows linearly with the speeds; that extrapolated ratio is
    printed beside the measured one (a lower bound when the march is less accurate)."""
    from threadpoolctl import threadpool_limits

    from mechrepro.models.chain_drive import solver
    from mechrepro.solve import pack
    run = load_paper(ROOT / "config/papers/chain_drive.yaml", profile).runs[scene]
    prm, res = dict(run["parameters"]), dict(run["resolution"])
    fd_kernel.warm()
    res_ref = dict(res, peak_tol=float(res["peak_tol"]) / 8)
    res_m = {k: v for k, v in res.items() if k not in ("method", "edge_tol", "peak_tol")}
    res_m.update(n_speeds=n_uniform, decay_times=4, window_periods=2)
    run_m = dict(run, options={k: v for k, v in run.get("options", {}).items()
                               if k != "dense_near_elastic"})
    # the march's amplitude carries the transient left after its settling, e^-D at D decay
    # times: a second march settles until that is below the shooting's 0.01 % (D = 9.2)
    settled = f"march {n_uniform}, D 9.2"
    res_s = dict(res_m, decay_times=9.2)
    with threadpool_limits(1, user_api="blas"):
        out = {}
        for name, r, rs in (("shooting", run, res), ("reference", run, res_ref),
                            (f"march {n_uniform}", run_m, res_m), (settled, run_m, res_s)):
            t0 = time.perf_counter()
            d = pack(solver.speed_sweep({**r, "parameters": prm, "resolution": rs}), r)
            out[name] = (d, time.perf_counter() - t0)
    d_ref = out["reference"][0]
    sp_ref, a_ref = _top_peaks(d_ref.speed.values, d_ref.amplitude.values,
                               d_ref.unstable.values.astype(bool), k_peaks)
    print(f"== {scene} ({profile}): shooting + adaptive speeds vs uniform march, equal accuracy "
          f"of the {k_peaks} largest stable peaks (reference: shooting, peak_tol "
          f"{res_ref['peak_tol']:g} rpm: peaks at {np.round(sp_ref, 2).tolist()} rpm, "
          f"{np.round(a_ref * 1e3, 4).tolist()} mm)")
    err, bands = {}, {}
    for name in ("shooting", f"march {n_uniform}", settled):
        d, t = out[name]
        un = d.unstable.values.astype(bool)
        sp, a = _top_peaks(d.speed.values, d.amplitude.values, un, 4 * k_peaks)
        j = [int(np.argmin(np.abs(sp - s0))) for s0 in sp_ref]
        e_w = float(np.max(np.abs(sp[j] - sp_ref)))
        e_a = float(np.max(np.abs(a[j] / a_ref - 1)))
        err[name] = (e_w, e_a, t)
        bands[name] = _bands(d.speed.values, un)
        print(f"{name:12s} speeds {d.speed.size:5d}  time {t:7.2f} s  peak speed error "
              f"{e_w:7.3f} rpm  peak amplitude error {e_a:7.2%}  unstable bands "
              f"{_bands(d.speed.values, un)}")
    (ws, as_, ts), (wm, am, tm) = err["shooting"], err[f"march {n_uniform}"]
    wd, ad, td = err[settled]
    print(f"time ratio march / shooting, measured: {tm / ts:.2f}x ({n_uniform} speeds, 4 decay "
          f"times), {td / ts:.2f}x ({settled})"
          + ("; both marches less accurate in peak speed and amplitude: lower bounds at equal "
             "accuracy" if min(wm, wd) >= ws and min(am, ad) >= as_ else ""))
    if wd > ws > 0:
        # the peak-speed error of a uniform grid falls linearly with its spacing, and the
        # march's time grows linearly with its speeds (one vectorised march)
        print(f"at equal peak-speed accuracy (~{n_uniform * wd / ws:.0f} uniform speeds, the "
              f"error linear in the spacing; time linear in the speeds): march ({settled}) "
              f"~{td * wd / ws:.0f} s, ratio ~{td * wd / ws / ts:.1f}x (extrapolated, a lower "
              f"bound: its amplitude error, {ad:.2%} against {as_:.2%} at {n_uniform} speeds, "
              f"is partly the peaks missed between its speeds and partly the march's own step "
              f"and settling, not measured at that grid)"
              + ("; the uniform marches find none of the shooting's unstable bands"
                 if bands["shooting"] and not bands[settled] else ""))


def rk4_step_flops(n_t: int, n_l: int, n_q: int, coupling: bool) -> int:
    """Flops of one step of the compiled RK4 (:func:`.galerkin_kernel.rk4`, as written):
    four right-hand sides, each six products with the modal matrices (2 n^2 each), the load
    at the n_q quadrature points (~6 each) and its projection on the sine modes
    (2 n_q n_t); with the coupling, the mode slopes and curvatures at the points
    (4 n_q (n_t + n_l)), their products (~12 per point) and the projection on the cosine
    modes (2 n_q n_l); and the three stage states and the update of the 2 (n_t + n_l)
    states (~13 each).  The forcing's evaluation is not counted."""
    rhs = 6 * (n_t * n_t + n_l * n_l) + 6 * n_q + 2 * n_q * n_t
    if coupling:
        rhs += 4 * n_q * (n_t + n_l) + 12 * n_q + 2 * n_q * n_l
    return 4 * rhs + 26 * (n_t + n_l)


def floor(profile: str, measure: bool = False) -> None:
    """chain_drive's solve floor from operation counts: every run of the profile sized by
    its declared cost model (:func:`.limits.size`, no solve), its flops counted as

    - march: speeds x points x steps x FLOPS_PER_UPDATE;
    - shooting, per speed of the initial grid (the adaptive refinement adds speeds; a method that needed no refinement would
      still need these): :func:`.limits.shooting_flops`, the monodromy march of 2n + 1
      lanes over one period, one LU solve and one Hessenberg reduction;
    - Galerkin: RK4 steps x :func:`rk4_step_flops` of the run's model (its step, modes
      and quadrature built as the solve builds them, no step taken); the solve_ivp
      comparison of the runs that ask for one is not counted;
    - the checks (exact, manufactured, time-step study, four-bar and impact curves): not
      counted (their rows show 0 flops beside the cost model's estimate);

    at :data:`_floor.RATE` (benchmarks/_floor.py).  The effects' evaluation on the time grid
    (transcendentals, ~30-60 % of a march today) is not in the floor."""
    from mechrepro import limits as costs
    from mechrepro.models.chain_drive import galerkin, limits
    cfg = load_paper(ROOT / "config/papers/chain_drive.yaml", profile)
    rows = []
    for name, run in cfg.runs.items():
        est = costs.run_cost("chain_drive", run)["seconds"]
        if run["solver"] == "galerkin":
            g = galerkin._galerkin_setup(run, run["parameters"], run["resolution"])
            mdl = g["model"]
            rows.append((name, "galerkin RK4", g["n_steps"] * rk4_step_flops(
                mdl.n_t, mdl.n_l, mdl.x.size, mdl.coupling), est))
            continue
        if run["solver"] != "speed_sweep" or run["resolution"].get("method") == "discrete":
            rows.append((name, f"{run['solver']} (not counted)", 0.0, est))
            continue
        z = limits.size(run)
        n = z["points"]
        if "steps" in z:
            rows.append((name, "speed_sweep march", z["speeds"] * n * z["steps"]
                         * FLOPS_PER_UPDATE, est))
        else:
            rows.append((name, "speed_sweep shooting",
                         float(limits.shooting_flops(n, z["steps_per_period"]).sum()), est))
    _floor.report("chain_drive", profile, rows, "limits.run_cost, per run (config/costs.csv)", cfg.runs if measure else None)


def _to_rtol(values: dict, order: float, rtol: float):
    """(converged value, cheapest knob whose error against it is <= rtol, errors): the
    converged value is the finest level's Richardson extrapolate at ``order``; an error is
    |value / converged - 1|."""
    knobs = sorted(values)
    fine, finer = values[knobs[-2]], values[knobs[-1]]
    r = knobs[-1] / knobs[-2]
    conv = finer + (finer - fine) / (r ** order - 1)
    errs = {k: abs(values[k] / conv - 1) for k in knobs}
    ok = [k for k in knobs if errs[k] <= rtol]
    return conv, (ok[0] if ok else None), errs


def discrete_vs_string(profile: str, rtol: float = 1e-3) -> None:
    """The discrete-link span (:mod:`.discrete`) beside the string march on scene
    ``accuracy_peak`` (third resonance, no impact): each one's peak amplitude (one-mode
    vertex through the sampled speeds) against its own converged value (Richardson from its
    two finest levels: RK4 steps per tooth period at order 4, central differencing's points
    per pitch at order 2), and the time of the cheapest level within ``rtol``."""
    from mechrepro.models.chain_drive import claims as C, discrete as D, geometry

    run = load_paper(ROOT / "config/papers/chain_drive.yaml", profile).runs["accuracy_peak"]
    prm, res = dict(run["parameters"]), dict(run["resolution"])
    w = np.linspace(prm["speed_min"], prm["speed_max"], 13)       # rad/s (SI)
    speeds = w * geometry.RPM
    disc, t_disc = {}, {}
    # 50 steps per tooth period is beyond RK4's stability interval for the pitch-scale mode
    for steps in (100, 200, 400, 800):
        t0 = time.perf_counter()
        amp = [D.periodic_orbit(run, prm, x, steps)["amplitude"] for x in w]
        t_disc[steps] = time.perf_counter() - t0
        disc[steps] = C.one_mode_peak(speeds, amp)[1]
    string, t_str = {}, {}
    for ppp in (3, 4, 6, 8, 12, 16):
        r = dict(res, points_per_pitch=ppp, differencing="central", cfl=0.98)
        t0 = time.perf_counter()
        out = span.sweep(run, prm, w, r)
        t_str[ppp] = time.perf_counter() - t0
        string[ppp] = C.one_mode_peak(speeds, out["amplitude"])[1]
    print(f"\n== discrete span vs string, scene accuracy_peak ({profile}), 13 speeds "
          f"{speeds[0]:.1f}-{speeds[-1]:.1f} rpm, peak amplitude to rtol {rtol:g} against each "
          "one's own converged value")
    for name, vals, times, order, unit in (("discrete (RK4)", disc, t_disc, 4.0, "steps/period"),
                                           ("string (central, cfl 0.98)", string, t_str, 2.0,
                                            "points/pitch")):
        conv, ok, errs = _to_rtol(vals, order, rtol)
        print(f"{name}: converged {conv * 1e3:.5g} mm")
        for k in sorted(vals):
            print(f"   {k:5d} {unit}: {vals[k] * 1e3:.6g} mm, error {errs[k]:.2e}, {times[k]:.2f} s")
        print(f"   cheapest within {rtol:g}: " + (f"{ok} {unit}, {times[ok]:.2f} s" if ok else "none"))
    print(f"discrete converged / string converged - 1 = "
          f"{_to_rtol(disc, 4.0, rtol)[0] / _to_rtol(string, 2.0, rtol)[0] - 1:+.3%}")


def main() -> None:
    ap = argparse.ArgumentParser()
    _floor.arguments(ap)
    ap.add_argument("--ref-ppp", type=int, default=24)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--schemes", action="store_true",
                    help="print the cost-of-accuracy table of both schemes instead")
    ap.add_argument("--shooting", action="store_true",
                    help="print shooting + adaptive speeds vs the uniform march (issue 26)")
    ap.add_argument("--scene", default="fig09a")
    ap.add_argument("--ppp", type=int, nargs="+", default=[2, 3, 4, 6, 8, 12])
    ap.add_argument("--only", choices=["galerkin", "library", "fd"], default=None,
                    help="with --speed: one of the comparisons")
    ap.add_argument("--speed", action="store_true",
                    help="print the issue-#18 comparisons (Galerkin RK4, library check, FD "
                         "sweeps against --base) instead")
    ap.add_argument("--discrete", action="store_true",
                    help="print the discrete-link span's cost beside the string march's "
                         "(each to rtol 1e-3 of its own converged peak, no impact)")
    ap.add_argument("--base", default="main",
                    help="with --speed: the git revision the FD sweeps are compared with")
    a = ap.parse_args()
    if a.floor:
        floor(a.profile, a.measure)
        return
    if a.discrete:
        discrete_vs_string(a.profile)
        return
    if a.shooting:
        shooting_vs_march(a.profile, a.scene)
        floor(a.profile, a.measure)
        return
    if a.speed:
        if a.only in (None, "galerkin"):
            galerkin_rk4(a.profile, a.repeat)
        if a.only in (None, "library"):
            library_check(a.profile)
        if a.only in (None, "fd"):
            fd_sweeps(a.profile, a.repeat, a.base)
        return
    if not fd_kernel.available():
        print("numba is not installed: the compiled loop is unavailable (pip install -r "
              "requirements.txt); the new default then runs the numpy loop")
    if a.schemes:
        schemes(a.profile, a.ppp, a.ref_ppp)
        return
    equal_accuracy(a.profile, a.ref_ppp, a.repeat)
    fig05(a.profile, a.repeat)
    floor(a.profile, a.measure)


if __name__ == "__main__":
    main()
