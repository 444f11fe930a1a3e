"""What the paper's numbers pin down: a joint fit of the rolling model's free constants.

Three constants enter every paper number through Eq. (4)'s stress: the stress scale
c = E alpha A (relative to the handbook steel at A = 50 degC), the Gaussian width s ("s = 5",
no unit) and the in-plane condition.  The data: Table 1's five diagonals (Eq. 9 at r_c = 65,
r_f = 25 mm) and Fig. 6a's f~(N_d = 4) = 502.1 Hz.  chi^2 takes half a unit of the last
printed digit as each number's uncertainty, Birge-scaled to chi^2 per degree of freedom 1;
the joint (s, c) regions are chi^2 within 2.30 (68 %) and 6.18 (95 %) of the minimum.  Table 1
pins mainly c s: the valley floor is stored along each profile, its direction at the best fit
is the soft axis of the chi^2 Hessian, and each number's share of the Fisher information says
which pins which.  Eq. (9) is linear in c; the N_d = 4 eigenvalue is splined from a coarse
(s, c) grid; profiles are minimised on a fine grid, then continuously (golden section).
"""
from __future__ import annotations

import numpy as np

from . import thermal
from .modal import eigen, frequency, positive_definite

#: half a unit of the last printed digit of Table 1's diagonals and of 502.1 Hz
PRINTED = {"table1": np.array([0.005e5, 0.005e4, 0.005e5, 0.005e6, 0.005e6]), "f_rolled": 0.05}


def unit_table1(disk, *, s, inplane_bc, r_c, amplitude, alpha, E, nu):
    """(Table 1 diagonals for stress scale 1 [rad^2/s^2], K^(sigma) of each harmonic)."""
    Ks = disk.stress_stiffness(thermal.field(amplitude=amplitude, r_c=r_c, s=s,
                                             r_f=disk.mesh.nodes[0], b=disk.mesh.nodes[-1],
                                             E=E, nu=nu, alpha=alpha, inplane_bc=inplane_bc))
    return disk.eq9(Ks), Ks


def _lowest_stable(K, M):
    """omega^2 of the lowest mode of (K, M), None when K has buckled."""
    return float(eigen(K, M, 1, 3)[0][0]) if positive_definite(K) else None


def scan(disk, *, widths, scales, fine, conditions, n_d_eigen=4, **load):
    """Table 1 for c = 1 and omega~^2(N_d = 4) on the fine c grid (NaN: buckled)."""
    from scipy.interpolate import CubicSpline

    unit = np.empty((len(conditions), len(widths), len(disk.n_d)))
    w2 = np.full((len(conditions), len(widths), len(fine)), np.nan)
    K, M = disk.K[n_d_eigen], disk.M[n_d_eigen]
    for a, bc in enumerate(conditions):
        for i, s in enumerate(widths):
            unit[a, i], Ks = unit_table1(disk, s=s, inplane_bc=bc, **load)
            coarse = []
            for c in scales:
                v = _lowest_stable(K + c * Ks[n_d_eigen], M)
                if v is None or v <= 0:
                    break
                coarse.append(v)
            m = len(coarse)
            if m >= 2:
                inside = fine <= scales[m - 1]
                w2[a, i, inside] = CubicSpline(scales[:m], coarse)(fine[inside])
    return unit, w2


