"""isoslide.studies.pelicun_export: fitted curves as a pelicun damage model, read back by the real pelicun."""

import json
import math
import socket

import numpy as np
import pandas as pd
import pytest
import xarray as xr

import pelicun
from pelicun import assessment, file_io

from isoslide.studies.fragility import probability
from isoslide.studies.pelicun_export import COMPONENT_IDS, G_PELICUN, damage_db, write_damage_db

G = 9.80665
LIMITS = [0.1, 0.2, 0.3]
IMS = ["pga", "pgv", "pfa", "pfv"]
# medians in m/s^2 (pga, pfa) and m/s (pgv, pfv); increasing with the limit state
THETA = np.array([[2.0, 0.3, 2.5, 0.35], [3.5, 0.5, 4.0, 0.55], [5.0, 0.7, 6.0, 0.8]])
BETA = np.array([[0.5, 0.5, 0.45, 0.40], [0.5, 0.5, 0.45, 0.42], [0.5, 0.5, 0.5, 0.45]])


def _curves(theta=THETA, beta=BETA, limits=LIMITS, ims=IMS):
    coords = {"limit_state": ("limit_state", np.asarray(limits, dtype=float), {"units": "m"}), "im": ims}
    return (xr.DataArray(np.asarray(theta, dtype=float), dims=("limit_state", "im"), coords=coords),
            xr.DataArray(np.asarray(beta, dtype=float), dims=("limit_state", "im"), coords=coords))


@pytest.fixture(autouse=True)
def no_network(monkeypatch):
    """Every test here runs offline: a socket connection raises (pelicun 3.10 downloads nothing)."""
    def refuse(*args, **kwargs):
        raise OSError("network access in an offline test")
    monkeypatch.setattr(socket.socket, "connect", refuse)
    monkeypatch.setattr(socket.socket, "connect_ex", refuse)


def test_pelicun_3_and_its_model_library_are_installed():
    """pelicun 3.x from environment.lock; its model library (dlml) is an installed package, not a download."""
    assert int(pelicun.__version__.split(".")[0]) == 3
    import dlml  # noqa: F401  (the FEMA P-58 data pelicun 3.10 reads, installed with it)


def test_the_units_written_are_pelicuns_own():
    """Demand-Unit strings pelicun knows, and the median in g uses pelicun's g exactly."""
    factors = assessment.Assessment({"PrintLog": False}).unit_conversion_factors
    assert factors["g"] == G_PELICUN == G
    assert factors["mps"] == 1.0 and factors["mps2"] == 1.0
    from pelicun.base import EDP_TYPES
    assert EDP_TYPES["Peak Floor Acceleration"] == {"Acronym": "PFA", "UnitType": "acceleration"}
    assert EDP_TYPES["Peak Floor Velocity"]["Acronym"] == "PFV"


def test_the_table_has_one_component_per_floor_im_in_pelicun_units():
    table = damage_db(*_curves())
    assert list(table.index) == [COMPONENT_IDS["pfa"], COMPONENT_IDS["pfv"]] == ["isoslide.PFA", "isoslide.PFV"]
    pfa, pfv = table.loc["isoslide.PFA"], table.loc["isoslide.PFV"]
    assert (pfa["Demand-Type"], pfa["Demand-Unit"]) == ("Peak Floor Acceleration", "g")
    assert (pfv["Demand-Type"], pfv["Demand-Unit"]) == ("Peak Floor Velocity", "mps")
    for k in range(3):
        assert pfa[f"LS{k + 1}-Family"] == "lognormal"
        assert pfa[f"LS{k + 1}-Theta_0"] == THETA[k, 2] / G
        assert pfa[f"LS{k + 1}-Theta_1"] == BETA[k, 2]
        assert pfv[f"LS{k + 1}-Theta_0"] == THETA[k, 3]
        assert pfv[f"LS{k + 1}-Theta_1"] == BETA[k, 3]
    assert (pfa["Incomplete"], pfa["Demand-Offset"], pfa["Demand-Directional"]) == (0, 0, 0)
    assert pfv["Demand-Directional"] == 0


