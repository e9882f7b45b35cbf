r"""Event-driven reference of a rigid isolated building on a triple friction pendulum, with contents.

A peer written with SciPy from the mechanics below, independently of the compiled kernel and of the
closed forms of :mod:`isoslide.model.tfp` (it reads only the bearing's parameters; the admissibility
check of :class:`~isoslide.model.tfp.TripleFrictionPendulum` is applied to them).  One horizontal
direction, along x.

Input in Pi form (:class:`TFPBuilding`)
----------------------------------------
Time ``tau = t/T_p``, lengths in ``a_p T_p**2``, masses in ``M_b`` (the slab with its rigid
superstructure), forces in ``M_b a_p``.  The bearing: effective radii ``(L1, L2, L3)`` and limits
``(d1, d2, d3)`` divided by ``a_p T_p**2``, friction coefficients ``(mu1, mu2, mu3)`` (constant, or
the fast values of a friction rising with speed: below), and the gravity ratio ``G = g/a_p``.  The weight on the bearing is ``W = (M_b + m_EC) g``, i.e.
``W = (1 + Pi8) G`` in units ``M_b a_p`` (``W = G``, the isolated mass's weight alone, with
``contents_weight=False``, the convention of isoslide's bearings); it sets the pendulum's restoring force ``W u_i/L_i`` and
the friction strengths ``mu_i W``.  An optional viscous damper beside the bearing has the coefficient
``c = c_b T_p/M_b`` (default 0).  The contents: ``Pi8 = m_EC/M_b``, kinetic friction
``Pi2 = mu_k g/a_p`` and ``Pi5 = mu_k/mu_s`` (Coulomb friction with a static level
``Pi2/Pi5``).  The ground acceleration is ``polarity * p(tau)``, ``p`` a pulse of
:mod:`isoslide.pulses`.

The bearing (massless sliders)
------------------------------
Surfaces 1..4 bottom to top (indices 0..3): radii ``(L2, L1, L1, L3)``, strengths
``(mu2, mu1, mu1, mu3) W``, limits ``(d2, d1, d1, d3)``, displacements ``u_i`` with ``x = sum u_i``
(``x``: slab relative to the ground).  Every surface transmits the same force ``F`` (the slide
plates and the slider have no mass), the weight times the slope of the surface's normal plus its
reaction ``q_i`` (friction, and a rigid restrainer's push once ``|u_i| = d_i``)::

    q_0 = F - W u_0/L2           q_1 = q_0 - W u_1/L1      (surface 2 rides on surface 1's plate)
    q_3 = F - W u_3/L3           q_2 = q_3 - W u_2/L1      (surface 3 rides on surface 4's plate)

A surface sticks (``u_i`` constant, true stick) while ``|q_i| <= mu_i W``, slides with
``q_i = mu_i W`` along its motion, and at its restrainer carries any excess pushing outward.

*Bearing held*: every surface stuck, so the slab is held (``x' = x'' = 0``) while the force it needs,
``F_need``, lies in ``[F_lo, F_hi]``: ``F_hi`` the least ``W slope_i + mu_i W`` over the surfaces able
to move forward (``u_i < d_i``), ``F_lo`` the greatest ``W slope_i - mu_i W`` over those able to move
back (``slope_i = (F - q_i)/W``: ``u_0/L2``, ``u_0/L2 + u_1/L1``, ``u_3/L3 + u_2/L1``, ``u_3/L3``).

*Bearing moving* (``x' != 0``, direction ``sigma``): the sliding surfaces are those whose reaction is
pinned at ``sigma``-consistent limits.  Keeping every sliding reaction pinned while ``x`` moves fixes
the rates ``du_i = r_i dx`` and ``dF = K dx`` (a linear system: ``dq_i = 0`` for the sliding
surfaces, ``sum r_i = 1``); stuck surfaces have ``r_i = 0``.  The set is chosen as the quasi-static
peer does (:mod:`isoslide.peers.tfp_quasistatic`): every combination of the surfaces at a limit
(stuck, or sliding in a direction they can move) is tried; a combination is consistent when every
sliding surface moves in its direction (``s_i sigma r_i >= 0``) and no stuck surface at a limit is
pushed beyond it; the consistent ones must share their rates (else ``RuntimeError``).  Within a
mode ``u_i`` and ``F`` are linear in ``x``, so the bearing's state is carried exactly from event to
event (``u_i = u_i^0 + r_i (x - x^0)``, ``F = F^0 + K (x - x^0)``) and only the slab and the
contents are integrated.  Their stage is Fenz and Constantinou's regime of the sliding pair
(:data:`isoslide.model.tfp.STAGE_NAMES`; the inner pair is V with both outer surfaces at their
restrainers, else I; 0 held; -1 any other set, e.g. beyond the capacity).

Equations of motion
-------------------
``A_b = p + x''`` is the slab's absolute acceleration, ``R`` the contents' friction on the slab::

    slab:      A_b = -F - c x' + R           (held: x'' = 0, F = F_need = -p + R)
    contents:  Pi8 (A_b + u'') = -R

Contents stuck (``u' = 0``): ``R = -Pi8 A_b`` while ``|A_b| <= Pi2/Pi5``, so a moving slab has
``A_b = -(F + c x')/(1 + Pi8)`` and a held one needs ``F_need = -(1 + Pi8) p``.  Sliding in
``s = sgn u'``: ``R = Pi8 s Pi2``.

Events and the choice of modes
------------------------------
Located by :func:`scipy.integrate.solve_ivp` (DOP853) events: a stuck surface's reaction reaching its
limit and a sliding surface reaching its restrainer (the bearing's mode is re-chosen; a restrainer is
released when that surface later slides back, which is a surface starting to slide); the slab
stopping (``x' = 0``); a held bearing breaking away (``F_need`` reaching ``F_hi`` or ``F_lo``); the
contents breaking away (``|A_b|`` reaching ``Pi2/Pi5``) or stopping (``u' = 0``); and the pulse's
breakpoints and end.  At every phase start the interfaces at rest (the slab with ``x' = 0``, the
contents with ``u' = 0``) choose their modes together, as :mod:`isoslide.peers.stick_slip` states
the rule: the combinations are tried in the order all stuck; contents stuck & bearing sliding;
contents sliding & bearing held; both sliding, and the first consistent one is taken (each stuck
interface within its limit, ``F_lo <= F_need <= F_hi`` for the bearing; each one starting from rest
accelerating in its direction, the bearing starting at ``F = F_hi`` or ``F_lo`` with a sliding mode
in that direction); an interface that just broke away slides in the direction of its need.  Every
consistent combination is found; a slide from rest that has a consistent stuck alternative (the
other interface's mode the same) is no rival (true stick: with ``mu_s > mu_k`` the contents are
consistent both stuck and sliding while their need lies between the two levels), and a choice among
several remaining rivals is counted in :attr:`TFPRun.ambiguous`.  ``Pi1 = max |u|`` is taken at the contents' stops and at the
end, the slab's peak ``max |x|`` at its stops and at the end.

Settlement
----------
After the pulse (``p = 0`` for good) a phase that starts with the bearing held and the contents stuck
ends the run (``settled = True``): the slab's acceleration is then zero, so the contents need no
friction and the held bearing needs ``F_need = 0``, which the choice of modes has found within
``[F_lo, F_hi]``; nothing changes this state again (a rigid-plastic bearing with true stick stores no
energy that could be released), which is the single friction pendulum's energy bound of
:mod:`isoslide.peers.reference_building` with zero energy.  A run not settled by the horizon
(default ``tau_end + 50 max(1, T_3)``, ``T_3 = 2 pi sqrt((L2 + L3)/G)`` the period of regime III)
ends with ``settled = False``.  The rule needs the slab to stop (``x' = 0``): with a damper that
overdamps the sliding regime the slab can creep towards the force-free point of its last regime
without ever stopping, and such a run ends at the horizon unsettled (its contents stuck, their need
decaying); without a damper a sliding slab always stops in finite time.

Energy
------
With ``KE = x'**2/2 + Pi8 (x' + u')**2/2`` the input work ``-int p (x' + Pi8 (x' + u')) dtau`` equals
``KE + int F dx + int c x'**2 dtau + int R u' dtau``.  The bearing's work ``int F dx`` splits into the
friction works ``int q_i du_i`` of the four surfaces and the gravity work
``int W sum_i slope_i du_i = W sum_i u_i**2/(2 L_i) + W int (u_0/L2 du_1 + u_3/L3 du_2)``.  The last
integral, the work of an inner surface's slope due to its plate's rotation, depends on the path: in
this model of massless sliders the gravity terms are not the gradient of a potential.  Each term is
exact from event to event (everything in the bearing is linear in ``x`` within a mode).

Friction rising with speed
--------------------------
With ``mu_slow`` and ``rate`` (:class:`TFPBuilding`) every surface follows the law of Constantinou,
Mokha and Reinhorn (1990), ``mu_i(v) = mu_i - (mu_i - mu_slow_i) exp(-a_i |v_i|)``, where ``v_i =
du_i/dtau`` is the surface's own sliding speed (units ``a_p T_p``) and ``rate = a a_p T_p`` (``a`` in
s/m); its strengths are ``Q_i(v) = W mu_i(v)``, from the breakaway ``Q_slow_i = W mu_slow_i`` to
``Q_fast_i = W mu_i``.  ``rate = 0`` gives ``mu_slow`` at every speed and ``mu_slow = mu`` gives ``mu``:
with every group so the bearing is the constant one above and the run is that of the constant peer,
bit for bit.  A bearing with some groups constant and others rising with speed is refused.

*A surface.*  At rest it sticks while ``|q_i| <= Q_slow_i`` (true stick at the breakaway level); it
slides in ``s_i`` with ``s_i q_i = Q_i(v_i)``, i.e. at the speed ``v_i = s_i V_i(s_i q_i)``, ``V_i(q) =
-ln((Q_fast_i - q)/(Q_fast_i - Q_slow_i))/a_i`` for ``Q_slow_i <= q < Q_fast_i``; at its restrainer it
stays while its reaction pushes outward or inward by less than ``Q_slow_i``.  Each ``v_i(F)`` (zero
within the slow level, the law beyond it, nothing outward at a restrainer) is non-decreasing in ``F``,
so while the slab moves the force is the unique root of ``sum_i v_i(F) = x'``.  The outer surface's
reaction rises above its slow level with speed, so two surfaces of one chain (1 and 2, or 3 and 4) can
slide at once, which the constant bearing never does.

*Between events.*  The sliding set ``S`` is fixed and the integrated state holds the slab and the
speeds ``v_i`` of the sliding surfaces: the gap ``Q_fast - s q = (Q_fast - Q_slow) exp(-a |v|)`` is below
the double's resolution of ``F`` once ``a |v|`` passes some 35, so the speeds cannot be recovered from
the displacements; they are carried instead, and the sliding surfaces' displacements and ``F`` follow
from ``x`` and the reactions ``q_i = s_i Q_i(v_i)`` by the linear system ``F = W slope_i + q_i`` (``i``
in ``S``), ``sum_i u_i = x`` (:meth:`_RateBearing.system`), so every surface's law holds exactly.
Differentiated, ``F' = W slope_i' + D_i v_i'`` with ``D_i = dQ_i/dv = a_i (Q_fast_i - Q_slow_i)
exp(-a_i |v_i|)`` and ``sum_i v_i' = x''``.  With two or more surfaces sliding this is stiff (their
split relaxes at a rate near ``W/(L D)``, which grows as ``exp(a |v|)``) and is integrated by Radau
with its exact Jacobian (:class:`_RatePhase`); a single sliding surface (``v = x'``) and the held
bearing are integrated by DOP853.  A surface whose ``a |v|`` reaches ``A_PIN = 25`` is pinned at
``Q_fast`` (its gap, ``1.4e-11 (Q_fast - Q_slow)`` and less, is dropped: the only approximation of
the path) and its speed follows from ``F' = W slope_i'`` with the others' speeds and ``x'``, which is
then integrated too; it is released on the law at ``a |v| = A_UNPIN = 24``, and a pinned surface
whose speed so found falls below that starts on the law there.

*Events.*  A sliding surface's speed returning to zero (its reaction back to its slow level; the last
one's is the slab stopping), a stuck surface's ``|q|`` passing its slow level (by ``1e-10`` of ``Q_fast
- Q_slow``; one resting on its level, as an inner surface does while its outer one is pinned, must
move on by as much: the round-off of its reaction is no event; at a restrainer only inward, the
surface leaving it), a sliding surface reaching its restrainer, a surface's ``a |v|`` crossing
``A_PIN`` or ``A_UNPIN``, the held bearing breaking away (the band ``[F_lo, F_hi]`` of the constant
bearing with the breakaway strengths ``Q_slow``), the contents' transitions and the pulse's
breakpoints.  Radau's event times are refined: the step is integrated to the event again from its
start and the time corrected by Newton's rule on the event's function.

*Which surfaces slide* (:meth:`_RateBearing.prepare`, :meth:`_RateBearing.resolve`).  The slab moving,
``F`` is the root above, found by :func:`scipy.optimize.brentq` on the shift of the force, with the
reactions of the surfaces sliding before taken from their gaps (precise however small); the surfaces
beyond their slow level there slide.  A surface at its slow level (to ``1e-9`` of ``Q_fast - Q_slow``)
slides if, held, its reaction would pass the level: the sets of such surfaces are tried held or sliding,
fewer sliding first, and the first is taken in which every held one's reaction rate ``F' - W
slope_j'`` (the set's speeds on their laws) does not point outward and every sliding one speeds up in
its direction; none consistent raises ``RuntimeError``.  The surfaces joining start from rest and the
others share ``x'`` (their reactions shifted alike); a pinned surface keeps the force at its fast
level.  Breaking away from rest, every surface at the edge slides (with no speed their reactions all
change at the rate ``F'``).  The slab stops when the last sliding surface does, or when every speed is
below ``1e-12``; surfaces sliding both ways carry on through ``x' = 0`` (the slab turns without
stopping).  The held band can be empty (an inner surface displaced beyond ``L1 (mu_slow1 +
mu_slow2)`` from its outer one, which the fast friction allows): a slab turning then finds the surfaces
sliding both ways, and a slab at rest finding it so raises ``RuntimeError``.  A surface within its slow
and fast levels creeps at the law's small speed, which can decay without ever reaching zero; a run
whose slab so creeps ends at the horizon unsettled.  The stage follows the outer surfaces 1 and 4
(each sliding, at its restrainer, or free): free and free, or at its restrainer and free, 1 (I);
sliding and free 2 (II); sliding and sliding 3 (III); at its restrainer and sliding 4 (IV); both at
their restrainers 5 (V); any other pair -1.  ``vertices["sliding"]`` records each surface's direction.

*Energy.*  The friction works ``int q_i v_i dtau`` and the plate-rotation work are integrated states;
a restrainer reached is snapped to (its surface's displacement set to ``+-d_i``), which the balance
sees at the tolerance's level.

*As the law flattens.*  ``Pi1`` tends to the constant bearing's of ``mu`` as ``rate`` grows, but not
at first order: a surface whose reaction lies between its slow and fast levels creeps on its law, and
would reach its slow level only after a time near ``a L (Q_fast - Q_slow)/W``; once that time is long
against the motion's, the error behaves as ``(A ln(rate) + B)/rate`` (measured in a scene that stays
in regime I; in scenes through regime II, where an inner surface rests on its level, the approach is
slower still over the rates that take reasonable time).  As ``mu_slow -> mu`` at a fixed rate it tends
to it at first order.

Units: as above; energies in ``M_b a_p**2 T_p**2``.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from ..model.tfp import TripleFrictionPendulum
from ..pulses import Pulse, accel_at, get_pulse
from ..scene import G_STANDARD, Scene
from ..model.validation import check_range

__all__ = ["A_PIN", "A_UNPIN", "ENERGY_NAMES", "RATE_ATOL", "RATE_RTOL", "TFPBuilding", "TFPRun", "default_horizon", "run_tfp",
           "single_pendulum_scene"]

_ULP4 = 4e-15
"""Relative slack of the stick limits (round-off of a limit reached at an event)."""

X, XD, U, UD, WIN, VISC, FRIC = range(7)
"""Indices of the integrated state: slab displacement and velocity relative to the ground, the
contents' sliding and its rate, input work, viscous and contents-friction dissipation."""

