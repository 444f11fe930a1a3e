"""Finite differences for the moving-string span, Eqs. (2-36)/(2-37) with (2-38).

    m u_tt + 2 m c u_xt + m c^2 u_xx + c_d (u_t + c u_x) - (P + P_t) u_xx - kappa P_t = 0

Time: central differences (three levels).  The gyroscopic term 2 m c u_xt is centred in
time, D(u^{j+1} - u^{j-1}) / (2 dt), which makes each step a tridiagonal solve but keeps
the scheme neutrally stable up to its von Neumann limit dx/sqrt(c_w^2 - c^2); a fully explicit lag of
that term is unconditionally (weakly) unstable for the moving string (tests show it).
Space: second derivative central; first derivatives by the mixed differencing of
Eq. (2-38) with weight s* (central at s* = 0, backward at s* = 1).

The whole speed sweep is one computation: every array is shaped (n_speeds, n_points)
and the S tridiagonal systems of a step are solved as one block-diagonal banded system
by LAPACK (``dgttrs``, factorised once per length state).  Time-dependent coefficients
(dynamic tension, end motions, span-length state) are evaluated by the effects for the
whole (time, speed) grid before stepping.

The time step is the von Neumann limit of this scheme, dt = cfl * dx / sqrt(c_w^2 - c^2)
(:func:`courant_limit`); a requested step beyond the limit is refused.  Near the limit
(cfl 0.98, the default of the sweeps without impact) the explicit u_xx transports waves
almost exactly (at c = 0 and nu = 1 the three-level scheme is exact), which removes most
of the error of the lightly damped resonance peaks; at cfl = 1 the sawtooth mode has a
double root at the largest tension and is left alone.

``differencing="central"`` (s* = 0) is second order; the paper's mixed differencing adds a
numerical Kelvin-Voigt damping ~ m c s* dx u_xxt (first order) -- which is also what keeps
the pitch-scale modes pumped by the impact pulse bounded (docs/chain_drive.md, hard case).

For a uniform step the time loop runs compiled (:mod:`.fd_kernel`, numba, cached on disk)
when numba is installed; the numpy loop below is the reference and the fallback.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import lapack

from . import fd_kernel
from .errors import KernelUnavailable, StabilityError, UnknownChoice  # noqa: F401 (re-exported)


@dataclass
class Excitation:
    """Time-dependent data on the step grid, arrays shaped (n_steps + 1, n_speeds).

    ``tension``: dynamic tension P_t; ``u_left``/``u_right``: prescribed end displacements at
    x = 0 (driven sprocket) and x = L (driving sprocket); ``long``: span-length state (True =
    long span); ``load``: transverse force per length (sag term kappa P_t).  None = absent.
    """
    tension: np.ndarray | None = None
    u_left: np.ndarray | None = None
    u_right: np.ndarray | None = None
    long: np.ndarray | None = None
    load: np.ndarray | None = None
    source: object = None     # callable(j) -> (S, n-1) distributed force at interior nodes


@dataclass
class Grid:
    """Spatial grid over the long span [0, L_long]; the short span ends at index n_short."""
    L_long: float
    n_long: int
    n_short: int

    @property
    def dx(self) -> float:
        return self.L_long / self.n_long

    @property
    def x(self) -> np.ndarray:
        return np.linspace(0.0, self.L_long, self.n_long + 1)


def amplification(nu, a, s_star, n_theta: int = 721):
    """Von Neumann amplification of the scheme as coded (principal part, no damping).

    With u_i^j = G^j e^{i i theta}, nu = c_w dt/dx (c_w^2 = (P + P_t)/m), a = c/c_w, the
    three-level scheme of :func:`march` (central u_tt, centred-in-time gyroscopic term with
    the mixed first difference of Eq. (2-38), explicit u_xx) gives

        (1 + beta) G^2 - (2 - 4 (1 - a^2) nu^2 sin^2(theta/2)) G + (1 - beta) = 0,
        beta = a nu (i sin theta + s* (1 - cos theta)).

    Returns max over theta in [0, pi] of the larger root modulus (broadcast over nu, a, s*).
    """
    th = np.linspace(0.0, np.pi, n_theta)
    nu = np.asarray(nu, float)[..., None]
    a = np.asarray(a, float)[..., None]
    s = np.asarray(s_star, float)[..., None]
    beta = a * nu * (1j * np.sin(th) + s * (1 - np.cos(th)))
    A, C = 1 + beta, 1 - beta
    B = -2 + 4 * (1 - a * a) * nu * nu * np.sin(th / 2) ** 2
    disc = np.sqrt(B * B - 4 * A * C + 0j)
    g = np.maximum(np.abs((-B + disc) / (2 * A)), np.abs((-B - disc) / (2 * A)))
    return np.max(g, axis=-1)


def courant_limit(a):
    """Largest stable nu = c_w dt/dx of the scheme: nu_max = 1/sqrt(1 - a^2), a = c/c_w < 1.

    From :func:`amplification`: the implicit (centred-in-time) gyroscopic term leaves the
    product of the roots |1 - beta|/|1 + beta| <= 1 for every s* >= 0, so stability is
    decided by the explicit u_xx term alone; at theta = pi the roots leave the unit circle
    once (1 - a^2) nu^2 > 1.  In dimensional form dt <= dx / sqrt(c_w^2 - c^2) -- larger
    than the characteristic bound dx/(c + c_w) by sqrt((c_w + c)/(c_w - c)) (1.73 at
    c = 0.5 c_w).  Checked against the numerical root modulus and by marching just inside
    and just outside the limit (tests/test_chain_drive_stability.py).
    """
    a = np.asarray(a, float)
    if np.any(a >= 1):
        raise StabilityError("c >= c_w: supercritical speed, the string model has no stable "
                             "time step")
    return 1.0 / np.sqrt(1.0 - a * a)


def stable_time_step(dx: float, c, P_max, m: float, cfl: float = 0.9) -> float:
    """dt = cfl * min over speeds of dx / sqrt(c_w^2 - c^2), c_w^2 = P_max/m: the von Neumann
    limit of the scheme as coded (:func:`courant_limit`)."""
    if not 0.0 < cfl <= 1.0:
        raise StabilityError(f"CFL safety factor {cfl} outside (0, 1]: the scheme is only "
                             "stable up to its von Neumann limit")
    P_max = np.asarray(P_max, float)
    if np.any(P_max <= 0):
        raise StabilityError("tension is not positive: the span is slack, a string model "
                             "cannot represent it")
    c = np.asarray(c, float)
    cw = np.sqrt(P_max / m)
    a = np.abs(c) / cw
    return float(cfl * dx * np.min(courant_limit(a) / cw))


def characteristic_time_step(dx: float, c, P_max, m: float) -> float:
    """The former, stated bound dt = dx / max(c + c_w) (kept to compare with)."""
    return float(dx / np.max(np.asarray(c, float) + np.sqrt(np.asarray(P_max, float) / m)))


def check_time_step(dt: float, dx: float, c, P_max, m: float) -> None:
    """Refuse a hand-picked step past the von Neumann limit (never return garbage)."""
    limit = stable_time_step(dx, c, P_max, m, cfl=1.0)
    if dt > limit * (1 + 1e-12):
        raise StabilityError(f"time step {dt:.4g} s exceeds the stability limit "
                             f"{limit:.4g} s = dx/sqrt(c_w^2 - c^2); refusing to step")


def mixed_weights(s_star, dx: float):
    """Eq. (2-38): weights of u_{i-1}, u_i, u_{i+1} in du/dx (shape (S, 3))."""
    s = np.asarray(s_star, float)
    return np.stack([-(1 + s) / (2 * dx), s / dx, (1 - s) / (2 * dx)], axis=-1)


@dataclass
class MarchResult:
    amplitude: np.ndarray                 # (S,) max |u| over x and the measuring window
    growth: np.ndarray                    # (S,) growth ratio of the last to first window block
    unstable: np.ndarray                  # (S,) bool: growing response (Mathieu) or capped
    block_max: np.ndarray                 # (n_blocks, S) max |u| per block of the window
    probes: np.ndarray | None = None      # (n_rec, S, n_probe) recorded u at probe indices
    t_rec: np.ndarray | None = None
    final: np.ndarray | None = None       # (S, n+1) last state
    n_steps: int = 0
    dt: float = 0.0


def _factor(dl, d, du):
    out = lapack.dgttrf(dl, d, du)
    if out[-1] != 0:
        raise StabilityError(f"tridiagonal step matrix is singular (info={out[-1]})")
    return out[:-1]


def _step_coeffs(h1, h2, *, m, c_d, c, W):
    """LHS tridiagonal blocks and explicit weights for steps h1 (j-1 -> j), h2 (j -> j+1)."""
    a_tt = 2.0 / (h2 * (h1 + h2))                  # multiplies u^{j+1} in u_tt
    b_t = 1.0 / (h1 + h2)                          # central first time derivative
    diag = m * a_tt + c_d * b_t + 2 * m * c * b_t * W[:, 1]
    low = 2 * m * c * b_t * W[:, 0]
    up = 2 * m * c * b_t * W[:, 2]
    return a_tt, b_t, low, diag, up


def _factors(low, diag, up, *, ni, ns, short: bool):
    """LU factors of the block-diagonal (one block per speed) tridiagonal step matrix;
    ``short``: the rows of the long span's extra pitch hold the boundary value."""
    dl = np.repeat(low[:, None], ni, 1)
    dd = np.repeat(diag[:, None], ni, 1)
    du = np.repeat(up[:, None], ni, 1)
    if short:
        # interior rows from index ns on are identity rows holding the boundary value
        k0 = ns - 1
        dd[:, k0:] = 1.0
        dl[:, k0:] = 0.0
        du[:, k0:] = 0.0
    dl[:, 0] = 0.0      # block boundaries: no coupling between speeds
    du[:, -1] = 0.0
    return _factor(dl.ravel()[1:], dd.ravel(), du.ravel()[:-1])


