"""Readers, pyslammer samples and pulse fits of isoslide.records."""

from __future__ import annotations

import math
import re
import warnings
from pathlib import Path

import numpy as np
import pytest

import isoslide
from isoslide import Scene
from isoslide import pulses
from isoslide import records as R
from isoslide.store.history_io import history_table
from isoslide.pulses import get_pulse
from isoslide.records import fitting, reading

DATA = Path(__file__).parent / "data" / "records"
EXPECTED = np.loadtxt(DATA / "expected_values.txt")  # g, 23 samples


# ----------------------------------------------------------------------------- AT2


def test_at2_nga_west2_header():
    r = R.read_at2(DATA / "nga_west2.AT2")
    assert r.name == "nga_west2"
    assert r.dt == 0.01
    assert r.npts == 23
    np.testing.assert_allclose(r.accel, EXPECTED, rtol=1e-7, atol=1e-12)
    assert r.event == "Synthetic-01, 1/17/1994"
    assert r.station == "Test Station A"
    assert r.component == "228"
    assert r.source.endswith("nga_west2.AT2")


def test_at2_old_header_and_run_together_numbers():
    r = R.read_at2(DATA / "nga_west1_runtogether.AT2")
    assert r.dt == 0.005
    assert r.npts == 23
    np.testing.assert_allclose(r.accel, EXPECTED, rtol=1e-6, atol=1e-12)
    assert r.station == "TEST STN B"
    assert r.component == "090"


def test_at2_units_converted_to_g():
    r = R.read_at2(DATA / "units_cms2.AT2")
    np.testing.assert_allclose(r.accel, [1.0, -0.5, 0.0, 0.01], rtol=1e-12)
    assert r.dt == 0.02


@pytest.mark.parametrize("fname, line, words", [
    ("truncated.AT2", 7, ["23 values", "ends after 15 values", "truncated"]),
    ("bad_token.AT2", 6, ["a number", "1.2E-0x"]),
    ("ambiguous.AT2", 7, ["ambiguous", "0.1230.456"]),
    ("no_npts.AT2", 4, ["NPTS"]),
    ("velocity.VT2", 3, ["acceleration"]),
])
def test_at2_bad_input_names_file_line_and_expectation(fname, line, words):
    with pytest.raises(R.RecordFormatError) as exc:
        R.read_at2(DATA / fname)
    e = exc.value
    msg = str(e)
    assert fname in msg
    assert e.line == line and f"line {line}" in msg
    assert "expected" in msg
    for w in words:
        assert w in msg
    assert isinstance(e, ValueError)


def test_at2_extra_values_rejected(tmp_path):
    p = tmp_path / "extra.AT2"
    text = (DATA / "nga_west2.AT2").read_text() + "  1.0E-02\n"
    p.write_text(text)
    with pytest.raises(R.RecordFormatError, match=r"extra.AT2, line 10: expected 23 values"):
        R.read_at2(p)


def test_at2_header_without_units_needs_override(tmp_path):
    p = tmp_path / "nounits.AT2"
    lines = (DATA / "nga_west2.AT2").read_text().splitlines()
    lines[2] = "ACCELERATION TIME SERIES"
    p.write_text("\n".join(lines) + "\n")
    with pytest.raises(R.RecordFormatError, match="line 3: expected a header line stating the units"):
        R.read_at2(p)
    r = R.read_at2(p, units="g")
    np.testing.assert_allclose(r.accel, EXPECTED, rtol=1e-7)


def test_at2_empty_file(tmp_path):
    p = tmp_path / "empty.AT2"
    p.write_text("")
    with pytest.raises(R.RecordFormatError, match="empty.AT2, line 1"):
        R.read_at2(p)


@pytest.mark.parametrize("text, expected", [
    (" 3.063994E-02-1.365951E-02", [0.03063994, -0.01365951]),
    ("1.2E-02-5.6E-03", [0.012, -0.0056]),
    (".1234E+01.5678E+00", [1.234, 0.5678]),
    ("  1.0, -2.0 ,3.0  ", [1.0, -2.0, 3.0]),
    ("1.0D-02 -.5", [0.01, -0.5]),
])
def test_tokens_quirks(text, expected):
    assert reading._tokens(text, "f", 1) == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("text", ["0.1230.456", "0.1234-102", "1.0E+001.5E-01", "1.2E-0x", "nan", "1..2"])
def test_tokens_reject_ambiguous_or_bad(text):
    with pytest.raises(R.RecordFormatError, match="f, line 9"):
        reading._tokens(text, "f", 9)


# ----------------------------------------------------------------------------- CSV


def test_csv_two_columns_with_comments():
    r = R.read_csv(DATA / "two_column.csv")
    assert r.npts == 23
    assert r.dt == pytest.approx(0.01, rel=1e-12)
    assert r.t_start == pytest.approx(1.0)
    np.testing.assert_allclose(r.accel, EXPECTED, rtol=1e-7)
    np.testing.assert_allclose(r.time[[0, -1]], [1.0, 1.22])


def test_csv_header_row_and_units():
    r = R.read_csv(DATA / "with_header.csv", units="m/s2", event="E", station="S")
    np.testing.assert_allclose(r.accel, EXPECTED / R.G, rtol=1e-7)
    assert (r.event, r.station) == ("E", "S")


def test_csv_bad_row_names_line():
    with pytest.raises(R.RecordFormatError, match=r"bad_row.csv, line 4: expected two numbers"):
        R.read_csv(DATA / "bad_row.csv")


def test_csv_nonuniform_names_line():
    with pytest.raises(R.RecordFormatError, match=r"nonuniform.csv, line 4: expected a uniform"):
        R.read_csv(DATA / "nonuniform.csv")


