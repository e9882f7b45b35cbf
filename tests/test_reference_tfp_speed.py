"""The event-driven triple-friction-pendulum reference with friction rising with speed.

isoslide.peers.reference_tfp with mu_slow and rate: every surface follows mu(v) = mu - (mu - mu_slow)
exp(-a |v|) of its own sliding speed, sticks at its breakaway level, and the bearing's force is the
root of sum_i v_i(F) = x'.  Checked: constant friction (rate 0, or mu_slow = mu) is today's run bit
for bit; a brute-force integration of the same law (displacements as states, the force from brentq
at every step, no choice of modes) gives the same slab; the energy balance closes at every vertex;
flipping the pulse flips every answer bit for bit; two surfaces of one chain slide at once, and the
answer holds at a tenfold finer tolerance; Pi1 tends to the constant bearing of mu as the rate
grows (with a logarithmic term, which a three-rate extrapolation removes to 2e-6) and, at first
order, as mu_slow -> mu; inputs outside their ranges are refused.

Scenes: G = g/a_p, W = G (contents_weight=False), L = (0.1, 0.5, 0.5) Lsum with Lsum = (Pi3/(2 pi))^2 G
and Pi3 = 2, mu = (0.5, 1, 2) 0.05, Pi2 = 0.3, Pi8 = 1e-3, a Ricker pulse; limits d = (0.05, 0.1, 0.2) G
(regimes I to III) or (0.08, 0.01, 0.06) (surfaces 1 and 4 reach their restrainers).
"""

import functools
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from isoslide.peers.reference_tfp import A_PIN, ENERGY_NAMES, TFPBuilding, run_tfp, single_pendulum_scene
from isoslide.pulses import accel_at

MU = (0.025, 0.05, 0.1)
FREE = (0.05, 0.1, 0.2)
STOPS = (0.08, 0.01, 0.06)


def _kw(G=1.0, d=FREE):
    lsum = (2.0 / (2.0 * math.pi)) ** 2 * G
    return dict(L=tuple(f * lsum for f in (0.1, 0.5, 0.5)), mu=MU, d=tuple(x * G for x in d), gravity=G, pi2=0.3,
                pi8=1e-3, contents_weight=False)


def _run(G=1.0, d=FREE, slow=0.5, rate=100.0, polarity=1, rtol=None, atol=None):
    """A run with its history (cached): mu_slow = slow * mu (None: constant mu)."""
    return _cached(G, d, slow, rate, polarity, rtol, atol)


@functools.lru_cache(maxsize=None)
def _cached(G, d, slow, rate, polarity, rtol, atol):
    kw = _kw(G, d)
    if slow is None:
        b = TFPBuilding(**kw, polarity=polarity)
    else:
        b = TFPBuilding(**kw, mu_slow=tuple(slow * m for m in MU), rate=rate, polarity=polarity)
    return run_tfp(b, rtol=rtol, atol=atol, history=True)


def _same_run(a, b):
    assert (a.pi1, a.x_peak, a.tau_end, a.settled, a.stages) == (b.pi1, b.x_peak, b.tau_end, b.settled, b.stages)
    assert a.vertices.keys() == b.vertices.keys()
    for key in a.vertices:
        assert np.array_equal(a.vertices[key], b.vertices[key]), key


def test_constant_friction_is_the_constant_run_bit_for_bit():
    """rate = 0 (friction mu_slow at every speed) and mu_slow = mu (mu at every speed) are the constant peer.

    The scene with restrainers: its Pi1 is today's 0.08290516704451625 (to the last bits, which the
    processor's vector paths may move); mu_slow = mu with a
    rate, and rate = 0 with mu = 2 mu_slow, give the same vertices to the bit.
    """
    today = _run(d=STOPS, slow=None)
    assert today.pi1 == pytest.approx(0.08290516704451625, rel=1e-14)
    same_mu = run_tfp(TFPBuilding(**_kw(d=STOPS), mu_slow=MU, rate=(50.0, 80.0, 20.0)))
    _same_run(today, same_mu)
    kw = _kw(d=STOPS)
    halved = run_tfp(TFPBuilding(**{**kw, "mu": tuple(0.5 * m for m in MU)}))
    slow_only = run_tfp(TFPBuilding(**kw, mu_slow=tuple(0.5 * m for m in MU), rate=0.0))
    _same_run(halved, slow_only)
    assert not TFPBuilding(**kw, mu_slow=MU, rate=5.0).rate_dependent
    assert TFPBuilding(**kw, mu_slow=0.02, rate=5.0).rate_dependent


