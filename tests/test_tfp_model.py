"""The triple friction pendulum's parameters and closed forms (isoslide.model.tfp).

Checked here on their own: the constructor's refusals, the regime table (stiffnesses, intercepts,
boundaries in Fenz and Constantinou's expanded form), continuity and oddness of the backbone, the
unloading rules (the first drop of ``2 mu1 W`` at regime I's stiffness, Masing's rule up to regime
III), the series model's elements, the reduction of a bearing with equal surfaces to a single
friction pendulum, and the capacity refusal.  The peer comparison is in test_tfp_quasistatic.py.
"""

import math

import numpy as np
import pytest

from isoslide.model import tfp
from isoslide.model.tfp import TripleFrictionPendulum as TFP

BEARING = dict(L=(0.3, 2.0, 2.5), mu=(0.02, 0.06, 0.1), d=(0.06, 0.4, 0.45), W=1000.0)


def _mid_amplitudes(b):
    """An amplitude inside each regime I..V and the capacity."""
    u = tfp.regime_boundaries(b).u
    return [0.5 * (u[k] + u[k + 1]) for k in range(5)] + [u[5]]


# ----------------------------------------------------------------------------------------------
# construction
# ----------------------------------------------------------------------------------------------

REFUSALS = [
    (dict(L=(0.3, 0.0, 2.5)), r"L2 = 0.0 is out of range; allowed range: 0 < value < inf"),
    (dict(L=(-0.3, 2.0, 2.5)), r"L1 = -0.3 is out of range"),
    (dict(d=(0.06, 0.4, -1.0)), r"d3 = -1.0 is out of range; allowed range: 0 < value < inf"),
    (dict(W=0.0), r"W = 0.0 is out of range; allowed range: 0 < value < inf"),
    (dict(mu=(-0.01, 0.06, 0.1)), r"mu1 = -0.01 is out of range; allowed range: 0 <= value < inf"),
    (dict(mu=(0.02, math.nan, 0.1)), r"mu2 = nan is out of range"),
    (dict(mu=(0.02, 0.06, math.inf)), r"mu3 = inf is out of range"),
    (dict(mu=(0.02, 0.06)), r"must be one value or three; got 2"),
    (dict(mu=(0.07, 0.06, 0.1)), r"mu1 = 0.07 exceeds mu2 = 0.06; the five regimes need mu1 <= mu2 <= mu3"),
    (dict(mu=(0.02, 0.11, 0.1)), r"mu2 = 0.11 exceeds mu3 = 0.1; the five regimes need mu1 <= mu2 <= mu3"),
    (dict(mu_slow=(0.01, 0.07, 0.05), rate=20.0), r"mu_slow2 = 0.07 exceeds mu2 = 0.06; .* needs mu_slow <= "
                                                  r"mu_fast"),
    (dict(rate=20.0), r"rate = 20.0 is given without mu_slow"),
    (dict(mu_slow=0.01), r"rate = None with mu_slow given; allowed: rate > 0"),
    (dict(mu_slow=0.01, rate=0.0), r"rate1 = 0.0 is out of range; allowed range: 0 < value < inf"),
    (dict(d=(0.06, 0.07, 0.45)), r"d2 = 0.07 is too small: surface 1 would reach its restrainer before surface "
                                 r"4 slides; allowed: d2/L2 >= mu3 - mu2"),
    (dict(d=(0.06, 0.4, 0.2)), r"d3 = 0.2 is too small: surface 4 would reach its restrainer before surface 1; "
                               r"allowed: mu2 \+ d2/L2 <= mu3 \+ d3/L3"),
    (dict(d=(0.02, 0.4, 0.45)), r"d1 = 0.02 is too small: surface 3 would reach its restrainer before regime V; "
                                r"allowed: d1/L1 >= mu3 - mu1"),
    (dict(d=(0.03, 0.1, 0.5)), r"d1 = 0.03 is too small: surface 2 would reach its restrainer before surface 4 "
                                r"reaches its own; allowed: mu3 \+ d3/L3 <= mu1 \+ d1/L1 \+ d2/L2"),
]


@pytest.mark.parametrize("change, message", REFUSALS)
def test_constructor_refuses_each_bad_parameter_naming_value_and_rule(change, message):
    with pytest.raises(ValueError, match=message):
        TFP(**{**BEARING, **change})