def test_csv_too_short(tmp_path):
    p = tmp_path / "one.csv"
    p.write_text("# t,a\n0.0,0.1\n")
    with pytest.raises(R.RecordFormatError, match="at least two data rows"):
        R.read_csv(p)


def test_csv_bad_units():
    with pytest.raises(R.RecordFormatError, match="acceleration units"):
        R.read_csv(DATA / "two_column.csv", units="furlongs")


# ----------------------------------------------------------------------------- Record


def test_record_is_validated_and_read_only():
    r = R.Record("x", [0.0, 0.1, -0.2], 0.01)
    with pytest.raises(ValueError):
        r.accel[0] = 1.0
    with pytest.raises(ValueError, match="dt"):
        R.Record("x", [0.0, 0.1], 0.0)
    with pytest.raises(ValueError, match="NaN"):
        R.Record("x", [0.0, np.nan], 0.01)
    with pytest.raises(ValueError, match="at least 2"):
        R.Record("x", [0.0], 0.01)
    assert r.pga == pytest.approx(0.2)
    assert r.duration == pytest.approx(0.02)
    np.testing.assert_allclose(r.velocity(), [0.0, 0.05 * 0.01 * R.G, 0.0])


# ----------------------------------------------------------------------------- samples


def test_samples_listed_and_pulse_like_present():
    names = R.samples()
    assert len(names) >= 4
    for n in R.PULSE_LIKE_SAMPLES:
        assert n in names


@pytest.mark.parametrize("name", R.samples())
def test_every_sample_loads_with_sane_dt_and_pga(name):
    r = R.sample(name)
    assert r.name == name
    assert r.dt in (0.005, 0.01, 0.02) or 0.001 <= r.dt <= 0.05
    assert 0.05 < r.pga < 2.0  # g
    assert r.duration > 10.0
    assert r.event and r.component
    assert "GPL-3.0" in r.licence
    assert r.source.startswith("pyslammer:")


def test_sample_lookup_by_part_and_errors():
    r = R.sample("TAK-090")
    assert r.name == "Kobe_1995_TAK-090"
    assert r.station == "Takatori" and r.component == "090"
    assert r.dt == pytest.approx(0.01)
    assert r.pga == pytest.approx(0.616, abs=0.01)
    assert R.sample("tcu068").name == "Chi-Chi_1999_TCU068-090"
    with pytest.raises(ValueError, match="allowed: one of"):
        R.sample("Northridge")  # ambiguous: two Northridge records
    with pytest.raises(ValueError, match="allowed: one of"):
        R.sample("no-such-record")


# ----------------------------------------------------------------------------- fits


def _synthetic_ricker(a_p_g=0.4, T_p=0.8, t_peak=6.3, polarity=-1, dt=0.01, dur=20.0, noise=0.05, seed=1):
    t = np.arange(0.0, dur, dt)
    x = (t - t_peak) / T_p
    a = polarity * a_p_g * (1 - 2 * np.pi**2 * x**2) * np.exp(-np.pi**2 * x**2)
    rng = np.random.default_rng(seed)
    return a + noise * a_p_g * rng.standard_normal(t.size), dt


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_fit_recovers_noisy_ricker_to_1_percent(seed):
    """White noise of 2 % of a_p per sample (dt = T_p/80).  Over 40 seeds the
    errors are unbiased with sd 0.46 % (a_p), 0.22 % (T_p), 0.04 % T_p (t_peak)."""
    a, dt = _synthetic_ricker(seed=seed, noise=0.02)
    f = R.fit_pulse(a, dt)
    assert f.shape == "ricker"
    assert f.a_p == pytest.approx(0.4 * R.G, rel=0.01)  # m/s^2
    assert f.a_p_g == pytest.approx(0.4, rel=0.01)
    assert f.T_p == pytest.approx(0.8, rel=0.01)
    assert f.t_peak == pytest.approx(6.3, abs=0.01 * 0.8)
    assert f.polarity == -1
    assert f.r2 > 0.99 and f.nrmse < 0.03
    assert f.window == pytest.approx((6.3 - 0.8, 6.3 + 0.8), abs=0.02)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_fit_with_5_percent_noise_within_3_sigma(seed):
    """5 % white noise: measured sd 1.15 % (a_p), 0.55 % (T_p), 0.1 % T_p (t_peak)."""
    a, dt = _synthetic_ricker(seed=seed, noise=0.05)
    f = R.fit_pulse(a, dt)
    assert f.a_p_g == pytest.approx(0.4, rel=0.035)
    assert f.T_p == pytest.approx(0.8, rel=0.017)
    assert f.t_peak == pytest.approx(6.3, abs=0.004 * 0.8)


def test_fit_ricker_among_stronger_short_period_clutter():
    """A long pulse with high-frequency clutter of larger peak is still found."""
    a, dt = _synthetic_ricker(a_p_g=0.3, T_p=1.2, t_peak=8.0, polarity=1, dt=0.005, dur=25, noise=0.0)
    t = np.arange(a.size) * dt
    rng = np.random.default_rng(7)
    clutter = 0.45 * np.sin(2 * np.pi * 7.0 * t + 1.0) * np.exp(-((t - 7.0) / 3.0) ** 2)
    f = R.fit_pulse(a + clutter + 0.01 * rng.standard_normal(t.size), dt)
    assert f.T_p == pytest.approx(1.2, rel=0.01)
    assert f.t_peak == pytest.approx(8.0, abs=0.012)
    assert f.a_p_g == pytest.approx(0.3, rel=0.02)


def test_fit_units_and_t_start():
    a, dt = _synthetic_ricker(noise=0.0)
    f_g = R.fit_pulse(a, dt)
    f_si = R.fit_pulse(a * R.G * 100, dt, units="cm/s2", t_start=10.0)
    assert f_si.a_p == pytest.approx(f_g.a_p, rel=1e-9)
    assert f_si.t_peak == pytest.approx(f_g.t_peak + 10.0, abs=1e-9)
    assert f_g.r2 == pytest.approx(1.0, abs=1e-9)


