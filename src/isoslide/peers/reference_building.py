"""Independent event-driven reference solver of the general building (plain Python + SciPy).

The general building extends the paper's model (Fig. 1-b) to Fig. 1-a and beyond: a nonlinear
isolator (bilinear bearing, or sliding bearing with true stick), a flexible superstructure of
``N`` storeys (a shear chain), and contents on the base slab or on any floor above it.  Like
:mod:`isoslide.peers.reference` it integrates phase by phase with
:func:`scipy.integrate.solve_ivp` (``DOP853``) and locates every transition with ``solve_ivp``'s
events; it is written from the equations below only, independently of the compiled kernel, to
cross-check it.

Model (dimensionless: ``tau = t/T_p``, lengths ``a_p T_p**2``, masses ``M_b``, forces ``M_b a_p``)
------------------------------------------------------------------------------------------------
Parameters: ``kd = (2 pi/Pi3)**2``, ``cb = 2 Pi4 (2 pi/Pi3)``, ``q = Pi9`` and ``ke = Pi9/Pi10``
(bilinear), ``m = Pi8``, ``thr = Pi2/Pi5`` and the friction level
``phi(v) = thr sech(Pi6 v) + Pi2 (1 - sech(Pi6 v)) + Pi7 |v|``.  A sliding bearing's friction may
rise with its speed (Constantinou, Mokha and Reinhorn 1990): its level at the slab's speed ``|x'|``
is ``q(|x'|) = Pi9 (1 - (1 - Pi22) exp(-Pi23 |x'|))``, from the breakaway level ``q0 = q(0) =
Pi9 Pi22`` up to ``Pi9``, and its stick limit is ``q0``.  With ``Pi23 = 0`` (``q0`` at every speed)
or ``Pi22 = 1`` (``Pi9``) the friction is constant: the bearing is then the constant-strength one of
``q(|x'|) = q0``, with the same numbers to the bit as a scene given ``Pi9 = Pi9 Pi22``.  While the
bearing slides in ``s`` its friction is computed as ``q(s x')``, whose smooth continuation past
``s x' = 0`` the integrator sees only inside the step that reaches a stop: the stop is then located
as accurately as any other event (``q(|x'|)`` has a kink there).

Superstructure.  Rigid when ``Pi12 = 0``: no floor states, slab mass ``mb = 1``, and the contents
are on the slab whatever ``scene.floor`` says.  Flexible when ``Pi12 > 0``: ``N = scene.storeys``
floors above the slab, of masses ``m_j = Pi11 w_j`` (``w_j = floor_masses[j-1]``, or ``1/N``),
slab mass ``mb = 1 - Pi11``.  Storey ``j = 1 .. N`` joins floor ``j-1`` and floor ``j`` (floor 0 is
the slab) with stiffness ``kappa r_j`` (``r_j = storey_stiffnesses[j-1]``, or 1).  ``Ks`` is the
``N x N`` fixed-base (slab held) stiffness matrix of this shear chain and ``Ms = diag(m_j)``;
``kappa`` makes the smallest eigenvalue of ``Ms^-1 Ks`` equal to ``(2 pi/Pi12)**2`` (the fixed-base
fundamental period is ``T_s``).  Damping is classical with ratio ``Pi13`` in every fixed-base mode:
``Cs = Ms Phi diag(2 Pi13 omega_i) Phi^T Ms``, ``Phi`` the mass-normalised fixed-base modes
(``Phi^T Ms Phi = I``), ``omega_i**2`` the eigenvalues.  With ``N = 1``: ``ks = m_1 (2 pi/Pi12)**2``,
``cs = 2 Pi13 (2 pi/Pi12) m_1``.

States ``y = (x, x', xs_1 .. xs_N, xs_1' .. xs_N', u, u', fh)``: slab rel. ground, floors rel.
slab, block rel. its floor, hysteretic isolator force (a rigid superstructure keeps one
unused floor slot at zero).  ``Ab = p + x''`` is the slab's absolute acceleration,
``A_j = Ab + xs_j''`` floor ``j``'s, ``A_F`` that of the block's floor ``k`` (``k = 0`` the slab)::

    F = kd x + cb x' + fh                   (isolator on the slab)
    f = Ks xs + Cs xs'                      (superstructure on its floors, a vector)
    slab:      mb Ab  = -F + sum_j f_j + [R on the slab]
    floor j:   m_j A_j = -f_j + [R on floor j]
    block:     m (A_F + u'') = -R

Block: stuck ``u' = 0``, ``R = -m A_F`` while ``|A_F| <= thr``; sliding in ``s = sgn(u')``,
``R = m s phi(|u'|)``.  Isolator: linear ``fh = 0``; bilinear (elastic-perfectly-plastic,
stiffness ``ke``, strength ``q``) ``fh' = ke x'`` while elastic, ``fh = +-q`` while yielding (from
``|fh| = q`` until ``x'`` changes sign); sliding bearing ``fh = q(|x'|) sgn(x')`` while sliding,
held (``x' = x'' = 0``, ``Ab = p``) while the force it must supply,
``fh_needed = -mb p - kd x + sum_j f_j + [R on the slab]``, is within ``|fh_needed| <= q0``.  A fixed
base (``Pi3 = 0``) is a bearing held for ever.  Every acceleration is explicit in the mode (no
linear solve; the floors' forces depend on the state only): with the slab held ``Ab = p``;
moving, ``Ab = (-F + S)/(mb + m)`` (block stuck on the slab), ``(-F + S + R)/mb`` (sliding on the
slab) or ``(-F + S)/mb`` (block upstairs), ``S = sum_j f_j``; floor ``j`` ``A_j = -f_j/m_j``, and
the block's floor ``-f_k/(m_k + m)`` (stuck) or ``(-f_k + R)/m_k`` (sliding).

Mode selection
--------------
The block and a sliding bearing are frictional interfaces.  At every phase start (pulse
breakpoints and events) the interfaces at zero relative velocity (a stuck one, or one that just
stopped) get their modes chosen together: the combinations of (stuck, +1, -1) are tried in the
order all stuck; block stuck & bearing sliding; block sliding & bearing stuck; both sliding, and
the first *consistent* one is taken: every stuck interface's needed force within its limit
(``|A_F| <= thr``, ``|fh_needed| <= q0``) and every sliding one accelerating in its own direction
(``s u'' > 0``, ``s x'' > 0``; a bearing leaving rest does so against its breakaway friction
``q(0) = q0``, the level of its stick limit).  An interface whose stick limit was just reached (a
breakaway event) slides in the direction of its needed force; breakaways are force-continuous
(``phi(0) = thr``, ``q(0) = q0``), so the other interface keeps its mode unless it is inconsistent
by itself.
The bilinear bearing's yield (``|fh| = q``) and unloading (``x' = 0``) are force-continuous too.
The rule and the state's layout are :mod:`isoslide.peers.stick_slip`, shared with the SI peer.
``Pi1 = max |u|``, taken at the block's stops and at the end (``|u|`` peaks only there).
A stop (a sliding velocity ``v`` back to zero) is located as the root of ``s v / (t - t0)``, which
has the sign of ``s v`` but not its trivial root at a phase start ``t0`` from rest: a reversal
that starts with a tiny acceleration and ends within one step is still found.

Vertical ground motion
----------------------
With ``Pi17 > 0`` and a vertical pulse shape ``p_z`` (``scene.vertical``; upward ground acceleration
``Pi17 g p_z(tau)`` on the horizontal pulse's time axis) the building, rigid vertically, moves up
and down with the ground, so every normal force carries the factor ``n(tau) = 1 + Pi17 p_z(tau)``
(``> 0``; the scene refuses lift-off).  The contents slide against ``R = m s n phi(|u'|)`` and stick
while ``|A_F| <= n thr``; a sliding bearing (friction pendulum) has the friction ``q(|x'|) n``, is
held while ``|fh_needed| <= q0 n`` with ``fh_needed = -mb p - kd n x + S + [R on the slab]``, and its
restoring stiffness is ``kd n`` (the pendulum's force ``W x / R`` scales with the weight).  Linear
and bilinear isolators and the superstructure do not change.  The vertical pulse's breakpoints are
phase breakpoints, and "after the pulse" below means after both pulses (``n = 1`` again): from
``max(tau_end, tau_end_z)``.  Before the horizontal pulse starts the building is at rest and stays
so (``p = 0``, every stick need zero), so the run starts at the horizontal pulse's start.

Settlement bound
----------------
After the pulse, with the block stuck and the bearing held, elastic or linear, the system is free
and linear: ``M z'' + C z' + K z = f`` with ``z = (x, xs_1 .. xs_N)`` (only the ``xs`` with the
slab held; none for a held slab under a rigid superstructure).  About its equilibrium ``z*`` the
energy ``E = (dz' M dz' + dz K dz)/2`` never increases (``C >= 0``), and every demand (the floor
acceleration ``A_F``, the bilinear force ``fh``, the held bearing's ``fh_needed``) is affine,
``d = d0 + c . w`` with ``w = (z - z*, z')``; so for all later times
``|d| <= |d0| + sqrt(2 E c^T P^-1 c)``, ``P = diag(K, M)`` (Cauchy-Schwarz).  The run settles
(``settled = True``) at the first moment every bound is within its limit: this is a terminal
event of the free phase, and changes only where the run stops, never ``Pi1``.  A run that has not
settled by the horizon (default ``tau_end + max(50 max(1, Pi3, Pi12), 50/rate)``, ``tau_end`` the
later end of the two pulses, ``rate`` the
slowest decay rate of the free system, 0 for an undamped one) ends with ``settled = False``.

Creep of a bearing whose friction rises with speed
--------------------------------------------------
After the pulse (``p = 0``, ``n = 1``) a bearing moving in ``s`` that would come to rest where
``q0 < |kd x| <= Pi9`` cannot be held there (its need exceeds ``q0``), yet moving it meets a
friction ``q(|x'|) > q0`` that balances the spring at a small speed.  About the edge of the stick
band, ``x* = -s q0/kd``, the motion is linearised as ``M x'' + (cb + (Pi9 - q0) Pi23) x' +
kd (x - x*) = 0`` (``q'(0) = Pi9 (1 - Pi22) Pi23``); when that is over-damped, ``x`` tends to ``x*``
with ``x'`` decaying exponentially and never zero: the bearing creeps to the edge of its band and
does not stop in finite time.  Nothing special is done for it (the stop event simply does not
occur), so without the rule below the run ends at the horizon with ``settled = False``: ``Pi1``
and the residual slide are those up to the horizon and the slab is still creeping.  The horizon's
``rate`` is the free pendulum's (``kd``, ``cb``), not the slower creep's
(``~ kd/(cb + (Pi9 - q0) Pi23)`` when strongly over-damped).

For a rigid superstructure (``Pi12 = 0``) with the contents stuck (on the slab; ``M = 1 + m``) and
the bearing moving in ``s`` after the pulse, the run settles by an exact bound.  With
``E = M x'^2/2 + kd (x - x*)^2/2``, as ``kd x + s q0 = kd (x - x*)``::

    M x'' = -kd (x - x*) - cb x' - s (q(|x'|) - q0)
    dE/dtau = x' (M x'' + kd (x - x*)) = -cb x'^2 - s x' (q(|x'|) - q0) = -cb x'^2 - |x'| (q(|x'|) - q0) <= 0

since ``s x' = |x'|`` and ``q(v) >= q0``: ``E`` does not increase while the bearing moves in
``s``.  The contents' demand is ``A_F = x''``; by Cauchy-Schwarz in the energy's norm
``|kd (x - x*) + cb x'| <= sqrt(2 E (kd + cb^2/M))`` (at most ``sqrt(2 E kd) + cb sqrt(2 E/M)``), and
``0 <= q(v) - q0 = (Pi9 - q0)(1 - exp(-Pi23 v)) <= (Pi9 - q0) min(1, Pi23 v)`` with
``v = |x'| <= sqrt(2 E/M)``, so

    ``|A_F| <= [sqrt(2 E (kd + cb^2/M)) + (Pi9 - q0) min(1, Pi23 sqrt(2 E/M))] / M``,

a bound that grows with ``E`` and so does not grow in time.  When it is within ``thr`` the contents
do not slip while the bearing moves in ``s``.  If the bearing stops, it does so from the side
``s``, so there ``s x'' <= 0``, and at ``x' = 0`` ``M s x'' = -kd s (x - x*)``: the stop is at
``0 <= s (x - x*) <= sqrt(2 E/kd)`` (``kd (x - x*)^2/2`` is then all of ``E``, no more than now).
The stick band ``|kd x| <= q0`` is ``0 <= s (x - x*) <= 2 q0/kd``, so with
``sqrt(2 E/kd) <= 2 q0/kd`` the stop lands inside it: the bearing is held (``|fh_needed| = |kd x|
<= q0``, the contents' demand ``p = 0``) and, ``p = 0`` with a rigid building, nothing moves again.
Either way the contents never slip again, and the run settles at the first moment both
conditions hold (at a phase start, or as a terminal event of the phase, like the bound above).
``Pi1`` and the residual slide are then final; the slab's last state is not its rest (it may
still creep or stop).  A bearing of constant friction stops in finite time and is then judged by
the free system's bound, so this rule is used only for one whose friction rises with speed; under
a flexible superstructure, or with the contents sliding, the run goes on until the bearing stops
(or the horizon).
"""

