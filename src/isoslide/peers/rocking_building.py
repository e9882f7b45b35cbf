r"""Independent event-driven peer of a rigid block that rests, slides, rocks and slide-rocks in the general building.

The building is that of :mod:`isoslide.peers.reference_building` (its parameters, matrices,
isolators and state layout are imported from there: linear, bilinear or sliding isolator with
true stick, fixed base ``Pi3 = 0``, rigid or flexible superstructure of ``N`` storeys, contents on
floor ``k``, vertical ground motion through the normal-force factor ``nz = 1 + Pi17 p_z(tau)``).
The contents are the rigid rectangular block of :mod:`isoslide.peers.slide_rock` (Housner's block
with Coulomb friction, Shenton's modes), and the coupling is two-way: the block's contact force
acts on its floor.  Written with plain Python and :func:`scipy.integrate.solve_ivp` (``DOP853``,
every transition an event), independently of the compiled engine (:mod:`isoslide.engine`), to
cross-check it.

Units (as the building's peer): time ``T_p``, lengths ``a_p T_p**2``, accelerations ``a_p``, masses
``M_b``, forces ``M_b a_p``, energies ``M_b a_p**2 T_p**2``.

Block
-----
``G = g/a_p = 1/(Pi18 Pi21)``, ``Gam = G nz(tau)``, ``alpha = atan(Pi18)``, ``k = 3/(4 R) = Pi19**2/G``
(so ``p**2 = k G``, ``p T_p = Pi19``), ``R = 3 G/(4 Pi19**2)``, ``b = R sin(alpha)``, ``h = R cos(alpha)``,
mass ``m = Pi8``, restitution ``e`` (:attr:`isoslide.Scene.restitution`).  Static friction: the
floor's acceleration that breaks stick is ``thr = Pi2/Pi5 = mu_s G``.  Sliding friction: the law
of the building's peer, ``nz phi(|u'|)`` per unit mass; this peer refuses ``Pi6 > 0`` and ``Pi7 > 0``
with a rocking block, and with ``Pi6 = Pi7 = 0`` that law is ``phi = thr`` at every speed (the
scene's convention, :mod:`isoslide.scene`, "Note on Pi6 = 0"), so the kinetic coefficient of the
block is ``mu_k = phi/G = mu_s``, in sliding, slide-rock and sliding impacts alike: ``Pi5 < 1`` does
not lower it.  (The equations below keep ``mu_s`` and ``mu_k`` apart.)

Sign convention (:mod:`isoslide.model.rocking`): ``theta > 0`` rocking on the right corner (the
block leans towards ``+x``).  On corner ``s = sgn(theta)`` with ``psi = s theta >= 0``,
``d = alpha - psi``, ``A_F`` the floor's absolute horizontal acceleration, ``(H, V)`` the contact force
on the block per unit mass (horizontal, vertical)::

    rock:        psi'' = -k [Gam sin d + s A_F cos d]
                 H = A_F + s R (cos d psi'' + sin d psi'**2),   V = Gam + R (sin d psi'' - cos d psi'**2)
    slide-rock:  the corner slides in sigma = sgn(u'); H = -mu_k sigma V closes the system, and the
                 corner's absolute acceleration a is explicit (module docstring of
                 isoslide.peers.slide_rock) and independent of A_F; u'' = a - A_F
    rest:        u'' = 0, H = A_F, V = Gam
    slide:       u'' = H - A_F with H = -sigma nz phi(|u'|), V = Gam

``u`` is the horizontal displacement, relative to the floor, of the bottom corner in contact (the
base's when flat); it is continuous at impacts and ``Pi1 = max |u|``.

Coupling
--------
The block pushes its floor with ``-m H``.  In every mode ``H = H1 A_F + H0`` is affine in ``A_F``:
rest ``H1 = 1``; rock ``H1 = 1 - 3/4 cos**2 d`` and ``H0 = s (R sin d psi'**2 - 3/4 Gam sin d cos d)``;
slide and slide-rock ``H1 = 0``.  The building's mass matrix in absolute accelerations is diagonal,
so the block's floor (the slab, of mass ``mb``, or floor ``k``, of mass ``m_k``) has the one equation
``m_F A_F = Q_F - m (H1 A_F + H0)`` with ``Q_F`` the other forces on it (``-F + S`` on a moving slab,
``-f_k`` on floor ``k``; :func:`~isoslide.peers.reference_building.structure_forces`), solved as
``A_F = (Q_F - m H0)/(m_F + m H1)`` (``m_F + m H1 >= m_F > 0``).  With the slab held (a stuck sliding
bearing, or a fixed base) and the block on it, ``A_F`` is the ground's acceleration; the bearing
then supplies ``fh_needed = -mb p - kd x + S - m H``.  At rest and sliding these are the equations of
the building's peer to the bit.  At an uplift ``H`` (and so ``A_F``) is continuous, and so at a rock
to slide-rock transition (``mu_k = mu_s``).

Transitions
-----------
Every one is the root of an event function located by ``solve_ivp``; after it the modes of the block
and of a sliding bearing are chosen at the phase start as in the building's peer (of the
candidates, in the order block at rest first, bearing held first, the first consistent one).

* rest, ``mu_s <= tan(alpha)``: the block never rocks; it breaks away when ``|A_F|`` reaches
  ``thr nz`` and slides exactly as in the building's peer.
* rest, ``mu_s > tan(alpha)``: it never slides from rest; it uplifts onto corner ``s = -sgn(A_F)``
  when ``|A_F|`` reaches ``Gam tan(alpha)`` (then ``psi'' > 0``), into slide-rock (``sigma =
  -sgn(H)``) if the friction the pivot needs already exceeds ``mu_s V`` (Shenton 1996).
* rock -> slide-rock when ``|H|`` reaches ``mu_s V`` (``psi < alpha`` only), ``sigma = -sgn(H)``,
  checked against ``sigma u'' >= 0``.
* slide-rock -> rock when ``u'`` reaches 0 and the pivot's need is within ``mu_s V``; else the
  corner slides back.
* flight: ``V < 0`` with ``psi < alpha`` raises :class:`~isoslide.peers.rocking.RockingContactError`
  naming the time; past ``psi > alpha`` friction and flight are not checked.
* overturn: ``psi`` reaches ``pi/2``; the run stops there.
* slide, ``mu_s > tan(alpha)`` (only after a sliding impact): with ``mu_k > tan(alpha)`` the block
  tips at once onto the corner ``s = sigma`` (slide-rock); else it stops when ``u'`` reaches 0, at
  rest if ``|A_F| <= mu_s Gam``, else sliding back.
* the isolator's own events (a bearing's breakaway and stop, a bilinear bearing's yield and
  unloading) are those of the building's peer.

Impact
------
At ``psi = 0`` with ``psi' < 0`` the other corner ``s' = -s`` strikes; the rule is
:mod:`isoslide.peers.slide_rock`'s, with the scene's restitution ``e``: ``theta'+ = e theta'- - kappa
(u'+ - u'-)``, ``kappa = 3 h/(4 R**2)``; sticking (``u'+ = 0``) if ``|J_x| <= mu_s J_y``, else sliding
with ``J_x = -mu_k sigma J_y``.  The building's velocities are continuous at an impact (its share of
the impulse is neglected, an approximation of order ``Pi8``); the kinetic energy the block loses
there, measured with velocities relative to the ground, is the impact loss of the energy ledger.

End of the impact cascade
-------------------------
After a sticking impact leaving at ``w = psi'+``, with ``theta_eps = theta_eps_ratio alpha``, ``Gam``
and ``A_F0`` (the floor's absolute acceleration with the block at rest, flat and stuck) at the
impact instant, ``D = k [Gam sin(alpha - theta_eps) - |A_F0| cos(alpha - theta_eps)]``: if ``D > 0``
and ``w**2 <= 2 D theta_eps`` the block is at rest from the impact on (``theta = theta' = u' = 0``;
its remaining kinetic energy is counted as an impact loss).  This freezes the floor over the
dying excursions (each lasts at most ``2 w/D``): a local estimate on a moving floor (on an isolated
slab or a flexible floor the block's own rocking moves it), a proof only where the floor's
acceleration stays zero, as on a fixed base after the pulse.  After a sliding impact the block is flat, sliding with its centre of
mass's velocity ``u' = u'+ + s' h psi'+``, when ``w**2/(2 d) <= theta_eps`` with ``d = -psi''`` of
slide-rock at ``psi = psi' = 0`` (> 0), as in :mod:`isoslide.peers.slide_rock`.

End of the run
--------------
At ``t_end`` (default :func:`~isoslide.peers.reference_building.default_horizon`: the later pulse's
end plus 50 times the longest of ``T_p``, ``T_b``, ``T_s``, or 50 decay times of the slowest free
mode), at the overturn, or earlier when the run settles: after the pulses, with the block at rest
and the bearing held or elastic, the building's peer's bound on every later demand (the floor's
acceleration within ``min(thr, G tan(alpha))``, neither uplift nor slip; the isolator's within its
limits) holds.

Energy ledger
-------------
Integrated with the state (without vertical ground motion): the ground's work on the building and
the block in the ground's frame, the viscous and isolator dissipation, and the block's friction
loss ``-m H u'``; with the kinetic energy (velocities relative to the ground; the block's ``m/2
(x_c'**2 + y_c'**2) + m R**2 psi'**2/6``), the potential energy (springs, the bilinear bearing's
elastic part, the block's ``m G (y_c - h)``) and the impact losses they balance at every instant.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np
from scipy.integrate import solve_ivp

from ..pulses import accel_at
from ..scene import Scene
from .reference_building import (_ULP4, Building, _periods, _settle_margin_fn, _slide_settle_margin_fn,
                                 _stop_event, building_of, default_horizon, excitation_breakpoints,
                                 excitation_end, structure_forces)
from .rocking import _HALF_PI, RockingContactError, _advance, _excursion_events
from .stick_slip import X, XD, XS, bearing_event, candidates, sign

__all__ = ["MODE_NAMES", "RockingBlock", "RockingBuildingHistory", "RockingBuildingResult", "block_of", "solve"]

REST, SLIDE, ROCK, SLIDE_ROCK = 0, 1, 2, 3
MODE_NAMES = ("rest", "slide", "rock", "slide-rock")
"""Names of the block's modes, indexed by the history's ``mode`` codes."""

_LEDGER = ("work", "viscous", "isolator", "friction")


@dataclass(frozen=True)
class RockingBlock:
    """The scene's block in the model's units (module docstring).

    Attributes
    ----------
    G : float
        ``g/a_p = 1/(Pi18 Pi21)`` (dimensionless).
    alpha : float
        Slenderness ``atan(Pi18)`` (rad).
    tan_a : float
        ``tan(alpha) = Pi18``.
    R, b, h : float
        Corner to centre of mass, half-width, half-height (units ``a_p T_p**2``).
    k : float
        ``3/(4 R)`` (units ``1/(a_p T_p**2)``); ``p**2 = k G`` (units ``1/T_p**2``).
    kappa : float
        ``3 h/(4 R**2)`` (units ``1/(a_p T_p**2)``), the impact rule's coupling of slip and rotation.
    e : float
        Restitution of the angular velocity at impact.
    m : float
        Mass ``Pi8`` (units ``M_b``).
    mu_s, mu_k : float
        Static and kinetic friction coefficients (dimensionless).
    theta_eps : float
        Tilt (rad) below which a dying cascade ends.
    """

    G: float
    alpha: float
    tan_a: float
    R: float
    b: float
    h: float
    k: float
    kappa: float
    e: float
    m: float
    mu_s: float
    mu_k: float
    theta_eps: float

    @property
    def can_rock(self) -> bool:
        """True when friction can hold a corner at uplift, ``mu_s > tan(alpha)`` (Shenton 1996)."""
        return self.mu_s > self.tan_a


def block_of(scene: Scene, theta_eps_ratio: float = 1e-3) -> RockingBlock:
    """The rocking block of a scene in the model's units.

    Parameters
    ----------
    scene : Scene
        A scene with a rocking block (``Pi18`` given), no Stribeck law (``Pi6 = Pi7 = 0``).
    theta_eps_ratio : float
        ``theta_eps / alpha``, in ``(0, 1)``.

    Returns
    -------
    RockingBlock

    Raises
    ------
    ValueError
        The scene has no rocking block, or one this peer does not model; the message names the group.
    """
    if not scene.rocks:
        raise ValueError("pi18 = None: the scene's contents only slide; allowed: a scene with a rocking block "
                         "(pi18, pi19, pi21), or isoslide.peers.reference_building for sliding contents")
    for name in ("pi6", "pi7"):
        if getattr(scene, name) > 0.0:
            raise ValueError(f"{name} = {getattr(scene, name)!r} > 0 with a rocking block (pi18 = {scene.pi18!r}); "
                             "allowed: pi6 = 0 and pi7 = 0 (Coulomb friction: this peer has no Stribeck law "
                             "for a block that can rock)")
    if scene.pi24 > 0.0:
        raise ValueError(f"pi24 = {scene.pi24!r} > 0 (a triple friction pendulum) with a rocking block; allowed: "
                         "pi24 = 0 (this peer's isolators are those of isoslide.peers.reference_building)")
    r = float(theta_eps_ratio)
    if not 0.0 < r < 1.0:
        raise ValueError(f"theta_eps_ratio = {theta_eps_ratio!r} is out of range; allowed: 0 < value < 1")
    G = 1.0 / (scene.pi18 * scene.pi21)
    alpha = math.atan(scene.pi18)
    R = 0.75 * G / scene.pi19 ** 2
    B = building_of(scene)
    mu_s = B.thr / G
    mu_k = B.phi(0.0) / G          # Pi6 = Pi7 = 0: phi = thr at every speed
    return RockingBlock(G=G, alpha=alpha, tan_a=float(scene.pi18), R=R, b=R * math.sin(alpha),
                        h=R * math.cos(alpha), k=0.75 / R, kappa=0.75 * math.cos(alpha) / R,
                        e=float(scene.restitution), m=float(scene.pi8), mu_s=mu_s, mu_k=mu_k,
                        theta_eps=r * alpha)


@dataclass(frozen=True)
class RockingBuildingHistory:
    """Time history of :func:`solve` (model units; an event appears twice, before and after).

    Attributes
    ----------
    tau : ndarray
        Time (units ``T_p``).
    theta, omega : ndarray
        Tilt (rad) and ``theta'`` (rad per ``T_p``); 0 when flat.
    u, ud : ndarray
        The contact corner's displacement and velocity relative to the floor (units ``a_p T_p**2``,
        ``a_p T_p``).
    mode : ndarray of int8
        The block's mode, an index into :data:`MODE_NAMES`.
    x, xd : ndarray
        The slab's displacement and velocity relative to the ground (units ``a_p T_p**2``, ``a_p T_p``).
    iso_mode : ndarray of int8
        The isolator's mode (0 held or elastic, +-1 sliding or yielding).
    work, viscous, isolator, friction, impact : ndarray
        Ground's work and the dissipations so far: viscous, isolator, the block's friction, the block's
        impact losses (units ``M_b a_p**2 T_p**2``).
    kinetic, potential : ndarray
        Energies at those times (units ``M_b a_p**2 T_p**2``; velocities relative to the ground).
    """

    tau: np.ndarray
    theta: np.ndarray
    omega: np.ndarray
    u: np.ndarray
    ud: np.ndarray
    mode: np.ndarray
    x: np.ndarray
    xd: np.ndarray
    iso_mode: np.ndarray
    work: np.ndarray
    viscous: np.ndarray
    isolator: np.ndarray
    friction: np.ndarray
    impact: np.ndarray
    kinetic: np.ndarray
    potential: np.ndarray


@dataclass(frozen=True)
class RockingBuildingResult:
    """Result of :func:`solve`.

    Attributes
    ----------
    pi1 : float
        Peak ``|u|`` of the block's base relative to its floor (units ``a_p T_p**2``).
    tau_pi1 : float
        Time of that peak (units ``T_p``).
    theta_max : float
        Peak ``|theta|`` (rad; ``pi/2`` when the block overturned).
    tau_theta_max : float
        Time of that peak (units ``T_p``).
    overturned : bool
        ``|theta|`` reached ``pi/2`` (the run stopped there).
    t_overturn : float
        Time it did (units ``T_p``), else nan.
    modes : tuple of str
        The block's modes visited, in the order first entered (among :data:`MODE_NAMES`): the rest it
        starts in and the mode of every phase integrated (a mode left at the instant it is entered,
        such as a flat slide that tips at once, is not counted).
    impacts : int
        Impacts at ``theta = 0``.
    settled : bool
        The run ended settled (module docstring, "End of the run").
    tau_end : float
        Time at which the run stopped (units ``T_p``).
    u_end : float
        Final ``u`` (units ``a_p T_p**2``).
    t_rest : float
        Last impact after which the block was declared at rest (units ``T_p``), else nan.
    nfev : int
        Right-hand-side evaluations.
    history : RockingBuildingHistory
        The time history.
    """

    pi1: float
    tau_pi1: float
    theta_max: float
    tau_theta_max: float
    overturned: bool
    t_overturn: float
    modes: tuple
    impacts: int
    settled: bool
    tau_end: float
    u_end: float
    t_rest: float
    nfev: int
    history: RockingBuildingHistory = field(repr=False)


class _Motion(NamedTuple):
    """Accelerations and forces in one mode (units ``a_p``, ``M_b a_p``, rad per ``T_p**2``)."""

    xdd: float
    xsdd: np.ndarray
    udd: float
    psidd: float
    fhd: float
    af: float
    fh_need: float
    H: float
    V: float
    fh: float


def _sgn(x: float) -> float:
    return 1.0 if x > 0.0 else (-1.0 if x < 0.0 else 0.0)


def _motion(B: Building, K: RockingBlock, p: float, nz: float, y, mode: int, s: int, sig: float, si: int,
            t: float = math.nan) -> _Motion:
    """The building's and the block's accelerations in the block's ``(mode, s, sig)`` and isolator mode ``si``.

    ``p`` the ground's acceleration (units ``a_p``), ``nz`` the normal-force factor, ``y`` the state
    (the building's peer's layout, then ``psi, psi'``), ``t`` the time for messages.
    """
    held = B.holds and si == 0
    n = B.n
    x, ud = y[X], y[B.UD]
    psi, w = y[B.n_state], y[B.n_state + 1]
    F, fh, kd, f, S = structure_forces(B, y, si, nz)
    Gam = K.G * nz
    # the contact force on the block, per unit mass: H = h1 A_F + h0
    if mode == REST:
        h1, h0 = 1.0, 0.0
    elif mode == SLIDE:
        h1, h0 = 0.0, -sig * (nz * B.phi(ud))
    else:
        sd, cd = math.sin(K.alpha - psi), math.cos(K.alpha - psi)
        if mode == ROCK:
            h1 = 1.0 - 0.75 * cd * cd
            h0 = s * (K.R * sd * w * w - 0.75 * Gam * sd * cd)
        else:
            c = s * cd + K.mu_k * sig * sd
            D = 1.0 - 0.75 * c * s * cd
            if not D > 0.0:
                raise RockingContactError(
                    f"no consistent contact mode at tau = {t!r}: slide-rock with mu_k = {K.mu_k!r} gives "
                    f"1 - 3/4 c s cos(alpha - psi) = {D:.6g} <= 0 (Painleve's paradox)", t, "indeterminate")
            a_sr = (0.75 * c * Gam * sd - K.R * w * w * (s * sd - K.mu_k * sig * cd) - K.mu_k * sig * Gam) / D
            P_sr = -K.k * (Gam * sd + s * a_sr * cd)
            V_sr = Gam + K.R * (sd * P_sr - cd * w * w)
            h1, h0 = 0.0, -K.mu_k * sig * V_sr
    m = B.m
    kf = B.floor
    if kf:
        ab = p if held else (-F + S) / B.mb
        A = -f / B.ms
        A[kf - 1] = (-f[kf - 1] - m * h0) / (B.ms[kf - 1] + m * h1)
        af = A[kf - 1]
    else:
        ab = p if held else (-F + S - m * h0) / (B.mb + m * h1)
        af = ab
        A = -f / B.ms if n else None
    H = h1 * af + h0
    if mode == REST:
        udd, P, V = 0.0, 0.0, Gam
    elif mode == SLIDE:
        udd, P, V = H - af, 0.0, Gam
    elif mode == ROCK:
        P = -K.k * (Gam * sd + s * af * cd)
        udd, V = 0.0, Gam + K.R * (sd * P - cd * w * w)
    else:
        udd, P, V = a_sr - af, P_sr, V_sr
    if held:
        xdd = 0.0
        fh_need = -B.mb * p - kd * x + S + (0.0 if kf else -m * H)
        fh = fh_need
    else:
        xdd = ab - p
        fh_need = math.nan
    xsdd = A - ab if n else np.zeros(1)
    fhd = B.ke * y[XD] if (B.kind == "bilinear" and si == 0) else 0.0
    return _Motion(xdd, xsdd, udd, P, fhd, af, fh_need, H, V, fh)


def _block_kinetic(B: Building, K: RockingBlock, y, mode: int, s: int) -> float:
    """The block's kinetic energy, velocities relative to the ground (units ``M_b a_p**2 T_p**2``)."""
    vf = y[XD] + (y[B.XSD + B.floor - 1] if B.floor else 0.0)
    if mode in (ROCK, SLIDE_ROCK):
        psi, w = y[B.n_state], y[B.n_state + 1]
        sd, cd = math.sin(K.alpha - psi), math.cos(K.alpha - psi)
        xc, yc = y[B.UD] + s * K.R * cd * w, K.R * sd * w
        return 0.5 * K.m * ((vf + xc) ** 2 + yc * yc + K.R * K.R * w * w / 3.0)
    return 0.5 * K.m * (vf + y[B.UD]) ** 2


def _impact(K: RockingBlock, t: float, s: int, q: float, v: float) -> tuple:
    """``(u'+, psi'+)`` after corner ``-s`` strikes at ``psi' = q < 0``, ``u' = v`` (slide_rock's rule)."""
    def post(D):
        r = -K.e * q + s * K.kappa * D
        return r, D - s * K.h * (r + q), K.b * (r - q)

    r, jx, jy = post(-v)
    if jy >= 0.0 and abs(jx) <= K.mu_s * jy and r > 0.0:
        return 0.0, r
    sig = -_sgn(jx)
    den = 1.0 - K.h * K.kappa + K.mu_k * sig * s * K.b * K.kappa
    D = q * (s * K.h * (1.0 - K.e) + K.mu_k * sig * K.b * (1.0 + K.e)) / den if den > 0.0 else math.nan
    v_new = v + D
    r, jx, jy = post(D)
    if not (den > 0.0 and sig != 0.0 and _sgn(v_new) == sig and jy >= 0.0 and r > 0.0):
        raise RockingContactError(
            f"the impact at tau = {t!r} has no consistent outcome (theta' = {s * q!r}, u' = {v!r}): sliding gives "
            f"u'+ = {v_new!r}, psi'+ = {r!r}, J_y/m = {jy!r}", t, "impact")
    return v_new, r


def solve(scene: Scene, *, rtol: float = 1e-10, atol: float = 1e-12, theta_eps_ratio: float = 1e-3,
          max_impacts: int = 100_000, t_end: float | None = None) -> RockingBuildingResult:
    """Move a rigid block on a floor of the general building, with two-way coupling, event by event.

    The building and the block start at rest at ``scene.pulse.tau_start``.  See the module docstring
    for the model and the rules.

    Parameters
    ----------
    scene : Scene
        A scene with a rocking block (``Pi18``, ``Pi19``, ``Pi21``; ``Pi20`` or Housner's restitution),
        without a Stribeck law (``Pi6 = Pi7 = 0``) or a triple friction pendulum.
    rtol, atol : float
        Tolerances of ``solve_ivp`` (``DOP853``; ``atol`` in the state's model units).
    theta_eps_ratio : float
        ``theta_eps/alpha`` of the end-of-cascade rule, in ``(0, 1)``.
    max_impacts : int
        Most impacts before ``RuntimeError``.
    t_end : float or None
        Horizon (units ``T_p``); None: :func:`~isoslide.peers.reference_building.default_horizon`.

    Returns
    -------
    RockingBuildingResult

    Raises
    ------
    ValueError
        A scene this peer does not model (the message names the group) or a bad option.
    RockingContactError
        Flight (``V < 0`` with ``|theta| < alpha``), an impact without a consistent outcome, or no
        consistent contact mode; the message names the time.
    RuntimeError
        More than ``max_impacts`` impacts, zero-length event chatter, or the integrator failed.
    """
    K = block_of(scene, theta_eps_ratio)
    B = building_of(scene)
    if isinstance(max_impacts, bool) or not isinstance(max_impacts, int) or max_impacts < 1:
        raise ValueError(f"max_impacts = {max_impacts!r} is invalid; allowed: a positive integer")
    pulse = scene.pulse
    code, params = int(pulse.code), pulse.param_array
    tau_end = excitation_end(scene)
    horizon = default_horizon(scene) if t_end is None else float(t_end)
    if not horizon > pulse.tau_start:
        raise ValueError(f"t_end = {t_end!r} is out of range; allowed: t_end > {pulse.tau_start!r} (the pulse's start)")
    bps = [float(b) for b in excitation_breakpoints(scene) if b < horizon]
    periods = _periods(B)
    hmax_pulse = min([1.0 / 64.0] + [T / 32.0 for T in periods])
    hmax_free = min([max(1.0, scene.pi3) / 64.0] + [T / 32.0 for T in periods])
    h_rock = 0.1 / scene.pi19
    lim_b = B.thr * (1.0 + _ULP4)                 # rest without rocking: |A_F| <= thr nz
    lim_up = K.G * K.tan_a * (1.0 + _ULP4)        # rest with rocking: |A_F| <= Gam tan(alpha)
    lim_q = B.q * (1.0 + _ULP4)
    mu_lim = K.mu_s * (1.0 + _ULP4)
    can_rock = K.can_rock
    rest_limit = min(B.thr, K.G * K.tan_a)
    B_settle = dataclasses.replace(B, thr=rest_limit)
    PSI, PSID = B.n_state, B.n_state + 1
    LED = B.n_state + 2
    UD, U, FH = B.UD, B.U, B.FH
    n_fl = B.n
    sliding = B.kind == "sliding"

    def p_at(t):
        return accel_at(code, params, t)

    n_at = B.normal

    def motion(p, nz, y, bm, si, t=math.nan):
        return _motion(B, K, p, nz, y, bm[0], bm[1], bm[2], si, t)

    # ---------------------------------------------------------------- bookkeeping
    tau = float(pulse.tau_start)
    y = np.zeros(B.n_state + 2 + len(_LEDGER))
    bm = (REST, 1, 0.0)          # block mode: (mode, corner s, sliding direction sigma)
    si = 0
    rising = None
    forced_b = None              # a block candidate set by an event
    forced_i = 0
    after_event = False
    u_peak, tau_u = 0.0, tau
    th_peak, tau_th = 0.0, tau
    overturned, t_over = False, math.nan
    settled = False
    t_rest = math.nan
    n_impacts = 0
    lost = 0.0
    nfev = 0
    zero_len = 0
    visited = ["rest"]         # the block starts at rest
    hist: list[tuple] = []

    def note(t, yy):
        nonlocal u_peak, tau_u, th_peak, tau_th
        if abs(yy[U]) > u_peak:
            u_peak, tau_u = abs(yy[U]), t
        if bm[0] in (ROCK, SLIDE_ROCK) and yy[PSI] > th_peak:
            th_peak, tau_th = yy[PSI], t

    def record(ts, Y, bm_, si_):
        ts = np.atleast_1d(np.asarray(ts, dtype=float))
        hist.append((ts, np.array(Y, dtype=float).reshape(y.size, -1), bm_, si_, lost))

    # ---------------------------------------------------------------- the modes at a phase start
    def resolve_rock(s, p, nz, yy, i, t):
        """Rock on corner ``s`` with the corner stuck, or slide-rock if friction cannot hold it."""
        mo = motion(p, nz, yy, (ROCK, s, 0.0), i, t)
        if yy[PSI] < K.alpha and abs(mo.H) > mu_lim * mo.V:
            return resolve_slide_rock(s, -_sgn(mo.H), p, nz, yy, i, t)
        return (ROCK, s, 0.0), mo

    def resolve_slide_rock(s, sgm, p, nz, yy, i, t):
        mo = motion(p, nz, yy, (SLIDE_ROCK, s, sgm), i, t)
        if sgm == 0.0 or sgm * mo.udd < -1e-12 * (K.G * nz + abs(mo.af)):
            return None
        return (SLIDE_ROCK, s, sgm), mo

    def resolve(c, p, nz, yy, i, free_b, t):
        """A block candidate ``c`` with the isolator in mode ``i``: ``(block mode, motion)`` or None."""
        kind = c[0]
        if kind == "rest":
            mo = motion(p, nz, yy, (REST, 1, 0.0), i, t)
            return ((REST, 1, 0.0), mo) if abs(mo.af) <= (lim_up if can_rock else lim_b) * nz else None
        if kind == "slide":
            sgm = c[1]
            if can_rock and K.mu_k > K.tan_a:       # the resultant would pass the leading corner: tip
                mo = motion(p, nz, yy, (SLIDE_ROCK, int(sgm), sgm), i, t)
                if not mo.psidd > 0.0:
                    raise RockingContactError(
                        f"no consistent contact mode at tau = {t!r}: sliding with mu_k = {K.mu_k!r} > tan(alpha) "
                        f"tips the block, but slide-rock gives psi'' = {mo.psidd!r}", t, "indeterminate")
                return (SLIDE_ROCK, int(sgm), sgm), mo
            mo = motion(p, nz, yy, (SLIDE, 1, sgm), i, t)
            if free_b and not sgm * mo.udd > 0.0:
                return None
            return (SLIDE, 1, sgm), mo
        if kind == "uplift":
            mo = motion(p, nz, yy, (ROCK, c[1], 0.0), i, t)
            if not mo.psidd > 0.0:
                return None
            return resolve_rock(c[1], p, nz, yy, i, t)
        if kind == "rock":
            return resolve_rock(c[1], p, nz, yy, i, t)
        if kind == "slide-rock":
            return (SLIDE_ROCK, c[1], c[2]), motion(p, nz, yy, (SLIDE_ROCK, c[1], c[2]), i, t)
        if kind == "start-slide-rock":
            return resolve_slide_rock(c[1], c[2], p, nz, yy, i, t)
        raise AssertionError(kind)

    def block_candidates(yy):
        """The block's candidates at a phase start and whether they are free (chosen at rest)."""
        if forced_b is not None:
            return [forced_b], False
        mode = bm[0]
        at_rest = mode == REST or (mode == SLIDE and yy[UD] == 0.0)
        if at_rest:
            if can_rock:
                return [("rest",), ("uplift", 1), ("uplift", -1)], True
            return [("rest",), ("slide", 1.0), ("slide", -1.0)], True
        if mode == SLIDE:
            return [("slide", _sgn(yy[UD]))], False
        if mode == ROCK:
            return [("rock", bm[1])], False
        return [("slide-rock", bm[1], bm[2])], False

    def choose(t, yy, si_):
        p, nz = p_at(t), n_at(t)
        cand_b, free_b = block_candidates(yy)
        cand_i, free_i = candidates(forced_i, si_, yy[XD]) if sliding else ((si_,), False)
        order = sorted(((c, i) for c in cand_b for i in cand_i),
                       key=lambda ci: (ci[0][0] != "rest", sliding and ci[1] != 0))
        for c, i in order:
            got = resolve(c, p, nz, yy, i, free_b, t)
            if got is None:
                continue
            mo = got[1]
            if sliding:
                if i == 0 and abs(mo.fh_need) > lim_q * nz:
                    continue
                if i != 0 and free_i and not i * mo.xdd > 0.0:
                    continue
            return got[0], i, mo
        raise RockingContactError(f"no consistent mode of the block and the isolator at tau = {t!r} (block "
                                  f"candidates {cand_b}, isolator {cand_i})", t, "indeterminate")

    def bilinear_mode(t, yy, si_):
        p, nz = p_at(t), n_at(t)
        fh, xd = yy[FH], yy[XD]
        if si_ == 0:
            if abs(fh) >= B.q * (1.0 - _ULP4):
                s_ = sign(fh)
                v = xd if xd != 0.0 else motion(p, nz, yy, bm, s_, t).xdd
                if s_ * v > 0.0:
                    return s_
            return 0
        v = xd if xd != 0.0 else motion(p, nz, yy, bm, si_, t).xdd
        return si_ if si_ * v > 0.0 else 0

    # ---------------------------------------------------------------- main loop
    record(tau, y, bm, si)
    while True:
        if B.kind == "bilinear" and not after_event:
            new = bilinear_mode(tau, y, si)
            if new != si:
                si = new
                if si:
                    y[FH] = si * B.q
        old_mode = bm[0]
        bm, si, _ = choose(tau, y, si)
        if old_mode in (REST, SLIDE) and bm[0] in (ROCK, SLIDE_ROCK):
            rising = True
        forced_b, forced_i = None, 0
        after_event = False
        if bm[0] == REST:
            y[UD] = 0.0
            y[PSI] = y[PSID] = 0.0
        if B.holds and si == 0:
            y[XD] = 0.0
        mo0 = motion(p_at(tau), n_at(tau), y, bm, si, tau)
        if MODE_NAMES[bm[0]] not in visited:
            visited.append(MODE_NAMES[bm[0]])
        rocking = bm[0] in (ROCK, SLIDE_ROCK)
        if rocking and y[PSI] < K.alpha and mo0.V < 0.0:
            raise RockingContactError(f"the block would leave the floor at tau = {tau!r} ({MODE_NAMES[bm[0]]}): "
                                      f"the vertical contact force would become negative (V/m = {mo0.V:.6g})",
                                      tau, "flight")
        settle_g = None
        if bm[0] == REST and tau >= tau_end:
            if si == 0:
                settle_g = _settle_margin_fn(B_settle, y, si)
                if settle_g is None or settle_g(tau, y) >= 0.0:
                    settled = True
                    break
            elif B.speed_dependent and not B.flexible:
                settle_g = _slide_settle_margin_fn(B_settle, si)
                if settle_g(tau, y) >= 0.0:
                    settled = True
                    break
        if tau >= horizon:
            break
        # ---- this segment --------------------------------------------------------------------
        nxt = [b for b in bps if b > tau]
        seg_end = min(nxt[0] if nxt else horizon, horizon)
        t_clip = math.nextafter(seg_end, -math.inf)
        t0 = tau
        hmax = hmax_pulse if t0 < tau_end else hmax_free
        if rocking:
            hmax = min(hmax, h_rock)
        bm_, si_ = bm, si

        def p_of(t, t0=t0, t_clip=t_clip):
            return accel_at(code, params, min(max(t, t0), t_clip))

        def n_of(t, t0=t0, t_clip=t_clip):
            return n_at(min(max(t, t0), t_clip))

        def mot(t, yy, bm_=bm_, si_=si_):
            return motion(p_of(t), n_of(t), yy, bm_, si_, t)

        def rhs(t, yy, bm_=bm_, si_=si_):
            p, nz = p_of(t), n_of(t)
            mo = motion(p, nz, yy, bm_, si_, t)
            d = np.empty(yy.size)
            d[X], d[XD] = yy[XD], mo.xdd
            d[XS:B.XSD] = yy[B.XSD:U]
            d[B.XSD:U] = mo.xsdd
            d[U], d[UD], d[FH] = yy[UD], mo.udd, mo.fhd
            d[PSI], d[PSID] = yy[PSID], mo.psidd
            # the ledger: ground's work, viscous, isolator and the block's friction dissipation
            xsd = yy[B.XSD:B.XSD + n_fl]
            vf = yy[XD] + (xsd[B.floor - 1] if B.floor else 0.0)
            xc, yc = yy[UD], 0.0
            if bm_[0] in (ROCK, SLIDE_ROCK):
                sd, cd = math.sin(K.alpha - yy[PSI]), math.cos(K.alpha - yy[PSI])
                xc += bm_[1] * K.R * cd * yy[PSID]
                yc = K.R * sd * yy[PSID]
            mom = B.mb * yy[XD] + float(B.ms @ (yy[XD] + xsd)) + K.m * (vf + xc)
            d[LED] = -p * mom - K.m * K.G * (nz - 1.0) * yc
            d[LED + 1] = B.cb * yy[XD] ** 2 + float(xsd @ B.Cs @ xsd)
            d[LED + 2] = mo.fh * yy[XD] - (mo.fh * mo.fhd / B.ke if B.kind == "bilinear" else 0.0)
            d[LED + 3] = -K.m * mo.H * yy[UD]
            return d

        specs = []

        def add(fn, kind, direction=-1.0, specs=specs):
            specs.append((fn, kind, direction))

        mode = bm[0]
        if mode == REST:
            if can_rock:
                for side in (1, -1):
                    add(lambda t, yy, side=side: lim_up * n_of(t) + side * mot(t, yy).af, ("uplift", side))
            else:
                for sgn_ in (1.0, -1.0):
                    add(lambda t, yy, sgn_=sgn_: lim_b * n_of(t) - sgn_ * mot(t, yy).af, ("slip",))
        elif mode == SLIDE:
            add(_stop_event(int(bm[2]), UD, t0, y, mo0.udd), ("stop",))
        else:
            ev_main, ev_over = _excursion_events(rising, PSI)
            add(ev_main, ("apex",) if rising else ("impact",), ev_main.direction)
            add(ev_over, ("overturn",) if rising else ("turn",), ev_over.direction)

            def ev_flight(t, yy):
                return mot(t, yy).V if yy[PSI] < K.alpha else 1.0

            add(ev_flight, ("flight",))
            if mode == ROCK:
                for sgn_ in (1.0, -1.0):
                    def ev_fr(t, yy, sgn_=sgn_):
                        if yy[PSI] >= K.alpha:
                            return 1.0
                        mo = mot(t, yy)
                        return mu_lim * mo.V - sgn_ * mo.H

                    add(ev_fr, ("friction",))
            else:
                add(lambda t, yy, sg=bm[2]: sg * yy[UD], ("stick",))
        if sliding:
            if si == 0:
                for sgn_ in (1.0, -1.0):
                    add(lambda t, yy, sgn_=sgn_: lim_q * n_of(t) - sgn_ * mot(t, yy).fh_need, ("iso_break",))
            else:
                add(_stop_event(si, XD, t0, y, mo0.xdd), ("iso_stop",))
        elif B.kind == "bilinear":
            if si == 0:
                add(lambda t, yy: B.q - yy[FH], ("yield",))
                add(lambda t, yy: B.q + yy[FH], ("yield",))
            else:
                add(_stop_event(si, XD, t0, y, mo0.xdd), ("unload",))
        if settle_g is not None:
            add(settle_g, ("settle",), 1.0)
        for fn, _, direction in specs:
            fn.terminal, fn.direction = True, direction
        events, kinds = [sp[0] for sp in specs], [sp[1] for sp in specs]

        sol = solve_ivp(rhs, (t0, seg_end), y, method="DOP853", rtol=rtol, atol=atol, events=events, max_step=hmax)
        nfev += sol.nfev
        if sol.status < 0:
            raise RuntimeError(f"solve_ivp failed from tau = {t0!r}: {sol.message}")
        if sol.status != 1:
            record(sol.t[1:], sol.y[:, 1:], bm, si)
            for j in range(1, sol.t.size):
                note(float(sol.t[j]), sol.y[:, j])
            tau = min(float(sol.t[-1]), seg_end)
            y = np.array(sol.y[:, -1], dtype=float)
            continue
        hits = [(float(te[0]), j) for j, te in enumerate(sol.t_events) if len(te)]
        te, j = min(hits)
        kind = kinds[j][0]
        zero_len = zero_len + 1 if te <= t0 else 0
        if zero_len > 8:
            raise RuntimeError(f"events of zero length repeat at tau = {te!r}")
        ys = sol.y.copy()
        ye = np.array(sol.y_events[j][0], dtype=float)
        # the event's own coordinate is exactly at its value
        if kind == "apex" or kind == "turn":
            ye[PSID] = 0.0
        elif kind == "overturn":
            ye[PSI] = _HALF_PI
        elif kind == "impact":
            ye[PSI] = 0.0
        elif kind in ("stop", "stick"):
            ye[UD] = 0.0
        elif kind == "iso_stop":
            ye[XD] = 0.0
        ys[:, -1] = ye
        record(sol.t[1:], ys[:, 1:], bm, si)
        for jj in range(1, sol.t.size):
            note(float(sol.t[jj]), ys[:, jj])
        tau, y = te, ye
        if kind == "settle":
            settled = True
            break
        after_event = True
        p, nz = p_at(tau), n_at(tau)
        if kind == "uplift":
            side = kinds[j][1]

            def ok(tt, side=side, yy=y, i=si):
                return _motion(B, K, p_at(tt), n_at(tt), yy, ROCK, side, 0.0, i, tt).psidd > 0.0

            t_up = _advance(tau, ok)
            if ok(t_up):
                tau = t_up
                forced_b = ("uplift", side)
            else:
                after_event = False
        elif kind == "slip":
            forced_b = ("slide", -_sgn(motion(p, nz, y, bm, si, tau).af))
        elif kind == "stop":
            if can_rock:
                af = motion(p, nz, y, (REST, 1, 0.0), si, tau).af
                if abs(af) > mu_lim * K.G * nz:
                    forced_b = ("slide", -_sgn(af))
                else:
                    bm = (REST, 1, 0.0)
            # else: chosen at the phase start among rest and sliding either way
        elif kind == "apex":
            rising = False
        elif kind == "turn":
            rising = True
        elif kind == "overturn":
            overturned, t_over = True, tau
            th_peak, tau_th = _HALF_PI, tau
            break
        elif kind == "flight":
            V = motion(p, nz, y, bm, si, tau).V
            raise RockingContactError(f"the block would leave the floor at tau = {tau!r} ({MODE_NAMES[bm[0]]}): "
                                      f"the vertical contact force would become negative (V/m = {V:.6g})",
                                      tau, "flight")
        elif kind == "friction":
            H = motion(p, nz, y, bm, si, tau).H
            forced_b = ("start-slide-rock", bm[1], -_sgn(H))
        elif kind == "stick":
            got = resolve_rock(bm[1], p, nz, y, si, tau)
            if got is None or got[0][0] == SLIDE_ROCK and got[0][2] == bm[2]:
                raise RockingContactError(f"no consistent contact mode at tau = {tau!r}: the sliding corner stops, "
                                          "friction cannot hold it, and it would slide on the same way", tau,
                                          "indeterminate")
            forced_b = ("rock", bm[1]) if got[0][0] == ROCK else ("start-slide-rock", bm[1], got[0][2])
        elif kind == "impact":
            n_impacts += 1
            if n_impacts > max_impacts:
                raise RuntimeError(f"more than max_impacts = {max_impacts} impacts by tau = {tau!r}: the cascade "
                                   "did not meet the end-of-cascade rule")
            s = bm[1]
            before = _block_kinetic(B, K, y, bm[0], s)
            v_new, r = _impact(K, tau, s, float(y[PSID]), float(y[UD]))
            s = -s
            y[UD], y[PSI], y[PSID] = v_new, 0.0, r
            rising = True
            if v_new == 0.0:
                Gam = K.G * nz
                af0 = abs(motion(p, nz, y, (REST, 1, 0.0), si, tau).af)
                D = K.k * (Gam * math.sin(K.alpha - K.theta_eps) - af0 * math.cos(K.alpha - K.theta_eps))
                if D > 0.0 and r * r <= 2.0 * D * K.theta_eps:      # the cascade ends: at rest
                    y[PSID] = 0.0
                    bm, t_rest = (REST, 1, 0.0), tau
                else:
                    bm, forced_b = (ROCK, s, 0.0), ("rock", s)
            else:
                sgm = _sgn(v_new)
                y0 = y.copy()
                y0[PSID] = 0.0
                P0 = motion(p, nz, y0, (SLIDE_ROCK, s, sgm), si, tau).psidd
                if P0 < 0.0 and r * r / (-2.0 * P0) <= K.theta_eps:    # flat, sliding with x_c'
                    y[UD] = v_new + s * K.h * r
                    y[PSID] = 0.0
                    sgm = _sgn(y[UD])
                    bm = (SLIDE, 1, sgm) if sgm != 0.0 else (REST, 1, 0.0)
                else:
                    bm, forced_b = (SLIDE_ROCK, s, sgm), ("slide-rock", s, sgm)
            lost += before - _block_kinetic(B, K, y, bm[0], s)
        elif kind == "iso_break":
            forced_i = sign(motion(p, nz, y, bm, si, tau).fh_need)
        elif kind in ("yield", "unload"):
            si = bearing_event(kind, y, FH, B.q)
        record(tau, y, bm, si)

    note(tau, y)
    if bm[0] in (ROCK, SLIDE_ROCK) and not overturned and y[PSI] > th_peak:
        th_peak, tau_th = float(y[PSI]), tau
    return RockingBuildingResult(pi1=float(u_peak), tau_pi1=float(tau_u), theta_max=float(th_peak),
                                 tau_theta_max=float(tau_th), overturned=overturned, t_overturn=t_over,
                                 modes=tuple(visited), impacts=n_impacts, settled=settled, tau_end=float(tau),
                                 u_end=float(y[U]), t_rest=t_rest, nfev=int(nfev),
                                 history=_history(B, K, hist))


def _history(B: Building, K: RockingBlock, hist: list) -> RockingBuildingHistory:
    """The recorded segments as one :class:`RockingBuildingHistory`, with the energies."""
    PSI, PSID, LED = B.n_state, B.n_state + 1, B.n_state + 2
    cols: dict[str, list] = {name: [] for name in ("tau", "theta", "omega", "u", "ud", "mode", "x", "xd", "iso",
                                                     "impact", "kin", "pot", "led")}
    n = B.n
    for ts, Y, bm, si, lost in hist:
        mode, s = bm[0], bm[1]
        rock = mode in (ROCK, SLIDE_ROCK)
        psi, w = (Y[PSI], Y[PSID]) if rock else (np.zeros(ts.size), np.zeros(ts.size))
        cols["tau"].append(ts)
        cols["theta"].append(s * psi)
        cols["omega"].append(s * w)
        cols["u"].append(Y[B.U])
        cols["ud"].append(Y[B.UD])
        cols["mode"].append(np.full(ts.size, mode, dtype=np.int8))
        cols["x"].append(Y[X])
        cols["xd"].append(Y[XD])
        cols["iso"].append(np.full(ts.size, si, dtype=np.int8))
        cols["impact"].append(np.full(ts.size, lost))
        xd = Y[XD]
        xs, xsd = Y[XS:XS + n], Y[B.XSD:B.XSD + n]
        kin = 0.5 * B.mb * xd ** 2 + (0.5 * (B.ms @ (xd[None, :] + xsd) ** 2) if n else 0.0)
        pot = 0.5 * B.kd * Y[X] ** 2 + (0.5 * np.einsum("it,ij,jt->t", xs, B.Ks, xs) if n else 0.0)
        if B.kind == "bilinear":
            pot = pot + Y[B.FH] ** 2 / (2.0 * B.ke)
        vf = xd + (xsd[B.floor - 1] if B.floor else 0.0)
        sd, cd = np.sin(K.alpha - psi), np.cos(K.alpha - psi)
        xc = Y[B.UD] + s * K.R * cd * w
        yc = K.R * sd * w
        kin = kin + 0.5 * K.m * ((vf + xc) ** 2 + yc ** 2 + K.R ** 2 * w ** 2 / 3.0)
        pot = pot + K.m * K.G * (K.R * cd - K.h)
        cols["kin"].append(kin)
        cols["pot"].append(pot)
        cols["led"].append(Y[LED:LED + len(_LEDGER)])
    cat = {k: np.concatenate(v, axis=-1) for k, v in cols.items()}
    led = cat["led"]
    return RockingBuildingHistory(tau=cat["tau"], theta=cat["theta"], omega=cat["omega"], u=cat["u"], ud=cat["ud"],
                                  mode=cat["mode"], x=cat["x"], xd=cat["xd"], iso_mode=cat["iso"], work=led[0],
                                  viscous=led[1], isolator=led[2], friction=led[3], impact=cat["impact"],
                                  kinetic=cat["kin"], potential=cat["pot"])
