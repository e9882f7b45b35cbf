"""The isolation studies (isoslide.studies.isolation_study) and their figures (isoslide.reports.isolation_plot)."""

import copy
import tempfile
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import isoslide
import isoslide.config
from isoslide.studies import design, isolation_study, sweep
from isoslide.reports import isolation_plot
from isoslide.config import ConfigError

G = 9.80665


def tiny_config(**isolation):
    """The default configuration with tiny isolation grids (every overlay key replaces its default)."""
    overlay = {
        "friction_pendulum": {"pi3": [2.0], "pi9": [0.05, 0.2], "pi2": {"num": 5}},
        "lead_rubber": {"pi3": [2.0], "pi9": [0.1], "pi2": {"num": 5}},
        "flexible": {"pi3": [1.0], "pi12": [0.0, 0.5], "pi2": {"num": 5}},
        "design": {"pulses": ["ricker"], "T_p": [1.0], "records": [], "mu_k": {"start": 0.02, "stop": 0.3, "num": 3}},
        # a_p = 0.05 m/s^2: both pendulums hold (below mu_slow g = 0.21 m/s^2); 0.3: only the speed-dependent one
        # breaks away (below mu g = 0.41 m/s^2); 6: both slide.  The triple pendulum: held at 0.05 (below mu1 g =
        # 0.13 m/s^2), its inner slider alone (regime I) at 0.3, its outer surfaces (regime III) at 6
        "bearings": {"a_p": [0.05, 0.3, 6.0], "mu_k": [0.05, 0.1]},
    }
    for k, v in isolation.items():
        overlay[k] = {**overlay.get(k, {}), **v}
    return isoslide.config.load(None, {"isolation": overlay})


@pytest.fixture(scope="module")
def bearings():
    """The bearing study of the tiny configuration: ``(cfg, {"isolation_bearings": dataset})``."""
    cfg = tiny_config()
    return cfg, {"isolation_bearings": isolation_study.bearings_dataset(isolation_study.isolation_settings(cfg))}


@pytest.fixture(scope="module")
def solved(bearings):
    cfg, data = bearings
    data = {**data, **{name: sweep.solve_study(spec) for name, spec in isolation_study.study_specs(cfg).items()}}
    settings = isolation_study.isolation_settings(cfg)
    data["isolation_rigid"] = isolation_study.rigid_dataset(
        {"base": data["iso_flex_base"], "roof": data["iso_flex_roof"]}, settings)
    data["isolation_design"] = isolation_study.design_dataset(settings)
    return cfg, data


# ----------------------------------------------------------------------------------------------
# the studies are ordinary studies of isoslide.studies.sweep
# ----------------------------------------------------------------------------------------------

def test_default_studies_sweep_the_bearing_and_superstructure_groups():
    specs = isolation_study.study_specs(isoslide.config.load())
    assert list(specs) == isolation_study.study_names()
    fp, lrb = specs["iso_fp"], specs["iso_lrb"]
    assert list(fp["dims"]) == ["pi3", "pi9"] and fp["fixed"]["pi10"] == 0.0      # sliding bearing
    assert list(lrb["dims"]) == ["pi3", "pi9"] and lrb["fixed"]["pi10"] > 0.0     # bilinear
    assert [specs[f"iso_flex_{f}"]["floor"] for f in ("base", "roof")] == ["base", "roof"]
    assert 0.0 in specs["iso_flex_roof"]["dims"]["pi12"]
    # a pendulum of R = 1.5 ... 4 m (T_b = 2.5 ... 4 s) under pulses of T_p = 1 ... 3 s
    assert min(fp["dims"]["pi3"]) <= 2.5 / 3.0 + 0.2 and max(fp["dims"]["pi3"]) >= 4.0 / 1.0 - 1.0
    for spec in specs.values():
        assert spec["pi2"]["stop"] != "auto" and spec["fixed"]["pi5"] == 1.0    # contents from `defaults`


def test_paper_studies_sit_on_the_base_by_default():
    specs = sweep.check_config(isoslide.config.load())
    assert {s["floor"] for s in specs.values()} == {"base"}


def test_roof_study_builds_roof_scenes_and_records_the_floor():
    spec = isolation_study.study_specs(tiny_config())["iso_flex_roof"]
    grid = sweep.build_grid(spec)
    scenes = grid.scenes()
    assert {s.floor for s in scenes} == {"roof"} and {s.pi12 for s in scenes} == {0.0, 0.5}
    ds = sweep.solve_study(spec)
    assert ds.attrs["floor"] == "roof" and set(ds["pi1"].dims) == {"pi3", "pi12", "pi2"} and ds["pi1"].dims[-1] == "pi2"
    # the dataset's answer is the solver's for the same roof scene
    one = grid.scenes([grid.size - 2])[0]
    got = float(ds["pi1"].sel(pi3=one.pi3, pi12=one.pi12, pi2=one.pi2))
    assert got == isoslide.solve(one, rtol=spec["solver"]["rtol"]).pi1


def test_flexible_study_without_the_rigid_reference_is_refused():
    with pytest.raises(ConfigError, match=r"isolation\.flexible\.pi12 = \[0\.1, 0\.5\] needs 0\.0"):
        isolation_study.study_specs(tiny_config(flexible={"pi12": [0.1, 0.5]}))


def test_bad_floor_of_a_study_names_its_key():
    cfg = isoslide.config.load()
    study = copy.deepcopy(cfg["studies"]["fig5_pi3"])
    study["floor"] = "attic"
    with pytest.raises(ConfigError, match=r"studies\.fig5_pi3\.floor = 'attic' is invalid"):
        sweep.normalise_study("fig5_pi3", study, cfg)


# ----------------------------------------------------------------------------------------------
# the rigid-superstructure reduction's error, on hand-made curves
# ----------------------------------------------------------------------------------------------

def _flex(pi1_rigid, pi1_flex, floor):
    pi2 = [0.1, 0.2, 0.3]
    data = np.array([[pi1_rigid, pi1_flex]])
    return xr.Dataset({"pi1": (("pi3", "pi12", "pi2"), data)},
                      coords={"pi3": [1.0], "pi12": [0.0, 0.5], "pi2": pi2, "pi11": 0.8, "pi13": 0.02},
                      attrs={"floor": floor, "pulse": "ricker"})


