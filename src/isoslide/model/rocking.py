"""Contents that rock: the rigid rectangular block of Housner (1963) and its closed forms.

The block is rigid and uniform, of half-width ``b`` and half-height ``h`` (metres), standing on a
floor that friction keeps it from sliding on.  It rocks about one bottom corner at a time.

Geometry and inertia
--------------------
``R = sqrt(b^2 + h^2)`` (m) is the distance from a corner to the centre of mass, ``alpha =
atan(b/h)`` (rad) the slenderness angle, ``I_O = 4/3 m R^2`` the moment of inertia about a corner
and ``p = sqrt(3 g / (4 R))`` (rad/s) the frequency parameter.

Sign convention and equation of motion
--------------------------------------
``theta`` (rad) is the tilt; ``theta > 0`` means rocking on the right corner (the corner at
``+b`` on the ``x`` axis; the block leans towards ``+x``), ``theta < 0`` on the left corner.
``A_F`` (m/s^2) is the floor's absolute horizontal acceleration, positive towards ``+x``, and
``a_v`` (m/s^2) its vertical acceleration, positive upwards.  In the floor's frame the block
feels the inertial force ``-m A_F``, so a floor accelerating towards ``-x`` tips it onto its right
corner.  Moments about the pivot give, with ``s = sgn(theta)``::

    theta'' = -p^2 [ (1 + a_v/g) sin(s alpha - theta) + (A_F/g) cos(s alpha - theta) ]

Mirroring the floor (``A_F -> -A_F``) mirrors the response (``theta -> -theta``).  With ``psi =
s theta >= 0`` the tilt measured on the current corner, ``psi'' = -p^2 [ (1 + a_v/g) sin(alpha -
psi) + s (A_F/g) cos(alpha - psi) ]``, which depends on the floor only through ``s A_F``.

The contact force on the block at the pivot, ``(H, V)`` (horizontal, vertical; N), follows from
the motion of the centre of mass::

    H / m = A_F + s R [cos(alpha - psi) psi'' + sin(alpha - psi) psi'^2]
    V / m = g + a_v + R [sin(alpha - psi) psi'' - cos(alpha - psi) psi'^2]

At rest ``H = m A_F`` and ``V = m (g + a_v)``.

Uplift, impact, overturning
---------------------------
From rest the block uplifts (Shenton 1996) when ``|A_F| > (g + a_v) tan(alpha)``, provided static
friction holds the corner, which at that instant needs ``mu_s > b/h``; with ``mu_s < b/h`` the
block slides first.  At ``theta = 0`` the block strikes the floor with its other corner and rocks
on about it; the angular velocity keeps its sign and is multiplied by the restitution ``e``,
Housner's value from conservation of angular momentum about the new corner being ``e = 1 - 3/2
sin^2(alpha)``, so a fraction ``e^2`` of the kinetic energy is kept.  The block overturns when
``|theta|`` reaches ``pi/2``.

Energy of free rocking
----------------------
On a quiet floor (``A_F = a_v = 0``) the energy per unit ``m g R``, ``E = psi'^2/(2 p^2) +
cos(alpha - psi) - cos(alpha)`` (zero at rest), is conserved between impacts and multiplied by
``e^2`` at each impact.  The block passes its unstable equilibrium ``psi = alpha`` (and then falls
over) when ``E >= 1 - cos(alpha)``.

Dimensionless groups
--------------------
The groups the engine will use for rocking contents (:func:`groups_of`; they continue the
numbering of :mod:`isoslide.groups`):

=====  ====================  =========================================================
group  definition            meaning
=====  ====================  =========================================================
Pi18   b / h                 aspect ratio, ``tan(alpha)``
Pi19   p T_p                 block frequency parameter over the pulse's
Pi20   e                     coefficient of restitution of the angular velocity
Pi21   a_p / (g tan alpha)   pulse amplitude over the uplift acceleration
=====  ====================  =========================================================

Closed forms of the linearised (slender) block
----------------------------------------------
For small ``alpha`` (``sin(alpha - psi) ~ alpha - psi``, ``cos ~ 1``) and no vertical motion the
equation is ``psi'' = p^2 (psi - alpha - s A_F / g)``: hyperbolic.  Released from rest at
``theta0`` it reaches ``theta = 0`` after a quarter of Housner's period ``T = (4/p)
arccosh(1 / (1 - theta0/alpha))`` (:func:`housner_period`).  Its response to a rectangular pulse,
its first impact and the least pulse amplitude that overturns it are
:func:`rectangular_pulse_response`, :func:`rectangular_pulse_first_impact` and
:func:`rectangular_overturn_ratio`.

References
----------
G. W. Housner (1963), The behavior of inverted pendulum structures during earthquakes, Bull.
Seism. Soc. Am. 53(2).  H. W. Shenton III (1996), Criteria for initiation of slide, rock, and
slide-rock rigid-body modes, J. Eng. Mech. 122(7).  N. Makris and Y. Roussos (2000), Rocking
response of rigid blocks under near-source ground motions, Geotechnique 50(3).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import quad

from .validation import check_range

__all__ = ["Block", "G_STANDARD", "free_rocking_quarter_period", "groups_of", "housner_period",
           "housner_restitution", "impact_energy_ratio", "rectangular_overturn_amplitude",
           "rectangular_overturn_ratio", "rectangular_pulse_first_impact", "rectangular_pulse_response",
           "uplift_acceleration"]

G_STANDARD = 9.80665
"""Standard gravity (m/s^2), the default ``g``."""


def housner_restitution(alpha: float) -> float:
    """Housner's coefficient of restitution ``e = 1 - 3/2 sin^2(alpha)`` of a uniform rectangular block.

    Parameters
    ----------
    alpha : float
        Slenderness angle ``atan(b/h)`` (rad), ``0 < alpha < pi/2``.

    Returns
    -------
    float
        Ratio of the angular velocity just after an impact to the one just before (dimensionless);
        conservation of angular momentum about the corner that strikes the floor.
    """
    a = check_range("alpha", alpha, 0.0, 0.5 * math.pi, lo_in=False, hi_in=False)
    return 1.0 - 1.5 * math.sin(a) ** 2


@dataclass(frozen=True)
class Block:
    """A rigid uniform rectangular block that rocks on its bottom corners.

    Attributes
    ----------
    b : float
        Half-width (m), positive and finite.
    h : float
        Half-height (m), positive and finite.
    restitution : float or None
        Coefficient of restitution ``e`` of the angular velocity at an impact (dimensionless), in
        ``0 < e <= 1 - 3/2 sin^2(alpha)`` (Housner's value, which angular momentum conservation
        allows at most); ``None`` takes Housner's value.

    Raises
    ------
    ValueError
        A value out of its range; the message names the parameter, its value and the range.
    """

    b: float
    h: float
    restitution: float | None = None

    def __post_init__(self):
        b = check_range("b", self.b, 0.0, math.inf, lo_in=False, hi_in=False)
        h = check_range("h", self.h, 0.0, math.inf, lo_in=False, hi_in=False)
        object.__setattr__(self, "b", b)
        object.__setattr__(self, "h", h)
        if not (math.isfinite(math.hypot(b, h)) and math.atan2(b, h) > 0.0):
            raise ValueError(f"b = {b!r}, h = {h!r} give no finite block with alpha > 0; allowed: "
                             "b/h representable and sqrt(b^2 + h^2) finite")
        if self.restitution is not None:
            e = check_range("restitution", self.restitution, 0.0, self.housner_restitution,
                            lo_in=False, hi_in=True)
            object.__setattr__(self, "restitution", e)

    @classmethod
    def from_slenderness(cls, alpha: float, R: float, restitution: float | None = None) -> Block:
        """The block of slenderness ``alpha`` (rad, ``0 < alpha < pi/2``) and size ``R`` (m, > 0).

        ``b = R sin(alpha)``, ``h = R cos(alpha)``.
        """
        a = check_range("alpha", alpha, 0.0, 0.5 * math.pi, lo_in=False, hi_in=False)
        r = check_range("R", R, 0.0, math.inf, lo_in=False, hi_in=False)
        return cls(r * math.sin(a), r * math.cos(a), restitution)

    @property
    def R(self) -> float:
        """Distance from a bottom corner to the centre of mass, ``sqrt(b^2 + h^2)`` (m)."""
        return math.hypot(self.b, self.h)

    @property
    def alpha(self) -> float:
        """Slenderness angle ``atan(b/h)`` (rad)."""
        return math.atan2(self.b, self.h)

    @property
    def housner_restitution(self) -> float:
        """Housner's ``e = 1 - 3/2 sin^2(alpha)`` (dimensionless)."""
        return housner_restitution(self.alpha)

    @property
    def e(self) -> float:
        """The coefficient of restitution in use: :attr:`restitution`, else Housner's."""
        return self.housner_restitution if self.restitution is None else self.restitution

    def p(self, g: float = G_STANDARD) -> float:
        """Frequency parameter ``sqrt(3 g / (4 R))`` (rad/s) for gravity ``g`` (m/s^2)."""
        g = _check_g(g)
        return math.sqrt(0.75 * g / self.R)


