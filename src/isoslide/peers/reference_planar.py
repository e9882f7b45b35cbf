"""Independent event-driven reference solver of contents sliding in the plane of the floor.

The planar sibling of :mod:`isoslide.peers.reference_building`: the same buildings (fixed base, or
a linear isolator under a rigid superstructure or a flexible shear building of ``N`` storeys),
moved by two horizontal ground components and optionally a vertical one, carry contents that
slide in any direction on their floor.  The right-hand side is plain Python + NumPy, integrated
segment by segment with :func:`scipy.integrate.solve_ivp` (``DOP853``, and ``Radau`` for slow
slips, see below) and every transition located with ``solve_ivp``'s events; nothing comes from the
compiled kernel (:mod:`isoslide.engine`), so the two can check each other.  Hysteretic isolators
(``Pi9 > 0``) are not modelled (refused).

Model (dimensionless: ``tau = t/T_p``, lengths ``a_p T_p**2``, accelerations ``a_p``, masses ``M_b``)
---------------------------------------------------------------------------------------------------
Ground.  ``g(tau) = (g_x, g_y)`` in the building's axes: the excitation
``(p(tau), Pi14 p_y((tau - Pi16)/Pi15))`` turned by ``scene.angle`` (no ``p_y`` term without a
``pulse_y``), as :meth:`isoslide.Scene.ground`.  Vertical: the normal-force factor
``nz(tau) = 1 + Pi17 p_z(tau)`` (1 without a ``pulse_z``; ``p_z`` on the main pulse's time axis).

Building, the same in ``x`` and in ``y`` (isotropic) and the two axes coupled only through the
contents' friction force.  Coordinates ``d`` relative to the ground, one per moving mass:

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
  ``C = cb e_0 e_0^T + T^T Cs T`` with ``xs = T d`` (``T = [-1 | I]``).

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
``w`` is held (``w = r n`` between slaved and sliding).  At a stop ``w = 0`` and the block sticks
if ``|A_S| <= thr nz``, else it starts again along ``-A_S/|A_S|``.

Inside a slip ``|u|`` peaks where ``(|u|**2)'/2 = u . w`` goes from positive to negative (a
non-terminal event); ``|u|`` is also taken at every stop and at the end of every segment, so the
maximum over time is exact.  A stuck block breaks away at the root of ``thr nz - |A_F|``
(terminal).  Segments also end at every breakpoint of the three pulses (each pulse's start and
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
decides where the run stops, never ``Pi1``.  A fixed base with the contents on the ground-fixed
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
from .reference_building import shear_building
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
        lam = scipy.linalg.eigh(self.K, np.diag(self.stuck_masses), eigvals_only=True)
        return [2.0 * math.pi / math.sqrt(v) for v in lam if v > 0.0]


def planar_building(scene: Scene) -> PlanarBuilding:
    """The building of a scene (module docstring); refuses a hysteretic isolator.

    Parameters
    ----------
    scene : Scene
        ``Pi9 = 0`` (a linear isolator, or a fixed base with ``Pi3 = 0``).

    Returns
    -------
    PlanarBuilding

    Raises
    ------
    ValueError
        ``pi9 > 0`` (a bilinear or sliding bearing), which this peer does not model.
    """
    if scene.pi9 > 0.0:
        raise ValueError(f"pi9 = {scene.pi9!r} (a hysteretic isolator) is not modelled by the planar reference "
                         "peer; allowed: pi9 = 0 (a linear isolator, or a fixed base with pi3 = 0)")
    flexible = scene.pi12 > 0.0
    floor = scene.floor_index if flexible else 0
    if flexible:
        n = scene.storeys
        shares = np.full(n, 1.0 / n) if scene.floor_masses is None else np.asarray(scene.floor_masses, dtype=float)
        ms = scene.pi11 * shares
        r = np.ones(n) if scene.storey_stiffnesses is None else np.asarray(scene.storey_stiffnesses, dtype=float)
        Ks, Cs, _ = shear_building(ms, r, scene.pi12, scene.pi13)
    common = dict(m=float(scene.pi8), thr=scene.pi2 / scene.pi5, pi2=float(scene.pi2), pi6=float(scene.pi6),
                  pi7=float(scene.pi7))
    if scene.pi3 == 0.0:
        if flexible and floor > 0:
            return PlanarBuilding(masses=ms, K=Ks, C=Cs, k=floor - 1, **common)
        return PlanarBuilding(masses=np.zeros(0), K=np.zeros((0, 0)), C=np.zeros((0, 0)), k=-1, **common)
    wb = 2.0 * math.pi / scene.pi3
    kd, cb = wb * wb, 2.0 * scene.pi4 * wb
    if not flexible:
        return PlanarBuilding(masses=np.ones(1), K=np.array([[kd]]), C=np.array([[cb]]), k=0, **common)
    T = np.hstack([-np.ones((n, 1)), np.eye(n)])
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
        Any scene with ``Pi9 = 0`` (a linear isolator or a fixed base; rigid or flexible
        superstructure; one or two horizontal components at any angle; vertical motion).
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
        at the end, ``n_events`` the breakaways (from rest, also right after a stop) and stops,
        ``nfev`` the right-hand-side evaluations of both integrators.

    Raises
    ------
    ValueError
        ``pi9 > 0`` (hysteretic isolator), ``history = True``, or a bad ``horizon``.
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
    i_u, i_w = 4 * B.nd, 4 * B.nd + 2
    lim = B.thr * (1.0 + _ULP4)
    stiff = STIFF_SPEED * B.thr
    tau_end = ex.tau_end
    t_stop = tau_end + float(horizon) * max(1.0, scene.pi3, scene.pi12)
    bps = [b for b in ex.breakpoints() if b < t_stop] + [t_stop]
    periods = B.periods()
    short = scene.pi15 if ex.y is not None else 1.0
    hmax_pulse = min([1.0 / 64.0, short / 64.0] + [T / 32.0 for T in periods])
    hmax_free = min([max(1.0, scene.pi3) / 64.0] + [T / 32.0 for T in periods])
    settle_g = _settle_margin(B) if settle else None
    sample_t = np.sort(np.asarray(samples, dtype=float).ravel()) if samples is not None else None
    rec_t, rec_y = [], []

    tau = ex.tau_start
    y = np.zeros(4 * B.nd + 4)
    mode = _STUCK
    implicit = False            # sliding: Radau (slow, stiff) or DOP853
    from_rest = False
    e = np.array([1.0, 0.0])     # a sliding segment's reference direction
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
        # ---- the mode at the segment start --------------------------------------------------
        if mode == _STUCK:
            y[i_w:i_w + 2] = 0.0
            af = _stuck_af(B, y, ground(tau))
            if math.hypot(af[0], af[1]) > lim * nz(tau):
                mode, from_rest = _SLAVED, True
                n_events += 1
        elif mode == _SLIDING:
            speed = math.hypot(y[i_w], y[i_w + 1])
            if speed < 0.75 * SLOW_SPEED:
                n_s = _slaved_direction(B, y, ground(tau), e)
                if y[i_w] * n_s[0] + y[i_w + 1] * n_s[1] >= speed * _COS_RELAXED:
                    y[i_w:i_w + 2] = (speed, 0.0)   # relaxed: slaved from here
                    mode, e = _SLAVED, n_s
                else:                       # not relaxed, so not stiff: the exact equations, explicitly
                    implicit = False
        free = mode == _STUCK and tau >= tau_end
        if free and settle and (settle_g is None or settle_g(tau, y) >= 0.0):
            settled = True
            break
        if tau >= t_stop:
            break
        # ---- this segment -------------------------------------------------------------------
        method = "DOP853"
        if mode == _SLAVED:
            seg = _slaved_segment(B, ground, nz, e, tau, y, from_rest)
        elif mode == _SLIDING:
            seg = _sliding_segment(B, ground, nz, e, atol, SLOW_SPEED / 2.0 if speed >= 0.75 * SLOW_SPEED else None,
                                   (2.0 * stiff, 1.0) if implicit else (stiff, -1.0))
            method = "Radau" if implicit else "DOP853"
        else:
            seg = _stuck_segment(B, ground, nz, lim, settle_g if free else None)
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
                rec_y.append(np.vstack([ys[i_u:i_u + 2], np.array([seg.velocity(t, c) for t, c in
                                                                   zip(ts, ys.T, strict=True)]).T]))
        for (_, _kind, terminal), te, ye in zip(specs, sol.t_events, sol.y_events, strict=True):
            if not terminal:            # the peaks of |u| inside a slip
                for t_, y_ in zip(te, ye, strict=True):
                    note(t_, y_)
        from_rest = False
        if sol.status != 1:             # the segment's end: a breakpoint or the horizon
            tau = t_end
            y = np.array(sol.y[:, -1], dtype=float)
            note(tau, y)
            if mode == _SLIDING:
                e = _unit(y[i_w:i_w + 2], e)
            continue
        te, ye, kind = min(((te[0], ye[0], s[1]) for te, ye, s in zip(sol.t_events, sol.y_events, specs, strict=True)
                            if s[2] and len(te)), key=lambda h: h[0])
        zero_len = zero_len + 1 if te <= tau else 0
        if zero_len > 8:
            raise RuntimeError(f"zero-length stick/slip chatter at tau={te!r}; scene={scene!r}")
        tau = float(te)
        y = np.array(ye, dtype=float)
        note(tau, y)
        if kind == "settle":
            settled = True
            break
        if kind == "break":             # slides from rest along -A_S/|A_S|
            mode, from_rest = _SLAVED, True
            n_events += 1
        elif kind == "stop":
            y[i_w:i_w + 2] = 0.0
            mode = _STUCK
            n_events += 1
        elif kind == "fast":            # the slaved speed reached SLOW_SPEED: the exact equations
            w = seg.velocity(tau, y)
            y[i_w:i_w + 2] = w
            e = _unit(w, e)
            mode, implicit = _SLIDING, True
        elif kind == "gear":            # between the explicit and the implicit integrator
            implicit = not implicit
            e = _unit(y[i_w:i_w + 2], e)
        else:                           # "turn", "slow": a new segment (slaved if slow and relaxed)
            e = _unit(y[i_w:i_w + 2], e)

    note(tau, y)
    res = PeerResult(method="reference", pi1=float(peak), pi1_residual=float(math.hypot(y[i_u], y[i_u + 1])),
                     tau_peak=float(tau_peak), settled=settled, n_events=n_events, tau_end=float(tau),
                     nfev=int(nfev), integrator="DOP853", peak_angle=float(angle_peak))
    if rec_t:
        tt, yy = np.concatenate(rec_t), np.concatenate(rec_y, axis=1)
    else:
        tt, yy = np.zeros(0), np.zeros((4, 0))
    return PlanarRun(result=res, tau=tt, u=yy[:2], w=yy[2:])


_STUCK, _SLAVED, _SLIDING = 0, 1, 2
"""The block's modes: stuck, sliding slowly along the slaved direction, sliding (module docstring)."""


