r"""Event-driven reference of a rigid isolated building on a triple friction pendulum, with contents.

A peer written with SciPy from the mechanics below, independently of the compiled kernel and of the
closed forms of :mod:`isoslide.model.tfp` (it reads only the bearing's parameters; the admissibility
check of :class:`~isoslide.model.tfp.TripleFrictionPendulum` is applied to them).  One horizontal
direction, along x.

Input in Pi form (:class:`TFPBuilding`)
----------------------------------------
Time ``tau = t/T_p``, lengths in ``a_p T_p**2``, masses in ``M_b`` (the slab with its rigid
superstructure), forces in ``M_b a_p``.  The bearing: effective radii ``(L1, L2, L3)`` and limits
``(d1, d2, d3)`` divided by ``a_p T_p**2``, friction coefficients ``(mu1, mu2, mu3)`` (constant),
and the gravity ratio ``G = g/a_p``.  The weight on the bearing is ``W = (M_b + m_EC) g``, i.e.
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

Units: as above; energies in ``M_b a_p**2 T_p**2``.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp

from ..model.tfp import TripleFrictionPendulum
from ..pulses import Pulse, accel_at, get_pulse
from ..scene import G_STANDARD, Scene
from ..model.validation import check_range

__all__ = ["ENERGY_NAMES", "TFPBuilding", "TFPRun", "default_horizon", "run_tfp", "single_pendulum_scene"]

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


@dataclass(frozen=True)
class TFPBuilding:
    """A rigid isolated building on a triple friction pendulum, with contents, in Pi form.

    Parameters
    ----------
    L : tuple of float
        Effective radii ``(L1, L2, L3)`` over ``a_p T_p**2`` (OpenSees's order: ``L1`` the inner
        surfaces, ``L2`` surface 1, ``L3`` surface 4), > 0.
    mu : tuple of float
        Friction coefficients ``(mu1, mu2, mu3)`` of the same surfaces (constant), >= 0.
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

    Raises
    ------
    ValueError
        Naming the parameter and its allowed range; a bearing outside the admissible set of
        :mod:`isoslide.model.tfp` (regimes I..V in order).
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
        b = TripleFrictionPendulum(self.L, self.mu, self.d, W=self.W)
        set_(self, "L", b.L)
        set_(self, "mu", b.mu)
        set_(self, "d", b.d)
        set_(self, "_bearing", b)

    @classmethod
    def from_physical(cls, L, mu, d, a_p: float, T_p: float, mass_ratio: float, mu_s: float, mu_k: float,
                      pulse="ricker", g: float = G_STANDARD, c: float = 0.0, polarity: int = 1) -> TFPBuilding:
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
        """
        s = a_p * T_p * T_p
        return cls(L=tuple(x / s for x in L), mu=tuple(mu), d=tuple(x / s for x in d), gravity=g / a_p,
                   pi2=mu_k * g / a_p, pi5=mu_k / mu_s, pi8=mass_ratio, pulse=pulse, damping=c * T_p,
                   polarity=polarity)

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
    mu = building.mu
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
        (the first vertex: 0), and ``energy`` (shape ``(n, 10)``, columns :data:`ENERGY_NAMES`).
    history : dict of ndarray or None
        With ``history=True``: ``tau``, ``x``, ``xd``, ``u``, ``ud``, ``F`` at the integrator's steps.
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


def run_tfp(building: TFPBuilding, rtol: float = 1e-12, atol: float = 1e-15, tau_max: float | None = None,
            history: bool = False, max_events: int = 100_000) -> TFPRun:
    """Solve one building on a triple friction pendulum, event to event (module docstring).

    Parameters
    ----------
    building : TFPBuilding
        The scene in Pi form; the run starts at rest at the pulse's start.
    rtol, atol : float
        Tolerances of ``solve_ivp`` (DOP853); ``atol`` in the state's units.
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
        the bearing's total travel), when two sliding sets with different rates are consistent, or
        when no combination of modes is consistent.
    """
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
        vert.append((t, yy[X], yy[XD], yy[U], yy[UD], F, ub.copy(), st,
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
            hist.append((tt, yy[:4], FF))
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
                "stage": np.array(cols[7], dtype=int), "energy": np.array(cols[8])}
    h = None
    if hist is not None:
        h = {"tau": np.concatenate([a for a, _, _ in hist]) if hist else np.array([tau])}
        yy = np.concatenate([b for _, b, _ in hist], axis=1) if hist else y[:4, None]
        for k, name in enumerate(("x", "xd", "u", "ud")):
            h[name] = yy[k].copy()
        h["F"] = np.concatenate([f for _, _, f in hist]) if hist else np.zeros(1)
    return TFPRun(pi1=float(peak), pi1_residual=float(y[U]), tau_peak=float(tau_peak), x_peak=float(x_peak),
                  peak_stage=int(peak_stage), stages=tuple(stages), settled=settled, tau_end=float(tau),
                  n_events=n_events, ambiguous=ambiguous, nfev=nfev, vertices=vertices, history=h)
