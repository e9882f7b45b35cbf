"""Tests of the planar SciPy reference peer (isoslide.peers.reference_planar), on its own.

Contents sliding in the plane of the floor: the one-dimensional reference peer recovered under a
one-dimensional excitation, equivariance under a turn of the excitation, closed forms (a constant
ground acceleration, the steady orbit under a circular translation of the floor), vertical ground
motion through the normal force, and the inputs the peer refuses.
"""

import dataclasses
import math

import numpy as np
import pytest

import isoslide
from isoslide import Scene
from isoslide.peers.reference_planar import (
    SLOW_SPEED,
    planar_building,
    planar_excitation,
    run_planar,
    solve_reference_planar,
)
from isoslide.pulses import makris_cn, sampled

FIXED = dict(pi2=0.15, pi3=0.0)
LINEAR = dict(pi2=0.15, pi3=2.0, pi4=0.1, pi8=0.3)
STOREYS = dict(pi2=0.15, pi3=2.0, pi4=0.1, pi8=0.05, pi11=0.5, pi12=0.3, pi13=0.05, storeys=3, floor=2)
PLANAR = dict(pulse_y="antisymmetric_ricker", pi14=0.7, pi15=1.3, pi16=-0.2)
"""A second horizontal component that makes the contents slide along a curve."""
FRICTION_PENDULUM = dict(pi2=0.1, pi3=2.0, pi4=0.05, pi9=0.12, pi8=0.2)
"""A sliding bearing (friction pendulum) under the slab, the contents on the slab acting back on it."""
FLEXIBLE_ROOF = dict(pi11=0.5, pi12=0.3, pi13=0.05, floor="roof")


def _angle_difference(a: float, b: float) -> float:
    """``a - b`` wrapped into ``(-pi, pi]`` (radians)."""
    return math.remainder(a - b, 2.0 * math.pi)


@pytest.mark.parametrize("kw", [FIXED, LINEAR, STOREYS], ids=["fixed base", "linear base, Pi8 = 0.3",
                                                              "three storeys, floor 2"])
def test_a_one_dimensional_excitation_gives_the_one_dimensional_reference(kw):
    """Under the main pulse alone along x, Pi1 equals the 1-D reference peer's
    (``method="reference"``) within 1e-7 relative, the run settles, and the peak lies on the x axis
    (``peak_angle`` 0 or pi)."""
    scene = Scene(**kw)
    ref = isoslide.solve(scene, method="reference")
    res = solve_reference_planar(scene)
    assert ref.pi1 > 0.01
    assert res.settled
    assert res.pi1 == pytest.approx(ref.pi1, rel=1e-7)
    assert min(abs(_angle_difference(res.peak_angle, 0.0)), abs(_angle_difference(res.peak_angle, math.pi))) < 1e-9
    assert res.tau_peak == pytest.approx(ref.tau_peak, abs=1e-6)


@pytest.mark.parametrize("kw", [FIXED, LINEAR, dict(FIXED, **PLANAR), dict(LINEAR, **PLANAR),
                                dict(FRICTION_PENDULUM, pi8=0.3, **PLANAR)],
                         ids=["fixed base", "linear base", "fixed base, planar", "linear base, planar",
                              "friction pendulum, planar"])
def test_turning_the_excitation_turns_the_answer(kw):
    """``angle = 0.7`` leaves Pi1 unchanged (1e-8 relative) and turns ``peak_angle`` by 0.7 rad, for
    an excitation along one line and for one that makes the contents slide along a curve (the
    buildings, the friction pendulum too, are isotropic)."""
    base = solve_reference_planar(Scene(**kw))
    turned = solve_reference_planar(Scene(**kw, angle=0.7))
    assert base.pi1 > 0.01
    assert turned.pi1 == pytest.approx(base.pi1, rel=1e-8)
    assert abs(_angle_difference(turned.peak_angle, base.peak_angle + 0.7)) < 1e-7


def test_a_curved_path_is_not_the_sum_of_its_components():
    """With two components the peak is off both axes and differs from each component's 1-D peak
    (so the coupling of the axes through the friction force is exercised)."""
    scene = Scene(**FIXED, **PLANAR)
    res = solve_reference_planar(scene)
    x_alone = solve_reference_planar(Scene(**FIXED))
    assert res.settled
    assert min(abs(math.sin(res.peak_angle)), abs(math.cos(res.peak_angle))) > 0.05
    assert abs(res.pi1 - x_alone.pi1) > 1e-3 * x_alone.pi1