def test_fit_bad_input():
    with pytest.raises(ValueError, match="shape"):
        R.fit_pulse(np.ones(100), 0.01, shape="gabor")
    with pytest.raises(ValueError, match="identically zero"):
        R.fit_pulse(np.zeros(100), 0.01)
    with pytest.raises(ValueError, match="dt"):
        R.fit_pulse(np.ones(100), -0.01)
    with pytest.raises(ValueError, match="T_range"):
        R.fit_pulse(np.ones(100), 0.01, T_range=(2.0, 1.0))


def _mp_record(gamma, nu, A=0.9, T=1.1, t0=7.0, dt=0.005, dur=20.0, noise=0.0, seed=3):
    t = np.arange(0.0, dur, dt)
    a = pulses.mp_accel(t, A, t0, T, gamma, nu) / R.G  # g
    rng = np.random.default_rng(seed)
    return a + noise * np.max(np.abs(a)) * rng.standard_normal(t.size), dt


@pytest.mark.parametrize("gamma, nu", [(2.0, 0.5 * np.pi), (1.8, 0.3), (3.0, 4.0)])
def test_mp_fit_recovers_parameters_with_noise(gamma, nu):
    a, dt = _mp_record(gamma, nu, noise=0.05)
    f = R.fit_pulse(a, dt, shape="mp")
    p = f.shape_params
    assert f.shape == "mavroeidis_papageorgiou"
    assert f.T_p == pytest.approx(1.1, rel=0.01)
    assert p["gamma"] == pytest.approx(gamma, rel=0.02)
    assert (p["nu"] - nu + np.pi) % (2 * np.pi) - np.pi == pytest.approx(0.0, abs=0.03)
    assert p["t0"] == pytest.approx(7.0, abs=0.011)
    assert p["A"] == pytest.approx(0.9, rel=0.02)
    peak = np.max(np.abs(a)) * R.G
    assert f.a_p == pytest.approx(peak / (1 + 0.05 * 3), rel=0.15)  # noisy peak vs clean fitted peak


def test_mp_fit_exact_a_p_and_scene_pulse_matches_fit():
    a, dt = _mp_record(2.4, 1.0, noise=0.0)
    f = R.fit_pulse(a, dt, shape="mavroeidis_papageorgiou")
    tt = np.linspace(*f.window, 20001)
    assert f.a_p == pytest.approx(np.max(np.abs(f.accel(tt))), rel=1e-6)
    for pol in (1, -1):
        fp = f if pol == f.polarity else R.PulseFit(**{**f.__dict__, "polarity": pol})
        P = fp.as_pulse()
        tau = np.linspace(P.tau_start, P.tau_end, 4001)
        if pol == f.polarity:
            ref = f.accel(f.t_ref + tau * f.T_p) / (f.polarity * f.a_p)
            np.testing.assert_allclose(P.accel(tau), ref, atol=1e-9)
        assert P.accel(np.array([(f.t_peak - f.t_ref) / f.T_p]))[0] == pytest.approx(pol * f.polarity, abs=1e-6)
    assert f.t_ref == f.shape_params["t0"]


def test_ricker_fit_as_pulse_and_kinematics():
    a, dt = _synthetic_ricker(noise=0.0)
    f = R.fit_pulse(a, dt)
    assert f.as_pulse() == get_pulse("ricker")
    assert f.scene_pulse() == f.as_pulse()
    t = np.arange(a.size) * dt
    np.testing.assert_allclose(f.accel(t) / R.G, a, atol=1e-8)
    v = np.concatenate([[0.0], np.cumsum(0.5 * (f.accel(t)[1:] + f.accel(t)[:-1]) * dt)])
    np.testing.assert_allclose(f.velocity(t), v, atol=1e-3 * np.max(np.abs(v)))  # trapezoid error
    assert f.length_scale == pytest.approx(f.a_p * f.T_p**2)


# ----------------------------------------------------------------------------- shapes of isoslide.pulses


def test_ricker_fit_is_evaluated_with_the_pulses_module_shape(monkeypatch):
    """The Ricker fit and its PulseFit evaluate isoslide.pulses.ricker_accel / ricker_velocity."""
    calls = []

    def spy(*args):
        calls.append(args)
        return pulses.ricker_accel(*args)

    monkeypatch.setattr(fitting, "ricker_accel", spy)
    a, dt = _synthetic_ricker(noise=0.0)
    f = R.fit_pulse(a, dt)
    assert calls, "fit_pulse did not evaluate isoslide.pulses.ricker_accel"
    t = np.arange(a.size) * dt
    A = f.polarity * f.a_p
    np.testing.assert_array_equal(f.accel(t), pulses.ricker_accel(t, A, f.t_peak, f.T_p))
    np.testing.assert_array_equal(f.velocity(t), pulses.ricker_velocity(t, A, f.t_peak, f.T_p))
    # the same pulse as the dimensionless Ricker of the scenes, inside its support
    tau = (t - f.t_peak) / f.T_p
    inside = np.abs(tau) < pulses.RICKER_HALF_WIDTH
    P = f.as_pulse()
    np.testing.assert_allclose(f.accel(t)[inside], A * P.accel(tau[inside]), rtol=1e-13, atol=1e-13 * f.a_p)
    np.testing.assert_allclose(f.velocity(t)[inside], A * f.T_p * P.velocity(tau[inside]),
                               rtol=1e-12, atol=1e-13 * f.a_p * f.T_p)


