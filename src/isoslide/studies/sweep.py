"""Grids of scenes ("studies") and their solution, chunk by chunk.

A *study* is one figure panel of the paper: a rectangular grid in Pi-space
whose last dimension is always ``pi2`` (the abscissa of the master curves)
and whose other dimensions are the swept Pi-groups (``pi3``, ``pi5``, ...).
Every other group is held at a fixed value.

The grid is flattened in C order (``pi2`` varies fastest) and cut into
chunks of ``chunk_size`` scenes; chunk ``k`` holds the flat indices
``[k * chunk_size, (k + 1) * chunk_size)``.  Chunks are solved
independently (:func:`solve_chunk`) and merged back into the grid by
:func:`isoslide.datasets.merge_chunks`.

Study specification
-------------------
A study is given as a mapping (normally one entry of ``config.yaml``)::

    {"dims": {"pi3": [0.01, 0.5, 1]},      # swept groups, in dimension order
     "fixed": {"pi4": 0.1},                # held groups (others: ``defaults``)
     "pulse": "ricker",
     "floor": "base",                      # the contents' floor (base or roof)
     "pi2": {"start": 0.02, "stop": "auto", "num": 64}}

``beta`` (s/m) may be used in ``dims`` or ``fixed`` in place of ``pi6``; it is
turned into ``pi6 = beta * a_p_T_p`` with the reference ``a_p T_p`` (m/s) of
the configuration, and kept as an auxiliary coordinate.

``pi2.stop = "auto"`` places the end of the abscissa just past the last
non-zero response, which is known exactly: while the contents stick, the
floor moves as a linear oscillator of mass ``M_b (1 + Pi8)``, and sliding
starts only if its peak acceleration (units of ``a_p``) exceeds the static
level ``Pi2 / Pi5``.  So ``Pi1 = 0`` for every ``Pi2 >= Pi5 * A_stick``
(:func:`peak_floor_accel`), and ``stop`` is the first multiple of
``pi2.step_round`` at or above ``pi2.margin * max(Pi5 * A_stick)``.
"""

from __future__ import annotations

import functools
import logging
import itertools
import json
import math
import time
from dataclasses import dataclass, field

import numpy as np

import xarray as xr

from .. import solver
from ..budget import compile_and_solve, phase
from ..config import ConfigError
from ..datasets import chunk_dataset, merge_chunks, open_dataset
from ..groups import BUILDING_NAMES, INPUT_NAMES, group
from ..store.progress import Progress
from ..pulses import get_pulse
from ..scene import FLOORS, Scene
from ..model.validation import check_range

log = logging.getLogger(__name__)

PI_NAMES = INPUT_NAMES
"""Input groups of a scene, in order (the registry's :data:`isoslide.groups.INPUT_NAMES`)."""

HELD = INPUT_NAMES[1:]
"""Groups a study holds or sweeps; ``pi2`` is always the abscissa."""

SWEEPABLE = HELD + ("beta",)
"""Names allowed as study dimensions or fixed values (``beta`` is an alias of ``pi6``)."""