def _rectangular_pair(a_y: float) -> dict:
    """A constant ground acceleration ``(1, a_y)`` over ``0 <= tau < 1`` (two rectangular pulses)."""
    return dict(pulse="rectangular", pulse_y="rectangular", pi14=a_y)


@pytest.mark.parametrize("angle", [0.0, 2.0])
def test_a_constant_ground_acceleration_slides_the_block_straight_back(angle):
    """On a fixed base a constant ground acceleration ``G`` over one ``T_p`` slides the block along
    ``-G`` at the rate ``|G| - Pi2``, then it stops under ``Pi2``: the closed form
    ``Pi1 = (|G| - Pi2)/2 + (|G| - Pi2)**2/(2 Pi2)`` at the angle of ``-G``."""
    pi2, a_y = 0.3, 0.5
    res = solve_reference_planar(Scene(pi2=pi2, pi3=0.0, angle=angle, **_rectangular_pair(a_y)))
    g = math.hypot(1.0, a_y)
    exact = (g - pi2) / 2.0 + (g - pi2) ** 2 / (2.0 * pi2)
    assert res.settled
    assert res.pi1 == pytest.approx(exact, rel=1e-10)
    assert res.tau_peak == pytest.approx(1.0 + (g - pi2) / pi2, rel=1e-10)
    assert abs(_angle_difference(res.peak_angle, math.atan2(-a_y, -1.0) + angle)) < 1e-10
    assert res.pi1_residual == pytest.approx(res.pi1, rel=1e-12)


def _circular_translation(n: int, pi2: float) -> Scene:
    """A fixed-base floor translated on a circle: ground acceleration ``(cos 2 pi tau, sin 2 pi tau)``
    over ``0 <= tau < n`` (Makris type-Cn pulses with the phases 0 and ``-pi/2``), so the ground
    displacement's circular part has the radius ``A = 1/(2 pi)**2``."""
    cn = makris_cn(n)
    x = dataclasses.replace(cn, params=(0.0, float(n), float(n)), tau_end=float(n), breakpoints=(0.0, float(n)))
    y = dataclasses.replace(x, params=(-0.5 * math.pi, float(n), float(n)))
    return Scene(pi2=pi2, pi3=0.0, pulse=x, pulse_y=y, pi14=1.0, pi15=1.0, pi16=0.0)


def test_a_circular_translation_drives_the_steady_orbit():
    """Under a circular translation of amplitude ``A`` at ``w = 2 pi`` rad per ``T_p`` the contents
    slide for ever on a relative orbit of radius ``rho = sqrt(A**2 - (Pi2/w**2)**2)`` at the speed
    ``w rho``, turning the ground's way: after nine periods (the transient decays like
    ``exp(-Pi2 tau/(2 w rho))``, to ~1e-10 by then) both within 1e-8 relative, 20 % away from the
    frictionless radius ``A``."""
    n, pi2 = 10, 0.6
    scene = _circular_translation(n, pi2)
    w = 2.0 * math.pi
    amp = 1.0 / w**2
    rho = math.sqrt(amp**2 - (pi2 / w**2) ** 2)
    ts = np.linspace(n - 1.0, n - 0.5, 11)
    run = run_planar(scene, horizon=0.0, samples=np.concatenate([ts, ts + 0.5]))
    assert run.tau.size == 2 * ts.size
    assert run.result.n_events == 1 and run.result.tau_end == pytest.approx(n)   # one breakaway, no stop
    across = run.u[:, :ts.size] - run.u[:, ts.size:]     # u(t) - u(t + 1/2): the orbit's diameter
    radius = 0.5 * np.hypot(*across)
    speed = np.hypot(*run.w)
    assert abs(rho - amp) > 0.1 * amp
    np.testing.assert_allclose(radius, rho, rtol=1e-8)
    np.testing.assert_allclose(speed, w * rho, rtol=1e-8)
    turning = across[0] * run.w[1, :ts.size] - across[1] * run.w[0, :ts.size]
    np.testing.assert_allclose(turning, 2.0 * w * rho**2, rtol=1e-7)   # counter-clockwise, as the ground


