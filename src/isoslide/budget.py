"""Where the time of a pipeline run goes, by phase: start-up, compilation, solving, writing, reporting.

Every pipeline job logs the seconds of its phases (:func:`phase`, and :func:`isoslide.store.provenance.log_to`
logs the start-up: interpreter and imports, from the process start to the job's first line); the
``benchmark:`` file of each job holds its total.  :func:`budget` adds them up::

    python -m isoslide.budget            # in the directory the workflow ran in

prints, per phase, the jobs that logged it and their seconds (summed over jobs: CPU-bound jobs on
two cores overlap, so the sum is about twice the wall-clock time), the rest of the job totals
(``other``: Snakemake's own script start and what no phase covers) and the wall-clock time of the
last Snakemake run (from ``.snakemake/log``).  A report job (papermill + nbconvert) counts as
``reporting`` as a whole.
"""

from __future__ import annotations

import argparse
import contextlib
import csv
import logging
import os
import re
import sys
import time
from datetime import datetime
from pathlib import Path

PHASES = ("start-up", "compilation", "solving", "writing", "reporting")
"""The phases of a job, in the order they happen."""

REPORT_RULES = ("report",)
"""Rules whose whole job is reporting (they run a notebook and log no phases)."""

_PHASE_LINE = re.compile(r" phase (?P<name>[\w-]+) (?P<seconds>[0-9.eE+-]+) s$")
_STAMP = re.compile(r"^\[(?P<stamp>\w{3} \w{3} +\d+ \d\d:\d\d:\d\d \d{4})\]$")

log = logging.getLogger(__name__)


def _check(name: str) -> str:
    if name not in PHASES:
        raise ValueError(f"phase = {name!r} is invalid; allowed: {PHASES}")
    return name


@contextlib.contextmanager
def phase(name: str, logger: logging.Logger | None = None):
    """Log the wall-clock seconds of the block as phase ``name`` (one of :data:`PHASES`)."""
    _check(name)
    t0 = time.perf_counter()
    try:
        yield
    finally:
        (logger or log).info("phase %s %.3f s", name, time.perf_counter() - t0)


def compile_and_solve(logger: logging.Logger | None, warm_up, solve):
    """Run ``warm_up()`` as the phase ``compilation``, then ``solve()`` as the phase ``solving``.

    Parameters
    ----------
    logger : logging.Logger or None
        Receives the seconds of each phase (:func:`phase`).
    warm_up : callable
        Readies the compiled kernels (:func:`isoslide.solver.warm_up` with the job's options).
    solve : callable
        The job's work; its result is returned.

    Returns
    -------
    object
        What ``solve()`` returns.
    """
    with phase("compilation", logger):
        warm_up()
    with phase("solving", logger):
        return solve()


def compile_solve_write(logger: logging.Logger, warm_up, solve, write):
    """:func:`compile_and_solve`, the result logged, then ``write(result)`` as the phase ``writing``.

    Parameters
    ----------
    logger : logging.Logger
        Receives the seconds of each phase (:func:`phase`) and the result (``%s``).
    warm_up, solve : callable
        As for :func:`compile_and_solve`.
    write : callable
        ``write(result)``: stores the result (a dataset: :func:`isoslide.datasets.write_netcdf`).

    Returns
    -------
    object
        What ``solve()`` returns.
    """
    result = compile_and_solve(logger, warm_up, solve)
    logger.info("%s", result)
    with phase("writing", logger):
        write(result)
    return result


def seconds_since_process_start() -> float | None:
    """Wall-clock seconds since this process started (Linux ``/proc``; None elsewhere)."""
    try:
        fields = Path(f"/proc/{os.getpid()}/stat").read_text().rsplit(")", 1)[1].split()
        start_ticks = int(fields[19])
        uptime = float(Path("/proc/uptime").read_text().split()[0])
        return max(0.0, uptime - start_ticks / os.sysconf("SC_CLK_TCK"))
    except (OSError, ValueError, IndexError):
        return None


