"""Compiled event-driven stick-slip kernel (numba).

Dimensionless equations (tau = t/T_p, lengths in units of a_p T_p^2, primes
are d/dtau).  ``x`` is the base displacement relative to the ground, ``u`` the
block's sliding displacement relative to the floor, ``p(tau)`` the ground
acceleration, ``w = 2 pi / Pi3``, ``z = Pi4``, ``F = 2 z w x' + w^2 x``.

Friction level in units of ``a_p`` (Eq. 1 with n = 1, literally)::

    phi(v) = (Pi2/Pi5) sech(Pi6 v) + Pi2 (1 - sech(Pi6 v)) + Pi7 |v|

STICK (u' = 0)::

    x'' = -p - F / (1 + Pi8),      a_req = -F / (1 + Pi8)   (fixed base: a_req = p)

  the block stays stuck while ``|a_req| <= Pi2/Pi5`` (true stick, no creep).

SLIP in direction ``s = sign(u')``::

    x'' = -p - F + Pi8 s phi(|u'|)
    u'' = F - (1 + Pi8) s phi(|u'|)          (fixed base: u'' = -p - s phi)

When ``u'`` returns to zero the block sticks if ``|a_req| <= Pi2/Pi5``,
otherwise it reverses at once.  Phases are integrated with the explicit
Dormand-Prince 8(5,3) pair (tableau in :mod:`isoslide.engine.dop853`); every
transition is located by a safeguarded Newton iteration on the step length,
re-stepping from the last accepted point, so it is found to ~1e-13 T_p.  Steps
end exactly on the pulse breakpoints.

Stopping (settlement): after the pulse (``tau >= tau_end``, ``p = 0``) the
total energy of the stuck system ``E = (1+Pi8) x'^2/2 + w^2 x^2/2`` can only
decrease.  Over all states with energy ``E``, the largest possible demand is
``max |F|/(1+Pi8) = sqrt(2 E ((2 z w)^2/(1+Pi8) + w^2)) / (1+Pi8)``.  Once that
bound is ``<= Pi2/Pi5`` while stuck, no further sliding is possible: the scene
is *settled* and the integration stops.  With ``z = 0`` the bound is attained
every half cycle, so a scene whose bound stays above the threshold never
settles; it is followed to the horizon and flagged ``settled = False``.

The state is ``y = [x, x', u, u']``; :func:`run` integrates one scene.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .. import jit_cache
from . import dop853
from ..pulses import accel_at, jerk_at

NS = dop853.N_STAGES
"""Stages of one DOP853 step."""
A = np.ascontiguousarray(dop853.A, dtype=np.float64)
B = np.ascontiguousarray(dop853.B, dtype=np.float64)
C = np.ascontiguousarray(dop853.C, dtype=np.float64)
E3 = np.ascontiguousarray(dop853.E3, dtype=np.float64)
E5 = np.ascontiguousarray(dop853.E5, dtype=np.float64)

# indices into the model-parameter array ``m`` (see :func:`run`)
M_W2, M_CW, M_P8, M_THR, M_PI2, M_PI6, M_PI7, M_FIXED, M_COULOMB = range(9)
N_M = 9
"""Length of the model-parameter array."""

INT_RESULTS = ("steps", "events", "settled", "slipped", "hist", "loc_stick", "loc_slip", "loc_peak", "rejected")
"""The integer results of :func:`run`, in order (their indices are ``R_*``)."""
R_STEPS, R_EVENTS, R_SETTLED, R_SLIPPED, R_HIST, R_LOC_STICK, R_LOC_SLIP, R_LOC_PEAK, R_REJECTED = range(9)
N_R = len(INT_RESULTS)
"""Length of the integer results."""
FLOAT_RESULTS = ("umax", "tpeak", "ures", "tend", "amax", "vmax", "upeak")
"""The float results of :func:`run`, in order (their indices are ``F_*``)."""
F_UMAX, F_TPEAK, F_URES, F_TEND, F_AMAX, F_VMAX, F_UPEAK = range(7)
N_F = len(FLOAT_RESULTS)
"""Length of the float results."""
# columns of the history returned by :func:`run`
H_TAU, H_X, H_XD, H_U, H_UD, H_PHASE = range(6)
N_H = 6
"""Columns of the history."""

# event kinds (:func:`locate`); also the indices of the per-kind step counters
EV_DEMAND, EV_SPEED, EV_PEAK = range(3)
CNT_REJECTED = 3
"""Index of the rejected-step counter (after the three event kinds)."""

NAN = math.nan
MAX_STEPS = 5_000_000
"""Smallest step budget of a scene (see :func:`isoslide.solver.step_budget`)."""
ATOL_SLIDE = 1e-3
"""Absolute tolerance of the sliding components (u, u') relative to the base's:
keeps short slides just above the no-slide threshold accurate in relative terms."""


# --- small shared pieces (inlined) --------------------------------------------
# Inlined helpers keep to scalars or short straight code: numba adds reference
# counting for the array arguments of larger inlined code, paid on every step.


@njit(cache=True, inline="always")
def _left_limit(t):
    """A time just below ``t`` (by about one ulp): where a right-continuous pulse shows its left limit."""
    return t - max(abs(t), 1e-300) * 2.3e-16


@njit(cache=True, inline="always")
def _stuck_demand(x, xd, m):
    """``-(2 z w xd + w^2 x) / (1 + Pi8)``: the stuck demand of an isolated base, units of a_p.

    With ``(x, xd) = (x, x')`` it is ``a_req``; with ``(x', x'')`` its rate
    ``d a_req / d tau``; with ``(x'', x''')`` the rate's derivative.
    """
    return -(m[M_CW] * xd + m[M_W2] * x) / (1.0 + m[M_P8])


@njit(cache=True, inline="always")
def _demand_bound(y, m):
    """Largest stuck demand (units of a_p) the stuck base can reach with its current energy.

    ``sqrt(2 E ((2 z w)^2/(1+Pi8) + w^2)) / (1+Pi8)`` with
    ``E = (1+Pi8) x'^2/2 + w^2 x^2/2`` (see the module docstring); valid
    after the pulse, where ``E`` can only decrease.  Zero for a fixed base.
    """
    w2 = m[M_W2]
    cw = m[M_CW]
    mt = 1.0 + m[M_P8]
    energy = 0.5 * mt * y[1] * y[1] + 0.5 * w2 * y[0] * y[0]
    return math.sqrt(2.0 * energy * (cw * cw / mt + w2)) / mt


@njit(cache=True, inline="always")
def _hermite_coeffs(g0, d0, g1, d1, h):
    """Coefficients ``c, e`` of the cubic Hermite interpolant ``g0 + d0 t + c t^2 + e t^3`` on [0, h]."""
    c = (3.0 * (g1 - g0) / h - 2.0 * d0 - d1) / h
    e = (d0 + d1 - 2.0 * (g1 - g0) / h) / (h * h)
    return c, e


@njit(cache=True, inline="always")
def _step_factor(err):
    """Step-length factor after an error norm ``err`` (no smaller than 0.2)."""
    return max(0.2, 0.9 * err ** (-1.0 / 8.0))


@njit(cache=True, inline="always")
def _next_step(h, err):
    """Proposed length of the step after an accepted step ``h`` with error norm ``err`` (<= 10 h)."""
    if err == 0.0:
        return 10.0 * h
    return h * min(10.0, _step_factor(err))


@njit(cache=True, inline="always")
def _restart_step(short, h_restart, hlast):
    """Step length after a transition: ``h_restart`` if ``short``, else half the last step (at least h_restart)."""
    return h_restart if short else max(h_restart, 0.5 * hlast)


@njit(cache=True, inline="always")
def _error_terms(K, i):
    """DOP853's two error estimates of component ``i`` of a step, before scaling and the step length.

    Returns ``(a5, a3)``: the sums over the stages ``j`` of ``E5[j] K[j, i]`` and ``E3[j] K[j, i]``
    (``K`` the stage rates, the last row at the step's end).
    """
    a5 = 0.0
    a3 = 0.0
    for j in range(NS + 1):
        a5 += E5[j] * K[j, i]
        a3 += E3[j] * K[j, i]
    return a5, a3


@njit(cache=True, inline="always")
def _error_norm(e5, e3, h):
    """DOP853's error norm of a step of length ``h`` from the sums ``e5``, ``e3`` of the squared scaled estimates."""
    den = e5 + 0.01 * e3
    if den == 0.0:  # both estimates underflowed: the step is exact to round-off
        return 0.0
    return abs(h) * e5 / math.sqrt(den * 4.0)


@njit(cache=True, inline="always")
def error_scale(i, lo, hi, a, b, atol, rtol):
    """Tolerance of state component ``i`` for values ``a`` and ``b``.

    ``atol`` for the building's components, ``atol * ATOL_SLIDE`` for the sliding block's, which
    are the components ``lo <= i < hi`` of the state; plus ``rtol`` times the larger magnitude.
    """
    return (atol * ATOL_SLIDE if lo <= i < hi else atol) + rtol * max(abs(a), abs(b))


@njit(cache=True, inline="always")
def stage_state(y, h, K, st, ys):
    """The state ``ys = y + h sum_j A[st, j] K[j]`` at which stage ``st`` of a step of length ``h`` is evaluated."""
    for i in range(y.shape[0]):
        acc = 0.0
        for j in range(st):
            acc += A[st, j] * K[j, i]
        ys[i] = y[i] + h * acc


@njit(cache=True, inline="always")
def end_state(y, h, K, ynew):
    """The eighth-order end state ``ynew = y + h sum_j B[j] K[j]`` of a step of length ``h``."""
    for i in range(y.shape[0]):
        acc = 0.0
        for j in range(NS):
            acc += B[j] * K[j, i]
        ynew[i] = y[i] + h * acc


@njit(cache=True, inline="always")
def scaled_error(K, y, ynew, h, atol, rtol, lo, hi):
    """DOP853's error norm of the step ``y -> ynew`` of length ``h`` with stages ``K`` (accept when <= 1).

    Each component's estimates are scaled by :func:`error_scale` (the block's components
    ``lo <= i < hi``).
    """
    e5 = 0.0
    e3 = 0.0
    for i in range(y.shape[0]):
        sc = error_scale(i, lo, hi, y[i], ynew[i], atol, rtol)
        a5, a3 = _error_terms(K, i)
        e5 += (a5 / sc) ** 2
        e3 += (a3 / sc) ** 2
    return _error_norm(e5, e3, h)


@njit(cache=True, inline="always")
def doubling_error(y, yb, ycand, atol, rtol, lo, hi):
    """Scaled error of a step's end state ``ycand`` against ``yb``, the end of two half steps from ``y``.

    The largest ``|yb - ycand|`` over the components, each scaled by :func:`error_scale` (the
    block's components ``lo <= i < hi``); accept when <= 1.
    """
    e = 0.0
    for i in range(y.shape[0]):
        e = max(e, abs(yb[i] - ycand[i]) / error_scale(i, lo, hi, y[i], ycand[i], atol, rtol))
    return e


@njit(cache=True, inline="always")
def _next_breakpoint(breakpoints, ib, tau):
    """Index of the first of ``breakpoints`` (from ``ib`` on) after ``tau``; one within 1e-14 relative of ``tau`` is passed."""
    while ib < breakpoints.shape[0] and breakpoints[ib] <= tau + 1e-14 * max(1.0, abs(tau)):
        ib += 1
    return ib


@njit(cache=True, inline="always")
def _step_target(breakpoints, ib, tau_stop):
    """Where the next step ends at the latest: the breakpoint ``ib``, or ``tau_stop`` when it comes first or none is left."""
    if ib < breakpoints.shape[0] and breakpoints[ib] < tau_stop:
        return breakpoints[ib]
    return tau_stop


@njit(cache=True, inline="always")
def _slip_direction(demand):
    """Sliding direction ``s = -sign(a_req)`` of a block the demand ``a_req`` sets sliding."""
    return -1.0 if demand > 0.0 else 1.0


@njit(cache=True, inline="always")
def _break_away(demand, events):
    """Stuck -> sliding under the demand ``a_req``.

    Returns the new ``(stick, s, just_started, slipped, events)``.
    """
    return False, _slip_direction(demand), True, True, events + 1


@njit(cache=True, inline="always")
def checkpoint(stick, s, just_started, slipped, events, demand, y, m, after_pulse, at_stop, thr, fixed, settle,
               track_max, amax, settled):
    """Mode check at an accepted point, shared by the paper kernel and the piecewise-exact propagation.

    Stuck contents break away where the demand ``|a_req|`` exceeds ``thr`` (Pi5 / Pi2, in units
    of ``a_p``), unless only the largest demand is tracked (``track_max``, which keeps the peak in
    ``amax``).  After the pulse (``after_pulse``) stuck contents settle where the bound of
    :func:`_demand_bound` proves no later demand reaches ``thr`` (``amax`` when tracking), or at
    once on a fixed base; the run stops there when ``settle`` (when tracking, at once).  At the
    horizon (``at_stop``) the run stops, a tracked stuck block adding its remaining bound.

    Parameters
    ----------
    stick, s, just_started, slipped, events
        The contact's mode: stuck, sliding direction, phase began at this point, ever slid,
        transition count.
    demand : float
        ``a_req`` at the point (read only while stuck).
    y : ndarray
        The state ``(x, x', u, u')`` at the point.

    Returns
    -------
    tuple
        ``(stop, stick, s, just_started, slipped, events, amax, settled)``.
    """
    if stick:
        if track_max and abs(demand) > amax:
            amax = abs(demand)
        if abs(demand) > thr and not track_max:
            stick, s, just_started, slipped, events = _break_away(demand, events)
        elif after_pulse:
            if fixed:
                settled = True
                if settle:
                    return True, stick, s, just_started, slipped, events, amax, settled
            bound = _demand_bound(y, m)
            if track_max:
                if bound <= amax:
                    return True, stick, s, just_started, slipped, events, amax, True
            elif bound <= thr:
                settled = True
                if settle:
                    return True, stick, s, just_started, slipped, events, amax, settled
    if at_stop:
        if track_max and stick and not fixed:
            amax = max(amax, _demand_bound(y, m))
        return True, stick, s, just_started, slipped, events, amax, settled
    return False, stick, s, just_started, slipped, events, amax, settled


@njit(cache=True, inline="always")
def _update_peak(u, tau, umax, tpeak, upeak):
    """Largest ``|u|`` so far, its time and ``u`` there: ``(umax, tpeak, upeak)`` updated with ``u`` at ``tau``."""
    if abs(u) > umax:
        return abs(u), tau, u
    return umax, tpeak, upeak


@njit(cache=True, inline="always")
def copy_state(dst, src):
    """``dst[:n] = src`` for a state ``src`` of ``n`` components."""
    for i in range(src.shape[0]):
        dst[i] = src[i]


@njit(cache=True, inline="always")
def _record(hist, nh, hist_cap, tau, y, phase):
    """Append the row ``[tau, y, phase]`` to the history while it has room; returns the new row count."""
    if nh < hist_cap:
        hist[nh, H_TAU] = tau
        hist[nh, H_X:H_PHASE] = y
        hist[nh, H_PHASE] = phase
        return nh + 1
    return nh


# --- equations of motion ----------------------------------------------------


@njit(cache=True, inline="always")
def friction(v, m):
    """Friction level phi(|v|) in units of a_p (m: model parameters)."""
    thr = m[M_THR]
    if m[M_COULOMB] == 1.0:
        return thr
    if m[M_COULOMB] == 2.0:  # sharp static/kinetic switch (limit Pi6 -> inf)
        return m[M_PI2] + m[M_PI7] * abs(v)
    av = abs(v)
    e = math.exp(-m[M_PI6] * av)
    sech = 2.0 * e / (1.0 + e * e)
    pi2 = m[M_PI2]
    return thr * sech + pi2 * (1.0 - sech) + m[M_PI7] * av


@njit(cache=True, inline="always")
def deriv4(stick, s, tau, y0, y1, y2, y3, m, code, params):
    """Right-hand side of the current phase as a 4-tuple (inlined in the hot loop)."""
    if m[M_FIXED] != 0.0:
        if stick:
            return 0.0, 0.0, 0.0, 0.0
        return 0.0, 0.0, y3, -accel_at(code, params, tau) - s * friction(y3, m)
    p = accel_at(code, params, tau)
    F = m[M_CW] * y1 + m[M_W2] * y0
    p8 = m[M_P8]
    if stick:
        return y1, -p - F / (1.0 + p8), 0.0, 0.0
    ph = friction(y3, m)
    return y1, -p - F + p8 * s * ph, y3, F - (1.0 + p8) * s * ph


@njit(cache=True)
def deriv(stick, s, tau, y, m, code, params, out):
    """Right-hand side of the current phase, written into ``out``."""
    out[0], out[1], out[2], out[3] = deriv4(stick, s, tau, y[0], y[1], y[2], y[3], m, code, params)


@njit(cache=True)
def a_req(tau, y, m, code, params):
    """Floor acceleration (units of a_p) a stuck block needs: the stick demand."""
    if m[M_FIXED] != 0.0:
        return accel_at(code, params, tau)
    return _stuck_demand(y[0], y[1], m)


@njit(cache=True)
def a_req_rate(tau, y, m, code, params, work):
    """Rate d a_req / d tau of the stick demand (units of a_p / T_p); ``work`` is scratch."""
    if m[M_FIXED] != 0.0:
        return jerk_at(code, params, tau)
    deriv(True, 0.0, tau, y, m, code, params, work)
    return _stuck_demand(y[1], work[1], m)


# --- one Runge-Kutta step ---------------------------------------------------


@njit(cache=True)
def rk_step(stick, s, tau, y, h, m, code, params, atol, rtol, K, ynew):
    """One DOP853 step of length h from (tau, y) into ynew; returns the error norm.

    ``K`` (at least ``(NS + 1, 4)``) receives the stages; row ``NS`` is the
    right-hand side at the step end.  The norm is Hairer's combination of the
    fifth- and third-order estimates, scaled by :func:`error_scale`
    (accept when <= 1).  A stuck fixed base does not move: ``ynew = y``,
    error 0.
    """
    if stick and m[M_FIXED] != 0.0:
        copy_state(ynew, y)
        return 0.0
    # the pulse is right-continuous; stages at the step end use its left
    # limit so that a step ending on a breakpoint sees the step's own piece
    t_left = _left_limit(tau + h)
    K[0, 0], K[0, 1], K[0, 2], K[0, 3] = deriv4(stick, s, tau, y[0], y[1], y[2], y[3], m, code, params)
    for st in range(1, NS):
        a0 = 0.0
        a1 = 0.0
        a2 = 0.0
        a3 = 0.0
        for j in range(st):
            a = A[st, j]
            a0 += a * K[j, 0]
            a1 += a * K[j, 1]
            a2 += a * K[j, 2]
            a3 += a * K[j, 3]
        ts = t_left if C[st] == 1.0 else tau + C[st] * h
        K[st, 0], K[st, 1], K[st, 2], K[st, 3] = deriv4(
            stick, s, ts, y[0] + h * a0, y[1] + h * a1, y[2] + h * a2, y[3] + h * a3, m, code, params)
    end_state(y, h, K, ynew)
    K[NS, 0], K[NS, 1], K[NS, 2], K[NS, 3] = deriv4(stick, s, t_left, ynew[0], ynew[1], ynew[2],
                                                    ynew[3], m, code, params)
    return scaled_error(K, y, ynew, h, atol, rtol, 2, 4)


@njit(cache=True)
def verify(stick, s, tau, y, h, ycand, m, code, params, atol, rtol, K):
    """Richardson check of one step: error of ``ycand`` against two half steps.

    Used where the embedded error estimate is unreliable: on the step that
    ends at a located transition and, for the Stribeck law, while the sliding
    speed is inside the static-to-kinetic transition ``|u'| < 30 / Pi6``.
    Returns the scaled error norm (accept when <= 1).
    """
    ya = np.empty(4)
    yb = np.empty(4)
    rk_step(stick, s, tau, y, 0.5 * h, m, code, params, atol, rtol, K, ya)
    rk_step(stick, s, tau + 0.5 * h, ya, 0.5 * h, m, code, params, atol, rtol, K, yb)
    return doubling_error(y, yb, ycand, atol, rtol, 2, 4)


# --- events -------------------------------------------------------------------


@njit(cache=True)
def _event_value(kind, sig, stick, s, tau, y, m, code, params, work):
    """Event function and its tau-derivative.

    kind EV_DEMAND: stick demand  g = sig * a_req - thr     (stick -> slip)
    kind EV_SPEED:  slip speed    g = s * u'                 (slip ends)
    kind EV_PEAK:   demand rate   g = sig * d a_req/dtau     (extremum of the demand)
    """
    if kind == EV_DEMAND:
        g = sig * a_req(tau, y, m, code, params) - m[M_THR]
        dg = sig * a_req_rate(tau, y, m, code, params, work)
        return g, dg
    if kind == EV_SPEED:
        deriv(False, s, tau, y, m, code, params, work)
        return s * y[3], s * work[3]
    # EV_PEAK: the rate of the stuck demand and, for the isolated base, its
    # derivative in closed form (x''' = -p' - (c x'' + k x') / (1 + Pi8))
    if m[M_FIXED] != 0.0:
        return sig * jerk_at(code, params, tau), NAN
    xdd = -accel_at(code, params, tau) + _stuck_demand(y[0], y[1], m)
    r = _stuck_demand(y[1], xdd, m)
    xddd = -jerk_at(code, params, tau) + r
    dr = _stuck_demand(xdd, xddd, m)
    return sig * r, sig * dr


