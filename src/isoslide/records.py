"""Real ground-motion records: readers, sample records and pulse extraction.

A :class:`Record` is a uniformly sampled horizontal ground acceleration
history.  **Units:** ``Record.accel`` is in units of standard gravity *g*
(``g = 9.80665 m/s^2``, :data:`isoslide.scene.G_STANDARD`), ``Record.dt`` and
all times are in seconds.  Fitted pulse amplitudes (:attr:`PulseFit.a_p`) are
in SI, **m/s^2**, so they can be passed straight to
:meth:`isoslide.Scene.from_physical`.

Readers
-------
* :func:`read_at2` -- PEER NGA ``.AT2`` files (NGA-West1 and NGA-West2 header
  variants, Fortran numbers run together such as ``1.2E-02-5.6E-03``);
* :func:`read_csv` -- two columns: time (s), acceleration (g by default);
* :func:`samples` / :func:`sample` -- the near-fault and other records that
  the ``pyslammer`` package ships (read from the installed package, no
  network).

Malformed input raises :class:`RecordFormatError` (a ``ValueError``) naming
the file, the line and what was expected; a truncated file never yields a
partial record.

Pulse extraction
----------------
:func:`fit_pulse` fits one analytical pulse to the *dominant acceleration
pulse* of a record by least squares:

1. a global search over ``(T_p, t_peak)``: for each trial period on a
   logarithmic grid the record is correlated with the unit-energy Ricker
   wavelet (a continuous wavelet transform with the Mexican-hat mother wavelet,
   Vassiliou & Makris 2011); with the amplitude profiled out, the squared
   normalised coefficient is exactly the reduction of the squared residual,
   so its maximum is the global least-squares optimum on the grid;
2. a local Levenberg-Marquardt style refinement (``scipy.optimize.least_squares``)
   of amplitude, period and time, on the continuous parameters.

The Mavroeidis & Papageorgiou (2003) pulse is fitted from many starts seeded
by the Ricker fit.  The fit is acceleration-based: it matches the pulse that
carries most of the acceleration energy, which for many near-fault records is
shorter than the velocity-pulse period usually quoted (Chi-Chi TCU068: 3.3 s
here against the ~12 s velocity pulse).  For Kobe Takatori 090, quoted at
about 1.2-1.6 s from velocity, the Ricker fit gives 1.56 s and the
Mavroeidis-Papageorgiou fit 1.24 s.

Measured fits of the pulse-like samples (Ricker; a_p in g, T_p in s, R^2 over
t_peak +- T_p): TAK-090 0.492, 1.561, 0.57; TCU068-090 0.249, 3.283, 0.40;
PAC-175 0.502, 0.470, 0.79; VSP-360 0.816, 0.460, 0.64.

Scenes excited by a record
--------------------------
``Scene(pi2, pi3, ..., pulse=record)`` calls :meth:`Record.as_pulse`, which
normalises the record by its fitted Ricker ``a_p`` and ``T_p`` and puts
``tau = 0`` at the fitted pulse peak, so record and fitted pulse are aligned
in ``tau`` and the Pi-groups of the scene use the fitted scales.  For other
scales pass ``pulse=record.as_pulse(a_p=..., T_p=...)``.
"""

from __future__ import annotations

import importlib.metadata
import importlib.resources
import importlib.util
import math
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .pulses import Pulse, get_pulse, ricker, sampled
from .scene import G_STANDARD

__all__ = [
    "G", "PULSE_LIKE_SAMPLES", "PulseFit", "Record", "RecordFormatError", "SHAPES",
    "fit_pulse", "read_at2", "read_csv", "sample", "samples",
]

G = G_STANDARD
"""Standard gravity used to convert g to m/s^2 (9.80665 m/s^2)."""

SHAPES = ("ricker", "mavroeidis_papageorgiou")
_MP_GAMMA_MAX = 6.0
"""Upper bound of the Mavroeidis-Papageorgiou oscillation parameter gamma in fits."""
"""Pulse shapes :func:`fit_pulse` can fit."""

_SHAPE_ALIASES = {"ricker": "ricker", "mavroeidis_papageorgiou": "mavroeidis_papageorgiou",
                  "mp": "mavroeidis_papageorgiou"}

