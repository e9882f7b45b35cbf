"""Tests of the independent event-driven rocking peer (isoslide.peers.rocking) against closed forms."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from isoslide.model.rocking import (
    G_STANDARD, Block, free_rocking_quarter_period, housner_period, rectangular_overturn_ratio,
    rectangular_pulse_first_impact, rectangular_pulse_response)
from isoslide.peers.rocking import RockingContactError, solve_rocking
from rocking_cases import rectangular, ricker  # tests/ is on sys.path

G = G_STANDARD


def quiet(t):
    return 0.0


def energy(blk, theta, omega):
    """Energy per unit m g R above rest on a quiet floor: omega^2/(2 p^2) + cos(alpha - |theta|) - cos(alpha)."""
    return omega ** 2 / (2 * blk.p(G) ** 2) + np.cos(blk.alpha - np.abs(theta)) - math.cos(blk.alpha)


def apex_after(blk, level):
    """Tilt reached with energy ``level`` (units m g R) on a quiet floor: the root of
    cos(alpha - theta) - cos(alpha) = 2 sin(alpha - theta/2) sin(theta/2) = level."""
    return brentq(lambda th: 2 * math.sin(blk.alpha - th / 2) * math.sin(th / 2) - level, 0.0, blk.alpha,
                  xtol=1e-300, rtol=1e-15)


# ------------------------------------------------------------------------------------------ free rocking

@pytest.mark.parametrize("alpha", [0.05, 0.2])
def test_free_rocking_impact_times_match_the_exact_quarter_periods(alpha):
    """Released at theta0: the first impact after the exact quarter period, the second two quarter periods
    of the reduced amplitude later (energy times e^2), to 1e-9 relative."""
    blk = Block.from_slenderness(alpha, 1.0)
    theta0 = 0.5 * alpha
    res = solve_rocking(blk, quiet, 4.0, theta0=theta0, t_quiet=0.0)
    t1, t2 = res.impacts[0, 0], res.impacts[1, 0]
    assert t1 == pytest.approx(free_rocking_quarter_period(blk, theta0), rel=1e-9)
    theta1 = apex_after(blk, blk.e ** 2 * float(energy(blk, theta0, 0.0)))
    assert t2 - t1 == pytest.approx(2 * free_rocking_quarter_period(blk, theta1), rel=1e-9)
    assert res.theta_max == theta0 and res.t_theta_max == 0.0


@pytest.mark.parametrize("alpha", [0.05, 0.025])
def test_free_rocking_period_of_a_slender_block_matches_housner_to_order_alpha_squared(alpha):
    """Four times the time to the first impact is Housner's linearised period up to ~0.03 alpha^2 relative
    (the linearisation sin(alpha - theta) ~ alpha - theta drops a relative (alpha - theta)^2/6)."""
    blk = Block.from_slenderness(alpha, 1.5)
    theta0 = 0.5 * alpha
    res = solve_rocking(blk, quiet, 1.0, theta0=theta0, t_quiet=0.0)
    err = 4 * res.impacts[0, 0] / housner_period(blk, theta0) - 1
    assert 0 < err < alpha ** 2 / 6
    assert err == pytest.approx(0.0293 * alpha ** 2, rel=0.02)


def test_free_rocking_with_radau_gives_the_same_first_impact():
    blk = Block.from_slenderness(0.2, 1.0)
    res = solve_rocking(blk, quiet, 0.6, theta0=0.1, t_quiet=0.0, method="Radau")
    assert res.impacts[0, 0] == pytest.approx(free_rocking_quarter_period(blk, 0.1), rel=1e-8)


def test_energy_is_conserved_between_impacts_and_kept_in_the_ratio_e_squared_across_one():
    blk = Block.from_slenderness(0.2, 1.0, restitution=0.7)
    res = solve_rocking(blk, quiet, 1.5, theta0=0.15, t_quiet=0.0, history=True, max_impacts=2)
    h = res.history
    t1, t2 = res.impacts[0, 0], res.impacts[1, 0]
    E = energy(blk, h.theta, h.omega)
    before = (h.t <= t1) & (h.mode == 1)
    between = (h.t >= t1) & (h.t <= t2) & (h.mode == -1)
    assert before.sum() > 10 and between.sum() > 10
    E0 = float(energy(blk, 0.15, 0.0))
    assert np.max(np.abs(E[before] - E0)) < 1e-9 * E0
    assert np.max(np.abs(E[between] - 0.49 * E0)) < 1e-9 * E0
    w_in, w_out = res.impacts[0, 1], res.impacts[0, 2]
    assert w_in < 0 and w_out < 0                     # theta' keeps its sign through the impact
    assert (w_out / w_in) ** 2 == pytest.approx(0.49, rel=1e-14)


# ------------------------------------------------------------------------------------------ uplift

@pytest.mark.parametrize("shape", ["sine", "negative sine", "ricker", "sine with vertical"])
def test_uplift_starts_when_the_floor_acceleration_first_exceeds_the_uplift_level(shape):
    """Onset time equals the first time |A_F| > (g + a_v) tan(alpha), to 1e-9 relative; the corner is
    the one opposite to the floor's acceleration."""
    blk = Block.from_slenderness(0.15, 0.8)
    tan_a = math.tan(0.15)
    a_v, level = None, G * tan_a
    if shape == "ricker":
        A_F, T_p = ricker(1.5 * G * tan_a, 0.5), 0.5
        expected = brentq(lambda t: A_F(t) - level, -0.25, 0.0, xtol=1e-15, rtol=1e-15)
        t0, corner = -2 * T_p, -1
    else:
        sign = -1.0 if shape == "negative sine" else 1.0
        if shape == "sine with vertical":
            a_v, level = (lambda t: -0.3 * G), 0.7 * G * tan_a
        w = 2 * math.pi / 0.8

        def A_F(t):
            return sign * 2.0 * G * tan_a * math.sin(w * t) if 0 <= t < 0.8 else 0.0
        expected = math.asin(level / (2.0 * G * tan_a)) / w
        t0, corner = 0.0, -int(sign)
    res = solve_rocking(blk, A_F, 0.5, a_v=a_v, t0=t0, max_step=0.01, history=True)
    assert res.uplifts[0] == pytest.approx(expected, rel=1e-9, abs=1e-12)
    h = res.history
    first = np.flatnonzero(h.mode != 0)[0]
    assert h.mode[first] == corner and h.t[first] == res.uplifts[0]


