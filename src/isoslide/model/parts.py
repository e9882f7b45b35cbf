"""The parts of an isolated building, each reading only the groups it needs.

A building is an :class:`Isolator` on the ground, a :class:`Superstructure` on the isolated slab
and :class:`Contents` on one of its floors; :func:`building_of` composes them from a scene's
Pi-groups (:class:`isoslide.Scene`, the Pi-form front door) and the engine assembles them into
arrays (:func:`isoslide.engine.building.parameters`).  Units are the model's: time ``T_p``,
lengths ``a_p T_p^2``, masses ``M_b`` (the isolated mass, contents excluded).

Which groups each part reads
----------------------------
=================  ==========================================================================
part               groups
=================  ==========================================================================
fixed base         none (``Pi3 = 0``: the slab moves with the ground)
linear isolator    ``Pi3 = T_b/T_p``, ``Pi4 = xi_b``
bilinear bearing   ``Pi3``, ``Pi4``, ``Pi9 = Q/(M_b a_p)``, ``Pi10 = D_y/(a_p T_p^2)``
sliding bearing    ``Pi3``, ``Pi4``, ``Pi9`` (true stick: no yield displacement), and for friction
                   that rises with speed ``Pi22 = mu_slow/mu_fast``, ``Pi23 = a a_p T_p``
triple pendulum    ``Pi3``, ``Pi4``, ``Pi9`` and ``Pi24 .. Pi30`` (a sliding bearing with ``Pi24 > 0``)
rigid              none (``Pi12 = 0``)
shear building     ``Pi11 = m_st/M_b``, ``Pi12 = T_s/T_p``, ``Pi13 = xi_s``, ``storeys``, the
                   floors' masses and storeys' stiffnesses (uniform by default)
contents           ``Pi2 = mu_k g/a_p``, ``Pi5 = mu_k/mu_s``, ``Pi6 = beta a_p T_p``,
                   ``Pi7 = gamma g T_p``, ``Pi8 = m_EC/M_b``, the floor
=================  ==========================================================================
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property, lru_cache

import numpy as np

from . import shear_building

ISOLATOR_KINDS = ("fixed", "linear", "bilinear", "sliding", "tfp")
"""Kinds of :class:`Isolator`."""


@dataclass(frozen=True)
class Isolator:
    """The isolation system between the ground and the slab.

    Attributes
    ----------
    kind : {"fixed", "linear", "bilinear", "sliding", "tfp"}
        A fixed base; the paper's linear spring and dashpot; a bilinear (lead-rubber) bearing, an
        elastic-perfectly-plastic spring in parallel; a sliding bearing (friction pendulum) that
        holds the slab (true stick) while the force needed is within its strength; a triple
        friction pendulum, four such surfaces in series with rigid restrainers.
    period : float
        ``Pi3 = T_b / T_p`` with the post-yield (or linear) stiffness ``k_d`` (a triple pendulum's:
        its outer surfaces sliding together, ``M_b g/(L2 + L3)``); 0 for a fixed base.
    damping : float
        ``Pi4 = xi_b``.
    strength : float
        ``Pi9 = Q / (M_b a_p)`` of a bilinear or sliding bearing (0 otherwise).
    yield_displacement : float
        ``Pi10 = D_y / (a_p T_p^2)`` of a bilinear bearing (0 otherwise).
    slow : float
        ``Pi22 = mu_slow / mu_fast`` of a sliding bearing whose friction rises with its speed
        (1 otherwise).
    rate : float
        ``Pi23 = a a_p T_p`` of that bearing (0: constant friction ``strength`` at every speed).
    shape : tuple
        A triple pendulum's ``(Pi24, Pi25, Pi26, Pi27, Pi28, Pi29, Pi30)``: radius ratios
        ``L1/(L2 + L3)``, ``L2/(L2 + L3)``, friction ratios ``mu1/mu2``, ``mu3/mu2`` (``strength`` is
        ``mu2``'s) and limits ``d1, d2, d3`` (units ``a_p T_p^2``); empty for any other kind.
    laws : tuple
        A triple pendulum whose friction rises with speed: ``((slow1, slow2, slow3), (rate1, rate2,
        rate3))``, each surface group's ``mu_slow/mu_fast`` and ``a a_p T_p``
        (:attr:`isoslide.Scene.tfp_speed`); empty for constant friction or any other kind.

    A sliding bearing's friction level (units ``M_b a_p``, before the normal-force factor) at the
    slab's speed ``v`` (units ``a_p T_p``) is ``strength (1 - (1 - slow) exp(-rate v))``
    (:meth:`level`); it sticks while the force that holds the slab is within :attr:`breakaway`.
    :func:`building_of` gives constant friction as ``slow = 1, rate = 0``.
    """

    kind: str
    period: float = 0.0
    damping: float = 0.0
    strength: float = 0.0
    yield_displacement: float = 0.0
    slow: float = 1.0
    rate: float = 0.0
    shape: tuple = ()
    laws: tuple = ()

    def __post_init__(self):
        if self.kind not in ISOLATOR_KINDS:
            raise ValueError(f"kind = {self.kind!r} is invalid; allowed: {ISOLATOR_KINDS}")

    def surfaces(self) -> tuple:
        """A triple pendulum's four surfaces, bottom to top: stiffnesses, strengths and limits.

        ``k_i = M_b g/L_i = k_d (L2 + L3)/L_i`` (units ``M_b/T_p^2``), ``mu_i M_b g`` (units ``M_b
        a_p``) and ``d_i`` (units ``a_p T_p^2``) of surface 1 (``L2, mu2, d2``), the inner surfaces 2
        and 3 (``L1, mu1, d1``) and surface 4 (``L3, mu3, d3``).
        """
        r1, r2, f1, f3, d1, d2, d3 = self.shape
        kd, q = self.stiffness, self.strength
        return ((kd / r2, kd / r1, kd / r1, kd / (1.0 - r2)), (q, q * f1, q * f1, q * f3), (d2, d1, d1, d3))

    def surface_laws(self) -> tuple:
        """A triple pendulum's slow strengths (units ``M_b a_p``) and rates, bottom to top (:meth:`surfaces`' order).

        Only for one whose friction rises with speed (:attr:`laws`).
        """
        (s1, s2, s3), (a1, a2, a3) = self.laws
        q = self.surfaces()[1]
        return (q[0] * s2, q[1] * s1, q[2] * s1, q[3] * s3), (a2, a1, a1, a3)

    @property
    def speed_dependent(self) -> bool:
        """True for a sliding bearing (or triple pendulum) whose friction rises with its speed (``rate > 0``, ``slow < 1``)."""
        if self.kind == "tfp":
            return bool(self.laws)
        return self.rate > 0.0 and self.slow < 1.0

    @property
    def breakaway(self) -> float:
        """Force that first moves the slab from rest (units ``M_b a_p``).

        ``Pi9 Pi22`` of a sliding bearing, ``mu1``'s strength ``Pi9 Pi26`` of a triple pendulum (its
        inner surfaces; their slow strength when its friction rises with speed), the strength of any
        other kind.
        """
        if self.kind == "tfp":
            return self.surface_laws()[0][1] if self.laws else self.strength * self.shape[2]
        return self.strength * self.slow

    def level(self, v: float) -> float:
        """Friction level of a sliding bearing at the speed ``|v|`` (units ``M_b a_p``)."""
        if not self.speed_dependent:
            return self.strength
        return self.strength * (1.0 - (1.0 - self.slow) * math.exp(-self.rate * abs(v)))

    @property
    def omega(self) -> float:
        """Circular frequency ``2 pi / Pi3`` of the post-yield (or linear) stiffness (0 fixed)."""
        return 2.0 * math.pi / self.period if self.kind != "fixed" else 0.0

    @property
    def stiffness(self) -> float:
        """Post-yield (or linear) stiffness ``k_d = (2 pi / Pi3)^2`` (units ``M_b / T_p^2``; 0 fixed)."""
        w = self.omega
        return w * w

    @property
    def viscous(self) -> float:
        """Viscous coefficient ``c_b = 2 Pi4 (2 pi / Pi3)`` (units ``M_b / T_p``; 0 fixed)."""
        return 2.0 * self.damping * self.omega

    @property
    def elastic_stiffness(self) -> float:
        """Stiffness ``k_e = Q / D_y`` of a bilinear bearing's elastic-plastic spring (0 otherwise)."""
        return self.strength / self.yield_displacement if self.kind == "bilinear" else 0.0

    @property
    def shortest_period(self) -> float:
        """Shortest period of the isolator; 0 for a fixed base.

        The bilinear bearing's elastic one, a triple pendulum's stiffest regime.
        """
        if self.kind == "tfp":
            k = self.surfaces()[0]
            pairs = (_series(k[1], k[2]), _series(k[0], k[2]), _series(k[0], k[3]), _series(k[1], k[3]))
            return self.period * math.sqrt(self.stiffness / max(pairs))
        if self.kind != "bilinear":
            return self.period
        kd = self.stiffness
        return self.period * math.sqrt(kd / (kd + self.elastic_stiffness))