def test_ordering_is_checked_at_every_speed_of_the_velocity_law():
    """Slow and fast values in order, but with different rates mu1(v) > mu2(v) at intermediate speeds."""
    args = dict(BEARING, mu=(0.05, 0.06, 0.1), mu_slow=(0.01, 0.02, 0.05), rate=(100.0, 1.0, 1.0),
                d=(0.06, 0.4, 0.45))
    with pytest.raises(ValueError, match=r"mu1 = 0.05 exceeds mu2 = 0.06 at every speed"):
        TFP(**args)
    ok = TFP(**dict(args, rate=30.0))             # one rate: the law is a convex combination, in order
    v = np.linspace(0.0, 0.5, 201)
    mus = np.array([ok.friction(x) for x in v])
    assert np.all(np.diff(mus, axis=1) >= 0.0)


def test_one_value_stands_for_three_and_the_bearing_is_frozen():
    b = TFP(L=(0.3, 2.0, 2.5), mu=(0.02, 0.06, 0.1), d=(0.06, 0.4, 0.55), mu_slow=0.01, rate=20.0)
    assert b.mu_slow == (0.01, 0.01, 0.01) and b.rate == (20.0, 20.0, 20.0) and b.W == 1.0
    with pytest.raises(AttributeError):
        b.W = 2.0


def test_velocity_law_values_and_the_constant_friction_bearing_at_a_speed():
    b = TFP(**dict(BEARING, d=(0.06, 0.4, 0.55)), mu_slow=(0.01, 0.03, 0.05), rate=(20.0, 10.0, 5.0))
    assert b.friction(0.0) == pytest.approx((0.01, 0.03, 0.05), rel=1e-15)
    assert b.friction() == b.mu
    v = 0.1
    expect = [f - (f - s) * math.exp(-r * v) for f, s, r in zip(b.mu, b.mu_slow, b.rate, strict=True)]
    assert b.friction(-v) == pytest.approx(expect, rel=1e-15)
    slow = b.at_speed(v)
    assert slow.mu == pytest.approx(expect, rel=1e-15) and slow.mu_slow is None and slow.L == b.L


# ----------------------------------------------------------------------------------------------
# the backbone
# ----------------------------------------------------------------------------------------------

def test_regime_stiffness_is_weight_over_the_two_sliding_radii():
    b = TFP(**BEARING)
    L1, L2, L3 = b.L
    W = b.W
    expect = {1: W / (2 * L1), 2: W / (L1 + L2), 3: W / (L2 + L3), 4: W / (L1 + L3), 5: W / (2 * L1)}
    for stage, k in expect.items():
        assert tfp.regime_stiffness(b, stage) == pytest.approx(k, rel=1e-15)
    with pytest.raises(ValueError, match=r"stage = 6 is invalid; allowed: \(1, 2, 3, 4, 5\)"):
        tfp.regime_stiffness(b, 6)


def test_regime_boundaries_equal_fenz_and_constantinous_expressions():
    b = TFP(**BEARING)
    (L1, L2, L3), (mu1, mu2, mu3), (d1, d2, d3) = b.L, b.mu, b.d
    bd = tfp.regime_boundaries(b)
    u_star = 2 * L1 * (mu2 - mu1)
    u_2star = u_star + (L1 + L2) * (mu3 - mu2)
    u_dr1 = u_2star + d2 * (1 + L3 / L2) - (mu3 - mu2) * (L2 + L3)
    u_dr4 = u_dr1 + (d3 / L3 + mu3 - d2 / L2 - mu2) * (L1 + L3)
    f_cap = mu1 + d1 / L1 + min(d2 / L2, d3 / L3)
    u_cap = u_dr4 + 2 * L1 * (f_cap - mu3 - d3 / L3)
    got = (bd.u_star, bd.u_2star, bd.u_dr1, bd.u_dr4, bd.u_capacity)
    assert got == pytest.approx((u_star, u_2star, u_dr1, u_dr4, u_cap), rel=1e-13)
    assert bd.F == pytest.approx(np.array([mu1, mu2, mu3, mu2 + d2 / L2, mu3 + d3 / L3, f_cap]) * b.W, rel=1e-15)
    assert tfp.capacity(b) == bd.u_capacity


def test_regime_intercepts_and_continuity_at_every_boundary():
    b = TFP(**BEARING)
    (L1, L2, _), (mu1, mu2, _) = b.L, b.mu
    bd = tfp.regime_boundaries(b)
    assert tfp.regime_intercept(b, 1) == pytest.approx(mu1 * b.W, rel=1e-14)
    assert tfp.regime_intercept(b, 2) == pytest.approx(b.W * (mu2 * (L2 - L1) + 2 * mu1 * L1) / (L1 + L2),
                                                       rel=1e-14)
    for stage in tfp.STAGES:
        K, c = tfp.regime_stiffness(b, stage), tfp.regime_intercept(b, stage)
        assert K * bd.u[stage - 1] + c == pytest.approx(bd.F[stage - 1], rel=1e-13)   # start of the regime
        assert K * bd.u[stage] + c == pytest.approx(bd.F[stage], rel=1e-13)           # its end
        F, s = tfp.force(b, 0.5 * (bd.u[stage - 1] + bd.u[stage]))
        assert s == stage and F == pytest.approx(K * 0.5 * (bd.u[stage - 1] + bd.u[stage]) + c, rel=1e-14)


