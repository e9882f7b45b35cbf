"""The floor's motion in the plane: planar PFA and PFV (the peak lengths of the floor's vectors)."""

import numpy as np
import pytest

import isoslide
from isoslide.engine.planar import floor_motion
from isoslide.studies.intensity import floor_peaks, planar_floor_peaks

ISOLATED = dict(a_p=3.0, T_p=1.0, M_b=1e6, T_b=2.5, xi_b=0.1, m_ec=2e5, mu_s=0.05, mu_k=0.05)


@pytest.mark.parametrize("kw", [{}, dict(Q_d=0.05 * 9.81e6, D_y=0.02)], ids=["linear", "bilinear"])
def test_a_floor_moving_along_a_line_has_the_1d_floor_peaks(kw):
    """An excitation along 0.6 rad, solved in the plane (``model="full"``), gives the 1-D PFA and PFV."""
    line = isoslide.Scene.from_physical(**ISOLATED, **kw, pulse="ricker")
    plane = isoslide.Scene.from_physical(**ISOLATED, **kw, pulse="ricker", angle=0.6)
    one = isoslide.solve(line, history=True, max_step=1e-3)
    two = isoslide.solve(plane, history=True, max_step=1e-3, model="full")
    assert two.facets.contact == "plane" and one.pi1 > 0.0
    pfa, pfv = planar_floor_peaks(two, plane)
    pfa_1, pfv_1 = floor_peaks(one, line)
    assert pfa == pytest.approx(pfa_1, rel=1e-5)
    assert pfv == pytest.approx(pfv_1, rel=1e-5)
    assert pfa < 0.7 * ISOLATED["a_p"]              # the isolation filters the ground motion


def test_on_a_fixed_base_the_planar_floor_peaks_are_the_ground_vectors_peaks():
    """The peaks over rows at most 1e-3 T_p apart against a dense grid: a smooth peak between rows is
    missed by at most ``|f''| h^2 / 8``, about 1e-5 of it here."""
    scene = isoslide.Scene.from_physical(a_p=3.0, T_p=1.0, M_b=1e6, T_b=0.0, xi_b=0.0, m_ec=1e3, mu_s=0.1, mu_k=0.1,
                                         pulse="ricker", pulse_y="antisymmetric_ricker", a_py=2.0, T_py=1.2, t_y=0.1)
    sol = isoslide.solve(scene, history=True, max_step=1e-3)
    pfa, pfv = planar_floor_peaks(sol, scene)
    tau = np.linspace(-3.0, 3.0, 600_001)
    gx, gy = scene.ground(tau)
    vx, vy = scene.ground_velocity(tau)
    assert pfa == pytest.approx(3.0 * np.max(np.hypot(gx, gy)), rel=2e-5)
    assert pfv == pytest.approx(3.0 * np.max(np.hypot(vx, vy)), rel=2e-5)


def test_the_ground_velocity_is_the_integral_of_the_ground_acceleration():
    scene = isoslide.Scene(pi2=0.1, pi3=0.0, pulse="ricker", pulse_y="makris_a", pi14=0.8, pi15=1.4, pi16=0.3,
                           angle=0.4)
    tau = np.linspace(-3.0, 3.0, 60_001)
    gx, gy = scene.ground(tau)
    vx, vy = scene.ground_velocity(tau)
    h = tau[1] - tau[0]
    for g, v in ((gx, vx), (gy, vy)):
        integral = np.concatenate([[0.0], np.cumsum(0.5 * (g[1:] + g[:-1]) * h)])
        np.testing.assert_allclose(v, integral, atol=1e-6)


def test_a_one_dimensional_history_is_refused():
    scene = isoslide.Scene(pi2=0.2, pi3=2.0, pulse="ricker")
    with pytest.raises(ValueError, match="one-dimensional"):
        floor_motion(scene, isoslide.solve(scene, history=True).history)