from __future__ import annotations

import dataclasses
import functools
import math
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg
from scipy.integrate import solve_ivp

from ..store.history import History
from ..pulses import accel_at
from ..scene import Scene
from .result import PeerResult, counted
from .stick_slip import X, XD, XS, StateIndex, bearing_event, choose_modes, farther, phase_modes, sign

__all__ = ["LEDGER_NAMES", "Building", "BuildingRun", "building_of", "default_horizon", "energies",
           "excitation_breakpoints", "excitation_end", "run_building", "shear_building", "solve_reference_building",
           "structure_forces"]

LEDGER_NAMES = ("work", "viscous", "isolator", "friction")
"""Ledger integrals appended to the state when requested: input work, viscous, isolator
(hysteretic, or bearing friction at the rate ``q(|x'|) |x'|``) and contents-friction dissipation,
units ``M_b a_p**2 T_p**2``."""

_ULP4 = 4e-15   # relative slack of the stick limits (see isoslide.peers.reference)


def storeys_of(scene: Scene) -> tuple:
    """Floor masses and relative storey stiffnesses of a scene's flexible superstructure.

    Returns
    -------
    ms, r : ndarray, shape (storeys,)
        Floor masses, units of ``M_b`` (they add up to ``pi11``), and storey stiffnesses relative to
        each other (bottom first; equal unless the scene gives them).
    """
    n = scene.storeys
    shares = np.full(n, 1.0 / n) if scene.floor_masses is None else np.asarray(scene.floor_masses, dtype=float)
    r = np.ones(n) if scene.storey_stiffnesses is None else np.asarray(scene.storey_stiffnesses, dtype=float)
    return scene.pi11 * shares, r


