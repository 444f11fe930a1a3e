"""Periodic steady state and Floquet stability of the linear span from ONE excitation period.

The span of Eqs. (2-36)/(2-37) is linear in u and its excitation (tension P_t, end motion,
span-length state, sag load) is periodic in the tooth period tau = 2 pi/(n1 omega1) (times
the period of an external load when there is one, :func:`excitation_period`).  The FD
march of :func:`.fd.march` is then an affine map of its state x = (u^{j-1}, u^j) over one
period N dt = T:

    x_N = M x_0 + b.

``M`` (the monodromy matrix of the discrete scheme) and ``b`` are built by marching the
*same* scheme (:func:`.span.assemble` for the excitation, :func:`.fd.march` for the step:
the physics is written once) over one period, for the zero state and for every unit state,
all as lanes of one vectorised march.  Then

- the periodic steady state is one linear solve (I - M) x* = b (shooting), and its
  amplitude is the maximum |u| over one more period marched from x* (which must come back
  to x*: the residual is returned);
- the span is unstable (Mathieu/parametric) iff the spectral radius rho(M) > 1 (Floquet),
  with growth rate log(rho)/T.

No settling time and no growth window enter: a slow growth is a multiplier just above 1,
found the same way as a fast one.  :func:`adaptive_sweep` samples the speed axis
adaptively: it bisects around every change of the stability verdict, every local maximum
of the Floquet growth rate (a tongue narrower than the grid shows there first as a bump of
rho) and every amplitude peak, until the intervals are below the requested widths.
"""
from __future__ import annotations

import bisect
import math
from dataclasses import dataclass

import numpy as np

from . import fd, fd_kernel, geometry, span
from .effects import EFFECTS
from .errors import KernelUnavailable, PeriodicityError  # noqa: F401 (re-exported)
from .limits import stability_only  # noqa: F401 (re-exported)


def excitation_period(prm: dict, run: dict, omega1: float) -> tuple[float, int]:
    """(T, q): the excitation period T = q tau.  Every effect repeats each tooth period
    tau, except one that declares ``tension_external``, an external load cos(r omega1 t)
    (Eq. 2-5), whose period 2 pi/(r omega1) is n1/r tooth periods: q is the smallest whole
    number of tooth periods holding a whole number of load periods (r must be rational with
    a small denominator)."""
    q = span.excitation_tooth_periods(prm, run)
    return q * float(geometry.tooth_period(omega1, int(prm["n1"]))), q


@dataclass
class PeriodicSolution:
    amplitude: float          # max |u| over x and one period of the periodic steady state
    rho: float                # spectral radius of the monodromy matrix (Floquet multiplier);
                              # nan where only bounded (rho_lower/upper) or slack
    growth_rate: float        # log(rho) / T  [1/s] (nan with rho)
    period: float             # T [s]
    n_steps: int              # steps per period
    residual: float           # max |x(T) - x*| of the steady state marched once more [m]
    slack: bool               # P + P_t <= 0 somewhere: the string model is invalid
    multipliers: np.ndarray   # the nonzero-column eigenvalues of M (empty where not computed)
    rho_lower: float = math.nan   # certified bounds of rho (= rho where computed); where
    rho_upper: float = math.nan   # rho is nan they prove stability or growth (rho_bounds)
    mode_wavelength: float = math.nan   # of the critical Floquet mode where it grows [m]


