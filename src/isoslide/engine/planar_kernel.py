"""Compiled event-driven kernel of planar sliding (numba).

Contents slide in the plane of their floor under two horizontal ground components (and the
vertical one through the normal force).  The building is the general building of
:mod:`isoslide.engine.building_kernel` (a fixed base or a linear isolator, a rigid superstructure
or a shear building of ``n`` floors, the contents on floor ``k``), isotropic in the plane: it
moves in x and in y with the same equations, coupled only through the contents' friction force,
a vector.  Units: time ``T_p``, lengths ``a_p T_p^2``, accelerations ``a_p``, masses ``M_b``;
primes are ``d/dtau``.  The model parameters ``P`` are the building kernel's
(:func:`isoslide.engine.building.parameters`).

State ``y`` (length ``2 (2 + 2 n) + 4``, :func:`state_size`): for each axis (x, then y) the
slab's displacement and velocity relative to the ground and the floors' displacements and
velocities relative to the slab (``[x, x', xs_1 .. xs_n, xs_1' .. xs_n']``, the building kernel's
order), then the block's displacement ``u = (u_x, u_y)`` and velocity ``w = (w_x, w_y)`` relative
to its floor.

Excitation (``ex = (code, params, code_y, params_y, G)``): the ground acceleration in the
building's axes is ``R(angle) (p(tau), Pi14 p_y((tau - Pi16) / Pi15))`` with ``G = [Pi14, Pi15,
Pi16, cos(angle), sin(angle), has_y]``; the normal-force factor ``nz = 1 + Pi17 p_z(tau)`` is the
building kernel's :func:`~isoslide.engine.building_kernel.normal`.

Contact (isotropic Stribeck friction, the friction level ``phi(|w|)`` of
:func:`isoslide.model.friction.stribeck`):

- stuck (``w = 0``): the block moves with its floor and needs the force ``-m A_F`` (``A_F`` the
  floor's absolute acceleration with the block's mass on it); it stays stuck while
  ``|A_F| <= thr nz`` (``thr = Pi2/Pi5``, the Euclidean norm);
- sliding: the friction force on the floor is ``R = m nz phi(|w|) w/|w|`` and
  ``w' = -A_F - nz phi(|w|) w/|w|``;
- breakaway when ``|A_F|`` reaches ``thr nz``: the block starts along ``-A_F/|A_F|``, the only
  direction in which a sliding block's acceleration is along its velocity (the back-reaction on
  the floor is along the same line);
- stop when the speed ``|w|`` returns to zero.

Locating the stop.  A sliding block stops only while the force driving it is below friction;
then its direction turns towards the driving force as ``(tau* - tau)^{a/c}`` and its speed falls
as ``c (tau* - tau)`` to first order (``c`` the net deceleration), so ``|w|`` reaches zero without
a sign change and the speed's Taylor prediction ``d = |w| / (-|w|')`` underestimates the time
left.  Each step of a decelerating slide is therefore limited to ``0.9 d``: the steps approach
the stop geometrically (each takes about nine tenths of the time left), none crosses it, and
once ``d`` is below ``1e-13 max(1, |tau|)`` one last step of length ``d`` ends the slide (the
distance it leaves out is below ``|w| d``).  The stop time is thus found to about ``1e-13``, like
every transition of the 1-D kernels.  A step whose velocity turns by more than a right angle is
rejected and halved.

The peak of ``|u|``.  The path curves, so ``|u|`` can peak inside a slide: where ``u . w``
changes sign from positive to negative, located by safeguarded Newton on the step length
(:func:`locate`), and at stops.  Breakaways are located the same way on ``|A_F| - thr nz``,
with its interior peaks found as roots of its rate.

Settlement: after the pulses, with the block stuck, the free building is linear and the same in
both axes; the modal bound of :func:`isoslide.engine.building_kernel._modal_within` per axis,
combined as ``sqrt(b_x^2 + b_y^2) <= thr``, proves the block never slides again.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .. import jit_cache
from ..pulses import accel_at, jerk_at
from .building_kernel import (KIND_FIXED, P_ARRAYS, P_CB, P_COULOMB, P_FLEX, P_FLOOR, P_KD, P_KIND, P_M, P_MB,
                              P_N, P_PI2, P_PI6, P_ROOF, P_THR, _storey_force, friction, normal)
from .kernel import ATOL_SLIDE, A, B, C, E3, E5, NS, _hermite_max, _left_limit, _next_step, _step_factor, hermite_root

G_PI14, G_PI15, G_PI16, G_COS, G_SIN, G_HAS_Y = range(6)
"""Indices of the excitation's array ``G``."""

INT_RESULTS = ("steps", "events", "settled", "slipped", "hist", "rejected")
"""The integer results of :func:`run`, in order."""
FLOAT_RESULTS = ("umax", "tpeak", "angle", "ures", "tend", "vmax", "ux", "uy")
"""The float results of :func:`run`, in order: peak ``|u|``, its time and direction, the final ``|u|``,
the end time, the largest speed, the final ``u``."""

