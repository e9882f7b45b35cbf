"""Numerical stability at the extremes of the valid domain (isoslide.accuracy.DOMAIN).

Property-based (hypothesis) over every corner and edge: Pi2 1e-4 .. far past the no-slide
threshold, Pi3 0 (fixed base), 1e-3 .. 100, xi_b 0 .. over-damped (10), Pi5 0.05 .. 1,
Pi6 0 .. 1e7, Pi7 0 .. 100, Pi8 0 .. 10, every pulse shape.  Checked: never NaN/inf, never
an exception, Pi1 >= 0, bounded cost per scene, Buckingham and mirror invariance, energy
balance, agreement between accuracy settings, and (slow) with the SciPy reference solver.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from types import SimpleNamespace

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from isoslide import Scene, StepBudgetError, solve
from isoslide.accuracy import DOMAIN
from isoslide.accuracy.domain import TFP_BASE
from isoslide.groups import TFP_NAMES
from isoslide.pulses import PULSE_NAMES, sampled
from isoslide.scene import G_STANDARD, PI_RANGES
from isoslide.solver import DEFAULT_HORIZON, peak_stuck_demand, solve_many

from work_bounds import assert_work_bounded  # tests/ is on sys.path


HYP = settings(deadline=None, max_examples=40, suppress_health_check=[HealthCheck.too_slow],
               derandomize=True)
HYP_FEW = settings(deadline=None, max_examples=15, suppress_health_check=[HealthCheck.too_slow],
                   derandomize=True)


def log_uniform(lo_exp, hi_exp):
    return st.floats(lo_exp, hi_exp, allow_nan=False).map(lambda e: float(10.0 ** e))


pi2_s = st.one_of(log_uniform(-4, 2), st.sampled_from([1e-4, 100.0]))
pi3_s = st.one_of(st.just(0.0), log_uniform(-3, 2), st.sampled_from([1e-3, 100.0]))
pi4_s = st.one_of(st.just(0.0), log_uniform(-3, 1), st.sampled_from([1.0, 10.0]))
pi5_s = st.one_of(st.just(1.0), st.floats(0.05, 1.0), st.just(0.05))
pi6_s = st.one_of(st.just(0.0), log_uniform(-1, 7), st.just(1e7))
pi7_s = st.one_of(st.just(0.0), log_uniform(-3, 2), st.just(100.0))
pi8_s = st.one_of(st.just(0.0), log_uniform(-6, 1), st.just(10.0))
pulse_s = st.sampled_from(PULSE_NAMES)


def many_marginal_slips(sc: Scene) -> bool:
    """Very stiff, (nearly) undamped base: thousands of slips during the pulse.

    Near the threshold many of them are marginal and the default tolerance misses some
    (test_marginal_slips_on_a_stiff_undamped_base); the loose settings (rtol = 1e-3) do not hold
    there, so these scenes are checked at the default rtol by
    test_accuracy_promise_with_many_marginal_transitions instead of the rtol sweeps.
    """
    return 0.0 < sc.pi3 < 0.02 and sc.pi4 < 0.05


@st.composite
def scenes(draw, pulses=pulse_s):
    sc = Scene(pi2=draw(pi2_s), pi3=draw(pi3_s), pi4=draw(pi4_s), pi5=draw(pi5_s), pi6=draw(pi6_s),
               pi7=draw(pi7_s), pi8=draw(pi8_s), pulse=draw(pulses))
    return sc


SLIDING_PULSES = st.sampled_from(["ricker", "antisymmetric_ricker", "makris_b", "mavroeidis_papageorgiou"])


@st.composite
def sliding_scenes(draw, pulses=SLIDING_PULSES):
    """Scenes that slide: Pi2/Pi5 a fraction of the stuck demand."""
    sc = draw(scenes(pulses))
    frac = draw(st.floats(0.02, 0.9))
    A = peak_stuck_demand(sc)
    out = Scene(pi2=frac * A * sc.pi5, pi3=sc.pi3, pi4=sc.pi4, pi5=sc.pi5, pi6=sc.pi6, pi7=sc.pi7,
                pi8=sc.pi8, pulse=sc.pulse)
    return out


def check_solution(s, sc: Scene, horizon: float = DEFAULT_HORIZON):
    """A finite answer within its physical bounds, and diagnostics that match what happened.

    Pi1 >= 0 and the permanent displacement within the peak; Pi1 = 0 exactly (with no residual
    and no stick/slip transition) when the label says the block never slid, Pi1 > 0 with at
    least one transition when it slid; integrator steps taken (at least one per located
    transition); the peak inside the followed window, which ends at the horizon unless the
    response settled first.
    """
    assert math.isfinite(s.pi1) and s.pi1 >= 0.0
    assert math.isfinite(s.pi1_residual) and abs(s.pi1_residual) <= s.pi1 * (1 + 1e-12) + 1e-300
    assert math.isfinite(s.tau_peak) and math.isfinite(s.tau_end)
    if "no-slide" in s.model:
        assert s.pi1 == 0.0 and s.pi1_residual == 0.0 and s.n_events == 0, s
    else:
        assert s.pi1 > 0.0 and s.n_events >= 1, s
    assert s.n_steps >= max(s.n_events, 1), s
    end = sc.pulse.tau_end + horizon * max(sc.pi3, 1.0)
    assert sc.pulse.tau_start <= s.tau_peak <= s.tau_end <= end * (1 + 1e-12), s
    assert s.settled or s.tau_end >= end * (1 - 1e-12), s


# ----------------------------------------------------------------------------------------------
# the domain
# ----------------------------------------------------------------------------------------------

def test_domain_is_inside_the_scene_ranges():
    for k, (lo, hi, text) in DOMAIN.items():
        plo, phi, lo_in, hi_in = PI_RANGES[k]
        assert (lo > plo or (lo == plo and lo_in)) and (hi < phi or (hi == phi and hi_in)), k
        assert text
        for v in (lo, hi):
            kw = {"pi2": 1.0, "pi3": 0.0, "pi11": 0.5}   # pi11 is read with a flexible superstructure
            kw[k] = v
            if k == "pi17":
                kw["pulse_z"] = "ricker"                  # pi17 scales a vertical pulse
            if k in TFP_NAMES:                            # the triple pendulum's groups shape a sliding bearing
                kw.update({**TFP_BASE, "pi3": 1.0, k: v})
            assert getattr(Scene(**kw), k) == v


CORNERS = {k: (DOMAIN[k][0], DOMAIN[k][1]) for k in DOMAIN}
CORNERS["pi3"] = (0.0, 1e-3, 100.0)
CORNERS["pi2"] = (1e-4, 0.05, 100.0)


@pytest.mark.parametrize("pi3", CORNERS["pi3"])
@pytest.mark.parametrize("pi4", CORNERS["pi4"])
@pytest.mark.parametrize("pi2", CORNERS["pi2"])
def test_corners_of_the_base(pi2, pi3, pi4):
    """Every corner of (Pi2, Pi3, xi_b), with the friction and mass groups at their corners too."""
    for pi5, pi6, pi7, pi8 in itertools.product(CORNERS["pi5"], CORNERS["pi6"], CORNERS["pi7"], CORNERS["pi8"]):
        sc = Scene(pi2=pi2, pi3=pi3, pi4=pi4, pi5=pi5, pi6=pi6, pi7=pi7, pi8=pi8)
        s = solve(sc)
        check_solution(s, sc)
        assert_work_bounded(s, sc)


# ----------------------------------------------------------------------------------------------
# properties over the whole domain
# ----------------------------------------------------------------------------------------------

@st.composite
def buildings(draw, pulses=pulse_s):
    """General buildings over the domain's corners and edges: bearings, flexible superstructures."""
    sc = draw(scenes(pulses))
    kw = {**sc.pis(), "pulse": sc.pulse}
    kw["pi9"] = draw(st.one_of(st.just(0.0), log_uniform(-3, 1), st.just(10.0)))
    kw["pi10"] = draw(st.one_of(st.just(0.0), log_uniform(-5, 0), st.just(1.0)))
    if draw(st.booleans()):   # a sliding bearing's friction rising with speed (read only when pi10 = 0)
        kw["pi22"] = draw(st.one_of(st.floats(0.05, 1.0), st.sampled_from([0.05, 1.0])))
        kw["pi23"] = draw(st.one_of(st.just(0.0), log_uniform(-3, 4), st.just(1e4)))
    if draw(st.booleans()):
        kw["pi11"] = draw(st.one_of(st.floats(0.01, 0.95), st.sampled_from([0.01, 0.95])))
        kw["pi12"] = draw(st.one_of(log_uniform(-2, 1), st.sampled_from([0.01, 10.0])))
        kw["pi13"] = draw(st.one_of(st.just(0.0), log_uniform(-3, 0), st.just(1.0)))
    kw["floor"] = draw(st.sampled_from(["base", "roof"]))
    return Scene(**kw)


