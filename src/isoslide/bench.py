"""Benchmark: per-scene cost and error of isoslide against its peers, measured side by side.

Run ``python -m isoslide.bench`` (``--help`` for options; ``benchmarks/bench_solver.py`` calls
the same).  On the representative scene set of :mod:`isoslide.accuracy` (a fixed-seed subsample
of every paper study plus the hard cases) it times, scene after scene and interleaved:

* ``isoslide.solve(scene)`` at its default accuracy (compiled event-driven DOP853);
* the plain SciPy event-driven solve (:func:`isoslide.peers.solve_reference`, ``solve_ivp``
  DOP853 with events) at the same nominal tolerance;
* the paper-style regularised solve (:func:`isoslide.peers.solve_regularized`, stiff
  elastic-plastic spring, SciPy Radau) on an evenly spread subset (it takes seconds per scene).

Errors are relative to the converged answer (isoslide at ``rtol = 1e-12``, every reduction
off).

A second section times the bundled records (:func:`isoslide.records.samples`) at one Pi point,
record after record and interleaved, through both exact paths: the exact piecewise propagation
that ``solve`` takes for a record with Coulomb contents (:mod:`isoslide.engine.piecewise`) and the
integrator, both as ``solve(..., piecewise_path=False)`` runs it (Coulomb and one-way reductions,
the solve before the piecewise path) and as ``solve(..., model="full")`` runs it.  It prints the cost per record sample (median and
largest over the records), the total time for all records and each path's error against the
integrator at ``rtol = 1e-12`` (:func:`run_records`, :func:`report_records`).  It prints the medians, the ratios of per-scene costs on the same scenes, the target
check (median <= 0.1 ms per scene at <= 1e-6 relative error) and where the time goes (steps
per scene by scene class).

A planar section (``--planar-only`` alone; :func:`run_planar`, :func:`run_pairs`) times, with the
compiled kernels readied first, planar scenes of a few building classes beside the same scenes
without their second horizontal component (the goal: planar at most 3x the 1-D cost), then
recorded pairs of :data:`PAIR_SUITE` run as recorded, per analysis and per sample of the x
component (the goal: at most 0.5 us per sample on median), beside the x component alone, and the
cost of one analysis of the planar fragility study at full size (``config/fragility_p695.yaml`` of
a checkout; :func:`run_fragility_cost`): a planar and two 1-D solves with the floor's peaks, per
building, and the CPU time the whole study takes at that cost.

A rocking section (``--rocking-only`` alone; :mod:`isoslide.accuracy.rocking_cost`) times contents
that rock beside the same contents sliding, on pulses and per sample of the bundled records (the
goal: at most 3x).

Timings are wall-clock on whatever else the machine is running:
read ratios, which are measured side by side, rather than absolute figures.
"""

from __future__ import annotations

import argparse
import functools
import json
import math
import platform
import sys
import time
from pathlib import Path

import numpy as np

from . import accuracy, config, records
from .accuracy import kernel_targets, measurements, opensees_cost, rocking_cost
from .accuracy.scenes import (BUILDING_POINTS, BUILDINGS, PAIR_LAG, PAIR_POINTS, PAIR_SUITE, PENDULUM,  # noqa: F401
                              PLANAR_BUILDINGS, PLANAR_EXCITATION, PLANAR_POINTS, SPEED_PENDULUM, STOREYS,
                              STOREYS_NAME, TARGET_TFP_RATIO, TFP_PENDULUM, recorded_pairs)
from .accuracy.timing import assembly_times, timed_solve
from .engine import building
from .model.parts import building_of
from .scene import Scene
from .studies import fragility_planar
from .solver import DEFAULT_RTOL, solve, warm_up

TARGET_MS = 0.1
TARGET_ERROR = 1e-6
RECORD_POINT = {"pi2": 0.2, "pi3": 1.0, "pi4": 0.1, "pi5": 1.0, "pi6": 0.0, "pi7": 0.0, "pi8": 1e-5}
"""Pi point of the records section (the record study's fixed groups, Pi2 = 0.2, Pi3 = 1)."""
RECORD_PATHS = {"pw": {}, "auto": {"piecewise_path": False}, "int": {"model": "full"}}
"""Paths timed on the records: ``solve`` keyword arguments by short name."""
TARGET_RECORDS_MS = 30.0
"""Target: all bundled records at one Pi point in at most this many milliseconds (piecewise path)."""
TARGET_NS_PER_SAMPLE = 150.0
"""Target: median cost per record sample of the piecewise path, nanoseconds."""


def _median(a):
    a = np.asarray([x for x in a if x is not None and math.isfinite(x)], dtype=float)
    return float(np.median(a)) if a.size else math.nan


def _rel(p, c):
    if not math.isfinite(p):
        return math.nan
    if c == 0.0:
        return 0.0 if p == 0.0 else math.inf
    return abs(p - c) / c


