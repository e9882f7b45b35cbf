"""OpenSees as an independent peer of the N-storey building.

The superstructure is a shear building of ``storeys`` floors whose fixed-base fundamental period is
``Pi12`` and whose damping is classical with ratio ``Pi13`` in every fixed-base mode; the OpenSees
model realises that damping matrix by a network of dashpots.  These tests check the model's
matrices, that OpenSees integrates them, the limits a building must reach, its symmetries, and that
the regularised answer converges to the event-driven reference peer.
"""

import ast
import dataclasses
import inspect
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.linalg import eigh

import isoslide
from isoslide.studies import opensees_convergence as oc
from isoslide.peers import opensees as peer
from isoslide.peers import opensees_available, solve_opensees
from isoslide.peers.opensees import opensees_model
from isoslide.pulses import sampled

pytestmark = pytest.mark.skipif(not opensees_available(),
                                reason="openseespy does not import (pip install -e .[peers])")

S = isoslide.Scene
FRAME = {"pi11": 0.5, "pi12": 0.3, "pi13": 0.02}
FP = {"pi2": 0.2, "pi3": 2.0, "pi9": 0.05}
LRB = {"pi2": 0.2, "pi3": 2.0, "pi4": 0.05, "pi9": 0.05, "pi10": 0.005}
TAPERED = {"floor_masses": (1.2, 1.1, 1.0, 0.9, 0.8), "storey_stiffnesses": (1.6, 1.4, 1.2, 1.0, 0.8)}
BUILDINGS = {
    "2 storeys": S(**FP, **FRAME, storeys=2, floor=1),
    "5 storeys": S(**LRB, **FRAME, storeys=5, floor="roof"),
    "8 storeys": S(**FP, **FRAME, storeys=8, floor=4),
    "5 storeys tapered": S(**FP, **FRAME, storeys=5, floor=3, **TAPERED),
}


def _full_damping_and_stiffness(M):
    """Assemble the links' springs and dashpots over the slab (index 0) and the floors."""
    n = M.storeys + 1
    K, C = np.zeros((n, n)), np.zeros((n, n))
    for i, j, k, c in M.links():
        for A, v in ((K, k), (C, c)):
            A[i, i] += v
            A[j, j] += v
            A[i, j] -= v
            A[j, i] -= v
    return K, C


@pytest.mark.parametrize("name", list(BUILDINGS))
def test_fixed_base_period_masses_and_modal_damping(name):
    """Fundamental fixed-base period Pi12, floor masses Pi11 w_j, stiffness ratios r_j, damping Pi13 in every mode."""
    sc = BUILDINGS[name]
    M = opensees_model(sc, stick_displacement=1e-6)
    Ms, Ks, Cs = M.matrices()
    n = sc.storeys
    assert Ms.shape == Ks.shape == Cs.shape == (n, n) and M.storeys == n and M.floor == sc.floor_index
    w = np.full(n, 1.0 / n) if sc.floor_masses is None else np.array(sc.floor_masses)
    assert np.allclose(np.diag(Ms), sc.pi11 * w, rtol=1e-14) and M.mb == pytest.approx(1.0 - sc.pi11)
    r = np.ones(n) if sc.storey_stiffnesses is None else np.array(sc.storey_stiffnesses)
    assert np.allclose(np.array(M.stiffnesses) / M.stiffnesses[0], r / r[0], rtol=1e-13)
    lam, phi = eigh(Ks, Ms)
    assert 2 * math.pi / math.sqrt(lam[0]) == pytest.approx(sc.pi12, rel=1e-12)
    modal = phi.T @ Cs @ phi
    omega = np.sqrt(lam)
    assert np.allclose(np.diag(modal), 2 * sc.pi13 * omega, rtol=1e-10)
    assert np.max(np.abs(modal - np.diag(np.diag(modal)))) < 1e-12 * np.max(np.abs(modal))
    assert np.array_equal(Cs, Cs.T)


