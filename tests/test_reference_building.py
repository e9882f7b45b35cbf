"""Tests of the general building's SciPy reference peer (isoslide.peers.reference_building).

Physics checks: the paper's model recovered by equivalent general forms, the rigid-plastic
oscillator's closed form, the energy balance, mirror symmetry and the settlement bound; and the
agreement of this peer with the compiled solver, written independently.
"""

import math

import numpy as np
import pytest

import isoslide
from isoslide import Scene
from isoslide.peers.reference import solve_reference
from isoslide.peers.reference_building import run_building, solve_reference_building
from isoslide.pulses import sampled

PAPER = dict(pi2=0.2, pi3=2.0, pi4=0.1, pi8=0.1)
STRIBECK = dict(pi2=0.15, pi3=1.5, pi4=0.05, pi5=0.7, pi6=80.0, pi7=0.05, pi8=0.3)


def paper_pi1(**kw) -> float:
    """Pi1 of a paper scene from the compiled solver, tightly converged."""
    return isoslide.solve(Scene(**kw), rtol=1e-10).pi1


@pytest.mark.parametrize("kw", [PAPER, STRIBECK, dict(PAPER, pulse="makris_b")], ids=["coulomb", "stribeck", "makris_b"])
def test_contents_on_the_roof_of_a_rigid_superstructure_are_on_the_base(kw):
    """With ``Pi12 = 0`` the roof is the slab: floor="roof" gives the paper model's Pi1."""
    ref = paper_pi1(**kw)
    assert ref > 0.01
    roof = solve_reference_building(Scene(**kw, floor="roof"))
    assert roof.settled
    assert roof.pi1 == pytest.approx(ref, rel=1e-6)


@pytest.mark.parametrize("pi10", [1e-3, 0.0], ids=["bilinear", "sliding"])
def test_a_vanishing_isolator_strength_gives_the_linear_isolator(pi10):
    """A bilinear or sliding bearing of strength ``Pi9 = 1e-9`` adds a force 1e-9 to the linear one."""
    kw = dict(STRIBECK)
    res = solve_reference_building(Scene(**kw, pi9=1e-9, pi10=pi10))
    assert res.pi1 == pytest.approx(paper_pi1(**kw), rel=1e-6)


@pytest.mark.parametrize("kw", [PAPER, STRIBECK], ids=["coulomb", "stribeck"])
def test_a_sliding_bearing_stronger_than_any_demand_is_a_fixed_base(kw):
    """``Pi9 > 1 + Pi8 Pi2/Pi5`` (the largest force the held slab can need, ``phi <= Pi2/Pi5``
    here): the bearing never slides, the answer is the fixed base's ``Scene(pi3=0)``."""
    thr = kw["pi2"] / kw.get("pi5", 1.0)
    sc = Scene(**kw, pi9=1.01 * (1.0 + kw["pi8"] * thr), pi10=0.0)
    run = run_building(sc, history=True)
    assert np.all(run.result.history.x == 0.0) and np.all(run.result.history.iso_phase == 0)
    fixed = dict(kw, pi3=0.0)
    assert run.result.pi1 == pytest.approx(paper_pi1(**fixed), rel=1e-6)


@pytest.mark.parametrize("pi9", [0.05, 0.2, 0.5])
def test_sliding_bearing_with_stuck_contents_under_the_rectangular_pulse_has_the_rigid_plastic_closed_form(pi9):
    """A sliding bearing under ``p = 1`` on ``[0, 1)`` carrying contents that never slip (``Pi2 = 50``).

    The whole mass ``M = 1 + Pi8`` slides back at once (``M > Pi9``): ``x'' + w^2 x = -(1 - Pi9/M)``,
    ``w^2 = k_d/M``, so ``x = -a (1 - cos w tau)``, ``a = (1 - Pi9/M)/w^2``.  With ``w < pi`` it still
    slides when the pulse ends; then ``x'' + w^2 x = c w^2`` (``c = Pi9/k_d``) until it stops at
    ``x = -X1``, ``X1 = hypot(x(1) - c, x'(1)/w) - c``, the peak ``|x|``.  Each later swing, about
    ``-+c``, ends ``2c`` nearer the origin, until ``|x| <= c`` holds it for good: the rest
    position is ``(-1)^(k+1) (X1 - 2 k c)``, ``k = max(0, ceil((X1 - c)/(2c)))``.
    """
    m = 0.01
    sc = Scene(pi2=50.0, pi3=3.0, pi4=0.0, pi8=m, pi9=pi9, pi10=0.0, pulse="rectangular")
    kd = (2.0 * math.pi / sc.pi3) ** 2
    M = 1.0 + m
    w = math.sqrt(kd / M)
    assert w < math.pi and M > pi9
    a = (1.0 - pi9 / M) / w ** 2
    x1, v1 = -a * (1.0 - math.cos(w)), -a * w * math.sin(w)
    c = pi9 / kd
    X1 = math.hypot(x1 - c, v1 / w) - c
    k = max(0, math.ceil((X1 - c) / (2.0 * c)))
    rest = (-1) ** (k + 1) * (X1 - 2 * k * c)
    res = solve_reference_building(sc, history=True)
    h = res.history
    assert res.pi1 == 0.0 and np.all(h.phase == 0)
    assert res.settled
    assert np.max(np.abs(h.x)) == pytest.approx(X1, rel=1e-8)
    assert h.x[-1] == pytest.approx(rest, rel=1e-8, abs=1e-12)
    assert np.max(np.abs(h.fh)) == pytest.approx(pi9, rel=1e-12)


