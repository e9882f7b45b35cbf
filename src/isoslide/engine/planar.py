"""The planar kernel's inputs and outputs in the scene's terms.

:func:`excitation` turns a scene's horizontal ground motion into the excitation tuple of
:mod:`isoslide.engine.planar_kernel` (the building's parameters are
:func:`isoslide.engine.building.parameters`); :func:`floor_motion` evaluates the contents' floor's
absolute acceleration and relative velocity at the rows of a planar
:class:`~isoslide.store.history.History`; :func:`pair_grid` the ground samples of a recorded pair on
one time grid, which :mod:`isoslide.engine.planar_piecewise` propagates exactly between slides.
"""

from __future__ import annotations

import math

import numpy as np

from . import building_kernel as bk
from . import planar_kernel
from ..pulses import SAMPLED
from ..scene import Scene
from .system import assemble

__all__ = ["excitation", "floor_motion", "pair_grid"]


def excitation(scene: Scene) -> tuple:
    """The planar kernel's excitation ``(code, params, code_y, params_y, G)`` of a scene."""
    has_y = scene.pulse_y is not None
    py = scene.pulse_y if has_y else scene.pulse
    G = np.array([scene.pi14, scene.pi15, scene.pi16, math.cos(scene.angle), math.sin(scene.angle),
                  1.0 if has_y else 0.0])
    return (scene.pulse.code, scene.pulse.param_array, py.code, py.param_array, G)


def floor_motion(scene: Scene, history) -> np.ndarray:
    """The contents' floor's motion at the rows of a planar history (``solve(scene, history=True)``).

    Parameters
    ----------
    scene : Scene
        A scene that ran in the plane (``Solution.facets.contact == "plane"``).
    history : isoslide.store.history.History
        Its history: ``x, xd, u, ud`` (and ``xs, xsd``, ``fh``) with two columns (x, y).

    Returns
    -------
    ndarray, shape (rows, 4)
        The floor's absolute acceleration ``(A_x, A_y)`` (units ``a_p``) and its velocity relative
        to the ground ``(V_x, V_y)`` (units ``a_p T_p``) in the building's axes
        (:func:`isoslide.engine.planar_kernel.floor_motion`).
    """
    if history.x.ndim != 2:
        raise ValueError("history is one-dimensional; allowed: the history of a scene that ran in the plane")
    P = assemble(scene, pi8=scene.pi8, coulomb=scene.rate_independent).P
    n = int(P[bk.P_N])
    hyst = P[bk.P_KIND] == bk.KIND_BILINEAR
    rows = history.tau.size
    zeros = np.zeros((rows, 2, n))
    xs = zeros if history.xs is None else history.xs
    xsd = zeros if history.xsd is None else history.xsd
    axes = [np.column_stack([history.x[:, a], history.xd[:, a], xs[:, a, :], xsd[:, a, :]]
                            + ([history.fh[:, a]] if hyst else [])) for a in range(2)]
    iso = np.zeros(rows) if history.iso_phase is None else history.iso_phase
    table = np.column_stack([history.tau, *axes, history.u, history.ud, history.phase, iso]).astype(float)
    return planar_kernel.floor_motion(P, excitation(scene), np.ascontiguousarray(table))


def pair_grid(scene: Scene):
    """The ground of a recorded pair along the building's axes at its samples, or None.

    Returns ``(gx, gy, tau0, dtau)`` (units of a_p and T_p) when both horizontal components are
    sampled records on one time grid (the second one's samples at the first one's times after
    ``Pi16 + Pi15 tau``, as many of them), the friction is speed-independent, nothing moves
    vertically and the building is a fixed base or a linear isolator under a rigid superstructure:
    the scenes whose stick phases :mod:`isoslide.engine.planar_piecewise` propagates exactly.
    """
    px, py = scene.pulse, scene.pulse_y
    if (py is None or px.code != SAMPLED or py.code != SAMPLED or not scene.rate_independent or scene.vertical
            or scene.pi9 > 0.0 or scene.pi12 > 0.0):
        return None
    a, b = px.param_array, py.param_array
    tau0, dtau = float(a[0]), float(a[1])
    if (a.size != b.size or abs(scene.pi16 + scene.pi15 * b[0] - tau0) > 1e-12 * (1.0 + abs(tau0))
            or abs(scene.pi15 * b[1] - dtau) > 1e-12 * dtau):
        return None
    c, s = math.cos(scene.angle), math.sin(scene.angle)
    sx, sy = a[2:], scene.pi14 * b[2:]
    return (np.ascontiguousarray(c * sx - s * sy), np.ascontiguousarray(s * sx + c * sy), tau0, dtau)
