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

The effective period is ``T_eff = 2 pi sqrt(M / K_eff)``.  This module evaluates those formulas and
inverts them: given ``T_eff``, ``beta_eff`` and ``D`` it returns the linear, bilinear and
friction-pendulum isolators that share them (:func:`design_linear`, :func:`design_bilinear`,
:func:`design_friction_pendulum`), as the keyword arguments of
:meth:`isoslide.Scene.from_physical` (:func:`scene_parameters`).  SI units throughout.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..scene import G_STANDARD
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
