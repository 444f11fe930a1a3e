"""chain_drive: the FD scheme against exact solutions, the kinematics and the loads."""
import math

import numpy as np
import pytest
from scipy.integrate import quad

from mechrepro.accuracy import observed_order
from mechrepro.effects import EffectRegistry
from mechrepro.models.chain_drive import EFFECTS, exact, fd, four_bar, geometry, loads, span
from test_chain_drive_contract import declared

P_C = 0.0127
BASE = dict(pitch=P_C, mass_per_length=0.61, static_tension=400.0, transverse_damping=12.2,
            n1=24, n2=24, centre_distance=20.25, lambda_support=0.9, axial_stiffness=2e6,
            driven_inertia=0.002, impact_mass_links=2, contact_stiffness=2e8,
            contact_damping_ratio=0.1, external_load_ratio=0.2, external_frequency_ratio=2.0,
            speed=300 * math.pi / 30, speed_min=100 * math.pi / 30, speed_max=300 * math.pi / 30,
            probe_fraction=1 / 3)
COARSE = dict(points_per_pitch=2, cfl=0.9, decay_times=0.5, window_periods=1)


def test_exact_moving_string_mode_second_order_central():
    cw = math.sqrt(400 / 0.61)
    errs, hs = [], []
    for n in (20, 40, 80):
        e, w_fd, w_ex, dt, _ = exact.free_vibration(n, L=0.254, m=0.61, T=400.0, c=0.5 * cw,
                                                    s_star=0.0)
        errs.append(e)
        hs.append(1 / n)
    assert 1.8 < observed_order(hs, errs) < 2.2
    assert abs(w_fd / w_ex - 1) < 1e-3          # Wickert-Mote frequency at n = 80


def test_wickert_mote_frequency_with_papers_mixed_differencing():
    cw = math.sqrt(400 / 0.61)
    for ratio in (0.0, 0.3, 0.7):
        _, w_fd, w_ex, _, _ = exact.free_vibration(80, L=0.254, m=0.61, T=400.0, c=ratio * cw)
        assert abs(w_fd / w_ex - 1) < 2e-3, ratio


def test_manufactured_solution_order():
    errs, hs = [], []
    for n in (20, 40, 80):
        e, dt, dx, _ = exact.manufactured(n, s_star=0.0, kappa=0.01)
        errs.append(e)
        hs.append(dx)
    assert 1.8 < observed_order(hs, errs) < 2.2
    # the paper's upwind-weighted differencing converges, at first order or better
    errs_m = [exact.manufactured(n, kappa=0.01)[0] for n in (20, 40, 80)]
    assert errs_m[-1] < errs_m[0] and observed_order(hs, errs_m) > 0.9


def test_resonance_speed_meets_wickert_mote():
    L = 20 * P_C
    for k in (1, 3, 5):
        w1 = geometry.resonance_speed(k, L, n1=24, p_c=P_C, T_s=400, m=0.61,
                                      tension_coefficient=0.9 * 0.61)
        c = geometry.chain_speed(w1, 24, P_C)
        P = geometry.axial_tension(400, 0.9 * 0.61, c)
        assert 24 * w1 == pytest.approx(geometry.moving_string_frequencies(k, c, P, 0.61, L), rel=1e-10)


def test_fractional_pitch_and_span_lengths():
    assert geometry.fractional_pitch(20.25 * P_C, P_C) == pytest.approx(0.25)
    assert geometry.fractional_pitch(20.0 * P_C, P_C) == 0.0
    assert geometry.span_lengths(20.0 * P_C, P_C) == (pytest.approx(20 * P_C),) * 2
    s, l = geometry.span_lengths(20.5 * P_C, P_C)
    assert (s, l) == (pytest.approx(20 * P_C), pytest.approx(21 * P_C))


def test_rigid_four_bar_kinematics():
    w1 = 300 * math.pi / 30
    t = np.linspace(0, 2 * math.pi / w1, 24 * 400, endpoint=False)   # one revolution
    same = four_bar.rigid_kinematics(t, w1, n1=24, n2=24, p_c=P_C, f_p=0.0)
    np.testing.assert_allclose(same["omega2"], w1, rtol=1e-9)         # in phase: no fluctuation
    for n2 in (15, 40):
        kin = four_bar.rigid_kinematics(t, w1, n1=24, n2=n2, p_c=P_C, f_p=0.3)
        # the driven sprocket turns by 24/n2 of the driver's angle: mean speed ratio n1/n2
        assert np.mean(kin["omega2"]) == pytest.approx(w1 * 24 / n2, rel=2e-3)
    # the long-span state lasts the fractional pitch of every tooth period
    kin = four_bar.rigid_kinematics(t, w1, n1=24, n2=24, p_c=P_C, f_p=0.3)
    assert np.mean(four_bar.long_span(kin["phase1"], kin["phase2"])) == pytest.approx(0.3, abs=0.01)