class FineModel:
    """The model between the coarse s points: splines along s of Table 1 and omega~^2."""

    def __init__(self, widths, unit, w2, fine):
        from scipy.interpolate import CubicSpline

        self.fine, self.widths = np.asarray(fine, float), np.asarray(widths, float)
        self._nan = ~np.isfinite(w2)   # buckled: no f~ there, nor between it and its neighbours
        self._t = CubicSpline(self.widths, unit, axis=1)
        self._w = CubicSpline(self.widths, np.where(self._nan, 0.0, w2), axis=1)
        self._dc = (self.fine[-1] - self.fine[0]) / (len(self.fine) - 1)   # uniform c grid

    def _interval(self, w):
        return np.clip(np.searchsorted(self.widths, w, side="right") - 1, 0,
                       len(self.widths) - 2)

    def __call__(self, w):
        """(Table 1 [condition, len(w), c, N_d], f~ [condition, len(w), c])."""
        w = np.atleast_1d(w)
        t1 = self._t(w)[:, :, None, :] * self.fine[None, None, :, None]
        j = self._interval(w)
        bad = self._nan[:, j] | self._nan[:, j + 1]
        return t1, np.where(bad, np.nan, frequency(self._w(w)))

    def at(self, w, a, c):
        """(Table 1 [N, N_d], f~ [N]) at the points (s = w, condition a, stress scale c):
        Table 1 linear in c; f~ from the along-s splines of the four fine-c columns around c
        (cubic Lagrange in c, exact at a column)."""
        w, a, c = (x.ravel() for x in np.broadcast_arrays(np.asarray(w, float),
                                                          np.asarray(a, int),
                                                          np.asarray(c, float)))
        t1 = self._t(w)[a, np.arange(w.size)] * c[:, None]
        j = self._interval(w)
        dx = w - self.widths[j]
        u = (c - self.fine[0]) / self._dc
        k0 = np.clip(np.floor(u).astype(int) - 1, 0, len(self.fine) - 4)
        t = u - k0
        w2 = np.zeros(w.size)
        bad = np.zeros(w.size, bool)
        for m in range(4):
            k = k0 + m
            coef = self._w.c[:, j, a, k]
            val = ((coef[0] * dx + coef[1]) * dx + coef[2]) * dx + coef[3]
            weight = np.prod([(t - q) / (m - q) for q in range(4) if q != m], axis=0)
            w2 += weight * val
            bad |= self._nan[a, j, k] | self._nan[a, j + 1, k]
        return t1, np.where(bad, np.nan, frequency(w2))


def chi2_terms(t1, f4, table1_paper, f_rolled_paper):
    """Squared normalised residuals [..., 6]: Table 1 N_d = 0..4, then f~(N_d = 4)."""
    r = (t1 - table1_paper) / PRINTED["table1"]
    rf = (f4 - f_rolled_paper) / PRINTED["f_rolled"]
    return np.concatenate([r**2, rf[..., None] ** 2], axis=-1)


def _chi2(terms, use):
    """chi^2 of the data ``use`` (inf where a used term does not exist: buckled)."""
    terms = terms[..., use]
    return np.where(np.all(np.isfinite(terms), axis=-1), terms.sum(axis=-1), np.inf)


#: Delta chi^2 of the joint (s, c) regions: 68 / 95 % of chi^2 with two degrees of freedom
#: (the profile intervals at these levels are the regions' extents)
LEVELS = {"68": 2.30, "95": 6.18}


def interval(values, prof, level=1.0, floor=None):
    """(best, lo, hi) of a profile: where prof <= min + level, ends interpolated."""
    k = int(np.nanargmin(prof))
    top = (prof[k] if floor is None else min(floor, prof[k])) + level
    ok = np.nonzero(prof <= top)[0]
    lo_i, hi_i = int(ok.min()), int(ok.max())

    def cross(i, o):   # between the inside point i and the outside point o
        y0, y1 = prof[i], prof[o]
        if not np.isfinite(y1) or y1 == y0:
            return float(values[i])
        return float(values[i] + (values[o] - values[i]) * (top - y0) / (y1 - y0))
    lo = float(values[0]) if lo_i == 0 else cross(lo_i, lo_i - 1)
    hi = float(values[-1]) if hi_i == len(values) - 1 else cross(hi_i, hi_i + 1)
    return float(values[k]), lo, hi


CONDITIONS = ("clamped", "free_disk")
DATA = [f"Table 1 N_d={n}" for n in range(5)] + ["f~ 502.1 Hz"]


#: the data subsets fitted: Table 1 with Fig. 6a's 502.1 Hz, and Table 1 alone
SUBSETS = {"table1_and_f_rolled": [0, 1, 2, 3, 4, 5], "table1": [0, 1, 2, 3, 4]}