def rho_bounds(M: np.ndarray, below: float, max_squarings: int) -> tuple[float, float]:
    """Certified (lower, upper) bounds of the spectral radius of M, cheaper than its
    eigenvalues.  For every K, with A = M^K (dimension n):

        |tr A| / n  <=  rho(M)^K = rho(A)  <=  ||A||_2 <= ||A||_F

    (the trace is the sum of the K-th powers of the multipliers; Gelfand for the norm).
    K = 2^s is reached by s matrix squarings (BLAS-3: one squaring of the 170 x 170
    monodromy matrix costs ~1/4 of its eigenvalues' CPU time, measured).  The loop stops as soon
    as the upper bound is below ``below`` (proven stable with margin) or the lower bound
    above 1 (proven unstable), when the upper bound stops decreasing (it has reached rho
    times the non-normal transient: neither will be proven) or after ``max_squarings``;
    the caller then computes the eigenvalues.  A is rescaled at every squaring (no
    overflow); round-off of the products is ~1e-13 relative, far below the margins the
    bounds are compared with."""
    A = np.array(M, float)
    n = A.shape[0]
    log_scale, K = 0.0, 1
    lo, hi = 0.0, math.inf
    for s in range(max_squarings + 1):
        nf = float(np.linalg.norm(A))
        if nf == 0.0:
            return 0.0, 0.0
        # round-off margins: 1e-10 of the norm (the products' error is ~n eps of it)
        up = math.exp((math.log(nf * (1 + 1e-10)) + log_scale) / K)
        tr = abs(float(np.trace(A))) - 1e-10 * nf * n
        if tr > 0.0:
            lo = max(lo, math.exp((math.log(tr / n) + log_scale) / K))
        if up >= hi:                 # stopped decreasing
            break
        hi = up
        if hi < below or lo > 1.0 + 1e-9 or s == max_squarings:
            break
        A /= nf
        log_scale = 2.0 * (log_scale + math.log(nf))
        A = A @ A
        K *= 2
    return lo, hi


def bounds_undecided(moduli: np.ndarray, below: float, max_squarings: int) -> bool:
    """Whether :func:`rho_bounds` (M, below, max_squarings) cannot prove either way, read
    from the moduli of M's eigenvalues: its upper bound is never below ``rho`` (Gelfand), so
    never below ``below`` where rho > below, and its lower bound at K = 2^s is at most

        (|tr M^K| / n)^(1/K)  <=  (sum_i |lambda_i|^K / n)^(1/K),

    so never above 1 where that is <= 1 for every K it may reach.  The moduli are inflated
    (and rho deflated) by 1e-6 against the eigenvalues' round-off, which is amplified by the
    condition of a non-normal M; the bounds' own round-off margins only lower their
    reach.  True means the squarings would be spent only to compute the eigenvalues next."""
    n = moduli.size
    if n == 0 or float(np.max(moduli)) * (1.0 - 1e-6) < below:
        return False
    lg = np.log(moduli[moduli > 0] * (1.0 + 1e-6))
    top = float(lg.max())
    for s in range(max_squarings + 1):
        K = float(2 ** s)
        if top + math.log(float(np.sum(np.exp((lg - top) * K))) / n) / K > 0.0:
            return False
    return True


def _wrapped(x):
    """The (time, 1) input of one speed over levels 0..N-1, wrapped periodically to levels
    N, N + 1 (= levels 0, 1: see :func:`periodic_solution`); one column, shared by every
    lane of a march (:func:`.fd.march`).  The wrap also settles the one sample a switch of
    the span-length state may fall on at t = T exactly (which side of the switch it reads
    is round-off)."""
    if x is None:
        return None
    x = np.asarray(x)[:-1, :1]
    return np.concatenate([x, x[:2]])


def _kernel():
    return "compiled" if fd_kernel.available() else "numpy"


def _march(a, exc, u0, u1, res, c, P, s_star, n_steps, record_every=0, probes=(),
           amplitude=True):
    # amplitude=False: no level is measured, so the march skips its max |u| pass over the
    # span (the monodromy lanes need their last two levels only: 5-8 % of their march)
    kw = dict(c=c, P=P, m=a["m"], c_d=a["c_d"], grid=a["grid"], dt=a["dt"], n_steps=n_steps,
              exc=exc, s_star=s_star, measure_from=0 if amplitude else n_steps + 1, n_blocks=1,
              u_cap=np.inf, u0=u0, u1=u1,
              differencing=res.get("differencing"), record_every=record_every, probes=probes)
    try:
        return fd.march(kernel=_kernel(), **kw)
    except KernelUnavailable:    # compiled loop unavailable here (e.g. not diagonally dominant)
        return fd.march(kernel="numpy", **kw)