def test_a_floor_below_the_uplift_level_leaves_the_block_at_rest():
    blk = Block.from_slenderness(0.15, 0.8)
    res = solve_rocking(blk, ricker(0.999 * G * math.tan(0.15), 0.5), 3.0, t0=-1.0, t_quiet=1.0,
                        max_step=0.01)
    assert res.theta_max == 0.0 and len(res.uplifts) == 0 and res.settled and res.n_impacts == 0


# ------------------------------------------------------------------------------------------ rectangular pulse

def _rectangular_errors(alpha):
    blk = Block.from_slenderness(alpha, 1.0)
    t_d = 1.0 / blk.p(G)
    a = -1.3 * G * alpha
    res = solve_rocking(blk, rectangular(a, t_d), 10.0, t_quiet=t_d, history=True, stop_when_decided=True)
    h = res.history
    t_hit = res.impacts[0, 0]
    on = h.t <= t_hit
    theta_lin, _ = rectangular_pulse_response(blk, a, t_d, h.t[on])
    err = np.max(np.abs(h.theta[on] - theta_lin)) / np.max(theta_lin)
    err_hit = t_hit / rectangular_pulse_first_impact(blk, a, t_d) - 1
    assert res.uplifts[0] == 0.0 and np.all(h.theta[on] >= 0)
    return err, err_hit