def _golden(f, lo, hi, iters=40):
    """Elementwise minimum of ``f`` over [lo, hi] (unimodal there): (x, f(x))."""
    g = (np.sqrt(5.0) - 1.0) / 2.0
    a, b = np.asarray(lo, float).copy(), np.asarray(hi, float).copy()
    x1, x2 = b - g * (b - a), a + g * (b - a)
    f1, f2 = f(x1), f(x2)
    for _ in range(iters):
        left = f1 <= f2                       # the minimum is in [a, x2]
        a, b = np.where(left, a, x1), np.where(left, x2, b)
        xn = np.where(left, b - g * (b - a), a + g * (b - a))
        fn = f(xn)
        x1, x2, f1, f2 = (np.where(left, xn, x2), np.where(left, x1, xn),
                          np.where(left, fn, f2), np.where(left, f1, fn))
    first = f1 <= f2
    return np.where(first, x1, x2), np.where(first, f1, f2)


def _refine(f, grid, k, at_k):
    """(x, f(x)) minimising ``f`` between the ``grid`` neighbours of each grid minimum ``k``
    (where ``f`` is ``at_k``), the grid point where the continuous minimum is no lower."""
    x, fx = _golden(f, grid[np.maximum(k - 1, 0)], grid[np.minimum(k + 1, len(grid) - 1)])
    keep = at_k <= fx
    return np.where(keep, grid[k], x), np.where(keep, at_k, fx)


def _profiles(fm, fine_widths, table1_paper, f_rolled_paper, uses, chunk=64):
    """Raw chi^2 profiles over s and c per condition and the other constant's minimiser
    along each (the valley floor), one dict per data subset of ``uses``: on the fine grid,
    then each point minimised continuously between its grid neighbours."""
    nw, nc, na = len(fine_widths), len(fm.fine), len(CONDITIONS)
    grid = [{"ps": np.full((na, nw), np.inf), "ks": np.zeros((na, nw), int),
             "pc": np.full((na, nc), np.inf), "is": np.zeros((na, nc), int)} for _ in uses]
    for i0 in range(0, nw, chunk):
        t1, f4 = fm(fine_widths[i0:i0 + chunk])
        terms = chi2_terms(t1, f4, table1_paper, f_rolled_paper)
        for use, g in zip(uses, grid):
            raw = _chi2(terms, use)                          # [condition, s, c]
            g["ps"][:, i0:i0 + chunk] = raw.min(axis=2)
            g["ks"][:, i0:i0 + chunk] = raw.argmin(axis=2)
            m, am = raw.min(axis=1), raw.argmin(axis=1) + i0
            better = m < g["pc"]
            g["pc"] = np.where(better, m, g["pc"])
            g["is"] = np.where(better, am, g["is"])
    out = []
    conds = np.arange(na)[:, None]
    for use, g in zip(uses, grid):
        def chi2_at(w, a, c, use=use):
            t1, f4 = fm.at(w, a, c)
            return _chi2(chi2_terms(t1, f4, table1_paper, f_rolled_paper), use)

        # s profile: c between the grid neighbours of the grid minimum at each (condition, s)
        W, A = np.broadcast_arrays(fine_widths[None, :], conds)
        c_s, p_s = _refine(lambda c: chi2_at(W, A, c).reshape(c.shape), fm.fine, g["ks"], g["ps"])
        # c profile: s between the grid neighbours of the grid minimum at each (condition, c)
        C, A = np.broadcast_arrays(fm.fine[None, :], conds)
        s_c, p_c = _refine(lambda w: chi2_at(w, A, C).reshape(w.shape), fine_widths, g["is"],
                           g["pc"])
        # the best point: polished from the best profile point (Nelder-Mead in grid units)
        a = int(np.argmin(p_s.min(axis=1)))
        ib = int(np.argmin(p_s[a]))
        best = _polish(chi2_at, a, fine_widths, fm.fine, fine_widths[ib], c_s[a, ib], p_s[a, ib])
        ca, wa = p_s.argmin(axis=0), p_c.argmin(axis=0)
        out.append({"prof_width": p_s.min(axis=0), "prof_condition": p_s.min(axis=1),
                    "prof_scale": p_c.min(axis=0),
                    "prof_width_scale": c_s[ca, np.arange(nw)],
                    "prof_scale_width": s_c[wa, np.arange(nc)],
                    "floor": (c_s, p_s), "chi2_at": chi2_at, "best": (a, *best)})
    return out


