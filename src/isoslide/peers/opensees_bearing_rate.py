r"""Optional peer: a rigid isolated building on a sliding bearing whose friction rises with speed, in OpenSees.

The isolator is a friction pendulum taken apart: a linear spring ``k_d`` and a linear dashpot
``c_b`` beside OpenSees's ``flatSliderBearing`` element with the ``VelDependent`` friction model,

    mu(v) = muFast - (muFast - muSlow) exp(-transRate |v|)

(Constantinou, Mokha and Reinhorn 1990), ``v`` the bearing's sliding speed.  Unlike
``singleFPBearing`` the flat slider's horizontal force has no term in the normal force times the
displacement over the radius (the pendulum's restoring force is the linear spring, as in isoslide),
so the model is isoslide's sliding bearing (:attr:`isoslide.model.parts.Isolator.level`): friction
``Pi9 (1 - (1 - Pi22) exp(-Pi23 |x'|))`` while sliding, breakaway at ``Pi9 Pi22``.  The contents
slide on the slab with Coulomb friction, modelled as in :mod:`isoslide.peers.opensees` by an
elastic-perfectly-plastic spring.

Model (dimensionless: time ``T_p``, lengths ``a_p T_p^2``, masses ``M_b``, forces ``M_b a_p``)
------------------------------------------------------------------------------------------------
A 2-D model (``ndm = 2``, ``ndf = 3``), every node at the origin:

* node 1, the ground: fixed;
* node 2, the slab: mass 1 in ``X`` only; ``X`` and the vertical ``Y`` free, rotation fixed;
* node 4, the contents: mass ``Pi8`` (at least ``1e-6``) in ``X``; ``X`` free, ``Y`` and rotation
  fixed;
* ``zeroLength`` element 1 (ground to slab, ``X``): ``Elastic`` material of stiffness
  ``k_d = (2 pi / Pi3)^2`` with damping tangent ``c_b = 2 Pi4 (2 pi / Pi3)``;
* ``flatSliderBearing`` element 2 (ground to slab), ``-orient 0 1 0 -1 0 0``: its local (axial)
  ``x`` is the vertical ``Y``, its shear direction the horizontal ``X``.  Axial material ``Elastic``
  of stiffness ``W / (VERTICAL_STRAIN uy)`` (``-P``), moment material ``Elastic`` (``-Mz``, never
  deformed); friction model ``VelDependent`` with ``muFast = Pi9 / W``, ``muSlow = Pi9 Pi22 / W``,
  ``transRate = Pi23``; elastic shear stiffness ``kInit = muSlow W / uy``;
* ``zeroLength`` element 4 (slab to contents, ``X``): ``ElasticPP`` of yield force ``Pi8 Pi2/Pi5``
  and yield displacement the contents' stick displacement (``uy`` unless given).

How ``N`` and ``mu`` are set, and the units
-------------------------------------------
The normal force is the weight ``W = g / a_p`` (the slab's mass 1 times gravity in units of
``a_p``; ``g / a_p`` from ``scene.scale`` when the scene was built from physical units, else 1,
as in :mod:`isoslide.peers.opensees_planar`), a constant load ``-W`` on the slab's vertical degree
of freedom, applied by a static analysis before the ground moves.  That degree of freedom has no
mass, so the element's axial force stays ``-W`` exactly: ``N = W`` at every step.  The element's
friction force is ``mu(v) N``, so ``muFast N = Pi9`` and ``muSlow N = Pi9 Pi22`` (units ``M_b
a_p``) whatever ``W`` is; ``W`` only scales the coefficients (the answer does not depend on it, to
round-off).  The element passes ``mu`` the relative speed of its nodes along the shear direction,
the slab's ``|x'|`` in units of ``a_p T_p``; the law's rate ``a`` (s/m) times a speed in m/s is
``a a_p T_p |x'| = Pi23 |x'|``, so ``transRate = Pi23``.  Stick is regularised by the element's
elastic range: it reaches the breakaway force ``muSlow W = Pi9 Pi22`` at the yield displacement
``uy`` (units ``a_p T_p^2``).  The element evaluates ``mu`` at the trial speed, which while stuck
is the elastic range's small rate of deformation, not 0, so the force it holds stuck can exceed
``Pi9 Pi22`` a little (0.1 % at ``uy = 1e-6`` on :data:`EXAMPLE`, falling with ``uy``); its
tangent leaves out ``d mu / d v``.

What isoslide does not model is kept out: the slab's rotation is fixed and the element has no
length, so its P-Delta moments (axial force times the shear displacement) go into the fixed
rotation, not into the sliding, and its shear force has no normal-force term (that term is the
axial force times the rotation of the bottom node, which is fixed).  No vertical ground motion
(``N`` is constant).

Integration: the ground acceleration ``p(tau)`` of ``scene.pulse`` sampled every ``dtau`` (a ``Path``
series), ``UniformExcitation`` in ``X`` (node displacements are relative to the ground), average
acceleration Newmark (``gamma = 1/2``, ``beta = 1/4``) with Newton iterations, a step that fails
retried as :func:`isoslide.peers.opensees.solve_opensees` does.

:func:`convergence` runs a refinement table over ``(uy, dtau)`` pairs; ``python -m
isoslide.peers.opensees_bearing_rate`` prints it for :data:`EXAMPLE`.  Needs ``openseespy``
(``pip install -e .[peers]``); the module imports without it.
"""

