"""The fragility study: how likely is it that contents slide farther than a limit at an intensity.

Multiple-stripe analysis (Baker 2015): every record ``r`` is scaled, as recorded, so that its
PGA (or PGV) equals each stripe level ``x_j``; for each record and stripe ``friction_samples``
kinetic friction coefficients are drawn from a lognormal; every analysis ``(r, j, s)`` is solved
exactly (:func:`isoslide.solve`; Coulomb contents on a linear isolator or a fixed base take the
exact piecewise path, model ``...+piecewise``) and gives the peak sliding ``u_max`` [m] and the
intensity measures of that analysis (:mod:`isoslide.studies.intensity`): ``pga``, ``pgv`` of the scaled
ground motion and ``pfa``, ``pfv`` of the floor the contents stand on.

Fragility curves ``P(u_max > limit | IM) = Phi(ln(IM / theta) / beta)`` are fitted by maximum
likelihood (:func:`isoslide.studies.fragility.fit_lognormal`) for each limit state and IM: the scaling
IM by its stripes (``z_j`` exceedances of ``n_j`` at ``x_j``), the three others per analysis
(each analysis has its own value); confidence bounds by resampling the records
(:func:`isoslide.studies.fragility.bootstrap`).  A curve the data cannot identify (no or every analysis
exceeding, perfect separation) is stored as NaN with its reason in ``fit_status``.

Scatter contributions, per stripe: the law of total variance splits the variance of an outcome
over the analyses of a stripe into the variance of the per-record means (record to record) and
the mean of the per-record variances (friction, the records fixed): for the exceedance indicator
of each limit state (``record_share_exceed``) and for ``ln u_max`` where every analysis of the
stripe slides (``record_share_ln_u``).  With ``n_s`` friction samples per record the record term
also holds ``1/n_s`` of the friction term (sampling noise of the record means).

Reproducibility: every friction coefficient is drawn up front, in the fixed order record, stripe,
sample, from ``numpy.random.default_rng(seed)``; a chunk takes its slice of that table, so a chunk
alone reproduces its analyses and the merged dataset does not depend on the chunking.

Pipeline functions: :func:`fragility_settings`, :func:`check_settings`, :func:`n_chunks`,
:func:`solve_chunk`, :func:`solve_all`, :func:`fragility_dataset`.
"""

from __future__ import annotations

import copy
import functools
import math
from dataclasses import dataclass

import numpy as np
import xarray as xr

from . import fragility as _fit
from ..budget import compile_and_solve, phase
from ..datasets import encode_facets, global_attrs, open_dataset
from .intensity import IM_NAMES, IM_UNITS, floor_peaks, ground_peaks
from ..pulses import sampled
from .record_study import resolve_record
from ..records import G
from ..scene import FLOORS, MAX_STOREYS, Scene, triple_friction_pendulum
from .. import solver

__all__ = ["BASES", "FIT_STATUS", "Study", "add_table_columns", "analysis_frame", "analysis_table", "base_of",
           "check_building", "check_floor", "check_settings", "check_storeys", "chunk_indices", "chunk_job", "dataset_job",
           "dataset_name", "dataset_names", "fit_curves", "fragility_dataset", "fragility_settings", "merge_chunks",
           "n_chunks", "scatter_contributions", "solve_all", "solve_analyses", "solve_chunk", "scaled_pulse"]

BASES = ("isolated", "fixed_base")
"""The two buildings of the study: the isolated slab, and the same contents on a fixed base."""

T_SCALE = 1.0
"""Time scale ``T_p`` [s] of the scenes: a record runs as recorded, so ``tau = t / 1 s``."""

FIT_STATUS = ("ok", "none_exceeded", "all_exceeded", "not_identifiable")
"""Meanings of the ``fit_status`` flag (0 ... 3)."""

REFERENCE_FRAGILITY = ("Baker, J. W. (2015): Efficient analytical fragility function fitting using dynamic "
                       "structural analysis, Earthquake Spectra 31(1), 579-599")
"""The ``references_fragility`` attribute of the datasets: the fitting method."""


def dataset_name(base: str) -> str:
    """``fragility`` (isolated) or ``fragility_fixed_base``: the file stem of a base's dataset."""
    return base_stem("fragility", base)


def base_stem(prefix: str, base: str) -> str:
    """The file stem of a base's dataset: ``prefix`` (isolated) or ``prefix_fixed_base``.

    Raises
    ------
    ValueError
        Unless ``base`` is one of ``BASES``.
    """
    if base not in BASES:
        raise ValueError(f"base = {base!r} is invalid; allowed: {BASES}")
    return prefix if base == "isolated" else f"{prefix}_fixed_base"


def base_of(name: str) -> str:
    """The base of a dataset stem: ``fragility`` -> ``isolated``, ``fragility_fixed_base`` -> ``fixed_base``."""
    return stem_base(name, dataset_name)


def stem_base(name: str, stem) -> str:
    """The base whose dataset stem ``stem(base)`` is ``name``.

    Parameters
    ----------
    name : str
        A dataset stem.
    stem : callable
        Maps a base (one of ``BASES``) to its dataset stem.

    Returns
    -------
    str
        The base, one of ``BASES``.
    """
    for base in BASES:
        if stem(base) == name:
            return base
    raise ValueError(f"name = {name!r} is invalid; allowed: {[stem(b) for b in BASES]}")


def dataset_names(settings: dict) -> list:
    """Dataset stems of a study: ``fragility``, and ``fragility_fixed_base`` with ``building.fixed_base``."""
    fixed = settings["fragility"]["building"]["fixed_base"]
    return [dataset_name(b) for b in BASES if b == "isolated" or fixed]


