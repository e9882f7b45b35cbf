"""Every figure of the paper, drawn from the pipeline's datasets.

One function per figure, ``fig1`` ... ``fig8``, each returning a matplotlib
Figure and its caption; :func:`draw` renders one to files.  Master curves
(Figs. 3, 5-8) are plotted from the study datasets only; Figs. 1, 2 and 4 draw
the model, the friction law and the pulse from their definitions.

All figures share one style (:data:`STYLE`): axis labels carry the
Pi-group definitions, curve families use one sequential colour map, and
the groups held fixed are printed in a box on each panel.

Outputs are deterministic: PDF/SVG carry no creation date, PNG carries the
caption as its ``Description`` text chunk (read by the gallery report).
"""

from __future__ import annotations

import json
import logging
import math
from pathlib import Path

import numpy as np

from ..atomic import atomic_path
from ..datasets import open_dataset
from ..groups import GROUPS
from ..model.friction import stribeck
from ..pulses import get_pulse
from ..studies.record_study import ratio_summary

log = logging.getLogger(__name__)

STYLE = {
    "font.family": "DejaVu Sans",
    "font.size": 8.5,
    "axes.titlesize": 9,
    "axes.labelsize": 8.5,
    "legend.fontsize": 7.5,
    "legend.title_fontsize": 7.5,
    "legend.frameon": False,
    "xtick.labelsize": 7.5,
    "ytick.labelsize": 7.5,
    "xtick.direction": "in",
    "ytick.direction": "in",
    "xtick.top": True,
    "ytick.right": True,
    "axes.linewidth": 0.7,
    "lines.linewidth": 1.3,
    "axes.grid": True,
    "grid.linewidth": 0.4,
    "grid.alpha": 0.35,
    "savefig.bbox": "tight",
    "savefig.pad_inches": 0.04,
    "svg.hashsalt": "isoslide",
    "pdf.compression": 6,
}
"""matplotlib rcParams shared by every figure."""

CMAP = "viridis"
WIDTH = 7.0
"""Figure width, inches (two columns)."""

LABELS = {name: g.label for name, g in GROUPS.items()}
"""Axis label of every Pi-group (from the registry :mod:`isoslide.groups`)."""

SYMBOL = {name: g.tex for name, g in GROUPS.items()}
"""TeX symbol of every Pi-group."""


def stribeck_mu(v, mu_s, mu_k, beta, gamma=0.0):
    """Stribeck friction coefficient of paper Eq. 1 (n = 1), by :func:`isoslide.model.friction.stribeck`.

    ``mu(v) = mu_s sech(beta v) + mu_k (1 - sech(beta v)) + gamma |v|``

    Parameters
    ----------
    v : array_like
        Sliding velocity, m/s.
    mu_s, mu_k : float
        Static and kinetic friction coefficients.
    beta, gamma : float
        Transition and viscous constants, s/m.
    """
    return stribeck(np.asarray(v, dtype=float), mu_s, mu_k, beta, gamma)[0]


def _fmt(x: float) -> str:
    if x == 0:
        return "0"
    if abs(x) < 1e-2 or abs(x) >= 1e4:
        m, e = f"{x:.0e}".split("e")
        return rf"{m}\times10^{{{int(e)}}}" if m != "1" else rf"10^{{{int(e)}}}"
    return f"{x:g}"


PULSE_NAMES = {"ricker": "symmetric Ricker pulse", "rectangular": "rectangular pulse"}


def _fixed_text(ds, skip=()) -> str:
    """One line listing the groups held fixed in a dataset (its scalar coordinates) and the pulse."""
    parts = []
    for name in ("pi3", "pi4", "pi5", "pi6", "pi7", "pi8"):
        if name in ds.coords and ds[name].ndim == 0 and name not in skip:
            text = rf"${SYMBOL[name]} = {_fmt(float(ds[name]))}$"
            if name == "pi6" and "beta" in ds.coords and ds["beta"].ndim == 0 and float(ds["beta"]) > 0:
                text += rf" ($\beta = {float(ds['beta']):g}$ s/m)"
            parts.append(text)
    pulse = ds.attrs.get("pulse", "")
    return ", ".join(parts) + (f"; {PULSE_NAMES.get(pulse, pulse)}" if pulse else "")


def _subtitle(ax, title, note, wrap=False):
    """Panel title with a note (the fixed groups) in small type beneath it (two lines if ``wrap``)."""
    if wrap:
        note = note.replace("; ", "\n")
    ax.set_title(title, pad=(20 if wrap else 13) if note else 6)
    if note:
        ax.text(0.5, 1.012, note, transform=ax.transAxes, ha="center", va="bottom", fontsize=6.3,
                color="0.25")


def _text_box(ax, text, loc="upper right"):
    x, ha = (0.97, "right") if "right" in loc else (0.03, "left")
    y, va = (0.97, "top") if "upper" in loc else ((0.5, "center") if "center" in loc else (0.03, "bottom"))
    ax.text(x, y, text, transform=ax.transAxes, ha=ha, va=va, fontsize=6.8,
            bbox=dict(boxstyle="round,pad=0.3", fc="white", ec="0.7", lw=0.5, alpha=0.9))


def _colors(n):
    import matplotlib

    cmap = matplotlib.colormaps[CMAP]
    return [cmap(x) for x in np.linspace(0.0, 0.88, n)]


