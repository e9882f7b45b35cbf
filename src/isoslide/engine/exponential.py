"""Exact propagation of a linearly isolated flexible building with Coulomb contents (numba).

The scenes: a flexible superstructure of ``n`` floors on a linear isolator, contents whose friction
does not depend on speed (``phi`` at every speed) on any floor, one horizontal pulse given by its
formula, no vertical motion and no rocking (:func:`applies`).  Between two transitions of the
contents such a building is linear and time-invariant, driven by the ground and, while the contents
slide in the direction ``s``, by their constant friction on their floor::

    z' = A_c z + b p(tau) + s e          (c: the contents stuck or sliding)

with ``z = y[idx]`` the building's moving states (:func:`isoslide.engine.building.free_states`; the
state layout is :mod:`isoslide.engine.building_kernel`'s).  With ``A_c = V diag(L) W``
(:func:`isoslide.engine.free_phase.decompose`) the modal coordinates ``a = W z`` obey ``a_k' = L_k
a_k + beta_k p + s gamma_k`` (``beta = W b``, ``gamma = W e``), and over a stretch of length ``d`` on
which ``p(t) = sum_l e_l (t/d)^l``::

    a_k(d) = exp(L_k d) a_k(0) + beta_k sum_l e_l l! d phi_{l+1}(L_k d) + s gamma_k d phi_1(L_k d)

exactly (``phi_l`` the functions of exponential integrators).  The contents need no integration:
sliding, their absolute acceleration is ``-s phi``, so their speed relative to their floor is
``u'(t) = u'(0) + vF(0) - s phi t - Vg(t) - vF(t)`` (``vF`` the floor's speed relative to the
ground, ``Vg`` the ground's speed gained since, the polynomial's integral) and ``u`` likewise.

How it steps.  The pulse is interpolated on each step ``[tau, tau + h]`` by the Chebyshev
polynomial of degree :data:`DEGREE`, ``h`` chosen so that its two last coefficients (the error
estimate) stay within ``rtol`` (the pulse's peak is 1); the step ends at the pulse's breakpoints.
Near a transition the step is cut into equal sub-steps with ``|L_k| d <= THETA`` for every mode, at
whose ends the state is exact and the event functions and their rates are known: the stuck
contents' demand ``sig A_F - thr`` (``A_F`` their floor's absolute acceleration) and the sliding
contents' speed ``s u'``.  A sign change, or an interior peak of the demand whose cubic Hermite
estimate comes within 1 % of the limit, is located by safeguarded Newton on the exact propagator
to about ``1e-13 T_p``.

Away from the transitions the cost follows the slow modes, not the fastest.  Each mode ``k`` is
its quasi-static response to the pulse and the friction, ``q_k = -(beta_k p + s gamma_k)/L_k``,
plus a free vibration ``b_k`` whose modulus grows by at most ``|beta_k/L_k| int |p'|`` (``Re L_k
<= 0``).  On a step the fastest modes whose free vibrations' bound on the transitions' row stays
within :data:`BUDGET` of its scale are bounded rather than followed (:func:`_cut`), and the step is
cut into long sub-steps that follow only the fastest remaining mode.  A long sub-step, propagated
exactly by the same formula (:func:`_psi` for any ``|L_k d|``), is taken when the row's smooth part
(the slow modes and the fast ones' quasi-static responses; its cubic Hermite interpolant checked
against its exact value at the middle) stays away from the limit by the bound and
:data:`PEAK_MARGIN` (:func:`_coarse`); otherwise it is halved, down to the sub-steps above.  A stiff
superstructure whose fastest modes the contents barely excite then costs some of its slow modes'
sub-steps and its transitions' searches.

The transitions, the choice of modes at a stop (:func:`~isoslide.engine.building_kernel._select_modes`),
the settlement test (:func:`~isoslide.engine.building_kernel._settled`) and the results' layout
(:data:`~isoslide.engine.building_kernel.INT_RESULTS`, ``FLOAT_RESULTS``) are those of
:func:`isoslide.engine.building_kernel.run`.  Units: time ``T_p``, lengths ``a_p T_p^2``,
accelerations ``a_p``.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .. import jit_cache
from ..pulses import RECTANGULAR, SAMPLED, accel_at
from . import building
from . import building_kernel as bk
from . import free_phase
from .kernel import (ROOT_AT_TRIAL, ROOT_OPEN, _hermite_max, _next_breakpoint, _step_target, bracket_open,
                     bracket_step, hermite_root)

DEGREE = 7
"""Degree of the Chebyshev polynomial that interpolates the pulse on a step."""
THETA = 1.0
"""Largest ``|lambda| d`` of a sub-step ``d`` over the modes."""
H_FREE = 0.25
"""Longest step after the pulse (units of T_p): how often settlement is tested."""
H_START = 0.05
"""First step, and the longest one after a transition (units of T_p)."""
PEAK_MARGIN = 1e-2
"""An interior peak of the stuck demand is located when its Hermite estimate comes within this
fraction of the limit."""
BUDGET = 0.25
"""The fastest modes are bounded on a step while their free vibration's bound on the stuck demand
stays within this fraction of its limit (of the limit times the step on the sliding speed)."""
MAX_HALVINGS = 40
"""Most halvings of a long sub-step (far more than any ratio of fastest to slowest mode needs)."""
_COS = np.array([[math.cos(k * (math.pi * (j + 0.5) / (DEGREE + 1))) for k in range(DEGREE + 1)]
                 for j in range(DEGREE + 1)])
"""``cos(k theta_j)`` at the Chebyshev nodes ``theta_j = pi (j + 1/2)/(DEGREE + 1)`` (:func:`_chebyshev`)."""
_FACT = np.array([math.factorial(k) for k in range(DEGREE + 3)], dtype=np.float64)
SERIES_LIMIT = 4.0
"""``|lambda d|`` from which the ``phi`` functions come from ``exp`` by the recurrence upwards (:func:`_psi`)."""
_TERMS = 64
_INV = np.array([1.0 / (DEGREE + 1 + i) for i in range(_TERMS)])


def applies(P: np.ndarray, code: int) -> bool:
    """Whether :func:`run` integrates the scene of the kernel parameters ``P`` and the pulse ``code``.

    A linear isolator, a flexible superstructure, friction independent of speed, no vertical motion,
    contents that slide without rocking and a pulse given by its formula (not a sampled record).
    """
    return (P[bk.P_KIND] == bk.KIND_LINEAR and P[bk.P_FLEX] != 0.0 and P[bk.P_COULOMB] == 1.0
            and P[bk.P_ZAMP] == 0.0 and P[bk.P_ROCK] == 0.0 and code != SAMPLED)


def arrays(P: np.ndarray, modal: tuple) -> tuple:
    """The arrays :func:`run` reads, for a scene where :func:`applies`.

    Parameters
    ----------
    P : ndarray
        The kernel's parameters (:func:`isoslide.engine.building.parameters`).
    modal : tuple of ndarray
        The free phase's modal data (:func:`isoslide.engine.building.modal_data`): the stuck
        configuration's modes.

    Returns
    -------
    tuple of ndarray
        ``(idx, L0, V0, W0, beta0, L1, V1, W1, beta1, gamma1, rows, consts)``: the moving states; the
        stuck configuration's modes (``L0, V0, W0``) and the sliding one's (``L1, V1, W1``,
        :func:`isoslide.engine.free_phase.modes`); the pulse's modal forcing in each (``beta0``,
        ``beta1``) and a slide forward's friction's (``gamma1``); the rows of
        :func:`linear_arrays`; the sliding floor acceleration's constant part and the friction level
        ``phi`` (``consts``).

    Raises
    ------
    ValueError
        If a configuration has no trustworthy modes (a growing mode, or eigenvectors whose condition
        number exceeds :data:`isoslide.engine.building_kernel.FREE_MODES_COND`).
    """
    n = int(P[bk.P_N])
    idx = np.array(building.free_states(P, False), dtype=np.int64)
    Wm, Vm, Lm = modal[0], modal[2], modal[3]
    if Lm.size != idx.size:
        raise ValueError("the stuck contents' configuration has no trustworthy modes")
    V0, W0 = np.ascontiguousarray(Vm[idx, :]), np.ascontiguousarray(Wm[:, idx])
    A1, b0, b1, e1, rows, c1 = linear_arrays(P, idx, bk.state_size(n))
    L1, V1, W1, cond, grows = free_phase.modes(A1)
    if grows or not cond <= bk.FREE_MODES_COND:
        raise ValueError("the sliding contents' configuration has no trustworthy modes")
    return (idx, Lm, V0, W0, W0 @ b0.astype(np.complex128), L1, V1, W1, W1 @ b1.astype(np.complex128),
            W1 @ e1.astype(np.complex128), rows, np.array([c1, P[bk.P_THR]]))


@njit(cache=True)
def _configuration(P, idx, ny, bm):
    """``(A, b, e, row, c)`` of one configuration (``bm`` 0 stuck, 1 sliding forward).

    ``z' = A z + b p + e`` for the moving states ``z = y[idx]`` and the floor's absolute acceleration
    ``row . z + c``: ``A`` and ``e`` from :func:`isoslide.engine.building_kernel.affine_rates`, ``b``
    from its :func:`~isoslide.engine.building_kernel.deriv` under a rectangular pulse's unit
    acceleration, ``row`` from ``_accels`` at unit states (both affine in the state and the pulse).
    """
    m = idx.shape[0]
    n = int(P[bk.P_N])
    none = np.zeros(0)
    A, e = bk.affine_rates(bm, P, RECTANGULAR, none, idx, ny)
    b = np.zeros(m)
    row = np.zeros(m)
    y = np.zeros(ny)
    out = np.zeros(ny)
    floors = np.zeros(max(n, 1))
    c = bk._accels(bm, 0.0, 0.0, 1.0, y, P, floors)[1]
    bk.deriv(bm, 0.0, 0.5, y, P, RECTANGULAR, none, out)   # the rectangular pulse: p = 1
    for i in range(m):
        b[i] = out[idx[i]] - e[i]
    for j in range(m):
        y[:] = 0.0
        y[idx[j]] = 1.0
        row[j] = bk._accels(bm, 0.0, 0.0, 1.0, y, P, floors)[1] - c
    return A, b, e, row, c


@njit(cache=True)
def linear_arrays(P, idx, ny):
    """The sliding configuration's matrix and both configurations' forcing and rows.

    Returns ``(A1, b0, b1, e1, rows, c1)``: ``z' = A1 z + b1 p + e1`` with the contents sliding forward
    (:func:`_configuration`; its modes are :func:`isoslide.engine.free_phase.modes`'), ``b0`` the
    pulse's forcing with them stuck; ``rows`` (4, n_states) the floor's absolute acceleration stuck
    and sliding (its linear part), its speed and its displacement relative to the ground; ``c1`` the
    sliding floor acceleration's constant part (a slide forward).
    """
    m = idx.shape[0]
    n = int(P[bk.P_N])
    _, b0, _, row0, _ = _configuration(P, idx, ny, 0.0)
    A1, b1, e1, row1, c1 = _configuration(P, idx, ny, 1.0)
    rows = np.zeros((4, m))
    fl = int(P[bk.P_FLOOR]) - 1
    roof = P[bk.P_ROOF] != 0.0
    for i in range(m):
        rows[0, i] = row0[i]
        rows[1, i] = row1[i]
        s = idx[i]
        if s == bk.Y_XD or (roof and s == bk.Y_XS + n + fl):
            rows[2, i] = 1.0
        if s == bk.Y_X or (roof and s == bk.Y_XS + fl):
            rows[3, i] = 1.0
    return A1, b0, b1, e1, rows, c1


@njit(cache=True)
def _chebyshev(code, params, tau, h, c):
    """Chebyshev coefficients ``c`` of the pulse on ``[tau, tau + h]`` (``x = 2 t/h - 1``); returns the error estimate."""
    q = DEGREE + 1
    for k in range(q):
        c[k] = 0.0
    for j in range(q):
        pj = accel_at(code, params, tau + 0.5 * h * (_COS[j, 1] + 1.0))
        for k in range(q):
            c[k] += pj * _COS[j, k]
    for k in range(q):
        c[k] *= 2.0 / q
    c[0] *= 0.5
    return abs(c[DEGREE]) + abs(c[DEGREE - 1])


@njit(cache=True)
def _local(c, alpha, beta, e, t0, t1, t2):
    """Monomial coefficients ``e`` in ``r`` of ``sum_k c_k T_k(alpha + beta r)`` (``t0..t2`` scratch)."""
    q = DEGREE + 1
    for l in range(q):
        e[l] = 0.0
        t0[l] = 0.0
        t1[l] = 0.0
    t0[0] = 1.0
    t1[0] = alpha
    t1[1] = beta
    for l in range(q):
        e[l] += c[0] * t0[l] + c[1] * t1[l]
    for k in range(2, q):
        for l in range(q):
            v = 2.0 * alpha * t1[l] - t0[l]
            if l > 0:
                v += 2.0 * beta * t1[l - 1]
            t2[l] = v
        for l in range(q):
            e[l] += c[k] * t2[l]
            t0[l] = t1[l]
            t1[l] = t2[l]


@njit(cache=True, inline="always")
def _series_terms(az2):
    """Terms of the series of ``phi_{DEGREE+1}(z)`` that reach round-off for ``|z|^2 = az2 < SERIES_LIMIT^2``.

    The term ``i`` is ``z^i/(i + DEGREE + 1)!``; the counts (for ``|z|`` up to 1/2, 1, 2 and 4) make
    the first term left out smaller than ``1e-17`` times the first.
    """
    if az2 <= 0.25:
        return 13
    if az2 <= 1.0:
        return 16
    if az2 <= 4.0:
        return 20
    return 26


@njit(cache=True)
def _psi(lam, d, psi):
    """``psi[k, l] = l! d phi_{l+1}(lam_k d)`` for ``l = 0 .. DEGREE`` and ``psi[k, DEGREE + 1] = exp(lam_k d)``.

    Any ``|z| = |lam_k d|``: below :data:`SERIES_LIMIT`, the series of ``phi_{DEGREE+1}(z)`` (to
    round-off) and the recurrence ``phi_l = z phi_{l+1} + 1/l!`` downwards (``exp(z)`` itself beyond
    :data:`THETA`); from it on, ``phi_0 = exp(z)`` and the recurrence upwards, ``phi_{l+1} = (phi_l -
    1/l!)/z``.  Each recurrence multiplies its errors by ``|z|`` (downwards) or about ``l/|z|``
    (upwards) per step, so the switch keeps both within some ``1e-14`` of each value.
    """
    q = DEGREE + 1
    for k in range(lam.shape[0]):
        if k > 0 and lam[k] == np.conj(lam[k - 1]):
            # the modes of a real system come in exactly conjugate pairs (free_phase.decompose)
            for l in range(q + 1):
                psi[k, l] = np.conj(psi[k - 1, l])
            continue
        z = lam[k] * d
        az2 = z.real * z.real + z.imag * z.imag
        if az2 < SERIES_LIMIT * SERIES_LIMIT:
            term = (1.0 + 0.0j) / _FACT[q]
            acc = term
            for i in range(1, _series_terms(az2)):
                term = term * z * _INV[i]
                acc += term
            phi = acc
            for l in range(q - 1, -1, -1):
                psi[k, l] = _FACT[l] * d * phi
                phi = z * phi + 1.0 / _FACT[l]
            psi[k, q] = phi if az2 <= THETA * THETA else np.exp(z)
            continue
        rz = 1.0 / z
        phi = np.exp(z)
        psi[k, q] = phi
        for l in range(q):
            phi = (phi - 1.0 / _FACT[l]) * rz
            psi[k, l] = _FACT[l] * d * phi


@njit(cache=True)
def _advance(a0, lam, beta, gam, s, e, r, psi, a):
    """Modal coordinates ``a`` after ``r`` of a sub-step whose pulse is ``sum_l e_l (t/d)^l`` (``psi`` at ``r d``)."""
    q = DEGREE + 1
    for k in range(a0.shape[0]):
        if k > 0 and lam[k] == np.conj(lam[k - 1]):
            # the twin of a conjugate pair (free_phase.decompose): its coordinate is the conjugate
            a[k] = np.conj(a[k - 1])
            continue
        f = 0.0 + 0.0j
        rl = 1.0
        for l in range(q):
            f += e[l] * rl * psi[k, l]
            rl *= r
        a[k] = psi[k, q] * a0[k] + beta[k] * f + s * gam[k] * psi[k, 0]


@njit(cache=True)
def _row(C, a):
    acc = 0.0
    for k in range(a.shape[0]):
        acc += (C[k] * a[k]).real
    return acc


@njit(cache=True)
def _rate_row(C, a, lam, beta, gam, s, p):
    acc = 0.0
    for k in range(a.shape[0]):
        acc += (C[k] * (lam[k] * a[k] + beta[k] * p + s * gam[k])).real
    return acc


@njit(cache=True)
def _poly(e, r):
    acc = 0.0
    for l in range(DEGREE, -1, -1):
        acc = acc * r + e[l]
    return acc


@njit(cache=True)
def _ground(e, r, d):
    """``(Vg, Dg)``: the ground's speed and displacement gained over ``r d`` of a sub-step of pulse ``e``."""
    v = 0.0
    x = 0.0
    rl = r
    for l in range(DEGREE + 1):
        v += e[l] * rl / (l + 1)
        x += e[l] * rl * r / ((l + 1) * (l + 2))
        rl *= r
    return d * v, d * d * x


@njit(cache=True)
def _dpoly(e, r):
    """Derivative in ``r`` of ``sum_l e_l r^l``."""
    acc = 0.0
    for l in range(DEGREE, 0, -1):
        acc = acc * r + l * e[l]
    return acc


@njit(cache=True)
def _variation(e):
    """A bound on ``int |p'|`` over a sub-step whose pulse is ``sum_l e_l r^l`` (``r`` from 0 to 1)."""
    acc = 0.0
    for l in range(1, DEGREE + 1):
        acc += l * abs(e[l])
    return acc


@njit(cache=True, inline="always")
def _mag(z):
    """``|z|`` of a complex number, without the care for overflow of ``abs`` (``hypot``)."""
    return math.sqrt(z.real * z.real + z.imag * z.imag)


@njit(cache=True, inline="always")
def _quasi_static(k, lam, beta, gam, bm, p):
    """Mode ``k``'s quasi-static response ``q_k = -(beta_k p + bm gamma_k)/lambda_k`` to the pulse ``p`` and the friction."""
    return -(beta[k] * p + bm * gam[k]) / lam[k]


@njit(cache=True, inline="always")
def _free_bound(k, q, a, absC, bl, var):
    """``|C_k| (|a_k - q_k| + |beta_k/lambda_k| var)``: mode ``k``'s free vibration's bound on a row (:func:`_smooth`)."""
    return absC[k] * (_mag(a[k] - q) + bl[k] * var)


@njit(cache=True)
def _smooth(C, absC, a, lam, beta, gam, bl, bm, s, p, dp, var, bound):
    """The row ``C`` of the modal state ``a`` with the free vibration of its ``s`` fastest modes set apart.

    A mode ``k < s`` is split as ``a_k = q_k + b_k``, ``q_k = -(beta_k p + bm gamma_k)/lambda_k`` its
    quasi-static response to the pulse ``p`` and the friction; then ``b_k' = lambda_k b_k + beta_k
    p'/lambda_k`` and, as ``Re lambda_k <= 0``, ``|b_k|`` grows on a stretch by at most ``|beta_k/lambda_k|
    int |p'|``.  Returns ``(G, G', B)``: ``G = sum_{k >= s} Re(C_k a_k) + sum_{k < s} Re(C_k q_k)``,
    its rate (``dp = p'``), and (with ``bound``; else 0) ``B = sum_{k < s} |C_k| (|b_k| +
    |beta_k/lambda_k| var)``, which bounds ``|row - G|`` from here over a stretch where ``int |p'| <=
    var``.  ``absC = |C|`` and ``bl = |beta/lambda|``.
    """
    G = 0.0
    R = 0.0
    B = 0.0
    for k in range(a.shape[0]):
        if k < s:
            q = _quasi_static(k, lam, beta, gam, bm, p)
            G += (C[k] * q).real
            R -= (C[k] * beta[k] * dp / lam[k]).real
            if bound:
                B += _free_bound(k, q, a, absC, bl, var)
        else:
            G += (C[k] * a[k]).real
            R += (C[k] * (lam[k] * a[k] + beta[k] * p + bm * gam[k])).real
    return G, R, B


@njit(cache=True)
def _cut(bm, h, a, lam, beta, gam, bl, absC, e, budget, nsub):
    """How many of the fastest modes a step ``h`` bounds instead of following: ``(s, n_long)``.

    The modes are taken fastest first while the bound of their free vibration on the row ``C``
    (:func:`_smooth`, with ``e`` the whole step's pulse; ``absC = |C|``, ``bl = |beta/lambda|``) stays
    within ``budget``; the long sub-steps
    then follow the fastest remaining mode (``|lambda_s| D <= THETA``; one when none remains).
    ``(0, nsub)``, the sub-steps of every mode, where that saves nothing.
    """
    if budget <= 0.0:
        return 0, nsub
    var = _variation(e)
    m = a.shape[0]
    acc = 0.0
    s = 0
    for k in range(m):
        if lam[k] == 0.0:
            break
        acc += _free_bound(k, _quasi_static(k, lam, beta, gam, bm, e[0]), a, absC, bl, var)
        if acc > budget:
            break
        s = k + 1
    if s == 0:
        return 0, nsub
    nc = 1 if s == m else max(1, int(math.ceil(h * abs(lam[s]) / THETA)))
    if 2 * nc >= nsub:
        return 0, nsub
    return s, nc


@njit(cache=True)
def _coarse(bm, s, D, a0, u0, ud0, lam, beta, gam, bl, C, absC, Cv, Cd, phi, thr, e, psiD, psiM, am, a1):
    """One long sub-step ``D`` whose ``s`` fastest modes are bounded, if no transition can fall in it.

    ``C`` is the row the transitions read (the stuck demand's, or the sliding speed's), ``absC`` its
    moduli and ``bl = |beta/lambda|``.  The row is split by
    :func:`_smooth` into a smooth part, known with its rate at both ends, and a bounded rest.  The
    sub-step is clear when the smooth part's cubic Hermite interpolant, checked against its exact
    value at the middle, stays away from the limit by the bound and :data:`PEAK_MARGIN`.  Returns
    ``(clear, u, u')``, the contents' state at the end, with the modal state there in ``a1``.
    """
    _advance(a0, lam, beta, gam, bm, e, 1.0, psiD, a1)
    _advance(a0, lam, beta, gam, bm, e, 0.5, psiM, am)
    var = _variation(e)
    p0 = e[0]
    p1 = _poly(e, 1.0)
    pm = _poly(e, 0.5)
    G0, R0, B = _smooth(C, absC, a0, lam, beta, gam, bl, bm, s, p0, e[1] / D, var, True)
    G1, R1, _ = _smooth(C, absC, a1, lam, beta, gam, bl, bm, s, p1, _dpoly(e, 1.0) / D, var, False)
    Gm, _, _ = _smooth(C, absC, am, lam, beta, gam, bl, bm, s, pm, _dpoly(e, 0.5) / D, var, False)
    if bm == 0.0:
        if abs(Gm - 0.5 * (G0 + G1) - 0.125 * D * (R0 - R1)) > 0.25 * PEAK_MARGIN * thr:
            return False, u0, ud0
        for sig in (1.0, -1.0):
            if _hermite_max(sig * G0 - thr, sig * R0, sig * G1 - thr, sig * R1, D) + B > -PEAK_MARGIN * thr:
                return False, u0, ud0
        return True, u0, 0.0
    w0 = ud0 + _row(Cv, a0)
    Vg1, Dg1 = _ground(e, 1.0, D)
    Vgm, _ = _ground(e, 0.5, D)
    F0 = bm * (w0 - G0)
    F1 = bm * (w0 - bm * phi * D - Vg1 - G1)
    Fm = bm * (w0 - 0.5 * bm * phi * D - Vgm - Gm)
    S0 = bm * (-bm * phi - p0 - R0)
    S1 = bm * (-bm * phi - p1 - R1)
    scale = max(abs(F0), abs(F1))
    if abs(Fm - 0.5 * (F0 + F1) - 0.125 * D * (S0 - S1)) > 0.25 * PEAK_MARGIN * scale:
        return False, u0, ud0
    if -_hermite_max(-F0, -S0, -F1, -S1, D) - B <= PEAK_MARGIN * scale:
        return False, u0, ud0
    u1 = u0 + w0 * D - 0.5 * bm * phi * D * D - Dg1 - (_row(Cd, a1) - _row(Cd, a0))
    return True, u1, w0 - bm * phi * D - Vg1 - _row(Cv, a1)


# the quantities at a point of a sub-step: (AF, AF', u, u')
@njit(cache=True)
def _point(bm, r, d, a0, u0, w0, dF0, lam, beta, gam, CF, Cv, Cd, afc, phi, e, psi, a):
    """Modal state ``a`` at ``r d`` into a sub-step and ``(AF, AF', u, u')`` there.

    ``a0`` the modal state at the sub-step's start, ``u0`` the contents' displacement there, ``w0``
    their speed relative to the ground and ``dF0`` their floor's displacement relative to the ground.
    """
    _psi(lam, r * d, psi)
    _advance(a0, lam, beta, gam, bm, e, r, psi, a)
    p = _poly(e, r)
    AF = _row(CF, a) + bm * afc
    dAF = _rate_row(CF, a, lam, beta, gam, bm, p)
    if bm == 0.0:
        return AF, dAF, u0, 0.0
    t = r * d
    Vg, Dg = _ground(e, r, d)
    ud = w0 - bm * phi * t - Vg - _row(Cv, a)
    u = u0 + w0 * t - 0.5 * bm * phi * t * t - Dg - (_row(Cd, a) - dF0)
    return AF, dAF, u, ud


@njit(cache=True)
def _event(kind, sig, bm, r, d, a0, u0, w0, dF0, lam, beta, gam, CF, Cv, Cd, afc, phi, thr, e, psi, a):
    """Event ``kind`` at ``r`` of a sub-step: 0 the stuck demand ``sig A_F - thr``, 1 its rate, 2 the speed ``bm u'``.

    Returns ``(g, dg/dt)`` (the rate's derivative not given: NaN) and the state ``(u, u')`` there.
    """
    AF, dAF, u, ud = _point(bm, r, d, a0, u0, w0, dF0, lam, beta, gam, CF, Cv, Cd, afc, phi, e, psi, a)
    if kind == 0:
        return sig * AF - thr, sig * dAF, u, ud
    if kind == 1:
        return sig * dAF, math.nan, u, ud
    return bm * ud, -bm * AF - phi, u, ud


@njit(cache=True)
def _locate(kind, sig, bm, lo, glo, hi, ghi, guess, tau, d, a0, u0, w0, dF0, lam, beta, gam, CF, Cv, Cd, afc, phi,
            thr, e, psi, a):
    """Root of the event ``kind`` in ``(lo, hi]`` (lengths into the sub-step, signs of ``glo``, ``ghi`` opposite).

    Safeguarded Newton (regula falsi without a rate) to ``1e-13 max(1, |tau|)``.  Returns ``(t, u, u')``
    with the modal state at the root in ``a``.
    """
    lo, glo, hi, ghi, side, tol, h = bracket_open(tau, guess, lo, glo, hi, ghi)
    state = ROOT_OPEN
    u = u0
    ud = 0.0
    for _it in range(100):
        g, dg, u, ud = _event(kind, sig, bm, h / d, d, a0, u0, w0, dF0, lam, beta, gam, CF, Cv, Cd, afc, phi, thr, e,
                              psi, a)
        state, h, lo, glo, hi, ghi, side = bracket_step(h, g, dg, lo, glo, hi, ghi, side, tol)
        if state != ROOT_OPEN:
            break
    res = h if state == ROOT_AT_TRIAL else hi
    _, _, u, ud = _event(kind, sig, bm, res / d, d, a0, u0, w0, dF0, lam, beta, gam, CF, Cv, Cd, afc, phi, thr, e, psi,
                         a)
    return res, u, ud


@njit(cache=True)
def _full_state(a, V, idx, u, ud, y):
    """The kernel's state ``y`` from the modal coordinates and the contents' ``(u, u')``."""
    for i in range(y.shape[0]):
        y[i] = 0.0
    for i in range(idx.shape[0]):
        acc = 0.0
        for k in range(a.shape[0]):
            acc += (V[i, k] * a[k]).real
        y[idx[i]] = acc
    y[y.shape[0] - 3] = u
    y[y.shape[0] - 2] = ud


@njit(cache=True)
def run(P, code, params, breakpoints, tau_start, tau_end, tau_stop, h_max, rtol, settle, max_steps, idx, L0, V0, W0, beta0,
        L1, V1, W1, beta1, gamma1, rows, consts, Wm, Cm, Vm, Lm, Wh, Ch, Vh, Lh):
    """Propagate one scene of :func:`applies` from rest at ``tau_start`` (see the module docstring).

    Arguments as :func:`isoslide.engine.building_kernel.run` (no history, no Runge-Kutta settings;
    ``h_max`` the longest step, units of T_p), then the arrays of :func:`arrays` and the free phase's
    modal data.  Returns ``(ints, floats, hist)`` in :func:`isoslide.engine.building_kernel.run`'s
    layout (no history rows); ``steps`` counts the sub-steps (the long ones tried too), the exact
    free steps and the trials of the root searches.
    """
    ny = Vm.shape[0]
    m = idx.shape[0]
    thr = P[bk.P_HOLD]
    phi = consts[1]
    y = np.zeros(ny)
    a = np.zeros(m, dtype=np.complex128)
    a0 = np.zeros(m, dtype=np.complex128)
    a1 = np.zeros(m, dtype=np.complex128)
    psi = np.zeros((m, DEGREE + 2), dtype=np.complex128)
    psi_tab = np.zeros((MAX_HALVINGS + 1, m, DEGREE + 2), dtype=np.complex128)
    stack_i = np.zeros(MAX_HALVINGS + 2, dtype=np.int64)
    have = np.zeros(MAX_HALVINGS + 1, dtype=np.bool_)
    stack_l = np.zeros(MAX_HALVINGS + 2, dtype=np.int64)
    a_mid = np.zeros(m, dtype=np.complex128)
    c = np.zeros(DEGREE + 1)
    e = np.zeros(DEGREE + 1)
    t0 = np.zeros(DEGREE + 1)
    t1 = np.zeros(DEGREE + 1)
    t2 = np.zeros(DEGREE + 1)
    CF0 = rows[0].astype(np.complex128) @ V0
    CF1 = rows[1].astype(np.complex128) @ V1
    Cv0 = rows[2].astype(np.complex128) @ V0
    Cv1 = rows[2].astype(np.complex128) @ V1
    Cd0 = rows[3].astype(np.complex128) @ V0
    Cd1 = rows[3].astype(np.complex128) @ V1
    gam0 = np.zeros(m, dtype=np.complex128)
    # moduli the bounds of the fastest modes read
    absCF0 = np.abs(CF0)
    absCv1 = np.abs(Cv1)
    bl0 = np.abs(beta0 / L0)
    bl1 = np.abs(beta1 / L1)
    wmax0 = np.max(np.abs(L0))
    wmax1 = np.max(np.abs(L1))
    afc = consts[0]
    limits = np.array([thr, 0.0])
    offsets = np.zeros((2, 2))
    a_x = np.zeros(Wm.shape[0], dtype=np.complex128)
    a_y = np.zeros(Wm.shape[0], dtype=np.complex128)
    tau = tau_start
    bm = 0.0
    u = 0.0
    ud = 0.0
    umax = 0.0
    tpeak = tau_start
    upeak = 0.0
    xmax = 0.0
    vmax = 0.0
    steps = 0
    events = 0
    settled = False
    slipped = False
    modes = 1
    just = False
    ib = 0
    h = H_START
    while True:
        modes |= 1 << bk.block_mode(bm)
        lam, V, W, beta, gam, CF, Cv, Cd = (L0, V0, W0, beta0, gam0, CF0, Cv0, Cd0) if bm == 0.0 else \
            (L1, V1, W1, beta1, gamma1, CF1, Cv1, Cd1)
        # the row of the transitions, its moduli and the modes' |beta/lambda|
        C, absC, bl = (CF0, absCF0, bl0) if bm == 0.0 else (Cv1, absCv1, bl1)
        # --- the mode at the accepted point (round-off past a limit) ---------------------
        if bm == 0.0 and abs(_row(CF, a)) > thr:
            _full_state(a, V, idx, u, 0.0, y)
            nb, _ = bk._select_modes(bm, 0.0, True, False, tau, y, P, code, params)
            if nb != bm:
                bm = nb
                events += 1
                slipped = True
                just = True
                free_phase.modal_coordinates(W1, y, 0, a)
                continue
        if tau >= tau_end and bm == 0.0:
            _full_state(a, V, idx, u, 0.0, y)
            if bk._settled(bm, 0.0, y, P, Wm, Cm, Wh, Ch):
                settled = True
                if settle:
                    break
        if tau >= tau_stop or steps > max_steps:
            break
        if tau >= tau_end and bm == 0.0:
            # the free phase: one exact step as long as its bound proves the contents stay stuck
            taken, tau = free_phase.exact_step(Wm, Cm, Vm, Lm, y, -1, False, 0.0, P[bk.P_KD], limits, offsets, a_x,
                                               a_y, tau, tau_stop, THETA / wmax0, False)
            if taken:
                steps += 1
                free_phase.modal_coordinates(W0, y, 0, a)
                xmax = max(xmax, abs(y[bk.Y_X]))
                continue
        # --- the step: the pulse's polynomial within rtol, the step ending at a breakpoint --------
        ib = _next_breakpoint(breakpoints, ib, tau)
        target = min(_step_target(breakpoints, ib, tau_stop), tau + h_max)
        if tau < tau_end:
            target = min(target, tau_end)
            h = min(h, target - tau)
            for _k in range(60):
                err = _chebyshev(code, params, tau, h, c)
                if err <= rtol:
                    break
                h *= max(0.2, 0.9 * (rtol / err) ** (1.0 / DEGREE))
            hnext = h * min(4.0, 0.9 * (rtol / max(err, 1e-300)) ** (1.0 / DEGREE))
        else:
            h = min(H_FREE, target - tau)
            for k in range(DEGREE + 1):
                c[k] = 0.0
            hnext = H_FREE
        wmax = wmax0 if bm == 0.0 else wmax1
        nsub = max(1, int(math.ceil(h * wmax / THETA)))
        # --- the fastest modes bounded where their vibration is small: long sub-steps ---------
        s = 0
        nc = nsub
        if nsub > 2:
            _local(c, -1.0, 2.0, e, t0, t1, t2)
            budget = BUDGET * thr if bm == 0.0 else BUDGET * thr * h
            s, nc = _cut(bm, h, a, lam, beta, gam, bl, absC, e, budget, nsub)
        # halvings of a long sub-step down to the sub-steps that follow every mode
        nlev = 0
        if s > 0:
            while h / (nc << nlev) * wmax > THETA:
                nlev += 1
        have[:nlev + 1] = False   # each level's psi computed when first needed
        ntot = nc << nlev
        d = h / ntot
        psi_d = psi_tab[nlev]
        # --- the sub-steps -----------------------------------------------------------------
        found = -1
        sig_found = 0.0
        t_found = 0.0
        for j in range(nc):
            stack_i[0] = j
            stack_l[0] = 0
            depth = 1
            while depth > 0:
                depth -= 1
                i = stack_i[depth]
                lev = stack_l[depth]
                if lev < nlev:
                    # a long sub-step: taken if clear, else its halves in turn
                    clear = False
                    if not just:
                        nint = nc << lev
                        for lv in (lev, lev + 1):
                            if not have[lv]:
                                _psi(lam, h / (nc << lv), psi_tab[lv])
                                have[lv] = True
                        _local(c, -1.0 + 2.0 * i / nint, 2.0 / nint, e, t0, t1, t2)
                        clear, u1, ud1 = _coarse(bm, s, h / nint, a, u, ud, lam, beta, gam, bl, C, absC, Cv, Cd, phi,
                                                 thr, e, psi_tab[lev], psi_tab[lev + 1], a_mid, a1)
                        steps += 1
                    if clear:
                        if bm != 0.0:
                            u = u1
                            ud = ud1
                            vmax = max(vmax, abs(ud))
                        for k in range(m):
                            a[k] = a1[k]
                        xmax = max(xmax, abs(_row(V[0], a)))
                    else:
                        stack_i[depth] = 2 * i + 1
                        stack_l[depth] = lev + 1
                        stack_i[depth + 1] = 2 * i
                        stack_l[depth + 1] = lev + 1
                        depth += 2
                    continue
                if not have[nlev]:
                    _psi(lam, d, psi_d)
                    have[nlev] = True
                _local(c, -1.0 + 2.0 * i / ntot, 2.0 / ntot, e, t0, t1, t2)
                for k in range(m):
                    a0[k] = a[k]
                w0 = ud + _row(Cv, a0)
                dF0 = _row(Cd, a0)
                p0 = e[0]
                AF0 = _row(CF, a0) + bm * afc
                dAF0 = _rate_row(CF, a0, lam, beta, gam, bm, p0)
                _advance(a0, lam, beta, gam, bm, e, 1.0, psi_d, a1)
                steps += 1
                p1 = _poly(e, 1.0)
                AF1 = _row(CF, a1) + bm * afc
                dAF1 = _rate_row(CF, a1, lam, beta, gam, bm, p1)
                if bm != 0.0:
                    Vg, Dg = _ground(e, 1.0, d)
                    ud1 = w0 - bm * phi * d - Vg - _row(Cv, a1)
                if bm == 0.0:
                    best = math.inf
                    for sig in (1.0, -1.0):
                        g0 = sig * AF0 - thr
                        r0 = sig * dAF0
                        g1 = sig * AF1 - thr
                        r1 = sig * dAF1
                        if g1 > 0.0:
                            if g0 >= 0.0:
                                ts = 0.0
                            else:
                                ts, _, _ = _locate(0, sig, bm, 0.0, g0, d, g1, hermite_root(g0, r0, g1, r1, d), tau, d,
                                                   a0, u, w0, dF0, lam, beta, gam, CF, Cv, Cd, afc, phi, thr, e, psi, a)
                                steps += 1
                        elif r0 > 0.0 and r1 < 0.0 and _hermite_max(g0, r0, g1, r1, d) >= -PEAK_MARGIN * thr:
                            tm, _, _ = _locate(1, sig, bm, 0.0, r0, d, r1, -1.0, tau, d, a0, u, w0, dF0, lam, beta, gam,
                                               CF, Cv, Cd, afc, phi, thr, e, psi, a)
                            gm, _, _, _ = _event(0, sig, bm, tm / d, d, a0, u, w0, dF0, lam, beta, gam, CF, Cv, Cd, afc,
                                                 phi, thr, e, psi, a)
                            steps += 1
                            if gm <= 0.0:
                                continue
                            ts, _, _ = _locate(0, sig, bm, 0.0, g0, tm, gm, -1.0, tau, d, a0, u, w0, dF0, lam, beta, gam,
                                               CF, Cv, Cd, afc, phi, thr, e, psi, a)
                        else:
                            continue
                        if ts < best:
                            best = ts
                            found = 0
                            sig_found = sig
                    if found >= 0:
                        t_found = best
                else:
                    f1 = bm * ud1
                    if f1 <= 0.0:
                        f0 = bm * ud
                        r1 = -bm * AF1 - phi
                        if just or f0 <= 0.0:
                            # the slide began at this sub-step's start: find a point of positive speed first
                            lo = d
                            glo = f1
                            for _k in range(200):
                                lo *= 0.5
                                glo, _, _, _ = _event(2, 0.0, bm, lo / d, d, a0, u, w0, dF0, lam, beta, gam, CF, Cv, Cd,
                                                      afc, phi, thr, e, psi, a)
                                steps += 1
                                if glo > 0.0 or lo < 1e-300:
                                    break
                            if glo > 0.0:
                                t_found, _, _ = _locate(2, 0.0, bm, lo, glo, d, f1, -1.0, tau, d, a0, u, w0, dF0, lam,
                                                        beta, gam, CF, Cv, Cd, afc, phi, thr, e, psi, a)
                            else:
                                t_found = 0.0
                        else:
                            r0 = -bm * AF0 - phi
                            t_found, _, _ = _locate(2, 0.0, bm, 0.0, f0, d, f1, hermite_root(f0, r0, f1, r1, d), tau, d,
                                                    a0, u, w0, dF0, lam, beta, gam, CF, Cv, Cd, afc, phi, thr, e, psi, a)
                        found = 2
                if found >= 0:
                    # the state at the transition
                    _, _, u_e, ud_e = _point(bm, t_found / d, d, a0, u, w0, dF0, lam, beta, gam, CF, Cv, Cd, afc, phi,
                                             e, psi, a)
                    tau = tau + i * d + t_found
                    u = u_e
                    xmax = max(xmax, abs(_row(V[0], a)))
                    if found == 0:
                        _full_state(a, V, idx, u, 0.0, y)
                        bm = -sig_found
                        ud = 0.0
                        events += 1
                        slipped = True
                        just = True
                        free_phase.modal_coordinates(W1, y, 0, a)
                    else:
                        ud = 0.0
                        events += 1
                        if abs(u) > umax:
                            umax, tpeak, upeak = abs(u), tau, u
                        _full_state(a, V, idx, u, 0.0, y)
                        nb, _ = bk._select_modes(bm, 0.0, True, False, tau, y, P, code, params)
                        bm = nb
                        just = bm != 0.0
                        free_phase.modal_coordinates(W0 if bm == 0.0 else W1, y, 0, a)
                    h = min(h, H_START)
                    break
                # accept the sub-step
                if bm != 0.0:
                    u = u + w0 * d - 0.5 * bm * phi * d * d - Dg - (_row(Cd, a1) - dF0)
                    ud = ud1
                    vmax = max(vmax, abs(ud))
                    just = False
                for k in range(m):
                    a[k] = a1[k]
                xmax = max(xmax, abs(_row(V[0], a)))
            if found >= 0:
                break
        if found >= 0:
            continue
        tau = tau + h if tau + h < target else target
        h = hnext
    if not settled and bm != 0.0 and abs(u) > umax:
        umax, tpeak, upeak = abs(u), tau, u
    ints = np.array([steps, events, 1 if settled else 0, 1 if slipped else 0, 0, 0, 0, 0, 0, 0, 0, modes, 0, 0],
                    dtype=np.int64)
    floats = np.array([umax, tpeak, u, tau, xmax, vmax, upeak, 0.0, math.nan])
    return ints, floats, np.zeros((0, ny + 4))


# numba reads the compiled code shipped with the package (isoslide.jit_cache) before compiling any of it
jit_cache.seed(run)
