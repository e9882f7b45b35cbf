"""The fragility study (isoslide.studies.fragility_study, isoslide.studies.intensity): analyses, IMs, fits, datasets."""

import copy
import logging

import numpy as np
import pytest
import xarray as xr

import isoslide.config
from isoslide.studies import fragility_study as fs
from isoslide import solver
from isoslide import datasets
from isoslide.datasets import write_netcdf
from isoslide.studies.fragility import fit_lognormal
from isoslide.store.history_io import history_table
from isoslide.studies.intensity import floor_peaks, peak_of_integral
from isoslide.records import G, sample
from isoslide.scene import Scene
from fragility_cases import study_fixtures  # tests/ is on sys.path

TINY = {
    "records": ["Northridge_1994_PAC-175", "Coyote_Lake_1979_G02-050"],
    "stripes": {"im": "pga", "levels": [2.0, 6.0, 10.0]},
    "friction_samples": 3,
    "limit_states": [0.01, 0.1, 100.0],
    "bootstrap": {"n_boot": 8, "level": 0.9},
    "chunk_size": 5,
}


def _settings(**fragility):
    cfg = isoslide.config.load(None, {"fragility": copy.deepcopy(TINY)}, {"fragility": fragility})
    return fs.fragility_settings(cfg)


settings, study, analyses, dataset = study_fixtures(_settings, fs, fs.fragility_dataset, "isolated")


# ---- reproducibility -------------------------------------------------------------------------

def test_same_settings_and_seed_give_the_same_bytes(tmp_path, analyses, study, settings, dataset):
    again = fs.fragility_dataset(fs.solve_all(fs.check_settings(settings), "isolated"), study, settings, "isolated")
    a, b = write_netcdf(dataset, tmp_path / "a.nc"), write_netcdf(again, tmp_path / "b.nc")
    assert a.read_bytes() == b.read_bytes()


def test_another_seed_draws_other_friction(study):
    other = fs.check_settings(_settings(seed=study.seed + 1))
    assert not np.allclose(other.mu_k, study.mu_k)


def test_the_merged_analyses_do_not_depend_on_the_chunking(analyses, study):
    assert fs.n_chunks(study) == 4          # 18 analyses in chunks of 5
    one = fs.check_settings(_settings(chunk_size=1000))
    assert fs.n_chunks(one) == 1
    xr.testing.assert_identical(fs.solve_all(one, "isolated"), analyses["isolated"])


def test_a_chunk_alone_reproduces_its_analyses(analyses, study):
    part = fs.solve_chunk(study, 2, "isolated")
    xr.testing.assert_identical(part, analyses["isolated"].isel(analysis=slice(10, 15)))


def test_the_chunk_jobs_and_the_dataset_job_give_the_fitted_dataset(tmp_path, study, settings, dataset):
    """The pipeline's jobs: each chunk solved and written, then merged and fitted, equal the dataset."""
    job_log = logging.getLogger("isoslide.test")
    paths = [write_netcdf(fs.chunk_job(fs, "fragility", c, settings, job_log), tmp_path / f"{c}.nc")
             for c in range(fs.n_chunks(study))]
    for chunks in (paths, []):      # no chunk files: the study is solved in the dataset job
        got = fs.dataset_job(fs, fs.fragility_dataset, chunks, "fragility", settings, job_log)
        xr.testing.assert_identical(got, dataset)


def test_friction_draws_follow_the_configured_lognormal():
    big = fs.check_settings(_settings(friction_samples=4000, contents={"mu_k": {"median": 0.25, "log_std": 0.4}}))
    ln = np.log(big.mu_k.ravel())
    assert abs(np.median(big.mu_k) / 0.25 - 1) < 0.02          # 24,000 draws: standard error ~0.3 %
    assert abs(ln.std() / 0.4 - 1) < 0.02


def test_analyses_run_in_record_stripe_sample_order(analyses, study):
    ds = analyses["isolated"]
    assert list(ds.analysis.values) == list(range(18))
    assert list(ds.record.values[:9]) == ["Northridge_1994_PAC-175"] * 9
    assert list(ds.stripe.values[:9]) == [0, 0, 0, 1, 1, 1, 2, 2, 2]
    assert list(ds.friction_sample.values[:3]) == [0, 1, 2]
    np.testing.assert_array_equal(ds.mu_k.values, study.mu_k.ravel())


