"""The exact planar solver against its independent peers.

The SciPy event-driven peer :mod:`isoslide.peers.reference_planar` shares no code with the compiled
planar kernel; both integrate the same model (planar Stribeck contents, the building in x and y,
vertical motion through the normal force, a friction pendulum as a second planar friction interface,
a bilinear bearing with a circular yield surface)
to far below the tolerance compared here.
"""

import math

import pytest

import isoslide
from isoslide.peers.reference_planar import solve_reference_planar

SCENES = {
    "fixed-base-coulomb": dict(pi2=0.12, pi3=0.0, pulse_y="antisymmetric_ricker", pi14=0.8),
    "linear-two-way": dict(pi2=0.12, pi3=2.0, pi4=0.1, pi8=0.2, pulse_y="antisymmetric_ricker", pi14=0.8),
    "fixed-base-stribeck-shifted": dict(pi2=0.1, pi3=0.0, pi5=0.6, pi6=20.0, pi7=0.3, pulse_y="ricker", pi14=1.2,
                                        pi15=0.6, pi16=0.3),
    "linear-vertical": dict(pi2=0.15, pi3=1.5, pi4=0.05, pi8=0.1, pi17=0.5, pulse_z="ricker",
                            pulse_y="makris_a", pi14=0.5, angle=0.4),
    "friction-pendulum-two-way": dict(pi2=0.1, pi3=2.0, pi4=0.05, pi9=0.12, pi8=0.3, pulse_y="antisymmetric_ricker",
                                      pi14=0.8),
    "friction-pendulum-flexible-roof-vertical": dict(pi2=0.12, pi3=2.5, pi9=0.06, pi11=0.5, pi12=0.3, pi13=0.05,
                                                     floor="roof", pi8=0.1, pi17=0.3, pulse_z="ricker",
                                                     pulse_y="ricker", pi14=0.9, pi15=0.7, pi16=0.25),
    "three-storeys-roof": dict(pi2=0.15, pi3=2.0, pi4=0.1, pi11=0.5, pi12=0.3, pi13=0.05, storeys=3, floor="roof",
                               pi8=0.1, pulse_y="antisymmetric_ricker", pi14=0.9, pi16=-0.2),
    "bilinear-two-way": dict(pi2=0.15, pi3=2.0, pi4=0.1, pi9=0.05, pi10=0.02, pi8=0.2, pulse_y="antisymmetric_ricker",
                             pi14=0.7),
    "bilinear-stribeck-shifted": dict(pi2=0.1, pi3=3.0, pi4=0.05, pi9=0.08, pi10=0.05, pi8=0.1, pi5=0.7, pi6=20.0,
                                      pulse_y="ricker", pi14=1.0, pi15=1.3, pi16=0.2),
    "bilinear-three-storeys-roof-vertical": dict(pi2=0.2, pi3=2.0, pi4=0.1, pi9=0.05, pi10=0.03, pi8=0.3, pi11=0.5,
                                                 pi12=0.3, pi13=0.05, storeys=3, floor="roof", pi17=0.3,
                                                 pulse_z="ricker", pulse_y="antisymmetric_ricker", pi14=0.8),
}


@pytest.mark.parametrize("name", list(SCENES))
def test_the_exact_planar_solver_agrees_with_the_scipy_peer(name):
    """Pi1 to 1e-6 relative and the peak's direction to 1e-6 rad, at the default tolerance."""
    scene = isoslide.Scene(**SCENES[name])
    assert scene.planar
    exact = isoslide.solve(scene, horizon=3.0)
    ref = solve_reference_planar(scene, horizon=3.0)
    assert exact.pi1 > 1e-3
    assert exact.pi1 == pytest.approx(ref.pi1, rel=1e-6)
    assert abs((exact.peak_angle - ref.peak_angle + math.pi) % (2.0 * math.pi) - math.pi) < 1e-6
    assert exact.tau_peak == pytest.approx(ref.tau_peak, abs=1e-5)


def test_method_reference_runs_the_planar_peer_for_a_planar_scene():
    scene = isoslide.Scene(**SCENES["fixed-base-coulomb"])
    sol = isoslide.solve(scene, method="reference")
    assert sol.model == "reference"
    assert sol.pi1 == pytest.approx(isoslide.solve(scene).pi1, rel=1e-6)
