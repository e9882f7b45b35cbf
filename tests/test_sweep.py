"""Study grids, chunking and configuration checks (isoslide.studies.sweep)."""

from pathlib import Path

import numpy as np
import pytest
import yaml

import isoslide
import isoslide.config
from isoslide.studies import sweep
from isoslide.datasets import write_netcdf

ROOT = Path(__file__).resolve().parents[1]


def load(name):
    return yaml.safe_load((ROOT / "config" / name).read_text())


BASE = {"chunk_size": 5, "reference": {"a_p_T_p": 9.80665}, "defaults": {"pi4": 0.1},
        "pi2": {"start": 0.1, "stop": 1.0, "num": 4}}


def cfg(**study):
    """A configuration with the schema defaults under BASE and one study (not schema-validated,
    so that the checks of isoslide.studies.sweep itself are exercised)."""
    c = isoslide.config.update(isoslide.config.defaults(), BASE)
    c["studies"] = {"s": {"figure": 5, **study}}
    return c


def test_defaults_filled_and_beta_turned_into_pi6():
    spec = sweep.check_config(cfg(dims={"beta": [10, 1000]}, fixed={"pi5": 0.5}))["s"]
    assert spec["dims"]["pi6"] == pytest.approx([98.0665, 9806.65])
    assert spec["beta"] == [10.0, 1000.0]
    assert spec["fixed"] == {"pi5": 0.5, "pi3": 0.0, "pi4": 0.1, "pi7": 0.0, "pi8": 1e-5,
                             "pi9": 0.0, "pi10": 0.0, "pi11": 0.0, "pi12": 0.0, "pi13": 0.0, "pi14": 1.0,
                             "pi15": 1.0, "pi16": 0.0, "pi17": 0.0, "pi22": 1.0, "pi23": 0.0, "pi24": 0.0,
                             "pi25": 0.5, "pi26": 1.0, "pi27": 1.0, "pi28": 0.0, "pi29": 0.0, "pi30": 0.0}
    assert spec["pulse"] == "ricker"


@pytest.mark.parametrize("study, key", [
    ({"dims": {"pi5": [0.5, 1.5]}}, "studies.s.dims.pi5[1]"),
    ({"dims": {"pi3": [1, 1]}}, "studies.s.dims.pi3"),
    ({"dims": {"pi18": [1]}}, "pi18"),
    ({"dims": {"pi12": [0.2]}}, "pi11"),
    ({"fixed": {"pi8": -1}}, "studies.s.fixed.pi8"),
    ({"pulse": "sine"}, "studies.s.pulse"),
    ({"dims": {"pi3": [1]}, "fixed": {"pi3": 2}}, "both swept"),
    ({"dims": {"beta": [1]}, "fixed": {"pi6": 2}}, "either beta or pi6"),
    ({"pi2": {"start": 0.5, "stop": 0.2}}, "studies.s.pi2.stop"),
])
def test_invalid_values_name_their_key(study, key):
    with pytest.raises(sweep.ConfigError, match=key.replace("[", r"\[").replace("]", r"\]")):
        sweep.check_config(cfg(**study))


def test_grid_order_and_chunks_cover_every_scene_once():
    spec = sweep.check_config(cfg(dims={"pi3": [0.5, 1.0, 2.0], "pi5": [0.5, 1.0]}))["s"]
    grid = sweep.build_grid(spec)
    assert grid.dim_names == ("pi3", "pi5", "pi2")
    assert grid.shape == (3, 2, 4) and grid.size == 24 == sweep.spec_size(spec)
    pts = grid.points()
    assert np.array_equal(pts["pi2"][:4], grid.dims["pi2"])          # pi2 varies fastest
    assert np.all(pts["pi3"][:8] == 0.5) and np.all(pts["pi5"][:4] == 0.5)
    chunks = sweep.spec_chunks(spec)
    assert chunks == list(range(5))
    idx = np.concatenate([grid.chunk_indices(k, spec["chunk_size"]) for k in chunks])
    assert np.array_equal(idx, np.arange(24))
    with pytest.raises(ValueError, match="chunk = 5"):
        grid.chunk_indices(5, spec["chunk_size"])
    scenes = grid.scenes([23])
    assert scenes[0] == isoslide.Scene(pi2=1.0, pi3=2.0, pi4=0.1, pi5=1.0, pi8=1e-5)


