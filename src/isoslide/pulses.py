"""Ground-acceleration pulses in dimensionless form.

Every pulse is written in dimensionless time ``tau = t / T_p`` with unit
acceleration amplitude, ``p(tau) = a_g(t) / a_p`` and ``max |p| = 1``.  Ground
velocity and displacement are therefore in units of ``a_p T_p`` and
``a_p T_p**2``; the ground is at rest (zero velocity and displacement) at
``tau_start``.

Two layers live here:

* scalar, numba-compiled evaluators :func:`accel_at` and :func:`jerk_at`,
  dispatching on an integer ``code`` and a float64 ``params`` array, which the
  solver kernel calls inside its integration loop;
* the frozen :class:`Pulse` description with vectorised numpy
  :meth:`Pulse.accel` (an independent implementation, used to cross-check the
  compiled one), and exact closed-form :meth:`Pulse.velocity` and
  :meth:`Pulse.displacement`.

Shapes
------
==========================  =======================================  =========================
name                        T_p is                                   support [tau_start, tau_end)
==========================  =======================================  =========================
``ricker``                  period of peak Fourier amplitude         [-2, 2) (truncated)
``rectangular``             pulse duration                           [0, 1)
``antisymmetric_ricker``    period of peak Fourier amplitude         [-2.5, 2.5) (truncated)
``makris_a``                period 2 pi/omega_p of the sine cycle    [0, 1)
``makris_b``                period 2 pi/omega_p of the cosine cycle  [0, 1)
``makris_cn``               period 2 pi/omega_p of the harmonic      [0, n + 1/2 - phi/pi)
``mavroeidis_papageorgiou`` 1/f_p, period of the modulated harmonic  [-gamma/2, gamma/2)
sampled record              chosen by the caller (``dtau = dt/T_p``)  first to last sample
==========================  =======================================  =========================

Final ground velocity and displacement (at ``tau_end``, units ``a_p T_p`` and
``a_p T_p**2``): both vanish for the two Rickers (up to the ~1e-16
truncation), Makris B and Cn, and for Mavroeidis-Papageorgiou with integer
``gamma`` or ``cos(nu) = 0``; Makris A ends at rest with a permanent
displacement ``1/(2 pi)``; the rectangular pulse ends with velocity 1 (the
ground then drifts, as in Newmark 1965).

Conventions
-----------
``p`` is right-continuous at its breakpoints (e.g. the rectangular pulse is 1
on ``[0, 1)`` and 0 at ``tau = 1``).  Outside ``[tau_start, tau_end)`` the
acceleration is exactly zero.  ``breakpoints`` lists every time where ``p`` or
``dp/dtau`` jumps (the truncation points of the two Rickers, where ``p`` jumps
by less than 1e-15, are ``tau_start`` and ``tau_end`` themselves).
"""

from __future__ import annotations

import functools
import inspect
import math
import numbers
from dataclasses import dataclass, field

import numpy as np
from numba import njit

from . import jit_cache
from .model.validation import check_range
from scipy.optimize import brentq

RICKER = 0
RECTANGULAR = 1
ANTISYMMETRIC_RICKER = 2
MAKRIS_A = 3
MAKRIS_B = 4
MAKRIS_CN = 5
MAVROEIDIS_PAPAGEORGIOU = 6
SAMPLED = 7

_PI = math.pi
_TWO_PI = 2.0 * math.pi
_PI2 = math.pi * math.pi
_C_ANTI = 2.0 * math.pi / math.sqrt(3.0)
"""Scale of the antisymmetric Ricker: ``s = _C_ANTI * tau`` is the Gaussian's argument."""

RICKER_HALF_WIDTH = 2.0
"""Half-width (in T_p) at which the symmetric Ricker is truncated: |p| < 6e-16 beyond it."""

ANTISYMMETRIC_RICKER_HALF_WIDTH = 2.5
"""Half-width (in T_p) at which the antisymmetric Ricker is truncated: |p| < 7.2e-16 beyond it."""

_S_PEAK_ANTI = math.sqrt(3.0 - math.sqrt(6.0))
ANTISYMMETRIC_RICKER_BETA = _S_PEAK_ANTI * (3.0 - _S_PEAK_ANTI**2) * math.exp(-0.5 * _S_PEAK_ANTI**2)
"""Peak of ``|s (s^2 - 3) exp(-s^2/2)|`` (at ``s^2 = 3 - sqrt 6``): 1.38012 (the "beta = 1.38"
of Vassiliou & Makris 2011), so that the normalised wavelet has ``max |p| = 1``."""


# ---------------------------------------------------------------------------
# compiled scalar evaluators (solver kernel)
# ---------------------------------------------------------------------------

@njit(cache=True)
def _sampled_segment(params, tau):
    """Index ``k`` of the segment ``[knot_k, knot_k+1)`` holding ``tau``, or -1 outside.

    Knots are ``tau0 + dtau * k`` exactly as :func:`sampled` computes them, so a
    ``tau`` equal to a knot always selects the segment starting there.
    """
    tau0 = params[0]
    dtau = params[1]
    n = params.shape[0] - 2
    if tau < tau0 or tau >= tau0 + dtau * (n - 1):
        return -1
    k = int(math.floor((tau - tau0) / dtau))
    if k > n - 2:
        k = n - 2
    if k < 0:
        k = 0
    if k > 0 and tau < tau0 + dtau * k:
        k -= 1
    elif k < n - 2 and tau >= tau0 + dtau * (k + 1):
        k += 1
    return k