@HYP
@given(buildings())
def test_valid_building_is_solved_finite_nonnegative_and_bounded(sc):
    """Bearings with true stick or yielding (friction constant or rising with speed), flexible superstructures, both floors, every corner."""
    s = solve(sc, horizon=50.0)
    check_solution(s, sc, horizon=50.0)
    assert_work_bounded(s, sc)

@HYP
@given(scenes())
def test_valid_scene_is_solved_finite_nonnegative_in_bounded_work(sc):
    s = solve(sc)
    check_solution(s, sc)
    assert_work_bounded(s, sc)
    if s.pi1 == 0.0:
        assert "no-slide" in s.model
    if sc.static_level > peak_stuck_demand(sc) * (1 + 1e-9):
        assert s.pi1 == 0.0


@HYP
@given(scenes())
def test_batch_agrees_with_single_solves(sc):
    b = solve_many([sc])
    s = solve(sc)
    assert b.pi1[0] == pytest.approx(s.pi1, rel=1e-12, abs=0.0) or (b.pi1[0] == 0.0 and s.pi1 == 0.0)


@HYP
@given(sliding_scenes(), st.floats(-1.0, 1.0), st.floats(-0.7, 0.7), st.floats(1.0, 7.0))
def test_buckingham_invariance(sc, log_ap_g, log_tp, log_mb):
    """Any a_p, T_p, M_b with the same Pi-groups give the same Pi1 (and u_max = Pi1 a_p T_p^2)."""
    a_p = G_STANDARD * 10.0 ** log_ap_g
    T_p = 10.0 ** log_tp
    M_b = 10.0 ** log_mb
    mu_k = sc.pi2 * a_p / G_STANDARD
    phys = Scene.from_physical(a_p=a_p, T_p=T_p, M_b=M_b, T_b=sc.pi3 * T_p, xi_b=sc.pi4,
                               m_ec=sc.pi8 * M_b, mu_s=mu_k / sc.pi5, mu_k=mu_k,
                               beta=sc.pi6 / (a_p * T_p), gamma=sc.pi7 / (G_STANDARD * T_p), pulse=sc.pulse)
    a, b = solve(sc), solve(phys)
    # the Pi-groups agree to round-off, so Pi1 agrees to well within the solver's rtol
    assert b.pi1 == pytest.approx(a.pi1, rel=1e-7, abs=1e-12)
    assert b.u_max == pytest.approx(b.pi1 * a_p * T_p ** 2, rel=1e-14)


