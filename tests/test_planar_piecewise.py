"""Recorded pairs in the plane: stick phases propagated exactly, slides in the planar kernel.

:mod:`isoslide.engine.planar_piecewise` against the planar kernel integrating the whole record
(``model="full"``), against the independent SciPy planar peer, and the scenes it takes.
"""

import math

import numpy as np
import pytest

import isoslide
from isoslide.engine.planar import pair_grid
from isoslide.peers.reference_planar import solve_reference_planar
from isoslide.pulses import sampled
from isoslide.records import suite

BASES = {
    "fixed-base": dict(pi2=0.2, pi3=0.0),
    "isolated-one-way": dict(pi2=0.2, pi3=2.0, pi4=0.1),
    "isolated-two-way": dict(pi2=0.15, pi3=2.5, pi4=0.05, pi8=0.3),
}


def _wrapped(a: float) -> float:
    return (a + math.pi) % (2.0 * math.pi) - math.pi


@pytest.fixture(scope="module")
def pairs():
    return suite("fema-p695-near-field-pulse")[:2]


@pytest.mark.parametrize("base", list(BASES))
@pytest.mark.parametrize("angle", [0.0, 0.4, -2.1])
def test_a_recorded_pair_gives_the_fully_integrated_answer(pairs, base, angle):
    """Pi1, its direction and the transitions of the exact stick propagation equal those of the planar kernel
    integrating every sample (both to far below the tolerance)."""
    for gm in pairs:
        scene = isoslide.Scene(**BASES[base], pulse=gm.x, pulse_y=gm.y, angle=angle)
        assert pair_grid(scene) is not None
        fast = isoslide.solve(scene)
        full = isoslide.solve(scene, model="full")
        assert fast.facets.propagation == "piecewise" and full.facets.propagation == "integrated"
        assert fast.facets.contact == full.facets.contact == "plane"
        assert full.pi1 > 1e-4
        assert fast.pi1 == pytest.approx(full.pi1, rel=1e-9)
        assert abs(_wrapped(fast.peak_angle - full.peak_angle)) < 1e-8
        assert fast.n_events == full.n_events
        assert fast.settled == full.settled


def _short_pair(seed: int, n: int = 240, dt: float = 0.02):
    """Two band-limited random components of ``n`` samples on one grid (units of a_p, T_p)."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) * dt
    env = np.sin(np.pi * t / t[-1]) ** 2
    comps = []
    for _ in range(2):
        a = sum(rng.normal() * np.sin(2.0 * np.pi * f * t + rng.uniform(0.0, 6.3)) for f in (0.6, 1.1, 1.7, 2.9))
        comps.append(env * a / np.max(np.abs(env * a)))
    return sampled(comps[0], dt), sampled(comps[1], dt)


@pytest.mark.parametrize("base", list(BASES))
def test_a_short_synthetic_pair_agrees_with_the_scipy_peer(base):
    """Pi1 to 1e-6 relative and its direction to 1e-6 rad against the independent event-driven peer."""
    px, py = _short_pair(7)
    scene = isoslide.Scene(**BASES[base], pulse=px, pulse_y=py, pi14=0.8, angle=0.3)
    sol = isoslide.solve(scene, horizon=3.0)
    ref = solve_reference_planar(scene, horizon=3.0)
    assert sol.facets.propagation == "piecewise" and ref.pi1 > 1e-3
    assert sol.pi1 == pytest.approx(ref.pi1, rel=1e-6)
    assert abs(_wrapped(sol.peak_angle - ref.peak_angle)) < 1e-6


def test_the_history_runs_forward_and_holds_the_peak():
    px, py = _short_pair(3)
    scene = isoslide.Scene(pi2=0.15, pi3=2.0, pi4=0.1, pulse=px, pulse_y=py)
    sol = isoslide.solve(scene, history=True)
    h = sol.history
    assert np.all(np.diff(h.tau) >= 0.0)
    size = np.hypot(h.u[:, 0], h.u[:, 1])
    assert size.max() == pytest.approx(sol.pi1, rel=1e-12)
    assert np.all(h.ud[h.phase == 0] == 0.0)


@pytest.mark.parametrize("extra", [dict(pi9=0.05), dict(pi5=0.6, pi6=20.0), dict(pi17=0.3, pulse_z="ricker"),
                                   dict(pi11=0.5, pi12=0.3, pi13=0.05, floor="roof"), dict(pi16=0.013)],
                         ids=["friction-pendulum", "stribeck", "vertical", "flexible", "shifted-grid"])
def test_scenes_outside_its_reach_are_integrated(extra):
    """A bearing, speed-dependent friction, vertical motion, a flexible superstructure or a second component
    off the first one's grid run in the planar kernel over every sample."""
    px, py = _short_pair(5)
    scene = isoslide.Scene(**{"pi2": 0.15, "pi3": 2.0, "pi4": 0.1, **extra}, pulse=px, pulse_y=py)
    assert pair_grid(scene) is None
    assert isoslide.solve(scene, horizon=3.0).facets.propagation == "integrated"
