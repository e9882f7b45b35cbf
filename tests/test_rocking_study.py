"""The rocking study (isoslide.studies.rocking): overturning spectra, the sliding-or-rocking map, what
isolation does, the overturning fragility and its pelicun export, the datasets and their bytes."""

import copy
import hashlib
import math
import socket
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import yaml

import isoslide
import isoslide.config
from isoslide import solver
from isoslide.datasets import open_dataset, write_netcdf
from isoslide.groups import group
from isoslide.model.rocking import rectangular_overturn_ratio
from isoslide.studies import registry, rocking
from isoslide.studies.fragility import probability

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def config():
    """The complete configuration of config/test.yaml (the tiny run's rocking section)."""
    solver.warm_up(records=True, building=True)
    return isoslide.config.load(ROOT / "config" / "config.yaml",
                                yaml.safe_load((ROOT / "config" / "test.yaml").read_text()))


@pytest.fixture
def settings(config):
    return rocking.rocking_settings(config)


def outcomes(rows):
    """:class:`rocking.Outcomes` from ``(theta_max, overturned, pi1, modes, status)`` rows."""
    cols = list(zip(*rows, strict=True)) if rows else [(), (), (), (), ()]
    return rocking.Outcomes(theta_max=np.array(cols[0], float), overturned=np.array(cols[1], bool),
                            pi1=np.array(cols[2], float), modes=np.array(cols[3], np.int8),
                            status=np.array(cols[4], np.int8))


def threshold_solver(threshold, seen=None):
    """A stand-in for solve_blocks: the block overturns where ``scene.pi21 >= threshold(scene)``.

    Below, it rocks to ``theta_max = alpha pi21 / (2 threshold)`` (rest below Pi21 = 1); above, it
    overturns (``theta_max = pi/2``).
    """
    def solve(scenes, rtol=None):
        rows = []
        for sc in scenes:
            if seen is not None:
                seen.append(sc)
            alpha = math.atan(sc.pi18)
            thr = threshold(sc)
            if sc.pi21 >= thr:
                rows.append((0.5 * math.pi, True, 0.0, 0b101, 0))
            elif sc.pi21 > 1.0:
                rows.append((alpha * sc.pi21 / (2 * thr), False, 0.0, 0b101, 0))
            else:
                rows.append((0.0, False, 0.0, 0b1, 0))
        return outcomes(rows)
    return solve


# ----------------------------------------------------------------------------------------------
# overturning spectra
# ----------------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def spectra(config):
    """The spectra of config/test.yaml, solved by the real solver."""
    return rocking.spectra_dataset(rocking.rocking_settings(config))


def test_the_bisected_bracket_holds_the_threshold_one_amplitude_below_stands_one_above_overturns(spectra, config):
    """Re-solved independently: pi21_survive does not overturn, pi21_overturn does, their ratio is within the
    tolerance, and no scan amplitude below the bracket overturned (it is the first bracket of the upward scan)."""
    sec = rocking.check_spectra(config["rocking"]["spectra"])
    tol = sec["tolerance"]
    checked = 0
    for p in spectra["pulse"].values:
        for b in spectra["pi3"].values:
            for x in spectra["pi19"].values:
                s = spectra.sel(pulse=p, pi3=b, pi19=x)
                if int(s["bracket_status"]) != 0:
                    continue
                lo, hi = float(s["pi21_survive"]), float(s["pi21_overturn"])
                assert 1.0 < hi / lo <= 1.0 + tol
                below, above = (isoslide.solve(rocking.spectra_scene(sec, str(p), float(b), float(x), a))
                                for a in (lo, hi))
                assert not below.overturned and above.overturned
                assert below.theta_max / math.atan(sec["pi18"]) == pytest.approx(
                    float(s["theta_max_over_alpha_survive"]), rel=1e-12)
                scan = s["overturned"].values
                first = int(np.argmax(scan == 1))
                assert np.all(scan[:first] == 0) and np.all(scan[first + 1:] == -1)
                assert spectra["pi21"].values[first - 1] <= lo < hi <= spectra["pi21"].values[first]
                checked += 1
    assert checked >= 4