EV_DEMAND, EV_RATE, EV_PEAK, EV_STOP = range(4)
"""Event kinds: a stuck block's demand ``|A_F| - thr nz``, its rate, ``u . w`` (the rate of
``|u|^2 / 2``) and the signed speed ``sg sigma`` of a slow slide (mode ``+-2``)."""

STOP_FRACTION = 0.9
"""Fraction of the predicted time to a stop that one step may take."""
STOP_TIME = 1e-13
"""A free slide whose predicted stop is this close (relative to ``max(1, |tau|)``) ends in one step."""
ALIGNED = 1e-3
"""A slow free slide joins the slaved line when its velocity is within this angle (radians) of it."""
SLAVED_FACTOR = 0.1
"""The slaved line holds slides below the speed ``SLAVED_FACTOR rtol^(2/3)`` (units of ``a_p T_p``;
:func:`slaved_speed`)."""


def slaved_speed(rtol: float) -> float:
    """Speed (units of ``a_p T_p``) below which a slide keeps the slaved line, for the local tolerance ``rtol``.

    A slide on the slaved line lags its true direction by ``alpha ~ s theta' / |D|`` (``theta'`` the
    turning rate of the drive ``D``); the error it leaves in ``Pi1`` was measured to grow as the
    1.5th power of the speed limit (about 1e-6 relative at 1e-5 on a two-way coupled isolated
    base), so the limit falls with the tolerance as ``rtol^(2/3)``.
    """
    return SLAVED_FACTOR * rtol ** (2.0 / 3.0)


def state_size(n: int) -> int:
    """Length of the state vector of a building of ``n`` floors."""
    return 2 * axis_size(n) + 4


def axis_size(n: int) -> int:
    """States of one axis of a building of ``n`` floors: the slab's and the floors'."""
    return 2 + 2 * n


def history_columns(n: int) -> dict:
    """Column of each quantity in a history row: ``tau``, the axes' first columns, ``u``, ``w``, ``phase``."""
    nb = axis_size(n)
    return {"tau": 0, "x": 1, "y": 1 + nb, "u": 1 + 2 * nb, "w": 3 + 2 * nb, "phase": 5 + 2 * nb}


@njit(cache=True)
def ground(tau, ex):
    """Horizontal ground acceleration ``(g_x, g_y)`` in the building's axes at ``tau`` (units of a_p)."""
    code, params, code_y, params_y, G = ex
    px = accel_at(code, params, tau)
    py = 0.0
    if G[G_HAS_Y] != 0.0:
        py = G[G_PI14] * accel_at(code_y, params_y, (tau - G[G_PI16]) / G[G_PI15])
    c = G[G_COS]
    s = G[G_SIN]
    return c * px - s * py, s * px + c * py


@njit(cache=True)
def ground_rate(tau, ex):
    """Rate ``d/dtau`` of :func:`ground`."""
    code, params, code_y, params_y, G = ex
    px = jerk_at(code, params, tau)
    py = 0.0
    if G[G_HAS_Y] != 0.0:
        py = G[G_PI14] / G[G_PI15] * jerk_at(code_y, params_y, (tau - G[G_PI16]) / G[G_PI15])
    c = G[G_COS]
    s = G[G_SIN]
    return c * px - s * py, s * px + c * py


@njit(cache=True)
def _axis(o, stuck, r, p, y, P, A):
    """Absolute accelerations of one axis: ``(Ab, A_F)``, the floors' into ``A``.

    ``o`` is the axis's first state, ``r`` the component of the sliding block's friction force on
    its floor, ``p`` the ground acceleration.  Linear and homogeneous in ``(y, p, r)``: given the
    states' rates and ``p'`` it returns the rates.
    """
    n = int(P[P_N])
    m = P[P_M]
    mb = P[P_MB]
    roof = P[P_ROOF] != 0.0
    flex = P[P_FLEX] != 0.0
    fl = int(P[P_FLOOR]) - 1
    zp = y[o + 2:o + 2 + n]
    zv = y[o + 2 + n:o + 2 + 2 * n]
    S = 0.0
    if flex:
        for j in range(n):
            G = _storey_force(j, zp, zv, P)
            S += G
            mj = P[P_ARRAYS + j]
            if roof and j == fl:
                A[j] = -G / (mj + m) if stuck else (-G + r) / mj
            else:
                A[j] = -G / mj
    if P[P_KIND] == KIND_FIXED:
        Ab = p
    else:
        F = P[P_KD] * y[o] + P[P_CB] * y[o + 1]
        if roof:
            Ab = (-F + S) / mb
        else:
            Ab = (-F + S) / (mb + m) if stuck else (-F + S + r) / mb
    if not flex:
        for j in range(n):
            A[j] = Ab
    return Ab, (A[fl] if roof else Ab)


@njit(cache=True)
def _level(s, nz, P):
    """Friction level ``nz phi(s)`` of a block sliding at speed ``s`` (units of a_p)."""
    if P[P_COULOMB] == 1.0:
        return P[P_THR] * nz
    return friction(s, P)[0] * nz


