"""The triple friction pendulum's closed forms against the independent quasi-static peer.

The peer (isoslide.peers.tfp_quasistatic) solves the equilibrium of the four surfaces event to event
along a line and in implicit increments in the plane; the closed forms (isoslide.model.tfp) are
piecewise-linear formulas.  Checked: every vertex of the loop (regime boundaries, force intercepts,
stiffnesses, the regime of each stretch) for several geometries and amplitudes in each regime, to
round-off; which surfaces slide in each regime; a bearing with equal surfaces; the peer beyond the
closed forms' capacity; the planar peer along straight lines in any direction (the line's loop,
rotated) and along circular orbits (the energy of a cycle: its value in regime I, positive,
independent of where the orbit starts and of its sense).
"""

import math

import numpy as np
import pytest

from isoslide.model import tfp
from isoslide.model.tfp import TripleFrictionPendulum as TFP
from isoslide.peers import tfp_quasistatic as peer

GEOMETRIES = {
    # surface 3 locks first (d3/L3 < d2/L2)
    "wide": TFP(L=(0.3, 2.0, 2.5), mu=(0.02, 0.06, 0.1), d=(0.06, 0.4, 0.45), W=1000.0),
    # the OpenSees example's radii and limits
    "opensees": TFP(L=(0.3937, 3.7465, 3.7465), mu=(0.01, 0.04, 0.08), d=(0.0716, 0.5043, 0.5043), W=1.0),
    # mu2 = mu3: regime II has zero length; surface 4 reverses before surface 1 leaves its restrainer
    "equal outer friction": TFP(L=(0.25, 1.5, 1.5), mu=(0.03, 0.08, 0.08), d=(0.05, 0.3, 0.35), W=2.0e5),
    # the OpenSees checking model
    "checking model": TFP(L=(0.36, 1.25, 1.25), mu=(0.012, 0.052, 0.14), d=(0.1, 0.2, 0.2), W=1000.0),
    # all frictions equal: regimes I and II have zero length
    "equal friction": TFP(L=(0.3, 2.0, 2.5), mu=0.04, d=(0.06, 0.4, 0.55), W=1.0),
}


def _amplitudes(b):
    """An amplitude inside each regime of positive length, and the capacity."""
    u = tfp.regime_boundaries(b).u
    return [0.5 * (u[k] + u[k + 1]) for k in range(5) if u[k + 1] > u[k]] + [u[5]]


CASES = [(name, k) for name, b in GEOMETRIES.items() for k in range(len(_amplitudes(b)))]


def _assert_same_path(got_u, got_F, want_u, want_F, W, rel=1e-9):
    scale_u = max(np.max(np.abs(want_u)), 1e-300)
    assert len(got_u) == len(want_u)
    assert np.max(np.abs(got_u - want_u)) <= rel * scale_u
    assert np.max(np.abs(got_F - want_F)) <= rel * np.max(np.abs(want_F))


@pytest.mark.parametrize("name, which", CASES)
def test_peer_loop_vertices_and_regimes_equal_the_closed_form(name, which):
    """Every vertex (u, F) of the loop from rest, and the regime of every stretch, to 1e-9."""
    b = GEOMETRIES[name]
    A = _amplitudes(b)[which]
    closed = tfp.cyclic_loop(b, A)
    path = peer.cycle(b, A)
    _assert_same_path(path.u, path.F, closed.u, closed.F, b.W)
    assert path.stage.tolist() == closed.stage.tolist()
    assert np.allclose(path.surfaces, closed.surfaces, rtol=0.0, atol=1e-12 * max(b.d))
    assert path.stage.max() == tfp.peak_regime(b, A)


@pytest.mark.parametrize("name", list(GEOMETRIES))
def test_peer_backbone_has_the_regime_boundaries_stiffnesses_and_intercepts(name):
    b = GEOMETRIES[name]
    bd = tfp.regime_boundaries(b)
    path = peer.solve_path(b, [bd.u_capacity])
    keep = [k for k in range(6) if k == 0 or bd.u[k] > bd.u[k - 1]]
    assert np.allclose(path.u[1:], np.array(bd.u)[keep], rtol=1e-12, atol=0.0)
    assert np.allclose(path.F[1:], np.array(bd.F)[keep], rtol=1e-12, atol=0.0)
    for k in range(2, len(path.u)):
        stage = path.stage[k]
        slope = (path.F[k] - path.F[k - 1]) / (path.u[k] - path.u[k - 1])
        assert slope == pytest.approx(tfp.regime_stiffness(b, stage), rel=1e-10)
        assert path.F[k] - slope * path.u[k] == pytest.approx(tfp.regime_intercept(b, stage), rel=1e-9,
                                                              abs=1e-12 * b.W)