MIRROR_HORIZON = 50.0
"""Isolation periods followed after the record in the mirror check (the property holds for any)."""


@HYP
@given(st.lists(st.floats(-1.0, 1.0), min_size=3, max_size=24), st.floats(0.02, 0.3),
       pi3_s, pi4_s, pi5_s, pi6_s, pi7_s, pi8_s, st.floats(0.02, 0.9))
def test_mirror_invariance(acc, dtau, pi3, pi4, pi5, pi6, pi7, pi8, frac):
    """Reversing the ground motion (a_g -> -a_g) mirrors the response: same Pi1, opposite residual."""
    a = np.asarray(acc)
    if not np.any(a != 0.0):
        a = np.array([0.0, 1.0, 0.0])
    a = a / np.max(np.abs(a))
    plus, minus = sampled(a, dtau, name="plus"), sampled(-a, dtau, name="minus")
    base = Scene(pi2=1.0, pi3=pi3, pi4=pi4, pi5=pi5, pi6=pi6, pi7=pi7, pi8=pi8, pulse=plus)
    pi2 = frac * peak_stuck_demand(base) * pi5
    if pi2 <= 0.0:
        return
    outcomes = []
    for pulse in (plus, minus):
        try:
            outcomes.append(solve(Scene(pi2=pi2, pi3=pi3, pi4=pi4, pi5=pi5, pi6=pi6, pi7=pi7, pi8=pi8, pulse=pulse),
                                  horizon=MIRROR_HORIZON))
        except StepBudgetError as e:
            outcomes.append(e)
    sp, sm = outcomes
    if isinstance(sp, StepBudgetError) or isinstance(sm, StepBudgetError):
        # an undamped, very stiff base followed for thousands of periods can exceed the step budget;
        # the mirrored run must then exceed it at the same time
        assert str(sp).split(" for Scene")[0] == str(sm).split(" for Scene")[0], (sp, sm)
        return
    assert sm.pi1 == pytest.approx(sp.pi1, rel=1e-10, abs=1e-15)
    assert sm.pi1_residual == pytest.approx(-sp.pi1_residual, rel=1e-10, abs=1e-14)