def run(per_study: int = 6, hard: bool = True, repeats: int = 15, peer_repeats: int = 3,
        reference_rtol: float = 1e-6, regularized_scenes: int = 6, stiffness: float = 1e6,
        regularized_rtol: float = 1e-6, horizon: float = 50.0, max_work: int = 2_000_000,
        log=None) -> dict:
    """Measure; return a dict of per-scene records and summaries (see :func:`report`)."""
    settings = accuracy.settings_from({"per_study": per_study, "hard": hard, "horizon": horizon})
    entries = accuracy.scene_set(None, settings)
    accuracy.warm_up()
    ref = accuracy.Setting(f"scipy event-driven rtol={reference_rtol:g}", "reference", reference_rtol)
    reg = accuracy.Setting(f"regularized K={stiffness:.0e}", "regularized", regularized_rtol, stiffness)
    reg_idx = set(entries.subset(regularized_scenes))
    rows = []
    for i, e in enumerate(entries):
        sc = e.scene
        conv = solve(sc, rtol=1e-12, horizon=horizon, model="full").pi1
        t_iso = []
        t_ref = []
        for r in range(max(repeats, peer_repeats)):
            # interleave: isoslide, then the reference, on the same scene
            if r < repeats:
                seconds, s = timed_solve(sc, horizon=horizon)
                t_iso.append(seconds)
            if r < peer_repeats:
                p_ref, t, w_ref, st_ref = accuracy.run_setting(ref, sc, horizon, max_work)
                t_ref.append(t if st_ref == "ok" else math.nan)
        row = {
            "i": i, "cls": e.cls, "label": e.label, "pi1": conv, "model": s.model,
            "iso_ms": 1e3 * _median(t_iso), "iso_err": _rel(s.pi1, conv), "steps": s.n_steps,
            "events": s.n_events, "settled": s.settled,
            "ref_ms": 1e3 * _median(t_ref), "ref_err": _rel(p_ref, conv), "ref_nfev": w_ref,
            "ref_status": st_ref, "reg_ms": math.nan, "reg_err": math.nan, "reg_status": "not-run",
        }
        if i in reg_idx:
            p_reg, t, w, st = accuracy.run_setting(reg, sc, horizon, max_work)
            row.update(reg_ms=1e3 * t if st == "ok" else math.nan, reg_err=_rel(p_reg, conv),
                       reg_status=st)
        rows.append(row)
        if log:
            log(f"  scene {i:3d} {e.cls:15s} iso {row['iso_ms']:8.3f} ms  ref {row['ref_ms']:9.2f} ms"
                + (f"  reg {row['reg_ms']:9.1f} ms" if i in reg_idx else ""))
    return {"rows": rows, "reference": ref.name, "regularized": reg.name, "repeats": repeats,
            "peer_repeats": peer_repeats, "rtol": DEFAULT_RTOL, "horizon": horizon}


def summarize(res: dict) -> dict:
    """Medians, side-by-side ratios, target check and the cost by scene class."""
    rows = res["rows"]
    iso = np.array([r["iso_ms"] for r in rows])
    sliding = np.array([r["pi1"] > 0 for r in rows])
    out = {"n": len(rows), "iso_median_ms": float(np.median(iso)),
           "iso_median_ms_sliding": float(np.median(iso[sliding])) if sliding.any() else math.nan}
    err = np.array([r["iso_err"] for r in rows])
    sig = np.array([r["pi1"] >= 1e-6 for r in rows])
    out["iso_err_median"] = float(np.nanmedian(err[sliding]))
    out["iso_err_max"] = float(np.nanmax(err[sliding]))
    out["iso_err_max_significant"] = float(np.nanmax(err[sig]))
    for peer in ("ref", "reg"):
        ms = np.array([r[f"{peer}_ms"] for r in rows])
        ok = np.isfinite(ms)
        e = np.array([r[f"{peer}_err"] for r in rows])
        out[f"{peer}_n"] = int(ok.sum())
        out[f"{peer}_failed"] = int(sum(r[f"{peer}_status"] in ("error", "over_budget") for r in rows))
        out[f"{peer}_median_ms"] = float(np.median(ms[ok])) if ok.any() else math.nan
        out[f"{peer}_iso_median_ms_same"] = float(np.median(iso[ok])) if ok.any() else math.nan
        out[f"{peer}_ratio_median"] = float(np.median(ms[ok] / iso[ok])) if ok.any() else math.nan
        es = e[ok & sliding]
        out[f"{peer}_err_median"] = float(np.nanmedian(es)) if es.size else math.nan
        out[f"{peer}_err_max"] = float(np.nanmax(es)) if es.size else math.nan
        es = e[ok & sig]
        out[f"{peer}_err_max_significant"] = float(np.nanmax(es)) if es.size else math.nan
    classes = {}
    for r in rows:
        classes.setdefault(r["cls"], []).append(r)
    by = []
    for c, rs in classes.items():
        ms = np.array([r["iso_ms"] for r in rs])
        st = np.array([r["steps"] for r in rs], dtype=float)
        by.append({"class": c, "n": len(rs), "median_ms": float(np.median(ms)), "max_ms": float(ms.max()),
                   "median_steps": float(np.median(st)), "max_steps": float(st.max()),
                   "median_events": float(np.median([r["events"] for r in rs])),
                   "us_per_step": float(np.median(1e3 * ms / np.maximum(st, 1))),
                   "unsettled": int(sum(not r["settled"] for r in rs))})
    by.sort(key=lambda d: -d["median_ms"])
    out["by_class"] = by
    steps = np.array([r["steps"] for r in rows], dtype=float)
    out["median_steps"] = float(np.median(steps))
    out["us_per_step"] = float(np.median(1e3 * iso / np.maximum(steps, 1)))
    out["target_met"] = bool(out["iso_median_ms"] <= TARGET_MS and out["iso_err_max_significant"] <= TARGET_ERROR)
    return out


def _header(p, hdr: str) -> None:
    """Print a table's column header ``hdr`` and a rule as long under it (``p`` prints a line)."""
    p(hdr)
    p("-" * len(hdr))


