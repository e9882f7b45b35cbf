"""Fragility in the plane (isoslide.studies.fragility_planar): recorded pairs of the FEMA P695 suites, both
components at once against one at a time, their curves, intervals and comparisons."""

import copy
import math

import numpy as np
import pytest
import xarray as xr

import isoslide.config
from isoslide import solver
from isoslide.datasets import write_netcdf
from isoslide.pulses import sampled
from isoslide.records import G, suite
from isoslide.scene import Scene
from isoslide.studies import fragility_planar as fp
from isoslide.studies.intensity import align_pair, pair_peaks
from fragility_cases import study_fixtures  # tests/ is on sys.path

TINY = {
    "limit_states": [0.005, 0.05],
    "bootstrap": {"n_boot": 6, "level": 0.9},
    "planar": {"suites": ["fema-p695-far-field", "fema-p695-near-field-pulse"], "pairs": 2, "angles": [0.0, 90.0],
               "stripes": {"im": "pga", "levels": [3.0, 8.0]}, "friction_samples": 1, "chunk_size": 6},
}


def _settings(planar=None, **fragility):
    base = copy.deepcopy(TINY)
    base["planar"].update(planar or {})
    cfg = isoslide.config.load(None, {"fragility": base}, {"fragility": fragility})
    return fp.planar_settings(cfg)


settings, study, analyses, dataset = study_fixtures(_settings, fp, fp.planar_dataset, "fixed_base")


# ---- the analysis table and reproducibility -------------------------------------------------------

def test_the_table_runs_floor_ground_motion_orientation_stripe_sample(study):
    assert study.shape == (1, 4, 2, 2, 1) and study.size == 16
    assert [gm.name for gm in study.motions[:2]] == [gm.name for gm in suite("fema-p695-far-field")[:2]]
    assert study.suite_index.tolist() == [0, 0, 1, 1]
    tab = fp.analysis_table(study)
    assert tab["ground_motion"].tolist()[:8] == [0, 0, 0, 0, 1, 1, 1, 1]
    assert tab["angle"].tolist()[:4] == [0.0, 0.0, 90.0, 90.0]
    # one friction draw per ground motion, stripe and draw, shared by the orientations
    np.testing.assert_array_equal(tab["mu_k"][tab["orientation"] == 0], tab["mu_k"][tab["orientation"] == 1])
    assert fp.n_chunks(study) == 3


def test_same_settings_and_seed_give_the_same_bytes(tmp_path, analyses, study, settings, dataset):
    again = fp.planar_dataset(fp.solve_all(fp.check_settings(settings), "fixed_base"), study, settings, "fixed_base")
    a, b = write_netcdf(dataset, tmp_path / "a.nc"), write_netcdf(again, tmp_path / "b.nc")
    assert a.read_bytes() == b.read_bytes()


def test_the_analyses_do_not_depend_on_the_chunking_and_a_chunk_reproduces_its_own(analyses, settings):
    one = fp.check_settings(_settings({"chunk_size": 1000}))
    assert fp.n_chunks(one) == 1
    xr.testing.assert_identical(fp.solve_all(one, "isolated"), analyses["isolated"])
    part = fp.solve_chunk(fp.check_settings(settings), 1, "isolated")
    xr.testing.assert_identical(part, analyses["isolated"].isel(analysis=slice(6, 12)))


def test_another_seed_draws_other_friction_and_sampled_angles_are_seeded(study):
    other = fp.check_settings(_settings(seed=study.seed + 1))
    assert not np.allclose(other.mu_k, study.mu_k)
    drawn = fp.check_settings(_settings({"sampled_angles": True, "angles": [0.0, 0.0, 0.0]}))
    assert drawn.angles.shape == (4, 3, 2, 1)
    assert np.all((drawn.angles >= 0) & (drawn.angles < 180)) and np.unique(drawn.angles).size == drawn.angles.size
    np.testing.assert_array_equal(drawn.angles,
                                  fp.check_settings(_settings({"sampled_angles": True, "angles": [0.0, 0.0, 0.0]})).angles)


