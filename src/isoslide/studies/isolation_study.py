"""Sliding contents in buildings as engineers isolate them: bearings, flexible frames, design.

Three studies beyond the paper's Fig. 1-b model (configuration section ``isolation``):

* **master curves of real bearings** -- ``Pi1(Pi2)`` for a friction pendulum (sliding bearing,
  ``Pi10 = 0``, swept over ``Pi3`` and its strength ``Pi9``) and a lead-rubber bearing (bilinear,
  ``Pi10 > 0``).  They are ordinary studies of :mod:`isoslide.studies.sweep` (the groups ``pi9 .. pi13``
  and the contents' ``floor`` are study keys like the paper's), solved and merged by the same
  rules into ``results/datasets/iso_fp.nc``, ``iso_lrb.nc``; :func:`study_specs` builds them.
* **superstructure flexibility and floor** -- ``Pi1(Pi2)`` over ``Pi12 = T_s/T_p`` with the
  contents on the base slab (``iso_flex_base``) and on the roof (``iso_flex_roof``); ``Pi12 = 0``
  is the paper's rigid superstructure.  :func:`rigid_error` measures where that reduction holds:
  the error of the rigid answer over ``Pi12`` and ``Pi2`` (``results/datasets/isolation_rigid.nc``).
* **which isolation protects contents best** -- a linear, a bilinear (lead-rubber) and a
  friction-pendulum isolator designed to the same effective period and damping at the design
  displacement (:mod:`isoslide.studies.design`), under the same pulses and real records, over the
  contents' friction coefficient: :func:`design_comparison` (``results/datasets/isolation_design.nc``).
* **what the bearing does to the contents, from service-level shaking to beyond the design** -- the
  lead-rubber bearing and the friction pendulum of that design, the same pendulum with friction
  rising with speed (Constantinou, Mokha and Reinhorn 1990) and a triple friction pendulum of the
  same effective period and damping at the design displacement (Fenz and Constantinou 2008; its
  regime I..V reached and its displacement capacity recorded), under one pulse scaled over its
  amplitude ``a_p``, with Coulomb contents of a few ``mu_k`` on the slab of a rigid superstructure
  and on the roof of a flexible one: :func:`bearing_study` (``results/datasets/isolation_bearings.nc``),
  its findings :func:`bearing_findings`.
"""

from __future__ import annotations

import copy
import math

import numpy as np
import xarray as xr

from . import design as _design
from .. import solver
from ..config import ConfigError
from ..datasets import encode_facets, global_attrs, open_dataset, pi_attrs
from .intensity import floor_peaks, peak_abs
from .record_study import resolve_record
from .solving import batch_solver
from ..records import G
from ..pulses import get_pulse
from ..scene import FLOORS, Scene, friction_pendulum
from ..store.history_io import history_table
from .sweep import normalise_study

__all__ = ["BEARING_ISOLATORS", "BUILDINGS", "FAMILIES", "NOMINAL_MASS", "REGIMES", "STAGE_FLAGS", "TRIPLE",
           "bearing_findings", "bearing_isolators", "bearing_onsets", "bearing_settings", "bearing_study",
           "bearing_summary", "bearing_triple", "bearings_dataset", "check_bearings", "dataset_names", "findings",
           "sliding_end", "design_comparison", "design_dataset", "design_excitations", "isolation_settings",
           "rigid_dataset", "rigid_error", "rigid_summary", "speed_effect", "study_entries", "study_names", "study_specs",
           "triple_against", "triple_regimes"]

FAMILIES = {"iso_fp": "friction_pendulum", "iso_lrb": "lead_rubber",
            "iso_flex_base": "flexible", "iso_flex_roof": "flexible"}
"""Study name -> the ``isolation`` subsection that defines it."""

NOMINAL_MASS = 1.0e6
"""Isolated mass [kg] of the designed isolators; every result is the same for any mass."""


def isolation_settings(config: dict) -> dict:
    """The sections of a complete configuration the isolation studies read (copies).

    ``isolation``, plus ``defaults`` (the contents' Pi5 ... Pi8) and ``solver``.
    """
    return {k: copy.deepcopy(config[k]) for k in ("isolation", "defaults", "solver")}


def study_names() -> list:
    """Names of the isolation studies (their dataset stems), in order."""
    return list(FAMILIES)


def dataset_names() -> list:
    """Every dataset of the isolation studies, in order.

    The studies' (:func:`study_names`), the rigid reduction's, the design comparison's and the
    bearing study's.
    """
    return study_names() + ["isolation_rigid", "isolation_design", "isolation_bearings"]


def study_entries(section: dict) -> dict:
    """The study entries (``studies:`` format of :func:`isoslide.studies.sweep.normalise_study`).

    Parameters
    ----------
    section : dict
        The ``isolation`` section of a complete configuration.
    """
    fp, lrb, flex = section["friction_pendulum"], section["lead_rubber"], section["flexible"]
    out = {
        "iso_fp": {
            "title": "Friction pendulum (sliding bearing, Pi10 = 0): strength Pi9 = mu_b g / a_p at several Pi3",
            "dims": {"pi3": list(fp["pi3"]), "pi9": list(fp["pi9"])},
            "fixed": {"pi4": fp["pi4"], "pi10": 0.0},
            "pi2": dict(fp["pi2"]),
        },
        "iso_lrb": {
            "title": "Lead-rubber bearing (bilinear): strength Pi9 = Q_d / (M_b a_p) at several Pi3",
            "dims": {"pi3": list(lrb["pi3"]), "pi9": list(lrb["pi9"])},
            "fixed": {"pi4": lrb["pi4"], "pi10": lrb["pi10"]},
            "pi2": dict(lrb["pi2"]),
        },
    }
    for floor in FLOORS:
        out[f"iso_flex_{floor}"] = {
            "title": f"Flexible superstructure, contents on the {floor}: Pi12 = T_s/T_p (0 = rigid, the paper)",
            "dims": {"pi3": list(flex["pi3"]), "pi12": list(flex["pi12"])},
            "fixed": {"pi4": flex["pi4"], "pi11": flex["pi11"], "pi13": flex["pi13"]},
            "floor": floor,
            "pi2": dict(flex["pi2"]),
        }
    return out


def study_specs(config: dict) -> dict:
    """``{name: normalised study specification}`` of the isolation studies of a complete configuration.

    Checked like the paper's studies (:func:`isoslide.studies.sweep.normalise_study`); a bad value raises
    :class:`isoslide.config.ConfigError` naming ``studies.<name>.<key>``, and the flexible study
    needs ``Pi12 = 0`` among its values (the rigid reference of :func:`rigid_error`).
    """
    section = config["isolation"]
    if 0.0 not in [float(v) for v in section["flexible"]["pi12"]]:
        raise ConfigError(f"isolation.flexible.pi12 = {section['flexible']['pi12']!r} needs 0.0 (the rigid "
                          f"superstructure the other values are compared with)")
    return {name: normalise_study(name, entry, config) for name, entry in study_entries(section).items()}


# ----------------------------------------------------------------------------------------------
# where the rigid-superstructure reduction holds
# ----------------------------------------------------------------------------------------------