from __future__ import annotations

import argparse
import math
import os
import time
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from ..scene import Scene
from ..store.history import History, phase_of
from .opensees import (BLOCK, GROUND, SLAB, _at_limit, _hold_static_load, _newmark_analysis, _opensees, _positive,
                       refuse_unmodelled_contents_and_motion,
                       _step, opensees_available, opensees_model)
from .result import PeerResult

__all__ = ["BearingRateModel", "BearingRateResult", "ConvergenceRow", "DEFAULT_PAIRS", "EXAMPLE", "HORIZON",
           "bearing_rate_model", "convergence", "format_table", "main", "solve_opensees_bearing_rate"]

HORIZON = 10.0
"""Default run after the pulse ends, units ``T_p`` (as :mod:`isoslide.studies.opensees_convergence`)."""

VERTICAL_STRAIN = 1e-3
"""The bearing's axial compression under ``W`` as a fraction of ``uy`` (sets the axial stiffness)."""

DEFAULT_PAIRS = ((1e-5, 1e-3), (1e-6, 1e-3), (1e-7, 3e-4), (1e-8, 3e-4))
"""``(uy, dtau)`` pairs of the refinement table (units ``a_p T_p^2`` and ``T_p``): ``uy`` ten times
smaller each time, ``dtau`` at most a fifth of the contents' stick period ``2 pi sqrt(uy / Pi2)``
(for ``Pi2 >= 0.2``).  On :data:`EXAMPLE` with constant friction (``Pi22 = 1``) the relative error
of ``Pi1`` against isoslide's exact answer is 10.6 %, 2.4 %, 0.72 % and 0.24 % (about half order in
``uy``: the regularised springs of the bearing and the contents reverse without stopping, see
:mod:`isoslide.studies.opensees_convergence`); with ``Pi22 = 0.5``, ``Pi23 = 20`` ``Pi1`` changes
by 5.5 %, 0.59 % and 0.15 % from pair to pair.  About 0.5 s per 14 000 steps."""

EXAMPLE = {"pi2": 0.2, "pi3": 2.0, "pi4": 0.0, "pi9": 0.3, "pi22": 0.5, "pi23": 20.0, "pi8": 0.01}
"""A scene whose bearing slides and sticks again (``T_b = 2 T_p``, breakaway ``0.15``, high-speed
friction ``0.3``, the rise over speeds of ``1 / 20`` of ``a_p T_p``) carrying contents of 1 % of its
mass that slide too (``Pi2 = 0.2``), under the Ricker pulse."""

