r"""OpenSees's ``TripleFrictionPendulum`` element: quasi-static loops against the closed forms, and under a building.

The element (Dao's implementation of Fenz and Constantinou's series model) takes the bearing's
parameters in the convention of :mod:`isoslide.model.tfp`: effective radii ``L1, L2, L3``, limits
``d1, d2, d3`` and one friction model per pair of surfaces.  Internally it is three elements in series,
of radii ``2 L1``, ``L2 - L1`` and ``L3 - L1`` (friction ``mu1, mu2, mu3``), each an elastic-plastic
spring with kinematic hardening in the plane (circular yield surface) beside an elastic gap that closes
at ``2 (d1 + L1 d3/L3)``, ``d2 (1 - L1/L2)`` and ``d3 (1 - L1/L3)``; the horizontal force is the
vertical load times the series' force per unit weight.  Stick is regularised: each spring's elastic
stiffness (and each gap's) is ``3 mu1 W / uy``, so the three in series reach ``mu1 W`` at the "yield
displacement" ``uy``.

What the regularisation changes, and why the error is of order ``uy``
---------------------------------------------------------------------
Beyond yield, a spring of radius ``R`` and friction ``mu`` has deformation ``R (f - mu) + mu uy /
(3 mu1)`` at force ``f W``: the rigid-plastic law shifted by a constant.  So away from the stuck
stretches the regularised loop is the closed-form loop shifted in displacement by at most a few
``uy`` (``(mu1 + mu2 + mu3) uy / (3 mu1)`` on the backbone, and the gaps close ``O(uy)`` early), and
its force differs by the regime's stiffness times that shift: ``O(uy / L1)`` relative to ``W``.  Where
every surface sticks the closed form is vertical and the element has the finite slope ``mu1 W / uy``:
from rest it needs ``uy`` to reach ``mu1 W``, and the drop of ``2 mu1 W`` at each reversal spans
``2 uy``.  There the force at a given displacement differs by up to ``2 mu1 W`` however small ``uy``,
so :func:`loop_error` leaves these stretches out (the displacement within ``uy`` of the start and
within ``2 uy`` after each reversal) and compares the force at the same displacement everywhere else.
After a reversal the springs that still stick go on unloading elastically, so the shift of the
unloading branch reaches ``2 (mu1 + mu2 + mu3) uy / (3 mu1)``: the force error is at most about
``(mu1 + mu2 + mu3) / (3 mu1) uy / L1`` relative to ``W`` (that shift times the stiffest regime's
``W / (2 L1)``).  :func:`regularised_backbone` is the regularised series model's backbone in closed
form; OpenSees's backbone equals it to round-off through all five regimes, so the element differs
from the closed forms by its regularisation only.

The path
--------
:func:`tfp_loop_opensees` builds a two-node model (``ndm = 3``, ``ndf = 6``, as the element requires):
the bottom node fixed, the top node's rotations fixed, its vertical degree of freedom carrying the
weight ``W`` (held constant) on a stiff elastic vertical material, and its horizontal displacement
imposed along a direction at angle ``angle`` from ``x`` (single-point constraints scaled by a path
time series, one static step per value).  The path goes from rest to ``A``, down to ``-A`` and back to
``A`` in increments of at most ``increment`` with every vertex of the closed-form loop inserted, so
the regime change points are computed exactly where the closed forms have them.  Friction is
Coulomb's with the bearing's constant ``mu`` (the closed forms' friction; a bearing's velocity law
is not used).

:func:`convergence` runs the loop for a few ``uy`` (fractions of the largest radius) with the
increment shrinking with ``uy`` and tabulates the error; :func:`format_table` prints it and
``python -m isoslide.peers.opensees_tfp`` runs it for :data:`DEFAULT_BEARING`.  The error falls in
proportion to ``uy``: measured on :data:`DEFAULT_BEARING` along ``x`` and at 35 degrees, at amplitudes in
regimes I, III and V, a least-squares order of 0.97 over ``uy / max(L) = 1e-3 .. 1e-5`` (1.0 between the
two finest), the largest error ``0.73 .. 2.13 uy / L1`` and always at a vertex of the loop.  The
module imports without ``openseespy``.

Units of the loops: lengths m, forces N, angles rad.

The rigid isolated building under a pulse
-----------------------------------------
:func:`solve_opensees_tfp` puts the element under the scene isoslide solves (``scene.isolator ==
"tfp"``), in the dimensionless units of :mod:`isoslide.peers.opensees` (time ``T_p``, lengths ``a_p
T_p^2``, masses ``M_b``, forces ``M_b a_p``): a 3-D model (``ndm = 3``, ``ndf = 6``, as the element
requires), every node at the origin,

* node 1, the ground: fixed;
* node 2, the slab: mass 1 in ``X`` only; ``X`` and the vertical ``Z`` free, ``Y`` and the rotations
  fixed;
* node 4, the contents: mass ``Pi8`` (at least ``1e-6``) in ``X``; everything else fixed;
* ``TripleFrictionPendulum`` element 2 (ground to slab): the bearing of
  :func:`isoslide.scene.tfp_bearing` (radii from ``L2 + L3 = (Pi3 / (2 pi))^2``, frictions ``Pi9
  (Pi26, 1, Pi27)``, limits ``Pi28, Pi29, Pi30``, weight 1) with its weight set to ``W = g / a_p``
  (from ``scene.scale`` when the scene was built from physical units, else 1): radii ``W L_i``,
  ``frictionModel('Coulomb', i, mu_i / W)``, limits ``d_i``, the element's ``W`` parameter ``W``,
  yield displacement ``uy``, vertical material ``Elastic`` of stiffness ``W / (VERTICAL_STRAIN uy)``,
  ``kvt = 1e-3`` of it, ``minFv = 1e-3 W``, ``tol`` :data:`BUILDING_TOL`;
* ``zeroLength`` element 1 (ground to slab, ``X``), when ``Pi4 > 0``: the damper, ``Elastic`` of
  stiffness 0 and damping tangent ``c_b = 2 Pi4 (2 pi / Pi3)``;
* ``zeroLength`` element 4 (slab to contents, ``X``): ``ElasticPP`` of yield force ``Pi8 Pi2/Pi5``
  and yield displacement the contents' stick displacement (``uy`` unless given), as in
  :func:`isoslide.peers.opensees.solve_opensees`.

The weight ``-W`` is a constant load on the slab's vertical degree of freedom, applied by a static
analysis before the ground moves; that degree of freedom has no mass, so the element's axial force
stays ``W`` at every step, and the element's horizontal force is ``W`` times its force per unit
weight: the pendulum's ``W x / (W L_i) = x / L_i`` and the friction ``(mu_i / W) W = mu_i`` in units
``M_b a_p``, the scene's (``W`` only scales the coefficients; the answer does not depend on it, to
round-off).  The contents' node is joined to the slab horizontally only, so the bearing carries the
slab's weight ``M_b g`` alone, as isoslide's does: there is no mismatch of weight.  The element's
sticks are regularised by its yield displacement ``uy`` (module docstring above), the contents' by
their spring's.  Ground acceleration ``p(tau)`` of ``scene.pulse`` sampled every ``dtau`` (a ``Path``
series), ``UniformExcitation`` in ``X``, average-acceleration Newmark with Newton iterations and the
retries of :func:`isoslide.peers.opensees.solve_opensees`.  Not modelled: a flexible superstructure,
friction of the contents that depends on speed, vertical or a second horizontal ground motion (each
a ValueError naming the group).

:func:`building_convergence` runs a refinement table over ``(uy, dtau)`` pairs against the exact
answer; ``python -m isoslide.peers.opensees_tfp --building`` prints it for :data:`BUILDING_SCENES`
(regimes III, IV and V) with :data:`DEFAULT_BUILDING_PAIRS`, against the SciPy event-driven peer
(:func:`reference_target`, isoslide's answer to 1e-11; this layer does not import the solver).
Measured: the error in ``Pi1`` falls from 3-7 % at ``uy = 1e-4`` to 5e-6 .. 5e-4 at ``uy = 1e-7``,
``dtau = 1e-4``, at an observed order of about 0.7 in ``uy`` in regimes III and IV (1.3 in V), the
slab's peak at 0.7 .. 1.0; the contents' stick and the bearing's contribute alike (each alone, the
other at ``1e-8``: 4.3 %, 0.73 %, 0.16 % for the bearing's ``uy`` of 1e-4, 1e-5, 1e-6 in regime III,
1.8 %, 0.47 %, 0.065 % for the contents').  About 0.7 s per 10 000 steps.
"""

