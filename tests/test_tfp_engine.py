"""The triple friction pendulum in the general building's kernel.

Its surfaces' logic against the closed-form loops of Fenz and Constantinou, whole scenes against the
independent SciPy peer, the reductions to the single friction pendulum, the API and the refusals.
"""

import math

import numpy as np
import pytest

import isoslide
from isoslide import Scene, solve
from isoslide.engine import building
from isoslide.engine import building_kernel as bk
from isoslide.model import tfp as closed
from isoslide.model.parts import building_of
from isoslide.peers.reference_tfp import TFPBuilding, run_tfp
from isoslide.pulses import accel_at, get_pulse, sampled
from isoslide.scene import tfp_bearing
from isoslide.solver import CapacityError

BASE = dict(pi2=0.3, pi3=2.0, pi4=0.0, pi8=1e-3, pi9=0.05, pi24=0.1, pi25=0.5, pi26=0.5, pi27=2.0, pi28=0.05,
            pi29=0.1, pi30=0.2)
"""A triple pendulum (L1 = 0.1 (L2 + L3), L2 = L3, mu1 : mu2 : mu3 = 0.5 : 1 : 2) under the Ricker pulse."""

NARROW = {**BASE, "pi28": 0.08, "pi29": 0.01, "pi30": 0.06}
"""The same with small limits: its outer restrainers engage (regimes IV and V)."""


def peer(scene: Scene):
    """The SciPy event-driven peer on the scene's bearing (weight ``M_b g``, Coulomb contents)."""
    b = tfp_bearing(scene)
    return run_tfp(TFPBuilding(L=b.L, mu=b.mu, d=b.d, gravity=1.0, pi2=scene.pi2, pi5=1.0, pi8=scene.pi8,
                               pulse=scene.pulse, damping=building_of(scene).isolator.viscous,
                               contents_weight=False))


# --- the surfaces, driven quasi-statically --------------------------------------------------------


def kernel_path(scene: Scene, targets) -> tuple:
    """Vertices ``(x, F)`` of a displacement-controlled path through ``targets``, by the kernel's surface rules.

    A held bearing's force moves to the edge of its stick band (:func:`tfp_band`) before the slab
    moves; a moving one follows its sliding set (:func:`tfp_mode`) to the next change
    (:func:`tfp_reach`), linear in between.  Forces per unit weight times ``W = 1`` (the bearing of
    :func:`isoslide.scene.tfp_bearing`).
    """
    P = building.parameters(scene)
    u = np.zeros(4)
    r = np.zeros(4)
    x, F = 0.0, 0.0
    xs, Fs = [x], [F]
    for target in targets:
        s = 1.0 if target > x else -1.0
        lo, hi = bk.tfp_band(u, P)
        F = hi if s > 0.0 else lo
        xs.append(x)
        Fs.append(F)
        while s * (target - x) > 1e-15:
            K = bk.tfp_mode(s, u, F, P, r)
            assert math.isfinite(K), "the path passes the capacity"
            dx = min(bk.tfp_reach(s, u, F, K, r, P), s * (target - x))
            moved = np.empty(4)
            bk.tfp_moved(u, r, s * dx, P, moved)
            u = moved
            x += s * dx
            F += s * K * dx
            xs.append(x)
            Fs.append(F)
    return np.array(xs), np.array(Fs)


