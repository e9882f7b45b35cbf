"""isoslide against OpenSees on every building class: the cost of each at an error of 1e-3 in ``Pi1``.

OpenSees (:func:`isoslide.peers.solve_opensees`) regularises every true stick by an elastic-plastic
spring of small yield displacement and integrates with a fixed Newmark step; its error falls as the
step and the stick displacement shrink together (:mod:`isoslide.studies.opensees_convergence`).
For a fair cost, each scene is given the coarsest ``(dtau, stick displacement)`` pair of
:data:`~isoslide.studies.opensees_convergence.DEFAULT_PAIRS` whose ``Pi1`` is within
:data:`TOLERANCE` of the exact answer (isoslide at ``rtol = 1e-9`` over the same time), and that run
is timed (one run: seconds, far above the timer's resolution). isoslide's cost on the same scene is
the median of :func:`isoslide.solve` at its default accuracy (which stops once the scene has
provably settled, where OpenSees runs to its horizon). The buildings are those of the buildings
section of the bench (:data:`~isoslide.accuracy.scenes.BUILDINGS`), on :data:`POINTS`; a friction
pendulum whose friction rises with speed runs as OpenSees's ``flatSliderBearing`` with ``VelDependent``
friction (:mod:`isoslide.peers.opensees_bearing_rate`), and a triple friction pendulum as OpenSees's
``TripleFrictionPendulum`` element (:func:`isoslide.peers.opensees_tfp.solve_opensees_tfp`), each
with its yield displacement the pair's stick displacement.  The planar classes (:data:`PLANAR_CLASSES`
under the bench's planar excitation, and a recorded pair as recorded on each base of
:data:`~isoslide.accuracy.scenes.PAIR_POINTS`) run on OpenSees's planar model
(:func:`isoslide.peers.opensees_planar.solve_opensees_planar`, a ``flatSliderBearing`` in 3-D) at
the stick stiffnesses :data:`PLANAR_STIFFNESSES`, coarsest first, each with the step the model takes
for it (:func:`planar_pairs`).  The triple pendulum runs on its own pairs
(:data:`TFP_PAIRS`), and the table ends with its two aims, measured in the same run: isoslide at least
:data:`TARGET_TFP_SPEEDUP` times faster than OpenSees on it, and isoslide's cost on it at most
:data:`~isoslide.accuracy.scenes.TARGET_TFP_RATIO` times its cost on the constant-friction pendulum.

``python -m isoslide.bench --opensees`` prints the table (a few minutes; needs ``pip install -e
.[peers]``).
"""
from __future__ import annotations

import sys
import time

import numpy as np

from ..model.parts import building_of
from ..peers import opensees_available, solve_opensees
from ..peers.opensees_bearing_rate import solve_opensees_bearing_rate
from ..peers.opensees_planar import MAX_DTAU, STEPS_PER_PERIOD, planar_model, solve_opensees_planar
from ..peers.opensees_tfp import solve_opensees_tfp
from ..scene import Scene
from ..solver import solve
from ..studies.opensees_convergence import DEFAULT_HORIZON, DEFAULT_PAIRS, target_pi1
from .timing import timed_solve
from .scenes import (BUILDING_POINTS, BUILDINGS, PAIR_POINTS, PENDULUM, PLANAR_BUILDINGS, PLANAR_EXCITATION,
                     TARGET_TFP_RATIO, TFP_PENDULUM, recorded_pairs)