@njit(cache=True, inline="always")
def _mp_phases(params, tau):
    """Support and phases of the Mavroeidis-Papageorgiou pulse at ``tau`` (units of T_p).

    Parameters
    ----------
    params : ndarray of float64
        ``(gamma, nu, 1 / peak)`` of :func:`mavroeidis_papageorgiou`, :attr:`Pulse.param_array`.
    tau : float
        Dimensionless time ``t / T_p``.

    Returns
    -------
    tuple
        ``(inside, gamma, a, x)``: whether ``tau`` lies in the support ``[-gamma/2, gamma/2)``, the
        envelope's length ``gamma`` (units of T_p), its angular frequency ``a = 2 pi / gamma`` (rad
        per T_p) and the harmonic's phase ``x = 2 pi tau + nu`` (rad); ``a`` and ``x`` are 0 outside.
    """
    gamma = params[0]
    half = 0.5 * gamma
    if tau < -half or tau >= half:
        return False, gamma, 0.0, 0.0
    return True, gamma, _TWO_PI / gamma, _TWO_PI * tau + params[1]


@njit(cache=True)
def accel_at(code, params, tau):
    """Dimensionless ground acceleration ``p(tau) = a_g / a_p`` (scalar, compiled).

    Parameters
    ----------
    code : int
        Shape code (``RICKER``, ..., ``SAMPLED``).
    params : ndarray of float64
        Shape parameters, :attr:`Pulse.param_array`.
    tau : float
        Dimensionless time ``t / T_p``.

    Returns
    -------
    float
        ``a_g / a_p``; 0 outside the support, NaN for an unknown code.
    """
    if code == RICKER:
        if tau < -RICKER_HALF_WIDTH or tau >= RICKER_HALF_WIDTH:
            return 0.0
        s = _PI2 * tau * tau
        return (1.0 - 2.0 * s) * math.exp(-s)
    if code == RECTANGULAR:
        if 0.0 <= tau < 1.0:
            return 1.0
        return 0.0
    if code == ANTISYMMETRIC_RICKER:
        if tau < -ANTISYMMETRIC_RICKER_HALF_WIDTH or tau >= ANTISYMMETRIC_RICKER_HALF_WIDTH:
            return 0.0
        s = _C_ANTI * tau
        return params[0] * s * (s * s - 3.0) * math.exp(-0.5 * s * s)
    if code == MAKRIS_A:
        if 0.0 <= tau < 1.0:
            return math.sin(_TWO_PI * tau)
        return 0.0
    if code == MAKRIS_B:
        if 0.0 <= tau < 1.0:
            return math.cos(_TWO_PI * tau)
        return 0.0
    if code == MAKRIS_CN:
        if 0.0 <= tau < params[1]:
            return math.cos(_TWO_PI * tau + params[0])
        return 0.0
    if code == MAVROEIDIS_PAPAGEORGIOU:
        inside, gamma, a, x = _mp_phases(params, tau)
        if not inside:
            return 0.0
        return -params[2] * (math.sin(a * tau) * math.cos(x) / gamma
                             + (1.0 + math.cos(a * tau)) * math.sin(x))
    if code == SAMPLED:
        k = _sampled_segment(params, tau)
        if k < 0:
            return 0.0
        w = (tau - (params[0] + params[1] * k)) / params[1]
        return (1.0 - w) * params[2 + k] + w * params[3 + k]
    return math.nan


@njit(cache=True)
def jerk_at(code, params, tau):
    """Time derivative ``dp/dtau`` of :func:`accel_at` (right derivative at breakpoints).

    Same arguments as :func:`accel_at`; the result is in units of ``a_p / T_p``.
    """
    if code == RICKER:
        if tau < -RICKER_HALF_WIDTH or tau >= RICKER_HALF_WIDTH:
            return 0.0
        s = _PI2 * tau * tau
        return 2.0 * _PI2 * tau * (2.0 * s - 3.0) * math.exp(-s)
    if code == RECTANGULAR:
        return 0.0
    if code == ANTISYMMETRIC_RICKER:
        if tau < -ANTISYMMETRIC_RICKER_HALF_WIDTH or tau >= ANTISYMMETRIC_RICKER_HALF_WIDTH:
            return 0.0
        s2 = (_C_ANTI * tau) ** 2
        return -params[0] * _C_ANTI * (s2 * s2 - 6.0 * s2 + 3.0) * math.exp(-0.5 * s2)
    if code == MAKRIS_A:
        if 0.0 <= tau < 1.0:
            return _TWO_PI * math.cos(_TWO_PI * tau)
        return 0.0
    if code == MAKRIS_B:
        if 0.0 <= tau < 1.0:
            return -_TWO_PI * math.sin(_TWO_PI * tau)
        return 0.0
    if code == MAKRIS_CN:
        if 0.0 <= tau < params[1]:
            return -_TWO_PI * math.sin(_TWO_PI * tau + params[0])
        return 0.0
    if code == MAVROEIDIS_PAPAGEORGIOU:
        inside, gamma, a, x = _mp_phases(params, tau)
        if not inside:
            return 0.0
        sa = math.sin(a * tau)
        ca = math.cos(a * tau)
        return -params[2] * ((a / gamma * ca + _TWO_PI * (1.0 + ca)) * math.cos(x)
                             - (_TWO_PI / gamma + a) * sa * math.sin(x))
    if code == SAMPLED:
        k = _sampled_segment(params, tau)
        if k < 0:
            return 0.0
        return (params[3 + k] - params[2 + k]) / params[1]
    return math.nan


