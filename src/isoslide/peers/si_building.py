"""The general building integrated in SI units, for the similarity check.

:func:`simulate_building_si` is the general-building branch of
:func:`isoslide.peers.si.simulate_si`: a hysteretic isolator (bilinear bearing, or sliding
bearing with true stick), a flexible superstructure of one or more storeys and contents on the
base slab or on any floor above it, written in newtons, metres, seconds and kilograms from the physical equations, independently of the
compiled kernel and of the dimensionless peers, so that ``Pi1 = u_max / (a_p T_p^2)`` of
realisations with equal Pi-groups (Pi9 .. Pi13 included) can be compared.  The state's layout and
the rule that chooses the modes below are shared with the dimensionless building reference
(:mod:`isoslide.peers.stick_slip`).

Equations (SI)
--------------
Masses: ``M_b`` the whole isolated mass (slab and superstructure), ``m_st`` the superstructure's
(0 when rigid, ``T_s = 0``), ``m_b = M_b - m_st`` the slab's, ``m`` the contents'.  Isolator
``F_iso = k_d x_b + c_b x_b' + f_h`` with ``k_d = M_b (2 pi / T_b)^2``,
``c_b = 2 xi_b sqrt(k_d M_b)``.  Superstructure: ``N`` floors (``storeys``) of masses ``m_j`` (kg),
storey ``j`` of stiffness ``k_j`` (N/m) joining floor ``j-1`` and floor ``j`` (floor 0 the slab);
given floor by floor (``floor_masses``, ``storey_stiffnesses``; then ``m_st = sum m_j``), or
uniform: ``m_j = m_st/N`` and equal ``k_j`` making the fixed-base fundamental period ``T_s``.
``K`` is the fixed-base stiffness matrix of the chain (N/m), ``C`` the classical damping with ratio
``xi_s`` in every fixed-base mode (N s/m); with ``N = 1``: ``k_s = m_st (2 pi / T_s)^2``,
``c_s = 2 xi_s sqrt(k_s m_st)``.  With ``x_s`` the floors' displacements relative to the slab and
``f = K x_s + C x_s'``::

    slab:            m_b  (a_g + x_b'')            = -F_iso + sum_j f_j + [R on the slab]
    floor j:         m_j  (a_g + x_b'' + x_s_j'')  = -f_j + [R on floor j]
    contents:        m    (a_F + u'')              = -F_f,   R = F_f

``a_F`` is the absolute acceleration of the contents' floor.  Contents: stuck (``u' = 0``,
``F_f = -m a_F``) while ``|a_F| <= mu_s g``; sliding in ``s = sgn(u')`` with
``F_f = m s mu(|u'|) g``, ``mu(v) = mu_s sech(beta v) + mu_k (1 - sech(beta v)) + gamma v``.
Isolator ``f_h``: 0 (linear, ``Q_d = 0``); elastic-perfectly-plastic of stiffness
``k_e = Q_d / D_y`` and strength ``Q_d`` (bilinear): ``f_h' = k_e x_b'`` while ``|f_h| < Q_d``,
``f_h = +-Q_d`` from yield until ``x_b'`` changes sign; sliding bearing (``D_y = 0``): held
(``x_b' = x_b'' = 0``) while the force it must supply
``f_need = -m_b a_g - k_d x_b + sum_j f_j + [R on the slab]`` has ``|f_need| <= Q_d``, else
``f_h = Q_d sgn(x_b')``.  ``T_b = 0`` is a fixed base (a bearing held for ever).

Modes at zero relative velocity
-------------------------------
The contents and a sliding bearing are frictional interfaces; at every phase start the modes of
those at zero relative velocity are chosen together: of the combinations (stuck, +1, -1), in the
order all stuck; contents stuck & bearing sliding; contents sliding & bearing stuck; both
sliding, the first consistent one is taken (every stuck interface within its limit, every
sliding one accelerating in its own direction).  A breakaway slides in the direction of the
force that broke the limit.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from ..store.history import History
from ..pulses import accel_at, get_pulse
from ..scene import FLOORS
from .result import PeerResult
from .stick_slip import X, XD, XS, StateIndex, bearing_event, choose_modes, farther, phase_modes, sign

__all__ = ["is_general", "simulate_building_si"]

# state (isoslide.peers.stick_slip.StateIndex): slab rel. ground (m, m/s), floors rel. slab (m each,
# then m/s each), contents rel. floor (m, m/s), hysteretic isolator force (N)
_SLACK = 4e-15       # relative slack of the stick limits against round-off


def is_general(p: dict) -> bool:
    """True when the SI parameters ``p`` describe more than the paper's model.

    A hysteretic isolator (``Q_d > 0`` on an isolated base) or a flexible superstructure
    (``T_s > 0``, or floors given one by one); the contents' floor alone changes nothing under a
    rigid superstructure.
    """
    hysteretic = p.get("Q_d", 0.0) > 0.0 and p["T_b"] > 0.0
    return hysteretic or p.get("T_s", 0.0) > 0.0 or p.get("floor_masses") is not None


def chain_matrices(masses, stiffnesses, xi: float) -> tuple:
    """Fixed-base stiffness and classical damping of a shear chain, and its circular frequencies.

    Parameters
    ----------
    masses : sequence of float
        Floor masses, bottom to top, kg (> 0).
    stiffnesses : sequence of float
        Storey stiffnesses, bottom to top, N/m (> 0); storey ``j`` joins floor ``j-1`` and floor
        ``j``, floor 0 being the held slab.
    xi : float
        Damping ratio of every fixed-base mode (>= 0).

    Returns
    -------
    (K, C, omega) : tuple of ndarray
        ``K`` (N/m) and ``C = M Phi diag(2 xi omega) Phi^T M`` (N s/m), ``Phi`` the mass-normalised
        fixed-base modes; ``omega`` the fixed-base circular frequencies, ascending, rad/s.
    """
    m = np.array(masses, dtype=float)
    k = np.array(stiffnesses, dtype=float)
    n = m.size
    K = np.diag(k + np.append(k[1:], 0.0)) - np.diag(k[1:], 1) - np.diag(k[1:], -1)
    s = 1.0 / np.sqrt(m)
    lam, V = np.linalg.eigh(s[:, None] * K * s[None, :])      # M^-1/2 K M^-1/2 = V lam V^T
    omega = np.sqrt(np.maximum(lam, 0.0))
    Phi = s[:, None] * V                                      # Phi^T M Phi = I
    MPhi = m[:, None] * Phi
    C = MPhi @ np.diag(2.0 * xi * omega) @ MPhi.T if n else np.zeros((0, 0))
    return K, 0.5 * (C + C.T), omega


@dataclass(frozen=True)
class _Building(StateIndex):
    """SI parameters of one realisation (kg, N/m, N s/m, N, m/s^2, s/m); ``ms, K, C`` of the floors."""

    mb: float
    m: float
    kd: float
    cb: float
    ms: np.ndarray
    K: np.ndarray
    C: np.ndarray
    omega: np.ndarray
    Q: float
    ke: float
    g: float
    mu_s: float
    mu_k: float
    beta: float
    gamma: float
    kind: str          # "linear", "bilinear", "sliding" or "fixed"
    flexible: bool
    floor: int         # 0 the slab, N the roof

    def friction(self, v: float) -> float:
        """Friction acceleration ``mu(|v|) g`` of the sliding contents, m/s^2."""
        v = abs(v)
        bv = self.beta * v
        sech = 0.0 if bv > 700.0 else 1.0 / math.cosh(bv)
        return (self.mu_s * sech + self.mu_k * (1.0 - sech) + self.gamma * v) * self.g


def _storeys(p: dict) -> int:
    """The number of floors ``N`` of a flexible superstructure in ``p`` (checked)."""
    fm = p.get("floor_masses")
    n = p.get("storeys", 1) if fm is None else len(fm)
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or not 1 <= n <= 64:
        raise ValueError(f"storeys = {n!r} is out of range; allowed: an integer, 1 <= value <= 64")
    if fm is not None and p.get("storeys", n) != n:
        raise ValueError(f"storeys = {p['storeys']!r} disagrees with floor_masses ({n} floors); allowed: {n}")
    return int(n)


def _floor_number(p: dict, n: int) -> int:
    """The contents' floor in ``p`` as a number, 0 (the slab, ``"base"``) .. ``n`` (``"roof"``)."""
    floor = p.get("floor", FLOORS[0])
    if isinstance(floor, str):
        if floor in FLOORS:
            return 0 if floor == FLOORS[0] else n
    elif not isinstance(floor, bool) and isinstance(floor, (int, np.integer)) and 0 <= floor <= n:
        return int(floor)
    raise ValueError(f"floor = {floor!r} is invalid; allowed: {FLOORS} or an integer, 0 <= value <= {n}")


