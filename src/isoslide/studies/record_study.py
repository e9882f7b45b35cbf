"""Real records against their fitted pulses: Fig. 4 data and the Pi2 x Pi3 comparison.

Pure functions returning :mod:`xarray` datasets (the pipeline writes them to
netCDF and draws the figures):

* :func:`fig4_data` -- a record and its fitted Ricker wavelet (paper Fig. 4);
* :func:`compare_grid` -- peak sliding ``Pi1`` under the real record and under
  its fitted pulse over a ``Pi2 x Pi3`` grid, with the fitted ``a_p`` and
  ``T_p`` as the scales of both, so ``ratio = Pi1_pulse / Pi1_record =
  u_pulse / u_record``;
* :func:`ratio_summary` and :func:`summary_markdown` -- how well the pulse
  predicts the peak sliding, per record;
* :func:`pairs_grid` (:func:`record_pairs_dataset` in the pipeline) -- the
  recorded pairs of a suite (by default the 14 FEMA P695 near-field records
  with a pulse) against their fitted pulses: each component on a line, as
  recorded and as its fitted pulse (the paper's Fig. 4 comparison), and the
  pair in the plane, as recorded and as the pair of fitted pulses with their
  relative amplitude, period and lag (``Pi14``, ``Pi15``, ``Pi16``,
  :func:`pair_groups`): ``Pi1`` and the direction of the planar peak;
* :func:`pairs_summary`, :func:`direction_summary`, :func:`fit_table`,
  :func:`ratio_by`, :func:`amplification` and :func:`pairs_findings` -- the
  ratio record/pulse per component and in the plane, whether the fitted pair
  catches the direction of the planar peak and where the fits fail.

Fitted pairs and the record's senses
------------------------------------
A fitted pulse runs positive at its peak (:meth:`PulseFit.as_pulse`) and
``Pi14 >= 0``, so a pair whose two fits have opposite polarities cannot be
written as one scene in the record's senses.  The contents, the friction and
the isolator are isotropic in the plane, so flipping a ground component
mirrors the response: the fitted pair is solved with both pulses positive and
its ``peak_angle`` mirrored by ``diag(polarity_x, polarity_y)``
(:func:`reflect_angle`; ``Pi1`` is unchanged).  The tests check this against a
sampled, sign-flipped pulse.

Stand-in for the paper's record
-------------------------------
The paper's Fig. 4 uses the 1994 Northridge record at Rinaldi Receiving
Station (RRS228), matched with a Ricker wavelet of ``T_p = 1 s``.  That record
is not available offline.  :data:`FIG4_RECORD` stands in for it: Kobe 1995
Takatori 090, a near-fault forward-directivity record with one dominant
long-period pulse (acceleration-fitted Ricker ``T_p = 1.56 s``, the closest
of the bundled records to the paper's 1 s; the two Northridge records shipped
by pyslammer fit to 0.46-0.47 s).
"""

from __future__ import annotations

import copy
import math
from pathlib import Path

import numpy as np
import xarray as xr

from .. import records as _rec
from ..records import G, Record, canonical_shape
from ..datasets import global_attrs
from ..scene import Scene
from .solving import batch_solver

__all__ = ["COMPONENTS", "FIG4_RECORD", "PAIR_SUITE", "STAND_IN_FOR", "SUMMARY_VIEWS", "VIEWS", "amplification",
           "check_pairs_settings", "compare_grid", "direction_summary", "fig4_data", "fig4_dataset", "fit_table",
           "line_angle", "pair_groups", "pair_pulses", "pair_scenes", "pairs_findings", "pairs_grid",
           "pairs_settings", "pairs_summary", "ratio_by", "ratio_summary", "record_dataset", "record_pairs_dataset",
           "records_dataset", "records_settings", "reflect_angle", "resolve_record", "select_motions",
           "sense_angle", "summary_markdown"]

FIG4_RECORD = "Kobe_1995_TAK-090"
"""pyslammer sample that stands in for the paper's Rinaldi record in Fig. 4."""

STAND_IN_FOR = "1994 Northridge, Rinaldi Receiving Station 228 (RRS228), not available offline"

_FIT_VARS = {
    "a_p": ("fitted pulse acceleration amplitude a_p", "m s-2"),
    "a_p_g": ("fitted pulse acceleration amplitude a_p in units of g", "1"),
    "T_p": ("fitted pulse period T_p", "s"),
    "t_peak": ("record time of the fitted pulse peak", "s"),
    "t_ref": ("record time of tau = 0", "s"),
    "polarity": ("sign of the fitted pulse at its peak", "1"),
    "r2": ("R^2 of the fit over the pulse window (uncentred)", "1"),
    "nrmse": ("RMS residual over the pulse window / a_p", "1"),
    "energy_fraction": ("share of the record's sum(a^2) captured by the pulse", "1"),
}
"""The fitted pulse's variables in the record datasets: name -> (long name, CF units)."""


def resolve_record(rec) -> Record:
    """A :class:`~isoslide.records.Record` from a record, a sample name or a file path.

    Parameters
    ----------
    rec : Record or str or Path
        A record; a name (or unique part of one) from
        :func:`isoslide.records.samples`; or a path to an ``.AT2`` or
        ``.csv`` file.
    """
    if isinstance(rec, Record):
        return rec
    p = Path(str(rec))
    if p.suffix.lower() in (".at2", ".csv") and p.is_file():
        return _rec.read_at2(p) if p.suffix.lower() == ".at2" else _rec.read_csv(p)
    return _rec.sample(str(rec))


def _fit_values(fit) -> dict:
    """The variables :data:`_FIT_VARS` of a :class:`~isoslide.records.PulseFit`, as floats (their units)."""
    return {k: float(getattr(fit, k)) for k in _FIT_VARS}


def _add_fit_vars(ds: xr.Dataset, dims, values: dict) -> None:
    """Store ``values[k]`` over ``dims`` for every ``k`` of :data:`_FIT_VARS`, with its long name and units."""
    for k, (long_name, units) in _FIT_VARS.items():
        ds[k] = (dims, values[k], {"long_name": long_name, "units": units})


def _fit_attrs(fit, prefix: str = "") -> dict:
    out = {f"{prefix}shape": fit.shape}
    for k, v in _fit_values(fit).items():
        out[f"{prefix}{k}"] = v
    for k, v in fit.params:
        out[f"{prefix}{k}"] = float(v)
    return out


def fig4_data(record_name=FIG4_RECORD, shapes=("ricker", "mavroeidis_papageorgiou"),
              t_before: float = 4.0, t_after: float = 6.0) -> xr.Dataset:
    """Data of Fig. 4: a record's acceleration and velocity with its fitted pulse(s).

    Parameters
    ----------
    record_name : Record or str or Path
        See :func:`resolve_record`; default :data:`FIG4_RECORD`.
    shapes : sequence of str
        Fitted shapes to include; the Ricker is always included first.
    t_before, t_after : float
        Suggested plot window, in Ricker periods before and after the fitted
        peak (attributes ``t_plot_min``, ``t_plot_max``; the data cover the
        whole record).

    Returns
    -------
    xarray.Dataset
        Coordinate ``time`` (s, record time) and ``tau`` (``(t - t_peak) /
        T_p`` of the Ricker fit); variables ``accel_record`` (g),
        ``velocity_record`` (m/s, trapezoidal integral from rest),
        ``accel_<shape>`` (g) and ``velocity_<shape>`` (m/s) of each fitted
        shape (``ricker``, ``mp``).  Attributes: record metadata and every fit
        value, prefixed ``ricker_`` / ``mp_``.
    """
    rec = resolve_record(record_name)
    shapes = ["ricker"] + [s for s in (canonical_shape(x) for x in shapes) if s != "ricker"]
    t = rec.time
    rick = rec.fit("ricker")
    ds = xr.Dataset(coords={
        "time": ("time", t, {"long_name": "record time", "units": "s"}),
        "tau": ("time", (t - rick.t_peak) / rick.T_p,
                {"long_name": "dimensionless time (t - t_peak)/T_p of the Ricker fit", "units": "1"}),
    })
    ds["accel_record"] = ("time", np.asarray(rec.accel),
                          {"long_name": f"ground acceleration, {rec.name}", "units": "g"})
    ds["velocity_record"] = ("time", rec.velocity(),
                             {"long_name": f"ground velocity, {rec.name} (integrated from rest)",
                              "units": "m s-1"})
    attrs = {
        "title": "Fig. 4: real pulse-like record and its fitted analytical pulse",
        "record": rec.name, "event": rec.event, "station": rec.station, "component": rec.component,
        "source": rec.source, "licence": rec.licence, "dt": rec.dt, "pga_g": rec.pga,
        "pgv": rec.pgv, "stand_in_for": STAND_IN_FOR if rec.name == FIG4_RECORD else "",
        "g": G, "t_plot_min": rick.t_peak - t_before * rick.T_p,
        "t_plot_max": rick.t_peak + t_after * rick.T_p,
    }
    for shape in shapes:
        fit = rec.fit(shape)
        key = "ricker" if shape == "ricker" else "mp"
        label = "Ricker wavelet" if shape == "ricker" else "Mavroeidis-Papageorgiou pulse"
        ds[f"accel_{key}"] = ("time", fit.accel(t) / G,
                              {"long_name": f"fitted {label} acceleration", "units": "g"})
        ds[f"velocity_{key}"] = ("time", fit.velocity(t),
                                 {"long_name": f"fitted {label} velocity (from rest)", "units": "m s-1"})
        attrs.update(_fit_attrs(fit, prefix=f"{key}_"))
    ds.attrs.update(attrs)
    return ds


