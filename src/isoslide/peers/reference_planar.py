"""Independent event-driven reference solver of contents sliding in the plane of the floor.

The planar sibling of :mod:`isoslide.peers.reference_building`: the same buildings (fixed base, or
a linear isolator or a sliding bearing under a rigid superstructure or a flexible shear building of
``N`` storeys),
moved by two horizontal ground components and optionally a vertical one, carry contents that
slide in any direction on their floor.  The right-hand side is plain Python + NumPy, integrated
segment by segment with :func:`scipy.integrate.solve_ivp` (``DOP853``, and ``Radau`` for slow
slips, see below) and every transition located with ``solve_ivp``'s events; nothing comes from the
compiled kernel (:mod:`isoslide.engine`), so the two can check each other.  The sliding bearing
(friction pendulum, ``Pi9 > 0`` with ``Pi10 = 0``) is a second friction interface in the plane,
with true stick; the bilinear bearing (``Pi9 > 0``, ``Pi10 > 0``) an elastic-plastic force with a
circular yield surface (below).

Model (dimensionless: ``tau = t/T_p``, lengths ``a_p T_p**2``, accelerations ``a_p``, masses ``M_b``)
---------------------------------------------------------------------------------------------------
Ground.  ``g(tau) = (g_x, g_y)`` in the building's axes: the excitation
``(p(tau), Pi14 p_y((tau - Pi16)/Pi15))`` turned by ``scene.angle`` (no ``p_y`` term without a
``pulse_y``), as :meth:`isoslide.Scene.ground`.  Vertical: the normal-force factor
``nz(tau) = 1 + Pi17 p_z(tau)`` (1 without a ``pulse_z``; ``p_z`` on the main pulse's time axis).

Building, the same in ``x`` and in ``y`` (isotropic) and the two axes coupled only through the
friction forces (the contents', the sliding bearing's).  Coordinates ``d`` relative to the ground,
one per moving mass:

* fixed base (``Pi3 = 0``), rigid superstructure or contents on the slab: none; the contents'
  floor moves with the ground (``A_F = g``) and their force does not act back;
* fixed base, flexible superstructure, contents on floor ``k >= 1``: the floors ``d_j = xs_j``,
  masses ``m_j``, stiffness ``Ks``, damping ``Cs`` (:func:`~.reference_building.shear_building`,
  built as in :mod:`~.reference_building`: ``m_j = Pi11 w_j``, fixed-base fundamental period
  ``Pi12``, classical damping ``Pi13``);
* linear isolator, rigid superstructure: the slab ``d_0 = x``, mass 1, stiffness
  ``kd = (2 pi/Pi3)**2``, damping ``cb = 2 Pi4 (2 pi/Pi3)``;
* linear isolator, flexible superstructure: the slab ``d_0 = x`` (mass ``1 - Pi11``) and the
  floors ``d_j = x + xs_j`` (masses ``m_j``), ``K = kd e_0 e_0^T + T^T Ks T`` and
  ``C = cb e_0 e_0^T + T^T Cs T`` with ``xs = T d`` (``T = [-1 | I]``);
* sliding bearing (friction pendulum), rigid or flexible superstructure: the coordinates of the
  linear isolator, the slab's row carrying the bearing's friction (below); on a fixed base
  (``Pi3 = 0``) the bearing has no effect.

With ``M`` the diagonal mass matrix and ``e_k`` the contents' floor, every axis obeys::

    M d'' + C d' + K d = -M 1 g_a + e_k R_a          (a = x, y)

and the floor's absolute acceleration is ``A_F = g + d_k''``.

Contents of mass ``m = Pi8``, sliding displacement ``u = (u_x, u_y)`` and velocity ``w = u'``
relative to their floor, friction level ``phi(s) = thr sech(Pi6 s) + Pi2 (1 - sech(Pi6 s)) + Pi7 s``
(``thr = Pi2/Pi5``, ``s = |w|``):

* stuck (``w = 0``): the block moves with its floor (its mass joins ``M_kk`` in both axes),
  ``R = -m A_F``; it stays stuck while ``|A_F| <= thr nz`` (Euclidean norm).  Then
  ``A_F = A_S = -(K_k d + C_k d')/(M_kk + m)`` (the ground term cancels).
* sliding: ``R = m nz phi(|w|) n``, ``w' = -A_F - nz phi(|w|) n`` with the friction direction
  ``n = w/|w|``;
* breakaway where ``|A_S|`` (``A_F`` stuck) reaches ``thr nz``: the block starts to slide along
  ``-A_S/|A_S|``; it is force-continuous (``phi(0) = thr``), and a block that stops where
  ``|A_S| > thr nz`` slides on along ``-A_S/|A_S|`` (consistent: its speed grows,
  ``|w|' = (M_kk + m)/M_kk (|A_S| - thr nz) > 0`` on a moving floor, ``|g| - thr nz`` on one that
  moves with the ground);
* ``Pi1 = max |u|``, ``peak_angle = atan2(u_y, u_x)`` there, ``tau_peak`` its time.

Sliding bearing (friction pendulum) under the slab of mass ``mb`` (``1 - Pi11`` under a flexible
superstructure, else 1; ``Ms_0`` is ``mb + m`` with the contents stuck on the slab, else ``mb``),
the slab's displacement ``x = d_0`` and velocity ``x'`` relative to the ground.  Its friction level
rises with the slab's speed ``s = |x'|`` (Constantinou, Mokha and Reinhorn 1990)::

    q(s) = q + (q_fast - q) (1 - exp(-Pi23 s)),   q = Pi9 Pi22,   q_fast = Pi9

from the breakaway level ``q`` at rest to ``q_fast`` (:meth:`PlanarBuilding.level`; ``Pi22 = 1``
or ``Pi23 = 0`` is the constant ``q = Pi9 Pi22`` at every speed).  Its force on the slab is ``-(kd
nz x + cb x' + fb)``: the pendulum's restoring force ``W x/R`` scales with the normal force, so the
slab's ``kd x`` in ``K d`` becomes ``kd nz x``, and ``fb`` is its friction:

* held (``x' = 0``, ``x'' = 0``: the slab moves with the ground, ``d_0`` stays): the force the
  bearing must supply, ``f_need = -Ms_0 g - kd nz x + S + R_0``, is within ``|f_need| <= q nz``;
  ``S`` is the storeys' force on the slab (``S - kd nz x`` is row 0 of ``-(K d + C d')`` with
  ``x' = 0``) and ``R_0`` the sliding contents' friction force when they are on the slab (0 on a
  floor above; stuck on the slab their ``-m g`` is the ``m`` of ``Ms_0``).  The floors above move
  on their rows of the equation of motion with ``d_0`` fixed, and the contents on the slab move
  with the ground (``A_S = g``);
* sliding: ``fb = q(|x'|) nz n_b``, ``n_b = x'/|x'|``; the slab's row is the linear isolator's with
  ``-fb`` added, ``Ms_0 (g + x'') = -kd nz x - cb x' - fb + S + R_0`` (stuck on the slab the
  contents see ``A_S = (-kd nz x - cb x' - fb + S)/(mb + m)``);
* breakaway where ``|f_need|`` reaches ``q nz``: the slab slides from rest along
  ``f_need/|f_need|`` (force-continuous: the friction ``-f_need`` held becomes ``q(0) nz = q nz``
  along the same line, and the contents keep their mode); a slab whose ``|x'|`` returns to zero
  stops, and the
  modes of the interfaces at rest are chosen (below).

Bilinear bearing (lead-rubber), ``q = Pi9``, ``D_y = Pi10``: the linear isolator (post-yield
stiffness ``kd`` in ``K``) plus a hysteretic force ``fh = (fh_x, fh_y)`` on the slab, a state:
``-fh`` joins the slab's row of ``-(K d + C d')``.  Elastic (``|fh| < q``, or unloading):
``fh' = ke x'`` with ``ke = q/D_y``; yielding (``|fh| = q`` and ``fh . x' > 0``): perfectly plastic
flow along ``fh``, ``fh' = ke (x' - (n_h . x') n_h)`` with ``n_h = fh/|fh|``, which keeps ``|fh| =
q``.  It yields at the root of ``q - |fh|`` and unloads at the root of ``fh . x'`` (terminal
events); after the pulses, with the contents stuck and the bearing elastic, the plastic offset
``x_p = x - fh/ke`` is fixed, the free system is linear about the displacement ``d*`` that
``K' d* = ke x_p e_0`` gives (``K' = K + ke e_0 e_0^T``), and settlement is the energy bound below
with ``K'`` and ``d - d*``, and ``|fh| <= ke |d*_0 - x_p| + ke |d_0 - d*_0|`` within ``q``.  It
does not act on contents on a fixed base (``Pi3 = 0``).

Joint modes
-----------
When one interface stops the force on the other jumps (the contents' ``-m A_S`` stuck against
``m nz phi n`` sliding; a held slab's acceleration ``g`` against a sliding one's), so the modes of
the interfaces at rest (stuck contents, a held bearing; after a stop, at every segment start) are
chosen together: (both stuck), (contents stuck, bearing slides), (contents slide, bearing held),
(both slide) are tried in that order and the first consistent one is taken (an interface that is
moving keeps its mode).  A stuck interface is consistent when its need is within its limit:
``|A_S| <= thr nz``, ``A_S`` the contents' floor's acceleration were they stuck computed with the
bearing in its candidate mode (``g`` on a held slab), and ``|f_need| <= q nz`` with the contents
in their candidate mode.  A starting interface is consistent when its speed grows from zero along
its starting direction: the contents' along ``-A_S/|A_S|`` (with the bearing in its candidate
mode, the sliding slab's ``-fb`` in ``A_S``), the bearing's along ``f_need/|f_need|`` (with the
contents in their candidate mode, sliding from rest at ``phi(0) = thr`` along their starting
direction).  Both starting on the slab, the two directions depend on each other:
``n_b = (f_0 + m nz phi n_c)/|.|`` and ``n_c = -(F_0 - q nz n_b)/|.|`` (``F_0`` row 0 of
``-(K d + C d')`` with ``x' = 0`` and ``kd nz``, ``f_0 = F_0 - mb g``), taken as their fixed point
by iteration (a contraction by about ``m/(mb + m)`` where both starts are consistent).  These
tests are the speeds' rates at zero speed, ``r' = (M_kk + m)/M_kk (|A_S| - thr nz)`` (``|g| -
thr nz`` on a floor that moves with the ground) and ``r_b' = (|f_need| - q nz)/Ms_0``, so a stuck candidate and a starting one of the same interface
exclude each other.  Under a one-dimensional excitation every direction keeps the excitation's
line and the choice is the 1-D reference's (:mod:`~.reference_building`).

Slips
-----
A slow slip is stiff: the direction of ``w`` relaxes towards ``-A_F/|A_F|`` at the rate
``|A_F|/|w|`` (in polar form ``|w| psi' = -|A_F| sin psi``, ``psi`` the angle of ``w`` from
``-A_F/|A_F|``), so an explicit integrator needs steps of about ``|w|/|A_F|``; after a breakaway
``|w|`` grows like ``(tau - tau_0)**2`` and following it from ``|w| = 0`` explicitly takes without
bound many steps, and a block creeping at a small speed takes as many.  A slip therefore runs in
segments of three kinds, by speed ``r = |w|``.

*Slaved* (``r < SLOW_SPEED = 1e-8 a_p T_p``, :data:`SLOW_SPEED`): the direction is the one the
relaxation tends to, ``n = -A_S/|A_S|`` with ``A_S`` the floor's acceleration were the block stuck
(``A_S = f_k/(M_kk + m)``, ``f_k = -(K_k d + C_k d')`` the floor's other forces; ``A_S = g`` on a
floor that moves with the ground), and the speed ``r`` is a state::

    r' = -A_F . n - nz phi(r),   u' = r n,   R = m nz phi(r) n

(on a moving floor ``r' = (M_kk + m)/M_kk (|A_S| - nz phi(r))``).  The true direction lags this
one by about ``r Omega/|A_S|`` (``Omega`` the turning rate of ``A_S``): below ``SLOW_SPEED`` the
friction force's direction is off by ~1e-7 at most, a change of the building's momentum
~1e-7 ``m nz phi`` times the slaved phase's duration (~1e-4 ``T_p`` after a breakaway), and of
``u`` ~``SLOW_SPEED`` times that.  Changing ``SLOW_SPEED`` from 1e-6 to 1e-10 changes ``Pi1`` by
less than 1e-12 relative on the scenes tried (1e-10 from 1e-6).  Under a one-dimensional
excitation ``A_S`` keeps its line and the slaved phase is exact.  Every slip from rest starts
slaved (along ``-A_S/|A_S|``, the breakaway direction) and switches to the exact equations when
``r`` reaches ``SLOW_SPEED``; a sliding block whose speed falls to ``SLOW_SPEED/2`` with ``w``
within 1e-5 rad of ``-A_S/|A_S|`` (relaxed) continues slaved.  A slaved slip stops at the root of
``r`` (of ``r/(tau - tau_0)`` from rest, which has the sign of ``r`` without the trivial root at
``tau_0``): ``r`` is smooth and crosses zero with ``r' < 0``, so the stop is located as exactly as
the one-dimensional reference's.

*Sliding*, the exact equations, with the implicit ``Radau`` integrator (stiffly stable) while
``r`` is below ``2 STIFF_SPEED thr`` after falling below ``STIFF_SPEED thr`` (:data:`STIFF_SPEED`,
``thr/256``: where the relaxation rate ``|A_F|/r`` exceeds ~256 per ``T_p``), else with
``DOP853``.  A sliding segment carries a fixed reference direction ``e`` (the direction of ``w``
at its start) and uses the friction direction ``n = sgn(w . e) w/|w|``, which is ``w/|w|`` while
``w`` stays within 90 degrees of ``e``.  It ends at the first of:

* *turn*: ``w . e = cos(30 deg) |w| - atol`` (``w`` has turned 30 degrees away from ``e``; the
  velocity's absolute tolerance ``atol`` keeps round-off in the direction of a ``w`` within
  ``atol`` of zero from starting segments): a new segment starts at once with ``e = w/|w|``;
* *slow*: ``r = SLOW_SPEED/2`` (slaved if relaxed, else on with DOP853, which is not stiff there:
  an unrelaxed direction relaxes slowly);
* *gear*: ``r`` through the stiff band's limits (the integrator changes);
* *stop* (reached only with DOP853 below ``SLOW_SPEED``, unrelaxed): ``w . e = 0``.  Before it
  ``w . e >= cos(30 deg) |w| - atol``, so there ``|w| <= atol/cos(30 deg)``: the root is the stop,
  to the velocity's tolerance.  It is a transversal root of a continuous function: past it the
  extension ``n = sgn(w . e) w/|w|`` keeps ``n`` continuous (``w`` comes back the way it came and
  ``n`` keeps its direction), exactly as the one-dimensional reference keeps the sign ``s`` of a
  slip past its stop.  ``solve_ivp`` brackets the root between accepted steps of the
  error-controlled solution and Brent's method refines it on the dense output to about 4 ulp:
  the stop time, ``u`` and the building's state are exact to the integration tolerances.

Only these changes of segment interrupt a slip; they change nothing in the state but the way
``w`` is held (``w = r n`` between slaved and sliding).  At a stop ``w = 0`` and the modes of the
interfaces at rest are chosen (Joint modes): alone, the block sticks if ``|A_S| <= thr nz``, else
it starts again along ``-A_S/|A_S|``.

The sliding bearing's slips run the same three kinds of segment, by the slab's speed
``r_b = |x'|``: slaved below ``SLOW_SPEED`` (the speed ``r_b`` a state, held in ``x'_x``, and
``x' = r_b n_b``) along ``n_b = f_S/|f_S|``, ``f_S`` the need ``f_need`` evaluated with ``x' = 0``
(the slab's damping ``-C_00 r_b n_b`` lies along ``n_b`` and does not turn it; the other rows get
``-C_j0 r_b n_b``), so ``r_b' = (|f_S| - C_00 r_b - q(r_b) nz)/Ms_0``; the exact equations with Radau
below ``STIFF_SPEED q`` (until ``2 STIFF_SPEED q``) and DOP853 above, with the reference direction
``e_b`` and the events *turn*, *slow*, *gear* and *stop* of ``x'``.  A segment runs with Radau when
either sliding interface is in its stiff band.  A slaved slip of both interfaces at once (both
from rest, the contents on the slab) takes the joint directions above at every evaluation (with
``q(r_b) nz`` and the damping ``C_00 r_b`` in place of ``q nz``).  Every sliding segment evaluates
the level at the signed speed along its friction direction, ``x' . n_b`` (``n_b = sgn(x' . e_b)
x'/|x'|``) or ``r_b``, which is ``|x'|`` up to a stop and negative past it inside a step: ``q(s)``
continues smoothly there, as the friction direction does, so the stop is a transversal root of a
smooth function.

Inside a slip ``|u|`` peaks where ``(|u|**2)'/2 = u . w`` goes from positive to negative (a
non-terminal event); ``|u|`` is also taken at every stop and at the end of every segment, so the
maximum over time is exact.  A stuck block breaks away at the root of ``thr nz - |A_S|``
and a held bearing at the root of ``q nz - |f_need|`` (terminal).  Segments also end at every breakpoint of the three pulses (each pulse's start and
``breakpoint_array``, mapped to ``tau`` for the second component: ``Pi16 + Pi15 b``); inside a
segment each pulse is evaluated on the segment's side of its breakpoints, so jumps are taken
one-sidedly.

Start and end
-------------
The run starts at rest at the earliest start of the pulses and follows the response past the
latest end ``tau_end`` of all of them.  After ``tau_end`` a stuck block on a free building
settles (``settled = True``, the run stops) as soon as it provably never slides again: the free
stuck system ``Ms d'' + C d' + K d = 0`` holds in every horizontal direction ``d`` (the
projections ``D d`` of the two axes' coordinates obey it), so the energy of the motion along
``d``, ``E_d = d^T Q d/2`` with ``Q = D^T K D + V^T Ms V``, never increases; ``A_F . d`` is
``c . (D d, V d)`` with ``c = -(K_k, C_k)/(M_kk + m)``, so for all later times
``|A_F| = max_d A_F . d <= sqrt(lambda_max(Q) c^T P^-1 c)`` (``P = diag(K, Ms)``,
Cauchy-Schwarz), with ``Q`` taken now.  Settlement is the first moment this bound is at most
``thr`` (checked at every segment start and as a terminal event of the free segments); it only
decides where the run stops, never ``Pi1``.  With a sliding bearing the response is free when the
contents are stuck and the bearing held (a sliding slab never settles, and one whose friction rises
with speed may creep towards its stick band until the horizon): then the slab stays at
``x`` and only the floors above it move, ``xs = d_j - x``, with the non-increasing ``Q`` of
``(xs, xs')`` over ``Ks`` and the floors' masses; ``|f_need| <= kd |x| + sqrt(lambda_max(Q)
c_b^T P^-1 c_b)`` with ``c_b`` the storeys' forces on the slab (``S``) and ``P = diag(Ks, Ms)``
(``|f_need| = kd |x|`` for ever under a rigid superstructure), and the contents' bound on a floor
above as before (on the held slab they move with the motionless ground); settlement is the first
moment both bounds are within their limits.  A fixed base with the contents on the ground-fixed
floor settles as soon as the block sticks after ``tau_end``.  A run that has not settled by
``tau_end + horizon max(1, Pi3, Pi12)`` ends there with ``settled = False``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg
from scipy.integrate import solve_ivp

from ..pulses import Pulse, accel_at
from ..scene import Scene
from .reference_building import shear_building, storeys_of
from .result import PeerResult, counted

__all__ = ["PlanarBuilding", "PlanarRun", "SLOW_SPEED", "STIFF_SPEED", "TURN_ANGLE", "planar_building",
           "planar_excitation",
           "run_planar", "solve_reference_planar"]

TURN_ANGLE = math.pi / 6.0
"""Largest angle (radians) the sliding velocity turns within one segment before a new segment
starts with a new reference direction (see the module docstring)."""

SLOW_SPEED = 1e-8
"""Speed (units ``a_p T_p``) below which a slip runs along the slaved direction ``-A_S/|A_S|``
(module docstring): up to it from rest, and from half of it, relaxed, to the stop."""

STIFF_SPEED = 1.0 / 256.0
"""Below the speed ``STIFF_SPEED thr`` (``STIFF_SPEED`` in units ``T_p``) the exact equations are stiff and run
with the implicit Radau integrator, above twice it with DOP853 (module docstring)."""

_COS_RELAXED = math.cos(1e-5)   # the sliding velocity is relaxed within 1e-5 rad of -A_S/|A_S|
_COS_TURN = math.cos(TURN_ANGLE)
_ULP4 = 4e-15      # relative slack of the stick limit, as in isoslide.peers.reference
_MERGE = 1e-10     # breakpoints closer than _MERGE (1 + |tau|) are one


@dataclass(frozen=True)
class PlanarBuilding:
    """The building of a scene in the coordinates of the module docstring (the same in x and y).

    Attributes
    ----------
    masses : ndarray
        Diagonal of ``M`` (units ``M_b``), one per moving coordinate (empty when the contents'
        floor moves with the ground).
    K, C : ndarray
        Stiffness (units ``M_b / T_p**2``) and damping (units ``M_b / T_p``) matrices, square.
    k : int
        Index of the contents' floor among the coordinates; -1 when it moves with the ground.
    m : float
        Contents' mass ``Pi8`` (units ``M_b``).
    thr : float
        Static friction level ``Pi2/Pi5`` (units ``a_p``).
    pi2, pi6, pi7 : float
        Kinetic level (units ``a_p``), Stribeck sharpness (units ``1/(a_p T_p)``) and viscous
        group (units ``1/T_p``) of the friction law.
    q : float
        Breakaway level ``Pi9 Pi22`` of a sliding bearing under the slab (units ``M_b a_p``, times
        ``nz``): its stick limit and its friction at rest; 0 without one (a linear isolator or a
        fixed base).
    q_fast, rate : float
        The bearing's friction at high speed ``Pi9`` (units ``M_b a_p``, times ``nz``) and the rate
        ``Pi23`` (units ``1/(a_p T_p)``) of its rise with the slab's speed (:meth:`level`);
        ``q_fast = q`` and ``rate = 0`` for constant friction.
    qy, ke : float
        A bilinear bearing's yield strength ``Pi9`` (units ``M_b a_p``) and the elastic stiffness
        of its hysteretic force ``Pi9/Pi10`` (units ``M_b / T_p**2``); 0 without one.
    kd : float
        The pendulum's stiffness ``(2 pi/Pi3)**2`` with a sliding bearing (units
        ``M_b / T_p**2``, times ``nz``; also in ``K[0, 0]``), else 0.
    """

    masses: np.ndarray
    K: np.ndarray
    C: np.ndarray
    k: int
    m: float
    thr: float
    pi2: float
    pi6: float
    pi7: float
    q: float = 0.0
    kd: float = 0.0
    qy: float = 0.0
    ke: float = 0.0
    q_fast: float = 0.0
    rate: float = 0.0

    def level(self, s: float) -> float:
        """The sliding bearing's friction level at the slab's speed ``s`` (units ``M_b a_p``, times ``nz``).

        ``q + (q_fast - q) (1 - exp(-rate s))``: ``q`` at rest, rising to ``q_fast``; ``q`` at every
        speed for constant friction.  ``s`` is the speed along the friction direction, negative past
        a stop inside a step, where the same expression continues the law smoothly (its exponent
        capped at 60 against overflow).
        """
        if self.rate == 0.0:
            return self.q
        return self.q - (self.q_fast - self.q) * math.expm1(min(-self.rate * s, 60.0))

    @property
    def hysteretic(self) -> bool:
        """True for a bilinear bearing: a hysteretic force ``fh`` on the slab with a circular yield surface."""
        return self.ke > 0.0

    @property
    def elastic_K(self) -> np.ndarray:
        """``K`` with a bilinear bearing's elastic stiffness on the slab (``K'`` of the module docstring)."""
        K = self.K.copy()
        if self.hysteretic:
            K[0, 0] += self.ke
        return K

    @property
    def bearing(self) -> bool:
        """True for a sliding bearing (friction pendulum) under the slab, a second friction interface."""
        return self.q > 0.0

    @property
    def nd(self) -> int:
        """Number of moving coordinates per axis."""
        return int(self.masses.size)

    @property
    def stuck_masses(self) -> np.ndarray:
        """Diagonal of ``M`` with the stuck block's mass on its floor (units ``M_b``)."""
        ms = self.masses.copy()
        if self.k >= 0:
            ms[self.k] += self.m
        return ms

    def phi(self, s: float) -> float:
        """Friction level ``phi(s)`` per unit weight at the speed ``s >= 0`` (units ``a_p``)."""
        a = self.pi6 * s
        sh = 0.0 if a > 700.0 else 1.0 / math.cosh(a)
        return self.thr * sh + self.pi2 * (1.0 - sh) + self.pi7 * s

    def periods(self) -> list:
        """Natural periods of the stuck building (units ``T_p``), to bound the step."""
        if not self.nd:
            return []
        lam = list(scipy.linalg.eigh(self.elastic_K, np.diag(self.stuck_masses), eigvals_only=True))
        if self.bearing and self.nd > 1:   # the floors above a held slab
            lam += list(scipy.linalg.eigh(self.K[1:, 1:], np.diag(self.stuck_masses[1:]), eigvals_only=True))
        return [2.0 * math.pi / math.sqrt(v) for v in lam if v > 0.0]


