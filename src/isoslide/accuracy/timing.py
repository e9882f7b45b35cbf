"""Running one setting on one scene, timed, and bounded by work (never by wall-clock time)."""

from __future__ import annotations

import logging
import math
import time

import numpy as np

from ..engine.system import assemble, forget_shared, unassembled
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


def timed_solve(scene: Scene, **options) -> tuple:
    """``(seconds, Solution)`` of :func:`isoslide.solve` (``options`` its keywords) on a new copy of ``scene``.

    The copy (:func:`~isoslide.engine.system.unassembled`) is made before the clock starts, so the
    solve pays for its own assembly, as a solve of a study's new scene does, and not for a copy.
    """
    sc = unassembled(scene)
    t0 = time.perf_counter()
    sol = solve(sc, **options)
    return time.perf_counter() - t0, sol


def timed_batch(scenes: list, exact: list, repeats: int = 3) -> tuple:
    """Solve new copies of ``scenes`` ``repeats`` times, all in a row.

    Returns ``(steps, ms, errors)``: the steps of one pass (:attr:`isoslide.Solution.n_steps`
    summed), the median time of a pass (ms) and each scene's relative error of ``Pi1`` against
    ``exact`` (its reference answers, all positive).
    """
    times = []
    for _ in range(repeats):
        copies = [unassembled(sc) for sc in scenes]
        t0 = time.perf_counter()
        sols = [solve(sc) for sc in copies]
        times.append(time.perf_counter() - t0)
    err = np.array([abs(s.pi1 - e) / e for s, e in zip(sols, exact, strict=True)])
    return sum(s.n_steps for s in sols), 1e3 * float(np.median(times)), err


def assembly_times(scenes: list, repeats: int, shared: bool = True) -> np.ndarray:
    """Median time (s) of assembling each general scene as a solve does (:func:`isoslide.engine.system.assemble`).

    Each assembly is of a new copy (:func:`~isoslide.engine.system.unassembled`): the parts, the
    kernel's arrays, the modal data, the breakpoints and the step budget, derived from the groups.
    With ``shared``, what scenes on the same building share (its superstructure's matrices, its
    modes) is kept from the scenes assembled before, as in a study; without, it is derived anew for
    each (:func:`~isoslide.engine.system.forget_shared`), as for a study's first scene.
    """
    t = np.zeros((repeats, len(scenes)))
    for r in range(repeats):
        for k, sc in enumerate(scenes):
            sc = unassembled(sc)
            if not shared:
                forget_shared()
            t0 = time.perf_counter()
            assemble(sc, pi8=sc.pi8, coulomb=sc.rate_independent)
            t[r, k] = time.perf_counter() - t0
    return np.median(t, axis=0)


PEER_MARGIN = 2.0
"""Isolation periods (at least T_p) the peers run past the converged answer's settlement."""


def tau_max(scene: Scene, horizon: float) -> float:
    """The common end time ``tau_end + horizon * max(1, Pi3)`` (units of T_p)."""
    return scene.pulse.tau_end + horizon * max(1.0, scene.pi3)


def peer_stop(scene: Scene, horizon: float, tau_settled: float) -> float:
    """Where the peers stop on ``scene``: past the converged answer's settlement, within the horizon.

    ``min(tau_max, max(tau_end_pulse, tau_settled) + PEER_MARGIN * max(1, Pi3))`` (units of T_p),
    with ``tau_settled`` the time from which the converged exact solution proves that the
    contents never slide again (the horizon's end where it does not settle).  Every slide of
    the scene lies before it, so the peak is the same quantity as over the whole horizon; the
    margin leaves room for a peer whose last slide ends late.
    """
    end = max(scene.pulse.tau_end, tau_settled) + PEER_MARGIN * max(1.0, scene.pi3)
    return min(tau_max(scene, horizon), end)


def run_setting(setting: Setting, scene: Scene, horizon: float, max_work: int | None = None,
                stop: float | None = None, **extra) -> tuple[float, float, int, str]:
    """Run one setting on one scene: ``(pi1, seconds, work, status)``.

    The compiled solver runs to settlement (or the horizon); the peers to ``stop`` (units of T_p;
    default the horizon's end, :func:`tau_max`; see :func:`peer_stop`).

    ``work`` counts integrator steps (exact and OpenSees) or right-hand-side evaluations
    (SciPy peers).  The SciPy peers stop after ``max_work`` right-hand-side evaluations
    (None: unbounded) and the exact solver at its step budget; such a run is returned as
    ``status = "over_budget"``, any other failure is logged and returned as ``"error"``; neither
    raises.  Only ``seconds`` depends on the machine: the outcome is a function of the inputs.
    """
    end = tau_max(scene, horizon) if stop is None else float(stop)
    t0 = time.perf_counter()
    try:
        if setting.method == "exact":
            s = solve(scene, rtol=setting.rtol, horizon=horizon, **extra)
            pi1, work = s.pi1, s.n_steps
        elif setting.method == "reference":
            r = solve_reference(scene, rtol=setting.rtol, tau_max=end, max_work=max_work)
            pi1, work = r.pi1, r.work
        elif setting.method == "regularized":
            r = solve_regularized(scene, stiffness=setting.stiffness, rtol=setting.rtol,
                                  method=extra.get("regularized_method", "Radau"),
                                  tau_max=end, max_work=max_work)
            pi1, work = r.pi1, r.work
        elif setting.method == "opensees":
            r = solve_opensees(scene, stiffness=setting.stiffness, tau_max=end)
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
