r"""The triple friction pendulum bearing: parameters and the closed-form quasi-static behaviour.

Conventions (those of OpenSees's ``TripleFrictionPendulum`` element)
--------------------------------------------------------------------
The bearing has four concave sliding surfaces, numbered bottom to top: surface 1 (outer, effective
radius ``L2``, friction ``mu2``, limit ``d2``), surfaces 2 and 3 (the two identical inner surfaces of
the articulated slider: radius ``L1``, friction ``mu1``, limit ``d1`` each) and surface 4 (outer,
``L3``, ``mu3``, ``d3``).  Radii are effective radii ``L = R - h`` (m), so that the displacement on a
surface is its effective radius times the rotation of the part sliding on it.  The limits ``d`` are
OpenSees's: the largest travel ``|u_i| <= d`` of the slider relative to that surface, in the same
(effective) measure as the total displacement ``u = u_1 + u_2 + u_3 + u_4``; in OpenSees's series
model the outer gap elements close at ``d2 (1 - L1/L2)`` and ``d3 (1 - L1/L3)``, which is
``|u_1| = d2`` and ``|u_4| = d3``, and ``TripleFrictionPendulumX`` clamps ``|u_1| <= d2``,
``|u_2|, |u_3| <= d1``, ``|u_4| <= d3``.  The restrainers are rigid.  ``W`` is the weight on the
bearing (N); ``W = 1`` gives forces per unit weight.

The mechanics (Fenz and Constantinou 2008)
------------------------------------------
Every surface transmits the same horizontal force ``F`` (the slide plates and the slider carry no
other horizontal load; their inertia is neglected).  The force through a surface is the weight times
the slope of that surface's normal where the load passes, plus the friction and restrainer reaction
``q_i`` of that surface.  The slide plate on surface 1 rotates with it by ``u_1/L2`` and carries
surface 2, so surface 2's slope is ``u_1/L2 + u_2/L1``; likewise surface 3 rides on the plate of
surface 4::

    F = W u_1/L2 + q_1              q_1 = W u_2/L1 + q_2
    F = W u_4/L3 + q_4              q_4 = W u_3/L1 + q_3

with ``|q_i| <= mu_i W`` while surface ``i`` sticks (true stick: ``u_i`` constant), ``q_i = mu_i W
sign(du_i)`` while it slides, and any excess taken by the restrainer when ``|u_i| = d_i``.  The inner
surface 2 is thus driven by the reaction ``q_1`` of surface 1, which is pinned at ``mu2 W`` while
surface 1 slides: that is why surface 2 stops when surface 1 starts (regime II) and slides again
once surface 1 rests on its restrainer (regime IV).  At most two surfaces slide at a time.

On first loading from rest (``F`` rising from 0; ``f = F/W``) every surface follows
``u = L clip(drive/W - mu, 0, d/L)``: ``u_1 = L2 clip(f - mu2, 0, d2/L2)``,
``u_4 = L3 clip(f - mu3, 0, d3/L3)``, ``u_2 = L1 clip(q_1/W - mu1, 0, d1/L1)`` with
``q_1/W = f - u_1/L2``, and ``u_3`` likewise with ``q_4``.  Summing gives the backbone.

The backbone: five regimes
--------------------------
Force levels ``f = F/W`` at which the regimes change: ``mu1`` (the inner surfaces start), ``mu2``
(surface 1 starts), ``mu3`` (surface 4 starts), ``f_dr1 = mu2 + d2/L2`` (surface 1 reaches its
restrainer), ``f_dr4 = mu3 + d3/L3`` (surface 4 reaches its restrainer) and
``f_cap = mu1 + d1/L1 + min(d2/L2, d3/L3)`` (the first inner surface reaches its restrainer: surface
2 at ``mu1 + d1/L1 + d2/L2``, surface 3 at ``mu1 + d1/L1 + d3/L3``).  Each regime's tangent stiffness
is ``W`` over the sum of the radii of the two sliding surfaces, and ``F = K u + b`` with

=====  ====================  =========================  ==========================================
stage  sliding surfaces      stiffness ``K``            valid for ``u`` in
=====  ====================  =========================  ==========================================
I      2 and 3               ``W / (2 L1)``             ``0 < u <= u*``,
                                                        ``u* = 2 L1 (mu2 - mu1)``
II     1 and 3               ``W / (L1 + L2)``          ``u* < u <= u**``,
                                                        ``u** = u* + (L1 + L2)(mu3 - mu2)``
III    1 and 4               ``W / (L2 + L3)``          ``u** < u <= u_dr1``,
                                                        ``u_dr1 = u** + (L2 + L3)(f_dr1 - mu3)``
IV     2 and 4 (1 stopped)   ``W / (L1 + L3)``          ``u_dr1 < u <= u_dr4``,
                                                        ``u_dr4 = u_dr1 + (L1 + L3)(f_dr4 - f_dr1)``
V      2 and 3 (1, 4         ``W / (2 L1)``             ``u_dr4 < u <= u_cap``,
       stopped)                                         ``u_cap = u_dr4 + 2 L1 (f_cap - f_dr4)``
=====  ====================  =========================  ==========================================

and intercepts ``b = F_k - K u_k`` at each regime's start ``(u_k, F_k)``: ``b_I = mu1 W``,
``b_II = W (mu2 - u*/(L1 + L2)) = W (mu2 (L2 - L1) + 2 mu1 L1)/(L1 + L2)``,
``b_III = W (mu3 - u**/(L2 + L3))``, ``b_IV = W (f_dr1 - u_dr1/(L1 + L3))``,
``b_V = W (f_dr4 - u_dr4/(2 L1))``.  Expanded, ``u_dr1 = u** + d2 (1 + L3/L2) - (mu3 - mu2)(L2 + L3)``
and ``u_dr4 = u_dr1 + (d3/L3 + mu3 - d2/L2 - mu2)(L1 + L3)``, the expressions of Fenz and
Constantinou's regime table (as coded in OpenSees's ``TripleFrictionPendulumX``).  The backbone is
odd: ``F(-u) = -F(u)``.

The admissible set
------------------
The five regimes come in this order exactly when ``mu1 <= mu2 <= mu3 <= f_dr1 <= f_dr4 <= f_cap``
(equalities give regimes of zero length, which are skipped), i.e.

* ``mu1 <= mu2 <= mu3`` (the usual ``mu1 < mu2 <= mu3``; equal values allowed);
* ``d2/L2 >= mu3 - mu2``: surface 1 does not reach its restrainer before surface 4 starts;
* ``mu2 + d2/L2 <= mu3 + d3/L3``: surface 1 reaches its restrainer first;
* ``d1/L1 >= mu3 - mu1`` and ``mu3 + d3/L3 <= mu1 + d1/L1 + d2/L2``: neither inner surface reaches
  its restrainer before regime V.

With a velocity-dependent law each condition must hold at every speed; it is checked over all speeds
(exactly: each is a difference of two exponentials).  Fenz and Constantinou's three-element series
model (OpenSees's element: radii ``2 L1``, ``L2 - L1``, ``L3 - L1``) reproduces this backbone and
these loops when in addition ``L2 > L1`` and ``L3 > L1`` (:meth:`TripleFrictionPendulum.series_elements`);
the closed forms below do not need it.  With all radii and frictions equal the inner surfaces never
slide (their drive ``q_1 = mu W`` never exceeds their strength) and the bearing is a single friction
pendulum of radius ``L2 + L3``.

Cyclic loops
------------
Unloading from a point of the backbone at force ``F_A`` every surface obeys the same rule in reverse,
``u_i = max(-d_i, min(u_i^A, L_i (drive/W + mu_i)))``, with the drive of an outer surface ``F`` and
of an inner one the reaction of its outer surface, which is non-decreasing in ``F`` along the branch.
So the loop first drops vertically by ``2 mu1 W`` (every surface sticks), then the inner surfaces
slide back (stiffness of regime I), and the regimes re-enter in order with friction reversed.  For
an amplitude in regimes I to III this is Masing's rule, ``F_down(u) = F_A - 2 F_backbone((u_A - u)/2)``.
From regimes IV and V a restrainer first unloads: surface 1 leaves its restrainer at
``F = W (d2/L2 - mu2)`` and surface 4 at ``W (d3/L3 - mu3)``, and in between the surfaces that
re-start are those whose reversal comes first (regime I, then II or IV, ...).  The branch ends at
``(-u_A, -F_A)`` and the reloading branch is its mirror image, so the loop closes after one cycle.

Units: lengths m, forces N (or per unit weight with ``W = 1``), speeds m/s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from .validation import check_range

STAGES = (1, 2, 3, 4, 5)
"""The regimes I..V as ints; 0 marks a stretch where every surface sticks (a vertical drop of the loop)."""

STAGE_NAMES = {0: "stuck", 1: "I", 2: "II", 3: "III", 4: "IV", 5: "V"}
"""Roman numeral of each regime number."""

_ROUNDING = 1e-12
"""Round-off allowed in the admissibility conditions (friction coefficients and ``d/L``, both O(0.1))."""


def _triple(name: str, value, lo: float, lo_in: bool, names=None) -> tuple:
    """Three checked floats (one value is repeated), named ``name1..name3`` in errors."""
    vals = value if isinstance(value, (tuple, list, np.ndarray)) else (value,)
    if len(vals) == 1:
        vals = tuple(vals) * 3
    if len(vals) != 3:
        raise ValueError(f"{name} = {value!r} must be one value or three; got {len(vals)}")
    names = names or [f"{name}{i}" for i in (1, 2, 3)]
    return tuple(check_range(n, v, lo, math.inf, lo_in, False) for n, v in zip(names, vals, strict=True))


@dataclass(frozen=True)
class TripleFrictionPendulum:
    """A triple friction pendulum bearing (OpenSees's parameters), checked on construction.

    Parameters
    ----------
    L : tuple of float
        Effective radii ``(L1, L2, L3)``, m: ``L1`` of each inner surface (2 and 3), ``L2`` of
        surface 1, ``L3`` of surface 4 (> 0).
    mu : tuple of float
        Friction coefficients ``(mu1, mu2, mu3)`` of the same surfaces (>= 0); with a velocity law,
        the fast (high-speed) values.
    d : tuple of float
        Displacement limits ``(d1, d2, d3)``, m: the largest travel of the slider on each surface
        (> 0).
    W : float
        Weight on the bearing, N (> 0); 1 gives forces per unit weight.
    mu_slow : tuple of float or None
        Slow-speed friction of the law ``mu(v) = mu_fast - (mu_fast - mu_slow) exp(-rate |v|)``,
        one value or three (``<= mu``); None: constant friction.
    rate : tuple of float or None
        ``rate`` of that law, s/m, one value or three (> 0); only with ``mu_slow``.

    Raises
    ------
    ValueError
        Naming the parameter, its value and the rule it breaks: non-positive radii, limits or
        weight; negative or non-finite friction; ``mu_slow > mu``; a friction ordering or geometry
        outside the five regimes in order (the admissible set of the module docstring).
    """

    L: tuple
    mu: tuple
    d: tuple
    W: float = 1.0
    mu_slow: tuple | None = None
    rate: tuple | None = None

    def __post_init__(self):
        set_ = object.__setattr__
        set_(self, "L", _triple("L", self.L, 0.0, False))
        set_(self, "d", _triple("d", self.d, 0.0, False))
        set_(self, "mu", _triple("mu", self.mu, 0.0, True))
        set_(self, "W", check_range("W", self.W, 0.0, math.inf, False, False))
        if self.mu_slow is None:
            if self.rate is not None:
                raise ValueError(f"rate = {self.rate!r} is given without mu_slow; allowed: rate = None "
                                 "for constant friction, or mu_slow with rate > 0")
        else:
            slow = _triple("mu_slow", self.mu_slow, 0.0, True)
            for i, (s, f) in enumerate(zip(slow, self.mu, strict=True), start=1):
                if s > f:
                    raise ValueError(f"mu_slow{i} = {s!r} exceeds mu{i} = {f!r}; the law mu(v) = mu_fast - "
                                     "(mu_fast - mu_slow) exp(-rate |v|) needs mu_slow <= mu_fast")
            if self.rate is None:
                raise ValueError("rate = None with mu_slow given; allowed: rate > 0 (s/m), one value or three")
            set_(self, "mu_slow", slow)
            set_(self, "rate", _triple("rate", self.rate, 0.0, False))
        self._check_sequence()

    # -- friction -----------------------------------------------------------------------------

    def friction(self, v: float = math.inf) -> tuple:
        """Friction coefficients ``(mu1, mu2, mu3)`` at sliding speed ``v`` (m/s; default: fast)."""
        if self.mu_slow is None:
            return self.mu
        v = abs(float(v))
        return tuple(f - (f - s) * math.exp(-r * v) for f, s, r in zip(self.mu, self.mu_slow, self.rate, strict=True))

    def at_speed(self, v: float) -> TripleFrictionPendulum:
        """The constant-friction bearing with the friction of speed ``v`` (m/s)."""
        return TripleFrictionPendulum(self.L, self.friction(v), self.d, self.W)

    def _difference_range(self, j: int, i: int) -> tuple:
        """Least and greatest ``mu_j(v) - mu_i(v)`` over ``v >= 0`` (indices 0..2 of ``mu``).

        ``g(v) = a - b exp(-r_j v) + c exp(-r_i v)`` has at most one stationary point, where
        ``b r_j exp(-r_j v) = c r_i exp(-r_i v)``; its extremes are among ``v = 0``, ``v -> inf`` and
        that point.
        """
        fj, fi = self.mu[j], self.mu[i]
        if self.mu_slow is None:
            return fj - fi, fj - fi
        b, c = fj - self.mu_slow[j], fi - self.mu_slow[i]
        rj, ri = self.rate[j], self.rate[i]

        def g(v):
            return (fj - b * math.exp(-rj * v)) - (fi - c * math.exp(-ri * v))

        values = [g(0.0), fj - fi]
        if b > 0.0 and c > 0.0 and rj != ri:
            v = math.log(c * ri / (b * rj)) / (ri - rj)
            if v > 0.0 and math.isfinite(v):
                values.append(g(v))
        return min(values), max(values)

    def _check_sequence(self):
        """Raise ValueError unless the regimes I..V come in order (the admissible set)."""
        (L1, L2, L3), (d1, d2, d3) = self.L, self.d
        mu1, mu2, mu3 = self.mu
        lo21, _ = self._difference_range(1, 0)
        lo32, hi32 = self._difference_range(2, 1)
        _, hi31 = self._difference_range(2, 0)
        speeds = " at every speed" if self.mu_slow is not None else ""
        eps = _ROUNDING
        if lo21 < -eps:
            raise ValueError(f"mu1 = {mu1!r} exceeds mu2 = {mu2!r}{speeds}; the five regimes need mu1 <= mu2 "
                             "<= mu3 (the inner surfaces slide first, then surface 1, then surface 4)")
        if lo32 < -eps:
            raise ValueError(f"mu2 = {mu2!r} exceeds mu3 = {mu3!r}{speeds}; the five regimes need mu1 <= mu2 "
                             "<= mu3 (the inner surfaces slide first, then surface 1, then surface 4)")
        if d2 / L2 < hi32 - eps:
            raise ValueError(f"d2 = {d2!r} is too small: surface 1 would reach its restrainer before surface 4 "
                             f"slides; allowed: d2/L2 >= mu3 - mu2{speeds} (d2 >= {hi32 * L2:g})")
        if d3 / L3 - d2 / L2 < -lo32 - eps:
            raise ValueError(f"d3 = {d3!r} is too small: surface 4 would reach its restrainer before surface 1; "
                             f"allowed: mu2 + d2/L2 <= mu3 + d3/L3{speeds} (d3 >= {(d2 / L2 - lo32) * L3:g})")
        if d1 / L1 < hi31 - eps:
            raise ValueError(f"d1 = {d1!r} is too small: surface 3 would reach its restrainer before regime V; "
                             f"allowed: d1/L1 >= mu3 - mu1{speeds} (d1 >= {hi31 * L1:g})")
        if d1 / L1 + d2 / L2 - d3 / L3 < hi31 - eps:
            need = (hi31 - d2 / L2 + d3 / L3) * L1
            raise ValueError(f"d1 = {d1!r} is too small: surface 2 would reach its restrainer before surface 4 "
                             f"reaches its own; allowed: mu3 + d3/L3 <= mu1 + d1/L1 + d2/L2{speeds} "
                             f"(d1 >= {need:g})")

    # -- the series model ------------------------------------------------------------------------

    def series_elements(self) -> tuple:
        """Fenz and Constantinou's three elements in series (OpenSees's ``TripleFrictionPendulum``).

        Each element ``k`` is a friction pendulum of radius ``R_k``, friction ``mu_k`` and travel
        limit ``c_k``, all carrying the same force: the inner pair ``(2 L1, mu1, 2 L1 (f_cap - mu1))``,
        ``(L2 - L1, mu2, d2 (1 - L1/L2))`` and ``(L3 - L1, mu3, d3 (1 - L1/L3))``.  OpenSees closes
        the inner element at ``2 (d1 + L1 d3/L3)``, which is ``2 L1 (f_cap - mu1)`` when
        ``d3/L3 <= d2/L2`` (surface 3 locks first); otherwise surface 2 locks first, at the
        smaller travel used here.

        Returns
        -------
        tuple of (R, mu, c)
            Radius (m), friction coefficient and travel limit (m) of each element.

        Raises
        ------
        ValueError
            When ``L2 <= L1`` or ``L3 <= L1`` (an element of non-positive radius).
        """
        (L1, L2, L3), (d1, d2, d3), (mu1, mu2, mu3) = self.L, self.d, self.mu
        for name, Lo in (("L2", L2), ("L3", L3)):
            if Lo <= L1:
                raise ValueError(f"{name} = {Lo!r} is not above L1 = {L1!r}; the series model's outer element "
                                 f"has radius {name} - L1, allowed: {name} > L1")
        f_cap = mu1 + d1 / L1 + min(d2 / L2, d3 / L3)
        return ((2.0 * L1, mu1, 2.0 * L1 * (f_cap - mu1)), (L2 - L1, mu2, d2 * (1.0 - L1 / L2)),
                (L3 - L1, mu3, d3 * (1.0 - L1 / L3)))


class Boundaries(NamedTuple):
    """Where the backbone's regimes change (displacements m, forces N).

    ``u[k]`` and ``F[k]`` are the start of regime ``k + 1`` (``u[0] = 0``, ``F[0] = mu1 W``); ``u[5]``,
    ``F[5]`` the capacity.  The named fields repeat them: ``u_star`` (I to II), ``u_2star`` (II to III),
    ``u_dr1`` (III to IV), ``u_dr4`` (IV to V), ``u_capacity`` (the first inner restrainer).
    """

    u: tuple
    F: tuple
    u_star: float
    u_2star: float
    u_dr1: float
    u_dr4: float
    u_capacity: float


def regime_boundaries(bearing: TripleFrictionPendulum) -> Boundaries:
    """The displacements and forces where the backbone's regimes change (module docstring)."""
    (L1, L2, L3), (d1, d2, d3), (mu1, mu2, mu3) = bearing.L, bearing.d, bearing.mu
    f = (mu1, mu2, mu3, mu2 + d2 / L2, mu3 + d3 / L3, mu1 + d1 / L1 + min(d2 / L2, d3 / L3))
    sums = (2.0 * L1, L1 + L2, L2 + L3, L1 + L3, 2.0 * L1)
    u = [0.0]
    for k in range(5):
        u.append(u[-1] + sums[k] * (f[k + 1] - f[k]))
    F = tuple(bearing.W * x for x in f)
    return Boundaries(tuple(u), F, u[1], u[2], u[3], u[4], u[5])


