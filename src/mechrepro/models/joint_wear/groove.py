"""The worn groove in the contact: a conforming pin-in-bushing contact over the arc.

The bushing's worn depth d(theta) (radial, per angle of the coupler frame, on a uniform
periodic grid) enters the contact gap, and the normal joint force is carried by a pressure
over the arc where the pin meets the worn surface: the elastic-foundation (Winkler) model of
a conforming pin in a bushing (Johnson, Contact Mechanics, Sec. 5.9; as Flores and Mukras
et al. spread the joint force over a worn revolute joint).  e is the pin centre's offset from
the bushing centre, n(theta) = (cos, sin) theta, R_j the bushing circle the depth is
measured from (the profile's unworn part), R_i the pin.

    u(theta) = e.n - (R_j - R_i) - d(theta)                                  (G1)
    p(theta) = k_f max(u, 0)                                                 (G2)
    w sum_theta p (R_j + d) n dtheta = F_N n_F                                (G3)

(G1): the interpenetration of a pin offset by e in a bushing worn by d (Eqs. 5-8 with a
worn surface), to first order in |e| / R_i (the conforming-contact gap: its neglected term
|e|^2 sin^2(phi) / 2 R_i narrows the contact arc by ~|e| / 2 R_i, ~5 % at the 1 mm offsets of
86 h).  (G3): the pressure balances the normal joint force of the mechanism (the friction
part, tangential, is Eq. 15's).  The foundation modulus k_f is the one with which a circle
of the radius under the load, R = R_j + d(psi_F), carries F_N at the penetration of the
paper's Eq. (11) (K' of Eq. 12 at that radius), by (G1)-(G3) integrated in closed form over
the circle's arc |phi| < phi0 (Johnson, Sec. 5.9):

    F_N = k_f w R e (phi0 - sin phi0 cos phi0),  e = R - R_i + delta,  cos phi0 = (R - R_i) / e  (G4)

so a uniform depth is the paper's circle of Sec. 4.4 (Eq. 11 sets its penetration, the
foundation only spreads F_N over the arc), and a groove the pin has worn spreads F_N over
the arc where it conforms.  Local Archard wear (Eq. 16 at each angle), per unit k:

    dh(theta) / k = sum_t p(theta, t) |v_T(t)| dt                               (G5)
    v_T = de/dt . t_F + omega R_i - dphi2/dt (R_j + d(psi_F))                   (G6)

(G6): the sliding speed of Eq. (10) at the worn surface under the load, e the offset in the
global frame, t_F the contact tangent.  Whether wear stays local is then decided by the
contact, not by a mean circle.
"""
from __future__ import annotations

import math

import numpy as np

from mechrepro.compiled import jit
from mechrepro.errors import Refusal

from . import quasistatic
from .geometry import FourBar

TWO_PI = 2.0 * math.pi


def foundation_circle(F_N, delta, R, R_pin, width):
    """(G4) for a bushing circle of radius R: k_f [N/m3], the contact half-angle phi0 [rad]
    and the peak pressure k_f delta [Pa] that carry F_N at the penetration delta."""
    c = R - R_pin
    e = c + delta
    phi0 = np.arccos(c / e)
    k_f = F_N / (width * R * e * (phi0 - np.sin(phi0) * np.cos(phi0)))
    return k_f, phi0, k_f * delta


def solve_offset(F_N, psi_F, theta, depth, fb: FourBar, tol=1e-6, max_iter=60, e0=None):
    """(G1)-(G4) per sample: the pin offset e (m x 2, bushing frame) whose foundation
    pressure balances F_N along psi_F, the modulus k_f (m), the pressure p (m x n) and the
    penetration delta of Eq. (11) at the local radius (m).

    (G3) is the gradient of the convex energy  sum a/2 max(u, 0)^2 - F.e  (a the nodes'
    foundation stiffness): Newton's steps with Armijo's backtracking on it converge from
    any start (moved along n_F until the first node is pressed by delta, or ``e0``); a sample out of
    contact is moved along n_F to the penetration delta first.  Refused if the balance
    does not reach tol * F_N."""
    F_N = np.asarray(F_N, float)
    psi_F = np.asarray(psi_F, float)
    cs, sn = np.cos(theta), np.sin(theta)
    dF = np.interp(psi_F, theta, depth, period=TWO_PI)
    R = fb.R_bush + dF
    K = fb.K_contact * np.sqrt(R * fb.clearance / (fb.R_bush * (R - fb.R_pin)))   # Eq. (12)
    delta = (np.maximum(F_N, 0.0) / K) ** (1.0 / fb.n_exp)                   # Eq. (11)
    k_f = foundation_circle(F_N, delta, R, fb.R_pin, fb.width)[0]
    a = (k_f * fb.width * (TWO_PI / theta.size))[:, None] * (fb.R_bush + depth)
    nF = np.stack([np.cos(psi_F), np.sin(psi_F)], axis=1)
    F = F_N[:, None] * nF
    gap = fb.clearance + depth
    if e0 is None:                   # along n_F until the first node is pressed by delta
        cosd = np.maximum(nF[:, :1] * cs + nF[:, 1:] * sn, 1e-3)
        e = ((gap + delta[:, None]) / cosd).min(1)[:, None] * nF
    else:
        e = np.array(e0, float)
    q, r, converged = _solve_offset_kernel(F_N, nF, cs, sn, gap, a, delta, F, e, tol, max_iter,
                                           0.1 * fb.clearance)
    if not converged:
        res = np.hypot(r[:, 0], r[:, 1]).max()
        raise Refusal("joint_wear: the groove's foundation balance (G3) did not converge in "
                      f"{max_iter} Newton steps (residual {res:.3g} N)")
    return e, k_f, q / a * k_f[:, None], delta