SLIDER, SPRING, CONTENTS = 2, 1, 4
"""Element tags: the ``flatSliderBearing``, the linear spring and dashpot, the contents' spring."""


@dataclass(frozen=True)
class BearingRateModel:
    """The parameters of the OpenSees model of a scene (units of the module docstring).

    Attributes
    ----------
    m : float
        Contents' mass ``Pi8`` (at least ``1e-6``).
    kd, cb : float
        Linear spring ``(2 pi / Pi3)^2`` and dashpot ``2 Pi4 (2 pi / Pi3)`` beside the slider.
    weight : float
        ``W = g / a_p``, the slider's normal force.
    mu_slow, mu_fast, rate : float
        ``VelDependent``'s ``muSlow = Pi9 Pi22 / W``, ``muFast = Pi9 / W``, ``transRate = Pi23``.
    uy : float
        The slider's yield displacement (``kInit = muSlow W / uy``).
    thr, d_block : float
        Contents' friction level ``Pi2 / Pi5`` (units ``a_p``) and stick displacement.
    """

    m: float
    kd: float
    cb: float
    weight: float
    mu_slow: float
    mu_fast: float
    rate: float
    uy: float
    thr: float
    d_block: float

    @property
    def k_init(self) -> float:
        """The slider's elastic shear stiffness ``muSlow W / uy`` (units ``M_b / T_p^2``)."""
        return self.mu_slow * self.weight / self.uy

    def level(self, v):
        """The slider's friction force while sliding at speed ``|v|``, ``mu(v) W`` (units ``M_b a_p``)."""
        return (self.mu_fast - (self.mu_fast - self.mu_slow) * np.exp(-self.rate * np.abs(v))) * self.weight


def _check_scene(scene: Scene) -> None:
    """ValueError naming the first group of a scene this peer does not model."""
    if scene.pi12 > 0.0:
        raise ValueError(f"pi12 = {scene.pi12!r} (a flexible superstructure) is not modelled by the OpenSees "
                         "bearing-rate peer; allowed: pi12 = 0 (rigid superstructure)")
    if scene.pi3 == 0.0 or scene.pi9 == 0.0 or scene.pi10 != 0.0:
        raise ValueError(f"pi3 = {scene.pi3!r}, pi9 = {scene.pi9!r}, pi10 = {scene.pi10!r} is not a sliding "
                         "bearing; allowed: pi3 > 0, pi9 > 0, pi10 = 0")
    refuse_unmodelled_contents_and_motion(scene, "OpenSees bearing-rate peer", "constant normal force")


def bearing_rate_model(scene: Scene, uy: float, stick_displacement: float | None = None) -> BearingRateModel:
    """The parameters of the OpenSees model of a scene (see the module docstring).

    Parameters
    ----------
    scene : Scene
        A rigid superstructure (``Pi12 = 0``) on a sliding bearing (``Pi3 > 0``, ``Pi9 > 0``,
        ``Pi10 = 0``, any ``Pi22``, ``Pi23``), contents with Coulomb friction, the main pulse alone.
        Other scenes raise a ValueError naming the group.
    uy : float
        The slider's yield displacement, units ``a_p T_p^2`` (> 0).
    stick_displacement : float or None
        The contents' spring's yield displacement, units ``a_p T_p^2``; None: ``uy``.

    Returns
    -------
    BearingRateModel
    """
    _check_scene(scene)
    uy = _positive("uy", uy)
    d = uy if stick_displacement is None else _positive("stick_displacement", stick_displacement)
    base = opensees_model(scene, stick_displacement=d)      # spring, dashpot, contents
    weight = scene.scale.g / scene.scale.a_p if scene.scale is not None else 1.0
    return BearingRateModel(m=base.m, kd=base.kd, cb=base.cb, weight=weight, mu_slow=scene.pi9 * scene.pi22 / weight,
                            mu_fast=scene.pi9 / weight, rate=scene.pi23, uy=uy, thr=base.thr, d_block=base.d_block)