@pytest.mark.parametrize("scene_kw, stage", [(BASE, 1), (BASE, 2), (BASE, 3), (NARROW, 4), (NARROW, 5)])
def test_quasi_static_loops_follow_the_closed_form_regimes(scene_kw, stage):
    """Cyclic loops of the kernel's surfaces lie on Fenz and Constantinou's branches, regime changes included.

    Amplitude in the middle of each regime I..V: backbone to ``A``, down to ``-A``, up to ``A``;
    every vertex of the kernel's path on the closed-form backbone or loop to 1e-12 of the force
    scale, and every closed-form vertex (each regime's start) is a vertex of the kernel's path.
    """
    scene = Scene(**scene_kw)
    b = tfp_bearing(scene)
    bounds = closed.regime_boundaries(b)
    A = 0.5 * (bounds.u[stage - 1] + bounds.u[stage])
    x, F = kernel_path(scene, [A, -A, A])
    scale = b.W * max(b.mu) + max(abs(closed.force(b, A)[0]), 1e-300)
    turn = int(np.argmax(x >= A * (1 - 1e-15)))      # end of the backbone
    assert (x[1], F[1]) == (0.0, pytest.approx(b.W * b.mu[0], rel=1e-15))   # the inner surfaces break away
    up = slice(2, turn + 1)
    np.testing.assert_allclose(F[up], closed.force(b, x[up])[0], rtol=0, atol=1e-12 * scale)
    loop = closed.cyclic_loop(b, A)
    half = np.argmin(x)                              # end of the unloading branch
    down = slice(turn + 2, half + 1)
    back = slice(half + 2, None)
    np.testing.assert_allclose(F[down], closed.loop_force(b, A, x[down], "down"), rtol=0, atol=1e-12 * scale)
    np.testing.assert_allclose(F[back], closed.loop_force(b, A, x[back], "up"), rtol=0, atol=1e-12 * scale)
    for uv in loop.u:
        assert np.min(np.abs(x - uv)) <= 1e-12 * A, f"closed-form vertex u = {uv!r} is not on the kernel's path"
    assert F[turn + 1] == pytest.approx(F[turn] - 2.0 * b.W * b.mu[0], abs=1e-12 * scale)


def test_equal_surfaces_carry_the_single_pendulum_force():
    """With equal frictions the inner surfaces never slide: one regime of stiffness ``W/(L2 + L3)``, as the single pendulum."""
    scene = Scene(**{**BASE, "pi26": 1.0, "pi27": 1.0})
    x, F = kernel_path(scene, [0.05, -0.05])
    kd = (2.0 * math.pi / scene.pi3) ** 2
    moving = np.diff(x) != 0.0
    np.testing.assert_allclose(np.diff(F)[moving] / np.diff(x)[moving], kd, rtol=1e-13)
    assert F[1] == pytest.approx(scene.pi9, rel=1e-15)
    assert F[-1] == pytest.approx(-kd * 0.05 - scene.pi9, rel=1e-13)


# --- whole scenes ---------------------------------------------------------------------------------

PEER_SCENES = [
    BASE,
    {**BASE, "pi8": 0.05},
    {**BASE, "pi4": 0.05},
    {**BASE, "pi29": 0.02, "pi30": 0.08},
    {**BASE, "pulse": "antisymmetric_ricker", "pi2": 0.15},
    {**BASE, "pi25": 0.3, "pi2": 0.1, "pi30": 0.3},
    {**NARROW, "pi2": 0.4},
    {**NARROW, "pi2": 0.4, "pulse": "rectangular"},
    {**BASE, "pi28": 0.06, "pi29": 0.01, "pi30": 0.05, "pi2": 0.2, "pulse": "rectangular", "pi3": 1.0},
    {**BASE, "pi9": 0.6, "pi26": 0.2, "pi2": 0.05},
    {**BASE, "pi9": 1.5, "pi26": 0.2, "pi2": 0.05},
]


@pytest.fixture(scope="module")
def pairs():
    out = []
    for kw in PEER_SCENES:
        scene = Scene(**kw)
        out.append((solve(scene, rtol=1e-8), peer(scene)))
    return out


def test_scenes_agree_with_the_reference_peer(pairs):
    """Contents' peak sliding, the slab's peak and the peak regime against the SciPy peer (measured ~1e-11)."""
    for sol, ref in pairs:
        assert sol.pi1 == pytest.approx(ref.pi1, rel=1e-6, abs=1e-12)
        assert sol.peak_stage == ref.peak_stage
        assert sol.settled and ref.settled
        assert sol.model.startswith("triple-friction-pendulum+")


