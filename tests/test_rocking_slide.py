"""Tests of the rest-slide-rock-slide-rock peer (isoslide.peers.slide_rock) against closed forms, the rock-only
peer and physical invariants."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from isoslide.model.rocking import G_STANDARD, Block
from isoslide.peers.rocking import RockingContactError, solve_rocking
from isoslide.peers.slide_rock import REST, ROCK, SLIDE, SLIDE_ROCK, solve_block
from rocking_cases import rectangular, ricker  # tests/ is on sys.path

G = G_STANDARD


def sine(a, T, cycles):
    w = 2 * math.pi / T

    def f(t):
        return a * math.sin(w * t) if 0.0 <= t < cycles * T else 0.0
    return f


def names(res):
    return [n for _, n, _ in res.modes]


# ------------------------------------------------------------------------------------------ pure sliding

@pytest.mark.parametrize("a_ratio,t_d,mu_s,mu_k", [(0.5 / 0.2, 0.3, 0.2, 0.2), (3.0, 0.1, 0.15, 0.15),
                                                  (2.0, 0.25, 0.3, 0.2)])
def test_rectangular_pulse_sliding_matches_newmarks_closed_form(a_ratio, t_d, mu_s, mu_k):
    """During the pulse u'' = -(a - mu_k g), after it the block decelerates at mu_k g and stops at
    t_s = t_d a / (mu_k g), having slid u_max = a t_d^2 (a / (mu_k g) - 1) / 2 (to 1e-12 relative);
    theta stays 0 and the modes are rest, slide, rest."""
    blk = Block(0.5, 0.25)                         # squat: b/h = 2
    a = a_ratio * mu_k * G
    res = solve_block(blk, rectangular(a, t_d), 3.0, mu_s=mu_s, mu_k=mu_k, t_quiet=t_d, history=True)
    u_max = a * t_d ** 2 * (a / (mu_k * G) - 1) / 2
    t_stop = t_d * a / (mu_k * G)
    assert res.u_max == pytest.approx(u_max, rel=1e-12)
    assert res.u_end == pytest.approx(-u_max, rel=1e-12) and res.t_u_max == pytest.approx(t_stop, rel=1e-12)
    assert names(res) == ["rest", "slide", "rest"]
    assert res.modes[1][0] == 0.0 and res.modes[1][2] == -1
    assert res.modes[2][0] == pytest.approx(t_stop, rel=1e-12)
    assert res.theta_max == 0.0 and np.all(res.history.theta == 0.0) and res.settled


def _floor_and_integrals(kind, a):
    """A floor acceleration with its first and second time integrals in closed form, and its support."""
    if kind.startswith("ricker"):
        T = 0.5

        def V1(t):
            tc = min(max(t, -2 * T), 2 * T)
            return a * tc * math.exp(-(math.pi * tc / T) ** 2)

        def V2(t):
            tc = min(max(t, -2 * T), 2 * T)
            return -a * T ** 2 / (2 * math.pi ** 2) * (math.exp(-(math.pi * tc / T) ** 2) - math.exp(-4 * math.pi ** 2))
        return ricker(a, T), V1, V2, -2 * T, 2 * T
    T, cycles = 0.4, int(kind[-1])
    w = 2 * math.pi / T

    def V1(t):
        tc = min(max(t, 0.0), cycles * T)
        return a / w * (1 - math.cos(w * tc))

    def V2(t):
        tc = min(max(t, 0.0), cycles * T)
        return a / w * (tc - math.sin(w * tc) / w)
    return sine(a, T, cycles), V1, V2, 0.0, cycles * T


def _sliding_reference(A, V1, V2, t0, t1, mu_s, mu_k, n=40_000):
    """A block that cannot tip, sliding on the floor: between stops the velocity and displacement are closed
    forms of the floor's integrals, v = v_s - [V1]_ts^t - mu_k sigma g (t - ts); the start and stop times are
    roots (brentq) bracketed on a fine grid.  Returns the peak |u| and the times the base starts and stops."""
    grid = np.linspace(t0, t1, n + 1)
    t, u, v, sigma = t0, 0.0, 0.0, 0.0
    peak, starts, stops = 0.0, [], []
    while True:
        if sigma == 0.0:                            # at rest: the first time |A| exceeds mu_s g
            ahead = grid[grid > t]
            over = [x for x in ahead if abs(A(x)) > mu_s * G]
            if not over:
                return peak, starts, stops
            x1 = over[0]
            x0 = max(t, ahead[ahead < x1][-1]) if np.any(ahead < x1) else t
            sgn_a = math.copysign(1.0, A(x1))
            t = brentq(lambda x, sa=sgn_a: sa * A(x) - mu_s * G, x0, x1, xtol=1e-15, rtol=1e-15)
            sigma = -sgn_a
            starts.append(t)
            continue
        ts, us, vs, sg = t, u, v, sigma

        def vel(x, ts=ts, vs=vs, sg=sg):
            return vs - (V1(x) - V1(ts)) - mu_k * sg * G * (x - ts)

        def disp(x, ts=ts, us=us, vs=vs, sg=sg):
            return us + vs * (x - ts) - (V2(x) - V2(ts) - V1(ts) * (x - ts)) - 0.5 * mu_k * sg * G * (x - ts) ** 2
        ahead = np.concatenate([grid[grid > ts], [t1 + 100.0]])
        x1 = next(x for x in ahead if sg * vel(x) <= 0)
        before = ahead[ahead < x1]
        x0 = before[-1] if len(before) else ts
        t = brentq(lambda x, sg=sg, vel=vel: sg * vel(x), x0, x1, xtol=1e-15, rtol=1e-15)
        u, v = disp(t), 0.0
        stops.append(t)
        peak = max(peak, abs(u))
        a_t = A(t)
        sigma = 0.0 if abs(a_t) <= mu_s * G else -math.copysign(1.0, a_t)


@pytest.mark.parametrize("kind,amp,mu_s,mu_k", [("ricker", 2.0, 0.4, 0.3), ("ricker", 3.0, 0.5, 0.5),
                                                 ("sine1", 1.5, 0.45, 0.45), ("sine2", 1.2, 0.3, 0.25)])
def test_a_block_with_mu_s_at_most_b_over_h_only_slides_and_matches_the_sliding_closed_form(kind, amp, mu_s, mu_k):
    """b/h = 0.5 >= mu_s: whatever the pulse, only rest and slide are visited and theta stays 0; the peak
    sliding and every start, stop and reversal time agree with a block that cannot tip (closed forms) to
    1e-9."""
    blk = Block(0.5, 1.0)
    A, V1, V2, t_lo, t_hi = _floor_and_integrals(kind, amp * G)
    res = solve_block(blk, A, t_hi + 10.0, mu_s=mu_s, mu_k=mu_k, t0=t_lo, t_quiet=t_hi,
                      breakpoints=(t_lo,), max_step=0.005, history=True)
    assert set(names(res)) == {"rest", "slide"} and res.settled
    assert res.theta_max == 0.0 and np.all(res.history.theta == 0.0)
    assert set(np.unique(res.history.mode)) == {REST, SLIDE}
    peak, starts, stops = _sliding_reference(A, V1, V2, t_lo, t_hi, mu_s, mu_k)
    assert res.u_max == pytest.approx(peak, rel=1e-9)
    solver_times = sorted({t for t, n, _ in res.modes[1:]})    # slide starts and reversals, and stops
    assert len(solver_times) == len(starts) + len(stops) >= 2
    np.testing.assert_allclose(solver_times, sorted(starts + stops), rtol=1e-9, atol=1e-12)


# ------------------------------------------------------------------------------------------ rock only

@pytest.mark.parametrize("case", ["ricker", "overturn"])
def test_with_ample_friction_the_block_rocks_exactly_as_the_rock_only_peer(case):
    """mu_s = 5: theta_max, the impact times and the outcome equal the rock-only peer's to 1e-10; u stays 0."""
    if case == "ricker":
        blk = Block.from_slenderness(0.2, 1.0)
        A, kw, t_end = ricker(2.0 * G * math.tan(0.2), 0.5), dict(t0=-1.0, t_quiet=1.0, max_step=0.01), 10.0
    else:
        blk = Block.from_slenderness(0.05, 1.0)
        t_d = 1.0 / blk.p(G)
        A, kw, t_end = rectangular(-2.0 * G * 0.05, t_d), dict(t_quiet=t_d), 30.0
    rock = solve_rocking(blk, A, t_end, **kw)
    both = solve_block(blk, A, t_end, mu_s=5.0, history=True, **kw)
    assert both.theta_max == pytest.approx(rock.theta_max, rel=1e-10)
    assert both.n_impacts == rock.n_impacts and both.overturned == rock.overturned
    np.testing.assert_allclose(both.impacts[:, 0], rock.impacts[:, 0], rtol=0, atol=1e-10)
    np.testing.assert_allclose(both.impacts[:, 1:3], rock.impacts[:, 1:], rtol=1e-9, atol=1e-12)
    assert both.u_max == 0.0 and np.all(both.history.u == 0.0)
    assert set(names(both)) <= {"rest", "rock", "overturned"}
    if case == "ricker":
        assert both.t_rest == pytest.approx(rock.t_rest, abs=1e-10) and both.settled
    else:
        assert both.t_overturn == pytest.approx(rock.t_overturn, rel=1e-10)


