"""The cost of contents that rock against the same contents that only slide, measured side by side.

A block that can rock (:attr:`isoslide.Scene.tips`) adds its tilt and its rate to the states the
engine integrates, events for its impacts, its overturning and its pivot slipping, and a cascade of
impacts as its rocking dies out.  Each rocking scene of :data:`POINTS` is timed interleaved with its
twin without ``Pi18`` (the same building, pulse and contents' mass and friction, contents that only
slide), under the Ricker and rectangular pulses (:data:`PULSES`) and under the bundled records
(:data:`isoslide.records.samples`, per sample).  The ratio of the medians of the two per-scene costs
is the aim of :data:`TARGET_RATIO`; rows where the rocking answer is an overturning (which stops the
response) are shown apart, since they cost less.  ``python -m isoslide.bench --rocking-only`` prints
the table.
"""
from __future__ import annotations

import dataclasses
import sys

import numpy as np

from .. import records
from ..scene import Scene
from ..solver import solve
from .timing import assembly_times, timed_solve

POINTS = {
    "fixed base": dict(pi3=0.0),
    "linear isolator (pi3 2)": dict(pi3=2.0, pi4=0.1),
    "friction pendulum (pi3 3, pi9 0.05)": dict(pi3=3.0, pi4=0.0, pi9=0.05),
    "3 storeys, roof": dict(pi3=2.5, pi4=0.1, pi11=0.6, pi12=0.3, pi13=0.02, storeys=3, floor="roof"),
}
"""Buildings of the rocking section (keyword arguments of :class:`isoslide.Scene`)."""
BLOCK = dict(pi2=0.8, pi8=0.05, pi18=0.25, pi19=2.0)
"""The contents: ``mu_s = Pi2 Pi21 tan(alpha) = 0.2 Pi21``, so the block tips for ``Pi21 > 1.25``."""
INTENSITIES = (1.5, 2.0, 3.0)
"""``Pi21`` of the rocking scenes."""
PULSES = ("ricker", "rectangular")
"""Pulses of the rocking scenes."""
RECORD_BUILDING = "linear isolator (pi3 2)"
"""Building under which the bundled records run."""
TARGET_RATIO = 3.0
"""Aim: a rocking scene costs at most this many times the same scene sliding."""


def _pair(building: dict, pulse, pi21: float) -> tuple:
    rock = Scene(pulse=pulse, pi21=pi21, **BLOCK, **building)
    return rock, dataclasses.replace(rock, pi18=None, pi19=None, pi21=None)


def _time(scenes: list, repeats: int) -> np.ndarray:
    """Median time (s) of :func:`isoslide.solve` per scene, the scenes interleaved ``repeats`` times."""
    t = np.zeros((repeats, len(scenes)))
    for r in range(repeats):
        for k, sc in enumerate(scenes):
            t[r, k], _ = timed_solve(sc)
    return np.median(t, axis=0)


def run(repeats: int = 7) -> dict:
    """Time every rocking scene beside its sliding twin; the records per sample at :data:`RECORD_BUILDING`."""
    rows = []
    for name, spec in POINTS.items():
        for pulse in PULSES:
            for pi21 in INTENSITIES:
                rows.append({"building": name, "pulse": pulse, "pi21": pi21, "scenes": _pair(spec, pulse, pi21)})
    for name in records.samples():
        pair = _pair(POINTS[RECORD_BUILDING], records.sample(name), INTENSITIES[0])
        rows.append({"building": RECORD_BUILDING, "pulse": name, "pi21": INTENSITIES[0], "scenes": pair,
                     "samples": pair[0].pulse.param_array.shape[0] - 2})
    flat = [sc for r in rows for sc in r["scenes"]]
    for sc in flat[:2]:   # compile or load every path before timing
        solve(sc)
    times = _time(flat, repeats)
    assembly = assembly_times(flat[::2], repeats)
    for k, r in enumerate(rows):
        rock, slide = r.pop("scenes")
        sol, twin = solve(rock), solve(slide)
        r.update(rock_s=float(times[2 * k]), slide_s=float(times[2 * k + 1]), assembly_s=float(assembly[k]),
                 overturned=sol.overturned, theta_max=sol.theta_max, modes="+".join(sol.modes), events=sol.n_events,
                 steps=sol.n_steps, slide_steps=twin.n_steps, slide_events=twin.n_events, slide_model=twin.model)
    return {"rows": rows, "repeats": repeats}