def set_ends(u, u_left, u_right, long, n_short: int) -> None:
    """Impose on the given first levels u (S, n + 1) what :func:`march` imposes on every
    level: the end displacements, and the end value on the long span's extra pitch (nodes
    from ``n_short`` on) in the rows whose span is short (``long`` False; None: no length
    change).  u_left, u_right, long: (S,) values at that level."""
    u[:, 0], u[:, -1] = u_left, u_right
    if long is not None:
        sh = ~long
        u[sh, n_short:] = u_right[sh, None]


def march(*, c, P, m: float, c_d: float, grid: Grid, dt, n_steps: int,
          exc: Excitation, s_star=None, measure_from: int | None = None, n_blocks: int = 4,
          u_cap: float = 1.0, probes=(), record_every: int = 0, u0=None, v0=None,
          dt_series=None, u1=None, differencing: str | None = None,
          kernel: str = "auto") -> MarchResult:
    """Step Eq. (2-36)/(2-37) for S operating speeds at once.

    c, P: (S,) chain speed and axial tension P = T_s (+ lambda m c^2).
    dt: the time step (check with :func:`check_time_step` first), or ``dt_series`` (n_steps,)
    for the non-uniform scheme of Sec. 3.1 (the matrix is then refactorised every step).
    u0, v0: initial displacement and velocity (S, n+1) (default rest).
    measure_from: first step of the measuring window (steady state); the window is split
    in ``n_blocks`` blocks whose maxima reveal growth.  Rows whose |u| exceeds ``u_cap``
    are frozen and reported unstable: growth is detected, never overflowed into NaN.
    differencing: ``"central"`` (s* = 0, second order), ``"mixed"`` (Eq. 2-38 with the
    given ``s_star``, first order) or None (``s_star`` as given; s* = c/c_w if None).
    kernel: ``"auto"`` runs the uniform-step loop compiled (:mod:`.fd_kernel`) when numba
    is installed, the march is large enough to pay for loading it (the march's size alone
    decides, so a run's numbers never depend on what its process ran before), there is
    no ``exc.source`` and the step matrix is diagonally dominant
    (Thomas without pivoting); ``"numpy"`` forces the numpy loop (LAPACK ``dgttrs``);
    ``"compiled"`` requires the compiled loop.  Both give the same result to round-off.
    """
    if differencing not in (None, "central", "mixed"):
        raise UnknownChoice(f"differencing {differencing!r}: allowed central, mixed")
    if kernel not in ("auto", "numpy", "compiled"):
        raise UnknownChoice(f"kernel {kernel!r}: allowed auto, numpy, compiled")
    c = np.atleast_1d(np.asarray(c, float))
    S = c.size
    if differencing == "central":
        s_star = 0.0
    P = np.broadcast_to(np.asarray(P, float), (S,)).copy()
    n, ns = grid.n_long, grid.n_short
    dx = grid.dx
    ni = n - 1
    s = c / np.sqrt(P / m) if s_star is None else np.broadcast_to(s_star, (S,))
    W = mixed_weights(np.clip(s, 0, 1), dx)              # (S, 3)
    # inputs shaped (time, 1) are shared by every speed (the lanes of a shooting march): the
    # compiled loop reads them as they are, the numpy loop and the first levels as (time, S)
    # views; the absent ones are zeros of the same width
    widths = {np.shape(x)[1] for x in (exc.tension, exc.u_left, exc.u_right, exc.load, exc.long)
              if x is not None}
    if len(widths) > 1 or widths - {1, S}:
        raise ValueError(f"excitation widths {sorted(widths)}: every input has 1 or {S} columns")
    zeros = np.zeros((n_steps + 1, widths.pop() if widths else S))
    raw = dict(Pt=exc.tension, uL=exc.u_left if exc.u_left is not None else zeros,
               uR=exc.u_right if exc.u_right is not None else zeros, q=exc.load,
               longs=exc.long)
    Pt, uL, uR, q, longs = (None if x is None else np.broadcast_to(x, (x.shape[0], S))
                            for x in (raw["Pt"] if exc.tension is not None else zeros,
                                      raw["uL"], raw["uR"], raw["q"], raw["longs"]))
    length_change = longs is not None and ns != n

    uniform = dt_series is None
    if uniform:
        hs = np.full(n_steps, float(dt))
    else:
        hs = np.asarray(dt_series, float)
        n_steps = hs.size
    h_prev = hs[0]
    sc = dict(m=m, c_d=c_d, c=c, W=W)
    coeffs = _step_coeffs(h_prev, hs[0], **sc)

    u_prev = np.zeros((S, n + 1)) if u0 is None else np.array(u0, float)
    set_ends(u_prev, uL[0], uR[0], longs[0] if length_change else None, ns)
    # second level from a Taylor step (rest or given velocity, no acceleration)
    if u1 is not None:
        u_cur = np.array(u1, float)
    else:
        u_cur = u_prev + (0.0 if v0 is None else hs[0] * np.asarray(v0, float))
    set_ends(u_cur, uL[1], uR[1], longs[1] if length_change else None, ns)

    measure_from = n_steps // 2 if measure_from is None else int(measure_from)
    win = max(n_steps - measure_from, 1)
    block_len = max(win // n_blocks, 1)
    if kernel != "numpy":
        _, _, low, diag, up = coeffs
        fast = (uniform and exc.source is None
                and (kernel == "compiled" or fd_kernel.worth_it(S * (n + 1) * n_steps))
                and fd_kernel.available()
                and bool(np.all(np.abs(diag) > np.abs(low) + np.abs(up))))
        if kernel == "compiled" and not fast:
            raise KernelUnavailable("compiled kernel unavailable here (needs numba, a uniform step, "
                             "no exc.source and a diagonally dominant step matrix)")
        if fast:
            return _march_compiled(c=c, P=P, W=W, m=m, c_d=c_d, grid=grid, dt=float(hs[0]),
                                   n_steps=n_steps, measure_from=measure_from,
                                   n_blocks=n_blocks, block_len=block_len, u_cap=u_cap,
                                   exc=exc, Pt=raw["Pt"], uL=raw["uL"], uR=raw["uR"],
                                   longs=raw["longs"] if length_change else None, u0=u_prev,
                                   u1=u_cur, probes=probes, record_every=record_every)
    # LAPACK factors for the numpy loop only (the compiled loop factorises its own)
    fac_long = _factors(*coeffs[2:], ni=ni, ns=ns, short=False)
    fac_short = _factors(*coeffs[2:], ni=ni, ns=ns, short=True) if length_change else None
    return _march_numpy(hs=hs, uniform=uniform, coeffs=coeffs, sc=sc, fac_long=fac_long,
                        fac_short=fac_short, u_prev=u_prev, u_cur=u_cur, Pt=Pt, uL=uL, uR=uR,
                        q=q, longs=longs, exc=exc, P=P, W=W, dx=dx, ni=ni, ns=ns, S=S,
                        n_steps=n_steps, measure_from=measure_from, n_blocks=n_blocks,
                        block_len=block_len, u_cap=u_cap, probes=probes,
                        record_every=record_every, length_change=length_change)


def _march_numpy(*, hs, uniform, coeffs, sc, fac_long, fac_short, u_prev, u_cur, Pt, uL, uR,
                 q, longs, exc, P, W, dx, ni, ns, S, n_steps, measure_from, n_blocks,
                 block_len, u_cap, probes, record_every, length_change) -> MarchResult:
    """The time loop of :func:`march` in numpy (LAPACK ``dgttrs``): the reference loop, and
    the one for a non-uniform step or a source term."""
    m, c_d, c = sc["m"], sc["c_d"], sc["c"]
    block_max = np.zeros((n_blocks, S))
    capped = np.zeros(S, bool)
    rec, t_rec = [], []
    probes = list(probes)
    t = hs[0]
    rhs = np.empty((S, ni))
    tmp = np.empty((S, ni))
    cdc = c_d * c
    for j in range(1, n_steps):
        h1, h2 = hs[j - 1], hs[j]
        if not uniform:
            coeffs = _step_coeffs(h1, h2, **sc)
            fac_long = _factors(*coeffs[2:], ni=ni, ns=ns, short=False)
            if length_change:
                fac_short = _factors(*coeffs[2:], ni=ni, ns=ns, short=True)
        a_tt, b_t, low, diag, up = coeffs
        a_prev = 2.0 / (h1 * (h1 + h2))
        a_cur = 2.0 / (h1 * h2)
        # rhs = m(a_cur u^j - a_prev u^{j-1}) + (P + P_t - m c^2) u_xx^j - c_d c D u^j
        #       + 2 m c b_t D u^{j-1} + c_d b_t u^{j-1} + load, as two 3-point stencils
        # with per-speed weights (only the tension weight changes in time)
        Tj = (P + Pt[j] - m * c * c) / (dx * dx)
        kl = Tj - cdc * W[:, 0]
        kc = m * a_cur - 2 * Tj - cdc * W[:, 1]
        ku = Tj - cdc * W[:, 2]
        g = 2 * m * b_t * c
        ql = g * W[:, 0]
        qc = g * W[:, 1] - (m * a_prev - c_d * b_t)
        qu = g * W[:, 2]
        uc, up_ = u_cur, u_prev
        np.multiply(uc[:, :-2], kl[:, None], out=rhs)
        np.multiply(uc[:, 1:-1], kc[:, None], out=tmp); rhs += tmp
        np.multiply(uc[:, 2:], ku[:, None], out=tmp); rhs += tmp
        np.multiply(up_[:, :-2], ql[:, None], out=tmp); rhs += tmp
        np.multiply(up_[:, 1:-1], qc[:, None], out=tmp); rhs += tmp
        np.multiply(up_[:, 2:], qu[:, None], out=tmp); rhs += tmp
        if q is not None:
            rhs += q[j][:, None]
        if exc.source is not None:
            rhs += exc.source(j)
        # known boundary values at j+1 of the implicit D u^{j+1}
        rhs[:, 0] -= low * uL[j + 1]
        rhs[:, -1] -= up * uR[j + 1]
        sol = lapack.dgttrs(*fac_long, rhs.ravel())[0].reshape(S, ni)
        if length_change:
            rs = rhs.copy()
            k0 = ns - 1
            rs[:, k0:] = uR[j + 1][:, None]   # identity rows; node ns couples in the matrix
            sol_s = lapack.dgttrs(*fac_short, rs.ravel())[0].reshape(S, ni)
            sh = ~longs[j + 1]
            sol[sh] = sol_s[sh]
        u_new = u_prev  # reuse the buffer of level j-1
        u_new[:, 1:-1] = sol
        u_new[:, 0] = uL[j + 1]
        u_new[:, -1] = uR[j + 1]
        if length_change:
            sh = ~longs[j + 1]
            u_new[sh, ns:] = uR[j + 1, sh, None]
        t += h2
        if j + 1 >= measure_from:
            amp = np.max(np.abs(u_new), axis=1)
            b = min((j + 1 - measure_from) // block_len, n_blocks - 1)
            np.maximum(block_max[b], amp, out=block_max[b])
        if j % 16 == 0:
            # freeze rows that left the linear range: growth is reported, never overflowed
            big = np.max(np.abs(u_new), axis=1) > u_cap
            if np.any(big):
                capped |= big
                u_new[big] = 0.0
                u_cur[big] = 0.0
        if record_every and (j + 1) % record_every == 0:
            rec.append(u_new[:, probes].copy())
            t_rec.append(t)
        u_prev, u_cur = u_cur, u_new
    return _result(block_max, capped, u_cap, rec, t_rec, u_cur, n_steps, float(hs.max()))


def _march_compiled(*, c, P, W, m, c_d, grid, dt, n_steps, measure_from, n_blocks,
                    block_len, u_cap, exc, Pt, uL, uR, longs, u0, u1, probes, record_every):
    block_max, capped, final, rec = fd_kernel.march_uniform(
        c=c, P=P, W=W, m=m, c_d=c_d, dx=grid.dx, dt=dt, n=grid.n_long, ns=grid.n_short,
        n_steps=n_steps, measure_from=measure_from, n_blocks=n_blocks, block_len=block_len,
        u_cap=u_cap, Pt=Pt, uL=uL, uR=uR, longs=longs, q=exc.load, u0=u0, u1=u1,
        probes=probes, record_every=record_every)
    t_rec = None
    if rec is not None:
        t_rec = dt * np.array([j + 1 for j in range(1, n_steps) if (j + 1) % record_every == 0],
                              float)
        if not rec.shape[0]:
            rec, t_rec = None, None
    return _result(block_max, capped, u_cap, rec, t_rec, final, n_steps, dt)


def _result(block_max, capped, u_cap, rec, t_rec, final, n_steps, dt) -> MarchResult:
    rec = None if rec is None or (isinstance(rec, list) and not rec) else np.asarray(rec)
    t_rec = None if t_rec is None or (isinstance(t_rec, list) and not t_rec) else np.asarray(t_rec)
    first = np.maximum(block_max[0], 1e-300)
    growth = block_max[-1] / first
    # a growing response: each block larger than the one before, the last by > 50 %
    monotone = np.all(np.diff(block_max, axis=0) > 0, axis=0)
    unstable = capped | (monotone & (growth > 1.5))
    amplitude = np.where(capped, u_cap, np.max(block_max, axis=0))
    return MarchResult(amplitude=amplitude, growth=np.where(capped, np.inf, growth),
                       unstable=unstable, block_max=block_max, probes=rec, t_rec=t_rec,
                       final=final, n_steps=n_steps, dt=dt)
