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
