"""Time histories of a solve as tables: ground, floor and block motion, to CSV or HDF5.

:func:`history_table` turns the solver's :class:`~isoslide.store.history.History`
(``tau, x, x', u, u', phase``) into the motion of the ground, the floor and the
block; :func:`write_history` writes it to ``.csv`` or ``.h5``/``.hdf5`` (chosen
by the file extension; HDF5 through h5py, units as attributes) and
:func:`read_history` reads either back.

Columns (:data:`COLUMNS`), in SI units when the scene was built with
:meth:`isoslide.Scene.from_physical` and dimensionless (units of ``T_p``,
``a_p``, ``a_p T_p``, ``a_p T_p^2``) otherwise:

============== =================================================== ========= ===========
name           meaning                                             SI unit   scale
============== =================================================== ========= ===========
time           time (``t = tau T_p``, the pulse's or record's)     s         T_p
ground_accel   ground acceleration                                 m s-2     a_p
floor_accel    absolute floor acceleration                         m s-2     a_p
floor_disp     floor displacement relative to the ground           m         a_p T_p^2
floor_vel      floor velocity relative to the ground               m s-1     a_p T_p
slide_disp     block sliding displacement relative to the floor    m         a_p T_p^2
slide_vel      block sliding velocity relative to the floor        m s-1     a_p T_p
phase          0 stuck, +1 / -1 sliding in the +/- direction       1         --
============== =================================================== ========= ===========

The floor acceleration follows from the equations of motion of
:mod:`isoslide.engine.kernel` with the model that ran (``Solution.facets``): stuck,
``-(2 Pi4 w x' + w^2 x) / (1 + Pi8)``; sliding, ``-(2 Pi4 w x' + w^2 x) +
Pi8 s phi(|u'|)`` (``Pi8 = 0`` for ``one-way`` coupling); the ground's for a
fixed base, and for a rigid building on a sliding bearing that held throughout (the solver's
``bearing-stuck`` reduction, facet ``isolator == "fixed-base"``).

A general building (:mod:`isoslide.engine.building`) has its contents' floor (the slab,
or the superstructure's roof) in ``floor_*``, its floor acceleration from
:mod:`isoslide.engine.building_kernel`'s equations, and six more columns
(:data:`BUILDING_COLUMNS`): the slab's and the superstructure's motion, the
hysteretic isolator force and the isolator's phase (and a triple friction pendulum's regime,
:data:`STAGE_COLUMNS`).  A superstructure of ``N > 1``
storeys has one ``super_disp_k``, ``super_vel_k`` per floor ``k = 1 .. N`` (relative to
the slab).  Contents that can rock add the block's tilt and its rate last
(:data:`ROCKING_COLUMNS`), and the block's groups with its ``theta_max`` and ``overturned`` to the
attributes.

A scene that ran in the plane (``Solution.facets.contact == "plane"``) has every
motion column twice, ``<name>_x`` and ``<name>_y`` along the building's axes (a
floor's index before the axis: ``super_disp_2_x``), its floor acceleration from
:func:`isoslide.engine.planar.floor_motion`, and its phases ``0`` stuck (held, or
elastic) and ``1`` sliding (or yielding), the direction being in the velocities
(:func:`table_columns` lists the columns of each kind of history).
"""

from __future__ import annotations

import csv
import json
import math
from dataclasses import dataclass
from pathlib import Path

import h5py
import numpy as np

from ..engine import building
from ..engine import building_kernel as bk
from ..engine.planar import floor_motion
from .history import History
from ..model.friction import stribeck
from ..model.parts import building_of
from ..models import Facets
from ..scene import Scene

__all__ = ["AXES", "BUILDING_COLUMNS", "COLUMNS", "FORMATS", "HistoryTable", "history_format", "history_table",
           "read_history", "table_columns", "write_history"]

