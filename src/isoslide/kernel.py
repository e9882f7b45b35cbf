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
Dormand-Prince 8(5,3) pair (coefficients from SciPy); every transition is
located by a safeguarded Newton iteration on the step length, re-stepping from
the last accepted point, so it is found to ~1e-13 T_p.  Steps end exactly on the
pulse breakpoints.

Stopping (settlement): after the pulse (``tau >= tau_end``, ``p = 0``) the
total energy of the stuck system ``E = (1+Pi8) x'^2/2 + w^2 x^2/2`` can only
decrease.  Over all states with energy ``E``, the largest possible demand is
``max |F|/(1+Pi8) = sqrt(2 E ((2 z w)^2/(1+Pi8) + w^2)) / (1+Pi8)``.  Once that
bound is ``<= Pi2/Pi5`` while stuck, no further sliding is possible: the scene
is *settled* and the integration stops.  With ``z = 0`` the bound is attained
every half cycle, so a scene whose bound stays above the threshold never
settles; it is followed to the horizon and flagged ``settled = False``.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from scipy.integrate._ivp import dop853_coefficients as _dop

from .pulses import accel_at, jerk_at

NS = _dop.N_STAGES
A = np.ascontiguousarray(_dop.A[:NS, :NS], dtype=np.float64)
B = np.ascontiguousarray(_dop.B, dtype=np.float64)
C = np.ascontiguousarray(_dop.C[:NS], dtype=np.float64)
E3 = np.ascontiguousarray(_dop.E3, dtype=np.float64)
E5 = np.ascontiguousarray(_dop.E5, dtype=np.float64)

# indices into the model-parameter array ``m``
M_W2, M_CW, M_P8, M_THR, M_PI2, M_PI6, M_PI7, M_FIXED, M_COULOMB = range(9)
N_M = 9

# integer results
R_STEPS, R_EVENTS, R_SETTLED, R_SLIPPED, R_HIST, R_LOC_STICK, R_LOC_SLIP, R_LOC_PEAK, R_REJECTED = range(9)
# float results
F_UMAX, F_TPEAK, F_URES, F_TEND, F_AMAX, F_VMAX = range(6)

NAN = math.nan
MAX_STEPS = 5_000_000
ATOL_SLIDE = 1e-3
"""Absolute tolerance of the sliding components (u, u') relative to the base's:
keeps short slides just above the no-slide threshold accurate in relative terms."""
"""Safety cap on integrator steps per scene (a scene that hits it is reported unsettled)."""


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
    d0, d1, d2, d3 = deriv4(stick, s, tau, y[0], y[1], y[2], y[3], m, code, params)
    out[0] = d0
    out[1] = d1
    out[2] = d2
    out[3] = d3


@njit(cache=True)
def a_req(tau, y, m, code, params):
    """Floor acceleration (units of a_p) a stuck block needs: the stick demand."""
    if m[M_FIXED] != 0.0:
        return accel_at(code, params, tau)
    return -(m[M_CW] * y[1] + m[M_W2] * y[0]) / (1.0 + m[M_P8])


@njit(cache=True)
def a_req_rate(tau, y, m, code, params, work):
    """d a_req / d tau in stick."""
    if m[M_FIXED] != 0.0:
        return jerk_at(code, params, tau)
    deriv(True, 0.0, tau, y, m, code, params, work)
    return -(m[M_CW] * work[1] + m[M_W2] * y[1]) / (1.0 + m[M_P8])


@njit(cache=True)
def rk_step(stick, s, tau, y, h, m, code, params, atol, rtol, K, ynew):
    """One DOP853 step of length h from (tau, y) into ynew; returns the error norm."""
    if stick and m[M_FIXED] != 0.0:
        for i in range(4):
            ynew[i] = y[i]
        return 0.0
    # the pulse is right-continuous; stages at the step end use its left
    # limit so that a step ending on a breakpoint sees the step's own piece
    t_end = tau + h
    t_left = t_end - max(abs(t_end), 1e-300) * 2.3e-16
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
    for i in range(4):
        acc = 0.0
        for j in range(NS):
            acc += B[j] * K[j, i]
        ynew[i] = y[i] + h * acc
    K[NS, 0], K[NS, 1], K[NS, 2], K[NS, 3] = deriv4(stick, s, t_left, ynew[0], ynew[1], ynew[2],
                                                    ynew[3], m, code, params)
    e5 = 0.0
    e3 = 0.0
    for i in range(4):
        sc = (atol if i < 2 else atol * ATOL_SLIDE) + rtol * max(abs(y[i]), abs(ynew[i]))
        a5 = 0.0
        a3 = 0.0
        for j in range(NS + 1):
            a5 += E5[j] * K[j, i]
            a3 += E3[j] * K[j, i]
        e5 += (a5 / sc) ** 2
        e3 += (a3 / sc) ** 2
    if e5 == 0.0 and e3 == 0.0:
        return 0.0
    den = e5 + 0.01 * e3
    if den == 0.0:  # both estimates underflowed: the step is exact to round-off
        return 0.0
    return abs(h) * e5 / math.sqrt(den * 4.0)