PULSE_LIKE_SAMPLES = (
    "Kobe_1995_TAK-090",
    "Chi-Chi_1999_TCU068-090",
    "Northridge_1994_PAC-175",
    "Northridge_1994_VSP-360",
)
"""The pyslammer samples the issue names as near-fault pulse-like records."""


# --------------------------------------------------------------------------- errors


class RecordFormatError(ValueError):
    """A record file is malformed or truncated.

    Attributes
    ----------
    path : str
        The file.
    line : int or None
        1-based line number where the problem was found.
    expected : str
        What the reader expected there.
    """

    def __init__(self, path, line, expected, found=None):
        self.path = str(path)
        self.line = line
        self.expected = expected
        self.found = found
        where = f"{self.path}, line {line}" if line is not None else self.path
        msg = f"{where}: expected {expected}"
        if found is not None:
            msg += f"; found {found!r}"
        super().__init__(msg)


# --------------------------------------------------------------------------- record


@dataclass(frozen=True, eq=False)
class Record:
    """A uniformly sampled horizontal ground-acceleration record.

    Parameters
    ----------
    name : str
        Short identifier, e.g. ``"Kobe_1995_TAK-090"``.
    accel : array_like
        Ground acceleration, **in units of g** (9.80665 m/s^2).  Stored as a
        read-only float64 array.
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

    Notes
    -----
    Records compare by identity.  :meth:`fit` results are cached per shape.
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
        a = np.array(self.accel, dtype=np.float64)
        if a.ndim != 1 or a.size < 2:
            raise ValueError(f"Record {self.name!r}: accel must be a 1-D array of at least 2 samples, "
                             f"got shape {a.shape}")
        if not np.all(np.isfinite(a)):
            raise ValueError(f"Record {self.name!r}: accel contains NaN or inf")
        dt = float(self.dt)
        if not (math.isfinite(dt) and dt > 0):
            raise ValueError(f"Record {self.name!r}: dt = {self.dt!r} is invalid; allowed range: 0 < dt < inf (s)")
        a.setflags(write=False)
        object.__setattr__(self, "accel", a)
        object.__setattr__(self, "dt", dt)
        object.__setattr__(self, "t_start", float(self.t_start))

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
    def fit(self, shape: str = "ricker", **options) -> "PulseFit":
        """Fit an analytical pulse to the record's dominant acceleration pulse (cached).

        Parameters
        ----------
        shape : {"ricker", "mavroeidis_papageorgiou"}
            Pulse shape (``"mp"`` is an alias of the latter).
        **options
            Passed to :func:`fit_pulse` (``T_range``, ``t_range``, ...).

        Returns
        -------
        PulseFit
        """
        shape = _canonical_shape(shape)
        key = (shape, tuple(sorted((k, _hashable(v)) for k, v in options.items())))
        if key not in self._fits:
            self._fits[key] = fit_pulse(self.accel, self.dt, shape=shape, t_start=self.t_start, **options)
        return self._fits[key]

    def as_pulse(self, a_p=None, T_p=None, t_ref=None, *, shape: str = "ricker", polarity=None,
                 window=None) -> Pulse:
        """The record as a dimensionless sampled :class:`~isoslide.pulses.Pulse`.

        ``p(tau) = a_g(t) / (polarity * a_p)`` with ``tau = (t - t_ref) / T_p``,
        linear between samples and zero outside the record.  With the defaults
        the scales are those of the record's fitted pulse (:meth:`fit`), so the
        record and :meth:`PulseFit.as_pulse` are aligned in ``tau`` (for the
        Ricker ``tau = 0`` at the fitted peak, where the fitted pulse is ``+1``).

        Parameters
        ----------
        a_p : float, optional
            Acceleration scale, m/s^2 (> 0).  Default: fitted ``a_p``.
        T_p : float, optional
            Time scale, s (> 0).  Default: fitted ``T_p``.
        t_ref : float, optional
            Record time that becomes ``tau = 0``, s.  Default: the fit's
            :attr:`PulseFit.t_ref` (the peak for the Ricker, the envelope
            centre for Mavroeidis-Papageorgiou).
        shape : str
            Which fit supplies missing values.
        polarity : {+1, -1}, optional
            Sign applied so the dominant pulse is positive.  Default: the fit's.
        window : (float, float), optional
            Keep only the samples with ``window[0] <= t <= window[1]`` (s).

        Returns
        -------
        Pulse
        """
        if a_p is None or T_p is None or t_ref is None or polarity is None:
            fit = self.fit(shape)
            a_p = fit.a_p if a_p is None else a_p
            T_p = fit.T_p if T_p is None else T_p
            t_ref = fit.t_ref if t_ref is None else t_ref
            polarity = fit.polarity if polarity is None else polarity
        a_p, T_p, t_ref = float(a_p), float(T_p), float(t_ref)
        if not (math.isfinite(a_p) and a_p > 0):
            raise ValueError(f"a_p = {a_p!r} is invalid; allowed range: 0 < a_p < inf (m/s^2)")
        if not (math.isfinite(T_p) and T_p > 0):
            raise ValueError(f"T_p = {T_p!r} is invalid; allowed range: 0 < T_p < inf (s)")
        if polarity not in (1, -1):
            raise ValueError(f"polarity = {polarity!r} is invalid; allowed: +1 or -1")
        i0, i1 = 0, self.npts
        if window is not None:
            t = self.time
            keep = np.nonzero((t >= window[0]) & (t <= window[1]))[0]
            if keep.size < 2:
                raise ValueError(f"window = {window!r} keeps fewer than 2 samples of record {self.name!r} "
                                 f"(t from {t[0]:g} to {t[-1]:g} s)")
            i0, i1 = int(keep[0]), int(keep[-1]) + 1
        p = self.accel[i0:i1] * (G / (polarity * a_p))
        tau0 = (self.t_start + i0 * self.dt - t_ref) / T_p
        return sampled(p, self.dt / T_p, tau0, name=self.name)


def _hashable(v):
    if isinstance(v, (list, np.ndarray)):
        return tuple(np.asarray(v).ravel().tolist())
    return v


# --------------------------------------------------------------------------- AT2 reader

_NUM = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[EeDd][+-]?\d+)?")
_SEP = re.compile(r"[\s,]+")
_NPTS = re.compile(r"NPTS\s*=\s*([^\s,]+)", re.I)
_DT = re.compile(r"\bDT\s*=\s*([^\s,]+)", re.I)
_OLD_NPTS_DT = re.compile(r"^\s*(\S+)\s+(\S+)\s+NPTS\s*,\s*DT\b", re.I)
_UNITS = re.compile(r"UNITS\s+OF\s+(.+?)\s*$", re.I)

_UNIT_FACTORS = {  # multiply by this to get g
    "G": 1.0, "G'S": 1.0,
    "CM/S/S": 1.0 / (100 * G), "CM/SEC/SEC": 1.0 / (100 * G), "CM/S^2": 1.0 / (100 * G),
    "CM/S2": 1.0 / (100 * G), "CM/SEC2": 1.0 / (100 * G), "CM/SEC^2": 1.0 / (100 * G), "GAL": 1.0 / (100 * G),
    "M/S/S": 1.0 / G, "M/SEC/SEC": 1.0 / G, "M/S^2": 1.0 / G, "M/S2": 1.0 / G, "M/SEC^2": 1.0 / G,
    "MM/S/S": 1.0 / (1000 * G), "MM/S^2": 1.0 / (1000 * G), "MM/S2": 1.0 / (1000 * G),
}


def _unit_factor(units: str, path, line) -> float:
    key = units.strip().upper().replace(" ", "").rstrip(".")
    if key not in _UNIT_FACTORS:
        raise RecordFormatError(path, line, f"acceleration units, one of {sorted(_UNIT_FACTORS)}", units)
    return _UNIT_FACTORS[key]


def _tokens(text: str, path, lineno: int) -> list[float]:
    """Split one data line into floats.

    Whitespace and commas separate numbers.  Numbers may also run together
    when the next one starts with a sign (``1.2E-02-5.6E-03``) or is a
    leading-dot number after an exponent (``.12E-01.34E-01``); any other
    adjacency (``0.1230.456``, ``0.1234-102``) is ambiguous and rejected.
    """
    out, out_text = [], []
    pos, n = 0, len(text)
    separated = True
    while pos < n:
        m = _SEP.match(text, pos)
        if m:
            pos = m.end()
            separated = True
            continue
        m = _NUM.match(text, pos)
        if not m:
            w0 = len(text[:pos]) - len(re.split(r"[\s,]", text[:pos])[-1])
            bad = re.split(r"[\s,]", text[w0:])[0]
            raise RecordFormatError(path, lineno, f"a number at column {pos + 1}", bad)
        tok = m.group(0)
        if not separated:
            plain = tok.lstrip("+-")
            signed = tok[0] in "+-" and ("." in plain or "e" in plain.lower() or "d" in plain.lower())
            after_exponent = (tok[0] == "." and re.search(r"[EeDd][+-]?\d\d$", out_text[-1]) is not None
                              and re.search(r"[EeDd][+-]?\d+$", tok) is not None)
            if not (signed or after_exponent):
                raise RecordFormatError(
                    path, lineno, f"numbers separated by blanks, commas or a sign at column {pos + 1} "
                    "(ambiguous run-together numbers)", text[max(0, pos - 12):m.end()].strip())
        out.append(float(tok.replace("D", "E").replace("d", "e")))
        out_text.append(tok)
        pos = m.end()
        separated = False
    return out


def _parse_int(text, path, line, what):
    try:
        v = float(text)
    except ValueError:
        raise RecordFormatError(path, line, f"an integer {what}", text) from None
    if not v.is_integer() or v < 2:
        raise RecordFormatError(path, line, f"an integer {what} >= 2", text)
    return int(v)


def _parse_dt(text, path, line):
    try:
        v = float(text.replace("D", "E").replace("d", "e"))
    except ValueError:
        raise RecordFormatError(path, line, "a time step DT in seconds", text) from None
    if not (math.isfinite(v) and v > 0):
        raise RecordFormatError(path, line, "a time step DT > 0 (s)", text)
    return v


def _header_line2(text: str):
    """Best-effort ``event, station, component`` from the second AT2 header line."""
    parts = [p.strip() for p in text.split(",") if p.strip()]
    if len(parts) >= 3:
        return ", ".join(parts[:-2]), parts[-2], parts[-1]
    if len(parts) == 2:
        return parts[0], parts[1], ""
    return text.strip(), "", ""


def read_at2(path, name: str | None = None, units: str | None = None) -> Record:
    """Read a PEER NGA strong-motion ``.AT2`` acceleration file.

    Layout: four header lines -- a title, ``event, [date,] station,
    component``, ``ACCELERATION TIME SERIES IN UNITS OF G``, and the sampling
    line in either of its two variants::

        NPTS=  1990, DT=   .0100 SEC          (NGA-West2)
          1990   .0100    NPTS, DT             (older NGA files)

    followed by ``NPTS`` values, any number per line, separated by blanks or
    commas or run together when the next one starts with a sign
    (``.1234E-02-.5678E-03``).

    Parameters
    ----------
    path : str or Path
        The file.
    name : str, optional
        Record name; default: the file name without extension.
    units : str, optional
        Override the units stated in the header (``"g"``, ``"cm/s/s"``, ...).

    Returns
    -------
    Record
        Acceleration in g, ``dt`` in s.

    Raises
    ------
    RecordFormatError
        Missing or malformed header, a non-numeric or ambiguous token, or a
        value count different from ``NPTS``; the message names the file, the
        line and what was expected.
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8-sig", errors="strict")
    except UnicodeDecodeError:
        text = path.read_text(encoding="latin-1")
    lines = text.splitlines()
    if not lines:
        raise RecordFormatError(path, 1, "a PEER NGA AT2 header (4 lines)", "empty file")

    # locate the NPTS/DT line among the first few lines
    npts = dt = None
    hdr_end = None
    for i, raw in enumerate(lines[:8]):
        m_n, m_d = _NPTS.search(raw), _DT.search(raw)
        if m_n or m_d:
            if not (m_n and m_d):
                raise RecordFormatError(path, i + 1, "both NPTS=<int> and DT=<seconds> on the sampling line", raw.strip())
            npts = _parse_int(m_n.group(1), path, i + 1, "NPTS")
            dt = _parse_dt(m_d.group(1), path, i + 1)
            hdr_end = i
            break
        m = _OLD_NPTS_DT.match(raw)
        if m:
            npts = _parse_int(m.group(1), path, i + 1, "NPTS")
            dt = _parse_dt(m.group(2), path, i + 1)
            hdr_end = i
            break
    if hdr_end is None:
        line = min(4, len(lines))
        raise RecordFormatError(path, line, "the sampling line 'NPTS= <int>, DT= <seconds> SEC' or "
                                "'<npts> <dt> NPTS, DT' within the first 8 lines",
                                lines[line - 1].strip() if lines else None)

    header = lines[:hdr_end]
    # quantity and units
    factor = None
    for i, raw in enumerate(header):
        up = raw.upper()
        if "VELOCITY" in up or "DISPLACEMENT" in up:
            if "TIME" in up or "UNITS" in up:
                raise RecordFormatError(path, i + 1, "an acceleration record (AT2)", raw.strip())
        m = _UNITS.search(raw)
        if m:
            factor = _unit_factor(m.group(1).split()[0] if units is None else units, path, i + 1)
    if factor is None:
        if units is None:
            raise RecordFormatError(path, min(3, hdr_end + 1),
                                    "a header line stating the units, e.g. "
                                    "'ACCELERATION TIME SERIES IN UNITS OF G' (or pass units=)",
                                    header[2].strip() if len(header) > 2 else None)
        factor = _unit_factor(units, path, None)

    event = station = component = ""
    if len(header) >= 2:
        event, station, component = _header_line2(header[1])

    values: list[float] = []
    last_data_line = hdr_end + 1
    for j in range(hdr_end + 1, len(lines)):
        raw = lines[j]
        if not raw.strip():
            continue
        vals = _tokens(raw, path, j + 1)
        if len(values) + len(vals) > npts:
            raise RecordFormatError(path, j + 1, f"{npts} values in all (NPTS on line {hdr_end + 1}); "
                                    f"extra values start here", raw.strip())
        values.extend(vals)
        last_data_line = j + 1
    if len(values) != npts:
        raise RecordFormatError(path, last_data_line,
                                f"{npts} values (NPTS on line {hdr_end + 1}); file ends after "
                                f"{len(values)} values (truncated file)")
    acc = np.asarray(values) * factor
    if not np.all(np.isfinite(acc)):
        raise RecordFormatError(path, None, "finite acceleration values")
    return Record(name or path.stem, acc, dt, event=event, station=station, component=component,
                  source=str(path), licence="")