@dataclass(frozen=True)
class _Segment:
    """What one segment integrates.

    ``rhs(t, y)``, its events ``(function, kind, terminal)`` and ``velocity(t, y)``, the sliding
    velocity ``w`` (units ``a_p T_p``) that the state stands for.
    """

    rhs: object
    events: list
    velocity: object


def _forces(B: PlanarBuilding, yy):
    """``-(C d' + K d)`` (shape ``(nd, 2)``, units ``M_b a_p``): every floor's spring and damper forces."""
    nd = B.nd
    return -(B.C @ yy[2 * nd:4 * nd].reshape(nd, 2) + B.K @ yy[:2 * nd].reshape(nd, 2))


def _stuck_af(B: PlanarBuilding, y, g) -> tuple:
    """Absolute acceleration ``A_S`` (units ``a_p``) of the contents' floor with the block stuck.

    ``g`` is the ground acceleration ``(g_x, g_y)``; on a moving floor the ground term cancels.
    """
    k, nd = B.k, B.nd
    if k < 0:
        return float(g[0]), float(g[1])
    a = -(B.K[k] @ y[:2 * nd].reshape(nd, 2) + B.C[k] @ y[2 * nd:4 * nd].reshape(nd, 2)) / (B.masses[k] + B.m)
    return float(a[0]), float(a[1])


