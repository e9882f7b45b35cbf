"""A sliding bearing whose friction rises with its speed: limits, settlement, the API and bad input."""

from __future__ import annotations

import numpy as np
import pytest

import isoslide
from isoslide.engine import building
from isoslide.model.parts import building_of
from isoslide.peers.reference_building import solve_reference_building

BASE = dict(pi2=0.3, pi3=2.0, pi8=0.01)
"""Contents that slide on a friction pendulum under the Ricker pulse."""


def _scene(**kw):
    return isoslide.Scene(**{**BASE, **kw})


def test_zero_rate_is_constant_friction_at_the_breakaway_level_to_the_bit():
    """``Pi23 = 0`` gives the answer of the constant strength ``Pi9 Pi22``, and ``Pi22 = 1`` that of ``Pi9``, bit for bit."""
    a = isoslide.solve(_scene(pi9=0.3, pi22=0.5, pi23=0.0))
    b = isoslide.solve(_scene(pi9=0.3 * 0.5))
    assert a.pi1 == b.pi1 and a.pi1 > 0.0
    assert a.model == b.model == "sliding-bearing+coulomb"
    c = isoslide.solve(_scene(pi9=0.3, pi22=1.0, pi23=50.0))
    d = isoslide.solve(_scene(pi9=0.3))
    assert c.pi1 == d.pi1 and c.model == d.model


def test_friction_pendulum_without_mu_slow_returns_the_constant_bearing_unchanged():
    assert isoslide.friction_pendulum(2.0, 0.08, 1e6) == isoslide.friction_pendulum(2.0, 0.08, 1e6, mu_slow=None)
    assert set(isoslide.friction_pendulum(2.0, 0.08, 1e6)) == {"T_b", "Q_d", "D_y"}


def test_friction_pendulum_with_zero_rate_is_the_pendulum_of_mu_slow_bit_for_bit():
    slow = isoslide.friction_pendulum(2.0, 0.08, 1e6, mu_slow=0.05, rate=0.0)
    assert slow == isoslide.friction_pendulum(2.0, 0.05, 1e6)
    kw = dict(a_p=3.0, T_p=1.0, M_b=1e6, xi_b=0.0, m_ec=1e4, mu_s=0.06, mu_k=0.06)
    a = isoslide.solve(isoslide.Scene.from_physical(**kw, **slow))
    b = isoslide.solve(isoslide.Scene.from_physical(**kw, **isoslide.friction_pendulum(2.0, 0.05, 1e6)))
    assert a.pi1 == b.pi1 > 0.0


def test_friction_pendulum_groups_follow_the_law():
    """``from_physical`` turns mu_slow and rate into ``Pi22 = mu_slow/mu`` and ``Pi23 = a a_p T_p``."""
    fp = isoslide.friction_pendulum(2.0, 0.08, 1e6, mu_slow=0.04, rate=25.0)
    sc = isoslide.Scene.from_physical(a_p=3.0, T_p=1.5, M_b=1e6, xi_b=0.0, m_ec=1e4, mu_s=0.3, mu_k=0.3, **fp)
    assert sc.pi9 == pytest.approx(0.08 * isoslide.G_STANDARD / 3.0, rel=1e-14)
    assert sc.pi22 == pytest.approx(0.5, rel=1e-14)
    assert sc.pi23 == pytest.approx(25.0 * 3.0 * 1.5, rel=1e-14)
    iso = building_of(sc).isolator
    assert iso.speed_dependent and iso.breakaway == pytest.approx(sc.pi9 * 0.5, rel=1e-14)
    assert iso.level(0.0) == pytest.approx(iso.breakaway, rel=1e-14)
    assert iso.level(1e9) == pytest.approx(sc.pi9, rel=1e-14)


def test_friction_between_the_constant_limits_and_converging_to_them():
    """Pi1 tends to the constant-friction answers at ``Pi9`` as ``Pi23`` grows and at ``Pi9 Pi22`` as it shrinks.

    The slow friction acts over speeds below about ``1/Pi23``: the distance to each limit shrinks
    at least at order 0.8 per decade of the rate (measured: 0.84 and 0.88 towards ``Pi9``, 1.0 towards
    ``Pi9 Pi22``).
    """
    fast = isoslide.solve(_scene(pi9=0.3)).pi1
    slow = isoslide.solve(_scene(pi9=0.15)).pi1
    assert abs(fast - slow) > 0.1 * fast
    high = [abs(isoslide.solve(_scene(pi9=0.3, pi22=0.5, pi23=r)).pi1 - fast) for r in (1e4, 1e5, 1e6)]
    low = [abs(isoslide.solve(_scene(pi9=0.3, pi22=0.5, pi23=r)).pi1 - slow) for r in (1e-1, 1e-2, 1e-3, 1e-4)]
    for seq in (high, low):
        assert all(np.log10(a / b) > 0.8 for a, b in zip(seq, seq[1:], strict=False)), seq
    assert high[-1] < 2e-4 * fast and low[-1] < 2e-5 * slow