def test_polygonal_load_scales_with_speed_squared():
    def peak(w):
        t = np.linspace(0, 4 * math.pi / (24 * w), 4000)
        kin = four_bar.rigid_kinematics(t, w, n1=24, n2=15, p_c=P_C, f_p=0.5)
        return np.max(np.abs(four_bar.polygonal_load_rigid(kin["alpha2"], 0.002, kin["r2"])))
    assert peak(60.0) / peak(30.0) == pytest.approx(4.0, rel=1e-3)


def test_impact_impulse_exact_even_when_step_exceeds_pulse():
    w1 = 300 * math.pi / 30
    k = loads.impact_constants(2 * P_C * 0.61, 2e8, 0.1)
    V, eta = loads.relative_velocity(w1, P_C), loads.pressure_angle(24)
    J = float(loads.impact_pulse_integral(np.inf, V, eta, k))
    assert J == pytest.approx(quad(lambda s: float(loads.impact_pulse(s, V, eta, k)), 0, k["t_i"],
                                   limit=200)[0], rel=1e-7)
    tau = 2 * math.pi / (24 * w1)
    dt = 5 * k["t_i"]                                  # the step is 5 pulses long
    t = np.arange(-0.5 * tau, 2.5 * tau, dt)
    avg = loads.impact_load(t, w1, 24, P_C, k, step=dt)
    # the step windows tile [-tau/2, 2.5 tau): impacts at 0, tau and 2 tau
    assert np.sum(avg) * dt == pytest.approx(3 * J, rel=1e-9)
    sampled = loads.impact_load(t, w1, 24, P_C, k)
    assert np.sum(sampled) * dt != pytest.approx(3 * J, rel=0.2)  # point sampling aliases it


def test_elastic_four_bar_resonance_from_span_stiffness():
    L = 20 * P_C
    k = 2e6 / L
    r2 = geometry.pitch_radius(P_C, 24)
    wc = four_bar.elastic_resonance(k, 0.002, r2, 24)
    ws = np.linspace(0.8 * wc, 1.2 * wc, 81)
    ptp = []
    for w in ws:
        sol = four_bar.elastic_four_bar(w, k=k, I2=0.002, n1=24, n2=24, p_c=P_C, f_p=0.5)
        tt = np.linspace(0, 2 * math.pi / (24 * w), 64, endpoint=False)
        pt = (sol["p"] * tt)[:, None]
        ptp.append(np.ptp(four_bar.polygonal_load_elastic_speeds(np.sin(pt), np.cos(pt), [sol],
                                                                 [w], k)))
    assert abs(ws[np.argmax(ptp)] / wc - 1) < 0.02
    assert np.all(np.isfinite(ptp))


def test_vectorised_sweep_equals_per_speed_loop():
    om = np.linspace(BASE["speed_min"], BASE["speed_max"], 4)
    eff = ["speed_tensioning", "polygonal_rigid", "end_excitation", "length_change", "impact"]
    a = span.sweep(declared(eff), BASE, om, COARSE)
    x = span.assemble(declared(eff), BASE, om, COARSE)
    e, b = x["exc"], []
    for i in range(om.size):      # the same inputs marched speed by speed
        sl = slice(i, i + 1)
        exc = fd.Excitation(**{k: (None if getattr(e, k) is None else getattr(e, k)[:, sl])
                               for k in ("tension", "u_left", "u_right", "long", "load")})
        b.append(fd.march(c=x["c"][sl], P=x["P"][sl], exc=exc, s_star=x["s_star"][sl], m=x["m"],
                          c_d=x["c_d"], grid=x["grid"], dt=x["dt"], n_steps=x["n_steps"],
                          measure_from=x["measure_from"], u_cap=0.05,
                          n_blocks=span.GROWTH_BLOCKS).amplitude[0])
    np.testing.assert_allclose(a["amplitude"], b, rtol=1e-10)
    assert np.all(a["amplitude"] > 0)


def test_effect_that_is_off_is_never_evaluated():
    reg = EffectRegistry("chain_drive")
    on = ["speed_tensioning", "polygonal_rigid", "end_excitation"]
    for name in EFFECTS.names:
        if name in on:
            reg.register(name)(EFFECTS.select([name])[name])
        else:
            def boom(ctx, _n=name):
                raise AssertionError(f"effect {_n} evaluated although off")
            reg.register(name)(boom)
    om = np.array([BASE["speed_min"]])
    out = span.sweep(declared(on), BASE, om, COARSE, registry=reg)
    assert np.isfinite(out["amplitude"]).all()
    with pytest.raises(AssertionError, match="external_load"):
        span.sweep(declared(on + ["external_load"]), BASE, om, COARSE, registry=reg)


