"""disk_tension speed: Eq. (9) vs eigen-analysis, and axisym vs 2-D at equal accuracy.

Run: `make benchmark` or `.venv/bin/python benchmarks/bench_disk_tension.py`;
`... bench_disk_tension.py --floor [--profile ci] [--measure]` prints only the solve floor of
the profile's runs from operation counts (:func:`floor`; the default run prints it last),
with ``--measure`` beside their measured solve (benchmarks/_floor.py);
`... bench_disk_tension.py --versus <git rev> [ci|default]` times the paper's solver jobs
(the batch and the 2-D Table 1-2 scene) under that revision's src and this worktree's, side
by side in alternating fresh processes (issue 18).
Targets (issue 4): the whole Fig. 6 + Fig. 8 grid (9 r_c x 3 r_f x N_d 0..4) with the
axisymmetric model in <= 3 s at better than 1e-4 relative frequency accuracy; the 2-D
model within 0.1 % of the exact unrolled N_d = 4 frequency in <= 60 s.  Printed, never
asserted: timings depend on the machine (and on whatever else shares its cores).

Every timing is the fastest of repeated calls (mechrepro.timing.time_call), and the grid
reference is the Richardson extrapolation of 64 and 128 elements (256 elements carry ~10x the
round-off of 128).  The benchmark runs with one BLAS thread unless the caller sets
OPENBLAS_NUM_THREADS (the axisym model solves small dense eigenproblems, which BLAS threads
only slow down on a shared machine; a 24 -> 32 element "cliff" once blamed on it could not be
reproduced, issue 29, and its comparison was removed).
"""
import os

# must precede the first numpy import: OpenBLAS reads it when it loads
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import subprocess  # noqa: E402
import sys  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent

from mechrepro.timing import phase, time_call  # noqa: E402
from mechrepro.models.disk_tension.effects import thermal_load  # noqa: E402
from mechrepro.config import load_paper  # noqa: E402
from mechrepro.models.disk_tension import exact  # noqa: E402
from mechrepro.solve import compute  # noqa: E402
from mechrepro.models.disk_tension.axisym import AxisymDisk  # noqa: E402
from mechrepro.levels import extrapolate  # noqa: E402

import _floor  # noqa: E402

CFG = load_paper(ROOT / "config/papers/disk_tension.yaml")
RC = CFG.runs["rc_grid"]["parameters"]["rolling_radius"]
RF = [0.025, 0.055, 0.075]
ND = list(range(5))


def setup():
    """Thickness and calibrated alpha from the solver itself (not part of the timing)."""
    ctx = compute(dict(CFG.runs["table12"], effects=["stress_calibration"]))
    return ctx


def grid(ctx, n_elements, min_time=0.2):
    """(f_eig[r_f, r_c, n], f_eq9[...], t_total, t_eigen, t_eq9) for the whole grid; each
    time is the fastest of repeated runs of that phase over the whole grid."""
    disks, Ks = [], []
    for r_f in RF:
        ctx.r_f = r_f
        disk = AxisymDisk(r_f=r_f, b=ctx.b, h=ctx.h, E=ctx.E, nu=ctx.nu, rho=ctx.rho, n_d=ND,
                          n_elements=n_elements)
        disk.unrolled()
        disks.append(disk)
        Ks.append([disk.stress_stiffness(thermal_load(ctx, r_c).sigma) for r_c in RC])

    def setup_all():
        for i, r_f in enumerate(RF):
            ctx.r_f = r_f
            d = AxisymDisk(r_f=r_f, b=ctx.b, h=ctx.h, E=ctx.E, nu=ctx.nu, rho=ctx.rho, n_d=ND,
                           n_elements=n_elements)
            d.unrolled()
            [d.stress_stiffness(thermal_load(ctx, r_c).sigma) for r_c in RC]

    def eig_all():
        return np.array([[d.rolled(k)[0] for k in ks] for d, ks in zip(disks, Ks)])

    def eq9_all():
        return np.array([[d.eq9(k) for k in ks] for d, ks in zip(disks, Ks)])

    _, t_setup = time_call(setup_all, min_time=min_time)
    w2, t_eig = time_call(eig_all, min_time=min_time)
    d9, t_eq9 = time_call(eq9_all, min_time=min_time)
    w0 = np.array([d.unrolled() for d in disks])[:, None, :]
    return (np.sqrt(w2) / (2 * np.pi), np.sqrt(w0 + d9) / (2 * np.pi), t_setup + t_eig + t_eq9,
            t_eig, t_eq9)