def _brute(b, t_stop, rtol=1e-11, atol=1e-14, max_step=2e-3):
    """Slab and surfaces by a plain integration of the law, the contents stuck (``Pi2`` large).

    States ``x, x', u_1..u_4``; while the slab moves its force is the root of ``sum_i v_i(F) = x'``
    (brentq), each ``v_i(F)`` zero within the slow level, the law beyond it and nothing outward at a
    restrainer; the slab stops at ``x' = 0`` and is held while ``-(1 + Pi8) p`` lies in the band of the
    slow levels.  The only events are the slab's and the restrainers'.
    """
    bb = b.bearing
    (L1, L2, L3), (f1, f2, f3), (s1, s2, s3), (a1, a2, a3), (d1, d2, d3) = bb.L, bb.mu, bb.mu_slow, bb.rate, bb.d
    W, M = bb.W, 1.0 + b.pi8
    R, D = np.array([L2, L1, L1, L3]), np.array([d2, d1, d1, d3])
    qf, qs, A = W * np.array([f2, f1, f1, f3]), W * np.array([s2, s1, s1, s3]), np.array([a2, a1, a1, a3])
    code, params = int(b.pulse.code), b.pulse.param_array

    def p_of(t):
        return b.polarity * accel_at(code, params, t)

    def slopes(u):
        return np.array([u[0] / R[0], u[0] / R[0] + u[1] / R[1], u[3] / R[3] + u[2] / R[2], u[3] / R[3]])

    def speeds(F, u):
        q, v = F - W * slopes(u), np.zeros(4)
        for i in range(4):
            if q[i] > qs[i] and u[i] < D[i]:
                g = qf[i] - q[i]
                v[i] = math.inf if g <= 0.0 else -math.log(g / (qf[i] - qs[i])) / A[i]
            elif q[i] < -qs[i] and u[i] > -D[i]:
                g = qf[i] + q[i]
                v[i] = -math.inf if g <= 0.0 else math.log(g / (qf[i] - qs[i])) / A[i]
        return v

    def edge(u, s):
        lim = W * slopes(u) + s * qs
        return lim[s * u < D].min() if s > 0 else lim[s * u < D].max()

    def force(u, xd, s):
        if xd * s <= 0.0:
            return edge(u, s)
        lo, hi = (edge(u, 1), (W * slopes(u) + qf)[u < D].min()) if s > 0 else \
            ((W * slopes(u) - qf)[u > -D].max(), edge(u, -1))
        f = lambda F: speeds(F, u).sum() - xd  # noqa: E731
        while not (math.isfinite(f(lo)) and math.isfinite(f(hi))):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if f(mid) < 0.0 else (lo, mid)
        return lo if f(lo) >= 0.0 else (hi if f(hi) <= 0.0 else brentq(f, lo, hi, xtol=1e-300, rtol=1e-15))

    tau, y, held, sigma, x_peak = float(b.pulse.tau_start), np.zeros(6), True, 0, 0.0
    while tau < t_stop:
        if held:
            lo, hi = edge(y[2:], -1), edge(y[2:], 1)
            evs = [lambda t, yy, hi=hi: hi + M * p_of(t), lambda t, yy, lo=lo: -M * p_of(t) - lo]
            for e in evs:
                e.terminal, e.direction = True, -1
            sol = solve_ivp(lambda t, yy: np.zeros(6), (tau, t_stop), y, events=evs, rtol=rtol, atol=atol,
                            max_step=max_step, method="DOP853")
            if sol.status != 1:
                break
            sigma = 1 if len(sol.t_events[0]) else -1
            tau, held = float(sol.t[-1]), False
            continue

        def rhs(t, yy, s=sigma):
            F = force(yy[2:], yy[1], s)
            return np.concatenate(([yy[1], -F / M - p_of(t)], speeds(F, yy[2:]) if yy[1] * s > 0.0 else np.zeros(4)))

        t0 = tau
        evs = [lambda t, yy, s=sigma, t0=t0: s * yy[1] if t > t0 else 1.0]
        for i in range(4):
            for sg in (1, -1):
                if sg * y[2 + i] < D[i] - 1e-13:
                    evs.append(lambda t, yy, i=i, sg=sg: D[i] - sg * yy[2 + i])
        for e in evs:
            e.terminal, e.direction = True, -1
        sol = solve_ivp(rhs, (tau, t_stop), y, events=evs, rtol=rtol, atol=atol, max_step=max_step, method="DOP853")
        tau, y = float(sol.t[-1]), np.array(sol.y[:, -1])
        y[2:] = np.clip(y[2:], -D, D)
        if sol.status != 1 or not len(sol.t_events[0]):
            continue
        y[1], x_peak = 0.0, max(x_peak, abs(y[0]))
        need = -M * p_of(tau)
        held = edge(y[2:], -1) <= need <= edge(y[2:], 1)
        sigma = 0 if held else (1 if need > edge(y[2:], 1) else -1)
    return x_peak, y


