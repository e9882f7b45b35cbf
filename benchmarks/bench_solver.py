"""Solver benchmark (not a timed test): ``python benchmarks/bench_solver.py [options]``.

Same as ``python -m isoslide.bench``: per-scene cost and error of ``isoslide.solve`` at its
default accuracy against a plain SciPy ``solve_ivp`` event-driven solve and the paper-style
regularised solve, measured side by side in one run.  ``--help`` lists the options.
"""

import sys

from isoslide.bench import main

if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