ENERGY_SCENES = {
    "bilinear-flexible-roof-stribeck": dict(pi2=0.15, pi3=2.0, pi4=0.08, pi5=0.7, pi6=60.0, pi7=0.05, pi8=0.3,
                                            pi9=0.06, pi10=0.004, pi11=0.6, pi12=0.3, pi13=0.04, floor="roof"),
    "sliding-flexible-base": dict(pi2=0.12, pi3=2.5, pi4=0.05, pi8=0.5, pi9=0.07, pi10=0.0, pi11=0.5,
                                  pi12=0.25, pi13=0.03, floor="base", pulse="makris_b"),
    "sliding-rigid-coulomb": dict(pi2=0.1, pi3=2.0, pi4=0.0, pi8=1.0, pi9=0.1, pi10=0.0),
}


@pytest.mark.parametrize("name", list(ENERGY_SCENES))
def test_energy_balance(name):
    """Input work = kinetic + potential + viscous + isolator + contents-friction dissipation, at every
    recorded time, to 1e-6 of the input work; the energies are computed here from the states."""
    sc = Scene(**ENERGY_SCENES[name])
    run = run_building(sc, ledger=True)
    h, L = run.result.history, run.ledger
    mst = sc.pi11 if sc.pi12 > 0 else 0.0
    mb, m = 1.0 - mst, sc.pi8
    xs = h.xs if h.xs is not None else 0.0 * h.x
    xsd = h.xsd if h.xsd is not None else 0.0 * h.x
    v_blk = h.xd + (xsd if sc.floor == "roof" else 0.0) + h.ud
    kinetic = 0.5 * (mb * h.xd ** 2 + mst * (h.xd + xsd) ** 2 + m * v_blk ** 2)
    kd = (2.0 * math.pi / sc.pi3) ** 2
    ks = mst * (2.0 * math.pi / sc.pi12) ** 2 if sc.pi12 > 0 else 0.0
    potential = 0.5 * kd * h.x ** 2 + 0.5 * ks * xs ** 2
    if sc.pi10 > 0.0:
        potential = potential + h.fh ** 2 / (2.0 * sc.pi9 / sc.pi10)
    accounted = kinetic + potential + L["viscous"] + L["isolator"] + L["friction"]
    W = np.max(np.abs(L["work"]))
    assert run.result.pi1 > 0.0 and L["friction"][-1] > 1e-3 * W and L["isolator"][-1] > 1e-3 * W
    for key in ("viscous", "isolator", "friction"):
        assert np.all(np.diff(L[key]) >= -1e-15 * W)
    assert np.max(np.abs(L["work"] - accounted)) <= 1e-6 * W


@pytest.mark.parametrize("kw", [
    dict(pi2=0.15, pi3=2.0, pi4=0.1, pi8=0.2, pi9=0.06, pi10=0.0, pi11=0.5, pi12=0.3, pi13=0.05, floor="roof"),
    dict(pi2=0.15, pi3=2.0, pi4=0.1, pi8=0.2, pi9=0.06, pi10=0.005, floor="base", pi5=0.8, pi6=40.0),
], ids=["sliding-roof", "bilinear-base"])
def test_mirror_symmetry(kw):
    """The negated pulse gives the same Pi1 and the negated residual slide and slab position."""
    tau = np.linspace(-2.0, 2.0, 401)
    p = (1 - 2 * math.pi ** 2 * tau ** 2) * np.exp(-math.pi ** 2 * tau ** 2)
    dt = tau[1] - tau[0]
    a = solve_reference_building(Scene(**kw, pulse=sampled(p, dt, tau0=-2.0)), history=True)
    b = solve_reference_building(Scene(**kw, pulse=sampled(-p, dt, tau0=-2.0)), history=True)
    assert a.pi1 > 0.01
    assert a.pi1 == pytest.approx(b.pi1, rel=1e-10)
    assert a.pi1_residual == pytest.approx(-b.pi1_residual, rel=1e-9)
    assert a.history.x[-1] == pytest.approx(-b.history.x[-1], rel=1e-9)