@pytest.mark.slow
def test_a_plain_integration_of_the_law_gives_the_same_slab():
    """Without modes or pinning: the slab's peak and the final x and u_i agree with the brute force to 1e-8.

    Rate 10 (stiff enough to need Radau in the reference, mild enough for DOP853 through the root), the
    contents stuck (Pi2 = 100), over the pulse and 1.5 T_p after it: regimes I to III and back, and the
    set of sliding surfaces changes some 50 times (both surfaces of a chain sliding in some 40 phases).
    """
    kw = {**_kw(), "pi2": 100.0}
    b = TFPBuilding(**kw, mu_slow=tuple(0.5 * m for m in MU), rate=10.0)
    t_stop = float(b.pulse.tau_end) + 1.5
    run = run_tfp(b, tau_max=t_stop)
    x_peak, y = _brute(b, t_stop)
    sl = run.vertices["sliding"]
    assert np.count_nonzero(((sl[:, 0] != 0) & (sl[:, 1] != 0)) | ((sl[:, 2] != 0) & (sl[:, 3] != 0))) >= 20
    assert run.n_events > 40 and run.x_peak > 0.05
    assert run.x_peak == pytest.approx(x_peak, rel=1e-8)
    assert abs(run.vertices["x"][-1] - y[0]) <= 1e-8 * run.x_peak
    assert np.max(np.abs(run.vertices["surfaces"][-1] - y[2:])) <= 1e-8 * run.x_peak


@pytest.mark.parametrize("d", [FREE, STOPS], ids=["regimes I-III", "restrainers"])
def test_energy_balance_at_every_vertex(d):
    """Input work = kinetic + W sum u_i^2/(2 L_i) + plate-rotation work + friction works + contents, to 1e-9.

    Each surface's friction work int q_i v_i dtau is an integrated state; every surface slides (each
    friction work positive at the end) and none dissipates negatively.
    """
    run = _run(d=d)
    assert run.settled and run.pi1 > 1e-3
    e = run.vertices["energy"]
    work = e[:, ENERGY_NAMES.index("work")]
    assert np.max(np.abs(run.balance())) <= 1e-9 * np.max(work)
    friction = e[:, [ENERGY_NAMES.index(f"friction{i}") for i in (1, 2, 3, 4)]]
    assert np.all(np.diff(friction, axis=0) >= -1e-13 * np.max(work)) and np.all(friction[-1] > 0.0)
    assert abs(e[-1, ENERGY_NAMES.index("plate")]) > 1e-3 * work[-1]
    if d == STOPS:
        assert run.peak_stage == 4