def test_a_bearing_creeping_to_its_stick_band_settles_with_the_answer_of_the_long_run():
    """After the pulse the slab creeps towards the edge of its stick band without stopping; the proof ends the run.

    The run that follows the scene to the horizon finds the same Pi1 (within the accuracy target)
    and the bearing still sliding when the settled run stopped.
    """
    sc = _scene(pi2=0.6, pi3=1.5, pi9=0.1, pi22=0.5, pi23=300.0)
    sol = isoslide.solve(sc, history=True)
    assert sol.settled and sol.pi1 > 0.0
    assert sol.history.iso_phase[-1] != 0      # sliding at the stop: settled by the creep proof
    assert sol.tau_end < 10.0
    full = isoslide.solve(sc, settle=False, horizon=20.0)
    assert full.tau_end > 20.0
    assert full.pi1 == pytest.approx(sol.pi1, rel=1e-6)


def test_the_stuck_bearing_reduction_uses_the_breakaway_strength():
    """A bearing stronger than the demand at speed but not at breakaway is integrated, not reduced."""
    strong = _scene(pi9=5.0)
    assert building.reduction(strong)[0] == "bearing-stuck"
    weak_at_rest = _scene(pi9=5.0, pi22=0.1, pi23=10.0)
    assert building.reduction(weak_at_rest)[0] == "general"
    sol = isoslide.solve(weak_at_rest)
    assert sol.model.startswith("sliding-bearing-speed+")


PLANAR = dict(BASE, pulse_y="antisymmetric_ricker", pi14=0.8)
"""The contents and the pendulum under two pulses not along one line: they slide in the plane."""


@pytest.mark.parametrize("kw", [
    dict(pi9=0.2, pi22=0.5, pi23=20.0),
    dict(pi9=0.2, pi22=0.3, pi23=20.0, pi11=0.4, pi12=0.3, pi13=0.02, floor="roof"),
    dict(pi9=0.2, pi22=0.5, pi23=60.0, pi17=0.3, pulse_z="ricker"),
], ids=["rigid", "flexible-roof", "vertical"])
def test_speed_dependent_bearing_in_the_plane_agrees_with_the_planar_reference_peer(kw):
    """The planar kernel and the SciPy planar peer agree to 1e-6 in Pi1, the bearing and the contents both sliding.

    Measured: about 2e-11 to 3e-11 relative on each scene.
    """
    sc = isoslide.Scene(**PLANAR, **kw)
    exact = isoslide.solve(sc, rtol=1e-8, history=True)
    ref = isoslide.solve(sc, method="reference")
    assert exact.model.startswith("sliding-bearing-speed+") and exact.model.endswith("+planar" + (
        "+vertical" if sc.vertical else ""))
    assert exact.pi1 > 0.0 and np.any(exact.history.iso_phase != 0)
    assert exact.pi1 == pytest.approx(ref.pi1, rel=1e-6, abs=1e-12)


def test_constant_bearing_friction_in_the_plane_is_the_constant_strength_to_the_bit():
    """``Pi23 = 0`` is the constant strength ``Pi9 Pi22`` and ``Pi22 = 1`` the constant ``Pi9``, in the plane, for both solvers."""
    zero = isoslide.Scene(**PLANAR, pi9=0.2, pi22=0.5, pi23=0.0)
    low = isoslide.Scene(**PLANAR, pi9=0.2 * 0.5)
    one = isoslide.Scene(**PLANAR, pi9=0.2, pi22=1.0, pi23=50.0)
    high = isoslide.Scene(**PLANAR, pi9=0.2)
    for a, b in ((zero, low), (one, high)):
        ea, eb = isoslide.solve(a), isoslide.solve(b)
        assert ea.pi1 == eb.pi1 > 0.0 and ea.tau_end == eb.tau_end and ea.n_steps == eb.n_steps
        assert ea.model == eb.model == "sliding-bearing+coulomb+planar"
        assert isoslide.solve(a, method="reference").pi1 == isoslide.solve(b, method="reference").pi1