def _build(ops, M: BearingRateModel) -> None:
    """Nodes, materials, elements and the static weight on the slider (the domain's time then 0)."""
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    for node in (GROUND, SLAB, BLOCK):
        ops.node(node, 0.0, 0.0)
    ops.fix(GROUND, 1, 1, 1)
    ops.fix(SLAB, 0, 0, 1)
    ops.fix(BLOCK, 0, 1, 1)
    ops.mass(SLAB, 1.0, 0.0, 0.0)
    ops.mass(BLOCK, M.m, 0.0, 0.0)
    ops.uniaxialMaterial("Elastic", 1, M.kd, M.cb)                   # k_d x + c_b x'
    ops.element("zeroLength", SPRING, GROUND, SLAB, "-mat", 1, "-dir", 1)
    ops.frictionModel("VelDependent", 1, M.mu_slow, M.mu_fast, M.rate)
    ops.uniaxialMaterial("Elastic", 2, M.weight / (VERTICAL_STRAIN * M.uy))   # axial: carries N = W
    ops.uniaxialMaterial("Elastic", 3, M.weight)                     # moment: rotations fixed
    ops.element("flatSliderBearing", SLIDER, GROUND, SLAB, 1, M.k_init, "-P", 2, "-Mz", 3,
                "-orient", 0.0, 1.0, 0.0, -1.0, 0.0, 0.0)
    ops.uniaxialMaterial("ElasticPP", 4, M.m * M.thr / M.d_block, M.d_block)   # contents, yield m thr
    ops.element("zeroLength", CONTENTS, SLAB, BLOCK, "-mat", 4, "-dir", 1)
    ops.timeSeries("Constant", 1)
    ops.pattern("Plain", 1, 1)
    ops.load(SLAB, 0.0, -M.weight, 0.0)
    _hold_static_load(ops, "the bearing's weight")


@dataclass(frozen=True)
class BearingRateResult(PeerResult):
    """A :class:`PeerResult` with the slab's peak displacement ``slab_peak`` (max ``|x|``, units ``a_p T_p^2``)."""

    slab_peak: float = math.nan


