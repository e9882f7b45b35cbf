"""Exact propagation of the free linear phase after the pulse (isoslide.engine.free_phase): the modal
step against the matrix exponential, the safe step against the demand it bounds, and whole solutions
with and without the exact steps."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.linalg import expm

from isoslide import Scene, solve
from isoslide.engine import building, free_phase
from isoslide.engine import building_kernel as bk
from isoslide.engine.system import unassembled

FLEX = dict(pi11=0.6, pi12=0.2, pi13=0.02)
BUILDINGS = {
    "flexible, roof": dict(pi2=0.3, pi3=2.0, pi4=0.05, pi8=0.01, **FLEX, floor="roof"),
    "three storeys, roof": dict(pi2=0.3, pi3=2.0, pi4=0.05, pi8=0.01, **FLEX, storeys=3, floor="roof"),
    "five storeys, floor 2": dict(pi2=0.05, pi3=2.0, pi4=0.05, pi8=0.01, **FLEX, storeys=5, floor=2),
    "lead-rubber": dict(pi2=0.1, pi3=2.0, pi4=0.05, pi8=0.01, pi9=0.05, pi10=0.005),
    "friction pendulum, flexible": dict(pi2=0.15, pi3=2.0, pi4=0.0, pi8=0.01, pi9=0.05, **FLEX, floor="roof"),
    "fixed base, three storeys": dict(pi2=0.2, pi3=0.0, pi8=0.01, **FLEX, storeys=3, floor="roof"),
    "Stribeck, flexible": dict(pi2=0.2, pi3=2.0, pi4=0.1, pi5=0.7, pi6=50.0, pi8=0.01, **FLEX, floor="roof"),
}
PLANAR = dict(pulse="ricker", pulse_y="antisymmetric_ricker", pi14=0.7)


def _system(sc: Scene, held: bool):
    P = building.parameters(sc)
    idx = building.free_states(P, held)
    ny = bk.state_size(int(P[bk.P_N]))
    A, _ = bk.free_system(P, sc.pulse.code, sc.pulse.param_array, held, np.array(idx), ny, 1)
    modal = building.modal_data(sc, P)
    return P, A, idx, modal[4:] if held else modal[:4]


@pytest.mark.parametrize("name", ["flexible, roof", "five storeys, floor 2", "lead-rubber"])
def test_a_modal_step_is_the_matrix_exponential(name):
    """advance(h) equals expm(A h) applied to the moving states, to round-off, for short and long steps."""
    sc = Scene(**BUILDINGS[name])
    P, A, idx, (W, C, V, L) = _system(sc, held=False)
    rng = np.random.default_rng(3)
    ny = W.shape[1]
    for h in (1e-3, 0.37, 5.0):
        y = np.zeros(ny)
        y[idx] = rng.normal(size=len(idx))
        y[ny - 3] = 0.25   # the stuck contents' displacement: not a moving state, kept
        a = np.empty(W.shape[0], dtype=complex)
        free_phase.modal_coordinates(W, y, 0, a)
        out = y.copy()
        free_phase.advance(a, L, V, h, out, 0)
        ref = expm(A * h) @ y[idx]
        assert np.max(np.abs(out[idx] - ref)) <= 1e-11 * max(1.0, np.max(np.abs(ref)))
        assert out[ny - 3] == 0.25


@pytest.mark.parametrize("name", ["flexible, roof", "five storeys, floor 2", "lead-rubber",
                                  "friction pendulum, flexible", "fixed base, three storeys"])
def test_the_modal_data_decompose_the_free_system_with_exact_conjugate_pairs(name):
    """V diag(L) W is the free system's matrix, W V the identity, and every complex mode's conjugate is a mode.

    Both configurations that occur (elastic, and held for a sliding bearing or a fixed base) are
    checked; the demand rows ``C`` are ``c V`` to the decomposition's margin.
    """
    sc = Scene(**BUILDINGS[name])
    P = building.parameters(sc)
    modal = building.modal_data(sc, P)
    ny = bk.state_size(int(P[bk.P_N]))
    checked = 0
    for held, (W, C, V, L) in ((False, modal[:4]), (True, modal[4:])):
        if L.size == 0:
            continue
        idx = building.free_states(P, held)
        A, c = bk.free_system(P, sc.pulse.code, sc.pulse.param_array, held, np.array(idx), ny, C.shape[0])
        Wm, Vm = W[:, idx], V[idx, :]
        scale = max(1.0, np.max(np.abs(A)))
        assert np.max(np.abs(Vm @ np.diag(L) @ Wm - A)) <= 1e-11 * scale
        assert np.max(np.abs(Wm @ Vm - np.eye(len(idx)))) <= 1e-11
        assert np.max(np.abs(C - c @ Vm)) <= 1e-9 * max(1.0, np.max(np.abs(C)))
        assert np.all(np.diff(np.abs(L)) <= 0.0)   # fastest first
        for k in np.flatnonzero(L.imag != 0.0):
            j = np.flatnonzero(L == np.conj(L[k]))
            assert j.size == 1 and np.array_equal(V[:, j[0]], np.conj(V[:, k]))
        checked += 1
    assert checked >= 1


def _dephased(a, lam, rng):
    """Modal coordinates of another real state: each pair of conjugate modes turned by a random phase."""
    out = a.copy()
    k = 0
    while k < len(a):
        if k + 1 < len(a) and lam[k].imag != 0.0 and lam[k + 1] == np.conj(lam[k]):
            turn = np.exp(1j * rng.uniform(0.0, 2.0 * np.pi))
            out[k], out[k + 1] = a[k] * turn, a[k + 1] / turn
            k += 2
        else:
            k += 1
    return out


@pytest.mark.parametrize("name", ["flexible, roof", "five storeys, floor 2", "lead-rubber"])
@pytest.mark.parametrize("planar", [False, True], ids=["line", "plane"])
def test_no_demand_reaches_its_limit_within_a_safe_step(name, planar):
    """Sampled densely inside safe_step's length, every demand (its length in the plane) stays within its limit."""
    sc = Scene(**BUILDINGS[name])
    P, A, idx, (W, C, V, L) = _system(sc, held=False)
    rng = np.random.default_rng(11)
    ny = W.shape[1]
    limits = np.array([P[bk.P_THR], P[bk.P_Q]])
    offsets = np.zeros((2, 2))
    checked = 0
    for _trial in range(60):
        ys = []
        for _axis in range(2 if planar else 1):
            y = np.zeros(ny)
            y[idx] = rng.normal(size=len(idx))
            ys.append(y)
        a = [np.empty(W.shape[0], dtype=complex) for _ in ys]
        for y, ak in zip(ys, a, strict=True):
            free_phase.modal_coordinates(W, y, 0, ak)
        a = [_dephased(ak, L, rng) for ak in a]
        ay = a[1] if planar else np.zeros_like(a[0])
        # scaled so that the largest demand bound is 1.05-3 times its limit: not yet settled
        bounds = np.abs(C) @ np.hypot(np.abs(a[0]), np.abs(ay))
        scale = rng.uniform(1.05, 3.0) * np.min(limits[:C.shape[0]] / bounds)
        a[0] *= scale
        ay = ay * scale
        h = free_phase.safe_step(a[0], ay, L, C, offsets, limits)
        if not (0.0 < h < np.inf):
            continue
        checked += 1
        s = np.linspace(0.0, h, 2001)
        for j in range(C.shape[0]):
            dx = np.real((C[j] * a[0]) @ np.exp(np.outer(L, s)))
            dy = np.real((C[j] * ay) @ np.exp(np.outer(L, s)))
            assert np.max(np.hypot(dx, dy)) <= limits[j]
    assert checked >= 10


