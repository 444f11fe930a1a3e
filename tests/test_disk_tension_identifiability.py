"""disk_tension: what the paper's numbers pin down (effect identifiability), as it is (issue
61): Table 1 fixes the product c s of the stress scale and the band width, so the c scan must
reach the valley at the s scan's lower end; an interval end the data do not fix says which
scan bounds it; the profiles are minima over a continuous constant, not over a grid (the
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


def test_interval_ends_say_which_scan_bounds_them(small):
    """Table 1 alone at 95 %: s open at the s scan's lower end (1 mm), and the upper end of c
    set by that same end (its minimiser s sits there), not by the data; at 68 % both are the
    data's.  The direction Table 1 fixes, c s, is named with its range."""
    rows = {(r[0], r[1]): dict(zip(idf.COLUMNS, r)) for r in idf.table(small)}
    s, c = rows[("table1", "gaussian_width")], rows[("table1", "stress_scale")]
    assert s["lo_95"].startswith("1 ") and "open: the s scan's end" in s["lo_95"]
    assert "(the s scan's end)" in c["hi_95"]
    for cell in (s["lo_68"], s["hi_68"], c["lo_68"], c["hi_68"], s["hi_95"]):
        assert "scan" not in cell, cell
    cs = rows[("table1", "stress_scale_x_width")]
    assert 5.5 < float(cs["best"]) < 8.5
    # along the 95 % valley c s moves by far less than s and c themselves
    assert float(cs["hi_95"].split()[0]) / float(cs["lo_95"].split()[0]) < 1.4
    assert "(the s scan's end)" in cs["lo_95"]          # the valley leaves the scan there
    assert float(s["hi_95"]) / float(s["lo_95"].split()[0]) > 10


def test_the_c_profile_is_smooth(small):
    """Between the best c and where the valley leaves the s scan, the Table 1 c profile
    rises monotonically: each point is a minimum over a continuous s, so no saw-tooth from
    the s grid (the grid minimum's teeth reached 0.5 in chi^2 above c = 1.8)."""
    j = list(idf.SUBSETS).index("table1")
    c = small["scan_scale"].values
    p = small["axisym_prof_scale"].values[j]
    floor = small["axisym_prof_scale_width"].values[j] * 1e3
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
