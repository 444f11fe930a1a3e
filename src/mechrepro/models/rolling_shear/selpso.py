"""selPSO: particle swarm with inertia weight and natural selection (Sec. 2.1, Fig. 1).

Eq. (1)  v_i^{k+1} = w v_i^k + c1 r1 (pbest_i - x_i^k) + c2 r2 (gbest - x_i^k)
Eq. (2)  x_i^{k+1} = x_i^k + v_i^{k+1}

w falls linearly from ``w_start`` to ``w_end`` (Shi & Eberhart, Ref. [12]); after each move the
worse half of the swarm takes the better half's positions and velocities; stop at
G(gbest) < ``tol``.  With a :class:`KernelFitness` an unbounded swarm runs compiled
(:func:`iterate`, the same random stream and bits); the numpy loop serves any fitness."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from mechrepro.compiled import jit

from . import closure


@dataclass(frozen=True)
class SelPSOSettings:
    swarm: int = 40
    max_iter: int = 1500
    w_start: float = 0.9
    w_end: float = 0.4
    c1: float = 2.0
    c2: float = 2.0
    tol: float = 1e-11
    init_scale: float = 1.0
    v_max: float = float("inf")
    #: natural selection (Sec. 2.1); off only to measure what it buys (tests, benchmark)
    selection: bool = True


class KernelFitness:
    """A fitness the compiled swarm knows: :func:`.closure.fitness` of ``kind`` with constants ``c``
    and knowns ``q``; ``fn`` is the same fitness in numpy."""

    def __init__(self, fn, kind: int, c: np.ndarray, q: tuple):
        self.fn, self.kind, self.c, self.q = fn, kind, c, tuple(float(v) for v in q)

    def __call__(self, X):
        return self.fn(X)


@dataclass
class SelPSOResult:
    x: np.ndarray
    fitness: float
    iterations: int
    evaluations: int
    converged: bool
    history: np.ndarray = field(repr=False)


def selpso(fitness, x_init, settings: SelPSOSettings, rng: np.random.Generator,
           lower=None, upper=None, period: float | None = None) -> SelPSOResult:
    """Minimise ``fitness`` from ``x_init`` (n,).

    With ``lower``/``upper`` the swarm is drawn in the box and clipped to it (lever optimisation).
    ``period`` reduces the initial value modulo 2 pi first: a large angle carries enough
    round-off to stall the swarm above the paper's G < 1e-11."""
    st = settings
    x_init = np.asarray(x_init, float)
    if period is not None:
        x_init = np.mod(x_init, period)
    N, n = st.swarm, x_init.size
    if lower is not None:
        X = lower + (upper - lower) * rng.random((N, n))
        V = 0.1 * (upper - lower) * rng.standard_normal((N, n))
    else:
        X = x_init + st.init_scale * rng.standard_normal((N, n))
        V = st.init_scale * rng.standard_normal((N, n))
    G = fitness(X)
    evals = N
    pbest, pG = X.copy(), G.copy()
    ib = int(np.argmin(G))
    gbest, gG = X[ib].copy(), float(G[ib])
    if isinstance(fitness, KernelFitness) and lower is None and N >= 2 and closure.available():
        hist = np.empty(st.max_iter + 1)
        hist[0] = gG
        gG, k = iterate(
            fitness.kind, fitness.c, fitness.q, X, V, pbest, pG, gbest, gG, rng, st.max_iter,
            float(st.w_start), float(st.w_end), float(st.c1), float(st.c2), float(st.tol),
            float(st.v_max), bool(np.isfinite(st.v_max)), bool(st.selection), hist)
        return SelPSOResult(gbest, gG, k, N * (k + 1), gG < st.tol, hist[:k + 1].copy())
    history = [gG]
    half = N // 2
    k = 0
    for k in range(1, st.max_iter + 1):
        if gG < st.tol:
            k -= 1
            break
        w = st.w_start - (st.w_start - st.w_end) * (k - 1) / max(st.max_iter - 1, 1)
        r1, r2 = rng.random((2, N, n))
        V = w * V + st.c1 * r1 * (pbest - X) + st.c2 * r2 * (gbest - X)
        if np.isfinite(st.v_max):
            np.clip(V, -st.v_max, st.v_max, out=V)
        X = X + V
        if lower is not None:
            np.clip(X, lower, upper, out=X)
        G = fitness(X)
        evals += N
        better = G < pG
        pbest[better], pG[better] = X[better], G[better]
        ib = int(np.argmin(pG))
        if pG[ib] < gG:
            gbest, gG = pbest[ib].copy(), float(pG[ib])
        if st.selection:
            natural_selection(X, V, G, half)
        history.append(gG)
    return SelPSOResult(gbest, gG, k, evals, gG < st.tol, np.asarray(history))