from __future__ import annotations

import argparse
import math
import os
import time
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from ..model import tfp
from ..model.tfp import TripleFrictionPendulum
from ..scene import Scene, tfp_bearing
from .opensees import (BLOCK, GROUND, SLAB, _hold_static_load, _newmark_analysis, _opensees, _step,
                       refuse_unmodelled_contents_and_motion,
                       opensees_available, opensees_model)
from .reference_tfp import TFPBuilding, run_tfp
from .result import PeerResult

__all__ = ["BUILDING_HORIZON", "BUILDING_SCENES", "BUILDING_TOL", "BuildingModel", "BuildingResult", "BuildingRow",
           "BuildingTarget", "DEFAULT_BEARING", "DEFAULT_BUILDING_PAIRS", "DEFAULT_FRACTIONS", "LoopError",
           "OpenSeesLoop", "building_convergence", "building_model", "building_order", "convergence", "cyclic_path",
           "default_amplitudes", "format_building_table", "format_table", "loop_error", "main", "observed_order",
           "reference_target", "regularised_backbone", "solve_opensees_tfp", "tfp_loop_opensees",
           "tfp_path_opensees"]

DEFAULT_BEARING = TripleFrictionPendulum(L=(0.3, 2.0, 2.5), mu=(0.02, 0.06, 0.1), d=(0.06, 0.4, 0.45), W=1000.0)
"""A bearing with five regimes of distinct stiffness (surface 3 locks first; capacity 0.964 m)."""

DEFAULT_FRACTIONS = (1e-3, 1e-4, 1e-5)
"""Yield displacements ``uy`` of the table as fractions of the bearing's largest radius."""

MAX_STEP_RATIO = 2.0
"""Largest increment allowed, in units of ``uy``: with longer steps the element's sub-stepping can
stall (measured on :data:`DEFAULT_BEARING`: ``4 uy`` does not finish in a minute, ``2 uy`` does).  At
a given ``uy`` the error does not depend on the increment up to this (each step is exact for the
piecewise-linear springs: measured the same to three digits from ``uy / 4`` to ``2 uy``)."""

_VERTICAL_STRAIN = 1e-6
"""Vertical compression of the element under ``W``, as a fraction of ``L1`` (sets the vertical stiffness)."""


class OpenSeesLoop(NamedTuple):
    """OpenSees's quasi-static path of a bearing along one direction.

    ``u`` (m): displacement of the top along the direction at each step, as imposed (the start at
    rest, 0, first; OpenSees's node follows it to round-off); ``F`` (N): the element's horizontal force on the top node along the direction (the
    bearing's restoring force, so ``F > 0`` for ``u > 0`` once sliding); ``F_normal`` (N): its
    component across the direction; ``branch[k]``: 0 on the way from rest to ``A``, 1 from ``A`` down
    to ``-A``, 2 back up to ``A``; ``vertex[k]``: True where the closed-form loop has a vertex (a
    regime change point or a reversal).
    """

    u: np.ndarray
    F: np.ndarray
    F_normal: np.ndarray
    branch: np.ndarray
    vertex: np.ndarray


def _positive(name: str, value) -> float:
    x = float(value)
    if not (math.isfinite(x) and x > 0.0):
        raise ValueError(f"{name} = {value!r} is out of range; allowed range: 0 < value < inf")
    return x


def _branches(bearing: TripleFrictionPendulum, amplitude: float) -> list:
    """The closed-form branches ``(u, F, stage)`` in travel order, vertical stretches' first vertex dropped.

    Branch 0 from rest (after the rise to ``mu1 W`` at ``u = 0``), branch 1 from ``A`` (after the
    drop) to ``-A``, branch 2 its mirror image.
    """
    up = tfp.backbone(bearing, amplitude)
    down = tfp.unloading_branch(bearing, amplitude)
    out = []
    for u, F, stage in ((up.u, up.F, up.stage), (down.u, down.F, down.stage), (-down.u, -down.F, down.stage)):
        keep = np.ones(len(u), dtype=bool)
        keep[:-1] = u[1:] != u[:-1]           # a vertex followed by a vertical stretch
        out.append((u[keep], F[keep], stage[keep]))
    return out


