"""Fragility in the plane: recorded pairs of ground-motion suites, both components at once, against one at a time.

Multiple-stripe analysis (Baker 2015) on suites of ground motions with two horizontal components
(:func:`isoslide.records.suite`, e.g. the FEMA P695 sets), configured under ``fragility.planar``
and sharing the building, contents, limit states, seed and bootstrap of the fragility study
(:mod:`isoslide.studies.fragility_study`).  Every pair ``(a_x, a_y)`` is scaled, as recorded, so
that its RotD50 PGA (or PGV, :func:`isoslide.studies.intensity.pair_peaks`) equals each stripe
level, one factor for both components.  For each ground motion, orientation ``theta`` (the angle
from the building's x axis to the recorded x component, ``angles`` in degrees, or drawn per
analysis with ``sampled_angles``), stripe and kinetic friction draw, three analyses run:

* **planar** -- both components at once, :func:`isoslide.solve` of
  ``Scene(pulse=a_x, pulse_y=a_y, angle=theta)``: the peak Euclidean slide ``u_max`` [m] and its
  direction;
* **x** and **y** -- one component at a time (the 1-D model): the ground motion along the
  building's x axis, ``a_x cos(theta) - a_y sin(theta)``, alone, and along its y axis,
  ``a_x sin(theta) + a_y cos(theta)``, alone: ``u_max_x``, ``u_max_y`` [m].

The building and the contents are isotropic in the plane (a fixed base, a linear isolator, a
friction pendulum, a lead-rubber bearing with its circular yield surface), so the planar answer does
not depend on ``theta`` (it only turns the direction; the analyses at several angles measure that
the solver agrees with itself), while the one-component answers do: the orientation is what one
component at a time leaves to chance.

Curves ``P(u > limit | IM) = Phi(ln(IM / theta) / beta)`` are fitted by maximum likelihood
(:func:`isoslide.studies.fragility.fit_lognormal`) for each floor, group of ground motions (all of
them, and each suite), **motion** and limit state, against three IMs of the scaled pair:
``pga_rotd50``, ``pgv_rotd50`` and ``sa_rotd50`` (5 %-damped pseudo-spectral acceleration at the
isolation period ``building.T_b``), and two of the floor the pair drives in the plane, ``pfa`` and
``pfv`` (the peak lengths of its absolute acceleration and velocity vectors under the planar
analysis, :func:`isoslide.studies.intensity.planar_floor_peaks`; on a fixed base the ground's); the
scaling IM by its stripe counts, the others per analysis.  The floor IMs are those of the shaking
in the plane: the one-component outcomes are fitted against the same values, so that every motion
is compared at one intensity.
The motions (:data:`MOTIONS`): ``planar``; ``one_component``, the x and y analyses pooled (each an
analysis of the 1-D model); ``max_component``, the larger of the two 1-D answers of an analysis (an
engineer who runs both directions and keeps the worse).

Confidence intervals come from one bootstrap (:data:`BOOT_SEED_OFFSET`): each resample draws, suite
by suite, as many ground motions as the suite has, with replacement, and refits every curve on
them (all its floors, angles, stripes and draws go in together); the group ``all`` is the union of
the suites' draws.  All resamples of a curve are fitted at once
(:func:`isoslide.studies.fragility.fit_weighted`, each analysis weighted by the times its ground
motion is drawn).  The same resamples give the intervals of the comparisons:
``theta_ratio`` (the planar median over the one-component one), ``beta_change`` (the planar
dispersion minus the one-component one), ``suite_theta_ratio`` (each suite's median over the
reference suite's, resampled independently) and ``floor_theta_ratio`` (each floor's median over
the first floor's).

Reproducibility: friction coefficients (per ground motion, stripe and draw, shared by the angles,
floors, bases and the three motions: the comparisons are paired) and sampled angles are drawn up
front from ``numpy.random.default_rng`` seeded with ``fragility.seed``; a chunk takes its slice of
the analysis table, so a chunk alone reproduces its analyses and the merged dataset does not
depend on the chunking.

Pipeline functions: :func:`planar_settings`, :func:`check_settings`, :func:`n_chunks`,
:func:`solve_chunk`, :func:`solve_all`, :func:`planar_dataset`.
"""

from __future__ import annotations

import copy
import functools
import math
import warnings
from dataclasses import dataclass

import numpy as np
import xarray as xr

from . import fragility as _fit
from .fragility_study import (REFERENCE_FRAGILITY, T_SCALE, add_curves, add_outputs, add_table_columns, analysis_frame,
                              base_label, base_stem, bootstrap_attrs, check_building, check_chunk_size, check_floor,
                              check_level, check_stripes, chunk_indices, design_attrs, isolator, merge_chunks,
                              n_chunks, new_outputs, solved, stem_base)
from .intensity import align_pair, pair_peaks, pair_sa, peak_abs, planar_floor_peaks
from ..datasets import global_attrs
from ..pulses import sampled
from ..records import G, suite
from ..scene import FLOORS, Scene

__all__ = ["BASES", "IM_UNITS", "MOTIONS", "PLANAR_IMS", "PlanarStudy", "analysis_table", "base_of",
           "check_settings", "chunk_indices", "dataset_name", "dataset_names", "fit_curves", "merge_chunks", "n_chunks",
           "pair_intensities", "planar_dataset", "planar_settings", "solve_all", "solve_analyses", "solve_chunk"]

BASES = ("isolated", "fixed_base")
"""The buildings: the isolated slab, and the same contents on a fixed base."""

MOTIONS = ("planar", "one_component", "max_component")
"""Fitted outcomes: both components at once; one at a time (x and y pooled); the larger of x and y."""

