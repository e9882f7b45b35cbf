"""Compiled event-driven kernel of planar sliding (numba).

Contents slide in the plane of their floor under two horizontal ground components (and the
vertical one through the normal force).  The building is the general building of
:mod:`isoslide.engine.building_kernel` (a fixed base, a linear isolator, a sliding bearing or a
bilinear bearing, a rigid superstructure or a shear building of ``n`` floors, the contents on
floor ``k``), isotropic in the plane: it moves in x and in y with the same equations, coupled
only through the friction forces and a bilinear bearing's force, vectors.  Units: time ``T_p``,
lengths ``a_p T_p^2``, accelerations ``a_p``, masses ``M_b``; primes are ``d/dtau``.  The model parameters ``P`` are the building kernel's
(:func:`isoslide.engine.building.parameters`).

State ``y`` (length ``2 (2 + 2 n) + 4``, :func:`state_size`; one more per axis on a bilinear
bearing): for each axis (x, then y) the slab's displacement and velocity relative to the ground
and the floors' displacements and velocities relative to the slab (``[x, x', xs_1 .. xs_n, xs_1'
.. xs_n']``, the building kernel's order) and a bilinear bearing's force ``fh`` (a circular yield
surface ``|fh| <= q``: elastic ``fh' = k_e x'``, yielding along ``fh``), then the block's
displacement ``u = (u_x, u_y)`` and velocity ``w = (w_x, w_y)`` relative to its floor.

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

A sliding bearing (friction pendulum) is a second interface of the same kind between the slab and
the ground, with circular friction: held (``x' = 0``) while the force ``f`` that holds the slab is
within its breakaway level, ``|f| <= q_s nz``; sliding with the friction force ``q(|x'|) nz
x'/|x'|`` on the slab; breaking away along ``f/|f|`` when ``|f|`` reaches ``q_s nz``.  The level
``q(w) = q - (q - q_s) exp(-a w)`` rises with the slab's planar speed ``w = |x'|`` from ``q_s``
at rest to ``q`` (Constantinou, Mokha and Reinhorn 1990;
:func:`~isoslide.engine.building_kernel.bearing_level`, ``q = P_Q``, ``q_s = P_QS``, ``a =
P_QA``); with ``a = 0`` it is the constant ``q = q_s``.  On its slaved line (mode ``+-2``, below)
the bearing slides at the signed speed ``sg sigma`` with the level ``q(sg sigma)``, the law
continued smoothly past a stop, so the force is continuous when a slide joins or leaves the line.

Locating the stop.  A sliding block stops only while the force driving it is below friction;
then its direction turns towards the driving force as ``(tau* - tau)^{a/c}`` and its speed falls
as ``c (tau* - tau)`` to first order (``c`` the net deceleration), so ``|w|`` reaches zero without
a sign change and the speed's Taylor prediction ``d = |w| / (-|w|')`` underestimates the time
left.  Each step of ``tau`` of a decelerating slide is therefore limited to ``0.9 d``: the steps approach
the stop geometrically (each takes about nine tenths of the time left), none crosses it, and
once ``d`` is below ``1e-13 max(1, |tau|)`` one last step of length ``d`` ends the slide (the
distance it leaves out is below ``|w| d``).  The stop time is thus found to about ``1e-13``, like
every transition of the 1-D kernels.  A step whose velocity turns by more than a right angle is
rejected and halved.

Slow free slides.  A free slide at the speed ``s`` turns towards its drive at the rate ``|D| /
s``; where a step ``h`` of ``tau`` would have ``h Pi2 / s > SPEED_TIME`` the slide steps in its own
time ``lambda``, ``dtau = s dlambda`` (:func:`rk_step_speed`, ``tau`` integrated with the state).
The stiffness ratio is the same in either time, but in ``lambda`` the speed decays towards a stop
without reaching it, so such a step needs no cap before the stop; measured on the bench's planar
scenes it takes fewer steps at the same accuracy.  A step of ``lambda`` holding a transition, a peak
of ``|u|`` or a breakpoint is taken again in ``tau``, where those are located as above.

The first step after every transition is ``h_restart``.  After a breakaway the slide starts on its
slaved line and its steps are held to leave it near ``2 slaved`` (:func:`_slow_cap`), so the first
step decides only where the free slide starts.  A first step from the local derivatives (Hairer
and Wanner's ``hinit``) or half the last step (the 1-D kernels' rule) saves steps only by carrying
the slide further along its slaved line, which costs accuracy where the drive turns fast; the
same held by the series of the slide's speed to the line's exit saves none
(``benchmarks/planar_restart.py`` at the commit of its rows in ``docs/measurements.csv``).

The peak of ``|u|``.  The path curves, so ``|u|`` can peak inside a slide: where ``u . w``
changes sign from positive to negative, located by safeguarded Newton on the step length
(:func:`locate`), and at stops.  Breakaways are located the same way on ``|A_F| - thr nz``,
with its interior peaks found as roots of its rate.

Settlement: after the pulses, with the block stuck, the free building is linear and the same in
both axes; the modal bound of :func:`isoslide.engine.building_kernel._modal_within` per axis,
combined as ``sqrt(b_x^2 + b_y^2) <= thr``, proves the block never slides again.  A sliding bearing
whose friction rises with speed may creep towards its stick band for ever after the pulses; the
energy bound of :func:`_creep_settled` then proves that the block stays stuck.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .. import jit_cache
from ..pulses import accel_at, jerk_at
from . import free_phase
from .building_kernel import (KIND_BILINEAR, KIND_FIXED, KIND_SLIDING, P_ARRAYS, P_CB, P_COULOMB, P_FLEX, P_FLOOR,
                              P_KD, P_KE, P_KIND, P_M, P_MB, P_N, P_PI2, P_PI6, P_Q, P_QA, P_QS, P_ROOF, P_THR,
                              _stiffness, _storey_force, bearing_level, friction, normal)
from .kernel import (ROOT_AT_TRIAL, ROOT_OPEN, B, C, E3, E5, NS, _error_norm, _hermite_max, _left_limit,
                     _next_breakpoint, _next_step, _step_factor, _step_target, bracket_open, bracket_step,
                     copy_state, doubling_error, end_state, error_scale, hermite_root, scaled_error, stage_state)
from .kernel import (A as RK_A)

G_PI14, G_PI15, G_PI16, G_COS, G_SIN, G_HAS_Y = range(6)
"""Indices of the excitation's array ``G``."""

M_BM, M_E0, M_E1, M_IM, M_I0, M_I1 = range(6)
"""Indices of the modes array ``md``: the block's mode and fallback direction, the bearing's."""

INT_RESULTS = ("steps", "events", "settled", "slipped", "hist", "rejected", "iso_events", "iso_moved")
"""The integer results of :func:`run`, in order."""
FLOAT_RESULTS = ("umax", "tpeak", "angle", "ures", "tend", "vmax", "ux", "uy", "xmax")
"""The float results of :func:`run`, in order: peak ``|u|``, its time and direction, the final ``|u|``,
the end time, the largest speed, the final ``u``, the largest slab displacement ``|x|``."""

EV_DEMAND, EV_RATE, EV_PEAK, EV_STOP, EV_BDEMAND, EV_BRATE, EV_BSTOP, EV_YIELD, EV_YRATE, EV_UNLOAD = range(10)
"""Event kinds: a stuck block's demand ``|A_F| - thr nz``, its rate, ``u . w`` (the rate of
``|u|^2 / 2``), the signed speed ``sg sigma`` of a slow slide (mode ``+-2``); a held sliding
bearing's demand ``|f_need| - q_s nz``, its rate, and its slow slide's signed speed; an elastic
bilinear bearing's ``|fh| - q``, its rate, and a yielding one's loading rate ``fh . x'/|fh|``."""

STOP_FRACTION = 0.9
"""Fraction of the predicted time to a stop that one step may take."""
STOP_TIME = 1e-13
"""A free slide whose predicted stop is this close (relative to ``max(1, |tau|)``) ends in one step."""
ALIGNED = 1e-3
"""A slow free slide joins the slaved line when its velocity is within this angle (radians) of it."""
SLAVED_FACTOR = 0.1
"""The slaved line holds slides below the speed ``SLAVED_FACTOR rtol^(2/3)`` (units of ``a_p T_p``;
:func:`slaved_speed`)."""
FD_STEP = 1e-6
"""Relative step of the central differences that give the rates of a sliding bearing's events."""
SPEED_TIME = 1.0
"""A free slide steps in its own time ``lambda`` (``dtau = |w| dlambda``, :func:`rk_step_speed`) where a
step ``h`` of ``tau`` would have ``h Pi2 / |w|`` above this (its direction's relaxation stiff)."""
SPEED_FIRST = 4.0
"""The step of ``lambda`` that follows a step of ``tau`` is at most this over ``Pi2``: a few times the time
``1 / |D|`` (units of ``lambda``) in which the direction relaxes, so that it is not rejected several
times over, as the step of ``tau`` carried over from a slaved start is."""


def slaved_speed(rtol: float) -> float:
    """Speed (units of ``a_p T_p``) below which a slide keeps the slaved line, for the local tolerance ``rtol``.

    A slide on the slaved line lags its true direction by ``alpha ~ s theta' / |D|`` (``theta'`` the
    turning rate of the drive ``D``); the error it leaves in ``Pi1`` was measured to grow as the
    1.5th power of the speed limit (about 1e-6 relative at 1e-5 on a two-way coupled isolated
    base), so the limit falls with the tolerance as ``rtol^(2/3)``.
    """
    return SLAVED_FACTOR * rtol ** (2.0 / 3.0)