def test_backbone_force_is_odd_zero_at_rest_and_numbers_the_regimes():
    b = TFP(**BEARING)
    u = np.linspace(-tfp.capacity(b), tfp.capacity(b), 401)
    F, stage = tfp.force(b, u)
    assert np.allclose(F, -F[::-1], rtol=0.0, atol=1e-12 * b.W) and np.array_equal(stage, stage[::-1])
    assert tfp.force(b, 0.0) == (0.0, 0)
    assert set(stage.tolist()) == {0, 1, 2, 3, 4, 5} and stage[200] == 0
    assert np.all(np.diff(F) > 0.0)
    bd = tfp.regime_boundaries(b)
    assert tfp.force(b, bd.u_star)[1] == 1 and tfp.force(b, bd.u_star * (1 + 1e-9))[1] == 2
    assert [tfp.peak_regime(b, a) for a in _mid_amplitudes(b)] == [1, 2, 3, 4, 5, 5]
    assert tfp.STAGE_NAMES[4] == "IV"


@pytest.mark.parametrize("call", [
    lambda b, a: tfp.force(b, a), lambda b, a: tfp.force(b, [0.0, -a]), lambda b, a: tfp.peak_regime(b, a),
    lambda b, a: tfp.cyclic_loop(b, a), lambda b, a: tfp.backbone(b, a), lambda b, a: tfp.unloading_branch(b, a),
    lambda b, a: tfp.dissipated_energy(b, a)])
def test_beyond_the_capacity_every_closed_form_refuses(call):
    b = TFP(**BEARING)
    a = tfp.capacity(b) * 1.001
    with pytest.raises(ValueError, match=r"exceeds the displacement capacity 0\.964.* m \(an inner surface at its "
                                         r"restrainer ends regime V\); allowed: \|u\| <= capacity"):
        call(b, a)
    call(b, tfp.capacity(b))        # the capacity itself is allowed


def test_loop_arguments_are_checked():
    b = TFP(**BEARING)
    with pytest.raises(ValueError, match=r"amplitude = 0.0 is not positive"):
        tfp.cyclic_loop(b, 0.0)
    with pytest.raises(ValueError, match=r"branch = 'left' is invalid"):
        tfp.loop_force(b, 0.1, 0.0, branch="left")
    with pytest.raises(ValueError, match=r"u outside the loop's range"):
        tfp.loop_force(b, 0.1, 0.2)


# ----------------------------------------------------------------------------------------------
# the loop
# ----------------------------------------------------------------------------------------------

@pytest.mark.parametrize("which", range(6))
def test_first_unloading_drops_two_mu1_w_then_follows_regime_one_stiffness(which):
    b = TFP(**BEARING)
    A = _mid_amplitudes(b)[which]
    down = tfp.unloading_branch(b, A)
    FA = tfp.force(b, A)[0]
    assert down.u[0] == down.u[1] == pytest.approx(A, rel=1e-15)
    assert down.F[0] - down.F[1] == pytest.approx(2 * b.mu[0] * b.W, rel=1e-12)
    assert down.stage[1] == 0 and down.F[0] == pytest.approx(FA, rel=1e-15)
    slope = (down.F[2] - down.F[1]) / (down.u[2] - down.u[1])
    assert slope == pytest.approx(tfp.regime_stiffness(b, 1), rel=1e-12)
    assert down.u[-1] == pytest.approx(-A, rel=1e-13) and down.F[-1] == pytest.approx(-FA, rel=1e-13)
    loop = tfp.cyclic_loop(b, A)
    assert loop.u[-1] == pytest.approx(A, rel=1e-13) and loop.F[-1] == pytest.approx(FA, rel=1e-13)


