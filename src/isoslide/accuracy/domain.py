"""The domain map: where the problem is stiff or slow, and what the solver does there."""

from __future__ import annotations

import math
import time

import numpy as np
import xarray as xr

from ..groups import INPUT_NAMES, TFP_NAMES
from ..scene import Scene
from ..solver import solve
from ..solver import warm_up
from .trade import rel_error

DOMAIN = {
    "pi2": (1e-4, 100.0, "1e-4 (nearly frictionless) to far past the no-slide threshold"),
    "pi3": (0.0, 100.0, "0 (fixed base), 1e-3 (very stiff base) to 100 (very long isolation period)"),
    "pi4": (0.0, 10.0, "0 (undamped: never settles) to over-damped (>= 1)"),
    "pi5": (0.05, 1.0, "0.05 (static friction 20 x kinetic) to 1 (Coulomb)"),
    "pi6": (0.0, 1e7, "0 (Coulomb with mu_s) to 1e7 (practically a jump from mu_s to mu_k)"),
    "pi7": (0.0, 100.0, "0 to 100 (friction dominated by the viscous term)"),
    "pi8": (0.0, 10.0, "0 (one-way coupling) to 10 (contents ten times the isolated mass)"),
    "pi9": (0.0, 10.0, "0 (linear isolator) to 10 (a bearing ten times as strong as the pulse's force)"),
    "pi10": (0.0, 1.0, "0 (sliding bearing, true stick) to 1 (yield displacement of the pulse's length)"),
    "pi11": (0.01, 0.95, "0.01 (light superstructure) to 0.95 (nearly all the isolated mass)"),
    "pi12": (0.0, 10.0, "0 (rigid superstructure), 0.01 (very stiff) to 10 (very flexible)"),
    "pi13": (0.0, 1.0, "0 (undamped superstructure) to 1 (critically damped)"),
    "pi14": (0.0, 2.0, "0 (no second component) to 2 (a transverse pulse twice the main one)"),
    "pi15": (0.25, 4.0, "0.25 (a transverse pulse four times shorter) to 4 (four times longer)"),
    "pi16": (-1.0, 1.0, "the transverse pulse one main period ahead to one behind"),
    "pi17": (0.0, 2.0, "0 (no vertical motion) to 2 (a vertical Ricker pulse of twice g: the normal force "
                       "falls to 11 % of its static value)"),
    "pi22": (0.05, 1.0, "0.05 (a bearing breaking away at a twentieth of its friction at speed) to 1 (constant "
                        "friction)"),
    "pi23": (0.0, 1e4, "0 (constant friction at breakaway) to 1e4 (the friction at speed as soon as the slab "
                       "moves)"),
    "pi24": (0.0, 0.5, "0 (a single friction pendulum) to 0.5 (inner surfaces of a quarter of the outer ones' "
                       "sum of radii each)"),
    "pi25": (0.45, 0.8, "0.45 (outer surfaces nearly alike) to 0.8 (a lower outer surface four times the upper's "
                        "radius)"),
    "pi26": (0.1, 1.0, "0.1 (inner surfaces of a tenth of the lower outer friction) to 1 (equal)"),
    "pi27": (1.0, 4.0, "1 (outer frictions equal) to 4 (the upper four times the lower)"),
    "pi28": (0.02, 0.5, "inner limits from 0.02 to 0.5 a_p T_p^2"),
    "pi29": (0.005, 0.09, "lower outer limit from 0.005 to 0.09 a_p T_p^2"),
    "pi30": (0.06, 0.5, "upper outer limit from 0.06 to 0.5 a_p T_p^2"),
}
"""The domain over which isoslide is tested (``tests/test_extremes.py``) and mapped
(:func:`domain_map`): (low, high, meaning).  The valid range of each group in
:data:`isoslide.groups.GROUPS` is the (wider) domain a Scene accepts."""

MAP_BASE = {"pi2": 0.1, "pi3": 1.0, "pi4": 0.1, "pi5": 0.7, "pi6": 1000.0, "pi7": 0.0, "pi8": 1e-3,
            "pi11": 0.5}
"""Base scene of the 1-D sweeps of :func:`domain_map` (Stribeck friction, resonance; the paper's
model: ``pi11`` is read only with a flexible superstructure)."""

TFP_BASE = {"pi9": 0.1, "pi24": 0.1, "pi25": 0.5, "pi26": 0.5, "pi27": 2.0, "pi28": 0.1, "pi29": 0.05, "pi30": 0.1}
"""A triple friction pendulum beside :data:`MAP_BASE` (``Pi3 = 1``) for which every value of
:data:`DOMAIN` of one of its groups, the others kept, is a bearing of regimes I to V in order."""

MAP_COMPANIONS = {"pi10": {"pi9": 0.1}, "pi11": {"pi12": 0.2, "pi13": 0.02},
                  "pi22": {"pi9": 0.1, "pi23": 20.0}, "pi23": {"pi9": 0.1, "pi22": 0.5},
                  **{g: TFP_BASE for g in TFP_NAMES},
                  "pi12": {"pi13": 0.02}, "pi13": {"pi12": 0.2}, "pi17": {"pulse_z": "ricker"},
                  **{g: {"pulse_y": "antisymmetric_ricker", "pi14": 0.7} for g in ("pi14", "pi15", "pi16")}}
