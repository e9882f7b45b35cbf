"""Tests of isoslide.engine.kernel and its DOP853 tableau (isoslide.engine.dop853): coefficients, results layout."""

import math
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate._ivp import dop853_coefficients as scipy_dop853

import isoslide
from isoslide.engine import dop853, kernel
from isoslide.pulses import get_pulse
from import_walk import import_targets  # tests/ is on sys.path

PKG = Path(isoslide.__file__).resolve().parent


def _bits(a):
    return np.ascontiguousarray(a, dtype=np.float64).view(np.uint64)


@pytest.mark.parametrize("name", ["A", "B", "C", "E3", "E5"])
def test_dop853_tableau_equals_scipys_to_the_last_bit(name):
    ns = scipy_dop853.N_STAGES
    theirs = {"A": scipy_dop853.A[:ns, :ns], "B": scipy_dop853.B, "C": scipy_dop853.C[:ns],
              "E3": scipy_dop853.E3, "E5": scipy_dop853.E5}[name]
    ours = getattr(dop853, name)
    assert dop853.N_STAGES == ns
    assert ours.dtype == np.float64 and ours.shape == theirs.shape
    assert np.array_equal(_bits(ours), _bits(theirs))
    assert np.array_equal(_bits(getattr(kernel, name)), _bits(theirs))


def test_dop853_tableau_satisfies_its_order_conditions():
    """Explicit, consistent (c = row sums of A), weights integrate polynomials up to degree 7 exactly."""
    A, B, C = dop853.A, dop853.B, dop853.C
    assert np.all(np.triu(A) == 0.0)
    assert np.allclose(A.sum(axis=1), C, rtol=0.0, atol=1e-14)
    for k in range(1, 9):
        assert abs(np.dot(B, C ** (k - 1)) - float(Fraction(1, k))) < 1e-14
    # the embedded estimators vanish on constants (they are differences of two solutions)
    assert abs(dop853.E5.sum()) < 1e-14
    assert abs(dop853.E3.sum()) < 1e-14
    # second-order condition sum b_i (sum_j a_ij c_j) = 1/6
    assert abs(B @ (A @ C) - 1.0 / 6.0) < 1e-14


def test_package_imports_no_private_scipy_module():
    """The package uses SciPy's public API only (the tableau lives in isoslide.engine.dop853)."""
    offenders = []
    for path in PKG.rglob("*.py"):
        for _, names in import_targets(path.read_text()):
            for n in names:
                parts = n.split(".")
                if parts[0] == "scipy" and any(p.startswith("_") for p in parts[1:]):
                    offenders.append(f"{path.relative_to(PKG)}: {n}")
    assert offenders == []


# --- run: the documented layout of its arguments and results -------------------------------


def _model(pi2, pi3, pi4=0.1, pi5=1.0, pi6=0.0, pi7=0.0, pi8=0.0, law=0.0, thr=None):
    m = np.zeros(kernel.N_M)
    if pi3 > 0.0:
        w = 2.0 * math.pi / pi3
        m[kernel.M_W2] = w * w
        m[kernel.M_CW] = 2.0 * pi4 * w
    m[kernel.M_P8] = pi8
    m[kernel.M_THR] = pi2 / pi5 if thr is None else thr
    m[kernel.M_PI2] = pi2
    m[kernel.M_PI6] = pi6
    m[kernel.M_PI7] = pi7
    m[kernel.M_FIXED] = 1.0 if pi3 == 0.0 else 0.0
    m[kernel.M_COULOMB] = law
    return m


def _run(m, pulse="ricker", track_max=False, hist_cap=100_000, settle=True, horizon=40.0):
    p = get_pulse(pulse)
    return kernel.run(m, p.code, p.param_array, p.breakpoint_array, p.tau_start, p.tau_end,
                      p.tau_end + horizon, 0.15, 0.125, 1e-9, 1e-12, track_max, hist_cap, 1e-3, settle,
                      kernel.MAX_STEPS)


SCENES = {
    "fixed base, Coulomb": (_model(0.25, 0.0), "ricker"),
    "fixed base, Stribeck": (_model(0.2, 0.0, pi5=0.75, pi6=500.0), "rectangular"),
    "isolated, Coulomb": (_model(0.1, 1.0, law=1.0), "ricker"),
    "isolated, Stribeck, two-way": (_model(0.15, 2.0, 0.05, pi5=0.6, pi6=3e3, pi7=0.5, pi8=0.2),
                                    "antisymmetric_ricker"),
    "isolated, static-kinetic": (_model(0.2, 1.0, pi5=0.7, law=2.0), "makris_b"),
}


