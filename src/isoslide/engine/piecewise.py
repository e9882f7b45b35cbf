"""Exact piecewise propagation of record-driven Coulomb scenes (numba).

A sampled record (pulse code ``SAMPLED``) is linear in time between samples.
With a linear isolator (``Pi3 > 0``, any ``Pi4 >= 0``) or a fixed base
(``Pi3 = 0``) and speed-independent friction (``phi = Pi2/Pi5``), every stick
or slip phase of the equations of :mod:`isoslide.engine.kernel` is a linear ODE
system ``y' = A y + b_p p(tau) + b_s s`` with a forcing ``p`` that is linear
on each sample interval, so it can be propagated exactly (the piecewise-exact
method of Nigam & Jennings 1969) instead of integrated step by step.

How
---
Each sample interval ``dtau`` is cut into ``n`` equal substeps with
``rho h <= RHO_STEP`` (``rho = 2 Pi4 w + w`` bounds the system's
eigenvalues, ``w = 2 pi / Pi3``).  For that substep the transition matrix of
the stuck and of the sliding system and their responses to a constant and a
ramp ground acceleration and to the friction force (the columns of a 4 x 7
matrix) are computed once per scene from the Taylor series of the exact
solution (``N_TAYLOR`` terms, truncation below 1e-20 at ``rho h = 0.5``).  A
substep without a transition costs one 4 x 7 matrix product.

Transitions are found inside a substep, on the closed-form (Taylor)
solution, by safeguarded Newton/bisection:

* breakaway: the stuck demand ``a_req = -(2 z w x' + w^2 x)/(1+Pi8)``
  (fixed base: ``p``), linear in the state, reaches ``+-Pi2/Pi5``, at the
  substep end or past an interior peak of ``|a_req|`` (examined when the
  cubic Hermite estimate of the peak from the end values and rates comes
  within 5 % of the threshold);
* end of slip: the relative sliding speed ``u'`` reaches zero (then stick if
  ``|a_req| <= Pi2/Pi5``, else an immediate reversal, as in the kernel); the
  peak ``|u|`` is taken there.

After the record the ground is at rest and the free vibration is propagated
the same way with substeps ``RHO_STEP / rho``; the settlement stop (energy
bound after the pulse), the horizon and the results layout (``R_*``, ``F_*``,
``H_*`` of :mod:`isoslide.engine.kernel`) are those of :func:`isoslide.engine.kernel.run`.
Units: time in T_p, lengths in a_p T_p^2, speeds in a_p T_p, accelerations
in a_p.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .. import jit_cache
from . import kernel
from .kernel import (F_AMAX, F_TEND, F_TPEAK, F_UMAX, F_UPEAK, F_URES, F_VMAX, M_CW, M_FIXED, M_P8, M_THR, M_W2, N_F, N_H,
                     N_R, R_EVENTS, R_HIST, R_LOC_PEAK, R_LOC_SLIP, R_LOC_STICK, R_REJECTED, R_SETTLED, R_SLIPPED,
                     R_STEPS, _hermite_max, _record, checkpoint)

INT_RESULTS = kernel.INT_RESULTS
"""The integer results of :func:`run`: the layout of :func:`isoslide.engine.kernel.run`."""
FLOAT_RESULTS = kernel.FLOAT_RESULTS
"""The float results of :func:`run`: the layout of :func:`isoslide.engine.kernel.run`."""

N_TAYLOR = 22
"""Taylor terms of the exact solution over one substep."""
RHO_STEP = 0.5
"""Largest ``rho h`` of a substep (``rho`` bounds the eigenvalues of the phase's system)."""
FIXED_FREE_STEP = 1.0
"""Substep after the record for a fixed base (units of T_p; the slip there is a polynomial)."""
PEAK_MARGIN = 0.05
"""Interior demand peaks whose Hermite estimate is within this fraction of the threshold are located exactly."""
N_COLS = 7
"""Columns of a propagation matrix: ``x, x', u, u'`` at the start, ``p``, ``dp/dtau`` and ``s``."""


# --- the linear systems ---------------------------------------------------------


@njit(cache=True)
def taylor(stick, s, y0, y1, y2, y3, p0, j, m, C):
    """Taylor coefficients of the exact solution of one phase from ``(x, x', u, u')``.

    ``C[k, i]`` (shape ``(N_TAYLOR, 4)``) receives the ``k``-th coefficient of
    component ``i`` for the ground acceleration ``p0 + j h`` (units of a_p,
    ``j`` in a_p / T_p) and the sliding direction ``s`` (0 while stuck).
    """
    fixed = m[M_FIXED] != 0.0
    w2 = m[M_W2]
    cw = m[M_CW]
    p8 = m[M_P8]
    mt = 1.0 + p8
    thr = m[M_THR]
    C[0, 0] = y0
    C[0, 1] = y1
    C[0, 2] = y2
    C[0, 3] = y3
    for k in range(N_TAYLOR - 1):
        x = C[k, 0]
        v = C[k, 1]
        ud = C[k, 3]
        pk = p0 if k == 0 else (j if k == 1 else 0.0)
        sk = s * thr if k == 0 else 0.0
        inv = 1.0 / (k + 1)
        if fixed:
            C[k + 1, 0] = 0.0
            C[k + 1, 1] = 0.0
            if stick:
                C[k + 1, 2] = 0.0
                C[k + 1, 3] = 0.0
            else:
                C[k + 1, 2] = ud * inv
                C[k + 1, 3] = (-pk - sk) * inv
        elif stick:
            C[k + 1, 0] = v * inv
            C[k + 1, 1] = (-pk - (cw * v + w2 * x) / mt) * inv
            C[k + 1, 2] = 0.0
            C[k + 1, 3] = 0.0
        else:
            F = cw * v + w2 * x
            C[k + 1, 0] = v * inv
            C[k + 1, 1] = (-pk - F + p8 * sk) * inv
            C[k + 1, 2] = ud * inv
            C[k + 1, 3] = (F - mt * sk) * inv


@njit(cache=True, inline="always")
def _horner(C, i, h):
    """Component ``i`` of the Taylor polynomial ``C`` at ``h``."""
    acc = C[N_TAYLOR - 1, i]
    for k in range(N_TAYLOR - 2, -1, -1):
        acc = acc * h + C[k, i]
    return acc


@njit(cache=True)
def _eval(C, h, out):
    """State at ``h`` from the Taylor coefficients ``C`` into ``out``."""
    for i in range(4):
        out[i] = _horner(C, i, h)


@njit(cache=True)
def propagation_matrix(stick, m, h):
    """4 x 7 matrix ``E`` of one phase over a substep ``h`` (``rho h <= RHO_STEP``).

    ``y(h) = E[:, :4] y(0) + E[:, 4] p0 + E[:, 5] j + E[:, 6] s`` exactly
    (to round-off) for the ground acceleration ``p0 + j tau``.
    """
    E = np.zeros((4, N_COLS))
    C = np.empty((N_TAYLOR, 4))
    out = np.empty(4)
    for c in range(N_COLS):
        e = np.zeros(4)
        if c < 4:
            e[c] = 1.0
        taylor(stick, 1.0 if c == 6 else 0.0, e[0], e[1], e[2], e[3], 1.0 if c == 4 else 0.0,
               1.0 if c == 5 else 0.0, m, C)
        _eval(C, h, out)
        for i in range(4):
            E[i, c] = out[i]
    return E


@njit(cache=True, inline="always")
def _apply(E, y, p0, j, s, out):
    """``out = E [y, p0, j, s]``."""
    for i in range(4):
        out[i] = (E[i, 0] * y[0] + E[i, 1] * y[1] + E[i, 2] * y[2] + E[i, 3] * y[3]
                  + E[i, 4] * p0 + E[i, 5] * j + E[i, 6] * s)


@njit(cache=True, inline="always")
def _demand(x, v, p, m):
    """Stuck demand ``a_req`` (units of a_p): ``p`` for a fixed base."""
    if m[M_FIXED] != 0.0:
        return p
    return -(m[M_CW] * v + m[M_W2] * x) / (1.0 + m[M_P8])


@njit(cache=True, inline="always")
def _demand_rate(x, v, p, j, m):
    """Rate ``d a_req / d tau`` of the stuck demand (units of a_p / T_p)."""
    if m[M_FIXED] != 0.0:
        return j
    mt = 1.0 + m[M_P8]
    acc = -p - (m[M_CW] * v + m[M_W2] * x) / mt
    return -(m[M_CW] * acc + m[M_W2] * v) / mt


@njit(cache=True, inline="always")
def _slide_accel(y, p, s, m):
    """Relative sliding acceleration ``u''`` (units of a_p) while sliding in direction ``s``."""
    if m[M_FIXED] != 0.0:
        return -p - s * m[M_THR]
    return m[M_CW] * y[1] + m[M_W2] * y[0] - (1.0 + m[M_P8]) * s * m[M_THR]


@njit(cache=True, inline="always")
def advance(k, i, g, nint, nsub):
    """The grid position after one substep: substep ``i`` of sample interval ``k`` (``k == nint``: free step ``g``)."""
    if k < nint:
        i += 1
        if i == nsub:
            i = 0
            k += 1
    else:
        g += 1
    return k, i, g


# --- root finding on a polynomial ------------------------------------------------


@njit(cache=True, inline="always")
def _poly(c, h):
    """Value and derivative of the polynomial with coefficients ``c`` at ``h``."""
    n = c.shape[0]
    acc = c[n - 1]
    d = 0.0
    for k in range(n - 2, -1, -1):
        d = d * h + acc
        acc = acc * h + c[k]
    return acc, d


@njit(cache=True)
def poly_root(c, lo, glo, hi, ghi):
    """Root in ``[lo, hi]`` of the polynomial ``c`` (``glo``, ``ghi`` of opposite sign or zero at ``hi``).

    Safeguarded Newton with bisection; stops when the bracket or the Newton
    correction is below 1e-15 of ``hi``.  Returns ``(root, iterations)``.
    """
    if ghi == 0.0:
        return hi, 0
    tol = 1e-15 * max(abs(hi), 1e-300)
    t = lo - glo * (hi - lo) / (ghi - glo)
    it = 0
    for it in range(1, 100):
        if not (lo < t < hi):
            t = 0.5 * (lo + hi)
        g, d = _poly(c, t)
        if g == 0.0:
            return t, it
        if (g > 0.0) == (glo > 0.0):
            lo, glo = t, g
        else:
            hi = t
        tn = t - g / d if d != 0.0 else 0.5 * (lo + hi)
        if not (lo < tn < hi):
            tn = 0.5 * (lo + hi)
        if abs(tn - t) <= tol or hi - lo <= tol:
            return tn, it
        t = tn
    return t, it


# --- one scene -----------------------------------------------------------------------


@njit(cache=True)
def run(m, params, tau_start, tau_end, tau_stop, track_max, hist_cap, settle, max_steps):
    """Propagate one record-driven Coulomb scene from rest at ``tau_start`` exactly.

    Parameters
    ----------
    m : ndarray of float64, shape (kernel.N_M,)
        Model parameters as for :func:`isoslide.engine.kernel.run` (the friction law
        is Coulomb at the level ``m[M_THR] = Pi2/Pi5``; ``inf`` with ``track_max``).
    params : ndarray of float64
        Parameters of the ``SAMPLED`` pulse: ``tau0, dtau`` (units of T_p),
        then the samples of ``a_g / a_p``.
    tau_start, tau_end : float
        First and last sample time (units of T_p); the ground is at rest outside.
    tau_stop : float
        Horizon: the propagation stops here if the scene has not settled.
    track_max : bool
        Keep the block stuck and record the largest stuck demand instead
        (``F_AMAX``), as :func:`isoslide.engine.kernel.run` does.
    hist_cap : int
        Rows of history to keep (0: none).
    settle : bool
        Stop at settlement (else follow the scene to the horizon).
    max_steps : int
        Budget of substeps (``F_TEND < tau_stop`` then tells a truncated run).

    Returns
    -------
    ints, floats, hist
        The layout of :func:`isoslide.engine.kernel.run`: ``R_STEPS`` substeps
        propagated (matrix or Taylor); ``R_LOC_STICK``, ``R_LOC_SLIP``,
        ``R_LOC_PEAK`` root-finding iterations for breakaways, ends of slip and
        demand peaks; ``R_REJECTED`` 0.  History rows at the start, at every
        substep end and at every transition.
    """
    thr = m[M_THR]
    fixed = m[M_FIXED] != 0.0
    tau0 = params[0]
    dtau = params[1]
    nint = params.shape[0] - 3  # sample intervals
    rho = m[M_CW] + math.sqrt(m[M_W2])
    nsub = 1
    if rho > 0.0:
        nsub = max(1, int(math.ceil(rho * dtau / RHO_STEP)))
    hreg = dtau / nsub
    hfree = FIXED_FREE_STEP if rho == 0.0 else RHO_STEP / rho
    Est = propagation_matrix(True, m, hreg)
    Esl = propagation_matrix(False, m, hreg)
    Fst = propagation_matrix(True, m, hfree)
    Fsl = propagation_matrix(False, m, hfree)
    C = np.empty((N_TAYLOR, 4))
    c = np.empty(N_TAYLOR)
    cg = np.empty(N_TAYLOR)
    cd = np.empty(N_TAYLOR - 1)
    y = np.zeros(4)
    y1 = np.empty(4)
    ye = np.empty(4)
    hist = np.empty((hist_cap if hist_cap > 0 else 1, N_H))
    nh = _record(hist, 0, hist_cap, tau_start, y, 0.0)
    t = tau_start
    stick = True
    s = 0.0
    just_started = False
    slipped = False
    settled = False
    umax = 0.0
    tpeak = tau_start
    upeak = 0.0
    amax = 0.0
    vmax = 0.0
    steps = 0
    events = 0
    loc_stick = 0
    loc_slip = 0
    loc_peak = 0
    # grid position: interval k (k == nint: after the record), substep i; free step g
    k = 0
    i = 0
    g = 0
    on_grid = True
    while True:
        # --- the ground acceleration at t and the current grid segment ------------
        if k < nint:
            tk = tau0 + dtau * k
            jj = (params[3 + k] - params[2 + k]) / dtau
            t_next = tk + hreg * (i + 1) if i + 1 < nsub else tau0 + dtau * (k + 1)
            p_t = params[2 + k] + jj * (t - tk)
            Emat_st, Emat_sl, hfull = Est, Esl, hreg
        else:
            jj = 0.0
            p_t = 0.0
            t_next = tau_end + hfree * (g + 1)
            Emat_st, Emat_sl, hfull = Fst, Fsl, hfree
            if t_next >= tau_stop:
                t_next = tau_stop
                on_grid = False
        # --- mode checks at the current point (as the kernel's) ------------------
        stop, stick, s, just_started, slipped, events, amax, settled = checkpoint(
            stick, s, just_started, slipped, events, _demand(y[0], y[1], p_t, m) if stick else 0.0, y, m,
            t >= tau_end, t >= tau_stop or steps > max_steps, thr, fixed, settle, track_max, amax, settled)
        if stop:
            break
        r = t_next - t
        steps += 1
        # --- fast substep: one matrix product and the end-point tests -------------
        slow = True
        if on_grid:
            slow = False
            if stick:
                _apply(Emat_st, y, p_t, jj, 0.0, y1)
                p1 = p_t + jj * hfull
                d0 = _demand(y[0], y[1], p_t, m)
                d1 = _demand(y1[0], y1[1], p1, m)
                r0 = _demand_rate(y[0], y[1], p_t, jj, m)
                r1 = _demand_rate(y1[0], y1[1], p1, jj, m)
                if track_max:
                    if abs(d1) > amax:
                        amax = abs(d1)
                for sig in (1.0, -1.0):
                    if sig * d1 > thr:
                        slow = True
                    elif sig * r0 > 0.0 and sig * r1 < 0.0:
                        if track_max or _hermite_max(sig * d0 - thr, sig * r0, sig * d1 - thr, sig * r1,
                                                     hfull) > -PEAK_MARGIN * thr:
                            slow = True
            else:
                _apply(Emat_sl, y, p_t, jj, s, y1)
                if s * y1[3] <= 0.0:
                    slow = True
                elif not just_started and s * _slide_accel(y, p_t, s, m) < 0.0 \
                        and s * _slide_accel(y1, p_t + jj * hfull, s, m) > 0.0:
                    slow = True  # an interior minimum of the sliding speed may reach zero
        # --- slow substep: the Taylor solution, with transitions located ---------
        te = -1.0
        if slow:
            taylor(stick, s, y[0], y[1], y[2], y[3], p_t, jj, m, C)
            if stick:
                # demand polynomial
                for q in range(N_TAYLOR):
                    if fixed:
                        c[q] = p_t if q == 0 else (jj if q == 1 else 0.0)
                    else:
                        c[q] = -(m[M_CW] * C[q, 1] + m[M_W2] * C[q, 0]) / (1.0 + m[M_P8])
                for q in range(N_TAYLOR - 1):
                    cd[q] = (q + 1) * c[q + 1]
                for sig in (1.0, -1.0):
                    g0 = sig * c[0] - thr
                    gr = sig * _poly(c, r)[0] - thr
                    hit = -1.0
                    if not track_max and gr > 0.0:
                        hit = r
                    else:
                        cdr = _poly(cd, r)[0]
                        if sig * cd[0] > 0.0 and sig * cdr < 0.0:
                            hm, it = poly_root(cd, 0.0, cd[0], r, cdr)
                            loc_peak += it
                            am = sig * _poly(c, hm)[0]
                            if track_max:
                                if am > amax:
                                    amax = am
                            elif am - thr > 0.0:
                                hit = hm
                    if hit > 0.0:
                        for q in range(N_TAYLOR):
                            cg[q] = sig * c[q]
                        cg[0] -= thr
                        root, it = poly_root(cg, 0.0, g0, hit, _poly(cg, hit)[0])
                        loc_stick += it
                        if te < 0.0 or root < te:
                            te = root
                if te >= 0.0:
                    _eval(C, te, ye)
                    ye[3] = 0.0
                    t = t + te
                    for q in range(4):
                        y[q] = ye[q]
                    ar = _demand(y[0], y[1], p_t + jj * te, m)
                    stick = False
                    s = -1.0 if ar > 0.0 else 1.0
                    just_started = True
                    slipped = True
                    events += 1
                    on_grid = False
                    nh = _record(hist, nh, hist_cap, t, y, 0.0)
                    continue
            else:
                for q in range(N_TAYLOR):
                    c[q] = s * C[q, 3]
                gr = _poly(c, r)[0]
                if gr > 0.0 and not just_started:
                    # an interior minimum of s u' that reaches zero ends the slip there
                    for q in range(N_TAYLOR - 1):
                        cd[q] = (q + 1) * c[q + 1]
                    cdr = _poly(cd, r)[0]
                    if cd[0] < 0.0 and cdr > 0.0:
                        hm, it = poly_root(cd, 0.0, cd[0], r, cdr)
                        loc_slip += it
                        gm = _poly(c, hm)[0]
                        if gm <= 0.0:
                            r, gr = hm, gm
                if gr <= 0.0:
                    lo = 0.0
                    glo = c[0]
                    found = True
                    if just_started:
                        hp = r
                        gp = gr
                        for _q in range(200):
                            hp *= 0.5
                            gp = _poly(c, hp)[0]
                            loc_slip += 1
                            if gp > 0.0 or hp < 1e-300:
                                break
                        if gp > 0.0:
                            lo, glo = hp, gp
                        else:
                            found = False
                            te = 0.0
                    if found:
                        te, it = poly_root(c, lo, glo, r, gr)
                        loc_slip += it
                    _eval(C, te, ye)
                    t = t + te
                    for q in range(4):
                        y[q] = ye[q]
                    y[3] = 0.0
                    events += 1
                    if abs(y[2]) > umax:
                        umax = abs(y[2])
                        tpeak = t
                        upeak = y[2]
                    ar = _demand(y[0], y[1], p_t + jj * te, m)
                    if abs(ar) <= thr:
                        stick = True
                        s = 0.0
                        just_started = False
                    else:
                        s = -1.0 if ar > 0.0 else 1.0
                        just_started = True
                    on_grid = False
                    nh = _record(hist, nh, hist_cap, t, y, s)
                    continue
            _eval(C, r, y1)
        # --- accept the substep end -------------------------------------------------
        if stick:
            y1[3] = 0.0
        else:
            just_started = False
            if abs(y1[3]) > vmax:
                vmax = abs(y1[3])
        for q in range(4):
            y[q] = y1[q]
        t = t_next
        on_grid = True
        k, i, g = advance(k, i, g, nint, nsub)
        nh = _record(hist, nh, hist_cap, t, y, s)
    if not settled and not stick:
        if abs(y[2]) > umax:
            umax = abs(y[2])
            tpeak = t
            upeak = y[2]
    ints = np.zeros(N_R, dtype=np.int64)
    ints[R_STEPS] = steps
    ints[R_EVENTS] = events
    ints[R_SETTLED] = 1 if settled else 0
    ints[R_SLIPPED] = 1 if slipped else 0
    ints[R_HIST] = nh
    ints[R_LOC_STICK] = loc_stick
    ints[R_LOC_SLIP] = loc_slip
    ints[R_LOC_PEAK] = loc_peak
    ints[R_REJECTED] = 0
    floats = np.zeros(N_F)
    floats[F_UMAX] = umax
    floats[F_TPEAK] = tpeak
    floats[F_URES] = y[2]
    floats[F_TEND] = t
    floats[F_AMAX] = amax
    floats[F_VMAX] = vmax
    floats[F_UPEAK] = upeak
    return ints, floats, hist[:nh]


# numba reads the compiled code shipped with the package (isoslide.jit_cache) before compiling any of it
jit_cache.seed(run)
