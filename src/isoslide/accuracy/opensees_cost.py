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
friction (:mod:`isoslide.peers.opensees_bearing_rate`), its yield displacement the pair's stick
displacement.

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
from ..scene import Scene
from ..solver import solve
from ..studies.opensees_convergence import DEFAULT_HORIZON, DEFAULT_PAIRS, target_pi1
from .scenes import BUILDING_POINTS, BUILDINGS

TOLERANCE = 1e-3
"""Relative error of ``Pi1`` at which OpenSees's cost is taken."""
POINTS = BUILDING_POINTS[2:4]
"""Pi points of the comparison (two of the buildings section's: ``pi2 = 0.1`` at ``pi3 = 2`` and 3)."""


def _timed(fn, repeats: int) -> tuple:
    times, out = [], None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return float(np.median(times)), out


def compare(scene: Scene, pairs=DEFAULT_PAIRS, tolerance: float = TOLERANCE, horizon: float = DEFAULT_HORIZON,
            repeats: int = 5) -> dict:
    """The cost of isoslide and of OpenSees on one scene, OpenSees at the coarsest pair within ``tolerance``.

    Returns
    -------
    dict
        ``exact`` (``Pi1`` at ``rtol = 1e-9``), ``isoslide_s`` and ``isoslide_error`` (its default
        solve), ``dtau``, ``stick`` (the pair that reached the tolerance, or the finest), ``reached``,
        ``opensees_error``, ``opensees_steps`` and ``opensees_s`` (seconds of that run).
    """
    tau_max = float(scene.pulse.tau_end) + float(horizon)
    _, exact = target_pi1(scene, "exact", tau_max)
    iso_s, sol = _timed(lambda: solve(scene), repeats)
    row = {"exact": exact, "isoslide_s": iso_s, "isoslide_error": abs(sol.pi1 - exact) / exact}
    speed = building_of(scene).isolator.speed_dependent
    for dtau, stick in sorted(pairs, reverse=True):
        t0 = time.perf_counter()
        if speed:   # a flatSliderBearing with VelDependent friction beside the pendulum's spring
            r = solve_opensees_bearing_rate(scene, uy=stick, dtau=dtau, tau_max=tau_max)
        else:
            r = solve_opensees(scene, tau_max=tau_max, dtau=dtau, stick_displacement=stick)
        seconds = time.perf_counter() - t0
        err = abs(r.pi1 - exact) / exact
        row.update(dtau=dtau, stick=stick, opensees_error=err, opensees_steps=r.n_steps, opensees_s=seconds,
                   reached=err <= tolerance)
        if err <= tolerance:
            break
    return row


def run(points=POINTS, buildings=None, repeats: int = 5) -> dict:
    """:func:`compare` for every building of :data:`~isoslide.accuracy.scenes.BUILDINGS` at every point."""
    if not opensees_available():
        raise RuntimeError("OpenSees is not installed: pip install -e .[peers]")
    buildings = BUILDINGS if buildings is None else buildings
    solve(Scene(**points[0]))  # kernels ready before timing
    return {name: [compare(Scene(**pt, **kw), repeats=repeats) for pt in points] for name, kw in buildings.items()}


def report(res: dict, file=sys.stdout) -> dict:
    """Print each class's costs and the ratio OpenSees / isoslide (median over the points); returns them."""
    p = lambda *a: print(*a, file=file)  # noqa: E731
    p(f"OpenSees against isoslide: OpenSees at the coarsest (dtau, stick displacement) of {len(DEFAULT_PAIRS)} "
      f"pairs within {TOLERANCE:g} of Pi1 (isoslide at rtol 1e-9), isoslide at its default rtol; "
      f"medians over {len(next(iter(res.values())))} Pi points")
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
                      "dtau": max(r["dtau"] for r in rows), "isoslide_error": max(r["isoslide_error"] for r in rows),
                      "opensees_error": max(r["opensees_error"] for r in rows)}
        s = summ[name]
        p(f"{name:48s} {s['isoslide_ms']:11.2f} {s['isoslide_error']:8.1e} {s['dtau']:7.0e} {ops:10.2f} "
          f"{s['opensees_error']:8.1e} {ratio:18.0f}{'' if reached else '  (tolerance not reached)'}")
    p(f"OpenSees / isoslide over the classes: smallest {min(v['ratio'] for v in summ.values()):.0f}x, "
      f"median {np.median([v['ratio'] for v in summ.values()]):.0f}x")
    return summ