@njit(cache=True)
def _event_value(kind, sig, stick, s, tau, y, m, code, params, work):
    """Event function and its tau-derivative.

    kind 0: stick demand  g = sig * a_req - thr     (stick -> slip)
    kind 1: slip speed    g = s * u'                 (slip ends)
    kind 2: demand rate   g = sig * d a_req/dtau     (extremum of the demand)
    """
    if kind == 0:
        g = sig * a_req(tau, y, m, code, params) - m[M_THR]
        dg = sig * a_req_rate(tau, y, m, code, params, work)
        return g, dg
    if kind == 1:
        deriv(False, s, tau, y, m, code, params, work)
        return s * y[3], s * work[3]
    # kind 2: the rate of the stuck demand and, for the isolated base, its
    # derivative in closed form (x''' = -p' - (c x'' + k x') / (1 + Pi8))
    if m[M_FIXED] != 0.0:
        return sig * jerk_at(code, params, tau), NAN
    mt = 1.0 + m[M_P8]
    cw = m[M_CW]
    w2 = m[M_W2]
    xdd = -accel_at(code, params, tau) - (cw * y[1] + w2 * y[0]) / mt
    xddd = -jerk_at(code, params, tau) - (cw * xdd + w2 * y[1]) / mt
    r = -(cw * xdd + w2 * y[1]) / mt
    dr = -(cw * xddd + w2 * xdd) / mt
    return sig * r, sig * dr


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
    e = 0.0
    for i in range(4):
        sc = (atol if i < 2 else atol * ATOL_SLIDE) + rtol * max(abs(y[i]), abs(ycand[i]))
        e = max(e, abs(yb[i] - ycand[i]) / sc)
    return e


@njit(cache=True)
def hermite_root(g0, d0, g1, d1, h):
    """Root in (0, h) of the cubic Hermite interpolant of g (g0, g1 of opposite sign)."""
    c = (3.0 * (g1 - g0) / h - 2.0 * d0 - d1) / h
    e = (d0 + d1 - 2.0 * (g1 - g0) / h) / (h * h)
    lo, hi = 0.0, h
    glo = g0
    t = -g0 * h / (g1 - g0)
    for it in range(30):
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
    that step (step doubling added when ``check``).
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
    for it in range(100):
        if not (lo < h < hi):
            h = 0.5 * (lo + hi)
        err = rk_step(stick, s, tau, y, h, m, code, params, atol, rtol, K, yout)
        cnt[kind] += 1
        g, dg = _event_value(kind, sig, stick, s, tau + h, yout, m, code, params, work)
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
        if not math.isnan(dg) and dg != 0.0:
            dh = g / dg
            if abs(dh) <= tol:
                res, on_res = h, True  # converged: the root is h to ~1e-13
                break
        res = hi
        if hi - lo <= tol:
            break
        if not math.isnan(dg) and dg != 0.0 and lo < h - g / dg < hi:
            h = h - g / dg
        else:
            h = lo - glo * (hi - lo) / (ghi - glo) if ghi != glo else 0.5 * (lo + hi)
    if not on_res:
        err = rk_step(stick, s, tau, y, res, m, code, params, atol, rtol, K, yout)
        cnt[kind] += 1
    if check and err <= 1.0:
        err = max(err, verify(stick, s, tau, y, res, yout, m, code, params, atol, rtol, K))
        cnt[kind] += 2
    return res, err


@njit(cache=True)
def _hermite_max(g0, d0, g1, d1, h):
    """Largest value of the cubic Hermite interpolant of g on [0, h]."""
    # p(t) = g0 + d0 t + c t^2 + e t^3 with t in [0, h]
    c = (3.0 * (g1 - g0) / h - 2.0 * d0 - d1) / h
    e = (d0 + d1 - 2.0 * (g1 - g0) / h) / (h * h)
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


