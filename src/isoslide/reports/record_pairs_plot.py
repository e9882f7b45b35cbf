"""The figure of the recorded pairs against their fitted pulses, from their dataset only.

:func:`draw` reads the dataset of :func:`isoslide.studies.record_study.record_pairs_dataset` and
draws ``record_pairs``:

* (a) on a line: ``Pi1`` under each component as recorded against ``Pi1`` under its fitted pulse
  (log-log, the 1:1 line and the tolerance band), one marker per component, colour by ``Pi3``;
* (b) in the plane: the pair as recorded against the pair of fitted pulses, the same way;
* (c) the ratio record/pulse per ground motion: each component on a line and the pair in the plane;
* (d) the direction of the planar peak: the fitted pair's against the record's (degrees), with
  the lines of equal direction and of opposite sense (the same line).
"""

from __future__ import annotations

import logging

import numpy as np

from .figures import WIDTH, _colors, stems_drawer

log = logging.getLogger(__name__)

FIGURES = ("record_pairs",)
"""Names (file stems) of the figures."""

DATASETS = ("record_pairs",)
"""Names of the datasets :func:`draw` reads (``results/datasets/<name>.nc``)."""

MARKERS = {"x": "o", "y": "^", "plane": "s"}
"""Marker of each view."""

DEG = 180.0 / np.pi


def _building(pi3: float) -> str:
    return "fixed base" if pi3 == 0.0 else f"Π₃ = {pi3:g}"


def _one_to_one(ax, lo: float, hi: float, tol: float) -> None:
    xs = np.array([lo, hi])
    ax.plot(xs, xs, color="0.3", lw=0.8, zorder=1)
    ax.fill_between(xs, xs * (1.0 - tol), xs * (1.0 + tol), color="0.85", lw=0, zorder=0)
    ax.set_xlim(lo, hi)
    ax.set_ylim(lo, hi)


def _limits(*arrays) -> tuple:
    v = np.concatenate([np.asarray(a, float).ravel() for a in arrays])
    v = v[np.isfinite(v) & (v > 0.0)]
    if v.size == 0:
        return 1e-3, 1.0
    return 10.0 ** np.floor(np.log10(v.min())), 10.0 ** np.ceil(np.log10(v.max()))