def _check(p: dict) -> None:
    for k in ("a_p", "T_p", "M_b", "g"):
        if not p[k] > 0.0:
            raise ValueError(f"{k} = {p[k]!r} is out of range; allowed range: 0 < value < inf")
    for k in ("T_b", "xi_b", "m_ec", "Q_d", "D_y", "T_s", "xi_s"):
        if not p.get(k, 0.0) >= 0.0:
            raise ValueError(f"{k} = {p[k]!r} is out of range; allowed range: 0 <= value < inf")
    fm, fk = p.get("floor_masses"), p.get("storey_stiffnesses")
    if (fm is None) != (fk is None):
        raise ValueError("floor_masses and storey_stiffnesses are given together; allowed: both or neither")
    n = _storeys(p)
    if fm is not None:
        for name, vals in (("floor_masses", fm), ("storey_stiffnesses", fk)):
            if len(vals) != n:
                raise ValueError(f"{name} has {len(vals)} values; allowed: one per storey (storeys = {n})")
            for i, v in enumerate(vals):
                if not (0.0 < v < math.inf):
                    raise ValueError(f"{name}[{i}] = {v!r} is out of range; allowed range: 0 < value < inf")
        total = math.fsum(fm)
        if not total < p["M_b"]:
            raise ValueError(f"floor_masses sum to {total!r} kg; allowed: less than M_b = {p['M_b']!r}")
        if p.get("m_st", 0.0) != 0.0 and abs(p["m_st"] - total) > 1e-9 * total:
            raise ValueError(f"m_st = {p['m_st']!r} disagrees with floor_masses (sum {total!r}); "
                             f"allowed: 0 or {total!r}")
    elif p.get("T_s", 0.0) > 0.0 and not 0.0 < p["m_st"] < p["M_b"]:
        raise ValueError(f"m_st = {p['m_st']!r} is out of range with T_s > 0; allowed range: "
                         f"0 < m_st < M_b = {p['M_b']!r}")
    _floor_number(p, n)