def shear_building(masses, stiffnesses, period: float, damping: float) -> tuple:
    """Fixed-base matrices of a shear chain scaled to a fundamental period.

    Parameters
    ----------
    masses : sequence of float
        Floor masses, bottom to top (any consistent unit, e.g. ``M_b`` or kg), all positive.
    stiffnesses : sequence of float
        Relative storey stiffnesses, bottom to top (storey ``j`` joins floor ``j-1`` and floor
        ``j``; floor 0 is the held slab), all positive; only their ratios matter.
    period : float
        Fixed-base fundamental period (the unit of time), ``> 0``.
    damping : float
        Damping ratio of every fixed-base mode, ``>= 0``.

    Returns
    -------
    (K, C, omega) : tuple of ndarray
        Stiffness and damping matrices (``N x N``; units mass/time**2 and mass/time), and the
        fixed-base circular frequencies in ascending order (units 1/time), ``omega[0] = 2 pi/period``.
    """
    m = np.asarray(masses, dtype=float)
    r = np.asarray(stiffnesses, dtype=float)
    n = m.size
    if n < 1 or r.size != n:
        raise ValueError(f"stiffnesses has {r.size} values; allowed: one per floor ({n} floors, at least 1)")
    if not np.all(m > 0.0) or not np.all(np.isfinite(m)):
        raise ValueError(f"masses = {m.tolist()!r} is out of range; allowed: every value 0 < value < inf")
    if not np.all(r > 0.0) or not np.all(np.isfinite(r)):
        raise ValueError(f"stiffnesses = {r.tolist()!r} is out of range; allowed: every value 0 < value < inf")
    if not (math.isfinite(period) and period > 0.0):
        raise ValueError(f"period = {period!r} is out of range; allowed range: 0 < value < inf")
    if not (math.isfinite(damping) and damping >= 0.0):
        raise ValueError(f"damping = {damping!r} is out of range; allowed range: 0 <= value < inf")
    unit = np.zeros((n, n))
    for j in range(n):                 # storey j+1: floor j (the slab when j = 0) to floor j+1
        unit[j, j] += r[j]
        if j:
            unit[j - 1, j - 1] += r[j]
            unit[j, j - 1] -= r[j]
            unit[j - 1, j] -= r[j]
    M = np.diag(m)
    lam, phi = scipy.linalg.eigh(unit, M)   # unit phi = M phi lam, phi^T M phi = I
    w1 = 2.0 * math.pi / period
    kappa = w1 * w1 / lam[0]
    omega = np.sqrt(kappa * lam)
    omega[0] = w1
    K = kappa * unit
    Mphi = M @ phi
    C = (Mphi * (2.0 * damping * omega)) @ Mphi.T
    return K, 0.5 * (C + C.T), omega


@dataclass(frozen=True)
class Building(StateIndex):
    """The scene's parameters in the model's units (see the module docstring).

    Attributes
    ----------
    mst, mb, m : float
        Superstructure (all floors), slab and block masses (units ``M_b``).
    kd, cb : float
        Isolator post-yield (linear) stiffness and viscous coefficient.
    ms : ndarray
        Floor masses ``m_1 .. m_N``, bottom to top (empty when rigid).
    Ks, Cs : ndarray
        Fixed-base stiffness and damping matrices of the floors (``N x N``; ``0 x 0`` when rigid).
    omega : ndarray
        Fixed-base circular frequencies, ascending (units ``1/T_p``; empty when rigid).
    q, ke : float
        Isolator strength and elastic stiffness (``ke = 0`` unless bilinear); a sliding bearing's
        ``q`` is its breakaway level ``Pi9 Pi22`` (its stick limit and its friction at zero speed).
    q_fast, rate : float
        A sliding bearing whose friction rises with speed: its friction at high speed ``Pi9`` and
        the rate ``Pi23``; ``rate = 0`` (and ``q_fast = q``) for constant friction and every other
        isolator.
    thr : float
        Static friction level ``Pi2/Pi5`` (units ``a_p``).
    kind : {"linear", "bilinear", "sliding", "fixed"}
        Isolator; ``"fixed"`` is a fixed base (``Pi3 = 0``).
    flexible : bool
        Flexible superstructure (``Pi12 > 0``).
    floor : int
        The block's floor: 0 the slab (always when rigid), ``N`` the roof.
    pi17 : float
        Vertical amplitude ``Pi17`` (units ``g``; 0 without vertical ground motion).
    zcode : int
        Shape code of the vertical pulse (:mod:`isoslide.pulses`; -1 without one).
    zparams : ndarray
        Shape parameters of the vertical pulse.
    """

    mst: float
    mb: float
    m: float
    kd: float
    cb: float
    ms: np.ndarray
    Ks: np.ndarray
    Cs: np.ndarray
    omega: np.ndarray
    q: float
    ke: float
    thr: float
    kind: str
    flexible: bool
    floor: int
    pi2: float = field(repr=False, default=0.0)
    pi6: float = field(repr=False, default=0.0)
    pi7: float = field(repr=False, default=0.0)
    pi17: float = 0.0
    zcode: int = -1
    zparams: np.ndarray = field(repr=False, default_factory=lambda: np.zeros(0))
    q_fast: float = 0.0
    rate: float = 0.0

    @property
    def speed_dependent(self) -> bool:
        """True for a sliding bearing whose friction rises with its speed (``Pi23 > 0``, ``Pi22 < 1``)."""
        return self.rate > 0.0

    def level(self, v: float) -> float:
        """A sliding bearing's friction level at the slab's speed ``v`` along its sliding direction.

        Units ``M_b a_p``, before the normal-force factor: ``q + (q_fast - q) (1 - exp(-rate v))``,
        which is ``Pi9 (1 - (1 - Pi22) exp(-Pi23 v))`` and is ``q`` itself at ``v = 0`` (the
        breakaway level, to the bit) and for constant friction.  For ``v < 0`` (past a stop, inside
        the integrator's step that reaches it) the same smooth expression continues the law, its
        exponent capped at 50, so that the stop is located as accurately as any other event.
        """
        if self.rate == 0.0:
            return self.q
        return self.q - (self.q_fast - self.q) * math.expm1(min(-self.rate * v, 50.0))

    @property
    def vertical(self) -> bool:
        """True when the ground moves vertically (the normal forces vary)."""
        return self.pi17 > 0.0 and self.zcode >= 0

    def normal(self, tau: float) -> float:
        """Normal-force factor ``n(tau) = 1 + Pi17 p_z(tau)`` (dimensionless; 1 without vertical motion).

        Parameters
        ----------
        tau : float
            Time, units ``T_p``.
        """
        if not self.vertical:
            return 1.0
        return 1.0 + self.pi17 * accel_at(self.zcode, self.zparams, tau)

    @property
    def n_state(self) -> int:
        """Length of the state (without the ledger)."""
        return self.U + 3

    @property
    def upstairs(self) -> bool:
        """True when the block is on a floor above the slab."""
        return self.floor > 0

    def phi(self, v: float) -> float:
        """Friction level ``phi(|v|)`` per unit block weight, units ``a_p``."""
        v = abs(v)
        a = self.pi6 * v
        sh = 0.0 if a > 700.0 else 1.0 / math.cosh(a)
        return self.thr * sh + self.pi2 * (1.0 - sh) + self.pi7 * v


