"""Histories written to CSV and HDF5: columns, units, round trip and the floor acceleration."""

import h5py
import numpy as np
import pytest

import isoslide
from isoslide import Scene
from isoslide.store.history_io import COLUMNS, history_table, read_history, write_history


def _physical_scene(**kw):
    args = dict(a_p=6.0, T_p=1.2, M_b=8e5, T_b=2.4, xi_b=0.1, m_ec=8e4, mu_s=0.25, mu_k=0.2,
                beta=200.0, gamma=0.05)
    return isoslide.Scene.from_physical(**(args | kw))


@pytest.mark.parametrize("suffix", [".csv", ".h5", ".hdf5"])
def test_write_then_read_gives_the_same_columns_units_and_attributes(tmp_path, suffix):
    scene = _physical_scene()
    sol = isoslide.solve(scene, history=True)
    table = history_table(sol, scene)
    path = write_history(sol, scene, tmp_path / f"h{suffix}")
    back = read_history(path)
    assert list(back.columns) == [c[0] for c in COLUMNS]
    for name, values in table.columns.items():
        np.testing.assert_array_equal(back.columns[name], values, err_msg=name)
    assert back.columns["phase"].dtype == np.int8
    assert back.units == table.units
    assert back.attrs == table.attrs
    assert back.attrs["u_max"] == sol.u_max and back.attrs["model"] == sol.model


def test_hdf5_datasets_carry_si_units_and_long_names(tmp_path):
    scene = _physical_scene()
    sol = isoslide.solve(scene, history=True)
    write_history(sol, scene, tmp_path / "h.h5")
    with h5py.File(tmp_path / "h.h5") as f:
        assert {k: f[k].attrs["units"] for k in f} == {
            "time": "s", "ground_accel": "m s-2", "floor_accel": "m s-2", "floor_disp": "m",
            "floor_vel": "m s-1", "slide_disp": "m", "slide_vel": "m s-1", "phase": "1"}
        assert f["slide_disp"].attrs["long_name"] == "block sliding displacement relative to the floor"
        assert f.attrs["T_p"] == 1.2 and bool(f.attrs["physical"]) is True


def test_physical_columns_are_the_dimensionless_history_times_the_scales():
    scene = _physical_scene()
    sol = isoslide.solve(scene, history=True)
    h, c = sol.history, history_table(sol, scene).columns
    a_p, T_p = 6.0, 1.2
    np.testing.assert_allclose(c["time"], h.tau * T_p, rtol=1e-15)
    np.testing.assert_allclose(c["slide_disp"], h.u * a_p * T_p**2, rtol=1e-15)
    np.testing.assert_allclose(c["floor_vel"], h.xd * a_p * T_p, rtol=1e-15)
    np.testing.assert_allclose(c["ground_accel"], scene.pulse.accel(h.tau) * a_p, rtol=1e-15)
    assert np.max(np.abs(c["slide_disp"])) == pytest.approx(sol.u_max, rel=1e-9)


def test_dimensionless_scene_gives_unit_1_columns(tmp_path):
    scene = isoslide.Scene(pi2=0.2, pi3=1.0, pi4=0.1)
    sol = isoslide.solve(scene, history=True)
    back = read_history(write_history(sol, scene, tmp_path / "h.csv"))
    assert set(back.units.values()) == {"1"}
    assert back.attrs["physical"] is False
    np.testing.assert_array_equal(back.columns["time"], sol.history.tau)
    with h5py.File(write_history(sol, scene, tmp_path / "h.h5")) as f:
        assert f["slide_disp"].attrs["scale"] == "a_p T_p^2"


@pytest.mark.parametrize("m_ec", [8e4, 0.0])
def test_floor_acceleration_is_ground_plus_derivative_of_floor_velocity(m_ec):
    """Away from stick/slip transitions (where it jumps) the floor's absolute acceleration equals
    the ground's plus the time derivative of the floor velocity relative to the ground."""
    scene = _physical_scene(m_ec=m_ec)
    sol = isoslide.solve(scene, history=True, max_step=0.002)
    c = history_table(sol, scene).columns
    assert np.any(c["phase"] != 0) and np.any(c["phase"] == 0)
    numeric = c["ground_accel"] + np.gradient(c["floor_vel"], c["time"])
    change = np.flatnonzero(np.diff(c["phase"]) != 0)
    away = np.ones(c["time"].size, dtype=bool)
    for k in change:
        away[max(k - 2, 0):k + 3] = False
    away[[0, -1]] = False
    scale = np.max(np.abs(c["floor_accel"]))
    np.testing.assert_allclose(c["floor_accel"][away], numeric[away], atol=2e-3 * scale)


def test_fixed_base_floor_moves_with_the_ground():
    scene = _physical_scene(T_b=0.0)
    sol = isoslide.solve(scene, history=True)
    c = history_table(sol, scene).columns
    np.testing.assert_array_equal(c["floor_accel"], c["ground_accel"])
    assert not np.any(c["floor_disp"])