def state_size(n: int, hysteretic: bool = False) -> int:
    """Length of the state vector of a building of ``n`` floors (``hysteretic``: on a bilinear bearing)."""
    return 2 * axis_size(n, hysteretic) + 4


def axis_size(n: int, hysteretic: bool = False) -> int:
    """States of one axis of a building of ``n`` floors: the slab's, the floors', a bilinear bearing's force."""
    return 2 + 2 * n + (1 if hysteretic else 0)


def history_columns(n: int, hysteretic: bool = False) -> dict:
    """Column of each quantity in a history row: ``tau``, the axes' first columns, ``u``, ``w``, the phases."""
    nb = axis_size(n, hysteretic)
    return {"tau": 0, "x": 1, "y": 1 + nb, "u": 1 + 2 * nb, "w": 3 + 2 * nb, "phase": 5 + 2 * nb,
            "iso_phase": 6 + 2 * nb}


@njit(cache=True, inline="always")
def _turned(tau, ex, rate):
    """The excitation's horizontal components (``rate``: their rates) turned into the building's axes."""
    code, params, code_y, params_y, G = ex
    px = jerk_at(code, params, tau) if rate else accel_at(code, params, tau)
    py = 0.0
    if G[G_HAS_Y] != 0.0:
        s = (tau - G[G_PI16]) / G[G_PI15]
        py = G[G_PI14] * (jerk_at(code_y, params_y, s) / G[G_PI15] if rate else accel_at(code_y, params_y, s))
    c = G[G_COS]
    sn = G[G_SIN]
    return c * px - sn * py, sn * px + c * py


@njit(cache=True, inline="always")
def ground(tau, ex):
    """Horizontal ground acceleration ``(g_x, g_y)`` in the building's axes at ``tau`` (units of a_p)."""
    return _turned(tau, ex, False)


@njit(cache=True, inline="always")
def ground_rate(tau, ex):
    """Rate ``d/dtau`` of :func:`ground`."""
    return _turned(tau, ex, True)


@njit(cache=True, inline="always")
def _sliding_bearing(P):
    """True for a sliding bearing (friction pendulum): a second planar friction interface."""
    return P[P_KIND] == KIND_SLIDING


@njit(cache=True, inline="always")
def _held(im, P):
    """True while the slab is held to the ground (a fixed base, or a stuck sliding bearing)."""
    return P[P_KIND] == KIND_FIXED or (P[P_KIND] == KIND_SLIDING and im == 0.0)


@njit(cache=True, inline="always")
def _hysteretic(P):
    """True for a bilinear (lead-rubber) bearing: an elastic-plastic force with a circular yield surface."""
    return P[P_KIND] == KIND_BILINEAR


@njit(cache=True, inline="always")
def _axis_len(P):
    """States of one axis: ``[x, x', xs_1 .. xs_n, xs_1' .. xs_n']`` and a bilinear bearing's force ``fh``."""
    return 2 + 2 * int(P[P_N]) + (1 if _hysteretic(P) else 0)


@njit(cache=True, inline="always")
def _axis(o, stuck, r, p, y, P, A, held, rb, nz):
    """Absolute accelerations of one axis: ``(Ab, A_F)``, the floors' into ``A``.

    ``o`` is the axis's first state, ``r`` the component of the sliding block's friction force on
    its floor, ``p`` the ground acceleration, ``held`` whether the slab is held to the ground,
    ``rb`` the component of a sliding bearing's friction force on the slab and ``nz`` the
    normal-force factor (a friction pendulum's stiffness scales with it).  Without a sliding
    bearing, linear and homogeneous in ``(y, p, r)``: given the states' rates and ``p'`` it returns
    the rates.
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
    if held:
        Ab = p
    else:
        F = _stiffness(nz, P) * y[o] + P[P_CB] * y[o + 1] + rb
        if roof:
            Ab = (-F + S) / mb
        else:
            Ab = (-F + S) / (mb + m) if stuck else (-F + S + r) / mb
    if not flex:
        for j in range(n):
            A[j] = Ab
    return Ab, (A[fl] if roof else Ab)


@njit(cache=True, inline="always")
def _level(s, nz, P):
    """Friction level ``nz phi(s)`` of a block sliding at speed ``s`` (units of a_p)."""
    if P[P_COULOMB] == 1.0:
        return P[P_THR] * nz
    return friction(s, P)[0] * nz


@njit(cache=True, inline="always")
def _unit(x, y, f0, f1):
    """``(x, y) / |(x, y)|``, or ``(f0, f1)`` for a zero vector."""
    r = math.sqrt(x * x + y * y)
    if r > 0.0:
        return x / r, y / r
    return f0, f1


@njit(cache=True, inline="always")
def _stuck_accels(y, gx, gy, P, A, held, rbx, rby, nz):
    """The floor's acceleration ``(A_Fx, A_Fy)`` with the block stuck on it (``A`` scratch space)."""
    nb = _axis_len(P)
    return (_axis(0, True, 0.0, gx, y, P, A, held, rbx, nz)[1],
            _axis(nb, True, 0.0, gy, y, P, A, held, rby, nz)[1])


@njit(cache=True, inline="always")
def _block_force(md, y, gx, gy, P, nz, tmp, held, rbx, rby):
    """The sliding block's friction force on its floor over its mass (per unit ``m``), and its level.

    Returns ``(fx, fy, ph, dx, dy, ax, ay, amag)``: the friction's direction on the floor, the level
    ``nz phi``, the slaved direction ``d`` (mode ``+-2``) and the stuck floor acceleration it comes
    from (zero outside mode ``+-2``).  Zero force for a stuck block.
    """
    bm = md[M_BM]
    U = y.shape[0] - 4
    if bm == 0.0:
        return 0.0, 0.0, 0.0, md[M_E0], md[M_E1], 0.0, 0.0, 0.0
    wx = y[U + 2]
    wy = y[U + 3]
    if bm == 1.0:
        dx, dy = _unit(wx, wy, md[M_E0], md[M_E1])
        return dx, dy, _level(math.sqrt(wx * wx + wy * wy), nz, P), dx, dy, 0.0, 0.0, 0.0
    ax, ay = _stuck_accels(y, gx, gy, P, tmp, held, rbx, rby, nz)
    amag = math.sqrt(ax * ax + ay * ay)
    dx, dy = _unit(-ax, -ay, md[M_E0], md[M_E1])
    sg = 0.5 * bm
    sigma = wx * dx + wy * dy
    return sg * dx, sg * dy, _level(abs(sigma), nz, P), dx, dy, ax, ay, amag


@njit(cache=True, _nrt=False)
def _bearing_need(md, y, gx, gy, P, nz, tmp):
    """Force ``(f_x, f_y)`` (units of ``M_b a_p``) a held sliding bearing must supply to hold the slab.

    ``-m_b p - k_d nz x + S + R`` with ``S`` the superstructure's force on the slab and ``R`` the
    block's force on it when it sits on the slab (stuck: ``-m p``; sliding: its friction, in its
    mode with the slab held).
    """
    n = int(P[P_N])
    nb = _axis_len(P)
    mb = P[P_MB]
    kd = _stiffness(nz, P)
    rx = 0.0
    ry = 0.0
    if P[P_ROOF] == 0.0:
        if md[M_BM] == 0.0:
            rx = -P[P_M] * gx
            ry = -P[P_M] * gy
        else:
            fx, fy, ph, _, _, _, _, _ = _block_force(md, y, gx, gy, P, nz, tmp, True, 0.0, 0.0)
            rx = P[P_M] * ph * fx
            ry = P[P_M] * ph * fy
    Sx = 0.0
    Sy = 0.0
    if P[P_FLEX] != 0.0:
        for j in range(n):
            Sx += _storey_force(j, y[2:2 + n], y[2 + n:2 + 2 * n], P)
            Sy += _storey_force(j, y[nb + 2:nb + 2 + n], y[nb + 2 + n:nb + 2 + 2 * n], P)
    return -mb * gx - kd * y[0] + Sx + rx, -mb * gy - kd * y[nb] + Sy + ry


@njit(cache=True, inline="always")
def _bearing_force(md, tau, y, P, ex, nz, tmp):
    """A sliding bearing's friction force on the slab ``(rb_x, rb_y)`` and its slaved direction.

    Returns ``(rbx, rby, dx, dy)``: ``q(|x'|) nz`` along the slab's velocity (mode 1) or ``q(sg
    sigma) nz`` along ``sg d_b`` (mode ``+-2``, ``d_b`` the held need's direction, ``sigma = x' .
    d_b`` the slaved speed); zero while held.  ``q(w)`` is the friction level at the speed ``w``
    (:func:`~isoslide.engine.building_kernel.bearing_level`: the constant ``q`` unless the friction
    rises with speed, then ``q_s`` at rest, continued smoothly past a stop).  A bilinear bearing's is
    its elastic-plastic force ``fh`` (a state) in either mode, with its direction.
    """
    im = md[M_IM]
    if _hysteretic(P):
        nb = _axis_len(P)
        dx, dy = _unit(y[nb - 1], y[2 * nb - 1], md[M_I0], md[M_I1])
        return y[nb - 1], y[2 * nb - 1], dx, dy
    if im == 0.0 or not _sliding_bearing(P):
        return 0.0, 0.0, md[M_I0], md[M_I1]
    nb = _axis_len(P)
    if im == 1.0:
        dx, dy = _unit(y[1], y[nb + 1], md[M_I0], md[M_I1])
        qn = bearing_level(math.sqrt(y[1] * y[1] + y[nb + 1] * y[nb + 1]), P)[0] * nz
        return qn * dx, qn * dy, dx, dy
    gx, gy = ground(tau, ex)
    fx, fy = _bearing_need(md, y, gx, gy, P, nz, tmp)
    dx, dy = _unit(fx, fy, md[M_I0], md[M_I1])
    sg = 0.5 * im
    qn = bearing_level(sg * (y[1] * dx + y[nb + 1] * dy), P)[0] * nz
    return qn * sg * dx, qn * sg * dy, dx, dy