def test_mp_fit_is_evaluated_with_the_pulses_module_shape(monkeypatch):
    """The M-P fit and its PulseFit evaluate isoslide.pulses.mp_accel and mp_accel_jacobian."""
    used = set()

    def spy(name):
        def wrapped(*args):
            used.add(name)
            return getattr(pulses, name)(*args)
        return wrapped

    for name in ("mp_accel", "mp_accel_jacobian"):
        monkeypatch.setattr(fitting, name, spy(name))
    a, dt = _mp_record(2.4, 1.0, noise=0.0)
    f = R.fit_pulse(a, dt, shape="mp")
    assert used == {"mp_accel", "mp_accel_jacobian"}
    p = f.shape_params
    t = np.arange(a.size) * dt
    args = (p["A"], p["t0"], f.T_p, p["gamma"], p["nu"])
    np.testing.assert_array_equal(f.accel(t), pulses.mp_accel(t, *args))
    np.testing.assert_array_equal(f.velocity(t), pulses.mp_velocity(t, *args))


@pytest.mark.parametrize("gamma, nu", [(1.5, 0.0), (2.4, 1.0), (3.7, -2.5)])
def test_mp_record_time_shape_is_the_scene_pulse_at_physical_scales(gamma, nu):
    """mp_accel / mp_velocity at (A, t0, T) equal the normalised scene pulse scaled by
    a_p = pi A N / T and a_p T; the Jacobian matches central differences."""
    A, t0, T = 0.7, 3.0, 1.3
    P = pulses.mavroeidis_papageorgiou(gamma=gamma, nu=nu)
    a_p = math.pi * A / T / P.params[2]
    t = t0 + T * np.linspace(P.tau_start, P.tau_end, 2001)[:-1]
    tau = (t - t0) / T
    np.testing.assert_allclose(pulses.mp_accel(t, A, t0, T, gamma, nu), a_p * P.accel(tau),
                               rtol=1e-12, atol=1e-12 * a_p)
    np.testing.assert_allclose(pulses.mp_velocity(t, A, t0, T, gamma, nu), a_p * T * P.velocity(tau),
                               rtol=1e-10, atol=1e-12 * A)
    x = np.array([A, t0, T, gamma, nu])
    J = pulses.mp_accel_jacobian(t, *x)
    for k in range(5):
        h = 1e-6 * max(1.0, abs(x[k]))
        up, dn = x.copy(), x.copy()
        up[k] += h
        dn[k] -= h
        fd = (pulses.mp_accel(t, *up) - pulses.mp_accel(t, *dn)) / (2 * h)
        interior = np.abs(tau) < 0.5 * gamma - 1e-3  # the support moves with t0, T and gamma
        np.testing.assert_allclose(J[interior, k], fd[interior], rtol=1e-5, atol=1e-6 * np.max(np.abs(fd)))


# ----------------------------------------------------------------------------- record as pulse


def test_record_as_pulse_runs_as_recorded_and_aligns_on_request():
    """Defaults: the record's own sign and time axis at the fitted scales; with the fit's
    ``t_ref`` and ``polarity`` it lines up with the fitted pulse; explicit scales and windows."""
    a, dt = _synthetic_ricker(noise=0.0, polarity=-1)
    r = R.Record("syn", a, dt, t_start=0.0)
    f = r.fit()
    assert r.fit() is f  # cached
    assert f.polarity == -1
    P = r.as_pulse()
    assert P.name == "syn"
    assert P.params[1] == pytest.approx(dt / f.T_p)
    assert P.tau_start == 0.0
    np.testing.assert_allclose(P.params[2:], a * R.G / f.a_p, atol=1e-15)  # as recorded: no sign flip
    tau = np.linspace(-1.5, 1.5, 301)
    A = r.as_pulse(t_ref=f.t_ref, polarity=f.polarity)
    assert A.tau_start == pytest.approx(-f.t_peak / f.T_p)
    # linear interpolation between samples (dtau = 0.0125) vs the exact wavelet
    np.testing.assert_allclose(A.accel(tau), f.as_pulse().accel(tau), atol=2e-3)
    np.testing.assert_allclose(P.accel(tau + f.t_peak / f.T_p), -f.as_pulse().accel(tau), atol=2e-3)
    # explicit scales override the fit
    Q = r.as_pulse(a_p=2.0, T_p=0.5, t_ref=1.0, polarity=1)
    assert Q.params[1] == pytest.approx(dt / 0.5)
    assert Q.tau_start == pytest.approx(-2.0)
    np.testing.assert_allclose(Q.params[2:], a * R.G / 2.0)
    # window
    W = r.as_pulse(window=(5.0, 7.0))
    assert W.tau_start == pytest.approx(5.0 / f.T_p, abs=dt / f.T_p)
    assert len(W.params) - 2 == 201
    with pytest.raises(ValueError, match="window"):
        r.as_pulse(window=(50.0, 60.0))
    with pytest.raises(ValueError, match="a_p"):
        r.as_pulse(a_p=-1.0)
    with pytest.raises(ValueError, match="polarity"):
        r.as_pulse(polarity=2)
    with pytest.raises(ValueError, match="t_ref = nan"):
        r.as_pulse(t_ref=math.nan)


def test_scene_accepts_record_and_uses_fitted_scales():
    """``Scene(pulse=record)`` is the record as recorded at its fitted scales; from_physical
    with the same scales gives the same pulse and Pi-groups."""
    a, dt = _synthetic_ricker(noise=0.0)
    r = R.Record("syn", a, dt)
    s = Scene(pi2=0.3, pi3=1.0, pi4=0.1, pulse=r)
    assert s.pulse == r.as_pulse()
    f = r.fit()
    s2 = Scene.from_physical(a_p=f.a_p, T_p=f.T_p, M_b=1e5, T_b=f.T_p, xi_b=0.1, m_ec=1.0,
                             mu_s=0.3, mu_k=0.3, pulse=r)
    assert s2.pulse == s.pulse
    assert s2.pi3 == pytest.approx(1.0)


