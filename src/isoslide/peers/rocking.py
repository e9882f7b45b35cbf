r"""Independent event-driven peer of a rigid block rocking on a moving floor (SciPy ``solve_ivp``).

The physics, the sign convention and the closed forms are those of :mod:`isoslide.model.rocking`
(Housner's block: rocking about one bottom corner at a time, impacts at ``theta = 0`` with the
restitution ``e``, overturning at ``|theta| = pi/2``).  This module integrates it on a prescribed
floor motion given as callables, in SI units, from rest (or from a given tilt) up to a horizon.
It shares no code with the compiled engine and is written to be read line by line.

Scope: rocking only
-------------------
Friction is assumed to hold the pivot.  With a finite static coefficient ``mu_s`` the peer checks
it: when the horizontal contact force needed exceeds ``mu_s`` times the vertical one (at rest, or
while rocking with ``|theta| < alpha``) it raises :class:`RockingContactError` naming the time; the
same for flight, a vertical contact force that would become negative.  Sliding and slide-rock
are modelled by :func:`isoslide.peers.slide_rock.solve_block`, which reduces to this peer when
friction holds; the block leaving the floor is outside both.  The impacts
themselves (Housner's instantaneous, non-bouncing, non-sliding impact) are not checked.  Past the
unstable equilibrium (``|theta| > alpha``) the contact is assumed to hold without checks: a block
toppling freely loses its vertical contact force near ``cos(alpha - |theta|) = 1/3`` whatever
``mu_s``, and the peer follows it to ``pi/2`` as the rigid-pivot model does.

Integration
-----------
On the current corner ``s = sgn(theta)`` the state is ``(psi, psi')`` with ``psi = s theta >= 0``;
the floor enters only through ``s A_F``, so a mirrored floor (``A_F -> -A_F``) gives the bit-for-bit
mirrored response.  Each excursion away from the floor is integrated in two segments, up to its
apex (event ``psi' = 0``, or overturn ``psi = pi/2``) and back down (events ``psi = 0``, an impact,
or ``psi' = 0``, the block turning up again before reaching the floor): a segment that starts on a
zero of one of its terminal events leaves it in the direction that event ignores, and no small
excursion can hide inside one step (the apex splits it).  Segments also end
at the floor's breakpoints (where ``A_F`` or ``a_v`` jump), at which the floor is evaluated from the
left inside each segment.  At rest the integration only scans time for the uplift condition
``(1 + a_v/g) sin(alpha) + s (A_F/g) cos(alpha) < 0`` (uplift onto corner ``s``, i.e. ``-s A_F > (g +
a_v) tan(alpha)``), the friction limit ``|A_F| > mu_s (g + a_v)`` and flight ``g + a_v < 0``; the
events are roots of functions of time alone, located by ``solve_ivp``'s Brent iteration to a few
ulp.  The onset is then moved forward where needed (by doubling steps from one ulp, at most
``2^24`` ulp; in practice none or one) so that ``psi''`` is strictly positive when rocking starts.

End of the impact cascade (return to rest)
------------------------------------------
Without a rule the impacts of a dying-out rocking motion accumulate in finite time (Zeno): the
excursions after an impact of outgoing speed ``w`` last ``~ 2 w / (p^2 sin(alpha))`` and ``w``
shrinks by ``e`` per impact.  The peer counts impacts (``max_impacts`` raises) and declares the
block at rest at an impact when it can prove that the block will never again tilt beyond
``theta_eps`` (default ``alpha / 1000``) and that the cascade ends within a known time:

*Quiet floor* (the impact at ``t_i >= t_quiet``, after which ``A_F = a_v = 0``): the energy per
unit ``m g R``, ``E = psi'^2 / (2 p^2) + cos(alpha - psi) - cos(alpha)``, is conserved between
impacts and multiplied by ``e^2`` at each, so it never exceeds its value ``w^2 / (2 p^2)`` just
after the impact.  If ``w^2 / (2 p^2) <= cos(alpha - theta_eps) - cos(alpha)``, no later excursion
passes ``theta_eps``.  On ``0 <= psi <= theta_eps`` the deceleration ``-psi'' = p^2 sin(alpha -
psi)`` is at least ``d = p^2 sin(alpha - theta_eps)``, so an excursion leaving at speed ``w_k`` lasts
at most ``2 w_k / d`` (at most ``w_k / d`` up; down from the apex ``H <= w_k^2 / (2 d)`` at most
``sqrt(2 H / d) <= w_k / d``) and returns at the same speed; with ``w_k = e^k w`` the whole
cascade ends by ``t_i + 2 w / (d (1 - e))``.

*Moving floor* (``t_i < t_quiet``): on a window ``[t_i, t_i + L]`` let ``A_F`` lie in ``[A_lo,
A_hi]`` and ``G = 1 + a_v/g`` in ``[G_lo, G_hi]``.  On ``0 <= psi <= theta_eps`` the deceleration
``f(psi, t) = p^2 [G sin(alpha - psi) + s (A_F/g) cos(alpha - psi)]`` is at least ``d = p^2 [G_lo
sin(alpha - theta_eps) - max(|A_lo|, |A_hi|) cos(alpha - theta_eps) / g]`` on either corner, and at
one ``psi`` it changes over the window by at most ``2 delta = p^2 [(G_hi - G_lo) sin(alpha) + (A_hi -
A_lo) / g]``.  If ``d > 0``, an excursion leaving at ``w_k`` rises at most ``H_k <= w_k^2 / (2 d)``,
lasts at most ``2 w_k / d``, and, comparing ``w_k^2 / 2 = integral_0^H f(psi, t_up) dpsi`` with
``u_k^2 / 2 = integral_0^H f(psi, t_down) dpsi``, returns at ``u_k^2 <= w_k^2 + 4 delta H_k <= w_k^2
(1 + 2 delta / d)``; the next one leaves at ``w_(k+1) = e u_k <= r w_k`` with ``r = e sqrt(1 + 2
delta / d)``.  So if ``r < 1`` and ``w^2 / (2 d) <= theta_eps`` the block never passes ``theta_eps``
and the cascade ends by ``t_i + 2 w / (d (1 - r))``, provided that time lies in the window (the
peer enlarges the window up to three times).  The ranges come from ``window_samples`` samples of
the floor on the window, each widened by the largest change between neighbouring samples: a proof
when the floor is quiet on the window, and otherwise as good as the samples.  In both cases the
floor's demand stays below the uplift level on the window (``d > 0``), so the rest that follows
is consistent.

The block is declared at rest at ``t_i`` (``theta = 0``); :attr:`RockingResult.rest_by` is the
latest time at which the real cascade ends.  A block at rest on a quiet floor stays at rest: the
run ends there with ``settled = True``.  Nothing of this affects ``theta_max`` beyond
``theta_eps``.

With ``stop_when_decided`` the run also ends at the first impact on a quiet floor after which
the energy is below ``cos(alpha - min(theta_max, alpha)) - cos(alpha)``: from then on no
excursion can reach the peak so far or the unstable equilibrium, so ``theta_max`` and the fact
that the block does not overturn are known.

Accuracy near overturning
-------------------------
Close to the overturning threshold the trajectory passes close to the unstable equilibrium
``|theta| = alpha``, where neighbouring trajectories separate like ``exp(p t)``: the block lingers
there for a time ``~ ln(1/|a - a_c|)/p`` and an error ``delta`` in the state decides the outcome
when the amplitude ``a`` is within ``~delta`` (relative) of the threshold ``a_c``.  So the outcome
near the threshold is set by the integration error of the state when it approaches ``alpha``, not
by event location (which is to a few ulp).  For a rectangular pulse on a block with ``alpha =
0.05`` the threshold found by bisection to ``1e-12`` relative is the same with ``rtol = 1e-8,
1e-10, 1e-12`` and with Radau; it is far below the linearisation error of the closed forms
(``O(alpha^2)``).  The contact past ``alpha`` is assumed, not checked (see above).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp

from ..model.rocking import G_STANDARD, Block
from ..model.validation import check_range

__all__ = ["RockingContactError", "RockingHistory", "RockingResult", "solve_rocking"]

REST = 0
_METHODS = ("DOP853", "Radau")
_HALF_PI = 0.5 * math.pi


class RockingContactError(RuntimeError):
    """The contact assumed by the rocking peer fails: the block would slide or leave the floor.

    Attributes
    ----------
    time : float
        Time (s) at which the contact first fails.
    kind : str
        ``"slide"`` (friction needed above ``mu_s`` times the normal force) or ``"flight"``
        (negative vertical contact force).
    """

    def __init__(self, message: str, time: float, kind: str):
        super().__init__(message)
        self.time = time
        self.kind = kind


@dataclass(frozen=True)
class RockingHistory:
    """Time history of a rocking solve (SI units).

    Attributes
    ----------
    t : ndarray
        Time (s): the integrator's steps, and every event; an impact appears twice (before, after).
    theta : ndarray
        Tilt (rad), positive on the right corner.
    omega : ndarray
        Angular velocity ``theta'`` (rad/s).
    mode : ndarray of int8
        0 at rest, +1 / -1 rocking on the right / left corner.
    """

    t: np.ndarray
    theta: np.ndarray
    omega: np.ndarray
    mode: np.ndarray


@dataclass(frozen=True)
class RockingResult:
    """Result of :func:`solve_rocking`.

    Attributes
    ----------
    theta_max : float
        Peak ``|theta|`` (rad) over the run (``pi/2`` when the block overturned).
    t_theta_max : float
        Time (s) of the peak.
    n_impacts : int
        Impacts at ``theta = 0``.
    overturned : bool
        Whether ``|theta|`` reached ``pi/2``.
    t_overturn : float
        Time (s) it did, else nan.
    settled : bool
        The run ended at rest on a quiet floor (nothing can happen any more).
    decided : bool
        The run ended early under ``stop_when_decided``.
    t_rest : float
        Start (s) of the last rest declared by the end-of-cascade rule, else nan.
    rest_by : float
        Latest time (s) by which that cascade really ends (see the module docstring), else nan.
    t_end : float
        Time (s) at which the run stopped.
    theta_end, omega_end : float
        Final tilt (rad) and angular velocity (rad/s).
    mode_end : int
        Final mode (0 rest, +1 / -1 rocking on the right / left corner).
    uplifts : ndarray
        Times (s) at which rocking started from rest.
    impacts : ndarray, shape (n, 3)
        Each impact's time (s) and angular velocity just before and just after it (rad/s).
    nfev : int
        Right-hand-side evaluations.
    history : RockingHistory or None
        The time history, when asked for.
    """

    theta_max: float
    t_theta_max: float
    n_impacts: int
    overturned: bool
    t_overturn: float
    settled: bool
    decided: bool
    t_rest: float
    rest_by: float
    t_end: float
    theta_end: float
    omega_end: float
    mode_end: int
    uplifts: np.ndarray = field(repr=False)
    impacts: np.ndarray = field(repr=False)
    nfev: int = -1
    history: RockingHistory | None = field(default=None, repr=False)


def _check_callable(name, f):
    if not callable(f):
        raise ValueError(f"{name} = {f!r} is not callable; allowed: a function of time t (s) returning "
                         "an acceleration (m/s^2)")
    return f


def _check_floor(block, A_F, a_v, g, t0, t_end) -> tuple[float, float, float]:
    """The block, the floor motion and the time span checked: ``(g, t0, t_end)``."""
    if not isinstance(block, Block):
        raise ValueError(f"block = {block!r} is invalid; allowed: an isoslide.model.rocking.Block")
    _check_callable("A_F", A_F)
    if a_v is not None:
        _check_callable("a_v", a_v)
    g = check_range("g", g, 0.0, math.inf, lo_in=False, hi_in=False)
    t0 = check_range("t0", t0, -math.inf, math.inf, lo_in=False, hi_in=False)
    t_end = check_range("t_end", t_end, t0, math.inf, lo_in=False, hi_in=False)
    return g, t0, t_end


def _check_mu_s(mu_s, *, zero_ok: bool) -> float:
    """``mu_s`` checked: ``inf``, or finite and positive (``zero_ok``: or 0)."""
    if not (isinstance(mu_s, (int, float)) and not isinstance(mu_s, bool) and mu_s == math.inf):
        mu_s = check_range("mu_s", mu_s, 0.0, math.inf, lo_in=zero_ok, hi_in=False)
    return mu_s


@dataclass(frozen=True)
class _Run:
    """The checked settings of a run, and the rules that need nothing else.

    Shared by :func:`solve_rocking` and :func:`~isoslide.peers.slide_rock.solve_block`.
    """

    block: Block
    g: float
    t_end: float
    t_quiet: float | None
    theta_eps: float
    rtol: float
    atol: float
    p: float
    max_step: float
    max_impacts: int
    window_samples: int
    bps: tuple[float, ...]

    def quiet(self, t):
        """From ``t`` on the floor is at rest for ever."""
        return self.t_quiet is not None and t >= self.t_quiet

    def step_at(self, t):
        """The largest step from ``t`` while the block moves: on a quiet floor at least ``0.1 / p``."""
        return max(self.max_step, 0.1 / self.p) if self.quiet(t) else self.max_step

    def segment(self, t):
        """The end of the segment that starts at ``t``, and the last time before it.

        A segment ends at the next breakpoint, or at the horizon; inside it the floor is evaluated at
        times clipped to ``[t, last]``, so from the left at a breakpoint.
        """
        nxt = [b for b in self.bps if b > t]
        t_seg = min(nxt[0], self.t_end) if nxt else self.t_end
        return t_seg, math.nextafter(t_seg, -math.inf)

    def scan_rest(self, events, t, t_seg):
        """The block at rest: ``solve_ivp`` over ``[t, t_seg]`` up to the first root of ``events``.

        ``events`` are functions of time alone; each ends the scan where it falls through 0.
        """
        for ev in events:
            ev.terminal, ev.direction = True, -1.0
        sol = solve_ivp(lambda tt, y: np.zeros(1), (t, t_seg), np.zeros(1), method="DOP853",
                        rtol=self.rtol, atol=self.atol, events=events, max_step=self.max_step)
        if sol.status < 0:
            raise RuntimeError(f"solve_ivp failed at rest from t = {t!r} s: {sol.message}")
        return sol

    def landing(self, t_i, w, floor):
        """``rest_by`` if a block rocking on stuck pivots stays below ``theta_eps``, else None.

        The end-of-cascade rule of the module docstring, for an impact at ``t_i`` that the block leaves
        at the angular speed ``w``.  ``floor(t)`` gives ``(A_F, G = 1 + a_v/g)``.
        """
        alpha, e, g = self.block.alpha, self.block.e, self.g
        p2, theta_eps = self.p * self.p, self.theta_eps
        sin_ae, cos_ae = math.sin(alpha - theta_eps), math.cos(alpha - theta_eps)
        if self.quiet(t_i):
            if w * w / (2.0 * p2) <= math.cos(alpha - theta_eps) - math.cos(alpha):
                return t_i + 2.0 * w / (p2 * sin_ae * (1.0 - e))
            return None
        A_i, G_i = floor(t_i)
        d0 = p2 * (G_i * sin_ae - abs(A_i) * cos_ae / g)
        if d0 <= 0.0 or w * w / (2.0 * d0) > theta_eps:
            return None
        length = 4.0 * w / (d0 * (1.0 - e))
        for _ in range(3):
            ts = t_i + length * np.linspace(0.0, 1.0, self.window_samples + 1)
            Fs = np.array([floor(float(t)) for t in ts])
            A_s, G_s = Fs[:, 0], Fs[:, 1]
            dA = float(np.max(np.abs(np.diff(A_s))))
            dG = float(np.max(np.abs(np.diff(G_s))))
            A_lo, A_hi = float(A_s.min()) - dA, float(A_s.max()) + dA
            G_lo, G_hi = float(G_s.min()) - dG, float(G_s.max()) + dG
            d = p2 * (G_lo * sin_ae - max(abs(A_lo), abs(A_hi)) * cos_ae / g)
            if d <= 0.0 or w * w / (2.0 * d) > theta_eps:
                return None
            delta = 0.5 * p2 * ((G_hi - G_lo) * math.sin(alpha) + (A_hi - A_lo) / g)
            r = e * math.sqrt(1.0 + 2.0 * delta / d)
            if r >= 1.0:
                return None
            need = 2.0 * w / (d * (1.0 - r))
            if need <= length:
                return t_i + need
            length = 2.0 * need
        return None

    def too_many_impacts(self, t, w):
        """The error past ``max_impacts`` impacts, the last at ``t`` leaving at ``w`` (rad/s)."""
        return RuntimeError(f"more than max_impacts = {self.max_impacts} impacts by t = {t!r} s (outgoing speed "
                            f"{w:.3g} rad/s): the cascade did not meet the end-of-cascade rule")


def _check_run(block: Block, g, t0, t_end, *, t_quiet, breakpoints, theta_eps, rtol, atol, method, max_step,
               max_impacts, window_samples) -> _Run:
    """The settings after the floor and friction checked (``g``, ``t0``, ``t_end`` already are)."""
    if t_quiet is not None:
        t_quiet = check_range("t_quiet", t_quiet, -math.inf, math.inf, lo_in=False, hi_in=False)
    alpha = block.alpha
    if theta_eps is None:
        theta_eps = 1e-3 * alpha
    theta_eps = check_range("theta_eps", theta_eps, 0.0, alpha, lo_in=False, hi_in=False)
    rtol = check_range("rtol", rtol, 1e-14, 1e-3)
    atol = check_range("atol", atol, 0.0, 1.0, lo_in=False)
    if method not in _METHODS:
        raise ValueError(f"method = {method!r} is invalid; allowed: one of {_METHODS}")
    p = block.p(g)
    if max_step is None:
        max_step = 0.1 / p
    max_step = check_range("max_step", max_step, 0.0, math.inf, lo_in=False, hi_in=False)
    if isinstance(max_impacts, bool) or not isinstance(max_impacts, int) or max_impacts < 1:
        raise ValueError(f"max_impacts = {max_impacts!r} is invalid; allowed: a positive integer")
    if isinstance(window_samples, bool) or not isinstance(window_samples, int) or window_samples < 2:
        raise ValueError(f"window_samples = {window_samples!r} is invalid; allowed: an integer >= 2")
    bps = sorted({check_range("breakpoints", b, -math.inf, math.inf, lo_in=False, hi_in=False)
                  for b in breakpoints} | ({t_quiet} if t_quiet is not None else set()))
    return _Run(block=block, g=g, t_end=t_end, t_quiet=t_quiet, theta_eps=theta_eps, rtol=rtol, atol=atol, p=p,
                max_step=max_step, max_impacts=max_impacts, window_samples=window_samples,
                bps=tuple(b for b in bps if t0 < b < t_end))


def _advance(t_e, ok):
    """The first time from ``t_e`` on (doubling steps from one ulp, at most 2^24 ulp) where ``ok``."""
    step = math.ulp(max(abs(t_e), 1.0))
    tt = t_e
    for _ in range(24):
        if ok(tt):
            return tt
        tt = t_e + step
        step *= 2.0
    return tt


def _excursion_events(rising, i):
    """The two terminal events of a segment of an excursion, with ``psi = y[i]`` and ``psi' = y[i + 1]``.

    Rising: the apex (``psi'`` falls through 0) and the overturn (``psi`` rises through ``pi/2``).
    Falling: the impact (``psi`` falls through 0) and the block turning up again before it reaches the
    floor (``psi'`` rises through 0).
    """
    if rising:
        def ev_main(tt, y):
            return y[i + 1]

        def ev_over(tt, y):
            return y[i] - _HALF_PI
    else:
        def ev_main(tt, y):
            return y[i]

        def ev_over(tt, y):
            return y[i + 1]
    ev_main.direction, ev_over.direction = -1.0, 1.0
    ev_main.terminal = ev_over.terminal = True
    return ev_main, ev_over


def solve_rocking(block: Block, A_F, t_end: float, *, a_v=None, g: float = G_STANDARD, t0: float = 0.0,
                  theta0: float = 0.0, omega0: float = 0.0, mu_s: float = math.inf,
                  t_quiet: float | None = None, breakpoints=(), theta_eps: float | None = None,
                  rtol: float = 1e-10, atol: float = 1e-14, method: str = "DOP853",
                  max_step: float | None = None, max_impacts: int = 100_000, window_samples: int = 64,
                  stop_when_decided: bool = False, history: bool = False) -> RockingResult:
    """Rock a rigid block on a prescribed floor motion, event by event.

    Parameters
    ----------
    block : Block
        The block (geometry and restitution).
    A_F : callable
        ``A_F(t)``: the floor's absolute horizontal acceleration (m/s^2, positive towards ``+x``) at
        time ``t`` (s).
    t_end : float
        Horizon (s), ``> t0``.
    a_v : callable or None
        ``a_v(t)``: the floor's vertical acceleration (m/s^2, upwards); None: none.
    g : float
        Gravity (m/s^2).
    t0 : float
        Start time (s).
    theta0, omega0 : float
        Initial tilt (rad, ``|theta0| < pi/2``) and angular velocity (rad/s); both 0 (default): at
        rest.
    mu_s : float
        Static friction coefficient at the pivot, ``> 0``; ``inf`` (default): friction always holds.
        Otherwise a need above it raises :class:`RockingContactError`.
    t_quiet : float or None
        Time (s) from which ``A_F = a_v = 0`` for ever (the end of a pulse); None: never assumed.
        Only with it can the run settle (see the module docstring); it is also a breakpoint.
    breakpoints : sequence of float
        Times (s) where ``A_F`` or ``a_v`` (or their derivatives) jump; segments end there.
    theta_eps : float or None
        Tilt (rad, ``0 < theta_eps < alpha``) below which a dying-out cascade is declared at rest;
        None: ``alpha / 1000``.
    rtol, atol : float
        Tolerances of ``solve_ivp`` (``atol`` in rad and rad/s).
    method : {"DOP853", "Radau"}
        The ``solve_ivp`` integrator.
    max_step : float or None
        Largest step (s); None: ``0.1 / p``.  Keep it below the floor's shortest time scale; on a quiet
        floor (from ``t_quiet`` on) the larger of it and ``0.1 / p``.
    max_impacts : int
        Most impacts before ``RuntimeError``.
    window_samples : int
        Samples of the floor on the end-of-cascade window (moving floor).
    stop_when_decided : bool
        End the run once ``theta_max`` and the absence of overturning are known (module docstring).
    history : bool
        Also return the :class:`RockingHistory`.

    Returns
    -------
    RockingResult

    Raises
    ------
    ValueError
        A parameter out of its range (the message names it, its value and the range).
    RockingContactError
        The block would slide or leave the floor (the message names the time).
    RuntimeError
        More than ``max_impacts`` impacts, or the integrator failed.
    """
    # ---------------------------------------------------------------- validation
    g, t0, t_end = _check_floor(block, A_F, a_v, g, t0, t_end)
    theta0 = check_range("theta0", theta0, -_HALF_PI, _HALF_PI, lo_in=False, hi_in=False)
    omega0 = check_range("omega0", omega0, -math.inf, math.inf, lo_in=False, hi_in=False)
    mu_s = _check_mu_s(mu_s, zero_ok=False)
    run = _check_run(block, g, t0, t_end, t_quiet=t_quiet, breakpoints=breakpoints, theta_eps=theta_eps,
                     rtol=rtol, atol=atol, method=method, max_step=max_step, max_impacts=max_impacts,
                     window_samples=window_samples)
    rtol, atol, p = run.rtol, run.atol, run.p
    quiet = run.quiet

    # ---------------------------------------------------------------- constants
    alpha = block.alpha
    p2 = p * p
    R = block.R
    e = block.e
    sin_a, cos_a = math.sin(alpha), math.cos(alpha)
    check_mu = math.isfinite(mu_s)
    rg = R / g

    def floor_raw(t):
        """``(A_F, G = 1 + a_v/g)`` at ``t``."""
        A = float(A_F(t))
        G = 1.0 if a_v is None else 1.0 + float(a_v(t)) / g
        return A, G

    # ---------------------------------------------------------------- bookkeeping
    nfev = 0
    n_impacts = 0
    impacts: list[tuple[float, float, float]] = []
    uplifts: list[float] = []
    hist: list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]] | None = [] if history else None
    peak, t_peak = abs(theta0), t0
    overturned, t_over = False, math.nan
    settled = decided = False
    t_rest, rest_by = math.nan, math.nan
    zero_len = 0

    def record(t, theta, omega, mode):
        if hist is not None:
            t = np.atleast_1d(np.asarray(t, dtype=float))
            hist.append((t, np.broadcast_to(np.asarray(theta, dtype=float), t.shape).copy(),
                         np.broadcast_to(np.asarray(omega, dtype=float), t.shape).copy(),
                         np.full(t.shape, mode, dtype=np.int8)))

    def note_peak(t, psi):
        nonlocal peak, t_peak
        if psi > peak:
            peak, t_peak = psi, t

    def contact(s, psi, dpsi, ddpsi, A, G):
        """``(V/(m g), s H/(m g))``: the contact force on corner ``s``."""
        sd, cd = math.sin(alpha - psi), math.cos(alpha - psi)
        V = G + rg * (sd * ddpsi - cd * dpsi * dpsi)
        sH = s * A / g + rg * (cd * ddpsi + sd * dpsi * dpsi)
        return V, sH

    def fail(kind, t, where, detail):
        if kind == "flight":
            raise RockingContactError(
                f"the block would leave the floor at t = {t!r} s ({where}): the vertical contact force "
                f"would become negative ({detail}); flight is outside this rocking model", t, "flight")
        raise RockingContactError(
            f"the block would slide at t = {t!r} s ({where}): the friction needed exceeds mu_s = {mu_s!r} "
            f"times the normal force ({detail}); sliding and slide-rock are outside this rocking model",
            t, "slide")

    def check_contact(t, V, sH, where):
        """Raise when the contact force ``(V, s H)`` (units ``m g``) breaks the rocking assumptions."""
        if V < 0.0:
            fail("flight", t, where, f"V/(m g) = {V:.6g}")
        if check_mu and abs(sH) > mu_s * V:
            fail("slide", t, where, f"|H|/V = {abs(sH) / V if V > 0.0 else math.inf:.6g}")

    def uplift_margin(s, A, G):
        """``G sin(alpha) + s (A/g) cos(alpha)``: ``-psi''/p^2`` at ``psi = 0`` on corner ``s``."""
        return G * sin_a + s * (A / g) * cos_a

    # ---------------------------------------------------------------- initial state
    t = t0
    if theta0 != 0.0:
        mode = 1 if theta0 > 0.0 else -1
        psi, dpsi = abs(theta0), mode * omega0
    elif omega0 != 0.0:
        mode = 1 if omega0 > 0.0 else -1
        psi, dpsi = 0.0, abs(omega0)
    else:
        mode, psi, dpsi = REST, 0.0, 0.0
    rising = None
    if mode != REST:
        A, G = floor_raw(t)
        acc = -p2 * (G * math.sin(alpha - psi) + mode * (A / g) * math.cos(alpha - psi))
        rising = dpsi > 0.0 or (dpsi == 0.0 and acc > 0.0)
    record(t, mode * psi if mode else 0.0, mode * dpsi if mode else 0.0, mode)

    # ---------------------------------------------------------------- main loop
    while t < t_end:
        t_seg, t_clip = run.segment(t)

        def floor(tt, t_lo=t, t_hi=t_clip):
            return floor_raw(min(max(tt, t_lo), t_hi))

        if mode == REST:
            A, G = floor_raw(t)
            check_contact(t, G, A / g, "at rest")
            up = [s for s in (1, -1) if uplift_margin(s, A, G) < 0.0]
            if up:
                mode, psi, dpsi, rising = up[0], 0.0, 0.0, True
                uplifts.append(t)
                record(t, 0.0, 0.0, mode)
                continue
            if quiet(t):
                settled = True
                break

            def ev_up_r(tt, y):
                A, G = floor(tt)
                return uplift_margin(1, A, G)

            def ev_up_l(tt, y):
                A, G = floor(tt)
                return uplift_margin(-1, A, G)

            def ev_flight(tt, y):
                return floor(tt)[1]

            events = [ev_up_r, ev_up_l, ev_flight]
            if check_mu:
                def ev_slide_r(tt, y):
                    A, G = floor(tt)
                    return mu_s * G - A / g

                def ev_slide_l(tt, y):
                    A, G = floor(tt)
                    return mu_s * G + A / g

                events += [ev_slide_r, ev_slide_l]
            sol = run.scan_rest(events, t, t_seg)
            nfev += sol.nfev
            if sol.status == 1:
                hits = [(float(te[0]), k) for k, te in enumerate(sol.t_events) if len(te)]
                te, k = min(hits)
                record(te, 0.0, 0.0, REST)
                if k >= 2:  # the root of the flight or a friction margin: the contact fails there
                    A, G = floor_raw(te)
                    if k == 2:
                        fail("flight", te, "at rest", f"1 + a_v/g = {G:.6g}")
                    fail("slide", te, "at rest", f"|A_F|/(g + a_v) = {abs(A) / (g * G):.6g}")
                s = 1 if k == 0 else -1
                # onset: the first time from te on (a few ulp at most) at which psi'' > 0 strictly
                t = _advance(te, lambda tt, s=s: uplift_margin(s, *floor_raw(tt)) < 0.0)
                if uplift_margin(s, *floor_raw(t)) < 0.0:
                    mode, psi, dpsi, rising = s, 0.0, 0.0, True
                    uplifts.append(t)
                    record(t, 0.0, 0.0, s)
                continue
            record(sol.t[1:], 0.0, 0.0, REST)
            t = t_seg
            continue

        # ------------------------------------------------------------ rocking on corner s = mode
        s = mode

        def rhs(tt, y, s=s):
            A, G = floor(tt)
            d = alpha - y[0]
            return np.array([y[1], -p2 * (G * math.sin(d) + s * (A / g) * math.cos(d))])

        def contact_at(tt, y, s=s):
            A, G = floor(tt)
            ddpsi = rhs(tt, y)[1]
            return contact(s, y[0], y[1], ddpsi, A, G)

        if psi < alpha:
            A, G = floor_raw(t)
            acc = -p2 * (G * math.sin(alpha - psi) + s * (A / g) * math.cos(alpha - psi))
            V, sH = contact(s, psi, dpsi, acc, A, G)
            check_contact(t, V, sH, "rocking")

        ev_main, ev_over = _excursion_events(rising, 0)   # apex and overturn, or impact and turning up

        def ev_alpha(tt, y):
            return y[0] - alpha

        def ev_flight(tt, y):
            return contact_at(tt, y)[0]

        events = [ev_main, ev_over, ev_alpha, ev_flight]
        if check_mu:
            def ev_slide_p(tt, y):
                V, sH = contact_at(tt, y)
                return mu_s * V - sH

            def ev_slide_m(tt, y):
                V, sH = contact_at(tt, y)
                return mu_s * V + sH

            events += [ev_slide_p, ev_slide_m]
        ev_alpha.terminal, ev_alpha.direction = False, 0.0
        for ev in events[3:]:
            ev.terminal, ev.direction = False, -1.0

        sol = solve_ivp(rhs, (t, t_seg), np.array([psi, dpsi]), method=method, rtol=rtol, atol=atol,
                        events=events, max_step=run.step_at(t))
        nfev += sol.nfev
        if sol.status < 0:
            raise RuntimeError(f"solve_ivp failed while rocking from t = {t!r} s: {sol.message}")
        t_stop = float(sol.t[-1])
        # contact checks inside the segment, where |theta| < alpha: a root of the flight or of a friction
        # margin (falling through 0) is a failure; entering |theta| < alpha the contact is checked
        fails = []
        for k in range(2, len(events)):
            for te, ye in zip(sol.t_events[k], sol.y_events[k], strict=True):
                if te > t_stop:
                    continue
                V, sH = contact_at(float(te), ye)
                if k == 2:
                    if V < 0.0:
                        fails.append((float(te), "flight", f"V/(m g) = {V:.6g}"))
                    elif check_mu and abs(sH) > mu_s * V:
                        fails.append((float(te), "slide", f"|H|/V = {abs(sH) / V:.6g}"))
                elif ye[0] < alpha:
                    fails.append((float(te), "flight" if k == 3 else "slide",
                                  f"V/(m g) = {V:.6g}, s H/(m g) = {sH:.6g}"))
        if fails:
            te, kind, detail = min(fails)
            fail(kind, te, "rocking", detail)
        ys = sol.y.copy()
        if sol.status == 1:
            hits = [(float(sol.t_events[k][0]), k) for k in (0, 1) if len(sol.t_events[k])]
            te, k = min(hits)
            # the event's own coordinate is exactly at its value (the root is within a few ulp)
            if rising:
                ys[1 - k, -1] = 0.0 if k == 0 else _HALF_PI
            else:
                ys[k, -1] = 0.0
        record(sol.t[1:], s * ys[0, 1:], s * ys[1, 1:], s)
        if sol.status == 1:
            zero_len = zero_len + 1 if te <= t else 0
            if zero_len > 8:
                raise RuntimeError(f"rocking events of zero length repeat at t = {te!r} s")
            t = te
            psi, dpsi = float(ys[0, -1]), float(ys[1, -1])
            if rising:
                if k == 0:                        # apex
                    note_peak(t, psi)
                    rising = False
                else:                             # overturned
                    overturned, t_over = True, t
                    note_peak(t, psi)
                    break
            else:
                if k == 1:                        # turns up again
                    rising = True
                    continue
                # impact: the other corner strikes; theta' keeps its sign, times e
                n_impacts += 1
                w_in = -dpsi
                w = e * w_in
                impacts.append((t, s * dpsi, -s * w))
                mode, psi, dpsi, rising = -s, 0.0, w, True
                record(t, 0.0, -s * w, -s)
                if n_impacts > run.max_impacts:
                    raise run.too_many_impacts(t, w)
                by = run.landing(t, w, floor_raw) if w > 0.0 else t
                if by is not None:
                    mode, psi, dpsi, rising = REST, 0.0, 0.0, None
                    t_rest, rest_by = t, by
                    record(t, 0.0, 0.0, REST)
                    continue
                if stop_when_decided and quiet(t):
                    level = math.cos(alpha - min(peak, alpha)) - cos_a
                    if w * w / (2.0 * p2) < level:
                        decided = True
                        break
        else:
            t = t_seg
            psi, dpsi = float(sol.y[0, -1]), float(sol.y[1, -1])
            note_peak(t, psi)

    if mode != REST and not overturned:
        note_peak(t, psi)
    h = None
    if hist is not None:
        h = RockingHistory(t=np.concatenate([a for a, _, _, _ in hist]),
                           theta=np.concatenate([b for _, b, _, _ in hist]),
                           omega=np.concatenate([c for _, _, c, _ in hist]),
                           mode=np.concatenate([m for _, _, _, m in hist]))
    theta_end = mode * psi if mode != REST else 0.0
    omega_end = mode * dpsi if mode != REST else 0.0
    return RockingResult(theta_max=float(peak), t_theta_max=float(t_peak), n_impacts=n_impacts,
                         overturned=overturned, t_overturn=t_over, settled=settled, decided=decided,
                         t_rest=t_rest, rest_by=rest_by, t_end=float(t), theta_end=float(theta_end),
                         omega_end=float(omega_end), mode_end=int(mode),
                         uplifts=np.asarray(uplifts, dtype=float),
                         impacts=np.asarray(impacts, dtype=float).reshape(-1, 3), nfev=int(nfev), history=h)
