"""Cost of one fragility analysis, and of its floor motion (PFA, PFV), on a configuration.

Run: ``python benchmarks/fragility_cost.py [OVERLAY.yaml] [STRIDE]`` (default
``config/fragility_large.yaml`` and every 500th analysis, about 1 min).  Solves a strided subset of
the analyses of each base (every record, stripe and friction level represented), after the
kernel's compilation, twice: with the history and the floor peaks (what the study does) and for
``u_max`` alone, and prints the cost per analysis of each, their ratio and the projected CPU time
of the whole configuration.
"""

import sys
import time

import numpy as np

import isoslide.config
from isoslide import solver
from isoslide.studies import fragility_study as fs


def main() -> None:
    overlay = sys.argv[1] if len(sys.argv) > 1 else "config/fragility_large.yaml"
    stride = int(sys.argv[2]) if len(sys.argv) > 2 else 500
    settings = fs.fragility_settings(isoslide.config.load(None, overlay))
    study = fs.check_settings(settings)
    solver.warm_up(records=True)
    total = 0.0
    for base in [fs.base_of(n) for n in fs.dataset_names(settings)]:
        idx = np.arange(0, study.size, stride)
        cost = {}
        for floor in (True, False):
            t = time.perf_counter()
            fs.solve_analyses(study, idx, base, floor=floor)
            cost[floor] = (time.perf_counter() - t) / idx.size
        total += cost[True] * study.size
        print(f"{base:10s} {idx.size} of {study.size} analyses: {cost[True] * 1e3:.2f} ms each with the floor "
              f"peaks, {cost[False] * 1e3:.2f} ms for u_max alone (ratio {cost[True] / cost[False]:.2f})")
    print(f"projected solving time of {overlay}: {total:.0f} CPU s ({total / 60:.1f} CPU min)")


if __name__ == "__main__":
    main()