def fragility_settings(config: dict) -> dict:
    """The sections of a complete configuration the study reads: ``fragility`` and ``solver`` (copies).

    ``fragility.planar`` is left out: the planar analyses
    (:mod:`isoslide.studies.fragility_planar`) read it, and changing it changes nothing here.
    """
    f = {k: copy.deepcopy(v) for k, v in config["fragility"].items() if k != "planar"}
    return {"fragility": f, "solver": copy.deepcopy(config["solver"])}


@dataclass(frozen=True)
class Study:
    """Checked settings of a fragility study (SI units).

    Attributes
    ----------
    records : tuple of Record
        The records, as recorded.
    im : str
        Scaling IM, ``"pga"`` or ``"pgv"``.
    levels : ndarray
        Stripe levels, m/s^2 or m/s, increasing.
    n_samples : int
        Friction draws per record and stripe.
    limit_states : ndarray
        Sliding limits, m, increasing.
    mu_k : ndarray, shape (records, stripes, samples)
        Every kinetic friction coefficient, drawn up front.
    building, contents : dict
        The configuration sections (T_b [s], xi_b, M_b [kg]; mass [kg], mu_s_over_mu_k,
        beta [s/m], gamma [s/m]), the building's floor named by :func:`check_building`.
    seed, n_boot, level, chunk_size : int, int, float, int
    rtol : float or None
    """

    records: tuple
    im: str
    levels: np.ndarray
    n_samples: int
    limit_states: np.ndarray
    mu_k: np.ndarray
    building: dict
    contents: dict
    seed: int
    n_boot: int
    level: float
    chunk_size: int
    rtol: float | None

    @property
    def size(self) -> int:
        """Number of analyses (records x stripes x samples)."""
        return int(self.mu_k.size)


def _increasing(key: str, values) -> np.ndarray:
    arr = np.asarray(values, dtype=float)
    if arr.ndim != 1 or arr.size == 0 or not np.all(np.isfinite(arr)) or np.any(arr <= 0):
        raise ValueError(f"fragility.{key} = {list(values)!r} is invalid; allowed: finite values > 0")
    if np.any(np.diff(arr) <= 0):
        raise ValueError(f"fragility.{key} = {list(values)!r} is invalid; allowed: strictly increasing values")
    return arr

def check_level(f: dict) -> float:
    """The confidence level ``fragility.bootstrap.level`` of the bootstrap intervals, checked.

    Raises
    ------
    ValueError
        Unless 0 < level < 1.
    """
    level = float(f["bootstrap"]["level"])
    if not 0.0 < level < 1.0:
        raise ValueError(f"fragility.bootstrap.level = {level!r} is out of range; allowed range: 0 < level < 1")
    return level


def check_chunk_size(key: str, value) -> int:
    """A chunk size ``value`` (the setting ``key``), checked.

    Raises
    ------
    ValueError
        Unless it is 1 or more.
    """
    chunk_size = int(value)
    if chunk_size < 1:
        raise ValueError(f"{key} = {chunk_size!r} is out of range; allowed range: >= 1")
    return chunk_size



def check_stripes(f: dict, section: dict, key: str, allowed: str) -> tuple:
    """The scaling IM, the stripes, the limit states and the friction draws of a study, checked in that order.

    Parameters
    ----------
    f : dict
        The ``fragility`` section (its ``limit_states``).
    section : dict
        The section with ``stripes`` and ``friction_samples``: ``f`` or ``f["planar"]``.
    key : str
        The path of ``section`` below ``fragility``, as the errors name it: ``""`` or ``"planar."``.
    allowed : str
        The allowed scaling IMs, as the error names them.

    Returns
    -------
    im : {"pga", "pgv"}
        The scaling IM.
    levels : ndarray
        Stripe levels, m/s^2 (pga) or m/s (pgv), increasing.
    limits : ndarray
        Sliding limits, m, increasing.
    n_samples : int
        Friction draws per ground motion and stripe.

    Raises
    ------
    ValueError
        Naming the key, its value and what is allowed.
    """
    im = section["stripes"]["im"]
    if im not in ("pga", "pgv"):
        raise ValueError(f"fragility.{key}stripes.im = {im!r} is invalid; allowed: {allowed}")
    levels = _increasing(f"{key}stripes.levels", section["stripes"]["levels"])
    limits = _increasing("limit_states", f["limit_states"])
    n_s = int(section["friction_samples"])
    if n_s < 1:
        raise ValueError(f"fragility.{key}friction_samples = {n_s!r} is out of range; allowed range: >= 1")
    return im, levels, limits, n_s


def check_building(f: dict) -> dict:
    """Check ``fragility.building`` and ``fragility.contents`` (schema-completed).

    Parameters
    ----------
    f : dict
        The ``fragility`` section.

    Returns
    -------
    dict
        A copy of ``fragility.building`` whose ``floor`` is named as :func:`check_floor` names it
        (``"base"``, ``"roof"`` or the number of a floor between).

    Raises
    ------
    ValueError
        Naming the key, its value and the allowed range.
    """
    b, c = f["building"], f["contents"]
    for key, value, lo, hi in (("building.T_b", b["T_b"], 0.0, 100.0), ("building.xi_b", b["xi_b"], 0.0, 1000.0),
                               ("building.M_b", b["M_b"], 0.0, math.inf), ("contents.mass", c["mass"], 0.0, math.inf),
                               ("contents.mu_k.median", c["mu_k"]["median"], 0.0, 10.0),
                               ("contents.mu_k.log_std", c["mu_k"]["log_std"], 0.0, 5.0),
                               ("contents.mu_s_over_mu_k", c["mu_s_over_mu_k"], 1.0, 100.0),
                               ("contents.beta", c["beta"], 0.0, math.inf), ("contents.gamma", c["gamma"], 0.0, math.inf)):
        v = float(value)
        strict_lo = key in ("building.T_b", "building.M_b", "contents.mu_k.median")
        if not math.isfinite(v) or v > hi or v < lo or (strict_lo and v == lo):
            op = "<" if strict_lo else "<="
            raise ValueError(f"fragility.{key} = {value!r} is out of range; allowed range: {lo:g} {op} {key.split('.')[-1]} <= {hi:g}")
    for key in ("Q_d", "D_y", "m_st", "T_s", "xi_s"):
        v = float(b[key])
        if not (math.isfinite(v) and v >= 0.0):
            raise ValueError(f"fragility.building.{key} = {b[key]!r} is out of range; allowed range: 0 <= {key} < inf")
    if float(b["T_s"]) > 0.0 and not 0.0 < float(b["m_st"]) < float(b["M_b"]):
        raise ValueError(f"fragility.building.m_st = {b['m_st']!r} is out of range with a flexible superstructure "
                         f"(T_s > 0); allowed range: 0 < m_st < M_b = {b['M_b']!r}")
    storeys = check_storeys(b)
    floor = check_floor("fragility.building.floor", b["floor"], storeys)
    check_tfp(b)
    if c["mass"] / b["M_b"] > 1000.0:
        raise ValueError(f"fragility.contents.mass = {c['mass']!r} is out of range; allowed range: "
                         f"mass / building.M_b <= 1000 (Pi8)")
    return dict(b, floor=floor)