# ------------------------------------------------------------------------------------------ slide-rock

SCENES = {
    # alpha = 0.2, b/h = 0.203 < mu_s = 0.25: uplift at g tan(alpha), then the pivot needs more than 0.25 V
    "stick after slide-rock": (0.2, None, 0.25, 0.22, 2.0),
    # alpha = 0.3: slide-rock until an impact with the corner still sliding, then flat sliding
    "sliding impact": (0.3, None, 0.35, 0.30, 2.5),
    # e = 0.7 < e_H: a rocking block's impacts need friction impulses above mu_s and slide
    "low restitution": (0.2, 0.7, 0.3, 0.2, 3.0),
}


def _scene(name, **extra):
    alpha, e, mu_s, mu_k, amp = SCENES[name]
    blk = Block.from_slenderness(alpha, 1.0, restitution=e)
    A = ricker(amp * G * math.tan(alpha), 0.5)
    kw = dict(t0=-1.0, t_quiet=1.0, max_step=0.01, mu_s=mu_s, mu_k=mu_k)
    kw.update(extra)
    return blk, A, kw


def _energy_terms(blk, h):
    """Kinetic and potential energy per unit mass from the state alone (psi = s theta on corner s)."""
    s = np.where((h.mode == ROCK) | (h.mode == SLIDE_ROCK), h.side, 0)
    psi, dpsi = s * h.theta, s * h.omega
    d = blk.alpha - psi
    xc = h.v + s * blk.R * np.cos(d) * dpsi
    yc = blk.R * np.sin(d) * dpsi
    kinetic = 0.5 * (xc ** 2 + yc ** 2) + blk.R ** 2 * h.omega ** 2 / 6
    return kinetic, G * (blk.R * np.cos(d) - blk.h)


