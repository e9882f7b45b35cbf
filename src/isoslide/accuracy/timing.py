"""Running one setting on one scene, timed, and bounded by work (never by wall-clock time)."""

from __future__ import annotations

import logging
import math
import time

import numpy as np

from ..peers import WorkLimitError, solve_opensees, solve_reference, solve_regularized
from ..scene import Scene
from ..solver import StepBudgetError, solve
from .settings import Setting

log = logging.getLogger(__name__)


STATUS = {"ok": 0, "error": 1, "over_budget": 2, "not-run": 3}
"""Outcome of a run and its code in the ``status`` variable."""
STATUS_ATTRS = {"long_name": "outcome of the run", "units": "1",
                "flag_values": np.array(list(STATUS.values()), dtype=np.int8),
                "flag_meanings": " ".join(k.replace("-", "_") for k in STATUS)}
"""CF attributes of the ``status`` variable."""


def tau_max(scene: Scene, horizon: float) -> float:
    """The common end time ``tau_end + horizon * max(1, Pi3)`` (units of T_p)."""
    return scene.pulse.tau_end + horizon * max(1.0, scene.pi3)


def run_setting(setting: Setting, scene: Scene, horizon: float, max_work: int | None = None,
                **extra) -> tuple[float, float, int, str]:
    """Run one setting on one scene: ``(pi1, seconds, work, status)``.

    ``work`` counts integrator steps (exact and OpenSees) or right-hand-side evaluations
    (SciPy peers).  The SciPy peers stop after ``max_work`` right-hand-side evaluations
    (None: unbounded) and the exact solver at its step budget; such a run is returned as
    ``status = "over_budget"``, any other failure is logged and returned as ``"error"``; neither
    raises.  Only ``seconds`` depends on the machine: the outcome is a function of the inputs.
    """
    t0 = time.perf_counter()
    try:
        if setting.method == "exact":
            s = solve(scene, rtol=setting.rtol, horizon=horizon, **extra)
            pi1, work = s.pi1, s.n_steps
        elif setting.method == "reference":
            r = solve_reference(scene, rtol=setting.rtol, tau_max=tau_max(scene, horizon), max_work=max_work)
            pi1, work = r.pi1, r.work
        elif setting.method == "regularized":
            r = solve_regularized(scene, stiffness=setting.stiffness, rtol=setting.rtol,
                                  method=extra.get("regularized_method", "Radau"),
                                  tau_max=tau_max(scene, horizon), max_work=max_work)
            pi1, work = r.pi1, r.work
        elif setting.method == "opensees":
            r = solve_opensees(scene, stiffness=setting.stiffness, tau_max=tau_max(scene, horizon))
            pi1, work = r.pi1, r.work
        else:
            raise ValueError(f"unknown method {setting.method!r}")
    except (WorkLimitError, StepBudgetError) as err:
        log.info("%s over its work budget on %r: %s", setting.name, scene, err)
        return math.nan, time.perf_counter() - t0, -1, "over_budget"
    except Exception as err:  # recorded, never fatal: the report lists failures
        log.warning("%s failed on %r: %r", setting.name, scene, err)
        return math.nan, time.perf_counter() - t0, -1, "error"
    return float(pi1), time.perf_counter() - t0, int(work), "ok"
