"""Cost and error of a triple friction pendulum whose friction rises with speed, beside the constant bearing.

Run: ``python benchmarks/tfp_speed_cost.py`` (a few minutes).  The bench's triple friction pendulum
(:data:`isoslide.accuracy.scenes.BUILDINGS` row :data:`~isoslide.accuracy.scenes.TFP_PENDULUM`) on
the first points of :data:`~isoslide.accuracy.scenes.BUILDING_POINTS`, its friction constant and
rising with speed (``mu_slow = mu/2`` on every surface, ``Pi23 = 20``), solved interleaved (the
median of three per scene).  The constant bearing runs the compiled kernel; the speed-dependent one
integrates its surfaces' flow implicitly (:mod:`isoslide.engine.tfp_flow`).  The error of the
speed-dependent bearing's ``Pi1`` at the default ``rtol = 1e-6`` is against ``rtol = 1e-9``.
``--measurements docs/measurements.csv`` rewrites this command's row of the documentation's table
(topic ``bearings``).
"""

import argparse
import time
from pathlib import Path

import numpy as np

from isoslide import Scene, solve
from isoslide.accuracy.measurements import Measurement, machine_conditions, write_rows
from isoslide.accuracy.scenes import BUILDING_POINTS, BUILDINGS, TFP_PENDULUM

POINTS = BUILDING_POINTS[:4]
"""Pi points timed (each with both bearings)."""
SPEED = dict(pi22=0.5, pi23=20.0)
"""The surfaces' law: breakaway at half the fast friction, rate group 20."""
COMMAND = "python benchmarks/tfp_speed_cost.py"
"""The command whose row of the topic ``bearings`` ``--measurements`` rewrites."""


def _timed(scene: Scene) -> tuple:
    t = time.perf_counter()
    sol = solve(scene)
    return time.perf_counter() - t, sol


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--measurements", type=Path, help="rewrite this command's row of this measurements table")
    args = parser.parse_args()
    const = [Scene(**pt, **BUILDINGS[TFP_PENDULUM]) for pt in POINTS]
    speed = [Scene(**pt, **BUILDINGS[TFP_PENDULUM], **SPEED) for pt in POINTS]
    for sc in const + speed:
        solve(sc)   # compile or load every path before timing
    exact = [solve(sc, rtol=1e-9).pi1 for sc in speed]
    t_const, t_speed, errors, steps = [[] for _ in POINTS], [[] for _ in POINTS], [], []
    for _ in range(3):
        for k in range(len(POINTS)):
            seconds, _ = _timed(const[k])
            t_const[k].append(seconds)
            seconds, sol = _timed(speed[k])
            t_speed[k].append(seconds)
            if len(errors) < len(POINTS):
                errors.append(abs(sol.pi1 / exact[k] - 1.0) if exact[k] > 0.0 else abs(sol.pi1))
                steps.append(sol.n_steps)
    tc = np.array([np.median(t) for t in t_const])
    ts = np.array([np.median(t) for t in t_speed])
    print(f"{len(POINTS)} scenes of the bench's triple friction pendulum; median of 3 interleaved runs")
    print(f"{'point':>6s} {'constant ms':>12s} {'speed s':>9s} {'ratio':>8s} {'steps':>6s} {'err':>9s}")
    for k in range(len(POINTS)):
        print(f"{k:6d} {1e3 * tc[k]:12.2f} {ts[k]:9.2f} {ts[k] / tc[k]:8.0f} {steps[k]:6d} {errors[k]:9.1e}")
    ratio = float(np.median(ts / tc))
    print(f"median: constant {1e3 * np.median(tc):.2f} ms, rising with speed {np.median(ts):.2f} s, ratio {ratio:.0f}; "
          f"largest error of Pi1 at rtol 1e-6 {max(errors):.1e}")
    if args.measurements:
        row = Measurement(f"triple friction pendulum whose friction rises with speed (mu_slow = mu/2, Pi23 = 20) "
                          f"over the same bearing with constant friction, median cost ratio over {len(POINTS)} "
                          "bench scenes", f"{ratio:.0f}", "x",
                          f"{np.median(ts):.2f} s against {1e3 * np.median(tc):.2f} ms per scene; largest error of "
                          f"Pi1 {max(errors):.1e} at rtol 1e-6 against rtol 1e-9; {machine_conditions()}")
        write_rows(args.measurements, "bearings", COMMAND, [row])


if __name__ == "__main__":
    main()
