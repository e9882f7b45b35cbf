"""Exact propagation of a linearly isolated flexible building (isoslide.engine.exponential): its
sub-step against the matrix exponential, its pulse polynomial against the pulse, and whole solves
against the Runge-Kutta kernel of the general building."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.linalg import expm

from isoslide import Scene, solve
from isoslide.engine import exponential as ex
from isoslide.engine import free_phase
from isoslide.engine.system import assemble
from isoslide.pulses import get_pulse, sampled

FLEX = dict(pi11=0.6, pi12=0.2, pi13=0.02)
SCENES = {
    "one storey, base": dict(pi2=0.1, pi3=2.0, pi4=0.05, pi8=0.01, **FLEX),
    "one storey, roof": dict(pi2=0.2, pi3=2.0, pi4=0.05, pi8=0.01, **FLEX, floor="roof"),
    "heavy contents, roof": dict(pi2=0.15, pi3=3.0, pi4=0.1, pi8=0.5, **FLEX, floor="roof"),
    "one-way contents": dict(pi2=0.1, pi3=2.0, pi4=0.05, pi8=0.0, **FLEX, floor="roof"),
    "static above kinetic": dict(pi2=0.1, pi3=2.0, pi4=0.05, pi5=0.7, pi6=0.0, pi8=0.01, **FLEX, floor="roof"),
    "two storeys, floor 1": dict(pi2=0.1, pi3=2.0, pi4=0.05, pi8=0.01, **FLEX, storeys=2, floor=1),
    "three storeys, roof": dict(pi2=0.05, pi3=1.5, pi4=0.2, pi8=0.02, **FLEX, storeys=3, floor="roof"),
    "rectangular pulse": dict(pi2=0.3, pi3=2.0, pi4=0.05, pi8=0.01, **FLEX, floor="roof", pulse="rectangular"),
    "Makris type B": dict(pi2=0.2, pi3=2.0, pi4=0.05, pi8=0.01, **FLEX, floor="roof", pulse="makris_b"),
    "Mavroeidis-Papageorgiou": dict(pi2=0.1, pi3=2.5, pi4=0.05, pi8=0.01, **FLEX, pulse="mavroeidis_papageorgiou"),
    "eight storeys, roof": dict(pi2=0.05, pi3=2.0, pi4=0.05, pi8=0.01, **FLEX, storeys=8, floor="roof"),
    "five storeys, heavy contents on floor 2": dict(pi2=0.1, pi3=2.5, pi4=0.05, pi8=1.0, **FLEX, storeys=5, floor=2,
                                                    pulse="makris_b"),
    "antisymmetric Ricker, undamped storey": dict(pi2=0.1, pi3=2.0, pi4=0.05, pi8=0.01, pi11=0.6, pi12=0.2,
                                                  pi13=0.0, floor="roof", pulse="antisymmetric_ricker"),
}


@pytest.mark.parametrize("name", list(SCENES))
def test_the_exact_propagation_gives_the_runge_kutta_kernels_answer(name):
    """Pi1 of the exact propagation equals the integrated general building's (the kernel a solve that
    records a history runs) to 1e-9 at rtol = 1e-10, with the same transitions, and the solve says
    which propagation ran."""
    sc = Scene(**SCENES[name])
    exact = solve(sc, rtol=1e-10)
    integrated = solve(sc, rtol=1e-10, history=True)
    assert exact.facets.propagation == "exponential"
    assert integrated.facets.propagation == "integrated"
    assert exact.model == integrated.model
    assert exact.n_events == integrated.n_events
    assert exact.settled and integrated.settled
    assert exact.pi1 == pytest.approx(integrated.pi1, rel=1e-9, abs=1e-13)
    assert exact.tau_peak == pytest.approx(integrated.tau_peak, abs=1e-7)
    assert exact.pi1_residual == pytest.approx(integrated.pi1_residual, rel=1e-8, abs=1e-12)


@pytest.mark.parametrize("name", ["one storey, roof", "three storeys, roof", "rectangular pulse"])
def test_the_tolerance_bounds_the_exact_propagations_error(name):
    """At rtol = 1e-3 .. 1e-8 Pi1 is within rtol of the answer at rtol = 1e-12."""
    sc = Scene(**SCENES[name])
    ref = solve(sc, rtol=1e-12).pi1
    for rtol in (1e-3, 1e-6, 1e-8):
        assert abs(solve(sc, rtol=rtol).pi1 - ref) <= rtol * ref


def test_histories_and_the_full_model_are_integrated():
    """A solve that records a history runs the Runge-Kutta kernel, with the exact propagation's answer."""
    sc = Scene(**SCENES["one storey, roof"])
    hist = solve(sc, history=True)
    assert hist.facets.propagation == "integrated" and hist.history is not None
    assert hist.pi1 == pytest.approx(solve(sc).pi1, rel=1e-7)