def test_limit_states_are_numbered_in_increasing_displacement_whatever_the_input_order():
    theta, beta = _curves()
    shuffled = damage_db(theta.isel(limit_state=[2, 0, 1]).transpose("im", "limit_state"),
                         beta.isel(limit_state=[1, 2, 0]))
    pd.testing.assert_frame_equal(shuffled, damage_db(theta, beta))


def test_written_csv_is_byte_stable_and_reads_back_to_the_same_numbers(tmp_path):
    theta, beta = _curves()
    a = write_damage_db(tmp_path / "a" / "db.csv", theta, beta, json_path=tmp_path / "a" / "db.json")
    b = write_damage_db(tmp_path / "b.csv", theta.copy(), beta.copy())
    assert a.read_bytes() == b.read_bytes()
    assert sorted(p.name for p in (tmp_path / "a").iterdir()) == ["db.csv", "db.json"]   # no temporary left
    back = pd.read_csv(a, index_col=0)
    assert back.loc["isoslide.PFA", "LS2-Theta_0"] == THETA[1, 2] / G     # repr round-trips exactly
    assert a.read_text().splitlines()[0].startswith(
        "ID,Incomplete,Demand-Type,Demand-Unit,Demand-Offset,Demand-Directional,LS1-Family,LS1-Theta_0,")
    meta = json.loads((tmp_path / "a" / "db.json").read_text())
    assert meta["isoslide.PFV"]["LimitStates"]["LS3"]["DS3"]["Description"] == "Peak sliding displacement above 0.3 m"


def _pelicun_exceedance(db_path, x_pfa, x_pfv, per_level, *, other=0.5, multiplier=1.0, direction="0"):
    """P(DS >= k) at each demand level from pelicun's damage sample (demands given in m/s^2 and m/s).

    The floor demands are given in two directions, ``x`` in direction 1 and ``other * x`` in
    direction 2; the components are assigned with ``direction`` and pelicun's non-directional
    multiplier is ``multiplier``.
    """
    asmnt = assessment.Assessment({"PrintLog": False, "Seed": 7, "NonDirectionalMultipliers": {"ALL": multiplier}})
    cols = pd.MultiIndex.from_tuples([("PFA", "0", "1"), ("PFA", "0", "2"), ("PFV", "0", "1"), ("PFV", "0", "2")])
    a, v = np.repeat(x_pfa, per_level), np.repeat(x_pfv, per_level)
    values = np.column_stack([a, other * a, v, other * v])
    units = pd.DataFrame([["mps2", "mps2", "mps", "mps"]], columns=cols, index=["Units"])
    asmnt.demand.load_sample(pd.concat([units, pd.DataFrame(values, columns=cols).astype(object)]))
    asmnt.stories = 1
    ids = list(COMPONENT_IDS.values())
    asmnt.asset.load_cmp_model({"marginals": pd.DataFrame(
        {"Units": "ea", "Location": "1", "Direction": direction, "Theta_0": 1}, index=ids)})
    asmnt.asset.generate_cmp_sample()
    db = file_io.load_data(str(db_path), reindex=False, unit_conversion_factors=asmnt.unit_conversion_factors)
    asmnt.damage.load_model_parameters([db], set(asmnt.asset.list_unique_component_ids()))
    asmnt.damage.calculate()
    sample = asmnt.damage.ds_model.sample
    out = {}
    for im, cid in COMPONENT_IDS.items():
        ds = sample[cid].T.groupby(level="ds").sum().T    # quantity in each damage state, one block
        state = ds.to_numpy().argmax(axis=1)
        state = state.reshape(-1, per_level)
        out[im] = np.stack([(state >= k).mean(axis=1) for k in (1, 2, 3)], axis=1)   # (level, k)
    return out