def _check_g(g) -> float:
    return check_range("g", g, 0.0, math.inf, lo_in=False, hi_in=False)


def groups_of(block: Block, a_p: float, T_p: float, g: float = G_STANDARD) -> dict:
    """The dimensionless groups of a rocking block under a pulse.

    Parameters
    ----------
    block : Block
        The block.
    a_p : float
        Pulse acceleration amplitude (m/s^2), positive.
    T_p : float
        Pulse period (s), positive.
    g : float
        Gravity (m/s^2).

    Returns
    -------
    dict
        ``{"pi18": b/h, "pi19": p T_p, "pi20": e, "pi21": a_p / (g tan(alpha))}``.
    """
    a_p = check_range("a_p", a_p, 0.0, math.inf, lo_in=False, hi_in=False)
    T_p = check_range("T_p", T_p, 0.0, math.inf, lo_in=False, hi_in=False)
    g = _check_g(g)
    tan_a = block.b / block.h
    return {"pi18": tan_a, "pi19": block.p(g) * T_p, "pi20": block.e, "pi21": a_p / (g * tan_a)}


def uplift_acceleration(block: Block, g: float = G_STANDARD, a_v: float = 0.0) -> float:
    """Least floor acceleration ``(g + a_v) tan(alpha)`` (m/s^2) that uplifts the block from rest.

    Parameters
    ----------
    block : Block
        The block.
    g : float
        Gravity (m/s^2).
    a_v : float
        Vertical floor acceleration at that instant (m/s^2, upwards positive), ``g + a_v > 0``.

    Returns
    -------
    float
        ``|A_F|`` must exceed this for rocking to start (with friction holding, ``mu_s > b/h``).
    """
    g = _check_g(g)
    a_v = check_range("a_v", a_v, -g, math.inf, lo_in=False, hi_in=False)
    return (g + a_v) * block.b / block.h