def test_two_surfaces_slide_at_a_time_and_surface_two_stops_while_surface_one_slides():
    """Regime I: 2 and 3; II: 1 and 3 (the plate of surface 1 pins the drive of surface 2); III: 1 and 4;
    IV: 2 and 4 (surface 1 at its restrainer); V: 2 and 3."""
    b = GEOMETRIES["wide"]
    path = peer.solve_path(b, [tfp.capacity(b)])
    moving = [tuple(np.flatnonzero(s) + 1) for s in path.sliding[2:]]
    assert moving == [(2, 3), (1, 3), (1, 4), (2, 4), (2, 3)]
    assert path.stage[2:].tolist() == [1, 2, 3, 4, 5]
    u1 = path.surfaces[:, 0]
    assert u1[4] == pytest.approx(b.d[1], rel=1e-15) and u1[-1] == u1[4]


def test_the_loop_repeats_cycle_after_cycle():
    b = GEOMETRIES["checking model"]
    A = _amplitudes(b)[3]
    path = peer.cycle(b, A, cycles=3)
    one = len(peer.cycle(b, A, cycles=1).u)
    per = (len(path.u) - one) // 2
    first = slice(one - 2 * per + per, one)        # the second half of the first cycle
    again = slice(len(path.u) - per, len(path.u))
    assert np.allclose(path.u[first], path.u[again], rtol=0.0, atol=1e-13)
    assert np.allclose(path.F[first], path.F[again], rtol=0.0, atol=1e-12 * b.W)


def test_peer_with_equal_surfaces_is_a_friction_pendulum_of_radius_two_l():
    L, mu, W = 1.2, 0.05, 500.0
    b = TFP(L=L, mu=mu, d=(1.0, 1.0, 1.0), W=W)
    path = peer.cycle(b, 0.5)
    assert np.all(path.surfaces[:, 1:3] == 0.0)            # the inner surfaces never slide
    assert path.u.tolist() == pytest.approx([0.0, 0.0, 0.5, 0.5, -0.5, -0.5, 0.5], abs=1e-15)
    F_fp = mu * W + W * 0.5 / (2 * L)
    assert path.F.tolist() == pytest.approx([0.0, mu * W, F_fp, F_fp - 2 * mu * W, -F_fp, -F_fp + 2 * mu * W,
                                             F_fp], rel=1e-13)


def test_peer_goes_on_past_the_capacity_until_the_total_travel():
    """Past the first inner restrainer the other inner surface slides alone (stiffness W/L1, none of the
    five regimes); every surface at its restrainer is the end of travel."""
    b = GEOMETRIES["wide"]
    travel = 2 * b.d[0] + b.d[1] + b.d[2]
    path = peer.solve_path(b, [travel])
    cap = tfp.regime_boundaries(b)
    k = int(np.argmin(np.abs(path.u - cap.u_capacity)))
    assert path.F[k] == pytest.approx(cap.F[5], rel=1e-12)
    assert path.stage[k + 1] == -1 and path.sliding[k + 1].tolist() == [False, True, False, False]
    slope = (path.F[k + 1] - path.F[k]) / (path.u[k + 1] - path.u[k])
    assert slope == pytest.approx(b.W / b.L[0], rel=1e-10)
    assert path.u[-1] == pytest.approx(travel, rel=1e-15)
    with pytest.raises(ValueError, match=r"target = 1\.02 m lies beyond the bearing's total travel 0\.97 m"):
        peer.solve_path(b, [0.5, 1.02])


def test_peer_uses_the_friction_of_a_velocity_law_at_a_given_speed():
    b = TFP(L=(0.3, 2.0, 2.5), mu=(0.02, 0.06, 0.1), d=(0.06, 0.4, 0.55), mu_slow=(0.01, 0.03, 0.05),
            rate=(20.0, 10.0, 5.0), W=1.0)
    slow = b.at_speed(0.05)
    A = _amplitudes(slow)[2]
    closed = tfp.cyclic_loop(slow, A)
    path = peer.cycle(slow, A)
    _assert_same_path(path.u, path.F, closed.u, closed.F, slow.W)


