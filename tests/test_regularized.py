"""Tests of the paper's stiff-spring (bilinear) regularization (isoslide.peers.regularized).

The regularized model is an approximation: these tests check that it converges
to the exact stick-slip values (public reference values, copied here) as the
stiffness K = k_r T_p^2 / m_EC grows, at the expected rate.
"""

import math

import numpy as np
import pytest

from isoslide.peers.regularized import solve_regularized
from isoslide.scene import Scene

# (pi2, pi3, pi4, pi5, pi6, pi7, pi8) -> exact Pi1 (public reference values, Ricker pulse)
RESONANCE_COULOMB = ((0.1, 1.0, 0.1, 1.0, 0, 0, 1e-05), 0.12410347317117676)
ONE_SLIP = ((0.6, 0, 0.0, 1.0, 0, 0, 1e-05), 0.01426380926379604)
FIXED_COULOMB = ((0.15, 0, 0.0, 1.0, 0, 0, 1e-05), 0.054538872938323886)
RESONANCE_STRIBECK = ((0.2, 1.0, 0.1, 0.7, 1000, 0, 1e-05), 0.1480298230458512)
TWO_WAY = ((0.1, 1.0, 0.1, 1.0, 0, 0, 0.1), 0.11924631005935986)
NO_SLIDING = ((1.0, 3.0, 0.1, 1.0, 0, 0, 1e-05), 0.0)


def _scene(pis, pulse="ricker"):
    pi2, pi3, pi4, pi5, pi6, pi7, pi8 = pis
    return Scene(pi2=pi2, pi3=pi3, pi4=pi4, pi5=pi5, pi6=pi6, pi7=pi7, pi8=pi8, pulse=pulse)


def _errors(case, stiffnesses, **kw):
    pis, exact = case
    sc = _scene(pis)
    out = []
    for K in stiffnesses:
        r = solve_regularized(sc, stiffness=K, **kw)
        assert r.settled
        out.append((r.pi1 - exact) / exact)
    return np.array(out)


def test_converges_like_inverse_sqrt_stiffness():
    """Resonance, Coulomb: direct reversals -> error ~ K^-1/2 (factor sqrt(10) per decade)."""
    err = _errors(RESONANCE_COULOMB, [1e4, 1e5, 1e6])
    assert np.all(err > 0)                      # the spring over-estimates Pi1
    ratios = err[:-1] / err[1:]
    assert np.all(ratios > 2.0) and np.all(ratios < 5.0), err
    assert err[-1] < 2e-3


def test_smooth_single_slip_converges_like_inverse_stiffness():
    """One smooth slip phase (no reversal, no step in p): error ~ 1/K."""
    err = _errors(ONE_SLIP, [1e4, 1e5])
    assert abs(err[1]) < 4e-3
    assert abs(err[0] / err[1]) > 6.0, err


def test_newmark_rectangular():
    """Rectangular pulse, fixed base: approaches Newmark's (1/Pi2 - 1)/2."""
    pi2 = 0.3
    exact = 0.5 * (1.0 / pi2 - 1.0)
    errs = []
    for K in (1e4, 1e5):
        r = solve_regularized(Scene(pi2=pi2, pi3=0.0, pulse="rectangular"), stiffness=K)
        assert r.settled and r.pi1_residual < 0
        errs.append(abs(r.pi1 - exact) / exact)
    assert errs[1] < errs[0] / 2 and errs[1] < 3e-3


def test_no_sliding_leaves_only_elastic_deflection():
    pis, _ = NO_SLIDING
    K = 1e5
    r = solve_regularized(_scene(pis), stiffness=K)
    assert r.settled
    assert 0.0 <= r.pi1 <= pis[0] / pis[3] / K * (1 + 1e-6)   # |u| <= phi(0)/K
    assert r.n_events == 0


def test_history_and_cost_fields():
    pis, _ = RESONANCE_COULOMB
    r = solve_regularized(_scene(pis), stiffness=1e4, history=True)
    h = r.history
    assert h.tau.size == r.n_steps + 1 or h.tau.size >= r.n_steps
    assert np.max(np.abs(h.u)) <= r.pi1 * (1 + 1e-12)
    assert (h.phase != 0).any() and r.n_events >= 2
    slide = h.phase != 0
    assert np.all(h.phase[slide] * h.ud[slide] > 0.0)   # plastic flow in the direction of u'
    assert r.nfev > r.n_steps > 0 and r.njev > 0
    assert r.method == "regularized" and r.integrator == "Radau" and r.stiffness == 1e4
    assert math.isclose(h.u[-1], r.pi1_residual)


def test_bdf_agrees_with_radau():
    pis, _ = RESONANCE_COULOMB
    a = solve_regularized(_scene(pis), stiffness=1e4, method="Radau")
    b = solve_regularized(_scene(pis), stiffness=1e4, method="BDF")
    # micro-slips from the spring ringing make Pi1 slightly method dependent (~1e-5),
    # far below the regularization error itself (~1e-2 at K = 1e4)
    assert a.pi1 == pytest.approx(b.pi1, rel=5e-5)


@pytest.mark.parametrize("bad", [0.0, -1.0, math.inf, math.nan])
def test_rejects_bad_stiffness(bad):
    with pytest.raises(ValueError, match="stiffness"):
        solve_regularized(_scene(RESONANCE_COULOMB[0]), stiffness=bad)


def test_rejects_lsoda():
    with pytest.raises(ValueError, match="LSODA"):
        solve_regularized(_scene(RESONANCE_COULOMB[0]), method="LSODA")


@pytest.mark.slow
@pytest.mark.parametrize("case", [FIXED_COULOMB, RESONANCE_STRIBECK, TWO_WAY],
                         ids=["fixed-coulomb", "resonance-stribeck", "two-way"])
def test_convergence_rate_slow(case):
    """Error vs K over 1e4..1e7: monotone, log-log slope close to -1/2."""
    Ks = np.array([1e4, 1e5, 1e6, 1e7])
    err = _errors(case, Ks)
    assert np.all(err > 0)
    assert np.all(np.diff(err) < 0), err
    slope = np.polyfit(np.log10(Ks), np.log10(err), 1)[0]
    assert -0.65 < slope < -0.35, (slope, err)
    assert err[-1] < 2e-3


@pytest.mark.slow
def test_physical_case_slow():
    kw = dict(a_p=6.0, T_p=1.2, M_b=800000.0, T_b=2.4, xi_b=0.1, m_ec=800.0, mu_s=0.25,
              mu_k=0.2, beta=200.0, gamma=0.05)
    sc = Scene.from_physical(**kw)
    r = solve_regularized(sc, stiffness=1e6)
    assert r.settled
    assert r.metres(sc) == pytest.approx(0.22592596746266558, rel=5e-3)
