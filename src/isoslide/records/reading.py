"""Readers of record files: PEER NGA ``.AT2`` and two-column text.

* :func:`read_at2` -- PEER NGA ``.AT2`` files (NGA-West1 and NGA-West2 header
  variants, Fortran numbers run together such as ``1.2E-02-5.6E-03``);
* :func:`read_csv` -- two columns: time (s), acceleration (g by default).

Both return a :class:`~isoslide.records.Record` with the acceleration in g.
Malformed input raises :class:`~isoslide.records.RecordFormatError` (a
``ValueError``) naming the file, the line and what was expected; a truncated
file never yields a partial record, and an acceleration beyond ``|a| <= 100 g``
(:data:`~isoslide.records.errors.MAX_ABS_ACCEL_G`) is refused with its line and
value.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np

from .errors import MAX_ABS_ACCEL_G, RecordFormatError
from .record import Record
from .units import unit_factor

__all__ = ["read_at2", "read_csv"]


# --------------------------------------------------------------------------- AT2 reader

_NUM = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[EeDd][+-]?\d+)?")
_SEP = re.compile(r"[\s,]+")
_NPTS = re.compile(r"NPTS\s*=\s*([^\s,]+)", re.I)
_DT = re.compile(r"\bDT\s*=\s*([^\s,]+)", re.I)
_OLD_NPTS_DT = re.compile(r"^\s*(\S+)\s+(\S+)\s+NPTS\s*,\s*DT\b", re.I)
_UNITS = re.compile(r"UNITS\s+OF\s+(.+?)\s*$", re.I)


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
        Missing or malformed header, a non-numeric or ambiguous token, a
        value count different from ``NPTS``, or an acceleration beyond
        ``|a| <= 100 g`` (:data:`~isoslide.records.errors.MAX_ABS_ACCEL_G`);
        the message names the file, the line and what was expected.
    """
    path = Path(path)
    text = _read_text(path, fallback="latin-1")
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

    if not math.isfinite(dt * (npts - 1)):
        raise RecordFormatError(path, hdr_end + 1, "a time step DT that keeps the duration (NPTS - 1) DT "
                                "finite (s)", lines[hdr_end].strip())
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
            factor = unit_factor(m.group(1).split()[0] if units is None else units, path, i + 1)
    if factor is None:
        if units is None:
            raise RecordFormatError(path, min(3, hdr_end + 1),
                                    "a header line stating the units, e.g. "
                                    "'ACCELERATION TIME SERIES IN UNITS OF G' (or pass units=)",
                                    header[2].strip() if len(header) > 2 else None)
        factor = unit_factor(units, path, None)

    event = station = component = ""
    if len(header) >= 2:
        event, station, component = _header_line2(header[1])

    values: list[float] = []
    linenos: list[int] = []
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
        linenos.extend([j + 1] * len(vals))
        last_data_line = j + 1
    if len(values) != npts:
        raise RecordFormatError(path, last_data_line,
                                f"{npts} values (NPTS on line {hdr_end + 1}); file ends after "
                                f"{len(values)} values (truncated file)")
    acc = _checked_accel(np.asarray(values), factor, linenos, path)
    return Record(name or path.stem, acc, dt, event=event, station=station, component=component,
                  source=str(path), licence="")



def _checked_accel(values: np.ndarray, factor: float, linenos, path) -> np.ndarray:
    """``values * factor`` (g), refusing a non-finite value or one beyond :data:`MAX_ABS_ACCEL_G`.

    Parameters
    ----------
    values : ndarray
        Accelerations as written in the file.
    factor : float
        Conversion of the file's units to g.
    linenos : sequence of int
        1-based line of each value.
    path : str or Path
        The file, named in the error.

    Returns
    -------
    ndarray
        Accelerations in g.

    Raises
    ------
    RecordFormatError
        Names the file, the line and the first offending value.
    """
    with np.errstate(over="ignore", invalid="ignore"):
        acc = values * factor
        bad = np.nonzero(~(np.abs(acc) <= MAX_ABS_ACCEL_G))[0]
    if bad.size:
        k = int(bad[0])
        raise RecordFormatError(path, linenos[k], f"a finite acceleration within |a| <= {MAX_ABS_ACCEL_G:g} g "
                                "(a larger value is no ground motion: a damaged file or wrong units)",
                                f"{values[k]:.6g}" + ("" if factor == 1.0 else f" ({acc[k]:.6g} g)"))
    return acc


def _read_text(path: Path, fallback: str | None = None) -> str:
    """The file's text (UTF-8, a BOM dropped; else ``fallback``); undecodable bytes are a RecordFormatError."""
    data = path.read_bytes()
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        if fallback is not None:
            return data.decode(fallback)
        line = data[:exc.start].count(b"\n") + 1
        raise RecordFormatError(path, line, "a text file in UTF-8",
                                f"not a text file ({exc.reason} at byte {exc.start})") from None


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
    path, name
        The file and the record's name, as for :func:`read_at2`.
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
        A file that is not UTF-8 text, a row without exactly two numbers,
        fewer than two rows, a non-uniform or non-increasing time column, or
        an acceleration beyond ``|a| <= 100 g``
        (:data:`~isoslide.records.errors.MAX_ABS_ACCEL_G`); the message names
        the file and the line.
    """
    path = Path(path)
    factor = unit_factor(units, path, None)
    text = _read_text(path)
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
    acc = _checked_accel(acc, factor, linenos, path)
    with np.errstate(over="ignore", invalid="ignore"):
        steps = np.diff(t)
        dt = float(np.median(steps))
        bad = np.nonzero(~(np.abs(steps - dt) <= dt_tolerance * abs(dt)) | (steps <= 0))[0]
    if not (math.isfinite(dt) and dt > 0) or bad.size:
        k = int(bad[0]) + 1 if bad.size else 1
        raise RecordFormatError(path, linenos[k], f"a uniform, increasing time step of {dt:.6g} s "
                                f"(tolerance {dt_tolerance:.0%})", f"time {t[k]:.6g} after {t[k - 1]:.6g}")
    dt = (t[-1] - t[0]) / (t.size - 1)  # mean step: removes the rounding of the time column
    if not (math.isfinite(dt) and dt > 0):
        raise RecordFormatError(path, linenos[-1], "a finite time span (s)", f"{t[0]:.6g} to {t[-1]:.6g}")
    meta = {"source": str(path)} | metadata
    return Record(name or path.stem, acc, float(dt), t_start=float(t[0]), **meta)