def _polish(chi2_at, a, widths, scales, s0, c0, f0):
    """(s, c, chi^2) polished by Nelder-Mead from (s0, c0) in the scan box."""
    from scipy.optimize import minimize

    ds, dc = widths[1] - widths[0], scales[1] - scales[0]

    def fun(x):
        s, c = x[0] * ds, x[1] * dc
        if not (widths[0] <= s <= widths[-1] and scales[0] <= c <= scales[-1]):
            return np.inf
        return float(chi2_at(np.array([s]), np.array([a]), np.array([c]))[0])

    x0 = np.array([s0 / ds, c0 / dc])
    r = minimize(fun, x0, method="Nelder-Mead",
                 options={"xatol": 1e-6, "fatol": 1e-10, "maxiter": 2000,
                          "initial_simplex": x0 + np.array([[0, 0], [0.5, 0], [0, 0.5]])})
    if r.fun < f0:
        return float(r.x[0] * ds), float(r.x[1] * dc), float(r.fun)
    return float(s0), float(c0), float(f0)


def region(chi2_at, widths, floor, top, c_scan, iters=48):
    """The region chi^2(s, c) <= top as c limits (c_lo, c_hi) [level, condition, s] (NaN where
    the ``floor`` (c*, chi^2(c*)) lies above), each bisected between c* and the scan end."""
    c_star, p_star = floor
    top = np.asarray(top, float)[:, None, None]
    A = np.arange(c_star.shape[0])[None, :, None]
    L, A, W, C = np.broadcast_arrays(top, A, widths[None, None, :], c_star[None])
    f = lambda c: chi2_at(W, A, c).reshape(c.shape)                        # noqa: E731
    ends = []
    for edge in c_scan:
        inside, outside = C.copy(), np.full(C.shape, float(edge))
        at_edge = f(outside) <= L
        for _ in range(iters):
            mid = 0.5 * (inside + outside)
            ok = f(mid) <= L
            inside, outside = np.where(ok, mid, inside), np.where(ok, outside, mid)
        ends.append(np.where(at_edge, float(edge), inside))
    step = 1e-6 * abs(c_scan[1] - c_scan[0])
    out = [np.where(C <= c_scan[0] + step, float(c_scan[0]),
                    np.where(C >= c_scan[1] - step, float(c_scan[1]), np.nan))] * 2
    empty = ~(p_star[None] <= L)
    return tuple(np.where(empty, o, e) for o, e in zip(out, ends))


def direction(chi2_at, a, s, c, scale=1.0, h=1e-3):
    """The degenerate direction at the best fit from the Hessian of chi^2 / ``scale`` in
    (ln s, ln c): (d ln c / d ln s along its soft axis, the 68 % half-lengths along the soft
    and the stiff axis); a slope of -1 is c s = const."""
    def f(x, y):
        return float(chi2_at(np.array([s * np.exp(x)]), np.array([a]),
                             np.array([c * np.exp(y)]))[0]) / scale
    f0 = f(0, 0)
    hxx = (f(h, 0) - 2 * f0 + f(-h, 0)) / h**2
    hyy = (f(0, h) - 2 * f0 + f(0, -h)) / h**2
    hxy = (f(h, h) - f(h, -h) - f(-h, h) + f(-h, -h)) / (4 * h**2)
    lam, vec = np.linalg.eigh(np.array([[hxx, hxy], [hxy, hyy]]))
    soft = vec[:, 0]
    return float(soft[1] / soft[0]), np.sqrt(LEVELS["68"] / np.maximum(lam, 1e-300))