def periodic_solution(run, prm: dict, omega1: float, res: dict,
                      registry=EFFECTS, rate_floor: float | None = None,
                      likely_undecided: bool = False) -> PeriodicSolution:
    """Monodromy matrix, Floquet multipliers and periodic steady state at one speed.  The
    inputs are sampled on levels 0..N-1 and wrapped (:func:`_wrapped`): the effects repeat
    every T by construction (:func:`excitation_period`); a sample that falls exactly on a
    pulse edge or a length switch at t = T reads either side by round-off, so the first
    and last sample are not compared.

    The multipliers (eigenvalues of M, the cost of a shooting speed) are computed only where
    they can matter: not at a slack speed (the string model is invalid there: it counts as
    unstable whatever rho is), and, given ``rate_floor`` (1/s, < 0), not where
    :func:`rho_bounds` proves rho < exp(rate_floor T) (stable, and too far below 1 to be a
    growth-rate bump that :func:`adaptive_sweep` bisects) or rho > 1 (unstable: a positive
    rate is never a bump); there ``rho`` is nan and ``rho_lower``/``rho_upper`` hold the
    proven bounds.  Without ``rate_floor`` they are always computed.

    ``likely_undecided`` (a neighbouring speed's bounds proved nothing) only orders the work,
    never its result: the multipliers first, and the bounds only where
    :func:`bounds_undecided` leaves them a chance (at the edges of the stability tongues
    the squarings prove nothing and cost ~1/4 of the eigenvalues)."""
    T, _ = excitation_period(prm, run, omega1)
    a = span.assemble(run, prm, [omega1], res, registry, period=T)
    N, n1 = a["n_steps"], a["grid"].n_long + 1
    e = a["exc"]
    # fd.march sets levels 0 and 1 and steps j = 1 .. n_steps - 1 (level j + 1 from the
    # inputs at j): one period maps (u^0, u^1) to (u^N, u^{N+1}), N + 1 levels marched
    exc = fd.Excitation(**{k: _wrapped(getattr(e, k))
                           for k in ("tension", "u_left", "u_right", "long", "load")})
    # the unit states the march keeps: it overwrites the end nodes, and the long span's
    # extra pitch where the span is short, at levels 0 and 1 (fd.set_ends), so those lanes
    # would march the zero state again and their columns of M are exactly 0; one lane
    # fewer in 2n + 1 saves a lane group of the compiled march where it crosses a multiple
    kept = np.full((2, n1), np.nan)
    length_change = exc.long is not None and a["grid"].n_short != a["grid"].n_long
    for k in (0, 1):
        fd.set_ends(kept[k:k + 1], np.zeros(1), np.zeros(1),
                    exc.long[k, :1] if length_change else None, a["grid"].n_short)
    kept = np.flatnonzero(np.isnan(kept.ravel()))
    L = kept.size + 1
    u01 = np.zeros((L, 2 * n1))
    u01[np.arange(1, L), kept] = 1.0
    u0, u1 = u01[:, :n1], u01[:, n1:]
    c, P, s = (np.repeat(a[k], L) for k in ("c", "P", "s_star"))
    r = _march(a, exc, u0, u1, res, c, P, s, N + 1, record_every=N, probes=np.arange(n1),
               amplitude=False)
    y = np.concatenate([r.probes[0], r.final], axis=1)      # (L, 2 n1): (u^N, u^{N+1})
    b = y[0]
    M = np.zeros((2 * n1, 2 * n1))
    M[:, kept] = (y[1:] - b).T                               # column k = image of unit state k
    # the overwritten states map to exactly 0 (their columns are zero), and the multipliers
    # are 0 and those of M without them (block triangular): a smaller problem
    live = np.flatnonzero(np.any(M != 0.0, axis=0))
    M_live = M[np.ix_(live, live)]
    slack = bool(np.any(a["P_min"] <= 0))
    mult = np.zeros(0, complex)
    rho = lo = hi = math.nan
    early = np.zeros(0, complex)      # multipliers computed before the bounds proved
    if not slack:
        below = math.nan
        if rate_floor is not None and rate_floor < 0:
            below = math.exp(rate_floor * T)
            # up to K T ~ 20/|rate_floor|: a non-normal transient up to e^10 may be outgrown
            k_max = max(1, math.ceil(math.log2(max(20.0 / (abs(rate_floor) * T), 2.0))))
            if likely_undecided:
                early = np.linalg.eigvals(M_live)
            if not (early.size and bounds_undecided(np.abs(early), below, k_max)):
                lo, hi = rho_bounds(M_live, below, k_max)
        if not (hi < below or lo > 1.0 + 1e-9):   # not proven either way (or not asked): exact
            mult = early if early.size else np.linalg.eigvals(M_live)
            rho = lo = hi = float(np.max(np.abs(mult)))
    # where the span grows, how long its growing mode is (the string model of a chain of
    # rigid links holds for waves of >= valid_wavelength pitches only, an assumed parameter)
    wavelength = (critical_wavelength(M_live, live, a["grid"], mult if mult.size else early)
                  if not slack and lo > 1.0 else math.nan)
    x = np.linalg.solve(np.eye(2 * n1) - M, b)
    r1 = _march(a, exc, x[None, :n1], x[None, n1:], res, a["c"], a["P"], a["s_star"], N + 1,
                record_every=N, probes=np.arange(n1))
    back = np.concatenate([r1.probes[0, 0], r1.final[0]])
    amp = max(float(r1.block_max.max()), float(np.max(np.abs(x))))
    return PeriodicSolution(amplitude=amp, rho=rho,
                            growth_rate=math.log(rho) / T if rho > 0 else math.nan,
                            period=T, n_steps=N,
                            residual=float(np.max(np.abs(back - x))),
                            slack=slack, multipliers=mult, rho_lower=lo, rho_upper=hi,
                            mode_wavelength=wavelength)


