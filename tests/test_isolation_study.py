"""The isolation studies (isoslide.studies.isolation_study) and their figures (isoslide.reports.isolation_plot)."""

import copy

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
    }
    for k, v in isolation.items():
        overlay[k] = {**overlay.get(k, {}), **v}
    return isoslide.config.load(None, {"isolation": overlay})


@pytest.fixture(scope="module")
def solved():
    cfg = tiny_config()
    data = {name: sweep.solve_study(spec) for name, spec in isolation_study.study_specs(cfg).items()}
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
