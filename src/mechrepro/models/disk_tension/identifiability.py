"""What the paper's numbers pin down: a joint fit of the rolling model's free constants.

The rolled stress of Eq. (4) enters every paper number through three constants the paper
leaves free or half-stated: the stress scale c = E alpha A (only the product matters; here
relative to the handbook E = 206 GPa, alpha = 12e-6/K, A = 50 degC), the Gaussian width s
("s = 5", no unit) and the in-plane condition at the clamp (``clamped`` / ``free_disk``).
The data: Table 1's five diagonals (Eq. 9 at r_c = 65, r_f = 25 mm) and Fig. 6a's
f~(N_d = 4, r_c = 65 mm) = 502.1 Hz (Sec. 4.3; the eigen-analysis).  434.5 Hz fixes the
thickness on its own (exactly, :func:`.calibration.thickness`) and 70.0 Hz is Table 1's
N_d = 4 entry converted (row paper_70hz_is_linearised_conversion): neither adds
information.

Misfit: chi^2 = sum ((model_k - paper_k) / u_k)^2 with u_k half a unit of the last printed
digit, scaled (Birge) so that the best fit has chi^2 per degree of freedom 1: the model
cannot meet the paper to its printed digits, and the scaling turns the remaining misfit
into the uncertainty.  Profiles: the minimum of chi^2 over the other constants at each value
of one; the interval is where the profile stays within 1 of its minimum (68 %).  Which
number pins which constant: each number's share of the Fisher information about s and c at
the best fit, and the fit with and without 502.1 Hz.

Eq. (9) is linear in c, so Table 1 is computed once per (s, condition) for c = 1; the
eigen-analysis of N_d = 4 is solved on a coarse (s, c) grid; both are interpolated (cubic
splines, smooth functions) onto fine grids, on which the narrow chi^2 valley is resolved.
"""
from __future__ import annotations

import numpy as np

from . import thermal
from .modal import eigen, frequency

#: half a unit of the last printed digit of Table 1's diagonals and of 502.1 Hz
PRINTED = {"table1": np.array([0.005e5, 0.005e4, 0.005e5, 0.005e6, 0.005e6]), "f_rolled": 0.05}


def unit_table1(disk, *, s, inplane_bc, r_c, amplitude, alpha, E, nu):
    """(Table 1 diagonals for stress scale 1 [rad^2/s^2], K^(sigma) of each harmonic)."""
    kw = dict(amplitude=amplitude, r_c=r_c, s=s, r_f=disk.mesh.nodes[0], b=disk.mesh.nodes[-1],
              E=E, nu=nu, alpha=alpha, inplane_bc=inplane_bc)
    Ks = disk.stress_stiffness((lambda r: thermal.thermal_stress(r, **kw)[0],
                                lambda r: thermal.thermal_stress(r, **kw)[1]))
    return disk.eq9(Ks), Ks


def scan(disk, *, widths, scales, fine, conditions, n_d_eigen=4, **load):
    """The model on the coarse s grid: Table 1 for c = 1 [condition, s, N_d] (Eq. 9 is
    linear in c) and f~(N_d = 4) [condition, s, c] on the ``fine`` c grid, the
    eigen-analysis solved on the coarse ``scales`` and interpolated (a cubic spline of a
    smooth, monotone function; NaN beyond a buckled scale)."""
    from scipy.interpolate import CubicSpline

    unit = np.empty((len(conditions), len(widths), len(disk.n_d)))
    f4 = np.empty((len(conditions), len(widths), len(fine)))
    K, M = disk.K[n_d_eigen], disk.M[n_d_eigen]
    for a, bc in enumerate(conditions):
        for i, s in enumerate(widths):
            unit[a, i], Ks = unit_table1(disk, s=s, inplane_bc=bc, **load)
            w2 = np.array([eigen(K + c * Ks[n_d_eigen], M, 1, 3)[0][0] for c in scales])
            ok = w2 > 0
            f = CubicSpline(scales[ok], frequency(w2[ok]))(fine)
            f4[a, i] = np.where(fine <= scales[ok].max(), f, np.nan)
    return unit, f4


class FineModel:
    """The model between the coarse s points: cubic splines along s of Table 1 (c = 1) and
    of f~ (both smooth in s), so that the chi^2 valley -- narrower than the coarse step --
    is resolved on ``fine_widths``."""

    def __init__(self, widths, unit, f4, fine):
        from scipy.interpolate import CubicSpline

        self.fine, self.widths = fine, np.asarray(widths)
        self._nan = ~np.isfinite(f4)   # buckled: no f~ there, nor between it and its neighbours
        self._t = CubicSpline(widths, unit, axis=1)
        self._f = CubicSpline(widths, np.where(self._nan, 0.0, f4), axis=1)

    def __call__(self, w):
        """(Table 1 [condition, len(w), c, N_d], f~ [condition, len(w), c])."""
        w = np.atleast_1d(w)
        t1 = self._t(w)[:, :, None, :] * self.fine[None, None, :, None]
        j = np.clip(np.searchsorted(self.widths, w), 1, len(self.widths) - 1)
        bad = self._nan[:, j - 1] | self._nan[:, j]
        return t1, np.where(bad, np.nan, self._f(w))