def solve_opensees_bearing_rate(scene: Scene, uy: float, dtau: float, tau_max: float | None = None,
                                stick_displacement: float | None = None, history: bool = False) -> BearingRateResult:
    """Peak sliding of the contents on a rigid building isolated by a speed-dependent sliding bearing, with OpenSees.

    See the module docstring for the model.  Everything starts at rest at ``pulse.tau_start``; the
    run goes to ``tau_max`` in steps of ``dtau``.

    Parameters
    ----------
    scene : Scene
        As :func:`bearing_rate_model` (``Pi22 = 1`` or ``Pi23 = 0`` is constant friction
        ``Pi9 Pi22``).
    uy : float
        The slider's yield displacement (units ``a_p T_p^2``, > 0), and the contents' stick
        displacement unless ``stick_displacement`` is given.
    dtau : float
        Newmark time step, units ``T_p`` (> 0).
    tau_max : float or None
        End time, units ``T_p``; default ``pulse.tau_end + HORIZON``.
    stick_displacement : float or None
        The contents' stick displacement (units ``a_p T_p^2``); None: ``uy``.
    history : bool
        Also return the step-by-step :class:`~isoslide.store.history.History`: ``x, xd`` the slab,
        ``u, ud`` the contents relative to it, ``phase`` the contents' spring at its yield force in
        the direction of ``u'``, ``fh`` the slider's horizontal force on the slab's motion (the
        friction force while sliding, units ``M_b a_p``) and ``iso_phase`` the slider at its
        friction force ``mu(x') W`` in the direction of ``x'``.

    Returns
    -------
    BearingRateResult
        ``method = "opensees_bearing_rate"``, ``pi1`` the peak ``|u|``, ``slab_peak`` the peak
        ``|x|``, ``tau_peak`` (of ``pi1``), ``pi1_residual`` the final ``u``, ``n_steps``,
        ``stiffness`` the contents' ``K = (Pi2/Pi5) / stick displacement``, ``integrator =
        "Newmark"``, ``settled`` False (the run goes to ``tau_max``).

    Raises
    ------
    ValueError
        For a scene the peer does not model (naming the group) or a step, ``uy`` or ``tau_max`` out
        of range.
    RuntimeError
        When OpenSees fails at a step.
    """
    M = bearing_rate_model(scene, uy, stick_displacement)
    dtau = _positive("dtau", dtau)
    pulse = scene.pulse
    end = pulse.tau_end + HORIZON if tau_max is None else float(tau_max)
    n = int(math.ceil((end - pulse.tau_start) / dtau - 1e-9))
    if not (math.isfinite(end) and n >= 1):
        raise ValueError(f"tau_max = {tau_max!r} is out of range; allowed range: > pulse.tau_start "
                         f"= {pulse.tau_start!r}")
    tt = pulse.tau_start + dtau * np.arange(n + 1)
    ops = _opensees()
    _build(ops, M)
    ops.logFile(os.devnull, "-noEcho")     # the retries of _step are expected; a failure raises
    ops.timeSeries("Path", 2, "-dt", dtau, "-values", *np.asarray(pulse.accel(tt), dtype=float).tolist())
    ops.pattern("UniformExcitation", 2, 1, "-accel", 2)
    _newmark_analysis(ops)
    umax = xmax = u = 0.0
    tau_peak = float(pulse.tau_start)
    rows = [(tau_peak, 0.0, 0.0, 0.0, 0.0, 0.0, 0, 0)] if history else None
    for i in range(n):
        if not _step(ops, dtau):
            ops.wipe()
            raise RuntimeError(f"OpenSees analysis failed at tau = {tt[i]:.6g} (dtau = {dtau!r}, uy = {M.uy!r})")
        x = ops.nodeDisp(SLAB, 1)
        u = ops.nodeDisp(BLOCK, 1) - x
        xmax = max(xmax, abs(x))
        if abs(u) > umax:
            umax, tau_peak = abs(u), float(tt[i + 1])
        if rows is not None:
            xd = ops.nodeVel(SLAB, 1)
            ud = ops.nodeVel(BLOCK, 1) - xd
            fh = -ops.eleResponse(SLIDER, "basicForce")[1]     # basic shear is along local y = -X
            force = ops.eleResponse(CONTENTS, "material", 1, "stress")[0]
            rows.append((float(tt[i + 1]), x, xd, u, ud, fh, _at_limit(force, M.m * M.thr, ud),
                         _at_limit(fh, float(M.level(xd)), xd)))
    ops.wipe()
    h = None
    if rows is not None:
        a = np.array(rows, dtype=float)
        h = History(tau=a[:, 0], x=a[:, 1], xd=a[:, 2], u=a[:, 3], ud=a[:, 4],
                    phase=phase_of(a[:, 6] != 0.0, a[:, 4]), fh=a[:, 5], iso_phase=a[:, 7].astype(np.int8))
    return BearingRateResult(method="opensees_bearing_rate", pi1=umax, pi1_residual=float(u), tau_peak=tau_peak,
                             settled=False, tau_end=float(tt[-1]), n_steps=n, stiffness=M.thr / M.d_block,
                             integrator="Newmark", history=h, slab_peak=xmax)


class ConvergenceRow(NamedTuple):
    """One run of the refinement table.

    ``uy`` (the slider's yield displacement and the contents' stick displacement), ``dtau``, ``pi1``,
    the slab's peak ``slab_peak``, ``n_steps`` and ``seconds`` (wall-clock time of the run).
    """

    uy: float
    dtau: float
    pi1: float
    slab_peak: float
    n_steps: int
    seconds: float


