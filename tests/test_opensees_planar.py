"""OpenSees as an independent peer of planar sliding (a 3-D flatSliderBearing with a circular yield surface).

The peer regularises the contents' stick by the element's elastic range (stiffness ``K m``) and
steps with a fixed step tied to the stick's period, so it approaches the exact answer only as ``K``
grows; these tests check that it does, that along one line it is the 1-D OpenSees peer, that the
circular friction surface makes it indifferent to the excitation's direction, and what it refuses.
"""

import math
import subprocess
import sys

import pytest

import isoslide
from isoslide.peers import opensees_available, solve_opensees
from isoslide.peers.opensees_planar import ground_window, planar_model, solve_opensees_planar
from isoslide.studies import opensees_planar_convergence as opc

needs_opensees = pytest.mark.skipif(not opensees_available(),
                                    reason="openseespy does not import (pip install -e .[peers])")

S = isoslide.Scene
LINE = S(pi2=0.2, pi3=0.0)
"""A Ricker along the building's x axis on a fixed base (the 1-D model)."""
PLANAR_FIXED = S(pi2=0.3, pi3=0.0, pulse="ricker", pulse_y="ricker", pi14=0.7, pi16=0.4)
PLANAR_TURNING = S(pi2=0.2, pi3=0.0, pulse="ricker", pulse_y="antisymmetric_ricker", pi14=0.8)
PLANAR_BASE = S(pi2=0.2, pi3=2.5, pi4=0.1, pi8=0.5, pulse="ricker", pulse_y="antisymmetric_ricker", pi14=0.8)


def _target(scene):
    """``(Pi1, peak_angle)`` of isoslide's exact solver, or of the planar reference peer."""
    _, pi1, angle = opc.target_of(scene, "auto")
    return pi1, angle


def _errors(scene, stiffnesses, **kw):
    pi1, angle = _target(scene)
    out = []
    for k in stiffnesses:
        r = solve_opensees_planar(scene, k, **kw)
        out.append((abs(r.pi1 - pi1) / pi1, abs(opc.angle_error(r.peak_angle, angle))))
    return out


@needs_opensees
def test_along_a_line_it_is_the_one_dimensional_peer_and_approaches_the_exact_answer():
    exact = isoslide.solve(LINE)
    for k in (1e3, 1e4, 1e5):
        r = solve_opensees_planar(LINE, k)
        one = solve_opensees(LINE, k)
        assert r.method == "opensees" and r.integrator == "Newmark" and r.stiffness == k
        assert r.pi1 == pytest.approx(one.pi1, rel=0.02)
        assert r.peak_angle == pytest.approx(math.pi)          # the contents slide towards -x first
        # reversing without stopping: the regularisation error falls like sqrt(stick displacement)
        assert abs(r.pi1 - exact.pi1) / exact.pi1 < 10.0 * math.sqrt(LINE.pi2 / k)
        assert r.settled and r.tau_end < LINE.pulse.tau_end + 1.0


@needs_opensees
def test_the_circular_surface_turns_the_answer_with_the_excitation():
    base = solve_opensees_planar(LINE, 1e4)
    turned = solve_opensees_planar(S(pi2=0.2, pi3=0.0, angle=0.6), 1e4)
    assert turned.pi1 == pytest.approx(base.pi1, rel=1e-3)
    assert opc.angle_error(turned.peak_angle, base.peak_angle + 0.6) == pytest.approx(0.0, abs=1e-3)
    assert turned.tau_peak == pytest.approx(base.tau_peak, abs=2e-3)


@needs_opensees
def test_a_planar_scene_on_a_fixed_base_converges_as_the_stick_stiffens():
    errors = _errors(PLANAR_FIXED, (1e3, 1e4, 1e5))
    rel, ang = zip(*errors, strict=True)
    assert rel[0] > rel[1] > rel[2] and rel[2] < 0.01
    assert ang[0] > ang[1] > ang[2] and ang[2] < 1e-3


@needs_opensees
def test_generalized_alpha_removes_the_lag_of_the_friction_direction():
    """Newmark's error on a turning slide is of order dt; balanced at midstep, only 1/K is left."""
    (newmark, _), = _errors(PLANAR_TURNING, (1e5,))
    (alpha, _), = _errors(PLANAR_TURNING, (1e5,), integrator="GeneralizedAlpha")
    assert alpha < 5e-5 < newmark
    (finer, _), = _errors(PLANAR_TURNING, (1e5,), dt=1e-4)
    assert finer < newmark                                      # the Newmark error falls with the step


