"""N-storey superstructures: the scene's floors, the assembled building, and limits of the exact solver."""

import math

import numpy as np
import pytest

from isoslide import Scene, solve
from isoslide.engine import building
from isoslide.model import shear_building
from isoslide.pulses import sampled

BASE = dict(pi2=0.15, pi3=2.0, pi4=0.1, pi8=0.01, pi11=0.6, pi12=0.3, pi13=0.05)
ISOLATORS = {"linear": {}, "friction pendulum": dict(pi9=0.05), "lead-rubber": dict(pi9=0.08, pi10=0.01)}


@pytest.mark.parametrize("iso", ISOLATORS.values(), ids=ISOLATORS)
@pytest.mark.parametrize("floor", ["base", "roof"])
def test_one_storey_given_explicitly_is_the_default_building_bit_for_bit(iso, floor):
    """``storeys=1`` (and floor 0 / 1 for base / roof) solves exactly as a scene that does not say it."""
    default = Scene(**BASE, **iso, floor=floor)
    explicit = Scene(**BASE, **iso, storeys=1, floor={"base": 0, "roof": 1}[floor])
    assert explicit == default
    a, b = solve(default, history=True), solve(explicit, history=True)
    assert (a.pi1, a.n_steps, a.n_events, a.tau_end, a.model) == (b.pi1, b.n_steps, b.n_events, b.tau_end, b.model)
    assert np.array_equal(a.history.u, b.history.u)


@pytest.mark.parametrize("n", [1, 2, 5, 8])
@pytest.mark.parametrize("shape", ["uniform", "non-uniform"])
def test_assembled_superstructure_has_the_fixed_base_period_and_damping_in_every_mode(n, shape):
    """Masses sum to Pi11, the fixed-base fundamental period is Pi12 and every mode's damping ratio Pi13."""
    extra = {} if shape == "uniform" else dict(floor_masses=tuple(1.0 + 0.3 * j for j in range(n)),
                                               storey_stiffnesses=tuple(2.0 - j / n for j in range(n)))
    sc = Scene(**BASE, storeys=n, **extra)
    masses, Ks, Cs = building.superstructure(sc)
    assert masses.sum() == pytest.approx(sc.pi11, rel=1e-14)
    lam, V = np.linalg.eig(np.linalg.solve(np.diag(masses), Ks))
    order = np.argsort(lam.real)
    omega = np.sqrt(lam.real[order])
    assert 2.0 * math.pi / omega[0] == pytest.approx(sc.pi12, rel=1e-12)
    phi = V.real[:, order]
    modal_c = phi.T @ Cs @ phi
    modal_m = phi.T @ np.diag(masses) @ phi
    assert np.allclose(modal_c - np.diag(np.diag(modal_c)), 0.0, atol=1e-10 * np.abs(modal_c).max())
    ratios = np.diag(modal_c) / (2.0 * omega * np.diag(modal_m))
    assert ratios == pytest.approx(np.full(n, sc.pi13), rel=1e-9)
    if shape == "uniform":   # equal storey stiffnesses: the top storey's (Ks[-1, -1]) and those between floors
        k = np.append(-np.diag(Ks, 1), Ks[-1, -1])
        assert np.ptp(k) <= 1e-12 * k.max()


def test_shear_chain_stiffness_matrix_by_hand():
    """Storey j joins floors j-1 and j: the 3-storey matrix written out."""
    K = shear_building.stiffness_matrix([3.0, 2.0, 1.0])
    assert np.array_equal(K, [[5.0, -2.0, 0.0], [-2.0, 3.0, -1.0], [0.0, -1.0, 1.0]])


