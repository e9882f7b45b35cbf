"""The similarity check's independent solver: the physical equations integrated in SI units.

:func:`simulate_si` takes the physical parameters of one realisation of a point
of Pi-space (metres, seconds, kilograms; see
:func:`isoslide.studies.similarity.physical_parameters`) and integrates the stick-slip
response with plain SciPy, independently of :mod:`isoslide.engine.kernel` and of the
dimensionless peers, so that ``Pi1 = u_max / (a_p T_p^2)`` can be compared
across realisations with equal Pi-groups.  A general building (hysteretic isolator, flexible
superstructure of one or more storeys, contents on any floor) is integrated by
:func:`isoslide.peers.si_building.simulate_building_si`; the paper's model by the plain
two-state solver below.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp

from ..store.history import History
from ..pulses import accel_at, get_pulse
from .result import PeerResult
from .si_building import is_general, simulate_building_si

__all__ = ["simulate_si"]


def simulate_si(p: dict, pulse="ricker", t_end: float | None = None, rtol: float = 1e-12,
                history: bool = False) -> PeerResult:
    """Stick-slip response of a block on an isolated floor, integrated in SI units.

    A deliberately plain implementation (SciPy ``solve_ivp``, DOP853, with
    event location) of the physical equations, independent of
    :mod:`isoslide.engine.kernel`, used to test the similarity groups:

    * base (relative to the ground), block stuck:
      ``(M_b + m) (x'' + a_g) = -c x' - k x``;
    * sliding in direction ``s``: friction acceleration of the block
      ``phi = -s mu(|u'|) g``, ``M_b (x'' + a_g) = -c x' - k x - m phi``,
      ``a_g + x'' + u'' = phi``;
    * the block sticks when ``u' = 0`` and the floor acceleration ``A``
      satisfies ``|A| <= mu_s g``; it breaks loose when ``|A| > mu_s g``,
      sliding in direction ``-sign(A)``.

    ``T_b = 0`` is a fixed base (floor = ground).  Where the block touches its stick limit
    tangentially and stick and slip would alternate at one instant, the run is integrated by the
    building's equations (which hold the paper's model) instead.  Parameters of a general building
    (``Q_d > 0`` on an isolated base, or ``T_s > 0``) are integrated with the building's
    equations by :func:`~isoslide.peers.si_building.simulate_building_si` (so are floors given one
    by one, ``floor_masses``).

    Parameters
    ----------
    p : dict
        SI parameters ``a_p, T_p, M_b, T_b, xi_b, m_ec, mu_s, mu_k, beta, gamma, g`` and
        optionally the building's ``Q_d`` (N), ``D_y`` (m), ``m_st`` (kg), ``T_s`` (s), ``xi_s``,
        ``floor``, ``storeys`` and ``floor_masses`` (kg) with ``storey_stiffnesses`` (N/m)
        (absent: the paper's model; as returned by
        :func:`isoslide.studies.similarity.physical_parameters`; see
        :func:`~isoslide.peers.si_building.simulate_building_si`).
    pulse : str or Pulse
        Ground-acceleration shape, ``a_g(t) = a_p p(t / T_p)``.
    t_end : float, optional
        End time, s (default: pulse end + 20 isolation or pulse periods).
    rtol : float
        Relative tolerance of the integrator.
    history : bool
        Also return the step-by-step :class:`~isoslide.store.history.History`
        (made dimensionless with ``a_p`` and ``T_p``).

    Returns
    -------
    PeerResult
        ``method = "si"``, ``integrator = "DOP853"``: ``pi1 = u_max / (a_p T_p^2)``
        (``u_max`` in m), ``pi1_residual``, ``tau_peak``, ``tau_end = t_end / T_p``,
        ``n_events``, ``nfev``; ``settled`` is False (the run always goes to ``t_end``).
    """
    if is_general(p):
        return simulate_building_si(p, pulse, t_end=t_end, rtol=rtol, history=history)
    try:
        return _simulate_paper(p, pulse, t_end, rtol, history)
    except _Stalled:
        # the block touched its stick limit tangentially and the two-state solver alternates
        # between stick and slip at one instant; the building's joint mode choice (a slip is
        # taken only when it accelerates in its own direction) settles the mode there
        return simulate_building_si(p, pulse, t_end=t_end, rtol=rtol, history=history)


class _Stalled(RuntimeError):
    """The paper model's two-state solver makes no progress in time (stick/slip alternation)."""