def planar_building(scene: Scene) -> PlanarBuilding:
    """The building of a scene (module docstring).

    Parameters
    ----------
    scene : Scene
        A fixed base (``Pi3 = 0``), a linear isolator (``Pi9 = 0``), a sliding bearing
        (``Pi9 > 0``, ``Pi10 = 0``) or a bilinear bearing (``Pi9 > 0``, ``Pi10 > 0``).

    Returns
    -------
    PlanarBuilding
    """
    flexible = scene.pi12 > 0.0
    floor = scene.floor_index if flexible else 0
    if flexible:
        ms, r = storeys_of(scene)
        Ks, Cs, _ = shear_building(ms, r, scene.pi12, scene.pi13)
    common = dict(m=float(scene.pi8), thr=scene.pi2 / scene.pi5, pi2=float(scene.pi2), pi6=float(scene.pi6),
                  pi7=float(scene.pi7))
    if scene.pi3 == 0.0:
        if flexible and floor > 0:
            return PlanarBuilding(masses=ms, K=Ks, C=Cs, k=floor - 1, **common)
        return PlanarBuilding(masses=np.zeros(0), K=np.zeros((0, 0)), C=np.zeros((0, 0)), k=-1, **common)
    wb = 2.0 * math.pi / scene.pi3
    kd, cb = wb * wb, 2.0 * scene.pi4 * wb
    if scene.pi9 > 0.0 and scene.pi10 > 0.0:
        common.update(qy=float(scene.pi9), ke=float(scene.pi9 / scene.pi10))
    elif scene.pi9 > 0.0:
        if scene.pi23 > 0.0 and scene.pi22 < 1.0:      # friction rising with speed from Pi9 Pi22 to Pi9
            common.update(q=float(scene.pi9 * scene.pi22), q_fast=float(scene.pi9), rate=float(scene.pi23), kd=kd)
        else:                                           # constant: Pi9 Pi22 at every speed
            q = float(scene.pi9 * scene.pi22)
            common.update(q=q, q_fast=q, kd=kd)
    if not flexible:
        return PlanarBuilding(masses=np.ones(1), K=np.array([[kd]]), C=np.array([[cb]]), k=0, **common)
    T = np.hstack([-np.ones((ms.size, 1)), np.eye(ms.size)])
    K = T.T @ Ks @ T
    C = T.T @ Cs @ T
    K[0, 0] += kd
    C[0, 0] += cb
    return PlanarBuilding(masses=np.concatenate([[1.0 - scene.pi11], ms]), K=0.5 * (K + K.T),
                          C=0.5 * (C + C.T), k=floor, **common)


