"""Tests of the rigid rocking block and its closed forms (isoslide.model.rocking)."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from isoslide.model.rocking import (
    G_STANDARD, Block, free_rocking_quarter_period, groups_of, housner_period, housner_restitution,
    impact_energy_ratio, rectangular_overturn_amplitude, rectangular_overturn_ratio,
    rectangular_pulse_first_impact, rectangular_pulse_response, uplift_acceleration)

G = G_STANDARD


def test_block_geometry_frequency_and_housner_restitution():
    blk = Block(0.3, 0.4)
    assert blk.R == pytest.approx(0.5, rel=1e-15)
    assert blk.alpha == pytest.approx(math.atan(0.75), rel=1e-15)
    assert blk.p(9.81) == pytest.approx(math.sqrt(3 * 9.81 / (4 * 0.5)), rel=1e-15)
    assert blk.housner_restitution == pytest.approx(1 - 1.5 * 0.6 ** 2, rel=1e-15)  # sin(alpha) = 3/5
    assert blk.e == blk.housner_restitution
    assert Block(0.3, 0.4, restitution=0.4).e == 0.4
    slender = Block.from_slenderness(0.05, 2.0)
    assert slender.alpha == pytest.approx(0.05, rel=1e-15) and slender.R == pytest.approx(2.0, rel=1e-15)


def test_groups_of_a_block_under_a_pulse():
    blk = Block(0.2, 1.0, restitution=0.8)
    out = groups_of(blk, a_p=3.0, T_p=0.5, g=9.81)
    assert set(out) == {"pi18", "pi19", "pi20", "pi21"}
    assert out["pi18"] == pytest.approx(0.2, rel=1e-15)
    assert out["pi19"] == pytest.approx(blk.p(9.81) * 0.5, rel=1e-15)
    assert out["pi20"] == 0.8
    assert out["pi21"] == pytest.approx(3.0 / (9.81 * 0.2), rel=1e-15)


def test_impact_energy_ratio_is_e_squared_and_uplift_level_is_g_tan_alpha():
    blk = Block(0.1, 0.5)
    assert impact_energy_ratio(blk) == pytest.approx(blk.e ** 2, rel=1e-15)
    assert uplift_acceleration(blk, g=9.81) == pytest.approx(9.81 * 0.2, rel=1e-15)
    assert uplift_acceleration(blk, g=9.81, a_v=-4.81) == pytest.approx(5.0 * 0.2, rel=1e-15)


def _quarter_by_ode(blk, theta0):
    """Release at theta0 on a quiet floor, integrated directly (exact equation) to theta = 0."""
    p2 = blk.p(G) ** 2

    def rhs(t, y):
        return [y[1], -p2 * math.sin(blk.alpha - y[0])]

    def hit(t, y):
        return y[0]
    hit.terminal, hit.direction = True, -1
    sol = solve_ivp(rhs, (0, 100), [theta0, 0.0], method="DOP853", rtol=1e-13, atol=1e-16, events=hit)
    return sol.t_events[0][0]


@pytest.mark.parametrize("alpha,frac", [(0.05, 0.5), (0.3, 0.9), (0.6, 0.01), (0.2, 0.999)])
def test_exact_quarter_period_by_quadrature_matches_direct_integration(alpha, frac):
    """The singularity-free quadrature equals an independent tight integration of the energy equation."""
    blk = Block.from_slenderness(alpha, 1.3)
    q = free_rocking_quarter_period(blk, frac * alpha)
    assert q == pytest.approx(_quarter_by_ode(blk, frac * alpha), rel=1e-10)


def test_housner_period_is_the_linearised_limit_of_the_exact_one_to_order_alpha_squared():
    """Relative error of (4/p) arccosh(1/(1 - theta0/alpha)) shrinks like alpha^2 at fixed theta0/alpha."""
    errs = []
    for alpha in (0.1, 0.05, 0.025):
        blk = Block.from_slenderness(alpha, 1.0)
        exact = 4 * free_rocking_quarter_period(blk, 0.5 * alpha)
        err = housner_period(blk, 0.5 * alpha) / exact - 1
        assert abs(err) < alpha ** 2 / 6
        errs.append(err)
    assert errs[0] / errs[1] == pytest.approx(4, rel=0.02)
    assert errs[1] / errs[2] == pytest.approx(4, rel=0.02)


def _linear_block_ode(blk, a, t_d, t_eval):
    """The linearised equation psi'' = p^2 (psi - alpha + |a|/g during the pulse) integrated numerically."""
    p2, alpha = blk.p(G) ** 2, blk.alpha

    def rhs(t, y):
        forcing = abs(a) / G if t < t_d else 0.0
        return [y[1], p2 * (y[0] - alpha + forcing)]

    s1 = solve_ivp(rhs, (0, t_d), [0.0, 0.0], method="DOP853", rtol=1e-13, atol=1e-16, dense_output=True)
    s2 = solve_ivp(rhs, (t_d, t_eval[-1]), s1.y[:, -1], method="DOP853", rtol=1e-13, atol=1e-16,
                   dense_output=True)
    return np.where(t_eval < t_d, s1.sol(np.minimum(t_eval, t_d))[0], s2.sol(np.maximum(t_eval, t_d))[0])


def test_rectangular_pulse_response_solves_the_linearised_equation_and_its_first_impact():
    blk = Block.from_slenderness(0.05, 1.0)
    a, t_d = -1.4 * G * 0.05, 0.7 / blk.p(G)
    t_hit = rectangular_pulse_first_impact(blk, a, t_d)
    assert t_d < t_hit < math.inf
    t = np.linspace(0.0, t_hit, 201)
    theta, omega = rectangular_pulse_response(blk, a, t_d, t)
    psi = _linear_block_ode(blk, a, t_d, t)
    assert np.max(np.abs(theta - psi)) < 1e-11 * np.max(psi)
    assert theta[-1] == pytest.approx(0.0, abs=1e-12 * np.max(psi))
    assert omega[-1] < 0 < np.max(theta)
    # mirror: the opposite pulse tilts the block onto the other corner
    theta_m, omega_m = rectangular_pulse_response(blk, -a, t_d, t)
    assert np.array_equal(theta_m, -theta) and np.array_equal(omega_m, -omega)
    # below the linearised uplift level g alpha nothing moves
    assert not np.any(rectangular_pulse_response(blk, 0.99 * G * 0.05, t_d, t)[0])
    assert math.isnan(rectangular_pulse_first_impact(blk, 0.99 * G * 0.05, t_d))


@pytest.mark.parametrize("p_td", [0.2, 1.0, 3.0])
def test_rectangular_overturn_ratio_separates_overturning_from_return(p_td):
    """Just above beta_c the linearised block passes alpha (no impact); just below it returns to the floor."""
    blk = Block.from_slenderness(0.05, 1.0)
    t_d = p_td / blk.p(G)
    beta_c = rectangular_overturn_ratio(p_td)
    assert beta_c == pytest.approx(1 / (1 - math.exp(-p_td)), rel=1e-14)
    assert rectangular_overturn_amplitude(blk, t_d) == pytest.approx(beta_c * G * 0.05, rel=1e-14)
    a_c = beta_c * G * 0.05
    assert math.isinf(rectangular_pulse_first_impact(blk, 1.001 * a_c, t_d))
    assert math.isfinite(rectangular_pulse_first_impact(blk, 0.999 * a_c, t_d))
    late = t_d + 20 / blk.p(G)
    assert rectangular_pulse_response(blk, -1.001 * a_c, t_d, late)[0] > 0.05


def test_rectangular_overturn_ratio_limits():
    """Long pulses need only the uplift level; short ones a velocity step a t_d -> g alpha / p."""
    assert rectangular_overturn_ratio(40.0) == pytest.approx(1.0, rel=1e-15)
    assert rectangular_overturn_ratio(1e-6) * 1e-6 == pytest.approx(1.0, rel=1e-6)


@pytest.mark.parametrize("kwargs,name,text", [
    (dict(b=-0.1, h=1.0), "b", "0 < value < inf"),
    (dict(b=0.1, h=0.0), "h", "0 < value < inf"),
    (dict(b=0.1, h=math.inf), "h", "0 < value < inf"),
    (dict(b=math.nan, h=1.0), "b", "0 < value < inf"),
    (dict(b=0.1, h=1.0, restitution=0.0), "restitution", "0 < value <="),
    (dict(b=0.1, h=1.0, restitution=0.999), "restitution", "0 < value <="),
])
def test_bad_block_errors_name_the_parameter_value_and_range(kwargs, name, text):
    with pytest.raises(ValueError) as err:
        Block(**kwargs)
    msg = str(err.value)
    assert msg.startswith(f"{name} = ") and repr(kwargs[name]) in msg and text in msg


def test_bad_closed_form_arguments_raise_with_messages():
    blk = Block.from_slenderness(0.1, 1.0)
    with pytest.raises(ValueError, match=r"theta0 = 0\.1 .*0 < value < 0\.1"):
        housner_period(blk, 0.1)
    with pytest.raises(ValueError, match="theta0 = -0.01"):
        free_rocking_quarter_period(blk, -0.01)
    with pytest.raises(ValueError, match="g = 0"):
        blk.p(0)
    with pytest.raises(ValueError, match="a_p = -1"):
        groups_of(blk, -1, 1)
    with pytest.raises(ValueError, match="t_d = -1"):
        rectangular_pulse_response(blk, 1.0, -1, [0.0])
    with pytest.raises(ValueError, match="p_td = 0"):
        rectangular_overturn_ratio(0)
    with pytest.raises(ValueError, match="alpha = 2"):
        housner_restitution(2)