def _constant_vertical(level: float) -> object:
    """A vertical pulse shape equal to ``level`` from tau = -3 to 9 (past the Ricker's end)."""
    return sampled([level, level], dtau=12.0, tau0=-3.0, name="constant")


@pytest.mark.parametrize("kw", [dict(FIXED, **PLANAR), dict(LINEAR, pi4=0.3, **PLANAR)],
                         ids=["fixed base", "linear base"])
@pytest.mark.parametrize("level, pi17", [(1.0, 0.5), (-1.0, 0.4)], ids=["upward", "downward"])
def test_a_constant_vertical_acceleration_scales_the_friction(kw, level, pi17):
    """A constant normal-force factor ``nz = 1 + Pi17 p_z`` over the whole response is Coulomb
    friction ``nz Pi2``: the same Pi1 and peak angle (1e-8), smaller for an upward ground
    acceleration (more friction) and larger for a downward one."""
    nz = 1.0 + pi17 * level
    vertical = solve_reference_planar(Scene(**kw, pi17=pi17, pulse_z=_constant_vertical(level)))
    scaled = solve_reference_planar(Scene(**dict(kw, pi2=kw["pi2"] * nz)))
    plain = solve_reference_planar(Scene(**kw))
    assert vertical.settled and scaled.settled
    assert vertical.pi1 == pytest.approx(scaled.pi1, rel=1e-8)
    assert abs(_angle_difference(vertical.peak_angle, scaled.peak_angle)) < 1e-8
    assert (vertical.pi1 < 0.95 * plain.pi1) if level > 0 else (vertical.pi1 > 1.05 * plain.pi1)


@pytest.mark.parametrize("kw", [dict(FIXED, pi17=0.5, pulse_z="ricker"),
                                dict(LINEAR, pi17=0.6, pulse_z="antisymmetric_ricker")],
                         ids=["fixed base, Ricker", "linear base, antisymmetric Ricker"])
def test_a_vertical_pulse_agrees_with_the_one_dimensional_reference(kw):
    """Under a time-varying vertical pulse and a one-dimensional horizontal one, Pi1 equals the 1-D
    reference peer's within 1e-7 relative, and differs from the scene without vertical motion."""
    scene = Scene(**kw)
    ref = isoslide.solve(scene, method="reference")
    res = solve_reference_planar(scene)
    plain = solve_reference_planar(Scene(**{k: v for k, v in kw.items() if k not in ("pi17", "pulse_z")}))
    assert res.pi1 == pytest.approx(ref.pi1, rel=1e-7)
    assert abs(res.pi1 - plain.pi1) > 1e-3 * plain.pi1


def test_the_ground_is_the_scenes():
    """The peer's ground acceleration equals ``Scene.ground`` (second component shifted, stretched,
    scaled, both turned) away from the pulses' breakpoints, and its normal-force factor is
    ``1 + Pi17 p_z``."""
    scene = Scene(**LINEAR, **PLANAR, angle=-1.1, pi17=0.3, pulse_z="ricker")
    ex = planar_excitation(scene)
    taus = np.linspace(-3.4, 3.4, 157) + 1e-3
    gx, gy = scene.ground(taus)
    mine = np.array([ex.ground(t) for t in taus]).T
    np.testing.assert_allclose(mine[0], gx, rtol=0, atol=1e-14)
    np.testing.assert_allclose(mine[1], gy, rtol=0, atol=1e-14)
    nz = np.array([ex.window(t, t + 1.0)[1](t) for t in taus])
    np.testing.assert_allclose(nz, 1.0 + 0.3 * scene.pulse_z.accel(taus), rtol=0, atol=1e-14)
    assert ex.tau_start == pytest.approx(min(-2.0, -0.2 - 1.3 * 2.5))
    assert ex.tau_end == pytest.approx(max(2.0, -0.2 + 1.3 * 2.5))