@pytest.mark.parametrize("name", list(SCENES))
def test_slide_rock_scenes_keep_the_energy_balance_continuity_contact_and_friction_law(name):
    """Floor work = kinetic + potential + friction loss + impact losses to 1e-7 of the peak work; u and theta
    continuous; V >= 0 while |theta| < alpha; |H| <= mu_s V when stuck and H = -mu_k V sgn(u') when sliding;
    impact losses never negative."""
    blk, A, kw = _scene(name)
    res = solve_block(blk, A, 6.0, history=True, **kw)
    h = res.history
    visited = set(names(res))
    assert {"rock", "rest"} <= visited and res.u_max > 1e-4 and not res.overturned
    assert ("slide-rock" in visited) == (name != "low restitution")
    if name != "stick after slide-rock":
        assert "slide" in visited and np.any(res.impacts[:, 4] != 0.0)
    T, U = _energy_terms(blk, h)
    balance = h.work - T - U - h.friction_loss - h.impact_loss
    assert np.max(np.abs(balance)) <= 1e-7 * np.max(np.abs(h.work))
    assert np.all(np.diff(h.impact_loss) >= 0) and np.all(np.diff(h.friction_loss) >= -1e-15)
    same = np.flatnonzero(np.diff(h.t) == 0)
    assert np.all(h.u[same] == h.u[same + 1]) and np.all(h.theta[same] == h.theta[same + 1])
    assert np.all(np.diff(h.t) >= 0)
    mu_s, mu_k = kw["mu_s"], kw["mu_k"]
    low = np.abs(h.theta) < blk.alpha
    assert np.all(h.V[low] >= 0)
    stuck = low & ((h.mode == REST) | (h.mode == ROCK))
    assert np.all(np.abs(h.H[stuck]) <= mu_s * h.V[stuck] * (1 + 1e-9))
    sliding = ((h.mode == SLIDE) | (h.mode == SLIDE_ROCK)) & (h.v != 0)
    assert sliding.sum() > 10
    np.testing.assert_allclose(h.H[sliding], -mu_k * h.V[sliding] * np.sign(h.v[sliding]), rtol=1e-9, atol=1e-9)
    assert np.all(h.v[(h.mode == REST) | (h.mode == ROCK)] == 0)


