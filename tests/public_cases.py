"""Public reference values shared by the solver tests.

Copied from the shared reference set (independent event-driven solver, adaptive RK8 per phase,
rtol 1e-12, converged to ~1e-9 relative); the package and the tests never read that file.
"""

# (pi2, pi3, pi4, pi5, pi6, pi7, pi8, pi1, note); pulse = symmetric Ricker.
PI_CASES = [
    (0.15, 0, 0.0, 1.0, 0, 0, 1e-05, 0.054538872938323886, "fixed base, Coulomb"),
    (0.25, 0, 0.0, 1.0, 0, 0, 1e-05, 0.05582108320729039, "fixed base, Coulomb"),
    (0.45, 0, 0.0, 1.0, 0, 0, 1e-05, 0.029266334156860033, "fixed base, Coulomb"),
    (0.6, 0, 0.0, 1.0, 0, 0, 1e-05, 0.01426380926379604, "fixed base, one slip phase"),
    (0.2, 0, 0.0, 0.75, 500, 0, 1e-05, 0.060922851513809745, "fixed base, Stribeck"),
    (0.1, 1.0, 0.1, 1.0, 0, 0, 1e-05, 0.12410347317117676, "resonance, Coulomb"),
    (0.3, 1.0, 0.1, 1.0, 0, 0, 1e-05, 0.1316826017550003, "resonance, Coulomb"),
    (0.2, 2.0, 0.05, 1.0, 0, 0, 1e-05, 0.09837793114060712, "isolated, Coulomb"),
    (0.05, 3.0, 0.2, 1.0, 0, 0, 1e-05, 0.05214987881021767, "long isolation period"),
    (0.15, 0.5, 0.15, 1.0, 0, 0, 1e-05, 0.06171021824036774, "short isolation period"),
    (0.2, 1.0, 0.1, 0.7, 1000, 0, 1e-05, 0.1480298230458512, "resonance, Stribeck"),
    (0.1, 1.0, 0.1, 1.0, 0, 0, 0.1, 0.11924631005935986, "two-way coupling"),
    (0.05, 2.0, 0.1, 1.0, 0, 0, 0.5, 0.07814573309873929, "heavy contents"),
    (0.8, 1.0, 0.1, 1.0, 0, 0, 1e-05, 0.05101886047487468, "amplified floor"),
    (1.0, 3.0, 0.1, 1.0, 0, 0, 1e-05, 0.0, "no sliding: exactly zero"),
]

# Physical cases (SI, g = 9.80665); expected u_max in metres.
PHYSICAL_CASES = [
    (dict(a_p=6.0, T_p=1.2, M_b=800000.0, T_b=2.4, xi_b=0.1, m_ec=800.0, mu_s=0.25, mu_k=0.2,
          beta=200.0, gamma=0.05), 0.22592596746266558),
    (dict(a_p=6.0, T_p=0.8, M_b=2000000.0, T_b=0.8, xi_b=0.15, m_ec=20000.0, mu_s=0.4, mu_k=0.3,
          beta=50.0, gamma=0.02), 0.30628117925119686),
    (dict(a_p=3.0, T_p=1.5, M_b=1000000.0, T_b=3.0, xi_b=0.1, m_ec=1000.0, mu_s=0.15, mu_k=0.15,
          beta=0.0, gamma=0.0), 0.020830347570352046),
]