def test_rigid_error_by_hand():
    """Rigid curve (1.05, 0.5, 0.2) against the flexible (1.0, 0.5, 0): relative errors 0.05, 0 and
    +inf (only the rigid model slides); relative to the flexible peak 1.0: 0.05, 0, 0.2."""
    base = _flex([1.05, 0.5, 0.2], [1.0, 0.5, 0.0], "base")
    roof = _flex([1.0, 0.5, 0.0], [2.0, 1.0, 0.0], "roof")
    ds = isolation_study.rigid_error({"base": base, "roof": roof}, 0.1)
    b = ds.sel(floor="base", pi3=1.0, pi12=0.5)
    np.testing.assert_allclose(b["rel_error"].values, [0.05, 0.0, np.inf], rtol=1e-12)
    np.testing.assert_allclose(b["peak_error"].values, [0.05, 0.0, 0.2], rtol=1e-12)
    assert b["holds"].values.tolist() == [1, 1, 0]
    assert float(b["share_holds"]) == pytest.approx(2.0 / 3.0, rel=1e-12)
    assert float(b["max_peak_error"]) == pytest.approx(0.2, rel=1e-12)
    assert float(b["peak_ratio"]) == pytest.approx(1.0 / 1.05, rel=1e-12)
    assert float(ds["pi12_limit"].sel(floor="base", pi3=1.0)) == 0.0           # fails at 0.5
    r = ds.sel(floor="roof", pi3=1.0, pi12=0.5)
    np.testing.assert_allclose(r["rel_error"].values, [-0.5, -0.5, 0.0], rtol=1e-12)
    assert float(r["peak_ratio"]) == pytest.approx(2.0, rel=1e-12)
    assert float(r["share_holds"]) == 0.0                                      # neither slides at Pi2 = 0.3
    # a wider band accepts the base's 0.2
    wide = isolation_study.rigid_error({"base": base, "roof": roof}, 0.25)
    assert float(wide["pi12_limit"].sel(floor="base", pi3=1.0)) == 0.5
    assert isolation_study.rigid_summary(ds)[0] == ("base", 1.0, 0.0, 0.5, pytest.approx(0.2), pytest.approx(1 / 1.05))


def test_rigid_error_needs_the_rigid_reference_and_both_floors():
    base = _flex([1.0, 0.5, 0.0], [1.0, 0.5, 0.0], "base")
    with pytest.raises(ValueError, match="lacks floor 'roof'"):
        isolation_study.rigid_error({"base": base}, 0.1)
    no_rigid = base.assign_coords(pi12=[0.1, 0.5])
    with pytest.raises(ValueError, match="lacks 0"):
        isolation_study.rigid_error({"base": no_rigid, "roof": no_rigid}, 0.1)


def test_rigid_dataset_of_solved_studies_is_zero_at_the_rigid_reference(solved):
    _, data = solved
    ds = data["isolation_rigid"]
    assert ds.attrs["Conventions"].startswith("CF") and "isoslide_config" in ds.attrs
    assert np.all(ds["rel_error"].sel(pi12=0.0).values == 0.0)
    # contents on the roof of a rigid superstructure are the paper's contents on the base
    np.testing.assert_array_equal(ds["pi1_rigid"].sel(floor="base").values, ds["pi1_rigid"].sel(floor="roof").values)
    for name in ("pi1", "rel_error", "peak_error", "holds", "peak_ratio", "pi12_limit"):
        assert ds[name].attrs.get("long_name") and "units" in ds[name].attrs, name


# ----------------------------------------------------------------------------------------------
# isolation systems of equal effective period and damping
# ----------------------------------------------------------------------------------------------

def test_design_comparison_solves_the_designed_isolators(solved):
    cfg, data = solved
    ds = data["isolation_design"]
    sec = cfg["isolation"]["design"]
    assert ds["u_max"].dims == ("system", "excitation", "mu_k")
    assert list(ds["system"].values) == list(design.SYSTEMS) and list(ds["excitation"].values) == ["ricker T_p=1s"]
    np.testing.assert_allclose(ds["T_eff"].values, sec["T_eff"], rtol=1e-12)
    np.testing.assert_allclose(ds["beta_eff"].values, sec["beta_eff"], rtol=1e-12)
    a_p, T_p = sec["a_p_g"] * G, 1.0
    np.testing.assert_allclose(ds["u_max"].values, ds["pi1"].values * a_p * T_p**2, rtol=1e-12)
    np.testing.assert_allclose(ds["pi2"].values[0], ds["mu_k"].values * G / a_p, rtol=1e-12)
    # the same answers from scenes written directly in Pi-groups
    systems = design.design(isolation_study.NOMINAL_MASS, sec["T_eff"], sec["beta_eff"], sec["D"], sec["D_y"])
    mu = float(ds["mu_k"][0])
    for name, iso in systems.items():
        scene = isoslide.Scene(pi2=mu * G / a_p, pi3=iso.T_b / T_p, pi4=iso.xi_b, pi8=1e-5,
                               pi9=iso.Q_d / (iso.M * a_p), pi10=iso.D_y / (a_p * T_p**2))
        assert scene.isolator == {"linear": "linear", "bilinear": "bilinear", "friction_pendulum": "sliding"}[name]
        expect = isoslide.solve(scene).pi1
        assert float(ds["pi1"].sel(system=name, mu_k=mu).squeeze()) == pytest.approx(expect, rel=1e-9, abs=1e-15), name


def test_no_sliding_where_static_friction_exceeds_the_floor_acceleration():
    cfg = tiny_config(design={"mu_k": {"start": 0.02, "stop": 0.6, "num": 7}})
    ds = isolation_study.design_comparison(isolation_study.isolation_settings(cfg))
    for s in ds["system"].values:
        pfa = float(ds["pfa"].sel(system=s).squeeze())
        assert pfa > 0.0
        u = ds["u_max"].sel(system=s).squeeze()
        above = u["mu_k"].values * G > 1.001 * pfa
        assert above.any() and np.all(u.values[above] == 0.0), s
        assert u.values[0] > 0.0, s                     # the lowest friction slides


def test_design_excitations_scale_records_by_their_fitted_pulse():
    sec = isoslide.config.load()["isolation"]["design"]
    sec = {**sec, "pulses": ["ricker"], "T_p": [1.0, 2.0], "records": ["Northridge_1994_PAC-175"]}
    exc = isolation_study.design_excitations(sec)
    assert [e[0] for e in exc] == ["ricker T_p=1s", "ricker T_p=2s", "Northridge_1994_PAC-175"]
    assert exc[0][3] == pytest.approx(sec["a_p_g"] * G) and exc[1][4] == 2.0
    fit = isoslide.records.sample("Northridge_1994_PAC-175").fit("ricker")
    assert exc[2][1] == "record" and exc[2][3] == pytest.approx(fit.a_p) and exc[2][4] == pytest.approx(fit.T_p)