def regime_stiffness(bearing: TripleFrictionPendulum, stage: int) -> float:
    """Tangent stiffness ``W / (sum of the two sliding radii)`` of regime ``stage`` (1..5), N/m."""
    L1, L2, L3 = bearing.L
    sums = {1: 2.0 * L1, 2: L1 + L2, 3: L2 + L3, 4: L1 + L3, 5: 2.0 * L1}
    if stage not in sums:
        raise ValueError(f"stage = {stage!r} is invalid; allowed: {STAGES}")
    return bearing.W / sums[stage]


def regime_intercept(bearing: TripleFrictionPendulum, stage: int) -> float:
    """Force intercept ``b`` of regime ``stage`` (1..5) on the positive backbone ``F = K u + b``, N."""
    b = regime_boundaries(bearing)
    k = regime_stiffness(bearing, stage)
    return b.F[stage - 1] - k * b.u[stage - 1]


def capacity(bearing: TripleFrictionPendulum) -> float:
    """Displacement capacity of the closed forms, m: the first inner surface reaches its restrainer."""
    return regime_boundaries(bearing).u_capacity


def _check_amplitude(bearing, u) -> np.ndarray:
    u = np.asarray(u, dtype=float)
    if not np.all(np.isfinite(u)):
        raise ValueError(f"u = {u!r} is not finite")
    cap = capacity(bearing)
    big = np.abs(u) > cap * (1.0 + 1e-12)
    if np.any(big):
        raise ValueError(f"u = {float(np.abs(u)[big].max())!r} exceeds the displacement capacity {cap!r} m "
                         "(an inner surface at its restrainer ends regime V); allowed: |u| <= capacity")
    return u


