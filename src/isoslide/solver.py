"""Solve a scene: exact stick-slip response and peak sliding ``Pi1``.

:func:`solve` runs the smallest model that is exact for the scene
(:func:`plan` says which) through the compiled kernel of
:mod:`isoslide.engine.kernel`; :func:`solve_many` does the same for many scenes and
skips the block entirely where the floor can never reach the static threshold.

Accuracy knob
-------------
``rtol`` is the target relative error of ``Pi1`` (default ``1e-6``).  It sets
the local tolerance of the Dormand-Prince 8(5,3) integrator to
``rtol * INTEGRATOR_FACTOR`` (relative; ``rtol * INTEGRATOR_FACTOR *
ATOL_SCALE`` absolute for the base, ``kernel.ATOL_SLIDE`` times less for the
slide), tightened for lightly damped bases (error grows with the periods
followed).  One refinement pass follows where ``Pi1`` is ill-conditioned: a
slide just above the no-slide threshold (:func:`near_threshold_rtol`) and
scenes with more than ``MANY_EVENTS`` transitions.  With these rules the
measured error stays far below ``rtol``: at the default, 2.2e-8 relative over
the 83 scenes of ``python -m isoslide.bench`` (``tests/test_solver.py``,
``tests/test_extremes.py`` and ``tests/test_cross_check.py`` guard it).
Transition times are located to ~1e-13 whatever ``rtol`` is, and exact zeros
(no sliding) are exactly zero.

Models (``Solution.model``, joined by ``+``)
--------------------------------------------
``fixed-base``
    ``Pi3 = 0``: floor = ground; the base is not integrated and ``Pi4``,
    ``Pi8`` have no effect.
``no-slide``
    The floor demand never reaches ``mu_s g``: ``Pi1 = 0`` exactly.  In a
    batch, decided once per base (``Pi3, Pi4, Pi8, pulse``) from the peak
    demand of the stuck system, with no block integration at all.
``coulomb``
    Friction independent of speed (``Pi7 = 0`` and ``Pi5 = 1`` or
    ``Pi6 = 0``): the Stribeck terms are not evaluated.
``one-way``
    The block's back-reaction on the base is dropped (``Pi8 = 0``): used when
    ``Pi8 = 0``, or, for Coulomb friction, when the a-posteriori bound below
    is under ``rtol / 10`` of ``Pi1``.  For rate-independent friction the map
    from floor velocity to block velocity is non-expansive, so
    ``|dPi1| <= 2 T sup|dv_floor|``, and the back-reaction changes the floor
    velocity by at most ``Pi8 (Pi2/Pi5) int |h'|`` (``h`` the base's impulse
    response); ``T`` is taken as twice the decoupled response's duration.
``stribeck``
    The full Stribeck law with two-way coupling (the general model).
``+piecewise``
    A sampled record with Coulomb contents on a linear or fixed base
    (:func:`piecewise_applies`): every phase is propagated exactly between
    samples by :mod:`isoslide.engine.piecewise` (no integrator, no refinement pass;
    the answer is exact to round-off, whatever ``rtol``).
"""

from __future__ import annotations

import dataclasses
import logging
import math
from dataclasses import dataclass, field

import numpy as np

from .engine import (building, building_kernel, exponential, kernel, piecewise, planar_kernel, planar_piecewise, tfp_flow,
                     tfp_plane)
from .engine.planar import excitation, pair_grid
from .engine.system import (DEFAULT_HORIZON, STEPS_PER_PERIOD, assemble, excitation_end, horizon_end,  # noqa: F401
                            step_budget)
from .store.history import History
from .model.parts import building_of
from .models import BEARING_REDUCTIONS, Facets
from .peers import SCENE_SOLVERS, PeerResult, solve_reference_planar
from .pulses import SAMPLED, sampled
from .store.progress import Progress
from .scene import Scene

DEFAULT_RTOL = 1e-6
INTEGRATOR_FACTOR = 3e-2
ATOL_SCALE = 1e-3
H_MAX_PULSE = 0.15
H_RESTART = 1e-4
MIN_INTEGRATOR_RTOL = 1e-14
MANY_EVENTS = 50
"""Above this many transitions the local tolerance is tightened in proportion (one refinement pass)."""
CONVERGENCE_PASSES = 3
"""Most tightening passes (each 10 x) for scenes with more than ``MANY_EVENTS`` transitions."""

log = logging.getLogger(__name__)


class StepBudgetError(RuntimeError):
    """A solve needed more Runge-Kutta steps than :func:`step_budget` allows."""


class CapacityError(RuntimeError):
    """A triple friction pendulum reached its displacement capacity: the model does not go past it."""


class ContactError(RuntimeError):
    """A rocking block would lose its contact with the floor in a way the model does not follow."""


CONTACT_TEXT = {
    "flight": "the rocking block would leave the floor (its vertical contact force turns negative below the "
              "tipping angle; flight is not modelled)",
    "impact": "the rocking block's impact has no impulse consistent with Coulomb friction and a non-bouncing "
              "contact",
    "indeterminate": "the rocking block's modes have no consistent choice (slide-rock whose equations have no "
                     "solution, Painleve's paradox, or whose pivot would slide against its direction)",
}
"""What each loss of contact (:data:`isoslide.engine.building_kernel.CONTACT_LOSSES`) means."""


@dataclass(frozen=True)
class Solution:
    """Result of :func:`solve`.

    Attributes
    ----------
    pi1 : float
        ``u_max / (a_p T_p^2)``: peak of ``|u_s|`` over the whole response.
    u_max : float
        Peak sliding displacement in metres for a scene made by
        :meth:`Scene.from_physical`, else equal to ``pi1``.
    pi1_residual, u_residual : float
        Signed permanent (final) sliding displacement, dimensionless and in metres.
    tau_peak, t_peak : float
        Time of the peak, in units of T_p and in seconds (pulse time origin).
    settled : bool
        True when no further sliding is possible (see :mod:`isoslide.engine.kernel`).
    model : str
        Which reduced model ran, as a display label derived from ``facets`` (see module docstring).
    tau_end : float
        Time at which the integration stopped (units of T_p).
    n_steps, n_events : int
        Integrator steps (incl. rejected and event-location steps) and stick/slip transitions.
    history : History or None
        Time history when requested.
    facets : Facets
        The model that ran, one value per independent property (:data:`isoslide.models.FACETS`).
    peak_angle : float
        Direction of the sliding displacement at its peak, ``atan2(u_y, u_x)`` in the building's
        axes (radians, in ``(-pi, pi]``); ``0`` or ``pi`` for the 1-D model along x, nan when the
        contents never slid.  ``pi1_residual`` is then the final displacement's component along
        the excitation's line, or its magnitude in the plane.
    peak_stage : int
        The highest regime a triple friction pendulum reached (Fenz and Constantinou's I..V as
        1..5, :data:`isoslide.model.tfp.STAGE_NAMES`); 0 when it never slid, and for every other
        isolator.
    theta_max : float
        A rocking block's peak ``|theta|`` (rad; ``pi/2`` when it overturned); 0 for contents that only
        slide.
    overturned : bool
        The rocking block overturned (``|theta|`` reached ``pi/2``; the response stops there).
    modes : tuple of str
        The contents' modes visited, in the order of
        :data:`isoslide.engine.building_kernel.BLOCK_MODES` (``"rest"``, ``"slide"``, ``"rock"``,
        ``"slide-rock"``).
    """

    pi1: float
    u_max: float
    pi1_residual: float
    u_residual: float
    tau_peak: float
    t_peak: float
    settled: bool
    model: str
    tau_end: float
    n_steps: int
    n_events: int
    history: History | None = field(default=None, repr=False)
    facets: Facets | None = None
    peak_angle: float = math.nan
    peak_stage: int = 0
    theta_max: float = 0.0
    overturned: bool = False
    modes: tuple = ()


