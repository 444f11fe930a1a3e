"""Dynamic clearance joint B: the right-hand side and Jacobian, written once.

State y = (theta3, phi2, dtheta3/dt, dphi2/dt) -- the two extra DOF of the clearance joint
in minimal coordinates (loads.py).  Every function here is plain scalar Python over a
:class:`Params` record (``math`` calls: for a 4-state system numpy's call overhead would
dominate); with numba installed each is compiled (``numba.njit``, cached on disk), without
it the same source runs as Python.  The integrators call these functions: scipy's through
:func:`rhs` / :func:`jac`, the compiled Radau of :mod:`.radau` through :func:`rhs_into` /
:func:`jac_into`.  There is no second copy of the physics.

Effects: friction off -> mu = 0; contact_damping off -> damping = 0 and the K'' term of
Eq. (14) is never evaluated.
"""
from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from mechrepro.compiled import available, jit  # noqa: F401  (callers ask clearance.available())

from . import loads
from .geometry import FourBar


#: the constants of one configuration (SI), by name, for the compiled and the Python path alike
Params = namedtuple("Params", "l1 l2 l3 l0 omega P Fx Fy g m2 m3 R_pin R_bush K n_exp d_max C_max "
                              "mu v_eps clearance M11 M22 am damping")


def params(fb: FourBar, damping: bool) -> Params:
    M11, M22, am = loads.mass_terms(fb)
    return Params(*(float(v) for v in (
        fb.l1, fb.l2, fb.l3, fb.l0, fb.omega, fb.P, fb.F[0], fb.F[1], fb.g, fb.m2, fb.m3,
        fb.R_pin, fb.R_bush, fb.K_contact, fb.n_exp, fb.d_max, fb.C_max, fb.mu, fb.v_eps,
        fb.clearance, M11, M22, am, 1.0 if damping else 0.0)))


def flat(p: Params) -> np.ndarray:
    """``p`` as a float array, the form scipy's callbacks (:func:`rhs`, :func:`jac`) are
    given: numba types an array argument far faster than a 24-field record, on every
    callback of a scipy period."""
    return np.array(p, dtype=float)


@jit
def record(a):
    """The :class:`Params` of :func:`flat`'s array (or of a record: indexing reads both)."""
    return Params(a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7], a[8], a[9], a[10], a[11],
                  a[12], a[13], a[14], a[15], a[16], a[17], a[18], a[19], a[20], a[21], a[22],
                  a[23])


@jit
def contact(t, th3, ph2, w3, w2, p):
    """Force on the bushing (fx, fy), F_N, F_T and the geometry of Eqs. (5)-(15)."""
    c3, s3, c2, s2 = math.cos(th3), math.sin(th3), math.cos(ph2), math.sin(ph2)
    th1 = p.omega * t
    c1, s1 = math.cos(th1), math.sin(th1)
    ex = p.l1 * c1 - (p.l0 + p.l3 * c3 + p.l2 * c2)
    ey = p.l1 * s1 - (p.l3 * s3 + p.l2 * s2)
    edx = -p.l1 * p.omega * s1 - (-p.l3 * w3 * s3 - p.l2 * w2 * s2)
    edy = p.l1 * p.omega * c1 - (p.l3 * w3 * c3 + p.l2 * w2 * c2)
    e = math.hypot(ex, ey)                               # Eq. (6)
    delta = e - p.clearance                              # Eq. (8)
    if delta <= 0.0:
        return 0.0, 0.0, 0.0, 0.0, c3, s3, c2, s2, ex, ey, edx, edy, e, delta
    nx, ny = ex / e, ey / e                              # Eq. (7)
    tx, ty = -ny, nx
    vN = edx * nx + edy * ny                             # Eq. (9)
    vT = edx * tx + edy * ty + p.omega * p.R_pin - w2 * p.R_bush   # Eq. (10)
    FN = p.K * delta ** p.n_exp                          # Eq. (11), elastic part
    if p.damping != 0.0:
        x = delta / p.d_max
        K2 = p.C_max if x >= 1.0 else p.C_max * x * x * (3.0 - 2.0 * x)   # Eq. (14)
        FN += K2 * vN
    if FN < 0.0:
        FN = 0.0
    FT = 0.0
    if p.mu != 0.0:
        FT = p.mu * FN * vT / math.sqrt(vT * vT + p.v_eps * p.v_eps)   # Eq. (15)
    return (FN * nx + FT * tx, FN * ny + FT * ty, FN, FT, c3, s3, c2, s2, ex, ey, edx,
            edy, e, delta)