def test_the_fixed_base_rectangular_curve_needs_order_alpha_squared_more_than_the_linearised_closed_form(config):
    """A slender block (b/h = 0.05): the exact least overturning Pi21 exceeds beta_c alpha / tan(alpha),
    beta_c = 1/(1 - exp(-Pi19)), by a positive amount below alpha^2 (bisected to 1e-5)."""
    s = rocking.rocking_settings(config)
    s["rocking"]["spectra"].update(pulses=["rectangular"], pi3=[0.0, 1.0], inverse_pi19=[0.25, 1.0, 2.0], pi18=0.05,
                                   tolerance=1e-5)
    ds = rocking.spectra_study(s)
    alpha = math.atan(0.05)
    exact = ds["pi21_overturn"].sel(pulse="rectangular", pi3=0.0).values
    closed = np.array([rectangular_overturn_ratio(p) for p in ds["pi19"].values]) * alpha / 0.05
    np.testing.assert_array_equal(ds["pi21_linearised_rectangular"].values, closed)
    rel = exact / closed - 1.0
    assert np.all(rel > 1e-5) and np.all(rel < alpha ** 2), rel
    check = rocking.rectangular_check(ds)
    assert check["max_abs"] == pytest.approx(np.max(np.abs(rel))) and check["alpha_squared"] == alpha ** 2


def test_the_scan_stops_each_curve_at_its_first_overturning_amplitude():
    """With a stand-in solver of known thresholds, every curve's answer is its threshold to the tolerance,
    amplitudes above the first overturning one are not solved, and scan-start and off-scan thresholds are flagged."""
    thresholds = {0.0: 2.0, 3.0: 0.3}                                       # Pi3 = 3: below the scan's start
    seen = []

    def thr(sc):
        return thresholds[sc.pi3] * (100.0 if sc.pi19 < 2 else 1.0)        # 1/Pi19 = 1: beyond the scan

    s = {"rocking": {"spectra": {**isoslide.config.defaults()["rocking"]["spectra"], "pulses": ["ricker"],
                                 "pi3": [0.0, 3.0], "inverse_pi19": [0.25, 1.0], "tolerance": 1e-3}},
         "solver": {"rtol": None}}
    ds = rocking.spectra_study(s, solve_blocks=threshold_solver(thr, seen))
    s0 = ds.sel(pulse="ricker", pi3=0.0, pi19=4.0)
    assert int(s0["bracket_status"]) == 0
    assert 2.0 <= float(s0["pi21_overturn"]) <= 2.0 * (1 + 1e-3) and float(s0["pi21_survive"]) < 2.0
    assert int(ds["bracket_status"].sel(pulse="ricker", pi3=3.0, pi19=4.0)) == 1          # overturns at the start
    assert float(ds["pi21_overturn"].sel(pulse="ricker", pi3=3.0, pi19=4.0)) == 0.5
    assert np.isnan(float(ds["pi21_survive"].sel(pulse="ricker", pi3=3.0, pi19=4.0)))
    assert (ds["bracket_status"].sel(pi19=1.0).values == 2).all()                           # none on the scan
    assert not any(sc.pi21 > 2.0 * 1.4 and sc.pi19 == 4.0 and sc.pi3 == 0.0 for sc in seen)
    assert float(ds["isolation_ratio"].sel(pulse="ricker", pi3=3.0, pi19=4.0)) == pytest.approx(
        0.5 / float(s0["pi21_overturn"]))


def test_an_unresolved_solve_stops_the_bisection_and_is_flagged():
    """A block that would leave the floor (ContactError) is kept as unresolved, never guessed."""
    scene = isoslide.Scene(pi2=10.0 / (0.2 * 10.226955373935212), pi3=1.0, pi4=0.1, pi8=1e-5, pi18=0.2, pi19=2.0,
                           pi21=10.226955373935212)
    out = rocking.solve_blocks([scene])
    assert out.status.tolist() == [1] and np.isnan(out.theta_max[0]) and not out.overturned[0]

    def lost_in_bracket(scenes, rtol=None):
        res = threshold_solver(lambda sc: 2.0)(scenes)
        status = np.where((res.theta_max > 0) & ~res.overturned, 1, 0).astype(np.int8)   # every rocking solve lost
        return rocking.Outcomes(np.where(status == 1, np.nan, res.theta_max), res.overturned & (status == 0),
                                res.pi1, res.modes, status)

    s = {"rocking": {"spectra": {**isoslide.config.defaults()["rocking"]["spectra"], "pulses": ["ricker"],
                                 "pi3": [0.0, 1.0], "inverse_pi19": [0.5]}}, "solver": {"rtol": None}}
    ds = rocking.spectra_study(s, solve_blocks=lost_in_bracket)
    assert (ds["bracket_status"].values == 3).all()
    assert (ds["solve_status"].values == 1).any() and ds["solve_status"].attrs["flag_meanings"].split()[2] == \
        "contact_lost"