ENERGY_NAMES = ("work", "kinetic", "potential", "plate", "friction1", "friction2", "friction3", "friction4",
                "contents", "viscous")
"""Columns of :attr:`TFPRun.energy`: input work, kinetic energy, ``W sum u_i**2/(2 L_i)``, the
path-dependent plate-rotation work, the friction work of surfaces 1..4, the contents' friction and
the viscous dissipation (units ``M_b a_p**2 T_p**2``)."""


def _sign(a: float) -> int:
    return 1 if a > 0.0 else (-1 if a < 0.0 else 0)


def _three(name: str, value, lo: float, lo_in: bool) -> tuple:
    """Three checked floats from one value or three, named ``name1..name3`` in errors."""
    vals = tuple(value) if isinstance(value, (tuple, list, np.ndarray)) else (value,)
    if len(vals) == 1:
        vals = vals * 3
    if len(vals) != 3:
        raise ValueError(f"{name} = {value!r} must be one value or three; got {len(vals)}")
    return tuple(check_range(f"{name}{i}", v, lo, math.inf, lo_in, False) for i, v in enumerate(vals, start=1))


@dataclass(frozen=True)
class TFPBuilding:
    """A rigid isolated building on a triple friction pendulum, with contents, in Pi form.

    Parameters
    ----------
    L : tuple of float
        Effective radii ``(L1, L2, L3)`` over ``a_p T_p**2`` (OpenSees's order: ``L1`` the inner
        surfaces, ``L2`` surface 1, ``L3`` surface 4), > 0.
    mu : tuple of float
        Friction coefficients ``(mu1, mu2, mu3)`` of the same surfaces, >= 0: constant, or with
        ``mu_slow`` the fast (high-speed) values.
    d : tuple of float
        Displacement limits ``(d1, d2, d3)`` over ``a_p T_p**2``, > 0.
    gravity : float
        ``G = g/a_p`` (> 0): the weight on the bearing is ``W = (1 + Pi8) G`` (units ``M_b a_p``).
    pi2 : float
        ``mu_k g/a_p`` of the contents (> 0).
    pi5 : float
        ``mu_k/mu_s`` of the contents, in (0, 1].
    pi8 : float
        ``m_EC/M_b`` (> 0).
    pulse : str or Pulse
        Ground-acceleration shape (:mod:`isoslide.pulses`).
    damping : float
        Viscous coefficient beside the bearing ``c_b T_p/M_b`` (>= 0).
    polarity : int
        +1 or -1: the ground acceleration is ``polarity * p(tau)``.
    contents_weight : bool
        Whether the bearing carries the contents' weight too: ``W = (1 + Pi8) G``; else ``W = G``.
    mu_slow : float or tuple of float or None
        Breakaway (slow) friction ``(mu_slow1, mu_slow2, mu_slow3)`` of a friction rising with speed,
        ``mu(v) = mu - (mu - mu_slow) exp(-a |v|)`` (module docstring), one value or three,
        ``0 <= mu_slow <= mu``; None: constant friction ``mu``.
    rate : float or tuple of float
        ``a a_p T_p`` of that law (``a`` in s/m, ``v`` the surface's own sliding speed), one value or
        three, >= 0; 0 gives ``mu_slow`` at every speed.  Without ``mu_slow`` it must be 0.  The
        groups must all rise with speed (``rate > 0`` and ``mu_slow < mu``) or all be constant.

    Raises
    ------
    ValueError
        Naming the parameter and its allowed range; a bearing outside the admissible set of
        :mod:`isoslide.model.tfp` (regimes I..V in order, at every speed).
    """

    L: tuple
    mu: tuple
    d: tuple
    gravity: float
    pi2: float
    pi5: float = 1.0
    pi8: float = 1e-5
    pulse: str | Pulse = "ricker"
    damping: float = 0.0
    polarity: int = 1
    contents_weight: bool = True
    mu_slow: tuple | None = None
    rate: float | tuple = 0.0
    _bearing: TripleFrictionPendulum = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        set_ = object.__setattr__
        check_range("gravity", self.gravity, 0.0, math.inf, False, False)
        check_range("pi2", self.pi2, 0.0, math.inf, False, False)
        check_range("pi5", self.pi5, 0.0, 1.0, False, True)
        check_range("pi8", self.pi8, 0.0, math.inf, False, False)
        check_range("damping", self.damping, 0.0, math.inf, True, False)
        if self.polarity not in (1, -1):
            raise ValueError(f"polarity = {self.polarity!r} is invalid; allowed: 1 or -1")
        set_(self, "pulse", get_pulse(self.pulse) if not isinstance(self.pulse, Pulse) else self.pulse)
        if self.mu_slow is None:
            rates = _three("rate", self.rate, 0.0, True)
            if any(r != 0.0 for r in rates):
                raise ValueError(f"rate = {self.rate!r} is given without mu_slow; allowed: rate = 0 (constant "
                                 "friction) when mu_slow is None, or mu_slow with rate >= 0")
            set_(self, "rate", 0.0)
            b = TripleFrictionPendulum(self.L, self.mu, self.d, W=self.W)
        else:
            fast = _three("mu", self.mu, 0.0, True)
            slow = _three("mu_slow", self.mu_slow, 0.0, True)
            rates = _three("rate", self.rate, 0.0, True)
            for i, (s_, f_) in enumerate(zip(slow, fast, strict=True), start=1):
                if s_ > f_:
                    raise ValueError(f"mu_slow{i} = {s_!r} exceeds mu{i} = {f_!r}; the law mu(v) = mu - (mu - mu_slow) "
                                     "exp(-rate |v|) needs 0 <= mu_slow <= mu")
            constant = [r == 0.0 or s_ == f_ for r, s_, f_ in zip(rates, slow, fast, strict=True)]
            set_(self, "mu_slow", slow)
            set_(self, "rate", rates)
            if all(constant):
                # rate 0: mu_slow at every speed; mu_slow = mu: mu at every speed
                eff = tuple(s_ if r == 0.0 else f_ for r, s_, f_ in zip(rates, slow, fast, strict=True))
                b = TripleFrictionPendulum(self.L, eff, self.d, W=self.W)
                set_(self, "L", b.L)
                set_(self, "d", b.d)
                set_(self, "mu", fast)
                set_(self, "_bearing", b)
                return
            if any(constant):
                const = ", ".join(f"mu{i}" for i, k in enumerate(constant, start=1) if k)
                rising = ", ".join(f"mu{i}" for i, k in enumerate(constant, start=1) if not k)
                raise ValueError(f"mu_slow = {self.mu_slow!r}, rate = {self.rate!r} keep {const} constant (rate 0 or "
                                 f"mu_slow = mu) while {rising} rise with speed; allowed: all three with rate > 0 and "
                                 "mu_slow < mu, or all three constant")
            b = TripleFrictionPendulum(self.L, fast, self.d, W=self.W, mu_slow=slow, rate=rates)
        set_(self, "L", b.L)
        set_(self, "mu", b.mu)
        set_(self, "d", b.d)
        set_(self, "_bearing", b)

    @classmethod
    def from_physical(cls, L, mu, d, a_p: float, T_p: float, mass_ratio: float, mu_s: float, mu_k: float,
                      pulse="ricker", g: float = G_STANDARD, c: float = 0.0, polarity: int = 1, mu_slow=None,
                      rate=0.0) -> TFPBuilding:
        """The Pi form of a physical building.

        Parameters
        ----------
        L, d : tuple of float
            Effective radii and limits, m.
        mu : tuple of float
            Friction coefficients of the bearing.
        a_p, T_p : float
            Pulse amplitude (m/s^2) and period (s).
        mass_ratio : float
            ``m_EC/M_b``.
        mu_s, mu_k : float
            Static and kinetic friction of the contents.
        pulse : str or Pulse
            Pulse shape.
        g : float
            Gravity, m/s^2.
        c : float
            Viscous coefficient per unit slab mass ``c_b/M_b``, 1/s.
        polarity : int
            Sign of the ground acceleration.
        mu_slow : float or tuple of float or None
            Breakaway friction of a friction rising with speed (one value or three); None: constant.
        rate : float or tuple of float
            ``a`` of the law ``mu(v) = mu - (mu - mu_slow) exp(-a |v|)``, s/m (one value or three).
        """
        s = a_p * T_p * T_p
        vals = tuple(rate) if isinstance(rate, (tuple, list, np.ndarray)) else (rate,)
        rates = tuple(check_range(f"rate{i}" if len(vals) > 1 else "rate", r, 0.0, math.inf, True, False) * a_p * T_p
                      for i, r in enumerate(vals, start=1))
        return cls(L=tuple(x / s for x in L), mu=tuple(mu), d=tuple(x / s for x in d), gravity=g / a_p,
                   pi2=mu_k * g / a_p, pi5=mu_k / mu_s, pi8=mass_ratio, pulse=pulse, damping=c * T_p,
                   polarity=polarity, mu_slow=mu_slow, rate=rates if len(rates) > 1 else rates[0])

    @property
    def rate_dependent(self) -> bool:
        """True when the bearing's friction rises with speed (``mu_slow < mu`` and ``rate > 0``)."""
        return self._bearing.mu_slow is not None

    @property
    def bearing(self) -> TripleFrictionPendulum:
        """The bearing in the model's units (lengths ``a_p T_p**2``, ``W = (1 + Pi8) G`` in ``M_b a_p``)."""
        return self._bearing

    @property
    def W(self) -> float:  # noqa: N802 - the weight, named as in the mechanics
        """Weight on the bearing, units ``M_b a_p``."""
        return ((1.0 + self.pi8) if self.contents_weight else 1.0) * self.gravity


