"""Speed versus accuracy, measured; where the problem is stiff or slow; what each reduction buys.

This module holds the science behind ``results/datasets/accuracy.nc`` and
``reports/accuracy.html`` (and the numbers ``python -m isoslide.bench``
prints).  Everything returns labelled :class:`xarray.Dataset` objects with
``long_name``/``units`` on every variable; the report notebook only reads and
plots them.

Scene set (:func:`scene_set`)
-----------------------------
* ``study``: a deterministic subsample (fixed seed) of every study's grid of
  the configuration (``per_study`` scenes each; without a configuration the
  paper's studies of :data:`PAPER_STUDIES`);
* the hard classes of :func:`hard_scenes`: just below and just above the
  no-slide threshold, resonance with light damping, ``xi_b = 0`` and
  over-damped bases, very sharp Stribeck transitions, heavy contents, long
  isolation periods, strong viscous contact, nearly frictionless contents,
  very stiff bases and the other pulse shapes.

The converged answer
--------------------
``pi1_converged`` is the compiled solver at ``rtol = 1e-12`` with every
reduction disabled (``model="full"``); ``converged_spread`` is its difference
to a second run with the step capped at ``0.01 T_p`` (a different step
sequence).  Where the plain SciPy reference solver runs
(:func:`isoslide.reference.solve_reference` at ``rtol = 1e-12``) its answer is
stored as ``pi1_reference`` so the converged answer is checked by an
independent code.  Errors are relative, ``|Pi1 - Pi1_conv| / Pi1_conv``, over
the scenes that slide; on scenes that do not slide ``abs_error`` is the whole
error (the exact solver answers exactly 0 there).

Peers
-----
``reference``: the plain SciPy event-driven solver (:mod:`isoslide.reference`);
``regularized``: the paper's method, signum replaced by a stiff elastic-plastic spring,
SciPy Radau (:mod:`isoslide.regularized`); ``opensees`` (optional, ``accuracy.opensees``
``auto``/``true``/``false``; needs ``pip install openseespy`` and, on Debian, ``libblas3``
``liblapack3``): the same bilinear spring in OpenSees (:func:`solve_opensees`), Coulomb
scenes only.  The peers run on evenly spread subsets of the scene set.

Horizon
-------
Every method follows a scene that does not settle (``xi_b = 0``) to the same
time, ``tau_end + horizon * max(1, Pi3)`` (``horizon`` of the configuration,
default 50), so the peak is the same quantity for all of them.

Determinism
-----------
Everything in the dataset is a deterministic function of the configuration
and the code, *except* the wall-clock cost variables, whose names end in
``_seconds`` and which carry the attribute ``nondeterministic = "true"``; the
dataset attribute ``nondeterministic_variables`` lists them and
:func:`deterministic_part` drops them (compare two runs with it).  Work
counters (``work``: integrator steps for the compiled solver, right-hand-side
evaluations for the SciPy peers) are deterministic.
"""

from __future__ import annotations

import contextlib
import inspect
import math
import signal
import threading
import time
from dataclasses import dataclass, field

import numpy as np
import xarray as xr

from .scene import PI_RANGES, Scene
from .solver import peak_stuck_demand, solve

PI_INPUTS = ("pi2", "pi3", "pi4", "pi5", "pi6", "pi7", "pi8")

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

PAPER_STUDIES = {
    "fig3_newmark": {"pulse": "rectangular", "fixed": {"pi3": 0.0, "pi4": 0.0},
                     "pi2": {"start": 0.02, "stop": 1.2, "num": 60}},
    "fig5_pi3": {"dims": {"pi3": [0.01, 0.5, 1.0, 1.5, 2.0, 3.0]}},
    "fig5_pi4": {"dims": {"pi3": [1.0, 0.5, 2.0], "pi4": [0.0, 0.05, 0.1, 0.15, 0.2, 0.3]}},
    "fig6_pi5": {"dims": {"pi3": [0.5, 1.0, 2.0], "pi5": [0.5, 0.6, 0.7, 0.8, 0.9, 1.0]},
                 "fixed": {"beta": 1000.0}},
    "fig7_pi6": {"dims": {"beta": [10.0, 30.0, 100.0, 300.0, 1000.0]},
                 "fixed": {"pi3": 1.0, "pi5": 0.5}},
    "fig7_pi7": {"dims": {"pi7": [0.0, 0.25, 0.5, 1.0, 2.0, 4.903325]}, "fixed": {"pi3": 1.0}},
    "fig8_pi8": {"dims": {"pi3": [0.1, 1.0, 2.0], "pi8": [1e-5, 1e-3, 1e-2, 0.1, 0.3, 1.0]}},
}
"""The paper's studies (as in ``config/config.yaml``), used when no configuration is given."""

PAPER_CONFIG = {
    "chunk_size": 400,
    "reference": {"a_p_T_p": 9.80665},
    "defaults": {"pulse": "ricker", "pi4": 0.1, "pi5": 1.0, "pi6": 0.0, "pi7": 0.0, "pi8": 1e-5},
    "pi2": {"start": 0.02, "stop": "auto", "num": 100, "margin": 1.05, "step_round": 0.05},
    "studies": PAPER_STUDIES,
}

DOMAIN = {
    "pi2": (1e-4, 100.0, "1e-4 (nearly frictionless) to far past the no-slide threshold"),
    "pi3": (0.0, 100.0, "0 (fixed base), 1e-3 (very stiff base) to 100 (very long isolation period)"),
    "pi4": (0.0, 10.0, "0 (undamped: never settles) to over-damped (>= 1)"),
    "pi5": (0.05, 1.0, "0.05 (static friction 20 x kinetic) to 1 (Coulomb)"),
    "pi6": (0.0, 1e7, "0 (Coulomb with mu_s) to 1e7 (practically a jump from mu_s to mu_k)"),
    "pi7": (0.0, 100.0, "0 to 100 (friction dominated by the viscous term)"),
    "pi8": (0.0, 10.0, "0 (one-way coupling) to 10 (contents ten times the isolated mass)"),
}
"""The domain over which isoslide is tested (``tests/test_extremes.py``) and mapped
(:func:`domain_map`): (low, high, meaning).  :data:`isoslide.scene.PI_RANGES` is the
(wider) domain the Scene accepts."""