# --------------------------------------------------------------------------- CSV reader


def _csv_fields(raw: str):
    s = raw.strip()
    if "," in s:
        parts = [p.strip() for p in s.split(",")]
    elif ";" in s:
        parts = [p.strip() for p in s.split(";")]
    else:
        parts = s.split()
    while parts and parts[-1] == "":
        parts.pop()
    return parts


def _is_number(s: str) -> bool:
    try:
        float(s)
        return True
    except ValueError:
        return False


def read_csv(path, name: str | None = None, units: str = "g", dt_tolerance: float = 0.01, **metadata) -> Record:
    """Read a two-column text record: time (s), acceleration.

    Columns are separated by a comma (or a semicolon, or blanks).  Blank lines
    and lines starting with ``#`` are skipped; one non-numeric header row is
    allowed before the data.  The time step must be uniform.

    Parameters
    ----------
    path : str or Path
        The file.
    name : str, optional
        Record name; default: the file name without extension.
    units : str
        Units of the acceleration column: ``"g"`` (default), ``"m/s2"``,
        ``"cm/s2"`` (also ``"m/s/s"``, ``"gal"``, ...).
    dt_tolerance : float
        Allowed deviation of each time step from the mean step, as a
        fraction of it (rounded time columns).
    **metadata
        ``event``, ``station``, ``component``, ``source``, ``licence``.

    Returns
    -------
    Record
        Acceleration in g, ``dt`` in s, ``t_start`` = first time.

    Raises
    ------
    RecordFormatError
        A row without exactly two numbers, fewer than two rows, or a
        non-uniform or non-increasing time column; the message names the file
        and the line.
    """
    path = Path(path)
    factor = _unit_factor(units, path, None)
    text = path.read_text(encoding="utf-8-sig")
    t, a, linenos = [], [], []
    header_seen = False
    for i, raw in enumerate(text.splitlines(), start=1):
        s = raw.strip().lstrip("\ufeff")
        if not s or s.startswith("#"):
            continue
        parts = _csv_fields(s)
        if len(parts) != 2 or not all(_is_number(p) for p in parts):
            if not t and not header_seen and not any(_is_number(p) for p in parts):
                header_seen = True  # a column-title row
                continue
            raise RecordFormatError(path, i, "two numbers: time (s), acceleration", s)
        t.append(float(parts[0]))
        a.append(float(parts[1]))
        linenos.append(i)
    if len(t) < 2:
        raise RecordFormatError(path, linenos[-1] if linenos else None,
                                "at least two data rows (time, acceleration)",
                                f"{len(t)} data row(s)")
    t = np.asarray(t)
    acc = np.asarray(a)
    if not np.all(np.isfinite(t)) or not np.all(np.isfinite(acc)):
        k = int(np.nonzero(~(np.isfinite(t) & np.isfinite(acc)))[0][0])
        raise RecordFormatError(path, linenos[k], "finite numbers", f"{t[k]}, {acc[k]}")
    steps = np.diff(t)
    dt = float(np.median(steps))
    bad = np.nonzero(~(np.abs(steps - dt) <= dt_tolerance * abs(dt)) | (steps <= 0))[0]
    if dt <= 0 or bad.size:
        k = int(bad[0]) + 1 if bad.size else 1
        raise RecordFormatError(path, linenos[k], f"a uniform, increasing time step of {dt:.6g} s "
                                f"(tolerance {dt_tolerance:.0%})", f"time {t[k]:.6g} after {t[k - 1]:.6g}")
    dt = (t[-1] - t[0]) / (t.size - 1)  # mean step: removes the rounding of the time column
    meta = {"source": str(path)} | metadata
    return Record(name or path.stem, acc * factor, float(dt), t_start=float(t[0]), **meta)


