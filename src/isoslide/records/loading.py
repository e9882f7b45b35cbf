"""One record from what a user types: a file path (``.AT2``, ``.csv``) or a sample name."""

from __future__ import annotations

from pathlib import Path

from .reading import read_at2, read_csv
from .record import Record
from .samples import sample, samples

__all__ = ["RECORD_SUFFIXES", "load_record"]

RECORD_SUFFIXES = (".at2", ".csv")
"""File extensions :func:`load_record` reads (case-insensitive)."""


def load_record(spec) -> Record:
    """A :class:`Record` from a record, a file path or a bundled sample name.

    Parameters
    ----------
    spec : Record or str or Path
        A record (returned as is); a path to a PEER ``.AT2`` file or a
        two-column ``.csv`` file (time in s, acceleration in g); or a name (or
        unique part of one) from :func:`isoslide.records.samples`.

    Returns
    -------
    Record

    Raises
    ------
    ValueError
        A path that does not exist or has another extension, an unknown
        sample name, or a malformed file (:class:`RecordFormatError`); the
        message names ``record`` and the value.
    """
    if isinstance(spec, Record):
        return spec
    text = str(spec)
    path = Path(text)
    suffix = path.suffix.lower()
    if suffix in RECORD_SUFFIXES:
        if not path.is_file():
            raise ValueError(f"record = {text!r}: no such file")
        try:
            return read_at2(path) if suffix == ".at2" else read_csv(path)
        except UnicodeDecodeError as exc:
            raise ValueError(f"record = {text!r}: not a text file ({exc.reason})") from None
        except OSError as exc:
            raise ValueError(f"record = {text!r}: cannot be read ({exc.strerror})") from None
    if path.exists() or "/" in text or "\\" in text:
        raise ValueError(f"record = {text!r} is invalid; allowed: a file ending in "
                         f"{' or '.join(RECORD_SUFFIXES)} (any case), or a sample name (isoslide records pyslammer)")
    hits = [n for n in samples() if text.lower() in n.lower()]
    if text not in hits and len(hits) != 1:
        raise ValueError(f"record = {text!r} is not a .at2/.csv file or a bundled sample; allowed: a sample "
                         f"name or a part matching exactly one (isoslide records pyslammer lists them; matched {hits})")
    return sample(text)