def master_curves(ax, ds, family: str, select=None, label_fmt=None, legend_loc="upper right",
                  legend_title=None):
    """Plot Pi1 against Pi2, one curve per value of ``family``.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    ds : xarray.Dataset
        A study dataset (dims ``(..., family, ..., pi2)``).
    family : str
        Dimension with one curve per value.
    select : dict, optional
        ``{dim: value}`` selecting the other swept dimensions.
    label_fmt : callable, optional
        ``(index, value) -> legend label``.

    Returns
    -------
    xarray.Dataset
        The selected dataset (its scalar coordinates are the groups held fixed).
    """
    sub = ds.sel(select) if select else ds
    pi1 = sub["pi1"].transpose(family, "pi2")
    values = sub[family].values
    for color, (k, val) in zip(_colors(len(values)), enumerate(values), strict=False):
        lab = label_fmt(k, val) if label_fmt else f"${_fmt(float(val))}$"
        ax.plot(sub["pi2"].values, pi1.values[k], color=color, label=lab)
    ax.set_xlabel(LABELS["pi2"])
    ax.set_ylabel(LABELS["pi1"])
    ax.set_xlim(0.0, float(sub["pi2"].max()))
    top = float(np.nanmax(pi1.values)) if pi1.size else 1.0
    ax.set_ylim(0.0, 1.12 * top if top > 0 else 1.0)
    ax.legend(title=legend_title or LABELS.get(family, family), loc=legend_loc, handlelength=1.6)
    return sub


# ----------------------------------------------------------------------------------------------
# the figures
# ----------------------------------------------------------------------------------------------

def fig1(datasets=None, settings=None):
    """Fig. 1: the model, drawn in code: isolated mass on spring-dashpot isolators, sliding block."""
    import matplotlib.pyplot as plt
    from matplotlib import patches

    fig, ax = plt.subplots(figsize=(WIDTH * 0.62, 2.7))
    ax.set_xlim(0, 10)
    ax.set_ylim(-0.9, 5.2)
    ax.set_aspect("equal")
    ax.axis("off")
    # ground with hatching and the abutment wall
    ax.add_patch(patches.Rectangle((0.3, -0.45), 9.2, 0.45, hatch="////", fc="white", ec="0.3", lw=0.8))
    ax.add_patch(patches.Rectangle((0.3, 0.0), 0.45, 2.6, hatch="////", fc="white", ec="0.3", lw=0.8))
    # isolated mass M_b on rollers
    mx, my, mw, mh = 3.4, 0.55, 5.2, 1.6
    ax.add_patch(patches.Rectangle((mx, my), mw, mh, fc="#dbe6f1", ec="0.15", lw=1.0))
    ax.text(mx + mw / 2, my + mh / 2, r"$M_b$" + "\n(isolated base and\nrigid superstructure)",
            ha="center", va="center", fontsize=7.5)
    for rx in (mx + 0.7, mx + mw - 0.7):
        ax.add_patch(patches.Circle((rx, 0.27), 0.27, fc="white", ec="0.15", lw=0.9))
    # spring k_b (upper) and dashpot c_b (lower) from the wall to the mass
    y1, y2, x0, x1 = my + 1.15, my + 0.45, 0.75, mx
    zz = np.linspace(x0 + 0.5, x1 - 0.5, 13)
    ys = y1 + 0.18 * np.where(np.arange(13) % 2 == 0, 0.0, np.where(np.arange(13) % 4 == 1, 1, -1))
    ax.plot(np.r_[x0, zz, x1], np.r_[y1, ys, y1], color="0.15", lw=0.9)
    ax.text((x0 + x1) / 2, y1 + 0.3, r"$k_b$", ha="center", fontsize=8)
    xm = (x0 + x1) / 2
    ax.plot([x0, xm - 0.1], [y2, y2], color="0.15", lw=0.9)
    ax.plot([xm - 0.1, xm - 0.1], [y2 - 0.22, y2 + 0.22], color="0.15", lw=0.9)
    ax.plot([xm - 0.35, xm + 0.4, xm + 0.4, xm - 0.35], [y2 + 0.3, y2 + 0.3, y2 - 0.3, y2 - 0.3],
            color="0.15", lw=0.9)
    ax.plot([xm + 0.4, x1], [y2, y2], color="0.15", lw=0.9)
    ax.text(xm, y2 - 0.62, r"$c_b$", ha="center", fontsize=8)
    # the sliding block m_EC with friction at its base
    bx, by, bw, bh = 5.2, my + mh, 1.6, 1.1
    ax.add_patch(patches.Rectangle((bx, by), bw, bh, fc="#f3d9b1", ec="0.15", lw=1.0))
    ax.text(bx + bw / 2, by + bh / 2, r"$m_{EC}$", ha="center", va="center", fontsize=8.5)
    ax.text(bx + bw + 0.15, by + 0.12, r"$\mu(\dot u_s)$: Stribeck, Eq. 1", fontsize=7, va="bottom")
    for k in range(7):
        xx = bx + 0.1 + k * 0.23
        ax.plot([xx, xx + 0.15], [by - 0.0, by + 0.12], color="0.4", lw=0.5)
    # displacement arrows
    arrow = dict(arrowstyle="-|>", lw=0.8, color="0.1", shrinkA=0, shrinkB=0, mutation_scale=8)
    ax.annotate("", xy=(2.3, -0.7), xytext=(0.9, -0.7), arrowprops=arrow)
    ax.text(2.4, -0.7, r"$u_g(t)$, $\ddot u_g = a_p\,p(t/T_p)$", va="center", fontsize=7.5)
    ax.annotate("", xy=(mx + mw + 0.9, my + mh / 2), xytext=(mx + mw, my + mh / 2), arrowprops=arrow)
    ax.text(mx + mw + 0.95, my + mh / 2, r"$u_b$", va="center", fontsize=8)
    ax.annotate("", xy=(bx + bw / 2 + 0.9, by + bh + 0.35), xytext=(bx + bw / 2, by + bh + 0.35),
                arrowprops=arrow)
    ax.plot([bx + bw / 2, bx + bw / 2], [by + bh + 0.2, by + bh + 0.5], color="0.1", lw=0.7)
    ax.text(bx + bw / 2 + 1.0, by + bh + 0.35, r"$u_s$ (sliding, relative to the floor)", va="center",
            fontsize=7.5)
    ax.text(0.3, 4.95, r"$T_b = 2\pi\sqrt{M_b/k_b}$,  $\xi_b = c_b / (2\sqrt{k_b M_b})$", fontsize=7.5)
    caption = ("Fig. 1. The model: a rigid isolated mass M_b (base and superstructure) on linear "
               "viscously damped isolators (k_b, c_b) carries a freestanding rigid block m_EC that "
               "slides with Stribeck friction mu(v); u_g is the ground, u_b the base relative to the "
               "ground and u_s the sliding of the block relative to the floor. T_b and xi_b are defined "
               "with M_b alone. Drawn in code (isoslide.reports.figures.fig1).")
    return fig, caption