def report(res: dict, summ: dict, file=sys.stdout) -> None:
    """Print the benchmark in plain text."""
    p = lambda *a: print(*a, file=file)  # noqa: E731
    p(f"isoslide benchmark: {summ['n']} scenes (paper studies subsampled + hard cases), "
      f"Python {platform.python_version()}, {platform.machine()}, one process, one thread")
    p(f"timing: isoslide median of {res['repeats']} runs per scene, SciPy reference median of "
      f"{res['peer_repeats']} (interleaved, same scene); regularized once per scene on a subset")
    p("errors: relative to isoslide at rtol=1e-12 with every reduction off; 'max*' over scenes "
      "with Pi1 >= 1e-6 (below, relative error is not meaningful)")
    p("")
    hdr = f"{'method':40s} {'scenes':>6s} {'median ms':>10s} {'x isoslide':>10s} {'med err':>9s} {'max err':>9s} {'max* err':>9s}"
    _header(p, hdr)
    p(f"{'isoslide.solve (default rtol=1e-6)':40s} {summ['n']:6d} {summ['iso_median_ms']:10.3f} {1.0:10.1f} "
      f"{summ['iso_err_median']:9.1e} {summ['iso_err_max']:9.1e} {summ['iso_err_max_significant']:9.1e}")
    for peer, name in (("ref", res["reference"]), ("reg", res["regularized"])):
        if summ[f"{peer}_n"] == 0:
            p(f"{name:40s} {0:6d}  (not run)")
            continue
        p(f"{name:40s} {summ[f'{peer}_n']:6d} {summ[f'{peer}_median_ms']:10.3f} "
          f"{summ[f'{peer}_ratio_median']:10.1f} {summ[f'{peer}_err_median']:9.1e} "
          f"{summ[f'{peer}_err_max']:9.1e} {summ[f'{peer}_err_max_significant']:9.1e}"
          + (f"   ({summ[f'{peer}_failed']} failed/timed out)" if summ[f"{peer}_failed"] else ""))
        p(f"{'':40s} {'':6s} (isoslide on the same scenes: {summ[f'{peer}_iso_median_ms_same']:.3f} ms; "
          f"'x isoslide' = median of per-scene ratios)")
    p("")
    verdict = "MET" if summ["target_met"] else "NOT MET"
    p(f"target: median <= {TARGET_MS} ms per scene at <= {TARGET_ERROR:g} relative error -> {verdict}: "
      f"median {summ['iso_median_ms']:.3f} ms (sliding scenes {summ['iso_median_ms_sliding']:.3f} ms), "
      f"max error {summ['iso_err_max_significant']:.1e}")
    p(f"where the time goes: median {summ['median_steps']:.0f} integrator steps per scene at "
      f"{summ['us_per_step']:.2f} us per step (steps include rejected, event-location and "
      f"verification steps)")
    p("")
    hdr = f"{'scene class':16s} {'n':>3s} {'median ms':>10s} {'max ms':>9s} {'med steps':>10s} {'max steps':>10s} {'med events':>10s} {'us/step':>8s} {'unsettled':>9s}"
    _header(p, hdr)
    for b in summ["by_class"]:
        p(f"{b['class']:16s} {b['n']:3d} {b['median_ms']:10.3f} {b['max_ms']:9.3f} {b['median_steps']:10.0f} "
          f"{b['max_steps']:10.0f} {b['median_events']:10.0f} {b['us_per_step']:8.2f} {b['unsettled']:9d}")


def run_records(point: dict | None = None, repeats: int = 7, names=None) -> dict:
    """Time both exact paths on the bundled records at one Pi point; return per-record rows.

    Parameters
    ----------
    point : dict, optional
        Pi-groups ``pi2 ... pi8`` (default :data:`RECORD_POINT`).
    repeats : int
        Timed runs per record and path (the median is kept), interleaved.
    names : sequence of str, optional
        Record names (default: every bundled sample).
    """
    point = dict(RECORD_POINT if point is None else point)
    names = records.samples() if names is None else tuple(names)
    scenes = [Scene(pulse=records.sample(n), **point) for n in names]
    for sc in scenes[:1]:   # compile or load every path before timing
        solve(sc)
        solve(sc, piecewise_path=False)
        solve(sc, model="full")
    rows = []
    for name, sc in zip(names, scenes, strict=True):
        conv = solve(sc, rtol=1e-12, model="full").pi1
        times = {path: [] for path in RECORD_PATHS}
        sols = {}
        for _ in range(repeats):
            for path, kw in RECORD_PATHS.items():
                t0 = time.perf_counter()
                sols[path] = solve(sc, **kw)
                times[path].append(time.perf_counter() - t0)
        row = {"record": name, "samples": sc.pulse.param_array.shape[0] - 2, "pi1": conv}
        for path in RECORD_PATHS:
            row.update({f"{path}_model": sols[path].model, f"{path}_s": _median(times[path]),
                        f"{path}_err": _rel(sols[path].pi1, conv), f"{path}_events": sols[path].n_events})
        rows.append(row)
    return {"rows": rows, "point": point, "repeats": repeats}


def summarize_records(res: dict) -> dict:
    """Per-path cost per sample (median, max), total time and errors (median, max) over the records."""
    rows = res["rows"]
    out = {"n": len(rows), "samples": int(sum(r["samples"] for r in rows))}
    for path in RECORD_PATHS:
        per = np.array([r[f"{path}_s"] / r["samples"] for r in rows])
        err = np.array([r[f"{path}_err"] for r in rows])
        out[f"{path}_ns_median"] = float(1e9 * np.median(per))
        out[f"{path}_ns_max"] = float(1e9 * per.max())
        out[f"{path}_total_ms"] = float(1e3 * sum(r[f"{path}_s"] for r in rows))
        out[f"{path}_err_median"] = float(np.median(err))
        out[f"{path}_err_max"] = float(err.max())
    out["target_met"] = bool(out["pw_total_ms"] <= TARGET_RECORDS_MS and out["pw_ns_median"] <= TARGET_NS_PER_SAMPLE
                             and out["pw_err_max"] <= TARGET_ERROR)
    return out


