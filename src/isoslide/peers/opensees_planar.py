"""Optional peer: the contents sliding in the plane of the floor, in a 3-D OpenSees model.

The contents (mass ``m``) rest on the floor under two horizontal ground components (and, if the
scene has one, a vertical one); friction is isotropic Coulomb friction, ``|f| <= mu_k N`` with the
friction force opposing the sliding velocity in the plane.

How the planar friction is modelled
-----------------------------------
A 3-D model (``ndm = 3``, ``ndf = 6``) with one ``flatSliderBearing`` element (OpenSees'
``FlatSliderSimple3d``) between the floor node and the contents node, oriented with
``-orient 0 0 1 1 0 0``: its local (axial) ``x`` is the global vertical ``Z``, its two shear
directions are the global ``X`` and ``Y``.

* Friction model ``Coulomb`` with ``mu = mu_k``: the element's yield force is ``mu N``, ``N`` the
  compression of its axial material.  The yield surface is a circle in the plane of the two shear
  forces (the element returns a trial shear force outside it radially onto it), which is the
  isotropic Coulomb law: while the contents slide the friction force has magnitude ``mu N`` and
  points along the plastic (sliding) displacement increment.
* Inside the circle the element is elastic with stiffness ``kInit = K m`` in both shear
  directions, ``K`` the dimensionless *stick stiffness* ``K T_p^2 / m``: a true stick is replaced
  by an elastic spring whose elastic displacement is at most the *stick displacement*
  ``mu N / kInit = Pi2 / K`` (units ``a_p T_p^2``).  As ``K`` grows, the elastic part of the relative
  displacement and the time the spring takes to load up at a stop or a breakaway (a quarter of its
  period ``2 pi / sqrt(K)``) both vanish, so the regularised response tends to the stick-slip one.
  At a fixed, small step the error of ``Pi1`` falls like ``1 / K`` on the planar scenes measured
  (:mod:`isoslide.studies.opensees_planar_convergence`), and like ``1 / sqrt(K)`` where the
  contents reverse along a line without stopping (the spring must swap its force across twice the
  stick displacement; the 1-D case of :mod:`isoslide.peers.opensees`).
* Time error: the element's radial return puts the friction force of a step along that step's
  plastic displacement increment, i.e. along the mean sliding velocity of the step, and Newmark's
  trapezoidal rule averages it with the previous step's: where the sliding direction turns, the
  force lags it by half a step, an error of order ``dt`` (about ``dt`` relative in ``Pi1`` on the
  scenes measured; none along a line).  The default step is therefore tied to the stick period
  (:data:`STEPS_PER_PERIOD` steps per period), and the whole error falls as ``K`` grows
  (:mod:`isoslide.studies.opensees_planar_convergence`).  ``integrator="GeneralizedAlpha"``
  balances the step at its midpoint displacement instead, where the element's force acts along
  the step's mean sliding velocity as it should: the lag and its error of order ``dt`` vanish and
  what is left is the regularisation's ``1 / K``.
* The normal force is the gravity load ``m g`` on the contents node, carried by the element's
  axial material, an elastic spring ``VERTICAL_RATIO kInit`` (stiff: its static compression is
  ``g / (VERTICAL_RATIO K)``), applied by a static analysis before the ground moves so that the
  contents start at rest; with a vertical ground motion (``Pi17 > 0``) the contents' vertical
  inertia changes ``N`` (and the friction) by the factor ``1 + Pi17 p_z(tau)``.  The rotations of
  both nodes are fixed: the element's moment and torsion materials never deform, and its P-Delta
  and V-Delta moments go into the supports, not into the sliding.
* Fixed base (``Pi3 = 0``): the floor node is the ground.  Linear isolator: a base node of mass
  ``M_b`` (vertical and rotations fixed) on the ground through a ``zeroLength`` element with an
  ``Elastic`` material of stiffness ``k_b = (2 pi / Pi3)^2 M_b`` and damping tangent
  ``c_b = 2 Pi4 sqrt(k_b M_b)`` in each of ``X`` and ``Y`` (an isotropic spring and dashpot); the
  contents act back on the base through the element (two-way coupling, ``Pi8 = m / M_b``).

The ground accelerations ``scene.ground(tau)`` (building axes) and ``Pi17 g p_z(tau)`` are sampled
every time step into ``Path`` series and applied by ``UniformExcitation`` patterns in directions 1,
2 and 3, so node displacements are relative to the ground; Newton iterations (retried as
:func:`isoslide.peers.opensees.solve_opensees` does) in each step of the time integrator
(:data:`INTEGRATORS`: average-acceleration Newmark by default).

Units: dimensionless, time ``T_p``, length ``a_p T_p^2``, acceleration ``a_p``, mass ``M_b`` (the
contents' mass is ``Pi8``, at least ``1e-6`` so that its node has one; on a fixed base it only
scales the forces).  Gravity is ``g / a_p`` from ``scene.scale`` when the scene was built from
physical units (then ``mu = mu_k``), else 1 (then ``mu = Pi2``); only ``mu g / a_p = Pi2`` enters
the answer.  Needs ``openseespy`` (``pip install -e .[peers]``).
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass

import numpy as np

from ..scene import Scene
from .opensees import _hold_static_load, _opensees, _step
from .result import PeerResult

__all__ = ["INTEGRATORS", "PlanarModel", "ground_window", "planar_model", "solve_opensees_planar"]

VERTICAL_RATIO = 100.0
"""Axial (vertical) stiffness of the friction element over its shear stiffness ``kInit``."""

STEPS_PER_PERIOD = 50
"""Default time steps per period of the stick spring (the shortest period of the model): the
time error, ``~ dt`` in the plane (see the module docstring), then falls like ``1 / sqrt(K)``."""

MAX_DTAU = 1e-3
"""Largest default time step, units ``T_p``."""

HORIZON = 50.0
"""Longest run after the ground stops: ``HORIZON max(1, Pi3)`` (units ``T_p``)."""

SETTLE = 9.0
"""The run stops when further sliding can add at most ``SETTLE`` stick displacements (see
:func:`solve_opensees_planar`)."""

INTEGRATORS = {"Newmark": ("Newmark", 0.5, 0.25), "GeneralizedAlpha": ("GeneralizedAlpha", 1.0, 0.5)}
"""OpenSees integrators by name: average-acceleration Newmark (``gamma = 1/2``, ``beta = 1/4``),
and the generalized-alpha method with ``alpha_M = 1``, ``alpha_F = 1/2`` (``gamma = 1``,
``beta = 9/16``: second order, unconditionally stable; the internal forces, the damping and the
ground's load at the step's midpoint, the inertia at its end)."""

GROUND, BASE, CONTENTS = 1, 2, 3
"""Node tags: the ground (fixed), the isolated base, the contents."""

SLIDER, ISOLATOR = 1, 2
"""Element tags: the contents' ``flatSliderBearing`` and the isolator's ``zeroLength``."""


@dataclass(frozen=True)
class PlanarModel:
    """The planar OpenSees model of a scene (dimensionless: mass ``M_b``, length ``a_p T_p^2``, time ``T_p``).

    Attributes
    ----------
    m : float
        Contents' mass ``Pi8`` (at least ``1e-6``), units ``M_b``.
    stiffness : float
        Stick stiffness ``K = kInit T_p^2 / m`` (dimensionless).
    gravity : float
        ``g / a_p``.
    mu : float
        Coulomb friction coefficient ``Pi2 / gravity``.
    kb, cb : float
        Isolator's stiffness ``(2 pi / Pi3)^2`` and viscous coefficient ``2 Pi4 2 pi / Pi3`` in each
        horizontal direction (units ``M_b / T_p^2`` and ``M_b / T_p``); 0 on a fixed base.
    fixed : bool
        Fixed base: the floor is the ground.
    vertical : float
        ``Pi17 gravity``: amplitude of the vertical ground acceleration, units ``a_p`` (0: none).
    """

    m: float
    stiffness: float
    gravity: float
    mu: float
    kb: float
    cb: float
    fixed: bool
    vertical: float

    @property
    def k_init(self) -> float:
        """The element's elastic shear stiffness ``K m`` (units ``M_b / T_p^2``)."""
        return self.stiffness * self.m

    @property
    def stick_displacement(self) -> float:
        """Largest elastic displacement of the stick, ``mu g / (a_p K) = Pi2 / K`` (units ``a_p T_p^2``)."""
        return self.mu * self.gravity / self.stiffness

    @property
    def stick_period(self) -> float:
        """Period of the contents on the stick spring (on the base, if isolated), units ``T_p``."""
        w2 = self.stiffness * (1.0 if self.fixed else 1.0 + self.m)
        return 2.0 * math.pi / math.sqrt(w2)