MAP_BASE = {"pi2": 0.1, "pi3": 1.0, "pi4": 0.1, "pi5": 0.7, "pi6": 1000.0, "pi7": 0.0, "pi8": 1e-3}
"""Base scene of the 1-D sweeps of :func:`domain_map` (Stribeck friction, resonance)."""

NONDETERMINISTIC_SUFFIX = "_seconds"


# ----------------------------------------------------------------------------------------------
# settings and configuration
# ----------------------------------------------------------------------------------------------

def settings_from(config: dict | None) -> dict:
    """The ``accuracy`` section of a configuration, with :data:`DEFAULTS` filled in.

    Accepts either the whole configuration (with an ``accuracy`` key) or the section itself.
    """
    cfg = dict(config or {})
    section = cfg.get("accuracy", cfg if not cfg.get("studies") else {}) or {}
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


# ----------------------------------------------------------------------------------------------
# scene sets
# ----------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Entry:
    """A scene of a scene set with its class and a readable label."""

    scene: Scene
    cls: str
    label: str
    study: str = ""


@dataclass(frozen=True)
class SceneSet:
    """An ordered list of :class:`Entry` (deterministic for a given configuration)."""

    entries: tuple = field(default_factory=tuple)

    def __len__(self):
        return len(self.entries)

    def __iter__(self):
        return iter(self.entries)

    def __getitem__(self, i):
        return self.entries[i]

    @property
    def scenes(self) -> list:
        return [e.scene for e in self.entries]

    def subset(self, n: int, avoid=("undamped", "long-period", "low-friction")) -> list[int]:
        """``n`` indices spread evenly over the set, spread over the classes.

        Classes in ``avoid`` (long runs) are used only when nothing else is left.
        """
        n = min(n, len(self))
        if n <= 0:
            return []
        by_class: dict = {}
        for i, e in enumerate(self.entries):
            by_class.setdefault(e.cls, []).append(i)
        order = [c for c in by_class if c not in avoid] + [c for c in by_class if c in avoid]
        picked: list[int] = []
        rank = 0
        while len(picked) < n:
            added = False
            for c in order:
                idx = by_class[c]
                if rank < len(idx):
                    # spread within the class: 0, last, middle, ...
                    j = _spread_order(len(idx))[rank]
                    picked.append(idx[j])
                    added = True
                    if len(picked) == n:
                        break
            if not added:
                break
            rank += 1
        return sorted(picked)


def _spread_order(n: int) -> list[int]:
    order, seen = [], set()
    for k in range(1, 64):
        for j in np.linspace(0, n - 1, min(n, 2 ** k - 1) if n > 1 else 1).round().astype(int):
            if int(j) not in seen:
                seen.add(int(j))
                order.append(int(j))
        if len(order) == n:
            break
    return order


def _label(sc: Scene) -> str:
    parts = [f"{k}={getattr(sc, k):.4g}" for k in PI_INPUTS]
    return " ".join(parts) + f" {sc.pulse.name}"


def study_entries(config: dict | None = None, per_study: int = 4, seed: int = 20240611) -> list[Entry]:
    """``per_study`` scenes drawn (fixed seed, without replacement) from every study's grid.

    Parameters
    ----------
    config : dict or None
        A pipeline configuration (``studies`` and the keys they inherit); ``None`` uses the
        paper's studies (:data:`PAPER_CONFIG`).
    """
    from .sweep import build_grid, check_config

    cfg = PAPER_CONFIG if not config or not config.get("studies") else config
    specs = check_config(cfg)
    out = []
    for name in sorted(specs):
        grid = build_grid(specs[name])
        rng = np.random.default_rng([seed, _stable_hash(name)])
        k = min(per_study, grid.size)
        idx = np.sort(rng.choice(grid.size, size=k, replace=False))
        for i, sc in zip(idx, grid.scenes(idx)):
            out.append(Entry(sc, "study", f"{name}[{int(i)}]", name))
    return out


def _stable_hash(text: str) -> int:
    h = 0
    for ch in text.encode():
        h = (h * 131 + ch) % (2**31 - 1)
    return h