# ---- the physics of each analysis ----------------------------------------------------------------

def test_pairs_are_scaled_to_the_rotd50_stripe(analyses, study):
    ds = analyses["fixed_base"]
    np.testing.assert_allclose(ds.pga_rotd50.values, study.levels[ds.stripe.values], rtol=1e-12)
    gm = study.motions[0]
    ax, ay = align_pair(gm.x.accel * G, gm.y.accel * G, gm.x.dt, gm.x.t_start, gm.y.t_start)
    first = ds.isel(analysis=0)
    pga, pgv = pair_peaks(ax * float(first.scale_factor), ay * float(first.scale_factor), gm.x.dt)
    assert float(first.pga_rotd50) == pytest.approx(pga, rel=1e-12)
    assert float(first.pgv_rotd50) == pytest.approx(pgv, rel=1e-12)
    # along the building's axes: at 0 degrees the recorded components, at 90 degrees the other way round
    zero = ds.where(ds.angle == 0.0, drop=True)
    assert float(zero.pga_x[0]) == pytest.approx(float(zero.scale_factor[0]) * np.max(np.abs(ax)), rel=1e-12)


def test_the_building_and_contents_are_isotropic_so_the_planar_slide_does_not_depend_on_the_angle(analyses):
    for base in fp.BASES:
        ds = analyses[base]
        u0 = ds.u_max.values[ds.orientation.values == 0]
        u90 = ds.u_max.values[ds.orientation.values == 1]
        np.testing.assert_allclose(u90, u0, rtol=2e-3, atol=1e-6)
    assert analyses["fixed_base"].u_max.max() > 0.01     # the contents do slide here


def test_the_floor_peaks_in_the_plane_are_the_ground_vectors_on_a_fixed_base_and_isotropic(analyses, study):
    """On a fixed base PFA is the largest length of the scaled ground-acceleration vector (at a sample: the
    record is linear between samples); on the isolated slab the floor peaks do not depend on the angle and
    the isolation keeps PFA below it."""
    fixed, iso = analyses["fixed_base"], analyses["isolated"]
    for k in range(0, fixed.sizes["analysis"], 7):
        row = fixed.isel(analysis=k)
        gm = next(g for g in study.motions if g.name == str(row.ground_motion.values))
        ax, ay = align_pair(gm.x.accel * G, gm.y.accel * G, gm.x.dt, gm.x.t_start, gm.y.t_start)
        assert float(row.pfa) == pytest.approx(float(row.scale_factor) * np.max(np.hypot(ax, ay)), rel=1e-12)
    o = iso.orientation.values
    for name in ("pfa", "pfv"):
        np.testing.assert_allclose(iso[name].values[o == 1], iso[name].values[o == 0], rtol=1e-3)
    assert np.all(iso.pfa.values < fixed.pfa.values)
    assert np.all(fixed.pfv.values > 0.0) and np.all(iso.pfv.values > 0.0)


def test_one_component_at_90_degrees_is_the_other_component_at_0(analyses):
    """At 90 degrees the building's x axis sees -a_y and its y axis a_x: the 1-D answers swap (a sign flip
    leaves a 1-D peak slide unchanged)."""
    for base in fp.BASES:
        ds = analyses[base]
        o = ds.orientation.values
        np.testing.assert_allclose(ds.u_max_x.values[o == 1], ds.u_max_y.values[o == 0], rtol=1e-9, atol=1e-12)
        np.testing.assert_allclose(ds.u_max_y.values[o == 1], ds.u_max_x.values[o == 0], rtol=1e-9, atol=1e-12)