def test_pelicun_damage_states_follow_the_fitted_curves(tmp_path):
    """pelicun reads the CSV (with its unit conversion: demands in m/s^2 against medians in g), and the
    share of realisations in DS >= k at each demand equals the fitted curve, the upper envelope
    max_{j >= k} P_j of the curves (pelicun's capacities of one component are perfectly correlated),
    within 4 binomial standard deviations of 4000 realisations per demand level."""
    theta, beta = _curves()
    path = write_damage_db(tmp_path / "db.csv", theta, beta)
    x_pfa = np.array([1.5, 2.5, 4.0, 6.0, 9.0])   # m/s^2
    x_pfv = np.array([0.2, 0.35, 0.55, 0.8, 1.2])  # m/s
    per_level = 4000
    got = _pelicun_exceedance(path, x_pfa, x_pfv, per_level)
    for im, x in (("pfa", x_pfa), ("pfv", x_pfv)):
        b = IMS.index(im)
        curves = np.stack([probability(x, THETA[k, b], BETA[k, b]) for k in range(3)], axis=1)
        envelope = np.maximum.accumulate(curves[:, ::-1], axis=1)[:, ::-1]
        sd = np.sqrt(envelope * (1 - envelope) / per_level)
        assert np.all(np.abs(got[im] - envelope) <= 4 * sd + 1e-12), (im, got[im], envelope)
        # where the fitted curves are ordered (all these demands), the envelope is the fitted curve itself
        np.testing.assert_allclose(envelope, curves, rtol=0, atol=1e-12)


def test_pelicun_reproduces_the_envelope_where_fitted_curves_cross(tmp_path):
    """LS2 steeper than LS1 (beta 0.2 against 0.8): above their crossing P_2 > P_1 and pelicun's
    P(DS >= 1) follows P_2, not the fitted P_1 (the documented behaviour of the export)."""
    theta = THETA.copy()
    beta = BETA.copy()
    beta[:, 2] = [0.8, 0.2, 0.25]
    path = write_damage_db(tmp_path / "db.csv", *_curves(theta, beta))
    x_pfa = np.array([5.0, 6.0])
    b = IMS.index("pfa")
    p1, p2 = probability(x_pfa, theta[0, b], beta[0, b]), probability(x_pfa, theta[1, b], beta[1, b])
    assert np.all(p2 > p1 + 0.05)     # the fitted curves have crossed at these demands
    got = _pelicun_exceedance(path, x_pfa, np.array([0.3, 0.3]), 4000)["pfa"][:, 0]
    want = np.maximum.reduce([probability(x_pfa, theta[k, b], beta[k, b]) for k in range(3)])
    sd = np.sqrt(want * (1 - want) / 4000)
    assert np.all(np.abs(got - want) <= 4 * sd), (got, want)
    assert np.all(np.abs(got - p1) > 4 * np.sqrt(p1 * (1 - p1) / 4000))


def test_medians_that_do_not_increase_are_refused_not_reordered():
    theta = THETA.copy()
    theta[2, 3] = theta[1, 3]
    with pytest.raises(ValueError, match=r"theta\[im='pfv'\] = 0\.55 at limit_state=0\.2 m and 0\.55 at "
                                         r"limit_state=0\.3 m: medians do not increase.*Not reordered"):
        damage_db(*_curves(theta=theta))


def test_a_missing_curve_raises_or_is_flagged_incomplete(tmp_path):
    theta = THETA.copy()
    theta[2, 2] = np.nan
    with pytest.raises(ValueError, match=r"theta\[limit_state=0\.3, im='pfa'\] = nan: the curve is missing"):
        damage_db(*_curves(theta=theta))
    assert not list(tmp_path.iterdir())
    table = damage_db(*_curves(theta=theta), incomplete="flag")
    assert table.loc["isoslide.PFA", "Incomplete"] == 1 and table.loc["isoslide.PFV", "Incomplete"] == 0
    assert math.isnan(table.loc["isoslide.PFA", "LS3-Theta_0"])
    assert table.loc["isoslide.PFA", "LS2-Theta_0"] == THETA[1, 2] / G