@njit(cache=True)
def _stuck_accels(y, gx, gy, P, A):
    """The floor's acceleration ``(A_Fx, A_Fy)`` with the block stuck on it (``A`` scratch space)."""
    nb = 2 + 2 * int(P[P_N])
    return _axis(0, True, 0.0, gx, y, P, A)[1], _axis(nb, True, 0.0, gy, y, P, A)[1]


@njit(cache=True)
def _axis_rates(o, stuck, r, p, y, P, out):
    """One axis's state rates into ``out`` (see :func:`_axis`); returns the floor's acceleration ``A_F``."""
    n = int(P[P_N])
    A = out[o + 2 + n:o + 2 + 2 * n]
    Ab, AF = _axis(o, stuck, r, p, y, P, A)
    if P[P_KIND] == KIND_FIXED:
        out[o] = 0.0
        out[o + 1] = 0.0
    else:
        out[o] = y[o + 1]
        out[o + 1] = Ab - p
    for j in range(n):
        out[o + 2 + j] = y[o + 2 + n + j]
        out[o + 2 + n + j] = A[j] - Ab
    return AF


@njit(cache=True)
def deriv(bm, e0, e1, tau, y, P, ex, out, tmp):
    """Right-hand side at ``(tau, y)`` in the mode ``bm``, written into ``out``; returns ``(A_Fx, A_Fy)``.

    Modes: 0 stuck; 1 sliding with friction along ``-w/|w|``; ``+-2`` sliding slowly along the
    slaved line (below the speed of :func:`slaved_speed`): ``w = sigma d`` with ``d = -A/|A|`` (``A`` the
    floor's acceleration were the block stuck), friction ``-sg nz phi(|sigma|) d`` on the block
    (``sg = bm / 2``, the sign of ``sigma`` in the phase), ``sigma' = -A_F . d - sg nz phi`` and
    ``w' = sigma' d + sigma d'``.  ``(e0, e1)`` is the direction used where it is undefined (a
    speed or a demand exactly zero).  ``tmp`` is scratch space of at least ``n`` entries.
    """
    n = int(P[P_N])
    nb = 2 + 2 * n
    U = 2 * nb
    gx, gy = ground(tau, ex)
    nz, _ = normal(tau, P)
    stuck = bm == 0.0
    slaved = bm == 2.0 or bm == -2.0
    dx = e0
    dy = e1
    fx = 0.0
    fy = 0.0
    ph = 0.0
    sigma = 0.0
    As = tmp
    ax = 0.0
    ay = 0.0
    amag = 0.0
    if not stuck:
        wx = y[U + 2]
        wy = y[U + 3]
        if slaved:
            ax, ay = _stuck_accels(y, gx, gy, P, As)
            amag = math.sqrt(ax * ax + ay * ay)
            if amag > 0.0:
                dx = -ax / amag
                dy = -ay / amag
            sigma = wx * dx + wy * dy
            ph = _level(abs(sigma), nz, P)
            fx = 0.5 * bm * dx
            fy = 0.5 * bm * dy
        else:
            s = math.sqrt(wx * wx + wy * wy)
            if s > 0.0:
                dx = wx / s
                dy = wy / s
            ph = _level(s, nz, P)
            fx = dx
            fy = dy
    m = P[P_M]
    AFx = _axis_rates(0, stuck, m * ph * fx, gx, y, P, out)
    AFy = _axis_rates(nb, stuck, m * ph * fy, gy, y, P, out)
    out[U] = y[U + 2]
    out[U + 1] = y[U + 3]
    if stuck:
        out[U + 2] = 0.0
        out[U + 3] = 0.0
    elif slaved:
        sd = -AFx * dx - AFy * dy - 0.5 * bm * ph
        ddx = 0.0
        ddy = 0.0
        if amag > 0.0:
            jx, jy = ground_rate(tau, ex)
            rx, ry = _stuck_accels(out, jx, jy, P, As)
            along = (rx * ax + ry * ay) / amag
            ddx = -(rx - along * ax / amag) / amag
            ddy = -(ry - along * ay / amag) / amag
        out[U + 2] = sd * dx + sigma * ddx
        out[U + 3] = sd * dy + sigma * ddy
    else:
        out[U + 2] = -AFx - ph * fx
        out[U + 3] = -AFy - ph * fy
    return AFx, AFy


@njit(cache=True)
def _error_scale(i, U, a, b, atol, rtol):
    """Tolerance of state component ``i`` (the block's ``u, w`` from ``U`` on get ``atol * ATOL_SLIDE``)."""
    return (atol * ATOL_SLIDE if i >= U else atol) + rtol * max(abs(a), abs(b))