def test_the_x_analysis_is_the_1d_solve_of_the_recorded_x_component(analyses, study):
    ds = analyses["isolated"]
    i = int(np.flatnonzero((ds.orientation.values == 0) & (ds.stripe.values == 1))[2])
    row = ds.isel(analysis=i)
    gm = next(g for g in study.motions if g.name == str(row.ground_motion.values))
    f, a_ref, mu = float(row.scale_factor), float(row.pga_rotd50), float(row.mu_k)
    b = study.building
    scene = Scene.from_physical(a_p=a_ref, T_p=1.0, M_b=b["M_b"], T_b=b["T_b"], xi_b=b["xi_b"], m_ec=500.0,
                                mu_s=mu, mu_k=mu, pulse=sampled(gm.x.accel * G * f / a_ref, gm.x.dt, gm.x.t_start))
    assert float(row.u_max_x) == pytest.approx(solver.solve(scene).u_max, rel=1e-12, abs=1e-15)
    assert str(row.model_contact.attrs["flag_meanings"]).split()[int(row.model_contact)] == "plane"


# ---- the fits and the comparisons -----------------------------------------------------------------

def test_fits_cover_floor_group_motion_limit_state_and_im(dataset, study):
    assert dict(dataset.theta.sizes) == {"floor": 1, "group": 3, "motion": 3, "limit_state": 2, "im": 5}
    assert dataset.im.values.tolist() == ["pga_rotd50", "pgv_rotd50", "sa_rotd50", "pfa", "pfv"]
    assert dataset.group.values.tolist() == ["all", "fema-p695-far-field", "fema-p695-near-field-pulse"]
    assert dataset.n_outcomes.sel(motion="one_component").values.tolist() == [[32, 16, 16]]
    assert dataset.n_outcomes.sel(motion="planar").values.tolist() == [[16, 8, 8]]
    ok = dataset.fit_status.values == 0
    assert ok.any()
    assert np.all(np.isfinite(dataset.theta.values[ok])) and np.all(np.isnan(dataset.theta.values[~ok]))
    # exceedances counted from the analyses
    exc = int((dataset.u_max > 0.005).sum())
    assert int(dataset.n_exceeded.sel(floor="base", group="all", motion="planar", limit_state=0.005)) == exc
    assert dataset.attrs["reference_suite"] == "fema-p695-far-field"


def test_the_comparisons_are_the_ratios_of_the_fitted_medians(dataset):
    t = dataset.theta.sel(floor="base")
    ratio = dataset.theta_ratio.sel(floor="base")
    np.testing.assert_allclose(ratio.sel(comparison="one_component").values,
                               (t.sel(motion="planar") / t.sel(motion="one_component")).values, rtol=1e-12)
    change = dataset.beta_change.sel(floor="base", comparison="max_component")
    b = dataset.beta.sel(floor="base")
    np.testing.assert_allclose(change.values, (b.sel(motion="planar") - b.sel(motion="max_component")).values)
    s = dataset.suite_theta_ratio.sel(floor="base", suite="fema-p695-near-field-pulse")
    np.testing.assert_allclose(s.values, (t.sel(group="fema-p695-near-field-pulse")
                                          / t.sel(group="fema-p695-far-field")).values, rtol=1e-12)
    ref = dataset.suite_theta_ratio.sel(suite="fema-p695-far-field").values
    assert np.all(np.isnan(ref) | (ref == 1.0))
    assert set(dataset.floor_theta_ratio.values[np.isfinite(dataset.floor_theta_ratio.values)]) == {1.0}


def test_bootstrap_bounds_come_from_the_resamples_and_are_seeded(dataset, study, analyses):
    ok = dataset.fit_status.values == 0
    lo, hi = dataset.theta_low.values[ok], dataset.theta_high.values[ok]
    finite = np.isfinite(lo)
    assert finite.any() and np.all(lo[finite] <= hi[finite])
    again = fp.fit_curves(analyses["fixed_base"], study)
    xr.testing.assert_identical(again.theta_ratio_low, dataset.theta_ratio_low)