def friction_level(sc, v):
    av = np.abs(v)
    sech = 1.0 / np.cosh(np.minimum(sc.pi6 * av, 700.0))
    return sc.static_level * sech + sc.pi2 * (1.0 - sech) + sc.pi7 * av


def energy_residual(sc, max_step=5e-4, horizon=3.0):
    """Energy balance over a solve, relative to the work done by the ground.

    Isolated base (per unit M_b): with T = x'^2/2 + Pi8 (x'+u')^2/2 and V = w^2 x^2/2,
    d(T+V)/dtau = -p (x' + Pi8 (x'+u')) - 2 z w x'^2 - Pi8 phi(|u'|) |u'|.
    Fixed base (per unit m_EC): d(u'^2/2)/dtau = -p u' - phi(|u'|) |u'|.
    The history is taken with steps of at most ``max_step`` T_p (every step point and every
    transition is a history point, so the integrands are smooth between points) and the
    power is integrated by the trapezoid rule, with p taken as its left limit at the end of
    each interval (the pulse may jump at breakpoints, where steps end): quadrature error
    ~ max_step^2 / 12 * |f''| * duration ~ 1e-6 of the input work.
    """
    s = solve(sc, history=True, max_step=max_step, horizon=horizon)
    h = s.history
    t, x, xd, _u, ud = h.tau, h.x, h.xd, h.u, h.ud
    p_right = sc.pulse.accel(t[:-1])
    p_left = sc.pulse.accel(np.nextafter(t[1:], -np.inf))
    if sc.fixed_base:
        E = 0.5 * ud ** 2
        inp0, inp1 = -p_right * ud[:-1], -p_left * ud[1:]
        dis = friction_level(sc, ud) * np.abs(ud)
    else:
        w = 2.0 * math.pi / sc.pi3
        z = sc.pi4
        E = 0.5 * xd ** 2 + 0.5 * sc.pi8 * (xd + ud) ** 2 + 0.5 * w * w * x ** 2
        inp0 = -p_right * (xd[:-1] + sc.pi8 * (xd[:-1] + ud[:-1]))
        inp1 = -p_left * (xd[1:] + sc.pi8 * (xd[1:] + ud[1:]))
        dis = 2.0 * z * w * xd ** 2 + sc.pi8 * friction_level(sc, ud) * np.abs(ud)
    dt = np.diff(t)
    work_in = np.sum(0.5 * dt * (inp0 + inp1))
    dissipated = np.sum(0.5 * dt * (dis[:-1] + dis[1:]))
    scale = np.sum(0.5 * dt * (np.abs(inp0) + np.abs(inp1)))
    return (E[-1] - E[0] - work_in + dissipated) / scale, s


@HYP_FEW
@given(sliding_scenes(st.sampled_from(["ricker", "rectangular", "makris_a", "antisymmetric_ricker"])))
def test_energy_balance(sc):
    if sc.pi3 != 0.0 and sc.pi3 < 0.05:
        sc = Scene(pi2=sc.pi2, pi3=0.05, pi4=sc.pi4, pi5=sc.pi5, pi6=sc.pi6, pi7=sc.pi7, pi8=sc.pi8,
                   pulse=sc.pulse)  # a stiffer base needs far more history points
    if sc.pi6 * sc.pi2 > 1e5:
        sc = Scene(pi2=sc.pi2, pi3=sc.pi3, pi4=sc.pi4, pi5=sc.pi5, pi6=1e5 / sc.pi2, pi7=sc.pi7,
                   pi8=sc.pi8, pulse=sc.pulse)  # the transition must span several history points
    res, s = energy_residual(sc)
    assert abs(res) < 2e-5, (res, s.model)


