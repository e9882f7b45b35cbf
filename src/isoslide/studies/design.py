"""Isolators designed to the same code linearisation: effective stiffness and damping at D.

Building codes (ASCE 7 Ch. 17, the AASHTO Guide Specifications for Seismic Isolation Design)
replace a hysteretic isolator by a linear one with the *effective* (secant) stiffness and the
*effective* damping of its loop at the design displacement ``D``:

* bilinear bearing (post-yield stiffness ``k_d``, characteristic strength ``Q``, yield
  displacement ``D_y``)::

      K_eff    = k_d + Q / D
      beta_eff = 2 Q (D - D_y) / (pi K_eff D^2)      (loop area 4 Q (D - D_y))

* friction pendulum (radius ``R``, friction coefficient ``mu``, weight ``W``): the bilinear bearing
  with ``k_d = W / R``, ``Q = mu W`` and ``D_y = 0``::

      K_eff    = W / R + mu W / D
      beta_eff = 2 mu / (pi (mu + D / R))

* linear isolator (the paper's): ``K_eff = k``, ``beta_eff = xi`` (viscous damping ratio).

* triple friction pendulum (:mod:`isoslide.model.tfp`, OpenSees's notation: inner radius ``L1``,
  outer ``L2``, ``L3``, frictions ``mu1 <= mu2 <= mu3``, limits ``d1, d2, d3``): ``K_eff = F(D) / D``
  with ``F`` the backbone force and ``beta_eff = E(D) / (2 pi K_eff D^2)`` with ``E`` the area of the
  closed-form cyclic loop (:func:`effective_triple_friction_pendulum`).

The effective period is ``T_eff = 2 pi sqrt(M / K_eff)``.  This module evaluates those formulas and
inverts them: given ``T_eff``, ``beta_eff`` and ``D`` it returns the linear, bilinear and
friction-pendulum isolators that share them (:func:`design_linear`, :func:`design_bilinear`,
:func:`design_friction_pendulum`), as the keyword arguments of
:meth:`isoslide.Scene.from_physical` (:func:`scene_parameters`), and the triple friction pendulum
of given proportions that shares them (:func:`design_triple_friction_pendulum`, the design rule
below).  SI units throughout.

The triple friction pendulum's design rule
------------------------------------------
A triple friction pendulum has seven parameters; two targets (``T_eff``, ``beta_eff`` at ``D``) fix
two of them once the proportions of a typical bearing are chosen:

* equal outer surfaces ``L2 = L3 = L`` with equal limits ``d2 = d3``, inner surfaces of radius
  ``L1 = lam L`` (``lam`` about 0.15-0.25: ``L1`` 0.3-0.5 m, ``L`` 1.5-3 m in built bearings);
* frictions ``mu1 = a mu2`` (the inner, low-friction slider, ``a`` about 0.2-0.4) and ``mu3 = c mu2``
  (``c >= 1``; ``c = 1`` removes regime II), as in the bearings of hospitals
  (``mu1`` 0.01-0.02, ``mu2`` 0.04-0.06, ``mu3`` 0.06-0.12);
* ``D`` in regime III (the outer surfaces sliding, stiffness ``W / (2 L)``), stiffening (regime IV,
  surface 1 on its restrainer) from ``u_dr1 = sigma D`` (``sigma > 1``) and the displacement
  capacity (the first inner restrainer, the end of regime V) at ``u_cap = rho D``.

Per unit weight, with ``mu2`` and ``L`` unknown, the regime boundaries are
``u* = 2 L1 (mu2 - mu1) = q L mu2`` and ``u** = u* + (L1 + L)(mu3 - mu2) = p L mu2`` with
``q = 2 lam (1 - a)``, ``p = q + (1 + lam)(c - 1)``.  In regime III the backbone is a pendulum of
radius ``2 L`` and friction ``mu_e``::

    F(D) / W = D / (2 L) + mu_e,         mu_e = mu3 - u** / (2 L) = kappa mu2,
    kappa    = c - p / 2

and the loop (Masing's rule from a regime-III amplitude, :mod:`isoslide.model.tfp`) has the area::

    E(D) / W = 4 (mu_e D - e0),          e0 = u** (mu3 - mu2) + u* (mu3 - mu1) - u**^2 / (2 L)
                                            = gamma L mu2^2,
    gamma    = p (c - 1) + q (c - a) - p^2 / 2

so ``K_eff / W = 1/(2 L) + mu_e / D`` and ``beta_eff = 2 (mu_e - e0 / D) / (pi (mu_e + D / (2 L)))``
-- the single pendulum's formulas with ``R = 2 L``, ``mu = mu_e``, less the energy ``4 W e0`` the
inner slider's early sliding takes from the loop.  With ``k = K_eff / W = (2 pi / T_eff)^2 / g``,
``B = pi beta_eff k D / 2`` (the friction of the single pendulum of the same targets) and
``s = gamma / kappa^2``, eliminating ``L = D / (2 (k D - mu_e))`` leaves a quadratic in ``mu_e``::

    (2 + s) mu_e^2 - 2 (k D + B) mu_e + 2 B k D = 0,
    mu_e = ((k D + B) - sqrt((k D + B)^2 - 2 (2 + s) B k D)) / (2 + s)

(the smaller root: ``mu_e -> B`` as ``s -> 0``); then ``mu2 = mu_e / kappa``, ``L = D / (2 (k D -
mu_e))``, ``L1 = lam L``, and the limits from ``u_dr1 = u** + 2 L (mu2 + d2 / L - mu3)`` and
``u_cap = u_dr4 + 2 L1 (mu1 + d1 / L1 - mu3)`` (``d2 = d3``, ``u_dr4 = u_dr1 + (L1 + L)(mu3 - mu2)``)::

    d2 = d3 = (sigma D - u**) / 2 + L (mu3 - mu2),
    d1      = (rho D - u_dr4) / 2 + L1 (mu3 - mu1).

The bearing matches ``T_eff`` and ``beta_eff`` at ``D`` exactly (the closed forms of
:mod:`isoslide.model.tfp` give them back, :func:`effective_triple_friction_pendulum`); it differs
from the single pendulum away from ``D``: softer and less damped below ``u**`` (the inner slider
breaks away at ``mu1 W``), stiffer beyond ``sigma D``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..scene import G_STANDARD, triple_friction_pendulum
from ..model import tfp as _tfp
from ..model.validation import check_range

SYSTEMS = ("linear", "bilinear", "friction_pendulum")
"""Isolation systems :func:`design` builds, in this order."""


@dataclass(frozen=True)
class Isolator:
    """One isolator of mass ``M``, as :meth:`isoslide.Scene.from_physical` takes it.

    Attributes
    ----------
    system : str
        One of :data:`SYSTEMS`.
    M : float
        Isolated mass, kg.
    k_d : float
        Linear (or post-yield) stiffness, N/m.
    xi_b : float
        Viscous damping ratio ``c / (2 sqrt(k_d M))``.
    Q_d : float
        Characteristic strength, N (0 for the linear isolator).
    D_y : float
        Yield displacement, m (0 for the linear isolator and the friction pendulum).
    """

    system: str
    M: float
    k_d: float
    xi_b: float
    Q_d: float
    D_y: float

    @property
    def T_b(self) -> float:
        """Period of the (post-yield) stiffness ``2 pi sqrt(M / k_d)``, s."""
        return 2.0 * math.pi * math.sqrt(self.M / self.k_d)

    def radius(self, g: float = G_STANDARD) -> float:
        """Radius of curvature ``R = W / k_d = M g / k_d`` of the equivalent pendulum, m."""
        return self.M * g / self.k_d

    def mu(self, g: float = G_STANDARD) -> float:
        """Characteristic strength over weight ``Q / W`` (a friction pendulum's ``mu``)."""
        return self.Q_d / (self.M * g)

    def effective(self, D: float) -> tuple[float, float]:
        """``(K_eff, beta_eff)`` of this isolator at displacement ``D`` (m): N/m and 1.

        The viscous damping ratio ``xi_b`` counts only for the linear isolator (the codes'
        linearisation of a hysteretic bearing has no viscous part; the designs here have none).
        """
        if self.system == "linear":
            return self.k_d, self.xi_b
        return effective_bilinear(self.k_d, self.Q_d, D, self.D_y)

    def scene_parameters(self) -> dict:
        """``T_b``, ``xi_b``, ``Q_d``, ``D_y`` and ``M_b``: keywords of :meth:`isoslide.Scene.from_physical`."""
        return {"M_b": self.M, "T_b": self.T_b, "xi_b": self.xi_b, "Q_d": self.Q_d, "D_y": self.D_y}


def _positive(name, value):
    return check_range(name, value, 0.0, math.inf, False, False)


def effective_period(M: float, K_eff: float) -> float:
    """``T_eff = 2 pi sqrt(M / K_eff)``, s, of mass ``M`` (kg) on stiffness ``K_eff`` (N/m)."""
    return 2.0 * math.pi * math.sqrt(_positive("M", M) / _positive("K_eff", K_eff))


def effective_bilinear(k_d: float, Q: float, D: float, D_y: float = 0.0) -> tuple[float, float]:
    """Effective stiffness and damping of a bilinear bearing at displacement ``D``.

    Parameters
    ----------
    k_d : float
        Post-yield stiffness, N/m (>= 0).
    Q : float
        Characteristic strength (force at zero displacement on the loop), N (>= 0).
    D : float
        Displacement amplitude, m (> ``D_y``).
    D_y : float
        Yield displacement, m (0 = rigid-plastic, a sliding bearing).

    Returns
    -------
    (float, float)
        ``K_eff = k_d + Q / D`` (N/m) and ``beta_eff = 2 Q (D - D_y) / (pi K_eff D^2)``.
    """
    k_d = check_range("k_d", k_d, 0.0, math.inf)
    Q = check_range("Q", Q, 0.0, math.inf)
    D_y = check_range("D_y", D_y, 0.0, math.inf)
    D = check_range("D", D, D_y, math.inf, False, False)
    K = k_d + Q / D
    if K <= 0.0:
        raise ValueError(f"k_d = {k_d!r} and Q = {Q!r}: the bearing has no stiffness; allowed: k_d + Q/D > 0")
    return K, 2.0 * Q * (D - D_y) / (math.pi * K * D * D)


def effective_friction_pendulum(R: float, mu: float, D: float, W: float) -> tuple[float, float]:
    """Effective stiffness and damping of a friction pendulum at displacement ``D``.

    Parameters
    ----------
    R : float
        Radius of curvature, m (> 0).
    mu : float
        Friction coefficient (>= 0).
    D : float
        Displacement amplitude, m (> 0).
    W : float
        Weight carried, N (> 0).

    Returns
    -------
    (float, float)
        ``K_eff = W / R + mu W / D`` (N/m) and ``beta_eff = 2 mu / (pi (mu + D / R))``.
    """
    R, W, D = _positive("R", R), _positive("W", W), _positive("D", D)
    mu = check_range("mu", mu, 0.0, math.inf)
    return W / R + mu * W / D, 2.0 * mu / (math.pi * (mu + D / R))


def _check_target(M, T_eff, beta_eff):
    M = _positive("M", M)
    T_eff = _positive("T_eff", T_eff)
    beta_eff = check_range("beta_eff", beta_eff, 0.0, 2.0 / math.pi, True, False)
    return M, T_eff, beta_eff


def design_linear(M: float, T_eff: float, beta_eff: float) -> Isolator:
    """The linear isolator with period ``T_eff`` (s) and viscous damping ratio ``beta_eff``."""
    M, T_eff, beta_eff = _check_target(M, T_eff, beta_eff)
    return Isolator("linear", M, M * (2.0 * math.pi / T_eff) ** 2, beta_eff, 0.0, 0.0)


def design_bilinear(M: float, T_eff: float, beta_eff: float, D: float, D_y: float) -> Isolator:
    """The bilinear bearing with ``T_eff`` (s) and ``beta_eff`` at ``D`` (m), yielding at ``D_y`` (m).

    Inverts :func:`effective_bilinear`: ``K_eff = M (2 pi / T_eff)^2``,
    ``Q = pi beta_eff K_eff D^2 / (2 (D - D_y))``, ``k_d = K_eff - Q / D``.

    Raises
    ------
    ValueError
        If ``D_y >= D`` or the damping asks for so much strength that ``k_d <= 0``
        (``beta_eff >= 2 (D - D_y) / (pi D)``).
    """
    M, T_eff, beta_eff = _check_target(M, T_eff, beta_eff)
    D = _positive("D", D)
    D_y = check_range("D_y", D_y, 0.0, D, True, False)
    K = M * (2.0 * math.pi / T_eff) ** 2
    Q = math.pi * beta_eff * K * D * D / (2.0 * (D - D_y))
    k_d = K - Q / D
    if k_d <= 0.0:
        limit = 2.0 * (D - D_y) / (math.pi * D)
        raise ValueError(f"beta_eff = {beta_eff!r} is out of range for D = {D!r} m, D_y = {D_y!r} m "
                         f"(no post-yield stiffness left); allowed range: 0 <= value < {limit:.6g}")
    return Isolator("bilinear" if D_y > 0.0 else "friction_pendulum", M, k_d, 0.0, Q, D_y)


def design_friction_pendulum(M: float, T_eff: float, beta_eff: float, D: float) -> Isolator:
    """The friction pendulum with ``T_eff`` (s) and ``beta_eff`` at ``D`` (m).

    Inverts :func:`effective_friction_pendulum`: ``mu = pi beta_eff D K_eff / (2 W)`` and
    ``1 / R = K_eff / W - mu / D`` with ``W = M g`` (see :meth:`Isolator.radius`, :meth:`Isolator.mu`).
    """
    return design_bilinear(M, T_eff, beta_eff, D, 0.0)


def design(M: float, T_eff: float, beta_eff: float, D: float, D_y: float) -> dict:
    """The three systems of :data:`SYSTEMS` sharing ``T_eff``, ``beta_eff`` at ``D``.

    Parameters
    ----------
    M : float
        Isolated mass, kg.
    T_eff : float
        Effective period at ``D``, s.
    beta_eff : float
        Effective damping ratio at ``D``.
    D : float
        Design displacement, m.
    D_y : float
        Yield displacement of the bilinear (lead-rubber) bearing, m (``0 < D_y < D``).

    Returns
    -------
    dict of str -> Isolator
    """
    check_range("D_y", D_y, 0.0, _positive("D", D), False, False)
    return {"linear": design_linear(M, T_eff, beta_eff),
            "bilinear": design_bilinear(M, T_eff, beta_eff, D, D_y),
            "friction_pendulum": design_friction_pendulum(M, T_eff, beta_eff, D)}


# ----------------------------------------------------------------------------------------------
# the triple friction pendulum
# ----------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class TripleIsolator:
    """A triple friction pendulum of mass ``M``, as :func:`design_triple_friction_pendulum` designs it.

    Attributes
    ----------
    M : float
        Isolated mass, kg.
    L : tuple of float
        Effective radii ``(L1, L2, L3)``, m (OpenSees's notation, :mod:`isoslide.model.tfp`).
    mu : tuple of float
        Friction coefficients ``(mu1, mu2, mu3)``, constant.
    d : tuple of float
        Displacement limits ``(d1, d2, d3)``, m.
    g : float
        Gravitational acceleration, m/s^2.
    """

    M: float
    L: tuple
    mu: tuple
    d: tuple
    g: float = G_STANDARD

    system = "triple_friction_pendulum"

    def bearing(self) -> _tfp.TripleFrictionPendulum:
        """The bearing of :mod:`isoslide.model.tfp`, carrying the weight ``W = M g`` (N)."""
        return _tfp.TripleFrictionPendulum(self.L, self.mu, self.d, W=self.M * self.g)

    @property
    def T_b(self) -> float:
        """Period of regime III (the outer surfaces sliding) ``2 pi sqrt((L2 + L3) / g)``, s."""
        return 2.0 * math.pi * math.sqrt((self.L[1] + self.L[2]) / self.g)

    def boundaries(self) -> _tfp.Boundaries:
        """Where the backbone's regimes I..V start and the capacity (:func:`isoslide.model.tfp.regime_boundaries`)."""
        return _tfp.regime_boundaries(self.bearing())

    @property
    def capacity(self) -> float:
        """Displacement capacity, m: the first inner surface on its restrainer ends regime V."""
        return _tfp.capacity(self.bearing())

    def effective(self, D: float) -> tuple[float, float]:
        """``(K_eff, beta_eff)`` at displacement ``D`` (m): N/m and 1 (:func:`effective_triple_friction_pendulum`)."""
        return effective_triple_friction_pendulum(self.bearing(), D)

    def regime(self, D: float) -> int:
        """Regime (1..5 = I..V) of the backbone at displacement ``D`` (m)."""
        return _tfp.peak_regime(self.bearing(), D)

    def scene_parameters(self) -> dict:
        """``M_b``, ``xi_b = 0``, ``T_b``, ``Q_d``, ``D_y`` and ``tfp``: keywords of :meth:`isoslide.Scene.from_physical`."""
        return {"M_b": self.M, "xi_b": 0.0, **triple_friction_pendulum(self.L, self.mu, self.d, self.M, g=self.g)}


def effective_triple_friction_pendulum(bearing: _tfp.TripleFrictionPendulum, D: float) -> tuple[float, float]:
    """Effective stiffness and damping of a triple friction pendulum at displacement ``D``.

    Parameters
    ----------
    bearing : isoslide.model.tfp.TripleFrictionPendulum
        The bearing (constant friction; its weight ``W`` in N).
    D : float
        Displacement amplitude, m (``0 < D <= capacity``).

    Returns
    -------
    (float, float)
        ``K_eff = F(D) / D`` (N/m; ``F`` the backbone force, :func:`isoslide.model.tfp.force`) and
        ``beta_eff = E(D) / (2 pi K_eff D^2)`` (``E`` the area of the closed-form loop,
        :func:`isoslide.model.tfp.dissipated_energy`).
    """
    D = _positive("D", D)
    F = _tfp.force(bearing, D)[0]
    K = F / D
    return K, _tfp.dissipated_energy(bearing, D) / (2.0 * math.pi * K * D * D)


def design_triple_friction_pendulum(M: float, T_eff: float, beta_eff: float, D: float, inner_radius: float,
                                    mu1_ratio: float, mu3_ratio: float, stiffening: float, capacity: float,
                                    g: float = G_STANDARD) -> TripleIsolator:
    """The triple friction pendulum of the given proportions with ``T_eff`` (s) and ``beta_eff`` at ``D`` (m).

    The design rule of the module docstring: ``L2 = L3 = L``, ``L1 = inner_radius L``, ``mu1 =
    mu1_ratio mu2``, ``mu3 = mu3_ratio mu2``, ``D`` in regime III, stiffening from ``stiffening D``
    and the capacity at ``capacity D``; ``mu2`` and ``L`` solve the targets exactly.

    Parameters
    ----------
    M : float
        Isolated mass, kg (> 0).
    T_eff, beta_eff : float
        Effective period (s) and damping at ``D``.
    D : float
        Design displacement, m (> 0).
    inner_radius : float
        ``L1 / L2`` (``L2 = L3``), in (0, 1).
    mu1_ratio : float
        ``mu1 / mu2``, in (0, 1].
    mu3_ratio : float
        ``mu3 / mu2``, >= 1.
    stiffening : float
        ``u_dr1 / D``, > 1: regime IV (surface 1 on its restrainer) starts there.
    capacity : float
        ``u_capacity / D``: the first inner restrainer, the end of regime V; above ``stiffening``
        by at least the length of regime IV.
    g : float
        Gravitational acceleration, m/s^2.

    Returns
    -------
    TripleIsolator

    Raises
    ------
    ValueError
        Naming the parameter and what is allowed: a ratio out of range, targets no such bearing meets
        (``beta_eff`` too large for the proportions), ``D`` not in regime III, or a capacity below
        the end of regime IV.
    """
    M, T_eff, beta_eff = _check_target(M, T_eff, beta_eff)
    D, g = _positive("D", D), _positive("g", g)
    lam = check_range("inner_radius", inner_radius, 0.0, 1.0, False, False)
    a = check_range("mu1_ratio", mu1_ratio, 0.0, 1.0, False, True)
    c = check_range("mu3_ratio", mu3_ratio, 1.0, math.inf, True, False)
    sigma = check_range("stiffening", stiffening, 1.0, math.inf, False, False)
    rho = check_range("capacity", capacity, sigma, math.inf, False, False)
    if beta_eff == 0.0:
        raise ValueError("beta_eff = 0.0 is out of range for a triple friction pendulum (friction dissipates "
                         "energy); allowed range: 0 < value < 2/pi")
    k = (2.0 * math.pi / T_eff) ** 2 / g
    B = math.pi * beta_eff * k * D / 2.0
    q = 2.0 * lam * (1.0 - a)
    p = q + (1.0 + lam) * (c - 1.0)
    kappa = c - p / 2.0
    gamma = p * (c - 1.0) + q * (c - a) - p * p / 2.0
    s = gamma / kappa**2
    disc = (k * D + B) ** 2 - 2.0 * (2.0 + s) * B * k * D
    if kappa <= 0.0 or disc < 0.0 or B >= k * D:
        raise ValueError(f"beta_eff = {beta_eff!r} is out of range for a triple friction pendulum of inner_radius = "
                         f"{lam!r}, mu1_ratio = {a!r}, mu3_ratio = {c!r} at D = {D!r} m, T_eff = {T_eff!r} s "
                         "(no friction level meets it); allowed: a smaller beta_eff, or mu1_ratio and mu3_ratio "
                         "closer to 1")
    mu_e = ((k * D + B) - math.sqrt(disc)) / (2.0 + s)
    mu2 = mu_e / kappa
    L = D / (2.0 * (k * D - mu_e))
    L1 = lam * L
    mu1, mu3 = a * mu2, c * mu2
    u2star = p * L * mu2
    if u2star >= D:
        raise ValueError(f"D = {D!r} m is not in regime III of the triple friction pendulum of mu1_ratio = {a!r}, "
                         f"mu3_ratio = {c!r}, inner_radius = {lam!r} (regime III starts at {u2star:.6g} m); allowed: "
                         "mu1_ratio and mu3_ratio closer to 1, or a larger D")
    d2 = (sigma * D - u2star) / 2.0 + L * (mu3 - mu2)
    u_dr4 = sigma * D + (L1 + L) * (mu3 - mu2)
    if rho * D <= u_dr4:
        raise ValueError(f"capacity = {rho!r} is out of range: regime IV of this bearing ends at {u_dr4 / D:.6g} D; "
                         f"allowed: capacity > {u_dr4 / D:.6g}")
    d1 = (rho * D - u_dr4) / 2.0 + L1 * (mu3 - mu1)
    out = TripleIsolator(M, (L1, L, L), (mu1, mu2, mu3), (d1, d2, d2), g)
    out.bearing()           # the admissible set of isoslide.model.tfp, checked
    return out