@njit(cache=True, inline="always")
def _axis_rates(o, stuck, r, p, y, P, out, held, rb, nz):
    """One axis's state rates into ``out`` (see :func:`_axis`); returns the floor's acceleration ``A_F``."""
    n = int(P[P_N])
    A = out[o + 2 + n:o + 2 + 2 * n]
    Ab, AF = _axis(o, stuck, r, p, y, P, A, held, rb, nz)
    if held:
        out[o] = 0.0
        out[o + 1] = 0.0
    else:
        out[o] = y[o + 1]
        out[o + 1] = Ab - p
    for j in range(n):
        out[o + 2 + j] = y[o + 2 + n + j]
        out[o + 2 + n + j] = A[j] - Ab
    return AF


@njit(cache=True, inline="always")
def _hysteretic_rates(im, y, P, out, nb):
    """A bilinear bearing's force rates into ``out``.

    Elastic (mode 0) ``fh' = k_e x'``; yielding (mode 1) ``k_e`` times the part of ``x'`` across
    ``fh``, the plastic flow taking the part along it, so that ``|fh| = q`` holds (a circular yield
    surface, perfectly plastic).
    """
    vx = y[1]
    vy = y[nb + 1]
    if im != 0.0:
        fx = y[nb - 1]
        fy = y[2 * nb - 1]
        f2 = fx * fx + fy * fy
        if f2 > 0.0:
            a = (vx * fx + vy * fy) / f2
            vx -= a * fx
            vy -= a * fy
    out[nb - 1] = P[P_KE] * vx
    out[2 * nb - 1] = P[P_KE] * vy


@njit(cache=True, inline="always")
def _yield_surface(y, P):
    """Put a yielding bilinear bearing's force back on its yield circle ``|fh| = q`` (the steps' round-off)."""
    nb = _axis_len(P)
    f = math.sqrt(y[nb - 1] ** 2 + y[2 * nb - 1] ** 2)
    if f > 0.0:
        y[nb - 1] *= P[P_Q] / f
        y[2 * nb - 1] *= P[P_Q] / f


@njit(cache=True, inline="always")
def _rates(md, tau, y, P, ex, out, tmp):
    """The state's rates in the modes ``md`` without the slaved lines' turning terms; ``(A_Fx, A_Fy)``."""
    nb = _axis_len(P)
    U = 2 * nb
    gx, gy = ground(tau, ex)
    nz, _ = normal(tau, P)
    held = _held(md[M_IM], P)
    rbx, rby, _, _ = _bearing_force(md, tau, y, P, ex, nz, tmp)
    fx, fy, ph, dx, dy, _, _, _ = _block_force(md, y, gx, gy, P, nz, tmp, held, rbx, rby)
    stuck = md[M_BM] == 0.0
    m = P[P_M]
    AFx = _axis_rates(0, stuck, m * ph * fx, gx, y, P, out, held, rbx, nz)
    AFy = _axis_rates(nb, stuck, m * ph * fy, gy, y, P, out, held, rby, nz)
    if _hysteretic(P):
        _hysteretic_rates(md[M_IM], y, P, out, nb)
    out[U] = y[U + 2]
    out[U + 1] = y[U + 3]
    if stuck:
        out[U + 2] = 0.0
        out[U + 3] = 0.0
    else:
        out[U + 2] = -AFx - ph * fx
        out[U + 3] = -AFy - ph * fy
    return AFx, AFy


@njit(cache=True, _nrt=False)
def deriv(md, tau, y, P, ex, out, tmp):
    """Right-hand side at ``(tau, y)`` in the modes ``md``, written into ``out``; returns ``(A_Fx, A_Fy)``.

    The block's mode ``md[0]``: 0 stuck; 1 sliding with friction along ``-w/|w|``; ``+-2`` sliding
    slowly along the slaved line (below :func:`slaved_speed`): ``w = sigma d`` with ``d = -A/|A|``
    (``A`` the floor's acceleration were the block stuck), friction ``-sg nz phi(|sigma|) d`` on
    the block (``sg = md[0] / 2``), ``sigma' = -A_F . d - sg nz phi`` and ``w' = sigma' d + sigma d'``.
    A sliding bearing's mode ``md[3]`` likewise for the slab's velocity ``x'``: 0 held, 1 sliding
    with friction ``q(|x'|) nz x'/|x'|``, ``+-2`` on its slaved line along the held need ``f/|f|``
    (friction ``sg q(sg sigma) nz f/|f|``, ``sigma = x' . f/|f|``).
    ``md[1:3]``, ``md[4:6]`` are the directions used where one is undefined (a zero speed or
    demand).  ``tmp`` is scratch space of at least ``n`` entries.
    """
    nb = _axis_len(P)
    U = 2 * nb
    AFx, AFy = _rates(md, tau, y, P, ex, out, tmp)
    bm = md[M_BM]
    im = md[M_IM]
    if bm == 2.0 or bm == -2.0:
        gx, gy = ground(tau, ex)
        nz, _ = normal(tau, P)
        held = _held(im, P)
        rbx, rby, _, _ = _bearing_force(md, tau, y, P, ex, nz, tmp)
        _, _, ph, dx, dy, ax, ay, amag = _block_force(md, y, gx, gy, P, nz, tmp, held, rbx, rby)
        sigma = y[U + 2] * dx + y[U + 3] * dy
        sd = -AFx * dx - AFy * dy - 0.5 * bm * ph
        ddx = 0.0
        ddy = 0.0
        if amag > 0.0:
            if _sliding_bearing(P):
                ddx, ddy = _turning(0, md, tau, y, P, ex, out, tmp, dx, dy)
            else:
                jx, jy = ground_rate(tau, ex)
                hx, hy = (out[nb - 1], out[2 * nb - 1]) if _hysteretic(P) else (0.0, 0.0)
                rx, ry = _stuck_accels(out, jx, jy, P, tmp, held, hx, hy, nz)
                along = (rx * ax + ry * ay) / amag
                ddx = -(rx - along * ax / amag) / amag
                ddy = -(ry - along * ay / amag) / amag
        out[U + 2] = sd * dx + sigma * ddx
        out[U + 3] = sd * dy + sigma * ddy
    if im == 2.0 or im == -2.0:
        nz, _ = normal(tau, P)
        _, _, dx, dy = _bearing_force(md, tau, y, P, ex, nz, tmp)
        sigma = y[1] * dx + y[nb + 1] * dy
        sd = out[1] * dx + out[nb + 1] * dy
        ddx, ddy = _turning(1, md, tau, y, P, ex, out, tmp, dx, dy)
        out[1] = sd * dx + sigma * ddx
        out[nb + 1] = sd * dy + sigma * ddy
    return AFx, AFy


@njit(cache=True, _nrt=False)
def _slaved_dir(which, md, tau, y, P, ex, tmp):
    """The slaved direction of the block (``which = 0``) or of a sliding bearing (1) at ``(tau, y)``."""
    gx, gy = ground(tau, ex)
    nz, _ = normal(tau, P)
    if which == 1:
        fx, fy = _bearing_need(md, y, gx, gy, P, nz, tmp)
        return _unit(fx, fy, md[M_I0], md[M_I1])
    held = _held(md[M_IM], P)
    rbx, rby, _, _ = _bearing_force(md, tau, y, P, ex, nz, tmp)
    ax, ay = _stuck_accels(y, gx, gy, P, tmp, held, rbx, rby, nz)
    return _unit(-ax, -ay, md[M_E0], md[M_E1])


@njit(cache=True, _nrt=False)
def _turning(which, md, tau, y, P, ex, rate, tmp, dx, dy):
    """Rate ``d'`` of a slaved direction along the motion ``rate`` (central differences; see :data:`FD_STEP`)."""
    ny = y.shape[0]
    eps = FD_STEP * max(1.0, abs(tau))
    yp = tmp[ny:2 * ny]
    ym = tmp[2 * ny:3 * ny]
    for i in range(ny):
        yp[i] = y[i] + eps * rate[i]
        ym[i] = y[i] - eps * rate[i]
    px, py = _slaved_dir(which, md, tau + eps, yp, P, ex, tmp)
    mx, my = _slaved_dir(which, md, tau - eps, ym, P, ex, tmp)
    return (px - mx) / (2.0 * eps), (py - my) / (2.0 * eps)


@njit(cache=True, _nrt=False)
def rk_step(md, tau, y, h, P, ex, atol, rtol, K, ynew):
    """One DOP853 step of length ``h`` from ``(tau, y)`` into ``ynew``; returns the error norm.

    ``K`` (``(NS + 5, len(y))``, C-contiguous) receives the stages (row ``NS`` the right-hand side
    at the step end; the last four rows are scratch space).
    """
    t_left = _left_limit(tau + h)
    ny = y.shape[0]
    U = ny - 4
    ys = K[NS + 1]
    tmp = K.reshape(K.size)[(NS + 2) * ny:(NS + 5) * ny]
    deriv(md, tau, y, P, ex, K[0], tmp)
    for st in range(1, NS):
        stage_state(y, h, K, st, ys)
        ts = t_left if C[st] == 1.0 else tau + C[st] * h
        deriv(md, ts, ys, P, ex, K[st], tmp)
    end_state(y, h, K, ynew)
    deriv(md, t_left, ynew, P, ex, K[NS], tmp)
    return scaled_error(K, y, ynew, h, atol, rtol, U, ny)