@needs_opensees
def test_contents_on_a_linear_base_act_back_and_converge():
    errors = _errors(PLANAR_BASE, (1e4, 1e5))
    assert errors[0][0] > errors[1][0] and errors[1][0] < 0.01
    assert errors[0][1] > errors[1][1]
    light = solve_opensees_planar(S(pi2=0.2, pi3=2.5, pi4=0.1, pi8=1e-5, pulse="ricker",
                                    pulse_y="antisymmetric_ricker", pi14=0.8), 1e5)
    heavy = solve_opensees_planar(PLANAR_BASE, 1e5)
    assert abs(light.pi1 - heavy.pi1) > 0.05 * heavy.pi1      # the two-way coupling matters


@needs_opensees
def test_vertical_ground_motion_changes_the_normal_force():
    sc = S(pi2=0.2, pi3=0.0, pi17=0.3, pulse_z="ricker")
    exact = isoslide.solve(sc).pi1
    r = solve_opensees_planar(sc, 1e5)
    assert abs(r.pi1 - exact) / exact < 0.03
    assert abs(r.pi1 - solve_opensees_planar(LINE, 1e5).pi1) > 0.1 * exact


@needs_opensees
def test_an_end_time_runs_exactly_there():
    t0 = ground_window(LINE)[0]
    r = solve_opensees_planar(LINE, 1e3, dt=2e-3, t_end=0.0)
    assert r.n_steps == round((0.0 - t0) / 2e-3) and not r.settled
    assert r.tau_end == pytest.approx(0.0)


@needs_opensees
def test_the_convergence_table_has_a_row_per_scene_and_stiffness():
    rows = opc.convergence_table({"line": LINE}, stiffnesses=(1e3, 1e4))
    assert [r["stiffness"] for r in rows] == [1e3, 1e4]
    assert rows[0]["target"] == "exact"
    assert abs(rows[1]["rel_error"]) < abs(rows[0]["rel_error"])
    assert rows[0]["dt"] == pytest.approx(1e-3)
    text = opc.format_table(rows)
    assert "line" in text and "rel. error" in text and len(text.splitlines()) == 5


@pytest.mark.parametrize("fields, name", [
    ({"pi5": 0.5, "pi6": 1.0}, "pi5"),
    ({"pi7": 0.1}, "pi7"),
    ({"pi3": 2.0, "pi9": 0.05}, "pi9"),
    ({"pi11": 0.5, "pi12": 0.3}, "pi12"),
])
def test_scenes_it_does_not_model_are_refused_naming_the_group(fields, name):
    sc = S(**{"pi2": 0.2, "pi3": 0.0, **fields})
    with pytest.raises(ValueError, match=rf"^{name} = .*allowed: "):
        solve_opensees_planar(sc)


@pytest.mark.parametrize("kw, name", [
    ({"stiffness": 0.0}, "stiffness"), ({"stiffness": -1e4}, "stiffness"), ({"stiffness": math.nan}, "stiffness"),
    ({"dt": 0.0}, "dt"), ({"dt": math.inf}, "dt"), ({"t_end": -5.0}, "t_end"),
    ({"integrator": "Euler"}, "integrator"),
])
def test_bad_arguments_are_refused_naming_them(kw, name):
    with pytest.raises(ValueError, match=rf"^{name} = .*allowed"):
        solve_opensees_planar(LINE, **kw)


def test_bad_table_arguments_are_refused():
    with pytest.raises(ValueError, match="stiffness"):
        opc.convergence_table({"line": LINE}, stiffnesses=(0.0,))
    with pytest.raises(ValueError, match="target"):
        opc.target_of(LINE, "finest")


def test_the_model_in_dimensionless_units():
    M = planar_model(PLANAR_BASE, 1e4)
    assert M.m == 0.5 and M.k_init == 0.5e4 and M.mu * M.gravity == pytest.approx(0.2)
    assert M.kb == pytest.approx((2.0 * math.pi / 2.5) ** 2) and M.cb == pytest.approx(0.2 * 2.0 * math.pi / 2.5)
    assert M.stick_displacement == pytest.approx(0.2 / 1e4)
    assert M.stick_period == pytest.approx(2.0 * math.pi / math.sqrt(1.5e4))
    physical = S.from_physical(a_p=3.0, T_p=1.0, M_b=1e5, T_b=0.0, xi_b=0.0, m_ec=10.0, mu_s=0.4, mu_k=0.4)
    assert planar_model(physical).mu == pytest.approx(0.4)


def test_the_table_module_imports_without_openseespy():
    code = ("import sys; sys.modules['openseespy'] = None; sys.modules['openseespylinux'] = None\n"
            "import isoslide.studies.opensees_planar_convergence as m\n"
            "from isoslide.peers.opensees import opensees_available\n"
            "assert not opensees_available() and m.SCENES\n")
    subprocess.run([sys.executable, "-c", code], check=True, timeout=120)
