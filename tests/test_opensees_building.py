"""OpenSees as an independent peer of the general building (bearings, flexible superstructure, floors).

The OpenSees model regularises every stick by an elastic-plastic spring with a small yield
displacement (the stick displacement) and steps with a fixed Newmark step, so it approaches the
exact answer only as both shrink; these tests check that it does, scene class by scene class.
"""

import math

import numpy as np
import pytest

import isoslide
from isoslide.studies import opensees_convergence as oc
from isoslide.peers import opensees_available, solve_opensees
from isoslide.peers.opensees import opensees_model

pytestmark = pytest.mark.skipif(not opensees_available(),
                                reason="openseespy does not import (pip install -e .[peers])")

S = isoslide.Scene
HORIZON = 10.0
SCENES = {
    "paper": S(pi2=0.2, pi3=1.0, pi4=0.1, pi8=0.2),
    "friction pendulum": S(pi2=0.2, pi3=2.0, pi9=0.05),
    "lead-rubber": S(pi2=0.2, pi3=2.0, pi4=0.05, pi9=0.05, pi10=0.005),
    "friction pendulum, flexible, roof": S(pi2=0.2, pi3=2.0, pi9=0.05, pi11=0.5, pi12=0.3, pi13=0.02,
                                           floor="roof", pi8=0.05),
    "lead-rubber, flexible, roof": S(pi2=0.2, pi3=2.0, pi4=0.05, pi9=0.05, pi10=0.005, pi11=0.5, pi12=0.3,
                                     pi13=0.02, floor="roof"),
    "linear, flexible, base": S(pi2=0.2, pi3=2.0, pi4=0.05, pi11=0.5, pi12=0.3, pi13=0.02, pi8=0.05),
    "fixed base, flexible, roof": S(pi2=0.3, pi3=0.0, pi11=0.5, pi12=0.5, pi13=0.05, floor="roof"),
}
FINE = {"dtau": 3e-4, "stick_displacement": 1e-7}
"""A step and stick displacement at which every scene above is within 0.3 % (measured 5e-5 .. 2.6e-3)."""


def _tau_max(sc):
    return sc.pulse.tau_end + HORIZON


def _peak(a):
    return float(np.max(np.abs(a)))


@pytest.mark.parametrize("name", list(SCENES))
def test_every_building_class_agrees_with_the_exact_solver_and_the_reference_peer(name):
    """Pi1 against isoslide.solve; slab and superstructure peaks against the reference peer's history."""
    sc = SCENES[name]
    exact = isoslide.solve(sc, rtol=1e-9, horizon=HORIZON).pi1
    ref = isoslide.solve(sc, method="reference", tau_max=_tau_max(sc), history=True).history
    r = solve_opensees(sc, tau_max=_tau_max(sc), history=True, **FINE)
    assert r.method == "opensees" and r.integrator == "Newmark"
    assert abs(r.pi1 - exact) / exact < 5e-3
    h = r.history
    assert (h.xs is not None) == sc.flexible
    assert (h.fh is not None) == (sc.pi9 > 0.0 and not sc.fixed_base)
    if not sc.fixed_base:
        assert abs(_peak(h.x) / _peak(ref.x) - 1.0) < 1e-3
    else:
        assert np.all(h.x == 0.0)
    if sc.flexible:
        assert abs(_peak(h.xs) / _peak(ref.xs) - 1.0) < 5e-3


def test_a_coarse_regularisation_is_measurably_wrong():
    """The tolerance above means something: at dtau = 1e-2, stick 1e-4 the friction pendulum is 8 % off."""
    sc = SCENES["friction pendulum"]
    exact = isoslide.solve(sc, rtol=1e-9, horizon=HORIZON).pi1
    r = solve_opensees(sc, tau_max=_tau_max(sc), dtau=1e-2, stick_displacement=1e-4)
    assert abs(r.pi1 - exact) / exact > 5e-2


def test_error_shrinks_as_the_step_and_the_stick_displacement_shrink():
    """Friction pendulum over the default pairs: each error smaller than the last, the finest under 3e-4."""
    conv = oc.opensees_convergence(SCENES["friction pendulum"])
    assert conv.target == "exact" and len(conv.rows) == len(oc.DEFAULT_PAIRS)
    errs = [r.rel_error for r in conv.rows]
    assert all(b < a for a, b in zip(errs, errs[1:], strict=False)), errs
    assert errs[0] > 3e-2 and errs[-1] < 3e-4
    assert [(r.dtau, r.stick_displacement) for r in conv.rows] == list(oc.DEFAULT_PAIRS)
    assert all(r.n_steps == math.ceil((conv.tau_max - conv.scene.pulse.tau_start) / r.dtau) for r in conv.rows)
    text = oc.format_table(conv)
    assert text.startswith("target: exact") and len(text.splitlines()) == 2 + len(conv.rows)