@dataclass(frozen=True)
class Batch:
    """Results of :func:`solve_many`, one entry per scene, in order."""

    pi1: np.ndarray
    pi1_residual: np.ndarray
    tau_peak: np.ndarray
    settled: np.ndarray
    model: np.ndarray
    tau_end: np.ndarray
    n_steps: np.ndarray
    n_events: np.ndarray
    facets: np.ndarray | None = None
    peak_angle: np.ndarray | None = None
    peak_stage: np.ndarray | None = None
    theta_max: np.ndarray | None = None
    overturned: np.ndarray | None = None

    def __len__(self):
        return self.pi1.shape[0]


def _check_rtol(rtol):
    rtol = DEFAULT_RTOL if rtol is None else rtol
    if not (isinstance(rtol, (int, float)) and math.isfinite(rtol) and 1e-13 <= rtol <= 1e-1):
        raise ValueError(f"rtol = {rtol!r} is out of range; allowed range: 1e-13 <= rtol <= 0.1")
    return float(rtol)


def _model_array(scene: Scene, pi8: float, coulomb: float, thr: float | None = None) -> np.ndarray:
    m = np.zeros(kernel.N_M)
    fixed = scene.pi3 == 0.0
    if not fixed:
        w = 2.0 * math.pi / scene.pi3
        m[kernel.M_W2] = w * w
        m[kernel.M_CW] = 2.0 * scene.pi4 * w
    m[kernel.M_P8] = pi8
    m[kernel.M_THR] = scene.static_level if thr is None else thr
    m[kernel.M_PI2] = scene.pi2
    m[kernel.M_PI6] = scene.pi6
    m[kernel.M_PI7] = scene.pi7
    m[kernel.M_FIXED] = 1.0 if fixed else 0.0
    m[kernel.M_COULOMB] = float(coulomb)
    return m


def _long_run_factor(scene: Scene, horizon: float) -> float:
    """Tolerance tightening for lightly damped isolated scenes.

    Global error grows with the number of isolation periods followed; the
    free vibration lasts about ``1 / (2 pi xi_b)`` periods (up to the horizon),
    so the local tolerance is divided by that count over ten (1 for
    ``xi_b >= 0.016``).
    """
    if scene.pi3 == 0.0:
        return 1.0
    periods = horizon if scene.pi4 == 0.0 else min(horizon, 1.0 / (2.0 * math.pi * scene.pi4))
    return max(1.0, periods / 10.0)


def integrator_rtol(scene: Scene, rtol: float, horizon: float = DEFAULT_HORIZON) -> float:
    """Local (per-step) relative tolerance of the integrator for a target ``rtol`` on Pi1."""
    return max(rtol * INTEGRATOR_FACTOR / _long_run_factor(scene, horizon), MIN_INTEGRATOR_RTOL)


def near_threshold_rtol(scene: Scene, rtol: float, pi1: float) -> float:
    """Local tolerance a slide of size ``pi1`` needs (near the no-slide threshold).

    A slide just above the threshold is driven by the small excess ``d`` of
    the floor demand over ``mu_s g``: ``Pi1 ~ d^2 / k`` with ``k`` the demand's
    curvature at its peak (``k ~ 10`` in units of a_p / T_p^2), so a relative
    demand error ``e`` becomes a relative Pi1 error ``~ 2 e thr / d``.  The
    tolerance returned keeps that estimate below ``rtol`` (measured errors
    sit about 4 times below the estimate).
    """
    d = math.sqrt(10.0 * pi1)
    return max(rtol * d / (2.0 * scene.static_level), MIN_INTEGRATOR_RTOL)


def base_atol(scene: Scene, irtol: float, many_transitions: bool = False) -> float:
    """Absolute tolerance of the base state for a local relative tolerance ``irtol``.

    ``irtol * ATOL_SCALE`` (lengths in ``a_p T_p^2``, speeds in ``a_p T_p``).  With
    ``many_transitions`` (a scene with more than ``MANY_EVENTS`` stick-slip transitions) it is
    scaled by ``min(1, Pi3^2)``: while the contents stick, the floor demand is ``w^2 x + c x'``
    with ``w = 2 pi / Pi3``, so an absolute error ``d`` in the base displacement is an error
    ``w^2 d`` in the demand that decides every breakaway; on a stiff base with hundreds of
    near-threshold breakaways that error must stay below ``40 irtol * ATOL_SCALE``.  Scenes with
    few transitions keep the plain tolerance: the scaled one buys them nothing and, on a stiff
    base, costs up to 1000 times the steps at ``rtol = 1e-12``.
    """
    if many_transitions and scene.pi3 > 0.0:
        return irtol * ATOL_SCALE * min(1.0, scene.pi3 ** 2)
    return irtol * ATOL_SCALE


@dataclass(frozen=True)
class Run:
    """One run of a compiled kernel, read through the kernel module's declared result layout.

    Every kernel module declares the names of its integer and float results, in order
    (``INT_RESULTS``, ``FLOAT_RESULTS``); :meth:`of` reads a run's arrays by those names, so no
    module indexes another's results.
    """

    ints: dict
    floats: dict
    hist: np.ndarray

    @classmethod
    def of(cls, module, res) -> "Run":
        """The run ``res = (ints, floats, hist)`` of ``module.run`` (or of a function with its layout)."""
        ints, floats, hist = res
        return cls(dict(zip(module.INT_RESULTS, ints.tolist(), strict=True)),
                   dict(zip(module.FLOAT_RESULTS, floats.tolist(), strict=True)), hist)

    @property
    def pi1(self) -> float:
        """Peak sliding displacement ``u_max / (a_p T_p^2)``."""
        return self.floats["umax"]

    @property
    def transitions(self) -> int:
        """Stick-slip transitions of every interface (the contents' and an isolator's)."""
        return self.ints["events"] + self.ints.get("iso_events", 0)

    def same_transitions(self, other: "Run") -> bool:
        """Whether ``other`` has as many transitions of each interface."""
        return all(self.ints.get(k, 0) == other.ints.get(k, 0) for k in ("events", "iso_events"))


