"""Tests of isoslide.pulses: normalisation, kernel/numpy agreement, exact kinematics."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad
from scipy.optimize import minimize_scalar

from isoslide import pulses as P

# Every analytical shape, plus non-default shape parameters.
CASES = {
    "ricker": {},
    "rectangular": {},
    "antisymmetric_ricker": {},
    "makris_a": {},
    "makris_b": {},
    "makris_cn": {},
    "makris_cn-n2": {"n": 2},
    "makris_cn-n3": {"n": 3},
    "mavroeidis_papageorgiou": {},
    "mavroeidis_papageorgiou-g1.5-nu0": {"gamma": 1.5, "nu": 0.0},
    "mavroeidis_papageorgiou-g3-nu90deg": {"gamma": 3.0, "nu": math.pi / 2},
    "mavroeidis_papageorgiou-g2.3-nu1": {"gamma": 2.3, "nu": 1.0},
}


def make(case: str) -> P.Pulse:
    return P.get_pulse(case.split("-")[0], **CASES[case])


ALL = pytest.mark.parametrize("case", list(CASES))


def nb_accel(pulse, tau):
    pa = pulse.param_array
    return np.array([P.accel_at(pulse.code, pa, float(t)) for t in np.ravel(tau)])


def nb_jerk(pulse, tau):
    pa = pulse.param_array
    return np.array([P.jerk_at(pulse.code, pa, float(t)) for t in np.ravel(tau)])


def pieces(pulse):
    """Smooth pieces [a, b) of the support, delimited by tau_start, breakpoints and tau_end."""
    edges = sorted({pulse.tau_start, pulse.tau_end}
                   | {float(b) for b in pulse.breakpoints if pulse.tau_start < b < pulse.tau_end})
    return list(zip(edges[:-1], edges[1:], strict=False))


def integrate(f, a, b, pulse):
    """High-accuracy integral of a scalar function across the pulse's breakpoints."""
    pts = [x for x in (pulse.tau_start, pulse.tau_end, *pulse.breakpoints) if a < x < b]
    val, err = quad(f, a, b, points=pts or None, epsabs=1e-13, epsrel=1e-12, limit=200)
    return val


def test_registry_names():
    assert P.PULSE_NAMES == ("ricker", "rectangular", "antisymmetric_ricker", "makris_a",
                             "makris_b", "makris_cn", "mavroeidis_papageorgiou")
    codes = {P.get_pulse(n).code for n in P.PULSE_NAMES}
    assert codes == {P.RICKER, P.RECTANGULAR, P.ANTISYMMETRIC_RICKER, P.MAKRIS_A, P.MAKRIS_B,
                     P.MAKRIS_CN, P.MAVROEIDIS_PAPAGEORGIOU}


@ALL
def test_peak_abs_accel_is_one(case):
    """max |p| = 1: no grid point exceeds 1, and the refined peak equals 1 to 1e-13."""
    pulse = make(case)
    tau = np.concatenate([np.linspace(pulse.tau_start, pulse.tau_end, 40001), pulse.breakpoint_array])
    y = np.abs(nb_accel(pulse, tau))
    assert y.max() <= 1.0 + 1e-15
    i = int(np.argmax(y))
    h = (pulse.tau_end - pulse.tau_start) / 40000
    lo, hi = max(tau[i] - h, pulse.tau_start), min(tau[i] + h, np.nextafter(pulse.tau_end, -np.inf))
    res = minimize_scalar(lambda t: -abs(P.accel_at(pulse.code, pulse.param_array, t)),
                          bounds=(lo, hi), method="bounded", options={"xatol": 1e-12})
    peak = max(-res.fun, y[i])
    assert abs(peak - 1.0) < 1e-13


