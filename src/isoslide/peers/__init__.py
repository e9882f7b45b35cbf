"""Independent peer solvers of the same physics, for cross-checks and the speed-accuracy study.

Each module is one solver, written independently of the compiled kernel, and each
returns a :class:`PeerResult` whose history is an :class:`isoslide.store.history.History`:

:func:`solve_reference` (:mod:`.reference`)
    Plain SciPy event-driven solver (DOP853 with events); ``solve(scene, method="reference")``.
    A general building (bearings, a flexible superstructure of one or more storeys, contents on
    any floor, vertical ground motion through the normal forces) goes to
    :func:`~.reference_building.solve_reference_building` (:mod:`.reference_building`), and
    contents sliding in the plane (two horizontal ground components, or an angle) to
    :func:`~.reference_planar.solve_reference_planar` (:mod:`.reference_planar`).
:func:`solve_regularized` (:mod:`.regularized`)
    The paper's method: the signum replaced by a stiff elastic-plastic spring, SciPy
    Radau; ``solve(scene, method="regularized", stiffness=...)``.
:func:`simulate_si` (:mod:`.si`)
    The physical equations in SI units, for the similarity check; a general building is
    integrated by :func:`~.si_building.simulate_building_si` (:mod:`.si_building`).
:func:`~.rocking.solve_rocking` (:mod:`.rocking`), :func:`~.slide_rock.solve_block` (:mod:`.slide_rock`)
    A rigid block on a moving floor: rocking on stuck corners (Housner), and with Coulomb friction
    rest, slide, rock and slide-rock (Shenton).
:func:`~.rocking_building.solve` (:mod:`.rocking_building`)
    That block on any floor of the general building, its contact force acting back on the floor
    (two-way), with impacts and overturning.
:func:`solve_opensees` (:mod:`.opensees`)
    The paper's model and the general building in OpenSees, sticks regularised by elastic-plastic
    springs (extra ``peers``; :func:`opensees_available`).
"""

from .opensees import opensees_available, solve_opensees
from .reference import solve_reference
from .reference_planar import solve_reference_planar
from .regularized import solve_regularized
from .result import PeerResult, WorkLimitError
from .si import simulate_si

SCENE_SOLVERS = {"reference": solve_reference, "regularized": solve_regularized}
"""The peers :func:`isoslide.solve` runs for ``method=...`` (they take a :class:`isoslide.Scene`)."""

__all__ = ["PeerResult", "SCENE_SOLVERS", "WorkLimitError", "opensees_available", "simulate_si",
           "solve_opensees", "solve_reference", "solve_reference_planar", "solve_regularized"]