# ----------------------------------------------------------------------------------------------
# findings and figures
# ----------------------------------------------------------------------------------------------

def test_findings_quote_the_datasets(solved):
    _, data = solved
    found = isolation_study.findings(data["iso_fp"], data["iso_lrb"], data["isolation_rigid"],
                                     data["isolation_design"])
    assert len(found) == 4 and all(title and text for title, text in found)
    fp = isolation_study.bearing_summary(data["iso_fp"])
    assert f"{fp[0][2]:.3g}" in found[0][1] and f"{fp[-1][2]:.3g}" in found[0][1]
    ratio = data["isolation_rigid"]["peak_ratio"].sel(floor="roof", pi3=1.0, pi12=0.5)
    assert f"{float(ratio):.2f}×" in found[1][1]
    best = [str(b) for b in data["isolation_design"]["best"].values if str(b)]
    assert f"{len(best)} of 1 excitations" in found[3][1]
    far = float(data["isolation_design"]["bearing_disp"].max()) > 2.0 * data["isolation_design"].attrs["D"]
    assert f"{'beyond' if far else 'within'} 2 D (1 excitations)" in found[3][1]


def test_sliding_end_is_the_last_sliding_pi2():
    assert isolation_study.sliding_end([0.3, 0.1, 0.0, 0.0], [0.1, 0.2, 0.3, 0.4]) == 0.2
    assert np.isnan(isolation_study.sliding_end([0.0, 0.0], [0.1, 0.2]))


def test_every_isolation_figure_is_drawn_with_its_caption(solved, tmp_path):
    from isoslide.reports.figures import read_caption

    _, data = solved
    outputs = [tmp_path / f"{name}.png" for name in isolation_plot.FIGURES]
    captions = isolation_plot.draw_all(data, outputs, {"dpi": 40})
    assert set(captions) == set(isolation_plot.FIGURES)
    for out in outputs:
        assert out.stat().st_size > 1000 and read_caption(out) == captions[out.stem]
    with pytest.raises(ValueError, match="not isolation figures"):
        isolation_plot.draw_all(data, [tmp_path / "fig5.png"], {"dpi": 40})


# ----------------------------------------------------------------------------------------------
# the bearings over the pulse's intensity: lead-rubber, constant and speed-dependent pendulums, triple pendulum
# ----------------------------------------------------------------------------------------------

def _designed(cfg):
    des = cfg["isolation"]["design"]
    return design.design(isolation_study.NOMINAL_MASS, des["T_eff"], des["beta_eff"], des["D"], des["D_y"])


def _scene(cfg, building, iso, a_p, mu_k):
    """The scene of the bearing study at one point, written out here from its parts."""
    sec = cfg["isolation"]["bearings"]
    M = isolation_study.NOMINAL_MASS
    frame = {"floor": "base"} if building == "rigid" else {
        "floor": "roof", "m_st": sec["pi11"] * M, "T_s": sec["pi12"] * sec["T_p"], "xi_s": sec["pi13"]}
    return isoslide.Scene.from_physical(a_p=a_p, T_p=sec["T_p"], pulse=sec["pulse"], m_ec=cfg["defaults"]["pi8"] * M,
                                        mu_s=mu_k, mu_k=mu_k, **frame, **iso)


def _triple(cfg):
    """The triple friction pendulum of the bearing study, designed here from the configuration's parts."""
    des, tfp = cfg["isolation"]["design"], cfg["isolation"]["bearings"]["tfp"]
    return design.design_triple_friction_pendulum(isolation_study.NOMINAL_MASS, des["T_eff"], des["beta_eff"], des["D"],
                                                  tfp["inner_radius"], tfp["mu1_ratio"], tfp["mu3_ratio"],
                                                  tfp["stiffening"], tfp["capacity"])


def _triple_params(cfg):
    """Its keywords of Scene.from_physical, through isoslide.triple_friction_pendulum."""
    iso = _triple(cfg)
    M = isolation_study.NOMINAL_MASS
    return {"M_b": M, "xi_b": 0.0, **isoslide.triple_friction_pendulum(iso.L, iso.mu, iso.d, M)}


def _speed_pendulum(cfg, **override):
    sec = {**cfg["isolation"]["bearings"], **override}
    fp = _designed(cfg)["friction_pendulum"]
    M = isolation_study.NOMINAL_MASS
    return {"M_b": M, "xi_b": 0.0, **isoslide.friction_pendulum(fp.radius(G), fp.mu(G), M, mu_slow=sec["mu_slow_ratio"]
                                                                 * fp.mu(G), rate=sec["rate"])}


