"""Code linearisation of isolators (isoslide.studies.design) against hand calculations."""

import math

import pytest

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