@pytest.mark.parametrize("kw", [
    dict(pi9=0.05),                                     # a friction pendulum: the bearing slides
    dict(pi9=0.05, pi10=0.005),                         # a lead-rubber bearing yields
    dict(pi5=0.7, pi6=20.0),                            # friction that depends on speed
    dict(pi17=0.5, pulse_z="ricker"),                   # vertical motion
    dict(pulse=sampled(np.array([0.0, 1.0, -0.5, 0.0]), 0.25)),   # a record
], ids=["pendulum", "lead-rubber", "stribeck", "vertical", "record"])
def test_scenes_outside_the_linear_class_are_integrated(kw):
    """Only a linear isolator, speed-independent friction, no vertical motion and a pulse's formula
    are propagated exactly; every other flexible building is integrated."""
    sc = Scene(**{**SCENES["one storey, roof"], **kw})
    system = assemble(sc, pi8=sc.pi8, coulomb=sc.rate_independent)
    assert system.linear is None
    assert solve(sc).facets.propagation == "integrated"


def _augmented(A, b, e, d):
    """The state after ``d`` of ``z' = A z + b sum_l e_l (t/d)^l`` from ``z0``, as a matrix exponential.

    The monomials ``w_l = (t/d)^l`` obey ``w_l' = (l/d) w_{l-1}`` with ``w(0) = (1, 0, ..)``.
    """
    m, q = A.shape[0], e.size
    M = np.zeros((m + q, m + q))
    M[:m, :m] = A
    M[:m, m:] = np.outer(b, e)
    for l in range(1, q):
        M[m + l, m + l - 1] = l / d
    return expm(M * d)


