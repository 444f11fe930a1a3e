"""Compiled time loop of :func:`.fd.march` for the uniform step (numba, cached on disk).

The scheme is exactly the one of :mod:`.fd` (same three-level stencils, same boundary and
span-length handling, same block maxima and capping); only the loop is compiled.  The
speeds are independent, so they are marched in lanes of ``LANES`` speeds at a time: every
array of a lane group is (n + 1, LANES) and stays in cache (L1/L2) for the whole record,
and the inner loops run over the lanes (SIMD).  The sweeps along the span (elimination,
back substitution, maximum) take four grid rows per pass over the lanes: the row just
computed stays in a register and the loop overhead is shared, each row's operations
unchanged.  The tridiagonal step matrix is constant in time for a uniform step, so each
speed's Thomas factors (no pivoting; used only when the matrix is diagonally dominant,
which :func:`.fd.march` checks) are computed once; the short-span state only turns the
rows from node ``n_short`` on into identity rows, which leaves the factors of the rows
above unchanged (the elimination runs top-down).

Compiled by :func:`mechrepro.compiled.jit` (its disk cache keyed on the package's
sources), lazily (numba costs ~0.3 s to import); :func:`available` says whether numba is
installed.  Without it :func:`.fd.march` runs its numpy loop, with the same results to
round-off.
"""
from __future__ import annotations

import numpy as np

from mechrepro.compiled import available, jit

# 32 speeds per lane group: eight AVX2 vectors per grid row hide the latency of the
# recurrences along the span better than four (the group's arrays still fit in L2)
LANES = 32
# "auto" compiles/loads the kernel only for marches of at least this many point-updates
# (S x (n + 1) x steps): importing numba and loading the cached kernel cost ~0.5-1 s per
# process, more than the numpy loop needs for a small march (exact-solution checks, a
# single-speed time history).  The choice depends on the march alone, never on what ran
# before in the process, so a run's numbers do not depend on how jobs are batched
MIN_UPDATES = 5_000_000
_KERNEL = None


def worth_it(updates: int) -> bool:
    """Whether ``kernel="auto"`` should use the compiled loop for a march of this size."""
    return updates >= MIN_UPDATES