def _positive(name: str, value) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        v = math.nan
    if not (math.isfinite(v) and v > 0.0):
        raise ValueError(f"{name} = {value!r} is out of range; allowed range: 0 < value < inf")
    return v


def _check_scene(scene: Scene) -> None:
    """ValueError naming the first group this peer does not model."""
    for name, allowed, what in (("pi5", 1.0, "1 (Coulomb friction)"), ("pi7", 0.0, "0 (no viscous contact)"),
                                ("pi9", 0.0, "0 (linear isolator)"), ("pi12", 0.0, "0 (rigid superstructure)")):
        value = getattr(scene, name)
        if value != allowed:
            raise ValueError(f"{name} = {value!r} is not modelled by the planar OpenSees peer; allowed: {what}")


def planar_model(scene: Scene, stiffness: float = 1e4) -> PlanarModel:
    """The parameters of the planar OpenSees model of a scene (see :func:`solve_opensees_planar`).

    Parameters
    ----------
    scene : Scene
        Coulomb friction (``Pi5 = 1``, ``Pi7 = 0``), linear isolator (``Pi9 = 0``) or fixed base,
        rigid superstructure (``Pi12 = 0``).
    stiffness : float
        Stick stiffness ``K T_p^2 / m`` (dimensionless), > 0.

    Returns
    -------
    PlanarModel
    """
    _check_scene(scene)
    K = _positive("stiffness", stiffness)
    gravity = scene.scale.g / scene.scale.a_p if scene.scale is not None else 1.0
    fixed = scene.pi3 == 0.0
    kb = cb = 0.0
    if not fixed:
        w = 2.0 * math.pi / scene.pi3
        kb, cb = w * w, 2.0 * scene.pi4 * w
    return PlanarModel(m=max(scene.pi8, 1e-6), stiffness=K, gravity=gravity, mu=scene.pi2 / gravity,
                       kb=kb, cb=cb, fixed=fixed, vertical=scene.pi17 * gravity if scene.vertical else 0.0)


