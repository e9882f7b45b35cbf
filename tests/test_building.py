"""The general building (isoslide.engine.building, isoslide.engine.building_kernel) against the paper's model,
its limits, a closed form, the energy balance, symmetry and similarity."""

from __future__ import annotations

import math

import numpy as np
import pytest

import isoslide
from isoslide import Scene, solve
from isoslide.engine import building
from isoslide.engine import building_kernel as bk
from isoslide.pulses import sampled
from isoslide.scene import G_STANDARD
from isoslide.engine.system import horizon_end
from isoslide.solver import base_atol, integrator_rtol

PAPER_SCENES = [
    Scene(pi2=0.2, pi3=1.0, pi4=0.1),
    Scene(pi2=0.1, pi3=2.0, pi4=0.05, pi8=0.5),
    Scene(pi2=0.1, pi3=1.5, pi4=0.1, pi5=0.5, pi6=300.0, pi7=0.5, pi8=0.2),
    Scene(pi2=0.3, pi3=0.0, pi5=0.6, pi6=100.0),
    Scene(pi2=0.05, pi3=3.0, pi4=0.0, pi8=1.0, pulse="makris_b"),
]
BASE = dict(pi2=0.15, pi3=2.5, pi4=0.05, pi8=0.01)
FLEX = dict(pi11=0.5, pi12=0.3, pi13=0.05)


def run_kernel(sc: Scene, rtol: float = 1e-6):
    """The building kernel on ``sc`` with the solver's tolerances (no reduction, no refinement)."""
    P = building.parameters(sc)
    pu = sc.pulse
    irt = integrator_rtol(sc, rtol)
    return bk.run(P, pu.code, pu.param_array, pu.breakpoint_array, pu.tau_start, pu.tau_end, horizon_end(sc, 200.0),
                  0.15, building.free_step(sc), irt, base_atol(sc, irt), 0, 1e-4, True, 10 ** 7,
                  *building.modal_data(sc, P))


@pytest.mark.parametrize("sc", PAPER_SCENES, ids=lambda s: f"pi3={s.pi3:g}-pi6={s.pi6:g}")
def test_the_building_kernel_on_a_paper_scene_is_the_paper_kernel(sc):
    """A linear isolator with a rigid superstructure: same Pi1, transitions and settling time."""
    ints, floats, _ = run_kernel(sc)
    ref = solve(sc, model="full")
    assert floats[bk.F_UMAX] == pytest.approx(ref.pi1, rel=1e-8)
    assert ints[bk.R_EVENTS] == ref.n_events and bool(ints[bk.R_SETTLED]) == ref.settled
    # the building kernel's modal bound is sharper than the paper kernel's energy bound: it settles no later
    assert floats[bk.F_TEND] <= ref.tau_end * (1.0 + 1e-9)


def test_the_new_groups_at_zero_are_the_paper_model():
    """pi9..pi13 = 0 (and the roof of a rigid superstructure) give the paper solver's answer, bit for bit."""
    for sc in PAPER_SCENES:
        a = solve(sc)
        b = solve(Scene(**{**sc.pis(), "pulse": sc.pulse, "floor": "roof"}))
        assert (a.pi1, a.model, a.n_steps) == (b.pi1, b.model, b.n_steps)


def test_bilinear_bearing_approaches_the_sliding_bearing_as_the_yield_displacement_vanishes():
    """pi10 -> 0: the bilinear bearing tends to the sliding bearing with true stick, at order 1/2.

    Its elastic branch rings at ``sqrt(k_e) ~ (Pi9 / Pi10)^(1/2)`` with floor-acceleration spikes
    that do not shrink, so the contents' response converges only like ``sqrt(Pi10)`` (a factor
    ``sqrt(10)`` per decade): the reason a stick displacement must be tuned in OpenSees.
    """
    target = solve(Scene(**BASE, pi9=0.05), model="full").pi1
    errs = [abs(solve(Scene(**BASE, pi9=0.05, pi10=d), model="full").pi1 - target) / target
            for d in (1e-3, 1e-4, 1e-5, 1e-6)]
    assert all(2.5 < a / b < 4.5 for a, b in zip(errs[:-1], errs[1:], strict=True)), errs
    target = solve(Scene(**BASE, pi9=0.3), model="full").pi1
    errs = [abs(solve(Scene(**BASE, pi9=0.3, pi10=d), model="full").pi1 - target) / target
            for d in (1e-3, 1e-5, 1e-7)]
    assert errs[2] < errs[1] < errs[0] and errs[2] < 5e-3, errs