@njit(cache=True, _nrt=False)
def _speed_rates(md, tau, y, P, ex, out, tmp):
    """The state's rates in the slide's own time, ``|w| d/dtau``, into ``out``; returns ``|w|``."""
    U = y.shape[0] - 4
    sp = math.sqrt(y[U + 2] * y[U + 2] + y[U + 3] * y[U + 3])
    deriv(md, tau, y, P, ex, out, tmp)
    for i in range(y.shape[0]):
        out[i] *= sp
    return sp


@njit(cache=True, _nrt=False)
def rk_step_speed(md, tau, y, h, P, ex, atol, rtol, K, ynew, sv):
    """One DOP853 step of length ``h`` in the free slide's own time ``lambda``; returns ``(err, dtau)``.

    A block sliding at the speed ``s = |w|`` turns towards its drive at the rate ``|D| / s`` (units
    of 1/T_p), a stiffness that holds an explicit step of ``tau`` to a few ``s / |D|`` however
    smooth the slide.  In ``lambda`` (``dtau = s dlambda``, units of ``T_p / (a_p T_p)``) the same
    equations, all rates multiplied by ``s``, relax at the rate ``|D|`` and the slide's speed grows
    or decays as a power or an exponential of ``lambda``: smooth, and never through zero, so a
    step cannot cross the slide's stop.  ``tau`` is integrated with the state (``tau' = s``, its
    own stages ``sv``, length ``NS + 1``) and its error enters the norm (scale ``atol + rtol
    max(1, |tau|)``).  ``K`` as :func:`rk_step`, its rows the rates in ``lambda``.
    """
    ny = y.shape[0]
    U = ny - 4
    ys = K[NS + 1]
    tmp = K.reshape(K.size)[(NS + 2) * ny:(NS + 5) * ny]
    sv[0] = _speed_rates(md, tau, y, P, ex, K[0], tmp)
    for st in range(1, NS):
        stage_state(y, h, K, st, ys)
        acc = 0.0
        for j in range(st):
            acc += RK_A[st, j] * sv[j]
        sv[st] = _speed_rates(md, tau + h * acc, ys, P, ex, K[st], tmp)
    end_state(y, h, K, ynew)
    dt = 0.0
    for j in range(NS):
        dt += B[j] * sv[j]
    dt *= h
    sv[NS] = _speed_rates(md, tau + dt, ynew, P, ex, K[NS], tmp)
    e5 = 0.0
    e3 = 0.0
    for i in range(ny):
        sc = error_scale(i, U, ny, y[i], ynew[i], atol, rtol)
        a5 = 0.0
        a3 = 0.0
        for j in range(NS + 1):
            a5 += E5[j] * K[j, i]
            a3 += E3[j] * K[j, i]
        e5 += (a5 / sc) ** 2
        e3 += (a3 / sc) ** 2
    sc = atol + rtol * max(1.0, abs(tau))
    a5 = 0.0
    a3 = 0.0
    for j in range(NS + 1):
        a5 += E5[j] * sv[j]
        a3 += E3[j] * sv[j]
    e5 += (a5 / sc) ** 2
    e3 += (a3 / sc) ** 2
    return _error_norm(e5, e3, h), dt


@njit(cache=True)
def verify_speed(md, tau, y, h, ycand, P, ex, atol, rtol, K, sv):
    """Richardson check of one step of :func:`rk_step_speed`: scaled error of ``ycand`` against two half steps."""
    ny = y.shape[0]
    ya = np.empty(ny)
    yb = np.empty(ny)
    _, dt = rk_step_speed(md, tau, y, 0.5 * h, P, ex, atol, rtol, K, ya, sv)
    rk_step_speed(md, tau + dt, ya, 0.5 * h, P, ex, atol, rtol, K, yb, sv)
    return doubling_error(y, yb, ycand, atol, rtol, ny - 4, ny)


@njit(cache=True)
def verify(md, tau, y, h, ycand, P, ex, atol, rtol, K):
    """Richardson check of one step: scaled error of ``ycand`` against two half steps."""
    ny = y.shape[0]
    ya = np.empty(ny)
    yb = np.empty(ny)
    rk_step(md, tau, y, 0.5 * h, P, ex, atol, rtol, K, ya)
    rk_step(md, tau + 0.5 * h, ya, 0.5 * h, P, ex, atol, rtol, K, yb)
    return doubling_error(y, yb, ycand, atol, rtol, ny - 4, ny)


@njit(cache=True, _nrt=False)
def _demand(kind, md, tau, y, P, ex, tmp):
    """Value of a demand event (EV_DEMAND or EV_BDEMAND) at ``(tau, y)``; ``tmp`` scratch space."""
    gx, gy = ground(tau, ex)
    nz, _ = normal(tau, P)
    if kind == EV_BDEMAND:
        # the need against the breakaway level (the friction at rest)
        fx, fy = _bearing_need(md, y, gx, gy, P, nz, tmp)
        return math.sqrt(fx * fx + fy * fy) - P[P_QS] * nz
    held = _held(md[M_IM], P)
    rbx, rby, _, _ = _bearing_force(md, tau, y, P, ex, nz, tmp)
    ax, ay = _stuck_accels(y, gx, gy, P, tmp, held, rbx, rby, nz)
    return math.sqrt(ax * ax + ay * ay) - P[P_THR] * nz


@njit(cache=True, _nrt=False)
def _event(kind, md, tau, y, P, ex, work):
    """Value and tau-rate ``(g, dg)`` of the event function ``kind`` at ``(tau, y)`` (rate NaN: not given).

    ``work`` (five times the state's length) receives the state's rates, then scratch space.
    """
    ny = y.shape[0]
    U = ny - 4
    nb = U // 2
    rate = work[:ny]
    tmp = work[ny:4 * ny]
    AFx, AFy = deriv(md, tau, y, P, ex, rate, tmp)
    if kind == EV_PEAK:
        g = y[U] * y[U + 2] + y[U + 1] * y[U + 3]
        dg = (y[U + 2] * y[U + 2] + y[U + 3] * y[U + 3] + y[U] * rate[U + 2] + y[U + 1] * rate[U + 3])
        return g, dg
    if kind == EV_STOP:
        dx, dy = _slaved_dir(0, md, tau, y, P, ex, tmp)
        sg = 0.5 * md[M_BM]
        return sg * (y[U + 2] * dx + y[U + 3] * dy), sg * (rate[U + 2] * dx + rate[U + 3] * dy)
    if kind == EV_BSTOP:
        dx, dy = _slaved_dir(1, md, tau, y, P, ex, tmp)
        sg = 0.5 * md[M_IM]
        return sg * (y[1] * dx + y[nb + 1] * dy), sg * (rate[1] * dx + rate[nb + 1] * dy)
    if kind == EV_YIELD or kind == EV_YRATE or kind == EV_UNLOAD:
        fx, fy = y[nb - 1], y[2 * nb - 1]
        dfx, dfy = rate[nb - 1], rate[2 * nb - 1]
        f = math.sqrt(fx * fx + fy * fy)
        if kind == EV_UNLOAD:
            if f == 0.0:
                return 0.0, math.nan
            vx, vy = y[1], y[nb + 1]
            g = (fx * vx + fy * vy) / f
            dg = (dfx * vx + dfy * vy + fx * rate[1] + fy * rate[nb + 1]) / f - g * (fx * dfx + fy * dfy) / (f * f)
            return g, dg
        df = (fx * dfx + fy * dfy) / f if f > 0.0 else math.sqrt(dfx * dfx + dfy * dfy)
        if kind == EV_YRATE:
            return df, math.nan
        return f - P[P_Q], df
    base = EV_DEMAND if (kind == EV_DEMAND or kind == EV_RATE) else EV_BDEMAND
    if _sliding_bearing(P):
        # central differences along the motion (the bearing's friction and stiffness make the
        # demands nonlinear in the state; they take in the rate of a friction level that varies
        # with the slab's speed, q'(|x'|) |x'|', and of the limit's nz)
        eps = FD_STEP * max(1.0, abs(tau))
        ys = work[4 * ny:5 * ny]
        for i in range(ny):
            ys[i] = y[i] + eps * rate[i]
        gp = _demand(base, md, tau + eps, ys, P, ex, tmp)
        for i in range(ny):
            ys[i] = y[i] - eps * rate[i]
        gm = _demand(base, md, tau - eps, ys, P, ex, tmp)
        g = _demand(base, md, tau, y, P, ex, tmp)
        dg = (gp - gm) / (2.0 * eps)
    else:
        n = int(P[P_N])
        nz, dnz = normal(tau, P)
        jx, jy = ground_rate(tau, ex)
        A_ = work[ny:ny + n]
        held = _held(md[M_IM], P)
        hx, hy = (rate[nb - 1], rate[2 * nb - 1]) if _hysteretic(P) else (0.0, 0.0)
        dAx = _axis(0, True, 0.0, jx, rate, P, A_, held, hx, nz)[1]
        dAy = _axis(nb, True, 0.0, jy, rate, P, A_, held, hy, nz)[1]
        mag = math.sqrt(AFx * AFx + AFy * AFy)
        dg = (AFx * dAx + AFy * dAy) / mag if mag > 0.0 else math.sqrt(dAx * dAx + dAy * dAy)
        dg -= P[P_THR] * dnz
        g = mag - P[P_THR] * nz
    if kind == EV_RATE or kind == EV_BRATE:
        return dg, math.nan
    return g, dg


