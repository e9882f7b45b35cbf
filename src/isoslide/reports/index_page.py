"""``reports/index.html``: a pipeline run at a glance, as one self-contained HTML page.

:func:`index_html` takes the paths of a run's outputs and returns the page: the studies and their
datasets (title, dimensions, file size and the Python line that opens each), the figures as
thumbnails linking to the full images, links to every report, and the provenance (isoslide version,
git commit, run time from the benchmark files, the configuration) as tables.  The page loads no
script and nothing from the network; links and images are relative to the page's directory, so the
``reports/`` directory and ``results/`` can be opened offline from any place they are copied to
together.
"""

from __future__ import annotations

import csv
import html
import json
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from datetime import datetime, timezone
from pathlib import Path

import xarray as xr
from PIL import Image

from .. import __version__
from ..store.provenance import git_commit

STYLE = """
body { font-family: system-ui, sans-serif; margin: 2em auto; max-width: 72em; padding: 0 1em;
       color: #222; line-height: 1.4; }
h1 { margin-bottom: 0.2em; }
table { border-collapse: collapse; margin: 0.5em 0 1.5em; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.6em; text-align: left; vertical-align: top; }
th { background: #f3f3f3; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
code { background: #f6f6f6; padding: 0 0.2em; }
.figures { display: flex; flex-wrap: wrap; gap: 1em; }
figure { margin: 0; width: 260px; }
figure img { width: 260px; border: 1px solid #ddd; }
figcaption { font-size: 0.85em; }
"""


CAPTION_CHARS = 160
"""Longest figure caption shown under a thumbnail, characters (longer ones are cut at a word)."""


@dataclass(frozen=True)
class JobTimes:
    """Run time of the jobs of one rule, from its benchmark files.

    Attributes
    ----------
    rule : str
        Rule name (the directory of its benchmark files).
    jobs : int
        Number of benchmark files (jobs).
    total_s : float
        Sum of the jobs' wall-clock times, s.
    max_s : float
        Longest job, s.
    max_rss_mb : float
        Largest resident memory of a job, MB.
    """

    rule: str
    jobs: int
    total_s: float
    max_s: float
    max_rss_mb: float


def human_size(n_bytes: int) -> str:
    """File size as text (``"12.3 kB"``), decimal units; ``n_bytes`` in bytes."""
    if n_bytes < 0:
        raise ValueError(f"n_bytes = {n_bytes} is negative; a file size is >= 0")
    if n_bytes < 1000:
        return f"{n_bytes} B"
    size = n_bytes / 1000
    for unit in ("kB", "MB"):
        if size < 1000:
            return f"{size:.1f} {unit}"
        size /= 1000
    return f"{size:.1f} GB"


def job_times(benchmark_dir: Path | str) -> list[JobTimes]:
    """Per rule, the jobs' times from ``<benchmark_dir>/<rule>/*.tsv`` (Snakemake benchmark files).

    Parameters
    ----------
    benchmark_dir : path
        Directory of the benchmark files (``results/benchmarks``); missing: no rows.

    Returns
    -------
    list of JobTimes
        One per rule with at least one readable benchmark file, by rule name.
    """
    root = Path(benchmark_dir)
    out = []
    for rule_dir in sorted(p for p in root.glob("*") if p.is_dir()):
        seconds, rss = [], []
        for tsv in sorted(rule_dir.rglob("*.tsv")):
            with open(tsv, newline="") as f:
                rows = list(csv.DictReader(f, delimiter="\t"))
            for row in rows[:1]:
                seconds.append(float(row["s"]))
                rss.append(float(row["max_rss"]) if row["max_rss"] not in ("", "NA", "-") else 0.0)
        if seconds:
            out.append(JobTimes(rule_dir.name, len(seconds), sum(seconds), max(seconds), max(rss)))
    return out


def flatten(config: Mapping, prefix: str = "") -> list[tuple[str, str]]:
    """``(dotted key, value as compact JSON)`` of every leaf of a nested configuration.

    Lists are leaves (one row each); mappings are walked in key order.
    """
    rows = []
    for key in sorted(config):
        value = config[key]
        name = f"{prefix}{key}"
        if isinstance(value, Mapping) and value:
            rows += flatten(value, name + ".")
        else:
            rows.append((name, json.dumps(value, default=str)))
    return rows


def _rel(path: Path | str, out_dir: Path | str) -> str:
    return Path(os.path.relpath(Path(path), Path(out_dir))).as_posix()


def _e(text) -> str:
    return html.escape(str(text), quote=True)


def _table(header: Sequence[str], rows: Sequence[Sequence[str]], numeric: Sequence[int] = ()) -> str:
    """HTML table; cells are HTML already; columns ``numeric`` right-aligned."""
    head = "".join(f"<th>{_e(h)}</th>" for h in header)
    body = "".join(
        "<tr>" + "".join(f'<td class="num">{c}</td>' if i in numeric else f"<td>{c}</td>"
                         for i, c in enumerate(row)) + "</tr>"
        for row in rows)
    return f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def _dataset_row(name: str, path: Path, out_dir: Path) -> list[str]:
    with xr.open_dataset(path) as ds:
        title = str(ds.attrs.get("title", ""))
        dims = ", ".join(f"{d} = {n}" for d, n in ds.sizes.items())
    line = f'xr.open_dataset("{Path(path).as_posix()}")'
    return [_e(name), _e(title), _e(dims), human_size(path.stat().st_size),
            f'<code>{_e(line)}</code> (<a href="{_e(_rel(path, out_dir))}">file</a>)']