@pytest.mark.parametrize("iso", ISOLATORS.values(), ids=ISOLATORS)
def test_two_storeys_with_a_rigid_lower_storey_behave_as_one_storey(iso):
    """A lower storey 1e6 times stiffer ties floor 1 to the slab: the building is the one-storey one
    whose superstructure is the upper floor (half the mass), to the compliance left (~1e-6)."""
    two = Scene(**{**BASE, "pi11": 0.3}, **iso, storeys=2, floor="roof", floor_masses=(1.0, 1.0),
                storey_stiffnesses=(1e6, 1.0))
    one = Scene(**{**BASE, "pi11": 0.15}, **iso, floor="roof")
    a, b = solve(two), solve(one)
    assert a.settled and b.settled
    assert a.pi1 == pytest.approx(b.pi1, rel=2e-6)


def test_a_stiff_superstructure_approaches_the_rigid_building_on_every_floor():
    """Pi12 -> 0: every floor moves with the slab, Pi1 on each floor tends to the rigid building's."""
    rigid = solve(Scene(**{**BASE, "pi12": 0.0}, pi9=0.05)).pi1
    for floor in (0, 2, 4):
        sc = Scene(**{**BASE, "pi12": 0.002}, pi9=0.05, storeys=4, floor=floor)
        assert solve(sc).pi1 == pytest.approx(rigid, rel=2e-3)


@pytest.mark.parametrize("floor", [0, 1, 3])
def test_flipping_the_ground_motion_flips_the_sliding_of_an_n_storey_building(floor):
    """Mirror symmetry: the negated record gives the same Pi1 and the opposite residual, on any floor."""
    rng = np.random.default_rng(5)
    acc = np.convolve(rng.standard_normal(400), np.ones(20) / 20.0, mode="same")
    acc /= np.max(np.abs(acc))
    kw = dict(**BASE, pi9=0.08, pi10=0.01, pi5=0.7, pi6=300.0, storeys=3, floor=floor)
    a = solve(Scene(**kw, pulse=sampled(acc, 0.01)))
    b = solve(Scene(**kw, pulse=sampled(-acc, 0.01)))
    assert a.pi1 > 0.0
    assert b.pi1 == pytest.approx(a.pi1, rel=1e-9)
    assert b.pi1_residual == pytest.approx(-a.pi1_residual, rel=1e-9, abs=1e-14)


def test_fixed_base_with_contents_upstairs_is_integrated():
    """Pi3 = 0 with contents on an upper floor runs the building, not the paper's fixed base."""
    up = solve(Scene(**{**BASE, "pi3": 0.0}, storeys=4, floor=3))
    slab = solve(Scene(**{**BASE, "pi3": 0.0}, storeys=4, floor=0))
    assert "flexible" in up.model and slab.model.startswith("fixed-base")
    assert up.pi1 != slab.pi1


@pytest.mark.parametrize("bad, match", [
    (dict(storeys=0), "storeys = 0"), (dict(storeys=2.5), "storeys = 2.5"), (dict(storeys=True), "storeys"),
    (dict(storeys=65), "storeys = 65"), (dict(storeys=3, floor=4), "floor = 4"), (dict(floor="mid"), "floor = 'mid'"),
    (dict(storeys=3, floor=-1), "floor = -1"), (dict(storeys=2, floor_masses=(1.0,)), "floor_masses has 1"),
    (dict(storeys=2, storey_stiffnesses=(1.0, -1.0)), r"storey_stiffnesses\[1\] = -1.0"),
])
def test_bad_storeys_floor_or_shape_are_refused_naming_the_parameter(bad, match):
    with pytest.raises(ValueError, match=match):
        Scene(**BASE, **bad)


def test_floor_names_and_numbers_are_one_floor():
    """``0`` is ``"base"``, ``storeys`` is ``"roof"``; numbers between stay numbers."""
    assert Scene(**BASE, storeys=3, floor=0) == Scene(**BASE, storeys=3, floor="base")
    assert Scene(**BASE, storeys=3, floor=3) == Scene(**BASE, storeys=3, floor="roof")
    sc = Scene(**BASE, storeys=3, floor=2)
    assert sc.floor == 2 and sc.floor_index == 2 and Scene(**BASE, storeys=3, floor="roof").floor_index == 3