@njit(cache=True)
def locate(kind, md, tau, y, ha, ga, hb, gb, h0, check, P, ex, atol, rtol, K, yout, work, cnt):
    """Find ``h`` in ``(ha, hb]`` where the event ``kind`` vanishes (``ga``, ``gb`` of opposite sign).

    Safeguarded Newton from ``h0`` (Illinois regula falsi where the rate is not given), each trial
    re-stepping from the accepted point; stops when the correction is below 1e-13 (relative to
    ``max(1, |tau|)``).  ``yout`` receives the state at the root; returns the step length and the
    error estimate of that step (step doubling added when ``check``).
    """
    lo, glo, hi, ghi, side, tol, h = bracket_open(tau, h0, ha, ga, hb, gb)
    err = 0.0
    state = ROOT_OPEN
    for _it in range(100):
        err = rk_step(md, tau, y, h, P, ex, atol, rtol, K, yout)
        cnt[0] += 1
        g, dg = _event(kind, md, tau + h, yout, P, ex, work)
        state, h, lo, glo, hi, ghi, side = bracket_step(h, g, dg, lo, glo, hi, ghi, side, tol)
        if state != ROOT_OPEN:
            break
    on_res = state == ROOT_AT_TRIAL
    res = h if on_res else hi
    if not on_res:
        err = rk_step(md, tau, y, res, P, ex, atol, rtol, K, yout)
        cnt[0] += 1
    if check and err <= 1.0:
        err = max(err, verify(md, tau, y, res, yout, P, ex, atol, rtol, K))
        cnt[0] += 2
    return res, err


@njit(cache=True)
def _breakaway(kind, limit, md, tau, y, y1, h, t_end, P, ex, atol, rtol, check, K, ye, work, cnt):
    """First point of the accepted step where a held interface's demand reaches its limit: ``(found, hs, herr)``.

    ``kind`` is EV_DEMAND (the block), EV_BDEMAND (a sliding bearing) or EV_YIELD (an elastic
    bilinear bearing); ``limit`` its static limit (for the margin of the interior-peak test).
    """
    rate = EV_RATE if kind == EV_DEMAND else (EV_BRATE if kind == EV_BDEMAND else EV_YRATE)
    g0, r0 = _event(kind, md, tau, y, P, ex, work)
    g1, r1 = _event(kind, md, t_end, y1, P, ex, work)
    if g1 > 0.0:
        if g0 >= 0.0:
            copy_state(ye, y)
            return True, 0.0, 0.0
        hs, herr = locate(kind, md, tau, y, 0.0, g0, h, g1, hermite_root(g0, r0, g1, r1, h), check, P, ex, atol,
                          rtol, K, ye, work, cnt)
        return True, hs, herr
    if not (r0 > 0.0 and r1 < 0.0):
        return False, 0.0, 0.0
    if _hermite_max(g0, r0, g1, r1, h) < -1e-2 * limit:
        return False, 0.0, 0.0
    hm, herr = locate(rate, md, tau, y, 0.0, r0, h, r1, -1.0, False, P, ex, atol, rtol, K, ye, work, cnt)
    gm, _ = _event(kind, md, tau + hm, ye, P, ex, work)
    if gm <= 0.0:
        return False, 0.0, 0.0
    hs, herr = locate(kind, md, tau, y, 0.0, g0, hm, gm, -1.0, check, P, ex, atol, rtol, K, ye, work, cnt)
    return True, hs, herr


@njit(cache=True)
def _unload(md, tau, y, y1, h, t_end, check, P, ex, atol, rtol, K, ye, work, cnt):
    """First point of the accepted step where a yielding bilinear bearing unloads (``fh . x'`` turns negative).

    Returns ``(found, hs, herr)``; ``ye`` holds the state there.
    """
    g1, r1 = _event(EV_UNLOAD, md, t_end, y1, P, ex, work)
    if g1 >= 0.0:
        return False, 0.0, 0.0
    g0, r0 = _event(EV_UNLOAD, md, tau, y, P, ex, work)
    if g0 <= 0.0:
        copy_state(ye, y)
        return True, 0.0, 0.0
    hs, herr = locate(EV_UNLOAD, md, tau, y, 0.0, g0, h, g1, hermite_root(g0, r0, g1, r1, h), check, P, ex, atol,
                      rtol, K, ye, work, cnt)
    return True, hs, herr


@njit(cache=True)
def _slow_stop(kind, just, md, tau, y, y1, h, t_end, check, P, ex, atol, rtol, K, ye, work, cnt):
    """End of a slow slide (mode ``+-2``; ``kind`` EV_STOP or EV_BSTOP) inside the accepted step.

    Returns ``(found, hs, herr)``; ``ye`` holds the state there.  A slide that began at the step's
    start (``just``) first needs an interior point of positive speed (found by halving); without
    one it ends at once.
    """
    g1, r1 = _event(kind, md, t_end, y1, P, ex, work)
    if g1 > 0.0:
        return False, 0.0, 0.0
    g0, r0 = _event(kind, md, tau, y, P, ex, work)
    if just or g0 <= 0.0:
        hp = h
        gp = g1
        for _k in range(200):
            hp *= 0.5
            rk_step(md, tau, y, hp, P, ex, atol, rtol, K, ye)
            cnt[0] += 1
            gp, _ = _event(kind, md, tau + hp, ye, P, ex, work)
            if gp > 0.0 or hp < 1e-300:
                break
        if gp > 0.0:
            hs, herr = locate(kind, md, tau, y, hp, gp, h, g1, -1.0, check, P, ex, atol, rtol, K, ye, work, cnt)
            return True, hs, herr
        copy_state(ye, y)
        return True, 0.0, 0.0
    hs, herr = locate(kind, md, tau, y, 0.0, g0, h, g1, hermite_root(g0, r0, g1, r1, h), check, P, ex, atol, rtol, K,
                      ye, work, cnt)
    return True, hs, herr


@njit(cache=True)
def _modal_bound(W, Cm, row, y, o, nb):
    """Modal bound of demand ``row`` of the stuck system along one axis (states from ``o``, ``nb`` of them).

    ``W``, ``Cm`` are the building kernel's modal data (:func:`isoslide.engine.building.modal_data`),
    whose states start with the same ``nb`` of one axis; negative when there are none.
    """
    n = W.shape[0]
    if n == 0 or row >= Cm.shape[0]:
        return -1.0
    bound = 0.0
    for k in range(n):
        acc = 0.0 + 0.0j
        for i in range(nb):
            acc += W[k, i] * y[o + i]
        bound += abs(Cm[row, k] * acc)
    return bound


@njit(cache=True)
def _settled(md, y, P, Wm, Cm, Wh, Ch):
    """True when, after the pulses, with the block stuck and the slab held or elastic, nothing slides again."""
    if md[M_BM] != 0.0 or md[M_IM] != 0.0:
        return False
    nb = _axis_len(P)
    held = _held(0.0, P)
    start = 2 if held else 0
    moving = False
    for a in range(2):
        for i in range(start, nb):
            if y[a * nb + i] != 0.0:
                moving = True
    sliding = _sliding_bearing(P)
    static = math.sqrt((P[P_KD] * y[0]) ** 2 + (P[P_KD] * y[nb]) ** 2) if sliding else 0.0
    strength = P[P_QS] if sliding else P[P_Q]     # a sliding bearing's breakaway, a bilinear one's yield
    if not moving:
        return not sliding or static <= strength
    W = Wh if held else Wm
    Cd = Ch if held else Cm
    bx = _modal_bound(W, Cd, 0, y, 0, nb)
    by = _modal_bound(W, Cd, 0, y, nb, nb)
    if bx < 0.0 or by < 0.0 or math.sqrt(bx * bx + by * by) > P[P_THR]:
        return False
    if sliding or _hysteretic(P):
        # the force holding a sliding bearing, or an elastic bilinear bearing's force, within its strength
        bx = _modal_bound(W, Cd, 1, y, 0, nb)
        by = _modal_bound(W, Cd, 1, y, nb, nb)
        if bx < 0.0 or by < 0.0 or static + math.sqrt(bx * bx + by * by) > strength:
            return False
    return True