@jit
def rhs_into(t, y, p, out):
    """dy/dt of y = (theta3, phi2, dtheta3/dt, dphi2/dt) into ``out``: the equations of motion
    in minimal coordinates (Eq. 3 projected, see loads.py) with the load P at E towards F,
    the link weights, and the contact force J^T f plus the friction moment R_j F_T."""
    th3, ph2, w3, w2 = y[0], y[1], y[2], y[3]
    fx, fy, FN, FT, c3, s3, c2, s2, ex, ey, edx, edy, e, delta = contact(t, th3, ph2, w3, w2, p)
    exx, eyy = p.l0 + 0.5 * p.l3 * c3, 0.5 * p.l3 * s3
    dx, dy = p.Fx - exx, p.Fy - eyy
    dn = math.hypot(dx, dy)
    Px, Py = p.P * dx / dn, p.P * dy / dn
    Q3 = (0.5 * p.l3 * (-s3 * Px + c3 * Py)
          - p.g * (0.5 * p.m3 * p.l3 + p.m2 * p.l3) * c3)
    Q2 = -p.g * p.m2 * 0.5 * p.l2 * c2
    Q3 += p.l3 * (-s3 * fx + c3 * fy)
    Q2 += p.l2 * (-s2 * fx + c2 * fy) + p.R_bush * FT
    cd = c3 * c2 + s3 * s2
    sd = s3 * c2 - c3 * s2
    b3 = Q3 - p.am * sd * w2 * w2
    b2 = Q2 + p.am * sd * w3 * w3
    m12 = p.am * cd
    det = p.M11 * p.M22 - m12 * m12
    out[0] = w3
    out[1] = w2
    out[2] = (p.M22 * b3 - m12 * b2) / det
    out[3] = (p.M11 * b2 - m12 * b3) / det

