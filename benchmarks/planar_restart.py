"""Candidate first steps after a planar transition: Runge-Kutta steps and errors of the bench's planar scenes.

Run: ``python benchmarks/planar_restart.py [NAME ...]`` (a few minutes per candidate: each compiles
the kernels afresh).  The candidates are compiled-in constants of
:mod:`isoslide.engine.planar_kernel` (``RESTART_MODE``, ``USE_LAM``); for each one this copies the
checkout's ``src`` and ``config`` to a temporary folder, sets the constant there and solves, in a
new process with its own numba cache, the planar scenes of the bench
(:data:`isoslide.accuracy.scenes.PLANAR_BUILDINGS` at each of
:data:`~isoslide.accuracy.scenes.PLANAR_POINTS`) at the default tolerance and at ``rtol = 1e-12``.
It prints per building the Runge-Kutta steps over the six points and the largest relative error
of ``Pi1``.
"""

import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CANDIDATES = {
    "h_restart": {"RESTART_MODE": "0", "USE_LAM": "False"},
    "derivatives+series": {"RESTART_MODE": "1", "USE_LAM": "False"},
    "half-last": {"RESTART_MODE": "2", "USE_LAM": "False"},
    "series": {"RESTART_MODE": "3", "USE_LAM": "False"},
    "derivatives": {"RESTART_MODE": "4", "USE_LAM": "False"},
    "slide-time": {"RESTART_MODE": "0", "USE_LAM": "True"},
}
"""Candidates by name: the kernel's constants each sets."""
WORKER = """
import json
from isoslide import Scene, solve
from isoslide.accuracy.scenes import PLANAR_BUILDINGS, PLANAR_EXCITATION, PLANAR_POINTS
out = {}
for name, kw in PLANAR_BUILDINGS.items():
    steps, err = 0, 0.0
    for pt in PLANAR_POINTS:
        sc = Scene(**{**pt, **kw}, **PLANAR_EXCITATION)
        s = solve(sc)
        c = solve(sc, rtol=1e-12).pi1
        steps += s.n_steps
        err = max(err, abs(s.pi1 - c) / c)
    out[name] = [steps, err]
print(json.dumps(out))
"""


def measure(name: str) -> dict:
    """Steps and largest error per building of one candidate, compiled in a copy of the checkout."""
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        shutil.copytree(ROOT / "src", tmp / "src", symlinks=True,
                        ignore=shutil.ignore_patterns("*.nbi", "*.nbc", "__pycache__"))
        shutil.copytree(ROOT / "config", tmp / "config")
        kernel = tmp / "src/isoslide/engine/planar_kernel.py"
        text = kernel.read_text()
        for const, value in CANDIDATES[name].items():
            text = re.sub(rf"^{const} = .*$", f"{const} = {value}", text, count=1, flags=re.M)
        kernel.write_text(text)
        env = dict(os.environ, PYTHONPATH=str(tmp / "src"), NUMBA_CACHE_DIR=str(tmp / "nbc"),
                   ISOSLIDE_SHIPPED_KERNELS="0")
        out = subprocess.run([sys.executable, "-c", WORKER], env=env, capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main() -> None:
    names = sys.argv[1:] or list(CANDIDATES)
    for name in names:
        res = measure(name)
        total = sum(v[0] for v in res.values())
        worst = max(v[1] for v in res.values())
        per = " / ".join(f"{v[0]}" for v in res.values())
        errs = " / ".join(f"{v[1]:.1e}" for v in res.values())
        print(f"{name:20s} steps {total:6d} ({per})  largest error {worst:.1e} ({errs})", flush=True)


if __name__ == "__main__":
    main()
