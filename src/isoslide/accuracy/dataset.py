"""Assembling the accuracy dataset from its parts; its tables and Pareto front."""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from ..datasets import global_attrs
from .domain import DOMAIN, domain_map
from .reductions import measure_reductions
from .scenes import scene_set
from .settings import settings_from
from .trade import measure_trade, summarize_trade

NONDETERMINISTIC_SUFFIX = "_seconds"
"""Names of the wall-clock variables end in this (the only non-deterministic ones)."""
TIMINGS_SUFFIX = "_timings.nc"
"""Files holding wall-clock measurements end in this; they live apart from the results."""

PARTS = ("exact", "regularized", "reductions", "map")
"""Independent pieces of the accuracy dataset (one pipeline job each)."""


def measure_part(part: str, config: dict | None = None) -> xr.Dataset:
    """Measure one part (see :data:`PARTS`) for ``config`` (whole config or its accuracy section)."""
    settings = settings_from(config)
    if part == "map":
        return domain_map(settings)
    entries = scene_set(config, settings)
    if part == "exact":
        return measure_trade(entries, settings, "exact")
    if part == "regularized":
        return measure_trade(entries, settings, "regularized")
    if part == "reductions":
        return measure_reductions(entries, settings)
    raise ValueError(f"part = {part!r} is invalid; allowed: {PARTS}")


def combine(parts: dict, config: dict | None = None) -> xr.Dataset:
    """Merge the parts into the accuracy dataset, add summaries and metadata."""
    settings = settings_from(config)
    trade = [parts[p] for p in ("exact", "regularized") if p in parts]
    if trade:
        per_setting = [v for v in trade[0].data_vars if "setting" in trade[0][v].dims]
        # string coordinates along `setting` are concatenated as objects (xarray would keep the
        # first part's fixed width and truncate longer names)
        str_coords = [c for c in trade[0].coords if "setting" in trade[0][c].dims
                      and trade[0][c].dtype.kind == "U"]
        cat = xr.concat([t[per_setting].assign_coords({c: t[c].astype(object) for c in str_coords})
                         for t in trade], dim="setting", coords="minimal", compat="equals", join="exact")
        cat = cat.assign_coords({c: cat[c].astype(str) for c in str_coords})
        scene_only = trade[0].drop_vars(per_setting + [c for c in trade[0].coords
                                                       if "setting" in trade[0][c].dims])
        trade_ds = summarize_trade(xr.merge([cat, scene_only], compat="equals", join="exact"),
                                   settings["default_rtol"], settings["error_floor"])
    else:
        trade_ds = xr.Dataset()
    pieces = [trade_ds] + [parts[p] for p in ("reductions", "map") if p in parts]
    ds = xr.merge(pieces, compat="equals", join="exact", combine_attrs="drop_conflicts")
    nondet = sorted(v for v in ds.data_vars if v.endswith(NONDETERMINISTIC_SUFFIX))
    extra = {k: trade_ds.attrs[k] for k in ("default_setting", "default_error_bound",
                                            "default_error_median", "default_error_bound_significant",
                                            "default_abs_error_bound_small", "error_floor")
             if k in trade_ds.attrs}
    map_attrs = {k: v for k, v in ds.attrs.items() if k.startswith("map_base_")}
    ds.attrs = global_attrs(
        title="isoslide: speed versus accuracy, the extremes of the domain, and the model reductions",
        history="isoslide.accuracy: error of Pi1 against a converged answer and cost per scene for every "
                "accuracy setting and peer method; 1-D sweeps across the domain; reductions against "
                "the full model",
        config=settings,
        nondeterministic_variables=" ".join(nondet),
        comment="Only the variables listed in nondeterministic_variables (wall-clock times, names "
                "ending in _seconds) differ between runs of the same configuration; "
                "isoslide.accuracy.split_timings separates them. Timings were taken on a shared "
                "machine: compare settings within one run, not across runs.",
        domain="; ".join(f"{k}: {v[2]}" for k, v in DOMAIN.items()),
        **extra, **map_attrs)
    return ds


def accuracy_dataset(config: dict | None = None, parts=PARTS) -> xr.Dataset:
    """Measure every part in this process and combine them (for tests and small runs)."""
    return combine({p: measure_part(p, config) for p in parts}, config)


def deterministic_part(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` without its wall-clock variables (those reproduce only up to timing noise)."""
    drop = [v for v in ds.data_vars if v.endswith(NONDETERMINISTIC_SUFFIX)]
    return ds.drop_vars(drop)


def split_timings(ds: xr.Dataset) -> tuple[xr.Dataset, xr.Dataset]:
    """``(results, timings)``: the deterministic part and the wall-clock part of ``ds``.

    ``results`` is a deterministic function of the configuration and the code (same
    configuration, same bytes); ``timings`` holds the variables whose names end in
    :data:`NONDETERMINISTIC_SUFFIX`, with their coordinates, and says so in its attributes.
    :func:`join_timings` puts them back together.
    """
    nondet = sorted(v for v in ds.data_vars if v.endswith(NONDETERMINISTIC_SUFFIX))
    results = ds.drop_vars(nondet)
    results.attrs = {k: v for k, v in ds.attrs.items() if k not in ("nondeterministic_variables", "comment")}
    results.attrs["comment"] = ("Every variable is a deterministic function of the configuration and the "
                                "code. The wall-clock costs of the same run are in the file of the same "
                                f"name ending in {TIMINGS_SUFFIX} (isoslide.accuracy.join_timings).")
    timings = ds[nondet]
    timings.attrs = dict(ds.attrs)
    timings.attrs["title"] = ds.attrs.get("title", "") + ": wall-clock costs"
    timings.attrs["nondeterministic"] = "true"
    timings.attrs["comment"] = ("Wall-clock seconds measured on the machine that ran the pipeline; they "
                                "differ between runs. Settings were timed side by side within one run: "
                                "compare them within a run, not across runs.")
    return results, timings


def join_timings(results: xr.Dataset, timings: xr.Dataset) -> xr.Dataset:
    """The accuracy dataset with its wall-clock variables (the inverse of :func:`split_timings`)."""
    return xr.merge([results, timings], compat="equals", join="exact", combine_attrs="override")


def trade_table(ds: xr.Dataset) -> list[dict]:
    """The error-versus-cost table, one row per setting (for the report and the README)."""
    rows = []
    for j, name in enumerate(ds["setting"].values):
        rows.append({
            "setting": str(name),
            "scenes": int(ds["n_scenes"].values[j]),
            "failed": int(ds["n_failed"].values[j]),
            "error_median": float(ds["error_median"].values[j]),
            "error_p95": float(ds["error_p95"].values[j]),
            "error_max": float(ds["error_max"].values[j]),
            "error_max_significant": float(ds["error_max_significant"].values[j]),
            "abs_error_max_small": float(ds["abs_error_max_small"].values[j]),
            "false_slides": int(ds["false_slides"].values[j]),
            "cost_median_ms": 1e3 * float(ds["cost_median_seconds"].values[j]),
            "work_median": float(ds["work_median"].values[j]),
        })
    return rows


def pareto_front(cost, error) -> np.ndarray:
    """Indices of the settings not dominated in (cost, error) (both lower is better), by cost."""
    cost = np.asarray(cost, dtype=float)
    error = np.asarray(error, dtype=float)
    ok = np.isfinite(cost) & np.isfinite(error)
    idx = [i for i in np.argsort(cost) if ok[i]]
    front, best = [], math.inf
    for i in idx:
        if error[i] < best:
            front.append(i)
            best = error[i]
    return np.array(front, dtype=int)