@njit(cache=True)
def _creep_settled(md, y, P, xmax):
    """True when a sliding bearing whose friction rises with speed provably leaves the block stuck for ever.

    After the pulses (``p = 0``, ``nz = 1``), under a rigid superstructure, with the block stuck on
    the slab and the bearing sliding (mode 1 or ``+-2``): the slab of mass ``M = mb + m`` obeys
    ``M x'' = -kd x - cb x' - q(|x'|) n`` (``n = x'/|x'|``) while it slides, and stays put while
    held (the only force on it, ``-kd x``, is then constant).  Its energy ``E = M |x'|^2/2 + kd
    |x|^2/2`` has ``E' = -cb |x'|^2 - q(|x'|) |x'| <= 0`` while it slides and ``E' = 0`` while it is
    held, and ``x``, ``x'`` are continuous at its stops and breakaways, so ``E`` never grows,
    whatever the direction of the slide and however often the slab stops and starts again.  (The
    1-D kernel's sharper bound, :func:`isoslide.engine.building_kernel._creep_settled`, measures the
    energy from the edge of the stick band on the side the slab slides towards; that needs a fixed
    direction, which a slide in the plane does not keep.)  Hence for all later times ``|x| <= sqrt(2
    E / kd)`` and ``|x'| <= w = sqrt(2 E / M)``, and, as ``q`` does not fall with speed, the block's
    demand is ``|A_F| = |kd x + cb x' + q(|x'|) n| / M <= (sqrt(2 E (kd + cb^2 / M)) + q(w)) / M``
    while the slab slides (Cauchy-Schwarz on the first two terms) and ``A_F = 0`` while it is held.
    The run settles when that bound is within the block's limit ``thr`` and ``sqrt(2 E / kd)``
    within the largest slab displacement ``xmax`` already reached: the block never slips again, so
    ``u``, the peak of ``|u|`` and ``xmax`` are final.  Constant friction is left to :func:`_settled`
    (its slide stops in finite time).
    """
    if md[M_BM] != 0.0 or md[M_IM] == 0.0 or P[P_QA] == 0.0 or not _sliding_bearing(P) or P[P_FLEX] != 0.0:
        return False
    nb = _axis_len(P)
    kd = P[P_KD]
    M = P[P_MB] + P[P_M]
    energy = 0.5 * M * (y[1] * y[1] + y[nb + 1] * y[nb + 1]) + 0.5 * kd * (y[0] * y[0] + y[nb] * y[nb])
    w = math.sqrt(2.0 * energy / M)
    demand = (math.sqrt(2.0 * energy * (kd + P[P_CB] * P[P_CB] / M)) + bearing_level(w, P)[0]) / M
    return demand <= P[P_THR] and math.sqrt(2.0 * energy / kd) <= xmax


@njit(cache=True)
def _record(hist, nh, hist_cap, tau, y, md):
    """Append ``[tau, y..., bm, im]`` to the history while it has room."""
    if nh < hist_cap:
        hist[nh, 0] = tau
        for i in range(y.shape[0]):
            hist[nh, 1 + i] = y[i]
        hist[nh, 1 + y.shape[0]] = md[M_BM]
        hist[nh, 2 + y.shape[0]] = md[M_IM]
        return nh + 1
    return nh


@njit(cache=True)
def _select(md, free_b, free_i, tau, y, P, ex, work):
    """Modes of the interfaces at rest (``free_b``: the block, ``free_i``: a sliding bearing), set in ``md``.

    Candidates in the order of :func:`isoslide.engine.modes.candidates` (fewest slides first): each
    stuck interface must need a force within its limit; each starting one slides along its slaved
    direction (computed with the other interface in its candidate mode) and must accelerate along
    it.  If none is consistent (round-off at a limit), each free interface slides.
    """
    ny = y.shape[0]
    U = ny - 4
    nb = U // 2
    rate = work[:ny]
    tmp = work[ny:4 * ny]
    nz, _ = normal(tau, P)
    trial = md.copy()
    for c in range(4):
        sb = (c == 2 or c == 3)
        si = (c == 1 or c == 3)
        if (sb and not free_b) or (si and not free_i):
            continue
        if free_b:
            trial[M_BM] = 2.0 if sb else 0.0
        if free_i:
            trial[M_IM] = 2.0 if si else 0.0
        for _it in range(2):
            if free_i and si:
                trial[M_I0], trial[M_I1] = _slaved_dir(1, trial, tau, y, P, ex, tmp)
            if free_b and sb:
                trial[M_E0], trial[M_E1] = _slaved_dir(0, trial, tau, y, P, ex, tmp)
        ok = True
        if free_b and not sb and _demand(EV_DEMAND, trial, tau, y, P, ex, tmp) > 0.0:
            ok = False
        if ok and free_i and not si and _demand(EV_BDEMAND, trial, tau, y, P, ex, tmp) > 0.0:
            ok = False
        if ok and (sb or si):
            _rates(trial, tau, y, P, ex, rate, tmp)
            if sb and free_b and not (rate[U + 2] * trial[M_E0] + rate[U + 3] * trial[M_E1] > 0.0):
                ok = False
            if si and free_i and not (rate[1] * trial[M_I0] + rate[nb + 1] * trial[M_I1] > 0.0):
                ok = False
        if ok:
            copy_state(md, trial)
            return
    if free_b:
        md[M_BM] = 2.0
        md[M_E0], md[M_E1] = _slaved_dir(0, md, tau, y, P, ex, tmp)
    if free_i:
        md[M_IM] = 2.0
        md[M_I0], md[M_I1] = _slaved_dir(1, md, tau, y, P, ex, tmp)


@njit(cache=True)
def _approach(which, md, tau, y, P, ex, work):
    """Predicted time to the stop of a free slide (mode 1) of the block (0) or the bearing (1); inf if not slowing."""
    ny = y.shape[0]
    U = ny - 4
    nb = U // 2
    deriv(md, tau, y, P, ex, work[:ny], work[ny:4 * ny])
    if which == 0:
        vx, vy, ax, ay = y[U + 2], y[U + 3], work[U + 2], work[U + 3]
    else:
        vx, vy, ax, ay = y[1], y[nb + 1], work[1], work[nb + 1]
    s = math.sqrt(vx * vx + vy * vy)
    if s == 0.0:
        return 0.0
    rate = (vx * ax + vy * ay) / s
    return s / -rate if rate < 0.0 else math.inf


@njit(cache=True)
def _slow_cap(which, md, tau, y, P, ex, work, slaved):
    """Longest step of a slow slide (mode ``+-2``) so that it leaves its slaved line near ``2 slaved``."""
    ny = y.shape[0]
    U = ny - 4
    nb = U // 2
    deriv(md, tau, y, P, ex, work[:ny], work[ny:4 * ny])
    dx, dy = _slaved_dir(which, md, tau, y, P, ex, work[ny:4 * ny])
    sg = 0.5 * (md[M_BM] if which == 0 else md[M_IM])
    if which == 0:
        rate = sg * (work[U + 2] * dx + work[U + 3] * dy)
        sig = sg * (y[U + 2] * dx + y[U + 3] * dy)
    else:
        rate = sg * (work[1] * dx + work[nb + 1] * dy)
        sig = sg * (y[1] * dx + y[nb + 1] * dy)
    if rate > 0.0:
        return max(2.0 * slaved - sig, 0.5 * slaved) / rate
    return math.inf


