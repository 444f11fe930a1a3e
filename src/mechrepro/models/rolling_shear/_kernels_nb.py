"""The numba kernels of :mod:`.kernels` (imported only through :func:`.kernels.kernel`:
importing this module imports numba).  Module-level functions, so that numba's disk cache
holds them (and the kernels that call each other) across processes."""
import math

import numba
import numpy as np

jit = numba.njit(cache=True, error_model="numpy")


@jit
def fitness(kind, c, X, G):
    """G = sum |residuals| per particle, Eq. (9) (kind LOOPS) or Eq. (7) (kind POSE)."""
    N = X.shape[0]
    if kind == 0:
        l1, l2, l3, l4 = c[0], c[1], c[2], c[3]
        cx, cy, c6, s6, ix, iy = c[4], c[5], c[6], c[7], c[8], c[9]
        l9, l10, l11 = c[10], c[11], c[12]
        for i in range(N):
            t1, t2, t3, t4 = X[i, 0], X[i, 1], X[i, 2], X[i, 3]
            f1 = l1 * math.cos(t1) - l3 * math.cos(t3) - cx - c6 - l10 - l9
            f2 = l1 * math.sin(t1) - l3 * math.sin(t3) - cy - s6 + l11
            f3 = l2 * math.cos(t2) - l4 * math.cos(t4) - ix - c6 - l10
            f4 = l2 * math.sin(t2) - l4 * math.sin(t4) - iy - s6 + l11
            G[i] = abs(f1) + abs(f2) + abs(f3) + abs(f4)
    else:
        l6, d, beta1, beta2, h, R, s, x_target = c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]
        y1 = -h
        for i in range(N):
            t5, t6 = X[i, 0], X[i, 1]
            b = t5 - beta2
            cb, sb = math.cos(b), math.sin(b)
            ox = l6 * math.cos(t6) + d * math.cos(t5 + beta1)
            oy = l6 * math.sin(t6) + d * math.sin(t5 + beta1)
            xh = ox + cb * 0.0 - sb * y1
            yh = oy + sb * 0.0 + cb * y1
            b = t5 - beta2
            xk = xh - R * math.sin(b)
            yk = yh - R * (1.0 - math.cos(b))
            G[i] = abs(xk - x_target) + abs(yk + s)


@jit
def stable_argsort(G, order):
    """order = np.argsort(G, kind="stable") (NaN last), by insertion: the swarm has tens of
    particles, and a stable sort's permutation is unique, so the same as numpy's."""
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
def selpso_iterate(kind, c, X, V, pbest, pG, gbest, gG, rng, max_iter, w_start, w_end,
                   c1, c2, tol, v_max, clip_v, selection, hist):
    """Iterations 1..max_iter of :func:`.selpso.selpso` (unbounded); X, V, pbest, pG,
    gbest updated in place, hist[k] = gG after iteration k.  Returns (gG, k)."""
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
        fitness(kind, c, X, G)
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
            stable_argsort(G, order)
            for m in range(half):
                dst, src = order[N - half + m], order[m]
                for j in range(n):
                    X[dst, j] = X[src, j]
                    V[dst, j] = V[src, j]
        hist[it] = gG
    return gG, k


@jit
def pose_newton(c, a, b, x_target, tol, max_iter, scale, singular_rtol):
    """:func:`.newton.pose` (Eq. 7): returns (a, b, G, iterations, status, det)."""
    l6, d, b1, b2, h, R, s = c[0], c[1], c[2], c[3], c[4], c[5], c[6]
    G = math.inf
    for k in range(max_iter + 1):
        be = a - b2
        cb, sb = math.cos(be), math.sin(be)
        c51, s51 = math.cos(a + b1), math.sin(a + b1)
        c6, s6 = math.cos(b), math.sin(b)
        xk = l6 * c6 + d * c51 + h * sb - R * sb
        yk = l6 * s6 + d * s51 - h * cb - R * (1.0 - cb)
        f1, f2 = xk - x_target, yk + s
        j11, j12 = -d * s51 + (h - R) * cb, -l6 * s6
        j21, j22 = d * c51 + (h - R) * sb, l6 * c6
        G = abs(f1) + abs(f2)
        if G < tol:
            return a, b, G, k, 0, 0.0
        if not math.isfinite(G):
            return a, b, G, k, 1, 0.0
        if k == max_iter:
            break
        det = j11 * j22 - j12 * j21
        if abs(det) <= singular_rtol * scale:
            return a, b, G, k, 2, det
        a -= (f1 * j22 - f2 * j12) / det
        b -= (j11 * f2 - j21 * f1) / det
    return a, b, G, max_iter, 3, 0.0