@dataclass(frozen=True)
class Grid:
    """A study grid: ordered dimensions (``pi2`` last) and fixed groups.

    Attributes
    ----------
    name : str
        Study name (also the dataset file name).
    dims : dict of str -> numpy.ndarray
        Swept groups in dimension order, ``pi2`` last; values in Pi units.
    fixed : dict of str -> float
        Every input group that is not a dimension.
    pulse : str
        Pulse name.
    beta : numpy.ndarray or float or None
        Stribeck constant in s/m when the study gave ``beta`` (array if swept).
    a_p_T_p : float
        Reference ``a_p T_p`` (m/s) used to turn ``beta`` into ``pi6``.
    spec : dict
        The normalised specification (JSON-serialisable) the grid was built from.
    """

    name: str
    dims: dict
    fixed: dict
    pulse: str
    beta: object = None
    a_p_T_p: float = 1.0
    spec: dict = field(default_factory=dict, compare=False)
    floor: str = FLOORS[0]

    @property
    def shape(self) -> tuple:
        """Number of values along each dimension."""
        return tuple(len(v) for v in self.dims.values())

    @property
    def size(self) -> int:
        """Number of scenes."""
        return int(np.prod(self.shape))

    @property
    def dim_names(self) -> tuple:
        """Dimension names, ``pi2`` last."""
        return tuple(self.dims)

    def n_chunks(self, chunk_size: int) -> int:
        """Number of chunks of at most ``chunk_size`` scenes."""
        return n_chunks(self.size, chunk_size)

    def chunk_indices(self, chunk: int, chunk_size: int) -> np.ndarray:
        """Flat (C-order) indices of the scenes of chunk ``chunk``."""
        n = self.n_chunks(chunk_size)
        if not 0 <= int(chunk) < n:
            raise ValueError(f"chunk = {chunk!r} is out of range; study {self.name!r} has "
                             f"chunks 0..{n - 1} at chunk_size = {chunk_size}")
        lo = int(chunk) * chunk_size
        return np.arange(lo, min(lo + chunk_size, self.size))

    def points(self, indices=None) -> dict:
        """Pi values of the scenes at flat ``indices`` (all by default).

        Returns
        -------
        dict of str -> numpy.ndarray
            One array per input group ``pi2 .. pi8``.
        """
        idx = np.arange(self.size) if indices is None else np.asarray(indices, dtype=int)
        sub = np.unravel_index(idx, self.shape)
        out = {}
        for name in PI_NAMES:
            if name in self.dims:
                out[name] = np.asarray(self.dims[name], dtype=float)[sub[self.dim_names.index(name)]]
            else:
                out[name] = np.full(idx.shape, float(self.fixed[name]))
        return out

    def scenes(self, indices=None) -> list:
        """:class:`~isoslide.Scene` objects at flat ``indices`` (all by default)."""
        pts = self.points(indices)
        n = len(pts["pi2"])
        return [Scene(**{k: float(pts[k][i]) for k in PI_NAMES}, pulse=self.pulse, floor=self.floor)
                for i in range(n)]


def n_chunks(size: int, chunk_size: int) -> int:
    """Number of chunks of at most ``chunk_size`` items covering ``size`` items."""
    if chunk_size < 1:
        raise ValueError(f"chunk_size = {chunk_size!r} is invalid; allowed range: chunk_size >= 1")
    return max(1, math.ceil(size / chunk_size))


# ----------------------------------------------------------------------------------------------
# configuration -> grids
# ----------------------------------------------------------------------------------------------

def _num(key: str, value, lo=-math.inf, hi=math.inf, lo_in=True, hi_in=True) -> float:
    try:
        return check_range(key, value, lo, hi, lo_in, hi_in)
    except ValueError as err:
        raise ConfigError(str(err)) from None


def _pi_value(key: str, name: str, value) -> float:
    """Validate one Pi value against the Scene's allowed range, naming the config key."""
    g = group(name)
    return _num(key, value, g.lo, g.hi, g.lo_in, g.hi_in)