def ground_window(scene: Scene) -> tuple:
    """``(tau_start, tau_end)``: when any ground component starts and when the last one stops (units ``T_p``)."""
    p = scene.pulse
    lo, hi = [p.tau_start], [p.tau_end]
    if scene.bidirectional:
        q = scene.pulse_y
        lo.append(scene.pi16 + scene.pi15 * q.tau_start)
        hi.append(scene.pi16 + scene.pi15 * q.tau_end)
    if scene.vertical:
        lo.append(scene.pulse_z.tau_start)
        hi.append(scene.pulse_z.tau_end)
    return float(min(lo)), float(max(hi))


def _build(ops, M: PlanarModel) -> int:
    """Nodes, materials, the friction element and the static gravity load; returns the floor's node."""
    ops.wipe()
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    ops.node(GROUND, 0.0, 0.0, 0.0)
    ops.fix(GROUND, 1, 1, 1, 1, 1, 1)
    floor = GROUND
    if not M.fixed:
        floor = BASE
        ops.node(BASE, 0.0, 0.0, 0.0)
        ops.fix(BASE, 0, 0, 1, 1, 1, 1)
        ops.mass(BASE, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0)
        ops.uniaxialMaterial("Elastic", 10, M.kb, M.cb)           # k_b x + c_b x' in X and in Y
        ops.element("zeroLength", ISOLATOR, GROUND, BASE, "-mat", 10, 10, "-dir", 1, 2)
    ops.node(CONTENTS, 0.0, 0.0, 0.0)
    ops.fix(CONTENTS, 0, 0, 0, 1, 1, 1)
    ops.mass(CONTENTS, M.m, M.m, M.m, 0.0, 0.0, 0.0)
    ops.frictionModel("Coulomb", 1, M.mu)
    ops.uniaxialMaterial("Elastic", 1, VERTICAL_RATIO * M.k_init)  # axial: carries N
    ops.uniaxialMaterial("Elastic", 2, M.k_init)                   # torsion and moments: rotations fixed
    ops.element("flatSliderBearing", SLIDER, floor, CONTENTS, 1, M.k_init, "-P", 1, "-T", 2, "-My", 2,
                "-Mz", 2, "-orient", 0.0, 0.0, 1.0, 1.0, 0.0, 0.0)
    ops.timeSeries("Constant", 1)
    ops.pattern("Plain", 1, 1)
    ops.load(CONTENTS, 0.0, 0.0, -M.m * M.gravity, 0.0, 0.0, 0.0)
    _hold_static_load(ops, "the planar model's gravity")
    return floor