# ---------------------------------------------------------------------------
# Pulse description with vectorised, exact kinematics
# ---------------------------------------------------------------------------

@dataclass(frozen=True)
class Pulse:
    """A dimensionless ground-acceleration pulse.

    Build pulses with the factories (:func:`ricker`, :func:`makris_cn`, ...)
    or :func:`get_pulse`; they fill ``params`` with normalisation constants.

    Attributes
    ----------
    name : str
        Shape name, e.g. ``"ricker"``.
    code : int
        Integer shape code used by the compiled kernel.
    params : tuple of float
        Shape parameters passed to the kernel as a float64 array.
    tau_start, tau_end : float
        Support of the pulse in units of T_p; the ground is at rest at
        ``tau_start`` and ``p = 0`` from ``tau_end`` on.
    breakpoints : tuple of float
        Times (units of T_p) where ``p`` or ``dp/dtau`` jumps; integration
        steps end exactly there.
    """

    name: str
    code: int
    params: tuple = ()
    tau_start: float = 0.0
    tau_end: float = 1.0
    breakpoints: tuple = field(default=(), repr=False)

    @functools.cached_property
    def param_array(self) -> np.ndarray:
        """Shape parameters as a contiguous float64 array (kernel input; computed once, not to be written to)."""
        return np.asarray(self.params if self.params else (0.0,), dtype=np.float64)

    @functools.cached_property
    def breakpoint_array(self) -> np.ndarray:
        """Sorted breakpoints inside the support, plus ``tau_end`` (kernel input; computed once, not to be written to)."""
        b = np.unique(np.append(np.asarray(self.breakpoints, dtype=np.float64), float(self.tau_end)))
        return np.ascontiguousarray(b[b > self.tau_start])

    def accel(self, tau):
        """Dimensionless ground acceleration ``a_g / a_p`` at ``tau`` (vectorised numpy).

        An implementation independent of :func:`accel_at` (same formulas,
        array code), so the two can check each other.
        """
        tau = np.asarray(tau, dtype=float)
        return _accel_np(self, tau)

    def velocity(self, tau):
        """Ground velocity in units of ``a_p T_p``, exact closed form (vectorised).

        Zero before ``tau_start``, constant after ``tau_end``.
        """
        tau = np.asarray(tau, dtype=float)
        t = np.clip(tau, self.tau_start, self.tau_end)
        return _kinematics(self, t)[0]

    def displacement(self, tau):
        """Ground displacement in units of ``a_p T_p**2``, exact closed form (vectorised).

        Zero before ``tau_start``; after ``tau_end`` it grows linearly with
        the final velocity (zero for most shapes).
        """
        tau = np.asarray(tau, dtype=float)
        t = np.clip(tau, self.tau_start, self.tau_end)
        d = _kinematics(self, t)[1]
        v_end = _kinematics(self, np.asarray(float(self.tau_end)))[0]
        return d + v_end * np.maximum(tau - self.tau_end, 0.0)

    @property
    def final_velocity(self) -> float:
        """Ground velocity at ``tau_end`` (units ``a_p T_p``)."""
        return float(self.velocity(self.tau_end))

    @property
    def final_displacement(self) -> float:
        """Ground displacement at ``tau_end`` (units ``a_p T_p**2``)."""
        return float(self.displacement(self.tau_end))


def _accel_np(pulse: Pulse, tau: np.ndarray) -> np.ndarray:
    """Vectorised ``p(tau)``; mirrors :func:`accel_at` branch by branch."""
    code, pa = pulse.code, pulse.param_array
    inside = (tau >= pulse.tau_start) & (tau < pulse.tau_end)
    if code == RICKER:
        s = _PI2 * tau**2
        p = (1.0 - 2.0 * s) * np.exp(-s)
    elif code == RECTANGULAR:
        p = np.ones_like(tau)
    elif code == ANTISYMMETRIC_RICKER:
        s = _C_ANTI * tau
        p = pa[0] * s * (s * s - 3.0) * np.exp(-0.5 * s * s)
    elif code == MAKRIS_A:
        p = np.sin(_TWO_PI * tau)
    elif code == MAKRIS_B:
        p = np.cos(_TWO_PI * tau)
    elif code == MAKRIS_CN:
        p = np.cos(_TWO_PI * tau + pa[0])
    elif code == MAVROEIDIS_PAPAGEORGIOU:
        p = _mp_accel_raw(tau, pa[0], pa[1]) * pa[2]
    elif code == SAMPLED:
        knots = pa[0] + pa[1] * np.arange(pa.size - 2)
        p = np.interp(tau, knots, pa[2:])
    else:
        raise ValueError(f"unknown pulse code {code!r}")
    return np.where(inside, p, 0.0)


def _mp_accel_raw(tau, gamma, nu):
    """Unnormalised Mavroeidis-Papageorgiou acceleration ``-B(tau)`` (d/dtau of ``_mp_vel_raw``)."""
    a = _TWO_PI / gamma
    x = _TWO_PI * tau + nu
    return -(np.sin(a * tau) * np.cos(x) / gamma + (1.0 + np.cos(a * tau)) * np.sin(x))