PLANAR_IMS = ("pga_rotd50", "pgv_rotd50", "sa_rotd50", "pfa", "pfv")
"""Intensity measures the curves are fitted against: of the scaled pair, and of the floor it drives in the plane."""

IM_UNITS = {"pga_rotd50": "m s-2", "pgv_rotd50": "m s-1", "sa_rotd50": "m s-2", "pfa": "m s-2", "pfv": "m s-1"}
"""CF units of each intensity measure."""

SCALING_IMS = {"pga": "pga_rotd50", "pgv": "pgv_rotd50"}
"""``fragility.planar.stripes.im`` -> the intensity measure the pairs are scaled to."""

BOOT_SEED_OFFSET = 2
"""The bootstrap draws from ``default_rng([seed, 2])``, the friction from ``[seed, 0]``, the angles from ``[seed, 1]``."""

_SETTINGS_KEYS = ("building", "contents", "limit_states", "seed", "bootstrap", "planar")

_NOT_STORED = ("D_y", "floor", "beta_stribeck", "gamma")
"""Attributes of :func:`isoslide.studies.fragility_study.design_attrs` the planar datasets leave out
(their floors are the attribute ``floors``)."""


def dataset_name(base: str) -> str:
    """``fragility_planar`` (isolated) or ``fragility_planar_fixed_base``: the file stem of a base's dataset."""
    return base_stem("fragility_planar", base)


def base_of(name: str) -> str:
    """The base of a dataset stem: ``fragility_planar`` -> ``isolated``, ``..._fixed_base`` -> ``fixed_base``."""
    return stem_base(name, dataset_name)


def dataset_names(settings: dict) -> list:
    """Dataset stems of the planar analyses.

    None with ``planar.enabled`` false, else ``fragility_planar`` and, with
    ``building.fixed_base``, ``fragility_planar_fixed_base``.
    """
    f = settings["fragility"]
    if not f["planar"]["enabled"]:
        return []
    return [dataset_name(b) for b in BASES if b == "isolated" or f["building"]["fixed_base"]]


def planar_settings(config: dict) -> dict:
    """What the planar analyses read of a complete configuration (copies).

    ``fragility.building``, ``contents``, ``limit_states``, ``seed``, ``bootstrap`` and ``planar``,
    and ``solver``: not the records, stripes or friction draws of the 1-D study.
    """
    f = config["fragility"]
    return {"fragility": {k: copy.deepcopy(f[k]) for k in _SETTINGS_KEYS},
            "solver": copy.deepcopy(config["solver"])}


@dataclass(frozen=True)
class PlanarStudy:
    """Checked settings of the planar fragility analyses (SI units).

    Attributes
    ----------
    motions : tuple of GroundMotion
        The ground motions, suite after suite, each with ``x`` and ``y`` (in g, as recorded).
    suites : tuple of str
        The suites, in the configured order.
    suite_index : ndarray of int, shape (ground motions,)
        Suite of each ground motion (index into ``suites``).
    floors : tuple of str or int
        Floors carrying the contents: ``"base"`` (the slab), ``"roof"`` or the number of a floor
        between (of ``building.storeys``); their ``str`` labels the datasets' ``floor`` and ``contents_floor``.
    im : str
        Scaling IM, ``"pga_rotd50"`` or ``"pgv_rotd50"``.
    levels : ndarray
        Stripe levels, m/s^2 or m/s, increasing.
    angles : ndarray, shape (ground motions, orientations, stripes, samples)
        Orientation of every analysis, degrees (the angle from the building's x axis to the
        recorded x component).
    mu_k : ndarray, shape (ground motions, stripes, samples)
        Kinetic friction coefficients, shared by the orientations, floors and motions.
    limit_states : ndarray
        Sliding limits, m, increasing.
    building, contents : dict
        The configuration sections, the building's floor named by
        :func:`isoslide.studies.fragility_study.check_building`.
    sa_period, sa_damping : float
        Period [s] and damping ratio of ``sa_rotd50``.
    sampled_angles : bool
        The angles were drawn (uniform in [0, 180) degrees) rather than configured.
    seed, n_boot, level, chunk_size : int, int, float, int
    rtol : float or None
    """

    motions: tuple
    suites: tuple
    suite_index: np.ndarray
    floors: tuple
    im: str
    levels: np.ndarray
    angles: np.ndarray
    mu_k: np.ndarray
    limit_states: np.ndarray
    building: dict
    contents: dict
    sa_period: float
    sa_damping: float
    sampled_angles: bool
    seed: int
    n_boot: int
    level: float
    chunk_size: int
    rtol: float | None

    @property
    def shape(self) -> tuple:
        """``(floors, ground motions, orientations, stripes, samples)``: the axes of the analysis table."""
        return (len(self.floors),) + self.angles.shape

    @property
    def size(self) -> int:
        """Number of analyses (each one planar and two 1-D solves)."""
        return int(np.prod(self.shape))


def _suite_motions(name: str, pairs: int, index: int) -> tuple:
    try:
        motions = suite(name)
    except (ValueError, OSError, ModuleNotFoundError) as err:
        raise ValueError(f"fragility.planar.suites[{index}] = {name!r} cannot be read: {err}") from None
    motions = tuple(motions if pairs == 0 else motions[:pairs])
    single = [gm.name for gm in motions if gm.y is None]
    if single:
        raise ValueError(f"fragility.planar.suites[{index}] = {name!r} has ground motions with one horizontal "
                         f"component ({', '.join(single[:3])}); allowed: suites of pairs")
    if len(motions) < 2:
        raise ValueError(f"fragility.planar.suites[{index}] = {name!r} gives {len(motions)} ground motion(s); allowed: "
                         "at least 2 per suite (the bootstrap resamples the ground motions of each suite)")
    return motions


