"""Contents sliding in the plane: two horizontal ground components, and a vertical one.

Configuration section ``planar``.  The contents (Pi5 ... Pi8 from ``defaults``) sit on a fixed
base (``Pi3 = 0``) or on the slab of a linear isolator (``Pi3 = T_b/T_p > 0``, damping ``Pi4``)
with a rigid superstructure.  The ground moves along the building's x axis with the main pulse
(``pulse``, amplitude ``a_p``, period ``T_p``) and along y with a second shape (``pulse_y``,
amplitude ``Pi14 a_p``, period ``Pi15 T_p``, lag ``Pi16 T_p``); a shape that is not proportional
to the main one moves the ground off any one line, and the contents slide in the plane
(:attr:`isoslide.Scene.planar`).  A vertical component ``Pi17 g p_z(t/T_p)`` (``pulse_z``) acts
through the normal force.

:func:`planar_dataset` returns, over ``pi17, pi3, pi15, pi14, pi2``, the peak Euclidean sliding
``Pi1`` and its direction (``peak_angle``, radians), the 1-D ``Pi1`` of the main component alone
on the same building (``pi1_line``), their ratio (``amplification``), the 1-D ``Pi1`` of the
transverse component alone (``pi1_transverse``, in the main component's units) and the direction
of the peak ground acceleration.  :func:`pi5_dataset` re-examines the paper's complete similarity
in ``Pi5 = mu_k/mu_s`` (its Fig. 6: Stribeck friction, ``0.7 <= Pi5 <= 1``) in the plane: ``Pi1``
over ``pi3, pi14, pi5, pi2`` and the spread between the ``Pi5`` curves
(:func:`isoslide.studies.similarity.curve_spread`'s measure).  :func:`findings` states the
answers with their numbers, from the datasets only.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Mapping

import numpy as np
import xarray as xr

from ..datasets import encode_facets, global_attrs, pi_attrs
from ..groups import group
from ..pulses import PULSE_NAMES
from ..scene import Scene
from .solving import batch_solver

__all__ = ["DIMS", "PI5_DIMS", "amplification_summary", "check_settings", "direction_summary", "findings",
           "line_deviation", "pendulum_summary", "pi5_dataset", "pi5_scenes", "pi5_study", "planar_dataset", "planar_settings",
           "planar_study", "scenes", "spread_summary", "vertical_summary"]

DIMS = ("pi17", "pi3", "pi15", "pi14", "pi2")
"""Dimensions of the study's grid, in order (Pi2, the master curves' abscissa, last)."""

PI5_DIMS = ("pi3", "pi14", "pi5", "pi2")
"""Dimensions of the Pi5 slice (:func:`pi5_study`)."""

GROUND_SAMPLES = 20001
"""Samples of the excitation's span on which the peak ground acceleration is looked for."""

DEG = 180.0 / math.pi


def planar_settings(config: Mapping) -> dict:
    """The sections of a complete configuration the study reads (copies).

    ``planar``, ``defaults`` (the contents' Pi5 ... Pi8) and ``solver``.
    """
    return {k: copy.deepcopy(config[k]) for k in ("planar", "defaults", "solver")}


# ----------------------------------------------------------------------------------------------
# the settings, checked
# ----------------------------------------------------------------------------------------------

