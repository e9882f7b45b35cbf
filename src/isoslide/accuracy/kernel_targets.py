"""Benchmark: the kernels compiled for this processor against the portable ones, side by side in one run.

``python -m isoslide.bench --cpu-targets`` starts one worker process per target of :data:`TARGETS`:
numba compiling for the host processor (``ISOSLIDE_CPU_TARGET=host``), for the portable x86-64
baseline the shipped kernels are compiled for (:mod:`isoslide.jit_cache`) and for the x86-64-v3
level. Each loads or compiles its kernels first (a target without shipped entries compiles once,
into numba's cache), then the parent asks them in turn, building by building with the order of the
targets rotating, to solve every point of that building of the buildings section
(:data:`isoslide.accuracy.scenes.BUILDINGS` on :data:`isoslide.accuracy.scenes.BUILDING_POINTS`: the paper's scene and
every building class) once each. All therefore run on the same machine under the same load; the
report gives each class's median cost per scene tuned to the host, the ratio of the other targets'
to it, and the largest relative difference of ``Pi1`` between the targets (their floating point
may differ: another target may fuse or vectorise other operations).
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import time

import numpy as np

from .. import jit_cache
from ..scene import Scene
from ..solver import solve
from .scenes import BUILDING_POINTS, BUILDINGS
from .timing import timed_solve

WORKER = [sys.executable, "-m", "isoslide.accuracy.kernel_targets", "--worker"]
TARGETS = {
    "host": {"ISOSLIDE_CPU_TARGET": "host"},
    "portable": {"ISOSLIDE_CPU_TARGET": "portable"},
    "x86-64-v3": {"NUMBA_CPU_NAME": "x86-64-v3", "NUMBA_CPU_FEATURES": ""},
}
"""The targets timed side by side (environment of each worker): tuned to this processor, the portable
x86-64 baseline the shipped kernels are compiled for, and the x86-64-v3 level (AVX2, FMA; Intel from
2013, AMD from 2015), the alternative that would leave older processors out."""


def _worker() -> int:
    """Worker loop: load the kernels, report the target, then time one round per ``round`` line."""
    scenes = {name: [Scene(**pt, **kw) for pt in BUILDING_POINTS] for name, kw in BUILDINGS.items()}
    t0 = time.perf_counter()
    for scs in scenes.values():
        solve(scs[0])
    cpu, features = jit_cache.target_in_force()
    print(json.dumps({"cpu": cpu, "features": features, "ready_s": time.perf_counter() - t0}), flush=True)
    for line in sys.stdin:
        name = line.rstrip("\n")
        if name not in scenes:
            break
        times, pi1 = [], []
        for sc in scenes[name]:
            seconds, sol = timed_solve(sc)
            times.append(seconds)
            pi1.append(sol.pi1)
        print(json.dumps({"times": times, "pi1": pi1}), flush=True)
    return 0


def _start(target: str) -> subprocess.Popen:
    env = {k: v for k, v in os.environ.items()
           if k not in ("NUMBA_CPU_NAME", "NUMBA_CPU_FEATURES", "ISOSLIDE_CPU_TARGET")}
    env.update(TARGETS[target])
    return subprocess.Popen(WORKER, env=env, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)


def _read(proc: subprocess.Popen) -> dict:
    line = proc.stdout.readline()
    if not line:
        raise RuntimeError(f"benchmark worker exited with status {proc.wait()}")
    return json.loads(line)


def run(rounds: int = 15) -> dict:
    """Time the buildings section on every target of :data:`TARGETS`, interleaved building by building.

    In each round every building's points are solved once on each target in turn, the order of the
    targets rotating from one building to the next.

    Returns
    -------
    dict
        ``targets`` (per target: ``cpu``, ``features``, ``ready_s`` the seconds its kernels took to
        load or compile), ``times`` (per target and building, per point the list over rounds of
        seconds per solve), ``pi1`` (per target and building, the last ``Pi1`` of each point),
        ``rounds``.
    """
    if not jit_cache.choose_target(environ={}).portable:
        raise RuntimeError(f"no portable kernels for this processor: {jit_cache.choose_target(environ={}).reason}")
    names = list(TARGETS)
    procs = {t: _start(t) for t in names}
    try:
        info = {t: _read(p) for t, p in procs.items()}
        times = {t: {b: None for b in BUILDINGS} for t in names}
        pi1 = {t: {} for t in names}
        turn = 0
        for _ in range(rounds):
            for b in BUILDINGS:
                turn += 1
                for t in names[turn % len(names):] + names[:turn % len(names)]:
                    procs[t].stdin.write(b + "\n")
                    procs[t].stdin.flush()
                    out = _read(procs[t])
                    if times[t][b] is None:
                        times[t][b] = [[] for _ in out["times"]]
                    for k, sec in enumerate(out["times"]):
                        times[t][b][k].append(sec)
                    pi1[t][b] = out["pi1"]
    finally:
        for p in procs.values():
            if p.stdin:
                p.stdin.close()
            p.wait()
    return {"targets": info, "times": times, "pi1": pi1, "rounds": rounds}


def report(res: dict, file=sys.stdout) -> dict:
    """Print each building class's cost per scene on every target and its ratio to host-tuned; returns them."""
    p = lambda *a: print(*a, file=file)  # noqa: E731
    info = res["targets"]
    names = [t for t in TARGETS if t != "host"]
    which = ", ".join(f"{t} ({info[t]['cpu']})" for t in TARGETS)
    p(f"kernel targets: {which}; every building class on "
      f"the buildings section's points, median of {res['rounds']} rounds interleaved building by building")
    p("kernels ready in: " + ", ".join(f"{t} {info[t]['ready_s']:.1f} s" for t in TARGETS) + " (loaded or compiled)")
    hdr = f"{'building':48s} {'host us':>8s}" + "".join(f" {t + '/host':>14s}" for t in names) + f" {'max dPi1':>9s}"
    p(hdr)
    p("-" * len(hdr))
    summ = {}
    for b, per_point in res["times"]["host"].items():
        host = np.array([np.median(x) for x in per_point])
        row = {"host_us": float(1e6 * np.median(host))}
        a = np.array(res["pi1"]["host"][b])
        diff = 0.0
        for t in names:
            other = np.array([np.median(x) for x in res["times"][t][b]])
            row[f"{t}_us"] = float(1e6 * np.median(other))
            row[f"{t}_ratio"] = float(np.median(other / host))
            c = np.array(res["pi1"][t][b])
            diff = max(diff, float(np.max(np.abs(a - c) / np.maximum(np.abs(a), 1e-300))))
        row["pi1_rel_diff"] = diff
        summ[b] = row
        p(f"{b:48s} {row['host_us']:8.1f}" + "".join(f" {row[f'{t}_ratio']:14.3f}" for t in names) + f" {diff:9.1e}")
    for t in names:
        ratios = [v[f"{t}_ratio"] for v in summ.values()]
        p(f"{t} / host over the classes: median {np.median(ratios):.3f}, largest {max(ratios):.3f}")
    return summ


if __name__ == "__main__":
    if sys.argv[1:] == ["--worker"]:
        sys.exit(_worker())
    report(run())