# ----------------------------------------------------------------------------------------------
# the sliding-or-rocking map
# ----------------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def rock_map(config):
    return rocking.map_dataset(rocking.rocking_settings(config))


def test_a_block_with_friction_at_most_its_aspect_ratio_never_rocks(rock_map, config):
    """mu_s <= b/h: the block cannot tip (Scene.tips is False) and visits neither rock nor slide-rock; every
    block that rocked can tip; the response agrees with the modes visited and the overturning flag."""
    sec = config["rocking"]["map"]
    tips = rock_map["tips"].values.astype(bool)
    for j, mu in enumerate(rock_map["mu_s"].values):
        for k, pi18 in enumerate(rock_map["pi18"].values):
            assert tips[j, k] == rocking.map_scene(sec, 0.0, float(mu), float(pi18)).tips == (mu > pi18)
    visited = rock_map["visited"]
    rocked = (visited.sel(mode="rock") + visited.sel(mode="slide-rock")).values > 0
    assert not np.any(rocked & ~tips[None]), "a block that cannot tip rocked"
    assert np.any(rocked) and np.any(~tips)
    resp = rock_map["response"].values
    over = rock_map["overturned"].values.astype(bool)
    assert np.array_equal(resp == 4, over)
    assert np.all(rock_map["theta_max_over_alpha"].values[~tips[None] & np.ones_like(over)] == 0.0)
    slid_only = (visited.sel(mode="slide").values == 1) & ~rocked & ~over
    assert np.array_equal(resp == 1, slid_only)
    assert np.all(rock_map["pi1"].values[resp == 0] == 0.0)
    np.testing.assert_allclose(rock_map["theta_max_over_alpha"].values[over],
                               (0.5 * math.pi / rock_map["alpha"].values[None, None, :] * np.ones_like(resp))[over])
    summary = rocking.map_summary(rock_map)
    assert all(row["rocked_without_tipping"] == 0 for row in summary)
    assert sum(row[name] for row in summary for name in rocking.RESPONSES) == resp.size


# ----------------------------------------------------------------------------------------------
# findings
# ----------------------------------------------------------------------------------------------

def fake_spectra(thresholds):
    """Spectra from a stand-in solver whose fixed-base and isolated thresholds are ``thresholds[pi3](pi19)``."""
    s = {"rocking": {"spectra": {**isoslide.config.defaults()["rocking"]["spectra"], "pulses": ["ricker"],
                                 "pi3": [0.0, 2.0], "inverse_pi19": [0.25, 0.5, 1.0]}}, "solver": {"rtol": None}}
    return rocking.spectra_dataset(s, solve_blocks=threshold_solver(lambda sc: thresholds[sc.pi3](sc.pi19)))


def test_isolation_verdicts_and_findings_are_computed_from_the_data(rock_map):
    """Isolated thresholds 3x the fixed base's for a small block (1/Pi19 = 0.25), 0.4x for large ones:
    isolation_effect says protects and exposes where it should, and the findings quote the measured ratios; other
    data give other sentences."""
    fixed = {4.0: 1.5, 2.0: 2.0, 1.0: 3.0}
    iso = {4.0: 4.5, 2.0: 0.8, 1.0: 1.2}
    ds = fake_spectra({0.0: lambda p: fixed[p], 2.0: lambda p: iso[p]})
    (row,) = rocking.isolation_effect(ds)
    assert row["protects"] == [0.25] and row["exposes"] == [0.5, 1.0] and not row["same"]
    ratio = ds["isolation_ratio"].sel(pulse="ricker", pi3=2.0).values
    np.testing.assert_allclose(ratio, [3.0, 0.4, 0.4], rtol=3e-3)
    assert row["ratio_max"] == pytest.approx(3.0, rel=3e-3) and row["at_max"] == 0.25
    frag = fake_fragility()
    found = dict(rocking.findings(ds, rock_map, frag))
    text = found["Does isolation protect the block or expose it?"]
    assert "protects at 1/Π₁₉ = 0.25" in text and "exposes at 1/Π₁₉ = 0.5, 1" in text
    assert f"{row['ratio_max']:.2f}" in text and f"{row['ratio_min']:.2f}" in text
    same = fake_spectra({0.0: lambda p: fixed[p], 2.0: lambda p: fixed[p]})
    text2 = dict(rocking.findings(same, rock_map, frag))["Does isolation protect the block or expose it?"]
    assert "makes no difference at 1/Π₁₉ = 0.25, 0.5, 1" in text2 and text2 != text
    n = rock_map.sizes["mu_s"] * rock_map.sizes["pi18"]
    assert f"over {n} blocks" in found["Sliding or rocking"] and "that rocked: 0" in found["Sliding or rocking"]
    over = int(frag["overturned"].sel(base="isolated").sum())
    assert f"isolated: {over} of" in found["Overturning fragility under recorded ground motions"]