def check_storeys(b: dict) -> int:
    """The number of storeys ``building.storeys`` of a fragility study's building, checked.

    Parameters
    ----------
    b : dict
        The ``fragility.building`` section (schema-completed).

    Returns
    -------
    int
        Floors of the superstructure above the isolated slab (1 ... ``MAX_STOREYS``).

    Raises
    ------
    ValueError
        Unless it is an integer in range, or if it is above 1 with a rigid superstructure
        (``building.T_s = 0``, where every floor moves with the slab).
    """
    storeys = b["storeys"]
    if isinstance(storeys, bool) or not isinstance(storeys, int) or not 1 <= storeys <= MAX_STOREYS:
        raise ValueError(f"fragility.building.storeys = {storeys!r} is out of range; allowed range: an integer, "
                         f"1 <= storeys <= {MAX_STOREYS}")
    if storeys > 1 and float(b["T_s"]) == 0.0:
        raise ValueError(f"fragility.building.storeys = {storeys!r} with a rigid superstructure (building.T_s = 0), "
                         "where every floor moves with the slab; allowed: storeys = 1, or building.T_s > 0")
    return storeys


def check_floor(key: str, floor, storeys: int):
    """A floor carrying the contents, checked and named as :class:`isoslide.Scene` names it.

    Parameters
    ----------
    key : str
        The setting, as the error names it (``fragility.building.floor``, ``fragility.planar.floors[1]``).
    floor : str or int
        ``"base"``, ``"roof"`` or a floor number ``0 .. storeys`` (0 the isolated slab, ``storeys``
        the roof).
    storeys : int
        Floors of the superstructure above the slab.

    Returns
    -------
    str or int
        ``"base"`` for the slab (``0``), ``"roof"`` for the top floor (``storeys``), the number of a
        floor between; its ``str`` is the floor's label in the datasets.

    Raises
    ------
    ValueError
        Naming ``key``, the value and the allowed range.
    """
    if isinstance(floor, str) and floor in FLOORS:
        return floor
    if isinstance(floor, int) and not isinstance(floor, bool) and 0 <= floor <= storeys:
        return FLOORS[0] if floor == 0 else (FLOORS[1] if floor == storeys else floor)
    raise ValueError(f"{key} = {floor!r} is out of range; allowed: {', '.join(map(repr, FLOORS))} or an integer, "
                     f"0 <= floor <= {storeys} (fragility.building.storeys = {storeys})")


def check_settings(settings: dict) -> Study:
    """Check the ``fragility`` section (schema-completed) and draw the friction table.

    Parameters
    ----------
    settings : dict
        :func:`fragility_settings` of a complete configuration.

    Returns
    -------
    Study
        The checked settings with the records read and every friction coefficient drawn.

    Raises
    ------
    ValueError
        Naming the key, its value and what is allowed (records that cannot be read included).
    """
    f = settings["fragility"]
    b, c = check_building(f), f["contents"]
    im, levels, limits, n_s = check_stripes(f, f, "", "'pga', 'pgv'")
    names = list(f["records"])
    if len(names) < 2:
        raise ValueError(f"fragility.records = {names!r} is invalid; allowed: at least 2 records "
                         f"(the bootstrap resamples records)")
    recs = []
    for i, name in enumerate(names):
        try:
            recs.append(resolve_record(name))
        except (ValueError, OSError, LookupError) as err:
            raise ValueError(f"fragility.records[{i}] = {name!r} cannot be read: {err}") from None
    rec_names = [r.name for r in recs]
    if len(set(rec_names)) != len(rec_names):
        raise ValueError(f"fragility.records = {names!r} is invalid; allowed: distinct records, got names {rec_names}")
    seed = int(f["seed"])
    rng = np.random.default_rng(seed)
    z = rng.standard_normal((len(recs), levels.size, n_s))
    mu_k = float(c["mu_k"]["median"]) * np.exp(float(c["mu_k"]["log_std"]) * z)
    level = check_level(f)
    chunk_size = check_chunk_size("fragility.chunk_size", f["chunk_size"])
    return Study(records=tuple(recs), im=im, levels=levels, n_samples=n_s, limit_states=limits, mu_k=mu_k,
                 building=b, contents=copy.deepcopy(c), seed=seed, n_boot=int(f["bootstrap"]["n_boot"]),
                 level=level, chunk_size=chunk_size, rtol=settings["solver"]["rtol"])