@dataclass(frozen=True)
class _Component:
    """One ground component ``amp p((tau - shift)/stretch)`` (``p`` a pulse shape)."""

    pulse: Pulse
    amp: float
    shift: float = 0.0
    stretch: float = 1.0
    code: int = field(init=False)
    params: np.ndarray = field(init=False, repr=False)
    knots: np.ndarray = field(init=False, repr=False)   # own time: the start and the breakpoints

    def __post_init__(self):
        object.__setattr__(self, "code", int(self.pulse.code))
        object.__setattr__(self, "params", np.asarray(self.pulse.param_array, dtype=np.float64))
        knots = np.union1d([float(self.pulse.tau_start)], np.asarray(self.pulse.breakpoint_array, dtype=float))
        object.__setattr__(self, "knots", knots)

    def tau_of(self, s):
        """The time ``tau`` (units ``T_p``) of the component's own time ``s``."""
        return self.shift + self.stretch * s

    @property
    def start(self) -> float:
        """Start of the component, units ``T_p``."""
        return float(self.tau_of(self.pulse.tau_start))

    @property
    def end(self) -> float:
        """End of the component, units ``T_p``."""
        return float(self.tau_of(self.pulse.tau_end))

    def own(self, tau: float) -> float:
        """The component's own time at ``tau``, snapped onto a knot within the merge tolerance."""
        taus = self.tau_of(self.knots)
        i = int(np.argmin(np.abs(taus - tau)))
        if abs(taus[i] - tau) <= _MERGE * (1.0 + abs(tau)):
            return float(self.knots[i])
        return (tau - self.shift) / self.stretch

    def window(self, t0: float, t1: float):
        """``a(tau)`` on the segment ``[t0, t1]``: the own time clamped to the segment's side of the knots."""
        lo = self.own(t0)
        hi = max(lo, math.nextafter(self.own(t1), -math.inf))
        code, params, amp, shift, stretch = self.code, self.params, self.amp, self.shift, self.stretch

        def a(tau):
            s = min(max((tau - shift) / stretch, lo), hi)
            return amp * accel_at(code, params, s)

        return a


