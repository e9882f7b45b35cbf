"""Tests of the N-storey superstructure in the general building's SciPy reference peer.

The assembled shear chain (fundamental period, storey stiffnesses, modal damping), its limits (a
stiff superstructure is the rigid building, light upper floors leave a one-storey building), the
energy balance, mirror symmetry and the settlement bound with several floors, and the dispatch of
``solve(method="reference")``.
"""

import math

import numpy as np
import pytest

import isoslide
from isoslide import Scene
from isoslide.peers.reference_building import (building_of, energies, run_building, shear_building,
                                               solve_reference_building)
from isoslide.pulses import sampled
from test_reference_building import assert_quiet_after_settlement  # tests/ is on sys.path

BILINEAR = dict(pi2=0.15, pi3=2.0, pi4=0.1, pi8=0.2, pi9=0.06, pi10=0.005, pi11=0.6, pi12=0.3, pi13=0.05)


def _fixed_base_modes(ms, Ks):
    """Circular frequencies (ascending) and mass-normalised modes of ``Ms^-1 Ks``, by numpy."""
    lam, V = np.linalg.eig(np.linalg.solve(np.diag(ms), Ks))
    order = np.argsort(lam.real)
    lam, V = lam.real[order], V.real[:, order]
    V = V / np.sqrt(np.einsum("ji,j,ji->i", V, ms, V))
    return np.sqrt(lam), V


@pytest.mark.parametrize("kw", [
    dict(storeys=5),
    dict(storeys=4, floor_masses=(3.0, 2.0, 2.0, 1.0), storey_stiffnesses=(4.0, 3.0, 2.0, 0.5)),
], ids=["uniform", "tapered"])
def test_assembled_shear_chain_has_the_period_the_storeys_and_the_damping_asked_for(kw):
    """``Ks`` is the shear chain of the storey stiffnesses (storey ``j`` between floors ``j-1`` and
    ``j``), the fixed-base fundamental period is ``T_s = Pi12``, every fixed-base mode has damping
    ratio ``Pi13`` and the modes stay uncoupled by ``Cs``; floor masses ``Pi11 w_j``."""
    sc = Scene(**BILINEAR, **kw)
    B = building_of(sc)
    n = sc.storeys
    w = np.full(n, 1.0 / n) if sc.floor_masses is None else np.asarray(sc.floor_masses)
    assert B.ms == pytest.approx(sc.pi11 * w, rel=1e-15) and B.mb == pytest.approx(1.0 - sc.pi11, rel=1e-15)
    r = np.ones(n) if sc.storey_stiffnesses is None else np.asarray(sc.storey_stiffnesses)
    kappa = B.Ks[n - 1, n - 1] / r[n - 1]
    chain = np.zeros((n, n))
    for j in range(n):
        chain[j, j] = r[j] + (r[j + 1] if j + 1 < n else 0.0)
        if j + 1 < n:
            chain[j, j + 1] = chain[j + 1, j] = -r[j + 1]
    assert np.allclose(B.Ks, kappa * chain, rtol=1e-13, atol=1e-13 * kappa)
    omega, V = _fixed_base_modes(B.ms, B.Ks)
    assert 2.0 * math.pi / omega[0] == pytest.approx(sc.pi12, rel=1e-12)
    assert omega[1] > 1.5 * omega[0]
    modal = V.T @ B.Cs @ V
    assert np.diag(modal) / (2.0 * omega) == pytest.approx(np.full(n, sc.pi13), rel=1e-10)
    off = modal - np.diag(np.diag(modal))
    assert np.max(np.abs(off)) <= 1e-10 * np.max(np.abs(modal))


def test_one_storey_matrices_are_the_single_mass_formulas():
    """``storeys = 1``: ``ks = Pi11 (2 pi/Pi12)**2`` and ``cs = 2 Pi13 (2 pi/Pi12) Pi11``."""
    sc = Scene(**BILINEAR)
    B = building_of(sc)
    ws = 2.0 * math.pi / sc.pi12
    assert B.Ks.shape == (1, 1) and B.ms.tolist() == [sc.pi11]
    assert B.Ks[0, 0] == pytest.approx(sc.pi11 * ws * ws, rel=1e-14)
    assert B.Cs[0, 0] == pytest.approx(2.0 * sc.pi13 * ws * sc.pi11, rel=1e-14)


@pytest.mark.parametrize("name, value", [("masses", [1.0, 0.0]), ("stiffnesses", [1.0, -2.0]),
                                         ("period", 0.0), ("damping", -0.1)])