def _building(p: dict) -> _Building:
    M = p["M_b"]
    fm = p.get("floor_masses")
    flexible = p.get("T_s", 0.0) > 0.0 or fm is not None
    if p["T_b"] == 0.0:
        kind, kd, cb = "fixed", 0.0, 0.0
    else:
        kd = M * (2.0 * math.pi / p["T_b"]) ** 2
        cb = 2.0 * p["xi_b"] * math.sqrt(kd * M)
        Q_d, D_y = p.get("Q_d", 0.0), p.get("D_y", 0.0)
        kind = "linear" if Q_d == 0.0 else ("bilinear" if D_y > 0.0 else "sliding")
    xi_s = p.get("xi_s", 0.0)
    if not flexible:
        ms, K, C, omega, floor = np.zeros(0), np.zeros((0, 0)), np.zeros((0, 0)), np.zeros(0), 0
    elif fm is not None:
        ms = np.array(fm, dtype=float)
        K, C, omega = chain_matrices(ms, p["storey_stiffnesses"], xi_s)
        T_s = p.get("T_s", 0.0)
        if T_s and abs(T_s - 2.0 * math.pi / omega[0]) > 1e-9 * T_s:
            raise ValueError(f"T_s = {T_s!r} disagrees with the floors given ({2.0 * math.pi / omega[0]!r}); "
                             f"allowed: 0 or {2.0 * math.pi / omega[0]!r}")
        floor = _floor_number(p, ms.size)
    else:
        n = _storeys(p)
        ms = np.full(n, p["m_st"] / n)
        _, _, w1 = chain_matrices(ms, np.ones(n), 0.0)      # unit storeys: scale to T_s
        k = (2.0 * math.pi / p["T_s"] / w1[0]) ** 2
        K, C, omega = chain_matrices(ms, np.full(n, k), xi_s)
        floor = _floor_number(p, n)
    Q = math.inf if kind == "fixed" else p.get("Q_d", 0.0)
    ke = p["Q_d"] / p["D_y"] if kind == "bilinear" else 0.0
    return _Building(mb=M - float(ms.sum()), m=p["m_ec"], kd=kd, cb=cb, ms=ms, K=K, C=C, omega=omega, Q=Q, ke=ke,
                     g=p["g"], mu_s=p["mu_s"], mu_k=p["mu_k"], beta=p["beta"], gamma=p["gamma"], kind=kind,
                     flexible=flexible, floor=floor)


