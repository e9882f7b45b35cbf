"""The planar study (isoslide.studies.planar): its grid, labels, derived answers, checks and figures."""

import copy
import hashlib
import math
from pathlib import Path

import numpy as np
import pytest
import yaml

import isoslide
import isoslide.config
from isoslide.datasets import FACET_VARIABLES, write_netcdf
from isoslide.reports import planar_plot
from isoslide.reports.figures import read_caption
from isoslide.studies import planar, registry
from refusals import assert_refused  # tests/ is on sys.path

ROOT = Path(__file__).resolve().parents[1]
G = 9.80665


@pytest.fixture(scope="module")
def base_settings():
    cfg = isoslide.config.load(ROOT / "config" / "config.yaml",
                               yaml.safe_load((ROOT / "config" / "test.yaml").read_text()))
    s = planar.planar_settings(cfg)
    s["planar"].update(pi2={"start": 0.1, "stop": 0.7, "num": 4}, pi3=[0.0, 1.0], pi14=[0.0, 0.5, 1.5],
                       pi15=[0.6, 1.0], pi17=[0.0, 0.5])
    s["planar"]["pi5"].update(pi5=[0.7, 1.0], pi3=[1.0], pi14=[0.0, 1.0])
    return s


@pytest.fixture
def settings(base_settings):
    return copy.deepcopy(base_settings)


@pytest.fixture(scope="module")
def datasets(base_settings):
    return planar.planar_dataset(base_settings), planar.pi5_dataset(base_settings)


def _scene(s, pi2, pi3, pi14, pi15, pi17):
    p = s["planar"]
    c = {k: s["defaults"][k] for k in ("pi5", "pi6", "pi7", "pi8")}
    return isoslide.Scene(pi2=pi2, pi3=pi3, pi4=p["pi4"] if pi3 > 0 else 0.0, **c, pulse=p["pulse"],
                          pulse_y=p["pulse_y"], pi14=pi14, pi15=pi15, pi16=p["pi16"], pi17=pi17,
                          pulse_z=p["pulse_z"] if pi17 > 0 else None)


def test_grid_variables_and_labels(datasets, base_settings):
    ds, ds5 = datasets
    assert ds["pi1"].dims == planar.DIMS
    assert dict(ds.sizes) == {"pi17": 2, "pi3": 2, "pi15": 2, "pi14": 3, "pi2": 4}
    assert np.allclose(ds["pi2"].values, np.linspace(0.1, 0.7, 4))
    assert list(ds["pi14"].values) == [0.0, 0.5, 1.5] and list(ds["pi17"].values) == [0.0, 0.5]
    assert ds["pi1_line"].dims == ("pi17", "pi3", "pi2")
    assert ds["pi1_transverse"].dims == ds["envelope_ratio"].dims == ("pi3", "pi15", "pi14", "pi2")
    assert ds["ground_peak_angle"].dims == ("pi15", "pi14")
    for v in ("pi1", "peak_angle", "peak_off_axis", "pi1_residual", "tau_peak", "settled", "pi1_line",
              "amplification", "vertical_ratio", "pi1_transverse", "envelope_ratio", "ground_peak",
              "ground_peak_angle", "pi4", *FACET_VARIABLES.values()):
        assert ds[v].attrs.get("long_name") and "units" in ds[v].attrs, v
    for v in ("peak_angle", "peak_off_axis", "ground_peak_angle"):
        assert ds[v].attrs["units"] == "rad", v
    assert ds["pi1"].attrs["units"] == "1" and "flag_meanings" in ds["model_contact"].attrs
    for c in ("pi17", "pi3", "pi15", "pi14", "pi2", "pi16", "pi5", "pi8"):
        assert ds[c].attrs.get("long_name", "").startswith(c.replace("pi", "Pi")), c
    assert ds.attrs["Conventions"].startswith("CF") and "isoslide_config" in ds.attrs and "source" in ds.attrs
    assert ds.attrs["pulse_y"] == "antisymmetric_ricker" and ds.attrs["pulse_z"] == "ricker"
    assert (ds["settled"] == 1).all()
    # the contact facet: a line at Pi14 = 0, the plane otherwise
    contact = np.array(ds["model_contact"].attrs["flag_meanings"].split())[ds["model_contact"].values]
    assert (contact[:, :, :, 0] == "line").all() and (contact[:, :, :, 1:] == "plane").all()
    # a peak angle only where the contents slide; in [0, pi/2] off the axis
    slid = ds["pi1"].values > 0
    assert np.isnan(ds["peak_angle"].values[~slid]).all() and np.isfinite(ds["peak_angle"].values[slid]).all()
    off = ds["peak_off_axis"].values[slid]
    assert (off >= 0).all() and (off <= math.pi / 2 + 1e-12).all()
    assert ds5["pi1"].dims == planar.PI5_DIMS and float(ds5["pi6"]) == base_settings["planar"]["pi5"]["pi6"]


