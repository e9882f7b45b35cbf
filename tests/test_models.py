"""Model labels: every label a solve produces has a flag code, and every listed label is produced."""

import numpy as np
import pytest
import xarray as xr

import isoslide
from isoslide import datasets
from isoslide.models import BUILDING_LABELS, MODEL_LABELS, PEER_LABELS, PIECEWISE_LABELS, label
from isoslide.pulses import sampled

RECORD = sampled(np.sin(np.linspace(0.0, 2.0 * np.pi, 201)), 0.005)
"""A short sampled record: one sine cycle of unit amplitude over one T_p."""

# one scene per model path of the exact solver: (scene, solve keyword arguments)
PATHS = [
    (isoslide.Scene(pi2=5.0, pi3=1.0, pi4=0.1), {}),                                  # no-slide
    (isoslide.Scene(pi2=5.0, pi3=0.0), {}),                                           # fixed-base+no-slide
    (isoslide.Scene(pi2=0.2, pi3=1.0, pi4=0.1, pi8=0.1), {}),                         # coulomb
    (isoslide.Scene(pi2=0.2, pi3=1.0, pi4=0.1, pi8=0.0), {}),                         # coulomb+one-way
    (isoslide.Scene(pi2=0.2, pi3=1.0, pi4=0.1, pi5=0.7, pi6=1e3, pi8=0.1), {}),       # stribeck
    (isoslide.Scene(pi2=0.2, pi3=1.0, pi4=0.1, pi5=0.7, pi6=1e3, pi8=0.0), {}),       # stribeck+one-way
    (isoslide.Scene(pi2=0.2, pi3=0.0), {}),                                           # fixed-base+coulomb
    (isoslide.Scene(pi2=0.2, pi3=0.0, pi5=0.7, pi6=1e3), {}),                         # fixed-base+stribeck
    (isoslide.Scene(pi2=0.2, pi3=1.0, pi4=0.1, pi5=0.7, pi8=0.1), {"model": "static-kinetic"}),
    (isoslide.Scene(pi2=0.2, pi3=1.0, pi4=0.1, pi5=0.7, pi8=0.0), {"model": "static-kinetic"}),
    (isoslide.Scene(pi2=0.2, pi3=0.0, pi5=0.7), {"model": "static-kinetic"}),
    (isoslide.Scene(pi2=0.3, pi3=0.0), {"method": "regularized", "stiffness": 1e4, "rtol": 1e-4}),
    (isoslide.Scene(pi2=0.3, pi3=0.0), {"method": "reference"}),
    # a sampled record with Coulomb contents: the exact piecewise propagation
    (isoslide.Scene(pi2=5.0, pi3=1.0, pi4=0.1, pulse=RECORD), {}),                    # no-slide+piecewise
    (isoslide.Scene(pi2=0.2, pi3=1.0, pi4=0.1, pi8=0.1, pulse=RECORD), {}),           # coulomb+piecewise
    (isoslide.Scene(pi2=0.2, pi3=1.0, pi4=0.1, pi8=0.0, pulse=RECORD), {}),           # coulomb+one-way+piecewise
    (isoslide.Scene(pi2=5.0, pi3=0.0, pulse=RECORD), {}),                             # fixed-base+no-slide+piecewise
    (isoslide.Scene(pi2=0.2, pi3=0.0, pulse=RECORD), {}),                             # fixed-base+coulomb+piecewise
]


def building_scene(name: str) -> isoslide.Scene:
    """A general building whose solve should carry the label ``name`` (built from its parts)."""
    parts = name.split("+")
    kw = {"pi2": 5.0 if "no-slide" in parts else 0.2, "pi3": 1.0, "pi4": 0.1, "pi8": 0.1}
    if "stribeck" in parts:
        kw.update(pi5=0.7, pi6=1e3)
    if "one-way" in parts:
        kw["pi8"] = 0.0
    if "piecewise" in parts:
        kw["pulse"] = RECORD
    if parts[0] == "bearing-stuck":        # a sliding bearing stronger than any demand
        kw.update(pi9=5.0)
    elif parts[0] == "bearing-elastic":    # a stiff, strong, over-damped bilinear bearing
        kw.update(pi4=2.0, pi9=1.0, pi10=0.01)
    elif parts[0] == "bilinear":
        kw.update(pi9=0.05, pi10=0.01)
    elif parts[0] == "sliding-bearing":
        kw.update(pi9=0.05)
    elif parts[0] == "fixed-base":
        kw.update(pi3=0.0)
    if "flexible" in parts:
        kw.update(pi11=0.5, pi12=0.2, pi13=0.05)
    if "roof" in parts:
        kw["floor"] = "roof"
    return isoslide.Scene(**kw)


PATHS += [(building_scene(name), {}) for name in BUILDING_LABELS]


def test_building_labels_name_their_scenes():
    """Each general-building label is the label of the scene built from its parts."""
    for name in BUILDING_LABELS:
        assert isoslide.solve(building_scene(name)).model == name


@pytest.fixture(scope="module")
def produced():
    return [isoslide.solve(sc, **kw).model for sc, kw in PATHS]


def test_every_listed_label_is_produced_by_some_solve(produced):
    assert sorted(produced) == sorted(MODEL_LABELS)


def test_labels_round_trip_through_a_dataset_flag_variable(produced, tmp_path):
    codes, attrs = datasets.encode_models(np.array(produced))
    ds = xr.Dataset({"model": (("scene",), codes, attrs)})
    path = tmp_path / "m.nc"
    datasets.write_netcdf(ds, path)
    back = datasets.decode_models(datasets.open_dataset(path)["model"])
    assert back.values.tolist() == produced


def test_solve_many_labels_are_listed():
    scenes = [sc for sc, kw in PATHS if not kw]
    batch = isoslide.solve_many(scenes)
    assert set(batch.model.tolist()) <= set(MODEL_LABELS)
    assert "no-slide" in batch.model.tolist() and "fixed-base+no-slide" in batch.model.tolist()


def test_label_rejects_an_unknown_friction_law():
    with pytest.raises(ValueError, match="friction = 'viscous'"):
        label(False, False, "viscous", False)
    assert set(PEER_LABELS) <= set(MODEL_LABELS)


def test_piecewise_then_building_labels_are_appended_after_the_older_codes():
    n = len(BUILDING_LABELS)
    assert MODEL_LABELS[-n:] == BUILDING_LABELS
    assert MODEL_LABELS[-n - len(PIECEWISE_LABELS):-n] == PIECEWISE_LABELS
    assert MODEL_LABELS.index("fixed-base+static-kinetic") == 12
    assert label(True, False, "coulomb", False, piecewise=True) == "fixed-base+coulomb+piecewise"
    with pytest.raises(ValueError, match="piecewise = True needs friction = 'coulomb'"):
        label(False, False, "stribeck", False, piecewise=True)
