"""The sample records shipped by the ``pyslammer`` package.

:func:`samples` lists them and :func:`sample` loads one as a
:class:`~isoslide.records.Record` (acceleration in g), read from the installed
package without importing it and without network access.  The records are
pyslammer package data, distributed with it under GPL-3.0-only
(:attr:`Record.licence <isoslide.records.Record.licence>` says so on every
loaded sample).
"""

from __future__ import annotations

import importlib.metadata
import importlib.resources
import importlib.util
from pathlib import Path

from .reading import read_csv
from .record import Record

__all__ = ["PULSE_LIKE_SAMPLES", "sample", "samples"]

PULSE_LIKE_SAMPLES = (
    "Kobe_1995_TAK-090",
    "Chi-Chi_1999_TCU068-090",
    "Northridge_1994_PAC-175",
    "Northridge_1994_VSP-360",
)
"""The pyslammer samples that are near-fault records with a dominant acceleration pulse."""

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
    """Terms under which the installed pyslammer distributes its sample records."""
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

