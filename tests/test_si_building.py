"""The SI-units integration of the general building (isoslide.peers.si_building through simulate_si).

Pi1 of physical realisations with random (a_p, T_p, M_b) equals isoslide's exact solution of the same
Pi-groups: Buckingham invariance of Pi9 .. Pi13 and the floor, shown by an integration written in
newtons, metres and seconds independently of the compiled kernel; superstructures of several storeys
(uniform, or given floor by floor in kg and N/m) agree with the dimensionless reference peer.
"""

import math

import numpy as np
import pytest
import xarray as xr

import isoslide
from isoslide.studies import similarity as S
from isoslide.peers.si import simulate_si
from isoslide.peers.reference_building import solve_reference_building
from isoslide.peers.si_building import chain_matrices, is_general

G = isoslide.G_STANDARD
PAPER = dict(pi2=0.2, pi3=2.0, pi4=0.05, pi5=0.8, pi6=0.0, pi7=0.0, pi8=0.01)
BUILDINGS = {
    "sliding bearing": (dict(PAPER, pi9=0.1), "base"),
    "bilinear bearing": (dict(PAPER, pi9=0.1, pi10=0.01), "base"),
    "flexible, base": (dict(PAPER, pi3=1.5, pi4=0.1, pi11=0.6, pi12=0.3, pi13=0.05), "base"),
    "flexible, roof": (dict(PAPER, pi3=1.5, pi4=0.1, pi11=0.6, pi12=0.3, pi13=0.05), "roof"),
    "friction pendulum, flexible, roof, Stribeck": (dict(PAPER, pi2=0.15, pi3=2.5, pi4=0.0, pi5=0.7, pi6=40.0,
                                                         pi8=0.05, pi9=0.08, pi11=0.5, pi12=0.2, pi13=0.03),
                                                    "roof"),
    "lead-rubber, flexible, base, viscous contact": (dict(PAPER, pi3=2.0, pi7=0.3, pi9=0.06, pi10=0.02,
                                                          pi11=0.7, pi12=0.4, pi13=0.02), "base"),
    "fixed base, flexible, roof": (dict(PAPER, pi3=0.0, pi4=0.0, pi2=0.3, pi11=0.5, pi12=0.5, pi13=0.05),
                                   "roof"),
}


def _realisations(seed, n=3):
    """n random (a_p m/s^2, T_p s, M_b kg), log-uniform over 0.1-3 g, 0.2-5 s, 1e3-1e7 kg."""
    rng = np.random.default_rng(seed)
    lo, hi = np.log([[0.1 * G, 0.2, 1e3]]), np.log([[3.0 * G, 5.0, 1e7]])
    return [tuple(float(v) for v in row) for row in np.exp(rng.uniform(lo, hi, (n, 3)))]


def _si(p, t_end_tau, pulse="ricker"):
    return simulate_si(p, pulse, t_end=t_end_tau * p["T_p"]).pi1


@pytest.mark.parametrize("name", list(BUILDINGS))
def test_random_realisations_agree_with_isoslide(name):
    """Pi1 of 3 random SI realisations equals isoslide.solve of the same groups to 1e-5 (relative)."""
    pis, floor = BUILDINGS[name]
    sol = isoslide.solve(isoslide.Scene(**pis, floor=floor))
    assert sol.pi1 > 1e-3
    for k, (a_p, T_p, M_b) in enumerate(_realisations(len(name))):
        p = S.physical_parameters(pis, a_p, T_p, M_b, floor=floor)
        assert is_general(p)
        assert _si(p, sol.tau_end + 1.0) == pytest.approx(sol.pi1, rel=1e-5), (k, a_p, T_p, M_b)


