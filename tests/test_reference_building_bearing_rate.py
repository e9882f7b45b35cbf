"""A sliding bearing whose friction rises with speed in the general building's SciPy reference peer.

The bearing (``Pi9 > 0``, ``Pi10 = 0``) slides against ``q(|x'|) n = Pi9 (1 - (1 - Pi22)
exp(-Pi23 |x'|)) n`` and is held while its need is within the breakaway level ``Pi9 Pi22 n``
(:mod:`isoslide.peers.reference_building`).  Checked here: the constant-friction forms against the
constant-strength scene, the limit of a fast rate, the energy balance, the settlement of a bearing
that creeps after the pulse, and the normal-force factor of vertical ground motion.
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from isoslide import Scene
from isoslide.peers.reference_building import run_building, solve_reference_building
from isoslide.pulses import sampled

RIGID = dict(pi2=0.2, pi3=2.0, pi9=0.2, pi8=0.01)
"""Contents on the slab of a rigid building on a friction pendulum, Ricker pulse."""

FLEXIBLE_ROOF = dict(pi2=0.15, pi3=2.0, pi4=0.08, pi5=0.7, pi6=60.0, pi7=0.05, pi8=0.3, pi9=0.12, pi11=0.6,
                     pi12=0.3, pi13=0.04, floor="roof")
"""Stribeck contents on the roof of a flexible building on a friction pendulum, Ricker pulse."""


def _same_run(a, b):
    """Assert two runs with histories are the same to the bit (result and every recorded state)."""
    ra, rb = a.result, b.result
    for name in ("pi1", "pi1_residual", "tau_peak", "settled", "n_events", "tau_end", "nfev"):
        assert getattr(ra, name) == getattr(rb, name), name
    for name in ("tau", "x", "xd", "u", "ud", "fh", "phase", "iso_phase"):
        assert np.array_equal(getattr(ra.history, name), getattr(rb.history, name)), name


@pytest.mark.parametrize("kw", [RIGID, FLEXIBLE_ROOF], ids=["rigid", "flexible-roof"])
def test_a_zero_rate_is_the_constant_strength_at_breakaway_to_the_bit(kw):
    """``Pi23 = 0``: friction ``Pi9 Pi22`` at every speed, the same run to the bit as the scene of
    constant strength ``Pi9 Pi22``; with ``Pi23 > 0`` the answer differs by more than 1 %, so the
    bearing matters in these scenes."""
    slow = 0.5
    zero = run_building(Scene(**kw, pi22=slow, pi23=0.0), history=True)
    plain = run_building(Scene(**dict(kw, pi9=kw["pi9"] * slow)), history=True)
    _same_run(zero, plain)
    rising = solve_reference_building(Scene(**kw, pi22=slow, pi23=200.0))
    assert abs(rising.pi1 - plain.result.pi1) > 1e-2 * plain.result.pi1


@pytest.mark.parametrize("kw", [RIGID, FLEXIBLE_ROOF], ids=["rigid", "flexible-roof"])
def test_a_ratio_of_one_is_the_constant_strength_to_the_bit(kw):
    """``Pi22 = 1`` (``mu_slow = mu_fast``): whatever ``Pi23``, the same run to the bit as the scene of
    constant strength ``Pi9``."""
    one = run_building(Scene(**kw, pi22=1.0, pi23=200.0), history=True)
    plain = run_building(Scene(**kw), history=True)
    _same_run(one, plain)


FAST_LIMIT = dict(pi2=0.15, pi3=2.5, pi4=0.05, pi9=0.1, pi8=0.3, pulse="makris_b")
RATES = (800.0, 1600.0, 3200.0, 6400.0, 12800.0)


def test_a_fast_rate_tends_to_the_constant_fast_friction_at_first_order():
    """As ``Pi23`` grows the friction is ``Pi9`` at any speed but a vanishing one, and the bearing
    creeps only ``O(1/Pi23)`` before it takes ``Pi9``: Pi1 tends to the constant-``Pi9`` scene's at
    first order.  Measured: the error halves with each doubling of ``Pi23`` (ratios 2.004 .. 2.001
    from 800 to 12800; required 1.9 .. 2.1), and the Richardson extrapolation ``2 P(2a) - P(a)``
    of the last pair is within 1e-7 of the limit (2e-8 measured; the error itself is 8e-5 there)."""
    limit = solve_reference_building(Scene(**FAST_LIMIT)).pi1
    p = [solve_reference_building(Scene(**FAST_LIMIT, pi22=0.5, pi23=a)).pi1 for a in RATES]
    err = [abs(v - limit) for v in p]
    assert err[0] > 1e-3 * limit
    ratios = [e0 / e1 for e0, e1 in zip(err, err[1:], strict=False)]
    assert all(1.9 < r < 2.1 for r in ratios), ratios
    assert abs(2.0 * p[-1] - p[-2] - limit) < 1e-7 * limit


def test_a_fast_rate_shrinks_the_gap_to_the_constant_fast_friction_monotonically():
    """A scene whose Pi1 moves by 11 % between ``Pi23 = 50`` and the limit: its distance to the
    constant-``Pi9`` scene shrinks with each doubling of ``Pi23`` from 50 to 6400, by a factor
    of at least 1.2 each time (1.24 .. 1.71 measured, rising towards 2: slower than first order
    at these rates) and to below 1 % of the limit at the end (0.58 % measured)."""
    kw = dict(pi2=0.2, pi3=2.0, pi9=0.3, pi8=0.01)
    limit = solve_reference_building(Scene(**kw)).pi1
    err = [abs(solve_reference_building(Scene(**kw, pi22=0.5, pi23=50.0 * 2 ** k)).pi1 - limit) for k in range(8)]
    assert err[0] > 0.1 * limit
    assert all(e1 * 1.2 < e0 for e0, e1 in zip(err, err[1:], strict=False)), err
    assert err[-1] < 1e-2 * limit


ENERGY_SCENES = {"rigid-creeping": dict(RIGID, pi22=0.5, pi23=200.0),
                 "rigid-coulomb": dict(pi2=0.1, pi3=2.0, pi4=0.05, pi8=1.0, pi9=0.1, pi22=0.4, pi23=30.0),
                 "flexible-base-makris": dict(pi2=0.12, pi3=2.5, pi4=0.05, pi8=0.5, pi9=0.07, pi11=0.5, pi12=0.25,
                                              pi13=0.03, floor="base", pulse="makris_b", pi22=0.6, pi23=50.0)}


@pytest.mark.parametrize("name", list(ENERGY_SCENES))
def test_energy_balance_with_friction_that_rises_with_speed(name):
    """Input work = kinetic + potential + viscous + isolator + contents-friction dissipation at every
    recorded time, to 1e-10 of the input work (1e-13 or less measured), the energies computed here from the
    states; and the bearing's dissipation ``int q(|x'|) |x'|`` lies strictly between ``Pi9 Pi22``
    and ``Pi9`` times the slab's travel (its total variation): at least 1.5 times the first and
    0.1 % below the second, so a ledger at either constant level fails."""
    sc = Scene(**ENERGY_SCENES[name])
    run = run_building(sc, ledger=True)
    h, L = run.result.history, run.ledger
    mst = sc.pi11 if sc.pi12 > 0 else 0.0
    mb, m = 1.0 - mst, sc.pi8
    xs = h.xs if h.xs is not None else 0.0 * h.x
    xsd = h.xsd if h.xsd is not None else 0.0 * h.x
    kinetic = 0.5 * (mb * h.xd ** 2 + mst * (h.xd + xsd) ** 2 + m * (h.xd + h.ud) ** 2)
    kd = (2.0 * math.pi / sc.pi3) ** 2
    ks = mst * (2.0 * math.pi / sc.pi12) ** 2 if sc.pi12 > 0 else 0.0
    potential = 0.5 * kd * h.x ** 2 + 0.5 * ks * xs ** 2
    accounted = kinetic + potential + L["viscous"] + L["isolator"] + L["friction"]
    W = np.max(np.abs(L["work"]))
    assert run.result.pi1 > 0.0 and L["friction"][-1] > 1e-3 * W and L["isolator"][-1] > 0.1 * W
    for key in ("viscous", "isolator", "friction"):
        assert np.all(np.diff(L[key]) >= -1e-15 * W)
    assert np.max(np.abs(L["work"] - accounted)) <= 1e-10 * W
    travel = float(np.sum(np.abs(np.diff(h.x))))     # every stop of the slab is a recorded event
    iso = L["isolator"][-1]
    assert 1.5 * sc.pi9 * sc.pi22 * travel < iso < (1.0 - 1e-3) * sc.pi9 * travel


CREEP_SCENES = {
    "creeps to the band's edge": dict(RIGID, pi22=0.5, pi23=200.0),
    "stops inside the band": dict(pi2=0.1, pi3=2.0, pi8=1.0, pi9=0.1, pi22=0.4, pi23=30.0),
}


@pytest.mark.parametrize("name", list(CREEP_SCENES))
def test_a_bearing_moving_after_the_pulse_is_proven_settled(name):
    """Rigid building, contents stuck, bearing still moving in ``s`` after the pulse: the run settles
    by the bound ``E = M x'^2/2 + kd (x - x*)^2/2``, ``x* = -s Pi9 Pi22/kd``, while the slab is
    still outside its stick band (creeping) or inside it but moving.  Followed 60 pulse periods
    further without the rule, the contents never slip again (Pi1 and the residual slide equal to the
    bit, required 1e-12), ``E`` never grows while the bearing moves in ``s`` (the derivation's
    ``dE/dtau <= 0``), and the bearing either creeps for ever towards the band's edge
    ``|kd x| = Pi9 Pi22`` (its linearisation over-damped) or stops inside the band and is held."""
    sc = Scene(**CREEP_SCENES[name])
    kd, M = (2.0 * math.pi / sc.pi3) ** 2, 1.0 + sc.pi8
    cb = 2.0 * sc.pi4 * 2.0 * math.pi / sc.pi3
    q0, c_lin = sc.pi9 * sc.pi22, cb + sc.pi9 * (1.0 - sc.pi22) * sc.pi23
    done = run_building(sc, history=True).result
    h = done.history
    s = int(h.iso_phase[-1])
    assert done.settled and s != 0 and h.phase[-1] == 0 and done.pi1 > 0.0
    assert done.tau_end >= sc.pulse.tau_end
    x_eq = -s * q0 / kd
    on = run_building(sc, settle=False, tau_max=done.tau_end + 60.0, history=True).result
    assert not on.settled and on.tau_end == pytest.approx(done.tau_end + 60.0)
    assert on.pi1 == pytest.approx(done.pi1, rel=1e-12, abs=0.0)
    assert on.pi1_residual == pytest.approx(done.pi1_residual, rel=1e-12, abs=0.0)
    H = on.history
    late = H.tau >= done.tau_end
    assert np.all(H.phase[late] == 0)
    moving = late & (H.iso_phase == s)
    E = 0.5 * M * H.xd[moving] ** 2 + 0.5 * kd * (H.x[moving] - x_eq) ** 2
    assert np.all(np.diff(E) <= 1e-13 * E[0])
    if c_lin ** 2 > 4.0 * kd * M:          # over-damped: never stops, ends at the band's edge
        assert np.all(H.iso_phase[late] == s) and s * H.xd[-1] > 0.0
        assert kd * abs(h.x[-1]) > 1.2 * q0          # outside the band when it settled
        assert abs(kd * abs(H.x[-1]) / q0 - 1.0) < 1e-10
    else:
        assert H.iso_phase[-1] == 0 and kd * abs(H.x[-1]) <= q0
        iso = H.iso_phase[late]
        stop = int(np.nonzero(iso != s)[0][0])
        assert np.all(iso[stop:] == 0)         # stops once and is held


def _constant(tau0: float, sign: float = 1.0):
    """Vertical acceleration ``p_z = sign`` from ``tau0`` for 12 T_p (longer than the pulse's response)."""
    return sampled(sign * np.ones(13), 1.0, tau0=tau0, name="constant")


VERTICAL_KW = dict(pi2=0.15, pi3=2.0, pi4=0.1, pi8=0.01, pi5=0.7, pi6=80.0, pi7=0.05, pi9=0.08, pi22=0.4, pi23=50.0)


@pytest.mark.parametrize("c", [0.4, -0.3], ids=["upward", "downward"])
def test_a_constant_vertical_acceleration_scales_the_speed_dependent_friction(c):
    """``n = 1 + c`` throughout: the bearing's friction ``q(|x'|) n`` is the scene's of ``Pi9 -> n Pi9``
    (same ``Pi22``, ``Pi23``), its stiffness ``kd n`` is ``Pi3 -> Pi3/sqrt(n)`` (``Pi4 -> Pi4/sqrt(n)``
    keeps ``cb``), the contents' friction ``Pi2 -> n Pi2``, ``Pi7 -> n Pi7``: the same Pi1 to 1e-9
    relative (1e-14 measured).  The speed dependence moves Pi1 by more than 1 % here (against
    ``Pi22 = 1``), so a law that missed ``n`` in its rising part fails."""
    n = 1.0 + c
    vertical = dict(pi17=abs(c), pulse_z=_constant(-2.0, math.copysign(1.0, c)))
    res = solve_reference_building(Scene(**VERTICAL_KW, **vertical))
    scaled = dict(VERTICAL_KW, pi2=0.15 * n, pi7=0.05 * n, pi9=0.08 * n, pi3=2.0 / math.sqrt(n),
                  pi4=0.1 / math.sqrt(n))
    plain = solve_reference_building(Scene(**scaled))
    assert res.settled and res.pi1 > 0.0
    assert res.pi1 == pytest.approx(plain.pi1, rel=1e-9)
    const = solve_reference_building(Scene(**dict(VERTICAL_KW, pi22=1.0), **vertical))
    assert abs(const.pi1 - res.pi1) > 1e-2 * res.pi1


def test_the_first_breakaway_under_a_vertical_pulse_is_at_the_breakaway_level_times_n():
    """Contents that never slip (``Pi2 = 50``) on a rigid building: until the bearing first slides the
    slab is held and must supply ``(1 + Pi8) |p|``, so it breaks away at the first root of
    ``(1 + Pi8) |p(tau)| = Pi9 Pi22 (1 + Pi17 p_z(tau))``, found here from the pulses alone.  The
    peer's first slide starts there to 1e-9 (and in the direction of ``-p``); the root without the
    factor ``n`` is more than 1e-3 away, and ``n`` is more than 10 % from 1 there."""
    sc = Scene(pi2=50.0, pi3=2.0, pi8=0.01, pi9=0.6, pi22=0.5, pi23=200.0, pi17=0.5, pulse_z="ricker")
    q0, M = sc.pi9 * sc.pi22, 1.0 + sc.pi8

    def p(t):
        return float(sc.pulse.accel(np.array([t]))[0])

    def n(t):
        return 1.0 + sc.pi17 * float(sc.pulse_z.accel(np.array([t]))[0])

    def first_root(g):
        t = np.linspace(sc.pulse.tau_start, sc.pulse.tau_end, 4001)
        v = np.array([g(x) for x in t])
        i = int(np.nonzero(v > 0.0)[0][0])
        return brentq(g, t[i - 1], t[i], xtol=1e-15, rtol=4 * np.finfo(float).eps)

    t_break = first_root(lambda t: M * abs(p(t)) - q0 * n(t))
    t_static = first_root(lambda t: M * abs(p(t)) - q0)
    assert abs(n(t_break) - 1.0) > 0.1 and abs(t_static - t_break) > 1e-3
    h = solve_reference_building(sc, history=True).history
    i = int(np.nonzero(h.iso_phase != 0)[0][0])
    assert np.all(h.phase == 0)
    assert h.tau[i] == pytest.approx(t_break, abs=1e-9)
    assert h.iso_phase[i] == -np.sign(p(t_break))