def _series(a: float, b: float) -> float:
    """Stiffness of two springs in series."""
    return a * b / (a + b)


@dataclass(frozen=True)
class Superstructure:
    """What stands on the slab: rigid, or a shear building of ``storeys`` floors.

    Attributes
    ----------
    mass : float
        ``Pi11 = m_st / M_b`` of a shear building (0 when rigid: the whole ``M_b`` is the slab's).
    period : float
        ``Pi12 = T_s / T_p``, the fixed-base fundamental period (0 when rigid).
    damping : float
        ``Pi13 = xi_s``, the damping ratio of every fixed-base mode.
    storeys : int
        Floors above the slab.
    floor_masses, storey_stiffnesses : tuple of float or None
        Shares of ``m_st`` per floor and relative storey stiffnesses, bottom to top; None: uniform.
    """

    mass: float = 0.0
    period: float = 0.0
    damping: float = 0.0
    storeys: int = 1
    floor_masses: tuple | None = None
    storey_stiffnesses: tuple | None = None

    @property
    def flexible(self) -> bool:
        """True for a shear building (``Pi12 > 0``)."""
        return self.period > 0.0

    def matrices(self) -> tuple:
        """Floor masses ``(N,)``, fixed-base stiffness and damping matrices ``(N, N)``.

        Units ``M_b``, ``M_b/T_p^2`` and ``M_b/T_p``.  Storey ``j`` joins floor ``j - 1`` (0 the slab) and floor ``j`` with the stiffness
        ``kappa r_j``, ``kappa`` chosen so that the fixed-base fundamental period is ``Pi12``; the
        damping is classical with ratio ``Pi13`` in every fixed-base mode
        (:mod:`isoslide.model.shear_building`).  One floor: ``k_s = m_st (2 pi/Pi12)^2``,
        ``c_s = 2 Pi13 (2 pi/Pi12) m_st`` exactly.  Derived once per superstructure (the arrays
        are shared: do not change them).
        """
        return self._modes[:3]

    @property
    def shortest_period(self) -> float:
        """Shortest fixed-base period (``Pi12`` for one floor; 0 when rigid)."""
        if not self.flexible or self.storeys == 1:
            return self.period
        return self._modes[3]

    @cached_property
    def _modes(self) -> tuple:
        """``(masses, Ks, Cs, shortest period)`` of :meth:`matrices` and :attr:`shortest_period`."""
        return _shear_modes(self)


