"""Tests of the independent event-driven reference solver (isoslide.peers.reference)."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from isoslide.peers.reference import energy_bound, friction_level, solve_reference, stuck_supremum
from isoslide.scene import Scene

from public_cases import PHYSICAL_CASES, PI_CASES  # noqa: E402  (tests/ is on sys.path)

REL = 1e-7


@pytest.mark.parametrize("case", PI_CASES, ids=[f"{i}-{c[-1]}" for i, c in enumerate(PI_CASES)])
def test_public_pi_cases(case):
    pi2, pi3, pi4, pi5, pi6, pi7, pi8, pi1, _ = case
    res = solve_reference(Scene(pi2=pi2, pi3=pi3, pi4=pi4, pi5=pi5, pi6=pi6, pi7=pi7, pi8=pi8))
    assert res.settled
    if pi1 == 0.0:
        assert res.pi1 == 0.0 and res.n_events == 0 and res.pi1_residual == 0.0
    else:
        assert res.pi1 == pytest.approx(pi1, rel=REL)
        assert res.n_events >= 2
        assert abs(res.pi1_residual) <= res.pi1


@pytest.mark.parametrize("kw,u_max", PHYSICAL_CASES)
def test_public_physical_cases(kw, u_max):
    scene = Scene.from_physical(**kw)
    res = solve_reference(scene)
    assert res.settled
    assert res.metres(scene) == pytest.approx(u_max, rel=REL)


@pytest.mark.parametrize("pi2", [0.1, 0.3, 0.5, 0.8, 0.999, 1.0, 1.7])
def test_newmark_rectangular(pi2):
    """Fixed base, Coulomb, rectangular pulse: Pi1 = (1/Pi2 - 1)/2 (Newmark 1965)."""
    res = solve_reference(Scene(pi2=pi2, pi3=0.0, pulse="rectangular"))
    expected = max(0.0, 0.5 * (1.0 / pi2 - 1.0))
    assert res.pi1 == pytest.approx(expected, rel=1e-11, abs=1e-14)
    assert res.settled
    if expected > 0:
        # one slip phase, stopping at tau = 1/Pi2 with u = -Pi1 (ground pushes +, block lags)
        assert res.n_events == 2
        assert res.tau_peak == pytest.approx(1.0 / pi2, rel=1e-10)
        assert res.pi1_residual == pytest.approx(-expected, rel=1e-11)
    else:
        assert res.pi1 == 0.0 and res.n_events == 0


def test_static_friction_is_coulomb_at_mu_s_when_pi6_zero():
    """Pi6 = 0 makes sech = 1: Coulomb friction at the static level Pi2/Pi5."""
    a = solve_reference(Scene(pi2=0.2, pi3=1.0, pi4=0.1, pi5=0.5, pi6=0.0))
    b = solve_reference(Scene(pi2=0.4, pi3=1.0, pi4=0.1))
    assert a.pi1 == pytest.approx(b.pi1, rel=1e-10)


def test_friction_level():
    s = Scene(pi2=0.2, pi3=0.0, pi5=0.5, pi6=100.0, pi7=2.0)
    assert friction_level(s, 0.0) == pytest.approx(0.4)
    assert friction_level(s, 1.0) == pytest.approx(0.2 + 2.0, rel=1e-12)   # sech(100) ~ 0
    v = 0.01
    sh = 1.0 / math.cosh(1.0)
    assert friction_level(s, -v) == pytest.approx(0.4 * sh + 0.2 * (1 - sh) + 0.02, rel=1e-14)


def test_history_is_consistent():
    res = solve_reference(Scene(pi2=0.1, pi3=1.0, pi4=0.1), history=True)
    h = res.history
    assert h is not None and h.tau.size > 10
    assert np.all(np.diff(h.tau) >= 0)
    assert np.max(np.abs(h.u)) <= res.pi1 * (1 + 1e-12)
    assert np.all(h.ud[h.phase == 0] == 0.0)
    assert set(np.unique(h.phase)) <= {-1, 0, 1} and (h.phase != 0).any()
    # while sliding the velocity never opposes the direction of the phase (up to the stop's rounding)
    assert np.all(h.phase * h.ud >= -1e-12)
    assert h.u[-1] == pytest.approx(res.pi1_residual)


def test_undamped_isolation_stops_at_horizon():
    """xi_b = 0: the floor keeps oscillating above the static level; no settling."""
    res = solve_reference(Scene(pi2=0.2, pi3=1.0, pi4=0.0))
    assert not res.settled
    assert res.tau_end == pytest.approx(2.0 + 50.0)


def test_settled_state_cannot_slip_again():
    """After the stop, integrating the free stuck oscillator never exceeds the static level."""
    sc = Scene(pi2=0.2, pi3=2.0, pi4=0.05)
    res = solve_reference(sc, history=True)
    assert res.settled and res.tau_end > sc.pulse.tau_end
    h = res.history
    x, v = h.x[-1], h.xd[-1]
    w, z, m1 = 2 * math.pi / sc.pi3, sc.pi4, 1 + sc.pi8
    t = np.linspace(0.0, 40.0, 40001)
    a = _free_areq(x, v, w, z, m1, t)
    assert np.max(np.abs(a)) <= sc.pi2 * (1 + 1e-9)
    assert energy_bound(x, v, w, z, m1) >= np.max(np.abs(a)) - 1e-12


def _free_areq(x, v, w, z, m1, t):
    """a_req(t) = x''(t) of m1 x'' + 2 z w x' + w^2 x = 0, via the matrix exponential."""
    from scipy.linalg import expm
    A = np.array([[0.0, 1.0], [-w * w / m1, -2 * z * w / m1]])
    out = np.empty(t.size)
    dt = t[1] - t[0]
    step = expm(A * dt)
    s = np.array([x, v])
    for i in range(t.size):
        out[i] = A[1] @ s
        s = step @ s
    return out