@jit
def pose_stroke(c, x_k, a0, b0, tol, max_iter, scale, singular_rtol, out):
    """The Newton loop of :func:`.optimise.stroke_poses`: out[i] = (theta5, theta6),
    each point from the linear extrapolation of the two previous.  Returns (index of
    the first point that fails or -1, its status, G, det)."""
    ga, gb = a0, b0
    for i in range(x_k.size):
        a, b, G, k, status, det = pose_newton(c, ga, gb, x_k[i], tol, max_iter, scale,
                                              singular_rtol)
        if status != 0:
            return i, status, G, det
        out[i, 0], out[i, 1] = a, b
        if i > 0:
            ga, gb = 2 * out[i, 0] - out[i - 1, 0], 2 * out[i, 1] - out[i - 1, 1]
        else:
            ga, gb = a, b
    return -1, 0, 0.0, 0.0


@jit
def assembles_clearly(c, poses, margin):
    """True when both dyads of Eq. (9) close at every pose (theta5, theta6) with theta1..4
    inside the paper's ranges by more than ``margin`` (rad, and a relative margin on the
    squared dyad height): the decision of :func:`.optimise.check_assembly` cannot depend on
    round-off then.  False means "not clearly": the caller runs the numpy check, which
    decides (and names the cut point that fails)."""
    l1, l2, l3, l4, l5, l6, l8, l9, l10, l11 = (c[0], c[1], c[2], c[3], c[4], c[5], c[6],
                                                c[7], c[8], c[9])
    alpha, e1, e2 = c[10], c[11], c[12]
    two_pi = 2.0 * math.pi
    for i in range(poses.shape[0]):
        t5, t6 = poses[i, 0], poses[i, 1]
        dx_, dy_ = l6 * math.cos(t6), l6 * math.sin(t6)
        for k in range(2):
            if k == 0:   # A -> C, levers l1, l3
                px, py = -l10 - l9, l11
                qx = dx_ + l8 * math.cos(t5 + alpha)
                qy = dy_ + l8 * math.sin(t5 + alpha)
                rp, rq, e = l1, l3, e1
            else:        # G -> I, levers l2, l4
                px, py = -l10, l11
                qx = dx_ + l5 * math.cos(t5)
                qy = dy_ + l5 * math.sin(t5)
                rp, rq, e = l2, l4, e2
            L = math.hypot(qx - px, qy - py)
            if not L > 0.0:
                return False
            ux, uy = (qx - px) / L, (qy - py) / L
            a = (rp * rp - rq * rq + L * L) / (2.0 * L)
            h2 = rp * rp - a * a
            if not h2 > margin * rp * rp:
                return False
            hgt = math.sqrt(h2)
            xx = px + a * ux + e * hgt * uy
            xy = py + a * uy - e * hgt * ux
            # theta1 / theta2 (crank, in [pi, 2 pi]) and theta3 / theta4 (rod, in [0, pi])
            crank = math.atan2(xy - py, xx - px) % two_pi
            rod = math.atan2(xy - qy, xx - qx) % two_pi
            if not (math.pi + margin < crank < two_pi - margin):
                return False
            if not (margin < rod < math.pi - margin):
                return False
    return True


