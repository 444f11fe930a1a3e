"""chain_drive: periodic steady state and Floquet stability from one excitation period
(shooting.py) against the time march of the same scheme (fd.march)."""
import numpy as np
import pytest
from threadpoolctl import threadpool_limits

from mechrepro.config import load_paper
from mechrepro.models.chain_drive import fd, four_bar, shooting, solver, span
from mechrepro.models.chain_drive.geometry import RPM
from test_chain_drive_contract import declared


@pytest.fixture(scope="module")
def fig09a():
    run = load_paper("config/papers/chain_drive.yaml").runs["fig09a"]
    return run, dict(run["parameters"]), dict(run["resolution"])


def _tile(x, K):
    """K periods of a one-period input (levels 0..N, level N = level 0), plus level 1."""
    if x is None:
        return None
    return np.concatenate([np.tile(x[:-1], (K, 1)), x[:2]], axis=0)


def _march_periods(run, prm, res, w, K, n_blocks):
    """March K excitation periods from rest with the shooting's own step and inputs."""
    s = shooting.periodic_solution(run, prm, w, res)
    a = span.assemble(run, prm, [w], res, period=s.period)
    e = a["exc"]
    exc = fd.Excitation(**{k: _tile(getattr(e, k), K)
                           for k in ("tension", "u_left", "u_right", "long", "load")})
    r = fd.march(c=a["c"], P=a["P"], m=a["m"], c_d=a["c_d"], grid=a["grid"], dt=a["dt"],
                 n_steps=K * a["n_steps"] + 1, exc=exc, s_star=a["s_star"], measure_from=0,
                 n_blocks=n_blocks, u_cap=np.inf, differencing=res.get("differencing"))
    return s, r


def test_shooting_and_march_agree_on_the_steady_amplitude(fig09a):
    run, prm, res = fig09a
    # 1000 rpm: stable, decay rate ~10 1/s; 120 periods (~0.3 s... 3 decay times x ~4)
    s, r = _march_periods(run, prm, res, 1000 / RPM, 400, 20)
    assert s.rho < 1 and s.residual < 1e-9 * s.amplitude
    assert r.block_max[-1, 0] == pytest.approx(s.amplitude, rel=1e-4)


@pytest.mark.parametrize("rpm", [1211.3, 1211.7])
def test_floquet_multiplier_is_the_measured_growth_per_period(fig09a, rpm):
    run, prm, res = fig09a
    K, nb = 300, 6
    s, r = _march_periods(run, prm, res, rpm / RPM, K, nb)
    per = (r.block_max[-1, 0] / r.block_max[-2, 0]) ** (nb / K)
    assert s.rho > 1
    assert per == pytest.approx(s.rho, rel=2e-3)


def test_fig09a_band_below_the_elastic_resonance_and_map_unchanged_by_a_finer_grid(fig09a):
    """The principal parametric band just below omega_c2 (issue 25/26: 1210.9-1211.8 rpm by
    the march) is found from the scene's initial grid, with the same edges (within the
    bisection width) from a grid twice as fine."""
    run, prm, res = fig09a
    window = run["options"]["speed_window_elastic"]
    prm["speed_min"], prm["speed_max"] = four_bar.elastic_speed_window(prm, window)
    sigma = prm["transverse_damping"] / (2 * prm["mass_per_length"])
    bands = []
    with threadpool_limits(1):
        n0 = int(res["n_speeds"])
        for n in (n0, 2 * n0):
            om = solver.dense_near_elastic(run, prm, span.speed_axis(prm, n), 0.01, n)
            w, sols, done = shooting.adaptive_sweep(
                each(lambda v: shooting.periodic_solution(run, prm, v, res)), om,
                edge_tol=0.05 / RPM, peak_tol=0.2 / RPM, rate_floor=-0.5 * sigma)
            un = np.array([x.rho > 1 or x.slack for x in sols]).astype(int)
            edges = np.flatnonzero(np.diff(un))
            bands.append([0.5 * (w[i] + w[i + 1]) * RPM for i in edges])
    assert len(bands[0]) == 2 and 1205 < bands[0][0] < 1211 < bands[0][1] < 1215
    assert np.allclose(bands[0], bands[1], atol=0.1)


def test_an_external_load_sets_the_period():
    prm = {"n1": 24, "external_load_ratio": 0.2, "external_frequency_ratio": 4.0}
    T, q = shooting.excitation_period(prm, declared(["external_load"]), 10.0)
    assert q == 6 and T == pytest.approx(6 * 2 * np.pi / (24 * 10.0))