def report_records(res: dict, summ: dict, file=sys.stdout) -> None:
    """Print the records section in plain text."""
    p = lambda *a: print(*a, file=file)  # noqa: E731
    pt = ", ".join(f"{k}={v:g}" for k, v in res["point"].items())
    p(f"records: {summ['n']} bundled records ({summ['samples']} samples) at {pt}; median of "
      f"{res['repeats']} interleaved runs per record and path; errors relative to the integrator at "
      f"rtol=1e-12 (model='full')")
    hdr = (f"{'path':40s} {'ns/sample med':>13s} {'ns/sample max':>13s} {'total ms':>9s} "
           f"{'med err':>9s} {'max err':>9s}")
    _header(p, hdr)
    for path, name in (("pw", "piecewise exact (solve default)"),
                       ("auto", "integrator (piecewise_path=False)"),
                       ("int", "integrator (model='full')")):
        p(f"{name:40s} {summ[f'{path}_ns_median']:13.1f} {summ[f'{path}_ns_max']:13.1f} "
          f"{summ[f'{path}_total_ms']:9.2f} {summ[f'{path}_err_median']:9.1e} {summ[f'{path}_err_max']:9.1e}")
    verdict = "MET" if summ["target_met"] else "NOT MET"
    p(f"target: all records <= {TARGET_RECORDS_MS:g} ms and median <= {TARGET_NS_PER_SAMPLE:g} ns per sample "
      f"at <= {TARGET_ERROR:g} relative error -> {verdict}: {summ['pw_total_ms']:.2f} ms, "
      f"{summ['pw_ns_median']:.1f} ns per sample ({summ['auto_total_ms'] / summ['pw_total_ms']:.1f}x faster "
      f"than the integrator with the same reductions, {summ['int_total_ms'] / summ['pw_total_ms']:.1f}x than "
      f"model='full')")


TARGET_BUILDING_RATIO = 2.0
"""Aim: a general building of one storey costs at most this many times the paper model's scene."""
TARGET_STOREYS = 8
"""Storeys of the building whose aim is :data:`TARGET_STOREYS_RATIO`."""
TARGET_STOREYS_RATIO = 4.0
"""Aim: a building of :data:`TARGET_STOREYS` storeys costs at most this many times the paper model's scene."""
TARGET_SPEED_PENDULUM_RATIO = 2.0
"""Aim: a friction pendulum whose friction rises with speed at most this many times the constant one's cost."""


def _pendulum_aim(p, rows: dict, summ: dict, name: str, target: float, what: str) -> None:
    """Print the aim line of row ``name`` against :data:`PENDULUM`; its median ratio goes to ``summ[name]``.

    The ratio is the median over the points of the two rows' per-point median costs; ``what`` names
    the class in the line (``"... at most 2x the constant-friction pendulum's cost per scene"``).
    """
    ratio = float(np.median(np.array([_median(x) for x in rows[name]["times"]])
                            / np.array([_median(x) for x in rows[PENDULUM]["times"]])))
    summ[name]["pendulum_ratio"] = ratio
    p(f"aim: {what} at most {target:g}x the constant-friction pendulum's ({PENDULUM}) cost per scene -> "
      f"{'MET' if ratio <= target else 'NOT MET'} (median ratio {ratio:.2f})")


def _limits(p, rows: dict, summ: dict, paper: str) -> None:
    """Print what sets each building's cost against the paper model's: its steps, and each step's cost.

    A class's cost ratio is its steps per scene over the paper's times its cost per step over the
    paper's; the steps follow the shortest period the explicit integrator must resolve (the
    isolator's or the superstructure's highest mode), each step's cost the size of the system.
    """
    steps0 = np.array(rows[paper]["steps"], dtype=float)
    p("what limits each: steps per scene and cost per step against the paper model's "
      "(shortest period followed, units of T_p), and the assembly of a general scene (parts, arrays, modal data, "
      "what the scenes on one building share kept from the others, as in a study, and derived anew; "
      "its share of the cost per scene)")
    for name, r in rows.items():
        if name == paper:
            continue
        steps = float(np.median(np.array(r["steps"], dtype=float) / steps0))
        per_step = summ[name]["ratio"] / steps
        share = r["assembly_us"] / summ[name]["us"]
        summ[name].update(steps_ratio=steps, step_cost_ratio=per_step, shortest_period=r["period"],
                          assembly_us=r["assembly_us"], assembly_share=share, assembly_cold_us=r["assembly_cold_us"])
        p(f"  {name:46s} steps x{steps:5.2f}  cost per step x{per_step:5.2f}  shortest period {r['period']:.3g}  "
          f"assembly {r['assembly_us']:6.0f} us ({100.0 * share:3.0f} %), {r['assembly_cold_us']:6.0f} us anew")


def run_buildings(repeats: int = 7) -> dict:
    """Time every building of :data:`BUILDINGS` on the same Pi points, interleaved; errors against rtol 1e-12."""
    scenes = {name: [Scene(**pt, **kw) for pt in BUILDING_POINTS] for name, kw in BUILDINGS.items()}
    for sc in scenes.values():   # compile or load every path before timing
        solve(sc[0])
    out = {}
    for name, scs in scenes.items():
        conv = [solve(sc, rtol=1e-12).pi1 for sc in scs]
        out[name] = {"conv": conv, "times": [[] for _ in scs], "pi1": [0.0] * len(scs), "models": [""] * len(scs),
                     "steps": [0] * len(scs), "period": building_of(scs[0]).shortest_period}
    for _ in range(repeats):
        for k in range(len(BUILDING_POINTS)):
            for name, scs in scenes.items():
                seconds, sol = timed_solve(scs[k])
                out[name]["times"][k].append(seconds)
                out[name]["pi1"][k], out[name]["models"][k], out[name]["steps"][k] = sol.pi1, sol.model, sol.n_steps
    for name, scs in scenes.items():
        general = [sc for sc in scs if building.reduction(sc)[0] == "general"]
        for key, shared in (("assembly_us", True), ("assembly_cold_us", False)):
            out[name][key] = 1e6 * float(np.median(assembly_times(general, repeats, shared))) if general else 0.0
    return {"rows": out, "points": BUILDING_POINTS, "repeats": repeats}