def test_antisymmetric_ricker_matches_vassiliou_makris_form():
    """p = (1/1.38) (4 pi^2 tau^2/3 - 3)(2 pi tau/sqrt 3) exp(-2 pi^2 tau^2/3), peaks at -/+0.2045."""
    pulse = P.antisymmetric_ricker()
    assert P.ANTISYMMETRIC_RICKER_BETA == pytest.approx(1.38, abs=5e-4)
    tau = np.linspace(-2.4, 2.4, 97)
    lit = ((4 * math.pi**2 * tau**2 / 3 - 3) * (2 * math.pi * tau / math.sqrt(3))
           * np.exp(-2 * math.pi**2 * tau**2 / 3)) / P.ANTISYMMETRIC_RICKER_BETA
    np.testing.assert_allclose(pulse.accel(tau), lit, rtol=0, atol=1e-15)
    t_star = math.sqrt(3 - math.sqrt(6)) * math.sqrt(3) / (2 * math.pi)
    assert pulse.accel(-t_star) == pytest.approx(1.0, abs=1e-15)
    assert pulse.accel(t_star) == pytest.approx(-1.0, abs=1e-15)


@ALL
def test_numba_and_numpy_accel_agree(case):
    """The compiled scalar and the vectorised numpy evaluators agree, breakpoints included."""
    pulse = make(case)
    bps = np.array([pulse.tau_start, pulse.tau_end, *pulse.breakpoints], dtype=float)
    tau = np.concatenate([
        np.linspace(pulse.tau_start - 0.5, pulse.tau_end + 0.5, 3001),
        bps, np.nextafter(bps, -np.inf), np.nextafter(bps, np.inf),
    ])
    np.testing.assert_allclose(nb_accel(pulse, tau), pulse.accel(tau), rtol=0, atol=2e-15)


@ALL
def test_zero_outside_support_and_right_continuous(case):
    pulse = make(case)
    outside = np.array([pulse.tau_start - 1.0, np.nextafter(pulse.tau_start, -np.inf),
                        pulse.tau_end, pulse.tau_end + 1.0])
    assert np.all(nb_accel(pulse, outside) == 0.0)
    assert np.all(nb_jerk(pulse, outside) == 0.0)
    assert np.all(pulse.accel(outside) == 0.0)
    # right-continuity: the value at a breakpoint is the limit from the right
    for b in pulse.breakpoint_array[:-1]:
        right = nb_accel(pulse, [b + 1e-9])[0]
        assert nb_accel(pulse, [b])[0] == pytest.approx(right, abs=1e-7)


@ALL
def test_ground_at_rest_at_start(case):
    pulse = make(case)
    before = np.array([pulse.tau_start - 3.0, pulse.tau_start - 0.1, pulse.tau_start])
    assert np.all(np.abs(pulse.velocity(before)) <= 1e-16)
    assert np.all(np.abs(pulse.displacement(before)) <= 1e-16)


@ALL
def test_velocity_is_integral_of_accel(case):
    """v(tau_k) - v(tau_{k-1}) = integral of accel_at (adaptive quadrature) on every subinterval."""
    pulse = make(case)
    tau = np.linspace(pulse.tau_start - 0.2, pulse.tau_end + 0.3, 41)
    pa = pulse.param_array
    steps = [integrate(lambda t: P.accel_at(pulse.code, pa, t), a, b, pulse)
             for a, b in zip(tau[:-1], tau[1:], strict=False)]
    expected = np.concatenate([[0.0], np.cumsum(steps)])
    np.testing.assert_allclose(pulse.velocity(tau), expected, rtol=0, atol=1e-12)


@ALL
def test_displacement_is_integral_of_velocity(case):
    pulse = make(case)
    tau = np.linspace(pulse.tau_start - 0.2, pulse.tau_end + 0.3, 41)
    steps = [integrate(lambda t: float(pulse.velocity(t)), a, b, pulse)
             for a, b in zip(tau[:-1], tau[1:], strict=False)]
    expected = np.concatenate([[0.0], np.cumsum(steps)])
    np.testing.assert_allclose(pulse.displacement(tau), expected, rtol=0, atol=1e-12)


