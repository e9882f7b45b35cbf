r"""OpenSees's ``TripleFrictionPendulum`` element on a quasi-static cyclic path, against the closed forms.

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

Units: lengths m, forces N, angles rad.
"""

from __future__ import annotations

import argparse
import math
import os
import time
from typing import NamedTuple

import numpy as np

from ..model import tfp
from ..model.tfp import TripleFrictionPendulum
from .opensees import _opensees, opensees_available

__all__ = ["DEFAULT_BEARING", "DEFAULT_FRACTIONS", "LoopError", "OpenSeesLoop", "convergence", "cyclic_path",
           "default_amplitudes", "format_table", "loop_error", "main", "observed_order", "regularised_backbone",
           "tfp_loop_opensees", "tfp_path_opensees"]

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


def format_table(rows, bearing: TripleFrictionPendulum | None = None) -> str:
    """The table as text: per amplitude a heading, a line per ``uy``, and the observed order.

    Columns: ``uy`` and the increment (m), ``uy / L1``, the largest ``|F - F_closed| / W`` over the
    loop, at the vertices and in each regime I..V (``-`` where the loop does not reach it), the
    largest ``|F_normal| / W``, steps and seconds.
    """
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


def main(argv=None) -> int:
    """``python -m isoslide.peers.opensees_tfp [--fractions F ...] [--angle DEG] [--steps-per-uy N]``."""
    ap = argparse.ArgumentParser(prog="python -m isoslide.peers.opensees_tfp", description=__doc__.split("\n")[0])
    ap.add_argument("--fractions", nargs="+", type=float, default=list(DEFAULT_FRACTIONS),
                    help="uy as fractions of the largest radius (default: %(default)s)")
    ap.add_argument("--angle", type=float, default=0.0, help="direction from x, degrees (default: 0)")
    ap.add_argument("--steps-per-uy", type=float, default=1.0, help="steps per uy of travel (default: 1)")
    args = ap.parse_args(argv)
    if not opensees_available():
        ap.error("openseespy does not import: pip install -e .[peers]")
    rows = convergence(DEFAULT_BEARING, None, args.fractions, args.steps_per_uy, math.radians(args.angle))
    print(format_table(rows, DEFAULT_BEARING), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