def _check_floors(floors, b: dict) -> tuple:
    """The floors of ``fragility.planar.floors``, checked and named as :func:`check_floor` names them.

    Parameters
    ----------
    floors : sequence of str or int
        ``"base"``, ``"roof"`` or floor numbers ``0 .. building.storeys``.
    b : dict
        The ``fragility.building`` section, checked (:func:`check_building`).

    Returns
    -------
    tuple of str or int
        The floors in the configured order: ``"base"``, ``"roof"`` or the number of a floor between.

    Raises
    ------
    ValueError
        Naming the key, its value and what is allowed: a floor out of range, a floor given twice
        (``0`` is ``"base"``, ``storeys`` is ``"roof"``), a floor above the slab with a rigid
        superstructure.
    """
    storeys = int(b["storeys"])
    given = list(floors)
    if not given:
        raise ValueError("fragility.planar.floors = [] is invalid; allowed: one or more floors")
    out = tuple(check_floor(f"fragility.planar.floors[{i}]", fl, storeys) for i, fl in enumerate(given))
    if len(set(out)) != len(out):
        raise ValueError(f"fragility.planar.floors = {given!r} is invalid; allowed: distinct floors (0 is 'base', "
                         f"{storeys} is 'roof' with fragility.building.storeys = {storeys})")
    above = [fl for fl in out if fl != FLOORS[0]]
    if above and float(b["T_s"]) == 0.0:
        raise ValueError(f"fragility.planar.floors has {above[0]!r} with a rigid superstructure (building.T_s = 0), "
                         "where every floor moves with the slab; allowed: floors above the slab ('roof', 1 ... "
                         "storeys) with building.T_s > 0")
    return out


def check_settings(settings: dict) -> PlanarStudy:
    """Check ``fragility.planar`` and the sections it shares, read the suites and draw the tables.

    The tables: a kinetic friction coefficient per ground motion, stripe and draw, and, with
    ``sampled_angles``, an orientation per analysis.

    Parameters
    ----------
    settings : dict
        :func:`planar_settings` of a complete configuration.

    Returns
    -------
    PlanarStudy
        The checked settings with the suites read and every friction coefficient and sampled angle drawn.

    Raises
    ------
    ValueError
        Naming the key, its value and what is allowed (suites that cannot be read included).
    """
    f = settings["fragility"]
    p = f["planar"]
    b = check_building(f)
    tfp = b["tfp"]
    if tfp is not None and "rate" not in isolator(b, "isolated"):
        raise ValueError(f"fragility.building.tfp = {tfp!r} has constant friction, which a triple friction pendulum "
                         "in the plane does not model; allowed: mu_slow below mu and rate > 0 on every surface")
    names = list(p["suites"])
    if not names or len(set(names)) != len(names):
        raise ValueError(f"fragility.planar.suites = {names!r} is invalid; allowed: one or more distinct suites")
    pairs = int(p["pairs"])
    if pairs < 0:
        raise ValueError(f"fragility.planar.pairs = {pairs!r} is out of range; allowed range: >= 0 (0: every pair)")
    motions, suite_index = [], []
    for i, name in enumerate(names):
        got = _suite_motions(str(name), pairs, i)
        motions += got
        suite_index += [i] * len(got)
    gm_names = [gm.name for gm in motions]
    if len(set(gm_names)) != len(gm_names):
        dup = sorted({n for n in gm_names if gm_names.count(n) > 1})
        raise ValueError(f"fragility.planar.suites = {names!r} share ground motions ({', '.join(dup[:3])}); "
                         "allowed: suites without a ground motion in common")
    floors = _check_floors(p["floors"], b)
    im, levels, limits, n_s = check_stripes(f, p, "planar.", "'pga', 'pgv' (RotD50)")
    angles_cfg = np.asarray(p["angles"], dtype=float)
    if angles_cfg.ndim != 1 or angles_cfg.size == 0 or not np.all((angles_cfg >= 0) & (angles_cfg < 180)):
        raise ValueError(f"fragility.planar.angles = {list(p['angles'])!r} is invalid; allowed: one or more angles "
                         "0 <= angle < 180 (degrees)")
    sampled_angles = bool(p["sampled_angles"])
    if not sampled_angles and np.unique(angles_cfg).size != angles_cfg.size:
        raise ValueError(f"fragility.planar.angles = {list(p['angles'])!r} is invalid; allowed: distinct angles")
    damping = float(p["sa_damping"])
    if not 0.0 <= damping < 1.0:
        raise ValueError(f"fragility.planar.sa_damping = {damping!r} is out of range; allowed range: 0 <= sa_damping < 1")
    chunk_size = check_chunk_size("fragility.planar.chunk_size", p["chunk_size"])
    level = check_level(f)
    seed = int(f["seed"])
    c = f["contents"]
    n_gm, n_j, n_a = len(motions), levels.size, angles_cfg.size
    z = np.random.default_rng([seed, 0]).standard_normal((n_gm, n_j, n_s))
    mu_k = float(c["mu_k"]["median"]) * np.exp(float(c["mu_k"]["log_std"]) * z)
    if sampled_angles:
        angles = np.random.default_rng([seed, 1]).uniform(0.0, 180.0, (n_gm, n_a, n_j, n_s))
    else:
        angles = np.broadcast_to(angles_cfg[None, :, None, None], (n_gm, n_a, n_j, n_s)).copy()
    return PlanarStudy(motions=tuple(motions), suites=tuple(map(str, names)), suite_index=np.asarray(suite_index),
                       floors=floors, im=SCALING_IMS[im], levels=levels, angles=angles, mu_k=mu_k,
                       limit_states=limits, building=b, contents=copy.deepcopy(c),
                       sa_period=float(b["T_b"]), sa_damping=damping, sampled_angles=sampled_angles, seed=seed,
                       n_boot=int(f["bootstrap"]["n_boot"]), level=level, chunk_size=chunk_size,
                       rtol=settings["solver"]["rtol"])