def _mp_vel_raw(tau, gamma, nu):
    """Unnormalised Mavroeidis-Papageorgiou velocity ``(1 + cos(2 pi tau/gamma)) cos(2 pi tau + nu) / (2 pi)``."""
    return (1.0 + np.cos(_TWO_PI * tau / gamma)) * np.cos(_TWO_PI * tau + nu) / _TWO_PI


def _sin_diff_over_k(k, x, x0, nu):
    """``(sin(k x + nu) - sin(k x0 + nu)) / k``, stable as ``k -> 0``."""
    dx = x - x0
    return np.cos(0.5 * k * (x + x0) + nu) * dx * np.sinc(k * dx / _TWO_PI)


def _kinematics(pulse: Pulse, t):
    """Exact ``(velocity, displacement)`` at times ``t`` inside ``[tau_start, tau_end]``.

    Each branch is ``F(t) - F(tau_start)`` for an antiderivative ``F``, so the
    ground is at rest at ``tau_start`` to the last bit.
    """
    code, pa = pulse.code, pulse.param_array
    t = np.asarray(t, dtype=float)
    if code == RICKER:
        h = RICKER_HALF_WIDTH
        eh = math.exp(-_PI2 * h * h)
        e = np.exp(-_PI2 * t * t)
        v = t * e + h * eh
        d = -(e - eh) / (2.0 * _PI2) + h * eh * (t + h)
        return v, d
    if code == RECTANGULAR:
        return t.copy(), 0.5 * t * t
    if code == ANTISYMMETRIC_RICKER:
        # p = -(1/beta) g'''(s), g(s) = exp(-s^2/2), s = c tau.
        c, inv_beta, t0 = _C_ANTI, pa[0], pulse.tau_start
        s, s0 = c * t, c * t0
        g2 = (s * s - 1.0) * np.exp(-0.5 * s * s)
        g2_0 = (s0 * s0 - 1.0) * math.exp(-0.5 * s0 * s0)
        g1 = -s * np.exp(-0.5 * s * s)
        g1_0 = -s0 * math.exp(-0.5 * s0 * s0)
        v = -inv_beta / c * (g2 - g2_0)
        d = -inv_beta / c * ((g1 - g1_0) / c - g2_0 * (t - t0))
        return v, d
    if code == MAKRIS_A:
        w = _TWO_PI * t
        return (1.0 - np.cos(w)) / _TWO_PI, t / _TWO_PI - np.sin(w) / _TWO_PI**2
    if code == MAKRIS_B:
        w = _TWO_PI * t
        return np.sin(w) / _TWO_PI, (1.0 - np.cos(w)) / _TWO_PI**2
    if code == MAKRIS_CN:
        phi = pa[0]
        w = _TWO_PI * t + phi
        v = (np.sin(w) - math.sin(phi)) / _TWO_PI
        d = (math.cos(phi) - np.cos(w)) / _TWO_PI**2 - t * math.sin(phi) / _TWO_PI
        return v, d
    if code == MAVROEIDIS_PAPAGEORGIOU:
        gamma, nu, inv_norm = pa[0], pa[1], pa[2]
        t0 = pulse.tau_start
        # velocity: p = inv_norm * d/dtau[(1 + cos(a tau)) cos(b tau + nu)] / (2 pi)
        v0 = float(_mp_vel_raw(np.asarray(t0), gamma, nu))  # 0 up to rounding (envelope zero)
        v = inv_norm * (_mp_vel_raw(t, gamma, nu) - v0)
        # (1 + cos a tau) cos(b tau + nu) = cos(b tau + nu) + cos((b+a) tau + nu)/2 + cos((b-a) tau + nu)/2
        a, b = _TWO_PI / gamma, _TWO_PI
        d = (_sin_diff_over_k(b, t, t0, nu) + 0.5 * _sin_diff_over_k(b + a, t, t0, nu)
             + 0.5 * _sin_diff_over_k(b - a, t, t0, nu)) * inv_norm / _TWO_PI
        d = d - inv_norm * v0 * (t - t0)
        return v, d
    if code == SAMPLED:
        return _sampled_kinematics(pa, t)
    raise ValueError(f"unknown pulse code {code!r}")


def _sampled_kinematics(pa: np.ndarray, t: np.ndarray):
    """Velocity and displacement of a piecewise-linear record for ``t`` inside the record.

    Integrated exactly: quadratic and cubic on each segment.
    """
    tau0, dtau, a = pa[0], pa[1], pa[2:]
    knots = tau0 + dtau * np.arange(a.size)
    slope = np.diff(a) / dtau
    v_knot = np.concatenate([[0.0], np.cumsum(0.5 * (a[1:] + a[:-1]) * dtau)])
    d_knot = np.concatenate([[0.0], np.cumsum(v_knot[:-1] * dtau + (2 * a[:-1] + a[1:]) * dtau**2 / 6)])
    k = np.clip(np.searchsorted(knots, t, side="right") - 1, 0, a.size - 2)
    s = t - knots[k]
    v = v_knot[k] + a[k] * s + 0.5 * slope[k] * s * s
    d = d_knot[k] + v_knot[k] * s + 0.5 * a[k] * s * s + slope[k] * s**3 / 6.0
    return v, d