def test_rectangular_pulse_response_of_a_slender_block_matches_the_linearised_closed_form():
    """During the pulse and after it up to the first impact: the exact block differs from the
    linearised one by ~5 alpha^2 of the peak tilt, and the first impact by ~0.84 alpha^2 (relative);
    both errors shrink fourfold when alpha halves."""
    e1, h1 = _rectangular_errors(0.05)
    e2, h2 = _rectangular_errors(0.025)
    assert e1 < 6 * 0.05 ** 2 and e2 < 6 * 0.025 ** 2
    assert abs(h1) < 0.05 ** 2 and abs(h2) < 0.025 ** 2
    assert e1 / e2 == pytest.approx(4, rel=0.05)
    assert h1 / h2 == pytest.approx(4, rel=0.05)


def _overturn_threshold(alpha, p_td, rtol=1e-10):
    blk = Block.from_slenderness(alpha, 1.0)
    t_d = p_td / blk.p(G)

    def overturns(beta):
        res = solve_rocking(blk, rectangular(-beta * G * alpha, t_d), 30.0, t_quiet=t_d,
                            stop_when_decided=True, rtol=rtol)
        assert res.overturned or res.decided
        return res.overturned

    lo, hi = 1.0, 3.0
    while hi - lo > 1e-8 * hi:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if overturns(mid) else (mid, hi)
    return hi


def test_overturning_threshold_of_a_rectangular_pulse_by_bisection_matches_the_closed_form():
    """beta_c = 1 / (1 - exp(-p t_d)) for p t_d = 1: the exact slender block needs ~0.34 alpha^2 more
    (relative), fourfold less when alpha halves; the bisected threshold does not move with rtol."""
    beta_c = rectangular_overturn_ratio(1.0)
    b1 = _overturn_threshold(0.05, 1.0)
    b2 = _overturn_threshold(0.025, 1.0)
    d1, d2 = b1 / beta_c - 1, b2 / beta_c - 1
    assert 0 < d1 < 0.05 ** 2 / 2 and 0 < d2 < 0.025 ** 2 / 2
    assert d1 / d2 == pytest.approx(4, rel=0.05)
    assert _overturn_threshold(0.05, 1.0, rtol=1e-8) == pytest.approx(b1, rel=2e-8)


def test_an_overturning_block_reports_the_time_it_reaches_pi_over_2():
    blk = Block.from_slenderness(0.05, 1.0)
    t_d = 1.0 / blk.p(G)
    res = solve_rocking(blk, rectangular(-2.0 * G * 0.05, t_d), 30.0, t_quiet=t_d, history=True)
    assert res.overturned and res.theta_max == math.pi / 2 and res.n_impacts == 0
    assert res.t_overturn == res.t_end and res.history.theta[-1] == math.pi / 2
    assert t_d < res.t_overturn < 30.0


# ------------------------------------------------------------------------------------------ symmetry

def test_mirrored_floor_motion_gives_the_exactly_mirrored_response():
    """A_F -> -A_F gives theta -> -theta bit for bit (with vertical motion and friction checks)."""
    blk = Block.from_slenderness(0.2, 1.0)
    A_F = ricker(2.0 * G * math.tan(0.2), 0.5)

    def A_F_mirrored(t):
        return -A_F(t)

    def a_v(t):
        return 0.2 * A_F(t + 0.1)

    kw = dict(a_v=a_v, t0=-1.0, t_quiet=1.0, mu_s=0.9, max_step=0.01, history=True)
    r = solve_rocking(blk, A_F, 30.0, **kw)
    m = solve_rocking(blk, A_F_mirrored, 30.0, **kw)
    assert r.n_impacts > 5 and r.theta_max > 0.1 * blk.alpha
    assert np.array_equal(m.history.t, r.history.t)
    assert np.array_equal(m.history.theta, -r.history.theta)
    assert np.array_equal(m.history.omega, -r.history.omega)
    assert np.array_equal(m.history.mode, -r.history.mode)
    assert np.array_equal(m.impacts[:, 0], r.impacts[:, 0])
    assert np.array_equal(m.impacts[:, 1:], -r.impacts[:, 1:])
    assert (m.theta_max, m.n_impacts, m.t_rest, m.settled) == (r.theta_max, r.n_impacts, r.t_rest, r.settled)


