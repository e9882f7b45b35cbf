"""Self-describing datasets: merging, CF metadata, compression, determinism, atomic writes."""

import copy
import json
import os
import re

import numpy as np
import pytest
import xarray as xr

import isoslide.config
from isoslide import datasets
from isoslide.studies import sweep
from isoslide.models import FACETS, MODEL_LABELS, Facets

CONFIG = {"chunk_size": 7, "reference": {"a_p_T_p": 9.80665}, "defaults": {"pi4": 0.1},
          "pi2": {"start": 0.05, "stop": 1.2, "num": 6},
          "studies": {"demo": {"figure": 6, "title": "demo study", "dims": {"pi3": [0.5, 1.0], "pi5": [0.7, 1.0]},
                               "fixed": {"beta": 1000.0}}}}


@pytest.fixture(scope="module")
def spec():
    return sweep.check_config(isoslide.config.validate(copy.deepcopy(CONFIG)))["demo"]


@pytest.fixture(scope="module")
def chunks(spec):
    return [sweep.solve_chunk(spec, k) for k in sweep.spec_chunks(spec)]


@pytest.fixture(scope="module")
def merged(spec, chunks):
    return datasets.merge_chunks(chunks, sweep.build_grid(spec))


def test_merge_is_independent_of_chunk_order_and_matches_a_direct_solve(spec, chunks, merged):
    again = datasets.merge_chunks(chunks[::-1], sweep.build_grid(spec))
    xr.testing.assert_identical(merged, again)
    grid = sweep.build_grid(spec)
    direct = sweep.solve_points(grid, np.arange(grid.size))
    assert np.array_equal(merged["pi1"].values.ravel(), direct.pi1)
    assert merged["pi1"].dims == ("pi3", "pi5", "pi2")


def test_merge_rejects_missing_or_foreign_chunks(spec, chunks):
    grid = sweep.build_grid(spec)
    with pytest.raises(ValueError, match="missing flat indices"):
        datasets.merge_chunks(chunks[:-1], grid)
    bad = chunks[0].assign_coords(pi2=chunks[0]["pi2"] * 1.0000001)
    with pytest.raises(ValueError, match="does not match the grid exactly"):
        datasets.merge_chunks([bad] + chunks[1:], grid)
    clash = chunks[0].copy()
    clash["pi1"] = clash["pi1"] + 1.0
    with pytest.raises(ValueError, match="overlap"):
        datasets.merge_chunks([clash] + chunks, grid)


def test_every_variable_and_coordinate_explains_itself(merged):
    for name, var in merged.variables.items():
        assert var.attrs.get("long_name"), name
        assert "units" in var.attrs, name
    for name in ("pi2", "pi3", "pi4", "pi5", "pi6", "pi7", "pi8"):
        assert merged[name].attrs["units"] == "1"
        assert merged[name].attrs["long_name"].startswith(f"Pi{name[2]} = ")
    for name in ("pi4", "pi6", "pi7", "pi8"):            # the fixed groups: scalar coordinates
        assert name in merged.coords and merged[name].ndim == 0
    assert float(merged["pi6"]) == pytest.approx(9806.65)
    assert merged["beta"].attrs["units"] == "s m-1"
    a = merged.attrs
    assert a["Conventions"].startswith("CF-")
    assert "demo study" in a["title"]
    assert "isoslide" in a["source"] and "git" in a["source"]
    assert "Nikfar" in a["references"] and "Newmark" in a["references"]
    assert json.loads(a["isoslide_config"])["study"] == "demo"
    assert not re.search(r"\d{4}-\d{2}-\d{2}|\d{2}:\d{2}:\d{2}", a["history"])   # no date or time
    assert "no timestamps" in a["history"]
    for field in ("pi1", "pi1_residual", "tau_peak", "settled", "tau_end", "n_steps", "n_events",
                  *datasets.FACET_VARIABLES.values()):
        assert field in merged
    names = datasets.model_labels(merged)
    assert set(np.unique(names.values)) <= set(MODEL_LABELS)


def test_written_file_is_compressed_deterministic_and_round_trips(tmp_path, merged):
    p1, p2 = tmp_path / "a.nc", tmp_path / "b.nc"
    datasets.write_netcdf(merged, p1)
    datasets.write_netcdf(merged, p2)
    assert p1.read_bytes() == p2.read_bytes()
    back = datasets.open_dataset(p1)
    xr.testing.assert_identical(back, merged)
    assert back["pi1"].encoding.get("zlib") is True
    assert sorted(os.listdir(tmp_path)) == ["a.nc", "b.nc"]          # no temporary files left


def test_atomic_write_leaves_nothing_on_failure(tmp_path, merged, monkeypatch):
    target = tmp_path / "x.nc"
    target.write_bytes(b"old")

    def boom(self, path, **kw):
        open(path, "wb").write(b"partial")
        raise RuntimeError("killed")

    monkeypatch.setattr(xr.Dataset, "to_netcdf", boom)
    with pytest.raises(RuntimeError):
        datasets.write_netcdf(merged, target)
    assert target.read_bytes() == b"old"
    assert os.listdir(tmp_path) == ["x.nc"]


def test_facet_variables_are_small_cf_flags_and_round_trip():
    """Each facet is an int8 flag variable of at most 16 meanings; decoding gives the facets back."""
    facets = [Facets(), Facets(isolator="sliding-bearing", superstructure="flexible", floor="intermediate",
                             friction="stribeck", coupling="one-way"),
              Facets(isolator="fixed-base", reduction="bearing-stuck", propagation="piecewise")]
    ds = xr.Dataset(datasets.encode_facets(facets, ("scene",)))
    ds["pi1"] = ("scene", np.array([0.0, 0.1, 0.2]))
    for name, var in datasets.FACET_VARIABLES.items():
        attrs = ds[var].attrs
        assert ds[var].dtype == np.int8 and len(attrs["flag_meanings"].split()) <= 16
        assert attrs["flag_meanings"].split() == list(FACETS[name])
        assert attrs["flag_values"].tolist() == list(range(len(FACETS[name])))
    assert datasets.decode_facets(ds).tolist() == facets
    assert datasets.model_labels(ds).values.tolist() == [
        "no-slide", "sliding-bearing+flexible+intermediate+stribeck+one-way",
        "bearing-stuck+fixed-base+coulomb+piecewise"]
    with pytest.raises(ValueError, match="is not an isoslide.models.Facets"):
        datasets.encode_facets(["coulomb"], ("scene",))


def test_assert_same_data_ignores_provenance_only(merged):
    other = merged.copy()
    other.attrs["source"] = "isoslide 0 (git other)"
    datasets.assert_same_data(merged, other)
    other["pi1"] = other["pi1"] * 1.0 + 1e-12
    with pytest.raises(AssertionError):
        datasets.assert_same_data(merged, other)