def test_floor_on_a_sliding_bearing_that_holds_moves_with_the_ground():
    """A friction pendulum stronger than the pulse never slides: the solver runs the fixed base
    (``bearing-stuck``), and the floor's absolute acceleration is the ground's, not zero."""
    from isoslide.studies.intensity import floor_peaks

    scene = Scene.from_physical(a_p=0.25, T_p=1.0, M_b=1e6, xi_b=0.0, m_ec=10.0, mu_s=0.3, mu_k=0.3,
                                **isoslide.friction_pendulum(R=3.0, mu=0.05, M_b=1e6))
    sol = isoslide.solve(scene, history=True, max_step=0.01)
    assert sol.facets.reduction == "bearing-stuck" and sol.facets.isolator == "fixed-base"
    c = history_table(sol, scene).columns
    np.testing.assert_array_equal(c["floor_accel"], c["ground_accel"])
    assert not np.any(c["floor_disp"])
    pfa, pfv = floor_peaks(sol, scene)
    assert pfa == np.max(np.abs(c["ground_accel"])) == pytest.approx(0.25, rel=1e-12)   # a row at the peak
    assert pfv > 0.0


def test_unknown_extension_and_missing_history_are_refused(tmp_path):
    scene = isoslide.Scene(pi2=0.2, pi3=1.0, pi4=0.1)
    with pytest.raises(ValueError, match=r"path = .*h\.txt.* allowed: \.csv, \.h5, \.hdf5"):
        write_history(isoslide.solve(scene, history=True), scene, tmp_path / "h.txt")
    with pytest.raises(ValueError, match="history=True"):
        write_history(isoslide.solve(scene), scene, tmp_path / "h.csv")


@pytest.mark.parametrize("floor", ["base", "roof"])
def test_building_history_floor_acceleration_is_the_rate_of_the_floor_velocity(floor, tmp_path):
    """General building: floor_accel = ground_accel + d(floor_vel)/dt, and the extra columns round-trip."""
    from isoslide.store.history_io import BUILDING_COLUMNS
    sc = Scene(pi2=0.1, pi3=3.0, pi4=0.05, pi8=0.1, pi9=0.05, pi11=0.6, pi12=0.3, pi13=0.02, floor=floor)
    sol = isoslide.solve(sc, history=True, max_step=1e-3)
    t = history_table(sol, sc)
    time_, v = t.columns["time"], t.columns["floor_vel"]
    mid = 0.5 * (time_[1:] + time_[:-1])
    same = lambda c: t.columns[c][1:] == t.columns[c][:-1]  # noqa: E731
    ok = (np.diff(time_) > 1e-6) & same("phase") & same("isolator_phase")   # no mode change inside
    rate = np.diff(v)[ok] / np.diff(time_)[ok]
    expect = np.interp(mid[ok], time_, t.columns["floor_accel"] - t.columns["ground_accel"])
    assert np.max(np.abs(rate - expect)) <= 1e-3 * np.max(np.abs(t.columns["floor_accel"]))
    if floor == "roof":
        assert np.allclose(t.columns["floor_disp"], t.columns["slab_disp"] + t.columns["super_disp"])
    back = read_history(write_history(sol, sc, tmp_path / "h.h5"))
    for name, *_ in BUILDING_COLUMNS:
        np.testing.assert_array_equal(back.columns[name], t.columns[name])


PLANAR = dict(pulse_y="antisymmetric_ricker", pi14=0.7)


@pytest.mark.parametrize("kw, n_columns", [
    (dict(pi2=0.15, pi3=0.0), 14),
    (dict(pi2=0.15, pi3=2.0, pi4=0.1, pi9=0.05, pi10=0.02, pi8=0.2), 25),
    (dict(pi2=0.15, pi3=2.0, pi4=0.1, pi11=0.5, pi12=0.3, pi13=0.05, storeys=3, floor=2, pi8=0.1), 33),
], ids=["fixed-base", "bilinear", "three-storeys"])
@pytest.mark.parametrize("suffix", [".csv", ".h5"])
def test_a_planar_history_has_every_motion_along_both_axes_and_reads_back(tmp_path, kw, n_columns, suffix):
    """Every motion column twice (``_x``, ``_y``); the table equals the solver's history; the file round-trips."""
    scene = Scene(**kw, **PLANAR)
    sol = isoslide.solve(scene, history=True)
    table = history_table(sol, scene)
    assert len(table.columns) == n_columns
    h = sol.history
    for a, axis in enumerate("xy"):
        np.testing.assert_array_equal(table.columns[f"slide_disp_{axis}"], h.u[:, a])
        np.testing.assert_array_equal(table.columns[f"ground_accel_{axis}"], scene.ground(h.tau)[a])
    assert set(np.unique(table.columns["phase"])) == {0, 1}
    back = read_history(write_history(sol, scene, tmp_path / f"h{suffix}"))
    assert list(back.columns) == list(table.columns)
    for name, values in table.columns.items():
        np.testing.assert_array_equal(back.columns[name], values, err_msg=name)
    assert back.attrs["peak_angle"] == sol.peak_angle


def test_a_flexible_superstructure_of_three_storeys_writes_a_column_per_floor(tmp_path):
    scene = Scene(pi2=0.15, pi3=2.0, pi4=0.1, pi11=0.5, pi12=0.3, pi13=0.05, storeys=3, floor="roof", pi8=0.1)
    sol = isoslide.solve(scene, history=True)
    back = read_history(write_history(sol, scene, tmp_path / "h.csv"))
    for k in range(3):
        np.testing.assert_array_equal(back.columns[f"super_disp_{k + 1}"], sol.history.xs[:, k])
        np.testing.assert_array_equal(back.columns[f"super_vel_{k + 1}"], sol.history.xsd[:, k])
