"""The storeys study (isoslide.studies.storeys): its grid, labels, derived answers, checks and figure."""

import copy
import hashlib
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
import yaml

import isoslide
import isoslide.config
from isoslide.datasets import write_netcdf
from isoslide.reports.figures import read_caption
from isoslide.studies import registry, storeys
from isoslide.reports.storeys_plot import draw
from refusals import assert_refused  # tests/ is on sys.path

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture
def settings():
    cfg = isoslide.config.load(ROOT / "config" / "config.yaml",
                               yaml.safe_load((ROOT / "config" / "test.yaml").read_text()))
    s = storeys.storeys_settings(cfg)
    s["storeys"].update(storeys=[1, 3], pi12=[0.5, 1.0], pi2=[0.2])
    return s


def fake_solve_many(values):
    """A stand-in solver: Pi1 from ``values(scene)``; records the scenes it was given."""
    seen = []

    def solve_many(scenes, rtol=None):
        seen.extend(scenes)
        return SimpleNamespace(pi1=np.array([values(sc) for sc in scenes]), settled=np.ones(len(scenes), bool))

    solve_many.seen = seen
    return solve_many


def height(scene):
    """Pi1 growing with the floor's number on the linear isolator, largest on floor 1 for the pendulum."""
    k = scene.floor_index
    if scene.pi9 > 0:
        return 0.1 if k == 1 else 0.05
    return 0.01 * (1 + k) * scene.pi12


def test_grid_labels_and_nan_above_the_roof(settings):
    solve = fake_solve_many(height)
    ds = storeys.storeys_study(settings, solve_many=solve)
    assert ds["pi1"].dims == ("isolator", "pi12", "pi2", "storeys", "floor")
    assert list(ds["isolator"].values) == ["linear", "friction_pendulum"]
    assert list(ds["storeys"].values) == [1, 3] and list(ds["floor"].values) == [0, 1, 2, 3]
    assert len(solve.seen) == 2 * 2 * 1 * (2 + 4)
    one = ds["pi1"].sel(storeys=1)
    assert np.isnan(one.sel(floor=[2, 3])).all() and not np.isnan(one.sel(floor=[0, 1])).any()
    assert (ds["settled"].sel(storeys=1, floor=3) == -1).all() and (ds["settled"].sel(storeys=3) == 1).all()
    lin = ds.sel(isolator="linear", pi12=1.0, pi2=0.2, storeys=3)
    assert float(lin["pi1"].sel(floor=2)) == pytest.approx(0.03)
    # the scenes are those of the study: pendulum a sliding bearing, floors 0 .. N of each N
    fp = [sc for sc in solve.seen if sc.pi9 > 0]
    assert fp and all(sc.pi10 == 0.0 and sc.pi4 == settings["storeys"]["friction_pendulum"]["pi4"] for sc in fp)
    assert {(sc.storeys, sc.floor_index) for sc in solve.seen} == {(1, 0), (1, 1), (3, 0), (3, 1), (3, 2), (3, 3)}
    for v in ("pi1", "settled", "peak_floor", "upper_ratio", "roof_ratio", "upper_beats_slab", "pi4", "pi9"):
        assert ds[v].attrs.get("long_name") and "units" in ds[v].attrs, v


def test_peak_floor_and_upper_floor_beating_the_slab(settings):
    ds = storeys.storeys_study(settings, solve_many=fake_solve_many(height))
    lin = ds.sel(isolator="linear", pi2=0.2)
    assert (lin["peak_floor"].values == np.array([1, 3])[None, :]).all()          # the roof
    assert float(lin["upper_ratio"].sel(pi12=0.5, storeys=3)) == pytest.approx(4.0)
    assert lin["upper_beats_slab"].values.all()
    fp = ds.sel(isolator="friction_pendulum", pi2=0.2)
    assert (fp["peak_floor"].values == 1).all()                                    # a floor between for N = 3
    assert float(fp["roof_ratio"].sel(pi12=0.5, storeys=3)) == pytest.approx(1.0)
    rows = {(r[0], r[1]): r for r in storeys.floor_summary(ds)}
    assert rows[("linear", 0.5)][3:8] == (0, 2, 0, 0, 1)
    assert rows[("friction_pendulum", 1.0)][3:8] == (0, 1, 1, 0, 1)


def test_a_tie_within_the_tolerance_does_not_beat_the_slab(settings):
    ds = storeys.storeys_study(settings, solve_many=fake_solve_many(lambda sc: 0.1 * (1 + 0.003 * sc.floor_index)))
    assert not ds["upper_beats_slab"].values.any() and (ds["peak_floor"].values > 0).all()
    found = dict(storeys.findings(ds))
    assert "at no N" in found["When an upper floor beats the slab"]