def _slaved_direction(B: PlanarBuilding, y, g, fallback) -> np.ndarray:
    """``-A_S/|A_S|`` (``fallback`` where ``A_S = 0``): the direction a slow slip relaxes to."""
    return _unit([-a for a in _stuck_af(B, y, g)], fallback)


def _stuck_segment(B: PlanarBuilding, ground, nz, lim: float, settle_g) -> _Segment:
    """A segment with the block stuck.

    Events: ``"break"`` (``|A_S|`` reaches ``lim nz``) and, when ``settle_g`` is given, ``"settle"``.
    """
    nd = B.nd
    Mst = B.stuck_masses

    def rhs(t, yy):
        d = np.zeros(yy.size)
        if nd:
            gx, gy = ground(t)
            acc = _forces(B, yy) / Mst[:, None]
            acc[:, 0] -= gx
            acc[:, 1] -= gy
            d[:2 * nd] = yy[2 * nd:4 * nd]
            d[2 * nd:4 * nd] = acc.ravel()
        return d

    def g_break(t, yy):
        af = _stuck_af(B, yy, ground(t))
        return lim * nz(t) - math.hypot(af[0], af[1])

    g_break.terminal, g_break.direction = True, -1.0
    events = [(g_break, "break", True)]
    if settle_g is not None:
        settle_g.terminal, settle_g.direction = True, 1.0
        events.append((settle_g, "settle", True))
    return _Segment(rhs, events, lambda t, yy: np.zeros(2))