def _group_value(key: str, name: str, value) -> float:
    """``value`` checked against the range of the Pi-group ``name`` (registry), named ``planar.<key>``."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ValueError(f"planar.{key} = {value!r} is not a number; allowed: a number in the range of {name}")
    try:
        return group(name).check(value)
    except ValueError as err:
        raise ValueError(f"planar.{key} = {value!r} is out of range ({err})") from None


def _group_list(key: str, name: str, values) -> list:
    if not isinstance(values, (list, tuple)) or not values:
        raise ValueError(f"planar.{key} = {values!r} is invalid; allowed: a non-empty list of {name} values")
    out = [_group_value(key, name, v) for v in values]
    if len(set(out)) != len(out) or out != sorted(out):
        raise ValueError(f"planar.{key} = {values!r} is not strictly increasing; allowed: increasing values, "
                         f"each once")
    return out


def _groups(prefix: str, section: Mapping, spec) -> dict:
    """The Pi-group keys of ``section`` checked, in the order of ``spec``.

    ``spec`` holds ``(name, check)`` pairs: ``section[name]`` checked by ``check``
    (:func:`_group_value` or :func:`_group_list`) against the range of the group ``name``, an
    error naming ``planar.<prefix><name>``.
    """
    return {name: check(prefix + name, name, section[name]) for name, check in spec}


def _fraction(key: str, value) -> float:
    ok = isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)
    if not (ok and 0.0 <= value <= 1.0):
        raise ValueError(f"planar.{key} = {value!r} is out of range; allowed range: 0 <= value <= 1")
    return float(value)


def _pulse(key: str, value) -> str:
    if value not in PULSE_NAMES:
        raise ValueError(f"planar.{key} = {value!r} is not a pulse shape; allowed: {list(PULSE_NAMES)}")
    return str(value)


def check_settings(settings: Mapping) -> dict:
    """The checked ``planar`` section of :func:`planar_settings` (lists as lists, numbers as floats).

    Adds ``pi2_values``, the abscissa (``pi2.num`` values from ``pi2.start`` to ``pi2.stop``).

    Raises
    ------
    ValueError
        Naming the key (``planar.<key>``), its value and what is allowed.
    """
    s = settings["planar"]
    p2 = s["pi2"]
    start, stop = _group_value("pi2.start", "pi2", p2["start"]), _group_value("pi2.stop", "pi2", p2["stop"])
    if stop < start:
        raise ValueError(f"planar.pi2.stop = {stop!r} is below planar.pi2.start = {start!r}; allowed: stop >= start")
    num = p2["num"]
    if isinstance(num, bool) or not isinstance(num, int) or not 1 <= num <= 10000:
        raise ValueError(f"planar.pi2.num = {num!r} is out of range; allowed: an integer in [1, 10000]")
    if num > 1 and stop == start:
        raise ValueError(f"planar.pi2 = {p2!r} gives {num} equal values; allowed: stop > start when num > 1")
    out = {
        "pulse": _pulse("pulse", s["pulse"]),
        "pulse_y": _pulse("pulse_y", s["pulse_y"]),
        "pulse_z": _pulse("pulse_z", s["pulse_z"]),
        "pi2": {"start": start, "stop": stop, "num": int(num)},
        "pi2_values": [float(v) for v in np.linspace(start, stop, int(num))],
        **_groups("", s, (("pi3", _group_list), ("pi4", _group_value), ("pi14", _group_list), ("pi15", _group_list),
                          ("pi16", _group_value), ("pi17", _group_list))),
        "tolerance": _fraction("tolerance", s["tolerance"]),
    }
    pend = s["pendulum"]
    out["pendulum"] = _groups("pendulum.", pend, (("pi3", _group_value), ("pi9", _group_value)))
    if out["pendulum"]["pi3"] == 0.0 or out["pendulum"]["pi9"] == 0.0:
        raise ValueError(f"planar.pendulum = {pend!r} is not a friction pendulum; allowed: pi3 > 0 (its period over "
                         "T_p) and pi9 > 0 (its friction mu_b g / a_p)")
    if out["pi17"][0] != 0.0:
        raise ValueError(f"planar.pi17 = {s['pi17']!r} does not start with 0; allowed: 0 (no vertical motion, the "
                         f"reference of the vertical effect) first")
    for v in out["pi17"]:
        try:
            Scene(pi2=0.5, pi3=0.0, pi17=v, pulse_z=out["pulse_z"])
        except ValueError as err:
            raise ValueError(f"planar.pi17 = {s['pi17']!r} holds {v!r}, which lifts the contents off under pulse_z "
                             f"{out['pulse_z']!r} ({err})") from None
    q = s["pi5"]
    out["pi5"] = {
        **_groups("pi5.", q, (("pi5", _group_list), ("pi6", _group_value), ("pi3", _group_list), ("pi14", _group_list),
                              ("pi15", _group_value))),
        "spread_tolerance": _fraction("pi5.spread_tolerance", q["spread_tolerance"]),
    }
    return out


# ----------------------------------------------------------------------------------------------
# the scenes
# ----------------------------------------------------------------------------------------------

def _contents(settings: Mapping) -> dict:
    return {k: float(settings["defaults"][k]) for k in ("pi5", "pi6", "pi7", "pi8")}


def _pi4(section: Mapping, pi3: float) -> float:
    """The isolator's damping; 0 on a fixed base (``Pi3 = 0``, no isolator)."""
    return section["pi4"] if pi3 > 0.0 else 0.0


def _scene(section: Mapping, contents: Mapping, pi2: float, pi3: float, pi14: float, pi15: float,
           pi17: float) -> Scene:
    """The two (or three) components on the building ``pi3``."""
    return Scene(pi2=pi2, pi3=pi3, pi4=_pi4(section, pi3), **contents, pulse=section["pulse"],
                 pulse_y=section["pulse_y"], pi14=pi14, pi15=pi15, pi16=section["pi16"], pi17=pi17,
                 pulse_z=section["pulse_z"] if pi17 > 0.0 else None)


def _line_scene(section: Mapping, contents: Mapping, pi2: float, pi3: float, pi17: float) -> Scene:
    """The main component alone (with the vertical one), the 1-D model along x."""
    return Scene(pi2=pi2, pi3=pi3, pi4=_pi4(section, pi3), **contents, pulse=section["pulse"], pi17=pi17,
                 pulse_z=section["pulse_z"] if pi17 > 0.0 else None)


def _transverse_scene(section: Mapping, contents: Mapping, pi2: float, pi3: float, pi14: float,
                      pi15: float) -> Scene:
    """The transverse component alone, as a 1-D scene in its own scales ``a_py = Pi14 a_p``, ``T_py = Pi15 T_p``.

    Its groups: ``mu_k g/a_py = Pi2/Pi14``, ``T_b/T_py = Pi3/Pi15``, ``beta a_py T_py = Pi6 Pi14
    Pi15``, ``gamma g T_py = Pi7 Pi15``; its ``Pi1`` times ``Pi14 Pi15^2`` is ``u_max/(a_p T_p^2)``.
    """
    return Scene(pi2=pi2 / pi14, pi3=pi3 / pi15, pi4=_pi4(section, pi3), pi5=contents["pi5"],
                 pi6=contents["pi6"] * pi14 * pi15, pi7=contents["pi7"] * pi15, pi8=contents["pi8"],
                 pulse=section["pulse_y"])