@pytest.mark.parametrize("pulse", ["rectangular", "antisymmetric_ricker", "mavroeidis_papageorgiou"])
def test_other_pulses_agree_with_isoslide(pulse):
    """Piecewise and multi-lobe pulses: a sliding bearing under a flexible superstructure, contents on the roof."""
    pis = dict(PAPER, pi9=0.1, pi11=0.6, pi12=0.3, pi13=0.05)
    sol = isoslide.solve(isoslide.Scene(**pis, floor="roof", pulse=pulse))
    assert sol.pi1 > 1e-3
    p = S.physical_parameters(pis, 0.7 * G, 1.7, 3e5, floor="roof")
    assert _si(p, sol.tau_end + 1.0, pulse) == pytest.approx(sol.pi1, rel=1e-5)


def _physical(**over):
    """A lead-rubber bearing under a flexible superstructure, contents on the roof, in SI units."""
    p = dict(a_p=3.0, T_p=1.2, M_b=4e5, T_b=2.4, xi_b=0.05, m_ec=4e3, mu_s=0.08, mu_k=0.06, beta=5.0, gamma=0.0,
             g=G, Q_d=5e4, D_y=0.02, m_st=2.4e5, T_s=0.4, xi_s=0.03, floor="roof")
    p.update(over)
    return p


def _scaled(p, mass=1.0, accel=1.0, time=1.0):
    """The same Pi-groups with masses, accelerations and times scaled (lengths scale as accel time^2)."""
    q = dict(p)
    for k in ("M_b", "m_ec", "m_st"):
        q[k] = p[k] * mass
    q["Q_d"] = p["Q_d"] * mass * accel
    q["a_p"], q["mu_s"], q["mu_k"] = p["a_p"] * accel, p["mu_s"] * accel, p["mu_k"] * accel
    q["D_y"] = p["D_y"] * accel * time**2
    for k in ("T_p", "T_b", "T_s"):
        q[k] = p[k] * time
    q["beta"] = p["beta"] / (accel * time)
    q["gamma"] = p["gamma"] / time
    return q


def test_physical_parameters_carry_the_building_and_the_floor():
    """physical_parameters realises Pi9 .. Pi13 and passes the floor (Scene.from_physical gets them back)."""
    pis = dict(PAPER, pi9=0.07, pi10=0.015, pi11=0.6, pi12=0.3, pi13=0.05)
    p = S.physical_parameters(pis, 4.0, 2.5, 3e5, floor="roof")
    assert p["floor"] == "roof"
    sc = isoslide.Scene.from_physical(**p)
    assert sc.floor == "roof"
    for k, v in pis.items():
        assert getattr(sc, k) == pytest.approx(v, rel=1e-12)
    assert S.physical_parameters(PAPER, 4.0, 2.5, 3e5)["floor"] == "base"
    with pytest.raises(ValueError, match="floor"):
        S.physical_parameters(PAPER, 4.0, 2.5, 3e5, floor="attic")


@pytest.mark.parametrize("scale", [dict(mass=2.0), dict(accel=3.0), dict(time=0.5),
                                   dict(mass=0.1, accel=0.4, time=3.0)])
def test_scaling_physical_parameters_at_fixed_groups_keeps_pi1(scale):
    """Q_d, M_b, m_ec, m_st doubled together (Pi8, Pi9, Pi11 fixed), D_y with a_p T_p^2, T_s with T_p: same Pi1."""
    p = _physical()
    base = _si(p, 6.0)
    assert base > 1e-3
    assert _si(_scaled(p, **scale), 6.0) == pytest.approx(base, rel=1e-7)


@pytest.mark.parametrize("change", [dict(Q_d=1e5), dict(D_y=0.06), dict(m_st=1.6e5), dict(T_s=0.8),
                                    dict(xi_s=0.3), dict(floor="base")])
def test_each_building_parameter_changes_pi1(change):
    """One building parameter changed alone (its group changes): Pi1 differs by more than 0.1 %.

    (The smallest change, xi_s 0.03 -> 0.3, moves Pi1 by 0.28 %; the fixed-group scalings above agree to
    1e-7, so 0.1 % is far outside the integration's error.)
    """
    base = _si(_physical(), 6.0)
    assert abs(_si(_physical(**change), 6.0) - base) > 1e-3 * base


