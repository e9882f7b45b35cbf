"""Quick-look plots of the command line: one solve's history, one record's fitted pulse.

:func:`plot_history` draws a :class:`~isoslide.store.history_io.HistoryTable`
(ground and floor accelerations above, sliding displacement below with the
stick and slip phases shaded; a planar history: the lengths of the acceleration
vectors, both sliding components and the path of the contents on the floor);
:func:`plot_fit` a record with its fitted pulse (acceleration and velocity).  Both write PNG,
PDF or SVG by the file extension (:data:`PLOT_SUFFIXES`).  The figures of the paper are
:mod:`isoslide.reports.figures`'.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..store.history_io import HistoryTable
from ..records import G, PulseFit, Record

__all__ = ["PLOT_SUFFIXES", "check_plot_path", "plot_fit", "plot_history"]

PLOT_SUFFIXES = (".png", ".pdf", ".svg")
"""File extensions the plots can be written to."""


def check_plot_path(path) -> Path:
    """``path`` as a Path if its extension is one of :data:`PLOT_SUFFIXES`.

    Raises
    ------
    ValueError
        Another extension (the message names the value and the allowed ones).
    """
    p = Path(path)
    if p.suffix.lower() not in PLOT_SUFFIXES:
        raise ValueError(f"plot = {str(path)!r} has an unknown extension {p.suffix!r}; "
                         f"allowed: {', '.join(PLOT_SUFFIXES)}")
    return p


def _figure(nrows: int):
    """A figure with ``nrows`` axes sharing the time axis (non-interactive backend)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(nrows, 1, figsize=(7.0, 2.6 * nrows), sharex=True, layout="constrained")
    return plt, fig, axes


def _spans(phase: np.ndarray):
    """``(start, end, value)`` index runs of equal ``phase``."""
    edges = np.flatnonzero(np.diff(phase) != 0) + 1
    starts = np.concatenate([[0], edges])
    ends = np.concatenate([edges, [phase.size - 1]])
    return [(int(a), int(b), int(phase[a])) for a, b in zip(starts, ends, strict=True)]


def plot_history(table: HistoryTable, path, title: str = "") -> Path:
    """Ground and floor acceleration, and sliding displacement with stick/slip phases shaded.

    Parameters
    ----------
    table : HistoryTable
        From :func:`isoslide.store.history_io.history_table` (SI or dimensionless).
    path : str or Path
        Output file, ``.png``, ``.pdf`` or ``.svg``.
    title : str
        Figure title.

    Returns
    -------
    Path
    """
    path = check_plot_path(path)
    if "slide_disp_x" in table.columns:
        return _plot_planar(table, path, title)
    c, u = table.columns, table.units
    phys = bool(table.attrs.get("physical"))
    t = c["time"]
    plt, fig, (ax1, ax2) = _figure(2)
    ax1.plot(t, c["ground_accel"], lw=0.9, color="0.45", label="ground")
    ax1.plot(t, c["floor_accel"], lw=1.1, color="C0", label="floor (absolute)")
    ax1.axhline(0.0, color="0.8", lw=0.6)
    ax1.set_ylabel(f"acceleration [{u['ground_accel']}]" if phys else "acceleration / a_p")
    ax1.legend(loc="upper right", fontsize=8)
    colours = {1: "C3", -1: "C2"}
    labelled = set()
    for a, b, ph in _spans(c["phase"]):
        if ph != 0:
            lab = f"slip {'+' if ph > 0 else '-'}" if ph not in labelled else None
            labelled.add(ph)
            ax2.axvspan(t[a], t[b], color=colours[ph], alpha=0.18, lw=0, label=lab)
    ax2.plot(t, c["slide_disp"], lw=1.2, color="k", label="sliding displacement")
    ax2.axhline(0.0, color="0.8", lw=0.6)
    ax2.set_ylabel(f"sliding [{u['slide_disp']}]" if phys else "sliding / (a_p T_p^2)")
    ax2.set_xlabel(f"time [{u['time']}]" if phys else "time / T_p")
    ax2.legend(loc="best", fontsize=8, title="unshaded: stuck", title_fontsize=8)
    if title:
        fig.suptitle(title, fontsize=10)
    fig.savefig(path)
    plt.close(fig)
    return path