def rigid_error(datasets: dict, tolerance: float) -> xr.Dataset:
    """Error of the rigid-superstructure answer (``Pi12 = 0``, the paper's Fig. 1-b) over Pi12 and Pi2.

    Parameters
    ----------
    datasets : dict of str -> xarray.Dataset
        The flexible studies by floor (``{"base": iso_flex_base, "roof": iso_flex_roof}``), each
        with dimensions ``pi3, pi12, pi2`` and ``Pi12 = 0`` among its values.
    tolerance : float
        Band of "the reduction holds": ``|error| <= tolerance``.

    Returns
    -------
    xarray.Dataset
        Dimensions ``floor, pi3, pi12, pi2``: ``pi1`` (flexible answer), ``pi1_rigid`` (the
        ``Pi12 = 0`` answer), ``rel_error = (pi1_rigid - pi1) / pi1`` (positive: the rigid model
        overestimates; 0 where neither slides, +inf where only the rigid model slides),
        ``peak_error = (pi1_rigid - pi1) / max_Pi2 pi1`` (relative to the flexible curve's peak;
        robust where Pi1 tends to 0 at the end of sliding), ``holds`` (``|rel_error| <= tolerance``);
        per ``floor, pi3, pi12``: ``max_peak_error``, ``peak_ratio`` (peak of the flexible curve over
        that of the rigid one) and ``share_holds`` (share of the Pi2 points where either model gives
        sliding at which ``holds``); per ``floor, pi3``: ``pi12_limit``, the largest Pi12 up to which
        every ``|max_peak_error| <= tolerance``.
    """
    tol = float(tolerance)
    parts = []
    for floor in FLOORS:
        if floor not in datasets:
            raise ValueError(f"datasets = {sorted(datasets)!r} lacks floor {floor!r}; allowed keys: {list(FLOORS)}")
        ds = datasets[floor]
        if 0.0 not in ds["pi12"].values:
            raise ValueError(f"pi12 = {ds['pi12'].values.tolist()!r} of floor {floor!r} lacks 0 (the rigid reference)")
        pi1 = ds["pi1"].transpose("pi3", "pi12", "pi2")
        parts.append(pi1.expand_dims(floor=[floor]))
    pi1 = xr.concat(parts, dim="floor", join="exact")
    rigid = pi1.sel(pi12=0.0)
    diff = rigid - pi1
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = xr.where(pi1 > 0, diff / pi1.where(pi1 > 0, 1.0), xr.where(rigid > 0, np.inf, 0.0))
        peak = pi1.max("pi2")
        peak_rigid = rigid.max("pi2")
        peak_err = xr.where(peak > 0, diff / peak.where(peak > 0, 1.0), xr.where(rigid > 0, np.inf, 0.0))
        peak_ratio = xr.where(peak_rigid > 0, peak / peak_rigid.where(peak_rigid > 0, 1.0), np.nan)
    holds = np.abs(rel) <= tol
    slides = (pi1 > 0) | (rigid > 0)
    n_slide = slides.sum("pi2")
    share = xr.where(n_slide > 0, (holds & slides).sum("pi2") / n_slide.where(n_slide > 0, 1), np.nan)
    max_peak = np.abs(peak_err).max("pi2")
    ok = (max_peak <= tol).transpose("floor", "pi3", "pi12").values
    pi12 = pi1["pi12"].values
    order = np.argsort(pi12)
    limit = np.full(ok.shape[:2], np.nan)
    for i in range(ok.shape[0]):
        for j in range(ok.shape[1]):
            good = ok[i, j, order]
            k = len(good) if good.all() else int(np.argmin(good))
            limit[i, j] = pi12[order][k - 1] if k > 0 else np.nan

    one = {"units": "1"}
    out = xr.Dataset(coords={
        "floor": ("floor", np.array(FLOORS, dtype=object), {"long_name": "floor carrying the contents"}),
        "pi3": ("pi3", pi1["pi3"].values, pi_attrs("pi3")),
        "pi12": ("pi12", pi12, pi_attrs("pi12")),
        "pi2": ("pi2", pi1["pi2"].values, pi_attrs("pi2")),
    })
    dims = ("floor", "pi3", "pi12", "pi2")
    out["pi1"] = (dims, pi1.transpose(*dims).values, {**pi_attrs("pi1"), "comment": "flexible superstructure"})
    out["pi1_rigid"] = (("floor", "pi3", "pi2"), rigid.transpose("floor", "pi3", "pi2").values,
                        {"long_name": "Pi1 of the rigid superstructure (Pi12 = 0, the paper's Fig. 1-b)", **one})
    out["rel_error"] = (dims, rel.transpose(*dims).values.astype(float),
                        {"long_name": "relative error of the rigid answer (pi1_rigid - pi1) / pi1", **one,
                         "comment": "0 where neither slides; +inf where only the rigid model slides"})
    out["peak_error"] = (dims, peak_err.transpose(*dims).values.astype(float),
                         {"long_name": "error of the rigid answer relative to the flexible curve's peak, "
                                       "(pi1_rigid - pi1) / max over Pi2 of pi1", **one})
    out["holds"] = (dims, holds.transpose(*dims).values.astype(np.int8),
                    {"long_name": "rigid reduction holds: |rel_error| <= tolerance", **one,
                     "flag_values": np.array([0, 1], np.int8), "flag_meanings": "fails holds"})
    d3 = ("floor", "pi3", "pi12")
    out["max_peak_error"] = (d3, max_peak.transpose(*d3).values.astype(float),
                             {"long_name": "largest |peak_error| over Pi2", **one})
    out["peak_ratio"] = (d3, peak_ratio.transpose(*d3).values.astype(float),
                         {"long_name": "peak Pi1 over Pi2 of the flexible building / that of the rigid one", **one})
    out["share_holds"] = (d3, share.transpose(*d3).values.astype(float),
                          {"long_name": "share of the sliding Pi2 points where the rigid reduction holds", **one})
    out["pi12_limit"] = (("floor", "pi3"), limit,
                         {"long_name": "largest Pi12 up to which max_peak_error <= tolerance at every Pi12", **one})
    first = datasets[FLOORS[0]]
    for name in ("pi4", "pi5", "pi6", "pi7", "pi8", "pi11", "pi13"):
        if name in first.coords and first[name].ndim == 0:
            out.coords[name] = ((), float(first[name]), pi_attrs(name))
    out.attrs.update({"tolerance": tol, "pulse": str(first.attrs.get("pulse", ""))})
    return out


def rigid_summary(ds: xr.Dataset) -> list:
    """The reduction's verdict per floor and Pi3 of a :func:`rigid_error` dataset.

    Returns
    -------
    list of tuple
        ``(floor, pi3, pi12_limit, worst pi12, its max_peak_error, its peak_ratio)``, the worst Pi12
        being the one of the largest error.
    """
    rows = []
    for floor in ds["floor"].values:
        for pi3 in ds["pi3"].values:
            sub = ds.sel(floor=floor, pi3=pi3)
            err = sub["max_peak_error"].values
            k = int(np.nanargmax(np.where(np.isfinite(err), err, -1.0)))
            rows.append((str(floor), float(pi3), float(sub["pi12_limit"]), float(sub["pi12"][k]), float(err[k]),
                         float(sub["peak_ratio"][k])))
    return rows


def rigid_dataset(paths_or_datasets: dict, settings: dict) -> xr.Dataset:
    """:func:`rigid_error` of the flexible studies with CF global attributes (rule isolation_rigid).

    Parameters
    ----------
    paths_or_datasets : dict of str -> path or xarray.Dataset
        ``{"base": ..., "roof": ...}``.
    settings : dict
        :func:`isolation_settings` of a complete configuration.
    """
    data = {k: open_dataset(v) if not isinstance(v, xr.Dataset) else v for k, v in paths_or_datasets.items()}
    tol = settings["isolation"]["flexible"]["tolerance"]
    ds = rigid_error(data, tol)
    extra = dict(ds.attrs)
    ds.attrs = global_attrs(
        title="isoslide: where the rigid-superstructure reduction (the paper's Fig. 1-b) holds",
        history=("isoslide.studies.isolation_study.rigid_error of the studies iso_flex_base and iso_flex_roof "
                 f"({ds.sizes['pi3']} Pi3 x {ds.sizes['pi12']} Pi12 x {ds.sizes['pi2']} Pi2 per floor); "
                 "no timestamps are stored"),
        config={"flexible": settings["isolation"]["flexible"]}, **extra)
    return ds


# ----------------------------------------------------------------------------------------------
# which isolation protects contents best
# ----------------------------------------------------------------------------------------------

def design_excitations(section: dict) -> list:
    """The excitations of the design comparison: ``(label, kind, pulse, a_p [m/s^2], T_p [s])``.

    Each analytical pulse of ``section["pulses"]`` at amplitude ``a_p_g`` g and each period of
    ``T_p``; then each record of ``section["records"]`` as recorded, with the ``a_p`` and ``T_p`` of
    its fitted Ricker wavelet as scales (:func:`isoslide.studies.record_study.resolve_record`).
    """
    out = []
    a_p = float(section["a_p_g"]) * G
    for shape in section["pulses"]:
        for T_p in section["T_p"]:
            out.append((f"{shape} T_p={float(T_p):g}s", "pulse", shape, a_p, float(T_p)))
    for name in section["records"]:
        rec = resolve_record(name)
        fit = rec.fit("ricker")
        out.append((rec.name, "record", rec, float(fit.a_p), float(fit.T_p)))
    return out


def _contents(defaults: dict, mu_k: float, a_p: float, T_p: float) -> dict:
    """The contents' physical parameters from the configured Pi5 ... Pi8 at ``mu_k``, ``a_p``, ``T_p``."""
    return {"m_ec": float(defaults["pi8"]) * NOMINAL_MASS, "mu_k": mu_k, "mu_s": mu_k / float(defaults["pi5"]),
            "beta": float(defaults["pi6"]) / (a_p * T_p), "gamma": float(defaults["pi7"]) / (G * T_p)}