def test_scene_from_record_with_given_scales_never_fits(monkeypatch):
    """With a_p and T_p given (from_physical, or as_pulse with both scales) no fit runs,
    even for a new Record object."""
    calls = []
    real = R.record.fit_pulse

    def spy(*args, **kw):
        calls.append(kw.get("shape"))
        return real(*args, **kw)

    monkeypatch.setattr(R.record, "fit_pulse", spy)
    a, dt = _synthetic_ricker(noise=0.0, polarity=-1)
    r = R.Record("fresh", a, dt)
    s = Scene.from_physical(a_p=3.0, T_p=0.8, M_b=1e5, T_b=1.6, xi_b=0.1, m_ec=1.0, mu_s=0.1,
                            mu_k=0.1, pulse=r)
    r.as_pulse(a_p=3.0, T_p=0.8)
    assert calls == []
    np.testing.assert_allclose(s.pulse.params[2:], a * R.G / 3.0, atol=1e-15)
    assert s.pulse.params[1] == pytest.approx(dt / 0.8)


def test_fit_cached_by_content_across_record_objects(monkeypatch):
    """Two Record objects with the same samples share one fit; different samples fit again."""
    calls = []
    real = R.record.fit_pulse

    def spy(*args, **kw):
        calls.append(1)
        return real(*args, **kw)

    monkeypatch.setattr(R.record, "fit_pulse", spy)
    a, dt = _synthetic_ricker(noise=0.0)
    a = a * 1.000123  # content not fitted by any other test
    f1 = R.Record("one", a, dt).fit()
    f2 = R.Record("two", a.copy(), dt).fit()
    assert f1 == f2 and len(calls) == 1
    R.Record("three", a * 2.0, dt).fit()
    assert len(calls) == 2


def test_record_fit_mp_through_record():
    a, dt = _mp_record(2.0, 0.5 * np.pi, noise=0.02)
    r = R.Record("mp", a, dt)
    f = r.fit("mp")
    assert r.fit("mavroeidis_papageorgiou") is f
    P = r.as_pulse(shape="mp", t_ref=f.t_ref, polarity=f.polarity)
    tau = np.linspace(-1.0, 1.0, 201)
    np.testing.assert_allclose(P.accel(tau), f.as_pulse().accel(tau), atol=0.1)


# ----------------------------------------------------------------------------- real records


def test_takatori_fit_within_sanity_band():
    """Takatori 090: velocity-pulse periods of about 1.2-1.6 s are quoted; the
    acceleration-based Ricker fit lands at the upper end of that band (1.56 s
    measured), a_p about half the PGA (0.49 g vs 0.62 g)."""
    r = R.sample("Kobe_1995_TAK-090")
    f = r.fit()
    assert 1.0 <= f.T_p <= 1.7
    assert 0.35 <= f.a_p_g <= 0.62
    assert 4.5 <= f.t_peak <= 6.5
    assert f.r2 > 0.4
    m = r.fit("mp")
    assert 1.0 <= m.T_p <= 1.7


def _kobe_kwargs(record):
    """Physical parameters at the record's fitted Ricker scales (Pi2 = 0.3, Pi3 = 1: it slides)."""
    f = record.fit()
    mu = 0.3 * f.a_p / R.G
    return dict(a_p=f.a_p, T_p=f.T_p, M_b=1e6, T_b=f.T_p, xi_b=0.1, m_ec=1e4, mu_s=mu, mu_k=mu)


def _kobe_scene(record):
    return Scene.from_physical(**_kobe_kwargs(record), pulse=record)


def test_history_ground_acceleration_is_the_raw_record_sample_by_sample():
    """Kobe TAK-090 (fitted Ricker of negative polarity) through ``pulse=record``: at every record
    time the history's ground acceleration is the record's, with its sign (m/s^2)."""
    r = R.sample("Kobe_1995_TAK-090")
    assert r.fit().polarity == -1
    scene = _kobe_scene(r)
    sol = isoslide.solve(scene, history=True)
    c = history_table(sol, scene).columns
    k = np.rint((c["time"] - r.t_start) / r.dt)
    on_sample = (np.abs(c["time"] - (r.t_start + k * r.dt)) < 1e-9) & (k >= 0) & (k < r.npts - 1)
    idx, first = np.unique(k[on_sample].astype(int), return_index=True)
    assert idx.size == r.npts - 1  # every sample but the last (the pulse is 0 from its end on)
    np.testing.assert_allclose(c["ground_accel"][on_sample][first], r.accel_si[idx], rtol=1e-12,
                               atol=1e-12 * r.pga * R.G)


def test_kobe_residual_sign_as_recorded_and_peak_as_mirrored():
    """Run as recorded, Kobe TAK-090 leaves the block displaced in the negative direction; the
    mirrored, fit-aligned record (the earlier behaviour) gives the same Pi1 and the opposite
    residual; Scene(pulse=record) equals the hand-built sampled pulse of the raw record."""
    r = R.sample("Kobe_1995_TAK-090")
    f = r.fit()
    as_recorded = isoslide.solve(_kobe_scene(r))
    hand = pulses.sampled(r.accel * R.G / f.a_p, r.dt / f.T_p, r.t_start / f.T_p, name=r.name)
    by_hand = isoslide.solve(Scene.from_physical(**_kobe_kwargs(r), pulse=hand))
    assert as_recorded.u_residual == pytest.approx(by_hand.u_residual, rel=1e-9)
    assert as_recorded.u_residual < 0.0
    dimless = isoslide.solve(Scene(pi2=0.3, pi3=1.0, pi4=0.1, pi8=0.01, pulse=r))
    mirrored = isoslide.solve(Scene(pi2=0.3, pi3=1.0, pi4=0.1, pi8=0.01,
                                    pulse=r.as_pulse(t_ref=f.t_ref, polarity=f.polarity)))
    assert dimless.pi1 > 0.0
    assert dimless.pi1 == pytest.approx(mirrored.pi1, rel=1e-6)
    assert dimless.pi1_residual == pytest.approx(-mirrored.pi1_residual, rel=1e-5)
    assert dimless.pi1_residual == pytest.approx(as_recorded.pi1_residual, rel=1e-6)
    assert dimless.tau_peak - mirrored.tau_peak == pytest.approx(f.t_peak / f.T_p, rel=1e-9)