def fig2(datasets=None, settings=None):
    """Fig. 2: the Stribeck friction law for several beta."""
    import matplotlib.pyplot as plt

    betas = settings["fig2_beta"]
    mu = settings["fig2_mu"]
    mu_s, mu_k, gamma = mu["mu_s"], mu["mu_k"], mu["gamma"]
    fig, (a, b) = plt.subplots(1, 2, figsize=(WIDTH, 2.6))
    v = np.linspace(-0.3, 0.3, 4001)
    vl = np.logspace(-5, 0.5, 800)
    for color, beta in zip(_colors(len(betas)), betas, strict=False):
        a.plot(v, stribeck_mu(v, mu_s, mu_k, beta, gamma) * np.sign(v), color=color,
               label=rf"$\beta = {beta:g}$ s/m")
        b.semilogx(vl, stribeck_mu(vl, mu_s, mu_k, beta, gamma), color=color, label=rf"$\beta = {beta:g}$ s/m")
    gv = 0.1
    b.semilogx(vl, stribeck_mu(vl, mu_s, mu_k, 100.0, gv), color="0.3", ls="--",
               label=rf"$\beta = 100$ s/m, $\gamma = {gv:g}$ s/m")
    a.axhline(0, color="0.5", lw=0.5)
    a.set_xlabel(r"sliding velocity $\dot u_s$ (m/s)")
    a.set_ylabel(r"$F_f / (m_{EC} g) = \mu(\dot u_s)\,\mathrm{sgn}(\dot u_s)$")
    a.set_title("(a) friction force")
    b.set_xlabel(r"$|\dot u_s|$ (m/s)")
    b.set_ylabel(r"$\mu(\dot u_s)$")
    b.set_title("(b) static-to-kinetic transition")
    b.axhline(mu_s, color="0.5", lw=0.6, ls=":")
    b.axhline(mu_k, color="0.5", lw=0.6, ls=":")
    b.text(1.5e-5, mu_s, r" $\mu_s$", va="bottom", fontsize=7)
    b.text(1.5e-5, mu_k, r" $\mu_k$", va="bottom", fontsize=7)
    b.legend(loc="upper right")
    a.legend(loc="upper left")
    _text_box(a, r"$\mu(v) = \mu_s\,\mathrm{sech}(\beta v) + \mu_k\,(1 - \mathrm{sech}(\beta v)) "
                 r"+ \gamma |v|$" + f"\n$\\mu_s = {mu_s:g}$, $\\mu_k = {mu_k:g}$, $\\gamma = {gamma:g}$ s/m",
              loc="lower right")
    fig.tight_layout()
    caption = (f"Fig. 2. Stribeck friction model (paper Eq. 1 with n = 1) for mu_s = {mu_s:g}, "
               f"mu_k = {mu_k:g} and beta = {', '.join(f'{x:g}' for x in betas)} s/m: the larger beta, "
               f"the sharper the drop from static to kinetic friction. Dashed: with viscous contact "
               f"gamma = {gv:g} s/m. In dimensionless form beta v = Pi6 v' and gamma g v = Pi7 v' "
               f"(v' = v/(a_p T_p)).")
    return fig, caption


def fig3(datasets, settings=None):
    """Fig. 3: rectangular pulse, ground velocity, and Newmark's solution against the solver."""
    import matplotlib.pyplot as plt


    ds = _open(datasets, "fig3_newmark")
    p = get_pulse(ds.attrs.get("pulse", "rectangular"))
    fig, axs = plt.subplots(1, 3, figsize=(WIDTH, 2.3), gridspec_kw={"width_ratios": [1, 1, 1.35]})
    tau = np.linspace(-0.5, 2.5, 3001)
    axs[0].plot(tau, p.accel(tau), color="C0")
    axs[0].set_xlabel(r"$\tau = t/T_p$")
    axs[0].set_ylabel(r"$\ddot u_g / a_p$")
    axs[0].set_title("(a) rectangular pulse")
    axs[0].set_ylim(-0.2, 1.3)
    axs[1].plot(tau, p.velocity(tau), color="C0")
    axs[1].set_xlabel(r"$\tau = t/T_p$")
    axs[1].set_ylabel(r"$\dot u_g / (a_p T_p)$")
    axs[1].set_title("(b) ground velocity")
    pi2 = ds["pi2"].values
    pi1 = ds["pi1"].values
    x = np.linspace(float(pi2.min()), float(pi2.max()), 600)
    newmark = np.where(x < 1.0, 0.5 * (1.0 / x - 1.0), 0.0)
    ax = axs[2]
    ax.plot(x, newmark, color="0.2", lw=1.0, label="Newmark (1965)")
    ax.plot(pi2, pi1, "o", ms=3.0, mfc="none", mew=0.8, color="C1", label="isoslide solver")
    ax.set_yscale("symlog", linthresh=0.01)
    ax.set_ylim(0, None)
    ax.set_xlabel(LABELS["pi2"])
    ax.set_ylabel(LABELS["pi1"])
    ax.set_title("(c) peak sliding, fixed base")
    ax.legend(loc="upper right")
    exact = np.where(pi2 < 1.0, 0.5 * (1.0 / pi2 - 1.0), 0.0)
    err = float(np.max(np.abs(pi1 - exact) / np.maximum(exact, 1e-300) * (exact > 0)))
    _text_box(ax, r"$\Pi_1 = \frac{1}{2}\left(\frac{1}{\Pi_2} - 1\right)$, $\Pi_2 < 1$"
                  + f"\nmax rel. difference {err:.1e}", loc="lower left")
    fig.tight_layout()
    caption = (f"Fig. 3. (a) Rectangular ground-acceleration pulse of amplitude a_p and duration T_p; "
               f"(b) ground velocity, which keeps a_p T_p after the pulse; (c) peak sliding of a rigid "
               f"block on a fixed base with Coulomb friction: Newmark's closed form "
               f"Pi1 = (1/Pi2 - 1)/2 against the isoslide solver ({pi2.size} points of dataset "
               f"fig3_newmark; largest relative difference {err:.1e}).")
    return fig, caption