@njit(cache=True)
def run(P, ex, breakpoints, tau_start, tau_end, tau_stop, h_max_pulse, h_max_free, rtol, atol, hist_cap,
        h_restart, settle, max_steps, Wm, Cm, Vm, Lm, Wh, Ch, Vh, Lh, y0, md0, slaved, stop_on_stick, final):
    """Integrate one planar scene from the state ``y0`` in the modes ``md0`` (see :func:`deriv`) at ``tau_start``.

    Arguments as :func:`isoslide.engine.building_kernel.run` (the modal data's states in this
    kernel's axis order), with the excitation ``ex`` (see the
    module docstring) instead of the pulse's code and parameters; slides slower than ``slaved``
    keep their slaved line (:func:`slaved_speed`).  With ``stop_on_stick`` the run returns as soon as
    the block, having slid, is stuck again (and a sliding bearing held); ``final`` (length
    ``len(y0) + 6``) receives the final state and modes.

    Returns
    -------
    ints : ndarray of int64
        :data:`INT_RESULTS`: Runge-Kutta steps of every kind, block transitions, settled, slipped,
        history rows, rejected steps, bearing transitions, the bearing slid.
    floats : ndarray of float64
        :data:`FLOAT_RESULTS`.
    hist : ndarray, shape (ints[4], state_size(n) + 3)
        Rows ``[tau, y..., bm, im]``.
    """
    nb_ = _axis_len(P)
    ny = 2 * nb_ + 4
    U = ny - 4
    bearing = _sliding_bearing(P)
    hyst = _hysteretic(P)
    y = y0.copy()
    md = md0.copy()
    y1 = np.empty(ny)
    ye = np.empty(ny)
    yb = np.empty(ny)
    K = np.empty((NS + 5, ny))
    sv = np.empty(NS + 1)
    work = np.empty(5 * ny)
    cnt = np.zeros(1, dtype=np.int64)
    hist = np.empty((hist_cap if hist_cap > 0 else 1, ny + 3))
    tau = tau_start
    s_now = math.sqrt(y[U + 2] ** 2 + y[U + 3] ** 2)
    if s_now > 0.0:
        md[M_E0], md[M_E1] = y[U + 2] / s_now, y[U + 3] / s_now
    umax = math.sqrt(y[U] ** 2 + y[U + 1] ** 2)
    tpeak = tau_start
    angle = math.atan2(y[U + 1], y[U]) if umax > 0.0 else math.nan
    vmax = s_now
    xmax = 0.0
    steps = 0
    rejected = 0
    events = 0
    iso_events = 0
    settled = False
    slipped = md[M_BM] != 0.0
    moved = md[M_IM] != 0.0
    just_b = False
    just_i = False
    hold = False
    no_lam = False
    h = h_restart
    ib = 0
    nh = _record(hist, 0, hist_cap, tau, y, md)
    a_x = np.empty(max(Wm.shape[0], Wh.shape[0]), dtype=np.complex128)
    a_y = np.empty(a_x.shape[0], dtype=np.complex128)
    limits = np.array([P[P_THR], P[P_QS] if bearing else P[P_Q]])
    offsets = np.zeros((2, 2))
    zone = 0.0
    if P[P_COULOMB] == 0.0 and P[P_PI6] > 0.0 and P[P_PI2] < P[P_THR]:
        zone = 30.0 / P[P_PI6]
    check = zone > 0.0
    while True:
        # --- a held interface past its limit (round-off at a transition) -----------------
        if not hold:
            free_b = md[M_BM] == 0.0 and _demand(EV_DEMAND, md, tau, y, P, ex, work[ny:4 * ny]) > 0.0
            free_i = bearing and md[M_IM] == 0.0 and _demand(EV_BDEMAND, md, tau, y, P, ex, work[ny:4 * ny]) > 0.0
            if free_b or free_i:
                bm0, im0 = md[M_BM], md[M_IM]
                _select(md, md[M_BM] == 0.0, bearing and md[M_IM] == 0.0, tau, y, P, ex, work)
                if md[M_BM] != bm0:
                    events += 1
                    slipped, just_b = True, True
                if md[M_IM] != im0:
                    iso_events += 1
                    moved, just_i = True, True
        if tau >= tau_end and (_settled(md, y, P, Wm, Cm, Wh, Ch) or _creep_settled(md, y, P, xmax)):
            settled = True
            if settle:
                break
        if tau >= tau_stop or steps + cnt[0] > max_steps:
            break
        if stop_on_stick and slipped and md[M_BM] == 0.0 and (not bearing or md[M_IM] == 0.0):
            break
        # --- the free linear phase: an exact step where its bound proves it safe ------------
        if tau >= tau_end and md[M_BM] == 0.0 and md[M_IM] == 0.0 and not hold:
            held = _held(0.0, P)
            W, Cd, V, L = (Wh, Ch, Vh, Lh) if held else (Wm, Cm, Vm, Lm)
            taken, tau = free_phase.exact_step(W, Cd, V, L, y, nb_, held, 0.0, P[P_KD], limits, offsets, a_x, a_y, tau,
                                               tau_stop, h_max_free, hist_cap > 0)
            if taken:
                steps += 1
                xmax = max(xmax, math.sqrt(y[0] ** 2 + y[nb_] ** 2))
                nh = _record(hist, nh, hist_cap, tau, y, md)
                continue
        # --- step length ---------------------------------------------------------------
        ib = _next_breakpoint(breakpoints, ib, tau)
        # after the pulses, steps are held to h_max_free while a demand is watched for its limit
        # (a stuck block, a held or elastic bearing); slides have only their stops, as during the pulses
        watch = md[M_BM] == 0.0 or ((bearing or hyst) and md[M_IM] == 0.0)
        hmax = h_max_pulse if tau < tau_end or not watch else h_max_free
        h = min(h, hmax)
        finished = -1
        cap_b = math.inf
        for which in range(2):
            mode = md[M_BM] if which == 0 else md[M_IM]
            if which == 1 and not bearing:
                continue
            if mode == 1.0:
                # a decelerating free slide approaches its stop geometrically (never crossing it)
                d_stop = _approach(which, md, tau, y, P, ex, work)
                if d_stop <= STOP_TIME * max(1.0, abs(tau)):
                    finished = which
                    h = d_stop
                    break
                if which == 0:
                    cap_b = STOP_FRACTION * d_stop
                else:
                    h = min(h, STOP_FRACTION * d_stop)
            elif mode != 0.0:
                # a slow slide leaves its slaved line near the speed it was set for
                h = min(h, _slow_cap(which, md, tau, y, P, ex, work, slaved))
        if finished >= 0:
            # the free slide ends within round-off of the time: one step to the stop
            rk_step(md, tau, y, h, P, ex, atol, rtol, K, y1)
            steps += 1
            tau += h
            copy_state(y, y1)
            umax, tpeak, angle, events, iso_events = _at_rest(finished, md, tau, y, umax, tpeak, angle, events,
                                                              iso_events)
            bm0, im0 = md[M_BM], md[M_IM]
            _select(md, md[M_BM] == 0.0, bearing and md[M_IM] == 0.0, tau, y, P, ex, work)
            if md[M_BM] != bm0:
                events += 1
                just_b = True
            if md[M_IM] != im0:
                iso_events += 1
                just_i = True
            h = h_restart
            nh = _record(hist, nh, hist_cap, tau, y, md)
            continue
        target = _step_target(breakpoints, ib, tau_stop)
        # a slow free slide whose direction's relaxation would hold the step steps in its own time
        s_b = math.sqrt(y[U + 2] ** 2 + y[U + 3] ** 2)
        lam = (not no_lam and not hold and md[M_BM] == 1.0 and s_b > 0.0
               and h * P[P_PI2] > SPEED_TIME * s_b and tau + h < target)
        no_lam = False
        hl = 0.0
        if lam:
            hl = min(h / s_b, SPEED_FIRST / P[P_PI2])
        else:
            h = min(h, cap_b)
        hit_target = False
        if tau + h >= target:
            h = target - tau
            hit_target = True
        # --- attempt until accepted ------------------------------------------------------
        while True:
            if lam:
                err, dt = rk_step_speed(md, tau, y, hl, P, ex, atol, rtol, K, y1, sv)
                steps += 1
                if not (err == err and dt == dt and hl > 1e-300):
                    lam = False
                    h = min(h, cap_b)
                    continue
                if not (0.0 < dt < min(target - tau, hmax)):
                    # past the next breakpoint or the longest step: shorter
                    rejected += 1
                    hl *= max(0.1, 0.5 * min(target - tau, hmax) / dt) if dt > 0.0 else 0.5
                    continue
                h = dt
            else:
                err = rk_step(md, tau, y, h, P, ex, atol, rtol, K, y1)
                steps += 1
            if err <= 1.0:
                if md[M_BM] == 1.0 and y[U + 2] * y1[U + 2] + y[U + 3] * y1[U + 3] < 0.0:
                    err = 4.0
                elif md[M_IM] == 1.0 and y[1] * y1[1] + y[nb_ + 1] * y1[nb_ + 1] < 0.0:
                    err = 4.0
                elif md[M_BM] != 0.0 and zone > 0.0:
                    s0 = math.sqrt(y[U + 2] ** 2 + y[U + 3] ** 2)
                    s1 = math.sqrt(y1[U + 2] ** 2 + y1[U + 3] ** 2)
                    if min(s0, s1) < zone:
                        if lam:
                            err = max(err, verify_speed(md, tau, y, hl, y1, P, ex, atol, rtol, K, sv))
                        else:
                            err = max(err, verify(md, tau, y, h, y1, P, ex, atol, rtol, K))
                        steps += 2
            if err <= 1.0:
                break
            rejected += 1
            if lam:
                hl *= _step_factor(err) if err < 4.0 else 0.5
            else:
                h *= _step_factor(err) if err < 4.0 else 0.5
            hit_target = False
        if lam:
            hnext = _next_step(hl, err) * math.sqrt(y1[U + 2] ** 2 + y1[U + 3] ** 2)
        else:
            hnext = _next_step(h, err)
        tnew = target if hit_target else tau + h
        t_end_step = _left_limit(tnew)
        # --- transitions inside the step: the earliest ------------------------------------
        best = -1
        hbest = math.inf
        herr_best = 0.0
        if hold:
            hold = False
        else:
            # a held interface reaching its limit: the block, a sliding bearing, an elastic bilinear one
            for kind in (EV_DEMAND, EV_BDEMAND, EV_YIELD):
                if kind == EV_DEMAND:
                    held_here = md[M_BM] == 0.0
                else:
                    held_here = md[M_IM] == 0.0 and (bearing if kind == EV_BDEMAND else hyst)
                if not held_here:
                    continue
                limit = P[P_THR] if kind == EV_DEMAND else (P[P_QS] if kind == EV_BDEMAND else P[P_Q])
                found, hs, herr = _breakaway(kind, limit, md, tau, y, y1, h, t_end_step, P, ex, atol, rtol, check,
                                             K, ye, work, cnt)
                if found and hs < hbest:
                    best, hbest, herr_best = kind, hs, herr
                    copy_state(yb, ye)
        # a yielding bilinear bearing unloading; a slow slide of the block or of a sliding bearing ending
        for kind in (EV_UNLOAD, EV_STOP, EV_BSTOP):
            if kind == EV_UNLOAD:
                if not (hyst and md[M_IM] == 1.0):
                    continue
                found, hs, herr = _unload(md, tau, y, y1, h, t_end_step, check, P, ex, atol, rtol, K, ye, work, cnt)
            else:
                mode = md[M_BM] if kind == EV_STOP else md[M_IM]
                if mode != 2.0 and mode != -2.0:
                    continue
                found, hs, herr = _slow_stop(kind, just_b if kind == EV_STOP else just_i, md, tau, y, y1, h,
                                             t_end_step, check, P, ex, atol, rtol, K, ye, work, cnt)
            if found and hs < hbest:
                best, hbest, herr_best = kind, hs, herr
                copy_state(yb, ye)
        if lam and (best >= 0 or (y[U] * y[U + 2] + y[U + 1] * y[U + 3] > 0.0
                                   and y1[U] * y1[U + 2] + y1[U + 1] * y1[U + 3] < 0.0)):
            # a transition or a peak of |u| inside: the step again in tau, where they are located
            no_lam = True
            continue
        if best >= 0:
            if herr_best > 1.0:
                h = 0.5 * hbest
                continue
            copy_state(ye, yb)
            # the peak of |u| before the transition, inside the slide
            if md[M_BM] != 0.0:
                t_old = tpeak
                umax, tpeak, angle = _peak_in(md, tau, y, ye, hbest, umax, tpeak, angle, P, ex, atol, rtol, K, y1,
                                              work, cnt)
                if tpeak != t_old and tau < tpeak < tau + hbest:
                    nh = _record(hist, nh, hist_cap, tpeak, y1, md)   # the peak of |u| is a history row
            tau += hbest
            copy_state(y, ye)
            if best == EV_STOP or best == EV_BSTOP:
                which = 0 if best == EV_STOP else 1
                if hbest == 0.0 and (just_b if which == 0 else just_i):
                    hold = True
                umax, tpeak, angle, events, iso_events = _at_rest(which, md, tau, y, umax, tpeak, angle, events,
                                                                  iso_events)
            bm0, im0 = md[M_BM], md[M_IM]
            if best == EV_DEMAND:
                # a breakaway keeps every force continuous: the other interface's mode stands
                y[U + 2] = 0.0
                y[U + 3] = 0.0
                md[M_BM] = 2.0
                md[M_E0], md[M_E1] = _slaved_dir(0, md, tau, y, P, ex, work[ny:4 * ny])
            elif best == EV_BDEMAND:
                y[1] = 0.0
                y[nb_ + 1] = 0.0
                md[M_IM] = 2.0
                md[M_I0], md[M_I1] = _slaved_dir(1, md, tau, y, P, ex, work[ny:4 * ny])
            elif best == EV_YIELD:
                # rate-independent plasticity: every force stays continuous, the block keeps its mode
                md[M_IM] = 1.0
                _yield_surface(y, P)
            elif best == EV_UNLOAD:
                md[M_IM] = 0.0
            elif not hold:
                _select(md, md[M_BM] == 0.0, bearing and md[M_IM] == 0.0, tau, y, P, ex, work)
            if md[M_BM] != bm0:
                events += 1
                slipped, just_b = True, True
            else:
                just_b = False
            if md[M_IM] != im0:
                iso_events += 1
                moved, just_i = True, True
            else:
                just_i = False
            xmax = max(xmax, math.sqrt(y[0] ** 2 + y[nb_] ** 2))
            h = h_restart
            nh = _record(hist, nh, hist_cap, tau, y, md)
            continue
        if md[M_BM] != 0.0:
            t_old = tpeak
            umax, tpeak, angle = _peak_in(md, tau, y, y1, h, umax, tpeak, angle, P, ex, atol, rtol, K, ye, work, cnt)
            if tpeak != t_old and tau < tpeak < tnew:
                nh = _record(hist, nh, hist_cap, tpeak, ye, md)
        # --- accept -----------------------------------------------------------------------
        tau = tnew
        copy_state(y, y1)
        just_b = False
        just_i = False
        if md[M_BM] == 0.0:
            y[U + 2] = 0.0
            y[U + 3] = 0.0
        else:
            vmax = max(vmax, _line_switch(0, md, tau, y, P, ex, work, slaved))
            um = math.sqrt(y[U] ** 2 + y[U + 1] ** 2)
            if um > umax:
                umax, tpeak, angle = um, tau, math.atan2(y[U + 1], y[U])
        if _held(md[M_IM], P):
            for a in range(2):
                y[a * nb_ + 1] = 0.0
        elif hyst:
            if md[M_IM] == 1.0:
                _yield_surface(y, P)
        elif bearing:
            _line_switch(1, md, tau, y, P, ex, work, slaved)
        if P[P_KIND] == KIND_FIXED:
            for a in range(2):
                y[a * nb_] = 0.0
        xmax = max(xmax, math.sqrt(y[0] ** 2 + y[nb_] ** 2))
        h = hnext
        nh = _record(hist, nh, hist_cap, tau, y, md)
    ures = math.sqrt(y[U] ** 2 + y[U + 1] ** 2)
    for i in range(ny):
        final[i] = y[i]
    for i in range(6):
        final[ny + i] = md[i]
    ints = np.array([steps + cnt[0], events, 1 if settled else 0, 1 if slipped else 0, nh, rejected, iso_events,
                     1 if moved else 0], dtype=np.int64)
    floats = np.array([umax, tpeak, angle, ures, tau, vmax, y[U], y[U + 1], xmax])
    return ints, floats, hist[:nh]