def hard_scenes() -> list[Entry]:
    """The hard cases, by class (deterministic; thresholds computed by the solver)."""
    E = []

    def add(cls, **kw):
        sc = Scene(**kw)
        E.append(Entry(sc, cls, f"{cls}: {_label(sc)}"))

    # just below / just above the no-slide threshold: Pi2/Pi5 against the stuck demand A
    for pi3, pi4 in ((1.0, 0.1), (2.0, 0.05)):
        A = peak_stuck_demand(Scene(pi2=1.0, pi3=pi3, pi4=pi4), rtol=1e-12)
        for f in (1e-2, 1e-4, 1e-6):
            add("near-threshold", pi2=A * (1.0 - f), pi3=pi3, pi4=pi4)
        add("above-threshold", pi2=A * (1.0 + 1e-6), pi3=pi3, pi4=pi4)
    add("near-threshold", pi2=1.0 - 1e-4, pi3=0.0, pi4=0.0)              # fixed base, Ricker peak 1
    add("above-threshold", pi2=1.0 + 1e-9, pi3=0.0, pi4=0.0)
    A = peak_stuck_demand(Scene(pi2=1.0, pi3=1.0, pi4=0.1), rtol=1e-12)
    add("near-threshold", pi2=0.5 * A * (1.0 - 1e-3), pi3=1.0, pi4=0.1, pi5=0.5, pi6=1000.0)
    # resonance with light damping
    for pi4, pi2 in ((0.02, 0.02), (0.02, 0.1), (0.05, 0.05)):
        add("resonance", pi2=pi2, pi3=1.0, pi4=pi4)
    # xi_b -> 0 and over-damped
    add("undamped", pi2=0.05, pi3=1.0, pi4=0.0)
    add("undamped", pi2=0.1, pi3=2.0, pi4=0.0)
    add("undamped", pi2=0.05, pi3=1.0, pi4=1e-3)
    add("overdamped", pi2=0.05, pi3=1.0, pi4=1.0)
    add("overdamped", pi2=0.02, pi3=2.0, pi4=5.0)
    # very sharp Stribeck transitions
    for pi6 in (1e4, 1e5, 1e6):
        add("sharp-stribeck", pi2=0.2, pi3=1.0, pi4=0.1, pi5=0.5, pi6=pi6)
    add("sharp-stribeck", pi2=0.03, pi3=1.0, pi4=0.1, pi5=0.05, pi6=1e4)
    add("sharp-stribeck", pi2=0.2, pi3=0.0, pi4=0.0, pi5=0.5, pi6=1e5)
    # heavy contents
    for pi8 in (0.3, 1.0, 10.0):
        add("heavy", pi2=0.1, pi3=1.0, pi4=0.1, pi8=pi8)
    add("heavy", pi2=0.1, pi3=1.0, pi4=0.1, pi5=0.7, pi6=1000.0, pi8=1.0)
    # long isolation periods
    for pi3, pi2 in ((5.0, 0.02), (20.0, 0.01), (100.0, 0.005)):
        add("long-period", pi2=pi2, pi3=pi3, pi4=0.1)
    # strong viscous contact
    for pi7 in (10.0, 100.0):
        add("viscous", pi2=0.05, pi3=1.0, pi4=0.1, pi7=pi7)
    # nearly frictionless contents
    add("low-friction", pi2=1e-3, pi3=1.0, pi4=0.1)
    add("low-friction", pi2=1e-4, pi3=0.0, pi4=0.0)
    # very stiff bases
    add("stiff-base", pi2=0.2, pi3=1e-3, pi4=0.1)
    add("stiff-base", pi2=0.2, pi3=1e-2, pi4=0.0)
    # other pulses
    add("pulses", pi2=0.3, pi3=0.0, pi4=0.0, pulse="rectangular")
    add("pulses", pi2=0.1, pi3=1.0, pi4=0.1, pulse="antisymmetric_ricker")
    add("pulses", pi2=0.1, pi3=1.5, pi4=0.1, pulse="makris_cn")
    add("pulses", pi2=0.1, pi3=1.0, pi4=0.1, pi5=0.7, pi6=300.0, pulse="mavroeidis_papageorgiou")
    return E


def scene_set(config: dict | None = None, settings: dict | None = None) -> SceneSet:
    """The representative scene set: study subsamples plus (if ``settings["hard"]``) the hard ones."""
    s = settings_from(settings if settings is not None else config)
    entries = study_entries(config, s["per_study"], s["seed"])
    if s["hard"]:
        entries += hard_scenes()
    return SceneSet(tuple(entries))


# ----------------------------------------------------------------------------------------------
# running one setting on one scene, with a wall-clock limit
# ----------------------------------------------------------------------------------------------

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
STATUS_ATTRS = {"long_name": "outcome of the run", "units": "1",
                "flag_values": np.array(list(STATUS.values()), dtype=np.int8),
                "flag_meanings": " ".join(k.replace("-", "_") for k in STATUS)}


def tau_max(scene: Scene, horizon: float) -> float:
    """The common end time ``tau_end + horizon * max(1, Pi3)`` (units of T_p)."""
    return scene.pulse.tau_end + horizon * max(1.0, scene.pi3)


def run_setting(setting: Setting, scene: Scene, horizon: float, timeout: float | None = None,
                **extra) -> tuple[float, float, int, str]:
    """Run one setting on one scene: ``(pi1, seconds, work, status)``.

    ``work`` counts integrator steps (exact) or right-hand-side evaluations (SciPy peers).
    """
    t0 = time.perf_counter()
    try:
        with time_limit(timeout):
            if setting.method == "exact":
                s = solve(scene, rtol=setting.rtol, horizon=horizon, **extra)
                pi1, work = s.pi1, s.n_steps
            elif setting.method == "reference":
                from .reference import solve_reference
                r = solve_reference(scene, rtol=setting.rtol, tau_max=tau_max(scene, horizon))
                pi1, work = r.pi1, r.nfev
            elif setting.method == "regularized":
                from .regularized import solve_regularized
                r = solve_regularized(scene, stiffness=setting.stiffness, rtol=setting.rtol,
                                      method=extra.get("regularized_method", "Radau"),
                                      tau_max=tau_max(scene, horizon))
                pi1, work = r.pi1, r.nfev
            elif setting.method == "opensees":
                pi1, work = solve_opensees(scene, stiffness=setting.stiffness,
                                           tau_max=tau_max(scene, horizon))
            else:
                raise ValueError(f"unknown method {setting.method!r}")
    except SceneTimeout:
        return math.nan, time.perf_counter() - t0, -1, "timeout"
    except Exception as err:  # recorded, never fatal: the report lists failures
        print(f"[accuracy] {setting.name} failed on {scene!r}: {err!r}", flush=True)
        return math.nan, time.perf_counter() - t0, -1, "error"
    return float(pi1), time.perf_counter() - t0, int(work), "ok"


def _warm_up():
    """Compile the kernel (and load numba caches) before anything is timed."""
    for sc in (Scene(pi2=0.2, pi3=1.0, pi4=0.1), Scene(pi2=0.2, pi3=0.0, pi5=0.5, pi6=10.0),
               Scene(pi2=0.2, pi3=1.0, pi4=0.1, pi7=1.0)):
        solve(sc)
        peak_stuck_demand(sc)