def critical_wavelength(M_live: np.ndarray, live: np.ndarray, grid,
                        mult: np.ndarray | None = None) -> float:
    """Wavelength [m] of the critical Floquet mode: the eigenvector of the largest |multiplier|
    of the monodromy matrix, its displacement u^N on the nodes projected on the grid's sine
    modes sin(k pi x / L); 2 L / k of the strongest k.  ``mult``: the multipliers when
    already computed (eigvals).

    The eigenvector by inverse iteration on that multiplier (one LU, three solves) instead
    of a second eigen-decomposition with vectors (np.linalg.eig: ~1.4x the CPU of eigvals,
    whose multipliers it would compute again, not bit-identically): only the strongest k is
    read, and on the 81 growing speeds of Fig. 7 at T_s = 400 N the two eigenvectors pick
    the same k, the runner-up at most 0.998 of it against a vector error ~1e-10 (measured)."""
    from scipy.linalg import lu_factor, lu_solve

    vals = np.linalg.eigvals(M_live) if mult is None or not mult.size else mult
    lam = vals[np.argmax(np.abs(vals))]
    n = M_live.shape[0]
    # shifted 1e-12 off the multiplier (a relative gap far above round-off, far below the
    # spectrum's spacing): the factorisation is never exactly singular
    lu = lu_factor(M_live - lam * (1.0 + 1e-12) * np.eye(n), check_finite=False)
    v = np.ones(n, complex)
    for _ in range(3):
        v = lu_solve(lu, v, check_finite=False)
        v /= np.linalg.norm(v)
    n = grid.n_long
    u = np.zeros(n + 1, complex)
    node = live < n + 1                      # u^N; the entries from n + 1 on are u^{N+1}
    u[live[node]] = v[node]
    k = np.arange(1, n)
    amp = np.abs(np.sin(np.pi * k[:, None] * np.arange(n + 1)[None, :] / n) @ u)
    return 2.0 * grid.L_long / float(k[np.argmax(amp)])