def _motion(B: _Building, ag: float, y, sb: int, si: int):
    """Accelerations (m/s^2), isolator force rate (N/s), floor acceleration and needed force.

    ``sb``: contents stuck (0) or sliding (+-1); ``si``: isolator held/elastic (0) or
    sliding/yielding (+-1).  Returns ``(x_b'', x_s'', u'', f_h', a_F, f_need)`` with ``x_s''`` an
    array over the floor slots and ``f_need`` (N) nan unless a bearing holds the slab.
    """
    held = B.holds and si == 0
    n, k = B.n, B.floor
    if n:
        f = B.K @ y[XS:XS + n] + B.C @ y[B.XSD:B.XSD + n]
        S = float(np.sum(f))
    else:
        S = 0.0
    if B.kind == "bilinear":
        fh = y[B.FH]
    elif B.kind == "sliding":
        fh = si * B.Q
    else:
        fh = 0.0
    F = B.kd * y[X] + B.cb * y[XD] + fh
    Ff = B.m * sb * B.friction(y[B.UD]) if sb else 0.0
    if k:
        a_b = ag if held else (-F + S) / B.mb
        a_fl = -f / B.ms
        if sb == 0:
            a_fl[k - 1] = -f[k - 1] / (B.ms[k - 1] + B.m)
            Ff = -B.m * a_fl[k - 1]
        else:
            a_fl[k - 1] = (-f[k - 1] + Ff) / B.ms[k - 1]
        a_F = a_fl[k - 1]
    else:
        if held:
            a_b = ag
        elif sb == 0:
            a_b = (-F + S) / (B.mb + B.m)
        else:
            a_b = (-F + S + Ff) / B.mb
        if sb == 0:
            Ff = -B.m * a_b
        a_fl = -f / B.ms if n else None
        a_F = a_b
    udd = 0.0 if sb == 0 else -a_F - Ff / B.m
    if held:
        xdd = 0.0
        f_need = -B.mb * ag - B.kd * y[X] + S + (0.0 if k else Ff)
    else:
        xdd = a_b - ag
        f_need = math.nan
    xsdd = a_fl - a_b if n else np.zeros(1)
    fhd = B.ke * y[XD] if (B.kind == "bilinear" and si == 0) else 0.0
    return xdd, xsdd, udd, fhd, a_F, f_need


def _modes(B: _Building, ag: float, y, sb: int, si: int, broke_b: int, broke_i: int):
    """Consistent modes ``(sb, si)`` of the contents and a sliding bearing at a phase start."""
    lim_b = B.mu_s * B.g * (1.0 + _SLACK)
    lim_q = B.Q * (1.0 + _SLACK)
    modes = choose_modes(B, y, sb, si, broke_b, broke_i, lim_b, lim_q, lambda b, i: _motion(B, ag, y, b, i))
    if modes is not None:
        return modes
    raise RuntimeError(f"simulate_si: no consistent stick/slip mode at the state {list(y)!r}, a_g = {ag!r}")


def _yield_mode(B: _Building, ag: float, y, sb: int, si: int) -> int:
    """Elastic (0) or yielding (+-1) state of a bilinear bearing at a phase start (no event)."""
    FH = B.FH
    if si == 0:
        s = sign(y[FH])
        if s and abs(y[FH]) >= B.Q * (1.0 - _SLACK):
            v = y[XD] if y[XD] != 0.0 else _motion(B, ag, y, sb, s)[0]
            if s * v > 0.0:
                return s
        return 0
    v = y[XD] if y[XD] != 0.0 else _motion(B, ag, y, sb, si)[0]
    return si if si * v > 0.0 else 0


def _stop(s: int, k: int, t0: float, v0: float, a0: float):
    """Event: velocity ``y[k]`` moving in direction ``s`` back to zero, without a root at ``t0``."""
    def ev(t, y):
        dt = t - t0
        if dt > 0.0:
            return s * y[k] / dt
        return s * v0 if v0 != 0.0 else s * a0
    ev.terminal, ev.direction = True, -1.0
    return ev


def _limit(fn):
    fn.terminal, fn.direction = True, -1.0
    return fn


def _both_ways(margin, kind: str) -> list:
    """The events of a stick limit reached from either side, each with what it marks (``kind``).

    ``margin(t, y, s)`` is the room left to the limit in direction ``s`` (N, or m/s^2 for the
    contents): one event for ``s = +1``, then one for ``s = -1``, each ending where it falls to zero.
    """
    return [(_limit(lambda t, y, s=s: margin(t, y, s)), kind) for s in (1.0, -1.0)]