def pairs_figure(ds):
    """The four panels of :mod:`this module <isoslide.reports.record_pairs_plot>`.  Returns the figure and its caption."""
    import matplotlib.pyplot as plt

    tol, atol = float(ds.attrs["tolerance"]), float(ds.attrs["angle_tolerance"])
    pi3s = ds["pi3"].values
    colors = dict(zip(pi3s, _colors(len(pi3s)), strict=True))
    fig, axs = plt.subplots(2, 2, figsize=(WIDTH, 6.4), layout="constrained")
    (a_line, a_plane), (a_ratio, a_angle) = axs

    # (a) on a line, (b) in the plane
    lo, hi = _limits(ds["pi1_record"], ds["pi1_pulse"], ds["pi1_record_plane"], ds["pi1_pulse_plane"])
    for ax, views, title in ((a_line, ("x", "y"), "(a) on a line: each component"),
                             (a_plane, ("plane",), "(b) in the plane: the pair")):
        _one_to_one(ax, lo, hi, tol)
        for view in views:
            if view == "plane":
                rec, pul = ds["pi1_record_plane"], ds["pi1_pulse_plane"]
            else:
                rec, pul = ds["pi1_record"].sel(component=view), ds["pi1_pulse"].sel(component=view)
            for pi3 in pi3s:
                r, p = rec.sel(pi3=pi3).values.ravel(), pul.sel(pi3=pi3).values.ravel()
                ok = (r > 0.0) & (p > 0.0)
                ax.scatter(p[ok], r[ok], s=12, marker=MARKERS[view], color=colors[pi3], alpha=0.8, lw=0,
                           label=f"{view}, {_building(pi3)}" if view != "plane" else _building(pi3), zorder=2)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(r"$\Pi_1$ under the fitted pulse" + ("s" if "plane" in views else ""))
        ax.set_ylabel(r"$\Pi_1$ under the record")
        ax.set_title(title, fontsize=8.5)
        ax.legend(loc="upper left", fontsize=6.5)

    # (c) the ratio per ground motion
    motions = [str(m) for m in ds["motion"].values]
    offsets = {"x": -0.22, "y": 0.0, "plane": 0.22}
    for i, m in enumerate(motions):
        for view, dx in offsets.items():
            if view == "plane":
                ratio = ds["record_over_pulse_plane"].sel(motion=m)
            else:
                ratio = ds["record_over_pulse"].sel(motion=m, component=view)
            for pi3 in pi3s:
                v = ratio.sel(pi3=pi3).values.ravel()
                v = v[np.isfinite(v) & (v > 0.0)]
                a_ratio.scatter(np.full(v.size, i + dx), v, s=10, marker=MARKERS[view], color=colors[pi3],
                                alpha=0.8, lw=0)
    a_ratio.axhline(1.0, color="0.3", lw=0.8)
    a_ratio.axhspan(1.0 - tol, 1.0 + tol, color="0.85", lw=0, zorder=0)
    a_ratio.set_yscale("log")
    a_ratio.set_xticks(range(len(motions)))
    a_ratio.set_xticklabels([m.split("_", 1)[-1] if len(motions) > 1 else m for m in motions], rotation=60,
                            ha="right", fontsize=6)
    a_ratio.set_ylabel(r"$\Pi_{1,record} / \Pi_{1,pulse}$")
    a_ratio.set_title("(c) ratio per pair: x ○, y △, plane □", fontsize=8.5)

    # (d) the direction of the planar peak
    ar, ap = ds["peak_angle_record"], ds["peak_angle_pulse"]
    for pi3 in pi3s:
        r, p = ar.sel(pi3=pi3).values.ravel() * DEG, ap.sel(pi3=pi3).values.ravel() * DEG
        ok = np.isfinite(r) & np.isfinite(p)
        a_angle.scatter(r[ok], p[ok], s=12, marker="s", color=colors[pi3], alpha=0.8, lw=0, label=_building(pi3))
    xs = np.array([-180.0, 180.0])
    a_angle.plot(xs, xs, color="0.3", lw=0.8)
    for shift in (-180.0, 180.0):
        a_angle.plot(xs, xs + shift, color="0.3", lw=0.8, ls="--")
    a_angle.set_xlim(-180, 180)
    a_angle.set_ylim(-180, 180)
    a_angle.set_xticks(range(-180, 181, 90))
    a_angle.set_yticks(range(-180, 181, 90))
    a_angle.set_xlabel("direction of the peak, recorded pair [°]")
    a_angle.set_ylabel("direction of the peak, fitted pair [°]")
    a_angle.set_title("(d) direction of the planar peak", fontsize=8.5)
    a_angle.legend(loc="lower right", fontsize=6.5)

    n_line = int(((ds["pi1_record"] > 0) & (ds["pi1_pulse"] > 0)).sum())
    n_plane = int(((ds["pi1_record_plane"] > 0) & (ds["pi1_pulse_plane"] > 0)).sum())
    caption = (
        f"Recorded pairs against their fitted {ds.attrs['shape']} pulses ({ds.sizes['motion']} pairs of "
        f"{ds.attrs.get('suite', 'the suite')}; Pi2 = {', '.join(f'{v:g}' for v in ds['pi2'].values)}; Pi3 = "
        f"{', '.join(f'{v:g}' for v in pi3s)}, Pi4 = {ds.attrs['pi4']:g}). (a) Pi1 under each component as "
        f"recorded against Pi1 under its fitted pulse, both in the component's own a_p and T_p ({n_line} cells "
        f"where both slide); (b) the pair as recorded against the pair of fitted pulses (Pi14, Pi15, Pi16 from "
        f"the two fits), in the x fit's scales ({n_plane} cells); grey: the 1:1 line and +-{tol:.0%}. (c) The "
        f"ratio record/pulse per pair. (d) The direction of the planar peak, atan2(u_y, u_x) in the building's "
        f"axes (wrapping at +-180 degrees): solid, the same direction; dashed, opposite senses on the same line "
        f"(the report counts a catch within {atol:g} degrees of the line). Cells where only one excitation "
        f"slides are not drawn.")
    return fig, caption


DRAWERS = {"record_pairs": pairs_figure}
"""The function drawing each figure of :data:`FIGURES`."""


draw = stems_drawer("draw", FIGURES, "figures of the recorded pairs",
                    lambda name, data: (DRAWERS[name], (data["record_pairs"],)),
                    "``record_pairs`` (:data:`DATASETS`).", log)