def _checked(run: Run, scene: Scene, horizon: float, budget: int, what: str, rtol: float | None = None) -> Run:
    """``run``, or :class:`StepBudgetError` when it stopped on its step budget before the horizon.

    ``what`` names the steps counted; ``rtol``, where the run's cost depends on it, is quoted with
    its allowed range.
    """
    if run.floats["tend"] < horizon_end(scene, horizon) and not run.ints["settled"] and run.ints["steps"] > budget:
        shorten = f"the horizon (horizon = {horizon:g}) for {scene}"
        advice = (f"Shorten {shorten}" if rtol is None else
                  f"Loosen rtol (allowed range: 1e-13 <= rtol <= 0.1) or shorten {shorten}")
        at = f"tau = {run.floats['tend']:.6g}" + ("" if rtol is None else f" with rtol = {rtol:g}")
        raise StepBudgetError(f"the step budget ({budget} {what}) ran out at {at}; the answer would be "
                              f"truncated. {advice}")
    return run


def _refined(out: Run, run, scene: Scene, rtol: float, horizon: float, demand_integrated: bool) -> Run:
    """The tolerance loop of every integrated solve.

    ``out`` is the run at the integrator tolerance :func:`integrator_rtol`; ``run(irtol, many)``
    integrates again at the local tolerance ``irtol`` (``many``: the base's absolute tolerance
    scaled for many transitions, :func:`base_atol`).  Where Pi1 is ill-conditioned the scene is
    run once more at a tighter tolerance: near the no-slide threshold (where the floor demand is
    integrated, ``demand_integrated``: :func:`near_threshold_rtol`), and where errors add up over
    more than ``MANY_EVENTS`` transitions.  With very many transitions, some of them marginal, a
    breakaway decided by a demand excess below the local error can be missed: the tolerance is
    tightened until two answers agree to ``rtol / 10`` with the same transitions (at most
    ``CONVERGENCE_PASSES`` times).
    """
    pi1 = out.pi1
    if not 0.0 < pi1:
        return out
    used = integrator_rtol(scene, rtol, horizon)
    many = out.transitions > MANY_EVENTS
    need = used * min(1.0, MANY_EVENTS / max(out.transitions, 1))
    if demand_integrated:
        need = min(need, near_threshold_rtol(scene, rtol, pi1))
    if need < used or (many and scene.pi3 < 1.0):
        need = max(need, MIN_INTEGRATOR_RTOL)
        out = run(need, many)
    if out.transitions > MANY_EVENTS:
        need = min(need, used)
        for _ in range(CONVERGENCE_PASSES):
            if need <= MIN_INTEGRATOR_RTOL:
                break
            need = max(need / 10.0, MIN_INTEGRATOR_RTOL)
            finer = run(need, True)
            a, b = out.pi1, finer.pi1
            same = out.same_transitions(finer)
            out = finer
            if abs(b - a) <= 0.1 * rtol * abs(b) and same:
                break
    return out


def _run(scene: Scene, pi8: float, coulomb: float, rtol: float, hist_cap: int = 0,
         horizon: float = DEFAULT_HORIZON, track_max: bool = False, max_step: float = math.inf,
         settle: bool = True, irtol: float | None = None, many_transitions: bool = False):
    pulse = scene.pulse
    if irtol is None:
        irtol = integrator_rtol(scene, rtol, horizon)
    m = _model_array(scene, pi8, coulomb, thr=math.inf if track_max else None)
    h_free = min(max(scene.pi3, 1.0) / 8.0, max_step)
    return kernel.run(m, pulse.code, pulse.param_array, pulse.breakpoint_array,
                      pulse.tau_start, pulse.tau_end, horizon_end(scene, horizon),
                      min(H_MAX_PULSE, max_step), h_free, irtol, base_atol(scene, irtol, many_transitions), track_max,
                      hist_cap, min(H_RESTART, max_step), settle, step_budget(scene, horizon))


def piecewise_applies(scene: Scene) -> bool:
    """True when ``model="auto"`` propagates the scene exactly (:mod:`isoslide.engine.piecewise`).

    The pulse is a sampled record (linear between samples) and the friction is
    speed-independent (:attr:`Scene.rate_independent`); the base is linear
    (``Pi3 > 0``) or fixed (``Pi3 = 0``).
    """
    return scene.pulse.code == SAMPLED and scene.rate_independent


def _run_piecewise(scene: Scene, pi8: float, hist_cap: int = 0, horizon: float = DEFAULT_HORIZON,
                   track_max: bool = False, settle: bool = True):
    """:func:`isoslide.engine.piecewise.run` for a scene, as a :class:`Run`."""
    pulse = scene.pulse
    m = _model_array(scene, pi8, 1.0, thr=math.inf if track_max else None)
    budget = step_budget(scene, horizon)
    res = piecewise.run(m, pulse.param_array, pulse.tau_start, pulse.tau_end, horizon_end(scene, horizon),
                        track_max, hist_cap, settle, budget)
    return _checked(Run.of(piecewise, res), scene, horizon, budget, "substeps")


def _impulse_velocity_l1(scene: Scene) -> float:
    """Bound on int_0^inf |h'(tau)| dtau for the base oscillator (h: displacement impulse response)."""
    w = 2.0 * math.pi / scene.pi3
    z = scene.pi4
    if z == 0.0:
        return math.inf
    if z < 1.0:
        return (1.0 + z / math.sqrt(1.0 - z * z)) / (z * w)
    if z == 1.0:
        return 2.0 / (math.e * w)
    r1 = -w * (z - math.sqrt(z * z - 1.0))
    r2 = -w * (z + math.sqrt(z * z - 1.0))
    t = math.log(r2 / r1) / (r1 - r2)
    return 2.0 * (math.exp(r1 * t) - math.exp(r2 * t)) / (r1 - r2)


def plan(scene: Scene) -> dict:
    """Which model the scene requires before any integration.

    Returns a dict with ``fixed`` (bool), ``coulomb`` (bool) and
    ``oneway_possible`` (bool: the one-way bound may pass).
    """
    fixed = scene.pi3 == 0.0
    coulomb = scene.rate_independent
    return {"fixed": fixed, "coulomb": coulomb, "oneway_possible": (not fixed) and coulomb}


def _history(h: np.ndarray) -> History:
    return History(tau=h[:, 0].copy(), x=h[:, 1].copy(), xd=h[:, 2].copy(), u=h[:, 3].copy(),
                   ud=h[:, 4].copy(), phase=h[:, 5].astype(np.int8))


MODEL_OPTIONS = ("auto", "full", "static-kinetic")
"""Values of ``solve(..., model=...)`` (the labels a solve produces are :data:`isoslide.models.MODEL_LABELS`)."""


