"""Vertical ground motion acting through the normal forces (Pi17, pulse_z) in the exact solver."""

import numpy as np
import pytest

from isoslide import Scene, solve
from isoslide.pulses import sampled

PLATEAU = 2001
"""Samples of a constant vertical acceleration from tau = -3 to 47 (longer than any response here)."""


def _constant(sign: float):
    return sampled(sign * np.ones(PLATEAU), 0.025, tau0=-3.0, name="constant")


SCENES = {
    "fixed base, Coulomb": (dict(pi2=0.15, pi3=0.0), lambda n: dict(pi2=0.15 * n, pi3=0.0)),
    "linear isolator, Coulomb": (dict(pi2=0.15, pi3=2.0, pi4=0.1, pi8=0.01),
                                 lambda n: dict(pi2=0.15 * n, pi3=2.0, pi4=0.1, pi8=0.01)),
    "linear isolator, Stribeck": (dict(pi2=0.15, pi3=2.0, pi4=0.1, pi8=0.01, pi5=0.7, pi6=300.0, pi7=0.2),
                                  lambda n: dict(pi2=0.15 * n, pi3=2.0, pi4=0.1, pi8=0.01, pi5=0.7, pi6=300.0,
                                                 pi7=0.2 * n)),
    # a friction pendulum's strength and stiffness both scale with its normal force
    "friction pendulum": (dict(pi2=0.15, pi3=2.0, pi4=0.1, pi8=0.01, pi9=0.05),
                          lambda n: dict(pi2=0.15 * n, pi3=2.0 / np.sqrt(n), pi4=0.1 / np.sqrt(n), pi8=0.01,
                                         pi9=0.05 * n)),
    "lead-rubber bearing, flexible, roof": (
        dict(pi2=0.15, pi3=2.0, pi4=0.1, pi8=0.01, pi9=0.08, pi10=0.01, pi11=0.5, pi12=0.3, pi13=0.05, floor="roof"),
        lambda n: dict(pi2=0.15 * n, pi3=2.0, pi4=0.1, pi8=0.01, pi9=0.08, pi10=0.01, pi11=0.5, pi12=0.3,
                       pi13=0.05, floor="roof")),
}


@pytest.mark.parametrize("c", [0.3, -0.3])
@pytest.mark.parametrize("name", SCENES)
def test_a_constant_vertical_acceleration_equals_scaled_friction(name, c):
    """N = m g (1 + c) throughout: the contents' friction levels (and a pendulum's strength and
    stiffness) scale by 1 + c, which is the scene without vertical motion and scaled groups."""
    kw, scaled = SCENES[name]
    vertical = solve(Scene(**kw, pi17=abs(c), pulse_z=_constant(np.sign(c))))
    plain = solve(Scene(**scaled(1.0 + c)))
    assert vertical.pi1 > 0.0 and vertical.settled
    assert vertical.pi1 == pytest.approx(plain.pi1, rel=1e-7)
    assert vertical.facets.vertical == "normal-force" and plain.facets.vertical == "none"


def test_an_upward_acceleration_holds_the_contents_harder_and_a_downward_one_lets_them_slide():
    """Where Pi1 falls with the friction (a fixed base at Pi2 = 0.4 under the Ricker pulse), more normal
    force means less sliding; at lower Pi2 a Ricker pulse's two lobes make Pi1 rise with friction."""
    kw = dict(pi2=0.4, pi3=0.0)
    up = solve(Scene(**kw, pi17=0.5, pulse_z=_constant(1.0))).pi1
    none = solve(Scene(**kw)).pi1
    down = solve(Scene(**kw, pi17=0.5, pulse_z=_constant(-1.0))).pi1
    assert up < none < down


def test_pi17_zero_is_the_scene_without_vertical_motion():
    kw = dict(pi2=0.15, pi3=2.0, pi4=0.1, pi8=0.01, pi9=0.05)
    a, b = solve(Scene(**kw)), solve(Scene(**kw, pi17=0.0, pulse_z="ricker"))
    assert (a.pi1, a.n_steps, a.model) == (b.pi1, b.n_steps, b.model)


def test_a_vertical_pulse_converges_to_no_vertical_motion_as_pi17_vanishes():
    kw = dict(pi2=0.15, pi3=2.0, pi4=0.1, pi8=0.01, pi5=0.7, pi6=300.0)
    base = solve(Scene(**kw)).pi1
    gaps = [abs(solve(Scene(**kw, pi17=a, pulse_z="ricker")).pi1 - base) for a in (1e-2, 1e-3, 1e-4)]
    assert gaps[0] > gaps[1] > gaps[2] and gaps[2] < 1e-4 * base


def test_lift_off_is_refused_naming_the_time_and_the_value():
    with pytest.raises(ValueError, match=r"pi17 = 3.0 lifts the contents off .* reaches 0 at tau = -?\d"):
        Scene(pi2=0.2, pi3=1.0, pi17=3.0, pulse_z="ricker")
    with pytest.raises(ValueError, match=r"pulse_z = None with pi17 = 0.5"):
        Scene(pi2=0.2, pi3=1.0, pi17=0.5)


def test_a_peer_without_vertical_motion_refuses_it():
    with pytest.raises(ValueError, match="method = 'regularized' does not model vertical ground motion"):
        solve(Scene(pi2=0.2, pi3=1.0, pi17=0.3, pulse_z="ricker"), method="regularized")


def test_from_physical_takes_the_vertical_amplitude_in_si():
    sc = Scene.from_physical(a_p=6.0, T_p=1.2, M_b=8e5, T_b=2.4, xi_b=0.1, m_ec=800.0, mu_s=0.25, mu_k=0.2,
                             a_pz=4.0, pulse_z="ricker")
    assert sc.pi17 == pytest.approx(4.0 / 9.80665) and sc.vertical and not sc.paper_model