def test_bearing_study_labels_and_designs(bearings):
    cfg, data = bearings
    ds = data["isolation_bearings"]
    sec, des = cfg["isolation"]["bearings"], cfg["isolation"]["design"]
    assert ds["u_max"].dims == ("building", "isolator", "a_p", "mu_k")
    assert dict(ds.sizes) == {"building": 2, "isolator": 4, "a_p": 3, "mu_k": 2, "regime": 5}
    assert list(ds["isolator"].values) == list(isolation_study.BEARING_ISOLATORS)
    assert list(ds["building"].values) == ["rigid", "flexible"] and list(ds["floor"].values) == ["base", "roof"]
    assert ds["a_p"].values.tolist() == sec["a_p"] and ds["mu_k"].values.tolist() == sec["mu_k"]
    assert ds["a_p"].attrs["units"] == "m s-2" and ds["u_max"].attrs["units"] == "m" and ds["pfa"].attrs["units"] == "m s-2"
    for name in ("u_max", "pi1", "pi2", "settled", "pfa", "bearing_disp", "bearing_slid", "model_isolator", "T_eff",
                 "peak_stage", "capacity_reached", "tfp_regime_start"):
        assert ds[name].attrs.get("long_name") and "units" in ds[name].attrs, name
    assert ds["peak_stage"].dims == ds["capacity_reached"].dims == ("building", "isolator", "a_p", "mu_k")
    assert ds["peak_stage"].attrs["flag_meanings"] == "not_triple_pendulum held I II III IV V"
    assert ds["peak_stage"].attrs["flag_values"].tolist() == [-1, 0, 1, 2, 3, 4, 5]
    assert ds["capacity_reached"].attrs["flag_meanings"] == "within_capacity capacity_reached"
    assert ds["regime"].attrs["flag_meanings"] == "I II III IV V" and ds["tfp_regime_start"].attrs["units"] == "m"
    assert ds.attrs["Conventions"].startswith("CF") and "isoslide_config" in ds.attrs and ds.attrs["source"]
    # the design's isolators: the same T_eff and beta_eff at D (the speed-dependent pendulum's with mu_fast)
    np.testing.assert_allclose(ds["T_eff"].values, des["T_eff"], rtol=1e-12)
    np.testing.assert_allclose(ds["beta_eff"].values, des["beta_eff"], rtol=1e-12)
    systems = _designed(cfg)
    fp = systems["friction_pendulum"]
    assert float(ds["Q_over_W"].sel(isolator="friction_pendulum")) == pytest.approx(fp.mu(G), rel=1e-12)
    assert float(ds["D_y"].sel(isolator="lead_rubber")) == des["D_y"]
    speed = ds.sel(isolator="friction_pendulum_speed")
    assert float(speed["Q_over_W"]) == pytest.approx(fp.mu(G), rel=1e-12)
    assert float(speed["mu_slow"]) == pytest.approx(sec["mu_slow_ratio"] * fp.mu(G), rel=1e-12)
    assert float(speed["rate"]) == sec["rate"] and float(speed["R"]) == pytest.approx(fp.radius(G), rel=1e-12)
    # u_max is Pi1 a_p T_p^2, Pi2 = mu_k g / a_p
    np.testing.assert_array_equal(ds["u_max"].values, ds["pi1"].values * (ds["a_p"].values * sec["T_p"] ** 2)[:, None])
    np.testing.assert_allclose(ds["pi2"].values, ds["mu_k"].values[None, :] * G / ds["a_p"].values[:, None], rtol=1e-15)
    # the model label: every isolator part of the solver shows up where it should
    facets = isoslide.datasets.decode_facets(ds)
    iso_parts = {str(i): {f.isolator for f in facets[:, k].ravel()} for k, i in enumerate(ds["isolator"].values)}
    assert iso_parts["lead_rubber"] <= {"bilinear", "linear"}
    assert "sliding-bearing" in iso_parts["friction_pendulum"]
    assert "sliding-bearing-speed" in iso_parts["friction_pendulum_speed"]
    assert "triple-friction-pendulum" in iso_parts["triple_friction_pendulum"]
    # the triple pendulum: the design's, its regimes and capacity recorded; the others have no regime
    tri = _triple(cfg)
    assert list(ds.attrs["tfp_L"]) == list(tri.L) and list(ds.attrs["tfp_mu"]) == list(tri.mu)
    assert list(ds.attrs["tfp_d"]) == list(tri.d) and ds.attrs["tfp_capacity"] == tri.capacity
    assert ds["tfp_regime_start"].values.tolist() == list(tri.boundaries().u[:5])
    assert float(ds["T_b"].sel(isolator="triple_friction_pendulum")) == pytest.approx(tri.T_b, rel=1e-12)
    assert float(ds["R"].sel(isolator="triple_friction_pendulum")) == pytest.approx(tri.L[1] + tri.L[2], rel=1e-12)
    assert float(ds["Q_over_W"].sel(isolator="triple_friction_pendulum")) == pytest.approx(tri.mu[1], rel=1e-12)
    others = ds.drop_sel(isolator="triple_friction_pendulum")
    assert (others["peak_stage"] == -1).all() and (ds["capacity_reached"] == 0).all()
    labels = isoslide.datasets.model_labels(ds, "u_max")
    assert labels.sel(building="rigid", isolator="friction_pendulum", a_p=0.05).values.tolist() == [
        "bearing-stuck+fixed-base+no-slide"] * 2


def test_constant_pendulum_is_a_direct_solve_of_the_designed_scene(bearings):
    cfg, data = bearings
    ds = data["isolation_bearings"]
    rtol = cfg["solver"]["rtol"]
    fp = _designed(cfg)["friction_pendulum"].scene_parameters()
    speed = _speed_pendulum(cfg)
    for building in ("rigid", "flexible"):
        for a_p in (0.3, 6.0):
            for mu_k in ds["mu_k"].values:
                for name, iso in (("friction_pendulum", fp), ("friction_pendulum_speed", speed)):
                    sol = isoslide.solve(_scene(cfg, building, iso, a_p, float(mu_k)), rtol=rtol)
                    got = float(ds["u_max"].sel(building=building, isolator=name, a_p=a_p, mu_k=mu_k))
                    assert got == pytest.approx(sol.u_max, rel=1e-9, abs=1e-15), (building, name, a_p, mu_k)
    assert float(ds["u_max"].sel(building="rigid", isolator="friction_pendulum", a_p=6.0, mu_k=0.05)) > 0.0


def test_triple_pendulum_is_a_direct_solve_of_the_designed_scene(bearings):
    """Its Pi1 and regime are those of isoslide.solve of the same scene, written out from its parts."""
    cfg, data = bearings
    ds = data["isolation_bearings"]
    rtol = cfg["solver"]["rtol"]
    tri = _triple_params(cfg)
    for building in ("rigid", "flexible"):
        for a_p in ds["a_p"].values:
            for mu_k in ds["mu_k"].values:
                sol = isoslide.solve(_scene(cfg, building, tri, float(a_p), float(mu_k)), rtol=rtol)
                at = ds.sel(building=building, isolator="triple_friction_pendulum", a_p=a_p, mu_k=mu_k)
                assert float(at["pi1"]) == pytest.approx(sol.pi1, rel=1e-9, abs=1e-15), (building, a_p, mu_k)
                assert int(at["peak_stage"]) == sol.peak_stage and int(at["capacity_reached"]) == 0
                assert int(at["model_isolator"]) == isoslide.models.FACETS["isolator"].index(sol.facets.isolator)
                if sol.peak_stage > 0:
                    assert sol.facets.isolator == "triple-friction-pendulum"