def cyclic_path(bearing: TripleFrictionPendulum, amplitude: float, increment: float) -> tuple:
    """Displacements from rest to ``A``, down to ``-A`` and back to ``A``, with the loop's vertices.

    Parameters
    ----------
    bearing : TripleFrictionPendulum
    amplitude : float
        ``A``, m, ``0 < A <= capacity(bearing)``.
    increment : float
        Largest step, m (> 0).

    Returns
    -------
    u : ndarray
        The displacements, m, starting at 0; each branch is a uniform grid of steps at most
        ``increment`` merged with the closed-form vertices on it.
    branch : ndarray of int
        0, 1, 2 for the three branches (the start counts to branch 0).
    vertex : ndarray of bool
        True at the closed-form vertices (the regime change points and the ends of the branches).

    Raises
    ------
    ValueError
        When ``A`` is not positive or exceeds the capacity, or ``increment`` is not positive.
    """
    A = float(amplitude)
    h = _positive("increment", increment)
    branches = _branches(bearing, A)                  # checks A
    us, bs, vs = [np.zeros(1)], [np.zeros(1, dtype=int)], [np.zeros(1, dtype=bool)]
    for k, (start, end) in enumerate(((0.0, A), (A, -A), (-A, A))):
        n = max(1, math.ceil(abs(end - start) / h))
        grid = np.linspace(start, end, n + 1)[1:]
        corners = branches[k][0]
        tiny = 1e-12 * A
        corners = np.where(np.abs(corners - end) <= tiny, end, corners)    # the end, to round-off
        corners = corners[(corners - start) * np.sign(end - start) > tiny]
        u = np.union1d(grid, corners)
        u = u if end > start else u[::-1]
        us.append(u)
        bs.append(np.full(len(u), k))
        vs.append(np.isin(u, corners))
    return np.concatenate(us), np.concatenate(bs), np.concatenate(vs)


def tfp_path_opensees(bearing: TripleFrictionPendulum, path, uy: float, angle: float = 0.0,
                      tol: float = 1e-6) -> tuple:
    """OpenSees's ``TripleFrictionPendulum`` element driven quasi-statically through ``path``.

    The model (module docstring): node 1 fixed, node 2 with its rotations fixed, the weight ``W`` on
    its vertical degree of freedom, its horizontal displacement imposed as ``path[k] (cos angle,
    sin angle)`` at step ``k``; ``element('TripleFrictionPendulum', 1, 1, 2, 1, 2, 3, 1, 2, 2, 2, L1,
    L2, L3, d1, d2, d3, W, uy, kvt, minFv, tol)`` with ``frictionModel('Coulomb', i, mu_i)``.

    Parameters
    ----------
    bearing : TripleFrictionPendulum
        Its constant friction ``mu`` is used.
    path : array of float
        Displacements along the direction, m, ``path[0] = 0`` (the start at rest).
    uy : float
        The element's yield displacement, m (> 0).
    angle : float
        Direction of the path from the ``x`` axis in the horizontal plane, rad.
    tol : float
        The element's relative tolerance on its displacement increment.

    Returns
    -------
    u, F, F_normal : ndarray
        Displacement (m) and force along the direction and force across it (N) at every step,
        ``u[0] = F[0] = 0``.

    Raises
    ------
    ImportError
        When ``openseespy`` does not import (``pip install -e .[peers]``).
    ValueError
        When ``uy`` is not positive, ``path`` does not start at 0, or a step exceeds
        ``MAX_STEP_RATIO uy``.
    RuntimeError
        When OpenSees fails to converge at a step (naming it).
    """
    uy = _positive("uy", uy)
    path = np.asarray(path, dtype=float)
    if path.ndim != 1 or len(path) < 2 or path[0] != 0.0 or not np.all(np.isfinite(path)):
        raise ValueError("path must be a finite 1-D array of at least two displacements starting at 0.0")
    step = float(np.max(np.abs(np.diff(path))))
    if step > MAX_STEP_RATIO * uy:
        raise ValueError(f"a step of {step!r} m exceeds {MAX_STEP_RATIO:g} uy = {MAX_STEP_RATIO * uy!r} m; "
                         "allowed: steps <= MAX_STEP_RATIO uy")
    if not opensees_available():
        raise ImportError("openseespy does not import: pip install -e .[peers]")
    ops = _opensees()
    (L1, L2, L3), (d1, d2, d3), W = bearing.L, bearing.d, bearing.W
    c, s = math.cos(angle), math.sin(angle)
    kv = W / (_VERTICAL_STRAIN * L1)
    ops.wipe()
    ops.logFile(os.devnull, "-noEcho")
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    ops.node(1, 0.0, 0.0, 0.0)
    ops.node(2, 0.0, 0.0, 0.0)
    ops.fix(1, 1, 1, 1, 1, 1, 1)
    ops.fix(2, 0, 0, 0, 1, 1, 1)
    ops.uniaxialMaterial("Elastic", 1, kv)                 # vertical
    ops.uniaxialMaterial("Elastic", 2, W * L1)             # rotations (fixed)
    for i, mu in enumerate(bearing.mu, start=1):
        ops.frictionModel("Coulomb", i, mu)
    ops.element("TripleFrictionPendulum", 1, 1, 2, 1, 2, 3, 1, 2, 2, 2, L1, L2, L3, d1, d2, d3, W, uy,
                1e-3 * kv, 1e-3 * W, tol)
    ops.timeSeries("Constant", 1)
    ops.pattern("Plain", 1, 1)
    ops.load(2, 0.0, 0.0, -W, 0.0, 0.0, 0.0)
    ops.timeSeries("Path", 2, "-dt", 1.0, "-values", *path.tolist(), path[-1])   # held past the end
    ops.pattern("Plain", 2, 2)
    ops.sp(2, 1, c)
    ops.sp(2, 2, s)
    ops.constraints("Transformation")
    ops.numberer("Plain")
    ops.system("FullGeneral")
    ops.test("NormDispIncr", 1e-8 * uy, 25)
    ops.algorithm("Newton")
    ops.integrator("LoadControl", 1.0)
    ops.analysis("Static")
    n = len(path)
    u, F, Fn = np.zeros(n), np.zeros(n), np.zeros(n)
    try:
        for k in range(1, n):
            if ops.analyze(1) != 0:
                raise RuntimeError(f"OpenSees did not converge at step {k} (u = {path[k]!r} m, uy = {uy!r} m)")
            ux, uy_ = ops.nodeDisp(2, 1), ops.nodeDisp(2, 2)
            r = ops.eleResponse(1, "force")
            u[k] = c * ux + s * uy_
            F[k] = c * r[6] + s * r[7]
            Fn[k] = -s * r[6] + c * r[7]
    finally:
        ops.wipe()
    return u, F, Fn


