"""The bench's figures written into the documentation's table of measurements (``docs/measurements.csv``).

Each row of that table is one measured figure with the command that measures it, the date, the
commit and the conditions (columns :data:`FIELDS`); the documentation renders the rows of a topic as
a table.  A bench section that measures a topic's figures rewrites, with :func:`write_rows`, exactly
the rows of that topic made by its own command, in place: other commands' rows of the topic (figures
measured another way) and every other topic stay as they are.  ``python -m isoslide.bench
--buildings-only --measurements docs/measurements.csv`` and ``--opensees --measurements ...`` do so
(:func:`buildings_rows`, :func:`opensees_rows`).
"""

from __future__ import annotations

import csv
import datetime
import io
import os
import subprocess
from dataclasses import dataclass
from pathlib import Path

from ..atomic import atomic_path

FIELDS = ("topic", "quantity", "value", "unit", "command", "date", "commit", "conditions")
"""Columns of the measurements table; every one is required but ``conditions``."""

BUILDINGS_COMMAND = "python -m isoslide.bench --buildings-only"
"""The command whose rows of the topic ``buildings`` :func:`buildings_rows` makes."""

OPENSEES_COMMAND = "python -m isoslide.bench --opensees"
"""The command whose rows of the topic ``opensees_cost`` :func:`opensees_rows` makes."""

PLANAR_COMMAND = "python -m isoslide.bench --planar-only"
"""The command whose rows of the topic ``planar`` :func:`planar_rows` makes."""

ROCKING_COMMAND = "python -m isoslide.bench --rocking-only"
"""The command whose rows of the topic ``rocking`` :func:`rocking_rows` makes."""


@dataclass(frozen=True)
class Measurement:
    """One measured figure: what it is, its value (as it is to be printed) and unit, and its conditions."""

    quantity: str
    value: str
    unit: str
    conditions: str = ""


def machine_conditions() -> str:
    """The machine's state as a row's conditions: its cores and the load average over the last minute."""
    return f"{os.cpu_count()}-core machine, load average {os.getloadavg()[0]:.1f}"


def head_commit(cwd: Path | None = None) -> str:
    """The short hash of the checkout's ``HEAD`` (``"unknown"`` outside a git checkout)."""
    try:
        out = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=cwd, capture_output=True, text=True,
                             check=True)
    except (OSError, subprocess.CalledProcessError):
        return "unknown"
    return out.stdout.strip() or "unknown"


def read_rows(path: Path) -> list[dict]:
    """The rows of a measurements table (a ValueError when its columns are not :data:`FIELDS`)."""
    with open(path, newline="", encoding="utf-8") as f:
        reader = csv.DictReader(f)
        if tuple(reader.fieldnames or ()) != FIELDS:
            raise ValueError(f"{path}: columns {reader.fieldnames}, expected {list(FIELDS)}")
        return list(reader)


def write_rows(path: Path, topic: str, command: str, rows: list[Measurement], date: str | None = None,
               commit: str | None = None) -> int:
    """Replace the rows of ``topic`` made by ``command`` with ``rows``; returns how many were replaced.

    The new rows take the place of the first old one (or follow the topic's last row, or end the
    table); the file is written whole or not at all.  ``date`` defaults to today, ``commit`` to the
    checkout's ``HEAD`` (:func:`head_commit`).
    """
    path = Path(path)
    old = read_rows(path)
    date = date or datetime.date.today().isoformat()
    commit = commit or head_commit(path.parent)
    new = [{"topic": topic, "quantity": m.quantity, "value": m.value, "unit": m.unit, "command": command,
            "date": date, "commit": commit, "conditions": m.conditions} for m in rows]
    mine = [i for i, r in enumerate(old) if r["topic"] == topic and r["command"] == command]
    same_topic = [i for i, r in enumerate(old) if r["topic"] == topic]
    at = mine[0] if mine else (same_topic[-1] + 1 if same_topic else len(old))
    kept = [r for i, r in enumerate(old) if i not in set(mine)]
    at -= sum(1 for i in mine if i < at)
    out = kept[:at] + new + kept[at:]
    buf = io.StringIO()
    writer = csv.DictWriter(buf, fieldnames=FIELDS, lineterminator="\n")
    writer.writeheader()
    writer.writerows(out)
    with atomic_path(path) as tmp:
        Path(tmp).write_text(buf.getvalue(), encoding="utf-8")
    return len(mine)


def buildings_rows(summary: dict, paper: str, points: int, repeats: int) -> list[Measurement]:
    """The buildings section's figures: the paper model's cost per scene, every other class's ratio to it.

    ``summary`` is :func:`isoslide.bench.report_buildings`'s return (``us``, ``ratio``, what limits
    each class: ``steps_ratio``, ``step_cost_ratio``, ``assembly_us``, ``assembly_share`` and
    ``assembly_cold_us``, and, for
    the pendulums, ``pendulum_ratio`` per building), ``paper`` the paper model's row name.
    """
    base = summary[paper]
    rows = [Measurement(f"{paper}: cost per scene", f"{base['us']:.1f}", "us",
                        f"{points} Pi points, median of {repeats} interleaved runs; {machine_conditions()}")]
    for name, s in summary.items():
        if name == paper:
            continue
        notes = []
        if "steps_ratio" in s:
            notes.append(f"steps x{s['steps_ratio']:.2f}, cost per step x{s['step_cost_ratio']:.2f}, assembly "
                         f"{s['assembly_us']:.0f} us ({100.0 * s['assembly_share']:.0f} % of its cost; "
                         f"{s['assembly_cold_us']:.0f} us with nothing shared with another scene)")
        if "pendulum_ratio" in s:
            notes.append(f"its ratio to the constant pendulum: {s['pendulum_ratio']:.2f}")
        rows.append(Measurement(f"{name}: cost ratio to the paper model", f"{s['ratio']:.2f}", "x", "; ".join(notes)))
    worst = max(s["err_max"] for s in summary.values())
    rows.append(Measurement("largest error of any building class at default rtol", f"{worst:.1e}", "1",
                            "against rtol = 1e-12"))
    return rows