def natural_selection(X: np.ndarray, V: np.ndarray, G: np.ndarray, half: int) -> None:
    """Sec. 2.1: rank by fitness G; the worse half takes the better half's positions and
    velocities (in place); pbest and gbest are kept by the caller."""
    order = np.argsort(G, kind="stable")
    X[order[-half:]] = X[order[:half]]
    V[order[-half:]] = V[order[:half]]


@jit
def _stable_argsort(G, order):
    """np.argsort(G, kind="stable") (NaN last) by insertion, for numba."""
    N = G.size
    for i in range(N):
        order[i] = i
    for i in range(1, N):
        k = order[i]
        key = G[k]
        j = i - 1
        while j >= 0:
            prev = G[order[j]]
            if key < prev or (math.isnan(prev) and not math.isnan(key)):
                order[j + 1] = order[j]
                j -= 1
            else:
                break
        order[j + 1] = k


@jit
def iterate(kind, c, q, X, V, pbest, pG, gbest, gG, rng, max_iter, w_start, w_end, c1, c2, tol,
            v_max, clip_v, selection, hist):
    """Iterations 1..max_iter of :func:`selpso` (unbounded) on :func:`.closure.fitness`, in place;
    hist[k] = gG after iteration k.  Returns (gG, k)."""
    p = closure.record(c)
    N, n = X.shape
    half = N // 2
    G = np.empty(N)
    r = np.empty((2, N, n))
    order = np.empty(N, np.int64)
    k = 0
    for it in range(1, max_iter + 1):
        k = it
        if gG < tol:
            k = it - 1
            break
        w = w_start - (w_start - w_end) * (it - 1) / max(max_iter - 1, 1)
        for a in range(2):
            for i in range(N):
                for j in range(n):
                    r[a, i, j] = rng.random()
        for i in range(N):
            for j in range(n):
                v = (w * V[i, j] + c1 * r[0, i, j] * (pbest[i, j] - X[i, j])
                     + c2 * r[1, i, j] * (gbest[j] - X[i, j]))
                if clip_v:
                    if v < -v_max:
                        v = -v_max
                    elif v > v_max:
                        v = v_max
                V[i, j] = v
                X[i, j] = X[i, j] + v
        closure.fitness(kind, p, q, X, G)
        for i in range(N):
            if G[i] < pG[i]:
                for j in range(n):
                    pbest[i, j] = X[i, j]
                pG[i] = G[i]
        ib = 0
        best = pG[0]
        if not math.isnan(best):
            for i in range(1, N):
                if math.isnan(pG[i]):
                    ib = i
                    break
                if pG[i] < best:
                    best = pG[i]
                    ib = i
        if pG[ib] < gG:
            for j in range(n):
                gbest[j] = pbest[ib, j]
            gG = pG[ib]
        if selection:
            _stable_argsort(G, order)
            for m in range(half):
                dst, src = order[N - half + m], order[m]
                for j in range(n):
                    X[dst, j] = X[src, j]
                    V[dst, j] = V[src, j]
        hist[it] = gG
    return gG, k