def building_of(scene: Scene) -> Building:
    """The model parameters of a scene.

    Parameters
    ----------
    scene : Scene
        Any scene (the paper's model included).

    Returns
    -------
    Building
    """
    flexible = scene.pi12 > 0.0
    if scene.pi3 == 0.0:
        kind, kd, cb = "fixed", 0.0, 0.0
    else:
        w = 2.0 * math.pi / scene.pi3
        kd, cb = w * w, 2.0 * scene.pi4 * w
        kind = "linear" if scene.pi9 == 0.0 else ("bilinear" if scene.pi10 > 0.0 else "sliding")
    if flexible:
        ms, r = storeys_of(scene)
        Ks, Cs, omega = shear_building(ms, r, scene.pi12, scene.pi13)
        mst, floor = scene.pi11, scene.floor_index
    else:
        ms, Ks, Cs, omega = np.zeros(0), np.zeros((0, 0)), np.zeros((0, 0)), np.zeros(0)
        mst, floor = 0.0, 0
    q = math.inf if kind == "fixed" else scene.pi9
    q_fast, rate = q, 0.0
    if kind == "sliding":
        # breakaway Pi9 Pi22; a friction that does not rise with speed (Pi23 = 0: Pi9 Pi22 at every
        # speed, Pi22 = 1: Pi9) is the constant strength, the same numbers as a scene given it
        q = scene.pi9 * scene.pi22
        if scene.pi23 > 0.0 and scene.pi22 < 1.0:
            q_fast, rate = scene.pi9, float(scene.pi23)
        else:
            q_fast = q
    ke = scene.pi9 / scene.pi10 if kind == "bilinear" else 0.0
    vertical = scene.vertical
    zp = scene.pulse_z if vertical else None
    return Building(mst=mst, mb=1.0 - mst, m=scene.pi8, kd=kd, cb=cb, ms=ms, Ks=Ks, Cs=Cs, omega=omega, q=q,
                    ke=ke, thr=scene.pi2 / scene.pi5, kind=kind, flexible=flexible, floor=floor, pi2=scene.pi2,
                    pi6=scene.pi6, pi7=scene.pi7, pi17=float(scene.pi17) if vertical else 0.0,
                    zcode=int(zp.code) if vertical else -1,
                    zparams=np.asarray(zp.param_array, dtype=float) if vertical else np.zeros(0),
                    q_fast=q_fast, rate=rate)


def excitation_end(scene: Scene) -> float:
    """End of the ground motion, units ``T_p``.

    The later of the two pulses' ends; the horizontal pulse's alone without vertical motion.
    """
    end = float(scene.pulse.tau_end)
    if scene.vertical:
        end = max(end, float(scene.pulse_z.tau_end))
    return end


def excitation_breakpoints(scene: Scene) -> np.ndarray:
    """Sorted breakpoints of the ground motion (both pulses'), units ``T_p``."""
    b = np.asarray(scene.pulse.breakpoint_array, dtype=float)
    if scene.vertical:
        b = np.union1d(b, np.asarray(scene.pulse_z.breakpoint_array, dtype=float))
    return b


def structure_forces(B: Building, y, si: int, nz: float = 1.0) -> tuple:
    """The forces that the building's state alone sets, whatever the contents do.

    Parameters
    ----------
    B : Building
    y : sequence
        State (module docstring); only the slab's, the floors' and the isolator's entries are read.
    si : int
        Isolator mode, as in :func:`_dynamics`.
    nz : float
        Normal-force factor ``n(tau)`` (dimensionless, > 0).

    Returns
    -------
    (F, fh, kd, f, S) : tuple
        ``F = kd x + cb x' + fh`` the isolator's force on the slab (units ``M_b a_p``), ``fh`` its
        hysteretic or friction part (a held bearing's is what it must supply, not this), ``kd`` its
        restoring stiffness (``kd n`` for a sliding bearing; units ``M_b/T_p**2``), ``f = Ks xs + Cs xs'``
        the storeys' forces on their floors (an array, None when rigid) and ``S = sum_j f_j`` (0 when
        rigid).
    """
    n = B.n
    xd = y[XD]
    f = None
    if n:
        f = B.Ks @ y[XS:XS + n] + B.Cs @ y[B.XSD:B.XSD + n]
        S = float(f.sum())
    else:
        S = 0.0
    if B.kind == "bilinear":
        fh = y[B.FH]
    elif B.kind == "sliding":
        fh = si * B.level(si * xd) * nz      # si xd = |x'| while sliding (continued past a stop)
    else:
        fh = 0.0
    kd = B.kd * nz if B.kind == "sliding" else B.kd     # a friction pendulum's W x / R
    F = kd * y[X] + B.cb * xd + fh
    return F, fh, kd, f, S


