"""Fitting an analytical pulse to the dominant acceleration pulse of a record.

:func:`fit_pulse` fits one analytical pulse by least squares:

1. a global search over ``(T_p, t_peak)``: for each trial period on a
   logarithmic grid the record is correlated with the unit-energy Ricker
   wavelet (a continuous wavelet transform with the Mexican-hat mother wavelet,
   Vassiliou & Makris 2011); with the amplitude profiled out, the squared
   normalised coefficient is exactly the reduction of the squared residual,
   so its maximum is the global least-squares optimum on the grid;
2. a local Levenberg-Marquardt style refinement (``scipy.optimize.least_squares``)
   of amplitude, period and time, on the continuous parameters.

The Mavroeidis & Papageorgiou (2003) pulse is fitted from many starts seeded
by the Ricker fit.  The shapes are those of :mod:`isoslide.pulses` at physical
scales (:func:`~isoslide.pulses.ricker_accel`,
:func:`~isoslide.pulses.mp_accel` and their velocities), so a
:class:`PulseFit` and its :meth:`PulseFit.as_pulse` describe the same pulse.

Units: accelerations in m/s^2 (the input is converted from ``units``, g by
default), times in s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares

from ..pulses import (Pulse, get_pulse, mp_accel, mp_accel_jacobian, mp_velocity, ricker,
                      ricker_accel, ricker_velocity)
from .errors import MAX_ABS_ACCEL_G
from .units import G, unit_factor

__all__ = ["PulseFit", "SHAPES", "canonical_shape", "fit_pulse"]

SHAPES = ("ricker", "mavroeidis_papageorgiou")
"""Pulse shapes :func:`fit_pulse` can fit."""

_SHAPE_ALIASES = {"ricker": "ricker", "mavroeidis_papageorgiou": "mavroeidis_papageorgiou",
                  "mp": "mavroeidis_papageorgiou"}

_MP_GAMMA_MAX = 6.0
"""Upper bound of the Mavroeidis-Papageorgiou oscillation parameter gamma in fits."""

_PI = math.pi


def canonical_shape(shape: str) -> str:
    """The full name of a fitted pulse shape.

    Parameters
    ----------
    shape : str
        ``"ricker"``, ``"mavroeidis_papageorgiou"`` or its alias ``"mp"``
        (case-insensitive).

    Returns
    -------
    str
        One of :data:`SHAPES`.

    Raises
    ------
    ValueError
        Any other name.
    """
    s = _SHAPE_ALIASES.get(str(shape).lower())
    if s is None:
        raise ValueError(f"shape = {shape!r} is invalid; allowed: one of {SHAPES} (or 'mp')")
    return s


# --------------------------------------------------------------------------- fit result


@dataclass(frozen=True)
class PulseFit:
    """An analytical pulse fitted to a record's dominant acceleration pulse.

    Attributes
    ----------
    shape : str
        ``"ricker"`` or ``"mavroeidis_papageorgiou"``.
    a_p : float
        Peak acceleration of the fitted pulse, **m/s^2** (> 0).
    T_p : float
        Pulse period, s: the Ricker ``T_p`` (Fourier-amplitude peak at
        ``1/T_p``) or the Mavroeidis-Papageorgiou ``1/f_P``.
    t_peak : float
        Record time of the fitted pulse's peak ``|a|``, s.
    polarity : int
        Sign of the fitted acceleration at ``t_peak`` (+1 or -1).
    params : tuple of (str, float)
        Shape parameters.  Mavroeidis-Papageorgiou: ``gamma`` (-),
        ``nu`` (rad, in [0, 2 pi)), ``t0`` (envelope centre, s) and ``A``
        (velocity amplitude, m/s).  Ricker: none.
    r2 : float
        ``1 - sum(res^2) / sum(a^2)`` over the pulse window (uncentred; the
        pulse has zero mean).
    nrmse : float
        RMS residual over the pulse window divided by ``a_p``.
    energy_fraction : float
        Share of the whole record's ``sum(a^2)`` removed by the pulse,
        ``1 - sum(res^2)/sum(a^2)`` over the full record.
    window : (float, float)
        Record times bounding the pulse window, s (Ricker: ``t_peak +- T_p``;
        M-P: the envelope support).
    """

    shape: str
    a_p: float
    T_p: float
    t_peak: float
    polarity: int
    params: tuple = ()
    r2: float = math.nan
    nrmse: float = math.nan
    energy_fraction: float = math.nan
    window: tuple = (math.nan, math.nan)

    @property
    def shape_params(self) -> dict:
        """``params`` as a dict."""
        return dict(self.params)

    @property
    def a_p_g(self) -> float:
        """``a_p`` in units of g."""
        return self.a_p / G

    @property
    def length_scale(self) -> float:
        """``L_p = a_p T_p^2``, m."""
        return self.a_p * self.T_p**2

    def accel(self, t) -> np.ndarray:
        """Fitted ground acceleration at record times ``t`` (s), m/s^2."""
        if self.shape == "ricker":
            return ricker_accel(t, self.polarity * self.a_p, self.t_peak, self.T_p)
        p = self.shape_params
        return mp_accel(t, p["A"], p["t0"], self.T_p, p["gamma"], p["nu"])

    def velocity(self, t) -> np.ndarray:
        """Fitted ground velocity at record times ``t`` (s), m/s, from rest before the pulse."""
        if self.shape == "ricker":
            return ricker_velocity(t, self.polarity * self.a_p, self.t_peak, self.T_p)
        p = self.shape_params
        return mp_velocity(t, p["A"], p["t0"], self.T_p, p["gamma"], p["nu"])

    @property
    def t_ref(self) -> float:
        """Record time of ``tau = 0`` of :meth:`as_pulse`, s.

        The pulse peak ``t_peak`` for the Ricker; the envelope centre ``t0``
        for Mavroeidis-Papageorgiou (the origin used by
        :func:`isoslide.pulses.mavroeidis_papageorgiou`).
        """
        if self.shape == "ricker":
            return self.t_peak
        return self.shape_params["t0"]

    def as_pulse(self) -> Pulse:
        """The fitted shape as a dimensionless :class:`~isoslide.pulses.Pulse`.

        ``p(tau) = a(t_ref + tau T_p) / (polarity a_p)``: the same normalisation
        as :meth:`Record.as_pulse` with its defaults, so the record and the
        pulse are aligned in ``tau`` and the pulse is ``+1`` at its peak.
        Ricker: :func:`isoslide.pulses.ricker`.  Mavroeidis-Papageorgiou:
        ``get_pulse("mavroeidis_papageorgiou", gamma=gamma, nu=nu')`` with
        ``nu' = nu`` for positive polarity and ``nu +- pi`` (the sign-flipped
        pulse) otherwise.
        """
        if self.shape == "ricker":
            return ricker()
        p = self.shape_params
        return get_pulse("mavroeidis_papageorgiou", gamma=p["gamma"], nu=_mp_phase(p["nu"], self.polarity))

    scene_pulse = as_pulse


def _mp_phase(nu: float, polarity: int) -> float:
    """Phase of the M-P pulse whose peak has sign ``+1``: ``nu`` or ``nu -+ pi`` (in [-pi, 2 pi))."""
    if polarity > 0:
        return float(nu)
    return float(nu - _PI if nu >= _PI else nu + _PI)


# --------------------------------------------------------------------------- fitting


def _ricker_grid_search(a, dt, T_grid, i_lo, i_hi):
    """Global least-squares search of (T_p, t_peak) by correlation with the Ricker wavelet."""
    best = (-1.0, None, None, None)
    for T in T_grid:
        J = int(math.ceil(2.0 * T / dt))
        k = ricker_accel(np.arange(-J, J + 1) * dt, 1.0, 0.0, T)
        from scipy.signal import fftconvolve  # here: scipy.signal costs 0.2 s to import

        c = fftconvolve(a, k, mode="same")  # kernel is symmetric: convolution == correlation
        score = c[i_lo:i_hi] ** 2 / np.dot(k, k)
        j = int(np.argmax(score))
        if score[j] > best[0]:
            best = (float(score[j]), float(T), j + i_lo, float(c[j + i_lo] / np.dot(k, k)))
    return best


def fit_pulse(accel, dt, shape: str = "ricker", *, units: str = "g", t_start: float = 0.0,
              T_range=None, t_range=None, n_periods: int = 64) -> PulseFit:
    """Fit an analytical pulse to the dominant acceleration pulse of a record.

    Parameters
    ----------
    accel : array_like
        Ground acceleration samples, in ``units`` (default g).
    dt : float
        Sampling interval, s.
    shape : {"ricker", "mavroeidis_papageorgiou"}
        Pulse shape (``"mp"`` is an alias of the latter).
    units : str
        Units of ``accel``: ``"g"`` (default), ``"m/s2"``, ``"cm/s2"``, ...
    t_start : float
        Time of the first sample, s.
    T_range : (float, float), optional
        Search range of the period, s.  Default ``(max(0.1, 8 dt),
        min(10, duration / 2))``.
    t_range : (float, float), optional
        Restrict the pulse peak to this time range, s.
    n_periods : int
        Number of trial periods in the global search (log-spaced).

    Returns
    -------
    PulseFit
        ``a_p`` in m/s^2, ``T_p`` and ``t_peak`` in s, shape parameters and
        goodness of fit.

    Raises
    ------
    ValueError
        Fewer than 8 samples, a non-finite sample or one beyond ``|accel| <=
        100 g`` (:data:`~isoslide.records.errors.MAX_ABS_ACCEL_G`), a bad
        ``dt``, an all-zero record or a bad search range.

    Notes
    -----
    The Ricker fit minimises ``sum (a - A r((t - t_peak)/T_p))^2`` over the
    whole record; the Mavroeidis-Papageorgiou fit minimises the same with its
    own shape, starting from 36 seeds around the Ricker fit.
    """
    shape = canonical_shape(shape)
    a = np.asarray(accel, dtype=float)
    if a.ndim != 1 or a.size < 8:
        raise ValueError(f"accel must be a 1-D array of at least 8 samples, got shape {a.shape}")
    if not np.all(np.isfinite(a)):
        raise ValueError("accel contains NaN or inf")
    dt = float(dt)
    if not (math.isfinite(dt) and dt > 0):
        raise ValueError(f"dt = {dt!r} is invalid; allowed range: 0 < dt < inf (s)")
    factor = unit_factor(units, "<accel>", None)
    big = np.nonzero(np.abs(a) * factor > MAX_ABS_ACCEL_G)[0]
    if big.size:  # also keeps the products below from overflowing
        k = int(big[0])
        raise ValueError(f"accel[{k}] = {a[k]:.6g} {units} is invalid; allowed range: "
                         f"|accel| <= {MAX_ABS_ACCEL_G:g} g")
    a = a * (factor * G)  # -> m/s^2
    if not np.any(a):
        raise ValueError("accel is identically zero: no pulse to fit")
    n = a.size
    duration = dt * (n - 1)
    t = t_start + dt * np.arange(n)
    if T_range is None:
        T_range = (max(0.1, 8 * dt), min(10.0, duration / 2))
    T_lo, T_hi = float(T_range[0]), float(T_range[1])
    if not (0 < T_lo < T_hi):
        raise ValueError(f"T_range = {T_range!r} is invalid; need 0 < T_min < T_max (s) "
                         f"(record duration {duration:g} s, dt {dt:g} s)")
    if t_range is None:
        i_lo, i_hi = 0, n
    else:
        i_lo = max(0, int(math.ceil((t_range[0] - t_start) / dt)))
        i_hi = min(n, int(math.floor((t_range[1] - t_start) / dt)) + 1)
        if i_hi <= i_lo:
            raise ValueError(f"t_range = {t_range!r} lies outside the record ({t[0]:g} to {t[-1]:g} s)")

    # ---- Ricker: global grid search, then local refinement
    T_grid = np.geomspace(T_lo, T_hi, n_periods)
    _, T0, j0, A0 = _ricker_grid_search(a, dt, T_grid, i_lo, i_hi)
    t_lo_b = t[i_lo] - 1e-12
    t_hi_b = t[i_hi - 1] + 1e-12
    x = np.array([A0, t[j0], T0])
    for _ in range(3):
        Tw = max(x[2], T_lo)
        k0 = max(0, int((x[1] - 3 * Tw - t_start) / dt))
        k1 = min(n, int((x[1] + 3 * Tw - t_start) / dt) + 2)
        tw, aw = t[k0:k1], a[k0:k1]

        def res(p, tw=tw, aw=aw):
            return ricker_accel(tw, p[0], p[1], p[2]) - aw

        x0 = np.array([x[0], np.clip(x[1], t_lo_b, t_hi_b), np.clip(x[2], T_lo, T_hi)])
        sol = least_squares(res, x0, bounds=([-np.inf, t_lo_b, T_lo], [np.inf, t_hi_b, T_hi]),
                            x_scale=[abs(A0) or 1.0, T0, T0], xtol=1e-12, ftol=1e-12, gtol=1e-12)
        moved = abs(sol.x[2] - Tw) > 0.3 * Tw
        x = sol.x
        if not moved:
            break
    A, tp, Tp = (float(v) for v in x)
    ricker_fit = _goodness(a, t, lambda tt: ricker_accel(tt, A, tp, Tp), tp - Tp, tp + Tp,
                           shape="ricker", a_p=abs(A), T_p=Tp, t_peak=tp, polarity=1 if A >= 0 else -1, params=())
    if shape == "ricker":
        return ricker_fit

    # ---- Mavroeidis-Papageorgiou: multi-start local fits around the Ricker fit,
    # on a decimated window first (>= ~40 samples per T_p), then polished at full rate
    T_mlo, T_mhi = max(T_lo, 0.5 * Tp), min(T_hi, 2.0 * Tp)
    g_lo, g_hi = 1.01, _MP_GAMMA_MAX
    half = 0.5 * g_hi * T_mhi + Tp
    k0 = max(0, int((tp - half - t_start) / dt))
    k1 = min(n, int((tp + half - t_start) / dt) + 2)
    tw, aw = t[k0:k1], a[k0:k1]
    step = max(1, int(Tp / (40 * dt)))
    lo = [-np.inf, tp - 2 * Tp, T_mlo, g_lo, -4 * _PI]
    hi = [np.inf, tp + 2 * Tp, T_mhi, g_hi, 6 * _PI]

    def fit_from(x0, tt, yy, tol, max_nfev=None):
        return least_squares(lambda p: mp_accel(tt, *p) - yy, x0, jac=lambda p: mp_accel_jacobian(tt, *p),
                             bounds=(lo, hi), x_scale=[abs(x0[0]) or 1.0, Tp, Tp, 1.0, 1.0],
                             xtol=tol, ftol=tol, max_nfev=max_nfev)

    ts, as_ = tw[::step], aw[::step]
    best = None
    for Tf in (0.8, 1.0, 1.25):
        for gam in (1.5, 2.5, 4.0):
            for nu in (0.0, 0.5 * _PI, _PI, 1.5 * _PI):
                T_s = float(np.clip(Tf * Tp, T_mlo, T_mhi))
                m = mp_accel(ts, 1.0, tp, T_s, gam, nu)
                mm = float(np.dot(m, m))
                if mm == 0:  # pragma: no cover
                    continue
                sol = fit_from([float(np.dot(m, as_) / mm), tp, T_s, gam, nu], ts, as_, 1e-6, max_nfev=40)
                if best is None or sol.cost < best.cost:
                    best = sol
    best = fit_from(np.clip(best.x, lo, hi), tw, aw, 1e-10)
    Av, t0, Tm, gam, nu = (float(v) for v in best.x)
    if Av < 0:
        Av, nu = -Av, nu + _PI
    nu = float(nu % (2 * _PI))
    tt = np.linspace(t0 - 0.5 * gam * Tm, t0 + 0.5 * gam * Tm, 20001)
    af = mp_accel(tt, Av, t0, Tm, gam, nu)
    k = int(np.argmax(np.abs(af)))
    # exact peak from the pulses module's normalisation: a_p = pi A N / T_p, N = max |raw shape|
    a_p = _PI * Av / Tm / get_pulse("mavroeidis_papageorgiou", gamma=gam, nu=nu).params[2]
    params = (("gamma", gam), ("nu", nu), ("t0", t0), ("A", Av))
    return _goodness(a, t, lambda s: mp_accel(s, Av, t0, Tm, gam, nu),
                     t0 - 0.5 * gam * Tm, t0 + 0.5 * gam * Tm, shape="mavroeidis_papageorgiou",
                     a_p=float(a_p), T_p=Tm, t_peak=float(tt[k]),
                     polarity=1 if af[k] >= 0 else -1, params=params)


def _goodness(a, t, model, w_lo, w_hi, **kw) -> PulseFit:
    """The :class:`PulseFit` of ``model`` (m/s^2 at times ``t``) with R^2 and NRMSE over ``[w_lo, w_hi]``."""
    m = model(t)
    res = a - m
    inw = (t >= w_lo) & (t <= w_hi)
    ss_w = float(np.dot(a[inw], a[inw]))
    rr_w = float(np.dot(res[inw], res[inw]))
    r2 = 1.0 - rr_w / ss_w if ss_w > 0 else math.nan
    nrmse = math.sqrt(rr_w / max(int(inw.sum()), 1)) / kw["a_p"] if kw["a_p"] > 0 else math.nan
    ef = 1.0 - float(np.dot(res, res)) / float(np.dot(a, a))
    return PulseFit(r2=r2, nrmse=nrmse, energy_fraction=ef, window=(float(w_lo), float(w_hi)), **kw)