def test_the_comparison_target_is_a_parameter():
    """A number, the exact solver and the reference peer give the same errors; 'opensees' refines the finest pair."""
    sc = SCENES["lead-rubber"]
    pairs = ((1e-2, 1e-4), (3e-3, 1e-5))
    exact = oc.opensees_convergence(sc, pairs, "exact")
    given = oc.opensees_convergence(sc, pairs, exact.target_pi1)
    assert given.target == "given" and given.target_pi1 == exact.target_pi1
    assert [r.rel_error for r in given.rows] == [r.rel_error for r in exact.rows]
    label, ref = oc.target_pi1(sc, "reference", exact.tau_max)
    assert label == "reference" and ref == pytest.approx(exact.target_pi1, rel=1e-8)
    label, finer = oc.target_pi1(sc, "opensees", exact.tau_max, pairs)
    direct = solve_opensees(sc, tau_max=exact.tau_max, dtau=3e-3 / oc.FINER,
                            stick_displacement=1e-5 / oc.FINER).pi1
    assert label == "opensees" and finer == direct


@pytest.mark.parametrize("name", [n for n in SCENES if SCENES[n].flexible])
def test_one_storey_building_is_the_single_superstructure_mass(name):
    """storeys = 1 (the default) is one mass on one spring-dashpot: explicit or not, the same run."""
    sc = SCENES[name]
    one = S(**{**sc.pis(), "floor": sc.floor, "storeys": 1, "floor_masses": (2.0,), "storey_stiffnesses": (3.0,)})
    assert opensees_model(one, stick_displacement=1e-6) == opensees_model(sc, stick_displacement=1e-6)
    a = solve_opensees(sc, tau_max=4.0, dtau=1e-3, stick_displacement=1e-6, history=True)
    b = solve_opensees(one, tau_max=4.0, dtau=1e-3, stick_displacement=1e-6, history=True)
    assert a.pi1 == b.pi1 and np.array_equal(a.history.xs, b.history.xs) and a.history.xs.ndim == 1


def test_the_auto_target_of_a_one_storey_scene_is_the_exact_solver():
    sc = SCENES["lead-rubber"]
    tau_max = _tau_max(sc)
    assert oc.target_pi1(sc, "auto", tau_max) == oc.target_pi1(sc, "exact", tau_max)


def test_roof_of_a_rigid_superstructure_is_the_base():
    a = solve_opensees(SCENES["friction pendulum"], tau_max=6.0, stiffness=1e5)
    b = solve_opensees(S(pi2=0.2, pi3=2.0, pi9=0.05, floor="roof"), tau_max=6.0, stiffness=1e5)
    assert a.pi1 == b.pi1


def test_stiffness_and_stick_displacement_are_the_same_regularisation():
    """K = (Pi2/Pi5) / stick displacement: the paper's model runs bit for bit the same either way."""
    sc = SCENES["paper"]
    a = solve_opensees(sc, tau_max=6.0, stiffness=1e5)
    b = solve_opensees(sc, tau_max=6.0, stick_displacement=sc.static_level / 1e5)
    assert a.pi1 == b.pi1 and a.n_steps == b.n_steps and b.stiffness == pytest.approx(1e5, rel=1e-12)


def test_an_unbreakable_sliding_bearing_is_the_fixed_base():
    """A bearing whose strength the demand never reaches holds the slab at its stick displacement."""
    strong = solve_opensees(S(pi2=0.2, pi3=2.0, pi9=5.0), tau_max=6.0, dtau=1e-3, stick_displacement=1e-7)
    fixed = solve_opensees(S(pi2=0.2, pi3=0.0), tau_max=6.0, dtau=1e-3, stick_displacement=1e-7)
    assert strong.pi1 == pytest.approx(fixed.pi1, rel=1e-4)