@pytest.mark.parametrize("G, d, slow, rate", [(1.0, STOPS, 0.5, 100.0), (30.0, FREE, 0.8, 102400.0)],
                         ids=["restrainers", "pinned"])
def test_flipping_the_pulse_flips_every_answer_bit_for_bit(G, d, slow, rate):
    """polarity = -1: the same event times, the negated slab, contents, surfaces, speeds' directions and force.

    The second scene's rate pins the inner surfaces at their fast level (a |v| beyond 25) for a while.
    """
    a = _run(G=G, d=d, slow=slow, rate=rate)
    b = _run(G=G, d=d, slow=slow, rate=rate, polarity=-1)
    assert np.array_equal(a.vertices["tau"], b.vertices["tau"])
    for key in ("x", "xd", "u", "ud", "F", "surfaces", "sliding"):
        assert np.array_equal(a.vertices[key], -b.vertices[key]), key
    for key in ("x", "u", "F", "surfaces"):
        assert np.array_equal(a.history[key], -b.history[key]), key
    assert (a.pi1, a.x_peak, a.peak_stage, a.settled, a.stages) == (b.pi1, b.x_peak, b.peak_stage, b.settled, b.stages)
    assert np.array_equal(a.vertices["energy"], b.vertices["energy"])
    if rate > 1e4:      # the two inner surfaces share the slab's speed: a |v| well past A_PIN
        assert rate * np.max(np.abs(a.history["xd"])) / 2.0 > 10.0 * A_PIN


def test_two_surfaces_of_one_chain_slide_at_once():
    """An outer surface's reaction rises above its slow level with speed, so its inner one keeps sliding.

    In the scene of regimes I to III, surfaces 1 and 2 (and 3 and 4) slide together in several phases,
    which the constant bearing never does; the vertices, Pi1 and the slab's peak agree with a run at
    a tenfold finer tolerance to 1e-9 (the surfaces to 1e-7 of the slab's peak).
    """
    run = _run()
    sl = run.vertices["sliding"]
    lower = np.count_nonzero((sl[:, 0] != 0) & (sl[:, 1] != 0))
    upper = np.count_nonzero((sl[:, 2] != 0) & (sl[:, 3] != 0))
    assert lower >= 5 and upper >= 5
    constant = _run(slow=None).vertices["sliding"]
    assert not np.any((constant[:, 0] != 0) & (constant[:, 1] != 0))
    fine = _run(rtol=1e-10, atol=1e-12)
    assert fine.n_events == run.n_events
    assert fine.pi1 == pytest.approx(run.pi1, rel=1e-9)
    assert fine.x_peak == pytest.approx(run.x_peak, rel=1e-9)
    assert np.max(np.abs(fine.vertices["surfaces"] - run.vertices["surfaces"])) <= 1e-7 * run.x_peak


def test_pi1_tends_to_the_fast_constant_bearing_as_the_rate_grows():
    """Pi1(rate) = Pi1(mu) + (A ln(rate) + B)/rate: three rates give Pi1(mu) to 2e-6 of it.

    A scene that stays in regime I (G = 30, mu_slow = 0.8 mu, the inner surfaces creeping for near
    rate L1 (Q_fast - Q_slow)/W = rate/660 T_p).  The error is not first order: rate times it grows by
    A ln 2 per doubling, so Richardson's first-order rule leaves 4e-5; with the logarithm the fit of
    rates 25600, 51200 and 102400 (surfaces pinned part of the time) lands within 2e-6.
    """
    fast = _run(G=30.0, slow=None).pi1
    rates = (25600.0, 51200.0, 102400.0)
    pi1 = [_run(G=30.0, slow=0.8, rate=r).pi1 for r in rates]
    assert all(_run(G=30.0, slow=0.8, rate=r).peak_stage == 1 for r in rates)
    err = [(p - fast) * r for p, r in zip(pi1, rates, strict=True)]
    steps = np.diff(err)
    assert steps[1] == pytest.approx(steps[0], rel=0.05)       # the same A ln 2 per doubling
    assert abs(2.0 * pi1[2] - pi1[1] - fast) > 1e-5 * fast      # first order is not enough
    fit = np.linalg.solve([[1.0, math.log(r) / r, 1.0 / r] for r in rates], pi1)
    assert fit[0] == pytest.approx(fast, rel=2e-6)