def scenes(settings: Mapping) -> dict:
    """Every scene of the main grid, in C order of its dimensions.

    Returns
    -------
    dict
        ``"planar"``: the scenes over :data:`DIMS`; ``"line"``: the main component alone over
        ``pi17, pi3, pi2``; ``"transverse"``: the transverse component alone (its own scales,
        :func:`_transverse_scene`) over ``pi3, pi15, pi14, pi2`` for ``Pi14 > 0`` and without
        vertical motion, with ``"transverse_index"`` their positions.
    """
    section = check_settings(settings)
    contents = _contents(settings)
    pi2s = section["pi2_values"]
    planar = [_scene(section, contents, pi2, pi3, pi14, pi15, pi17)
              for pi17 in section["pi17"] for pi3 in section["pi3"] for pi15 in section["pi15"]
              for pi14 in section["pi14"] for pi2 in pi2s]
    line = [_line_scene(section, contents, pi2, pi3, pi17)
            for pi17 in section["pi17"] for pi3 in section["pi3"] for pi2 in pi2s]
    transverse, index = [], []
    for i, pi3 in enumerate(section["pi3"]):
        for j, pi15 in enumerate(section["pi15"]):
            for k, pi14 in enumerate(section["pi14"]):
                if pi14 == 0.0:
                    continue
                for m, pi2 in enumerate(pi2s):
                    transverse.append(_transverse_scene(section, contents, pi2, pi3, pi14, pi15))
                    index.append((i, j, k, m))
    pend = section["pendulum"]
    pendulum = [_pendulum_scene(section, contents, pi2, pi14, pi15, pi9)
                for pi9 in (pend["pi9"], 0.0) for pi15 in section["pi15"] for pi14 in section["pi14"] for pi2 in pi2s]
    return {"planar": planar, "line": line, "transverse": transverse, "transverse_index": index,
            "pendulum": pendulum}


def _pendulum_scene(section: Mapping, contents: Mapping, pi2: float, pi14: float, pi15: float, pi9: float) -> Scene:
    """The two horizontal components on a friction pendulum (``pi9 > 0``) or on its linear twin (``pi9 = 0``).

    Both of period ``Pi3 = planar.pendulum.pi3`` (the pendulum's ``T_b = 2 pi sqrt(R/g)``) and damping
    ``Pi4``; the pendulum's friction ``Pi9 = mu_b g / a_p`` and true stick, in the plane.
    """
    pi3 = section["pendulum"]["pi3"]
    return Scene(pi2=pi2, pi3=pi3, pi4=_pi4(section, pi3), **contents, pulse=section["pulse"], pulse_y=section["pulse_y"],
                 pi14=pi14, pi15=pi15, pi16=section["pi16"], pi9=pi9)


def pi5_scenes(settings: Mapping) -> list:
    """The scenes of the Pi5 slice over :data:`PI5_DIMS`, in C order.

    The contents' Pi5 and Pi6 are swept, Pi7 and Pi8 from ``defaults``; no vertical motion.
    """
    section = check_settings(settings)
    q = section["pi5"]
    contents = _contents(settings)
    return [Scene(pi2=pi2, pi3=pi3, pi4=_pi4(section, pi3), pi5=pi5, pi6=q["pi6"], pi7=contents["pi7"],
                  pi8=contents["pi8"], pulse=section["pulse"], pulse_y=section["pulse_y"], pi14=pi14,
                  pi15=q["pi15"], pi16=section["pi16"])
            for pi3 in q["pi3"] for pi14 in q["pi14"] for pi5 in q["pi5"] for pi2 in section["pi2_values"]]


# ----------------------------------------------------------------------------------------------
# the derived quantities
# ----------------------------------------------------------------------------------------------

def line_deviation(angle, reference=0.0):
    """Angle between the line along ``angle`` and the line along ``reference`` (radians, in ``[0, pi/2]``).

    Directions that differ by ``pi`` lie on one line (a slide to ``-x`` is along the x axis); nan stays nan.
    """
    d = np.abs(np.remainder(np.asarray(angle, dtype=float) - reference + math.pi, 2.0 * math.pi) - math.pi)
    return np.minimum(d, math.pi - d)