def _slaved_segment(B: PlanarBuilding, ground, nz, e, t0: float, y0, from_rest: bool) -> _Segment:
    """A slow slip: the speed ``r`` (held in ``y[w_x]``) along ``n = -A_S/|A_S|`` (module docstring).

    Events: ``"stop"`` (``r`` to zero; ``r/(tau - t0)`` from rest) and ``"fast"`` (``r`` up to
    :data:`SLOW_SPEED`), terminal, and ``"peak"`` (``u . n`` from positive to negative).  ``e``
    is the direction where ``A_S = 0``.
    """
    nd, k, m = B.nd, B.k, B.m
    M = B.masses
    i_u, i_w = 4 * nd, 4 * nd + 2
    ex_, ey_ = float(e[0]), float(e[1])
    phi = B.phi

    def parts(t, yy):
        """Direction, floor acceleration, floor forces (None on a ground-fixed floor), friction, ground."""
        g = ground(t)
        fr = nz(t) * phi(abs(yy[i_w]))
        if k >= 0:
            f = _forces(B, yy)
            ax, ay = f[k]
        else:
            f = None
            ax, ay = g
        a = math.hypot(ax, ay)
        nx, ny = (-ax / a, -ay / a) if a > 0.0 else (ex_, ey_)
        if k >= 0:
            f[k, 0] += m * fr * nx
            f[k, 1] += m * fr * ny
            afx, afy = f[k, 0] / M[k], f[k, 1] / M[k]
        else:
            afx, afy = ax, ay
        return nx, ny, afx, afy, f, fr, g

    def rhs(t, yy):
        nx, ny, afx, afy, f, fr, g = parts(t, yy)
        r = yy[i_w]
        d = np.zeros(yy.size)
        if k >= 0:
            acc = f / M[:, None]
            acc[:, 0] -= g[0]
            acc[:, 1] -= g[1]
            d[:2 * nd] = yy[2 * nd:4 * nd]
            d[2 * nd:4 * nd] = acc.ravel()
        d[i_u], d[i_u + 1] = r * nx, r * ny
        d[i_w] = -(afx * nx + afy * ny) - fr
        return d

    r0 = float(rhs(t0, np.asarray(y0, dtype=float))[i_w])

    def g_stop(t, yy):
        if not from_rest:
            return yy[i_w]
        dt = t - t0
        return yy[i_w] / dt if dt > 0.0 else max(r0, 0.0)   # a start that cannot grow stops at once

    def g_fast(t, yy):
        return yy[i_w] - SLOW_SPEED

    def g_peak(t, yy):
        nx, ny = parts(t, yy)[:2]
        return yy[i_w] * (yy[i_u] * nx + yy[i_u + 1] * ny)

    def velocity(t, yy):
        nx, ny = parts(t, yy)[:2]
        return np.array([yy[i_w] * nx, yy[i_w] * ny])

    for fn, terminal, direction in ((g_stop, True, -1.0), (g_fast, True, 1.0), (g_peak, False, -1.0)):
        fn.terminal, fn.direction = terminal, direction
    return _Segment(rhs, [(g_stop, "stop", True), (g_fast, "fast", True), (g_peak, "peak", False)], velocity)