def _dynamics(B: Building, p: float, y, sb: int, si: int, nz: float = 1.0):
    """Accelerations and forces in the mode ``(sb, si)``.

    Parameters
    ----------
    B : Building
    p : float
        Ground acceleration (units ``a_p``).
    y : sequence
        State (module docstring).
    sb : int
        Block mode: 0 stuck, +-1 sliding.
    si : int
        Isolator mode: 0 held (sliding bearing, fixed base) or elastic (bilinear), +-1 sliding or
        yielding; ignored for a linear isolator.
    nz : float
        Normal-force factor ``n(tau)`` (dimensionless, > 0): scales the block's friction and a
        sliding bearing's strength and stiffness.

    Returns
    -------
    tuple
        ``(x'', xs'', u'', fh', A_F, fh_needed, R, fh)``: ``xs''`` an array of the floor slots,
        ``fh_needed`` nan unless the slab is held.
    """
    held = B.holds and si == 0
    n = B.n
    x, xd, ud = y[X], y[XD], y[B.UD]
    F, fh, kd, f, S = structure_forces(B, y, si, nz)
    m = B.m
    k = B.floor
    if sb != 0:
        ph = nz * B.phi(ud)
        R = m * sb * ph
    if k:
        Ab = p if held else (-F + S) / B.mb
        A = -f / B.ms
        if sb == 0:
            A[k - 1] = -f[k - 1] / (B.ms[k - 1] + m)
            R = -m * A[k - 1]
            udd = 0.0
        else:
            A[k - 1] = (-f[k - 1] + R) / B.ms[k - 1]
            udd = -A[k - 1] - sb * ph
        AF = A[k - 1]
    else:
        if held:
            Ab = p
            if sb == 0:
                R = -m * p
                udd = 0.0
            else:
                udd = -p - sb * ph
        elif sb == 0:
            Ab = (-F + S) / (B.mb + m)
            R = -m * Ab
            udd = 0.0
        else:
            Ab = (-F + S + R) / B.mb
            udd = -Ab - sb * ph
        A = -f / B.ms if n else None
        AF = Ab
    if held:
        xdd = 0.0
        fh_need = -B.mb * p - kd * x + S + (0.0 if k else R)
        fh = fh_need
    else:
        xdd = Ab - p
        fh_need = math.nan
    xsdd = A - Ab if n else np.zeros(1)
    fhd = B.ke * xd if (B.kind == "bilinear" and si == 0) else 0.0
    return xdd, xsdd, udd, fhd, AF, fh_need, R, fh


def _choose(B: Building, p: float, y, sb: int, si: int, forced_b: int = 0, forced_i: int = 0,
            nz: float = 1.0):
    """Consistent modes of the frictional interfaces at a phase start (module docstring).

    Parameters
    ----------
    B, p, y
        Model, ground acceleration, state.
    sb, si : int
        Current modes.
    forced_b, forced_i : int
        Nonzero: the block (bearing) just broke away and slides in this direction.
    nz : float
        Normal-force factor ``n(tau)`` (scales both stick limits).

    Returns
    -------
    (sb, si) : tuple of int
    """
    lim_b = B.thr * nz * (1.0 + _ULP4)
    lim_q = B.q * nz * (1.0 + _ULP4)
    modes = choose_modes(B, y, sb, si, forced_b, forced_i, lim_b, lim_q, lambda b, i: _dynamics(B, p, y, b, i, nz))
    if modes is not None:
        return modes
    raise RuntimeError(f"no consistent stick/slip mode at the state {list(y[:B.n_state])!r}, p = {p!r}")


def _stop_event(s: int, k: int, t0: float, y0, acc0: float):
    """Event function of the velocity ``y[k]`` (moving in direction ``s``) returning to zero.

    ``s y[k] / (t - t0)``: the sign of ``s y[k]`` for ``t > t0`` but, for a phase that starts at
    rest, without the trivial root at ``t0`` itself (there it is ``s`` times the acceleration
    ``acc0``), so a slip that starts with a tiny acceleration and ends soon is still located.
    """
    v0 = s * y0[k]

    def g(t, yy):
        dt = t - t0
        if dt > 0.0:
            return s * yy[k] / dt
        return v0 if v0 != 0.0 else s * acc0

    return g


def _bilinear_mode(B: Building, p: float, y, sb: int, si: int, nz: float = 1.0) -> int:
    """Elastic (0) or yielding (+-1) mode of a bilinear bearing at a phase start (not an event).

    ``nz`` is the normal-force factor (it scales the sliding block's friction).
    """
    fh, xd = y[B.FH], y[XD]
    if si == 0:
        if abs(fh) >= B.q * (1.0 - _ULP4):
            s = sign(fh)
            v = xd if xd != 0.0 else _dynamics(B, p, y, sb, s, nz)[0]
            if s * v > 0.0:
                return s
        return 0
    v = xd if xd != 0.0 else _dynamics(B, p, y, sb, si, nz)[0]
    return si if si * v > 0.0 else 0


def _free_system(B: Building, y, si: int):
    """The free linear system (``p = 0``, block stuck, bearing held/elastic/linear).

    Returns
    -------
    tuple
        ``(M, C, K, z_eq, idx, vel, demands)``: mass, damping and stiffness matrices of the moving
        coordinates ``y[idx]`` (displacements; their velocities are ``y[vel]``), their
        equilibrium, and a list of ``(limit, d0, c)``: each demand is ``d0 + c . (z - z_eq, z')``.
    """
    held = B.holds and si == 0
    m, n, k = B.m, B.n, B.floor
    dem = []
    floors = list(range(XS, XS + n))
    floor_vel = list(range(B.XSD, B.XSD + n))
    if held:
        if not n:
            if B.kind == "sliding":
                dem.append((B.q, -B.kd * y[X], np.zeros(0)))
            return np.zeros((0, 0)), np.zeros((0, 0)), np.zeros((0, 0)), np.zeros(0), [], [], dem
        masses = B.ms.copy()
        if k:
            masses[k - 1] += m
        M, C, K = np.diag(masses), B.Cs, B.Ks
        if k:      # A_F = -f_k / (m_k + m)
            dem.append((B.thr, 0.0, -np.concatenate([B.Ks[k - 1], B.Cs[k - 1]]) / masses[k - 1]))
        if B.kind == "sliding":   # fh_needed = -kd x + sum_j f_j
            dem.append((B.q, -B.kd * y[X], np.concatenate([B.Ks.sum(axis=0), B.Cs.sum(axis=0)])))
        return M, C, K, np.zeros(n), floors, floor_vel, dem
    k1 = B.kd + B.ke
    off = y[B.FH] - B.ke * y[X] if B.kind == "bilinear" else 0.0   # fh = off + ke x while elastic
    x_eq = -off / k1
    if not n:
        M, C, K = np.array([[1.0 + m]]), np.array([[B.cb]]), np.array([[k1]])
        dem.append((B.thr, 0.0, -np.array([k1, B.cb]) / (1.0 + m)))
        if B.kind == "bilinear":
            dem.append((B.q, off + B.ke * x_eq, np.array([B.ke, 0.0])))
        return M, C, K, np.array([x_eq]), [X], [XD], dem
    m_slab = B.mb + (0.0 if k else m)
    m_fl = B.ms.copy()
    if k:
        m_fl[k - 1] += m
    # kinetic energy: m_slab x'^2 + sum_j m_fl_j (x' + xs_j')^2, over 2
    M = np.zeros((n + 1, n + 1))
    M[0, 0] = m_slab + m_fl.sum()
    M[0, 1:] = M[1:, 0] = m_fl
    M[1:, 1:] = np.diag(m_fl)
    C = np.zeros((n + 1, n + 1))
    C[0, 0], C[1:, 1:] = B.cb, B.Cs
    K = np.zeros((n + 1, n + 1))
    K[0, 0], K[1:, 1:] = k1, B.Ks
    # w = (x - x_eq, xs_1 .. xs_N, x', xs_1' .. xs_N')
    if k:
        c = np.zeros(2 * n + 2)
        c[1:n + 1], c[n + 2:] = -B.Ks[k - 1], -B.Cs[k - 1]
        dem.append((B.thr, 0.0, c / m_fl[k - 1]))
    else:
        c = np.concatenate([[-k1], B.Ks.sum(axis=0), [-B.cb], B.Cs.sum(axis=0)])
        dem.append((B.thr, 0.0, c / m_slab))
    if B.kind == "bilinear":
        c = np.zeros(2 * n + 2)
        c[0] = B.ke
        dem.append((B.q, off + B.ke * x_eq, c))
    return M, C, K, np.concatenate([[x_eq], np.zeros(n)]), [X] + floors, [XD] + floor_vel, dem