def design_comparison(settings: dict, solve_many=None) -> xr.Dataset:
    """Peak sliding of the contents under linear, bilinear and friction-pendulum isolation.

    The three isolators of :func:`isoslide.studies.design.design` share the effective period ``T_eff``
    and damping ``beta_eff`` at the design displacement ``D`` (the code linearisation); each
    carries the same contents (friction ``mu_k`` swept, Pi5 ... Pi8 from ``defaults``) on the
    same floor of the same building under the same excitations (:func:`design_excitations`).

    Parameters
    ----------
    settings : dict
        :func:`isolation_settings` of a complete configuration.
    solve_many : callable, optional
        The batch solver (:mod:`isoslide.studies.solving`); of its answers the comparison reads
        ``pi1`` and ``settled``.

    Returns
    -------
    xarray.Dataset
        Dimensions ``system, excitation, mu_k``: ``u_max`` [m], ``pi1``, ``pi2``, ``settled``;
        per ``system, excitation``: ``bearing_disp`` (peak isolator displacement [m], against
        the design ``D``) and ``pfa`` (peak absolute acceleration of the contents' floor [m/s^2],
        with the contents stuck: ``mu_s g`` above it means no sliding); per ``system``: the
        isolator (``T_b``, ``xi_b``, ``Q_over_W``, ``D_y``, ``R``) and its ``T_eff``, ``beta_eff``
        evaluated back at ``D``; per ``excitation``: ``kind``, ``a_p``, ``T_p``; ``best``, the
        system of the smallest mean ``u_max`` over ``mu_k`` (per excitation, ``""`` if none slides).
    """
    solve_many = batch_solver(solve_many)
    sec = settings["isolation"]["design"]
    defaults = settings["defaults"]
    rtol = settings["solver"]["rtol"]
    M = NOMINAL_MASS
    D = float(sec["D"])
    systems = _design.design(M, float(sec["T_eff"]), float(sec["beta_eff"]), D, float(sec["D_y"]))
    excitations = design_excitations(sec)
    ax = sec["mu_k"]
    mu = np.linspace(float(ax["start"]), float(ax["stop"]), int(ax["num"]))
    floor = sec["floor"]
    building = {"m_st": float(sec["pi11"]) * M if float(sec["pi12"]) > 0 else 0.0, "xi_s": float(sec["pi13"])}
    ns, ne, nm = len(systems), len(excitations), mu.size
    scenes, probes = [], []
    for iso in systems.values():
        for _label, _kind, pulse, a_p, T_p in excitations:
            base = dict(a_p=a_p, T_p=T_p, pulse=pulse, floor=floor, T_s=float(sec["pi12"]) * T_p,
                        **building, **iso.scene_parameters())
            for m in mu:
                scenes.append(Scene.from_physical(**base, **_contents(defaults, float(m), a_p, T_p)))
            # the bearing and the floor barely feel the contents (Pi8): one history at the largest mu_k
            probes.append(Scene.from_physical(**base, **_contents(defaults, float(mu[-1]), a_p, T_p)))
    batch = solve_many(scenes, rtol=rtol)
    pi1 = np.asarray(batch.pi1, dtype=float).reshape(ns, ne, nm)
    settled = np.asarray(batch.settled, dtype=bool).reshape(ns, ne, nm)
    length = np.array([[a_p * T_p**2 for *_, a_p, T_p in excitations]] * ns)[..., None]
    u_max = pi1 * length
    bearing = np.zeros((ns, ne))
    pfa = np.zeros((ns, ne))
    for k, scene in enumerate(probes):
        sol = solver.solve(scene, rtol=rtol, history=True)
        i, j = divmod(k, ne)
        bearing[i, j] = float(np.max(np.abs(sol.history.x))) * scene.scale.length
        pfa[i, j] = floor_peaks(sol, scene)[0]
    names = list(systems)
    mean_u = u_max.mean(axis=2)
    best = np.array([names[int(np.argmin(mean_u[:, j]))] if np.any(mean_u[:, j] > 0) else ""
                     for j in range(ne)], dtype=object)

    one = {"units": "1"}
    ds = xr.Dataset(coords={
        "system": ("system", np.array(names, dtype=object), {"long_name": "isolation system"}),
        "excitation": ("excitation", np.array([e[0] for e in excitations], dtype=object),
                       {"long_name": "ground motion: analytical pulse (shape, T_p) or real record as recorded"}),
        "mu_k": ("mu_k", mu, {"long_name": "kinetic friction coefficient of the contents", **one}),
    })
    d3 = ("system", "excitation", "mu_k")
    ds["u_max"] = (d3, u_max, {"long_name": "peak sliding displacement of the contents", "units": "m"})
    ds["pi1"] = (d3, pi1, pi_attrs("pi1"))
    ds["pi2"] = (("excitation", "mu_k"), mu[None, :] * G / np.array([e[3] for e in excitations])[:, None],
                 pi_attrs("pi2"))
    ds["settled"] = (d3, settled.astype(np.int8), {"long_name": "response settled", **one,
                                                    "flag_values": np.array([0, 1], np.int8),
                                                    "flag_meanings": "not_settled settled"})
    d2 = ("system", "excitation")
    ds["bearing_disp"] = (d2, bearing, {"long_name": "peak isolator displacement (contents at the largest mu_k)",
                                        "units": "m"})
    ds["pfa"] = (d2, pfa, {"long_name": "peak absolute acceleration of the contents' floor "
                                        "(contents at the largest mu_k)", "units": "m s-2"})
    ds["best"] = ("excitation", best, {"long_name": "system with the smallest mean u_max over mu_k "
                                                    "(empty: no sliding under any system)"})
    eff = [iso.effective(D) for iso in systems.values()]
    per_sys = {
        "T_b": ([iso.T_b for iso in systems.values()], "period of the (post-yield) stiffness 2 pi sqrt(M_b/k_d)", "s"),
        "xi_b": ([iso.xi_b for iso in systems.values()], "viscous damping ratio of the isolator", "1"),
        "Q_over_W": ([iso.mu(G) for iso in systems.values()], "characteristic strength over weight Q/W "
                                                                  "(a friction pendulum's mu)", "1"),
        "D_y": ([iso.D_y for iso in systems.values()], "yield displacement", "m"),
        "R": ([iso.radius(G) for iso in systems.values()], "radius of the pendulum of the same k_d, M_b g/k_d", "m"),
        "T_eff": ([_design.effective_period(M, K) for K, _ in eff], "effective period at D (code linearisation)", "s"),
        "beta_eff": ([b for _, b in eff], "effective damping at D (code linearisation)", "1"),
    }
    for k, (v, ln, u) in per_sys.items():
        ds[k] = ("system", np.asarray(v, dtype=float), {"long_name": ln, "units": u})
    ds["kind"] = ("excitation", np.array([e[1] for e in excitations], dtype=object), {"long_name": "pulse or record"})
    ds["a_p"] = ("excitation", np.array([e[3] for e in excitations]),
                 {"long_name": "pulse amplitude a_p (records: of the fitted Ricker wavelet)", "units": "m s-2"})
    ds["T_p"] = ("excitation", np.array([e[4] for e in excitations]),
                 {"long_name": "pulse period T_p (records: of the fitted Ricker wavelet)", "units": "s"})
    ds.attrs.update({"D": D, "T_eff_target": float(sec["T_eff"]), "beta_eff_target": float(sec["beta_eff"]),
                     "D_y_bilinear": float(sec["D_y"]), "floor": floor, "M_b": M,
                     "rtol": "default" if rtol is None else float(rtol)})
    return ds


def design_dataset(settings: dict) -> xr.Dataset:
    """:func:`design_comparison` with CF global attributes (rule isolation_design)."""
    ds = design_comparison(settings)
    extra = dict(ds.attrs)
    ds.attrs = global_attrs(
        title="isoslide: contents under linear, bilinear and friction-pendulum isolation of equal "
              "effective period and damping",
        history=(f"isoslide.studies.isolation_study.design_comparison: {ds.sizes['system']} systems x "
                 f"{ds.sizes['excitation']} excitations x {ds.sizes['mu_k']} mu_k, isolators by "
                 "isoslide.studies.design (ASCE 7 / AASHTO linearisation); no timestamps are stored"),
        config={"design": settings["isolation"]["design"], "defaults": settings["defaults"],
                "solver": settings["solver"]}, **extra)
    return ds


# ----------------------------------------------------------------------------------------------
# the report's findings, with their numbers
# ----------------------------------------------------------------------------------------------

def sliding_end(pi1: np.ndarray, pi2: np.ndarray) -> float:
    """Largest Pi2 of a master curve at which the contents still slide (NaN if they never do)."""
    pi1 = np.asarray(pi1, dtype=float)
    k = np.flatnonzero(pi1 > 0)
    return float(np.asarray(pi2)[k[-1]]) if k.size else math.nan


def bearing_summary(ds: xr.Dataset) -> list:
    """The master curves of a bearing study (``iso_fp``, ``iso_lrb``) in numbers.

    Returns
    -------
    list of tuple
        Per Pi3 and Pi9: ``(pi3, pi9, peak Pi1, Pi2 at the peak, last sliding Pi2)``.
    """
    rows = []
    for pi3 in ds["pi3"].values:
        for pi9 in ds["pi9"].values:
            curve = ds["pi1"].sel(pi3=pi3, pi9=pi9).values
            k = int(np.argmax(curve))
            rows.append((float(pi3), float(pi9), float(curve[k]), float(ds["pi2"].values[k]),
                         sliding_end(curve, ds["pi2"].values)))
    return rows


def _bearing_text(name: str, ds: xr.Dataset) -> str:
    rows = bearing_summary(ds)
    pi9 = ds["pi9"].values
    lo, hi = float(pi9.min()), float(pi9.max())
    top = float(ds["pi2"].max())

    def end(x):
        return f"beyond {top:g} (the axis end)" if x >= top else f"{x:.3g}"

    parts = []
    for pi3 in ds["pi3"].values:
        r = {row[1]: row for row in rows if row[0] == float(pi3)}
        a, b = r[lo], r[hi]
        parts.append(f"at Π₃ = {float(pi3):g} the peak Π₁ goes from {a[2]:.3g} (Π₉ = {lo:g}) to {b[2]:.3g} "
                     f"(Π₉ = {hi:g}), {b[2] / a[2]:.2f}×, and sliding ends at Π₂ = {end(a[4])} and {end(b[4])}"
                     if a[2] > 0 else f"at Π₃ = {float(pi3):g} no sliding at Π₉ = {lo:g}")
    return f"{name}: " + "; ".join(parts) + "."


def findings(fp: xr.Dataset, lrb: xr.Dataset, rigid: xr.Dataset, design: xr.Dataset) -> list:
    """The report's findings, each ``(title, text with its numbers)``.

    Parameters
    ----------
    fp, lrb : xarray.Dataset
        The bearing studies ``iso_fp`` and ``iso_lrb``.
    rigid : xarray.Dataset
        :func:`rigid_error` (``isolation_rigid.nc``).
    design : xarray.Dataset
        :func:`design_comparison` (``isolation_design.nc``).
    """
    out = []
    out.append(("A stronger bearing lowers the peak of the master curve but can lengthen sliding",
                _bearing_text("Friction pendulum", fp) + " " + _bearing_text("Lead-rubber bearing", lrb)))

    tol = float(rigid.attrs["tolerance"])
    lines = []
    for floor in rigid["floor"].values:
        for pi3 in rigid["pi3"].values:
            sub = rigid.sel(floor=floor, pi3=pi3)
            ratio = sub["peak_ratio"].values
            pi12 = sub["pi12"].values
            k_hi, k_lo = int(np.nanargmax(ratio)), int(np.nanargmin(ratio))
            lines.append(f"contents on the {floor}, Π₃ = {float(pi3):g}: the peak Π₁ of the flexible building is "
                         f"{ratio[k_lo]:.2f}× (Π₁₂ = {pi12[k_lo]:g}) to {ratio[k_hi]:.2f}× (Π₁₂ = {pi12[k_hi]:g}) "
                         f"the rigid one")
    out.append(("A flexible superstructure changes the peak sliding, differently on the base and on the roof",
                "; ".join(lines) + "."))

    lines = []
    for floor, pi3, limit, worst, err, _ratio in rigid_summary(rigid):
        share = rigid["share_holds"].sel(floor=floor, pi3=pi3)
        shares = ", ".join(f"{float(s):.0%}" for s in share.values[1:])
        lim = f"up to Π₁₂ = {limit:g}" if np.isfinite(limit) else "at no Π₁₂ > 0"
        lines.append(f"contents on the {floor}, Π₃ = {pi3:g}: within {tol:.0%} of the flexible curve's peak "
                     f"{lim}; the largest error, {err:.0%} of the peak, at Π₁₂ = {worst:g}; pointwise within "
                     f"{tol:.0%} at {shares} of the sliding Π₂ points for Π₁₂ = "
                     f"{', '.join(f'{v:g}' for v in share['pi12'].values[1:])}")
    out.append(("Where the paper's rigid-superstructure reduction holds", "; ".join(lines) + "."))

    names = [str(s) for s in design["system"].values]
    best = [str(b) for b in design["best"].values if str(b)]
    mean = design["u_max"].mean("mu_k")
    counts = ", ".join(f"{n.replace('_', ' ')} {best.count(n)}" for n in names)
    ref = mean.sel(system="linear")
    ratios = []
    for n in names[1:]:
        r = (mean.sel(system=n) / ref.where(ref > 0)).values
        r = r[np.isfinite(r)]
        if r.size:
            ratios.append(f"{n.replace('_', ' ')} / linear: median {np.median(r):.2f} ({r.min():.2f} to "
                          f"{r.max():.2f})")
    pfa = design["pfa"].median("excitation")
    disp = design["bearing_disp"]
    D = float(design.attrs["D"])
    far = disp.max("system").values > 2.0 * D       # the isolators driven far beyond the design point
    split = []
    for label, mask in (("within 2 D", ~far), ("beyond 2 D", far)):
        won = [str(b) for b, m in zip(design["best"].values, mask, strict=True) if m and str(b)]
        if won:
            split.append(f"{label} ({len(won)} excitations): "
                         + ", ".join(f"{n.replace('_', ' ')} {won.count(n)}" for n in names))
    out.append((
        "Which isolation protects the contents best at equal effective period and damping",
        f"Smallest mean u_max over μ_k = {float(design['mu_k'].min()):g} to {float(design['mu_k'].max()):g}, "
        f"counted over the {len(best)} of {design.sizes['excitation']} excitations under which the contents slide: "
        f"{counts}. Mean u_max relative to the linear isolator, per excitation: {'; '.join(ratios)}. Median peak "
        f"floor acceleration over the excitations: "
        + ", ".join(f"{n.replace('_', ' ')} {float(pfa.sel(system=n)) / G:.2f} g" for n in names)
        + f". The three share T_eff = {design.attrs['T_eff_target']:g} s and β_eff = "
        f"{design.attrs['beta_eff_target']:g} only at D = {design.attrs['D']:g} m; the bearings reached "
        f"{float(disp.min()):.2f} to {float(disp.max()):.2f} m (median {float(disp.median()):.2f} m). "
        f"Best system by the largest bearing displacement of the excitation, " + "; ".join(split) + "."))
    return out