# ----------------------------------------------------------------------------------------------
# the trade: error versus cost
# ----------------------------------------------------------------------------------------------

def converged(entries, settings: dict, reference_idx=()) -> dict:
    """Converged answers: ``pi1_converged``, ``converged_spread`` and ``pi1_reference``."""
    n = len(entries)
    conv = np.full(n, np.nan)
    spread = np.full(n, np.nan)
    ref = np.full(n, np.nan)
    rtol = settings["converged_rtol"]
    H = settings["horizon"]
    can_cap = "max_step" in inspect.signature(solve).parameters
    for i, e in enumerate(entries):
        a = solve(e.scene, rtol=rtol, horizon=H, model="full").pi1
        conv[i] = a
        if can_cap:
            b = solve(e.scene, rtol=rtol, horizon=H, model="full", max_step=0.01).pi1
            spread[i] = abs(a - b) / a if a > 0 else abs(a - b)
    for i in reference_idx:
        pi1, _, _, st = run_setting(Setting("reference converged", "reference", rtol), entries[i].scene,
                                    H, timeout=settings["peer_timeout"])
        ref[i] = pi1 if st == "ok" else np.nan
    return {"pi1_converged": conv, "converged_spread": spread, "pi1_reference": ref}


def _rel_error(pi1, conv):
    pi1 = np.asarray(pi1, dtype=float)
    conv = np.broadcast_to(np.asarray(conv, dtype=float), pi1.shape)
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = np.where(conv > 0, np.abs(pi1 - conv) / np.where(conv > 0, conv, 1.0), np.nan)
    return rel


def _scene_coords(entries) -> dict:
    coords = {"scene": ("scene", np.arange(len(entries), dtype=np.int32),
                        {"long_name": "scene number in the accuracy scene set", "units": "1"})}
    for k in PI_INPUTS:
        from .datasets import pi_attrs
        coords[k] = ("scene", np.array([getattr(e.scene, k) for e in entries], dtype=float), pi_attrs(k))
    coords["pulse"] = ("scene", np.array([e.scene.pulse.name for e in entries], dtype=str),
                       {"long_name": "ground-acceleration pulse shape", "units": "1"})
    coords["scene_class"] = ("scene", np.array([e.cls for e in entries], dtype=str),
                             {"long_name": "scene class: study subsample or hard case", "units": "1"})
    coords["scene_label"] = ("scene", np.array([e.label for e in entries], dtype=str),
                             {"long_name": "scene description", "units": "1"})
    return coords


def _setting_coords(sets) -> dict:
    return {
        "setting": ("setting", np.array([s.name for s in sets], dtype=str),
                    {"long_name": "method and accuracy setting", "units": "1"}),
        "method": ("setting", np.array([s.method for s in sets], dtype=str),
                   {"long_name": "solution method: exact (isoslide.solve), reference (plain SciPy "
                                 "solve_ivp event-driven), regularized (paper-style stiff spring, SciPy "
                                 "Radau), opensees (optional peer)", "units": "1"}),
        "rtol": ("setting", np.array([s.rtol for s in sets], dtype=float),
                 {"long_name": "tolerance handed to the method (isoslide: target relative error of Pi1; "
                               "SciPy peers: solve_ivp rtol)", "units": "1"}),
        "stiffness": ("setting", np.array([s.stiffness for s in sets], dtype=float),
                      {"long_name": "regularising stiffness K = k_r T_p^2 / m_EC (nan: not regularised)",
                       "units": "1"}),
    }