@pytest.mark.parametrize("name", list(BUILDINGS))
def test_springs_and_dashpots_assemble_to_the_building_matrices(name):
    """The elements OpenSees gets: the floors' block is K_s and C_s, and a rigid motion loads none of them."""
    M = opensees_model(BUILDINGS[name], stick_displacement=1e-6)
    _, Ks, Cs = M.matrices()
    K, C = _full_damping_and_stiffness(M)
    assert np.allclose(K[1:, 1:], Ks, rtol=0, atol=1e-12 * np.max(np.abs(Ks)))
    assert np.allclose(C[1:, 1:], Cs, rtol=0, atol=1e-12 * np.max(np.abs(Cs)))
    assert np.allclose(C @ np.ones(len(C)), 0.0, atol=1e-12 * np.max(np.abs(Cs)))
    storeys = [(i, j) for i, j, k, _ in M.links() if k != 0.0]
    assert storeys == [(j - 1, j) for j in range(1, M.storeys + 1)]


def test_one_storey_is_the_single_superstructure_mass():
    """storeys = 1: one spring-dashpot of k_s = m_st (2 pi/Pi12)^2, c_s = 2 Pi13 (2 pi/Pi12) m_st under one mass."""
    sc = S(**LRB, **FRAME, floor="roof")
    M = opensees_model(sc, stick_displacement=1e-6)
    ws = 2 * math.pi / sc.pi12
    assert M.masses == (sc.pi11,) and M.storeys == 1 and M.floor == 1 and M.roof
    assert M.links() == [(0, 1, sc.pi11 * ws * ws, 2 * sc.pi13 * ws * sc.pi11)]
    assert (M.ks, M.cs) == M.links()[0][2:]
    h = solve_opensees(sc, tau_max=3.0, dtau=1e-3, stick_displacement=1e-6, history=True).history
    assert h.xs.ndim == 1 and h.xs.shape == h.x.shape


def _linear_building(M, pulse, tau):
    """The building's slab and floors (relative to the slab) by SciPy from the model's matrices."""
    Ms, Ks, Cs = M.matrices()
    n, one = M.storeys, np.ones(M.storeys)
    A = np.zeros((n + 1, n + 1))                   # mass matrix in (x, xs): slab row carries the floors
    A[0, 0] = M.mb + Ms.sum()
    A[0, 1:] = A[1:, 0] = Ms @ one
    A[1:, 1:] = Ms
    K = np.zeros_like(A)
    C = np.zeros_like(A)
    K[0, 0], C[0, 0] = M.kd, M.cb
    K[1:, 1:], C[1:, 1:] = Ks, Cs
    Ai = np.linalg.inv(A)
    load = np.concatenate(([M.mb + Ms.sum()], Ms @ one))

    def f(t, y):
        z, zd = y[: n + 1], y[n + 1:]
        return np.concatenate((zd, Ai @ (-load * pulse.accel(np.array([t]))[0] - C @ zd - K @ z)))

    sol = solve_ivp(f, (tau[0], tau[-1]), np.zeros(2 * n + 2), method="DOP853", t_eval=tau, rtol=1e-11, atol=1e-13)
    return sol.y[0], sol.y[1: n + 1]