def tfp_loop_opensees(bearing: TripleFrictionPendulum, amplitude: float, uy: float,
                      steps_per_uy: float = 1.0, angle: float = 0.0) -> OpenSeesLoop:
    """OpenSees's loop from rest of amplitude ``A`` along the direction ``angle``.

    Parameters
    ----------
    bearing : TripleFrictionPendulum
    amplitude : float
        ``A``, m, ``0 < A <= capacity(bearing)``.
    uy : float
        The element's yield displacement, m (> 0).
    steps_per_uy : float
        Steps per ``uy`` of travel (the increment is ``uy / steps_per_uy``; at least
        ``1 / MAX_STEP_RATIO``).
    angle : float
        Direction from the ``x`` axis, rad.

    Returns
    -------
    OpenSeesLoop

    Raises
    ------
    ImportError, ValueError, RuntimeError
        As :func:`tfp_path_opensees` and :func:`cyclic_path`.
    """
    uy = _positive("uy", uy)
    steps = _positive("steps_per_uy", steps_per_uy)
    path, branch, vertex = cyclic_path(bearing, amplitude, uy / steps)
    u, F, Fn = tfp_path_opensees(bearing, path, uy, angle)
    if np.max(np.abs(u - path)) > 1e-9 * max(float(amplitude), uy):
        raise RuntimeError("OpenSees's displacement departs from the imposed path")
    return OpenSeesLoop(path, F, Fn, branch, vertex)


def regularised_backbone(bearing: TripleFrictionPendulum, F, uy: float):
    """Displacement on first loading of the element's regularised series model at force ``F``, m.

    The three springs of the module docstring in series, each with elastic stiffness ``E = 3 mu1 /
    uy`` (per unit weight), yield force ``mu_k``, post-yield tangent ``1 / R_k`` and an elastic gap of
    stiffness ``E`` that closes at deformation ``g_k``: a spring's deformation is ``f / E`` up to
    ``f = mu_k``, ``R_k (f - mu_k) + mu_k / E`` beyond, and ``g_k + (f - f_k) / (E + 1 / R_k)`` once
    its gap has closed at ``f_k = mu_k + (g_k - mu_k / E) / R_k``.  As ``uy -> 0`` it is the
    closed-form backbone (:func:`isoslide.model.tfp.backbone`).

    Parameters
    ----------
    bearing : TripleFrictionPendulum
        With ``L2 > L1`` and ``L3 > L1`` (:meth:`~isoslide.model.tfp.TripleFrictionPendulum.series_elements`).
    F : float or array
        Force, N, ``>= 0``.
    uy : float
        The element's yield displacement, m (> 0).

    Returns
    -------
    float or ndarray
        The displacement, m.
    """
    uy = _positive("uy", uy)
    (L1, L2, L3), (d1, d2, d3), mus = bearing.L, bearing.d, bearing.mu
    f = np.asarray(F, dtype=float) / bearing.W
    E = 3.0 * mus[0] / uy
    radii = (2.0 * L1, L2 - L1, L3 - L1)
    gaps = (2.0 * (d1 + L1 * d3 / L3), d2 * (1.0 - L1 / L2), d3 * (1.0 - L1 / L3))
    u = np.zeros_like(f)
    for R, mu, g in zip(radii, mus, gaps, strict=True):
        fk = mu + (g - mu / E) / R
        spring = np.where(f <= mu, f / E, R * (f - mu) + mu / E)
        u = u + np.where(f <= fk, spring, g + (f - fk) / (E + 1.0 / R))
    return float(u) if np.ndim(F) == 0 else u


class LoopError(NamedTuple):
    """OpenSees's loop against the closed form, forces relative to ``W``.

    ``uy`` and ``increment`` (m), ``amplitude`` (m), ``angle`` (rad), ``peak_stage`` (the regime at
    ``A``); ``max_error``: largest ``|F - F_closed| / W`` at the same displacement outside the stuck
    stretches; ``vertex_error``: the same at the closed form's vertices (regime change points and
    reversals); ``stage_error[k]``: the largest in regime ``k + 1`` (nan where the loop has no point
    in it); ``normal_error``: largest ``|F_normal| / W``; ``steps``; ``seconds`` (wall-clock time of
    OpenSees's run).
    """

    uy: float
    increment: float
    amplitude: float
    angle: float
    peak_stage: int
    max_error: float
    vertex_error: float
    stage_error: tuple
    normal_error: float
    steps: int
    seconds: float


def _closed_on_branches(bearing, amplitude, u, branch) -> tuple:
    """Closed-form force and regime at each point of a path on its branch."""
    Fc = np.empty(len(u))
    stage = np.zeros(len(u), dtype=int)
    for k, (bu, bF, bs) in enumerate(_branches(bearing, amplitude)):
        on = branch == k
        sign = 1.0 if k != 1 else -1.0                 # travel coordinate increases along the branch
        t, x = sign * bu, sign * u[on]
        Fc[on] = np.interp(x, t, bF)
        stage[on] = bs[np.searchsorted(t, x, side="left").clip(1, len(t) - 1)]
    start = branch == 0
    Fc[start & (u == 0.0)] = 0.0
    return Fc, stage


def loop_error(bearing: TripleFrictionPendulum, amplitude: float, loop: OpenSeesLoop, uy: float) -> tuple:
    """The force errors of an OpenSees loop against the closed form (relative to ``W``).

    Points within the regularised stuck stretches are left out (module docstring): ``u < uy`` on
    the way from rest, ``u > A - 2 uy`` on the way down, ``u < -A + 2 uy`` on the way up.

    Returns
    -------
    max_error, vertex_error : float
        Largest ``|F - F_closed| / W`` over the points compared, and over those at the vertices.
    stage_error : tuple of float
        Largest error in each regime I..V (nan where no point is in it).
    normal_error : float
        Largest ``|F_normal| / W``.
    """
    A, W = float(amplitude), bearing.W
    Fc, stage = _closed_on_branches(bearing, A, loop.u, loop.branch)
    u, b = loop.u, loop.branch
    scale = 1e-9 * uy
    stuck = (((b == 0) & (u < uy - scale)) | ((b == 1) & (u > A - 2.0 * uy + scale))
             | ((b == 2) & (u < -A + 2.0 * uy - scale)))
    err = np.abs(loop.F - Fc) / W
    use = ~stuck
    max_error = float(err[use].max())
    vertex_error = float(err[use & loop.vertex].max()) if np.any(use & loop.vertex) else math.nan
    stage_error = tuple(float(err[use & (stage == k)].max()) if np.any(use & (stage == k)) else math.nan
                        for k in tfp.STAGES)
    return max_error, vertex_error, stage_error, float(np.abs(loop.F_normal).max() / W)