def single_pendulum_scene(building: TFPBuilding) -> Scene:
    """The equivalent single-friction-pendulum :class:`~isoslide.Scene` of a bearing of equal frictions.

    With ``mu1 = mu2 = mu3 = mu`` the inner surfaces never slide and the bearing is a friction
    pendulum of radius ``L2 + L3`` and friction ``mu`` under the weight ``W = (1 + Pi8) G`` until
    surface 1 reaches its restrainer.  isoslide's sliding bearing has the force
    ``(2 pi/Pi3)**2 x + Pi9 sgn(x')`` per unit ``M_b a_p`` (its ``k_d`` and ``Q`` per ``M_b``), so
    ``Pi3 = 2 pi sqrt((L2 + L3)/((1 + Pi8) G))``, ``Pi9 = mu (1 + Pi8) G``,
    ``Pi4 = c Pi3/(4 pi)`` (its viscous coefficient ``2 Pi4 (2 pi/Pi3)``), ``Pi10 = 0``.

    Raises
    ------
    ValueError
        When the three frictions differ.
    """
    if building.rate_dependent:
        raise ValueError(f"mu_slow = {building.mu_slow!r}, rate = {building.rate!r}: the friction rises with speed; "
                         "the single-friction-pendulum scene needs constant friction (rate = 0 or mu_slow = mu)")
    mu = building.bearing.mu
    if not (mu[0] == mu[1] == mu[2]):
        raise ValueError(f"mu = {mu!r} has different values; the bearing is a single friction pendulum only "
                         "with mu1 = mu2 = mu3")
    L = building.L[1] + building.L[2]
    W = building.W
    pi3 = 2.0 * math.pi * math.sqrt(L / W)
    return Scene(pi2=building.pi2, pi3=pi3, pi4=building.damping * pi3 / (4.0 * math.pi), pi5=building.pi5,
                 pi8=building.pi8, pulse=building.pulse, pi9=mu[0] * W, pi10=0.0)


@dataclass(frozen=True)
class TFPRun:
    """A run of :func:`run_tfp`.

    Attributes
    ----------
    pi1 : float
        ``max |u|`` over the response, units ``a_p T_p**2``.
    pi1_residual : float
        Final ``u``.
    tau_peak : float
        Time of ``Pi1`` (units ``T_p``).
    x_peak : float
        The slab's peak ``max |x|`` relative to the ground, units ``a_p T_p**2``.
    peak_stage : int
        Highest regime reached by the bearing (1..5 for I..V; 0 when it never slid).  A stretch with
        another set of sliding surfaces (stage -1, e.g. beyond the capacity) shows in ``stages``.
    stages : tuple of (float, int)
        The stage history: ``(tau, stage)`` at every change (0 held, 1..5 regimes I..V, -1 other
        sets of sliding surfaces).
    settled : bool
        True when the run stopped by the settlement rule (module docstring).
    tau_end : float
        Time at which the run stopped.
    n_events : int
        Located events (surfaces, slab stops, the contents' transitions).
    ambiguous : int
        Mode choices made among more than one consistent combination.
    nfev : int
        Right-hand-side evaluations.
    vertices : dict of ndarray
        At every phase boundary: ``tau``, ``x``, ``xd``, ``u``, ``ud``, ``F`` (the bearing's force:
        ``F_need`` while held), ``surfaces`` (shape ``(n, 4)``), ``stage`` of the phase ending there
        (the first vertex: 0), ``sliding`` (shape ``(n, 4)``: each surface's direction in that phase,
        0 stuck) and ``energy`` (shape ``(n, 10)``, columns :data:`ENERGY_NAMES`).
    history : dict of ndarray or None
        With ``history=True``: ``tau``, ``x``, ``xd``, ``u``, ``ud``, ``F`` and ``surfaces`` (shape
        ``(n, 4)``) at the integrator's steps.
    """

    pi1: float
    pi1_residual: float
    tau_peak: float
    x_peak: float
    peak_stage: int
    stages: tuple
    settled: bool
    tau_end: float
    n_events: int
    ambiguous: int
    nfev: int
    vertices: dict = field(repr=False)
    history: dict | None = field(default=None, repr=False)

    def balance(self) -> np.ndarray:
        """Energy residual at each vertex: input work minus every stored and dissipated part."""
        e = self.vertices["energy"]
        return e[:, 0] - e[:, 1:].sum(axis=1)


class _Bearing:
    """The bearing's equilibrium in the model's units (module docstring)."""

    def __init__(self, b: TripleFrictionPendulum):
        (L1, L2, L3), (mu1, mu2, mu3), (d1, d2, d3) = b.L, b.mu, b.d
        self.W = b.W
        self.R = np.array([L2, L1, L1, L3])
        self.m = self.W * np.array([mu2, mu1, mu1, mu3])
        self.d = np.array([d2, d1, d1, d3])
        self.tol_q = 1e-10 * self.W
        self.tol_u = 1e-12 * float(self.d.max())
        self.eps_dq = 1e-9 * self.W / float(self.R.min())

    def slopes(self, u):
        """``(F - q_i)/W`` of the four surfaces."""
        R = self.R
        s0, s3 = u[0] / R[0], u[3] / R[3]
        return np.array([s0, s0 + u[1] / R[1], s3 + u[2] / R[2], s3])

    def reactions(self, u, F):
        return F - self.W * self.slopes(u)

    def dreactions(self, r, K):
        """Rates of the reactions per unit ``x`` for surface rates ``r`` and force rate ``K``."""
        return K - self.W * self.slopes(r)

    def edge(self, u, s: int) -> float:
        """``F_hi`` (``s = 1``) or ``F_lo`` (``s = -1``): the force at which the first surface able to move in ``s`` slides."""
        lim = self.W * self.slopes(u) + s * self.m
        able = s * u < self.d - self.tol_u
        if not able.any():
            return s * math.inf
        return float(lim[able].min()) if s > 0 else float(lim[able].max())

    def mode(self, u, F, sigma: int):
        """Rates ``(K, r)`` per unit ``x`` of the consistent sliding set for motion ``sigma``, or None."""
        q = self.reactions(u, F)
        options = []
        for i in range(4):
            opts = [0]
            for s in (1, -1):
                if s * q[i] >= self.m[i] - self.tol_q and s * u[i] < self.d[i] - self.tol_u:
                    opts.append(s)
            options.append(opts)
        found = []
        for combo in itertools.product(*options):
            S = [i for i in range(4) if combo[i]]
            if not S:
                continue
            n = len(S) + 1
            A = np.zeros((n, n))
            rhs = np.zeros(n)
            for col in range(n):          # columns: K, then r_i of the sliding surfaces
                r = np.zeros(4)
                K = 1.0 if col == 0 else 0.0
                if col:
                    r[S[col - 1]] = 1.0
                dq = self.dreactions(r, K)
                for row, i in enumerate(S):
                    A[row, col] = dq[i]
                A[n - 1, col] = r.sum()
            rhs[n - 1] = 1.0
            if abs(np.linalg.det(A)) < 1e-300:
                continue
            sol = np.linalg.solve(A, rhs)
            K = float(sol[0])
            r = np.zeros(4)
            r[S] = sol[1:]
            dq = self.dreactions(r, K)
            ok = all(combo[i] * sigma * r[i] >= -1e-12 for i in S)
            for j in range(4):
                if combo[j] == 0:
                    ok = ok and all(s * sigma * dq[j] <= self.eps_dq for s in options[j][1:])
            if ok:
                found.append((K, r))
        if not found:
            return None
        K, r = found[0]
        for K2, r2 in found[1:]:
            if abs(K2 - K) > 1e-8 * abs(K) + self.eps_dq or np.max(np.abs(r2 - r)) > 1e-8:
                raise RuntimeError(f"two sliding sets with different rates at u = {u.tolist()}, F = {F!r}")
        return K, r

    def stage(self, r, u) -> int:
        """Fenz and Constantinou's regime of a stretch with rates ``r`` (0 none, -1 none of the five)."""
        moving = tuple(int(i) for i in np.flatnonzero(np.abs(r) > 1e-12))
        if not moving:
            return 0
        if moving == (1, 2):
            at_stop = (abs(u[0]) >= self.d[0] - self.tol_u) and (abs(u[3]) >= self.d[3] - self.tol_u)
            return 5 if at_stop else 1
        return {(0, 2): 2, (0, 3): 3, (1, 3): 4}.get(moving, -1)


def _stop_event(s: int, k: int, t0: float, v0: float, acc0: float):
    """``s y[k]/(t - t0)``: the sign of the velocity ``y[k]`` (moving in ``s``) without a root at ``t0``."""
    v0 = s * v0

    def g(t, yy):
        dt = t - t0
        if dt > 0.0:
            return s * yy[k] / dt
        return v0 if v0 != 0.0 else s * acc0

    return g


def default_horizon(building: TFPBuilding) -> float:
    """Default end of a run that does not settle, units ``T_p`` (module docstring)."""
    L = building.L
    T3 = 2.0 * math.pi * math.sqrt((L[1] + L[2]) / building.gravity)
    return float(building.pulse.tau_end) + 50.0 * max(1.0, T3)


