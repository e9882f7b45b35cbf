"""OpenSees's flatSliderBearing with VelDependent friction beside a linear spring: a rigid building on a
sliding bearing whose friction rises with speed, carrying sliding contents.

The scenes (:data:`~isoslide.peers.opensees_bearing_rate.EXAMPLE`): ``T_b = 2 T_p``, no viscous damping,
a bearing of high-speed friction ``Pi9 = 0.3`` under the Ricker pulse, so that the slab sticks, breaks
away and slides in both directions (about an eighth of the steps) and sticks again; contents of 1 % of the
building's mass with ``Pi2 = 0.2`` that slide on the slab too.  With ``Pi22 = 0.5``, ``Pi23 = 20`` the
bearing breaks away at ``0.15`` and slides at speeds ``|x'|`` up to about ``0.17``, where ``Pi23 |x'|``
reaches 3.4: its friction runs over most of the law, from ``0.15`` to ``0.29``.

Checked: with constant friction (``Pi22 = 1``) the model is the existing OpenSees peer's elastic-plastic
bearing to round-off and converges to isoslide's exact answer as ``uy`` and ``dtau`` shrink (at about half
order in ``uy``, the rate of the regularised springs that reverse: see
:mod:`isoslide.studies.opensees_convergence`); with ``Pi22 < 1`` it converges on itself; the bearing
slides with the law's friction to round-off and breaks away at ``Pi9 Pi22``; ``Pi23 = 0`` is constant
friction ``Pi9 Pi22``; the weight ``W`` only scales the friction coefficients; scenes the peer does not
model are refused naming the group.
"""

import dataclasses
import functools
import math

import numpy as np
import pytest

import isoslide
from isoslide.peers import opensees_available, solve_opensees
from isoslide.peers import opensees_bearing_rate as br
from isoslide.scene import PhysicalScale

needs_opensees = pytest.mark.skipif(not opensees_available(),
                                    reason="openseespy does not import (pip install -e .[peers])")

S = isoslide.Scene
RATE = S(**br.EXAMPLE)
"""Friction rising with speed: breakaway ``Pi9 Pi22 = 0.15``, ``0.3`` at high speed, ``Pi23 = 20``."""
CONSTANT = dataclasses.replace(RATE, pi22=1.0, pi23=0.0)
"""The same bearing with the constant friction ``Pi9 = 0.3`` (isoslide's exact solver models it)."""
PAIRS = ((1e-5, 1e-3), (1e-6, 1e-3), (1e-7, 3e-4), (1e-8, 3e-4))
"""``(uy, dtau)``: ``uy`` ten times smaller each time, ``dtau`` at most a fifth of the contents' stick
period (``2 pi sqrt(uy / Pi2)``, 1.4e-3 at the finest)."""
TAU_MAX = RATE.pulse.tau_end + br.HORIZON


@functools.lru_cache(maxsize=None)
def _table(name: str) -> tuple:
    return tuple(br.convergence({"rate": RATE, "constant": CONSTANT}[name], PAIRS))


@functools.lru_cache(maxsize=None)
def _history(uy: float, dtau: float):
    return br.solve_opensees_bearing_rate(RATE, uy, dtau, history=True)


# ----------------------------------------------------------------------------------------------
# the model's parameters and the refusals (no OpenSees needed)
# ----------------------------------------------------------------------------------------------

def test_model_sets_the_normal_force_friction_coefficients_and_stick_stiffness_from_the_groups():
    """mu N = Pi9 at high speed and Pi9 Pi22 at breakaway, transRate = Pi23, kInit = mu_slow N / uy."""
    for scale, weight in ((None, 1.0), (PhysicalScale(a_p=3.0, T_p=1.0, M_b=1.0, g=9.80665), 9.80665 / 3.0)):
        M = br.bearing_rate_model(dataclasses.replace(RATE, scale=scale), 1e-6)
        assert M.weight == pytest.approx(weight, rel=1e-15)
        assert M.mu_fast * M.weight == pytest.approx(0.3, rel=1e-15)
        assert M.mu_slow * M.weight == pytest.approx(0.15, rel=1e-15)
        assert M.rate == 20.0 and M.k_init == pytest.approx(0.15 / 1e-6, rel=1e-15)
        assert M.kd == pytest.approx(math.pi ** 2) and M.cb == 0.0
        assert M.level(0.0) == pytest.approx(0.15) and M.level(-1e3) == pytest.approx(0.3)
        assert M.thr == 0.2 and M.d_block == 1e-6 and M.m == 0.01
    assert br.bearing_rate_model(RATE, 1e-6, stick_displacement=1e-8).d_block == 1e-8


