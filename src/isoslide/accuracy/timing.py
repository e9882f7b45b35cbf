"""Running one setting on one scene, timed and with a wall-clock limit."""

from __future__ import annotations

import contextlib
import logging
import math
import signal
import threading
import time

import numpy as np

from ..peers import solve_opensees, solve_reference, solve_regularized
from ..scene import Scene
from ..solver import peak_stuck_demand, solve
from .settings import Setting

log = logging.getLogger(__name__)


class SceneTimeout(Exception):
    """A run exceeded its wall-clock limit."""


@contextlib.contextmanager
def time_limit(seconds: float | None):
    """Raise :class:`SceneTimeout` in the block after ``seconds`` (main thread, POSIX only)."""
    usable = (seconds is not None and seconds > 0 and hasattr(signal, "setitimer")
              and threading.current_thread() is threading.main_thread())
    if not usable:
        yield
        return

    def handler(signum, frame):
        raise SceneTimeout(f"over {seconds:g} s")

    old = signal.signal(signal.SIGALRM, handler)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)


STATUS = {"ok": 0, "error": 1, "timeout": 2, "not-run": 3}
"""Outcome of a run and its code in the ``status`` variable."""
STATUS_ATTRS = {"long_name": "outcome of the run", "units": "1",
                "flag_values": np.array(list(STATUS.values()), dtype=np.int8),
                "flag_meanings": " ".join(k.replace("-", "_") for k in STATUS)}
"""CF attributes of the ``status`` variable."""


def tau_max(scene: Scene, horizon: float) -> float:
    """The common end time ``tau_end + horizon * max(1, Pi3)`` (units of T_p)."""
    return scene.pulse.tau_end + horizon * max(1.0, scene.pi3)


def run_setting(setting: Setting, scene: Scene, horizon: float, timeout: float | None = None,
                **extra) -> tuple[float, float, int, str]:
    """Run one setting on one scene: ``(pi1, seconds, work, status)``.

    ``work`` counts integrator steps (exact and OpenSees) or right-hand-side evaluations
    (SciPy peers).  A failure is logged and returned as ``status = "error"``, a run over
    ``timeout`` seconds as ``"timeout"``; neither raises.
    """
    t0 = time.perf_counter()
    try:
        with time_limit(timeout):
            if setting.method == "exact":
                s = solve(scene, rtol=setting.rtol, horizon=horizon, **extra)
                pi1, work = s.pi1, s.n_steps
            elif setting.method == "reference":
                r = solve_reference(scene, rtol=setting.rtol, tau_max=tau_max(scene, horizon))
                pi1, work = r.pi1, r.work
            elif setting.method == "regularized":
                r = solve_regularized(scene, stiffness=setting.stiffness, rtol=setting.rtol,
                                      method=extra.get("regularized_method", "Radau"),
                                      tau_max=tau_max(scene, horizon))
                pi1, work = r.pi1, r.work
            elif setting.method == "opensees":
                r = solve_opensees(scene, stiffness=setting.stiffness, tau_max=tau_max(scene, horizon))
                pi1, work = r.pi1, r.work
            else:
                raise ValueError(f"unknown method {setting.method!r}")
    except SceneTimeout:
        return math.nan, time.perf_counter() - t0, -1, "timeout"
    except Exception as err:  # recorded, never fatal: the report lists failures
        log.warning("%s failed on %r: %r", setting.name, scene, err)
        return math.nan, time.perf_counter() - t0, -1, "error"
    return float(pi1), time.perf_counter() - t0, int(work), "ok"


def warm_up():
    """Compile the kernel (and load numba caches) before anything is timed."""
    for sc in (Scene(pi2=0.2, pi3=1.0, pi4=0.1), Scene(pi2=0.2, pi3=0.0, pi5=0.5, pi6=10.0),
               Scene(pi2=0.2, pi3=1.0, pi4=0.1, pi7=1.0)):
        solve(sc)
        peak_stuck_demand(sc)
