"""Checks of the SLURM test (tests/cluster/run.sh): what a run on the scheduler must have produced.

    python tests/cluster/check.py failure --cluster DIR --log LOG --record NAME
    python tests/cluster/check.py results --local DIR --cluster DIR --dry-run-log LOG

``failure``: the run with a record that does not exist failed because of that record's job, named
its log (``logs/.../<NAME>.log``) and the SLURM job that ran it, and the log says why.

``results``: every compute job of the local reference run (one benchmark file each, since every
rule declares one) also ran on the cluster, inside a SLURM job that ``sacct`` lists COMPLETED (the
job ids are read from the plugin's SLURM logs, which name the benchmark of every job they ran);
every dataset (``results/datasets/*.nc``) holds the same variables and coordinates with equal
values as the local run's; and a dry run after the cluster run has nothing left to do.
Exit code 0 when all hold, 1 with one line per failed check otherwise.
"""

import argparse
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import xarray as xr

BENCHMARK_LINE = re.compile(r"^\s+benchmark: (\S+)$", re.MULTILINE)


def failure_problems(cluster: Path, log: Path, record: str) -> list[str]:
    """What is wrong with the failing run's output (empty list: nothing)."""
    text = log.read_text(errors="replace")
    problems = []
    if "Error in rule record_compare" not in text:
        problems.append("the failing run does not report an error in rule record_compare")
    named = re.search(rf"^\s+log: (logs/\S*{re.escape(record)}\.log)", text, re.MULTILINE)
    if not named:
        problems.append(f"the failing run does not name the job's log (logs/.../{record}.log)")
    if not re.search(rf"slurm_logs/rule_record_compare/{re.escape(record)}/\d+\.log", text):
        problems.append("the failing run does not name the SLURM log of the failed job")
    if "SLURM status is: 'FAILED'" not in text:
        problems.append("the failing run does not report the SLURM state FAILED")
    if named:
        path = cluster / named.group(1)
        if not path.is_file():
            problems.append(f"{named.group(1)} was not written")
        elif f"sample = {record!r} is invalid" not in path.read_text(errors="replace"):
            problems.append(f"{named.group(1)} does not say that sample = {record!r} is invalid")
        else:
            print(f"check: the failing run names {named.group(1)}: sample = {record!r} is invalid")
    return problems


def sacct_states() -> dict[str, str]:
    """SLURM job id -> state of every job in the accounting database."""
    out = subprocess.run(
        ["sacct", "-X", "-n", "-P", "-a", "-S", "2000-01-01", "-o", "JobID,State"],
        check=True, capture_output=True, text=True,
    ).stdout
    return dict(line.split("|", 1) for line in out.splitlines() if line.strip())


def slurm_jobs_by_benchmark(cluster: Path) -> dict[str, set[str]]:
    """Benchmark path -> ids of the SLURM jobs whose log names it (the plugin's %j.log files)."""
    found: dict[str, set[str]] = {}
    for path in (cluster / ".snakemake" / "slurm_logs").rglob("*.log"):
        for bench in BENCHMARK_LINE.findall(path.read_text(errors="replace")):
            found.setdefault(bench, set()).add(path.stem)
    return found


def benchmarks(root: Path) -> set[str]:
    """Benchmark files of a run, relative to its directory (one per compute job)."""
    return {str(p.relative_to(root)) for p in (root / "results" / "benchmarks").rglob("*.tsv")}


def dataset_problems(local: Path, cluster: Path) -> tuple[list[str], int, int]:
    """Differences between the datasets of two runs; also the number compared and byte-identical."""
    problems = []
    names_local = sorted(p.name for p in (local / "results" / "datasets").glob("*.nc"))
    names_cluster = sorted(p.name for p in (cluster / "results" / "datasets").glob("*.nc"))
    if names_local != names_cluster:
        problems.append(f"datasets differ: local {names_local}, cluster {names_cluster}")
    identical = 0
    for name in sorted(set(names_local) & set(names_cluster)):
        a_path, b_path = local / "results/datasets" / name, cluster / "results/datasets" / name
        identical += a_path.read_bytes() == b_path.read_bytes()
        with xr.open_dataset(a_path) as a, xr.open_dataset(b_path) as b:
            for kind, va, vb in (("variables", a.data_vars, b.data_vars), ("coordinates", a.coords, b.coords)):
                if sorted(va) != sorted(vb):
                    problems.append(f"{name}: {kind} differ: {sorted(va)} != {sorted(vb)}")
                    continue
                for var in va:
                    x, y = va[var], vb[var]
                    if x.dims != y.dims or x.dtype != y.dtype or not _equal(x.values, y.values):
                        problems.append(f"{name}: {kind[:-1]} {var} differs")
    return problems, len(names_local), identical


def _equal(x: np.ndarray, y: np.ndarray) -> bool:
    """Equal shapes and values, NaN equal to NaN."""
    if x.shape != y.shape:
        return False
    if x.dtype.kind in "fc":
        return bool(np.array_equal(x, y, equal_nan=True))
    return bool(np.array_equal(x, y))


def results_problems(local: Path, cluster: Path, dry_run_log: Path) -> list[str]:
    """Everything wrong with the cluster run against the local one (empty list: nothing)."""
    problems = []
    jobs = benchmarks(local)
    if not jobs:
        problems.append("the local run wrote no benchmark files")
    if benchmarks(cluster) != jobs:
        problems.append(f"benchmarks differ: only local {sorted(jobs - benchmarks(cluster))}, "
                        f"only cluster {sorted(benchmarks(cluster) - jobs)}")
    states = sacct_states()
    by_bench = slurm_jobs_by_benchmark(cluster)
    for bench in sorted(jobs):
        ids = by_bench.get(bench, set())
        if not any(states.get(i) == "COMPLETED" for i in ids):
            problems.append(f"{bench}: no COMPLETED SLURM job ran it (jobs {sorted(ids)}, "
                            f"states {[states.get(i) for i in sorted(ids)]})")
    used = set().union(*by_bench.values()) if by_bench else set()
    print(f"check: {len(jobs)} compute jobs, all in {len(used)} SLURM jobs "
          f"({sum(states.get(i) == 'COMPLETED' for i in used)} COMPLETED) of {len(states)} in sacct")
    more, compared, identical = dataset_problems(local, cluster)
    problems += more
    print(f"check: {compared} datasets compared variable by variable, {identical} also byte-identical")
    if "Nothing to be done" not in dry_run_log.read_text(errors="replace"):
        problems.append(f"a dry run after the cluster run still has jobs to do ({dry_run_log})")
    return problems


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="what", required=True)
    f = sub.add_parser("failure")
    f.add_argument("--cluster", type=Path, required=True)
    f.add_argument("--log", type=Path, required=True)
    f.add_argument("--record", required=True)
    r = sub.add_parser("results")
    r.add_argument("--local", type=Path, required=True)
    r.add_argument("--cluster", type=Path, required=True)
    r.add_argument("--dry-run-log", type=Path, required=True)
    args = parser.parse_args(argv)
    if args.what == "failure":
        problems = failure_problems(args.cluster, args.log, args.record)
    else:
        problems = results_problems(args.local, args.cluster, args.dry_run_log)
    for p in problems:
        print(f"check FAILED: {p}")
    if not problems:
        print(f"check {args.what}: passed")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
