"""Contents on every floor of an isolated building of N storeys, and the floor they slide most on.

Configuration section ``storeys``.  The building is the flexible superstructure of
:class:`isoslide.Scene` with ``storeys = N`` uniform floors (fundamental fixed-base period
``T_s``, ``Pi12 = T_s/T_p``; mass fraction ``Pi11``, damping ``Pi13``) on one of two isolators:

* ``linear``: the paper's spring and dashpot (``Pi3 = T_b/T_p``, damping ``Pi4``);
* ``friction_pendulum``: a sliding bearing with true stick (``Pi9 = mu_b g/a_p > 0``,
  ``Pi10 = 0``; ``Pi3`` the pendulum's period, ``Pi4`` its viscous damping besides friction).

For every isolator, ``Pi12``, ``Pi2`` and ``N = storeys``, the contents are put on each floor
``0`` (the isolated slab) to ``N`` (the roof) and solved exactly (:func:`isoslide.solve_many`).
:func:`storeys_dataset` returns ``Pi1`` over ``isolator, pi12, pi2, storeys, floor`` (floors above
the roof are NaN) with, per building, the floor of the largest ``Pi1`` (``peak_floor``) and
whether an upper floor beats the slab (``upper_beats_slab``: its ``Pi1`` exceeds the slab's by more
than ``tolerance``).  :func:`findings` states the answers with their numbers.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Mapping

import numpy as np
import xarray as xr

from ..datasets import global_attrs, pi_attrs
from ..scene import MAX_STOREYS, Scene
from .solving import batch_solver

__all__ = ["ISOLATORS", "MAX_STOREYS", "check_settings", "findings", "floor_summary", "scenes", "storeys_dataset",
           "storeys_settings", "storeys_study"]

ISOLATORS = ("linear", "friction_pendulum")
"""Isolators of the study, in the order of the ``isolator`` dimension."""

ISOLATOR_LABELS = {"linear": "linear isolator", "friction_pendulum": "friction pendulum"}
"""Names of the isolators in text."""


def storeys_settings(config: Mapping) -> dict:
    """The sections of a complete configuration the study reads (copies).

    ``storeys``, ``defaults`` (the contents' Pi5 ... Pi8 and the pulse) and ``solver``.
    """
    return {k: copy.deepcopy(config[k]) for k in ("storeys", "defaults", "solver")}


def _positive_list(key: str, values, integer: bool = False, hi: float = math.inf) -> list:
    if not isinstance(values, (list, tuple)) or not values:
        raise ValueError(f"storeys.{key} = {values!r} is invalid; allowed: a non-empty list of values > 0")
    out = []
    for v in values:
        ok = isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) and 0 < v <= hi
        if integer:
            ok = ok and float(v).is_integer()
        if not ok:
            kind = "integers" if integer else "numbers"
            raise ValueError(f"storeys.{key} = {values!r} holds {v!r}; allowed: {kind} in (0, {hi:g}]")
        out.append(int(v) if integer else float(v))
    if len(set(out)) != len(out) or out != sorted(out):
        raise ValueError(f"storeys.{key} = {values!r} is not strictly increasing; allowed: increasing values, "
                         f"each once")
    return out


def _number(key: str, value, lo: float, hi: float, lo_in: bool = True, hi_in: bool = True) -> float:
    ok = isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)
    ok = ok and (value >= lo if lo_in else value > lo) and (value <= hi if hi_in else value < hi)
    if not ok:
        left, right = ("<=" if lo_in else "<"), ("<=" if hi_in else "<")
        raise ValueError(f"storeys.{key} = {value!r} is out of range; allowed range: {lo:g} {left} value {right} {hi:g}")
    return float(value)


def check_settings(settings: Mapping) -> dict:
    """The checked ``storeys`` section of :func:`storeys_settings` (lists as lists, numbers as floats).

    Raises
    ------
    ValueError
        Naming the key (``storeys.<key>``), its value and the allowed range.
    """
    s = settings["storeys"]
    out = {
        "storeys": _positive_list("storeys", s["storeys"], integer=True, hi=MAX_STOREYS),
        "pi12": _positive_list("pi12", s["pi12"], hi=1e4),
        "pi2": _positive_list("pi2", s["pi2"]),
        "pi3": _number("pi3", s["pi3"], 0.0, 1e4, lo_in=False),
        "pi11": _number("pi11", s["pi11"], 0.0, 1.0, lo_in=False, hi_in=False),
        "pi13": _number("pi13", s["pi13"], 0.0, 1e3),
        "tolerance": _number("tolerance", s["tolerance"], 0.0, 1.0),
        "linear": {"pi4": _number("linear.pi4", s["linear"]["pi4"], 0.0, 1e3)},
        "friction_pendulum": {"pi4": _number("friction_pendulum.pi4", s["friction_pendulum"]["pi4"], 0.0, 1e3),
                              "pi9": _number("friction_pendulum.pi9", s["friction_pendulum"]["pi9"], 0.0, 1e6,
                                             lo_in=False)},
    }
    return out


def _isolator_groups(section: Mapping) -> dict:
    """``{isolator: {"pi4", "pi9", "pi10"}}``."""
    return {"linear": {"pi4": section["linear"]["pi4"], "pi9": 0.0, "pi10": 0.0},
            "friction_pendulum": {"pi4": section["friction_pendulum"]["pi4"],
                                  "pi9": section["friction_pendulum"]["pi9"], "pi10": 0.0}}


def scenes(settings: Mapping) -> tuple[list, list]:
    """Every scene of the study with its index ``(isolator, pi12, pi2, storeys, floor)``.

    Returns
    -------
    tuple of list
        The :class:`isoslide.Scene` objects and, for each, its position in the dataset's
        ``pi1`` array (floors ``0 .. N`` of each building ``N``).
    """
    section = check_settings(settings)
    defaults = settings["defaults"]
    contents = {k: float(defaults[k]) for k in ("pi5", "pi6", "pi7", "pi8")}
    out, index = [], []
    for i, groups in enumerate(_isolator_groups(section).values()):
        for j, pi12 in enumerate(section["pi12"]):
            for k, pi2 in enumerate(section["pi2"]):
                for m, n in enumerate(section["storeys"]):
                    for floor in range(n + 1):
                        out.append(Scene(pi2=pi2, pi3=section["pi3"], **groups, **contents, pulse=defaults["pulse"],
                                         pi11=section["pi11"], pi12=pi12, pi13=section["pi13"], storeys=n,
                                         floor=floor))
                        index.append((i, j, k, m, floor))
    return out, index


def storeys_study(settings: Mapping, solve_many=None) -> xr.Dataset:
    """Peak sliding of the contents on every floor of every building of the study.

    ``settings`` of :func:`storeys_settings` and ``solve_many`` as in :mod:`isoslide.studies.solving`;
    of the solver's answers the study reads ``pi1`` and ``settled``.

    Returns
    -------
    xarray.Dataset
        Dimensions ``isolator, pi12, pi2, storeys, floor``: ``pi1`` (NaN above the roof) and
        ``settled``; per building (``isolator, pi12, pi2, storeys``): ``peak_floor`` (floor of the
        largest Pi1, -1 if the contents slide on no floor), ``peak_pi1``, ``upper_ratio`` (largest
        Pi1 of the floors 1 .. N over the slab's; +inf where only upper floors slide, NaN where no
        floor does), ``roof_ratio`` (the roof's over the slab's) and ``upper_beats_slab``
        (``upper_ratio > 1 + tolerance``); per isolator its ``pi4``, ``pi9``, ``pi10``.
    """
    solve_many = batch_solver(solve_many)
    section = check_settings(settings)
    rtol = settings["solver"]["rtol"]
    tol = section["tolerance"]
    batch_scenes, index = scenes(settings)
    batch = solve_many(batch_scenes, rtol=rtol)
    n_floor = max(section["storeys"]) + 1
    shape = (len(ISOLATORS), len(section["pi12"]), len(section["pi2"]), len(section["storeys"]), n_floor)
    pi1 = np.full(shape, np.nan)
    settled = np.full(shape, -1, dtype=np.int8)
    rows = tuple(np.array(a) for a in zip(*index, strict=True))
    pi1[rows] = np.asarray(batch.pi1, dtype=float)
    settled[rows] = np.asarray(batch.settled, dtype=bool).astype(np.int8)

    slab = pi1[..., 0]
    upper = np.nanmax(np.where(np.arange(n_floor) >= 1, pi1, np.nan), axis=-1)
    peak = np.nanmax(pi1, axis=-1)
    peak_floor = np.where(peak > 0, np.nanargmax(np.where(np.isnan(pi1), -np.inf, pi1), axis=-1), -1)
    top = np.broadcast_to(np.array(section["storeys"])[:, None], shape[:-1] + (1,))
    roof = np.take_along_axis(pi1, top, axis=-1)[..., 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        upper_ratio = np.where(slab > 0, upper / np.where(slab > 0, slab, 1.0), np.where(upper > 0, np.inf, np.nan))
        roof_ratio = np.where(slab > 0, roof / np.where(slab > 0, slab, 1.0), np.where(roof > 0, np.inf, np.nan))
    beats = np.where(np.isnan(upper_ratio), False, upper_ratio > 1.0 + tol)

    one = {"units": "1"}
    ds = xr.Dataset(coords={
        "isolator": ("isolator", np.array(ISOLATORS, dtype=object),
                     {"long_name": "isolation system: linear spring-dashpot or friction pendulum (Pi10 = 0)"}),
        "pi12": ("pi12", np.array(section["pi12"]), pi_attrs("pi12")),
        "pi2": ("pi2", np.array(section["pi2"]), pi_attrs("pi2")),
        "storeys": ("storeys", np.array(section["storeys"], dtype=np.int32),
                    {"long_name": "number of storeys N of the superstructure above the isolated slab", **one}),
        "floor": ("floor", np.arange(n_floor, dtype=np.int32),
                  {"long_name": "floor carrying the contents: 0 the isolated slab, N the roof", **one}),
    })
    dims = ("isolator", "pi12", "pi2", "storeys", "floor")
    ds["pi1"] = (dims, pi1, {**pi_attrs("pi1"), "comment": "NaN on floors above the roof (floor > storeys)"})
    ds["settled"] = (dims, settled, {"long_name": "response settled", **one,
                                     "flag_values": np.array([-1, 0, 1], np.int8),
                                     "flag_meanings": "no_such_floor not_settled settled"})
    d4 = dims[:-1]
    ds["peak_floor"] = (d4, peak_floor.astype(np.int32),
                        {"long_name": "floor on which the contents slide most (-1: on none)", **one})
    ds["peak_pi1"] = (d4, peak, {"long_name": "largest Pi1 over the floors", **one})
    ds["upper_ratio"] = (d4, upper_ratio, {"long_name": "largest Pi1 of the floors 1 .. N over Pi1 on the slab", **one,
                                           "comment": "+inf where only upper floors slide; NaN where no floor does"})
    ds["roof_ratio"] = (d4, roof_ratio, {"long_name": "Pi1 on the roof over Pi1 on the slab", **one,
                                         "comment": "+inf where only the roof slides; NaN where neither does"})
    ds["upper_beats_slab"] = (d4, beats.astype(np.int8),
                              {"long_name": "an upper floor beats the slab: upper_ratio > 1 + tolerance", **one,
                               "flag_values": np.array([0, 1], np.int8), "flag_meanings": "slab_or_tie upper_floor"})
    groups = _isolator_groups(section)
    for g in ("pi4", "pi9", "pi10"):
        ds[g] = ("isolator", np.array([groups[i][g] for i in ISOLATORS]), pi_attrs(g))
    for g, v in (("pi3", section["pi3"]), ("pi11", section["pi11"]), ("pi13", section["pi13"])):
        ds.coords[g] = ((), v, pi_attrs(g))
    for g in ("pi5", "pi6", "pi7", "pi8"):
        ds.coords[g] = ((), float(settings["defaults"][g]), pi_attrs(g))
    ds.attrs.update({"tolerance": tol, "pulse": str(settings["defaults"]["pulse"]),
                     "rtol": "default" if rtol is None else float(rtol)})
    return ds


def storeys_dataset(settings: Mapping, solve_many=None) -> xr.Dataset:
    """:func:`storeys_study` with CF global attributes and provenance (rule storeys_dataset)."""
    ds = storeys_study(settings, solve_many=solve_many)
    extra = dict(ds.attrs)
    n = int(np.sum(ds["settled"].values >= 0))
    ds.attrs = global_attrs(
        title="isoslide: contents on every floor of isolated buildings of N storeys (linear isolator and "
              "friction pendulum)",
        history=(f"isoslide.studies.storeys.storeys_study: {n} scenes ({ds.sizes['isolator']} isolators x "
                 f"{ds.sizes['pi12']} Pi12 x {ds.sizes['pi2']} Pi2 x floors 0 .. N of N = "
                 f"{', '.join(str(int(v)) for v in ds['storeys'].values)}), each solved exactly by "
                 "isoslide.solve_many; no timestamps are stored"),
        config={k: settings[k] for k in ("storeys", "defaults", "solver")}, **extra)
    return ds


# ----------------------------------------------------------------------------------------------
# the report's findings, with their numbers
# ----------------------------------------------------------------------------------------------

def _where(peak_floor: np.ndarray, storeys: np.ndarray) -> np.ndarray:
    """``"slab"``, ``"roof"``, ``"between"`` or ``"none"`` for each building's peak floor."""
    return np.where(peak_floor < 0, "none", np.where(peak_floor == 0, "slab",
                                                     np.where(peak_floor == storeys, "roof", "between")))


def floor_summary(ds: xr.Dataset) -> list:
    """Per isolator, Pi12 and Pi2: where the contents slide most and when an upper floor beats the slab.

    Returns
    -------
    list of tuple
        ``(isolator, pi12, pi2, buildings where the slab / the roof / a floor between / no floor
        gives the largest Pi1, smallest N at which an upper floor beats the slab (0: at none),
        largest upper_ratio, its N)``.
    """
    rows = []
    storeys = ds["storeys"].values
    for iso in ds["isolator"].values:
        for pi12 in ds["pi12"].values:
            for pi2 in ds["pi2"].values:
                sub = ds.sel(isolator=iso, pi12=pi12, pi2=pi2)
                where = _where(sub["peak_floor"].values, storeys)
                beats = sub["upper_beats_slab"].values.astype(bool)
                ratio = sub["upper_ratio"].values
                finite = np.where(np.isfinite(ratio), ratio, -np.inf)
                k = int(np.argmax(finite))
                rows.append((str(iso), float(pi12), float(pi2), int(np.sum(where == "slab")),
                             int(np.sum(where == "roof")), int(np.sum(where == "between")),
                             int(np.sum(where == "none")), int(storeys[beats][0]) if beats.any() else 0,
                             float(ratio[k]) if np.isfinite(ratio[k]) else math.nan, int(storeys[k])))
    return rows


def findings(ds: xr.Dataset) -> list:
    """The storeys study's findings, each ``(title, text with its numbers)``, from the dataset only."""
    storeys = ds["storeys"].values
    where = _where(ds["peak_floor"].values, storeys[None, None, None, :])
    n_build = int(np.prod(ds["peak_floor"].shape[1:]))
    lines = []
    for i, iso in enumerate(ds["isolator"].values):
        w = where[i]
        parts = [f"{int(np.sum(w == key))} on the {key}" if key != "between" else
                 f"{int(np.sum(w == key))} on a floor between"
                 for key in ("slab", "roof", "between")]
        none = int(np.sum(w == "none"))
        lines.append(f"{ISOLATOR_LABELS[str(iso)]}: the contents slide most " + ", ".join(parts)
                     + f" of {n_build} buildings" + (f" ({none} without sliding on any floor)" if none else ""))
    out = [("On which floor the contents slide most",
            f"Over N = {int(storeys.min())} to {int(storeys.max())} storeys, Π₁₂ = "
            f"{', '.join(f'{v:g}' for v in ds['pi12'].values)} and Π₂ = "
            f"{', '.join(f'{v:g}' for v in ds['pi2'].values)}: " + "; ".join(lines) + ".")]

    tol = float(ds.attrs["tolerance"])
    lines = []
    for row in floor_summary(ds):
        iso, pi12, pi2, *_counts, first, ratio, at = row
        label = f"{ISOLATOR_LABELS[iso]}, Π₁₂ = {pi12:g}, Π₂ = {pi2:g}"
        n_beats = int(ds["upper_beats_slab"].sel(isolator=iso, pi12=pi12, pi2=pi2).sum())
        if first:
            lines.append(f"{label}: at {n_beats} of {len(storeys)} N, the smallest N = {first} (largest ratio "
                         f"{ratio:.2f}× at N = {at})")
        elif np.isfinite(ratio):
            lines.append(f"{label}: at no N (the upper floors reach at most {ratio:.2f}× the slab, at N = {at})")
        else:
            lines.append(f"{label}: at no N (no sliding on the slab or above)")
    out.append(("When an upper floor beats the slab",
                f"An upper floor beats the slab when the contents' Π₁ there exceeds the slab's by more than "
                f"{tol:.0%}: " + "; ".join(lines) + "."))
    return out