def _peak_abs(f, df, lo: float, hi: float, per_unit: int = 512) -> tuple[float, float]:
    """``(max |f|, argmax)`` on ``[lo, hi]`` for a smooth ``f`` with derivative ``df``.

    A dense grid locates the candidate maxima; each is refined to machine
    precision by a root of ``df`` (Brent).
    """
    n = max(4097, int(per_unit * (hi - lo)) + 1)
    x = np.linspace(lo, hi, n)
    y = np.abs(f(x))
    i_best = int(np.argmax(y))
    best, where = float(y[i_best]), float(x[i_best])
    interior = np.flatnonzero((y[1:-1] >= y[:-2]) & (y[1:-1] >= y[2:]) & (y[1:-1] >= 0.99 * best)) + 1
    for i in interior:
        xl, xr = float(x[i - 1]), float(x[i + 1])
        fl, fr = float(df(np.asarray(xl))), float(df(np.asarray(xr)))
        if fl == 0.0 or fr == 0.0 or fl * fr > 0:
            continue
        r = brentq(lambda z: float(df(np.asarray(z))), xl, xr, xtol=1e-15, rtol=4 * np.finfo(float).eps)
        yr = abs(float(f(np.asarray(r))))
        if yr > best:
            best, where = yr, r
    return best, where


# ---------------------------------------------------------------------------
# validation
# ---------------------------------------------------------------------------

_check = check_range


# ---------------------------------------------------------------------------
# factories
# ---------------------------------------------------------------------------

def ricker() -> Pulse:
    """Symmetric Ricker wavelet (paper Eq. 3; Vassiliou & Makris 2011).

    ``p(tau) = (1 - 2 pi^2 tau^2) exp(-pi^2 tau^2)``, the second derivative of
    a Gaussian, ``max |p| = p(0) = 1``.

    ``T_p = 2 pi / omega_p`` is the period at which the Fourier amplitude of
    the acceleration peaks (``|P(f)| ~ f^2 exp(-f^2)`` in units of ``1/T_p``).
    Support ``[-2, 2)`` T_p: the wavelet is truncated where ``|p| < 6e-16``.
    Ground velocity ``tau exp(-pi^2 tau^2)`` (units ``a_p T_p``), displacement
    ``-exp(-pi^2 tau^2) / (2 pi^2)`` (units ``a_p T_p^2``), each shifted by
    the ~1e-17 values at ``tau = -2`` so the ground starts at rest; the final
    velocity and displacement are below 1e-16.
    """
    h = RICKER_HALF_WIDTH
    return Pulse("ricker", RICKER, (), -h, h, ())


def rectangular() -> Pulse:
    """Rectangular pulse of Newmark (1965): ``p = 1`` on ``0 <= tau < 1``.

    ``T_p`` is the pulse duration.  The ground ends with velocity ``1`` (units
    ``a_p T_p``) and drifts afterwards; displacement ``tau^2 / 2`` on the pulse.
    """
    return Pulse("rectangular", RECTANGULAR, (), 0.0, 1.0, (0.0,))


def antisymmetric_ricker() -> Pulse:
    """Antisymmetric Ricker wavelet of Vassiliou & Makris (2011).

    ``p(tau) = (1/beta) (4 pi^2 tau^2 / 3 - 3) (2 pi tau / sqrt 3) exp(-2 pi^2 tau^2 / 3)``,
    i.e. ``-(1/beta) d^3/ds^3 exp(-s^2/2)`` with ``s = 2 pi tau / sqrt 3``;
    ``beta = 1.38012`` (:data:`ANTISYMMETRIC_RICKER_BETA`) makes
    ``max |p| = 1``, reached at ``tau = -/+ 0.20453`` with ``p = +/-1``.

    ``T_p = 2 pi / omega_p`` is the period at which the Fourier amplitude of
    the acceleration peaks (``|P| ~ omega^3 exp(-3 omega^2 / (8 pi^2))``, in
    units where ``T_p = 1``, peaks at ``omega = 2 pi``).  Support
    ``[-2.5, 2.5)`` T_p, truncated where ``|p| < 7.2e-16``.  Velocity and
    displacement are exact (Gaussian times polynomials, units ``a_p T_p`` and
    ``a_p T_p^2``); both end below 1e-16.
    """
    h = ANTISYMMETRIC_RICKER_HALF_WIDTH
    return Pulse("antisymmetric_ricker", ANTISYMMETRIC_RICKER, (1.0 / ANTISYMMETRIC_RICKER_BETA,),
                 -h, h, ())


def makris_a() -> Pulse:
    """Makris (1997) type-A one-cycle pulse (forward motion).

    Ground velocity ``v_p (1 - cos(omega_p t)) / 2`` on ``0 <= t < T_p``, so
    ``p(tau) = sin(2 pi tau)`` on ``[0, 1)`` with ``a_p = omega_p v_p / 2``.
    ``T_p = 2 pi / omega_p`` is the period (and duration) of the cycle.

    Velocity ``(1 - cos 2 pi tau) / (2 pi)`` (units ``a_p T_p``), displacement
    ``tau / (2 pi) - sin(2 pi tau) / (4 pi^2)`` (units ``a_p T_p^2``): the
    ground ends at rest with a permanent displacement ``1 / (2 pi)``.
    ``p`` is continuous; ``dp/dtau`` jumps at ``tau = 0`` and ``1``.
    """
    return Pulse("makris_a", MAKRIS_A, (), 0.0, 1.0, (0.0, 1.0))


