"""Intensity measures of a pair of horizontal components (isoslide.studies.intensity): RotDnn of PGA,
PGV and Sa against their definition (Boore 2010)."""

import math

import numpy as np
import pytest
from scipy import signal

from isoslide.studies import intensity as im

DT = 0.01


def _record(n=2000, seed=3, lag=0):
    """A smooth random acceleration from rest (m/s^2), tapered to zero at both ends."""
    rng = np.random.default_rng(seed)
    a = np.convolve(rng.standard_normal(n + 40), np.hanning(25), mode="same")[20:20 + n]
    a *= np.hanning(n)
    a[0] = 0.0
    return np.roll(a, lag)


def _by_definition(ax, ay, dt, what):
    """The peak of every rotated component, one angle at a time, with the 1-D peaks of the package."""
    peaks = []
    for deg in im.ROTD_ANGLES:
        t = math.radians(deg)
        comp = ax * math.cos(t) + ay * math.sin(t)
        pga, pgv = im.ground_peaks(comp / 9.80665, dt)
        peaks.append(pga if what == "pga" else pgv)
    return np.array(peaks)


def test_rotd50_of_a_pair_along_one_line_is_the_peak_times_cos_45_degrees():
    """A pair a(t) (cos phi, sin phi) is a(t) cos(theta - phi) along theta: the median of
    |cos(theta - phi)| over theta = 0 ... 179 degrees (phi a whole degree) is cos 45 degrees exactly."""
    a = _record()
    for phi in (0.0, 30.0, 117.0):
        ax, ay = a * math.cos(math.radians(phi)), a * math.sin(math.radians(phi))
        pga, pgv = im.pair_peaks(ax, ay, DT)
        pga1, pgv1 = im.ground_peaks(a / 9.80665, DT)
        assert pga == pytest.approx(pga1 * math.sqrt(0.5), rel=1e-12)
        assert pgv == pytest.approx(pgv1 * math.sqrt(0.5), rel=1e-12)
        # RotD100 is the peak along the line, RotD0 (the direction across it) nothing
        assert im.rotd(im.rotated_peaks(ax, ay), 100) == pytest.approx(pga1, rel=1e-12)
        sa = im.pair_sa(ax, ay, DT, 2.0)
        d = im.oscillator_displacement(a, DT, 2.0)
        assert sa == pytest.approx((2 * math.pi / 2.0) ** 2 * np.max(np.abs(d)) * math.sqrt(0.5), rel=1e-12)


@pytest.mark.parametrize("alpha", [37.0, -90.0, 151.0])
def test_rotd_does_not_change_when_the_pair_is_rotated_by_whole_degrees(alpha):
    ax, ay = _record(seed=1), 0.6 * _record(seed=2)
    c, s = math.cos(math.radians(alpha)), math.sin(math.radians(alpha))
    bx, by = c * ax - s * ay, s * ax + c * ay
    for p in (50.0, 100.0, 0.0):
        assert im.rotd(im.rotated_peaks(bx, by), p) == pytest.approx(im.rotd(im.rotated_peaks(ax, ay), p), rel=1e-12)
        assert im.rotd(im.rotated_velocity_peaks(bx, by, DT), p) == pytest.approx(
            im.rotd(im.rotated_velocity_peaks(ax, ay, DT), p), rel=1e-12)
    assert im.pair_sa(bx, by, DT, 1.5) == pytest.approx(im.pair_sa(ax, ay, DT, 1.5), rel=1e-12)


def test_rotd_of_a_pair_rotated_by_a_fraction_of_a_degree_moves_by_less_than_the_grid():
    ax, ay = _record(seed=1), 0.6 * _record(seed=2)
    c, s = math.cos(math.radians(12.5)), math.sin(math.radians(12.5))
    pga, pgv = im.pair_peaks(c * ax - s * ay, s * ax + c * ay, DT)
    pga0, pgv0 = im.pair_peaks(ax, ay, DT)
    assert pga == pytest.approx(pga0, rel=0.02) and pgv == pytest.approx(pgv0, rel=0.02)


def test_a_circular_motion_has_rotd50_equal_to_its_radius():
    """a = A (cos wt, sin wt): every rotated component is A cos(wt - theta), so every RotDnn is A
    (sampled 2000 times a cycle: the crest between samples is missed by at most (pi/2000)^2/2)."""
    A, n_cycle = 3.0, 2000
    t = np.arange(5 * n_cycle + 1) / n_cycle
    ax, ay = A * np.cos(2 * np.pi * t), A * np.sin(2 * np.pi * t)
    peaks = im.rotated_peaks(ax, ay)
    assert np.all(np.abs(peaks - A) <= A * 0.5 * (np.pi / n_cycle) ** 2 * 1.01)
    for p in (0.0, 50.0, 100.0):
        assert im.rotd(peaks, p) == pytest.approx(A, rel=2e-6)