def test_n_chunks():
    assert sweep.n_chunks(10, 3) == 4
    assert sweep.n_chunks(9, 3) == 3
    assert sweep.n_chunks(0, 3) == 1
    with pytest.raises(ValueError, match="chunk_size"):
        sweep.n_chunks(10, 0)


def test_auto_stop_is_past_the_last_nonzero_response():
    c = cfg(dims={"pi3": [0.5, 1.0]})
    c["pi2"].update({"start": 0.02, "stop": "auto", "num": 12})
    grid = sweep.build_grid(sweep.check_config(c)["s"])
    stop = grid.dims["pi2"][-1]
    demand = max(sweep.peak_floor_accel(p, 0.1, 1e-5) for p in (0.5, 1.0))
    assert demand * 1.05 <= stop + 1e-12 < demand * 1.05 + 0.05 + 1e-12
    batch = isoslide.solve_many(grid.scenes())
    pi1 = batch.pi1.reshape(grid.shape)
    assert np.all(pi1[:, -1] == 0.0)                 # past the last non-zero response
    assert np.all(pi1[:, 0] > 0.0)


def test_shipped_configs_are_valid_and_cover_the_paper():
    main, _test = isoslide.config.load(), load("test.yaml")
    specs = sweep.check_config(main)
    assert set(load("test.yaml")["studies"]) == set(specs)   # the tiny config shrinks every study
    for name, spec in specs.items():
        if name != "fig3_newmark":
            assert spec["pi2"]["num"] >= 60 and spec["pi2"]["start"] == 0.02
    assert specs["fig5_pi3"]["dims"]["pi3"] == [0.01, 0.5, 1.0, 1.5, 2.0, 3.0]
    assert specs["fig5_pi4"]["dims"]["pi4"] == [0.0, 0.05, 0.1, 0.15, 0.2, 0.3]
    assert min(specs["fig6_pi5"]["dims"]["pi5"]) == 0.5 and max(specs["fig6_pi5"]["dims"]["pi5"]) == 1.0
    assert specs["fig7_pi6"]["beta"][0] == 10 and specs["fig7_pi6"]["beta"][-1] == 1000
    assert max(specs["fig7_pi7"]["dims"]["pi7"]) == pytest.approx(0.1 * isoslide.G_STANDARD * 5.0)
    assert specs["fig8_pi8"]["dims"]["pi8"][0] == 1e-5 and specs["fig8_pi8"]["dims"]["pi8"][-1] == 1.0
    tiny = sweep.check_config(isoslide.config.load(None, ROOT / "config" / "test.yaml"))
    assert all(sweep.spec_size(tiny[k]) < sweep.spec_size(specs[k]) for k in specs)


def test_solve_chunk_dataset():
    spec = sweep.check_config(cfg(dims={"pi3": [1.0]}))["s"]
    ds = sweep.solve_chunk(spec, 0)
    assert ds.sizes["scene"] == 4
    assert list(ds["scene"].values) == [0, 1, 2, 3]
    assert ds["pi1"].values[0] > 0
    ref = isoslide.solve(isoslide.Scene(pi2=0.1, pi3=1.0, pi4=0.1))
    assert ds["pi1"].values[0] == pytest.approx(ref.pi1, rel=1e-6)


def test_a_study_of_one_chunk_solved_in_one_job_gives_the_same_bytes(tmp_path):
    """solve_study equals solve_chunk -> chunk file -> merge_chunk_files, byte for byte once written."""
    spec = sweep.check_config(cfg(dims={"pi3": [1.0]}))["s"]          # 4 scenes, chunk_size 5
    chunk = write_netcdf(sweep.solve_chunk(spec, 0), tmp_path / "0.nc")
    a = write_netcdf(sweep.merge_chunk_files([chunk], spec), tmp_path / "merged.nc")
    b = write_netcdf(sweep.solve_study(spec), tmp_path / "direct.nc")
    assert a.read_bytes() == b.read_bytes()
    two = sweep.check_config(cfg(dims={"pi3": [1.0, 2.0]}))["s"]      # 8 scenes: two chunks
    with pytest.raises(ValueError, match="has 2 chunks at chunk_size = 5"):
        sweep.solve_study(two)