def normalise_study(name: str, study: dict, config: dict) -> dict:
    """Return the full, JSON-serialisable specification of one study.

    Groups neither swept nor fixed take ``config["defaults"]`` (so do the pulse and the contents'
    ``floor``), the Pi2 axis
    completes the study's ``pi2`` with ``config["pi2"]`` (the configuration
    schema fills both, see :func:`isoslide.config.load`), ``beta`` becomes
    ``pi6`` and every value is checked,
    raising :class:`ConfigError` with the key path (``studies.<name>.<key>``)
    on the first invalid one.

    Parameters
    ----------
    name : str
        Study name.
    study : dict
        The study's entry of the configuration.
    config : dict
        The whole configuration (for ``defaults``, ``pi2``, ``reference``, ``chunk_size``,
        ``solver``).
    """
    where = f"studies.{name}"
    defaults = {}
    for k, v in config["defaults"].items():
        if k in ("pulse", "floor"):
            continue
        if k not in HELD:
            raise ConfigError(f"defaults.{k}: unknown group; allowed: {list(HELD)}")
        defaults[k] = _pi_value(f"defaults.{k}", k, v)
    missing = [k for k in HELD if k not in defaults]
    if missing:
        raise ConfigError(f"defaults: no value for {missing}; load the configuration with "
                          f"isoslide.config.load, which fills the schema defaults")
    pulse = study.get("pulse", config["defaults"]["pulse"])
    try:
        get_pulse(pulse)
    except ValueError as err:
        raise ConfigError(f"{where}.pulse: {err}") from None
    floor = study.get("floor", config["defaults"]["floor"])
    if floor not in FLOORS:
        raise ConfigError(f"{where}.floor = {floor!r} is invalid; allowed: {', '.join(map(repr, FLOORS))}")
    a_p_T_p = _num("reference.a_p_T_p", config["reference"]["a_p_T_p"], 0.0, math.inf, False, False)

    dims_in = study.get("dims") or {}
    fixed_in = study.get("fixed") or {}
    for k in list(dims_in) + list(fixed_in):
        if k not in SWEEPABLE:
            raise ConfigError(f"{where}: unknown group {k!r}; allowed: {list(SWEEPABLE)} "
                              f"(pi2 is always the abscissa, set it under pi2:)")
    both = set(dims_in) & set(fixed_in)
    if both:
        raise ConfigError(f"{where}: {sorted(both)} both swept (dims) and fixed")
    for a, b in (("beta", "pi6"),):
        if (a in dims_in or a in fixed_in) and (b in dims_in or b in fixed_in):
            raise ConfigError(f"{where}: give either {a} or {b}, not both")

    dims, beta = {}, None
    for k, values in dims_in.items():
        if not isinstance(values, (list, tuple)) or len(values) < 1:
            raise ConfigError(f"{where}.dims.{k}: must be a non-empty list of numbers")
        if k == "beta":
            vals = [_num(f"{where}.dims.beta[{i}]", v, 0.0) for i, v in enumerate(values)]
            beta = vals
            dims["pi6"] = [b * a_p_T_p for b in vals]
        else:
            dims[k] = [_pi_value(f"{where}.dims.{k}[{i}]", k, v) for i, v in enumerate(values)]
        key = "pi6" if k == "beta" else k
        if len(set(dims[key])) != len(dims[key]):
            raise ConfigError(f"{where}.dims.{k}: values must be distinct")
    fixed = {}
    for k, v in fixed_in.items():
        if k == "beta":
            beta = _num(f"{where}.fixed.beta", v, 0.0)
            fixed["pi6"] = beta * a_p_T_p
        else:
            fixed[k] = _pi_value(f"{where}.fixed.{k}", k, v)
    for k, v in defaults.items():
        if k not in dims and k not in fixed:
            fixed[k] = v
    for k in ("pi6",):
        if k in fixed:
            _pi_value(f"{where}.fixed.{k}", k, fixed[k])
    for i, v in enumerate(dims.get("pi6", [])):
        _pi_value(f"{where}.dims.pi6[{i}]", "pi6", v)

    values = {k: list(dims[k]) if k in dims else [fixed[k]] for k in BUILDING_NAMES if k in dims or k in fixed}
    if any(v > 0.0 for v in values.get("pi12", [])):
        bad = [v for v in values.get("pi11", [0.0]) if not 0.0 < v < 1.0]
        if bad:
            key = f"{where}.dims.pi11" if "pi11" in dims else f"{where}.fixed.pi11"
            raise ConfigError(f"{key} = {bad[0]!r} is out of range with a flexible superstructure (pi12 > 0); "
                              f"allowed range: 0 < value < 1")
    building = any(v != 0.0 for vs in values.values() for v in vs)
    pi2 = dict(config["pi2"])
    pi2.update(study.get("pi2") or {})
    if building and pi2["stop"] == "auto":
        raise ConfigError(f"{where}.pi2.stop = 'auto' needs the paper's model (pi9 .. pi13 = 0); "
                          f"give a number for a general building")
    pi2["start"] = _pi_value(f"{where}.pi2.start", "pi2", pi2["start"])
    pi2["num"] = int(_num(f"{where}.pi2.num", pi2["num"], 2))
    pi2["margin"] = _num(f"{where}.pi2.margin", pi2["margin"], 1.0)
    pi2["step_round"] = _num(f"{where}.pi2.step_round", pi2["step_round"], 0.0, math.inf, False)
    if pi2["stop"] != "auto":
        pi2["stop"] = _pi_value(f"{where}.pi2.stop", "pi2", pi2["stop"])
        if pi2["stop"] <= pi2["start"]:
            raise ConfigError(f"{where}.pi2.stop = {pi2['stop']!r} must be > start = {pi2['start']!r}")

    return {
        "study": name,
        "title": study.get("title", name),
        "figure": study.get("figure"),
        "panel": study.get("panel"),
        "pulse": pulse,
        "floor": floor,
        "dims": dims,
        "fixed": fixed,
        "beta": beta,
        "a_p_T_p": a_p_T_p,
        "pi2": pi2,
        "chunk_size": int(_num("chunk_size", config["chunk_size"], 1)),
        "solver": {"rtol": config["solver"]["rtol"], "method": config["solver"]["method"]},
    }