def fig4(datasets=None, settings=None):
    """Fig. 4: a real pulse-like record (acceleration, velocity) with its fitted Ricker wavelet.

    ``datasets["record"]`` is the output of :func:`isoslide.studies.record_study.fig4_data`
    (``results/datasets/fig4_record.nc``); without it the Ricker wavelet is drawn alone.
    """
    import matplotlib.pyplot as plt

    datasets = datasets or {}
    if datasets.get("record") is None:
        return _fig4_ricker_only()
    rec = _open(datasets, "record")
    at = rec.attrs
    t = rec["time"].values
    lo, hi = float(at["t_plot_min"]), float(at["t_plot_max"])
    keep = (t >= lo) & (t <= hi)
    t = t[keep]
    fig, (a, b) = plt.subplots(1, 2, figsize=(WIDTH, 2.9))
    name = str(at.get("record", "record"))
    fits = [("ricker", "C3", "-", "fitted Ricker")]
    if "accel_mp" in rec:
        fits.append(("mp", "C0", "--", "fitted M-P pulse"))
    a.plot(t, rec["accel_record"].values[keep], color="0.55", lw=0.8, label=name)
    b.plot(t, rec["velocity_record"].values[keep], color="0.55", lw=0.8, label=name)
    for key, color, ls, label in fits:
        a.plot(t, rec[f"accel_{key}"].values[keep], color=color, ls=ls, lw=1.2, label=label)
        b.plot(t, rec[f"velocity_{key}"].values[keep], color=color, ls=ls, lw=1.2, label=label)
    a.set_xlabel("t (s)")
    a.set_ylabel(r"$\ddot u_g$ (g)")
    a.set_title("(a) ground acceleration")
    b.set_xlabel("t (s)")
    b.set_ylabel(r"$\dot u_g$ (m/s)")
    b.set_title("(b) ground velocity")
    for ax in (a, b):
        ax.set_xlim(lo, hi)
    a.legend(loc="lower left", fontsize=6.3, handlelength=1.6)
    stand_in = str(at.get("stand_in_for", ""))
    fit_text = (rf"Ricker fit: $a_p$ = {float(at['ricker_a_p_g']):.3f} g, $T_p$ = {float(at['ricker_T_p']):.2f} s, "
                rf"$R^2$ = {float(at['ricker_r2']):.2f}")
    if "mp_r2" in at:
        fit_text += rf"; M-P fit: $T_p$ = {float(at['mp_T_p']):.2f} s, $R^2$ = {float(at['mp_r2']):.2f}"
    note = (f"{name} ({at.get('event', '')}, {at.get('station', '')} {at.get('component', '')})"
            + (" stands in for the paper's Rinaldi RRS228 (1994 Northridge), not available offline."
               if stand_in else ".") + "\n" + fit_text)
    fig.text(0.01, 0.01, note, fontsize=6.6, color="0.25", ha="left", va="bottom")
    fig.tight_layout(rect=(0, 0.12, 1, 1))
    caption = (f"Fig. 4. Real pulse-like record {name} ({at.get('event', '')}, {at.get('station', '')} "
               f"{at.get('component', '')}; {at.get('source', '')}) and the analytical pulse fitted to its dominant "
               f"acceleration pulse: (a) acceleration, (b) velocity (integrated from rest). "
               + (f"It stands in for the paper's record, {stand_in}. " if stand_in else "")
               + f"Fitted symmetric Ricker wavelet: a_p = {float(at['ricker_a_p_g']):.3f} g, "
               f"T_p = {float(at['ricker_T_p']):.2f} s, R^2 = {float(at['ricker_r2']):.2f} over the pulse window"
               + (f"; Mavroeidis-Papageorgiou pulse: T_p = {float(at['mp_T_p']):.2f} s, "
                  f"R^2 = {float(at['mp_r2']):.2f}" if "mp_r2" in at else "")
               + ". The paper's Rinaldi record is fitted with T_p = 1 s.")
    return fig, caption