def solve(scene: Scene, rtol: float | None = None, history: bool = False, method: str = "exact",
          horizon: float = DEFAULT_HORIZON, model: str = "auto", max_step: float = math.inf,
          settle: bool = True, piecewise_path: bool = True, **options) -> Solution:
    """Peak sliding of one scene.

    Parameters
    ----------
    scene : Scene
        The scene (see :class:`isoslide.Scene` for every Pi-group).
    rtol : float, optional
        Target relative error of ``Pi1`` (default ``1e-6``), see module docstring.
    history : bool
        Return the time history (every accepted step and every transition).
    method : {"exact", "regularized", "reference"}
        ``"exact"``: the compiled event-driven solver (this module);
        ``"regularized"``: the paper's method, signum replaced by a stiff
        elastic-plastic spring (option ``stiffness``), see
        :mod:`isoslide.peers.regularized`; ``"reference"``: plain SciPy
        event-driven solver, see :mod:`isoslide.peers.reference`.  Further
        keyword ``options`` go to the peer.
    horizon : float
        How long to follow a scene that does not settle, after the pulse, in
        isolation periods (pulse periods for a fixed base).
    model : {"auto", "full", "static-kinetic"}
        ``"auto"`` runs the smallest exact model (the exact piecewise
        propagation where :func:`piecewise_applies`); ``"full"`` disables every
        reduction but the fixed base and always integrates (to test the
        reductions and the piecewise path against the full model); ``"static-kinetic"`` is the limit ``Pi6 -> inf`` (stick up to
        ``mu_s``, kinetic ``mu_k`` at any sliding speed).
    max_step : float
        Largest step in units of T_p (a denser history; accuracy is set by ``rtol``).
    settle : bool
        Stop at settlement (default).  ``False`` follows the scene to the
        horizon, to check the settlement criterion.
    piecewise_path : bool
        With ``model="auto"``, propagate a scene exactly where
        :func:`piecewise_applies` (default; a finite ``max_step`` keeps the
        integrator); ``False`` integrates it with every other reduction (the
        solve before the piecewise path, for comparison).

    Returns
    -------
    Solution
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be an isoslide.Scene, got {type(scene).__name__}")
    if method != "exact":
        if method not in SCENE_SOLVERS:
            raise ValueError(f"method = {method!r} is invalid; allowed: 'exact', "
                             + ", ".join(repr(m) for m in SCENE_SOLVERS))
        if not scene.in_line:
            if method != "reference":
                raise ValueError(f"method = {method!r} does not model two horizontal ground components or an angle "
                                 f"(pulse_y = {getattr(scene.pulse_y, 'name', None)!r}, angle = {scene.angle!r}); "
                                 "allowed: method='exact' or 'reference', or the main pulse alone along x")
            return _from_peer(scene, solve_reference_planar(scene, history=history, **options))
        if scene.vertical and method != "reference":
            raise ValueError(f"method = {method!r} does not model vertical ground motion (pi17 = {scene.pi17!r} "
                             "with a pulse_z); allowed: method='exact', or pi17 = 0")
        return _from_peer(scene, SCENE_SOLVERS[method](scene, history=history, **options))
    if options:
        raise TypeError(f"unexpected options for method='exact': {sorted(options)}")
    if model not in MODEL_OPTIONS:
        raise ValueError(f"model = {model!r} is invalid; allowed: {MODEL_OPTIONS}")
    if not (math.isfinite(horizon) and horizon > 0):
        raise ValueError(f"horizon = {horizon!r} is out of range; allowed range: 0 < horizon < inf")
    if not (max_step > 0):
        raise ValueError(f"max_step = {max_step!r} is out of range; allowed range: 0 < max_step <= inf")
    rtol = _check_rtol(rtol)
    if not scene.in_line:
        return _solve_horizontal(scene, rtol, history, horizon, model, max_step, settle, piecewise_path)
    if not scene.paper_model or (model == "full" and scene.rocks):
        return _solve_building(scene, rtol, history, horizon, model, max_step, settle, piecewise_path)
    pl = plan(scene)
    fixed = pl["fixed"]
    if model == "static-kinetic":
        friction = 2.0
    else:
        friction = 1.0 if (pl["coulomb"] and model == "auto") else 0.0
    coulomb = friction == 1.0
    hist_cap = 200_000 if history else 0
    pi8 = 0.0 if fixed else scene.pi8
    oneway = pi8 == 0.0
    if model == "auto" and piecewise_path and math.isinf(max_step) and piecewise_applies(scene):
        out = _run_piecewise(scene, pi8, hist_cap, horizon, settle=settle)
        facets = scene_facets(scene, friction="coulomb", oneway=oneway, propagation="piecewise")
        return _solution(scene, out, facets, _history(out.hist) if history else None)

    def run(p8, irtol=None, many=False):
        res = _run(scene, p8, friction, rtol, hist_cap, horizon, max_step=max_step, settle=settle,
                   irtol=irtol, many_transitions=many)
        return _checked(Run.of(kernel, res), scene, horizon, step_budget(scene, horizon), "Runge-Kutta steps",
                        rtol)

    out = None
    p8_used = pi8
    if model == "auto" and pl["oneway_possible"] and pi8 > 0.0:
        l1 = _impulse_velocity_l1(scene)
        span = scene.pulse.tau_end - scene.pulse.tau_start
        if 2.0 * 2.0 * span * pi8 * scene.static_level * l1 <= 0.1 * rtol:
            trial = run(0.0)
            T = 2.0 * (trial.floats["tend"] - scene.pulse.tau_start)
            bound = 2.0 * T * pi8 * scene.static_level * l1
            if bound <= 0.1 * rtol * trial.pi1:
                out, oneway, p8_used = trial, True, 0.0
    if out is None:
        out = run(pi8)
    out = _refined(out, lambda irtol, many: run(p8_used, irtol, many), scene, rtol, horizon,
                   demand_integrated=not fixed)
    law = "static-kinetic" if model == "static-kinetic" else ("coulomb" if coulomb else "stribeck")
    facets = scene_facets(scene, friction=law, oneway=oneway)
    return _solution(scene, out, facets, _history(out.hist) if history else None)


def _solve_building(scene: Scene, rtol: float, history: bool, horizon: float, model: str, max_step: float,
                    settle: bool, piecewise_path: bool) -> Solution:
    """:func:`solve` for a general building (:mod:`isoslide.engine.building`): its smallest exact model.

    With ``model="auto"`` a reduction to the paper's model runs that model (the label gets the
    reduction's name in front); otherwise :func:`isoslide.engine.building_kernel.run` integrates it,
    with the Stribeck terms only where the friction depends on speed and the back-reaction
    dropped for ``Pi8 = 0``.  The tolerance rules are the paper model's (see the module
    docstring), with the refinement passes over many transitions counting those of both
    interfaces.
    """
    name, paper = building.reduction(scene) if model == "auto" else ("general", None)
    if paper is not None:
        sol = solve(paper, rtol=rtol, history=history, horizon=horizon, model=model, max_step=max_step,
                    settle=settle, piecewise_path=piecewise_path)
        if name not in BEARING_REDUCTIONS:
            return sol
        facets = dataclasses.replace(sol.facets, reduction=name)
        return dataclasses.replace(sol, facets=facets, model=facets.label(sol.pi1 > 0.0))
    coulomb = (scene.rate_independent and model == "auto") or model == "static-kinetic"
    if model == "static-kinetic":
        raise ValueError("model = 'static-kinetic' is available for the paper's model only "
                         "(pi9 = 0 and pi12 = 0)")
    if scene.tfp_speed is not None:
        return _solve_tfp_flow(scene, rtol, history, horizon, coulomb, settle)
    pi8 = scene.pi8
    rocking = scene.rocks and (scene.tips or model == "full")
    system = assemble(scene, pi8=pi8, coulomb=coulomb, rocking=rocking, horizon=horizon)
    pulse = scene.pulse
    hist_cap = 200_000 if history else 0
    h_free = min(system.free_step, max_step)

    exact = system.linear is not None and model == "auto" and not history

    def run(irtol, many=False):
        if exact:
            # the building linear between transitions: propagated exactly (isoslide.engine.exponential)
            res = exponential.run(system.P, pulse.code, pulse.param_array, system.breakpoints, pulse.tau_start,
                                  system.end, system.stop, max_step, irtol, settle, system.budget, *system.linear,
                                  *system.modal)
            return _checked(Run.of(building_kernel, res), scene, horizon, system.budget, "exact sub-steps", rtol)
        res = building_kernel.run(system.P, pulse.code, pulse.param_array, system.breakpoints, pulse.tau_start,
                                  system.end, system.stop, min(H_MAX_PULSE, max_step), h_free, irtol,
                                  base_atol(scene, irtol, many), hist_cap, min(H_RESTART, max_step), settle,
                                  system.budget, *system.modal)
        return _checked(Run.of(building_kernel, res), scene, horizon, system.budget, "Runge-Kutta steps", rtol)

    out = _refined(run(integrator_rtol(scene, rtol, horizon)), run, scene, rtol, horizon, demand_integrated=True)
    _check_capacity(out, scene)
    if out.ints["contact"]:
        raise ContactError(CONTACT_TEXT[building_kernel.CONTACT_LOSSES[out.ints["contact"]]]
                           + f" at tau = {out.floats['tcontact']:.6g} for {scene}")
    facets = scene_facets(scene, friction="coulomb" if coulomb else "stribeck", oneway=pi8 == 0.0, rocking=rocking,
                          propagation="exponential" if exact else "integrated")
    return _solution(scene, out, facets, _building_history(out.hist, scene, rocking) if history else None,
                     peak_stage=out.ints["stage_max"])


def _check_capacity(out: Run, scene: Scene) -> None:
    """:class:`CapacityError` when a triple pendulum's run reached its displacement capacity."""
    if out.ints["capacity"]:
        raise CapacityError(f"the triple friction pendulum reaches its displacement capacity (an inner surface on "
                            f"its restrainer) at tau = {out.floats['tend']:.6g} for {scene}; the model of rigid "
                            "restrainers does not go past it")


