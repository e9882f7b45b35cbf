"""Vertical ground motion in the general building's SciPy reference peer.

The peer (:mod:`isoslide.peers.reference_building`) multiplies every normal force by
``n(tau) = 1 + Pi17 p_z(tau)``: the contents' friction and stick limit, and a friction pendulum's
strength and stiffness.  It is checked against the exact solver on time-varying vertical pulses,
against the scene of scaled friction under a constant vertical acceleration, and against the scene
without vertical motion as ``Pi17`` vanishes.
"""

import math

import numpy as np
import pytest

import isoslide
from isoslide import Scene
from isoslide.peers.reference import solve_reference
from isoslide.peers.reference_building import excitation_end, run_building, solve_reference_building
from isoslide.pulses import sampled

RTOL = 1e-6
"""Relative agreement required of the peer's Pi1 with the exact solver's."""

COULOMB = dict(pi2=0.15, pi3=2.0, pi4=0.1, pi8=0.01)
STRIBECK = dict(pi2=0.15, pi3=2.0, pi4=0.1, pi8=0.01, pi5=0.7, pi6=80.0, pi7=0.05)
FLEXIBLE = dict(pi11=0.5, pi12=0.3, pi13=0.05)


def _late_record():
    """A piecewise-linear vertical record (``|p_z| <= 1``) from tau = -2.5 to 6, past the Ricker's end."""
    t = np.arange(-2.5, 6.0 + 1e-9, 0.05)
    return sampled(np.sin(2.0 * math.pi * t / 0.7) * np.exp(-0.1 * (t + 2.5)), 0.05, tau0=-2.5, name="late")


VERTICAL_SCENES = {
    "fixed base, Coulomb, Ricker": dict(pi2=0.15, pi3=0.0, pi17=0.5, pulse_z="ricker"),
    "fixed base, Stribeck, antisymmetric Ricker": dict(STRIBECK, pi3=0.0, pi17=0.8,
                                                       pulse_z="antisymmetric_ricker"),
    "linear isolator, Coulomb, Ricker": dict(COULOMB, pi17=0.3, pulse_z="ricker"),
    "linear isolator, Stribeck, antisymmetric Ricker": dict(STRIBECK, pi17=0.6, pulse_z="antisymmetric_ricker"),
    "linear isolator, Coulomb, record outlasting the pulse": dict(COULOMB, pi17=0.5, pulse_z=_late_record()),
    "friction pendulum, Coulomb, Ricker": dict(COULOMB, pi9=0.05, pi17=0.8, pulse_z="ricker"),
    "friction pendulum, Stribeck, antisymmetric Ricker": dict(STRIBECK, pi9=0.05, pi17=0.4,
                                                              pulse_z="antisymmetric_ricker"),
    "friction pendulum, flexible, roof, Stribeck": dict(STRIBECK, **FLEXIBLE, pi9=0.05, floor="roof", pi17=0.5,
                                                        pulse_z="ricker"),
    "lead-rubber bearing, Coulomb, antisymmetric Ricker": dict(COULOMB, pi9=0.08, pi10=0.01, pi17=0.2,
                                                               pulse_z="antisymmetric_ricker"),
    "lead-rubber bearing, flexible, roof, Stribeck": dict(STRIBECK, **FLEXIBLE, pi9=0.08, pi10=0.01, floor="roof",
                                                          pi17=0.5, pulse_z="ricker"),
    "linear isolator, three storeys, roof, Coulomb": dict(COULOMB, **FLEXIBLE, storeys=3, floor="roof", pi17=0.6,
                                                          pulse_z="antisymmetric_ricker"),
}


def _without_vertical(kw: dict) -> dict:
    return {k: v for k, v in kw.items() if k not in ("pi17", "pulse_z")}