@pytest.mark.parametrize("name", sorted(SCENES))
def test_run_results_follow_the_documented_layout(name):
    m, pulse = SCENES[name]
    ints, floats, hist = _run(m, pulse)
    p = get_pulse(pulse)
    assert ints.shape == (kernel.N_R,) and ints.dtype == np.int64
    assert floats.shape == (kernel.N_F,) and floats.dtype == np.float64
    assert hist.shape == (ints[kernel.R_HIST], kernel.N_H)
    assert ints[kernel.R_SLIPPED] == 1 and ints[kernel.R_SETTLED] == 1 and ints[kernel.R_EVENTS] >= 2
    counted = ints[[kernel.R_LOC_STICK, kernel.R_LOC_SLIP, kernel.R_LOC_PEAK, kernel.R_REJECTED]]
    assert np.all(counted >= 0) and ints[kernel.R_STEPS] > counted.sum()
    # the history starts at rest and ends where the integration stopped
    assert np.array_equal(hist[0], [p.tau_start, 0.0, 0.0, 0.0, 0.0, 0.0])
    assert hist[-1, kernel.H_TAU] == floats[kernel.F_TEND]
    assert hist[-1, kernel.H_U] == floats[kernel.F_URES]
    assert np.all(np.diff(hist[:, kernel.H_TAU]) >= 0.0)
    phase = hist[:, kernel.H_PHASE]
    assert set(np.unique(phase)) <= {-1.0, 0.0, 1.0}
    assert np.all(hist[phase == 0.0, kernel.H_UD] == 0.0)
    sliding = phase != 0.0
    assert np.all(hist[sliding, kernel.H_UD] * phase[sliding] >= 0.0)
    # u is monotone within a slip phase, so its peak is at a recorded transition
    u = np.abs(hist[:, kernel.H_U])
    k = int(np.argmax(u))
    assert floats[kernel.F_UMAX] == u[k] > 0.0
    assert floats[kernel.F_TPEAK] == hist[k, kernel.H_TAU]
    assert floats[kernel.F_VMAX] == np.abs(hist[:, kernel.H_UD]).max()
    assert floats[kernel.F_AMAX] == 0.0


def test_run_history_stops_at_its_capacity_without_changing_the_results():
    m, pulse = SCENES["isolated, Stribeck, two-way"]
    full = _run(m, pulse)
    short = _run(m, pulse, hist_cap=7)
    assert short[0][kernel.R_HIST] == 7
    assert np.array_equal(short[2], full[2][:7])
    assert np.array_equal(short[1], full[1])
    keep = [i for i in range(kernel.N_R) if i != kernel.R_HIST]
    assert np.array_equal(short[0][keep], full[0][keep])


def _stuck_demand(m, x, xd):
    return -(m[kernel.M_CW] * xd + m[kernel.M_W2] * x) / (1.0 + m[kernel.M_P8])


@pytest.mark.parametrize("pi3, pi4, pi8", [(1.0, 0.1, 0.0), (2.0, 0.02, 0.5), (0.5, 1.5, 1.0)])
def test_track_max_bounds_every_recorded_stuck_demand(pi3, pi4, pi8):
    m = _model(1.0, pi3, pi4, pi8=pi8, thr=math.inf)
    ints, floats, hist = _run(m, track_max=True)
    assert ints[kernel.R_SLIPPED] == 0 and ints[kernel.R_EVENTS] == 0
    assert np.all(hist[:, kernel.H_PHASE] == 0.0) and np.all(hist[:, kernel.H_U] == 0.0)
    demand = np.abs(_stuck_demand(m, hist[:, kernel.H_X], hist[:, kernel.H_XD]))
    assert floats[kernel.F_AMAX] >= demand.max() * (1.0 - 1e-15)
    assert floats[kernel.F_AMAX] <= demand.max() * 1.01
    assert ints[kernel.R_LOC_PEAK] > 0 and floats[kernel.F_UMAX] == 0.0


def test_demand_bound_is_the_largest_demand_at_the_current_energy():
    rng = np.random.default_rng(3)
    for _ in range(50):
        m = _model(0.3, 10.0 ** rng.uniform(-2, 1), 10.0 ** rng.uniform(-3, 1), pi8=rng.uniform(0, 2))
        mt = 1.0 + m[kernel.M_P8]
        w = math.sqrt(m[kernel.M_W2])
        y = np.array([rng.normal(), rng.normal(), 0.0, 0.0])
        bound = kernel._demand_bound(y, m)
        # every state of the same energy: x = r cos(t) / w, x' = r sin(t) / sqrt(1 + Pi8)
        r = math.sqrt(mt * y[1] ** 2 + m[kernel.M_W2] * y[0] ** 2)
        t = np.linspace(0.0, 2.0 * math.pi, 20001)
        demand = np.abs(_stuck_demand(m, r * np.cos(t) / w, r * np.sin(t) / math.sqrt(mt)))
        assert bound >= demand.max() * (1.0 - 1e-12)
        assert bound <= demand.max() * (1.0 + 1e-6)
        assert bound >= abs(_stuck_demand(m, y[0], y[1])) * (1.0 - 1e-15)
    assert kernel._demand_bound(np.array([0.5, -0.2, 0.0, 0.0]), _model(0.3, 0.0)) == 0.0