@ALL
def test_jerk_is_derivative_of_accel(case):
    """Inside each smooth piece: p(b-) - p(a) = integral of jerk_at, on a fine partition;
    plus a 6th-order central difference at interior points."""
    pulse = make(case)
    pa = pulse.param_array
    for a, b in pieces(pulse):
        edges = np.linspace(a, b, 21)
        for lo, hi in zip(edges[:-1], edges[1:], strict=False):
            hi_in = np.nextafter(hi, -np.inf) if hi == b else hi
            dp = P.accel_at(pulse.code, pa, hi_in) - P.accel_at(pulse.code, pa, lo)
            ij, _ = quad(lambda t: P.jerk_at(pulse.code, pa, t), lo, hi_in, epsabs=1e-14, epsrel=1e-13)
            assert dp == pytest.approx(ij, abs=1e-12)
        h = 1e-3
        c = np.array([-1, 9, -45, 0, 45, -9, 1]) / (60 * h)
        for x in np.linspace(a, b, 9)[1:-1]:
            fd = sum(ci * P.accel_at(pulse.code, pa, x + k * h) for ci, k in zip(c, range(-3, 4), strict=False))
            assert P.jerk_at(pulse.code, pa, x) == pytest.approx(fd, abs=1e-8)


def test_jerk_is_right_derivative_at_breakpoints():
    pa = P.makris_a().param_array
    assert P.jerk_at(P.MAKRIS_A, pa, 0.0) == pytest.approx(2 * math.pi)
    assert P.jerk_at(P.MAKRIS_A, pa, 1.0) == 0.0


# Final ground velocity and displacement (units a_p T_p, a_p T_p^2); None = not zero, checked
# against quadrature by the tests above.
FINAL = {
    "ricker": (0.0, 0.0),
    "rectangular": (1.0, 0.5),
    "antisymmetric_ricker": (0.0, 0.0),
    "makris_a": (0.0, 1 / (2 * math.pi)),
    "makris_b": (0.0, 0.0),
    "makris_cn": (0.0, 0.0),
    "makris_cn-n2": (0.0, 0.0),
    "makris_cn-n3": (0.0, 0.0),
    "mavroeidis_papageorgiou": (0.0, 0.0),
    "mavroeidis_papageorgiou-g1.5-nu0": (0.0, None),
    "mavroeidis_papageorgiou-g3-nu90deg": (0.0, 0.0),
    "mavroeidis_papageorgiou-g2.3-nu1": (0.0, None),
}


@ALL
def test_final_velocity_and_displacement(case):
    """Zero mean (zero final velocity) and zero final displacement where the shape has them."""
    pulse = make(case)
    v_end, d_end = FINAL[case]
    late = np.array([pulse.tau_end, pulse.tau_end + 2.0])
    assert pulse.final_velocity == pytest.approx(v_end, abs=1e-15)
    np.testing.assert_allclose(pulse.velocity(late), v_end, atol=1e-15)
    if d_end is None:
        assert abs(pulse.final_displacement) > 1e-3
    else:
        assert pulse.final_displacement == pytest.approx(d_end, abs=1e-15)
        np.testing.assert_allclose(pulse.displacement(late), d_end + v_end * (late - pulse.tau_end),
                                   atol=1e-15)


def test_makris_cn_phase_matches_literature():
    """phi = 0.0697 pi (C1) and 0.0410 pi (C2), Makris & Chang (2000)."""
    assert P.makris_cn_phase(1) / math.pi == pytest.approx(0.0697, abs=5e-5)
    assert P.makris_cn_phase(2) / math.pi == pytest.approx(0.0410, abs=5e-5)
    c1 = P.makris_cn(1)
    assert c1.tau_end == pytest.approx(1.5 - 0.0697, abs=1e-4)
    assert c1.accel(0.0) == pytest.approx(math.cos(P.makris_cn_phase(1)))


def _fourier_peak(pulse, n=8001):
    tau = np.linspace(pulse.tau_start, pulse.tau_end, n)
    p = pulse.accel(tau)
    dt = tau[1] - tau[0]

    def neg_amp(f):
        return -abs(np.sum(p * np.exp(-2j * np.pi * f * tau)) * dt)

    return minimize_scalar(neg_amp, bounds=(0.3, 3.0), method="bounded", options={"xatol": 1e-10}).x


@pytest.mark.parametrize("name", ["ricker", "antisymmetric_ricker"])
def test_ricker_fourier_amplitude_peaks_at_one_over_tp(name):
    assert _fourier_peak(P.get_pulse(name)) == pytest.approx(1.0, abs=1e-6)