def force(bearing: TripleFrictionPendulum, u):
    """Backbone force on first loading from rest and its regime, closed form.

    Parameters
    ----------
    bearing : TripleFrictionPendulum
    u : float or array
        Displacement of the top relative to the bottom, m, ``|u| <= capacity(bearing)``.

    Returns
    -------
    F : float or array
        Force, N: ``F = K_k u + b_k`` in regime ``k`` for ``u > 0``, odd in ``u``; 0 at ``u = 0``
        (at rest; the force rises to ``mu1 W`` before anything slides).
    stage : int or array of int
        Regime 1..5 (regime ``k`` holds for ``u_{k-1} < |u| <= u_k``; regimes of zero length are
        never returned); 0 at ``u = 0``.

    Raises
    ------
    ValueError
        When ``|u|`` exceeds the capacity.
    """
    arr = _check_amplitude(bearing, u)
    b = regime_boundaries(bearing)
    a = np.abs(arr)
    stage = np.searchsorted(np.asarray(b.u), a, side="left").clip(1, 5)
    stage = np.where(a == 0.0, 0, stage)
    Fk = np.asarray(b.F)[np.maximum(stage - 1, 0)]
    uk = np.asarray(b.u)[np.maximum(stage - 1, 0)]
    K = np.array([0.0] + [regime_stiffness(bearing, s) for s in STAGES])[stage]
    F = np.where(stage == 0, 0.0, np.sign(arr) * (Fk + K * (a - uk)))
    if np.ndim(u) == 0:
        return float(F), int(stage)
    return F, stage