def test_points_equal_direct_solves(datasets, base_settings):
    ds, _ = datasets
    rtol = base_settings["solver"]["rtol"]
    pi2 = float(ds["pi2"].values[1])
    for pi3, pi14, pi15, pi17 in ((1.0, 1.5, 1.0, 0.0), (0.0, 0.5, 0.6, 0.5), (1.0, 0.0, 0.6, 0.5)):
        sol = isoslide.solve(_scene(base_settings, pi2, pi3, pi14, pi15, pi17), rtol=rtol)
        got = ds.sel(pi17=pi17, pi3=pi3, pi15=pi15, pi14=pi14).isel(pi2=1)
        assert float(got["pi1"]) == pytest.approx(sol.pi1, rel=1e-12, abs=1e-15)
        assert float(got["peak_angle"]) == pytest.approx(sol.peak_angle, rel=1e-12, abs=1e-12)
        assert ("+planar" in sol.model) == (sol.facets.contact == "plane") == (pi14 > 0)
    line = isoslide.solve(isoslide.Scene(pi2=pi2, pi3=1.0, pi4=base_settings["planar"]["pi4"]), rtol=rtol)
    assert float(ds["pi1_line"].sel(pi17=0.0, pi3=1.0).isel(pi2=1)) == pytest.approx(line.pi1, rel=1e-12)


def test_amplification_is_one_at_pi14_zero(datasets):
    ds, _ = datasets
    amp = ds["amplification"].sel(pi14=0.0).values
    line = np.broadcast_to(ds["pi1_line"].values[:, :, None, :], amp.shape)
    assert np.array_equal(ds["pi1"].sel(pi14=0.0).values, line)
    assert np.all(amp[line > 0] == 1.0) and np.isnan(amp[line == 0]).all()
    assert (line > 0).sum() > 0
    assert (ds["pi1_transverse"].sel(pi14=0.0) == 0).all()
    # elsewhere the ratio is the two answers' ratio
    cur = ds.sel(pi17=0.0, pi3=0.0, pi15=1.0, pi14=1.5).isel(pi2=2)
    assert float(cur["amplification"]) == pytest.approx(float(cur["pi1"] / cur["pi1_line"]))
    assert float(cur["amplification"]) > 1.0
    assert (ds["vertical_ratio"].sel(pi17=0.0).fillna(1.0) == 1.0).all()


def test_transverse_component_alone_in_the_main_scales(datasets, base_settings):
    """pi1_transverse is the transverse pulse alone, solved in SI units on the same building."""
    ds, _ = datasets
    a_p, T_p, M_b = 0.4 * G, 1.2, 1.0e6
    pi2, pi3, pi14, pi15 = float(ds["pi2"].values[0]), 1.0, 1.5, 0.6
    sc = isoslide.Scene.from_physical(a_p=pi14 * a_p, T_p=pi15 * T_p, M_b=M_b, T_b=pi3 * T_p,
                                      xi_b=base_settings["planar"]["pi4"], m_ec=base_settings["defaults"]["pi8"] * M_b,
                                      mu_s=pi2 * a_p / G, mu_k=pi2 * a_p / G, pulse="antisymmetric_ricker")
    u = isoslide.solve(sc, rtol=base_settings["solver"]["rtol"]).u_max
    got = float(ds["pi1_transverse"].sel(pi3=pi3, pi15=pi15, pi14=pi14).isel(pi2=0))
    assert got > 0 and got == pytest.approx(u / (a_p * T_p ** 2), rel=1e-6)