def exact_f(ctx):
    return np.array([exact.natural_frequencies(n, a=0.025, b=ctx.b, h=ctx.h, E=ctx.E, nu=ctx.nu,
                                               rho=ctx.rho)[0] for n in ND])


def plate2d_at_0_1_percent(ctx, meshes=((3, 24), (4, 32), (6, 48), (6, 64), (8, 64), (12, 64))):
    """First mesh whose unrolled N_d = 0..4 are all within 0.1 % of exact."""
    from mechrepro.models.disk_tension.plate2d import PlateDisk

    fe = exact_f(ctx)
    for nr, ns in meshes:
        with phase("benchmark:1") as sw:
            p = PlateDisk(r_f=0.025, b=ctx.b, h=ctx.h, E=ctx.E, nu=ctx.nu, rho=ctx.rho, n_d=ND,
                          n_rings=nr, n_sectors=ns)
            p.unrolled()
        dt = sw.seconds
        err = np.abs(np.sqrt([p.omega2[n].mean() for n in ND]) / (2 * np.pi) / fe - 1)
        print(f"  plate2d {nr:2d} x {ns:3d} ({p.basis.N:5d} DOFs): N_d=4 error {err[4]:.2e}, "
              f"max over N_d {err.max():.2e}, {dt:.2f} s")
        if err.max() < 1e-3:
            return nr, ns, err.max(), dt
    return None


def axisym_at(ctx, tol):
    fe = exact_f(ctx)
    for n in (1, 2, 3, 4, 6, 8, 12, 16):
        with phase("benchmark:2") as sw:
            d = AxisymDisk(r_f=0.025, b=ctx.b, h=ctx.h, E=ctx.E, nu=ctx.nu, rho=ctx.rho, n_d=ND,
                           n_elements=n)
            d.unrolled()
        dt = sw.seconds
        err = np.abs(np.sqrt([d.omega2[k] for k in ND]) / (2 * np.pi) / fe - 1).max()
        if err < tol:
            return n, err, dt


def test_bench_disk_tension():
    ctx = setup()
    # converged reference: Richardson (h^4) of 64 and 128 elements, ~5e-9 on the exact
    # unrolled frequencies (256 elements alone: round-off ~5e-8)
    ref = extrapolate(grid(ctx, 64, 0.0)[0], grid(ctx, 128, 0.0)[0], 2.0, 4.0)  # h^4, n and 2n
    print(f"\ndisk_tension: full Fig. 6 + Fig. 8 grid (9 r_c x 3 r_f x N_d 0..4), axisym, "
          f"OPENBLAS_NUM_THREADS={os.environ.get('OPENBLAS_NUM_THREADS')}, fastest of repeats")
    chosen = None
    for n in (8, 16, 24, 32, 48, 64):
        f_eig, f_eq9, t, t_eig, t_eq9 = grid(ctx, n)
        err = np.max(np.abs(f_eig / ref - 1))
        print(f"  {n:3d} elements: max rel error vs Richardson(64, 128) {err:.1e}, grid {t:.3f} s "
              f"(eigen {t_eig:.3f} s, Eq. 9 {t_eq9:.4f} s)")
        if chosen is None and err < 1e-4:
            chosen = (n, err, t, t_eig, t_eq9, f_eig, f_eq9)
    n, err, t, t_eig, t_eq9, f_eig, f_eq9 = chosen
    e9 = np.nanmax(np.abs(f_eq9 / f_eig - 1))
    print(f"  -> {n} elements reach {err:.1e} < 1e-4: whole grid {t:.3f} s (target <= 3 s)")
    print(f"  Eq. (9) vs eigen-analysis on the same K_sigma: {t_eq9 * 1e3:.2f} ms vs "
          f"{t_eig * 1e3:.1f} ms, ratio {t_eig / t_eq9:.0f}x; Eq. (9) max frequency error {e9:.3f}")
    print("disk_tension: 2-D Argyris model until N_d = 0..4 are within 0.1 % of exact (N_d = 4 "
          "is the target's)")
    hit = plate2d_at_0_1_percent(ctx)
    ax = axisym_at(ctx, 1e-3)
    if hit:
        nr, ns, e2, t2 = hit
        print(f"  -> plate2d {nr} x {ns}: max error {e2:.1e} in {t2:.2f} s (target <= 60 s); axisym at the "
              f"same accuracy: {ax[0]} elements, error {ax[1]:.1e} in {ax[2] * 1e3:.1f} ms "
              f"-> axisym {t2 / ax[2]:.0f}x faster")