def spec_size(spec: dict) -> int:
    """Number of scenes of a normalised study specification (no solver needed)."""
    return int(np.prod([len(v) for v in spec["dims"].values()] + [spec["pi2"]["num"]]))


def spec_chunks(spec: dict) -> list:
    """Chunk numbers ``0 .. n-1`` of a normalised study specification."""
    return list(range(n_chunks(spec_size(spec), spec["chunk_size"])))


@functools.lru_cache(maxsize=64)
def _grid_cached(text: str) -> "Grid":
    return _build_grid(json.loads(text))


def build_grid(spec: dict) -> Grid:
    """Build the :class:`Grid` of a normalised study specification (see :func:`normalise_study`).

    Cached on the specification's JSON text (``pi2.stop = "auto"`` runs the solver).
    """
    return _grid_cached(spec_json(spec))


def _build_grid(spec: dict) -> Grid:
    """Build the :class:`Grid` of a normalised study specification (see :func:`normalise_study`)."""
    dims = {k: np.asarray(v, dtype=float) for k, v in spec["dims"].items()}
    pi2 = spec["pi2"]
    stop = pi2["stop"]
    if stop == "auto":
        stop = auto_pi2_stop(dims, spec["fixed"], spec["pulse"], pi2["margin"], pi2["step_round"])
        stop = max(stop, pi2["start"] + pi2["step_round"])
    dims["pi2"] = np.linspace(pi2["start"], stop, pi2["num"])
    beta = spec.get("beta")
    if isinstance(beta, list):
        beta = np.asarray(beta, dtype=float)
    return Grid(name=spec["study"], dims=dims, fixed=dict(spec["fixed"]), pulse=spec["pulse"],
                beta=beta, a_p_T_p=spec["a_p_T_p"], spec=spec, floor=spec["floor"])


def study_grid(name: str, config: dict) -> Grid:
    """The grid of study ``name`` of ``config``."""
    try:
        study = config["studies"][name]
    except KeyError:
        raise ConfigError(f"studies.{name}: no such study; known: {sorted(config['studies'])}") from None
    return build_grid(normalise_study(name, study, config))


def check_config(config: dict) -> dict:
    """Check every study of ``config`` beyond the JSON schema; return ``{name: spec}``.

    Raises
    ------
    ConfigError
        Naming the key path of the first invalid value.
    """
    studies = config.get("studies") or {}
    if not studies:
        raise ConfigError("studies: at least one study is required")
    return {name: normalise_study(name, s, config) for name, s in studies.items()}


def jsonable(obj):
    """A plain-JSON copy of a configuration fragment (dicts, lists, str, float, int, bool, None)."""
    return json.loads(json.dumps(obj, default=float))


def spec_json(spec: dict) -> str:
    """Canonical JSON text of a specification (sorted keys): the study's rerun trigger."""
    return json.dumps(spec, sort_keys=True, separators=(",", ":"))


# ----------------------------------------------------------------------------------------------
# the exact no-slide boundary
# ----------------------------------------------------------------------------------------------

def peak_floor_accel(pi3: float, pi4: float, pi8: float = 0.0, pulse="ricker") -> float:
    """Peak floor acceleration demand (units of a_p) while the contents stick.

    The floor and the stuck contents form a linear oscillator of mass
    ``M_b (1 + Pi8)`` on the isolators; sliding can start only where the
    floor acceleration exceeds the static level ``Pi2 / Pi5``.  This is the
    solver's rigorous upper bound :func:`isoslide.solver.peak_stuck_demand`.

    Parameters
    ----------
    pi3, pi4, pi8 : float
        ``T_b/T_p``, ``xi_b`` and ``m_EC/M_b``.  ``pi3 = 0`` is a fixed base.
    pulse : str or Pulse
        Ground-acceleration pulse.
    """
    return solver.peak_stuck_demand(Scene(pi2=1.0, pi3=pi3, pi4=pi4, pi8=pi8, pulse=pulse))


def auto_pi2_stop(dims: dict, fixed: dict, pulse, margin: float = 1.05, step_round: float = 0.05) -> float:
    """End of the Pi2 axis just past the last non-zero response of every curve of a study.

    ``stop = ceil(margin * max(Pi5 * A_stick) / step_round) * step_round`` over all
    combinations of the swept groups, with ``A_stick`` from :func:`peak_floor_accel`.
    """
    names = [k for k in dims if k != "pi2"]
    worst = 0.0
    cache = {}
    for combo in itertools.product(*(dims[k] for k in names)):
        v = dict(fixed)
        v.update(zip(names, combo, strict=True))
        key = (v["pi3"], v["pi4"], v["pi8"])
        if key not in cache:
            cache[key] = peak_floor_accel(*key, pulse=pulse)
        worst = max(worst, v["pi5"] * cache[key])
    return math.ceil(round(margin * worst / step_round, 9)) * step_round