def measure_trade(entries, settings: dict, part: str | None = None, log=print) -> xr.Dataset:
    """Error and cost of every setting (of ``part``) on the scene set.

    The compiled solver's settings run on every scene, ``repeats`` times, interleaved
    (setting after setting, then the next repetition) so that they are timed side by side;
    the cost is the median.  The SciPy peers run on an evenly spread subset
    (``reference_scenes``/``regularized_scenes``) with ``peer_repeats`` and a wall-clock
    limit of ``peer_timeout`` seconds per run.

    Parameters
    ----------
    entries : SceneSet or list of Entry
    settings : dict
        :func:`settings_from` output.
    part : {None, "exact", "reference", "regularized"}
        Which method family to measure (``"exact"`` includes the reference peer).
    """
    if not isinstance(entries, SceneSet):
        entries = SceneSet(tuple(entries))
    sets = method_settings(settings, part)
    n, m = len(entries), len(sets)
    H = settings["horizon"]
    pi1 = np.full((m, n), np.nan)
    secs = np.full((m, n), np.nan)
    work = np.full((m, n), -1, dtype=np.int64)
    status = np.full((m, n), STATUS["not-run"], dtype=np.int8)
    ref_idx = entries.subset(settings["reference_scenes"])
    reg_idx = entries.subset(settings["regularized_scenes"])
    coulomb = [i for i, e in enumerate(entries) if e.scene.rate_independent]
    os_idx = [coulomb[k] for k in SceneSet(tuple(entries[i] for i in coulomb)).subset(settings["opensees_scenes"])]
    _warm_up()
    extra = {"regularized_method": settings["regularized_method"]}
    exact_rows = [j for j, s in enumerate(sets) if s.method == "exact"]
    for i, e in enumerate(entries):
        runs = {j: [] for j in exact_rows}
        for _ in range(settings["repeats"]):
            for j in exact_rows:
                p, t, w, st = run_setting(sets[j], e.scene, H)
                runs[j].append(t)
                pi1[j, i], work[j, i], status[j, i] = p, w, STATUS[st]
        for j in exact_rows:
            secs[j, i] = float(np.median(runs[j]))
    for j, s in enumerate(sets):
        if s.method == "exact":
            continue
        idx = {"reference": ref_idx, "regularized": reg_idx, "opensees": os_idx}[s.method]
        for i in idx:
            ts = []
            for _ in range(settings["peer_repeats"]):
                p, t, w, st = run_setting(s, entries[i].scene, H, settings["peer_timeout"], **extra)
                ts.append(t)
                if st != "ok":
                    break
            pi1[j, i], work[j, i], status[j, i] = p, w, STATUS[st]
            secs[j, i] = float(np.median(ts))
            log(f"[accuracy] {s.name} scene {i} ({entries[i].cls}): pi1={p:.10g} {secs[j, i]:.3f} s {st}")
    conv = converged(entries, settings, ref_idx if part in (None, "exact", "reference") else ())
    rel = _rel_error(pi1, conv["pi1_converged"][None, :])
    abs_err = np.abs(pi1 - conv["pi1_converged"][None, :])
    coords = _scene_coords(entries.entries)
    coords.update(_setting_coords(sets))
    ds = xr.Dataset(
        {
            "pi1": (("setting", "scene"), pi1, {"long_name": "Pi1 = u_max / (a_p T_p^2) of the setting",
                                                "units": "1"}),
            "rel_error": (("setting", "scene"), rel,
                          {"long_name": "relative error |Pi1 - Pi1_converged| / Pi1_converged "
                                        "(nan: not run, or the scene does not slide)", "units": "1"}),
            "abs_error": (("setting", "scene"), abs_err,
                          {"long_name": "absolute error |Pi1 - Pi1_converged|", "units": "1"}),
            "cost_seconds": (("setting", "scene"), secs,
                             {"long_name": "wall-clock time per scene (median over repetitions)",
                              "units": "s", "nondeterministic": "true",
                              "comment": "measured, not reproducible: the only non-deterministic "
                                         "kind of variable in this dataset"}),
            "work": (("setting", "scene"), work,
                     {"long_name": "work per scene: integrator steps (exact, incl. rejected and "
                                   "event-location steps) or right-hand-side evaluations (SciPy peers); "
                                   "-1 not run", "units": "1"}),
            "status": (("setting", "scene"), status, dict(STATUS_ATTRS)),
            "pi1_converged": ("scene", conv["pi1_converged"],
                              {"long_name": "converged Pi1: isoslide.solve at rtol=%g, model='full'"
                                            % settings["converged_rtol"], "units": "1"}),
            "converged_spread": ("scene", conv["converged_spread"],
                                 {"long_name": "relative change of the converged Pi1 when the step is "
                                               "capped at 0.01 T_p (a different step sequence)",
                                  "units": "1"}),
            "pi1_reference": ("scene", conv["pi1_reference"],
                              {"long_name": "Pi1 of the independent plain-SciPy reference solver at "
                                            "rtol=%g (nan: not run on this scene)"
                                            % settings["converged_rtol"], "units": "1"}),
        },
        coords=coords,
    )
    return ds


def summarize_trade(ds: xr.Dataset, default_rtol: float = 1e-6, error_floor: float = 1e-6) -> xr.Dataset:
    """Per-setting statistics over the sliding scenes each setting ran on; adds the default bound.

    Relative errors are summarised over every sliding scene (``error_*``) and over the scenes
    that slide at least ``error_floor`` (units of a_p T_p^2, ``error_*_significant``); below
    the floor the absolute error is summarised (``abs_error_max_small``): a slide of 1e-13
    a_p T_p^2 is below the integrator's absolute tolerance and its relative error is not
    controlled.
    """
    sl = ds["pi1_converged"] > 0
    big = ds["pi1_converged"] >= error_floor
    ok = ds["status"] == STATUS["ok"]
    e = ds["rel_error"].where(sl & ok)
    c = ds["cost_seconds"].where(ok)
    w = ds["work"].where(ok & (ds["work"] >= 0))
    out = ds.copy()
    q = lambda da, f: xr.apply_ufunc(lambda a: _nanq(a, f), da, input_core_dims=[["scene"]],  # noqa: E731
                                     vectorize=True)
    out["n_scenes"] = (ok).sum("scene").astype(np.int32).assign_attrs(
        long_name="scenes the setting ran on successfully", units="1")
    out["n_failed"] = ((ds["status"] == STATUS["error"]) | (ds["status"] == STATUS["timeout"])).sum(
        "scene").astype(np.int32).assign_attrs(long_name="scenes with an error or a timeout", units="1")
    out["error_median"] = q(e, 50).assign_attrs(long_name="median relative error of Pi1 over sliding scenes",
                                                units="1")
    out["error_p95"] = q(e, 95).assign_attrs(long_name="95th percentile of the relative error", units="1")
    out["error_max"] = q(e, 100).assign_attrs(long_name="largest relative error of Pi1 over sliding scenes",
                                              units="1")
    out["error_max_significant"] = q(e.where(big), 100).assign_attrs(
        long_name=f"largest relative error over scenes with Pi1 >= {error_floor:g}", units="1")
    out["error_median_significant"] = q(e.where(big), 50).assign_attrs(
        long_name=f"median relative error over scenes with Pi1 >= {error_floor:g}", units="1")
    out["abs_error_max_small"] = q(ds["abs_error"].where(ok & ~big), 100).assign_attrs(
        long_name=f"largest absolute error of Pi1 over scenes with Pi1 < {error_floor:g} "
                  f"(including those that do not slide)", units="1")
    out.attrs["error_floor"] = float(error_floor)
    fs = ((ds["abs_error"] > 0) & ~sl & ok).sum("scene").astype(np.int32)
    out["false_slides"] = fs.assign_attrs(long_name="scenes that do not slide but got Pi1 > 0", units="1")
    out["cost_median_seconds"] = q(c, 50).assign_attrs(long_name="median wall-clock cost per scene",
                                                       units="s", nondeterministic="true")
    out["work_median"] = q(w, 50).assign_attrs(long_name="median work per scene (see work)", units="1")
    # the same statistics on the subset every setting ran on, for a like-for-like comparison
    common = ok.all("setting") if ds.sizes["setting"] else ok.any("setting")
    out["common_scene"] = common.astype(np.int8).assign_attrs(
        long_name="scene on which every setting ran (like-for-like comparison)", units="1")
    out["error_max_common"] = q(e.where(common), 100).assign_attrs(
        long_name="largest relative error over the common sliding scenes", units="1")
    out["cost_median_common_seconds"] = q(c.where(common), 50).assign_attrs(
        long_name="median cost per scene over the common scenes", units="s", nondeterministic="true")
    names = [str(s) for s in ds["setting"].values]
    dname = f"exact rtol={default_rtol:.0e}"
    if dname in names:
        j = names.index(dname)
        out.attrs["default_setting"] = dname
        out.attrs["default_error_bound"] = float(out["error_max"].values[j])
        out.attrs["default_error_median"] = float(out["error_median"].values[j])
        out.attrs["default_error_bound_significant"] = float(out["error_max_significant"].values[j])
        out.attrs["default_abs_error_bound_small"] = float(out["abs_error_max_small"].values[j])
    return out


