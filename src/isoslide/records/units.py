"""Acceleration units of records and their conversion to units of g."""

from __future__ import annotations

from ..scene import G_STANDARD
from .errors import RecordFormatError

__all__ = ["G", "unit_factor"]

G = G_STANDARD
"""Standard gravity used to convert g to m/s^2 (9.80665 m/s^2)."""

_UNIT_FACTORS = {  # multiply by this to get g
    "G": 1.0, "G'S": 1.0,
    "CM/S/S": 1.0 / (100 * G), "CM/SEC/SEC": 1.0 / (100 * G), "CM/S^2": 1.0 / (100 * G),
    "CM/S2": 1.0 / (100 * G), "CM/SEC2": 1.0 / (100 * G), "CM/SEC^2": 1.0 / (100 * G), "GAL": 1.0 / (100 * G),
    "M/S/S": 1.0 / G, "M/SEC/SEC": 1.0 / G, "M/S^2": 1.0 / G, "M/S2": 1.0 / G, "M/SEC^2": 1.0 / G,
    "MM/S/S": 1.0 / (1000 * G), "MM/S^2": 1.0 / (1000 * G), "MM/S2": 1.0 / (1000 * G),
}


def unit_factor(units: str, path, line) -> float:
    """Factor that converts an acceleration in ``units`` to units of g.

    Parameters
    ----------
    units : str
        Unit name, case and blanks ignored: ``"g"``, ``"cm/s/s"``, ``"gal"``,
        ``"m/s2"``, ``"mm/s^2"``, ...
    path : str or Path
        File (or label) named in the error message.
    line : int or None
        Line named in the error message.

    Returns
    -------
    float
        An acceleration in ``units`` times this factor is the acceleration in g.

    Raises
    ------
    RecordFormatError
        Unknown units.
    """
    key = units.strip().upper().replace(" ", "").rstrip(".")
    if key not in _UNIT_FACTORS:
        raise RecordFormatError(path, line, f"acceleration units, one of {sorted(_UNIT_FACTORS)}", units)
    return _UNIT_FACTORS[key]
