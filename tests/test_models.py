"""The model that ran: its facets (pinned flag codes) and the display label derived from them.

Every label a solve produces is listed, every listed label is produced, and every facet value a
solve produces has a committed flag code.
"""

import json
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import isoslide
from isoslide import datasets
from isoslide.models import (BUILDING_LABELS, FACETS, MODEL_LABELS, PEER_LABELS, PIECEWISE_LABELS, PLANAR_LABELS,
                             ROCKING_LABELS, TFP_SPEED_LABELS, VERTICAL_LABELS, Facets, label)
from isoslide.pulses import sampled

CODES_FILE = Path(__file__).parent / "data" / "facet_codes.json"
"""Committed flag codes of the facets' values; codes are append-only."""

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
    elif parts[0] == "sliding-bearing-speed":
        kw.update(pi9=0.1, pi22=0.5, pi23=20.0)
    elif parts[0] in ("triple-friction-pendulum", "triple-friction-pendulum-speed"):
        kw.update(pi9=0.05, pi24=0.1, pi25=0.5, pi26=0.5, pi27=2.0, pi28=0.05, pi29=0.1, pi30=0.2)
        if parts[0].endswith("-speed"):
            kw.update(pi22=0.5, pi23=10.0)
    elif parts[0] == "fixed-base":
        kw.update(pi3=0.0)
    if "flexible" in parts:
        kw.update(pi11=0.5, pi12=0.2, pi13=0.05)
    if "roof" in parts:
        kw["floor"] = "roof"
    if "intermediate" in parts:
        kw.update(storeys=2, floor=1)
    if "vertical" in parts:
        kw.update(pi17=0.2, pulse_z="ricker")
    if "planar" in parts:
        kw.update(pulse_y="antisymmetric_ricker", pi14=0.8)
    if "rocking" in parts:   # a block that tips (mu_s = 1.001 tan(alpha) when it slides) and slide-rocks
        kw.update(pi2=5.0 if "no-slide" in parts else 0.25025, pi18=0.2, pi19=1.0, pi21=4.0)
    return isoslide.Scene(**kw)


PATHS += [(building_scene(name), {}) for name in BUILDING_LABELS + VERTICAL_LABELS + PLANAR_LABELS + ROCKING_LABELS]


def test_building_labels_name_their_scenes():
    """Each general-building label is the label of the scene built from its parts (vertical motion, the plane,
    a rocking block)."""
    for name in BUILDING_LABELS + VERTICAL_LABELS + PLANAR_LABELS + ROCKING_LABELS:
        assert isoslide.solve(building_scene(name)).model == name


@pytest.mark.slow
def test_speed_dependent_triple_pendulum_labels_name_their_scenes():
    """Each label of a triple pendulum whose friction rises with speed is the label of the scene built from its parts."""
    for name in TFP_SPEED_LABELS:
        assert isoslide.solve(building_scene(name)).model == name


@pytest.fixture(scope="module")
def solutions():
    return [isoslide.solve(sc, **kw) for sc, kw in PATHS]


@pytest.fixture(scope="module")
def produced(solutions):
    return [s.model for s in solutions]


def pinned_codes() -> dict:
    """The committed values of every facet (``tests/data/facet_codes.json``), never regenerated here."""
    return json.loads(CODES_FILE.read_text())["facets"]


def test_every_listed_label_is_produced_by_some_solve(produced):
    """Every label but a speed-dependent triple pendulum's (seconds per solve: the slow test above) comes from PATHS."""
    assert sorted(produced) == sorted(n for n in MODEL_LABELS if n not in TFP_SPEED_LABELS)


def test_the_label_is_derived_from_the_facets_and_whether_the_contents_slid(solutions):
    for s in solutions:
        assert s.model == s.facets.label(slid=s.pi1 > 0.0)


def test_facet_codes_are_append_only():
    """No committed value disappears or moves; new values come after the committed ones, in the file too."""
    pinned = pinned_codes()
    assert list(pinned) == list(FACETS), "facets added, removed or reordered"
    for name, values in pinned.items():
        assert list(FACETS[name][:len(values)]) == values, f"facet {name!r}: committed codes changed"
        assert len(FACETS[name]) == len(values), f"facet {name!r}: values without a committed code"


def test_every_facet_fits_a_small_flag_variable():
    assert all(1 <= len(values) <= 16 for values in FACETS.values())


def test_every_produced_facet_value_has_a_code_and_each_facet_varies(solutions):
    """The paths cover more than one value of each facet but ``reduction`` (set by solve_many and buildings)."""
    for name in FACETS:
        seen = {getattr(s.facets, name) for s in solutions}
        assert seen <= set(FACETS[name])
        if name != "reduction":
            assert len(seen) > 1, f"the paths exercise one value of {name!r} only"


def test_facets_refuse_an_unknown_value_naming_the_facet():
    with pytest.raises(ValueError, match="isolator = 'magnetic' is invalid"):
        Facets(isolator="magnetic")


def test_facets_round_trip_through_a_dataset(solutions, tmp_path):
    facets = np.empty(len(solutions), dtype=object)
    facets[:] = [s.facets for s in solutions]
    ds = xr.Dataset(datasets.encode_facets(facets, ("scene",)))
    ds["pi1"] = ("scene", np.array([s.pi1 for s in solutions]))
    path = tmp_path / "m.nc"
    datasets.write_netcdf(ds, path)
    back = datasets.open_dataset(path)
    assert datasets.decode_facets(back).tolist() == facets.tolist()
    assert datasets.model_labels(back).values.tolist() == [s.model for s in solutions]


def test_solve_many_labels_match_the_single_solves(produced):
    """solve_many labels each scene as solve does, and every label it gives is listed.

    Scenes solve_many answers ``no-slide`` from the shared stuck demand alone may lack the
    ``+piecewise`` part the single solve adds, so that part is left out of the comparison.
    """
    plain = [i for i, (sc, kw) in enumerate(PATHS) if not kw]
    result = isoslide.solve_many([PATHS[i][0] for i in plain])
    batch = result.model.tolist()
    assert not sorted(set(batch) - set(MODEL_LABELS))
    assert batch == [f.label(slid=p > 0.0) for f, p in zip(result.facets, result.pi1, strict=True)]

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
