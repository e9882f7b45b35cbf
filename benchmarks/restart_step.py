"""The first step after a transition: steps, time and error of the planar scenes at several lengths.

Run: ``python benchmarks/restart_step.py`` (about a minute).  Every integrated solve restarts its
Runge-Kutta steps at ``isoslide.solver.H_RESTART`` (units of T_p) after each transition (a
breakaway, a stop, the pulse's breakpoints).  In the plane the sliding direction turns near a
breakaway as a power of the time since it, which the embedded error estimate does not see reliably
on a long first step.  For each restart length this prints, over the planar scenes of the bench
(:data:`isoslide.accuracy.scenes.PLANAR_BUILDINGS` at each of
:data:`~isoslide.accuracy.scenes.PLANAR_POINTS`), the total Runge-Kutta steps, the time of all the
solves (the median of 3, each scene a new copy) and the largest and median relative error of
``Pi1`` against ``solve(rtol=1e-12)`` at the default length.  ``--measurements
docs/measurements.csv`` rewrites this command's row of the documentation's table (topic ``planar``).
"""

import argparse
from pathlib import Path

import numpy as np

from isoslide import Scene, solve, solver
from isoslide.accuracy.measurements import Measurement, machine_conditions, write_rows
from isoslide.accuracy.scenes import PLANAR_BUILDINGS, PLANAR_EXCITATION, PLANAR_POINTS
from isoslide.accuracy.timing import timed_batch

LENGTHS = (1e-4, 1e-3, 1e-2, 3e-2)
"""Restart lengths compared (units of T_p); the first is the solver's."""
COMMAND = "python benchmarks/restart_step.py"
"""The command whose row of the topic ``planar`` ``--measurements`` rewrites."""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--measurements", type=Path, help="rewrite this command's row of this measurements table")
    args = parser.parse_args()
    scenes = [Scene(**{**pt, **kw}, **PLANAR_EXCITATION) for kw in PLANAR_BUILDINGS.values() for pt in PLANAR_POINTS]
    default = solver.H_RESTART
    exact = [solve(sc, rtol=1e-12).pi1 for sc in scenes]
    print(f"{len(scenes)} planar scenes; errors against solve(rtol=1e-12) with the restart length {default:g}")
    print(f"{'restart':>8s} {'steps':>7s} {'ms':>8s} {'max err':>9s} {'med err':>9s}")
    steps, worst, ms = [], [], []
    try:
        for length in LENGTHS:
            solver.H_RESTART = length
            n, t_ms, err = timed_batch(scenes, exact)
            steps.append(n)
            worst.append(err.max())
            ms.append(t_ms)
            print(f"{length:8.0e} {n:7d} {t_ms:8.1f} {err.max():9.1e} {np.median(err):9.1e}")
    finally:
        solver.H_RESTART = default
    if args.measurements:
        row = Measurement(f"first step after a transition {' / '.join(f'{x:g}' for x in LENGTHS)} T_p (the first the "
                          f"solver's): Runge-Kutta steps over the {len(scenes)} planar scenes of the bench",
                          " / ".join(map(str, steps)), "steps",
                          "largest error of Pi1 " + " / ".join(f"{e:.1e}" for e in worst) + " against rtol = 1e-12 "
                          "(default rtol 1e-6); time " + " / ".join(f"{t:.1f}" for t in ms) + f" ms; "
                          f"{machine_conditions()}")
        write_rows(args.measurements, "planar", COMMAND, [row])


if __name__ == "__main__":
    main()
