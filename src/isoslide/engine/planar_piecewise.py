"""Exact propagation of the stick phases of a recorded pair in the plane (numba).

A pair of sampled records on one time grid is linear in time between samples in both horizontal
components.  On a linear isolator (``Pi3 > 0``, rigid superstructure) or a fixed base, with
speed-independent friction and no vertical motion, the building with the contents stuck obeys the
same linear system along x and along y, each driven by its component: the 1-D stick phase of
:mod:`isoslide.engine.piecewise`, propagated exactly sample by sample with its transition matrix
(``Pi8`` on the slab while stuck), one matrix product per axis and substep.  The contents stay
stuck while the floor's demand vector ``d = (d_x, d_y)`` (``d_a`` the 1-D stuck demand of axis
``a``; on a fixed base the ground acceleration) is within the static level, ``|d| <= Pi2/Pi5``.

A substep whose end, or whose interior (the cubic Hermite interpolants of ``d_x``, ``d_y`` from the
ends' values and rates, sampled, coming within :data:`isoslide.engine.piecewise.PEAK_MARGIN` of the
level), may pass the level is evaluated on its Taylor solution instead: the polynomial ``|d|^2 -
thr^2`` is sampled at :data:`SCAN` points and its first sign change located by safeguarded Newton
(:func:`isoslide.engine.piecewise.poly_root`), which is the breakaway.  From there the slide runs in the planar kernel (:func:`isoslide.engine.planar_kernel.run`
with ``stop_on_stick``: it returns when the contents stick again), and the stick propagation resumes
from the kernel's state on the Taylor solution to the next grid point.  After the records the free
vibration is propagated the same way; it settles once the energy bound of each axis
(:func:`isoslide.engine.kernel._demand_bound`) gives ``sqrt(b_x^2 + b_y^2) <= thr`` (at once on a
fixed base).

Results, history rows and units are the planar kernel's (:data:`INT_RESULTS`, :data:`FLOAT_RESULTS`).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .. import jit_cache
from . import planar_kernel
from .kernel import M_CW, M_FIXED, M_P8, M_THR, M_W2, _demand_bound, _hermite_coeffs
from .planar_kernel import M_BM
from .piecewise import (FIXED_FREE_STEP, N_TAYLOR, PEAK_MARGIN, RHO_STEP, _apply, _demand, _demand_rate, _eval,
                        _poly, advance, poly_root, propagation_matrix, taylor)

INT_RESULTS = planar_kernel.INT_RESULTS
"""The integer results of :func:`run`: the planar kernel's (``steps`` counts substeps and Runge-Kutta steps)."""
FLOAT_RESULTS = planar_kernel.FLOAT_RESULTS
"""The float results of :func:`run`: the planar kernel's."""

NY = planar_kernel.state_size(1)
"""Length of the planar kernel's state of a rigid superstructure (one floor)."""
NB = planar_kernel.axis_size(1)
"""States of one axis of that state (``x, x'`` first, then the block's ``u`` from ``2 NB``)."""
I_STEPS, I_EVENTS, I_SETTLED, I_SLIPPED, I_REJECTED = (INT_RESULTS.index(k) for k in
                                                        ("steps", "events", "settled", "slipped", "rejected"))
F_UMAX, F_TPEAK, F_ANGLE, F_TEND, F_VMAX, F_XMAX = (FLOAT_RESULTS.index(k) for k in
                                                    ("umax", "tpeak", "angle", "tend", "vmax", "xmax"))
"""Positions of the planar kernel's results that a slide hands back, from its declared layout."""
SCAN = 32
"""Points at which a substep's ``|d|^2 - thr^2`` is sampled for its first sign change."""
HERMITE_SAMPLES = 8
"""Interior points at which the demand's Hermite interpolants are sampled in a fast substep."""


@njit(cache=True, inline="always")
def _hermite_at(g0, d0, g1, d1, h, s):
    """The cubic Hermite interpolant of ``(g0, d0)``, ``(g1, d1)`` on ``[0, h]`` at ``s``."""
    c, e = _hermite_coeffs(g0, d0, g1, d1, h)
    return g0 + s * (d0 + s * (c + s * e))