def report_buildings(res: dict, file=sys.stdout) -> dict:
    """Print the buildings section: median cost per scene, ratio to the paper model, errors; returns them."""
    p = lambda *a: print(*a, file=file)  # noqa: E731
    rows = res["rows"]
    paper = next(iter(rows))
    base = np.array([_median(t) for t in rows[paper]["times"]])
    p(f"buildings: {len(res['points'])} Pi points (pi2 0.05-0.3, pi3 2-3, pi4 0.05, pi8 0.01) per building; median "
      f"of {res['repeats']} interleaved runs; errors relative to solve(rtol=1e-12)")
    hdr = f"{'building':48s} {'us/scene':>9s} {'x paper':>8s} {'med err':>9s} {'max err':>9s}  models"
    _header(p, hdr)
    summ = {}
    for name, r in rows.items():
        t = np.array([_median(x) for x in r["times"]])
        err = np.array([_rel(a, c) for a, c in zip(r["pi1"], r["conv"], strict=True)])
        ratio = float(np.median(t / base))
        summ[name] = {"us": float(1e6 * np.median(t)), "ratio": ratio, "err_median": float(np.median(err)),
                      "err_max": float(err.max())}
        p(f"{name:48s} {1e6 * np.median(t):9.1f} {ratio:8.2f} {np.median(err):9.1e} {err.max():9.1e}  "
          f"{', '.join(sorted(set(r['models'])))}")
    multi = {STOREYS_NAME.format(n) for n in STOREYS}
    worst = max(v["ratio"] for k, v in summ.items() if k not in multi)
    p(f"aim: a general building of one storey at most {TARGET_BUILDING_RATIO:g}x the paper model's cost per "
      f"scene -> {'MET' if worst <= TARGET_BUILDING_RATIO else 'NOT MET'} (largest median ratio {worst:.2f})")
    _pendulum_aim(p, rows, summ, SPEED_PENDULUM, TARGET_SPEED_PENDULUM_RATIO, "the speed-dependent friction pendulum")
    _pendulum_aim(p, rows, summ, TFP_PENDULUM, TARGET_TFP_RATIO,
                  "the triple friction pendulum (regime III, true stick on four surfaces)")
    _limits(p, rows, summ, paper)
    tall = summ[STOREYS_NAME.format(TARGET_STOREYS)]["ratio"]
    p(f"aim: {TARGET_STOREYS} storeys at most {TARGET_STOREYS_RATIO:g}x -> "
      f"{'MET' if tall <= TARGET_STOREYS_RATIO else 'NOT MET'} (median ratio {tall:.2f})")
    return summ


TARGET_PLANAR_RATIO = 3.0
"""Goal: a planar scene costs at most this many times the same scene without its second component."""
TARGET_PAIR_US_PER_SAMPLE = 0.5
"""Goal: a recorded pair costs at most this many microseconds per sample of its x component, on median."""


def run_planar(repeats: int = 7) -> dict:
    """Time every planar scene beside the same scene along x alone (no ``pulse_y``), interleaved.

    Parameters
    ----------
    repeats : int
        Timed runs of each scene (the median is kept); the planar scene and its 1-D twin run one
        after the other, point after point and building after building, in every repeat.

    Returns
    -------
    dict
        ``rows``: per building the planar and 1-D times per point, Pi1, the models and the planar
        scenes' Pi1 at ``rtol = 1e-12``; ``points``, ``repeats``.
    """
    scenes = {name: [(Scene(**{**pt, **kw}), Scene(**{**pt, **kw}, **PLANAR_EXCITATION)) for pt in PLANAR_POINTS]
              for name, kw in PLANAR_BUILDINGS.items()}
    for pairs in scenes.values():   # compile or load every path before timing
        for one, planar in pairs:
            solve(one)
            solve(planar)
    out = {}
    for name, pairs in scenes.items():
        n = len(pairs)
        out[name] = {"conv": [solve(planar, rtol=1e-12).pi1 for _, planar in pairs],
                     "t_1d": [[] for _ in range(n)], "t_planar": [[] for _ in range(n)], "pi1": [0.0] * n,
                     "pi1_1d": [0.0] * n, "models": [""] * n, "models_1d": [""] * n, "steps": [0] * n,
                     "steps_1d": [0] * n}
    for r in range(repeats):
        for k in range(len(PLANAR_POINTS)):
            for name, pairs in scenes.items():
                row = out[name]
                order = (("1d", 0), ("planar", 1)) if r % 2 == 0 else (("planar", 1), ("1d", 0))
                for which, j in order:
                    seconds, sol = timed_solve(pairs[k][j])
                    row[f"t_{which}"][k].append(seconds)
                    tail = "" if which == "planar" else "_1d"
                    row[f"pi1{tail}"][k], row[f"models{tail}"][k], row[f"steps{tail}"][k] = \
                        sol.pi1, sol.model, sol.n_steps
    return {"rows": out, "points": PLANAR_POINTS, "repeats": repeats}