# ---- intensity measures ----------------------------------------------------------------------

def _dense_peak_velocity(accel_si, dt, refine=200):
    """PGV by brute force: the linear-between-samples acceleration integrated on a 200x finer grid."""
    t = dt * np.arange(accel_si.size)
    tf = np.linspace(0.0, t[-1], (accel_si.size - 1) * refine + 1)
    af = np.interp(tf, t, accel_si)
    v = np.concatenate([[0.0], np.cumsum(0.5 * (af[1:] + af[:-1]) * np.diff(tf))])
    return float(np.max(np.abs(v)))


@pytest.mark.parametrize("im, level", [("pga", 3.7), ("pgv", 0.45)])
def test_a_scaled_record_has_the_stripe_level_as_its_pga_or_pgv(im, level):
    rec = sample("Northridge_1994_PAC-175")
    pulse, pga, pgv = fs.scaled_pulse(rec, im, level)
    factor = (pga / (rec.pga * G))
    assert {"pga": pga, "pgv": pgv}[im] == pytest.approx(level, rel=1e-12)
    assert pga == pytest.approx(np.max(np.abs(rec.accel)) * G * factor, rel=1e-12)
    assert pgv == pytest.approx(_dense_peak_velocity(rec.accel * G * factor, rec.dt), rel=1e-6)
    assert pgv >= rec.pgv * factor                       # the samples alone can only miss the peak
    assert float(np.max(np.abs(pulse.accel(pulse.breakpoint_array)))) == pytest.approx(1.0, rel=1e-12)


def test_peak_of_integral_finds_the_extremum_inside_an_interval():
    # rate 1 - 2t: f = t - t^2 peaks at t = 0.5 with 0.25, between the rows 0 and 1 (both 0)
    assert peak_of_integral([0.0, 1.0], [0.0, 0.0], [1.0, -1.0]) == pytest.approx(0.25, rel=1e-14)
    assert peak_of_integral([0.0, 1.0, 2.0], [0.0, 1.0, 2.0], [1.0, 1.0, 1.0]) == 2.0


def test_peak_of_integral_is_exact_for_a_cubic_between_rows():
    # f = 1 - (t - 0.4)^2 (1 + t): its maximum f = 1 at t = 0.4 lies between the rows
    t = np.array([0.0, 0.3, 0.6, 0.9])
    f = 1.0 - (t - 0.4) ** 2 * (1.0 + t)
    rate = -(2.0 * (t - 0.4) * (1.0 + t) + (t - 0.4) ** 2)
    assert np.max(np.abs(f)) < 1.0 - 1e-3
    assert peak_of_integral(t, f, rate) == pytest.approx(1.0, rel=1e-12)


def test_fixed_base_floor_peaks_are_the_ground_peaks(analyses):
    ds = analyses["fixed_base"]
    np.testing.assert_allclose(ds.pfa.values, ds.pga.values, rtol=1e-12)
    np.testing.assert_allclose(ds.pfv.values, ds.pgv.values, rtol=1e-12)
    np.testing.assert_array_equal(ds.pga.values, analyses["isolated"].pga.values)


def test_isolated_floor_peaks_agree_with_a_dense_integration():
    """PFA/PFV from the exact path's rows (every 20 ms sample) against the integrator's every 0.15 ms.

    The rows alone miss the acceleration peak by about 1e-4 here; with the floor jerk between
    rows (cubic Hermite) the two agree to 1e-6.
    """
    rec = sample("Northridge_1994_PAC-175")
    pulse, pga, _ = fs.scaled_pulse(rec, "pga", 6.0)
    scene = Scene.from_physical(a_p=pga, T_p=1.0, M_b=1e6, T_b=2.5, xi_b=0.15, m_ec=2e4, mu_s=0.03, mu_k=0.03,
                                pulse=pulse)
    exact = solver.solve(scene, history=True)
    assert exact.model.endswith("+piecewise") and exact.u_max > 0
    dense = solver.solve(scene, history=True, max_step=1.5e-4, rtol=1e-10)
    pfa, pfv = floor_peaks(exact, scene)
    pfa_d, pfv_d = floor_peaks(dense, scene)
    rows_only = np.max(np.abs(history_table(exact, scene).columns["floor_accel"]))
    assert rows_only < pfa_d * (1 - 3e-5)
    assert pfa == pytest.approx(pfa_d, rel=1e-6)
    assert pfv == pytest.approx(pfv_d, rel=1e-6)
    assert pfa < 0.5 * pga                                # the isolation filters the ground motion