@pytest.mark.parametrize("sc", [
    Scene(pi2=0.2, pi3=1.0, pi4=0.1),
    Scene(pi2=0.1, pi3=1.0, pi4=0.1, pi5=0.5, pi6=300.0, pi8=1.0),
    Scene(pi2=0.05, pi3=2.0, pi4=0.0, pi7=2.0, pi8=0.3),
    Scene(pi2=0.3, pi3=0.0, pulse="rectangular"),
    Scene(pi2=0.1, pi3=0.0, pi5=0.5, pi6=100.0, pi7=1.0),
])
def test_energy_balance_named(sc):
    """The residual is the trapezoid rule's error: it falls like max_step^2 (to round-off)."""
    coarse, _ = energy_residual(sc, max_step=5e-4)
    fine, _ = energy_residual(sc, max_step=1e-4)
    assert abs(coarse) < 2e-6
    assert abs(fine) < max(abs(coarse) / 10.0, 1e-11)


@st.composite
def marginal_scenes(draw):
    """Stiff, (nearly) undamped bases with the static level just below the stuck demand's peak:
    hundreds to thousands of transitions, many of them marginal."""
    pi3 = draw(log_uniform(-3, -1.7))
    pi4 = draw(st.one_of(st.just(0.0), log_uniform(-4, -1.3)))
    pi5 = draw(st.one_of(st.just(1.0), st.floats(0.5, 1.0)))
    pi6 = 0.0 if pi5 == 1.0 else draw(st.one_of(st.just(0.0), log_uniform(2, 4)))
    pulse = draw(st.sampled_from(["makris_b", "ricker", "rectangular", "antisymmetric_ricker"]))
    base = Scene(pi2=1.0, pi3=pi3, pi4=pi4, pi5=pi5, pi6=pi6, pi8=draw(st.sampled_from([0.0, 1e-3])),
                 pulse=pulse)
    frac = 1.0 - draw(log_uniform(-6, -1))
    return Scene(pi2=frac * peak_stuck_demand(base) * pi5, pi3=pi3, pi4=pi4, pi5=pi5, pi6=pi6,
                 pi8=base.pi8, pulse=pulse)


@pytest.mark.slow
@HYP_FEW
@given(marginal_scenes())
def test_accuracy_promise_with_many_marginal_transitions(sc):
    """The default rtol = 1e-6 holds on stiff undamped bases with many near-threshold slips."""
    conv = solve(sc, rtol=1e-12, model="full").pi1
    p = solve(sc).pi1
    assert abs(p - conv) <= 1e-6 * max(conv, 1e-6), (p, conv)


@HYP
@given(sliding_scenes().filter(lambda s: not many_marginal_slips(s)))
def test_accuracy_settings_agree(sc):
    """Each rtol meets its target against rtol = 1e-12 (relative above 1e-6 a_p T_p^2)."""
    conv = solve(sc, rtol=1e-12, model="full").pi1
    for rtol in (1e-3, 1e-6):
        p = solve(sc, rtol=rtol).pi1
        assert abs(p - conv) <= rtol * max(conv, 1e-6), (rtol, p, conv)


@pytest.mark.slow
@settings(deadline=None, max_examples=400, suppress_health_check=[HealthCheck.too_slow], derandomize=True)
@given(scenes())
def test_valid_scene_heavy_sweep(sc):
    """Many more scenes of the domain (slow): finite, non-negative, in bounded work, batch = single."""
    s = solve(sc)
    check_solution(s, sc)
    assert_work_bounded(s, sc)
    assert solve_many([sc]).pi1[0] == s.pi1


