"""joint_wear physics: kinematics, contact law, equations of motion, wear, effects."""
import math

import numpy as np
import pytest

from mechrepro.config import load_paper
from mechrepro.io import check_cf
from mechrepro.models.joint_wear import EFFECTS, setup
from mechrepro.solve import solve
from mechrepro.models.joint_wear import clearance, contact, dynamics, kinematics, quasistatic, wear
from mechrepro.models.joint_wear.geometry import FourBar, material_h, stiffness_K

from conftest import ROOT

CFG = load_paper(ROOT / "config/papers/joint_wear.yaml")


def run_of(scene, **params):
    run = dict(CFG.runs[scene])
    run["parameters"] = dict(run["parameters"], **params)
    return run


def fourbar(scene="period_dynamic", **params):
    return setup(run_of(scene, **params))[0]


# --- the equations as the paper writes them, checked against the model's statistics ---------
def damping_K2(delta, d_max, C_max):
    """Eq. (14): step damping K''(delta) rising smoothly from 0 to C_max at d_max."""
    x = np.clip(np.asarray(delta, float) / d_max, 0.0, 1.0)
    return C_max * x * x * (3.0 - 2.0 * x)


def normal_force(delta, delta_dot, K, n_exp, d_max, C_max):
    """Eq. (11): F_N = K' delta^n + K'' delta_dot, zero out of contact, never adhesive."""
    delta = np.asarray(delta, float)
    dp = np.maximum(delta, 0.0)
    F = K * dp ** n_exp + damping_K2(dp, d_max, C_max) * delta_dot
    return np.where(delta > 0.0, np.maximum(F, 0.0), 0.0)


def contact_area(delta, R_pin, R_bush, width):
    """Eq. (20): A_a = |AB| w [m2]."""
    return contact.contact_chord(delta, R_pin, R_bush) * width


def local_wear_depth(k: float, F_mean: float, S: float, A_mean: float) -> float:
    """Eq. (25): dh* = (K/H) F_N S / A_a -- the depth if all wear sat at one point G."""
    return k * F_mean * S / A_mean


def distributed_wear_depth(dh_star: float, AB_mean: float, L_wear: float) -> float:
    """Eq. (28): the volume of Eq. (26) spread over the wear range: dh* AB / L."""
    return dh_star * AB_mean / L_wear


def test_kinematics_closes_the_loop_and_matches_finite_differences():
    fb = fourbar()
    t = np.linspace(0, fb.period, 4001)
    th1 = fb.omega * t
    th3, ph2 = kinematics.positions(fb, th1)
    # loop closure B = D + l3 u3 + l2 u2
    bx = fb.l0 + fb.l3 * np.cos(th3) + fb.l2 * np.cos(ph2)
    by = fb.l3 * np.sin(th3) + fb.l2 * np.sin(ph2)
    assert np.max(np.hypot(bx - fb.l1 * np.cos(th1), by - fb.l1 * np.sin(th1))) < 1e-12
    w3, w2 = kinematics.velocities(fb, th1, th3, ph2)
    a3, a2 = kinematics.accelerations(fb, th1, th3, ph2, w3, w2)
    dt = t[1] - t[0]
    for ang, w, a in ((th3, w3, a3), (ph2, w2, a2)):
        assert np.allclose(np.gradient(np.unwrap(ang), dt)[1:-1], w[1:-1], atol=1e-5)
        assert np.allclose(np.gradient(w, dt)[1:-1], a[1:-1], atol=1e-5)
    # Grashof crank-rocker: the follower rocks, period 6.25 s (Eq. 34: 1152 periods in 2 h)
    assert np.ptp(th3) < np.pi
    assert fb.period == pytest.approx(6.25)


