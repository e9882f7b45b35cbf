"""The bench's side-by-side sections: OpenSees at the coarsest step within a tolerance, kernel targets' ratios."""
from __future__ import annotations

import io

import pytest

from isoslide import Scene
from isoslide.accuracy import kernel_targets, opensees_cost
from isoslide.peers import opensees_available

COARSE = ((4e-2, 1e-3), (2e-2, 1e-4), (1e-2, 1e-5))


@pytest.mark.skipif(not opensees_available(), reason="OpenSees not installed (pip install -e .[peers])")
def test_opensees_is_timed_at_the_coarsest_pair_within_the_tolerance_or_at_the_finest_when_none_reaches_it():
    """A loose tolerance stops at the coarsest pair; an unreachable one runs every pair and says so."""
    scene = Scene(pi2=0.2, pi3=2.0, pi4=0.1)
    loose = opensees_cost.compare(scene, pairs=COARSE, tolerance=1.0, horizon=2.0, repeats=1)
    assert (loose["dtau"], loose["reached"]) == (4e-2, True)
    assert loose["opensees_error"] <= 1.0 and loose["isoslide_error"] < 1e-5
    strict = opensees_cost.compare(scene, pairs=COARSE, tolerance=1e-14, horizon=2.0, repeats=1)
    assert (strict["dtau"], strict["stick"], strict["reached"]) == (1e-2, 1e-5, False)
    assert strict["opensees_error"] < loose["opensees_error"]
    assert strict["opensees_s"] > 0.0 and strict["opensees_steps"] > loose["opensees_steps"]


def test_kernel_target_report_gives_each_targets_median_ratio_to_host_tuned_and_the_largest_pi1_difference():
    """Per point the median over rounds; per class the median over points of target / host; dPi1 relative."""
    times = {"host": {"a": [[1.0, 3.0, 2.0], [4.0, 4.0, 4.0]]},
             "portable": {"a": [[2.0, 2.0, 2.0], [4.0, 6.0, 5.0]]},
             "x86-64-v3": {"a": [[1.0, 1.0, 1.0], [2.0, 2.0, 2.0]]}}
    pi1 = {"host": {"a": [1.0, 2.0]}, "portable": {"a": [1.0, 2.0]}, "x86-64-v3": {"a": [1.0, 2.0 * (1 + 1e-12)]}}
    info = {t: {"cpu": t, "features": "", "ready_s": 0.5} for t in kernel_targets.TARGETS}
    out = io.StringIO()
    summ = kernel_targets.report({"targets": info, "times": times, "pi1": pi1, "rounds": 3}, file=out)
    assert summ["a"]["portable_ratio"] == pytest.approx(1.125)   # median of 2/2 and 5/4
    assert summ["a"]["x86-64-v3_ratio"] == pytest.approx(0.5)
    assert summ["a"]["host_us"] == pytest.approx(3e6)            # median of the points' medians 2 and 4
    assert summ["a"]["pi1_rel_diff"] == pytest.approx(1e-12)
    assert "portable / host over the classes: median 1.125" in out.getvalue()


@pytest.mark.skipif(not opensees_available(), reason="OpenSees not installed (pip install -e .[peers])")
def test_a_triple_pendulum_runs_on_opensees_element_with_its_own_pairs():
    """The triple pendulum's class takes TFP_PAIRS (coarsest first) and OpenSees's TripleFrictionPendulum peer."""
    from isoslide.accuracy.scenes import BUILDING_POINTS, BUILDINGS, TFP_PENDULUM

    scene = Scene(**BUILDING_POINTS[2], **BUILDINGS[TFP_PENDULUM])
    row = opensees_cost.compare(scene, tolerance=1.0, horizon=2.0, repeats=1)
    assert (row["dtau"], row["stick"], row["reached"]) == (*opensees_cost.TFP_PAIRS[0], True)
    assert 0.0 < row["opensees_error"] < 0.2 and row["isoslide_error"] < 1e-5


def test_opensees_report_ends_with_the_triple_pendulums_aims():
    """Against OpenSees (a lower bound when the tolerance was not reached) and against the constant pendulum."""
    from isoslide.accuracy.scenes import PENDULUM, TFP_PENDULUM

    def row(iso_s, os_s, reached):
        return {"isoslide_s": iso_s, "opensees_s": os_s, "reached": reached, "dtau": 1e-3, "isoslide_error": 1e-9,
                "opensees_error": 5e-4 if reached else 2e-3}

    res = {PENDULUM: [row(1e-3, 4.0, True)] * 2, TFP_PENDULUM: [row(1.5e-3, 15.0, True), row(1.5e-3, 15.0, False)]}
    out = io.StringIO()
    summ = opensees_cost.report(res, file=out)
    text = out.getvalue()
    assert summ[TFP_PENDULUM]["ratio"] == pytest.approx(1e4) and not summ[TFP_PENDULUM]["reached"]
    assert summ[TFP_PENDULUM]["pendulum_ratio"] == pytest.approx(1.5)
    assert "at least 20x faster than OpenSees's TripleFrictionPendulum at 0.001 in Pi1 -> MET" in text
    assert "a lower bound: OpenSees did not reach the tolerance" in text
    assert f"at most 2x its cost on the constant-friction pendulum ({PENDULUM}) -> MET (ratio 1.50" in text


