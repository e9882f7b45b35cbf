"""OpenSees's TripleFrictionPendulum element against the triple friction pendulum's closed forms.

The element regularises stick by an elastic range reaching ``mu1 W`` at its yield displacement ``uy``;
away from the stuck stretches its quasi-static loop is the closed-form loop (isoslide.model.tfp)
shifted by a few ``uy``, so the force error is of order ``uy / L1`` relative to ``W``.  Checked: the
cyclic path (vertices inserted, steps bounded); the element's backbone equal to the regularised
series model's to round-off through regimes I..V; at the finest ``uy`` the loop within the shift
bound ``(mu1 + mu2 + mu3) / (3 mu1) uy / L1`` at amplitudes in regimes I, III and V, along ``x`` and
at 35 degrees, with no force across the direction; the error a hundred times smaller at ``uy`` a
hundred times smaller (first order), in every regime the loop reaches.
"""

import functools
import math

import numpy as np
import pytest

from isoslide.model import tfp
from isoslide.peers import opensees_available
from isoslide.peers import opensees_tfp as ot

needs_opensees = pytest.mark.skipif(not opensees_available(),
                                    reason="openseespy does not import (pip install -e .[peers])")

B = ot.DEFAULT_BEARING
L1 = B.L[0]
COARSE, FINE = 1e-3, 1e-5
"""``uy`` as fractions of the largest radius (2.5 mm and 25 micrometres)."""
SHIFT_BOUND = sum(B.mu) / (3.0 * B.mu[0])
"""Largest force error in units of ``uy / L1`` (3 for this bearing): the largest shift of the
regularised loop, ``2 (mu1 + mu2 + mu3) uy / (3 mu1)``, times the stiffest regime's ``W / (2 L1)``;
measured up to 2.13."""
ANGLES = {"x": 0.0, "35 deg": math.radians(35.0)}


@functools.lru_cache(maxsize=None)
def _row(regime: str, angle: str, fraction: float) -> ot.LoopError:
    A = ot.default_amplitudes(B)[regime]
    (row,) = ot.convergence(B, [A], (fraction,), steps_per_uy=1.0, angle=ANGLES[angle])
    return row


# ----------------------------------------------------------------------------------------------
# the path and the refusals (no OpenSees needed)
# ----------------------------------------------------------------------------------------------

def test_cyclic_path_goes_to_both_amplitudes_in_bounded_steps_through_every_closed_form_vertex():
    A = ot.default_amplitudes(B)["V"]
    h = 0.01
    u, branch, vertex = ot.cyclic_path(B, A, h)
    assert u[0] == 0.0 and u[-1] == A and np.max(np.abs(np.diff(u))) <= h * (1 + 1e-12)
    assert np.all(np.diff(u[branch == 0]) > 0) and np.all(np.diff(u[branch == 1]) < 0)
    assert np.all(np.diff(u[branch == 2]) > 0) and u[branch == 1][-1] == -A
    loop = tfp.cyclic_loop(B, A)
    for x in loop.u:                                    # every vertex of the closed-form loop is a step
        assert np.min(np.abs(u - x)) <= 1e-12 * A
    assert np.all(np.isin(np.round(loop.u[2:], 12), np.round(u[vertex], 12)))


def test_opensees_path_refuses_steps_beyond_twice_uy_and_a_path_not_starting_at_rest():
    with pytest.raises(ValueError, match=r"exceeds 2 uy = .*allowed: steps <= MAX_STEP_RATIO uy"):
        ot.tfp_path_opensees(B, [0.0, 1e-3, 3.5e-3], uy=1e-3)
    with pytest.raises(ValueError, match=r"starting at 0.0"):
        ot.tfp_path_opensees(B, [1e-3, 2e-3], uy=1e-3)
    with pytest.raises(ValueError, match=r"uy = 0.0 is out of range"):
        ot.tfp_loop_opensees(B, 0.1, uy=0.0)


def test_regularised_backbone_tends_to_the_closed_form_backbone_as_uy_shrinks():
    F = np.linspace(B.mu[0], 0.99 * tfp.regime_boundaries(B).F[5], 200)
    bb = tfp.backbone(B, tfp.capacity(B))
    u_closed = np.interp(F, bb.F[1:], bb.u[1:])
    gaps = [np.max(np.abs(ot.regularised_backbone(B, F, uy) - u_closed)) / uy for uy in (1e-3, 1e-5, 1e-7)]
    assert max(gaps) <= 2 * SHIFT_BOUND and gaps == pytest.approx([gaps[0]] * 3, rel=0.02)


# ----------------------------------------------------------------------------------------------
# OpenSees
# ----------------------------------------------------------------------------------------------

@needs_opensees
def test_opensees_backbone_equals_the_regularised_series_model_to_round_off_in_every_regime():
    """The element's first loading is the closed form's series model with its elastic springs and gaps."""
    A = ot.default_amplitudes(B)["V"]
    uy = COARSE * max(B.L)
    loop = ot.tfp_loop_opensees(B, A, uy)
    on = (loop.branch == 0) & (loop.u >= uy)
    want = ot.regularised_backbone(B, loop.F[on], uy)
    assert np.max(np.abs(loop.u[on] - want)) <= 1e-9 * uy
    stages = tfp.force(B, loop.u[on])[1]
    assert set(stages.tolist()) == {1, 2, 3, 4, 5}


@needs_opensees
@pytest.mark.parametrize("angle", list(ANGLES))
@pytest.mark.parametrize("regime", ["I", "III", "V"])
def test_opensees_loop_is_within_the_shift_bound_of_the_closed_form_at_the_finest_uy(regime, angle):
    """Largest |F - F_closed| / W outside the stuck stretches, and at the vertices, <= 3 uy / L1."""
    r = _row(regime, angle, FINE)
    assert r.peak_stage == {"I": 1, "III": 3, "V": 5}[regime]
    tol = SHIFT_BOUND * r.uy / L1                      # 2.5e-4 relative to W
    assert r.max_error <= tol and r.vertex_error <= tol
    assert r.normal_error <= 1e-9


@needs_opensees
@pytest.mark.parametrize("regime, angle", [("I", "x"), ("III", "35 deg"), ("V", "x"), ("V", "35 deg")])
def test_opensees_error_falls_in_proportion_to_uy_in_every_regime_the_loop_reaches(regime, angle):
    """uy 100 times smaller: the error 100 times smaller overall and per regime (order 1, within 0.1)."""
    coarse, fine = _row(regime, angle, COARSE), _row(regime, angle, FINE)
    ratio = coarse.uy / fine.uy
    order = math.log(coarse.max_error / fine.max_error) / math.log(ratio)
    assert 0.9 <= order <= 1.1
    reached = [k for k, e in enumerate(fine.stage_error) if math.isfinite(e)]
    assert reached == [k for k, e in enumerate(coarse.stage_error) if math.isfinite(e)]
    for k in reached:
        assert 0.8 <= math.log(coarse.stage_error[k] / fine.stage_error[k]) / math.log(ratio) <= 1.2
    rows = [coarse, fine]
    assert ot.observed_order(rows) == pytest.approx(order, rel=1e-12)
    text = ot.format_table(rows, B)
    assert f"observed order in uy: {order:.2f}" in text and f"{fine.uy:9.2e}" in text