@pytest.mark.parametrize("base", ["isolated", "fixed_base"])
def test_the_bootstrap_fits_are_the_resampled_analyses_fitted_one_by_one(analyses, base):
    """All resamples of a curve fitted at once equal each resample's rows fitted by fit_lognormal."""
    study = fp.check_settings(_settings(bootstrap={"n_boot": 40, "level": 0.9}))
    ds = analyses[base]
    members, outcomes = fp._members(study, ds), fp._outcomes(ds)
    rows = fp._group_rows(members, study)
    _, _, status = fp._fit_all(study, ds, outcomes, rows)
    boot_t, boot_b = fp._boot_fits(study, ds, outcomes, members, rows, fp._boot_draws(study), status == 0)
    rng = np.random.default_rng([study.seed, fp.BOOT_SEED_OFFSET])
    by_suite = [np.flatnonzero(study.suite_index == i) for i in range(len(study.suites))]
    for i in range(study.n_boot):
        drawn = [idx[rng.integers(0, idx.size, size=idx.size)] for idx in by_suite]
        drawn_rows = [[np.concatenate([members[f][g] for g in gms]) for gms in [np.concatenate(drawn)] + drawn]
                      for f in range(len(study.floors))]
        theta, beta, _ = fp._fit_all(study, ds, outcomes, drawn_rows)
        theta[status != 0], beta[status != 0] = np.nan, np.nan
        np.testing.assert_allclose(boot_t[i], theta, rtol=1e-10)
        np.testing.assert_allclose(boot_b[i], beta, rtol=1e-10)
    assert np.isfinite(boot_t).any()


def test_no_resamples_give_no_bounds(analyses, settings):
    study = fp.check_settings(_settings(bootstrap={"n_boot": 0}))
    fits = fp.fit_curves(analyses["fixed_base"], study)
    assert np.all(np.isnan(fits.theta_low.values)) and np.all(np.isnan(fits.theta_ratio_high.values))
    assert np.isfinite(fits.theta.values).any() and not fits.n_boot_failed.values.any()


def test_the_planar_slide_is_at_least_the_one_component_slides_here(analyses):
    """Not a law, but what these records do: the pair slides the contents at least as far as the larger
    component alone in most analyses that slide at all."""
    ds = analyses["fixed_base"]
    slides = ds.u_max.values > 1e-4
    ratio = ds.u_max.values[slides] / np.maximum(ds.u_max_x.values, ds.u_max_y.values)[slides]
    assert np.median(ratio) >= 1.0


# ---- settings ----------------------------------------------------------------------------------------

def test_dataset_names_follow_the_configuration():
    assert fp.dataset_names(_settings()) == ["fragility_planar", "fragility_planar_fixed_base"]
    assert fp.dataset_names(_settings(building={"fixed_base": False})) == ["fragility_planar"]
    assert fp.dataset_names(_settings({"enabled": False})) == []
    assert [fp.base_of(n) for n in ("fragility_planar", "fragility_planar_fixed_base")] == list(fp.BASES)


def test_the_planar_settings_leave_out_the_1d_records_and_the_1d_settings_leave_out_planar():
    from isoslide.studies import fragility_study
    cfg = isoslide.config.load(None, {"fragility": copy.deepcopy(TINY)})
    assert set(fp.planar_settings(cfg)["fragility"]) == {"building", "contents", "limit_states", "seed",
                                                         "bootstrap", "planar"}
    assert "planar" not in fragility_study.fragility_settings(cfg)["fragility"]