# --------------------------------------------------------------------------- pyslammer samples

_PYSLAMMER_DIR = "sample_ground_motions"
_STATION_NAMES = {"TAK": "Takatori", "TCU068": "TCU068"}
"""Station codes whose full name is certain; others keep the code."""


def _pyslammer_dir():
    """Directory of pyslammer's sample records (located without importing pyslammer)."""
    spec = importlib.util.find_spec("pyslammer")
    if spec is None:
        raise ModuleNotFoundError("the sample records come from the 'pyslammer' package, which is not "
                                  "installed (pip install pyslammer)")
    if spec.submodule_search_locations:
        d = Path(next(iter(spec.submodule_search_locations))) / _PYSLAMMER_DIR
        if d.is_dir():
            return d
    return importlib.resources.files("pyslammer") / _PYSLAMMER_DIR  # pragma: no cover


def _pyslammer_licence() -> str:
    try:
        ver = importlib.metadata.version("pyslammer")
    except importlib.metadata.PackageNotFoundError:  # pragma: no cover
        ver = "?"
    return (f"pyslammer {ver} package data, distributed with the package under GPL-3.0-only; "
            "the upstream source of the records is not stated in the package (the names follow "
            "the USGS SLAMMER record library)")


def samples() -> tuple[str, ...]:
    """Names of the sample records shipped by the installed ``pyslammer`` package.

    Returns
    -------
    tuple of str
        Sorted names such as ``"Kobe_1995_TAK-090"`` (file stems); see also
        :data:`PULSE_LIKE_SAMPLES`.
    """
    d = _pyslammer_dir()
    return tuple(sorted(p.name[:-4] for p in d.iterdir() if p.name.endswith(".csv")))