def _build(lanes):
    B = lanes

    @jit(fastmath={"contract"})
    def march_lanes(c, P, W, m, c_d, dx, dt, n, ns, n_steps, measure_from, n_blocks,
                    block_len, u_cap, Pt, has_Pt, uL, uR, longs, length_change, q, has_q,
                    u0, u1, probes, record_every, block_max, capped, final, rec):
        S = c.size                        # a multiple of B (padded by the caller)
        S_in = uL.shape[1]                # the speeds of the (time, speed) inputs
        ni = n - 1
        k0 = ns - 1 if length_change else ni   # first identity row of the short state
        h2 = 1.0 / (dt * dt)              # a_tt = a_prev = 1/dt^2, a_cur = 2/dt^2 (uniform)
        b_t = 1.0 / (2.0 * dt)
        idx2 = 1.0 / (dx * dx)
        up_ = np.empty((n + 1, B))
        uc_ = np.empty((n + 1, B))
        r = np.empty((ni, B))
        w = np.empty((ni, B))             # Thomas multipliers
        invd = np.empty((ni, B))          # inverse pivots
        low = np.empty(B); upc = np.empty(B)
        Tc = np.empty(B); cdw0 = np.empty(B); cdw1 = np.empty(B); cdw2 = np.empty(B)
        ql = np.empty(B); qc = np.empty(B); qu = np.empty(B)
        kl = np.empty(B); kc = np.empty(B); ku = np.empty(B)
        ld = np.zeros(B); uRn = np.empty(B); uLn = np.empty(B)
        keep = np.ones(B)                 # 0 in lanes whose span is short at j + 1
        amp = np.empty(B)
        for s0 in range(0, S, B):
            for k in range(B):
                s = s0 + k
                cc = c[s]
                g = 2.0 * m * cc * b_t
                low[k] = g * W[s, 0]
                dia = m * h2 + c_d * b_t + g * W[s, 1]
                upc[k] = g * W[s, 2]
                Tc[k] = (P[s] - m * cc * cc) * idx2
                cdw0[k] = c_d * cc * W[s, 0]
                cdw1[k] = c_d * cc * W[s, 1]
                cdw2[k] = c_d * cc * W[s, 2]
                ql[k] = g * W[s, 0]
                qc[k] = g * W[s, 1] - (m * h2 - c_d * b_t)
                qu[k] = g * W[s, 2]
                d = dia
                w[0, k] = 0.0
                invd[0, k] = 1.0 / d
                for i in range(1, ni):
                    wi = low[k] / d
                    d = dia - wi * upc[k]
                    w[i, k] = wi
                    invd[i, k] = 1.0 / d
                for i in range(n + 1):
                    up_[i, k] = u0[s, i]
                    uc_[i, k] = u1[s, i]
            u_prev = up_
            u_cur = uc_
            irec = 0
            for j in range(1, n_steps):
                for k in range(B):
                    # the (time, speed) inputs are not padded: padded lanes repeat the last
                    s = min(s0 + k, S_in - 1)
                    Tj = Tc[k]
                    if has_Pt:
                        Tj += Pt[j, s] * idx2
                    kl[k] = Tj - cdw0[k]
                    kc[k] = 2.0 * m * h2 - 2.0 * Tj - cdw1[k]
                    ku[k] = Tj - cdw2[k]
                    if has_q:
                        ld[k] = q[j, s]
                    uLn[k] = uL[j + 1, s]
                    uRn[k] = uR[j + 1, s]
                    if length_change:
                        keep[k] = 1.0 if longs[j + 1, s] else 0.0
                # right-hand side fused with the forward elimination (row i - 1 = node i)
                for k in range(B):
                    r[0, k] = (kl[k] * u_cur[0, k] + kc[k] * u_cur[1, k] + ku[k] * u_cur[2, k]
                               + ql[k] * u_prev[0, k] + qc[k] * u_prev[1, k]
                               + qu[k] * u_prev[2, k] + ld[k] - low[k] * uLn[k])
                # four rows per pass over the lanes: the row eliminated just above stays in
                # a register and the per-row loop overhead (numba's alias checks between the
                # lane arrays, reloaded pointers) is shared; each row's operations and their
                # order are those of the one-row loop below, so the result is bit for bit
                i = 2
                while i + 3 <= k0:
                    for k in range(B):
                        a = kl[k]; b = kc[k]; e = ku[k]; f = ql[k]; g = qc[k]; h = qu[k]
                        y = (a * u_cur[i - 1, k] + b * u_cur[i, k] + e * u_cur[i + 1, k]
                             + f * u_prev[i - 1, k] + g * u_prev[i, k] + h * u_prev[i + 1, k]
                             + ld[k] - w[i - 1, k] * r[i - 2, k])
                        r[i - 1, k] = y
                        y = (a * u_cur[i, k] + b * u_cur[i + 1, k] + e * u_cur[i + 2, k]
                             + f * u_prev[i, k] + g * u_prev[i + 1, k] + h * u_prev[i + 2, k]
                             + ld[k] - w[i, k] * y)
                        r[i, k] = y
                        y = (a * u_cur[i + 1, k] + b * u_cur[i + 2, k] + e * u_cur[i + 3, k]
                             + f * u_prev[i + 1, k] + g * u_prev[i + 2, k] + h * u_prev[i + 3, k]
                             + ld[k] - w[i + 1, k] * y)
                        r[i + 1, k] = y
                        y = (a * u_cur[i + 2, k] + b * u_cur[i + 3, k] + e * u_cur[i + 4, k]
                             + f * u_prev[i + 2, k] + g * u_prev[i + 3, k] + h * u_prev[i + 4, k]
                             + ld[k] - w[i + 2, k] * y)
                        r[i + 2, k] = y
                    i += 4
                while i <= k0:
                    for k in range(B):
                        r[i - 1, k] = (kl[k] * u_cur[i - 1, k] + kc[k] * u_cur[i, k]
                                       + ku[k] * u_cur[i + 1, k] + ql[k] * u_prev[i - 1, k]
                                       + qc[k] * u_prev[i, k] + qu[k] * u_prev[i + 1, k]
                                       + ld[k] - w[i - 1, k] * r[i - 2, k])
                    i += 1
                # rows from node n_short on: identity rows (= the end value) in short lanes
                for i in range(max(k0 + 1, 2), n):
                    for k in range(B):
                        v = (kl[k] * u_cur[i - 1, k] + kc[k] * u_cur[i, k]
                             + ku[k] * u_cur[i + 1, k] + ql[k] * u_prev[i - 1, k]
                             + qc[k] * u_prev[i, k] + qu[k] * u_prev[i + 1, k]
                             + ld[k] - w[i - 1, k] * r[i - 2, k])
                        r[i - 1, k] = keep[k] * v + (1.0 - keep[k]) * uRn[k]
                if k0 == 0 and length_change:
                    for k in range(B):
                        r[0, k] = keep[k] * r[0, k] + (1.0 - keep[k]) * uRn[k]
                # the end value of the last row (long lanes; a short lane's last row is an
                # identity row): d' x = y - up u_R, folded into the back substitution
                u_new = u_prev
                for k in range(B):
                    u_new[n, k] = uRn[k]
                    u_new[0, k] = uLn[k]
                # back substitution (long lanes) / copy (identity rows of short lanes)
                for i in range(n - 1, k0, -1):
                    for k in range(B):
                        x = (r[i - 1, k] - upc[k] * u_new[i + 1, k]) * invd[i - 1, k]
                        u_new[i, k] = keep[k] * x + (1.0 - keep[k]) * r[i - 1, k]
                # four rows per pass, as the elimination (unrolled one row at a time the
                # lane loop stayed scalar: the row just stored is read by the next)
                i = min(k0, n - 1)
                while i >= 4:
                    for k in range(B):
                        a = upc[k]
                        x = (r[i - 1, k] - a * u_new[i + 1, k]) * invd[i - 1, k]
                        u_new[i, k] = x
                        x = (r[i - 2, k] - a * x) * invd[i - 2, k]
                        u_new[i - 1, k] = x
                        x = (r[i - 3, k] - a * x) * invd[i - 3, k]
                        u_new[i - 2, k] = x
                        x = (r[i - 4, k] - a * x) * invd[i - 4, k]
                        u_new[i - 3, k] = x
                    i -= 4
                while i >= 1:
                    for k in range(B):
                        u_new[i, k] = (r[i - 1, k] - upc[k] * u_new[i + 1, k]) * invd[i - 1, k]
                    i -= 1
                measuring = j + 1 >= measure_from
                check = j % 16 == 0
                if measuring or check:
                    for k in range(B):
                        amp[k] = 0.0
                    # four rows per pass, the maxima taken in the same order of rows
                    i = 0
                    while i + 3 <= n:
                        for k in range(B):
                            x = max(amp[k], abs(u_new[i, k]))
                            x = max(x, abs(u_new[i + 1, k]))
                            x = max(x, abs(u_new[i + 2, k]))
                            amp[k] = max(x, abs(u_new[i + 3, k]))
                        i += 4
                    while i <= n:
                        for k in range(B):
                            amp[k] = max(amp[k], abs(u_new[i, k]))
                        i += 1
                    if measuring:
                        b = min((j + 1 - measure_from) // block_len, n_blocks - 1)
                        for k in range(B):
                            block_max[b, s0 + k] = max(block_max[b, s0 + k], amp[k])
                    if check:
                        # freeze rows that left the linear range (as fd.march)
                        for k in range(B):
                            if amp[k] > u_cap:
                                capped[s0 + k] = True
                                for i in range(n + 1):
                                    u_new[i, k] = 0.0
                                    u_cur[i, k] = 0.0
                if record_every > 0 and (j + 1) % record_every == 0:
                    for p in range(probes.size):
                        for k in range(B):
                            rec[irec, s0 + k, p] = u_new[probes[p], k]
                    irec += 1
                u_prev = u_cur
                u_cur = u_new
            for k in range(B):
                for i in range(n + 1):
                    final[s0 + k, i] = u_cur[i, k]

    return march_lanes


def kernel():
    """The compiled lane kernel (built and loaded from numba's disk cache on first use)."""
    global _KERNEL
    if _KERNEL is None:
        _KERNEL = _build(LANES)
    return _KERNEL


def march_uniform(*, c, P, W, m, c_d, dx, dt, n, ns, n_steps, measure_from, n_blocks,
                  block_len, u_cap, Pt, uL, uR, longs, q, u0, u1, probes, record_every):
    """Run the compiled loop; returns (block_max, capped, final, rec) for the S speeds."""
    S = c.size
    Sp = -(-S // LANES) * LANES
    pad = np.minimum(np.arange(Sp, dtype=np.int64), S - 1)

    def cols(x, dtype=float):
        # (time, speed) inputs are read unpadded (the kernel repeats the last speed in the
        # padded lanes): no copy when already C-contiguous of the right type
        return np.ascontiguousarray(np.asarray(x, dtype))

    def rows(x):
        return np.ascontiguousarray(np.asarray(x, float)[pad])

    dummy = np.zeros((1, 1))
    # the steps j = 1 .. n_steps - 1 with (j + 1) % record_every == 0
    n_rec = max(n_steps // record_every - 1 // record_every, 0) if record_every > 0 else 0
    block_max = np.zeros((n_blocks, Sp))
    capped = np.zeros(Sp, np.bool_)
    final = np.empty((Sp, n + 1))
    probes = np.asarray(probes, np.int64).reshape(-1)
    rec = np.zeros((max(n_rec, 1), Sp, max(probes.size, 1)))
    kernel()(rows(c), rows(P), rows(W), float(m), float(c_d), float(dx), float(dt),
             int(n), int(ns), int(n_steps), int(measure_from), int(n_blocks), int(block_len),
             float(u_cap), dummy if Pt is None else cols(Pt), Pt is not None, cols(uL), cols(uR),
             np.zeros((1, 1), np.bool_) if longs is None else cols(longs, np.bool_),
             longs is not None, dummy if q is None else cols(q), q is not None,
             rows(u0), rows(u1), probes, int(record_every), block_max, capped, final, rec)
    out_rec = rec[:n_rec, :S] if record_every and probes.size else None
    return block_max[:, :S], capped[:S], final[:S], out_rec


def warm() -> None:
    """Load the lane kernel (numba's disk cache, or a compile) by one call on a one-node,
    no-step march of the production argument types: a solver process pays this ~0.3-0.5 s
    once, before any timed solve, not inside the first sweep's time."""
    if not available():
        return
    z = np.zeros
    march_uniform(c=z(1), P=np.ones(1), W=z((1, 3)), m=1.0, c_d=0.0, dx=1.0, dt=1.0, n=2, ns=2,
                  n_steps=1, measure_from=1, n_blocks=1, block_len=1, u_cap=1.0, Pt=None,
                  uL=z((2, 1)), uR=z((2, 1)), longs=None, q=None, u0=z((1, 3)), u1=z((1, 3)),
                  probes=[], record_every=0)