# ----------------------------------------------------------------------------------------------
# the overturning fragility and pelicun
# ----------------------------------------------------------------------------------------------

CAPACITY = {0: 5.0, 1: 9.0, 2: 7.0}
"""PGA (m/s^2) above which the stand-in block overturns, by record, on the fixed base; twice that isolated."""


def fake_fragility(motions=3):
    """The fragility of a stand-in block: the real records and floor motions, outcomes by :data:`CAPACITY`."""
    s = {"rocking": {"fragility": {**isoslide.config.defaults()["rocking"]["fragility"], "motions": motions,
                                   "levels": [3.0, 6.0, 8.0, 10.0, 13.0], "bootstrap": {"n_boot": 20, "level": 0.9}}},
         "solver": {"rtol": None}}
    names = [r.name for r in rocking.fragility_records(rocking.check_fragility(s["rocking"]["fragility"]))]

    def solve(scenes, rtol=None):
        rows = []
        for sc in scenes:
            cap = CAPACITY[names.index(sc.pulse.name)] * (1.0 if sc.pi3 == 0 else 1.6)
            pga = sc.scale.a_p
            alpha = math.atan(sc.pi18)
            rows.append((0.5 * math.pi, True, 0.0, 0b101, 0) if pga > cap else
                        (alpha * pga / cap, False, 0.0, 0b101, 0))
        return outcomes(rows)

    return rocking.fragility_dataset(s, solve_blocks=solve)


@pytest.fixture(scope="module")
def fragility(config):
    return fake_fragility()


def test_fragility_outcomes_intensities_and_curves(fragility):
    """Overturning where the stand-in says, PGA at the stripes, PFA = PGA and PFV = PGV on the fixed base, the
    isolated floor's peaks proportional to the level; overturning curves fitted on every IM."""
    ds = fragility
    over = ds["overturned"].values.astype(bool)
    levels = ds["im_level"].values
    for r, cap in CAPACITY.items():
        np.testing.assert_array_equal(over[0, r], levels > cap)
        np.testing.assert_array_equal(over[1, r], levels > 1.6 * cap)
    np.testing.assert_allclose(ds["pga"].values, np.broadcast_to(levels, ds["pga"].shape), rtol=1e-12)
    np.testing.assert_array_equal(ds["pfa"].sel(base="fixed_base").values, ds["pga"].values)
    np.testing.assert_array_equal(ds["pfv"].sel(base="fixed_base").values, ds["pgv"].values)
    iso = ds["pfa"].sel(base="isolated").values / ds["pga"].values
    np.testing.assert_allclose(iso, iso[:, :1] * np.ones_like(iso), rtol=1e-12)
    assert list(ds["limit_state_name"].values) == ["rotation_0.5", "overturning"]
    assert float(ds["limit_state"][-1]) == pytest.approx(0.5 * math.pi / ds.attrs["alpha"])
    last = ds.isel(limit_state=-1)
    assert (last["fit_status"].values == 0).all(), last["fit_status"].values
    np.testing.assert_array_equal(ds["n_exceeded"].isel(limit_state=-1).values, over.reshape(2, -1).sum(axis=1))
    rows = rocking.fragility_summary(ds)
    assert len(rows) == 2 * 2 * 4 and {r["status"] for r in rows if r["limit_state"] == "overturning"} == {"ok"}


@pytest.fixture
def offline(monkeypatch):
    """pelicun runs offline: a socket connection raises."""
    def refuse(*args, **kwargs):
        raise OSError("network access in an offline test")
    monkeypatch.setattr(socket.socket, "connect", refuse)
    monkeypatch.setattr(socket.socket, "connect_ex", refuse)