def _sliding_segment(B: PlanarBuilding, ground, nz, e, slack: float, slow, gear) -> _Segment:
    """A sliding segment with the reference direction ``e`` (module docstring).

    The friction direction is ``sgn(w . e) w/|w|`` (``e`` where ``w = 0``).  Events, terminal:
    ``"stop"`` (``w . e`` to zero), ``"turn"`` (``w . e - cos(30 deg) |w| + slack`` to zero: ``w``
    30 degrees from ``e``, ``slack`` the velocity's absolute tolerance), ``"slow"`` (``|w|`` down to
    ``slow``; none when ``slow`` is None) and ``"gear"`` (``|w|`` through ``gear[0]`` in the
    direction ``gear[1]``); and ``"peak"`` (``u . w`` from positive to negative).
    """
    nd, k, m = B.nd, B.k, B.m
    M = B.masses
    i_u, i_w = 4 * nd, 4 * nd + 2
    ex_, ey_ = float(e[0]), float(e[1])
    phi = B.phi

    def rhs(t, yy):
        gx, gy = ground(t)
        wx, wy = yy[i_w], yy[i_w + 1]
        s = math.hypot(wx, wy)
        if s > 0.0:
            sg = 1.0 if wx * ex_ + wy * ey_ >= 0.0 else -1.0
            nx, ny = sg * wx / s, sg * wy / s
        else:
            nx, ny = ex_, ey_
        fr = nz(t) * phi(s)
        d = np.empty(yy.size)
        if k >= 0:
            f = _forces(B, yy)
            f[k, 0] += m * fr * nx
            f[k, 1] += m * fr * ny
            acc = f / M[:, None]
            afx, afy = acc[k, 0], acc[k, 1]
            acc[:, 0] -= gx
            acc[:, 1] -= gy
            d[:2 * nd] = yy[2 * nd:4 * nd]
            d[2 * nd:4 * nd] = acc.ravel()
        else:
            afx, afy = gx, gy
        d[i_u], d[i_u + 1] = wx, wy
        d[i_w], d[i_w + 1] = -afx - fr * nx, -afy - fr * ny
        return d

    def g_stop(t, yy):
        return yy[i_w] * ex_ + yy[i_w + 1] * ey_

    def g_turn(t, yy):
        return yy[i_w] * ex_ + yy[i_w + 1] * ey_ - _COS_TURN * math.hypot(yy[i_w], yy[i_w + 1]) + slack

    def g_peak(t, yy):
        return yy[i_u] * yy[i_w] + yy[i_u + 1] * yy[i_w + 1]

    def g_gear(t, yy):
        return math.hypot(yy[i_w], yy[i_w + 1]) - gear[0]

    events = [(g_stop, "stop", True, -1.0), (g_turn, "turn", True, -1.0), (g_gear, "gear", True, gear[1]),
              (g_peak, "peak", False, -1.0)]
    if slow is not None:
        def g_slow(t, yy):
            return math.hypot(yy[i_w], yy[i_w + 1]) - slow

        events.append((g_slow, "slow", True, -1.0))
    for fn, _, terminal, direction in events:
        fn.terminal, fn.direction = terminal, direction
    return _Segment(rhs, [ev[:3] for ev in events], lambda t, yy: np.array(yy[i_w:i_w + 2]))


def _unit(v, fallback) -> np.ndarray:
    """``v/|v|``, or ``fallback`` for a zero vector."""
    r = math.hypot(v[0], v[1])
    return np.array([v[0] / r, v[1] / r]) if r > 0.0 else np.asarray(fallback, dtype=float)


def _settle_margin(B: PlanarBuilding):
    """The settlement margin ``g(tau, y) = thr - sqrt(lambda_max(Q) c^T P^-1 c)`` (module docstring).

    ``Q = D^T K D + V^T Ms V`` (2 x 2; ``D``, ``V`` the coordinates and velocities of both axes) holds
    twice the energy of the motion projected on any direction ``d``, ``d^T Q d``, which never
    increases along the free stuck response; so neither does ``lambda_max(Q)``, and ``g`` never
    decreases.  ``g >= 0`` once the contents can never slide again.  None when the contents' floor
    moves with the ground (after the pulses nothing can move it).
    """
    if B.k < 0:
        return None
    n, k = B.nd, B.k
    K, Ms = B.K, B.stuck_masses
    c = -np.concatenate([K[k], B.C[k]]) / Ms[k]
    P = np.zeros((2 * n, 2 * n))
    P[:n, :n], P[n:, n:] = K, np.diag(Ms)
    scale = math.sqrt(float(c @ np.linalg.solve(P, c)))
    thr = B.thr

    def g(t, yy):
        D = yy[:2 * n].reshape(n, 2)
        V = yy[2 * n:4 * n].reshape(n, 2)
        Q = D.T @ K @ D + (V * Ms[:, None]).T @ V
        lam = 0.5 * (Q[0, 0] + Q[1, 1] + math.hypot(Q[0, 0] - Q[1, 1], 2.0 * Q[0, 1]))
        return thr - math.sqrt(max(lam, 0.0)) * scale

    return g
