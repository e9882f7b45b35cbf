"""Code linearisation of isolators (isoslide.studies.design) against hand calculations."""

import math

import pytest

from isoslide.model import tfp
from isoslide.studies import design

G = 9.80665


def test_bilinear_effective_properties_by_hand():
    """k_d = 1000 N/m, Q = 50 N, D = 0.25 m, D_y = 0.05 m: K_eff = 1000 + 50/0.25 = 1200 N/m,
    beta_eff = 2 * 50 * 0.20 / (pi * 1200 * 0.0625) = 20 / 235.619 = 0.0848826."""
    K, beta = design.effective_bilinear(1000.0, 50.0, 0.25, 0.05)
    assert K == pytest.approx(1200.0, rel=1e-12)
    assert beta == pytest.approx(0.0848826, rel=1e-6)


def test_friction_pendulum_effective_properties_by_hand():
    """W = 1 MN, R = 2 m, mu = 0.06, D = 0.3 m: K_eff = 500 kN/m + 200 kN/m = 700 kN/m,
    beta_eff = 0.12 / (pi (0.06 + 0.15)) = 0.181891."""
    K, beta = design.effective_friction_pendulum(2.0, 0.06, 0.3, 1.0e6)
    assert K == pytest.approx(7.0e5, rel=1e-12)
    assert beta == pytest.approx(0.181891, rel=1e-5)


def test_friction_pendulum_is_the_rigid_plastic_bilinear_bearing():
    W, R, mu, D = 2.0e6, 2.5, 0.05, 0.25
    assert design.effective_friction_pendulum(R, mu, D, W) == pytest.approx(
        design.effective_bilinear(W / R, mu * W, D, 0.0), rel=1e-14)


def test_friction_pendulum_design_by_hand():
    """M = 1e6 kg, T_eff = 3 s, beta_eff = 0.2, D = 0.3 m: K_eff = M (2 pi/3)^2 = 4.38649 MN/m;
    mu = pi * 0.2 * 0.3 * K_eff / (2 M g) = 0.0421568; 1/R = K_eff/W - mu/D = 0.447298 - 0.140523,
    R = 3.25972 m (T_b = 2 pi sqrt(R/g) = 3.62251 s)."""
    iso = design.design_friction_pendulum(1.0e6, 3.0, 0.2, 0.3)
    assert iso.system == "friction_pendulum" and iso.D_y == 0.0 and iso.xi_b == 0.0
    assert iso.mu(G) == pytest.approx(0.0421568, rel=1e-5)
    assert iso.radius(G) == pytest.approx(3.25972, rel=1e-5)
    assert iso.T_b == pytest.approx(2.0 * math.pi * math.sqrt(iso.radius(G) / G), rel=1e-12)
    assert iso.T_b == pytest.approx(3.62251, rel=1e-5)
    K, beta = design.effective_friction_pendulum(iso.radius(G), iso.mu(G), 0.3, 1.0e6 * G)
    assert design.effective_period(1.0e6, K) == pytest.approx(3.0, rel=1e-12)
    assert beta == pytest.approx(0.2, rel=1e-12)


@pytest.mark.parametrize("T_eff, beta_eff, D, D_y", [(2.5, 0.15, 0.2, 0.01), (3.0, 0.25, 0.35, 0.03),
                                                      (4.0, 0.05, 0.5, 0.2)])
def test_all_three_systems_share_the_target_at_the_design_displacement(T_eff, beta_eff, D, D_y):
    systems = design.design(8.0e5, T_eff, beta_eff, D, D_y)
    assert tuple(systems) == design.SYSTEMS
    for name, iso in systems.items():
        K, beta = iso.effective(D)
        assert design.effective_period(8.0e5, K) == pytest.approx(T_eff, rel=1e-12), name
        assert beta == pytest.approx(beta_eff, rel=1e-12), name
    lin, bil, fp = systems.values()
    assert lin.Q_d == 0.0 and lin.T_b == pytest.approx(T_eff, rel=1e-12)
    assert bil.D_y == D_y and fp.D_y == 0.0
    # the longer the elastic branch, the more strength the same damping needs, and the softer the
    # post-yield branch that keeps K_eff
    assert bil.Q_d > fp.Q_d > 0.0 and bil.T_b > fp.T_b