def test_weak_isolator_approaches_the_linear_isolator():
    """pi9 -> 0 for both bearings: the error against the paper's linear isolator shrinks in proportion."""
    target = solve(Scene(**BASE)).pi1
    for pi10 in (0.0, 0.01):
        errs = [abs(solve(Scene(**BASE, pi9=q, pi10=pi10), model="full").pi1 - target) / target
                for q in (1e-3, 1e-4, 1e-5)]
        assert errs[1] < errs[0] / 5.0 and errs[2] < errs[1] / 5.0, errs
        assert errs[-1] < 1e-4, errs


@pytest.mark.parametrize("floor", ["base", "roof"])
def test_stiff_superstructure_approaches_the_rigid_one(floor):
    """pi12 -> 0: contents on the base or the roof see the paper's rigid building."""
    target = solve(Scene(**BASE)).pi1
    errs = [abs(solve(Scene(**BASE, pi11=0.5, pi12=t, pi13=0.05, floor=floor)).pi1 - target) / target
            for t in (0.1, 0.03, 0.01)]
    assert errs[1] < errs[0] and errs[2] < errs[1], errs
    assert errs[-1] < 2e-3, errs


def test_a_sliding_bearing_that_never_slips_gives_the_fixed_base_answer():
    """Full integration of a strong sliding bearing equals the fixed base; the planner proves it."""
    fixed = solve(Scene(pi2=BASE["pi2"], pi3=0.0))
    sc = Scene(**BASE, pi9=2.0)
    full = solve(sc, model="full")
    assert full.pi1 == pytest.approx(fixed.pi1, rel=1e-9)
    assert full.model == "sliding-bearing+stribeck"   # "full" evaluates the Stribeck terms
    auto = solve(sc)
    assert auto.model == "bearing-stuck+fixed-base+coulomb" and auto.pi1 == fixed.pi1


def test_a_bilinear_bearing_that_never_yields_runs_as_a_linear_isolator_of_its_initial_stiffness():
    sc = Scene(pi2=0.2, pi3=1.0, pi4=2.0, pi8=0.1, pi9=1.0, pi10=0.01)
    auto, full = solve(sc), solve(sc, model="full")
    assert auto.model.startswith("bearing-elastic+")
    assert auto.pi1 == pytest.approx(full.pi1, rel=1e-7)


@pytest.mark.parametrize("pi9", [0.05, 0.2, 0.5])
def test_sliding_bearing_under_the_rectangular_pulse_is_a_rigid_plastic_oscillator(pi9):
    """Contents that stick: the slab is a rigid-plastic oscillator with linear hardening (closed form).

    With ``p = 1`` on ``0 <= tau < 1`` and the block stuck (total mass ``1 + Pi8``), the slab slides
    back at once (``1 + Pi8 > Pi9``) with ``x'' = -w'^2 x - (1 - Pi9 / (1 + Pi8))``,
    ``w'^2 = k_d / (1 + Pi8)``; after the pulse it swings about ``-+c``, ``c = Pi9 / k_d``, each
    swing ending ``2 c`` closer to the origin, until it stops within ``|x| <= c`` for good.  The
    peak ``|x|`` (the first stop) and the number of bearing transitions are exact.
    """
    m = 0.01
    sc = Scene(pi2=50.0, pi3=3.0, pi4=0.0, pi8=m, pi9=pi9, pulse="rectangular")
    kd = (2.0 * math.pi / sc.pi3) ** 2
    w = math.sqrt(kd / (1.0 + m))
    a = (1.0 - pi9 / (1.0 + m)) / w ** 2
    assert w < math.pi   # still sliding when the pulse ends
    x1, v1 = -a * (1.0 - math.cos(w)), -a * w * math.sin(w)
    c = pi9 / kd
    first = math.hypot(x1 - c, v1 / w) - c          # |x| at the first stop
    stops = math.ceil((first - c) / (2.0 * c)) + 1   # |x_k| = first - 2 k c until <= c
    ints, floats, _ = run_kernel(sc, rtol=1e-9)
    assert ints[bk.R_SLIPPED] == 0 and ints[bk.R_SETTLED] == 1
    assert floats[bk.F_XMAX] == pytest.approx(first, rel=1e-9)
    assert ints[bk.R_ISO_EVENTS] == 1 + stops