@njit(cache=True)
def hermite_root(g0, d0, g1, d1, h):
    """Root in (0, h) of the cubic Hermite interpolant of g (g0, g1 of opposite sign)."""
    c, e = _hermite_coeffs(g0, d0, g1, d1, h)
    lo, hi = 0.0, h
    glo = g0
    t = -g0 * h / (g1 - g0)
    for _it in range(30):
        gt = g0 + t * (d0 + t * (c + t * e))
        if (gt > 0.0) == (glo > 0.0):
            lo, glo = t, gt
        else:
            hi = t
        dt = d0 + t * (2.0 * c + 3.0 * t * e)
        tn = t - gt / dt if dt != 0.0 else 0.5 * (lo + hi)
        if not (lo < tn < hi):
            tn = 0.5 * (lo + hi)
        if abs(tn - t) <= 1e-15 * h:
            return tn
        t = tn
    return t


@njit(cache=True)
def _hermite_max(g0, d0, g1, d1, h):
    """Largest value of the cubic Hermite interpolant of g on [0, h]."""
    # p(t) = g0 + d0 t + c t^2 + e t^3 with t in [0, h]
    c, e = _hermite_coeffs(g0, d0, g1, d1, h)
    best = max(g0, g1)
    # p'(t) = d0 + 2 c t + 3 e t^2
    if e == 0.0:
        if c != 0.0:
            t = -d0 / (2.0 * c)
            if 0.0 < t < h:
                best = max(best, g0 + d0 * t + c * t * t)
        return best
    disc = 4.0 * c * c - 12.0 * e * d0
    if disc >= 0.0:
        sq = math.sqrt(disc)
        for t in ((-2.0 * c + sq) / (6.0 * e), (-2.0 * c - sq) / (6.0 * e)):
            if 0.0 < t < h:
                best = max(best, g0 + d0 * t + c * t * t + e * t * t * t)
    return best