def test_shear_building_rejects_input_out_of_range(name, value):
    """Nonpositive masses, stiffnesses or period, or a negative damping ratio, raise a ValueError
    naming the parameter."""
    args = dict(masses=[1.0, 1.0], stiffnesses=[1.0, 1.0], period=0.5, damping=0.05)
    args[name] = value
    with pytest.raises(ValueError, match=name):
        shear_building(**args)


@pytest.mark.slow
@pytest.mark.parametrize("floor", [1, "roof"])
def test_a_stiff_superstructure_approaches_the_rigid_building(floor):
    """Fixed base, two storeys: halving ``Pi12`` (0.1 -> 0.05) brings Pi1 nearer the rigid building's
    (``Pi12 = 0``, contents on the ground's floor), within 3 %."""
    kw = dict(pi2=0.3, pi3=0.0, pi8=0.2)
    rigid = solve_reference_building(Scene(**kw)).pi1
    assert rigid > 0.01
    gaps = [abs(solve_reference_building(Scene(**kw, pi11=0.6, pi12=pi12, pi13=0.05, storeys=2, floor=floor)).pi1
                / rigid - 1.0) for pi12 in (0.1, 0.05)]
    assert gaps[1] < 0.6 * gaps[0]
    assert gaps[1] < 0.03


def test_light_upper_floors_leave_the_one_storey_building():
    """Three storeys with floors 2 and 3 of mass ``eps`` on storeys of stiffness ``4 eps`` (their own
    frequencies above the fundamental one), contents on floor 1: Pi1 tends to the one-storey
    building's with the contents on its roof, the gap shrinking with ``eps``."""
    one = solve_reference_building(Scene(**BILINEAR, floor="roof")).pi1
    assert one > 0.01
    gaps = []
    for eps in (1e-2, 1e-3):
        sc = Scene(**BILINEAR, storeys=3, floor=1, floor_masses=(1.0, eps, eps),
                   storey_stiffnesses=(1.0, 4.0 * eps, 4.0 * eps))
        gaps.append(abs(solve_reference_building(sc).pi1 / one - 1.0))
    assert gaps[1] < 0.2 * gaps[0]
    assert gaps[1] < 1e-3


ENERGY_SCENES = {
    "bilinear-3-storeys-floor-2-stribeck": dict(BILINEAR, pi5=0.7, pi6=60.0, pi7=0.05, storeys=3, floor=2),
    "sliding-4-storeys-tapered-base": dict(pi2=0.12, pi3=2.5, pi4=0.05, pi8=0.5, pi9=0.07, pi10=0.0, pi11=0.5,
                                           pi12=0.25, pi13=0.03, storeys=4, floor="base", pulse="makris_b",
                                           floor_masses=(2.0, 1.5, 1.0, 1.0),
                                           storey_stiffnesses=(3.0, 2.0, 2.0, 1.0)),
}


@pytest.mark.parametrize("name", list(ENERGY_SCENES))
def test_energy_balance_with_several_floors(name):
    """Input work = kinetic + potential + viscous + isolator + contents-friction dissipation at every
    recorded time, to 1e-6 of the input work; the energies are computed here from every floor's
    state (and agree with the module's :func:`energies`)."""
    sc = Scene(**ENERGY_SCENES[name])
    run = run_building(sc, ledger=True)
    h, L = run.result.history, run.ledger
    B = building_of(sc)
    xs, xsd = run.floors
    assert xs.shape == (sc.storeys, h.tau.size)
    assert np.array_equal(h.xs, xs[-1]) and np.array_equal(h.xsd, xsd[-1])
    k = sc.floor_index
    v_floor = h.xd + (xsd[k - 1] if k else 0.0)
    kinetic = 0.5 * (B.mb * h.xd ** 2 + sc.pi8 * (v_floor + h.ud) ** 2)
    potential = 0.5 * (2.0 * math.pi / sc.pi3) ** 2 * h.x ** 2
    n = sc.storeys
    storey_k = [B.Ks[0, 0] + (B.Ks[0, 1] if n > 1 else 0.0)] + [-B.Ks[j - 1, j] for j in range(1, n)]
    for j in range(n):
        kinetic = kinetic + 0.5 * B.ms[j] * (h.xd + xsd[j]) ** 2
        drift = xs[j] - (xs[j - 1] if j else 0.0)
        potential = potential + 0.5 * storey_k[j] * drift ** 2
    if sc.pi10 > 0.0:
        potential = potential + h.fh ** 2 / (2.0 * sc.pi9 / sc.pi10)
    kin_m, pot_m = energies(sc, h, run.floors)
    W = np.max(np.abs(L["work"]))
    assert np.max(np.abs(kin_m - kinetic)) <= 1e-12 * W and np.max(np.abs(pot_m - potential)) <= 1e-12 * W
    accounted = kinetic + potential + L["viscous"] + L["isolator"] + L["friction"]
    assert run.result.pi1 > 0.0 and L["friction"][-1] > 1e-3 * W and L["isolator"][-1] > 1e-3 * W
    for key in ("viscous", "isolator", "friction"):
        assert np.all(np.diff(L[key]) >= -1e-15 * W)
    assert np.max(np.abs(L["work"] - accounted)) <= 1e-6 * W