def test_hermite_root_finds_the_root_of_a_cubic():
    # g(t) = (t - 0.3) (t^2 + 1) on [0, 1]: the interpolant is g itself
    def g(t):
        return (t - 0.3) * (t * t + 1.0)

    def dg(t):
        return 3.0 * t * t - 0.6 * t + 1.0

    root = kernel.hermite_root(g(0.0), dg(0.0), g(1.0), dg(1.0), 1.0)
    assert abs(root - 0.3) < 1e-14


def test_stuck_step_screen_lets_through_exactly_the_steps_with_something_to_locate():
    """_stick_event_possible is false exactly when _stick_event would locate nothing."""
    m = _model(0.3, 1.0, 0.1)
    p = get_pulse("ricker")
    rng = np.random.default_rng(7)
    y = np.array([0.01, -0.02, 0.0, 0.0])
    K = np.zeros((kernel.NS + 2, 4))
    ye, work = np.empty(4), np.empty(4)
    thr = m[kernel.M_THR]
    seen = {True: 0, False: 0}
    for _ in range(400):
        ar0, ar1 = rng.uniform(-1.5, 1.5, 2) * thr
        r0, r1 = rng.normal(size=2) * rng.choice([1e-3, 1.0, 30.0])
        h = 10.0 ** rng.uniform(-4, -1)
        track_max = bool(rng.integers(2))
        possible = kernel._stick_event_possible(ar0, ar1, r0, r1, h, thr, track_max)
        cnt = np.zeros(4, dtype=np.int64)
        found, _, _, amax = kernel._stick_event(0.0, -1.0, y, h, ar0, ar1, r0, r1, track_max, False, m, p.code,
                                                p.param_array, 1e-12, 1e-9, K, ye, work, cnt, 0.5)
        assert possible == (cnt.sum() > 0)
        if not possible:
            assert not found and amax == 0.5
        seen[possible] += 1
    assert min(seen.values()) > 50


@pytest.mark.parametrize("module", ["kernel", "building_kernel", "piecewise"])
def test_every_kernel_declares_its_result_layout_and_the_indices_follow_it(module):
    """``R_<NAME>`` / ``F_<NAME>`` index ``INT_RESULTS`` / ``FLOAT_RESULTS`` at ``<name>``, and a run's
    arrays have exactly the declared lengths (the solver reads results by these names only)."""
    import importlib

    from isoslide import Scene, solver
    from isoslide.engine import building

    mod = importlib.import_module(f"isoslide.{module}")
    for prefix, names in (("R_", mod.INT_RESULTS), ("F_", mod.FLOAT_RESULTS)):
        consts = {k: v for k, v in vars(mod).items() if k.startswith(prefix) and isinstance(v, int)}
        assert consts, f"{module} declares no {prefix}* indices"
        for k, v in consts.items():
            assert names[v] == k[len(prefix):].lower(), (module, k, v)
    sc = Scene(pi2=0.2, pi3=1.0, pi4=0.1, pi9=0.05 if module == "building_kernel" else 0.0)
    if module == "building_kernel":
        P = building.parameters(sc)
        pu = sc.pulse
        res = mod.run(P, pu.code, pu.param_array, pu.breakpoint_array, pu.tau_start, pu.tau_end, 20.0, 0.05, 0.05,
                      1e-8, 1e-10, 0, 1e-3, True, 10**6, *building.modal_data(sc, P))
    elif module == "kernel":
        res = solver._run(sc, sc.pi8, 1.0, 1e-6)
    else:
        from isoslide.pulses import sampled
        sc = Scene(pi2=0.2, pi3=1.0, pi4=0.1, pulse=sampled(np.sin(np.linspace(0, 6.3, 101)), 0.01))
        res = None
        run = solver._run_piecewise(sc, sc.pi8)
    if res is not None:
        assert len(res[0]) == len(mod.INT_RESULTS) and len(res[1]) == len(mod.FLOAT_RESULTS)
        run = solver.Run.of(mod, res)
    assert run.pi1 > 0.0 and run.ints["settled"] == 1 and run.ints["steps"] > 0