def test_end_excitation_phase_sets_first_mode_response():
    """System A (integral pitch, ends in phase) is amplified at the first resonance,
    system B (half pitch, ends out of phase) is not (Fig. 5 claim, small grid)."""
    prm = dict(BASE)
    res = dict(points_per_pitch=3, cfl=0.9, decay_times=3, window_periods=2)
    out = {}
    for cd in (20.0, 20.5):
        prm["centre_distance"] = cd
        L = geometry.span_geometry(prm, False)["L_ct"]
        w1 = geometry.resonance_speed(1, L, n1=24, p_c=P_C, T_s=400, m=0.61,
                                      tension_coefficient=0.9 * 0.61)
        r = span.sweep(declared(["speed_tensioning", "end_excitation"]), prm, np.array([0.3 * w1, w1]), res)
        out[cd] = r["amplitude"][1] / r["amplitude"][0]
    assert out[20.0] > 2.0 > out[20.5]


# ---------------------------------------------------------------------------- issue 18: speed

def test_fast_impact_load_equals_the_cumulative_impulse_formula():
    """impact_load evaluates the pulse only near impacts; elsewhere whole impulses cancel."""
    import math as _m

    from mechrepro.models.chain_drive import loads as _loads
    k = _loads.impact_constants(2 * 0.0127 * 0.61, 2e8, 0.1)
    om = np.linspace(50, 800, 37) * _m.pi / 30
    for dt in (7.5e-5, 1.1e-5):
        t = (np.arange(int(0.05 / dt)) * dt)[:, None]
        got = _loads.impact_load(t, om[None, :], 24, 0.0127, k, step=dt)
        tau = 2 * np.pi / (24 * om[None, :])
        V, eta = _loads.relative_velocity(om[None, :], 0.0127), _loads.pressure_angle(24)
        J = _loads.impact_pulse_integral(np.inf * np.ones_like(V), V, eta, k)

        def cum(s):
            return np.floor(s / tau) * J + _loads.impact_pulse_integral(np.mod(s, tau), V, eta, k)
        want = (cum(t + dt / 2) - cum(t - dt / 2)) / dt
        assert np.max(np.abs(got - want)) <= 1e-12 * np.max(np.abs(want))


def test_fast_rigid_kinematics_matches_chain_travel():
    """rigid_kinematics (travel within the tooth period, sqrt for the sines) against the
    direct form of Eqs. (2-7)-(2-9) through chain_travel and np.mod; the span-length state
    identical at every sample."""
    import math as _m

    from mechrepro.models.chain_drive import four_bar as fb
    from mechrepro.models.chain_drive.geometry import pitch_radius
    om = np.linspace(50, 800, 41)[None, :] * _m.pi / 30
    t = (np.arange(2000) * 7.5e-5)[:, None]
    p = 0.0127
    for n1, n2, f_p in ((24, 24, 0.25), (24, 24, 0.0), (15, 40, 0.5)):
        kin = fb.rigid_kinematics(t, om, n1=n1, n2=n2, p_c=p, f_p=f_p)
        r1, r2 = pitch_radius(p, n1), pitch_radius(p, n2)
        s, th1 = fb.chain_travel(t, om, n1, r1)
        th20s = np.pi / 2 - np.pi / n2
        th20 = th20s + fb.driven_phase(n2, f_p)
        s2 = np.mod(s + r2 * (np.cos(th20s) - np.cos(th20)), p)
        th2 = np.arccos(np.clip(np.cos(th20s) - s2 / r2, -1.0, 1.0))
        w2 = om * r1 * np.sin(th1) / (r2 * np.sin(th2))
        a2 = (r1 * om**2 * np.cos(th1) - r2 * w2**2 * np.cos(th2)) / (r2 * np.sin(th2))
        for key, want in (("theta1", th1), ("cos_theta2", np.cos(th2)), ("omega2", w2),
                          ("alpha2", a2), ("phase2", s2 / p), ("phase1", np.mod(s, p) / p)):
            assert np.max(np.abs(kin[key] - want)) <= 1e-12 * np.max(np.abs(want)), key
        assert np.array_equal(fb.long_span(kin["phase1"], kin["phase2"]),
                              fb.long_span(np.mod(s, p) / p, s2 / p))