# ---- fits --------------------------------------------------------------------------------------

def test_stripe_counts_behind_each_curve_follow_from_u_max(dataset, study):
    u = dataset.u_max.values
    for ls in dataset.limit_state.values:
        exc = u > ls
        assert int(dataset.n_exceeded.sel(limit_state=ls)) == int(exc.sum())
        if int(dataset.fit_status.sel(limit_state=ls, im="pga")) != 0:
            continue
        z = [int(exc[dataset.stripe.values == j].sum()) for j in range(dataset.sizes["im_level"])]
        n = [int((dataset.stripe.values == j).sum()) for j in range(dataset.sizes["im_level"])]
        fit = fit_lognormal(dataset.im_level.values, np.array(z), np.array(n))
        assert float(dataset.theta.sel(limit_state=ls, im="pga")) == pytest.approx(fit.theta, rel=1e-12)
        assert float(dataset.beta.sel(limit_state=ls, im="pga")) == pytest.approx(fit.beta, rel=1e-12)


def test_a_curve_that_nothing_exceeds_is_nan_with_its_reason(dataset):
    assert int(dataset.n_exceeded.sel(limit_state=100.0)) == 0
    sel = dataset.sel(limit_state=100.0)
    assert np.all(np.isnan(sel.theta.values)) and np.all(np.isnan(sel.beta.values))
    meanings = dataset.fit_status.attrs["flag_meanings"].split()
    assert {meanings[int(s)] for s in sel.fit_status.values} == {"none_exceeded"}


def test_dataset_layout_units_and_provenance(dataset):
    for v in ("record", "stripe", "friction_sample", "mu_k", "pga", "pgv", "pfa", "pfv", "u_max",
              *datasets.FACET_VARIABLES.values()):
        assert dataset[v].dims == ("analysis",), v
    for v in ("theta", "beta", "theta_low", "theta_high", "beta_low", "beta_high"):
        assert dataset[v].dims == ("limit_state", "im"), v
    assert list(dataset.im.values) == ["pga", "pgv", "pfa", "pfv"]
    assert dataset.limit_state.attrs["units"] == "m"
    assert {v: dataset[v].attrs["units"] for v in ("pga", "pgv", "pfa", "pfv", "u_max")} == {
        "pga": "m s-2", "pgv": "m s-1", "pfa": "m s-2", "pfv": "m s-1", "u_max": "m"}
    for name in list(dataset.data_vars) + list(dataset.coords):
        assert "long_name" in dataset[name].attrs, name
    for key in ("Conventions", "source", "history", "references", "isoslide_config"):
        assert key in dataset.attrs


def test_scatter_shares_of_constructed_outcomes(study):
    base = {"record": ("analysis", np.repeat(["a", "b"], 3)), "stripe": ("analysis", np.zeros(6, int))}
    one = fs.check_settings(_settings(stripes={"levels": [1.0, 2.0]}))
    only_records = xr.Dataset({**base, "u_max": ("analysis", np.repeat([0.001, 1.0], 3))})
    out = fs.scatter_contributions(only_records, one)
    assert float(out.record_share_exceed.sel(limit_state=0.1, im_level=1.0)) == pytest.approx(1.0)
    assert float(out.record_share_ln_u.sel(im_level=1.0)) == pytest.approx(1.0)
    only_friction = xr.Dataset({**base, "u_max": ("analysis", np.tile([0.001, 0.5, 1.0], 2))})
    out = fs.scatter_contributions(only_friction, one)
    assert float(out.record_share_exceed.sel(limit_state=0.1, im_level=1.0)) == pytest.approx(0.0)
    assert float(out.record_share_ln_u.sel(im_level=1.0)) == pytest.approx(0.0)