@dataclass(frozen=True)
class _Excitation:
    """The ground motion of a scene: two horizontal components, turned, and the vertical one."""

    x: _Component
    y: _Component | None
    z: _Component | None
    angle: float

    @property
    def parts(self) -> list:
        return [c for c in (self.x, self.y, self.z) if c is not None]

    @property
    def tau_start(self) -> float:
        """Earliest start of the pulses, units ``T_p``."""
        return min(c.start for c in self.parts)

    @property
    def tau_end(self) -> float:
        """Latest end of the pulses, units ``T_p``."""
        return max(c.end for c in self.parts)

    def breakpoints(self) -> np.ndarray:
        """Sorted segment boundaries after :attr:`tau_start` (near-equal ones merged), units ``T_p``."""
        b = np.unique(np.concatenate([c.tau_of(c.knots) for c in self.parts] + [[self.tau_end]]))
        out = []
        for t in b:
            if out and t - out[-1] <= _MERGE * (1.0 + abs(t)):
                continue
            out.append(float(t))
        t0 = self.tau_start
        return np.asarray([t for t in out if t > t0 + _MERGE * (1.0 + abs(t0))])

    def window(self, t0: float, t1: float):
        """``(ground, nz)`` on the segment ``[t0, t1]``, one-sided at its ends.

        ``ground(tau)`` is ``(g_x, g_y)`` (units ``a_p``, building axes), ``nz(tau)`` the
        normal-force factor (dimensionless).
        """
        ax = self.x.window(t0, t1)
        ay = self.y.window(t0, t1) if self.y is not None else None
        az = self.z.window(t0, t1) if self.z is not None else None
        c, s = math.cos(self.angle), math.sin(self.angle)

        def ground(tau):
            gx = ax(tau)
            gy = ay(tau) if ay is not None else 0.0
            return c * gx - s * gy, s * gx + c * gy

        def nz(tau):
            return 1.0 + az(tau) if az is not None else 1.0

        return ground, nz

    def ground(self, tau: float) -> tuple:
        """``(g_x, g_y)`` at ``tau`` (units ``a_p``; right-continuous), as :meth:`Scene.ground`."""
        return self.window(tau, tau + 1.0)[0](tau)


def planar_excitation(scene: Scene) -> _Excitation:
    """The scene's ground motion as the peer evaluates it (``.ground(tau)``, ``.tau_start``, ...)."""
    y = (_Component(scene.pulse_y, float(scene.pi14), float(scene.pi16), float(scene.pi15))
         if scene.bidirectional else None)
    z = _Component(scene.pulse_z, float(scene.pi17)) if scene.vertical else None
    return _Excitation(_Component(scene.pulse, 1.0), y, z, float(scene.angle))


