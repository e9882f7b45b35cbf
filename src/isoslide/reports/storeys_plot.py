"""The figure of the storeys study: Pi1 over the contents' floor, one curve per number of storeys.

:func:`draw` reads the dataset of :func:`isoslide.studies.storeys.storeys_dataset` only.  One row
per isolator and Pi2, one column per Pi12; in each panel Pi1 over the floor's height ``k/N`` (0 the
isolated slab, 1 the roof), a curve per number of storeys ``N``.
"""

from __future__ import annotations

import logging
from pathlib import Path

import numpy as np

from ..datasets import open_dataset
from .figures import WIDTH, _colors, _render

log = logging.getLogger(__name__)

FIGURE = "storeys"
"""Name (file stem) of the figure."""

LABELS = {"linear": "linear isolator", "friction_pendulum": "friction pendulum"}


def figure(ds):
    """The figure and its caption."""
    import matplotlib.pyplot as plt

    isolators, pi12s, pi2s = ds["isolator"].values, ds["pi12"].values, ds["pi2"].values
    rows = [(iso, pi2) for iso in isolators for pi2 in pi2s]
    fig, axs = plt.subplots(len(rows), len(pi12s), figsize=(WIDTH, 1.9 * len(rows) + 0.6), squeeze=False,
                            layout="constrained", sharex=True)
    storeys = ds["storeys"].values
    colors = _colors(len(storeys))
    for r, (iso, pi2) in enumerate(rows):
        for c, pi12 in enumerate(pi12s):
            ax = axs[r, c]
            sub = ds["pi1"].sel(isolator=iso, pi2=pi2, pi12=pi12)
            for n, color in zip(storeys, colors, strict=True):
                floors = np.arange(int(n) + 1)
                ax.plot(floors / n, sub.sel(storeys=n).values[: int(n) + 1], marker="o", markersize=2.5,
                        color=color, label=f"N = {int(n)}")
            ax.set_title(rf"{LABELS.get(str(iso), str(iso))}, $\Pi_2 = {float(pi2):g}$, $\Pi_{{12}} = {float(pi12):g}$",
                         fontsize=7.5)
            ax.set_ylim(bottom=0.0)
            if c == 0:
                ax.set_ylabel(r"$\Pi_1 = u_{max}/(a_p T_p^2)$")
            if r == len(rows) - 1:
                ax.set_xlabel("floor height k/N (0 slab, 1 roof)")
    axs[0, -1].legend(title="storeys", loc="best", ncol=2)
    caption = (f"Storeys. Peak sliding Pi1 of contents on floor k of an isolated building of N storeys "
               f"(N = {', '.join(str(int(n)) for n in storeys)}), over the floor's height k/N, for a linear isolator "
               f"(Pi4 = {float(ds['pi4'].sel(isolator='linear')):g}) and a friction pendulum "
               f"(Pi9 = {float(ds['pi9'].sel(isolator='friction_pendulum')):g}, Pi10 = 0); Pi3 = {float(ds['pi3']):g}, "
               f"Pi11 = {float(ds['pi11']):g}, Pi13 = {float(ds['pi13']):g}; columns: Pi12 = T_s/T_p; "
               f"pulse {ds.attrs.get('pulse', '')}.")
    return fig, caption


def draw(dataset, outputs, settings: dict) -> str:
    """Draw the figure into every file of ``outputs`` (``storeys.<png|pdf|svg>``).

    Parameters
    ----------
    dataset : path or xarray.Dataset
        The storeys dataset (``results/datasets/storeys.nc``).
    outputs : sequence of path
        Files to write; each stem must be :data:`FIGURE`.
    settings : dict
        The ``figures`` section of a complete configuration (``dpi``).

    Returns
    -------
    str
        The caption (also stored in each file's metadata).
    """
    outputs = [Path(p) for p in outputs]
    wrong = sorted({p.stem for p in outputs} - {FIGURE})
    if wrong:
        raise ValueError(f"outputs = {wrong!r} are not the storeys figure; allowed stem: {FIGURE!r}")
    ds = open_dataset(dataset) if isinstance(dataset, (str, Path)) else dataset
    caption = _render(figure, (ds,), outputs, settings["dpi"])
    log.info("%s: %s", FIGURE, caption)
    return caption