@pytest.mark.parametrize("name", ["sliding impact", "low restitution"])
def test_impacts_keep_the_angular_momentum_rule_and_coulombs_law_for_the_impulse(name):
    """Every impact: theta'+ = e theta'- - 3h/(4R^2) (u'+ - u'-) to 1e-12; the impulse (jumps of the centre of
    mass's velocity) is within mu_s J_y when the new corner sticks and equals -mu_k sgn(u'+) J_y when it
    slides (1e-12); J_y > 0."""
    blk, A, kw = _scene(name)
    res = solve_block(blk, A, 6.0, **kw)
    kappa = 0.75 * blk.h / blk.R ** 2
    slid = 0
    for _, om_in, om_out, v_in, v_out in res.impacts:
        assert om_out == pytest.approx(blk.e * om_in - kappa * (v_out - v_in), rel=1e-12, abs=1e-15)
        jx = (v_out + blk.h * om_out) - (v_in + blk.h * om_in)     # x_c' = u' + h theta' at theta = 0
        jy = blk.b * (abs(om_out) + abs(om_in))                   # y_c' = b psi' on either corner
        assert jy > 0
        if v_out == 0.0:
            assert abs(jx) <= kw["mu_s"] * jy
        else:
            slid += 1
            assert jx == pytest.approx(-kw["mu_k"] * math.copysign(1.0, v_out) * jy, rel=1e-12)
    assert slid >= 1


def test_rock_to_slide_rock_happens_where_the_rock_only_peer_finds_friction_exceeded():
    """The onset of slide-rock equals the time the rock-only peer raises for lack of friction (1e-9 s),
    and there the pivot needs exactly mu_s V; the corner then slides, comes to a stop and rocks on."""
    blk, A, kw = _scene("stick after slide-rock")
    with pytest.raises(RockingContactError) as err:
        solve_rocking(blk, A, 6.0, t0=kw["t0"], t_quiet=kw["t_quiet"], max_step=kw["max_step"], mu_s=kw["mu_s"])
    res = solve_block(blk, A, 6.0, history=True, **kw)
    entries = [(t, n) for t, n, _ in res.modes]
    t_sr = next(t for t, n in entries if n == "slide-rock")
    assert t_sr == pytest.approx(err.value.time, abs=1e-9)
    h = res.history
    at = np.flatnonzero((h.t == t_sr) & (h.mode == ROCK))[-1]
    assert abs(h.H[at]) == pytest.approx(kw["mu_s"] * h.V[at], rel=1e-8)
    t_back = next(t for t, n in entries if n == "rock" and t > t_sr)
    k = np.flatnonzero(h.t == t_back)
    assert np.all(h.v[k] == 0) and np.all(h.v[(h.t > t_sr) & (h.t < t_back)] != 0)


@pytest.mark.parametrize("ratio_over", [0.999, 1.001])
def test_slide_rock_starts_from_rest_when_a_floor_jump_asks_the_pivot_for_more_than_mu_s(ratio_over):
    """Shenton's slide-rock onset: a rectangular pulse a = 1.5 g tan(alpha) from rest; rocking at once needs
    |H|/V = [a (1 - 3/4 cos^2) + 3/4 g sin cos] / [g (1 - 3/4 sin^2) + 3/4 a sin cos] (alpha's sine and
    cosine).  With mu_s just above that ratio the block rocks, just below it slide-rocks, from t = 0."""
    alpha = 0.25
    blk = Block.from_slenderness(alpha, 1.0)
    sn, cs = math.sin(alpha), math.cos(alpha)
    a = 1.5 * G * math.tan(alpha)
    need = (a * (1 - 0.75 * cs ** 2) + 0.75 * G * sn * cs) / (G * (1 - 0.75 * sn ** 2) + 0.75 * a * sn * cs)
    mu_s = need / ratio_over
    assert mu_s > math.tan(alpha)
    res = solve_block(blk, rectangular(-a, 0.05), 0.05, mu_s=mu_s, breakpoints=(0.0,))
    assert res.modes[1] == (0.0, "rock" if ratio_over < 1 else "slide-rock", 1)