@dataclass(frozen=True)
class PlanarRun:
    """A planar reference solve with its sampled trajectory.

    Attributes
    ----------
    result : PeerResult
        As :func:`solve_reference_planar` returns it.
    tau : ndarray
        The sample times that the run reached (units ``T_p``), ascending.
    u, w : ndarray
        Sliding displacement (units ``a_p T_p**2``) and velocity (units ``a_p T_p``) at those
        times, shape ``(2, n)`` (``x`` and ``y`` in the building's axes).
    """

    result: PeerResult
    tau: np.ndarray
    u: np.ndarray
    w: np.ndarray


def solve_reference_planar(scene: Scene, history: bool = False, rtol: float = 1e-11, atol: float = 1e-13,
                           horizon: float = 200.0, max_work: int | None = None) -> PeerResult:
    """Solve one scene with contents sliding in the plane, event-driven (module docstring).

    Parameters
    ----------
    scene : Scene
        Any scene: a fixed base, a linear isolator, a sliding bearing or a bilinear bearing; rigid
        or flexible superstructure; one or two horizontal components at any angle; vertical motion.
    history : bool
        Must be False: a planar response has no one-dimensional
        :class:`~isoslide.store.history.History`; :func:`run_planar` samples its trajectory.
    rtol, atol : float
        Tolerances passed to ``solve_ivp`` (DOP853, and Radau for slow slips); ``atol`` in the
        state's units (``a_p T_p**2``, ``a_p T_p``).
    horizon : float
        Follow an unsettled response up to ``horizon max(1, Pi3, Pi12)`` (units ``T_p``) after the
        last pulse's end, ``>= 0``.
    max_work : int or None
        Most right-hand-side evaluations (raises :class:`~isoslide.peers.result.WorkLimitError`).

    Returns
    -------
    PeerResult
        ``method = "reference"``, ``integrator = "DOP853"`` (that of every stuck and fast
        phase; slow slips run with Radau or slaved, see the module docstring); ``pi1 = max |u|`` (units
        ``a_p T_p**2``), ``peak_angle = atan2(u_y, u_x)`` at the peak (radians, building axes; nan
        with ``pi1 = 0`` if the block never slid; ``tau_peak`` then nan too), ``pi1_residual = |u|``
        at the end, ``n_events`` the breakaways (from rest, also right after a stop) and stops of
        the contents and of a sliding bearing, ``nfev`` the right-hand-side evaluations of both
        integrators.

    Raises
    ------
    ValueError
        ``history = True``, or a bad ``horizon``.
    """
    if history:
        raise ValueError("history = True is not available for a planar response (no one-dimensional History); "
                         "allowed: history = False (run_planar(scene, samples=...) samples the trajectory)")
    return run_planar(scene, rtol=rtol, atol=atol, horizon=horizon, max_work=max_work).result


def run_planar(scene: Scene, rtol: float = 1e-11, atol: float = 1e-13, horizon: float = 200.0,
               max_work: int | None = None, samples=None, max_segments: int = 1_000_000,
               settle: bool = True) -> PlanarRun:
    """:func:`solve_reference_planar`, optionally sampling the trajectory.

    Parameters
    ----------
    scene, rtol, atol, horizon, max_work
        As :func:`solve_reference_planar`.
    samples : array_like or None
        Times (units ``T_p``) at which to record ``u`` and ``w`` (those the run reaches).
    settle : bool
        Stop at settlement (default); ``False`` follows the scene to the horizon (``settled``
        stays False), to check the settlement bound.
    max_segments : int
        Safety cap on the number of integration segments (raises ``RuntimeError``).

    Returns
    -------
    PlanarRun
    """
    B = planar_building(scene)
    if isinstance(horizon, bool) or not (isinstance(horizon, (int, float)) and math.isfinite(horizon)
                                         and horizon >= 0.0):
        raise ValueError(f"horizon = {horizon!r} is out of range; allowed range: 0 <= value < inf")
    ex = planar_excitation(scene)
    P = _Planar(B)
    nd = B.nd
    i_u, i_w, i_v = 4 * nd, 4 * nd + 2, 2 * nd
    lims = (B.thr * (1.0 + _ULP4), B.q * (1.0 + _ULP4))
    stiff = (STIFF_SPEED * B.thr, STIFF_SPEED * B.q)
    tau_end = ex.tau_end
    t_stop = tau_end + float(horizon) * max(1.0, scene.pi3, scene.pi12)
    bps = [b for b in ex.breakpoints() if b < t_stop] + [t_stop]
    periods = B.periods()
    short = scene.pi15 if ex.y is not None else 1.0
    hmax_pulse = min([1.0 / 64.0, short / 64.0] + [T / 32.0 for T in periods])
    hmax_free = min([max(1.0, scene.pi3) / 64.0] + [T / 32.0 for T in periods])
    settle_of = _settle_margin(B, lims[1]) if settle else None
    sample_t = np.sort(np.asarray(samples, dtype=float).ravel()) if samples is not None else None
    rec_t, rec_y = [], []

    tau = ex.tau_start
    i_h = 4 * nd + 4                        # a bilinear bearing's force fh
    y = np.zeros(i_h + (2 if B.hysteretic else 0))
    plastic = False                         # the bilinear bearing yielding
    # the interfaces: 0 the contents on their floor, 1 the sliding bearing (_NONE without one)
    modes = [_STUCK, _STUCK if B.bearing else _NONE]
    implicit = [False, False]               # sliding: Radau (slow, stiff) or DOP853
    from_rest = [False, False]
    dirs = [np.array([1.0, 0.0]), np.array([1.0, 0.0])]   # the reference directions
    slots = ((i_w, i_w + 2), (i_v, i_v + 2))               # where each interface's velocity is held
    peak, tau_peak, angle_peak = 0.0, math.nan, math.nan
    n_events = nfev = zero_len = segments = ib = 0
    used = [0]
    settled = False

    def note(t, yy):
        nonlocal peak, tau_peak, angle_peak
        r = math.hypot(yy[i_u], yy[i_u + 1])
        if r > peak:
            peak, tau_peak, angle_peak = r, float(t), math.atan2(yy[i_u + 1], yy[i_u])

    while True:
        segments += 1
        if segments > max_segments:
            raise RuntimeError(f"more than {max_segments} segments; scene={scene!r}")
        while ib < len(bps) and bps[ib] <= tau:
            ib += 1
        t_end = bps[ib] if ib < len(bps) else t_stop
        ground, nz = ex.window(tau, max(t_end, tau))
        g0, z0 = ground(tau), nz(tau)
        # ---- the modes at the segment start -------------------------------------------------
        slow = [None, None]
        for j in (0, 1):
            if modes[j] != _SLIDING:
                continue
            a, b = slots[j]
            speed = math.hypot(y[a], y[a + 1])
            if speed >= 0.75 * SLOW_SPEED:
                slow[j] = SLOW_SPEED / 2.0
                continue
            trial = modes.copy()
            trial[j] = _SLAVED
            yt = y.copy()
            yt[a:b] = (speed, 0.0)
            n_s = P.directions(g0, z0, yt, trial, dirs)[j]
            if y[a] * n_s[0] + y[a + 1] * n_s[1] >= speed * _COS_RELAXED:
                y[a:b] = (speed, 0.0)           # relaxed: slaved from here
                modes[j], dirs[j] = _SLAVED, n_s
            else:                               # not relaxed, so not stiff: the exact equations, explicitly
                implicit[j] = False
        for j in (0, 1):
            if modes[j] == _STUCK:
                a, b = slots[j]
                y[a:b] = 0.0
        if _STUCK in modes:
            chosen = P.choose(g0, z0, y, modes, dirs, lims)
            for j in (0, 1):
                if chosen[j] != modes[j]:
                    n_events += 1
                    from_rest[j] = True
            modes = chosen
        free = modes[0] == _STUCK and modes[1] in (_STUCK, _NONE) and not plastic and tau >= tau_end
        settle_g = settle_of(y) if free and settle_of is not None else None
        if free and settle and (settle_g is None or settle_g(tau, y) >= 0.0):
            settled = True
            break
        if tau >= t_stop:
            break
        # ---- this segment -------------------------------------------------------------------
        gears = [(2.0 * stiff[j], 1.0) if implicit[j] else (stiff[j], -1.0) for j in (0, 1)]
        method = "Radau" if any(modes[j] == _SLIDING and implicit[j] for j in (0, 1)) else "DOP853"
        seg = _segment(P, ground, nz, tuple(modes), dirs, tau, y, from_rest, atol, lims, slow, gears, settle_g,
                       plastic)
        rhs, specs = seg.rhs, seg.events
        sol = solve_ivp(counted(rhs, max_work, "reference", used), (tau, t_end), y, method=method, rtol=rtol,
                        atol=atol, events=[s[0] for s in specs], max_step=hmax_pulse if tau < tau_end else hmax_free,
                        dense_output=sample_t is not None)
        nfev += sol.nfev
        if sol.status < 0:
            raise RuntimeError(f"solve_ivp ({method}) failed at tau = {sol.t[-1]!r}: {sol.message}; scene={scene!r}")
        if sample_t is not None:
            lo = rec_t[-1][-1] if rec_t else -math.inf
            ts = sample_t[(sample_t >= tau) & (sample_t <= sol.t[-1]) & (sample_t > lo)]
            if ts.size:
                ys = np.asarray(sol.sol(ts)).reshape(y.size, -1)
                rec_t.append(ts)
                rec_y.append(np.vstack([ys[i_u:i_u + 2], np.array([seg.velocity(t, c)[0] for t, c in
                                                                   zip(ts, ys.T, strict=True)]).T]))
        for (_, _kind, terminal), te, ye in zip(specs, sol.t_events, sol.y_events, strict=True):
            if not terminal:            # the peaks of |u| inside a slip
                for t_, y_ in zip(te, ye, strict=True):
                    note(t_, y_)
        from_rest = [False, False]
        if sol.status != 1:             # the segment's end: a breakpoint or the horizon
            tau = t_end
            y = np.array(sol.y[:, -1], dtype=float)
            note(tau, y)
            for j in (0, 1):
                if modes[j] == _SLIDING:
                    dirs[j] = _unit(y[slots[j][0]:slots[j][1]], dirs[j])
            continue
        te, ye, (j, kind) = min(((te[0], ye[0], s[1]) for te, ye, s in
                                 zip(sol.t_events, sol.y_events, specs, strict=True) if s[2] and len(te)),
                                key=lambda h: h[0])
        zero_len = zero_len + 1 if te <= tau else 0
        if zero_len > 8:
            raise RuntimeError(f"zero-length stick/slip chatter at tau={te!r}; scene={scene!r}")
        tau = float(te)
        y = np.array(ye, dtype=float)
        note(tau, y)
        if kind == "settle":
            settled = True
            break
        if kind in ("yield", "unload"):     # the bilinear bearing: nothing else changes
            plastic = kind == "yield"
            if plastic:
                y[i_h:i_h + 2] *= B.qy / math.hypot(y[i_h], y[i_h + 1])
            continue
        a, b = slots[j]
        if kind == "break":             # slides from rest along its slaved direction
            modes[j], from_rest[j] = _SLAVED, True
            n_events += 1
        elif kind == "stop":            # at rest: the modes are chosen at the next segment's start
            y[a:b] = 0.0
            modes[j] = _STUCK
            n_events += 1
        elif kind == "fast":            # the slaved speed reached SLOW_SPEED: the exact equations
            v = seg.velocity(tau, y)[j]
            y[a:b] = v
            dirs[j] = _unit(v, dirs[j])
            modes[j], implicit[j] = _SLIDING, True
        elif kind == "gear":            # between the explicit and the implicit integrator
            implicit[j] = not implicit[j]
            dirs[j] = _unit(y[a:b], dirs[j])
        else:                           # "turn", "slow": a new segment (slaved if slow and relaxed)
            dirs[j] = _unit(y[a:b], dirs[j])

    note(tau, y)
    res = PeerResult(method="reference", pi1=float(peak), pi1_residual=float(math.hypot(y[i_u], y[i_u + 1])),
                     tau_peak=float(tau_peak), settled=settled, n_events=n_events, tau_end=float(tau),
                     nfev=int(nfev), integrator="DOP853", peak_angle=float(angle_peak))
    if rec_t:
        tt, yy = np.concatenate(rec_t), np.concatenate(rec_y, axis=1)
    else:
        tt, yy = np.zeros(0), np.zeros((4, 0))
    return PlanarRun(result=res, tau=tt, u=yy[:2], w=yy[2:])


