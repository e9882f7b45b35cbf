"""The figures of the planar study, from its datasets only.

:func:`draw_all` reads the datasets of :func:`isoslide.studies.planar.planar_dataset` and
:func:`isoslide.studies.planar.pi5_dataset` and draws

* ``planar``: master curves Pi1 over Pi2, one curve per Pi14 (0: the main component alone, the
  paper's 1-D model), one panel per building (Pi3) and Pi15, without vertical motion;
* ``planar_ratio``: the planar/1-D amplification over Pi2 (top) and the angle of the peak's line
  off the main component's line (bottom, degrees), per building;
* ``planar_vertical``: Pi1 with the vertical component over Pi1 without it, per building;
* ``planar_pi5``: the Pi5 curves of the complete-similarity slice, 1-D (Pi14 = 0) and in the plane.
"""

from __future__ import annotations

import logging

import numpy as np

from .figures import WIDTH, _colors, stems_drawer

log = logging.getLogger(__name__)

FIGURES = ("planar", "planar_ratio", "planar_vertical", "planar_pi5")
"""Names (file stems) of the figures, in order."""

DATASETS = ("planar", "planar_pi5")
"""Names of the datasets :func:`draw_all` reads (``results/datasets/<name>.nc``)."""

STYLES = ("-", "--", ":", "-.")
"""Line styles of the Pi15 values, in order."""

DEG = 180.0 / np.pi


def _building(pi3: float) -> str:
    return "fixed base (Π₃ = 0)" if pi3 == 0.0 else f"isolated, Π₃ = {pi3:g}"


def _grid_text(ds) -> str:
    return (f"pulse {ds.attrs['pulse']} along x, {ds.attrs['pulse_y']} along y (Pi16 = {float(ds['pi16']):g}); "
            f"contents Pi5 = {float(ds['pi5']):g}, Pi6 = {float(ds['pi6']):g}, Pi7 = {float(ds['pi7']):g}, "
            f"Pi8 = {float(ds['pi8']):g}; isolator Pi4 = {float(ds['pi4'].max()):g}")

def _grid_axes(ax, bottom_row: bool, first_column: bool, ylabel: str) -> None:
    """Start the y axis at 0; label y in the first column and Pi2 along the bottom row."""
    ax.set_ylim(bottom=0.0)
    if first_column:
        ax.set_ylabel(ylabel)
    if bottom_row:
        ax.set_xlabel(r"$\Pi_2 = \mu_k g / a_p$")



def master(ds):
    """Pi1 over Pi2 per Pi14; rows Pi15, columns Pi3 (Pi17 = 0).  Returns the figure and its caption."""
    import matplotlib.pyplot as plt

    pi3s, pi15s, pi14s = ds["pi3"].values, ds["pi15"].values, ds["pi14"].values
    fig, axs = plt.subplots(len(pi15s), len(pi3s), figsize=(WIDTH, 2.0 * len(pi15s) + 0.6), squeeze=False,
                            layout="constrained", sharex=True)
    colors = _colors(len(pi14s))
    sub = ds["pi1"].sel(pi17=0.0)
    for r, pi15 in enumerate(pi15s):
        for c, pi3 in enumerate(pi3s):
            ax = axs[r, c]
            for pi14, color in zip(pi14s, colors, strict=True):
                label = "Π₁₄ = 0 (1-D)" if pi14 == 0.0 else f"Π₁₄ = {pi14:g}"
                ax.plot(ds["pi2"], sub.sel(pi3=pi3, pi15=pi15, pi14=pi14), marker="o", markersize=2.2, color=color,
                        label=label)
            ax.set_title(f"{_building(pi3)}, Π₁₅ = {pi15:g}", fontsize=7.5)
            _grid_axes(ax, r == len(pi15s) - 1, c == 0, r"$\Pi_1 = u_{max}/(a_p T_p^2)$")
    axs[0, -1].legend(loc="best")
    caption = ("Planar. Peak Euclidean sliding Pi1 over Pi2, one curve per Pi14 = a_py/a_p (0: the main component "
               "alone, the 1-D model); columns: fixed base and linear isolators (Pi3 = T_b/T_p), rows: Pi15 = "
               f"T_py/T_p; no vertical motion; {_grid_text(ds)}.")
    return fig, caption


def ratio(ds):
    """Amplification (top) and the peak's angle off the main axis (bottom) over Pi2; columns Pi3 (Pi17 = 0)."""
    import matplotlib.pyplot as plt
    from matplotlib.ticker import NullFormatter, ScalarFormatter

    pi3s, pi15s = ds["pi3"].values, ds["pi15"].values
    pi14s = ds["pi14"].values[ds["pi14"].values > 0]
    fig, axs = plt.subplots(2, len(pi3s), figsize=(WIDTH, 5.0), squeeze=False, layout="constrained", sharex=True)
    colors = _colors(len(pi14s) + 1)[1:]
    sub = ds.sel(pi17=0.0)
    for c, pi3 in enumerate(pi3s):
        top, bottom = axs[0, c], axs[1, c]
        for pi14, color in zip(pi14s, colors, strict=True):
            for pi15, style in zip(pi15s, STYLES, strict=False):
                cur = sub.sel(pi3=pi3, pi15=pi15, pi14=pi14)
                amp = np.where(np.isfinite(cur["amplification"].values), cur["amplification"].values, np.nan)
                label = f"Π₁₄ = {pi14:g}, Π₁₅ = {pi15:g}"
                top.plot(ds["pi2"], amp, style, color=color, marker="o", markersize=2, label=label)
                bottom.plot(ds["pi2"], cur["peak_off_axis"].values * DEG, style, color=color, marker="o",
                            markersize=2)
        top.axhline(1.0, color="0.3", linewidth=0.7)
        top.set_yscale("log")
        top.yaxis.set_major_formatter(ScalarFormatter())
        top.yaxis.set_minor_formatter(NullFormatter())
        top.set_title(_building(pi3), fontsize=7.5)
        bottom.set_ylim(0.0, 90.0)
        bottom.set_yticks([0, 30, 60, 90])
        bottom.set_xlabel(r"$\Pi_2 = \mu_k g / a_p$")
        if c == 0:
            top.set_ylabel("Π₁ plane / Π₁ 1-D")
            bottom.set_ylabel("peak's line off x [deg]")
    handles, labels = axs[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=len(pi14s), fontsize=6.5)
    caption = ("Planar ratio. Top: Pi1 in the plane over Pi1 of the main component alone on the same building "
               "(log scale; missing where the 1-D contents do not slide). Bottom: angle between the line of the peak "
               "sliding displacement and the main component's line (0 to 90 degrees). Colours: Pi14, line styles: "
               f"Pi15; no vertical motion; {_grid_text(ds)}.")
    return fig, caption