COLUMNS = (
    ("time", "time", "s", "T_p"),
    ("ground_accel", "ground acceleration", "m s-2", "a_p"),
    ("floor_accel", "absolute floor acceleration", "m s-2", "a_p"),
    ("floor_disp", "floor displacement relative to the ground", "m", "a_p T_p^2"),
    ("floor_vel", "floor velocity relative to the ground", "m s-1", "a_p T_p"),
    ("slide_disp", "block sliding displacement relative to the floor", "m", "a_p T_p^2"),
    ("slide_vel", "block sliding velocity relative to the floor", "m s-1", "a_p T_p"),
    ("phase", "stick/slip phase: 0 stuck, +1/-1 sliding in the +/- direction", "1", "1"),
)
"""``(name, long name, SI unit, dimensionless scale)`` of every column, in file order."""

BUILDING_COLUMNS = (
    ("slab_disp", "isolated slab displacement relative to the ground", "m", "a_p T_p^2"),
    ("slab_vel", "isolated slab velocity relative to the ground", "m s-1", "a_p T_p"),
    ("super_disp", "superstructure displacement relative to the slab", "m", "a_p T_p^2"),
    ("super_vel", "superstructure velocity relative to the slab", "m s-1", "a_p T_p"),
    ("isolator_force", "hysteretic isolator force (a stuck sliding bearing: the force holding it)", "N",
     "M_b a_p"),
    ("isolator_phase", "isolator phase: 0 stuck or elastic, +1/-1 sliding or yielding in the +/- direction",
     "1", "1"),
)
"""Columns added after :data:`COLUMNS` for a general building (not the paper's model)."""

STAGE_COLUMNS = (
    ("isolator_stage", "triple friction pendulum's regime: 0 held, 1..5 Fenz and Constantinou's I..V, -1 another "
                       "set of sliding surfaces", "1", "1"),
)
"""Column added after :data:`BUILDING_COLUMNS` for a triple friction pendulum."""

ROCKING_COLUMNS = (
    ("tilt", "rocking block's tilt, positive on its corner at +b", "rad", "1"),
    ("tilt_rate", "rocking block's angular velocity", "rad s-1", "1/T_p"),
)
"""Columns added last for contents that can rock (:attr:`isoslide.Scene.tips`); their ``phase`` adds 4
times the corner the block rocks on (+4 / -4 rocking, the others slide-rock)."""

FORMATS = {".csv": "csv", ".h5": "hdf5", ".hdf5": "hdf5"}
"""File extensions :func:`write_history` and :func:`read_history` understand."""

AXES = ("x", "y")
"""The building's horizontal axes, the suffixes of a planar history's columns."""

_PLANAR_PHASES = {"phase": "stick/slip phase: 0 stuck, 1 sliding (the direction: slide_vel_x, slide_vel_y)",
                  "isolator_phase": "isolator phase: 0 stuck or elastic, 1 sliding or yielding"}
_STOREY_COLUMNS = ("super_disp", "super_vel")


def table_columns(planar: bool = False, general: bool = False, storeys: int = 1, rocking: bool = False,
                  stage: bool = False) -> tuple:
    """``(name, long name, SI unit, dimensionless scale)`` of the columns of one kind of history, in file order.

    Parameters
    ----------
    planar : bool
        The contents slid in the plane: every motion column along each of :data:`AXES`.
    general : bool
        A general building: :data:`BUILDING_COLUMNS` follow :data:`COLUMNS`.
    storeys : int
        Floors of the superstructure (``>= 1``); above one, a ``super_*`` column per floor.
    rocking : bool
        Contents that can rock: :data:`ROCKING_COLUMNS` come last.
    stage : bool
        A triple friction pendulum: :data:`STAGE_COLUMNS` after the building's columns.
    """
    out = []
    for name, long_name, unit, scale in COLUMNS + (BUILDING_COLUMNS if general else ()):
        if name == "time":
            out.append((name, long_name, unit, scale))
            continue
        if name.endswith("phase"):
            out.append((name, _PLANAR_PHASES[name] if planar else long_name, unit, scale))
            continue
        floors = ([(name, long_name)] if storeys == 1 or name not in _STOREY_COLUMNS else
                  [(f"{name}_{k}", f"{long_name}, floor {k}") for k in range(1, storeys + 1)])
        for fname, flong in floors:
            if planar:
                out.extend((f"{fname}_{a}", f"{flong}, along the building's {a} axis", unit, scale) for a in AXES)
            else:
                out.append((fname, flong, unit, scale))
    return tuple(out) + (STAGE_COLUMNS if stage else ()) + (ROCKING_COLUMNS if rocking else ())