def test_write_leaves_nothing_when_the_table_is_refused(tmp_path):
    theta = THETA.copy()
    theta[0, 2] = -1.0
    with pytest.raises(ValueError, match=r"theta\[limit_state=0\.1, im='pfa'\] = -1\.0 is out of range"):
        write_damage_db(tmp_path / "db.csv", *_curves(theta=theta))
    assert not list(tmp_path.iterdir())


@pytest.mark.parametrize("make, pattern", [
    (lambda t, b: (t.values, b), r"^theta is a ndarray; allowed: an xarray\.DataArray"),
    (lambda t, b: (t.rename(im="ims"), b), r"^theta has dims \('limit_state', 'ims'\)"),
    (lambda t, b: (t.assign_coords(im=["pga", "pgv", "pfa", "sa"]), b), r"theta\.im = .* has \['sa'\]"),
    (lambda t, b: (t.assign_coords(limit_state=[0.1, 0.1, 0.3]), b), r"theta\.limit_state = \[0\.1, 0\.1, 0\.3\]"),
    (lambda t, b: (t.assign_coords(limit_state=[0.0, 0.1, 0.3]), b), r"allowed: distinct sliding limits > 0 m"),
    (lambda t, b: (t, b.assign_coords(limit_state=[0.1, 0.2, 0.4])), r"^beta has coordinates .* allowed: those of theta"),
    (lambda t, b: (t.sel(im=["pga", "pgv"]), b.sel(im=["pga", "pgv"])), r"has no floor IM; allowed: at least one"),
    (lambda t, b: (t, b.where(b.im != "pfv", 0.0)), r"^beta\[limit_state=0\.1, im='pfv'\] = 0\.0 is out of range"),
])
def test_damage_db_rejects_curves_pelicun_cannot_take(make, pattern):
    with pytest.raises(ValueError, match=pattern):
        damage_db(*make(*_curves()))


def test_component_ids_can_be_renamed_and_incomplete_must_be_known():
    table = damage_db(*_curves(), component_ids={"pfv": "lab.shelf.PFV"})
    assert list(table.index) == ["isoslide.PFA", "lab.shelf.PFV"]
    with pytest.raises(ValueError, match=r"^incomplete = 'skip' is invalid; allowed: 'raise', 'flag'"):
        damage_db(*_curves(), incomplete="skip")


@pytest.mark.parametrize("other, multiplier, direction", [(1.6, 1.2, "0"), (0.5, 1.2, "1"), (1.25, 1.0, "2")])
def test_pelicun_reads_the_contents_as_non_directional(tmp_path, other, multiplier, direction):
    """Demand-Directional 0: pelicun feeds each curve the larger of the two floor directions times its
    non-directional multiplier (1.2 by default), whatever direction the component was assigned, so
    P(DS >= k) is the fitted curve at multiplier * max(x, other * x)."""
    theta, beta = _curves()
    path = write_damage_db(tmp_path / "db.csv", theta, beta)
    x_pfa = np.array([1.5, 3.0, 5.0])
    x_pfv = np.array([0.2, 0.4, 0.7])
    per_level = 3000
    got = _pelicun_exceedance(path, x_pfa, x_pfv, per_level, other=other, multiplier=multiplier,
                              direction=direction)
    for im, x in (("pfa", x_pfa), ("pfv", x_pfv)):
        b = IMS.index(im)
        demand = multiplier * np.maximum(x, other * x)
        want = np.stack([probability(demand, THETA[k, b], BETA[k, b]) for k in range(3)], axis=1)
        want = np.maximum.accumulate(want[:, ::-1], axis=1)[:, ::-1]
        sd = np.sqrt(want * (1 - want) / per_level)
        assert np.all(np.abs(got[im] - want) <= 4 * sd + 1e-12), (im, got[im], want)
        # and not the curve at the direction-1 demand alone, where the two differ
        alone = probability(x, THETA[0, b], BETA[0, b])
        differs = np.abs(want[:, 0] - alone) > 8 * np.sqrt(alone * (1 - alone) / per_level) + 0.02
        assert np.all(np.abs(got[im][differs, 0] - alone[differs]) > 4 * sd[differs, 0])