@njit(cache=True)
def _at_rest(which, md, tau, y, umax, tpeak, angle, events, iso_events):
    """A slide of the block (``which = 0``) or of a sliding bearing (1) ends at ``(tau, y)``.

    Its velocity is zeroed and its mode set to rest, one event of that interface; returns the peak
    of ``|u|`` ``(umax, tpeak, angle)`` with the stop's ``|u|`` taken in and the event counts
    ``(events, iso_events)`` of the block and the bearing.
    """
    U = y.shape[0] - 4
    if which == 0:
        y[U + 2] = 0.0
        y[U + 3] = 0.0
        md[M_BM] = 0.0
        um = math.sqrt(y[U] ** 2 + y[U + 1] ** 2)
        if um > umax:
            return um, tau, math.atan2(y[U + 1], y[U]), events + 1, iso_events
        return umax, tpeak, angle, events + 1, iso_events
    nb = U // 2
    y[1] = 0.0
    y[nb + 1] = 0.0
    md[M_IM] = 0.0
    return umax, tpeak, angle, events, iso_events + 1


@njit(cache=True)
def _line_switch(which, md, tau, y, P, ex, work, slaved):
    """At an accepted point, move a sliding interface between its free mode (1) and its slaved line (``+-2``).

    ``which``: the block (0) or a sliding bearing (1).  A free slide slower than ``slaved`` joins the
    line when its velocity is within :data:`ALIGNED` of it (keeping its speed); a slow one leaves it
    above ``2 slaved``.  Updates the fallback direction; returns the speed.
    """
    ny = y.shape[0]
    U = ny - 4
    iv, jv = (U + 2, U + 3) if which == 0 else (1, U // 2 + 1)
    mi, di = (M_BM, M_E0) if which == 0 else (M_IM, M_I0)
    s1 = math.sqrt(y[iv] ** 2 + y[jv] ** 2)
    if md[mi] == 1.0 and s1 < slaved:
        dx, dy = _slaved_dir(which, md, tau, y, P, ex, work[ny:4 * ny])
        if abs(y[iv] * dy - y[jv] * dx) < ALIGNED * s1:
            sg = 1.0 if y[iv] * dx + y[jv] * dy >= 0.0 else -1.0
            md[mi] = 2.0 * sg
            md[di], md[di + 1] = dx, dy
            y[iv] = sg * s1 * dx
            y[jv] = sg * s1 * dy
    elif md[mi] != 1.0 and s1 >= 2.0 * slaved:
        md[mi] = 1.0
    if s1 > 0.0 and md[mi] == 1.0:
        md[di], md[di + 1] = y[iv] / s1, y[jv] / s1
    return s1


@njit(cache=True)
def _peak_in(md, tau, y, y1, h, umax, tpeak, angle, P, ex, atol, rtol, K, ye, work, cnt):
    """The peak of ``|u|`` inside the step ``(tau, y) -> y1`` where ``u . w`` turns negative: ``(umax, tpeak, angle)``."""
    U = y.shape[0] - 4
    q0 = y[U] * y[U + 2] + y[U + 1] * y[U + 3]
    q1 = y1[U] * y1[U + 2] + y1[U + 1] * y1[U + 3]
    if q0 > 0.0 and q1 < 0.0:
        t_end = _left_limit(tau + h)
        g0, r0 = _event(EV_PEAK, md, tau, y, P, ex, work)
        g1, r1 = _event(EV_PEAK, md, t_end, y1, P, ex, work)
        hp, _ = locate(EV_PEAK, md, tau, y, 0.0, g0, h, g1, hermite_root(g0, r0, g1, r1, h), False, P, ex, atol, rtol,
                       K, ye, work, cnt)
        um = math.sqrt(ye[U] ** 2 + ye[U + 1] ** 2)
        if um > umax:
            return um, tau + hp, math.atan2(ye[U + 1], ye[U])
    return umax, tpeak, angle


@njit(cache=True)
def floor_motion(P, ex, rows):
    """The contents' floor's motion at history rows ``[tau, y..., bm, im]`` (:func:`run`'s ``hist``).

    Returns an array of shape ``(rows, 4)``: the floor's absolute acceleration ``(A_Fx, A_Fy)``
    (units ``a_p``; :func:`deriv` in the row's modes) and its velocity relative to the ground
    ``(V_Fx, V_Fy)`` (units ``a_p T_p``: the slab's, plus the floor's relative to the slab when the
    contents stand on a floor of a flexible superstructure).
    """
    nr = rows.shape[0]
    ny = rows.shape[1] - 3
    nb = ny // 2 - 2
    n = int(P[P_N])
    md = np.array([0.0, 1.0, 0.0, 0.0, 1.0, 0.0])
    y = np.empty(ny)
    out = np.empty(ny)
    tmp = np.empty(3 * ny)
    res = np.empty((nr, 4))
    upstairs = P[P_ROOF] != 0.0 and P[P_FLEX] != 0.0
    fl = int(P[P_FLOOR]) - 1
    for r in range(nr):
        for i in range(ny):
            y[i] = rows[r, 1 + i]
        md[M_BM] = rows[r, 1 + ny]
        md[M_IM] = rows[r, 2 + ny]
        ax, ay = deriv(md, rows[r, 0], y, P, ex, out, tmp)
        res[r, 0] = ax
        res[r, 1] = ay
        for a in range(2):
            v = y[a * nb + 1]
            if upstairs:
                v += y[a * nb + 2 + n + fl]
            res[r, 2 + a] = v
    return res


# numba reads the compiled code shipped with the package (isoslide.jit_cache) before compiling any of it
jit_cache.seed(run)