def peak_regime(bearing: TripleFrictionPendulum, amplitude: float) -> int:
    """The regime (1..5) the backbone is in at displacement ``amplitude`` (m; 0 at 0).

    Raises
    ------
    ValueError
        When ``|amplitude|`` exceeds the capacity.
    """
    return force(bearing, float(amplitude))[1]


def _surfaces_backbone(bearing, f: float) -> np.ndarray:
    """Displacements ``(u_1, u_2, u_3, u_4)`` on the backbone at force ``f = F/W >= 0``."""
    (L1, L2, L3), (d1, d2, d3), (mu1, mu2, mu3) = bearing.L, bearing.d, bearing.mu
    u1 = L2 * min(max(f - mu2, 0.0), d2 / L2)
    u4 = L3 * min(max(f - mu3, 0.0), d3 / L3)
    u2 = L1 * min(max(f - u1 / L2 - mu1, 0.0), d1 / L1)
    u3 = L1 * min(max(f - u4 / L3 - mu1, 0.0), d1 / L1)
    return np.array([u1, u2, u3, u4])


def _surfaces_down(bearing, f: float, start: np.ndarray) -> np.ndarray:
    """Displacements on the unloading branch at ``f = F/W`` from the backbone state ``start``."""
    (L1, L2, L3), (d1, d2, d3), (mu1, mu2, mu3) = bearing.L, bearing.d, bearing.mu
    u1 = max(-d2, min(start[0], L2 * (f + mu2)))
    u4 = max(-d3, min(start[3], L3 * (f + mu3)))
    u2 = max(-d1, min(start[1], L1 * (f - u1 / L2 + mu1)))
    u3 = max(-d1, min(start[2], L1 * (f - u4 / L3 + mu1)))
    return np.array([u1, u2, u3, u4])