@pytest.mark.slow
@settings(deadline=None, max_examples=150, suppress_health_check=[HealthCheck.too_slow], derandomize=True)
@given(sliding_scenes(st.sampled_from(PULSE_NAMES)).filter(lambda s: not many_marginal_slips(s)))
def test_accuracy_settings_agree_heavy(sc):
    """Each rtol from 1e-2 to 1e-8 meets its target against rtol = 1e-12 (more pulse shapes, slow).

    An undamped base that never settles is followed to the horizon through hundreds of slips, and
    its error there sits at a few 1e-8 whatever the tolerance (see
    test_tightest_tolerance_agrees_with_reference_undamped): such scenes are held to rtol >= 1e-6.
    Contents heavier than the building on a very soft base are held to rtol <= 1e-6 (see
    test_heavy_contents_on_a_soft_base_meet_rtol_1e_4).  A scene whose tightest solve runs out of
    its step budget has no reference and is not judged.
    """
    try:
        ref = solve(sc, rtol=1e-12, model="full")
    except StepBudgetError:
        assume(False)   # no reference to judge by: the tightest tolerance does not fit the step budget
    conv = ref.pi1
    rtols = (1e-2, 1e-4, 1e-6) if (sc.pi4 == 0.0 and sc.pi3 > 0.0 and not ref.settled) else (1e-2, 1e-4, 1e-6, 1e-8)
    if sc.pi8 > 1.0 and sc.pi3 >= 10.0:
        rtols = (1e-6, 1e-8)   # loose tolerances miss late marginal breakaways there (see below)
    for rtol in rtols:
        p = solve(sc, rtol=rtol).pi1
        assert abs(p - conv) <= rtol * max(conv, 1e-6), (rtol, p, conv)


HEAVY_ON_SOFT = Scene(pi2=0.002333462310971313, pi3=100.0, pi4=0.03162277660168379, pi8=10.0, pulse="rectangular")
"""Contents ten times the building's mass on a base of period 100 T_p (Pi1 = 217.6, ten transitions)."""


UNDAMPED_AT_HORIZON = Scene(pi2=0.08569495819168338, pi3=1.0, pi4=0.0, pi8=0.0, pulse="antisymmetric_ricker")
"""An undamped base under the antisymmetric Ricker, still sliding at the horizon (407 transitions)."""


@pytest.mark.slow
@pytest.mark.parametrize("scene, rtol", [
    pytest.param(HEAVY_ON_SOFT, 1e-4, id="heavy_contents_on_a_soft_base", marks=pytest.mark.xfail(
        strict=True, reason="rtol = 1e-4 misses two late marginal breakaways (8 transitions instead of 10) and "
                            "gives Pi1 = 217.088 against 217.597 (2.3e-3); rtol <= 1e-6 finds all ten")),
    pytest.param(UNDAMPED_AT_HORIZON, 1e-8, id="undamped_base_still_sliding_at_the_horizon", marks=pytest.mark.xfail(
        strict=True, reason="followed 200 undamped periods through 407 slips, the default and the tight "
                            "tolerances give 0.50187683 and 0.50187686: 5.7e-8 apart whatever rtol <= 1e-6 is "
                            "asked (a max_step of 0.01 gives the former)")),
])
def test_hard_scenes_meet_the_asked_rtol(scene, rtol):
    """Pi1 at ``rtol`` within ``rtol`` of the converged full-model answer (known misses, marked xfail)."""
    conv = solve(scene, rtol=1e-12, model="full").pi1
    p = solve(scene, rtol=rtol).pi1
    assert abs(p - conv) <= rtol * conv, (p, conv)


STIFF_UNDAMPED_HEAVY = Scene(pi2=0.01, pi3=10 ** -2.5, pi4=0.0, pi5=0.05, pi6=1.0, pi8=1.0, pulse="rectangular")
"""An undamped very stiff base carrying contents of its own mass with a strong Stribeck drop: about
175,000 transitions over 63,000 isolation periods."""


@pytest.mark.slow
@pytest.mark.xfail(strict=True, raises=StepBudgetError,
                   reason="the tightening of the tolerance over ~175,000 transitions needs more than the step "
                          "budget (12.7 million steps; ten times that runs out as well)")
def test_stiff_undamped_heavy_contents_solve_at_the_default():
    """The stiff undamped base with heavy Stribeck contents solves at the default rtol (a known limit:
    it raises StepBudgetError, which names rtol and the horizon); rtol = 1e-3 answers."""
    loose = solve(STIFF_UNDAMPED_HEAVY, rtol=1e-3)
    assert loose.pi1 > 0.0 and loose.n_events > 100_000
    s = solve(STIFF_UNDAMPED_HEAVY)
    check_solution(s, STIFF_UNDAMPED_HEAVY)