def test_lead_rubber_bearing_by_hand():
    """M = 1e6 kg, T_eff = 3 s, beta_eff = 0.2, D = 0.3 m, D_y = 0.02 m:
    Q = pi * 0.2 * K_eff * 0.09 / (2 * 0.28) = 442.947 kN, k_d = K_eff - Q/D = 2.91000 MN/m."""
    iso = design.design_bilinear(1.0e6, 3.0, 0.2, 0.3, 0.02)
    assert iso.Q_d == pytest.approx(442.947e3, rel=1e-5)
    assert iso.k_d == pytest.approx(2.91000e6, rel=1e-5)
    params = iso.scene_parameters()
    assert set(params) == {"M_b", "T_b", "xi_b", "Q_d", "D_y"} and params["D_y"] == 0.02


@pytest.mark.parametrize("call, name", [
    (lambda: design.design_bilinear(1e6, 3.0, 0.2, 0.3, 0.3), "D_y"),
    (lambda: design.design_bilinear(1e6, 3.0, 0.6, 0.3, 0.02), "beta_eff"),
    (lambda: design.design_linear(1e6, -1.0, 0.1), "T_eff"),
    (lambda: design.design_linear(1e6, 3.0, 0.7), "beta_eff"),
    (lambda: design.effective_bilinear(1000.0, 50.0, 0.05, 0.05), "D"),
    (lambda: design.effective_friction_pendulum(0.0, 0.05, 0.3, 1e6), "R"),
    (lambda: design.design(1e6, 3.0, 0.2, 0.3, 0.0), "D_y"),
])
def test_bad_input_names_the_parameter(call, name):
    with pytest.raises(ValueError, match=rf"^{name} = .*allowed range"):
        call()


# ----------------------------------------------------------------------------------------------
# the triple friction pendulum's design rule
# ----------------------------------------------------------------------------------------------


@pytest.mark.parametrize("T_eff, beta_eff, D, lam, a, c, sigma, rho", [
    (3.0, 0.2, 0.3, 0.2, 0.3, 1.5, 1.25, 1.6),       # the bearing study's
    (3.0, 0.2, 0.3, 0.2, 0.3, 1.0, 1.05, 1.3),       # mu2 = mu3: no regime II; stiffening just past D
    (2.5, 0.15, 0.2, 0.15, 0.2, 2.0, 1.5, 2.5),
    (4.0, 0.25, 0.5, 0.25, 0.4, 1.2, 1.1, 1.4),
])
def test_triple_pendulum_meets_the_targets_at_d_in_regime_three(T_eff, beta_eff, D, lam, a, c, sigma, rho):
    """The closed forms of isoslide.model.tfp (backbone force, loop area) give T_eff and beta_eff back at D."""
    iso = design.design_triple_friction_pendulum(8.0e5, T_eff, beta_eff, D, lam, a, c, sigma, rho)
    (L1, L2, L3), (mu1, mu2, mu3), (_d1, d2, d3) = iso.L, iso.mu, iso.d
    assert L2 == L3 and d2 == d3 and L1 == pytest.approx(lam * L2, rel=1e-14)
    assert mu1 == pytest.approx(a * mu2, rel=1e-14) and mu3 == pytest.approx(c * mu2, rel=1e-14)
    K, beta = iso.effective(D)
    assert design.effective_period(8.0e5, K) == pytest.approx(T_eff, rel=1e-12)
    assert beta == pytest.approx(beta_eff, rel=1e-12)
    b = iso.boundaries()
    assert iso.regime(D) == 3 and b.u_2star < D <= b.u_dr1
    assert b.u_dr1 == pytest.approx(sigma * D, rel=1e-12) and iso.capacity == pytest.approx(rho * D, rel=1e-12)
    assert iso.T_b == pytest.approx(2.0 * math.pi * math.sqrt((L2 + L3) / G), rel=1e-14)
    # the same isolator to Scene.from_physical: isoslide.triple_friction_pendulum of it
    params = iso.scene_parameters()
    assert params["M_b"] == 8.0e5 and params["xi_b"] == 0.0 and params["D_y"] == 0.0
    assert params["Q_d"] == pytest.approx(mu2 * 8.0e5 * G, rel=1e-14) and params["tfp"][4:] == iso.d