def _energy_terms(sc: Scene, sol) -> tuple:
    """Input work and the energy accounted for (kinetic, potential, dissipated) along a history."""
    h = sol.history
    P = building.parameters(sc)
    mb, mst, m = P[bk.P_MB], P[bk.P_MST], P[bk.P_M]
    kd, cb, ks, cs = P[bk.P_KD], P[bk.P_CB], P[bk.P_KS], P[bk.P_CS]
    tau = h.tau
    x, xd, ud = h.x, h.xd, h.ud
    xs = h.xs if h.xs is not None else np.zeros_like(tau)
    xsd = h.xsd if h.xsd is not None else np.zeros_like(tau)
    fh = h.fh if h.fh is not None else np.zeros_like(tau)
    roof = sc.flexible and sc.floor == "roof"
    vfloor = xd + xsd if roof else xd
    p_left = sc.pulse.accel(np.nextafter(tau, -np.inf))
    p_right = sc.pulse.accel(tau)
    from isoslide.peers.reference import friction_level
    phi = np.array([friction_level(sc, v) for v in ud])
    kinetic = 0.5 * mb * xd ** 2 + 0.5 * mst * (xd + xsd) ** 2 + 0.5 * m * (vfloor + ud) ** 2
    potential = 0.5 * kd * x ** 2 + 0.5 * ks * xs ** 2
    momentum = mb * xd + mst * (xd + xsd) + m * (vfloor + ud)
    dt = np.diff(tau)

    def trap(f0, f1):
        return np.concatenate([[0.0], np.cumsum(0.5 * dt * (f0 + f1))])

    work_in = trap(-p_right[:-1] * momentum[:-1], -p_left[1:] * momentum[1:])
    rate = cb * xd ** 2 + cs * xsd ** 2 + fh * xd + m * phi * np.abs(ud)
    spent = trap(rate[:-1], rate[1:])
    return work_in, kinetic + potential + spent


@pytest.mark.parametrize("kw", [
    dict(pi9=0.05),
    dict(pi9=0.1, pi10=0.02, pi8=0.3),
    dict(pi9=0.05, floor="roof", **FLEX),
    dict(pi5=0.7, pi6=300.0, pi7=0.2, pi8=0.5, **FLEX),
], ids=["sliding", "bilinear", "sliding-flexible-roof", "linear-flexible-stribeck"])
def test_energy_balance(kw):
    """Input work = kinetic + potential + viscous + hysteretic/bearing friction + contents friction."""
    sc = Scene(**{**BASE, **kw})
    sol = solve(sc, history=True, max_step=5e-4, rtol=1e-9)
    work_in, accounted = _energy_terms(sc, sol)
    assert np.max(work_in) > 0.0
    assert np.max(np.abs(work_in - accounted)) <= 1e-5 * np.max(np.abs(work_in))


@pytest.mark.parametrize("kw", [dict(pi9=0.05), dict(pi9=0.1, pi10=0.02), dict(pi9=0.05, floor="roof", **FLEX)],
                         ids=["sliding", "bilinear", "sliding-flexible-roof"])
def test_mirror_symmetry(kw):
    """The negated record gives the same Pi1 and the opposite residual displacement."""
    rng = np.random.default_rng(5)
    acc = np.convolve(rng.standard_normal(400), np.ones(20) / 20.0, mode="same")
    acc /= np.max(np.abs(acc))
    plus, minus = sampled(acc, 0.01), sampled(-acc, 0.01)
    a = solve(Scene(**{**BASE, **kw}, pulse=plus))
    b = solve(Scene(**{**BASE, **kw}, pulse=minus))
    assert a.pi1 > 0.0
    assert b.pi1 == pytest.approx(a.pi1, rel=1e-9)
    assert b.pi1_residual == pytest.approx(-a.pi1_residual, rel=1e-9, abs=1e-14)