# --- solver jobs side by side: a git revision's src against this worktree's --------------
_JOB_CODE = r"""
import json, time
from mechrepro.config import load_paper
from mechrepro.solve import run_solver
cfg = load_paper({cfg!r}, {profile!r})
t0, c0 = time.perf_counter(), time.process_time()
solve = 0.0
for name in {names!r}:
    solve += run_solver(cfg.runs[name]).attrs["wall_time_s"]
print(json.dumps({{"process": time.perf_counter() - t0, "cpu": time.process_time() - c0,
                  "solve": solve}}))
"""


def _job_runs(profile):
    cfg = load_paper(ROOT / "config/papers/disk_tension.yaml", profile)
    alone = [n for n in cfg.runs if n.split("@")[0] == "table12_plate2d"]
    return {"batch": [n for n in cfg.runs if n not in alone], "table12_plate2d": alone}


def versus(rev, profile="ci", repeats=3):
    """Each solver job of ``profile`` (the batch of cheap runs, and the 2-D Table 1-2 scene
    with its variant) solved by the src of git revision ``rev`` and by this worktree's,
    in fresh processes, alternating, fastest of ``repeats``: wall and process CPU time of
    the runs (imports excluded; on a shared machine the CPU time is the comparable one) and
    the sum of their recorded solve times."""
    import json
    import tempfile

    tmp = Path(tempfile.mkdtemp(prefix="bench_disk_tension_"))
    archive = subprocess.run(["git", "-C", str(ROOT), "archive", rev, "src"], check=True,
                             capture_output=True).stdout
    subprocess.run(["tar", "-x", "-C", str(tmp)], input=archive, check=True)
    srcs = {rev: str(tmp / "src"), "worktree": str(ROOT / "src")}
    print(f"disk_tension solver jobs ({profile}), {rev} vs worktree, fastest of {repeats}, "
          f"OPENBLAS_NUM_THREADS={os.environ.get('OPENBLAS_NUM_THREADS')}")
    for job, names in _job_runs(profile).items():
        best = {k: {"process": float("inf"), "cpu": float("inf"), "solve": float("inf")}
                for k in srcs}
        for _ in range(repeats):
            for key, src in srcs.items():
                code = _JOB_CODE.format(src=src, cfg=str(ROOT / "config/papers/disk_tension.yaml"),
                                        profile=profile, names=names)
                out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True,
                                     text=True, env=dict(os.environ, PYTHONPATH=src)).stdout
                got = json.loads(out.strip().splitlines()[-1])
                for k in got:
                    best[key][k] = min(best[key][k], got[k])
        a, b = best[rev], best["worktree"]
        print(f"  {job:16s} ({len(names):2d} runs): runs {a['process']:6.2f} -> {b['process']:6.2f} s "
              f"(x{a['process'] / b['process']:.2f}); CPU {a['cpu']:6.2f} -> {b['cpu']:6.2f} s "
              f"(x{a['cpu'] / b['cpu']:.2f}); recorded solve times {a['solve']:6.2f} -> "
              f"{b['solve']:6.2f} s (x{a['solve'] / b['solve']:.2f})")