def analysis_table(study: PlanarStudy) -> dict:
    """Index arrays of every analysis in the fixed order floor, ground motion, orientation, stripe, sample.

    Returns
    -------
    dict
        ``floor``, ``ground_motion``, ``orientation``, ``stripe``, ``friction_sample`` (int
        indices), ``angle`` (degrees) and ``mu_k`` (flat arrays).
    """
    f, g, k, j, s = np.meshgrid(*(np.arange(n) for n in study.shape), indexing="ij")
    return {"floor": f.ravel(), "ground_motion": g.ravel(), "orientation": k.ravel(), "stripe": j.ravel(),
            "friction_sample": s.ravel(), "angle": study.angles[g, k, j, s].ravel(), "mu_k": study.mu_k[g, j, s].ravel()}


def pair_intensities(ax, ay, dt: float, period: float, damping: float) -> dict:
    """RotD50 of PGA [m/s^2], PGV [m/s] and Sa(period, damping) [m/s^2] of a pair in m/s^2 on one time axis."""
    pga, pgv = pair_peaks(ax, ay, dt)
    return {"pga_rotd50": pga, "pgv_rotd50": pgv, "sa_rotd50": pair_sa(ax, ay, dt, period, damping)}


@functools.lru_cache(maxsize=8)
def _pair(study_key, gm):
    """The pair of a ground motion in m/s^2 on one time axis, its start [s] and its unscaled IMs."""
    period, damping = study_key
    ax, ay = align_pair(np.asarray(gm.x.accel) * G, np.asarray(gm.y.accel) * G, gm.x.dt, gm.x.t_start, gm.y.t_start)
    return ax, ay, min(gm.x.t_start, gm.y.t_start), pair_intensities(ax, ay, gm.x.dt, period, damping)


def _scene(study: PlanarStudy, base: str, floor, a_ref: float, mu_k: float, pulse, pulse_y=None,
           angle: float = 0.0) -> Scene:
    b, c = study.building, study.contents
    return Scene.from_physical(a_p=a_ref, T_p=T_SCALE, M_b=b["M_b"], xi_b=b["xi_b"], m_ec=c["mass"],
                               mu_s=mu_k * c["mu_s_over_mu_k"], mu_k=mu_k, beta=c["beta"], gamma=c["gamma"], pulse=pulse,
                               pulse_y=pulse_y, angle=angle, m_st=b["m_st"], T_s=b["T_s"], xi_s=b["xi_s"],
                               storeys=b["storeys"], floor=floor, **isolator(b, base))


_OUT = ("scale_factor", "pga_rotd50", "pgv_rotd50", "sa_rotd50", "pfa", "pfv", "pga_x", "pga_y", "u_max", "u_max_x",
        "u_max_y", "peak_angle")


def solve_analyses(study: PlanarStudy, indices, base: str) -> xr.Dataset:
    """Solve the analyses ``indices`` (global, any subset) on ``base``: one planar and two 1-D solves each.

    Parameters
    ----------
    study : PlanarStudy
    indices : array_like of int
        Analysis indices (:func:`analysis_table` order: floor, ground motion, orientation, stripe, sample).
    base : {"isolated", "fixed_base"}

    Returns
    -------
    xarray.Dataset
        Dimension ``analysis`` (global indices): ``ground_motion`` (name), ``record_suite``,
        ``pulse`` (1, 0, or -1 not classified), ``contents_floor``, ``orientation``, ``angle``
        [degree], ``stripe``, ``friction_sample``, ``mu_k``, ``scale_factor``, the IMs of the
        scaled pair (``pga_rotd50``, ``pgv_rotd50`` [m/s^2, m/s], ``sa_rotd50``), the planar floor
        peaks (``pfa`` [m/s^2], ``pfv`` [m/s]), the PGA of the
        components along the building's axes (``pga_x``, ``pga_y``), ``u_max`` (planar),
        ``u_max_x``, ``u_max_y`` (one component) [m], ``peak_angle`` [degree] and the facets of the
        planar model (``model_<facet>`` flags).
    """
    dataset_name(base)
    idx = np.asarray(indices, dtype=np.int64)
    tab = analysis_table(study)
    out, models = new_outputs(idx.size, _OUT)
    key = (study.sa_period, study.sa_damping)
    for k, i in enumerate(idx):
        g, j, fl = int(tab["ground_motion"][i]), int(tab["stripe"][i]), study.floors[int(tab["floor"][i])]
        gm = study.motions[g]
        ax, ay, t0, ims = _pair(key, gm)
        factor = float(study.levels[j]) / ims[study.im]
        a_ref = factor * ims["pga_rotd50"]     # the pulse scale a_p [m/s^2]: the scaled pair's RotD50 PGA
        mu = float(tab["mu_k"][i])
        theta = math.radians(float(tab["angle"][i]))
        c, s = math.cos(theta), math.sin(theta)
        dt = gm.x.dt / T_SCALE
        px = sampled(ax * (factor / a_ref), dt, t0 / T_SCALE, name=gm.x.name)
        py = sampled(ay * (factor / a_ref), dt, t0 / T_SCALE, name=gm.y.name)
        what = f"pair {gm.name!r} at stripe {float(study.levels[j])!r}"
        scene = _scene(study, base, fl, a_ref, mu, px, py, theta)
        sol = solved(scene, what, rtol=study.rtol, history=True)
        out["pfa"][k], out["pfv"][k] = planar_floor_peaks(sol, scene)
        for label, comp in (("x", c * ax - s * ay), ("y", s * ax + c * ay)):
            one = sampled(comp * (factor / a_ref), dt, t0 / T_SCALE, name=f"{gm.name}@{label}")
            out[f"u_max_{label}"][k] = solved(_scene(study, base, fl, a_ref, mu, one), what, rtol=study.rtol).u_max
            out[f"pga_{label}"][k] = factor * peak_abs(comp)
        out["scale_factor"][k] = factor
        for name in ("pga_rotd50", "pgv_rotd50", "sa_rotd50"):
            out[name][k] = factor * ims[name]
        out["u_max"][k] = sol.u_max
        out["peak_angle"][k] = math.degrees(sol.peak_angle)
        models[k] = sol.facets
    return _analysis_dataset(study, idx, tab, out, models)