@pytest.mark.parametrize("name", R.PULSE_LIKE_SAMPLES)
def test_pulse_like_samples_fit_sanely(name):
    r = R.sample(name)
    f = r.fit()
    assert 0.2 <= f.T_p <= 5.0
    assert 0.1 <= f.a_p_g <= r.pga * 1.3  # the least-squares peak may exceed the PGA (PAC-175: 0.50 vs 0.42 g)
    assert r.time[0] < f.t_peak < r.time[-1]
    assert 0.3 < f.r2 <= 1.0
    assert 0.0 < f.energy_fraction < 1.0
    assert math.isfinite(f.nrmse)


def test_at2_crlf_line_endings(tmp_path):
    p = tmp_path / "crlf.AT2"
    p.write_bytes((DATA / "nga_west2.AT2").read_text().replace("\n", "\r\n").encode())
    np.testing.assert_allclose(R.read_at2(p).accel, EXPECTED, rtol=1e-7)


def test_record_fit_options_cached_separately():
    a, dt = _synthetic_ricker(noise=0.0)
    r = R.Record("syn", a, dt)
    f1 = r.fit(T_range=(0.5, 2.0))
    assert r.fit(T_range=(0.5, 2.0)) is f1
    f2 = r.fit(t_range=(0.0, 3.0))  # excludes the true peak at 6.3 s
    assert f2 is not f1 and f2.t_peak <= 3.0 + 1e-9


# ----------------------------------------------------------------------------- damaged files

_NUM_RE = r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[EeDd][+-]?\d+)?"


def _on_line(k, fn):
    """Apply ``fn`` to line ``k`` (0-based, negative from the end) of the text."""
    def damage(text):
        lines = text.splitlines(keepends=True)
        lines[k] = fn(lines[k])
        return "".join(lines)
    return damage


def _last_number(repl):
    """Replace the last number on a line (an acceleration in both formats)."""
    def fn(line):
        found = list(re.finditer(_NUM_RE, line))
        return line if not found else line[:found[-1].start()] + repl + line[found[-1].end():]
    return fn


def _first_number(repl):
    """Replace the first number on a line (NPTS on an AT2 sampling line, the time in a CSV row)."""
    return lambda line: re.sub(_NUM_RE, lambda m: repl, line, count=1)


def _keep_lines(n):
    return lambda text: "".join(text.splitlines(keepends=True)[:n])


def _drop_line(k):
    def damage(text):
        lines = text.splitlines(keepends=True)
        del lines[k]
        return "".join(lines)
    return damage


def _swap(i, j):
    def damage(text):
        lines = text.splitlines(keepends=True)
        lines[i], lines[j] = lines[j], lines[i]
        return "".join(lines)
    return damage