def analyse(disk, *, widths, scales, fine, fine_widths, single_width, table1_paper,
            f_rolled_paper, **load):
    """The joint fit of (c, s, in-plane condition) to each data subset (:data:`SUBSETS`)
    and the single-alpha reading (s = ``single_width``, free_disk, c on Table 1's N_d = 4
    entry), as the arrays of output ``identifiability``; ``fine`` must be uniform."""
    unit, w2 = scan(disk, widths=widths, scales=scales, fine=fine, conditions=CONDITIONS, **load)
    fm = FineModel(widths, unit, w2, fine)
    u = np.r_[PRINTED["table1"], PRINTED["f_rolled"]]
    # the single-alpha reading, solved directly (not on the grid)
    u1, Ks = unit_table1(disk, s=single_width, inplane_bc="free_disk", **load)
    c1 = table1_paper[4] / u1[4]
    f1 = frequency(eigen(disk.K[4] + c1 * Ks[4], disk.M[4], 1, 3)[0][0])
    single_terms = chi2_terms(c1 * u1, np.asarray(f1), table1_paper, f_rolled_paper)
    rows = []
    profiles = _profiles(fm, fine_widths, table1_paper, f_rolled_paper, list(SUBSETS.values()))
    for use, pr in zip(SUBSETS.values(), profiles):
        a, w, c, chi2 = pr["best"]
        birge = max(chi2 / max(len(use) - 3, 1), 1.0)
        lo, hi = region(pr["chi2_at"], fine_widths, pr["floor"],
                        [chi2 + level * birge for level in LEVELS.values()],
                        np.asarray(fine)[[0, -1]])
        slope, half = direction(pr["chi2_at"], a, w, c, birge)
        t1, f4 = fm.at(w, a, c)
        # Fisher shares at the best point: central differences along s and c
        hs, hc = 1e-3 * (fine_widths[1] - fine_widths[0]), 1e-3 * (fine[1] - fine[0])
        sh = np.zeros((2, len(u)))
        for row, (ds, dc) in enumerate(((hs, 0.0), (0.0, hc))):
            (tl, fl), (th, fh) = fm.at(w - ds, a, c - dc), fm.at(w + ds, a, c + dc)
            d = (np.r_[th[0], fh] - np.r_[tl[0], fl]) / (2 * (ds + dc))
            info = (d[use] / u[use]) ** 2
            sh[row, use] = info / info.sum()
        rows.append({**{k: pr[k] / birge for k in ("prof_width", "prof_scale", "prof_condition")},
                     "prof_width_scale": pr["prof_width_scale"],
                     "prof_scale_width": pr["prof_scale_width"], "birge": birge,
                     "chi2_min": chi2 / birge, "region_c_lo": lo, "region_c_hi": hi,
                     "direction_slope": slope, "direction_halfwidth": half, "best_width": w,
                     "best_scale": c, "best_condition": a,
                     "best_table1_rel": t1[0] / table1_paper - 1, "best_f_rolled": f4[0],
                     "shares": sh, "single_chi2": float(np.sum(single_terms[use]) / birge)})
    out = {k: np.array([r[k] for r in rows]) for k in rows[0]}
    out.update(single_scale=c1, single_table1_rel=c1 * u1 / table1_paper - 1, single_f_rolled=f1)
    return out


def _bound(end, grid, other, other_grid, name, other_name, unit) -> str:
    """What bounds an extent's end if not the data (a scan's end); '' where the data do."""
    step = abs(grid[1] - grid[0])
    if end <= grid.min() + 1e-9 * step or end >= grid.max() - 1e-9 * step:
        return f"{name} scan {'start' if end <= grid.min() + step else 'end'} {end:g}{unit}"
    k = int(np.clip(np.searchsorted(grid, end), 1, len(grid) - 1))
    o = other[k - 1:k + 1]                    # the grid points either side of the end
    ostep = abs(other_grid[1] - other_grid[0])
    for edge, which in ((other_grid.min(), "start"), (other_grid.max(), "end")):
        if np.any(abs(o - edge) <= ostep):
            return f"{other_name} scan {which} {edge:g}{' mm' if other_name == 's' else ''}"
    return ""