def run_tfp(building: TFPBuilding, rtol: float | None = None, atol: float | None = None,
            tau_max: float | None = None, history: bool = False, max_events: int = 100_000) -> TFPRun:
    """Solve one building on a triple friction pendulum, event to event (module docstring).

    Parameters
    ----------
    building : TFPBuilding
        The scene in Pi form; the run starts at rest at the pulse's start.
    rtol, atol : float or None
        Tolerances of ``solve_ivp`` (DOP853, and Radau for the stiff phases of a friction rising with
        speed); ``atol`` in the state's units.  None: ``1e-12`` and ``1e-15`` for constant friction,
        :data:`RATE_RTOL` and :data:`RATE_ATOL` (``1e-9``, ``1e-11``; DOP853 a thousandfold tighter)
        for a friction rising with speed, about ``1e-11`` relative in ``Pi1``.  Radau's error estimate
        filters the stiff split of the speeds: at ``rtol = 1e-8`` it can step over the growth of that
        split as the surfaces slow down (an error near ``1e-6``).
    tau_max : float or None
        Horizon, units ``T_p``; default :func:`default_horizon`.
    history : bool
        Also return the integrator's steps.
    max_events : int
        Cap on the number of events (``RuntimeError`` beyond).

    Returns
    -------
    TFPRun

    Raises
    ------
    RuntimeError
        When the moving slab finds no sliding set (every surface at its restrainer in its direction:
        the bearing's total travel), when two sliding sets with different rates are consistent, when
        no combination of modes is consistent, or (friction rising with speed) when a slab at rest
        finds its held band empty.
    """
    if building.rate_dependent:
        return _run_rate(building, RATE_RTOL if rtol is None else rtol, RATE_ATOL if atol is None else atol,
                         tau_max, history, max_events)
    rtol = 1e-12 if rtol is None else rtol
    atol = 1e-15 if atol is None else atol
    B = _Bearing(building.bearing)
    W, m = B.W, building.pi8
    thr, kin, c = building.pi2 / building.pi5, building.pi2, building.damping
    lim_c = thr * (1.0 + _ULP4)
    pulse = building.pulse
    code, params, pol = int(pulse.code), pulse.param_array, float(building.polarity)
    tau_end = float(pulse.tau_end)
    horizon = default_horizon(building) if tau_max is None else float(tau_max)
    bps = [float(b) for b in pulse.breakpoint_array if b < horizon]
    L = building.L
    T_min = 2.0 * math.pi * math.sqrt(2.0 * L[0] / W)
    hmax = min(1.0 / 64.0, T_min / 32.0)

    def p_at(t):
        return pol * accel_at(code, params, t)

    def motion(p, x, xd, ud, bm, F, cm):
        """``(x'', u'', A_b, R, F_need)`` with the bearing held (``bm = 0``) or moving with force ``F``."""
        if cm:
            R = m * cm * kin
        if bm == 0:
            Ab = p
            if cm == 0:
                R = -m * p
                udd = 0.0
            else:
                udd = -p - cm * kin
            return 0.0, udd, Ab, R, -p + R
        Fb = F + c * xd
        if cm == 0:
            Ab = -Fb / (1.0 + m)
            R = -m * Ab
            udd = 0.0
        else:
            Ab = -Fb + R
            udd = -Ab - cm * kin
        return Ab - p, udd, Ab, R, math.nan

    tau = float(pulse.tau_start)
    y = np.zeros(7)
    ub = np.zeros(4)        # surface displacements at the current x
    Fb = 0.0                # bearing force at the current x while it moves
    bm, cm = 0, 0           # bearing: 0 held, +-1 moving; contents: 0 stuck, +-1 sliding
    K, r = 0.0, np.zeros(4)
    forced_b = forced_c = 0
    fric = np.zeros(4)
    plate = 0.0
    peak, tau_peak, x_peak = 0.0, tau, 0.0
    n_events = ambiguous = nfev = 0
    zero_len = 0
    settled = False
    stages = [(tau, 0)]
    stage = 0
    vert = []
    hist = [] if history else None

    def vertex(t, yy, F, st):
        ke = 0.5 * yy[XD] ** 2 + 0.5 * m * (yy[XD] + yy[UD]) ** 2
        pot = float(W * np.sum(ub * ub / (2.0 * B.R)))
        sl = np.where(np.abs(r) > 1e-12, bm * np.sign(r), 0.0).astype(int) if bm else np.zeros(4, dtype=int)
        vert.append((t, yy[X], yy[XD], yy[U], yy[UD], F, ub.copy(), st, sl,
                     (yy[WIN], ke, pot, plate, *fric, yy[FRIC], yy[VISC])))

    vertex(tau, y, 0.0, 0)

    while True:
        if n_events > max_events:
            raise RuntimeError(f"more than max_events = {max_events} events; building={building!r}")
        # ---- modes at the phase start ----------------------------------------------------------
        p0 = p_at(tau)
        if forced_b:
            cand_b, free_b = (forced_b,), False
        elif y[XD] == 0.0:
            cand_b, free_b = (0, 1, -1), True
        else:
            cand_b, free_b = (_sign(y[XD]),), False
        if forced_c:
            cand_c, free_c = (forced_c,), False
        elif cm == 0 or y[UD] == 0.0:
            cand_c, free_c = (0, 1, -1), True
        else:
            cand_c, free_c = (_sign(y[UD]),), False
        order = sorted(((cc, bb) for cc in cand_c for bb in cand_b), key=lambda k: (k[0] != 0, k[1] != 0))
        consistent = []
        edges = {}
        for cc, bb in order:
            if bb == 0:
                acc = motion(p0, y[X], 0.0, y[UD], 0, 0.0, cc)
                need = acc[4]
                lo, hi = B.edge(ub, -1), B.edge(ub, 1)
                slack = _ULP4 * max(abs(lo), abs(hi), W)
                if not (lo - slack <= need <= hi + slack):
                    continue
            else:
                if y[XD] == 0.0:
                    if bb not in edges:
                        Fe = B.edge(ub, bb)
                        edges[bb] = (Fe, B.mode(ub, Fe, bb) if math.isfinite(Fe) else None)
                    Fe, md = edges[bb]
                    if md is None:
                        continue
                else:
                    Fe = Fb
                acc = motion(p0, y[X], y[XD], y[UD], bb, Fe, cc)
                if free_b and not bb * acc[0] > 0.0:
                    continue
            if cc == 0 and abs(acc[2]) > lim_c:
                continue
            if cc != 0 and free_c and not cc * acc[1] > 0.0:
                continue
            consistent.append((cc, bb))
        if not consistent:
            raise RuntimeError(f"no consistent modes at tau = {tau!r}, state {y[:4].tolist()!r}, "
                               f"surfaces {ub.tolist()!r}")
        # a slide from rest is no alternative where sticking is consistent too (true stick; with
        # mu_s > mu_k the contents can be consistent both ways while the need lies between the levels)
        rivals = [(cc, bb) for cc, bb in consistent
                  if not ((cc and free_c and (0, bb) in consistent) or (bb and free_b and (cc, 0) in consistent))]
        ambiguous += len(rivals) > 1
        cm, bm = consistent[0]
        forced_b = forced_c = 0
        if cm == 0:
            y[UD] = 0.0
        if bm == 0:
            y[XD] = 0.0
        else:
            if y[XD] == 0.0:
                Fb = edges[bm][0]
            md = B.mode(ub, Fb, bm)
            if md is None:
                raise RuntimeError(f"the slab moving in {bm:+d} at tau = {tau!r} finds every surface at its "
                                   f"restrainer (x = {float(y[X])!r}, the bearing's total travel)")
            K, r = md
        new_stage = B.stage(r, ub) if bm else 0
        if new_stage != stage:
            stages.append((tau, new_stage))
            stage = new_stage
        if tau >= tau_end and bm == 0 and cm == 0:
            settled = True
            break
        if tau >= horizon:
            break
        # ---- the phase -------------------------------------------------------------------------
        nxt = [b for b in bps if b > tau]
        t_end = min(nxt[0] if nxt else horizon, horizon)
        t_clip = math.nextafter(t_end, -math.inf)
        t0, x0, u0, F0 = tau, float(y[X]), ub.copy(), Fb
        q0 = B.reactions(u0, F0) if bm else None
        dq = B.dreactions(r, K) if bm else None

        def p_of(t, t0=t0, t_clip=t_clip):
            return p_at(min(max(t, t0), t_clip))

        def force(x, bm=bm, K=K, x0=x0, F0=F0):
            return F0 + K * (x - x0) if bm else 0.0

        def rhs(t, yy, bm=bm, cm=cm):
            p = p_of(t)
            xdd, udd, Ab, R, _ = motion(p, yy[X], yy[XD], yy[UD], bm, force(yy[X]), cm)
            mom = yy[XD] + m * (yy[XD] + yy[UD])
            return np.array([yy[XD], xdd, yy[UD], udd, -p * mom, c * yy[XD] ** 2, R * yy[UD]])

        specs = []
        xdd0, udd0 = motion(p0, y[X], y[XD], y[UD], bm, force(y[X]), cm)[:2]
        if bm:
            specs.append((_stop_event(bm, XD, t0, y[XD], xdd0), "slab_stop", -1.0))
            for j in range(4):
                if r[j] == 0.0 or abs(r[j]) <= 1e-12:
                    rate = bm * dq[j]
                    if abs(rate) > B.eps_dq:
                        s = _sign(rate)
                        if s * u0[j] < B.d[j] - B.tol_u:
                            specs.append((lambda t, yy, j=j, s=s, q0=q0, dq=dq, x0=x0:
                                          B.m[j] - s * (q0[j] + dq[j] * (yy[X] - x0)), ("limit", j, s), -1.0))
                else:
                    s = _sign(bm * r[j])
                    specs.append((lambda t, yy, j=j, s=s, u0=u0, r=r, x0=x0:
                                  B.d[j] - s * (u0[j] + r[j] * (yy[X] - x0)), ("stop", j, s), -1.0))
        else:
            lo, hi = B.edge(ub, -1), B.edge(ub, 1)

            def need(t, cm=cm):
                p = p_of(t)
                return -(1.0 + m) * p if cm == 0 else -p + m * cm * kin

            if math.isfinite(hi):
                specs.append((lambda t, yy, hi=hi, need=need: hi - need(t), ("break", 1), -1.0))
            if math.isfinite(lo):
                specs.append((lambda t, yy, lo=lo, need=need: need(t) - lo, ("break", -1), -1.0))
        if cm == 0:
            def ab(t, yy, bm=bm):
                return motion(p_of(t), yy[X], yy[XD], 0.0, bm, force(yy[X]), 0)[2]
            specs.append((lambda t, yy, ab=ab: lim_c - ab(t, yy), ("slip", 1), -1.0))
            specs.append((lambda t, yy, ab=ab: lim_c + ab(t, yy), ("slip", -1), -1.0))
        else:
            specs.append((_stop_event(cm, UD, t0, y[UD], udd0), "contents_stop", -1.0))
        for fn, _, direction in specs:
            fn.terminal, fn.direction = True, direction
        sol = solve_ivp(rhs, (t0, t_end), y, method="DOP853", rtol=rtol, atol=atol,
                        events=[s[0] for s in specs], max_step=hmax)
        nfev += sol.nfev
        if sol.status < 0:
            raise RuntimeError(f"solve_ivp failed: {sol.message}")
        kind = None
        if sol.status == 1:
            hits = [(te[0], ye[0], s[1]) for te, ye, s in zip(sol.t_events, sol.y_events, specs, strict=True)
                    if len(te)]
            te, ye, kind = min(hits, key=lambda h: h[0])
            zero_len = zero_len + 1 if te <= t0 else 0
            if zero_len > 4:
                raise RuntimeError(f"zero-length phases at tau = {te!r}; building={building!r}")
            tau, y = float(te), np.array(ye, dtype=float)
        else:
            tau, y = t_end, np.array(sol.y[:, -1], dtype=float)
        if hist is not None:
            keep = sol.t <= tau
            tt, yy = sol.t[keep], sol.y[:, keep]
            FF = (F0 + K * (yy[X] - x0)) if bm else np.array([motion(p_of(t), 0.0, 0.0, 0.0, 0, 0.0, cm)[4]
                                                               for t in tt])
            UU = (u0[None, :] + (yy[X] - x0)[:, None] * r[None, :]) if bm else np.repeat(ub[None, :], tt.size, axis=0)
            hist.append((tt, yy[:4], FF, UU))
        # ---- the bearing carried to the phase's end --------------------------------------------
        if bm:
            dx = float(y[X]) - x0
            ub = u0 + r * dx
            Fb = F0 + K * dx
            q1 = B.reactions(ub, Fb)
            du = ub - u0
            fric += 0.5 * (q0 + q1) * du
            plate += W * (0.5 * (u0[0] + ub[0]) / B.R[0] * du[1] + 0.5 * (u0[3] + ub[3]) / B.R[3] * du[2])
            F_end = Fb
        else:
            F_end = motion(p_of(tau), 0.0, 0.0, y[UD], 0, 0.0, cm)[4]
        if kind is not None:
            n_events += 1
            p = p_at(tau)
            if isinstance(kind, tuple) and kind[0] == "stop":
                ub[kind[1]] = kind[2] * B.d[kind[1]]
            elif kind == "slab_stop":
                y[XD] = 0.0
                x_peak = max(x_peak, abs(float(y[X])))
            elif kind == "contents_stop":
                y[UD] = 0.0
                if abs(y[U]) > peak:
                    peak, tau_peak = abs(float(y[U])), tau
            elif isinstance(kind, tuple) and kind[0] == "break":
                forced_b = kind[1]
            elif isinstance(kind, tuple) and kind[0] == "slip":
                acc = motion(p, y[X], y[XD], 0.0, bm, Fb, 0)
                forced_c = -_sign(acc[2])
        vertex(tau, y, F_end, stage)

    if abs(y[U]) > peak:
        peak, tau_peak = abs(float(y[U])), tau
    x_peak = max(x_peak, abs(float(y[X])))
    peak_stage = max(s for _, s in stages)
    cols = list(zip(*vert, strict=True))
    vertices = {"tau": np.array(cols[0]), "x": np.array(cols[1]), "xd": np.array(cols[2]), "u": np.array(cols[3]),
                "ud": np.array(cols[4]), "F": np.array(cols[5]), "surfaces": np.array(cols[6]),
                "stage": np.array(cols[7], dtype=int), "sliding": np.array(cols[8], dtype=int),
                "energy": np.array(cols[9])}
    h = None
    if hist is not None:
        h = {"tau": np.concatenate([a for a, _, _, _ in hist]) if hist else np.array([tau])}
        yy = np.concatenate([b for _, b, _, _ in hist], axis=1) if hist else y[:4, None]
        for k, name in enumerate(("x", "xd", "u", "ud")):
            h[name] = yy[k].copy()
        h["F"] = np.concatenate([f for _, _, f, _ in hist]) if hist else np.zeros(1)
        h["surfaces"] = np.concatenate([s_ for _, _, _, s_ in hist]) if hist else ub[None, :]
    return TFPRun(pi1=float(peak), pi1_residual=float(y[U]), tau_peak=float(tau_peak), x_peak=float(x_peak),
                  peak_stage=int(peak_stage), stages=tuple(stages), settled=settled, tau_end=float(tau),
                  n_events=n_events, ambiguous=ambiguous, nfev=nfev, vertices=vertices, history=h)