@njit(cache=True)
def rk_step(bm, e0, e1, tau, y, h, P, ex, atol, rtol, K, ynew):
    """One DOP853 step of length ``h`` from ``(tau, y)`` into ``ynew``; returns the error norm.

    ``K`` (``(NS + 3, len(y))``) receives the stages (row ``NS`` the right-hand side at the step
    end; the last two rows are scratch space).
    """
    t_left = _left_limit(tau + h)
    ny = y.shape[0]
    U = ny - 4
    ys = K[NS + 1]
    tmp = K[NS + 2]
    deriv(bm, e0, e1, tau, y, P, ex, K[0], tmp)
    for st in range(1, NS):
        for i in range(ny):
            acc = 0.0
            for j in range(st):
                acc += A[st, j] * K[j, i]
            ys[i] = y[i] + h * acc
        ts = t_left if C[st] == 1.0 else tau + C[st] * h
        deriv(bm, e0, e1, ts, ys, P, ex, K[st], tmp)
    for i in range(ny):
        acc = 0.0
        for j in range(NS):
            acc += B[j] * K[j, i]
        ynew[i] = y[i] + h * acc
    deriv(bm, e0, e1, t_left, ynew, P, ex, K[NS], tmp)
    e5 = 0.0
    e3 = 0.0
    for i in range(ny):
        sc = _error_scale(i, U, y[i], ynew[i], atol, rtol)
        a5 = 0.0
        a3 = 0.0
        for j in range(NS + 1):
            a5 += E5[j] * K[j, i]
            a3 += E3[j] * K[j, i]
        e5 += (a5 / sc) ** 2
        e3 += (a3 / sc) ** 2
    den = e5 + 0.01 * e3
    if den == 0.0:
        return 0.0
    return abs(h) * e5 / math.sqrt(den * 4.0)


@njit(cache=True)
def verify(bm, e0, e1, tau, y, h, ycand, P, ex, atol, rtol, K):
    """Richardson check of one step: scaled error of ``ycand`` against two half steps."""
    ny = y.shape[0]
    ya = np.empty(ny)
    yb = np.empty(ny)
    rk_step(bm, e0, e1, tau, y, 0.5 * h, P, ex, atol, rtol, K, ya)
    rk_step(bm, e0, e1, tau + 0.5 * h, ya, 0.5 * h, P, ex, atol, rtol, K, yb)
    e = 0.0
    for i in range(ny):
        e = max(e, abs(yb[i] - ycand[i]) / _error_scale(i, ny - 4, y[i], ycand[i], atol, rtol))
    return e


@njit(cache=True)
def _event(kind, bm, e0, e1, tau, y, P, ex, work):
    """Value and tau-rate ``(g, dg)`` of the event function ``kind`` at ``(tau, y)`` (rate NaN: not given).

    ``work`` (twice the state's length) receives the state's rates, then scratch space.
    """
    ny = y.shape[0]
    U = ny - 4
    ny2 = y.shape[0]
    AFx, AFy = deriv(bm, e0, e1, tau, y, P, ex, work[:ny2], work[ny2:])
    if kind == EV_PEAK:
        g = y[U] * y[U + 2] + y[U + 1] * y[U + 3]
        dg = (y[U + 2] * y[U + 2] + y[U + 3] * y[U + 3] + y[U] * work[U + 2] + y[U + 1] * work[U + 3])
        return g, dg
    if kind == EV_STOP:
        dx, dy = _slaved_direction(tau, y, P, ex, e0, e1, work[ny2:])
        sg = 0.5 * bm
        return sg * (y[U + 2] * dx + y[U + 3] * dy), sg * (work[U + 2] * dx + work[U + 3] * dy)
    n = int(P[P_N])
    nb = 2 + 2 * n
    nz, dnz = normal(tau, P)
    jx, jy = ground_rate(tau, ex)
    A = work[ny2:]
    dAx = _axis(0, True, 0.0, jx, work, P, A)[1]
    dAy = _axis(nb, True, 0.0, jy, work, P, A)[1]
    mag = math.sqrt(AFx * AFx + AFy * AFy)
    rate = (AFx * dAx + AFy * dAy) / mag if mag > 0.0 else math.sqrt(dAx * dAx + dAy * dAy)
    rate -= P[P_THR] * dnz
    if kind == EV_RATE:
        return rate, math.nan
    return mag - P[P_THR] * nz, rate