def analysis_table(study: Study) -> dict:
    """Index arrays of every analysis in the fixed order record, stripe, sample.

    Returns
    -------
    dict
        ``record``, ``stripe``, ``friction_sample`` (int indices) and ``mu_k`` (flat arrays).
    """
    r, j, s = np.meshgrid(np.arange(len(study.records)), np.arange(study.levels.size),
                          np.arange(study.n_samples), indexing="ij")
    return {"record": r.ravel(), "stripe": j.ravel(), "friction_sample": s.ravel(), "mu_k": study.mu_k.ravel()}


def n_chunks(study: Study) -> int:
    """Number of chunks of ``chunk_size`` analyses."""
    return max(1, -(-study.size // study.chunk_size))


def chunk_indices(study: Study, chunk: int) -> np.ndarray:
    """Analysis indices of chunk ``chunk`` (0-based)."""
    n = n_chunks(study)
    if not 0 <= chunk < n:
        raise ValueError(f"chunk = {chunk!r} is out of range; allowed range: 0 <= chunk < {n}")
    return np.arange(chunk * study.chunk_size, min((chunk + 1) * study.chunk_size, study.size))


def scaled_pulse(record, im: str, level: float):
    """The record scaled so its ``im`` equals ``level``, as a pulse, with its peaks.

    Parameters
    ----------
    record : Record
        Run as recorded (own sign and time axis).
    im : {"pga", "pgv"}
        Scaling intensity measure (:func:`isoslide.studies.intensity.ground_peaks`).
    level : float
        Target, m/s^2 (pga) or m/s (pgv).

    Returns
    -------
    pulse, pga, pgv
        A sampled pulse in units of ``a_p = pga`` [m/s^2] and ``T_p`` = :data:`T_SCALE`, and the
        scaled record's PGA [m/s^2] and PGV [m/s].
    """
    pga0, pgv0 = ground_peaks(record.accel, record.dt)
    factor = level / (pga0 if im == "pga" else pgv0)
    pga, pgv = pga0 * factor, pgv0 * factor
    a = np.asarray(record.accel) * (G * factor / pga)
    pulse = sampled(a, record.dt / T_SCALE, (record.t_start) / T_SCALE, name=record.name)
    return pulse, pga, pgv


def _scene(study: Study, pulse, pga: float, mu_k: float, base: str) -> Scene:
    b, c = study.building, study.contents
    return Scene.from_physical(a_p=pga, T_p=T_SCALE, M_b=b["M_b"], xi_b=b["xi_b"], m_ec=c["mass"],
                               mu_s=mu_k * c["mu_s_over_mu_k"], mu_k=mu_k, beta=c["beta"], gamma=c["gamma"], pulse=pulse,
                               m_st=b["m_st"], T_s=b["T_s"], xi_s=b["xi_s"], storeys=b["storeys"], floor=b["floor"],
                               **isolator(b, base))


def solve_chunk(study: Study, chunk: int, base: str) -> xr.Dataset:
    """Solve the analyses of one chunk on ``base`` (``"isolated"`` or ``"fixed_base"``).

    Returns
    -------
    xarray.Dataset
        :func:`solve_analyses` of the chunk's indices.
    """
    return solve_analyses(study, chunk_indices(study, chunk), base)


def solve_analyses(study: Study, indices, base: str, floor: bool = True) -> xr.Dataset:
    """Solve the analyses ``indices`` (global, in any subset) on ``base``.

    Parameters
    ----------
    study : Study
    indices : array_like of int
        Analysis indices (:func:`analysis_table` order).
    base : {"isolated", "fixed_base"}
    floor : bool
        Compute PFA and PFV (a solve with history, :func:`isoslide.studies.intensity.floor_peaks`);
        ``False`` solves for ``u_max`` only and leaves them NaN (to measure what the floor costs).

    Returns
    -------
    xarray.Dataset
        Dimension ``analysis`` (global indices): ``record`` (name), ``stripe``,
        ``friction_sample``, ``mu_k``, ``pga`` [m/s^2], ``pgv`` [m/s], ``pfa`` [m/s^2],
        ``pfv`` [m/s], ``u_max`` [m], and the facets of the model that ran (``model_<facet>`` flags).
    """
    dataset_name(base)
    idx = np.asarray(indices, dtype=np.int64)
    tab = analysis_table(study)
    out, models = new_outputs(idx.size, ("pga", "pgv", "pfa", "pfv", "u_max"))
    cache: dict = {}
    for k, i in enumerate(idx):
        r, j, mu = int(tab["record"][i]), int(tab["stripe"][i]), float(tab["mu_k"][i])
        if (r, j) not in cache:
            cache.clear()
            cache[(r, j)] = scaled_pulse(study.records[r], study.im, float(study.levels[j]))
        pulse, pga, pgv = cache[(r, j)]
        scene = _scene(study, pulse, pga, mu, base)
        sol = solved(scene, f"record {study.records[r].name!r} at stripe {float(study.levels[j])!r}", rtol=study.rtol,
                     history=floor)
        if floor:
            out["pfa"][k], out["pfv"][k] = floor_peaks(sol, scene)
        out["pga"][k], out["pgv"][k], out["u_max"][k] = pga, pgv, sol.u_max
        models[k] = sol.facets
    return _analysis_dataset(study, idx, tab, out, models)


def new_outputs(n: int, names) -> tuple:
    """Empty outputs of ``n`` analyses: NaN arrays ``names`` and a column for their model facets.

    Returns
    -------
    out : dict
        Name -> float array of length ``n``, NaN until solved.
    models : numpy.ndarray of object
        Length ``n``, for the model facets of each analysis (:func:`add_outputs`).
    """
    return {k: np.full(n, np.nan) for k in names}, np.empty(n, dtype=object)


_ANALYSIS_META = {
    "stripe": ("index of the stripe (im_level) the record was scaled to", "1"),
    "friction_sample": ("index of the friction draw of this record and stripe", "1"),
    "mu_k": ("kinetic friction coefficient of the contents (lognormal draw)", "1"),
    "pga": ("peak ground acceleration of the scaled record", "m s-2"),
    "pgv": ("peak ground velocity of the scaled record (exact integral, linear between samples)", "m s-1"),
    "pfa": ("peak absolute acceleration of the floor under the contents", "m s-2"),
    "pfv": ("peak absolute velocity of the floor under the contents", "m s-1"),
    "u_max": ("peak sliding displacement of the contents relative to the floor", "m"),
}


def _analysis_dataset(study, idx, tab, out, models) -> xr.Dataset:
    names = np.array([study.records[int(r)].name for r in tab["record"][idx]], dtype=object)
    ds = analysis_frame(idx, "record, stripe, friction sample")
    ds["record"] = ("analysis", names, {"long_name": "record name"})
    add_table_columns(ds, tab, idx, ("stripe", "friction_sample"), ("mu_k",))
    return add_outputs(ds, out, ("pga", "pgv", "pfa", "pfv", "u_max"), _ANALYSIS_META, models)


def analysis_frame(idx: np.ndarray, order: str) -> xr.Dataset:
    """A dataset over ``analysis`` holding only its coordinate: the global indices of the analyses.

    Parameters
    ----------
    idx : numpy.ndarray of int
        Analysis indices (global, in the order of the study's analysis table).
    order : str
        The axes of that table, outermost first, as the coordinate's ``long_name`` names them.
    """
    return xr.Dataset(coords={"analysis": ("analysis", idx.astype(np.int64),
                                           {"long_name": f"analysis index ({order} order)", "units": "1"})})


def add_table_columns(ds: xr.Dataset, tab: dict, idx: np.ndarray, ints: tuple, floats: tuple) -> None:
    """Store the analysis table's columns at the analyses ``idx`` in ``ds`` (in place).

    Parameters
    ----------
    ds : xarray.Dataset
        Dataset over ``analysis`` (:func:`analysis_frame` of ``idx``).
    tab : dict
        The study's analysis table (flat arrays over every analysis).
    idx : numpy.ndarray of int
        The analyses of ``ds``.
    ints, floats : tuple of str
        Columns stored as 32-bit indices, then columns stored as they are, in that order.
    """
    for k in ints:
        ds[k] = ("analysis", tab[k][idx].astype(np.int32))
    for k in floats:
        ds[k] = ("analysis", tab[k][idx])


def add_outputs(ds: xr.Dataset, out: dict, names: tuple, meta: dict, models) -> xr.Dataset:
    """Store the outputs of the analyses, their CF attributes and the model facets in ``ds`` (in place).

    Parameters
    ----------
    ds : xarray.Dataset
        Dataset over ``analysis``.
    out : dict
        Output arrays over ``analysis``.
    names : tuple
        Keys of ``out`` to store, in order.
    meta : dict
        Variable name -> (long_name, units) of variables in ``ds`` once ``names`` are stored.
    models : list
        Model facets of the analyses (:func:`isoslide.datasets.encode_facets`).

    Returns
    -------
    xarray.Dataset
        ``ds``.
    """
    for k in names:
        ds[k] = ("analysis", out[k])
    for k, (ln, u) in meta.items():
        ds[k].attrs.update(long_name=ln, units=u)
    for name, var in encode_facets(models, ("analysis",)).items():
        ds[name] = var
    return ds


def merge_chunks(parts) -> xr.Dataset:
    """Concatenate chunk datasets along ``analysis`` in index order (checks that none is missing)."""
    parts = sorted(parts, key=lambda p: int(p["analysis"].values[0]))
    ds = xr.concat(parts, dim="analysis", data_vars="all", coords="minimal", combine_attrs="override")
    a = ds["analysis"].values
    if not np.array_equal(a, np.arange(a.size)):
        raise ValueError("fragility chunks do not cover the analyses 0 ... n-1 exactly once")
    return ds


def solve_all(study: Study, base: str) -> xr.Dataset:
    """Every analysis of the study on ``base``, chunk by chunk (the merge job of a one-chunk study)."""
    return merge_chunks([solve_chunk(study, c, base) for c in range(n_chunks(study))])


def chunk_job(module, name: str, chunk: int, settings: dict, job_log) -> xr.Dataset:
    """The pipeline's chunk job of a fragility dataset: the analyses of one chunk, solved.

    Parameters
    ----------
    module, name, settings, job_log
        As for :func:`dataset_job` (``module.solve_chunk`` solves).
    chunk : int
        The chunk (0-based).

    Returns
    -------
    xarray.Dataset
        ``module.solve_chunk`` of the chunk.
    """
    base = module.base_of(name)
    study = module.check_settings(settings)
    job_log.info("%s, chunk %d (%s base)", name, chunk, base)
    return compile_and_solve(job_log, functools.partial(solver.warm_up, records=True),
                             functools.partial(module.solve_chunk, study, chunk, base))


def dataset_job(module, make_dataset, paths, name: str, settings: dict, job_log) -> xr.Dataset:
    """The pipeline's dataset job of a fragility dataset: its chunks merged (or solved here), then fitted.

    Parameters
    ----------
    module : module
        The study: :mod:`isoslide.studies.fragility_study` or :mod:`isoslide.studies.fragility_planar`
        (its ``base_of``, ``check_settings`` and ``solve_all``).
    make_dataset : callable
        ``(analyses, study, settings, base) -> xarray.Dataset``: :func:`fragility_dataset` or
        :func:`isoslide.studies.fragility_planar.planar_dataset`.
    paths : sequence of path-like
        The chunk files of the dataset; none for a dataset of one chunk.
    name : str
        The dataset stem (``fragility``, ``fragility_planar_fixed_base``, ...), which names the base.
    settings : dict
        The study's settings (:func:`fragility_settings` or ``planar_settings``).
    job_log : logging.Logger
        Receives what the job does and the seconds of each phase (:func:`isoslide.budget.phase`).

    Returns
    -------
    xarray.Dataset
        ``make_dataset`` of the analyses.
    """
    base = module.base_of(name)
    study = module.check_settings(settings)
    if paths:
        job_log.info("merging %d chunk files of %s", len(paths), name)
        with phase("writing", job_log):
            analyses = merge_chunks([open_dataset(p) for p in paths])
    else:
        job_log.info("%s is one chunk (%d analyses): solved in this job", name, study.size)
        analyses = compile_and_solve(job_log, functools.partial(solver.warm_up, records=True),
                                     functools.partial(module.solve_all, study, base))
    with phase("solving", job_log):  # maximum-likelihood fits and the bootstrap
        return make_dataset(analyses, study, settings, base)


def _exceeded(u: np.ndarray, limit: float) -> np.ndarray:
    return u > limit


def fit_curves(ds: xr.Dataset, study: Study) -> xr.Dataset:
    """Fitted ``theta``, ``beta``, bounds and status over ``limit_state`` x ``im``.

    The scaling IM is fitted by stripes (counts per level), the others per analysis; the
    bootstrap resamples records (``n_boot`` resamples, ``level`` two-sided, seeded with ``seed``).
    """
    u = ds["u_max"].values
    groups = ds["record"].values.astype(str)
    nl, ni = study.limit_states.size, len(IM_NAMES)
    shape = (nl, ni)
    res = {k: np.full(shape, np.nan) for k in ("theta", "beta", "theta_low", "theta_high", "beta_low",
                                               "beta_high", "log_likelihood")}
    status = np.zeros(shape, dtype=np.int8)
    n_failed = np.zeros(shape, dtype=np.int32)
    stripe = ds["stripe"].values
    n_exc = np.zeros(nl, dtype=np.int64)
    for a, limit in enumerate(study.limit_states):
        exc = _exceeded(u, float(limit))
        n_exc[a] = int(exc.sum())
        for b, im in enumerate(IM_NAMES):
            if im == study.im:
                x = study.levels[stripe]
                z = np.array([int(exc[stripe == j].sum()) for j in range(study.levels.size)])
                nj = np.array([int((stripe == j).sum()) for j in range(study.levels.size)])
                args = (study.levels, z, nj)
            else:
                x = ds[im].values
                args = (x, exc, None)
            if not exc.any():
                status[a, b] = 1
                continue
            if exc.all():
                status[a, b] = 2
                continue
            try:
                fit = _fit.fit_lognormal(*args)
            except (ValueError, RuntimeError):  # not identifiable; RuntimeError: no convergence
                status[a, b] = 3
                continue
            res["theta"][a, b], res["beta"][a, b] = fit.theta, fit.beta
            res["log_likelihood"][a, b] = fit.log_likelihood
            if study.n_boot > 0:
                try:
                    bi = _fit.bootstrap(x, exc, groups, n_boot=study.n_boot, seed=study.seed + 7919 * a + b,
                                        level=study.level)
                except (ValueError, RuntimeError):  # the bootstrap as a whole failed: no bounds
                    n_failed[a, b] = study.n_boot
                    continue
                res["theta_low"][a, b], res["theta_high"][a, b] = bi.theta_low, bi.theta_high
                res["beta_low"][a, b], res["beta_high"][a, b] = bi.beta_low, bi.beta_high
                n_failed[a, b] = bi.n_failed
    units = [IM_UNITS[k] for k in IM_NAMES]
    out = xr.Dataset(coords={
        "limit_state": ("limit_state", study.limit_states,
                        {"long_name": "sliding displacement limit (u_max > limit_state exceeds it)", "units": "m"}),
        "im": ("im", np.array(IM_NAMES, dtype=object), {"long_name": "intensity measure"}),
        "im_units": ("im", np.array(units, dtype=object), {"long_name": "units of the intensity measure"}),
    })
    dims = ("limit_state", "im")
    u_txt = "m s-2 (pga, pfa) or m s-1 (pgv, pfv): see im_units"
    pct = f"{study.level:.0%}"
    add_curves(out, dims, res, status, n_failed, u="u_max", u_txt=u_txt, pct=pct, resampled="records",
               extra={"log_likelihood": ("maximised log-likelihood of the fit", "1")})
    out["n_exceeded"] = ("limit_state", n_exc, {"long_name": "analyses with u_max > limit_state", "units": "1"})
    out["fit_method"] = ("im", np.array(["stripes" if k == study.im else "per analysis" for k in IM_NAMES],
                                        dtype=object),
                         {"long_name": "maximum likelihood on stripe counts or on one outcome per analysis"})
    return out


def add_curves(out: xr.Dataset, dims: tuple, res: dict, status: np.ndarray, failed: np.ndarray, *, u: str,
               u_txt: str, pct: str, resampled: str, extra: dict | None = None) -> None:
    """Store fitted curves with their CF attributes in ``out`` (in place).

    Writes ``theta``, ``beta``, their bootstrap bounds, the entries of ``extra``, then
    ``fit_status`` and ``n_boot_failed``, all over ``dims``.

    Parameters
    ----------
    out : xarray.Dataset
        The dataset receiving the variables.
    dims : tuple
        Dimensions of every variable.
    res : dict
        Arrays ``theta``, ``beta``, ``theta_low``, ``theta_high``, ``beta_low``, ``beta_high`` and
        those named in ``extra``.
    status, failed : numpy.ndarray
        ``fit_status`` flags (see ``FIT_STATUS``) and failed bootstrap resamples.
    u : str
        Name of the response in the curve's formula (``u_max`` or ``u``).
    u_txt : str
        Units of ``theta`` and its bounds.
    pct : str
        Confidence level of the bounds as text (``"90%"``).
    resampled : str
        What the bootstrap resamples (``records``, ``ground motions``).
    extra : dict, optional
        Further variables, name -> (long_name, units), stored after the bounds.
    """
    meta = {
        "theta": (f"median capacity theta of P({u} > limit | IM) = Phi(ln(IM/theta)/beta)", u_txt),
        "beta": ("lognormal dispersion beta of the fragility curve", "1"),
        "theta_low": (f"lower bound of the {pct} bootstrap interval of theta ({resampled} resampled)", u_txt),
        "theta_high": (f"upper bound of the {pct} bootstrap interval of theta ({resampled} resampled)", u_txt),
        "beta_low": (f"lower bound of the {pct} bootstrap interval of beta ({resampled} resampled)", "1"),
        "beta_high": (f"upper bound of the {pct} bootstrap interval of beta ({resampled} resampled)", "1"),
        **(extra or {}),
    }
    for k, (ln, un) in meta.items():
        out[k] = (dims, res[k], {"long_name": ln, "units": un})
    out["fit_status"] = (dims, status, {
        "long_name": "why a curve is missing (NaN theta, beta)", "units": "1",
        "flag_values": np.arange(len(FIT_STATUS), dtype=np.int8), "flag_meanings": " ".join(FIT_STATUS)})
    out["n_boot_failed"] = (dims, failed, {"long_name": "bootstrap resamples whose fit failed", "units": "1"})


def _share(values: np.ndarray, groups: np.ndarray) -> float:
    """Share of the variance of ``values`` between the group means (law of total variance)."""
    total = float(np.var(values))
    if total == 0.0:
        return math.nan
    means = np.array([values[groups == g].mean() for g in np.unique(groups)])
    counts = np.array([(groups == g).sum() for g in np.unique(groups)])
    between = float(np.sum(counts * (means - values.mean()) ** 2) / counts.sum())
    return between / total


def scatter_contributions(ds: xr.Dataset, study: Study) -> xr.Dataset:
    """Record-to-record share of the scatter per stripe (the rest is the friction's).

    Returns
    -------
    xarray.Dataset
        ``record_share_exceed`` (limit_state, im_level) for the exceedance indicators and
        ``record_share_ln_u`` (im_level) for ``ln u_max`` (NaN where some analysis does not slide,
        or nothing varies), each the between-record variance over the total.
    """
    u = ds["u_max"].values
    rec = ds["record"].values.astype(str)
    stripe = ds["stripe"].values
    nj = study.levels.size
    exc = np.full((study.limit_states.size, nj), np.nan)
    lnu = np.full(nj, np.nan)
    for j in range(nj):
        m = stripe == j
        if not m.any():
            continue
        for a, limit in enumerate(study.limit_states):
            exc[a, j] = _share(_exceeded(u[m], float(limit)).astype(float), rec[m])
        if np.all(u[m] > 0):
            lnu[j] = _share(np.log(u[m]), rec[m])
    out = xr.Dataset(coords={"limit_state": ("limit_state", study.limit_states, {
        "long_name": "sliding displacement limit (u_max > limit_state exceeds it)", "units": "m"}),
                             "im_level": ("im_level", study.levels, {
        "long_name": f"stripe level of the scaling intensity measure ({study.im})", "units": IM_UNITS[study.im]})})
    note = (" (law of total variance over the analyses of a stripe; the rest is the friction scatter "
            "within records; with n friction samples the record term also holds 1/n of it)")
    out["record_share_exceed"] = (("limit_state", "im_level"), exc, {
        "long_name": "record-to-record share of the variance of the exceedance indicator" + note, "units": "1"})
    out["record_share_ln_u"] = ("im_level", lnu, {
        "long_name": "record-to-record share of the variance of ln u_max (NaN unless every analysis slides)" + note,
        "units": "1"})
    return out


def check_tfp(b: dict) -> None:
    """Check ``fragility.building.tfp`` (schema-completed): a bearing :func:`isolator` can build.

    Raises
    ------
    ValueError
        Naming the key, its value and the rule: the bearing's own rules
        (:func:`isoslide.triple_friction_pendulum`), or ``Q_d`` or ``D_y`` set beside it.
    """
    tfp = b["tfp"]
    if tfp is None:
        return
    for key in ("Q_d", "D_y"):
        if float(b[key]) != 0.0:
            raise ValueError(f"fragility.building.{key} = {b[key]!r} is set beside fragility.building.tfp; allowed: "
                             f"{key} = 0 with a triple friction pendulum (its geometry and friction give it)")
    try:
        isolator(b, "isolated")
    except ValueError as err:
        raise ValueError(f"fragility.building.tfp = {tfp!r} is invalid: {err}") from None


def isolator(b: dict, base: str) -> dict:
    """The isolator's keyword arguments of :meth:`isoslide.Scene.from_physical` for the building ``b`` on ``base``.

    Parameters
    ----------
    b : dict
        The ``fragility.building`` section (schema-completed).
    base : {"isolated", "fixed_base"}

    Returns
    -------
    dict
        On a fixed base ``T_b = 0`` (and the section's ``Q_d``, ``D_y``); isolated, the section's
        ``T_b``, ``Q_d`` and ``D_y``, or with ``tfp`` those of
        :func:`isoslide.triple_friction_pendulum` (``T_b`` [s], ``Q_d`` [N], ``D_y`` [m], ``tfp`` and,
        with friction rising with speed, ``Q_slow`` [N] and ``rate`` [s/m]).
    """
    tfp = b["tfp"]
    if base == "fixed_base" or tfp is None:
        return {"T_b": 0.0 if base == "fixed_base" else b["T_b"], "Q_d": b["Q_d"], "D_y": b["D_y"]}
    return triple_friction_pendulum(tfp["L"], tfp["mu"], tfp["d"], b["M_b"], mu_slow=tfp["mu_slow"], rate=tfp["rate"])


def solved(scene: Scene, what: str, **options):
    """:func:`isoslide.solve` of one analysis' ``scene``; a bearing past its capacity names the analysis.

    Raises
    ------
    isoslide.solver.CapacityError
        With ``what`` (the analysis: ground motion and stripe) and the keys that size the bearing
        and the stripes: the model of rigid restrainers does not go past them.
    """
    try:
        return solver.solve(scene, **options)
    except solver.CapacityError as err:
        raise solver.CapacityError(f"{what}: {err}; a larger fragility.building.tfp.d or lower stripes "
                                   "keep the bearing within its capacity") from None


def base_label(base: str) -> str:
    """``isolated slab`` or ``fixed base``: the base as the title of a fragility dataset names it."""
    return "isolated slab" if base == "isolated" else "fixed base"


def design_attrs(study, base: str) -> dict:
    """The global attributes of a fragility dataset that describe its building and contents, in stored order.

    Parameters
    ----------
    study : Study or isoslide.studies.fragility_planar.PlanarStudy
        Its ``building`` and ``contents`` sections.
    base : {"isolated", "fixed_base"}

    Returns
    -------
    dict
        ``T_b`` [s] (0 on a fixed base), ``xi_b`` [1], ``M_b`` [kg], ``m_ec`` [kg], ``Q_d`` [N],
        ``D_y`` [m], ``m_st`` [kg], ``T_s`` [s], ``xi_s`` [1], ``storeys`` (floors above the slab),
        ``floor`` (its label: ``base``, ``roof`` or the floor's number), ``mu_k_median`` [1],
        ``mu_k_log_std`` [1], ``mu_s_over_mu_k`` [1], ``beta_stribeck`` [s/m], ``gamma`` [s/m]; on a
        triple friction pendulum (``T_b``, ``Q_d``, ``D_y`` its own) also ``tfp_L`` [m], ``tfp_mu`` [1],
        ``tfp_d`` [m] and, with ``mu_slow``, ``tfp_mu_slow`` [1] and ``tfp_rate`` [s/m] (three values each).
    """
    b, c = study.building, study.contents
    iso = isolator(b, base)
    out = {"T_b": float(iso["T_b"]), "xi_b": float(b["xi_b"]),
           "M_b": float(b["M_b"]), "m_ec": float(c["mass"]), "Q_d": float(iso["Q_d"]), "D_y": float(iso["D_y"]),
           "m_st": float(b["m_st"]), "T_s": float(b["T_s"]), "xi_s": float(b["xi_s"]),
           "storeys": int(b["storeys"]), "floor": str(b["floor"]),
           "mu_k_median": float(c["mu_k"]["median"]), "mu_k_log_std": float(c["mu_k"]["log_std"]),
           "mu_s_over_mu_k": float(c["mu_s_over_mu_k"]), "beta_stribeck": float(c["beta"]),
           "gamma": float(c["gamma"])}
    tfp = b["tfp"]
    if "tfp" in iso:
        keys = ("L", "mu", "d") if tfp["mu_slow"] is None else ("L", "mu", "d", "mu_slow", "rate")
        out.update({f"tfp_{k}": np.broadcast_to(np.array(tfp[k], dtype=np.float64), 3).copy() for k in keys})
    return out


def bootstrap_attrs(study) -> dict:
    """The global attributes ``seed``, ``n_boot`` and ``confidence_level`` of a fragility dataset."""
    return {"seed": study.seed, "n_boot": study.n_boot, "confidence_level": study.level}


def fragility_dataset(analyses: xr.Dataset, study: Study, settings: dict, base: str) -> xr.Dataset:
    """The study dataset: the analyses, the fitted curves, the scatter shares, CF attributes.

    Parameters
    ----------
    analyses : xarray.Dataset
        :func:`merge_chunks` of every chunk (or :func:`solve_all`).
    study : Study
        :func:`check_settings` of ``settings``.
    settings : dict
        :func:`fragility_settings` (stored as ``isoslide_config``).
    base : {"isolated", "fixed_base"}
    """
    dataset_name(base)
    ds = analyses.copy()
    ds["record"] = ds["record"].astype(str)
    ds["record"].attrs["long_name"] = "record name"
    ds = xr.merge([ds, fit_curves(analyses, study), scatter_contributions(analyses, study)],
                  combine_attrs="override")
    ds["stripe"].attrs["long_name"] = "index of the stripe (into im_level) the record was scaled to"
    betas = {k: ds["beta"].sel(im=k).values for k in IM_NAMES}
    mean_beta = ", ".join(f"{k} {float(np.mean(v[np.isfinite(v)])):.3g}" if np.isfinite(v).any() else f"{k} n/a"
                          for k, v in betas.items())
    ds.attrs = global_attrs(
        title=f"isoslide fragility of sliding contents ({base_label(base)})",
        history=(f"isoslide.studies.fragility_study: {len(study.records)} records x {study.levels.size} stripes of "
                 f"{study.im} x {study.n_samples} friction draws = {study.size} analyses solved exactly "
                 f"(isoslide.solve with history), fitted by maximum likelihood (isoslide.studies.fragility), "
                 f"{study.n_boot} bootstrap resamples of the records; no timestamps are stored"),
        config=settings,
        references_fragility=REFERENCE_FRAGILITY,
        base=base, scaling_im=study.im, **design_attrs(study, base), **bootstrap_attrs(study),
        mean_beta_by_im=mean_beta,
        peaks=("pga: largest sample; pgv: exact integral of the linear-between-samples record; pfa: largest "
               "history row refined by a parabola through it and its neighbours; pfv: history rows and the "
               "interior extremum where the floor acceleration changes sign (linear between rows)"),
        sources="; ".join(sorted({r.licence for r in study.records if r.licence})),
    )
    return ds