TOLERANCE = 1e-3
"""Relative error of ``Pi1`` at which OpenSees's cost is taken."""
POINTS = BUILDING_POINTS[2:4]
"""Pi points of the comparison (two of the buildings section's: ``pi2 = 0.1`` at ``pi3 = 2`` and 3)."""
TARGET_SPEEDUP = 50.0
"""Aim: isoslide is at least this many times faster than OpenSees on every class, at the same accuracy."""
TARGET_TFP_SPEEDUP = 20.0
"""Aim: on the triple friction pendulum isoslide is at least this many times faster than OpenSees's
``TripleFrictionPendulum`` element at the same accuracy (the OpenSees / isoslide ratio)."""
PLANAR_CLASSES = ("fixed base", "linear isolator, two-way coupling (pi8 = 0.2)")
"""Planar classes of :data:`~isoslide.accuracy.scenes.PLANAR_BUILDINGS` compared (the ones OpenSees's
planar model takes: Coulomb contents on a fixed base or a linear isolator under a rigid superstructure)."""
PLANAR_STIFFNESSES = (1e3, 1e4, 1e5, 1e6, 1e7)
"""Stick stiffnesses ``K T_p^2 / m`` of OpenSees's planar model, coarsest first (:func:`planar_pairs`):
its error falls like ``1 / sqrt(K)`` once the step's is below it; a recorded pair on a fixed base
needs about ``1e7`` for ``1e-3`` (``2.2e-3`` at ``1e6``)."""
TFP_PAIRS = ((1e-2, 1e-4), (3e-3, 1e-5), (1e-3, 1e-6), (1e-3, 1e-7), (1e-3, 1e-8))
"""``(dtau, uy)`` pairs of the triple pendulum: :data:`DEFAULT_PAIRS` with ``dtau`` held at ``1e-3``
once ``uy <= 1e-6``.  The element's error is set by ``uy`` (the step's part measured 4e-4 relative in
:mod:`isoslide.peers.opensees_tfp`), and with ``uy = 1e-8`` its own iterations slow down at small
steps: on :data:`POINTS` at ``pi3 = 3``, 13 s at ``dtau = 1e-3`` and 197 s at ``3e-4`` for errors of
2.5e-3 and 1.8e-3 (at ``pi3 = 2``: 13 s and 12 s, 5.3e-4 and 4.7e-4; 87 s at ``dtau = 1e-4``).  So
these pairs reach the tolerance at a lower cost to OpenSees than :data:`DEFAULT_PAIRS`, or come as close."""


def planar_pairs(scene: Scene) -> tuple:
    """``(dtau, K)`` of OpenSees's planar model at each of :data:`PLANAR_STIFFNESSES`, coarsest first.

    The step is the peer's own for each stick stiffness (:func:`isoslide.peers.opensees_planar.planar_model`:
    ``min(1e-3, T_K / 50)``, ``T_K`` the period of the contents on the stick spring).
    """
    return tuple((min(MAX_DTAU, planar_model(scene, K).stick_period / STEPS_PER_PERIOD), K)
                 for K in PLANAR_STIFFNESSES)


def _opensees_run(scene: Scene, dtau: float, stick: float, tau_max: float):
    """OpenSees's model of the scene's building class at one pair (the module docstring says which)."""
    if not scene.in_line:                                # flatSliderBearing in 3-D, stick stiffness K
        return solve_opensees_planar(scene, stiffness=stick, dt=dtau, t_end=tau_max)
    if scene.isolator == "tfp":                           # the TripleFrictionPendulum element
        return solve_opensees_tfp(scene, uy=stick, dtau=dtau, tau_max=tau_max)
    if building_of(scene).isolator.speed_dependent:      # flatSliderBearing, VelDependent, beside a spring
        return solve_opensees_bearing_rate(scene, uy=stick, dtau=dtau, tau_max=tau_max)
    return solve_opensees(scene, tau_max=tau_max, dtau=dtau, stick_displacement=stick)