def test_triple_pendulum_loop_area_in_regime_three_by_the_module_formula():
    """E/W = 4 (mu_e D - e0), e0 = u** (mu3 - mu2) + u* (mu3 - mu1) - u**^2/(2 L), against the loop's area."""
    b = tfp.TripleFrictionPendulum((0.4, 2.0, 2.0), (0.015, 0.05, 0.08), (0.06, 0.3, 0.3))
    bd = tfp.regime_boundaries(b)
    L = 2.0
    for D in (0.2, 0.3, bd.u_dr1):
        assert bd.u_2star < D <= bd.u_dr1
        mu_e = 0.08 - bd.u_2star / (2.0 * L)
        e0 = bd.u_2star * (0.08 - 0.05) + bd.u_star * (0.08 - 0.015) - bd.u_2star**2 / (2.0 * L)
        assert tfp.dissipated_energy(b, D) == pytest.approx(4.0 * (mu_e * D - e0), rel=1e-12)
        assert tfp.force(b, D)[0] == pytest.approx(D / (2.0 * L) + mu_e, rel=1e-12)


def test_triple_pendulum_of_equal_frictions_is_the_single_pendulum_of_radius_2l():
    """mu1 = mu2 = mu3: the inner slider never slides first and the design is the single pendulum's."""
    fp = design.design_friction_pendulum(1.0e6, 3.0, 0.2, 0.3)
    iso = design.design_triple_friction_pendulum(1.0e6, 3.0, 0.2, 0.3, 0.2, 1.0, 1.0, 1.2, 1.5)
    assert iso.mu == pytest.approx((fp.mu(G),) * 3, rel=1e-12)
    assert iso.L[1] + iso.L[2] == pytest.approx(fp.radius(G), rel=1e-12)
    assert iso.boundaries().u_2star == 0.0


@pytest.mark.parametrize("kw, message", [
    ({"beta_eff": 0.6}, r"^beta_eff = 0\.6 is out of range for a triple friction pendulum"),
    ({"beta_eff": 0.0}, r"^beta_eff = 0\.0 is out of range for a triple friction pendulum"),
    ({"capacity": 1.3}, r"^capacity = 1\.3 is out of range: regime IV of this bearing ends at 1\.39"),
    ({"capacity": 1.2}, r"^capacity = 1\.2 is out of range; allowed range"),
    ({"mu1_ratio": 0.0}, r"^mu1_ratio = 0\.0 is out of range; allowed range"),
    ({"mu3_ratio": 0.9}, r"^mu3_ratio = 0\.9 is out of range; allowed range"),
    ({"stiffening": 1.0}, r"^stiffening = 1\.0 is out of range; allowed range"),
    ({"D": 0.5, "beta_eff": 0.16, "inner_radius": 0.8, "mu1_ratio": 0.5, "mu3_ratio": 2.2, "capacity": 20.0},
     r"^D = 0\.5 m is not in regime III"),
])
def test_bad_triple_pendulum_design_names_the_parameter(kw, message):
    args = {"M": 1.0e6, "T_eff": 3.0, "beta_eff": 0.2, "D": 0.3, "inner_radius": 0.2, "mu1_ratio": 0.3,
            "mu3_ratio": 1.5, "stiffening": 1.25, "capacity": 1.6, **kw}
    with pytest.raises(ValueError, match=message):
        design.design_triple_friction_pendulum(**args)