def test_pi1_tends_to_the_constant_bearing_at_first_order_as_mu_slow_tends_to_mu():
    """mu_slow = (1 - eps) mu at rate 400: Richardson's rule on eps and eps/2 gives Pi1(mu) to 2e-6 of it."""
    fast = _run(G=30.0, slow=None).pi1
    eps = (0.003125, 0.0015625)
    pi1 = [_run(G=30.0, slow=1.0 - e, rate=400.0).pi1 for e in eps]
    assert abs(pi1[1] - fast) > 1e-5 * fast
    assert 2.0 * pi1[1] - pi1[0] == pytest.approx(fast, rel=2e-6)


def test_from_physical_scales_the_rate():
    """``rate`` in s/m becomes ``a a_p T_p``; one value or three."""
    b = TFPBuilding.from_physical(L=(0.3, 2.0, 2.5), mu=(0.02, 0.06, 0.1), d=(0.05, 0.35, 0.4), a_p=3.0, T_p=1.5,
                                  mass_ratio=0.05, mu_s=0.12, mu_k=0.1, mu_slow=(0.01, 0.03, 0.05), rate=20.0)
    assert b.rate == (90.0, 90.0, 90.0) and b.mu_slow == (0.01, 0.03, 0.05) and b.rate_dependent
    b3 = TFPBuilding.from_physical(L=(0.3, 2.0, 2.5), mu=(0.02, 0.06, 0.1), d=(0.05, 0.35, 0.4), a_p=3.0, T_p=1.5,
                                   mass_ratio=0.05, mu_s=0.12, mu_k=0.1, mu_slow=(0.01, 0.03, 0.05),
                                   rate=(20.0, 10.0, 30.0))
    assert b3.rate == (90.0, 45.0, 135.0)
    assert b3.bearing.rate == b3.rate and b3.bearing.mu_slow == (0.01, 0.03, 0.05)


@pytest.mark.parametrize("change, match", [
    ({"rate": 10.0}, "rate = 10.0 is given without mu_slow"),
    ({"mu_slow": 0.03, "rate": 10.0}, "mu_slow1 = 0.03 exceeds mu1"),
    ({"mu_slow": 0.01, "rate": -1.0}, "rate1 = -1.0 is out of range"),
    ({"mu_slow": (0.01, 0.02), "rate": 10.0}, "mu_slow = .* must be one value or three"),
    ({"mu_slow": (0.025, 0.03, 0.05), "rate": 10.0}, "keep mu1 constant .* while mu2, mu3 rise"),
    ({"mu_slow": 0.01, "rate": (10.0, 0.0, 10.0)}, "keep mu2 constant"),
    ({"mu_slow": (0.01, 0.02, 0.1), "rate": 10.0}, "keep mu3 constant"),
])
def test_inputs_outside_their_ranges_are_refused(change, match):
    """mu_slow and rate are checked on construction, naming the parameter, its value and the rule."""
    with pytest.raises(ValueError, match=match):
        TFPBuilding(**{**_kw(), **change})


def test_the_single_pendulum_scene_needs_constant_friction():
    """A friction rising with speed has no single-friction-pendulum equivalent (every surface then slides)."""
    kw = {**_kw(), "mu": (0.05, 0.05, 0.05)}
    with pytest.raises(ValueError, match="rises with speed"):
        single_pendulum_scene(TFPBuilding(**kw, mu_slow=0.03, rate=50.0))
    assert single_pendulum_scene(TFPBuilding(**kw, mu_slow=0.03, rate=0.0)).pi9 == pytest.approx(0.03)
