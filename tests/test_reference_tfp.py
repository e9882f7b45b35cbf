"""The event-driven reference of a rigid building on a triple friction pendulum, with contents.

isoslide.peers.reference_tfp integrates the slab and the contents between events and carries the
bearing's four surfaces exactly (massless sliders).  Checked: with equal frictions it is isoslide's
single friction pendulum (the compiled solver, to 1e-6 in Pi1 and the slab's peak); driven slowly,
every vertex of its force-displacement path lies on the closed-form backbone and unloading branch of
isoslide.model.tfp (to 1e-9 of the weight) and its peak force is the quasi-static one; the energy
balance holds to 1e-7 with every surface's friction work; flipping the pulse flips every displacement
exactly; scenes reaching regimes I to V report that peak regime, which is the closed-form regime of the
slab's peak displacement; inputs outside their ranges are refused.
"""

import math

import numpy as np
import pytest

import isoslide
from isoslide.model import tfp
from isoslide.peers.reference_tfp import ENERGY_NAMES, TFPBuilding, run_tfp, single_pendulum_scene

G = 9.80665
BEARING = dict(L=(0.3, 2.0, 2.5), mu=(0.02, 0.06, 0.10), d=(0.05, 0.35, 0.40))
"""A bearing (m) whose five regimes all have positive length; surface 4's restrainer is reached before
the inner surface 3's (d3/L3 < d2/L2)."""


def _building(a_p_over_g, T_p, bearing=BEARING, **kw):
    kw = {"mass_ratio": 0.05, "mu_s": 0.12, "mu_k": 0.1, **kw}
    return TFPBuilding.from_physical(**bearing, a_p=a_p_over_g * G, T_p=T_p, **kw)


EQUAL = {
    "equal surfaces": dict(L=(1.2, 1.2, 1.2), mu=(0.06, 0.06, 0.06), d=(0.4, 0.4, 0.4)),
    "equal frictions, unequal radii": dict(L=(0.4, 1.5, 2.0), mu=(0.05, 0.05, 0.05), d=(0.1, 0.45, 0.6)),
}

SINGLE_PENDULUM_CASES = [
    ("equal surfaces", "ricker", 0.3, 0.0),
    ("equal surfaces", "ricker", 0.6, 0.0),
    ("equal surfaces", "makris_b", 0.6, 0.0),
    ("equal surfaces", "antisymmetric_ricker", 0.3, 0.0),
    ("equal surfaces", "rectangular", 0.3, 0.0),
    ("equal surfaces", "ricker", 0.6, 0.4),
    ("equal frictions, unequal radii", "ricker", 0.5, 0.0),
]


@pytest.mark.parametrize("name, pulse, a_p_over_g, c", SINGLE_PENDULUM_CASES)
def test_equal_frictions_give_the_compiled_single_friction_pendulum(name, pulse, a_p_over_g, c):
    """Equal frictions: Pi1, the residual and the slab's peak equal isoslide.solve's sliding bearing to 1e-6.

    The equivalent scene has Pi3 = 2 pi sqrt((L2 + L3)/((1 + Pi8) G)) and Pi9 = mu (1 + Pi8) G, since
    isoslide's sliding bearing has its k_d and Q per M_b while the bearing carries (M_b + m_EC) g;
    Pi4 = c Pi3/(4 pi); the contents' static and kinetic friction are equal (Pi5 = 1: isoslide's
    Coulomb friction with Pi6 = 0 slides at the static level).  Below surface 1's restrainer (regime
    III) the inner surfaces never slide and the plate-rotation work is zero; with equal radii regimes
    IV and V have the same stiffness and the equivalence holds beyond.
    """
    b = TFPBuilding.from_physical(**EQUAL[name], a_p=a_p_over_g * G, T_p=1.5, mass_ratio=0.1, mu_s=0.1,
                                  mu_k=0.1, pulse=pulse, c=c)
    scene = single_pendulum_scene(b)
    W = (1.0 + 0.1) * G / (a_p_over_g * G)
    assert scene.pi3 == pytest.approx(2.0 * math.pi * math.sqrt((b.L[1] + b.L[2]) / W), rel=1e-15)
    assert scene.pi9 == pytest.approx(b.mu[0] * W, rel=1e-15)
    assert scene.pi4 == pytest.approx(0.4 * 1.5 * scene.pi3 / (4.0 * math.pi), rel=1e-15) if c else scene.pi4 == 0.0
    run = run_tfp(b)
    sol = isoslide.solve(scene, history=True)
    assert sol.model.startswith("sliding-bearing")
    assert run.settled and sol.settled
    assert sol.pi1 > 1e-3
    assert run.pi1 == pytest.approx(sol.pi1, rel=1e-6)
    assert run.pi1_residual == pytest.approx(sol.pi1_residual, rel=1e-6, abs=1e-6 * sol.pi1)
    assert run.x_peak == pytest.approx(float(np.max(np.abs(sol.history.x))), rel=1e-6)
    assert {s for _, s in run.stages} <= {0, 3, 4, 5}
    if run.peak_stage == 3:
        assert np.all(run.vertices["surfaces"][:, 1:3] == 0.0)
        assert np.all(run.vertices["energy"][:, ENERGY_NAMES.index("plate")] == 0.0)