def test_the_compared_classes_add_the_planar_buildings_and_each_base_of_a_recorded_pair():
    """Every building at every point, then the planar classes OpenSees's planar model takes, then the pairs."""
    from isoslide.accuracy.scenes import BUILDINGS, PAIR_POINTS

    classes = opensees_cost.scenes_by_class(pairs=1)
    names = list(classes)
    assert names[:len(BUILDINGS)] == list(BUILDINGS)
    planar = [f"planar: {n}" for n in opensees_cost.PLANAR_CLASSES]
    pairs = [f"recorded pair, {b}" for b in PAIR_POINTS]
    assert names[len(BUILDINGS):] == planar + pairs
    for name in planar + pairs:
        assert all(sc.planar and sc.pi5 == 1.0 and sc.pi9 == 0.0 and sc.pi12 == 0.0 for sc in classes[name]), name
    assert len(classes[pairs[0]]) == 1 and classes[pairs[1]][0].pi3 == 0.0


@pytest.mark.skipif(not opensees_available(), reason="OpenSees not installed (pip install -e .[peers])")
def test_a_planar_scene_runs_on_opensees_planar_model_from_its_softest_stick():
    """The planar classes take their stick stiffnesses coarsest first, each with the planar model's own step."""
    from isoslide.accuracy.scenes import BUILDING_POINTS, PLANAR_EXCITATION

    scene = Scene(**{**BUILDING_POINTS[2], "pi3": 0.0}, **PLANAR_EXCITATION)
    pairs = opensees_cost.planar_pairs(scene)
    assert [k for _, k in pairs] == list(opensees_cost.PLANAR_STIFFNESSES)
    assert all(a >= b for (a, _), (b, _) in zip(pairs, pairs[1:], strict=False))
    row = opensees_cost.compare(scene, tolerance=1.0, horizon=2.0, repeats=1)
    assert (row["dtau"], row["stick"], row["reached"]) == (*pairs[0], True)
    strict = opensees_cost.compare(scene, pairs=pairs[:2], tolerance=1e-14, horizon=2.0, repeats=1)
    assert strict["stick"] == pairs[1][1] and strict["opensees_error"] < row["opensees_error"]


def test_the_buildings_section_splits_each_class_into_steps_cost_per_step_and_assembly():
    """Each class's ratio to the paper model is its steps ratio times its cost per step; the assembly's
    share is its time over the class's cost; the aims are the bench's constants."""
    from isoslide import bench
    from isoslide.accuracy.scenes import BUILDINGS, STOREYS_NAME

    points = 2
    rows = {}
    for k, name in enumerate(BUILDINGS):
        us = 100.0 * (k + 1)
        rows[name] = {"times": [[us * 1e-6] * 3 for _ in range(points)], "pi1": [1.0] * points,
                      "conv": [1.0] * points, "models": ["m"] * points, "steps": [10 * (k + 1)] * points,
                      "period": 1.0, "assembly_us": 0.0 if k == 0 else 25.0 * (k + 1),
                      "assembly_cold_us": 0.0 if k == 0 else 40.0 * (k + 1)}
    out = io.StringIO()
    summ = bench.report_buildings({"rows": rows, "points": [{}] * points, "repeats": 3}, file=out)
    text = out.getvalue()
    name = list(BUILDINGS)[2]
    assert summ[name]["ratio"] == pytest.approx(3.0) and summ[name]["steps_ratio"] == pytest.approx(3.0)
    assert summ[name]["step_cost_ratio"] == pytest.approx(1.0) and summ[name]["assembly_share"] == pytest.approx(0.25)
    assert f"at most {bench.TARGET_BUILDING_RATIO:g}x the paper model's cost" in text
    assert f"aim: {bench.TARGET_STOREYS} storeys at most {bench.TARGET_STOREYS_RATIO:g}x" in text
    assert STOREYS_NAME.format(bench.TARGET_STOREYS) in summ and "assembly     75 us ( 25 %),    120 us anew" in text