def _nanq(a, f):
    a = np.asarray(a, dtype=float)
    a = a[np.isfinite(a)]
    if a.size == 0:
        return np.nan
    return float(np.percentile(a, f))


# ----------------------------------------------------------------------------------------------
# model reductions: error against the full model, and the saving
# ----------------------------------------------------------------------------------------------

NOSLIDE_COLUMN = 20
"""Scenes per base over which the no-slide shortcut's cost is amortised (a Pi2 column)."""

REDUCTIONS = ("fixed-base", "no-slide", "coulomb", "one-way", "settlement")
REDUCTION_TEXT = {
    "fixed-base": "Pi3 = 0: floor = ground (base not integrated); full model: the same scene with a "
                  "very stiff, damped base, Pi3 = 1e-3, xi_b = 0.1",
    "no-slide": "batch shortcut of solve_many: Pi1 = 0 without integrating the block when Pi2/Pi5 "
                "exceeds the stuck floor's peak demand (one demand per base, cost per scene amortised "
                "over a column of 20 Pi2 values); full model: solve(model='full') per scene",
    "coulomb": "rate-independent friction: the Stribeck terms are not evaluated; full model: "
               "solve(model='full')",
    "one-way": "the block's back-reaction on the base is dropped (Pi8 -> 0 in the base equation); "
               "isoslide takes it by itself only where its a-posteriori bound is under rtol/10 "
               "(red_taken); full model: solve(model='full') with the scene's Pi8",
    "settlement": "integration stops when no further sliding is possible; full model: followed to "
                  "the horizon (settle=False)",
}


def _full_variant(red: str, sc: Scene):
    """(scene, kwargs) of the full model for reduction ``red``, or None if not applicable."""
    if red == "fixed-base":
        if sc.pi3 != 0.0:
            return None
        return Scene(pi2=sc.pi2, pi3=1e-3, pi4=0.1, pi5=sc.pi5, pi6=sc.pi6, pi7=sc.pi7,
                     pi8=sc.pi8, pulse=sc.pulse), {"model": "full"}
    if red == "settlement":
        return sc, {"settle": False}
    if red == "one-way":
        return sc, {"model": "full"}
    return sc, {"model": "full"}


