"""Figures of the fragility study, from its datasets only (``results/datasets/fragility*.nc``).

:func:`draw_curves` draws one panel per intensity measure: the fitted curves
``P(u_max > limit | IM)`` of every limit state, their bootstrap band (the envelope of the curves
at the corners of the theta and beta intervals: a simple, conservative band), the empirical
fractions (per stripe for the scaling IM, per equal-count bin of the analyses for the others)
and, dashed, the fixed-base curves on the ground-motion panels.  :func:`empirical_fractions`
gives the points.

The planar analyses (``results/datasets/fragility_planar*.nc``): :func:`draw_planar_curves` draws,
per building and limit state, the curves of the three motions (both components at once, one at a
time pooled, the larger of the two) against the scaling IM with the observed fractions per
stripe; :func:`draw_suite_curves` the planar curves of each suite against one IM.
"""

from __future__ import annotations

import itertools

import numpy as np
import xarray as xr

from ..studies.fragility import probability

__all__ = ["IM_LABELS", "MOTION_LABELS", "band", "caption_text", "draw_curves", "draw_planar_curves",
           "draw_suite_curves", "empirical_fractions", "planar_fractions"]

IM_LABELS = {"pga": "PGA [m/s²]", "pgv": "PGV [m/s]", "pfa": "PFA [m/s²]", "pfv": "PFV [m/s]"}
"""Axis labels of the intensity measures (Unicode: reports render offline, no TeX)."""

IM_LABELS.update({"pga_rotd50": "RotD50 PGA [m/s²]", "pgv_rotd50": "RotD50 PGV [m/s]",
                  "sa_rotd50": "RotD50 Sa(T_b) [m/s²]"})

MOTION_LABELS = {"planar": "both components (planar)", "one_component": "one component at a time",
                 "max_component": "larger of the two components"}
"""Legend text of the motions of the planar analyses."""

_MOTION_STYLES = {"planar": "-", "one_component": "--", "max_component": ":"}


def empirical_fractions(ds: xr.Dataset, im: str, limit: float, n_bins: int = 6):
    """Observed exceedance fractions of ``u_max > limit`` against ``im``.

    Parameters
    ----------
    ds : xarray.Dataset
        A fragility dataset.
    im : str
        ``pga``, ``pgv``, ``pfa`` or ``pfv``.
    limit : float
        Limit state, m.
    n_bins : int
        Equal-count bins for an IM that is not the scaling IM.

    Returns
    -------
    (x, fraction, count) : ndarrays
        Stripe level (or bin's median IM), fraction exceeded, analyses behind each point.
    """
    u = ds["u_max"].values
    exc = u > limit
    if im == ds.attrs.get("scaling_im"):
        levels = ds["im_level"].values
        stripe = ds["stripe"].values
        counts = np.array([(stripe == j).sum() for j in range(levels.size)])
        frac = np.array([exc[stripe == j].mean() for j in range(levels.size)])
        return levels, frac, counts
    x = ds[im].values
    order = np.argsort(x, kind="stable")
    parts = np.array_split(order, min(n_bins, x.size))
    return (np.array([np.median(x[p]) for p in parts]), np.array([exc[p].mean() for p in parts]),
            np.array([p.size for p in parts]))


def band(x, theta_low, theta_high, beta_low, beta_high):
    """Lower and upper envelope of the curves at the four corners of the theta and beta intervals."""
    curves = [probability(x, t, b) for t, b in itertools.product((theta_low, theta_high), (beta_low, beta_high))]
    return np.min(curves, axis=0), np.max(curves, axis=0)