@pytest.mark.parametrize("name", list(VERTICAL_SCENES))
def test_peer_agrees_with_the_exact_solver_under_a_vertical_pulse(name):
    """Pi1 of the peer within 1e-6 relative of ``isoslide.solve`` (rtol 1e-10), on a scene whose
    vertical motion changes Pi1 by more than 0.1 % (so a peer ignoring it fails)."""
    kw = VERTICAL_SCENES[name]
    scene = Scene(**kw)
    assert scene.vertical
    exact = isoslide.solve(scene, rtol=1e-10)
    peer = solve_reference_building(scene)
    assert exact.settled and peer.settled
    assert peer.pi1 == pytest.approx(exact.pi1, rel=RTOL)
    plain = solve_reference_building(Scene(**_without_vertical(kw)))
    assert abs(peer.pi1 - plain.pi1) > 1e-3 * plain.pi1


def test_a_friction_pendulum_breaks_away_at_its_strength_times_the_normal_force():
    """The pendulum's slab both slides and is held; while held its holding force stays within
    ``q n(tau)``, and it breaks away where that force reaches ``q n(tau)`` with ``n`` 5 % or more
    away from 1 (so the static strength ``q`` alone would be wrong there)."""
    scene = Scene(**VERTICAL_SCENES["friction pendulum, Stribeck, antisymmetric Ricker"])
    h = solve_reference_building(scene, history=True).history
    assert np.any(h.iso_phase != 0) and np.any(h.iso_phase == 0)
    held = h.iso_phase == 0
    n = 1.0 + scene.pi17 * np.asarray(scene.pulse_z.accel(h.tau[held]), dtype=float)
    ratio = np.abs(h.fh[held]) / (scene.pi9 * n)
    assert np.all(ratio <= 1.0 + 1e-9)
    at_limit = ratio >= 1.0 - 1e-9
    assert np.any(at_limit)
    assert np.all(np.abs(n[at_limit] - 1.0) > 0.05)


def _constant(tau0: float, sign: float = 1.0):
    """Vertical acceleration ``p_z = sign`` from ``tau0`` for 40 T_p (longer than any response here)."""
    return sampled(sign * np.ones(41), 1.0, tau0=tau0, name="constant")


CONSTANT_SCENES = {
    "fixed base, Coulomb": (dict(pi2=0.15, pi3=0.0), lambda n: dict(pi2=0.15 * n, pi3=0.0)),
    "linear isolator, Stribeck": (dict(STRIBECK, pi6=300.0, pi7=0.2),
                                  lambda n: dict(STRIBECK, pi2=0.15 * n, pi6=300.0, pi7=0.2 * n)),
    "friction pendulum, Coulomb": (dict(COULOMB, pi9=0.05),
                                   lambda n: dict(COULOMB, pi3=2.0 / math.sqrt(n), pi4=0.1 / math.sqrt(n),
                                                  pi2=0.15 * n, pi9=0.05 * n)),
    "lead-rubber bearing, flexible, roof": (dict(COULOMB, **FLEXIBLE, pi9=0.08, pi10=0.01, floor="roof"),
                                            lambda n: dict(COULOMB, **FLEXIBLE, pi2=0.15 * n, pi9=0.08,
                                                           pi10=0.01, floor="roof")),
}


@pytest.mark.parametrize("c", [0.4, -0.3], ids=["upward", "downward"])
@pytest.mark.parametrize("name", list(CONSTANT_SCENES))
def test_a_constant_vertical_acceleration_equals_scaled_friction_in_the_peer(name, c):
    """``n = 1 + c`` throughout (``Pi17 = |c|``, ``p_z = sgn c``): ``Pi2 -> n Pi2``, ``Pi7 -> n Pi7``
    (and for a friction pendulum ``Pi9 -> n Pi9``, ``Pi3 -> Pi3/sqrt(n)``, ``Pi4 -> Pi4/sqrt(n)``) in
    the scene without vertical motion give the same Pi1 to 1e-9 relative."""
    kw, scaled = CONSTANT_SCENES[name]
    vertical = Scene(**kw, pi17=abs(c), pulse_z=_constant(-2.0, math.copysign(1.0, c)))
    res = solve_reference_building(vertical)
    plain = solve_reference_building(Scene(**scaled(1.0 + c)))
    assert res.settled and res.pi1 > 0.0
    assert res.pi1 == pytest.approx(plain.pi1, rel=1e-9)
    # the scaling is not the identity: the unscaled scene slides differently
    assert abs(solve_reference_building(Scene(**kw)).pi1 - res.pi1) > 1e-3 * res.pi1