def _inside(x0: float, x1: float, r: float, floor: float) -> float:
    """The predicted point r, kept at least m = max((x1 - x0)/8, floor) from both ends of
    [x0, x1] (the midpoint when the interval is shorter than 2 m, or r is not finite): each
    refinement shrinks the interval by >= 1/8 or by ``floor``, so a poor prediction costs
    at most a few more points than bisection, and a good one lands next to the target."""
    m = max((x1 - x0) / 8.0, floor)
    if x1 - x0 <= 2.0 * m or not math.isfinite(r):
        return 0.5 * (x0 + x1)
    return min(max(r, x0 + m), x1 - m)


def adaptive_sweep(evaluate, speeds, *, edge_tol: float,
                   peak_tol: float, rate_floor: float, prominence: float | None = 0.02,
                   max_evals: int = 3000, until_unstable: bool = False):
    """Sample ``evaluate([omega, ...]) -> [PeriodicSolution, ...]`` (a batch at a time) from
    the initial ``speeds`` (rad/s, the scene's speed axis), then refine

    (i) every interval whose ends differ in stability, down to ``edge_tol``: at the zero
        of the growth rate interpolated between its ends when both multipliers are exact
        (regula falsi; bisection otherwise: with a bound standing in for a rate, Fig. 9b
        lost a narrow band the bisection's points had found), kept >= 1/8 of the interval
        (or edge_tol/2) from its ends (:func:`_inside`: the bracket always shrinks);
    (ii) both intervals beside every interior local maximum of the Floquet growth rate
         above ``rate_floor`` (1/s; e.g. half the damping-only rate -c_d/2m: a parametric
         tongue narrower than the grid shows first as a bump of the growth rate towards
         0), bisected down to ``peak_tol``;
    (iii) both intervals beside every amplitude peak of prominence >= ``prominence`` x the
         largest amplitude, bisected down to ``peak_tol`` (a one-mode vertex prediction
         was tried: it stops 1-6 % below the sampled peak of Fig. 9a, whose peaks are not
         one-mode shaped at 0.2 rpm, and merged a double peak of Fig. 7); not with
         ``prominence=None``;

    until nothing is left to refine (the verdicts and peaks no longer change at these
    widths), or, ``until_unstable`` (:func:`stability_only`), until one speed is unstable.
    Returns the sorted speeds, their solutions and whether the refinement finished within
    ``max_evals`` (False: the sampling is not converged, and the caller says so)."""
    from threadpoolctl import threadpool_limits

    # scipy.signal.find_peaks by the same algorithm, without importing scipy.signal and
    # scipy.stats (~0.6-1 s in every solve process that shoots)
    from .claims import find_peaks

    with threadpool_limits(1, user_api="blas"):     # many small (2n x 2n) eigenproblems
        pts = dict(zip(ws := [float(w) for w in np.asarray(speeds, float)], evaluate(ws)))
        done = False
        while len(pts) < max_evals:
            w = np.array(sorted(pts))
            sol = [pts[v] for v in w]
            un = np.array([s.rho_lower > 1.0 or s.slack for s in sol])   # exact rho, or proven
            if until_unstable and un.any():
                done = True
                break
            slack = np.array([s.slack for s in sol])
            # the growth rate, or a proven bound where rho was only bounded: the upper one
            # below rate_floor (never a bump, and a bump beside it is still seen as one),
            # the lower one above 0 (never a bump either, and above any bump beside it)
            g = np.array([math.log(s.rho_upper if s.rho_upper < 1 else s.rho_lower) / s.period
                          if s.rho_lower > 0 else math.nan for s in sol])
            exact = np.array([math.isfinite(s.rho) and s.rho > 0 for s in sol])
            A = np.array([s.amplitude for s in sol])
            new = set()
            for i in range(w.size - 1):
                # a stability edge (a slack speed is outside the string model: its edges
                # are drawn at the grid's width, not refined)
                if (un[i] != un[i + 1] and not (slack[i] or slack[i + 1])
                        and w[i + 1] - w[i] > edge_tol):
                    r = math.nan
                    if exact[i] and exact[i + 1] and g[i] != g[i + 1]:
                        r = w[i] - g[i] * (w[i + 1] - w[i]) / (g[i + 1] - g[i])
                    new.add(_inside(w[i], w[i + 1], r, 0.5 * edge_tol))
            bumps = [i for i in range(1, w.size - 1)
                     if rate_floor < g[i] <= 0 and g[i] >= g[i - 1] and g[i] >= g[i + 1]]
            peaks = []
            if prominence is not None:
                stable_A = np.where(un, 0.0, A)
                peaks = find_peaks(stable_A, prominence * max(stable_A.max(), 1e-300))
            for i in [*bumps, *peaks]:
                for j in (i - 1, i):
                    if w[j + 1] - w[j] > peak_tol:
                        new.add(0.5 * (w[j] + w[j + 1]))
            new -= set(pts)
            if not new:
                done = True
                break
            pts.update(zip(ws := sorted(new), evaluate(ws)))
    w = np.array(sorted(pts))
    return w, [pts[v] for v in w], done