def test_triple_pendulum_regimes_over_the_intensity(bearings):
    """Held below mu1 g, its inner slider alone (I) just above, the outer surfaces (III) at the design level."""
    cfg, data = bearings
    ds = data["isolation_bearings"]
    tri = _triple(cfg)
    for building in ("rigid", "flexible"):
        sub = ds.sel(building=building)
        t, fp = sub.sel(isolator="triple_friction_pendulum"), sub.sel(isolator="friction_pendulum")
        stage = t["peak_stage"]
        # a_p = 0.05 m/s^2 < mu1 g: the bearing holds, the floor moves with the ground, the contents hold
        assert (stage.sel(a_p=0.05) == 0).all() and int(t["bearing_slid"].sel(a_p=0.05)) == 0
        assert float(t["bearing_disp"].sel(a_p=0.05)) == 0.0 and (t["u_max"].sel(a_p=0.05) == 0).all()
        # a_p = 0.3 m/s^2: mu1 g < 0.3 < mu g: the single pendulum holds, the triple one's inner slider moves
        assert (stage.sel(a_p=0.3) == 1).all() and int(t["bearing_slid"].sel(a_p=0.3)) == 1
        assert 0.0 < float(t["bearing_disp"].sel(a_p=0.3)) <= tri.boundaries().u_star * (1.0 + 1e-9)
        if building == "rigid":
            # the single pendulum holds and its floor moves with the ground; the triple one's floor peaks below it
            assert int(fp["bearing_slid"].sel(a_p=0.3)) == 0
            assert float(t["pfa"].sel(a_p=0.3)) < float(fp["pfa"].sel(a_p=0.3)) == pytest.approx(0.3, rel=1e-9)
        # a_p = 6 m/s^2: about D, in regime III (the outer surfaces), within the capacity
        assert (stage.sel(a_p=6.0) == 3).all()
        b = tri.boundaries()
        assert b.u_2star < float(t["bearing_disp"].sel(a_p=6.0)) <= b.u_dr1
    runs = {r[0]: r for r in isolation_study.triple_regimes(ds)}
    assert [(name, lo, hi) for name, lo, hi, _ in runs["rigid"][1]] == [("held", 0.05, 0.05), ("I", 0.3, 0.3),
                                                                          ("III", 6.0, 6.0)]
    assert np.isnan(runs["rigid"][2])


def test_triple_pendulum_past_its_capacity_is_flagged_never_a_number():
    """a_p = 15 m/s^2 drives the triple pendulum to its capacity: Pi1, u_max, pfa, bearing_disp NaN, flagged."""
    cfg = tiny_config(bearings={"a_p": [1.0, 15.0], "mu_k": [0.1], "buildings": ["rigid"]})
    ds = isolation_study.bearing_study(isolation_study.isolation_settings(cfg))
    t = ds.sel(building="rigid", isolator="triple_friction_pendulum")
    with pytest.raises(isoslide.solver.CapacityError):
        isoslide.solve(_scene(cfg, "rigid", _triple_params(cfg), 15.0, 0.1), rtol=cfg["solver"]["rtol"])
    assert t["capacity_reached"].values.tolist() == [[0], [1]]
    assert t["peak_stage"].values.tolist() == [[2], [5]]             # V: the capacity ends regime V
    for name in ("pi1", "u_max"):
        assert np.isfinite(t[name].sel(a_p=1.0)).all() and np.isnan(t[name].sel(a_p=15.0)).all()
    for name in ("pfa", "bearing_disp"):
        assert np.isfinite(float(t[name].sel(a_p=1.0))) and np.isnan(float(t[name].sel(a_p=15.0)))
    assert int(t["bearing_slid"].sel(a_p=15.0)) == 1 and int(t["settled"].sel(a_p=15.0, mu_k=0.1)) == 0
    # the other bearings have no capacity in the model: numbers there
    others = ds.drop_sel(isolator="triple_friction_pendulum").sel(a_p=15.0)
    assert np.isfinite(others["pi1"]).all() and (others["capacity_reached"] == 0).all()
    # the flags survive the file; the findings and the figure say so
    path = isoslide.datasets.write_netcdf(ds, Path(tempfile.mkdtemp()) / "bearings.nc")
    back = isoslide.datasets.open_dataset(path)
    assert back["capacity_reached"].values.tolist() == ds["capacity_reached"].values.tolist()
    assert np.isnan(back["pi1"].sel(isolator="triple_friction_pendulum", a_p=15.0)).all()
    assert back["peak_stage"].dtype == np.int8 and back["peak_stage"].attrs["flag_meanings"].endswith("IV V")
    text = " ".join(t for _, t in isolation_study.bearing_findings(back))
    assert "past its capacity from a_p = 15 m/s²" in text and "triple friction pendulum past its capacity" in text
    cap = isolation_study.bearing_onsets(back)[-1]
    assert cap[1] == "triple_friction_pendulum" and cap[7] == 15.0 and np.isnan(cap[5])
    fig, caption = isolation_plot.intensity({"isolation_bearings": back})
    texts = [t.get_text() for ax in fig.axes for t in ax.texts]
    assert "cap." in texts and "II" in texts and "capacity" in caption


def test_speed_dependent_pendulum_differs_where_the_bearing_slides(bearings):
    _, data = bearings
    ds = data["isolation_bearings"]
    rigid = ds.sel(building="rigid")
    const, speed = rigid.sel(isolator="friction_pendulum"), rigid.sel(isolator="friction_pendulum_speed")
    # a_p = 0.05 m/s^2 is below mu_slow g: both hold, the floor moves with the ground, nothing differs
    assert int(const["bearing_slid"].sel(a_p=0.05)) == 0 == int(speed["bearing_slid"].sel(a_p=0.05))
    assert float(const["pfa"].sel(a_p=0.05)) == float(speed["pfa"].sel(a_p=0.05)) == pytest.approx(0.05, rel=1e-9)
    np.testing.assert_array_equal(const["u_max"].sel(a_p=0.05).values, speed["u_max"].sel(a_p=0.05).values)
    # a_p = 0.3 m/s^2: above mu_slow g, below mu g: only the speed-dependent pendulum breaks away, and its floor
    # no longer moves with the ground
    assert int(speed["bearing_slid"].sel(a_p=0.3)) == 1 and int(const["bearing_slid"].sel(a_p=0.3)) == 0
    assert float(const["bearing_disp"].sel(a_p=0.3)) == 0.0 < float(speed["bearing_disp"].sel(a_p=0.3))
    assert float(speed["pfa"].sel(a_p=0.3)) < float(const["pfa"].sel(a_p=0.3)) == pytest.approx(0.3, rel=1e-9)
    # a_p = 6 m/s^2: both slide; the floors and the contents' sliding differ
    assert int(const["bearing_slid"].sel(a_p=6.0)) == 1 == int(speed["bearing_slid"].sel(a_p=6.0))
    assert float(speed["pfa"].sel(a_p=6.0)) != pytest.approx(float(const["pfa"].sel(a_p=6.0)), rel=1e-3)
    uc, us = const["u_max"].sel(a_p=6.0).values, speed["u_max"].sel(a_p=6.0).values
    assert uc[0] > 0.0 and us[0] != pytest.approx(uc[0], rel=1e-3)
    # the lead-rubber bearing is elastic at a_p = 0.05, yields at 6 with a displacement of the order of D
    lrb = rigid.sel(isolator="lead_rubber")
    assert int(lrb["bearing_slid"].sel(a_p=0.05)) == 0 and int(lrb["bearing_slid"].sel(a_p=6.0)) == 1
    assert 0.5 * ds.attrs["D"] < float(lrb["bearing_disp"].sel(a_p=6.0)) < 2.0 * ds.attrs["D"]