def _fig4_ricker_only():
    import matplotlib.pyplot as plt


    p = get_pulse("ricker")
    t = np.linspace(-2.5, 2.5, 2001)
    fig, (a, b) = plt.subplots(1, 2, figsize=(WIDTH, 2.4))
    a.plot(t, p.accel(t), color="C3", label=r"symmetric Ricker, $T_p = 1$ s")
    b.plot(t, p.velocity(t), color="C3", label=r"symmetric Ricker, $T_p = 1$ s")
    a.set_xlabel("t (s)")
    a.set_ylabel(r"$\ddot u_g / a_p$")
    a.set_title("(a) ground acceleration")
    b.set_xlabel("t (s)")
    b.set_ylabel(r"$\dot u_g / (a_p T_p)$")
    b.set_title("(b) ground velocity")
    for ax in (a, b):
        ax.legend(loc="upper right")
        _text_box(ax, "Ricker wavelet only: no record dataset\nwas given (results/datasets/fig4_record.nc)",
                  loc="lower left")
    fig.tight_layout()
    caption = ("Fig. 4. Symmetric Ricker wavelet (paper Eq. 3) with T_p = 1 s, whose Fourier amplitude "
               "peaks at 1/T_p: (a) acceleration, (b) velocity. No record dataset was given, so the "
               "Ricker wavelet is drawn alone.")
    return fig, caption


def records(datasets, settings=None):
    """Peak sliding under each real record against under its fitted pulse (``records.nc``).

    One panel per record: Pi1(Pi2) under the record (solid) and under its fitted pulse (dashed), one
    colour per Pi3; a last panel: Pi1_pulse against Pi1_record over every cell where both slide.
    """
    import matplotlib.pyplot as plt


    ds = _open(datasets, "records")
    tol = float(ds.attrs.get("tolerance", 0.25))
    summ = ratio_summary(ds, tol)
    names = [str(r) for r in ds["record"].values]
    n = len(names) + 1
    ncols = min(3, n)
    nrows = math.ceil(n / ncols)
    fig, axs = plt.subplots(nrows, ncols, figsize=(WIDTH, 2.9 * nrows + 0.3), squeeze=False)
    axs = axs.ravel()
    pi3s = ds["pi3"].values
    colors = _colors(len(pi3s))
    for k, name in enumerate(names):
        ax = axs[k]
        sub = ds.sel(record=name)
        for c, pi3 in zip(colors, pi3s, strict=False):
            ax.plot(ds["pi2"].values, sub["pi1_record"].sel(pi3=pi3).values, color=c, ls="-",
                    label=rf"${_fmt(float(pi3))}$")
            ax.plot(ds["pi2"].values, sub["pi1_pulse"].sel(pi3=pi3).values, color=c, ls="--")
        ax.set_xlabel(LABELS["pi2"])
        ax.set_ylabel(LABELS["pi1"] if k % ncols == 0 else "")
        ax.set_xlim(0.0, float(ds["pi2"].max()))
        ax.set_ylim(bottom=0.0)
        s = summ.sel(record=name)
        _note_title(ax, f"({'abcdefghijkl'[k]}) {name}",
                    rf"$a_p$ = {float(sub['a_p_g']):.2f} g, $T_p$ = {float(sub['T_p']):.2f} s, "
                    rf"$R^2$ = {float(sub['r2']):.2f}" + "\n" + _summary_line(s, tol))
        if k == 0:
            ax.legend(title=LABELS["pi3"], loc="best", handlelength=1.6, fontsize=6.5)
    ax = axs[len(names)]
    marks = "osD^v<>p*hX"
    both = ds["slides_record"].values.astype(bool) & ds["slides_pulse"].values.astype(bool)
    hi = 0.0
    for k, name in enumerate(names):
        m = both[k]
        x, y = ds["pi1_record"].values[k][m], ds["pi1_pulse"].values[k][m]
        ax.scatter(x, y, s=9, marker=marks[k % len(marks)], label=name, alpha=0.8, lw=0)
        if x.size:
            hi = max(hi, float(x.max()), float(y.max()))
    if hi > 0:
        lo = hi * 1e-3
        xs = np.array([lo, hi * 1.5])
        ax.plot(xs, xs, color="k", lw=0.8)
        ax.fill_between(xs, xs * (1 - tol), xs * (1 + tol), color="0.5", alpha=0.2, lw=0,
                        label=rf"$\pm${tol:.0%}")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlim(lo, hi * 1.5)
        ax.set_ylim(lo, hi * 1.5)
    ax.set_xlabel(r"$\Pi_1$ under the record")
    ax.set_ylabel(r"$\Pi_1$ under the fitted pulse")
    _note_title(ax, f"({'abcdefghijkl'[len(names)]}) all records, cells where both slide",
                _summary_line(summ.sel(record="all"), tol))
    if len(axs) > n:   # an empty panel: the legend of the scatter goes there, clear of the points
        handles, labels = ax.get_legend_handles_labels()
        axs[n].legend(handles, labels, loc="center left", fontsize=6.5, title="panel "
                      f"({'abcdefghijkl'[len(names)]})", title_fontsize=6.5)
        axs[n].set_axis_off()
    else:
        ax.legend(loc="upper left", fontsize=5.8, handlelength=1.0, borderaxespad=0.2)
    for ax in axs[n + 1:]:
        ax.set_visible(False)
    note = (f"Solid: real record; dashed: its fitted {_shape_name(ds)} pulse (in its own a_p and T_p the same "
            f"master curves for every record). The fitted a_p and T_p scale both, so the ratio "
            f"Pi1_pulse/Pi1_record is the ratio of the physical peak sliding. "
            f"Fixed: Pi4 = {float(ds.attrs['pi4']):g}, Pi5 = {float(ds.attrs['pi5']):g}, "
            f"Pi6 = {float(ds.attrs['pi6']):g}, Pi7 = {float(ds.attrs['pi7']):g}, "
            f"Pi8 = {float(ds.attrs['pi8']):g}.")
    fig.text(0.01, 0.005, note, fontsize=6.3, color="0.25", ha="left", va="bottom", wrap=True)
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    a = summ.sel(record="all")
    caption = (f"Records. Peak sliding Pi1 under {len(names)} real pulse-like record{'s' if len(names) > 1 else ''} ({', '.join(names)}) "
               f"and under each record's fitted {_shape_name(ds)} pulse, over Pi2 = "
               f"{float(ds['pi2'].min()):g}...{float(ds['pi2'].max()):g} ({ds.sizes['pi2']} values) and "
               f"Pi3 = {_list(ds['pi3'])}, with the fitted a_p and T_p as the scales (solid: record, dashed: pulse; "
               f"scaled by its own a_p and T_p the fitted pulse gives the same master curves for every record). "
               f"Over all "
               f"{int(a['n_cells'])} cells: both slide in {int(a['n_both_slide'])}, where the ratio "
               f"Pi1_pulse/Pi1_record has median {float(a['median_ratio']):.2f}, P10-P90 "
               f"{float(a['p10_ratio']):.2f}-{float(a['p90_ratio']):.2f}, and {_pct(a['within_tol'])} of cells lie "
               f"within +-{tol:.0%}; only the record slides in {int(a['n_only_record'])} cells, only the pulse in "
               f"{int(a['n_only_pulse'])}. Fixed: Pi4 = {float(ds.attrs['pi4']):g}, Coulomb friction "
               f"(Pi5 = {float(ds.attrs['pi5']):g}, Pi6 = {float(ds.attrs['pi6']):g}), "
               f"Pi7 = {float(ds.attrs['pi7']):g}, Pi8 = {float(ds.attrs['pi8']):g}.")
    return fig, caption