V0, FR0, PLATE = 7, 11, 15
"""Further indices of the integrated state of a bearing whose friction rises with speed: the four
surfaces' sliding speeds ``v_i`` (7..10), their friction works ``int q_i du_i`` (11..14) and the
plate-rotation work (15)."""

_N_RATE = 16

RATE_RTOL, RATE_ATOL = 1e-9, 1e-11
"""Default ``rtol`` and ``atol`` of a bearing whose friction rises with speed: Radau's (the stiff phases);
DOP853's (a single sliding surface, the held bearing) are a thousandfold tighter."""

_V_TINY = 1e-12
"""Speed (units ``a_p T_p``) below which a surface counts as stopped when the slab stops."""

A_PIN, A_UNPIN = 25.0, 24.0
"""``a |v|`` above which a sliding surface is pinned at ``Q_fast`` and below which it is released on its
law: the gap ``(Q_fast - Q_slow) exp(-a |v|)`` so dropped, ``1.4e-11 (Q_fast - Q_slow)`` at most, is
the peer's only approximation of the path."""

_EXP_MAX = 600.0
"""Cap of ``a |v|`` in the gaps of the choice of modes (``exp(-600)`` is still a double); the speeds of
the surfaces so far out are those of pinned surfaces, found from the others'."""


def _root(f, lo: float, hi: float) -> float:
    """Root of the non-decreasing ``f`` with ``f(lo) <= 0 <= f(hi)`` (either may be infinite).

    Bisection until both ends are finite, then :func:`scipy.optimize.brentq` to the double's
    precision.
    """
    flo, fhi = f(lo), f(hi)
    for _ in range(400):
        if flo == 0.0:
            return lo
        if fhi == 0.0:
            return hi
        if math.isfinite(flo) and math.isfinite(fhi):
            break
        mid = 0.5 * (lo + hi)
        if mid == lo or mid == hi:
            return mid
        fm = f(mid)
        if fm < 0.0:
            lo, flo = mid, fm
        else:
            hi, fhi = mid, fm
    if lo == hi or flo >= 0.0:      # (a bracket valid in exact arithmetic, off by round-off)
        return lo
    if fhi <= 0.0:
        return hi
    return brentq(f, lo, hi, xtol=1e-300, rtol=4.0 * np.finfo(float).eps, maxiter=1000)


@dataclass
class _RateMode:
    """A sliding set: sorted surface indices ``S``, directions ``s`` (4 ints), speeds ``v`` (4) and force ``F``."""

    S: tuple
    s: np.ndarray
    v: np.ndarray
    F: float


class _RateBearing(_Bearing):
    """The bearing whose friction rises with speed, in the model's units (module docstring).

    ``m`` holds the breakaway strengths ``Q_slow`` (the held band's edges), ``qf`` the fast ones.
    """

    def __init__(self, b: TripleFrictionPendulum):
        super().__init__(b)
        (s1, s2, s3), (a1, a2, a3) = b.mu_slow, b.rate
        self.qf = self.m.copy()
        self.qs = self.W * np.array([s2, s1, s1, s3])
        self.m = self.qs
        self.dq = self.qf - self.qs
        self.a = np.array([a2, a1, a1, a3])
        self.tol_t = 1e-9 * self.dq
        R = self.R
        self.kappa = np.array([[1.0 / R[0], 0.0, 0.0, 0.0], [1.0 / R[0], 1.0 / R[1], 0.0, 0.0],
                               [0.0, 0.0, 1.0 / R[2], 1.0 / R[3]], [0.0, 0.0, 0.0, 1.0 / R[3]]])

    # -- the law ------------------------------------------------------------------------------

    def gap(self, i: int, sv: float) -> float:
        """``Q_fast - s q`` of surface ``i`` sliding with ``s v = sv``: ``(Q_fast - Q_slow) exp(-a sv)``.

        Units ``M_b a_p``; ``a sv`` capped at :data:`_EXP_MAX`.
        """
        return self.dq[i] * math.exp(-min(self.a[i] * sv, _EXP_MAX))

    def speed(self, i: int, g: float) -> float:
        """Signed-in-its-direction speed of surface ``i`` at gap ``g`` (the law inverted; +inf for ``g <= 0``)."""
        if g <= 0.0:
            return math.inf
        return -math.log(g / self.dq[i]) / self.a[i]

    # -- sliding sets -------------------------------------------------------------------------

    def system(self, S, u):
        """``(Minv, c)``: ``(u_S, F) = Minv @ (-q_S + c[:n], x + c[n])`` with the other surfaces at ``u``."""
        n = len(S)
        W, K = self.W, self.kappa
        M = np.zeros((n + 1, n + 1))
        c = np.zeros(n + 1)
        frozen = [j for j in range(4) if j not in S]
        for k, i in enumerate(S):
            M[k, :n] = W * K[i, list(S)]
            M[k, n] = -1.0
            c[k] = -W * sum(K[i, j] * u[j] for j in frozen)
        M[n, :n] = 1.0
        c[n] = -sum(u[j] for j in frozen)
        return np.linalg.inv(M), c

    def split(self, S, st, G, target: float):
        """Force shift and speeds of the sliding set ``S`` (normalized directions ``st``) carrying ``target``.

        ``G[k]`` is the gap ``Q_fast - st q`` of surface ``S[k]`` at zero shift; the shift ``delta`` of the
        force solves ``sum_k st_k V_k(G_k - st_k delta) = target`` (the law extended below the slow level).
        """
        n = len(S)
        if n == 1:
            i = S[0]
            return st[0] * (G[0] - self.gap(i, st[0] * target)), np.array([target])
        inv = [st[k] * (G[k] - self.gap(i, st[k] * target / n)) for k, i in enumerate(S)]

        def speeds(delta):
            out = np.empty(n)
            for k, i in enumerate(S):
                out[k] = st[k] * self.speed(i, G[k] - st[k] * delta)
            return out

        lo, hi = min(inv), max(inv)
        delta = lo if lo == hi else _root(lambda dl: float(np.sum(speeds(dl))) - target, lo, hi)
        return delta, speeds(delta)

    def prepare(self, u, F, v, s, xd: float, sigma: int, pinned=()):
        """The surfaces' gaps and the sliding ones at the phase start, the slab moving in ``sigma``.

        In the frame normalized by ``sigma`` (motion forward): the gaps ``Gp = Q_fast - q`` and
        ``Gm = Q_fast + q`` at zero force shift (from the speeds of the surfaces sliding before, else from
        ``F`` and ``u``), the restrainers, and the force shift where the surfaces' speeds, each by its law
        with true stick below the slow level and none outward at a restrainer, add up to ``|x'|`` (the
        edge ``F_hi`` for ``x' = 0``; no shift while a surface of ``pinned`` can still move: it holds the
        force at its fast level).  Returns None when every surface is at its restrainer forward.
        """
        sg = float(sigma)
        ut, Ft, vt, xdt = sg * u, sg * F, sg * v, sg * xd
        bt = self.W * self.slopes(ut)
        Gp, Gm = np.empty(4), np.empty(4)
        for i in range(4):
            if s[i] != 0 and xd != 0.0:
                st = int(sg) * int(s[i])
                e = self.gap(i, st * vt[i])
                Gp[i], Gm[i] = (e, 2.0 * self.qf[i] - e) if st > 0 else (2.0 * self.qf[i] - e, e)
            else:
                qt = Ft - bt[i]
                Gp[i], Gm[i] = self.qf[i] - qt, self.qf[i] + qt
        bp = ut >= self.d - self.tol_u
        bmn = ut <= -(self.d - self.tol_u)
        able = [i for i in range(4) if not bp[i]]
        if not able:
            return None

        def phi(delta):
            total = 0.0
            for i in range(4):
                gp, gm = Gp[i] - delta, Gm[i] + delta
                if not bp[i] and gp < self.dq[i]:
                    total += self.speed(i, gp)
                elif not bmn[i] and gm < self.dq[i]:
                    total -= self.speed(i, gm)
            return total

        d_hi = min(Gp[i] - self.dq[i] for i in able)
        pins = [i for i in pinned if xd != 0.0 and s[i] != 0 and not (bp[i] if sg * s[i] > 0 else bmn[i])]
        if pins:
            delta = 0.0     # a pinned surface holds the force at its fast level
        elif xdt > 0.0:
            # below every surface's slow level and each sliding one at most its share of x': phi <= x'
            prev = [i for i in range(4) if s[i] != 0]
            d_lo = d_hi
            for i in prev:
                st = int(sg) * int(s[i])
                G = Gp[i] if st > 0 else Gm[i]
                d_lo = min(d_lo, st * (G - self.gap(i, st * xdt / len(prev))))
            # and beyond: phi >= x' (phi grows without bound towards the least fast level)
            d_max = min(Gp[i] for i in able)
            d_up = min(Gp[i] - self.gap(i, xdt) for i in able)
            for _ in range(200):
                if phi(d_up) >= xdt or d_up >= d_max:
                    break
                d_up = 0.5 * (d_up + d_max)
            delta = _root(lambda dl: phi(dl) - xdt, d_lo, d_up)
        else:
            delta = d_hi
        strict, ties = [], []
        for i in range(4):
            gp, gm = Gp[i] - delta, Gm[i] + delta
            tol = self.tol_t[i]
            if not bp[i] and gp < self.dq[i] + tol:
                (strict if gp < self.dq[i] - tol else ties).append((i, 1))
            elif not bmn[i] and gm < self.dq[i] + tol:
                if xdt == 0.0 and gm < self.dq[i] - tol:
                    raise RuntimeError(f"the held band is empty at u = {u.tolist()!r}: surface {i + 1} would slide "
                                       "back while the slab breaks away forward (not modelled)")
                (strict if gm < self.dq[i] - tol else ties).append((i, -1))
        return dict(sg=sg, Ft=Ft, Gp=Gp, Gm=Gm, strict=strict, ties=ties, xdt=xdt, delta=delta, pins=pins, v=vt)

    def resolve(self, prep, xdd_of):
        """The consistent sliding set (:class:`_RateMode`) for the prepared phase start, or None.

        Every surface at its slow level (``ties``) is tried held or sliding, fewer sliding first: a held
        one must not be driven beyond its level, a sliding one must speed up in its direction, both
        judged by the rates with the set's speeds held on their laws (module docstring).  ``xdd_of(F)``
        gives the slab's acceleration for the force ``F``.
        """
        sg, W = prep["sg"], self.W
        strict, ties = prep["strict"], prep["ties"]
        if prep["xdt"] == 0.0:
            # breaking away from rest: every surface at the edge has the reaction rate F', so all slide
            if not ties:
                return None
            s = np.zeros(4, dtype=int)
            for i, d in ties:
                s[i] = int(sg) * d
            return _RateMode(S=tuple(sorted(i for i, _ in ties)), s=s, v=np.zeros(4), F=sg * (prep["Ft"] + prep["delta"]))
        subsets = [c for k in range(len(ties) + 1) for c in itertools.combinations(ties, k)]
        for sub in subsets:
            members = sorted(strict + list(sub))
            if not members:
                continue
            S = tuple(i for i, _ in members)
            # the surfaces leaving their slow level start from rest; the others share x'
            carry = sorted(strict) if strict or prep["xdt"] == 0.0 else members
            vt = np.zeros(4)
            if prep["pins"]:
                # the force stays at the pinned surfaces' fast level; their speeds follow from the others'
                delta = 0.0
                for i, d in carry:
                    vt[i] = prep["v"][i] if i in prep["pins"] else d * self.speed(
                        i, prep["Gp"][i] if d > 0 else prep["Gm"][i])
            elif carry and prep["xdt"] != 0.0:
                Sc = [i for i, _ in carry]
                delta, vS = self.split(Sc, [d for _, d in carry],
                                       [prep["Gp"][i] if d > 0 else prep["Gm"][i] for i, d in carry], prep["xdt"])
                vt[Sc] = vS
            else:
                delta = prep["delta"]
            Ft = prep["Ft"] + delta
            F = sg * Ft
            xddt = sg * xdd_of(F)
            D = np.array([self.a[i] * self.gap(i, d * vt[i]) for i, d in members])
            srt = W * self.slopes(vt)
            H = float(np.sum(1.0 / D))
            Fpt = (xddt + float(np.sum(srt[list(S)] / D))) / H
            ok = True
            for j, d in ties:
                rate = d * (Fpt - srt[j])
                scale = 1e-12 * (abs(Fpt) + abs(srt[j]) + abs(xddt) / H)
                if (j, d) in sub:
                    ok = ok and rate > -scale
                else:
                    ok = ok and rate <= scale
            if ok:
                s = np.zeros(4, dtype=int)
                for i, d in members:
                    s[i] = int(sg) * d
                return _RateMode(S=S, s=s, v=sg * vt, F=F)
        return None

    def stage(self, S, u) -> int:
        """The regime of the sliding set ``S`` by the outer surfaces' states (module docstring)."""
        if not S:
            return 0

        def status(i):
            if i in S:
                return "slide"
            return "stop" if abs(u[i]) >= self.d[i] - self.tol_u else "free"

        return {("free", "free"): 1, ("stop", "free"): 1, ("slide", "free"): 2, ("slide", "slide"): 3,
                ("stop", "slide"): 4, ("stop", "stop"): 5}.get((status(0), status(3)), -1)