def sample(name: str) -> Record:
    """Load one of the ``pyslammer`` sample records.

    Parameters
    ----------
    name : str
        A name from :func:`samples`, or any case-insensitive part of one that
        matches exactly one record (e.g. ``"TAK-090"``, ``"tcu068"``).

    Returns
    -------
    Record
        Acceleration in g, ``dt`` in s; metadata parsed from the file header.
    """
    names = samples()
    if name.endswith(".csv"):
        name = name[:-4]
    if name not in names:
        hits = [n for n in names if name.lower() in n.lower()]
        if len(hits) != 1:
            raise ValueError(f"sample = {name!r} is invalid; allowed: one of {names} "
                             f"(or a part matching exactly one; matched {hits})")
        name = hits[0]
    path = _pyslammer_dir() / f"{name}.csv"
    title = ""
    with open(path, encoding="utf-8-sig") as fh:
        for raw in fh:
            s = raw.strip().lstrip("\ufeff")
            if s.startswith("#") and "time series" in s.lower():
                title = s.split(":", 1)[1].strip().rstrip(",").strip()
                break
    event, _, sc = title.rpartition(" - ")
    station, _, component = sc.rpartition("-")
    station = _STATION_NAMES.get(station, station)
    return read_csv(path, name=name, units="g", event=event, station=station, component=component,
                    source=f"pyslammer:{_PYSLAMMER_DIR}/{name}.csv", licence=_pyslammer_licence())