def chi2_terms(t1, f4, table1_paper, f_rolled_paper):
    """Squared normalised residuals [..., 6]: Table 1 N_d = 0..4, then f~(N_d = 4)."""
    r = (t1 - table1_paper) / PRINTED["table1"]
    rf = (f4 - f_rolled_paper) / PRINTED["f_rolled"]
    return np.concatenate([r**2, rf[..., None] ** 2], axis=-1)


def interval(values, prof, level=1.0):
    """(best, lo, hi) of a profile: argmin and the range where prof <= min + level (grid
    resolution; an end of the grid means the data do not bound it there)."""
    k = int(np.nanargmin(prof))
    ok = np.nonzero(prof <= prof[k] + level)[0]
    return float(values[k]), float(values[ok.min()]), float(values[ok.max()])


CONDITIONS = ("clamped", "free_disk")
DATA = ["Table 1 N_d=0", "Table 1 N_d=1", "Table 1 N_d=2", "Table 1 N_d=3", "Table 1 N_d=4",
        "f~ 502.1 Hz"]


#: the data subsets fitted: Table 1 with Fig. 6a's 502.1 Hz, and Table 1 alone
SUBSETS = {"table1_and_f_rolled": [0, 1, 2, 3, 4, 5], "table1": [0, 1, 2, 3, 4]}


def _profiles(fm, fine_widths, table1_paper, f_rolled_paper, uses, chunk=64):
    """Raw chi^2 profiles over s, c and the condition, and the best point (a, i, k), over
    the fine grid, one (pw, pc, pa, at) per data subset of ``uses`` (evaluated in chunks of
    s; the model and its residuals once per chunk for all subsets)."""
    nc = len(fm.fine)
    out = [[np.full(len(fine_widths), np.inf), np.full(nc, np.inf), np.full(2, np.inf),
            np.inf, None] for _ in uses]
    for i0 in range(0, len(fine_widths), chunk):
        t1, f4 = fm(fine_widths[i0:i0 + chunk])
        all_terms = chi2_terms(t1, f4, table1_paper, f_rolled_paper)
        for use, o in zip(uses, out):
            terms = all_terms[..., use]
            raw = np.where(np.all(np.isfinite(terms), axis=-1), terms.sum(axis=-1), np.inf)
            o[0][i0:i0 + chunk] = raw.min(axis=(0, 2))
            o[1] = np.minimum(o[1], raw.min(axis=(0, 1)))
            o[2] = np.minimum(o[2], raw.min(axis=(1, 2)))
            if raw.min() < o[3]:
                o[3] = float(raw.min())
                a, i, k = np.unravel_index(int(np.argmin(raw)), raw.shape)
                o[4] = (int(a), i0 + int(i), int(k))
    return [(pw, pc, pa, at) for pw, pc, pa, _, at in out]


