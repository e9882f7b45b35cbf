"""Input validation with errors that name the parameter, its value and the allowed range."""

from __future__ import annotations

import math


def range_text(lo: float, hi: float, lo_in: bool = True, hi_in: bool = True) -> str:
    """Human-readable interval, e.g. ``0 < value <= 1``."""
    return f"{lo:g} {'<=' if lo_in else '<'} value {'<=' if hi_in else '<'} {hi:g}"


def check_range(name: str, value, lo: float, hi: float, lo_in: bool = True, hi_in: bool = True) -> float:
    """Return ``float(value)`` or raise ``ValueError`` naming the parameter, value and range.

    NaN, infinities, booleans and non-numbers are rejected.
    """
    if isinstance(value, bool):
        x = math.nan
    else:
        try:
            x = float(value)
        except (TypeError, ValueError):
            raise ValueError(f"{name} = {value!r} is not a number; allowed range: "
                             f"{range_text(lo, hi, lo_in, hi_in)}") from None
    ok = math.isfinite(x) and (x >= lo if lo_in else x > lo) and (x <= hi if hi_in else x < hi)
    if not ok:
        raise ValueError(f"{name} = {value!r} is out of range; allowed range: "
                         f"{range_text(lo, hi, lo_in, hi_in)}")
    return x
