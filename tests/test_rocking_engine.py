"""The compiled engine's rocking block (Pi18..Pi21) against the independent peers and closed forms.

On a fixed base the floor is the ground, so the engine's two-way model must give the one-way peers'
answer (:mod:`isoslide.peers.rocking`, :mod:`isoslide.peers.slide_rock`) whatever ``Pi8``.  Units:
the peers run in SI with ``T_p = 1 s``, ``g`` standard, ``a_p = Pi21 g tan(alpha)`` and ``R = 3 g /
(4 Pi19^2)``.
"""

import dataclasses
import json
import math
import re

import numpy as np
import pytest
from scipy.optimize import brentq

import isoslide
from isoslide.engine import building_kernel as bk
from isoslide.model.rocking import G_STANDARD, Block, housner_restitution, rectangular_overturn_ratio
from isoslide.peers.rocking import solve_rocking
from isoslide.peers.slide_rock import solve_block

G = G_STANDARD


def _floor(scene):
    """The ground acceleration (m/s^2) of a scene run with ``T_p = 1 s``, and its breakpoints (s)."""
    a_p = scene.pi21 * G * scene.pi18
    pulse = scene.pulse

    def A_F(t):
        return a_p * float(pulse.accel(np.array([t]))[0])

    return A_F, list(getattr(pulse, "breakpoints", ()) or ())


def _block(scene):
    return Block.from_slenderness(math.atan(scene.pi18), 0.75 * G / scene.pi19**2, scene.pi20)


# (pi18, pi19, pi21, pulse): rocking that dies out, and overturning, on Ricker and rectangular pulses
ROCKING = [(0.2, 8.0, 1.1, "ricker"), (0.2, 4.0, 1.3, "ricker"), (0.15, 3.0, 1.6, "ricker"),
           (0.25, 6.0, 1.05, "ricker"), (0.2, 8.0, 1.5, "ricker"), (0.1, 10.0, 2.0, "ricker"),
           (0.2, 5.0, 1.2, "rectangular"), (0.2, 5.0, 1.6, "rectangular"), (0.1, 2.0, 1.9, "rectangular")]


@pytest.mark.parametrize("pi18, pi19, pi21, pulse", ROCKING)
def test_fixed_base_rocking_matches_the_rock_only_peer(pi18, pi19, pi21, pulse):
    """With friction that always holds the pivot, theta_max, the overturning flag and its time agree to 1e-6."""
    scene = isoslide.Scene(pi2=50.0, pi3=0.0, pi8=0.3, pi18=pi18, pi19=pi19, pi21=pi21, pulse=pulse)
    sol = isoslide.solve(scene, rtol=1e-8)
    A_F, bps = _floor(scene)
    ref = solve_rocking(_block(scene), A_F, t_end=max(sol.tau_end, scene.pulse.tau_end) + 1.0,
                        t0=scene.pulse.tau_start, t_quiet=scene.pulse.tau_end, breakpoints=bps, rtol=1e-12, atol=1e-14)
    assert sol.overturned == ref.overturned
    assert sol.theta_max == pytest.approx(ref.theta_max, rel=1e-6)
    assert sol.pi1 == 0.0 and "rock" in sol.modes and "slide-rock" not in sol.modes
    if sol.overturned:
        assert sol.tau_end == pytest.approx(ref.t_overturn, abs=1e-6)
        assert sol.theta_max == 0.5 * math.pi
    else:
        assert sol.settled


# (pi2, pi18, pi19, pi21, pulse): mu_s = Pi2 Pi21 tan(alpha) just above tan(alpha): the pivot slips
SLIDE_ROCK = [(0.9, 0.2, 6.0, 1.25, "ricker"), (0.85, 0.2, 6.0, 1.4, "ricker"), (0.8, 0.3, 4.0, 1.5, "rectangular"),
              (0.95, 0.2, 8.0, 2.0, "ricker")]


