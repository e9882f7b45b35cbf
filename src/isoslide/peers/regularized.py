"""The paper's own method: friction regularized by a stiff bilinear spring.

Nikfar & Konstantinidis replace the signum of the friction law by "a bilinear
model with very large initial stiffness" and integrate the resulting smooth-ish
state-space system with a general MATLAB ODE solver.  This module does the
same with scipy: no events, no stick/slip logic, one ODE system integrated by a
stiff solver (``Radau`` by default, ``BDF`` selectable; see
:func:`solve_regularized` for why not ``LSODA``).  It is an
*approximation* of the exact stick-slip model solved by
:mod:`isoslide.peers.reference`; it converges to it as the stiffness grows, and is
kept to measure that error and its cost.

Model (dimensionless, as in :mod:`isoslide.peers.reference`)
------------------------------------------------------------
The friction force on the block is ``-rho m_EC a_p`` with ``rho`` the force of
an elastic-perfectly-plastic spring between block and floor:

* ``r = K (u - u_p)`` is the elastic spring force (units ``m_EC a_p``), ``u_p``
  the plastic (sliding) part of the displacement;
* the dimensionless stiffness is ``K = k_r T_p**2 / m_EC`` (``stiffness``),
  i.e. ``K = (2 pi T_p / T_r)**2`` with ``T_r = 2 pi sqrt(m_EC / k_r)`` the
  period of the block on the regularizing spring: ``K = 1e6`` gives
  ``T_r = 0.0063 T_p`` and an elastic "stick" deflection ``|u - u_p| <=
  phi / K``;
* the yield level is the Stribeck friction level ``Y = phi(|u'|)`` evaluated
  at the block's sliding velocity ``u'`` (paper Eq. 1 with ``u_s' = u'``), so
  the static level ``Pi2/Pi5`` applies at ``u' ~ 0``;
* elastic (``|r| < Y``) or unloading (``r u' <= 0``): ``r' = K u'``;
  plastic flow (``|r| >= Y`` and ``r u' > 0``): ``r`` follows the yield
  surface, ``r' = d(sign(r) Y)/dtau = phi'(|u'|) u''`` (consistency condition),
  and ``rho = clip(r, -Y, Y)`` removes any drift above it.

Equations of motion (``w = 2 pi / Pi3``, ``z = Pi4``)::

    x'' = -p - 2 z w x' - w**2 x + Pi8 rho         (fixed base: x = 0)
    u'' = -rho - p - x''
    r'  = K u'  or  phi'(|u'|) u''  (see above)

State ``(x, x', u, u', r)``.  The regularizing spring is undamped, as in a
plain bilinear model.  After each stop the spring force must jump from the
yield level to the demand ``-a_req``; it rings about it at period
``2 pi / sqrt(K)`` with force amplitude up to ``|phi(0) - |a_req||`` (``u``
amplitude ``<= 2 phi / K``).  This ringing belongs to the model: it can re-yield
the spring (spurious micro-slips, so the step-point slip count ``n_events``
grows with ``K``), and the integrator has to follow it, which is most of the
cost.

Accuracy and cost (measured, Radau, ``rtol = 1e-6``, 2-core machine)
--------------------------------------------------------------------
The error in ``Pi1`` decreases like ``K**-1/2`` wherever the block reverses
directly or breaks away under a step in ``p``: crossing the elastic range
``2 phi/K`` takes a time ``~ sqrt(phi / (K a))`` during which the friction is
wrong by ``O(phi)``, a velocity error ``O(K**-1/2)``.  A smooth single slip
converges like ``1/K``.  Relative errors against the reference solver::

    scene                           K=1e4    1e5      1e6      1e7
    fixed base Coulomb, Pi2=0.15    1.9e-2   6.7e-3   2.2e-3   7.0e-4
    resonance Coulomb, Pi2=0.1      9.5e-3   3.5e-3   1.1e-3   3.7e-4
    resonance Stribeck, Pi5=0.7     2.5e-2   1.1e-2   4.3e-3   1.4e-3
    two-way coupling, Pi8=0.1       1.0e-2   3.6e-3   1.2e-3   3.8e-4
    fixed base, one smooth slip     2.0e-2   2.0e-3   2.0e-4   2.0e-5
    Newmark rectangle, Pi2=0.3      4.5e-3   1.4e-3   4.5e-4   1.4e-4

(always an over-estimate).  Cost at ``K = 1e6`` (shared 2-core machine):
3,000-15,000 Radau steps, 38,000-116,000 right-hand-side calls, 2-4 s per
Ricker scene, against 3,300-10,300 calls and 0.02-0.16 s for the event-driven
reference at ``rtol = 1e-12`` (i.e. ~20-100x slower for an answer ~1e-3 off);
at ``K = 1e7`` 4-14 s.  The cost is mostly spent following the spring's
ringing while the pulse still acts (the rectangular pulse, whose stop comes
after the pulse, needs only ~50 steps).  Reproduce with a loop over
:func:`solve_regularized` and :func:`isoslide.peers.solve_reference`
(see ``tests/test_regularized.py``).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import minimize_scalar

from ..store.history import History, phase_of
from ..pulses import accel_at
from ..scene import Scene
from .reference import _default_horizon, _sech
from .result import PeerResult, counted

__all__ = ["solve_regularized"]


def solve_regularized(scene: Scene, stiffness: float = 1e6, rtol: float = 1e-6,
                      history: bool = False, method: str = "Radau",
                      atol: float | None = None, tau_max: float | None = None,
                      use_jac: bool = True, max_work: int | None = None) -> PeerResult:
    """Solve one scene with the paper's stiff-spring (bilinear) regularization.

    Parameters
    ----------
    scene : Scene
        Point of Pi-space and pulse; starts at rest at ``pulse.tau_start``.
    stiffness : float
        Dimensionless regularizing stiffness ``K = k_r T_p**2 / m_EC`` (> 0).
    rtol : float
        Relative tolerance of the stiff integrator.  The regularization error
        (~1e-3 at ``K = 1e6``) dominates: ``rtol`` 1e-6 and 1e-8 give the same
        ``Pi1`` to ~1e-8 relative, the former at about half the cost.
    history : bool
        Also return the step-point :class:`~isoslide.store.history.History`
        (``phase``: plastic flow, in the direction of ``u'``).
    method : {"Radau", "BDF"}
        scipy ``solve_ivp`` method (both given the analytic Jacobian).  Radau
        IIA (implicit Runge-Kutta, order 5, L-stable) is the default and the
        robust choice; BDF is cheaper per step but can fail ("required step
        size is less than spacing between numbers") at Stribeck slip onsets.
        ``LSODA`` is refused: it stalls (steps of ~1e-10) at slip onsets,
        where the right-hand side switches branch with the sign of ``u'``.
    atol : float or None
        Absolute tolerance; default ``1e-3 * rtol`` on every component.
    tau_max : float or None
        Horizon (units ``T_p``); default as :func:`isoslide.peers.solve_reference`.
    use_jac : bool
        Pass the analytic (piecewise) Jacobian to the integrator (default);
        False uses scipy's finite differences (about 2x the cost).
    max_work : int or None
        Work cap, as for :func:`isoslide.peers.solve_reference`.

    Returns
    -------
    PeerResult
        ``method = "regularized"``, ``stiffness = K``, ``integrator = method``; ``n_events``
        counts elastic -> plastic switches between accepted steps (an estimate of the
        number of slip phases; no events are located); cost in ``nfev``, ``njev``, ``n_steps``.
    """
    if not scene.paper_model:
        raise ValueError(f"method = 'regularized' solves the paper's model only (pi9 = 0 and pi12 = 0); "
                         f"got pi9 = {scene.pi9!r}, pi12 = {scene.pi12!r}")
    if method not in ("Radau", "BDF"):
        raise ValueError(f"method = {method!r} is invalid; allowed: 'Radau' or 'BDF' "
                         "(LSODA stalls at slip onsets)")
    K = float(stiffness)
    if not (math.isfinite(K) and K > 0):
        raise ValueError(f"stiffness = {stiffness!r} is invalid; allowed range: 0 < stiffness < inf")
    pulse = scene.pulse
    code = int(pulse.code)
    params = pulse.param_array
    fixed = scene.fixed_base
    om = 0.0 if fixed else 2.0 * math.pi / scene.pi3
    c = 2.0 * scene.pi4 * om
    k = om * om
    m1 = 1.0 + scene.pi8
    pi8 = scene.pi8
    phis = scene.pi2 / scene.pi5
    phik = scene.pi2
    b6 = scene.pi6
    g7 = scene.pi7
    sqK = math.sqrt(K)
    tau_end = float(pulse.tau_end)
    horizon = _default_horizon(scene) if tau_max is None else float(tau_max)
    if atol is None:
        atol = 1e-3 * rtol

    def phi(v):
        sh = _sech(b6 * v)
        return phis * sh + phik * (1.0 - sh) + g7 * v

    def dphi(v):
        a = b6 * v
        sh = _sech(a)
        return -(phis - phik) * b6 * sh * math.tanh(a) + g7

    def phi_low(v):
        sh = _sech(b6 * v)
        return phis * sh + phik * (1.0 - sh)

    def make_rhs(t0, t1):
        t_clip = math.nextafter(t1, -math.inf)

        def rhs(t, y):
            p = accel_at(code, params, min(max(t, t0), t_clip))
            ud = y[3]
            r = y[4]
            v = abs(ud)
            Y = phi(v)
            rho = min(max(r, -Y), Y)
            if fixed:
                xdd = 0.0
            else:
                xdd = -p - c * y[1] - k * y[0] + pi8 * rho
            udd = -rho - p - xdd
            if abs(r) >= Y and r * ud > 0.0:
                rd = dphi(v) * udd
            else:
                rd = K * ud
            return np.array([y[1], xdd, ud, udd, rd])

        def jac(t, y):
            ud = y[3]
            r = y[4]
            v = abs(ud)
            Y = phi(v)
            J = np.zeros((5, 5))
            J[0, 1] = 1.0
            J[2, 3] = 1.0
            if abs(r) > Y:  # rho = sign(r) Y(|u'|)
                dr_dr, dr_du = 0.0, math.copysign(1.0, r) * dphi(v) * math.copysign(1.0, ud)
            else:
                dr_dr, dr_du = 1.0, 0.0
            if not fixed:
                J[1, 0], J[1, 1] = -k, -c
                J[1, 3], J[1, 4] = pi8 * dr_du, pi8 * dr_dr
                J[3, 0], J[3, 1] = k, c
                J[3, 3], J[3, 4] = -m1 * dr_du, -m1 * dr_dr
            else:
                J[3, 3], J[3, 4] = -dr_du, -dr_dr
            if abs(r) >= Y and r * ud > 0.0:
                J[4] = dphi(v) * J[3]
            else:
                J[4, 3] = K
            return J
        rhs.jac = jac
        return rhs

    slack = 1e-6 + 10.0 * rtol

    def settle(t, y):
        if t < tau_end:
            return -1.0
        if fixed:
            aE, areq = 0.0, 0.0
        else:
            E = 0.5 * m1 * y[1] ** 2 + 0.5 * k * y[0] ** 2
            aE = math.sqrt(2.0 * E * (c * c / m1 + k)) / m1
            areq = -(c * y[1] + k * y[0]) / m1
        Y0 = phi(abs(y[3]))
        A = math.hypot(min(max(y[4], -Y0), Y0) + areq, sqK * y[3])
        return phi_low(A / sqK) * (1.0 + slack) - aE - A
    settle.terminal = True
    settle.direction = 1.0

    bps = [float(b) for b in pulse.breakpoint_array if b < horizon]
    edges = [float(pulse.tau_start)] + [b for b in bps if b > pulse.tau_start] + [horizon]
    y = np.zeros(5)
    sols = []
    nfev = njev = nsteps = 0
    used = [0]
    settled = False
    ts, ys = [], []
    for t0, t1 in zip(edges[:-1], edges[1:], strict=True):
        if t1 <= t0:
            continue
        ev = [settle] if t1 > tau_end else None
        if ev and t0 >= tau_end and settle(t0, y) >= 0.0:
            settled = True
            break
        fun = make_rhs(t0, t1)
        jkw = {"jac": fun.jac} if use_jac else {}
        sol = solve_ivp(counted(fun, max_work, "regularized", used), (t0, t1), y, method=method,
                        rtol=rtol, atol=atol,
                        dense_output=True, events=ev, **jkw)
        if sol.status < 0:
            raise RuntimeError(f"solve_ivp failed: {sol.message}")
        nfev += sol.nfev
        njev += sol.njev
        nsteps += sol.t.size - 1
        sols.append(sol)
        ts.append(sol.t)
        ys.append(sol.y)
        y = sol.y[:, -1].copy()
        if sol.status == 1:
            settled = True
            break
    tt = np.concatenate(ts)
    yy = np.concatenate(ys, axis=1)
    tau_stop = float(tt[-1])

    # ---- peak of |u|: refine the largest step-point maxima on the dense output
    au = np.abs(yy[2])
    peak, tau_peak = float(au[-1]), tau_stop
    i_best = int(np.argmax(au))
    if au[i_best] > 0.0:
        cand = np.argsort(au)[::-1][:8]
        for i in cand:
            lo, hi = tt[max(i - 1, 0)], tt[min(i + 1, tt.size - 1)]
            for sol in sols:
                if sol.t[0] <= tt[i] <= sol.t[-1]:
                    a, b = max(lo, sol.t[0]), min(hi, sol.t[-1])
                    if b > a:
                        f = sol.sol
                        res = minimize_scalar(lambda t, f=f: -abs(f(t)[2]), bounds=(a, b),
                                              method="bounded", options={"xatol": 1e-12})
                        if -res.fun > peak:
                            peak, tau_peak = float(-res.fun), float(res.x)
                    if au[i] > peak:
                        peak, tau_peak = float(au[i]), float(tt[i])
                    break
    # ---- slip-phase count: elastic -> plastic switches at step points
    Yv = np.array([phi(abs(v)) for v in yy[3]])
    plastic = (np.abs(yy[4]) >= Yv * (1.0 - 1e-9)) & (yy[4] * yy[3] > 0.0)
    n_events = int(np.count_nonzero(plastic[1:] & ~plastic[:-1]))
    h = None
    if history:
        h = History(tau=tt, x=yy[0], xd=yy[1], u=yy[2], ud=yy[3], phase=phase_of(plastic, yy[3]))
    return PeerResult(method="regularized", pi1=peak, pi1_residual=float(yy[2, -1]), tau_peak=tau_peak,
                      settled=settled, n_events=n_events, tau_end=tau_stop, nfev=int(nfev), njev=int(njev),
                      n_steps=int(nsteps), stiffness=K, integrator=method, history=h)
