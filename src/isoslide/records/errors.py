"""The error raised for malformed or truncated record files."""

from __future__ import annotations

__all__ = ["RecordFormatError"]


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