def default_amplitudes(bearing: TripleFrictionPendulum) -> dict:
    """An amplitude in the middle of each regime of positive length, keyed by its Roman numeral (m)."""
    u = tfp.regime_boundaries(bearing).u
    return {tfp.STAGE_NAMES[k + 1]: 0.5 * (u[k] + u[k + 1]) for k in range(5) if u[k + 1] > u[k]}


def convergence(bearing: TripleFrictionPendulum = DEFAULT_BEARING, amplitudes=None, fractions=DEFAULT_FRACTIONS,
                steps_per_uy: float = 1.0, angle: float = 0.0) -> list:
    """OpenSees's loops at shrinking ``uy`` against the closed form.

    Parameters
    ----------
    bearing : TripleFrictionPendulum
    amplitudes : sequence of float or None
        Amplitudes ``A`` (m); None: the middle of regimes I, III and V.
    fractions : sequence of float
        ``uy`` as fractions of the bearing's largest radius.
    steps_per_uy : float
        Steps per ``uy`` of travel: the increment shrinks with ``uy``.
    angle : float
        Direction of the loops from ``x``, rad.

    Returns
    -------
    list of LoopError
        One per amplitude and ``uy``, amplitude by amplitude.
    """
    if amplitudes is None:
        mid = default_amplitudes(bearing)
        amplitudes = [mid[k] for k in ("I", "III", "V") if k in mid]
    rows = []
    for A in amplitudes:
        peak = tfp.peak_regime(bearing, A)
        for frac in fractions:
            uy = _positive("fraction", frac) * max(bearing.L)
            t0 = time.perf_counter()
            loop = tfp_loop_opensees(bearing, A, uy, steps_per_uy, angle)
            seconds = time.perf_counter() - t0
            max_e, vert_e, stage_e, normal_e = loop_error(bearing, A, loop, uy)
            rows.append(LoopError(uy, uy / steps_per_uy, float(A), float(angle), peak, max_e, vert_e, stage_e,
                                  normal_e, len(loop.u) - 1, seconds))
    return rows


def observed_order(rows) -> float:
    """Least-squares slope of ``log max_error`` against ``log uy`` over ``rows`` (one amplitude)."""
    x = np.log([r.uy for r in rows])
    y = np.log([r.max_error for r in rows])
    return float(np.polyfit(x, y, 1)[0])


def format_table(rows, bearing: TripleFrictionPendulum | None = None, target=None) -> str:
    """The table as text: per amplitude a heading, a line per ``uy``, and the observed order.

    Columns: ``uy`` and the increment (m), ``uy / L1``, the largest ``|F - F_closed| / W`` over the
    loop, at the vertices and in each regime I..V (``-`` where the loop does not reach it), the
    largest ``|F_normal| / W``, steps and seconds.  Rows of the building under a pulse
    (:class:`BuildingRow`) go to :func:`format_building_table` with ``target``.
    """
    if rows and isinstance(rows[0], BuildingRow):
        return format_building_table(rows, target)
    lines = []
    if bearing is not None:
        lines.append(f"bearing: L = {bearing.L} m, mu = {bearing.mu}, d = {bearing.d} m, W = {bearing.W:g} N; "
                     f"capacity {tfp.capacity(bearing):.4g} m")
    groups = {}
    for r in rows:
        groups.setdefault((r.amplitude, r.angle), []).append(r)
    L1 = bearing.L[0] if bearing is not None else None
    for (A, angle), group in groups.items():
        if lines:
            lines.append("")
        lines.append(f"A = {A:.4g} m (peak in regime {tfp.STAGE_NAMES[group[0].peak_stage]}), "
                     f"direction {math.degrees(angle):g} deg from x")
        lines.append(f"{'uy':>9} {'increment':>9} {'uy/L1':>9} {'max err':>9} {'vertices':>9} "
                     + " ".join(f"{tfp.STAGE_NAMES[k]:>9}" for k in tfp.STAGES)
                     + f" {'normal':>9} {'steps':>7} {'time':>7}")
        for r in group:
            ratio = f"{r.uy / L1:9.2e}" if L1 else f"{'':>9}"
            stages = " ".join(f"{e:9.2e}" if math.isfinite(e) else f"{'-':>9}" for e in r.stage_error)
            lines.append(f"{r.uy:9.2e} {r.increment:9.2e} {ratio} {r.max_error:9.2e} {r.vertex_error:9.2e} "
                         f"{stages} {r.normal_error:9.1e} {r.steps:7d} {r.seconds:6.2f}s")
        if len(group) > 1:
            lines.append(f"observed order in uy: {observed_order(group):.2f}")
    return "\n".join(lines)


# --- the rigid isolated building on the element, under a pulse ------------------------------------

BUILDING_HORIZON = 10.0
"""Default run after the pulse ends, units ``T_p`` (as :mod:`isoslide.peers.opensees_bearing_rate`)."""

BUILDING_TOL = 1e-6
"""The element's relative tolerance on its displacement increment in the building's runs.  Measured
on :data:`BUILDING_SCENES` ``"III"`` at ``uy = 1e-5``, ``dtau = 1e-3``: ``Pi1`` is the same to 1e-11
at ``1e-6`` and ``1e-8``, but ``1e-8`` has Newton steps retried and ``1e-10`` retries 270 steps and
runs 190 times longer (the element's own iterations stop converging)."""

VERTICAL_STRAIN = 1e-3
"""The element's vertical compression under ``W`` as a fraction of ``uy`` (sets its vertical stiffness)."""

DEFAULT_BUILDING_PAIRS = ((1e-4, 1e-3), (1e-5, 1e-3), (1e-6, 3e-4), (1e-7, 1e-4))
"""``(uy, dtau)`` pairs of the building's refinement table (units ``a_p T_p^2`` and ``T_p``): ``uy``
ten times smaller each time, ``dtau`` shrinking with it.  ``uy`` is the element's yield displacement
and the contents' stick displacement."""

