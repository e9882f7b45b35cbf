"""Settings of the speed-versus-accuracy measurement: the ``accuracy`` section and the methods measured."""

from __future__ import annotations

import math
from dataclasses import dataclass

from .. import config as _config
from ..peers import opensees_available

DEFAULTS = {
    "seed": 20240611,
    "per_study": 6,
    "hard": True,
    "horizon": 50.0,
    "repeats": 5,
    "exact_rtols": [1e-2, 1e-3, 1e-4, 1e-6, 1e-8, 1e-10],
    "default_rtol": 1e-6,
    "converged_rtol": 1e-12,
    "reference_rtols": [1e-6, 1e-9],
    "reference_scenes": 16,
    "regularized_stiffness": [1e4, 1e5, 1e6],
    "regularized_rtol": 1e-6,
    "regularized_method": "Radau",
    "regularized_scenes": 6,
    "peer_repeats": 1,
    "peer_timeout": 8.0,
    "opensees": "auto",
    "opensees_scenes": 10,
    "reduction_repeats": 5,
    "map_points": 9,
    "map_repeats": 3,
    "error_floor": 1e-6,
}
"""Defaults of the ``accuracy`` configuration section (see :func:`settings_from`)."""

PAPER_CONFIG = _config.load()
"""The paper's complete configuration (``config/config.yaml`` as the package ships it), used when
no configuration is given."""

PAPER_STUDIES = PAPER_CONFIG["studies"]
"""The paper's studies (those of :data:`PAPER_CONFIG`)."""


def settings_from(config: dict | None) -> dict:
    """The ``accuracy`` section of a configuration, with :data:`DEFAULTS` filled in.

    Accepts either the whole configuration (with an ``accuracy`` key) or the section itself.
    """
    cfg = dict(config or {})
    if "accuracy" in cfg:
        section = cfg["accuracy"] or {}
    else:
        section = {} if cfg.get("studies") else cfg
    out = dict(DEFAULTS)
    for k, v in section.items():
        if k not in DEFAULTS:
            raise ValueError(f"accuracy.{k}: unknown key; allowed: {sorted(DEFAULTS)}")
        out[k] = v
    for k in ("exact_rtols", "reference_rtols", "regularized_stiffness"):
        out[k] = [float(x) for x in out[k]]
    if out["default_rtol"] not in out["exact_rtols"]:
        out["exact_rtols"] = sorted(set(out["exact_rtols"]) | {out["default_rtol"]}, reverse=True)
    if out["opensees"] not in (True, False, "auto"):
        raise ValueError(f"accuracy.opensees = {out['opensees']!r}; allowed: true, false, auto")
    for k in ("per_study", "repeats", "reference_scenes", "regularized_scenes", "opensees_scenes", "peer_repeats",
              "reduction_repeats", "map_points", "map_repeats", "seed"):
        out[k] = int(out[k])
        if out[k] < 0 or (k.endswith("repeats") and out[k] < 1):
            raise ValueError(f"accuracy.{k} = {out[k]!r} is out of range")
    for k in ("horizon", "peer_timeout", "default_rtol", "converged_rtol", "regularized_rtol",
              "error_floor"):
        out[k] = float(out[k])
        if not (math.isfinite(out[k]) and out[k] > 0):
            raise ValueError(f"accuracy.{k} = {out[k]!r} must be a positive number")
    return out


@dataclass(frozen=True)
class Setting:
    """One accuracy setting of one method.

    Attributes
    ----------
    name : str
        Label, e.g. ``"exact rtol=1e-06"``, ``"regularized K=1e+05"``.
    method : str
        ``"exact"``, ``"reference"``, ``"regularized"`` or ``"opensees"``.
    rtol : float
        Tolerance handed to the method.
    stiffness : float
        Regularising stiffness ``K = k_r T_p^2 / m_EC`` (regularized and opensees), else nan.
    """

    name: str
    method: str
    rtol: float
    stiffness: float = math.nan


def method_settings(settings: dict, part: str | None = None) -> list[Setting]:
    """The settings measured, in a fixed order; ``part`` selects one method family."""
    out = []
    if part in (None, "exact"):
        out += [Setting(f"exact rtol={r:.0e}", "exact", r) for r in settings["exact_rtols"]]
    if part in (None, "exact", "reference"):
        out += [Setting(f"reference rtol={r:.0e}", "reference", r) for r in settings["reference_rtols"]]
    if part in (None, "regularized"):
        out += [Setting(f"regularized K={k:.0e}", "regularized", settings["regularized_rtol"], k)
                for k in settings["regularized_stiffness"]]
        if settings["opensees"] is True and not opensees_available():
            raise RuntimeError("accuracy.opensees = true but openseespy does not import: pip install "
                               "openseespy (on Debian also apt-get install libblas3 liblapack3)")
        if settings["opensees"] is True or (settings["opensees"] == "auto" and opensees_available()):
            out += [Setting(f"opensees K={k:.0e}", "opensees", math.nan, k)
                    for k in settings["regularized_stiffness"]]
    return out
