"""Where the planar steps go: slides too slow for an explicit step, and the slaved line that takes them.

Run: ``python benchmarks/slow_slide.py`` (about a minute).  A block sliding in the plane with speed
``s = |w|`` turns its direction towards the force driving it at the rate ``phi / s`` (``phi`` its
friction per unit mass): just after a breakaway and just before a stop that rate is far faster
than the motion, and an explicit Runge-Kutta step must stay below a few times ``s / phi`` however
smooth the path is.  This prints, over the planar scenes of the bench
(:data:`isoslide.accuracy.scenes.PLANAR_BUILDINGS` at each of
:data:`~isoslide.accuracy.scenes.PLANAR_POINTS`):

1. the accepted steps of free slides (the block's mode 1) and how many of them were stiff, i.e.
   took ``h phi / s > 1`` with ``phi >= Pi2`` (the kinetic level; a Stribeck block's is higher at
   low speed, so the count is a lower bound), from each solve's history;
2. the Runge-Kutta steps, the time and the largest and median relative error of ``Pi1`` (against
   ``solve(rtol=1e-12)``) when the slaved line, on which a slow slide keeps the direction of its
   drive (:func:`isoslide.engine.planar_kernel.slaved_speed`), holds slides up to 1, 10, 100 and
   1000 times its speed: what slaving the direction at zeroth order buys and what it costs.

``--measurements docs/measurements.csv`` rewrites this command's rows of the documentation's table
(topic ``planar``).
"""

import argparse
from pathlib import Path

import numpy as np

from isoslide import Scene, solve
from isoslide.accuracy.measurements import Measurement, machine_conditions, write_rows
from isoslide.accuracy.scenes import PLANAR_BUILDINGS, PLANAR_EXCITATION, PLANAR_POINTS
from isoslide.accuracy.timing import timed_batch
from isoslide.engine import planar_kernel

FACTORS = (1.0, 10.0, 100.0, 1000.0)
"""Multiples of the slaved line's speed limit compared; the first is the solver's."""
COMMAND = "python benchmarks/slow_slide.py"
"""The command whose rows of the topic ``planar`` ``--measurements`` rewrites."""


def stiff_steps(scene: Scene) -> tuple[int, int]:
    """``(free, stiff)``: accepted steps of free slides in one solve, and those with ``h Pi2 / s > 1``."""
    h = solve(scene, history=True).history
    s = np.hypot(h.ud[:, 0], h.ud[:, 1])
    free = np.flatnonzero((h.phase[:-1] == 1) & (h.phase[1:] == 1) & (s[:-1] > 0.0))
    dt = np.diff(h.tau)[free]
    return free.size, int(np.count_nonzero(dt * scene.pi2 > s[free]))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--measurements", type=Path, help="rewrite this command's rows of this measurements table")
    args = parser.parse_args()
    scenes = [Scene(**{**pt, **kw}, **PLANAR_EXCITATION) for kw in PLANAR_BUILDINGS.values() for pt in PLANAR_POINTS]
    counts = np.array([stiff_steps(sc) for sc in scenes])
    total = sum(solve(sc).n_steps for sc in scenes)
    print(f"{len(scenes)} planar scenes: {total} Runge-Kutta steps, {counts[:, 0].sum()} accepted steps of free "
          f"slides, {counts[:, 1].sum()} of them stiff (h Pi2 / s > 1)")
    exact = [solve(sc, rtol=1e-12).pi1 for sc in scenes]
    default = planar_kernel.SLAVED_FACTOR
    steps, worst = [], []
    print(f"{'slaved speed':>12s} {'steps':>7s} {'ms':>8s} {'max err':>9s} {'med err':>9s}")
    try:
        for factor in FACTORS:
            planar_kernel.SLAVED_FACTOR = default * factor
            n, ms, err = timed_batch(scenes, exact)
            steps.append(n)
            worst.append(err.max())
            print(f"{factor:11g}x {n:7d} {ms:8.1f} {err.max():9.1e} {np.median(err):9.1e}")
    finally:
        planar_kernel.SLAVED_FACTOR = default
    if args.measurements:
        where = f"the {len(scenes)} planar scenes of the bench"
        cond = machine_conditions()
        rows = [
            Measurement(f"free-slide steps held by the direction's turning rate phi/|w| (h Pi2/|w| > 1) among the "
                        f"accepted free-slide steps of {where}", f"{counts[:, 1].sum()} / {counts[:, 0].sum()}", "steps",
                        f"{total} Runge-Kutta steps in all (rejected and checking steps included); {cond}"),
            Measurement("slaved line held up to " + " / ".join(f"{f:g}x" for f in FACTORS) + " its speed limit (the "
                        f"first the solver's): Runge-Kutta steps over {where}", " / ".join(map(str, steps)), "steps",
                        "largest error of Pi1 " + " / ".join(f"{e:.1e}" for e in worst)
                        + f" against rtol = 1e-12 (default rtol 1e-6); {cond}"),
        ]
        write_rows(args.measurements, "planar", COMMAND, rows)

if __name__ == "__main__":
    main()
