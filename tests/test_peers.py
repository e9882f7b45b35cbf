"""The peer solvers share one result type and the solver's time history, and solve() maps them."""

import dataclasses

import numpy as np
import pytest

import isoslide
from isoslide import peers, solver
from isoslide.store.history import History
from isoslide.peers import PeerResult
from isoslide.studies.similarity import physical_parameters

SCENE = isoslide.Scene(pi2=0.2, pi3=1.0, pi4=0.1)   # resonance, Coulomb: every peer can run it
HORIZON = 10.0                                       # T_p after the pulse
SOLVER_FIELDS = ["tau", "x", "xd", "u", "ud", "phase"]
BUILDING_FIELDS = ["xs", "xsd", "fh", "iso_phase", "stage", "theta", "thetad"]
"""Optional states of a general building (None for the paper's model; stage for a triple friction pendulum)."""


def _run(name, history=True):
    tau_max = SCENE.pulse.tau_end + HORIZON
    if name == "reference":
        return peers.solve_reference(SCENE, tau_max=tau_max, history=history)
    if name == "regularized":
        return peers.solve_regularized(SCENE, stiffness=1e4, rtol=1e-4, tau_max=tau_max, history=history)
    if name == "si":
        a_p, T_p = 3.0, 0.8
        p = physical_parameters(SCENE.pis(), a_p, T_p, 2e5)
        return peers.simulate_si(p, SCENE.pulse, t_end=tau_max * T_p, history=history)
    if name == "opensees":
        if not peers.opensees.opensees_available():
            pytest.skip("openseespy does not import (pip install -e .[peers])")
        return peers.solve_opensees(SCENE, stiffness=1e4, tau_max=tau_max, history=history)
    raise ValueError(name)


PEERS = ["reference", "regularized", "si", "opensees"]


@pytest.fixture(scope="module")
def exact():
    return isoslide.solve(SCENE, horizon=HORIZON, history=True)


@pytest.mark.parametrize("name", PEERS)
def test_every_peer_returns_a_peer_result_with_the_solvers_history(name, exact):
    res = _run(name)
    assert isinstance(res, PeerResult) and res.method == name
    h = res.history
    assert isinstance(h, History) and History is solver.History
    assert [f.name for f in dataclasses.fields(h)] == SOLVER_FIELDS + BUILDING_FIELDS
    assert all(getattr(h, f) is None for f in BUILDING_FIELDS)
    assert all(getattr(h, f).shape == h.tau.shape for f in SOLVER_FIELDS)
    assert h.phase.dtype == np.int8 and set(np.unique(h.phase)) == {-1, 0, 1}
    assert np.all(np.diff(h.tau) >= 0.0)
    # dimensionless like the solver's: the peak and the residual are read off the history
    assert np.max(np.abs(h.u)) <= res.pi1 * (1 + 1e-12)
    assert h.u[-1] == pytest.approx(res.pi1_residual, rel=1e-12)
    assert h.tau[-1] == pytest.approx(res.tau_end, rel=1e-12)
    # phase +1 / -1 is the direction of sliding, as in the solver (up to the stop's rounding)
    slide = h.phase != 0
    assert np.all(h.phase[slide] * h.ud[slide] >= -1e-12)
    assert h.phase[slide][0] == exact.history.phase[exact.history.phase != 0][0]
    # the same physics: Pi1 near the exact solver's (the spring peers to their regularisation error)
    assert res.pi1 == pytest.approx(exact.pi1, rel=1e-6 if name in ("reference", "si") else 5e-2)
    assert res.work > 0


@pytest.mark.parametrize("name", PEERS)
def test_history_is_recorded_only_on_request_and_changes_no_number(name):
    a, b = _run(name, history=False), _run(name, history=True)
    assert a.history is None
    assert dataclasses.replace(b, history=None) == a


@pytest.mark.parametrize("method, options", [("reference", {}), ("regularized", {"stiffness": 1e4})])
def test_solve_maps_a_peer_result_to_a_solution(method, options):
    scene = isoslide.Scene.from_physical(a_p=6.0, T_p=1.2, M_b=8e5, T_b=1.2, xi_b=0.1, m_ec=800.0,
                                         mu_s=0.15, mu_k=0.15)
    res = peers.SCENE_SOLVERS[method](scene, history=True, **options)
    sol = isoslide.solve(scene, method=method, history=True, **options)
    assert isinstance(sol, solver.Solution) and sol.model == method
    assert (sol.pi1, sol.pi1_residual, sol.tau_peak, sol.settled, sol.tau_end, sol.n_events) == (
        res.pi1, res.pi1_residual, res.tau_peak, res.settled, res.tau_end, res.n_events)
    assert sol.n_steps == (res.n_steps if res.n_steps >= 0 else res.nfev) > 0
    L, T_p = 6.0 * 1.2**2, 1.2
    assert sol.u_max == res.pi1 * L == pytest.approx(res.metres(scene))
    assert sol.u_residual == res.pi1_residual * L and sol.t_peak == res.tau_peak * T_p
    assert isinstance(sol.history, History)
    np.testing.assert_array_equal(sol.history.u, res.history.u)


def test_a_peer_that_finds_no_slide_reports_zero_events():
    scene = isoslide.Scene(pi2=1.0, pi3=3.0, pi4=0.1)
    sol = isoslide.solve(scene, method="reference")
    assert sol.pi1 == 0.0 and sol.n_events == 0 and sol.settled


def test_unknown_method_names_the_peers():
    with pytest.raises(ValueError, match="'reference'.*'regularized'"):
        isoslide.solve(SCENE, method="magic")