_ANALYSIS_META = {
    "orientation": ("index of the orientation (into fragility.planar.angles, or of the draw)", "1"),
    "angle": ("angle from the building's x axis to the recorded x component", "degree"),
    "stripe": ("index of the stripe (into im_level) the pair was scaled to", "1"),
    "friction_sample": ("index of the friction draw of this ground motion and stripe", "1"),
    "mu_k": ("kinetic friction coefficient of the contents (lognormal draw)", "1"),
    "scale_factor": ("factor applied to both recorded components", "1"),
    "pga_rotd50": ("RotD50 peak ground acceleration of the scaled pair (Boore 2010)", "m s-2"),
    "pgv_rotd50": ("RotD50 peak ground velocity of the scaled pair (exact between samples)", "m s-1"),
    "sa_rotd50": ("RotD50 pseudo-spectral acceleration of the scaled pair at sa_period, sa_damping", "m s-2"),
    "pfa": ("peak length of the absolute acceleration of the floor carrying the contents, in the plane "
            "(max over the history rows of the planar analysis)", "m s-2"),
    "pfv": ("peak length of the absolute velocity of the floor carrying the contents, in the plane "
            "(max over the history rows of the planar analysis)", "m s-1"),
    "pga_x": ("peak ground acceleration of the scaled pair along the building's x axis", "m s-2"),
    "pga_y": ("peak ground acceleration of the scaled pair along the building's y axis", "m s-2"),
    "u_max": ("peak Euclidean sliding displacement, both components at once (planar)", "m"),
    "u_max_x": ("peak sliding displacement under the component along the building's x axis alone (1-D)", "m"),
    "u_max_y": ("peak sliding displacement under the component along the building's y axis alone (1-D)", "m"),
    "peak_angle": ("direction of the planar peak slide in the building's axes", "degree"),
}


def _analysis_dataset(study, idx, tab, out, models) -> xr.Dataset:
    g = tab["ground_motion"][idx]
    ds = analysis_frame(idx, "floor, ground motion, orientation, stripe, friction sample")
    ds["ground_motion"] = ("analysis", np.array([study.motions[int(r)].name for r in g], dtype=object),
                           {"long_name": "ground motion name"})
    ds["record_suite"] = ("analysis", np.array([study.suites[int(study.suite_index[r])] for r in g], dtype=object),
                          {"long_name": "suite of the ground motion"})
    pulse = np.array([{True: 1, False: 0}.get(study.motions[int(r)].pulse, -1) for r in g], dtype=np.int8)
    ds["pulse"] = ("analysis", pulse, {"long_name": "velocity pulse of the ground motion (suite metadata)",
                                       "units": "1", "flag_values": np.array([-1, 0, 1], dtype=np.int8),
                                       "flag_meanings": "not_classified no_pulse pulse"})
    ds["contents_floor"] = ("analysis", np.array([str(study.floors[int(f)]) for f in tab["floor"][idx]], dtype=object),
                            {"long_name": "floor carrying the contents"})
    add_table_columns(ds, tab, idx, ("orientation", "stripe", "friction_sample"), ("angle", "mu_k"))
    return add_outputs(ds, out, _OUT, _ANALYSIS_META, models)


def solve_chunk(study: PlanarStudy, chunk: int, base: str) -> xr.Dataset:
    """Solve the analyses of one chunk on ``base`` (:func:`solve_analyses` of the chunk's indices)."""
    return solve_analyses(study, chunk_indices(study, chunk), base)


def solve_all(study: PlanarStudy, base: str) -> xr.Dataset:
    """Every analysis on ``base``, chunk by chunk (the merge job of a one-chunk study)."""
    return merge_chunks([solve_chunk(study, c, base) for c in range(n_chunks(study))])


# ----------------------------------------------------------------------------------------------
# the fits, the bootstrap and the comparisons
# ----------------------------------------------------------------------------------------------

def _outcomes(ds: xr.Dataset) -> dict:
    """Per motion: ``(rows, u)``, the analysis row of each outcome and the outcome [m]."""
    n = ds.sizes["analysis"]
    ux, uy = ds["u_max_x"].values, ds["u_max_y"].values
    rows = np.arange(n)
    return {"planar": (rows, ds["u_max"].values),
            "one_component": (np.concatenate([rows, rows]), np.concatenate([ux, uy])),
            "max_component": (rows, np.maximum(ux, uy))}


def _fit_status(exc: np.ndarray) -> int:
    return 1 if not exc.any() else (2 if exc.all() else 0)