def job_phases(log_file: Path) -> dict:
    """``{phase: seconds}`` logged in one job log."""
    out: dict = {}
    for line in Path(log_file).read_text(errors="replace").splitlines():
        m = _PHASE_LINE.search(line)
        if m and m["name"] in PHASES:
            out[m["name"]] = out.get(m["name"], 0.0) + float(m["seconds"])
    return out


def _benchmark_seconds(tsv: Path) -> float:
    with open(tsv, newline="") as f:
        rows = list(csv.DictReader(f, delimiter="\t"))
    return float(rows[-1]["s"]) if rows else 0.0


def _last_run_wall_clock(root: Path) -> float | None:
    logs = sorted((root / ".snakemake" / "log").glob("*.snakemake.log"))
    if not logs:
        return None
    stamps = []
    for line in logs[-1].read_text(errors="replace").splitlines():
        m = _STAMP.match(line.strip())
        if m:
            stamps.append(datetime.strptime(m["stamp"], "%a %b %d %H:%M:%S %Y"))
    return (stamps[-1] - stamps[0]).total_seconds() if len(stamps) >= 2 else None


def budget(root=".") -> dict:
    """Seconds by phase over the jobs of the run in ``root``.

    Returns
    -------
    dict
        ``phases``: ``{phase: {"jobs": n, "seconds": s}}`` for every name of :data:`PHASES` and
        ``"other"``; ``jobs``: number of benchmark files; ``job_seconds``: sum of their totals;
        ``wall_clock``: seconds of the last Snakemake run (None if unknown).
    """
    root = Path(root)
    bench_dir = root / "results" / "benchmarks"
    if not bench_dir.is_dir():
        raise FileNotFoundError(f"no benchmark files under {bench_dir}: run the workflow first")
    phases = {p: {"jobs": 0, "seconds": 0.0} for p in PHASES + ("other",)}
    total, jobs = 0.0, 0
    for tsv in sorted(bench_dir.rglob("*.tsv")):
        rel = tsv.relative_to(bench_dir).with_suffix("")
        rule = rel.parts[0]
        seconds = _benchmark_seconds(tsv)
        total += seconds
        jobs += 1
        if rule in REPORT_RULES:
            logged = {"reporting": seconds}
        else:
            log_file = root / "logs" / rel.with_suffix(".log")
            logged = job_phases(log_file) if log_file.exists() else {}
        for name, s in logged.items():
            phases[name]["jobs"] += 1
            phases[name]["seconds"] += s
        phases["other"]["jobs"] += 1
        phases["other"]["seconds"] += max(0.0, seconds - sum(logged.values()))
    return {"phases": phases, "jobs": jobs, "job_seconds": total, "wall_clock": _last_run_wall_clock(root)}


def report(b: dict, file=None) -> None:
    """Print :func:`budget`'s result as a table (to ``file``, default standard output)."""
    file = sys.stdout if file is None else file
    total = b["job_seconds"] or 1.0
    print(f"{'phase':<12} {'jobs':>5} {'seconds':>9} {'share':>6}", file=file)
    for name, row in b["phases"].items():
        print(f"{name:<12} {row['jobs']:>5d} {row['seconds']:>9.1f} {100 * row['seconds'] / total:>5.0f}%",
              file=file)
    print(f"{'all jobs':<12} {b['jobs']:>5d} {b['job_seconds']:>9.1f}   (sum over jobs)", file=file)
    wall = b["wall_clock"]
    print("wall-clock of the last run: " + (f"{wall:.0f} s" if wall is not None else "unknown"), file=file)


def main(argv=None) -> int:
    """``python -m isoslide.budget [ROOT]``: the time budget of the run in ROOT by phase."""
    ap = argparse.ArgumentParser(prog="python -m isoslide.budget", description=__doc__.splitlines()[0])
    ap.add_argument("root", nargs="?", default=".", help="directory the workflow ran in (default: .)")
    a = ap.parse_args(argv)
    try:
        report(budget(a.root))
    except FileNotFoundError as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