def test_opensees_integrates_the_building_matrices():
    """Linear isolator, tapered 5 storeys, 10 % damping, contents that never slide: slab and every
    floor as SciPy integrates M z'' + C z' + K z = -M 1 p, within 1e-4 of the peak (measured 4e-6;
    dashpots of the wrong sign between floors are 3e-3 off at 2 % damping)."""
    sc = S(pi2=50.0, pi3=2.0, pi4=0.05, pi8=1e-6, pi11=0.5, pi12=0.3, pi13=0.1, storeys=5, floor=3, **TAPERED)
    M = opensees_model(sc, stick_displacement=1e-9)
    r = solve_opensees(sc, tau_max=4.0, dtau=2e-4, stick_displacement=1e-9, history=True)
    h = r.history
    x, xs = _linear_building(M, sc.pulse, h.tau)
    assert r.pi1 < 1e-8
    assert h.xs.shape == (h.tau.size, 5)
    assert np.max(np.abs(h.x - x)) < 1e-4 * np.max(np.abs(x))
    for j in range(5):
        assert np.max(np.abs(h.xs[:, j] - xs[j])) < 1e-4 * np.max(np.abs(xs[j])), j
    assert np.array_equal(h.xs[:, -1], h.xs[:, 4]) and np.max(np.abs(xs[4])) > np.max(np.abs(xs[0]))


@pytest.mark.parametrize("floor", ["roof", 2])
def test_a_stiff_superstructure_approaches_the_rigid_building(floor):
    """Contents on the roof or floor 2 of 4 storeys: 100x closer to the rigid building's Pi1 at
    Pi12 = 0.01 than at Pi12 = 0.1, and within 1e-4 (measured 0.3-4e-3 and 2-5e-5 at 5 storeys)."""
    kw = {"tau_max": 6.0, "dtau": 2e-4, "stick_displacement": 1e-6}
    base = dict(FP, pi11=0.5, pi13=0.02, storeys=4, floor=floor)
    rigid = solve_opensees(S(**base, pi12=0.0), **kw).pi1
    err = [abs(solve_opensees(S(**base, pi12=p), **kw).pi1 / rigid - 1) for p in (0.1, 0.01)]
    assert err[1] < 1e-4 and err[1] < err[0] / 10, err


def test_a_flexible_building_is_not_the_rigid_one():
    """The check above can fail: at Pi12 = 0.3 the roof's Pi1 is over 0.5 % from the rigid building's."""
    kw = {"tau_max": 6.0, "dtau": 5e-4, "stick_displacement": 1e-6}
    base = dict(FP, pi11=0.5, pi13=0.02, storeys=4, floor="roof")
    rigid = solve_opensees(S(**base, pi12=0.0), **kw).pi1
    assert abs(solve_opensees(S(**base, pi12=0.3), **kw).pi1 / rigid - 1) > 5e-3


def test_a_mirrored_ground_motion_mirrors_the_response():
    """Coulomb friction is odd: -p gives the same Pi1 and the negated slab, floor and sliding histories."""
    tau = np.arange(0.0, 2.0 + 1e-12, 1e-3)
    a = isoslide.pulses.ricker().accel(tau)
    kw = {"tau_max": 4.0, "dtau": 5e-4, "stick_displacement": 1e-6, "history": True}
    base = dict(LRB, **FRAME, storeys=5, floor=3)
    plus = solve_opensees(S(**base, pulse=sampled(a, 1e-3)), **kw)
    minus = solve_opensees(S(**base, pulse=sampled(-a, 1e-3)), **kw)
    assert plus.pi1 > 1e-2 and minus.pi1 == pytest.approx(plus.pi1, rel=1e-9)
    for f in ("x", "u", "xs", "fh"):
        p, m = getattr(plus.history, f), getattr(minus.history, f)
        assert np.allclose(m, -p, rtol=0, atol=1e-9 * np.max(np.abs(p))), f
    assert np.array_equal(minus.history.phase, -plus.history.phase)