def test_an_inner_surface_resting_on_its_limit_while_its_outer_one_slides_takes_no_event():
    """Regime II entered from I on the way back leaves inner surface 2 exactly on its friction limit
    while outer surface 1 slides: its reaction stays put, so the set of sliding surfaces does not
    change there (a round-off rate once fired that change at once, for ever); the answer is the peer's."""
    scene = Scene(pi2=0.1, pi3=1.0, pi4=0.1, pi8=0.001, pi9=0.1, pi11=0.5, pi24=0.2057798568918039, pi25=0.5,
                  pi26=0.5, pi27=2.0, pi28=0.1, pi29=0.05, pi30=0.1)
    sol, ref = solve(scene, rtol=1e-8), peer(scene)
    assert sol.pi1 == pytest.approx(ref.pi1, rel=1e-6)
    assert sol.settled and sol.peak_stage == ref.peak_stage == 3


def test_the_peer_scenes_visit_every_regime(pairs):
    """The scenes above reach each of the regimes I to V at their peak."""
    assert {sol.peak_stage for sol, _ in pairs} == {1, 2, 3, 4, 5}


def test_history_records_the_regimes_in_order():
    """The stage column of a history climbs I, II, III on first loading and its peak is the Solution's."""
    sol = solve(Scene(**BASE), history=True)
    stage = sol.history.stage
    first = [s for i, s in enumerate(stage) if s > 0 and (i == 0 or stage[i - 1] != s)][:3]
    assert first == [1, 2, 3]
    assert stage.max() == sol.peak_stage == 3
    assert np.all(stage[sol.history.iso_phase == 0] == 0)


@pytest.mark.parametrize("extra", [
    {},
    {"pi4": 0.1, "pi8": 0.02},
    {"pi11": 0.6, "pi12": 0.3, "pi13": 0.05, "floor": "roof"},
    {"pi11": 0.6, "pi12": 0.4, "pi13": 0.05, "storeys": 3, "floor": 2},
    {"pi17": 0.3, "pulse_z": "ricker"},
])
def test_equal_frictions_reduce_to_the_single_pendulum(extra):
    """``mu1 = mu2 = mu3`` and limits out of reach: the single pendulum of radius ``L2 + L3`` (1e-9).

    Rigid and flexible superstructures, contents on an upper floor, vertical ground motion (both
    bearings' forces scale with the normal force).
    """
    single = {k: v for k, v in BASE.items() if not k.startswith(("pi24", "pi25", "pi26", "pi27", "pi28", "pi29",
                                                                 "pi30"))}
    tfp = Scene(**{**BASE, "pi26": 1.0, "pi27": 1.0, "pi28": 10.0, "pi29": 10.0, "pi30": 10.0, **extra})
    fp = Scene(**{**single, **extra})
    a, b = solve(tfp, rtol=1e-9), solve(fp, rtol=1e-9)
    assert a.pi1 == pytest.approx(b.pi1, rel=1e-9, abs=1e-12)
    assert a.pi1_residual == pytest.approx(b.pi1_residual, rel=1e-8, abs=1e-11)
    assert a.peak_stage == (3 if "bearing-stuck" not in b.model else 0)


def test_a_strong_bearing_is_proven_held():
    """A bearing whose first breakaway (the inner surfaces', ``mu1``) exceeds every demand runs as a fixed base."""
    sol = solve(Scene(**{**BASE, "pi9": 4.0, "pi28": 0.5, "pi29": 0.5, "pi30": 1.0}))
    assert sol.model.startswith("bearing-stuck+fixed-base")
    assert sol.pi1 == solve(Scene(pi2=BASE["pi2"], pi3=0.0, pi8=BASE["pi8"])).pi1