@pytest.mark.parametrize("pi2, pi18, pi19, pi21, pulse", SLIDE_ROCK)
def test_fixed_base_slide_rock_matches_the_slide_rock_peer(pi2, pi18, pi19, pi21, pulse):
    """Slide-rock, sliding impacts and rock again: Pi1, theta_max and the overturning flag agree to 1e-6."""
    scene = isoslide.Scene(pi2=pi2, pi3=0.0, pi8=0.3, pi18=pi18, pi19=pi19, pi21=pi21, pulse=pulse)
    assert scene.tips
    sol = isoslide.solve(scene, rtol=1e-8)
    A_F, bps = _floor(scene)
    mu = pi2 * pi21 * pi18       # mu_s = Pi2 / (Pi5 g/a_p); a rocking block slides at mu_s
    a_p = pi21 * G * pi18
    ref = solve_block(_block(scene), A_F, t_end=max(sol.tau_end, scene.pulse.tau_end) + 1.0, mu_s=mu, mu_k=mu,
                      t0=scene.pulse.tau_start, t_quiet=scene.pulse.tau_end, breakpoints=bps, rtol=1e-12,
                      atol=1e-14)
    assert sol.overturned == ref.overturned
    assert sol.theta_max == pytest.approx(ref.theta_max, rel=1e-6)
    assert sol.pi1 == pytest.approx(ref.u_max / a_p, rel=1e-6, abs=1e-12)
    assert {name for _, name, _ in ref.modes} - {"overturned"} <= set(sol.modes)


@pytest.mark.parametrize("building", [{}, {"pi3": 2.0, "pi4": 0.1}, {"pi3": 2.0, "pi9": 0.1},
                                      {"pi3": 2.5, "pi12": 0.3, "pi11": 0.5, "pi13": 0.05, "storeys": 3,
                                       "floor": "roof"}])
def test_a_block_that_cannot_tip_gives_the_sliding_answer_bit_for_bit(building):
    """mu_s <= tan(alpha): the sliding model runs and gives the same numbers as contents that only slide."""
    base = isoslide.Scene(pi2=0.3, pi3=building.pop("pi3", 0.0), pi8=0.2, **building)
    tall = dataclasses.replace(base, pi18=0.5, pi19=6.0, pi21=1.5)       # mu_s = 0.3 * 1.5 * 0.5 < 0.5
    assert not tall.tips
    a, b = isoslide.solve(base), isoslide.solve(tall)
    assert a.pi1 > 0.0
    assert (a.pi1, a.pi1_residual, a.tau_end, a.n_steps) == (b.pi1, b.pi1_residual, b.tau_end, b.n_steps)
    assert a.model == b.model and b.facets.contents == "sliding"
    assert b.theta_max == 0.0 and not b.overturned and b.modes == ("rest", "slide")
    full = isoslide.solve(tall, model="full", rtol=1e-8)          # the rocking model, run anyway
    assert full.facets.contents == "rocking" and full.modes == ("rest", "slide") and full.theta_max == 0.0
    assert full.pi1 == pytest.approx(a.pi1, rel=1e-6)


def test_a_floor_below_the_uplift_level_leaves_the_block_at_rest():
    """An isolated floor that never reaches g tan(alpha): no transition, theta_max 0, the mode rest alone."""
    scene = isoslide.Scene(pi2=2.0, pi3=3.0, pi4=0.1, pi8=0.01, pi18=0.2, pi19=8.0, pi21=1.2)
    sol = isoslide.solve(scene)
    assert (sol.theta_max, sol.overturned, sol.modes, sol.n_events) == (0.0, False, ("rest",), 0)
    assert sol.facets.contents == "rocking" and sol.model.endswith("+rocking")


def test_uplift_starts_when_the_ground_first_reaches_g_tan_alpha():
    """On a fixed base the block leaves rest where the Ricker pulse first reaches 1/Pi21 in magnitude (1e-9)."""
    scene = isoslide.Scene(pi2=50.0, pi3=0.0, pi18=0.2, pi19=8.0, pi21=1.2)
    sol = isoslide.solve(scene, history=True)
    h = sol.history
    first = int(np.argmax(h.phase != 0))
    assert abs(int(h.phase[first])) == 4                         # rocking, on the corner opposite the floor
    p = scene.pulse

    def excess(t):
        return abs(float(p.accel(np.array([t]))[0])) - 1.0 / scene.pi21

    ts = np.linspace(p.tau_start, p.tau_end, 4001)
    i = int(np.argmax([excess(t) > 0.0 for t in ts]))
    onset = brentq(excess, ts[i - 1], ts[i], xtol=1e-15)
    assert h.tau[first] == pytest.approx(onset, abs=1e-9)
    assert np.sign(h.phase[first]) == -np.sign(p.accel(np.array([onset]))[0])


