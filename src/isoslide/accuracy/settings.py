"""Settings of the speed-versus-accuracy measurement: the ``accuracy`` section and the methods measured."""

from __future__ import annotations

import math
from dataclasses import dataclass

from .. import config as _config
from ..peers import opensees_available

PAPER_CONFIG = _config.load()
"""The paper's complete configuration (``config/config.yaml`` as the package ships it), used when
no configuration is given."""

PAPER_STUDIES = PAPER_CONFIG["studies"]
"""The paper's studies (those of :data:`PAPER_CONFIG`)."""


def settings_from(config: dict | None) -> dict:
    """The ``accuracy`` section of a configuration, completed with the schema's defaults.

    Accepts the whole configuration (with an ``accuracy`` key), the section itself, or ``None``
    (the paper's configuration).  Missing keys take the defaults of ``config/schema.yaml``
    (:func:`isoslide.config.defaults`), the only place they are written.
    """
    if config is None:
        section = PAPER_CONFIG["accuracy"]
    elif "accuracy" in config:
        section = config["accuracy"] or {}
    else:
        section = {} if "studies" in config else config
    defaults = _config.defaults()["accuracy"]
    out = dict(defaults)
    for k, v in section.items():
        if k not in defaults:
            raise ValueError(f"accuracy.{k}: unknown key; allowed: {sorted(defaults)}")
        out[k] = v
    for k in ("exact_rtols", "reference_rtols", "regularized_stiffness"):
        out[k] = [float(x) for x in out[k]]
    if out["default_rtol"] not in out["exact_rtols"]:
        out["exact_rtols"] = sorted(set(out["exact_rtols"]) | {out["default_rtol"]}, reverse=True)
    if out["opensees"] not in (True, False, "auto"):
        raise ValueError(f"accuracy.opensees = {out['opensees']!r}; allowed: true, false, auto")
    for k in ("per_study", "repeats", "reference_scenes", "regularized_scenes", "opensees_scenes", "peer_repeats",
              "peer_max_work",
              "reduction_repeats", "map_points", "map_repeats", "seed"):
        out[k] = int(out[k])
        if out[k] < 0 or (k.endswith("repeats") and out[k] < 1):
            raise ValueError(f"accuracy.{k} = {out[k]!r} is out of range")
    for k in ("horizon", "default_rtol", "converged_rtol", "regularized_rtol",
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
                               "-e .[peers] (pinned in environment.lock)")
        if settings["opensees"] is True or (settings["opensees"] == "auto" and opensees_available()):
            out += [Setting(f"opensees K={k:.0e}", "opensees", math.nan, k)
                    for k in settings["regularized_stiffness"]]
    return out