# --------------------------------------------------------------------------- analytic shapes (physical time)

_PI = math.pi
_PI2 = _PI * _PI


def _ricker_shape(x):
    """Unit Ricker acceleration ``(1 - 2 pi^2 x^2) exp(-pi^2 x^2)``, x = (t - t_peak)/T_p."""
    s = _PI2 * x * x
    return (1.0 - 2.0 * s) * np.exp(-s)


def _mp_accel(t, A, t0, T, gamma, nu):
    """Mavroeidis-Papageorgiou (2003) acceleration, m/s^2, for velocity amplitude ``A`` (m/s).

    ``v = A/2 [1 + cos(2 pi x / gamma)] cos(2 pi x + nu)`` for ``|x| <= gamma/2``,
    ``x = (t - t0) / T``, and ``a = dv/dt``.
    """
    x = (np.asarray(t, dtype=float) - t0) / T
    inside = np.abs(x) <= 0.5 * gamma
    ph = 2 * _PI * x + nu
    env = 2 * _PI * x / gamma
    a = -(A * _PI / (gamma * T)) * (np.sin(env) * np.cos(ph) + gamma * (1 + np.cos(env)) * np.sin(ph))
    return np.where(inside, a, 0.0)


def _mp_jac(t, A, t0, T, gamma, nu):
    """Jacobian of :func:`_mp_accel` with respect to ``(A, t0, T, gamma, nu)``, shape (n, 5)."""
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