ROOT_OPEN = 0
"""Bracket state of :func:`bracket_step`: no root yet, go on from the next trial."""
ROOT_AT_TRIAL = 1
"""Bracket state of :func:`bracket_step`: the trial itself is the root."""
ROOT_SHUT = 2
"""Bracket state of :func:`bracket_step`: the bracket is narrower than the tolerance, the root is its upper end."""


@njit(cache=True, inline="always")
def _regula_falsi(lo, glo, hi, ghi):
    """Secant point of the bracket ``(lo, hi)`` through ``(lo, glo)`` and ``(hi, ghi)``; its midpoint if ``glo == ghi``."""
    return lo - glo * (hi - lo) / (ghi - glo) if ghi != glo else 0.5 * (lo + hi)


@njit(cache=True, inline="always")
def first_trial(h0, lo, glo, hi, ghi):
    """First trial step length of the root search on the bracket ``(lo, hi)`` (same units as ``h0``).

    The guess ``h0`` when it lies strictly inside the bracket, else the secant point of the bracket,
    else (the secant point rounded onto an end) the midpoint.
    """
    h = h0 if lo < h0 < hi else _regula_falsi(lo, glo, hi, ghi)
    return h if lo < h < hi else 0.5 * (lo + hi)


@njit(cache=True, inline="always")
def bracket_open(tau, h0, ha, ga, hb, gb):
    """Start of a root search on the bracket ``(ha, hb)`` of step lengths from ``tau``.

    Returns ``(lo, glo, hi, ghi, side, tol, h)`` for :func:`bracket_step`: the bracket with the
    event function at its ends (``ga``, ``gb`` of opposite sign), no end moved yet, the tolerance
    ``1e-13 max(1, |tau|)`` on the step length and the first trial (:func:`first_trial` of the
    guess ``h0``).
    """
    return ha, ga, hb, gb, 0, 1e-13 * max(1.0, abs(tau)), first_trial(h0, ha, ga, hb, gb)