def table(ds) -> list[list]:
    """Rows of ``identifiability.csv``: per data subset and constant the best fit, the
    extents of the joint (s, c) region at 68 and 95 % with what bounds them and which numbers
    pin it; c s along the valley floor; the degenerate direction; the in-plane condition."""
    g = lambda k: ds[k].values  # noqa: E731
    widths, fine = g("scan_width") * 1e3, g("scan_scale")
    rows = []
    for j, name in enumerate(SUBSETS):
        base = float(g("chi2_min")[j])
        floors = {"gaussian_width": g("prof_width_scale")[j],
                  "stress_scale": g("prof_scale_width")[j] * 1e3}
        ext = {}
        for const, prof, grid, unit, sh, other_grid, names in (
                ("gaussian_width", g("prof_width")[j], widths, "mm", g("shares")[j, 0], fine,
                 ("s", "c", " mm")),
                ("stress_scale", g("prof_scale")[j], fine, "x handbook E alpha A",
                 g("shares")[j, 1], widths, ("c", "s", ""))):
            ends, flags = [], []
            for level in LEVELS.values():
                _, lo, hi = interval(grid, prof, level, floor=base)
                ends += [f"{lo:.3g}", f"{hi:.3g}"]
                why = [f"{side}: {b}" for side, e in (("lo", lo), ("hi", hi))
                       if (b := _bound(e, grid, floors[const], other_grid, *names))]
                flags.append("; ".join(why))
                ext[const, level] = (lo, hi)
            top = np.argsort(sh)[::-1][:2]
            best = (float(g("best_width")[j]) * 1e3 if const == "gaussian_width"
                    else float(g("best_scale")[j]))
            rows.append([name, const, unit, f"{best:.3g}", *ends, *flags,
                         "; ".join(f"{DATA[t]} {sh[t]:.0%}" for t in top)])
        # c s along the valley floor (the c that minimises chi^2 at each s) inside each extent
        c_floor = floors["gaussian_width"]
        cells, flags, k95 = [], [], None
        for level in LEVELS.values():
            lo, hi = ext["gaussian_width", level]
            inside = (widths >= lo) & (widths <= hi)
            cs = widths[inside] * c_floor[inside]
            cells += [f"{cs.min():.3g}", f"{cs.max():.3g}"]
            flags.append("lo: s scan start" if lo <= widths.min() else "")
            k95 = np.polyfit(np.log(widths[inside]), np.log(c_floor[inside]), 1)[0]
        rows.append([name, "stress_scale_x_width", "mm (c s along the valley floor)",
                     f"{float(g('best_width')[j]) * 1e3 * float(g('best_scale')[j]):.3g}",
                     *cells, *flags, "the product Table 1 fixes: the extents of s and c above "
                     "are mostly motion along it"])
        slope = float(g("direction_slope")[j])
        soft, stiff = g("direction_halfwidth")[j]
        rows.append([name, "degenerate_direction", "d ln c / d ln s", f"{slope:.3g}",
                     "", "", "", "", "", "",
                     f"soft axis of the chi^2 Hessian at the best fit: c ~ s^{slope:.2f}, 68 % "
                     f"half-lengths x/ {np.exp(soft):.3g} along it and +-{stiff:.2%} across "
                     f"(ratio {soft / stiff:.0f}); the valley floor over the 95 % extent of s: "
                     f"c ~ s^{k95:.2f} (c s = const: -1)"])
        pc = g("prof_condition")[j]
        a = int(np.nanargmin(pc))
        rows.append([name, "inplane_bc", "1", CONDITIONS[a], "", "", "", "", "", "",
                     f"chi^2 to {CONDITIONS[1 - a]} +{pc[1 - a] - pc[a]:.1f}"])
    return rows


COLUMNS = ["data", "constant", "unit", "best", "lo_68", "hi_68", "lo_95", "hi_95",
           "bounded_68", "bounded_95", "pinned_by"]
READING_COLUMNS = (["data", "reading", "inplane_bc", "s_mm", "stress_scale"]
                   + [f"table1_nd{n}_rel" for n in range(5)] + ["f_rolled_hz", "delta_chi2"])


def readings(ds) -> list[list]:
    """Rows of the joint fit and of the single-alpha calibration, per data subset."""
    g = lambda k: ds[k].values  # noqa: E731
    out = []
    for j, name in enumerate(SUBSETS):
        out.append([name, "joint fit", CONDITIONS[int(g("best_condition")[j])],
                    float(g("best_width")[j]) * 1e3, float(g("best_scale")[j]),
                    *map(float, g("best_table1_rel")[j]), float(g("best_f_rolled")[j]), 0.0])
        out.append([name, "single-alpha calibration", "free_disk", float(g("single_width")) * 1e3,
                    float(g("single_scale")), *map(float, g("single_table1_rel")),
                    float(g("single_f_rolled")), float(g("single_chi2")[j] - g("chi2_min")[j])])
    return out


def fit_table(R) -> tuple[list, list]:
    """Table ``identifiability``: :func:`table` of run ``identifiability``."""
    return COLUMNS, table(R.run("identifiability"))


def readings_table(R) -> tuple[list, list]:
    """Table ``identifiability_readings``: :func:`readings` of run ``identifiability``."""
    return READING_COLUMNS, readings(R.run("identifiability"))