def _ratio(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``a / b``; +inf where only ``a`` is positive, nan where neither is."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(b > 0.0, a / np.where(b > 0.0, b, 1.0), np.where(a > 0.0, np.inf, np.nan))


def ground_peak(section: Mapping, pi14: float, pi15: float) -> tuple:
    """Peak of the horizontal ground acceleration's magnitude (units of ``a_p``) and its direction (radians).

    Looked for on :data:`GROUND_SAMPLES` points of the excitation's span.
    """
    sc = Scene(pi2=0.5, pi3=0.0, pulse=section["pulse"], pulse_y=section["pulse_y"], pi14=pi14, pi15=pi15,
               pi16=section["pi16"])
    lo, hi = sc.span
    ax, ay = sc.ground(np.linspace(lo, hi, GROUND_SAMPLES))
    mag = np.hypot(ax, ay)
    i = int(np.argmax(mag))
    return float(mag[i]), float(math.atan2(ay[i], ax[i]))


# ----------------------------------------------------------------------------------------------
# the datasets
# ----------------------------------------------------------------------------------------------

_ANGLE_ATTRS = {"long_name": "direction of the sliding displacement at its peak, atan2(u_y, u_x) in the building's "
                             "axes (the main component acts along x)", "units": "rad",
                "comment": "in (-pi, pi]; nan where the contents do not slide"}


def _coords(values: Mapping) -> dict:
    return {name: (name, np.array(v, dtype=float), pi_attrs(name)) for name, v in values.items()}


def _solution(batch, shape, dims) -> dict:
    """``pi1``, ``pi1_residual``, ``tau_peak``, ``settled``, ``peak_angle`` and the facets of ``batch``."""
    one = {"units": "1"}
    out = {
        "pi1": (dims, np.asarray(batch.pi1, dtype=float).reshape(shape), pi_attrs("pi1")),
        "pi1_residual": (dims, np.asarray(batch.pi1_residual, dtype=float).reshape(shape),
                         {"long_name": "final sliding displacement over a_p T_p^2: its magnitude in the plane, or its "
                                       "signed component along the line of a 1-D excitation", **one}),
        "tau_peak": (dims, np.asarray(batch.tau_peak, dtype=float).reshape(shape),
                     {"long_name": "time of the peak sliding displacement, t_peak / T_p", **one}),
        "settled": (dims, np.asarray(batch.settled, dtype=bool).astype(np.int8).reshape(shape),
                    {"long_name": "response settled: no further sliding possible at tau_end", **one,
                     "flag_values": np.array([0, 1], np.int8), "flag_meanings": "not_settled settled"}),
        "peak_angle": (dims, np.asarray(batch.peak_angle, dtype=float).reshape(shape), dict(_ANGLE_ATTRS)),
    }
    out.update(encode_facets(batch.facets, dims, shape))
    return out


def planar_study(settings: Mapping, solve_many=None) -> xr.Dataset:
    """Peak sliding in the plane over the study's grid, with the 1-D answers it is compared with.

    ``settings`` of :func:`planar_settings` and ``solve_many`` as in :mod:`isoslide.studies.solving`;
    of the solver's answers (an :class:`isoslide.Batch` by default) the dataset stores ``pi1``,
    ``pi1_residual``, ``tau_peak``, ``settled``, ``peak_angle`` and ``facets``.

    Returns
    -------
    xarray.Dataset
        Over :data:`DIMS`: ``pi1``, ``peak_angle`` (rad), ``peak_off_axis`` (rad, the peak's line
        against the main component's, in ``[0, pi/2]``), ``pi1_residual``, ``tau_peak``,
        ``settled``, the ``model_<facet>`` flags and ``amplification`` (``pi1 / pi1_line``: +inf
        where only the plane slides, nan where neither does) and ``vertical_ratio`` (``pi1`` over
        its value at ``Pi17 = 0``, same conventions); over ``pi17, pi3, pi2``: ``pi1_line``, the
        main component alone; over ``pi3, pi15, pi14, pi2``: ``pi1_transverse`` (the transverse
        component alone, units of ``a_p T_p^2``; 0 at ``Pi14 = 0``) and ``envelope_ratio``
        (``pi1`` at ``Pi17 = 0`` over the larger of the two components alone); over ``pi15,
        pi14``: ``ground_peak`` (peak ``|a_g|/a_p``) and ``ground_peak_angle`` (rad); over
        ``pi3``: ``pi4``; over ``pi15, pi14, pi2``: ``pi1_pendulum`` (a friction pendulum,
        ``planar.pendulum``), ``pi1_pendulum_linear`` (the linear isolator of its period) and
        ``pendulum_ratio``.
    """
    solve_many = batch_solver(solve_many)
    section = check_settings(settings)
    rtol = settings["solver"]["rtol"]
    built = scenes(settings)
    values = {name: section["pi2_values"] if name == "pi2" else section[name] for name in DIMS}
    shape = tuple(len(values[d]) for d in DIMS)

    batch = solve_many(built["planar"], rtol=rtol)
    line = np.asarray(solve_many(built["line"], rtol=rtol).pi1, dtype=float).reshape(
        shape[0], shape[1], shape[4])
    transverse = np.zeros(shape[1:])
    if built["transverse"]:
        t = np.asarray(solve_many(built["transverse"], rtol=rtol).pi1, dtype=float)
        for value, (i, j, k, m) in zip(t, built["transverse_index"], strict=True):
            pi14, pi15 = section["pi14"][k], section["pi15"][j]
            transverse[i, j, k, m] = value * pi14 * pi15 * pi15

    ds = xr.Dataset(_solution(batch, shape, DIMS), coords=_coords(values))
    pi1 = ds["pi1"].values
    one = {"units": "1"}
    ds["peak_off_axis"] = (DIMS, line_deviation(ds["peak_angle"].values),
                           {"long_name": "angle between the line of the peak sliding displacement and the main "
                                         "component's line (x)", "units": "rad",
                            "comment": "in [0, pi/2]; nan where the contents do not slide"})
    ds["pi1_line"] = (("pi17", "pi3", "pi2"), line,
                      {**pi_attrs("pi1"), "long_name": "Pi1 of the main component alone (1-D model along x) on the "
                                                       "same building"})
    ds["amplification"] = (DIMS, _ratio(pi1, line[:, :, None, None, :]),
                           {"long_name": "Pi1 in the plane over Pi1 of the main component alone", **one,
                            "comment": "+inf where only the plane slides; nan where neither slides"})
    ds["vertical_ratio"] = (DIMS, _ratio(pi1, pi1[:1]),
                            {"long_name": "Pi1 over Pi1 without vertical motion (Pi17 = 0)", **one,
                             "comment": "+inf where only the vertical motion makes the contents slide; nan where "
                                        "neither slides"})
    d4 = ("pi3", "pi15", "pi14", "pi2")
    ds["pi1_transverse"] = (d4, transverse,
                            {**pi_attrs("pi1"), "long_name": "Pi1 of the transverse component alone (1-D model "
                                                             "along y) on the same building, units a_p T_p^2",
                             "comment": "solved in its own scales a_py = Pi14 a_p, T_py = Pi15 T_p and converted; "
                                        "0 at Pi14 = 0; without vertical motion"})
    ds["envelope_ratio"] = (d4, _ratio(pi1[0], np.maximum(line[0][:, None, None, :], transverse)),
                            {"long_name": "Pi1 in the plane (Pi17 = 0) over the larger Pi1 of the two components "
                                          "acting alone", **one,
                             "comment": "+inf where only the plane slides; nan where nothing slides"})
    peaks = np.array([[ground_peak(section, pi14, pi15) for pi14 in section["pi14"]] for pi15 in section["pi15"]])
    ds["ground_peak"] = (("pi15", "pi14"), peaks[..., 0],
                         {"long_name": "peak magnitude of the horizontal ground acceleration over a_p", **one})
    ds["ground_peak_angle"] = (("pi15", "pi14"), peaks[..., 1],
                               {"long_name": "direction of the horizontal ground acceleration at its peak magnitude, "
                                             "atan2(a_gy, a_gx)", "units": "rad"})
    ds["pi4"] = ("pi3", np.array([_pi4(section, p) for p in section["pi3"]]),
                 {**pi_attrs("pi4"), "comment": "0 on the fixed base (Pi3 = 0)"})
    pend = section["pendulum"]
    d3 = ("pi15", "pi14", "pi2")
    both = np.asarray(solve_many(built["pendulum"], rtol=rtol).pi1, dtype=float).reshape((2,) + shape[2:])
    ds["pi1_pendulum"] = (d3, both[0],
                          {**pi_attrs("pi1"), "long_name": "Pi1 in the plane on a friction pendulum (Pi9 = "
                                                           f"{pend['pi9']:g}, Pi3 = {pend['pi3']:g}), without vertical "
                                                           "motion"})
    ds["pi1_pendulum_linear"] = (d3, both[1],
                                 {**pi_attrs("pi1"), "long_name": "Pi1 in the plane on the linear isolator of the "
                                                                  f"pendulum's period (Pi3 = {pend['pi3']:g}, Pi9 = 0)"})
    ds["pendulum_ratio"] = (d3, _ratio(both[0], both[1]),
                            {"long_name": "Pi1 on the friction pendulum over Pi1 on its linear twin", **one,
                             "comment": "+inf where only the pendulum's floor slides; nan where neither does"})
    ds.attrs.update({"pendulum_pi3": pend["pi3"], "pendulum_pi9": pend["pi9"]})
    ds.coords["pi16"] = ((), section["pi16"], pi_attrs("pi16"))
    for g, v in _contents(settings).items():
        ds.coords[g] = ((), v, pi_attrs(g))
    ds.attrs.update({"pulse": section["pulse"], "pulse_y": section["pulse_y"], "pulse_z": section["pulse_z"],
                     "tolerance": section["tolerance"], "rtol": "default" if rtol is None else float(rtol)})
    return ds


def pi5_study(settings: Mapping, solve_many=None) -> xr.Dataset:
    """The paper's complete similarity in Pi5 re-examined in the plane.

    ``settings`` and ``solve_many`` as for :func:`planar_study`.

    Returns
    -------
    xarray.Dataset
        Over :data:`PI5_DIMS`: ``pi1``, ``peak_angle`` and the solver's fields; over ``pi3,
        pi14``: ``spread`` (largest over Pi2 of the range of Pi1 over the Pi5 curves), ``peak``
        (largest Pi1 of those curves), ``relative_spread`` (spread / peak), ``pi2_at`` (where the
        spread is largest) and ``similar`` (``relative_spread <= spread_tolerance``).
    """
    solve_many = batch_solver(solve_many)
    section = check_settings(settings)
    q = section["pi5"]
    rtol = settings["solver"]["rtol"]
    values = {"pi3": q["pi3"], "pi14": q["pi14"], "pi5": q["pi5"], "pi2": section["pi2_values"]}
    shape = tuple(len(values[d]) for d in PI5_DIMS)
    batch = solve_many(pi5_scenes(settings), rtol=rtol)
    ds = xr.Dataset(_solution(batch, shape, PI5_DIMS), coords=_coords(values))
    pi1 = ds["pi1"].values
    by_pi2 = pi1.max(axis=2) - pi1.min(axis=2)
    spread = by_pi2.max(axis=-1)
    peak = pi1.max(axis=(2, 3))
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = np.where(peak > 0.0, spread / np.where(peak > 0.0, peak, 1.0), np.nan)
    one = {"units": "1"}
    d2 = ("pi3", "pi14")
    ds["spread"] = (d2, spread, {"long_name": "largest over Pi2 of the range of Pi1 over the Pi5 curves", **one})
    ds["peak"] = (d2, peak, {"long_name": "largest Pi1 of the Pi5 curves", **one})
    ds["relative_spread"] = (d2, rel, {"long_name": "spread over peak", **one,
                                       "comment": "nan where no curve slides"})
    ds["pi2_at"] = (d2, np.asarray(ds["pi2"].values)[by_pi2.argmax(axis=-1)],
                    {"long_name": "Pi2 where the spread is largest", **one})
    ds["similar"] = (d2, np.where(np.isnan(rel), 0, rel <= q["spread_tolerance"]).astype(np.int8),
                     {"long_name": "complete similarity in Pi5 holds: relative_spread <= spread_tolerance", **one,
                      "flag_values": np.array([0, 1], np.int8), "flag_meanings": "does_not_hold holds"})
    ds["pi4"] = ("pi3", np.array([_pi4(section, p) for p in q["pi3"]]),
                 {**pi_attrs("pi4"), "comment": "0 on the fixed base (Pi3 = 0)"})
    for g, v in (("pi6", q["pi6"]), ("pi15", q["pi15"]), ("pi16", section["pi16"])):
        ds.coords[g] = ((), v, pi_attrs(g))
    for g in ("pi7", "pi8"):
        ds.coords[g] = ((), float(settings["defaults"][g]), pi_attrs(g))
    ds.attrs.update({"pulse": section["pulse"], "pulse_y": section["pulse_y"],
                     "spread_tolerance": q["spread_tolerance"], "rtol": "default" if rtol is None else float(rtol)})
    return ds


def _history(ds: xr.Dataset, dims, what: str) -> str:
    n = int(np.prod([ds.sizes[d] for d in dims]))
    return (f"isoslide.studies.planar.{what}: {n} scenes (" + " x ".join(f"{ds.sizes[d]} {d}" for d in dims)
            + "), each solved exactly by isoslide.solve_many; no timestamps are stored")


def planar_dataset(settings: Mapping, solve_many=None) -> xr.Dataset:
    """:func:`planar_study` with CF global attributes and provenance (rule planar_dataset)."""
    ds = planar_study(settings, solve_many=solve_many)
    extra = dict(ds.attrs)
    ds.attrs = global_attrs(
        title="isoslide: contents sliding in the plane under two horizontal ground components (and a vertical "
              "one) on a fixed base and a linear isolator",
        history=_history(ds, DIMS, "planar_study") + "; the components alone as 1-D scenes besides",
        config={k: settings[k] for k in ("planar", "defaults", "solver")}, **extra)
    return ds


def pi5_dataset(settings: Mapping, solve_many=None) -> xr.Dataset:
    """:func:`pi5_study` with CF global attributes and provenance (rule planar_dataset)."""
    ds = pi5_study(settings, solve_many=solve_many)
    extra = dict(ds.attrs)
    ds.attrs = global_attrs(
        title="isoslide: complete similarity in Pi5 = mu_k/mu_s re-examined in the plane",
        history=_history(ds, PI5_DIMS, "pi5_study"),
        config={k: settings[k] for k in ("planar", "defaults", "solver")}, **extra)
    return ds


# ----------------------------------------------------------------------------------------------
# the report's findings, with their numbers
# ----------------------------------------------------------------------------------------------

def _finite(a) -> np.ndarray:
    a = np.asarray(a, dtype=float).ravel()
    return a[np.isfinite(a)]


def _building(pi3: float) -> str:
    return "fixed base" if pi3 == 0.0 else f"isolated, Π₃ = {pi3:g}"


def amplification_summary(ds: xr.Dataset, pi17: float = 0.0) -> list:
    """Per building, Pi15 and Pi14 > 0 (at ``pi17``): how much farther the contents slide in the plane.

    Returns
    -------
    list of dict
        ``pi3, pi15, pi14``; ``peak_ratio`` (largest Pi1 over Pi2 in the plane over that of the main
        component alone), ``median``, ``largest`` (of ``amplification`` over the Pi2 where both slide)
        and ``pi2_at`` (where it is largest), ``line_share`` (the 1-D Pi1 there over its largest),
        ``only_plane`` (Pi2 values where only the plane slides), ``envelope_peak_ratio`` (largest Pi1 in
        the plane over the largest of either component alone; at ``Pi17 = 0``).
    """
    rows = []
    sub = ds.sel(pi17=pi17)
    for pi3 in ds["pi3"].values:
        line = sub["pi1_line"].sel(pi3=pi3).values
        for pi15 in ds["pi15"].values:
            for pi14 in ds["pi14"].values:
                if pi14 == 0.0:
                    continue
                cur = sub.sel(pi3=pi3, pi15=pi15, pi14=pi14)
                amp = cur["amplification"].values
                pi1 = cur["pi1"].values
                fin = np.isfinite(amp)
                k = int(np.argmax(np.where(fin, amp, -np.inf))) if fin.any() else -1
                alone = np.maximum(line, ds["pi1_transverse"].sel(pi3=pi3, pi15=pi15, pi14=pi14).values)
                rows.append({
                    "pi3": float(pi3), "pi15": float(pi15), "pi14": float(pi14),
                    "peak_ratio": float(pi1.max() / line.max()) if line.max() > 0 else math.nan,
                    "median": float(np.median(amp[fin])) if fin.any() else math.nan,
                    "largest": float(amp[k]) if k >= 0 else math.nan,
                    "pi2_at": float(ds["pi2"].values[k]) if k >= 0 else math.nan,
                    "line_share": float(line[k] / line.max()) if k >= 0 else math.nan,
                    "only_plane": int(np.sum(np.isposinf(amp))),
                    "envelope_peak_ratio": (float(ds["pi1"].sel(pi17=0.0, pi3=pi3, pi15=pi15, pi14=pi14).max()
                                                  / alone.max()) if alone.max() > 0 else math.nan),
                })
    return rows


def direction_summary(ds: xr.Dataset, pi17: float = 0.0) -> list:
    """Per Pi15 and Pi14 > 0 (at ``pi17``): where the peak slide points.

    Returns
    -------
    list of dict
        ``pi15, pi14``; ``median_deg``, ``max_deg`` (angle of the peak's line off the main
        component's line over the sliding scenes, degrees), ``ground_deg`` (that of the peak ground
        acceleration), ``median_to_ground_deg`` (angle between the peak's line and the peak ground
        acceleration's line, median over the sliding scenes), ``n`` (sliding scenes).
    """
    rows = []
    sub = ds.sel(pi17=pi17)
    for pi15 in ds["pi15"].values:
        for pi14 in ds["pi14"].values:
            if pi14 == 0.0:
                continue
            cur = sub.sel(pi15=pi15, pi14=pi14)
            off = _finite(cur["peak_off_axis"].values)
            g = float(ds["ground_peak_angle"].sel(pi15=pi15, pi14=pi14))
            to_ground = _finite(line_deviation(cur["peak_angle"].values, g))
            rows.append({"pi15": float(pi15), "pi14": float(pi14),
                         "median_deg": float(np.median(off) * DEG) if off.size else math.nan,
                         "max_deg": float(off.max() * DEG) if off.size else math.nan,
                         "ground_deg": float(line_deviation(g) * DEG),
                         "median_to_ground_deg": float(np.median(to_ground) * DEG) if to_ground.size else math.nan,
                         "n": int(off.size)})
    return rows


def vertical_summary(ds: xr.Dataset) -> list:
    """Per Pi17 > 0 and building: how the vertical component changes Pi1.

    Returns
    -------
    list of dict
        ``pi17, pi3``; ``median``, ``low``, ``high`` of ``vertical_ratio - 1`` over the scenes
        (every Pi15, Pi14, Pi2) that slide with and without it, ``median_abs`` of ``|vertical_ratio
        - 1|``, ``peak_change`` (largest Pi1 over Pi2 with it over that without, minus 1, median over
        Pi15 and Pi14), ``n``, ``only_vertical`` (scenes that slide only with it), ``matters``
        (``median_abs > tolerance``).
    """
    rows = []
    tol = float(ds.attrs["tolerance"])
    for pi17 in ds["pi17"].values[1:]:
        for pi3 in ds["pi3"].values:
            r = ds["vertical_ratio"].sel(pi17=pi17, pi3=pi3).values
            fin = _finite(r)
            peaks = ds["pi1"].sel(pi3=pi3).max("pi2")
            with np.errstate(divide="ignore", invalid="ignore"):
                pc = _finite((peaks.sel(pi17=pi17) / peaks.sel(pi17=0.0)).values - 1.0)
            med_abs = float(np.median(np.abs(fin - 1.0))) if fin.size else math.nan
            rows.append({"pi17": float(pi17), "pi3": float(pi3),
                         "median": float(np.median(fin) - 1.0) if fin.size else math.nan,
                         "low": float(fin.min() - 1.0) if fin.size else math.nan,
                         "high": float(fin.max() - 1.0) if fin.size else math.nan,
                         "median_abs": med_abs, "peak_change": float(np.median(pc)) if pc.size else math.nan,
                         "n": int(fin.size), "only_vertical": int(np.sum(np.isposinf(r))),
                         "matters": bool(med_abs > tol) if fin.size else False})
    return rows


def spread_summary(ds5: xr.Dataset) -> list:
    """Per building and Pi14 of the Pi5 slice: where the Pi5 curves part most.

    Returns
    -------
    list of dict
        ``pi3, pi14, relative_spread, pi2_at, similar`` (see :func:`pi5_study`) and ``at_end``: at
        ``pi2_at`` some Pi5 curve has stopped sliding while another still slides (the curves end at
        different Pi2).
    """
    rows = []
    for pi3 in ds5["pi3"].values:
        for pi14 in ds5["pi14"].values:
            at = float(ds5["pi2_at"].sel(pi3=pi3, pi14=pi14))
            there = ds5["pi1"].sel(pi3=pi3, pi14=pi14, pi2=at).values
            rows.append({"pi3": float(pi3), "pi14": float(pi14),
                         "relative_spread": float(ds5["relative_spread"].sel(pi3=pi3, pi14=pi14)),
                         "pi2_at": at, "similar": bool(ds5["similar"].sel(pi3=pi3, pi14=pi14)),
                         "at_end": bool(there.min() == 0.0 < there.max())})
    return rows


def _x(v: float) -> str:
    return "∞" if np.isposinf(v) else ("n/a" if not np.isfinite(v) else f"{v:.2f}×")


def _pct(v: float) -> str:
    return "n/a" if not np.isfinite(v) else f"{100.0 * v:+.0f}%"


def findings(ds: xr.Dataset, ds5: xr.Dataset | None = None) -> list:
    """The planar study's findings, each ``(title, text with its numbers)``, from the datasets only.

    Parameters
    ----------
    ds : xarray.Dataset
        :func:`planar_dataset`.
    ds5 : xarray.Dataset, optional
        :func:`pi5_dataset`; without it the Pi5 finding is left out.
    """
    out = []
    rows = amplification_summary(ds)
    lines = []
    for pi14 in ds["pi14"].values[ds["pi14"].values > 0]:
        sel = [r for r in rows if r["pi14"] == pi14]
        parts = []
        for pi3 in ds["pi3"].values:
            pr = _finite([r["peak_ratio"] for r in sel if r["pi3"] == pi3])
            span = "n/a" if not pr.size else (_x(pr.min()) if np.isclose(pr.min(), pr.max(), rtol=5e-3)
                                               else f"{_x(pr.min())} to {_x(pr.max())}")
            parts.append(f"{span} {'on the fixed base' if pi3 == 0.0 else f'at Π₃ = {pi3:g}'}")
        meds = _finite([r["median"] for r in sel])
        best = max(sel, key=lambda r: r["largest"] if np.isfinite(r["largest"]) else -np.inf)
        only = sum(r["only_plane"] for r in sel)
        joined = ", ".join(parts[:-1]) + " and " + parts[-1] if len(parts) > 1 else parts[0]
        lines.append(f"Π₁₄ = {pi14:g}: the planar master curve's peak over the 1-D one's is {joined}; pointwise, over the "
                     f"Π₂ where both slide, the median ratio is "
                     + (f"{np.min(meds):.2f}× to {np.max(meds):.2f}×" if meds.size else "n/a")
                     + f" and the largest {_x(best['largest'])} ({_building(best['pi3'])}, Π₁₅ = {best['pi15']:g}, "
                       f"Π₂ = {best['pi2_at']:.2f}, where the 1-D Π₁ is {best['line_share']:.0%} of its peak)"
                     + (f"; {only} scenes slide in the plane only" if only else ""))
    env = _finite([r["envelope_peak_ratio"] for r in rows])
    n_pi2 = ds.sizes["pi2"]
    out.append(("How much farther the contents slide when both components act",
                f"Peak sliding Π₁ in the plane over that of the main component alone (the paper's 1-D model) on the "
                f"same building, over {n_pi2} Π₂ from {float(ds['pi2'].min()):g} to {float(ds['pi2'].max()):g} and "
                f"Π₁₅ = {', '.join(f'{v:g}' for v in ds['pi15'].values)} (ranges over Π₁₅), without vertical motion. "
                + ". ".join(lines) + ". Against the larger of the two components acting alone, the planar peak is "
                + (f"{env.min():.2f}× to {env.max():.2f}× (median {np.median(env):.2f}×)" if env.size else "n/a")
                + "."))

    drows = direction_summary(ds)
    lines = [f"Π₁₅ = {r['pi15']:g}, Π₁₄ = {r['pi14']:g}: median {r['median_deg']:.0f}° (at most {r['max_deg']:.0f}°) "
             f"off the main axis; the peak ground acceleration points {r['ground_deg']:.0f}° off it, and the slide's "
             f"peak is a median {r['median_to_ground_deg']:.0f}° off that line" for r in drows if r["n"]]
    out.append(("Where the peak points",
                "The line of the peak sliding displacement against the main component's line (angles between lines, "
                "0° to 90°, over the sliding scenes of every building and Π₂): " + "; ".join(lines) + "."))

    vrows = vertical_summary(ds)
    tol = float(ds.attrs["tolerance"])
    lines = []
    for r in vrows:
        verdict = "matters" if r["matters"] else "does not matter"
        size = "n/a" if not np.isfinite(r["median_abs"]) else f"{100.0 * r['median_abs']:.0f}%"
        lines.append(f"Π₁₇ = {r['pi17']:g}, {_building(r['pi3'])}: Π₁ changes by a median {_pct(r['median'])} "
                     f"(median size {size}, from {_pct(r['low'])} to {_pct(r['high'])} over {r['n']} sliding scenes), "
                     f"the curves' peaks by a median {_pct(r['peak_change'])}"
                     + (f", {r['only_vertical']} scenes slide only with it" if r["only_vertical"] else "")
                     + f": it {verdict}")
    out.append(("The vertical component on the isolated and on the fixed floor",
                f"A vertical pulse {ds.attrs['pulse_z']} of amplitude Π₁₇ g on the main pulse's time axis, with both "
                f"horizontal components (every Π₁₅, Π₁₄, Π₂); it matters where the median size of the change of Π₁ "
                f"exceeds {tol:.0%}: " + "; ".join(lines) + "."))

    if ds5 is not None:
        srows = spread_summary(ds5)
        tol5 = float(ds5.attrs["spread_tolerance"])
        lines = []
        for pi14 in ds5["pi14"].values:
            rs = [r for r in srows if r["pi14"] == pi14]
            held = sum(r["similar"] for r in rs)
            label = "the 1-D model (Π₁₄ = 0)" if pi14 == 0.0 else f"the plane (Π₁₄ = {pi14:g})"
            lines.append(f"{label}: relative spread " + ", ".join(
                f"{r['relative_spread']:.3f} at Π₃ = {r['pi3']:g}" + (" (largest at Π₂ = "
                                                                     f"{r['pi2_at']:.2f}, where one Π₅ curve has "
                                                                     "stopped sliding and another still slides)"
                                                                     if r["at_end"] else "")
                for r in rs)
                + f"; complete similarity holds at {held} of {len(rs)}")
        out.append(("Complete similarity in Π₅ in the plane",
                    f"The paper finds Π₁ almost independent of Π₅ = μ_k/μ_s over {float(ds5['pi5'].min()):g} to "
                    f"{float(ds5['pi5'].max()):g} (Stribeck friction, Π₆ = {float(ds5['pi6']):g}). The largest spread "
                    f"between the Π₅ curves over the largest Π₁ of those curves (similarity holds at most "
                    f"{tol5:g}), with Π₁₅ = {float(ds5['pi15']):g}: " + "; ".join(lines) + "."))
    if "pi1_pendulum" in ds:
        prows = pendulum_summary(ds)
        lines = [f"Π₁₅ = {r['pi15']:g}, Π₁₄ = {r['pi14']:g}: peak {_x(r['peak_ratio'])}, median "
                 + (f"{r['median']:.2f}×" if np.isfinite(r["median"]) else "n/a")
                 + (f", {r['only_pendulum']} Π₂ slide on the pendulum only" if r["only_pendulum"] else "")
                 for r in prows]
        out.append(("Friction pendulum against a linear isolator in the plane",
                    f"Π₁ on a friction pendulum (Π₉ = μ_b g/a_p = {float(ds.attrs['pendulum_pi9']):g}, true stick, its "
                    f"circular friction and the contents' coupled in the plane) over Π₁ on a linear isolator of the same "
                    f"period (Π₃ = {float(ds.attrs['pendulum_pi3']):g}), both components acting, no vertical motion "
                    "(peak of the pendulum's master curve over the linear one's, and the median pointwise ratio over "
                    "the Π₂ where both slide): " + "; ".join(lines) + "."))
    return out


def pendulum_summary(ds: xr.Dataset) -> list:
    """Friction pendulum against its linear twin, per ``pi15, pi14``: peak and median ratios of ``Pi1``.

    Rows with ``peak_ratio`` (the pendulum curve's largest ``Pi1`` over the linear one's), ``median``
    (pointwise ratio over the ``Pi2`` where both slide) and ``only_pendulum`` (``Pi2`` where only the
    pendulum's floor slides).
    """
    rows = []
    for pi15 in ds["pi15"].values:
        for pi14 in ds["pi14"].values:
            a = ds["pi1_pendulum"].sel(pi15=pi15, pi14=pi14).values
            b = ds["pi1_pendulum_linear"].sel(pi15=pi15, pi14=pi14).values
            both = (a > 0.0) & (b > 0.0)
            rows.append({"pi15": float(pi15), "pi14": float(pi14),
                         "peak_ratio": float(a.max() / b.max()) if b.max() > 0.0 else math.inf,
                         "median": float(np.median(a[both] / b[both])) if both.any() else math.nan,
                         "only_pendulum": int(np.sum((a > 0.0) & (b == 0.0)))})
    return rows
