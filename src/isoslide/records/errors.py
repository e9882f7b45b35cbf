"""The error raised for malformed or truncated record files, and the bound on a record's values."""

from __future__ import annotations

__all__ = ["MAX_ABS_ACCEL_G", "RecordFormatError"]

MAX_ABS_ACCEL_G = 100.0
"""Largest ground acceleration a record may hold, in g (|a| <= 100 g).

Earthquake records peak at a few g; a larger value is a damaged file or a
wrong unit, so the readers, :class:`~isoslide.records.Record` and
:func:`~isoslide.records.fit_pulse` refuse it (the readers name the file, the
line and the value).
"""


class RecordFormatError(ValueError):
    """A record file is malformed or truncated.

    Parameters
    ----------
    path : str or Path
        The file (or a label such as ``"<accel>"`` for an array).
    line : int or None
        1-based line number where the problem was found.
    expected : str
        What the reader expected there.
    found : object, optional
        What it found instead.

    Attributes
    ----------
    path : str
        The file.
    line : int or None
        1-based line number where the problem was found.
    expected : str
        What the reader expected there.
    found : object or None
        What it found instead.
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
