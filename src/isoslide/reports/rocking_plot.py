"""The rocking study's figures, drawn from its datasets only (:mod:`isoslide.studies.rocking`).

* :func:`draw_spectra` -- the least ``Pi21 = a_p/(g tan alpha)`` that overturns the block against
  ``1/Pi19 = 1/(p T_p)``, one panel per pulse, one curve per ``Pi3 = T_b/T_p`` (0: fixed base), with
  the linearised closed form of the rectangular pulse;
* :func:`draw_isolation` -- the ratio of the isolated to the fixed-base overturning ``Pi21``;
* :func:`draw_map` -- what a block does over its friction ``mu_s`` and aspect ratio ``Pi18 = b/h``
  (rest, slide, rock, slide and rock, overturn), with ``theta_max/alpha`` written in each cell;
* :func:`draw_fragility` -- the probability of overturning against PGA, PFA and PFV, fitted curves
  and observed fractions, fixed base and isolated slab.

Each returns the :class:`matplotlib.figure.Figure` (the report's notebook shows it inline) and, given
``outputs``, also saves it there.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..groups import GROUPS
from ..studies.fragility import probability
from ..studies.rocking import RESPONSES
from .figures import WIDTH, _colors

__all__ = ["draw_fragility", "draw_isolation", "draw_map", "draw_spectra"]

INVERSE_PI19 = r"$1/\Pi_{19} = 1/(p\,T_p)$"
"""Abscissa label of the spectra."""

RESPONSE_COLOURS = {"rest": "#f2f2f2", "slide": "#9ecae1", "rock": "#fdae6b", "slide_and_rock": "#a1d99b",
                    "overturned": "#de2d26"}
"""Colour of each response of the map."""


def _save(fig, outputs, dpi: int) -> None:
    for path in outputs:
        fig.savefig(path, dpi=dpi)


def _base_label(pi3: float) -> str:
    return "fixed base" if pi3 == 0.0 else rf"$\Pi_3 = {pi3:g}$"


def draw_spectra(ds: xr.Dataset, outputs=(), dpi: int = 150):
    """The overturning spectra of ``rocking_spectra.nc``: least overturning Pi21 over 1/Pi19."""
    import matplotlib.pyplot as plt

    pulses = [str(p) for p in ds["pulse"].values]
    fig, axs = plt.subplots(1, len(pulses), figsize=(WIDTH, 3.0), squeeze=False, layout="constrained", sharey=True)
    inv = ds["inverse_pi19"].values
    colours = _colors(ds.sizes["pi3"])
    for ax, p in zip(axs[0], pulses, strict=True):
        for b, c in zip(ds["pi3"].values, colours, strict=True):
            s = ds.sel(pulse=p, pi3=b)
            style = dict(color="k", ls="-") if b == 0.0 else dict(color=c, ls="-")
            ax.plot(inv, s["pi21_overturn"].values, marker="o", markersize=3, label=_base_label(float(b)), **style)
            starts = s["bracket_status"].values == 1
            if starts.any():
                ax.plot(inv[starts], s["pi21_overturn"].values[starts], "v", color=style["color"], markersize=5)
        if p == "rectangular":
            ax.plot(inv, ds["pi21_linearised_rectangular"].values, "k:", label="linearised, fixed base")
        ax.set_yscale("log")
        ax.axhline(float(ds["pi21"].values[-1]), color="0.6", lw=0.6, ls="--")
        ax.set_title(f"{p} pulse", fontsize=9)
        ax.set_xlabel(INVERSE_PI19)
        ax.grid(alpha=0.3, which="both")
    axs[0, 0].set_ylabel(r"least overturning $\Pi_{21} = a_p/(g\tan\alpha)$")
    axs[0, -1].legend(fontsize=7, loc="upper left")
    fig.suptitle(rf"Overturning spectra, $b/h = {float(ds['pi18']):g}$ (dashed grey: top of the scan; "
                 r"triangles: the scan's first amplitude overturns)", fontsize=8.5)
    _save(fig, outputs, dpi)
    return fig


def draw_isolation(ds: xr.Dataset, outputs=(), dpi: int = 150):
    """Isolated over fixed-base least overturning Pi21, per pulse and Pi3, over 1/Pi19."""
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(WIDTH * 0.62, 3.0), layout="constrained")
    inv = ds["inverse_pi19"].values
    colours = _colors(ds.sizes["pi3"])
    for p, marker in zip(ds["pulse"].values, "osd^v", strict=False):
        for b, c in zip(ds["pi3"].values[1:], colours[1:], strict=True):
            r = ds["isolation_ratio"].sel(pulse=p, pi3=b).values
            ax.plot(inv, r, marker=marker, color=c, markersize=3.5, ls="-" if p == "ricker" else "--",
                    label=rf"{p}, $\Pi_3 = {float(b):g}$")
    ax.axhline(1.0, color="k", lw=0.8)
    ax.set_yscale("log")
    ax.set_xlabel(INVERSE_PI19)
    ax.set_ylabel(r"$\Pi_{21}$ isolated / $\Pi_{21}$ fixed base")
    ax.text(0.02, 0.97, "above 1: isolation protects", transform=ax.transAxes, va="top", fontsize=7)
    ax.text(0.02, 0.03, "below 1: isolation exposes", transform=ax.transAxes, va="bottom", fontsize=7)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, loc="center right")
    _save(fig, outputs, dpi)
    return fig


def draw_map(ds: xr.Dataset, outputs=(), dpi: int = 150):
    """What each block of ``rocking_map.nc`` does, one panel per Pi3; theta_max/alpha in each cell."""
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    pi3 = ds["pi3"].values
    fig, axs = plt.subplots(1, pi3.size, figsize=(WIDTH, 3.3), squeeze=False, layout="constrained")
    cmap = ListedColormap(["white"] + [RESPONSE_COLOURS[r] for r in RESPONSES])
    mu, pi18 = ds["mu_s"].values, ds["pi18"].values
    for ax, b in zip(axs[0], pi3, strict=True):
        s = ds.sel(pi3=b)
        resp = s["response"].transpose("mu_s", "pi18").values.astype(int) + 1
        ax.imshow(resp, origin="lower", cmap=cmap, vmin=0, vmax=len(RESPONSES), aspect="auto")
        th = s["theta_max_over_alpha"].transpose("mu_s", "pi18").values
        for i in range(mu.size):
            for j in range(pi18.size):
                if resp[i, j] - 1 in (2, 3):
                    ax.text(j, i, f"{th[i, j]:.2f}", ha="center", va="center", fontsize=6)
        # the boundary mu_s = b/h: below it the block cannot tip
        ax.plot(np.interp(mu, pi18, np.arange(pi18.size), left=-0.5, right=pi18.size - 0.5), np.arange(mu.size),
                "k--", lw=0.8)
        ax.set_xticks(range(pi18.size), [f"{v:g}" for v in pi18], fontsize=7)
        ax.set_yticks(range(mu.size), [f"{v:g}" for v in mu], fontsize=7)
        ax.set_xlabel(GROUPS["pi18"].label)
        ax.set_title(_base_label(float(b)), fontsize=9)
    axs[0, 0].set_ylabel(r"$\mu_s = \mu_k$")
    handles = [Patch(color=RESPONSE_COLOURS[r], label=r.replace("_", " ")) for r in RESPONSES]
    fig.legend(handles=handles, loc="outside lower center", ncol=len(RESPONSES), fontsize=7)
    fig.suptitle(rf"{ds.attrs['pulse']} pulse, $a_p/g = {ds.attrs['a_p_over_g']:g}$, "
                 rf"$\Pi_{{19}} = {float(ds['pi19']):g}$; numbers: $\theta_{{max}}/\alpha$ of the blocks that rocked; "
                 r"dashed: $\mu_s = b/h$", fontsize=8)
    _save(fig, outputs, dpi)
    return fig


def _fractions(ds: xr.Dataset, base: str, im: str, exceeded: np.ndarray):
    """Observed fractions: per stripe for PGA, per equal-count bin of the analyses for the others."""
    ok = ds["solve_status"].sel(base=base).values == 0
    if im == "pga":
        levels = ds["im_level"].values
        n = ok.sum(axis=0)
        z = (exceeded & ok).sum(axis=0)
        keep = n > 0
        return levels[keep], z[keep] / n[keep]
    x = ds[im].sel(base=base).values if "base" in ds[im].dims else ds[im].values
    x, e = x[ok], exceeded[ok]
    order = np.argsort(x)
    bins = np.array_split(order, min(6, max(1, x.size // 4)))
    return np.array([np.exp(np.mean(np.log(x[b]))) for b in bins]), np.array([e[b].mean() for b in bins])


def draw_fragility(ds: xr.Dataset, outputs=(), dpi: int = 150):
    """Probability of overturning (and of the rotation limits) of ``rocking_fragility.nc`` over PGA, PFA, PFV."""
    import matplotlib.pyplot as plt

    ims = ("pga", "pfa", "pfv")
    fig, axs = plt.subplots(1, len(ims), figsize=(WIDTH, 2.9), squeeze=False, layout="constrained", sharey=True)
    colours = {"fixed_base": "k", "isolated": "C3"}
    last = ds.sizes["limit_state"] - 1
    for ax, im in zip(axs[0], ims, strict=True):
        x_all = ds[im].values
        x = np.linspace(float(np.nanmax(x_all)) / 200.0, 1.1 * float(np.nanmax(x_all)), 300)
        for base in ds["base"].values:
            c = colours.get(str(base), "C0")
            for k in range(ds.sizes["limit_state"]):
                sel = ds.sel(base=base, im=im).isel(limit_state=k)
                name = str(sel["limit_state_name"].values)
                ls = "-" if k == last else ":"
                th, be = float(sel["theta"]), float(sel["beta"])
                label = f"{str(base).replace('_', ' ')}, {name.replace('_', ' ')}"
                if np.isfinite(th):
                    ax.plot(x, probability(x, th, be), ls=ls, color=c, label=f"{label}: θ = {th:.3g}")
                else:
                    ax.plot([], [], ls=ls, color=c, label=f"{label}: no curve")
                if k == last:
                    exc = ds["overturned"].sel(base=base).values.astype(bool)
                    px, pf = _fractions(ds, str(base), im, exc)
                    ax.plot(px, pf, "o", color=c, markersize=3.5)
        ax.set_xlabel(f"{im.upper()} [{ds['im_units'].sel(im=im).values}]")
        ax.set_ylim(-0.02, 1.02)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=5.5, loc="lower right")
    axs[0, 0].set_ylabel("probability of exceedance")
    fig.suptitle("Overturning (solid) and rotation limits (dotted); dots: observed fractions of overturning",
                 fontsize=8.5)
    _save(fig, outputs, dpi)
    return fig