def impact_energy_ratio(block: Block) -> float:
    """Fraction ``e^2`` of the kinetic energy (and of the whole energy) kept across an impact.

    At ``theta = 0`` both corners are on the floor and the potential energy is the same on either
    side, so the ratio of the kinetic energies, ``(e theta')^2 / theta'^2``, is also the ratio of the
    energies.
    """
    return block.e ** 2


def _check_theta0(block: Block, theta0) -> float:
    return check_range("theta0", theta0, 0.0, block.alpha, lo_in=False, hi_in=False)


def housner_period(block: Block, theta0: float, g: float = G_STANDARD) -> float:
    """Housner's period of free rocking of the linearised block released from rest at ``theta0``.

    ``T = (4/p) arccosh(1 / (1 - theta0/alpha))`` (s): the linear equation ``theta'' = p^2 (theta -
    alpha)`` gives ``theta = alpha - (alpha - theta0) cosh(p t)``, which reaches 0 after ``T/4``;
    impacts are not counted (each quarter is one way from an apex to the floor).  Relative to the
    exact quarter period (:func:`free_rocking_quarter_period`) it errs by ``O(alpha^2)``: the
    linearisation drops ``(alpha - theta)^2 / 6`` relative from ``sin(alpha - theta)``.

    Parameters
    ----------
    block : Block
        The block.
    theta0 : float
        Release tilt (rad), ``0 < theta0 < alpha``.
    g : float
        Gravity (m/s^2).

    Returns
    -------
    float
        The period ``T`` (s).
    """
    t0 = _check_theta0(block, theta0)
    return 4.0 / block.p(g) * math.acosh(1.0 / (1.0 - t0 / block.alpha))