def report_planar(res: dict, file=sys.stdout) -> dict:
    """Print the planar scenes' cost beside their 1-D twins and the goal check; return the summary."""
    p = lambda *a: print(*a, file=file)  # noqa: E731
    rows = res["rows"]
    p(f"planar: {len(res['points'])} Pi points (pi2 0.1-0.3, pi3 1-2, pi4 0.1) per building, "
      f"pulse='ricker' with pulse_y='antisymmetric_ricker', pi14=0.7, beside the same scene without pulse_y; "
      f"median of {res['repeats']} interleaved runs; errors of the planar scene relative to solve(rtol=1e-12)")
    hdr = (f"{'building':48s} {'us 1-D':>8s} {'us planar':>10s} {'planar/1-D':>10s} {'steps 1-D':>9s} "
           f"{'steps planar':>12s} {'med err':>9s} {'max err':>9s}  goal")
    _header(p, hdr)
    summ = {}
    for name, r in rows.items():
        t1 = np.array([_median(x) for x in r["t_1d"]])
        tp = np.array([_median(x) for x in r["t_planar"]])
        err = np.array([_rel(a, c) for a, c in zip(r["pi1"], r["conv"], strict=True)])
        ratio = float(np.median(tp / t1))
        met = ratio <= TARGET_PLANAR_RATIO
        summ[name] = {"us_1d": float(1e6 * np.median(t1)), "us_planar": float(1e6 * np.median(tp)),
                      "ratio": ratio, "err_median": float(np.median(err)), "err_max": float(err.max()),
                      "met": bool(met), "models": sorted(set(r["models"]))}
        p(f"{name:48s} {1e6 * np.median(t1):8.1f} {1e6 * np.median(tp):10.1f} {ratio:10.2f} "
          f"{np.median(r['steps_1d']):9.0f} {np.median(r['steps']):12.0f} "
          f"{np.median(err):9.1e} {err.max():9.1e}  {'met' if met else 'NOT MET'}")
    worst = max(v["ratio"] for v in summ.values())
    p(f"goal: planar/1-D <= {TARGET_PLANAR_RATIO:g}x (median over the points of each building's per-scene "
      f"ratio) -> {'MET' if worst <= TARGET_PLANAR_RATIO else 'NOT MET'} (largest {worst:.2f}x; "
      f"{sum(v['met'] for v in summ.values())} of {len(summ)} buildings meet it)")
    return summ


def run_pairs(n: int = 4, repeats: int = 5, suite_name: str = PAIR_SUITE) -> dict:
    """Time recorded pairs as recorded, beside their x component alone, at each of :data:`PAIR_POINTS`.

    Parameters
    ----------
    n : int
        Number of pairs (the suite's first ``n``).
    repeats : int
        Timed runs of each scene (the median is kept), interleaved: every pair and point, planar
        then 1-D, in every repeat.
    suite_name : str
        Suite of the pairs (default :data:`PAIR_SUITE`); bundled samples when it is unavailable.

    Returns
    -------
    dict
        ``rows``: per pair and point the samples of the x component, the median planar and 1-D
        times, Pi1 and the models; ``source``, ``repeats``.
    """
    source, pairs = recorded_pairs(n, suite_name)
    cases = []
    for name, x, y, lag in pairs:
        for where, pt in PAIR_POINTS.items():
            planar = Scene(**pt, pulse=x, pulse_y=y, pi16=lag)
            cases.append({"pair": name, "point": where, "samples": int(x.npts), "planar": planar,
                          "one": Scene(**pt, pulse=x), "t_planar": [], "t_1d": []})
    for c in cases:   # compile or load every path before timing
        solve(c["planar"])
        solve(c["one"])
    for _ in range(repeats):
        for c in cases:
            t_planar, sp = timed_solve(c["planar"])
            t_1d, s1 = timed_solve(c["one"])
            c["t_planar"].append(t_planar)
            c["t_1d"].append(t_1d)
            c.update(pi1=sp.pi1, model=sp.model, steps=sp.n_steps, pi1_1d=s1.pi1, model_1d=s1.model)
    rows = [{k: v for k, v in c.items() if k not in ("planar", "one", "t_planar", "t_1d")}
            | {"planar_s": _median(c["t_planar"]), "one_s": _median(c["t_1d"])} for c in cases]
    return {"rows": rows, "source": source, "repeats": repeats, "points": PAIR_POINTS}


def report_pairs(res: dict, file=sys.stdout) -> dict:
    """Print the recorded pairs' cost per analysis and per sample, the 1-D cost and the goal check."""
    p = lambda *a: print(*a, file=file)  # noqa: E731
    rows = res["rows"]
    pts = "; ".join(f"{k}: " + ", ".join(f"{g}={v:g}" for g, v in pt.items()) for k, pt in res["points"].items())
    p(f"recorded pairs: {len({r['pair'] for r in rows})} pairs of {res['source']}, as recorded ({pts}); "
      f"median of {res['repeats']} interleaved runs; per sample = per analysis / samples of the x component")
    hdr = (f"{'pair':24s} {'base':10s} {'samples':>7s} {'steps':>7s} {'ms planar':>9s} {'us/sample':>9s} "
           f"{'1-D us/sample':>13s} {'planar/1-D':>10s}  models (planar | 1-D)")
    _header(p, hdr)
    for r in rows:
        p(f"{r['pair'][:24]:24s} {r['point']:10s} {r['samples']:7d} {r['steps']:7d} {1e3 * r['planar_s']:9.2f} "
          f"{1e6 * r['planar_s'] / r['samples']:9.3f} {1e6 * r['one_s'] / r['samples']:13.3f} "
          f"{r['planar_s'] / r['one_s']:10.1f}  {r['model']} | {r['model_1d']}")
    summ = {}
    for where in res["points"]:
        rs = [r for r in rows if r["point"] == where]
        per = np.array([r["planar_s"] / r["samples"] for r in rs])
        one = np.array([r["one_s"] / r["samples"] for r in rs])
        summ[where] = {"ms_median": float(1e3 * np.median([r["planar_s"] for r in rs])),
                       "us_per_sample_median": float(1e6 * np.median(per)), "us_per_sample_max": float(1e6 * per.max()),
                       "us_per_sample_1d_median": float(1e6 * np.median(one))}
        p(f"{'median':24s} {where:10s} {'':7s} {'':7s} {summ[where]['ms_median']:9.2f} "
          f"{summ[where]['us_per_sample_median']:9.3f} {summ[where]['us_per_sample_1d_median']:13.3f}")
    per = np.array([r["planar_s"] / r["samples"] for r in rows])
    med = float(1e6 * np.median(per))
    summ["us_per_sample_median"] = med
    summ["met"] = bool(med <= TARGET_PAIR_US_PER_SAMPLE)
    p(f"goal: a recorded pair <= {TARGET_PAIR_US_PER_SAMPLE:g} us per sample on median -> "
      f"{'MET' if summ['met'] else 'NOT MET'} (median {med:.3f} us per sample over every pair and base; "
      f"the x component alone {1e6 * np.median([r['one_s'] / r['samples'] for r in rows]):.3f} us per sample)")
    return summ