def draw_curves(ds: xr.Dataset, outputs, fixed: xr.Dataset | None = None, dpi: int = 150):
    """Draw the fragility curves of ``ds`` (and ``fixed``, dashed) into every path of ``outputs``.

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    ims = [str(v) for v in ds["im"].values]
    fig, axes = plt.subplots(2, 2, figsize=(9.0, 7.0), constrained_layout=True)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for ax, im in zip(axes.ravel(), ims, strict=True):
        x_all = ds[im].values
        hi = float(np.nanmax(x_all)) if x_all.size else 1.0
        if fixed is not None and im in ("pga", "pgv"):
            hi = max(hi, float(np.nanmax(fixed[im].values)))
        x = np.linspace(hi / 200.0, 1.1 * hi, 300)
        for k, limit in enumerate(ds["limit_state"].values):
            c = colours[k % len(colours)]
            sel = ds.sel(limit_state=limit, im=im)
            label = f"{limit:g} m"
            th, be = float(sel["theta"]), float(sel["beta"])
            if np.isfinite(th) and np.isfinite(be):
                ax.plot(x, probability(x, th, be), color=c, label=f"{label}: θ = {th:.3g}, β = {be:.2f}")
                bounds = [float(sel[v]) for v in ("theta_low", "theta_high", "beta_low", "beta_high")]
                if all(np.isfinite(bounds)):
                    lo, up = band(x, *bounds)
                    ax.fill_between(x, lo, up, color=c, alpha=0.15, linewidth=0)
            else:
                status = ds["fit_status"].attrs["flag_meanings"].split()[int(sel["fit_status"])]
                ax.plot([], [], color=c, label=f"{label}: no curve ({status.replace('_', ' ')})")
            px, pf, _ = empirical_fractions(ds, im, float(limit))
            ax.plot(px, pf, "o", color=c, markersize=4)
            if fixed is not None and im in ("pga", "pgv"):
                fs = fixed.sel(limit_state=limit, im=im)
                if np.isfinite(float(fs["theta"])):
                    ax.plot(x, probability(x, float(fs["theta"]), float(fs["beta"])), "--", color=c,
                            label=f"{label} fixed base: θ = {float(fs['theta']):.3g}")
        ax.set_xlabel(IM_LABELS.get(im, im))
        ax.set_ylabel("P(u_max > limit | IM)")
        ax.set_ylim(-0.02, 1.02)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="lower right")
    fig.suptitle("Sliding fragility: fitted curves (bands: bootstrap over records), observed fractions (dots)"
                 + ("; dashed: fixed base" if fixed is not None else ""), fontsize=9)
    caption = caption_text(ds, fixed)
    for path in outputs:
        meta = {"Description": caption} if str(path).endswith(".png") else {"Subject": caption}
        fig.savefig(path, dpi=dpi, metadata=meta)
    return fig


def caption_text(ds: xr.Dataset, fixed: xr.Dataset | None = None) -> str:
    """One-paragraph caption of the figure (stored in the PNG's ``Description``)."""
    a = ds.attrs
    n_rec = len(set(map(str, ds["record"].values)))
    text = (f"Sliding fragility P(u_max > limit | IM) of {a['m_ec']:g} kg contents (mu_k lognormal, median "
            f"{a['mu_k_median']:g}, log std {a['mu_k_log_std']:g}) on a slab isolated at T_b = {a['T_b']:g} s, "
            f"xi_b = {a['xi_b']:g}: {ds.sizes['analysis']} analyses ({n_rec} records x {ds.sizes['im_level']} "
            f"{a['scaling_im'].upper()} stripes x friction draws); maximum-likelihood lognormal curves, bands from "
            f"{a['n_boot']} bootstrap resamples of the records, dots the observed fractions")
    return text + ("; dashed: the same contents on a fixed base." if fixed is not None else ".")


def planar_fractions(ds: xr.Dataset, motion: str, limit: float, floor: str | None = None,
                     suite: str | None = None):
    """Observed exceedance fractions per stripe of a planar fragility dataset.

    Parameters
    ----------
    ds : xarray.Dataset
        A ``fragility_planar`` dataset.
    motion : {"planar", "one_component", "max_component"}
    limit : float
        Limit state, m.
    floor, suite : str, optional
        Keep the analyses of one floor (default: the first) and one suite (default: all).

    Returns
    -------
    (x, fraction) : ndarrays
        Stripe levels of the scaling IM and the fraction of outcomes above ``limit``.
    """
    floor = str(ds["floor"].values[0]) if floor is None else floor
    keep = ds["contents_floor"].values.astype(str) == floor
    if suite is not None:
        keep &= ds["record_suite"].values.astype(str) == suite
    ux, uy, up = (ds[k].values[keep] for k in ("u_max_x", "u_max_y", "u_max"))
    stripe = ds["stripe"].values[keep]
    u, st = {"planar": (up, stripe), "one_component": (np.concatenate([ux, uy]), np.concatenate([stripe, stripe])),
             "max_component": (np.maximum(ux, uy), stripe)}[motion]
    levels = ds["im_level"].values
    frac = np.array([np.mean(u[st == j] > limit) if np.any(st == j) else np.nan for j in range(levels.size)])
    return levels, frac


def _curve(ax, ds, x, sel, style, colour, label):
    th, be = float(sel["theta"]), float(sel["beta"])
    if np.isfinite(th) and np.isfinite(be):
        ax.plot(x, probability(x, th, be), style, color=colour, label=f"{label}: θ = {th:.3g}, β = {be:.2f}")
    else:
        status = ds["fit_status"].attrs["flag_meanings"].split()[int(sel["fit_status"])]
        ax.plot([], [], style, color=colour, label=f"{label}: no curve ({status.replace('_', ' ')})")


def draw_planar_curves(datasets: dict, outputs=(), dpi: int = 150):
    """Curves of the three motions against the scaling IM, one panel per building and limit state.

    Parameters
    ----------
    datasets : dict
        ``{building label: fragility_planar dataset}`` (e.g. isolated, fixed base).
    outputs : sequence of path
        Files to save the figure to.
    dpi : int

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    first = next(iter(datasets.values()))
    limits = first["limit_state"].values
    im = first.attrs["scaling_im"]
    fig, axes = plt.subplots(len(datasets), limits.size, figsize=(3.4 * limits.size, 3.0 * len(datasets)),
                             constrained_layout=True, squeeze=False)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for row, (label, ds) in zip(axes, datasets.items(), strict=True):
        floor = str(ds["floor"].values[0])
        levels = ds["im_level"].values
        x = np.linspace(levels[-1] / 200.0, 1.3 * levels[-1], 300)
        for ax, limit in zip(row, limits, strict=True):
            for m, motion in enumerate(ds["motion"].values.astype(str)):
                c = colours[m % len(colours)]
                _curve(ax, ds, x, ds.sel(floor=floor, group="all", motion=motion, limit_state=limit, im=im),
                       _MOTION_STYLES[motion], c, MOTION_LABELS[motion])
                px, pf = planar_fractions(ds, motion, float(limit), floor)
                ax.plot(px, pf, "o", color=c, markersize=4)
            _probability_axes(ax, f"{label}, u > {limit:g} m", im, 0.02, "upper left")
    fig.suptitle("Sliding in the plane against one component at a time: fitted curves, observed fractions (dots)",
                 fontsize=9)
    for path in outputs:
        fig.savefig(path, dpi=dpi)
    return fig

def _probability_axes(ax, title: str, im: str, margin: float, legend_loc: str) -> None:
    """Title, labels, limits 0 - ``margin`` ... 1 + ``margin``, grid and legend of a panel of exceedance probabilities."""
    ax.set_title(title, fontsize=9)
    ax.set_xlabel(IM_LABELS.get(im, im))
    ax.set_ylabel("P(u > limit | IM)")
    ax.set_ylim(-margin, 1.0 + margin)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=6, loc=legend_loc)



def draw_suite_curves(ds: xr.Dataset, im: str, motion: str = "planar", outputs=(), dpi: int = 150):
    """Curves of each suite against ``im``, one panel per limit state (the dataset's first floor).

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    limits = ds["limit_state"].values
    floor = str(ds["floor"].values[0])
    fig, axes = plt.subplots(1, limits.size, figsize=(3.4 * limits.size, 3.0), constrained_layout=True,
                             squeeze=False)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    hi = float(np.nanmax(ds[im].values))
    x = np.linspace(hi / 200.0, 1.1 * hi, 300)
    for ax, limit in zip(axes[0], limits, strict=True):
        for k, name in enumerate(ds["suite"].values.astype(str)):
            c = colours[k % len(colours)]
            _curve(ax, ds, x, ds.sel(floor=floor, group=name, motion=motion, limit_state=limit, im=im), "-", c,
                   name.replace("fema-p695-", ""))
            keep = (ds["record_suite"].values.astype(str) == name) & (ds["contents_floor"].values.astype(str) == floor)
            ax.plot(ds[im].values[keep], (ds["u_max"].values[keep] > limit) * 1.0 + (k - 1) * 0.01, "|",
                    color=c, markersize=6, alpha=0.6)
        _probability_axes(ax, f"u > {limit:g} m ({MOTION_LABELS[motion]})", im, 0.05, "center right")
    fig.suptitle(f"Suites compared at equal {IM_LABELS.get(im, im)} (ticks: each analysis, at 0 or 1)", fontsize=9)
    for path in outputs:
        fig.savefig(path, dpi=dpi)
    return fig
