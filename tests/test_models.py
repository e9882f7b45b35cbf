"""Model labels: every label a solve produces has a flag code, and every listed label is produced."""

import json
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import isoslide
from isoslide import datasets
from isoslide.models import BUILDING_LABELS, MODEL_LABELS, PEER_LABELS, PIECEWISE_LABELS, label
from isoslide.pulses import sampled

CODES_FILE = Path(__file__).parent / "data" / "model_codes.json"
"""Committed flag codes of the model labels; codes are append-only."""

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


def pinned_codes() -> dict:
    """The committed flag code of every label (``tests/data/model_codes.json``), never regenerated here."""
    return json.loads(CODES_FILE.read_text())["codes"]


def test_every_listed_label_is_produced_by_some_solve(produced):
    assert sorted(produced) == sorted(MODEL_LABELS)


def test_every_produced_label_has_a_flag_code(produced):
    """encode_models accepts every label a solve produced and maps it to its position in MODEL_LABELS."""
    codes, attrs = datasets.encode_models(np.array(produced))
    assert codes.tolist() == [MODEL_LABELS.index(name) for name in produced]
    assert attrs["flag_meanings"].split() == list(MODEL_LABELS)


def test_pinned_flag_codes_are_contiguous_from_zero():
    """The committed codes are 0, 1, ..., n - 1 with no gap or repeat (so the file itself is sound)."""
    pinned = pinned_codes()
    assert sorted(pinned.values()) == list(range(len(pinned)))


def test_flag_codes_are_append_only():
    """No committed label disappears or changes its code; new labels come after the committed ones."""
    pinned = pinned_codes()
    missing = sorted(set(pinned) - set(MODEL_LABELS))
    assert not missing, f"labels removed from MODEL_LABELS: {missing}"
    moved = {n: (c, MODEL_LABELS.index(n)) for n, c in pinned.items() if MODEL_LABELS.index(n) != c}
    assert not moved, f"labels whose flag code changed (committed, now): {moved}"
    codes, _ = datasets.encode_models(np.array(list(pinned)))
    assert codes.tolist() == list(pinned.values())


def test_every_label_has_a_pinned_flag_code():
    """Each label in MODEL_LABELS is in the committed code file (append a new label there on purpose)."""
    unpinned = [n for n in MODEL_LABELS if n not in pinned_codes()]
    assert not unpinned, f"labels without a committed flag code in {CODES_FILE.name}: {unpinned}"


def test_flag_codes_fit_the_int8_flag_variable():
    assert len(MODEL_LABELS) - 1 <= np.iinfo(np.int8).max
    codes, attrs = datasets.encode_models(np.array(MODEL_LABELS))
    assert codes.dtype == np.int8 and codes.tolist() == list(range(len(MODEL_LABELS)))
    assert attrs["flag_values"].tolist() == codes.tolist()


def test_labels_round_trip_through_a_dataset_flag_variable(produced, tmp_path):
    codes, attrs = datasets.encode_models(np.array(produced))
    ds = xr.Dataset({"model": (("scene",), codes, attrs)})
    path = tmp_path / "m.nc"
    datasets.write_netcdf(ds, path)
    back = datasets.decode_models(datasets.open_dataset(path)["model"])
    assert back.values.tolist() == produced


def test_solve_many_labels_match_the_single_solves(produced):
    """solve_many labels each scene as solve does, and every label it gives has a flag code.

    Scenes solve_many answers ``no-slide`` from the shared stuck demand alone may lack the
    ``+piecewise`` part the single solve adds, so that part is left out of the comparison.
    """
    plain = [i for i, (sc, kw) in enumerate(PATHS) if not kw]
    batch = isoslide.solve_many([PATHS[i][0] for i in plain]).model.tolist()
    datasets.encode_models(np.array(batch))
    assert not sorted(set(batch) - set(MODEL_LABELS))

    def paper_part(name):
        return name.removesuffix("+piecewise") if "no-slide" in name else name

    assert [paper_part(m) for m in batch] == [paper_part(produced[i]) for i in plain]


def test_peer_methods_carry_their_own_label(produced):
    """solve(..., method=m) is labelled m, for each peer label (and the peer paths cover them all)."""
    peers = [(kw["method"], produced[i]) for i, (sc, kw) in enumerate(PATHS) if "method" in kw]
    assert [m for m, _ in peers] == [name for _, name in peers]
    assert sorted(m for m, _ in peers) == sorted(PEER_LABELS)


def test_label_rejects_an_unknown_friction_law():
    with pytest.raises(ValueError, match="friction = 'viscous'"):
        label(False, False, "viscous", False)


def test_piecewise_label_needs_coulomb_friction():
    assert label(True, False, "coulomb", False, piecewise=True) == "fixed-base+coulomb+piecewise"
    assert all(name.endswith("+piecewise") for name in PIECEWISE_LABELS)
    with pytest.raises(ValueError, match="piecewise = True needs friction = 'coulomb'"):
        label(False, False, "stribeck", False, piecewise=True)