def test_rotated_peaks_agree_with_the_peaks_of_each_rotated_component_by_definition():
    """The vectorised peaks against a loop over the angles with the 1-D peaks (PGV exact between samples)."""
    ax, ay = _record(seed=4), 0.8 * _record(seed=5, lag=37)
    np.testing.assert_allclose(im.rotated_peaks(ax, ay), _by_definition(ax, ay, DT, "pga"), rtol=1e-13)
    np.testing.assert_allclose(im.rotated_velocity_peaks(ax, ay, DT), _by_definition(ax, ay, DT, "pgv"),
                               rtol=1e-12)
    pga, pgv = im.pair_peaks(ax, ay, DT)
    assert pga == pytest.approx(np.median(_by_definition(ax, ay, DT, "pga")), rel=1e-13)
    assert pgv == pytest.approx(np.median(_by_definition(ax, ay, DT, "pgv")), rel=1e-12)


@pytest.mark.parametrize("period, damping", [(0.3, 0.05), (2.5, 0.05), (4.0, 0.0)])
def test_oscillator_displacement_is_scipys_exact_linear_interpolation_response(period, damping):
    """scipy.signal.lsim integrates an input linear between samples exactly (matrix exponential)."""
    a = _record(n=1500, seed=6)
    d = im.oscillator_displacement(a, DT, period, damping, free_periods=0.0)
    w = 2 * math.pi / period
    sys = signal.lti([[0.0, 1.0], [-w * w, -2 * damping * w]], [[0.0], [-1.0]], [[1.0, 0.0]], [[0.0]])
    _, ref, _ = signal.lsim(sys, a, DT * np.arange(a.size))
    np.testing.assert_allclose(d, ref, rtol=0, atol=1e-10 * np.max(np.abs(ref)))


def test_the_free_vibration_after_the_record_is_searched_for_the_peak():
    """A short pulse drives a long-period oscillator whose peak comes after the record ends."""
    a = np.zeros(50)
    a[1:10] = 1.0
    d = im.oscillator_displacement(a, DT, 4.0, 0.05, free_periods=1.0)
    assert d.size == 50 + 400
    assert int(np.argmax(np.abs(d))) > 50
    assert np.max(np.abs(d)) > 1.5 * np.max(np.abs(d[:50]))
    sa = im.pair_sa(a, np.zeros_like(a), DT, 4.0)     # one line: RotD50 = the peak times cos 45 degrees
    assert sa == pytest.approx((2 * math.pi / 4) ** 2 * np.max(np.abs(d)) * math.sqrt(0.5), rel=1e-12)


def test_align_pair_pads_with_zeros_and_refuses_a_fractional_lag():
    x, y = im.align_pair([1.0, 2.0, 3.0], [5.0, 6.0], 0.01, t0_x=0.0, t0_y=0.02)
    np.testing.assert_array_equal(x, [1, 2, 3, 0])
    np.testing.assert_array_equal(y, [0, 0, 5, 6])
    x, y = im.align_pair([1.0], [5.0, 6.0], 0.01, t0_x=0.01, t0_y=0.0)
    np.testing.assert_array_equal(x, [0, 1])
    np.testing.assert_array_equal(y, [5, 6])
    with pytest.raises(ValueError, match=r"allowed: a whole number of samples"):
        im.align_pair([1.0], [2.0], 0.01, t0_y=0.005)


@pytest.mark.parametrize("call, pattern", [
    (lambda: im.rotd([1.0, 2.0], 101), r"percentile = 101 is out of range"),
    (lambda: im.rotated_peaks([1.0, 2.0], [1.0]), r"allowed: two 1-D arrays of one length"),
    (lambda: im.oscillator_displacement([0.0, 1.0], DT, 0.0), r"period = 0\.0 is out of range"),
    (lambda: im.oscillator_displacement([0.0, 1.0], DT, 1.0, 1.0), r"damping = 1\.0 is out of range"),
])
def test_bad_inputs_are_refused_naming_the_value(call, pattern):
    with pytest.raises(ValueError, match=pattern):
        call()