def test_from_physical_builds_a_non_uniform_building_from_floor_masses_and_stiffnesses():
    """SI floors: m_st is their sum, T_s their fixed-base period; the shapes are kept as ratios."""
    masses, k = [1.2e5, 1.0e5, 0.8e5], [3e8, 2e8, 1e8]
    sc = Scene.from_physical(a_p=6.0, T_p=1.2, M_b=8e5, T_b=2.4, xi_b=0.1, m_ec=800.0, mu_s=0.25, mu_k=0.2,
                             xi_s=0.05, floor=1, floor_masses=masses, storey_stiffnesses=k)
    T_s = shear_building.fundamental_period(masses, k)
    assert sc.storeys == 3 and sc.pi11 == pytest.approx(3e5 / 8e5) and sc.pi12 == pytest.approx(T_s / 1.2)
    assert sc.storey_stiffnesses == pytest.approx((1.0, 2 / 3, 1 / 3))
    M, Ks, _ = building.superstructure(sc)
    assert M * 8e5 == pytest.approx(masses)          # the floor masses back in kg
    assert Ks * 8e5 / 1.2**2 == pytest.approx(shear_building.stiffness_matrix(k))   # and the storeys in N/m
    with pytest.raises(ValueError, match="T_s = 0.1 disagrees"):
        Scene.from_physical(a_p=6.0, T_p=1.2, M_b=8e5, T_b=2.4, xi_b=0.1, m_ec=800.0, mu_s=0.25, mu_k=0.2,
                            T_s=0.1, floor_masses=masses, storey_stiffnesses=k)


REFERENCE_SCENES = {
    "2 storeys, linear, roof, Stribeck": dict(storeys=2, floor="roof", pi5=0.7, pi6=300.0, pi7=0.2),
    "2 storeys, lead-rubber, middle floor": dict(storeys=2, floor=1, pi9=0.08, pi10=0.01),
    "5 storeys, friction pendulum, floor 2, Stribeck": dict(storeys=5, floor=2, pi9=0.05, pi5=0.7, pi6=300.0,
                                                            pi7=0.2),
    "5 storeys, friction pendulum, slab": dict(storeys=5, floor=0, pi9=0.05),
    "8 storeys, fixed base, floor 4": dict(storeys=8, floor=4, pi3=0.0),
    "8 storeys, friction pendulum, roof": dict(storeys=8, floor="roof", pi9=0.05),
}
SLOW_REFERENCE_SCENES = {
    "5 storeys, linear, roof": dict(storeys=5, floor="roof"),
    "8 storeys, lead-rubber, floor 4, Stribeck": dict(storeys=8, floor=4, pi9=0.08, pi10=0.01, pi5=0.7, pi6=300.0,
                                                      pi7=0.2),
    "3 storeys, tapered, friction pendulum, floor 1": dict(storeys=3, floor=1, pi9=0.05, floor_masses=(3.0, 2.0, 1.0),
                                                           storey_stiffnesses=(3.0, 2.0, 1.0)),
}


def _against_reference(kw):
    sc = Scene(**{**BASE, **kw})
    exact, ref = solve(sc), solve(sc, method="reference")
    assert exact.settled and ref.settled
    assert exact.pi1 > 0.0
    assert exact.pi1 == pytest.approx(ref.pi1, rel=1e-6)


@pytest.mark.parametrize("kw", REFERENCE_SCENES.values(), ids=REFERENCE_SCENES)
def test_n_storey_buildings_agree_with_the_independent_reference_solver(kw):
    """The compiled N-storey building against the SciPy event-driven peer (rtol 1e-12): Pi1 to 1e-6."""
    _against_reference(kw)


@pytest.mark.slow
@pytest.mark.parametrize("kw", SLOW_REFERENCE_SCENES.values(), ids=SLOW_REFERENCE_SCENES)
def test_n_storey_buildings_agree_with_the_reference_solver_where_it_is_slow(kw):
    """As above on scenes where the SciPy peer takes 5-15 s (linear and lead-rubber isolators, tapered)."""
    _against_reference(kw)