def measure_reductions(entries, settings: dict, log=print) -> xr.Dataset:
    """For each reduction and each scene it applies to: Pi1 and cost, reduced versus full.

    Both variants of a scene are timed side by side (interleaved, ``reduction_repeats``
    times, median).  A reduction applies to a scene when the solver actually takes it
    (by its model label: ``fixed-base``, ``coulomb``, ``one-way``; ``no-slide`` when
    :func:`isoslide.solve_many` answers without integrating; settlement on every scene
    that settles).
    """
    from .solver import solve_many

    if not isinstance(entries, SceneSet):
        entries = SceneSet(tuple(entries))
    can_settle = "settle" in inspect.signature(solve).parameters
    n, m = len(entries), len(REDUCTIONS)
    H = settings["horizon"]
    R = settings["reduction_repeats"]
    rtol = settings["default_rtol"]
    shape = (m, n)
    pr, pf = np.full(shape, np.nan), np.full(shape, np.nan)
    tr, tf = np.full(shape, np.nan), np.full(shape, np.nan)
    wr, wf = np.full(shape, -1, np.int64), np.full(shape, -1, np.int64)
    taken = np.zeros(shape, dtype=bool)
    _warm_up()
    for i, e in enumerate(entries):
        sc = e.scene
        auto = solve(sc, rtol=rtol, horizon=H)
        label = auto.model
        applies = {
            "fixed-base": "fixed-base" in label,
            "coulomb": "coulomb" in label,
            "one-way": sc.pi3 > 0 and sc.pi8 > 0,
            "settlement": auto.settled and can_settle,
        }
        batch = solve_many([sc], rtol=rtol, horizon=H)
        applies["no-slide"] = "no-slide" in str(batch.model[0]) and batch.n_steps[0] == 0
        taken[REDUCTIONS.index("one-way"), i] = "one-way" in label and sc.pi8 > 0
        taken[REDUCTIONS.index("fixed-base"), i] = applies["fixed-base"]
        taken[REDUCTIONS.index("coulomb"), i] = applies["coulomb"]
        taken[REDUCTIONS.index("no-slide"), i] = applies["no-slide"]
        taken[REDUCTIONS.index("settlement"), i] = applies["settlement"]
        oneway_scene = Scene(pi2=sc.pi2, pi3=sc.pi3, pi4=sc.pi4, pi5=sc.pi5, pi6=sc.pi6, pi7=sc.pi7,
                             pi8=0.0, pulse=sc.pulse)
        for k, red in enumerate(REDUCTIONS):
            if not applies[red]:
                continue
            full_sc, kw = _full_variant(red, sc)
            t_red, t_full = [], []
            # the no-slide shortcut shares one stuck-demand computation per base: time it on a
            # column of NOSLIDE_COLUMN scenes (Pi2 above the threshold) as in a study grid
            column = [sc] + [Scene(pi2=sc.pi2 * (1.0 + 0.01 * q), pi3=sc.pi3, pi4=sc.pi4, pi5=sc.pi5,
                                   pi6=sc.pi6, pi7=sc.pi7, pi8=sc.pi8, pulse=sc.pulse)
                             for q in range(1, NOSLIDE_COLUMN)]
            for _ in range(R):
                t0 = time.perf_counter()
                if red == "no-slide":
                    b = solve_many(column, rtol=rtol, horizon=H)
                    p_red, w_red = float(b.pi1[0]), int(b.n_steps[0])
                elif red == "one-way":
                    s = solve(oneway_scene, rtol=rtol, horizon=H, model="full")
                    p_red, w_red = s.pi1, s.n_steps
                else:
                    s = solve(sc, rtol=rtol, horizon=H)
                    p_red, w_red = s.pi1, s.n_steps
                t_red.append((time.perf_counter() - t0) / (len(column) if red == "no-slide" else 1))
                t0 = time.perf_counter()
                f = solve(full_sc, rtol=rtol, horizon=H, **kw)
                t_full.append(time.perf_counter() - t0)
            pr[k, i], pf[k, i] = p_red, f.pi1
            wr[k, i], wf[k, i] = w_red, f.n_steps
            tr[k, i], tf[k, i] = np.median(t_red), np.median(t_full)
    coords = _scene_coords(entries.entries)
    coords["reduction"] = ("reduction", np.array(REDUCTIONS, dtype=str),
                           {"long_name": "model reduction made by isoslide.solve", "units": "1"})
    coords["reduction_text"] = ("reduction", np.array([REDUCTION_TEXT[r] for r in REDUCTIONS], dtype=str),
                                {"long_name": "what the reduction does and what it is compared with",
                                 "units": "1"})
    dims = ("reduction", "scene")
    with np.errstate(divide="ignore", invalid="ignore"):
        scale = np.maximum(np.abs(pf), 0.0)
        rel = np.where(scale > 0, np.abs(pr - pf) / np.where(scale > 0, scale, 1.0),
                       np.where(np.isfinite(pr), np.abs(pr - pf), np.nan))
    ds = xr.Dataset(
        {
            "red_pi1": (dims, pr, {"long_name": "Pi1 with the reduction (default rtol)", "units": "1"}),
            "red_pi1_full": (dims, pf, {"long_name": "Pi1 of the full model (default rtol)", "units": "1"}),
            "red_error": (dims, rel, {"long_name": "|Pi1_reduced - Pi1_full| / Pi1_full (absolute "
                                                   "difference where Pi1_full = 0; nan: not applicable)",
                                      "units": "1"}),
            "red_taken": (dims, taken.astype(np.int8),
                          {"long_name": "isoslide.solve (or solve_many) takes this reduction by itself on "
                                        "this scene at the default rtol", "units": "1"}),
            "red_work": (dims, wr, {"long_name": "integrator steps with the reduction (-1: n/a)", "units": "1"}),
            "red_work_full": (dims, wf, {"long_name": "integrator steps of the full model (-1: n/a)",
                                         "units": "1"}),
            "red_cost_seconds": (dims, tr, {"long_name": "wall-clock time with the reduction (median)",
                                            "units": "s", "nondeterministic": "true"}),
            "red_cost_full_seconds": (dims, tf, {"long_name": "wall-clock time of the full model (median)",
                                                 "units": "s", "nondeterministic": "true"}),
        },
        coords=coords,
    )
    return ds


# ----------------------------------------------------------------------------------------------
# the domain map: where the problem is stiff or slow, and what the solver does there
# ----------------------------------------------------------------------------------------------

def map_values(group: str, npts: int = 9) -> np.ndarray:
    """Values of ``group`` swept by :func:`domain_map` across :data:`DOMAIN` (zero included)."""
    lo, hi, _ = DOMAIN[group]
    if group == "pi5":
        return np.linspace(lo, hi, npts)
    if group == "pi4":
        return np.concatenate([[0.0], np.logspace(-3, 1, npts - 1)])
    if group == "pi3":
        return np.concatenate([[0.0], np.logspace(-3, 2, npts - 1)])
    if lo == 0.0:
        return np.concatenate([[0.0], np.logspace(-3 if group != "pi6" else -1, math.log10(hi), npts - 1)])
    return np.logspace(math.log10(lo), math.log10(hi), npts)