def test_the_overturning_fragility_export_loads_in_pelicun_and_follows_the_fitted_curve(fragility, tmp_path, offline):
    """pelicun 3 reads the CSV (PFA in g, PFV in m/s): the share of realisations in DS1 at a floor demand is the
    isolated slab's fitted overturning curve there, within 4 binomial standard deviations of 3000 realisations."""
    from pelicun import assessment, file_io

    path = rocking.write_pelicun(fragility, tmp_path / "db.csv", json_path=tmp_path / "db.json")
    table = pd.read_csv(path, index_col=0, float_precision="round_trip")
    assert list(table.index) == list(rocking.PELICUN_COMPONENTS.values())
    assert (table["Incomplete"] == 0).all() and list(table["Demand-Unit"]) == ["g", "mps"]
    last = fragility.sel(base="isolated").isel(limit_state=-1)
    assert table.loc["isoslide.BLOCK.PFA", "LS1-Theta_0"] == float(last["theta"].sel(im="pfa")) / 9.80665
    assert table.loc["isoslide.BLOCK.PFV", "LS1-Theta_1"] == float(last["beta"].sel(im="pfv"))
    assert "The block overturned" in (tmp_path / "db.json").read_text()

    asmnt = assessment.Assessment({"PrintLog": False, "Seed": 11, "NonDirectionalMultipliers": {"ALL": 1.0}})
    x_pfa = np.array([0.6, 1.0, 1.4]) * float(last["theta"].sel(im="pfa"))
    x_pfv = np.array([0.6, 1.0, 1.4]) * float(last["theta"].sel(im="pfv"))
    per = 3000
    cols = pd.MultiIndex.from_tuples([("PFA", "0", "1"), ("PFA", "0", "2"), ("PFV", "0", "1"), ("PFV", "0", "2")])
    a, v = np.repeat(x_pfa, per), np.repeat(x_pfv, per)
    units = pd.DataFrame([["mps2", "mps2", "mps", "mps"]], columns=cols, index=["Units"])
    sample = pd.DataFrame(np.column_stack([a, 0.5 * a, v, 0.5 * v]), columns=cols).astype(object)
    asmnt.demand.load_sample(pd.concat([units, sample]))
    asmnt.stories = 1
    ids = list(rocking.PELICUN_COMPONENTS.values())
    asmnt.asset.load_cmp_model({"marginals": pd.DataFrame(
        {"Units": "ea", "Location": "1", "Direction": "0", "Theta_0": 1}, index=ids)})
    asmnt.asset.generate_cmp_sample()
    db = file_io.load_data(str(path), reindex=False, unit_conversion_factors=asmnt.unit_conversion_factors)
    asmnt.damage.load_model_parameters([db], set(asmnt.asset.list_unique_component_ids()))
    asmnt.damage.calculate()
    damage = asmnt.damage.ds_model.sample
    for im, x in (("pfa", x_pfa), ("pfv", x_pfv)):
        ds = damage[rocking.PELICUN_COMPONENTS[im]].T.groupby(level="ds").sum().T
        share = (ds.to_numpy().argmax(axis=1) >= 1).reshape(-1, per).mean(axis=1)
        want = probability(x, float(last["theta"].sel(im=im)), float(last["beta"].sel(im=im)))
        sd = np.sqrt(want * (1 - want) / per)
        assert np.all(np.abs(share - want) <= 4 * sd + 1e-12), (im, share, want)


# ----------------------------------------------------------------------------------------------
# datasets, provenance, bytes, settings, registry
# ----------------------------------------------------------------------------------------------

def test_datasets_carry_the_variables_the_pi_group_coordinates_and_provenance(spectra, rock_map, fragility):
    for ds, groups in ((spectra, ("pi3", "pi19", "pi21", "pi18", "pi20")), (rock_map, ("pi3", "pi18", "pi2", "pi21")),
                       (fragility, ("pi18", "pi20"))):
        assert {"theta_max_over_alpha", "overturned"} <= set(ds.data_vars)
        assert ds["theta_max_over_alpha"].attrs["units"] == "1" and "alpha" in ds["theta_max_over_alpha"].attrs[
            "long_name"]
        assert ds["overturned"].attrs["flag_meanings"].endswith("overturned")
        for g in groups:
            assert ds[g].attrs["long_name"] == group(g).long_name, g
        assert ds.attrs["Conventions"].startswith("CF") and "isoslide_config" in ds.attrs and "git" in ds.attrs["source"]
        for name, var in ds.variables.items():
            assert "long_name" in var.attrs, name
    assert spectra["inverse_pi19"].values.tolist() == sorted(spectra["inverse_pi19"].values.tolist())
    np.testing.assert_allclose(spectra["inverse_pi19"].values * spectra["pi19"].values, 1.0, rtol=1e-15)