@njit(cache=True)
def locate(kind, bm, e0, e1, tau, y, ha, ga, hb, gb, h0, check, P, ex, atol, rtol, K, yout, work, cnt):
    """Find ``h`` in ``(ha, hb]`` where the event ``kind`` vanishes (``ga``, ``gb`` of opposite sign).

    Safeguarded Newton from ``h0`` (Illinois regula falsi where the rate is not given), each trial
    re-stepping from the accepted point; stops when the correction is below 1e-13 (relative to
    ``max(1, |tau|)``).  ``yout`` receives the state at the root; returns the step length and the
    error estimate of that step (step doubling added when ``check``).
    """
    lo, glo, hi, ghi = ha, ga, hb, gb
    side = 0
    tol = 1e-13 * max(1.0, abs(tau))
    h = h0
    if not (lo < h < hi):
        h = lo - glo * (hi - lo) / (ghi - glo) if ghi != glo else 0.5 * (lo + hi)
    res = hi
    err = 0.0
    on_res = False
    for _it in range(100):
        if not (lo < h < hi):
            h = 0.5 * (lo + hi)
        err = rk_step(bm, e0, e1, tau, y, h, P, ex, atol, rtol, K, yout)
        cnt[0] += 1
        g, dg = _event(kind, bm, e0, e1, tau + h, yout, P, ex, work)
        if g == 0.0:
            res, on_res = h, True
            break
        if (g > 0.0) == (glo > 0.0):
            lo, glo = h, g
            if side == -1:
                ghi *= 0.5
            side = -1
        else:
            hi, ghi = h, g
            if side == 1:
                glo *= 0.5
            side = 1
        if not math.isnan(dg) and dg != 0.0 and abs(g / dg) <= tol:
            res, on_res = h, True
            break
        res = hi
        if hi - lo <= tol:
            break
        if not math.isnan(dg) and dg != 0.0 and lo < h - g / dg < hi:
            h = h - g / dg
        else:
            h = lo - glo * (hi - lo) / (ghi - glo) if ghi != glo else 0.5 * (lo + hi)
    if not on_res:
        err = rk_step(bm, e0, e1, tau, y, res, P, ex, atol, rtol, K, yout)
        cnt[0] += 1
    if check and err <= 1.0:
        err = max(err, verify(bm, e0, e1, tau, y, res, yout, P, ex, atol, rtol, K))
        cnt[0] += 2
    return res, err


@njit(cache=True)
def _breakaway(tau, y, y1, h, t_end, P, ex, atol, rtol, check, K, ye, work, cnt):
    """First point of the accepted stuck step where the demand reaches its limit: ``(found, hs, herr)``."""
    thr = P[P_THR]
    g0, r0 = _event(EV_DEMAND, 0.0, 1.0, 0.0, tau, y, P, ex, work)
    g1, r1 = _event(EV_DEMAND, 0.0, 1.0, 0.0, t_end, y1, P, ex, work)
    if g1 > 0.0:
        if g0 >= 0.0:
            for i in range(y.shape[0]):
                ye[i] = y[i]
            return True, 0.0, 0.0
        hs, herr = locate(EV_DEMAND, 0.0, 1.0, 0.0, tau, y, 0.0, g0, h, g1, hermite_root(g0, r0, g1, r1, h), check,
                          P, ex, atol, rtol, K, ye, work, cnt)
        return True, hs, herr
    if not (r0 > 0.0 and r1 < 0.0):
        return False, 0.0, 0.0
    if _hermite_max(g0, r0, g1, r1, h) < -1e-2 * thr:
        return False, 0.0, 0.0
    hm, herr = locate(EV_RATE, 0.0, 1.0, 0.0, tau, y, 0.0, r0, h, r1, -1.0, False, P, ex, atol, rtol, K, ye, work,
                      cnt)
    gm, _ = _event(EV_DEMAND, 0.0, 1.0, 0.0, tau + hm, ye, P, ex, work)
    if gm <= 0.0:
        return False, 0.0, 0.0
    hs, herr = locate(EV_DEMAND, 0.0, 1.0, 0.0, tau, y, 0.0, g0, hm, gm, -1.0, check, P, ex, atol, rtol, K, ye,
                      work, cnt)
    return True, hs, herr


@njit(cache=True)
def _slaved_direction(tau, y, P, ex, e0, e1, tmp):
    """The slaved direction ``d = -A/|A|`` (``A`` the floor's acceleration were the block stuck), or ``(e0, e1)``."""
    gx, gy = ground(tau, ex)
    ax, ay = _stuck_accels(y, gx, gy, P, tmp)
    amag = math.sqrt(ax * ax + ay * ay)
    if amag > 0.0:
        return -ax / amag, -ay / amag
    return e0, e1


@njit(cache=True)
def _stuck_floor(tau, y, P, ex, work):
    """The floor's acceleration ``(A_Fx, A_Fy)`` with the block stuck, and the stick limit ``thr nz``."""
    ny = y.shape[0]
    AFx, AFy = deriv(0.0, 1.0, 0.0, tau, y, P, ex, work[:ny], work[ny:])
    return AFx, AFy, P[P_THR] * normal(tau, P)[0]


@njit(cache=True)
def _modal_bound(W, Cm, y, o, nb):
    """Modal bound of the stuck block's floor demand along one axis (states from ``o``, ``nb`` of them).

    ``W``, ``Cm`` are the building kernel's modal data (:func:`isoslide.engine.building.modal_data`),
    whose states start with the same ``nb`` of one axis; negative when there are none.
    """
    n = W.shape[0]
    if n == 0:
        return -1.0
    bound = 0.0
    for k in range(n):
        acc = 0.0 + 0.0j
        for i in range(nb):
            acc += W[k, i] * y[o + i]
        bound += abs(Cm[0, k] * acc)
    return bound