def sweep(run, prm: dict, omega1, res: dict, registry=EFFECTS) -> dict:
    """Figs. 5-9 by shooting (a run repeating another is solved once by the framework:
    :meth:`mechrepro.config.PaperConfig.same_solve`): :func:`periodic_solution` at every speed of an
    :func:`adaptive_sweep` started from ``omega1``, with the outputs of :func:`.span.sweep`
    (``growth`` is the Floquet multiplier rho here, ``unstable`` = rho > 1 or slack).
    Resolution: ``edge_tol`` and ``peak_tol`` (rpm) the bisection widths."""
    sigma = prm["transverse_damping"] / (2 * prm["mass_per_length"])
    only = stability_only(run)
    seen_w: list = []        # the speeds solved so far (sorted) and their solutions
    seen: dict = {}

    def evaluate(v):
        # whether the nearest speed solved so far needed its multipliers (its bounds proved
        # nothing): only orders periodic_solution's work, never changes its result
        i = bisect.bisect(seen_w, v)
        near = min(seen_w[max(i - 1, 0):i + 1], key=lambda u: abs(u - v), default=None)
        sol = periodic_solution(run, prm, v, res, registry, rate_floor=-0.5 * sigma,
                                likely_undecided=near is not None
                                and math.isfinite(seen[near].rho))
        bisect.insort(seen_w, v)
        seen[v] = sol
        return sol

    w, sols, done = adaptive_sweep(lambda ws: [evaluate(v) for v in ws], omega1,
                             edge_tol=float(res["edge_tol"]) / geometry.RPM,
                             peak_tol=float(res["peak_tol"]) / geometry.RPM,
                             rate_floor=-0.5 * sigma, prominence=None if only else 0.02,
                             until_unstable=only)
    a = span.assemble(run, prm, w[:1], res, registry, period=sols[0].period)
    rho = np.array([s.rho for s in sols])
    lower = np.array([s.rho_lower for s in sols])
    slack = np.array([s.slack for s in sols])
    return {"omega1": w, "amplitude": np.array([s.amplitude for s in sols]), "growth": rho,
            "growth_rate": np.array([s.growth_rate for s in sols]),
            "rho_lower": lower, "rho_upper": np.array([s.rho_upper for s in sols]),
            "mode_wavelength": np.array([s.mode_wavelength for s in sols]),
            "unstable": (lower > 1.0) | slack, "slack": slack, "sampling_converged": done,
            "grid": a["grid"], "span": a["span"], "n_steps": int(sum(s.n_steps for s in sols)),
            "tension_coefficient": a["tension_coefficient"]}