def _settle_margin_fn(B: Building, y0, si: int):
    """``g(y)``: the smallest margin ``limit - (|d0| + sqrt(2 E c^T P^-1 c))`` over the demands.

    Non-decreasing along the free response; ``g >= 0`` means no interface can slip or yield again.
    Returns None when there is no demand (nothing can ever slip).
    """
    M, C, K, z_eq, idx, vel, dem = _free_system(B, y0, si)
    if not dem:
        return None
    n = len(idx)
    P = np.zeros((2 * n, 2 * n))
    P[:n, :n], P[n:, n:] = K, M
    scale = [math.sqrt(float(c @ np.linalg.solve(P, c))) if n else 0.0 for _, _, c in dem]

    def g(t, yy):
        if n:
            dz = yy[idx] - z_eq
            v = yy[vel]
            two_e = float(dz @ K @ dz + v @ M @ v)
        else:
            two_e = 0.0
        r = math.sqrt(max(two_e, 0.0))
        return min(lim - (abs(d0) + r * s) for (lim, d0, _), s in zip(dem, scale, strict=True))

    return g


def _slide_settle_margin_fn(B: Building, s: int):
    """``g(y)``: the settlement margin of a rigid building's bearing sliding in ``s`` after the pulse.

    For a bearing whose friction rises with speed, the contents stuck on the slab (module
    docstring, "Creep of a bearing whose friction rises with speed"): with ``x* = -s q/kd`` and ``E = M x'^2/2 + kd (x - x*)^2/2``
    (``M = 1 + m``), the smaller of the contents' margin
    ``thr - (sqrt(2 E (kd + cb^2/M)) + (q_fast - q) min(1, rate sqrt(2 E/M)))/M`` and the
    re-stick margin ``2 q - sqrt(2 E kd)``.  Non-decreasing while the bearing moves in ``s``;
    ``g >= 0`` means the contents never slip again and the bearing, if it stops, stays held.
    """
    M = B.mb + B.m
    kd, cb, thr = B.kd, B.cb, B.thr
    x_eq = -s * B.q / kd
    drop = B.q_fast - B.q
    stiff = kd + cb * cb / M

    def g(t, yy):
        dx, v = yy[X] - x_eq, yy[XD]
        two_e = max(M * v * v + kd * dx * dx, 0.0)
        demand = (math.sqrt(two_e * stiff) + drop * min(1.0, B.rate * math.sqrt(two_e / M))) / M
        return min(thr - demand, 2.0 * B.q - math.sqrt(two_e * kd))

    return g


def _slowest_rate(B: Building) -> float:
    """Slowest decay rate of the free linear systems (0 if one of them is undamped)."""
    rates = []
    for si in ([0] if B.kind == "fixed" else [0, 1] if B.kind == "sliding" else [0]):
        y = np.zeros(B.n_state)
        if B.kind == "sliding" and si == 1:   # moving slab on kd alone
            M, C, K, _, idx, _, _ = _free_system(dataclasses.replace(B, kind="linear", q=0.0), y, 0)
        else:
            M, C, K, _, idx, _, _ = _free_system(B, y, si)
        n = len(idx)
        if n == 0:
            continue
        A = np.block([[np.zeros((n, n)), np.eye(n)], [-np.linalg.solve(M, K), -np.linalg.solve(M, C)]])
        lam = np.linalg.eigvals(A)
        rate = float(np.min(np.abs(lam.real)))
        rates.append(0.0 if rate <= 1e-9 * float(np.max(np.abs(lam))) else rate)   # round-off of 0
    return min(rates) if rates else math.inf


def _periods(B: Building) -> list:
    """Natural periods of the structure's parts (units ``T_p``), to bound the integration step."""
    out = []
    if B.kd > 0.0:
        out.append(2.0 * math.pi * math.sqrt(1.0 / (B.kd + B.ke)))
    out.extend(2.0 * math.pi / w for w in B.omega)
    return out


def default_horizon(scene: Scene) -> float:
    """Default end of a run that does not settle, units of ``T_p`` (see the module docstring)."""
    B = building_of(scene)
    base = 50.0 * max(1.0, scene.pi3, scene.pi12)
    rate = _slowest_rate(B)
    extra = base if rate == 0.0 or not math.isfinite(rate) else max(base, 50.0 / rate)
    return excitation_end(scene) + extra


@dataclass(frozen=True)
class BuildingRun:
    """A reference solve of the general building.

    Attributes
    ----------
    result : PeerResult
        As :func:`solve_reference_building` returns it; for ``N > 1`` floors its history's
        ``xs, xsd`` are the roof's (floor ``N``).
    ledger : dict or None
        With ``ledger=True``: ``"work"``, ``"viscous"``, ``"isolator"``, ``"friction"`` (the
        integrals of :data:`LEDGER_NAMES` at the history's times) and ``"kinetic"``,
        ``"potential"`` (energies at those times), units ``M_b a_p**2 T_p**2``.
    floors : tuple of ndarray or None
        With a history of a flexible superstructure: ``(xs, xsd)``, every floor's displacement and
        velocity relative to the slab (shape ``(N, n_times)``, units ``a_p T_p**2`` and ``a_p T_p``).
    """

    result: PeerResult
    ledger: dict | None = None
    floors: tuple | None = None


