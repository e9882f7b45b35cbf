"""Tests of the rocking block in the general building with two-way coupling (isoslide.peers.rocking_building):
its sliding limit against the building's peer, its light-block limit against the one-way block peer, the
energy balance of the coupled system, mirror symmetry and refusals."""

import dataclasses

import numpy as np
import pytest

from isoslide import Scene
from isoslide.model.rocking import Block
from isoslide.peers.reference_building import default_horizon, excitation_end, solve_reference_building
from isoslide.peers.rocking_building import block_of, solve
from isoslide.peers.slide_rock import solve_block
from isoslide.pulses import get_pulse
from rocking_cases import rectangular, ricker  # tests/ is on sys.path

# ------------------------------------------------------------------------------------------ sliding limit


@pytest.mark.parametrize("isolator", [dict(pi3=2.0, pi4=0.1, pi8=0.3, pi2=0.3),
                                      dict(pi3=3.0, pi4=0.05, pi8=0.2, pi2=0.15, pi5=0.8, pi9=0.08)],
                         ids=["linear", "sliding bearing"])
def test_block_that_cannot_rock_slides_as_in_the_building_peer(isolator):
    """With mu_s <= tan(alpha) (here 0.3 and 0.1875 against tan(alpha) = 0.5) the block never rocks:
    on a rigid isolated building (linear isolator; sliding bearing with stick) its Pi1 is the building
    peer's for the same scene without Pi18 to 1e-9 relative, theta stays 0 and the modes are rest and
    slide."""
    shape = dict(pi18=0.5, pi19=1.0, pi21=2.0)          # G = g/a_p = 1
    scene = Scene(**isolator, **shape)
    assert block_of(scene).mu_s <= 0.5
    ref = solve_reference_building(Scene(**isolator), rtol=1e-12, atol=1e-15)
    res = solve(scene, rtol=1e-12, atol=1e-15)
    assert ref.pi1 > 1e-4
    assert abs(res.pi1 - ref.pi1) <= 1e-9 * ref.pi1
    assert res.theta_max == 0.0 and res.impacts == 0 and not res.overturned
    assert res.modes == ("rest", "slide")


# ------------------------------------------------------------------------------------------ light block

G_SI = 9.81        # m/s^2
B_HALF, H_HALF = 0.2, 1.0    # m: tan(alpha) = 0.2, R = 1.02 m, p = 2.69 rad/s
T_P = 0.4          # s: Pi19 = p T_p = 1.07


def _light_block_scene(pulse, pi21, mu):
    """A 1 mg block in a 1000 t fixed-base building (Pi8 = 1e-9), built from SI values."""
    a_p = pi21 * G_SI * B_HALF / H_HALF
    scene = Scene.from_physical(a_p=a_p, T_p=T_P, M_b=1e6, T_b=0.0, xi_b=0.0, m_ec=1e-3, mu_s=mu, mu_k=mu, g=G_SI,
                                pulse=pulse, b=B_HALF, h=H_HALF)
    return scene, a_p


def _one_way(scene, a_p, mu):
    """slide_rock.solve_block on the ground motion of the scene, in SI units."""
    floor = (ricker if scene.pulse.name == "ricker" else rectangular)(a_p, T_P)
    return solve_block(Block(B_HALF, H_HALF), floor, default_horizon(scene) * T_P, mu_s=mu, mu_k=mu, g=G_SI,
                       t0=scene.pulse.tau_start * T_P, t_quiet=excitation_end(scene) * T_P,
                       breakpoints=[b * T_P for b in scene.pulse.breakpoint_array])


@pytest.mark.parametrize("pulse,pi21,mu,expect", [("ricker", 3.0, 1.0, "rock"),
                                                  ("rectangular", 2.0, 1.0, "overturn"),
                                                  ("ricker", 3.0, 0.23, "slide-rock")])
