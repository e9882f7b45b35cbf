"""The general building integrated in SI units, for the similarity check.

:func:`simulate_building_si` is the general-building branch of
:func:`isoslide.peers.si.simulate_si`: a hysteretic isolator (bilinear bearing, or sliding
bearing with true stick), a flexible superstructure and contents on the base slab or on the roof,
written in newtons, metres, seconds and kilograms from the physical equations, independently of the
compiled kernel and of the dimensionless peers, so that ``Pi1 = u_max / (a_p T_p^2)`` of
realisations with equal Pi-groups (Pi9 .. Pi13 included) can be compared.

Equations (SI)
--------------
Masses: ``M_b`` the whole isolated mass (slab and superstructure), ``m_st`` the superstructure's
(0 when rigid, ``T_s = 0``), ``m_b = M_b - m_st`` the slab's, ``m`` the contents'.  Isolator
``F_iso = k_d x_b + c_b x_b' + f_h`` with ``k_d = M_b (2 pi / T_b)^2``,
``c_b = 2 xi_b sqrt(k_d M_b)``; superstructure ``S = k_s x_s + c_s x_s'`` with
``k_s = m_st (2 pi / T_s)^2``, ``c_s = 2 xi_s sqrt(k_s m_st)``::

    slab:            m_b  (a_g + x_b'')          = -F_iso + S + [R on the base]
    superstructure:  m_st (a_g + x_b'' + x_s'')  = -S + [R on the roof]
    contents:        m    (a_F + u'')            = -F_f,   R = F_f

``a_F`` is the absolute acceleration of the contents' floor.  Contents: stuck (``u' = 0``,
``F_f = -m a_F``) while ``|a_F| <= mu_s g``; sliding in ``s = sgn(u')`` with
``F_f = m s mu(|u'|) g``, ``mu(v) = mu_s sech(beta v) + mu_k (1 - sech(beta v)) + gamma v``.
Isolator ``f_h``: 0 (linear, ``Q_d = 0``); elastic-perfectly-plastic of stiffness
``k_e = Q_d / D_y`` and strength ``Q_d`` (bilinear): ``f_h' = k_e x_b'`` while ``|f_h| < Q_d``,
``f_h = +-Q_d`` from yield until ``x_b'`` changes sign; sliding bearing (``D_y = 0``): held
(``x_b' = x_b'' = 0``) while the force it must supply
``f_need = -m_b a_g - k_d x_b + S + [R on the base]`` has ``|f_need| <= Q_d``, else
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

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from ..history import History
from ..pulses import accel_at, get_pulse
from ..scene import FLOORS
from .result import PeerResult

__all__ = ["is_general", "simulate_building_si"]

# state: slab rel. ground (m, m/s), superstructure rel. slab (m, m/s), contents rel. floor (m, m/s),
# hysteretic isolator force (N)
X, XD, XS, XSD, U, UD, FH = range(7)
_SLACK = 4e-15       # relative slack of the stick limits against round-off


def is_general(p: dict) -> bool:
    """True when the SI parameters ``p`` describe more than the paper's model.

    A hysteretic isolator (``Q_d > 0`` on an isolated base) or a flexible superstructure
    (``T_s > 0``); the contents' floor alone changes nothing under a rigid superstructure.
    """
    hysteretic = p.get("Q_d", 0.0) > 0.0 and p["T_b"] > 0.0
    return hysteretic or p.get("T_s", 0.0) > 0.0


@dataclass(frozen=True)
class _Building:
    """SI parameters of one realisation (kg, N/m, N s/m, N, m/s^2, s/m)."""

    mb: float
    mst: float
    m: float
    kd: float
    cb: float
    ks: float
    cs: float
    Q: float
    ke: float
    g: float
    mu_s: float
    mu_k: float
    beta: float
    gamma: float
    kind: str          # "linear", "bilinear", "sliding" or "fixed"
    flexible: bool
    roof: bool

    @property
    def holds(self) -> bool:
        return self.kind in ("sliding", "fixed")

    def friction(self, v: float) -> float:
        """Friction acceleration ``mu(|v|) g`` of the sliding contents, m/s^2."""
        v = abs(v)
        bv = self.beta * v
        sech = 0.0 if bv > 700.0 else 1.0 / math.cosh(bv)
        return (self.mu_s * sech + self.mu_k * (1.0 - sech) + self.gamma * v) * self.g


def _check(p: dict) -> None:
    for k in ("a_p", "T_p", "M_b", "g"):
        if not p[k] > 0.0:
            raise ValueError(f"{k} = {p[k]!r} is out of range; allowed range: 0 < value < inf")
    for k in ("T_b", "xi_b", "m_ec", "Q_d", "D_y", "T_s", "xi_s"):
        if not p.get(k, 0.0) >= 0.0:
            raise ValueError(f"{k} = {p[k]!r} is out of range; allowed range: 0 <= value < inf")
    if p.get("T_s", 0.0) > 0.0 and not 0.0 < p["m_st"] < p["M_b"]:
        raise ValueError(f"m_st = {p['m_st']!r} is out of range with T_s > 0; allowed range: "
                         f"0 < m_st < M_b = {p['M_b']!r}")
    floor = p.get("floor", FLOORS[0])
    if floor not in FLOORS:
        raise ValueError(f"floor = {floor!r} is invalid; allowed: {FLOORS}")


def _building(p: dict) -> _Building:
    M = p["M_b"]
    flexible = p.get("T_s", 0.0) > 0.0
    mst = p["m_st"] if flexible else 0.0
    if p["T_b"] == 0.0:
        kind, kd, cb = "fixed", 0.0, 0.0
    else:
        kd = M * (2.0 * math.pi / p["T_b"]) ** 2
        cb = 2.0 * p["xi_b"] * math.sqrt(kd * M)
        Q_d, D_y = p.get("Q_d", 0.0), p.get("D_y", 0.0)
        kind = "linear" if Q_d == 0.0 else ("bilinear" if D_y > 0.0 else "sliding")
    if flexible:
        ks = mst * (2.0 * math.pi / p["T_s"]) ** 2
        cs = 2.0 * p.get("xi_s", 0.0) * math.sqrt(ks * mst)
    else:
        ks = cs = 0.0
    Q = math.inf if kind == "fixed" else p.get("Q_d", 0.0)
    ke = p["Q_d"] / p["D_y"] if kind == "bilinear" else 0.0
    return _Building(mb=M - mst, mst=mst, m=p["m_ec"], kd=kd, cb=cb, ks=ks, cs=cs, Q=Q, ke=ke, g=p["g"],
                     mu_s=p["mu_s"], mu_k=p["mu_k"], beta=p["beta"], gamma=p["gamma"], kind=kind,
                     flexible=flexible, roof=flexible and p.get("floor", FLOORS[0]) == "roof")


def _motion(B: _Building, ag: float, y, sb: int, si: int):
    """Accelerations (m/s^2), isolator force rate (N/s), floor acceleration and needed force.

    ``sb``: contents stuck (0) or sliding (+-1); ``si``: isolator held/elastic (0) or
    sliding/yielding (+-1).  Returns ``(x_b'', x_s'', u'', f_h', a_F, f_need)`` with ``f_need``
    (N) nan unless a bearing holds the slab.
    """
    held = B.holds and si == 0
    S = B.ks * y[XS] + B.cs * y[XSD]
    if B.kind == "bilinear":
        fh = y[FH]
    elif B.kind == "sliding":
        fh = si * B.Q
    else:
        fh = 0.0
    F = B.kd * y[X] + B.cb * y[XD] + fh
    Ff = B.m * sb * B.friction(y[UD]) if sb else 0.0
    if B.roof:
        a_b = ag if held else (-F + S) / B.mb
        if sb == 0:
            a_s = -S / (B.mst + B.m)
            Ff = -B.m * a_s
        else:
            a_s = (-S + Ff) / B.mst
        a_F = a_s
    else:
        if held:
            a_b = ag
        elif sb == 0:
            a_b = (-F + S) / (B.mb + B.m)
        else:
            a_b = (-F + S + Ff) / B.mb
        if sb == 0:
            Ff = -B.m * a_b
        a_s = -S / B.mst if B.flexible else a_b
        a_F = a_b
    udd = 0.0 if sb == 0 else -a_F - Ff / B.m
    if held:
        xdd = 0.0
        f_need = -B.mb * ag - B.kd * y[X] + S + (0.0 if B.roof else Ff)
    else:
        xdd = a_b - ag
        f_need = math.nan
    xsdd = a_s - a_b if B.flexible else 0.0
    fhd = B.ke * y[XD] if (B.kind == "bilinear" and si == 0) else 0.0
    return xdd, xsdd, udd, fhd, a_F, f_need


def _sgn(a: float) -> int:
    return 1 if a > 0.0 else (-1 if a < 0.0 else 0)


def _modes(B: _Building, ag: float, y, sb: int, si: int, broke_b: int, broke_i: int):
    """Consistent modes ``(sb, si)`` of the contents and a sliding bearing at a phase start."""
    lim_b = B.mu_s * B.g * (1.0 + _SLACK)
    lim_q = B.Q * (1.0 + _SLACK)
    if broke_b:
        cand_b, free_b = (broke_b,), False
    elif sb == 0 or y[UD] == 0.0:
        cand_b, free_b = (0, 1, -1), True
    else:
        cand_b, free_b = (_sgn(y[UD]),), False
    if B.kind != "sliding":
        cand_i, free_i = (si,), False
    elif broke_i:
        cand_i, free_i = (broke_i,), False
    elif si == 0 or y[XD] == 0.0:
        cand_i, free_i = (0, 1, -1), True
    else:
        cand_i, free_i = (_sgn(y[XD]),), False
    order = sorted(((b, i) for b in cand_b for i in cand_i),
                   key=lambda c: (c[0] != 0, B.kind == "sliding" and c[1] != 0))
    for b, i in order:
        xdd, _, udd, _, a_F, f_need = _motion(B, ag, y, b, i)
        if b == 0 and abs(a_F) > lim_b:
            continue
        if b != 0 and free_b and not b * udd > 0.0:
            continue
        if B.kind == "sliding":
            if i == 0 and abs(f_need) > lim_q:
                continue
            if i != 0 and free_i and not i * xdd > 0.0:
                continue
        return b, i
    raise RuntimeError(f"simulate_si: no consistent stick/slip mode at the state {list(y)!r}, a_g = {ag!r}")


def _yield_mode(B: _Building, ag: float, y, sb: int, si: int) -> int:
    """Elastic (0) or yielding (+-1) state of a bilinear bearing at a phase start (no event)."""
    if si == 0:
        s = _sgn(y[FH])
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


def simulate_building_si(p: dict, pulse="ricker", t_end: float | None = None, rtol: float = 1e-12,
                         history: bool = False) -> PeerResult:
    """Stick-slip response of contents in a general building, integrated in SI units.

    Parameters
    ----------
    p : dict
        SI parameters of :func:`isoslide.similarity.physical_parameters`: ``a_p`` (m/s^2), ``T_p``
        (s), ``M_b`` (kg, slab and superstructure), ``T_b`` (s, 0 = fixed base), ``xi_b``, ``m_ec``
        (kg), ``mu_s``, ``mu_k``, ``beta`` (s/m), ``gamma`` (s/m), ``g`` (m/s^2), ``Q_d`` (N),
        ``D_y`` (m), ``m_st`` (kg), ``T_s`` (s, 0 = rigid), ``xi_s`` and ``floor``
        (``"base"``/``"roof"``, default ``"base"``).
    pulse : str or Pulse
        Ground-acceleration shape, ``a_g(t) = a_p p(t / T_p)``.
    t_end : float, optional
        End time, s (default: pulse end + 20 times the longest of ``T_p``, ``T_b``, ``T_s``).
    rtol : float
        Relative tolerance of the integrator.
    history : bool
        Also return the :class:`~isoslide.history.History` (dimensionless with ``a_p``, ``T_p``,
        ``M_b``).

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
    if B.flexible:
        periods.append(p["T_s"])
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
    atol = np.array([L, V, L, V, L, V, Fs]) * 1e-12
    lim_b = B.mu_s * B.g * (1.0 + _SLACK)
    lim_q = B.Q * (1.0 + _SLACK)

    t, y = t0, np.zeros(7)
    sb = si = 0
    broke_b = broke_i = 0
    after_event = False
    u_max, t_peak, n_events, nfev, repeats = 0.0, t0, 0, 0, 0
    hist = [] if history else None
    while t < t_end:
        if n_events > 200_000:
            raise RuntimeError("simulate_si: too many transitions (chattering?)")
        ag0 = ag_at(t)
        if B.kind == "bilinear" and not after_event:
            new = _yield_mode(B, ag0, y, sb, si)
            if new != si:
                n_events += 1
                si = new
                if si:
                    y[FH] = si * B.Q
        nb, ni = _modes(B, ag0, y, sb, si, broke_b, broke_i)
        if not after_event:
            n_events += (nb != sb) + (B.kind == "sliding" and ni != si)
        sb, si = nb, ni
        broke_b = broke_i = 0
        after_event = False
        if sb == 0:
            y[UD] = 0.0
        if B.holds and si == 0:
            y[XD] = 0.0

        t_next = next((b for b in bounds if b > t), t_end)
        t_last = math.nextafter(t_next, -math.inf)
        t_start = t

        def ag_in(tt, t_start=t_start, t_last=t_last):
            # the segment's own branch of a piecewise pulse, also at its ends
            return ag_at(min(max(tt, t_start), t_last))

        def rhs(tt, yy, sb=sb, si=si, ag_in=ag_in):
            xdd, xsdd, udd, fhd, _, _ = _motion(B, ag_in(tt), yy, sb, si)
            return (yy[XD], xdd, yy[XSD], xsdd, yy[UD], udd, fhd)

        xdd0, _, udd0 = _motion(B, ag_in(t), y, sb, si)[:3]
        events, kinds = [], []
        if sb == 0:
            for s in (1.0, -1.0):
                events.append(_limit(lambda tt, yy, s=s, sb=sb, si=si, ag_in=ag_in:
                                     lim_b - s * _motion(B, ag_in(tt), yy, sb, si)[4]))
                kinds.append("contents_break")
        else:
            events.append(_stop(sb, UD, t, y[UD], udd0))
            kinds.append("contents_stop")
        if B.kind == "sliding":
            if si == 0:
                for s in (1.0, -1.0):
                    events.append(_limit(lambda tt, yy, s=s, sb=sb, ag_in=ag_in:
                                         lim_q - s * _motion(B, ag_in(tt), yy, sb, 0)[5]))
                    kinds.append("bearing_break")
            else:
                events.append(_stop(si, XD, t, y[XD], xdd0))
                kinds.append("bearing_stop")
        elif B.kind == "bilinear":
            if si == 0:
                for s in (1.0, -1.0):
                    events.append(_limit(lambda tt, yy, s=s: B.Q - s * yy[FH]))
                    kinds.append("yield")
            else:
                events.append(_stop(si, XD, t, y[XD], xdd0))
                kinds.append("unload")

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
            broke_b = -_sgn(_motion(B, ag, y, sb, si)[4])
        elif kind == "contents_stop":
            y[UD] = 0.0
            if abs(y[U]) > u_max:
                u_max, t_peak = abs(y[U]), t
        elif kind == "bearing_break":
            broke_i = _sgn(_motion(B, ag, y, sb, si)[5])
        elif kind == "bearing_stop":
            y[XD] = 0.0
        elif kind == "yield":
            si = _sgn(y[FH])
            y[FH] = si * B.Q
        elif kind == "unload":
            si = 0
            y[FH] = math.copysign(B.Q, y[FH])
    if abs(y[U]) > u_max:
        u_max, t_peak = abs(y[U]), t
    hh = None
    if hist is not None:
        tt = np.concatenate([a for a, _, _ in hist])
        yy = np.concatenate([b for _, b, _ in hist], axis=1)
        ph = np.concatenate([np.full(a.shape, f, dtype=np.int8) for a, _, f in hist])
        hh = History(tau=tt / T_p, x=yy[X] / L, xd=yy[XD] / V, u=yy[U] / L, ud=yy[UD] / V, phase=ph,
                     xs=yy[XS] / L if B.flexible else None, xsd=yy[XSD] / V if B.flexible else None,
                     fh=yy[FH] / Fs if B.kind == "bilinear" else None)
    return PeerResult(method="si", pi1=u_max / L, pi1_residual=float(y[U]) / L, tau_peak=t_peak / T_p,
                      settled=False, n_events=n_events, tau_end=t / T_p, nfev=nfev, integrator="DOP853",
                      history=hh)