def test_rate_zero_is_the_constant_pendulum_of_mu_slow():
    cfg = tiny_config(bearings={"a_p": [0.5, 6.0], "mu_k": [0.05], "rate": 0.0, "buildings": ["rigid"]})
    ds = isolation_study.bearing_study(isolation_study.isolation_settings(cfg))
    fp = _designed(cfg)["friction_pendulum"]
    M = isolation_study.NOMINAL_MASS
    slow = {"M_b": M, "xi_b": 0.0, **isoslide.friction_pendulum(fp.radius(G), 0.5 * fp.mu(G), M)}
    assert "Q_slow" not in slow
    speed = ds.sel(building="rigid", isolator="friction_pendulum_speed")
    assert float(speed["Q_over_W"]) == pytest.approx(0.5 * fp.mu(G), rel=1e-12) == float(speed["mu_slow"])
    for a_p in (0.5, 6.0):
        sol = isoslide.solve(_scene(cfg, "rigid", slow, a_p, 0.05), rtol=cfg["solver"]["rtol"])
        assert float(speed["u_max"].sel(a_p=a_p, mu_k=0.05)) == pytest.approx(sol.u_max, rel=1e-9, abs=1e-15)
        assert sol.facets.isolator == "sliding-bearing"
    facets = isoslide.datasets.decode_facets(ds.sel(isolator="friction_pendulum_speed"))
    assert {f.isolator for f in facets.ravel()} == {"sliding-bearing"}
    assert float(speed["u_max"].sel(a_p=6.0, mu_k=0.05)) > 0.0


def test_bearing_study_asks_the_batch_solver_for_every_scene_in_order():
    """Any batch solver stands in (isoslide.studies.solving): one call, the scenes in the order of the dims."""
    from types import SimpleNamespace

    from isoslide.models import Facets

    cfg = tiny_config(bearings={"a_p": [0.05, 6.0], "mu_k": [0.05, 0.1], "buildings": ["rigid"]})
    calls = []

    def stub(scenes, rtol=None):
        calls.append(scenes)
        n = len(scenes)
        return SimpleNamespace(pi1=np.arange(n, dtype=float), settled=np.ones(n, bool),
                               facets=np.array([Facets()] * n, dtype=object))

    ds = isolation_study.bearing_study(isolation_study.isolation_settings(cfg), stub)
    # the triple pendulum's scenes are solved one by one (isoslide.solve reports the regime and the capacity)
    assert len(calls) == 1 and len(calls[0]) == 3 * 2 * 2
    singles = ds.drop_sel(isolator="triple_friction_pendulum")
    np.testing.assert_array_equal(singles["pi1"].values.ravel(), np.arange(12.0))
    tri = ds.sel(isolator="triple_friction_pendulum")
    assert np.isfinite(tri["pi1"]).all() and (tri["peak_stage"].sel(a_p=0.05) == 0).all()
    assert not any(s.isolator == "tfp" for s in calls[0])
    assert [s.pi9 > 0 for s in calls[0]] == [True] * 12                     # every isolator is hysteretic
    assert calls[0][0].pi10 > 0.0 and calls[0][4].pi10 == 0.0 == calls[0][8].pi10
    assert calls[0][4].pi22 == 1.0 and calls[0][8].pi22 == pytest.approx(0.5)
    assert [s.pi2 for s in calls[0][:4]] == pytest.approx([0.05 * G / 0.05, 0.1 * G / 0.05, 0.05 * G / 6.0,
                                                           0.1 * G / 6.0])


def _hand_made(u_const, u_speed):
    """A bearing dataset of one building and one mu_k with the two pendulums' u_max given."""
    a_p = np.array([0.25, 0.5, 1.0, 2.0, 4.0, 8.0])
    u = np.array([np.zeros_like(a_p), u_const, u_speed, np.zeros_like(a_p)], dtype=float)[None, :, :, None]
    return xr.Dataset({"u_max": (("building", "isolator", "a_p", "mu_k"), u)},
                      coords={"building": ["rigid"], "isolator": list(isolation_study.BEARING_ISOLATORS),
                              "a_p": a_p, "mu_k": [0.1]})


def test_speed_effect_splits_the_intensities_into_runs_by_hand():
    ds = _hand_made([0.0, 0.0, 1.0, 2.0, 4.0, 8.0], [0.0, 0.5, 1.5, 1.0, 4.02, 8.0])
    rows = isolation_study.speed_effect(ds, tolerance=0.01)
    assert [(r[2], r[3], r[4], r[5]) for r in rows] == [
        ("none", 0.25, 0.25, 1), ("more", 0.5, 1.0, 2), ("less", 2.0, 2.0, 1), ("same", 4.0, 8.0, 2)]
    more = rows[1]
    assert more[6] == 1.5 and more[7] == np.inf                     # only the speed-dependent one slides at 0.5
    assert (more[8], more[9], more[10]) == (0.5, 0.0, 0.5)          # the largest difference: at a_p = 0.5
    assert rows[2][6] == rows[2][7] == 0.5
    assert rows[3][6] == pytest.approx(1.0) and rows[3][7] == pytest.approx(1.005)