@settings(max_examples=40, deadline=None)
@given(x=st.floats(-1, 1), v=st.floats(-1, 1), pi3=st.floats(0.2, 5.0),
       z=st.sampled_from([0.0, 0.02, 0.3, 0.999, 1.0, 1.0000001, 1.5, 8.0]),
       pi8=st.sampled_from([0.0, 0.1, 2.0]))
def test_stuck_supremum_matches_brute_force(x, v, pi3, z, pi8):
    w, m1 = 2 * math.pi / pi3, 1 + pi8
    sup, t_sup = stuck_supremum(x, v, w, z, m1)
    t = np.linspace(0.0, 3.0 * pi3 * (1 + 2 * z), 6001)
    a = _free_areq(x, v, w, z, m1, t)
    brute = np.max(np.abs(a))
    assert sup >= brute * (1 - 1e-7) - 1e-12          # never an under-estimate
    assert sup <= brute * (1 + 1e-3) + 1e-12          # and attained (grid resolution)
    assert t_sup >= 0.0
    # the energy bound is an upper bound of the supremum
    assert sup <= energy_bound(x, v, w, z, m1) * (1 + 1e-12) + 1e-15


def test_mirror_symmetry():
    """Reversing the pulse mirrors the response: same Pi1, opposite residual."""
    from isoslide.pulses import sampled
    tau = np.linspace(-2.0, 2.0, 801)
    p = (1 - 2 * math.pi**2 * tau**2) * np.exp(-math.pi**2 * tau**2)
    kw = dict(pi2=0.2, pi3=1.0, pi4=0.1)
    a = solve_reference(Scene(**kw, pulse=sampled(p, tau[1] - tau[0], tau0=-2.0)))
    b = solve_reference(Scene(**kw, pulse=sampled(-p, tau[1] - tau[0], tau0=-2.0)))
    assert a.pi1 == pytest.approx(b.pi1, rel=1e-10)
    assert a.pi1_residual == pytest.approx(-b.pi1_residual, rel=1e-9)