def test_light_block_on_a_fixed_base_matches_the_one_way_peer(pulse, pi21, mu, expect):
    """With Pi8 = 1e-9 on a fixed base the floor is the ground: the peer agrees with slide_rock.solve_block
    driven by the ground motion in SI units in theta_max (1e-6 relative), in overturning and its time, in
    the number of impacts, and for slide-rock in the peak slide Pi1 a_p T_p^2 (1e-6 relative)."""
    scene, a_p = _light_block_scene(pulse, pi21, mu)
    assert scene.pi8 == pytest.approx(1e-9) and scene.pi3 == 0.0
    res = solve(scene)
    one = _one_way(scene, a_p, mu)
    assert res.overturned == one.overturned == (expect == "overturn")
    assert abs(res.theta_max - one.theta_max) <= 1e-6 * one.theta_max
    assert res.impacts == one.n_impacts
    if expect == "overturn":
        assert abs(res.t_overturn * T_P - one.t_overturn) <= 1e-6 * abs(one.t_overturn)
    else:
        assert 0.01 < res.theta_max < block_of(scene).alpha
        assert res.impacts > 10
    visited = {name for _, name, _ in one.modes}
    assert ("slide-rock" in res.modes) == ("slide-rock" in visited) == (expect == "slide-rock")
    if expect == "slide-rock":
        u_one = one.u_max / (a_p * T_P ** 2)
        assert u_one > 1e-3
        assert abs(res.pi1 - u_one) <= 1e-6 * u_one
    else:
        assert res.pi1 == one.u_max == 0.0


# ------------------------------------------------------------------------------------------ coupling

COUPLED = dict(pi3=1.0, pi4=0.05, pi18=0.2, pi19=1.0, pi21=3.0, pi2=0.23 / (0.2 * 3.0))   # mu_s = 0.23


def test_heavy_block_on_an_isolated_base_balances_energy_and_changes_the_response():
    """Pi8 = 0.5 on a rigid linearly isolated base, through rest, rock and slide-rock with impacts: at every
    recorded time the ground's work equals kinetic + potential energy + viscous, friction and impact losses
    to 1e-8 of the largest work (a block whose reaction on the slab were wrong would break it), and the
    response differs from that of a light block (Pi8 = 1e-9) by more than 3 % in theta_max and Pi1."""
    res = solve(Scene(pi8=0.5, **COUPLED))
    h = res.history
    assert set(res.modes) == {"rest", "rock", "slide-rock"} and res.impacts > 10 and not res.overturned
    loss = h.viscous + h.isolator + h.friction + h.impact
    imbalance = h.work - (h.kinetic + h.potential + loss)
    scale = np.max(np.abs(h.work))
    assert np.max(np.abs(imbalance)) <= 1e-8 * scale
    assert h.friction[-1] > 1e-3 * scale and h.impact[-1] > 1e-3 * scale
    light = solve(Scene(pi8=1e-9, **COUPLED))
    assert abs(res.theta_max - light.theta_max) > 0.03 * light.theta_max
    assert abs(res.pi1 - light.pi1) > 0.03 * light.pi1


def test_negated_pulse_mirrors_the_response_bit_for_bit():
    """The antisymmetric Ricker pulse and its negative (Pi8 = 0.5, isolated base, slide-rock): the same times,
    modes and impacts, and theta, u and the slab's displacement negated, bit for bit."""
    pulse = get_pulse("antisymmetric_ricker")
    negative = dataclasses.replace(pulse, params=tuple(-v for v in pulse.params))
    a = solve(Scene(pi8=0.5, pulse=pulse, **COUPLED))
    b = solve(Scene(pi8=0.5, pulse=negative, **COUPLED))
    assert a.theta_max > 0.01 and a.pi1 > 0.01 and "slide-rock" in a.modes
    assert (a.theta_max, a.pi1, a.impacts, a.modes) == (b.theta_max, b.pi1, b.impacts, b.modes)
    ha, hb = a.history, b.history
    assert np.array_equal(ha.tau, hb.tau) and np.array_equal(ha.mode, hb.mode)
    for name in ("theta", "omega", "u", "ud", "x", "xd"):
        assert np.array_equal(getattr(ha, name), -getattr(hb, name)), name
    assert np.max(np.abs(ha.theta)) == pytest.approx(a.theta_max, rel=1e-12)


# ------------------------------------------------------------------------------------------ refusals

@pytest.mark.parametrize("group", ["pi6", "pi7"])
def test_stribeck_friction_with_a_rocking_block_is_refused_naming_the_group(group):
    """A Stribeck law (Pi6 > 0 or Pi7 > 0) with a rocking block, set on a scene past its own checks, is refused
    by the peer with a ValueError naming the group and its value."""
    scene = Scene(pi2=1.0, pi3=2.0, pi18=0.2, pi19=1.0, pi21=3.0)
    object.__setattr__(scene, group, 0.5)
    with pytest.raises(ValueError, match=rf"^{group} = 0\.5 > 0 with a rocking block"):
        solve(scene)


def test_scene_without_a_rocking_block_is_refused_naming_pi18():
    """Contents that only slide (Pi18 = None) are refused with a ValueError naming pi18."""
    with pytest.raises(ValueError, match="pi18"):
        solve(Scene(pi2=0.3, pi3=2.0))