def test_bearing_findings_quote_the_dataset(bearings):
    _, data = bearings
    ds = data["isolation_bearings"]
    found = isolation_study.bearing_findings(ds)
    assert len(found) == 5 and all(title and text for title, text in found)
    text = " ".join(t for _, t in found)
    rows = isolation_study.speed_effect(ds)
    for r in rows:
        if r[2] in ("more", "less") and np.isfinite(r[7]) and r[7] > 0:
            assert f"{r[2]} at a_p = {r[3]:g}" in text and f"{r[10] * 100:.2f} against {r[9] * 100:.2f} cm" in text
    n = {v: sum(r[5] for r in rows if r[2] == v) for v in ("less", "more")}
    assert any(f"{v} at {k}" in found[0][1] for v, k in n.items() if k)
    onsets = {(r[0], r[1]): r for r in isolation_study.bearing_onsets(ds)}
    fs = onsets[("rigid", "friction_pendulum_speed")]
    assert fs[2] == 0.3 and onsets[("rigid", "friction_pendulum")][2] == 6.0   # first a_p at which each slides
    assert f"{fs[3] / G:.4f} g on the speed-dependent one" in found[1][1]
    assert f"{onsets[('rigid', 'lead_rubber')][5]:.3f} m" in found[2][1]
    assert "Flexible superstructure, contents on the roof" in found[0][1]
    # the triple friction pendulum: its design, its regimes over a_p, its contents against the single pendulum's
    title, text = found[4]
    assert "triple friction pendulum" in title.lower()
    mu1, mu2, _ = ds.attrs["tfp_mu"]
    assert f"μ1 = {mu1:.4f}, μ2 = {mu2:.4f}" in text and f"μ1 g = {mu1 * G:.3f} m/s²" in text
    assert "Rigid superstructure, contents on the slab: its regimes held at a_p = 0.05 m/s² (0.00 D), I at a_p = 0.3 m/s²" in text
    assert "III at a_p = 6 m/s²" in text and "within its capacity at every a_p" in text
    pfa = ds["pfa"].sel(building="rigid", a_p=0.05)
    assert (f"the floor peaks at {float(pfa.sel(isolator='triple_friction_pendulum')) / G:.4f} g on it, "
            f"{float(pfa.sel(isolator='friction_pendulum')) / G:.4f} g on the single pendulum") in text
    for r in isolation_study.triple_against(ds, "friction_pendulum"):
        assert f"of the {r[2]} (a_p, μ_k) points within its capacity where either's contents slide" in text
        assert f"more at {r[3]}, less at {r[4]}, the same at {r[5]}" in text
    u = ds["u_max"].sel(building="rigid", a_p=6.0, isolator="triple_friction_pendulum").values
    assert f"at a_p = 6 m/s² (regime III, the largest a_p within its capacity) its contents slide " \
           f"{', '.join(f'{v * 100:.2f}' for v in u)} cm" in text


# ----------------------------------------------------------------------------------------------
# the bearing study's configuration
# ----------------------------------------------------------------------------------------------

@pytest.mark.parametrize("bad, message", [
    ({"mu_slow_ratio": 1.5}, r"isolation\.bearings\.mu_slow_ratio: 1\.5 is greater than the maximum of 1"),
    ({"mu_slow_ratio": 0.0}, r"isolation\.bearings\.mu_slow_ratio: 0\.0 is less than or equal to the minimum of 0"),
    ({"rate": -1.0}, r"isolation\.bearings\.rate: -1\.0 is less than the minimum of 0"),
    ({"T_p": 0.0}, r"isolation\.bearings\.T_p: 0\.0 is less than or equal to the minimum of 0"),
    ({"a_p": [0.5, -1.0]}, r"isolation\.bearings\.a_p\.1: -1\.0 is less than or equal to the minimum of 0"),
    ({"mu_k": []}, r"isolation\.bearings\.mu_k: \[\] should be non-empty"),
    ({"buildings": ["attic"]}, r"isolation\.bearings\.buildings\.0: 'attic' is not one of \['rigid', 'flexible'\]"),
    ({"shape": "ricker"}, r"isolation\.bearings: Additional properties are not allowed \('shape' was unexpected\)"),
    ({"tfp": {"mu3_ratio": 0.5}}, r"isolation\.bearings\.tfp\.mu3_ratio: 0\.5 is less than the minimum of 1"),
    ({"tfp": {"stiffening": 1.0}}, r"isolation\.bearings\.tfp\.stiffening: 1\.0 is less than or equal to the minimum"),
    ({"tfp": {"mu2": 0.05}}, r"isolation\.bearings\.tfp: Additional properties are not allowed \('mu2' was unexpected\)"),
])
def test_bad_bearing_settings_are_refused_by_the_schema_naming_the_key(bad, message):
    with pytest.raises(ConfigError, match=message):
        tiny_config(bearings=bad)


def test_triple_pendulum_the_design_cannot_meet_is_refused_naming_its_section():
    settings = isolation_study.isolation_settings(isoslide.config.load())
    settings["isolation"]["bearings"]["tfp"]["capacity"] = 1.3          # regime IV of the design ends at 1.39 D
    with pytest.raises(ConfigError, match=r"^isolation\.bearings\.tfp = .* with isolation\.design T_eff = 3\.0, "
                                          r"beta_eff = 0\.2, D = 0\.3: capacity = 1\.3 is out of range"):
        isolation_study.bearing_isolators(settings)
    settings["isolation"]["bearings"]["tfp"]["capacity"] = 1.6
    settings["isolation"]["design"]["beta_eff"] = 0.55
    with pytest.raises(ConfigError, match=r"beta_eff = 0\.55 is out of range for a triple friction pendulum"):
        isolation_study.bearing_study(settings, solve_many=lambda scenes, rtol=None: pytest.fail("solved"))