def test_a_sub_step_is_the_matrix_exponential_of_the_forced_system():
    """The modal sub-step with a polynomial pulse and a constant force equals expm of the augmented
    system, for fractions of a sub-step too (the root searches' trials)."""
    rng = np.random.default_rng(5)
    m = 6
    K = rng.normal(size=(m // 2, m // 2))
    K = K @ K.T + 3.0 * np.eye(m // 2)
    A = np.block([[np.zeros((m // 2, m // 2)), np.eye(m // 2)], [-K, -0.1 * np.eye(m // 2)]])
    lam, V, W, cond, grows = free_phase.decompose(A)
    assert not grows and cond < 1e6
    b = rng.normal(size=m)
    g = rng.normal(size=m)
    e = rng.normal(size=ex.DEGREE + 1)
    z0 = rng.normal(size=m)
    d = ex.THETA / np.max(np.abs(lam))
    beta, gam = W @ b.astype(complex), W @ g.astype(complex)
    psi = np.zeros((m, ex.DEGREE + 2), dtype=complex)
    out = np.zeros(m, dtype=complex)
    for r in (1.0, 0.37, 1e-3):
        ex._psi(lam, r * d, psi)
        for s in (1.0, -1.0):
            ex._advance(W @ z0.astype(complex), lam, beta, gam, s, e, r, psi, out)
            got = (V @ out).real
            # the forcing b p + s g: g as a constant pulse of its own
            E = _augmented(np.block([[A, g[:, None]], [np.zeros((1, m + 1))]]),
                           np.append(b, 0.0), e * r ** np.arange(e.size), r * d)
            want = (E @ np.concatenate([z0, [s], [1.0], np.zeros(e.size - 1)]))[:m]
            assert np.max(np.abs(got - want)) <= 1e-12 * max(1.0, np.max(np.abs(want)))


@pytest.mark.parametrize("pulse", ["ricker", "antisymmetric_ricker", "makris_cn", "mavroeidis_papageorgiou"])
def test_the_pulse_polynomials_error_estimate_bounds_its_error(pulse):
    """On steps of several lengths the Chebyshev interpolant's largest error is within 10 times its
    estimate (the two last coefficients), and the local monomials reproduce it on every sub-step."""
    p = get_pulse(pulse)
    c = np.zeros(ex.DEGREE + 1)
    e, t0, t1, t2 = (np.zeros(ex.DEGREE + 1) for _ in range(4))
    for tau, h in ((-1.0, 0.05), (-0.3, 0.2), (0.1, 0.6)):
        est = ex._chebyshev(p.code, p.param_array, tau, h, c)
        t = tau + h * np.linspace(0.0, 1.0, 401)
        exact = np.array([p.accel(x) for x in t])
        cheb = np.polynomial.chebyshev.chebval(2.0 * (t - tau) / h - 1.0, c)
        assert np.max(np.abs(cheb - exact)) <= 10.0 * est + 1e-15
        nsub = 5
        for i in range(nsub):
            ex._local(c, -1.0 + 2.0 * i / nsub, 2.0 / nsub, e, t0, t1, t2)
            r = np.linspace(0.0, 1.0, 11)
            x = -1.0 + 2.0 * (i + r) / nsub
            assert np.allclose(np.polyval(e[::-1], r), np.polynomial.chebyshev.chebval(x, c), rtol=0.0, atol=1e-13)


def test_the_fastest_modes_are_bounded_where_their_vibration_is_small():
    """Where the fastest modes barely vibrate, long sub-steps bound them instead of following them: a
    stiff eight-storey building takes fewer than a fifth of the sub-steps that |lambda| d <= THETA
    on its fastest mode needs over the same span, and as many transitions as the Runge-Kutta
    kernel."""
    sc = Scene(**SCENES["eight storeys, roof"])
    exact = solve(sc)
    lam = np.abs(assemble(sc, pi8=sc.pi8, coulomb=True).linear[1])
    span = exact.tau_end - sc.pulse.tau_start
    assert exact.n_steps < span * np.max(lam) / ex.THETA / 5.0
    assert exact.n_events == solve(sc, history=True).n_events


def _phi_reference(z, q):
    """``phi_0 .. phi_q`` at ``z`` from the matrix exponential of the augmented Jordan block."""
    M = np.zeros((q + 1, q + 1), dtype=complex)
    M[0, 0] = z
    for j in range(q):
        M[j, j + 1] = 1.0
    return expm(M)[0]


@pytest.mark.parametrize("modulus", [0.3, 0.5, 1.0, 1.5, 2.0, 3.9, 4.1, 7.9, 30.0, 300.0, 3000.0])
def test_the_long_sub_steps_phi_functions_equal_the_matrix_exponentials(modulus):
    """The forcing weights of a sub-step of any length (l! d phi_{l+1}(lambda d), and exp(lambda d))
    equal those of the augmented matrix exponential to 1e-13 of their size, for lightly and heavily
    damped modes, on both sides of the switches between series and recurrences and at the moduli
    where the series' term count changes."""
    q = ex.DEGREE + 1
    d = 0.125
    for zeta in (0.0, 0.02, 0.3, 1.0):
        lam = np.array([modulus * complex(-zeta, math.sqrt(1.0 - zeta * zeta)) / d])
        psi = np.zeros((1, q + 1), dtype=complex)
        ex._psi(lam, d, psi)
        ref = _phi_reference(lam[0] * d, q)
        want = np.array([math.factorial(l) * d * ref[l + 1] for l in range(q)] + [ref[0]])
        scale = np.array([math.factorial(l) * d * abs(ref[l + 1]) for l in range(q)] + [abs(ref[0])])
        assert np.all(np.abs(psi[0] - want) <= 5e-14 * scale)