def test_bearing_histories_respect_their_strength_and_stick():
    """|fh| <= Q; a stuck sliding bearing's slab barely moves; a sliding one carries fh = +-Q."""
    fp = SCENES["friction pendulum"]
    h = solve_opensees(fp, tau_max=_tau_max(fp), history=True, **FINE).history
    q = fp.pi9
    assert _peak(h.fh) <= q * (1 + 1e-12)
    stuck, sliding = h.iso_phase == 0, h.iso_phase != 0
    assert stuck.any() and sliding.any() and set(np.unique(h.iso_phase)) == {-1, 0, 1}
    assert _peak(h.xd[stuck]) < 1e-2 * _peak(h.xd)
    assert np.allclose(h.fh[sliding], q * h.iso_phase[sliding], rtol=1e-9, atol=0.0)
    assert np.all(np.sign(h.xd[sliding]) == h.iso_phase[sliding])
    lrb = SCENES["lead-rubber"]
    h = solve_opensees(lrb, tau_max=_tau_max(lrb), history=True, **FINE).history
    assert _peak(h.fh) <= lrb.pi9 * (1 + 1e-12) and (h.iso_phase != 0).any()


def test_model_parameters_follow_the_building_equations():
    sc = SCENES["lead-rubber, flexible, roof"]
    M = opensees_model(sc, stick_displacement=1e-6)
    w, ws = 2 * math.pi / sc.pi3, 2 * math.pi / sc.pi12
    assert (M.mb, M.mst, M.m) == (0.5, 0.5, sc.pi8)
    assert M.kd == pytest.approx(w * w) and M.cb == pytest.approx(2 * sc.pi4 * w)
    assert (M.q, M.d_iso) == (sc.pi9, sc.pi10)
    assert M.ks == pytest.approx(0.5 * ws * ws) and M.cs == pytest.approx(2 * sc.pi13 * ws * 0.5)
    assert M.roof and M.flexible and not M.fixed and M.d_block == 1e-6
    assert (M.storeys, M.floor, M.masses) == (1, 1, (0.5,)) and M.links() == [(0, 1, M.ks, M.cs)]
    fp = opensees_model(SCENES["friction pendulum"], stick_displacement=2e-6)
    assert fp.d_iso == 2e-6 and not fp.roof and fp.mst == 0.0


@pytest.mark.parametrize("kwargs, name", [({"stick_displacement": 0.0}, "stick_displacement"),
                                          ({"stiffness": -1.0}, "stiffness"),
                                          ({"dtau": float("nan")}, "dtau")])
def test_bad_regularisation_is_refused_naming_the_parameter(kwargs, name):
    with pytest.raises(ValueError, match=name):
        solve_opensees(SCENES["friction pendulum"], tau_max=3.0, **kwargs)


def test_bad_convergence_input_is_refused():
    sc = SCENES["friction pendulum"]
    with pytest.raises(ValueError, match="Coulomb"):
        solve_opensees(S(pi2=0.2, pi3=2.0, pi9=0.05, pi5=0.5, pi6=10.0))
    with pytest.raises(ValueError, match="target"):
        oc.opensees_convergence(sc, ((1e-2, 1e-4),), target="nonsense")
    with pytest.raises(ValueError, match="stick_displacement"):
        oc.opensees_convergence(sc, ((1e-2, 0.0),))
    with pytest.raises(ValueError, match="pairs"):
        oc.opensees_convergence(sc, ())
    with pytest.raises(ValueError, match="horizon"):
        oc.opensees_convergence(sc, ((1e-2, 1e-4),), horizon=0.0)


def test_command_line_prints_the_table(capsys):
    assert oc.main(["--scene", "pi2=0.2", "pi3=2.0", "pi9=0.05", "floor=roof", "--target", "0.1"]) == 0
    out = capsys.readouterr().out
    assert "target: given, Pi1 = 0.1" in out and "floor='roof'" in out
    assert len([ln for ln in out.splitlines() if ln.strip().startswith("1.0e-02")]) == 1


@pytest.mark.slow
@pytest.mark.parametrize("name", list(SCENES))
def test_every_building_class_converges_to_the_reference_peer(name):
    """Default pairs against the event-driven reference: each error smaller than the last, the finest
    within 1e-3 and 30x below the coarsest (measured 5e-4 .. 2e-6 finest, 4e-2 .. 1e-1 coarsest)."""
    conv = oc.opensees_convergence(SCENES[name], target="reference")
    errs = [r.rel_error for r in conv.rows]
    assert all(b < a for a, b in zip(errs, errs[1:], strict=False)), errs
    assert errs[-1] < 1e-3 and errs[-1] < errs[0] / 30, errs