# ----------------------------------------------------------------------------------------------
# what the bearing does to the contents, from service-level shaking to beyond the design
# ----------------------------------------------------------------------------------------------

BEARING_ISOLATORS = ("lead_rubber", "friction_pendulum", "friction_pendulum_speed", "triple_friction_pendulum")
"""Isolators of the bearing study (:func:`bearing_study`), in the order of its ``isolator`` dimension."""

TRIPLE = "triple_friction_pendulum"
"""The triple friction pendulum's name in the ``isolator`` dimension."""

BEARING_LABELS = {"lead_rubber": "lead-rubber bearing", "friction_pendulum": "friction pendulum (constant μ)",
                  "friction_pendulum_speed": "friction pendulum (μ rising with speed)",
                  TRIPLE: "triple friction pendulum"}
"""Names of the bearing study's isolators in text."""

REGIMES = ("I", "II", "III", "IV", "V")
"""Fenz and Constantinou's regimes of the triple friction pendulum, numbered 1..5 in ``peak_stage``."""

STAGE_FLAGS = {-1: "not_triple_pendulum", 0: "held", **dict(zip(range(1, 6), REGIMES, strict=True))}
"""Values and meanings of the dataset's ``peak_stage``."""

TFP_KEYS = {"inner_radius": (0.0, 1.0, False, False), "mu1_ratio": (0.0, 1.0, False, True),
            "mu3_ratio": (1.0, 10.0, True, True), "stiffening": (1.0, 100.0, False, True),
            "capacity": (1.0, 100.0, False, True)}
"""Keys of ``isolation.bearings.tfp`` and their ranges ``(lo, hi, lo included, hi included)``."""

BUILDINGS = {"rigid": "base", "flexible": "roof"}
"""Buildings of the bearing study -> the floor carrying the contents (the slab of a rigid
superstructure, the roof of a flexible one)."""

BEARING_DESIGN_KEYS = ("T_eff", "beta_eff", "D", "D_y")
"""Keys of the ``isolation.design`` section the bearing study designs its isolators with."""

PROBE_STEP = 0.01
"""Largest step, in units of ``T_p``, of the histories giving the floor's and the bearing's peaks
(the peak floor acceleration over their rows is within about 0.2 % of the continuous one)."""

PROBE_HORIZON = 10.0
"""How long those histories follow a response that does not settle, after the pulse, in isolation
periods (the solver's ``horizon``): the peaks come during the pulse and the cycle after it, while a
pendulum creeping towards its rest at ``x = mu_slow R`` under a flexible superstructure is followed
for the solver's default horizon before it counts as unsettled."""

SPEED_TOLERANCE = 0.01
"""Relative difference of ``u_max`` below which the two pendulums' contents slide "the same"."""


def _bearing_number(key: str, value, lo: float, hi: float, lo_in: bool = True, hi_in: bool = True) -> float:
    """``value`` as a float, or a :class:`~isoslide.config.ConfigError` naming ``isolation.bearings.<key>``."""
    ok = isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)
    ok = ok and (value >= lo if lo_in else value > lo) and (value <= hi if hi_in else value < hi)
    if not ok:
        left, right = ("<=" if lo_in else "<"), ("<=" if hi_in else "<")
        raise ConfigError(f"isolation.bearings.{key} = {value!r} is out of range; allowed range: "
                          f"{lo:g} {left} value {right} {hi:g}")
    return float(value)


def _bearing_list(key: str, values, hi: float) -> list:
    if not isinstance(values, (list, tuple)) or not values:
        raise ConfigError(f"isolation.bearings.{key} = {values!r} is invalid; allowed: a non-empty list of "
                          f"numbers in (0, {hi:g}]")
    out = []
    for v in values:
        if not (isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) and 0 < v <= hi):
            raise ConfigError(f"isolation.bearings.{key} = {values!r} holds {v!r}; allowed: numbers in (0, {hi:g}]")
        out.append(float(v))
    if len(set(out)) != len(out) or out != sorted(out):
        raise ConfigError(f"isolation.bearings.{key} = {values!r} is not strictly increasing; allowed: increasing "
                          f"values, each once")
    return out


def check_bearings(section: dict) -> dict:
    """The checked ``isolation.bearings`` section (lists as lists of floats, numbers as floats).

    Raises
    ------
    isoslide.config.ConfigError
        Naming the key (``isolation.bearings.<key>``), its value and what is allowed.
    """
    pulse = section["pulse"]
    try:
        get_pulse(pulse)
    except (TypeError, ValueError) as err:
        raise ConfigError(f"isolation.bearings.pulse = {pulse!r} is invalid: {err}") from None
    buildings = section["buildings"]
    if (not isinstance(buildings, (list, tuple)) or not buildings or len(set(buildings)) != len(buildings)
            or any(b not in BUILDINGS for b in buildings)):
        raise ConfigError(f"isolation.bearings.buildings = {buildings!r} is invalid; allowed: a non-empty list of "
                          f"distinct values among {list(BUILDINGS)}")
    return {
        "pulse": pulse,
        "T_p": _bearing_number("T_p", section["T_p"], 0.0, 100.0, lo_in=False),
        "a_p": _bearing_list("a_p", section["a_p"], 1000.0),
        "mu_k": _bearing_list("mu_k", section["mu_k"], 10.0),
        "mu_slow_ratio": _bearing_number("mu_slow_ratio", section["mu_slow_ratio"], 0.0, 1.0, lo_in=False),
        "rate": _bearing_number("rate", section["rate"], 0.0, 1e5),
        "buildings": [str(b) for b in buildings],
        "pi11": _bearing_number("pi11", section["pi11"], 0.0, 1.0, lo_in=False, hi_in=False),
        "pi12": _bearing_number("pi12", section["pi12"], 0.0, 1e4, lo_in=False),
        "pi13": _bearing_number("pi13", section["pi13"], 0.0, 1e3),
        "tfp": _check_tfp(section["tfp"]),
    }


def _check_tfp(tfp) -> dict:
    """The checked ``isolation.bearings.tfp`` section (:data:`TFP_KEYS`)."""
    if not isinstance(tfp, dict) or set(tfp) != set(TFP_KEYS):
        raise ConfigError(f"isolation.bearings.tfp = {tfp!r} is invalid; allowed: a mapping of exactly "
                          f"{list(TFP_KEYS)}")
    out = {k: _bearing_number(f"tfp.{k}", tfp[k], *rng) for k, rng in TFP_KEYS.items()}
    if out["capacity"] <= out["stiffening"]:
        raise ConfigError(f"isolation.bearings.tfp.capacity = {tfp['capacity']!r} is out of range; allowed: above "
                          f"isolation.bearings.tfp.stiffening = {tfp['stiffening']!r}")
    return out


def bearing_settings(settings: dict) -> dict:
    """What the bearing study reads of :func:`isolation_settings` (copies).

    ``isolation.bearings``, the design keys of ``isolation.design`` (:data:`BEARING_DESIGN_KEYS`),
    ``defaults`` and ``solver``.
    """
    iso = settings["isolation"]
    return {"isolation": {"bearings": copy.deepcopy(iso["bearings"]),
                          "design": {k: iso["design"][k] for k in BEARING_DESIGN_KEYS}},
            "defaults": copy.deepcopy(settings["defaults"]), "solver": copy.deepcopy(settings["solver"])}


def bearing_triple(settings: dict) -> _design.TripleIsolator:
    """The bearing study's triple friction pendulum (:func:`isoslide.studies.design.design_triple_friction_pendulum`).

    The ``T_eff`` and ``beta_eff`` of ``isolation.design`` at its ``D``, the proportions of
    ``isolation.bearings.tfp``; constant friction.

    Raises
    ------
    isoslide.config.ConfigError
        Naming ``isolation.bearings.tfp`` when no such bearing meets the targets.
    """
    tfp = check_bearings(settings["isolation"]["bearings"])["tfp"]
    des = settings["isolation"]["design"]
    try:
        return _design.design_triple_friction_pendulum(
            NOMINAL_MASS, float(des["T_eff"]), float(des["beta_eff"]), float(des["D"]), tfp["inner_radius"],
            tfp["mu1_ratio"], tfp["mu3_ratio"], tfp["stiffening"], tfp["capacity"], g=G)
    except ValueError as err:
        raise ConfigError(f"isolation.bearings.tfp = {tfp!r} with isolation.design T_eff = {des['T_eff']!r}, "
                          f"beta_eff = {des['beta_eff']!r}, D = {des['D']!r}: {err}") from None