def _grid_values(arg: str, kind: str, names: list, pi2_values, pi3_values) -> tuple:
    """The Pi2 and Pi3 values of a grid as flat float arrays, checked with the names of its rows.

    Parameters
    ----------
    arg : str
        The argument that gives the rows (``names``, ``motions``), as the errors call it.
    kind : str
        What a row is (``record``, ``motion``), as the errors call it.
    names : list of str
        The names of the rows (records or ground motions), in order.
    pi2_values, pi3_values : array_like of float
        The grid's Pi2 and Pi3 values.

    Returns
    -------
    (pi2_values, pi3_values) : tuple of ndarray

    Raises
    ------
    ValueError
        When there are no rows, no Pi2 or no Pi3 values, or two rows have the same name.
    """
    pi2_values = np.asarray(pi2_values, dtype=float).ravel()
    pi3_values = np.asarray(pi3_values, dtype=float).ravel()
    if len(names) == 0 or pi2_values.size == 0 or pi3_values.size == 0:
        raise ValueError(f"{arg}, pi2_values and pi3_values must all be non-empty")
    if len(set(names)) != len(names):
        raise ValueError(f"{kind} names must be unique, got {names}")
    return pi2_values, pi3_values


def compare_grid(names, pi2_values, pi3_values, pi4: float = 0.1, pi5: float = 1.0, pi6: float = 0.0,
                 pi7: float = 0.0, pi8: float = 1e-5, shape: str = "ricker", rtol=None,
                 solve_many=None) -> xr.Dataset:
    """Peak sliding under each real record and under its fitted pulse, over Pi2 x Pi3.

    For each record the fit of ``shape`` gives ``a_p``, ``T_p`` and the time
    origin; the record (:meth:`Record.as_pulse`) and the fitted pulse
    (:meth:`PulseFit.as_pulse`) are both normalised by them, so
    ``Pi2 = mu_k g / a_p`` and ``Pi3 = T_b / T_p`` describe the same physical
    building under both excitations and the ratio of the two ``Pi1`` is the
    ratio of the physical peak sliding displacements.

    Parameters
    ----------
    names : sequence of (Record or str or Path)
        Records, see :func:`resolve_record`.
    pi2_values, pi3_values : sequence of float
        Grid of ``Pi2 = mu_k g / a_p`` (> 0) and ``Pi3 = T_b / T_p`` (>= 0).
    pi4, pi5, pi6, pi7, pi8 : float
        The other groups, fixed (see :class:`isoslide.Scene`).
    shape : str
        Fitted shape whose scales and pulse are used.
    rtol : float, optional
        Passed to the solver.
    solve_many : callable, optional
        The batch solver (:mod:`isoslide.studies.solving`); of its answers the grid reads
        ``pi1``, and ``settled`` where they have it.

    Returns
    -------
    xarray.Dataset
        Dims ``(record, pi2, pi3)``: ``pi1_record``, ``pi1_pulse``, ``ratio``
        (``pi1_pulse / pi1_record``; NaN where ``pi1_record = 0``),
        ``slides_record``, ``slides_pulse`` (bool), ``settled_record``,
        ``settled_pulse`` (bool, if the solver reports it).  Per record: the
        fit values (``a_p`` [m/s^2], ``T_p`` [s], ``t_peak`` [s], ``r2``, ...),
        ``pga`` [g], ``pgv`` [m/s], ``duration`` [s].
    """
    solve_many = batch_solver(solve_many)
    recs = [resolve_record(n) for n in names]
    names_out = [r.name for r in recs]
    pi2_values, pi3_values = _grid_values("names", "record", names_out, pi2_values, pi3_values)
    shape = canonical_shape(shape)
    nr, n2, n3 = len(recs), pi2_values.size, pi3_values.size
    pi1_rec = np.full((nr, n2, n3), np.nan)
    pi1_pul = np.full((nr, n2, n3), np.nan)
    set_rec = np.zeros((nr, n2, n3), dtype=bool)
    set_pul = np.zeros((nr, n2, n3), dtype=bool)
    has_settled = True
    per_rec = {k: np.full(nr, np.nan) for k in _FIT_VARS}
    extra = {"pga": np.zeros(nr), "pgv": np.zeros(nr), "duration": np.zeros(nr), "dt": np.zeros(nr)}
    for i, rec in enumerate(recs):
        fit = rec.fit(shape)
        p_rec = rec.as_pulse(shape=shape)
        p_fit = fit.as_pulse()
        scenes = []
        for pulse in (p_rec, p_fit):
            for pi2 in pi2_values:
                for pi3 in pi3_values:
                    scenes.append(Scene(pi2=pi2, pi3=pi3, pi4=pi4, pi5=pi5, pi6=pi6, pi7=pi7, pi8=pi8,
                                        pulse=pulse))
        batch = solve_many(scenes, rtol=rtol)
        pi1 = np.asarray(batch.pi1, dtype=float).reshape(2, n2, n3)
        pi1_rec[i], pi1_pul[i] = pi1
        settled = getattr(batch, "settled", None)
        if settled is None:
            has_settled = False
        else:
            set_rec[i], set_pul[i] = np.asarray(settled, dtype=bool).reshape(2, n2, n3)
        for k, v in _fit_values(fit).items():
            per_rec[k][i] = v
        extra["pga"][i], extra["pgv"][i] = rec.pga, rec.pgv
        extra["duration"][i], extra["dt"][i] = rec.duration, rec.dt

    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(pi1_rec > 0, pi1_pul / np.where(pi1_rec > 0, pi1_rec, 1.0), np.nan)
    dims = ("record", "pi2", "pi3")
    ds = xr.Dataset(coords={
        "record": ("record", np.array(names_out, dtype=object), {"long_name": "record name"}),
        "pi2": ("pi2", pi2_values, {"long_name": "Pi2 = mu_k g / a_p (fitted a_p)", "units": "1"}),
        "pi3": ("pi3", pi3_values, {"long_name": "Pi3 = T_b / T_p (fitted T_p)", "units": "1"}),
    })
    ds["pi1_record"] = (dims, pi1_rec, {"long_name": "Pi1 = u_max/(a_p T_p^2) under the real record",
                                        "units": "1"})
    ds["pi1_pulse"] = (dims, pi1_pul, {"long_name": f"Pi1 = u_max/(a_p T_p^2) under the fitted {shape} pulse",
                                       "units": "1"})
    ds["ratio"] = (dims, ratio, {"long_name": "pi1_pulse / pi1_record (NaN where the record gives no sliding)",
                                 "units": "1"})
    ds["slides_record"] = (dims, pi1_rec > 0, {"long_name": "contents slide under the record"})
    ds["slides_pulse"] = (dims, pi1_pul > 0, {"long_name": "contents slide under the fitted pulse"})
    if has_settled:
        ds["settled_record"] = (dims, set_rec, {"long_name": "response settled within the horizon (record)"})
        ds["settled_pulse"] = (dims, set_pul, {"long_name": "response settled within the horizon (pulse)"})
    _add_fit_vars(ds, "record", per_rec)
    ds["pga"] = ("record", extra["pga"], {"long_name": "peak ground acceleration of the record", "units": "g"})
    ds["pgv"] = ("record", extra["pgv"], {"long_name": "peak ground velocity of the record", "units": "m s-1"})
    ds["duration"] = ("record", extra["duration"], {"long_name": "record duration", "units": "s"})
    ds["dt"] = ("record", extra["dt"], {"long_name": "record sampling interval", "units": "s"})
    ds.attrs.update({
        "title": "Peak sliding under real pulse-like records and under their fitted pulses",
        "shape": shape, "pi4": float(pi4), "pi5": float(pi5), "pi6": float(pi6), "pi7": float(pi7),
        "pi8": float(pi8), "rtol": "default" if rtol is None else float(rtol), "g": G,
        "scales": "a_p and T_p of each record's fitted pulse normalise both the record and the pulse",
        "sources": "; ".join(sorted({r.source.split(':')[0] + ': ' + r.licence for r in recs if r.licence})),
    })
    return ds