def test_uniform_shares_and_scaled_stiffnesses_are_the_same_building():
    """Explicit equal shares are the uniform building; storey stiffnesses are relative (kappa absorbs their scale)."""
    uniform = opensees_model(S(**FP, **FRAME, storeys=4, floor=2), stick_displacement=1e-6)
    explicit = opensees_model(S(**FP, **FRAME, storeys=4, floor=2, floor_masses=(3, 3, 3, 3),
                                storey_stiffnesses=(1, 1, 1, 1)), stick_displacement=1e-6)
    assert explicit == uniform
    a = opensees_model(S(**FP, **FRAME, storeys=5, floor=3, **TAPERED), stick_displacement=1e-6)
    scaled = dict(TAPERED, storey_stiffnesses=tuple(7.0 * v for v in TAPERED["storey_stiffnesses"]))
    b = opensees_model(S(**FP, **FRAME, storeys=5, floor=3, **scaled), stick_displacement=1e-6)
    assert np.allclose(a.stiffnesses, b.stiffnesses, rtol=1e-12) and np.allclose(a.damping, b.damping, rtol=1e-10)
    five = opensees_model(S(**FP, **FRAME, storeys=5, floor=3), stick_displacement=1e-6)
    assert not np.allclose(a.stiffnesses, five.stiffnesses, rtol=1e-2)


def test_the_contents_floor_is_the_one_asked_for():
    """The block's element joins the contents' floor: Pi1 differs floor by floor and 'roof' is floor N."""
    kw = {"tau_max": 4.0, "dtau": 1e-3, "stick_displacement": 1e-6}
    pi1 = [solve_opensees(S(**FP, **FRAME, storeys=3, floor=k), **kw).pi1 for k in range(4)]
    assert len({round(v, 6) for v in pi1}) == 4, pi1
    assert solve_opensees(S(**FP, **FRAME, storeys=3, floor="roof"), **kw).pi1 == pi1[3]
    assert solve_opensees(S(**FP, **FRAME, storeys=3, floor="base"), **kw).pi1 == pi1[0]
    rigid = [solve_opensees(S(**FP, pi11=0.5, storeys=3, floor=k), **kw).pi1 for k in range(4)]
    assert len(set(rigid)) == 1


@pytest.mark.parametrize("kind", ["linear", "bilinear", "sliding", "fixed"])
def test_every_isolator_under_three_storeys_agrees_with_the_reference_peer(kind):
    """Contents on floor 2 of 3: OpenSees at dtau 3e-4, stick 1e-7 within 2e-3 of the event-driven
    reference peer (measured 1.4e-4 .. 6.9e-4)."""
    iso = {"linear": {"pi3": 2.0, "pi4": 0.05}, "bilinear": {"pi3": 2.0, "pi4": 0.05, "pi9": 0.05, "pi10": 0.005},
           "sliding": {"pi3": 2.0, "pi9": 0.05}, "fixed": {"pi3": 0.0, "pi2": 0.3}}[kind]
    sc = S(**{"pi2": 0.2, **FRAME, "pi8": 0.05, "storeys": 3, "floor": 2, **iso})
    assert sc.isolator == {"fixed": sc.isolator}.get(kind, kind) and sc.fixed_base == (kind == "fixed")
    tau_max = sc.pulse.tau_end + 5.0
    ref = isoslide.solve(sc, method="reference", tau_max=tau_max).pi1
    r = solve_opensees(sc, tau_max=tau_max, dtau=3e-4, stick_displacement=1e-7)
    assert abs(r.pi1 / ref - 1) < 2e-3


def test_error_falls_as_the_stick_displacement_shrinks():
    """5 storeys, lead-rubber, roof, against a 10x finer OpenSees run: each error smaller than the last."""
    pairs = ((1e-2, 1e-4), (3e-3, 1e-5), (1e-3, 1e-6))
    conv = oc.opensees_convergence(BUILDINGS["5 storeys"], pairs, target="opensees", horizon=2.0)
    errs = [r.rel_error for r in conv.rows]
    assert conv.target == "opensees"
    assert all(b < a for a, b in zip(errs, errs[1:], strict=False)) and errs[-1] < errs[0] / 10, errs