@pytest.mark.parametrize("kw", [
    dict(pi9=0.2, pi22=0.5, pi23=20.0),
    dict(pi9=0.2, pi22=0.5, pi23=20.0, pi11=0.4, pi12=0.3, pi13=0.02, floor="roof"),
    dict(pi9=0.2, pi22=0.5, pi23=20.0, pi17=0.3, pulse_z="ricker"),
], ids=["rigid", "flexible-roof", "vertical"])
def test_speed_dependent_bearing_along_one_line_in_the_plane_is_the_1d_answer(kw):
    """Proportional components (the same shape, ``Pi14 = 0.5``) run in the plane give the 1-D answer along their line.

    The line's amplitude ``sqrt(1 + Pi14^2)`` scales the rate ``Pi23`` as it does ``1/Pi9``
    (measured: 3e-11 relative or less).
    """
    sc = _scene(pulse_y="ricker", pi14=0.5, **kw)
    plane = isoslide.solve(sc, model="full", rtol=1e-8)
    line = isoslide.solve(sc, rtol=1e-8)
    assert plane.model.endswith("+planar" + ("+vertical" if sc.vertical else ""))
    assert "+planar" not in line.model and plane.pi1 > 0.0
    assert plane.pi1 == pytest.approx(line.pi1, rel=1e-6)


def test_a_bearing_creeping_in_the_plane_settles_with_the_answer_of_the_long_run():
    """After the pulses the slab creeps in the plane without stopping; the energy bound ends the run.

    The run that follows the scene to the horizon finds the same Pi1 and the contents stuck from
    the settled run's end on.
    """
    sc = isoslide.Scene(pi2=0.6, pi3=1.5, pi8=0.01, pi9=0.1, pi22=0.5, pi23=300.0, pulse_y="antisymmetric_ricker",
                        pi14=0.8)
    sol = isoslide.solve(sc, history=True)
    assert sol.settled and sol.pi1 > 0.0
    assert sol.history.iso_phase[-1] != 0      # sliding at the stop: settled by the energy bound
    full = isoslide.solve(sc, settle=False, horizon=20.0, history=True)
    assert full.tau_end > 20.0
    assert full.pi1 == pytest.approx(sol.pi1, rel=1e-6)
    assert np.all(full.history.phase[full.history.tau >= sol.tau_end] == 0)


@pytest.mark.parametrize("kw, match", [
    (dict(mu_slow=0.2), r"mu_slow = 0\.2 is out of range; allowed range: 0 < value <= 0\.1"),
    (dict(mu_slow=0.0, rate=5.0), r"mu_slow = 0\.0 is out of range"),
    (dict(mu_slow=0.05, rate=-1.0), r"rate = -1\.0 is out of range; allowed range: 0 <= value < inf"),
    (dict(rate=5.0), r"rate = 5\.0 is given without mu_slow"),
])
def test_friction_pendulum_refuses_a_law_it_cannot_represent(kw, match):
    with pytest.raises(ValueError, match=match):
        isoslide.friction_pendulum(2.0, 0.1, 1e6, **kw)


def test_from_physical_refuses_a_breakaway_strength_without_a_sliding_bearing():
    kw = dict(a_p=3.0, T_p=1.0, M_b=1e6, T_b=2.0, xi_b=0.1, m_ec=1e3, mu_s=0.3, mu_k=0.3)
    with pytest.raises(ValueError, match=r"Q_slow = 1000\.0 is given without a sliding bearing"):
        isoslide.Scene.from_physical(**kw, Q_slow=1e3, rate=5.0)
    with pytest.raises(ValueError, match=r"Q_slow = 3000\.0 is out of range; allowed range: 0 < value <= 2000"):
        isoslide.Scene.from_physical(**kw, Q_d=2e3, Q_slow=3e3, rate=5.0)


@pytest.mark.parametrize("name, value", [("pi22", 0.0), ("pi22", 1.5), ("pi23", -1.0)])
def test_scene_refuses_bearing_groups_out_of_range(name, value):
    with pytest.raises(ValueError, match=rf"{name} = {value!r} is out of range"):
        _scene(pi9=0.1, **{name: value})


@pytest.mark.parametrize("kw", [
    dict(pi9=0.3, pi22=0.5, pi23=20.0),
    dict(pi9=0.2, pi22=0.5, pi23=200.0),
    dict(pi9=0.1, pi22=0.4, pi23=50.0, pi3=3.0, pi4=0.05),
    dict(pi9=0.2, pi22=0.5, pi23=5.0, pi11=0.4, pi12=0.3, pi13=0.05, floor="roof"),
    dict(pi9=0.2, pi22=0.5, pi23=60.0, pi17=0.4, pulse_z="ricker"),
])
def test_speed_dependent_bearing_agrees_with_the_reference_peer(kw):
    """The compiled solver and the SciPy event-driven peer agree to 1e-6 in Pi1 (rigid, flexible roof, vertical)."""
    sc = _scene(**kw)
    exact = isoslide.solve(sc, rtol=1e-8)
    ref = solve_reference_building(sc, rtol=1e-11)
    assert exact.pi1 > 0.0
    assert exact.pi1 == pytest.approx(ref.pi1, rel=1e-6, abs=1e-12)
