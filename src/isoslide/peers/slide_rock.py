r"""Independent event-driven peer of a rigid block that rests, slides, rocks and slide-rocks on a floor.

The block, the sign convention and the floor motion are those of :mod:`isoslide.model.rocking`
and :mod:`isoslide.peers.rocking`; here the contact has Coulomb friction of static coefficient
``mu_s`` and kinetic coefficient ``mu_k <= mu_s`` (Shenton and Jones 1991; Shenton 1996), so the
block moves through the planar modes

* rest: flat on the floor, ``u' = theta = 0``;
* slide: flat, translating relative to the floor;
* rock: rotating about a bottom corner that sticks;
* slide-rock: rotating about a bottom corner that slides;
* overturned: ``|theta|`` reached ``pi/2`` (the run ends).

``u`` (m) is the horizontal displacement, relative to the floor, of the bottom corner in contact
(the base's translation when the block is flat; at ``theta = 0`` both corners are at ``u -+ b``,
so ``u`` is continuous across an impact).  It shares no code with the compiled engine.

Equations of motion (per unit mass)
-----------------------------------
In the floor's frame the block feels gravity and the inertial force ``-m (A_F, a_v)``; write
``Gam = g + a_v``.  On corner ``s = sgn(theta)`` with ``psi = s theta >= 0``, ``d = alpha - psi``,
the centre of mass is at ``x_c = u + s (b - R sin d)``, ``y_c = R cos d``, so::

    x_c'' = u'' + s R (cos d psi'' + sin d psi'^2),      y_c'' = R (sin d psi'' - cos d psi'^2)

Newton-Euler with the contact force ``(H, V)`` at the corner (moments about the corner, which
accelerates at ``u''``; ``I_O = 4/3 m R^2``, ``k = 3/(4 R)``, ``a = A_F + u''`` the corner's
absolute horizontal acceleration)::

    psi'' = -k [Gam sin d + s a cos d]                   (1)
    H / m = a + s R (cos d psi'' + sin d psi'^2)          (2)
    V / m = Gam + R (sin d psi'' - cos d psi'^2)          (3)

*Rock*: ``u'' = 0`` (so ``a = A_F``); (1) is Housner's equation and (2), (3) give the contact
force needed.  *Slide-rock* in the direction ``sigma = sgn(u')`` of the corner's sliding velocity:
``H = -mu_k V sigma`` closes the system; eliminating ``psi''`` and ``V`` with ``c = s cos d + mu_k
sigma sin d``::

    a [1 - 3/4 c s cos d] = 3/4 c Gam sin d - R psi'^2 (s sin d - mu_k sigma cos d) - mu_k sigma Gam

then ``u'' = a - A_F`` and (1), (3).  The bracket ``D`` is at least ``1/4`` when ``mu_k sigma s
<= 0``; a non-positive ``D`` (large ``mu_k`` with the corner sliding towards the lean, Painleve's
paradox) raises :class:`~isoslide.peers.rocking.RockingContactError` (kind ``"indeterminate"``).
*Rest*: ``H = m A_F``, ``V = m Gam``.  *Slide*: ``u'' = -A_F - mu_k Gam sigma`` (Newmark's sliding
block), ``H = -mu_k V sigma``, ``V = m Gam``.

The moment of the contact forces about the centre of mass of a flat block vanishes when the
normal force's resultant lies at ``x_V = -h H / V`` from the base's centre; it lies on the base
when ``|H| <= V b/h``.  So a flat block slides without tipping exactly while ``mu_k <= b/h``
(independent of the floor), and stays at rest without tipping while ``|A_F| <= Gam b/h``.

Transitions
-----------
Each is the root of an event function located by ``solve_ivp`` (Brent's method to a few ulp in
time, on the integrator's dense output):

*rest -> slide or rock* (Shenton's onsets).  With ``mu_s <= b/h`` the block slides, in the direction
``sigma = -sgn(A_F)``, once ``|A_F| > mu_s Gam``; it never rocks from rest, since that needs ``|A_F|
> Gam b/h``, which is reached no earlier.  With ``mu_s > b/h`` it uplifts onto the corner ``s =
-sgn(A_F)`` once ``|A_F| > Gam b/h`` and never slides from rest.  At the uplift the pivot needs
``|H|/V = b/h`` and, as ``psi''`` grows, more (``d(|H|/V)/d|A_F| = 1/(4 Gam) > 0`` at the
threshold); if the friction needed already exceeds ``mu_s V`` when the motion starts (a
jump of the floor above the threshold, or ``mu_s`` just above ``b/h``), the block enters
slide-rock at once: Shenton's (1996) slide-rock onset from rest.  At ``mu_s = b/h`` both limits
are reached together; the rule gives slide (a stuck pivot cannot rock there, since the friction
it needs rises above ``b/h`` as soon as ``psi'' > 0``, while sliding needs only ``mu_k <= b/h``).

*slide -> rest*: ``u'`` reaches 0 and the floor's demand is within static friction, ``|A_F| <=
mu_s Gam``; else the block slides back (``sigma = -sgn(A_F)``).

*slide -> slide-rock*: the resultant of the normal force would have to pass the leading corner,
``mu_k > b/h``.  This holds or not for the whole slide; it can only happen on a slide entered from
slide-rock through a sliding impact (``mu_s > b/h``), where the block tips at once onto the corner ``s = sigma`` (checked
against ``psi'' > 0``).

*rock -> slide-rock*: the friction the pivot needs exceeds ``mu_s V`` (events ``mu_s V -+ H =
0``); the corner slides opposite to the friction needed, ``sigma = -sgn(H)``, which must give
``sigma u'' >= 0`` (else the run raises, kind ``"indeterminate"``).

*slide-rock -> rock*: ``u'`` reaches 0 and the friction the rocking pivot needs there is within
``mu_s V``; else the corner slides back (``sigma`` reversed, checked likewise).

*Flight*: ``V < 0`` with ``|theta| < alpha`` (or ``Gam < 0`` when flat) raises
:class:`~isoslide.peers.rocking.RockingContactError` (kind ``"flight"``) naming the time.  Past
``|theta| > alpha`` (the falling block) neither friction nor flight is checked, as in
:func:`~isoslide.peers.rocking.solve_rocking`; the block overturns at ``|theta| = pi/2``.

Impact
------
At ``theta = 0`` (``psi' < 0``) the other corner ``s' = -s`` strikes the floor and becomes the
pivot; the old corner leaves it.  The impulse ``(J_x, J_y)`` acts at the new corner only, so the
angular momentum about that corner is conserved.  Writing it with the pre-impact state (corner
``s``, ``theta'^-``, ``u'^-``) and the post-impact one (corner ``s'``, ``theta'^+``, ``u'^+``)::

    theta'^+ = e_H theta'^- - kappa (u'^+ - u'^-),      kappa = 3 h / (4 R^2)

with Housner's ``e_H = 1 - 3/2 sin^2(alpha)``: for a stuck base (``u'^- = u'^+ = 0``) this is
Housner's rule, and a base that keeps its sliding velocity keeps Housner's rule too.  The peer
uses the block's restitution ``e`` in place of ``e_H`` (``e < e_H`` models losses beyond the
rigid impulse, as in :func:`~isoslide.peers.rocking.solve_rocking`).  The new corner's vertical
velocity is zero after the impact (no bounce).  The impulses are the jumps of the centre of
mass's velocity: at ``theta = 0`` on corner ``s``, ``x_c' = u' + s h psi'`` and ``y_c' = b psi'``,
so ``J_x/m = (u'^+ + s' h psi'^+) - (u'^- + s h psi'^-)`` and ``J_y/m = b (psi'^+ - psi'^-)``, each
``psi'`` on its own corner.  The one remaining unknown, ``u'^+``, follows from Coulomb's law for
impulses:

* the new corner sticks, ``u'^+ = 0``, if that needs ``|J_x| <= mu_s J_y``;
* else it slides, ``J_x = -mu_k sigma J_y`` with ``sigma = -sgn(J_x)`` of the sticking solution,
  solved for ``u'^+`` (linear) and checked for ``sgn(u'^+) = sigma``, ``J_y >= 0`` and ``psi'^+ > 0``
  (else the run raises, kind ``"impact"``).

Why this rule: it is the only one of the usual choices consistent with the angular momentum
balance that defines Housner's ``e`` and with Coulomb friction at the striking corner, and it
reduces exactly to the rock-only peer's ``theta' -> e theta'`` when the base sticks before and
after.  Continuity of the centre of mass's horizontal velocity would contradict Housner's own
impact, whose horizontal impulse ``-m h theta'^- (1 - e_H)`` is not zero.  With ``u'^- = 0`` the
sticking impact needs ``mu_s >= (h/b)(1 - e)/(1 + e)``, which Housner's ``e`` meets whenever
``mu_s > b/h`` (``(h/b)(1 - e_H)/(1 + e_H) = 3 sin(alpha) cos(alpha) / (4 - 3 sin^2(alpha))``);
a smaller ``e`` can make a rocking block's impacts slide.

End of the impact cascade
-------------------------
A sticking impact (``u'^+ = 0``) is followed by rocking on a stuck pivot: the rock-only peer's
proven end-of-cascade rule applies unchanged (module docstring of
:mod:`isoslide.peers.rocking`) and the block is declared at rest.  After a sliding impact the
block is declared flat when the outgoing angular speed ``w`` cannot lift it past ``theta_eps``
against the slide-rock deceleration at ``psi = 0``, ``d = -psi''(psi = psi' = 0) > 0``: ``w^2 / (2
d) <= theta_eps``.  It then slides on with the horizontal velocity of its centre of mass, ``u' =
u'^+ + s' h psi'^+`` (the horizontal momentum is kept; the kinetic energy of the rotation and of
the vertical motion, ``T - u'^2/2 >= 0``, is counted as an impact loss): over the tiny excursions
it stands for, the base moves on average with the centre of mass.  (Keeping ``u'^+`` instead
would create energy whenever ``s' h psi'^+`` opposes ``u'^+``.)  This last rule is a local
estimate (the floor and the sliding velocity are taken as frozen over the excursion), not a
proof.

Energy
------
The integrator also carries the floor's work ``W' = -A_F x_c' - a_v y_c'`` and the friction loss
``F' = -H u'`` (both per unit mass), and the run sums the kinetic energy lost at impacts, so that
``W = T + g (y_c - h) + F + impact losses`` at every instant, with ``T = (x_c'^2 + y_c'^2)/2 + R^2
theta'^2 / 6``.

References
----------
H. W. Shenton III and N. P. Jones (1991), Base excitation of rigid bodies. I: Formulation, J.
Eng. Mech. 117(10).  H. W. Shenton III (1996), Criteria for initiation of slide, rock, and
slide-rock rigid-body modes, J. Eng. Mech. 122(7).  G. W. Housner (1963), Bull. Seism. Soc. Am.
53(2).  N. M. Newmark (1965), Effects of earthquakes on dams and embankments, Geotechnique 15(2).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp

from ..model.rocking import G_STANDARD, Block
from ..model.validation import check_range
from .rocking import (_HALF_PI, RockingContactError, _advance, _check_floor, _check_mu_s, _check_run,
                      _excursion_events)

__all__ = ["BlockHistory", "BlockResult", "MODE_NAMES", "OVERTURNED", "REST", "ROCK", "SLIDE", "SLIDE_ROCK",
           "solve_block"]

REST, SLIDE, ROCK, SLIDE_ROCK, OVERTURNED = 0, 1, 2, 3, 4
MODE_NAMES = ("rest", "slide", "rock", "slide-rock", "overturned")


@dataclass(frozen=True)
class BlockHistory:
    """Time history of :func:`solve_block` (SI units; forces and energies per unit mass).

    Attributes
    ----------
    t : ndarray
        Time (s): the integrator's steps and every event; a transition appears twice (before, after).
    u, v : ndarray
        Sliding displacement (m) and velocity (m/s) of the contact corner relative to the floor.
    theta, omega : ndarray
        Tilt (rad, positive on the right corner) and angular velocity (rad/s).
    mode : ndarray of int8
        :data:`REST`, :data:`SLIDE`, :data:`ROCK` or :data:`SLIDE_ROCK`.
    side : ndarray of int8
        Rock and slide-rock: the corner (+1 right, -1 left); slide: ``sgn(u')``; rest: 0.
    H, V : ndarray
        Horizontal and vertical contact force on the block per unit mass (m/s^2), from Newton's law
        of the centre of mass (``H = A_F + x_c''``, ``V = g + a_v + y_c''``).
    work : ndarray
        Work of the floor per unit mass (J/kg), ``integral of -A_F x_c' - a_v y_c'``.
    friction_loss : ndarray
        Energy dissipated by sliding friction per unit mass (J/kg).
    impact_loss : ndarray
        Kinetic energy lost at impacts so far per unit mass (J/kg).
    """

    t: np.ndarray
    u: np.ndarray
    v: np.ndarray
    theta: np.ndarray
    omega: np.ndarray
    mode: np.ndarray
    side: np.ndarray
    H: np.ndarray
    V: np.ndarray
    work: np.ndarray
    friction_loss: np.ndarray
    impact_loss: np.ndarray


@dataclass(frozen=True)
class BlockResult:
    """Result of :func:`solve_block`.

    Attributes
    ----------
    u_max : float
        Peak ``|u|`` (m), the sliding of the base relative to the floor.
    t_u_max : float
        Time (s) of that peak.
    theta_max : float
        Peak ``|theta|`` (rad) (``pi/2`` when the block overturned).
    t_theta_max : float
        Time (s) of that peak.
    overturned : bool
        Whether ``|theta|`` reached ``pi/2``.
    t_overturn : float
        Time (s) it did, else nan.
    n_impacts : int
        Impacts at ``theta = 0``.
    settled : bool
        The run ended at rest on a quiet floor.
    t_end : float
        Time (s) at which the run stopped.
    u_end, v_end, theta_end, omega_end : float
        Final state (m, m/s, rad, rad/s).
    mode_end : int
        Final mode (:data:`MODE_NAMES` indexes it).
    modes : tuple of (float, str, int)
        Every mode entered: its time (s), name (:data:`MODE_NAMES`) and side (corner for rock and
        slide-rock, sliding direction for slide, 0 otherwise); the first entry is the initial mode.
    impacts : ndarray, shape (n, 5)
        Each impact's time (s), ``theta'`` before and after (rad/s) and ``u'`` before and after (m/s).
    t_rest : float
        Start (s) of the last rest declared by the end-of-cascade rule, else nan.
    rest_by : float
        Latest time (s) by which that cascade really ends, else nan.
    nfev : int
        Right-hand-side evaluations.
    history : BlockHistory or None
        The time history, when asked for.
    """

    u_max: float
    t_u_max: float
    theta_max: float
    t_theta_max: float
    overturned: bool
    t_overturn: float
    n_impacts: int
    settled: bool
    t_end: float
    u_end: float
    v_end: float
    theta_end: float
    omega_end: float
    mode_end: int
    modes: tuple = field(repr=False)
    impacts: np.ndarray = field(repr=False)
    t_rest: float = math.nan
    rest_by: float = math.nan
    nfev: int = -1
    history: BlockHistory | None = field(default=None, repr=False)


def _sgn(x: float) -> float:
    return 1.0 if x > 0.0 else (-1.0 if x < 0.0 else 0.0)


def solve_block(block: Block, A_F, t_end: float, *, mu_s: float, mu_k: float | None = None, a_v=None,
                g: float = G_STANDARD, t0: float = 0.0, t_quiet: float | None = None, breakpoints=(),
                theta_eps: float | None = None, rtol: float = 1e-10, atol: float = 1e-14,
                method: str = "DOP853", max_step: float | None = None, max_impacts: int = 100_000,
                window_samples: int = 64, history: bool = False) -> BlockResult:
    """Move a rigid block on a floor with Coulomb friction through rest, slide, rock and slide-rock.

    The block starts at rest at ``t0``.  See the module docstring for the equations and the rules.

    Parameters
    ----------
    block : Block
        The block (geometry and restitution).
    A_F : callable
        ``A_F(t)``: floor's absolute horizontal acceleration (m/s^2, positive towards ``+x``).
    t_end : float
        Horizon (s), ``> t0``.
    mu_s : float
        Static friction coefficient, ``> 0``; ``inf``: the base never slides (the rock-only model).
    mu_k : float or None
        Kinetic friction coefficient, ``0 <= mu_k <= mu_s``; None: ``mu_s``.
    a_v : callable or None
        ``a_v(t)``: floor's vertical acceleration (m/s^2, upwards); None: none.
    g : float
        Gravity (m/s^2).
    t0 : float
        Start time (s).
    t_quiet : float or None
        Time (s) from which ``A_F = a_v = 0`` for ever; also a breakpoint.  Only with it can the run
        settle, and the end-of-cascade rule use its quiet-floor form.
    breakpoints : sequence of float
        Times (s) where the floor motion or its derivatives jump; segments end there.
    theta_eps : float or None
        Tilt (rad, ``0 < theta_eps < alpha``) below which a dying-out cascade ends; None: ``alpha/1000``.
    rtol, atol : float
        Tolerances of ``solve_ivp`` (``atol`` in the state's SI units).
    method : {"DOP853", "Radau"}
        The ``solve_ivp`` integrator.
    max_step : float or None
        Largest step (s); None: ``0.1 / p``.  Keep it below the floor's shortest time scale.
    max_impacts : int
        Most impacts before ``RuntimeError``.
    window_samples : int
        Samples of the floor on the end-of-cascade window (moving floor).
    history : bool
        Also return the :class:`BlockHistory`.

    Returns
    -------
    BlockResult

    Raises
    ------
    ValueError
        A parameter out of its range (the message names it, its value and the range).
    RockingContactError
        Flight (``"flight"``), an impact without a consistent outcome (``"impact"``), or no consistent
        mode (``"indeterminate"``); the message names the time.
    RuntimeError
        More than ``max_impacts`` impacts, or the integrator failed.
    """
    # ---------------------------------------------------------------- validation
    g, t0, t_end = _check_floor(block, A_F, a_v, g, t0, t_end)
    mu_s = _check_mu_s(mu_s, zero_ok=False)
    if mu_k is None:
        mu_k = mu_s if math.isfinite(mu_s) else 0.0
    else:
        mu_k = check_range("mu_k", mu_k, 0.0, min(mu_s, 1e300), lo_in=True, hi_in=True)
    run = _check_run(block, g, t0, t_end, t_quiet=t_quiet, breakpoints=breakpoints, theta_eps=theta_eps,
                     rtol=rtol, atol=atol, method=method, max_step=max_step, max_impacts=max_impacts,
                     window_samples=window_samples)
    theta_eps, rtol, atol, max_step = run.theta_eps, run.rtol, run.atol, run.max_step
    quiet = run.quiet

    # ---------------------------------------------------------------- constants
    alpha = block.alpha
    b, h, R = block.b, block.h, block.R
    tan_a = b / h
    k = 0.75 / R                      # 1/R times m R^2 / I_O
    kappa = 0.75 * h / (R * R)        # 3 h / (4 R^2)
    e = block.e
    sin_a, cos_a = math.sin(alpha), math.cos(alpha)
    can_rock = mu_s > tan_a
    check_mu = math.isfinite(mu_s)

    def floor_raw(t):
        """``(A_F, a_v)`` at ``t``."""
        return float(A_F(t)), (0.0 if a_v is None else float(a_v(t)))

    def floor_G(t):
        """``(A_F, G = 1 + a_v/g)`` at ``t``, the floor of the end-of-cascade rule."""
        A, av = floor_raw(t)
        return A, 1.0 + av / g

    def indeterminate(t, detail):
        raise RockingContactError(f"no consistent contact mode at t = {t!r} s: {detail}", t, "indeterminate")

    # ---------------------------------------------------------------- dynamics of each mode
    def dyn(mode, s, sig, v, psi, w, A, av, t=math.nan):
        """``(u'', psi'', H, V, x_c', y_c')`` per unit mass in ``mode`` on side ``s``, sliding ``sig``."""
        Gam = g + av
        if mode == REST:
            return 0.0, 0.0, A, Gam, 0.0, 0.0
        if mode == SLIDE:
            X = -A - mu_k * sig * Gam
            return X, 0.0, A + X, Gam, v, 0.0
        sd, cd = math.sin(alpha - psi), math.cos(alpha - psi)
        if mode == ROCK:
            a = A
        else:
            c = s * cd + mu_k * sig * sd
            D = 1.0 - 0.75 * c * s * cd
            if not D > 0.0:
                indeterminate(t, f"slide-rock with mu_k = {mu_k!r} gives 1 - 3/4 c s cos(alpha - psi) = {D:.6g} "
                                 "<= 0 (Painleve's paradox)")
            a = (0.75 * c * Gam * sd - R * w * w * (s * sd - mu_k * sig * cd) - mu_k * sig * Gam) / D
        X = a - A
        P = -k * (Gam * sd + s * a * cd)
        H = a + s * R * (cd * P + sd * w * w)
        V = Gam + R * (sd * P - cd * w * w)
        return X, P, H, V, v + s * R * cd * w, R * sd * w

    # ---------------------------------------------------------------- bookkeeping
    nfev = 0
    n_impacts = 0
    impacts: list[tuple[float, float, float, float, float]] = []
    modes: list[tuple[float, str, int]] = []
    hist: list[tuple] | None = [] if history else None
    u_peak, t_u_peak = 0.0, t0
    th_peak, t_th_peak = 0.0, t0
    overturned, t_over = False, math.nan
    settled = False
    t_rest, rest_by = math.nan, math.nan
    lost = 0.0                     # impact losses so far (J/kg)
    zero_len = 0

    def record(ts, Y, mode, s, sig, floor):
        """Append the states ``Y`` (rows u, v, psi, psi', W, F) at times ``ts`` to the history."""
        if hist is None:
            return
        ts = np.atleast_1d(np.asarray(ts, dtype=float))
        Y = np.asarray(Y, dtype=float).reshape(6, -1)
        side = s if mode in (ROCK, SLIDE_ROCK) else (sig if mode == SLIDE else 0)
        Hs = np.empty(ts.shape)
        Vs = np.empty(ts.shape)
        for i, tt in enumerate(ts):
            A, av = floor(float(tt))
            _, _, Hs[i], Vs[i], _, _ = dyn(mode, s, sig, Y[1, i], Y[2, i], Y[3, i], A, av, float(tt))
        sgn = s if mode in (ROCK, SLIDE_ROCK) else 0
        hist.append((ts, Y[0].copy(), Y[1].copy(), sgn * Y[2], sgn * Y[3], np.full(ts.shape, mode, np.int8),
                     np.full(ts.shape, side, np.int8), Hs, Vs, Y[4].copy(), Y[5].copy(),
                     np.full(ts.shape, lost)))

    def enter(t, mode, side):
        if not modes or modes[-1][1:] != (MODE_NAMES[mode], side):
            modes.append((float(t), MODE_NAMES[mode], int(side)))

    def note_u(t, u):
        nonlocal u_peak, t_u_peak
        if abs(u) > u_peak:
            u_peak, t_u_peak = abs(u), t

    def note_theta(t, psi):
        nonlocal th_peak, t_th_peak
        if psi > th_peak:
            th_peak, t_th_peak = psi, t

    def flight(t, where, detail):
        raise RockingContactError(
            f"the block would leave the floor at t = {t!r} s ({where}): the vertical contact force would "
            f"become negative ({detail}); flight is outside this model", t, "flight")

    # ---------------------------------------------------------------- impact
    def impact(t, s, q, v):
        """``(v+, r, J_x, J_y)``: after an impact on corner ``s`` at ``psi' = q < 0``, ``u' = v``."""
        def post(D):
            r = -e * q + s * kappa * D
            return r, D - s * h * (r + q), b * (r - q)

        r, jx, jy = post(-v)
        if jy >= 0.0 and abs(jx) <= mu_s * jy and r > 0.0:
            return 0.0, r, jx, jy
        sig = -_sgn(jx)
        den = 1.0 - h * kappa + mu_k * sig * s * b * kappa
        D = q * (s * h * (1.0 - e) + mu_k * sig * b * (1.0 + e)) / den if den > 0.0 else math.nan
        v_new = v + D
        r, jx, jy = post(D)
        if not (den > 0.0 and sig != 0.0 and _sgn(v_new) == sig and jy >= 0.0 and r > 0.0):
            raise RockingContactError(
                f"the impact at t = {t!r} s has no consistent outcome (theta' = {s * q!r} rad/s, u' = {v!r} "
                f"m/s): sliding gives u'+ = {v_new!r} m/s, psi'+ = {r!r} rad/s, J_y/m = {jy!r} m/s", t, "impact")
        return v_new, r, jx, jy

    def kinetic(s, v, psi, w):
        sd, cd = math.sin(alpha - psi), math.cos(alpha - psi)
        xc, yc = v + s * R * cd * w, R * sd * w
        return 0.5 * (xc * xc + yc * yc) + R * R * w * w / 6.0

    # ---------------------------------------------------------------- state
    t = t0
    mode, s, sig = REST, 1, 0.0
    y = np.zeros(6)                    # u, u', psi, psi', W, F
    rising = None

    def start_rock(t, side, floor):
        """Mode on corner ``side`` with the corner stuck: rock, or slide-rock if friction cannot hold it."""
        A, av = floor(t)
        _, P, H, V, _, _ = dyn(ROCK, side, 0.0, 0.0, y[2], y[3], A, av, t)
        if y[2] < alpha:
            if V < 0.0:
                flight(t, "rocking", f"V/m = {V:.6g} m/s^2")
            if check_mu and abs(H) > mu_s * V:
                return start_slide_rock(t, side, -_sgn(H), floor)
        return ROCK, 0.0

    def start_slide_rock(t, side, sgm, floor):
        A, av = floor(t)
        X, _, _, _, _, _ = dyn(SLIDE_ROCK, side, sgm, 0.0, y[2], y[3], A, av, t)
        if sgm == 0.0 or sgm * X < -1e-12 * (g + abs(A)):
            indeterminate(t, f"the corner would slide in the direction {sgm:+g} but accelerates the other way "
                             f"(u'' = {X!r} m/s^2)")
        return SLIDE_ROCK, sgm

    enter(t, REST, 0)
    record(t, y, REST, s, sig, floor_raw)

    # ---------------------------------------------------------------- main loop
    while t < t_end:
        t_seg, t_clip = run.segment(t)

        def floor(tt, t_lo=t, t_hi=t_clip):
            return floor_raw(min(max(tt, t_lo), t_hi))

        # ------------------------------------------------------------ rest
        if mode == REST:
            A, av = floor_raw(t)
            if g + av < 0.0:
                flight(t, "at rest", f"1 + a_v/g = {1.0 + av / g:.6g}")

            def up_margin(side, tt):
                A, av = floor_raw(tt)
                return (g + av) * sin_a + side * A * cos_a

            def slide_margin(side, tt):
                A, av = floor_raw(tt)
                return mu_s * (g + av) + side * A

            margin = up_margin if can_rock else slide_margin
            go = [side for side in (1, -1) if margin(side, t) < 0.0]
            if not go:
                if quiet(t):
                    settled = True
                    break

                def ev_r(tt, _y):
                    A, av = floor(tt)
                    return (g + av) * sin_a + A * cos_a if can_rock else mu_s * (g + av) + A

                def ev_l(tt, _y):
                    A, av = floor(tt)
                    return (g + av) * sin_a - A * cos_a if can_rock else mu_s * (g + av) - A

                def ev_flight(tt, _y):
                    return g + floor(tt)[1]

                sol = run.scan_rest([ev_r, ev_l, ev_flight], t, t_seg)
                nfev += sol.nfev
                if sol.status != 1:
                    record(sol.t[1:], np.repeat(y[:, None], len(sol.t) - 1, axis=1), REST, s, sig, floor)
                    t = t_seg
                    continue
                te, kk = min((float(tv[0]), j) for j, tv in enumerate(sol.t_events) if len(tv))
                record(te, y, REST, s, sig, floor_raw)
                if kk == 2:
                    flight(te, "at rest", f"1 + a_v/g = {1.0 + floor_raw(te)[1] / g:.6g}")
                side = 1 if kk == 0 else -1
                t = _advance(te, lambda tt, side=side, m=margin: m(side, tt) < 0.0)
                if not margin(side, t) < 0.0:
                    continue
                go = [side]
            side = go[0]
            if can_rock:                      # uplift onto corner `side` (= -sgn(A_F))
                y[2] = y[3] = 0.0
                mode, sig = start_rock(t, side, floor_raw)
                s, rising = side, True
            else:                             # slide in the direction sigma = -sgn(A_F) = side
                mode, sig = SLIDE, float(side)
            enter(t, mode, s if mode != SLIDE else side)
            record(t, y, mode, s, sig, floor_raw)
            continue

        # ------------------------------------------------------------ slide
        if mode == SLIDE:
            if mu_k > tan_a:                  # the normal force's resultant would pass the leading corner
                s, rising = int(sig), True
                A, av = floor_raw(t)
                _, P, _, _, _, _ = dyn(SLIDE_ROCK, s, sig, y[1], 0.0, 0.0, A, av, t)
                if not P > 0.0:
                    indeterminate(t, f"sliding with mu_k = {mu_k!r} > b/h tips the block, but slide-rock "
                                     f"gives psi'' = {P!r} rad/s^2")
                mode = SLIDE_ROCK
                enter(t, mode, s)
                record(t, y, mode, s, sig, floor_raw)
                continue
            if g + floor_raw(t)[1] < 0.0:
                flight(t, "sliding", f"1 + a_v/g = {1.0 + floor_raw(t)[1] / g:.6g}")
            sg = sig

            def rhs_slide(tt, yy, sg=sg):
                A, av = floor(tt)
                X = -A - mu_k * sg * (g + av)
                return np.array([yy[1], X, 0.0, 0.0, -A * yy[1], mu_k * (g + av) * sg * yy[1]])

            def ev_stop(tt, yy, sg=sg):
                return sg * yy[1]

            def ev_flight(tt, yy):
                return g + floor(tt)[1]

            for ev in (ev_stop, ev_flight):
                ev.terminal, ev.direction = True, -1.0
            sol = solve_ivp(rhs_slide, (t, t_seg), y, method=method, rtol=rtol, atol=atol,
                            events=[ev_stop, ev_flight], max_step=max_step)
            nfev += sol.nfev
            if sol.status < 0:
                raise RuntimeError(f"solve_ivp failed while sliding from t = {t!r} s: {sol.message}")
            ys = sol.y.copy()
            if sol.status == 1:
                te, kk = min((float(tv[0]), j) for j, tv in enumerate(sol.t_events) if len(tv))
                if kk == 1:
                    flight(te, "sliding", f"1 + a_v/g = {1.0 + floor_raw(te)[1] / g:.6g}")
                ys[1, -1] = 0.0
            record(sol.t[1:], ys[:, 1:], SLIDE, s, sig, floor)
            t = float(sol.t[-1])
            y = ys[:, -1].copy()
            note_u(t, y[0])
            if sol.status == 1:
                zero_len = zero_len + 1 if sol.t[-1] <= sol.t[0] else 0
                if zero_len > 8:
                    raise RuntimeError(f"events of zero length repeat at t = {t!r} s")
                A, av = floor_raw(t)
                if abs(A) <= mu_s * (g + av):
                    mode, sig = REST, 0.0
                    enter(t, REST, 0)
                else:
                    sig = -_sgn(A)
                    enter(t, SLIDE, int(sig))
                record(t, y, mode, s, sig, floor_raw)
            continue

        # ------------------------------------------------------------ rock / slide-rock on corner s
        md, sd_, sg = mode, s, sig

        def rhs(tt, yy, md=md, sd_=sd_, sg=sg):
            A, av = floor(tt)
            X, P, H, _, xc, yc = dyn(md, sd_, sg, yy[1], yy[2], yy[3], A, av, tt)
            return np.array([yy[1], X, yy[3], P, -A * xc - av * yc, -H * yy[1]])

        def contact_at(tt, yy, md=md, sd_=sd_, sg=sg):
            A, av = floor(tt)
            _, _, H, V, _, _ = dyn(md, sd_, sg, yy[1], yy[2], yy[3], A, av, tt)
            return H, V

        if y[2] < alpha:                          # the contact where the segment starts (the floor may jump)
            H, V = contact_at(t, y)
            if V < 0.0:
                flight(t, MODE_NAMES[md], f"V/m = {V:.6g} m/s^2")
            if md == ROCK and check_mu and abs(H) > mu_s * V:
                mode, sig = start_slide_rock(t, s, -_sgn(H), floor_raw)
                enter(t, mode, s)
                record(t, y, mode, s, sig, floor_raw)
                continue

        ev_main, ev_over = _excursion_events(rising, 2)   # apex and overturn, or impact and turning up

        def ev_flight(tt, yy):
            return contact_at(tt, yy)[1] if yy[2] < alpha else 1.0

        events = [ev_main, ev_over, ev_flight]
        if md == ROCK and check_mu:
            def ev_fr_p(tt, yy):
                if yy[2] >= alpha:
                    return 1.0
                H, V = contact_at(tt, yy)
                return mu_s * V - H

            def ev_fr_m(tt, yy):
                if yy[2] >= alpha:
                    return 1.0
                H, V = contact_at(tt, yy)
                return mu_s * V + H

            events += [ev_fr_p, ev_fr_m]
        elif md == SLIDE_ROCK:
            def ev_stick(tt, yy, sg=sg):
                return sg * yy[1]

            events.append(ev_stick)
        for ev in events:
            ev.terminal = True
        for ev in events[2:]:
            ev.direction = -1.0

        sol = solve_ivp(rhs, (t, t_seg), y, method=method, rtol=rtol, atol=atol, events=events,
                        max_step=run.step_at(t))
        nfev += sol.nfev
        if sol.status < 0:
            raise RuntimeError(f"solve_ivp failed in {MODE_NAMES[md]} from t = {t!r} s: {sol.message}")
        ys = sol.y.copy()
        kk = None
        if sol.status == 1:
            te, kk = min((float(tv[0]), j) for j, tv in enumerate(sol.t_events) if len(tv))
            if kk == 0:
                ys[3 if rising else 2, -1] = 0.0
            elif kk == 1:
                if rising:
                    ys[2, -1] = _HALF_PI
                else:
                    ys[3, -1] = 0.0
            elif md == SLIDE_ROCK and kk == 3:
                ys[1, -1] = 0.0
        record(sol.t[1:], ys[:, 1:], md, s, sig, floor)
        t = float(sol.t[-1])
        y = ys[:, -1].copy()
        note_u(t, y[0])
        if kk is None:
            note_theta(t, y[2])
            continue
        zero_len = zero_len + 1 if sol.t[-1] <= sol.t[0] else 0
        if zero_len > 8:
            raise RuntimeError(f"events of zero length repeat at t = {t!r} s")
        if kk == 2:
            H, V = contact_at(t, y)
            flight(t, MODE_NAMES[md], f"V/m = {V:.6g} m/s^2")
        if kk >= 3:
            if md == ROCK:                        # rock -> slide-rock: friction cannot hold the pivot
                H, _ = contact_at(t, y)
                mode, sig = start_slide_rock(t, s, -_sgn(H), floor_raw)
            else:                                 # slide-rock: the corner stops sliding
                mode, sig = start_rock(t, s, floor_raw)
                if mode == SLIDE_ROCK and sig == sg:
                    indeterminate(t, "the sliding corner stops, friction cannot hold it, and it would slide on "
                                     "the same way")
            enter(t, mode, s)
            record(t, y, mode, s, sig, floor_raw)
            continue
        if rising:
            note_theta(t, y[2])
            if kk == 0:                           # apex
                rising = False
            else:                                 # overturned
                overturned, t_over = True, t
                enter(t, OVERTURNED, s)
                break
            continue
        if kk == 1:                               # turns up again before the floor
            rising = True
            continue
        # impact at psi = 0: the corner -s strikes
        n_impacts += 1
        q, v = float(y[3]), float(y[1])
        v_new, r, _, _ = impact(t, s, q, v)
        lost += kinetic(s, v, 0.0, q) - kinetic(-s, v_new, 0.0, r)
        impacts.append((t, s * q, -s * r, v, v_new))
        if n_impacts > run.max_impacts:
            raise run.too_many_impacts(t, r)
        s = -s
        y[1], y[2], y[3] = v_new, 0.0, r
        rising = True
        if v_new == 0.0:
            mode, sig = ROCK, 0.0
            by = run.landing(t, r, floor_G)
            if by is not None:
                lost += kinetic(s, 0.0, 0.0, r)
                y[3] = 0.0
                mode, t_rest, rest_by = REST, t, by
                enter(t, REST, 0)
                record(t, y, REST, s, 0.0, floor_raw)
                continue
            mode, sig = start_rock(t, s, floor_raw)
        else:
            sig = _sgn(v_new)
            A, av = floor_raw(t)
            _, P0, _, _, _, _ = dyn(SLIDE_ROCK, s, sig, v_new, 0.0, 0.0, A, av, t)
            if P0 < 0.0 and r * r / (-2.0 * P0) <= theta_eps:   # declared flat, keeping x_c'
                v_flat = v_new + s * h * r
                lost += kinetic(s, v_new, 0.0, r) - 0.5 * v_flat * v_flat
                y[1], y[3] = v_flat, 0.0
                sig = _sgn(v_flat)
                mode = SLIDE if sig != 0.0 else REST
                enter(t, mode, int(sig))
                record(t, y, mode, s, sig, floor_raw)
                continue
            mode = SLIDE_ROCK
        enter(t, mode, s)
        record(t, y, mode, s, sig, floor_raw)

    h_out = None
    if hist is not None:
        cols = list(zip(*hist, strict=True))
        arrs = [np.concatenate(c) for c in cols]
        h_out = BlockHistory(t=arrs[0], u=arrs[1], v=arrs[2], theta=arrs[3], omega=arrs[4], mode=arrs[5],
                             side=arrs[6], H=arrs[7], V=arrs[8], work=arrs[9], friction_loss=arrs[10],
                             impact_loss=arrs[11])
    flat = mode in (REST, SLIDE)
    return BlockResult(u_max=float(u_peak), t_u_max=float(t_u_peak), theta_max=float(th_peak),
                       t_theta_max=float(t_th_peak), overturned=overturned, t_overturn=t_over,
                       n_impacts=n_impacts, settled=settled, t_end=float(t), u_end=float(y[0]),
                       v_end=float(y[1]), theta_end=0.0 if flat else float(s * y[2]),
                       omega_end=0.0 if flat else float(s * y[3]), mode_end=OVERTURNED if overturned else mode,
                       modes=tuple(modes), impacts=np.asarray(impacts, dtype=float).reshape(-1, 5),
                       t_rest=t_rest, rest_by=rest_by, nfev=int(nfev), history=h_out)