@pytest.mark.parametrize("planar, fragility, pattern", [
    ({"pairs": 1}, {}, r"fragility\.planar\.suites\[0\] = 'fema-p695-far-field' gives 1 ground motion"),
    ({"suites": ["fema-p695-near-field", "fema-p695-near-field-pulse"]}, {}, r"share ground motions"),
    ({"suites": ["no_such_suite"]}, {}, r"fragility\.planar\.suites\[0\] = 'no_such_suite' cannot be read"),
    ({"suites": ["pyslammer"]}, {}, r"one horizontal component"),
    ({"floors": ["roof"]}, {}, r"'roof' with a rigid superstructure"),
    ({"angles": [0.0, 0.0]}, {}, r"fragility\.planar\.angles = \[0\.0, 0\.0\] is invalid; allowed: distinct"),
    ({"stripes": {"levels": [8.0, 3.0]}}, {}, r"fragility\.planar\.stripes\.levels"),
    ({}, {"building": {"tfp": {"L": [0.3, 2.0, 2.0], "mu": [0.02, 0.06, 0.1], "d": [0.05, 0.4, 0.4]}}},
     r"fragility\.building\.tfp = .* has constant friction, .*allowed: mu_slow below mu and rate > 0"),
])
def test_bad_settings_are_refused_naming_the_key(planar, fragility, pattern):
    with pytest.raises(ValueError, match=pattern):
        fp.check_settings(_settings(planar, **fragility))


def test_floors_of_a_flexible_superstructure_are_compared():
    """Contents on the base and on the roof of a flexible superstructure: one table, the roof's median
    over the base's with its interval."""
    s = _settings({"floors": ["base", "roof"], "pairs": 2, "angles": [30.0], "suites": ["fema-p695-near-field-pulse"]},
                  building={"T_s": 0.5, "m_st": 5.0e5, "xi_s": 0.05, "fixed_base": False})
    study = fp.check_settings(s)
    ds = fp.planar_dataset(fp.solve_all(study, "isolated"), study, s, "isolated")
    assert ds.floor.values.tolist() == ["base", "roof"]
    assert sorted(set(ds.contents_floor.values.tolist())) == ["base", "roof"]
    base, roof = (ds.u_max.values[ds.contents_floor.values == f] for f in ("base", "roof"))
    assert not np.allclose(base, roof)
    r = ds.floor_theta_ratio.sel(floor="roof").values
    t = ds.theta.values
    np.testing.assert_allclose(r, t[1] / t[0], rtol=1e-12)
    assert math.isfinite(float(ds.u_max.max()))


def test_a_lead_rubber_bearing_runs_in_the_plane_and_its_slides_do_not_depend_on_the_angle():
    """The bilinear bearing's circular yield surface is isotropic: the planar slides and floor peaks at 0 and
    90 degrees agree, and the bearing yields (the floor's PFA above the elastic bearing's would not tell)."""
    s = _settings({"pairs": 2, "angles": [0.0, 90.0], "suites": ["fema-p695-near-field-pulse"]},
                  building={"Q_d": 0.04 * 9.81 * 1.0e6, "D_y": 0.01})
    study = fp.check_settings(s)
    ds = fp.solve_all(study, "isolated")
    o = ds.orientation.values
    assert str(ds.model_isolator.attrs["flag_meanings"]).split()[int(ds.model_isolator[0])] == "bilinear"
    for name in ("u_max", "pfa", "pfv"):
        np.testing.assert_allclose(ds[name].values[o == 1], ds[name].values[o == 0], rtol=2e-3, atol=1e-6)
    assert ds.u_max.max() > 0.0