@pytest.mark.parametrize("p_td", [1.0, 3.0])
def test_a_slender_block_overturns_just_above_the_linearised_threshold_of_a_rectangular_pulse(p_td):
    """alpha = 0.02: 1 % above Housner-Makris' threshold overturns, 1 % below does not (the error is O(alpha^2))."""
    beta = rectangular_overturn_ratio(p_td)
    out = []
    for f in (0.99, 1.01):
        scene = isoslide.Scene(pi2=1e3, pi3=0.0, pi18=math.tan(0.02), pi19=p_td, pi21=beta * f / (math.tan(0.02) / 0.02),
                               pulse="rectangular")
        out.append(isoslide.solve(scene).overturned)
    assert out == [False, True]


def test_two_way_coupling_changes_the_floor_of_a_heavy_block():
    """A block of Pi8 = 0.5 on a long-period isolated slab slows it: the light block overturns, the heavy one not."""
    light = isoslide.Scene(pi2=50.0, pi3=3.0, pi4=0.1, pi8=1e-9, pi18=0.2, pi19=6.0, pi21=8.0)
    heavy = dataclasses.replace(light, pi8=0.5)
    a, b = isoslide.solve(light), isoslide.solve(heavy)
    assert a.overturned and a.theta_max == 0.5 * math.pi
    assert not b.overturned and 0.0 < b.theta_max < math.atan(0.2)
    assert b.modes == ("rest", "rock") and b.facets.coupling == "two-way"


def test_history_carries_theta_and_the_rocking_modes():
    scene = isoslide.Scene(pi2=50.0, pi3=0.0, pi18=0.2, pi19=4.0, pi21=1.3)
    sol = isoslide.solve(scene, history=True)
    h = sol.history
    assert h.theta is not None and h.thetad is not None
    assert np.max(np.abs(h.theta)) <= sol.theta_max + 1e-15
    rocking = np.abs(h.phase) == 4
    assert np.all(np.sign(h.theta[rocking & (h.theta != 0.0)]) == np.sign(h.phase[rocking & (h.theta != 0.0)]))
    assert np.all(h.theta[h.phase == 0] == 0.0)


def test_every_block_mode_and_contact_loss_has_a_name():
    assert bk.BLOCK_MODES == ("rest", "slide", "rock", "slide-rock")
    assert [bk.block_mode(m) for m in (0.0, 1.0, -1.0, 4.0, -4.0, 5.0, 3.0, -3.0, -5.0)] == [0, 1, 1, 2, 2, 3, 3, 3, 3]
    assert set(isoslide.solver.CONTACT_TEXT) == set(bk.CONTACT_LOSSES[1:])


@pytest.mark.parametrize("kwargs, pattern", [
    ({"pi18": 0.2, "pi19": 5.0}, r"pi21 = None with pi18 = 0\.2"),
    ({"pi19": 5.0}, r"pi19 = 5\.0 is given without pi18"),
    ({"pi18": -0.2, "pi19": 5.0, "pi21": 1.0}, r"pi18 = -0\.2 is out of range; allowed range: 0 < value <= 1000"),
    ({"pi18": 0.2, "pi19": 5.0, "pi21": 1.0, "pi20": 0.99}, r"pi20 = 0\.99 is out of range; allowed range: 0 < value"),
    ({"pi18": 0.2, "pi19": 5.0, "pi21": 1.0, "pi6": 3.0}, r"pi6 = 3\.0, pi7 = 0\.0 with a rocking block"),
    ({"pi18": 0.2, "pi19": 5.0, "pi21": 1.0, "pulse_y": "ricker"}, r"rocking under two horizontal components"),
    ({"pi18": 0.2, "pi19": 5.0, "pi21": 1.0, "angle": 0.3}, r"angle = 0\.3"),
])
def test_bad_rocking_input_names_the_parameter_value_and_range(kwargs, pattern):
    with pytest.raises(ValueError, match=pattern):
        isoslide.Scene(pi2=0.3, pi3=2.0, **kwargs)


def test_from_physical_makes_the_rocking_groups_and_checks_the_block():
    s = isoslide.Scene.from_physical(a_p=3.0, T_p=1.2, M_b=1e5, T_b=2.5, xi_b=0.1, m_ec=200.0, mu_s=0.5, mu_k=0.4,
                                     b=0.3, h=0.9)
    R = math.hypot(0.3, 0.9)
    assert s.pi18 == pytest.approx(1 / 3, rel=1e-15)
    assert s.pi19 == pytest.approx(math.sqrt(3 * G / (4 * R)) * 1.2, rel=1e-15)
    assert s.pi21 == pytest.approx(3.0 / (G / 3), rel=1e-15)
    assert s.restitution == pytest.approx(housner_restitution(math.atan(1 / 3)), rel=1e-15)
    assert s.tips                                   # mu_s = 0.5 > 1/3
    for kw, pattern in (({"b": 0.3}, r"b = 0\.3, h = None"), ({"b": -0.3, "h": 1.0}, r"b = -0\.3 is out of range"),
                        ({"restitution": 0.5}, r"restitution = 0\.5 is given without b and h")):
        with pytest.raises(ValueError, match=pattern):
            isoslide.Scene.from_physical(a_p=3.0, T_p=1.2, M_b=1e5, T_b=2.5, xi_b=0.1, m_ec=200.0, mu_s=0.5,
                                         mu_k=0.4, **kw)