def _shape_name(ds) -> str:
    shape = str(ds.attrs.get("shape", "ricker"))
    return {"ricker": "Ricker", "mavroeidis_papageorgiou": "Mavroeidis-Papageorgiou"}.get(shape, shape)


def _pct(x) -> str:
    x = float(x)
    return f"{x:.0%}" if np.isfinite(x) else "n/a"


def _summary_line(s, tol) -> str:
    """Three or two lines: the ratio statistics of one record (or all) from :func:`ratio_summary`."""
    only = f"slides under record only / pulse only: {int(s['n_only_record'])} / {int(s['n_only_pulse'])}"
    if int(s["n_both_slide"]) == 0:
        return "no cell where both slide\n" + only
    return (f"ratio median {float(s['median_ratio']):.2f} (P10-P90 {float(s['p10_ratio']):.2f}-"
            f"{float(s['p90_ratio']):.2f})\nwithin $\\pm${tol:.0%}: {_pct(s['within_tol'])}\n" + only)


def _note_title(ax, title, note):
    """Panel title with a multi-line note in small type beneath it."""
    lines = note.count("\n") + 1
    ax.set_title(title, pad=4 + 7.5 * lines, fontsize=8)
    ax.text(0.5, 1.012, note, transform=ax.transAxes, ha="center", va="bottom", fontsize=5.9,
            color="0.25", linespacing=1.15)


def fig5(datasets, settings=None):
    """Fig. 5: master curves for Pi3 (left) and for Pi4 = xi_b at Pi3 = 1 (right)."""
    import matplotlib.pyplot as plt

    left, right = _open(datasets, "fig5_pi3"), _open(datasets, "fig5_pi4")
    fig, (a, b) = plt.subplots(1, 2, figsize=(WIDTH, 3.0))
    sub = master_curves(a, left, "pi3")
    _subtitle(a, r"(a) isolation period ratio $\Pi_3$", _fixed_text(sub, skip=("pi3",)))
    sel = {"pi3": 1.0} if "pi3" in right.dims else None
    sub = master_curves(b, right, "pi4", select=sel)
    _subtitle(b, r"(b) isolation damping $\Pi_4 = \xi_b$ at resonance", _fixed_text(sub, skip=("pi4",)))
    fig.tight_layout()
    caption = ("Fig. 5. Master curves Pi1(Pi2) of a symmetric Ricker pulse: (a) for isolation-to-pulse "
               f"period ratios Pi3 = {_list(left['pi3'])} (0.01: effectively a fixed base) with "
               f"xi_b = {_scalar(left, 'pi4')}; (b) for isolation damping xi_b = {_list(right['pi4'])} "
               f"at resonance, Pi3 = 1. Coulomb friction (Pi5 = 1, Pi6 = 0), Pi7 = 0, "
               f"Pi8 = {_scalar(left, 'pi8')}. Each curve holds for every a_p, T_p and M_b.")
    return fig, caption


def _panels(ds, family, fig_note, width=WIDTH, label_fmt=None):
    """One panel per Pi3 of ``ds``, curves over ``family``; the fixed groups as a figure note."""
    import matplotlib.pyplot as plt

    pi3s = ds["pi3"].values
    fig, axs = plt.subplots(1, len(pi3s), figsize=(width, 2.8), squeeze=False)
    sub = ds
    for k, (ax, pi3) in enumerate(zip(axs[0], pi3s, strict=False)):
        sub = master_curves(ax, ds, family, select={"pi3": float(pi3)}, label_fmt=label_fmt)
        ax.set_title(rf"({'abcdefgh'[k]}) $\Pi_3 = T_b/T_p = {float(pi3):g}$")
        if k:
            ax.set_ylabel("")
    note = "Fixed: " + _fixed_text(sub, skip=("pi3", family)) + (f".\n{fig_note}" if fig_note else "")
    fig.text(0.01, 0.01, note, fontsize=6.6, color="0.25", ha="left", va="bottom")
    fig.tight_layout(rect=(0, 0.1 if fig_note else 0.06, 1, 1))
    return fig