@pytest.mark.parametrize("changes, named", [
    ({"pi11": 0.5, "pi12": 0.3, "pi13": 0.02}, "pi12"),     # flexible superstructure
    ({"pi5": 0.8, "pi6": 5.0}, "pi6"),                      # Stribeck friction of the contents
    ({"pi7": 0.1}, "pi7"),                                  # viscous contact
    ({"pi10": 0.005}, "pi10"),                              # a bilinear bearing, not a sliding one
])
def test_scenes_the_peer_does_not_model_raise_a_value_error_naming_the_group(changes, named):
    scene = S(**{**br.EXAMPLE, **changes})
    with pytest.raises(ValueError, match=named):
        br.solve_opensees_bearing_rate(scene, 1e-6, 1e-3)


def test_a_step_or_yield_displacement_out_of_range_is_refused_naming_it():
    with pytest.raises(ValueError, match=r"uy = 0.0 is out of range"):
        br.solve_opensees_bearing_rate(RATE, 0.0, 1e-3)
    with pytest.raises(ValueError, match=r"dtau = -1.0 is out of range"):
        br.solve_opensees_bearing_rate(RATE, 1e-6, -1.0)
    with pytest.raises(ValueError, match=r"uy = nan is out of range"):
        br.convergence(RATE, [(math.nan, 1e-3)])


# ----------------------------------------------------------------------------------------------
# OpenSees
# ----------------------------------------------------------------------------------------------

@needs_opensees
def test_constant_friction_is_the_existing_peers_elastic_plastic_bearing_to_round_off():
    """Pi22 = 1: flatSliderBearing + spring == solve_opensees's ElasticPP + spring at the same uy and dtau."""
    row = _table("constant")[0]
    other = solve_opensees(CONSTANT, tau_max=TAU_MAX, dtau=row.dtau, stick_displacement=row.uy).pi1
    assert row.pi1 == pytest.approx(other, rel=1e-10)


@needs_opensees
def test_constant_friction_converges_to_the_exact_answer_as_uy_and_dtau_shrink():
    """Pi22 = 1 against isoslide.solve: the error falls at every refinement, at order >= 0.45 in uy overall
    (measured 0.55: 10.6 %, 2.4 %, 0.72 %, 0.24 %) and is under 3e-3 at uy = 1e-8, dtau = 3e-4; there the
    slab's peak is within 1e-4 of the reference peer's."""
    exact = isoslide.solve(CONSTANT, rtol=1e-9, horizon=br.HORIZON).pi1
    rows = _table("constant")
    assert [(r.uy, r.dtau) for r in rows] == list(PAIRS)
    errs = [abs(r.pi1 - exact) / exact for r in rows]
    assert all(b < a / 10 ** 0.4 for a, b in zip(errs, errs[1:], strict=False)), errs
    order = np.polyfit(np.log10([r.uy for r in rows]), np.log10(errs), 1)[0]
    assert order >= 0.45, (order, errs)
    assert errs[0] > 5e-2 and errs[-1] < 3e-3
    ref = isoslide.solve(CONSTANT, method="reference", tau_max=TAU_MAX, history=True).history
    assert abs(rows[-1].slab_peak / np.max(np.abs(ref.x)) - 1.0) < 1e-4        # measured 1e-6
    text = br.format_table(rows, exact)
    assert len(text.splitlines()) == 1 + len(rows) and f"{errs[-1]:11.2e}" in text