def _solve_tfp_flow(scene: Scene, rtol: float, history: bool, horizon: float, coulomb: bool,
                    settle: bool) -> Solution:
    """:func:`solve` for a triple pendulum whose friction rises with speed (:mod:`isoslide.engine.tfp_flow`).

    The building and the contents are the general building's (any floor, storeys, Stribeck or
    Coulomb contents, vertical motion through the normal forces); the bearing's surfaces are
    integrated implicitly (Radau) at :data:`isoslide.engine.tfp_flow.RTOL_FACTOR` of ``rtol``.
    """
    if scene.tips:
        raise ValueError(f"a rocking block (pi18 = {scene.pi18!r}) on a triple friction pendulum whose friction rises "
                         f"with speed (pi22 = {scene.pi22!r}, pi23 = {scene.pi23!r}) is not modelled; allowed: "
                         "contents that slide (pi18 = None, or a block that slides before it tips), or constant "
                         "bearing friction (pi22 = 1 or pi23 = 0)")
    system = assemble(scene, pi8=scene.pi8, coulomb=coulomb, rocking=False, horizon=horizon)
    surfaces = tfp_flow.Surfaces.of(system.P, *building_of(scene).isolator.surface_laws())
    pulse = scene.pulse
    res = tfp_flow.run(system.P, pulse.code, pulse.param_array, system.breakpoints, pulse.tau_start, system.end,
                       system.stop, surfaces, rtol, settle, system.modal, 200_000 if history else 0)
    out = Run.of(building_kernel, res)
    _check_capacity(out, scene)
    facets = scene_facets(scene, friction="coulomb" if coulomb else "stribeck", oneway=scene.pi8 == 0.0,
                          rocking=False)
    return _solution(scene, out, facets, _building_history(out.hist, scene) if history else None,
                     peak_stage=out.ints["stage_max"])


def _solve_tfp_plane(scene: Scene, rtol: float, history: bool, horizon: float, settle: bool) -> Solution:
    """:func:`solve` in the plane on a triple pendulum whose friction rises with speed (:mod:`isoslide.engine.tfp_plane`).

    The building and the contents are the planar kernel's (any floor, storeys, Stribeck or Coulomb
    contents, vertical motion through the normal forces); the bearing's four surfaces have circular
    friction and circular restrainers, integrated implicitly (Radau) at
    :data:`isoslide.engine.tfp_flow.RTOL_FACTOR` of ``rtol``.
    """
    parts = building_of(scene)
    if not parts.isolator.speed_dependent:
        raise ValueError(f"a triple friction pendulum of constant friction (pi22 = {scene.pi22!r}, pi23 = "
                         f"{scene.pi23!r}) under two horizontal ground components that are not along one line is "
                         "not modelled (its surfaces' sliding sets in the plane); allowed: friction that rises with "
                         "speed (pi22 < 1 and pi23 > 0), an excitation along one line, or a single friction "
                         "pendulum (pi24 = 0)")
    if scene.tips:
        raise ValueError(f"a rocking block (pi18 = {scene.pi18!r}) on a triple friction pendulum in the plane is "
                         "not modelled; allowed: contents that slide (pi18 = None, or a block that slides before "
                         "it tips)")
    coulomb = scene.rate_independent
    system = assemble(scene, pi8=scene.pi8, coulomb=coulomb, rocking=False, horizon=horizon)
    surfaces = tfp_flow.Surfaces.of(system.P, *parts.isolator.surface_laws())
    res = tfp_plane.run(system.P, excitation(scene), system.breakpoints, system.start, system.end, system.stop,
                        surfaces, rtol, settle, system.planar_modal, 200_000 if history else 0)
    out = Run.of(tfp_plane, res)
    _check_capacity(out, scene)
    facets = dataclasses.replace(scene_facets(scene, friction="coulomb" if coulomb else "stribeck",
                                              oneway=scene.pi8 == 0.0), contact="plane")
    sol = _solution(scene, out, facets, peak_stage=out.ints["stage_max"])
    if history:
        n = int(system.P[building_kernel.P_N])
        h = _planar_history(out.hist, n, scene, hyst=True)
        sol = dataclasses.replace(sol, history=dataclasses.replace(h, stage=out.hist[:, -1].astype(np.int8)))
    return sol