def _plot_planar(table: HistoryTable, path: Path, title: str) -> Path:
    """:func:`plot_history` of a planar history.

    The lengths ``|a|`` of the ground's and the floor's accelerations; ``u_x``, ``u_y`` and ``|u|``
    with the slides shaded; the path ``(u_x, u_y)`` of the contents on their floor.
    """
    c, u = table.columns, table.units
    phys = bool(table.attrs.get("physical"))
    t = c["time"]
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=(7.0, 7.8), layout="constrained")
    grid = fig.add_gridspec(3, 1)
    ax1 = fig.add_subplot(grid[0])
    ax2 = fig.add_subplot(grid[1], sharex=ax1)
    ax3 = fig.add_subplot(grid[2])
    ax1.plot(t, np.hypot(c["ground_accel_x"], c["ground_accel_y"]), lw=0.9, color="0.45", label="ground")
    ax1.plot(t, np.hypot(c["floor_accel_x"], c["floor_accel_y"]), lw=1.1, color="C0", label="floor (absolute)")
    ax1.set_ylabel(f"|acceleration| [{u['ground_accel_x']}]" if phys else "|acceleration| / a_p")
    ax1.legend(loc="upper right", fontsize=8)
    for a, b, ph in _spans(c["phase"]):
        if ph != 0:
            ax2.axvspan(t[a], t[b], color="C3", alpha=0.18, lw=0)
    ax2.plot(t, c["slide_disp_x"], lw=1.0, color="C0", label="x")
    ax2.plot(t, c["slide_disp_y"], lw=1.0, color="C2", label="y")
    ax2.plot(t, np.hypot(c["slide_disp_x"], c["slide_disp_y"]), lw=1.3, color="k", label="|u|")
    ax2.axhline(0.0, color="0.8", lw=0.6)
    ax2.set_ylabel(f"sliding [{u['slide_disp_x']}]" if phys else "sliding / (a_p T_p^2)")
    ax2.set_xlabel(f"time [{u['time']}]" if phys else "time / T_p")
    ax2.legend(loc="best", fontsize=8, title="shaded: sliding", title_fontsize=8)
    ax3.plot(c["slide_disp_x"], c["slide_disp_y"], lw=1.2, color="k")
    ax3.plot([0.0], [0.0], "o", color="0.5", ms=4)
    ax3.set_aspect("equal", adjustable="datalim")
    unit = f" [{u['slide_disp_x']}]" if phys else " / (a_p T_p^2)"
    ax3.set_xlabel("sliding along x" + unit)
    ax3.set_ylabel("sliding along y" + unit)
    if title:
        fig.suptitle(title, fontsize=10)
    fig.savefig(path)
    plt.close(fig)
    return path


def plot_fit(record: Record, fit: PulseFit, path, before: float = 4.0, after: float = 6.0) -> Path:
    """A record's acceleration and velocity with its fitted pulse, around the pulse.

    Parameters
    ----------
    record : Record
        The record (acceleration in g).
    fit : PulseFit
        Its fitted pulse (:meth:`Record.fit`).
    path : str or Path
        Output file, ``.png``, ``.pdf`` or ``.svg``.
    before, after : float
        Plotted window, in fitted periods before and after the fitted peak.

    Returns
    -------
    Path
    """
    path = check_plot_path(path)
    t = record.time
    plt, fig, (ax1, ax2) = _figure(2)
    label = "Ricker" if fit.shape == "ricker" else "Mavroeidis-Papageorgiou"
    ax1.plot(t, record.accel, lw=0.8, color="0.4", label=record.name)
    ax1.plot(t, fit.accel(t) / G, lw=1.4, color="C3",
             label=f"{label}: a_p = {fit.a_p_g:.3f} g, T_p = {fit.T_p:.3f} s, R^2 = {fit.r2:.2f}")
    ax1.set_ylabel("ground acceleration [g]")
    ax1.legend(loc="upper right", fontsize=8)
    ax2.plot(t, record.velocity(), lw=0.8, color="0.4", label="record (integrated from rest)")
    ax2.plot(t, fit.velocity(t), lw=1.4, color="C3", label=f"fitted {label}")
    ax2.set_ylabel("ground velocity [m/s]")
    ax2.set_xlabel("record time [s]")
    ax2.legend(loc="upper right", fontsize=8)
    ax2.set_xlim(max(t[0], fit.t_peak - before * fit.T_p), min(t[-1], fit.t_peak + after * fit.T_p))
    fig.suptitle(f"{record.name}: {record.event}, {record.station} {record.component}".strip(", "),
                 fontsize=10)
    fig.savefig(path)
    plt.close(fig)
    return path