@njit(cache=True)
def _first_crossing(cx, cy, r, thr, q):
    """First ``h`` in ``[0, r]`` where ``|d(h)|`` passes ``thr`` (``-1`` if none is found).

    ``q`` (length ``2 N_TAYLOR - 1``) receives the coefficients of ``|d|^2 - thr^2``, the demand
    polynomials ``cx``, ``cy`` squared; its first sign change among :data:`SCAN` points is located
    by :func:`isoslide.engine.piecewise.poly_root`.
    """
    for a in range(q.shape[0]):
        q[a] = 0.0
    for a in range(N_TAYLOR):
        for b in range(N_TAYLOR):
            q[a + b] += cx[a] * cx[b] + cy[a] * cy[b]
    q[0] -= thr * thr
    if q[0] > 0.0:
        return 0.0
    lo, glo = 0.0, q[0]
    for k in range(1, SCAN + 1):
        hi = r * k / SCAN
        ghi = _poly(q, hi)[0]
        if ghi > 0.0:
            return poly_root(q, lo, glo, hi, ghi)[0]
        lo, glo = hi, ghi
    return -1.0


@njit(cache=True)
def _demand_poly(C, p0, j, m, c):
    """Coefficients ``c`` of one axis's stuck demand on the Taylor solution ``C`` (fixed base: the ground)."""
    if m[M_FIXED] != 0.0:
        for q in range(N_TAYLOR):
            c[q] = p0 if q == 0 else (j if q == 1 else 0.0)
        return
    mt = 1.0 + m[M_P8]
    for q in range(N_TAYLOR):
        c[q] = -(m[M_CW] * C[q, 1] + m[M_W2] * C[q, 0]) / mt


@njit(cache=True)
def _full_state(ax, ay, u, yfull):
    """The planar kernel's state (one rigid floor) of the axes ``ax``, ``ay`` (``[x, x', ...]``) and ``u``."""
    for i in range(yfull.shape[0]):
        yfull[i] = 0.0
    yfull[0] = ax[0]
    yfull[1] = ax[1]
    yfull[NB] = ay[0]
    yfull[NB + 1] = ay[1]
    yfull[2 * NB] = u[0]
    yfull[2 * NB + 1] = u[1]