_NONE, _STUCK, _SLAVED, _SLIDING = -1, 0, 1, 2
"""The modes of a friction interface: stuck (a held bearing), sliding slowly along the slaved
direction, sliding (module docstring); ``_NONE`` where there is no sliding bearing."""

_JOINT_ITERATIONS = 200


def _unit(v, fallback) -> np.ndarray:
    """``v/|v|``, or ``fallback`` for a zero vector."""
    r = math.hypot(v[0], v[1])
    return np.array([v[0] / r, v[1] / r]) if r > 0.0 else np.array(fallback, dtype=float)


def _along(v, e) -> np.ndarray:
    """The friction direction ``sgn(v . e) v/|v|`` of a sliding velocity ``v`` (``e`` for a zero one)."""
    r = math.hypot(v[0], v[1])
    if r == 0.0:
        return np.array(e, dtype=float)
    s = 1.0 if v[0] * e[0] + v[1] * e[1] >= 0.0 else -1.0
    return np.array([s * v[0] / r, s * v[1] / r])


@dataclass(frozen=True)
class _State:
    """The building and the interfaces at one instant in given modes (see :meth:`_Planar.state`).

    ``A`` the coordinates' absolute accelerations (shape ``(nd, 2)``, units ``a_p``; a held slab's
    is ``g``), ``V`` their velocities (a slaved slab's ``r_b n_b``), ``AF`` the contents' floor's
    absolute acceleration, ``nc``/``nb`` the contents' and the bearing's friction directions (None
    where the interface is stuck or absent), ``fr`` the contents' friction level ``nz phi``,
    ``need`` the force a held bearing must supply (None otherwise), ``g`` the ground acceleration.
    """

    A: np.ndarray
    V: np.ndarray
    AF: np.ndarray
    nc: np.ndarray | None
    nb: np.ndarray | None
    fr: float
    need: np.ndarray | None
    g: np.ndarray