def _solve_horizontal(scene: Scene, rtol: float, history: bool, horizon: float, model: str, max_step: float,
                      settle: bool, piecewise_path: bool) -> Solution:
    """:func:`solve` (exact, arguments checked) for an excitation that is not the main pulse along x alone.

    In the plane (:attr:`isoslide.Scene.planar`, or any such scene with ``model="full"``) the
    planar kernel integrates it; along one line the 1-D model runs along that line
    (:func:`along_line`), the building and the contents being isotropic.
    """
    if model == "static-kinetic":
        raise ValueError("model = 'static-kinetic' is available for the paper's model only "
                         "(pi9 = 0, pi12 = 0, the main pulse alone along x)")
    if scene.planar or model == "full":
        if scene.isolator == "tfp":
            return _solve_tfp_plane(scene, rtol, history, horizon, settle)
        return _solve_planar(scene, rtol, history, horizon, model, max_step, settle)
    line, lam, theta = along_line(scene)
    sol = solve(line, rtol=rtol, history=history, horizon=horizon, model=model, max_step=max_step,
                settle=settle, piecewise_path=piecewise_path)
    L = scene.scale.length if scene.scale is not None else 1.0
    Tp = scene.scale.T_p if scene.scale is not None else 1.0
    angle = math.nan if math.isnan(sol.peak_angle) else _wrapped(sol.peak_angle + theta)
    return dataclasses.replace(sol, pi1=lam * sol.pi1, u_max=lam * sol.pi1 * L,
                               pi1_residual=lam * sol.pi1_residual, u_residual=lam * sol.pi1_residual * L,
                               t_peak=sol.tau_peak * Tp, peak_angle=angle)


def _wrapped(angle: float) -> float:
    """``angle`` in ``(-pi, pi]``."""
    a = math.atan2(math.sin(angle), math.cos(angle))
    return math.pi if a == -math.pi else a


def along_line(scene: Scene) -> tuple:
    """The 1-D scene of an excitation along one line, with the line's amplitude and direction.

    The ground moves along the direction ``theta`` (:attr:`isoslide.Scene.direction`) with the
    peak acceleration ``lam a_p`` (:attr:`isoslide.Scene.line_amplitude`).  The building and the
    contents are isotropic, so the contents slide along that line as the 1-D model does under the
    main pulse scaled by ``lam``: with ``lam a_p`` as the pulse amplitude, the groups holding
    ``a_p`` become ``Pi2 / lam``, ``Pi6 lam``, ``Pi9 / lam``, ``Pi10 / lam``, ``Pi23 lam``, a triple
    pendulum's limits ``Pi28 .. Pi30`` over ``lam``, and ``Pi1 = lam Pi1'``.

    Returns
    -------
    (Scene, float, float)
        The 1-D scene (main pulse along x, no scale), ``lam`` and ``theta`` (radians).
    """
    theta = scene.direction
    if theta is None:
        raise ValueError(f"the excitation of {scene} is not along one line (pulse_y {scene.pulse_y.name!r} "
                         f"with pi15 = {scene.pi15!r}, pi16 = {scene.pi16!r}); allowed: no pulse_y, or pulse_y "
                         "equal to pulse with pi15 = 1 and pi16 = 0")
    lam = scene.line_amplitude
    line = dataclasses.replace(scene, pulse_y=None, pi14=1.0, pi15=1.0, pi16=0.0, angle=0.0, pi2=scene.pi2 / lam,
                               pi6=scene.pi6 * lam, pi9=scene.pi9 / lam, pi10=scene.pi10 / lam,
                               pi23=scene.pi23 * lam, pi28=scene.pi28 / lam, pi29=scene.pi29 / lam,
                               pi30=scene.pi30 / lam, scale=None)
    return line, lam, theta


def _solve_planar(scene: Scene, rtol: float, history: bool, horizon: float, model: str, max_step: float,
                  settle: bool, state: tuple | None = None) -> Solution:
    """:func:`solve` in the plane: :func:`isoslide.engine.planar_kernel.run` with the general building's parameters.

    ``state``, when given, is ``(y0, md0)``: the initial state and modes (see the kernel's
    :func:`~isoslide.engine.planar_kernel.deriv`).
    """
    coulomb = scene.rate_independent and model == "auto"
    system = assemble(scene, pi8=scene.pi8, coulomb=coulomb, horizon=horizon)
    P, modal, bps, start, stop, budget = (system.P, system.planar_modal, system.breakpoints, system.start,
                                          system.stop, system.budget)
    n = int(P[building_kernel.P_N])
    hyst = P[building_kernel.P_KIND] == building_kernel.KIND_BILINEAR
    hist_cap = 200_000 if history else 0
    h_free = min(system.free_step, max_step)
    ex = excitation(scene)
    y0, md0 = (np.zeros(planar_kernel.state_size(n, hyst)), np.array([0.0, 1.0, 0.0, 0.0, 1.0, 0.0])) \
        if state is None else state

    grid = pair_grid(scene) if model == "auto" and state is None else None

    def run(irtol, many=False):
        kernel_args = (min(H_MAX_PULSE, max_step), h_free, irtol, base_atol(scene, irtol, many))
        if grid is not None:
            # a recorded pair: the stick phases propagated exactly, the slides in the planar kernel
            res = planar_piecewise.run(_model_array(scene, scene.pi8, 1.0), *grid, system.end, stop, hist_cap,
                                       settle, budget, P, ex, bps, *kernel_args, min(H_RESTART, max_step), *modal,
                                       planar_kernel.slaved_speed(irtol))
            return _checked(Run.of(planar_piecewise, res), scene, horizon, budget, "substeps and Runge-Kutta steps",
                            rtol)
        res = planar_kernel.run(P, ex, bps, start, system.end, stop, *kernel_args, hist_cap,
                                min(H_RESTART, max_step), settle, budget, *modal, np.asarray(y0, dtype=float),
                                np.asarray(md0, dtype=float), planar_kernel.slaved_speed(irtol), False,
                                np.empty(len(y0) + 6))
        return _checked(Run.of(planar_kernel, res), scene, horizon, budget, "Runge-Kutta steps", rtol)

    out = _refined(run(integrator_rtol(scene, rtol, horizon)), run, scene, rtol, horizon, demand_integrated=True)
    facets = dataclasses.replace(scene_facets(scene, friction="coulomb" if coulomb else "stribeck",
                                              oneway=scene.pi8 == 0.0 or scene.fixed_base and not scene.flexible,
                                              propagation="integrated" if grid is None else "piecewise"),
                                 contact="plane")
    sol = _solution(scene, out, facets)
    if history:
        sol = dataclasses.replace(sol, history=_planar_history(out.hist, n, scene, hyst))
    return sol