@njit(cache=True)
def run(m, gx, gy, tau0, dtau, tau_end, tau_stop, hist_cap, settle, max_steps, P, ex, breakpoints, h_max_pulse,
        h_max_free, rtol, atol, h_restart, Wm, Cm, Vm, Lm, Wh, Ch, Vh, Lh, slaved):
    """Propagate a recorded pair in the plane from rest at ``tau0``: stick phases exactly, slides in the planar kernel.

    Parameters
    ----------
    m : ndarray of float64
        The 1-D model array of :func:`isoslide.engine.kernel.run` (Coulomb level ``m[M_THR]``).
    gx, gy : ndarray of float64
        The ground acceleration along the building's axes at the samples ``tau0 + dtau k`` (units of a_p).
    tau0, dtau, tau_end : float
        First sample, sample interval and the records' end (units of T_p).
    tau_stop, hist_cap, settle, max_steps
        As :func:`isoslide.engine.planar_kernel.run`; ``max_steps`` counts substeps and Runge-Kutta steps.
    P, ex, breakpoints, h_max_pulse, h_max_free, rtol, atol, h_restart, Wm, Cm, Vm, Lm, Wh, Ch, Vh, Lh, slaved
        The planar kernel's arguments for the slides.

    Returns
    -------
    ints, floats, hist
        :data:`INT_RESULTS`, :data:`FLOAT_RESULTS` and the rows ``[tau, y..., bm, im]`` of the
        planar kernel (a row at every substep end, every transition and every step of a slide).
    """
    thr = m[M_THR]
    fixed = m[M_FIXED] != 0.0
    nint = gx.shape[0] - 1
    rho = m[M_CW] + math.sqrt(m[M_W2])
    nsub = max(1, int(math.ceil(rho * dtau / RHO_STEP))) if rho > 0.0 else 1
    hreg = dtau / nsub
    hfree = FIXED_FREE_STEP if rho == 0.0 else RHO_STEP / rho
    Est = propagation_matrix(True, m, hreg)
    Fst = propagation_matrix(True, m, hfree)
    ny = NY
    Cx = np.empty((N_TAYLOR, 4))
    Cy = np.empty((N_TAYLOR, 4))
    cx = np.empty(N_TAYLOR)
    cy = np.empty(N_TAYLOR)
    q2 = np.empty(2 * N_TAYLOR - 1)
    ax = np.zeros(4)
    ay = np.zeros(4)
    ax1 = np.empty(4)
    ay1 = np.empty(4)
    u = np.zeros(2)
    yfull = np.zeros(ny)
    md = np.array([0.0, 1.0, 0.0, 0.0, 1.0, 0.0])
    final = np.empty(ny + 6)
    hist = np.empty((hist_cap if hist_cap > 0 else 1, ny + 3))
    nh = planar_kernel._record(hist, 0, hist_cap, tau0, yfull, md)
    t = tau0
    steps = 0
    events = 0
    rejected = 0
    settled = False
    slipped = False
    umax = 0.0
    tpeak = tau0
    angle = math.nan
    vmax = 0.0
    xmax = 0.0
    k = 0
    i = 0
    g = 0
    on_grid = True
    slide = False
    while True:
        # --- the ground on the current grid segment -----------------------------------
        if k < nint:
            tk = tau0 + dtau * k
            jx = (gx[k + 1] - gx[k]) / dtau
            jy = (gy[k + 1] - gy[k]) / dtau
            px = gx[k] + jx * (t - tk)
            py = gy[k] + jy * (t - tk)
            t_next = tk + hreg * (i + 1) if i + 1 < nsub else tau0 + dtau * (k + 1)
            E, hfull = Est, hreg
        else:
            jx = jy = px = py = 0.0
            t_next = tau_end + hfree * (g + 1)
            E, hfull = Fst, hfree
            if t_next >= tau_stop:
                t_next = tau_stop
                on_grid = False
        dx0 = _demand(ax[0], ax[1], px, m)
        dy0 = _demand(ay[0], ay[1], py, m)
        if dx0 * dx0 + dy0 * dy0 > thr * thr:
            slide = True
        elif t >= tau_end:
            bx = 0.0 if fixed else _demand_bound(ax, m)
            by = 0.0 if fixed else _demand_bound(ay, m)
            if bx * bx + by * by <= thr * thr:
                settled = True
                if settle:
                    break
        if not slide:
            if t >= tau_stop or steps > max_steps:
                break
            r = t_next - t
            steps += 1
            slow = not on_grid
            if on_grid:
                _apply(E, ax, px, jx, 0.0, ax1)
                _apply(E, ay, py, jy, 0.0, ay1)
                px1 = px + jx * hfull
                py1 = py + jy * hfull
                dx1 = _demand(ax1[0], ax1[1], px1, m)
                dy1 = _demand(ay1[0], ay1[1], py1, m)
                if dx1 * dx1 + dy1 * dy1 > thr * thr:
                    slow = True
                else:
                    rx0 = _demand_rate(ax[0], ax[1], px, jx, m)
                    ry0 = _demand_rate(ay[0], ay[1], py, jy, m)
                    rx1 = _demand_rate(ax1[0], ax1[1], px1, jx, m)
                    ry1 = _demand_rate(ay1[0], ay1[1], py1, jy, m)
                    near = ((1.0 - PEAK_MARGIN) * thr) ** 2
                    for q in range(1, HERMITE_SAMPLES + 1):
                        s = hfull * q / (HERMITE_SAMPLES + 1)
                        hx = _hermite_at(dx0, rx0, dx1, rx1, hfull, s)
                        hy = _hermite_at(dy0, ry0, dy1, ry1, hfull, s)
                        if hx * hx + hy * hy > near:
                            slow = True
                            break
            if slow:
                # the Taylor solution of both axes; the breakaway at the first crossing of the level
                taylor(True, 0.0, ax[0], ax[1], 0.0, 0.0, px, jx, m, Cx)
                taylor(True, 0.0, ay[0], ay[1], 0.0, 0.0, py, jy, m, Cy)
                _demand_poly(Cx, px, jx, m, cx)
                _demand_poly(Cy, py, jy, m, cy)
                te = _first_crossing(cx, cy, r, thr, q2)
                if te >= 0.0:
                    _eval(Cx, te, ax)
                    _eval(Cy, te, ay)
                    t = t + te
                    slide = True
                else:
                    _eval(Cx, r, ax1)
                    _eval(Cy, r, ay1)
            if not slide:
                for q in range(2):
                    ax[q] = ax1[q]
                    ay[q] = ay1[q]
                t = t_next
                on_grid = True
                k, i, g = advance(k, i, g, nint, nsub)
                xmax = max(xmax, math.sqrt(ax[0] ** 2 + ay[0] ** 2))
                _full_state(ax, ay, u, yfull)
                nh = planar_kernel._record(hist, nh, hist_cap, t, yfull, md)
                continue
        # --- a slide: the planar kernel until the contents stick again ----------------------
        slide = False
        _full_state(ax, ay, u, yfull)
        kb = max(k - 2, 0)
        res = planar_kernel.run(P, ex, breakpoints[kb:], t, tau_end, tau_stop, h_max_pulse, h_max_free, rtol, atol,
                                max(hist_cap - nh, 0), h_restart, settle, max(max_steps - steps, 0), Wm, Cm, Vm, Lm,
                                Wh, Ch, Vh, Lh, yfull, md, slaved, True, final)
        ints, floats, rows = res
        steps += ints[I_STEPS]
        events += ints[I_EVENTS]
        rejected += ints[I_REJECTED]
        if ints[I_SLIPPED] != 0:
            slipped = True
        for r_ in range(rows.shape[0]):
            if nh < hist_cap:
                for c_ in range(ny + 3):
                    hist[nh, c_] = rows[r_, c_]
                nh += 1
        if floats[F_UMAX] > umax:
            umax, tpeak, angle = floats[F_UMAX], floats[F_TPEAK], floats[F_ANGLE]
        vmax = max(vmax, floats[F_VMAX])
        xmax = max(xmax, floats[F_XMAX])
        t = floats[F_TEND]
        ax[0], ax[1] = final[0], final[1]
        ay[0], ay[1] = final[NB], final[NB + 1]
        u[0], u[1] = final[2 * NB], final[2 * NB + 1]
        if ints[I_SETTLED] != 0:
            settled = True
            break
        if final[ny + M_BM] != 0.0 or t >= tau_stop or steps > max_steps:
            break
        # back on the grid: the substep holding t, from t to its end on the Taylor solution
        if t < tau_end:
            k = min(int(math.floor((t - tau0) / dtau)), nint - 1)
            i = min(int(math.floor((t - (tau0 + dtau * k)) / hreg)), nsub - 1)
            if tau0 + dtau * k + hreg * (i + 1) <= t:
                i += 1
                if i == nsub:
                    i = 0
                    k += 1
        else:
            k = nint
            g = int(math.floor((t - tau_end) / hfree))
        on_grid = False
    ures = math.sqrt(u[0] ** 2 + u[1] ** 2)
    ints = np.array([steps, events, 1 if settled else 0, 1 if slipped else 0, nh, rejected, 0, 0], dtype=np.int64)
    floats = np.array([umax, tpeak, angle, ures, t, vmax, u[0], u[1], xmax])
    return ints, floats, hist[:nh]


# numba reads the compiled code shipped with the package (isoslide.jit_cache) before compiling any of it
jit_cache.seed(run)