def planar_rows(summary: dict, repeats: int, target_ratio: float, target_us: float) -> list[Measurement]:
    """The planar section's figures: planar over 1-D per building, recorded pairs per sample, the study's cost.

    ``summary`` is :func:`isoslide.bench.run_report_planar`'s return (``scenes``, ``pairs`` and
    ``fragility``); ``target_ratio`` and ``target_us`` the section's goals.
    """
    scenes, pairs, frag = summary["scenes"], summary["pairs"], summary.get("fragility")
    worst = max(scenes, key=lambda k: scenes[k]["ratio"])
    rows = [Measurement("planar cost over the same 1-D scene: " + " / ".join(scenes),
                        " / ".join(f"{v['ratio']:.1f}" for v in scenes.values()), "x",
                        f"medians of {repeats} interleaved runs; goal {target_ratio:g}x, largest {worst}; "
                        f"{machine_conditions()}"),
            Measurement("planar scenes at default rtol: largest error of Pi1",
                        f"{max(v['err_max'] for v in scenes.values()):.1e}", "1", "against rtol = 1e-12")]
    bases = [k for k, v in pairs.items() if isinstance(v, dict)]
    rows.append(Measurement(f"recorded pairs in the plane, median cost per sample over every pair and base "
                            f"(goal {target_us:g})", f"{pairs['us_per_sample_median']:.2f}", "us",
                            "; ".join(f"{b} {pairs[b]['us_per_sample_median']:.2f} (the x component alone "
                                      f"{pairs[b]['us_per_sample_1d_median']:.3f})" for b in bases)))
    if frag is not None:
        cpu = {b: frag[b]["mean_ms"] * 1e-3 * frag["analyses"] / 60.0 for b in frag if isinstance(frag[b], dict)
               and "mean_ms" in frag[b]}
        rows.append(Measurement(f"planar fragility study at full size ({frag['analyses']} analyses per building): "
                                "CPU time of solving, " + " / ".join(cpu), " / ".join(f"{v:.1f}" for v in cpu.values()),
                                "CPU-min", f"{len(frag['sampled'])} analyses per building timed (seeded draw), each "
                                "a planar and two 1-D solves with the floor's peaks"))
    return rows


def rocking_rows(summary: dict, repeats: int) -> list[Measurement]:
    """The rocking section's figures: a rocking scene's cost over the same scene sliding, records per sample.

    ``summary`` is :func:`isoslide.accuracy.rocking_cost.report`'s return.
    """
    rows = [Measurement("rocking block / the same contents sliding: cost ratio, median / largest (not overturning)",
                        f"{summary['ratio_median']:.2f} / {summary['ratio_max']:.2f}", "x",
                        f"{summary['rows']} scenes (4 buildings, Ricker and rectangular pulses, 3 intensities), "
                        f"median of {repeats} interleaved runs; {machine_conditions()}")]
    if "slow" in summary:
        rows.append(Measurement("rocking scenes past the 3x aim: steps / cost per step over the sliding twin's",
                                f"{summary['slow_steps_ratio']:.1f} / {summary['slow_step_cost_ratio']:.1f}", "x",
                                f"{summary['slow']} scenes, on the general building's solver where their "
                                "sliding twins run the paper model's own"))
    if "records" in summary:
        rows.append(Measurement("rocking block on the bundled records: cost per sample, rocking / sliding",
                                f"{summary['rock_ns_per_sample']:.0f} / {summary['slide_ns_per_sample']:.0f}", "ns",
                                f"{summary['records']} records under a linear isolator, medians"))
    return rows


def opensees_rows(summary: dict, points: int) -> list[Measurement]:
    """The OpenSees comparison's figures: OpenSees's cost over isoslide's per building class.

    ``summary`` is :func:`isoslide.accuracy.opensees_cost.report`'s return.
    """
    rows = []
    for name, s in summary.items():
        reach = (f"at dtau {s['dtau']:.0e} ({s['opensees_error']:.1e})" if s["reached"] else
                 f"at the finest pair dtau {s['dtau']:.0e}, still {s['opensees_error']:.1e} off "
                 "(the tolerance not reached)")
        rows.append(Measurement(f"OpenSees / isoslide cost per scene at 1e-3 in Pi1: {name}", f"{s['ratio']:.0f}",
                                "ratio", f"isoslide {s['isoslide_ms']:.2f} ms, OpenSees {s['opensees_s']:.2f} s "
                                f"{reach}; medians over {s.get('scenes', points)} scenes; {machine_conditions()}"))
    return rows