def _closed_form_force(bearing, x, turn, direction):
    """Closed-form force at ``x`` moving in ``direction`` after a reversal at ``turn`` from the backbone (None: none yet).

    Breaking away from rest at ``x = 0`` the force is ``mu1 W`` in the direction of motion.
    """
    if turn is None and x == 0.0:
        return direction * bearing.mu[0] * bearing.W
    if turn is not None and abs(x) <= abs(turn):
        return tfp.loop_force(bearing, abs(turn), x, "down" if turn > 0 else "up")
    return math.copysign(tfp.force(bearing, abs(x))[0], x)


def test_a_slow_drive_follows_the_closed_form_backbone_and_unloading_branches():
    """Driven slowly, every vertex (x, F) lies on the closed-form loop to 1e-9 W.

    A Ricker pulse of T_p = 40 s (the regimes' periods are 1.1 s to 4.3 s), run over the pulse: a first
    excursion to regime III, the unloading branch past its mirror point onto the backbone through IV
    and V, and the unloading branch from V.  Every turn from the backbone (an excursion beyond every
    earlier one) starts a branch of the closed forms; the comparison stops at the first turn inside
    the envelope.  A damper (c_b/M_b = 4 1/s, about critical in regime V) keeps the slab from turning
    back when the stiffness jumps into V: without it the velocity the slab brings from IV (where the
    stiffness is 4.7 times smaller) overshoots and a minor loop follows, which the closed forms do not
    describe.  The force breaking away after the first turn is 2 mu1 W below the turning force, the
    displacements where the regimes change on the backbone are the closed-form boundaries, and the
    peak force is the quasi-static (1 + Pi8) a_p, i.e. W/G, to 2e-2 (inertia and the damper).
    """
    b = _building(0.33, 40.0, mu_s=2.0, mu_k=2.0, polarity=-1, c=4.0)
    bearing = b.bearing
    W = bearing.W
    run = run_tfp(b, tau_max=b.pulse.tau_end)
    assert run.peak_stage == 5
    v = run.vertices
    x, F, stage = v["x"], v["F"], v["stage"]
    turn, envelope, direction, checked, first_drop, F_turn = None, 0.0, 0.0, 0, None, 0.0
    backbone_breaks = []
    for k in range(1, x.size):
        if stage[k] == 0:
            continue
        step = np.sign(x[k] - x[k - 1])
        if direction and step != direction:
            a = x[k - 1]
            if abs(a) < envelope * (1.0 - 1e-12):
                break                              # a turn inside the envelope: the comparison ends
            turn = a
            if first_drop is None:
                first_drop = (F_turn, F[k - 1])
        direction = step
        envelope = max(envelope, abs(x[k]))
        want = _closed_form_force(bearing, x[k], turn, step)
        assert abs(F[k] - want) <= 1e-9 * W, (k, x[k], F[k], want)
        if stage[k - 1] == 0:                      # the force at a break from rest lies on the branch too
            assert abs(F[k - 1] - _closed_form_force(bearing, x[k - 1], turn, step)) <= 1e-9 * W
        if turn is None or abs(x[k]) > abs(turn):
            backbone_breaks.append((abs(x[k]), stage[k]))
        F_turn = F[k]
        checked += 1
    assert checked >= 10
    assert first_drop is not None
    assert first_drop[0] - first_drop[1] == pytest.approx(math.copysign(2.0 * bearing.mu[0] * W, first_drop[0]),
                                                          rel=1e-9)
    # on the backbone the regime ends where the closed form says
    bounds = tfp.regime_boundaries(bearing).u
    ends = {s: u for u, s in backbone_breaks}
    for s in (1, 2, 3, 4):
        assert ends[s] == pytest.approx(bounds[s], rel=1e-9)
    assert sorted(ends) == [1, 2, 3, 4, 5]
    assert np.max(np.abs(F[stage != 0])) == pytest.approx(W / b.gravity, rel=2e-2)