FRAGILITY_CONFIG = Path(__file__).resolve().parents[2] / "config" / "fragility_p695.yaml"
"""The planar fragility study at full size whose per-analysis cost the planar section measures (a checkout's)."""
FRAGILITY_SAMPLE = 12
"""Analyses drawn (seeded) from that study's table and timed on each building."""


def run_fragility_cost(n: int = FRAGILITY_SAMPLE, path: Path = FRAGILITY_CONFIG) -> dict | None:
    """Time ``n`` analyses of the planar fragility study of ``path`` on each building (None without the file).

    Each analysis is :func:`isoslide.studies.fragility_planar.solve_analyses` of one index (a
    planar and two 1-D solves and the floor's peaks), timed after a first call that readies its
    pair's intensity measures (computed once per pair and chunk in the pipeline).
    """
    if not path.exists():
        return None
    study = fragility_planar.check_settings(fragility_planar.planar_settings(config.load(None, path)))
    idx = np.sort(np.random.default_rng(0).choice(study.size, size=min(n, study.size), replace=False))
    out = {"config": str(path), "analyses": int(study.size), "sampled": [int(i) for i in idx]}
    for base in fragility_planar.BASES:
        times = []
        for i in idx:
            fragility_planar.solve_analyses(study, [i], base)
            t0 = time.perf_counter()
            fragility_planar.solve_analyses(study, [i], base)
            times.append(time.perf_counter() - t0)
        out[base] = {"mean_ms": 1e3 * float(np.mean(times)), "median_ms": 1e3 * float(np.median(times)),
                     "max_ms": 1e3 * float(np.max(times))}
    return out


def report_fragility_cost(res: dict | None, file=sys.stdout) -> dict | None:
    """Print the per-analysis cost of :func:`run_fragility_cost` and the study's CPU time at it."""
    p = functools.partial(print, file=file)
    if res is None:
        p(f"planar fragility analyses: skipped ({FRAGILITY_CONFIG} is not here: a checkout holds it)")
        return None
    p(f"planar fragility analyses: {len(res['sampled'])} of the {res['analyses']} analyses per building of "
      f"{Path(res['config']).name} (seeded draw), each a planar and two 1-D solves with the floor's peaks")
    total = 0.0
    for base in fragility_planar.BASES:
        r = res[base]
        cpu = r["mean_ms"] * 1e-3 * res["analyses"]
        total += cpu
        p(f"  {base:10s} mean {r['mean_ms']:8.1f} ms  median {r['median_ms']:8.1f} ms  largest {r['max_ms']:8.1f} ms"
          f"  -> {cpu / 60.0:6.1f} CPU-min for the building's {res['analyses']} analyses")
    p(f"  both buildings: {total / 60.0:.1f} CPU-min of solving (the fits and the start-up of each job come on top)")
    return res


PLANAR_REPEATS = {False: 7, True: 3}
"""Interleaved runs of each planar scene, without and with ``--quick``."""


def run_report_planar(quick: bool = False, file=sys.stdout) -> dict:
    """The planar section: compiled kernels readied, planar scenes beside 1-D, recorded pairs, fragility analyses."""
    warm_up(records=True, building=True)
    out = {"scenes": report_planar(run_planar(repeats=PLANAR_REPEATS[quick]), file=file)}
    print("", file=file)
    out["pairs"] = report_pairs(run_pairs(n=2 if quick else 4, repeats=3 if quick else 5), file=file)
    print("", file=file)
    out["fragility"] = report_fragility_cost(run_fragility_cost(n=4 if quick else FRAGILITY_SAMPLE), file=file)
    return out


SECTION_FLAGS = (
    ("--records-only", "only the records section (both exact paths on the bundled records, about 15 s)"),
    ("--no-records", "leave out the records section"),
    ("--buildings-only", "only the buildings section (bearings and flexible superstructures beside the paper "
                         "model, about 20 s)"),
    ("--planar-only", "only the planar section (planar scenes beside their 1-D twins, recorded pairs per "
                      "sample, the planar fragility study's cost per analysis; about a minute)"),
    ("--no-planar", "leave out the planar section"),
    ("--rocking-only", "only the rocking section (contents that rock beside the same contents sliding, on pulses "
                       "and per sample of the bundled records; isoslide.accuracy.rocking_cost)"),
    ("--no-rocking", "leave out the rocking section"),
    ("--opensees", "only OpenSees against isoslide on every building class, OpenSees at the coarsest step within "
                   "1e-3 of Pi1 (isoslide.accuracy.opensees_cost; a few minutes)"),
    ("--cpu-targets", "only the kernels compiled for this processor against the portable level the shipped "
                      "ones are compiled for, on the buildings section's scenes (isoslide.accuracy.kernel_targets)"),
)
"""The command line's section flags (each on or off) and their help: one section alone, or one left out."""