def test_the_building_matches_the_shear_chain():
    """The flexible building's stuck matrices have the isolation period on the slab alone and the
    fixed-base fundamental period on the floors alone (slab held), the masses sum to ``M_b``."""
    B = planar_building(Scene(**STOREYS))
    assert B.masses.sum() == pytest.approx(1.0)
    assert B.k == 2
    lam = np.linalg.eigvalsh(B.K[1:, 1:] / np.sqrt(np.outer(B.masses[1:], B.masses[1:])))
    assert 2.0 * math.pi / math.sqrt(lam[0]) == pytest.approx(0.3, rel=1e-12)
    kd = B.K.sum()   # the storeys' forces cancel in a rigid translation
    assert 2.0 * math.pi / math.sqrt(kd) == pytest.approx(2.0, rel=1e-12)
    fixed = planar_building(Scene(**FIXED))
    assert fixed.nd == 0 and fixed.k == -1


@pytest.mark.parametrize("scene, horizon", [
    (Scene(**dict(LINEAR, pi4=0.05), **PLANAR), 15.0),
    (Scene(**dict(FRICTION_PENDULUM, pi2=0.15, pi3=3.0, pi4=0.0, pi9=0.05, pi8=0.1, **FLEXIBLE_ROOF),
           pulse="ricker", pulse_y="antisymmetric_ricker", pi14=0.8), 5.0),
], ids=["lightly damped isolator", "held friction pendulum, contents on the roof"])
def test_no_slip_follows_settlement(scene, horizon):
    """A planar scene settles after its pulses while the building still moves (a lightly damped
    isolator; a friction pendulum held under a flexible superstructure, by the bounds of the bearing's
    need and of the roof's acceleration); followed on to ``horizon`` isolation periods past the pulses
    without the settlement test, it has the same transitions, Pi1 and final displacement (the bound
    that stopped it was safe)."""
    settled = run_planar(scene).result
    followed = run_planar(scene, settle=False, horizon=horizon).result
    end = planar_excitation(scene).tau_end
    assert settled.settled and not followed.settled
    assert end < settled.tau_end < followed.tau_end == pytest.approx(end + horizon * scene.pi3)
    assert followed.n_events == settled.n_events
    assert followed.pi1 == settled.pi1
    assert followed.pi1_residual == settled.pi1_residual


def test_a_slow_slip_is_insensitive_to_the_slaved_speed(monkeypatch):
    """Pi1 of a planar scene with slow slips (breakaways at the stick limit) changes by less than
    1e-10 relative when the speed below which slips run slaved goes from 1e-8 to 1e-10."""
    import isoslide.peers.reference_planar as peer

    scene = Scene(**LINEAR, **PLANAR)
    base = solve_reference_planar(scene)
    monkeypatch.setattr(peer, "SLOW_SPEED", SLOW_SPEED / 100.0)
    lower = solve_reference_planar(scene)
    assert base.n_events >= 2
    assert lower.pi1 == pytest.approx(base.pi1, rel=1e-10)


VERTICAL = dict(pi17=0.4, pulse_z="ricker")


def _one_dimensional_peak(scene: Scene) -> tuple:
    """``(Pi1, tau_peak, the direction of the peak)`` of the 1-D reference peer (``method="reference"``);
    the direction, 0 or pi, from the sign of ``u`` at its largest, and whether the bearing slid."""
    ref = isoslide.solve(scene, method="reference", history=True)
    h = ref.history
    i = int(np.argmax(np.abs(h.u)))
    return ref.pi1, ref.tau_peak, (0.0 if h.u[i] > 0.0 else math.pi), bool(np.any(h.iso_phase != 0))


@pytest.mark.parametrize("kw", [FRICTION_PENDULUM, dict(FRICTION_PENDULUM, pi8=0.0),
                                dict(FRICTION_PENDULUM, pi2=0.15, pi9=0.08, **FLEXIBLE_ROOF),
                                dict(FRICTION_PENDULUM, pi2=0.15, pi9=0.08, pi11=0.5, pi12=0.3, pi13=0.05),
                                dict(FRICTION_PENDULUM, pi2=0.12, pi3=2.5, pi9=0.06, pi5=0.7, pi6=20.0, **VERTICAL)],
                         ids=["rigid, two-way", "rigid, one-way", "flexible, roof", "flexible, slab",
                              "vertical, Stribeck"])