def fig6(datasets, settings=None):
    """Fig. 6: master curves for Pi5 at three Pi3."""
    ds = _open(datasets, "fig6_pi5")
    fig = _panels(ds, "pi5", _ref_text(ds))
    caption = (f"Fig. 6. Effect of the kinetic-to-static friction ratio Pi5 = mu_k/mu_s "
               f"({_list(ds['pi5'])}) for Pi3 = {_list(ds['pi3'])}, xi_b = {_scalar(ds, 'pi4')}, "
               f"beta = {_scalar(ds, 'beta')} s/m, i.e. Pi6 = {_scalar(ds, 'pi6')} with the reference "
               f"a_p T_p = {_ref(ds)} m/s (a_p = 1 g, T_p = 1 s); Pi7 = 0, Pi8 = {_scalar(ds, 'pi8')}.")
    return fig, caption


def fig7(datasets, settings=None):
    """Fig. 7: master curves for Pi6 (one panel per Pi5 of the study) and Pi7 (last panel)."""
    import matplotlib.pyplot as plt

    left, right = _open(datasets, "fig7_pi6"), _open(datasets, "fig7_pi7")
    pi5s = [float(v) for v in left["pi5"].values] if "pi5" in left.dims else [None]
    n = len(pi5s) + 1
    fig, axs = plt.subplots(1, n, figsize=(WIDTH * (1.0 if n <= 2 else 1.25), 3.1), squeeze=False)
    axs = axs[0]
    if "beta" in left.coords and left["beta"].ndim:
        fmt = lambda k, v: rf"${float(v):.4g}$ ($\beta$ = {float(left['beta'][k]):g})"  # noqa: E731
        title = r"$\Pi_6 = \beta a_p T_p$ ($\beta$ in s/m)"
    else:
        fmt, title = None, None
    letters = "abcdefgh"
    for k, pi5 in enumerate(pi5s):
        sel = {"pi5": pi5} if pi5 is not None else None
        sub = master_curves(axs[k], left, "pi6", select=sel, label_fmt=fmt, legend_title=title)
        head = rf"({letters[k]}) Stribeck transition $\Pi_6$" + (rf", $\Pi_5 = {pi5:g}$" if pi5 is not None else "")
        _subtitle(axs[k], head, _fixed_text(sub, skip=("pi6", "pi5")), wrap=n > 2)
    sub = master_curves(axs[-1], right, "pi7", label_fmt=lambda k, v: f"${float(v):.4g}$")
    _subtitle(axs[-1], rf"({letters[n - 1]}) viscous contact $\Pi_7 = \gamma g T_p$", _fixed_text(sub, skip=("pi7",)),
              wrap=n > 2)
    fig.text(0.01, 0.01, _ref_text(left) + "\n" + r"$\Pi_{7,max} = \gamma_{max}\, g\, T_{p,max}$ = 0.1 s/m "
             r"$\times$ g $\times$ 5 s = 4.90 (the paper prints $\gamma a_p T_p$: $\approx$ 10 at "
             r"$a_{p,max} = 2g$)", fontsize=6.6, color="0.25", ha="left", va="bottom")
    fig.tight_layout(rect=(0, 0.1, 1, 1))
    beta_list = _list(left["beta"]) if "beta" in left.coords else "-"
    pi5_text = _list(left["pi5"]) if "pi5" in left.coords else "-"
    caption = (f"Fig. 7. Left: effect of the Stribeck transition, beta = {beta_list} s/m, i.e. "
               f"Pi6 = {_list(left['pi6'])} with the reference a_p T_p = {_ref(left)} m/s, at "
               f"Pi3 = {_scalar(left, 'pi3')} and Pi5 = {pi5_text} (the paper states neither). Right: effect "
               f"of viscous contact Pi7 = gamma g T_p = {_list(right['pi7'])} at Pi3 = {_scalar(right, 'pi3')}, "
               f"Coulomb friction; the upper bound 4.90 = gamma_max g T_p,max with gamma_max = 0.1 s/m and "
               f"T_p,max = 5 s. The paper prints this group as gamma a_p T_p, which is not a similarity group "
               f"unless a_p = g (see the similarity report). xi_b = 0.1 throughout.")
    return fig, caption


def fig8(datasets, settings=None):
    """Fig. 8: master curves for Pi8 at three Pi3."""
    ds = _open(datasets, "fig8_pi8")
    fig = _panels(ds, "pi8", "")
    caption = (f"Fig. 8. Effect of the mass ratio Pi8 = m_EC/M_b ({_list(ds['pi8'])}) for "
               f"Pi3 = {_list(ds['pi3'])}, xi_b = {_scalar(ds, 'pi4')}, Coulomb friction. The coupled "
               f"two-degree-of-freedom model is solved exactly: while the block sticks the moving mass "
               f"is M_b (1 + Pi8).")
    return fig, caption


FIGURES = {f"fig{n}": f for n, f in enumerate((fig1, fig2, fig3, fig4, fig5, fig6, fig7, fig8), start=1)}
FIGURES["records"] = records


def _open(datasets, name):

    if name not in datasets:
        raise KeyError(f"figure needs dataset {name!r}; given: {sorted(datasets)}")
    d = datasets[name]
    return open_dataset(d) if isinstance(d, (str, Path)) else d


def _list(da) -> str:
    return ", ".join(f"{float(v):g}" for v in np.asarray(da).ravel())


def _scalar(ds, name) -> str:
    return f"{float(ds[name]):g}" if name in ds.coords else "-"


def _ref(ds) -> str:
    cfg = ds.attrs.get("isoslide_config")
    if cfg:
        return f"{json.loads(cfg).get('a_p_T_p'):g}"
    return "?"


def _ref_text(ds) -> str:
    return (rf"$\beta$ (s/m) $\to \Pi_6 = \beta\,(a_pT_p)_{{ref}}$ with the reference "
            rf"$(a_pT_p)_{{ref}}$ = {_ref(ds)} m/s ($a_p$ = 1 g, $T_p$ = 1 s)")