# ---- bad settings ------------------------------------------------------------------------------

@pytest.mark.parametrize("override, match", [
    ({"stripes": {"levels": [3.0, 2.0]}}, r"fragility\.stripes\.levels = \[3\.0, 2\.0\].*strictly increasing"),
    ({"limit_states": [0.3, 0.2]}, r"fragility\.limit_states = .*strictly increasing"),
    ({"records": ["Northridge_1994_PAC-175", "no_such_record"]}, r"fragility\.records\[1\] = 'no_such_record'"),
    ({"records": ["Northridge_1994_PAC-175", "PAC-175"]}, r"fragility\.records = .*distinct records"),
    ({"contents": {"mass": 2e9}}, r"fragility\.contents\.mass = 2000000000\.0 .*mass / building\.M_b <= 1000"),
    ({"building": {"T_s": 0.5}}, r"fragility\.building\.m_st = 0\.0 .*0 < m_st < M_b"),
    ({"building": {"tfp": {"L": [0.3, 2.0, 2.0], "mu": [0.06, 0.02, 0.1], "d": [0.05, 0.4, 0.4]}}},
     r"fragility\.building\.tfp = .* is invalid: .*mu"),
    ({"building": {"tfp": {"L": [0.3, -2.0, 2.0], "mu": [0.02, 0.06, 0.1], "d": [0.05, 0.4, 0.4]}}},
     r"fragility\.building\.tfp = .* is invalid: .*L2"),
    ({"building": {"Q_d": 1.0e5, "tfp": {"L": [0.3, 2.0, 2.0], "mu": [0.02, 0.06, 0.1], "d": [0.05, 0.4, 0.4]}}},
     r"fragility\.building\.Q_d = 100000\.0 is set beside fragility\.building\.tfp"),
])
def test_bad_settings_name_the_key_value_and_range(override, match):
    with pytest.raises(ValueError, match=match):
        fs.check_settings(_settings(**override))


@pytest.mark.parametrize("override, key", [
    ({"contents": {"mu_k": {"log_std": -0.1}}}, "fragility.contents.mu_k.log_std"),
    ({"stripes": {"im": "sa"}}, "fragility.stripes.im"),
    ({"building": {"T_b": 0.0}}, "fragility.building.T_b"),
    ({"friction_samples": 0}, "fragility.friction_samples"),
])
def test_the_schema_rejects_out_of_range_values_naming_the_key(override, key):
    with pytest.raises(isoslide.config.ConfigError, match=key.replace(".", r"\.")):
        _settings(**override)


def test_a_friction_pendulum_building_runs_through_the_building_solver():
    """The building section takes a friction pendulum under a flexible superstructure, contents on the roof."""
    fp = isoslide.friction_pendulum(R=2.5, mu=0.05, M_b=1e6)
    cfg = _settings(building={"T_b": fp["T_b"], "Q_d": fp["Q_d"], "m_st": 6e5, "T_s": 0.5, "xi_s": 0.02,
                              "floor": "roof", "fixed_base": False},
                    stripes={"im": "pga", "levels": [3.0, 6.0]}, friction_samples=1)
    st = fs.check_settings(cfg)
    out = fs.solve_analyses(st, [0, 1], "isolated")
    models = set(datasets.model_labels(out, result="u_max").values.tolist())
    assert models and all(m.startswith("sliding-bearing+flexible+roof") for m in models), models
    sc = fs._scene(st, sample("Northridge_1994_PAC-175").as_pulse(), 3.0, 0.2, "isolated")
    assert (sc.isolator, sc.flexible, sc.floor) == ("sliding", True, "roof")


TFP = {"L": [0.3, 2.0, 2.0], "mu": [0.02, 0.06, 0.10], "d": [0.05, 0.4, 0.4]}
"""A triple friction pendulum of OpenSees's proportions: inner radius 0.3 m, outer 2 m, regime III period 4 s."""