def simulate_building_si(p: dict, pulse="ricker", t_end: float | None = None, rtol: float = 1e-12,
                         history: bool = False) -> PeerResult:
    """Stick-slip response of contents in a general building, integrated in SI units.

    Parameters
    ----------
    p : dict
        SI parameters of :func:`isoslide.studies.similarity.physical_parameters`: ``a_p`` (m/s^2), ``T_p``
        (s), ``M_b`` (kg, slab and superstructure), ``T_b`` (s, 0 = fixed base), ``xi_b``, ``m_ec``
        (kg), ``mu_s``, ``mu_k``, ``beta`` (s/m), ``gamma`` (s/m), ``g`` (m/s^2), ``Q_d`` (N),
        ``D_y`` (m), ``m_st`` (kg), ``T_s`` (s, 0 = rigid), ``xi_s``, ``floor`` (``"base"``,
        ``"roof"`` or a floor's number ``0 .. storeys``; default ``"base"``), ``storeys`` (default 1:
        a uniform superstructure of ``storeys`` floors) or, for a non-uniform one,
        ``floor_masses`` (kg) and ``storey_stiffnesses`` (N/m), bottom to top (then ``m_st`` and
        ``T_s`` may be 0; given, they must agree with the floors).
    pulse : str or Pulse
        Ground-acceleration shape, ``a_g(t) = a_p p(t / T_p)``.
    t_end : float, optional
        End time, s (default: pulse end + 20 times the longest of ``T_p``, ``T_b``, ``T_s``).
    rtol : float
        Relative tolerance of the integrator.
    history : bool
        Also return the :class:`~isoslide.store.history.History` (dimensionless with ``a_p``, ``T_p``,
        ``M_b``; ``xs, xsd`` the roof's).

    Returns
    -------
    PeerResult
        As :func:`isoslide.peers.si.simulate_si`; ``n_events`` counts the contents' and the
        isolator's transitions.
    """
    _check(p)
    B = _building(p)
    pul = get_pulse(pulse)
    a_p, T_p = p["a_p"], p["T_p"]
    L, V, Fs = a_p * T_p * T_p, a_p * T_p, p["M_b"] * a_p
    code, params = pul.code, pul.param_array

    def ag_at(t):
        return a_p * accel_at(code, params, t / T_p)

    periods = [T_p]
    if B.kind != "fixed":
        periods.append(p["T_b"])
        if B.kind == "bilinear":
            periods.append(2.0 * math.pi * math.sqrt(p["M_b"] / (B.kd + B.ke)))
    periods.extend(2.0 * math.pi / w for w in B.omega)
    t0 = pul.tau_start * T_p
    if t_end is None:
        t_end = pul.tau_end * T_p + 20.0 * max(periods)
    bounds = sorted({float(b) * T_p for b in pul.breakpoint_array} | {t_end})
    bounds = [b for b in bounds if t0 < b <= t_end] or [t_end]
    # events are seen where their function changes sign between steps: a stick limit touched for
    # less than about a step goes unseen, and the slip it misses moves the contents by about
    # jerk * step^3; 128 steps per shortest period keep that far below the check's tolerance
    h_max = min(periods) / 128.0
    h_slip = min(periods) / 200.0 if (B.beta > 0.0 and B.mu_s != B.mu_k) else h_max
    slots = max(1, B.n)
    XSD, U, UD, FH = B.XSD, B.U, B.UD, B.FH
    atol = np.array([L, V] + [L] * slots + [V] * slots + [L, V, Fs]) * 1e-12
    lim_b = B.mu_s * B.g * (1.0 + _SLACK)
    lim_q = B.Q * (1.0 + _SLACK)

    t, y = t0, np.zeros(U + 3)
    sb = si = 0
    broke_b = broke_i = 0
    after_event = False
    u_max, t_peak, n_events, nfev, repeats = 0.0, t0, 0, 0, 0
    hist = [] if history else None
    while t < t_end:
        if n_events > 200_000:
            raise RuntimeError("simulate_si: too many transitions (chattering?)")
        ag0 = ag_at(t)
        sb, si, changes = phase_modes(B, y, sb, si, B.Q, after_event, functools.partial(_yield_mode, B, ag0, y, sb),
                                      functools.partial(_modes, B, ag0, y, sb, broke_b=broke_b, broke_i=broke_i))
        n_events += changes
        broke_b = broke_i = 0
        after_event = False

        t_next = next((b for b in bounds if b > t), t_end)
        t_last = math.nextafter(t_next, -math.inf)
        t_start = t

        def ag_in(tt, t_start=t_start, t_last=t_last):
            # the segment's own branch of a piecewise pulse, also at its ends
            return ag_at(min(max(tt, t_start), t_last))

        def rhs(tt, yy, sb=sb, si=si, ag_in=ag_in):
            xdd, xsdd, udd, fhd, _, _ = _motion(B, ag_in(tt), yy, sb, si)
            return np.concatenate(([yy[XD], xdd], yy[XSD:U], xsdd, [yy[UD], udd, fhd]))

        xdd0, _, udd0 = _motion(B, ag_in(t), y, sb, si)[:3]
        marks = []          # (event function, what it marks)
        if sb == 0:
            marks += _both_ways(lambda tt, yy, s, sb=sb, si=si, ag_in=ag_in:
                                lim_b - s * _motion(B, ag_in(tt), yy, sb, si)[4], "contents_break")
        else:
            marks.append((_stop(sb, UD, t, y[UD], udd0), "contents_stop"))
        if B.kind == "sliding":
            if si == 0:
                marks += _both_ways(lambda tt, yy, s, sb=sb, ag_in=ag_in:
                                    lim_q - s * _motion(B, ag_in(tt), yy, sb, 0)[5], "bearing_break")
            else:
                marks.append((_stop(si, XD, t, y[XD], xdd0), "bearing_stop"))
        elif B.kind == "bilinear":
            if si == 0:
                marks += _both_ways(lambda tt, yy, s: B.Q - s * yy[FH], "yield")
            else:
                marks.append((_stop(si, XD, t, y[XD], xdd0), "unload"))
        events, kinds = [ev for ev, _ in marks], [k for _, k in marks]

        h = h_slip if sb != 0 else h_max
        sol = solve_ivp(rhs, (t, t_next), y, method="DOP853", rtol=rtol, atol=atol, events=events or None,
                        max_step=h)
        if sol.status < 0:
            raise RuntimeError(f"simulate_si: integration failed: {sol.message}")
        nfev += sol.nfev
        if hist is not None:
            hist.append((sol.t, sol.y.copy(), sb))
        hits = [(float(te[0]), np.array(ye[0], dtype=float), k)
                for te, ye, k in zip(sol.t_events or [], sol.y_events or [], kinds, strict=False) if len(te)]
        if sol.status != 1 or not hits:
            t, y = t_next, np.array(sol.y[:, -1], dtype=float)
            continue
        te, ye, kind = min(hits, key=lambda e: e[0])
        repeats = repeats + 1 if te <= t else 0
        if repeats > 4:
            raise RuntimeError(f"simulate_si: zero-length stick/slip chatter at t = {te!r} s")
        t, y = te, ye
        n_events += 1
        after_event = True
        ag = ag_at(t)
        if kind == "contents_break":
            broke_b = -sign(_motion(B, ag, y, sb, si)[4])
        elif kind == "contents_stop":
            y[UD] = 0.0
            u_max, t_peak = farther(u_max, t_peak, y[U], t)
        elif kind == "bearing_break":
            broke_i = sign(_motion(B, ag, y, sb, si)[5])
        elif kind == "bearing_stop":
            y[XD] = 0.0
        elif kind in ("yield", "unload"):
            si = bearing_event(kind, y, FH, B.Q)
    u_max, t_peak = farther(u_max, t_peak, y[U], t)
    hh = None
    if hist is not None:
        tt = np.concatenate([a for a, _, _ in hist])
        yy = np.concatenate([b for _, b, _ in hist], axis=1)
        ph = np.concatenate([np.full(a.shape, f, dtype=np.int8) for a, _, f in hist])
        hh = History(tau=tt / T_p, x=yy[X] / L, xd=yy[XD] / V, u=yy[U] / L, ud=yy[UD] / V, phase=ph,
                     xs=yy[U - 1 - slots] / L if B.flexible else None, xsd=yy[U - 1] / V if B.flexible else None,
                     fh=yy[FH] / Fs if B.kind == "bilinear" else None)
    return PeerResult(method="si", pi1=u_max / L, pi1_residual=float(y[U]) / L, tau_peak=t_peak / T_p,
                      settled=False, n_events=n_events, tau_end=t / T_p, nfev=nfev, integrator="DOP853",
                      history=hh)