def energies(scene: Scene, h: History, floors: tuple | None = None) -> tuple:
    """Kinetic and potential energy along a history (units ``M_b a_p**2 T_p**2``).

    Velocities are relative to the ground; the potential energy holds the springs ``kd``,
    ``Ks`` and the bilinear bearing's elastic part ``fh**2 / (2 ke)``.

    Parameters
    ----------
    scene : Scene
    h : History
        From this module (building states present where the scene has them).
    floors : tuple of ndarray or None
        ``(xs, xsd)`` of every floor, shape ``(N, n_times)`` (:attr:`BuildingRun.floors`);
        needed when the superstructure has more than one floor, else taken from ``h``.

    Returns
    -------
    (kinetic, potential) : tuple of ndarray
    """
    B = building_of(scene)
    n = B.n
    if floors is None:
        if n > 1:
            raise ValueError(f"floors = None is invalid for a superstructure of {n} floors; allowed: "
                             "the (xs, xsd) arrays of every floor (BuildingRun.floors)")
        xs = (h.xs if h.xs is not None else np.zeros_like(h.x))[None, :]
        xsd = (h.xsd if h.xsd is not None else np.zeros_like(h.x))[None, :]
    else:
        xs, xsd = (np.asarray(a, dtype=float) for a in floors)
        if xs.shape != (n, h.x.size) or xsd.shape != (n, h.x.size):
            raise ValueError(f"floors has the shapes {xs.shape}, {xsd.shape}; allowed: ({n}, {h.x.size}) each")
    kin = 0.5 * (B.mb * h.xd ** 2 + B.m * (h.xd + (xsd[B.floor - 1] if B.floor else 0.0) + h.ud) ** 2)
    pot = 0.5 * B.kd * h.x ** 2
    if n:
        kin = kin + 0.5 * (B.ms @ (h.xd[None, :] + xsd) ** 2)
        pot = pot + 0.5 * np.einsum("it,ij,jt->t", xs, B.Ks, xs)
    if B.kind == "bilinear":
        pot = pot + h.fh ** 2 / (2.0 * B.ke)
    return kin, pot


def solve_reference_building(scene: Scene, rtol: float = 1e-12, history: bool = False,
                             atol: float = 1e-15, tau_max: float | None = None,
                             max_events: int = 100_000, max_work: int | None = None) -> PeerResult:
    """Solve one general-building scene with the event-driven DOP853 reference integrator.

    Parameters
    ----------
    scene : Scene
        Any scene (also the paper's model, solved with the general equations).  Starts at rest at
        ``scene.pulse.tau_start``.
    rtol, atol : float
        Tolerances passed to ``solve_ivp`` (DOP853); ``atol`` in the state's units.
    history : bool
        Also return the :class:`~isoslide.store.history.History` (with ``xs, xsd`` for a flexible
        superstructure, the roof's when it has several floors; ``fh, iso_phase`` for a bilinear
        or sliding bearing).
    tau_max : float or None
        Horizon in units of ``T_p``; default :func:`default_horizon`.
    max_events : int
        Safety cap on the number of transitions (raises ``RuntimeError``).
    max_work : int or None
        Most right-hand-side evaluations (raises :class:`~isoslide.peers.result.WorkLimitError`).

    Returns
    -------
    PeerResult
        ``method = "reference"``, ``integrator = "DOP853"``; ``n_events`` counts the block's
        and the isolator's transitions.
    """
    return run_building(scene, rtol=rtol, history=history, atol=atol, tau_max=tau_max,
                        max_events=max_events, max_work=max_work).result