def _simulate_paper(p: dict, pulse, t_end: float | None, rtol: float, history: bool) -> PeerResult:
    """:func:`simulate_si` for the paper's model (linear isolator, rigid superstructure)."""
    pul = get_pulse(pulse)
    a_p, T_p, g = p["a_p"], p["T_p"], p["g"]
    M, m = p["M_b"], p["m_ec"]
    mu_s, mu_k, beta, gamma = p["mu_s"], p["mu_k"], p["beta"], p["gamma"]
    fixed = p["T_b"] == 0.0
    k = 0.0 if fixed else M * (2.0 * math.pi / p["T_b"]) ** 2
    c = 0.0 if fixed else 2.0 * p["xi_b"] * math.sqrt(k * M)
    code, params = pul.code, pul.param_array
    L = a_p * T_p * T_p

    def ag(t):
        return a_p * accel_at(code, params, t / T_p)

    def floor_stuck(t, y):
        """Absolute floor acceleration with the block stuck."""
        return ag(t) if fixed else (-c * y[1] - k * y[0]) / (M + m)

    def mu(v):
        bv = min(abs(beta * v), 700.0)
        sech = 1.0 / math.cosh(bv)
        return mu_s * sech + mu_k * (1.0 - sech) + gamma * abs(v)

    def rhs_stick(t, y):
        if fixed:
            return (0.0, 0.0, 0.0, 0.0)
        xdd = floor_stuck(t, y) - ag(t)
        return (y[1], xdd, 0.0, 0.0)

    def make_slip(s):
        def rhs(t, y):
            phi = -s * mu(y[3]) * g
            xdd = 0.0 if fixed else (-c * y[1] - k * y[0] - m * phi) / M - ag(t)
            return (y[1], xdd, y[3], phi - ag(t) - xdd)
        return rhs

    def decide(t, y):
        A = floor_stuck(t, y)
        if abs(A) <= mu_s * g:
            return 0
        return -1 if A > 0 else 1

    period = T_p if fixed else max(p["T_b"], 1e-300)
    t0 = pul.tau_start * T_p
    t_pulse_end = pul.tau_end * T_p
    if t_end is None:
        t_end = t_pulse_end + 20.0 * max(period, T_p)
    bounds = sorted({float(b) * T_p for b in pul.breakpoint_array if pul.tau_start < b} | {t_end})
    bounds = [b for b in bounds if t0 < b <= t_end] or [t_end]
    h_pulse = min(T_p, period) / 12.0
    h_free = h_pulse
    # sliding under a sharp Stribeck drop is sensitive to the first instants of slip: resolve them
    stribeck = beta > 0.0 and mu_s != mu_k
    h_slip = min(T_p, period) / 200.0

    atol = np.array([1e-12 * L, 1e-12 * a_p * T_p, 1e-12 * L, 1e-12 * a_p * T_p])
    t, y = t0, np.zeros(4)
    phase = decide(t, y)
    u_max, t_peak, n_events, nfev = 0.0, t0, 0, 0
    hist = [] if history else None
    bi = 0
    guard = 0
    stall, t_last = 0, t
    while t < t_end - 1e-12 * T_p:
        guard += 1
        if guard > 100000:
            raise RuntimeError("simulate_si: too many phases (chattering?)")
        stall = stall + 1 if t == t_last else 0
        t_last = t
        if stall > 1000:
            raise _Stalled(f"simulate_si: stick and slip alternate at t = {t!r} s")
        while bi < len(bounds) and bounds[bi] <= t + 1e-14 * T_p:
            bi += 1
        t_next = bounds[bi] if bi < len(bounds) else t_end
        h = h_pulse if t < t_pulse_end else h_free
        if phase != 0 and stribeck:
            h = min(h, h_slip)
        if phase == 0:
            if fixed:
                fun = rhs_stick
            else:
                fun = rhs_stick
            up = lambda tt, yy: floor_stuck(tt, yy) - mu_s * g  # noqa: E731
            dn = lambda tt, yy: floor_stuck(tt, yy) + mu_s * g  # noqa: E731
            up.terminal, up.direction = True, 1.0
            dn.terminal, dn.direction = True, -1.0
            events = [up, dn]
        else:
            fun = make_slip(phase)
            stop = lambda tt, yy: yy[3]  # noqa: E731
            stop.terminal, stop.direction = True, -float(phase)
            events = [stop]
        if fixed and phase == 0 and pul.code != 0:
            # piecewise-constant ground acceleration of a fixed base: nothing moves while stuck
            t = t_next
            if hist is not None:
                hist.append((np.array([t]), y[:, None].copy(), 0))
            phase = decide(t, y)
            continue
        sol = solve_ivp(fun, (t, t_next), y, method="DOP853", rtol=rtol, atol=atol, events=events,
                        max_step=h)
        if sol.status == -1:
            raise RuntimeError(f"simulate_si: integration failed: {sol.message}")
        nfev += sol.nfev
        if hist is not None:
            hist.append((sol.t, sol.y.copy(), phase))
        hit = [i for i, te in enumerate(sol.t_events) if len(te)]
        if hit:
            i = hit[0]
            t, y = float(sol.t_events[i][0]), np.array(sol.y_events[i][0], dtype=float)
            n_events += 1
            if phase != 0:
                y[3] = 0.0
                if abs(y[2]) > u_max:
                    u_max, t_peak = abs(y[2]), t
                phase = decide(t, y)
            else:
                phase = -1 if floor_stuck(t, y) > 0 else 1
        else:
            t, y = float(sol.t[-1]), sol.y[:, -1].copy()
            j = int(np.argmax(np.abs(sol.y[2])))
            if abs(sol.y[2, j]) > u_max:
                u_max, t_peak = float(abs(sol.y[2, j])), float(sol.t[j])
            if phase == 0 or y[3] == 0.0:
                phase = decide(t, y)
    if abs(y[2]) > u_max:
        u_max, t_peak = abs(y[2]), t
    v = a_p * T_p
    h = None
    if hist is not None:
        tt = np.concatenate([a for a, _, _ in hist]) if hist else np.array([t])
        yy = np.concatenate([b for _, b, _ in hist], axis=1) if hist else y[:, None]
        ph = np.concatenate([np.full(a.shape, f, dtype=np.int8) for a, _, f in hist]) if hist \
            else np.zeros(1, dtype=np.int8)
        h = History(tau=tt / T_p, x=yy[0] / L, xd=yy[1] / v, u=yy[2] / L, ud=yy[3] / v, phase=ph)
    return PeerResult(method="si", pi1=u_max / (a_p * T_p**2), pi1_residual=float(y[2]) / (a_p * T_p**2),
                      tau_peak=t_peak / T_p, settled=False, n_events=n_events, tau_end=t / T_p,
                      nfev=nfev, integrator="DOP853", history=h)