@njit(cache=True, inline="always")
def bracket_step(h, g, dg, lo, glo, hi, ghi, side, tol):
    """One step of safeguarded Newton / Illinois regula falsi on a bracket of a sign change.

    Parameters
    ----------
    h : float
        The trial step length just evaluated (same units as ``lo``, ``hi``, ``tol``).
    g, dg : float
        The event function at the trial and its derivative with respect to ``h`` (NaN: not given).
    lo, glo, hi, ghi : float
        The bracket ``(lo, hi)`` and the event function at its ends (of opposite sign).
    side : int
        Which end the previous step moved (-1 lower, +1 upper, 0 none): a second move of the same
        end halves the value kept at the other (Illinois).
    tol : float
        Absolute tolerance on the step length.

    Returns
    -------
    tuple
        ``(state, h, lo, glo, hi, ghi, side)``: ``state`` is :data:`ROOT_AT_TRIAL` (``g == 0`` or
        the Newton correction ``|g / dg|`` is within ``tol``), :data:`ROOT_SHUT` (the bracket is
        narrower than ``tol``: the root is ``hi``) or :data:`ROOT_OPEN`; ``h`` is then the next
        trial: the Newton step where it stays strictly inside the bracket, else the secant point,
        else the midpoint.
    """
    if g == 0.0:
        return ROOT_AT_TRIAL, h, lo, glo, hi, ghi, side
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
    newton = not math.isnan(dg) and dg != 0.0
    if newton and abs(g / dg) <= tol:
        return ROOT_AT_TRIAL, h, lo, glo, hi, ghi, side
    if hi - lo <= tol:
        return ROOT_SHUT, hi, lo, glo, hi, ghi, side
    if newton and lo < h - g / dg < hi:
        h = h - g / dg
    else:
        h = _regula_falsi(lo, glo, hi, ghi)
    return ROOT_OPEN, (h if lo < h < hi else 0.5 * (lo + hi)), lo, glo, hi, ghi, side