def domain_map(settings: dict, base: dict | None = None, log=print) -> xr.Dataset:
    """1-D sweeps of every input group across its domain from :data:`MAP_BASE`.

    For each point: Pi1 (default and converged), integrator steps, transitions, model label,
    settled flag, end time, and the wall-clock cost (median of ``map_repeats``).
    """
    base = dict(MAP_BASE if base is None else base)
    npts = settings["map_points"]
    H = settings["horizon"]
    rtol = settings["default_rtol"]
    groups = list(PI_INPUTS)
    shape = (len(groups), npts)
    vals = np.full(shape, np.nan)
    out = {k: np.full(shape, np.nan) for k in ("pi1", "pi1_conv", "cost", "tau_end")}
    steps = np.full(shape, -1, np.int64)
    events = np.full(shape, -1, np.int64)
    settled = np.full(shape, -1, np.int8)
    models = np.full(shape, "", dtype=object)
    _warm_up()
    for g, name in enumerate(groups):
        for k, v in enumerate(map_values(name, npts)):
            kw = dict(base)
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
            "map_rel_error": (dims, _rel_error(out["pi1"], out["pi1_conv"]),
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


# ----------------------------------------------------------------------------------------------
# assembling the dataset
# ----------------------------------------------------------------------------------------------

PARTS = ("exact", "regularized", "reductions", "map")
"""Independent pieces of the accuracy dataset (one pipeline job each)."""


def measure_part(part: str, config: dict | None = None, log=print) -> xr.Dataset:
    """Measure one part (see :data:`PARTS`) for ``config`` (whole config or its accuracy section)."""
    settings = settings_from(config)
    if part == "map":
        return domain_map(settings, log=log)
    entries = scene_set(config, settings)
    if part == "exact":
        return measure_trade(entries, settings, "exact", log=log)
    if part == "regularized":
        return measure_trade(entries, settings, "regularized", log=log)
    if part == "reductions":
        return measure_reductions(entries, settings, log=log)
    raise ValueError(f"part = {part!r} is invalid; allowed: {PARTS}")


def combine(parts: dict, config: dict | None = None) -> xr.Dataset:
    """Merge the parts into the accuracy dataset, add summaries and metadata."""
    from .datasets import global_attrs

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
                "ending in _seconds) differ between runs of the same configuration; drop them with "
                "isoslide.accuracy.deterministic_part before comparing. Timings were taken on a shared "
                "machine: compare settings within one run, not across runs.",
        domain="; ".join(f"{k}: {v[2]}" for k, v in DOMAIN.items()),
        **extra, **map_attrs)
    return ds


def accuracy_dataset(config: dict | None = None, parts=PARTS, log=print) -> xr.Dataset:
    """Measure every part in this process and combine them (for tests and small runs)."""
    return combine({p: measure_part(p, config, log=log) for p in parts}, config)


def deterministic_part(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` without its wall-clock variables (those reproduce only up to timing noise)."""
    drop = [v for v in ds.data_vars if v.endswith(NONDETERMINISTIC_SUFFIX)]
    return ds.drop_vars(drop)


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


# ----------------------------------------------------------------------------------------------
# OpenSees (optional peer)
# ----------------------------------------------------------------------------------------------

def opensees_available() -> bool:
    """True when ``openseespy`` imports (``pip install openseespy``; Debian libblas3 liblapack3)."""
    try:
        import openseespy.opensees  # noqa: F401
    except Exception:
        return False
    return True


def solve_opensees(scene: Scene, stiffness: float = 1e6, tau_max: float | None = None,
                   dtau: float | None = None) -> tuple[float, int]:
    """Pi1 of a Coulomb scene with OpenSees (elastic-perfectly-plastic friction spring, Newmark).

    Two-DOF model in dimensionless units (masses 1 and Pi8, lengths a_p T_p^2, time T_p):
    the base on a linear spring ``w^2`` with a dashpot ``2 z w`` (``Elastic`` material with
    damping tangent), the block on an ``ElasticPP`` spring of stiffness ``K Pi8`` and yield
    force ``Pi8 Pi2/Pi5`` (the paper's bilinear regularisation with a very large initial
    stiffness), under ``UniformExcitation`` by the ground acceleration ``p`` sampled every
    ``dtau`` (default ``min(1e-3, T_r / 10)``, ``T_r = 2 pi / sqrt(K)``), average-acceleration
    Newmark with Newton iterations.  A fixed base ties the block to the ground.  Coulomb
    friction only (``Pi7 = 0`` and ``Pi5 = 1`` or ``Pi6 = 0``).  Returns ``(pi1, steps)``.
    """
    import openseespy.opensees as ops

    if not scene.rate_independent:
        raise ValueError("the OpenSees peer models Coulomb friction only")
    pulse = scene.pulse
    mu = scene.static_level
    K = float(stiffness)
    if dtau is None:
        dtau = min(1e-3, 2.0 * math.pi / math.sqrt(K) / 10.0)
    end = tau_max if tau_max is not None else pulse.tau_end + 50.0 * max(1.0, scene.pi3)
    n = int(math.ceil((end - pulse.tau_start) / dtau))
    tt = pulse.tau_start + dtau * np.arange(n + 1)
    acc = pulse.accel(tt)
    m_c = max(scene.pi8, 1e-6)
    ops.wipe()
    ops.model("basic", "-ndm", 1, "-ndf", 1)
    ops.node(1, 0.0)
    ops.fix(1, 1)
    ops.node(3, 0.0)
    ops.mass(3, m_c)
    floor = 1
    if not scene.fixed_base:
        w = 2.0 * math.pi / scene.pi3
        ops.node(2, 0.0)
        ops.mass(2, 1.0)
        ops.uniaxialMaterial("Elastic", 1, w * w, 2.0 * scene.pi4 * w)
        ops.element("zeroLength", 1, 1, 2, "-mat", 1, "-dir", 1)
        floor = 2
    k_r = K * m_c
    ops.uniaxialMaterial("ElasticPP", 2, k_r, mu * m_c / k_r)
    ops.element("zeroLength", 2, floor, 3, "-mat", 2, "-dir", 1)
    ops.timeSeries("Path", 1, "-dt", dtau, "-values", *acc.tolist())
    ops.pattern("UniformExcitation", 1, 1, "-accel", 1)
    ops.constraints("Plain")
    ops.numberer("Plain")
    ops.system("FullGeneral")
    ops.test("NormDispIncr", 1e-14, 50)
    ops.algorithm("Newton")
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")
    umax = 0.0
    for _ in range(n):
        if ops.analyze(1, dtau) != 0:
            ops.wipe()
            raise RuntimeError("OpenSees analysis failed")
        u = ops.nodeDisp(3, 1) - (ops.nodeDisp(floor, 1) if floor != 1 else 0.0)
        umax = max(umax, abs(u))
    ops.wipe()
    return umax, n