def test_a_vanishing_vertical_pulse_tends_to_the_scene_without_it():
    """A friction pendulum under a vertical Ricker: the change of Pi1 is linear in Pi17 as it
    vanishes (its slope at Pi17 = 1e-4 and 1e-6 agrees to 1 %), so Pi1 tends to the plain scene's."""
    kw = dict(COULOMB, pi9=0.05)
    plain = solve_reference_building(Scene(**kw)).pi1
    slopes = []
    for pi17 in (1e-4, 1e-6):
        pi1 = solve_reference_building(Scene(**kw, pi17=pi17, pulse_z="ricker")).pi1
        slopes.append((pi1 - plain) / (pi17 * plain))
    assert abs(slopes[0]) > 1e-2
    assert slopes[1] == pytest.approx(slopes[0], rel=1e-2)


def test_pi17_zero_with_a_vertical_shape_is_the_scene_without_it():
    """``Pi17 = 0`` with a ``pulse_z`` has no vertical motion: the peer's Pi1 is identical."""
    kw = dict(STRIBECK, pi9=0.05)
    assert (solve_reference_building(Scene(**kw, pi17=0.0, pulse_z="ricker")).pi1
            == solve_reference_building(Scene(**kw)).pi1)


def test_a_paper_model_scene_with_vertical_motion_goes_to_the_building_peer():
    """``solve_reference`` sends a linear isolator under a rigid superstructure with vertical motion
    (not the paper's model) to the general building's peer, which models the normal force."""
    kw = VERTICAL_SCENES["linear isolator, Coulomb, Ricker"]
    scene = Scene(**kw)
    assert not scene.paper_model
    via_dispatch = solve_reference(scene)
    assert via_dispatch.pi1 == solve_reference_building(scene).pi1
    assert abs(via_dispatch.pi1 - solve_reference(Scene(**_without_vertical(kw))).pi1) > 1e-3 * via_dispatch.pi1


def test_the_run_settles_only_after_the_later_pulse_ends():
    """With a vertical record ending at tau = 6 after the Ricker's end (2), the peer's excitation end
    is 6 and a settled run stops no earlier."""
    scene = Scene(**VERTICAL_SCENES["linear isolator, Coulomb, record outlasting the pulse"])
    assert excitation_end(scene) == pytest.approx(6.0)
    res = solve_reference_building(scene)
    assert res.settled and res.tau_end >= 6.0


def test_the_vertical_pulses_breakpoints_are_phase_boundaries():
    """Every knot of a sampled vertical record (where ``dn/dtau`` jumps) ends an integration phase:
    each is a time of the history, as is every breakpoint of the horizontal pulse."""
    scene = Scene(**VERTICAL_SCENES["linear isolator, Coulomb, record outlasting the pulse"])
    h = solve_reference_building(scene, history=True).history
    knots = np.union1d(scene.pulse_z.breakpoint_array, scene.pulse.breakpoint_array)
    knots = knots[knots > scene.pulse.tau_start]
    assert knots.size > 100
    assert np.all(np.isin(knots, h.tau))


def test_the_energy_ledger_refuses_vertical_motion():
    """The ledger holds no vertical work: ``ledger=True`` on a vertical scene is a ValueError."""
    with pytest.raises(ValueError, match="vertical ground motion"):
        run_building(Scene(**VERTICAL_SCENES["linear isolator, Coulomb, Ricker"]), ledger=True)