# ----------------------------------------------------------------------------------------------
# solving
# ----------------------------------------------------------------------------------------------

def solve_points(grid: Grid, indices, rtol=None, method="exact"):
    """Solve the scenes of ``grid`` at flat ``indices``; return the solver's Batch.

    Uses :func:`isoslide.solve_many` for the exact method and one
    :func:`isoslide.solve` per scene otherwise.
    """
    scenes = grid.scenes(indices)
    if method == "exact":
        return solver.solve_many(scenes, rtol=rtol)
    progress = Progress(log, f"study {grid.name} ({method})", len(scenes))
    sols = []
    for i, s in enumerate(scenes):
        progress.update(i)
        sols.append(solver.solve(s, rtol=rtol, method=method))
    progress.finish()
    fields = ("pi1", "pi1_residual", "tau_peak", "settled", "model", "tau_end", "n_steps", "n_events")
    facets = np.empty(len(sols), dtype=object)
    facets[:] = [s.facets for s in sols]
    return solver.Batch(**{f: np.array([getattr(s, f) for s in sols]) for f in fields}, facets=facets)


def solve_chunk(spec: dict, chunk: int):
    """Solve chunk ``chunk`` of the study ``spec``; return its dataset (dimension ``scene``).

    Parameters
    ----------
    spec : dict
        Normalised study specification (:func:`normalise_study`).
    chunk : int
        Chunk number, ``0 <= chunk < grid.n_chunks(spec["chunk_size"])``.

    Returns
    -------
    xarray.Dataset
        See :func:`isoslide.datasets.chunk_dataset`.
    """
    grid = build_grid(spec)
    idx = grid.chunk_indices(int(chunk), spec["chunk_size"])
    log.info("study %s, chunk %d: %d scenes", grid.name, int(chunk), idx.size)
    start = time.monotonic()
    batch = solve_points(grid, idx, rtol=spec["solver"]["rtol"], method=spec["solver"]["method"])
    took = time.monotonic() - start
    log.info("study %s, chunk %d: %d scenes solved in %.3g s (%.4g scenes/s)", grid.name, int(chunk),
             idx.size, took, idx.size / max(took, 1e-12))
    return chunk_dataset(grid, idx, batch)


def solve_study(spec: dict) -> xr.Dataset:
    """Solve a study that fits one chunk in this process: the dataset of ``spec``.

    The same dataset (byte for byte once written) as solving its one chunk with
    :func:`solve_chunk`, writing it and merging the file with :func:`merge_chunk_files`; the
    pipeline does this where a study has a single chunk, saving a job and a file.
    """
    grid = build_grid(spec)
    n = grid.n_chunks(spec["chunk_size"])
    if n != 1:
        raise ValueError(f"study {grid.name!r} has {n} chunks at chunk_size = {spec['chunk_size']}; "
                         "solve_study takes a study of one chunk (solve_chunk and merge_chunk_files "
                         "the others)")
    return merge_chunks([solve_chunk(spec, 0)], grid)


def merge_chunk_files(paths, spec: dict) -> xr.Dataset:
    """Open chunk files and :func:`isoslide.datasets.merge_chunks` them into the dataset of ``spec``."""
    grid = build_grid(spec)
    chunks = [open_dataset(p) for p in paths]
    log.info("merging %d chunk file(s) of study %s into grid %s", len(chunks), grid.name, grid.shape)
    return merge_chunks(chunks, grid)


def study_dataset(paths, spec: dict, job_log: logging.Logger | None = None) -> xr.Dataset:
    """The dataset of ``spec``: its chunk files merged, or, given none, the study solved here.

    The pipeline's study job: :func:`merge_chunk_files` when the study was cut into chunk
    jobs, :func:`solve_study` when it fits one chunk. ``job_log`` receives the time of each
    phase (:func:`isoslide.budget.phase`).
    """
    paths = list(paths)
    if paths:
        with phase("writing", job_log):
            return merge_chunk_files(paths, spec)
    log.info("study %s is one chunk: solved in this job", spec["study"])
    return compile_and_solve(job_log, solver.warm_up, lambda: solve_study(spec))