_BASE = dict(pi2=0.3, pi3=2.0, pi4=0.0, pi8=1e-3, pi9=0.05, pi24=0.1, pi25=0.5, pi26=0.5, pi27=2.0, pi28=0.05,
             pi29=0.1, pi30=0.2)
BUILDING_SCENES = {
    "III": _BASE,
    "IV": {**_BASE, "pi28": 0.08, "pi29": 0.01, "pi30": 0.06},
    "V": {**_BASE, "pi2": 0.4, "pi28": 0.08, "pi29": 0.01, "pi30": 0.06, "pulse": "rectangular"},
}
"""Scenes of the building's table (keyword arguments of :class:`isoslide.Scene`), keyed by the regime
the bearing reaches: a triple pendulum with ``L1 = 0.1 (L2 + L3)``, ``L2 = L3``, ``mu1 : mu2 : mu3 =
0.5 : 1 : 2``, ``Pi9 = 0.05``, ``T_3 = 2 T_p`` and contents of ``Pi8 = 1e-3``; under the Ricker pulse
(regime III), with small limits (the outer restrainers engage: IV), and those under the rectangular
pulse with ``Pi2 = 0.4`` (both outer surfaces at their restrainers: V)."""

BEARING, DAMPER, CONTENTS = 2, 1, 4
"""Element tags: the ``TripleFrictionPendulum``, the viscous damper, the contents' spring."""


@dataclass(frozen=True)
class BuildingModel:
    """The parameters of the OpenSees model of a scene on a triple friction pendulum (units of the module docstring).

    Attributes
    ----------
    bearing : TripleFrictionPendulum
        The element's bearing: radii ``W L_i``, limits ``d_i``, frictions ``mu_i / W`` and the weight
        ``W`` (``L_i, mu_i`` those of :func:`isoslide.scene.tfp_bearing`, whose weight is 1).
    m : float
        Contents' mass ``Pi8`` (at least ``1e-6``).
    cb : float
        The damper ``2 Pi4 (2 pi / Pi3)`` (units ``M_b / T_p``; 0: none).
    uy : float
        The element's yield displacement (units ``a_p T_p^2``).
    thr, d_block : float
        Contents' friction level ``Pi2 / Pi5`` (units ``a_p``) and stick displacement (units
        ``a_p T_p^2``).
    """

    bearing: TripleFrictionPendulum
    m: float
    cb: float
    uy: float
    thr: float
    d_block: float

    @property
    def weight(self) -> float:
        """``W = g / a_p``, the element's vertical load (units ``M_b a_p``)."""
        return self.bearing.W


def _check_building_scene(scene: Scene) -> None:
    """ValueError naming the first group of a scene the building peer does not model."""
    if scene.isolator != "tfp" or scene.pi3 == 0.0:
        raise ValueError(f"pi24 = {scene.pi24!r}, pi9 = {scene.pi9!r}, pi10 = {scene.pi10!r}, pi3 = {scene.pi3!r} "
                         "is not a triple friction pendulum; allowed: pi24 > 0 with pi9 > 0, pi10 = 0, pi3 > 0")
    if scene.pi12 > 0.0:
        raise ValueError(f"pi12 = {scene.pi12!r} (a flexible superstructure) is not modelled by the OpenSees "
                         "triple pendulum peer; allowed: pi12 = 0 (rigid superstructure)")
    refuse_unmodelled_contents_and_motion(scene, "OpenSees triple pendulum peer", "constant vertical load")


def building_model(scene: Scene, uy: float, stick_displacement: float | None = None) -> BuildingModel:
    """The parameters of the OpenSees model of a scene on a triple friction pendulum (module docstring).

    Parameters
    ----------
    scene : Scene
        A rigid superstructure (``Pi12 = 0``) on a triple friction pendulum (``scene.isolator ==
        "tfp"``), with or without a damper ``Pi4``, contents with Coulomb friction, the main pulse
        alone.  Other scenes raise a ValueError naming the group.
    uy : float
        The element's yield displacement, units ``a_p T_p^2`` (> 0).
    stick_displacement : float or None
        The contents' spring's yield displacement, units ``a_p T_p^2``; None: ``uy``.

    Returns
    -------
    BuildingModel
    """
    _check_building_scene(scene)
    uy = _positive("uy", uy)
    d = uy if stick_displacement is None else _positive("stick_displacement", stick_displacement)
    base = opensees_model(scene, stick_displacement=d)        # the contents and the damper
    W = scene.scale.g / scene.scale.a_p if scene.scale is not None else 1.0
    b = tfp_bearing(scene)
    bearing = TripleFrictionPendulum(L=tuple(W * x for x in b.L), mu=tuple(x / W for x in b.mu), d=b.d, W=W)
    return BuildingModel(bearing=bearing, m=base.m, cb=base.cb, uy=uy, thr=base.thr, d_block=base.d_block)