def _fit_one(scaling: bool, levels, stripe, x, exc):
    """``(theta, beta, status)`` of one curve: by stripe counts (``scaling``) or per analysis."""
    status = _fit_status(exc)
    if status:
        return math.nan, math.nan, status
    try:
        if scaling:
            nj = np.bincount(stripe, minlength=levels.size).astype(float)
            zj = np.bincount(stripe, weights=exc.astype(float), minlength=levels.size)
            keep = nj > 0
            args = (levels[keep], zj[keep], nj[keep])
        else:
            args = (x, exc.astype(float), np.ones(x.size))
        fit = _fit.fit_lognormal(*args)
    except (ValueError, RuntimeError):   # separated outcomes, or no convergence
        return math.nan, math.nan, 3
    return fit.theta, fit.beta, 0


def _combinations(study, ds, outcomes, rows):
    """Every curve of the analyses ``rows[floor][group]``.

    Yields ``(index, scaling, pick, r, exc, im)``: the index into (floor, group, motion,
    limit_state, im), whether the IM is the scaling one, the outcomes picked (into ``outcomes``),
    their analysis rows, whether each exceeded the limit state, and the IM name.
    """
    n = ds.sizes["analysis"]
    for f in range(len(study.floors)):
        for gi in range(len(study.suites) + 1):
            sel = rows[f][gi]
            for m, motion in enumerate(MOTIONS):
                rows_m, u = outcomes[motion]
                pick = sel if motion != "one_component" else np.concatenate([sel, sel + n])
                r = rows_m[pick]
                for a, limit in enumerate(study.limit_states):
                    exc = u[pick] > limit
                    for b, im in enumerate(PLANAR_IMS):
                        yield (f, gi, m, a, b), im == study.im, pick, r, exc, im


def _shape(study) -> tuple:
    return len(study.floors), len(study.suites) + 1, len(MOTIONS), study.limit_states.size, len(PLANAR_IMS)


def _fit_all(study, ds, outcomes, rows) -> tuple:
    """theta, beta, status over (floor, group, motion, limit_state, im) for the analyses ``rows[floor][group]``."""
    shape = _shape(study)
    theta, beta = np.full(shape, np.nan), np.full(shape, np.nan)
    status = np.zeros(shape, dtype=np.int8)
    stripe = ds["stripe"].values
    ims = {k: ds[k].values for k in PLANAR_IMS}
    for i, scaling, _, r, exc, im in _combinations(study, ds, outcomes, rows):
        theta[i], beta[i], status[i] = _fit_one(scaling, study.levels, stripe[r], ims[im][r], exc)
    return theta, beta, status


def _boot_fits(study, ds, outcomes, members, rows, draws, ok) -> tuple:
    """Bootstrap theta and beta, shape ``(n_boot,)`` + the curves' shape, NaN where a resample fits no curve.

    ``rows``: :func:`_group_rows`; ``draws``: :func:`_boot_draws`.  Only the curves ``ok`` are fitted, all resamples of one curve
    at once (:func:`isoslide.studies.fragility.fit_weighted`, each analysis weighted by the times
    its ground motion is drawn), as :func:`_fit_one` fits each.
    """
    boot_t = np.full((study.n_boot,) + ok.shape, np.nan)
    boot_b = np.full_like(boot_t, np.nan)
    if not study.n_boot:
        return boot_t, boot_b
    counts = _fit.times_drawn([np.concatenate(d) for d in draws], len(study.motions))
    motion_of = _row_motions(members, study)
    stripe = ds["stripe"].values
    ims = {k: ds[k].values for k in PLANAR_IMS}
    weighted = None
    for i, scaling, pick, r, exc, im in _combinations(study, ds, outcomes, rows):
        if not ok[i]:
            continue
        if weighted != i[:3]:    # times each outcome is drawn, per resample (one_component: x rows, then y rows)
            gm = motion_of[i[0]][i[1]]
            w, weighted = counts[:, gm if pick.size == gm.size else np.concatenate([gm, gm])], i[:3]
        if scaling:
            onehot = (stripe[r][:, None] == np.arange(study.levels.size)).astype(float)
            nj, zj = w @ onehot, w @ (onehot * exc[:, None])   # integer sums: exact
            keep = nj > 0
            args = (study.levels, keep.astype(float), zj, nj,
                    lambda j, keep=keep, zj=zj, nj=nj: (study.levels[keep[j]], zj[j][keep[j]], nj[j][keep[j]]))
        else:
            args = (ims[im][r], w, exc.astype(float), np.ones(pick.size),
                    _resampled(ds, outcomes, members, draws, i, study))
        boot_t[(slice(None),) + i], boot_b[(slice(None),) + i], _, _ = _fit.fit_weighted(*args)
    return boot_t, boot_b


def _resampled(ds, outcomes, members, draws, index, study):
    """``expanded(j)`` of :func:`isoslide.studies.fragility.fit_weighted` for the per-analysis curve ``index``.

    The IM, outcomes and counts of resample ``j`` in the order drawn: the rows of each ground
    motion drawn, as often as it is drawn (one_component: then the same rows' y outcomes).
    """
    f, gi, m, a, b = index
    rows_m, u = outcomes[MOTIONS[m]]
    x, limit, n = ds[PLANAR_IMS[b]].values, study.limit_states[a], ds.sizes["analysis"]

    def expanded(j: int) -> tuple:
        gms = np.concatenate(draws[j]) if gi == 0 else draws[j][gi - 1]
        sel = np.concatenate([members[f][g] for g in gms])
        pick = sel if MOTIONS[m] != "one_component" else np.concatenate([sel, sel + n])
        return x[rows_m[pick]], (u[pick] > limit).astype(float), np.ones(pick.size)
    return expanded