def _mp_velocity(t, A, t0, T, gamma, nu):
    x = (np.asarray(t, dtype=float) - t0) / T
    inside = np.abs(x) <= 0.5 * gamma
    v = 0.5 * A * (1 + np.cos(2 * _PI * x / gamma)) * np.cos(2 * _PI * x + nu)
    return np.where(inside, v, 0.0)


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
        t = np.asarray(t, dtype=float)
        if self.shape == "ricker":
            return self.polarity * self.a_p * _ricker_shape((t - self.t_peak) / self.T_p)
        p = self.shape_params
        return _mp_accel(t, p["A"], p["t0"], self.T_p, p["gamma"], p["nu"])

    def velocity(self, t) -> np.ndarray:
        """Fitted ground velocity at record times ``t`` (s), m/s, from rest before the pulse."""
        t = np.asarray(t, dtype=float)
        if self.shape == "ricker":
            x = (t - self.t_peak) / self.T_p
            return self.polarity * self.a_p * self.T_p * x * np.exp(-_PI2 * x * x)
        p = self.shape_params
        return _mp_velocity(t, p["A"], p["t0"], self.T_p, p["gamma"], p["nu"])

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


def _canonical_shape(shape: str) -> str:
    s = _SHAPE_ALIASES.get(str(shape).lower())
    if s is None:
        raise ValueError(f"shape = {shape!r} is invalid; allowed: one of {SHAPES} (or 'mp')")
    return s