# ----------------------------------------------------------------------------------------------
# in the plane
# ----------------------------------------------------------------------------------------------

@pytest.mark.parametrize("which", [1, 2, 5])
@pytest.mark.parametrize("angle", [0.0, 0.9, -2.6])
def test_planar_peer_along_a_line_is_the_lines_loop_rotated(which, angle):
    """Force along the line equals the closed-form loop at every point, the force across it vanishes,
    and every surface moves along the line (restrainers included)."""
    b = GEOMETRIES["wide"]
    A = _amplitudes(b)[which]
    n = 30
    path = peer.solve_planar(b, peer.line_points([A, -A, A], angle, n=n))
    e = np.array([math.cos(angle), math.sin(angle)])
    s = path.u[1:] @ e
    along, across = path.F[1:] @ e, path.F[1:] @ np.array([-e[1], e[0]])
    want = np.concatenate([tfp.force(b, s[:n])[0], tfp.loop_force(b, A, s[n:2 * n], "down"),
                           tfp.loop_force(b, A, s[2 * n:], "up")])
    assert np.max(np.abs(along - want)) <= 1e-9 * np.max(np.abs(want))
    assert np.max(np.abs(across)) <= 1e-9 * np.max(np.abs(want))
    surf_across = path.surfaces[1:] @ np.array([-e[1], e[0]])
    assert np.max(np.abs(surf_across)) <= 1e-12
    assert np.max(path.stage) == tfp.peak_regime(b, A)


def _orbit_energy(b, radius, start=0.0, clockwise=False, n=180):
    pts = peer.orbit_points(radius, n=n, cycles=2, start=start, clockwise=clockwise, approach=10)
    path = peer.solve_planar(b, pts)
    return peer.path_work(path, 10 + n, 10 + 2 * n + 1), path


def test_planar_orbit_in_regime_one_dissipates_two_pi_a_mu1_w_per_cycle():
    """Both inner surfaces slide on circles of radius A/2 with friction mu1 W along their motion;
    the outer surfaces stay stuck while ``W sqrt((A / 2 L1)^2 + mu1^2) <= mu2 W``."""
    b = GEOMETRIES["wide"]
    A = 0.02
    assert math.hypot(A / (2 * b.L[0]), b.mu[0]) < b.mu[1]
    energy, path = _orbit_energy(b, A)
    assert energy == pytest.approx(2 * math.pi * A * b.mu[0] * b.W, rel=1e-3)
    assert set(path.stage[1:].tolist()) == {1} and np.all(path.surfaces[:, [0, 3]] == 0.0)
    assert np.allclose(path.surfaces[:, 1], path.surfaces[:, 2], rtol=0.0, atol=1e-15)


@pytest.mark.parametrize("radius", [0.3, 0.85])
def test_planar_orbit_energy_is_positive_and_independent_of_its_start_and_sense(radius):
    b = GEOMETRIES["wide"]
    base, path = _orbit_energy(b, radius)
    assert base > 0.0
    for start, clockwise in ((1.1, False), (-2.0, True)):
        other, _ = _orbit_energy(b, radius, start=start, clockwise=clockwise)
        assert other == pytest.approx(base, rel=1e-9)
    # equilibrium: every reaction within its friction circle, unless its restrainer pushes
    R = np.array([b.L[1], b.L[0], b.L[0], b.L[2]])
    m = b.W * np.array([b.mu[1], b.mu[0], b.mu[0], b.mu[2]])
    lim = np.array([b.d[1], b.d[0], b.d[0], b.d[2]])
    u, F = path.surfaces, path.F
    q0 = F - b.W * u[:, 0] / R[0]
    q3 = F - b.W * u[:, 3] / R[3]
    q = np.stack([q0, q0 - b.W * u[:, 1] / R[1], q3 - b.W * u[:, 2] / R[2], q3], axis=1)
    free = np.linalg.norm(u, axis=2) < lim * (1 - 1e-12)
    assert np.all(np.linalg.norm(q, axis=2)[free] <= (m * (1 + 1e-9))[np.nonzero(free)[1]])


def test_planar_peer_refuses_a_point_beyond_the_total_travel():
    b = GEOMETRIES["wide"]
    with pytest.raises(ValueError, match=r"point \[0\.8, 0\.8\] lies beyond the bearing's total travel 0\.97 m"):
        peer.solve_planar(b, [[0.1, 0.1], [0.8, 0.8]])