def makris_b() -> Pulse:
    """Makris (1997) type-B one-cycle pulse (forward-and-back motion).

    Ground velocity ``v_p sin(omega_p t)`` on ``0 <= t < T_p``, so
    ``p(tau) = cos(2 pi tau)`` on ``[0, 1)`` with ``a_p = omega_p v_p``.
    ``T_p = 2 pi / omega_p`` is the period (and duration) of the cycle.

    Velocity ``sin(2 pi tau) / (2 pi)``, displacement
    ``(1 - cos 2 pi tau) / (4 pi^2)``; both vanish at the end.  ``p`` jumps
    from 0 to 1 at ``tau = 0`` and from 1 to 0 at ``tau = 1``.
    """
    return Pulse("makris_b", MAKRIS_B, (), 0.0, 1.0, (0.0, 1.0))


def makris_cn_phase(n: int) -> float:
    """Phase ``phi`` (rad) of the Makris & Chang (2000) type-Cn pulse.

    The root in ``(0, pi/2)`` of ``cos(phi) = ((n + 1/2) pi - phi) sin(phi)``,
    which makes the ground displacement vanish at the end of the pulse;
    ``phi = 0.0697 pi`` for n = 1 and ``0.0410 pi`` for n = 2, as in the
    literature.
    """
    n = _check_n(n)
    g = lambda p: math.cos(p) - ((n + 0.5) * math.pi - p) * math.sin(p)  # noqa: E731
    return brentq(g, 0.0, 0.5 * math.pi, xtol=1e-16, rtol=4 * np.finfo(float).eps)


def _check_n(n) -> int:
    ok = isinstance(n, numbers.Real) and not isinstance(n, bool) and math.isfinite(n) \
        and float(n) == int(n) and int(n) >= 1
    if not ok:
        raise ValueError(f"n = {n!r} is invalid; allowed range: integer n >= 1")
    return int(n)


def makris_cn(n: int = 1) -> Pulse:
    """Makris & Chang (2000) type-Cn pulse (n main velocity half-cycles, "C1", "C2", ...).

    Ground velocity ``v_p [sin(omega_p t + phi) - sin(phi)]`` and acceleration
    ``omega_p v_p cos(omega_p t + phi)`` on
    ``0 <= t < (n + 1/2 - phi/pi) T_p``; so ``p(tau) = cos(2 pi tau + phi)``
    with ``a_p = omega_p v_p``.  ``T_p = 2 pi / omega_p`` is the period of the
    harmonic (not the pulse duration).

    Parameters
    ----------
    n : int, default 1
        Number of cycles, integer ``>= 1``.  The phase ``phi`` is not free: it
        is computed by :func:`makris_cn_phase` (``0.0697 pi`` for n = 1,
        ``0.0410 pi`` for n = 2) so that the final ground velocity and
        displacement both vanish (the velocity vanishes for any ``phi``, the
        displacement fixes ``phi``).

    Notes
    -----
    Velocity ``(sin(2 pi tau + phi) - sin phi) / (2 pi)`` (units ``a_p T_p``),
    displacement ``(cos phi - cos(2 pi tau + phi)) / (4 pi^2) - tau sin(phi) / (2 pi)``
    (units ``a_p T_p^2``).  ``p`` jumps at both ends (to ``cos phi`` at 0, from
    ``-cos phi`` at the end).
    """
    n = _check_n(n)
    phi = makris_cn_phase(n)
    tau_end = n + 0.5 - phi / math.pi
    return Pulse("makris_cn", MAKRIS_CN, (phi, tau_end, float(n)), 0.0, tau_end, (0.0, tau_end))


MP_GAMMA_MAX = 100.0
"""Largest accepted Mavroeidis-Papageorgiou ``gamma`` (support = gamma T_p); fits to records give ~1.5-3."""


def mavroeidis_papageorgiou(gamma: float = 2.0, nu: float = 0.0) -> Pulse:
    """Mavroeidis & Papageorgiou (2003) pulse, normalised to ``max |p| = 1``.

    Ground velocity (with the pulse centred at ``t_0 = 0``)
    ``v(t) = (A/2) [1 + cos(2 pi f_p t / gamma)] cos(2 pi f_p t + nu)`` for
    ``|t| <= gamma / (2 f_p)``, zero otherwise.  ``T_p = 1 / f_p`` (the
    prevailing period, that of the modulated harmonic); in units of ``T_p``
    the support is ``[-gamma/2, gamma/2)``.  The acceleration is the exact
    derivative, divided by its peak: ``a_p = pi f_p A N`` with
    ``N = max |(1/gamma) sin(2 pi tau/gamma) cos(2 pi tau + nu) + (1 + cos(2 pi tau/gamma)) sin(2 pi tau + nu)|``
    found numerically once (grid + Brent to machine precision) and stored in
    ``params`` as ``1/N``.

    Parameters
    ----------
    gamma : float, default 2
        Oscillatory character (number of half-cycles per envelope, roughly);
        allowed ``1 < gamma <= 100`` (MP2003 require ``gamma > 1``).
    nu : float, default 0
        Phase of the harmonic, radians; allowed ``-2 pi <= nu <= 2 pi`` (a
        value in degrees such as 90 is rejected rather than misread).

    Notes
    -----
    Velocity ``(1 + cos(2 pi tau/gamma)) cos(2 pi tau + nu) / (2 pi N)``
    (units ``a_p T_p``) and displacement in closed form (three sines, units
    ``a_p T_p^2``).  ``p`` is continuous, ``dp/dtau`` jumps at both ends.  The
    final velocity is zero; the final displacement is zero when ``gamma`` is
    an integer or ``cos(nu) = 0`` and is a permanent offset otherwise.
    Defaults (``gamma = 2, nu = 0``) are illustrative: a symmetric two-sided
    velocity pulse with zero final displacement.
    """
    gamma = _check("gamma", gamma, 1.0, MP_GAMMA_MAX, lo_in=False, hi_in=True)
    nu = _check("nu", nu, -2.0 * math.pi, 2.0 * math.pi)
    f = lambda t: _mp_accel_raw(t, gamma, nu)  # noqa: E731

    def df(t):
        a = _TWO_PI / gamma
        x = _TWO_PI * t + nu
        sa, ca = np.sin(a * t), np.cos(a * t)
        return -((a / gamma * ca + _TWO_PI * (1.0 + ca)) * np.cos(x) - (_TWO_PI / gamma + a) * sa * np.sin(x))

    peak, _ = _peak_abs(f, df, -0.5 * gamma, 0.5 * gamma)
    h = 0.5 * gamma
    return Pulse("mavroeidis_papageorgiou", MAVROEIDIS_PAPAGEORGIOU, (gamma, nu, 1.0 / peak),
                 -h, h, (-h, h))