PLATEAU = {"pi2": 1.0, "pi3": 1e-3, "pi4": 10.0, "pi7": 56.2, "pi8": 1.0, "pulse": "rectangular"}
"""A stuck demand lying on the static level for the whole rectangular pulse (stiff over-damped base,
heavy contents, strong viscous contact): the arguments of its Scene."""


def test_plateau_at_threshold_is_solved_in_bounded_work():
    """The plateau scene is solved in a few thousand transitions and bounded work, without chattering
    through millions of stick/slip transitions.  Runs in a subprocess that must end within 60 s: the
    compiled kernel cannot be interrupted from Python, so a chattering run would hang the suite."""
    import subprocess
    import sys

    code = (f"from isoslide import Scene, solve; s = solve(Scene(**{PLATEAU!r})); "
            "print(s.pi1, s.n_steps, s.n_events, s.tau_end)")
    try:
        out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    except subprocess.TimeoutExpired:
        pytest.fail("no answer within 60 s")
    assert out.returncode == 0, out.stderr
    pi1, n_steps, n_events, tau_end = out.stdout.split()
    s = SimpleNamespace(pi1=float(pi1), n_steps=int(n_steps), n_events=int(n_events), tau_end=float(tau_end))
    assert s.pi1 >= 0.0
    assert 0 < s.n_events <= 10_000, s
    assert_work_bounded(s, Scene(**PLATEAU))


MANY = Scene(pi2=1.4999999949765033, pi3=1e-3, pi4=0.0, pi8=0.0, pulse="rectangular")
"""~2000 slips during the pulse (very stiff undamped base under the rectangular pulse)."""


def test_error_target_with_thousands_of_transitions():
    """Over more than 1000 transitions the default rtol = 1e-6 still meets 1e-6 against the
    converged answer (errors accumulated over the transitions are controlled)."""
    conv = solve(MANY, rtol=1e-12, model="full").pi1
    s = solve(MANY)
    assert s.n_events > 1000
    assert abs(s.pi1 - conv) <= 1e-6 * conv


MARGINAL = Scene(pi2=1.0000007860939033, pi3=1e-3, pi4=0.0, pi8=0.0, pulse="makris_b")
"""~2000 slips, most of them marginal (Pi2 0.8 ppm above the floor's plateau)."""


def test_marginal_slips_on_a_stiff_undamped_base():
    """~2000 slips decided by a demand excess of 0.8 ppm: the default meets its 1e-6 promise.

    The converged answer agrees with the independent SciPy event-driven peer run at
    rtol 1e-12, atol 1e-20 (1.8432093039922e-05, 2.9e-10 apart).
    """
    conv = solve(MARGINAL, rtol=1e-12, model="full")
    assert conv.n_events == 2000 and conv.pi1 == pytest.approx(1.8432093039922e-05, rel=1e-9)
    s = solve(MARGINAL)
    assert abs(s.pi1 - conv.pi1) <= 1e-6 * conv.pi1
    tight = solve(MARGINAL, rtol=1e-8)
    assert abs(tight.pi1 - conv.pi1) <= 1e-8 * conv.pi1


UNDAMPED = Scene(pi2=0.06128900902154921, pi3=1.0, pi4=0.0, pi8=0.0)
"""Undamped base followed 200 periods (405 transitions)."""


@pytest.mark.slow
@pytest.mark.xfail(strict=True, reason="at rtol <= 1e-11 the compiled solver gives 0.42576758646 "
                                       "for UNDAMPED, 4e-9 (relative) below the SciPy reference "
                                       "(0.4257675881..., rtol 1e-10 .. 1e-13) and below its own rtol=1e-9, "
                                       "1e-10 and max_step-capped answers")
def test_tightest_tolerance_agrees_with_reference_undamped():
    from isoslide.peers import solve_reference

    ref = solve_reference(UNDAMPED, rtol=1e-12, atol=1e-16, tau_max=UNDAMPED.pulse.tau_end + 200.0).pi1
    assert solve(UNDAMPED, rtol=1e-12).pi1 == pytest.approx(ref, rel=1e-10)


def test_no_slide_threshold_is_sharp():
    for pi3, pi4 in ((0.0, 0.0), (1.0, 0.1), (2.0, 0.0), (0.5, 1.5)):
        A = peak_stuck_demand(Scene(pi2=1.0, pi3=pi3, pi4=pi4), rtol=1e-12)
        assert solve(Scene(pi2=A * (1 + 1e-9), pi3=pi3, pi4=pi4)).pi1 == 0.0
        assert solve(Scene(pi2=A * (1 - 1e-6), pi3=pi3, pi4=pi4)).pi1 > 0.0


