"""Speed versus accuracy, measured; where the problem is stiff or slow; what each reduction buys.

This package holds the science behind ``results/datasets/accuracy.nc`` and
``reports/accuracy.html`` (and the numbers ``python -m isoslide.bench``
prints).  Everything returns labelled :class:`xarray.Dataset` objects with
``long_name``/``units`` on every variable; the report notebook only reads and
plots them.

Scene set (:func:`scene_set`)
-----------------------------
* ``study``: a deterministic subsample (fixed seed) of every study's grid of
  the configuration given (``per_study`` scenes each); the pipeline gives none,
  so its scene set comes from the paper's studies of :data:`PAPER_STUDIES` and
  does not change when a study of the run's configuration is edited;
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
(:func:`isoslide.peers.solve_reference` at ``rtol = 1e-12``) its answer is
stored as ``pi1_reference`` so the converged answer is checked by an
independent code.  Errors are relative, ``|Pi1 - Pi1_conv| / Pi1_conv``, over
the scenes that slide; on scenes that do not slide ``abs_error`` is the whole
error (the exact solver answers exactly 0 there).

Peers
-----
``reference``: the plain SciPy event-driven solver (:mod:`isoslide.peers.reference`);
``regularized``: the paper's method, signum replaced by a stiff elastic-plastic spring,
SciPy Radau (:mod:`isoslide.peers.regularized`); ``opensees`` (optional, ``accuracy.opensees``
``auto``/``true``/``false``; needs ``pip install -e .[peers]``, pinned in ``environment.lock``):
the same bilinear spring in OpenSees (:func:`isoslide.peers.solve_opensees`), Coulomb
scenes only.  The peers run on evenly spread subsets of the scene set.

Horizon
-------
Every method follows a scene that does not settle (``xi_b = 0``) to the same
time, ``tau_end + horizon * max(1, Pi3)`` (``horizon`` of the configuration,
default 50), so the peak is the same quantity for all of them.  The compiled
solver stops where it proves that the contents never slide again; the peers,
which cannot all prove it, stop two isolation periods (at least ``T_p``) after
the converged answer settles (``peer_stop``), so their cost is that of the
motion, not of following a block at rest to the horizon.

Determinism
-----------
Everything measured is a deterministic function of the configuration and the
code, *except* the wall-clock cost variables, whose names end in ``_seconds``
and which carry the attribute ``nondeterministic = "true"``.  The pipeline
writes them apart (:func:`split_timings`): ``results/datasets/accuracy.nc`` is
the same bytes for the same configuration, and
``results/timings/accuracy_timings.nc`` holds the costs (:func:`join_timings`
puts them back together).  Work counters (``work``: integrator steps for the
compiled solver, right-hand-side evaluations for the SciPy peers) are
deterministic, and so is every outcome: the peers are bounded by work
(``peer_max_work``), never by wall-clock time.

Modules
-------
:mod:`.settings`
    The ``accuracy`` section (:func:`settings_from`) and the methods measured (:func:`method_settings`).
:mod:`.scenes`
    The scene set: study subsamples and the hard cases.
:mod:`.timing`
    One setting on one scene, timed, bounded by work (:func:`run_setting`).
:mod:`.trade`, :mod:`.reductions`, :mod:`.domain`
    The measurements: error versus cost, the model reductions, the domain map.
:mod:`.dataset`
    The parts (:data:`PARTS`, :func:`measure_part`) combined into the dataset, its table and
    Pareto front.
"""

from ..groups import INPUT_NAMES as PI_INPUTS
from ..peers import opensees_available, solve_opensees
from .dataset import (NONDETERMINISTIC_SUFFIX, PARTS, TIMINGS_SUFFIX, accuracy_dataset, combine,
                      deterministic_part, join_timings, measure_part, pareto_front, split_timings,
                      trade_table)
from .domain import DOMAIN, MAP_BASE, domain_map, map_values
from .reductions import NOSLIDE_COLUMN, REDUCTION_TEXT, REDUCTIONS, measure_reductions
from .scenes import Entry, SceneSet, hard_scenes, scene_coords, scene_set, study_entries
from .settings import PAPER_CONFIG, PAPER_STUDIES, Setting, method_settings, settings_from
from ..solver import warm_up
from .timing import STATUS, STATUS_ATTRS, run_setting, tau_max
from .trade import converged, measure_trade, rel_error, summarize_trade

__all__ = [
    "DOMAIN", "Entry", "MAP_BASE", "NONDETERMINISTIC_SUFFIX", "NOSLIDE_COLUMN", "PAPER_CONFIG",
    "PAPER_STUDIES", "PARTS", "PI_INPUTS", "REDUCTIONS", "REDUCTION_TEXT", "STATUS", "STATUS_ATTRS",
    "SceneSet", "Setting", "TIMINGS_SUFFIX", "accuracy_dataset", "combine", "converged",
    "deterministic_part", "domain_map", "hard_scenes", "join_timings", "map_values", "measure_part",
    "measure_reductions", "measure_trade", "method_settings", "opensees_available", "pareto_front",
    "rel_error", "run_setting", "scene_coords", "scene_set", "settings_from", "solve_opensees",
    "split_timings", "study_entries", "summarize_trade", "tau_max", "trade_table", "warm_up",
]
