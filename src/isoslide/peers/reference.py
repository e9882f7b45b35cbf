"""Independent event-driven reference solver (plain Python + scipy ``solve_ivp``).

This is the "plain scipy" peer of the compiled solver: the same physics,
written independently, integrated phase by phase with :func:`scipy.integrate.solve_ivp`
(``DOP853``, 8th order, dense output of order 7) and with every stick/slip
transition located by ``solve_ivp``'s event machinery (Brent's method on the
dense output, to about 4 ulp).  It is slow (pure Python right-hand side) but
simple enough to be checked line by line, and is used to cross-check the fast
solver and as the benchmark baseline.

Model (dimensionless; ``tau = t / T_p``, lengths in ``a_p T_p**2``, primes are
``d/dtau``, accelerations in units of ``a_p``)
---------------------------------------------------------------------------
``x``  base displacement relative to the ground, ``u`` block displacement
relative to the floor (the sliding displacement), ``p(tau)`` the ground
acceleration pulse, ``w = 2 pi / Pi3``, ``z = Pi4`` and ``m1 = 1 + Pi8``.
Friction level (per unit block weight, in units of ``a_p``)::

    phi(v) = (Pi2/Pi5) sech(Pi6 v) + Pi2 (1 - sech(Pi6 v)) + Pi7 |v|

so ``phi(0) = Pi2/Pi5 = mu_s g / a_p`` is the static level.

* STICK (``u' = 0``): the block moves with the floor,
  ``x'' = -p - (2 z w x' + w**2 x) / m1``.  The floor acceleration (absolute,
  i.e. what the friction must supply to the block) is
  ``a_req = x'' + p = -(2 z w x' + w**2 x) / m1``; for a fixed base
  (``Pi3 = 0``) ``x = 0`` and ``a_req = p``.  Stick holds while
  ``|a_req| <= Pi2/Pi5``; on breakaway the block slips in direction
  ``s = -sign(a_req)``.
* SLIP with ``s = sign(u')``::

      x'' = -p - 2 z w x' - w**2 x + Pi8 s phi(|u'|)
      u'' = -s phi(|u'|) - p - x''            (fixed base: u'' = -s phi - p)

* When ``u'`` returns to zero the block sticks if ``|a_req| <= Pi2/Pi5``
  (``a_req`` from the STICK formula), otherwise it reverses at once
  (``s -> -sign(a_req)``, which equals ``-s``).

``Pi1 = max |u|`` over the whole response.  ``|u|`` can only peak at the end of
a slip phase (``u' = 0``) or at the final time, so the peak is taken exactly at
those event points.

Stopping rule ("no further sliding is possible")
------------------------------------------------
After the pulse (``tau >= tau_end``, ``p = 0``) a stuck system is the free
linear oscillator ``m1 x'' + 2 z w x' + w**2 x = 0`` and
``a_req = x''`` obeys the same equation.  Its energy
``E = m1 x'**2 / 2 + w**2 x**2 / 2`` is non-increasing, and with
``A = sqrt(m1) x'``, ``B = w x`` (so ``A**2 + B**2 = 2 E``)::

    |a_req| = |(2 z w / sqrt(m1)) A + w B| / m1
            <= sqrt(2 E (4 z**2 w**2 / m1 + w**2)) / m1 =: a_E

(Cauchy-Schwarz, attained for some state of that energy).  If ``a_E <=
Pi2/Pi5`` the block can never slip again.  This bound is conservative when
``z > 0``, so the solver uses the *exact* supremum of ``|a_req(tau)|`` over
the future free response instead (closed form: for an under-damped oscillator
successive extrema of ``a_req`` shrink by ``exp(-sigma pi / w_d)``, so the
supremum is reached within the first half damped period; an over-damped one
has at most one extremum); :func:`energy_bound` gives the bound.  The
supremum test is sharp: the run stops at the first moment no further slip is
possible, which only changes where the run stops, never ``Pi1``.  A fixed base
is settled as soon as it sticks after the pulse.  A run that has not settled
by the horizon ``tau_max`` (default: ``tau_end + max(50 max(1, Pi3), 50 /
rate)`` with ``rate`` the slowest decay rate of the isolated oscillator, so
the oscillation would have decayed by ``e**-50``; for ``Pi4 = 0`` simply
``tau_end + 50 max(1, Pi3)``) is reported with ``settled = False``.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp

from ..store.history import History
from ..pulses import accel_at
from ..scene import Scene
from .reference_building import solve_reference_building
from .result import PeerResult, counted

__all__ = ["solve_reference", "friction_level", "stuck_supremum", "energy_bound"]

STICK = 0
SLIP = 1


def _sech(a: float) -> float:
    """``1 / cosh(a)`` without overflow."""
    a = abs(a)
    if a > 700.0:
        return 0.0
    e = math.exp(-a)
    return 2.0 * e / (1.0 + e * e)


def friction_level(scene: Scene, v: float) -> float:
    """Friction per unit block weight ``phi(|v|)``, in units of ``a_p``.

    Parameters
    ----------
    scene : Scene
        Supplies ``Pi2, Pi5, Pi6, Pi7``.
    v : float
        Sliding velocity in units of ``a_p T_p``.
    """
    v = abs(v)
    sh = _sech(scene.pi6 * v)
    return (scene.pi2 / scene.pi5) * sh + scene.pi2 * (1.0 - sh) + scene.pi7 * v


def stuck_supremum(x: float, xdot: float, omega: float, zeta: float, m1: float):
    """Exact ``sup_{t >= 0} |a_req(t)|`` of the free, stuck isolated system.

    Solves ``m1 x'' + 2 zeta omega x' + omega**2 x = 0`` from ``(x, xdot)``;
    ``a_req = x''`` obeys the same equation.

    Parameters
    ----------
    x, xdot : float
        Base displacement (units ``a_p T_p**2``) and velocity (``a_p T_p``).
    omega : float
        ``2 pi / Pi3`` (rad per ``T_p``).
    zeta : float
        Isolation damping ratio ``Pi4``.
    m1 : float
        ``1 + Pi8``.

    Returns
    -------
    sup : float
        Supremum of ``|a_req|`` (units of ``a_p``).
    t_sup : float
        Time from now (units of ``T_p``) at which it is reached (0 if now).
    """
    c = 2.0 * zeta * omega
    k = omega * omega
    a0 = -(c * xdot + k * x) / m1
    a1 = -(c * a0 + k * xdot) / m1          # a_req'
    a2 = -(c * a1 + k * a0) / m1            # a_req''
    sigma = 0.5 * c / m1
    w0sq = k / m1
    best, t_best = abs(a0), 0.0
    disc = sigma * sigma - w0sq
    if disc < 0.0:  # under-damped: extrema of a every pi/wd, shrinking
        wd = math.sqrt(-disc)
        b1 = (a1 + sigma * a0) / wd
        b2 = (a2 + sigma * a1) / wd
        # a'(t) = exp(-sigma t) (a1 cos + b2 sin)(wd t); first zero in (0, pi]
        delta = math.atan2(b2, a1)
        th = (delta + 0.5 * math.pi) % math.pi
        if th <= 0.0:
            th = math.pi
        t = th / wd
        at = math.exp(-sigma * t) * (a0 * math.cos(th) + b1 * math.sin(th))
        if abs(at) > best:
            best, t_best = abs(at), t
        return best, t_best
    d = math.sqrt(disc)
    if d <= 1e-7 * sigma:  # critically damped: a = (a0 + (a1 + sigma a0) t) e^{-sigma t}
        q = a1 + sigma * a0
        if q != 0.0:
            t = a1 / (sigma * q)
            if t > 0.0:
                at = (a0 + q * t) * math.exp(-sigma * t)
                if abs(at) > best:
                    best, t_best = abs(at), t
        return best, t_best
    lam1 = -w0sq / (sigma + d)   # slow root, computed without cancellation
    lam2 = -sigma - d
    c1 = (a1 - lam2 * a0) / (lam1 - lam2)
    c2 = a0 - c1
    if c1 != 0.0:
        ratio = -lam2 * c2 / (lam1 * c1)
        if ratio > 1.0:
            t = math.log(ratio) / (lam1 - lam2)
            at = c1 * math.exp(lam1 * t) + c2 * math.exp(lam2 * t)
            if abs(at) > best:
                best, t_best = abs(at), t
    return best, t_best


def energy_bound(x: float, xdot: float, omega: float, zeta: float, m1: float) -> float:
    """Conservative bound ``a_E`` on the future floor demand of the free, stuck isolated system.

    ``a_E = sqrt(2 E (4 zeta**2 omega**2 / m1 + omega**2)) / m1`` with the energy
    ``E = m1 x'**2 / 2 + omega**2 x**2 / 2`` (see the module docstring).

    Parameters
    ----------
    x, xdot, omega, zeta, m1 : float
        The base's state and constants, as for :func:`stuck_supremum`.

    Returns
    -------
    float
        The bound, units of ``a_p``.
    """
    c = 2.0 * zeta * omega
    k = omega * omega
    E = 0.5 * m1 * xdot ** 2 + 0.5 * k * x ** 2
    return math.sqrt(2.0 * E * (c * c / m1 + k)) / m1


def _default_horizon(scene: Scene) -> float:
    tau_end = scene.pulse.tau_end
    base = 50.0 * max(1.0, scene.pi3)
    if scene.fixed_base or scene.pi4 == 0.0:
        return tau_end + base
    om = 2.0 * math.pi / scene.pi3
    z = scene.pi4
    rate = om * z if z <= 1.0 else om / (z + math.sqrt(z * z - 1.0))
    return tau_end + max(base, 50.0 / rate)


def solve_reference(scene: Scene, rtol: float = 1e-12, history: bool = False,
                    atol: float = 1e-15, tau_max: float | None = None,
                    max_events: int = 100_000, max_work: int | None = None) -> PeerResult:
    """Solve one scene with the event-driven DOP853 reference integrator.

    A general building (``not scene.paper_model``: a hysteretic isolator, a flexible
    superstructure or vertical ground motion) goes to
    :func:`isoslide.peers.reference_building.solve_reference_building` with the same arguments and
    result type.

    Parameters
    ----------
    scene : Scene
        The point of Pi-space and its pulse.  The system starts at rest at
        ``scene.pulse.tau_start``.
    rtol : float
        Relative tolerance passed to ``solve_ivp`` (DOP853).
    history : bool
        Also return the step-by-step :class:`~isoslide.store.history.History`.
    atol : float
        Absolute tolerance (lengths in ``a_p T_p**2``, velocities in ``a_p T_p``).
    tau_max : float or None
        Horizon in units of ``T_p``; default see the module docstring.
    max_events : int
        Safety cap on the number of transitions (raises ``RuntimeError``).
    max_work : int or None
        Most right-hand-side evaluations (raises :class:`~isoslide.peers.result.WorkLimitError`);
        None: unbounded.

    Returns
    -------
    PeerResult
        ``method = "reference"``, ``integrator = "DOP853"``; cost in ``nfev``.
    """
    if not scene.paper_model:
        return solve_reference_building(scene, rtol=rtol, history=history, atol=atol, tau_max=tau_max,
                                        max_events=max_events, max_work=max_work)
    pulse = scene.pulse
    code = int(pulse.code)
    params = pulse.param_array
    fixed = scene.fixed_base
    om = 0.0 if fixed else 2.0 * math.pi / scene.pi3
    z = scene.pi4
    m1 = 1.0 + scene.pi8
    pi8 = scene.pi8
    c = 2.0 * z * om
    k = om * om
    phi0 = scene.pi2 / scene.pi5
    # stick holds while |a_req| <= lim; lim exceeds phi0 by a few ulp so that an
    # a_req resting exactly on the static level (e.g. rectangular pulse with
    # Pi2 = 1) sticks instead of chattering, and a breakaway starts with a
    # strictly outward relative acceleration.  Shifts transition times by
    # ~1e-15 / |a_req'|, far below any tolerance.
    lim = phi0 * (1.0 + 4e-15)
    tau_end = float(pulse.tau_end)
    horizon = _default_horizon(scene) if tau_max is None else float(tau_max)
    bps = [float(b) for b in pulse.breakpoint_array if b < horizon]
    # max step so a stick/slip excursion cannot hide inside one step
    hmax_pulse = 1.0 / 64.0
    hmax_free = max(1.0, scene.pi3) / 64.0

    def phi(v):
        return friction_level(scene, v)

    def areq(tau, y):
        if fixed:
            return accel_at(code, params, tau)
        return -(c * y[1] + k * y[0]) / m1

    tau = float(pulse.tau_start)
    y = np.zeros(4)
    mode, s = STICK, 0.0
    peak, tau_peak = 0.0, tau
    n_events = 0
    nfev = 0
    used = [0]
    settled = False
    hist = [] if history else None
    zero_len = 0

    def record(sol, phase):
        if hist is not None:
            hist.append((sol.t, sol.y.copy(), np.full(sol.t.shape, phase, dtype=np.int8)))

    while True:
        if n_events > max_events:
            raise RuntimeError(f"more than {max_events} stick/slip transitions; scene={scene!r}")
        # ---- decide the phase at the current point --------------------------------
        if mode == STICK:
            a = areq(tau, y)
            if abs(a) > lim:
                mode, s = SLIP, -math.copysign(1.0, a)
                n_events += 1
                continue
            if tau >= tau_end:
                if fixed:
                    settled = True
                    break
                sup, t_sup = stuck_supremum(y[0], y[1], om, z, m1)
                if sup <= lim:
                    settled = True
                    break
        if tau >= horizon:
            break
        # ---- end of this integration segment ----------------------------------------
        nxt = [b for b in bps if b > tau]
        t_end = nxt[0] if nxt else horizon
        if mode == STICK and tau >= tau_end and not fixed:
            t_end = min(horizon, tau + 1.05 * t_sup + 1e-6 * max(1.0, scene.pi3))
        t_end = min(t_end, horizon)
        # p is evaluated on [tau, t_end) only: its left limit at t_end
        t_clip = math.nextafter(t_end, -math.inf)
        t0 = tau
        hmax = hmax_pulse if t0 < tau_end else hmax_free

        def p_of(t, t0=t0, t_clip=t_clip):
            return accel_at(code, params, min(max(t, t0), t_clip))

        if mode == STICK:
            def rhs(t, yy):
                if fixed:
                    return np.zeros(4)
                xdd = -p_of(t) - (c * yy[1] + k * yy[0]) / m1
                return np.array([yy[1], xdd, 0.0, 0.0])

            if fixed:
                def ev_pos(t, yy):
                    return lim - p_of(t)

                def ev_neg(t, yy):
                    return lim + p_of(t)
            else:
                def ev_pos(t, yy):
                    return lim + (c * yy[1] + k * yy[0]) / m1

                def ev_neg(t, yy):
                    return lim - (c * yy[1] + k * yy[0]) / m1
            ev_pos.terminal = ev_neg.terminal = True
            ev_pos.direction = ev_neg.direction = -1.0
            events = [ev_pos, ev_neg]
        else:
            ss = s

            def rhs(t, yy, ss=ss):
                ph = phi(yy[3])
                p = p_of(t)
                if fixed:
                    return np.array([0.0, 0.0, yy[3], -ss * ph - p])
                xdd = -p - c * yy[1] - k * yy[0] + pi8 * ss * ph
                return np.array([yy[1], xdd, yy[3], -ss * ph - p - xdd])

            def ev_stop(t, yy, ss=ss):
                return ss * yy[3]
            ev_stop.terminal = True
            ev_stop.direction = -1.0
            events = [ev_stop]

        sol = solve_ivp(counted(rhs, max_work, "reference", used), (t0, t_end), y, method="DOP853",
                        rtol=rtol, atol=atol, events=events, max_step=hmax)
        nfev += sol.nfev
        if sol.status < 0:
            raise RuntimeError(f"solve_ivp failed: {sol.message}")
        record(sol, 0 if mode == STICK else int(s))
        if sol.status == 1:  # an event
            hits = [(te[0], ye[0]) for te, ye in zip(sol.t_events, sol.y_events, strict=True) if len(te)]
            te, ye = min(hits, key=lambda h: h[0])
            zero_len = zero_len + 1 if te <= t0 else 0
            if zero_len > 4:
                raise RuntimeError(f"zero-length stick/slip chatter at tau={te!r}; scene={scene!r}")
            tau = float(te)
            y = np.array(ye, dtype=float)
            n_events += 1
            if mode == STICK:
                a = areq(tau, y) if not fixed else p_of(tau)
                mode, s = SLIP, -math.copysign(1.0, a)
                y[3] = 0.0
            else:
                y[3] = 0.0
                if abs(y[2]) > peak:
                    peak, tau_peak = abs(y[2]), tau
                a = areq(tau, y) if not fixed else p_of(tau)
                if abs(a) <= lim:
                    mode, s = STICK, 0.0
                else:
                    s = -math.copysign(1.0, a)
        else:
            tau = float(sol.t[-1])
            y = np.array(sol.y[:, -1], dtype=float)
            if tau >= t_end:
                tau = t_end  # land exactly on the breakpoint

    if abs(y[2]) > peak:
        peak, tau_peak = abs(y[2]), tau
    h = None
    if hist is not None:
        tt = np.concatenate([a for a, _, _ in hist]) if hist else np.array([tau])
        yy = np.concatenate([b for _, b, _ in hist], axis=1) if hist else y[:, None]
        ph = np.concatenate([m for _, _, m in hist]) if hist else np.zeros(1, dtype=np.int8)
        h = History(tau=tt, x=yy[0], xd=yy[1], u=yy[2], ud=yy[3], phase=ph)
    return PeerResult(method="reference", pi1=float(peak), pi1_residual=float(y[2]),
                      tau_peak=float(tau_peak), settled=settled, n_events=n_events, tau_end=float(tau),
                      nfev=int(nfev), integrator="DOP853", history=h)