def forget_shared() -> None:
    """Forget the superstructures' matrices kept for the scenes that share them."""
    _shear_modes.cache_clear()


@lru_cache(maxsize=256)
def _shear_modes(sup: Superstructure) -> tuple:
    """``Superstructure._modes``, kept per superstructure: a study's scenes share theirs.

    The stiffness shape's modes are those of ``Ks`` (a scalar multiple of it) with frequencies scaled
    so that the first is ``2 pi/Pi12``.  The arrays are read-only.
    """
    n = sup.storeys
    ws = 2.0 * math.pi / sup.period
    if n == 1:
        out = (np.array([sup.mass]), np.array([[sup.mass * ws * ws]]),
               np.array([[2.0 * sup.damping * ws * sup.mass]]), sup.period)
    else:
        w = np.full(n, 1.0 / n) if sup.floor_masses is None else np.asarray(sup.floor_masses)
        r = np.ones(n) if sup.storey_stiffnesses is None else np.asarray(sup.storey_stiffnesses)
        masses = sup.mass * w
        shape = shear_building.stiffness_matrix(r)
        omega, phi = shear_building.fixed_base_modes(masses, shape)
        scale = ws / omega[0]
        omega = omega * scale
        out = (masses, scale * scale * shape, shear_building.classical_damping(masses, omega, phi, sup.damping),
               2.0 * math.pi / omega[-1])
    for a in out[:3]:
        a.flags.writeable = False
    return out


@dataclass(frozen=True)
class Contents:
    """The sliding contents on one floor, with the Stribeck law and true stick.

    Attributes
    ----------
    floor : int
        0 the slab, ``storeys`` the roof (the slab whenever the superstructure is rigid).
    mass : float
        ``Pi8 = m_EC / M_b``.
    kinetic, static : float
        Friction levels ``Pi2 = mu_k g / a_p`` and ``Pi2 / Pi5 = mu_s g / a_p``.
    sharpness, viscous : float
        ``Pi6 = beta a_p T_p`` and ``Pi7 = gamma g T_p``.
    aspect : float
        ``Pi18 = b/h = tan(alpha)`` of a block the rocking model integrates (0: contents that only slide;
        see :func:`building_of`).
    frequency : float
        ``Pi19 = p T_p`` of a block that can rock.
    restitution : float
        Its coefficient of restitution ``e`` at impact.
    gravity : float
        ``g / a_p = 1/(Pi18 Pi21)`` (0 without a rocking block).
    """

    floor: int
    mass: float
    kinetic: float
    static: float
    sharpness: float = 0.0
    viscous: float = 0.0
    aspect: float = 0.0
    frequency: float = 0.0
    restitution: float = 0.0
    gravity: float = 0.0

    @property
    def rocks(self) -> bool:
        """True for a block the rocking model integrates (:func:`building_of`)."""
        return self.aspect > 0.0

    @property
    def tips(self) -> bool:
        """True for a block that tips before it can slide, ``mu_s > tan(alpha)`` (:attr:`isoslide.Scene.tips`)."""
        return self.rocks and self.static > self.gravity * self.aspect

    @property
    def radius(self) -> float:
        """``R = 3 g / (4 p^2)`` of a block that can rock, units ``a_p T_p^2`` (0 without one)."""
        return 0.75 * self.gravity / self.frequency**2 if self.aspect > 0.0 else 0.0

    @property
    def rate_independent(self) -> bool:
        """True when the friction does not depend on speed (plain Coulomb at the static level)."""
        return self.viscous == 0.0 and (self.static == self.kinetic or self.sharpness == 0.0)