def test_rho_bounds_bracket_the_spectral_radius():
    """The cheap bounds (matrix squarings) bracket the eigenvalues' spectral radius, on
    random non-normal matrices and scaled to be stable, marginal or unstable."""
    rng = np.random.default_rng(0)
    for n in (6, 40, 120):
        A = rng.standard_normal((n, n)) + 3 * np.triu(rng.standard_normal((n, n)), 1)
        rho = np.max(np.abs(np.linalg.eigvals(A)))
        for target in (0.5, 0.97, 1.0, 1.03, 3.0):
            M = A * (target / rho)
            lo, hi = shooting.rho_bounds(M, below=0.9, max_squarings=14)
            assert lo <= target * (1 + 1e-9) and hi >= target * (1 - 1e-9)


def test_bounds_undecided_only_where_the_squarings_prove_nothing():
    """Where bounds_undecided says so (from the eigenvalues), rho_bounds proves neither
    rho < below nor rho > 1: skipping its squarings changes no result."""
    rng = np.random.default_rng(1)
    undecided = 0
    for n in (6, 40, 120):
        A = rng.standard_normal((n, n)) + 3 * np.triu(rng.standard_normal((n, n)), 1)
        rho = np.max(np.abs(np.linalg.eigvals(A)))
        for target in (0.5, 0.93, 0.97, 0.999, 1.0, 1.001, 1.03, 3.0):
            M = A * (target / rho)
            moduli = np.abs(np.linalg.eigvals(M))
            for k in (3, 8, 11):
                if shooting.bounds_undecided(moduli, 0.9, k):
                    undecided += 1
                    lo, hi = shooting.rho_bounds(M, below=0.9, max_squarings=k)
                    assert not (hi < 0.9 or lo > 1.0 + 1e-9), (n, target, k, lo, hi)
    assert undecided >= 10


def test_work_order_leaves_the_solution_unchanged(fig09a):
    """likely_undecided (eigenvalues before bounds) only reorders periodic_solution's
    work: every field is bit-identical, at stable, marginal and growing speeds."""
    run, prm, res = fig09a
    sigma = prm["transverse_damping"] / (2 * prm["mass_per_length"])
    for rpm in (1100.0, 1211.3, 1211.5, 1250.0):
        a, b = (shooting.periodic_solution(run, prm, rpm / RPM, res, rate_floor=-0.5 * sigma,
                                           likely_undecided=first) for first in (False, True))
        for f in ("amplitude", "rho", "growth_rate", "residual", "rho_lower", "rho_upper",
                  "mode_wavelength", "n_steps", "slack"):
            assert np.array_equal(getattr(a, f), getattr(b, f), equal_nan=True), (rpm, f)
        assert np.array_equal(a.multipliers, b.multipliers)


def test_bounded_speeds_keep_the_exact_verdicts(fig09a):
    """Where rho_bounds proves a speed stable (rho < exp(-sigma T / 2)) or growing (rho > 1)
    the eigenvalues are skipped; the verdict, bump bracket and amplitude are those of the
    exact multipliers at every speed of a window across the 1211 rpm band."""
    run, prm, res = fig09a
    sigma = prm["transverse_damping"] / (2 * prm["mass_per_length"])
    skipped = 0
    for rpm in np.linspace(1100, 1300, 21):
        ex = shooting.periodic_solution(run, prm, rpm / RPM, res)
        b = shooting.periodic_solution(run, prm, rpm / RPM, res, rate_floor=-0.5 * sigma)
        assert b.amplitude == ex.amplitude
        assert b.rho_lower <= ex.rho * (1 + 1e-9) and b.rho_upper >= ex.rho * (1 - 1e-9)
        if np.isnan(b.rho):
            skipped += 1
            assert (b.rho_lower > 1) == (ex.rho > 1)
            assert b.rho_lower > 1 or b.rho_upper < np.exp(-0.5 * sigma * ex.period)
    assert skipped >= 10


def each(evaluate):
    """adaptive_sweep's evaluator (a list of speeds at a time) of a one-speed ``evaluate``."""
    return lambda ws: [evaluate(w) for w in ws]


def _synthetic(peak_at: float):
    """A stable sweep with one resonance peak (amplitude 1 / (1 + (w - peak)^2)), no edges
    and no growth-rate bumps: only the amplitude-peak refinement adds speeds."""
    def evaluate(w):
        return shooting.PeriodicSolution(
            amplitude=1.0 / (1.0 + (w - peak_at) ** 2), rho=0.5, growth_rate=np.log(0.5),
            period=1.0, n_steps=10, residual=0.0, slack=False, multipliers=np.zeros(0),
            rho_lower=0.5, rho_upper=0.5)
    return evaluate