def bearing_isolators(settings: dict) -> dict:
    """The isolators of the bearing study: ``{name: keyword arguments of Scene.from_physical}``.

    The lead-rubber (bilinear) bearing and the friction pendulum of :func:`isoslide.studies.design.design`
    (the isolators of :func:`design_comparison`: the same ``T_eff`` and ``beta_eff`` at ``D``), that
    pendulum with friction rising with speed (:func:`isoslide.friction_pendulum` with its radius,
    ``mu_fast`` its ``mu``, ``mu_slow = mu_slow_ratio mu_fast`` and ``rate``) and the triple friction
    pendulum of :func:`bearing_triple` (:func:`isoslide.triple_friction_pendulum`), in the order of
    :data:`BEARING_ISOLATORS`.
    """
    sec = check_bearings(settings["isolation"]["bearings"])
    des = settings["isolation"]["design"]
    M = NOMINAL_MASS
    systems = _design.design(M, float(des["T_eff"]), float(des["beta_eff"]), float(des["D"]), float(des["D_y"]))
    fp = systems["friction_pendulum"]
    mu = fp.mu(G)
    speed = {"M_b": M, "xi_b": fp.xi_b,
             **friction_pendulum(fp.radius(G), mu, M, g=G, mu_slow=sec["mu_slow_ratio"] * mu, rate=sec["rate"])}
    return {"lead_rubber": systems["bilinear"].scene_parameters(), "friction_pendulum": fp.scene_parameters(),
            "friction_pendulum_speed": speed, TRIPLE: bearing_triple(settings).scene_parameters()}


def _building_parameters(building: str, sec: dict) -> dict:
    """``floor``, ``m_st``, ``T_s``, ``xi_s`` of one building of the bearing study."""
    if building == "rigid":
        return {"floor": BUILDINGS[building]}
    return {"floor": BUILDINGS[building], "m_st": sec["pi11"] * NOMINAL_MASS, "T_s": sec["pi12"] * sec["T_p"],
            "xi_s": sec["pi13"]}


def _coulomb(pi8: float, mu_k: float) -> dict:
    """Coulomb contents of friction ``mu_k`` and mass ``pi8 NOMINAL_MASS``."""
    return {"m_ec": pi8 * NOMINAL_MASS, "mu_s": mu_k, "mu_k": mu_k}


def _probe(scene: Scene, rtol) -> tuple:
    """``(peak floor acceleration [m/s^2], peak bearing displacement [m], bearing slid)`` of one scene.

    From its history with steps of at most :data:`PROBE_STEP` ``T_p``, followed at most
    :data:`PROBE_HORIZON` isolation periods after the pulse: the largest ``|floor_accel|``
    over the rows (:func:`isoslide.store.history_io.history_table`), the largest ``|x|`` (the slab
    relative to the ground) and whether the isolator ever slid or yielded (a bearing that held
    throughout ran as a fixed base: facet ``isolator == "fixed-base"``).  A triple friction
    pendulum that reaches its displacement capacity (:class:`isoslide.solver.CapacityError`) gives
    ``(nan, nan, True)``: the model does not go past it.
    """
    try:
        sol = solver.solve(scene, rtol=rtol, history=True, max_step=PROBE_STEP, horizon=PROBE_HORIZON)
    except solver.CapacityError:
        return math.nan, math.nan, True
    h = sol.history
    pfa = peak_abs(history_table(sol, scene).columns["floor_accel"])
    disp = float(np.max(np.abs(h.x))) * scene.scale.length
    slid = (sol.facets.isolator != "fixed-base" and h.iso_phase is not None
            and bool(np.any(np.asarray(h.iso_phase) != 0)))
    return pfa, disp, slid


def _solve_triple(scenes: list, rtol) -> tuple:
    """Triple-pendulum scenes, one :func:`isoslide.solve` each (it reports the regime and the capacity).

    Returns
    -------
    tuple of numpy.ndarray
        ``pi1`` (NaN where the bearing reached its capacity), ``settled``, ``facets``,
        ``peak_stage`` (:attr:`isoslide.Solution.peak_stage`; 5 = V, the regime the capacity ends,
        where it was reached) and ``capacity`` (True where :class:`isoslide.solver.CapacityError`
        was raised).
    """
    n = len(scenes)
    pi1, settled, stage, cap = np.full(n, np.nan), np.zeros(n, bool), np.zeros(n, np.int8), np.zeros(n, bool)
    facets = np.empty(n, dtype=object)
    for i, sc in enumerate(scenes):
        try:
            sol = solver.solve(sc, rtol=rtol)
        except solver.CapacityError:
            facets[i] = solver.scene_facets(sc, friction="coulomb", oneway=sc.pi8 == 0.0)
            stage[i], cap[i] = len(REGIMES), True
            continue
        pi1[i], settled[i], facets[i], stage[i] = sol.pi1, sol.settled, sol.facets, sol.peak_stage
    return pi1, settled, facets, stage, cap