@pytest.mark.parametrize("bad, message", [
    ({"a_p": [2.0, 1.0]}, r"isolation\.bearings\.a_p = \[2\.0, 1\.0\] is not strictly increasing; allowed: increasing"),
    ({"mu_k": [0.1, 0.1]}, r"isolation\.bearings\.mu_k = \[0\.1, 0\.1\] is not strictly increasing"),
    ({"a_p": [1.0, float("inf")]}, r"isolation\.bearings\.a_p = \[1\.0, inf\] holds inf; allowed: numbers in \(0, 1000\]"),
    ({"mu_slow_ratio": 0.0}, r"isolation\.bearings\.mu_slow_ratio = 0\.0 is out of range; allowed range: 0 < value <= 1"),
    ({"rate": -2}, r"isolation\.bearings\.rate = -2 is out of range; allowed range: 0 <= value <= 100000"),
    ({"pi11": 1.0}, r"isolation\.bearings\.pi11 = 1\.0 is out of range; allowed range: 0 < value < 1"),
    ({"pulse": "sine"}, r"isolation\.bearings\.pulse = 'sine' is invalid"),
    ({"buildings": ["rigid", "rigid"]}, r"isolation\.bearings\.buildings = \['rigid', 'rigid'\] is invalid; allowed: "
                                        r"a non-empty list of distinct values among \['rigid', 'flexible'\]"),
    ({"tfp": {"inner_radius": 0.2, "mu1_ratio": 0.3, "mu3_ratio": 1.5, "stiffening": 1.5, "capacity": 1.4}},
     r"isolation\.bearings\.tfp\.capacity = 1\.4 is out of range; allowed: above isolation\.bearings\.tfp\.stiffening"),
    ({"tfp": {"inner_radius": 0.2, "mu1_ratio": 0.0, "mu3_ratio": 1.5, "stiffening": 1.5, "capacity": 2.0}},
     r"isolation\.bearings\.tfp\.mu1_ratio = 0\.0 is out of range; allowed range: 0 < value <= 1"),
    ({"tfp": {"inner_radius": 0.2, "mu1_ratio": 0.3}}, r"isolation\.bearings\.tfp = .* is invalid; allowed: a mapping"),
])
def test_bad_bearing_settings_are_refused_by_the_study_naming_the_key(bad, message):
    section = {**isoslide.config.load()["isolation"]["bearings"], **bad}
    with pytest.raises(ConfigError, match=message):
        isolation_study.check_bearings(section)
    settings = isolation_study.isolation_settings(isoslide.config.load())
    settings["isolation"]["bearings"] = section
    with pytest.raises(ConfigError, match=message):
        isolation_study.bearing_study(settings, solve_many=lambda scenes, rtol=None: pytest.fail("solved"))


def test_default_bearing_settings_pass_and_keep_the_design_keys_only():
    cfg = isoslide.config.load()
    sec = isolation_study.check_bearings(cfg["isolation"]["bearings"])
    assert set(sec["tfp"]) == set(isolation_study.TFP_KEYS)
    # the default triple pendulum: D in regime III, its capacity beyond the single pendulum's reach at 1.5 x the
    # intensity that brings it to D (the maximum considered), short of it at the largest a_p
    tri = isolation_study.bearing_triple(isolation_study.isolation_settings(cfg))
    assert tri.regime(cfg["isolation"]["design"]["D"]) == 3 and 1.45 < tri.capacity / cfg["isolation"]["design"]["D"]
    assert sec["a_p"][0] < 1.0 < 6.0 <= sec["a_p"][-1] and sec["mu_slow_ratio"] == 0.5 and sec["rate"] == 30.0
    sub = isolation_study.bearing_settings(isolation_study.isolation_settings(cfg))
    assert set(sub["isolation"]) == {"bearings", "design"}
    assert set(sub["isolation"]["design"]) == set(isolation_study.BEARING_DESIGN_KEYS)


# ----------------------------------------------------------------------------------------------
# the isolation report's notebook, run and rendered as the report rule does
# ----------------------------------------------------------------------------------------------

@pytest.mark.slow
def test_report_notebook_renders_the_bearing_section(solved, tmp_path):
    import json
    import os
    import subprocess
    import sys
    from pathlib import Path

    from isoslide.datasets import write_netcdf
    from isoslide.reports import storeys_plot
    from isoslide.studies import registry, storeys

    root = Path(__file__).resolve().parents[1]
    cfg, data = solved
    st = storeys.storeys_settings(cfg)
    st["storeys"].update(storeys=[1, 2], pi12=[0.5], pi2=[0.2])
    data = {**data, "storeys": storeys.storeys_dataset(st)}
    paths = {name: write_netcdf(ds, tmp_path / f"{name}.nc") for name, ds in data.items()}
    figures = tmp_path / "figures"
    figures.mkdir()
    isolation_plot.draw_all(paths, [figures / f"{name}.png" for name in isolation_plot.FIGURES], {"dpi": 40})
    storeys_plot.draw(paths["storeys"], [figures / "storeys.png"], {"dpi": 40})
    # the notebook's parameters, as the report rule hands them (the registry's data files, renamed here)
    entry = registry.reports(cfg)["isolation"]
    parameters = {name: str(paths[Path(f).stem]) for name, f in entry["data"].items()} | {"figure_dir": str(figures)}
    assert parameters["bearings_path"].endswith("isolation_bearings.nc")
    out = tmp_path / "isolation.ipynb"
    args = [a for name, value in parameters.items() for a in ("-p", name, value)]
    env = {**os.environ, "MPLBACKEND": "Agg", "PYTHONPATH": str(root / "src")}
    proc = subprocess.run([sys.executable, "-m", "papermill", str(root / "workflow" / "notebooks" / "isolation.ipynb"),
                           str(out), "-k", "python3", *args, "--no-progress-bar"], cwd=tmp_path, capture_output=True,
                          text=True, timeout=600, env=env)
    assert proc.returncode == 0, proc.stderr[-4000:]
    nb = json.loads(out.read_text())
    errors = [o for c in nb["cells"] for o in c.get("outputs", []) if o.get("output_type") == "error"]
    assert not errors
    proc = subprocess.run([sys.executable, "-m", "nbconvert", "--to", "html", "--no-input", "--embed-images",
                           "--template-file", str(root / "workflow" / "notebooks" / "offline.html.j2"),
                           "--output-dir", str(tmp_path), "--output", "isolation", str(out)],
                          capture_output=True, text=True, timeout=600, env=env)
    assert proc.returncode == 0, proc.stderr[-4000:]
    html = (tmp_path / "isolation.html").read_text()
    assert "Traceback" not in html
    assert "What the bearing does to the contents, from service-level shaking to beyond the design" in html
    for title, text in isolation_study.bearing_findings(data["isolation_bearings"]):
        assert title.replace("'", "&#39;") in html or title in html
        assert text.split(";")[0].split("(")[0] in html.replace("&#39;", "'"), title
    assert "sliding-bearing-speed" in html and "bearing-stuck+fixed-base+no-slide" in html
    # every figure of the report is embedded, the bearing study's among them
    assert html.count("data:image/png;base64,") >= len(isolation_plot.FIGURES) + 1
