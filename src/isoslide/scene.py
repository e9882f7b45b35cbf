"""One scene: a point in Pi-space with its excitation, validated.

The dimensionless groups, their definitions and valid ranges are those of
:mod:`isoslide.groups` (repeating variables a_p, T_p, M_b).  T_b = 2 pi
sqrt(M_b / k_b) and xi_b = c_b / (2 sqrt(k_b M_b)) use the isolated mass M_b
alone (the block is excluded), as in the paper.

Note on Pi7
-----------
The paper prints ``Pi7 = gamma a_p T_p``.  With the Stribeck law of Eq. 1
taken literally, the viscous term adds ``gamma |v| m_EC g`` to the friction
force; in units of ``m_EC a_p`` and with ``v = a_p T_p v'`` it is
``(gamma g T_p) |v'|``.  The group that governs the response is therefore
``gamma g T_p``; the printed one only agrees when ``a_p = g``.  isoslide uses
``Pi7 = gamma g T_p`` and :func:`paper_groups` reports the printed one, so the
similarity report can show it failing.  ``Pi6 = beta a_p T_p`` holds as printed.

Note on Pi6 = 0
---------------
Taken literally, ``beta = 0`` makes ``sech(beta v) = 1``: the friction is
``mu_s`` at every speed, i.e. Coulomb friction with coefficient ``mu_s =
mu_k / Pi5``.  With the default ``Pi5 = 1`` this is Coulomb friction with
``mu_k``, the paper's Coulomb case.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .pulses import Pulse, get_pulse
from .groups import INPUT_NAMES, INPUTS, ROCKING_NAMES, TFP_NAMES, TFP_SPEED, TFP_SPEED_NAMES, group
from .model.shear_building import fundamental_period
from .groups import defaults as _group_defaults
from .model.rocking import housner_restitution
from .model.tfp import TripleFrictionPendulum, _triple
from .model.validation import check_range

_DEFAULTS = _group_defaults()

G_STANDARD = 9.80665
"""Standard gravity, m/s^2."""

PI_RANGES = {g.name: (g.lo, g.hi, g.lo_in, g.hi_in) for g in INPUTS}
"""Valid range of each input group: (low, high, low inclusive, high inclusive), from the registry."""

FLOORS = ("base", "roof")
"""Named floors the contents can sit on: the isolated slab (floor ``0``), or the superstructure's top
floor (floor ``storeys``); the floors between are given by their number."""

ANGLE_LIMIT = 8.0 * math.pi
"""Largest ``|angle|`` (radians) a scene accepts."""

MAX_STOREYS = 64
"""Most storeys a superstructure may have."""

ISOLATORS = ("linear", "bilinear", "sliding", "tfp")
"""Isolator kinds (:attr:`Scene.isolator`): the paper's linear spring-dashpot (``Pi9 = 0``), a
bilinear bearing (``Pi9 > 0, Pi10 > 0``), a sliding bearing with true stick (``Pi9 > 0, Pi10 = 0``)
and a triple friction pendulum (such a sliding bearing with ``Pi24 > 0``)."""


@dataclass(frozen=True)
class PhysicalScale:
    """Scales of a scene built from physical units (SI).

    Attributes
    ----------
    a_p : float
        Pulse acceleration amplitude, m/s^2.
    T_p : float
        Pulse period, s.
    M_b : float
        Isolated mass, kg.
    g : float
        Gravitational acceleration, m/s^2.
    """

    a_p: float
    T_p: float
    M_b: float
    g: float = G_STANDARD

    @property
    def length(self) -> float:
        """Characteristic length ``L_p = a_p T_p**2``, m."""
        return self.a_p * self.T_p**2


@dataclass(frozen=True)
class Scene:
    """A validated point of Pi-space with its excitation.

    Parameters
    ----------
    pi2 : float
        ``mu_k g / a_p``, kinetic friction over pulse amplitude, > 0.
    pi3 : float
        ``T_b / T_p``; 0 means a fixed base (floor = ground).
    pi4 : float
        ``xi_b``, isolation damping ratio (>= 1 is over-damped and valid).
    pi5 : float, default 1
        ``mu_k / mu_s`` in (0, 1]; 1 is Coulomb friction.
    pi6 : float, default 0
        ``beta a_p T_p``, Stribeck transition sharpness.
    pi7 : float, default 0
        ``gamma g T_p``, viscous contact group (see module note).
    pi8 : float, default 1e-5
        ``m_EC / M_b``, contents-to-isolated mass ratio.
    pulse : str or Pulse, default "ricker"
        Excitation shape; see :mod:`isoslide.pulses`.
    pi9 : float, default 0
        ``Q / (M_b a_p)``, strength of a hysteretic isolator; 0 is the paper's linear isolator.
    pi10 : float, default 0
        ``D_y / (a_p T_p^2)``, yield displacement of a bilinear bearing; 0 (with ``pi9 > 0``) is a
        sliding bearing (friction pendulum) with true stick.
    pi11 : float, default 0
        ``m_st / M_b``, superstructure mass fraction; read only when ``pi12 > 0``, where it must
        lie in (0, 1).
    pi12 : float, default 0
        ``T_s / T_p``, superstructure period over pulse period; 0 is a rigid superstructure.
    pi13 : float, default 0
        ``xi_s``, superstructure damping ratio.
    floor : {"base", "roof"} or int, default "base"
        Floor carrying the contents: ``"base"`` (or ``0``) the isolated slab, ``"roof"`` (or
        ``storeys``) the top floor, an integer ``1 .. storeys - 1`` a floor between (every floor is
        the slab's when the superstructure is rigid).  Stored as ``"base"``, ``"roof"`` or the
        floor's number in between.
    storeys : int, default 1
        Number of floors of the superstructure above the slab (``1 <= storeys <= 64``); read only
        with a flexible superstructure (``Pi12 > 0``).  A uniform shear building: each floor of mass
        ``Pi11 M_b / storeys``, equal storey stiffnesses chosen so that the fixed-base fundamental
        period (slab held) is ``T_s``, classical damping with ratio ``Pi13`` in every fixed-base
        mode.  ``storeys = 1`` is a single superstructure mass.
    floor_masses : tuple of float or None
        Non-uniform building: the floors' shares of the superstructure's mass, bottom to top
        (``storeys`` positive values, normalised to sum 1); ``None`` is uniform.
    storey_stiffnesses : tuple of float or None
        Non-uniform building: the storeys' relative stiffnesses, bottom to top (``storeys``
        positive values, normalised to 1 for the bottom storey; their scale is set by ``T_s``);
        ``None`` is uniform.
    pulse_y : str or Pulse or record, optional
        Shape of the second horizontal ground component (``None``: none).  In the scene's
        excitation axes ``a_gx(tau) = a_p p(tau)`` and ``a_gy(tau) = Pi14 a_p p_y((tau - Pi16) /
        Pi15)``.  With a record as ``pulse`` and another as ``pulse_y`` (a recorded pair) both
        run as recorded on the record's time axis with one ``a_p``, ``T_p`` (the ``pulse``
        record's fitted pulse's): keep ``Pi14 = Pi15 = 1``, ``Pi16 = 0``.
    pi14, pi15, pi16 : float, default 1, 1, 0
        ``a_py / a_p``, ``T_py / T_p`` and ``t_y / T_p`` of the second horizontal component (see
        :mod:`isoslide.groups`); read only with a ``pulse_y``.
    pi17 : float, default 0
        ``a_pz / g``: vertical ground acceleration ``a_gz = Pi17 g p_z(tau)``; read only with a
        ``pulse_z``.
    pulse_z : str or Pulse or record, optional
        Shape of the vertical ground acceleration, on the main pulse's time axis.
    pi22 : float, default 1
        ``mu_slow / mu_fast`` of a sliding bearing whose friction depends on its speed,
        ``mu(v) = mu_fast - (mu_fast - mu_slow) exp(-a |v|)`` (Constantinou, Mokha and Reinhorn
        1990), ``Pi9 = mu_fast g / a_p``: the bearing sticks while the force that holds it is within
        ``Pi9 Pi22`` (times the normal-force factor) and slides with ``Pi9 (1 - (1 - Pi22)
        exp(-Pi23 |x'|))``; 1 is constant friction.  Read only with a sliding bearing.
    pi23 : float, default 0
        ``a a_p T_p``, the rate of that law (``a`` in s/m); 0 is constant friction ``Pi9 Pi22``.
        Read only with a sliding bearing.
    pi24 .. pi30 : float
        A triple friction pendulum (``Pi24 > 0``; 0: a single one): ``Pi24 = L1/(L2 + L3)``,
        ``Pi25 = L2/(L2 + L3)``, ``Pi26 = mu1/mu2``, ``Pi27 = mu3/mu2`` and the limits
        ``Pi28, Pi29, Pi30 = d1, d2, d3 / (a_p T_p^2)`` (> 0), in OpenSees's notation
        (:func:`triple_friction_pendulum`), with ``Pi3 = 2 pi sqrt((L2 + L3)/g)/T_p`` and ``Pi9 = mu2
        g/a_p``.  With ``Pi22 < 1`` and ``Pi23 > 0`` every surface's friction rises with its own
        sliding speed by the law above (``Pi22``, ``Pi23`` surface 1's, ``Pi31`` to ``Pi34`` the
        others').
    pi31, pi32, pi33, pi34 : float or None, default None
        A triple pendulum whose friction rises with speed: ``mu_slow1/mu1`` of its inner surfaces,
        ``mu_slow3/mu3`` of its upper one, and their rates ``a1 a_p T_p``, ``a3 a_p T_p``
        (:data:`isoslide.groups.TFP_SPEED`); ``None`` takes surface 1's ``Pi22`` or ``Pi23``.
    pi18, pi19, pi20, pi21 : float or None, default None
        Contents that can rock: a rigid rectangular block of half-width ``b`` and half-height ``h``
        (``alpha = atan(b/h)``, ``R = sqrt(b^2 + h^2)``, ``p = sqrt(3 g / (4 R))``), rocking in the
        vertical plane of the building's x axis (:mod:`isoslide.model.rocking`): ``Pi18 = b/h``,
        ``Pi19 = p T_p``, ``Pi20 = e`` the restitution of its angular velocity at impact (``None``:
        Housner's ``1 - 3/2 sin^2(alpha)``; allowed ``0 < e <=`` that) and ``Pi21 = a_p / (g tan
        alpha)``, so that ``g / a_p = 1/(Pi18 Pi21)``.  ``Pi18 = None``: contents that only slide
        (the paper's model); with ``Pi18``, ``Pi19`` and ``Pi21`` are needed.
    angle : float, default 0
        Angle (radians, counter-clockwise) from the building's x axis to the excitation's x axis:
        the horizontal ground acceleration in the building's axes is the excitation's rotated by
        ``angle`` (``|angle| <= 8 pi``).  The building and the contents are isotropic in the plane,
        so ``angle`` only turns the answer's direction (:attr:`Solution.peak_angle`).
    scale : PhysicalScale or None
        Set by :meth:`from_physical`, so results can be given in metres.

    The model of the general building (``pi9 .. pi13``, ``floor``) is in
    :mod:`isoslide.engine.building`; with their defaults the scene is the paper's model.
    """

    pi2: float
    pi3: float
    pi4: float = _DEFAULTS["pi4"]
    pi5: float = _DEFAULTS["pi5"]
    pi6: float = _DEFAULTS["pi6"]
    pi7: float = _DEFAULTS["pi7"]
    pi8: float = _DEFAULTS["pi8"]
    pulse: Pulse | str = "ricker"
    pi9: float = _DEFAULTS["pi9"]
    pi10: float = _DEFAULTS["pi10"]
    pi11: float = _DEFAULTS["pi11"]
    pi12: float = _DEFAULTS["pi12"]
    pi13: float = _DEFAULTS["pi13"]
    floor: str | int = FLOORS[0]
    storeys: int = 1
    floor_masses: tuple | None = None
    storey_stiffnesses: tuple | None = None
    pulse_y: Pulse | str | None = None
    pi14: float = _DEFAULTS["pi14"]
    pi15: float = _DEFAULTS["pi15"]
    pi16: float = _DEFAULTS["pi16"]
    pi17: float = _DEFAULTS["pi17"]
    pulse_z: Pulse | str | None = None
    pi22: float = _DEFAULTS["pi22"]
    pi23: float = _DEFAULTS["pi23"]
    pi24: float = _DEFAULTS["pi24"]
    pi25: float = _DEFAULTS["pi25"]
    pi26: float = _DEFAULTS["pi26"]
    pi27: float = _DEFAULTS["pi27"]
    pi28: float = _DEFAULTS["pi28"]
    pi29: float = _DEFAULTS["pi29"]
    pi30: float = _DEFAULTS["pi30"]
    pi18: float | None = None
    pi19: float | None = None
    pi20: float | None = None
    pi21: float | None = None
    pi31: float | None = None
    pi32: float | None = None
    pi33: float | None = None
    pi34: float | None = None
    angle: float = 0.0
    scale: PhysicalScale | None = field(default=None, compare=False)

    def __post_init__(self):
        for g in INPUTS:
            object.__setattr__(self, g.name, g.check(getattr(self, g.name)))
        for g in TFP_SPEED:
            if getattr(self, g.name) is not None:
                object.__setattr__(self, g.name, g.check(getattr(self, g.name)))
        if self.pi12 > 0.0 and not 0.0 < self.pi11 < 1.0:
            raise ValueError(f"pi11 = {self.pi11!r} is out of range with a flexible superstructure "
                             f"(pi12 = {self.pi12!r} > 0); allowed range: 0 < value < 1")
        object.__setattr__(self, "storeys", _check_storeys(self.storeys))
        object.__setattr__(self, "floor", _canonical_floor(self.floor, self.storeys))
        for name in ("floor_masses", "storey_stiffnesses"):
            object.__setattr__(self, name, _check_shape(name, getattr(self, name), self.storeys))
        if self.floor_masses is not None:
            total = math.fsum(self.floor_masses)
            object.__setattr__(self, "floor_masses", tuple(m / total for m in self.floor_masses))
        if self.storey_stiffnesses is not None:
            k0 = self.storey_stiffnesses[0]
            object.__setattr__(self, "storey_stiffnesses", tuple(k / k0 for k in self.storey_stiffnesses))
        object.__setattr__(self, "angle", check_range("angle", self.angle, -ANGLE_LIMIT, ANGLE_LIMIT))
        x, y = _resolve_pair(self.pulse, self.pulse_y)
        object.__setattr__(self, "pulse", x)
        object.__setattr__(self, "pulse_y", y)
        if self.pulse_z is not None:
            object.__setattr__(self, "pulse_z", _resolve_pulse(self.pulse_z))
        elif self.pi17 > 0.0:
            raise ValueError(f"pulse_z = None with pi17 = {self.pi17!r} > 0; allowed: a vertical pulse shape "
                             "(pulse_z) when pi17 > 0")
        if self.vertical:
            _check_contact(self.pi17, self.pulse_z)
        if self.pi24 > 0.0:
            _check_tfp(self)
        elif _speed_groups_given(self):
            raise ValueError(f"{_speed_groups_given(self)!r} given without a triple friction pendulum (pi24 = "
                             f"{self.pi24!r}); allowed: None, or pi24 > 0 with pi22 < 1 and pi23 > 0")
        _check_rocking(self)

    @classmethod
    def from_physical(cls, a_p, T_p, M_b, T_b, xi_b, m_ec, mu_s, mu_k, beta=0.0, gamma=0.0,
                      g=G_STANDARD, pulse="ricker", Q_d=0.0, D_y=0.0, m_st=0.0, T_s=0.0, xi_s=0.0,
                      floor="base", storeys=1, floor_masses=None, storey_stiffnesses=None, a_pz=0.0,
                      pulse_z=None, pulse_y=None, a_py=None, T_py=None, t_y=0.0, angle=0.0, Q_slow=None,
                      rate=0.0, tfp=None, b=None, h=None, restitution=None) -> "Scene":
        """Build a scene from physical parameters in SI units.

        Parameters
        ----------
        a_p : float
            Pulse acceleration amplitude, m/s^2 (> 0).
        T_p : float
            Pulse period, s (> 0).
        M_b : float
            Whole isolated mass ``m_b + m_st`` (base slab + superstructure), kg (> 0).
        T_b : float
            Isolation period ``2 pi sqrt(M_b/k_d)`` with the isolator's post-yield (or linear)
            stiffness ``k_d``, s; 0 = fixed base.
        xi_b : float
            Isolation damping ratio ``c_b / (2 sqrt(k_b M_b))``.
        m_ec : float
            Mass of the sliding contents, kg (>= 0).
        mu_s, mu_k : float
            Static and kinetic friction coefficients, ``0 < mu_k <= mu_s``.
        beta : float
            Stribeck transition constant, s/m.
        gamma : float
            Viscous contact constant, s/m.
        g : float
            Gravitational acceleration, m/s^2.
        pulse : str or Pulse
            Excitation shape.
        Q_d : float
            Characteristic strength of a hysteretic isolator, N (0 = linear isolator); for a
            friction pendulum ``mu_b M_b g`` (see :func:`friction_pendulum`).
        D_y : float
            Yield displacement of a bilinear bearing, m (0 with ``Q_d > 0`` = sliding bearing).
        m_st : float
            Superstructure mass, kg, part of ``M_b`` (``0 < m_st < M_b`` when ``T_s > 0``).
        T_s : float
            Superstructure period on a fixed slab ``2 pi sqrt(m_st/k_s)``, s (0 = rigid).
        xi_s : float
            Superstructure damping ratio ``c_s / (2 sqrt(k_s m_st))``.
        floor : {"base", "roof"} or int
            Floor carrying the contents (``0 .. storeys``, see :class:`Scene`).
        storeys : int
            Floors of a uniform superstructure of mass ``m_st`` and fixed-base fundamental period
            ``T_s`` (see :class:`Scene`).
        floor_masses, storey_stiffnesses : sequence of float, optional
            A non-uniform superstructure, given together: the floors' masses (kg) and the storeys'
            stiffnesses (N/m), bottom to top.  Then ``storeys`` is their length, ``m_st`` their
            total mass and ``T_s`` their fixed-base fundamental period (leave ``m_st`` and ``T_s``
            at 0, or give the same values).
        a_pz : float
            Amplitude of the vertical ground acceleration, m/s^2 (>= 0; upward positive).
        pulse_z : str or Pulse or record, optional
            Shape of the vertical ground acceleration on the horizontal pulse's time axis (a record
            runs as recorded, scaled by ``a_pz``).
        pulse_y : str or Pulse or record, optional
            Shape of the second horizontal ground component (a record runs as recorded, scaled by
            ``a_p`` and ``T_p`` like the main one).
        a_py, T_py : float, optional
            Amplitude (m/s^2, >= 0) and period (s, > 0) of the second horizontal component;
            default ``a_p`` and ``T_p``.
        t_y : float
            Time (s) by which the second horizontal component lags the main one.
        angle : float
            Angle (radians) from the building's x axis to the excitation's (see :class:`Scene`).
        Q_slow : float, optional
            Breakaway strength ``mu_slow M_b g`` of a sliding bearing whose friction depends on its
            speed, N (``0 < Q_slow <= Q_d``; ``None``: ``Q_d`` at every speed); ``Q_d`` is then the
            strength at high speed, ``mu_fast M_b g`` (see :func:`friction_pendulum`).
        rate : float
            Rate ``a`` of the bearing's law ``mu(v) = mu_fast - (mu_fast - mu_slow) exp(-a |v|)``,
            s/m (>= 0; 0: ``Q_slow`` at every speed).
        tfp : tuple, optional
            A triple friction pendulum (:func:`triple_friction_pendulum`): ``(L1/(L2 + L3), L2/(L2 +
            L3), mu1/mu2, mu3/mu2, d1, d2, d3)`` (limits in m), with ``T_b = 2 pi sqrt((L2 + L3)/g)``
            and ``Q_d = mu2 M_b g``; ``None``: a single friction pendulum.  Its friction rises with
            speed when ``Q_slow`` and ``rate`` (surface 1's law) are given and ``tfp`` ends with
            ``(mu_slow1/mu1, mu_slow3/mu3, a1, a3)`` (``a`` in s/m) for the inner and upper surfaces.
        b, h : float, optional
            Half-width and half-height of the contents as a rigid rectangular block that can rock in
            the vertical plane of x, m (> 0, given together); ``None``: contents that only slide.
        restitution : float, optional
            The block's coefficient of restitution ``e`` of the angular velocity at impact (``None``:
            Housner's ``1 - 3/2 sin^2(alpha)``).
        """
        v = {"a_p": a_p, "T_p": T_p, "M_b": M_b, "T_b": T_b, "xi_b": xi_b, "m_ec": m_ec, "mu_s": mu_s,
             "mu_k": mu_k, "beta": beta, "gamma": gamma, "g": g, "Q_d": Q_d, "D_y": D_y, "T_s": T_s,
             "xi_s": xi_s}
        # checked in this order: (name, whether 0 is allowed); every one is finite and >= 0, and
        # mu_k is at most mu_s
        for name, zero_allowed in (("a_p", False), ("T_p", False), ("M_b", False), ("T_b", True),
                                   ("xi_b", True), ("m_ec", True), ("mu_s", False), ("mu_k", False),
                                   ("beta", True), ("gamma", True), ("g", False), ("Q_d", True),
                                   ("D_y", True), ("T_s", True), ("xi_s", True)):
            hi, hi_in = (v["mu_s"], True) if name == "mu_k" else (math.inf, False)
            v[name] = check_range(name, v[name], 0.0, hi, zero_allowed, hi_in)
        a_p, T_p, M_b, T_b, xi_b, m_ec, mu_s, mu_k, beta, gamma, g, Q_d, D_y, T_s, xi_s = v.values()
        if (floor_masses is None) != (storey_stiffnesses is None):
            raise ValueError("floor_masses and storey_stiffnesses are given together; allowed: both or neither")
        if floor_masses is not None:
            storeys = len(floor_masses)
            floor_masses = _check_shape("floor_masses", floor_masses, storeys)
            storey_stiffnesses = _check_shape("storey_stiffnesses", storey_stiffnesses, storeys)
            m_st, T_s = _derived_superstructure(m_st, T_s, floor_masses, storey_stiffnesses)
        m_st = check_range("m_st", m_st, 0.0, M_b, T_s == 0.0, False)
        a_py = a_p if a_py is None else check_range("a_py", a_py, 0.0, math.inf, True, False)
        T_py = T_p if T_py is None else check_range("T_py", T_py, 0.0, math.inf, False, False)
        t_y = check_range("t_y", t_y, -math.inf, math.inf, False, False)
        rate = check_range("rate", rate, 0.0, math.inf, True, False)
        if Q_slow is None:
            if rate != 0.0:
                raise ValueError(f"rate = {rate!r} is given without Q_slow; allowed: rate = 0 when Q_slow is None "
                                 "(constant bearing friction)")
            Q_slow = Q_d
        elif Q_d == 0.0 or D_y != 0.0:
            raise ValueError(f"Q_slow = {Q_slow!r} is given without a sliding bearing (Q_d = {Q_d!r}, "
                             f"D_y = {D_y!r}); allowed: Q_slow with Q_d > 0 and D_y = 0")
        else:
            Q_slow = check_range("Q_slow", Q_slow, 0.0, Q_d, False, True)
        shape = {}
        if tfp is not None:
            if len(tfp) not in (7, 11):
                raise ValueError(f"tfp = {tfp!r} has {len(tfp)} values; allowed: (L1/(L2 + L3), L2/(L2 + L3), "
                                 "mu1/mu2, mu3/mu2, d1, d2, d3), followed with friction rising with speed by "
                                 "(mu_slow1/mu1, mu_slow3/mu3, a1, a3), as triple_friction_pendulum returns")
            length = a_p * T_p**2
            shape = dict(zip(TFP_NAMES, (*tfp[:4], *(d / length for d in tfp[4:7])), strict=True))
            if len(tfp) == 11:
                shape.update(zip(TFP_SPEED_NAMES, (tfp[7], tfp[8], tfp[9] * a_p * T_p, tfp[10] * a_p * T_p),
                                 strict=True))
        if (b is None) != (h is None):
            raise ValueError(f"b = {b!r}, h = {h!r}; allowed: both (a block that can rock, m) or neither")
        if b is not None:
            b = check_range("b", b, 0.0, math.inf, False, False)
            h = check_range("h", h, 0.0, math.inf, False, False)
            shape.update(pi18=b / h, pi19=math.sqrt(3.0 * g / (4.0 * math.hypot(b, h))) * T_p, pi20=restitution,
                         pi21=a_p / (g * b / h))
        elif restitution is not None:
            raise ValueError(f"restitution = {restitution!r} is given without b and h; allowed: a restitution with "
                             "a block that can rock (b, h)")
        return cls(
            pi2=mu_k * g / a_p, pi3=T_b / T_p, pi4=xi_b, pi5=mu_k / mu_s,
            pi6=beta * a_p * T_p, pi7=gamma * g * T_p, pi8=m_ec / M_b,
            pulse=_resolve_pulse(pulse, a_p=a_p, T_p=T_p),
            pi9=Q_d / (M_b * a_p), pi10=D_y / (a_p * T_p**2), pi11=m_st / M_b, pi12=T_s / T_p,
            pi13=xi_s, floor=floor, storeys=storeys, floor_masses=floor_masses,
            storey_stiffnesses=storey_stiffnesses,
            pulse_y=None if pulse_y is None else _resolve_pulse(pulse_y, a_p=a_p, T_p=T_p),
            pi14=a_py / a_p, pi15=T_py / T_p, pi16=t_y / T_p, angle=angle, pi17=a_pz / g,
            pulse_z=None if pulse_z is None else _resolve_pulse(pulse_z, a_p=a_pz if a_pz > 0.0 else None, T_p=T_p),
            pi22=Q_slow / Q_d if Q_d > 0.0 else 1.0, pi23=rate * a_p * T_p, **shape,
            scale=PhysicalScale(a_p, T_p, M_b, g),
        )

    @property
    def static_level(self) -> float:
        """``mu_s g / a_p = Pi2 / Pi5``: floor acceleration (units of a_p) that breaks stick."""
        return self.pi2 / self.pi5

    @property
    def rocks(self) -> bool:
        """True when the contents are a block that can rock (``Pi18`` given)."""
        return self.pi18 is not None

    @property
    def restitution(self) -> float | None:
        """The rocking block's restitution ``e``.

        ``Pi20``, or Housner's ``1 - 3/2 sin^2(alpha)`` (at least 0); ``None`` without a rocking block.
        """
        if not self.rocks:
            return None
        return self.pi20 if self.pi20 is not None else max(housner_restitution(math.atan(self.pi18)), 0.0)

    @property
    def tips(self) -> bool:
        """True when the contents are a block that tips before it can slide.

        That is ``mu_s > tan(alpha)``, i.e. ``Pi2 Pi21 / Pi5 > 1``.  With ``mu_s <= tan(alpha)`` a block never rocks (Shenton 1996): from rest it slides once
        ``|A_F| > mu_s (g + a_v)``, no later than it could tip (``|A_F| > (g + a_v) tan(alpha)``), and a
        flat block sliding with friction ``mu_k <= tan(alpha)`` keeps the resultant of its normal force
        on its base whatever the floor does.  The sliding model is then the whole answer.
        """
        return self.rocks and self.pi2 * self.pi21 / self.pi5 > 1.0

    @property
    def fixed_base(self) -> bool:
        """True for ``Pi3 = 0``: the floor moves with the ground."""
        return self.pi3 == 0.0

    @property
    def tfp_speed(self) -> tuple | None:
        """A triple pendulum's friction laws ``((slow1, slow2, slow3), (rate1, rate2, rate3))`` when they rise with speed.

        ``mu_slow/mu_fast`` and ``a a_p T_p`` of its inner surfaces (``Pi31``, ``Pi33``), surface 1
        (``Pi22``, ``Pi23``) and the upper surface (``Pi32``, ``Pi34``), in OpenSees's order (``mu1, mu2,
        mu3``); ``None`` for any other bearing or constant friction (``Pi22 = 1`` or ``Pi23 = 0``).
        """
        if self.pi24 == 0.0 or self.pi22 == 1.0 or self.pi23 == 0.0:
            return None

        def either(value, default):
            return default if value is None else value
        return ((either(self.pi31, self.pi22), self.pi22, either(self.pi32, self.pi22)),
                (either(self.pi33, self.pi23), self.pi23, either(self.pi34, self.pi23)))

    @property
    def rate_independent(self) -> bool:
        """True when friction does not depend on sliding speed (plain Coulomb)."""
        return self.pi7 == 0.0 and (self.pi5 == 1.0 or self.pi6 == 0.0)

    @property
    def isolator(self) -> str:
        """Isolator kind, one of :data:`ISOLATORS`.

        ``"linear"`` (``Pi9 = 0``), ``"bilinear"`` (``Pi9 > 0, Pi10 > 0``), ``"sliding"``
        (``Pi9 > 0, Pi10 = 0``) or ``"tfp"`` (that with ``Pi24 > 0``); with a fixed base (``Pi3 = 0``)
        the isolator has no effect.
        """
        if self.pi9 == 0.0:
            return ISOLATORS[0]
        if self.pi10 > 0.0:
            return ISOLATORS[1]
        return ISOLATORS[3] if self.pi24 > 0.0 else ISOLATORS[2]

    @property
    def flexible(self) -> bool:
        """True for a flexible superstructure (``Pi12 > 0``)."""
        return self.pi12 > 0.0

    @property
    def floor_index(self) -> int:
        """Number of the contents' floor: 0 the slab, ``storeys`` the roof."""
        return {"base": 0, "roof": self.storeys}.get(self.floor, self.floor)

    @property
    def uniform(self) -> bool:
        """True for a uniform superstructure (equal floor masses and storey stiffnesses)."""
        return self.floor_masses is None and self.storey_stiffnesses is None

    @property
    def vertical(self) -> bool:
        """True when the ground moves vertically (``Pi17 > 0`` with a ``pulse_z``)."""
        return self.pi17 > 0.0 and self.pulse_z is not None

    @property
    def paper_model(self) -> bool:
        """True when the scene is the paper's model (Fig. 1-b).

        A linear isolator (``Pi9 = 0``), a rigid superstructure (``Pi12 = 0``), no vertical ground
        motion, the main pulse alone along the building's x axis (:attr:`in_line`) and contents that
        only slide (not :attr:`tips`); the contents' floor then makes no difference.
        """
        return self.pi9 == 0.0 and self.pi12 == 0.0 and not self.vertical and self.in_line and not self.tips

    @property
    def span(self) -> tuple:
        """``(start, end)`` of the whole excitation, units of T_p: the union of its components' supports."""
        starts, ends = [self.pulse.tau_start], [self.pulse.tau_end]
        if self.bidirectional:
            starts.append(self.pi16 + self.pi15 * self.pulse_y.tau_start)
            ends.append(self.pi16 + self.pi15 * self.pulse_y.tau_end)
        if self.vertical:
            ends.append(self.pulse_z.tau_end)
        return min(starts), max(ends)

    @property
    def in_line(self) -> bool:
        """True when the excitation is the main pulse along the building's x axis (the 1-D model as is)."""
        return not self.bidirectional and self.angle == 0.0

    @property
    def bidirectional(self) -> bool:
        """True when the ground moves in both horizontal directions (a ``pulse_y`` with ``Pi14 > 0``)."""
        return self.pulse_y is not None and self.pi14 > 0.0

    @property
    def direction(self) -> float | None:
        """Direction (radians, building axes) of a horizontal excitation along one line, else ``None``.

        One line: no second component, or a second one proportional to the first (the same shape,
        ``Pi15 = 1``, ``Pi16 = 0``: the ground moves along ``atan2(Pi14, 1)`` in the excitation's
        axes).  Such a scene is the 1-D model along that line (:attr:`planar` is False).
        """
        if not self.bidirectional:
            return self.angle
        if self.pulse_y == self.pulse and self.pi15 == 1.0 and self.pi16 == 0.0:
            return self.angle + math.atan2(self.pi14, 1.0)
        return None

    @property
    def planar(self) -> bool:
        """True when the horizontal ground motion is not along one line: the contents slide in the plane."""
        return self.direction is None

    @property
    def line_amplitude(self) -> float:
        """Peak ground acceleration along :attr:`direction` over ``a_p``: ``sqrt(1 + Pi14^2)`` or 1."""
        return math.hypot(1.0, self.pi14) if self.bidirectional and not self.planar else 1.0

    def ground(self, tau) -> tuple:
        """Horizontal ground acceleration ``(a_gx, a_gy) / a_p`` in the building's axes at ``tau``.

        The excitation ``(p(tau), Pi14 p_y((tau - Pi16) / Pi15))`` (second term 0 without a
        ``pulse_y``) rotated by :attr:`angle`; vectorised numpy.
        """
        tau = np.asarray(tau, dtype=float)
        ax = self.pulse.accel(tau)
        ay = (self.pi14 * self.pulse_y.accel((tau - self.pi16) / self.pi15) if self.pulse_y is not None
              else np.zeros_like(ax))
        c, s = math.cos(self.angle), math.sin(self.angle)
        return c * ax - s * ay, s * ax + c * ay

    def ground_velocity(self, tau) -> tuple:
        """Horizontal ground velocity ``(v_gx, v_gy) / (a_p T_p)`` in the building's axes at ``tau``.

        The integral of :meth:`ground` from rest: ``(V(tau), Pi14 Pi15 V_y((tau - Pi16) / Pi15))``
        with ``V``, ``V_y`` the pulses' velocities (:meth:`isoslide.pulses.Pulse.velocity`), rotated
        by :attr:`angle`; vectorised numpy.
        """
        tau = np.asarray(tau, dtype=float)
        vx = np.asarray(self.pulse.velocity(tau), dtype=float)
        vy = (self.pi14 * self.pi15 * np.asarray(self.pulse_y.velocity((tau - self.pi16) / self.pi15), dtype=float)
              if self.pulse_y is not None else np.zeros_like(vx))
        c, s = math.cos(self.angle), math.sin(self.angle)
        return c * vx - s * vy, s * vx + c * vy

    def pis(self) -> dict:
        """The input groups as a dict ``{"pi2": ..., ..., "pi13": ...}``."""
        return {k: getattr(self, k) for k in INPUT_NAMES}


def _check_contact(pi17: float, pulse_z: Pulse) -> None:
    """ValueError when the vertical ground motion lifts the contents off (normal force ``<= 0``).

    The normal force over its static value is ``1 + Pi17 p_z(tau)``; it is evaluated on a grid of
    the pulse's support and every breakpoint, and the first time it reaches zero is located by
    bisection.
    """
    taus = np.union1d(np.linspace(pulse_z.tau_start, pulse_z.tau_end, 20001), pulse_z.breakpoint_array)
    n = 1.0 + pi17 * np.asarray(pulse_z.accel(taus), dtype=float)
    if np.all(n > 0.0):
        return
    k = int(np.argmax(n <= 0.0))
    lo, hi = (taus[k - 1], taus[k]) if k > 0 else (taus[0], taus[0])
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if 1.0 + pi17 * float(pulse_z.accel(np.array([mid]))[0]) > 0.0 else (lo, mid)
    i = int(np.argmin(n))
    raise ValueError(f"pi17 = {pi17!r} lifts the contents off under pulse_z {pulse_z.name!r}: the normal force "
                     f"over its static value, 1 + pi17 p_z(tau), reaches 0 at tau = {hi:.6g} (its least value "
                     f"{n[i]:.6g} at tau = {taus[i]:.6g}); allowed: 1 + pi17 p_z(tau) > 0 at every tau, "
                     f"pi17 < {pi17 / (1.0 - n[i]):.6g} for this pulse")


def _check_rocking(scene) -> None:
    """Check the rocking block's groups (``ValueError`` naming the group, its value and the rule)."""
    if scene.pi18 is None:
        for name in ROCKING_NAMES[1:]:
            if getattr(scene, name) is not None:
                raise ValueError(f"{name} = {getattr(scene, name)!r} is given without pi18; allowed: {name} = None "
                                 "for contents that only slide, or pi18 = b/h with pi19 and pi21")
        return
    for name in ROCKING_NAMES:
        value = getattr(scene, name)
        if value is None:
            if name == "pi20":
                continue
            raise ValueError(f"{name} = None with pi18 = {scene.pi18!r}; allowed: a rocking block needs pi19 = p T_p "
                             "and pi21 = a_p/(g tan alpha)")
        object.__setattr__(scene, name, group(name).check(value))
    if scene.pi20 is not None:
        e_h = housner_restitution(math.atan(scene.pi18))
        object.__setattr__(scene, "pi20", check_range("pi20", scene.pi20, 0.0, e_h, False, True))
    if scene.pi6 > 0.0 or scene.pi7 > 0.0:
        raise ValueError(f"pi6 = {scene.pi6!r}, pi7 = {scene.pi7!r} with a rocking block (pi18 = {scene.pi18!r}); "
                         "allowed: pi6 = pi7 = 0: a block that can rock has Coulomb friction, mu_s at rest and "
                         "while it slides")
    if scene.pulse_y is not None or scene.angle != 0.0:
        raise ValueError(f"a rocking block (pi18 = {scene.pi18!r}) with pulse_y = "
                         f"{None if scene.pulse_y is None else scene.pulse_y.name!r}, angle = {scene.angle!r}; "
                         "allowed: one horizontal component along the building's x axis (pulse_y = None, angle = 0): "
                         "the block rocks in the vertical plane of x, and rocking under two horizontal components is "
                         "not modelled")


def tfp_bearing(scene) -> TripleFrictionPendulum:
    """The triple friction pendulum of a scene in the model's units, with ``g/a_p = 1``.

    Radii ``(Pi24, Pi25, 1 - Pi25) L`` with ``L = L2 + L3 = (Pi3/(2 pi))^2``, frictions ``(Pi26, 1,
    Pi27) Pi9`` (``Pi9 Pi22`` with ``Pi23 = 0``), limits ``(Pi28, Pi29, Pi30)``, weight 1: the stiffnesses ``W/L_i`` (units ``M_b/T_p^2``)
    and strengths ``mu_i W`` (units ``M_b a_p``) of the scene's bearing; a friction that rises with
    speed (:attr:`Scene.tfp_speed`) gives every surface its slow value and rate (units ``1/(a_p
    T_p)``).  Every admissibility rule
    of :mod:`isoslide.model.tfp` compares ``d/L`` with frictions, both proportional to ``a_p/g``, so
    the choice ``g/a_p = 1`` decides nothing.
    """
    L = (scene.pi3 / (2.0 * math.pi)) ** 2
    mu2 = scene.pi9 * (scene.pi22 if scene.pi23 == 0.0 else 1.0)
    mu = (scene.pi26 * mu2, mu2, scene.pi27 * mu2)
    laws = scene.tfp_speed
    speed = {} if laws is None else {"mu_slow": tuple(r * m for r, m in zip(laws[0], mu, strict=True)),
                                     "rate": laws[1]}
    return TripleFrictionPendulum(L=(scene.pi24 * L, scene.pi25 * L, (1.0 - scene.pi25) * L), mu=mu,
                                  d=(scene.pi28, scene.pi29, scene.pi30), W=1.0, **speed)


def _speed_groups_given(scene) -> dict:
    """The speed-dependent triple pendulum's optional groups (``Pi31`` .. ``Pi34``) that ``scene`` sets."""
    return {n: getattr(scene, n) for n in TFP_SPEED_NAMES if getattr(scene, n) is not None}


def _check_tfp(scene) -> None:
    """``ValueError`` unless a scene with ``Pi24 > 0`` is a triple friction pendulum the model represents."""
    if scene.pi9 == 0.0 or scene.pi10 != 0.0 or scene.pi3 == 0.0:
        raise ValueError(f"pi24 = {scene.pi24!r} > 0 needs a sliding bearing (pi3 > 0, pi9 > 0, pi10 = 0); got "
                         f"pi3 = {scene.pi3!r}, pi9 = {scene.pi9!r}, pi10 = {scene.pi10!r}")
    given = _speed_groups_given(scene)
    if given and scene.tfp_speed is None:
        raise ValueError(f"{given!r} given with constant friction on the triple pendulum (pi22 = {scene.pi22!r}, "
                         f"pi23 = {scene.pi23!r}); allowed: None, or with pi22 < 1 and pi23 > 0")
    if scene.tfp_speed is not None and any(r >= 1.0 for r in scene.tfp_speed[0]):
        raise ValueError(f"pi31, pi32 = {scene.pi31!r}, {scene.pi32!r} with pi22 = {scene.pi22!r} < 1 keep a surface "
                         "constant while the others rise with speed; allowed: every ratio below 1")
    for name in ("pi28", "pi29", "pi30"):
        if getattr(scene, name) <= 0.0:
            raise ValueError(f"{name} = {getattr(scene, name)!r} is out of range with a triple friction pendulum "
                             "(pi24 > 0); allowed range: 0 < value <= 1e6")
    try:
        tfp_bearing(scene)
    except ValueError as err:
        raise ValueError(f"pi24 .. pi30 = {tuple(getattr(scene, f'pi{i}') for i in range(24, 31))!r} (with "
                         f"pi3 = {scene.pi3!r}, pi9 = {scene.pi9!r}) do not make a triple friction pendulum whose "
                         f"regimes I to V come in order, in units L2 + L3 = (pi3/(2 pi))^2, mu_i g/a_p: {err}") from None


def _resolve_pair(pulse, pulse_y) -> tuple:
    """The main and the second horizontal pulses; a recorded pair shares the main record's scales.

    A record as ``pulse_y`` next to a record as ``pulse`` runs on the main record's fitted
    ``a_p``, ``T_p`` (both as recorded, one time axis); otherwise each is resolved on its own.
    """
    if pulse_y is None:
        return _resolve_pulse(pulse), None
    fit = getattr(pulse, "fit", None)
    if callable(getattr(pulse, "as_pulse", None)) and callable(getattr(pulse_y, "as_pulse", None)) \
            and callable(fit):
        f = fit()
        return _resolve_pulse(pulse, f.a_p, f.T_p), _resolve_pulse(pulse_y, f.a_p, f.T_p)
    return _resolve_pulse(pulse), _resolve_pulse(pulse_y)


def _check_storeys(storeys) -> int:
    """``storeys`` as an int in ``1 .. MAX_STOREYS``, or a ValueError naming it."""
    ok = not isinstance(storeys, bool) and isinstance(storeys, (int, float)) and float(storeys).is_integer() \
        and 1 <= storeys <= MAX_STOREYS
    if not ok:
        raise ValueError(f"storeys = {storeys!r} is out of range; allowed: an integer, 1 <= value <= {MAX_STOREYS}")
    return int(storeys)


def _canonical_floor(floor, storeys: int):
    """``"base"`` for floor 0, ``"roof"`` for floor ``storeys``, the number of a floor between."""
    if isinstance(floor, str):
        if floor in FLOORS:
            return floor
    elif not isinstance(floor, bool) and isinstance(floor, (int, float)) and float(floor).is_integer() \
            and 0 <= floor <= storeys:
        k = int(floor)
        return FLOORS[0] if k == 0 else (FLOORS[1] if k == storeys else k)
    raise ValueError(f"floor = {floor!r} is invalid; allowed: {', '.join(map(repr, FLOORS))} or an integer, "
                     f"0 <= value <= {storeys} (storeys = {storeys})")


def _derived_superstructure(m_st, T_s, masses: tuple, stiffnesses: tuple) -> tuple:
    """``(m_st, T_s)`` of a superstructure given floor by floor; given values must agree to 1e-9."""
    derived = {"m_st": math.fsum(masses), "T_s": float(fundamental_period(masses, stiffnesses))}
    for name, given in (("m_st", m_st), ("T_s", T_s)):
        given = check_range(name, given, 0.0, math.inf, True, False)
        if given != 0.0 and abs(given - derived[name]) > 1e-9 * derived[name]:
            raise ValueError(f"{name} = {given!r} disagrees with the floors given ({derived[name]!r}); "
                             f"allowed: 0 or {derived[name]!r}")
    return derived["m_st"], derived["T_s"]


def _check_shape(name: str, values, storeys: int):
    """A tuple of ``storeys`` positive finite floats (or ``None``), or a ValueError naming ``name``."""
    if values is None:
        return None
    values = tuple(values)
    if len(values) != storeys:
        raise ValueError(f"{name} has {len(values)} values; allowed: one per storey (storeys = {storeys})")
    return tuple(check_range(f"{name}[{i}]", v, 0.0, math.inf, False, False) for i, v in enumerate(values))


def friction_pendulum(R, mu, M_b, g=G_STANDARD, mu_slow=None, rate=0.0) -> dict:
    """Isolator parameters of a friction pendulum (single concave sliding surface).

    Parameters
    ----------
    R : float
        Radius of curvature of the sliding surface, m (> 0).
    mu : float
        Friction coefficient of the slider (> 0); with ``mu_slow`` its value at high speed,
        ``mu_fast``.
    M_b : float
        Whole isolated mass carried, kg (> 0).
    g : float
        Gravitational acceleration, m/s^2.
    mu_slow : float, optional
        Friction coefficient at breakaway (zero speed) of a PTFE-type surface whose friction rises
        with speed, ``mu(v) = mu - (mu - mu_slow) exp(-rate |v|)`` (Constantinou, Mokha and Reinhorn
        1990), ``0 < mu_slow <= mu``; ``None``: ``mu`` at every speed.
    rate : float
        ``a`` of that law, s/m (>= 0); 0 gives ``mu_slow`` at every speed.

    Returns
    -------
    dict
        ``T_b = 2 pi sqrt(R/g)`` (s; the pendulum's stiffness ``k_d = M_b g / R``), ``Q_d = mu M_b g``
        (N) and ``D_y = 0`` (true stick): keyword arguments for :meth:`Scene.from_physical`.  With
        ``mu_slow`` and ``rate > 0`` also ``Q_slow = mu_slow M_b g`` (N, the breakaway strength) and
        ``rate``; with ``rate = 0`` the friction is constant, ``Q_d = mu_slow M_b g``, exactly as
        ``friction_pendulum(R, mu_slow, M_b, g)``.  The friction forces scale with the bearing's
        normal force, vertical ground motion included (:class:`Scene`, ``Pi17``).
    """
    R = check_range("R", R, 0.0, math.inf, False, False)
    mu = check_range("mu", mu, 0.0, math.inf, False, False)
    M_b = check_range("M_b", M_b, 0.0, math.inf, False, False)
    g = check_range("g", g, 0.0, math.inf, False, False)
    rate = check_range("rate", rate, 0.0, math.inf, True, False)
    out = {"T_b": 2.0 * math.pi * math.sqrt(R / g), "Q_d": mu * M_b * g, "D_y": 0.0}
    if mu_slow is None:
        if rate != 0.0:
            raise ValueError(f"rate = {rate!r} is given without mu_slow; allowed: rate = 0 when mu_slow is None "
                             "(constant friction)")
        return out
    mu_slow = check_range("mu_slow", mu_slow, 0.0, mu, False, True)
    if rate == 0.0:
        out["Q_d"] = mu_slow * M_b * g
        return out
    return {**out, "Q_slow": mu_slow * M_b * g, "rate": rate}


def _resolve_pulse(pulse, a_p=None, T_p=None) -> Pulse:
    """A Pulse from a Pulse, a shape name, or a record (anything with ``as_pulse``).

    A record runs as recorded (its own sign and time axis, ``t = tau T_p``),
    scaled by the given ``a_p`` (m/s^2, a positive scale: ``|a_p|`` is used) and
    ``T_p`` (s) when a scene is built from physical units, without fitting
    anything; else by its own fitted pulse's scales.
    """
    if isinstance(pulse, Pulse):
        return pulse
    as_pulse = getattr(pulse, "as_pulse", None)
    if callable(as_pulse):
        if a_p is None:
            return as_pulse()
        return as_pulse(a_p=abs(a_p), T_p=T_p, t_ref=0.0, polarity=1)
    return get_pulse(pulse)


def to_metres(pi1: float, scene: Scene) -> float:
    """Convert a dimensionless length (units of ``a_p T_p^2``, e.g. Pi1) to metres.

    The scene must be built with :meth:`Scene.from_physical`.
    """
    if scene.scale is None:
        raise ValueError("scene has no physical scale; build it with Scene.from_physical")
    return pi1 * scene.scale.length


def paper_groups(a_p, T_p, M_b, T_b, xi_b, m_ec, mu_s, mu_k, beta=0.0, gamma=0.0, g=G_STANDARD) -> dict:
    """The eight groups exactly as the paper prints them (Eq. 5), for comparison.

    Differs from :class:`Scene` only in ``pi7 = gamma a_p T_p`` (printed)
    instead of ``gamma g T_p`` (the group that holds for Eq. 1).
    """
    return {
        "pi2": mu_k * g / a_p, "pi3": T_b / T_p, "pi4": xi_b, "pi5": mu_k / mu_s,
        "pi6": beta * a_p * T_p, "pi7": gamma * a_p * T_p, "pi8": m_ec / M_b,
    }


def triple_friction_pendulum(L, mu, d, M_b, g=G_STANDARD, mu_slow=None, rate=0.0) -> dict:
    """Isolator parameters of a triple friction pendulum (OpenSees's ``TripleFrictionPendulum``).

    Parameters
    ----------
    L : tuple of float
        Effective radii ``(L1, L2, L3)``, m: ``L1`` of each of the two inner surfaces, ``L2`` of the
        lower outer surface (surface 1), ``L3`` of the upper one (surface 4) (> 0).
    mu : tuple of float
        Friction coefficients ``(mu1, mu2, mu3)`` of the same surfaces, ``0 < mu1 <= mu2 <= mu3``.
    d : tuple of float
        Displacement limits ``(d1, d2, d3)``, m (> 0): the largest travel on each surface, rigid
        restrainers beyond.
    M_b : float
        Whole isolated mass carried, kg (> 0): the weight ``M_b g`` on the bearing, as for
        :func:`friction_pendulum`.
    g : float
        Gravitational acceleration, m/s^2.
    mu_slow : float or tuple of float, optional
        Friction at breakaway of surfaces whose friction rises with speed, one value or three; with
        ``rate = 0`` the constant friction of every surface (``mu_slow`` replaces ``mu``).
    rate : float or tuple of float
        ``a`` of the law ``mu(v) = mu - (mu - mu_slow) exp(-a |v|)`` of each surface's own sliding
        speed, s/m (>= 0), one value or three: all zero (constant friction) or all positive with
        ``mu_slow < mu`` on every surface (:mod:`isoslide.engine.tfp_flow` integrates that bearing).

    Returns
    -------
    dict
        ``T_b = 2 pi sqrt((L2 + L3)/g)`` (s; the period of the outer surfaces sliding together,
        regime III), ``Q_d = mu2 M_b g`` (N), ``D_y = 0`` and ``tfp = (L1/(L2 + L3), L2/(L2 + L3),
        mu1/mu2, mu3/mu2, d1, d2, d3)``: keyword arguments for :meth:`Scene.from_physical`.  With
        equal frictions the bearing is the single friction pendulum of radius ``L2 + L3`` until
        surface 1 reaches its restrainer.  Friction that rises with speed adds surface 1's law,
        ``Q_slow = mu_slow2 M_b g`` (N) and ``rate = a2`` (s/m), and ends ``tfp`` with
        ``(mu_slow1/mu1, mu_slow3/mu3, a1, a3)``.

    Raises
    ------
    ValueError
        Naming the parameter, its value and the rule: non-positive radii or limits, friction
        ordering or geometry outside what the series model reproduces (regimes I to V in order, at
        every speed: :class:`isoslide.model.tfp.TripleFrictionPendulum`), ``mu_slow > mu``, rates
        that mix constant and rising friction.
    """
    M_b = check_range("M_b", M_b, 0.0, math.inf, False, False)
    g = check_range("g", g, 0.0, math.inf, False, False)
    rates = _triple("rate", rate, 0.0, True)
    speed = {}
    if mu_slow is not None:
        checked = TripleFrictionPendulum(L, mu, d, mu_slow=mu_slow, rate=1.0)
        if any(r > 0.0 for r in rates):
            constant = [i for i in range(3) if rates[i] == 0.0 or checked.mu_slow[i] == checked.mu[i]]
            if constant:
                raise ValueError(f"mu_slow = {mu_slow!r}, rate = {rate!r} keep mu{constant[0] + 1} constant (rate 0 or "
                                 "mu_slow = mu) while other surfaces' friction rises with speed; allowed: every "
                                 "rate > 0 with mu_slow < mu, or every rate 0")
            speed = {"mu_slow": checked.mu_slow, "rate": rates}
        else:
            mu = checked.mu_slow
    elif any(r != 0.0 for r in rates):
        raise ValueError(f"rate = {rate!r} is given without mu_slow; allowed: rate = 0 when mu_slow is None "
                         "(constant friction)")
    b = TripleFrictionPendulum(L, mu, d, **speed)
    if (b.mu_slow or b.mu)[0] <= 0.0:
        raise ValueError(f"mu1 = {b.mu[0]!r} is out of range; allowed range: 0 < mu1 <= mu2 <= mu3")
    (L1, L2, L3), (mu1, mu2, mu3), (d1, d2, d3) = b.L, b.mu, b.d
    outer = L2 + L3
    out = {"T_b": 2.0 * math.pi * math.sqrt(outer / g), "Q_d": mu2 * M_b * g, "D_y": 0.0,
           "tfp": (L1 / outer, L2 / outer, mu1 / mu2, mu3 / mu2, d1, d2, d3)}
    if speed:
        (s1, s2, s3), (a1, a2, a3) = b.mu_slow, b.rate
        out.update(Q_slow=s2 * M_b * g, rate=a2, tfp=(*out["tfp"], s1 / mu1, s3 / mu3, a1, a3))
    return out