def report(res: dict, file=sys.stdout) -> dict:
    """Print the rocking section: each scene's cost beside its sliding twin's, the aim; returns the summary."""
    p = lambda *a: print(*a, file=file)  # noqa: E731
    rows = res["rows"]
    p(f"rocking: a block (pi2 {BLOCK['pi2']:g}, pi8 {BLOCK['pi8']:g}, b/h {BLOCK['pi18']:g}, pT_p {BLOCK['pi19']:g}) "
      f"that rocks beside the same contents sliding (no pi18); median of {res['repeats']} interleaved runs")
    hdr = (f"{'building':36s} {'pulse':12s} {'pi21':>5s} {'us rock':>9s} {'us slide':>9s} {'ratio':>6s} "
           f"{'us asm':>7s} {'steps':>11s} {'events':>9s}  modes")
    p(hdr)
    p("-" * len(hdr))
    for r in rows:
        if "samples" in r:
            continue
        p(f"{r['building']:36s} {r['pulse']:12s} {r['pi21']:5g} {1e6 * r['rock_s']:9.1f} {1e6 * r['slide_s']:9.1f} "
          f"{r['rock_s'] / r['slide_s']:6.2f} {1e6 * r['assembly_s']:7.1f} {r['steps']:5d}/{r['slide_steps']:<5d} "
          f"{r['events']:4d}/{r['slide_events']:<4d}  {r['modes']}"
          f"{' overturned' if r['overturned'] else ''}")
    pulses = [r for r in rows if "samples" not in r]
    kept = [r["rock_s"] / r["slide_s"] for r in pulses if not r["overturned"]]
    ratio = float(np.median(kept)) if kept else float("nan")
    worst = float(max(kept)) if kept else float("nan")
    recs = [r for r in rows if "samples" in r]
    summ = {"ratio_median": ratio, "ratio_max": worst, "rows": len(pulses)}
    p(f"aim: a rocking scene (not overturning) at most {TARGET_RATIO:g}x the same scene sliding -> "
      f"{'MET' if worst <= TARGET_RATIO else 'NOT MET'} (median ratio {ratio:.2f}, largest {worst:.2f}, over "
      f"{len(kept)} scenes)")
    slow = [r for r in pulses if not r["overturned"] and r["rock_s"] > TARGET_RATIO * r["slide_s"]]
    if slow:
        steps = float(np.median([r["steps"] / r["slide_steps"] for r in slow]))
        per_step = float(np.median([(r["rock_s"] / r["steps"]) / (r["slide_s"] / r["slide_steps"]) for r in slow]))
        summ.update(slow=len(slow), slow_steps_ratio=steps, slow_step_cost_ratio=per_step)
        events = [r["events"] for r in slow]
        p(f"limit: the {len(slow)} scenes past the aim ({', '.join(sorted({r['building'] for r in slow}))}) take "
          f"{steps:.1f}x their sliding twins' steps (median; the rocking block's events per scene "
          f"{min(events)} to {max(events)}: impacts as its rocking dies out) at {per_step:.1f}x the cost per step: "
          f"they run the general building's solver (its assembly about "
          f"{1e6 * float(np.median([r['assembly_s'] for r in slow])):.0f} us per scene) where their twins run the "
          f"paper model's own")
    if recs:
        rock = np.array([1e9 * r["rock_s"] / r["samples"] for r in recs])
        slide = np.array([1e9 * r["slide_s"] / r["samples"] for r in recs])
        summ.update(records=len(recs), rock_ns_per_sample=float(np.median(rock)),
                    slide_ns_per_sample=float(np.median(slide)))
        p(f"records: {len(recs)} bundled records under the {RECORD_BUILDING} at pi21 {INTENSITIES[0]:g}: "
          f"{np.median(rock):.1f} ns per sample rocking, {np.median(slide):.1f} sliding (medians; "
          f"{', '.join(sorted({r['modes'] for r in recs}))})")
    return summ