@njit(cache=True)
def locate(kind, sig, stick, s, tau, y, ha, ga, hb, gb, h0, check, m, code, params, atol, rtol,
           K, yout, work, cnt):
    """Find h in (ha, hb] with g(step(tau, y, h)) = 0, ga and gb of opposite sign.

    Safeguarded Newton from the guess ``h0`` (the root of the step's cubic
    Hermite interpolant when available), falling back to Illinois regula
    falsi when the derivative is unavailable or Newton leaves the bracket.
    Each trial re-steps from the accepted point (tau, y), so the event state
    carries the integrator's own accuracy; the iteration stops when the Newton
    correction is below 1e-13 (relative to max(1, |tau|)).  ``yout`` receives
    the state at the root; returns the step length and the error estimate of
    that step (step doubling added when ``check``).  Every step taken is
    counted in ``cnt[kind]``.
    """
    lo, glo, hi, ghi, side, tol, h = bracket_open(tau, h0, ha, ga, hb, gb)
    err = 0.0
    state = ROOT_OPEN
    for _it in range(100):
        err = rk_step(stick, s, tau, y, h, m, code, params, atol, rtol, K, yout)
        cnt[kind] += 1
        g, dg = _event_value(kind, sig, stick, s, tau + h, yout, m, code, params, work)
        state, h, lo, glo, hi, ghi, side = bracket_step(h, g, dg, lo, glo, hi, ghi, side, tol)
        if state != ROOT_OPEN:
            break
    on_res = state == ROOT_AT_TRIAL
    res = h if on_res else hi
    if not on_res:
        err = rk_step(stick, s, tau, y, res, m, code, params, atol, rtol, K, yout)
        cnt[kind] += 1
    if check and err <= 1.0:
        err = max(err, verify(stick, s, tau, y, res, yout, m, code, params, atol, rtol, K))
        cnt[kind] += 2
    return res, err