@jit
def guide_scan(c, betas, x_target, dx, dy, f):
    """:func:`.pose._guide_point_array` and |ED| - l6 over the scan grid (the same
    operations; the caller re-evaluates values near zero by the scalar path)."""
    R, h, d, beta1, beta2, s, l6 = c[0], c[1], c[2], c[3], c[4], c[5], c[6]
    for i in range(betas.size):
        b = betas[i]
        sb, cb = math.sin(b), math.cos(b)
        mx, my = x_target + R * sb, -s + R * (1.0 - cb)
        ox, oy = mx + h * -sb, my + h * cb
        t = b + beta2 + beta1
        dx[i] = ox - d * math.cos(t)
        dy[i] = oy - d * math.sin(t)
        f[i] = math.hypot(dx[i], dy[i]) - l6


@jit
def newton2_dyad(la, lb, px, py, a, b, tol, max_iter, scale, singular_rtol):
    """:func:`.newton._newton2` on one block of Eq. (9) (the dyad la, lb closing on
    (px, py)): returns (a, b, G, iterations, status, det)."""
    G = math.inf
    for k in range(max_iter + 1):
        ca, sa, cb, sb = math.cos(a), math.sin(a), math.cos(b), math.sin(b)
        f1, f2 = la * ca - lb * cb - px, la * sa - lb * sb - py
        j11, j12, j21, j22 = -la * sa, lb * sb, la * ca, -lb * cb
        G = abs(f1) + abs(f2)
        if G < tol:
            return a, b, G, k, 0, 0.0
        if not math.isfinite(G):
            return a, b, G, k, 1, 0.0
        if k == max_iter:
            break
        det = j11 * j22 - j12 * j21
        if abs(det) <= singular_rtol * scale:
            return a, b, G, k, 2, det
        a -= (f1 * j22 - f2 * j12) / det
        b -= (j11 * f2 - j21 * f1) / det
    return a, b, G, max_iter, 3, 0.0


@jit
def loops_newton(c, t1, t2, t3, t4, theta5, theta6, tol, max_iter, singular_rtol):
    """:func:`.newton.loops` (Eq. 9): the two dyads' results, each (a, b, G, iterations,
    status, det)."""
    l1, l2, l3, l4, l5, l6, l8, l9, l10, l11, alpha = (c[0], c[1], c[2], c[3], c[4], c[5],
                                                       c[6], c[7], c[8], c[9], c[10])
    c6, s6 = l6 * math.cos(theta6), l6 * math.sin(theta6)
    cx = l8 * math.cos(theta5 + alpha) + c6 + l10 + l9
    cy = l8 * math.sin(theta5 + alpha) + s6 - l11
    ix = l5 * math.cos(theta5) + c6 + l10
    iy = l5 * math.sin(theta5) + s6 - l11
    r1 = newton2_dyad(l1, l3, cx, cy, t1, t3, 0.5 * tol, max_iter, l1 * l3, singular_rtol)
    r2 = newton2_dyad(l2, l4, ix, iy, t2, t4, 0.5 * tol, max_iter, l2 * l4, singular_rtol)
    return r1, r2


@jit
def loops_stroke(c, theta, tol, max_iter, singular_rtol):
    """The Eq. (9) continuation of :func:`.stroke._newton_loops_stroke` (poses given, each
    point from the linear extrapolation of the two previous); returns the summed fitness
    (so that the work is not optimised away)."""
    g1, g2, g3, g4 = theta[0, 0], theta[0, 1], theta[0, 2], theta[0, 3]
    p1 = p2 = p3 = p4 = 0.0
    total = 0.0
    for i in range(theta.shape[0]):
        r1, r2 = loops_newton(c, g1, g2, g3, g4, theta[i, 4], theta[i, 5], tol, max_iter,
                              singular_rtol)
        x1, x2, x3, x4 = r1[0], r2[0], r1[1], r2[1]
        if i > 0:
            g1, g2, g3, g4 = 2 * x1 - p1, 2 * x2 - p2, 2 * x3 - p3, 2 * x4 - p4
        else:
            g1, g2, g3, g4 = x1, x2, x3, x4
        p1, p2, p3, p4 = x1, x2, x3, x4
        total += r1[2] + r2[2]
    return total