def test_stability_only_variants_refine_only_the_growth_rate_bumps():
    """(iii) of adaptive_sweep bisects amplitude peaks; a stability-only run
    (options.variants = stability, a rival or range-end variant: ``prominence=None``,
    ``until_unstable``) leaves a stable sweep without growth-rate bumps at its initial
    speeds, and stops at the first unstable speed."""
    kw = dict(peak_tol=0.01, rate_floor=-0.1)   # log 0.5 is below: no growth-rate bumps
    grid = np.linspace(0.0, 10.0, 11)
    w, sols, done = shooting.adaptive_sweep(each(_synthetic(4.3)), grid, edge_tol=0.01, **kw)
    assert done and w.size > grid.size and np.min(np.abs(w - 4.3)) < 0.01
    w0, sols0, done0 = shooting.adaptive_sweep(each(_synthetic(4.3)), grid, edge_tol=0.01,
                                               prominence=None, until_unstable=True, **kw)
    assert done0 and np.array_equal(w0, grid)

    def tongue(w):      # unstable on (4.2, 4.6): edges at 4 | 5 are not bisected
        s = _synthetic(4.3)(w)
        s.rho = s.rho_lower = s.rho_upper = 2.0 if 4.2 < w < 4.6 else 0.5
        return s
    w1, _, done1 = shooting.adaptive_sweep(each(tongue), np.r_[grid, 4.4], edge_tol=0.01,
                                           prominence=None, until_unstable=True, **kw)
    assert done1 and w1.size == grid.size + 1
    base = {"options": {"variants": "stability"}}
    assert [shooting.stability_only({**base, "variant": v})
            for v in (None, "coarser", "coarsest", "rival-slack_tension",
                      "transverse_damping-lo")] == [False, False, False, True, True]
    assert not shooting.stability_only({"variant": "rival-slack_tension"})


def test_declared_cost_is_above_a_measured_run_and_refuses_a_huge_one():
    """chain_drive's cost model (models/chain_drive/limits.py) against one march measured
    in a fresh process (ci fig05_plain: 376 speeds x 61 points x ~2000 steps), and a
    resolution within the schema that no 2000 MB job holds, refused before any job."""
    from conftest import ROOT
    from test_inputs import _measured

    from mechrepro import limits

    cfg = load_paper(ROOT / "config" / "papers" / "chain_drive.yaml", "ci")
    run = dict(cfg.runs["fig05_plain"])
    peak, seconds = _measured("chain_drive", run, ROOT)
    est = limits.run_cost("chain_drive", run)
    assert peak < est["mem_mb"] < 2 * peak, (peak, est)
    # wall time of a fresh process (imports, kernel load) on a machine that may be loaded
    # (the test suite runs two workers beside other jobs: 18 s measured for ~4 s idle):
    # only the order of magnitude is checked here
    start = limits.coefficients()["chain_drive", "(job)"]["start"]
    assert seconds < 10 * (est["seconds"] + start), (seconds, est)
    huge = dict(run, resolution=dict(run["resolution"], n_speeds=5000, points_per_pitch=12))
    assert limits.run_cost("chain_drive", huge)["mem_mb"] > limits.SOLVE_MEM_MB


def test_critical_wavelength_reads_the_growing_modes_sine_harmonic():
    """A monodromy matrix whose dominant mode is sin(3 pi x / L) on the u^N nodes (the
    interior ones live, the u^{N+1} half too): its wavelength is 2 L / 3."""
    grid = fd.Grid(0.5, 20, 20)
    n1 = grid.n_long + 1
    live = np.r_[np.arange(1, n1 - 1), np.arange(n1 + 1, 2 * n1 - 1)]
    x = np.arange(n1) / grid.n_long
    v = np.r_[np.sin(3 * np.pi * x[1:-1]), 0.5 * np.sin(3 * np.pi * x[1:-1])]
    M = 1.2 * np.outer(v, v) / (v @ v) + 0.1 * np.eye(live.size)
    assert shooting.critical_wavelength(M, live, grid) == pytest.approx(2 * 0.5 / 3)


def test_fig09_classes_split_growth_outside_the_string_model_from_growth():
    """Every speed of a sweep is in one class of Fig. 9; a flagged growing speed leaves the
    growth class (and a march's dataset, with no flag, keeps today's growth)."""
    import xarray as xr

    from mechrepro.models.chain_drive import figures as F

    ds = xr.Dataset({"unstable": ("speed", np.array([0, 1, 1, 1, 0], "i1")),
                     "slack": ("speed", np.array([0, 0, 0, 1, 0], "i1")),
                     "outside_validity": ("speed", np.array([0, 0, 1, 0, 0], "i1"))},
                    coords={"speed": np.arange(5.0)})
    k = F.stability_classes(ds)
    assert sum(m.astype(int) for m in k.values()).tolist() == [1] * 5
    assert k["growth"].tolist() == [False, True, False, False, False]
    assert k["outside"].tolist() == [False, False, True, False, False]
    k = F.stability_classes(ds.drop_vars("outside_validity"))
    assert k["growth"].tolist() == [False, True, True, False, False] and not k["outside"].any()