def test_bad_building_input_is_named():
    with pytest.raises(ValueError, match="m_st"):
        simulate_si(_physical(m_st=5e5), "ricker")
    with pytest.raises(ValueError, match="floor"):
        simulate_si(_physical(floor="attic"), "ricker")
    with pytest.raises(ValueError, match="D_y"):
        simulate_si(_physical(D_y=-1.0), "ricker")


def _building_study(floor):
    """A small general-building study dataset (Pi9 swept, Pi2 the abscissa) solved by isoslide."""
    fixed = dict(PAPER, pi10=0.0, pi11=0.6, pi12=0.3, pi13=0.05)
    pi9, pi2 = np.array([0.05, 0.1]), np.array([0.15, 0.25])
    sols = [[isoslide.solve(isoslide.Scene(**dict(fixed, pi9=a, pi2=b), floor=floor)) for b in pi2] for a in pi9]
    var = {k: (("pi9", "pi2"), np.array([[getattr(s, k) for s in row] for row in sols], dtype=float))
           for k in ("pi1", "tau_end")}
    var["settled"] = (("pi9", "pi2"), np.ones((2, 2), dtype=np.int8))
    coords = {"pi9": pi9, "pi2": pi2, **{k: v for k, v in fixed.items() if k != "pi2"}}
    return xr.Dataset(var, coords=coords, attrs={"study": f"tiny_{floor}", "pulse": "ricker", "floor": floor})


def test_buckingham_study_realises_a_general_building_on_its_floor():
    """The Buckingham check realises Pi9 .. Pi13 and the dataset's floor: the SI Pi1 equals the grid's."""
    settings = dict(seed=3, points=2, realisations=2, a_p_g=[0.1, 2.0], T_p=[0.3, 4.0], M_b=[1e4, 1e7])
    for floor in ("base", "roof"):
        out = S.buckingham_study(_building_study(floor), settings)
        assert out.attrs["floor"] == floor
        assert out.sizes["sample"] == 2
        assert float(out["pi12"][0]) == 0.3
        si = out["pi1_si"].sel(convention="isoslide").values
        grid = out["pi1_grid"].values[:, None]
        assert np.all(np.abs(si / grid - 1.0) < 1e-5)


def test_study_floor_defaults_to_the_base():
    """A dataset without a floor attribute (the paper's studies) is realised on the base slab."""
    assert S.study_floor(xr.Dataset(attrs={"study": "x"})) == "base"
    assert S.study_floor(xr.Dataset(attrs={"floor": "roof"})) == "roof"
    with pytest.raises(ValueError, match="floor"):
        S.study_floor(xr.Dataset(attrs={"floor": "attic"}))


def test_paper_points_without_building_coordinates_are_the_paper_model():
    """A dataset of the paper's groups only: the building groups are realised as 0 (linear, rigid)."""
    ds = xr.Dataset({"pi1": (("pi2",), [0.1])}, coords={"pi2": [0.2], **{k: v for k, v in PAPER.items()
                                                                       if k != "pi2"}})
    pt = S._point_pis(ds, (0,))
    assert all(pt[k] == 0.0 for k in ("pi9", "pi10", "pi11", "pi12", "pi13"))
    assert not is_general(S.physical_parameters(pt, 3.0, 1.0, 1e5))
    assert math.isclose(pt["pi3"], PAPER["pi3"])