def test_ricker_is_paper_eq3():
    tau = np.linspace(-1.9, 1.9, 77)
    np.testing.assert_allclose(P.ricker().accel(tau),
                               (1 - 2 * np.pi**2 * tau**2) * np.exp(-np.pi**2 * tau**2), atol=1e-15)


def test_mavroeidis_papageorgiou_velocity_is_mp2003_form():
    """Velocity is proportional to (1 + cos(2 pi tau/gamma)) cos(2 pi tau + nu) on the support."""
    gamma, nu = 2.3, 1.0
    pulse = P.mavroeidis_papageorgiou(gamma, nu)
    tau = np.linspace(-gamma / 2, gamma / 2, 101)
    shape = (1 + np.cos(2 * np.pi * tau / gamma)) * np.cos(2 * np.pi * tau + nu)
    v = pulse.velocity(tau)
    k = v[50] / shape[50]
    np.testing.assert_allclose(v, k * shape, atol=1e-15)
    assert k == pytest.approx(pulse.params[2] / (2 * np.pi), rel=1e-14)


@settings(max_examples=12, deadline=None)
@given(gamma=st.floats(1.01, 6.0), nu=st.floats(-math.pi, math.pi))
def test_mavroeidis_papageorgiou_property(gamma, nu):
    pulse = P.mavroeidis_papageorgiou(gamma, nu)
    tau = np.linspace(pulse.tau_start, pulse.tau_end, 6001)
    y = np.abs(nb_accel(pulse, tau))
    assert y.max() <= 1.0 + 1e-14
    assert y.max() > 1.0 - 1e-5  # grid resolution only
    pa = pulse.param_array
    total = integrate(lambda t: P.accel_at(pulse.code, pa, t), pulse.tau_start, pulse.tau_end, pulse)
    assert pulse.final_velocity == pytest.approx(total, abs=1e-12)
    dtot = integrate(lambda t: float(pulse.velocity(t)), pulse.tau_start, pulse.tau_end, pulse)
    assert pulse.final_displacement == pytest.approx(dtot, abs=1e-12)


# --------------------------------------------------------------------------- sampled records

def test_sampled_triangle_exact():
    """Triangle 0 -> 1 -> 0 over [0, 2]: v and d by hand."""
    pulse = P.sampled([0.0, 1.0, 0.0], dtau=1.0)
    tau = np.array([-1.0, 0.0, 0.5, 1.0, 1.5, 2.0, 3.0])
    v = np.array([0, 0, 0.125, 0.5, 0.875, 1.0, 1.0])
    d = np.array([0, 0, 0.5**3 / 6, 1 / 6, 1 / 6 + 0.5 * 0.5 + 0.5 * 0.25 - 0.5**3 / 6, 1.0, 2.0])
    np.testing.assert_allclose(pulse.velocity(tau), v, atol=1e-15)
    np.testing.assert_allclose(pulse.displacement(tau), d, atol=1e-15)


def test_sampled_random_record_exact_integration():
    rng = np.random.default_rng(7)
    acc = rng.normal(size=40)
    pulse = P.sampled(acc, dtau=0.037, tau0=0.1)
    pa = pulse.param_array
    tau = np.linspace(0.0, pulse.tau_end + 0.2, 57)
    tau = np.concatenate([tau, pulse.breakpoint_array])
    tau.sort()
    v_q = np.concatenate([[0.0], np.cumsum([integrate(lambda t: P.accel_at(P.SAMPLED, pa, t), a, b, pulse)
                                            for a, b in zip(tau[:-1], tau[1:], strict=False)])])
    np.testing.assert_allclose(pulse.velocity(tau), v_q, atol=1e-12)
    d_q = np.concatenate([[0.0], np.cumsum([integrate(lambda t: float(pulse.velocity(t)), a, b, pulse)
                                            for a, b in zip(tau[:-1], tau[1:], strict=False)])])
    np.testing.assert_allclose(pulse.displacement(tau), d_q, atol=1e-12)
    # accel at the knots is the sample itself; numpy and numba agree between them
    knots = np.array(pulse.breakpoints)
    np.testing.assert_array_equal(nb_accel(pulse, knots), acc[:-1])
    mid = knots + 0.5 * 0.037
    np.testing.assert_allclose(nb_accel(pulse, mid), pulse.accel(mid), atol=1e-15)


