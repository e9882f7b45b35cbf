"""Ground-acceleration pulses in dimensionless form.

Every pulse is written in dimensionless time ``tau = t / T_p`` with unit
acceleration amplitude, ``p(tau) = a_g(t) / a_p``.  Ground velocity and
displacement are therefore in units of ``a_p T_p`` and ``a_p T_p**2``; the
ground is at rest (zero velocity and displacement) at ``tau_start``.

Two layers live here:

* scalar, numba-compiled evaluators :func:`accel_at` and :func:`jerk_at`,
  dispatching on an integer ``code`` and a float64 ``params`` array, which the
  solver kernel calls inside its integration loop;
* the frozen :class:`Pulse` description with vectorised, exact
  :meth:`Pulse.accel`, :meth:`Pulse.velocity` and :meth:`Pulse.displacement`.

Conventions
-----------
``p`` is right-continuous at its breakpoints (e.g. the rectangular pulse is 1
on ``[0, 1)`` and 0 at ``tau = 1``).  Outside ``[tau_start, tau_end)`` the
acceleration is exactly zero.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numba import njit

RICKER = 0
RECTANGULAR = 1
ANTISYMMETRIC_RICKER = 2
MAKRIS_A = 3
MAKRIS_B = 4
MAKRIS_CN = 5
MAVROEIDIS_PAPAGEORGIOU = 6
SAMPLED = 7

_PI2 = math.pi * math.pi
RICKER_HALF_WIDTH = 2.0
"""Half-width (in T_p) at which the symmetric Ricker is truncated: |p| < 6e-16 beyond it."""


@njit(cache=True)
def accel_at(code, params, tau):
    """Dimensionless ground acceleration ``p(tau) = a_g / a_p`` (scalar, compiled)."""
    if code == RICKER:
        if tau < -RICKER_HALF_WIDTH or tau >= RICKER_HALF_WIDTH:
            return 0.0
        s = _PI2 * tau * tau
        return (1.0 - 2.0 * s) * math.exp(-s)
    if code == RECTANGULAR:
        if 0.0 <= tau < 1.0:
            return 1.0
        return 0.0
    if code == SAMPLED:
        tau0 = params[0]
        dtau = params[1]
        n = params.shape[0] - 2
        x = (tau - tau0) / dtau
        if x < 0.0 or x >= n - 1:
            return 0.0
        k = int(math.floor(x))
        if k >= n - 1:
            k = n - 2
        w = x - k
        return (1.0 - w) * params[2 + k] + w * params[3 + k]
    return math.nan


@njit(cache=True)
def jerk_at(code, params, tau):
    """Time derivative ``dp/dtau`` of :func:`accel_at` (right derivative at breakpoints)."""
    if code == RICKER:
        if tau < -RICKER_HALF_WIDTH or tau >= RICKER_HALF_WIDTH:
            return 0.0
        s = _PI2 * tau * tau
        return 2.0 * _PI2 * tau * (2.0 * s - 3.0) * math.exp(-s)
    if code == RECTANGULAR:
        return 0.0
    if code == SAMPLED:
        tau0 = params[0]
        dtau = params[1]
        n = params.shape[0] - 2
        x = (tau - tau0) / dtau
        if x < 0.0 or x >= n - 1:
            return 0.0
        k = int(math.floor(x))
        if k >= n - 1:
            k = n - 2
        return (params[3 + k] - params[2 + k]) / dtau
    return math.nan


@dataclass(frozen=True)
class Pulse:
    """A dimensionless ground-acceleration pulse.

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

    @property
    def param_array(self) -> np.ndarray:
        """Shape parameters as a contiguous float64 array (kernel input)."""
        return np.asarray(self.params if self.params else (0.0,), dtype=np.float64)

    @property
    def breakpoint_array(self) -> np.ndarray:
        """Sorted breakpoints inside the support, plus ``tau_end`` (kernel input)."""
        b = sorted(set(float(x) for x in self.breakpoints) | {float(self.tau_end)})
        return np.asarray([x for x in b if x > self.tau_start], dtype=np.float64)

    def accel(self, tau):
        """Dimensionless ground acceleration ``a_g / a_p`` at ``tau`` (vectorised)."""
        tau = np.asarray(tau, dtype=float)
        pa = self.param_array
        out = np.array([accel_at(self.code, pa, float(t)) for t in tau.ravel()])
        return out.reshape(tau.shape)

    def velocity(self, tau):
        """Ground velocity in units of ``a_p T_p`` (exact where a closed form exists)."""
        tau = np.asarray(tau, dtype=float)
        if self.code == RICKER:
            t = np.clip(tau, -RICKER_HALF_WIDTH, RICKER_HALF_WIDTH)
            v0 = -RICKER_HALF_WIDTH * math.exp(-_PI2 * RICKER_HALF_WIDTH**2)
            return t * np.exp(-_PI2 * t * t) - v0
        if self.code == RECTANGULAR:
            return np.clip(tau, 0.0, 1.0)
        return _cumulative(self, tau, order=1)

    def displacement(self, tau):
        """Ground displacement in units of ``a_p T_p**2`` (exact where a closed form exists)."""
        tau = np.asarray(tau, dtype=float)
        if self.code == RICKER:
            h = RICKER_HALF_WIDTH
            v0 = -h * math.exp(-_PI2 * h * h)
            t = np.clip(tau, -h, h)
            d = -(np.exp(-_PI2 * t * t) - math.exp(-_PI2 * h * h)) / (2 * _PI2) - v0 * (t + h)
            return d + (self.velocity(h) * np.maximum(tau - h, 0.0))
        if self.code == RECTANGULAR:
            t = np.clip(tau, 0.0, 1.0)
            return 0.5 * t * t + np.maximum(tau - 1.0, 0.0)
        return _cumulative(self, tau, order=2)