def sampled(accel, dtau: float, tau0: float = 0.0, name: str = "record") -> Pulse:
    """A sampled acceleration history, linear between samples, zero outside.

    Velocity and displacement are the exact integrals of the piecewise-linear
    history.  Unlike the analytical shapes, the samples are used as given:
    ``max |p|`` is 1 only if the caller divided by the peak (for a record,
    ``dtau = dt / T_p`` and ``accel = a_g / a_p`` with the caller's choice of
    ``T_p`` and ``a_p``).

    Parameters
    ----------
    accel : array_like
        Samples of ``a_g / a_p`` (dimensionless), at least 2.
    dtau : float
        Sampling interval in units of T_p (``dt / T_p``), > 0.
    tau0 : float
        Time of the first sample in units of T_p.
    name : str
        Label of the record.
    """
    a = np.asarray(accel, dtype=float)
    if a.ndim != 1 or a.size < 2:
        raise ValueError(f"accel must be a 1-D array of at least 2 samples, got shape {a.shape}")
    if not np.all(np.isfinite(a)):
        raise ValueError("accel contains NaN or inf")
    dtau = _check("dtau", dtau, 0.0, math.inf, lo_in=False, hi_in=False)
    tau0 = _check("tau0", tau0, -math.inf, math.inf, lo_in=False, hi_in=False)
    knots = tau0 + dtau * np.arange(a.size)
    params = (tau0, dtau) + tuple(float(x) for x in a)
    return Pulse(name, SAMPLED, params, float(knots[0]), float(knots[-1]), tuple(float(k) for k in knots[:-1]))


_FACTORIES = {
    "ricker": ricker,
    "rectangular": rectangular,
    "antisymmetric_ricker": antisymmetric_ricker,
    "makris_a": makris_a,
    "makris_b": makris_b,
    "makris_cn": makris_cn,
    "mavroeidis_papageorgiou": mavroeidis_papageorgiou,
}
PULSE_NAMES = tuple(_FACTORIES)


def get_pulse(pulse, **shape_params) -> Pulse:
    """Resolve a pulse name with its shape parameters (or pass a :class:`Pulse` through).

    Parameters
    ----------
    pulse : str or Pulse
        One of :data:`PULSE_NAMES`, or a ready :class:`Pulse`.
    **shape_params
        Shape parameters of the named factory (e.g. ``n`` for ``"makris_cn"``,
        ``gamma`` and ``nu`` for ``"mavroeidis_papageorgiou"``).

    Raises
    ------
    ValueError
        Unknown name, unknown shape parameter, or a value out of its range
        (the message names the parameter, the value and the allowed range).
    """
    if isinstance(pulse, Pulse):
        if shape_params:
            raise ValueError(f"shape parameters {sorted(shape_params)} given with a ready Pulse; "
                             "allowed: none")
        return pulse
    if isinstance(pulse, str) and pulse in _FACTORIES:
        factory = _FACTORIES[pulse]
        allowed = tuple(inspect.signature(factory).parameters)
        for key, value in shape_params.items():
            if key not in allowed:
                raise ValueError(f"{key} = {value!r} is not a shape parameter of pulse {pulse!r}; "
                                 f"allowed: {allowed if allowed else 'none'}")
        return factory(**shape_params)
    raise ValueError(f"pulse = {pulse!r} is invalid; allowed: one of {PULSE_NAMES} or a Pulse")


# ---------------------------------------------------------------------------
# shapes in record time, with free scales (fitting pulses to records)
# ---------------------------------------------------------------------------

def ricker_accel(t, A, t_peak, T):
    """Ricker wavelet acceleration at record times ``t``, not truncated.

    ``a(t) = A (1 - 2 pi^2 x^2) exp(-pi^2 x^2)`` with ``x = (t - t_peak) / T``:
    the shape of :func:`ricker` at physical scales, over the whole real line
    (no truncation at ``|x| = 2``), for least-squares fits to records.

    Parameters
    ----------
    t : array_like
        Times, s.
    A : float
        Signed peak acceleration ``a(t_peak)``, in any acceleration unit
        (the result has the same unit).
    t_peak : float
        Time of the peak, s.
    T : float
        Period ``T_p`` of peak Fourier amplitude, s (> 0).

    Returns
    -------
    ndarray
        Acceleration, in the unit of ``A``.
    """
    x = (np.asarray(t, dtype=float) - t_peak) / T
    s = _PI2 * x * x
    return A * ((1.0 - 2.0 * s) * np.exp(-s))