def free_rocking_quarter_period(block: Block, theta0: float, g: float = G_STANDARD) -> float:
    """Exact (nonlinear) time from release at rest at ``theta0`` to the impact at ``theta = 0``.

    On a quiet floor energy is conserved until the impact, ``theta'^2 = 2 p^2 [cos(alpha - theta0)
    - cos(alpha - theta)]``, so ``t = integral_0^theta0 dtheta / |theta'|``.  The integrand has an
    inverse square-root singularity at ``theta0``; the substitution ``theta = theta0 (1 - s^2)`` and
    ``cos A - cos B = 2 sin((A+B)/2) sin((B-A)/2)`` turn it into the smooth integral::

        t = sqrt(2 theta0) / p  integral_0^1  ds / sqrt(sin(alpha - theta0 + theta0 s^2/2) sinc(theta0 s^2/2))

    with ``sinc(x) = sin(x)/x``, evaluated by :func:`scipy.integrate.quad` (no cancellation, no
    singularity).

    Parameters
    ----------
    block : Block
        The block.
    theta0 : float
        Release tilt (rad), ``0 < theta0 < alpha`` (the time grows without bound as ``theta0 ->
        alpha``, the unstable equilibrium).
    g : float
        Gravity (m/s^2).

    Returns
    -------
    float
        The quarter period (s); the period of free rocking without impact losses is four times it.
    """
    t0 = _check_theta0(block, theta0)
    alpha = block.alpha

    def f(s):
        x = 0.5 * t0 * s * s
        sinc = math.sin(x) / x if x > 0.0 else 1.0
        return 1.0 / math.sqrt(math.sin(alpha - t0 + x) * sinc)

    val, _ = quad(f, 0.0, 1.0, epsabs=0.0, epsrel=1e-13, limit=200)
    return math.sqrt(2.0 * t0) / block.p(g) * val


def _rect_args(block: Block, a, t_d, g):
    a = check_range("a", a, -math.inf, math.inf, lo_in=False, hi_in=False)
    t_d = check_range("t_d", t_d, 0.0, math.inf, lo_in=True, hi_in=False)
    g = _check_g(g)
    return a, t_d, g


def rectangular_pulse_response(block: Block, a: float, t_d: float, t, g: float = G_STANDARD):
    """Tilt and angular velocity of the linearised block under a rectangular floor pulse, from rest.

    The floor accelerates at ``A_F = a`` (m/s^2) for ``0 <= t < t_d`` and is quiet afterwards.  With
    ``beta = |a| / (g alpha)`` the block uplifts when ``beta > 1`` (linearised threshold ``g alpha``),
    onto the corner ``s = -sgn(a)``; on that corner ``psi = s theta`` obeys ``psi'' = p^2 (psi -
    alpha + |a|/g)`` during the pulse and ``psi'' = p^2 (psi - alpha)`` after it, so::

        psi(t) = alpha (beta - 1) (cosh(p t) - 1)                                      0 <= t <= t_d
        psi(t) = alpha + (psi_d - alpha) cosh(p (t - t_d)) + (psi'_d / p) sinh(p (t - t_d))   t >= t_d

    with ``psi_d = alpha (beta - 1) (cosh(p t_d) - 1)`` and ``psi'_d = alpha (beta - 1) p sinh(p
    t_d)``.  This holds until the first impact (:func:`rectangular_pulse_first_impact`) or, if the
    block overturns, while the linearisation lasts (``psi`` well below 1).  With ``beta <= 1`` the
    block stays at rest (``theta = 0``).

    Parameters
    ----------
    block : Block
        The block (its ``p`` and ``alpha``).
    a : float
        Floor acceleration during the pulse (m/s^2), signed.
    t_d : float
        Pulse duration (s), ``>= 0``.
    t : array_like
        Times (s), ``t >= 0``.
    g : float
        Gravity (m/s^2).

    Returns
    -------
    theta, omega : ndarray
        Tilt (rad) and angular velocity (rad/s) at ``t``.
    """
    a, t_d, g = _rect_args(block, a, t_d, g)
    t = np.asarray(t, dtype=float)
    alpha, p = block.alpha, block.p(g)
    beta = abs(a) / (g * alpha)
    if beta <= 1.0:
        return np.zeros_like(t), np.zeros_like(t)
    s = -math.copysign(1.0, a)
    c = alpha * (beta - 1.0)
    during = t < t_d
    pt = p * np.where(during, t, 0.0)
    psi_in = c * (np.cosh(pt) - 1.0)
    om_in = c * p * np.sinh(pt)
    psi_d = c * (math.cosh(p * t_d) - 1.0)
    om_d = c * p * math.sinh(p * t_d)
    q = p * np.maximum(t - t_d, 0.0)
    psi_out = alpha + (psi_d - alpha) * np.cosh(q) + (om_d / p) * np.sinh(q)
    om_out = (psi_d - alpha) * p * np.sinh(q) + om_d * np.cosh(q)
    psi = np.where(during, psi_in, psi_out)
    om = np.where(during, om_in, om_out)
    return s * psi, s * om


