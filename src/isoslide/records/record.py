"""The :class:`Record` type: a uniformly sampled horizontal ground-acceleration history."""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass, field

import numpy as np

from ..pulses import Pulse, sampled
from .errors import MAX_ABS_ACCEL_G
from .fitting import PulseFit, canonical_shape, fit_pulse
from .units import G

__all__ = ["Record"]


@dataclass(frozen=True, eq=False)
class Record:
    """A uniformly sampled horizontal ground-acceleration record.

    Parameters
    ----------
    name : str
        Short identifier, e.g. ``"Kobe_1995_TAK-090"``.
    accel : array_like
        Ground acceleration, **in units of g** (9.80665 m/s^2), finite and
        within ``|accel| <= 100 g`` (:data:`~isoslide.records.errors.MAX_ABS_ACCEL_G`).
        Stored as a read-only float64 array.
    dt : float
        Sampling interval, s (> 0).
    event, station, component : str
        Descriptive metadata (free text; ``component`` is usually an azimuth).
    source : str
        Where the data came from (file path or package).
    licence : str
        Licence or terms under which the data are distributed, if known.
    t_start : float
        Time of the first sample, s.

    Raises
    ------
    ValueError
        Bad ``accel``, ``dt`` or ``t_start``; the message names the record,
        its ``source`` (the file) when given, the value and the allowed range.

    Notes
    -----
    Records compare by identity.  :meth:`fit` results are cached per shape and by content.
    """

    name: str
    accel: np.ndarray
    dt: float
    event: str = ""
    station: str = ""
    component: str = ""
    source: str = ""
    licence: str = ""
    t_start: float = 0.0
    _fits: dict = field(default_factory=dict, init=False, repr=False)

    def __post_init__(self):
        who = self._who
        try:
            a = np.array(self.accel, dtype=np.float64)
        except (TypeError, ValueError):
            raise ValueError(f"{who}: accel is invalid; allowed: a 1-D array of numbers (g)") from None
        if a.ndim != 1 or a.size < 2:
            raise ValueError(f"{who}: accel must be a 1-D array of at least 2 samples, got shape {a.shape}")
        if not np.all(np.isfinite(a)):
            k = int(np.nonzero(~np.isfinite(a))[0][0])
            raise ValueError(f"{who}: accel[{k}] = {a[k]!r} is invalid (NaN or inf); allowed: finite values (g)")
        big = np.nonzero(np.abs(a) > MAX_ABS_ACCEL_G)[0]
        if big.size:
            k = int(big[0])
            raise ValueError(f"{who}: accel[{k}] = {a[k]:.6g} g is invalid; allowed range: "
                             f"|accel| <= {MAX_ABS_ACCEL_G:g} g")
        try:
            dt = float(self.dt)
        except (TypeError, ValueError):
            dt = math.nan
        if not (math.isfinite(dt) and dt > 0):
            raise ValueError(f"{who}: dt = {self.dt!r} is invalid; allowed range: 0 < dt < inf (s)")
        t_start = float(self.t_start)
        if not math.isfinite(t_start):
            raise ValueError(f"{who}: t_start = {self.t_start!r} is invalid; allowed range: "
                             "-inf < t_start < inf (s)")
        if not math.isfinite(t_start + dt * (a.size - 1)):
            raise ValueError(f"{who}: dt = {dt!r} with {a.size} samples from t_start = {t_start!r} is "
                             "invalid; allowed: a finite end time (s)")
        a.setflags(write=False)
        object.__setattr__(self, "accel", a)
        object.__setattr__(self, "dt", dt)
        object.__setattr__(self, "t_start", t_start)

    @property
    def _who(self) -> str:
        """``Record 'name'`` and, when known, the file it was read from (for error messages)."""
        return f"Record {self.name!r}" + (f" from {self.source}" if self.source else "")

    # ---- basic properties
    @property
    def npts(self) -> int:
        """Number of samples."""
        return int(self.accel.size)

    @property
    def time(self) -> np.ndarray:
        """Sample times, s."""
        return self.t_start + self.dt * np.arange(self.npts)

    @property
    def duration(self) -> float:
        """``(npts - 1) dt``, s."""
        return self.dt * (self.npts - 1)

    @property
    def pga(self) -> float:
        """Peak ground acceleration ``max |accel|``, g."""
        return float(np.max(np.abs(self.accel)))

    @property
    def accel_si(self) -> np.ndarray:
        """Ground acceleration in m/s^2."""
        return self.accel * G

    def velocity(self) -> np.ndarray:
        """Ground velocity, m/s, by trapezoidal integration from rest at ``t_start``.

        No baseline correction is applied (the records are taken as processed).
        """
        a = self.accel_si
        return np.concatenate([[0.0], np.cumsum(0.5 * (a[1:] + a[:-1]) * self.dt)])

    @property
    def pgv(self) -> float:
        """Peak ground velocity ``max |velocity()|``, m/s."""
        return float(np.max(np.abs(self.velocity())))

    def __repr__(self):
        return (f"Record(name={self.name!r}, npts={self.npts}, dt={self.dt:g} s, "
                f"pga={self.pga:.3f} g, event={self.event!r}, station={self.station!r}, "
                f"component={self.component!r})")

    # ---- pulse
    def fit(self, shape: str = "ricker", **options) -> PulseFit:
        """Fit an analytical pulse to the record's dominant acceleration pulse (cached by content).

        Parameters
        ----------
        shape : {"ricker", "mavroeidis_papageorgiou"}
            Pulse shape (``"mp"`` is an alias of the latter).
        **options
            Passed to :func:`~isoslide.records.fit_pulse` (``T_range``,
            ``t_range``, ...).

        Returns
        -------
        PulseFit

        Raises
        ------
        ValueError
            The record cannot be fitted (too few samples, all zero, a bad
            option); the message names the record and its file.

        Notes
        -----
        Fits are cached per record object and, across objects, by content
        (samples, ``dt``, ``t_start``, shape and options), so reading the same
        file twice fits it once.
        """
        shape = canonical_shape(shape)
        key = (shape, tuple(sorted((k, _hashable(v)) for k, v in options.items())))
        if key not in self._fits:
            ckey = (self.content_key, key)
            fit = _FIT_CACHE.get(ckey)
            if fit is None:
                try:
                    fit = fit_pulse(self.accel, self.dt, shape=shape, t_start=self.t_start, **options)
                except ValueError as exc:
                    raise ValueError(f"{self._who}: no pulse fit: {exc}") from exc
                if len(_FIT_CACHE) >= _FIT_CACHE_SIZE:
                    _FIT_CACHE.pop(next(iter(_FIT_CACHE)))
                _FIT_CACHE[ckey] = fit
            self._fits[key] = fit
        return self._fits[key]

    @property
    def content_key(self) -> tuple:
        """``(sha256 of the samples, dt, t_start)``: equal for records with equal data."""
        key = self.__dict__.get("_content_key")
        if key is None:
            key = (hashlib.sha256(self.accel.tobytes()).hexdigest(), self.dt, self.t_start)
            object.__setattr__(self, "_content_key", key)
        return key

    def as_pulse(self, a_p=None, T_p=None, t_ref=0.0, *, shape: str = "ricker", polarity=1,
                 window=None) -> Pulse:
        """The record, as recorded, as a dimensionless sampled :class:`~isoslide.pulses.Pulse`.

        ``p(tau) = a_g(t) / (polarity * a_p)`` with ``tau = (t - t_ref) / T_p``,
        linear between samples and zero outside the record.  With the
        defaults the record runs as recorded: its own sign (``polarity = +1``)
        and its own time axis (``t_ref = 0``, so ``t = tau T_p`` is the record
        time), and the histories and signed residuals of a solve refer to the
        record itself.  Missing scales are those of the record's fitted pulse
        (:meth:`fit`, called only when ``a_p`` or ``T_p`` is missing); the
        fitted pulse's sign does not matter, ``a_p`` is a positive scale.

        To align the record with :meth:`PulseFit.as_pulse` (``tau = 0`` at the
        fitted peak, the dominant pulse positive) pass
        ``t_ref=fit.t_ref, polarity=fit.polarity``.

        Parameters
        ----------
        a_p : float, optional
            Acceleration scale, m/s^2 (> 0).  Default: fitted ``a_p``.
        T_p : float, optional
            Time scale, s (> 0).  Default: fitted ``T_p``.
        t_ref : float
            Record time that becomes ``tau = 0``, s (default 0: the record's
            own time axis).
        shape : str
            Which fit supplies missing scales.
        polarity : {+1, -1}
            Sign applied to the record (default +1: as recorded).
        window : (float, float), optional
            Keep only the samples with ``window[0] <= t <= window[1]`` (s).

        Returns
        -------
        Pulse
            A sampled pulse (:func:`isoslide.pulses.sampled`) named after the
            record, with knots at ``(t_i - t_ref) / T_p`` for the record times
            ``t_i``.
        """
        if a_p is None or T_p is None:
            fit = self.fit(shape)
            a_p = fit.a_p if a_p is None else a_p
            T_p = fit.T_p if T_p is None else T_p
        a_p, T_p, t_ref = float(a_p), float(T_p), float(t_ref)
        if not (math.isfinite(a_p) and a_p > 0):
            raise ValueError(f"a_p = {a_p!r} is invalid; allowed range: 0 < a_p < inf (m/s^2)")
        if not (math.isfinite(T_p) and T_p > 0):
            raise ValueError(f"T_p = {T_p!r} is invalid; allowed range: 0 < T_p < inf (s)")
        if not math.isfinite(t_ref):
            raise ValueError(f"t_ref = {t_ref!r} is invalid; allowed range: -inf < t_ref < inf (s)")
        if polarity not in (1, -1):
            raise ValueError(f"polarity = {polarity!r} is invalid; allowed: +1 or -1")
        i0, i1 = 0, self.npts
        if window is not None:
            t = self.time
            keep = np.nonzero((t >= window[0]) & (t <= window[1]))[0]
            if keep.size < 2:
                raise ValueError(f"window = {window!r} keeps fewer than 2 samples of {self._who} "
                                 f"(t from {t[0]:g} to {t[-1]:g} s)")
            i0, i1 = int(keep[0]), int(keep[-1]) + 1
        p = self.accel[i0:i1] * (G / (polarity * a_p))
        tau0 = (self.t_start + i0 * self.dt - t_ref) / T_p
        return sampled(p, self.dt / T_p, tau0, name=self.name)


_FIT_CACHE: dict = {}
"""Fits by record content and fit options (see :meth:`Record.fit`)."""
_FIT_CACHE_SIZE = 256
"""Most fits kept in :data:`_FIT_CACHE` (the oldest goes first)."""


def _hashable(v):
    """A hashable stand-in for a fit option (lists and arrays become tuples)."""
    if isinstance(v, (list, np.ndarray)):
        return tuple(np.asarray(v).ravel().tolist())
    return v