@dataclass(frozen=True)
class Building:
    """An isolated building with its contents: the parts the engine assembles."""

    isolator: Isolator
    superstructure: Superstructure
    contents: Contents

    @property
    def shortest_period(self) -> float:
        """Shortest period the engine follows (isolator and superstructure; 0 when neither moves)."""
        periods = [p for p in (self.isolator.shortest_period, self.superstructure.shortest_period) if p > 0.0]
        return min(periods) if periods else 0.0


def building_of(scene, rocking: bool | None = None) -> Building:
    """The parts of a scene (:class:`isoslide.Scene`), each reading only the groups it needs.

    The isolator is fixed for ``Pi3 = 0`` and otherwise the scene's kind (``scene.isolator``:
    linear, bilinear or sliding); the superstructure is a shear building for ``Pi12 > 0``; the
    contents sit on the scene's floor of a shear building, on the slab of a rigid one.  They are a
    block that can rock when ``rocking`` (default: when the scene's block tips before it can slide,
    :attr:`isoslide.Scene.tips`; ``True`` keeps the rocking model for any block, to check that the
    sliding model is its answer where it cannot tip).  The parts are derived once per scene and
    model (a scene is immutable) and kept with it.
    """
    rocking = bool((scene.tips if rocking is None else rocking) and scene.rocks)
    built = scene.__dict__.setdefault("_parts", {})
    if rocking not in built:
        built[rocking] = _assembled(scene, rocking)
    return built[rocking]


def _assembled(scene, rocking: bool) -> Building:
    """:func:`building_of` derived anew (``rocking``: a block that can rock, given by the scene)."""
    kind = "fixed" if scene.pi3 == 0.0 else scene.isolator
    groups = {"fixed": {}, "linear": dict(period=scene.pi3, damping=scene.pi4),
              "bilinear": dict(period=scene.pi3, damping=scene.pi4, strength=scene.pi9,
                               yield_displacement=scene.pi10),
              "sliding": _sliding(scene), "tfp": {}}[kind]
    if kind == "tfp":
        groups = {**_sliding(scene), "shape": tuple(getattr(scene, f"pi{i}") for i in range(24, 31)),
                  "laws": scene.tfp_speed or ()}
    iso = Isolator(kind, **groups)
    flexible = scene.pi12 > 0.0
    sup = Superstructure(scene.pi11, scene.pi12, scene.pi13, scene.storeys, scene.floor_masses,
                         scene.storey_stiffnesses) if flexible else Superstructure()
    block = {}
    if rocking:
        block = dict(aspect=scene.pi18, frequency=scene.pi19, restitution=scene.restitution,
                     gravity=1.0 / (scene.pi18 * scene.pi21))
    contents = Contents(floor=scene.floor_index if flexible else 0, mass=scene.pi8, kinetic=scene.pi2,
                        static=scene.pi2 / scene.pi5, sharpness=scene.pi6, viscous=scene.pi7, **block)
    return Building(iso, sup, contents)


def _sliding(scene) -> dict:
    """The groups of a sliding bearing; a friction that does not depend on speed is stored as constant.

    ``Pi23 = 0`` is the constant friction ``Pi9 Pi22`` and ``Pi22 = 1`` the constant ``Pi9``, both
    as ``slow = 1, rate = 0``: the same arrays, hence the same answer to the bit, as a scene given
    that constant strength.
    """
    groups = dict(period=scene.pi3, damping=scene.pi4, strength=scene.pi9)
    if scene.pi23 == 0.0 or scene.pi22 == 1.0:
        groups["strength"] = scene.pi9 * scene.pi22
        return groups
    return {**groups, "slow": scene.pi22, "rate": scene.pi23}