def rectangular_pulse_first_impact(block: Block, a: float, t_d: float, g: float = G_STANDARD) -> float:
    """Time (s) of the first impact of the linearised block after a rectangular pulse from rest.

    During the pulse ``psi`` only grows; after it, ``x = psi - alpha = A exp(p tau) + B exp(-p
    tau)`` (``tau = t - t_d``) with ``A = (x_d + psi'_d/p)/2`` and ``B = (x_d - psi'_d/p)/2``.  The
    block returns to ``psi = 0`` when ``A z^2 + alpha z + B = 0`` with ``z = exp(p tau) > 1``; for
    ``A < 0`` (no overturning, both ``A`` and ``B`` negative) that is the larger root ``z = (-alpha
    - sqrt(alpha^2 - 4 A B)) / (2 A)``.

    Returns
    -------
    float
        ``t_d + ln(z)/p``; ``inf`` when the block overturns (``A >= 0``, see
        :func:`rectangular_overturn_ratio`); ``nan`` when it never uplifts (``|a| <= g alpha``).
    """
    a, t_d, g = _rect_args(block, a, t_d, g)
    alpha, p = block.alpha, block.p(g)
    beta = abs(a) / (g * alpha)
    if beta <= 1.0:
        return math.nan
    c = alpha * (beta - 1.0)
    x_d = c * (math.cosh(p * t_d) - 1.0) - alpha
    v_d = c * math.sinh(p * t_d)  # psi'_d / p
    A = 0.5 * (x_d + v_d)
    B = 0.5 * (x_d - v_d)
    if A >= 0.0:
        return math.inf
    z = (-alpha - math.sqrt(alpha * alpha - 4.0 * A * B)) / (2.0 * A)
    return t_d + math.log(z) / p


def rectangular_overturn_ratio(p_td: float) -> float:
    """Least ``a / (g alpha)`` of a rectangular pulse of duration ``t_d`` that overturns the linearised block.

    Derivation: after the pulse, ``x = psi - alpha`` obeys ``x'' = p^2 x``, whose invariant ``x'^2/p^2
    - x^2`` splits the phase plane at the separatrix ``x'/p = -x``; the block passes ``psi = alpha``
    (and overturns) exactly when ``x_d + x'_d / p > 0`` at the end of the pulse.  With the response
    of :func:`rectangular_pulse_response`, ``psi_d + psi'_d/p = alpha (beta - 1) (exp(p t_d) - 1)``,
    so it overturns when ``(beta - 1)(exp(p t_d) - 1) > 1``, that is::

        beta > beta_c = 1 / (1 - exp(-p t_d))

    (for ``beta = beta_c`` it creeps up to the unstable equilibrium).  No impact can come first:
    ``psi`` grows monotonically during the pulse.  Long pulses need ``beta -> 1`` (the uplift
    threshold); short ones ``beta ~ 1/(p t_d)``, a fixed velocity step ``a t_d ~ g alpha / p``.  The
    exact block's threshold differs by ``O(alpha^2)`` relative for ``p t_d`` of order one.

    Parameters
    ----------
    p_td : float
        ``p t_d`` (dimensionless), positive.

    Returns
    -------
    float
        ``beta_c`` (dimensionless).
    """
    x = check_range("p_td", p_td, 0.0, math.inf, lo_in=False, hi_in=False)
    return -1.0 / math.expm1(-x)


def rectangular_overturn_amplitude(block: Block, t_d: float, g: float = G_STANDARD) -> float:
    """Least ``|a|`` (m/s^2) of a rectangular floor pulse of duration ``t_d`` (s) that overturns the linearised block.

    ``g alpha beta_c(p t_d)`` with :func:`rectangular_overturn_ratio`.
    """
    t_d = check_range("t_d", t_d, 0.0, math.inf, lo_in=False, hi_in=False)
    g = _check_g(g)
    return g * block.alpha * rectangular_overturn_ratio(block.p(g) * t_d)