class _Planar:
    """The equations of motion of a :class:`PlanarBuilding` in the interfaces' modes (module docstring)."""

    def __init__(self, B: PlanarBuilding):
        self.B = B
        self.nd, self.k, self.m = B.nd, B.k, B.m
        self.masses, self.stuck = B.masses, B.stuck_masses
        self.C0 = B.C[:, 0].copy() if B.nd else np.zeros(0)

    def state(self, g, z: float, yy, modes, dirs) -> _State:
        """Accelerations, velocities, friction directions and the held bearing's need at ``(g, nz, y)``.

        ``modes = (contents, bearing)``, ``dirs`` their reference directions (the fallbacks of
        the slaved directions and the signs of the sliding ones).
        """
        B, nd, k, m = self.B, self.nd, self.k, self.m
        cm, bm = modes
        i_w = 4 * nd + 2
        gv = np.array([float(g[0]), float(g[1])])
        held = bm == _STUCK
        nc = nb = None
        if cm == _SLIDING:
            nc = _along(yy[i_w:i_w + 2], dirs[0])
            fr = z * B.phi(math.hypot(yy[i_w], yy[i_w + 1]))
        elif cm == _SLAVED:
            fr = z * B.phi(abs(yy[i_w]))
        else:
            fr = 0.0
        Ms = self.stuck if cm == _STUCK else self.masses
        F = V = None
        if nd:
            D = yy[:2 * nd].reshape(nd, 2)
            V = yy[2 * nd:4 * nd].reshape(nd, 2)
            if bm in (_STUCK, _SLAVED):
                V = V.copy()
                V[0] = 0.0
            F = -(B.C @ V + B.K @ D)
            if B.hysteretic:
                F[0] -= yy[4 * nd + 4:4 * nd + 6]
            if bm != _NONE:
                if z != 1.0:            # the pendulum's stiffness scales with the normal force
                    F[0] -= (z - 1.0) * B.kd * D[0]
                if bm == _SLIDING:
                    nb = _along(V[0], dirs[1])
                    F[0] -= B.level(float(V[0] @ nb)) * z * nb
                elif bm == _SLAVED:
                    rb = yy[2 * nd]
                    qb = B.level(rb) * z
                    need = F[0] - Ms[0] * gv
                    if k == 0 and cm == _SLAVED:
                        nb, nc = _joint_directions(F[0], need, self.C0[0] * rb + qb, m * fr, dirs)
                    else:
                        if k == 0 and cm == _SLIDING:
                            need = need + m * fr * nc
                        nb = _unit(need, dirs[1])
                    F -= np.outer(self.C0, rb * nb)
                    F[0] -= qb * nb
                    V[0] = rb * nb
        if cm == _SLAVED and nc is None:
            AS = gv if k < 0 or (held and k == 0) else F[k] / self.stuck[k]
            nc = -_unit(AS, -np.asarray(dirs[0], dtype=float))
        if cm != _STUCK and k >= 0:
            F[k] += m * fr * nc
        A = None
        if nd:
            A = F / Ms[:, None]
            if held:
                A[0] = gv
        AF = gv if k < 0 else A[k]
        need = F[0] - Ms[0] * gv if held else None
        return _State(A=A, V=V, AF=AF, nc=nc, nb=nb, fr=fr, need=need, g=gv)

    def directions(self, g, z: float, yy, modes, dirs) -> tuple:
        """The friction directions ``(n_c, n_b)`` in the modes ``modes``."""
        s = self.state(g, z, yy, modes, dirs)
        return s.nc, s.nb

    def rates(self, yy, s: _State, modes, plastic: bool = False) -> np.ndarray:
        """The state's rates from :meth:`state`'s ``s`` in the modes ``modes`` (``plastic``: a bilinear bearing yields)."""
        nd = self.nd
        i_u, i_w = 4 * nd, 4 * nd + 2
        cm, bm = modes
        d = np.zeros(yy.size)
        if nd:
            d[:2 * nd] = s.V.ravel()
            acc = s.A - s.g
            if bm == _SLAVED:
                acc[0] = (float(acc[0] @ s.nb), 0.0)
            d[2 * nd:4 * nd] = acc.ravel()
        if cm == _SLAVED:
            r = yy[i_w]
            d[i_u:i_u + 2] = r * s.nc
            d[i_w] = -float(s.AF @ s.nc) - s.fr
        elif cm == _SLIDING:
            d[i_u:i_u + 2] = yy[i_w:i_w + 2]
            d[i_w:i_w + 2] = -s.AF - s.fr * s.nc
        if self.B.hysteretic:
            v = np.array(s.V[0], dtype=float)
            if plastic:
                n_h = _unit(yy[4 * nd + 4:4 * nd + 6], v)
                v -= float(n_h @ v) * n_h
            d[4 * nd + 4:4 * nd + 6] = self.B.ke * v
        return d

    @staticmethod
    def consistent(s: _State, modes, rest, lims, z: float) -> bool:
        """True when the modes of the interfaces at rest (``rest[j]``) are consistent (module docstring)."""
        cm, bm = modes
        if rest[0]:
            if cm == _STUCK:
                if math.hypot(s.AF[0], s.AF[1]) > lims[0] * z:
                    return False
            elif not -float(s.AF @ s.nc) - s.fr > 0.0:
                return False
        if rest[1]:
            if bm == _STUCK:
                if math.hypot(s.need[0], s.need[1]) > lims[1] * z:
                    return False
            elif not float((s.A[0] - s.g) @ s.nb) > 0.0:
                return False
        return True

    def choose(self, g, z: float, yy, modes, dirs, lims) -> list:
        """The modes of the interfaces at rest (stuck or held), chosen together (module docstring).

        Tried in the order both stuck, contents stuck and bearing sliding, contents sliding and
        bearing held, both sliding; the first consistent one is taken.
        """
        rest = [modes[0] == _STUCK, modes[1] == _STUCK]
        for cm in ((_STUCK, _SLAVED) if rest[0] else (modes[0],)):
            for bm in ((_STUCK, _SLAVED) if rest[1] else (modes[1],)):
                trial = (cm, bm)
                if self.consistent(self.state(g, z, yy, trial, dirs), trial, rest, lims, z):
                    return [cm, bm]
        raise RuntimeError(f"no consistent stick/slip modes of the interfaces at rest (modes {modes!r}) at the "
                           f"state {list(yy)!r}, ground {tuple(g)!r}, nz = {z!r}")


def _joint_directions(a, b, beta: float, gamma: float, dirs) -> tuple:
    """The slaved directions of a joint slow slip of the contents on the slab and of the bearing.

    The bearing slides along ``n_b = (b + gamma n_c)/|.|`` (its need with the contents' friction
    ``gamma n_c``) and the contents along ``n_c = -(a - beta n_b)/|.|`` (minus the slab's
    acceleration were they stuck, times ``mb + m``, with the bearing's friction ``beta n_b``): the
    fixed point, by iteration (a contraction near a consistent joint slip, by the factor
    ``m/(mb + m)`` about).
    """
    nb = _unit(b, dirs[1])
    back = -np.asarray(dirs[0], dtype=float)
    for _ in range(_JOINT_ITERATIONS):
        nc = -_unit(a - beta * nb, back)
        nb_new = _unit(b + gamma * nc, nb)
        done = abs(nb_new[0] - nb[0]) + abs(nb_new[1] - nb[1]) <= 4e-16
        nb = nb_new
        if done:
            break
    return nb, -_unit(a - beta * nb, back)


@dataclass(frozen=True)
class _Segment:
    """What one segment integrates.

    ``rhs(t, y)``, its events ``(function, (interface, kind), terminal)`` and ``velocity(t, y)``,
    the sliding velocities ``(w, x')`` (units ``a_p T_p``) that the state stands for.
    """

    rhs: object
    events: list
    velocity: object


