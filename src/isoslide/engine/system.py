"""A scene assembled once into the system the compiled kernels integrate.

A solve needs, besides the scene's groups, what the engine derives from them: the parts of the
building (:func:`isoslide.model.parts.building_of`), the kernel's parameter array
(:func:`isoslide.engine.building.parameters`), the modal data of the free phase
(:func:`isoslide.engine.building.modal_data`), every breakpoint of the excitation, the end of the
excitation and of the run, the step budget and the longest free step.  :func:`assemble` derives
them once and keeps them with the scene (a :class:`isoslide.Scene` is immutable), so that the
planner, the tolerance loop, the kernels and the post-processing of a solve
(:func:`isoslide.engine.planar.floor_motion`) read one :class:`System` instead of deriving each
piece again.

Times are in units of ``T_p``.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np

from . import building, exponential, free_phase, kernel
from . import building_kernel as bk
from ..model import parts
from ..scene import Scene

DEFAULT_HORIZON = 200.0
"""How long a scene that does not settle is followed after its excitation, in isolation periods
(pulse periods for a fixed base)."""
STEPS_PER_PERIOD = 200
"""Runge-Kutta steps a run may take per period followed (:func:`step_budget`)."""


def excitation_end(scene: Scene) -> float:
    """End of the excitation: the last of its components' (:attr:`isoslide.Scene.span`)."""
    return scene.span[1]


def horizon_end(scene: Scene, horizon: float = DEFAULT_HORIZON) -> float:
    """Time at which a run that has not settled stops: ``horizon`` periods after the excitation."""
    return excitation_end(scene) + horizon * max(scene.pi3, 1.0)


def breakpoints(scene: Scene) -> np.ndarray:
    """Every acting component's breakpoints on the main pulse's time axis (the second pulse's mapped)."""
    b = scene.pulse.breakpoint_array
    if scene.bidirectional:
        py = scene.pulse_y
        b = np.union1d(b, scene.pi16 + scene.pi15 * np.append(py.breakpoint_array, py.tau_start))
    if scene.vertical:
        b = np.union1d(b, scene.pulse_z.breakpoint_array)
    return b[b > scene.span[0]]


def step_budget(scene: Scene, horizon: float = DEFAULT_HORIZON) -> int:
    """Most Runge-Kutta steps one run of a scene may take.

    ``STEPS_PER_PERIOD`` per isolation period followed (a stiff undamped base is followed for up to
    ``horizon / Pi3`` periods, each with its own breakaways; for a general building the shortest
    period it integrates counts, see :func:`isoslide.engine.building.free_step`), and never fewer than
    :data:`isoslide.engine.kernel.MAX_STEPS`.  A run that needs more raises
    :class:`isoslide.solver.StepBudgetError`.
    """
    span = horizon_end(scene, horizon) - scene.pulse.tau_start
    periods = span / scene.pi3 if scene.pi3 > 0.0 else span
    if not scene.paper_model:
        periods = max(periods, span / (8.0 * building.free_step(scene)))
    return int(max(kernel.MAX_STEPS, min(STEPS_PER_PERIOD * periods, 1e12)))


@dataclass(frozen=True)
class System:
    """A general scene as the building and planar kernels integrate it.

    Attributes
    ----------
    P : ndarray
        The kernel's parameters (:func:`isoslide.engine.building.parameters`).
    modal : tuple of ndarray
        Modal data of the free phase (:func:`isoslide.engine.building.modal_data`).
    breakpoints : ndarray
        Breakpoints of every acting component (:func:`breakpoints`).
    start, end, stop : float
        Start and end of the excitation, and the time a run that has not settled stops
        (:func:`horizon_end`), units of T_p.
    budget : int
        Most Runge-Kutta steps of one run (:func:`step_budget`).
    free_step : float
        Longest step after the pulse (:func:`isoslide.engine.building.free_step`), units of T_p.
    linear : tuple of ndarray or None
        The arrays of the exact propagation (:func:`isoslide.engine.exponential.arrays`) where it
        applies (:func:`isoslide.engine.exponential.applies`), else None.
    """

    P: np.ndarray
    modal: tuple
    breakpoints: np.ndarray
    start: float
    end: float
    stop: float
    budget: int
    free_step: float
    linear: tuple | None = None

    @cached_property
    def planar_modal(self) -> tuple:
        """:attr:`modal` in the planar kernel's axis order (:func:`isoslide.engine.planar_kernel.run`).

        An axis of the planar state is ``[x, x', xs.., xs'..]`` and a bilinear bearing's ``fh``, which
        the general kernel's state holds last (after the block's ``u, u'``): ``W``'s columns and
        ``V``'s rows are taken in that order.
        """
        n = int(self.P[bk.P_N])
        Wm, Cm, Vm, Lm, Wh, Ch, Vh, Lh = self.modal
        hyst = self.P[bk.P_KIND] == bk.KIND_BILINEAR
        cols = list(range(2 + 2 * n)) + ([Wm.shape[1] - 1] if hyst else [])
        return (np.ascontiguousarray(Wm[:, cols]), Cm, np.ascontiguousarray(Vm[cols, :]), Lm,
                np.ascontiguousarray(Wh[:, cols]), Ch, np.ascontiguousarray(Vh[cols, :]), Lh)


def assemble(scene: Scene, pi8: float | None = None, coulomb: bool = False, rocking: bool | None = None,
             horizon: float = DEFAULT_HORIZON) -> System:
    """The :class:`System` of a general scene, derived once per scene and these arguments.

    Parameters
    ----------
    scene : Scene
    pi8, coulomb, rocking
        As for :func:`isoslide.engine.building.parameters`: the contents' mass ``Pi8 = m_EC/M_b``
        (0: one-way coupling; None: the scene's), friction at its static level at every speed, the
        rocking model (None: for a block that tips before it can slide).
    horizon : float
        As for :func:`horizon_end`, in isolation periods.

    Returns
    -------
    System
        The same object for the same scene and arguments: the kernels copy what they change.
    """
    key = (pi8, bool(coulomb), rocking, float(horizon))
    systems = scene.__dict__.setdefault("_systems", {})
    if key not in systems:
        P = building.parameters(scene, pi8=pi8, coulomb=coulomb, rocking=rocking)
        start, end = scene.span
        modal = building.modal_data(scene, P)
        linear = None
        if not scene.bidirectional and exponential.applies(P, scene.pulse.code):
            try:
                linear = exponential.arrays(P, modal)
            except ValueError:
                linear = None   # modes not trustworthy: the Runge-Kutta kernel integrates it
        systems[key] = System(P=P, modal=modal, breakpoints=breakpoints(scene), start=start, end=end,
                              stop=horizon_end(scene, horizon), budget=step_budget(scene, horizon),
                              free_step=building.free_step(scene), linear=linear)
    return systems[key]



def unassembled(scene: Scene) -> Scene:
    """A scene equal to ``scene`` that carries nothing assembled yet.

    A solve of it pays for its own assembly, as a solve of a study's new scene does: the
    benchmarks time such copies, so that the cost they report is a study's and not that of a scene
    solved again.
    """
    return replace(scene)


def forget_shared() -> None:
    """Forget what scenes that share a building share: its superstructure's matrices and its modes.

    The next assembly derives them anew, as a study's first scene on a building does
    (:func:`isoslide.engine.free_phase.modes`, :meth:`isoslide.model.parts.Superstructure.matrices`).
    """
    free_phase.forget()
    parts.forget_shared()