@njit(cache=True, inline="always")
def _stick_event_possible(ar0, ar1, r0, r1, h, thr, track_max):
    """Whether :func:`_stick_event` has anything to locate in the stuck step of length ``h``.

    ``ar0, ar1`` are the stuck demand and ``r0, r1`` its rate at the two ends
    of the step.  True when the step ends above the threshold, or the demand
    has an interior peak that may exceed it (any peak with ``track_max``): the
    same tests :func:`_stick_event` makes, done first so that the common
    stuck step costs no call.
    """
    for sig in (1.0, -1.0):
        if not track_max and sig * ar1 - thr > 0.0:
            return True
    for sig in (1.0, -1.0):
        d0 = sig * r0
        d1 = sig * r1
        if not (d0 > 0.0 and d1 < 0.0):
            continue
        if track_max or not (_hermite_max(sig * ar0 - thr, d0, sig * ar1 - thr, d1, h) < -1e-2 * thr):
            return True
    return False


@njit(cache=True)
def _stick_event(s, tau, y, h, ar0, ar1, r0, r1, track_max, check, m, code, params, atol, rtol, K, ye, work,
                 cnt, amax):
    """First breakaway inside the accepted stuck step of length ``h`` from ``(tau, y)``.

    ``ar0, ar1`` are the stuck demand and ``r0, r1`` its rate at the two ends
    of the step.  A breakaway is a root of ``sig a_req - thr`` (either sign
    ``sig``): found directly when the step ends above the threshold, or else
    past an interior peak of the demand (a root of its rate) that exceeds the
    threshold; peaks whose Hermite estimate stays 1 % of ``thr`` below it are
    not examined.  With ``track_max`` there is no breakaway: every interior
    peak of ``|a_req|`` raises ``amax``.

    Returns ``(found, hs, herr, amax)``: whether a breakaway was found, the
    step length to it and that step's error norm (``ye`` holds the state
    there), and the largest stuck demand seen.
    """
    thr = m[M_THR]
    found = False
    hs = 0.0
    herr = 0.0
    if not track_max:
        for sig in (1.0, -1.0):
            g0 = sig * ar0 - thr
            g1 = sig * ar1 - thr
            if g1 > 0.0:
                h0 = hermite_root(g0, sig * r0, g1, sig * r1, h)
                hs, herr = locate(EV_DEMAND, sig, True, s, tau, y, 0.0, g0, h, g1, h0, check, m, code,
                                  params, atol, rtol, K, ye, work, cnt)
                found = True
                break
    for sig in (1.0, -1.0):
        if found:
            break
        d0 = sig * r0
        d1 = sig * r1
        if not (d0 > 0.0 and d1 < 0.0):
            continue
        g0 = sig * ar0 - thr
        g1 = sig * ar1 - thr
        if not track_max and _hermite_max(g0, d0, g1, d1, h) < -1e-2 * thr:
            continue
        hm, herr = locate(EV_PEAK, sig, True, s, tau, y, 0.0, d0, h, d1, -1.0, False, m, code,
                          params, atol, rtol, K, ye, work, cnt)
        am = sig * a_req(tau + hm, ye, m, code, params)
        if track_max:
            if am > amax:
                amax = am
        elif am - thr > 0.0:
            hs, herr = locate(EV_DEMAND, sig, True, s, tau, y, 0.0, g0, hm, am - thr, -1.0, check, m,
                              code, params, atol, rtol, K, ye, work, cnt)
            found = True
    return found, hs, herr, amax


@njit(cache=True)
def _slip_end(s, tau, y, h, g1, just_started, check, m, code, params, atol, rtol, K, ye, work, cnt):
    """End of slip inside the sliding step of length ``h`` from ``(tau, y)``.

    ``g1 = s u' <= 0`` at the step end.  When the slip began at ``tau``
    (``just_started``, where ``s u' = 0``) an interior point with
    ``s u' > 0`` is found first by halving the step; without one the slip
    ends at once (``hs = 0``).  The stages of the step must be in ``K``.

    Returns ``(hs, herr)``: the step length to the end of slip and that
    step's error norm; ``ye`` holds the state there.
    """
    if just_started:
        # the slip began at this step's start, where g = 0: find an
        # interior point with g > 0 before bracketing the end of slip
        hp = h
        gp = g1
        for _k in range(200):
            hp *= 0.5
            rk_step(False, s, tau, y, hp, m, code, params, atol, rtol, K, ye)
            cnt[EV_SPEED] += 1
            gp = s * ye[3]
            if gp > 0.0 or hp < 1e-300:
                break
        if gp > 0.0:
            return locate(EV_SPEED, 0.0, False, s, tau, y, hp, gp, h, g1, -1.0, check, m, code, params,
                          atol, rtol, K, ye, work, cnt)
        copy_state(ye, y)
        return 0.0, 0.0
    glo = s * y[3]
    h0 = hermite_root(glo, s * K[0, 3], g1, s * K[NS, 3], h)
    return locate(EV_SPEED, 0.0, False, s, tau, y, 0.0, glo, h, g1, h0, check, m, code, params, atol,
                  rtol, K, ye, work, cnt)