def _stage_of(moving: tuple, at_stop: tuple) -> int:
    """Regime number of a stretch from the surfaces that move and the outer ones at a restrainer.

    The inner pair sliding is regime V when both outer surfaces rest on their restrainers, else I.
    """
    if not moving:
        return 0
    if moving == (1, 2):
        return 5 if all(at_stop) else 1
    return {(0, 2): 2, (0, 3): 3, (1, 3): 4}.get(moving, -1)


class Loop(NamedTuple):
    """A piecewise-linear force-displacement path: its vertices and the regime of each stretch.

    ``u`` (m) and ``F`` (N) are the vertices in order; ``stage[k]`` is the regime of the stretch
    from vertex ``k - 1`` to vertex ``k`` (``stage[0] = 0``; 0 for a vertical stretch where every
    surface sticks; the inner pair sliding is V with both outer surfaces at their restrainers, else I;
    -1 for other sets of sliding surfaces); ``surfaces[k]`` the displacements ``(u_1, u_2, u_3, u_4)`` at vertex ``k``.
    """

    u: np.ndarray
    F: np.ndarray
    stage: np.ndarray
    surfaces: np.ndarray


def _polyline(bearing, fs, states) -> tuple:
    """Vertices (u, F), stages and surface states along force levels ``fs`` (duplicates dropped)."""
    d2, d3 = bearing.d[1], bearing.d[2]
    us, Fs, stages, surf = [], [], [], []
    for f, s in zip(fs, states, strict=True):
        if surf and abs(f * bearing.W - Fs[-1]) <= 1e-14 * bearing.W and np.allclose(s, surf[-1], 0.0, 1e-15):
            continue
        if surf:
            delta = s - surf[-1]
            scale = max(bearing.d) * 1e-12
            moving = tuple(i for i in range(4) if abs(delta[i]) > scale)
            mid = 0.5 * (s + surf[-1])
            stop = (abs(abs(mid[0]) - d2) <= scale, abs(abs(mid[3]) - d3) <= scale)
            stages.append(_stage_of(moving, stop))
        else:
            stages.append(0)
        us.append(float(s.sum()))
        Fs.append(f * bearing.W)
        surf.append(s)
    return us, Fs, stages, surf


