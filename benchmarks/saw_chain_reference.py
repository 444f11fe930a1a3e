"""What the saw_chain benchmark times against the pipeline: the whole difference method as a
per-step Python loop (the paper's MATLAB style; as in tests/test_saw_chain.py) and the Richardson
extrapolation of one extremum from K/4, K/2, K (as in tests/test_saw_chain_richardson.py)."""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from mechrepro.models.saw_chain.difference import load_x
from mechrepro.models.saw_chain.richardson import _levels, from_levels


def difference_method_loop(p1, p2, z, omega, m_L, m_C, M, N, K):
    """Tight-side velocity and total dynamic load x over one period, step by step."""
    R = math.sqrt(p1**2 + p2**2 + 2 * p1 * p2 * math.cos(math.pi / z)) / (2 * math.sin(math.pi / z))
    Tx = p1 + 2 * p2
    phi1 = 2 * math.asin(p2 / (2 * R))
    phi2 = phi1 + 2 * math.asin(p1 / (2 * R))
    m_tight = M * m_L + N * m_C
    velocity, load = [R * omega], [0.0]
    v_prev = vm_prev = R * omega
    for L, m_link, span in ((p2, m_C, phi1), (p1, m_L, phi2 - phi1)):
        dt = span / K / omega
        x_prev = xm_prev = None
        for i in range(K + 1):
            phi = span * i / K
            xl = Tx + R * math.sin(phi)
            yl = R * (1.0 - math.cos(phi))
            xt = xl - math.sqrt(L * L - yl * yl)
            xm = 0.5 * (xl + xt)
            if i > 0:
                v, vm = (xt - x_prev) / dt, (xm - xm_prev) / dt
                a, am = (v - v_prev) / dt, (vm - vm_prev) / dt
                velocity.append(v)
                load.append(m_link * am + m_tight * a)
                v_prev, vm_prev = v, vm
            x_prev, xm_prev = xt, xm
        vm_prev = v_prev  # A2 starts with O2's values at t1
    return velocity, load


def extrapolate_extreme(chain, K: int, fn=np.max):
    """``fn`` of the load x over one period, extrapolated from K/4, K/2, K."""
    Ks = _levels(K)
    return from_levels(chain, Ks, [float(fn(load_x(replace(chain, K=k)))) for k in Ks])