@pytest.mark.parametrize("which", range(3))
def test_unloading_from_regimes_one_to_three_is_masings_rule(which):
    """``F_down(u) = F_A - 2 F_backbone((A - u)/2)`` while no restrainer has been reached."""
    b = TFP(**BEARING)
    A = _mid_amplitudes(b)[which]
    FA = tfp.force(b, A)[0]
    u = np.linspace(-A, A * (1 - 1e-9), 301)
    Fb = tfp.force(b, (A - u) / 2.0)[0]
    assert np.allclose(tfp.loop_force(b, A, u, "down"), FA - 2.0 * Fb, rtol=0.0, atol=1e-11 * b.W)
    assert np.allclose(tfp.loop_force(b, A, -u, "up"), -(FA - 2.0 * Fb), rtol=0.0, atol=1e-11 * b.W)
    down = tfp.unloading_branch(b, A)
    assert down.stage[1:].tolist() == [0] + list(range(1, which + 2))


def test_unloading_from_regime_five_releases_the_restrainers_at_their_forces():
    b = TFP(**BEARING)
    (_, L2, L3), (_, mu2, mu3), (_, d2, d3) = b.L, b.mu, b.d
    A = tfp.capacity(b)
    down = tfp.unloading_branch(b, A)
    # surface 1 leaves its restrainer at F = W (d2/L2 - mu2), surface 4 at W (d3/L3 - mu3)
    assert b.W * (d2 / L2 - mu2) == pytest.approx(down.F[2], rel=1e-13)
    assert b.W * (d3 / L3 - mu3) == pytest.approx(down.F[3], rel=1e-13)
    assert down.stage[1:5].tolist() == [0, 5, 2, 3]


def test_energy_per_cycle_in_regime_one_is_four_mu1_w_a():
    b = TFP(**BEARING)
    A = _mid_amplitudes(b)[0]
    assert tfp.dissipated_energy(b, A) == pytest.approx(4 * b.mu[0] * b.W * A, rel=1e-13)
    energies = [tfp.dissipated_energy(b, a) for a in _mid_amplitudes(b)]
    assert np.all(np.diff(energies) > 0.0)


# ----------------------------------------------------------------------------------------------
# reductions and the series model
# ----------------------------------------------------------------------------------------------

def test_equal_surfaces_make_a_single_friction_pendulum_of_radius_l2_plus_l3():
    """All radii and frictions equal: the inner surfaces never slide (their drive is pinned at mu W),
    the outer two slide together: radius ``L2 + L3 = 2 L``, friction ``mu``, a drop of ``2 mu W``."""
    L, mu, W = 1.2, 0.05, 500.0
    b = TFP(L=L, mu=mu, d=(1.0, 1.0, 1.0), W=W)
    u = np.linspace(1e-6, tfp.regime_boundaries(b).u_dr1, 50)   # until the outer restrainers
    F, stage = tfp.force(b, u)
    assert np.allclose(F, mu * W + W * u / (2 * L), rtol=1e-14) and np.all(stage == 3)
    A = 0.5
    down = tfp.unloading_branch(b, A)
    assert len(down.u) == 3 and np.allclose(down.surfaces[:, 1:3], 0.0)
    assert down.F[1] == pytest.approx(mu * W + W * A / (2 * L) - 2 * mu * W, rel=1e-14)
    assert (down.F[1] - down.F[2]) / (down.u[1] - down.u[2]) == pytest.approx(W / (2 * L), rel=1e-13)
    assert tfp.dissipated_energy(b, A) == pytest.approx(4 * mu * W * A, rel=1e-13)


def test_series_elements_reproduce_the_backbone():
    """Fenz and Constantinou's three elements in series, each ``R (f - mu)`` clipped to ``[0, c]``."""
    b = TFP(**BEARING)
    elements = b.series_elements()
    L1, L2, L3 = b.L
    assert [e[0] for e in elements] == pytest.approx([2 * L1, L2 - L1, L3 - L1], rel=1e-15)
    assert elements[1][2] == pytest.approx(b.d[1] * (1 - L1 / L2), rel=1e-15)
    u = np.linspace(0.0, tfp.capacity(b), 301)[1:]
    F = tfp.force(b, u)[0]
    total = sum(np.clip(R * (F / b.W - mu), 0.0, c) for R, mu, c in elements)
    assert np.allclose(total, u, rtol=1e-12, atol=0.0)
    # OpenSees closes the inner element at 2 (d1 + L1 d3/L3): the same when surface 3 locks first
    assert elements[0][2] == pytest.approx(2 * (b.d[0] + L1 * b.d[2] / L3), rel=1e-13)
    with pytest.raises(ValueError, match=r"L2 = 0.2 is not above L1 = 0.3; .* allowed: L2 > L1"):
        TFP(L=(0.3, 0.2, 2.5), mu=(0.02, 0.03, 0.04), d=(0.06, 0.2, 2.5)).series_elements()