def backbone(bearing: TripleFrictionPendulum, amplitude: float) -> Loop:
    """The backbone from rest to ``amplitude`` (m, ``>= 0``) as vertices, closed form.

    Raises
    ------
    ValueError
        When ``amplitude`` exceeds the capacity.
    """
    A = float(_check_amplitude(bearing, amplitude))
    if A < 0.0:
        raise ValueError(f"amplitude = {amplitude!r} is negative; allowed: 0 <= amplitude <= capacity")
    b = regime_boundaries(bearing)
    FA = force(bearing, A)[0] if A > 0.0 else b.F[0]
    fs = [0.0] + [F / bearing.W for F, u in zip(b.F, b.u, strict=True) if u < A] + [FA / bearing.W]
    states = [np.zeros(4)] + [_surfaces_backbone(bearing, f) for f in fs[1:]]
    us, Fs, stages, surf = _polyline(bearing, fs, states)
    return Loop(np.array(us), np.array(Fs), np.array(stages), np.array(surf))


def unloading_branch(bearing: TripleFrictionPendulum, amplitude: float) -> Loop:
    """The branch from ``(A, F(A))`` on the backbone down to ``(-A, -F(A))``, closed form.

    Every surface follows ``max(-d, min(u^A, L (drive/W + mu)))`` (module docstring); the vertices
    are the force levels where one of these clauses changes, and the branch is linear in between.

    Raises
    ------
    ValueError
        When ``amplitude`` exceeds the capacity or is not positive.
    """
    A = float(_check_amplitude(bearing, amplitude))
    if A <= 0.0:
        raise ValueError(f"amplitude = {amplitude!r} is not positive; allowed: 0 < amplitude <= capacity")
    (L1, L2, L3), (d1, d2, d3), (mu1, mu2, mu3) = bearing.L, bearing.d, bearing.mu
    fA = force(bearing, A)[0] / bearing.W
    start = _surfaces_backbone(bearing, fA)
    levels = {fA, -fA, start[0] / L2 - mu2, -d2 / L2 - mu2, start[3] / L3 - mu3, -d3 / L3 - mu3}
    for u_inner, u_outer, Lo, mo, do in ((start[1], start[0], L2, mu2, d2), (start[2], start[3], L3, mu3, d3)):
        for q in (u_inner / L1 - mu1, -d1 / L1 - mu1):    # the inner clause changes at drive q
            levels.add(q + u_outer / Lo if q > -mo else q - do / Lo)
    fs = sorted((f for f in levels if -fA <= f <= fA), reverse=True)
    states = [_surfaces_down(bearing, f, start) for f in fs]
    us, Fs, stages, surf = _polyline(bearing, fs, states)
    return Loop(np.array(us), np.array(Fs), np.array(stages), np.array(surf))