def test_a_triple_friction_pendulum_whose_friction_rises_with_speed_is_the_planar_scenes_bearing():
    """``building.tfp`` with friction rising with speed: every isolated analysis, planar and one-component, is
    the scene of :func:`isoslide.triple_friction_pendulum` (the planar triple-pendulum model's groups), the
    fixed base stays a fixed base, and the datasets state the bearing."""
    tfp = {"L": [0.3, 2.0, 2.0], "mu": [0.02, 0.06, 0.10], "d": [0.05, 0.4, 0.4], "mu_slow": [0.01, 0.03, 0.05],
           "rate": 30.0}
    s = _settings({"pairs": 2, "angles": [30.0], "suites": ["fema-p695-near-field-pulse"]},
                  building={"tfp": tfp, "xi_b": 0.0})
    study = fp.check_settings(s)
    px, py = (sampled(np.sin(np.linspace(0.0, 3.0, 301)), 0.01) for _ in range(2))
    kw = isoslide.triple_friction_pendulum(tfp["L"], tfp["mu"], tfp["d"], 1.0e6, mu_slow=tfp["mu_slow"], rate=30.0)
    want = Scene.from_physical(a_p=3.0, T_p=fp.T_SCALE, M_b=1.0e6, xi_b=0.0, m_ec=500.0, mu_s=0.2, mu_k=0.2, pulse=px,
                               pulse_y=py, angle=0.5, **kw)
    got = fp._scene(study, "isolated", "base", 3.0, 0.2, px, py, 0.5)
    assert got == want and got.isolator == "tfp" and got.pi22 == 0.5 and got.pi23 > 0.0
    assert fp._scene(study, "fixed_base", "base", 3.0, 0.2, px).pi3 == 0.0
    attrs = fp.design_attrs(study, "isolated")
    assert attrs["tfp_rate"].tolist() == [30.0] * 3 and attrs["T_b"] == kw["T_b"]


# ---- floors of a building of several storeys ---------------------------------------------------------

FLEXIBLE = {"T_s": 0.5, "m_st": 8.0e5, "xi_s": 0.03, "fixed_base": False}


@pytest.mark.parametrize("planar, building, pattern", [
    ({"floors": [0, 4]}, {"storeys": 3}, r"fragility\.planar\.floors\[1\] = 4 is out of range; allowed: 'base', "
                                         r"'roof' or an integer, 0 <= floor <= 3 \(fragility\.building\.storeys = 3\)"),
    ({"floors": [0, "base"]}, {"storeys": 3}, r"fragility\.planar\.floors = \[0, 'base'\] is invalid; allowed: "
                                              r"distinct floors"),
    ({"floors": [3, "roof"]}, {"storeys": 3}, r"distinct floors \(0 is 'base', 3 is 'roof'"),
    ({"floors": [0, 1]}, {"T_s": 0.0}, r"fragility\.planar\.floors has 'roof' with a rigid superstructure"),
    ({"floors": [0]}, {"storeys": 2, "T_s": 0.0},
     r"fragility\.building\.storeys = 2 with a rigid superstructure \(building\.T_s = 0\)"),
])
def test_floors_outside_the_building_are_refused_naming_the_key_value_and_range(planar, building, pattern):
    with pytest.raises(ValueError, match=pattern):
        fp.check_settings(_settings(planar, building={**FLEXIBLE, **building}))


@pytest.mark.parametrize("planar, building, key", [
    ({"floors": [-1]}, {}, "fragility.planar.floors"),
    ({"floors": ["middle"]}, {}, "fragility.planar.floors"),
    ({}, {"storeys": 0}, "fragility.building.storeys"),
    ({}, {"storeys": 65}, "fragility.building.storeys"),
])
def test_the_schema_rejects_floors_and_storeys_out_of_range(planar, building, key):
    with pytest.raises(isoslide.config.ConfigError, match=key.replace(".", r"\.")):
        _settings(planar, building={**FLEXIBLE, **building})


def test_floor_numbers_are_named_as_the_scene_names_them():
    s = _settings({"floors": [0, 1, 2, 3]}, building={**FLEXIBLE, "storeys": 3})
    assert fp.check_settings(s).floors == ("base", 1, 2, "roof")
    assert fp.check_settings(_settings({"floors": ["roof", 0]}, building={**FLEXIBLE, "storeys": 3})).floors == \
        ("roof", "base")


@pytest.fixture(scope="module")
def storeys_dataset():
    """Contents on the slab, floor 1 and the roof of a three-storey isolated building: 2 pairs x 2 stripes."""
    s = _settings({"floors": [0, 1, 3], "pairs": 2, "angles": [0.0], "suites": ["fema-p695-near-field-pulse"],
                   "stripes": {"im": "pga", "levels": [2.0, 6.0]}},
                  building={**FLEXIBLE, "storeys": 3})
    study = fp.check_settings(s)
    return study, fp.planar_dataset(fp.solve_all(study, "isolated"), study, s, "isolated")