def test_ground_peak_and_line_deviation(datasets):
    ds, _ = datasets
    assert float(ds["ground_peak"].sel(pi15=1.0, pi14=0.0)) == pytest.approx(1.0, abs=1e-6)
    assert float(ds["ground_peak_angle"].sel(pi15=1.0, pi14=0.0)) == pytest.approx(0.0, abs=1e-9)
    assert float(ds["ground_peak"].sel(pi15=1.0, pi14=1.5)) > 1.0
    dev = planar.line_deviation(np.array([0.0, math.pi, -math.pi / 2, 3 * math.pi / 4, np.nan]))
    assert np.allclose(dev[:4], [0.0, 0.0, math.pi / 2, math.pi / 4]) and np.isnan(dev[4])
    assert planar.line_deviation(0.1, 0.1 + math.pi) == pytest.approx(0.0, abs=1e-12)


def test_pi5_slice_and_its_spread(datasets):
    _, ds5 = datasets
    pi1 = ds5["pi1"].sel(pi3=1.0, pi14=1.0).values
    spread = (pi1.max(axis=0) - pi1.min(axis=0)).max()
    assert float(ds5["spread"].sel(pi3=1.0, pi14=1.0)) == pytest.approx(spread)
    rel = float(ds5["relative_spread"].sel(pi3=1.0, pi14=1.0))
    assert rel == pytest.approx(spread / pi1.max())
    assert bool(ds5["similar"].sel(pi3=1.0, pi14=1.0)) == (rel <= ds5.attrs["spread_tolerance"])
    assert (ds5["pi1"] > 0).any() and (ds5["settled"] == 1).all()
    for row in planar.spread_summary(ds5):
        there = ds5["pi1"].sel(pi3=row["pi3"], pi14=row["pi14"], pi2=row["pi2_at"]).values
        assert row["at_end"] == (there.min() == 0.0 < there.max())
        assert row["relative_spread"] == float(ds5["relative_spread"].sel(pi3=row["pi3"], pi14=row["pi14"]))


def test_findings_state_the_dataset_s_numbers(datasets):
    ds, ds5 = datasets
    found = dict(planar.findings(ds, ds5))
    assert list(found) == ["How much farther the contents slide when both components act", "Where the peak points",
                           "The vertical component on the isolated and on the fixed floor",
                           "Complete similarity in Π₅ in the plane",
                           "Friction pendulum against a linear isolator in the plane"]
    rows = planar.amplification_summary(ds)
    assert len(rows) == 2 * 2 * 2
    fixed = [r for r in rows if r["pi3"] == 0.0 and r["pi14"] == 1.5]
    lo, hi = sorted(r["peak_ratio"] for r in fixed)
    assert f"{lo:.2f}× to {hi:.2f}× on the fixed base" in found["How much farther the contents slide when both components act"]
    d = planar.direction_summary(ds)[-1]
    assert f"Π₁₅ = 1, Π₁₄ = 1.5: median {d['median_deg']:.0f}°" in found["Where the peak points"]
    v = [r for r in planar.vertical_summary(ds) if r["pi3"] == 0.0][0]
    assert f"Π₁₇ = 0.5, fixed base: Π₁ changes by a median {100 * v['median']:+.0f}%" in \
        found["The vertical component on the isolated and on the fixed floor"]
    rel = float(ds5["relative_spread"].sel(pi3=1.0, pi14=1.0))
    assert f"{rel:.3f} at Π₃ = 1" in found["Complete similarity in Π₅ in the plane"]
    p = [r for r in planar.pendulum_summary(ds) if r["pi15"] == 1.0 and r["pi14"] == 1.5][0]
    assert f"Π₁₅ = 1, Π₁₄ = 1.5: peak {planar._x(p['peak_ratio'])}" in \
        found["Friction pendulum against a linear isolator in the plane"]
    assert len(planar.findings(ds)) == 4