# --- the solve floor from operation counts (issue 35) --------------------------------------
#: flops of one axisymmetric element matrix (4 x 4 Hermite, 6 Gauss points, ~8 flops per
#: entry and point): [K] per N_d, [M] once, [K^(sigma)] per stress state and N_d
AXI_ELEMENT = 6 * 16 * 8


def axi_eigen_flops(n: int) -> float:
    """Flops of one fundamental of a pencil of n unknowns as :func:`.modal.eigen` solves it:
    in the banded range (64 <= n <= 128) inverse iteration, the banded Cholesky factor
    n (u + 1)^2 and ~17 steps of a triangular solve pair 4 n (u + 1), a banded product with
    M 2 n (2 u + 1) and 6 n of scaling (u = 3: ~630 n); otherwise LAPACK's subset driver
    sygvx, Cholesky n^3 / 3 + reduction to standard form n^3 + tridiagonalisation 4/3 n^3
    (8/3 n^3), plus the dense Rayleigh quotient 4 n^2."""
    u = 3
    if 64 <= n <= 128:
        return n * (u + 1) ** 2 + 17 * (4 * n * (u + 1) + 2 * n * (2 * u + 1) + 6 * n)
    return 8 / 3 * n ** 3 + 4 * n ** 2


def _count(p, key):
    return len(np.atleast_1d(p[key])) if key in p else 0


def axisym_flops(run: dict) -> float:
    """An axisym run: every (stress state, N_d) its effects solve, each an element assembly
    of [K^(sigma)] (n_e AXI_ELEMENT) and :func:`axi_eigen_flops` of n = 2 n_e unknowns:
    the unrolled disk; eigen, critical_load: each r_c; stressed_reference: each
    reference_stress; stiffness_sensitivity: two solves per annulus radius (with their
    meshes' [K], [M]); rolled_reference: the 64- and 128-element models, unrolled and at
    each r_c (solved once per process for the same parameters: counted once, see
    :func:`floor`); critical_speed: untensioned and each r_c, a full dense eigh of
    (n^2 M - K^c, K), 8/3 n^3; identifiability: 2 in-plane conditions x the scan's widths
    x stress scales, one N_d each (and a [K^(sigma)] per condition and width)."""
    p, eff, ne = run["parameters"], run["effects"], int(run["resolution"]["n_elements"])
    nd, rc = _count(p, "nodal_diameters"), _count(p, "rolling_radius")
    n = 2 * ne
    one = ne * AXI_ELEMENT + axi_eigen_flops(n)
    states = 1 + rc * (("eigen" in eff) + ("critical_load" in eff))
    states += _count(p, "reference_stress") * ("stressed_reference" in eff)
    flops = ne * AXI_ELEMENT * (1 + nd) + states * nd * one
    if "stiffness_sensitivity" in eff:
        flops += _count(p, "annulus_radii") * nd * 2 * (2 * ne * AXI_ELEMENT + axi_eigen_flops(n))
    if "critical_speed" in eff:
        flops += (1 + rc) * nd * (8 / 3 * n ** 3 + ne * AXI_ELEMENT)
    if "identifiability" in eff:
        (w0, w1, dw), (c0, c1, dc) = p["scan_gaussian_width"], p["scan_stress_scale"]
        widths = np.arange(w0, w1 + dw / 2, dw).size
        scales = np.arange(c0, c1 + dc / 2, dc).size
        flops += 2 * widths * (nd * ne * AXI_ELEMENT + scales * axi_eigen_flops(n))
    return flops


def rolled_reference_flops(run: dict) -> float:
    """The 64- and 128-element reference of effect rolled_reference (:func:`axisym_flops`)."""
    p = run["parameters"]
    nd, rc = _count(p, "nodal_diameters"), _count(p, "rolling_radius")
    return sum((1 + rc) * nd * (ne * AXI_ELEMENT + axi_eigen_flops(2 * ne)) + ne * AXI_ELEMENT
               for ne in (64, 128))


#: per triangle of the 2-D mesh: the Argyris basis at the 16 points of quadrature order 8
#: (21 functions, value and derivatives to second order, ~30 flops each through the affine
#: map) and one bilinear form, 21^2 entries x 16 points x ~6 flops
PLATE_BASIS, PLATE_FORM = 21 * 16 * 6 * 30, 21 * 21 * 16 * 6