def _segment(P: _Planar, ground, nz, modes: tuple, dirs, t0: float, y0, from_rest, atol: float, lims,
             slow, gears, settle_g, plastic: bool = False) -> _Segment:
    """One segment in the modes ``modes = (contents, bearing)`` (module docstring).

    Events of an interface, by mode: stuck ``"break"`` (its need reaches its limit); slaved
    ``"stop"`` (``r`` to zero; ``r/(tau - t0)`` from rest) and ``"fast"`` (``r`` up to
    :data:`SLOW_SPEED`); sliding ``"stop"`` (``v . e`` to zero), ``"turn"`` (``v . e - cos(30
    deg) |v| + atol`` to zero), ``"slow"`` (``|v|`` down to ``slow[j]``; none when None) and
    ``"gear"`` (``|v|`` through ``gears[j][0]`` in the direction ``gears[j][1]``), all terminal;
    the contents' ``"peak"`` (``u . w`` from positive to negative) is not.  ``settle_g``, when
    given, adds ``"settle"``.  A bilinear bearing adds ``"yield"`` (``|fh|`` up to ``q``) while
    elastic, ``"unload"`` (``fh . x'`` to zero) while yielding (``plastic``).
    """
    nd = P.nd
    i_u, i_w, i_v = 4 * nd, 4 * nd + 2, 2 * nd
    slots = (i_w, i_v)
    dirs = [np.array(d, dtype=float) for d in dirs]
    cache = [None, None, None]

    def state(t, yy):
        if cache[0] == t and np.array_equal(cache[1], yy):
            return cache[2]
        s = P.state(ground(t), nz(t), yy, modes, dirs)
        cache[0], cache[1], cache[2] = t, np.array(yy), s
        return s

    def rhs(t, yy):
        return P.rates(yy, state(t, yy), modes, plastic)

    y0 = np.asarray(y0, dtype=float)
    d0 = rhs(t0, y0)
    events = []     # (function, (interface, kind), terminal, direction)
    for j in (0, 1):
        mode, ix, e = modes[j], slots[j], dirs[j]
        if mode == _STUCK:
            lim = lims[j]
            if j == 0:
                def g_break(t, yy, lim=lim):
                    af = state(t, yy).AF
                    return lim * nz(t) - math.hypot(af[0], af[1])
            else:
                def g_break(t, yy, lim=lim):
                    need = state(t, yy).need
                    return lim * nz(t) - math.hypot(need[0], need[1])
            events.append((g_break, (j, "break"), True, -1.0))
        elif mode == _SLAVED:
            r0 = max(float(d0[ix]), 0.0)

            def g_stop(t, yy, ix=ix, r0=r0, rest=from_rest[j]):
                if not rest:
                    return yy[ix]
                dt = t - t0
                return yy[ix] / dt if dt > 0.0 else r0   # a start that cannot grow stops at once

            def g_fast(t, yy, ix=ix):
                return yy[ix] - SLOW_SPEED

            events += [(g_stop, (j, "stop"), True, -1.0), (g_fast, (j, "fast"), True, 1.0)]
            if j == 0:
                def g_peak(t, yy):
                    nc = state(t, yy).nc
                    return yy[i_w] * (yy[i_u] * nc[0] + yy[i_u + 1] * nc[1])

                events.append((g_peak, (0, "peak"), False, -1.0))
        elif mode == _SLIDING:
            ex_, ey_ = float(e[0]), float(e[1])

            def g_stop(t, yy, ix=ix, ex_=ex_, ey_=ey_):
                return yy[ix] * ex_ + yy[ix + 1] * ey_

            def g_turn(t, yy, ix=ix, ex_=ex_, ey_=ey_):
                return yy[ix] * ex_ + yy[ix + 1] * ey_ - _COS_TURN * math.hypot(yy[ix], yy[ix + 1]) + atol

            def g_gear(t, yy, ix=ix, level=gears[j][0]):
                return math.hypot(yy[ix], yy[ix + 1]) - level

            events += [(g_stop, (j, "stop"), True, -1.0), (g_turn, (j, "turn"), True, -1.0),
                       (g_gear, (j, "gear"), True, gears[j][1])]
            if slow[j] is not None:
                def g_slow(t, yy, ix=ix, level=slow[j]):
                    return math.hypot(yy[ix], yy[ix + 1]) - level

                events.append((g_slow, (j, "slow"), True, -1.0))
            if j == 0:
                def g_peak(t, yy):
                    return yy[i_u] * yy[i_w] + yy[i_u + 1] * yy[i_w + 1]

                events.append((g_peak, (0, "peak"), False, -1.0))
    if P.B.hysteretic:
        i_h = 4 * nd + 4
        if plastic:
            def g_unload(t, yy):
                return float(state(t, yy).V[0] @ yy[i_h:i_h + 2])

            events.append((g_unload, (2, "unload"), True, -1.0))
        else:
            def g_yield(t, yy, q=P.B.qy):
                return q - math.hypot(yy[i_h], yy[i_h + 1])

            events.append((g_yield, (2, "yield"), True, -1.0))
    if settle_g is not None:
        events.append((settle_g, (0, "settle"), True, 1.0))
    for fn, _, terminal, direction in events:
        fn.terminal, fn.direction = terminal, direction

    def velocity(t, yy):
        s = state(t, yy)
        w = (yy[i_w] * s.nc if modes[0] == _SLAVED else
             np.array(yy[i_w:i_w + 2]) if modes[0] == _SLIDING else np.zeros(2))
        v = (yy[i_v] * s.nb if modes[1] == _SLAVED else
             np.array(yy[i_v:i_v + 2]) if modes[1] == _SLIDING else np.zeros(2))
        return w, v

    return _Segment(rhs, [ev[:3] for ev in events], velocity)


def _settle_margin(B: PlanarBuilding, lim_b: float):
    """The settlement margin of the free stuck response (module docstring), or None.

    Returns a function of the state at a free segment's start giving ``g(tau, y)``, non-decreasing
    along the free stuck response, ``>= 0`` once no interface can slip again: ``thr - sqrt(2 E
    c^T P^-1 c)`` for the contents on a moving floor, and with a held sliding bearing also
    ``q - kd |x| - sqrt(2 E c_b^T P^-1 c_b)`` (``x`` the held slab's displacement, ``E`` the
    energy of the floors above it).  None when nothing can ever slip after the pulses (the
    contents on a floor that moves with the ground, on a fixed base).
    """
    n, k, thr = B.nd, B.k, B.thr
    if B.hysteretic:
        return _hysteretic_margin(B)
    if not B.bearing:
        if k < 0:
            return None
        K, Ms = B.K, B.stuck_masses
        c = -np.concatenate([K[k], B.C[k]]) / Ms[k]
        P = np.zeros((2 * n, 2 * n))
        P[:n, :n], P[n:, n:] = K, np.diag(Ms)
        scale = math.sqrt(float(c @ np.linalg.solve(P, c)))

        def g(t, yy):
            D = yy[:2 * n].reshape(n, 2)
            V = yy[2 * n:4 * n].reshape(n, 2)
            return thr - math.sqrt(_largest_energy(D, V, K, Ms)) * scale

        return lambda y: g
    # a held sliding bearing: the floors above the held slab are free, xs = d_j - x
    f = n - 1
    Ks, Cs, Mf = B.K[1:, 1:], B.C[1:, 1:], B.stuck_masses[1:]
    scales = []
    if f:
        P = np.zeros((2 * f, 2 * f))
        P[:f, :f], P[f:, f:] = Ks, np.diag(Mf)
        cb = np.concatenate([Ks.sum(axis=0), Cs.sum(axis=0)])
        scales.append((lim_b, True, math.sqrt(float(cb @ np.linalg.solve(P, cb)))))
        if k >= 1:
            cc = -np.concatenate([Ks[k - 1], Cs[k - 1]]) / Mf[k - 1]
            scales.append((thr, False, math.sqrt(float(cc @ np.linalg.solve(P, cc)))))
    else:
        scales.append((lim_b, True, 0.0))
    kd = B.kd

    def margin(y):
        held = kd * math.hypot(y[0], y[1])

        def g(t, yy):
            if f:
                D = yy[:2 * n].reshape(n, 2)
                r = math.sqrt(_largest_energy(D[1:] - D[0], yy[2 * n + 2:4 * n].reshape(f, 2), Ks, Mf))
            else:
                r = 0.0
            return min(lim - (held if bearing else 0.0) - r * s for lim, bearing, s in scales)

        return g

    return margin


def _hysteretic_margin(B: PlanarBuilding):
    """The settlement margin on an elastic bilinear bearing (module docstring): ``y -> g(tau, y)``.

    With the plastic offset ``x_p`` of the state at the free segment's start, ``g`` is the least of
    ``thr - sqrt(2 E c^T P^-1 c)`` and ``q - ke |d*_0 - x_p| - sqrt(2 E c_h^T P^-1 c_h)``, ``E`` the
    energy of ``d - d*`` with ``K'``, ``c_h = ke e_0``.
    """
    n, k = B.nd, B.k
    K, Ms = B.elastic_K, B.stuck_masses
    P = np.zeros((2 * n, 2 * n))
    P[:n, :n], P[n:, n:] = K, np.diag(Ms)
    cc = -np.concatenate([K[k], B.C[k]]) / Ms[k]
    ch = np.zeros(2 * n)
    ch[0] = B.ke
    sc = math.sqrt(float(cc @ np.linalg.solve(P, cc)))
    sh = math.sqrt(float(ch @ np.linalg.solve(P, ch)))
    e0 = np.zeros(n)
    e0[0] = 1.0
    r = B.ke * np.linalg.solve(K, e0)       # d* = r x_p^T
    i_h = 4 * n + 4

    def margin(y):
        xp = np.asarray(y[0:2], dtype=float) - np.asarray(y[i_h:i_h + 2], dtype=float) / B.ke
        dstar = np.outer(r, xp)
        off = B.ke * math.hypot(*(dstar[0] - xp))

        def g(t, yy):
            D = yy[:2 * n].reshape(n, 2) - dstar
            e = math.sqrt(_largest_energy(D, yy[2 * n:4 * n].reshape(n, 2), K, Ms))
            return min(B.thr - e * sc, B.qy - off - e * sh)

        return g

    return margin


def _largest_energy(D, V, K, M) -> float:
    """Twice the largest energy of the motion projected on a horizontal direction.

    ``lambda_max(Q)``, ``Q = D^T K D + V^T M V`` (2 x 2), ``D`` and ``V`` the coordinates and
    velocities of both axes, shape ``(n, 2)``.
    """
    Q = D.T @ K @ D + (V * M[:, None]).T @ V
    return max(0.5 * (Q[0, 0] + Q[1, 1] + math.hypot(Q[0, 0] - Q[1, 1], 2.0 * Q[0, 1])), 0.0)