def _members(study: PlanarStudy, ds: xr.Dataset) -> list:
    """``members[floor][ground motion]``: the analysis rows of that floor and ground motion."""
    fl = {str(name): i for i, name in enumerate(study.floors)}
    floor = np.array([fl[str(v)] for v in ds["contents_floor"].values])
    names = {gm.name: i for i, gm in enumerate(study.motions)}
    gm = np.array([names[str(v)] for v in ds["ground_motion"].values])
    return [[np.flatnonzero((floor == f) & (gm == g)) for g in range(len(study.motions))]
            for f in range(len(study.floors))]


def _group_motions(study: PlanarStudy) -> list:
    """The ground motions of each group: ``all`` (every suite), then each suite."""
    by_suite = [np.flatnonzero(study.suite_index == i) for i in range(len(study.suites))]
    return [np.concatenate(by_suite)] + by_suite


def _group_rows(members: list, study: PlanarStudy) -> list:
    """``rows[floor][group]``: the analysis rows of a floor and group, ground motion by ground motion."""
    return [[np.concatenate([members[f][g] for g in gms]) for gms in _group_motions(study)]
            for f in range(len(members))]


def _boot_draws(study: PlanarStudy) -> list:
    """``draws[i][s]``: the ground motions resample ``i`` draws from suite ``s``, in the order drawn.

    Suite by suite, as many ground motions as the suite has, with replacement, from
    ``default_rng([seed, BOOT_SEED_OFFSET])``.
    """
    rng = np.random.default_rng([study.seed, BOOT_SEED_OFFSET])
    by_suite = _group_motions(study)[1:]
    return [[idx[rng.integers(0, idx.size, size=idx.size)] for idx in by_suite] for _ in range(study.n_boot)]


def _row_motions(members: list, study: PlanarStudy) -> list:
    """``motion_of[floor][group]``: the ground motion of each row of :func:`_group_rows`."""
    return [[np.concatenate([np.full(members[f][g].size, g) for g in gms]) for gms in _group_motions(study)]
            for f in range(len(members))]


def _interval(values: np.ndarray, level: float) -> tuple:
    """Percentile bounds over the first axis, NaN ignored; NaN where no value is finite."""
    q = [(1.0 - level) / 2.0, (1.0 + level) / 2.0]
    if values.shape[0] == 0:     # no resamples (bootstrap.n_boot = 0): no bounds
        return np.full(values.shape[1:], np.nan), np.full(values.shape[1:], np.nan)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)   # all-NaN slices: no bounds
        lo, hi = np.nanquantile(values, q, axis=0)
    return lo, hi


def fit_curves(ds: xr.Dataset, study: PlanarStudy) -> xr.Dataset:
    """Fitted curves, their bootstrap intervals and the comparisons of the planar analyses.

    Parameters
    ----------
    ds : xarray.Dataset
        :func:`merge_chunks` of every chunk (or :func:`solve_all`).
    study : PlanarStudy

    Returns
    -------
    xarray.Dataset
        Over ``floor`` x ``group`` (``all`` and each suite) x ``motion`` x ``limit_state`` x
        ``im``: ``theta``, ``beta``, their ``_low``/``_high`` bounds, ``fit_status``,
        ``n_exceeded``, ``n_boot_failed``; ``theta_ratio`` and ``beta_change`` (planar against
        each of ``comparison``: ``one_component``, ``max_component``) with bounds;
        ``suite_theta_ratio`` (each suite against ``reference_suite``) and
        ``floor_theta_ratio`` (each floor against the first) with bounds.
    """
    members = _members(study, ds)
    outcomes = _outcomes(ds)
    rows = _group_rows(members, study)
    theta, beta, status = _fit_all(study, ds, outcomes, rows)
    groups = ("all",) + study.suites
    n_exc = np.zeros(theta.shape[:4], dtype=np.int32)
    n_ana = np.zeros(theta.shape[:3], dtype=np.int32)
    for (f, gi, m, a, _b), _, pick, _, exc, _ in _combinations(study, ds, outcomes, rows):
        n_ana[f, gi, m] = pick.size
        n_exc[f, gi, m, a] = int(exc.sum())
    ok = status == 0
    boot_t, boot_b = _boot_fits(study, ds, outcomes, members, rows, _boot_draws(study), ok)
    res = {"theta": theta, "beta": beta}
    res["theta_low"], res["theta_high"] = _interval(boot_t, study.level)
    res["beta_low"], res["beta_high"] = _interval(boot_b, study.level)
    failed = np.where(ok, np.isnan(boot_t).sum(axis=0), 0).astype(np.int32) if study.n_boot else \
        np.zeros(theta.shape, dtype=np.int32)

    out = xr.Dataset(coords={
        "floor": ("floor", np.array([str(f) for f in study.floors], dtype=object),
                  {"long_name": "floor carrying the contents"}),
        "group": ("group", np.array(groups, dtype=object),
                  {"long_name": "ground motions fitted: all of them, or one suite"}),
        "motion": ("motion", np.array(MOTIONS, dtype=object), {
            "long_name": "outcome: planar (both components at once), one_component (x and y alone, pooled), "
                         "max_component (the larger of x and y alone)"}),
        "limit_state": ("limit_state", study.limit_states,
                        {"long_name": "sliding displacement limit (u > limit_state exceeds it)", "units": "m"}),
        "im": ("im", np.array(PLANAR_IMS, dtype=object), {"long_name": "intensity measure of the scaled pair"}),
        "im_units": ("im", np.array([IM_UNITS[k] for k in PLANAR_IMS], dtype=object),
                     {"long_name": "units of the intensity measure"}),
        "im_level": ("im_level", study.levels, {"long_name": f"stripe level of the scaling intensity measure "
                                                             f"({study.im})", "units": IM_UNITS[study.im]}),
        "suite": ("suite", np.array(study.suites, dtype=object), {"long_name": "suite of ground motions"}),
        "comparison": ("comparison", np.array(MOTIONS[1:], dtype=object),
                       {"long_name": "the one-component outcome the planar one is compared with"}),
    })
    dims = ("floor", "group", "motion", "limit_state", "im")
    u_txt = "m s-2 (pga_rotd50, sa_rotd50, pfa) or m s-1 (pgv_rotd50, pfv): see im_units"
    pct = f"{study.level:.0%}"
    add_curves(out, dims, res, status, failed, u="u", u_txt=u_txt, pct=pct, resampled="ground motions")
    out["n_exceeded"] = (dims[:4], n_exc, {"long_name": "outcomes with u > limit_state", "units": "1"})
    out["n_outcomes"] = (dims[:3], n_ana, {"long_name": "outcomes fitted (one_component: two per analysis)",
                                           "units": "1"})

    def ratio(name, long_name, point, boot, dims_, units="1"):
        lo, hi = _interval(boot, study.level)
        out[name] = (dims_, point, {"long_name": long_name, "units": units})
        out[f"{name}_low"] = (dims_, lo, {"long_name": f"lower bound of the {pct} bootstrap interval: " + long_name,
                                          "units": units})
        out[f"{name}_high"] = (dims_, hi, {"long_name": f"upper bound of the {pct} bootstrap interval: " + long_name,
                                           "units": units})

    with np.errstate(divide="ignore", invalid="ignore"):
        cdims = ("floor", "group", "comparison", "limit_state", "im")
        ratio("theta_ratio", "planar median capacity over the compared one (below 1: shaking in the plane slides "
              "the contents at a lower intensity)", theta[:, :, :1] / theta[:, :, 1:],
              boot_t[:, :, :, :1] / boot_t[:, :, :, 1:], cdims)
        ratio("beta_change", "planar dispersion minus the compared one", beta[:, :, :1] - beta[:, :, 1:],
              boot_b[:, :, :, :1] - boot_b[:, :, :, 1:], cdims)
        ref = study.suites.index("fema-p695-far-field") if "fema-p695-far-field" in study.suites else 0
        sdims = ("floor", "motion", "suite", "limit_state", "im")
        ratio("suite_theta_ratio", "median capacity of the suite over that of the reference suite (below 1: the "
              "suite slides the contents at a lower intensity)",
              np.moveaxis(theta[:, 1:] / theta[:, 1 + ref:2 + ref], 1, 2),
              np.moveaxis(boot_t[:, :, 1:] / boot_t[:, :, 1 + ref:2 + ref], 2, 3), sdims)
        ratio("floor_theta_ratio", "median capacity on the floor over that on the first floor",
              theta / theta[:1], boot_t / boot_t[:, :1], dims)
    out.attrs["reference_suite"] = study.suites[ref]
    return out