def _buildings(repeats: int, path: str | None) -> dict:
    """The buildings section, run and printed; its rows of the measurements table rewritten when ``path`` is given."""
    summ = report_buildings(run_buildings(repeats=repeats))
    if path:
        measurements.write_rows(path, "buildings", measurements.BUILDINGS_COMMAND,
                                measurements.buildings_rows(summ, next(iter(BUILDINGS)), len(BUILDING_POINTS),
                                                            repeats))
    return summ


def _planar(quick: bool, path: str | None) -> dict:
    """The planar section, run and printed; its rows of the measurements table rewritten when ``path`` is given."""
    summ = run_report_planar(quick=quick)
    if path:
        measurements.write_rows(path, "planar", measurements.PLANAR_COMMAND,
                                measurements.planar_rows(summ, PLANAR_REPEATS[quick], TARGET_PLANAR_RATIO,
                                                         TARGET_PAIR_US_PER_SAMPLE))
    return summ


def _rocking(repeats: int, path: str | None) -> dict:
    """The rocking section, run and printed; its rows of the measurements table rewritten when ``path`` is given."""
    summ = rocking_cost.report(rocking_cost.run(repeats=repeats))
    if path:
        measurements.write_rows(path, "rocking", measurements.ROCKING_COMMAND,
                                measurements.rocking_rows(summ, repeats))
    return summ


def _write_json(path: str | None, out: dict) -> None:
    """Write ``out`` as JSON to ``path`` (numbers as floats); nothing when ``path`` is None."""
    if path:
        with open(path, "w") as f:
            json.dump(out, f, indent=1, default=float)


def main(argv=None) -> int:
    """Command line: measure, then print the report (or JSON); returns the exit status."""
    ap = argparse.ArgumentParser(prog="python -m isoslide.bench", description=__doc__.split("\n\n")[0])
    ap.add_argument("--per-study", type=int, default=6, help="scenes drawn from each paper study (6)")
    ap.add_argument("--no-hard", action="store_true", help="leave out the hard scene classes")
    ap.add_argument("--repeats", type=int, default=15, help="isoslide runs per scene (15)")
    ap.add_argument("--peer-repeats", type=int, default=3, help="SciPy reference runs per scene (3)")
    ap.add_argument("--reference-rtol", type=float, default=1e-6, help="solve_ivp rtol of the reference (1e-6)")
    ap.add_argument("--regularized-scenes", type=int, default=6,
                    help="scenes for the regularised solve (6; 0 = skip)")
    ap.add_argument("--stiffness", type=float, default=1e6, help="regularising stiffness K (1e6)")
    ap.add_argument("--regularized-rtol", type=float, default=1e-6, help="Radau rtol (1e-6)")
    ap.add_argument("--max-work", type=int, default=2_000_000,
                    help="most right-hand-side evaluations per peer run (2000000)")
    ap.add_argument("--quick", action="store_true", help="1 scene per study, 5 repeats, 2 regularised scenes")
    ap.add_argument("--json", metavar="PATH", help="also write the records and summary as JSON")
    ap.add_argument("--measurements", metavar="PATH",
                    help="rewrite the buildings, planar, rocking and OpenSees sections' rows of the documentation's measurements "
                         "table (docs/measurements.csv) from this run (isoslide.accuracy.measurements)")
    ap.add_argument("-v", "--verbose", action="store_true", help="print every scene as it is measured")
    for flag, text in SECTION_FLAGS:
        ap.add_argument(flag, action="store_true", help=text)
    a = ap.parse_args(argv)
    if a.opensees:
        summ = opensees_cost.report(opensees_cost.run(repeats=3 if a.quick else 5))
        if a.measurements:
            measurements.write_rows(a.measurements, "opensees_cost", measurements.OPENSEES_COMMAND,
                                    measurements.opensees_rows(summ, len(opensees_cost.POINTS)))
        _write_json(a.json, {"opensees": summ})
        return 0
    if a.cpu_targets:
        _write_json(a.json, {"cpu_targets": kernel_targets.report(kernel_targets.run(rounds=5 if a.quick else 15))})
        return 0
    if a.planar_only:
        _write_json(a.json, {"planar": _planar(a.quick, a.measurements)})
        return 0
    if a.buildings_only:
        _write_json(a.json, {"buildings": _buildings(3 if a.quick else 7, a.measurements)})
        return 0
    if a.rocking_only:
        _write_json(a.json, {"rocking": _rocking(3 if a.quick else 7, a.measurements)})
        return 0
    if a.quick:
        a.per_study, a.repeats, a.peer_repeats, a.regularized_scenes = 1, 5, 1, 2
    out = {}
    if not a.no_records:
        rres = run_records(repeats=3 if a.quick else 7)
        rsumm = summarize_records(rres)
        report_records(rres, rsumm)
        out["records"] = {"result": rres, "summary": rsumm}
        if a.records_only:
            _write_json(a.json, out)
            return 0
        print("")
    res = run(per_study=a.per_study, hard=not a.no_hard, repeats=a.repeats, peer_repeats=a.peer_repeats,
              reference_rtol=a.reference_rtol, regularized_scenes=a.regularized_scenes,
              stiffness=a.stiffness, regularized_rtol=a.regularized_rtol, max_work=a.max_work,
              log=print if a.verbose else None)
    summ = summarize(res)
    report(res, summ)
    print("")
    out["buildings"] = _buildings(3 if a.quick else 7, a.measurements)
    if not a.no_planar:
        print("")
        out["planar"] = _planar(a.quick, a.measurements)
    if not a.no_rocking:
        print("")
        out["rocking"] = _rocking(3 if a.quick else 7, a.measurements)
    _write_json(a.json, {"result": res, "summary": summ, **out})
    return 0


if __name__ == "__main__":
    sys.exit(main())