@pytest.mark.parametrize("a_p_over_g, c", [(0.37, 0.0), (0.42, 0.3)])
def test_energy_balance_with_every_surface_and_the_contents(a_p_over_g, c):
    """Input work = kinetic + W sum u_i^2/(2 L_i) + plate-rotation work + friction works + viscous, to 1e-7.

    Runs that reach regime IV or V with sliding contents, without and with a viscous damper.  Every friction work is non-negative and every
    surface slides; the plate-rotation work (an inner surface sliding on its rotated plate) is a
    sizeable part of the balance: in this model of massless sliders the gravity terms are not the
    gradient of a potential.
    """
    run = run_tfp(_building(a_p_over_g, 2.0, c=c))
    assert run.peak_stage >= 4 and run.pi1 > 1e-3 and run.settled
    e = run.vertices["energy"]
    work = e[:, ENERGY_NAMES.index("work")]
    assert np.max(np.abs(run.balance())) <= 1e-7 * np.max(work)
    friction = e[:, [ENERGY_NAMES.index(f"friction{i}") for i in (1, 2, 3, 4)]]
    assert np.all(friction >= -1e-15) and np.all(friction[-1] > 0.0)
    assert np.all(np.diff(e[:, ENERGY_NAMES.index("contents")]) >= -1e-15)
    assert abs(e[-1, ENERGY_NAMES.index("plate")]) > 1e-3 * work[-1]
    if c:
        assert e[-1, ENERGY_NAMES.index("viscous")] > 0.0


@pytest.mark.parametrize("a_p_over_g", [0.2, 0.37])
def test_flipping_the_pulse_flips_every_displacement_exactly(a_p_over_g):
    """polarity = -1: the same event times and the negated slab, contents, surfaces and force, bit for bit."""
    a = run_tfp(_building(a_p_over_g, 2.0), history=True)
    b = run_tfp(_building(a_p_over_g, 2.0, polarity=-1), history=True)
    assert a.pi1 > 0.0 or a_p_over_g < 0.3
    assert np.array_equal(a.vertices["tau"], b.vertices["tau"])
    for key in ("x", "xd", "u", "ud", "F", "surfaces"):
        assert np.array_equal(a.vertices[key], -b.vertices[key]), key
    for key in ("x", "u", "F"):
        assert np.array_equal(a.history[key], -b.history[key]), key
    assert (a.pi1, a.x_peak, a.peak_stage, a.settled) == (b.pi1, b.x_peak, b.peak_stage, b.settled)
    assert [(t, s) for t, s in a.stages] == [(t, s) for t, s in b.stages]


REGIMES = [(1.0, 0.05, 1), (1.0, 0.1, 2), (2.0, 0.2, 3), (2.0, 0.34, 4), (2.0, 0.365, 5)]


@pytest.mark.parametrize("T_p, a_p_over_g, regime", REGIMES)
def test_scenes_reach_each_regime(T_p, a_p_over_g, regime):
    """Ricker pulses of T_p (s) and a_p reach regimes I..V: the peak stage, and the closed-form regime of the slab's peak.

    The regimes first appear in order I, II, ... up to the peak one.
    """
    b = _building(a_p_over_g, T_p)
    run = run_tfp(b)
    assert run.settled
    assert run.peak_stage == regime
    assert tfp.peak_regime(b.bearing, run.x_peak) == regime
    first = list(dict.fromkeys(s for _, s in run.stages if s > 0))
    assert first == list(range(1, regime + 1))


def test_the_bearing_total_travel_is_refused_with_the_time():
    """A slab reaching every restrainer in its direction raises, naming the time and the travel."""
    with pytest.raises(RuntimeError, match="total travel"):
        run_tfp(_building(0.6, 2.0))


@pytest.mark.parametrize("change, match", [
    ({"polarity": 0}, "polarity"),
    ({"gravity": 0.0}, "gravity"),
    ({"pi5": 1.5}, "pi5"),
    ({"mu": (0.1, 0.06, 0.02)}, "mu1"),
])
def test_inputs_outside_their_ranges_are_refused(change, match):
    """Pi-form inputs are checked on construction, the bearing against the admissible set of the closed forms."""
    kw = dict(L=(0.01, 0.05, 0.06), mu=(0.02, 0.06, 0.1), d=(0.002, 0.01, 0.012), gravity=5.0, pi2=0.5, pi5=0.8,
              pi8=0.05)
    kw.update(change)
    with pytest.raises(ValueError, match=match):
        TFPBuilding(**kw)


def test_the_single_pendulum_scene_needs_equal_frictions():
    """Different frictions have no single-friction-pendulum equivalent."""
    with pytest.raises(ValueError, match="mu1 = mu2 = mu3"):
        single_pendulum_scene(_building(0.3, 2.0))