# ------------------------------------------------------------------------------------------ end of the cascade

def test_free_rocking_cascade_ends_after_the_predicted_impact_and_within_its_time_bound():
    """On a quiet floor the energy after n impacts is e^(2n) E0; the rule declares rest at the first impact
    where it is below the energy of a tilt theta_eps, and the remaining excursions (two exact quarter periods
    each) add up to less than rest_by - t_rest."""
    blk = Block.from_slenderness(0.2, 1.0)
    theta0, eps = 0.1, 1e-3 * 0.2
    res = solve_rocking(blk, quiet, 100.0, theta0=theta0, t_quiet=0.0, history=True)
    E0 = float(energy(blk, theta0, 0.0))
    level = float(energy(blk, eps, 0.0))
    n_pred = math.ceil(math.log(level / E0) / math.log(blk.e ** 2))
    assert res.n_impacts == n_pred
    assert res.settled and res.mode_end == 0 and res.t_rest == res.impacts[-1, 0] and res.t_end == res.t_rest
    h = res.history
    assert h.mode[-1] == 0 and h.theta[-1] == 0.0
    remaining, E = 0.0, blk.e ** (2 * n_pred) * E0
    while E > 1e-40 * E0:
        remaining += 2 * free_rocking_quarter_period(blk, apex_after(blk, E))
        E *= blk.e ** 2
    assert remaining < res.rest_by - res.t_rest < 1.2 * remaining


@pytest.mark.parametrize("ratio,restitution", [(1.1, None), (1.3, 0.7)])
def test_a_cascade_during_floor_motion_lands_and_never_again_passes_theta_eps(ratio, restitution):
    """The moving-floor rule: rerun with a theta_eps a thousand times smaller, the block stays below the first
    run's theta_eps after its landing and comes to rest again before that run's rest_by."""
    alpha = 0.2
    blk = Block.from_slenderness(alpha, 1.0, restitution=restitution)
    A_F, T_p = ricker(ratio * G * math.tan(alpha), 2.0), 2.0
    kw = dict(t0=-2 * T_p, t_quiet=2 * T_p, max_step=T_p / 64)
    first = solve_rocking(blk, A_F, 20.0, **kw)
    assert first.settled and first.t_rest < 2 * T_p         # landed while the floor still moved
    fine = solve_rocking(blk, A_F, 20.0, theta_eps=1e-6 * alpha, history=True, **kw)
    assert fine.settled and fine.n_impacts > first.n_impacts
    after = fine.history.t >= first.t_rest
    assert np.max(np.abs(fine.history.theta[after])) <= 1e-3 * alpha
    assert fine.impacts[-1, 0] <= first.rest_by


def test_impacts_are_counted_and_a_run_stops_with_a_clear_error_past_max_impacts():
    blk = Block.from_slenderness(0.2, 1.0)
    with pytest.raises(RuntimeError, match=r"more than max_impacts = 3 impacts by t = "):
        solve_rocking(blk, quiet, 100.0, theta0=0.1, t_quiet=0.0, max_impacts=3)


def test_stop_when_decided_ends_at_the_first_impact_that_cannot_raise_the_peak():
    blk = Block.from_slenderness(0.05, 1.0)
    t_d = 1.0 / blk.p(G)
    res = solve_rocking(blk, rectangular(-1.3 * G * 0.05, t_d), 100.0, t_quiet=t_d, stop_when_decided=True)
    full = solve_rocking(blk, rectangular(-1.3 * G * 0.05, t_d), 10.0, t_quiet=t_d)
    assert res.decided and res.n_impacts == 1 and not res.overturned and res.t_end == res.impacts[0, 0]
    assert full.theta_max == res.theta_max and full.n_impacts > 5 and not full.decided


# ------------------------------------------------------------------------------------------ contact checks