def assert_quiet_after_settlement(sc, periods: float):
    """Followed ``periods`` pulse periods past its settlement, ``sc`` has no further transition.

    Returns the settled run.
    """
    done = run_building(sc).result
    assert done.settled
    on = run_building(sc, settle=False, tau_max=done.tau_end + periods, history=True).result
    assert not on.settled and on.tau_end == pytest.approx(done.tau_end + periods)
    assert on.n_events == done.n_events
    assert on.pi1 == done.pi1 and on.pi1_residual == done.pi1_residual
    late = on.history.tau > done.tau_end
    assert np.all(on.history.phase[late] == 0) and np.all(on.history.iso_phase[late] == 0)
    return done


@pytest.mark.parametrize("name", ["bilinear-flexible-roof-stribeck", "sliding-flexible-base"])
def test_nothing_slips_or_yields_after_the_settlement_bound_passes(name):
    """Followed 30 pulse periods past its settlement, a scene has no further transition."""
    assert_quiet_after_settlement(Scene(**ENERGY_SCENES[name]), 30.0)


@pytest.mark.parametrize("name", list(ENERGY_SCENES))
def test_agrees_with_the_compiled_solver(name):
    """Two independent implementations of the general building give the same Pi1."""
    sc = Scene(**ENERGY_SCENES[name])
    assert solve_reference_building(sc).pi1 == pytest.approx(isoslide.solve(sc, rtol=1e-10).pi1, rel=1e-8)


def test_reference_method_dispatches_general_scenes_here():
    """``solve(method="reference")`` of a general building runs this peer, with its states."""
    sc = Scene(**ENERGY_SCENES["bilinear-flexible-roof-stribeck"])
    sol = isoslide.solve(sc, method="reference", history=True)
    direct = solve_reference_building(sc)
    assert sol.pi1 == direct.pi1 == solve_reference(sc).pi1
    h = sol.history
    assert h.xs is not None and h.xsd is not None and h.fh is not None and h.iso_phase.dtype == np.int8
    assert np.max(np.abs(h.fh)) <= sc.pi9 * (1 + 1e-12)
    assert sol.pi1 != pytest.approx(paper_pi1(**{k: v for k, v in ENERGY_SCENES["bilinear-flexible-roof-stribeck"].items()
                                                 if k in ("pi2", "pi3", "pi4", "pi5", "pi6", "pi7", "pi8")}), rel=1e-3)


def test_stick_constraints_hold_through_coupled_transitions():
    """Block on the slab of a sliding bearing, with a block stop that makes the bearing break away
    at the same instant (the force on the slab jumps): wherever the block is stuck its floor
    acceleration is within ``Pi2/Pi5``, wherever the bearing is held its force within ``Pi9``."""
    sc = Scene(pi2=0.6114250573137107, pi3=0.5, pi4=0.1862927709482709, pi8=1.0, pi9=0.5855766698175415,
               pi10=0.0)
    res = solve_reference_building(sc, history=True)
    h = res.history
    same = np.nonzero(h.tau[1:] == h.tau[:-1])[0]     # an event: the old and the new modes
    assert any(h.phase[i] != 0 and h.phase[i + 1] == 0 and h.iso_phase[i] == 0 and h.iso_phase[i + 1] != 0
               for i in same)
    thr, q, m = sc.pi2 / sc.pi5, sc.pi9, sc.pi8
    w = 2.0 * math.pi / sc.pi3
    held = h.iso_phase == 0
    assert np.all(np.abs(h.fh[held]) <= q * (1 + 1e-12))
    assert np.all(np.abs(h.fh[~held]) == q) and np.all(h.xd[held] == 0.0)
    stuck_held = (h.phase == 0) & held
    assert np.all(np.abs(sc.pulse.accel(h.tau[stuck_held])) <= thr * (1 + 1e-12))
    stuck_moving = (h.phase == 0) & ~held
    a_floor = -(w * w * h.x + 2.0 * sc.pi4 * w * h.xd + h.fh) / (1.0 + m)
    assert np.all(np.abs(a_floor[stuck_moving]) <= thr * (1 + 1e-12))
    assert res.pi1 == pytest.approx(isoslide.solve(sc, rtol=1e-10).pi1, rel=1e-8)


def test_undamped_building_with_a_brief_reversal_runs_to_the_horizon():
    """Undamped isolator and superstructure (Pi4 = Pi13 = 0), contents on the roof: at tau ~ 3.156 the
    block stops and reverses with a floor demand 1e-3 above its limit, a slip far shorter than a
    step, which is located; the free system keeps its energy, so the run ends unsettled at the
    horizon ``tau_end + 50 max(1, Pi3, Pi12)``; Pi1 as the compiled solver's."""
    sc = Scene(pi2=0.2, pi3=2.0, pi4=0.0, pi8=0.1, pi11=0.5, pi12=0.3, pi13=0.0, floor="roof", pi9=0.05,
               pi10=0.01)
    res = solve_reference_building(sc)
    assert not res.settled and res.tau_end == pytest.approx(sc.pulse.tau_end + 50.0 * sc.pi3)
    assert res.pi1 == pytest.approx(isoslide.solve(sc, rtol=1e-10).pi1, rel=1e-8)