DAMAGE = {
    # the file's structure
    "empty": lambda t: "",
    "blank": lambda t: "  \n\n \n",
    "first_line_only": _keep_lines(1),
    "header_and_one_row": _keep_lines(5),
    "four_data_rows": _keep_lines(7),
    "half_the_bytes": lambda t: t[: len(t) // 2],
    "ninety_percent_of_the_bytes": lambda t: t[: 9 * len(t) // 10],
    "cut_inside_a_number": lambda t: t.rstrip()[:-3],
    "last_line_dropped": _drop_line(-1),
    "first_line_dropped": _drop_line(0),
    "second_line_dropped": _drop_line(1),
    "third_line_dropped": _drop_line(2),
    "fourth_line_dropped": _drop_line(3),
    "last_line_twice": lambda t: t + t.splitlines(keepends=True)[-1],
    "middle_line_twice": lambda t: "".join((lambda ls: ls[:6] + ls[5:])(t.splitlines(keepends=True))),
    "lines_3_and_4_swapped": _swap(2, 3),
    "lines_reversed": lambda t: "\n".join(reversed(t.splitlines())) + "\n",
    "file_twice": lambda t: t + t,
    "one_line": lambda t: " ".join(t.splitlines()),
    "crlf": lambda t: t.replace("\n", "\r\n"),
    "cr_only": lambda t: t.replace("\n", "\r"),
    "bom": lambda t: "\ufeff" + t,
    "nul_bytes": lambda t: t[: len(t) // 2].encode() + b"\x00\x00\x00" + t[len(t) // 2:].encode(),
    "binary": lambda t: bytes(range(256)) * 4,
    "invalid_utf8_byte": lambda t: t[: len(t) // 2].encode() + b"\xff\xfe" + t[len(t) // 2:].encode(),
    "latin1_header": lambda t: ("\u00e9" + t).encode("latin-1"),
    "tabs": lambda t: t.replace(" ", "\t").replace(",", "\t"),
    "text_line_inserted": lambda t: "".join((lambda ls: ls[:6] + ["garbage here\n"] + ls[6:])(
        t.splitlines(keepends=True))),
    "blank_lines_everywhere": lambda t: t.replace("\n", "\n\n"),
    "very_long_number": _on_line(-3, _last_number("1" * 5000)),
    "digits_removed_on_a_line": _on_line(-3, lambda line: re.sub(r"\d", "", line)),
    "lower_case": lambda t: t.lower(),
    # one acceleration value
    "value_1e308": _on_line(-3, _last_number("1e308")),
    "value_minus_1e308": _on_line(-3, _last_number("-1e308")),
    "value_1e309": _on_line(-3, _last_number("1e309")),
    "value_nan": _on_line(-3, _last_number("nan")),
    "value_inf": _on_line(-3, _last_number("inf")),
    "value_minus_inf": _on_line(-3, _last_number("-inf")),
    "value_word": _on_line(-3, _last_number("abc")),
    "value_deleted": _on_line(-3, _last_number("")),
    "value_denormal": _on_line(-3, _last_number("1e-320")),
    "value_150_g": _on_line(-3, _last_number("150.0")),
    "value_99_g": _on_line(-3, _last_number("99.0")),
    "value_decimal_comma": _on_line(-3, _last_number("1,5")),
    "value_two_points": _on_line(-3, _last_number("1.2.3")),
    "value_double_sign": _on_line(-3, _last_number("--1")),
    "value_hex": _on_line(-3, _last_number("0x1F")),
    "value_bare_exponent": _on_line(-3, _last_number("1e")),
    "value_exponent_999": _on_line(-3, _last_number("1E+999")),
    "value_fortran_d": _on_line(-3, _last_number("1.0D-02")),
    "values_run_together": _on_line(-3, _last_number("0.1230.456")),
    "value_appended": _on_line(-3, lambda line: line.rstrip("\r\n") + " 0.01\n"),
    "value_removed": _on_line(-3, _last_number(" ")),
    "every_exponent_raised": lambda t: t.replace("E-0", "E+0"),
    # the sampling line of an AT2 (line 4), the fourth line of a CSV
    "npts_zero": _on_line(3, _first_number("0")),
    "npts_one": _on_line(3, _first_number("1")),
    "npts_negative": _on_line(3, _first_number("-5")),
    "npts_1e9": _on_line(3, _first_number("1000000000")),
    "npts_fraction": _on_line(3, _first_number("2.5")),
    "npts_word": _on_line(3, _first_number("x")),
    "dt_zero": lambda t: re.sub(r"DT=\s*\S+", "DT= 0.0", t),
    "dt_negative": lambda t: re.sub(r"DT=\s*\S+", "DT= -0.01", t),
    "dt_huge": lambda t: re.sub(r"DT=\s*\S+", "DT= 1e308", t),
    "dt_tiny": lambda t: re.sub(r"DT=\s*\S+", "DT= 1e-300", t),
    "dt_word": lambda t: re.sub(r"DT=\s*\S+", "DT= abc", t),
    "time_huge": _on_line(-3, _first_number("1e308")),
    "units_unknown": lambda t: t.replace("UNITS OF G", "UNITS OF FURLONGS"),
    "velocity": lambda t: t.replace("ACCELERATION", "VELOCITY"),
}
"""Kinds of damage done to a record file's text (a new text or bytes)."""


def _damaged(tmp_path, source, kind, name=None):
    """``source`` with the damage ``kind`` written to ``tmp_path / name``."""
    out = DAMAGE[kind](source.read_text())
    path = tmp_path / (name or source.name)
    path.write_bytes(out if isinstance(out, bytes) else out.encode("utf-8"))
    return path


def _read_or_refused(read, path, names) -> str:
    """``"read"`` or ``"refused"``; a refusal must be a ValueError naming the file (one of ``names``)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        try:
            read(path)
        except ValueError as exc:
            assert any(n in str(exc) for n in names), f"{names} not named in: {exc}"
            return "refused"
    return "read"


def _load_and_fit(path):
    """What the command line does with --record: read, then fit the pulse."""
    R.load_record(path).fit()


def test_damage_kinds_are_many_and_distinct():
    """At least 60 kinds, each changing both sample files (a no-op would test nothing twice)."""
    assert len(DAMAGE) >= 60
    for kind, damage in DAMAGE.items():
        changed = [damage((DATA / f).read_text()) != (DATA / f).read_text()
                   for f in ("nga_west2.AT2", "two_column.csv")]
        assert any(changed), kind


@pytest.mark.parametrize("kind", DAMAGE)
@pytest.mark.parametrize("fname", ["nga_west2.AT2", "two_column.csv"])
def test_a_damaged_record_file_is_read_or_refused_naming_the_file(tmp_path, fname, kind):
    """Through load_record and the pulse fit: a clean record or a ValueError that names the file."""
    path = _damaged(tmp_path, DATA / fname, kind)
    _read_or_refused(_load_and_fit, path, [path.name])


def test_damaged_files_are_mostly_refused_and_the_harmless_damage_is_read(tmp_path):
    """The fuzz test sees both outcomes: harmless damage (CRLF, a BOM, blank lines) reads."""
    outcomes = {kind: _read_or_refused(_load_and_fit, _damaged(tmp_path, DATA / "nga_west2.AT2", kind),
                                       ["nga_west2.AT2"]) for kind in DAMAGE}
    for kind in ("crlf", "bom", "blank_lines_everywhere", "value_99_g", "value_fortran_d"):
        assert outcomes[kind] == "read", kind
    assert sum(o == "refused" for o in outcomes.values()) > len(DAMAGE) // 2


@pytest.mark.parametrize("fname, line", [("nga_west2.AT2", 7), ("two_column.csv", 23)])
@pytest.mark.parametrize("kind, shown", [("value_1e308", "1e+308"), ("value_minus_1e308", "-1e+308"),
                                         ("value_150_g", "150")])
def test_an_acceleration_beyond_100_g_is_refused_naming_file_line_and_value(tmp_path, fname, line, kind, shown):
    path = _damaged(tmp_path, DATA / fname, kind)
    reader = R.read_at2 if fname.endswith(".AT2") else R.read_csv
    with pytest.raises(R.RecordFormatError) as exc:
        reader(path)
    msg = str(exc.value)
    assert f"{fname}, line {line}" in msg and "100 g" in msg and shown in msg, msg


def test_an_acceleration_beyond_100_g_in_other_units_shows_both_values(tmp_path):
    p = tmp_path / "gal.AT2"
    p.write_text((DATA / "units_cms2.AT2").read_text().replace("980.665", "1.0E+06"))
    with pytest.raises(R.RecordFormatError, match=r"gal.AT2, line \d+: .*found '1e\+06 \(1019.7\d* g\)'"):
        R.read_at2(p)


def test_a_record_too_short_to_fit_names_its_file(tmp_path):
    path = _damaged(tmp_path, DATA / "two_column.csv", "four_data_rows")
    rec = R.read_csv(path)
    assert rec.npts == 5
    with pytest.raises(ValueError, match=r"two_column.csv: no pulse fit: .*at least 8 samples"):
        rec.fit()


def test_record_and_fit_refuse_accelerations_beyond_100_g():
    with pytest.raises(ValueError, match=r"Record 'x': accel\[1\] = 101 g is invalid; allowed range: "
                                         r"\|accel\| <= 100 g"):
        R.Record("x", [0.0, 101.0, 0.0], 0.01)
    with pytest.raises(ValueError, match=r"accel\[3\] = 1e\+308 g is invalid"):
        R.fit_pulse([0.0, 0.1, 0.2, 1e308, 0.1, 0.0, 0.0, 0.0, 0.0, 0.0], 0.01)
    assert R.Record("x", [0.0, 100.0, -100.0], 0.01).pga == 100.0


def _pair_folder(tmp_path):
    """A folder with one ground motion: x and y components as AT2 files."""
    folder = tmp_path / "pairs"
    folder.mkdir()
    text = (DATA / "nga_west2.AT2").read_text()
    (folder / "RSN1_TEST_STA000.AT2").write_text(text)
    (folder / "RSN1_TEST_STA090.AT2").write_text(text.replace("228", "318"))
    return folder


def _read_suite_and_fit(path):
    for gm in R.suite(path):
        for rec in gm.components.values():
            rec.fit()


@pytest.mark.parametrize("kind", DAMAGE)
@pytest.mark.parametrize("which", ["RSN1_TEST_STA000.AT2", "RSN1_TEST_STA090.AT2"])
def test_a_damaged_component_of_a_folder_pair_is_read_or_refused_naming_it(tmp_path, which, kind):
    folder = _pair_folder(tmp_path)
    _damaged(folder, folder / which, kind)
    _read_or_refused(_read_suite_and_fit, folder, [which])


MANIFEST = ("# three ground motions\nname,x,y,pulse\ngm1,rec/a.AT2,rec/b.csv,yes\n"
            "gm2,rec/b.csv,rec/a.AT2,no\ngm3,rec/a.AT2,rec/a.AT2,\n")

MANIFEST_DAMAGE = {
    "duplicate_name": lambda t: t.replace("gm2", "gm1"),
    "missing_file": lambda t: t.replace("rec/b.csv,rec/a", "rec/nope.csv,rec/a"),
    "absolute_missing_file": lambda t: t.replace("rec/a.AT2,rec/b", "/no/such/a.AT2,rec/b"),
    "folder_as_file": lambda t: t.replace("rec/a.AT2,rec/b", "rec/sub.AT2,rec/b"),
    "other_suffix": lambda t: t.replace("rec/a.AT2,rec/b", "rec/a.txt,rec/b"),
    "empty_name": lambda t: t.replace("gm1", ""),
    "empty_x": lambda t: t.replace("gm1,rec/a.AT2", "gm1,"),
    "cell_missing": lambda t: t.replace(",yes", ""),
    "cell_extra": lambda t: t.replace(",yes", ",yes,extra"),
    "header_only": _keep_lines(2),
    "header_misspelt": lambda t: t.replace("name,x", "nmae,x"),
    "header_twice_x": lambda t: t.replace("name,x,y", "name,x,x"),
    "bad_pulse": lambda t: t.replace(",yes", ",maybe"),
    "unbalanced_quote": lambda t: t.replace("gm1", '"gm1'),
    "manifest_lists_itself": lambda t: t.replace("rec/a.AT2,rec/b", "m.csv,rec/b"),
    "y_of_another_dt": lambda t: t.replace("rec/b.csv,rec/a.AT2", "rec/b.csv,rec/c.AT2"),
}
"""Damage only a manifest can have."""


def _manifest(tmp_path):
    rec = tmp_path / "rec"
    rec.mkdir()
    (rec / "sub.AT2").mkdir()
    (rec / "a.AT2").write_text((DATA / "nga_west2.AT2").read_text())
    (rec / "b.csv").write_text((DATA / "two_column.csv").read_text())
    (rec / "c.AT2").write_text((DATA / "nga_west2.AT2").read_text().replace(".0100 SEC", ".0200 SEC"))
    path = tmp_path / "m.csv"
    path.write_text(MANIFEST)
    return path


@pytest.mark.parametrize("kind", [*DAMAGE, *MANIFEST_DAMAGE])
def test_a_damaged_manifest_is_read_or_refused_naming_it(tmp_path, kind):
    path = _manifest(tmp_path)
    out = {**DAMAGE, **MANIFEST_DAMAGE}[kind](MANIFEST)
    path.write_bytes(out if isinstance(out, bytes) else out.encode("utf-8"))
    _read_or_refused(_read_suite_and_fit, path, ["m.csv"])


def test_every_manifest_damage_is_refused(tmp_path):
    """Each manifest-only damage is an error (none of them may be read silently)."""
    for kind, damage in MANIFEST_DAMAGE.items():
        sub = tmp_path / kind
        sub.mkdir()
        path = _manifest(sub)
        path.write_text(damage(MANIFEST))
        assert _read_or_refused(_read_suite_and_fit, path, ["m.csv"]) == "refused", kind