def plate2d_flops(run: dict) -> float:
    """A plate2d run on the polar mesh of n_r rings x n_s sectors (2 n_r n_s triangles):
    N ~ 6 (n_r + 1) n_s + (3 n_r + 1) n_s Argyris unknowns (6 per vertex, 1 per edge);
    ordered sector by sector, the matrix has a half-bandwidth b ~ 2 x the unknowns of a
    radial line, 2 (6 (n_r + 1) + 3 n_r); per eigen-analysis (the unrolled disk, each r_c of
    eigen and critical_load, each reference_stress) the shift-inverted LU 2 N b^2 and the
    Lanczos iterations of ARPACK (~3 ncv operator applications, ncv = max(2k + 1, 20) for
    the k = 2 max N_d + 5 modes), each a triangular solve pair 4 N b, a product with M
    (~150 N) and the orthogonalisation 4 N ncv; assembly of [K], [M] and each [K^(sigma)]
    per triangle (PLATE_BASIS + PLATE_FORM each).  The in-plane residual-stress problem
    and the modal labelling are not counted."""
    p, eff, res = run["parameters"], run["effects"], run["resolution"]
    nr, ns = int(res["n_rings"]), int(res["n_sectors"])
    tri, N = 2 * nr * ns, 6 * (nr + 1) * ns + (3 * nr + 1) * ns
    b = 2 * (6 * (nr + 1) + 3 * nr)
    k = 2 * int(np.max(p["nodal_diameters"])) + 5
    ncv = max(2 * k + 1, 20)
    rc = _count(p, "rolling_radius")
    states = 1 + rc * (("eigen" in eff) + ("critical_load" in eff))
    states += _count(p, "reference_stress") * ("stressed_reference" in eff)
    eig = 2 * N * b * b + 3 * ncv * (4 * N * b + 150 * N + 4 * N * ncv)
    return tri * (PLATE_BASIS + PLATE_FORM * (2 + states - 1)) + states * eig


def floor(profile="default", measure=False):
    """disk_tension's solve floor from operation counts: every run sized from its run
    record (n_elements, or n_rings x n_sectors; N_d, r_c and the effects' own lists), its
    eigen-analyses and assemblies counted as :func:`axisym_flops` and
    :func:`plate2d_flops` say, at :data:`_floor.RATE`.  Not counted: the exact Bessel
    references (root finding, a few ms, cached), the thermal stress fields, the
    calibration of alpha (one eigen-analysis, cached per process), Eq. (9) and the
    bookkeeping; a rolled_reference is counted once per set of parameters, as the process
    solves it once (the measured runs share it in config order, as a job does)."""
    from mechrepro import limits

    cfg = load_paper(ROOT / "config/papers/disk_tension.yaml", profile)
    rows, seen = [], set()
    for name, run in cfg.runs.items():
        flops = axisym_flops(run) if run["solver"] == "axisym" else plate2d_flops(run)
        key = str(sorted(run["parameters"].items()))
        if "rolled_reference" in run["effects"] and key not in seen:
            seen.add(key)
            flops += rolled_reference_flops(run)
        rows.append((name, run["solver"], flops, limits.run_cost("disk_tension", run)["seconds"]))
    _floor.report("disk_tension", profile, rows, "limits.run_cost, per run",
                  cfg.runs if measure else None)


if __name__ == "__main__":
    if "--floor" in sys.argv:
        prof = sys.argv[sys.argv.index("--profile") + 1] if "--profile" in sys.argv else "default"
        floor(prof, "--measure" in sys.argv)
        sys.exit(0)
    if "--versus" in sys.argv:
        i = sys.argv.index("--versus")
        rev = sys.argv[i + 1]
        prof = sys.argv[i + 2] if len(sys.argv) > i + 2 and not sys.argv[i + 2].startswith("-") else "ci"
        versus(rev, prof)
        sys.exit(0)
    test_bench_disk_tension()
    floor()
