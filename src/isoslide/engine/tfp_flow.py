r"""A triple friction pendulum whose friction rises with speed, integrated as the flow of its surfaces.

Each sliding surface ``i`` of the bearing (:mod:`isoslide.model.tfp`; bottom to top: surface 1 of
radius ``L2``, the inner surfaces 2 and 3 of radius ``L1``, surface 4 of radius ``L3``) follows the
law of Constantinou, Mokha and Reinhorn (1990), ``mu_i(v) = mu_fast - (mu_fast - mu_slow) exp(-a |v|)``
of its own sliding speed ``v = u_i'``.  Per unit normal force (``W nz``, :func:`~isoslide.engine.building_kernel.normal`),
with the bearing's force ``f`` and the slope ``s_i`` of the surface where the load passes
(:func:`~isoslide.engine.building_kernel._tfp_slopes`), the surface's reaction is ``q_i = f - s_i``,
and it

* sticks (``u_i' = 0``) while ``|q_i| <= Q_slow,i`` (true stick at its breakaway level);
* slides beyond it at the speed that makes its friction equal to the reaction,
  ``u_i' = sign(q_i) V_i(|q_i|)``, ``V_i(q) = -ln((Q_fast,i - q)/(Q_fast,i - Q_slow,i))/a_i``;
* on its restrainer (``|u_i| = d_i``) does not move further out.

So each surface's speed is a single-valued, non-decreasing function of the bearing's force, zero in
its stick band and unbounded as ``|q_i|`` nears ``Q_fast,i``: the surfaces need no choice of a sliding
set.  While the slab moves, ``f`` is the unique root of ``sum_i u_i'(f) = x'`` (:func:`force`; in a
slab at rest whose bands overlap, ``f`` is the edge of the common band ``[f_lo, f_hi]`` in the
direction it starts; where the bands do not overlap the root is unique at ``x' = 0`` too, and the slab
turns without stopping).  The integrated state is the building's (the layout of
:mod:`isoslide.engine.building_kernel`, whose right-hand side :func:`~isoslide.engine.building_kernel.deriv`
gives every floor's and the contents' motion under the bearing force ``nz f``) with the four surface
displacements ``u_i`` appended.

Two surfaces sliding at once share the slab's speed through their laws, and that split relaxes at a
rate near ``W/(L D)`` with ``D = a (Q_fast - Q_slow) exp(-a |v|)``: the system is stiff once the
surfaces slide fast, and it is integrated by the implicit Radau IIA method of order 5
(:func:`scipy.integrate.solve_ivp`).  Events end each integration: the slab stopping (``x' = 0``),
a surface reaching its restrainer (it is set on it), a surface's reaction crossing its breakaway level
(a kink of its law, where the integration restarts), the held slab breaking away (its holding force
leaving the band), the contents breaking away or stopping, and the excitation's breakpoints.  At a
stop the interfaces at rest choose their modes together, as the compiled kernel's
:func:`~isoslide.engine.building_kernel._select_modes`, with the band of the surfaces' present
displacements (:func:`~isoslide.engine.building_kernel.tfp_band`).

Settlement.  A surface whose reaction lies between its slow and fast levels creeps at the law's small
speed, which can decay towards its stick band without reaching it in finite time, so a slab that
creeps after the excitation is never held.  A run is settled once the slab is held and the contents
stuck after the excitation and the kernel's bound (:func:`~isoslide.engine.building_kernel._settled`)
proves that nothing can move again; a run whose slab still creeps at the horizon ends there, unsettled
(its contents' peak is reported with ``settled = False``).  An inner surface reaching its restrainer
is the bearing's displacement capacity, which the model of rigid restrainers does not pass (the run
stops with the ``capacity`` flag).

Units: time ``T_p``, lengths ``a_p T_p^2``, forces ``M_b a_p`` (per unit normal-force factor), speeds
``a_p T_p``; the rates ``a`` in ``1/(a_p T_p)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numba import njit
from scipy.integrate import solve_ivp

from .. import jit_cache
from . import building_kernel as bk

RTOL_FACTOR = 1e-2
"""Radau's relative tolerance over the solve's ``rtol`` (its error estimate filters the stiff split of
the surfaces' speeds, which a looser tolerance can step over as the surfaces slow down)."""
RTOL_FLOOR = 1e-12
"""Tightest relative tolerance given to Radau."""
ATOL_FACTOR = 1e-3
"""Radau's absolute tolerance over its relative one (lengths and speeds are O(0.01..1))."""
H_MAX = 0.02
"""Longest integration step (units of T_p): the events are located on each step."""
H_SETTLE = 1.0
"""Longest integration after the excitation (units of T_p): how often settlement is tested."""
MAX_PHASES = 200_000
"""Most integrations one run may start (events included)."""
JAC_STEP = 1e-8
"""Relative step of the Jacobian's forward differences (:func:`_jacobian`)."""
GAP_FLOOR = 1e-30
"""The law's speed is continued linearly where the friction's gap to its fast level falls below this
fraction of ``Q_fast - Q_slow`` (speeds of some ``69/a`` and more, which a double cannot resolve from
the force anyway), so that an implicit integrator's trial states keep finite rates."""
_INNER = (1, 2)
"""The inner surfaces: one on its restrainer is the bearing's displacement capacity."""


@dataclass(frozen=True)
class Surfaces:
    """The four sliding surfaces' laws, bottom to top, per unit normal-force factor.

    Attributes
    ----------
    stiffness : ndarray, shape (4,)
        ``k_i = M_b g / L_i`` (units ``M_b/T_p^2``).
    fast, slow : ndarray, shape (4,)
        ``Q_fast,i = mu_fast,i M_b g`` and ``Q_slow,i = mu_slow,i M_b g`` (units ``M_b a_p``),
        ``Q_slow < Q_fast``.
    rate : ndarray, shape (4,)
        ``a_i a_p T_p`` (> 0).
    limit : ndarray, shape (4,)
        ``d_i`` (units ``a_p T_p^2``).
    """

    stiffness: np.ndarray
    fast: np.ndarray
    slow: np.ndarray
    rate: np.ndarray
    limit: np.ndarray

    @classmethod
    def of(cls, P: np.ndarray, slow: np.ndarray, rate: np.ndarray) -> Surfaces:
        """The surfaces of the kernel parameters ``P`` (their fast strengths) with the slow strengths and rates."""
        o = int(P[bk.P_TFP])
        fast = np.array(P[o + 4:o + 8], dtype=float)
        slow = np.asarray(slow, dtype=float)
        rate = np.asarray(rate, dtype=float)
        if slow.shape != (4,) or rate.shape != (4,) or not (np.all(slow < fast) and np.all(slow >= 0.0)
                                                              and np.all(rate > 0.0)):
            raise ValueError(f"slow = {slow!r}, rate = {rate!r}; allowed: four slow strengths 0 <= slow < fast = "
                             f"{fast!r} and four rates > 0")
        return cls(np.array(P[o:o + 4], dtype=float), fast, slow, rate, np.array(P[o + 8:o + 12], dtype=float))

    @cached_property
    def table(self) -> np.ndarray:
        """The five rows ``stiffness, fast, slow, rate, limit`` as one array (the compiled functions read it)."""
        return np.ascontiguousarray(np.vstack((self.stiffness, self.fast, self.slow, self.rate, self.limit)))


def slopes(s: Surfaces, u) -> np.ndarray:
    """``f - q_i`` of the four surfaces at the displacements ``u`` (the load's slope on each)."""
    sl = np.empty(4)
    _slopes(s.table, _writable(u), sl)
    return sl


def on_stops(s: Surfaces, u) -> np.ndarray:
    """``+1``/``-1`` for each surface resting on its restrainer on that side, 0 for one off them."""
    return np.where(np.abs(u) >= s.limit * (1.0 - 1e-12), np.sign(u), 0.0)


def speeds(s: Surfaces, f: float, u, stops) -> np.ndarray:
    """Each surface's sliding speed ``u_i'`` under the bearing force ``f`` (module docstring).

    ``stops`` (:func:`on_stops`) marks the surfaces on their restrainers, which do not move further
    out; the others follow their law wherever they are (an integrator's trial state may pass a
    restrainer, whose event then ends the integration).
    """
    v = np.zeros(4)
    _speeds(s.table, _writable(stops), float(f), _writable(u), v)
    return v


def band(s: Surfaces, u, stops) -> tuple:
    """``(f_lo, f_hi)``: the force within which every surface sticks at ``u`` (``-inf``/``inf`` where none can move)."""
    return _band(s.table, _writable(stops), _writable(u))


def force(s: Surfaces, u, xd: float, sig: float, stops) -> float:
    """The bearing force ``f`` at the displacements ``u`` and the slab's speed ``x'`` (module docstring).

    ``sig`` is the direction in which the slab moves: with overlapping bands, ``f`` is the edge of the
    common band in ``sig`` for a slab at rest (``x' = 0``) starting to move, and for the integrator's
    round-off excursions backwards before it stops.  NaN for a state that is not finite (a trial
    of the implicit integrator).
    """
    return _force(s.table, _writable(stops), _writable(u), float(xd), float(sig))


def _writable(a) -> np.ndarray:
    """``a`` as a writable, contiguous float array: the one signature the compiled functions are cached for."""
    a = np.ascontiguousarray(a, dtype=float)
    return a if a.flags.writeable else a.copy()


@njit(cache=True)
def _slopes(T, u, sl):
    k = T[0]
    sl[0] = k[0] * u[0]
    sl[3] = k[3] * u[3]
    sl[1] = sl[0] + k[1] * u[1]
    sl[2] = sl[3] + k[2] * u[2]


@njit(cache=True)
def _law_speed(gap, span, rate):
    """``-ln(gap/span)/rate``, continued linearly below ``gap = GAP_FLOOR span`` (an integrator's trial states)."""
    g0 = GAP_FLOOR * span
    if gap >= g0:
        return -math.log(gap / span) / rate
    return (-math.log(GAP_FLOOR) + (g0 - gap) / g0) / rate


@njit(cache=True)
def _flow(T, stops, f, sl, v):
    """Speeds ``v`` of the surfaces of slopes ``sl`` under ``f``; returns their sum and its rate in ``f``."""
    total = 0.0
    rate = 0.0
    for i in range(4):
        q = f - sl[i]
        fast, slow, a = T[1, i], T[2, i], T[3, i]
        v[i] = 0.0
        if q > slow and stops[i] <= 0.0:
            gap = fast - q
            v[i] = _law_speed(gap, fast - slow, a)
            rate += 1.0 / (a * max(gap, GAP_FLOOR * (fast - slow)))
        elif q < -slow and stops[i] >= 0.0:
            gap = fast + q
            v[i] = -_law_speed(gap, fast - slow, a)
            rate += 1.0 / (a * max(gap, GAP_FLOOR * (fast - slow)))
        total += v[i]
    return total, rate


@njit(cache=True)
def _speeds(T, stops, f, u, v):
    sl = np.empty(4)
    _slopes(T, u, sl)
    _flow(T, stops, f, sl, v)


@njit(cache=True)
def _band(T, stops, u):
    sl = np.empty(4)
    _slopes(T, u, sl)
    lo = -math.inf
    hi = math.inf
    for i in range(4):
        if stops[i] <= 0.0:
            hi = min(hi, sl[i] + T[2, i])
        if stops[i] >= 0.0:
            lo = max(lo, sl[i] - T[2, i])
    return lo, hi


@njit(cache=True)
def _reach(T, sl, stops, sig):
    """The force at which the first surface free to move in ``sig`` would slide infinitely fast."""
    best = math.inf
    for i in range(4):
        if sig * stops[i] <= 0.0:
            best = min(best, sig * sl[i] + T[1, i])
    return sig * best


@njit(cache=True)
def _force(T, stops, u, xd, sig):
    """:func:`force`: the root of ``sum_i v_i(f) = x'`` by Newton's rule kept within its bracket."""
    if not math.isfinite(xd):
        return math.nan
    for i in range(4):
        if not math.isfinite(u[i]):
            return math.nan
    sl = np.empty(4)
    v = np.empty(4)
    _slopes(T, u, sl)
    lo, hi = _band(T, stops, u)
    if lo <= hi:
        if xd * sig <= 0.0:
            # at rest, or a round-off excursion backwards before the stop event: the edge
            return hi if sig > 0.0 else lo
        if xd > 0.0:
            a, b = hi, _reach(T, sl, stops, 1.0)
        else:
            a, b = _reach(T, sl, stops, -1.0), lo
    else:
        a, b = _reach(T, sl, stops, -1.0), _reach(T, sl, stops, 1.0)
    span = 1.0
    for i in range(4):
        span = max(span, abs(sl[i]) + T[1, i] + 1.0)
    a = max(a, -span)
    b = min(b, span)
    ga = _flow(T, stops, a, sl, v)[0] - xd
    if ga >= 0.0:
        return a
    gb = _flow(T, stops, b, sl, v)[0] - xd
    if gb <= 0.0:
        return b
    f = 0.5 * (a + b)
    for _ in range(200):
        g, dg = _flow(T, stops, f, sl, v)
        g -= xd
        if g == 0.0:
            return f
        if g > 0.0:
            b = f
        else:
            a = f
        if b - a <= 4.0 * np.spacing(max(abs(a), abs(b))):
            return f
        step = f - g / dg if dg > 0.0 else 0.5 * (a + b)
        f = step if a < step < b else 0.5 * (a + b)
    return f


def phase_end(t0: float, breakpoints, tau_end: float) -> float:
    """End of the integration starting at ``t0``: the next of the sorted ``breakpoints`` after it.

    After the excitation's end ``tau_end``, at most :data:`H_SETTLE` on (how often settlement is tested).
    """
    t1 = next(b for b in breakpoints if b > t0)
    return min(t1, t0 + H_SETTLE) if t0 >= tau_end else t1


def stage(s: Surfaces, u, v) -> int:
    """Fenz and Constantinou's regime by the outer surfaces 1 and 4: 0 none sliding, 1..5 I..V.

    Each outer surface slides (``v != 0``), rests on its restrainer, or is free: free and free (or one
    on its restrainer and the other free) is I, sliding and free II, both sliding III, on its
    restrainer and sliding IV, both on their restrainers V.
    """
    if not np.any(v != 0.0):
        return 0

    stops = on_stops(s, u)

    def status(i):
        if v[i] != 0.0:
            return "slide"
        return "stop" if stops[i] != 0.0 else "free"

    pair = {status(0), status(3)}
    if pair == {"stop"}:
        return 5
    if pair == {"slide"}:
        return 3
    if pair == {"slide", "stop"}:
        return 4
    if "slide" in pair:
        return 2
    return 1


@dataclass
class _Run:
    """The mutable state of a run between phases."""

    tau: float
    z: np.ndarray
    bm: float = 0.0
    im: float = 0.0
    umax: float = 0.0
    tpeak: float = 0.0
    upeak: float = 0.0
    xmax: float = 0.0
    vmax: float = 0.0
    steps: int = 0
    events: int = 0
    iso_events: int = 0
    slipped: bool = False
    moved: bool = False
    stage_max: int = 0
    capacity: bool = False
    settled: bool = False
    modes: int = 1
    stops: np.ndarray = None


def run(P, code, params, breakpoints, tau_start, tau_end, tau_stop, surfaces: Surfaces, rtol, settle, modal,
        hist_cap=0):
    """Integrate one scene on a triple friction pendulum whose friction rises with speed, from rest.

    Parameters
    ----------
    P : ndarray
        The kernel's parameters (:func:`isoslide.engine.building.parameters`); not modified.
    code, params : int, ndarray
        The main pulse (:mod:`isoslide.pulses`).
    breakpoints : ndarray
        The excitation's breakpoints (integrations end there).
    tau_start, tau_end, tau_stop : float
        Start, end of the excitation and horizon (units of T_p).
    surfaces : Surfaces
        The surfaces' laws.
    rtol : float
        Target relative error of the contents' peak; Radau runs at :data:`RTOL_FACTOR` of it.
    settle : bool
        Stop at settlement.
    modal : tuple
        The free phase's modal data ``(Wm, Cm, Vm, Lm, Wh, Ch, Vh, Lh)`` (:func:`isoslide.engine.building.modal_data`).
    hist_cap : int
        Most history rows (0: none).

    Returns
    -------
    tuple
        ``(ints, floats, hist)`` in :func:`isoslide.engine.building_kernel.run`'s layout
        (:data:`~isoslide.engine.building_kernel.INT_RESULTS`, ``FLOAT_RESULTS``; history rows
        ``[tau, y..., bm, im, stage]`` with ``y[-1]`` the bearing force per unit normal force).
    """
    Pc = np.array(P, dtype=float)
    ny = bk.state_size(int(P[bk.P_N]))
    Wm, Cm, _, _, Wh, Ch, _, _ = modal
    s = surfaces
    r_tol = max(RTOL_FLOOR, RTOL_FACTOR * rtol)
    a_tol = ATOL_FACTOR * r_tol
    code = int(code)
    params = np.array(params, dtype=float)
    bps = sorted({float(b) for b in breakpoints if tau_start < b < tau_stop} | {float(tau_end), float(tau_stop)})
    st = _Run(tau=float(tau_start), z=np.zeros(ny + 3), tpeak=float(tau_start))
    y = np.zeros(ny)
    out = np.zeros(ny)
    work = np.zeros(ny)
    hist = []

    def full(z, f):
        y[:ny - 1] = z[:ny - 1]
        y[ny - 1] = f
        return y

    def bearing_force(z, im):
        if im == 0.0:
            return 0.0
        return force(s, z[ny - 1:], z[bk.Y_XD], im, st.stops)

    def select(free_b, free_i, forced_i=0.0):
        """The modes of the interfaces at rest at the run's present point."""
        z = st.z
        u = z[ny - 1:]
        st.stops = on_stops(s, u)
        Pc[bk.P_FLO], Pc[bk.P_FHI] = band(s, u, st.stops)
        if free_i and Pc[bk.P_FLO] > Pc[bk.P_FHI]:
            # the bands do not overlap: the slab turns without stopping
            f = force(s, u, 0.0, 1.0, st.stops)
            bk.deriv(st.bm, 1.0, st.tau, full(z, f), Pc, code, params, out)
            st.im = 1.0 if out[bk.Y_XD] > 0.0 else -1.0
            free_i = False
        if forced_i != 0.0:
            st.im = forced_i
            free_i = False
        f = bearing_force(z, st.im) if not free_i else 0.0
        b, i = bk._select_modes(st.bm, st.im, free_b, free_i, st.tau, full(z, f), Pc, code, params)
        st.bm, st.im = float(b), float(i)

    free_b = True
    free_i = True
    forced_i = 0.0
    sides = {}
    for _ in range(MAX_PHASES):
        if st.tau >= tau_stop:
            break
        if free_b or free_i or forced_i != 0.0:
            select(free_b, free_i, forced_i)
        free_b = free_i = False
        forced_i = 0.0
        st.modes |= 1 << bk.block_mode(st.bm)
        bm, im = st.bm, st.im
        st.slipped |= bm != 0.0
        st.moved |= im != 0.0
        u0 = st.z[ny - 1:].copy()
        st.stops = on_stops(s, u0)
        Pc[bk.P_FLO], Pc[bk.P_FHI] = band(s, u0, st.stops)
        if st.tau >= tau_end and bm == 0.0 and im == 0.0:
            if bk._settled(0.0, 0.0, full(st.z, 0.0), Pc, Wm, Cm, Wh, Ch):
                st.settled = True
                if settle:
                    break
        t0 = st.tau
        t1 = phase_end(t0, bps, tau_end)
        evs, kinds = _events(s, st, Pc, code, params, ny, full, bearing_force, y, work, u0, sides)
        sides = {}

        def rhs(t, z, bm=bm, im=im):
            f = bearing_force(z, im)
            bk.deriv(bm, im, t, full(z, f), Pc, code, params, out)
            dz = np.empty(ny + 3)
            dz[:ny - 1] = out[:ny - 1]
            dz[ny - 1:] = speeds(s, f, z[ny - 1:], st.stops) if im != 0.0 else 0.0
            return dz

        if im != 0.0:
            sol = solve_ivp(rhs, (t0, t1), st.z, method="Radau", events=evs, rtol=r_tol, atol=a_tol, max_step=H_MAX,
                            jac=lambda t, z, rhs=rhs: _jacobian(rhs, t, z))
        else:
            sol = solve_ivp(rhs, (t0, t1), st.z, method="DOP853", events=evs, rtol=r_tol, atol=a_tol, max_step=H_MAX)
        if sol.status < 0:
            raise RuntimeError(f"the integration failed at tau = {sol.t[-1]!r}: {sol.message}")
        st.steps += max(len(sol.t) - 1, 1)
        _track(st, sol, s, ny, im, hist, hist_cap, bearing_force, full, bm)
        st.tau = float(sol.t[-1])
        st.z = np.array(sol.y[:, -1])
        np.clip(st.z[ny - 1:], -s.limit, s.limit, out=st.z[ny - 1:])
        if sol.status != 1:
            free_b = free_i = False
            continue
        k = next(j for j, te in enumerate(sol.t_events) if len(te))
        kind = kinds[k]
        if kind[0] == "stop":
            st.z[bk.Y_XD] = 0.0
            st.xmax = max(st.xmax, abs(st.z[bk.Y_X]))
            st.iso_events += 1
            free_i = True
            free_b = st.bm == 0.0
        elif kind[0] == "breakaway":
            st.iso_events += 1
            forced_i = kind[1]
            free_b = st.bm == 0.0
        elif kind[0] == "kink":
            sides[(kind[1], kind[2])] = -kind[3]
        elif kind[0] == "restrainer":
            i = kind[1]
            st.z[ny - 1 + i] = kind[2] * s.limit[i]
            if i in _INNER:
                st.capacity = True
                break
        elif kind[0] == "slip":
            st.events += 1
            st.bm = -kind[1]
        elif kind[0] == "stick":
            st.events += 1
            st.z[ny - 2] = 0.0
            u = st.z[ny - 3]
            if abs(u) > st.umax:
                st.umax, st.tpeak, st.upeak = abs(u), st.tau, u
            free_b = True
            free_i = st.im == 0.0
    else:
        raise RuntimeError(f"more than {MAX_PHASES} phases in one run; the last at tau = {st.tau!r}")
    u = st.z[ny - 3]
    if not st.settled and abs(u) > st.umax:
        st.umax, st.tpeak, st.upeak = abs(u), st.tau, u
    st.xmax = max(st.xmax, abs(st.z[bk.Y_X]))
    ints = np.zeros(bk.N_R, dtype=np.int64)
    ints[bk.R_STEPS] = st.steps
    ints[bk.R_EVENTS] = st.events
    ints[bk.R_SETTLED] = st.settled
    ints[bk.R_SLIPPED] = st.slipped
    ints[bk.R_HIST] = len(hist)
    ints[bk.R_ISO_EVENTS] = st.iso_events
    ints[bk.R_ISO_MOVED] = st.moved
    ints[bk.R_STAGE_MAX] = st.stage_max
    ints[bk.R_CAPACITY] = st.capacity
    ints[bk.R_MODES] = st.modes
    floats = np.zeros(bk.N_F)
    floats[bk.F_UMAX] = st.umax
    floats[bk.F_TPEAK] = st.tpeak
    floats[bk.F_URES] = u
    floats[bk.F_TEND] = st.tau
    floats[bk.F_XMAX] = st.xmax
    floats[bk.F_VMAX] = st.vmax
    floats[bk.F_UPEAK] = st.upeak
    floats[bk.F_TCONTACT] = math.nan
    width = bk.history_width(int(P[bk.P_N]))
    return ints, floats, np.array(hist).reshape(-1, width) if hist else np.zeros((0, width))


def _track(st: _Run, sol, s: Surfaces, ny: int, im: float, hist: list, hist_cap: int, bearing_force, full, bm):
    """Peaks, the stage and the history over the integrator's steps of one phase."""
    for j in range(sol.y.shape[1]):
        z = sol.y[:, j]
        st.vmax = max(st.vmax, abs(z[ny - 2]))
        if im != 0.0:
            st.xmax = max(st.xmax, abs(z[bk.Y_X]))
            f = bearing_force(z, im)
            g = stage(s, z[ny - 1:], speeds(s, f, z[ny - 1:], st.stops))
            st.stage_max = max(st.stage_max, g)
        else:
            f, g = 0.0, 0
        if len(hist) < hist_cap:
            hist.append(np.concatenate(([sol.t[j]], full(z, f), [bm, im, g])))


def _events(s: Surfaces, st: _Run, Pc, code, params, ny, full, bearing_force, y, work, u0, sides):
    """The event functions of the phase starting at the run's present point, and what each means.

    ``sides`` gives the side (+1 sliding, -1 stuck) a surface at its breakaway level is leaving for,
    where the last event knows it: ``{(i, sg): side}``.
    """
    evs, kinds = [], []
    t0, bm, im, z0 = st.tau, st.bm, st.im, st.z

    def add(fun, direction, kind):
        fun.terminal = True
        fun.direction = direction
        evs.append(fun)
        kinds.append(kind)

    if im != 0.0:
        add(lambda t, z: im * z[bk.Y_XD] if t > t0 else 1.0, -1, ("stop",))
        for i in range(4):
            for sg in (1.0, -1.0):
                if st.stops[i] != sg:     # not resting on its restrainer on that side
                    add(lambda t, z, i=i, sg=sg: s.limit[i] - sg * z[ny - 1 + i], -1, ("restrainer", i, sg))
        # a surface's reaction crossing its breakaway level: a kink of its law
        f0 = bearing_force(z0, im)
        sl0 = slopes(s, u0)
        for i in range(4):
            for sg in (1.0, -1.0):
                side = sg * (f0 - sl0[i]) - s.slow[i]
                if abs(side) <= 1e-12 * max(s.slow[i], 1e-300):
                    # at its level: the side it is leaving for
                    if (i, sg) in sides:
                        side = sides[(i, sg)]
                    elif z0[bk.Y_XD] == 0.0:
                        side = 1.0 if sg == im else -1.0
                    else:
                        side = _probe(s, i, sg, bm, im, t0, z0, f0, Pc, code, params, full, work, bearing_force, ny)
                    if side == 0.0:
                        continue
                sign = 1.0 if side > 0.0 else -1.0

                def kink(t, z, i=i, sg=sg, sign=sign):
                    f = bearing_force(z, im)
                    return sign * (sg * (f - slopes(s, z[ny - 1:])[i]) - s.slow[i])
                add(kink, -1, ("kink", i, sg, sign))
    else:
        for sg in (1.0, -1.0):
            def need(t, z, sg=sg):
                return bk._event(bk.EV_BEAR, sg, bm, 0.0, t, full(z, 0.0), Pc, code, params, work)[0]
            add(need, 1, ("breakaway", sg))
    if bm == 0.0:
        for sg in (1.0, -1.0):
            def demand(t, z, sg=sg):
                return bk._event(bk.EV_BLOCK, sg, 0.0, im, t, full(z, bearing_force(z, im)), Pc, code, params, work)[0]
            add(demand, 1, ("slip", sg))
    else:
        add(lambda t, z: bm * z[ny - 2] if t > t0 else 1.0, -1, ("stick",))
    return evs, kinds


def _jacobian(rhs, t, z, pairs=()) -> np.ndarray:
    """Forward-difference Jacobian of ``rhs`` at ``(t, z)``, steps ``JAC_STEP max(|z_j|, 1e-6)``.

    SciPy's adaptive differences can overflow on the law's steep rise near the fast level; fixed
    relative steps keep every entry finite (the implicit integrator's Newton iteration needs no more).
    ``pairs``: the indices ``(i, j)`` of sliding interfaces' velocities in the plane (the slab's, a
    block's, :mod:`isoslide.engine.tfp_plane`), whose friction turns with the velocity's direction.
    Their columns step by ``JAC_STEP |v|`` away from zero in each component (zero columns at rest), so
    that no step turns the direction far (a step of the other columns' size near a small velocity would
    reverse it, a spurious stiffness that pins the slide).
    """
    f0 = rhs(t, z)
    J = np.zeros((z.size, z.size))
    moving = {}
    for i, j in pairs:
        moving[i] = moving[j] = math.hypot(z[i], z[j])
    for j in range(z.size):
        if j in moving:
            if moving[j] == 0.0:
                continue
            h = JAC_STEP * moving[j] * (1.0 if z[j] >= 0.0 else -1.0)
        else:
            h = JAC_STEP * max(abs(z[j]), 1e-6)
        zj = z.copy()
        zj[j] += h
        J[:, j] = (rhs(t, zj) - f0) / h
    return J


def _probe(s, i, sg, bm, im, t, z, f, Pc, code, params, full, work, bearing_force, ny):
    """Which side of its level surface ``i``'s reaction (direction ``sg``) moves to just after ``t``."""
    dt = 1e-7
    zt = z.copy()
    zt[ny - 1:] += dt * speeds(s, f, z[ny - 1:], on_stops(s, z[ny - 1:]))
    zt[bk.Y_XD] += dt * _slab_rate(bm, im, t, z, f, Pc, code, params, full, work)
    ft = bearing_force(zt, im)
    return sg * ((ft - slopes(s, zt[ny - 1:])[i]) - (f - slopes(s, z[ny - 1:])[i]))


def _slab_rate(bm, im, t, z, f, Pc, code, params, full, out):
    """The slab's acceleration relative to the ground ``x''`` under the bearing force ``f``."""
    bk.deriv(bm, im, t, full(z, f), Pc, code, params, out)
    return out[bk.Y_XD]


# numba reads the compiled code shipped with the package (isoslide.jit_cache) before compiling any of it
jit_cache.seed(_force)
