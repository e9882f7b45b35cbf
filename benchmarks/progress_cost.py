"""Cost of the progress lines: ``solve_many`` on 2000 scenes with the log off and on.

Run: ``python benchmarks/progress_cost.py`` (about 10 s).  Prints the median of 5 runs with the
``isoslide.solver`` log off (level WARNING), on (INFO to a file, the default 5 s interval) and on
with a line every 10 ms (the cost when lines are actually written), and the ratios to "off".
"""

import functools
import logging
import tempfile
import time
from pathlib import Path

import numpy as np

import isoslide
from isoslide import solver
from isoslide.store.progress import Progress

SCENES = [isoslide.Scene(pi2=p2, pi3=p3, pi4=0.1, pi5=0.8, pi6=300.0)
          for p2 in np.linspace(0.05, 0.6, 40) for p3 in np.linspace(0.5, 3.0, 50)]


def _timed() -> float:
    t = time.perf_counter()
    solver.solve_many(SCENES)
    return time.perf_counter() - t


def main() -> None:
    solver.warm_up()
    solver.solve_many(SCENES[:50])
    root = logging.getLogger()
    log_file = Path(tempfile.mkdtemp()) / "progress.log"
    handler = logging.FileHandler(log_file, mode="w")
    handler.setFormatter(logging.Formatter("%(asctime)s %(levelname)s %(name)s: %(message)s"))
    default = solver.Progress
    times = {"off": [], "on": [], "often": []}
    for _ in range(5):
        root.setLevel(logging.WARNING)
        root.removeHandler(handler)
        times["off"].append(_timed())
        root.setLevel(logging.INFO)
        root.addHandler(handler)
        times["on"].append(_timed())
        solver.Progress = functools.partial(Progress, interval=0.01)
        times["often"].append(_timed())
        solver.Progress = default
    root.removeHandler(handler)
    med = {k: float(np.median(v)) for k, v in times.items()}
    print(f"{len(SCENES)} scenes, median of 5: log off {med['off']:.3f} s; INFO on, 5 s interval "
          f"{med['on']:.3f} s (ratio {med['on'] / med['off']:.3f}); a line every 10 ms {med['often']:.3f} s "
          f"(ratio {med['often'] / med['off']:.3f}); {sum(1 for _ in open(log_file))} lines in {log_file}")


if __name__ == "__main__":
    main()