def test_stiffness_eq12_and_contact_arc_eq18_19():
    h = material_h(2.04e11, 0.285) + material_h(6.9e10, 0.33)
    K = stiffness_K(9.9e-3, 10e-3, h)
    assert K == pytest.approx(4 / (3 * math.pi * h) * math.sqrt(9.9e-3 * 10e-3 / 1e-4))
    assert 7e10 < K < 8e10
    d = np.array([1e-9, 1e-7, 1e-6, 1e-5])
    ab = contact.contact_chord(d, 9.9e-3, 10e-3)
    assert np.all(np.diff(ab) > 0) and ab[0] > 0
    # |AB| = 2 R_j sin(theta) (Eq. 19 simplified)
    th = contact.half_contact_angle(d, 9.9e-3, 10e-3)
    assert np.allclose(ab, 2 * 10e-3 * np.sin(th))
    # Eq. (14): damping starts at zero with zero slope and saturates at C_max
    assert damping_K2(0.0, 1e-5, 5.0) == 0.0
    assert damping_K2(2e-5, 1e-5, 5.0) == 5.0
    # no adhesion: separating with damping never pulls
    assert normal_force(1e-7, -1e3, K, 1.5, 1e-5, 1e8) == 0.0


def test_contact_jacobian_matches_finite_differences():
    fb = fourbar()
    r = dynamics.simulate(fb, 1.0, 11, rtol=1e-6, damping=True, start="equilibrium")
    y = r["y"][:, -1]
    p = clearance.params(fb, damping=True)
    Jn = np.zeros((4, 4))
    for k in range(4):
        h = 1e-10 if k < 2 else 1e-8
        yp, ym = y.copy(), y.copy()
        yp[k] += h
        ym[k] -= h
        Jn[:, k] = (clearance.rhs(1.0, yp, p) - clearance.rhs(1.0, ym, p)) / (2 * h)
    Ja = clearance.jac(1.0, y, p)
    # the contact (stiff) blocks are exact; M(q) and velocity terms are frozen (~1 %)
    assert np.allclose(Ja[2:], Jn[2:], rtol=0.02, atol=1e-3 * np.abs(Jn[2:]).max())


def test_quasistatic_continuous_contact_matches_dynamic_clearance_joint():
    fb = fourbar()
    qs = quasistatic.one_period(fb, 720)
    dyn = dynamics.simulate(fb, fb.period, 721, rtol=1e-5, damping=True, start="equilibrium")
    assert dyn["status"] == 0
    assert dyn["delta"].min() > 0           # continuous contact over the whole period
    assert qs["F_N"].min() > 0
    assert np.mean(dyn["F_N"][:-1]) == pytest.approx(np.mean(qs["F_N"]), rel=1e-3)
    # sliding distance ~ one relative turn of the pin, 2 pi R
    S = wear.period_wear_factor(qs, fb, fb.period)["S"]
    assert S == pytest.approx(2 * math.pi * fb.R_pin, rel=0.02)


def test_calibration_replays_the_measured_wear_and_interval_counts():
    fb = fourbar("period_quasistatic")
    G = lambda R: 1e5 * (1 + (R - fb.R_bush) / fb.R_bush)  # noqa: E731
    h = np.array([0.0229, 0.0496, 0.0779, 0.1000, 0.1221]) * 1e-3
    k, kmean, Gs = wear.calibrate(h, 2.0, 6.25, fb.R_bush, G)
    assert np.allclose(np.cumsum(k * Gs * 1152), h)     # Eqs. (32)-(34) invert exactly
    # Sec. 4.5: 38, 19, 10, 5 simulations for 2, 4, 8, 16 h
    for iv, n in ((2, 38), (4, 19), (8, 10), (16, 5)):
        assert wear.interval_nodes(10, 86, iv).size - 1 == n
    # with a one-period interval the interval method is the period-by-period method
    nodes, hp, _ = wear.predict(1e-4, 0.0, 50 * 6.25 / 3600, 6.25 / 3600, kmean, 6.25, fb.R_bush, G)
    assert hp[-1] == pytest.approx(wear.period_by_period(1e-4, 50, kmean, fb.R_bush, G), rel=1e-12)