def _caption(png: Path) -> str:
    """The PNG's ``Description`` text (its caption), at most about CAPTION_CHARS characters."""
    with Image.open(png) as im:
        text = str(getattr(im, "text", {}).get("Description", ""))
    text = " ".join(text.split())
    if len(text) <= CAPTION_CHARS:
        return text
    return text[:text.rfind(" ", 0, CAPTION_CHARS)] + " …"


def _figure(png: Path, out_dir: Path) -> str:
    others = sorted(p for p in png.parent.glob(png.stem + ".*") if p.suffix != ".png")
    extra = "".join(f' <a href="{_e(_rel(p, out_dir))}">{_e(p.suffix[1:].upper())}</a>' for p in others)
    href = _e(_rel(png, out_dir))
    return (f'<figure><a href="{href}"><img src="{href}" alt="{_e(png.stem)}" loading="eager"></a>'
            f"<figcaption><b>{_e(png.stem)}</b>{extra}. {_e(_caption(png))}</figcaption></figure>")


def index_html(*, datasets: Mapping[str, Path | str], figures: Sequence[Path | str],
               reports: Sequence[Path | str], config: Mapping, out_dir: Path | str,
               benchmark_dir: Path | str | None, commit: str | None = None) -> str:
    """The index page of a run.

    Parameters
    ----------
    datasets : mapping of str to path
        ``{study or dataset name: netCDF file}``, in the order to show; the paths are printed as
        given in the Python line that opens each (so pass them relative to the workflow
        directory).
    figures : sequence of path
        PNG files, shown as thumbnails; a file of the same stem with another suffix (PDF) is linked
        next to each.
    reports : sequence of path
        HTML reports to link.
    config : mapping
        The complete configuration of the run, shown as a table of dotted keys.
    out_dir : path
        Directory the page is written to; every link is relative to it.
    benchmark_dir : path or None
        Directory of the run's benchmark files (``results/benchmarks``), for the run time; None or
        missing: the time is reported as not available.
    commit : str, optional
        Git commit to report; by default :func:`isoslide.store.provenance.git_commit`.

    Returns
    -------
    str
        A complete HTML document without scripts.
    """
    out_dir = Path(out_dir)
    missing = [str(p) for p in [*datasets.values(), *figures, *reports] if not Path(p).is_file()]
    if missing:
        raise FileNotFoundError(f"index page: input files missing: {missing}")
    ds_rows = [_dataset_row(name, Path(p), out_dir) for name, p in datasets.items()]
    report_items = "".join(f'<li><a href="{_e(_rel(p, out_dir))}">{_e(Path(p).stem)}</a></li>'
                           for p in reports)
    times = job_times(benchmark_dir) if benchmark_dir is not None else []
    if times:
        time_rows = [[_e(t.rule), str(t.jobs), f"{t.total_s:.1f}", f"{t.max_s:.1f}", f"{t.max_rss_mb:.0f}"]
                     for t in times]
        time_rows.append(["<b>all jobs</b>", str(sum(t.jobs for t in times)),
                          f"<b>{sum(t.total_s for t in times):.1f}</b>", f"{max(t.max_s for t in times):.1f}",
                          f"{max(t.max_rss_mb for t in times):.0f}"])
        time_html = ("<p>Wall-clock time of the jobs, from their benchmark files (summed over jobs; "
                     "jobs run side by side, so the run itself took less).</p>"
                     + _table(["rule", "jobs", "total (s)", "longest job (s)", "largest max_rss (MB)"],
                              time_rows, numeric=(1, 2, 3, 4)))
    else:
        time_html = "<p>Run time: not available (no benchmark files).</p>"
    prov = [["isoslide version", _e(__version__)],
            ["git commit", f"<code>{_e(commit if commit is not None else git_commit())}</code>"],
            ["page written", _e(datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC"))]]
    cfg_rows = [[f"<code>{_e(k)}</code>", f"<code>{_e(v)}</code>"] for k, v in flatten(config)]
    return f"""<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1.0">
<title>isoslide: the run at a glance</title>
<style>{STYLE}</style>
</head>
<body>
<h1>isoslide: the run at a glance</h1>
<p>Peak sliding of freestanding contents on seismically isolated floors under pulse-like ground
motion: datasets, figures and reports of this pipeline run.</p>
<h2>Reports</h2>
<ul>{report_items}</ul>
<h2>Studies and datasets</h2>
<p>Open a dataset in Python with <code>import xarray as xr</code> and the line next to it (from the
directory the workflow ran in).</p>
{_table(["name", "title", "dimensions", "size", "open with"], ds_rows, numeric=(3,))}
<h2>Figures</h2>
<div class="figures">{"".join(_figure(Path(p), out_dir) for p in figures)}</div>
<h2>Provenance</h2>
{_table(["item", "value"], prov)}
{time_html}
<h3>Configuration</h3>
{_table(["key", "value"], cfg_rows)}
</body>
</html>
"""