def _planar_history(h: np.ndarray, n: int, scene: Scene, hyst: bool = False) -> History:
    """The planar kernel's rows as a :class:`History` whose ``x, xd, u, ud`` (and ``fh``) have two columns (x, y)."""
    c = planar_kernel.history_columns(n, hyst)
    nb = planar_kernel.axis_size(n, hyst)

    def pair(k):
        return np.column_stack([h[:, c["x"] + k], h[:, c["y"] + k]])

    xs = np.stack([h[:, c["x"] + 2:c["x"] + 2 + n], h[:, c["y"] + 2:c["y"] + 2 + n]], axis=1)
    xsd = np.stack([h[:, c["x"] + 2 + n:c["x"] + nb], h[:, c["y"] + 2 + n:c["y"] + nb]], axis=1)
    bearing = scene.pi9 > 0.0 and not scene.fixed_base
    return History(tau=h[:, c["tau"]].copy(), x=pair(0), xd=pair(1), u=h[:, c["u"]:c["u"] + 2].copy(),
                   ud=h[:, c["w"]:c["w"] + 2].copy(), phase=h[:, c["phase"]].astype(np.int8),
                   xs=xs if scene.flexible else None, xsd=xsd if scene.flexible else None,
                   fh=pair(nb - 1) if hyst else None,
                   iso_phase=h[:, c["iso_phase"]].astype(np.int8) if bearing else None)


def _building_history(h: np.ndarray, scene: Scene, rocking: bool = False) -> History:
    """The general kernel's history rows as a :class:`History` (building states included)."""
    n = scene.storeys if scene.flexible else 1
    c = building_kernel.history_columns(n)

    def part(name):
        return h[:, c[name]:c[name] + n].copy() if n > 1 else h[:, c[name]].copy()

    return History(tau=h[:, c["tau"]].copy(), x=h[:, c["x"]].copy(), xd=h[:, c["xd"]].copy(),
                   u=h[:, c["u"]].copy(), ud=h[:, c["ud"]].copy(), phase=h[:, c["phase"]].astype(np.int8),
                   xs=part("xs") if scene.flexible else None,
                   xsd=part("xsd") if scene.flexible else None,
                   fh=h[:, c["fh"]].copy() if scene.pi9 > 0.0 else None,
                   iso_phase=h[:, c["iso_phase"]].astype(np.int8) if scene.pi9 > 0.0 else None,
                   stage=h[:, c["stage"]].astype(np.int8) if scene.isolator == "tfp" else None,
                   theta=h[:, c["theta"]].copy() if rocking else None,
                   thetad=h[:, c["thetad"]].copy() if rocking else None)


def scene_facets(scene: Scene, friction: str, oneway: bool, propagation: str = "integrated",
                 solver: str = "exact", rocking: bool | None = None) -> Facets:
    """The facets of a solve of ``scene`` (:class:`isoslide.models.Facets`) that integrated its model.

    The isolator, superstructure and floor are the scene's parts
    (:func:`isoslide.model.parts.building_of`: a base with ``Pi3 = 0`` is ``fixed-base``, a rigid
    superstructure carries the contents on the slab); ``friction``, ``oneway``, ``propagation`` and
    ``solver`` say how it was solved, ``rocking`` whether the contents' model rocks (None: where
    they tip before they can slide).
    """
    parts = building_of(scene)
    kind = parts.isolator.kind
    if kind in ("sliding", "tfp") and parts.isolator.speed_dependent:
        kind += "-speed"
    k, top = parts.contents.floor, parts.superstructure.storeys
    return Facets(isolator={"fixed": "fixed-base", "sliding": "sliding-bearing",
                            "sliding-speed": "sliding-bearing-speed", "tfp": "triple-friction-pendulum",
                            "tfp-speed": "triple-friction-pendulum-speed"}.get(kind, kind),
                  superstructure="flexible" if parts.superstructure.flexible else "rigid",
                  floor="base" if k == 0 else ("roof" if k == top else "intermediate"),
                  friction=friction, coupling="one-way" if oneway else "two-way", propagation=propagation,
                  solver=solver, vertical="normal-force" if scene.vertical else "none",
                  contents="rocking" if (scene.tips if rocking is None else rocking) else "sliding")


def _solution(scene, run: Run, facets: Facets, hist=None, peak_stage: int = 0) -> Solution:
    pi1 = run.pi1
    res = run.floats["ures"]
    tpk = run.floats["tpeak"]
    L = scene.scale.length if scene.scale is not None else 1.0
    Tp = scene.scale.T_p if scene.scale is not None else 1.0
    if not pi1 > 0.0:
        angle = math.nan
    elif "angle" in run.floats:
        angle = run.floats["angle"]
    else:
        angle = 0.0 if run.floats["upeak"] > 0.0 else math.pi
    if "modes" in run.ints:
        visited = run.ints["modes"]
        modes = tuple(m for k, m in enumerate(building_kernel.BLOCK_MODES) if visited >> k & 1)
    else:
        modes = building_kernel.BLOCK_MODES[:2] if pi1 > 0.0 else building_kernel.BLOCK_MODES[:1]
    return Solution(pi1=pi1, u_max=pi1 * L, pi1_residual=res, u_residual=res * L, tau_peak=tpk,
                    t_peak=tpk * Tp, settled=bool(run.ints["settled"]), model=facets.label(pi1 > 0.0),
                    tau_end=run.floats["tend"], n_steps=run.ints["steps"], n_events=run.ints["events"],
                    history=hist, facets=facets, peak_angle=angle, theta_max=run.floats.get("thmax", 0.0),
                    overturned=bool(run.ints.get("overturned", 0)), modes=modes, peak_stage=peak_stage)


def _from_peer(scene: Scene, res: PeerResult) -> Solution:
    """A peer's result as a :class:`Solution` (``model`` is the peer's name).

    ``n_steps`` holds the peer's time steps, or its right-hand-side evaluations
    where it does not count steps.
    """
    L = scene.scale.length if scene.scale is not None else 1.0
    Tp = scene.scale.T_p if scene.scale is not None else 1.0
    return Solution(pi1=res.pi1, u_max=res.pi1 * L, pi1_residual=res.pi1_residual,
                    u_residual=res.pi1_residual * L, tau_peak=res.tau_peak, t_peak=res.tau_peak * Tp,
                    settled=res.settled, model=res.method, tau_end=res.tau_end,
                    n_steps=res.n_steps if res.n_steps >= 0 else res.nfev, n_events=res.n_events,
                    history=res.history,
                    facets=scene_facets(scene, "coulomb" if scene.rate_independent else "stribeck",
                                        oneway=scene.pi3 == 0.0 and not scene.flexible, solver=res.method))