def test_the_command_line_solves_a_rocking_block_in_pi_groups_and_in_metres(capsys):
    """``isoslide solve --pi18 ...`` and ``solve-physical --b --h`` print theta_max, overturned and the modes."""
    from isoslide.cli import main
    assert main(["solve", "--pi2", "50", "--pi3", "0", "--pi18", "0.2", "--pi19", "8", "--pi21", "1.5",
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    sol = isoslide.solve(isoslide.Scene(pi2=50.0, pi3=0.0, pi18=0.2, pi19=8.0, pi21=1.5))
    assert (out["theta_max"], out["overturned"], out["modes"]) == (sol.theta_max, sol.overturned, list(sol.modes))
    assert out["scene"]["pi18"] == 0.2 and out["scene"]["pi20"] is None
    assert main(["solve-physical", "--a-p", "3", "--T-p", "1", "--M-b", "1e5", "--T-b", "0", "--xi-b", "0",
                 "--m-ec", "100", "--mu-s", "0.6", "--mu-k", "0.6", "--b", "0.2", "--h", "0.8", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    ref = isoslide.solve(isoslide.Scene.from_physical(a_p=3.0, T_p=1.0, M_b=1e5, T_b=0.0, xi_b=0.0, m_ec=100.0,
                                                      mu_s=0.6, mu_k=0.6, b=0.2, h=0.8))
    assert out["theta_max"] == ref.theta_max and "rock" in out["modes"]


@pytest.mark.parametrize("ext", [".csv", ".h5"])
def test_history_files_of_a_rocking_block_carry_its_tilt(tmp_path, ext):
    """The history table adds tilt and tilt_rate, and the block's groups and outcome, and reads back the same."""
    from isoslide.store.history_io import history_table, read_history, write_history
    scene = isoslide.Scene.from_physical(a_p=3.0, T_p=1.0, M_b=1e5, T_b=2.0, xi_b=0.1, m_ec=1e3, mu_s=0.6, mu_k=0.6,
                                         b=0.2, h=0.8)
    sol = isoslide.solve(scene, history=True)
    tab = history_table(sol, scene)
    assert tuple(tab.columns)[-2:] == ("tilt", "tilt_rate")
    assert tab.units["tilt"] == "rad" and tab.units["tilt_rate"] == "rad s-1"
    np.testing.assert_array_equal(tab.columns["tilt"], sol.history.theta)
    assert np.max(np.abs(tab.columns["tilt"])) <= sol.theta_max
    assert tab.attrs["theta_max"] == sol.theta_max and tab.attrs["pi18"] == scene.pi18
    back = read_history(write_history(sol, scene, tmp_path / f"h{ext}"))
    assert tuple(back.columns) == tuple(tab.columns)
    np.testing.assert_array_equal(back.columns["tilt"], tab.columns["tilt"])
    assert back.attrs["overturned"] == sol.overturned


def test_a_block_on_a_sliding_bearing_that_holds_rocks_as_on_a_fixed_base():
    """A bearing too strong to slip under the rocking block's push: the slab is the ground, theta_max as fixed."""
    fixed = isoslide.Scene(pi2=50.0, pi3=0.0, pi8=0.3, pi18=0.2, pi19=4.0, pi21=1.3)
    held = dataclasses.replace(fixed, pi3=3.0, pi9=5.0)
    a, b = isoslide.solve(fixed, rtol=1e-8), isoslide.solve(held, rtol=1e-8)
    assert b.facets.isolator == "sliding-bearing" and b.facets.contents == "rocking"
    assert b.theta_max == pytest.approx(a.theta_max, rel=1e-9) and b.overturned == a.overturned


# two-way coupled scenes: (building, contents) keyword arguments of isoslide.Scene
TWO_WAY = {
    "linear, heavy block rocks": dict(pi2=50.0, pi3=2.0, pi4=0.1, pi8=0.5, pi19=3.0, pi21=3.0),
    "linear, slide-rock, overturns": dict(pi2=0.4, pi3=2.0, pi4=0.1, pi8=0.3, pi19=2.0, pi21=3.0, pulse="rectangular"),
    "linear, slide-rock, rests": dict(pi2=0.21 / 0.4, pi3=2.0, pi4=0.1, pi8=0.3, pi19=1.0, pi21=2.0,
                                      pulse="rectangular"),
    "lead-rubber": dict(pi2=0.4, pi3=2.5, pi4=0.05, pi8=0.3, pi9=0.1, pi10=0.01, pi19=2.0, pi21=3.0),
    "sliding bearing slips under the block": dict(pi2=1 / 0.6, pi3=2.0, pi8=0.4, pi9=0.12, pi19=1.0, pi21=3.0),
    "sliding bearing": dict(pi2=0.4, pi3=3.0, pi8=0.3, pi9=0.08, pi19=2.0, pi21=5.0),
    "fixed base, vertical motion": dict(pi2=0.7, pi3=0.0, pi8=0.2, pi19=2.0, pi21=2.0, pi17=0.6, pulse_z="ricker"),
    "linear, vertical motion": dict(pi2=0.7, pi3=2.0, pi4=0.1, pi8=0.2, pi19=2.0, pi21=2.0, pi17=0.6,
                                    pulse_z="ricker"),
    "2 storeys, roof, slide-rock": dict(pi2=0.4, pi3=2.5, pi4=0.1, pi8=0.3, pi11=0.6, pi12=0.3, pi13=0.02, storeys=2,
                                        floor="roof", pi19=2.0, pi21=5.0, pulse="rectangular"),
}


@pytest.mark.parametrize("name", TWO_WAY)
def test_rocking_block_on_isolated_buildings_matches_the_two_way_peer(name):
    """Engine against the independent SciPy peer of the coupled building: theta_max and Pi1 to 1e-6, flag, modes."""
    from isoslide.peers.rocking_building import solve as peer
    scene = isoslide.Scene(pi18=0.2, **TWO_WAY[name])
    sol = isoslide.solve(scene, rtol=1e-8)
    ref = peer(scene)
    assert sol.overturned == ref.overturned
    assert sol.theta_max == pytest.approx(ref.theta_max, rel=1e-6)
    assert sol.pi1 == pytest.approx(ref.pi1, rel=1e-6, abs=1e-12)
    assert set(sol.modes) == set(ref.modes)
    assert "rock" in sol.modes


SLENDER = {
    # a block on its pivot whose friction lets go just before the tipping angle, in a step that
    # ends past it: it slides as it rocks, then overturns
    "pivot slips near the tipping angle": dict(pi2=2.02391, pi18=0.520076, pi19=2.95334, pi21=1.86029, pi3=2.02249,
                                               pi4=0.0253302, pi8=0.0252079, pulse="rectangular"),
    # the slide of a slide-rocking block ends by an impact, not by stopping: its peak still counts
    "slide-rock ended by an impact": dict(pi2=1.80455, pi18=0.685707, pi19=1.148, pi21=1.24736, pi3=1.31016, pi4=0.0,
                                          pi8=0.0168818, pulse="makris_b"),
    # the tilt peaks inside a step that a later event ends: theta_max there, not at the step's ends
    "tilt peak before an event": dict(pi2=1.84042, pi18=0.536748, pi19=2.36118, pi21=1.02481, pi3=0.0,
                                      pi8=0.000104096, pulse="makris_b"),
    "slide-rock on a lead-rubber bearing": dict(pi2=0.464355, pi18=0.982347, pi19=1.68619, pi21=3.69991,
                                                pi20=0.164444, pi3=2.24659, pi4=0.0352574, pi8=0.0463171,
                                                pi9=0.0494288, pi10=0.0368771, pulse="antisymmetric_ricker"),
}


@pytest.mark.parametrize("name", SLENDER)
def test_slender_blocks_that_slide_as_they_rock_match_the_two_way_peer(name):
    """Slide-rock reached near the tipping angle or ended by an impact, a tilt peaking just before an
    event: Pi1 (the largest |u| over the whole response), theta_max, the flag and the modes as the
    independent peer's, to 1e-6."""
    from isoslide.peers.rocking_building import solve as peer
    scene = isoslide.Scene(pi5=1.0, **SLENDER[name])
    sol = isoslide.solve(scene, rtol=1e-8)
    ref = peer(scene)
    assert "rock" in sol.modes and set(sol.modes) == set(ref.modes)
    assert sol.overturned == ref.overturned
    assert sol.theta_max == pytest.approx(ref.theta_max, rel=1e-6)
    assert sol.pi1 == pytest.approx(ref.pi1, rel=1e-6, abs=1e-12)


@pytest.mark.parametrize("pi20", [None, 0.85])
def test_free_rocking_after_the_pulse_keeps_e_squared_of_the_energy_at_each_impact(pi20):
    """On a quiet fixed base each impact's outgoing angular speed is e times the previous one (energy ratio e^2)."""
    scene = isoslide.Scene(pi2=50.0, pi3=0.0, pi18=0.2, pi19=4.0, pi20=pi20, pi21=1.3)
    sol = isoslide.solve(scene, rtol=1e-10, history=True)
    h = sol.history
    after = (h.tau > scene.pulse.tau_end) & (h.theta == 0.0) & (np.abs(h.phase) == 4)
    w = np.abs(h.thetad[after])
    assert w.size >= 5
    np.testing.assert_allclose(w[1:] / w[:-1], scene.restitution, rtol=1e-7)
    assert np.all(np.sign(h.phase[after][1:]) == -np.sign(h.phase[after][:-1]))     # the pivot alternates


def test_first_impact_after_a_rectangular_pulse_converges_to_the_linearised_closed_form_as_alpha_squared():
    """The slender block's first impact time differs from Housner's linearised one by O(alpha^2), and only so."""
    from isoslide.model.rocking import rectangular_pulse_first_impact
    errors = []
    for alpha in (0.02, 0.01):
        beta, p_td = 1.1, 2.0                     # below the overturning ratio 1/(1 - exp(-2)) = 1.157
        scene = isoslide.Scene(pi2=1e3, pi3=0.0, pi18=math.tan(alpha), pi19=p_td, pi21=beta * alpha / math.tan(alpha),
                               pulse="rectangular")
        h = isoslide.solve(scene, rtol=1e-10, history=True).history
        first = h.tau[np.flatnonzero((h.theta == 0.0) & (np.abs(h.phase) == 4) & (h.tau > 0.5))[0]]
        block = Block.from_slenderness(alpha, 0.75 * G / p_td**2)
        exact = rectangular_pulse_first_impact(block, beta * G * alpha, 1.0)
        errors.append(abs(first - exact) / exact)
    assert errors[1] < 3e-4
    assert 3.5 < errors[0] / errors[1] < 4.5


def test_flight_stops_the_solve_naming_the_time_the_peer_finds():
    """A light block rocking hard on an isolated slab would leave the floor: ContactError at the peer's time (1e-6)."""
    from isoslide.peers.rocking import RockingContactError
    from isoslide.peers.rocking_building import solve as peer
    scene = isoslide.Scene(pi2=5.0, pi3=1.0, pi4=0.05, pi8=1e-3, pi18=0.2, pi19=2.0, pi21=10.0)
    with pytest.raises(RockingContactError, match="leave the floor") as ref:
        peer(scene)
    t_ref = float(re.search(r"at tau = ([0-9.e+-]+)", str(ref.value)).group(1))
    with pytest.raises(isoslide.solver.ContactError, match="would leave the floor") as err:
        isoslide.solve(scene, rtol=1e-8)
    t = float(re.search(r"at tau = ([0-9.e+-]+)", str(err.value)).group(1))
    assert t == pytest.approx(t_ref, abs=1e-5)


def test_a_mirrored_ground_motion_mirrors_the_rocking_response():
    """The ground negated: theta and u change sign, the modes and times stay (a sampled Ricker pulse, isolated)."""
    from isoslide.pulses import get_pulse, sampled
    taus = np.linspace(-2.0, 2.0, 801)
    wave = np.asarray(get_pulse("ricker").accel(taus), dtype=float)
    runs = []
    for sign in (1.0, -1.0):
        scene = isoslide.Scene(pi2=0.26, pi3=2.0, pi4=0.1, pi8=0.3, pi18=0.2, pi19=1.0, pi21=4.0,
                               pulse=sampled(sign * wave, 4.0 / 800, tau0=-2.0))
        runs.append(isoslide.solve(scene, history=True))
    a, b = runs
    assert a.theta_max > 0.0 and a.modes == b.modes and a.theta_max == b.theta_max and a.pi1 == b.pi1
    np.testing.assert_array_equal(a.history.tau, b.history.tau)
    np.testing.assert_array_equal(a.history.theta, -b.history.theta)
    np.testing.assert_array_equal(a.history.u, -b.history.u)