def test_unit_reading_of_the_wear_coefficient():
    # k = K/H [1/Pa]: wear depth per period = k F S / (w L) is a length
    ds = solve(CFG.runs["wear_no_update"])
    G = float(ds["wear_factor"])               # N/m
    assert ds["wear_factor"].attrs["units"] == "N/m"
    assert ds["k_mean"].attrs["units"] == "m2/N"
    assert ds["K_table_mean"].attrs["units"] == "1/Pa"
    assert np.allclose(ds["K_table_mean"].values, 21 * ds["k_mean"].values)
    fb = fourbar("period_quasistatic")
    f = wear.period_wear_factor(quasistatic.one_period(fb, 720), fb, fb.period)
    assert G == pytest.approx(f["F_N_mean"] * f["S"] / (fb.width * f["L_arc"]))
    # doubling the width halves the wear per period (Eq. 29)
    wide = fourbar("period_quasistatic", width=2 * fb.width)
    f2 = wear.period_wear_factor(quasistatic.one_period(wide, 720), wide, wide.period)
    assert f2["G"] == pytest.approx(G / 2, rel=1e-9)
    # the calibration replays the measurements: k G M = dh
    dh = np.asarray(CFG.runs["wear_no_update"]["parameters"]["measured_increment_B1"])
    kp = ds["k_calibrated"].sel(side="B1").values
    Gp = ds["wear_factor_calibration"].sel(side="B1").values
    assert np.allclose(kp * Gp * 1152, dh, rtol=1e-9)


def test_effects_change_the_result():
    base = solve(run_of("period_quasistatic"))
    run = run_of("period_quasistatic")
    run["effects"] = ["gravity"]
    nofric = solve(run)
    # friction turns the contact point by ~atan(mu) and adds a friction force
    assert float(np.abs(nofric["F_T"]).max()) == 0.0
    assert float(np.abs(base["F_T"]).max()) > 0.05 * float(base["F_N_mean"])
    run["effects"] = ["friction"]
    nograv = solve(run)
    # without the link weights the coupler is a two-force member: the arc collapses
    assert float(nograv["contact_arc_angle"]) < 0.1 * float(base["contact_arc_angle"])


def test_wear_update_and_unbalanced_load():
    up, frozen = solve(CFG.runs["wear_prediction"]), solve(CFG.runs["wear_no_update"])
    for ds in (up, frozen):
        assert list(ds["side"].values) == ["B1", "B2"]
        assert np.all(np.diff(ds["wear_predicted"].values, axis=1) > 0)
    # the paper's own tables imply a wear factor falling slowly as the bushing grows;
    # with the update the 86-h wear therefore differs (slightly) from the frozen bushing
    d = float(up["wear_at_end_B1"] / frozen["wear_at_end_B1"]) - 1
    assert -0.1 < d < 0 and abs(d) > 1e-4
    # B1 wears more than B2 (Sec. 4.2)
    assert float(up["wear_at_end_B1"]) > float(up["wear_at_end_B2"])
    assert int(up["n_simulations_per_side"]) == 38


# ---- Eq. (3) in Cartesian coordinates with Lagrange multipliers: the independent check --------
# bodies 1 crank, 2 coupler, 3 follower, q_i = (x_i, y_i, phi_i) of the centre of mass (link
# mid-points); revolute joints A, B, C, D and the driver phi1 = omega t give nine constraints
# for nine coordinates.  [M Phi_q^T; Phi_q 0] [q''; lam] = [g; gamma] (Eqs. 3-4) is solved per
# instant (stacked 18x18 solves); lam_B is the force the pin exerts on the bushing when joint B
# is ideal.
def _rot(phi):
    c, s = np.cos(phi), np.sin(phi)
    return c, s