def test_a_tangential_touch_of_the_stick_limit_in_the_paper_model():
    """A paper-model realisation whose floor acceleration touches mu_s g tangentially (at tau = 1.706):
    the two-state solver stalls there, simulate_si integrates it by the building's equations and
    agrees with isoslide.solve to 1e-5 (the Buckingham check of a rigid-superstructure grid point)."""
    from isoslide.peers import si

    pis = dict(pi2=0.908, pi3=1.0, pi4=0.1, pi5=1.0, pi6=0.0, pi7=0.0, pi8=1e-5)
    sol = isoslide.solve(isoslide.Scene(**pis))
    p = S.physical_parameters(pis, 15.400856331533095, 0.35986102112663587, 13351.122482138764)
    t_end = (sol.tau_end + 1.0) * p["T_p"]
    with pytest.raises(si._Stalled):
        si._simulate_paper(p, "ricker", t_end, 1e-12, False)
    assert simulate_si(p, "ricker", t_end=t_end).pi1 == pytest.approx(sol.pi1, rel=1e-5)


def test_a_short_slip_near_the_sliding_threshold_is_not_stepped_over():
    """A lead-rubber point just above its sliding threshold (Pi1 = 7.8e-4): the contents slip for
    0.02 T_p at tau = 0.215, a stick-limit excursion shorter than a step of 1/32 of the elastic period
    (which missed it, Pi1 off by 2.4e-4 relative); the realisation agrees with isoslide.solve to 1e-5."""
    pis = dict(pi2=1.5301694915254236, pi3=1.0, pi4=0.03, pi5=1.0, pi6=0.0, pi7=0.0, pi8=1e-5, pi9=0.2,
               pi10=0.002)
    sol = isoslide.solve(isoslide.Scene(**pis))
    p = S.physical_parameters(pis, 1.34185835, 2.72750898, 79084.98545812)
    r = simulate_si(p, "ricker", t_end=(sol.tau_end + 1.0) * p["T_p"], history=True)
    assert r.pi1 == pytest.approx(sol.pi1, rel=1e-5)
    slipping = r.history.tau[r.history.phase != 0]
    assert slipping.min() == pytest.approx(0.215, abs=1e-3)


def _two_storeys(**over):
    """A bilinear bearing under a two-storey superstructure given floor by floor (kg, N/m), contents on
    floor 1, in SI units."""
    p = dict(a_p=4.0, T_p=0.9, M_b=2e6, T_b=1.8, xi_b=0.1, m_ec=4e5, mu_s=0.0765, mu_k=0.0612, beta=50.0,
             gamma=0.0, g=G, Q_d=4.8e5, D_y=0.016, m_st=0.0, T_s=0.0, xi_s=0.05, floor=1,
             floor_masses=(7e5, 5e5), storey_stiffnesses=(3e8, 1.5e8))
    p.update(over)
    return p


@pytest.mark.slow
def test_storeys_given_floor_by_floor_agree_with_the_reference_peer():
    """Two storeys in kg and N/m, contents on floor 1: Pi1 integrated in SI units equals the
    dimensionless reference peer's Pi1 of ``Scene.from_physical`` of the same building to 1e-8, for
    two realisations of one point (masses, accelerations and times scaled)."""
    p = _two_storeys()
    sc = isoslide.Scene.from_physical(**p)
    assert sc.storeys == 2 and sc.floor == 1 and sc.pi12 > 0.0
    ref = solve_reference_building(sc)
    assert ref.pi1 > 1e-3
    for q in (p, _scaled_storeys(p, mass=3.0, accel=0.5, time=2.0)):
        assert _si(q, ref.tau_end + 1.0) == pytest.approx(ref.pi1, rel=1e-8)


def _scaled_storeys(p, mass, accel, time):
    """:func:`_scaled` for a superstructure given floor by floor (stiffnesses scale as mass/time^2)."""
    q = _scaled(p, mass, accel, time)
    q["floor_masses"] = tuple(m * mass for m in p["floor_masses"])
    q["storey_stiffnesses"] = tuple(k * mass / time ** 2 for k in p["storey_stiffnesses"])
    return q