@jit
def _state(e0, e1, cs, sn, gap, a, F0, F1, u, q):
    """(G1) and (G3) of one sample at the offset (e0, e1): u and q written into the rows
    given, returns the energy and the residual."""
    w = r0 = r1 = 0.0
    for j in range(cs.size):
        u[j] = e0 * cs[j] + e1 * sn[j] - gap[j]                               # (G1)
        p = max(u[j], 0.0)
        q[j] = a[j] * p
        w += q[j] * p
        r0 += q[j] * cs[j]
        r1 += q[j] * sn[j]
    return 0.5 * w - (F0 * e0 + F1 * e1), r0 - F0, r1 - F1                    # (G3)


@jit
def _solve_offset_kernel(F_N, nF, cs, sn, gap, a, delta, F, e, tol, max_iter, cap0):
    """The iteration of solve_offset from e (updated in place): (q, r, converged).  The
    samples step together until all are balanced (a balanced one keeps stepping: when the
    loop ends decides the numbers).  The Levenberg-Marquardt tries run per sample: a sample
    that is not worse keeps its lam, so repeating its try while others retry would repeat
    its step."""
    m, n = a.shape
    u, q = np.empty((m, n)), np.empty((m, n))
    ut, qt = np.empty(n), np.empty(n)
    energy, r, lam = np.empty(m), np.empty((m, 2)), np.zeros(m)
    for i in range(m):
        energy[i], r[i, 0], r[i, 1] = _state(e[i, 0], e[i, 1], cs, sn, gap, a[i], F[i, 0],
                                             F[i, 1], u[i], q[i])
    for _ in range(max_iter):
        converged = True
        for i in range(m):
            converged = converged and math.hypot(r[i, 0], r[i, 1]) <= tol * F_N[i]
        if converged:
            return q, r, True
        for i in range(m):
            res = math.hypot(r[i, 0], r[i, 1])
            h11 = h12 = h22 = 0.0
            umax = -math.inf
            for j in range(n):
                if u[i, j] > 0.0:
                    h11 += a[i, j] * (cs[j] * cs[j])
                    h12 += a[i, j] * (cs[j] * sn[j])
                    h22 += a[i, j] * (sn[j] * sn[j])
                umax = max(umax, u[i, j])
            free = not h11 + h22 > 0.0
            # Levenberg-Marquardt: raised where the energy does not fall (a node or two in
            # contact leave the slide along the groove free)
            lam[i] = max(0.1 * lam[i], 1e-6 * (h11 + h22))
            for _ in range(40):
                if free:
                    s0, s1 = (delta[i] - umax) * nF[i, 0], (delta[i] - umax) * nF[i, 1]
                else:
                    d11, d22 = h11 + lam[i], h22 + lam[i]
                    det = d11 * d22 - h12 * h12
                    s0 = -(d22 * r[i, 0] - h12 * r[i, 1]) / det
                    s1 = -(d11 * r[i, 1] - h12 * r[i, 0]) / det
                cap = max(cap0, 0.5 * math.hypot(e[i, 0], e[i, 1]))
                f = min(1.0, cap / max(math.hypot(s0, s1), 1e-300))
                s0, s1 = s0 * f, s1 * f
                et, rt0, rt1 = _state(e[i, 0] + s0, e[i, 1] + s1, cs, sn, gap, a[i], F[i, 0],
                                      F[i, 1], ut, qt)
                worse = (not free and et > energy[i] + 1e-4 * (r[i, 0] * s0 + r[i, 1] * s1)
                         and res > 1e-3 * F_N[i])     # near the balance: full steps (round-off)
                if not worse:
                    break
                lam[i] = max(lam[i] * 10.0, 1e-6 * (h11 + h22))
            e[i, 0], e[i, 1] = e[i, 0] + s0, e[i, 1] + s1
            u[i], q[i] = ut, qt
            energy[i], r[i, 0], r[i, 1] = et, rt0, rt1
    return q, r, False