def compare(scene: Scene, pairs=None, tolerance: float = TOLERANCE, horizon: float = DEFAULT_HORIZON,
            repeats: int = 5) -> dict:
    """The cost of isoslide and of OpenSees on one scene, OpenSees at the coarsest pair within ``tolerance``.

    ``pairs`` of ``(dtau, stick displacement)``: None takes :data:`TFP_PAIRS` for a triple friction
    pendulum, else :data:`~isoslide.studies.opensees_convergence.DEFAULT_PAIRS`.

    Returns
    -------
    dict
        ``exact`` (``Pi1`` at ``rtol = 1e-9``), ``isoslide_s`` and ``isoslide_error`` (its default
        solve), ``dtau``, ``stick`` (the pair that reached the tolerance, or the finest), ``reached``,
        ``opensees_error``, ``opensees_steps`` and ``opensees_s`` (seconds of that run).
    """
    tau_max = float(scene.pulse.tau_end) + float(horizon)
    _, exact = target_pi1(scene, "exact", tau_max)
    times, sols = zip(*(timed_solve(scene) for _ in range(repeats)), strict=True)
    iso_s, sol = float(np.median(times)), sols[-1]
    row = {"exact": exact, "isoslide_s": iso_s, "isoslide_error": abs(sol.pi1 - exact) / exact}
    if pairs is None:
        pairs = planar_pairs(scene) if not scene.in_line else (TFP_PAIRS if scene.isolator == "tfp" else DEFAULT_PAIRS)
    for dtau, stick in (pairs if not scene.in_line else sorted(pairs, reverse=True)):
        t0 = time.perf_counter()
        r = _opensees_run(scene, dtau, stick, tau_max)
        seconds = time.perf_counter() - t0
        err = abs(r.pi1 - exact) / exact
        row.update(dtau=dtau, stick=stick, opensees_error=err, opensees_steps=r.n_steps, opensees_s=seconds,
                   reached=err <= tolerance)
        if err <= tolerance:
            break
    return row


def scenes_by_class(points=POINTS, buildings=None, planar: bool = True, pairs: int = 1) -> dict:
    """The compared scenes, by class: each building at each point, then the planar classes and recorded pairs.

    ``buildings`` (default :data:`~isoslide.accuracy.scenes.BUILDINGS`) at every point; with
    ``planar`` each of :data:`PLANAR_CLASSES` at every point under the bench's planar excitation
    (:data:`~isoslide.accuracy.scenes.PLANAR_EXCITATION`), and the first ``pairs`` recorded pairs
    (:func:`~isoslide.accuracy.scenes.recorded_pairs`) as recorded at each of
    :data:`~isoslide.accuracy.scenes.PAIR_POINTS`, one class per base.
    """
    buildings = BUILDINGS if buildings is None else buildings
    out = {name: [Scene(**pt, **kw) for pt in points] for name, kw in buildings.items()}
    if not planar:
        return out
    for name in PLANAR_CLASSES:
        out[f"planar: {name}"] = [Scene(**{**pt, **PLANAR_BUILDINGS[name]}, **PLANAR_EXCITATION) for pt in points]
    _, motions = recorded_pairs(pairs)
    for base, pt in PAIR_POINTS.items():
        out[f"recorded pair, {base}"] = [Scene(**pt, pulse=x, pulse_y=y, pi16=lag) for _, x, y, lag in motions]
    return out


def run(points=POINTS, buildings=None, repeats: int = 5, planar: bool = True, pairs: int = 1) -> dict:
    """:func:`compare` on every scene of :func:`scenes_by_class` (the same arguments), class by class."""
    if not opensees_available():
        raise RuntimeError("OpenSees is not installed: pip install -e .[peers]")
    classes = scenes_by_class(points, buildings, planar, pairs)
    for scenes in classes.values():   # kernels ready before timing
        solve(scenes[0])
    return {name: [compare(sc, repeats=repeats) for sc in scenes] for name, scenes in classes.items()}