def test_along_a_line_the_one_component_answer_holds():
    """Two equal components along 45 degrees: the 1-D pendulum along that line (limits scaled with the line)."""
    sc = Scene(**NARROW, pulse_y="ricker", pi14=1.0)
    line = Scene(**{**NARROW, "pi2": NARROW["pi2"] / math.sqrt(2.0), "pi9": NARROW["pi9"] / math.sqrt(2.0),
                    **{k: NARROW[k] / math.sqrt(2.0) for k in ("pi28", "pi29", "pi30")}})
    assert solve(sc).pi1 == pytest.approx(math.sqrt(2.0) * solve(line).pi1, rel=1e-9)


def test_passing_the_displacement_capacity_is_an_error():
    """An inner surface reaching its restrainer in regime V stops the solve, at the time the peer finds it (1e-6)."""
    scene = Scene(**{**NARROW, "pi28": 0.025, "pi2": 1.0, "pulse": "rectangular"})
    with pytest.raises(CapacityError, match="displacement capacity .* at tau = ") as err:
        solve(scene)
    tau = float(str(err.value).split("at tau = ")[1].split()[0])
    beyond = [t for t, stage in peer(scene).stages if stage == -1]
    assert tau == pytest.approx(beyond[0], abs=1e-6)


# --- the API and bad input --------------------------------------------------------------------------


def test_triple_friction_pendulum_gives_the_scene_groups():
    """``triple_friction_pendulum`` in SI units gives the Pi-groups of its definition; equal frictions the FP's ``T_b``."""
    kw = isoslide.triple_friction_pendulum(L=(0.3, 2.1, 2.4), mu=(0.02, 0.06, 0.1), d=(0.08, 0.4, 0.6),
                                           M_b=2e6)
    a_p, T_p = 3.0, 1.5
    sc = Scene.from_physical(a_p, T_p, 2e6, xi_b=0.0, m_ec=200.0, mu_s=0.3, mu_k=0.3, **kw)
    assert sc.isolator == "tfp"
    assert (sc.pi24, sc.pi25, sc.pi26, sc.pi27) == pytest.approx((0.3 / 4.5, 2.1 / 4.5, 1 / 3, 5 / 3))
    assert (sc.pi28, sc.pi29, sc.pi30) == pytest.approx(tuple(d / (a_p * T_p**2) for d in (0.08, 0.4, 0.6)))
    assert sc.pi9 == pytest.approx(0.06 * isoslide.G_STANDARD / a_p)
    fp = isoslide.friction_pendulum(R=4.5, mu=0.06, M_b=2e6)
    assert kw["T_b"] == fp["T_b"] and kw["Q_d"] == fp["Q_d"]
    assert isoslide.triple_friction_pendulum((0.3, 2.1, 2.4), (0.05, 0.06, 0.1), (0.08, 0.4, 0.6), 2e6,
                                             mu_slow=0.05)["tfp"][2] == pytest.approx(1.0)


@pytest.mark.parametrize("kw, match", [
    (dict(L=(0.3, 2.1, 2.4), mu=(0.08, 0.06, 0.1), d=(0.08, 0.4, 0.6)), "mu1 = 0.08 exceeds mu2"),
    (dict(L=(0.3, 2.1, 2.4), mu=(0.02, 0.06, 0.1), d=(0.08, 0.01, 0.6)), "d2 = 0.01 is too small"),
    (dict(L=(0.0, 2.1, 2.4), mu=(0.02, 0.06, 0.1), d=(0.08, 0.4, 0.6)), "L1 = 0.0 is out of range"),
    (dict(L=(0.3, 2.1, 2.4), mu=(0.02, 0.06, 0.1), d=(0.08, 0.4, -1.0)), "d3 = -1.0 is out of range"),
    (dict(L=(0.3, 2.1, 2.4), mu=(0.02, 0.06, 0.1), d=(0.08, 0.4, 0.6), mu_slow=0.07), "mu_slow1 = 0.07 exceeds"),
    (dict(L=(0.3, 2.1, 2.4), mu=(0.02, 0.06, 0.1), d=(0.08, 0.4, 0.6), mu_slow=0.02, rate=20.0),
     "keep mu1 constant"),
])
def test_triple_friction_pendulum_refuses_what_it_cannot_represent(kw, match):
    with pytest.raises(ValueError, match=match):
        isoslide.triple_friction_pendulum(M_b=1e6, **kw)