@jit
def jac_into(t, y, p, J):
    """d rhs / d y into ``J``: the contact terms exact (stiffness, damping, friction through
    Eqs. 5-15), the slow, non-stiff parts (mass-matrix variation, velocity terms) left out
    -- they only affect Newton convergence, never the solution."""
    th3, ph2, w3, w2 = y[0], y[1], y[2], y[3]
    for i in range(4):
        for j in range(4):
            J[i, j] = 0.0
    J[0, 2] = 1.0
    J[1, 3] = 1.0
    fx, fy, FN, FT, c3, s3, c2, s2, ex, ey, edx, edy, e, delta = contact(t, th3, ph2, w3, w2, p)
    if delta <= 0.0 or FN <= 0.0:
        return
    nx, ny = ex / e, ey / e
    tx, ty = -ny, nx
    vN = edx * nx + edy * ny
    vTe = edx * tx + edy * ty
    vT = vTe + p.omega * p.R_pin - w2 * p.R_bush
    a = p.n_exp * p.K * delta ** (p.n_exp - 1.0)
    gx, gy = a * nx, a * ny                 # dFN/de
    hx, hy = 0.0, 0.0                       # dFN/d(edot)
    if p.damping != 0.0:
        x = delta / p.d_max
        if x < 1.0:
            K2 = p.C_max * x * x * (3.0 - 2.0 * x)
            dK2 = p.C_max * (6.0 * x - 6.0 * x * x) / p.d_max
        else:
            K2, dK2 = p.C_max, 0.0
        gx = gx + dK2 * vN * nx + K2 * vTe / e * tx
        gy = gy + dK2 * vN * ny + K2 * vTe / e * ty
        hx, hy = K2 * nx, K2 * ny
    v2 = p.v_eps * p.v_eps
    s = vT / math.sqrt(vT * vT + v2)
    ds = v2 / (vT * vT + v2) ** 1.5
    mu = p.mu
    dvx, dvy = -vN / e * tx, -vN / e * ty   # dvT/de
    ax = mu * (s * gx + FN * ds * dvx)      # dFT/de
    ay = mu * (s * gy + FN * ds * dvy)
    bx = mu * (s * hx + FN * ds * tx)       # dFT/d(edot)
    by = mu * (s * hy + FN * ds * ty)
    dFT_dw2 = mu * FN * ds * (-p.R_bush)
    # f = FN n + FT t: df/de (A), df/d(edot) (B)
    fe = FN / e
    te = FT / e
    A00 = nx * gx + fe * tx * tx + tx * ax - te * nx * tx
    A01 = nx * gy + fe * tx * ty + tx * ay - te * nx * ty
    A10 = ny * gx + fe * ty * tx + ty * ax - te * ny * tx
    A11 = ny * gy + fe * ty * ty + ty * ay - te * ny * ty
    B00 = nx * hx + tx * bx
    B01 = nx * hy + tx * by
    B10 = ny * hx + ty * bx
    B11 = ny * hy + ty * by
    l3, l2 = p.l3, p.l2
    Jb00, Jb01, Jb10, Jb11 = -l3 * s3, -l2 * s2, l3 * c3, l2 * c2
    D00, D01, D10, D11 = l3 * w3 * c3, l2 * w2 * c2, l3 * w3 * s3, l2 * w2 * s2
    # X = A (-Jb) + B D
    X00 = -(A00 * Jb00 + A01 * Jb10) + (B00 * D00 + B01 * D10)
    X01 = -(A00 * Jb01 + A01 * Jb11) + (B00 * D01 + B01 * D11)
    X10 = -(A10 * Jb00 + A11 * Jb10) + (B10 * D00 + B11 * D10)
    X11 = -(A10 * Jb01 + A11 * Jb11) + (B10 * D01 + B11 * D11)
    q00 = Jb00 * X00 + Jb10 * X10
    q01 = Jb00 * X01 + Jb10 * X11
    q10 = Jb01 * X00 + Jb11 * X10
    q11 = Jb01 * X01 + Jb11 * X11
    rb = p.R_bush
    q10 += rb * (-(ax * Jb00 + ay * Jb10) + (bx * D00 + by * D10))
    q11 += rb * (-(ax * Jb01 + ay * Jb11) + (bx * D01 + by * D11))
    # Y = B (-Jb); dQ_dw = Jb^T Y
    Y00 = -(B00 * Jb00 + B01 * Jb10)
    Y01 = -(B00 * Jb01 + B01 * Jb11)
    Y10 = -(B10 * Jb00 + B11 * Jb10)
    Y11 = -(B10 * Jb01 + B11 * Jb11)
    r00 = Jb00 * Y00 + Jb10 * Y10
    r01 = Jb00 * Y01 + Jb10 * Y11
    r10 = Jb01 * Y00 + Jb11 * Y10
    r11 = Jb01 * Y01 + Jb11 * Y11
    r10 += rb * (-(bx * Jb00 + by * Jb10))
    r11 += rb * (-(bx * Jb01 + by * Jb11))
    r01 += Jb00 * tx * dFT_dw2 + Jb10 * ty * dFT_dw2
    r11 += Jb01 * tx * dFT_dw2 + Jb11 * ty * dFT_dw2
    r11 += rb * dFT_dw2
    m12 = p.am * (c3 * c2 + s3 * s2)
    det = p.M11 * p.M22 - m12 * m12
    i00, i01, i11 = p.M22 / det, -m12 / det, p.M11 / det
    J[2, 0] = i00 * q00 + i01 * q10
    J[2, 1] = i00 * q01 + i01 * q11
    J[3, 0] = i01 * q00 + i11 * q10
    J[3, 1] = i01 * q01 + i11 * q11
    J[2, 2] = i00 * r00 + i01 * r10
    J[2, 3] = i00 * r01 + i01 * r11
    J[3, 2] = i01 * r00 + i11 * r10
    J[3, 3] = i01 * r01 + i11 * r11


@jit
def history(T, Y, p):
    """F_N, F_T, delta, v_T and the contact angle (not yet wrapped) at samples (T, Y)."""
    m = T.size
    out = np.empty((5, m))
    for k in range(m):
        th3, ph2, w3, w2 = Y[0, k], Y[1, k], Y[2, k], Y[3, k]
        fx, fy, FN, FT, c3, s3, c2, s2, ex, ey, edx, edy, e, delta = contact(
            T[k], th3, ph2, w3, w2, p)
        out[0, k] = FN
        out[1, k] = FT
        out[2, k] = delta
        if e:
            nx, ny = ex / e, ey / e
        else:
            nx, ny = 1.0, 0.0
        out[3, k] = edx * -ny + edy * nx + p.omega * p.R_pin - w2 * p.R_bush
        out[4, k] = math.atan2(ny, nx) - ph2
    return out


@jit
def rhs(t, y, a):
    """:func:`rhs_into` into a new array (the callback of scipy's integrators); ``a`` is
    :func:`flat`'s array (or the record itself)."""
    out = np.empty(4)
    rhs_into(t, y, record(a), out)
    return out


@jit
def jac(t, y, a):
    J = np.empty((4, 4))
    jac_into(t, y, record(a), J)
    return J