# ------------------------------------------------------------------------------------------ symmetry

def test_mirrored_floor_gives_the_exactly_mirrored_sliding_and_rocking():
    """A_F -> -A_F (with vertical motion) gives u -> -u, theta -> -theta, H -> -H bit for bit, through slide,
    rock, slide-rock and sliding impacts."""
    for name in ("sliding impact", "low restitution"):
        blk, A, kw = _scene(name)

        def a_v(t, A=A):
            return 0.2 * A(t + 0.1)

        def A_m(t, A=A):
            return -A(t)
        r = solve_block(blk, A, 4.0, a_v=a_v, history=True, **kw)
        m = solve_block(blk, A_m, 4.0, a_v=a_v, history=True, **kw)
        assert r.u_max > 1e-3 and r.theta_max > 0
        assert np.array_equal(m.history.t, r.history.t)
        for key in ("u", "v", "theta", "omega", "H", "side"):
            assert np.array_equal(getattr(m.history, key), -getattr(r.history, key)), key
        for key in ("mode", "V", "work", "friction_loss", "impact_loss"):
            assert np.array_equal(getattr(m.history, key), getattr(r.history, key)), key
        assert [(t, n, -sd) for t, n, sd in r.modes] == list(m.modes)
        assert (m.u_max, m.theta_max, m.n_impacts) == (r.u_max, r.theta_max, r.n_impacts)


# ------------------------------------------------------------------------------------------ onset times

def test_onsets_from_rest_are_at_the_friction_and_uplift_levels_of_the_floor():
    """rest -> slide when |A_F| first equals mu_s (g + a_v) (mu_s <= b/h) and rest -> rock when it first
    equals (g + a_v) tan(alpha) (mu_s > b/h), each to 1e-9 relative, on the corner opposite to A_F."""
    w = 2 * math.pi / 0.8
    a = 0.6 * G
    A = sine(a, 0.8, 1)

    def a_v(t):
        return -0.2 * G

    squat = Block(0.5, 0.5)                        # b/h = 1
    res = solve_block(squat, A, 0.5, mu_s=0.3, mu_k=0.2, a_v=a_v, max_step=0.01)
    assert res.modes[1][1:] == ("slide", -1)
    assert res.modes[1][0] == pytest.approx(math.asin(0.3 * 0.8 * G / a) / w, rel=1e-9)
    slender = Block.from_slenderness(0.2, 1.0)
    res = solve_block(slender, lambda t: -A(t), 0.5, mu_s=0.8, a_v=a_v, max_step=0.01)
    assert res.modes[1][1:] == ("rock", 1)
    assert res.modes[1][0] == pytest.approx(math.asin(0.8 * G * math.tan(0.2) / a) / w, rel=1e-9)


# ------------------------------------------------------------------------------------------ errors

def test_flight_raises_naming_the_time_and_bad_friction_input_is_rejected():
    blk = Block(0.5, 0.5)
    with pytest.raises(RockingContactError, match="would leave the floor") as err:
        solve_block(blk, lambda t: 0.0, 2.0, mu_s=0.3, a_v=lambda t: -2.0 * G * t, max_step=0.05)
    assert err.value.kind == "flight" and err.value.time == pytest.approx(0.5, rel=1e-12)
    with pytest.raises(ValueError, match=r"mu_k = 0\.5 is out of range; allowed range: 0 <= value <= 0\.3"):
        solve_block(blk, lambda t: 0.0, 1.0, mu_s=0.3, mu_k=0.5)
    with pytest.raises(ValueError, match=r"mu_s = -1\.0 is out of range"):
        solve_block(blk, lambda t: 0.0, 1.0, mu_s=-1.0)
    with pytest.raises(ValueError, match=r"mu_s = 0\.0 is out of range; allowed range: 0 < value < inf"):
        solve_block(blk, lambda t: 0.0, 1.0, mu_s=0.0)