# --- one scene ------------------------------------------------------------------


@njit(cache=True)
def run(m, code, params, breakpoints, tau_start, tau_end, tau_stop, h_max_pulse, h_max_free,
        rtol, atol, track_max, hist_cap, h_restart, settle, max_steps):
    """Integrate one scene from rest at ``tau_start``; see the module docstring.

    Time is in units of T_p, lengths in a_p T_p^2, speeds in a_p T_p,
    accelerations in a_p.

    Parameters
    ----------
    m : ndarray of float64, shape (N_M,)
        Model parameters: ``m[M_W2] = w^2 = (2 pi / Pi3)^2`` and
        ``m[M_CW] = 2 Pi4 w`` (both 0 for a fixed base), ``m[M_P8] = Pi8``
        (0: one-way coupling), ``m[M_THR]`` the static level ``Pi2/Pi5``
        (``inf`` with ``track_max``), ``m[M_PI2]``, ``m[M_PI6]``,
        ``m[M_PI7]`` the friction groups, ``m[M_FIXED]`` 1.0 for a fixed base
        (else 0.0), ``m[M_COULOMB]`` the friction law: 0.0 Stribeck, 1.0
        Coulomb at the static level, 2.0 static-kinetic switch (stick up to
        ``thr``, ``Pi2 + Pi7 |u'|`` at any sliding speed).
    code : int
        Pulse shape code (:mod:`isoslide.pulses`).
    params : ndarray of float64
        Pulse shape parameters.
    breakpoints : ndarray of float64
        Sorted times where the pulse or its derivatives jump (steps end on
        them), ``tau_end`` included.
    tau_start, tau_end : float
        Start and end of the pulse (ground acceleration 0 outside).
    tau_stop : float
        Horizon: the integration stops here if the scene has not settled.
    h_max_pulse, h_max_free : float
        Longest step during the pulse and after it.
    rtol, atol : float
        Per-step relative tolerance and absolute tolerance of ``x, x'``
        (``atol * ATOL_SLIDE`` for ``u, u'``).
    track_max : bool
        Keep the block stuck and record the largest stuck demand ``|a_req|``
        instead (``F_AMAX``; ``m[M_THR]`` must be ``inf``).  The run stops once
        the energy bound after the pulse is below the largest demand seen
        (settled), else at the horizon, where the bound is added to
        ``F_AMAX`` so that it stays an upper bound.
    hist_cap : int
        Rows of history to keep (0: none).
    h_restart : float
        Step length after a transition, or half the last step if that is
        longer (not when a slip begins under the Stribeck law, whose
        static-to-kinetic transition zone is checked step by step).
    settle : bool
        Stop at settlement (else follow the scene to the horizon).
    max_steps : int
        Step budget: the integration stops after this many Runge-Kutta steps
        (``F_TEND < tau_stop`` then tells a truncated run).

    Returns
    -------
    ints : ndarray of int64, shape (N_R,)
        ``R_STEPS`` Runge-Kutta steps of every kind (accepted, rejected,
        verification and event-location steps); ``R_EVENTS`` transitions
        (breakaways and ends of slip, a reversal counted once);
        ``R_SETTLED`` 1 if the scene settled; ``R_SLIPPED`` 1 if the block
        slid at all; ``R_HIST`` rows of ``hist``; ``R_LOC_STICK``, ``R_LOC_SLIP``, ``R_LOC_PEAK`` steps spent
        locating breakaways, ends of slip and peaks of the stuck demand
        (included in ``R_STEPS``); ``R_REJECTED`` steps rejected by the error
        test (included in ``R_STEPS``).
    floats : ndarray of float64, shape (N_F,)
        ``F_UMAX`` largest ``|u|`` (= Pi1); ``F_TPEAK`` time it was reached
        (``tau_start`` if the block never slid); ``F_URES`` ``u`` at the end
        (residual displacement); ``F_TEND`` time the integration stopped;
        ``F_AMAX`` largest stuck demand ``|a_req|`` (``track_max`` only, else
        0); ``F_VMAX`` largest ``|u'|`` at the ends of accepted sliding steps.
    hist : ndarray of float64, shape (ints[R_HIST], N_H)
        Rows ``[tau, x, x', u, u', phase]`` (columns ``H_TAU`` ... ``H_PHASE``)
        at the start, at every accepted step and at every transition, the
        first ``hist_cap`` of them.  ``phase`` is 0 while stuck, the sliding
        direction ``s = +-1`` while sliding; the row of a breakaway has phase
        0 (the state just before sliding), the row of an end of slip the phase
        that follows it.
    """
    thr = m[M_THR]
    fixed = m[M_FIXED] != 0.0
    y = np.zeros(4)
    y1 = np.empty(4)
    ye = np.empty(4)
    K = np.empty((NS + 2, 4))
    work = np.empty(4)
    cnt = np.zeros(4, dtype=np.int64)
    hist = np.empty((hist_cap if hist_cap > 0 else 1, N_H))
    tau = tau_start
    stick = True
    s = 0.0
    just_started = False
    umax = 0.0
    tpeak = tau_start
    upeak = 0.0
    steps = 0
    events = 0
    settled = False
    slipped = False
    amax = 0.0
    vmax = 0.0
    h = h_restart
    hlast = h_restart
    ib = 0
    nh = _record(hist, 0, hist_cap, tau, y, 0.0)
    hs = 0.0
    herr = 0.0
    zone = 0.0
    if m[M_COULOMB] == 0.0 and m[M_PI6] > 0.0 and m[M_PI2] < thr:
        zone = 30.0 / m[M_PI6]
    check = zone > 0.0
    while True:
        # --- mode checks at the current (accepted) point -------------------
        stop, stick, s, just_started, slipped, events, amax, settled = checkpoint(
            stick, s, just_started, slipped, events, a_req(tau, y, m, code, params) if stick else 0.0, y, m,
            tau >= tau_end, tau >= tau_stop or steps > max_steps, thr, fixed, settle, track_max, amax, settled)
        if stop:
            break
        # --- step length -----------------------------------------------------
        ib = _next_breakpoint(breakpoints, ib, tau)
        hmax = h_max_pulse if tau < tau_end else h_max_free
        h = min(h, hmax)
        target = _step_target(breakpoints, ib, tau_stop)
        if stick and fixed:
            h = hmax
        hit_target = False
        if tau + h >= target:
            h = target - tau
            hit_target = True
        # --- attempt until accepted -------------------------------------------
        while True:
            err = rk_step(stick, s, tau, y, h, m, code, params, atol, rtol, K, y1)
            steps += 1
            if err <= 1.0 and not stick and zone > 0.0 and (
                    min(abs(y[3]), abs(y1[3])) < zone or y[3] * y1[3] <= 0.0):
                err = max(err, verify(stick, s, tau, y, h, y1, m, code, params, atol, rtol, K))
                steps += 2
            if err <= 1.0:
                break
            cnt[CNT_REJECTED] += 1
            h *= _step_factor(err)
            hit_target = False
        hnext = _next_step(h, err)
        # --- events inside the step -------------------------------------------
        tnew = tau + h
        if hit_target:
            tnew = target
        if stick:
            # the stuck demand and its rate at both ends of the step; for the
            # isolated base the rates come from the step's own first and last stages
            ar0 = a_req(tau, y, m, code, params)
            # the demand at the step's end as the step saw it: on a fixed base the ground
            # acceleration's left limit (a record's last sample, not the zero after it)
            ar1 = a_req(_left_limit(tnew) if fixed else tnew, y1, m, code, params)
            if fixed:
                r0 = jerk_at(code, params, tau)
                r1 = jerk_at(code, params, _left_limit(tnew))
            else:
                r0 = _stuck_demand(y[1], K[0, 1], m)
                r1 = _stuck_demand(y1[1], K[NS, 1], m)
            found = False
            if _stick_event_possible(ar0, ar1, r0, r1, h, thr, track_max):
                found, hs, herr, amax = _stick_event(s, tau, y, h, ar0, ar1, r0, r1, track_max, check, m, code,
                                                     params, atol, rtol, K, ye, work, cnt, amax)
            if found:
                if herr > 1.0:
                    # the single step to the event is not accurate enough:
                    # retry from the same point with a shorter step
                    h = 0.5 * hs
                    continue
                tau = tau + hs
                copy_state(y, ye)
                stick, s, just_started, slipped, events = _break_away(a_req(tau, y, m, code, params), events)
                h = _restart_step(check, h_restart, hlast)
                nh = _record(hist, nh, hist_cap, tau, y, 0.0)
                continue
        else:
            g1 = s * y1[3]
            if g1 <= 0.0:
                hs, herr = _slip_end(s, tau, y, h, g1, just_started, check, m, code, params, atol, rtol,
                                     K, ye, work, cnt)
                if herr > 1.0:
                    h = 0.5 * hs
                    continue
                tau = tau + hs
                copy_state(y, ye)
                y[3] = 0.0
                events += 1
                umax, tpeak, upeak = _update_peak(y[2], tau, umax, tpeak, upeak)
                ar = a_req(tau, y, m, code, params)
                if abs(ar) <= thr:
                    stick = True
                    s = 0.0
                    just_started = False
                else:
                    s = _slip_direction(ar)
                    just_started = True
                h = _restart_step(check and not stick, h_restart, hlast)
                nh = _record(hist, nh, hist_cap, tau, y, s)
                continue
            just_started = False
            if abs(y1[3]) > vmax:
                vmax = abs(y1[3])
        # --- accept -------------------------------------------------------------
        tau = tnew
        copy_state(y, y1)
        if stick:
            y[3] = 0.0
        hlast = h
        h = hnext
        nh = _record(hist, nh, hist_cap, tau, y, s)
    if not settled and not stick:
        umax, tpeak, upeak = _update_peak(y[2], tau, umax, tpeak, upeak)
    ints = np.array([steps + cnt[EV_DEMAND] + cnt[EV_SPEED] + cnt[EV_PEAK], events, 1 if settled else 0,
                     1 if slipped else 0, nh, cnt[EV_DEMAND], cnt[EV_SPEED], cnt[EV_PEAK],
                     cnt[CNT_REJECTED]], dtype=np.int64)
    floats = np.array([umax, tpeak, y[2], tau, amax, vmax, upeak])
    return ints, floats, hist[:nh]


# numba reads the compiled code shipped with the package (isoslide.jit_cache) before compiling any of it
jit_cache.seed(run)