def analyse(disk, *, widths, scales, fine, fine_widths, single_width, table1_paper,
            f_rolled_paper, **load):
    """The joint fit of (c, s, in-plane condition) to each data subset (:data:`SUBSETS`) and
    the single-alpha reading (s = ``single_width``, free_disk, c on Table 1's N_d = 4 entry
    alone), as arrays: Birge-scaled profiles over s, c and the condition, the best point, its
    Table 1 relative errors and f~, Fisher shares, Birge factors."""
    unit, f4 = scan(disk, widths=widths, scales=scales, fine=fine, conditions=CONDITIONS, **load)
    fm = FineModel(widths, unit, f4, fine)
    u = np.r_[PRINTED["table1"], PRINTED["f_rolled"]]
    # the single-alpha reading, solved directly (not on the grid)
    u1, Ks = unit_table1(disk, s=single_width, inplane_bc="free_disk", **load)
    c1 = table1_paper[4] / u1[4]
    f1 = frequency(eigen(disk.K[4] + c1 * Ks[4], disk.M[4], 1, 3)[0][0])
    single_terms = chi2_terms(c1 * u1, np.asarray(f1), table1_paper, f_rolled_paper)
    out = {k: [] for k in ("prof_width", "prof_scale", "prof_condition", "birge", "best_width",
                           "best_scale", "best_condition", "best_table1_rel", "best_f_rolled",
                           "shares", "single_chi2", "chi2_min")}
    profiles = _profiles(fm, fine_widths, table1_paper, f_rolled_paper, list(SUBSETS.values()))
    for use, (pw, pc, pa, (a, i, k)) in zip(SUBSETS.values(), profiles):
        dof = max(len(use) - 3, 1)
        birge = max(float(pw.min()) / dof, 1.0)
        out["prof_width"].append(pw / birge)
        out["prof_scale"].append(pc / birge)
        out["prof_condition"].append(pa / birge)
        out["birge"].append(birge)
        out["chi2_min"].append(float(pw.min()) / birge)
        w = fine_widths[i]
        t1, f4b = fm(w)
        out["best_width"].append(w)
        out["best_scale"].append(fine[k])
        out["best_condition"].append(a)
        out["best_table1_rel"].append(t1[a, 0, k] / table1_paper - 1)
        out["best_f_rolled"].append(f4b[a, 0, k])
        # Fisher shares at the best point: derivatives along s and c on the fine grids
        lo, hi = fine_widths[max(i - 1, 0)], fine_widths[min(i + 1, len(fine_widths) - 1)]
        (tl, fl), (th, fh) = fm(lo), fm(hi)
        d_s = (np.r_[th[a, 0, k], fh[a, 0, k]] - np.r_[tl[a, 0, k], fl[a, 0, k]]) / (hi - lo)
        k0, k1 = max(k - 1, 0), min(k + 1, len(fine) - 1)
        d_c = (np.r_[t1[a, 0, k1], f4b[a, 0, k1]] - np.r_[t1[a, 0, k0], f4b[a, 0, k0]]) \
            / (fine[k1] - fine[k0])
        sh = np.zeros((2, len(u)))
        for row, d in enumerate((d_s, d_c)):
            info = (d[use] / u[use]) ** 2
            sh[row, use] = info / info.sum()
        out["shares"].append(sh)
        out["single_chi2"].append(float(np.sum(single_terms[use]) / birge))
    out = {k: np.array(v) for k, v in out.items()}
    out.update(single_scale=c1, single_table1_rel=c1 * u1 / table1_paper - 1, single_f_rolled=f1)
    return out


def table(ds, prefix="axisym_") -> list[list]:
    """Rows of ``identifiability.csv`` from a run of effect ``identifiability``: per data
    subset and constant [data, constant, unit, best, lo, hi, pinned by], then the two readings
    [data, reading, condition, s, c, Table 1 relative errors, f~, chi^2]."""
    g = lambda k: ds[prefix + k if prefix + k in ds else k].values  # noqa: E731
    widths, fine = g("scan_width") * 1e3, g("scan_scale")
    rows = []
    for j, name in enumerate(SUBSETS):
        for const, prof, grid, unit, sh in (("gaussian_width", g("prof_width")[j], widths, "mm",
                                             g("shares")[j, 0]),
                                            ("stress_scale", g("prof_scale")[j], fine,
                                             "x handbook E alpha A", g("shares")[j, 1])):
            best, lo, hi = interval(grid, prof)
            top = np.argsort(sh)[::-1][:2]
            edge = " (open: the scan's end)" if hi >= grid.max() or lo <= grid.min() else ""
            rows.append([name, const, unit, f"{best:.3g}", f"{lo:.3g}", f"{hi:.3g}{edge}",
                         "; ".join(f"{DATA[t]} {sh[t]:.0%}" for t in top)])
        pc = g("prof_condition")[j]
        a = int(np.nanargmin(pc))
        rows.append([name, "inplane_bc", "1", CONDITIONS[a], "", "",
                     f"chi^2 to {CONDITIONS[1 - a]} +{pc[1 - a] - pc[a]:.1f}"])
    return rows


def readings(ds, prefix="axisym_") -> list[list]:
    """[data, reading, condition, s mm, c, Table 1 N_d=0..4 relative errors, f~ Hz, chi^2 -
    chi^2_min] of the joint fit and of the single-alpha calibration, per data subset."""
    g = lambda k: ds[prefix + k if prefix + k in ds else k].values  # noqa: E731
    out = []
    for j, name in enumerate(SUBSETS):
        out.append([name, "joint fit", CONDITIONS[int(g("best_condition")[j])],
                    float(g("best_width")[j]) * 1e3, float(g("best_scale")[j]),
                    *[float(x) for x in g("best_table1_rel")[j]], float(g("best_f_rolled")[j]),
                    0.0])
        out.append([name, "single-alpha calibration", "free_disk",
                    float(g("single_width")) * 1e3,
                    float(g("single_scale")), *[float(x) for x in g("single_table1_rel")],
                    float(g("single_f_rolled")),
                    float(g("single_chi2")[j] - g("chi2_min")[j])])
    return out
