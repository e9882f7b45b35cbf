"""The parts of a building (isoslide.model.parts): what each reads, and the building they compose."""

import math

import numpy as np
import pytest

from isoslide import Scene
from isoslide.engine import building
from isoslide.model.parts import Isolator, building_of

BASE = dict(pi2=0.15, pi3=2.0, pi4=0.1, pi8=0.01)


@pytest.mark.parametrize("kw, kind", [({}, "linear"), (dict(pi9=0.05), "sliding"),
                                      (dict(pi9=0.05, pi10=0.01), "bilinear"), (dict(pi3=0.0), "fixed"),
                                      (dict(pi3=0.0, pi9=0.05), "fixed")])
def test_the_isolator_kind_follows_the_scene(kw, kind):
    assert building_of(Scene(**{**BASE, **kw})).isolator.kind == kind


@pytest.mark.parametrize("kw, unread, unchanged", [
    (dict(pi3=0.0), dict(pi4=0.3, pi9=0.2), ("isolator", "superstructure", "contents")),   # fixed: reads nothing
    ({}, dict(pi10=0.02), ("isolator", "superstructure", "contents")),      # linear isolator: Pi3, Pi4 only
    (dict(pi9=0.05), dict(pi11=0.3, pi13=0.1), ("isolator", "superstructure", "contents")),  # rigid: nothing
    (dict(pi11=0.5, pi12=0.2), dict(floor="roof"), ("isolator", "superstructure")),  # the floor is the contents'
])
def test_each_part_reads_only_its_groups(kw, unread, unchanged):
    """Changing a group a part does not read leaves that part as it was."""
    a = building_of(Scene(**{**BASE, **kw}))
    b = building_of(Scene(**{**BASE, **kw, **unread}))
    for part in unchanged:
        assert getattr(a, part) == getattr(b, part), part
    assert a != b or len(unchanged) == 3


def test_contents_stand_on_the_slab_of_a_rigid_superstructure_whatever_the_floor():
    rigid = building_of(Scene(**BASE, pi9=0.05, storeys=3, floor="roof"))
    assert rigid.contents.floor == 0 and not rigid.superstructure.flexible
    flexible = building_of(Scene(**BASE, pi11=0.5, pi12=0.2, storeys=3, floor=2))
    assert flexible.contents.floor == 2 and flexible.superstructure.flexible


def test_the_assembled_array_holds_the_parts():
    """The kernel's parameters are the parts' values (bilinear bearing under three storeys)."""
    sc = Scene(**BASE, pi9=0.08, pi10=0.01, pi11=0.6, pi12=0.3, pi13=0.05, pi5=0.7, pi6=300.0, storeys=3, floor=1)
    parts = building_of(sc)
    P = building.parameters(sc)
    bk = building.bk
    w = 2.0 * math.pi / sc.pi3
    assert P[bk.P_KD] == w * w and P[bk.P_CB] == 2.0 * sc.pi4 * w
    assert P[bk.P_Q] == sc.pi9 and P[bk.P_KE] == sc.pi9 / sc.pi10 and P[bk.P_THR] == sc.pi2 / sc.pi5
    assert P[bk.P_N] == 3 and P[bk.P_FLOOR] == 1 and P[bk.P_MB] == pytest.approx(0.4)
    masses, Ks, Cs = parts.superstructure.matrices()
    assert np.array_equal(P[bk.P_ARRAYS:bk.P_ARRAYS + 3], masses)
    assert np.array_equal(P[bk.P_ARRAYS + 3:bk.P_ARRAYS + 12].reshape(3, 3), Ks)
    assert np.array_equal(P[bk.P_ARRAYS + 12:].reshape(3, 3), Cs)


def test_a_bilinear_bearing_follows_its_elastic_period():
    iso = Isolator("bilinear", period=2.0, damping=0.1, strength=0.08, yield_displacement=0.01)
    assert iso.shortest_period == pytest.approx(2.0 * math.sqrt(iso.stiffness / (iso.stiffness + 8.0)))
    assert Isolator("sliding", period=2.0, strength=0.05).shortest_period == 2.0


def test_an_unknown_isolator_kind_is_refused_naming_it():
    with pytest.raises(ValueError, match="kind = 'magnetic' is invalid"):
        Isolator("magnetic")


def test_scenes_that_share_a_superstructure_share_its_read_only_matrices():
    """Two scenes with the same shear building (other groups differing) get the same matrices, which
    cannot be written, and the fundamental fixed-base period of the scaled stiffness is Pi12."""
    kw = dict(pi11=0.6, pi12=0.3, pi13=0.02, storeys=4, storey_stiffnesses=(4.0, 3.0, 2.0, 1.0))
    a = building_of(Scene(**BASE, **kw)).superstructure
    b = building_of(Scene(**{**BASE, "pi2": 0.3, "pi3": 3.0}, **kw)).superstructure
    masses, Ks, Cs = a.matrices()
    assert all(x is y for x, y in zip(a.matrices(), b.matrices(), strict=True))
    assert not any(x.flags.writeable for x in (masses, Ks, Cs))
    w2 = np.linalg.eigvals(np.linalg.solve(np.diag(masses), Ks)).real
    assert 2.0 * math.pi / math.sqrt(w2.min()) == pytest.approx(0.3, rel=1e-12)