def ricker_velocity(t, A, t_peak, T):
    """Ground velocity of :func:`ricker_accel`, from rest at ``t = -inf``.

    ``v(t) = A T x exp(-pi^2 x^2)`` with ``x = (t - t_peak) / T``.

    Parameters
    ----------
    t : array_like
        Times, s.
    A : float
        Signed peak acceleration, e.g. m/s^2.
    t_peak : float
        Time of the acceleration peak, s.
    T : float
        Period ``T_p``, s (> 0).

    Returns
    -------
    ndarray
        Velocity, in the unit of ``A`` times s (m/s for ``A`` in m/s^2).
    """
    x = (np.asarray(t, dtype=float) - t_peak) / T
    return A * T * x * np.exp(-_PI2 * x * x)


def mp_accel(t, A, t0, T, gamma, nu):
    """Mavroeidis-Papageorgiou (2003) acceleration at record times ``t``, unnormalised.

    The exact derivative of the velocity :func:`mp_velocity`,
    ``a = -(A pi / (gamma T)) [sin(2 pi x/gamma) cos(2 pi x + nu) + gamma (1 + cos(2 pi x/gamma)) sin(2 pi x + nu)]``
    for ``|x| <= gamma/2``, ``x = (t - t0) / T``, and 0 outside: the shape of
    :func:`mavroeidis_papageorgiou` at physical scales, with free ``gamma``
    and ``nu`` (its peak is ``pi A N / T``, ``N`` as there).

    Parameters
    ----------
    t : array_like
        Times, s.
    A : float
        Velocity amplitude, e.g. m/s.
    t0 : float
        Centre of the envelope, s.
    T : float
        Period ``T_p = 1/f_p`` of the modulated harmonic, s (> 0).
    gamma : float
        Oscillatory character (> 1; the support is ``gamma T`` long).
    nu : float
        Phase of the harmonic, rad.

    Returns
    -------
    ndarray
        Acceleration, in the unit of ``A`` per s (m/s^2 for ``A`` in m/s).
    """
    x = (np.asarray(t, dtype=float) - t0) / T
    inside = np.abs(x) <= 0.5 * gamma
    ph = 2 * _PI * x + nu
    env = 2 * _PI * x / gamma
    a = -(A * _PI / (gamma * T)) * (np.sin(env) * np.cos(ph) + gamma * (1 + np.cos(env)) * np.sin(ph))
    return np.where(inside, a, 0.0)


def mp_accel_jacobian(t, A, t0, T, gamma, nu):
    """Jacobian of :func:`mp_accel` with respect to ``(A, t0, T, gamma, nu)``.

    Parameters
    ----------
    t : array_like
        Times, s (1-D).
    A, t0, T, gamma, nu : float
        As in :func:`mp_accel`.

    Returns
    -------
    ndarray, shape (len(t), 5)
        Columns ``da/dA`` (1/s), ``da/dt0``, ``da/dT`` (unit of ``A`` per
        s^2), ``da/dgamma`` and ``da/dnu`` (unit of ``A`` per s); zero
        outside the support.
    """
    x = (np.asarray(t, dtype=float) - t0) / T
    inside = np.abs(x) <= 0.5 * gamma
    e = 2 * _PI * x / gamma
    ph = 2 * _PI * x + nu
    S, C, s, c = np.sin(e), np.cos(e), np.sin(ph), np.cos(ph)
    F = S * c + gamma * (1 + C) * s
    Fx = (2 * _PI / gamma) * C * c - 4 * _PI * S * s + 2 * _PI * gamma * (1 + C) * c
    Fg = -(2 * _PI * x / gamma**2) * C * c + (1 + C) * s + (2 * _PI * x / gamma) * S * s
    Fn = -S * s + gamma * (1 + C) * c
    K = -_PI / (gamma * T)
    J = np.stack([K * F, -A * K * Fx / T, -(A * K / T) * (F + x * Fx), A * K * (Fg - F / gamma),
                  A * K * Fn], axis=-1)
    return np.where(inside[:, None], J, 0.0)


def mp_velocity(t, A, t0, T, gamma, nu):
    """Mavroeidis-Papageorgiou (2003) ground velocity at record times ``t``.

    ``v = (A/2) [1 + cos(2 pi x / gamma)] cos(2 pi x + nu)`` for
    ``|x| <= gamma/2``, ``x = (t - t0) / T``, and 0 outside.

    Parameters
    ----------
    t : array_like
        Times, s.
    A, t0, T, gamma, nu : float
        As in :func:`mp_accel`.

    Returns
    -------
    ndarray
        Velocity, in the unit of ``A`` (m/s).
    """
    x = (np.asarray(t, dtype=float) - t0) / T
    inside = np.abs(x) <= 0.5 * gamma
    v = 0.5 * A * (1 + np.cos(2 * _PI * x / gamma)) * np.cos(2 * _PI * x + nu)
    return np.where(inside, v, 0.0)


# numba reads the compiled code shipped with the package (isoslide.jit_cache) before compiling any of it
jit_cache.seed(accel_at)