def _settle_level(M: PlanarModel, x, xd, vc) -> float:
    """Bound on the floor's acceleration while the contents stick, once the ground is still (units ``a_p``).

    With the ground at rest the energy ``E = k_b |x|^2 / 2 + |x'|^2 / 2 + m |v_c|^2 / 2`` (``x`` the
    base's displacement, ``v_c`` the contents' velocity, relative to the ground) can only fall, and
    ``k_b |x| + c_b |x'| <= sqrt(2 E (k_b + c_b^2))``: the floor's acceleration with the contents
    stuck is at most that over ``1 + m``, and while they slide their relative speed falls at
    ``Pi2 - (that)`` or faster.  0 on a fixed base.
    """
    if M.fixed:
        return 0.0
    e2 = M.kb * (x[0] ** 2 + x[1] ** 2) + xd[0] ** 2 + xd[1] ** 2 + M.m * (vc[0] ** 2 + vc[1] ** 2)
    return math.sqrt(e2 * (M.kb + M.cb * M.cb)) / (1.0 + M.m)


def solve_opensees_planar(scene: Scene, stiffness: float = 1e4, dt: float | None = None,
                          t_end: float | None = None, integrator: str = "Newmark") -> PeerResult:
    """Peak planar sliding of the contents with OpenSees (``flatSliderBearing``, Newmark).

    See the module docstring for the model.  The contents start at rest (relative to the floor,
    with the floor at rest) when the first ground component starts.

    Parameters
    ----------
    scene : Scene
        Coulomb friction (``Pi5 = 1``, ``Pi7 = 0``), a fixed base (``Pi3 = 0``) or a linear isolator
        (``Pi9 = 0``, ``Pi3 = T_b / T_p``, ``Pi4 = xi_b``, ``Pi8 = m / M_b`` coupling the contents
        back), rigid superstructure (``Pi12 = 0``); any horizontal excitation (``pulse``,
        ``pulse_y``, ``Pi14 .. Pi16``, ``angle``) and optionally a vertical one (``Pi17``,
        ``pulse_z``).  Other scenes raise a ValueError naming the group.
    stiffness : float
        Stick stiffness ``K T_p^2 / m`` (dimensionless), > 0: the element's ``kInit = K m``, its
        stick displacement ``Pi2 / K`` (units ``a_p T_p^2``).
    dt : float or None
        Time step, units ``T_p``; default ``min(1e-3, T_K / 50)`` (:data:`MAX_DTAU`,
        :data:`STEPS_PER_PERIOD`), ``T_K = 2 pi / sqrt(K (1 + m))`` the period of the contents on
        the stick spring (``2 pi / sqrt(K)`` on a fixed base): the step shrinks with the stick's
        period, so the time error (order ``dt`` where the sliding direction turns) falls with
        the stick error as ``K`` grows.
    t_end : float or None
        End time, units ``T_p``: the run goes exactly there.  None: the run stops once the ground
        is still, the floor's motion can no longer make the contents slide (its acceleration bound
        of :func:`_settle_level` is at most ``Pi2 / 2``) and the contents' relative speed ``s``
        can add at most ``s^2 / Pi2 <= SETTLE Pi2 / K`` to the sliding; at the latest
        ``HORIZON max(1, Pi3)`` after the ground stops.
    integrator : {"Newmark", "GeneralizedAlpha"}
        Time integrator (:data:`INTEGRATORS`); ``"GeneralizedAlpha"`` has no time error of order
        ``dt`` where the sliding direction turns (see the module docstring).

    Returns
    -------
    PeerResult
        ``method = "opensees"``, ``pi1`` the peak of ``|u|`` (Euclidean norm of the contents'
        displacement relative to the floor, units ``a_p T_p^2``), ``peak_angle = atan2(u_y, u_x)``
        at the peak (building axes, radians; nan when the peak is 0), ``tau_peak`` (units ``T_p``),
        ``stiffness = K``, ``n_steps`` time steps run, ``integrator`` as given, ``settled``
        True when the run stopped by the settling test, ``tau_end`` its last time;
        ``pi1_residual`` is nan (the final displacement is a vector).
    """
    if integrator not in INTEGRATORS:
        raise ValueError(f"integrator = {integrator!r} is invalid; allowed: {', '.join(map(repr, INTEGRATORS))}")
    M = planar_model(scene, stiffness)
    dtau = min(MAX_DTAU, M.stick_period / STEPS_PER_PERIOD) if dt is None else _positive("dt", dt)
    tau0, tau_g = ground_window(scene)
    if t_end is None:
        tau_max, adaptive = tau_g + HORIZON * max(1.0, scene.pi3), True
    else:
        tau_max, adaptive = float(t_end), False
        if not (math.isfinite(tau_max) and tau_max > tau0):
            raise ValueError(f"t_end = {t_end!r} is out of range; allowed range: {tau0!r} < value < inf "
                             "(after the ground starts)")
    n_max = max(1, int(math.ceil((tau_max - tau0) / dtau - 1e-9)))
    n_ground = min(n_max, int(math.ceil((tau_g - tau0) / dtau)) + 1)
    tt = tau0 + dtau * np.arange(n_ground + 1)
    gx, gy = scene.ground(tt)
    ops = _opensees()
    floor = _build(ops, M)
    ops.logFile(os.devnull, "-noEcho")         # the retries of _step are expected; a failure raises
    series = [(1, gx), (2, gy)]
    if M.vertical > 0.0:
        series.append((3, M.vertical * np.asarray(scene.pulse_z.accel(tt), dtype=float)))
    for direction, values in series:           # Path series are 0 after their last value
        ops.timeSeries("Path", 10 + direction, "-dt", dtau, "-values", *np.asarray(values, dtype=float).tolist())
        ops.pattern("UniformExcitation", 10 + direction, direction, "-accel", 10 + direction)
    ops.constraints("Plain")
    ops.numberer("Plain")
    ops.system("FullGeneral")
    ops.test("NormDispIncr", 1e-14, 50)
    ops.algorithm("Newton")
    ops.integrator(*INTEGRATORS[integrator])
    ops.analysis("Transient")
    umax, angle, tau_peak = 0.0, math.nan, tau0
    zero = (0.0, 0.0)
    limit = SETTLE * M.stick_displacement * scene.pi2
    settled = False
    n = 0
    while n < n_max:
        if not _step(ops, dtau):
            ops.wipe()
            raise RuntimeError(f"OpenSees analysis failed at tau = {tau0 + n * dtau:.6g} (dt = {dtau!r})")
        n += 1
        c = ops.nodeDisp(CONTENTS)
        f = ops.nodeDisp(floor) if floor != GROUND else zero
        ux, uy = c[0] - f[0], c[1] - f[1]
        r = math.hypot(ux, uy)
        tau = tau0 + n * dtau
        if r > umax:
            umax, angle, tau_peak = r, math.atan2(uy, ux), tau
        if adaptive and tau >= tau_g:
            vc = ops.nodeVel(CONTENTS)
            vf = ops.nodeVel(floor) if floor != GROUND else zero
            s2 = (vc[0] - vf[0]) ** 2 + (vc[1] - vf[1]) ** 2
            if _settle_level(M, f, vf, vc) <= 0.5 * scene.pi2 and s2 <= limit:
                settled = True
                break
    ops.wipe()
    return PeerResult(method="opensees", pi1=umax, tau_peak=float(tau_peak), settled=settled,
                      tau_end=float(tau0 + n * dtau), n_steps=n, stiffness=M.stiffness, integrator=integrator,
                      peak_angle=angle)