def bearing_study(settings: dict, solve_many=None) -> xr.Dataset:
    """Peak sliding of the contents and the floor's peak acceleration over the pulse's intensity.

    The isolators of :func:`bearing_isolators` (a lead-rubber bearing and a friction pendulum of the
    same ``T_eff``, ``beta_eff`` at ``D``, that pendulum with friction rising with speed, and a
    triple friction pendulum of the same ``T_eff``, ``beta_eff`` at ``D``) under the buildings of
    ``isolation.bearings.buildings`` (:data:`BUILDINGS`), one pulse of period ``T_p`` scaled to each
    ``a_p``, Coulomb contents (``mu_s = mu_k``, mass ratio Pi8 from ``defaults``) of each ``mu_k``.

    Parameters
    ----------
    settings : dict
        :func:`isolation_settings` of a complete configuration (or its :func:`bearing_settings`).
    solve_many : callable, optional
        The batch solver (:mod:`isoslide.studies.solving`) of the scenes of every isolator but the
        triple friction pendulum, called once; of its answers the study reads ``pi1``, ``settled``
        and ``facets``.  The triple pendulum's scenes are solved one by one by :func:`isoslide.solve`,
        which reports the regime reached and raises :class:`isoslide.solver.CapacityError` at the
        bearing's displacement capacity.

    Returns
    -------
    xarray.Dataset
        Dimensions ``building, isolator, a_p, mu_k``: ``u_max`` [m] (``Pi1 a_p T_p^2``, as
        :attr:`isoslide.Solution.u_max`), ``pi1``, ``settled`` and the model facets
        (``model_*``, :func:`isoslide.datasets.encode_facets`; labels by
        :func:`isoslide.datasets.model_labels`); ``pi2`` over ``a_p, mu_k``; per ``building,
        isolator, a_p``, from one history with the contents at the largest ``mu_k`` (Pi8 is small:
        the bearing and the floor barely feel them): ``pfa`` (peak absolute acceleration of the
        contents' floor [m/s^2]), ``bearing_disp`` (peak isolator displacement [m]) and
        ``bearing_slid`` (the bearing slid, or the lead-rubber bearing yielded); per ``isolator``:
        ``T_b``, ``Q_over_W`` (``mu_fast`` of a pendulum), ``mu_slow``, ``rate``, ``D_y``, ``R``,
        ``T_eff`` and ``beta_eff`` at ``D`` (the code linearisation; the speed-dependent pendulum's
        with ``mu_fast``; the triple pendulum's from its closed-form backbone and loop, its
        ``T_b``, ``R`` and ``Q_over_W`` those of regime III: ``L2 + L3`` and ``mu2``).  The triple
        friction pendulum: ``peak_stage`` over ``building, isolator, a_p, mu_k`` (its regime
        reached, :data:`STAGE_FLAGS`; -1 for the other isolators), ``capacity_reached`` (1 where
        :class:`isoslide.solver.CapacityError` was raised: ``pi1``, ``u_max`` NaN there, and the
        probe's ``pfa``, ``bearing_disp`` NaN where its history reached it), ``tfp_regime_start``
        over ``regime`` (where each regime starts on the backbone [m]) and the attributes
        ``tfp_L``, ``tfp_mu``, ``tfp_d`` (OpenSees's ``L1..L3`` [m], ``mu1..mu3``, ``d1..d3`` [m])
        and ``tfp_capacity`` [m].
    """
    solve_many = batch_solver(solve_many)
    sec = check_bearings(settings["isolation"]["bearings"])
    des = settings["isolation"]["design"]
    rtol = settings["solver"]["rtol"]
    pi8 = float(settings["defaults"]["pi8"])
    isolators = bearing_isolators(settings)
    triple = bearing_triple(settings)
    buildings, a_p, mu = sec["buildings"], np.array(sec["a_p"]), np.array(sec["mu_k"])
    T_p, pulse = sec["T_p"], sec["pulse"]
    shape = (len(buildings), len(isolators), a_p.size, mu.size)
    scenes, probes, is_triple = [], [], []
    for b in buildings:
        frame = _building_parameters(b, sec)
        for name, iso in isolators.items():
            for a in a_p:
                base = dict(a_p=float(a), T_p=T_p, pulse=pulse, **frame, **iso)
                scenes += [Scene.from_physical(**base, **_coulomb(pi8, float(m))) for m in mu]
                is_triple += [name == TRIPLE] * mu.size
                probes.append(Scene.from_physical(**base, **_coulomb(pi8, float(mu[-1]))))
    is_triple = np.array(is_triple, dtype=bool)
    n = len(scenes)
    pi1, settled, facets = np.full(n, np.nan), np.zeros(n, bool), np.empty(n, dtype=object)
    stage, capacity = np.full(n, -1, np.int8), np.zeros(n, bool)
    batch = solve_many([s for s, t in zip(scenes, is_triple, strict=True) if not t], rtol=rtol)
    pi1[~is_triple] = np.asarray(batch.pi1, dtype=float)
    settled[~is_triple] = np.asarray(batch.settled, dtype=bool)
    facets[~is_triple] = list(batch.facets)
    (pi1[is_triple], settled[is_triple], facets[is_triple], stage[is_triple],
     capacity[is_triple]) = _solve_triple([s for s, t in zip(scenes, is_triple, strict=True) if t], rtol)
    pi1, settled, stage, capacity = (x.reshape(shape) for x in (pi1, settled, stage, capacity))
    length = np.array([s.scale.length for s in scenes]).reshape(shape)
    peaks = np.array([_probe(s, rtol) for s in probes], dtype=float).reshape(*shape[:3], 3)

    one = {"units": "1"}
    ds = xr.Dataset(coords={
        "building": ("building", np.array(buildings, dtype=object),
                     {"long_name": "building: rigid superstructure (contents on the slab) or flexible one "
                                   "(contents on the roof)"}),
        "isolator": ("isolator", np.array(list(isolators), dtype=object), {"long_name": "isolator"}),
        "a_p": ("a_p", a_p, {"long_name": "pulse amplitude a_p", "units": "m s-2"}),
        "mu_k": ("mu_k", mu, {"long_name": "friction coefficient of the Coulomb contents (mu_s = mu_k)", **one}),
    })
    ds.coords["floor"] = ("building", np.array([BUILDINGS[b] for b in buildings], dtype=object),
                          {"long_name": "floor carrying the contents"})
    d4 = ("building", "isolator", "a_p", "mu_k")
    beyond = "NaN where the triple friction pendulum reached its displacement capacity (capacity_reached)"
    ds["u_max"] = (d4, pi1 * length, {"long_name": "peak sliding displacement of the contents", "units": "m",
                                      "comment": beyond})
    ds["pi1"] = (d4, pi1, {**pi_attrs("pi1"), "comment": beyond})
    ds["pi2"] = (("a_p", "mu_k"), mu[None, :] * G / a_p[:, None], pi_attrs("pi2"))
    ds["settled"] = (d4, settled.astype(np.int8), {"long_name": "response settled", **one,
                                                    "flag_values": np.array([0, 1], np.int8),
                                                    "flag_meanings": "not_settled settled"})
    for name, (dims, codes, attrs) in encode_facets(facets, d4, shape).items():
        ds[name] = (dims, codes, attrs)
    ds["peak_stage"] = (d4, stage, {
        "long_name": "highest regime of the triple friction pendulum (Fenz and Constantinou's I..V)", **one,
        "flag_values": np.array(list(STAGE_FLAGS), np.int8), "flag_meanings": " ".join(STAGE_FLAGS.values()),
        "comment": "held: the bearing never slid; V where capacity_reached (the capacity ends regime V); "
                   "not_triple_pendulum for the other isolators"})
    ds["capacity_reached"] = (d4, capacity.astype(np.int8), {
        "long_name": "the triple friction pendulum reached its displacement capacity (isoslide.solver.CapacityError)",
        **one, "flag_values": np.array([0, 1], np.int8), "flag_meanings": "within_capacity capacity_reached",
        "comment": "pi1 and u_max are NaN where 1: the model of rigid restrainers does not go past the capacity"})
    d3 = ("building", "isolator", "a_p")
    probe = (f"contents at the largest mu_k; history steps <= {PROBE_STEP:g} T_p, at most {PROBE_HORIZON:g} "
             "isolation periods after the pulse")
    probe_nan = probe + "; NaN where that history reached the triple friction pendulum's capacity"
    ds["pfa"] = (d3, peaks[..., 0], {"long_name": "peak absolute acceleration of the contents' floor",
                                     "units": "m s-2", "comment": probe_nan})
    ds["bearing_disp"] = (d3, peaks[..., 1], {"long_name": "peak isolator displacement", "units": "m",
                                              "comment": probe_nan})
    ds["bearing_slid"] = (d3, peaks[..., 2].astype(np.int8),
                          {"long_name": "the bearing slid (a lead-rubber bearing: yielded)", **one,
                           "flag_values": np.array([0, 1], np.int8), "flag_meanings": "held slid",
                           "comment": probe})
    D = float(des["D"])
    rows = {"T_b": [], "Q_over_W": [], "mu_slow": [], "rate": [], "D_y": [], "R": [], "T_eff": [], "beta_eff": []}
    for name, iso in isolators.items():
        W = iso["M_b"] * G
        k_d = iso["M_b"] * (2.0 * math.pi / iso["T_b"]) ** 2
        if name == TRIPLE:
            K, beta = triple.effective(D)
        else:
            K, beta = _design.effective_bilinear(k_d, iso["Q_d"], D, iso["D_y"])
        for k, v in (("T_b", iso["T_b"]), ("Q_over_W", iso["Q_d"] / W), ("mu_slow", iso.get("Q_slow", iso["Q_d"]) / W),
                     ("rate", iso.get("rate", 0.0)), ("D_y", iso["D_y"]), ("R", W / k_d),
                     ("T_eff", _design.effective_period(iso["M_b"], K)), ("beta_eff", beta)):
            rows[k].append(float(v))
    meta = {"T_b": ("period of the (post-yield) stiffness 2 pi sqrt(M_b/k_d)", "s"),
            "Q_over_W": ("characteristic strength over weight Q/W (a pendulum's mu_fast)", "1"),
            "mu_slow": ("friction at breakaway (zero speed) over weight; Q/W where friction is constant", "1"),
            "rate": ("rate a of mu(v) = mu_fast - (mu_fast - mu_slow) exp(-a |v|); 0: constant", "s m-1"),
            "D_y": ("yield displacement", "m"),
            "R": ("radius of the pendulum of the same k_d, M_b g/k_d", "m"),
            "T_eff": ("effective period at D (code linearisation, mu_fast)", "s"),
            "beta_eff": ("effective damping at D (code linearisation, mu_fast)", "1")}
    for k, v in rows.items():
        ds[k] = ("isolator", np.asarray(v), {"long_name": meta[k][0], "units": meta[k][1]})
    ds["R"].attrs["comment"] = "the triple friction pendulum's: L2 + L3, the radius of regime III"
    ds["Q_over_W"].attrs["comment"] = "the triple friction pendulum's: mu2 (constant friction)"
    bounds = triple.boundaries()
    ds.coords["regime"] = ("regime", np.arange(1, len(REGIMES) + 1, dtype=np.int8),
                           {"long_name": "regime of the triple friction pendulum", **one,
                            "flag_values": np.arange(1, len(REGIMES) + 1, dtype=np.int8),
                            "flag_meanings": " ".join(REGIMES)})
    ds["tfp_regime_start"] = ("regime", np.asarray(bounds.u[:len(REGIMES)], dtype=float),
                              {"long_name": "displacement where each regime of the triple friction pendulum starts "
                                            "on its backbone", "units": "m",
                               "comment": "regimes of zero length start where the next one does"})
    ds.attrs.update({"D": D, "T_eff_target": float(des["T_eff"]), "beta_eff_target": float(des["beta_eff"]),
                     "D_y_bilinear": float(des["D_y"]), "T_p": T_p, "pulse": pulse, "M_b": NOMINAL_MASS,
                     "pi8": pi8, "mu_slow_ratio": sec["mu_slow_ratio"], "rate": sec["rate"],
                     "pi11_flexible": sec["pi11"], "pi12_flexible": sec["pi12"], "pi13_flexible": sec["pi13"],
                     "probe_step": PROBE_STEP, "probe_horizon": PROBE_HORIZON, "rtol": "default" if rtol is None else float(rtol),
                     "tfp_L": np.asarray(triple.L, dtype=float), "tfp_mu": np.asarray(triple.mu, dtype=float),
                     "tfp_d": np.asarray(triple.d, dtype=float), "tfp_capacity": float(triple.capacity)})
    return ds


def bearings_dataset(settings: dict) -> xr.Dataset:
    """:func:`bearing_study` with CF global attributes (rule isolation_bearings)."""
    ds = bearing_study(settings)
    extra = dict(ds.attrs)
    sub = bearing_settings(settings)
    ds.attrs = global_attrs(
        title="isoslide: contents on isolated floors from service-level shaking to beyond the design, under a "
              "lead-rubber bearing, friction pendulums of constant and speed-dependent friction and a triple "
              "friction pendulum",
        history=(f"isoslide.studies.isolation_study.bearing_study: {ds.sizes['building']} buildings x "
                 f"{ds.sizes['isolator']} isolators x {ds.sizes['a_p']} a_p x {ds.sizes['mu_k']} mu_k, isolators by "
                 "isoslide.studies.design (ASCE 7 / AASHTO linearisation); no timestamps are stored"),
        config={"bearings": sub["isolation"]["bearings"], "design": sub["isolation"]["design"],
                "defaults": sub["defaults"], "solver": sub["solver"]}, **extra)
    return ds


# ----------------------------------------------------------------------------------------------
# the bearing study's findings, with their numbers
# ----------------------------------------------------------------------------------------------

BUILDING_TEXT = {"rigid": "rigid superstructure, contents on the slab",
                 "flexible": "flexible superstructure, contents on the roof"}
"""The bearing study's buildings in text."""


def _speed_verdict(u_const: float, u_speed: float, tolerance: float) -> str:
    """``none`` (neither slides), ``more``, ``less`` or ``same`` (within ``tolerance``) for the speed-dependent pendulum."""
    if u_const <= 0.0 and u_speed <= 0.0:
        return "none"
    if u_const <= 0.0:
        return "more"
    if u_speed <= 0.0:
        return "less"
    r = u_speed / u_const
    return "more" if r > 1.0 + tolerance else "less" if r < 1.0 - tolerance else "same"