def test_energies_of_several_floors_need_every_floor():
    """Without the floors' states the energy of a three-storey history is refused (ValueError)."""
    sc = Scene(**ENERGY_SCENES["bilinear-3-storeys-floor-2-stribeck"])
    h = run_building(sc, history=True, tau_max=0.0).result.history
    with pytest.raises(ValueError, match="floors"):
        energies(sc, h)


def test_mirror_symmetry_with_several_floors():
    """Sliding bearing, three storeys, contents on floor 2: the negated pulse gives the same Pi1 and
    the negated residual slide, slab position and floor displacements."""
    kw = dict(pi2=0.15, pi3=2.0, pi4=0.1, pi8=0.2, pi9=0.06, pi10=0.0, pi11=0.5, pi12=0.3, pi13=0.05,
              storeys=3, floor=2)
    tau = np.linspace(-2.0, 2.0, 401)
    p = (1 - 2 * math.pi ** 2 * tau ** 2) * np.exp(-math.pi ** 2 * tau ** 2)
    dt = tau[1] - tau[0]
    a = run_building(Scene(**kw, pulse=sampled(p, dt, tau0=-2.0)), history=True)
    b = run_building(Scene(**kw, pulse=sampled(-p, dt, tau0=-2.0)), history=True)
    assert a.result.pi1 > 0.01
    assert a.result.pi1 == pytest.approx(b.result.pi1, rel=1e-10)
    assert a.result.pi1_residual == pytest.approx(-b.result.pi1_residual, rel=1e-9)
    assert a.result.history.x[-1] == pytest.approx(-b.result.history.x[-1], rel=1e-9)
    scale = np.max(np.abs(a.floors[0]))
    assert np.max(np.abs(a.floors[0][:, -1] + b.floors[0][:, -1])) <= 1e-8 * scale


def test_contents_floor_matters():
    """The same two-storey building gives different Pi1 with the contents on the slab, floor 1 and
    the roof (the floor is read), and the roof's differs from the one-storey roof's."""
    pis = [solve_reference_building(Scene(**BILINEAR, storeys=2, floor=f)).pi1 for f in ("base", 1, "roof")]
    one = solve_reference_building(Scene(**BILINEAR, floor="roof")).pi1
    assert min(pis) > 0.01
    assert len({round(v, 6) for v in pis + [one]}) == 4


def test_nothing_slips_or_yields_after_the_settlement_bound_passes_with_several_floors():
    """Two storeys, contents on the roof, bilinear bearing: followed 10 pulse periods past its
    settlement, the scene has no further transition."""
    done = assert_quiet_after_settlement(Scene(**BILINEAR, storeys=2, floor="roof"), 10.0)
    assert done.settled and done.pi1 > 0.01


def test_reference_method_solves_several_storeys():
    """``solve(method="reference")`` of a two-storey scene runs this peer; its history's ``xs`` is
    the roof's."""
    sc = Scene(**BILINEAR, storeys=2, floor=1)
    sol = isoslide.solve(sc, method="reference", history=True)
    run = run_building(sc, history=True)
    assert sol.pi1 == run.result.pi1 > 0.01
    assert np.array_equal(sol.history.xs, run.floors[0][-1])


CROSS_SCENES = {
    "bilinear-3-storeys-floor-2": dict(BILINEAR, pi5=0.7, pi6=60.0, pi7=0.05, storeys=3, floor=2),
    "sliding-4-storeys-tapered-roof": dict(ENERGY_SCENES["sliding-4-storeys-tapered-base"], floor="roof"),
    "fixed-base-2-storeys-floor-1": dict(pi2=0.3, pi3=0.0, pi8=0.2, pi11=0.6, pi12=0.3, pi13=0.05, storeys=2,
                                         floor=1),
}


@pytest.mark.parametrize("name", list(CROSS_SCENES))
def test_several_storeys_agree_with_the_compiled_solver(name):
    """Two independent implementations of the N-storey building give the same Pi1 (to 1e-8)."""
    sc = Scene(**CROSS_SCENES[name])
    ref = solve_reference_building(sc).pi1
    assert ref > 1e-3
    assert ref == pytest.approx(isoslide.solve(sc, rtol=1e-10).pi1, rel=1e-8)