@njit(cache=True)
def _settled(y, P, Wm, Cm, Wh, Ch):
    """True when, after the pulses and with the block stuck, the floor demand stays within the limit."""
    n = int(P[P_N])
    nb = 2 + 2 * n
    moving = False
    for i in range(2 * nb):
        if y[i] != 0.0:
            moving = True
            break
    if not moving:
        return True
    held = P[P_KIND] == KIND_FIXED
    W = Wh if held else Wm
    Cd = Ch if held else Cm
    bx = _modal_bound(W, Cd, y, 0, nb)
    by = _modal_bound(W, Cd, y, nb, nb)
    if bx < 0.0 or by < 0.0:
        return False
    return math.sqrt(bx * bx + by * by) <= P[P_THR]


@njit(cache=True)
def _record(hist, nh, hist_cap, tau, y, bm):
    """Append ``[tau, y..., bm]`` to the history while it has room."""
    if nh < hist_cap:
        hist[nh, 0] = tau
        for i in range(y.shape[0]):
            hist[nh, 1 + i] = y[i]
        hist[nh, 1 + y.shape[0]] = bm
        return nh + 1
    return nh


@njit(cache=True)
def _copy(dst, src):
    for i in range(src.shape[0]):
        dst[i] = src[i]


@njit(cache=True)
def _slow_stop(bm, e0, e1, tau, y, y1, h, t_end, just, check, P, ex, atol, rtol, K, ye, work, cnt):
    """End of a slow slide (mode ``+-2``) inside the accepted step, where ``sg sigma`` falls to zero.

    Returns ``(found, hs, herr)``; ``ye`` holds the state there.  A slide that began at the step's
    start (``just``) first needs an interior point of positive speed (found by halving); without
    one it ends at once.
    """
    g1, r1 = _event(EV_STOP, bm, e0, e1, t_end, y1, P, ex, work)
    if g1 > 0.0:
        return False, 0.0, 0.0
    g0, r0 = _event(EV_STOP, bm, e0, e1, tau, y, P, ex, work)
    if just or g0 <= 0.0:
        hp = h
        gp = g1
        for _k in range(200):
            hp *= 0.5
            rk_step(bm, e0, e1, tau, y, hp, P, ex, atol, rtol, K, ye)
            cnt[0] += 1
            gp, _ = _event(EV_STOP, bm, e0, e1, tau + hp, ye, P, ex, work)
            if gp > 0.0 or hp < 1e-300:
                break
        if gp > 0.0:
            hs, herr = locate(EV_STOP, bm, e0, e1, tau, y, hp, gp, h, g1, -1.0, check, P, ex, atol, rtol, K, ye,
                              work, cnt)
            return True, hs, herr
        _copy(ye, y)
        return True, 0.0, 0.0
    hs, herr = locate(EV_STOP, bm, e0, e1, tau, y, 0.0, g0, h, g1, hermite_root(g0, r0, g1, r1, h), check, P, ex,
                      atol, rtol, K, ye, work, cnt)
    return True, hs, herr