def _kind_of(names, ordered: bool = True):
    """``(planar, general, storeys, rocking, stage)`` of a history with the columns ``names`` (in that order when ``ordered``).

    None when no kind of :func:`table_columns` has them.
    """
    names = tuple(names)
    planar = "slide_disp_x" in names
    general = "isolator_phase" in names
    storeys = max(1, sum(1 for n in names if n.startswith("super_disp")) // (2 if planar else 1))
    kind = (planar, general, storeys, "tilt" in names, "isolator_stage" in names)
    expected = tuple(c[0] for c in table_columns(*kind))
    return kind if (names == expected if ordered else set(names) == set(expected)) else None


@dataclass(frozen=True)
class HistoryTable:
    """A history as named columns with their units.

    Attributes
    ----------
    columns : dict of str to ndarray
        One array per name of :data:`COLUMNS` (``phase`` as int8).
    units : dict of str to str
        Unit of each column: the SI unit, or ``"1"`` when dimensionless.
    attrs : dict
        Scene and result: ``physical`` (bool), ``pulse``, ``model``, the
        Pi-groups ``pi2`` ... ``pi8``, ``pi1``, ``pi1_residual``, and, for a
        physical scene, ``a_p`` (m s-2), ``T_p`` (s), ``M_b`` (kg), ``g`` (m s-2),
        ``u_max`` and ``u_residual`` (m).
    """

    columns: dict
    units: dict
    attrs: dict

    def __len__(self):
        return int(self.columns["time"].size)


def history_format(path) -> str:
    """``"csv"`` or ``"hdf5"`` from the extension of ``path``.

    Raises
    ------
    ValueError
        Any other extension (the message names the path and the allowed ones).
    """
    ext = Path(path).suffix.lower()
    if ext not in FORMATS:
        raise ValueError(f"path = {str(path)!r} has an unknown extension {ext!r}; "
                         f"allowed: {', '.join(FORMATS)}")
    return FORMATS[ext]


def _friction(v, scene: Scene, facets: Facets) -> np.ndarray:
    """Friction level phi(|v|), units of a_p, of the friction law that ran (:func:`isoslide.model.friction.stribeck`)."""
    if facets.friction == "static-kinetic":   # kinetic level at every sliding speed
        return stribeck(v, scene.pi2, scene.pi2, 0.0, scene.pi7)[0]
    return stribeck(v, scene.static_level, scene.pi2, scene.pi6, scene.pi7)[0]


def _floor_accel(h: History, scene: Scene, facets: Facets, ground: np.ndarray) -> np.ndarray:
    """Absolute floor acceleration, units of a_p (see the module docstring)."""
    if scene.fixed_base or facets.isolator == "fixed-base":      # Pi3 = 0, or a bearing that held throughout
        return ground.copy()
    w = 2.0 * math.pi / scene.pi3
    F = 2.0 * scene.pi4 * w * h.xd + w * w * h.x
    p8 = 0.0 if facets.coupling == "one-way" else scene.pi8
    s = h.phase.astype(float)
    return np.where(h.phase == 0, -F / (1.0 + p8), -F + p8 * s * _friction(h.ud, scene, facets))


def _building_floor(h: History, scene: Scene, facets: Facets, ground: np.ndarray) -> tuple:
    """Floor acceleration (units of a_p), displacement and velocity of a general building's contents."""
    P = building.parameters(scene, pi8=0.0 if facets.coupling == "one-way" else None,
                            coulomb=facets.friction == "coulomb")
    n = h.tau.size
    nfl = int(P[bk.P_N])
    y = np.zeros(bk.state_size(nfl))
    floors = np.empty(nfl)
    acc = np.empty(n)
    xs = np.zeros((n, nfl)) if h.xs is None else np.asarray(h.xs).reshape(n, -1)
    xsd = np.zeros((n, nfl)) if h.xsd is None else np.asarray(h.xsd).reshape(n, -1)
    fh = h.fh if h.fh is not None else np.zeros(n)
    iso = h.iso_phase if h.iso_phase is not None else np.zeros(n, dtype=np.int8)
    th = h.theta if h.theta is not None else np.zeros(n)
    thd = h.thetad if h.thetad is not None else np.zeros(n)
    for i in range(n):
        y[:] = (h.x[i], h.xd[i], *xs[i], *xsd[i], th[i], thd[i], h.u[i], h.ud[i], fh[i])
        acc[i] = bk._accels(float(h.phase[i]), float(iso[i]), ground[i], bk.normal(h.tau[i], P)[0], y, P,
                            floors)[1]
    k = building_of(scene).contents.floor
    if k == 0:
        return acc, h.x, h.xd
    return acc, h.x + xs[:, k - 1], h.xd + xsd[:, k - 1]


def history_table(solution, scene: Scene) -> HistoryTable:
    """Ground, floor and block motion of a solve with ``history=True``.

    Parameters
    ----------
    solution : isoslide.Solution
        Result of ``isoslide.solve(scene, history=True)``.
    scene : Scene
        The scene solved.

    Returns
    -------
    HistoryTable
        SI units if ``scene.scale`` is set, else dimensionless.
    """
    h = solution.history
    if h is None:
        raise ValueError("solution has no history; solve with isoslide.solve(scene, history=True)")
    if h.x.ndim == 2:
        return _planar_table(solution, scene)
    ground = np.asarray(scene.pulse.accel(h.tau), dtype=float)
    general = h.xs is not None or h.fh is not None or h.theta is not None
    if general:
        floor, fdisp, fvel = _building_floor(h, scene, solution.facets, ground)
    else:
        floor, fdisp, fvel = _floor_accel(h, scene, solution.facets, ground), h.x, h.xd
    sc = scene.scale
    T, A = (sc.T_p, sc.a_p) if sc is not None else (1.0, 1.0)
    L, V = A * T * T, A * T
    cols = {"time": h.tau * T, "ground_accel": ground * A, "floor_accel": floor * A,
            "floor_disp": fdisp * L, "floor_vel": fvel * V, "slide_disp": h.u * L, "slide_vel": h.ud * V,
            "phase": h.phase.astype(np.int8)}
    columns = COLUMNS
    if general:
        zeros = np.zeros_like(h.tau)
        F = sc.M_b * sc.a_p if sc is not None else 1.0
        cols.update({"slab_disp": h.x * L, "slab_vel": h.xd * V})
        cols.update(_storey_columns(h.xs, h.xsd, h.tau.size, L, V))
        cols.update({"isolator_force": (h.fh if h.fh is not None else zeros) * F,
                     "isolator_phase": (h.iso_phase if h.iso_phase is not None
                                        else zeros.astype(np.int8)).astype(np.int8)})
        columns = table_columns(False, True, _storeys(h), h.theta is not None, h.stage is not None)
        if h.stage is not None:
            cols["isolator_stage"] = h.stage.astype(np.int8)
        if h.theta is not None:
            cols.update({"tilt": h.theta.copy(), "tilt_rate": h.thetad / T})
    return _table(cols, columns, solution, scene)


def _storeys(h: History) -> int:
    """Floors of a history's superstructure (1 for a rigid one)."""
    return 1 if h.xs is None or np.ndim(h.xs) == 1 else h.xs.shape[-1]


def _storey_columns(xs, xsd, rows: int, L: float, V: float, axis: str = "") -> dict:
    """``super_disp``, ``super_vel`` (one per floor above one storey), scaled by ``L``, ``V``."""
    out = {}
    for name, v, scale in (("super_disp", xs, L), ("super_vel", xsd, V)):
        v = np.zeros((rows, 1)) if v is None else np.asarray(v).reshape(rows, -1)
        n = v.shape[1]
        for k in range(n):
            out[f"{name}_{k + 1}{axis}" if n > 1 else f"{name}{axis}"] = v[:, k] * scale
    return out


def _table(cols: dict, columns: tuple, solution, scene: Scene) -> HistoryTable:
    """The :class:`HistoryTable` of ``cols`` in the order of ``columns``, with the units and the attributes."""
    sc = scene.scale
    cols = {name: cols[name] for name, _, _, _ in columns}
    units = {name: (unit if sc is not None else "1") for name, _, unit, _ in columns}
    attrs = {"physical": sc is not None, "pulse": scene.pulse.name, "model": solution.model,
             **scene.pis(), "floor": scene.floor, "pi1": solution.pi1, "pi1_residual": solution.pi1_residual}
    if scene.rocks:
        attrs.update({"pi18": scene.pi18, "pi19": scene.pi19, "pi20": scene.restitution, "pi21": scene.pi21,
                      "theta_max": solution.theta_max, "overturned": solution.overturned})
    if scene.pulse_y is not None:
        attrs.update({"pulse_y": scene.pulse_y.name, "angle": scene.angle,
                      "peak_angle": solution.peak_angle})
    if sc is not None:
        attrs.update({"a_p": sc.a_p, "T_p": sc.T_p, "M_b": sc.M_b, "g": sc.g,
                      "u_max": solution.u_max, "u_residual": solution.u_residual})
    return HistoryTable(columns=cols, units=units, attrs=attrs)


def _planar_table(solution, scene: Scene) -> HistoryTable:
    """:func:`history_table` of a scene that ran in the plane (columns along each of :data:`AXES`)."""
    h = solution.history
    motion = floor_motion(scene, h)
    gx, gy = scene.ground(h.tau)
    sc = scene.scale
    T, A = (sc.T_p, sc.a_p) if sc is not None else (1.0, 1.0)
    L, V = A * T * T, A * T
    F = sc.M_b * sc.a_p if sc is not None else 1.0
    general = h.xs is not None or h.fh is not None or h.iso_phase is not None
    k = building_of(scene).contents.floor
    n = _storeys(h)
    cols = {"time": h.tau * T, "phase": (h.phase != 0).astype(np.int8)}
    for a, axis in enumerate(AXES):
        sfx = f"_{axis}"
        fdisp = h.x[:, a] + (h.xs[:, a, k - 1] if k > 0 and h.xs is not None else 0.0)
        cols.update({f"ground_accel{sfx}": (gx, gy)[a] * A, f"floor_accel{sfx}": motion[:, a] * A,
                     f"floor_disp{sfx}": fdisp * L, f"floor_vel{sfx}": motion[:, 2 + a] * V,
                     f"slide_disp{sfx}": h.u[:, a] * L, f"slide_vel{sfx}": h.ud[:, a] * V})
        if general:
            cols.update({f"slab_disp{sfx}": h.x[:, a] * L, f"slab_vel{sfx}": h.xd[:, a] * V,
                         f"isolator_force{sfx}": (h.fh[:, a] if h.fh is not None else np.zeros_like(h.tau)) * F})
            cols.update(_storey_columns(None if h.xs is None else h.xs[:, a, :],
                                        None if h.xsd is None else h.xsd[:, a, :], h.tau.size, L, V, sfx))
    if general:
        cols["isolator_phase"] = ((h.iso_phase != 0) if h.iso_phase is not None
                                  else np.zeros(h.tau.size, dtype=bool)).astype(np.int8)
    return _table(cols, table_columns(True, general, n), solution, scene)


def write_history(solution, scene: Scene, path) -> Path:
    """Write the history of a solve to ``path`` (format by extension).

    Parameters
    ----------
    solution, scene
        As for :func:`history_table`.
    path : str or Path
        ``.csv`` (comment lines ``# key: value`` with the scene, then a header
        ``name [unit]`` and one row per time) or ``.h5`` / ``.hdf5`` (one
        dataset per column with ``units`` and ``long_name`` attributes, the
        scene and result as root attributes).

    Returns
    -------
    Path
        ``path``.
    """
    fmt = history_format(path)
    path = Path(path)
    table = history_table(solution, scene)
    if fmt == "hdf5":
        with h5py.File(path, "w") as f:
            for name, long_name, _, scale in table_columns(*_kind_of(table.columns)):
                d = f.create_dataset(name, data=table.columns[name])
                d.attrs["units"] = table.units[name]
                d.attrs["long_name"] = long_name
                if not table.attrs["physical"]:
                    d.attrs["scale"] = scale
            for k, v in table.attrs.items():
                f.attrs[k] = v
        return path
    with open(path, "w", newline="") as fh:
        fh.write("# isoslide history (ground, floor and block motion)\n")
        for k, v in table.attrs.items():
            fh.write(f"# {k}: {json.dumps(v)}\n")
        w = csv.writer(fh)
        names = tuple(table.columns)
        w.writerow([f"{name} [{table.units[name]}]" for name in names])
        data = [table.columns[name] for name in names]
        for i in range(len(table)):
            w.writerow([int(c[i]) if name.endswith(("phase", "stage")) else repr(float(c[i]))
                        for name, c in zip(names, data, strict=True)])
    return path


def read_history(path) -> HistoryTable:
    """Read a history written by :func:`write_history`.

    Parameters
    ----------
    path : str or Path
        A ``.csv``, ``.h5`` or ``.hdf5`` file.

    Returns
    -------
    HistoryTable
    """
    fmt = history_format(path)
    path = Path(path)
    if fmt == "hdf5":
        with h5py.File(path, "r") as f:
            kind = _kind_of(list(f), ordered=False)
            if kind is None:
                raise ValueError(f"path = {str(path)!r} has datasets {sorted(f)}; expected the columns of "
                                 "isoslide.store.history_io.table_columns")
            names = [c[0] for c in table_columns(*kind)]
            cols = {name: f[name][()] for name in names}
            units = {name: str(f[name].attrs["units"]) for name in names}
            attrs = {k: _plain(v) for k, v in f.attrs.items()}
        return HistoryTable(columns=cols, units=units, attrs=attrs)
    attrs, header, rows = {}, None, []
    with open(path, newline="") as fh:
        for line in fh:
            if line.startswith("#"):
                key, sep, value = line[1:].partition(":")
                if sep and key.strip() and value.strip():
                    attrs[key.strip()] = json.loads(value)
                continue
            if header is None:
                header = next(csv.reader([line]))
                continue
            if line.strip():
                rows.append(line)
    base = [c[0] for c in COLUMNS]
    if header is None:
        raise ValueError(f"path = {str(path)!r} has no header row; expected: "
                         + ", ".join(f"{n} [unit]" for n in base))
    names = [h.split(" [")[0] for h in header]
    if _kind_of(names) is None:
        raise ValueError(f"path = {str(path)!r} has columns {names}; expected {base}, optionally followed by "
                         f"{[c[0] for c in BUILDING_COLUMNS]} (isoslide.store.history_io.table_columns: in the "
                         "plane each motion column along x and y, a super_* column per floor, then a triple "
                         "pendulum's isolator_stage and a rocking block's tilt and tilt_rate)")
    units = {n: h.split(" [", 1)[1].rstrip("]") for n, h in zip(names, header, strict=True)}
    data = np.array([[float(x) for x in r] for r in csv.reader(rows)], dtype=float).reshape(-1, len(names))
    cols = {n: data[:, i] for i, n in enumerate(names)}
    for n in names:
        if n.endswith(("phase", "stage")):
            cols[n] = cols[n].astype(np.int8)
    return HistoryTable(columns=cols, units=units, attrs=attrs)


def _plain(v):
    """An HDF5 attribute value as a plain Python value."""
    if isinstance(v, np.generic):
        return v.item()
    if isinstance(v, bytes):
        return v.decode()
    return v