def run_building(scene: Scene, rtol: float = 1e-12, history: bool = False, atol: float = 1e-15,
                 tau_max: float | None = None, max_events: int = 100_000, max_work: int | None = None,
                 ledger: bool = False, settle: bool = True) -> BuildingRun:
    """:func:`solve_reference_building`, optionally with the energy ledger.

    Parameters
    ----------
    scene, rtol, history, atol, tau_max, max_events, max_work
        As :func:`solve_reference_building`.
    ledger : bool
        Integrate the input work and the dissipations along with the state and return them
        (implies ``history=True``); see :class:`BuildingRun`.  Refused (ValueError) for a scene
        with vertical ground motion, whose work the ledger does not hold.
    settle : bool
        Stop at settlement (default); ``False`` follows the scene to the horizon (``settled``
        stays False), to check the settlement bound.

    Returns
    -------
    BuildingRun
    """
    B = building_of(scene)
    pulse = scene.pulse
    code = int(pulse.code)
    params = pulse.param_array
    history = history or ledger
    if ledger and B.vertical:
        raise ValueError("ledger = True is invalid for a scene with vertical ground motion (the ledger holds "
                         "no vertical work); allowed: ledger = False, or pi17 = 0")
    tau_end = excitation_end(scene)
    horizon = default_horizon(scene) if tau_max is None else float(tau_max)
    bps = [float(b) for b in excitation_breakpoints(scene) if b < horizon]
    periods = _periods(B)
    hmax_pulse = min([1.0 / 64.0] + [T / 32.0 for T in periods])
    hmax_free = min([max(1.0, scene.pi3) / 64.0] + [T / 32.0 for T in periods])
    lim_b = B.thr * (1.0 + _ULP4)
    lim_q = B.q * (1.0 + _ULP4)
    nl = len(LEDGER_NAMES) if ledger else 0

    tau = float(pulse.tau_start)
    y = np.zeros(B.n_state + nl)
    XSD, U, UD, FH, n_fl = B.XSD, B.U, B.UD, B.FH, B.slots
    sb, si = 0, 0
    forced_b = forced_i = 0
    event_transition = False
    peak, tau_peak = 0.0, tau
    n_events = 0
    nfev = 0
    used = [0]
    settled = False
    zero_len = 0
    hist = [] if history else None

    def p_at(t):
        return accel_at(code, params, t)

    n_at = B.normal

    while True:
        if n_events > max_events:
            raise RuntimeError(f"more than {max_events} transitions; scene={scene!r}")
        # ---- modes at the phase start ---------------------------------------------------------
        # (an event was counted where it was located; elsewhere every mode change counts)
        p0 = p_at(tau)
        n0 = n_at(tau)
        sb, si, changes = phase_modes(B, y, sb, si, B.q, event_transition,
                                      functools.partial(_bilinear_mode, B, p0, y, sb, nz=n0),
                                      functools.partial(_choose, B, p0, y, sb, forced_b=forced_b, forced_i=forced_i,
                                                        nz=n0))
        n_events += changes
        forced_b = forced_i = 0
        event_transition = False
        free = tau >= tau_end and sb == 0 and si == 0
        settle_g = None
        if free and settle:
            settle_g = _settle_margin_fn(B, y, si)
            if settle_g is None or settle_g(tau, y) >= 0.0:
                settled = True
                break
        elif settle and tau >= tau_end and sb == 0 and si != 0 and B.speed_dependent and not B.flexible:
            settle_g = _slide_settle_margin_fn(B, si)
            if settle_g(tau, y) >= 0.0:
                settled = True
                break
        if tau >= horizon:
            break
        # ---- this segment ----------------------------------------------------------------------
        nxt = [b for b in bps if b > tau]
        t_end = min(nxt[0] if nxt else horizon, horizon)
        t_clip = math.nextafter(t_end, -math.inf)
        t0 = tau
        hmax = hmax_pulse if t0 < tau_end else hmax_free
        mb_, mi_ = sb, si

        def p_of(t, t0=t0, t_clip=t_clip):
            return accel_at(code, params, min(max(t, t0), t_clip))

        def n_of(t, t0=t0, t_clip=t_clip):
            return n_at(min(max(t, t0), t_clip))

        def rhs(t, yy, mb_=mb_, mi_=mi_):
            p = p_of(t)
            xdd, xsdd, udd, fhd, _, _, R, fh = _dynamics(B, p, yy, mb_, mi_, n_of(t))
            d = np.empty(yy.size)
            d[X], d[XD] = yy[XD], xdd
            d[XS:XSD] = yy[XSD:U]
            d[XSD:U] = xsdd
            d[U], d[UD], d[FH] = yy[UD], udd, fhd
            if nl:
                xsd = yy[XSD:XSD + B.n]
                v_blk = yy[XD] + (xsd[B.floor - 1] if B.floor else 0.0) + yy[UD]
                mom = B.mb * yy[XD] + float(B.ms @ (yy[XD] + xsd)) + B.m * v_blk
                visc = B.cb * yy[XD] ** 2 + float(xsd @ B.Cs @ xsd)
                iso = fh * yy[XD] - (fh * fhd / B.ke if B.kind == "bilinear" else 0.0)
                d[FH + 1:] = (-p * mom, visc, iso, R * yy[UD])
            return d

        specs = []          # (event function, what it marks, direction of the zero crossing)
        xdd0, _, udd0 = _dynamics(B, p0, y, sb, si, n0)[:3]

        def add(fn, kind, direction=-1.0, specs=specs):
            specs.append((fn, kind, direction))

        def add_breaks(lim, k, kind, mb_=mb_, mi_=mi_):
            # a stuck contact breaks away when its need (item k of _dynamics) reaches +-lim n(tau)
            def ev(t, yy, sgn):
                nz = n_of(t)
                return lim * nz - sgn * _dynamics(B, p_of(t), yy, mb_, mi_, nz)[k]
            add(lambda t, yy: ev(t, yy, 1.0), kind)
            add(lambda t, yy: ev(t, yy, -1.0), kind)

        if sb == 0:
            add_breaks(lim_b, 4, "block_break")
        else:
            add(_stop_event(sb, UD, t0, y, udd0), "block_stop")
        if B.kind == "sliding":
            if si == 0:
                add_breaks(lim_q, 5, "iso_break")       # mi_ = si = 0
            else:
                add(_stop_event(si, XD, t0, y, xdd0), "iso_stop")
        elif B.kind == "bilinear":
            if si == 0:
                add(lambda t, yy: B.q - yy[FH], "yield")
                add(lambda t, yy: B.q + yy[FH], "yield")
            else:
                add(_stop_event(si, XD, t0, y, xdd0), "unload")
        if settle_g is not None:
            add(settle_g, "settle", 1.0)
        for fn, _, direction in specs:
            fn.terminal, fn.direction = True, direction
        events, kinds = [s[0] for s in specs], [s[1] for s in specs]

        sol = solve_ivp(counted(rhs, max_work, "reference", used), (t0, t_end), y, method="DOP853",
                        rtol=rtol, atol=atol, events=events, max_step=hmax)
        nfev += sol.nfev
        if sol.status < 0:
            raise RuntimeError(f"solve_ivp failed: {sol.message}")
        if hist is not None:
            n = sol.t.size
            hist.append((sol.t, sol.y.copy(), np.full(n, sb, dtype=np.int8), np.full(n, si, dtype=np.int8)))
        if sol.status != 1:
            tau = float(sol.t[-1])
            y = np.array(sol.y[:, -1], dtype=float)
            if tau >= t_end:
                tau = t_end
            continue
        hits = [(te[0], ye[0], k) for te, ye, k in zip(sol.t_events, sol.y_events, kinds, strict=True)
                if len(te)]
        te, ye, kind = min(hits, key=lambda h: h[0])
        zero_len = zero_len + 1 if te <= t0 else 0
        if zero_len > 4:
            raise RuntimeError(f"zero-length stick/slip chatter at tau={te!r}; scene={scene!r}")
        tau = float(te)
        y = np.array(ye, dtype=float)
        if kind == "settle":
            settled = True
            break
        n_events += 1
        event_transition = True
        p, nz = p_at(tau), n_at(tau)
        if kind == "block_break":
            forced_b = -sign(_dynamics(B, p, y, sb, si, nz)[4])
        elif kind == "block_stop":
            y[UD] = 0.0
            peak, tau_peak = farther(peak, tau_peak, y[U], tau)
        elif kind == "iso_break":
            forced_i = sign(_dynamics(B, p, y, sb, si, nz)[5])
        elif kind == "iso_stop":
            y[XD] = 0.0
        elif kind in ("yield", "unload"):
            si = bearing_event(kind, y, FH, B.q)

    peak, tau_peak = farther(peak, tau_peak, y[U], tau)
    h = led = fl = None
    if hist is not None:
        if hist:
            tt = np.concatenate([a for a, _, _, _ in hist])
            yy = np.concatenate([b for _, b, _, _ in hist], axis=1)
            ph_b = np.concatenate([c for _, _, c, _ in hist])
            ph_i = np.concatenate([d for _, _, _, d in hist])
        else:
            tt, yy = np.array([tau]), y[:, None]
            ph_b = ph_i = np.zeros(1, dtype=np.int8)
        fh = yy[FH].copy()
        top = XS + B.n - 1                     # the roof's slot
        if B.kind == "sliding":
            fh = np.array([_dynamics(B, p_at(t), col, b, i, n_at(t))[7] for t, col, b, i in
                           zip(tt, yy.T, ph_b, ph_i, strict=True)])
        iso = B.kind in ("bilinear", "sliding")
        h = History(tau=tt, x=yy[X].copy(), xd=yy[XD].copy(), u=yy[U].copy(), ud=yy[UD].copy(), phase=ph_b,
                    xs=yy[top].copy() if B.flexible else None, xsd=yy[top + n_fl].copy() if B.flexible else None,
                    fh=fh if iso else None, iso_phase=ph_i if iso else None)
        if B.flexible:
            fl = (yy[XS:XS + B.n].copy(), yy[XSD:XSD + B.n].copy())
        if ledger:
            led = {name: yy[B.n_state + k].copy() for k, name in enumerate(LEDGER_NAMES)}
            led["kinetic"], led["potential"] = energies(scene, h, fl)
    res = PeerResult(method="reference", pi1=float(peak), pi1_residual=float(y[U]), tau_peak=float(tau_peak),
                     settled=settled, n_events=n_events, tau_end=float(tau), nfev=int(nfev), integrator="DOP853",
                     history=h)
    return BuildingRun(result=res, ledger=led, floors=fl)
