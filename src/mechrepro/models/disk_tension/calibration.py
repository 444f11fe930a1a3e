"""The two constants the paper does not give, calibrated on one number each.

* thickness h: the exact (Bessel) unrolled frequency of N_d = 4 at r_f = 25 mm equals the
  paper's 434.5 Hz (Sec. 4.3).  Kirchhoff frequencies are proportional to h, so one exact
  solve at a trial thickness fixes h.
* effective thermal-expansion coefficient of the thermal analogy (``stress_calibration``):
  the temperature of Eq. (4) is fictitious, only alpha * T matters, and Eq. (9)'s
  Delta omega^2 is linear in it; alpha is scaled so that Table 1's N_d = 4 diagonal
  (2.40e6 rad^2/s^2 at r_c = 65 mm, r_f = 25 mm) is met.  Why this entry: it is the
  largest, the text confirms it (its linearised conversion is Sec. 4.3's 70.0 Hz), and it is
  the least sensitive to the in-plane condition.  The 502.1 / 67.6 / 70.0 Hz of Sec. 4.3 sit
  at the calibration's own mode and operating point, so the two calibrations fix them
  whatever the model variant (`determined`); the other Table 1 entries (ratios, alpha
  cancels), Table 2 and Figs. 6-8 are predictions.
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np

from mechrepro.errors import Refusal

from . import exact, thermal
from .axisym import AxisymDisk

CALIBRATION_ELEMENTS = 128  # unrolled error ~1e-8: the calibration does not depend on the run


def thickness(*, f_target, n_d, r_f, b, E, nu, rho):
    """h [m] such that the exact fundamental of ``n_d`` is ``f_target`` [Hz]."""
    trial = 1e-3
    f_trial = exact.natural_frequencies(n_d, a=r_f, b=b, h=trial, E=E, nu=nu, rho=rho)[0]
    return trial * f_target / f_trial


def _calibration_case(*, n_d, r_c, r_f, b, h, E, nu, rho, alpha, amplitude, s, inplane_bc,
                      stress_model="thermal_analogy"):
    """(disk, K^(sigma)) of the calibration case on a fine axisymmetric mesh (``stress_model``:
    a rival's, :func:`.thermal.residual_stress`, re-calibrated on its own stress)."""
    disk = AxisymDisk(r_f=r_f, b=b, h=h, E=E, nu=nu, rho=rho, n_d=[n_d],
                      n_elements=CALIBRATION_ELEMENTS)
    disk.unrolled()
    kw = dict(amplitude=amplitude, r_c=r_c, s=s, r_f=r_f, b=b, E=E, nu=nu, alpha=alpha,
              inplane_bc=inplane_bc, stress_model=stress_model, profile_rc=r_c)
    sig = (lambda r: thermal.residual_stress(r, **kw)[0],
           lambda r: thermal.residual_stress(r, **kw)[1])
    return disk, disk.stress_stiffness(sig)


def alpha_effective(*, target, memo=True, **case):
    """alpha [1/K] that makes Eq. (9)'s Delta omega^2 of ``n_d`` equal ``target``, and the
    handbook-alpha prediction it replaces: (alpha_eff, Delta omega^2, eigen Delta f [Hz]).

    A pure function of scalars, memoised: the runs of a batch share a handful of calibration
    cases (one per Poisson ratio and in-plane condition), each solved once per process
    (``memo=False`` solves afresh: what the calibration costs cold)."""
    key = tuple(sorted(case.items()))
    return _alpha_effective(target, key) if memo else _alpha_effective.__wrapped__(target, key)


@lru_cache(maxsize=256)
def _alpha_effective(target, case):
    case = dict(case)
    disk, Ks = _calibration_case(**case)
    n = case["n_d"]
    d = float(disk.eq9(Ks)[0])
    if not np.isfinite(d) or d == 0.0 or np.sign(d) != np.sign(target):
        raise Refusal(f"cannot calibrate alpha: Eq. (9) gives {d:g}, target {target:g}")
    w2 = float(disk.rolled(Ks)[0][0])
    df = (np.sqrt(w2) - np.sqrt(disk.omega2[n])) / (2 * np.pi) if w2 > 0 else np.nan
    return case["alpha"] * target / d, d, df
