"""A scene is assembled once into the system the kernels integrate (isoslide.engine.system)."""

from __future__ import annotations

import numpy as np
import pytest

from isoslide import Scene, solve
from isoslide.engine import building, planar, system
from isoslide.model.parts import building_of

FLEX = dict(pi2=0.1, pi3=2.0, pi4=0.05, pi8=0.01, pi9=0.05, pi11=0.6, pi12=0.2, pi13=0.02, storeys=3, floor="roof")
"""Three storeys on a friction pendulum, the contents on the roof."""
PLANAR = dict(pi2=0.2, pi3=2.0, pi4=0.1, pi8=0.2, pulse="ricker", pulse_y="antisymmetric_ricker", pi14=0.7)
"""A linear isolator under a Ricker pulse along x and an antisymmetric Ricker along y."""


def _counting(monkeypatch) -> dict:
    """Count the calls of the assembly's two costly steps."""
    calls = {"parameters": 0, "modal_data": 0}
    for name in calls:
        original = getattr(building, name)

        def counted(*args, _original=original, _name=name, **kwargs):
            calls[_name] += 1
            return _original(*args, **kwargs)

        monkeypatch.setattr(building, name, counted)
    return calls


def test_the_same_scene_and_model_give_the_same_system_and_another_model_another():
    sc = Scene(**FLEX)
    a = system.assemble(sc, pi8=sc.pi8, coulomb=True)
    assert system.assemble(sc, pi8=sc.pi8, coulomb=True) is a
    b = system.assemble(sc, pi8=0.0, coulomb=True)
    assert b is not a and b.P[building.bk.P_M] == 0.0 and a.P[building.bk.P_M] == sc.pi8
    assert system.assemble(sc, pi8=sc.pi8, coulomb=False) is not a
    assert system.assemble(sc, pi8=sc.pi8, coulomb=True, horizon=10.0).stop < a.stop


def test_a_system_holds_what_each_step_of_the_assembly_derives():
    sc = Scene(**FLEX)
    s = system.assemble(system.unassembled(sc), pi8=sc.pi8, coulomb=True)
    P = building.parameters(sc, pi8=sc.pi8, coulomb=True)
    assert np.array_equal(s.P, P)
    for got, want in zip(s.modal, building.modal_data(sc, P), strict=True):
        assert np.array_equal(got, want)
    assert np.array_equal(s.breakpoints, system.breakpoints(sc))
    assert (s.start, s.end) == sc.span
    assert s.stop == system.horizon_end(sc) == sc.span[1] + system.DEFAULT_HORIZON * sc.pi3
    assert s.budget == system.step_budget(sc)
    assert s.free_step == building.free_step(sc)


def test_an_unassembled_copy_equals_the_scene_and_is_assembled_anew():
    sc = Scene(**FLEX)
    a = system.assemble(sc)
    copy = system.unassembled(sc)
    assert copy == sc and copy is not sc
    b = system.assemble(copy)
    assert b is not a and np.array_equal(a.P, b.P)


def test_the_parts_of_a_scene_are_derived_once_per_model():
    sc = Scene(**FLEX, pi18=0.25, pi19=3.0, pi21=2.0, pi5=1.0)
    assert building_of(sc) is building_of(sc)
    sliding, rocking = building_of(sc, rocking=False), building_of(sc, rocking=True)
    assert sliding is not rocking and not sliding.contents.rocks and rocking.contents.rocks
    sup = building_of(sc).superstructure
    assert all(a is b for a, b in zip(sup.matrices(), sup.matrices(), strict=True))
    assert sup.shortest_period == pytest.approx(2.0 * np.pi / np.sqrt(np.max(np.linalg.eigvals(
        np.linalg.solve(np.diag(sup.matrices()[0]), sup.matrices()[1])).real)), rel=1e-12)


def test_a_building_solve_assembles_its_scene_once_and_a_second_solve_not_again(monkeypatch):
    """The tolerance loop's runs, the planner and the facets read one assembly; another rtol reuses it."""
    calls = _counting(monkeypatch)
    sc = Scene(**FLEX)
    first = solve(sc, rtol=1e-8)
    assert calls == {"parameters": 1, "modal_data": 1}
    again = solve(sc, rtol=1e-8)
    assert calls == {"parameters": 1, "modal_data": 1}
    assert again.pi1 == first.pi1 and again.n_steps == first.n_steps


def test_a_planar_solve_and_its_floor_motion_assemble_the_scene_once(monkeypatch):
    calls = _counting(monkeypatch)
    sc = Scene(**PLANAR)
    sol = solve(sc, history=True)
    motion = planar.floor_motion(sc, sol.history)
    assert calls == {"parameters": 1, "modal_data": 1}
    assert motion.shape == (sol.history.tau.size, 4) and np.isfinite(motion).all()


def test_an_assembled_scene_answers_as_a_new_one_bit_for_bit():
    """Reusing an assembly changes nothing: the kernels copy what they change (a triple pendulum's band)."""
    sc = Scene(pi2=0.1, pi3=2.0, pi4=0.05, pi8=0.01, pi9=0.05, pi24=0.1, pi25=0.5, pi26=0.5, pi27=1.5, pi28=0.05,
               pi29=0.3, pi30=0.3)
    first = solve(sc)
    second = solve(sc)
    fresh = solve(system.unassembled(sc))
    assert (first.pi1, first.n_steps, first.tau_end) == (second.pi1, second.n_steps, second.tau_end) \
        == (fresh.pi1, fresh.n_steps, fresh.tau_end)
    assert first.peak_stage > 0


def test_forgetting_what_scenes_share_derives_it_anew_with_the_same_bits():
    """After forget_shared a new scene on the same building decomposes its matrices again, and its
    modal data equal, bit for bit, those assembled while they were kept."""
    from isoslide.engine import free_phase

    sc = Scene(pi2=0.1, pi3=2.0, pi4=0.05, pi8=0.01, pi11=0.6, pi12=0.2, pi13=0.02, storeys=3, floor="roof")
    kept = system.assemble(system.unassembled(sc), pi8=sc.pi8, coulomb=True)
    assert free_phase._MODES
    system.forget_shared()
    assert not free_phase._MODES
    anew = system.assemble(system.unassembled(sc), pi8=sc.pi8, coulomb=True)
    for got, want in zip(anew.modal + anew.linear, kept.modal + kept.linear, strict=True):
        assert np.array_equal(got, want)