def _ricker_grid_search(a, dt, T_grid, i_lo, i_hi):
    """Global least-squares search of (T_p, t_peak) by correlation with the Ricker wavelet."""
    from scipy.signal import fftconvolve

    best = (-1.0, None, None, None)
    for T in T_grid:
        J = int(math.ceil(2.0 * T / dt))
        k = _ricker_shape(np.arange(-J, J + 1) * dt / T)
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

    Notes
    -----
    The Ricker fit minimises ``sum (a - A r((t - t_peak)/T_p))^2`` over the
    whole record; the Mavroeidis-Papageorgiou fit minimises the same with its
    own shape, starting from 36 seeds around the Ricker fit.
    """
    from scipy.optimize import least_squares

    shape = _canonical_shape(shape)
    a = np.asarray(accel, dtype=float)
    if a.ndim != 1 or a.size < 8:
        raise ValueError(f"accel must be a 1-D array of at least 8 samples, got shape {a.shape}")
    if not np.all(np.isfinite(a)):
        raise ValueError("accel contains NaN or inf")
    dt = float(dt)
    if not (math.isfinite(dt) and dt > 0):
        raise ValueError(f"dt = {dt!r} is invalid; allowed range: 0 < dt < inf (s)")
    a = a * (_unit_factor(units, "<accel>", None) * G)  # -> m/s^2
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
            return p[0] * _ricker_shape((tw - p[1]) / p[2]) - aw

        x0 = np.array([x[0], np.clip(x[1], t_lo_b, t_hi_b), np.clip(x[2], T_lo, T_hi)])
        sol = least_squares(res, x0, bounds=([-np.inf, t_lo_b, T_lo], [np.inf, t_hi_b, T_hi]),
                            x_scale=[abs(A0) or 1.0, T0, T0], xtol=1e-12, ftol=1e-12, gtol=1e-12)
        moved = abs(sol.x[2] - Tw) > 0.3 * Tw
        x = sol.x
        if not moved:
            break
    A, tp, Tp = (float(v) for v in x)
    ricker_fit = _goodness(a, t, lambda tt: A * _ricker_shape((tt - tp) / Tp), tp - Tp, tp + Tp,
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
        return least_squares(lambda p: _mp_accel(tt, *p) - yy, x0, jac=lambda p: _mp_jac(tt, *p),
                             bounds=(lo, hi), x_scale=[abs(x0[0]) or 1.0, Tp, Tp, 1.0, 1.0],
                             xtol=tol, ftol=tol, max_nfev=max_nfev)

    ts, as_ = tw[::step], aw[::step]
    best = None
    for Tf in (0.8, 1.0, 1.25):
        for gam in (1.5, 2.5, 4.0):
            for nu in (0.0, 0.5 * _PI, _PI, 1.5 * _PI):
                T_s = float(np.clip(Tf * Tp, T_mlo, T_mhi))
                m = _mp_accel(ts, 1.0, tp, T_s, gam, nu)
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
    af = _mp_accel(tt, Av, t0, Tm, gam, nu)
    k = int(np.argmax(np.abs(af)))
    # exact peak from the pulses module's normalisation: a_p = pi A N / T_p, N = max |raw shape|
    a_p = _PI * Av / Tm / get_pulse("mavroeidis_papageorgiou", gamma=gam, nu=nu).params[2]
    params = (("gamma", gam), ("nu", nu), ("t0", t0), ("A", Av))
    return _goodness(a, t, lambda s: _mp_accel(s, Av, t0, Tm, gam, nu),
                     t0 - 0.5 * gam * Tm, t0 + 0.5 * gam * Tm, shape="mavroeidis_papageorgiou",
                     a_p=float(a_p), T_p=Tm, t_peak=float(tt[k]),
                     polarity=1 if af[k] >= 0 else -1, params=params)


def _goodness(a, t, model, w_lo, w_hi, **kw) -> PulseFit:
    m = model(t)
    res = a - m
    inw = (t >= w_lo) & (t <= w_hi)
    ss_w = float(np.dot(a[inw], a[inw]))
    rr_w = float(np.dot(res[inw], res[inw]))
    r2 = 1.0 - rr_w / ss_w if ss_w > 0 else math.nan
    nrmse = math.sqrt(rr_w / max(int(inw.sum()), 1)) / kw["a_p"] if kw["a_p"] > 0 else math.nan
    ef = 1.0 - float(np.dot(res, res)) / float(np.dot(a, a))
    return PulseFit(r2=r2, nrmse=nrmse, energy_fraction=ef, window=(float(w_lo), float(w_hi)), **kw)