def speed_effect(ds: xr.Dataset, tolerance: float = SPEED_TOLERANCE) -> list:
    """Where the speed-dependent pendulum's contents slide more or less than the constant one's.

    Parameters
    ----------
    ds : xarray.Dataset
        :func:`bearing_study` (``isolation_bearings.nc``).
    tolerance : float
        Relative difference of ``u_max`` counted as "the same".

    Returns
    -------
    list of tuple
        Per building and ``mu_k``, each run of consecutive ``a_p`` with one verdict:
        ``(building, mu_k, verdict, first a_p, last a_p, points, smallest ratio, largest ratio, a_p of
        the largest difference, its u_max constant [m], its u_max speed-dependent [m])``; the verdict
        is ``none`` (neither slides), ``more``, ``less`` or ``same``, the ratio
        ``u_max speed / u_max constant`` (``inf`` where only the speed-dependent one slides).
    """
    rows = []
    a_p = ds["a_p"].values
    for b in ds["building"].values:
        for m in ds["mu_k"].values:
            sel = ds["u_max"].sel(building=b, mu_k=m)
            uc = sel.sel(isolator="friction_pendulum").values
            us = sel.sel(isolator="friction_pendulum_speed").values
            verdicts = [_speed_verdict(float(c), float(v), tolerance) for c, v in zip(uc, us, strict=True)]
            start = 0
            for k in range(1, len(verdicts) + 1):
                if k < len(verdicts) and verdicts[k] == verdicts[start]:
                    continue
                idx = np.arange(start, k)
                with np.errstate(divide="ignore", invalid="ignore"):
                    ratio = np.where(uc[idx] > 0, us[idx] / np.where(uc[idx] > 0, uc[idx], 1.0),
                                     np.where(us[idx] > 0, np.inf, np.nan))
                j = idx[int(np.argmax(np.abs(us[idx] - uc[idx])))]
                finite = ratio[~np.isnan(ratio)]
                rows.append((str(b), float(m), verdicts[start], float(a_p[start]), float(a_p[k - 1]), int(idx.size),
                             float(finite.min()) if finite.size else math.nan,
                             float(finite.max()) if finite.size else math.nan,
                             float(a_p[j]), float(uc[j]), float(us[j])))
                start = k
    return rows


def bearing_onsets(ds: xr.Dataset) -> list:
    """Where each bearing and its contents start to move, and where the bearing reaches ``D``.

    Returns
    -------
    list of tuple
        Per building and isolator: ``(building, isolator, first a_p at which the bearing slid or
        yielded, peak floor acceleration at the smallest a_p [m/s^2], first a_p at which the
        bearing reaches D, its displacement at the largest a_p [m], first a_p at which the contents
        slide per mu_k (tuple), first a_p at which the bearing reached its displacement capacity)``;
        NaN where it never happens on the grid (the displacement at the largest ``a_p`` too, where
        the capacity was reached there).
    """
    D = float(ds.attrs["D"])
    a_p = ds["a_p"].values

    def first(mask):
        k = np.flatnonzero(np.asarray(mask))
        return float(a_p[k[0]]) if k.size else math.nan

    rows = []
    for b in ds["building"].values:
        for iso in ds["isolator"].values:
            sub = ds.sel(building=b, isolator=iso)
            disp = sub["bearing_disp"].values
            cap = (sub["capacity_reached"] > 0).any("mu_k").values if "capacity_reached" in sub else np.zeros(a_p.size)
            rows.append((str(b), str(iso), first(sub["bearing_slid"].values > 0), float(sub["pfa"].values[0]),
                         first(disp >= D), float(disp[-1]),
                         tuple(first(sub["u_max"].sel(mu_k=m).values > 0) for m in ds["mu_k"].values), first(cap)))
    return rows


def triple_regimes(ds: xr.Dataset) -> list:
    """The triple friction pendulum's regime over the intensity, per building.

    The regime at each ``a_p`` is the highest over the ``mu_k`` (the contents barely move the
    bearing: Pi8 is small).

    Returns
    -------
    list of tuple
        Per building: ``(building, runs, first a_p of the capacity (NaN: never on the grid))``, the
        runs ``(regime, first a_p, last a_p, peak bearing displacement at the last a_p [m])`` of
        consecutive ``a_p`` in one regime below the capacity, ``regime`` one of ``"held"``,
        :data:`REGIMES`.
    """
    a_p = ds["a_p"].values
    rows = []
    for b in ds["building"].values:
        sub = ds.sel(building=b, isolator=TRIPLE)
        stage = sub["peak_stage"].max("mu_k").values
        cap = (sub["capacity_reached"] > 0).any("mu_k").values
        disp = sub["bearing_disp"].values
        runs, k = [], 0
        within = np.flatnonzero(~cap)
        while k < within.size:
            j = k
            while j + 1 < within.size and within[j + 1] == within[j] + 1 and stage[within[j + 1]] == stage[within[k]]:
                j += 1
            runs.append((STAGE_FLAGS[int(stage[within[k]])], float(a_p[within[k]]), float(a_p[within[j]]),
                         float(disp[within[j]])))
            k = j + 1
        rows.append((str(b), runs, float(a_p[np.flatnonzero(cap)[0]]) if cap.any() else math.nan))
    return rows


def triple_against(ds: xr.Dataset, other: str, tolerance: float = SPEED_TOLERANCE) -> list:
    """The triple friction pendulum's contents and floor against those of another isolator.

    Parameters
    ----------
    ds : xarray.Dataset
        :func:`bearing_study` (``isolation_bearings.nc``).
    other : str
        An isolator of ``ds`` (``"friction_pendulum"``, ``"lead_rubber"``, ...).
    tolerance : float
        Relative difference of ``u_max`` counted as "the same".

    Returns
    -------
    list of tuple
        Per building, over the ``(a_p, mu_k)`` within the triple pendulum's capacity where either
        isolator's contents slide: ``(building, other, points, more, less, same, smallest ratio,
        median ratio, largest ratio, smallest floor ratio, its a_p, largest floor ratio, its a_p)``; ``more``,
        ``less``, ``same``: how many points the triple pendulum's contents slide more, less or the
        same (within ``tolerance``), the ratio ``u_max triple / u_max other`` (finite ones; NaN if
        none), the floor ratio that of the peak floor accelerations over the ``a_p`` within the
        capacity.
    """
    rows = []
    a_p = ds["a_p"].values
    for b in ds["building"].values:
        sub = ds.sel(building=b)
        ut, uo = sub["u_max"].sel(isolator=TRIPLE).values, sub["u_max"].sel(isolator=other).values
        within = sub["capacity_reached"].sel(isolator=TRIPLE).values == 0
        verdicts = [_speed_verdict(float(o), float(t), tolerance)
                    for o, t, w in zip(uo.ravel(), ut.ravel(), within.ravel(), strict=True) if w]
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = np.where(within & (uo > 0), ut / np.where(uo > 0, uo, 1.0), np.nan)
        finite = ratio[np.isfinite(ratio)]
        pt, po = sub["pfa"].sel(isolator=TRIPLE).values, sub["pfa"].sel(isolator=other).values
        fr = np.where(np.isfinite(pt), pt / po, np.nan)
        floor = (math.nan,) * 4                  # past the capacity at every a_p
        if np.isfinite(fr).any():
            k_lo, k_hi = int(np.nanargmin(fr)), int(np.nanargmax(fr))
            floor = (float(fr[k_lo]), float(a_p[k_lo]), float(fr[k_hi]), float(a_p[k_hi]))
        ratios = ((float(finite.min()), float(np.median(finite)), float(finite.max())) if finite.size
                  else (math.nan,) * 3)
        rows.append((str(b), str(other), sum(v != "none" for v in verdicts), verdicts.count("more"),
                     verdicts.count("less"), verdicts.count("same"), *ratios, *floor))
    return rows


def _ap(x: float) -> str:
    return "never on the grid" if not np.isfinite(x) else f"{x:g} m/s²"


def _span(lo: float, hi: float) -> str:
    return f"a_p = {lo:g} m/s²" if lo == hi else f"a_p = {lo:g} to {hi:g} m/s²"