def test_a_building_of_several_storeys_labels_its_floors_and_says_its_storeys(storeys_dataset):
    study, ds = storeys_dataset
    assert ds.floor.values.tolist() == ["base", "1", "roof"]
    assert ds.contents_floor.values.tolist() == ["base"] * 4 + ["1"] * 4 + ["roof"] * 4
    assert (ds.attrs["storeys"], ds.attrs["floors"]) == (3, "base, 1, roof")
    r = ds.floor_theta_ratio.values
    np.testing.assert_allclose(r, ds.theta.values / ds.theta.values[:1], rtol=1e-12)


def test_the_floors_move_as_a_flexible_superstructure_does(storeys_dataset):
    """The same pairs, stripes and friction draws on each floor: the floor accelerations grow up the building
    (the superstructure's first mode), so the roof's PFA exceeds the slab's, floor 1 in between; the slides
    differ from floor to floor."""
    study, ds = storeys_dataset
    pfa = {f: ds.pfa.values[ds.contents_floor.values == f] for f in ("base", "1", "roof")}
    assert np.all(pfa["roof"] > pfa["base"])
    assert np.all(pfa["1"] > pfa["base"]) and np.all(pfa["1"] < pfa["roof"])
    u = {f: ds.u_max.values[ds.contents_floor.values == f] for f in ("base", "roof")}
    assert u["base"].max() > 0.01 and not np.allclose(u["base"], u["roof"])
    for name in ("ground_motion", "stripe", "friction_sample", "mu_k", "pga_rotd50"):
        rows = ds[name].values.reshape(3, -1)
        assert (rows == rows[0]).all(), name


def test_an_analysis_on_a_floor_between_is_the_scene_on_that_floor(storeys_dataset):
    study, ds = storeys_dataset
    row = ds.isel(analysis=int(np.flatnonzero(ds.contents_floor.values == "1")[-1]))
    gm = next(g for g in study.motions if g.name == str(row.ground_motion.values))
    ax, ay = align_pair(gm.x.accel * G, gm.y.accel * G, gm.x.dt, gm.x.t_start, gm.y.t_start)
    a_ref = float(row.pga_rotd50)
    f = float(row.scale_factor) / a_ref
    t0 = min(gm.x.t_start, gm.y.t_start)
    b, c, mu = study.building, study.contents, float(row.mu_k)
    scene = Scene.from_physical(a_p=a_ref, T_p=1.0, M_b=b["M_b"], T_b=b["T_b"], xi_b=b["xi_b"], m_ec=c["mass"],
                                mu_s=mu, mu_k=mu, pulse=sampled(ax * f, gm.x.dt, t0), pulse_y=sampled(ay * f, gm.x.dt, t0),
                                m_st=b["m_st"], T_s=b["T_s"], xi_s=b["xi_s"], storeys=3, floor=1)
    assert float(row.u_max) == pytest.approx(solver.solve(scene, rtol=study.rtol).u_max, rel=1e-9, abs=1e-12)


def test_one_storey_and_the_slab_alone_leave_the_study_as_it_was(analyses, dataset):
    """storeys = 1 and floors = [base] (or [0]) are the planar study of one floor: the same analyses, the floor
    labelled base, one storey said."""
    s = _settings({"floors": [0]})
    study = fp.check_settings(s)
    assert study.floors == ("base",) and study.shape[0] == 1
    xr.testing.assert_identical(fp.solve_chunk(study, 0, "isolated"), analyses["isolated"].isel(analysis=slice(0, 6)))
    assert dataset.floor.values.tolist() == ["base"]
    assert (dataset.attrs["storeys"], dataset.attrs["floors"]) == (1, "base")
