"""isoslide against independent integrations of the same physics.

* ``isoslide.peers.solve_reference``: plain SciPy DOP853 with events,
  written separately (rtol 1e-12); agreement on random scenes over every pulse
  shape, base, damping, friction law and mass ratio.
* For very sharp Stribeck transitions (Pi6 >= 3e4) the reference drifts by up
  to ~3e-5 (it scales as 1/Pi6); there a direct phase-by-phase SciPy
  integration with a 1e-5 step cap arbitrates and agrees with isoslide.
"""

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

import isoslide
from isoslide.peers import solve_reference

PULSES = ["ricker", "antisymmetric_ricker", "makris_a", "makris_b", "makris_cn",
          "mavroeidis_papageorgiou", "rectangular"]


def random_scenes(seed, n):
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        pi5 = float(rng.choice([1.0, 0.6, 0.8]))
        out.append(isoslide.Scene(
            pi2=float(rng.uniform(0.02, 1.2)), pi3=float(rng.choice([0.0, 0.3, 1.0, 2.0, 3.5])),
            pi4=float(rng.choice([0.0, 0.05, 0.2, 1.2])), pi5=pi5,
            pi6=0.0 if pi5 == 1.0 else float(10 ** rng.uniform(1, 4)),
            pi7=float(rng.choice([0.0, 0.0, 0.5, 5.0])), pi8=float(rng.choice([1e-5, 0.1, 1.0])),
            pulse=str(rng.choice(PULSES))))
    return out


@pytest.mark.parametrize("seed", [11, 12])
def test_agrees_with_independent_reference_solver(seed):
    for sc in random_scenes(seed, 20):
        ref = solve_reference(sc)
        sol = isoslide.solve(sc, horizon=50)
        assert sol.settled == ref.settled, sc
        if ref.pi1 == 0.0:
            assert sol.pi1 == 0.0, sc
        else:
            # 1e-6 relative, or 1e-12 absolute for slides ~1e-6 long
            assert abs(sol.pi1 - ref.pi1) <= 1e-6 * ref.pi1 + 1e-12, (sc, sol.pi1, ref.pi1)


def test_sharp_stribeck_against_direct_phase_integration():
    """Fixed base, Pi6 = 3e4: breakaway, reversal, stop, integrated directly."""
    pi2, pi5, pi6 = 0.2, 0.7, 3e4
    thr = pi2 / pi5
    ricker = isoslide.get_pulse("ricker")
    p = lambda t: float(ricker.accel(np.array([t]))[0])  # noqa: E731

    def phi(v):
        x = min(pi6 * abs(v), 700.0)
        return thr / np.cosh(x) + pi2 * (1 - 1 / np.cosh(x))

    t, u = brentq(lambda t: abs(p(t)) - thr, -0.6, -0.45, xtol=1e-16), 0.0
    peaks = []
    for _ in range(2):  # breakaway -> reversal -> stop
        s = -np.sign(p(t))
        ev = lambda t, y: y[1]  # noqa: E731
        ev.terminal, ev.direction = True, -s
        r = solve_ivp(lambda t, y, s=s: [y[1], -p(t) - s * phi(y[1])], (t + 1e-12, 3.0), [u, 0.0],
                      method="DOP853", rtol=1e-13, atol=1e-16, events=ev, max_step=1e-4,
                      first_step=1e-10)
        t, u = float(r.t_events[0][0]), float(r.y_events[0][0][0])
        peaks.append(abs(u))
    sol = isoslide.solve(isoslide.Scene(pi2, 0.0, pi5=pi5, pi6=pi6), rtol=1e-8)
    assert sol.n_events == 3
    assert abs(sol.pi1 - max(peaks)) < 1e-8 * max(peaks)


def random_buildings(seed, n):
    """Random general buildings: bearings, flexible superstructures, both floors, every pulse."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        pi5 = float(rng.choice([1.0, 0.7]))
        kw = dict(pi2=float(rng.uniform(0.02, 0.6)), pi3=float(rng.choice([0.0, 1.0, 2.0, 3.5])),
                  pi4=float(rng.choice([0.0, 0.05, 0.2])), pi5=pi5,
                  pi6=0.0 if pi5 == 1.0 else float(10 ** rng.uniform(1, 3)),
                  pi7=float(rng.choice([0.0, 0.0, 0.5])), pi8=float(rng.choice([1e-3, 0.1, 0.5])),
                  pulse=str(rng.choice(PULSES)), floor=str(rng.choice(["base", "roof"])))
        iso = rng.choice(["linear", "bilinear", "sliding"])
        if iso != "linear":
            kw["pi9"] = float(10 ** rng.uniform(-2, -0.3))
            kw["pi10"] = float(10 ** rng.uniform(-3, -1)) if iso == "bilinear" else 0.0
        if iso == "linear" or rng.uniform() < 0.5:
            kw.update(pi11=float(rng.uniform(0.3, 0.8)), pi12=float(rng.choice([0.1, 0.3, 0.6])),
                      pi13=float(rng.choice([0.0, 0.02, 0.1])))
        out.append(isoslide.Scene(**kw))
    return out


@pytest.mark.parametrize("seed", [21, 22])
def test_general_buildings_agree_with_the_independent_reference_solver(seed):
    """Bearings with true stick, yielding, flexible superstructures: the compiled solver at its
    default rtol against the SciPy event-driven peer (rtol 1e-12) to 1e-6."""
    for sc in random_buildings(seed, 12):
        ref = solve_reference(sc)
        sol = isoslide.solve(sc, horizon=50)
        if ref.pi1 == 0.0:
            assert sol.pi1 == 0.0, sc
        else:
            assert abs(sol.pi1 - ref.pi1) <= 1e-6 * ref.pi1 + 1e-12, (sc, sol.pi1, ref.pi1)
