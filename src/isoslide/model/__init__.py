"""What is simulated: the parts of a building and the contact laws, in plain Python.

:mod:`isoslide.model.friction` holds the contact law, written once for the compiled solvers,
the time-history tables and the figures.
"""