def planar_dataset(analyses: xr.Dataset, study: PlanarStudy, settings: dict, base: str) -> xr.Dataset:
    """The dataset of the planar analyses: the analyses, the curves, the comparisons, CF attributes.

    The arguments are those of :func:`isoslide.studies.fragility_study.fragility_dataset`, of the
    planar analyses: a :class:`PlanarStudy` and :func:`planar_settings` (stored as ``isoslide_config``).
    """
    dataset_name(base)
    ds = analyses.copy()
    for k in ("ground_motion", "record_suite", "contents_floor"):
        attrs = ds[k].attrs
        ds[k] = ds[k].astype(str)
        ds[k].attrs.update(attrs)
    fits = fit_curves(analyses, study)
    ref = fits.attrs.pop("reference_suite")
    ds = xr.merge([ds, fits], combine_attrs="override")
    licences = sorted({r.licence for gm in study.motions for r in (gm.x, gm.y) if r.licence})
    ds.attrs = global_attrs(
        title=f"isoslide fragility of sliding contents in the plane ({base_label(base)})",
        history=(f"isoslide.studies.fragility_planar: {len(study.floors)} floor(s) x {len(study.motions)} ground "
                 f"motions ({', '.join(study.suites)}) x {study.angles.shape[1]} orientations"
                 f"{' drawn per analysis' if study.sampled_angles else ''} x {study.levels.size} stripes of "
                 f"{study.im} x {study.angles.shape[3]} friction draws = {study.size} analyses, each solved in the "
                 f"plane and with each component alone (isoslide.solve), fitted by maximum likelihood "
                 f"(isoslide.studies.fragility), {study.n_boot} bootstrap resamples of the ground motions per suite; "
                 f"no timestamps are stored"),
        config=settings,
        references_fragility=REFERENCE_FRAGILITY,
        references_rotd=("Boore, D. M. (2010): Orientation-independent, nongeometric-mean measures of seismic "
                         "intensity from two horizontal components of motion, BSSA 100(4), 1830-1835"),
        base=base, scaling_im=study.im, suites=", ".join(study.suites), reference_suite=ref,
        floors=", ".join(map(str, study.floors)), sampled_angles=int(study.sampled_angles),
        **{k: v for k, v in design_attrs(study, base).items() if k not in _NOT_STORED},
        sa_period=study.sa_period, sa_damping=study.sa_damping, **bootstrap_attrs(study),
        floor_ims=("pfa, pfv: the peak lengths of the floor's absolute acceleration and velocity vectors over the "
                   "history rows of the planar analysis (every record sample, step and transition; "
                   "isoslide.studies.intensity.planar_floor_peaks)"),
        sources="; ".join(licences),
    )
    return ds