def joint_B_reaction(fb: FourBar, t, crank_mass: float, crank_inertia: float):
    """Force on the bushing at an ideal joint B (N x 2) and q'' (N x 9) from Eq. (3)."""
    t = np.asarray(t, float)
    n = t.size
    th1 = fb.omega * t
    th3, ph2 = kinematics.positions(fb, th1)
    w3, w2 = kinematics.velocities(fb, th1, th3, ph2)
    w1 = np.full(n, fb.omega)
    phi = [th1, ph2, th3]
    om = [w1, w2, w3]
    L = [fb.l1, fb.l2, fb.l3]
    m = [crank_mass, fb.m2, fb.m3]
    inertia = [crank_inertia, fb.I2, fb.I3]
    # local points: crank A (-l1/2), B (+l1/2); coupler C (-l2/2), B (+l2/2);
    # follower D (-l3/2), C (+l3/2)
    # joints as (body_i, s_i, body_j, s_j); body -1 = ground
    joints = [(0, -L[0] / 2, -1, None),          # A at the origin
              (0, +L[0] / 2, 1, +L[1] / 2),      # B: crank end = coupler end
              (1, -L[1] / 2, 2, +L[2] / 2),      # C
              (2, -L[2] / 2, -1, None)]          # D at (l0, 0)
    A = np.zeros((n, 18, 18))
    b = np.zeros((n, 18))
    for i in range(3):
        A[:, 3 * i, 3 * i] = A[:, 3 * i + 1, 3 * i + 1] = m[i]
        A[:, 3 * i + 2, 3 * i + 2] = inertia[i]
        b[:, 3 * i + 1] = -m[i] * fb.g
    # load P at E (the follower's centre of mass) towards F
    ex, ey = fb.l0 + fb.l3 / 2 * np.cos(th3), fb.l3 / 2 * np.sin(th3)
    dx, dy = fb.F[0] - ex, fb.F[1] - ey
    dn = np.hypot(dx, dy)
    b[:, 6] += fb.P * dx / dn
    b[:, 7] += fb.P * dy / dn
    row = 9
    for (bi, si, bj, sj) in joints:
        for body, s, sign in ((bi, si, 1.0), (bj, sj, -1.0)):
            if body < 0:
                continue
            c, sn = _rot(phi[body])
            # Phi = sum sign * (r + A s); d/dphi (A s) = (-s sin, s cos)
            A[:, row, 3 * body] = sign
            A[:, row + 1, 3 * body + 1] = sign
            A[:, row, 3 * body + 2] = sign * (-s * sn)
            A[:, row + 1, 3 * body + 2] = sign * (s * c)
            # gamma = -(Phi_q q')_q q' = sign * A s phi'^2
            b[:, row] += sign * s * c * om[body] ** 2
            b[:, row + 1] += sign * s * sn * om[body] ** 2
        row += 2
    A[:, row, 2] = 1.0                      # driver phi1 - omega t = 0, gamma = 0
    # symmetric: Phi_q^T in the upper right block
    A[:, :9, 9:] = np.transpose(A[:, 9:, :9], (0, 2, 1))
    x = np.linalg.solve(A, b[..., None])[..., 0]
    lam = x[:, 9:]
    # M q'' + Phi_q^T lam = g: the constraint force on body j is -Phi_qj^T lam;
    # joint B's Phi has -I for the coupler's r, so the force on the bushing is +lam_B
    return lam[:, 2:4], x[:, :9]


def test_minimal_coordinates_equal_the_lagrange_multiplier_form_eq3():
    """The joint-B force of the minimal-coordinate equations (ideal joint, no friction)
    equals the Lagrange multiplier of Eq. (3) in Cartesian coordinates."""
    fb = fourbar("period_quasistatic")          # gravity on, friction off below
    fb = fb.__class__(**{**fb.__dict__, "mu": 0.0})
    qs = quasistatic.one_period(fb, 200, passes=0)   # the ideal joint: no clearance kinematics
    lamB, qdd = joint_B_reaction(fb, qs["t"], 0.4973, 8.801e-4)
    fx = qs["F_N"] * qs["nx"]
    fy = qs["F_N"] * qs["ny"]
    assert np.allclose(lamB[:, 0], fx, rtol=1e-9, atol=1e-9 * qs["F_N"].max())
    assert np.allclose(lamB[:, 1], fy, rtol=1e-9, atol=1e-9 * qs["F_N"].max())
    # the crank turns at constant speed
    assert np.allclose(qdd[:, 2], 0.0, atol=1e-9)


def test_point_wear_distributed_over_the_range_is_eq29():
    """Eq. (25) (all wear at one point G) spread over the range by Eq. (28) is Eq. (29)."""
    fb = fourbar("period_quasistatic")
    f = wear.period_wear_factor(quasistatic.one_period(fb, 360), fb, fb.period)
    k = 6.4e-14
    dh_star = local_wear_depth(k, f["F_N_mean"], f["S"], f["A_mean"])
    dh = distributed_wear_depth(dh_star, f["AB_mean"], f["L_wear"])
    assert dh == pytest.approx(k * f["G"], rel=1e-12)
    # A_a = |AB| w (Eq. 20) at the mean penetration is close to the mean area
    d = quasistatic.one_period(fb, 360)["delta"]
    assert float(np.mean(contact_area(d, fb.R_pin, fb.R_bush, fb.width))) == pytest.approx(f["A_mean"])