@pytest.mark.parametrize("kw, match", [
    ({"pi10": 0.01}, "needs a sliding bearing"),
    ({"pi28": 0.0}, "pi28 = 0.0 is out of range with a triple friction pendulum"),
    ({"pi22": 0.5, "pi23": 10.0, "pi31": 1.0}, "pi31 = 1.0 is out of range"),
    ({"pi29": 0.001}, "d2 = 0.001 is too small"),
    ({"pi25": 1.0}, "pi25 = 1.0 is out of range"),
    ({"pi26": 1.5}, "pi26 = 1.5 is out of range"),
])
def test_scene_refuses_a_triple_pendulum_it_cannot_represent(kw, match):
    with pytest.raises(ValueError, match=match):
        Scene(**{**BASE, **kw})


def test_a_constant_friction_triple_pendulum_in_the_plane_is_refused_by_name():
    """Constant friction under two components not along one line: a ValueError naming pi22 and pi23."""
    with pytest.raises(ValueError, match=r"triple friction pendulum of constant friction \(pi22 = .*pi23 = .*not modelled"):
        solve(Scene(**BASE, pulse_y="antisymmetric_ricker", pi14=0.8))


def test_batches_carry_the_peak_regime():
    """``solve_many`` gives each scene's peak regime, as ``solve`` does (0 for other isolators)."""
    scenes = [Scene(**BASE), Scene(**NARROW, pulse="rectangular"), Scene(pi2=0.3, pi3=2.0, pi9=0.05)]
    batch = isoslide.solve_many(scenes)
    assert batch.peak_stage.tolist() == [solve(sc).peak_stage for sc in scenes]
    assert batch.peak_stage[-1] == 0 and batch.peak_stage[0] == 3


def test_a_recorded_ground_motion_runs_on_the_triple_pendulum():
    """A sampled record (linear between samples) drives the triple pendulum like an analytic pulse does.

    The Ricker pulse sampled finely enough gives the analytic answer to the sampling's accuracy.
    """
    ricker = get_pulse("ricker")
    tau = np.linspace(ricker.tau_start, ricker.tau_end, 8001)
    record = sampled(np.array([accel_at(ricker.code, ricker.param_array, t) for t in tau]), tau[1] - tau[0],
                     tau0=ricker.tau_start)
    a = solve(Scene(**BASE))
    b = solve(Scene(**{**BASE, "pulse": record}))
    assert b.model.startswith("triple-friction-pendulum")
    assert b.pi1 == pytest.approx(a.pi1, rel=1e-4)


def test_history_files_of_a_triple_pendulum_carry_its_regime(tmp_path):
    """The history table adds isolator_stage after the building's columns, and it reads back as written."""
    from isoslide.store.history_io import history_table, read_history, write_history
    scene = isoslide.Scene(pi2=0.1, pi3=2.0, pi4=0.0, pi8=0.01, pi9=0.05, pi24=0.1, pi25=0.5, pi26=0.5, pi27=2.0,
                           pi28=0.05, pi29=0.1, pi30=0.2)
    sol = isoslide.solve(scene, history=True)
    tab = history_table(sol, scene)
    assert tuple(tab.columns)[-1] == "isolator_stage"
    np.testing.assert_array_equal(tab.columns["isolator_stage"], sol.history.stage)
    assert tab.columns["isolator_stage"].max() == sol.peak_stage > 0
    for ext in (".csv", ".h5"):
        back = read_history(write_history(sol, scene, tmp_path / f"h{ext}"))
        assert tuple(back.columns) == tuple(tab.columns)
        np.testing.assert_array_equal(back.columns["isolator_stage"], tab.columns["isolator_stage"])
