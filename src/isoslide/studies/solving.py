"""The arguments the grid studies share: their settings and the batch solver they call.

The study functions that solve grids of scenes from the configuration
(:func:`isoslide.studies.planar.planar_study`, :func:`~isoslide.studies.planar.pi5_study`,
:func:`isoslide.studies.storeys.storeys_study`,
:func:`isoslide.studies.record_study.record_pairs_dataset`,
:func:`isoslide.studies.isolation_study.design_comparison` and the ``*_dataset`` functions built
on them) take these two arguments alike, and the grids of records
(:func:`~isoslide.studies.record_study.compare_grid`, :func:`~isoslide.studies.record_study.pairs_grid`)
take ``solve_many`` alike; each function names only its own settings function and what it reads of
the solver's answers.

``settings`` : mapping
    The sections of a complete configuration the study reads, as the study's ``*_settings``
    function copies them (:func:`isoslide.studies.planar.planar_settings`,
    :func:`isoslide.studies.storeys.storeys_settings`,
    :func:`isoslide.studies.record_study.pairs_settings`).
``solve_many`` : callable, optional
    ``solve_many(scenes, rtol=...)``, called once or more with a list of :class:`isoslide.Scene`,
    returning an object with an array, one entry per scene in order, for each field of
    :class:`isoslide.Batch` the study reads.  ``None`` (the default) is :func:`isoslide.solve_many`
    (:func:`batch_solver`); any other such callable stands in for it, e.g. a stub that answers
    without solving.
"""

from __future__ import annotations

from .. import solver

__all__ = ["batch_solver"]


def batch_solver(solve_many=None):
    """The batch solver a study calls: ``solve_many``, or :func:`isoslide.solve_many` if it is None.

    Parameters
    ----------
    solve_many : callable, optional
        As the module describes it.

    Returns
    -------
    callable
        ``solve_many(scenes, rtol=...)``.
    """
    return solver.solve_many if solve_many is None else solve_many