def cyclic_loop(bearing: TripleFrictionPendulum, amplitude: float) -> Loop:
    """The quasi-static loop from rest: backbone to ``A``, down to ``-A``, back up to ``A``.

    Closed form (module docstring): the backbone, the unloading branch and its mirror image as
    the reloading branch; the loop closes at ``(A, F(A))``.

    Parameters
    ----------
    bearing : TripleFrictionPendulum
        Constant friction ``bearing.mu`` is used (see :meth:`TripleFrictionPendulum.at_speed`).
    amplitude : float
        Displacement amplitude ``A``, m, ``0 < A <= capacity(bearing)``.

    Raises
    ------
    ValueError
        When ``A`` exceeds the capacity (beyond it the closed forms do not hold) or is not positive.
    """
    up = backbone(bearing, amplitude)
    down = unloading_branch(bearing, amplitude)
    cat = [np.concatenate([up[k], down[k][1:], -down[k][1:]]) for k in range(2)]
    stage = np.concatenate([up.stage, down.stage[1:], down.stage[1:]])
    surf = np.concatenate([up.surfaces, down.surfaces[1:], -down.surfaces[1:]])
    return Loop(cat[0], cat[1], stage, surf)


def loop_force(bearing: TripleFrictionPendulum, amplitude: float, u, branch: str = "down"):
    """Force (N) on the ``"down"`` (unloading) or ``"up"`` (reloading) branch of the loop at ``u`` (m).

    At ``u = A`` the unloading branch gives the force after the vertical drop of ``2 mu1 W``
    (likewise ``-A`` on the reloading branch).
    """
    if branch not in ("down", "up"):
        raise ValueError(f"branch = {branch!r} is invalid; allowed: ('down', 'up')")
    down = unloading_branch(bearing, amplitude)
    x = np.asarray(u, dtype=float)
    if np.any(np.abs(x) > amplitude * (1.0 + 1e-12)):
        raise ValueError(f"u outside the loop's range [-{amplitude!r}, {amplitude!r}]")
    uu, FF = down.u[1:][::-1], down.F[1:][::-1]        # increasing u, past the vertical drop
    F = np.interp(x, uu, FF) if branch == "down" else -np.interp(-x, uu, FF)
    return float(F) if np.ndim(u) == 0 else F


def dissipated_energy(bearing: TripleFrictionPendulum, amplitude: float) -> float:
    """Energy dissipated in one cycle of amplitude ``A`` (J): the area of the loop.

    The area is ``-2`` times the integral of ``F_down du`` over ``[-A, A]``, because the

    reloading branch is the mirror image of the unloading one, ``F_up(u) = -F_down(-u)``.
    """
    down = unloading_branch(bearing, amplitude)
    u, F = down.u[1:], down.F[1:]
    return float(-2.0 * np.sum(0.5 * (F[1:] + F[:-1]) * (u[:-1] - u[1:])))