def _without_exact_steps(monkeypatch):
    """Modal data without the propagation arrays: every step after the pulse is a Runge-Kutta step."""
    original = building.modal_data

    def settlement_only(scene, P):
        Wm, Cm, Vm, Lm, Wh, Ch, Vh, Lh = original(scene, P)
        return (Wm, Cm, Vm[:, :0].copy(), Lm[:0].copy(), Wh, Ch, Vh[:, :0].copy(), Lh[:0].copy())

    monkeypatch.setattr(building, "modal_data", settlement_only)


@pytest.mark.parametrize("planar", [False, True], ids=["line", "plane"])
@pytest.mark.parametrize("name", list(BUILDINGS))
def test_exact_free_steps_give_the_integrated_answer_in_fewer_steps(name, planar, monkeypatch):
    """Pi1, the transitions and settlement with the exact free steps equal those of Runge-Kutta steps
    alone (rtol 1e-10), in no more steps."""
    sc = Scene(**BUILDINGS[name], **(PLANAR if planar else {}))
    fast = solve(sc, rtol=1e-10, model="full")
    with monkeypatch.context() as m:
        _without_exact_steps(m)
        slow = solve(unassembled(sc), rtol=1e-10, model="full")
    assert fast.pi1 == pytest.approx(slow.pi1, rel=1e-8, abs=1e-14)
    assert (fast.n_events, fast.settled) == (slow.n_events, slow.settled)
    assert fast.n_steps <= slow.n_steps


def test_a_long_free_tail_takes_few_exact_steps(monkeypatch):
    """Five storeys on a lightly damped isolator: the waits between the contents' last slides and for
    settlement take exact steps instead of steps of an eighth of the shortest period."""
    sc = Scene(pi2=0.5, pi3=2.0, pi4=0.02, pi8=0.01, **FLEX, storeys=5, floor="roof")
    fast = solve(sc, model="full")
    with monkeypatch.context() as m:
        _without_exact_steps(m)
        slow = solve(unassembled(sc), model="full")
    assert fast.pi1 == pytest.approx(slow.pi1, rel=1e-6)
    assert fast.settled and slow.settled
    assert fast.n_steps < 0.7 * slow.n_steps


def test_a_matrix_is_decomposed_once_with_the_bits_of_a_fresh_decomposition(monkeypatch):
    """free_phase.modes keeps each matrix's modes: an equal matrix gets the same arrays, bit for bit
    those of free_phase.decompose, and no more than MODES_KEPT matrices are kept."""
    monkeypatch.setattr(free_phase, "_MODES", {})
    monkeypatch.setattr(free_phase, "MODES_KEPT", 3)
    rng = np.random.default_rng(2)
    A = -np.eye(4) + 0.3 * rng.normal(size=(4, 4))
    kept = free_phase.modes(A)
    again = free_phase.modes(A.copy())
    assert all(x is y for x, y in zip(kept, again, strict=True))
    for x, y in zip(kept, free_phase.decompose(A), strict=True):
        assert np.array_equal(x, y)
    for k in range(5):
        free_phase.modes(A + 0.01 * (k + 1) * np.eye(4))
    assert len(free_phase._MODES) == 3
    assert free_phase.modes(A) is not kept    # the oldest was dropped: decomposed anew, the same bits
    assert all(np.array_equal(x, y) for x, y in zip(free_phase.modes(A), kept, strict=True))