def vertical(ds):
    """Pi1 with the vertical component over Pi1 without it, over Pi2; columns Pi3."""
    import matplotlib.pyplot as plt

    pi3s, pi15s, pi14s = ds["pi3"].values, ds["pi15"].values, ds["pi14"].values
    pi17s = ds["pi17"].values[1:]
    rows = max(len(pi17s), 1)
    fig, axs = plt.subplots(rows, len(pi3s), figsize=(WIDTH, 2.2 * rows + 1.0), squeeze=False, layout="constrained",
                            sharex=True, sharey=True)
    colors = _colors(len(pi14s))
    for r, pi17 in enumerate(pi17s):
        for c, pi3 in enumerate(pi3s):
            ax = axs[r, c]
            for pi14, color in zip(pi14s, colors, strict=True):
                for pi15, style in zip(pi15s, STYLES, strict=False):
                    v = ds["vertical_ratio"].sel(pi17=pi17, pi3=pi3, pi15=pi15, pi14=pi14).values
                    ax.plot(ds["pi2"], np.where(np.isfinite(v), v, np.nan), style, color=color, marker="o",
                            markersize=2, label=f"Π₁₄ = {pi14:g}, Π₁₅ = {pi15:g}")
            ax.axhline(1.0, color="0.3", linewidth=0.7)
            ax.set_title(f"{_building(pi3)}, Π₁₇ = {pi17:g}", fontsize=7.5)
            if c == 0:
                ax.set_ylabel("Π₁ with / without vertical")
            if r == rows - 1:
                ax.set_xlabel(r"$\Pi_2 = \mu_k g / a_p$")
    if len(pi17s):
        handles, labels = axs[0, 0].get_legend_handles_labels()
        fig.legend(handles, labels, loc="outside lower center", ncol=len(pi14s), fontsize=6.5)
    caption = (f"Planar vertical. Pi1 with a vertical {ds.attrs['pulse_z']} pulse of amplitude Pi17 g (main pulse's "
               "time axis) over Pi1 without it, both horizontal components acting; missing where the contents slide "
               f"in neither case. Colours: Pi14, line styles: Pi15; {_grid_text(ds)}.")
    return fig, caption


def pi5(ds5):
    """The Pi5 curves: rows Pi14 (0: 1-D), columns Pi3; the relative spread in each title."""
    import matplotlib.pyplot as plt

    pi3s, pi14s, pi5s = ds5["pi3"].values, ds5["pi14"].values, ds5["pi5"].values
    fig, axs = plt.subplots(len(pi14s), len(pi3s), figsize=(WIDTH, 2.0 * len(pi14s) + 0.6), squeeze=False,
                            layout="constrained", sharex=True)
    colors = _colors(len(pi5s))
    for r, pi14 in enumerate(pi14s):
        for c, pi3 in enumerate(pi3s):
            ax = axs[r, c]
            for p5, color in zip(pi5s, colors, strict=True):
                ax.plot(ds5["pi2"], ds5["pi1"].sel(pi3=pi3, pi14=pi14, pi5=p5), color=color, marker="o", markersize=2,
                        label=f"Π₅ = {p5:g}")
            rel = float(ds5["relative_spread"].sel(pi3=pi3, pi14=pi14))
            where = "1-D" if pi14 == 0.0 else f"Π₁₄ = {pi14:g}"
            ax.set_title(f"{where}, Π₃ = {pi3:g}: spread {rel:.3f}", fontsize=7.5)
            _grid_axes(ax, r == len(pi14s) - 1, c == 0, r"$\Pi_1$")
    axs[0, -1].legend(loc="best")
    caption = ("Planar Pi5. Pi1 over Pi2 per Pi5 = mu_k/mu_s (Stribeck friction, Pi6 = "
               f"{float(ds5['pi6']):g}), in the 1-D model (Pi14 = 0) and in the plane (Pi15 = {float(ds5['pi15']):g}); "
               "spread: largest range of Pi1 over the Pi5 curves at one Pi2, over their largest Pi1 (complete "
               f"similarity holds at most {float(ds5.attrs['spread_tolerance']):g}).")
    return fig, caption


DRAWERS = {"planar": (master, "planar"), "planar_ratio": (ratio, "planar"),
           "planar_vertical": (vertical, "planar"), "planar_pi5": (pi5, "planar_pi5")}
"""``{figure: (drawer, dataset it reads)}``."""


def _drawer_of(name, data):
    drawer, source = DRAWERS[name]
    return drawer, (data[source],)


draw_all = stems_drawer("draw_all", FIGURES, "planar figures", _drawer_of,
                        "``planar`` and ``planar_pi5`` (:data:`DATASETS`).", log)