def bearing_findings(ds: xr.Dataset) -> list:
    """The bearing study's findings, each ``(title, text with its numbers)``.

    Parameters
    ----------
    ds : xarray.Dataset
        :func:`bearing_study` (``isolation_bearings.nc``).
    """
    out = []
    names = BEARING_LABELS
    tol = SPEED_TOLERANCE
    runs = speed_effect(ds, tol)
    lines = []
    for b in ds["building"].values:
        per_mu = []
        for m in ds["mu_k"].values:
            parts = []
            for row in runs:
                if row[0] != str(b) or row[1] != float(m) or row[2] == "none":
                    continue
                _, _, verdict, lo, hi, _n, rmin, rmax, at, uc, us = row
                if verdict == "same":
                    parts.append(f"the same within {tol:.0%} at {_span(lo, hi)}")
                    continue
                ratio = (f"ratio {rmin:.2f}" if rmin == rmax else f"ratio {rmin:.2f} to {rmax:.2f}")
                if not np.isfinite(rmax):
                    ratio = "only the speed-dependent one's slide"
                elif rmax == 0.0:
                    ratio = "only the constant one's slide"
                parts.append(f"{verdict} at {_span(lo, hi)} ({ratio}; {us * 100:.2f} against {uc * 100:.2f} cm "
                             f"at a_p = {at:g} m/s²)")
            if parts:
                per_mu.append(f"μ_k = {float(m):g}: " + ", ".join(parts))
            else:
                per_mu.append(f"μ_k = {float(m):g}: neither slides")
        lines.append(f"{BUILDING_TEXT.get(str(b), str(b)).capitalize()} — " + "; ".join(per_mu))
    counted = []
    for verdict in ("less", "more", "same"):
        sel = [r for r in runs if r[2] == verdict]
        n = sum(r[5] for r in sel)
        if n:
            where = f" ({_span(min(r[3] for r in sel), max(r[4] for r in sel))})" if verdict != "same" else ""
            counted.append(f"{verdict if verdict != 'same' else f'the same within {tol:.0%}'} at {n}{where}")
    total = sum(r[5] for r in runs if r[2] != "none")
    summary = (f"Of the {total} (building, a_p, μ_k) points where either pendulum's contents slide, the speed-dependent "
               f"pendulum's slide " + ", ".join(counted) + ".") if total else "Neither pendulum's contents slide."
    out.append(("Friction rising with speed: where the pendulum's contents slide more, and where less",
                f"Peak sliding u_max of the contents under the pendulum whose friction rises with speed (μ_slow = "
                f"{ds.attrs['mu_slow_ratio']:g} μ_fast, a = {ds.attrs['rate']:g} s/m) against the same pendulum "
                f"of constant friction μ = μ_fast = {float(ds['Q_over_W'].sel(isolator='friction_pendulum')):.4f}. "
                + ". ".join(lines) + ". " + summary))

    onsets = bearing_onsets(ds)
    lines = []
    for b in ds["building"].values:
        rows = {r[1]: r for r in onsets if r[0] == str(b)}
        fp, fs, lrb = rows["friction_pendulum"], rows["friction_pendulum_speed"], rows["lead_rubber"]
        pfa = ds["pfa"].sel(building=b)
        ratio = (pfa.sel(isolator="friction_pendulum_speed") / pfa.sel(isolator="friction_pendulum")).values
        k_lo, k_hi = int(np.argmin(ratio)), int(np.argmax(ratio))
        a_p = ds["a_p"].values
        lines.append(
            f"{BUILDING_TEXT.get(str(b), str(b)).capitalize()}: at the smallest a_p = {a_p[0]:g} m/s² the floor "
            f"peaks at {fp[3] / G:.4f} g on the constant pendulum, {fs[3] / G:.4f} g on the speed-dependent one and "
            f"{lrb[3] / G:.4f} g on the lead-rubber bearing; the constant pendulum first slides at {_ap(fp[2])}, the "
            f"speed-dependent one at {_ap(fs[2])} (breakaway at μ_slow = "
            f"{float(ds['mu_slow'].sel(isolator='friction_pendulum_speed')):.4f}), the lead-rubber bearing yields "
            f"at {_ap(lrb[2])}; the speed-dependent pendulum's floor acceleration is {ratio[k_lo]:.2f}× "
            f"(a_p = {a_p[k_lo]:g} m/s²) to {ratio[k_hi]:.2f}× (a_p = {a_p[k_hi]:g} m/s²) the constant one's")
    out.append(("Which bearing holds, which one breaks away, and what the floor feels",
                ". ".join(lines) + "."))

    D = float(ds.attrs["D"])
    lines = []
    for b in ds["building"].values:
        parts = []
        for r in (r for r in onsets if r[0] == str(b)):
            reach = f"reaches D at a_p = {r[4]:g} m/s²" if np.isfinite(r[4]) else "stays below D"
            slide = ", ".join(f"{_ap(a)} (μ_k = {float(m):g})" for a, m in zip(r[6], ds["mu_k"].values, strict=True))
            if np.isfinite(r[5]):
                far = f"{r[5]:.3f} m = {r[5] / D:.2f} D at the largest a_p"
            else:
                disp = ds["bearing_disp"].sel(building=b, isolator=r[1]).values
                k = np.flatnonzero(np.isfinite(disp))
                far = (f"reaches its displacement capacity {ds.attrs['tfp_capacity']:.3f} m = "
                       f"{ds.attrs['tfp_capacity'] / D:.2f} D at a_p = {r[7]:g} m/s²"
                       + (f" ({disp[k[-1]]:.3f} m = {disp[k[-1]] / D:.2f} D at a_p = {ds['a_p'].values[k[-1]]:g} m/s²)"
                          if k.size else ""))
            parts.append(f"{names[r[1]]} {reach}, {far}; its contents start sliding at {slide}")
        lines.append(f"{BUILDING_TEXT.get(str(b), str(b)).capitalize()}: " + "; ".join(parts))
    out.append((f"From service level to beyond the design displacement D = {D:g} m", ". ".join(lines) + "."))

    u = ds["u_max"]
    counts = []
    for b in ds["building"].values:
        sub = u.sel(building=b)
        slides = (sub > 0).any("isolator").values
        least = (sub == sub.min("isolator")).values          # ties count for each
        n = int(slides.sum())
        tally = ", ".join(f"{names[str(iso)]} {int(np.sum(least[i] & slides))}"
                          for i, iso in enumerate(ds["isolator"].values))
        top = sub.isel(a_p=-1, mu_k=0)
        at_top = ", ".join(f"{names[str(i)]} {float(top.sel(isolator=i)) * 100:.1f} cm"
                           if np.isfinite(float(top.sel(isolator=i))) else f"{names[str(i)]} past its capacity"
                           for i in ds["isolator"].values)
        counts.append(f"{BUILDING_TEXT.get(str(b), str(b))}: of the {n} (a_p, μ_k) points where any contents slide, the "
                      f"smallest u_max (ties counted for each) is under the {tally}; at the largest a_p and μ_k = "
                      f"{float(ds['mu_k'][0]):g} {at_top}")
    capped = int((ds["capacity_reached"] > 0).sum()) if "capacity_reached" in ds else 0
    out.append(("Which bearing lets the contents slide least", "; ".join(counts).capitalize() + "."
                + (f" The {capped} points past the triple friction pendulum's capacity count for no bearing."
                   if capped else "")))
    if TRIPLE in ds["isolator"].values:
        out.append(_triple_finding(ds))
    return out


def _triple_finding(ds: xr.Dataset) -> tuple:
    """The bearing study's finding on the triple friction pendulum: ``(title, text with its numbers)``."""
    D = float(ds.attrs["D"])
    (L1, L2, _L3), (m1, m2, m3), (d1, d2, _d3) = (np.asarray(ds.attrs[k], dtype=float)
                                                  for k in ("tfp_L", "tfp_mu", "tfp_d"))
    start = ds["tfp_regime_start"].values
    cap = float(ds.attrs["tfp_capacity"])
    head = (f"The triple friction pendulum (L1 = {L1:.3f} m, L2 = L3 = {L2:.3f} m, μ1 = {m1:.4f}, μ2 = {m2:.4f}, "
            f"μ3 = {m3:.4f}, d1 = {d1:.3f} m, d2 = d3 = {d2:.3f} m; constant friction on its surfaces in this "
            f"study) shares T_eff = {float(ds['T_eff'].sel(isolator=TRIPLE)):.3f} s "
            f"and β_eff = {float(ds['beta_eff'].sel(isolator=TRIPLE)):.3f} with the other bearings at D = {D:g} m, "
            f"where it is in regime III; its inner slider breaks away at μ1 g = {m1 * G:.3f} m/s² of floor "
            f"acceleration, against μ g = {float(ds['Q_over_W'].sel(isolator='friction_pendulum')) * G:.3f} m/s² for "
            f"the single pendulum; regime II starts at {start[1] * 100:.1f} cm, III at {start[2] * 100:.1f} cm, IV "
            f"(stiffening) at {start[3] / D:.2f} D, V at {start[4] / D:.2f} D, and its capacity is {cap:.3f} m = "
            f"{cap / D:.2f} D.")
    lines = []
    regimes = {r[0]: r for r in triple_regimes(ds)}
    against = {(r[0], r[1]): r for other in ("friction_pendulum", "lead_rubber") for r in triple_against(ds, other)}
    a_p = ds["a_p"].values
    for b in ds["building"].values:
        _, runs, cap_from = regimes[str(b)]
        seq = ", ".join(f"{name} at {_span(lo, hi)} ({disp / D:.2f} D)" for name, lo, hi, disp in runs)
        capacity = (f"; past its capacity from a_p = {cap_from:g} m/s² (Π₁ NaN there: the model stops at the "
                    "restrainer)" if np.isfinite(cap_from) else "; within its capacity at every a_p")
        pfa = ds["pfa"].sel(building=b)
        k0 = 0
        service = (f"at a_p = {a_p[k0]:g} m/s² the floor peaks at {float(pfa.sel(isolator=TRIPLE)[k0]) / G:.4f} g on "
                   f"it, {float(pfa.sel(isolator='friction_pendulum')[k0]) / G:.4f} g on the single pendulum and "
                   f"{float(pfa.sel(isolator='lead_rubber')[k0]) / G:.4f} g on the lead-rubber bearing")
        comp = []
        for other in ("friction_pendulum", "lead_rubber"):
            _, _, n, more, less, same, rmin, rmed, rmax, flo, alo, fhi, ahi = against[(str(b), other)]
            ratio = f", u_max ratio median {rmed:.2f} ({rmin:.2f} to {rmax:.2f})" if np.isfinite(rmin) else ""
            comp.append(f"against the {BEARING_LABELS[other]}, of the {n} (a_p, μ_k) points within its capacity where "
                        f"either's contents slide, the triple pendulum's slide more at {more}, less at {less}, the "
                        f"same at {same}{ratio}; its floor peaks at {flo:.2f}× (a_p = {alo:g} m/s²) to {fhi:.2f}× "
                        f"(a_p = {ahi:g} m/s²) that one's")
        last = runs[-1] if runs else None
        strongest = ""
        if last is not None and last[0] not in ("held", "I"):
            u = ds["u_max"].sel(building=b, a_p=last[2])
            mus = ", ".join(f"{float(m):g}" for m in ds["mu_k"].values)
            strongest = (f"; at a_p = {last[2]:g} m/s² (regime {last[0]}, the largest a_p within its capacity) its "
                         f"contents slide {', '.join(f'{v * 100:.2f}' for v in u.sel(isolator=TRIPLE).values)} cm, "
                         f"against {', '.join(f'{v * 100:.2f}' for v in u.sel(isolator='friction_pendulum').values)} cm "
                         f"on the single pendulum and "
                         f"{', '.join(f'{v * 100:.2f}' for v in u.sel(isolator='lead_rubber').values)} cm on the "
                         f"lead-rubber bearing (μ_k = {mus}), its floor peaking at "
                         f"{float(pfa.sel(isolator=TRIPLE, a_p=last[2])) / G:.3f} g against "
                         f"{float(pfa.sel(isolator='friction_pendulum', a_p=last[2])) / G:.3f} g and "
                         f"{float(pfa.sel(isolator='lead_rubber', a_p=last[2])) / G:.3f} g")
        lines.append(f"{BUILDING_TEXT.get(str(b), str(b)).capitalize()}: its regimes {seq}{capacity}; {service}; "
                     + "; ".join(comp) + strongest)
    return ("The triple friction pendulum: its regimes over the intensity, and its contents against the single "
            "pendulum's and the lead-rubber bearing's", head + " " + ". ".join(lines) + ".")