@pytest.mark.slow
@pytest.mark.parametrize("name", list(oc.STOREY_SCENES))
def test_every_storey_scene_converges_to_the_reference_peer(name):
    """Default pairs against the reference peer: each error smaller than the last, the finest within
    2e-3 and 40x below the coarsest (measured at horizon 10: finest 1.2e-4 .. 1.02e-3, coarsest
    5e-2 .. 1e-1; the lead-rubber roofs, whose contents reverse without stopping, fall as the
    square root of the stick displacement)."""
    conv = oc.opensees_convergence(oc.STOREY_SCENES[name], target="reference", horizon=5.0)
    errs = [r.rel_error for r in conv.rows]
    assert all(b < a for a, b in zip(errs, errs[1:], strict=False)), errs
    assert errs[-1] < 2e-3 and errs[-1] < errs[0] / 40, errs


def test_a_solver_that_reads_one_storey_only_is_not_a_target(monkeypatch):
    """'exact' refuses, and 'auto' passes over, a solver whose Pi1 of N storeys is that of one storey."""
    sc = BUILDINGS["2 storeys"]
    calls = []

    def one_storey_only(scene, method="exact", **kw):
        """An exact solver blind to the storeys; a reference peer that refuses several storeys."""
        calls.append((scene.storeys, method))
        if method == "reference" and scene.storeys > 1:
            raise NotImplementedError("one storey only")
        return type("Result", (), {"pi1": 0.125})()

    monkeypatch.setattr(oc, "solve", one_storey_only)
    tau_max = sc.pulse.tau_end + 2.0
    with pytest.raises(ValueError, match="target = 'exact'"):
        oc.target_pi1(sc, "exact", tau_max)
    assert oc.modelled_pi1("exact", sc, tau_max) is None
    label, value = oc.target_pi1(sc, "auto", tau_max, ((1e-2, 1e-4),))
    direct = solve_opensees(sc, tau_max=tau_max, dtau=1e-2 / oc.FINER, stick_displacement=1e-4 / oc.FINER).pi1
    assert (label, value) == ("opensees", direct)
    assert {(2, "exact"), (1, "exact"), (2, "reference")} <= set(calls)


def test_a_solver_that_models_the_storeys_is_the_auto_target(monkeypatch):
    """'auto' takes the exact solver when its Pi1 of N storeys differs from its one-storey Pi1."""
    sc = BUILDINGS["2 storeys"]
    monkeypatch.setattr(oc, "solve", lambda scene, **kw: type("R", (), {"pi1": 0.1 + 0.01 * scene.storeys})())
    assert oc.target_pi1(sc, "auto", 5.0) == ("exact", pytest.approx(0.12))
    assert oc.modelled_pi1("exact", dataclasses.replace(sc, storeys=1, floor="roof"), 5.0) == pytest.approx(0.11)
    with pytest.raises(ValueError, match="target = 'opensees'"):
        oc.modelled_pi1("opensees", sc, 5.0)


def test_command_line_reads_storeys_floors_and_shares(capsys):
    assert oc.main(["--scene", "pi2=0.2", "pi3=2.0", "pi9=0.05", "pi11=0.5", "pi12=0.3", "storeys=3", "floor=2",
                    "floor_masses=1,2,1", "--target", "0.1", "--horizon", "0.5"]) == 0
    out = capsys.readouterr().out
    assert "storeys=3" in out and "floor=2" in out and "floor_masses=(0.25, 0.5, 0.25)" in out
    assert "target: given, Pi1 = 0.1" in out and len(out.strip().splitlines()) == 3 + len(oc.DEFAULT_PAIRS)


def test_the_peer_builds_its_own_matrices():
    """The OpenSees peer imports none of isoslide's own solvers."""
    tree = ast.parse(inspect.getsource(peer))
    imported = {n.module for n in ast.walk(tree) if isinstance(n, ast.ImportFrom) and n.module} | \
        {a.name for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names}
    forbidden = {"building", "building_kernel", "kernel", "engine", "model", "solver", "piecewise"}
    assert not {m.lstrip(".").split(".")[-1] for m in imported} & forbidden, imported