def _motion(p: float, xd: float, bm: int, F: float, cm: int, m: float, c: float, kin: float):
    """``(x'', u'', A_b, R, F_need)``: the slab held (``bm = 0``) or moving under the bearing force ``F``."""
    if cm:
        Rc = m * cm * kin
    if bm == 0:
        if cm == 0:
            return 0.0, 0.0, p, -m * p, -p - m * p
        return 0.0, -p - cm * kin, p, Rc, -p + Rc
    Fb = F + c * xd
    if cm == 0:
        Ab = -Fb / (1.0 + m)
        return Ab - p, 0.0, Ab, -m * Ab, math.nan
    Ab = -Fb + Rc
    return Ab - p, -Ab - cm * kin, Ab, Rc, math.nan


class _RatePhase:
    """One phase of the speed-dependent bearing: the sliding set ``S`` (directions ``s``) fixed.

    The state holds ``x`` and the speeds of the sliding surfaces on their laws; a surface of ``pinned``
    (its ``a |v|`` past :data:`A_PIN`) is held at ``Q_fast`` and its speed follows from the others', and
    the slab's speed ``x'`` is then a state too.  The sliding surfaces' displacements and the force
    follow from :meth:`_RateBearing.system` (module docstring).  ``bm``, ``cm``: the slab's and the
    contents' modes; ``m, c, kin``: ``Pi8``, the damper and ``Pi2``; ``p_of(t)``: the ground's
    acceleration.
    """

    def __init__(self, B: _RateBearing, S, s, ub, pinned, bm: int, cm: int, m: float, c: float, kin: float,
                 p_of):
        self.B, self.S, self.n = B, tuple(S), len(S)
        self.s = [int(s[i]) for i in S]
        self.a = [float(B.a[i]) for i in S]
        self.dq = [float(B.dq[i]) for i in S]
        self.qf = [float(B.qf[i]) for i in S]
        self.P = [k for k, i in enumerate(self.S) if i in pinned]
        self.Rk = [k for k, i in enumerate(self.S) if i not in pinned]
        self.bm, self.cm, self.m, self.c, self.kin = bm, cm, m, c, kin
        self.W = float(B.W)
        self.R = [float(r) for r in B.R]
        self.u0 = [float(x) for x in ub]
        self.p_of = p_of
        self._key = self._val = None
        self._rkey = self._rval = None
        if self.n:
            Minv, csys = B.system(self.S, ub)
            self.Minv_np, self.Minv, self.csys = Minv, Minv.tolist(), csys.tolist()
        if self.P:
            # (v_P, F') from F' = W kappa_p . v (p pinned) and sum v = x'
            npn, K, W = len(self.P), B.kappa, self.W
            A = np.zeros((npn + 1, npn + 1))
            for row, p in enumerate(self.P):
                for col, p2 in enumerate(self.P):
                    A[row, col] = -W * K[self.S[p], self.S[p2]]
                A[row, npn] = 1.0
            A[npn, :npn] = 1.0
            self.Ainv_np = np.linalg.inv(A)
            self.Ainv = self.Ainv_np.tolist()
            self.Kpr = [[W * float(K[self.S[p], self.S[r]]) for r in self.Rk] for p in self.P]

    def slopes(self, u):
        R = self.R
        s0, s3 = u[0] / R[0], u[3] / R[3]
        return (s0, s0 + u[1] / R[1], s3 + u[2] / R[2], s3)

    def state(self, yy):
        """``(u, F, q_S, D_S, v)``: displacements, force, reactions and ``dq/dv`` of the sliding surfaces, speeds.

        The speeds of pinned surfaces are not filled in (see :meth:`rates`).
        """
        vals = yy.tolist()
        key = (vals[X], vals[V0], vals[V0 + 1], vals[V0 + 2], vals[V0 + 3])
        if key == self._key:
            return self._val[:5]
        n, S = self.n, self.S
        v = vals[V0:V0 + 4]
        q, D, r = [], [], []
        lin = self._lin = [False] * n
        for k in range(n):
            if k in self.P:
                e = 0.0
                Dk = 0.0
            else:
                arg = self.a[k] * self.s[k] * v[S[k]]
                if arg >= 0.0:
                    e = self.dq[k] * math.exp(-min(arg, 700.0))
                    Dk = self.a[k] * e
                else:
                    # moving against its direction (only past a stop, which ends the phase): the law
                    # continued by its tangent, not by the exponential wall of exp(-a s v)
                    e = self.dq[k] * (1.0 - arg)
                    Dk = self.a[k] * self.dq[k]
                    lin[k] = True
            qk = self.s[k] * (self.qf[k] - e)
            q.append(qk)
            D.append(Dk)
            r.append(-qk + self.csys[k])
        r.append(vals[X] + self.csys[n])
        u = list(self.u0)
        F = 0.0
        for j in range(n + 1):
            row = self.Minv[j]
            z = 0.0
            for k in range(n + 1):
                z += row[k] * r[k]
            if j < n:
                u[S[j]] = z
            else:
                F = z
        self._key, self._val = key, (u, F, q, D, v, lin)
        return self._val[:5]

    def rates(self, t, yy):
        """``(u, F, F', v, v', x', x'', u'', A_b, R, p, q_S, D_S)`` at the state ``yy`` (``v`` complete)."""
        key = (t, self._key_of(yy))
        if key == self._rkey:
            return self._rval
        u, F, q, D, v = self.state(yy)
        S, n, W = self.S, self.n, self.W
        p = self.p_of(t)
        vd = [0.0, 0.0, 0.0, 0.0]
        if self.P:
            v = list(v)
            xd = float(yy[XD])
            xdd, udd, Ab, Rc, _ = _motion(p, xd, 1, F, self.cm, self.m, self.c, self.kin)
            b = []
            for row in self.Kpr:
                acc = 0.0
                for w_, r in zip(row, self.Rk, strict=True):
                    acc += w_ * v[S[r]]
                b.append(acc)
            last = xd
            for r in self.Rk:
                last -= v[S[r]]
            b.append(last)
            npn = len(self.P)
            z = []
            for j in range(npn + 1):
                acc = 0.0
                for k in range(npn + 1):
                    acc += self.Ainv[j][k] * b[k]
                z.append(acc)
            for j, pk in enumerate(self.P):
                v[S[pk]] = z[j]
            Fp = z[npn]
            sr = [W * x for x in self.slopes(v)]
            for r in self.Rk:
                vd[S[r]] = (Fp - sr[S[r]]) / D[r]
        else:
            xd = 0.0
            for i in S:
                xd += v[i]
            xdd, udd, Ab, Rc, _ = _motion(p, xd, 1, F, self.cm, self.m, self.c, self.kin)
            sr = [W * x for x in self.slopes(v)]
            if n == 1:
                vd[S[0]] = xdd
                Fp = sr[S[0]] + D[0] * xdd
            else:
                # v_i' = (F' - sr_i)/D_i with F' = (x'' + sum_k sr_k/D_k)/H, H = sum_k 1/D_k, written with the
                # differences sr_k - sr_i so that round-off stays out of sum_i v_i' = x'' when D is tiny
                inv = [1.0 / Dk for Dk in D]
                H = 0.0
                for k in range(n):
                    H += inv[k]
                Fp = xdd / H
                for k in range(n):
                    Fp += inv[k] / H * sr[S[k]]
                for i_ in range(n):
                    acc = xdd
                    si = sr[S[i_]]
                    for k in range(n):
                        if k != i_:
                            acc += (sr[S[k]] - si) * inv[k]
                    vd[S[i_]] = acc * (inv[i_] / H)
        self._rkey = key
        self._rval = (u, F, Fp, v, vd, xd, xdd, udd, Ab, Rc, p, q, D)
        return self._rval

    @staticmethod
    def _key_of(yy):
        return (float(yy[X]), float(yy[XD]), float(yy[V0]), float(yy[V0 + 1]), float(yy[V0 + 2]),
                float(yy[V0 + 3]))

    def speed(self, yy) -> float:
        """The slab's speed ``x'``."""
        if self.P:
            return float(yy[XD])
        xd = 0.0
        for i in self.S:
            xd += float(yy[V0 + i])
        return xd

    def rhs(self, t, yy):
        m, c = self.m, self.c
        out = [0.0] * _N_RATE
        ud = float(yy[UD])
        if self.bm == 0:
            p = self.p_of(t)
            _, udd, _, Rc, _ = _motion(p, 0.0, 0, 0.0, self.cm, m, c, self.kin)
            out[U], out[UD], out[WIN], out[FRIC] = ud, udd, -p * m * ud, Rc * ud
            return np.array(out)
        u, F, Fp, v, vd, xd, xdd, udd, Ab, Rc, p, q, D = self.rates(t, yy)
        out[X], out[U], out[UD] = xd, ud, udd
        if self.P:
            out[XD] = xdd
        out[WIN] = -p * (xd + m * (xd + ud))
        out[VISC] = c * xd * xd
        out[FRIC] = Rc * ud
        out[V0:V0 + 4] = vd
        for k, i in enumerate(self.S):
            out[FR0 + i] = q[k] * v[i]
        R = self.R
        out[PLATE] = self.W * (u[0] / R[0] * v[1] + u[3] / R[3] * v[2])
        return np.array(out)

    def jac(self, t, yy):
        """The Jacobian of :meth:`rhs` (exact in the slab's and the surfaces' rows)."""
        self.state(yy)
        u, F, Fp, v, vd, xd, xdd, udd, Ab, Rc, p, q, D = self.rates(t, yy)
        S, n, W, m, c, B = self.S, self.n, self.W, self.m, self.c, self.B
        P, Rk = self.P, self.Rk
        Minv = self.Minv_np
        D = np.array(D)
        v = np.array(v)
        Jm = np.zeros((_N_RATE, _N_RATE))
        cols = [X] + ([XD] if P else []) + [V0 + S[k] for k in Rk]
        nc = len(cols)
        off = 2 if P else 1
        ev = {k: off + j for j, k in enumerate(Rk)}     # column of each rate surface's speed
        dq = np.zeros((n, nc))
        for k in Rk:
            dq[k, ev[k]] = D[k]
        dz = Minv[:, :n] @ (-dq)
        dz[:, 0] += Minv[:, n]
        dF = dz[n]
        du = np.zeros((4, nc))
        du[list(S)] = dz[:n]
        dv = np.zeros((4, nc))
        for k in Rk:
            dv[S[k], ev[k]] = 1.0
        dxd = np.zeros(nc)
        if P:
            dxd[1] = 1.0
            db = np.zeros((len(P) + 1, nc))
            for row in range(len(P)):
                for j, r in enumerate(Rk):
                    db[row, ev[r]] = self.Kpr[row][j]
            db[len(P), 1] = 1.0
            for r in Rk:
                db[len(P), ev[r]] = -1.0
            dzp = self.Ainv_np @ db
            for j, pk in enumerate(P):
                dv[S[pk]] = dzp[j]
            dFp_pin = dzp[len(P)]
        else:
            for k in Rk:
                dxd[ev[k]] = 1.0
        if self.cm == 0:
            dxdd = -(dF + c * dxd) / (1.0 + m)
            dR = -m * dxdd
        else:
            dxdd = -(dF + c * dxd)
            dR = np.zeros(nc)
        Kw = W * B.kappa
        sr = Kw @ v
        dsr = Kw @ dv
        if P:
            dFp = dFp_pin
        elif n == 1:
            dFp = None
        else:
            invD = 1.0 / D
            H = float(np.sum(invD))
            dN = dxdd.copy()
            dH = np.zeros(nc)
            lin = self._val[5]
            for k in range(n):
                dinv = 0.0 if lin[k] else self.a[k] * self.s[k] * invD[k]
                dN += dsr[S[k]] * invD[k]
                dN[ev[k]] += sr[S[k]] * dinv
                dH[ev[k]] += dinv
            dFp = (dN - Fp * dH) / H
        for k in Rk:
            i = S[k]
            if dFp is None:
                dvd = dxdd
            else:
                dvd = (dFp - dsr[i]) / D[k]
                if not self._val[5][k]:
                    dvd[ev[k]] += (Fp - sr[i]) * self.a[k] * self.s[k] / D[k]
            Jm[V0 + i, cols] = dvd
        Jm[X, cols] = dxd
        if P:
            Jm[XD, cols] = dxdd
        Jm[U, UD] = 1.0
        if self.cm:
            Jm[UD, cols] = -dxdd                        # u'' = -A_b - cm kin, A_b = x'' + p
        Jm[WIN, cols] = -p * (1.0 + m) * dxd
        Jm[WIN, UD] = -p * m
        Jm[VISC, cols] = 2.0 * c * xd * dxd
        Jm[FRIC, UD] = Rc
        Jm[FRIC, cols] += dR * float(yy[UD])
        for k, i in enumerate(S):
            Jm[FR0 + i, cols] = q[k] * dv[i] + v[i] * dq[k]
        R = self.R
        Jm[PLATE, cols] = W * (du[0] / R[0] * v[1] + u[0] / R[0] * dv[1] + du[3] / R[3] * v[2]
                               + u[3] / R[3] * dv[2])
        return Jm