def report(res: dict, file=sys.stdout) -> dict:
    """Print each class's costs and the ratio OpenSees / isoslide (median over the points); returns them."""
    p = lambda *a: print(*a, file=file)  # noqa: E731
    p(f"OpenSees against isoslide: OpenSees at the coarsest (dtau, stick displacement) of {len(DEFAULT_PAIRS)} "
      f"pairs (the triple pendulum: of its {len(TFP_PAIRS)}) within {TOLERANCE:g} of Pi1 (isoslide at rtol "
      f"1e-9), isoslide at its default rtol; "
      f"medians over each class's scenes (the Pi points; a recorded pair: its pairs)")
    hdr = (f"{'building':48s} {'isoslide ms':>11s} {'iso err':>8s} {'dtau':>7s} {'OpenSees s':>10s} "
           f"{'OS err':>8s} {'OpenSees/isoslide':>18s}")
    p(hdr)
    p("-" * len(hdr))
    summ = {}
    for name, rows in res.items():
        iso = float(np.median([r["isoslide_s"] for r in rows]))
        ops = float(np.median([r["opensees_s"] for r in rows]))
        ratio = float(np.median([r["opensees_s"] / r["isoslide_s"] for r in rows]))
        reached = all(r["reached"] for r in rows)
        summ[name] = {"isoslide_ms": 1e3 * iso, "opensees_s": ops, "ratio": ratio, "reached": reached,
                      "scenes": len(rows),
                      "dtau": max(r["dtau"] for r in rows), "isoslide_error": max(r["isoslide_error"] for r in rows),
                      "opensees_error": max(r["opensees_error"] for r in rows)}
        s = summ[name]
        p(f"{name:48s} {s['isoslide_ms']:11.2f} {s['isoslide_error']:8.1e} {s['dtau']:7.0e} {ops:10.2f} "
          f"{s['opensees_error']:8.1e} {ratio:18.0f}{'' if reached else '  (tolerance not reached)'}")
    low = min(summ, key=lambda k: summ[k]["ratio"])
    p(f"OpenSees / isoslide over the classes: smallest {summ[low]['ratio']:.0f}x ({low}), "
      f"median {np.median([v['ratio'] for v in summ.values()]):.0f}x")
    met = summ[low]["ratio"] >= TARGET_SPEEDUP
    p(f"aim: isoslide at least {TARGET_SPEEDUP:g}x faster than OpenSees on every class -> "
      f"{'MET' if met else 'NOT MET'} (smallest ratio {summ[low]['ratio']:.0f}x)")
    if TFP_PENDULUM in summ:
        _tfp_aims(p, summ)
    return summ


def _tfp_aims(p, summ: dict) -> None:
    """Print the triple friction pendulum's aims: against OpenSees's element, and against the constant pendulum.

    When OpenSees does not reach the tolerance at its finest pair, the ratio at that pair is a lower
    bound of the ratio at the tolerance (a finer pair costs more), and the line says so.  The second
    aim, when :data:`~isoslide.accuracy.scenes.PENDULUM` ran too, is the ratio of isoslide's median
    costs per scene on the two (stored as ``pendulum_ratio``).
    """
    s = summ[TFP_PENDULUM]
    met = s["ratio"] >= TARGET_TFP_SPEEDUP
    p(f"aim: on the triple friction pendulum isoslide at least {TARGET_TFP_SPEEDUP:g}x faster than OpenSees's "
      f"TripleFrictionPendulum at {TOLERANCE:g} in Pi1 -> {'MET' if met else 'NOT MET'} (median ratio "
      f"{s['ratio']:.0f}x{'' if s['reached'] else ', a lower bound: OpenSees did not reach the tolerance'})")
    if PENDULUM not in summ:
        return
    ratio = s["isoslide_ms"] / summ[PENDULUM]["isoslide_ms"]
    s["pendulum_ratio"] = ratio
    p(f"aim: isoslide on the triple friction pendulum at most {TARGET_TFP_RATIO:g}x its cost on the "
      f"constant-friction pendulum ({PENDULUM}) -> {'MET' if ratio <= TARGET_TFP_RATIO else 'NOT MET'} "
      f"(ratio {ratio:.2f} of the medians above)")