def peak_stuck_demand(scene: Scene, rtol: float | None = None, horizon: float = DEFAULT_HORIZON) -> float:
    """Rigorous upper bound of the floor acceleration demand of the stuck system, units of a_p.

    If ``Pi2/Pi5`` is at least this value the block can never slide
    (``Pi1 = 0`` exactly).  Depends on ``Pi3, Pi4, Pi8`` and the pulse only.
    """
    rtol = _check_rtol(rtol)
    pi8 = 0.0 if scene.pi3 == 0.0 else scene.pi8
    if scene.pulse.code == SAMPLED:  # linear between samples: exact peaks (isoslide.engine.piecewise)
        return _run_piecewise(scene, pi8, 0, horizon, track_max=True).floats["amax"]
    return Run.of(kernel, _run(scene, pi8, 1.0, rtol, 0, horizon, track_max=True)).floats["amax"]


def solve_many(scenes, rtol: float | None = None, horizon: float = DEFAULT_HORIZON,
               model: str = "auto") -> Batch:
    """Solve many scenes (the parameter sweeps use this).

    Scenes of the paper's model that share a base (``Pi3, Pi4, Pi8`` and pulse) share one
    computation of the stuck system's peak demand; every scene whose static
    threshold ``Pi2/Pi5`` exceeds it is answered ``Pi1 = 0`` (model
    ``no-slide``) without integrating anything.  Progress (scenes done, rate,
    time left) goes to the ``isoslide.solver`` log at most every 5 s
    (:class:`isoslide.store.progress.Progress`).

    Returns
    -------
    Batch
        With each scene's ``peak_stage`` (a triple pendulum's highest regime, 0 otherwise); a
        triple pendulum past its displacement capacity raises :class:`CapacityError`, as
        :func:`solve` does.
    """
    scenes = list(scenes)
    n = len(scenes)
    rtol = _check_rtol(rtol)
    pi1 = np.zeros(n)
    res = np.zeros(n)
    tpk = np.zeros(n)
    settled = np.zeros(n, dtype=bool)
    models = np.empty(n, dtype=object)
    facets = np.empty(n, dtype=object)
    tend = np.zeros(n)
    nsteps = np.zeros(n, dtype=np.int64)
    nev = np.zeros(n, dtype=np.int64)
    angle = np.full(n, np.nan)
    stage = np.zeros(n, dtype=np.int8)
    theta = np.zeros(n)
    over = np.zeros(n, dtype=bool)
    demand: dict = {}
    progress = Progress(log, "solve_many", n)
    for i, sc in enumerate(scenes):
        progress.update(i)
        if not isinstance(sc, Scene):
            raise TypeError(f"scenes[{i}] must be an isoslide.Scene, got {type(sc).__name__}")
        key = (sc.pi3, sc.pi4, 0.0 if sc.pi3 == 0 else sc.pi8, sc.pulse)
        if model == "auto" and sc.paper_model:
            if key not in demand:
                demand[key] = peak_stuck_demand(sc, rtol, horizon)
            if sc.static_level > demand[key] * (1.0 + 1e-9):
                facets[i] = dataclasses.replace(
                    scene_facets(sc, friction="coulomb", oneway=sc.pi3 == 0.0 or sc.pi8 == 0.0),
                    reduction="demand-bound", propagation="none")
                models[i] = facets[i].label(slid=False)
                settled[i] = True
                tpk[i] = sc.pulse.tau_start
                tend[i] = sc.pulse.tau_start
                continue
        s = solve(sc, rtol=rtol, horizon=horizon, model=model)
        pi1[i], res[i], tpk[i], settled[i] = s.pi1, s.pi1_residual, s.tau_peak, s.settled
        models[i], tend[i], nsteps[i], nev[i] = s.model, s.tau_end, s.n_steps, s.n_events
        facets[i] = s.facets
        angle[i] = s.peak_angle
        stage[i] = s.peak_stage
        theta[i], over[i] = s.theta_max, s.overturned
    progress.finish(n)
    return Batch(pi1=pi1, pi1_residual=res, tau_peak=tpk, settled=settled, model=models.astype(str),
                 tau_end=tend, n_steps=nsteps, n_events=nev, facets=facets, peak_angle=angle, peak_stage=stage,
                 theta_max=theta, overturned=over)


def warm_up(records: bool = False, building: bool = False, speed_bearing: bool = False) -> None:
    """Have the compiled kernel ready: load it from numba's cache, or compile it (once per install).

    Solves three tiny scenes (isolated Coulomb, fixed-base Stribeck, viscous contact) and their
    stuck demand, so that the first timed or logged solve measures solving, not compilation.
    ``records=True`` also readies the piecewise-exact path of record-driven scenes (a recorded pair's
    in the plane too), ``building=True`` the general building's kernel
    (:mod:`isoslide.engine.building_kernel`) and the planar kernel, ``speed_bearing=True`` a triple
    pendulum whose friction rises with speed along a line and in the plane
    (:mod:`isoslide.engine.tfp_flow`, :mod:`isoslide.engine.tfp_plane`: their compiled functions and the
    building and planar kernels' called from Python; solves of some seconds).
    """
    scenes = [Scene(pi2=0.2, pi3=1.0, pi4=0.1), Scene(pi2=0.2, pi3=0.0, pi5=0.5, pi6=10.0),
              Scene(pi2=0.2, pi3=1.0, pi4=0.1, pi7=1.0)]
    if records:
        scenes.append(Scene(pi2=0.2, pi3=1.0, pi4=0.1, pulse=sampled(np.array([0.0, 1.0, -0.5, 0.0]), 0.25)))
    for sc in scenes:
        solve(sc)
        peak_stuck_demand(sc)
    if records:
        ax, ay = np.array([0.0, 1.0, -0.5, 0.0]), np.array([0.0, -0.5, 1.0, 0.0])
        solve(Scene(pi2=0.2, pi3=1.0, pi4=0.1, pulse=sampled(ax, 0.25), pulse_y=sampled(ay, 0.25)))
    if building:
        solve(Scene(pi2=0.2, pi3=1.0, pi4=0.1, pi9=0.05, pi11=0.5, pi12=0.2, floor="roof"))
        solve(Scene(pi2=0.2, pi3=1.0, pi4=0.1, pi11=0.5, pi12=0.2, floor="roof"))
        solve(Scene(pi2=0.2, pi3=1.0, pi4=0.1, pulse_y="antisymmetric_ricker", pi14=0.5))
        solve(Scene(pi2=0.2, pi3=1.0, pi4=0.1, pi5=0.7, pi6=1e3, pi9=0.05, pi10=0.01))
    if speed_bearing:
        bearing = dict(pi2=0.2, pi3=2.0, pi9=0.05, pi24=0.1, pi26=0.5, pi27=2.0, pi28=0.05, pi29=0.1, pi30=0.2,
                       pi22=0.5, pi23=10.0)
        solve(Scene(**bearing), rtol=1e-3)
        solve(Scene(**bearing, pulse_y="antisymmetric_ricker", pi14=0.5), rtol=1e-3)