def test_uniform_storeys_agree_with_the_reference_peer():
    """Three uniform storeys of total mass ``m_st`` and fundamental period ``T_s``, contents on the roof of
    a sliding bearing's building: SI Pi1 equals the reference peer's for the same groups to 1e-8."""
    pis = dict(PAPER, pi3=1.5, pi4=0.1, pi9=0.08, pi11=0.6, pi12=0.3, pi13=0.05)
    ref = solve_reference_building(isoslide.Scene(**pis, storeys=3, floor="roof"))
    assert ref.pi1 > 1e-3
    p = dict(S.physical_parameters(pis, 2.5, 1.1, 7e5, floor="roof"), storeys=3)
    assert _si(p, ref.tau_end + 1.0) == pytest.approx(ref.pi1, rel=1e-8)
    one = solve_reference_building(isoslide.Scene(**pis, floor="roof")).pi1
    assert abs(one / ref.pi1 - 1.0) > 1e-3


@pytest.mark.parametrize("xi", [0.0, 0.07])
def test_chain_matrices_are_the_storeys_with_the_damping_asked_for(xi):
    """``K`` joins storey ``j`` between floors ``j-1`` and ``j``; each fixed-base mode of ``M^-1 K``
    has frequency ``omega_i`` and damping ratio ``xi`` under ``C``, the modes uncoupled by ``C``."""
    m, k = np.array([3e5, 2e5, 1e5]), np.array([4e8, 2e8, 1e8])
    K, C, omega = chain_matrices(m, k, xi)
    assert np.allclose(K, [[6e8, -2e8, 0.0], [-2e8, 3e8, -1e8], [0.0, -1e8, 1e8]], rtol=0.0, atol=1e-6)
    lam, V = np.linalg.eig(np.linalg.solve(np.diag(m), K))
    order = np.argsort(lam)
    lam, V = lam[order], V[:, order]
    V = V / np.sqrt(np.einsum("ji,j,ji->i", V, m, V))
    assert omega == pytest.approx(np.sqrt(lam), rel=1e-12)
    modal = V.T @ C @ V
    assert np.diag(modal) == pytest.approx(2.0 * xi * omega, rel=1e-10, abs=1e-12 * omega[-1])
    assert np.max(np.abs(modal - np.diag(np.diag(modal)))) <= 1e-10 * max(np.max(np.abs(modal)), 1.0)


@pytest.mark.parametrize("over, name", [
    (dict(storey_stiffnesses=None), "storey_stiffnesses"),
    (dict(floor=3), "floor"),
    (dict(T_s=0.1), "T_s"),
    (dict(m_st=1e5), "m_st"),
    (dict(floor_masses=(7e5, -5e5)), r"floor_masses\[1\]"),
    (dict(floor_masses=(7e5, 5e5, 1e5)), "storey_stiffnesses"),
    (dict(floor_masses=(1.5e6, 5e5)), "floor_masses"),
], ids=["stiffnesses-missing", "floor-above-the-roof", "T_s-disagrees", "m_st-disagrees", "negative-mass",
        "lengths-differ", "floors-outweigh-M_b"])
def test_bad_storey_input_is_named(over, name):
    """Floors given inconsistently raise a ValueError naming the parameter."""
    with pytest.raises(ValueError, match=name):
        simulate_si(_two_storeys(**over), "ricker", t_end=0.1)


def test_uniform_storeys_out_of_range_are_named():
    """``storeys`` outside 1 .. 64 raises a ValueError naming it."""
    p = dict(_physical(), storeys=0)
    with pytest.raises(ValueError, match="storeys"):
        simulate_si(p, "ricker", t_end=0.1)


def test_floors_given_one_by_one_make_a_general_building():
    """A superstructure given by its floors (``T_s = 0``) is a flexible building, not the paper's model."""
    assert is_general(_two_storeys(T_b=1.8, Q_d=0.0))
    assert not is_general(_two_storeys(Q_d=0.0, floor_masses=None, storey_stiffnesses=None))
