"""The compiled solvers and what they integrate: the model assembled into arrays, the kernels.

:mod:`isoslide.engine.building` assembles a building into the arrays of
:mod:`isoslide.engine.building_kernel` (the general event-driven engine of a slab, N floors and
the contents on any floor), and :mod:`isoslide.engine.system` keeps that assembly (with the modal
data, breakpoints and step budget) once per scene; :mod:`isoslide.engine.kernel` (the paper's model) and
:mod:`isoslide.engine.piecewise` (exact propagation of sampled records) are fast paths the
planner in :mod:`isoslide.solver` chooses; :mod:`isoslide.engine.planar_kernel` integrates the
same buildings with the contents sliding in the plane, from the inputs :mod:`isoslide.engine.planar`
assembles, and :mod:`isoslide.engine.planar_piecewise` propagates a recorded pair's stick phases
exactly between the planar kernel's slides; :mod:`isoslide.engine.free_phase` steps the free linear
phase after the pulse exactly, and :mod:`isoslide.engine.exponential` a linearly isolated flexible
building between its contents' transitions; :mod:`isoslide.engine.dop853` holds the Runge-Kutta
tableau.
Nothing is imported here.
"""
