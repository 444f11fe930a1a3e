"""disk_tension: what the paper's numbers pin down (effect identifiability), as it is (issue
61): Table 1 fixes the product c s of the stress scale and the band width, so the c scan must
reach the valley at the s scan's lower end; the joint (s, c) regions are the chi^2 surface
about the joint fit, and a region cut by a scan's end says which scan cuts it; the profiles are minima over a continuous constant, not over a grid (the
grid minimum made the c profile jagged)."""
import copy

import numpy as np
import pytest

from mechrepro.config import load_paper
from mechrepro.inputs import read_yaml
from mechrepro.models.disk_tension import calibration, identifiability as idf
from mechrepro.models.disk_tension.axisym import AxisymDisk
from mechrepro.solve import _solve_once

CFG = "config/papers/disk_tension.yaml"
E, NU, RHO, B = 206e9, 0.3, 7850.0, 0.1275


@pytest.fixture(scope="module")
def small():
    """The identifiability scene on a coarse scan (1 mm, 0.25 x; 32 elements): ~2 s."""
    run = copy.deepcopy(load_paper(CFG, "ci").runs["identifiability"])
    run["resolution"] = {"n_elements": 32}
    run["options"] = {"timing_min_s": 0.0}
    run["parameters"].update(scan_gaussian_width=[0.001, 0.020, 0.001],
                             scan_stress_scale=[0.25, 8.0, 0.25])
    return _solve_once(run)


def test_the_c_scan_reaches_the_valley_at_the_s_scans_lower_end():
    """At the s scan's lower end Table 1's N_d = 4 entry needs c ~ 6.4 (c s ~ const): a c
    scan that stops below (it stopped at 2.4) draws its own end as a wall in the s profile."""
    p = read_yaml(CFG)["parameters"]
    s0 = p["scan_gaussian_width"]["value"][0] * 1e-3
    c_top = p["scan_stress_scale"]["value"][1]
    h = calibration.thickness(f_target=434.5, n_d=4, r_f=0.025, b=B, E=E, nu=NU, rho=RHO)
    d = AxisymDisk(r_f=0.025, b=B, h=h, E=E, nu=NU, rho=RHO, n_d=range(5), n_elements=32)
    d.unrolled()
    load = dict(r_c=0.065, amplitude=50.0, alpha=12e-6, E=E, nu=NU)
    for bc in idf.CONDITIONS:
        unit = idf.unit_table1(d, s=s0, inplane_bc=bc, **load)[0]
        needed = p["calibration_delta_omega2"]["value"] / unit[4]
        assert 5 < needed and needed * 1.2 < c_top, (bc, needed, c_top)


def _rows(ds):
    return {(r[0], r[1]): dict(zip(idf.COLUMNS, r)) for r in idf.table(ds)}


def test_region_ends_say_which_scan_bounds_them(small):
    """Table 1 alone: the 95 % region reaches the s scan's start (1 mm) and is flagged there,
    and the upper end of c is set by that same end (the region's largest c lies at s = 1 mm),
    not by the data; the 68 % region closes inside both scans.  The direction Table 1 fixes,
    c s, is named with its range, and the degenerate direction is the Hessian's soft axis,
    close to c s = const (slope -1)."""
    rows = _rows(small)
    s, c = rows[("table1", "gaussian_width")], rows[("table1", "stress_scale")]
    assert float(s["lo_95"]) == 1 and s["bounded_95"] == "lo: s scan start 1 mm"
    assert c["bounded_95"] == "hi: s scan start 1 mm"
    assert s["bounded_68"] == c["bounded_68"] == ""
    cs = rows[("table1", "stress_scale_x_width")]
    assert 5.5 < float(cs["best"]) < 8.5
    # along the 95 % valley c s moves by far less than s and c themselves
    assert float(cs["hi_95"]) / float(cs["lo_95"]) < 1.4
    assert float(s["hi_95"]) / float(s["lo_95"]) > 10
    slope = float(rows[("table1", "degenerate_direction")]["best"])
    assert -1.2 < slope < -0.6
    soft, stiff = small["direction_halfwidth"].values[list(idf.SUBSETS).index("table1")]
    assert soft > 30 * stiff


def test_the_region_is_the_chi2_surface_about_the_joint_fit(small):
    """The surface's minimum is the joint fit: no profile point lies below its chi^2, the s
    profile meets it at the best s, and the 68 % region there contains the best c; each
    region's extent in s is where the s profile crosses its level."""
    for j, name in enumerate(idf.SUBSETS):
        base = float(small["chi2_min"].values[j])
        w = small["scan_width"].values
        for prof in ("prof_width", "prof_scale"):
            assert small[prof].values[j].min() >= base - 1e-9 * max(base, 1)
        i = int(np.argmin(abs(w - float(small["best_width"].values[j]))))
        a = int(small["best_condition"].values[j])
        c = float(small["best_scale"].values[j])
        lo, hi = small["region_c_lo"].values[j], small["region_c_hi"].values[j]
        assert lo[0, a, i] <= c <= hi[0, a, i], name
        for li, level in enumerate(idf.LEVELS.values()):
            some = np.isfinite(lo[li]).any(axis=0)
            inside = small["prof_width"].values[j] <= base + level
            assert np.array_equal(some, inside), (name, level)