def test_a_friction_pendulum_along_a_line_gives_the_one_dimensional_reference(kw):
    """A sliding bearing under the main pulse alone, turned by 0.6 rad: Pi1 equals the 1-D reference
    peer's (which models the bearing with true stick) within 1e-7 relative, at the same time, and the
    peak's direction is the 1-D one turned by 0.6 rad; both interfaces slide and stick."""
    pi1, tau_peak, angle, slid = _one_dimensional_peak(Scene(**kw))
    res = solve_reference_planar(Scene(**kw, angle=0.6))
    assert slid and pi1 > 0.01
    assert res.settled
    assert res.pi1 == pytest.approx(pi1, rel=1e-7)
    assert res.tau_peak == pytest.approx(tau_peak, abs=1e-6)
    assert abs(_angle_difference(res.peak_angle, angle + 0.6)) < 1e-7


@pytest.mark.parametrize("kw, chosen", [
    (dict(pi2=0.055, pi3=2.9, pi4=0.05, pi9=0.17, pi8=0.3, pulse="makris_b"), ((0, 0), (1, 1))),
    (dict(pi2=0.035, pi3=2.85, pi4=0.0, pi9=0.25, pi8=1.0, pulse="antisymmetric_ricker"), ((0, 0), (1, 0))),
], ids=["both start", "the contents start, the bearing held"])
def test_the_modes_at_rest_are_chosen_together(monkeypatch, kw, chosen):
    """Scenes where both interfaces are at rest and the first consistent joint mode has the contents
    sliding (a pulse that starts with a jump: both start at once; a bearing that stops while the
    contents are stuck on the slab: they slide off on the held slab): along a line, 0.6 rad from x,
    Pi1 equals the 1-D reference peer's within 1e-7 relative."""
    import isoslide.peers.reference_planar as peer

    seen = []
    choose = peer._Planar.choose

    def recording(self, *args):
        out = choose(self, *args)
        seen.append((tuple(args[3]), tuple(out)))
        return out

    monkeypatch.setattr(peer._Planar, "choose", recording)
    pi1, _, angle, slid = _one_dimensional_peak(Scene(**kw))
    res = solve_reference_planar(Scene(**kw, angle=0.6))
    assert chosen in seen and slid
    assert res.pi1 == pytest.approx(pi1, rel=1e-7)
    assert abs(_angle_difference(res.peak_angle, angle + 0.6)) < 1e-7


@pytest.mark.parametrize("kw", [dict(FRICTION_PENDULUM, pi8=0.3),
                                dict(FRICTION_PENDULUM, pi2=0.15, pi3=3.0, pi4=0.0, pi9=0.05, pi8=0.1, **FLEXIBLE_ROOF),
                                dict(FRICTION_PENDULUM, pi2=0.12, pi3=2.5, pi9=0.06, pi5=0.7, pi6=20.0, **VERTICAL)],
                         ids=["rigid, two-way", "flexible, roof", "vertical, Stribeck"])
def test_a_planar_friction_pendulum_agrees_with_the_exact_solver(kw):
    """A Ricker along x and an antisymmetric Ricker along y (``Pi14 = 0.8``) on a friction pendulum:
    Pi1 and the peak's direction agree with the compiled planar kernel's (``isoslide.solve``) within
    1e-6, and the bearing slid."""
    scene = Scene(**kw, pulse="ricker", pulse_y="antisymmetric_ricker", pi14=0.8)
    assert scene.planar
    exact = isoslide.solve(scene, history=True)
    res = solve_reference_planar(scene)
    assert np.any(exact.history.iso_phase != 0)
    assert exact.pi1 > 0.01 and res.settled
    assert res.pi1 == pytest.approx(exact.pi1, rel=1e-6)
    assert abs(_angle_difference(res.peak_angle, exact.peak_angle)) < 1e-6
    assert res.tau_peak == pytest.approx(exact.tau_peak, abs=1e-5)


def test_history_and_a_negative_horizon_are_refused():
    """``history=True`` and a negative ``horizon`` raise a ValueError naming them."""
    with pytest.raises(ValueError, match="history"):
        solve_reference_planar(Scene(**FIXED), history=True)
    with pytest.raises(ValueError, match="horizon"):
        solve_reference_planar(Scene(**FIXED), horizon=-1.0)