@njit(cache=True)
def run(m, code, params, breakpoints, tau_start, tau_end, tau_stop, h_max_pulse, h_max_free,
        rtol, atol, track_max, hist_cap, h_restart, settle):
    """Integrate one scene; see the module docstring.

    Returns (ints, floats, hist, nhist) where ints = [steps, events, settled,
    slipped, nhist], floats = [u_max, tau_peak, u_residual, tau_end,
    max stuck demand (track_max only), max |u'|], hist = (nhist, 6) array of
    [tau, x, x', u, u', phase] (phase 0 stick, +-1 slip).
    """
    thr = m[M_THR]
    fixed = m[M_FIXED] != 0.0
    y = np.zeros(4)
    y1 = np.empty(4)
    ye = np.empty(4)
    K = np.empty((NS + 2, 4))
    work = np.empty(4)
    cnt = np.zeros(4, dtype=np.int64)
    hist = np.empty((hist_cap if hist_cap > 0 else 1, 6))
    nh = 0
    tau = tau_start
    stick = True
    s = 0.0
    just_started = False
    umax = 0.0
    tpeak = tau_start
    steps = 0
    events = 0
    settled = False
    slipped = False
    amax = 0.0
    vmax = 0.0
    h = h_restart
    hlast = h_restart
    ib = 0
    nb = breakpoints.shape[0]
    if hist_cap > 0:
        hist[0, 0] = tau
        hist[0, 1:5] = 0.0
        hist[0, 5] = 0.0
        nh = 1
    hs = 0.0
    herr = 0.0
    zone = 0.0
    if m[M_COULOMB] == 0.0 and m[M_PI6] > 0.0 and m[M_PI2] < thr:
        zone = 30.0 / m[M_PI6]
    check = zone > 0.0
    while True:
        # --- mode checks at the current (accepted) point -------------------
        if stick:
            ar = a_req(tau, y, m, code, params)
            if track_max and abs(ar) > amax:
                amax = abs(ar)
            if abs(ar) > thr and not track_max:
                stick = False
                s = -1.0 if ar > 0.0 else 1.0
                just_started = True
                slipped = True
                events += 1
            elif tau >= tau_end:
                if fixed:
                    settled = True
                    if settle:
                        break
                w2 = m[M_W2]
                cw = m[M_CW]
                mt = 1.0 + m[M_P8]
                energy = 0.5 * mt * y[1] * y[1] + 0.5 * w2 * y[0] * y[0]
                bound = math.sqrt(2.0 * energy * (cw * cw / mt + w2)) / mt
                if track_max:
                    if bound <= amax:
                        settled = True
                        break
                elif bound <= thr:
                    settled = True
                    if settle:
                        break
        if tau >= tau_stop or steps > MAX_STEPS:
            if track_max and stick and not fixed:
                w2 = m[M_W2]
                cw = m[M_CW]
                mt = 1.0 + m[M_P8]
                energy = 0.5 * mt * y[1] * y[1] + 0.5 * w2 * y[0] * y[0]
                amax = max(amax, math.sqrt(2.0 * energy * (cw * cw / mt + w2)) / mt)
            break
        # --- step length -----------------------------------------------------
        while ib < nb and breakpoints[ib] <= tau + 1e-14 * max(1.0, abs(tau)):
            ib += 1
        hmax = h_max_pulse if tau < tau_end else h_max_free
        h = min(h, hmax)
        target = tau_stop
        if ib < nb and breakpoints[ib] < target:
            target = breakpoints[ib]
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
            cnt[3] += 1
            fac = max(0.2, 0.9 * err ** (-1.0 / 8.0))
            h *= fac
            hit_target = False
        if err == 0.0:
            hnext = 10.0 * h
        else:
            hnext = h * min(10.0, max(0.2, 0.9 * err ** (-1.0 / 8.0)))
        # --- events inside the step -------------------------------------------
        tnew = tau + h
        if hit_target:
            tnew = target
        if stick:
            found = False
            # demand and its rate at both ends of the step; for the isolated
            # base the rates come from the step's own first and last stages
            ar0 = a_req(tau, y, m, code, params)
            ar1 = a_req(tnew, y1, m, code, params)
            if fixed:
                r0 = jerk_at(code, params, tau)
                r1 = jerk_at(code, params, tnew - max(abs(tnew), 1e-300) * 2.3e-16)
            else:
                mt = 1.0 + m[M_P8]
                r0 = -(m[M_CW] * K[0, 1] + m[M_W2] * y[1]) / mt
                r1 = -(m[M_CW] * K[NS, 1] + m[M_W2] * y1[1]) / mt
            if not track_max:
                for sig in (1.0, -1.0):
                    g0 = sig * ar0 - thr
                    g1 = sig * ar1 - thr
                    if g1 > 0.0:
                        h0 = hermite_root(g0, sig * r0, g1, sig * r1, h)
                        hs, herr = locate(0, sig, True, s, tau, y, 0.0, g0, h, g1, h0, check, m, code,
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
                hm, herr = locate(2, sig, True, s, tau, y, 0.0, d0, h, d1, -1.0, False, m, code,
                                  params, atol, rtol, K, ye, work, cnt)
                am = sig * a_req(tau + hm, ye, m, code, params)
                if track_max:
                    if am > amax:
                        amax = am
                elif am - thr > 0.0:
                    hs, herr = locate(0, sig, True, s, tau, y, 0.0, g0, hm, am - thr, -1.0, check, m,
                                      code, params, atol, rtol, K, ye, work, cnt)
                    found = True
            if found and herr > 1.0:
                # the single step to the event is not accurate enough: retry
                # from the same point with a shorter step
                h = 0.5 * hs
                continue
            if found:
                tau = tau + hs
                for i in range(4):
                    y[i] = ye[i]
                ar = a_req(tau, y, m, code, params)
                stick = False
                s = -1.0 if ar > 0.0 else 1.0
                just_started = True
                slipped = True
                events += 1
                h = h_restart if check else max(h_restart, 0.5 * hlast)
                if hist_cap > 0 and nh < hist_cap:
                    hist[nh, 0] = tau
                    hist[nh, 1:5] = y
                    hist[nh, 5] = 0.0
                    nh += 1
                continue
        else:
            g1 = s * y1[3]
            if g1 <= 0.0:
                lo = 0.0
                glo = 0.0
                if just_started:
                    # the slip began at this step's start, where g = 0: find an
                    # interior point with g > 0 before bracketing the end of slip
                    hp = h
                    gp = g1
                    for k in range(200):
                        hp *= 0.5
                        rk_step(stick, s, tau, y, hp, m, code, params, atol, rtol, K, ye)
                        cnt[1] += 1
                        gp = s * ye[3]
                        if gp > 0.0 or hp < 1e-300:
                            break
                    if gp > 0.0:
                        lo = hp
                        glo = gp
                        hs, herr = locate(1, 0.0, False, s, tau, y, lo, glo, h, g1, -1.0, check, m,
                                          code, params, atol, rtol, K, ye, work, cnt)
                    else:
                        hs = 0.0
                        herr = 0.0
                        for i in range(4):
                            ye[i] = y[i]
                else:
                    glo = s * y[3]
                    h0 = hermite_root(glo, s * K[0, 3], g1, s * K[NS, 3], h)
                    hs, herr = locate(1, 0.0, False, s, tau, y, 0.0, glo, h, g1, h0, check, m, code,
                                      params, atol, rtol, K, ye, work, cnt)
                if herr > 1.0:
                    h = 0.5 * hs
                    continue
                tau = tau + hs
                for i in range(4):
                    y[i] = ye[i]
                y[3] = 0.0
                events += 1
                if abs(y[2]) > umax:
                    umax = abs(y[2])
                    tpeak = tau
                ar = a_req(tau, y, m, code, params)
                if abs(ar) <= thr:
                    stick = True
                    s = 0.0
                    just_started = False
                else:
                    s = -1.0 if ar > 0.0 else 1.0
                    just_started = True
                h = h_restart if (check and not stick) else max(h_restart, 0.5 * hlast)
                if hist_cap > 0 and nh < hist_cap:
                    hist[nh, 0] = tau
                    hist[nh, 1:5] = y
                    hist[nh, 5] = s
                    nh += 1
                continue
            just_started = False
            if abs(y1[3]) > vmax:
                vmax = abs(y1[3])
        # --- accept -------------------------------------------------------------
        tau = tnew
        for i in range(4):
            y[i] = y1[i]
        if stick:
            y[3] = 0.0
        hlast = h
        h = hnext
        if hist_cap > 0 and nh < hist_cap:
            hist[nh, 0] = tau
            hist[nh, 1:5] = y
            hist[nh, 5] = s
            nh += 1
    if not settled and not stick:
        if abs(y[2]) > umax:
            umax = abs(y[2])
            tpeak = tau
    ints = np.array([steps + cnt[0] + cnt[1] + cnt[2], events, 1 if settled else 0, 1 if slipped else 0, nh,
                     cnt[0], cnt[1], cnt[2], cnt[3]], dtype=np.int64)
    floats = np.array([umax, tpeak, y[2], tau, amax, vmax])
    return ints, floats, hist[:nh]