"""Groups (and the vertical pulse) set beside a swept one so that it acts: a bearing for ``pi10``,
a flexible superstructure for ``pi11`` and ``pi13``, a vertical Ricker pulse for ``pi17``, a sliding
bearing whose friction rises with speed for ``pi22`` and ``pi23``, a triple friction pendulum
(:data:`TFP_BASE`) for ``pi24`` to ``pi30``, a transverse antisymmetric Ricker pulse (the contents
slide in the plane) for ``pi14`` to ``pi16``."""


def map_values(group: str, npts: int = 9) -> np.ndarray:
    """Values of ``group`` swept by :func:`domain_map` across :data:`DOMAIN` (zero included)."""
    lo, hi, _ = DOMAIN[group]
    if group in ("pi5", "pi22", "pi25", "pi26", "pi27"):
        return np.linspace(lo, hi, npts)
    if group == "pi4":
        return np.concatenate([[0.0], np.logspace(-3, 1, npts - 1)])
    if group == "pi3":
        return np.concatenate([[0.0], np.logspace(-3, 2, npts - 1)])
    if group == "pi12":
        return np.concatenate([[0.0], np.logspace(-2, 1, npts - 1)])
    if group == "pi16":
        return np.linspace(lo, hi, npts)
    if lo == 0.0:
        return np.concatenate([[0.0], np.logspace(-3 if group != "pi6" else -1, math.log10(hi), npts - 1)])
    return np.logspace(math.log10(lo), math.log10(hi), npts)


def domain_map(settings: dict, base: dict | None = None) -> xr.Dataset:
    """1-D sweeps of every input group across its domain from :data:`MAP_BASE`.

    For each point: Pi1 (default and converged), integrator steps, transitions, model label,
    settled flag, end time, and the wall-clock cost (median of ``map_repeats``).
    """
    base = dict(MAP_BASE if base is None else base)
    npts = settings["map_points"]
    H = settings["horizon"]
    rtol = settings["default_rtol"]
    groups = list(INPUT_NAMES)
    shape = (len(groups), npts)
    vals = np.full(shape, np.nan)
    out = {k: np.full(shape, np.nan) for k in ("pi1", "pi1_conv", "cost", "tau_end")}
    steps = np.full(shape, -1, np.int64)
    events = np.full(shape, -1, np.int64)
    settled = np.full(shape, -1, np.int8)
    models = np.full(shape, "", dtype=object)
    warm_up()
    for g, name in enumerate(groups):
        for k, v in enumerate(map_values(name, npts)):
            kw = dict(base)
            kw.update(MAP_COMPANIONS[name] if name in MAP_COMPANIONS else {})
            kw[name] = float(v)
            if kw["pi3"] == 0.0:
                kw["pi4"] = 0.0
            sc = Scene(**kw)
            vals[g, k] = v
            ts = []
            for _ in range(settings["map_repeats"]):
                t0 = time.perf_counter()
                s = solve(sc, rtol=rtol, horizon=H)
                ts.append(time.perf_counter() - t0)
            out["pi1"][g, k], out["cost"][g, k], out["tau_end"][g, k] = s.pi1, np.median(ts), s.tau_end
            out["pi1_conv"][g, k] = solve(sc, rtol=settings["converged_rtol"], horizon=H, model="full").pi1
            steps[g, k], events[g, k], settled[g, k], models[g, k] = s.n_steps, s.n_events, s.settled, s.model
    dims = ("group", "point")
    ds = xr.Dataset(
        {
            "map_value": (dims, vals, {"long_name": "value of the swept group (others at the base scene)",
                                       "units": "1"}),
            "map_pi1": (dims, out["pi1"], {"long_name": "Pi1 at the default rtol", "units": "1"}),
            "map_pi1_converged": (dims, out["pi1_conv"], {"long_name": "converged Pi1", "units": "1"}),
            "map_rel_error": (dims, rel_error(out["pi1"], out["pi1_conv"]),
                              {"long_name": "relative error of the default setting", "units": "1"}),
            "map_steps": (dims, steps, {"long_name": "integrator steps", "units": "1"}),
            "map_events": (dims, events, {"long_name": "stick/slip transitions", "units": "1"}),
            "map_settled": (dims, settled, {"long_name": "settled before the horizon (1) or not (0)",
                                            "units": "1"}),
            "map_model": (dims, models.astype(str), {"long_name": "model the solver ran", "units": "1"}),
            "map_tau_end": (dims, out["tau_end"], {"long_name": "end time of the integration / T_p",
                                                   "units": "1"}),
            "map_cost_seconds": (dims, out["cost"], {"long_name": "wall-clock time per scene (median)",
                                                     "units": "s", "nondeterministic": "true"}),
        },
        coords={"group": ("group", np.array(groups, dtype=str), {"long_name": "swept input group",
                                                                 "units": "1"}),
                "point": ("point", np.arange(npts, dtype=np.int32), {"long_name": "point of the sweep",
                                                                     "units": "1"})},
    )
    for k, v in base.items():
        ds.attrs[f"map_base_{k}"] = float(v)
    return ds