def _stop_value_event(s: int, value, t0: float, v0: float, acc0: float):
    """``s value(y)/(t - t0)``: the sign of a velocity (moving in ``s``) without a root at ``t0``."""
    v0 = s * v0

    def g(t, yy):
        dt = t - t0
        if dt > 0.0:
            return s * value(yy) / dt
        return v0 if v0 != 0.0 else s * acc0

    return g


def _run_rate(building: TFPBuilding, rtol: float, atol: float, tau_max, history: bool, max_events: int) -> TFPRun:
    """:func:`run_tfp` for a bearing whose friction rises with speed (module docstring)."""
    B = _RateBearing(building.bearing)
    W, m = B.W, building.pi8
    thr, kin, c = building.pi2 / building.pi5, building.pi2, building.damping
    lim_c = thr * (1.0 + _ULP4)
    pulse = building.pulse
    code, params, pol = int(pulse.code), pulse.param_array, float(building.polarity)
    tau_end = float(pulse.tau_end)
    horizon = default_horizon(building) if tau_max is None else float(tau_max)
    bps = [float(b) for b in pulse.breakpoint_array if b < horizon]
    L = building.L
    T_min = 2.0 * math.pi * math.sqrt(2.0 * L[0] / W)
    hmax = min(1.0 / 64.0, T_min / 32.0)
    R = B.R

    def p_at(t):
        return pol * accel_at(code, params, t)

    def motion(p, xd, bm, F, cm):
        return _motion(p, xd, bm, F, cm, m, kin=kin, c=c)

    tau = float(pulse.tau_start)
    y = np.zeros(_N_RATE)
    ub = np.zeros(4)        # surface displacements
    Fb = 0.0                # bearing force (while it moves)
    sb = np.zeros(4, dtype=int)
    S = ()
    bm, cm = 0, 0
    forced_b = forced_c = 0
    peak, tau_peak, x_peak = 0.0, tau, 0.0
    n_events = ambiguous = nfev = 0
    zero_len = 0
    keep = 0                # the direction of a slab turning while surfaces slide both ways
    pinned = set()          # sliding surfaces pinned at Q_fast
    force_pin, force_unpin = set(), set()
    settled = False
    stages = [(tau, 0)]
    stage = 0
    vert = []
    hist = [] if history else None

    def vertex(t, yy, F, st, sl):
        ke = 0.5 * yy[XD] ** 2 + 0.5 * m * (yy[XD] + yy[UD]) ** 2
        pot = float(W * np.sum(ub * ub / (2.0 * R)))
        vert.append((t, yy[X], yy[XD], yy[U], yy[UD], F, ub.copy(), st, sl.copy(),
                     (yy[WIN], ke, pot, yy[PLATE], *yy[FR0:FR0 + 4], yy[FRIC], yy[VISC])))

    vertex(tau, y, 0.0, 0, sb)

    def settle_pins(S, sb, ub, pinned, y, cm):
        """The pinned surfaces and the speeds at a phase start (``y[XD]`` the slab's speed; ``y`` updated).

        A pinned surface's speed follows from the others' (its gap is taken as zero); one whose speed so
        found is below ``A_UNPIN/a`` leaves the set with the speed ``A_UNPIN/a`` (its gap the smallest
        resolved), and when no pinned surface is left the law's speeds carry ``x'`` again.
        """
        pinned = set(pinned)
        xd = float(y[XD])
        sg = _sign(xd)
        for _ in range(8):
            if not pinned:
                St = [i for i in S]
                st = [sg * int(sb[i]) for i in St]
                G = [B.gap(i, int(sb[i]) * float(y[V0 + i])) for i in St]
                _, vS = B.split(St, st, G, sg * xd)
                for i, vk in zip(St, vS, strict=True):
                    y[V0 + i] = sg * vk
                new = {i for i in S if B.a[i] * sb[i] * y[V0 + i] >= A_PIN}
                if not new:
                    y[XD] = sum(float(y[V0 + i]) for i in S)
                    return set()
                pinned = new
                continue
            tmp = _RatePhase(B, S, sb, ub, pinned, 1, cm, m, c, kin, lambda t: 0.0)
            v_full = tmp.rates(0.0, y)[3]
            low = [i for i in sorted(pinned) if B.a[i] * sb[i] * v_full[i] < A_UNPIN]
            if not low:
                for i in pinned:
                    y[V0 + i] = v_full[i]
                return pinned
            for i in low:
                pinned.discard(i)
                y[V0 + i] = sb[i] * A_UNPIN / B.a[i]
        raise RuntimeError(f"no consistent pinned set at speeds {y[V0:V0 + 4].tolist()!r}")

    while True:
        if n_events > max_events:
            raise RuntimeError(f"more than max_events = {max_events} events; building={building!r}")
        if tau >= horizon:
            break
        # ---- modes at the phase start ----------------------------------------------------------
        p0 = p_at(tau)
        xd0 = float(y[XD])
        if keep:
            # the slab turning while surfaces slide both ways: every mode carries on
            bm, keep = keep, 0
        else:
            if forced_b:
                cand_b, free_b = (forced_b,), False
            elif xd0 == 0.0:
                cand_b, free_b = (0, 1, -1), True
            else:
                cand_b, free_b = (_sign(xd0),), False
            if forced_c:
                cand_c, free_c = (forced_c,), False
            elif cm == 0 or y[UD] == 0.0:
                cand_c, free_c = (0, 1, -1), True
            else:
                cand_c, free_c = (_sign(y[UD]),), False
            order = sorted(((cc, bb) for cc in cand_c for bb in cand_b), key=lambda k: (k[0] != 0, k[1] != 0))
            consistent = []
            preps, modes = {}, {}
            for cc, bb in order:
                if bb == 0:
                    acc = motion(p0, 0.0, 0, 0.0, cc)
                    need = acc[4]
                    lo, hi = B.edge(ub, -1), B.edge(ub, 1)
                    slack = _ULP4 * max(abs(lo), abs(hi), W)
                    if not (lo - slack <= need <= hi + slack):
                        continue
                else:
                    if bb not in preps:
                        preps[bb] = B.prepare(ub, Fb, y[V0:V0 + 4], sb, xd0, bb, pinned - force_unpin)
                        if preps[bb] is None and xd0 != 0.0:
                            raise RuntimeError(f"the slab moving in {bb:+d} at tau = {tau!r} finds every surface at its "
                                               f"restrainer (x = {float(y[X])!r}, the bearing's total travel)")
                    prep = preps[bb]
                    if prep is None:
                        continue
                    md = B.resolve(prep, lambda F, bb=bb, cc=cc, p0=p0, xd0=xd0: motion(p0, xd0, bb, F, cc)[0])
                    if md is None:
                        continue
                    acc = motion(p0, xd0, bb, md.F, cc)
                    if free_b and not bb * acc[0] > 0.0:
                        continue
                    modes[(cc, bb)] = md
                if cc == 0 and abs(acc[2]) > lim_c:
                    continue
                if cc != 0 and free_c and not cc * acc[1] > 0.0:
                    continue
                consistent.append((cc, bb))
            if not consistent:
                raise RuntimeError(f"no consistent modes at tau = {tau!r}, state {y[:4].tolist()!r}, "
                                   f"surfaces {ub.tolist()!r}, speeds {y[V0:V0 + 4].tolist()!r}")
            rivals = [(cc, bb) for cc, bb in consistent
                      if not ((cc and free_c and (0, bb) in consistent) or (bb and free_b and (cc, 0) in consistent))]
            ambiguous += len(rivals) > 1
            cm, bm = consistent[0]
            forced_b = forced_c = 0
            if cm == 0:
                y[UD] = 0.0
            if bm == 0:
                y[XD] = 0.0
                y[V0:V0 + 4] = 0.0
                sb = np.zeros(4, dtype=int)
                S = ()
                pinned = set()
            else:
                md = modes[(cm, bm)]
                v_prev = y[V0:V0 + 4].copy()
                S, sb, Fb = md.S, md.s, md.F
                y[V0:V0 + 4] = md.v
                new_pinned = set()
                for i in S:
                    if i in force_unpin:
                        continue
                    if i in pinned:          # its speed follows from the others': the law's split is void
                        if i in force_pin or B.a[i] * sb[i] * v_prev[i] >= A_UNPIN:
                            new_pinned.add(i)
                    elif i in force_pin or B.a[i] * sb[i] * md.v[i] >= A_PIN:
                        new_pinned.add(i)
                pinned = new_pinned
                if not pinned or xd0 == 0.0:
                    y[XD] = sum(float(md.v[i]) for i in S)
                else:
                    y[XD] = xd0
                    pinned = settle_pins(S, sb, ub, pinned, y, cm)
        force_pin, force_unpin = set(), set()
        new_stage = B.stage(S, ub)
        if new_stage != stage:
            stages.append((tau, new_stage))
            stage = new_stage
        if tau >= tau_end and bm == 0 and cm == 0:
            settled = True
            break
        if tau >= horizon:
            break
        # ---- the phase -------------------------------------------------------------------------
        nxt = [b for b in bps if b > tau]
        t_end = min(nxt[0] if nxt else horizon, horizon)
        t_clip = math.nextafter(t_end, -math.inf)
        t0 = tau
        n = len(S)
        s_ph = sb.copy()

        def p_of(t, t0=t0, t_clip=t_clip):
            return p_at(min(max(t, t0), t_clip))

        ph = _RatePhase(B, S, s_ph, ub, pinned, bm, cm, m, c, kin, p_of)
        rates, rhs = ph.rates, ph.rhs
        ph.margin = lambda yy, j, sj, ph=ph: B.qs[j] - sj * (ph.state(yy)[1] - W * ph.slopes(ph.state(yy)[0])[j])

        specs = []       # (guarded function or None, kind, raw function, its time rate from ph.rates)
        if bm:
            r0 = rates(t0, y)
            specs.append((_stop_value_event(bm, ph.speed, t0, float(y[XD]), r0[6]), "slab_stop",
                          lambda t, yy, ph=ph, bm=bm: bm * ph.speed(yy), lambda r, bm=bm: bm * r[6]))
            for i in S:
                si = int(s_ph[i])
                ai = float(B.a[i])
                if i in pinned:
                    specs.append((None, ("unpin", i),
                                  lambda t, yy, i=i, si=si, ai=ai, rates=rates: ai * si * rates(t, yy)[3][i] - A_UNPIN,
                                  None))
                else:
                    if n > 1:
                        specs.append((_stop_event(si, V0 + i, t0, float(y[V0 + i]), r0[4][i]), ("surface_stop", i),
                                      lambda t, yy, i=i, si=si: si * yy[V0 + i], lambda r, i=i, si=si: si * r[4][i]))
                    specs.append((None, ("pin", i), lambda t, yy, i=i, si=si, ai=ai: A_PIN - ai * si * yy[V0 + i],
                                  lambda r, i=i, si=si, ai=ai: -ai * si * r[4][i]))
                specs.append((None, ("stop", i, si), lambda t, yy, ph=ph, i=i, si=si: B.d[i] - si * ph.state(yy)[0][i],
                              lambda r, i=i, si=si: -si * r[3][i]))
            for j in range(4):
                if j in S:
                    continue
                for sj in (1, -1):
                    if sj * ub[j] >= B.d[j] - B.tol_u:
                        continue
                    specs.append((None, ("limit", j, sj), lambda t, yy, ph=ph, j=j, sj=sj: ph.margin(yy, j, sj),
                                  lambda r, ph=ph, j=j, sj=sj: -sj * (r[2] - W * ph.slopes(r[3])[j])))
        else:
            lo, hi = B.edge(ub, -1), B.edge(ub, 1)

            def need(t, cm=cm, p_of=p_of):
                p = p_of(t)
                return -(1.0 + m) * p if cm == 0 else -p + m * cm * kin

            if math.isfinite(hi):
                specs.append((lambda t, yy, hi=hi, need=need: hi - need(t), ("break", 1), None, None))
            if math.isfinite(lo):
                specs.append((lambda t, yy, lo=lo, need=need: need(t) - lo, ("break", -1), None, None))
        if cm == 0:
            if bm:
                def ab(t, yy, rates=rates):
                    return rates(t, yy)[8]

                def ab_rate(r):     # A_b = -(F + c x')/(1 + Pi8)
                    return -(r[2] + c * r[6]) / (1.0 + m)
            else:
                def ab(t, yy, p_of=p_of):
                    return p_of(t)
                ab_rate = None
            specs.append((None, ("slip", 1), lambda t, yy, ab=ab: lim_c - ab(t, yy),
                          None if ab_rate is None else (lambda r, ab_rate=ab_rate: -ab_rate(r))))
            specs.append((None, ("slip", -1), lambda t, yy, ab=ab: lim_c + ab(t, yy), ab_rate))
        else:
            udd0 = ph.rhs(t0, y)[UD]
            specs.append((_stop_event(cm, UD, t0, y[UD], udd0), "contents_stop",
                          lambda t, yy, cm=cm: cm * yy[UD], (lambda r, cm=cm: cm * r[7]) if bm else None))
        events = []
        for fn, kind_, raw, _ in specs:
            if fn is None:
                g0 = raw(t0, y)
                if isinstance(kind_, tuple) and kind_[0] == "limit":
                    # a held surface passing its slow level by 1e-10 of the slow-fast span; one resting on its
                    # level (an inner surface while its outer one is pinned) must move on by as much (the
                    # round-off of its reaction is no event)
                    off = (0.0 if g0 > 0.0 else g0) - 1e-10 * B.dq[kind_[1]]
                else:
                    off = min(0.0, g0)
                fn = (lambda t, yy, raw=raw, off=off: raw(t, yy) - off)
            fn.terminal, fn.direction = True, -1.0
            events.append(fn)
        method = "Radau" if n > 1 else "DOP853"
        if method == "Radau":
            kw = dict(method=method, rtol=rtol, atol=atol, max_step=hmax)
        else:       # cheap, and less far within its tolerance than Radau
            kw = dict(method=method, rtol=max(rtol * 1e-3, 1e-13), atol=atol * 1e-3, max_step=hmax)
        if method == "Radau":
            kw["jac"] = ph.jac
        sol = solve_ivp(rhs, (t0, t_end), y, events=events, **kw)
        nfev += sol.nfev
        if sol.status < 0:
            raise RuntimeError(f"solve_ivp failed: {sol.message}")
        kind = None
        if sol.status == 1:
            hits = [(te[0], ye[0], k) for k, (te, ye) in enumerate(zip(sol.t_events, sol.y_events, strict=True))
                    if len(te)]
            te, ye, k_ev = min(hits, key=lambda h: h[0])
            kind = specs[k_ev][1]
            if method == "Radau" and te > t0:
                # the collocation polynomial is less accurate than the steps: integrate to the event
                # from the last step and correct its time by Newton's rule on the event's function
                ta, ya = float(sol.t[-2]), sol.y[:, -2]
                if te > ta:
                    s2 = solve_ivp(rhs, (ta, te), ya, **kw)
                    nfev += s2.nfev
                    ye = s2.y[:, -1]
                raw, rate_fn = specs[k_ev][2], specs[k_ev][3]
                if raw is not None and rate_fn is not None:
                    for _ in range(4):
                        gdot = rate_fn(rates(te, ye))
                        if not (gdot != 0.0 and math.isfinite(gdot)):
                            break
                        dt = -raw(te, ye) / gdot
                        if not (math.isfinite(dt) and abs(dt) < hmax) or abs(dt) <= 4e-16 * max(1.0, abs(te)):
                            break
                        s2 = solve_ivp(rhs, (te, te + dt), ye, **kw)
                        nfev += s2.nfev
                        te, ye = te + dt, s2.y[:, -1]
            zero_len = zero_len + 1 if te <= t0 else 0
            if zero_len > 4:
                raise RuntimeError(f"zero-length phases at tau = {te!r}; building={building!r}")
            tau, y = float(te), np.array(ye, dtype=float)
        else:
            tau, y = t_end, np.array(sol.y[:, -1], dtype=float)
        if hist is not None:
            mask = sol.t <= tau
            tt, yy = sol.t[mask], sol.y[:, mask]
            if bm:
                bs = [ph.state(yy[:, k]) for k in range(tt.size)]
                FF = np.array([b_[1] for b_ in bs])
                UU = np.array([b_[0] for b_ in bs]).reshape(-1, 4)
                XD_ = np.array([ph.speed(yy[:, k]) for k in range(tt.size)])
            else:
                FF = np.array([motion(p_of(t), 0.0, 0, 0.0, cm)[4] for t in tt])
                UU = np.repeat(ub[None, :], tt.size, axis=0)
                XD_ = np.zeros(tt.size)
            hh = yy[:4].copy()
            hh[XD] = XD_
            hist.append((tt, hh, FF, UU))
        # ---- the bearing at the phase's end -------------------------------------------------------
        if bm:
            r_end = rates(tau, y)
            u_end, F_end = r_end[0], r_end[1]
            ub = np.array(u_end)
            Fb = F_end
            for i in pinned:
                y[V0 + i] = r_end[3][i]
            if not pinned:
                y[XD] = ph.speed(y)
        else:
            F_end = motion(p_of(tau), 0.0, 0, 0.0, cm)[4]
        if kind is not None:
            n_events += 1
            p = p_at(tau)
            if bm and kind != "slab_stop" and all(abs(y[V0 + i]) <= _V_TINY for i in S):
                kind = "slab_stop"          # the last sliding surfaces stop with the slab
            if isinstance(kind, tuple) and kind[0] == "stop":
                ub[kind[1]] = kind[2] * B.d[kind[1]]
            elif kind == "slab_stop":
                x_peak = max(x_peak, abs(float(y[X])))
                v = y[V0:V0 + 4]
                if len({int(sb[i]) for i in S if sb[i] * v[i] > _V_TINY}) > 1:
                    # surfaces sliding in opposite directions carry on: the slab turns without stopping
                    xdd_t = rates(tau, y)[6]
                    if xdd_t == 0.0:
                        raise RuntimeError(f"the slab stops at tau = {tau!r} with no acceleration while surfaces "
                                           f"slide in opposite directions (speeds {v.tolist()!r})")
                    keep = _sign(xdd_t)
                else:
                    y[XD] = 0.0
                    y[V0:V0 + 4] = 0.0
            elif kind == "contents_stop":
                y[UD] = 0.0
                if abs(y[U]) > peak:
                    peak, tau_peak = abs(float(y[U])), tau
            elif isinstance(kind, tuple) and kind[0] == "pin":
                force_pin.add(kind[1])
            elif isinstance(kind, tuple) and kind[0] == "unpin":
                force_unpin.add(kind[1])
            elif isinstance(kind, tuple) and kind[0] == "break":
                forced_b = kind[1]
            elif isinstance(kind, tuple) and kind[0] == "slip":
                Ab = motion(p, float(y[XD]), bm, Fb, 0)[2] if bm else p
                forced_c = -_sign(Ab)
        vertex(tau, y, F_end, stage, sb if bm else np.zeros(4, dtype=int))

    if abs(y[U]) > peak:
        peak, tau_peak = abs(float(y[U])), tau
    x_peak = max(x_peak, abs(float(y[X])))
    peak_stage = max(s for _, s in stages)
    cols = list(zip(*vert, strict=True))
    vertices = {"tau": np.array(cols[0]), "x": np.array(cols[1]), "xd": np.array(cols[2]), "u": np.array(cols[3]),
                "ud": np.array(cols[4]), "F": np.array(cols[5]), "surfaces": np.array(cols[6]),
                "stage": np.array(cols[7], dtype=int), "sliding": np.array(cols[8], dtype=int),
                "energy": np.array(cols[9])}
    h = None
    if hist is not None:
        h = {"tau": np.concatenate([a_ for a_, _, _, _ in hist]) if hist else np.array([tau])}
        yy = np.concatenate([b_ for _, b_, _, _ in hist], axis=1) if hist else y[:4, None]
        for k, name in enumerate(("x", "xd", "u", "ud")):
            h[name] = yy[k].copy()
        h["F"] = np.concatenate([f_ for _, _, f_, _ in hist]) if hist else np.zeros(1)
        h["surfaces"] = np.concatenate([u_ for _, _, _, u_ in hist]) if hist else ub[None, :]
    return TFPRun(pi1=float(peak), pi1_residual=float(y[U]), tau_peak=float(tau_peak), x_peak=float(x_peak),
                  peak_stage=int(peak_stage), stages=tuple(stages), settled=settled, tau_end=float(tau),
                  n_events=n_events, ambiguous=ambiguous, nfev=nfev, vertices=vertices, history=h)