def _cumulative(pulse: Pulse, tau, order: int):
    """Velocity (order 1) or displacement (order 2) by exact integration of a
    piecewise-linear sampled pulse; the trapezoid rule is exact for it."""
    if pulse.code != SAMPLED:
        raise NotImplementedError(f"no closed form for pulse {pulse.name!r}")
    pa = pulse.param_array
    tau0, dtau, a = pa[0], pa[1], pa[2:]
    knots = tau0 + dtau * np.arange(a.size)
    v = np.concatenate([[0.0], np.cumsum(0.5 * (a[1:] + a[:-1]) * dtau)])
    d = np.concatenate([[0.0], np.cumsum(v[:-1] * dtau + (2 * a[:-1] + a[1:]) * dtau**2 / 6)])
    t = np.clip(np.asarray(tau, dtype=float), knots[0], knots[-1])
    k = np.clip(((t - tau0) // dtau).astype(int), 0, a.size - 2)
    s = t - knots[k]
    slope = (a[k + 1] - a[k]) / dtau
    vel = v[k] + a[k] * s + 0.5 * slope * s * s
    if order == 1:
        return vel
    disp = d[k] + v[k] * s + a[k] * s * s / 2 + slope * s**3 / 6
    return disp + v[-1] * np.maximum(np.asarray(tau, dtype=float) - knots[-1], 0.0)


def ricker() -> Pulse:
    """Symmetric Ricker wavelet (paper Eq. 3): ``p = (1 - 2 pi^2 tau^2) exp(-pi^2 tau^2)``.

    Its Fourier amplitude peaks at ``1/T_p``; truncated to ``|tau| < 2``.
    """
    h = RICKER_HALF_WIDTH
    return Pulse("ricker", RICKER, (), -h, h, ())


def rectangular() -> Pulse:
    """Rectangular pulse of Newmark (1965): ``p = 1`` on ``0 <= tau < 1``."""
    return Pulse("rectangular", RECTANGULAR, (), 0.0, 1.0, (0.0,))


def sampled(accel, dtau: float, tau0: float = 0.0, name: str = "record") -> Pulse:
    """A sampled acceleration history, linear between samples, zero outside.

    Parameters
    ----------
    accel : array_like
        Samples of ``a_g / a_p`` (dimensionless).
    dtau : float
        Sampling interval in units of T_p.
    tau0 : float
        Time of the first sample in units of T_p.
    """
    a = np.asarray(accel, dtype=float)
    if a.ndim != 1 or a.size < 2:
        raise ValueError(f"accel must be a 1-D array of at least 2 samples, got shape {a.shape}")
    if not np.all(np.isfinite(a)):
        raise ValueError("accel contains NaN or inf")
    if not (np.isfinite(dtau) and dtau > 0):
        raise ValueError(f"dtau = {dtau!r} is invalid; allowed range: 0 < dtau < inf")
    knots = tau0 + dtau * np.arange(a.size)
    params = (float(tau0), float(dtau)) + tuple(float(x) for x in a)
    return Pulse(name, SAMPLED, params, float(knots[0]), float(knots[-1]), tuple(knots[:-1]))


_FACTORIES = {"ricker": ricker, "rectangular": rectangular}
PULSE_NAMES = tuple(_FACTORIES)


def get_pulse(pulse, **shape_params) -> Pulse:
    """Resolve a pulse name (or pass a :class:`Pulse` through)."""
    if isinstance(pulse, Pulse):
        return pulse
    if isinstance(pulse, str) and pulse in _FACTORIES:
        return _FACTORIES[pulse](**shape_params)
    raise ValueError(f"pulse = {pulse!r} is invalid; allowed: one of {PULSE_NAMES} or a Pulse")
