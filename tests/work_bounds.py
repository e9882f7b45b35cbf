"""Work bound of a solver run: its steps in proportion to what the response does.

A run may take at most :data:`STEPS_PER_UNIT` integrator steps per located stick/slip (or
bearing) transition and per shortest period it follows, so that the cost of a scene grows
with its physics (how long it is followed, how often a contact changes mode) and never
through chattering or steps that stall.  Counted in steps, the bound is the same on every
machine and under any load.
"""

from __future__ import annotations

from isoslide.engine.building import free_step

STEPS_PER_UNIT = 1000
"""Most steps per transition and per shortest period followed (the domain's sweeps reach about 350:
an undamped base with a sharp Stribeck law, 211,065 steps for 407 transitions over 205 periods)."""


def periods_followed(s, sc) -> float:
    """Shortest periods of ``sc`` (an eighth of them is :func:`free_step`) in the window ``s`` followed."""
    return (s.tau_end - sc.span[0]) / (8.0 * free_step(sc))


def assert_work_bounded(s, sc):
    """``s.n_steps`` at most :data:`STEPS_PER_UNIT` per transition and per shortest period followed."""
    units = s.n_events + periods_followed(s, sc) + 1.0
    assert s.n_steps <= STEPS_PER_UNIT * units, (
        f"{s.n_steps} steps for {s.n_events} transitions over {periods_followed(s, sc):.4g} periods: {sc!r}")