def test_sliding_before_uplift_raises_naming_the_time_friction_is_exceeded():
    """mu_s < b/h: the floor exceeds mu_s g before g tan(alpha), at t = asin(mu_s g / a) / w."""
    blk = Block.from_slenderness(0.2, 1.0)
    a, w = 2.0 * G * math.tan(0.2), 2 * math.pi

    def A_F(t):
        return a * math.sin(w * t) if 0 <= t < 1 else 0.0
    with pytest.raises(RockingContactError) as err:
        solve_rocking(blk, A_F, 1.0, mu_s=0.1, max_step=0.01)
    expected = math.asin(0.1 * G / a) / w
    assert err.value.kind == "slide" and err.value.time == pytest.approx(expected, rel=1e-9)
    assert f"t = {err.value.time!r} s" in str(err.value) and "mu_s = 0.1" in str(err.value)
    assert "slide-rock" in str(err.value)


def test_sliding_while_rocking_raises_naming_the_time():
    """Released at theta0 = 0.1 (alpha = 0.2) the pivot needs |H|/V = 0.075 at once."""
    blk = Block.from_slenderness(0.2, 1.0)
    with pytest.raises(RockingContactError, match=r"would slide at t = 0\.0 s \(rocking\)") as err:
        solve_rocking(blk, quiet, 1.0, theta0=0.1, mu_s=0.05)
    assert err.value.kind == "slide"
    res = solve_rocking(blk, quiet, 1.0, theta0=0.1, mu_s=0.5)   # enough friction
    assert res.n_impacts == 1 and res.t_end == 1.0


def test_flight_at_rest_raises_at_the_time_the_floor_falls_faster_than_gravity():
    blk = Block.from_slenderness(0.2, 1.0)
    with pytest.raises(RockingContactError, match="would leave the floor") as err:
        solve_rocking(blk, quiet, 2.0, a_v=lambda t: -2.0 * G * t, max_step=0.05)
    assert err.value.kind == "flight" and err.value.time == pytest.approx(0.5, rel=1e-12)


def test_flight_while_rocking_raises_naming_the_time():
    blk = Block.from_slenderness(0.2, 1.0)
    t1 = free_rocking_quarter_period(blk, 0.1)
    with pytest.raises(RockingContactError, match=r"would leave the floor at t = .* s \(rocking\)") as err:
        solve_rocking(blk, quiet, 2.0, theta0=0.1, a_v=lambda t: -4.0 * G * t, max_step=0.01)
    assert err.value.kind == "flight" and 0.0 < err.value.time < 0.25 < t1


# ------------------------------------------------------------------------------------------ bad input

@pytest.mark.parametrize("kwargs,pattern", [
    (dict(A_F=3.0), r"A_F = 3\.0 is not callable"),
    (dict(a_v="x"), r"a_v = 'x' is not callable"),
    (dict(t_end=0.0), r"t_end = 0\.0 is out of range; allowed range: 0 < value < inf"),
    (dict(g=-9.81), r"g = -9\.81 is out of range"),
    (dict(theta0=2.0), r"theta0 = 2\.0 is out of range; allowed range: -1\.5708 < value < 1\.5708"),
    (dict(mu_s=-1.0), r"mu_s = -1\.0 is out of range"),
    (dict(theta_eps=0.3), r"theta_eps = 0\.3 is out of range; allowed range: 0 < value < 0\.2"),
    (dict(method="RK45"), r"method = 'RK45' is invalid; allowed: one of \('DOP853', 'Radau'\)"),
    (dict(max_impacts=0), r"max_impacts = 0 is invalid; allowed: a positive integer"),
    (dict(max_step=0.0), r"max_step = 0\.0 is out of range"),
    (dict(block="block"), r"block = 'block' is invalid"),
])
def test_bad_peer_input_errors_name_the_parameter_value_and_range(kwargs, pattern):
    args = dict(block=Block.from_slenderness(0.2, 1.0), A_F=quiet, t_end=1.0)
    args.update(kwargs)
    with pytest.raises(ValueError, match=pattern):
        solve_rocking(args.pop("block"), args.pop("A_F"), args.pop("t_end"), **args)