def ratio_summary(ds: xr.Dataset, tolerance: float = 0.25) -> xr.Dataset:
    """How well the fitted pulse predicts the record's peak sliding, per record.

    Parameters
    ----------
    ds : xarray.Dataset
        Output of :func:`compare_grid`.
    tolerance : float
        Relative band for ``within_tol``: ``|ratio - 1| <= tolerance``.

    Returns
    -------
    xarray.Dataset
        Per ``record`` (and ``"all"``): ``n_cells``; ``n_both_slide``;
        ``n_both_still`` (neither slides); ``n_only_record`` / ``n_only_pulse``
        (only one slides: the pulse misses or invents sliding);
        ``median_ratio``, ``gmean_ratio`` (geometric mean), ``p10_ratio``,
        ``p90_ratio``, ``min_ratio``, ``max_ratio`` over cells where both
        slide; ``within_tol`` (share of those cells within the band).
    """
    rows = {}
    labels = [str(r) for r in ds["record"].values] + ["all"]
    for lab in labels:
        sub = ds if lab == "all" else ds.sel(record=lab)
        sr = np.asarray(sub["slides_record"].values, bool).ravel()
        sp = np.asarray(sub["slides_pulse"].values, bool).ravel()
        r = np.asarray(sub["ratio"].values, float).ravel()
        both = sr & sp
        rb = r[both]
        stats = {
            "n_cells": sr.size, "n_both_slide": int(both.sum()), "n_both_still": int((~sr & ~sp).sum()),
            "n_only_record": int((sr & ~sp).sum()), "n_only_pulse": int((~sr & sp).sum()),
        }
        if rb.size:
            lr = np.log(rb)
            stats.update(median_ratio=float(np.median(rb)), gmean_ratio=float(np.exp(lr.mean())),
                         p10_ratio=float(np.percentile(rb, 10)), p90_ratio=float(np.percentile(rb, 90)),
                         min_ratio=float(rb.min()), max_ratio=float(rb.max()),
                         within_tol=float(np.mean(np.abs(rb - 1.0) <= tolerance)))
        else:
            stats.update(median_ratio=math.nan, gmean_ratio=math.nan, p10_ratio=math.nan,
                         p90_ratio=math.nan, min_ratio=math.nan, max_ratio=math.nan, within_tol=math.nan)
        rows[lab] = stats
    out = xr.Dataset(coords={"record": ("record", np.array(labels, dtype=object))})
    for k in next(iter(rows.values())):
        out[k] = ("record", np.array([rows[lab][k] for lab in labels]))
    out.attrs.update({"tolerance": float(tolerance),
                      "ratio": "pi1_pulse / pi1_record = u_pulse / u_record (same a_p, T_p)"})
    return out