@pytest.mark.parametrize("seed", range(4))
def test_buckingham_invariance_of_the_building_groups(seed):
    """Random physical buildings with the same Pi-groups give the same Pi1 (and u_max = Pi1 a_p T_p^2)."""
    rng = np.random.default_rng(seed)
    pis = dict(pi2=0.12, pi3=2.0, pi4=0.05, pi8=0.02, pi9=0.08, pi10=0.004, pi11=0.6, pi12=0.25, pi13=0.03)
    ref = solve(Scene(**pis, floor="roof"))
    a_p = G_STANDARD * 10.0 ** rng.uniform(-1.0, 0.5)
    T_p = 10.0 ** rng.uniform(-0.7, 0.7)
    M_b = 10.0 ** rng.uniform(3.0, 7.0)
    mu_k = pis["pi2"] * a_p / G_STANDARD
    phys = Scene.from_physical(a_p=a_p, T_p=T_p, M_b=M_b, T_b=pis["pi3"] * T_p, xi_b=pis["pi4"],
                               m_ec=pis["pi8"] * M_b, mu_s=mu_k, mu_k=mu_k, Q_d=pis["pi9"] * M_b * a_p,
                               D_y=pis["pi10"] * a_p * T_p ** 2, m_st=pis["pi11"] * M_b, T_s=pis["pi12"] * T_p,
                               xi_s=pis["pi13"], floor="roof")
    sol = solve(phys)
    assert sol.pi1 == pytest.approx(ref.pi1, rel=1e-7)
    assert sol.u_max == pytest.approx(ref.pi1 * a_p * T_p ** 2, rel=1e-7)


def test_friction_pendulum_parameters():
    """T_b = 2 pi sqrt(R/g) and Q = mu M_b g, so Pi9 = mu g / a_p whatever the mass."""
    fp = isoslide.friction_pendulum(R=2.0, mu=0.05, M_b=3e6)
    assert fp["T_b"] == pytest.approx(2.0 * math.pi * math.sqrt(2.0 / G_STANDARD), rel=1e-15)
    sc = Scene.from_physical(a_p=3.0, T_p=1.0, M_b=3e6, xi_b=0.0, m_ec=100.0, mu_s=0.3, mu_k=0.3, **fp)
    assert sc.pi9 == pytest.approx(0.05 * G_STANDARD / 3.0, rel=1e-14) and sc.isolator == "sliding"


def test_settlement_is_final():
    """Followed to the horizon after the settlement stop, nothing slips or yields again."""
    for kw in (dict(pi9=0.05), dict(pi9=0.1, pi10=0.02), dict(pi9=0.05, floor="roof", **FLEX)):
        sc = Scene(**{**BASE, **kw})
        a = solve(sc, model="full")
        b = solve(sc, model="full", settle=False, horizon=20.0)
        assert a.settled
        assert b.pi1 == pytest.approx(a.pi1, rel=1e-9) and b.n_events == a.n_events


@pytest.mark.parametrize("kw, match", [
    (dict(pi9=float("nan")), r"pi9 = nan .*allowed range"),
    (dict(pi10=-1.0), r"pi10 = -1.0 .*allowed range"),
    (dict(pi12=0.3), r"pi11 = 0.0 .*allowed range: 0 < value < 1"),
    (dict(pi11=1.0, pi12=0.3), r"pi11 = 1.0 .*allowed range"),
    (dict(pi13=math.inf), r"pi13 = inf .*allowed range"),
    (dict(floor="attic"), r"floor = 'attic' is invalid; allowed: 'base', 'roof'"),
])
def test_bad_building_input_names_parameter_value_and_range(kw, match):
    with pytest.raises(ValueError, match=match):
        Scene(pi2=0.2, pi3=1.0, **kw)