def test_the_friction_pendulum_points_equal_direct_solves(datasets, base_settings):
    """The pendulum and its linear twin in the plane, at one grid point, solved directly."""
    ds, _ = datasets
    p = base_settings["planar"]
    c = {k: base_settings["defaults"][k] for k in ("pi5", "pi6", "pi7", "pi8")}
    kw = dict(pi2=float(ds["pi2"][1]), pi3=p["pendulum"]["pi3"], pi4=p["pi4"], **c, pulse=p["pulse"],
              pulse_y=p["pulse_y"], pi14=1.5, pi15=1.0, pi16=p["pi16"])
    pend = isoslide.solve(isoslide.Scene(**kw, pi9=p["pendulum"]["pi9"]))
    lin = isoslide.solve(isoslide.Scene(**kw))
    assert pend.model.startswith("sliding-bearing+") and pend.model.endswith("+planar")
    got = ds.sel(pi15=1.0, pi14=1.5).isel(pi2=1)
    assert float(got["pi1_pendulum"]) == pend.pi1
    assert float(got["pi1_pendulum_linear"]) == lin.pi1
    assert ds["pendulum_ratio"].dims == ("pi15", "pi14", "pi2")


def test_dataset_is_byte_identical(settings, datasets, tmp_path):
    a, _ = datasets
    b = planar.planar_dataset(settings)
    digests = [hashlib.sha256(write_netcdf(ds, tmp_path / f"{k}.nc").read_bytes()).hexdigest()
               for k, ds in enumerate((a, b))]
    assert digests[0] == digests[1]
    assert '"pi14": [0.0, 0.5, 1.5]' in a.attrs["isoslide_config"]


@pytest.mark.parametrize("key, value, match", [
    ("pi3", [1.0, 0.0], "planar.pi3 = .* is not strictly increasing"),
    ("pi14", [-0.5], r"planar.pi14 = -0.5 is out of range"),
    ("pi15", [0.0], r"planar.pi15 = 0.0 is out of range"),
    ("pi17", [0.5], r"planar.pi17 = \[0.5\] does not start with 0"),
    ("pi17", [0.0, 5.0], r"planar.pi17 = \[0.0, 5.0\] holds 5.0, which lifts the contents off"),
    ("pulse_y", "sine", r"planar.pulse_y = 'sine' is not a pulse shape"),
    ("pi2", {"start": 0.5, "stop": 0.1, "num": 3}, r"planar.pi2.stop = 0.1 is below planar.pi2.start"),
    ("tolerance", 1.5, r"planar.tolerance = 1.5 is out of range"),
])
def test_bad_settings_name_the_key_and_what_is_allowed(settings, key, value, match):
    settings["planar"][key] = value
    assert_refused(planar.check_settings, settings, match)


def test_bad_pi5_settings_name_the_key(settings):
    settings["planar"]["pi5"]["pi5"] = [0.7, 1.2]
    with pytest.raises(ValueError, match=r"planar.pi5.pi5 = 1.2 is out of range"):
        planar.check_settings(settings)


def test_figures_have_their_captions(datasets, tmp_path):
    ds, ds5 = datasets
    outputs = [tmp_path / f"{name}.png" for name in planar_plot.FIGURES] + [tmp_path / "planar_ratio.pdf"]
    captions = planar_plot.draw_all({"planar": ds, "planar_pi5": ds5}, outputs, {"dpi": 40})
    assert list(captions) == list(planar_plot.FIGURES)
    for name in planar_plot.FIGURES:
        assert captions[name].startswith("Planar") and read_caption(tmp_path / f"{name}.png") == captions[name]
    assert (tmp_path / "planar_ratio.pdf").stat().st_size > 1000
    with pytest.raises(ValueError, match="outputs"):
        planar_plot.draw_all({"planar": ds, "planar_pi5": ds5}, [tmp_path / "other.png"], {"dpi": 40})


def test_the_study_is_registered():
    study = {s.name: s for s in registry.STUDIES}["planar"]
    assert study.dataset_names({}) == ["planar", "planar_pi5"]
    assert study.figures == registry.PLANAR_FIGURES == planar_plot.FIGURES
    assert [r.name for r in study.reports] == ["planar"] and study.reports[0].code == "planar"
    assert registry.slurm_groups()["planar_dataset"] == "merge"
    assert "studies.planar" in registry.code_families()["planar"]