def convergence(scene: Scene, pairs=DEFAULT_PAIRS, tau_max: float | None = None) -> list:
    """The peer over ``(uy, dtau)`` pairs: one :class:`ConvergenceRow` per pair, in their order.

    Parameters
    ----------
    scene : Scene
        As :func:`solve_opensees_bearing_rate`.
    pairs : sequence of (float, float)
        ``(uy, dtau)``, units ``a_p T_p^2`` and ``T_p``, each > 0; ``uy`` is also the contents'
        stick displacement.
    tau_max : float or None
        End time of every run (default ``pulse.tau_end + HORIZON``).

    Returns
    -------
    list of ConvergenceRow
    """
    checked = [(_positive("uy", uy), _positive("dtau", dtau)) for uy, dtau in pairs]
    if not checked:
        raise ValueError("pairs = () is empty; allowed: at least one (uy, dtau) pair")
    rows = []
    for uy, dtau in checked:
        t0 = time.perf_counter()
        r = solve_opensees_bearing_rate(scene, uy, dtau, tau_max)
        rows.append(ConvergenceRow(uy, dtau, r.pi1, r.slab_peak, r.n_steps, time.perf_counter() - t0))
    return rows


def format_table(rows, target: float | None = None) -> str:
    """The table as text, a line per row after a heading.

    Columns: ``uy``, ``dtau``, ``Pi1``, its relative change from the row before (or, with a ``target``
    ``Pi1``, its relative error against it), the slab's peak, steps and seconds.
    """
    label = "rel. error" if target is not None else "change"
    lines = [f"{'uy':>9} {'dtau':>9} {'Pi1':>13} {label:>11} {'slab peak':>11} {'steps':>8} {'time':>7}"]
    prev = None
    for r in rows:
        if target is not None:
            e = f"{abs(r.pi1 - target) / target:11.2e}"
        else:
            e = f"{abs(r.pi1 - prev) / abs(r.pi1):11.2e}" if prev is not None else f"{'-':>11}"
        lines.append(f"{r.uy:9.1e} {r.dtau:9.1e} {r.pi1:13.8f} {e} {r.slab_peak:11.6f} {r.n_steps:8d} "
                     f"{r.seconds:6.2f}s")
        prev = r.pi1
    return "\n".join(lines)


def main(argv=None) -> int:
    """``python -m isoslide.peers.opensees_bearing_rate [--pi22 X] [--pi23 X] [--pairs UY DTAU ...]``."""
    ap = argparse.ArgumentParser(prog="python -m isoslide.peers.opensees_bearing_rate",
                                 description=__doc__.split("\n")[0])
    ap.add_argument("--pi22", type=float, default=EXAMPLE["pi22"], help="mu_slow / mu_fast (default: %(default)s)")
    ap.add_argument("--pi23", type=float, default=EXAMPLE["pi23"], help="a a_p T_p (default: %(default)s)")
    ap.add_argument("--pairs", nargs="+", type=float, default=[v for p in DEFAULT_PAIRS for v in p],
                    help="uy and dtau, pair after pair (default: %(default)s)")
    args = ap.parse_args(argv)
    if len(args.pairs) % 2:
        ap.error("--pairs takes uy and dtau in pairs")
    if not opensees_available():
        ap.error("openseespy does not import: pip install -e .[peers]")
    scene = Scene(**{**EXAMPLE, "pi22": args.pi22, "pi23": args.pi23})
    pairs = list(zip(args.pairs[::2], args.pairs[1::2], strict=True))
    print(f"scene: {EXAMPLE | {'pi22': args.pi22, 'pi23': args.pi23}}, ricker pulse", flush=True)
    print(format_table(convergence(scene, pairs)), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