def test_a_triple_friction_pendulum_building_is_the_bearings_scene_and_says_its_geometry():
    """With ``building.tfp`` every isolated analysis is the scene of :func:`isoslide.triple_friction_pendulum`
    (constant friction: the triple-pendulum model), its period and strength are the dataset's ``T_b`` and
    ``Q_d``, its geometry rides along, and the fixed base stays a fixed base."""
    cfg = _settings(building={"tfp": TFP, "xi_b": 0.0}, stripes={"im": "pga", "levels": [3.0, 6.0]},
                    friction_samples=1)
    st = fs.check_settings(cfg)
    pulse = sample("Northridge_1994_PAC-175").as_pulse()
    want = Scene.from_physical(a_p=3.0, T_p=fs.T_SCALE, M_b=1.0e6, xi_b=0.0, m_ec=500.0, mu_s=0.2, mu_k=0.2,
                               pulse=pulse, **isoslide.triple_friction_pendulum(TFP["L"], TFP["mu"], TFP["d"], 1.0e6))
    assert fs._scene(st, pulse, 3.0, 0.2, "isolated") == want
    assert fs._scene(st, pulse, 3.0, 0.2, "fixed_base").pi3 == 0.0
    out = fs.solve_analyses(st, [0, 1], "isolated", floor=False)
    models = set(datasets.model_labels(out, result="u_max").values.tolist())
    assert models and all(m.startswith("triple-friction-pendulum") for m in models), models
    attrs = fs.design_attrs(st, "isolated")
    tfp = isoslide.triple_friction_pendulum(TFP["L"], TFP["mu"], TFP["d"], 1.0e6)
    assert (attrs["T_b"], attrs["Q_d"]) == (tfp["T_b"], tfp["Q_d"])
    np.testing.assert_array_equal(attrs["tfp_L"], TFP["L"])
    assert "tfp_rate" not in attrs and "tfp_L" not in fs.design_attrs(fs.check_settings(_settings()), "isolated")


def test_a_triple_friction_pendulum_past_its_capacity_names_the_analysis():
    """A bearing whose restrainers the record reaches stops the study with the record, the stripe and the
    keys that size them, rather than a number past the model."""
    small = dict(TFP, d=[0.025, 0.1, 0.1])
    st = fs.check_settings(_settings(building={"tfp": small}, records=["Kobe_1995_TAK-090", "Northridge_1994_PAC-175"],
                                     stripes={"im": "pga", "levels": [6.0, 10.0]}, friction_samples=1))
    with pytest.raises(solver.CapacityError, match=r"record 'Kobe_1995_TAK-090' at stripe 10\.0: .*capacity.*"
                                                   r"fragility\.building\.tfp\.d"):
        fs.solve_analyses(st, [1], "isolated", floor=False)


def test_the_building_takes_storeys_and_puts_the_contents_on_a_floor_between():
    """A three-storey superstructure with the contents on floor 2: the scene of every analysis, and the
    dataset's attributes say the storeys and the floor."""
    cfg = _settings(building={"m_st": 6e5, "T_s": 0.5, "xi_s": 0.03, "storeys": 3, "floor": 2, "fixed_base": False},
                    stripes={"im": "pga", "levels": [3.0, 6.0]}, friction_samples=1)
    st = fs.check_settings(cfg)
    sc = fs._scene(st, sample("Northridge_1994_PAC-175").as_pulse(), 3.0, 0.2, "isolated")
    assert (sc.storeys, sc.floor, sc.floor_index) == (3, 2, 2)
    ds = fs.fragility_dataset(fs.solve_all(st, "isolated"), st, cfg, "isolated")
    assert (ds.attrs["storeys"], ds.attrs["floor"]) == (3, "2")
    assert np.isfinite(ds.u_max.values).all() and np.all(ds.pfa.values > 0)


@pytest.mark.parametrize("building, match", [
    ({"m_st": 6e5, "T_s": 0.5, "storeys": 3, "floor": 4},
     r"fragility\.building\.floor = 4 is out of range; allowed: 'base', 'roof' or an integer, 0 <= floor <= 3"),
    ({"storeys": 2}, r"fragility\.building\.storeys = 2 with a rigid superstructure"),
])
def test_a_floor_or_storeys_the_building_does_not_have_are_refused(building, match):
    with pytest.raises(ValueError, match=match):
        fs.check_settings(_settings(building=building))