@needs_opensees
def test_friction_rising_with_speed_converges_to_the_exact_answer_as_uy_and_dtau_shrink():
    """Pi22 = 0.5, Pi23 = 20 against isoslide.solve: the error falls at every refinement, at order >= 0.45
    in uy overall (measured 6.4 %, 0.90 %, 0.30 %, 0.16 %) and is under 3e-3 at uy = 1e-8, dtau = 3e-4."""
    exact = isoslide.solve(RATE, rtol=1e-9, horizon=br.HORIZON).pi1
    rows = _table("rate")
    errs = [abs(r.pi1 - exact) / exact for r in rows]
    assert all(b < a / 10 ** 0.25 for a, b in zip(errs, errs[1:], strict=False)), errs
    order = np.polyfit(np.log10([r.uy for r in rows]), np.log10(errs), 1)[0]
    assert order >= 0.45, (order, errs)
    assert errs[0] > 3e-2 and errs[-1] < 3e-3


@needs_opensees
def test_friction_rising_with_speed_converges_on_itself_and_differs_from_constant_friction():
    """Pi22 = 0.5, Pi23 = 20: each refinement changes Pi1 at most half as much as the one before (measured
    5.5 %, 0.59 %, 0.15 %), the last under 3e-3; the answer is far (> 10 %) from the constant Pi9's."""
    rows = _table("rate")
    p = [r.pi1 for r in rows]
    changes = [abs(b - a) / b for a, b in zip(p, p[1:], strict=False)]
    assert all(b < a / 2 for a, b in zip(changes, changes[1:], strict=False)), changes
    assert changes[-1] < 3e-3
    assert abs(p[-1] / _table("constant")[-1].pi1 - 1.0) > 0.1
    assert all(r.slab_peak > 0.04 and r.n_steps == math.ceil((TAU_MAX - RATE.pulse.tau_start) / r.dtau - 1e-9)
               for r in rows)


@needs_opensees
def test_bearing_slides_with_the_laws_friction_and_breaks_away_at_the_slow_friction():
    """While sliding |f| = Pi9 (1 - (1 - Pi22) exp(-Pi23 |x'|)) to round-off, over most of the law; while
    stuck |f| stays within 0.2 % above the breakaway Pi9 Pi22 and reaches it; the contents slide too."""
    r = _history(1e-6, 1e-3)
    h = r.history
    sliding = h.iso_phase != 0
    law = 0.3 * (1.0 - 0.5 * np.exp(-20.0 * np.abs(h.xd)))
    assert 0.05 < sliding.mean() < 0.5
    assert np.max(np.abs(np.abs(h.fh[sliding]) - law[sliding])) < 1e-12
    assert np.min(np.abs(h.fh[sliding])) < 0.16 and np.max(np.abs(h.fh[sliding])) > 0.28
    stuck = np.max(np.abs(h.fh[~sliding]))
    assert 0.15 * (1 - 1e-3) < stuck < 0.15 * 1.002
    assert np.any(h.phase != 0) and r.pi1 == pytest.approx(np.max(np.abs(h.u)), rel=1e-15)
    assert r.slab_peak == pytest.approx(np.max(np.abs(h.x)), rel=1e-15)


@needs_opensees
def test_no_rate_is_constant_friction_at_the_slow_coefficient():
    """Pi23 = 0: the existing peer's sliding bearing of strength Pi9 Pi22, to round-off."""
    slow = dataclasses.replace(RATE, pi23=0.0)
    a = br.solve_opensees_bearing_rate(slow, 1e-5, 1e-3, tau_max=6.0).pi1
    b = solve_opensees(dataclasses.replace(CONSTANT, pi9=0.15), tau_max=6.0, dtau=1e-3, stick_displacement=1e-5).pi1
    assert a == pytest.approx(b, rel=1e-10)


@needs_opensees
def test_the_weight_only_scales_the_friction_coefficients():
    """W = g / a_p of a physical scale against W = 1: the same Pi1 to round-off."""
    scaled = dataclasses.replace(RATE, scale=PhysicalScale(a_p=3.0, T_p=1.0, M_b=1.0, g=9.80665))
    a = br.solve_opensees_bearing_rate(scaled, 1e-5, 1e-3, tau_max=6.0)
    b = br.solve_opensees_bearing_rate(RATE, 1e-5, 1e-3, tau_max=6.0)
    assert a.pi1 == pytest.approx(b.pi1, rel=1e-9) and a.slab_peak == pytest.approx(b.slab_peak, rel=1e-9)
    assert a.method == "opensees_bearing_rate" and a.integrator == "Newmark" and a.tau_end == pytest.approx(6.0)
