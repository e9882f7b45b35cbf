"""The triple friction pendulum in the plane whose friction rises with speed (isoslide.engine.tfp_plane)."""

import math

import numpy as np
import pytest

from isoslide import Scene, solve
from isoslide.engine import tfp_flow, tfp_plane

SPEED_TFP = dict(pi2=0.3, pi3=2.0, pi4=0.0, pi8=1e-3, pi9=0.05, pi24=0.1, pi25=0.5, pi26=0.5, pi27=2.0, pi28=0.05,
                 pi29=0.1, pi30=0.2, pi22=0.5, pi23=20.0)
"""A speed-dependent triple pendulum on a rigid building that reaches regime III under the Ricker pulse."""
NARROW = {**SPEED_TFP, "pi28": 0.08, "pi29": 0.01, "pi30": 0.06}
"""The same bearing with tight outer limits: its outer surfaces reach their restrainers (regimes IV and V)."""
TABLE = np.array([[19.7392, 98.696, 98.696, 19.7392], [0.05, 0.025, 0.025, 0.1], [0.025, 0.0125, 0.0125, 0.05],
                  [20.0, 20.0, 20.0, 20.0], [0.1, 0.05, 0.05, 0.2]])
"""Laws of four surfaces (stiffness, fast and slow strengths, rates, limits; tfp_flow.Surfaces.table's rows)."""


def _root(u, xd, guess=(0.0, 0.0), rim=None):
    F = np.empty(2)
    vs = np.empty((4, 2))
    rim = np.zeros(4, dtype=np.bool_) if rim is None else np.asarray(rim, dtype=np.bool_)
    tfp_plane._force(TABLE, rim, np.ascontiguousarray(u), float(xd[0]), float(xd[1]), float(guess[0]),
                     float(guess[1]), F, vs)
    return F, vs


def test_the_bearing_force_makes_the_surfaces_speeds_sum_to_the_slabs_velocity_from_any_guess():
    """The root of sum_i u_i'(F) = x' is reached to round-off and does not depend on Newton's first guess.

    Speeds up to some 0.4 a_p T_p (``a |v|`` up to 8 on a surface): faster, a surface's speed is set by
    digits of its reaction's gap to the fast level that a double does not hold.
    """
    rng = np.random.default_rng(1)
    for _ in range(300):
        u = rng.normal(size=(4, 2)) * 1e-4
        xd = rng.normal(size=2) * 0.1
        F, vs = _root(u, xd, rng.normal(size=2) * 0.05)
        F0, _ = _root(u, xd)
        assert np.abs(vs.sum(axis=0) - xd).max() <= 1e-9 * max(1.0, np.abs(vs).sum())
        assert np.abs(F - F0).max() <= 1e-12


def test_the_bearing_force_along_a_line_is_the_one_dimensional_bearings():
    """With every displacement and the velocity along x, the planar root is tfp_flow's force."""
    s = tfp_flow.Surfaces(*TABLE)
    rng = np.random.default_rng(2)
    for _ in range(200):
        u1 = rng.normal(size=4) * 3e-4
        xd = rng.normal() * 0.1
        f1 = tfp_flow.force(s, u1, xd, 1.0 if xd >= 0.0 else -1.0, tfp_flow.on_stops(s, u1))
        u = np.zeros((4, 2))
        u[:, 0] = u1
        F, vs = _root(u, (xd, 0.0))
        if abs(vs.sum(axis=0)[0] - xd) > 1e-9:      # the 1-D state has no root within the fast levels
            continue
        assert F[0] == pytest.approx(f1, abs=1e-15)
        assert F[1] == 0.0


def test_a_surface_on_its_restrainer_slides_round_the_rim_and_leaves_it_when_pulled_inward():
    """On its restrainer (outward o), a surface pushed outward moves along the rim's tangent at its law's
    speed of the tangential reaction; pulled inward it follows its reaction as off the rim."""
    v = np.empty(2)
    J = np.zeros((2, 2))
    fast, slow, a = TABLE[1, 0], TABLE[2, 0], TABLE[3, 0]
    speed = -math.log((fast - 0.04) / (fast - slow)) / a
    tfp_plane._surface(TABLE, 0, True, 1.0, 0.0, 0.5, 0.04, v, J)
    assert v[0] == 0.0
    assert v[1] == pytest.approx(speed, rel=1e-14)
    tfp_plane._surface(TABLE, 0, True, 1.0, 0.0, -0.01, 0.04, v, J)
    r = math.hypot(-0.01, 0.04)
    along = -math.log((fast - r) / (fast - slow)) / a
    assert v == pytest.approx([-0.01 / r * along, 0.04 / r * along], rel=1e-14)
    tfp_plane._surface(TABLE, 0, True, 1.0, 0.0, 0.5, 0.02, v, J)    # tangential part within the stick level
    assert v[0] == v[1] == 0.0


@pytest.mark.parametrize("bearing, regime", [(SPEED_TFP, 3), (NARROW, 5)])
def test_the_planar_bearing_along_a_diagonal_line_reproduces_the_one_dimensional_model(bearing, regime):
    """Both components equal (45 degrees): the planar engine (model='full') gives the 1-D model's Pi1 to 1e-6.

    Along a line the solver runs the 1-D model rotated; forcing the planar engine exercises its
    circular friction and restrainers off the axes, through regimes III to V.
    """
    scene = Scene(**bearing, pulse_y="ricker", pi14=1.0)
    line = solve(scene)
    plane = solve(scene, model="full")
    assert plane.facets.contact == "plane"
    assert plane.peak_stage == line.peak_stage == regime
    assert plane.settled
    assert plane.pi1 == pytest.approx(line.pi1, rel=1e-6)


@pytest.mark.slow
def test_a_bidirectional_scene_converges_as_the_tolerance_tightens():
    """Two components not along one line: rtol 1e-6 and 1e-8 agree within 1e-6 in Pi1 (restrainers reached)."""
    scene = Scene(**NARROW, pulse_y="antisymmetric_ricker", pi14=0.7, pi15=0.6)
    loose = solve(scene, rtol=1e-6)
    tight = solve(scene, rtol=1e-8)
    assert loose.peak_stage >= 4
    assert loose.pi1 == pytest.approx(tight.pi1, rel=1e-6)


@pytest.mark.slow
def test_the_planar_bearing_is_isotropic():
    """Rotating the whole excitation leaves Pi1 and the peak stage unchanged (circular friction and restrainers)."""
    base = Scene(**SPEED_TFP, pulse_y="antisymmetric_ricker", pi14=0.7)
    turned = Scene(**SPEED_TFP, pulse_y="antisymmetric_ricker", pi14=0.7, angle=0.6)
    a, b = solve(base), solve(turned)
    assert a.peak_stage == b.peak_stage
    assert a.pi1 == pytest.approx(b.pi1, rel=1e-6)


def test_constant_friction_in_the_plane_is_refused_by_name():
    """A constant-friction triple pendulum under two components not along one line is a ValueError naming pi22."""
    with pytest.raises(ValueError, match="pi22 = 1.0"):
        solve(Scene(**{**SPEED_TFP, "pi22": 1.0}, pulse_y="antisymmetric_ricker", pi14=0.7))