def period(fb: FourBar, n_steps: int, theta, depth) -> dict:
    """One quasi-static period (quasistatic.one_period) with the bushing centre placed by
    the groove's offset (G1-G4) in the clearance kinematics, the sliding speed of (G6) as
    ``v_T`` and the pressure over the arc, ``pressure`` (samples x theta).  fb: the bushing
    circle the depth is measured from."""
    def to_global(e, ph2):        # the offset from the bushing (coupler) frame
        c, s = np.cos(ph2), np.sin(ph2)
        return c * e[:, 0] - s * e[:, 1], s * e[:, 0] + c * e[:, 1]

    hist = quasistatic.one_period(fb, n_steps, offset=lambda out, ph2: to_global(
        solve_offset(out["F_N"], out["ang_n"] - ph2, theta, depth, fb)[0], ph2))
    ph2 = hist["phi2"]
    e, _, p, _ = solve_offset(hist["F_N"], hist["psi"], theta, depth, fb)
    ox, oy = to_global(e, ph2)
    (dox, doy), _ = quasistatic.periodic_derivatives(np.vstack([ox, oy]), fb.period,
                                                     second=False)
    ang = hist["psi"] + ph2
    dF = np.interp(hist["psi"], theta, depth, period=TWO_PI)
    v_T = (-dox * np.sin(ang) + doy * np.cos(ang) + fb.omega * fb.R_pin
           - hist["w2"] * (fb.R_bush + dF))                                    # (G6)
    return {**hist, "v_T": v_T, "pressure": p, "offset": e}


def interval_method(period_of, theta, placements, dh_measured, t_cal_h: float,
                    t_end_h: float, interval_h: float, samples: int, step: float):
    """Sec. 4.4 with the groove in the contact: (G5) integrated in tau = k x periods.

    The profile's growth per unit tau does not depend on k, so one integration serves every
    placement of the measuring points: the calibration (Eqs. 33-34) reads tau_p where a
    placement's mean depth reaches the measured h^p, k = mean (tau_p - tau_(p-1)) / M, so that
    tau runs in proportion to time and the prediction reads the profile at
    tau_10 t / t_cal.  The mechanism (``period_of(profile) -> (hist, fb, d0)``: a groove
    period of the bushing circle R0 + d0 with the depth profile - d0) is simulated once per
    interval of the paper's method (at the measured depths of the first placement, then every
    interval_h); in between, the foundation (G1-G4) is re-solved on ``samples`` samples of
    that period at every explicit step of ``step`` local relaxation times (a groove worn
    deeper per step than the contact's compliance is bridged by the pin, which then bears on
    its rims).  placements: measuring-point angle arrays, the first the baseline.
    Returns {tau, peak, mean (placement x step), tau_cal (per placement), profile (the
    baseline's at t_end), refreshes, steps}."""
    from .wear import at_points
    h_cal = np.cumsum(np.asarray(dh_measured, float))
    ratio = t_end_h / t_cal_h
    prof = np.zeros(theta.size)
    taus, peaks, means = [0.0], [0.0], [[0.0] * len(placements)]
    tau_cal = [None] * len(placements)
    tau, land, stop, due, n_refresh, steps, hour_next = 0.0, math.inf, math.inf, True, 0, 0, 0.0
    profile_end = None
    while tau < stop:
        if due:
            hist, fb_w, d0 = period_of(prof)
            n_refresh += 1
            sl = slice(None, None, max(1, hist["F_N"].size // samples))
            F, psi, v = hist["F_N"][sl], hist["psi"][sl], np.abs(hist["v_T"][sl])
            dt = fb_w.period / F.size
            e = None
        e, k_f, p, _ = solve_offset(F, psi, theta, prof - d0, fb_w, e0=e)
        inc = v @ p * dt
        # explicit Euler on d' = inc(d), the step in units of 1 / max D(theta), D = sum_t
        # |v_T| k_f dt over the samples in contact at theta: the decay rate of a bump on the
        # foundation alone; the pin's approach that balances the load slows it
        dtau = step / float(((v * k_f * dt) @ (p > 0.0)).max())
        landing = profile_end is None and tau + dtau >= land
        tau = land if landing else tau + dtau
        prof = prof + (land - taus[-1] if landing else dtau) * inc
        steps += 1
        if landing:
            profile_end = prof
        taus.append(tau)
        peaks.append(float(prof.max()))
        means.append([at_points(prof, theta, pts) for pts in placements])
        for k in range(len(placements)):                          # Eqs. (33)-(34)
            if tau_cal[k] is None and means[-1][k] >= h_cal[-1]:
                tau_cal[k] = float(np.interp(h_cal[-1], np.asarray(means)[:, k], taus))
        if tau_cal[0] is None:       # the mechanism once per measured interval
            due = int(np.searchsorted(h_cal, means[-1][0], side="right")) >= n_refresh
        else:                        # then every interval_h
            land = tau_cal[0] * ratio
            if hour_next == 0.0:
                hour_next = t_cal_h
            due = tau / tau_cal[0] * t_cal_h >= hour_next
            if due:
                hour_next += interval_h
        if all(t is not None for t in tau_cal):
            stop = max(tau_cal) * ratio
    return {"tau": np.asarray(taus), "peak": np.asarray(peaks), "mean": np.asarray(means).T,
            "tau_cal": tau_cal, "profile": profile_end, "refreshes": n_refresh, "steps": steps}