def test_a_region_cut_by_the_c_scan_is_flagged(small):
    """With the c scan stopped at 2.4 (where it stopped before), the 95 % region of Table 1
    runs into the c scan's end at small s: its c limit sits there, and the table flags the
    end of c as the c scan's and the start of s as set by the c scan (not by the data)."""
    run = copy.deepcopy(load_paper(CFG, "ci").runs["identifiability"])
    run["resolution"] = {"n_elements": 32}
    run["options"] = {"timing_min_s": 0.0}
    run["parameters"].update(scan_gaussian_width=[0.001, 0.020, 0.001],
                             scan_stress_scale=[0.25, 2.4, 0.25])
    ds = _solve_once(run)
    j = list(idf.SUBSETS).index("table1")
    hi = ds["region_c_hi"].values[j, 1]
    assert np.nanmax(hi) == pytest.approx(ds["scan_scale"].values[-1])
    rows = _rows(ds)
    assert "hi: c scan end 2.4" in rows[("table1", "stress_scale")]["bounded_95"]
    assert "lo: c scan end" in rows[("table1", "gaussian_width")]["bounded_95"]


def test_the_c_profile_is_smooth(small):
    """Between the best c and where the valley leaves the s scan, the Table 1 c profile
    rises monotonically: each point is a minimum over a continuous s, so no saw-tooth from
    the s grid (the grid minimum's teeth reached 0.5 in chi^2 above c = 1.8)."""
    j = list(idf.SUBSETS).index("table1")
    c = small["scan_scale"].values
    p = small["prof_scale"].values[j]
    floor = small["prof_scale_width"].values[j] * 1e3
    wall = np.nonzero(floor <= floor.min() + 1e-9)[0].min()     # s reaches 1 mm
    k = int(np.argmin(p))
    seg = p[k:wall]
    assert len(seg) > 100 and c[wall] > 5
    assert np.all(np.diff(seg) >= -1e-9 * seg.max()), np.diff(seg).min()
    # and the valley floor moves continuously along c s ~ const: s falls as c rises, by
    # about as much in relative terms, never by jumps of the s grid
    ds_rel, dc_rel = np.diff(np.log(floor[k:wall])), np.diff(np.log(c[k:wall]))
    assert np.all(ds_rel < 0) and np.all(-ds_rel < 2 * dc_rel)


def test_the_fit_recovers_a_synthetic_paper_on_the_extended_scan():
    """The joint fit on the config's scan range recovers (s, c, condition) from Table 1 and
    f~ made by the model itself at s = 3 mm, c = 2.9 (beyond the former c scan), clamped."""
    from mechrepro.models.disk_tension.modal import eigen, frequency

    h = calibration.thickness(f_target=434.5, n_d=4, r_f=0.025, b=B, E=E, nu=NU, rho=RHO)
    d = AxisymDisk(r_f=0.025, b=B, h=h, E=E, nu=NU, rho=RHO, n_d=range(5), n_elements=32)
    d.unrolled()
    load = dict(r_c=0.065, amplitude=50.0, alpha=12e-6, E=E, nu=NU)
    unit, Ks = idf.unit_table1(d, s=0.003, inplane_bc="clamped", **load)
    f4 = frequency(eigen(d.K[4] + 2.9 * Ks[4], d.M[4], 1, 3)[0][0])
    r = idf.analyse(d, widths=np.arange(1e-3, 6.01e-3, 0.5e-3),
                    scales=np.arange(0.25, 8.01, 0.25), fine=np.linspace(0.25, 8, 1241),
                    fine_widths=np.linspace(1e-3, 6e-3, 51), single_width=0.005,
                    table1_paper=2.9 * unit, f_rolled_paper=float(f4), **load)
    assert r["best_width"][0] == pytest.approx(0.003, abs=0.01e-3)
    assert r["best_scale"][0] == pytest.approx(2.9, abs=2e-3)
    assert r["best_condition"][0] == 0
    # noise-free data: the 68 % region holds the truth at its s (3 mm, grid point 20)
    lo, hi = r["region_c_lo"][0, 0, 0, 20], r["region_c_hi"][0, 0, 0, 20]
    assert lo <= 2.9 <= hi and hi - lo < 0.1