def test_the_same_configuration_gives_the_same_bytes(config, tmp_path):
    s = rocking.rocking_settings(config)
    digests = []
    for k in range(2):
        paths = [write_netcdf(rocking.map_dataset(copy.deepcopy(s)), tmp_path / f"map{k}.nc"),
                 write_netcdf(fake_spectra({0.0: lambda p: 2.0, 2.0: lambda p: 1.5}), tmp_path / f"sp{k}.nc"),
                 rocking.write_pelicun(fake_fragility(2), tmp_path / f"db{k}.csv")]
        digests.append([hashlib.sha256(Path(p).read_bytes()).hexdigest() for p in paths])
    assert digests[0] == digests[1]
    assert open_dataset(tmp_path / "map0.nc")["response"].dims == ("pi3", "mu_s", "pi18")


@pytest.mark.parametrize("section, change, pattern", [
    ("spectra", {"pi3": [1.0, 2.0]}, r"rocking\.spectra\.pi3 = \[1\.0, 2\.0\] does not start at 0\.0"),
    ("spectra", {"inverse_pi19": [1.0, 0.5]}, r"rocking\.spectra\.inverse_pi19 = \[1\.0, 0\.5\] is not strictly"),
    ("spectra", {"pi20": 0.99}, r"rocking\.spectra\.pi20 = 0\.99 exceeds Housner's"),
    ("spectra", {"pulses": ["no_such_pulse"]}, r"rocking\.spectra\.pulses = 'no_such_pulse' is invalid"),
    ("map", {"mu_s": [0.3, 0.2]}, r"rocking\.map\.mu_s = \[0\.3, 0\.2\] is not strictly increasing"),
    ("fragility", {"motions": 1}, r"rocking\.fragility\.motions = 1 is out of range"),
    ("fragility", {"rotation_limits": [0.5, 0.3]}, r"rocking\.fragility\.rotation_limits = \[0\.5, 0\.3\]"),
])
def test_bad_settings_name_the_key_the_value_and_what_is_allowed(settings, section, change, pattern):
    settings["rocking"][section].update(change)
    with pytest.raises(ValueError, match=pattern):
        rocking.check_settings(settings)


def test_a_suite_shorter_than_the_motions_asked_for_is_refused(settings):
    settings["rocking"]["fragility"].update(motions=50)
    with pytest.raises(ValueError, match=r"rocking\.fragility\.motions = 50 exceeds the 22 ground motions"):
        rocking.overturning_fragility(settings)


def test_the_study_is_registered_with_its_datasets_report_and_pelicun_file(config):
    study = {s.name: s for s in registry.STUDIES}["rocking"]
    targets = registry.all_targets(config)
    for name in rocking.DATASETS:
        assert registry.dataset_path(name) in targets
    assert registry.ROCKING_PELICUN in targets and "reports/rocking.html" in targets
    report = registry.reports(config)["rocking"]
    assert report["data"] == {"spectra_path": "results/datasets/rocking_spectra.nc",
                              "map_path": "results/datasets/rocking_map.nc",
                              "fragility_path": "results/datasets/rocking_fragility.nc",
                              "pelicun_path": registry.ROCKING_PELICUN}
    assert study.rule_files == ("rocking.smk",) and study.groups == {"rocking_datasets": "merge"}
    assert rocking.rocking_settings(config).keys() == {"rocking", "solver"}


def test_the_report_figures_draw_from_the_datasets(spectra, rock_map, fragility, tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from isoslide.reports.rocking_plot import draw_fragility, draw_isolation, draw_map, draw_spectra

    for draw, ds in ((draw_spectra, spectra), (draw_isolation, spectra), (draw_map, rock_map),
                     (draw_fragility, fragility)):
        out = tmp_path / f"{draw.__name__}.png"
        fig = draw(ds, outputs=[out], dpi=40)
        assert out.stat().st_size > 1000 and fig.axes
        plt.close(fig)