def test_sampled_jerk_at_knot_is_slope_of_next_segment():
    """A knot where (tau - tau0)/dtau rounds below the integer still starts the next segment."""
    acc = np.arange(12, dtype=float) ** 2
    pulse = P.sampled(acc, dtau=0.1, tau0=0.3)
    pa = pulse.param_array
    slopes = np.diff(acc) / 0.1
    knots = np.array(pulse.breakpoints)
    assert any(math.floor((k - 0.3) / 0.1) != i for i, k in enumerate(knots))  # the trap exists
    np.testing.assert_allclose([P.jerk_at(P.SAMPLED, pa, k) for k in knots], slopes, rtol=1e-12)
    assert P.jerk_at(P.SAMPLED, pa, pulse.tau_end) == 0.0


@pytest.mark.parametrize("kwargs, name", [
    ({"accel": [1.0, 2.0], "dtau": 0.0}, "dtau"),
    ({"accel": [1.0, 2.0], "dtau": float("nan")}, "dtau"),
    ({"accel": [1.0, 2.0], "dtau": 0.1, "tau0": float("inf")}, "tau0"),
    ({"accel": [1.0], "dtau": 0.1}, "accel"),
    ({"accel": [1.0, float("nan")], "dtau": 0.1}, "accel"),
])
def test_sampled_rejects_bad_input(kwargs, name):
    with pytest.raises(ValueError, match=name):
        P.sampled(**kwargs)


# --------------------------------------------------------------------------- validation, identity

@pytest.mark.parametrize("name, params, bad", [
    ("makris_cn", {"n": 0}, "n"),
    ("makris_cn", {"n": 1.5}, "n"),
    ("makris_cn", {"n": True}, "n"),
    ("makris_cn", {"n": "two"}, "n"),
    ("mavroeidis_papageorgiou", {"gamma": 1.0}, "gamma"),
    ("mavroeidis_papageorgiou", {"gamma": 0.5}, "gamma"),
    ("mavroeidis_papageorgiou", {"gamma": float("nan")}, "gamma"),
    ("mavroeidis_papageorgiou", {"gamma": 1e4}, "gamma"),
    ("mavroeidis_papageorgiou", {"nu": 90.0}, "nu"),
    ("mavroeidis_papageorgiou", {"nu": "x"}, "nu"),
    ("mavroeidis_papageorgiou", {"gama": 2.0}, "gama"),
    ("ricker", {"n": 2}, "n"),
])
def test_bad_shape_params_raise_valueerror_naming_them(name, params, bad):
    with pytest.raises(ValueError, match=rf"^{bad} = .*allowed"):
        P.get_pulse(name, **params)


def test_unknown_pulse_name():
    with pytest.raises(ValueError, match="pulse = 'gabor'.*allowed"):
        P.get_pulse("gabor")


def test_integral_n_as_float_accepted():
    assert P.get_pulse("makris_cn", n=2.0) == P.makris_cn(2)


def test_pulse_is_frozen_hashable_and_deterministic():
    a = P.get_pulse("mavroeidis_papageorgiou", gamma=2.5, nu=0.3)
    b = P.mavroeidis_papageorgiou(gamma=2.5, nu=0.3)
    assert a == b and hash(a) == hash(b)
    assert isinstance(a.params, tuple)
    assert len({P.get_pulse(n) for n in P.PULSE_NAMES}) == len(P.PULSE_NAMES)
    with pytest.raises(dataclasses.FrozenInstanceError):
        a.tau_end = 3.0
    assert P.get_pulse(a) is a
    with pytest.raises(ValueError):
        P.get_pulse(a, gamma=3.0)


@ALL
def test_breakpoint_array_ends_at_tau_end(case):
    pulse = make(case)
    b = pulse.breakpoint_array
    assert b[-1] == pulse.tau_end and np.all(np.diff(b) > 0) and b[0] > pulse.tau_start
