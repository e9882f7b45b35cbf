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
"""

from __future__ import annotations

import copy
import math

import numpy as np
import xarray as xr

from . import design as _design
from .. import solver
from ..config import ConfigError
from ..datasets import global_attrs, open_dataset, pi_attrs
from .intensity import floor_peaks
from .record_study import resolve_record
from .solving import batch_solver
from ..records import G
from ..scene import FLOORS, Scene
from .sweep import normalise_study

__all__ = ["FAMILIES", "NOMINAL_MASS", "bearing_summary", "findings", "sliding_end", "design_comparison", "design_dataset", "design_excitations",
           "isolation_settings", "rigid_dataset", "rigid_error", "rigid_summary", "study_entries", "study_names",
           "study_specs"]

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