def summary_markdown(ds: xr.Dataset, tolerance: float = 0.25) -> str:
    """A markdown table of :func:`ratio_summary` with the fit of each record.

    Parameters
    ----------
    ds : xarray.Dataset
        Output of :func:`compare_grid`.
    tolerance : float
        Band for the "within" column.

    Returns
    -------
    str
    """
    s = ratio_summary(ds, tolerance)
    lines = [
        f"| record | a_p [g] | T_p [s] | R^2 | cells both slide | only record / only pulse | "
        f"median ratio | P10-P90 ratio | within +-{tolerance:.0%} |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for lab in s["record"].values:
        row = s.sel(record=lab)
        if lab == "all":
            fit = ["", "", ""]
        else:
            d = ds.sel(record=lab)
            fit = [f"{float(d['a_p_g']):.3f}", f"{float(d['T_p']):.3f}", f"{float(d['r2']):.2f}"]
        n = int(row["n_cells"])
        cells = [str(lab), *fit, f"{int(row['n_both_slide'])}/{n}",
                 f"{int(row['n_only_record'])} / {int(row['n_only_pulse'])}",
                 f"{float(row['median_ratio']):.2f}",
                 f"{float(row['p10_ratio']):.2f}-{float(row['p90_ratio']):.2f}",
                 f"{float(row['within_tol']):.0%}" if np.isfinite(float(row['within_tol'])) else "n/a"]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


# ----------------------------------------------------------------------------------------------
# pipeline datasets (rules fig4_record, record_compare, records_dataset)
# ----------------------------------------------------------------------------------------------

def records_settings(config: dict) -> dict:
    """The sections of a complete configuration (:func:`isoslide.config.load`) the record study reads.

    Returns ``{"records": ..., "defaults": ..., "solver": ...}`` (copies); the schema holds the defaults.
    """
    return {k: copy.deepcopy(config[k]) for k in ("records", "defaults", "solver")}


def _axes(settings: dict):
    rec = settings["records"]
    a = rec["pi2"]
    pi2 = np.linspace(float(a["start"]), float(a["stop"]), int(a["num"]))
    pi3 = np.asarray(rec["pi3"], dtype=float)
    return pi2, pi3


def _groups(settings: dict) -> dict:
    d = settings["defaults"]
    return {"pi4": float(settings["records"]["pi4"]),
            **{k: float(d[k]) for k in ("pi5", "pi6", "pi7", "pi8")}}


def fig4_dataset(settings: dict) -> xr.Dataset:
    """:func:`fig4_data` of the Fig. 4 record ``settings["records"]["fig4"]``, with CF global attributes."""
    ds = fig4_data(settings["records"]["fig4"])
    extra = dict(ds.attrs)
    title = extra.pop("title")
    ds.attrs = global_attrs(
        title=f"isoslide {title}",
        history=f"isoslide.studies.record_study.fig4_data({extra['record']!r}): record read from the installed "
                f"pyslammer package, Ricker and Mavroeidis-Papageorgiou pulses fitted by least squares "
                f"(isoslide.records.fit_pulse)",
        config={"fig4": settings["records"]["fig4"]}, **extra)
    return ds


def record_dataset(name: str, settings: dict) -> xr.Dataset:
    """:func:`compare_grid` of one record over the configured grid (dimension ``record`` of length 1).

    ``settings`` is :func:`records_settings` of a complete configuration.
    """
    pi2, pi3 = _axes(settings)
    rtol = settings["solver"]["rtol"]
    return compare_grid([name], pi2, pi3, rtol=rtol, **_groups(settings))


def records_dataset(parts, settings: dict) -> xr.Dataset:
    """Concatenate per-record :func:`record_dataset` outputs into the records dataset.

    Records follow the configured order; CF global attributes, the ``tolerance`` and the
    summary of :func:`ratio_summary` are added.
    """
    parts = list(parts)
    by_name = {str(p["record"].values[0]): p for p in parts}
    order = [resolve_record(n).name for n in settings["records"]["names"]]
    missing = [n for n in order if n not in by_name]
    if missing:
        raise ValueError(f"records_dataset: no part for record(s) {missing}; parts: {sorted(by_name)}")
    ds = xr.concat([by_name[n] for n in order], dim="record", data_vars="minimal", coords="minimal",
                   combine_attrs="drop_conflicts")
    ds["record"] = ds["record"].astype(str)
    ds["record"].attrs["long_name"] = "record name"
    for v in ("slides_record", "slides_pulse", "settled_record", "settled_pulse"):
        if v in ds:
            ds[v] = ds[v].astype(np.int8).assign_attrs(
                {**ds[v].attrs, "flag_values": np.array([0, 1], np.int8), "flag_meanings": "no yes"})
    tol = float(settings["records"]["tolerance"])
    summ = ratio_summary(ds.assign({v: ds[v].astype(bool) for v in ("slides_record", "slides_pulse")}), tol)
    a = summ.sel(record="all")
    first = parts[0].attrs
    keep = {k: first[k] for k in ("shape", "pi4", "pi5", "pi6", "pi7", "pi8", "rtol", "g", "scales") if k in first}
    sources = sorted({p.attrs.get("sources", "") for p in parts} - {""})
    ds.attrs = global_attrs(
        title="isoslide peak sliding under real pulse-like records and under their fitted pulses",
        history=(f"isoslide.studies.record_study.compare_grid, one job per record ({len(order)} records x "
                 f"{ds.sizes['pi2']} Pi2 x {ds.sizes['pi3']} Pi3), concatenated by "
                 f"isoslide.studies.record_study.records_dataset; no timestamps are stored"),
        config=settings, **keep, tolerance=tol, sources="; ".join(sources),
        fig4_record=(f"{settings['records']['fig4']}" + (f" (stands in for {STAND_IN_FOR})"
                     if resolve_record(settings["records"]["fig4"]).name == FIG4_RECORD else "")),
        summary_median_ratio=float(a["median_ratio"]), summary_p10_ratio=float(a["p10_ratio"]),
        summary_p90_ratio=float(a["p90_ratio"]), summary_within_tol=float(a["within_tol"]),
        summary_n_cells=int(a["n_cells"]), summary_n_both_slide=int(a["n_both_slide"]),
        summary_n_only_record=int(a["n_only_record"]), summary_n_only_pulse=int(a["n_only_pulse"]))
    return ds


# ----------------------------------------------------------------------------------------------
# recorded pairs against their fitted pulses, on a line and in the plane (rule record_pairs)
# ----------------------------------------------------------------------------------------------

PAIR_SUITE = "fema-p695-near-field-pulse"
"""Suite of the recorded pairs: the 14 FEMA P695 near-field records with a velocity pulse."""

COMPONENTS = ("x", "y")
"""The horizontal components of a pair (FEMA P695 components ``a`` and ``b``), the building's axes."""

VIEWS = ("x", "y", "plane")
"""What a pair's summary compares: each component on a line (its own scales), and the pair in the plane."""

def pair_groups(fit_x, fit_y) -> dict:
    """``Pi14``, ``Pi15``, ``Pi16`` of a fitted pair and the polarities of its two pulses.

    Parameters
    ----------
    fit_x, fit_y : PulseFit
        The fits of the two horizontal components (same shape); ``fit_x`` gives the scales.

    Returns
    -------
    dict
        ``pi14 = a_py / a_p``, ``pi15 = T_py / T_p``, ``pi16 = (t_ref,y - t_ref,x) / T_p`` (the lag
        of the y pulse's reference time behind the x pulse's, over ``T_p``; for the Ricker
        ``t_ref`` is the peak) and ``polarity_x``, ``polarity_y`` (+1 or -1: the sign of each
        fitted pulse at its peak in the record's own sense).
    """
    return {"pi14": fit_y.a_p / fit_x.a_p, "pi15": fit_y.T_p / fit_x.T_p,
            "pi16": (fit_y.t_ref - fit_x.t_ref) / fit_x.T_p,
            "polarity_x": int(fit_x.polarity), "polarity_y": int(fit_y.polarity)}


def reflect_angle(angle, polarity_x: int, polarity_y: int):
    """A peak direction (radians) mirrored by ``diag(polarity_x, polarity_y)``; nan stays nan.

    The contents, the friction and the isolator are isotropic in the plane, so flipping the sign
    of one ground component mirrors the whole response: ``Pi1`` is unchanged and the peak's
    direction ``(cos a, sin a)`` becomes ``(polarity_x cos a, polarity_y sin a)``.  A fitted pair
    is solved with both pulses positive at their peaks (``PulseFit.as_pulse``) and its direction
    mirrored by this function into the record's own senses.
    """
    a = np.asarray(angle, dtype=float)
    out = np.arctan2(polarity_y * np.sin(a), polarity_x * np.cos(a))
    return float(out) if out.ndim == 0 else out


def line_angle(angle, reference=0.0):
    """Angle between the line along ``angle`` and the line along ``reference`` (radians, in ``[0, pi/2]``).

    Directions that differ by ``pi`` lie on one line; nan stays nan.
    """
    d = np.abs(np.remainder(np.asarray(angle, dtype=float) - reference + math.pi, 2.0 * math.pi) - math.pi)
    return np.minimum(d, math.pi - d)


def sense_angle(angle, reference=0.0):
    """Angle between the directions ``angle`` and ``reference`` (radians, in ``[0, pi]``); nan stays nan."""
    return np.abs(np.remainder(np.asarray(angle, dtype=float) - reference + math.pi, 2.0 * math.pi) - math.pi)


def select_motions(suite_name: str = PAIR_SUITE, motions="all") -> tuple:
    """Ground motions of a suite that have two horizontal components.

    Parameters
    ----------
    suite_name : str
        A suite of :func:`isoslide.records.suite`.
    motions : "all" or sequence of str
        ``"all"``: every motion of the suite with a ``y`` component, in the suite's order; or
        their names, in the order given.

    Returns
    -------
    tuple of GroundMotion

    Raises
    ------
    ValueError
        A name not in the suite, a name given twice, a motion without a ``y`` component, or none.
    """
    found = _rec.suite(suite_name)
    if isinstance(motions, str):
        if motions != "all":
            raise ValueError(f"motions = {motions!r} is invalid; allowed: 'all' or a list of motion names")
        out = tuple(gm for gm in found if gm.y is not None)
    else:
        names = [str(m) for m in motions]
        if len(set(names)) != len(names):
            raise ValueError(f"motions = {names!r} names a motion twice; allowed: each once")
        by_name = {gm.name: gm for gm in found}
        unknown = [n for n in names if n not in by_name]
        if unknown:
            raise ValueError(f"motions {unknown!r} are not in suite {suite_name!r}; known: {sorted(by_name)}")
        out = tuple(by_name[n] for n in names)
        single = [gm.name for gm in out if gm.y is None]
        if single:
            raise ValueError(f"motions {single!r} of suite {suite_name!r} have one horizontal component; "
                             f"allowed: pairs (x and y)")
    if not out:
        raise ValueError(f"suite {suite_name!r}: no motion with two horizontal components selected")
    return out


def pair_pulses(gm, shape: str = "ricker") -> dict:
    """The excitations of one ground motion: its records as recorded and its fitted pulses.

    Parameters
    ----------
    gm : GroundMotion
        A pair (``x`` and ``y``).
    shape : str
        Fitted pulse shape.

    Returns
    -------
    dict
        ``record_x``, ``record_y`` (each in its own fit's scales), ``plane_x``, ``plane_y`` (both
        in the x fit's scales, on the record's time axis: the pair as recorded), ``pulse_x``,
        ``pulse_y`` (the fitted pulses, positive at their peaks) as
        :class:`~isoslide.pulses.Pulse` s, and the groups of :func:`pair_groups`.
    """
    shape = canonical_shape(shape)
    fits = {c: getattr(gm, c).fit(shape) for c in COMPONENTS}
    fx = fits["x"]
    out = {}
    for c in COMPONENTS:
        rec = getattr(gm, c)
        out[f"record_{c}"] = rec.as_pulse(a_p=fits[c].a_p, T_p=fits[c].T_p)
        out[f"plane_{c}"] = rec.as_pulse(a_p=fx.a_p, T_p=fx.T_p)
        out[f"pulse_{c}"] = fits[c].as_pulse()
    return out | pair_groups(fx, fits["y"])


def pair_scenes(gm, pi2: float, pi3: float, shape: str = "ricker", pulses: dict | None = None, **groups) -> dict:
    """The scenes of one ground motion at one ``(Pi2, Pi3)``: records as recorded and their fitted pulses.

    Parameters
    ----------
    gm : GroundMotion
        A pair (``x`` and ``y``).
    pi2, pi3 : float
        ``Pi2 = mu_k g / a_p`` and ``Pi3 = T_b / T_p``, in the scales of the run (below).
    shape : str
        Fitted pulse shape.
    pulses : dict, optional
        :func:`pair_pulses` of ``gm`` and ``shape``, when at hand.
    **groups
        The other groups (``pi4`` ... ``pi8``) of :class:`isoslide.Scene`.

    Returns
    -------
    dict
        ``{"x": (record, pulse), "y": (record, pulse), "plane": (record pair, fitted pair)}`` of
        scenes.  On a line each component runs as recorded and as its fitted pulse, both in the
        scales (``a_p``, ``T_p``) of that component's fit.  In the plane, in the x fit's scales:
        the pair as recorded (as ``Scene(pulse=gm.x, pulse_y=gm.y)`` runs it), and the two fitted
        pulses with :func:`pair_groups`' ``Pi14``, ``Pi15``, ``Pi16``, each positive at its peak:
        mirror the fitted pair's ``peak_angle`` by :func:`reflect_angle` with the fits' polarities.
    """
    p = pair_pulses(gm, shape) if pulses is None else pulses
    out = {c: (Scene(pi2=pi2, pi3=pi3, pulse=p[f"record_{c}"], **groups),
               Scene(pi2=pi2, pi3=pi3, pulse=p[f"pulse_{c}"], **groups)) for c in COMPONENTS}
    out["plane"] = (
        Scene(pi2=pi2, pi3=pi3, pulse=p["plane_x"], pulse_y=p["plane_y"], **groups),
        Scene(pi2=pi2, pi3=pi3, pulse=p["pulse_x"], pulse_y=p["pulse_y"], pi14=p["pi14"], pi15=p["pi15"],
              pi16=p["pi16"], **groups),
    )
    return out


def _over(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``a / b``; +inf where only ``a`` is positive, nan where neither is."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(b > 0.0, a / np.where(b > 0.0, b, 1.0), np.where(a > 0.0, np.inf, np.nan))


def _flag(values, long_name: str) -> tuple:
    return np.asarray(values, dtype=bool).astype(np.int8), {
        "long_name": long_name, "flag_values": np.array([0, 1], np.int8), "flag_meanings": "no yes"}


def _pulse_flag(value) -> int:
    return -1 if value is None else int(bool(value))


def pairs_grid(motions, pi2_values, pi3_values, pi4: float = 0.1, pi5: float = 1.0, pi6: float = 0.0,
               pi7: float = 0.0, pi8: float = 1e-5, shape: str = "ricker", rtol=None,
               solve_many=None) -> xr.Dataset:
    """Peak sliding under recorded pairs and under their fitted pulses, on a line and in the plane.

    For every ground motion and ``(Pi2, Pi3)`` the scenes of :func:`pair_scenes` are solved: each
    component as recorded and as its fitted pulse (the paper's Fig. 4 comparison, in that
    component's own scales), and in the plane the pair as recorded and the pair of fitted pulses
    (in the x fit's scales).  The ratio of two ``Pi1`` in one scale is the ratio of the physical
    peak sliding displacements.

    Parameters
    ----------
    motions : sequence of GroundMotion
        Pairs (see :func:`select_motions`), unique names.
    pi2_values, pi3_values : sequence of float
        ``Pi2 = mu_k g / a_p`` (> 0) and ``Pi3 = T_b / T_p`` (>= 0; 0 is a fixed base).
    pi4, pi5, pi6, pi7, pi8 : float
        The other groups, fixed (see :class:`isoslide.Scene`).
    shape : str
        Fitted pulse shape.
    rtol : float, optional
        Passed to the solver.
    solve_many : callable, optional
        The batch solver (:mod:`isoslide.studies.solving`); of its answers the grid reads
        ``pi1``, ``peak_angle`` and ``settled``.

    Returns
    -------
    xarray.Dataset
        Over ``(motion, component, pi2, pi3)``: ``pi1_record``, ``pi1_pulse``,
        ``record_over_pulse`` (``pi1_record / pi1_pulse``: +inf where only the record slides,
        nan where neither does), ``settled_record``, ``settled_pulse``.  Over ``(motion, pi2,
        pi3)``: ``pi1_record_plane``, ``pi1_pulse_plane``, ``record_over_pulse_plane``,
        ``peak_angle_record``, ``peak_angle_pulse`` (rad, building axes, the record's own senses),
        ``angle_off_line`` (rad, in ``[0, pi/2]``: between the lines of the two peaks),
        ``angle_off`` (rad, in ``[0, pi]``: between their directions), the settled flags.  Over
        ``(motion, component)``: the fit values, ``record`` (the component's name), ``pga`` (g),
        ``pgv`` (m/s), ``duration`` (s), ``dt`` (s), ``peak_over_a_p`` (PGA over the fitted
        ``a_p``).  Over ``motion``: ``pi14``, ``pi15``, ``pi16`` and metadata (event, station,
        ``rsn``, magnitude, distance, ``pulse``).
    """
    solve_many = batch_solver(solve_many)
    motions = list(motions)
    names = [gm.name for gm in motions]
    pi2_values, pi3_values = _grid_values("motions", "motion", names, pi2_values, pi3_values)
    missing_y = [gm.name for gm in motions if gm.y is None]
    if missing_y:
        raise ValueError(f"motions {missing_y!r} have no y component; allowed: pairs")
    shape = canonical_shape(shape)
    groups = {"pi4": pi4, "pi5": pi5, "pi6": pi6, "pi7": pi7, "pi8": pi8}
    nm, n2, n3, nc = len(motions), pi2_values.size, pi3_values.size, len(COMPONENTS)
    line = {k: np.full((nm, nc, n2, n3), np.nan) for k in ("pi1_record", "pi1_pulse")}
    line_set = {k: np.zeros((nm, nc, n2, n3), bool) for k in ("record", "pulse")}
    plane = {k: np.full((nm, n2, n3), np.nan) for k in ("pi1_record", "pi1_pulse", "angle_record", "angle_pulse")}
    plane_set = {k: np.zeros((nm, n2, n3), bool) for k in ("record", "pulse")}
    fit_vals = {k: np.full((nm, nc), np.nan) for k in _FIT_VARS}
    comp = {k: np.full((nm, nc), np.nan) for k in ("pga", "pgv", "duration", "dt")}
    comp_names = np.empty((nm, nc), dtype=object)
    per_motion = {k: np.full(nm, np.nan) for k in ("pi14", "pi15", "pi16", "magnitude", "rupture_distance_km",
                                                   "vs30_m_s")}
    meta_int = {k: np.zeros(nm, dtype=np.int32) for k in ("rsn", "year")}
    meta_str = {k: np.empty(nm, dtype=object) for k in ("event", "station", "site_class", "fault_type")}
    pulse_flag = np.zeros(nm, dtype=np.int8)
    licences = set()
    for i, gm in enumerate(motions):
        fits = {c: getattr(gm, c).fit(shape) for c in COMPONENTS}
        g = pair_pulses(gm, shape)
        scenes, index = [], []
        for j, pi2 in enumerate(pi2_values):
            for k, pi3 in enumerate(pi3_values):
                cell = pair_scenes(gm, pi2, pi3, shape=shape, pulses=g, **groups)
                for view in VIEWS:
                    for which, sc in zip(("record", "pulse"), cell[view], strict=True):
                        scenes.append(sc)
                        index.append((view, which, j, k))
        batch = solve_many(scenes, rtol=rtol)
        pi1 = np.asarray(batch.pi1, dtype=float)
        angle = np.asarray(getattr(batch, "peak_angle", np.full(len(scenes), np.nan)), dtype=float)
        settled = np.asarray(getattr(batch, "settled", np.zeros(len(scenes), bool)), dtype=bool)
        for n, (view, which, j, k) in enumerate(index):
            if view == "plane":
                plane[f"pi1_{which}"][i, j, k] = pi1[n]
                plane[f"angle_{which}"][i, j, k] = (angle[n] if which == "record" else
                                                    reflect_angle(angle[n], g["polarity_x"], g["polarity_y"]))
                plane_set[which][i, j, k] = settled[n]
            else:
                c = COMPONENTS.index(view)
                line[f"pi1_{which}"][i, c, j, k] = pi1[n]
                line_set[which][i, c, j, k] = settled[n]
        for c, label in enumerate(COMPONENTS):
            rec, fit = getattr(gm, label), fits[label]
            for key, v in _fit_values(fit).items():
                fit_vals[key][i, c] = v
            comp["pga"][i, c], comp["pgv"][i, c] = rec.pga, rec.pgv
            comp["duration"][i, c], comp["dt"][i, c] = rec.duration, rec.dt
            comp_names[i, c] = rec.name
            if rec.licence:
                licences.add(rec.source.split(":")[0] + ": " + rec.licence)
        for key in ("pi14", "pi15", "pi16"):
            per_motion[key][i] = g[key]
        m = gm.metadata
        for key in ("magnitude", "rupture_distance_km", "vs30_m_s"):
            per_motion[key][i] = float(m.get(key, math.nan))
        for key in meta_int:
            meta_int[key][i] = int(m.get(key, -1))
        for key in meta_str:
            meta_str[key][i] = str(m.get(key, ""))
        pulse_flag[i] = _pulse_flag(gm.pulse)

    one = {"units": "1"}
    ds = xr.Dataset(coords={
        "motion": ("motion", np.array(names, dtype=object), {"long_name": "ground motion (a recorded pair)"}),
        "component": ("component", np.array(COMPONENTS, dtype=object),
                      {"long_name": "horizontal component: x = the suite's component a, y = its component b "
                                    "(the building's axes)"}),
        "pi2": ("pi2", pi2_values, {"long_name": "Pi2 = mu_k g / a_p (fitted a_p: the component's on a line, "
                                                 "the x component's in the plane)", **one}),
        "pi3": ("pi3", pi3_values, {"long_name": "Pi3 = T_b / T_p (fitted T_p: the component's on a line, "
                                                 "the x component's in the plane); 0 is a fixed base", **one}),
    })
    d_line, d_plane = ("motion", "component", "pi2", "pi3"), ("motion", "pi2", "pi3")
    ds["pi1_record"] = (d_line, line["pi1_record"], {
        "long_name": "Pi1 = u_max/(a_p T_p^2) under the component as recorded, on a line (its own fit's scales)",
        **one})
    ds["pi1_pulse"] = (d_line, line["pi1_pulse"], {
        "long_name": f"Pi1 = u_max/(a_p T_p^2) under the component's fitted {shape} pulse, on a line", **one})
    ds["record_over_pulse"] = (d_line, _over(line["pi1_record"], line["pi1_pulse"]), {
        "long_name": "pi1_record / pi1_pulse = u_record / u_pulse on a line", **one,
        "comment": "+inf where only the record makes the contents slide, nan where neither does"})
    for which in ("record", "pulse"):
        ds[f"settled_{which}"] = (d_line, *_flag(line_set[which], f"response settled within the horizon ({which}, "
                                                                   "on a line)"))
    ds["pi1_record_plane"] = (d_plane, plane["pi1_record"], {
        "long_name": "Pi1 = peak |u|/(a_p T_p^2) in the plane under the pair as recorded (the x fit's scales)",
        **one})
    ds["pi1_pulse_plane"] = (d_plane, plane["pi1_pulse"], {
        "long_name": f"Pi1 = peak |u|/(a_p T_p^2) in the plane under the pair of fitted {shape} pulses "
                     "(Pi14, Pi15, Pi16 of the two fits)", **one})
    ds["record_over_pulse_plane"] = (d_plane, _over(plane["pi1_record"], plane["pi1_pulse"]), {
        "long_name": "pi1_record_plane / pi1_pulse_plane = u_record / u_pulse in the plane", **one,
        "comment": "+inf where only the recorded pair makes the contents slide, nan where neither does"})
    angle_attrs = {"units": "rad", "comment": "atan2(u_y, u_x) at the peak of |u|, in (-pi, pi]; nan where the "
                                              "contents do not slide"}
    ang_r = np.where(plane["pi1_record"] > 0.0, plane["angle_record"], np.nan)
    ang_p = np.where(plane["pi1_pulse"] > 0.0, plane["angle_pulse"], np.nan)
    ds["peak_angle_record"] = (d_plane, ang_r, {"long_name": "direction of the peak sliding displacement under "
                                                             "the pair as recorded, building axes", **angle_attrs})
    ds["peak_angle_pulse"] = (d_plane, ang_p, {
        "long_name": "direction of the peak sliding displacement under the fitted pair, building axes, in the "
                     "record's senses (solved with both pulses positive, mirrored by diag(polarity_x, polarity_y))",
        **angle_attrs})
    ds["angle_off_line"] = (d_plane, line_angle(ang_p, ang_r), {
        "long_name": "angle between the lines of the two peaks (fitted pair against recorded pair)", "units": "rad",
        "comment": "in [0, pi/2]; nan where either does not slide"})
    ds["angle_off"] = (d_plane, sense_angle(ang_p, ang_r), {
        "long_name": "angle between the directions of the two peaks (fitted pair against recorded pair)",
        "units": "rad", "comment": "in [0, pi]; nan where either does not slide"})
    for which in ("record", "pulse"):
        ds[f"settled_{which}_plane"] = (d_plane, *_flag(plane_set[which], "response settled within the horizon "
                                                                          f"({which}, in the plane)"))
    d_comp = ("motion", "component")
    ds["record"] = (d_comp, comp_names.astype(str), {"long_name": "name of the component's record"})
    _add_fit_vars(ds, d_comp, fit_vals)
    ds["pga"] = (d_comp, comp["pga"], {"long_name": "peak ground acceleration of the component", "units": "g"})
    ds["pgv"] = (d_comp, comp["pgv"], {"long_name": "peak ground velocity of the component", "units": "m s-1"})
    ds["duration"] = (d_comp, comp["duration"], {"long_name": "record duration", "units": "s"})
    ds["dt"] = (d_comp, comp["dt"], {"long_name": "record sampling interval", "units": "s"})
    ds["peak_over_a_p"] = (d_comp, comp["pga"] / fit_vals["a_p_g"], {
        "long_name": "peak ground acceleration of the component over its fitted a_p", **one})
    ds["pi14"] = ("motion", per_motion["pi14"], {"long_name": "Pi14 = a_py / a_p of the fitted pair", **one})
    ds["pi15"] = ("motion", per_motion["pi15"], {"long_name": "Pi15 = T_py / T_p of the fitted pair", **one})
    ds["pi16"] = ("motion", per_motion["pi16"], {
        "long_name": "Pi16 = (t_ref,y - t_ref,x) / T_p of the fitted pair: the y pulse's lag", **one})
    ds["magnitude"] = ("motion", per_motion["magnitude"], {"long_name": "moment magnitude", **one})
    ds["rupture_distance_km"] = ("motion", per_motion["rupture_distance_km"],
                                 {"long_name": "closest distance to the rupture plane", "units": "km"})
    ds["vs30_m_s"] = ("motion", per_motion["vs30_m_s"], {"long_name": "site Vs30", "units": "m s-1"})
    ds["rsn"] = ("motion", meta_int["rsn"], {"long_name": "PEER NGA record sequence number (-1: none)"})
    ds["year"] = ("motion", meta_int["year"], {"long_name": "year of the earthquake (-1: unknown)"})
    for key, ln in (("event", "earthquake"), ("station", "recording station"), ("site_class", "NEHRP site class"),
                    ("fault_type", "fault type")):
        ds[key] = ("motion", meta_str[key].astype(str), {"long_name": ln})
    ds["pulse"] = ("motion", pulse_flag, {"long_name": "classified as pulse-like by its suite",
                                          "flag_values": np.array([-1, 0, 1], np.int8),
                                          "flag_meanings": "not_classified no yes"})
    ds.attrs.update({
        "title": "Peak sliding under recorded pairs and under their fitted pulses, on a line and in the plane",
        "shape": shape, "pi4": float(pi4), "pi5": float(pi5), "pi6": float(pi6), "pi7": float(pi7),
        "pi8": float(pi8), "rtol": "default" if rtol is None else float(rtol), "g": G,
        "scales": "on a line each component's fitted a_p and T_p normalise both its record and its pulse; in the "
                  "plane the x component's normalise both pairs",
        "sources": "; ".join(sorted(licences)),
    })
    return ds


# ----------------------------------------------------------------------------------------------
# what the recorded pairs say (the report reads these, from the dataset only)
# ----------------------------------------------------------------------------------------------

SUMMARY_VIEWS = ("x", "y", "line", "plane")
"""Views of :func:`pairs_summary`: each component on a line, both components pooled, the plane."""

DEG = 180.0 / math.pi


def _view(ds: xr.Dataset, view: str) -> tuple:
    """``(pi1_record, pi1_pulse)`` arrays of one view (``x``, ``y``, ``line`` or ``plane``)."""
    if view == "plane":
        return ds["pi1_record_plane"].values, ds["pi1_pulse_plane"].values
    sub = ds if view == "line" else ds.sel(component=view)
    return sub["pi1_record"].values, sub["pi1_pulse"].values


def _stats(rec: np.ndarray, pul: np.ndarray, tolerance: float) -> dict:
    rec, pul = np.asarray(rec, float).ravel(), np.asarray(pul, float).ravel()
    sr, sp = rec > 0.0, pul > 0.0
    both = sr & sp
    out = {"n_cells": int(rec.size), "n_both_slide": int(both.sum()), "n_both_still": int((~sr & ~sp).sum()),
           "n_only_record": int((sr & ~sp).sum()), "n_only_pulse": int((~sr & sp).sum())}
    r = rec[both] / pul[both]
    if r.size:
        out.update(median=float(np.median(r)), gmean=float(np.exp(np.log(r).mean())),
                   p10=float(np.percentile(r, 10)), p90=float(np.percentile(r, 90)), min=float(r.min()),
                   max=float(r.max()), within_tol=float(np.mean(np.abs(r - 1.0) <= tolerance)))
    else:
        out.update({k: math.nan for k in ("median", "gmean", "p10", "p90", "min", "max", "within_tol")})
    return out


def _by_motion(ds: xr.Dataset) -> list:
    """``(label, part)`` of each ground motion of ``ds`` (its selection, ``motion`` kept), then ``("all", ds)``."""
    return [(str(m), ds.sel(motion=[str(m)])) for m in ds["motion"].values] + [("all", ds)]


def _attr_or(ds: xr.Dataset, name: str, value: float | None) -> float:
    """``value``, or the dataset's attribute ``name`` when ``value`` is None, as a float."""
    return float(ds.attrs[name] if value is None else value)


def pairs_summary(ds: xr.Dataset, tolerance: float | None = None) -> xr.Dataset:
    """The ratio record/pulse per view and ground motion: how far the fitted pulses stand in.

    Parameters
    ----------
    ds : xarray.Dataset
        Output of :func:`pairs_grid` (or :func:`record_pairs_dataset`): its ``pi1_record``,
        ``pi1_pulse`` (per component) and ``pi1_record_plane``, ``pi1_pulse_plane``.
    tolerance : float, optional
        Band of ``within_tol``: ``|ratio - 1| <= tolerance``; default the dataset's ``tolerance``
        attribute.

    Returns
    -------
    xarray.Dataset
        Over ``view`` (:data:`SUMMARY_VIEWS`) and ``motion`` (each, then ``"all"``): ``n_cells``,
        ``n_both_slide``, ``n_both_still``, ``n_only_record`` (the pulse misses the sliding),
        ``n_only_pulse`` (the pulse invents it); over the cells where both slide, the ratio
        ``pi1_record / pi1_pulse``'s ``median``, ``gmean`` (geometric mean), ``p10``, ``p90``,
        ``min``, ``max`` and ``within_tol`` (share within the band).
    """
    tolerance = _attr_or(ds, "tolerance", tolerance)
    parts = _by_motion(ds)
    labels = [lab for lab, _ in parts]
    rows = {(view, lab): _stats(*_view(sub, view), tolerance) for view in SUMMARY_VIEWS for lab, sub in parts}
    keys = list(next(iter(rows.values())))
    out = xr.Dataset(coords={"view": ("view", np.array(SUMMARY_VIEWS, dtype=object)),
                             "motion": ("motion", np.array(labels, dtype=object))})
    for k in keys:
        out[k] = (("view", "motion"), np.array([[rows[v, lab][k] for lab in labels] for v in SUMMARY_VIEWS]))
    out.attrs.update({"tolerance": tolerance, "ratio": "pi1_record / pi1_pulse = u_record / u_pulse (one scale)"})
    return out


def direction_summary(ds: xr.Dataset, angle_tolerance: float | None = None) -> xr.Dataset:
    """Whether the fitted pair catches the direction of the planar peak, per ground motion.

    Parameters
    ----------
    ds : xarray.Dataset
        Output of :func:`pairs_grid` (or :func:`record_pairs_dataset`): its ``angle_off_line`` and
        ``angle_off`` [rad].
    angle_tolerance : float, optional
        Degrees: the pair "catches" the peak's line when its line is within this angle of the
        record's; default the dataset's ``angle_tolerance`` attribute.

    Returns
    -------
    xarray.Dataset
        Over ``motion`` (each, then ``"all"``), over the cells where both pairs slide in the
        plane: ``n_both_slide``, ``median_line_off`` and ``p90_line_off`` (degrees between the
        lines of the two peaks), ``within_angle`` (share of cells within ``angle_tolerance``) and
        ``same_sense`` (share where the two peaks also point the same way: less than 90 degrees
        apart).
    """
    tol = _attr_or(ds, "angle_tolerance", angle_tolerance)
    parts = _by_motion(ds)
    cols = {k: [] for k in ("n_both_slide", "median_line_off", "p90_line_off", "within_angle", "same_sense")}
    for _, sub in parts:
        off = sub["angle_off_line"].values.ravel() * DEG
        sense = sub["angle_off"].values.ravel() * DEG
        ok = np.isfinite(off)
        off, sense = off[ok], sense[ok]
        cols["n_both_slide"].append(int(ok.sum()))
        if off.size:
            cols["median_line_off"].append(float(np.median(off)))
            cols["p90_line_off"].append(float(np.percentile(off, 90)))
            cols["within_angle"].append(float(np.mean(off <= tol)))
            cols["same_sense"].append(float(np.mean(sense < 90.0)))
        else:
            for k in ("median_line_off", "p90_line_off", "within_angle", "same_sense"):
                cols[k].append(math.nan)
    out = xr.Dataset(coords={"motion": ("motion", np.array([lab for lab, _ in parts], dtype=object))})
    for k, v in cols.items():
        out[k] = ("motion", np.array(v))
    out.attrs.update({"angle_tolerance": tol, "units_of_angles": "degrees"})
    return out


def ratio_by(ds: xr.Dataset, dim: str) -> xr.Dataset:
    """Median ratio record/pulse per value of ``dim`` (``pi2`` or ``pi3``), on a line and in the plane.

    Over the cells where both slide; ``line`` pools the two components.  Also the counts of
    cells where only the record slides (``only_record_line``, ``only_record_plane``).
    """
    if dim not in ("pi2", "pi3"):
        raise ValueError(f"dim = {dim!r} is invalid; allowed: 'pi2' or 'pi3'")
    out = xr.Dataset(coords={dim: ds[dim].values})
    for view in ("line", "plane"):
        med, only = [], []
        for v in ds[dim].values:
            s = _stats(*_view(ds.sel({dim: [v]}), view), 0.0)
            med.append(s["median"])
            only.append(s["n_only_record"])
        out[f"median_{view}"] = (dim, np.array(med))
        out[f"only_record_{view}"] = (dim, np.array(only))
    return out


def fit_table(ds: xr.Dataset, tolerance: float | None = None):
    """Each component's fit against how well its pulse stands in for it on a line.

    Parameters
    ----------
    ds : xarray.Dataset
        Output of :func:`pairs_grid` (or :func:`record_pairs_dataset`).
    tolerance : float, optional
        Band of ``stands_in``; default the dataset's ``tolerance`` attribute.

    Returns
    -------
    pandas.DataFrame
        One row per ``(motion, component)``, sorted by ``|log median|`` (worst first): ``T_p``
        (s), ``a_p_g``, ``r2``, ``energy_fraction``, ``peak_over_a_p`` (PGA / fitted ``a_p``),
        ``median`` (ratio record/pulse where both slide), ``n_both_slide``, ``n_only_record``,
        ``n_only_pulse`` and ``stands_in`` (the median within ``|median - 1| <= tolerance``).
    """
    import pandas as pd

    tolerance = _attr_or(ds, "tolerance", tolerance)
    rows = []
    for m in ds["motion"].values:
        for c in ds["component"].values:
            sub = ds.sel(motion=m, component=c)
            s = _stats(sub["pi1_record"].values, sub["pi1_pulse"].values, tolerance)
            rows.append({"motion": str(m), "component": str(c), "T_p": float(sub["T_p"]),
                         "a_p_g": float(sub["a_p_g"]), "r2": float(sub["r2"]),
                         "energy_fraction": float(sub["energy_fraction"]),
                         "peak_over_a_p": float(sub["peak_over_a_p"]), "median": s["median"],
                         "n_both_slide": s["n_both_slide"], "n_only_record": s["n_only_record"],
                         "n_only_pulse": s["n_only_pulse"],
                         "stands_in": bool(np.isfinite(s["median"]) and abs(s["median"] - 1.0) <= tolerance)})
    df = pd.DataFrame(rows).set_index(["motion", "component"])
    order = np.argsort(-np.abs(np.log(df["median"].to_numpy(dtype=float))), kind="stable")
    return df.iloc[order]


def _spearman(a, b) -> float:
    """Spearman's rank correlation of ``a`` and ``b`` over their finite pairs (nan for fewer than 3)."""
    import pandas as pd

    a, b = np.asarray(a, float), np.asarray(b, float)
    ok = np.isfinite(a) & np.isfinite(b)
    if ok.sum() < 3:
        return math.nan
    ra, rb = pd.Series(a[ok]).rank().to_numpy(), pd.Series(b[ok]).rank().to_numpy()
    if np.std(ra) == 0.0 or np.std(rb) == 0.0:
        return math.nan
    return float(np.corrcoef(ra, rb)[0, 1])


def amplification(ds: xr.Dataset) -> dict:
    """Median planar/1-D amplification of the recorded pair and of the fitted pair.

    ``pi1_record_plane / pi1_record(x)`` and ``pi1_pulse_plane / pi1_pulse(x)`` (one scale: the
    x fit's) over the cells where the plane and the x component alone both slide.

    Returns
    -------
    dict
        ``record`` and ``pulse`` (medians), ``n_record`` and ``n_pulse`` (cells).
    """
    out = {}
    for which in ("record", "pulse"):
        plane = ds[f"pi1_{which}_plane"].values.ravel()
        line = ds[f"pi1_{which}"].sel(component="x").values.ravel()
        ok = (plane > 0.0) & (line > 0.0)
        out[which] = float(np.median(plane[ok] / line[ok])) if ok.any() else math.nan
        out[f"n_{which}"] = int(ok.sum())
    return out


def _num(v: float, fmt: str = ".2f") -> str:
    return "n/a" if not np.isfinite(v) else format(v, fmt)


def _pct(v: float) -> str:
    return "n/a" if not np.isfinite(v) else f"{v:.0%}"


def pairs_findings(ds: xr.Dataset) -> list:
    """The answers of the recorded pairs, as markdown sentences with their numbers (from ``ds`` only).

    Parameters
    ----------
    ds : xarray.Dataset
        Output of :func:`record_pairs_dataset` (attributes ``tolerance``, ``angle_tolerance``).

    Returns
    -------
    list of str
        On a line (both components), in the plane, the planar amplification, the direction of the
        planar peak, where the fits fail (the components whose median ratio leaves the band, the
        rank correlations with the fit's R^2, with PGA / a_p and with T_p, the cells only the
        record makes slide) and the ratio over Pi3.
    """
    tol = float(ds.attrs["tolerance"])
    atol = float(ds.attrs["angle_tolerance"])
    s = pairs_summary(ds, tol)
    out = []
    for view, what in (("line", "On a line (each component against its own fitted pulse, both components)"),
                       ("plane", "In the plane (the pair as recorded against the pair of fitted pulses)")):
        a = s.sel(view=view, motion="all")
        out.append(
            f"{what}: of {int(a.n_cells)} cells, both make the contents slide in {int(a.n_both_slide)}; there "
            f"Π₁,record / Π₁,pulse has median **{_num(float(a['median']))}** (geometric mean "
            f"{_num(float(a.gmean))}), P10–P90 **{_num(float(a.p10))}–{_num(float(a.p90))}** (range "
            f"{_num(float(a['min']), '.2g')}–{_num(float(a['max']), '.3g')}), and {_pct(float(a.within_tol))} of "
            f"them lie within ±{tol:.0%}. Cells where only the record slides (the pulse misses the sliding): "
            f"{int(a.n_only_record)}; only the pulse (it invents sliding): {int(a.n_only_pulse)}.")
    for c in COMPONENTS:
        a = s.sel(view=c, motion="all")
        out.append(f"Component {c} alone: median ratio {_num(float(a['median']))}, P10–P90 "
                   f"{_num(float(a.p10))}–{_num(float(a.p90))} over {int(a.n_both_slide)} cells.")
    amp = amplification(ds)
    out.append(
        f"Sliding in the plane against the x component alone (one scale): the recorded pair slides a median "
        f"**{_num(amp['record'])}×** as far as its x record ({amp['n_record']} cells), the fitted pair "
        f"**{_num(amp['pulse'])}×** as far as its x pulse ({amp['n_pulse']} cells).")
    d = direction_summary(ds, atol).sel(motion="all")
    out.append(
        f"Direction of the planar peak: where both pairs slide ({int(d.n_both_slide)} cells), the fitted pair's "
        f"peak lies on a line a median **{_num(float(d.median_line_off), '.0f')}°** from the record's (P90 "
        f"{_num(float(d.p90_line_off), '.0f')}°); within ±{atol:g}° in **{_pct(float(d.within_angle))}** of the "
        f"cells, and pointing the same way (less than 90° apart) in {_pct(float(d.same_sense))}.")
    ft = fit_table(ds, tol)
    fails = ft[~ft["stands_in"]]
    listed = "; ".join(
        f"{m} {c} (median {_num(r['median'])}, R² {r['r2']:.2f}, T_p {r['T_p']:.2f} s, PGA/a_p "
        f"{r['peak_over_a_p']:.2f})" for (m, c), r in fails.head(6).iterrows())
    out.append(
        f"Where the fits fail: {len(fails)} of {len(ft)} components have a median ratio outside ±{tol:.0%}"
        + (f", the worst: {listed}" if len(fails) else "") + ". "
        f"Rank correlation of |ln median ratio| with the fit's R²: "
        f"{_num(_spearman(ft['r2'], np.abs(np.log(ft['median']))))} (negative: the better the fit, the closer the "
        f"ratio to 1); with PGA/a_p: {_num(_spearman(ft['peak_over_a_p'], np.abs(np.log(ft['median']))))} "
        f"(positive: the more the record's peak exceeds the pulse's, the farther the ratio from 1).")
    tp, med = ft["T_p"].to_numpy(float), ft["median"].to_numpy(float)
    split = float(np.median(tp))
    halves = []
    for label, sel in (("below", tp < split), ("at or above", tp >= split)):
        m = med[sel & np.isfinite(med)]
        inside = int(np.sum(np.abs(m - 1.0) <= tol))
        halves.append(f"{label} it {_num(float(np.median(m)) if m.size else math.nan)} ({inside} of {m.size} "
                      f"within ±{tol:.0%})")
    out.append(
        f"By the fitted period: rank correlation of ln median ratio with T_p "
        f"{_num(_spearman(tp, np.log(med)))}; the components' median T_p is {split:.2f} s, and the median ratio "
        f"of the components {halves[0]}, {halves[1]}.")
    by2 = ratio_by(ds, "pi2")
    hi = float(ds["pi2"].max())
    n_line, n_plane = int(by2["only_record_line"].sum()), int(by2["only_record_plane"].sum())
    out.append(
        f"Cells where only the record makes the contents slide: {n_line} on a line and {n_plane} in the plane, "
        f"of which {int(by2['only_record_line'].sel(pi2=hi))} and {int(by2['only_record_plane'].sel(pi2=hi))} "
        f"at the largest Π₂ = {hi:g} (a pulse slides the contents only for Π₂ below its stuck demand; the "
        f"records' PGA reaches {float(ds['peak_over_a_p'].max()):.2f} a_p).")
    by3 = ratio_by(ds, "pi3")
    parts = [f"Π₃ = {float(v):g}: {_num(float(by3['median_line'].sel(pi3=v)))} on a line, "
             f"{_num(float(by3['median_plane'].sel(pi3=v)))} in the plane, only the record slides in "
             f"{int(by3['only_record_line'].sel(pi3=v))} and {int(by3['only_record_plane'].sel(pi3=v))} cells"
             for v in ds["pi3"].values]
    out.append("Median ratio by building: " + "; ".join(parts) + ".")
    return out


# ----------------------------------------------------------------------------------------------
# the pipeline's dataset of the recorded pairs (rule record_pairs)
# ----------------------------------------------------------------------------------------------

def pairs_settings(config: dict) -> dict:
    """What the recorded pairs read of a complete configuration (:func:`isoslide.config.load`), as copies.

    ``{"records": {"pairs": ...}, "defaults": ..., "solver": ...}``: only the ``pairs`` part of
    the ``records`` section, so the rest of the record study leaves the pairs' job alone.  The
    schema holds the defaults.
    """
    return {"records": {"pairs": copy.deepcopy(config["records"]["pairs"])},
            "defaults": copy.deepcopy(config["defaults"]), "solver": copy.deepcopy(config["solver"])}


def _values(key: str, values, low: float, low_in: bool) -> list:
    if isinstance(values, (str, bytes)) or not hasattr(values, "__iter__"):
        raise ValueError(f"{key} = {values!r} is invalid; allowed: a list of numbers")
    out = []
    for i, v in enumerate(values):
        ok = isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) \
            and (v >= low if low_in else v > low)
        if not ok:
            raise ValueError(f"{key}[{i}] = {v!r} is invalid; allowed range: {low:g} {'<=' if low_in else '<'} "
                             f"value < inf")
        out.append(float(v))
    if not out or len(set(out)) != len(out):
        raise ValueError(f"{key} = {list(values)!r} is invalid; allowed: a non-empty list of distinct values")
    return out


def check_pairs_settings(settings: dict) -> dict:
    """The ``records.pairs`` section of :func:`pairs_settings`, checked (a ValueError names the key).

    Checks the values without reading the suite: a motion's name is checked when the job reads
    it (:func:`select_motions`).

    Returns
    -------
    dict
        The section with ``pi2`` and ``pi3`` as lists of floats.
    """
    sec = dict(settings["records"]["pairs"])
    key = "records.pairs"
    if not isinstance(sec.get("suite"), str) or not sec["suite"]:
        raise ValueError(f"{key}.suite = {sec.get('suite')!r} is invalid; allowed: a suite name or path")
    m = sec.get("motions")
    if isinstance(m, str):
        if m != "all":
            raise ValueError(f"{key}.motions = {m!r} is invalid; allowed: 'all' or a list of motion names")
    elif not isinstance(m, (list, tuple)) or not m or len(set(map(str, m))) != len(m):
        raise ValueError(f"{key}.motions = {m!r} is invalid; allowed: 'all' or a non-empty list of distinct names")
    sec["pi2"] = _values(f"{key}.pi2", sec["pi2"], 0.0, False)
    sec["pi3"] = _values(f"{key}.pi3", sec["pi3"], 0.0, True)
    for name, lo, hi in (("pi4", 0.0, 1000.0), ("tolerance", 0.0, math.inf), ("angle_tolerance", 0.0, 90.0)):
        v = sec[name]
        if not (isinstance(v, (int, float)) and not isinstance(v, bool) and lo <= v <= hi
                and (name == "pi4" or v > lo)):
            raise ValueError(f"{key}.{name} = {v!r} is out of range; allowed: {lo:g} < value <= {hi:g}")
    return sec


def record_pairs_dataset(settings: dict, solve_many=None) -> xr.Dataset:
    """:func:`pairs_grid` of the configured pairs, with CF global attributes and the headline numbers.

    ``settings`` of :func:`pairs_settings` and ``solve_many`` (handed to :func:`pairs_grid`) as in
    :mod:`isoslide.studies.solving`.

    Returns
    -------
    xarray.Dataset
        :func:`pairs_grid`'s dataset; attributes add the suite, the ``tolerance`` and
        ``angle_tolerance`` (degrees) of the summaries, the configuration and ``summary_*``: the
        median, P10 and P90 of the ratio record/pulse on a line and in the plane and the share of
        planar cells whose peak line the fitted pair catches.
    """
    sec = check_pairs_settings(settings)
    d = settings["defaults"]
    motions = select_motions(sec["suite"], sec["motions"])
    ds = pairs_grid(motions, sec["pi2"], sec["pi3"], pi4=float(sec["pi4"]),
                    **{k: float(d[k]) for k in ("pi5", "pi6", "pi7", "pi8")}, rtol=settings["solver"]["rtol"],
                    solve_many=solve_many)
    ds["motion"] = ds["motion"].astype(str)
    ds["motion"].attrs["long_name"] = "ground motion (a recorded pair)"
    ds["component"] = ds["component"].astype(str)
    ds["component"].attrs["long_name"] = ("horizontal component: x = the suite's component a, y = its component "
                                          "b (the building's axes)")
    tol, atol = float(sec["tolerance"]), float(sec["angle_tolerance"])
    ds.attrs.update(tolerance=tol, angle_tolerance=atol)
    summ = pairs_summary(ds, tol).sel(motion="all")
    direc = direction_summary(ds, atol).sel(motion="all")
    extra = dict(ds.attrs)
    title = extra.pop("title")
    numbers = {}
    for view in ("line", "plane"):
        a = summ.sel(view=view)
        for k in ("median", "p10", "p90", "within_tol"):
            numbers[f"summary_{k}_{view}"] = float(a[k])
        for k in ("n_cells", "n_both_slide", "n_only_record", "n_only_pulse"):
            numbers[f"summary_{k}_{view}"] = int(a[k])
    numbers["summary_within_angle"] = float(direc["within_angle"])
    numbers["summary_median_line_off_deg"] = float(direc["median_line_off"])
    ds.attrs = global_attrs(
        title=f"isoslide {title}",
        history=(f"isoslide.studies.record_study.pairs_grid: {ds.sizes['motion']} recorded pairs of suite "
                 f"{sec['suite']!r} x {ds.sizes['pi2']} Pi2 x {ds.sizes['pi3']} Pi3, six scenes per cell (each "
                 f"component as recorded and as its fitted pulse, the pair as recorded and the fitted pair), "
                 f"solved exactly by isoslide.solve_many; by isoslide.studies.record_study.record_pairs_dataset; "
                 f"no timestamps are stored"),
        config=settings, suite=sec["suite"], **extra, **numbers)
    return ds