def draw(name: str, datasets: dict, outputs, settings: dict):
    """Draw figure ``name`` (``"fig1"`` ... ``"fig8"``) from ``datasets`` into each path of ``outputs``.

    Parameters
    ----------
    name : str
        Figure name: ``"fig1"`` ... ``"fig8"`` or ``"records"`` (record versus pulse).
    datasets : dict of str -> path or xarray.Dataset
        Study datasets by study name; ``"record"`` (Fig. 4) and ``"records"`` for the record figures.
    outputs : sequence of path
        Files to write; the format follows the extension (png, pdf, svg).
    settings : dict
        The ``figures`` section of a complete configuration (:func:`isoslide.config.load`).

    Returns
    -------
    str
        The caption.
    """
    if name not in FIGURES:
        raise ValueError(f"figure = {name!r} is invalid; allowed: {sorted(FIGURES)}")
    caption = _render(FIGURES[name], (datasets, settings), outputs, settings["dpi"])
    log.info("%s", caption)
    return caption


def render_stems(outputs, figures, what: str, datasets: dict, drawer_of, dpi: int, logger=log) -> dict:
    """Draw every figure of ``figures`` into the ``outputs`` whose stem is its name.

    Parameters
    ----------
    outputs : sequence of path
        Files to write (``<figure>.<png|pdf|svg>``); every stem must be in ``figures``.
    figures : sequence of str
        Figure names, in drawing order.
    what : str
        What the figures are, for the error message (``"planar figures"``).
    datasets : dict of str -> path or xarray.Dataset
        Opened once (paths with :func:`isoslide.datasets.open_dataset`) before drawing.
    drawer_of : callable
        ``(name, data) -> (drawer, args)``: ``drawer(*args)`` returns ``(fig, caption)``.
    dpi : int
        Resolution of raster outputs.
    logger : logging.Logger, optional
        Receives each figure's caption.

    Returns
    -------
    dict of str -> str
        Caption of each figure drawn.

    Raises
    ------
    ValueError
        If a stem of ``outputs`` is not in ``figures``.
    """
    outputs = [Path(p) for p in outputs]
    unknown = sorted({p.stem for p in outputs} - set(figures))
    if unknown:
        raise ValueError(f"outputs = {unknown!r} are not {what}; allowed stems: {list(figures)}")
    data = {k: open_dataset(v) if isinstance(v, (str, Path)) else v for k, v in datasets.items()}
    captions = {}
    for name in figures:
        mine = [p for p in outputs if p.stem == name]
        if not mine:
            continue
        caption = _render(*drawer_of(name, data), mine, dpi)
        logger.info("%s: %s", name, caption)
        captions[name] = caption
    return captions


_DRAW_DOC = """Draw every figure of :data:`FIGURES` into the ``outputs`` whose stem is its name.

    Parameters
    ----------
    datasets : dict of str -> path or xarray.Dataset
        {datasets}
    outputs : sequence of path
        Files to write (``<figure>.<png|pdf|svg>``).
    settings : dict
        The ``figures`` section of a complete configuration (``dpi``).

    Returns
    -------
    dict of str -> str
        Caption of each figure drawn.
    """


def stems_drawer(name: str, figures, what: str, drawer_of, datasets_doc: str, logger=log):
    """The ``draw(datasets, outputs, settings)`` of a module's figures: :func:`render_stems` at ``settings["dpi"]``.

    Parameters
    ----------
    name : str
        The function's name in its module (``draw_all``).
    figures, what, drawer_of, logger
        As for :func:`render_stems`.
    datasets_doc : str
        The datasets the figures read, for the function's docstring.

    Returns
    -------
    callable
        ``draw(datasets, outputs, settings) -> {figure: caption}``.
    """
    def draw(datasets: dict, outputs, settings: dict) -> dict:
        return render_stems(outputs, figures, what, datasets, drawer_of, settings["dpi"], logger)

    draw.__name__ = draw.__qualname__ = name
    draw.__doc__ = _DRAW_DOC.format(datasets=datasets_doc)
    return draw


def _render(drawer, args, outputs, dpi: int) -> str:
    """Draw ``drawer(*args)`` -> ``(fig, caption)`` in :data:`STYLE`, save it into every path of ``outputs``.

    Each file is written by :func:`_save`; the figure is closed, also on error.  Returns the caption.
    """
    import matplotlib
    import matplotlib.pyplot as plt

    with matplotlib.rc_context(STYLE):
        fig, caption = drawer(*args)
        try:
            for k, out in enumerate(outputs):
                _save(fig, Path(out), caption, dpi=dpi)
                if k == 0:
                    # the layout the first file settled holds for the others: not computed again
                    fig.set_layout_engine("none")
        finally:
            plt.close(fig)
    return caption


def _save(fig, path: Path, caption: str, dpi: int = 200):
    """Save deterministically and atomically; the caption goes into the file's metadata."""
    ext = path.suffix.lstrip(".").lower()
    title = f"isoslide {path.stem}"
    meta = {
        "png": {"Title": title, "Description": caption, "Software": "isoslide/matplotlib"},
        "pdf": {"Title": title, "Subject": caption, "CreationDate": None, "ModDate": None},
        "svg": {"Title": title, "Description": caption, "Date": None},
    }
    if ext not in meta:
        raise ValueError(f"unsupported figure format {ext!r}; allowed: png, pdf, svg")
    with atomic_path(path, suffix=f".{ext}") as tmp:
        fig.savefig(tmp, format=ext, dpi=dpi, metadata=meta[ext])


def read_caption(png_path) -> str:
    """Caption stored in a figure PNG's ``Description`` text chunk ("" if none)."""
    from PIL import Image

    with Image.open(png_path) as im:
        return im.text.get("Description", "") if hasattr(im, "text") else ""