def test_no_sliding_anywhere(settings):
    ds = storeys.storeys_study(settings, solve_many=fake_solve_many(lambda sc: 0.0))
    assert (ds["peak_floor"].values == -1).all() and np.isnan(ds["upper_ratio"].values).all()
    assert not ds["upper_beats_slab"].values.any()
    assert "of 4 buildings (4 without sliding on any floor)" in storeys.findings(ds)[0][1]


def test_findings_state_the_dataset_s_numbers(settings):
    ds = storeys.storeys_study(settings, solve_many=fake_solve_many(height))
    (t1, x1), (t2, x2) = storeys.findings(ds)
    assert "linear isolator: the contents slide most 0 on the slab, 4 on the roof, 0 on a floor between of 4" in x1
    assert "friction pendulum: the contents slide most 0 on the slab, 2 on the roof, 2 on a floor between" in x1
    ratio = float(ds["upper_ratio"].sel(isolator="linear", pi12=1.0, pi2=0.2, storeys=3))
    assert f"largest ratio {ratio:.2f}× at N = 3" in x2 and "at 2 of 2 N, the smallest N = 1" in x2


def test_dataset_is_cf_labelled_and_byte_identical(settings, tmp_path):
    a = storeys.storeys_dataset(settings, solve_many=fake_solve_many(height))
    b = storeys.storeys_dataset(copy.deepcopy(settings), solve_many=fake_solve_many(height))
    assert a.attrs["Conventions"].startswith("CF") and "isoslide_config" in a.attrs and "source" in a.attrs
    assert '"storeys": [1, 3]' in a.attrs["isoslide_config"]
    digests = [hashlib.sha256(write_netcdf(ds, tmp_path / f"{k}.nc").read_bytes()).hexdigest()
               for k, ds in enumerate((a, b))]
    assert digests[0] == digests[1]


@pytest.mark.parametrize("key, value, match", [
    ("storeys", [0, 1], "storeys.storeys"),
    ("storeys", [2, 1], "storeys.storeys"),
    ("storeys", [1.5], "storeys.storeys"),
    ("pi12", [], "storeys.pi12"),
    ("pi2", [-0.1], "storeys.pi2"),
    ("pi11", 1.0, "storeys.pi11 = 1.0 is out of range"),
    ("tolerance", 2.0, "storeys.tolerance"),
])
def test_bad_settings_name_the_key_and_the_allowed_range(settings, key, value, match):
    settings["storeys"][key] = value
    assert_refused(storeys.check_settings, settings, match)


def test_a_pendulum_without_strength_is_refused(settings):
    settings["storeys"]["friction_pendulum"]["pi9"] = 0.0
    with pytest.raises(ValueError, match=r"storeys.friction_pendulum.pi9 = 0.0 is out of range"):
        storeys.check_settings(settings)


def test_figure_has_its_caption(settings, tmp_path):
    ds = storeys.storeys_study(settings, solve_many=fake_solve_many(height))
    caption = draw(ds, [tmp_path / "storeys.png", tmp_path / "storeys.pdf"], {"dpi": 50})
    assert caption.startswith("Storeys.") and "N = 1, 3" in caption
    assert read_caption(tmp_path / "storeys.png") == caption and (tmp_path / "storeys.pdf").stat().st_size > 1000
    with pytest.raises(ValueError, match="outputs"):
        draw(ds, [tmp_path / "other.png"], {"dpi": 50})


def test_the_study_is_registered():
    study = {s.name: s for s in registry.STUDIES}["storeys"]
    assert study.dataset_names({}) == ["storeys"] and study.figures == ("storeys",)
    assert [r.name for r in study.reports] == ["isolation"]


@pytest.mark.slow
def test_exact_solutions_on_the_slab_and_the_roof(settings):
    """Floor 0 and floor N of the study are the solver's "base" and "roof" scenes."""
    settings["storeys"].update(storeys=[1, 2], pi12=[0.5], pi2=[0.2])
    ds = storeys.storeys_study(settings)
    s = settings["storeys"]
    for iso, groups in (("linear", {"pi4": s["linear"]["pi4"]}),
                        ("friction_pendulum", {"pi4": 0.0, "pi9": s["friction_pendulum"]["pi9"], "pi10": 0.0})):
        for n in (1, 2):
            for floor in ("base", "roof"):
                sc = isoslide.Scene(pi2=0.2, pi3=s["pi3"], pi11=s["pi11"], pi12=0.5, pi13=s["pi13"], storeys=n,
                                    floor=floor, **groups)
                k = 0 if floor == "base" else n
                got = float(ds["pi1"].sel(isolator=iso, pi12=0.5, pi2=0.2, storeys=n, floor=k))
                assert got == pytest.approx(isoslide.solve(sc, rtol=settings["solver"]["rtol"]).pi1, rel=1e-9)
    assert (ds["settled"].sel(storeys=2) == 1).all()