# ----------------------------------------------------------------------------------------------
# the independent SciPy reference (slow)
# ----------------------------------------------------------------------------------------------

@pytest.mark.slow
@settings(deadline=None, max_examples=12, suppress_health_check=[HealthCheck.too_slow], derandomize=True)
@given(sliding_scenes(st.sampled_from(["ricker", "makris_b"])).filter(lambda s: s.pi3 >= 0.05)
       .map(lambda s: dataclasses.replace(s, pi6=0.0, pi7=0.0)))   # the stuck demand ignores pi6, pi7
def test_agrees_with_reference_coulomb(sc):
    from isoslide.peers import solve_reference

    H = 20.0
    a = solve(sc, rtol=1e-10, horizon=H).pi1
    b = solve_reference(sc, rtol=1e-12, tau_max=sc.pulse.tau_end + H * max(1.0, sc.pi3)).pi1
    assert b == pytest.approx(a, rel=1e-7, abs=1e-12)


SHARP = Scene(pi2=0.2, pi3=1.0, pi4=0.1, pi5=0.5, pi6=9806.65)
"""Fig. 6/7 scene (beta = 1000 s/m): the SciPy reference ends the second slip 8.5e-6 T_p late."""


def test_sharp_stribeck_exact_matches_brute_force():
    """The compiled solver's end of the 2nd slip of SHARP equals a brute-force small-step solve."""
    from scipy.integrate import solve_ivp

    from isoslide.pulses import accel_at

    s = solve(SHARP, rtol=1e-12, history=True, max_step=1e-3)
    h = s.history
    stops = h.tau[(h.ud == 0.0) & (h.phase != 0)]
    t_stop = stops[stops > 0.5][0]
    k = np.searchsorted(h.tau, 0.70)
    y0 = np.array([h.x[k], h.xd[k], h.u[k], h.ud[k]])
    w = 2.0 * math.pi
    code, pa = SHARP.pulse.code, SHARP.pulse.param_array

    def rhs(t, y):
        ph = friction_level(SHARP, y[3])
        p = accel_at(code, pa, t)
        xdd = -p - 2 * 0.1 * w * y[1] - w * w * y[0] + SHARP.pi8 * (-1.0) * ph
        return [y[1], xdd, y[3], ph - p - xdd]

    def stop(t, y):
        return -y[3]
    stop.terminal, stop.direction = True, -1.0
    sol = solve_ivp(rhs, (h.tau[k], 0.8), y0, method="DOP853", rtol=1e-13, atol=1e-16, events=stop,
                    max_step=1e-4)
    assert sol.t_events[0][0] == pytest.approx(t_stop, abs=1e-9)


@pytest.mark.slow
@pytest.mark.xfail(strict=True, reason="isoslide.peers.reference (SciPy events on a DOP853 step over the sharp "
                                       "Stribeck transition) ends the 2nd slip 8.5e-6 T_p late: Pi1 off "
                                       "by 9e-5; the compiled solver agrees with a brute-force solve")
def test_reference_agrees_on_sharp_stribeck():
    from isoslide.peers import solve_reference

    a = solve(SHARP, rtol=1e-12).pi1
    b = solve_reference(SHARP, rtol=1e-12).pi1
    assert b == pytest.approx(a, rel=1e-7)


@pytest.mark.slow
@pytest.mark.xfail(strict=True, reason="isoslide.peers.reference misses a breakaway whose demand exceeds the "
                                       "static level only briefly (sign-change event detection between "
                                       "steps): Pi1 = 0 instead of 2e-9 just below the no-slide threshold")
def test_reference_finds_slips_just_below_threshold():
    from isoslide.peers import solve_reference

    A = peak_stuck_demand(Scene(pi2=1.0, pi3=1.0, pi4=0.1), rtol=1e-12)
    sc = Scene(pi2=A * (1 - 1e-4), pi3=1.0, pi4=0.1)
    a = solve(sc, rtol=1e-12).pi1
    assert a > 0.0
    assert solve_reference(sc, rtol=1e-6).pi1 > 0.0