@njit(cache=True)
def run(P, ex, breakpoints, tau_start, tau_end, tau_stop, h_max_pulse, h_max_free, rtol, atol, hist_cap,
        h_restart, settle, max_steps, Wm, Cm, Wh, Ch, y0, bm0, slaved):
    """Integrate one planar scene from the state ``y0`` (mode ``bm0``, see :func:`deriv`) at ``tau_start``.

    Arguments as :func:`isoslide.engine.building_kernel.run`, with the excitation ``ex`` (see the
    module docstring) instead of the pulse's code and parameters; slides slower than ``slaved``
    keep the slaved line (:func:`slaved_speed`).

    Returns
    -------
    ints : ndarray of int64
        :data:`INT_RESULTS`: Runge-Kutta steps of every kind, block transitions, settled, slipped,
        history rows, rejected steps.
    floats : ndarray of float64
        :data:`FLOAT_RESULTS`.
    hist : ndarray, shape (ints[4], state_size(n) + 2)
        Rows ``[tau, y..., bm]``.
    """
    nfl = int(P[P_N])
    nb_ = 2 + 2 * nfl
    ny = 2 * nb_ + 4
    U = ny - 4
    y = y0.copy()
    y1 = np.empty(ny)
    ye = np.empty(ny)
    K = np.empty((NS + 3, ny))
    work = np.empty(2 * ny)
    cnt = np.zeros(1, dtype=np.int64)
    hist = np.empty((hist_cap if hist_cap > 0 else 1, ny + 2))
    tau = tau_start
    bm = bm0
    e0 = 1.0
    e1 = 0.0
    s_now = math.sqrt(y[U + 2] ** 2 + y[U + 3] ** 2)
    if s_now > 0.0:
        e0, e1 = y[U + 2] / s_now, y[U + 3] / s_now
    umax = math.sqrt(y[U] ** 2 + y[U + 1] ** 2)
    tpeak = tau_start
    angle = math.atan2(y[U + 1], y[U]) if umax > 0.0 else math.nan
    vmax = s_now
    steps = 0
    rejected = 0
    events = 0
    settled = False
    slipped = bm != 0.0
    just = False
    hold = False
    h = h_restart
    ib = 0
    nb = breakpoints.shape[0]
    nh = _record(hist, 0, hist_cap, tau, y, bm)
    zone = 0.0
    if P[P_COULOMB] == 0.0 and P[P_PI6] > 0.0 and P[P_PI2] < P[P_THR]:
        zone = 30.0 / P[P_PI6]
    check = zone > 0.0
    while True:
        # --- a stuck block past its limit (round-off at a transition) ---------------------
        if bm == 0.0 and not hold:
            AFx, AFy, lim = _stuck_floor(tau, y, P, ex, work)
            mag = math.sqrt(AFx * AFx + AFy * AFy)
            if mag > lim:
                bm, slipped, just = 2.0, True, True
                e0, e1 = -AFx / mag, -AFy / mag
                events += 1
        if tau >= tau_end and bm == 0.0 and _settled(y, P, Wm, Cm, Wh, Ch):
            settled = True
            if settle:
                break
        if tau >= tau_stop or steps + cnt[0] > max_steps:
            break
        # --- step length ---------------------------------------------------------------
        while ib < nb and breakpoints[ib] <= tau + 1e-14 * max(1.0, abs(tau)):
            ib += 1
        hmax = h_max_pulse if tau < tau_end else h_max_free
        h = min(h, hmax)
        if bm == 1.0:
            # a decelerating slide approaches its stop geometrically (never crossing it)
            s0 = math.sqrt(y[U + 2] ** 2 + y[U + 3] ** 2)
            deriv(bm, e0, e1, tau, y, P, ex, work[:ny], work[ny:])
            rate = (y[U + 2] * work[U + 2] + y[U + 3] * work[U + 3]) / s0
            if rate < 0.0:
                d_stop = s0 / -rate
                if d_stop <= STOP_TIME * max(1.0, abs(tau)):
                    # the slide ends within round-off of the time: one step to the stop
                    rk_step(bm, e0, e1, tau, y, d_stop, P, ex, atol, rtol, K, y1)
                    steps += 1
                    tau += d_stop
                    _copy(y, y1)
                    y[U + 2] = 0.0
                    y[U + 3] = 0.0
                    events += 1
                    um = math.sqrt(y[U] ** 2 + y[U + 1] ** 2)
                    if um > umax:
                        umax, tpeak, angle = um, tau, math.atan2(y[U + 1], y[U])
                    AFx, AFy, lim = _stuck_floor(tau, y, P, ex, work)
                    mag = math.sqrt(AFx * AFx + AFy * AFy)
                    if mag > lim:
                        e0, e1 = -AFx / mag, -AFy / mag
                        bm, just = 2.0, True
                        events += 1
                    else:
                        bm = 0.0
                    h = h_restart
                    nh = _record(hist, nh, hist_cap, tau, y, bm)
                    continue
                h = min(h, STOP_FRACTION * d_stop)
        elif bm != 0.0:
            # a slow slide leaves the slaved line near the speed it was set for, not far above it
            deriv(bm, e0, e1, tau, y, P, ex, work[:ny], work[ny:])
            dx, dy = _slaved_direction(tau, y, P, ex, e0, e1, work[ny:])
            rate = 0.5 * bm * (work[U + 2] * dx + work[U + 3] * dy)
            if rate > 0.0:
                sig = 0.5 * bm * (y[U + 2] * dx + y[U + 3] * dy)
                h = min(h, max(2.0 * slaved - sig, 0.5 * slaved) / rate)
        target = tau_stop
        if ib < nb and breakpoints[ib] < target:
            target = breakpoints[ib]
        hit_target = False
        if tau + h >= target:
            h = target - tau
            hit_target = True
        # --- attempt until accepted ------------------------------------------------------
        while True:
            err = rk_step(bm, e0, e1, tau, y, h, P, ex, atol, rtol, K, y1)
            steps += 1
            if bm != 0.0 and err <= 1.0:
                if bm == 1.0 and y[U + 2] * y1[U + 2] + y[U + 3] * y1[U + 3] < 0.0:
                    err = 4.0
                elif zone > 0.0:
                    s0 = math.sqrt(y[U + 2] ** 2 + y[U + 3] ** 2)
                    s1 = math.sqrt(y1[U + 2] ** 2 + y1[U + 3] ** 2)
                    if min(s0, s1) < zone:
                        err = max(err, verify(bm, e0, e1, tau, y, h, y1, P, ex, atol, rtol, K))
                        steps += 2
            if err <= 1.0:
                break
            rejected += 1
            h *= _step_factor(err) if err < 4.0 else 0.5
            hit_target = False
        hnext = _next_step(h, err)
        tnew = target if hit_target else tau + h
        t_end_step = _left_limit(tnew)
        # --- transitions inside the step ------------------------------------------------
        if bm == 0.0:
            if hold:
                found, hs, herr = False, 0.0, 0.0
                hold = False
                g1, _ = _event(EV_DEMAND, 0.0, 1.0, 0.0, t_end_step, y1, P, ex, work)
                if g1 > 0.0:
                    found, hs = True, h
                    _copy(ye, y1)
            else:
                found, hs, herr = _breakaway(tau, y, y1, h, t_end_step, P, ex, atol, rtol, check, K, ye, work, cnt)
            if found:
                if herr > 1.0:
                    h = 0.5 * hs
                    continue
                tau += hs
                _copy(y, ye)
                y[U + 2] = 0.0
                y[U + 3] = 0.0
                AFx, AFy, lim = _stuck_floor(tau, y, P, ex, work)
                mag = math.sqrt(AFx * AFx + AFy * AFy)
                if mag > 0.0:
                    e0, e1 = -AFx / mag, -AFy / mag
                bm, slipped, just = 2.0, True, True
                events += 1
                h = h_restart
                nh = _record(hist, nh, hist_cap, tau, y, bm)
                continue
        else:
            if bm != 1.0:
                found, hs, herr = _slow_stop(bm, e0, e1, tau, y, y1, h, t_end_step, just, check, P, ex, atol, rtol,
                                             K, ye, work, cnt)
                if found:
                    if herr > 1.0:
                        h = 0.5 * hs
                        continue
                    if hs == 0.0 and just:
                        hold = True
                    tau += hs
                    _copy(y, ye)
                    y[U + 2] = 0.0
                    y[U + 3] = 0.0
                    events += 1
                    um = math.sqrt(y[U] ** 2 + y[U + 1] ** 2)
                    if um > umax:
                        umax, tpeak, angle = um, tau, math.atan2(y[U + 1], y[U])
                    AFx, AFy, lim = _stuck_floor(tau, y, P, ex, work)
                    mag = math.sqrt(AFx * AFx + AFy * AFy)
                    if mag > lim and not hold:
                        e0, e1 = -AFx / mag, -AFy / mag
                        bm, just = 2.0, True
                        events += 1
                    else:
                        bm, just = 0.0, False
                    h = h_restart
                    nh = _record(hist, nh, hist_cap, tau, y, bm)
                    continue
            q0 = y[U] * y[U + 2] + y[U + 1] * y[U + 3]
            q1 = y1[U] * y1[U + 2] + y1[U + 1] * y1[U + 3]
            if q0 > 0.0 and q1 < 0.0:
                g0, r0 = _event(EV_PEAK, bm, e0, e1, tau, y, P, ex, work)
                g1, r1 = _event(EV_PEAK, bm, e0, e1, t_end_step, y1, P, ex, work)
                hp, _ = locate(EV_PEAK, bm, e0, e1, tau, y, 0.0, g0, h, g1, hermite_root(g0, r0, g1, r1, h), False,
                               P, ex, atol, rtol, K, ye, work, cnt)
                um = math.sqrt(ye[U] ** 2 + ye[U + 1] ** 2)
                if um > umax:
                    umax, tpeak, angle = um, tau + hp, math.atan2(ye[U + 1], ye[U])
        # --- accept -----------------------------------------------------------------------
        tau = tnew
        _copy(y, y1)
        just = False
        if bm == 0.0:
            y[U + 2] = 0.0
            y[U + 3] = 0.0
        else:
            s1 = math.sqrt(y[U + 2] ** 2 + y[U + 3] ** 2)
            if bm == 1.0 and s1 < slaved:
                dx, dy = _slaved_direction(tau, y, P, ex, e0, e1, work[ny:])
                if abs(y[U + 2] * dy - y[U + 3] * dx) < ALIGNED * s1:
                    sg = 1.0 if y[U + 2] * dx + y[U + 3] * dy >= 0.0 else -1.0
                    bm = 2.0 * sg
                    y[U + 2] = sg * s1 * dx
                    y[U + 3] = sg * s1 * dy
            elif bm != 1.0 and s1 >= 2.0 * slaved:
                bm = 1.0
            if s1 > 0.0:
                e0, e1 = y[U + 2] / s1, y[U + 3] / s1
            vmax = max(vmax, s1)
            um = math.sqrt(y[U] ** 2 + y[U + 1] ** 2)
            if um > umax:
                umax, tpeak, angle = um, tau, math.atan2(y[U + 1], y[U])
        if P[P_KIND] == KIND_FIXED:
            for a in range(2):
                y[a * nb_] = 0.0
                y[a * nb_ + 1] = 0.0
        h = hnext
        nh = _record(hist, nh, hist_cap, tau, y, bm)
    ures = math.sqrt(y[U] ** 2 + y[U + 1] ** 2)
    ints = np.array([steps + cnt[0], events, 1 if settled else 0, 1 if slipped else 0, nh, rejected],
                    dtype=np.int64)
    floats = np.array([umax, tpeak, angle, ures, tau, vmax, y[U], y[U + 1]])
    return ints, floats, hist[:nh]


# numba reads the compiled code shipped with the package (isoslide.jit_cache) before compiling any of it
jit_cache.seed(run)