def _build_building(ops, M: BuildingModel, tol: float) -> None:
    """Nodes, materials, elements and the static weight on the bearing (the domain's time then 0)."""
    (L1, L2, L3), (d1, d2, d3), W = M.bearing.L, M.bearing.d, M.weight
    kv = W / (VERTICAL_STRAIN * M.uy)
    ops.wipe()
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    for node in (GROUND, SLAB, BLOCK):
        ops.node(node, 0.0, 0.0, 0.0)
    ops.fix(GROUND, 1, 1, 1, 1, 1, 1)
    ops.fix(SLAB, 0, 1, 0, 1, 1, 1)                  # X and the (massless) vertical Z free
    ops.fix(BLOCK, 0, 1, 1, 1, 1, 1)
    ops.mass(SLAB, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    ops.mass(BLOCK, M.m, 0.0, 0.0, 0.0, 0.0, 0.0)
    ops.uniaxialMaterial("Elastic", 1, kv)          # vertical: carries N = W
    ops.uniaxialMaterial("Elastic", 2, W * L1)      # rotations (fixed)
    for i, mu in enumerate(M.bearing.mu, start=1):
        ops.frictionModel("Coulomb", i, mu)
    ops.element("TripleFrictionPendulum", BEARING, GROUND, SLAB, 1, 2, 3, 1, 2, 2, 2, L1, L2, L3, d1, d2, d3, W,
                M.uy, 1e-3 * kv, 1e-3 * W, tol)
    if M.cb > 0.0:
        ops.uniaxialMaterial("Elastic", 3, 0.0, M.cb)                # c_b x'
        ops.element("zeroLength", DAMPER, GROUND, SLAB, "-mat", 3, "-dir", 1)
    ops.uniaxialMaterial("ElasticPP", 4, M.m * M.thr / M.d_block, M.d_block)   # contents, yield m thr
    ops.element("zeroLength", CONTENTS, SLAB, BLOCK, "-mat", 4, "-dir", 1)
    ops.timeSeries("Constant", 1)
    ops.pattern("Plain", 1, 1)
    ops.load(SLAB, 0.0, 0.0, -W, 0.0, 0.0, 0.0)
    _hold_static_load(ops, "the bearing's weight")


@dataclass(frozen=True)
class BuildingResult(PeerResult):
    """A :class:`PeerResult` with the slab's peak displacement ``slab_peak`` (max ``|x|``, units ``a_p T_p^2``)."""

    slab_peak: float = math.nan


def _run_length(scene: Scene, dtau: float, tau_max: float | None) -> int:
    """Newmark steps of ``dtau`` from ``pulse.tau_start`` to ``tau_max`` (default ``tau_end + BUILDING_HORIZON``)."""
    pulse = scene.pulse
    end = pulse.tau_end + BUILDING_HORIZON if tau_max is None else float(tau_max)
    n = int(math.ceil((end - pulse.tau_start) / dtau - 1e-9)) if math.isfinite(end) else 0
    if n < 1:
        raise ValueError(f"tau_max = {tau_max!r} is out of range; allowed range: > pulse.tau_start "
                         f"= {pulse.tau_start!r}")
    return n


def solve_opensees_tfp(scene: Scene, uy: float, dtau: float, tau_max: float | None = None,
                       stick_displacement: float | None = None, tol: float = BUILDING_TOL) -> BuildingResult:
    """Peak sliding of the contents on a rigid building on OpenSees's ``TripleFrictionPendulum`` element.

    See the module docstring for the model.  Everything starts at rest at ``pulse.tau_start``; the
    run goes to ``tau_max`` in Newmark steps of ``dtau``.

    Parameters
    ----------
    scene : Scene
        As :func:`building_model`.
    uy : float
        The element's yield displacement (units ``a_p T_p^2``, > 0), and the contents' stick
        displacement unless ``stick_displacement`` is given.
    dtau : float
        Newmark time step, units ``T_p`` (> 0).
    tau_max : float or None
        End time, units ``T_p``; default ``pulse.tau_end + BUILDING_HORIZON``.
    stick_displacement : float or None
        The contents' stick displacement (units ``a_p T_p^2``); None: ``uy``.
    tol : float
        The element's relative tolerance on its displacement increment (> 0; see :data:`BUILDING_TOL`).

    Returns
    -------
    BuildingResult
        ``method = "opensees_tfp"``, ``pi1`` the peak ``|u|``, ``slab_peak`` the peak ``|x|``,
        ``tau_peak`` (of ``pi1``), ``pi1_residual`` the final ``u``, ``n_steps``, ``stiffness``
        the contents' ``K = (Pi2/Pi5) / stick displacement``, ``integrator = "Newmark"``,
        ``settled`` False (the run goes to ``tau_max``).

    Raises
    ------
    ImportError
        When ``openseespy`` does not import (``pip install -e .[peers]``).
    ValueError
        For a scene the peer does not model (naming the group) or ``uy``, ``dtau``, ``tol`` or
        ``tau_max`` out of range.
    RuntimeError
        When OpenSees fails at a step (after the retries of :func:`isoslide.peers.opensees._step`).
    """
    M = building_model(scene, uy, stick_displacement)
    dtau = _positive("dtau", dtau)
    tol = _positive("tol", tol)
    n = _run_length(scene, dtau, tau_max)
    if not opensees_available():
        raise ImportError("openseespy does not import: pip install -e .[peers]")
    pulse = scene.pulse
    tt = pulse.tau_start + dtau * np.arange(n + 1)
    ops = _opensees()
    ops.logFile(os.devnull, "-noEcho")     # the element's banner and the retries of _step; a failure raises
    _build_building(ops, M, tol)
    ops.timeSeries("Path", 2, "-dt", dtau, "-values", *np.asarray(pulse.accel(tt), dtype=float).tolist())
    ops.pattern("UniformExcitation", 2, 1, "-accel", 2)
    _newmark_analysis(ops)
    umax = xmax = u = 0.0
    tau_peak = float(pulse.tau_start)
    try:
        for i in range(n):
            if not _step(ops, dtau):
                raise RuntimeError(f"OpenSees analysis failed at tau = {tt[i]:.6g} (dtau = {dtau!r}, uy = {M.uy!r})")
            x = ops.nodeDisp(SLAB, 1)
            u = ops.nodeDisp(BLOCK, 1) - x
            xmax = max(xmax, abs(x))
            if abs(u) > umax:
                umax, tau_peak = abs(u), float(tt[i + 1])
    finally:
        ops.wipe()
    return BuildingResult(method="opensees_tfp", pi1=umax, pi1_residual=float(u), tau_peak=tau_peak, settled=False,
                          tau_end=float(tt[-1]), n_steps=n, stiffness=M.thr / M.d_block, integrator="Newmark",
                          slab_peak=xmax)


class BuildingTarget(NamedTuple):
    """The exact answer a building's table is measured against: ``pi1`` and the slab's peak ``slab_peak``."""

    pi1: float
    slab_peak: float


def reference_target(scene: Scene, tau_max: float | None = None) -> BuildingTarget:
    """The SciPy event-driven peer's answer on a scene (:mod:`isoslide.peers.reference_tfp`).

    It models the same building exactly (true stick on every surface and of the contents) and agrees
    with :func:`isoslide.solve` to about 1e-11 in ``Pi1`` (``tests/test_tfp_engine.py``); its run
    ends at ``tau_max`` (default ``pulse.tau_end + BUILDING_HORIZON``) or where it settles.
    """
    _check_building_scene(scene)
    b = tfp_bearing(scene)
    run = run_tfp(TFPBuilding(L=b.L, mu=b.mu, d=b.d, gravity=1.0, pi2=scene.static_level, pi5=1.0,
                              pi8=scene.pi8, pulse=scene.pulse, damping=opensees_model(scene).cb,
                              contents_weight=False),
                  tau_max=scene.pulse.tau_end + BUILDING_HORIZON if tau_max is None else float(tau_max))
    return BuildingTarget(run.pi1, run.x_peak)


class BuildingRow(NamedTuple):
    """One run of the building's refinement table.

    ``uy`` (the element's yield displacement and the contents' stick displacement, units ``a_p
    T_p^2``), ``dtau`` (units ``T_p``), ``pi1`` and its relative ``error`` against the target, the
    slab's peak ``slab_peak`` and its relative ``slab_error``, ``n_steps`` and ``seconds``
    (wall-clock time of the run).
    """

    uy: float
    dtau: float
    pi1: float
    error: float
    slab_peak: float
    slab_error: float
    n_steps: int
    seconds: float


def building_convergence(scene: Scene, pairs=DEFAULT_BUILDING_PAIRS, target: BuildingTarget | None = None,
                         tau_max: float | None = None) -> list:
    """The building peer over ``(uy, dtau)`` pairs against the exact answer: one :class:`BuildingRow` per pair.

    Parameters
    ----------
    scene : Scene
        As :func:`solve_opensees_tfp`.
    pairs : sequence of (float, float)
        ``(uy, dtau)``, units ``a_p T_p^2`` and ``T_p``, each > 0; ``uy`` is also the contents'
        stick displacement.
    target : BuildingTarget or None
        The exact ``Pi1`` and slab peak over the same time (``isoslide.solve(scene, rtol=1e-10)``'s);
        None: :func:`reference_target`.
    tau_max : float or None
        End time of every run (default ``pulse.tau_end + BUILDING_HORIZON``).

    Returns
    -------
    list of BuildingRow
        In the order of ``pairs``.
    """
    checked = [(_positive("uy", uy), _positive("dtau", dtau)) for uy, dtau in pairs]
    if not checked:
        raise ValueError("pairs = () is empty; allowed: at least one (uy, dtau) pair")
    target = reference_target(scene, tau_max) if target is None else BuildingTarget(*target)
    rows = []
    for uy, dtau in checked:
        t0 = time.perf_counter()
        r = solve_opensees_tfp(scene, uy, dtau, tau_max)
        rows.append(BuildingRow(uy, dtau, r.pi1, abs(r.pi1 - target.pi1) / target.pi1, r.slab_peak,
                                abs(r.slab_peak - target.slab_peak) / target.slab_peak, r.n_steps,
                                time.perf_counter() - t0))
    return rows


def building_order(rows, field: str = "error") -> float:
    """Least-squares slope of ``log`` of a row's ``field`` (``"error"`` or ``"slab_error"``) against ``log uy``."""
    return float(np.polyfit(np.log([r.uy for r in rows]), np.log([getattr(r, field) for r in rows]), 1)[0])


def format_building_table(rows, target: BuildingTarget | None = None) -> str:
    """The building's table as text: a heading, a line per run, the observed orders in ``uy``.

    Columns: ``uy``, ``dtau``, ``Pi1`` and its relative error, the slab's peak and its relative
    error, steps and seconds; a first line with the target when it is given.
    """
    lines = []
    if target is not None:
        lines.append(f"exact: Pi1 = {target.pi1:.10g}, slab peak = {target.slab_peak:.10g}")
    lines.append(f"{'uy':>9} {'dtau':>9} {'Pi1':>12} {'rel. error':>11} {'slab peak':>11} {'slab error':>11} "
                 f"{'steps':>8} {'time':>7}")
    for r in rows:
        lines.append(f"{r.uy:9.1e} {r.dtau:9.1e} {r.pi1:12.8f} {r.error:11.2e} {r.slab_peak:11.7f} "
                     f"{r.slab_error:11.2e} {r.n_steps:8d} {r.seconds:6.2f}s")
    if len(rows) > 1:
        lines.append(f"observed order in uy: Pi1 {building_order(rows):.2f}, slab peak "
                     f"{building_order(rows, 'slab_error'):.2f}")
    return "\n".join(lines)


def main(argv=None) -> int:
    """``python -m isoslide.peers.opensees_tfp [--fractions F ...] [--angle DEG] [--steps-per-uy N]``.

    With ``--building [REGIME ...] [--pairs UY DTAU ...]`` the rigid building under a pulse instead:
    the tables of :func:`building_convergence` on :data:`BUILDING_SCENES` (all three by default).
    """
    ap = argparse.ArgumentParser(prog="python -m isoslide.peers.opensees_tfp", description=__doc__.split("\n")[0])
    ap.add_argument("--fractions", nargs="+", type=float, default=list(DEFAULT_FRACTIONS),
                    help="uy as fractions of the largest radius (default: %(default)s)")
    ap.add_argument("--angle", type=float, default=0.0, help="direction from x, degrees (default: 0)")
    ap.add_argument("--steps-per-uy", type=float, default=1.0, help="steps per uy of travel (default: 1)")
    ap.add_argument("--building", nargs="*", choices=list(BUILDING_SCENES), metavar="REGIME",
                    help="the rigid building under a pulse instead of the loops: scenes of BUILDING_SCENES by "
                         f"the regime they reach, {' '.join(BUILDING_SCENES)} (default: all)")
    ap.add_argument("--pairs", nargs="+", type=float, default=[v for p in DEFAULT_BUILDING_PAIRS for v in p],
                    help="with --building: uy and dtau, pair after pair (default: %(default)s)")
    args = ap.parse_args(argv)
    if len(args.pairs) % 2:
        ap.error("--pairs takes uy and dtau in pairs")
    if not opensees_available():
        ap.error("openseespy does not import: pip install -e .[peers]")
    if args.building is None:
        rows = convergence(DEFAULT_BEARING, None, args.fractions, args.steps_per_uy, math.radians(args.angle))
        print(format_table(rows, DEFAULT_BEARING), flush=True)
        return 0
    pairs = list(zip(args.pairs[::2], args.pairs[1::2], strict=True))
    for k, regime in enumerate(args.building or list(BUILDING_SCENES)):
        scene = Scene(**BUILDING_SCENES[regime])
        target = reference_target(scene)
        print(("\n" if k else "") + f"regime {regime}: {BUILDING_SCENES[regime]}", flush=True)
        print(format_table(building_convergence(scene, pairs, target), target=target), flush=True)
    return 0

if __name__ == "__main__":
    raise SystemExit(main())
